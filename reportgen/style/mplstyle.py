"""matplotlib figures for the printed report: same serif font, decimal comma,
deterministic SVG.

Scenes create a figure with :func:`figure` (an OO ``Figure``; pyplot and its
figure registry are never used), draw on it, and hand :func:`to_svg` bytes to
the report::

    fig = figure(160, 90)
    ax = fig.add_subplot()
    ax.plot(phi_deg, v_B)
    ax.set_xlabel("φ, град")
    svg = to_svg(fig)

The style is applied to ``matplotlib.rcParams`` by :func:`apply_style` (called
by :func:`figure`), because artists added to a figure later read their
defaults (line widths, font) from ``rcParams`` at creation time; the values are
the same for every report, so this is idempotent.
"""

from __future__ import annotations

import contextlib
import functools
import io
import os

import matplotlib
from matplotlib import font_manager
from matplotlib.figure import Figure
from matplotlib.ticker import ScalarFormatter

from . import fonts, mplreuse, svgslim
from .fontheights import rc_values, share_font_heights
from .numbers import mpl_formatter

__all__ = ["MM", "style_rc", "apply_style", "style", "figure", "localize_axes", "to_svg"]

MM = 1 / 25.4  # inches per millimetre
SVG_HASHSALT = "reportgen"


@functools.lru_cache(maxsize=None)
def _register_font() -> str:
    """Register the report's serif faces with matplotlib; return the family name."""
    family = fonts.find_serif()
    for path in family.faces().values():
        font_manager.fontManager.addfont(str(path))
    _settle_font_list(family.faces().values())
    return font_manager.FontProperties(fname=str(family.regular)).get_name()


def _settle_font_list(preferred) -> None:
    """Make matplotlib's choice of a font file independent of the user's font cache.

    ``findfont`` returns the *first* entry of ``fontManager.ttflist`` among those of the
    best score, and that list is in the order of a Python ``set`` of file names at the time
    the cache (``~/.cache/matplotlib/fontlist-*.json``) was built, so it changes with the
    hash seed of the process that built it. Two files of one family (Debian's
    ``fonts-liberation`` and ``fonts-liberation2`` both install "Liberation Serif", with
    different outlines and the same PostScript name) then gave figures whose glyphs came
    from one file or the other depending on the cache. Here the report's own faces come
    first and the rest is sorted by file, so the same installed fonts give the same files.
    """
    manager = font_manager.fontManager
    ours = {os.path.realpath(p) for p in preferred}

    def key(e):
        return (os.path.realpath(e.fname) not in ours, str(e.fname), getattr(e, "index", 0),
                e.name, e.style, e.variant, str(e.weight), str(e.stretch), str(e.size))

    manager.ttflist.sort(key=key)
    manager.afmlist.sort(key=key)
    font_manager.FontManager._findfont_cached.cache_clear()


def style_rc() -> dict:
    """rcParams for figures printed at 1:1 on an A4 page (sizes in points)."""
    name = _register_font()
    return {
        "font.family": "serif",
        "font.serif": [name, "DejaVu Serif"],
        "font.size": 11,
        "axes.titlesize": 11,
        "axes.labelsize": 11,
        "xtick.labelsize": 10,
        "ytick.labelsize": 10,
        "legend.fontsize": 10,
        "mathtext.fontset": "custom",
        "mathtext.rm": name,
        "mathtext.it": f"{name}:italic",
        "mathtext.bf": f"{name}:bold",
        "mathtext.sf": name,
        "mathtext.cal": name,
        "mathtext.tt": "DejaVu Sans Mono",
        "mathtext.fallback": "stix",
        "axes.unicode_minus": True,
        "axes.linewidth": 0.8,
        "axes.edgecolor": "black",
        "axes.labelcolor": "black",
        "axes.grid": True,
        "axes.axisbelow": True,
        "axes.prop_cycle": matplotlib.cycler(
            color=["#000000", "#1f4e9c", "#b2182b", "#2e7d32", "#6a3d9a", "#e08214"]
        ),
        "grid.color": "#9a9a9a",
        "grid.linestyle": (0, (3, 2)),
        "grid.linewidth": 0.4,
        "lines.linewidth": 1.4,
        "lines.markersize": 4,
        "xtick.color": "black",
        "ytick.color": "black",
        "xtick.direction": "in",
        "ytick.direction": "in",
        "xtick.major.width": 0.8,
        "ytick.major.width": 0.8,
        "xtick.major.size": 3.5,
        "ytick.major.size": 3.5,
        "legend.frameon": True,
        "legend.framealpha": 1.0,
        "legend.edgecolor": "#555555",
        "legend.fancybox": False,
        "figure.facecolor": "white",
        "axes.facecolor": "white",
        "savefig.facecolor": "white",
        "figure.dpi": 100,
        "svg.fonttype": "path",
        "svg.hashsalt": SVG_HASHSALT,
        "svg.image_inline": True,
        "path.simplify": True,
    }


def apply_style() -> None:
    """Put the report style into ``matplotlib.rcParams`` (idempotent)."""
    matplotlib.rcParams.update(style_rc())
    share_mathtext()
    share_svg_text_metrics()
    share_font_heights()
    mplreuse.share_all()


MATHTEXT_CACHE = 4096  # parsed mathtext strings kept by a process (ws000's four sections: about 170)


def share_mathtext() -> None:
    """One cache of parsed mathtext for the whole process (idempotent).

    matplotlib caches ``MathTextParser._parse_cached`` in an ``lru_cache(50)`` keyed by the
    parser itself, and every renderer makes its own parser (``RendererBase._text2path``,
    ``RendererAgg.mathtext_parser``): the label placer's Agg renderer, savefig's SVG renderer
    and each renderer the layout engine asks for. So a label was parsed again for every renderer
    that measured or drew it (ws000's dynamics: 25 distinct strings parsed 78 times, a
    quarter of the section's CPU time). Here the cache is keyed by what the parse depends on instead of the
    parser: the output type (vector or raster), the string, dpi, font properties, antialiasing,
    glyph flags and the ``mathtext.*`` and hinting settings; a parse is the same whichever
    parser of the same output type ran it, so the figures do not change.
    """
    from matplotlib import mathtext

    if getattr(mathtext.MathTextParser._parse_cached, "_reportgen_shared", False):
        return
    parse = mathtext.MathTextParser._parse_cached
    parse = getattr(parse, "__wrapped__", parse)       # matplotlib's own function, without its cache
    canonical = {}

    @functools.lru_cache(MATHTEXT_CACHE)
    def parsed(kind, s, dpi, prop, rest, rc):
        parser = canonical.get(kind)
        if parser is None:
            parser = canonical[kind] = mathtext.MathTextParser("path" if kind == "vector" else "agg")
        return parse(parser, s, dpi, prop, *rest)

    def shared(self, s, dpi, prop, *rest):     # rest: antialiased (and glyph flags since 3.10)
        return parsed(self._output_type, s, dpi, prop, rest, _rc_key())

    shared._reportgen_shared = True
    shared.cache_info = parsed.cache_info
    shared.__wrapped__ = parse
    mathtext.MathTextParser._parse_cached = shared


def share_svg_text_metrics() -> None:
    """One cache of text extents for every SVG renderer of the process (idempotent).

    matplotlib caches a text's width, height and descent per renderer instance
    (``text._get_text_metrics_with_cache``), and ``savefig`` of a figure with a layout engine
    makes three SVG renderers (one for the draw before the drawing, one that the layout engine
    asks for, one to draw): every tick label and legend entry was measured up to three times in
    every figure. An SVG renderer measures with its ``TextToPath`` at a fixed 72 dpi and nothing of
    its own, so one shared ``TextToPath`` gives the same extents; other renderers (Agg for
    the label placer) keep matplotlib's cache.
    """
    from matplotlib import text as mtext
    from matplotlib.backends.backend_mixed import MixedModeRenderer
    from matplotlib.backends.backend_svg import RendererSVG
    from matplotlib.textpath import TextToPath

    if getattr(mtext._get_text_metrics_with_cache, "_reportgen_shared", False):
        return
    original = mtext._get_text_metrics_with_cache
    measure = TextToPath()

    @functools.lru_cache(MATHTEXT_CACHE)
    def svg_metrics(text, fontprop, ismath, dpi, rc):
        return measure.get_text_width_height_descent(text, fontprop, ismath)

    def metrics(renderer, text, fontprop, ismath, dpi):
        # savefig draws through a MixedModeRenderer: in vector mode it measures with its SVG renderer
        if type(renderer) is MixedModeRenderer and renderer._renderer is renderer._vector_renderer:
            renderer = renderer._renderer
        if type(renderer) is RendererSVG and ismath != "TeX":
            return svg_metrics(text, fontprop.copy(), ismath, dpi, _rc_key())
        return original(renderer, text, fontprop, ismath, dpi)

    metrics._reportgen_shared = True
    mtext._get_text_metrics_with_cache = metrics


def _rc_key() -> tuple:
    return rc_values(_MATHTEXT_RC)


# the settings a parse reads besides its arguments (the fonts of the custom set, fallback, hinting)
_MATHTEXT_RC = ("mathtext.fontset", "mathtext.rm", "mathtext.it", "mathtext.bf", "mathtext.bfit",
                "mathtext.sf", "mathtext.tt", "mathtext.cal", "mathtext.fallback", "mathtext.default",
                "text.hinting", "text.hinting_factor", "text.kerning_factor", "font.family",
                "font.serif", "font.sans-serif", "font.monospace", "font.cursive", "font.fantasy")


@contextlib.contextmanager
def style():
    """The report style for the duration of a ``with`` block only."""
    with matplotlib.rc_context(style_rc()):
        yield


class _Figure(Figure):
    """A figure that skips the artists in ``savefig``'s draw before the drawing.

    With a layout engine, ``savefig`` draws the figure twice: first with every ``draw_*`` of the
    renderer disabled (``RendererBase._draw_disabled``), only so that the layout runs once
    before the real drawing (which keeps that layout); then for real. The first pass here runs
    the layout alone, without drawing every artist into nothing. Other draws with drawing
    disabled (``draw_without_rendering``, to update the artists' state) stay whole."""

    def draw(self, renderer):
        if (self.axes and self.get_layout_engine() is not None and getattr(self.canvas, "_is_saving", False)
                and _disabled(renderer)):
            self.get_layout_engine().execute(self)
            return
        super().draw(renderer)


def _disabled(renderer) -> bool:
    """The renderer's drawing is switched off (``_draw_disabled`` puts no-ops on the instance;
    a vector backend's ``MixedModeRenderer`` passes them on to its vector renderer)."""
    from matplotlib.backends.backend_mixed import MixedModeRenderer
    if isinstance(renderer, MixedModeRenderer):
        renderer = renderer._renderer
    return "draw_path" in getattr(renderer, "__dict__", {})


def figure(width_mm: float = 160, height_mm: float = 90, **kw) -> Figure:
    """A new OO figure of the given printed size (constrained layout)."""
    apply_style()
    kw.setdefault("layout", "constrained")
    return _Figure(figsize=(width_mm * MM, height_mm * MM), **kw)


def localize_axes(ax, digits: int | None = None) -> None:
    """Decimal-comma tick labels with U+2212 on both axes of ``ax``.

    Only default (scalar) formatters are replaced; a formatter the scene set
    itself (degrees, log scale, …) is kept.
    """
    for axis in (ax.xaxis, ax.yaxis):
        if axis.get_scale() != "linear":
            continue
        if type(axis.get_major_formatter()) is ScalarFormatter:
            axis.set_major_formatter(mpl_formatter(digits))


# figures serialised while a ``captured()`` block is active (the drawing sheets take the scenes'
# matplotlib figures themselves, to place them as vector views on an A1 sheet)
_CAPTURE: list[list[Figure]] = []


@contextlib.contextmanager
def captured():
    """Collect every figure that :func:`to_svg` serialises inside the block."""
    sink: list[Figure] = []
    _CAPTURE.append(sink)
    try:
        yield sink
    finally:
        _CAPTURE.remove(sink)


def to_svg(fig: Figure) -> bytes:
    """The figure as deterministic SVG bytes (glyphs as paths, no date, fixed ids), rewritten
    by :func:`~reportgen.style.svgslim.slim` to draw the same with far fewer elements."""
    for ax in fig.axes:
        localize_axes(ax)
    for sink in _CAPTURE:
        sink.append(fig)
    buf = io.BytesIO()
    with matplotlib.rc_context({"svg.fonttype": "path", "svg.hashsalt": SVG_HASHSALT}):
        fig.savefig(buf, format="svg", metadata={"Date": None})
    return svgslim.slim(buf.getvalue())
