"""The figures of the mechanism read at print scale (issue 9, item 1; defects from the page-by-page
review of ws002 and ws004): the Assur groups drawn apart each at its own ГОСТ 2.302 scale and
large enough to read, a point's label nearer its own point than any other, position numbers a
character's width apart. Fast: the scene objects are drawn alone, no note is built."""
import math
from pathlib import Path

import numpy as np
import pytest

from reportgen.scenes import labels as L
from reportgen.scenes.draw import GOST_K, panel_scales
from reportgen.style import mplstyle

CASES = Path(__file__).resolve().parents[1] / "cases"
MM = 72 / 25.4     # points per mm


def _study(name):
    from reportgen import load_case
    return load_case(CASES / f"{name}.toml")


@pytest.fixture(scope="module")
def ws002():
    return _study("ws002_tractor_hitch")


@pytest.fixture(scope="module")
def ws004():
    return _study("ws004_slotted_lever")


@pytest.fixture
def captured(monkeypatch):
    """The figures the scenes write, and every label placer with the texts it placed."""
    figs, placers = [], []
    orig_svg, orig_place = mplstyle.to_svg, L.LabelPlacer.place

    def keep(fig):
        figs.append(fig)
        return orig_svg(fig)

    def place(self):
        texts = orig_place(self)
        placers.append((self, texts))
        return texts
    monkeypatch.setattr(mplstyle, "to_svg", keep)
    monkeypatch.setattr(L.LabelPlacer, "place", place)
    return figs, placers


def _position(st):
    from reportgen.report.sections.common import chosen_position
    return chosen_position(st)


def _px_mm(fig):
    return fig.dpi / 25.4


# --- Figure 1.2: the initial mechanism and the Assur groups --------------------------------------

def test_ws002_groups_each_at_own_scale_and_readable(ws002, captured):
    """ws002's initial mechanism (1,2,3) — cylinder, rod and lever, 0,25 × 0,55 m — was drawn at the
    groups' common 1:40, 14 mm tall, its labels crowded. Each group now has its own ГОСТ 2.302
    scale, written under it, and every group is at least 38 mm across on paper."""
    from reportgen.scenes.mechanism import AssurGroups
    figs, _ = captured
    d = AssurGroups(_position(ws002)).draw(ws002)
    assert [p[0].split()[0] for p in d.panels] == ["(1,2,3)", "(4,5)", "(6,7)"]
    for title, mu, extent in d.panels:
        assert any(abs(mu * 1000 - k) < 1e-9 for k in GOST_K), title
        assert extent >= 38.0, (title, extent)
    assert d.width_mm <= 165.0 + 1e-9
    fig = figs[-1]
    assert L.check_figure(fig) == []
    # each group's scale written under it, in the note's notation
    scales = [t.get_text() for t in fig.texts if "м/мм" in t.get_text()]
    assert len(scales) == len(d.panels)
    assert all(t.startswith(r"$\mu_l$ = ") and "." not in t for t in scales)
    # every label inside its own group's drawing
    r = fig.canvas.get_renderer()
    for ax in fig.axes:
        box = ax.get_window_extent(r)
        for t in ax.texts:
            bb = t.get_window_extent(r)
            assert box.x0 <= bb.x0 and bb.x1 <= box.x1 and box.y0 <= bb.y0 and bb.y1 <= box.y1, t.get_text()


def test_panel_scales_enlarge_the_small_group():
    """A group a quarter the size of the others gets a larger scale, not the common one."""
    mus = panel_scales([(0.25, 0.55, 14, 14), (1.0, 0.7, 14, 14), (1.6, 0.6, 14, 14)], 165.0, 75.0, 32.0)
    drawn = [max(w, h) / mu for (w, h), mu in zip([(0.25, 0.55), (1.0, 0.7), (1.6, 0.6)], mus)]
    assert mus[0] < mus[1] <= mus[2]
    assert min(drawn) >= 38.0
    widths = [max(w / mu + 14, 32.0) for w, mu in zip((0.25, 1.0, 1.6), mus)]
    assert sum(widths) <= 165.0


# --- Figures 1.1 and 2.1: a point's label beside its own point -----------------------------------

def _linkage_cases() -> list[str]:
    """Every case of cases/ that has a linkage (a derived case, ``base = …``, is built by batch)."""
    from reportgen import load_case
    from reportgen.errors import CaseError
    out = []
    for path in sorted(CASES.glob("*.toml")):
        try:
            if load_case(path).has_linkage:
                out.append(path.stem)
        except CaseError:
            continue
    return out


OWN_CASES = _linkage_cases()


@pytest.mark.parametrize("name", OWN_CASES)
def test_point_labels_nearer_their_own_point(name, captured):
    """ws002's «23» stood by the support 07 (nearer 07's circle than 23's) and read as the
    support's. On the kinematic scheme and on the plan of positions every point label's centre is
    nearer its own point than any other labelled point (2 mm or more from it) by at least 1 mm
    on paper, unless a leader line joins it to its point (a label moved clear of the lines)."""
    from reportgen.scenes.mechanism import NUMBER_GAP_MM, KinematicScheme, PositionsPlan
    st = _study(name)
    _, placers = captured
    for scene in (KinematicScheme(_position(st)), PositionsPlan()):
        placers.clear()
        scene.draw(st)
        for placer, texts in placers:
            ax = placer.ax
            r = ax.figure.canvas.get_renderer()
            px = _px_mm(ax.figure)
            # position numbers (A₀, A₁ … at the crank pin's positions, placed NUMBER_GAP_MM off) are
            # numbers of one point's positions, kept apart by test_plan_of_positions_labels_distinct
            named = [(it, t) for it, t in zip(placer.items, texts)
                     if it.text.startswith("$") and it.gap_mm != NUMBER_GAP_MM]
            anchors = np.array([ax.transData.transform((it.x, it.y)) for it, _ in named]).reshape(-1, 2)
            for (it, t), own in zip(named, anchors):
                if hasattr(t, "leader"):
                    assert np.allclose(t.leader.get_xydata()[0], (it.x, it.y))
                    continue
                bb = t.get_window_extent(r)
                c = np.array([(bb.x0 + bb.x1) / 2, (bb.y0 + bb.y1) / 2])
                d_own = float(np.hypot(*(c - own)))
                others = anchors[np.hypot(*(anchors - own).T) > 2.0 * px]   # nearly at one place: A, A′
                if len(others):
                    d_other = float(np.hypot(*(others - c).T).min())
                    assert d_own + 1.0 * px < d_other, (type(scene).__name__, it.text, d_own / px, d_other / px)


# --- Figure 2.1: position numbers apart ---------------------------------------------------------

def _gap(a, b) -> float:
    """The clearance between two boxes (0 if they meet): the larger of the two axis gaps."""
    return max(b.x0 - a.x1, a.x0 - b.x1, b.y0 - a.y1, a.y0 - b.y1, 0.0)


def test_ws004_position_numbers_a_character_apart(ws004, captured):
    """On ws004's plan of positions the number «1» stood beside the link number «3» by position 0
    and the two read as «13». Every position number keeps at least a digit's width from every
    other label."""
    from reportgen.scenes.mechanism import POSITION_NUMBER, PositionsPlan
    figs, _ = captured
    PositionsPlan().draw(ws004)
    fig = figs[-1]
    r = fig.canvas.get_renderer()
    ax = fig.axes[0]
    numbers = [t for t in ax.texts if t.get_label() == POSITION_NUMBER]
    assert len(numbers) >= 10
    probe = ax.text(0, 0, "0", fontsize=numbers[0].get_fontsize())
    digit = probe.get_window_extent(r).width
    probe.remove()
    others = [t for t in ax.texts if t.get_text().strip()]
    for t in numbers:
        bb = t.get_window_extent(r)
        for o in others:
            if o is not t:
                g = _gap(bb, o.get_window_extent(r))
                assert g >= 0.95 * digit, (t.get_text(), o.get_text(), g / digit)
    assert math.isfinite(digit) and digit > 0


def test_label_that_cannot_avoid_a_line_gets_a_halo():
    """A label with no free place (a dense fan of lines on the plan of positions: ws002's «23′»)
    breaks the lines under it with a white halo; a label in free space gets none."""
    fig = mplstyle.figure(40, 30, layout=None)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 40)
    ax.set_ylim(0, 30)
    for y in np.arange(0.0, 30.0, 0.6):           # lines every 0,6 mm: no room between them
        ax.plot([0, 40], [y, y], lw=0.3)
    pl = L.LabelPlacer(ax)
    pl.add(20, 15, "$B′$")
    crowded = pl.place()[0]
    assert crowded.get_path_effects()
    fig2 = mplstyle.figure(40, 30, layout=None)
    ax2 = fig2.add_axes((0, 0, 1, 1))
    ax2.set_xlim(0, 40)
    ax2.set_ylim(0, 30)
    pl2 = L.LabelPlacer(ax2)
    pl2.add(20, 15, "$B′$")
    assert not pl2.place()[0].get_path_effects()
