"""The coursework report end to end: content, layout facts, fonts, determinism, laziness."""
import hashlib
import re
import subprocess
from pathlib import Path

import pytest

from conftest import CASES
from reportgen import load_case
from reportgen.cli import main
from reportgen.report.assemble import build_report, needs
from reportgen.report.render import build_outputs



@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("reports")
    files = {}
    for name in ("ws000_six_bar", "ws004_slotted_lever"):
        rc = main(["build", str(CASES / f"{name}.toml"), "-o", str(out)])
        assert rc == 0
        files[name] = (out / f"{name}.pdf", out / f"{name}.html")
    return files


def _text(pdf: Path) -> str:
    return subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True, check=True).stdout


def test_report_structure_and_key_numbers(built):
    pdf, html = built["ws000_six_bar"]
    text = _text(pdf)
    for needle in ["ПОЯСНИТЕЛЬНАЯ ЗАПИСКА", "ЗАДАНИЕ", "СОДЕРЖАНИЕ", "ВВЕДЕНИЕ", "ЗАКЛЮЧЕНИЕ",
                   "СПИСОК ИСПОЛЬЗОВАННЫХ ИСТОЧНИКОВ", "1 Структурный анализ механизма",
                   "2 Кинематический анализ механизма", "Рисунок 1.1 — Кинематическая схема механизма",
                   "Таблица 1.1 — Звенья механизма", "План скоростей для положения 12",
                   "План ускорений для положения 12", "Продолжение таблицы",
                   "I(0,1) → II(2,3) → II(4,5)"]:
        assert needle in text, needle
    # numbers of worksheet 000 at f, formatted the Russian way
    assert "95,76" in text          # φ3 at f, degrees
    assert "6,807" in text          # ω1, rad/s
    assert "−0,1735" in text or "−0,174" in text   # x_A at f
    # TOC lines carry page numbers
    assert re.search(r"ВВЕДЕНИЕ\s*\.{3,}\s*\d+", text)
    # the title page has no page number: page 1 ends without a bare number line
    first = text.split("\f")[0].strip().splitlines()
    assert not re.fullmatch(r"\s*\d+\s*", first[-1])
    pages = int(re.search(r"Pages:\s+(\d+)", subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True).stdout).group(1))
    assert 12 <= pages <= 60


def test_fonts_embedded(built):
    pdf, _ = built["ws004_slotted_lever"]
    out = subprocess.run(["pdffonts", str(pdf)], capture_output=True, text=True, check=True).stdout
    fams = {line.split()[0].split("+")[-1] for line in out.splitlines()[2:] if line.strip()}
    assert fams, out
    assert all(f.startswith("Report-Serif") for f in fams), fams   # one bundled family (by path), nothing from fontconfig
    assert all(" yes " in line for line in out.splitlines()[2:] if line.strip())   # embedded


def test_html_self_contained_and_same_content(built):
    pdf, html = built["ws000_six_bar"]
    h = html.read_text(encoding="utf-8")
    assert not re.search(r"""(src|href)\s*=\s*["'](https?:|file:)""", h)
    assert "url(http" not in h and "url(file" not in h
    for needle in ["Кинематическая схема механизма", "План скоростей для положения 12", "СОДЕРЖАНИЕ"]:
        assert needle in h


def test_deterministic_outputs(tmp_path):
    study = load_case(CASES / "ws004_slotted_lever.toml")
    r1 = build_outputs(build_report(study), tmp_path / "a", "x")
    study2 = load_case(CASES / "ws004_slotted_lever.toml")
    r2 = build_outputs(build_report(study2), tmp_path / "b", "x")
    for kind in ("pdf", "html"):
        assert hashlib.sha256(r1[kind].read_bytes()).digest() == hashlib.sha256(r2[kind].read_bytes()).digest(), kind


def test_report_computes_only_what_its_sections_need():
    study = load_case(CASES / "ws000_six_bar.toml")
    build_report(study, ["structure"])
    assert "structure" in study.computed
    assert "cycle" not in study.computed           # the structure section needs no cycle curves
    assert "dynamics" not in study.computed and "forces" not in study.computed
    assert needs(study, ["structure"]) == {"structure", "kinematics"}
    study = load_case(CASES / "ws000_six_bar.toml")
    build_report(study, ["structure", "kinematics"])
    assert "cycle" in study.computed
    # the kinematics section judges which stroke is the working one from the resisting loads' reduced
    # moments (the dynamics analysis, a few milliseconds); the force analysis is not computed
    assert "forces" not in study.computed


def test_unknown_section_is_a_clear_error(capsys):
    rc = main(["build", str(CASES / "ws004_slotted_lever.toml"), "--sections", "kinematic"])
    err = capsys.readouterr().err
    assert rc == 2 and "kinematic" in err and "kinematics" in err
