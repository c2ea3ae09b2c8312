"""Centrifugal governor with friction circles ([governor]) and worksheet 001 problem 7:
ω = 20,36 rad/s against the drawing's 20,3; independent checks by virtual power with the friction
losses, the tangency of every line of action to its friction circle and the three-force point."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from reportgen.analysis.study import load_case
from reportgen.core import governor as CG
from reportgen.errors import CaseError

CASES = Path(__file__).resolve().parent.parent / "cases"
CASE = CASES / "ws001_p7_governor.toml"


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def test_problem_2013_7():
    st = load_case(CASE)
    g = st.governor
    s = g.scalars
    assert round(s["governor_rho"], 4) == 0.0046                     # printed 0,0046 м
    assert round(math.degrees(s["governor_alpha"]), 1) == 3.5        # printed 3,5°
    assert round(s["governor_R"]) == 74                              # printed 74 Н
    assert s["governor_P"] == pytest.approx(80.8, abs=0.2)           # drawing, 1 Н/мм
    assert math.degrees(s["governor_R76_angle"]) == pytest.approx(63.2, abs=0.05)
    assert s["governor_F_i"] == pytest.approx(85.1, abs=0.2)         # drawing, 1 Н/мм
    assert round(s["governor_omega"], 2) == 20.36                    # exact; the drawing gives 20,3
    assert round(math.sqrt(85.1 / 0.206), 1) == 20.3                 # the worksheet's arithmetic
    assert s["governor_r_D"] == pytest.approx(0.05 + 0.22 * math.sqrt(0.5), rel=1e-15)
    # the sleeve's closed form of the worksheet: R = m₂g/(2 cos(45° + α))
    assert s["governor_R"] == pytest.approx(98.1 / (2 * math.cos(math.pi / 4 + s["governor_alpha"])), rel=1e-12)
    assert s["governor_omega_down"] < s["governor_omega_0"] < s["governor_omega_up"]
    assert [p["key"] for p in g.printed] == ["phi_f", "r_D", "rho", "alpha", "R", "P", "R76_angle", "F_i", "omega"]
    assert set(g.tables()["governor"].columns) >= {"mode", "omega"}


@pytest.mark.parametrize("sense", [1, -1])
def test_virtual_power_with_friction(sense):
    """Power of the applied and inertia forces on the half (sleeve share Q/2) equals the friction
    losses ρ·|R|·|ω_rel| in H, F and B (the reactions do no work otherwise)."""
    geo = CG.geometry(0.05, 0.05, 0.15, 0.22, 0.15, math.radians(45))
    rho = CG.friction_radius(0.3, 0.016)
    r = CG.solve(geo, 98.1, 1.0, 9.81, rho, sense)
    th = math.radians(45)
    vD = sense * 0.22 * np.array([math.cos(th), math.sin(th)])
    vB = sense * geo["dyB"]
    applied = r["F_i"] * vD[0] + r["G"] @ vD - 0.5 * 98.1 * vB
    w6, w3 = sense * geo["dphi6"], sense * geo["dphi3"]
    losses = rho * (r["R"] * abs(w3) + r["R"] * abs(w6 - w3) + np.hypot(*r["R76"]) * abs(w6))
    assert applied == pytest.approx(losses, rel=1e-12)
    # the frictionless case: the virtual power is zero
    r0 = CG.solve(geo, 98.1, 1.0, 9.81, rho, 0)
    v1 = 0.22 * np.array([math.cos(th), math.sin(th)])
    assert r0["F_i"] * v1[0] + r0["G"] @ v1 - 0.5 * 98.1 * geo["dyB"] == pytest.approx(0, abs=1e-12)


def test_lines_tangent_to_friction_circles():
    geo = CG.geometry(0.05, 0.05, 0.15, 0.22, 0.15, math.radians(45))
    rho = CG.friction_radius(0.3, 0.016)
    assert rho == pytest.approx(0.016 * math.sin(math.atan(0.3)), rel=1e-15)
    r = CG.solve(geo, 98.1, 1.0, 9.81, rho, 1)
    e = r["R36"] / np.hypot(*r["R36"])
    for C in (geo["F"], geo["B"]):                    # the rod's line touches both circles
        assert abs(_cross(r["rod_point"] - C, e)) == pytest.approx(rho, rel=1e-12)
    # on opposite sides of BF (crossed tangent): the signed distances differ in sign
    d = [_cross(r["rod_point"] - C, e) for C in (geo["F"], geo["B"])]
    assert d[0] * d[1] < 0
    # three-force theorem: R76 through K has the friction moment about H, tangent to its circle
    e76 = r["R76"] / np.hypot(*r["R76"])
    assert _cross(r["K"] - geo["H"], r["R76"]) == pytest.approx(r["M_H"], rel=1e-10)
    assert abs(_cross(r["K"] - geo["H"], e76)) == pytest.approx(rho, rel=1e-10)
    # K lies on the horizontal through D
    assert r["K"][1] == pytest.approx(geo["D"][1], abs=1e-15)


def test_no_friction_no_zone():
    geo = CG.geometry(0.05, 0.05, 0.15, 0.22, 0.15, math.radians(45))
    ws = [CG.solve(geo, 98.1, 1.0, 9.81, 0.0, s)["omega"] for s in (1, 0, -1)]
    assert ws[0] == pytest.approx(ws[1], rel=1e-14) and ws[2] == pytest.approx(ws[1], rel=1e-14)


def test_governor_case_errors(tmp_path):
    text = CASE.read_text(encoding="utf-8").split("[governor.printed]")[0]
    for old, new, msg in [('\nrod = "0.15 m"', '\nrod = "0.05 m"', "короче"),
                          ('speeding = "up"', 'speeding = "fast"', "speeding"),
                          ('angle = "45 deg"', 'angle = "95 deg"', "ниже шарнира")]:
        p = tmp_path / "g.toml"
        p.write_text(text.replace(old, new), encoding="utf-8")
        with pytest.raises(CaseError, match=msg):
            load_case(p).governor
