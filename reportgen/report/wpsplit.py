"""The first line of a text measured once per process, not once per box and per document.

WeasyPrint (70.0) fits a piece of text into a width by ``weasyprint.text.line_break.split_first_line``:
it makes a Pango layout of the text, asks Pango for its first line, and measures it — the inline
layout of every text box of every line (``layout/inline.py: split_text_box``) and twice more for the
min- and max-content width of every table cell and inline block (``layout/preferred.py:
inline_line_widths``). The answer — the first line's length, the index the next line resumes at, its
width, height and baseline, and the layout itself, freed (``Layout.deactivate``: what is left of it
is plain numbers and the text) — depends on nothing but the text, the width offered, the font
configuration and the style's values that the function and ``Layout`` read (font, white space,
spacing, breaking and hyphenation: :data:`_READ`). A note measures the same texts again and again:
a column of numbers for its min- and max-content widths and then in its cells, the same units,
symbols and headers in every table, and a batch worker the same note of the next variant with
other numbers but the same words (each document with new style objects: the memory of session 10,
``wpfast.nowrap_widths``, which this replaces, was keyed by the style object and kept only the
widths of a text that does not wrap within one document).

:func:`first_lines` puts in WeasyPrint's place, while a document is laid out, a routine that keeps
each answer on the font configuration (like ``wptext``'s shaped lines) under the text, the values
the style has for :data:`_READ`, the width and the other arguments, and hands a remembered answer out
as a new ``Layout`` object with the same attributes (each box owns its layout: WeasyPrint writes the
justification into it). The widths, so the pages and the PDF, are the same bytes
(tests/test_pdf_ratio.py).
"""
from __future__ import annotations

from .wpfast import _FONT, _replaced

__all__ = ["first_lines", "STATS"]

# every computed value split_first_line, create_layout, Layout.setup/set_text/set_tabs, line_size
# and first_line_metrics read (WeasyPrint 70.0), beside the font ones of wpfast._FONT
_READ = ("font_family", "white_space", "hyphens", "hyphenate_limit_chars", "hyphenate_limit_zone",
         "hyphenate_character", "overflow_wrap", "word_break", "word_spacing", "letter_spacing", "tab_size",
         "text_decoration_line", "font_variation_settings", *_FONT)
_LIMIT = 30000  # answers remembered per font configuration (then forgotten all at once)
STATS = {"hits": 0, "misses": 0, "general": 0}  # calls answered from memory / measured / left to WeasyPrint


def _signature(style, styles: dict):
    """The values of :data:`_READ` of ``style`` (one tuple per style object and document), or
    ``None`` if one is not hashable."""
    kept = styles.get(id(style))
    if kept is not None and kept[0] is style:
        return kept[1]
    values = tuple(tuple(value) if isinstance(value, list) else value for value in map(style.__getitem__, _READ))
    try:
        hash(values)
    except TypeError:
        values = None
    styles[id(style)] = (style, values)
    return values


def _split(general):
    """``split_first_line`` answered from the font configuration's memory when the same text was
    fitted to the same width with the same values of :data:`_READ` (see the module)."""
    from weasyprint.text.line_break import Layout

    styles: dict = {}  # per document laid out: id(style) -> (style, signature)

    def split(text, style, context, max_width, justification_spacing, is_line_start=True, minimum=False):
        signature = _signature(style, styles)
        if signature is None:
            STATS["general"] += 1
            return general(text, style, context, max_width, justification_spacing, is_line_start, minimum)
        white_space = style["white_space"]
        if white_space not in ("normal", "pre-wrap", "pre-line"):
            max_width = None  # as split_first_line: a text that does not wrap is laid out unconstrained
        if style["word_break"] != "break-all" and style["overflow_wrap"] not in ("anywhere", "break-word"):
            line_start = None  # step 5 (breaking a word) is the only reader of these two
        else:
            line_start = (is_line_start, minimum)
        key = (text, signature, max_width, justification_spacing, line_start)
        memory = style.font_config.__dict__.get("_reportgen_splits")
        if memory is None:
            memory = style.font_config.__dict__["_reportgen_splits"] = {}
        kept = memory.get(key)
        if kept is not None:
            STATS["hits"] += 1
            layout = Layout.__new__(Layout)
            layout.__dict__.update(kept[0])
            return (layout, *kept[1:])
        STATS["misses"] += 1
        got = general(text, style, context, max_width, justification_spacing, is_line_start, minimum)
        if len(memory) >= _LIMIT:
            memory.clear()
        memory[key] = (dict(got[0].__dict__), *got[1:])
        return got

    return split


def first_lines():
    """While a document is laid out (``render``): ``split_first_line`` by :func:`_split` where the
    inline layout and the preferred widths call it (both modules bind the name at import; the
    preferred widths' ``inline_line_widths`` calls the name of ``layout.preferred``)."""
    import contextlib

    from weasyprint.layout import inline, preferred

    stack = contextlib.ExitStack()
    stack.enter_context(_replaced(inline, "split_first_line", _split))
    stack.enter_context(_replaced(preferred, "split_first_line", _split))
    return stack
