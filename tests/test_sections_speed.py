"""Caches of the section and figure building (issue #15) give what the plain paths give, and do
save the work they are for: text extents measured through savefig's MixedModeRenderer come from
the shared SVG cache (a second figure of the same texts measures nothing again) and equal a new
SVG renderer's."""
from __future__ import annotations

import io

import matplotlib
import numpy as np
from matplotlib.backends.backend_mixed import MixedModeRenderer
from matplotlib.backends.backend_svg import RendererSVG
from matplotlib.font_manager import FontProperties

from reportgen.style import mplstyle


def _chart():
    fig = mplstyle.figure(120, 80)
    ax = fig.add_subplot()
    x = np.linspace(0, 360, 37)
    ax.plot(x, np.sin(np.radians(x)), label=r"$M_{\Sigma}$")
    ax.legend()
    ax.set_xlabel("φ, град")
    ax.set_ylabel(r"$A$, Дж")
    return fig


def test_savefig_measures_each_text_once_per_process(monkeypatch):
    from matplotlib import textpath

    first = mplstyle.to_svg(_chart())
    calls = []
    measure = textpath.TextToPath.get_text_width_height_descent
    monkeypatch.setattr(textpath.TextToPath, "get_text_width_height_descent",
                        lambda self, *a: calls.append(a) or measure(self, *a))
    assert mplstyle.to_svg(_chart()) == first
    assert calls == []


def test_mixed_mode_renderer_extents_are_the_svg_renderers():
    from matplotlib import text as mtext

    mplstyle.apply_style()
    fig = mplstyle.figure(50, 50)
    for s, math in (("φ, град", False), ("−0,25", False), (r"$J_{II}$, кг·м²", True)):
        prop = FontProperties(size=10, family="serif")
        mixed = MixedModeRenderer(fig, 1, 1, 72, RendererSVG(100, 100, io.StringIO()))
        got = mtext._get_text_metrics_with_cache(mixed, s, prop, math, 72)
        want = RendererSVG(100, 100, io.StringIO()).get_text_width_height_descent(s, prop, math)
        assert got == want


def _clear_slim_caches():
    from reportgen.style import svgslim
    for fn in (svgslim._transform, svgslim._parsed, svgslim._placed, svgslim._compact):
        fn.cache_clear()


def test_slim_with_its_caches_writes_what_it_writes_without():
    """The text paths of a figure slimmed with the glyph caches cold, warm (the same texts in
    another figure) and bypassed (each glyph parsed and written anew) are the same bytes."""
    from reportgen.style import svgslim

    fig = _chart()
    buf = io.BytesIO()
    with matplotlib.rc_context({"svg.fonttype": "path", "svg.hashsalt": mplstyle.SVG_HASHSALT}):
        fig.savefig(buf, format="svg", metadata={"Date": None})
    raw = buf.getvalue()
    _clear_slim_caches()
    cold = svgslim.slim(raw)
    assert svgslim._placed.cache_info().currsize > 0
    warm = svgslim.slim(raw)
    assert svgslim._placed.cache_info().hits > 0
    assert svgslim._compact.cache_info().hits > 0        # a tick mark's path compacted once
    placed, parsed, transform, compact = svgslim._placed, svgslim._parsed, svgslim._transform, svgslim._compact
    try:
        svgslim._placed = lambda d, m: svgslim._write_path(svgslim._parse_path(d), m)
        svgslim._parsed = svgslim._parse_path
        svgslim._transform = transform.__wrapped__
        svgslim._compact = compact.__wrapped__
        plain = svgslim.slim(raw)
    finally:
        svgslim._placed, svgslim._parsed, svgslim._transform, svgslim._compact = placed, parsed, transform, compact
    assert cold == warm == plain
    assert b"<use" not in plain


def _segments(rng, n):
    """test_figure_speed_paths' random segments, with some shorter than the parallel tolerance
    and some ends at −∞ besides."""
    from test_figure_speed_paths import _random_segments

    segs = _random_segments(rng, n)
    tiny = rng.random(n) < 0.05
    segs[tiny, 2:] = segs[tiny, :2] + 1e-13
    segs[rng.random(n) < 0.01, 3] = -np.inf
    return segs


def test_clip_kernels_count_as_the_numpy_forms():
    """The placer's compiled clipping (reportgen.core.clip) against the NumPy forms it replaced:
    the same count for every rectangle and every leader, whatever the segments."""
    from reportgen.scenes import labels as L

    rng = np.random.default_rng(11)
    for n in (0, 1, 7, 60, 2500):
        segs = _segments(rng, n)
        index = L._Segs(segs)
        corner = rng.uniform(-20, 420, (300, 2))
        size = rng.uniform(0, 40, (300, 2)) * (rng.random((300, 1)) < 0.9)      # some empty boxes
        ends = rng.uniform(-20, 420, (300, 2))
        vertical = rng.random(300) < 0.2
        ends[vertical, 0] = corner[vertical, 0]                                   # vertical leaders
        for (x, y), (w, h), (ex, ey) in zip(corner, size, ends):
            box = L._Box(x, y, x + w, y + h)
            with np.errstate(invalid="ignore"):
                assert index.crossings(box) == index.crossings_numpy(box) == L._crossings(segs, box)
            lead = [x, y, ex, ey]
            assert index.cuts(lead) == index.cuts_numpy(lead)


def test_clip_warm_compiles_what_the_placer_calls():
    """``clip.warm`` (run by ``reportgen warmup`` and each batch worker) compiles the kernels
    for the very argument types the placer passes: placing labels compiles nothing more."""
    from reportgen.core import clip
    from reportgen.scenes import labels as L

    clip.warm()
    before = (len(clip.crossings.signatures), len(clip.cuts.signatures))
    index = L._Segs(_segments(np.random.default_rng(3), 50))
    index.crossings(L._Box(10.0, 10.0, 60.0, 40.0))
    index.crossings(L._Box(np.float64(10), 10, 60, 40))
    index.cuts([0, 0, 200.0, 150.0])
    assert (len(clip.crossings.signatures), len(clip.cuts.signatures)) == before


def test_brentq_finds_scipys_roots_to_the_bit():
    """reportgen.analysis.roots.brentq against scipy.optimize.brentq: the same root (==) on
    smooth, steep, flat and kinked functions, brackets either way round, tight and loose
    tolerances, roots at an end; the same errors."""
    import math

    import pytest
    from scipy import optimize

    from reportgen.analysis.roots import brentq

    rng = np.random.default_rng(5)
    fns = [lambda x: math.cos(x) - x, lambda x: x ** 3 - 2 * x - 5, lambda x: math.exp(x) - 3.7,
           lambda x: math.atan(50 * (x - 0.3)), lambda x: (x - 0.7) ** 3, lambda x: abs(x - 0.2) - 0.05,
           lambda x: math.sin(7 * x) + 0.3 * x, lambda x: np.float64(math.tanh(x - 0.1))]
    eps = np.finfo(float).eps
    checked = 0
    for f in fns:
        for _ in range(60):
            a, b = rng.uniform(-3, 3, 2)
            if not f(a) * f(b) <= 0:
                continue
            for xtol, rtol, it in ((1e-15, 4 * eps, 200), (1e-13, 4 * eps, 200), (1e-6, 1e-8, 100), (1e-3, 1e-3, 5)):
                try:
                    want = optimize.brentq(f, a, b, xtol=xtol, rtol=rtol, maxiter=it)
                except RuntimeError:
                    with pytest.raises(RuntimeError):
                        brentq(f, a, b, xtol=xtol, rtol=rtol, maxiter=it)
                    continue
                assert brentq(f, a, b, xtol=xtol, rtol=rtol, maxiter=it) == want
                checked += 1
    assert checked > 500
    assert brentq(lambda x: x - 1.0, 1.0, 2.0) == optimize.brentq(lambda x: x - 1.0, 1.0, 2.0) == 1.0
    for bad in (dict(f=lambda x: x * x + 1, a=-1, b=1), dict(f=lambda x: math.nan, a=0, b=1),
                dict(f=lambda x: x, a=-1, b=1, xtol=0.0), dict(f=lambda x: x, a=-1, b=1, rtol=eps)):
        with pytest.raises(ValueError):
            optimize.brentq(**bad)
        with pytest.raises(ValueError):
            brentq(**bad)


def test_export_and_the_report_modules_import_no_scipy_optimize(tmp_path):
    """``reportgen export`` of ws000 (roots by analysis.roots) and the note's modules (the cam's
    laws included) leave scipy.optimize unimported: its import costs about 0,3 s of CPU."""
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    code = ("import sys; from reportgen.cli import main; from reportgen.report import assemble; "
            f"main(['export', {str(root / 'cases/ws000_six_bar.toml')!r}, '-o', {str(tmp_path)!r}]); "
            "print(sorted(m for m in sys.modules if m.startswith('scipy.optimize')))")
    out = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().splitlines()[-1] == "[]"
    assert (tmp_path / "cycle.csv").exists()


def test_text_layout_reads_each_font_once_and_lays_out_as_matplotlib():
    """``Text._get_layout`` finds a text's font files and reads their height tables once per font
    (``style.fontheights``), not for every tick label at every layout pass; the boxes and the
    figure's SVG are those of matplotlib's own lookups."""
    from matplotlib import text as mtext
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    mplstyle.apply_style()
    kept, get_font = mtext.fontManager, mtext.get_font
    assert hasattr(kept, "_manager") and hasattr(get_font, "__wrapped__")     # installed by the style
    fig = mplstyle.figure(100, 60)
    ax = fig.add_subplot()
    texts = [ax.text(0.1 * i, 0.5, f"{i},5", fontsize=9, rotation=15 * i) for i in range(8)]
    FigureCanvasAgg(fig)
    renderer = fig.canvas.get_renderer()
    before = kept.searches
    boxes = [t._get_layout(renderer)[0].bounds for t in texts]
    assert kept.searches - before <= 1                     # one size, one family: one search at most
    svg = mplstyle.to_svg(_chart())
    try:
        mtext.fontManager, mtext.get_font = kept._manager, get_font.__wrapped__     # matplotlib's own
        assert [t._get_layout(renderer)[0].bounds for t in texts] == boxes
        assert mplstyle.to_svg(_chart()) == svg
    finally:
        mtext.fontManager, mtext.get_font = kept, get_font
    searches = kept.searches
    mplstyle.to_svg(_chart())
    assert kept.searches == searches                       # a figure of known fonts searches nothing


def test_label_placer_reads_the_axes_and_figure_boxes_once():
    """The label placer tests every candidate place against where a label may lie (inside the
    axes and the figure) read once per placing, not per candidate (each ``Bbox.x0`` is a method
    call); the labels land where the per-candidate reading put them."""
    from matplotlib.transforms import Bbox

    from reportgen.scenes.labels import LabelPlacer

    def placed(counting):
        fig = mplstyle.figure(80, 60, layout=None)
        ax = fig.add_axes((0.1, 0.1, 0.8, 0.8))
        ax.set_xlim(0, 10)
        ax.set_ylim(0, 10)
        for i in range(6):
            ax.plot([0, 10], [i * 2, 10 - i], lw=0.8)
        placer = LabelPlacer(ax)
        for i in range(12):
            placer.add(1 + (i * 7) % 9, 1 + (i * 5) % 9, f"$B_{{{i}}}$", point=True)
        reads = []
        if counting:
            extent = ax.get_window_extent

            class Counted(Bbox):
                @property
                def x0(self):
                    reads.append(1)
                    return super().x0

            ax.get_window_extent = lambda *a, **k: Counted(extent(*a, **k).get_points())
        texts = placer.place()
        return [t.get_position() for t in texts], len(reads)

    where, reads = placed(True)
    assert reads <= 2
    assert where == placed(False)[0]


def _aligned_charts():
    """Two charts over one shared axis, their y labels aligned (the label alignment asks every
    sibling axis for its ticks), a legend and mathtext: what the note's diagrams have."""
    fig = mplstyle.figure(120, 90)
    a1, a2 = fig.subplots(2, 1, sharex=True)
    x = np.linspace(0, 360, 73)
    a1.plot(x, 120 * np.sin(np.radians(x)), label=r"$M_{д}$")
    a2.plot(x, np.cos(np.radians(x)), label="ω, рад/с")
    a1.legend(loc="best")
    a2.set_xlabel("φ, град")
    a1.set_ylabel(r"$M$, Н·м")
    a2.set_ylabel("ω, рад/с")
    fig.align_ylabels([a1, a2])
    return fig


def test_ticks_are_updated_once_per_tight_box_and_axis_draw(monkeypatch):
    """``Axis._update_ticks`` (locate, format, place every tick) ran about 13 times per axis and
    figure — for the axis, each of its four spines and each aligned sibling, inside every tight box
    of the layout's two passes and in the drawing; inside one ``Axes.get_tightbbox`` or one
    ``Axis.draw`` nothing it reads changes, so it now runs once per axis there
    (``style.mplreuse``), and the figure is the same."""
    from matplotlib import axis as maxis

    from reportgen.style import mplreuse

    runs = []
    locs = maxis.Axis.get_majorticklocs
    monkeypatch.setattr(maxis.Axis, "get_majorticklocs", lambda self: runs.append(self) or locs(self))
    svg = mplstyle.to_svg(_aligned_charts())
    shared = len(runs)
    runs.clear()
    with mplreuse.unshared():
        assert mplstyle.to_svg(_aligned_charts()) == svg
    assert shared <= 5 * 4 and 3 * shared <= len(runs)      # 4 axes; 18 and 58 when written


def test_glyph_layouts_of_text_drawn_as_paths_are_made_once_per_string(monkeypatch):
    """Every text of an SVG figure is drawn as glyph paths (``svg.fonttype = path``): HarfBuzz
    shaping and FreeType outlines for every tick label of every figure. The layout of a string in
    a font is now kept (``style.mplreuse``): a second figure with the same texts shapes none of
    them again, and the SVG is byte for byte matplotlib's."""
    from matplotlib import _text_helpers

    from reportgen.style import mplreuse

    shaped = []
    layout = _text_helpers.layout
    monkeypatch.setattr(_text_helpers, "layout", lambda s, *a, **k: shaped.append(s) or layout(s, *a, **k))
    first = mplstyle.to_svg(_aligned_charts())
    shaped.clear()
    assert mplstyle.to_svg(_aligned_charts()) == first
    assert shaped == []
    with mplreuse.unshared():
        assert mplstyle.to_svg(_aligned_charts()) == first
    assert len(shaped) > 10                   # matplotlib's own path shapes every tick label again


def test_kept_glyph_layouts_answer_as_matplotlib():
    """The kept layout gives the glyph ids, positions and outlines matplotlib computes — also for a
    glyph from a fallback font and for a map the caller fills (``return_new_glyphs_only=False``) —
    and hands out outlines a caller may change without changing the kept ones."""
    from matplotlib import textpath

    mplstyle.apply_style()
    own = textpath.TextToPath.get_glyphs_with_font.__wrapped__
    prop = FontProperties(family="serif", size=10)
    for s in ["0,5", "−12,25", "φ, град", "ω₁ → ∞", "0,5"]:
        t2p = textpath.TextToPath()
        ours = t2p.get_glyphs_with_font(t2p._get_font(prop), s, glyph_map={}, return_new_glyphs_only=True)
        theirs = own(t2p, t2p._get_font(prop), s, glyph_map={}, return_new_glyphs_only=True)
        assert ours[0] == theirs[0] and list(ours[1]) == list(theirs[1]) and ours[2] == theirs[2] == []
        for (v1, c1), (v2, c2) in zip(ours[1].values(), theirs[1].values()):
            assert np.array_equal(v1, v2) and np.array_equal(c1, c2)
            v1 += 1.0                               # a copy: the kept outline is not changed
        filled = {}
        t2p.get_glyphs_with_font(t2p._get_font(prop), s, glyph_map=filled)
        assert list(filled) == list(theirs[1])
    again = textpath.TextToPath()
    info, outlines, _ = again.get_glyphs_with_font(again._get_font(prop), "0,5", return_new_glyphs_only=True)
    plain = own(again, again._get_font(prop), "0,5", return_new_glyphs_only=True)[1]
    assert all(np.array_equal(outlines[k][0], plain[k][0]) for k in plain)


def test_text_drawn_as_paths_finds_its_font_through_the_kept_lookups(monkeypatch):
    """``TextToPath._get_font`` searched the font files (``_find_fonts_by_props``) for every text
    drawn as paths; it now uses the lookups kept for the text layout: a figure of known fonts
    searches nothing."""
    from matplotlib import font_manager

    mplstyle.to_svg(_aligned_charts())
    searches = []
    manager = font_manager.fontManager
    find = manager._find_fonts_by_props
    monkeypatch.setattr(manager, "_find_fonts_by_props", lambda *a, **k: searches.append(a) or find(*a, **k))
    mplstyle.to_svg(_aligned_charts())
    assert searches == []


def test_cache_keys_read_the_settings_without_rcparams_getitem(monkeypatch):
    """The text caches key every measure and parse by ~20 ``rcParams`` settings; they are read as
    ``RcParams._get`` reads them (no ``__getitem__`` with its deprecation checks per key) and are
    the same values."""
    mplstyle.apply_style()
    rc = matplotlib.rcParams
    expected = tuple(tuple(v) if isinstance(v, list) else v for v in (rc[k] for k in mplstyle._MATHTEXT_RC))
    reads = []
    getitem = matplotlib.RcParams.__getitem__
    monkeypatch.setattr(matplotlib.RcParams, "__getitem__", lambda self, k: reads.append(k) or getitem(self, k))
    assert mplstyle._rc_key() == expected
    assert reads == []


def test_crank_view_passes_the_traced_paths_as_the_per_point_segments(monkeypatch):
    """The enlarged crank view looks for its free place among the drawing's segments, the traced
    paths of the centres of mass among them (≈ 10 000 point pairs): stacked as arrays now, not a
    Python tuple of numpy scalars per pair; the segments are the same float64 numbers."""
    from pathlib import Path

    from reportgen import batch
    from reportgen.analysis.study import Study
    from reportgen.case.load import load_spec
    from reportgen.report import assemble
    from reportgen.scenes import mechanism, plans

    root = Path(__file__).resolve().parents[1]
    seen, args = [], []
    place, view = plans.free_place, mechanism.crank_view
    monkeypatch.setattr(plans, "free_place", lambda c, h, segs, *a: seen.append(segs) or place(c, h, segs, *a))
    monkeypatch.setattr(mechanism, "crank_view", lambda *a: args.append((a, len(seen))) or view(*a))
    v = batch.read_variants(root / "cases/class_six_bar.csv", root / "cases/ws000_six_bar.toml")[0]
    spec = load_spec(v.base, v.params)
    spec.meta_overrides = dict(v.meta)
    assemble.build_report(Study(spec), sections=["kinematics"])
    (study, rows, cv, _, _, coms), first = args[0]
    assert coms and len(seen) > first                 # the view is drawn (this variant needs it)
    segs = []
    for row in rows:
        for link in study.mechanism.moving:
            xy = [(float(row[f"x_{p}"]) / cv.mu, float(row[f"y_{p}"]) / cv.mu) for p in link.points]
            segs += [(*xy[i], *xy[j]) for i in range(len(xy)) for j in range(i + 1, len(xy))]
    for p in coms:
        path = np.column_stack([study.cycle[f"x_{p}"], study.cycle[f"y_{p}"]]) / cv.mu
        segs += [(*path[i], *path[i + 1]) for i in range(len(path) - 1)]
    expected = np.array(segs).reshape(-1, 4)
    assert seen[first].dtype == expected.dtype and np.array_equal(seen[first], expected)


def test_text_layouts_are_made_once_per_text_and_style():
    """``Text._get_layout`` laid out every tick label, legend entry and axis label again in each
    pass of the constrained layout, for the label alignment, in the drawing and in the next
    figure; its answer depends on the text and its style only, never on the position, and is now
    kept (``style.mplreuse``): a second figure with the same texts lays out none of them again,
    and the SVG is byte for byte matplotlib's."""
    from reportgen.style import mplreuse

    first = mplstyle.to_svg(_aligned_charts())
    made, asked = mplreuse.LAYOUTS.made, mplreuse.LAYOUTS.asked
    assert mplstyle.to_svg(_aligned_charts()) == first
    assert mplreuse.LAYOUTS.made == made and mplreuse.LAYOUTS.asked > asked + 50
    with mplreuse.unshared():
        assert mplstyle.to_svg(_aligned_charts()) == first


def test_kept_text_layouts_answer_as_matplotlib():
    """The kept layout is matplotlib's — for rotated, anchored, multi-line, mathtext and
    differently spaced texts, through the SVG, savefig's mixed-mode and the label placer's Agg
    renderers, after a text's style changes — and the box handed out may be changed by the
    caller without changing the kept one."""
    from matplotlib import text as mtext
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    mplstyle.apply_style()
    own = mtext.Text._get_layout.__wrapped__
    fig = mplstyle.figure(80, 60)
    ax = fig.add_subplot()
    texts = [ax.text(0.5, 0.5, "φ, град"), ax.text(0.1, 0.2, "−0,25", rotation=90, va="top"),
             ax.text(0.3, 0.3, "ω₁ →\nε₂, рад/с²", ha="right", multialignment="right", linespacing=1.6),
             ax.text(0.2, 0.7, r"$J_{II}$, кг·м²", rotation=30, rotation_mode="anchor", va="baseline"),
             ax.text(0.6, 0.1, "12,5", fontsize=7, ha="left", va="center_baseline")]
    svg = RendererSVG(100, 100, io.StringIO())
    renderers = [svg, MixedModeRenderer(fig, 1, 1, 72, svg), FigureCanvasAgg(fig).get_renderer()]
    for _ in range(2):
        for t in texts:
            for r in renderers:
                ours, theirs = mtext.Text._get_layout(t, r), own(t, r)
                assert np.array_equal(ours[0].get_points(), theirs[0].get_points())
                assert ours[1:] == theirs[1:]
                ours[0].set_points(np.zeros((2, 2)))         # the caller's copy
        for t in texts:
            t.set_rotation((t.get_rotation() + 45) % 360)   # a new style: laid out anew
            t.set_fontsize(t.get_fontsize() + 1)


def _crowded_legend_chart():
    """A small chart whose legend is taller than its axes (every «best» place reaches out)."""
    fig = mplstyle.figure(70, 40)
    ax = fig.add_subplot()
    x = np.linspace(0, 360, 37)
    for k in range(7):
        ax.plot(x, np.sin(np.radians(x + 40 * k)), label=f"кривая {k + 1}")
    ax.legend(loc="best")
    return fig


def test_legend_best_place_is_searched_once_per_drawing(monkeypatch):
    """A legend at ``loc="best"`` was searched its place four times per figure: in both passes
    of the constrained layout and twice in its drawing. In a layout pass its box, wherever placed
    inside its axes, does not change the axes' tight box, so the search is left out when every
    place it may choose lies inside the axes; in the drawing the place found is kept
    (``style.mplreuse``). A legend that does not fit its axes is still searched in the layout.
    The figures are byte for byte matplotlib's."""
    from matplotlib import legend as mlegend

    from reportgen.style import mplreuse

    searches = []
    data = mlegend.Legend._auto_legend_data
    monkeypatch.setattr(mlegend.Legend, "_auto_legend_data", lambda self, r: searches.append(self) or data(self, r))
    for chart, shared, own in ((_aligned_charts, 1, 4), (_crowded_legend_chart, 3, 4)):
        searches.clear()
        svg = mplstyle.to_svg(chart())
        assert len(searches) == shared
        searches.clear()
        with mplreuse.unshared():
            assert mplstyle.to_svg(chart()) == svg
        assert len(searches) == own
