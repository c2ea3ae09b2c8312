"""The kinematic engine against the independent high-precision reference (tests/reference.py).

For the worksheet cases and the extra example cases, at positions that no worksheet prints,
``study.at(q)`` must agree with the reference (Newton at 50 digits on the poses of all links,
5-point stencils with h = 1e-12): scaled error |x − x_ref| / max(1, |x_ref|) ≤ 1e-12 for
positions and first analogs, ≤ 1e-11 for second analogs.  Loop closure is recomputed from the
DataFrame at every point of the cycle grid (≤ 1e-12·size).
"""
from __future__ import annotations

import math
import sys
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest
from mpmath import mp, mpf

sys.path.insert(0, str(Path(__file__).resolve().parent))

from reference import (DPS, closure_residuals, reference_columns, scaled_errors)  # noqa: E402
from reportgen import load_case  # noqa: E402
from reportgen.analysis.study import Study  # noqa: E402
from reportgen.case.load import CaseSpec  # noqa: E402

CASES = Path(__file__).resolve().parents[1] / "cases"
WORKSHEETS = ["ws000_six_bar", "ws002_tractor_hitch", "ws004_slotted_lever"]
EXTRA = ["slider_crank", "four_bar", "whitworth", "class3_triad"]
ALL = WORKSHEETS + EXTRA

TOL = {"position": 1e-12, "first": 1e-12, "second": 1e-11}
TOL_CLOSURE = 1e-12

# crank angles (rad) that are not on any worksheet's grid (multiples of 30°, ws000's 99.1°)
ROTARY_Q = [0.37, 1.9, 4.1, 2.77, 5.3, 6.0]
# actuator lengths (m) inside ws002's range [0.42, 0.67] m, off its 10-point grid and off S_p
ACTUATOR_Q = [0.4213, 0.4571, 0.5032, 0.5517, 0.6094, 0.6688]


@lru_cache(maxsize=None)
def study(name: str):
    return load_case(CASES / f"{name}.toml")


def positions(s) -> list[float]:
    d = s.mechanism.driver
    if d.rotary:
        return ROTARY_Q
    lo, hi = d.q_range
    qs = [q for q in ACTUATOR_Q if lo < q < hi]
    assert len(qs) == len(ACTUATOR_Q), f"actuator test lengths {ACTUATOR_Q} are not inside {d.q_range}"
    return qs


def assert_matches_reference(s, qs, label: str, df=None) -> dict:
    """Every column of the engine at ``qs`` (``df``, else solved here) within TOL of the
    independent reference (scaled errors); returns the errors."""
    df = s.at(qs) if df is None else df
    ref = reference_columns(s, qs, frame=df)
    err = scaled_errors(df, ref)
    for kind, tol in TOL.items():
        e, col, i = err[kind]
        assert e <= tol, (f"{label}: {kind} column {col} at q = {qs[i]!r}: scaled error {e:.3e} > {tol:g} "
                          f"(engine {df[col].iloc[i]!r}, reference {float(ref[col][i])!r})")
    return err


# ----------------------------------------------------------------------------- the cases

@pytest.mark.parametrize("name", ALL)
def test_positions_and_analogs_match_reference(name):
    s = study(name)
    qs = positions(s)
    assert not np.isin(np.round(qs, 9), np.round(s.grid.q, 9)).any(), "test positions must be off the report grid"
    assert_matches_reference(s, qs, name)


@pytest.mark.parametrize("name", ALL)
def test_loop_closure_on_the_cycle_grid(name):
    s = study(name)
    cyc = s.cycle
    assert len(cyc) == len(s.grid.cycle)
    size = s.mechanism.size()
    res, where = closure_residuals(s.mechanism, cyc)
    assert res <= TOL_CLOSURE * size, f"{name}: loop closure {res:.3e} > {TOL_CLOSURE:g}·{size:.3g} ({where})"


@pytest.mark.parametrize("name", [n for n in ALL if n != "ws002_tractor_hitch"])
def test_true_motion_from_reference_analogs(name):
    """v = ω·x′ and a = ω²·x″ + ε·x′ with the reference analogs (driver speed of the case)."""
    s = study(name)
    d = s.mechanism.driver
    assert d.omega is not None
    qs = positions(s)[:3]
    df = s.at(qs)
    ref = reference_columns(s, qs, frame=df)
    w, e = mpf(d.omega), mpf(d.epsilon)
    worst = (0.0, "")
    with mp.workdps(DPS):
        for col in ref:
            for pre, (vq, aq, v, a) in {"x_": ("vqx_", "aqx_", "vx_", "ax_"), "y_": ("vqy_", "aqy_", "vy_", "ay_"),
                                         "phi_": ("wq_", "eq_", "w_", "e_"),
                                         "s_": ("vqs_", "aqs_", "vs_", "as_")}.items():
                if not col.startswith(pre):
                    continue
                base = col[len(pre):]
                for i in range(len(qs)):
                    vr = w * ref[vq + base][i]
                    ar = w * w * ref[aq + base][i] + e * ref[vq + base][i]
                    for c, r in ((v + base, vr), (a + base, ar)):
                        err = float(abs(mpf(float(df[c].iloc[i])) - r) / max(1, abs(r)))
                        if err > worst[0]:
                            worst = (err, c)
    assert worst[0] <= 1e-11, f"{name}: true motion {worst[1]} scaled error {worst[0]:.3e}"


# ----------------------------------------------------------------------------- the extra cases

EXPECTED_GROUPS = {"slider_crank": ["RRP"], "four_bar": ["RRR"], "whitworth": ["RPR", "RRP"], "class3_triad": []}


@pytest.mark.parametrize("name", EXTRA)
def test_extra_case_loads_solves_and_matches_reference(name):
    s = load_case(CASES / f"{name}.toml")
    assert [g.kind for g in s.structure.groups if g.klass == 2] == EXPECTED_GROUPS[name]
    assert s.structure.W == 1
    if name == "class3_triad":        # a class III group of order 3, solved by Newton
        (g,) = [g for g in s.structure.groups if g.klass == 3]
        assert g.order == 3 and g.solver == "NEWTON" and s.structure.mech_class == 3
    k = s.kinematics
    assert len(k) == 12 and list(k["pos"]) == [str(i) for i in range(12)]
    cyc = s.cycle                       # the whole cycle assembles (AssemblyError otherwise)
    assert np.isfinite(cyc.to_numpy(dtype=float)).all()
    # the report positions themselves against the reference
    assert_matches_reference(s, list(k["q"]), name + " (report positions)")
    for c in cyc.columns:
        if c.startswith("mu_"):
            assert cyc[c].min() > math.radians(30), f"{name}: poor transmission angle {c}"


def test_extra_case_geometry():
    """The example cases are what their comments say."""
    # offset slider-crank: stroke of B = sqrt((l+r)² − e²) − sqrt((l−r)² − e²)
    s = study("slider_crank")
    xb = s.cycle["x_B"]
    r, l, e = 0.1, 0.4, 0.02
    assert math.isclose(xb.max() - xb.min(), math.sqrt((l + r) ** 2 - e ** 2) - math.sqrt((l - r) ** 2 - e ** 2),
                        rel_tol=1e-6)
    assert np.allclose(s.cycle["y_B"], e, atol=1e-15)
    # Grashof crank-rocker: the rocker oscillates, the crank turns fully
    s = study("four_bar")
    phi3 = s.cycle["phi_3"].to_numpy()
    assert np.ptp(phi3) < math.pi and abs(phi3[-1] - phi3[0]) < 1e-9
    # Whitworth: the slotted link turns fully with the crank; time ratio of the ram K = 2
    s = study("whitworth")
    cyc = s.cycle
    phi3 = cyc["phi_3"].to_numpy()
    assert math.isclose(phi3[-1] - phi3[0], 2 * math.pi, rel_tol=1e-9)
    q, xd = cyc["q"].to_numpy(), cyc["x_D"].to_numpy()
    q_min, q_max = q[np.argmin(xd)], q[np.argmax(xd)]
    fwd = (q_max - q_min) % (2 * math.pi)
    ratio = max(fwd, 2 * math.pi - fwd) / min(fwd, 2 * math.pi - fwd)
    assert abs(ratio - 2.0) < 0.01, f"Whitworth time ratio {ratio}"


# ----------------------------------------------------------------------------- reference sanity

def test_reference_against_closed_form_slider_crank():
    """The reference solver itself against the closed form of the offset slider-crank
    x_B = r cos q + sqrt(l² − (e − r sin q)²) (derivatives by mpmath's own mp.diff)."""
    s = study("slider_crank")
    qs = [0.37, 1.9, 4.1]
    ref = reference_columns(s, qs)
    with mp.workdps(DPS):
        r, l, e = mpf(s.mechanism.link("1").points["A"][0]), mpf(s.mechanism.link("2").points["B"][0]), \
            mpf(s.mechanism.joints[-1].line_point[1])

        def xb(q):
            return r * mp.cos(q) + mp.sqrt(l * l - (e - r * mp.sin(q)) ** 2)

        for i, q in enumerate(qs):
            q = mpf(q)
            for col, n in (("x_B", 0), ("vqx_B", 1), ("aqx_B", 2)):
                exact = mp.diff(xb, q, n)
                assert abs(ref[col][i] - exact) < mpf("1e-25"), f"reference {col} at {float(q)}: {ref[col][i]} vs {exact}"


# ----------------------------------------------------------------------------- rod guides
#
# A prismatic pair whose GUIDE is the actuator's rod.  The kernel merges the rod into the
# cylinder body, so the rod's local points are p0 + q·(1, 0), for revolute and prismatic pairs
# alike (jf columns 6..9 of a prismatic pair).  Before this was handled the guide line was placed
# through the cylinder's base instead of the rod end: wrong positions without an error (T-head)
# or a valid mechanism reported as not assembling (transverse bar).


def _t_head() -> dict:
    """ВПВ with the cylinder: the rod 2 ends in a transverse T-head (guide through the rod end E
    at 90° to the rod); the lever 3 (pivot C) slides on it with its point K (the lever's local x
    axis lies along the T-head)."""
    return {
        "frame": {"points": {"O1": [0.0, 0.0], "C": [0.8, 0.3]}},
        "links": [
            {"name": "1", "title": "гидроцилиндр", "points": {"O1": [0, 0]}},
            {"name": "2", "title": "шток с поперечной направляющей", "points": {"E": [0, 0]}},
            {"name": "3", "title": "рычаг", "points": {"C": [0, 0], "K": [0.5, 0]}},
        ],
        "joints": [
            {"type": "R", "links": ["0", "1"], "point": "O1"},
            {"type": "P", "name": "32", "guide": "2", "slider": "3", "point": "K",
             "line": {"through": "E", "angle": math.pi / 2}},
            {"type": "R", "links": ["0", "3"], "point": "C"},
        ],
        "driver": {"type": "actuator", "cylinder": "1", "rod": "2", "base": "O1", "end": "E",
                   "range": [0.5, 0.7], "speed": 0.1},
        "grid": {"positions": 5},
        "sketch": {"points": {"K": [0.6, 0.7]}},
    }


def _transverse_bar() -> dict:
    """Cylinder 1–2 and rocker 3 (ВВВ, as in ws002); the rod carries a bar through its end E at 90°
    on which the slider 4 moves, pinned at F to the link 5 pivoted at D (a later ВВП group)."""
    return {
        "frame": {"points": {"O1": [0.0, 0.0], "C": [0.6, 0.5], "D": [0.5, 1.1]}},
        "links": [
            {"name": "1", "title": "гидроцилиндр", "points": {"O1": [0, 0]}},
            {"name": "2", "title": "шток с поперечной штангой", "points": {"E": [0, 0]}},
            {"name": "3", "title": "коромысло", "points": {"C": [0, 0], "E": [0.4, 0]}},
            {"name": "4", "title": "ползун", "points": {"F": [0, 0]}},
            {"name": "5", "title": "коромысло", "points": {"D": [0, 0], "F": [0.5, 0]}},
        ],
        "joints": [
            {"type": "R", "links": ["0", "1"], "point": "O1"},
            {"type": "R", "links": ["2", "3"], "point": "E"},
            {"type": "R", "links": ["0", "3"], "point": "C"},
            {"type": "P", "name": "42", "guide": "2", "slider": "4", "point": "F",
             "line": {"through": "E", "angle": math.pi / 2}},
            {"type": "R", "links": ["4", "5"], "point": "F"},
            {"type": "R", "links": ["0", "5"], "point": "D"},
        ],
        "driver": {"type": "actuator", "cylinder": "1", "rod": "2", "base": "O1", "end": "E",
                   "range": [0.45, 0.65], "speed": 0.1},
        "grid": {"positions": 5},
        "sketch": {"points": {"E": [0.54, 0.1], "F": [0.5, 0.6]}},
    }


def _transverse_bar_guess(q: float) -> list[float]:
    """Poses (links 1..5) of the transverse-bar mechanism by hand geometry (for the reference)."""
    C, D = np.array([0.6, 0.5]), np.array([0.5, 1.1])
    d = float(np.linalg.norm(C))
    x = (q * q - 0.4 ** 2 + d * d) / (2 * d)
    h = math.sqrt(q * q - x * x)
    ex = C / d
    E = x * ex + h * np.array([ex[1], -ex[0]])
    th = math.atan2(E[1], E[0])
    u = np.array([-math.sin(th), math.cos(th)])
    w = E - D
    b = float(w @ u)
    F = E + (-b - math.sqrt(b * b - (float(w @ w) - 0.5 ** 2))) * u
    th3 = math.atan2(E[1] - C[1], E[0] - C[0])
    th5 = math.atan2(F[1] - D[1], F[0] - D[0])
    return [0, 0, th, E[0], E[1], th, C[0], C[1], th3, F[0], F[1], th + math.pi / 2, D[0], D[1], th5]


@pytest.mark.parametrize("build, qs, what", [
    (_t_head, [0.55, 0.6, 0.65], "T-head on the rod, ВПВ group with the cylinder"),
    (_transverse_bar, [0.5, 0.55, 0.6], "transverse bar on the rod, later ВВП group")],
    ids=["t-head-RPR", "transverse-bar-RRP"])
def test_prismatic_pair_guided_by_the_actuator_rod(build, qs, what):
    """Regression: a prismatic pair guided by the actuator's rod, whose points move with q
    (p = p0 + q·(1, 0) in the merged cylinder–rod body)."""
    from reference import ReferenceMechanism
    from reportgen.errors import AssemblyError

    s = Study(CaseSpec(Path("rod_guide.toml"), build()))
    label = f"prismatic pair guided by the actuator rod ({what})"
    if build is _transverse_bar:
        # the mechanism is valid: the reference assembles it exactly from a hand-made guess
        ref_mech = ReferenceMechanism(s.mechanism)
        for q in qs:
            ref_mech.evaluate(q, _transverse_bar_guess(q))
    try:
        df = s.at(qs)
    except AssemblyError as e:
        raise AssertionError(
            f"{label}: the engine reports that a valid mechanism does not assemble ({e}); "
            f"the kernel places the rod's guide line through the cylinder base instead of the rod end "
            f"(q·(1, 0) of the rod's line point is dropped for prismatic pairs)") from None
    res, where = closure_residuals(s.mechanism, df)
    size = s.mechanism.size()
    assert res <= TOL_CLOSURE * size, (
        f"{label}: loop closure violated by {res:.3g} m ({where}) — the kernel drops the "
        f"q-dependent part q·(1, 0) of the rod's line point (guide placed through the cylinder base)")
    assert_matches_reference(s, qs, label, df)
