"""Shortcuts through WeasyPrint's drawing code that write the very same PDF operators.

WeasyPrint (70.0, pinned in pyproject.toml) draws the borders of a box by its general
routine (``weasyprint.draw.border.draw_border``). A table cell of the note has a border on
two or three sides only (right and bottom, and left in the first column: the separate border
model of gost.css), which WeasyPrint cannot draw as one rounded rectangle: it draws each side
alone, clipped to the side's trapezoid — a clip path and an even-odd fill of the border box
less the padding box (ГОСТ 2.303's solid line of the table grid). That is some 1 700 sides in
a heavy part, and its general code (three closures built per side, the colours and styles of
all four sides looked up, the rounded boxes computed three times per side) costs more than
the operators it writes.

:func:`cell_borders` puts in its place, while a note's PDF is written, a routine that writes
those operators directly for the one case the note's tables need — solid sides of one colour,
no rounded corner, no border image, no column rule — and hands every other box to
WeasyPrint's own routine. The operators, their numbers and their order are WeasyPrint's: the
same expressions on the same floats (a side's clip path as ``clip_border_segment`` traces it
when no corner is rounded; ``draw_rounded_border``'s two rectangles), so the PDF is the same
bytes (tests/test_pdf_ratio.py compares whole notes with and without it). ws000's parts
written alternately with and without it (one process, 3 rounds, load 9,5): sum of the
minimums 1,194 → 1,028 s CPU, heavy parts 0,367/0,349/0,272 → 0,287/0,305/0,249 s; ws004's
kinematics 0,334 → 0,270 s; every part the same bytes.

Two more for the text (layout and drawing; the min- and max-content widths of a text that does
not wrap, measured once here since session 10, are now ``wpsplit.first_lines``'s):
:func:`text_layouts` (the Pango context, font description and feature string of a piece of text
made once per font, not per piece: :func:`_layout_setup`) and :func:`line_struts` (a style's strut computed once: :func:`_struts`). ws000, ``python
bench/bench_wpfast.py``: 23 635 set-ups 16,2 → 7,0 µs, 14 467 struts 8,2 → 0,2 µs; about
0,34 s CPU less per note, the same bytes.
"""
from __future__ import annotations

import contextlib

__all__ = ["cell_borders", "line_struts", "text_layouts", "writing"]

_ORDER = (2, 3, 1, 0)  # bottom, left, right, top: WeasyPrint's order of the sides


def _draw_border(stream, box, general):
    """``weasyprint.draw.border.draw_border`` for a box whose drawn sides are all solid, of one
    opaque colour, without rounded corners (and not all four: that WeasyPrint draws as one
    rectangle); any other box goes to ``general`` (WeasyPrint's own routine)."""
    style = box.style
    widths = (box.border_top_width, box.border_right_width, box.border_bottom_width, box.border_left_width)
    if (0 not in widths or not any(widths) or style["visibility"] != "visible"
            or style["border_image_source"][0] != "none" or style["column_width"] != "auto"
            or style["column_count"] != "auto" or box.border_top_left_radius != (0, 0)
            or box.border_top_right_radius != (0, 0) or box.border_bottom_right_radius != (0, 0)
            or box.border_bottom_left_radius != (0, 0)):
        return general(stream, box)
    from weasyprint.draw.color import get_color

    color = None
    for side, width in zip(("top", "right", "bottom", "left"), widths):
        if width:
            c = get_color(style, f"border_{side}_color")
            if style[f"border_{side}_style"] != "solid" or not c.alpha or (color is not None and c != color):
                return general(stream, box)
            color = c
    x, y, w, h, *radii = box.rounded_border_box()
    if any(rx != 0 or ry != 0 for rx, ry in radii):
        return general(stream, box)
    px, py, pw, ph, *pradii = box.rounded_padding_box()
    if not all(0 in corner for corner in pradii):
        return general(stream, box)
    bt, br, bb, bl = widths
    if stream._tags is not None:  # a tagged PDF: each side marked as an artifact
        for index in _ORDER:
            if widths[index]:
                with stream.artifact(), stream.stacked():
                    _side(stream.stream, stream, index, x, y, w, h, bt, br, bb, bl, px, py, pw, ph, color)
        return None
    data = stream.stream
    for index in _ORDER:
        if widths[index]:
            stream.push_state()
            _side(data, stream, index, x, y, w, h, bt, br, bb, bl, px, py, pw, ph, color)
            stream.pop_state()
    return None


def _side(data: list, stream, index: int, x, y, w, h, bt, br, bb, bl, px, py, pw, ph, color) -> None:
    """One side's operators as WeasyPrint writes them inside its ``q``…``Q``, appended to the
    stream's list ``data`` as pydyf's ``move_to``, ``line_to``, ``clip``, ``end``, ``rectangle`` and
    ``fill`` append them (the same bytes: pydyf's ``_to_bytes`` of the same floats); the colour
    by the stream's ``set_color`` (it remembers the colour set)."""
    from pydyf import _to_bytes as b

    # clip_border_segment, solid, no rounded corner: each transition point is the inner
    # corner of the border box, (±width of one side, ±width of the other)
    if index == 0:  # top
        points = ((x + w, y), (x, y), (x + bl, y + bt), (x + w + -br, y + bt))
    elif index == 1:  # right
        main = x + w
        points = ((main, y + h), (main, y), (main + -br, y + bt), (main + -br, y + h + -bb))
    elif index == 2:  # bottom
        main = y + h
        points = ((x + w, main), (x, main), (x + bl, main + -bb), (x + w + -br, main + -bb))
    else:  # left
        points = ((x, y + h), (x, y), (x + bl, y + bt), (x + bl, y + h + -bb))
    (x0, y0), (x1, y1), (x2, y2), (x3, y3) = points
    data += (b" ".join((b(x0), b(y0), b"m")), b" ".join((b(x1), b(y1), b"l")), b" ".join((b(x2), b(y2), b"l")),
             b" ".join((b(x3), b(y3), b"l")), b"W*", b"n")
    # draw_rounded_border, solid, no rounded corner
    stream.set_color(color)
    data += (b" ".join((b(px), b(py), b(pw), b(ph), b"re")), b" ".join((b(x), b(y), b(w), b(h), b"re")), b"f*")


@contextlib.contextmanager
def _replaced(owner, name: str, make):
    """``owner.name`` replaced by ``make(original)`` until exit; a nested use keeps the
    outermost replacement (marked ``_reportgen``)."""
    general = getattr(owner, name)
    if getattr(general, "_reportgen", False):
        yield
        return
    fast = make(general)
    fast._reportgen = True
    setattr(owner, name, fast)
    try:
        yield
    finally:
        setattr(owner, name, general)


def cell_borders():
    """While a document is written (``write_pdf``): the borders of table cells drawn by
    :func:`_draw_border`, the same operators as WeasyPrint's. WeasyPrint's drawing module
    looks the routine up by name when it draws a box, so the name is replaced there and put
    back on exit (nested uses keep the outermost)."""
    from weasyprint import draw

    return _replaced(draw, "draw_border", lambda general: lambda stream, box: _draw_border(stream, box, general))


_FONT = ("direction", "font_language_override", "lang", "font_style", "font_stretch", "font_weight", "font_size",
         "font_variant_caps", "font_kerning", "font_variant_ligatures", "font_variant_position",
         "font_variant_numeric", "font_variant_alternates", "font_variant_east_asian", "font_feature_settings")


def _text_setting(style, contexts: dict) -> tuple:
    """What ``Layout.setup`` makes for ``style``: the Pango context (font map, no glyph position
    rounding, base direction, language — one per direction and language, in ``contexts``), the
    language, the font description and the OpenType feature string (or ``None``), each made
    as WeasyPrint's ``setup`` makes it."""
    from weasyprint.text.constants import LST_TO_ISO, PANGO_DIRECTION
    from weasyprint.text.ffi import ffi, gobject, pango, unicode_to_char_p
    from weasyprint.text.fonts import font_features, get_font_description

    if style["font_language_override"] != "normal":
        override = style["font_language_override"]
        lang = LST_TO_ISO.get(override.lower(), override)
    else:
        lang = style["lang"] or None
    kept = contexts.get((style["direction"], lang))
    if kept is None:
        context = ffi.gc(pango.pango_font_map_create_context(style.font_config.font_map), gobject.g_object_unref)
        pango.pango_context_set_round_glyph_positions(context, False)
        pango.pango_context_set_base_dir(context, PANGO_DIRECTION[style["direction"]])
        if lang is None:
            language = pango.pango_language_get_default()
        else:
            lang_p, _ = unicode_to_char_p(lang)
            language = pango.pango_language_from_string(lang_p)
            pango.pango_context_set_language(context, language)
        kept = contexts[style["direction"], lang] = (context, language)
    features = font_features(
        style["font_kerning"], style["font_variant_ligatures"], style["font_variant_position"],
        style["font_variant_caps"], style["font_variant_numeric"], style["font_variant_alternates"],
        style["font_variant_east_asian"], style["font_feature_settings"])
    features = ",".join(f"{key} {value}" for key, value in features.items()).encode() if features else None
    return (*kept, get_font_description(style), features)


def _layout_setup(general):
    """``weasyprint.text.line_break.Layout.setup`` — which makes, for every piece of text laid
    out and again when it is drawn, a new Pango context (font map, rounding, base direction,
    language), a new font description and the font's feature string — with all three made
    once per font configuration, direction, language and font (family, style, stretch,
    weight, size, variants, features): Pango copies the description into the layout and only
    reads the context's settings, which no one changes after they are made, so the glyphs and
    their positions are the same. A style with font variations or a text decoration (which
    reads the font metrics from the context) goes to WeasyPrint's own ``setup``."""
    from weasyprint.text.ffi import ffi, gobject, pango

    def setup(self, style):
        if style["font_variation_settings"] != "normal" or style["text_decoration_line"] != "none":
            return general(self, style)
        font_config = style.font_config
        settings = font_config.__dict__.get("_reportgen_text")
        if settings is None:
            settings = font_config.__dict__["_reportgen_text"] = ({}, {})  # settings, contexts
        key = (tuple(style["font_family"]), *[style[name] for name in _FONT])
        try:
            kept = settings[0].get(key)
        except TypeError:  # an unhashable value
            return general(self, style)
        if kept is None:
            kept = settings[0][key] = _text_setting(style, settings[1])
        context, language, description, features = kept
        self.style = style
        self.first_line_direction = 0
        self.language = language
        self.layout = ffi.gc(pango.pango_layout_new(context), gobject.g_object_unref)
        pango.pango_layout_set_auto_dir(self.layout, False)
        pango.pango_layout_set_font_description(self.layout, description)
        self.ascent = None
        self.underline_position = None
        self.strikethrough_position = None
        if features is not None:
            # as WeasyPrint: one attribute per feature string, kept by the font configuration
            attr = font_config.font_features.setdefault(features, pango.pango_attr_font_features_new(features))
            attr_list = pango.pango_attr_list_new()
            pango.pango_attr_list_insert(attr_list, attr)
            pango.pango_layout_set_attributes(self.layout, attr_list)

    return setup


def text_layouts():
    """While a document is laid out or written: ``Layout.setup`` by :func:`_layout_setup`
    (a Pango context and a font description made once, not per piece of text)."""
    from weasyprint.text.line_break import Layout

    return _replaced(Layout, "setup", _layout_setup)


def _struts(general):
    """``weasyprint.text.line_break.strut(style)`` (the used line height and baseline of a
    style's strut, CSS 2.1 §10.8.1) answered once per style object: WeasyPrint looks its own
    cache up by a key it builds as the text of a 16-value tuple on every call (11,8 µs a call;
    some 5 000 calls for ws000's dynamics part, 444 styles). The answer depends on the style's
    font and line height only, which a computed style no longer changes when its boxes are
    laid out in lines."""
    memo: dict = {}

    def strut(style):
        kept = memo.get(id(style))
        if kept is not None and kept[0] is style:
            return kept[1]
        got = general(style)
        if len(memo) > 4096:
            memo.clear()
        memo[id(style)] = (style, got)
        return got

    return strut


def line_struts():
    """While a document is laid out: ``strut`` by :func:`_struts` where the inline layout calls
    it (``weasyprint.layout.inline`` binds the name at import). Its calls while computed values
    are being made (``css.units``, ``css.computed_values``: a style not yet complete) are left
    to WeasyPrint."""
    from weasyprint.layout import inline

    return _replaced(inline, "strut", _struts)


@contextlib.contextmanager
def writing():
    """While a laid-out document is written (``write_pdf``): the shortcuts of the drawing —
    :func:`cell_borders`, :func:`text_layouts` and ``wptext.drawn_lines`` (a line of text
    shaped once and replayed)."""
    from .wptext import drawn_lines

    with cell_borders(), text_layouts(), drawn_lines():
        yield
