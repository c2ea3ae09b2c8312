"""Work that matplotlib repeats while one figure is laid out and saved, done once.

Every figure of a note is laid out (constrained layout: two passes, each asking every axes for
its tight box) and drawn into SVG with its text as glyph paths. Three things were computed over
and over with the same inputs and the same results:

* ``Axis._update_ticks`` (tick locations, labels, positions): called by the axis itself, by
  each of its four spines (``Spine.get_window_extent``) and by the label alignment
  (``_get_tick_boxes_siblings``) inside one ``Axes.get_tightbbox`` or one ``Axis.draw``
  — about 13 times per axis and figure instead of 3;
* the glyph layout of a text drawn as paths (``TextToPath.get_glyphs_with_font``: HarfBuzz
  shaping and FreeType outlines of every glyph), for every tick label of every figure — the
  same strings («0,5», «−10», «φ, град») in the same font;
* the font search of ``TextToPath._get_font`` for each drawn text (``textpath`` keeps its own
  reference to the font manager, so the lookups :mod:`.fontheights` keeps were not used there);
* the layout of a text (``Text._get_layout``: its box relative to its position and its lines),
  made for every tick label in each layout pass, the label alignment and the drawing, and again
  in the next figure for the same strings;
* the «best» place of a legend, searched in both layout passes and twice in its drawing.

Here each is kept for as long as its inputs cannot change, so a figure is laid out and written
from the same numbers as before (``tests/test_sections_speed.py``: the same SVG bytes, and the
counts of the work done).
"""
from __future__ import annotations

import contextlib
import functools
from collections import OrderedDict

GLYPH_CACHE = 4096  # (font, string) glyph layouts kept by a process (three class variants: 131)


def share_all() -> None:
    """Install every reuse of this module (idempotent)."""
    share_tick_updates()
    share_glyph_layouts()
    share_font_search()
    share_text_layouts()
    share_legend_search()


# (owner, attribute, matplotlib's own, ours) for every attribute replaced here
_PATCHES: list[tuple] = []


_DONE: set[str] = set()


def _installed(what: str) -> bool:
    """Whether ``what`` was installed already (then True); marks it installed otherwise. Not
    read from the methods themselves: inside :func:`unshared` they are matplotlib's again."""
    if what in _DONE:
        return True
    _DONE.add(what)
    return False


def _patch(group: str, owner, name: str, new) -> None:
    _PATCHES.append((group, owner, name, getattr(owner, name), new))
    setattr(owner, name, new)


@contextlib.contextmanager
def unshared(*groups: str):
    """matplotlib's own methods for the duration of the block (a test and a bench compare
    the figures and the time with and without the reuse in one process); ``groups``: only those
    reuses (``"ticks"``, ``"glyphs"``, ``"fonts"``, ``"layouts"``, ``"legends"``), else all."""
    chosen = [p for p in _PATCHES if not groups or p[0] in groups]
    for _, owner, name, own, _ in reversed(chosen):     # an attribute replaced twice: the first own last
        setattr(owner, name, own)
    try:
        yield
    finally:
        for _, owner, name, _, ours in chosen:
            setattr(owner, name, ours)


# --- tick updates ---------------------------------------------------------------------------------

class _TickScope:
    """The axes whose tight box or axis drawing is in progress, and the ticks their axes gave.

    Inside ``Axes.get_tightbbox`` and ``Axis.draw`` nothing but the axes' ``apply_aspect`` (run
    first by ``get_tightbbox``) changes an axis's limits, box, locator or formatter: the result
    of ``_update_ticks`` is kept per axis for the scope and reused while those are the same."""

    def __init__(self):
        self.depth = 0
        self.kept: dict = {}
        self.updates = 0          # real ``_update_ticks`` runs (a test reads them)
        self.reused = 0

    def enter(self) -> None:
        self.depth += 1

    def leave(self) -> None:
        self.depth -= 1
        if not self.depth:
            self.kept.clear()


TICKS = _TickScope()


def _axis_state(axis) -> tuple:
    """What ``_update_ticks`` reads that may differ between two calls: the view interval, the
    axes' box in pixels, the locator and formatter objects and the number of ticks made."""
    return (tuple(axis.get_view_interval()), axis.axes.bbox.bounds, id(axis.major.locator),
            id(axis.major.formatter), id(axis.minor.locator), id(axis.minor.formatter),
            len(axis.majorTicks), len(axis.minorTicks))


def share_tick_updates() -> None:
    """Keep ``Axis._update_ticks`` within one tight box or one axis drawing (idempotent)."""
    from matplotlib import axis as maxis
    from matplotlib.axes import _base

    if _installed("ticks"):
        return
    update = maxis.Axis._update_ticks

    def _update_ticks(self):
        if not TICKS.depth:
            TICKS.updates += 1
            return update(self)
        state = _axis_state(self)
        kept = TICKS.kept.get(self)
        if kept is not None and kept[0] == state:
            TICKS.reused += 1
            return list(kept[1])
        TICKS.updates += 1
        ticks = update(self)
        TICKS.kept[self] = (_axis_state(self), list(ticks))   # after: the update may add ticks
        return ticks

    def scoped(fn):
        @functools.wraps(fn)
        def run(*args, **kw):
            TICKS.enter()
            try:
                return fn(*args, **kw)
            finally:
                TICKS.leave()
        return run

    _update_ticks.__wrapped__ = update
    _patch("ticks", maxis.Axis, "_update_ticks", _update_ticks)
    _patch("ticks", maxis.Axis, "draw", scoped(maxis.Axis.draw))
    _patch("ticks", _base._AxesBase, "get_tightbbox", scoped(_base._AxesBase.get_tightbbox))


# --- font search of the text drawn as paths -------------------------------------------------------

def share_font_search() -> None:
    """``TextToPath._get_font`` (a text drawn as glyph paths) finds its font files through the
    lookups that :func:`.fontheights.share_font_heights` keeps for the text layout (the same
    ``_find_fonts_by_props`` answers, searched once per font instead of once per text)."""
    from matplotlib import text as mtext
    from matplotlib import textpath

    from .fontheights import share_font_heights

    if _installed("fonts"):
        return
    share_font_heights()
    _patch("fonts", textpath, "_fontManager", mtext.fontManager)


# --- glyph layouts --------------------------------------------------------------------------------

class _Glyphs:
    """Counts of the glyph layouts made and asked for (a test reads them)."""
    made = 0
    asked = 0


GLYPHS = _Glyphs()


def share_glyph_layouts() -> None:
    """Keep ``TextToPath.get_glyphs_with_font``'s layout of a string per font (idempotent).

    The layout (glyph ids and positions, from HarfBuzz) and the outlines (``FT2Font.get_path``
    of each glyph) depend on the font file, its size and the string (and the text's features
    and language); ``TextToPath`` always sets the size itself (``_get_font``: ``FONT_SCALE``
    at 72 dpi) just before, so a font it has just returned is keyed by itself. Which of the
    glyphs are new to a figure (``return_new_glyphs_only``) is decided per call, as matplotlib
    does; the outlines are handed out as copies."""
    from matplotlib import textpath

    if _installed("glyphs"):
        return
    get_glyphs = textpath.TextToPath.get_glyphs_with_font
    get_font = textpath.TextToPath._get_font
    sized: dict = {}   # id(font) -> (font, size) for fonts that _get_font has just sized

    def _get_font(self, prop):
        font = get_font(self, prop)
        sized[id(font)] = (font, (self.FONT_SCALE, self.DPI))
        return font

    @functools.lru_cache(GLYPH_CACHE)
    def layout(font, size, s, features, language):
        GLYPHS.made += 1
        glyph_info, glyph_map, _ = get_glyphs(textpath.text_to_path, font, s, features=features, language=language)
        for verts, codes in glyph_map.values():
            verts.setflags(write=False)
            codes.setflags(write=False)
        return tuple(glyph_info), dict(glyph_map)

    def get_glyphs_with_font(self, font, s, glyph_map=None, return_new_glyphs_only=False, *,
                             features=None, language=None):
        known = sized.get(id(font))
        if (known is None or known[0] is not font or known[1] != (self.FONT_SCALE, self.DPI)
                or type(self) is not textpath.TextToPath):
            return get_glyphs(self, font, s, glyph_map, return_new_glyphs_only,
                              features=features, language=language)
        sized.pop(id(font))      # sized again by the next _get_font; someone else may resize it
        GLYPHS.asked += 1
        info, outlines = layout(font, known[1], s,
                                None if features is None else tuple(features),
                                language if language is None or isinstance(language, str) else tuple(language))
        if glyph_map is None:
            glyph_map = OrderedDict()
        new = OrderedDict() if return_new_glyphs_only else glyph_map
        for repr_, *_ in info:
            if repr_ not in glyph_map and repr_ not in new:
                verts, codes = outlines[repr_]
                new[repr_] = (verts.copy(), codes.copy())
        return list(info), new, []

    get_glyphs_with_font.__wrapped__ = get_glyphs
    get_glyphs_with_font.cache_info = layout.cache_info
    _patch("glyphs", textpath.TextToPath, "get_glyphs_with_font", get_glyphs_with_font)
    _patch("glyphs", textpath.TextToPath, "_get_font", _get_font)


# --- text layouts ---------------------------------------------------------------------------------

TEXT_LAYOUT_CACHE = 8192   # text layouts kept by a process (a class variant lays out about 400 distinct)


class _Layouts:
    """Counts of the text layouts made and asked for (a test reads them)."""
    made = 0
    asked = 0


LAYOUTS = _Layouts()


def _layout_renderer(renderer, svg, agg, mixed):
    """What of a renderer a text layout depends on: ``"svg"`` for an SVG renderer (``svg``; and
    savefig's mixed-mode one, ``mixed``, while it draws vectors: their extents come from the
    shared ``TextToPath``, :func:`.mplstyle.share_svg_text_metrics`), ``("agg", dpi)`` for an
    Agg renderer (``agg``: the label placer's); ``None`` for any other, whose layouts are not
    kept."""
    kind = type(renderer)
    if kind is mixed and renderer._renderer is renderer._vector_renderer:
        renderer = renderer._renderer
        kind = type(renderer)
    if kind is svg:
        return "svg"
    if kind is agg:
        return ("agg", renderer.dpi)
    return None


def share_text_layouts() -> None:
    """Keep ``Text._get_layout``'s answer per text content and style (idempotent).

    The layout of a text (its box relative to the text's position, each line's width, ascent,
    descent and offset) is made from the string, the font properties, the line spacing, the
    alignments, the angle and rotation mode, the figure's dpi, the renderer's text extents and
    the font's height metrics — never from the position. A figure lays out each tick label and
    legend entry in both passes of the constrained layout, again for the label alignment and
    for the drawing, and the next figure has the same «0,5», «φ, град»; here the answer is
    computed once for those inputs (plus the ``mathtext``/``font`` settings the extents read)
    and handed out as a new ``Bbox`` with the same lines. Wrapped text (its lines depend on the
    position), TeX and renderers other than SVG and Agg are laid out by matplotlib each time."""
    from matplotlib import text as mtext
    from matplotlib.backends.backend_agg import RendererAgg
    from matplotlib.backends.backend_mixed import MixedModeRenderer
    from matplotlib.backends.backend_svg import RendererSVG
    from matplotlib.transforms import Bbox

    from .mplstyle import _rc_key

    if _installed("layouts"):
        return
    get_layout = mtext.Text._get_layout

    kept: dict = {}     # key -> (box corners, lines, text-aligned box); the oldest dropped first

    def _get_layout(self, renderer):
        kind = _layout_renderer(renderer, RendererSVG, RendererAgg, MixedModeRenderer)
        fig = self.get_figure(root=True)
        if kind is None or fig is None or self.get_wrap() or self.get_usetex():
            return get_layout(self, renderer)
        LAYOUTS.asked += 1
        key = (kind, fig.dpi, self.get_text(), hash(self._fontproperties), self.get_parse_math(),
               self._linespacing, self._multialignment, self._horizontalalignment,
               self._verticalalignment, self.get_rotation(), self._rotation_mode, _rc_key())
        got = kept.get(key)
        if got is None:
            LAYOUTS.made += 1
            bbox, info, corner = get_layout(self, renderer)
            points = bbox.get_points().copy()
            points.setflags(write=False)
            if len(kept) >= TEXT_LAYOUT_CACHE:
                del kept[next(iter(kept))]
            got = kept[key] = (points, tuple(info), corner)
        points, info, corner = got
        return Bbox(points.copy()), list(info), corner

    _get_layout.__wrapped__ = get_layout
    _get_layout.kept = kept
    _patch("layouts", mtext.Text, "_get_layout", _get_layout)


# --- the «best» place of a legend -----------------------------------------------------------------

class _LegendSearch:
    """The state of the legends' «best» place search: the axes whose tight box for a layout
    engine is being computed (innermost last), the places found within each ``Legend.draw``,
    and counts of the searches made, kept and left out (a test reads them)."""

    def __init__(self):
        self.layout_axes: list = []
        self.drawing: dict = {}
        self.searched = 0
        self.kept = 0
        self.skipped = 0


LEGENDS = _LegendSearch()


def _candidates_inside(legend, width: float, height: float, renderer) -> bool:
    """Every place the «best» search can choose for a legend box of ``width`` × ``height``
    lies strictly inside its axes' box (``get_window_extent``, as ``Axes.get_tightbbox`` reads
    it): the places are the box anchored at the nine codes in the anchor box less
    ``borderaxespad`` (``offsetbox._get_anchored_bbox``), so when the box fits that padded box
    and the padded box is strictly inside the axes', all of them are."""
    pad = legend.borderaxespad * renderer.points_to_pixels(legend._fontsize)
    if not pad > 0:
        return False
    inner = legend.get_bbox_to_anchor().padded(-pad)
    ax = legend.parent.get_window_extent(renderer)      # the box the axes' tight box is united with
    return (width <= inner.width and height <= inner.height and inner.x0 > ax.x0 and inner.y0 > ax.y0
            and inner.x1 < ax.x1 and inner.y1 < ax.y1)


def share_legend_search() -> None:
    """Search the «best» place of a legend (``loc="best"``) once per drawing (idempotent).

    matplotlib searches it (``Legend._find_best_position``: the count of the axes' line
    vertices, offsets and boxes under each of nine places) whenever the legend's box is asked
    for: in both passes of the constrained layout (``Axes.get_tightbbox(for_layout_only=True)``)
    and twice in ``Legend.draw`` (its frame, then its contents). Here

    * inside a layout's tight box of the legend's own axes, when every place it could choose lies
      strictly inside the axes' box (:func:`_candidates_inside`), the first place is given
      without a search: the tight box is the union with the axes' box, which holds any of them,
      so the layout is the same;
    * within one ``Legend.draw`` the place found first is given again for the same box size and
      renderer (nothing the search reads changes while the legend draws itself)."""
    from matplotlib import legend as mlegend
    from matplotlib.axes import _base
    from matplotlib.transforms import Bbox

    if _installed("legends"):
        return
    find = mlegend.Legend._find_best_position
    draw = mlegend.Legend.draw
    tight = _base._AxesBase.get_tightbbox

    def _find_best_position(self, width, height, renderer):
        axes = LEGENDS.layout_axes
        if axes and self.parent is axes[-1] and _candidates_inside(self, width, height, renderer):
            LEGENDS.skipped += 1
            return self._get_anchored_bbox(1, Bbox.from_bounds(0, 0, width, height),
                                           self.get_bbox_to_anchor(), renderer)
        found = LEGENDS.drawing.get(self)
        key = (width, height, id(renderer))
        if found is not None and key in found:
            LEGENDS.kept += 1
            return found[key]
        LEGENDS.searched += 1
        place = find(self, width, height, renderer)
        if found is not None:
            found[key] = place
        return place

    @functools.wraps(draw)
    def legend_draw(self, renderer):
        LEGENDS.drawing[self] = {}
        try:
            return draw(self, renderer)
        finally:
            LEGENDS.drawing.pop(self, None)

    @functools.wraps(tight)
    def get_tightbbox(self, *args, **kw):
        if not kw.get("for_layout_only"):
            return tight(self, *args, **kw)
        LEGENDS.layout_axes.append(self)
        try:
            return tight(self, *args, **kw)
        finally:
            LEGENDS.layout_axes.pop()

    _find_best_position.__wrapped__ = find
    _patch("legends", mlegend.Legend, "_find_best_position", _find_best_position)
    _patch("legends", mlegend.Legend, "draw", legend_draw)
    _patch("legends", _base._AxesBase, "get_tightbbox", get_tightbbox)
