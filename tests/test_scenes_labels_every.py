"""Every text of the drawings of the cam, train, structure-graph, governor, cross-slide and synthesis
sections and of the gear drawings (mesh, rack, sliding) is crossed by no line, arrow or outline
(``line_problems(every=True)``: not only the labels a placer set, every text of the axes), none
overlaps another or is clipped (``check_figure``), in every case of cases/ that has the section.
Before, these texts were written with ``ax.text``/``annotate`` at fixed offsets, across the
lines (the curve names of the phase portrait over its hatching, a link's number under its
graph's edges, the rack's captions over its teeth)."""
import importlib
from functools import lru_cache
from pathlib import Path

import pytest

from reportgen.scenes import labels as L

CASES = Path(__file__).resolve().parents[1] / "cases"
SECTIONS = ("cam", "train", "dof", "governor", "cross", "synthesis")


@lru_cache(maxsize=None)
def _study(path: Path):
    from reportgen import load_case
    return load_case(path)


def _cases(name: str) -> list:
    """The cases of cases/ that have the section ``name`` (a derived case, built by batch only, is left out)."""
    from reportgen.errors import CaseError
    present = importlib.import_module(f"reportgen.report.sections.{name}").present
    out = []
    for path in sorted(CASES.glob("*.toml")):
        try:
            st = _study(path)
        except CaseError:
            continue
        if present(st):
            out.append(pytest.param(path, id=path.stem))
    return out


def _clean(fig) -> list[str]:
    return L.check_figure(fig) + L.line_problems(fig, every=True)


@pytest.mark.parametrize("name,path", [pytest.param(n, *p.values, id=f"{n}-{p.id}") for n in SECTIONS
                                       for p in _cases(n)])
def test_section_texts_clear_of_lines(name, path, captured):
    """Every figure the section puts into the note."""
    st = _study(path)
    captured.clear()
    importlib.import_module(f"reportgen.report.sections.{name}").build(st)
    assert captured
    for fig in captured:
        assert _clean(fig) == [], name


@pytest.mark.parametrize("path", _cases("gears"))
def test_gear_drawings_texts_clear_of_lines(path):
    """The mesh (external or internal), the generating rack mesh and the sliding diagram; the
    labels stay near what they name (a point's label within the placer's rings)."""
    from reportgen.scenes import gears as S
    gr = _study(path).gears
    figs = []
    if gr.geo is not None:          # as the section: the pair's drawings, the rack's for an external gear
        figs += [(S.internal_mesh_drawing(gr) if gr.internal else S.mesh_drawing(gr)).fig, S.sliding_diagram(gr)]
    if gr.geo is None or not gr.internal:
        figs.append(S.rack_drawing(gr)[0])
    for fig in figs:
        assert _clean(fig) == []
        for ax in fig.axes:
            for t in ax.texts:
                a, c = ax.transData.transform(t.anchor), ax.transData.transform(t.get_position())
                assert ((a - c) ** 2).sum() ** 0.5 <= L.RADII_MM[-1] * fig.dpi / 25.4 + 1e-6, t.get_text()


@pytest.mark.parametrize("path", _cases("dynamics"))
def test_energy_and_motion_notes_clear_of_lines(path, captured):
    """The notes ΔT_I max, ΔT_I min of the energy curves and ω_ср of the motion curves: near their
    points, over no curve and not under the legend (before: written at a fixed offset, across
    the curves)."""
    from reportgen.scenes.dynamics import EnergyCurves, MotionCurves
    st = _study(path)
    for scene in (EnergyCurves(), MotionCurves()):
        captured.clear()
        scene.draw(st)
        fig = captured[-1]
        assert _clean(fig) == []
        for ax in fig.axes:
            legend = ax.get_legend()
            for t in ax.texts:
                assert hasattr(t, "anchor"), t.get_text()
                if legend is not None:
                    assert not t.get_window_extent().overlaps(legend.get_window_extent()), t.get_text()


@pytest.mark.parametrize("path", [p for p in _cases("gears") if _study(p.values[0]).gears.geo is not None])
def test_blocking_contour_texts_clear_of_lines(path):
    """The blocking contour: every isoline's value (ε = 1,3 … 1,6) along its line, crossed by no
    other line, contour or the isoline itself beside its cut, and «выбрано» beside its point
    (before: ``ax.clabel``'s own places, ε = 1,5 and 1,6 across the x_min lines; the contour
    lines were not seen by the check at all)."""
    from matplotlib.contour import ContourSet
    from reportgen.scenes import gears as S
    fig = S.blocking_contour(_study(path).gears)
    assert _clean(fig) == []
    ax = fig.axes[0]
    isolines = [c for c in ax.collections if isinstance(c, ContourSet) and not c.filled and len(c.levels) > 1]
    assert len(isolines) == 1 and len(isolines[0].labelTexts) == len(isolines[0].levels)
    # the check sees the contour lines: a text set on one is crossed
    t = ax.text(float(_study(path).gears.x1), float(_study(path).gears.x2), "выбрано выбрано", ha="center")
    assert L.line_problems(fig, every=True)
    t.remove()


@pytest.mark.parametrize("path", [p for p in _cases("dynamics") if _study(p.values[0]).dynamics.result.flywheel.needed])
def test_flywheel_dimensions_clear_of_lines(path, captured):
    """The flywheel's drawing: every dimension number (Ø D₂, Ø D₁, b, Ø D) crossed by no line and
    clear of the neighbouring view (before: swing_conveyor's Ø257 and Ø205 at 1:10 across the rim's
    and the disk's outlines, its views 4 mm apart)."""
    from reportgen.scenes.dynamics import FlywheelDrawing
    FlywheelDrawing().draw(_study(path))
    fig = captured[-1]
    assert len([t for t in fig.axes[0].texts if t.get_text()]) == 7     # five dimensions, two captions
    assert _clean(fig) == []


@pytest.mark.parametrize("path", _cases("forces"))
def test_group_force_arrows_inside_the_figure(path, captured):
    """Every arrow of every group's force drawing lies inside the figure (before: a reaction
    opposite to a load at its point, swing_conveyor's R₀₇ against G₇, is drawn from the point as
    the load is, but the canvas was sized for it ending at the point: it ran off the top)."""
    from matplotlib.patches import FancyArrowPatch
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import GroupForces
    st = _study(path)
    lab = chosen_position(st)
    if lab not in st.forces.labels:
        lab = st.forces.labels[1]
    for gi in range(len(st.forces.model.groups)):
        captured.clear()
        GroupForces(lab, gi).draw(st)
        fig = captured[-1]
        r = L._renderer(fig)
        fb = fig.bbox
        for ax in fig.axes:
            for p in ax.patches:
                if isinstance(p, FancyArrowPatch):
                    bb = p.get_window_extent(r)
                    assert fb.x0 - 0.5 <= bb.x0 and bb.x1 <= fb.x1 + 0.5 and fb.y0 - 0.5 <= bb.y0 \
                        and bb.y1 <= fb.y1 + 0.5, (gi, bb, fb)


@pytest.mark.parametrize("path", _cases("forces"))
def test_group_force_polygons_not_a_dot(path):
    """Every Assur group the note's force section draws, at every report position, carries a
    non-zero force: its polygon is never a single dot. (ws004's group (4,5) drawn alone was a
    dot: ws004 has no [forces] — no loads, no masses — so every reaction of its force analysis is
    zero, and the note builds no force section for it: checked below.)"""
    import numpy as np
    from reportgen.scenes.forces import group_vectors
    st = _study(path)
    for lab in st.forces.labels:
        for gi in range(len(st.forces.model.groups)):
            ext, _, internal = group_vectors(st, lab, gi)
            assert max(float(np.hypot(*v.F)) for v in ext + internal) > 0.0, (lab, gi)


def test_case_without_loads_has_no_force_drawings():
    """ws004 (no [forces], no loads, no masses): its force analysis is identically zero and the
    note has no force section, so no empty force polygon is drawn."""
    from reportgen.report.sections import forces
    st = _study(CASES / "ws004_slotted_lever.toml")
    assert not forces.present(st)
    assert all(abs(float(x)) < 1e-12 for x in st.forces.tables()["forces"].filter(regex=r"^R_").to_numpy().ravel())


@pytest.mark.parametrize("path", _cases("forces"))
def test_lever_arrows_apart(path, captured):
    """On Жуковский's lever as the note draws it, every arrow is MIN_ARROW_MM long at least (a
    shorter one is all head) and arrows leaving one image in nearly one direction (within FAN_DEG)
    end FAN_STEP_MM apart at least (ws000's G₃ and M′Φ₂ at b, M″Φ₄ and G₅ at h lay head on head)."""
    import math

    import numpy as np
    from matplotlib.patches import FancyArrowPatch
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import FAN_DEG, FAN_STEP_MM, MIN_ARROW_MM, ZhukovskyLever
    st = _study(path)
    lab = chosen_position(st)
    if lab not in st.forces.labels:
        lab = st.forces.labels[1]
    ZhukovskyLever(lab, landscape=True).draw(st)
    fig = captured[-1]
    ax = fig.axes[0]
    px_mm = fig.dpi / 25.4
    ends = [tuple(ax.transData.transform(q) / px_mm for q in p._posA_posB)     # the forces (an inset's
            for p in ax.patches if isinstance(p, FancyArrowPatch) and p.get_zorder() == 6]   # plan arrows apart)
    assert ends
    for i, (a0, a1) in enumerate(ends):
        n0 = float(np.hypot(*(a1 - a0)))
        assert n0 >= MIN_ARROW_MM - 1e-6
        for b0, b1 in ends[i + 1:]:
            n1 = float(np.hypot(*(b1 - b0)))
            if np.hypot(*(a0 - b0)) < 2.0 and np.dot(a1 - a0, b1 - b0) / (n0 * n1) > math.cos(math.radians(FAN_DEG)) + 1e-6:
                assert abs(n0 - n1) >= FAN_STEP_MM - 1e-6, (a0, n0, n1)
    assert L.check_figure(fig) == []
