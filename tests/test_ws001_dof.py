"""Degrees of freedom with a higher pair and a passive roller ([dof]) and worksheet 001 problem 1:
W = 3·7 − 2·9 − 1 = 2 before the replacement (passive roller included), W = 3·7 − 2·10 = 1 after.
Independent check: the loop formulation W = Σf − 3k with k = p − n independent loops."""
from __future__ import annotations

from pathlib import Path

import pytest

from reportgen.analysis.study import load_case
from reportgen.core import dof as CD
from reportgen.errors import CaseError

CASE = Path(__file__).resolve().parent.parent / "cases" / "ws001_p1_dof.toml"


def _loops_W(n, pairs):
    f = sum(2 if t == "H" else 1 for *_, t in pairs)
    return f - 3 * (len(pairs) - n)


def test_problem_2013_1():
    d = load_case(CASE).dof
    assert (d.before["n"], d.before["p5"], d.before["p4"]) == (7, 9, 1)
    assert d.before["W"] == 3 * 7 - 2 * 9 - 1 == 2                   # printed 2
    assert d.before["q"] == 1 and d.before["W_true"] == 1
    assert (d.after["n"], d.after["p5"], d.after["p4"]) == (7, 10, 0)
    assert d.after["W"] == 3 * 7 - 2 * 10 == 1                        # printed 1
    assert _loops_W(d.n, d.pairs) == d.before["W"]
    assert _loops_W(d.n_after, d.pairs_after) == d.after["W"]
    assert d.names_after[4] == "K′"
    assert [p["key"] for p in d.printed] == ["W", "W_after"]


def test_higher_pair_without_roller_adds_a_link():
    """Cam 1 on the frame pushing a flat rocker 2: W = 3·2 − 2·2 − 1 = 1; the replacement adds link 3
    with two revolutes, W = 3·3 − 2·4 = 1 (the same, no passive freedom)."""
    pairs = [(0, 1, "R"), (0, 2, "R"), (1, 2, "H")]
    assert CD.count(2, pairs)["W"] == 1
    n, after, new = CD.replace_higher(2, pairs)
    assert (n, new) == (3, [3]) and sorted(after) == sorted([(0, 1, "R"), (0, 2, "R"), (1, 3, "R"), (3, 2, "R")])
    assert CD.count(n, after)["W"] == 1 == _loops_W(n, after)


def test_dof_case_errors(tmp_path):
    text = CASE.read_text(encoding="utf-8").split("[dof.printed]")[0]
    for old, new, msg in [("rollers = [4]", "rollers = [5]", "не ролик"),
                          ('{ links = [6, 7], type = "R", name = "M" }', '{ links = [6, 9], type = "R", name = "M" }',
                           "двух разных звеньев"),
                          ('type = "P"', 'type = "Q"', "type")]:
        p = tmp_path / "d.toml"
        p.write_text(text.replace(old, new), encoding="utf-8")
        with pytest.raises(CaseError, match=msg):
            load_case(p).dof


def test_three_olympiad_kinds_in_one_case(tmp_path):
    """Problems 1, 3 and 7 as the sections of one case: every kind is found and solved."""
    cases = CASE.parent
    gov = (cases / "ws001_p7_governor.toml").read_text(encoding="utf-8")
    cross = (cases / "ws001_p3_cross.toml").read_text(encoding="utf-8")
    dof = CASE.read_text(encoding="utf-8")
    text = gov + "\n" + cross[cross.index("[parameters]"):] + "\n" + dof[dof.index("[dof]"):]
    p = tmp_path / "all.toml"
    p.write_text(text, encoding="utf-8")
    st = load_case(p)
    s = st.all_scalars()
    assert s["dof_W_after"] == 1 and round(s["governor_omega"], 2) == 20.36
    assert s["cross_F_red"] == pytest.approx(50 * 3 ** 0.5, rel=1e-14)
