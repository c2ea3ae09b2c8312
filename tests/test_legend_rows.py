"""Legends of several columns read row by row, with balanced rows (ws000 Fig. 4.5 printed
«R₀₁ R₂₃ R₀₃ R₃₄ R₄₅ R₀₅» and R₁₂ alone in a second row: matplotlib fills columns first)."""
import pytest
from matplotlib.axes import Axes

from reportgen.scenes.draw import legend_rows
from reportgen.style import mplstyle


def _rows(legend, fig):
    """The legend's labels as printed: rows top to bottom, each left to right."""
    fig.draw_without_rendering()
    r = fig._get_renderer()
    boxes = [(t.get_window_extent(r), t.get_text()) for t in legend.get_texts()]
    ys = sorted({round(b.y0, 1) for b, _ in boxes}, reverse=True)
    return [[t for b, t in sorted(boxes, key=lambda bt: bt[0].x0) if round(b.y0, 1) == y] for y in ys]


@pytest.mark.parametrize("n, most, shape", [(7, 6, [4, 3]), (7, 7, [7]), (12, 6, [6, 6]), (10, 4, [4, 4, 2]),
                                            (5, 4, [3, 2]), (3, 4, [3])])
def test_legend_reads_row_by_row_in_balanced_rows(n, most, shape):
    fig = mplstyle.figure(160, 90)
    ax = fig.add_subplot()
    names = [f"L{i}" for i in range(n)]
    for i, name in enumerate(names):
        ax.plot([0, 1], [i, i], label=name)
    rows = _rows(legend_rows(ax, most, fontsize=8), fig)
    assert [len(r) for r in rows] == shape
    assert [t for r in rows for t in r] == names


def test_reactions_legend_of_ws000_in_plotting_order(ws000, monkeypatch):
    from reportgen.scenes.forces import ReactionCurves
    made = []
    orig = Axes.legend
    monkeypatch.setattr(Axes, "legend", lambda self, *a, **k: made.append((self, orig(self, *a, **k))) or made[-1][1])
    ReactionCurves().draw(ws000)
    ax, leg = made[0]
    plotted = [ln.get_label() for ln in ax.get_lines() if not ln.get_label().startswith("_")]
    rows = _rows(leg, ax.figure)
    assert len(plotted) == 7 and [len(r) for r in rows] == [7]
    assert [t for r in rows for t in r] == plotted
