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
bytes (tests/test_pdf_ratio.py compares whole notes with and without it).
"""
from __future__ import annotations

import contextlib

__all__ = ["cell_borders"]

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
    for index in _ORDER:
        if widths[index] == 0:
            continue
        with stream.artifact(), stream.stacked():
            # clip_border_segment, solid, no rounded corner: each transition point is the
            # inner corner of the border box, (±width of one side, ±width of the other)
            if index == 0:  # top
                stream.move_to(x + w, y)
                stream.line_to(x, y)
                stream.line_to(x + bl, y + bt)
                stream.line_to(x + w + -br, y + bt)
            elif index == 1:  # right
                main = x + w
                stream.move_to(main, y + h)
                stream.line_to(main, y)
                stream.line_to(main + -br, y + bt)
                stream.line_to(main + -br, y + h + -bb)
            elif index == 2:  # bottom
                main = y + h
                stream.move_to(x + w, main)
                stream.line_to(x, main)
                stream.line_to(x + bl, main + -bb)
                stream.line_to(x + w + -br, main + -bb)
            else:  # left
                stream.move_to(x, y + h)
                stream.line_to(x, y)
                stream.line_to(x + bl, y + bt)
                stream.line_to(x + bl, y + h + -bb)
            stream.clip(even_odd=True)
            stream.end()
            # draw_rounded_border, solid, no rounded corner
            stream.set_color(color)
            stream.rectangle(px, py, pw, ph)
            stream.rectangle(x, y, w, h)
            stream.fill(even_odd=True)


@contextlib.contextmanager
def cell_borders():
    """While a document is written (``write_pdf``): the borders of table cells drawn by
    :func:`_draw_border`, the same operators as WeasyPrint's. WeasyPrint's drawing module
    looks the routine up by name when it draws a box, so the name is replaced there and put
    back on exit (nested uses keep the outermost)."""
    from weasyprint import draw

    general = draw.draw_border
    if getattr(general, "_reportgen", False):
        yield
        return

    def fast(stream, box):
        return _draw_border(stream, box, general)

    fast._reportgen = True
    draw.draw_border = fast
    try:
        yield
    finally:
        draw.draw_border = general
