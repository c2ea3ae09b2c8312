"""The complete course project (issue 14, item 4): the six-bar of worksheet 000 with its dynamics
and forces, a cam, a gear pair and a planetary reducer in one case and one note.

One Study is shared by the module (the six-bar's cycle, dynamics and forces are the costly part);
the note is built as HTML only."""
import json
import math
import re
from html import unescape
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from reportgen import load_case
from reportgen.registry import KINDS

CASE = Path(__file__).resolve().parents[1] / "cases" / "course_project.toml"
KINDS_HERE = ["dynamics", "forces", "cam", "gears", "train"]


@pytest.fixture(scope="module")
def study():
    return load_case(CASE)


@pytest.fixture(scope="module")
def report(study):
    from reportgen.report.assemble import build_report
    return build_report(study)


@pytest.fixture(scope="module")
def html(report, study, tmp_path_factory):
    from reportgen.report.render import build_outputs
    out = tmp_path_factory.mktemp("course")
    files = build_outputs(report, out, study.name, ("html",))
    return files["html"].read_text(encoding="utf-8")


def test_case_enables_every_kind_of_the_project(study):
    assert study.has_linkage
    assert study.tasks() == KINDS_HERE
    # registry order is the course order: structure, kinematics, dynamics, forces, cam, gears, train
    order = [k.name for k in KINDS]
    assert [order.index(n) for n in KINDS_HERE] == sorted(order.index(n) for n in KINDS_HERE)


def test_drive_is_consistent_with_the_crank(study):
    """Motor → planetary reducer (u = 6) → gear pair (u = z2/z1 = 2,5) → crank at 65 об/мин; the
    flywheel on the motor shaft is J_доп/u² with u = 15 (the rule of [dynamics] flywheel_ratio)."""
    sc = study.all_scalars()
    g, t = study.gears.scalars, study.train.scalars
    u_train = t["train_u"]
    assert u_train == pytest.approx(6.0, rel=1e-12)
    assert t["train_u_direct"] == pytest.approx(u_train, rel=1e-12)
    omega_crank = study.mechanism.driver.omega
    assert omega_crank == pytest.approx(65 * math.pi / 30, rel=1e-12)
    omega_pinion = 162.5 * math.pi / 30
    assert omega_pinion / (30 / 12) == pytest.approx(omega_crank, rel=1e-12)
    assert omega_pinion * u_train / omega_crank == pytest.approx(15.0, rel=1e-12)
    assert all(np.isfinite(v) for v in sc.values() if isinstance(v, float))
    assert g["gears_eps_alpha"] >= 1.2 and not g["gears_undercut1"]
    d = study.dynamics.scalars
    assert d["fw_ratio"] == 15.0
    assert d["J_fly_shaft"] == pytest.approx(d["J_fly"] / 15.0 ** 2, rel=1e-12)


def test_note_has_every_section_in_order(report, html):
    from reportgen.report.assemble import SECTIONS
    titles = [s.title for s in report.sections]
    expected = [SECTIONS[n][0] for n in ["structure", "kinematics"] + KINDS_HERE]
    assert len(titles) == len(expected)
    heads = [re.sub(r"<[^>]+>", "", h) for h in re.findall(r"<h1[^>]*>(.*?)</h1>", html, re.S)]
    pos = [next(i for i, h in enumerate(heads) if t in h) for t in titles]
    assert pos == sorted(pos)
    assert titles == ["Структурный анализ механизма", "Кинематический анализ механизма",
                      "Динамический анализ и синтез маховика", "Силовой (кинетостатический) анализ",
                      "Синтез кулачкового механизма", "Синтез эвольвентного зубчатого зацепления",
                      "Синтез планетарного механизма"]


def test_contents_assignment_and_conclusion_cover_every_section(report, html):
    start = html.index("СОДЕРЖАНИЕ")
    toc = html[start:html.index("</ul>", start)]
    links = re.findall(r'href="#(sec-[^"]+)"', toc)
    pos = [links.index(s.id) for s in report.sections]
    assert pos == sorted(pos)
    for s in report.sections:
        assert s.title in re.sub(r"<[^>]+>", "", toc)
    assign = html[html.index("ЗАДАНИЕ"):html.index("СОДЕРЖАНИЕ")]
    for clause in ("структурный анализ", "кинематический анализ", "маховик", "силовой", "кулачков",
                   "зубчатого зацепления", "планетарного механизма"):
        assert clause in assign
    end = html.rindex("СПИСОК ИСПОЛЬЗОВАННЫХ")
    concl = unescape(re.sub(r"<[^>]+>", "", html[html.rindex("ЗАКЛЮЧЕНИЕ", 0, end):end]))
    for word in ("W = 1", "маховик", "уравновешивающий", "Кулачковый", "зубчатая передача", "планетарного"):
        assert word.replace(" ", "") in concl.replace("\u00a0", "").replace(" ", ""), word
    text = unescape(re.sub(r"<[^>]+>", " ", re.sub(r"<(img|svg)\b.*?>", "", html, flags=re.S)))
    assert "flywheel_ratio" not in text and "fw_ratio" not in text and "J_fly" not in text
    assert not re.search(r"\b(nan|inf)\b", text, re.I)


def test_export_tables_of_every_kind_no_collision_no_nan(study, tmp_path):
    from reportgen.export import export, tables
    per_kind = {n: study.analysis(n).tables() for n in KINDS_HERE}
    names = [t for tabs in per_kind.values() for t in tabs]
    assert len(names) == len(set(names)), names
    for n, tabs in per_kind.items():
        assert tabs, n
    files = export(study, tmp_path)
    written = {p.stem for p in files}
    assert set(names) <= written and "kinematics" in written or set(names) <= written
    assert len(files) == len(tables(study)) + 1
    for p in files:
        if p.suffix == ".csv":
            df = pd.read_csv(p)
            num = df.select_dtypes(include=[np.number]).to_numpy(dtype=float)
            assert np.isfinite(num[~np.isnan(num)]).all(), p.name
            assert not df.isin(["inf", "-inf", "nan", "NaN"]).any().any(), p.name
    text = (tmp_path / "scalars.json").read_text(encoding="utf-8")
    assert "NaN" not in text and "Infinity" not in text
    json.loads(text)


def test_check_passes(capsys):
    from reportgen.cli import main
    assert main(["check", str(CASE)]) == 0
    out = capsys.readouterr().out
    for n in KINDS_HERE:
        assert f"Раздел [{n}] проверен." in out
