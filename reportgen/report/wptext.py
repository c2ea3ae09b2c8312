"""A line of text drawn from its shaped glyphs remembered, not shaped a second time.

WeasyPrint (70.0) lays a text box out with a Pango layout, frees it, and when the box is drawn
(``weasyprint.draw.text.draw_text``) makes a new layout for it (``Layout.reactivate``: setup and
text again), shapes the line once more (``pango_layout_get_line_readonly``) and turns its glyphs
into the PDF text operators in a Python loop over every glyph (``draw_first_line``). The glyphs,
their widths and offsets depend on nothing but the font settings of the style, the text and its
spacing (word spacing with the justification, letter spacing, breaking of words); a note draws
the same short texts again and again (a decimal point, «=», a unit, a symbol, a repeated number:
ws000's 8 069 text boxes are 3 043 distinct lines).

:func:`drawn_lines` puts in WeasyPrint's place, while a document is written, a routine that
shapes a line once per font configuration and process (:func:`_shape`) and keeps what
``draw_first_line`` makes of it: the fonts in order with the size set for each, the ``TJ``
strings, and for every glyph its Unicode text and width (which ``draw_first_line`` puts in the
document's font, for its ``ToUnicode`` map and ``Widths``, when the font has no entry yet). A
box drawn again only replays them (:func:`_replay`): the same operators on the same stream, the
same entries put in the fonts in the same order — the same PDF bytes (tests/test_pdf_ratio.py).
Anything else goes to WeasyPrint's own ``draw_text``: an invisible box, a text decoration, an
ellipsis, font variations, a tab, a glyph missing from the fonts (``.notdef``) or the empty glyph
0, a raised glyph (``y_offset``), a colour or bitmap font (emoji images).
"""
from __future__ import annotations

from .wpfast import _FONT, _replaced

__all__ = ["drawn_lines"]

_LIMIT = 20000  # lines remembered per font configuration (then forgotten all at once)


def _key(textbox) -> tuple | None:
    """What the shaped line of ``textbox`` depends on (``Layout.setup`` and ``set_text(justify=True)``
    of WeasyPrint), or ``None`` for a box left to WeasyPrint."""
    style = textbox.style
    layout = textbox.pango_layout
    text = layout.text
    if (style["visibility"] != "visible" or style["text_decoration_line"] != "none"
            or style["font_variation_settings"] != "normal" or "\t" in text):
        return None
    try:
        key = (text, layout.justification_spacing, style["word_spacing"], style["letter_spacing"],
               style["overflow_wrap"], tuple(style["font_family"]), *[style[name] for name in _FONT])
        hash(key)
    except TypeError:  # an unhashable value
        return None
    return key


def _shape(stream, textbox, alive: dict):
    """The line of ``textbox`` shaped as ``draw_text`` shapes it (a new layout, the text with its
    justification spacing, one paragraph) and read as ``draw_first_line`` reads it: a list of
    ``TJ`` strings and fonts ``(pango font, size set, [(glyph, Unicode text, width), ...])``, or
    ``None`` where ``draw_first_line`` would do more (see the module). The document's fonts get
    the entries ``draw_first_line`` gives them, in its order. ``alive`` keeps, per Pango font, a
    layout holding it, so the fonts remembered stay the same objects."""
    from weasyprint.text.ffi import FROM_UNITS, ffi, pango

    layout = textbox.pango_layout
    layout.reactivate(textbox.style)
    try:
        pango.pango_layout_set_single_paragraph_mode(layout.layout, True)
        first_line, _ = layout.get_first_line()
        steps: list = []
        previous = None
        string = ""
        utf8 = layout.text.encode()
        old_pango = pango.pango_version() < 14802
        run = first_line.runs[0]
        while run != ffi.NULL:
            glyph_item = run.data
            run = run.next
            glyph_string = glyph_item.glyphs
            num_glyphs = glyph_string.num_glyphs
            clusters = glyph_string.log_clusters
            item = glyph_item.item
            pango_font = item.analysis.font
            if pango_font != previous:
                previous = pango_font
                font, font_size = stream.add_font(pango_font)
                if font.svg or font.png or font.colr:
                    return None
                if old_pango:
                    font_size = textbox.style["font_size"]
                if string:
                    steps.append(string)
                string = ""
                glyphs: list = []
                steps.append((pango_font, 1 if font.bitmap else font_size, glyphs))
                alive.setdefault(int(ffi.cast("uintptr_t", pango_font)), layout.layout)
            string += "<"
            rtl = item.analysis.level % 2
            for i, glyph_info in enumerate(glyph_string.glyphs[0:num_glyphs]):
                glyph_id = glyph_info.glyph
                width = glyph_info.geometry.width
                if glyph_id == pango.PANGO_GLYPH_EMPTY:
                    string += f">{-width / font_size}<"
                    continue
                if glyph_id & pango.PANGO_GLYPH_UNKNOWN_FLAG or glyph_id == 0 or glyph_info.geometry.y_offset:
                    return None
                t1 = clusters[i]
                if rtl:
                    t2 = item.length if i == 0 else clusters[i - 1]
                else:
                    t2 = item.length if i == num_glyphs - 1 else clusters[i + 1]
                try:
                    unicode = utf8[item.offset + t1:item.offset + t2].decode()
                except UnicodeDecodeError:
                    return None
                font.to_unicode.setdefault(glyph_id, unicode)
                offset = glyph_info.geometry.x_offset / font_size
                if offset:
                    string += f">{-offset}<"
                string += f"{glyph_id:02x}" if font.bitmap else f"{glyph_id:04x}"
                if glyph_id in font.widths:
                    logical_width = font.widths[glyph_id]
                else:
                    pango.pango_font_get_glyph_extents(pango_font, glyph_id, stream.ink_rect, stream.logical_rect)
                    logical_width = font.widths[glyph_id] = round(
                        stream.logical_rect.width * 1000 * FROM_UNITS / font_size)
                kerning = logical_width + offset - width * 1000 * FROM_UNITS / font_size
                if kerning:
                    string += f">{int(kerning)}<"
                glyphs.append((glyph_id, unicode, logical_width))
            if string[-1] == "<":
                string = string[:-1]
            else:
                string += ">"
        steps.append(string)
        return steps
    finally:
        layout.deactivate()


def _replay(stream, textbox, steps) -> None:
    """The operators ``draw_text`` writes for ``textbox`` whose line is ``steps`` (:func:`_shape`;
    ``None``: a line of spaces only, which WeasyPrint draws as an empty text object), and the
    entries ``draw_first_line`` puts in the document's fonts that they do not have yet."""
    from weasyprint.matrix import Matrix

    stream.set_color(textbox.style["color"])
    stream.begin_text()
    if steps is not None:
        x, y = textbox.position_x, textbox.position_y + textbox.baseline
        stream.set_text_matrix(*Matrix(d=-1, e=x, f=y).values)
        for step in steps:
            if step.__class__ is str:
                stream.show_text(step)
                continue
            pango_font, size, glyphs = step
            font, _ = stream.add_font(pango_font)
            to_unicode, widths = font.to_unicode, font.widths
            for glyph_id, unicode, width in glyphs:
                if glyph_id not in to_unicode:
                    to_unicode[glyph_id] = unicode
                if glyph_id not in widths:
                    widths[glyph_id] = width
            stream.set_font_size(font.hash, size)
    stream.end_text()


def _draw_text(general):
    """``weasyprint.draw.text.draw_text`` with each line shaped once (:func:`_shape`) and replayed
    (:func:`_replay`); a box :func:`_key` or :func:`_shape` refuses goes to ``general``."""

    def draw_text(stream, textbox, offset_x, text_overflow, block_ellipsis="none"):
        if text_overflow == "ellipsis" or block_ellipsis != "none":
            return general(stream, textbox, offset_x, text_overflow, block_ellipsis)
        style = textbox.style
        assert style["font_size"]  # as WeasyPrint: Pango crashes with font-size: 0
        if not textbox.text.strip() and style["visibility"] == "visible" and style["text_decoration_line"] == "none":
            return _replay(stream, textbox, None)  # draw_first_line draws nothing for it
        if style["font_size"] < 1e-6:
            return general(stream, textbox, offset_x, text_overflow, block_ellipsis)
        key = _key(textbox)
        if key is None:
            return general(stream, textbox, offset_x, text_overflow, block_ellipsis)
        font_config = style.font_config
        kept = font_config.__dict__.get("_reportgen_lines")
        if kept is None:
            kept = font_config.__dict__["_reportgen_lines"] = ({}, {})  # lines, a layout per font
        lines, alive = kept
        steps = lines.get(key)
        if steps is None:
            steps = _shape(stream, textbox, alive)
            if steps is None:
                return general(stream, textbox, offset_x, text_overflow, block_ellipsis)
            if len(lines) >= _LIMIT:
                lines.clear()
            lines[key] = steps
        _replay(stream, textbox, steps)

    return draw_text


def drawn_lines():
    """While a document is written (``write_pdf``): ``draw_text`` by :func:`_draw_text`, where
    WeasyPrint's drawing module calls it (``weasyprint.draw`` binds the name at import)."""
    from weasyprint import draw

    return _replaced(draw, "draw_text", _draw_text)
