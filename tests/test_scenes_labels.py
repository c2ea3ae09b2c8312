"""Every drawing of every case in cases/: no two labels overlap and none is clipped by the
figure (matplotlib's rendered extents, ``Text.get_window_extent``), labels in textbook notation
(mathtext, never a plain "nbc"), mechanism drawings at a ГОСТ 2.302 scale."""
import re
from pathlib import Path

import numpy as np
import pytest

from reportgen.scenes import labels as L
from reportgen.scenes.draw import BLOCK_REACH_MM, GOST_K, gost_ratio, gost_scale
from reportgen.style import mplstyle

CASES = Path(__file__).resolve().parents[1] / "cases"


def _studies():
    from reportgen import load_case
    from reportgen.errors import CaseError
    out = []
    for path in sorted(CASES.glob("*.toml")):
        try:
            st = load_case(path)
        except CaseError:          # a derived case (``base = …``) is built by batch, not alone
            continue
        if st.has_linkage:
            out.append(pytest.param(st, id=path.stem))
    return out


STUDIES = _studies()


def _scenes(st):
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.mechanism import AssurGroups, KinematicScheme, PositionsPlan
    from reportgen.scenes.plans import PlanScene
    lab = chosen_position(st)
    yield "scheme", KinematicScheme(lab)
    yield "positions", PositionsPlan()
    yield "groups", AssurGroups(lab)
    if st.mechanism.driver.omega is not None:
        yield "vplan", PlanScene(lab, "velocity")
        yield "aplan", PlanScene(lab, "acceleration")


def _placed_near(fig) -> list[str]:
    """The placed labels (every text of the drawing's axes): each names its point from at most
    ``RADII_MM[-1]`` away (centre to point), and one farther than ``LEADER_MM`` (a slider's
    label: than its block's reach and ``REACH_LEAD_MM``) has its leader line."""
    bad = []
    for ax in fig.axes:
        px_mm = fig.dpi / 25.4
        for t in ax.texts:
            if not hasattr(t, "anchor"):
                bad.append(f"not placed: {t.get_text()!r}")
                continue
            a = ax.transData.transform(t.anchor)
            c = ax.transData.transform(t.get_position())
            r = float(np.hypot(*(c - a))) / px_mm
            if r > L.RADII_MM[-1] + 1e-6:
                bad.append(f"far: {t.get_text()!r} {r:.1f} mm")
            if r > t.lead_mm + 1e-6 and not hasattr(t, "leader"):
                bad.append(f"no leader: {t.get_text()!r} {r:.1f} mm")
            if t.lead_mm > L.LEADER_MM and t.lead_mm > BLOCK_REACH_MM + L.REACH_LEAD_MM + 1e-9:
                bad.append(f"leader too far: {t.get_text()!r} {t.lead_mm:.1f} mm")
    return bad


POSITIONS_NEAR_MM = 14.0     # a label of the plan of positions from its point at most (centre to point)


def _farthest_mm(fig) -> float:
    """The largest distance (mm on paper) of a placed label's centre from its point."""
    px_mm = fig.dpi / 25.4
    return max((float(np.hypot(*(ax.transData.transform(t.get_position()) - ax.transData.transform(t.anchor))))
                / px_mm for ax in fig.axes for t in ax.texts if hasattr(t, "anchor")), default=0.0)


@pytest.mark.parametrize("st", STUDIES)
def test_no_label_overlaps_or_clipping(st, captured):
    """No two labels overlap, none is clipped and no line, arrow or outline crosses a label
    (``check_figure``), every label near its point (a leader when it is farther); on the plan of
    positions within POSITIONS_NEAR_MM of it (a label may interrupt the thin lines of the other
    positions rather than sit far: before, the conveyor's E and ws002's 01, 34 were 23 mm off on
    leaders across those lines, 19 labels of the cases farther than 14 mm)."""
    for name, scene in _scenes(st):
        captured.clear()
        scene.draw(st)
        for fig in captured:
            assert L.check_figure(fig) == [], name
            assert _placed_near(fig) == [], name
            if name == "positions":
                assert _farthest_mm(fig) <= POSITIONS_NEAR_MM + 1e-6
            texts = [t.get_text() for ax in fig.axes for t in ax.texts]
            for t in texts:          # point labels in textbook notation: no bare "nbc", "S2"
                assert not re.fullmatch(r"[a-zA-Z]+\d+|n[a-z]{2,}", t), (name, t)


@pytest.mark.parametrize("st", [s for s in STUDIES if s.values[0].root.has("forces")])
def test_force_drawings_labels(st, captured):
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import GroupForces, ZhukovskyLever
    lab = chosen_position(st)
    if lab not in st.forces.labels:
        lab = st.forces.labels[1]
    scenes = [GroupForces(lab, gi) for gi in range(len(st.forces.model.groups))] + [ZhukovskyLever(lab)]
    for sc in scenes:
        captured.clear()
        sc.draw(st)
        for fig in captured:
            assert L.check_figure(fig) == [], type(sc).__name__
            assert _placed_near(fig) == [], type(sc).__name__


def test_check_figure_finds_overlap_and_clipping():
    """The checker itself: two texts at one point overlap; a text beyond the edge is clipped."""
    fig = mplstyle.figure(40, 20, layout=None)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.text(0.5, 0.5, "$R_{12}$")
    ax.text(0.5, 0.5, "$R_{23}$")
    ax.text(1.05, 0.5, "$G_{2}$")
    probs = L.check_figure(fig)
    assert any(p.startswith("overlap") for p in probs) and any(p.startswith("clipped") for p in probs)


def test_placer_separates_coincident_labels():
    fig = mplstyle.figure(60, 40, layout=None)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.plot([0, 1], [0.5, 0.5])
    pl = L.LabelPlacer(ax)
    for t in ("$a$", "$b′$", "$n_{BA}$", "$s′_{2}$"):
        pl.add(0.5, 0.5, t)
    pl.place()
    assert L.check_figure(fig) == []


def test_placer_keeps_labels_off_other_arrows_tips():
    """Forces drawn from one crowded point (the couples' forces at the pole of Жуковский's lever,
    jaw crusher): two short arrows pointing up with tips 1,6 mm apart. The first label must not
    be set over the other arrow's tip, else every leader of the second passes through it."""
    from reportgen.scenes.draw import arrow
    fig = mplstyle.figure(60, 40, layout=None)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 60)
    ax.set_ylim(0, 40)
    p = np.array([16.0, 24.0])
    for end in ((17.0, 0.0), (60.0, 10.0), (55.0, 5.0)):       # the lever's lines from the pole
        ax.plot([p[0], end[0]], [p[1], end[1]], color="k", lw=1.2)
    ax.plot([p[0]], [p[1]], "o", ms=3, color="k")
    pl = L.LabelPlacer(ax)
    pl.add(*p, "$p$", prefer=(-1, -1))
    tips = {"$G_{1}$": (0.0, -4.8), "$M″_{\\Phi 1}$": (2.39, 4.16), "$M″_{\\Phi 3}$": (0.91, 4.72),
            "$M″_{\\Phi 5}$": (4.8, 0.3)}
    for text, d in tips.items():
        tip = p + d
        arrow(ax, p[0], p[1], tip[0], tip[1], lw=1.1, head_mm=2.0, zorder=6)
        pl.add(*tip, text, prefer=d)
    pl.place()
    assert L.check_figure(fig) == []
    assert _placed_near(fig) == []
    px_mm = fig.dpi / 25.4
    for t in ax.texts:          # no label over another label's arrow tip
        bb = t.get_window_extent(L._renderer(fig))
        for d in tips.values():
            x, y = ax.transData.transform(p + d)
            if not np.allclose(t.anchor, p + d):
                assert not (bb.x0 - 0.5 * px_mm < x < bb.x1 + 0.5 * px_mm
                            and bb.y0 - 0.5 * px_mm < y < bb.y1 + 0.5 * px_mm), t.get_text()


def test_gost_scales():
    assert gost_ratio(0.04) == "1:40" and gost_ratio(0.0025) == "1:2,5" and gost_ratio(0.0005) == "2:1"
    for extent in (0.05, 0.3, 0.9, 2.7, 11.0):
        mu = gost_scale(extent, 150.0)
        assert mu * 1000 in GOST_K and extent / mu <= 150.0 + 1e-9


def _placed_on_line(offset_mm: float):
    """A figure with a line and one placed label moved ``offset_mm`` off the line (its box's
    lower edge that far above it; negative: the line through the box)."""
    from matplotlib.patches import FancyArrowPatch  # noqa: F401
    fig = mplstyle.figure(60, 40, layout=None)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 60)
    ax.set_ylim(0, 40)         # 1 unit = 1 mm
    ax.plot([0, 60], [20, 20], lw=0.7)
    pl = L.LabelPlacer(ax)
    pl.add(30, 10, "$S_{2}$")
    t = pl.place()[0]
    r = L._renderer(fig)
    h = t.get_window_extent(r).height / (fig.dpi / 25.4)
    t.set_position((30, 20 + offset_mm + h / 2))
    return fig


def test_check_figure_finds_a_line_through_a_label():
    """A line through a placed label's box is reported; one only touching it (within
    ``LINE_TOL_MM`` of the box's edge, where the glyphs do not reach) is not."""
    assert any(p.startswith("crossed") for p in L.check_figure(_placed_on_line(-1.0)))
    assert L.check_figure(_placed_on_line(-0.5 * L.LINE_TOL_MM)) == []
    assert L.check_figure(_placed_on_line(0.5)) == []


def test_check_figure_finds_an_arrowhead_under_a_label():
    """An arrowhead (drawn at its printed size) under a label is reported; the label's own
    leader line is not."""
    from reportgen.scenes.draw import arrow
    fig = mplstyle.figure(60, 40, layout=None)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 60)
    ax.set_ylim(0, 40)
    arrow(ax, 10, 20, 30, 20, head_mm=3.0)
    pl = L.LabelPlacer(ax)
    pl.add(45, 20, "$F$")
    t = pl.place()[0]
    assert L.check_figure(fig) == []
    t.set_position((29.0, 20.0))          # on the head only: the shaft ends inside it
    assert any(p.startswith("crossed") for p in L.check_figure(fig))
    fig2 = mplstyle.figure(60, 40, layout=None)
    ax2 = fig2.add_axes((0, 0, 1, 1))
    ax2.set_xlim(0, 60)
    ax2.set_ylim(0, 40)
    ax2.plot([0, 60], [20, 20], lw=0.7)
    pl = L.LabelPlacer(ax2)
    pl.add(30, 20, "$A$")
    pl.place()
    assert L.check_figure(fig2) == []


def test_placer_uses_a_leader_when_no_near_place_is_free():
    """A point inside a grid of lines 4 mm apart: no ring near it is free, so the label goes
    out of the grid with a leader line, and the leader passes through no other label."""
    fig = mplstyle.figure(80, 80, layout=None)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 80)
    ax.set_ylim(0, 80)
    for v in np.arange(24, 57, 3.0):
        ax.plot([v, v], [24, 56], lw=0.5)
        ax.plot([24, 56], [v, v], lw=0.5)
    pl = L.LabelPlacer(ax)
    pl.add(40.5, 40.5, "$B$", point=True)
    pl.add(40.5, 37.5, "$C$", point=True)
    ts = pl.place()
    assert L.check_figure(fig) == []
    assert all(hasattr(t, "leader") for t in ts)
    assert _placed_near(fig) == []


def _guide_links(st) -> dict:
    mech = st.mechanism
    return {j.links[0]: j for j in mech.prismatic if j.links[0] != "0" and not j.driving}


SLOTTED = [s for s in STUDIES if _guide_links(s.values[0])]


def test_slotted_cases_found():
    """The cases with a slot on a moving link (the slotting machine has none: its slider runs on
    a fixed guide, its rocker CBD is a bell crank)."""
    names = {s.id for s in SLOTTED}
    assert {"whitworth", "shaper_swinging_lever", "ws004_slotted_lever", "swing_conveyor"} <= names
    assert "slotting_machine" not in names


@pytest.mark.parametrize("st", SLOTTED)
def test_slotted_link_drawn_as_slot_and_arms(st, captured):
    """A slotted link (кулиса) is drawn as a bar along its slot and arms to its other pairs,
    never as a plate spanned over its points (the conveyor's rocker D–K–F was a filled
    triangle, three times on the plan of positions)."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.mechanism import KinematicScheme, PositionsPlan
    lab = chosen_position(st)
    guides = _guide_links(st)
    for scene in (KinematicScheme(lab), PositionsPlan()):
        captured.clear()
        scene.draw(st)
        ax = captured[-1].axes[0]
        k = st.kinematics
        rows = [k[k["pos"] == lab].iloc[0]] if isinstance(scene, KinematicScheme) else [r for _, r in k.iterrows()]
        for name in guides:
            link = st.mechanism.link(name)
            for row in rows:
                pts = np.array([[row[f"x_{p}"], row[f"y_{p}"]] for p in link.points])
                for patch in ax.patches:
                    if type(patch).__name__ != "Polygon":
                        continue
                    v = patch.get_xy()
                    on = sum(bool(np.any(np.hypot(*(v - q).T) < 1e-9)) for q in pts)
                    assert on < 3, (scene, name, row["pos"])


def test_conveyor_rocker_bars():
    """The conveyor's slotted rocker 5: the slot D–K and the arm D–F, the centre of mass S5 on
    no bar (it is no pair's point)."""
    from reportgen.scenes.draw import _slotted_bars
    st = next(s.values[0] for s in SLOTTED if s.id == "swing_conveyor")
    row = st.kinematics.iloc[0]
    bars = _slotted_bars(st.mechanism, row, st.mechanism.link("5"))
    pt = {p: (float(row[f"x_{p}"]), float(row[f"y_{p}"])) for p in ("D", "K", "F", "E")}

    def close(a, b):
        return np.hypot(a[0] - b[0], a[1] - b[1]) < 1e-9
    assert len(bars) == 2
    (a, b), (c, d) = bars
    assert close(c, pt["D"]) and close(d, pt["F"])
    # the slot spans D, K and the stone's point E
    u = np.subtract(b, a) / np.hypot(*np.subtract(b, a))
    for p in ("D", "K", "E"):
        t = np.dot(np.subtract(pt[p], a), u)
        assert -1e-9 <= t <= np.hypot(*np.subtract(b, a)) + 1e-9


def _with_dynamics():
    from reportgen.report.sections import dynamics
    return [s for s in STUDIES if dynamics.present(s.values[0])]


@pytest.mark.parametrize("st", _with_dynamics())
def test_wittenbauer_labels_clear_of_the_curves(st, captured):
    """The energy–mass diagram's position numbers and K, L were written 3 pt off their points,
    across the curve and the tangents: now every text of its axes is placed, near its point and
    crossed by no line (``line_problems(every=True)``: the annotations too)."""
    from reportgen.scenes.dynamics import WittenbauerDiagram
    captured.clear()
    WittenbauerDiagram().draw(st)
    fig = captured[-1]
    assert L.check_figure(fig) == []
    assert L.line_problems(fig, every=True) == []
    assert _placed_near(fig) == []

@pytest.mark.parametrize("st", [s for s in STUDIES if s.values[0].mechanism.driver.rotary])
def test_crank_positions_apart_on_paper(st, captured):
    """On the plan of positions the crank pin's numbered positions are POSITION_GAP_MM apart on
    paper at least: on the main view, or (a small crank) on its enlarged view at a ГОСТ 2.302
    scale, numbered there A₀ … A₁₁ with no number left at the crank of the main view. The
    distances are taken from the kinematics table, not from the drawing's own bookkeeping."""
    import numpy as np
    from reportgen.scenes.mechanism import POSITION_GAP_MM, POSITION_NUMBER, PositionsPlan
    d = PositionsPlan().draw(st)
    pin = st.mechanism.crank_pin()
    k = st.kinematics
    rows = k[~k["pos"].astype(str).str.startswith("д")]
    p = rows[[f"x_{pin}", f"y_{pin}"]].to_numpy(float)
    dist = np.hypot(*(p[:, None, :] - p[None, :, :]).transpose(2, 0, 1))[np.triu_indices(len(p), 1)]
    dist = dist[dist > 1e-9 * max(1.0, float(np.abs(p).max()))]      # coinciding positions share a label
    mu = d.detail_mu or d.mu
    assert dist.min() / mu >= POSITION_GAP_MM, (d.mu, d.detail_mu)
    numbers = [t.get_text() for fig in captured for ax in fig.axes for t in ax.texts
               if t.get_label() == POSITION_NUMBER]
    if d.detail_mu is not None:
        assert d.detail_mu * 1000 in GOST_K and d.detail_mu < d.mu
        assert numbers and all(t.startswith("$" + pin.rstrip("0123456789")) for t in numbers)
        assert any(gost_ratio(d.detail_mu) in t.get_text() for fig in captured for ax in fig.axes for t in ax.texts)
        # at a scale asked by a drawing sheet the view is drawn alike (and the marks kept apart)
        assert PositionsPlan(centre_lines=True, mu=d.mu).draw(st).detail_mu == d.detail_mu


def test_placer_interrupts_thin_lines_rather_than_a_far_leader():
    """A point inside a grid of thin lines 3 mm apart (as the other positions on a plan of
    positions): with the lines ``breakable`` its label sits at its point and the lines under it
    are interrupted (a NaN gap in their data: no line crosses the label, check_figure is clean);
    with ordinary lines the same label goes out of the grid on a leader."""
    def grid(breakable):
        fig = mplstyle.figure(80, 80, layout=None)
        ax = fig.add_axes((0, 0, 1, 1))
        ax.set_xlim(0, 80)
        ax.set_ylim(0, 80)
        for v in np.arange(24, 57, 3.0):
            for ln in ax.plot([v, v], [24, 56], lw=0.5) + ax.plot([24, 56], [v, v], lw=0.5):
                ln.breakable = breakable
        pl = L.LabelPlacer(ax)
        pl.add(40.5, 40.5, "$B$", point=True)
        return fig, ax, pl.place()[0]

    fig, ax, t = grid(True)
    assert L.check_figure(fig) == [] and _placed_near(fig) == []
    r = np.hypot(*(ax.transData.transform(t.get_position()) - ax.transData.transform(t.anchor))) / (fig.dpi / 25.4)
    assert r <= L.LEADER_MM and not hasattr(t, "leader")
    cut = [ln for ln in ax.lines if np.isnan(np.asarray(ln.get_xdata(), float)).any()]
    assert 1 <= len(cut) <= L.MAX_BREAKS
    fig, ax, t = grid(False)
    assert L.check_figure(fig) == [] and hasattr(t, "leader")


def test_cut_leaves_the_rest_of_the_line():
    """_Thin.cut cuts only the part of a polyline inside the box: the vertices outside are
    kept, the cut ends lie on the box's edges."""
    fig = mplstyle.figure(80, 80, layout=None)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 80)
    ax.set_ylim(0, 80)
    (ln,) = ax.plot([10, 40, 70], [40, 40, 10], lw=0.5)
    tr = ax.transData
    (x0, y0), (x1, y1) = tr.transform((30, 35)), tr.transform((50, 45))
    L._Thin([ln]).cut(L._Box(x0, y0, x1, y1))
    x, y = np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float)
    ok = np.isfinite(x)
    assert (~ok).sum() == 1
    pts = np.column_stack([x[ok], y[ok]])
    np.testing.assert_allclose(pts, [[10, 40], [30, 40], [45, 35], [70, 10]], atol=1e-9)


@pytest.mark.parametrize("st", [s for s in STUDIES if not s.values[0].mechanism.driver.periodic])
def test_every_input_kind_gets_an_enlarged_view(st, captured):
    """The rule of the crank's enlarged view for every input kind (a rocker, a cylinder): at the
    plan's own scale and at the first ГОСТ 2.302 scale coarser than that where the numbered
    point's positions come closer than POSITION_GAP_MM, they are POSITION_GAP_MM apart on the
    main view or on an enlarged view at a finer ГОСТ scale, numbered there only (before: a rocker's
    view drew a whole crank circle, a cylinder's input got none). Distances from the kinematics
    table."""
    from reportgen.scenes.mechanism import (POSITION_GAP_MM, POSITION_NUMBER, PositionsPlan, _position_groups,
                                            position_gap_mm)
    k = st.kinematics
    rows = [r for _, r in k[~k["pos"].astype(str).str.startswith("д")].iterrows()]
    d = PositionsPlan().draw(st)
    names = [t for ax in captured[-1].axes for t in ax.texts if t.get_label() == POSITION_NUMBER]
    assert d.detail_mu is None and names
    # the point the numbers name: the nearest point of the mechanism to the first number's anchor
    a = np.asarray(names[0].anchor)
    pts = {c[2:]: (float(rows[0][c]), float(rows[0]["y_" + c[2:]])) for c in k.columns if c.startswith("x_")}
    p = min(pts, key=lambda q: np.hypot(*(np.asarray(pts[q]) - a)))
    groups = _position_groups(k, rows, p, 0.5 * d.mu)
    gap = position_gap_mm(groups, d.mu)
    assert gap >= POSITION_GAP_MM
    coarse = next(q / 1000 for q in GOST_K if q / 1000 > d.mu and position_gap_mm(groups, q / 1000) < POSITION_GAP_MM)
    captured.clear()
    v = PositionsPlan(mu=coarse).draw(st)
    fig = captured[-1]
    assert v.detail_mu is not None and v.detail_mu * 1000 in GOST_K and v.detail_mu < coarse
    assert position_gap_mm(groups, v.detail_mu) >= POSITION_GAP_MM
    head = p.rstrip("0123456789")
    numbers = [t.get_text() for ax in fig.axes for t in ax.texts if t.get_label() == POSITION_NUMBER]
    # named as the crank's (A₀ …), a point named by digits only (ws002's «56») by the number alone
    assert numbers and all(t.startswith("$" + head) if head else re.fullmatch(r"\([\d, ]+\)", t) for t in numbers)
    assert any(gost_ratio(v.detail_mu) in t.get_text() for ax in fig.axes for t in ax.texts)
    assert L.check_figure(fig) == []
    if st.mechanism.driver.swing:        # a rocker's arc, not a whole circle
        from matplotlib.patches import Circle
        r = np.hypot(*(np.asarray(groups[0][:2]) - np.asarray(pts[st.mechanism.driver.center])))
        k_view = coarse / v.detail_mu
        assert not any(isinstance(c, Circle) and abs(c.radius - r * k_view) < 1e-9 * r * k_view
                       for ax in fig.axes for c in ax.patches)


@pytest.mark.parametrize("st", STUDIES)
def test_plan_of_positions_labels_distinct(st, captured):
    """On the plan of positions no two labels carry the same text unless they name the same
    point (a point drawn on the main view and again on the crank's enlarged view): position
    numbers are the numbered point's letter with the number as index (A₀, A₁ …; a point named by
    digits only: «(5)»), never a plain digit read as a link number (yoke_pump had two «1», «2», «3»:
    link 1 and position 1)."""
    from collections import Counter

    from reportgen.scenes.mechanism import POSITION_NUMBER, PositionsPlan
    PositionsPlan().draw(st)
    texts = [t for ax in captured[-1].axes for t in ax.texts if t.get_text().strip()]
    points = {L.tex_point(p) for p in st.kinematics.columns.str[2:][st.kinematics.columns.str.startswith("x_")]}
    twice = {t for t, n in Counter(t.get_text() for t in texts).items() if n > 1}
    assert twice <= points, twice
    links = {ln.name for ln in st.mechanism.moving}
    numbers = [t.get_text() for t in texts if t.get_label() == POSITION_NUMBER]
    assert numbers and not set(numbers) & links
