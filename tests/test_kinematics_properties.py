"""Property tests of the kinematic engine on random mechanisms of every kind of class II group.

Each strategy draws a case dict (bare numbers are SI) with random dimensions, offsets, guide
angles, a random placement of the whole mechanism, random local frames of the links (rotation and
translation; a slider's frame only translated, because its local x axis must lie along its guide),
random crank phase and direction and a random sketch point, so that both assembly branches occur.
Draws that do not assemble over the whole cycle (``AssemblyError``) or whose transmission angles
``mu_*`` fall below ``MU_MIN`` somewhere on ``study.cycle`` are rejected with ``assume``.

Properties checked for every accepted draw:

* loop closure over the whole cycle grid (``reference.closure_residuals``) ≤ 1e-12·size;
* positions and first/second analogs at two random q, at the grid point of the poorest
  transmission angle and at a random grid point, against the independent mpmath reference
  (``reference.reference_columns``: Newton at 50 digits, 5-point stencils with h = 1e-12; the
  reference's own error is < 1e-25, so the bounds below measure the engine only):
  scaled error |x − x_ref| / max(1, |x_ref|) ≤ 1e-12 for positions and first analogs and
  ≤ 1e-11 for second analogs;
* ``study.at([q])`` equals the row of ``study.cycle`` at the same q (angles modulo 2π) to 1e-12
  (scaled as above).

The random cases use a cycle grid of ``CYCLE_POINTS`` = 720 steps (the default is 3600) and
``EXAMPLES`` draws per kind to keep the run time of the file at ~25 s.
"""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parent))

from reference import closure_residuals, reference_columns, scaled_errors  # noqa: E402
from reportgen.analysis.study import Study  # noqa: E402
from reportgen.case.load import CaseSpec  # noqa: E402
from reportgen.errors import AssemblyError  # noqa: E402

MU_MIN = math.radians(5.0)
CYCLE_POINTS = 720
TOL_POS = 1e-12
TOL_FIRST = 1e-12
TOL_SECOND = 1e-11
TOL_CLOSURE = 1e-12
TOL_AT_CYCLE = 1e-12
EXAMPLES = 15

SETTINGS = settings(max_examples=EXAMPLES, deadline=None, database=None, derandomize=True,
                    suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])

# ----------------------------------------------------------------------------- drawing helpers

angle = st.floats(-math.pi, math.pi)
shift = st.floats(-0.3, 0.3)
unit = st.floats(0.0, 1.0)


def rot(b, p):
    c, s = math.cos(b), math.sin(b)
    return (c * p[0] - s * p[1], s * p[0] + c * p[1])


class Placement:
    """A rigid transform p ↦ R(β) p + t (used for the global placement and for local frames)."""

    def __init__(self, beta=0.0, tx=0.0, ty=0.0):
        self.beta, self.t = beta, (tx, ty)

    def __call__(self, p):
        x, y = rot(self.beta, p)
        return [x + self.t[0], y + self.t[1]]

    def line(self, through, ang):
        return {"through": self(through), "angle": ang + self.beta}


@st.composite
def frames(draw, rotate=True):
    """A random local frame of a link (a slider: rotate=False)."""
    b = draw(angle) if rotate else 0.0
    return Placement(b, draw(shift), draw(shift))


def pts(frame: Placement, canon: dict) -> dict:
    return {k: frame(v) for k, v in canon.items()}


def R(a, b, p):
    return {"type": "R", "links": [a, b], "point": p}


def P(guide, slider, point, line, offset=0.0, name=None):
    j = {"type": "P", "guide": guide, "slider": slider, "point": point, "line": line, "offset": offset}
    if name:
        j["name"] = name
    return j


def link(name, points):
    return {"name": name, "points": points}


@st.composite
def cranks(draw, link_name="1", center="O"):
    return {"type": "crank", "link": link_name, "center": center, "phi0": draw(angle),
            "direction": draw(st.sampled_from(["ccw", "cw"])), "omega": 10.0}


def case(frame_points, links, joints, driver, sketch):
    return {"frame": {"points": frame_points}, "links": links, "joints": joints, "driver": driver,
            "grid": {"positions": 12, "cycle_points": CYCLE_POINTS}, "sketch": {"points": sketch}}


sketch_point = st.tuples(st.floats(-2, 2), st.floats(-2, 2)).map(list)


# ----------------------------------------------------------------------------- the six kinds

@st.composite
def four_bar(draw, with_rocker_arm=False):
    """ВВВ: Grashof crank-rocker four-bar with a coupler point (optionally a rocker arm D)."""
    a = draw(st.floats(0.08, 0.35))
    b, c, d = draw(st.floats(0.3, 1.4)), draw(st.floats(0.3, 1.4)), draw(st.floats(0.4, 1.4))
    rest = [b, c, d]
    assume(a + max(rest) < sum(rest) - max(rest) - 0.005 and a < min(rest) - 0.01)
    g = draw(frames())
    f1, f2, f3 = draw(frames()), draw(frames()), draw(frames())
    rm, am = draw(unit), draw(angle)
    canon3 = {"C": (0, 0), "B": (c, 0), "S3": (0.5 * c, 0)}
    if with_rocker_arm:
        canon3["D"] = rot(draw(angle), (draw(st.floats(0.1, 0.5)), 0))
    data = case(
        {"O": g((0, 0)), "C": g((d, 0))},
        [link("1", pts(f1, {"O": (0, 0), "A": (a, 0)})),
         link("2", pts(f2, {"A": (0, 0), "B": (b, 0), "M": (rm * math.cos(am), rm * math.sin(am))})),
         link("3", pts(f3, canon3))],
        [R("0", "1", "O"), R("1", "2", "A"), R("2", "3", "B"), R("0", "3", "C")],
        draw(cranks()), {"B": draw(sketch_point)})
    return data, g


@st.composite
def slider_crank(draw):
    """ВВП: offset slider-crank on a guide of random direction; the slider's guide point is the
    pin B or another slider point K.  Variant ``block_guides_frame``: the pair is written the other
    way round — the block 3 carries the guide line and the frame is the "slider" with its point Q
    (so the guide direction is the frame's x axis); this exercises the guide-is-unknown branch."""
    a = draw(st.floats(0.05, 0.3))
    l = draw(st.floats(0.3, 1.2))
    e1, e2 = draw(st.floats(-0.2, 0.2)), draw(st.floats(-0.1, 0.1))
    t0 = draw(st.floats(-1, 1))
    g = draw(frames())
    f1, f2 = draw(frames()), draw(frames())
    block_guides_frame = draw(st.booleans())
    if block_guides_frame:
        gam = -g.beta                   # the guide must lie along the frame's x axis
        f3 = draw(frames())             # the block is now the guide: any local frame
        L = (draw(st.floats(-0.2, 0.2)), draw(st.floats(-0.1, 0.1)))
        e_pin = e1 - L[1] - e2
        slider = pts(f3, {"B": (0, 0), "K": (0.1, 0.05)})
    else:
        gam = draw(angle)
        f3 = draw(frames(rotate=False))
        k = draw(st.tuples(st.floats(-0.2, 0.2), st.floats(-0.1, 0.1)))
        use_k = draw(st.booleans())
        e_pin = e1 + e2 - (k[1] if use_k else 0.0)
        slider = pts(f3, {"B": (0, 0), "K": k})
    assume(a + abs(e_pin) < l - 0.005)
    n = rot(gam, (0, e1))
    u = rot(gam, (t0, 0))
    on_line = (n[0] + u[0], n[1] + u[1])
    frame_points = {"O": g((0, 0))}
    if block_guides_frame:
        frame_points["Q"] = g(on_line)
        prism = P("3", "0", "Q", f3.line(L, 0.0), e2, name="03")
    else:
        prism = P("0", "3", "K" if use_k else "B", g.line(on_line, gam), e2, name="30")
    data = case(
        frame_points,
        [link("1", pts(f1, {"O": (0, 0), "A": (a, 0)})),
         link("2", pts(f2, {"A": (0, 0), "S2": (0.4 * l, 0), "B": (l, 0)})),
         link("3", slider)],
        [R("0", "1", "O"), R("1", "2", "A"), R("2", "3", "B"), prism],
        draw(cranks()), {"B": draw(sketch_point)})
    return data, g


@st.composite
def slotted_lever(draw):
    """ВПВ: crank OA, block 2 pinned at A, link 3 pivoted at C; the prismatic pair 2–3 with the
    guide on link 3 (block slides in the slot) or on the block (link 3 slides in a swinging
    sleeve).  |OC| > OA: oscillating lever; |OC| < OA: rotating lever (Whitworth)."""
    a = draw(st.floats(0.05, 0.4))
    d = draw(st.floats(0.05, 1.2))
    assume(abs(d - a) > 0.05)
    e = draw(st.floats(-0.3, 0.3))
    assume(abs(e) < abs(d - a) - 0.03)
    guide_on_3 = draw(st.booleans())
    g = draw(frames())
    f1 = draw(frames())
    L3 = draw(st.floats(0.2, 1.0))
    canon3 = {"C": (0, 0), "B": (L3, 0)}
    if guide_on_3:
        f2, f3 = draw(frames(rotate=False)), draw(frames())
        slot = draw(angle)
        prism = P("3", "2", "A", f3.line((0, 0), slot), e, name="23")
        canon3["B"] = rot(slot, (L3, 0))
    else:
        f2, f3 = draw(frames()), draw(frames(rotate=False))
        prism = P("2", "3", "C", f2.line((0, 0), 0.0), e, name="32")
    data = case(
        {"O": g((0, 0)), "C": g((0, -d))},
        [link("1", pts(f1, {"O": (0, 0), "A": (a, 0)})),
         link("2", pts(f2, {"A": (0, 0)})),
         link("3", pts(f3, canon3))],
        [R("0", "1", "O"), R("1", "2", "A"), prism, R("0", "3", "C")],
        draw(cranks()), {"B": draw(sketch_point)})
    return data, g


@st.composite
def shaper(draw):
    """ПВП (after an oscillating ВПВ): block 4 slides on the lever 3 and is pinned at D to the
    ram 5 on a frame guide roughly perpendicular to the lever (the quick-return shaper).  With a
    fully rotating crank as the carrier of the guide the ПВП group would pass through parallel
    guides twice a turn, so its guide is carried by the oscillating lever.  Variant
    ``ram_guides_frame``: the ram's pair is written with the ram as the guide and the frame point Q
    as the "slider" (the ram then moves along the frame's x axis)."""
    a = draw(st.floats(0.05, 0.3))
    d = draw(st.floats(0.3, 1.0))
    assume(a / d <= 0.6)
    e1 = draw(st.floats(-0.05, 0.05))
    assume(abs(e1) < d - a - 0.03)
    ram_guides_frame = draw(st.booleans())
    g = draw(frames()) if not ram_guides_frame else Placement(draw(st.floats(-0.35, 0.35)), draw(shift), draw(shift))
    f1, f3 = draw(frames()), draw(frames())
    f2, f4 = draw(frames(rotate=False)), draw(frames(rotate=False))
    a4 = draw(st.floats(-0.2, 0.2))
    through4 = (draw(st.floats(-0.2, 0.2)), draw(st.floats(-0.1, 0.1)))
    e4 = draw(st.floats(-0.05, 0.05))
    H = d + draw(st.floats(0.1, 0.6))
    e5 = draw(st.floats(-0.05, 0.05))
    frame_points = {"O": g((0, d)), "C": g((0, 0))}
    if ram_guides_frame:
        f5 = draw(frames())
        L = (draw(st.floats(-0.3, 0.3)), draw(st.floats(-0.05, 0.05)))
        frame_points["Q"] = g((0, H))
        ram_pair = P("5", "0", "Q", f5.line(L, 0.0), e5, name="05")
    else:
        f5 = draw(frames(rotate=False))
        tau = draw(st.floats(-0.35, 0.35))
        ram_pair = P("0", "5", "D", g.line((0, H), tau), e5, name="50")
    data = case(
        frame_points,
        [link("1", pts(f1, {"O": (0, 0), "A": (a, 0)})),
         link("2", pts(f2, {"A": (0, 0)})),
         link("3", pts(f3, {"C": (0, 0), "B": (d + 0.7, 0), "T": through4})),
         link("4", pts(f4, {"D": (0, 0)})),
         link("5", pts(f5, {"D": (0, 0), "E": (0.3, 0.05)}))],
        [R("0", "1", "O"), R("1", "2", "A"), P("3", "2", "A", f3.line((0, 0), 0.0), e1, name="23"),
         R("0", "3", "C"), P("3", "4", "D", f3.line(through4, a4), e4, name="43"), R("4", "5", "D"),
         ram_pair],
        draw(cranks()), {"B": g((0, d + 0.7))})
    return data, g


@st.composite
def scotch_yoke(draw):
    """ВПП: block 2 pinned to the crank slides in the slot of the yoke 3, which slides on a frame
    guide; the slot is not parallel to the frame guide.  Variant ``yoke_guides_frame``: the yoke's
    pair with the frame is written with the yoke as the guide and the frame point Q as the
    "slider" (the yoke then moves along the frame's x axis and may have any local frame)."""
    a = draw(st.floats(0.05, 0.4))
    g = draw(frames())
    f1 = draw(frames())
    f2 = draw(frames(rotate=False))
    slot = draw(st.floats(0.5, math.pi - 0.5)) * draw(st.sampled_from([1, -1]))
    slot_through = (draw(shift), draw(shift))
    through0 = (draw(shift), draw(shift))
    e0 = draw(st.floats(-0.2, 0.2))
    frame_points = {"O": g((0, 0))}
    if draw(st.booleans()):
        f3 = draw(frames())
        frame_points["Q"] = g(through0)
        frame_pair = P("3", "0", "Q", f3.line((draw(shift), draw(shift)), 0.0), e0, name="03")
    else:
        f3 = draw(frames(rotate=False))
        frame_pair = P("0", "3", "Y", g.line(through0, draw(angle)), e0, name="30")
    data = case(
        frame_points,
        [link("1", pts(f1, {"O": (0, 0), "A": (a, 0)})),
         link("2", pts(f2, {"A": (0, 0)})),
         link("3", pts(f3, {"Y": (0, 0), "E": (0.4, 0.1)}))],
        [R("0", "1", "O"), R("1", "2", "A"),
         P("3", "2", "A", f3.line(slot_through, slot), draw(st.floats(-0.1, 0.1)), name="23"),
         frame_pair],
        draw(cranks()), {})
    return data, g


@st.composite
def six_bar(draw):
    """ВВВ + ВВП: a four-bar whose rocker arm D drives a coupler DH and a slider H on a frame guide
    passing near the rocker pivot C (the ws000 layout, random dimensions)."""
    data, g = draw(four_bar(with_rocker_arm=True))
    l4 = draw(st.floats(1.0, 2.0))
    gam, e5 = draw(angle), draw(st.floats(-0.3, 0.3))
    C = data["frame"]["points"]["C"]
    n = rot(gam, (0, e5))
    f4, f5 = draw(frames()), draw(frames(rotate=False))
    data["links"] += [link("4", pts(f4, {"D": (0, 0), "S4": (0.5 * l4, 0), "H": (l4, 0)})),
                      link("5", pts(f5, {"H": (0, 0)}))]
    data["joints"] += [R("3", "4", "D"), R("4", "5", "H"),
                       P("0", "5", "H", {"through": [C[0] + n[0], C[1] + n[1]], "angle": gam}, name="50")]
    data["sketch"]["points"]["H"] = draw(sketch_point)
    return data, g


# ----------------------------------------------------------------------------- the properties

def _solve(data):
    """Study of a random case; rejects draws that do not assemble or transmit poorly."""
    study = Study(CaseSpec(Path("random.toml"), data))
    try:
        cyc = study.cycle
    except AssemblyError:
        assume(False)
    for c in cyc.columns:
        if c.startswith("mu_"):
            assume(float(cyc[c].min()) >= MU_MIN)
    return study, cyc


def check_study(study, cyc, qs, grid_index) -> dict:
    """All properties of one random mechanism; returns the measured maxima."""
    mech = study.mechanism
    size = mech.size()
    # 1. loop closure over the whole cycle grid
    clo, where = closure_residuals(mech, cyc)
    assert clo <= TOL_CLOSURE * size, f"loop closure {clo:.3e} > {TOL_CLOSURE}·{size:.3g} ({where})"
    # 2. positions and analogs against the independent reference
    q_grid = float(study.grid.cycle[grid_index])
    mus = [c for c in cyc.columns if c.startswith("mu_")]
    if mus:
        # also the grid point of the poorest transmission angle (largest error amplification)
        worst_mu = cyc[mus].min(axis=1).to_numpy()
        qs = list(qs) + [float(cyc["q"].iloc[int(np.argmin(worst_mu))])]
    qs = list(qs) + [q_grid]
    df = study.at(qs)
    ref = reference_columns(study, qs, frame=df)
    err = scaled_errors(df, ref)
    for kind, tol in (("position", TOL_POS), ("first", TOL_FIRST), ("second", TOL_SECOND)):
        e, col, i = err[kind]
        assert e <= tol, (f"{kind} {col} at q = {qs[i]!r}: scaled error {e:.3e} > {tol:g} "
                          f"(engine {df[col].iloc[i]!r}, reference {float(ref[col][i])!r})")
    # 3. at(q) equals the cycle row at the same q
    row = cyc.iloc[grid_index]
    one = df.iloc[len(qs) - 1]
    worst_at = 0.0
    for c in cyc.columns:
        a, b = float(one[c]), float(row[c])
        d = a - b
        if c.startswith("phi_"):
            d = math.remainder(d, 2 * math.pi)     # the cycle's angles are unwrapped
        e = abs(d) / max(1.0, abs(b))
        worst_at = max(worst_at, e)
        assert e <= TOL_AT_CYCLE, f"at({qs[-1]!r}) vs cycle row {grid_index}: {c} {a!r} != {b!r}"
    return {"closure": clo / size, "position": err["position"][0], "first": err["first"][0],
            "second": err["second"][0], "at_vs_cycle": worst_at}


q_draw = st.floats(0.0, 2 * math.pi, exclude_max=True)
grid_draw = st.integers(0, CYCLE_POINTS)


def _property(strategy):
    @SETTINGS
    @given(strategy, st.lists(q_draw, min_size=2, max_size=2), grid_draw)
    def test(drawn, qs, grid_index):
        data, _ = drawn
        study, cyc = _solve(data)
        check_study(study, cyc, qs, grid_index)
    return test


# the mechanism families of the property tests (here and in test_forces.py): the name of the
# test, the strategy, the dyad kinds its random cases must decompose into
FAMILIES = {
    "rrr_crank_rocker": (four_bar, ["RRR"]),
    "rrp_offset_slider_crank": (slider_crank, ["RRP"]),
    "rpr_slotted_lever": (slotted_lever, ["RPR"]),
    "prp_shaper_ram": (shaper, ["RPR", "PRP"]),
    "rpp_scotch_yoke": (scotch_yoke, ["RPP"]),
    "six_bar_rrr_rrp": (six_bar, ["RRR", "RRP"]),
}


def property_tests(make) -> dict:
    """One property test per family: ``test_<name>`` = ``make(<its strategy>)``."""
    return {f"test_{name}": make(strategy()) for name, (strategy, _) in FAMILIES.items()}


globals().update(property_tests(_property))     # test_rrr_crank_rocker … test_six_bar_rrr_rrp


@pytest.mark.parametrize("strategy, kinds", [(strategy(), kinds) for strategy, kinds in FAMILIES.values()])
def test_strategies_produce_the_intended_groups(strategy, kinds):
    """The random cases really decompose into the dyad kinds they are meant to exercise."""
    seen = []

    @settings(max_examples=3, deadline=None, database=None,
              suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
    @given(strategy)
    def inner(drawn):
        study = Study(CaseSpec(Path("random.toml"), drawn[0]))
        got = [g.kind for g in study.structure.groups if g.klass == 2]
        assert got == kinds, f"groups {got}, expected {kinds}"
        seen.append(got)

    inner()
    assert seen
