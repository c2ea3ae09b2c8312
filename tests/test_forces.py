"""Properties of the force analysis (kinetostatics by Assur groups) and worksheet 000 at f.

Random mechanisms of every kind of class II group (the strategies of
``test_kinematics_properties``), a class III mechanism and random actuator-driven linkages get
random masses, moments of inertia, centres of mass, an applied force and an applied moment, and
the driver a random angular acceleration.  For each accepted draw, at random positions:

* every link is in equilibrium under its loads (weights, applied, inertia Φ = −m·a_S,
  M_Φ = −J_S·ε computed here from ``study.at``) and the exported reactions of all its pairs
  (both orientations R_i_j, R_j_i; prismatic N, M_p): |ΣF|, |ΣM| ≤ 1e-9 of the load scale;
* the balancing moment (or the actuator force) equals the virtual-power value computed here
  from the velocity analogs: |M_ур·φ′₁ + Σ F·x′ + Σ M·φ′| ≤ 1e-10 of Σ|terms|;
* in the static mode an actuator's force equals load × transfer ratio (virtual work).

Worksheet 000 at f = 99.1°: the reactions agree with an independent solution (all 15 unknowns
of the mechanism in one global linear system, loads written out by hand from the worksheet's
data), and the Жуковский lever agrees with the balancing moment to 1e-10.
"""
from __future__ import annotations

import copy
import math
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parent))

from test_kinematics_properties import _solve, property_tests  # noqa: E402
from reportgen.analysis.study import Study  # noqa: E402
from reportgen.case.load import CaseSpec  # noqa: E402
from reportgen.errors import AssemblyError  # noqa: E402
from reportgen.mechanism.model import FRAME  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
TOL_EQUILIBRIUM = 1e-9
TOL_POWER = 1e-10
EXAMPLES = 15
SETTINGS = settings(max_examples=EXAMPLES, deadline=None, database=None, derandomize=True,
                    suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
G = 9.81


# ----------------------------------------------------------------------------- random loads

@st.composite
def loaded(draw, base, static=None):
    """A drawn case with masses, J_S, centres of mass, an applied force and moment, a random
    ε of the driver and [forces] (kinetostatic at constant ω, or static)."""
    data, _ = draw(base)
    data = copy.deepcopy(data)
    for ln in data["links"]:
        if draw(st.integers(0, 4)) == 0:
            continue                                   # some links massless
        ln["mass"] = draw(st.floats(0.5, 30.0))
        ln["J_S"] = draw(st.floats(0.0, 2.0))
        ln["com"] = draw(st.sampled_from(sorted(ln["points"])))
    on = draw(st.sampled_from(data["links"]))
    by = draw(st.sampled_from(data["links"]))
    data["loads"] = {
        "g": G,
        "force": [{"name": "Fa", "link": on["name"], "point": draw(st.sampled_from(sorted(on["points"]))),
                   "F": [draw(st.floats(-2000, 2000)), draw(st.floats(-2000, 2000))]}],
        "moment": [{"name": "Ma", "link": by["name"], "M": draw(st.floats(-300, 300))}],
    }
    is_static = draw(st.booleans()) if static is None else static
    if data["driver"]["type"] == "crank":
        data["driver"]["epsilon"] = draw(st.floats(-60.0, 60.0))
    else:
        data["driver"]["speed"] = draw(st.floats(0.05, 0.5))
        data["driver"]["acceleration"] = draw(st.floats(-2.0, 2.0))
    data["forces"] = {"mode": "static"} if is_static else {"motion": "constant"}
    return data


@st.composite
def actuator_linkage(draw):
    """A hydraulic cylinder (cylinder 1 with a point K1 on its axis, rod 2 with K2) turning a
    rocker 3 about O3, which drives a coupler 4 and a slider 5 on a frame guide (ВВП) or a
    rocker 5 (ВВВ).  Angle of the cylinder's arm at O3 between 40° and 140° (no dead point)."""
    L3 = draw(st.floats(0.15, 0.4))
    D = L3 + draw(st.floats(0.1, 0.6))
    psi = draw(st.floats(-math.pi, math.pi))
    O1 = [D * math.cos(psi), D * math.sin(psi)]
    lo, hi = sorted(math.sqrt(D * D + L3 * L3 - 2 * D * L3 * math.cos(math.radians(t))) for t in (40, 140))
    beta = draw(st.floats(-math.pi, math.pi))
    LB = draw(st.floats(0.2, 0.6))
    B = [LB * math.cos(beta), LB * math.sin(beta)]
    l4 = draw(st.floats(0.3, 0.9))
    links = [{"name": "1", "points": {"O1": [0, 0], "K1": [draw(st.floats(0.05, 0.3)), 0.0]}},
             {"name": "2", "points": {"23": [0, 0], "K2": [-draw(st.floats(0.05, 0.3)), 0.0]}},
             {"name": "3", "points": {"O3": [0, 0], "23": [L3, 0], "B": B}},
             {"name": "4", "points": {"B": [0, 0], "C": [l4, 0], "M4": [0.5 * l4, 0.05]}}]
    joints = [{"type": "R", "links": ["0", "1"], "point": "O1"}, {"type": "R", "links": ["2", "3"], "point": "23"},
              {"type": "R", "links": ["0", "3"], "point": "O3"}, {"type": "R", "links": ["3", "4"], "point": "B"},
              {"type": "R", "links": ["4", "5"], "point": "C"}]
    frame = {"O1": O1, "O3": [0, 0]}
    if draw(st.booleans()):
        gam = draw(st.floats(-math.pi, math.pi))
        e = draw(st.floats(-0.1, 0.1))
        assume(l4 > LB + abs(e) + 0.1)
        links.append({"name": "5", "points": {"C": [0, 0], "K5": [0.1, 0.03]}})
        joints.append({"type": "P", "guide": "0", "slider": "5", "point": "C",
                       "line": {"through": [-math.sin(gam) * e, math.cos(gam) * e], "angle": gam}, "name": "50"})
    else:
        l5 = draw(st.floats(0.3, 0.9))
        d_lo, d_hi = abs(l4 - l5) + LB + 0.05, l4 + l5 - LB - 0.05
        assume(d_lo < d_hi)
        dO5 = draw(st.floats(d_lo, d_hi))
        ang = draw(st.floats(-math.pi, math.pi))
        frame["O5"] = [dO5 * math.cos(ang), dO5 * math.sin(ang)]
        links.append({"name": "5", "points": {"O5": [0, 0], "C": [l5, 0]}})
        joints.append({"type": "R", "links": ["0", "5"], "point": "O5"})
    data = {"frame": {"points": frame}, "links": links, "joints": joints,
            "driver": {"type": "actuator", "cylinder": "1", "rod": "2", "base": "O1", "end": "23",
                       "range": [lo, hi]},
            "grid": {"positions": 6, "cycle_points": 360},
            "sketch": {"at": lo, "points": {"C": [draw(st.floats(-2, 2)), draw(st.floats(-2, 2))]}}}
    return data, None


# ----------------------------------------------------------------------------- the checks

def _vec(row, pre, p):
    return np.array([row[f"{pre}x_{p}"], row[f"{pre}y_{p}"]], dtype=float)


def _cross(r, f):
    return r[0] * f[1] - r[1] * f[0]


def link_loads(study, row, static: bool):
    """(link, point or None, force, moment) of every load, written out from the case data and
    the kinematics (true motion at the driver's constant ω, ε)."""
    mech = study.mechanism
    data = study.spec.data
    out = []
    for l in mech.moving:
        if l.weight:
            out.append((l.name, l.com, np.array([0.0, -l.weight]), 0.0))
        if not static and l.mass:
            out.append((l.name, l.com, -l.mass * _vec(row, "a", l.com), 0.0))
        if not static and l.J_S:
            out.append((l.name, None, np.zeros(2), -l.J_S * row["e_" + l.name]))
    for f in data.get("loads", {}).get("force", []):
        out.append((f["link"], f["point"], np.array(f["F"], dtype=float), 0.0))
    for m in data.get("loads", {}).get("moment", []):
        out.append((m["link"], None, np.zeros(2), float(m["M"])))
    return out


def pair_loads(study, t):
    """(link, point, force, moment) of every reaction acting on every moving link, read from the
    exported columns in the orientation «force of the other link on this link»."""
    mech = study.mechanism
    out = []
    for j in mech.joints:
        a, b = j.links
        for this, other in ((b, a), (a, b)):
            key = f"{other}_{this}"
            f = np.array([t["Rx_" + key], t["Ry_" + key]])
            m = 0.0
            if j.kind == "P":
                m = t[f"Mp_{a}_{b}"] * (1.0 if this == b else -1.0)
            if this != FRAME:
                out.append((this, j.point, f, m))
    d = mech.driver
    if d.rotary:
        out.append((d.link, None, np.zeros(2), t["M_bal"]))
    else:
        for this, other in ((d.rod, d.link), (d.link, d.rod)):
            key = f"{other}_{this}"
            sgn = 1.0 if this == d.rod else -1.0
            out.append((this, d.end, np.array([t["Rx_" + key], t["Ry_" + key]]), sgn * t[f"Mp_{d.link}_{d.rod}"]))
    return out


def check_position(study, row, t, static: bool) -> tuple[float, float]:
    """Largest equilibrium residual of the links (relative) and the power-balance residual."""
    mech = study.mechanism
    loads = link_loads(study, row, static)
    reacts = pair_loads(study, t)
    size = mech.size()
    worst = 0.0
    # residuals relative to the largest load or reaction of the whole mechanism: a link that
    # carries only round-off (1e-16 N) must not be judged relative to its own round-off
    scale = max((max(float(np.hypot(*f)), abs(m) / size) for _, _, f, m in loads + reacts), default=0.0)
    for l in mech.moving:
        F = np.zeros(2)
        M = 0.0
        for link, p, f, m in loads + reacts:
            if link != l.name:
                continue
            F += f
            M += m + (_cross(_vec(row, "", p), f) if p is not None else 0.0)
        if scale == 0.0:
            continue
        worst = max(worst, float(np.hypot(*F)) / scale, abs(M) / (scale * size))
    # virtual power: M_ур·φ′₁ (or F·1) + Σ F·x′ + Σ M·φ′ = 0
    terms = []
    for link, p, f, m in loads:
        if p is not None:
            terms.append(float(f @ _vec(row, "vq", p)))
        if m:
            terms.append(m * row["wq_" + link])
    d = mech.driver
    drive = t["M_bal"] * d.direction if d.rotary else t["F_act"]
    # scale: the terms themselves, or the loads times the size where the analogs vanish
    fs = sum(float(np.hypot(*f)) + abs(m) / size for _, _, f, m in loads)
    total = max(abs(drive) + sum(abs(x) for x in terms), fs * (size if d.rotary else 1.0))
    power = abs(drive + sum(terms)) / total if total else 0.0
    return worst, power


def check_study(study, qs):
    static = study.spec.data["forces"].get("mode") == "static"
    f = study.forces
    tab = f.frame(f.solve(qs))
    kin = study.at(qs)
    worst = power = 0.0
    for i in range(len(qs)):
        e, p = check_position(study, kin.iloc[i], tab.iloc[i], static)
        worst, power = max(worst, e), max(power, p)
    assert worst <= TOL_EQUILIBRIUM, f"equilibrium residual {worst:.3e}"
    assert power <= TOL_POWER, f"power balance residual {power:.3e}"
    # the module's own checks agree (Жуковский's lever, power balance)
    assert float(tab["dev_zhukovsky_pct"].max()) <= 1e-6
    assert float(tab["dev_power"].max()) <= TOL_POWER
    return tab


q_draw = st.lists(st.floats(0.0, 2 * math.pi, exclude_max=True), min_size=3, max_size=3)


def _property(strategy):
    @SETTINGS
    @given(loaded(strategy), q_draw)
    def test(data, qs):
        study, _ = _solve(data)
        check_study(study, qs)
    return test


globals().update(property_tests(_property))     # test_rrr_crank_rocker … test_six_bar_rrr_rrp


@SETTINGS
@given(loaded(actuator_linkage()), st.lists(st.floats(0.0, 1.0), min_size=3, max_size=3))
def test_actuator_linkage(data, ts):
    study, _ = _solve(data)       # μ ≥ 5° over the cycle, as the other families
    lo, hi = data["driver"]["range"]
    check_study(study, [lo + t * (hi - lo) for t in ts])


@SETTINGS
@given(actuator_linkage(), st.floats(100.0, 5e4), st.floats(0.0, 1.0))
def test_static_actuator_force_is_load_times_transfer_ratio(drawn, P, t):
    """Static mode, one vertical load P at a point X of the output link: F = P·dy_X/dS."""
    data, _ = drawn
    out = data["links"][-1]
    X = sorted(out["points"])[-1]
    data["loads"] = {"weights": False, "force": [{"name": "P", "link": out["name"], "point": X, "F": [0.0, -P]}]}
    data["forces"] = {"mode": "static"}
    study = Study(CaseSpec(Path("random.toml"), data))
    lo, hi = data["driver"]["range"]
    S = lo + t * (hi - lo)
    try:
        kin = study.at([S])
    except AssemblyError:
        assume(False)
    f = study.forces
    tab = f.frame(f.solve([S]))
    i_X = float(kin[f"vqy_{X}"].iloc[0])
    assert abs(tab.F_act.iloc[0] - P * i_X) <= 1e-10 * P * max(1.0, abs(i_X))


# ----------------------------------------------------------------------------- class III

def test_class_three_triad_equilibrium_and_power():
    data = tomllib.loads((ROOT / "cases" / "class3_triad.toml").read_text(encoding="utf-8"))
    masses = {"1": (1.5, 0.01, "A"), "2": (2.0, 0.04, "B"), "3": (5.0, 0.08, "S3"), "4": (1.2, 0.02, "C"),
              "5": (1.4, 0.03, "D")}
    for ln in data["links"]:
        m, J, S = masses[ln["name"]]
        ln.update(mass=m, J_S=J, com=S)
    data["driver"]["epsilon"] = 7.0
    data["loads"] = {"force": [{"name": "Fa", "link": "3", "point": "C", "F": [300.0, -150.0]}],
                     "moment": [{"name": "Ma", "link": "5", "M": -40.0}]}
    data["forces"] = {"motion": "constant"}
    study = Study(CaseSpec(ROOT / "cases" / "class3_triad.toml", data))
    groups = study.forces.model.groups
    assert [len(g.links) for g in groups] == [4, 1]
    check_study(study, list(np.linspace(0.0, 2 * math.pi, 7, endpoint=False) + 0.1))


# ----------------------------------------------------------------------------- worksheet 000

@pytest.fixture(scope="module")
def frc000(ws000):
    return ws000.forces


def _global_solution(study, row):
    """All unknowns of the six-bar at once: R_0_1, R_1_2, R_2_3, R_0_3, R_3_4, R_4_5 (x, y),
    N and M_p of the slider on its guide, M_ур: 15 equations of the five links, moments about the
    origin, loads from the worksheet's data (g = 10 m/s², G_3 = 160 N, m_3 = 9 kg as the case)."""
    P = {p: _vec(row, "", p) for p in ("O", "A", "B", "C", "D", "H", "S2", "S4")}
    eps = row["eps"]
    dyn = study.dynamics
    J_fly = dyn.result.J_I - dyn.J_crank
    acc = {p: np.array([row[f"ax_{p}"], row[f"ay_{p}"]]) for p in ("S2", "B", "S4")}
    loads = {  # link: list of (point, force) and a moment
        "1": ([], -J_fly * (-eps)),                      # M_Φ1 = −J·ε₁, ε₁ = −ε (clockwise crank)
        "2": ([("S2", np.array([0, -90.0])), ("S2", -9.0 * acc["S2"])], -0.45 * row["e_2"]),
        "3": ([("B", np.array([0, -160.0])), ("B", -9.0 * acc["B"])], -0.55 * row["e_3"]),
        "4": ([("S4", np.array([0, -220.0])), ("S4", -22.0 * acc["S4"])], -1.61 * row["e_4"]),
        "5": ([("H", np.array([0, -35.0])), ("H", np.array([-9000.0 if row["vqx_H"] >= 0 else 0.0, 0.0]))], 0.0),
    }
    pins = [("0", "1", "O"), ("1", "2", "A"), ("2", "3", "B"), ("0", "3", "C"), ("3", "4", "D"), ("4", "5", "H")]
    links = ["1", "2", "3", "4", "5"]
    A = np.zeros((15, 15))
    b = np.zeros(15)
    for k, l in enumerate(links):
        pts, M = loads[l]
        F = sum((f for _, f in pts), np.zeros(2))
        b[3 * k:3 * k + 2] = -F
        b[3 * k + 2] = -(M + sum(_cross(P[p], f) for p, f in pts))
    for c, (a, bb, p) in enumerate(pins):
        for link, s in ((bb, 1.0), (a, -1.0)):
            if link == "0":
                continue
            k = links.index(link)
            A[3 * k, 2 * c] += s
            A[3 * k + 1, 2 * c + 1] += s
            A[3 * k + 2, 2 * c] += -s * P[p][1]
            A[3 * k + 2, 2 * c + 1] += s * P[p][0]
    k5 = links.index("5")
    A[3 * k5 + 1, 12] = 1.0                              # N·(0, 1) of the horizontal guide on 5
    A[3 * k5 + 2, 12] = P["H"][0]
    A[3 * k5 + 2, 13] = 1.0                              # M_p
    A[2, 14] = 1.0                                       # M_ур on the crank
    x = np.linalg.solve(A, b)
    out = {f"{a}_{bb}": x[2 * c:2 * c + 2] for c, (a, bb, p) in enumerate(pins)}
    out.update(N_0_5=x[12], Mp_0_5=x[13], M_bal=x[14])
    return out


def test_ws000_reactions_at_f_against_a_global_solution(frc000, ws000):
    row_f = frc000.row("f")
    mot = ws000.dynamics.motion
    kin = mot[mot.pos == "f"].iloc[0].copy()
    k = ws000.kinematics
    for c in k.columns:
        if c.startswith(("x_", "y_", "vq")):
            kin[c] = k[k.pos == "f"].iloc[0][c]
    ref = _global_solution(ws000, kin)
    scale = max(np.hypot(*v) for key, v in ref.items() if key not in ("N_0_5", "Mp_0_5", "M_bal"))
    for key, v in ref.items():
        if key in ("N_0_5", "Mp_0_5", "M_bal"):
            assert abs(row_f[key] - v) <= 1e-10 * scale, key
        else:
            assert abs(row_f["Rx_" + key] - v[0]) <= 1e-10 * scale, key
            assert abs(row_f["Ry_" + key] - v[1]) <= 1e-10 * scale, key
    # magnitudes of the order of the cutting force; the slider is pressed down onto its guide
    assert 5000 < row_f.R_4_5 < 20000 and row_f.N_0_5 > 0


def test_ws000_zhukovsky_and_power_at_f(frc000, ws000):
    r = frc000.row("f")
    assert abs(r.M_bal - r.M_bal_zhukovsky) <= 1e-10 * abs(r.M_bal)
    assert abs(r.M_bal - r.M_bal_power) <= 1e-10 * abs(r.M_bal)
    assert r.dev_zhukovsky_pct <= 1e-8
    # with the inertia moment of the first group on the crank (worksheet: M_Φ1 = −J_1пр·ε) the
    # balancing moment is the driving moment of the dynamics (clockwise crank: negative)
    assert abs(r.M_bal - (-ws000.dynamics.scalars["M_d"])) <= 1e-10 * abs(r.M_bal)
    assert frc000.scalars["dev_zhukovsky_max_pct"] <= 1e-8
    # both orientations of every pair
    for key in ("0_1", "1_2", "2_3", "0_3", "3_4", "4_5", "0_5"):
        a, b = key.split("_")
        assert r[f"Rx_{b}_{a}"] == -r[f"Rx_{key}"] and r[f"R_{b}_{a}"] == r[f"R_{key}"]
