"""Readability of the plans and the force polygons at print scale (issue 9, item 1), measured on
the scene objects: rendered label extents (``Text.get_window_extent``) and segment geometry."""
from pathlib import Path

import numpy as np
import pytest

from notehelpers import arrows_mm as _arrows_mm, share_near as _share_near

CASES = Path(__file__).resolve().parents[1] / "cases"


@pytest.fixture(scope="module")
def ws000():
    from reportgen import load_case
    return load_case(CASES / "ws000_six_bar.toml")


def _label_gaps_mm(fig) -> list[tuple[float, str, str]]:
    """Printed distance between every two label boxes of the figure, mm."""
    from reportgen.scenes.labels import _renderer
    r = _renderer(fig)
    fig.draw_without_rendering()
    texts = [t for ax in fig.axes for t in ax.texts if t.get_visible() and t.get_text().strip()]
    boxes = [(t.get_text(), t.get_window_extent(r)) for t in texts]
    px_mm = fig.dpi / 25.4
    out = []
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            a, b = boxes[i][1], boxes[j][1]
            dx = max(0.0, b.x0 - a.x1, a.x0 - b.x1)
            dy = max(0.0, b.y0 - a.y1, a.y0 - b.y1)
            out.append((float(np.hypot(dx, dy)) / px_mm, boxes[i][0], boxes[j][0]))
    return out


def _plan(study, kind):
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.plans import PlanScene
    return PlanScene(chosen_position(study), kind, landscape=True)


@pytest.mark.parametrize("kind", ["acceleration", "velocity"])
def test_ws000_plan_labels_apart(ws000, captured, kind):
    """Every label of the plan (as in the note) at least 2,5 mm from every other at print scale."""
    _plan(ws000, kind).draw(ws000)
    gaps = _label_gaps_mm(captured[-1])
    close = [g for g in gaps if g[0] < 2.45]
    assert not close, close


def test_ws000_short_vectors_enlarged(ws000, captured):
    """Every vector of the acceleration plan shorter than MIN_MM (n_HD, n_BA, a^τ_AO) is drawn
    again in an enlarged view, at least twice as long, with the magnification written."""
    from reportgen.scenes.plans import MIN_MM, _drawn_segments
    d = _plan(ws000, "acceleration").draw(ws000)
    short = [s.name for s, a, b in _drawn_segments(d.plan, d.mu) if np.hypot(*(b - a)) / d.mu < MIN_MM]
    assert {"a^n_HD", "a^n_BA"} <= set(short)
    shown = {name: ins.k for ins in d.insets for name in ins.segments}
    assert set(short) <= set(shown), (short, shown)
    assert all(k >= 2 for k in shown.values())
    texts = [t.get_text() for t in captured[-1].axes[0].texts]
    for ins in d.insets:
        assert any(t.startswith(ins.mark) and f"×{ins.k:g}" in t for t in texts), texts
    # the crowded points are labelled in the view only, once
    for lab in ("$a′$", "$d′$", "$n_{HD}$", "$n_{BA}$"):
        assert texts.count(lab) == 1, (lab, texts)


def test_insets_free_of_the_plan(ws000):
    """An enlarged view holds no point of the plan and meets none of its lines."""
    from reportgen.scenes import plans as P
    sc = _plan(ws000, "acceleration")
    plan, _, mu, _ = sc.construct(ws000)
    plan = P.similarity_only(plan, ws000.mechanism)
    insets = P.find_insets(plan, mu, 240.0)
    assert insets
    tips = np.array([[0.0, 0.0]] + [list(v) for v in plan.tips.values()])
    for ins in insets:
        R = ins.radius * ins.k
        assert np.all(np.hypot(*(tips - ins.at).T) > R)
        for seg, a, b in P._drawn_segments(plan, mu):
            # distance from the view's centre to the segment
            t = np.clip((ins.at - a) @ (b - a) / ((b - a) @ (b - a)), 0, 1)
            assert np.hypot(*(a + t * (b - a) - ins.at)) > R


def test_ws000_group_45_polygon_arrows_apart(ws000, captured):
    """The group (4, 5) drawing of the note: no two force arrows run within 0,7 mm of each other
    along more than 25 % of the shorter one (R₅₄ was drawn on top of R^n₃₄, G₅ on R₀₅), and no label
    overlaps another or is clipped."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import GroupForces
    from reportgen.scenes.labels import check_figure
    groups = ws000.forces.model.groups
    gi = next(i for i, g in enumerate(groups) if set(g.links) == {"4", "5"})
    GroupForces(chosen_position(ws000), gi, landscape=True).draw(ws000)
    fig = captured[-1]
    arrows = [s for s in _arrows_mm(fig) if np.linalg.norm(s[1] - s[0]) > 1.0]
    bad = []
    for i in range(len(arrows)):
        for j in range(len(arrows)):
            if i == j:
                continue
            (a0, a1), (b0, b1) = arrows[i], arrows[j]
            if np.linalg.norm(a1 - a0) <= np.linalg.norm(b1 - b0) and _share_near(a0, a1, b0, b1) > 0.25:
                bad.append((i, j, _share_near(a0, a1, b0, b1)))
    assert not bad, bad
    assert check_figure(fig) == []
    # the arrow heads do not pile up: at most two arrows end within 2 mm of any arrow's head
    heads = np.array([b for _, b in arrows])
    for h in heads:
        assert np.sum(np.linalg.norm(heads - h, axis=1) < 2.0) <= 2


def test_collinear_closing_side_moved_aside():
    """A closing side along an existing side is moved beside it; a side at an angle is not."""
    from reportgen.scenes.forces import _clear_of_sides, covered
    poly = np.array([[0.0, 0.0], [100.0, 0.0], [100.0, 0.5], [0.0, 60.0]])
    s, e, moved = _clear_of_sides(poly[2], poly[0], poly, 3.5, 1.2)
    assert moved and covered(s, e, poly[0], poly[1], 1.2) == 0.0
    assert np.isclose(np.linalg.norm(s - poly[2]), 3.5) and s[1] < 0.5     # outside the polygon
    s, e, moved = _clear_of_sides(poly[3], poly[0], poly, 3.5, 1.2)
    assert not moved and np.array_equal(s, poly[3])


def test_insets_named_in_the_text(ws000):
    """The note names each enlarged view with its scale μ/k (and says nothing when there is none)."""
    from types import SimpleNamespace
    from reportgen.report.sections.kinematics import _insets_text
    d = _plan(ws000, "acceleration").draw(ws000)
    text = _insets_text(d, "ускорений", "a", "м·с⁻²/мм")
    ins = d.insets[0]
    assert f"выносным элементом {ins.mark} (<span class=\"nowrap\">μ<sub>a</sub>/{ins.k:g}</span> = " in text
    assert _insets_text(SimpleNamespace(insets=[], mu=1.0), "скоростей", "v", "м·с⁻¹/мм") == ""
