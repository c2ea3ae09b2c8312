"""The faster paths of drawing the figures give what the plain ones give: the label placer's
indexed and one-by-one clipping against the vectorised clipping, a label's extent moved to a
candidate place against ``Text.get_window_extent``, the shared SVG text extents against a new
SVG renderer's, and savefig of a report figure (layout only in the draw before the drawing)
against matplotlib's own ``Figure`` byte for byte."""
from __future__ import annotations

import io

import numpy as np
import pytest
from matplotlib.figure import Figure
from matplotlib.transforms import Bbox

from reportgen.scenes import labels as L
from reportgen.style import mplstyle


def _random_segments(rng, n):
    a = rng.uniform(0, 400, (n, 2))
    d = rng.normal(0, 12, (n, 2))
    d[: n // 10] *= 25                       # long ones
    d[rng.random(n) < 0.2, 0] = 0.0           # vertical
    d[rng.random(n) < 0.2, 1] = 0.0           # horizontal
    d[rng.random(n) < 0.03] = 0.0             # points
    segs = np.hstack([a, a + d])
    segs[rng.random(n) < 0.01, 2] = np.nan    # non-finite ends
    segs[rng.random(n) < 0.01, 1] = np.inf
    return segs


def test_indexed_and_few_clipping_count_as_the_vectorised_one():
    rng = np.random.default_rng(7)
    for n in (0, 1, 5, 40, 3000):
        segs = _random_segments(rng, n)
        index = L._Segs(segs)
        for _ in range(400):
            x, y = rng.uniform(-20, 420, 2)
            w, h = rng.uniform(0, 40, 2)
            bb = Bbox([[x, y], [x + w, y + h]])
            want = L._crossings(segs, bb)
            assert index.crossings(bb) == want
            assert index.crossings(L._Box(x, y, x + w, y + h)) == want
            finite = segs[np.all(np.isfinite(segs), axis=1)]
            p = L.PAD_PX
            assert L._crossings_few(finite.tolist(), x - p, y - p, x + w + p, y + h + p) == L._crossings(finite, bb)


def test_extent_moved_to_a_place_is_the_rendered_extent():
    fig = mplstyle.figure(80, 60, layout=None)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 10)
    ax.set_ylim(0, 7)
    renderer = L._renderer(fig)
    for text in (r"$S_{2}$", r"$M_{\mathrm{ур}}$", "12", ""):
        t = ax.text(1.0, 1.0, text, fontsize=10, ha="center", va="center")
        extent = L._Extent(t, renderer)
        for xy in ((2.5, 3.25), (9.1, 0.3), (0.0, 6.9)):
            got = extent.at(np.array(xy))
            t.set_position(xy)
            want = t.get_window_extent(renderer)
            assert (got.x0, got.y0, got.x1, got.y1) == (want.x0, want.y0, want.x1, want.y1)


def test_shared_svg_text_extents_are_a_new_renderers():
    from matplotlib import text as mtext
    from matplotlib.backends.backend_svg import RendererSVG
    from matplotlib.font_manager import FontProperties

    mplstyle.apply_style()
    for s, math in (("φ, град", False), ("−0,25", False), (r"$J_{II}$, кг·м²", True)):
        prop = FontProperties(size=10, family="serif")
        got = mtext._get_text_metrics_with_cache(RendererSVG(100, 100, io.StringIO()), s, prop, math, 72)
        want = RendererSVG(100, 100, io.StringIO()).get_text_width_height_descent(s, prop, math)
        assert got == want


def _plot(fig):
    ax, bx = fig.subplots(2, 1, sharex=True)
    x = np.linspace(0, 360, 73)
    ax.plot(x, np.sin(np.radians(x)), label=r"$M_{\Sigma}$")
    ax.plot(x, np.cos(np.radians(x)), label=r"$J_{II}$")
    ax.legend(loc="best")
    ax.set_title("Моменты")
    bx.plot(x, x / 100)
    bx.set_xlabel("φ, град")
    bx.set_ylabel(r"$A$, Дж")
    return fig


@pytest.mark.parametrize("size", [(160, 85), (120, 120)])
def test_report_figure_saves_the_same_svg_as_matplotlibs_figure(size):
    mine = _plot(mplstyle.figure(*size))
    assert type(mine) is not Figure
    plain = _plot(Figure(figsize=(size[0] * mplstyle.MM, size[1] * mplstyle.MM), layout="constrained"))
    assert mplstyle.to_svg(mine) == mplstyle.to_svg(plain)
    mine.draw_without_rendering()             # a draw to update the artists stays whole
    assert mine.axes[0].title.get_position() == plain.axes[0].title.get_position()
