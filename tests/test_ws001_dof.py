"""Degrees of freedom with a higher pair and a passive roller ([dof]) and worksheet 001 problem 1:
W = 3·7 − 2·9 − 1 = 2 before the replacement (passive roller included), W = 3·7 − 2·10 = 1 after.
Independent check: the loop formulation W = Σf − 3k with k = p − n independent loops."""
from __future__ import annotations

import math
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
    assert d.names_after[2] == "K′" and d.pairs_after[2] == (2, 3, "R")
    assert [p["key"] for p in d.printed] == ["W", "W_after", "angle_OML"]


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
    for old, new, msg in [("rollers = [3]", "rollers = [5]", "не ролик"),
                          ('{ links = [6, 7], type = "R", name = "M" }', '{ links = [6, 9], type = "R", name = "M" }',
                           "двух разных звеньев"),
                          ('type = "P"', 'type = "Q"', "type")]:
        p = tmp_path / "d.toml"
        p.write_text(text.replace(old, new), encoding="utf-8")
        with pytest.raises(CaseError, match=msg):
            load_case(p).dof


def test_three_olympiad_kinds_in_one_case(tmp_path):
    """Problems 1, 3 and 7 as the sections of one case: every kind is found and solved (problem 1
    without its question 3, which needs its own linkage)."""
    cases = CASE.parent
    gov = (cases / "ws001_p7_governor.toml").read_text(encoding="utf-8")
    cross = (cases / "ws001_p3_cross.toml").read_text(encoding="utf-8")
    dof = CASE.read_text(encoding="utf-8")
    text = gov + "\n" + cross[cross.index("[parameters]"):] + "\n" + dof[dof.index("[dof]"):dof.index("angle_OML = ")]
    p = tmp_path / "all.toml"
    p.write_text(text, encoding="utf-8")
    st = load_case(p)
    s = st.all_scalars()
    assert s["dof_W_after"] == 1 and round(s["governor_omega"], 2) == 20.36
    assert s["cross_F_red"] == pytest.approx(50 * 3 ** 0.5, rel=1e-14)


def test_problem_2013_1_question_3_pusher_stops_where_ML_perp_MO():
    """Question 3: V_T = V_M1 + V_M6M1 = 0 when ML ⊥ MO.  The engine finds the position as the root
    of the pusher's first analog; independently, the block M is then at the foot of the
    perpendicular from O to the slot: |OM| = h on the pusher's axis x = a, so
    sin φ₁ = −a/h (the slot y' = h in link 1's frame meets x = a where s = 0), y_M = √(h² − a²)."""
    st = load_case(CASE)
    d = st.dof
    z = d.zero
    assert len(z) == 1
    h, a = 0.25, 0.15
    r = z.iloc[0]
    assert r["q"] == pytest.approx(-math.asin(a / h), abs=1e-14)
    assert r["s"] == pytest.approx(math.sqrt(h * h - a * a), abs=1e-14)
    assert abs(r["angle_OML"] - math.pi / 2) < 1e-13
    assert r["OM"] == pytest.approx(h, abs=1e-14) and r["h"] == pytest.approx(h, abs=1e-14)
    # V_M1 and the relative velocity cancel: equal and opposite, along the slot
    assert abs(r["vqx_M1"] + r["vqx_rel"]) < 1e-13 and abs(r["vqy_M1"] + r["vqy_rel"]) < 1e-13
    assert abs(r["vq_out"]) < 1e-13
    # the pusher's position y_M(φ) = (a sin φ + h)/cos φ has its minimum there (closed form)
    ys = [(a * math.sin(q) + h) / math.cos(q) for q in (r["q"] - 1e-3, r["q"], r["q"] + 1e-3)]
    assert ys[1] < ys[0] and ys[1] < ys[2]
    sc = st.all_scalars()
    assert sc["dof_zero_count"] == 1 and sc["dof_angle_OML"] == pytest.approx(math.pi / 2, abs=1e-13)
    printed = {p["key"]: p for p in d.printed}
    assert printed["angle_OML"]["printed"] == pytest.approx(math.pi / 2)


def test_zero_speed_errors(tmp_path):
    text = CASE.read_text(encoding="utf-8")
    for old, new, msg in [('point = "M"', 'point = "T"', "не скользит по прорези"),
                          ('line = "L"', 'line = "O"', "не принадлежит прорези")]:
        p = tmp_path / "z.toml"
        p.write_text(text.replace(old, new, 1), encoding="utf-8")
        with pytest.raises(CaseError, match=msg):
            load_case(p).dof
