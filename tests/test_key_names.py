"""The answer key reads as a teacher's document (issue 9, item 5): every scalar of every analysis
has a glossary entry (reportgen/report/key_names.py) — Russian name, symbol, unit, format, the
position of an extreme — over EVERY case in cases/; the key's text holds no identifier of the
program; a value's unit and the position of an extreme stand in its row."""
from __future__ import annotations

import html
import math
import re

import numpy as np
import pytest

from conftest import CASES
from reportgen import load_case
from reportgen.errors import CaseError
from reportgen.registry import KINDS
from reportgen.report.key import build_key, result_rows, value_text
from reportgen.report.key_names import GLOSSARY, entry
from reportgen.report.render import render_html

IDENTIFIER = re.compile(r"\b\w+_\w+\b|\b(?:phi|omega|eps)\w*|as printed|Mathcad", re.I)


def _studies():
    for path in sorted(CASES.glob("*.toml")):
        try:
            yield path.stem, load_case(path)
        except CaseError:           # a table of variants (``base = …``) is built by batch, not alone
            continue


@pytest.fixture(scope="module")
def every_scalar():
    """(case, kind, scalars, study) of every task of every case in cases/."""
    out = []
    for name, st in _studies():
        for kind in KINDS:
            if kind.name in st.tasks():
                out.append((name, kind.name, st.analysis(kind.name).scalars, st))
    return out


def test_glossary_covers_every_scalar_of_every_case(every_scalar):
    missing, unsaid, lost = [], [], []
    for case, kind, scalars, st in every_scalar:
        for key, value in scalars.items():
            e = entry(kind, key)
            if e is None:
                missing.append(f"{case}: {kind}.{key}")
                continue
            if e.position:
                # a position is shown in the row of the extreme it locates
                if not any((entry(kind, k) or e).where == key for k in scalars):
                    lost.append(f"{case}: {kind}.{key}")
                continue
            cell = value_text(e, value, st, kind)
            if cell is None and not (isinstance(e.words, dict) and e.words.get(value) == ""):
                unsaid.append(f"{case}: {kind}.{key} = {value!r}")
            elif cell is not None and not isinstance(value, (str, bool, np.bool_)):
                assert cell[0] == "—" or not math.isnan(float(value)), (case, key)
    assert not missing, "scalars without a glossary entry: " + ", ".join(missing)
    assert not unsaid, "switches not said in words: " + ", ".join(unsaid)
    assert not lost, "positions no row shows: " + ", ".join(lost)
    assert len({(k, key) for _, k, sc, _ in every_scalar for key in sc}) > 200


def test_glossary_is_consistent():
    for kind, table in GLOSSARY.items():
        for key, e in table.items():
            if e.position:
                continue
            assert e.name and not IDENTIFIER.search(re.sub(r"<[^>]+>", "", e.name)), (kind, key)
            if e.where is not None:
                assert table[e.where].position, (kind, key)
            if e.same_as is not None:
                assert e.same_as in table, (kind, key)
            if e.conv == "deg":
                assert e.unit == "°", (kind, key)


def test_pair_family_escapes_case_names():
    e = entry("forces", "R_<b>_1_max")
    assert "<b>" not in e.name and "&lt;b&gt;" in e.name and e.where == "q_R_<b>_1_max"
    assert entry("forces", "q_R_0_1_max").position
    assert entry("forces", "R_0_1_max").unit == "Н"
    assert entry("dynamics", "no_such_key") is None


def _key_text(case: str, *, printed: bool) -> tuple[str, str]:
    """(plain text, HTML) of the key of ``case``; without the printed-values comparison unless
    ``printed`` (that comparison names the worksheet's own quantities)."""
    rep = build_key(load_case(CASES / f"{case}.toml"))
    if not printed:
        rep.sections = [s for s in rep.sections if s.id != "key-printed"]
    h = render_html(rep, for_print=False)
    body = re.sub(r"(?s)<(style|script|head)\b.*?</\1>", " ", h)
    return html.unescape(re.sub(r"<[^>]+>", " ", body)), body


@pytest.fixture(scope="module")
def ws002():
    return _key_text("ws002_tractor_hitch", printed=False)


@pytest.fixture(scope="module")
def cross():
    return _key_text("ws001_p3_cross", printed=False)


@pytest.mark.parametrize("case", ["ws002_tractor_hitch", "ws001_p3_cross", "cam_rocker_flat", "synth_shaper",
                                  "gear_pair_shifted"])
def test_key_text_holds_no_identifier(case, request):
    text = (request.getfixturevalue("ws002")[0] if case == "ws002_tractor_hitch" else
            request.getfixturevalue("cross")[0] if case == "ws001_p3_cross" else
            _key_text(case, printed=False)[0])
    found = sorted(set(m.group(0) for m in IDENTIFIER.finditer(text)))
    assert not found, found
    assert "Величина (имя в программе)" not in text


def _rows(body: str) -> list[str]:
    return [html.unescape(re.sub(r"<[^>]+>", " ", r)) for r in re.findall(r"(?s)<tr\b.*?</tr>", body)]


def test_units_and_position_in_the_row(ws002):
    rows = _rows(ws002[1])
    r56 = [r for r in rows if "Наибольшая реакция в паре 5–6" in r]
    assert len(r56) == 1
    assert re.search(r"\bН\b", r56[0]) and re.search(r"S\s*=\s*0,664\s*м", r56[0]), r56[0]
    p = [r for r in rows if "Давление в гидросистеме" in r][0]
    assert re.search(r"\b17,5\b", p) and "МПа" in p      # as the case gives it: 17,5 MPa, not 1,75·10⁷ Па
    # a switch is said in words, in a sentence before the tables
    assert re.search(r"Вид силового расчёта:\s+статический \(без сил инерции\)\.", ws002[0])
    assert "Требуемое давление выше давления в гидросистеме: да — превышено." in ws002[0]
    assert not any("Вид силового расчёта" in r for r in rows)


def test_rotary_extreme_at_crank_angle(every_scalar):
    by = {(case, kind): (sc, st) for case, kind, sc, st in every_scalar}
    sc, st = by[("ws001_p3_cross", "cross")]          # no linkage, no positions: no «Где» column
    for rows in result_rows(st, "cross", sc).values():
        assert all(r["where"] == "" for r in rows)
    sc, st = by[("conveyor_four_bar", "forces")]
    rows = [r for g in result_rows(st, "forces", sc).values() for r in g]
    big = [r for r in rows if "уравновешивающий момент" in str(r["name"])][0]
    assert re.fullmatch(r"φ&nbsp;=&nbsp;−?\d+,\d°", str(big["where"])), big
    assert big["unit"] == "Н·м"
    sc, st = by[("conveyor_four_bar", "dynamics")]
    rows = [r for g in result_rows(st, "dynamics", sc).values() for r in g]
    w = [r for r in rows if str(r["name"]) == "Наибольшая угловая скорость звена приведения"][0]
    assert w["unit"] == "рад/с" and re.fullmatch(r"φ&nbsp;=&nbsp;\d+,\d\d°", str(w["where"])), w


def test_chosen_method_not_repeated(every_scalar):
    by = {(case, kind): (sc, st) for case, kind, sc, st in every_scalar}
    sc, st = by[("ws000_six_bar", "dynamics")]
    assert sc["method"] == "mertsalov"
    names = [str(r["name"]) for g in result_rows(st, "dynamics", sc).values() for r in g]
    assert "Требуемый момент инерции первой группы звеньев" in names
    assert not any(n.startswith("Момент инерции первой группы по Мерцалову") for n in names)
    assert any(n.startswith("Момент инерции первой группы точно") for n in names)
    assert len(names) == len(set(names))


def test_output_link_in_words_and_units(every_scalar):
    by = {(case, kind): st for case, kind, _, st in every_scalar}
    st = by[("ws000_six_bar", "dynamics")]
    out = {k: v for k, v in st.scalars.items() if entry("kinematics", k) is not None}
    rows = {str(r["name"]): r for g in result_rows(st, "kinematics", out).values() for r in g}
    assert rows["Ход выходного звена"]["unit"] == "м"
    assert rows["Средняя скорость рабочего хода"]["unit"] == "м/с"
    assert rows["Угол кривошипа в первом крайнем положении выходного звена"]["value"] == "193,8"


def test_tasks_without_linkage_have_checks(every_scalar):
    from reportgen.report.key import _second_formulations
    by = {case: st for case, _, _, st in every_scalar}
    for case, needle in (("gear_pair_shifted", "ε<sub>α</sub>"), ("train_3k_select", "Виллиса"),
                         ("synth_crank_rocker", "Синтез")):
        rows = _second_formulations(by[case])
        assert len(rows) == 1 and needle in str(rows[0]["what"]), case
        assert "выполнена" in str(rows[0]["verdict"]) and "НЕ" not in str(rows[0]["verdict"]), case
