"""Every drawing of every case in cases/: no two labels overlap and none is clipped by the
figure (matplotlib's rendered extents, ``Text.get_window_extent``), labels in textbook notation
(mathtext, never a plain "nbc"), mechanism drawings at a ГОСТ 2.302 scale."""
import re
from pathlib import Path

import pytest

from reportgen.scenes import labels as L
from reportgen.scenes.draw import GOST_K, gost_ratio, gost_scale
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


@pytest.mark.parametrize("st", STUDIES)
def test_no_label_overlaps_or_clipping(st, captured):
    for name, scene in _scenes(st):
        captured.clear()
        scene.draw(st)
        for fig in captured:
            assert L.check_figure(fig) == [], name
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


def test_gost_scales():
    assert gost_ratio(0.04) == "1:40" and gost_ratio(0.0025) == "1:2,5" and gost_ratio(0.0005) == "2:1"
    for extent in (0.05, 0.3, 0.9, 2.7, 11.0):
        mu = gost_scale(extent, 150.0)
        assert mu * 1000 in GOST_K and extent / mu <= 150.0 + 1e-9


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
