"""Mechanism with a cross-slider ([cross]) and worksheet 001 problem 3: every printed velocity and
the reduced force, exact (√3, 50√3); independent checks: C on the Thales circle (numerical
derivative of the intersection of the two rockers), virtual power for the reduced force."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from reportgen.analysis.study import load_case
from reportgen.core import cross as CX
from reportgen.errors import CaseError

CASE = Path(__file__).resolve().parent.parent / "cases" / "ws001_p3_cross.toml"


def test_problem_2013_3():
    st = load_case(CASE)
    s = st.cross.scalars
    assert s["cross_l_O1C"] == pytest.approx(0.1, rel=1e-14)
    assert round(s["cross_l_O2C"], 3) == 0.173
    assert round(s["cross_v_B3"], 3) == 0.866 and s["cross_v_B3B2"] == pytest.approx(0.5, rel=1e-14)
    assert round(s["cross_w3"], 2) == 8.66 and s["cross_w5"] == pytest.approx(s["cross_w3"], rel=1e-15)
    assert s["cross_v_C3"] == pytest.approx(s["cross_v_B3"], rel=1e-14)      # O₁C = O₁B
    assert s["cross_v_C5"] == pytest.approx(1.5, rel=1e-14)
    assert round(8.66 * 0.173, 3) == 1.498                                   # the worksheet's rounded product
    assert s["cross_v_C4"] == pytest.approx(math.sqrt(3), rel=1e-14)          # printed 1,73
    assert s["cross_F_red"] == pytest.approx(50 * math.sqrt(3), rel=1e-14)    # printed 86,6
    assert [p["key"] for p in st.cross.printed] == ["l_O2C", "v_B3", "v_B3B2", "w3", "v_C5", "v_C4", "F_red"]


def test_against_finite_motion():
    """Move the mechanism: the joint B of link 1 and slider 2 translates with v_A, B(t) = B₀ + v_A·t·e₁;
    rocker 3 passes through O₁ and B(t); C is the foot of the perpendicular from O₂ on rocker 3
    (the cross keeps O₁C ⊥ O₂C).  Central differences of φ₃ and C reproduce ω₃ and V_C4
    (independent of the plans of velocities)."""
    v, gam, lB, d, al = 1.0, math.radians(60), 0.1, 0.2, math.radians(60)
    r = CX.solve(v, gam, lB, d, al, 10.0)
    B0, e1 = r["B"], r["v1"] / v

    def state(t):
        B = B0 + v * t * e1
        phi3 = math.atan2(B[1], B[0])
        e3 = np.array([math.cos(phi3), math.sin(phi3)])
        C = float(np.array([d, 0.0]) @ e3) * e3
        return phi3, C

    h = 1e-6
    (p1, C1), (p2, C2) = state(-h), state(h)
    w3 = (p2 - p1) / (2 * h)
    vC = (C2 - C1) / (2 * h)
    assert abs(w3) == pytest.approx(abs(r["w3"]), rel=1e-7)
    assert np.hypot(*vC) == pytest.approx(r["v_C4"], rel=1e-7)
    assert vC == pytest.approx(r["vC4"], rel=1e-6, abs=1e-9)
    # equal powers: the reduced force at A does the work of M on the shaft O₂
    assert r["F_red"] * v == pytest.approx(10.0 * abs(r["w5"]), rel=1e-15)


def test_cross_case_errors(tmp_path):
    text = CASE.read_text(encoding="utf-8").split("[cross.printed]")[0]
    p = tmp_path / "c.toml"
    p.write_text(text.replace('angle_O1 = "60 deg"', 'angle_O1 = "90 deg"'), encoding="utf-8")
    with pytest.raises(CaseError, match="острым"):
        load_case(p).cross
