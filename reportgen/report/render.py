"""Rendering of a :class:`~reportgen.report.document.Report` to HTML and PDF.

* :func:`render_html` — one HTML string (print flavour for WeasyPrint, or a
  self-contained screen flavour with fonts and images as ``data:`` URLs);
* :func:`write_html`, :func:`write_pdf` — atomic writers (temporary file in the
  same folder, then ``os.replace``);
* :func:`build_outputs` — both at once.

Numbering is done here, in Python, once: sections «1», «1.2», «1.2.1»,
appendices «А», «Б», …; figures, tables and formulas per chapter («2.1»,
«А.1»). The numbers are written into the HTML as text, so the screen HTML
(browsers have no ``target-counter``) and the PDF agree, and cross-references
(:func:`~reportgen.report.document.ref`) resolve to text. Page numbers in the
table of contents come from CSS ``target-counter`` (print only).

«Продолжение таблицы N» (ГОСТ 7.32) is done in passes (docs/reporting.md §2.1):

1. every table is laid out whole, its caption being the first row of
   ``<thead>``; WeasyPrint repeats the header on every page, so each later
   page reserves at least the height of a «Продолжение таблицы N» line;
2. the rows that start each page (the rows' ``data-row`` names) become
   split points; the table is cut into parts, each continuation part starting
   on a new page (``break-before: page``) under «Продолжение таблицы N» with
   the column header repeated;
3. the layout is repeated until no part spans two pages (a part that still
   overflows moves its end, and the later split points, up); normally two
   passes. Cell borders are drawn inside the cells so that a row takes the
   same height at the end of a part as before a page break.
4. a figure that did not fit under the text before it and left that page largely empty is
   placed as a typesetter would (:func:`_figure_fix_at`): drawn smaller, to 85 % at least, when
   that fits; else the text after it flows before it. The decision is kept in the split points
   (``figure:<id>``); a figure is decided once, so the passes still end.

Which split points and figure entries a note gets is defined in document order
(:func:`_greedy_step`, the *canonical* ones): each table and figure is decided by those rules on
the layout where every earlier one is decided and no later one (later tables whole, later
figures unmoved). The passes of a build find them faster (:func:`_next_pass`): from none, every
table and the first figures at once (:func:`_next_splits`) until nothing changes; then, and from
a guess, :func:`_settle_step` walks the points of ONE layout in document order and proves each
(a table by running its own passes on a model of its rows read from that layout,
:func:`_table_verdict`; a figure by its rule read from that layout, moved or not,
:func:`_figure_verdict`), sets the first one it can disprove right (often from the same layout)
and goes on. The passes end only on a layout where every point is proved, i.e. on the
canonical split points, whatever they started from.

Split points are remembered per unsplit HTML (sha256), in the process and in the
cache folder (``<cache>/splits``), so laying out the same report again, in the
same process or in a later ``reportgen build``, takes one pass. Those of a similar
HTML (another variant of a class, a case with one length changed) are a guess for
:func:`_settle_step`, proved or set right there: the bytes do not depend on what was
remembered, and a right guess costs one pass.

What does not change between builds is kept in the same cache folder, each entry keyed by
everything it is made from, so a cached one gives the same bytes as a fresh one (tests/
test_html_caches.py): the subset faces of the screen HTML and the faces' code points
(``<cache>/fonts``), the compiled templates (``<cache>/jinja``); the formulas typeset as HTML
are kept by :mod:`reportgen.report.formulas` (``<cache>/mathhtml``). Within one build
(:func:`build_outputs`) the print parts and the screen HTML share the tables' cells, and the
text nodes fixed by the typography are remembered by the process.

A PDF is byte-identical from build to build: the subset fonts are stamped with
a fixed date (:func:`_fixed_font_timestamp`).
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import html as _html
import json
import logging
import math
import numbers as _numbers
import os
import re
import tempfile
import time
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import jinja2
from markupsafe import Markup, escape

from ..style import fonts
from .document import Column, Figure, FormulaBlock, Paragraph, Report, Section, Table
from .formulas import _cache_dir as _formula_cache_dir
from .formulas import Formula, data_uri, formula_images, inline_math, where_rows
from ..style.numbers import DASH, fmt

__all__ = [
    "DEFAULT_OPTIONS",
    "ESKD_MARGINS",
    "TEMPLATES_DIR",
    "resolve_options",
    "render_html",
    "render_fragment",
    "write_html",
    "write_pdf",
    "build_outputs",
    "RenderStats",
    "last_stats",
]

log = logging.getLogger(__name__)

TEMPLATES_DIR = Path(os.environ.get("REPORTGEN_TEMPLATES")
                     or Path(__file__).resolve().parents[2] / "templates")

# ГОСТ 7.32-2017 defaults; every key can be overridden by Report.options.
DEFAULT_OPTIONS: dict[str, Any] = {
    "margin_top_mm": 20.0,
    "margin_right_mm": 15.0,
    "margin_bottom_mm": 20.0,
    "margin_left_mm": 30.0,
    "font_size_pt": 14.0,
    "table_font_size_pt": 12.0,  # ГОСТ 7.32 allows a smaller size in tables
    "line_height": 1.5,
    "indent_mm": 12.5,
    "figure_word": "Рисунок",  # or «Рис.»
    "table_word": "Таблица",
    "continuation_words": "Продолжение таблицы",
    "dash": " — ",  # between number and caption; «.» gives «Рисунок 1.1. Схема»
    "eskd_frame": False,  # frame 20/5/5/5 mm and form-2a stamp after the title page
    "section_new_page": True,  # every level-1 section starts a page
    "toc_depth": 2,  # levels of headings listed in СОДЕРЖАНИЕ (1–3)
    "font": None,  # "Liberation Serif" | "STIXGeneral" | "DejaVu Serif" | None (auto)
    "title_page": True,
    "assignment_page": True,
    "assignment_title": "ЗАДАНИЕ",
    "toc_title": "СОДЕРЖАНИЕ",
    "introduction_title": "ВВЕДЕНИЕ",
    "conclusion_title": "ЗАКЛЮЧЕНИЕ",
    "references_title": "СПИСОК ИСПОЛЬЗОВАННЫХ ИСТОЧНИКОВ",
    "appendix_word": "ПРИЛОЖЕНИЕ",
    "note_word": "Примечание",
    "where_word": "где",
    "eq_number_width_mm": 18.0,
    "screen_max_width_px": 860,
}

# Margins used with the ЕСКД frame unless the options set them: text 5 mm inside
# the frame on the left and right, the 15 mm stamp in the bottom margin.
ESKD_MARGINS = {
    "margin_top_mm": 15.0,
    "margin_right_mm": 10.0,
    "margin_bottom_mm": 27.0,
    "margin_left_mm": 25.0,
}

# Letters of appendices (ГОСТ 7.32: no Ё, З, Й, О, Ч, Ъ, Ы, Ь).
APPENDIX_LETTERS = "АБВГДЕЖИКЛМНПРСТУФХЦШЩЭЮЯ"

PAGE_W_MM, PAGE_H_MM = 210.0, 297.0
PT_MM = 25.4 / 72

MAX_PASSES = 12
MIN_PART_ROWS = 3  # fewest rows of a table left on a page before «Продолжение таблицы»
LEAD_TABLE_ROWS = 6  # a paragraph before a one-part table of at most this many rows keeps with it (_blocks.html.j2)
# A figure that does not fit under the text before it (_figure_fixes) has an entry in the split
# points under this prefix and its id: [elements of the following text put before it, scale in ‰].
FIGURE_KEY = "figure:"
MIN_FIGURE_SCALE = 0.85  # a figure is drawn at least this large to fit the room left on a page
FIGURE_ROOM = 0.5  # a figure is placed anew only when it leaves more than this of the page before it empty


def resolve_options(options: dict | None) -> dict:
    """Defaults + overrides; unknown keys are an error (they are usually typos)."""
    from .safety import validate_options
    options = validate_options(options)  # types and ranges: CaseError
    o = dict(DEFAULT_OPTIONS)
    if options.get("eskd_frame"):
        o.update(ESKD_MARGINS)
    o.update(options)
    dash = str(o["dash"])
    if dash.strip() == ".":
        dash = ". "
    o["dash"] = dash
    o["text_width_mm"] = PAGE_W_MM - o["margin_left_mm"] - o["margin_right_mm"]
    o["text_height_mm"] = PAGE_H_MM - o["margin_top_mm"] - o["margin_bottom_mm"]
    # a landscape page is bound on its top edge: the portrait margins turned by 90° (left → top)
    o["landscape_text_width_mm"] = PAGE_H_MM - o["margin_top_mm"] - o["margin_bottom_mm"]
    o["landscape_text_height_mm"] = PAGE_W_MM - o["margin_left_mm"] - o["margin_right_mm"]
    o["toc_depth"] = max(1, min(3, int(o["toc_depth"])))
    return o


# ---------------------------------------------------------------- view model


@dataclass
class _Heading:
    kind: str  # "numbered" | "structural" | "appendix"
    level: int
    number: str
    title: Markup
    id: str
    new_page: bool = False


@dataclass
class _Part:
    caption: Markup
    continued: bool
    rows: list
    new_page: bool = False  # the table starts on a new page (too few rows fit)


@dataclass
class _TableView:
    id: str
    key: str  # id used for row anchors
    ncols: int
    header: list  # [(html, cls)]
    units: list | None
    parts: list
    note: Markup | None


@dataclass
class _FigureView:
    id: str
    src: str
    width_mm: float
    caption: Markup
    landscape: bool = False


@dataclass
class _EqView:
    id: str
    number: str
    lines: list
    where: list


@dataclass
class _Node:
    kind: str  # "section" | "p" | "raw" | "figure" | "table" | "formulas"
    item: Any = None
    children: list = field(default_factory=list)


_BLOCK_START = re.compile(r"^\s*<(ul|ol|div|table|p|figure|blockquote|dl)\b", re.I)
# a paragraph «где …» explaining the formula above it: kept on the formula's page
_WHERE_START = re.compile(r"^\s*где\s")


def _missing(v) -> bool:
    """None, NaN, pandas.NA / NaT: printed as an em dash."""
    if v is None:
        return True
    if isinstance(v, str):
        return False
    try:
        return bool(v != v)  # NaN; pandas.NA raises in bool()
    except TypeError:
        return True


def _is_number(v) -> bool:
    return isinstance(v, _numbers.Real) and not isinstance(v, bool)


def column_decimals(col: Column, values) -> int | None:
    """One number of decimals for a column printed to ``sig`` significant digits (ГОСТ 7.32,
    6.6.6: the numbers of a column are written to the same number of decimals): the decimals its
    largest value needs, e.g. 0,9455 / 5,014 / 10,03 → 0,946 / 5,014 / 10,030.  None for a column
    with its own ``digits`` or formatter, or of integers only (printed as they are)."""
    if col.fmt is not None or col.digits is not None or not col.sig:
        return None
    nums = [abs(float(v)) for v in values if _is_number(v) and not _missing(v)]
    if not nums or all(isinstance(v, _numbers.Integral) for v in values if _is_number(v)):
        return None
    big = max(nums)
    if 0 < big < 1e-9:          # rounding noise of an exact zero (a reaction 5,9·10⁻¹³ Н)
        return col.sig - 1
    if big == 0 or not math.isfinite(big) or big >= 1e6 or big < 1e-4:
        return None
    return max(0, col.sig - 1 - math.floor(math.log10(big)))


# id(table) -> (table, its cells) while build_outputs runs: the print parts and the screen
# HTML of one build format every cell once (see _cells_shared)
_SHARED_CELLS: dict | None = None


def _table_cells(tab: Table, make) -> tuple:
    """``make(tab)``, or what it gave for this very table earlier in the same build."""
    shared = _SHARED_CELLS
    if shared is None:
        return make(tab)
    hit = shared.get(id(tab))
    if hit is not None and hit[0] is tab:
        return hit[1]
    out = make(tab)
    shared[id(tab)] = (tab, out)
    return out


@contextlib.contextmanager
def _cells_shared():
    """Within: the cells of a table formatted once, for the print and the screen views alike
    (they differ in the row ids only, which are not kept)."""
    global _SHARED_CELLS
    before = _SHARED_CELLS
    _SHARED_CELLS = {} if before is None else before
    try:
        yield
    finally:
        _SHARED_CELLS = before


class _Builder:
    """Numbers the document and turns the model into template views."""

    def __init__(self, report: Report, opts: dict, *, for_print: bool,
                 splits: dict[str, list[int]] | None):
        self.report = report
        self.o = opts
        self.for_print = for_print
        self.splits = splits or {}
        self.targets: dict[str, str] = {}  # id -> reference text
        self.toc: list[dict] = []
        self.serial = 0
        self.prefix = ""
        self.counters = {"fig": 0, "tab": 0, "eq": 0}
        self.eq_max_em = (opts["text_width_mm"] - 2 * opts["eq_number_width_mm"]) / (
            opts["font_size_pt"] * PT_MM)
        self.tables: dict[str, int] = {}  # table key -> number of rows
        self.table_rows: dict[str, tuple] = {}  # table key -> (view, rows, caption, continuation)
        self.unnumbered = False  # blocks of the «Задание» page carry no numbers
        self._units_row = False
        self.figures: dict[str, tuple[_FigureView, float]] = {}  # figure id -> (view, width as made)
        self.figure_sections: list[tuple[_Node, list]] = []  # sections holding figures: (node, blocks as made)

    # -- numbering helpers
    def _register(self, target_id: str, text: str) -> None:
        if target_id in self.targets:
            raise ValueError(f"Идентификатор «{target_id}» встречается в отчёте дважды")
        self.targets[target_id] = text

    def _next(self, kind: str) -> str:
        if self.unnumbered:
            return ""
        self.counters[kind] += 1
        n = self.counters[kind]
        return f"{self.prefix}.{n}" if self.prefix else str(n)

    def _auto_id(self, kind: str) -> str:
        self.serial += 1
        return f"auto-{kind}-{self.serial}"

    def start_chapter(self, prefix: str) -> None:
        self.prefix = prefix
        self.counters = {k: 0 for k in self.counters}

    def caption(self, word_key: str, number: str, caption: str) -> Markup:
        if self.unnumbered:
            return Markup(caption)
        return Markup("{} {}{}").format(self.o[word_key], number, self.o["dash"]) + Markup(caption)

    # -- blocks
    def blocks(self, children) -> list[_Node]:
        out = []
        for child in children:
            if isinstance(child, Section):
                out.append(self.section(child, level=max(2, child.level)))
            elif isinstance(child, Paragraph):
                kind = "raw" if _BLOCK_START.match(child.html) else \
                    "where" if _WHERE_START.match(child.html) else "p"
                out.append(_Node(kind, Markup(child.html)))
            elif isinstance(child, str):
                out.append(_Node("p", Markup(child)))
            elif isinstance(child, Figure):
                out.append(_Node("figure", self.figure(child)))
            elif isinstance(child, Table):
                out.append(_Node("table", self.table(child)))
            elif isinstance(child, FormulaBlock):
                out.append(_Node("formulas", [self.formula(f) for f in child.formulas]))
            elif isinstance(child, Formula):
                out.append(_Node("formulas", [self.formula(child)]))
            else:
                raise TypeError(f"Unsupported report block: {type(child).__name__}")
        return out

    def section(self, sec: Section, parents: list | None = None,
                counter: list[int] | None = None, level: int | None = None) -> _Node:
        """A section with its heading; numbered «1», «1.2», «А.1» from ``parents``.

        A Section met among plain blocks (introduction, assignment) is an
        unnumbered subheading.
        """
        o = self.o
        in_body = counter is not None
        if not in_body:  # outside the numbered body
            parents, counter, numbered = [], [0], False
        else:
            numbered = sec.numbered
        level = level or sec.level
        if numbered:
            counter[0] += 1
            nums = list(parents) + [counter[0]]
            number = ".".join(str(n) for n in nums)
        else:
            nums = list(parents)
            number = ""
        if not sec.id:
            raise ValueError(f"У раздела «{sec.title}» нет идентификатора")
        if level == 1:
            self.start_chapter(number)
        self._register(sec.id, number or re.sub(r"<[^>]+>", "", sec.title))
        kind = "numbered" if number else ("structural" if level == 1 else "plain")
        if in_body and level <= o["toc_depth"] and (numbered or level == 1):
            self.toc.append({"level": level, "number": number, "title": Markup(sec.title),
                             "id": sec.id, "kind": kind})
        head = _Heading(kind, level, number, Markup(sec.title), sec.id,
                        level == 1 and o["section_new_page"])
        children = []
        sub_counter = [0]
        for child in sec.children:
            if isinstance(child, Section):
                if in_body and (numbered or level == 1):
                    children.append(self.section(child, nums, sub_counter, min(level + 1, 3)))
                else:
                    children.append(self.section(child, None, None, min(level + 1, 3)))
            else:
                children.extend(self.blocks([child]))
        node = _Node("section", head, children)
        if any(c.kind == "figure" for c in children):
            self.figure_sections.append((node, list(children)))
            node.children = _placed(children, self._figure_moves())
        return node

    def figure(self, fig: Figure) -> _FigureView:
        number = self._next("fig")
        fid = fig.id or self._auto_id("fig")
        self._register(fid, number)
        data = fig.svg
        if isinstance(data, (bytes, bytearray)) and data[:8] == b"\x89PNG\r\n\x1a\n":
            import base64

            src = "data:image/png;base64," + base64.b64encode(bytes(data)).decode("ascii")
        else:
            src = data_uri(data)
        limit = self.o["landscape_text_width_mm"] if fig.landscape and self.for_print else self.o["text_width_mm"]
        width = min(float(fig.width_mm), limit)
        view = _FigureView(fid, src, width, self.caption("figure_word", number, fig.caption),
                           fig.landscape and self.for_print)
        self.figures[fid] = (view, width)
        view.width_mm = width * _figure_entry(self.splits, fid)[1] / 1000
        return view

    def header_cell(self, col: Column) -> Markup:
        head = inline_math(col.header) if col.latex else Markup(col.header)
        if col.unit and not self._units_row:
            head = head + Markup(", ") + escape(col.unit)
        return head

    def _cells(self, tab: Table) -> tuple[list, list | None, list]:
        """The header, the units row (or None) and the cells of every row of a table: the same
        in the print and the screen HTML."""
        df = tab.data
        header = []
        units = [] if tab.units_row else None
        if tab.index_header is not None:
            header.append((Markup(tab.index_header), "idx"))
            if units is not None:
                units.append(Markup(""))
        for col in tab.columns:
            if col.key not in df.columns:
                raise KeyError(f"Таблица «{tab.caption}»: нет столбца «{col.key}» в данных")
            header.append((self.header_cell(col), ""))
            if units is not None:
                units.append(escape(col.unit or ""))
        body = []
        cols = [(c, df[c.key].tolist()) for c in tab.columns]
        cols = [(c if (k := column_decimals(c, vals)) is None else replace(c, digits=k),
                 vals) for c, vals in cols]
        index = list(df.index)
        for i in range(len(df)):
            cells = []
            if tab.index_header is not None:
                v = index[i]
                if tab.index_fmt is not None:
                    text = tab.index_fmt(v)
                elif _is_number(v):
                    text = fmt(v) if not float(v).is_integer() else fmt(int(v))
                else:
                    text = str(v)
                cells.append((escape(text), "idx"))
            for col, values in cols:
                v = values[i]
                if _missing(v):
                    cells.append((DASH, "num"))
                elif _is_number(v) or col.fmt is not None:
                    cells.append((escape(col.format(v)), "num" if _is_number(v) else "text"))
                else:
                    cells.append((escape(str(v)), "text"))
            body.append(cells)
        return header, units, body

    def table(self, tab: Table) -> _TableView:
        number = self._next("tab")
        tid = tab.id or self._auto_id("tab")
        self._register(tid, number)
        self._units_row = bool(tab.units_row)
        header, units, body = _table_cells(tab, self._cells)
        highlight = set(int(i) for i in tab.highlight_rows)
        rows = [{"id": f"{tid}__r{i}" if self.for_print else None,
                 "cls": "hl" if i in highlight else "",
                 "cells": cells} for i, cells in enumerate(body)]
        self.tables[tid] = len(rows)
        note = None
        if tab.note:
            note = Markup("{}{}").format(self.o["note_word"], " — ") + Markup(tab.note)
        view = _TableView(tid, tid, len(header), header, units, [], note)
        self.table_rows[tid] = (view, rows, self.caption("table_word", number, tab.caption),
                                Markup("{} {}").format(self.o["continuation_words"], number))
        self._cut(tid)
        return view

    def _cut(self, tid: str) -> None:
        """The parts of table ``tid`` at its split points (``self.splits``)."""
        view, rows, caption, continued = self.table_rows[tid]
        cuts = [0] + sorted(s for s in set(self.splits.get(tid, ())) if 0 < s < len(rows))
        parts = []
        for k, start in enumerate(cuts):
            end = cuts[k + 1] if k + 1 < len(cuts) else len(rows)
            parts.append(_Part(caption if k == 0 else continued, k > 0, rows[start:end],
                               k == 0 and 0 in self.splits.get(tid, ())))
        view.parts = parts

    def resplit(self, splits: dict[str, list[int]] | None) -> None:
        """Cut every table at other split points: the views are those of a builder made with
        ``splits`` (the numbering and the rows do not depend on them)."""
        self.splits = splits or {}
        for tid in self.table_rows:
            self._cut(tid)
        for fid, (view, width) in self.figures.items():
            view.width_mm = width * _figure_entry(self.splits, fid)[1] / 1000
        moves = self._figure_moves()
        for node, made in self.figure_sections:
            node.children = _placed(made, moves)

    def _figure_moves(self) -> dict[str, int]:
        """Figure id -> how many elements after it are put before it (:func:`_figure_fixes`)."""
        return {fid: n for fid in self.figures if (n := _figure_entry(self.splits, fid)[0])}

    def formula(self, f) -> _EqView:
        n = self._next("eq")
        number = f"({n})" if n else ""
        eid = f.label or self._auto_id("eq")
        self._register(eid, number)
        lines = formula_images(f, self.eq_max_em)
        return _EqView(eid, number, lines, where_rows(f))


def _figure_entry(splits: dict, fid: str) -> tuple[int, int]:
    """``(elements moved before the figure, scale in ‰)`` of figure ``fid`` in the split points
    (:data:`FIGURE_KEY`; ``(0, 1000)`` when it has no entry)."""
    entry = splits.get(FIGURE_KEY + fid)
    if not entry or len(entry) != 2:
        return 0, 1000
    # (a remembered entry is clamped to what _figure_fixes gives: never smaller than 85 %)
    return max(0, int(entry[0])), min(1000, max(int(MIN_FIGURE_SCALE * 1000), int(entry[1])))


def _elements(node: _Node) -> int | None:
    """How many top-level elements the template makes of a block (``_blocks.html.j2``): one
    paragraph or table, a formula and its «где» table; ``None`` for what a figure is never moved
    past (a section, another figure, raw HTML)."""
    if node.kind in ("p", "where", "table"):
        return 1
    if node.kind == "formulas":
        return sum(1 + bool(e.where) for e in node.item)
    return None


def _placed(blocks: list, moves: dict[str, int]) -> list:
    """``blocks`` with each figure of ``moves`` put after the number of elements it names (the text
    that follows a figure flows before it: :func:`_figure_fixes`), never past a section, another
    figure or raw HTML. Numbers are not changed (they were given in the order made)."""
    out: list = []
    held, left = None, 0
    for node in blocks:
        if held is not None:
            size = _elements(node)
            if size is None or size > left:
                out.append(held)
                held = None
            else:
                out.append(node)
                left -= size
                if left == 0:
                    out.append(held)
                    held = None
                continue
        if node.kind == "figure" and moves.get(node.item.id):
            held, left = node, moves[node.item.id]
            continue
        out.append(node)
    if held is not None:
        out.append(held)
    return out


def _walk(builder: _Builder, report: Report):
    """Number headings and blocks in document order; return the body views."""
    o = builder.o
    body = []

    def structural(key: str, hid: str, children, toc=True):
        builder.start_chapter("")
        title = o[key]
        builder._register(hid, title)
        if toc:
            builder.toc.append({"level": 1, "number": "", "title": Markup(escape(title)),
                                "id": hid, "kind": "structural"})
        head = _Heading("structural", 1, "", Markup(escape(title)), hid, True)
        return _Node("section", head, builder.blocks(children) if children else [])

    intro = structural("introduction_title", "introduction", report.introduction) \
        if report.introduction else None
    if intro:
        body.append(intro)
    counter = [0]
    for sec in report.sections:
        body.append(builder.section(sec, [], counter, 1))
    if report.conclusion:
        body.append(structural("conclusion_title", "conclusion", report.conclusion))
    if report.references:
        builder.start_chapter("")
        hid = "references"
        builder._register(hid, o["references_title"])
        builder.toc.append({"level": 1, "number": "", "title": Markup(escape(o["references_title"])),
                            "id": hid, "kind": "structural"})
        head = _Heading("structural", 1, "", Markup(escape(o["references_title"])), hid, True)
        items = [{"number": str(i + 1), "text": escape(t)} for i, t in enumerate(report.references)]
        body.append(_Node("references", head, items))
    for i, app in enumerate(report.appendices or ()):
        if i >= len(APPENDIX_LETTERS):
            raise ValueError("Слишком много приложений")
        letter = APPENDIX_LETTERS[i]
        builder.start_chapter(letter)
        builder._register(app.id, letter)
        word = f"{o['appendix_word']} {letter}"
        builder.toc.append({"level": 1, "number": "", "title": Markup("{} {}").format(
            o["appendix_word"].capitalize() + " " + letter, Markup(app.title)),
            "id": app.id, "kind": "appendix"})
        head = _Heading("appendix", 1, word, Markup(app.title), app.id, True)
        children = []
        sub_counter = [0]
        for child in app.children:
            if isinstance(child, Section):
                children.append(builder.section(child, [letter], sub_counter, 2))  # «А.1»
            else:
                children.extend(builder.blocks([child]))
        body.append(_Node("section", head, children))
    return body


# ---------------------------------------------------------------- templates


def _bytecode_cache() -> jinja2.BytecodeCache | None:
    """The compiled templates kept in the cache folder (``<cache>/jinja``), so a fresh process
    does not compile them again (part of the first-call figures of ``bench/bench_html.py``). Jinja checks an entry against the template's
    source and the Python version, so a stale one is compiled again; none when the cache is
    off or its folder cannot be made."""
    folder = _formula_cache_dir()
    if folder is None:
        return None
    folder = folder.parent / "jinja"
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return _BytecodeCache(str(folder))


class _BytecodeCache(jinja2.FileSystemBytecodeCache):
    """Jinja's cache of compiled templates in a folder (atomic writes; an entry that does not
    match the source is compiled again), which a read-only folder does not fail."""

    def dump_bytecode(self, bucket) -> None:
        try:
            super().dump_bytecode(bucket)
        except OSError:
            pass  # a read-only cache folder is no reason to fail a report


def _env() -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(TEMPLATES_DIR)),
        bytecode_cache=_bytecode_cache(),
        autoescape=jinja2.select_autoescape(["html", "j2"], default_for_string=True),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
    )
    env.filters["mm"] = lambda v: f"{float(v):.2f}".rstrip("0").rstrip(".") + "mm"
    env.filters["num"] = lambda v: f"{float(v):.3f}".rstrip("0").rstrip(".")
    env.filters["last_word"] = last_word
    return env


_VOID_TAGS = frozenset("area base br col embed hr img input link meta source track wbr".split())


def last_word(html) -> tuple[Markup, Markup]:
    """``(head, tail)`` of a title's HTML split at its last space outside any element: the
    contents keep the tail, the leader dots and the page number on one line (ГОСТ 7.32: a long
    title wraps, its dots and number stay on its last line); ``head`` ends with the space."""
    html = escape(html)          # a plain string is text; Markup stays as it is
    parts = _TAG_SPLIT.split(str(html))
    depth, cut = 0, None
    for n, part in enumerate(parts):
        if part.startswith("<"):
            name = part[1:].lstrip("/").split(None, 1)[0].rstrip("/>").lower() if len(part) > 2 else ""
            if part.startswith("</"):
                depth -= 1
            elif name not in _VOID_TAGS and not part.endswith("/>"):
                depth += 1
        elif depth == 0 and " " in part:
            cut = (n, part.rindex(" ") + 1)
    if cut is None:
        return Markup(""), html
    n, k = cut
    return Markup("".join(parts[:n]) + parts[n][:k]), Markup(parts[n][k:] + "".join(parts[n + 1:]))


_ENV: jinja2.Environment | None = None


def _get_env() -> jinja2.Environment:
    global _ENV
    if _ENV is None:
        _ENV = _env()
    return _ENV


_REF = re.compile(r'<a class="ref" href="#([^"]+)"></a>')
# (a pattern that starts with a literal is found by a fast scan; the word character before the
# space is checked in the replacement)
_REF_AFTER_WORD = re.compile(r' <a class="ref" href="#([^"]+)">')
_WORD_CHAR = re.compile(r"\w")
# a data: URL (an image or an embedded font) and its stand-in while the text is processed
_DATA_URL = re.compile(r"data:[^\"')\s<>]+")
_STASHED = re.compile("\x00(\\d+)\x00")
_TAG_SPLIT = re.compile(r"(<[^>]*>)")
_SUP_RUN = re.compile(r"[⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺]+")
_NB = r"(?:&nbsp;|&#160;|\u00a0)"
# «65&nbsp;об/мин» (browsers and WeasyPrint break after «/»)
_UNIT_SLASH = re.compile(r"([^\s<>]+)(" + _NB + r")([^\s<>&/]+/[^\s<>&]+)")
_UNIT_SLASH_BARE = re.compile(r"(" + _NB + r"[^\s<>&/]+/[^\s<>&]+)")
_NBSP_BEFORE_IMG = re.compile(_NB + r"(<img\b[^>]*>)")
_NBSP_BEFORE_TAG = re.compile(_NB + r"(<(?:a|span|i|b|em|strong)\b[^>]*>)")
# a compound unit («Н·м», «кг·м²», «Н·с/м») with the number before it, and initials with the
# surname («Н. И. Мерцалов», «Мерцалов Н. И.»): never broken across lines
_UNIT_DOT = re.compile(r"(?:[-−+]?\d[\d,.]*(?:" + _NB + r"|\s))?[A-Za-zА-Яа-яЁё]+(?:²|³)?(?:·[A-Za-zА-Яа-яЁё]+(?:²|³)?)+")
_NUM_UNIT = re.compile(r"(\d) (?=(?:Н·мм|Н·м|Н/мм|Н|кг·м²|кг/м³|кг|мм|м/мм|м/с²|м/с|м|рад/с²|рад/с|рад|об/мин|"
                       r"Дж|МПа|кПа|Па|кВт|Вт|с|%|°)(?![\wА-Яа-яЁё]))")
_EQ_NUMBER = re.compile(r"(?:(?<=\S)|^) = (?=[−\-]?\d)")     # «μF = 200»: never «μF =» | «200» on two lines
_INITIALS = re.compile(r"\b([А-ЯЁ]\.)(?!\d)[ \u00a0]?([А-ЯЁ]\.)?[ \u00a0]([А-ЯЁ][а-яё]+)"
                       r"|\b([А-ЯЁ][а-яё]+)[ \u00a0]([А-ЯЁ]\.)(?![\dа-яё])[ \u00a0]?([А-ЯЁ]\.)?(?![\dа-яё])")
_SUP_PLAIN = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺", "0123456789\u2212+")


def _fill_refs(html: str, targets: dict[str, str]) -> str:
    missing = []

    def repl(m):
        tid = m.group(1)
        if tid not in targets:
            missing.append(tid)
            return m.group(0)
        return f'<a class="ref" href="#{tid}">{_html.escape(targets[tid])}</a>'

    out = _REF.sub(repl, html)

    # «в таблице 1.1»: a no-break space between the word and the number, as the
    # first character of the link (see _typography for why not before it)
    def after_word(m):
        i = m.start()
        if i and _WORD_CHAR.match(out, i - 1):
            return f'<a class="ref" href="#{m.group(1)}">&#160;'
        return m.group(0)

    out = _REF_AFTER_WORD.sub(after_word, out)
    if missing:
        raise KeyError("Ссылки на несуществующие объекты: " + ", ".join(sorted(set(missing))))
    return out


def _stash_data_urls(html: str) -> tuple[str, list[str]]:
    """``data:`` URLs (images, embedded fonts: most of the bytes of a note) replaced by short
    stand-ins while references and typography are processed, which look at the text only:
    their regular expressions then scan a tenth of the bytes. Nothing is stashed when the
    HTML holds the stand-in's NUL character already."""
    if "\x00" in html:
        return html, []
    urls: list[str] = []

    def stash(m):
        urls.append(m.group(0))
        return f"\x00{len(urls) - 1}\x00"

    return _DATA_URL.sub(stash, html), urls


def _restore_data_urls(html: str, urls: list[str]) -> str:
    return _STASHED.sub(lambda m: urls[int(m.group(1))], html) if urls else html


def _sup(m: re.Match) -> str:
    run = m.group(0)
    if set(run) <= set("¹²³"):
        return run
    return "<sup>" + run.translate(_SUP_PLAIN) + "</sup>"


# every fix below needs one of these characters (a space, a no-break space or entity, «·», the
# full stop of initials, a superscript): a text node without them (a number) is left as it is
_FIXABLE = re.compile("[ \u00a0&·.⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺]")


def _fix_text(text: str) -> str:
    """The fixes of :func:`_typography` in one text node (a pure function of the text)."""
    if not _FIXABLE.search(text):
        return text
    text = _NUM_UNIT.sub("\\1\u00a0", text)   # «8 мм» written with a plain space
    if text.startswith(" —"):   # a dash after a symbol never starts a line («<i>ω</i> — угловая скорость»)
        text = "\u00a0" + text[1:]
    text = _EQ_NUMBER.sub("\u00a0=\u00a0", text)
    text = _UNIT_SLASH.sub(r'<span class="nobr">\1 \3</span>', text)
    text = _UNIT_SLASH_BARE.sub(r'<span class="nobr">\1</span>', text)
    text = _UNIT_DOT.sub(lambda m: '<span class="nobr">' + re.sub(r"\s", "\u00a0", m.group(0)) + "</span>"
                         if "<span" not in m.group(0) else m.group(0), text)
    text = _INITIALS.sub(lambda m: re.sub(r"\s", "\u00a0", m.group(0)), text)
    return _SUP_RUN.sub(_sup, text)


# text node → its fixed text: a note is rendered several times (the print parts before and
# after their split points are known, the screen HTML), with the same text nodes each time
_FIXED_TEXT: dict[str, str] = {}
_FIXED_TEXT_MAX = 200_000


def _typography(html: str) -> str:
    """Typographic fixes in text nodes.

    * Unicode superscripts not in Latin-1 (⁰ ⁴…⁹ ⁻ ⁺, absent from Liberation
      Serif) become ``<sup>``, so that no fallback font is needed;
    * a unit with a slash after a number and a no-break space («65 об/мин»)
      is kept on one line (browsers and WeasyPrint break after «/»);
    * a no-break space before an inline element becomes a nowrap span
      (works around a WeasyPrint 70 line-breaking bug, see below).
    """
    fixed = _FIXED_TEXT
    if len(fixed) > _FIXED_TEXT_MAX:
        fixed.clear()

    # A no-break space right before an inline element («=&nbsp;<img>»,
    # «таблицы&nbsp;<a>») makes WeasyPrint 70 break lines wrongly: it
    # hyphenates the first word of the paragraph instead. The same space as the
    # first character inside the element is laid out correctly.
    html = _NBSP_BEFORE_IMG.sub(r'<span class="nb">&#160;\1</span>', html)
    html = _NBSP_BEFORE_TAG.sub(r'\1&#160;', html)

    pieces = _TAG_SPLIT.split(html)
    in_style = False
    for i, piece in enumerate(pieces):
        if i % 2 == 1:  # a tag
            low = piece.lower()
            if low.startswith(("<style", "<title")):
                in_style = True  # raw text elements: no markup inside
            elif low.startswith(("</style", "</title")):
                in_style = False
            continue
        if not in_style and piece:
            text = fixed.get(piece)
            if text is None:
                text = fixed[piece] = _fix_text(piece)
            pieces[i] = text
    return "".join(pieces)


def _visible_text(html: str) -> str:
    html = re.sub(r"<style.*?</style>", " ", html, flags=re.S | re.I)
    html = re.sub(r"<[^>]*>", " ", html)
    return _html.unescape(html)


def _check_glyphs(html: str, family: fonts.FontFamily) -> None:
    # (the set of characters: the check looks at each character once, whatever the length)
    missing = fonts.check_text("".join(set(_visible_text(html))), family, cmap=_font_cmap)
    if missing:
        chars = " ".join(f"{c} (U+{ord(c):04X})" for c in missing)
        warnings.warn(f"В шрифте «{family.name}» нет символов: {chars}; они будут "
                      f"взяты из другого шрифта", RuntimeWarning, stacklevel=3)


def _frame_svg() -> str:
    """The ЕСКД frame (ГОСТ 2.104): 20 mm from the left edge, 5 mm elsewhere."""
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="210mm" height="297mm" '
            'viewBox="0 0 210 297"><rect x="20" y="5" width="185" height="287" '
            'fill="none" stroke="#000" stroke-width="0.6"/></svg>')


@dataclass
class _Views:
    """A report numbered and turned into views once: the whole document, its front matter
    (title page, assignment, contents) or one top-level body node can be rendered from it."""

    opts: dict
    family: Any
    builder: _Builder
    ctx: dict

    def html(self, *, front: bool = True, body: list | None = None,
             toc_pages: dict | None = None, chunk: bool = False,
             head: bool = True, toc: bool = True) -> str:
        """The HTML of the front matter (``front``) followed by ``body`` (default: the whole
        body). ``toc_pages``: the contents' page numbers as text (a document laid out in parts,
        where ``target-counter`` cannot see the headings); ``chunk``: a body part laid out on
        its own (no page number in its footer: the joined PDF gets the numbers afterwards).
        ``head`` (title page and assignment) and ``toc`` (СОДЕРЖАНИЕ) choose the pieces of the
        front matter (laid out apart in parts: the contents only once the page numbers are
        known)."""
        env = _get_env()
        ctx = dict(self.ctx)
        css_ctx = dict(ctx.pop("css_ctx"), chunk=chunk)
        if not front or not head:
            ctx.update(title_page=False, show_assignment=False)
        ctx["show_toc"] = front and toc
        css = env.get_template("gost.css" if ctx["for_print"] else "screen.css").render(**css_ctx)
        ctx.update(css=Markup(css), front=front, toc_pages=toc_pages,
                   body=ctx["body"] if body is None else body)
        html = env.get_template("base.html.j2").render(**ctx)
        html, urls = _stash_data_urls(html)
        html = _fill_refs(html, self.builder.targets)
        return _restore_data_urls(_typography(html), urls)


_WOFF_CACHE_VERSION = 1
_WOFF_MEMO: dict[Path, bytes] = {}


def _woff_key(path: Path) -> str:
    """Key of a font's subset: the font file's bytes, the code and ranges that subset it, and
    the fontTools version that does."""
    import inspect

    import fontTools

    h = hashlib.sha256(f"{_WOFF_CACHE_VERSION}|{fontTools.version}|{fonts._SUBSET_RANGES!r}|".encode())
    h.update(inspect.getsource(fonts._subset_woff).encode("utf-8"))
    h.update(Path(path).read_bytes())
    return h.hexdigest()


def _is_woff(data: bytes) -> bool:
    """A whole WOFF file: its signature, and the length its header gives."""
    return len(data) >= 44 and data[:4] == b"wOFF" and int.from_bytes(data[8:12], "big") == len(data)


def _font_derived(memo: dict, path: Path, suffix: str, key, compute, decode, encode):
    """``compute(path)`` for a font file, kept in ``memo`` and in the cache folder as
    ``<cache>/fonts/<key(path)><suffix>`` (``encode``d; ``decode`` gives ``None`` for a damaged
    file, which is computed again)."""
    path = Path(path)
    value = memo.get(path)
    if value is not None:
        return value
    folder = _formula_cache_dir()
    file = None
    if folder is not None:
        try:
            file = folder.parent / "fonts" / f"{key(path)}{suffix}"
            value = decode(file.read_bytes())
        except (OSError, ValueError):
            value = None
    if value is None:
        value = compute(path)
        if file is not None:
            try:
                _atomic_write(file, encode(value))
            except OSError:
                pass  # a read-only cache folder is no reason to fail a report
    memo[path] = value
    return value


def _embedded_woff(path: Path) -> bytes:
    """:func:`reportgen.style.fonts._subset_woff` of a face of the screen HTML, kept in the
    process and in the cache folder (``<cache>/fonts``): subsetting the faces costs about a
    second of CPU, the same bytes every time (the subsetter is deterministic), so the screen
    HTML is the same with a cached subset as without."""
    return _font_derived(_WOFF_MEMO, path, ".woff", _woff_key, fonts._subset_woff,
                         lambda data: data if _is_woff(data) else None, bytes)


_CMAP_MEMO: dict[Path, frozenset] = {}


def _cmap_key(path: Path) -> str:
    return hashlib.sha256(f"cmap|{_WOFF_CACHE_VERSION}|".encode() + Path(path).read_bytes()).hexdigest()


def _cmap_decode(data: bytes) -> frozenset[int] | None:
    codes = json.loads(data.decode("ascii"))
    ok = isinstance(codes, list) and codes and all(isinstance(c, int) for c in codes)
    return frozenset(codes) if ok else None


def _font_cmap(path: Path) -> frozenset[int]:
    """:func:`reportgen.style.fonts._cmap` (the code points a face draws, for the glyph check)
    kept in the process and in the cache folder (``<cache>/fonts``, keyed by the font's bytes):
    a fresh process then need not import fontTools and parse the font."""
    return _font_derived(_CMAP_MEMO, path, ".cmap.json", _cmap_key, fonts._cmap, _cmap_decode,
                         lambda codes: json.dumps(sorted(codes)).encode("ascii"))


@functools.lru_cache(maxsize=8)
def _font_css(family, embed: bool) -> str:
    """The ``@font-face`` rules of the note (``embed``: the subset faces as ``data:`` URLs)."""
    return fonts.font_face_css(family, embed=embed, woff=_embedded_woff)


def warm_caches() -> None:
    """Fill the cache folder with what the HTML of every build reads from it (``reportgen
    warmup``, a batch worker's start): the compiled templates, the subset faces of the screen
    HTML and the faces' code points. Nothing when the cache is off."""
    if _formula_cache_dir() is None:
        return
    env = _get_env()
    for name in env.list_templates(filter_func=lambda n: n.endswith((".j2", ".css"))):
        env.get_template(name)
    family = fonts.find_serif()
    _font_css(family, True)
    for fam in (family, fonts.symbol_family()):
        if fam is not None:
            _font_cmap(fam.regular)


def _views(report: Report, *, for_print: bool, splits=None) -> _Views:
    opts = resolve_options(report.options)
    family = fonts.find_serif(opts["font"])
    builder = _Builder(report, opts, for_print=for_print, splits=splits)
    title_on = opts["title_page"]
    assignment = []
    if opts["assignment_page"]:
        builder.unnumbered = True
        assignment = builder.blocks(report.assignment)
        builder.unnumbered = False
    body = _walk(builder, report)
    meta = {k: ("" if v is None else v) for k, v in (report.meta or {}).items()}
    css_ctx = {"o": opts, "for_print": for_print, "family": fonts.CSS_FAMILY,
               "frame_uri": data_uri(_frame_svg()) if opts["eskd_frame"] else "", "chunk": False}
    ctx = {
        "o": opts,
        "meta": meta,
        "for_print": for_print,
        "font_css": Markup(_font_css(family, not for_print)),
        "css_ctx": css_ctx,
        "title_page": title_on,
        "assignment": assignment,
        "show_assignment": opts["assignment_page"] and (bool(assignment) or bool(meta)),
        "toc": builder.toc,
        "body": body,
        "eskd": bool(opts["eskd_frame"]) and for_print,
    }
    return _Views(opts, family, builder, ctx)


def _checked_html(views: _Views) -> str:
    """The whole document of ``views``, its characters checked against the fonts."""
    html = views.html()
    _check_glyphs(html, views.family)
    return html


def _render(report: Report, *, for_print: bool, splits=None) -> tuple[str, _Builder]:
    views = _views(report, for_print=for_print, splits=splits)
    return _checked_html(views), views.builder


def render_html(report: Report, *, for_print: bool) -> str:
    """The report as one HTML string.

    ``for_print=True``: the WeasyPrint flavour (ГОСТ print stylesheet, fonts by
    ``file://`` URL, tables whole: :func:`write_pdf` splits them).
    ``for_print=False``: self-contained screen HTML (fonts and images as
    ``data:`` URLs, no external references).
    """
    return _render(report, for_print=for_print)[0]


def render_fragment(block, *, options: dict | None = None, chapter: str = "1",
                    for_print: bool = False) -> str:
    """HTML of a single block (Table, Figure, FormulaBlock, Paragraph) numbered as
    the first of its kind in chapter ``chapter``: for previews and snapshot tests."""
    opts = resolve_options(options)
    dummy = Report(meta={}, assignment=[], introduction=[], sections=[], conclusion=[],
                   references=[], options=options or {})
    builder = _Builder(dummy, opts, for_print=for_print, splits=None)
    builder.start_chapter(chapter)
    nodes = builder.blocks([block])
    env = _get_env()
    module = env.get_template("_blocks.html.j2").make_module({"o": opts, "for_print": for_print})
    html = module.render_nodes(nodes)
    html = _fill_refs(str(html), builder.targets)
    return _typography(html)


# ---------------------------------------------------------------- writers


def _atomic_write(path: Path, data: bytes) -> Path:
    """``data`` to ``path`` through a temporary file renamed over it; a path that exists and is
    not a regular file (``/dev/null``, a pipe) is written in place: a rename would replace the
    device itself."""
    path = Path(path)
    if path.exists() and not path.is_file():
        with open(path, "wb") as fh:
            fh.write(data)
        return path
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    return path


def write_html(report: Report, path) -> Path:
    """Write the self-contained screen HTML atomically."""
    html = render_html(report, for_print=False)
    return _atomic_write(Path(path), html.encode("utf-8"))


@dataclass
class RenderStats:
    passes: int = 0
    pages: int = 0
    seconds_html: float = 0.0
    seconds_layout: float = 0.0
    seconds_pdf: float = 0.0
    splits: dict = field(default_factory=dict)
    parts: Any = None  # parallel.PartsStats of a note laid out in parts


last_stats = RenderStats()


class _QuietFontTools(logging.Filter):
    """Drop WeasyPrint's notice about using fontTools instead of HarfBuzz-Subset, and its
    error about a link to an anchor outside the document: a part of a note laid out alone
    (:mod:`reportgen.report.parallel`) links to the other parts, and those links are made
    when the parts are joined (an unknown reference is an error before any layout)."""

    def filter(self, record):  # pragma: no cover - depends on the host libraries
        msg = record.getMessage()
        return "HarfBuzz-Subset" not in msg and not msg.startswith("No anchor #")


def _quiet_weasyprint() -> None:
    wlog = logging.getLogger("weasyprint")
    if not any(isinstance(f, _QuietFontTools) for f in wlog.filters):
        wlog.addFilter(_QuietFontTools())


_ROW_ANCHOR = re.compile(r"^(.+)__r(\d+)$")
_SPLIT_MEMO: dict[str, dict[str, list[int]]] = {}  # sha256 of the unsplit print HTML -> splits


_SPLIT_CACHE_VERSION = 5  # 2: only the split points of the passes from none are remembered; 4: figure entries;
# 5: the canonical (greedy, document-order) split points of _greedy_step


_DATA_SVG = re.compile(r"data:image/svg\+xml;base64,([A-Za-z0-9+/=]+)")
_SVG_ROOT = re.compile(rb"<svg\b[^>]*>")
_SVG_SIZE = re.compile(rb'\s(width|height|viewBox)="([^"]*)"')


def _svg_size(m: re.Match) -> str:
    """An SVG image in the key by what the layout reads of it: its root's width, height
    and viewBox (the drawing inside does not move a line of the page)."""
    import base64

    root = _SVG_ROOT.search(base64.b64decode(m.group(1)))
    size = dict(_SVG_SIZE.findall(root.group(0))) if root else {}
    return "svg:" + "|".join(size.get(k, b"").decode("ascii", "replace")
                             for k in (b"width", b"height", b"viewBox"))


def weasyprint_version() -> str:
    """The installed WeasyPrint's version, read from its package metadata: a process that
    does not lay anything out (the CLI's parent with early workers) need not import it."""
    from importlib import metadata

    try:
        return metadata.version("weasyprint")
    except metadata.PackageNotFoundError:  # pragma: no cover - a source checkout on sys.path
        import weasyprint

        return weasyprint.__version__


def _split_key(html: str) -> str:
    """Key of the split points: the unsplit print HTML (it names the font files) with every
    SVG image reduced to its size, and the WeasyPrint version (which lays it out)."""
    h = hashlib.sha256(f"{_SPLIT_CACHE_VERSION}|{weasyprint_version()}|".encode())
    h.update(_DATA_SVG.sub(_svg_size, html).encode("utf-8"))
    return h.hexdigest()


_SHAPE_DROP = re.compile(r"data:[^\"')\s]+|<title>[^<]*</title>|<meta [^>]*>")
_NUMBER = re.compile("[\u2212+\\-]?\\d[\\d\u00a0\u2009\u202f ,.]*")  # sign, digits, groups, decimals


def _shape_key(html: str) -> str:
    """Key of a *guess* of the split points: the print HTML with every ``data:`` URL (figures,
    formulas), the title and the ``<meta>`` tags (the student's name) left out and every number
    (its sign, digit groups and decimals) written as ``0``, so the variants of one case (other
    numbers, the same tables) and a student's case after a changed length share it. Split
    points found under it are only a guess: :func:`_settle_step` decides whether a layout
    made with them is the one the passes from no split points give."""
    h = hashlib.sha256(f"shape|{_SPLIT_CACHE_VERSION}|{weasyprint_version()}|".encode())
    h.update(_NUMBER.sub("0", _SHAPE_DROP.sub("data:", html)).encode("utf-8"))
    return h.hexdigest()


_SKELETON = re.compile(r"<(?:h[1-6]|figure|tr)\b[^>]*\bid=\"[^\"]*\"[^>]*>")


def _skeleton_key(html: str) -> str:
    """Key of a coarser guess of the split points: the headings, figures (with their classes:
    a landscape one has a page of its own) and tables (their caption rows) of the print HTML, by
    id and in order, whatever the text between them. A variant whose text differs from the
    notes built before (a paragraph more, a figure drawn on a portrait page) takes the split
    points of one with the same sequence: the first variant of a class from its base case, a
    note from a neighbour with a sentence more. Only a guess, checked as the shape key's is."""
    h = hashlib.sha256(f"skeleton|{_SPLIT_CACHE_VERSION}|{weasyprint_version()}|".encode())
    h.update("".join(_SKELETON.findall(html)).encode("utf-8"))
    return h.hexdigest()


def _split_file(key: str) -> Path | None:
    """``<cache>/splits/<key>.json`` in the cache folder of the formulas (REPORTGEN_CACHE or
    XDG_CACHE_HOME/reportgen; none when the cache is off)."""
    d = _formula_cache_dir()
    return None if d is None else d.parent / "splits" / f"{key}.json"


def _recall_splits(key: str) -> dict[str, list[int]] | None:
    """Split points found for this HTML before, in this process or (the CLI) an earlier one.

    They only save layout passes. Only the split points the passes from none gave are
    remembered (:func:`_start_splits`), so an entry under the exact key is that result and its
    layout is a fixed point; one that is not (stale, damaged) is dropped and the passes start
    from none: a pass lost, never a different page."""
    known = _SPLIT_MEMO.get(key)
    if known is None:
        path = _split_file(key)
        try:
            data = json.loads(path.read_text(encoding="utf-8")) if path else None
        except (OSError, ValueError):
            data = None
        if isinstance(data, dict) and all(
                isinstance(v, list) and all(isinstance(i, int) for i in v) for v in data.values()):
            known = data
    return {k: list(v) for k, v in known.items()} if known else None


def _remember_splits(key: str, splits: dict[str, list[int]]) -> None:
    if len(_SPLIT_MEMO) >= 64:
        _SPLIT_MEMO.pop(next(iter(_SPLIT_MEMO)))
    _SPLIT_MEMO[key] = {k: list(v) for k, v in splits.items()}
    path = _split_file(key)
    if path is None:
        return
    try:
        _atomic_write(path, json.dumps(_SPLIT_MEMO[key], sort_keys=True).encode("utf-8"))
    except OSError:
        pass  # a read-only cache folder is no reason to fail a report


def _start_splits(html: str) -> tuple[str, tuple[str, ...], dict[str, list[int]], str]:
    """``(key, guesses, splits, start)`` for the unsplit print HTML of a note or part: the split
    points remembered under its exact key (``start`` "known"), else those of a similar HTML
    under its shape key (:func:`_shape_key`) or, failing that, its skeleton key
    (:func:`_skeleton_key`; ``start`` "guess"), else none (""). ``guesses``: the keys the result
    is remembered under as a guess. A known start is kept when its layout is a fixed point of
    :func:`_next_splits`, a guess only when :func:`_settle_step` proves it or sets it right
    (:func:`_next_pass`)."""
    key, guesses = _split_key(html), (_shape_key(html), _skeleton_key(html))
    known = _recall_splits(key)
    if known:
        return key, guesses, known, "known"
    guess = next((g for g in map(_recall_splits, guesses) if g), None)
    return key, guesses, guess or {}, "guess" if guess else ""


COLD_PASSES = 6  # passes from none that change every point at once before the checked ones


def _next_pass(document, splits: dict[str, list[int]], start: str, state: dict):
    """``(split points of the next pass or None when these are final, start)`` after a layout
    made with ``splits``. A ``start`` "known" (remembered for this very HTML, written only by
    the canonical passes) is kept when no rule asks for a change (:func:`_greedy_step`), else
    dropped (the passes start from none: a pass lost, never a different page). From none, the
    passes of :func:`_next_splits` (every table and the first figures at once: a guess, as fast
    as before) go on until they stop, at most :data:`COLD_PASSES`; then, and from a guess
    (``start`` "guess"), the fast passes of :func:`_settle_step`, which end only on the
    canonical split points (:func:`_greedy_step`), whatever the start: the bytes do not depend
    on it."""
    if start == "known":
        if _greedy_step(document, splits) is None:
            return None, start
        state.clear()
        return {}, ""
    if not start and state.get("cold", 0) < COLD_PASSES:
        # from none: the rules change every point at once (_next_splits), which mostly reaches
        # the canonical split points in fewest passes; where it stops, the fast passes check it
        state["cold"] = state.get("cold", 0) + 1
        new = _next_splits(document, splits)
        if new is not None:
            return new, start
        state["cold"] = COLD_PASSES
    return _settle_step(document, splits, state), start


def _remember_result(key: str, guesses, splits: dict[str, list[int]], start: str) -> None:
    """Remember the canonical split points under the exact key, and under the keys of a guess
    (:func:`_start_splits`) for a similar HTML (checked there by :func:`_settle_step`, so a
    guess only saves passes)."""
    if not splits or start == "known":
        return
    _remember_splits(key, splits)
    for g in guesses:
        _remember_splits(g, splits)


def _named_rows(page) -> dict[str, tuple[float, float, float, float]]:
    """``{"<table id>__r<row>": (x1, y1, x2, y2)}`` of the table rows on a laid-out page, named
    by their ``data-row`` attribute (the print HTML), each at its border box as WeasyPrint
    gives an anchor (``page.anchors``), the first occurrence on the page kept.

    The rows are named by an attribute and not by an id because WeasyPrint makes an id a
    style property (``-weasy-anchor``): an element with an id, and every element inside it,
    gets a computed style of its own, which for a row is a style per cell (figures in
    docs/performance.md, ``bench/bench_layout_styles.py``; ``tests/test_layout_structure.py``
    counts them)."""
    from weasyprint.formatting_structure import boxes as wb

    out: dict[str, tuple[float, float, float, float]] = {}
    box = getattr(page, "_page_box", None)
    stack = [box] if box is not None else []
    while stack:
        b = stack.pop()
        if isinstance(b, wb.TableRowBox):
            name = b.element.get("data-row") if b.element is not None else None
            if name and name not in out:
                x, y, w, h = b.hit_area()
                out[name] = (x, y, x + w, y + h)
        elif isinstance(b, wb.ParentBox) and not isinstance(b, (wb.LineBox, wb.InlineBox)):
            stack.extend(reversed(list(b.all_children())))
    return out


def _page_rows(document, with_boxes: bool = False):
    """``{table id: {row index: page index}}`` from the laid-out document; with
    ``with_boxes`` also ``{table id: {row index: (top, bottom)}}`` (CSS px on its page).
    Rows are found by :func:`_named_rows` or, in the tests' stand-in pages, by anchors
    ``<table id>__r<row>``."""
    out: dict[str, dict[int, int]] = {}
    boxes: dict[str, dict[int, tuple[float, float]]] = {}
    for p, page in enumerate(document.pages):
        for anchor, pos in [*page.anchors.items(), *_named_rows(page).items()]:
            m = _ROW_ANCHOR.match(anchor)
            if m:
                tid, r = m.group(1), int(m.group(2))
                out.setdefault(tid, {})[r] = p
                if with_boxes and len(pos) >= 4:
                    boxes.setdefault(tid, {})[r] = (pos[1], pos[3])
    return (out, boxes) if with_boxes else out


def _tidy_cuts(cuts: list[int], n: int, min_rows: int) -> list[int]:
    """Keep at least ``min_rows`` rows in the last part (moving its start up,
    which only leaves some room at the bottom of the previous page)."""
    if not cuts or n - cuts[-1] >= min_rows:
        return cuts
    prev = cuts[-2] if len(cuts) > 1 else 0
    start = max(n - min_rows, prev + min_rows)
    if start >= n or start <= prev:
        return cuts
    return cuts[:-1] + [min(start, cuts[-1])]


def _content_bottoms(document) -> list[float | None]:
    """The bottom of each page's content area (CSS px from the page top); ``None`` where
    WeasyPrint does not tell it."""
    out = []
    for page in document.pages:
        box = getattr(page, "_page_box", None)
        try:
            out.append(box.content_box_y() + box.height)
        except (AttributeError, TypeError):
            out.append(None)
    return out


PREMATURE_ROOM = 0.25  # of a page's content height: room left under a cut that makes it premature


def _premature_cut(cuts: list[int], where: dict[int, int], boxes: dict[int, tuple],
                   bottoms: list, min_rows: int) -> int | None:
    """Index in ``cuts`` of the first split point that leaves a page largely empty: the
    part before it ends on a page with room for at least a quarter of the page (and for
    ``min_rows + 1`` of its rows) under its last row. Such a cut was decided while the
    table started lower (an earlier table has since moved). A part that runs onto the next page
    (its first and last rows on different pages) is not cut too early but too late: the room
    under its last row, at the top of the next page, is the overflow's, which moves the cut up
    (:func:`_table_step`); dropping the cut instead would make the whole table give it again."""
    for k, c in enumerate(cuts):
        last = c - 1
        if last not in where or last not in boxes:
            continue
        first = cuts[k - 1] if k else 0
        if first in where and where[first] != where[last]:
            continue
        page = where[last]
        bottom = bottoms[page] if page < len(bottoms) else None
        if bottom is None:
            continue
        top, low = boxes[last]
        row_h = max(low - top, 1.0)
        room = bottom - low
        if room > PREMATURE_ROOM * bottom and room > (min_rows + 1) * row_h:
            return k
    return None


def _next_splits(document, splits: dict[str, list[int]],
                 min_rows: int = MIN_PART_ROWS) -> dict[str, list[int]] | None:
    """New split points from a laid-out document, or ``None`` when every table
    part fits on one page.

    A table without split points yet is cut at the first row of each of its
    later pages; if fewer than ``min_rows`` rows would stay on its first page,
    the table starts on a new page instead (split point 0). Otherwise the
    first part that still spans two pages is fixed: its end moves up to the
    overflowing row and every later split point moves by the same number of
    rows (parts keep their sizes); a last part that overflows is cut at the
    first row of each of its later pages. The last part keeps ``min_rows`` rows.
    A split point under which a page stays largely empty (decided while an
    earlier table still pushed this one lower) is dropped with the later ones,
    and the rest of the table is cut afresh in the next pass.
    """
    rows, boxes = _page_rows(document, with_boxes=True)
    bottoms = _content_bottoms(document)
    result = {k: list(v) for k, v in splits.items()}
    changed = False
    for tid, where in rows.items():
        new = _table_step(where, boxes.get(tid, {}), bottoms, splits.get(tid, ()), changed, min_rows)
        if new is not None:
            result[tid] = new
            changed = True
    # a figure above every changed table is placed in the same pass (_figure_fixes)
    first = min((rows[t][0] for t in rows if result.get(t) != splits.get(t) and 0 in rows[t]),
                default=len(document.pages))
    fixes = _figure_fixes(document, splits, first)
    return {**result, **fixes} if (changed or fixes) else None


def _table_step(where: dict[int, int], boxes: dict[int, tuple], bottoms: list, given,
                changed: bool = False, min_rows: int = MIN_PART_ROWS) -> list[int] | None:
    """The new entry of one table by the rules of :func:`_next_splits` (``where``: row -> page,
    ``boxes``: row -> (top, bottom) of the layout made with the entry ``given``), or ``None``
    when the rules leave it as it is. ``changed``: an earlier table changed in the same pass."""
    n = max(where) + 1
    lead = [0] if 0 in given else []
    cuts = sorted(c for c in set(given) if 0 < c < n)

    def page_starts(a: int, b: int) -> list[int]:
        return [r for r in range(a + 1, b)
                if r in where and (r - 1) in where and where[r] != where[r - 1]]

    if not cuts:
        starts = page_starts(0, n)
        if not starts:
            return None
        if starts[0] < min_rows and not lead:   # (a table of at most min_rows rows is never cut)
            if changed:
                # an earlier table changed in this pass, so where this one starts is not
                # known yet: moving it to a new page now may leave a page half empty
                # (decided in the next pass)
                return None
            return [0]  # too few rows would stay: start on a new page
        return lead + _tidy_cuts(starts, n, min_rows)
    early = _premature_cut(cuts, where, boxes, bottoms, min_rows)
    if early is not None:
        return lead + cuts[:early]
    bounds = [0] + cuts + [n]
    for k in range(len(bounds) - 1):
        a, b = bounds[k], bounds[k + 1]
        first_page = where.get(a)
        overflow = next((r for r in range(a + 1, b) if where.get(r) != first_page), None)
        if overflow is None:
            continue
        if b < n:  # b is a split point: move it and the later ones up
            delta = b - overflow
            new = cuts[:k] + [overflow] + [c - delta for c in cuts[k + 1:]]
        else:  # the last part overflowed: cut it at each of its later pages
            new = cuts + (page_starts(a, n) or [overflow])
        new = sorted(c for c in set(new) if 0 < c < n)
        return lead + _tidy_cuts(new, n, min_rows)
    return None


def split_target(key: str) -> str:
    """The element id a split-point entry belongs to (a table's, or a figure's)."""
    return key[len(FIGURE_KEY):] if key.startswith(FIGURE_KEY) else key


def _flow_box(page):
    """The page's box of the document flow (not its margin boxes), or ``None``."""
    from weasyprint.formatting_structure.boxes import MarginBox
    box = getattr(page, "_page_box", None)
    return next((c for c in getattr(box, "children", ()) if not isinstance(c, MarginBox)), None)


def _ink_bottom(box) -> float:
    """How far down the content of a box reaches (its lines, images and table rows), CSS px."""
    from weasyprint.formatting_structure.boxes import LineBox, ReplacedBox, TableRowBox
    low = 0.0
    for b in box.descendants():
        if isinstance(b, (LineBox, ReplacedBox, TableRowBox)):
            low = max(low, b.position_y + b.margin_height())
    return low


def _parent_of(root, target):
    for b in root.descendants():
        if target in getattr(b, "children", ()):
            return b
    return None


FIGURE_SLACK = 2.0  # CSS px kept free under a figure drawn smaller or text moved before it


FIGURE_LOOKAHEAD = 2  # pages after a figure's whose text may flow before it


def _blocks_after(document, i: int, fig, parent) -> tuple[list, set]:
    """The blocks after figure box ``fig`` (a child of ``parent``, on page ``i``) in its section,
    on that page and the next :data:`FIGURE_LOOKAHEAD`: ``[[element, tag, classes, height, end]]``
    (the fragments of a block on several pages summed; ``end``: the page and the bottom of its
    last fragment), and the elements (by ``id()``) that
    have boxes further on (blocks not whole within these pages)."""
    out: list[list] = []
    last = min(len(document.pages) - 1, i + FIGURE_LOOKAHEAD)
    for j in range(i, last + 1):
        if j == i:
            kids = parent.children[parent.children.index(fig) + 1:]
        else:
            flow = _flow_box(document.pages[j])
            frag = next((b for b in flow.descendants() if getattr(b, "element", None) is parent.element),
                        None) if flow is not None else None
            if frag is None:
                break
            kids = frag.children
        for b in kids:
            el = getattr(b, "element", None)
            end = (j, b.position_y + b.margin_height())
            if out and el is not None and out[-1][0] is el:
                out[-1][3] += b.margin_height()
                out[-1][4] = end
                continue
            cls = (el.get("class") or "").split() if el is not None else []
            out.append([el, getattr(b, "element_tag", None), cls, b.margin_height(), end])
    flow = _flow_box(document.pages[last + 1]) if last + 1 < len(document.pages) else None
    later = {id(b.element) for b in flow.descendants()
             if getattr(b, "element", None) is not None} if flow is not None else set()
    return out, later


def _text_units(blocks, later: set) -> list[tuple]:
    """The blocks after a figure (:func:`_blocks_after`) as units that move together:
    ``(elements, height, breakable, whole, end)``: a paragraph with the formulas it leads into, a
    table with the paragraph announcing it, a formula with its «где» lines. Stops at anything
    else (a heading, a figure). ``later``: the elements (by ``id()``) that go on further (a
    block not whole)."""
    return _units_and_stop(blocks, later)[0]


def _units_and_stop(blocks, later: set) -> tuple[list[tuple], int | None]:
    """``(units, stop)``: the units of :func:`_text_units` and the index in ``blocks`` of the
    block they stopped at (a heading, a figure: nothing after it is read), ``None`` when they
    took every block."""
    units: list[list] = []
    lead = intro = False
    stop = None
    for at, (el, tag, cls, h, *where) in enumerate(blocks):
        end = where[0] if where else None
        if (tag == "p" and "where-note" in cls) or (tag == "table" and "where" in cls):
            if not units:
                stop = at
                break
            units[-1][0] += 1
            units[-1][1] += h
            units[-1][2] = False
            units[-1][4] = end
        elif tag == "div" and "tbl-wrap" in cls and lead:
            units[-1][0] += 1
            units[-1][1] += h
            units[-1][4] = end
            lead = False
        elif tag == "div" and "eq" in cls and intro:
            units[-1][0] += 1     # the formulas a paragraph leads into go with it
            units[-1][1] += h
            units[-1][2] = False
            units[-1][4] = end
        elif tag == "div" and "eq" in cls:
            units.append([1, h, False, True, end])
            intro = True
        elif tag == "p" or (tag == "div" and "tbl-wrap" in cls):
            units.append([1, h, True, True, end])
            lead = tag == "p" and "lead" in cls
            intro = tag == "p"
        else:
            stop = at
            break
        units[-1][3] = units[-1][3] and id(el) not in later
    if lead:
        units.pop()  # a paragraph announcing a table that is not there
    return [tuple(u) for u in units], stop


def _figure_fixes(document, splits: dict[str, list[int]], upto: int | None = None) -> dict[str, list[int]]:
    """A figure that did not fit under the text before it and left that page less than half full
    (:data:`FIGURE_ROOM`; ГОСТ 7.32 allows a figure on the next page, not a half-empty one; a
    page fuller than that is left as it is, so that most notes take no extra layout pass and
    the split points of a similar note stay a provable guess), as a good typesetter
    places it: drawn smaller, down to :data:`MIN_FIGURE_SCALE`, when that fits the room; else
    the text after it (whole paragraphs, formulas, tables with their announcing paragraph,
    within its section) flows before it, as much as fills the room, and one paragraph or table
    more, broken across the page, when the page would still be less than half full and the
    figure then still fits under that block's end. The figure stays at the top of the next page,
    after the text that first names it.

    A wide figure on a landscape page of its own is not drawn smaller; the text after it fills
    the portrait page before it the same way.

    Returns the new entry (:data:`FIGURE_KEY`) of the first such figure on a page before ``upto``
    (where the layout changes in this pass anyway), or ``{}``. A figure is decided once (its
    entry is kept by the later passes), so the passes end."""
    bottoms = _content_bottoms(document)
    for i in range(1, min(len(document.pages), len(document.pages) if upto is None else upto)):
        fid, fix, _read = _figure_fix_at(document, i, bottoms, splits)
        if fix:
            return fix
    return {}


def _figure_fix_at(document, i: int, bottoms: list, splits: dict) -> tuple[str | None, dict, tuple]:
    """The rule of :func:`_figure_fixes` at page ``i``: ``(figure id, entry)`` when a figure without
    an entry stands at the top of page ``i`` after a page less than half full (the rule decides
    it: ``entry`` is ``{}`` when neither drawing it smaller nor moving text fits), else
    ``(None, {})``; third, ``(page, y)`` up to which the decision read the layout after the figure
    (the end of the last block it weighed, or of the block its text stopped at: a heading, a
    figure, the rest of its own caption on the next page). What decides it: the page before, the figure, and the
    blocks after it in its section on pages ``i`` to ``i +`` :data:`FIGURE_LOOKAHEAD` (and which
    of them go on further)."""
    page, before = document.pages[i], document.pages[i - 1]
    flow, prev_flow = _flow_box(page), _flow_box(before)
    if flow is None or prev_flow is None or bottoms[i - 1] is None or bottoms[i] is None:
        return None, {}, (i, 0.0)
    if before.width > before.height:
        return None, {}, (i, 0.0)  # a landscape page holds one wide figure
    land = page.width > page.height       # a wide figure on a landscape page of its own
    box = page._page_box
    top = box.content_box_y()
    fig = next((b for b in flow.descendants() if getattr(b, "element_tag", None) == "figure"), None)
    if fig is None or fig.position_y > top + 0.5:
        return None, {}, (i, 0.0)  # no figure at the top of the page
    fid = fig.element.get("id") or ""
    if land != ("landscape" in (fig.element.get("class") or "")) or FIGURE_KEY + fid in splits or not fid:
        return None, {}, (i, 0.0)
    room = bottoms[i - 1] - _ink_bottom(prev_flow)
    height = bottoms[i - 1] - before._page_box.content_box_y()
    if room <= FIGURE_ROOM * height:
        return None, {}, (i, 0.0)  # the page is at least half full (ГОСТ 7.32 layout asks no more)
    margins = float(fig.style["margin_top"].value) + float(fig.style["margin_bottom"].value)
    img = next((b for b in fig.descendants() if getattr(b, "element_tag", None) == "img"), None)
    if img is None:
        return fid, {}, (i, 0.0)
    h_img = img.margin_height()
    rest = fig.border_height() - h_img + margins
    scale = (room - rest - FIGURE_SLACK) / h_img
    if scale >= MIN_FIGURE_SCALE and not land:
        return fid, {FIGURE_KEY + fid: [0, min(999, int(scale * 1000))]}, (i, 0.0)
    parent = _parent_of(flow, fig)
    if parent is None:
        return fid, {}, (i, 0.0)
    line = float(fig.style["font_size"]) * 1.5
    blocks, later = _blocks_after(document, i, fig, parent)
    units, stop = _units_and_stop(blocks, later)
    moved, used = 0, 0.0
    k = 0
    while k < len(units) and units[k][3] and used + units[k][1] <= room - FIGURE_SLACK:
        moved += units[k][0]
        used += units[k][1]
        k += 1
    read = units[min(k, len(units) - 1)][4] if units else None
    if k < len(units) and room - used > height / 2:
        n, h, breakable, whole = units[k][:4]
        # what stays of it on the next page, then the figure (three lines spare for the
        # orphans and widows of the break); a landscape figure has a page of its own
        if breakable and whole and (land or (h - (room - used)) + rest + h_img + 3 * line <= height):
            moved += n
    if k >= len(units) or read is None:
        # the text ran out before the room did: read up to the block it stopped at (a heading, a
        # figure: its tag read, nothing after it), else every block up to where _blocks_after looked
        read = blocks[stop][4] if stop is not None else (min(len(document.pages), i + FIGURE_LOOKAHEAD + 2), 0.0)
    return fid, ({FIGURE_KEY + fid: [moved, 1000]} if moved else {}), read


SPLIT_EPS = 0.01  # CSS px: heights equal, and a row not fitting, only beyond this


def _norm(key: str, entry) -> list[int] | None:
    """An entry in the form the rules compare: a table's split points sorted without repeats, a
    figure's entry as it is; ``None`` for no entry (an empty table entry lays out as none)."""
    if not entry:
        return None
    return list(entry) if key.startswith(FIGURE_KEY) else sorted(set(int(c) for c in entry))


def _points(document, rows: dict, boxes: dict) -> list[tuple[int, float, str]]:
    """The decision points of a laid-out document in document order, ``(page, y, key)``: every
    table with named rows (key: its id; where its first row is) and every figure with an id
    (key: :data:`FIGURE_KEY` + id; where its box is). A decision about one of them changes
    the HTML from that element on, never before it."""
    out = []
    for tid, where in rows.items():
        first = min(where, default=None)
        if first is not None:
            out.append((where[first], boxes.get(tid, {}).get(first, (0.0,))[0], tid))
    seen = set()
    for i, page in enumerate(document.pages):
        flow = _flow_box(page)
        if flow is None:
            continue
        for b in flow.descendants():
            if getattr(b, "element_tag", None) == "figure":
                fid = b.element.get("id") if b.element is not None else None
                if fid and fid not in seen:
                    seen.add(fid)
                    out.append((i, b.position_y, FIGURE_KEY + fid))
    return sorted(out)


def _greedy_step(document, splits: dict[str, list[int]],
                 min_rows: int = MIN_PART_ROWS) -> dict[str, list[int]] | None:
    """One pass of the canonical split rule, literally (the reference the fast passes of
    :func:`_settle_step` are checked against, tests/test_split_greedy.py): the first decision
    point in document order (:func:`_points`) where a rule asks for a change gets it, and only
    it; ``None`` when no rule asks for anything. The rules: a table's (:func:`_table_step`,
    as an only table changing) and a figure's without an entry (:func:`_figure_fix_at`).

    The passes from none, each with this step, define the split points of an HTML (the
    *canonical* ones): every decision is made on the layout where every earlier one is made
    and every later one not (later tables whole, later figures unmoved), because a decision
    changes the layout only from its own element on and the earlier points are left as they
    are once no rule asks anything of them."""
    rows, boxes = _page_rows(document, with_boxes=True)
    bottoms = _content_bottoms(document)
    for page, _y, key in _points(document, rows, boxes):
        if key.startswith(FIGURE_KEY):
            if key in splits or page == 0:
                continue
            fid, fix, _read = _figure_fix_at(document, page, bottoms, splits)
            if fix and FIGURE_KEY + fid == key:
                return {**{k: list(v) for k, v in splits.items()}, **fix}
            continue
        new = _table_step(rows[key], boxes.get(key, {}), bottoms, splits.get(key, ()), False, min_rows)
        if new is not None:
            return {**{k: list(v) for k, v in splits.items()}, key: new}
    return None


_WHY: list | None = None  # when a list: why a table or figure was not decided (for debugging)


def _why(verdict, reason: str):
    if _WHY is not None:
        _WHY.append(reason)
    return verdict


SIM_EPS = 0.05  # CSS px: a row of the model where the layout has it
SIM_MARGIN = SPLIT_EPS  # CSS px: a row of the model ending this close to a page bottom is not decided by it


def _uniform(values: list, pages) -> float | None:
    got = {round(values[p], 3) for p in pages if p < len(values) and values[p] is not None}
    return got.pop() if len(got) == 1 else None


def _table_verdict(where: dict[int, int], rb: dict[int, tuple], table_top: float | None,
                   tops: list, bottoms: list, cur: list[int] | None, before: tuple | None,
                   min_rows: int = MIN_PART_ROWS, shift: float = 0.0) -> tuple[str, list[int] | None, bool]:
    """Whether the entry ``cur`` of a table is the one the canonical passes give, read from ONE
    layout made with it: ``("ok", None, True)``, ``("fix", entry, same_end)`` (the canonical entry,
    when it is another; ``same_end``: the table would end where it ends here, so the layout after
    it would not change) or ``("unknown", None, False)``.

    The table's layout in the passes is modelled from this one: every row keeps its height (the
    assumption every pass makes: borders inside the cells, a row's height depends neither on
    its page nor on the rows sharing its part; WeasyPrint's automatic column widths come from
    the rows of a part, so a header wrapping otherwise in a part is caught only where it shows in
    this layout); a part's rows follow each other from its first, which stands ``head`` below
    where the part starts (the table's caption row and column header, repeated whole on each
    later page of a whole table or of the first part; the «Продолжение таблицы» header ``cont``
    of a continuation part, starting a page); a row that would end below the page's content
    bottom starts the next page under the repeated header. ``head`` is read here; ``cont`` only
    where this layout has a continuation part; the page geometry must be the same on the
    table's pages. The table starts where its first row is here, unless this entry starts it on
    a new page (split point 0): then it would start under the block before it (``before``: that
    block's border bottom and bottom margin on the page before, :func:`_block_before`), the
    collapsed margin apart (the table's own top margin being what it keeps at the top of a page
    after the forced break).

    The model is first checked against this layout (every row of ``cur`` on its page and at its
    place within :data:`SIM_EPS`), then the passes from none are run on it with
    :func:`_table_step` (the same rules, an only table changing). Unknown when a quantity is
    missing, the model does not match, or a row ends within :data:`SIM_MARGIN` of a page bottom
    in a modelled layout (too close to say which page WeasyPrint gives it).

    ``shift``: the passes are run with the table starting that much higher on its page than
    here (a table not started on a new page), which makes the answer a *guess* of its entry for
    a layout where the blocks above it on its page are gone (:func:`_shifted_guesses`)."""
    unknown = ("unknown", None, False)
    n = max(where) + 1
    if set(where) != set(range(n)) or set(rb) != set(range(n)) or table_top is None:
        return _why(unknown, "rows missing")
    pages = set(where.values())
    top, bottom = _uniform(tops, pages), _uniform(bottoms, pages)
    if top is None or bottom is None:
        return _why(unknown, "page geometry")
    h = [rb[r][1] - rb[r][0] for r in range(n)]
    head = rb[0][0] - table_top
    lead = bool(cur) and 0 in cur
    cuts = [c for c in (cur or ()) if 0 < c < n]
    conts = {round(rb[c][0] - top, 3) for c in cuts if where[c] != where[c - 1]}
    if len(conts) > 1:
        return _why(unknown, "continuation headers differ")
    cont = conts.pop() if conts else None
    y0 = None if lead else rb[0][0]
    lead_off = table_top - top  # the table's own top margin, kept after the forced break of split point 0

    def lay(entry):
        lead_, cuts_ = bool(entry) and 0 in entry, [c for c in (entry or ()) if 0 < c < n]
        w, b = {}, {}
        page = 0
        for j, (a, z) in enumerate(zip([0] + cuts_, cuts_ + [n])):
            if j == 0 and not lead_:
                if y0 is None:
                    return None
                y, rep = y0, head
            elif j == 0:
                page, y, rep = 1, top + lead_off + head, head
            else:
                if cont is None:
                    return None
                page, y, rep = page + 1, top + cont, cont
            for r in range(a, z):
                if abs(y + h[r] - bottom) < SIM_MARGIN:
                    return None
                if y + h[r] > bottom:
                    if r == a:
                        return None  # not even one row where the part starts: not modelled
                    page, y = page + 1, top + rep
                    if y + h[r] > bottom - SIM_MARGIN:
                        return None
                w[r], b[r] = page, (y, y + h[r])
                y += h[r]
        return w, b

    base = where[0] - (1 if lead else 0)
    here = lay(cur)
    if here is None or any(base + here[0][r] != where[r] or abs(here[1][r][0] - rb[r][0]) > SIM_EPS
                           for r in range(n)):
        return _why(unknown, "model does not match")
    sim_bottoms = [bottom] * (n + 3)
    entry = None
    if shift:
        if lead or y0 - shift - head < top - SIM_EPS:
            return _why(unknown, "shifted start not modelled")
        y0 -= shift
    if lead:
        # unsplit, the table starts under the block before it: that block's border bottom, then
        # the larger of the adjoining margins (its own bottom ones, the table's top one)
        if before is None or n <= LEAD_TABLE_ROWS or lead_off < 0:
            return _why(unknown, "start of a table moved to a new page")
        y0 = before[0] + max(before[1], lead_off) + head
    for _ in range(MAX_PASSES):
        laid = lay(entry)
        if laid is None:
            return _why(unknown, "not modelled (a row at a page bottom, a part not starting)")
        new = _table_step(laid[0], laid[1], sim_bottoms, entry or [], False, min_rows)
        if new is None:
            break
        entry = _norm("", new)
    else:
        return _why(unknown, "passes do not end")
    if entry == cur:
        return "ok", None, True
    laid = lay(entry)
    same_end = (laid is not None and n > LEAD_TABLE_ROWS and base + laid[0][n - 1] == where[n - 1]
                and abs(laid[1][n - 1][1] - rb[n - 1][1]) <= SIM_EPS)
    return "fix", entry, same_end


def _block_before(document, page: int, tid: str) -> tuple[float, float] | None:
    """``(border bottom, bottom margin)`` of the block before table ``tid`` (at the top of page
    ``page``) on the page before: the last block of its parent there, the bottom margins of its
    last descendants that adjoin its own counted (they collapse with it); ``None`` when not found."""
    from weasyprint.formatting_structure.boxes import BlockBox, TableRowBox
    flow, prev_flow = _flow_box(document.pages[page]), _flow_box(document.pages[page - 1])
    if flow is None or prev_flow is None:
        return None
    stack, path = [(flow, [flow])], None
    while stack:
        b, trail = stack.pop()
        if isinstance(b, TableRowBox) and b.element is not None and b.element.get("id") == tid:
            path = trail
            break
        stack.extend((c, trail + [c]) for c in reversed(getattr(b, "children", None) or ())
                     if not isinstance(c, str))
    wrap = next((k for k, b in enumerate(path or ()) if getattr(b, "element_tag", None) == "div"
                 and "tbl-wrap" in (b.element.get("class") or "")), None)
    if not wrap:
        return None
    parent = path[wrap - 1].element
    frag = next((b for b in prev_flow.descendants() if getattr(b, "element", None) is parent), None)
    kids = [c for c in getattr(frag, "children", ()) if isinstance(c, BlockBox)]
    if not kids:
        return None
    b = kids[-1]
    low, margin = b.border_box_y() + b.border_height(), b.margin_bottom
    while b.padding_bottom == 0 and b.border_bottom_width == 0:
        inner = [c for c in getattr(b, "children", ()) if isinstance(c, BlockBox)]
        if not inner or inner[-1] is not b.children[-1]:
            break
        b = inner[-1]
        margin = max(margin, b.margin_bottom)
    return low, margin


def _section_blocks(document, parent_el) -> list[list]:
    """The child blocks of element ``parent_el`` over all pages, in order:
    ``[element, tag, classes, height, (first page, top), (last page, bottom)]`` (the fragments of a
    block on several pages summed, as :func:`_blocks_after` does)."""
    out: list[list] = []
    for j, page in enumerate(document.pages):
        flow = _flow_box(page)
        frag = next((b for b in flow.descendants() if getattr(b, "element", None) is parent_el),
                    None) if flow is not None else None
        if frag is None:
            continue
        for b in frag.children:
            el = getattr(b, "element", None)
            low = b.position_y + b.margin_height()
            if out and el is not None and out[-1][0] is el:
                out[-1][3] += b.margin_height()
                out[-1][5] = (j, low)
                continue
            cls = (el.get("class") or "").split() if el is not None else []
            out.append([el, getattr(b, "element_tag", None), cls, b.margin_height(), (j, b.position_y), (j, low)])
    return out


def _figure_box(document, page: int, key: str):
    """``(flow box of page ``page``, box of the figure of entry ``key`` on it or None)``."""
    fid = key[len(FIGURE_KEY):]
    flow = _flow_box(document.pages[page])
    fig = next((b for b in flow.descendants() if getattr(b, "element_tag", None) == "figure"
                and b.element is not None and b.element.get("id") == fid), None) if flow is not None else None
    return flow, fig


def _decision_order(document, points: list, splits: dict) -> list:
    """The decision points (:func:`_points`) in the order their decisions change the HTML: a
    figure with text moved before it (entry ``[n, 1000]``, ``n > 0``) decides from where the
    first of those blocks starts, so it comes before the tables among them (their layout is
    the figure's decision's). Laid out after the figure, they would be decided first and a
    changed figure entry would not undo what was proved of them."""
    def where(point):
        page, y, key = point
        cur = _norm(key, splits.get(key)) if key.startswith(FIGURE_KEY) else None
        if not cur or not cur[0]:
            return point
        flow, fig = _figure_box(document, page, key)
        parent = _parent_of(flow, fig) if fig is not None else None
        if parent is None:
            return point
        blocks = _section_blocks(document, parent.element)
        at = next((n for n, b in enumerate(blocks) if b[0] is fig.element), None)
        if at is None or at < cur[0]:
            return point
        first_page, top = blocks[at - cur[0]][4]
        return (first_page, top - SPLIT_EPS, key)

    return sorted(points, key=where)


FIGURE_MARGIN = 0.5  # CSS px: a figure quantity this close to what a rule compares it with is not decided


def _figure_verdict(document, page: int, key: str, cur: list[int], bottoms: list):
    """Whether the entry ``cur`` of a figure is the one its rule (:func:`_figure_fix_at`) gives on
    the canonical layout, read from ONE layout made with it: ``("ok", None)``, ``("fix", entry or
    None)`` or ``("unknown", None)``.

    On the canonical layout the figure stands unmoved and at full size after the text before it
    (the same HTML up to it). What the rule reads of it is read here: the text before it ends at
    the same place (the ink above the first block moved before the figure, or above the figure
    drawn smaller); the figure at full size is as high as here with its image ``1000 / scale``
    times as high (its width is scaled, its caption spans the column); the blocks after it are
    those moved before it here and those after it, each as high as here (whole blocks keep their
    height; a block broken across pages is summed over its fragments, as the rule sums them).
    A landscape figure stands on a page of its own (a forced break before and after it): the
    page before it ends with the text before it, and the blocks after it start the next page.
    Unknown where that does not hold or does not decide: the figure perhaps
    fitting under the text before it at full size, the blocks weighed reaching further than
    1.5 pages (where the rule's «goes on further» is not read here), or a comparison of the rule
    within :data:`FIGURE_MARGIN`."""
    unknown = ("unknown", None)
    if len(cur) != 2 or (cur[0] and cur[1] != 1000) or not (cur[0] or cur[1] < 1000):
        return _why(unknown, "entry not made by the rule")
    moved_n, s = int(cur[0]), int(cur[1])
    flow, fig = _figure_box(document, page, key)
    if fig is None:
        return _why(unknown, "figure not found")
    land = "landscape" in (fig.element.get("class") or "")  # on a landscape page of its own
    if land and (s != 1000 or document.pages[page].width <= document.pages[page].height):
        return _why(unknown, "figure not found")
    img = next((b for b in fig.descendants() if getattr(b, "element_tag", None) == "img"), None)
    parent = _parent_of(flow, fig)
    if img is None or parent is None:
        return _why(unknown, "no image or parent")
    blocks = _section_blocks(document, parent.element)
    at = next((n for n, b in enumerate(blocks) if b[0] is fig.element), None)
    if at is None or at < moved_n:
        return _why(unknown, "moved blocks missing")
    moved = blocks[at - moved_n:at]
    if any(b[1] not in ("p", "div", "table") for b in moved):
        return _why(unknown, "moved block not text")
    first = moved[0] if moved else blocks[at]
    p, y_cut = first[4]
    if p >= len(document.pages) - 1 or bottoms[p] is None:
        return _why(unknown, "page after")
    before = document.pages[p]
    if before.width > before.height or (not land and document.pages[p + 1].width > document.pages[p + 1].height):
        return _why(unknown, "page orientation")
    box = before._page_box
    top, bottom = box.content_box_y(), bottoms[p]
    from weasyprint.formatting_structure.boxes import LineBox, ReplacedBox, TableRowBox
    ink = max((b.position_y + b.margin_height() for b in _flow_box(before).descendants()
               if isinstance(b, (LineBox, ReplacedBox, TableRowBox))
               and b.position_y + b.margin_height() <= y_cut + SPLIT_EPS), default=None)
    if ink is None:
        if p > 0 and document.pages[p - 1].width > document.pages[p - 1].height:
            # nothing before it on its page, after a landscape page (which holds one wide figure):
            # on the canonical layout the figure starts the page after that one, where the rule
            # (_figure_fix_at) gives no entry
            return "fix", None
        return _why(unknown, "no text before on its page")
    margins = float(fig.style["margin_top"].value) + float(fig.style["margin_bottom"].value)
    h_img = img.margin_height() * 1000 / s
    rest = fig.border_height() - img.margin_height() + margins
    room, height = bottom - ink, bottom - top

    def close(a: float, b: float) -> bool:
        return abs(a - b) < FIGURE_MARGIN

    if close(room, FIGURE_ROOM * height):
        return _why(unknown, "room close to half")
    full = 0.0 if land else fig.border_height() - img.margin_height() + h_img
    # (at full size it would start at least its own top margin under the text before it)
    if not land and not ink + float(fig.style["margin_top"].value) + full > bottom + FIGURE_MARGIN:
        return _why(unknown, "might fit at full size")
    if room <= FIGURE_ROOM * height:
        return "fix", None  # the page before is at least half full: no entry
    scale = (room - rest - FIGURE_SLACK) / h_img
    if close(scale * h_img, MIN_FIGURE_SCALE * h_img) or abs(scale * 1000 - round(scale * 1000)) < 1e-6:
        return _why(unknown, "scale at a bound")
    if scale >= MIN_FIGURE_SCALE and not land:
        want = [0, min(999, int(scale * 1000))]
        return ("ok", None) if want == cur else ("fix", want)
    # the blocks after it on the canonical layout: those moved before it here, then the rest
    after = [b[:4] for b in moved] + [b[:4] for b in blocks[at + 1:]]
    units = _text_units(after, set())
    line = float(fig.style["font_size"]) * 1.5
    n_moved, used, k = 0, 0.0, 0
    while k < len(units) and used + units[k][1] <= room - FIGURE_SLACK:
        if close(used + units[k][1], room - FIGURE_SLACK):
            return _why(unknown, "block close to the room")
        n_moved += units[k][0]
        used += units[k][1]
        k += 1
    if k < len(units) and close(used + units[k][1], room - FIGURE_SLACK):
        return _why(unknown, "block close to the room")
    # the rule reads whether a block goes on past its pages for the blocks it moves, and for
    # the one after them only when it would break that one across the page (room left > half)
    if k < len(units) and close(room - used, height / 2):
        return _why(unknown, "room close to half")
    broken = k < len(units) and room - used > height / 2
    if full + (0.0 if land else margins) + sum(u[1] for u in units[:k + broken]) >= 1.5 * height:
        return _why(unknown, "blocks beyond 1.5 pages")  # (whether one goes on past the rule's pages)
    if broken:
        n, h, breakable = units[k][:3]
        fits = (h - (room - used)) + rest + h_img + 3 * line
        if breakable and not land and close(fits, height):
            return _why(unknown, "broken block close to the page")
        if breakable and (land or fits <= height):
            n_moved += n
    want = [n_moved, 1000] if n_moved else None
    return ("ok", None) if want == cur else ("fix", want)


def _shifted_guesses(document, page: int, key: str, entry, rows: dict, boxes: dict,
                     table_tops: dict, tops: list, bottoms: list, splits: dict,
                     min_rows: int = MIN_PART_ROWS) -> dict[str, list[int] | None]:
    """Guesses of the entries of the tables after a landscape figure (``key``, on page ``page``)
    just given text moved before it (``entry`` ``[n, 1000]``), for the next layout: the figure
    has a page of its own (forced breaks before and after it), so the blocks after the moved
    ones start the page after it as they stand here, only higher by where the first of them
    starts here. Each table with an entry starting on that page after them gets the entry its
    own passes give on the model of :func:`_table_verdict` started that much higher (``None``:
    it needs none). Without this its stale entry cost a pass of its own (checked, found
    wrong, dropped). A guess: the passes end only where :func:`_settle_step` proves it."""
    n = entry[0] if entry and len(entry) == 2 and entry[1] == 1000 else 0
    if not n or page + 1 >= len(document.pages):
        return {}
    flow, fig = _figure_box(document, page, key)
    parent = _parent_of(flow, fig) if fig is not None else None
    if parent is None or "landscape" not in (fig.element.get("class") or ""):
        return {}
    blocks = _section_blocks(document, parent.element)
    at = next((k for k, b in enumerate(blocks) if b[0] is fig.element), None)
    if at is None or at + n + 1 >= len(blocks) or tops[page + 1] is None:
        return {}
    nxt = page + 1
    if any(b[4][0] != nxt or b[5][0] != nxt for b in blocks[at + 1:at + n + 1]) or blocks[at + n + 1][4][0] != nxt:
        return {}  # the moved blocks not all on the page after the figure
    start = blocks[at + n + 1][4][1]
    shift = start - tops[nxt]
    out: dict[str, list[int] | None] = {}
    for tid, where in rows.items():
        cur = _norm(tid, splits.get(tid))
        rb = boxes.get(tid, {})
        if not cur or 0 in cur or where.get(0) != nxt or 0 not in rb or rb[0][0] < start - SPLIT_EPS:
            continue
        verdict, want, _same = _table_verdict(where, rb, table_tops.get(tid), tops, bottoms, cur, None,
                                              min_rows, shift)
        if verdict == "fix":
            out[tid] = want
    return out


def _entries_before(points, idx: int, splits: dict, end: tuple) -> list[str]:
    """The points after ``points[idx]`` with an entry that start before ``end`` (page, y)."""
    return [k for p, y, k in points[idx + 1:] if (p, y) < tuple(end) and _norm(k, splits.get(k))]


def _settle_step(document, splits: dict[str, list[int]], state: dict,
                 min_rows: int = MIN_PART_ROWS) -> dict[str, list[int]] | None:
    """The next split points of the fast passes, or ``None`` when ``splits`` (with which
    ``document`` was laid out) are the canonical ones (:func:`_greedy_step`).

    The decision points are walked in document order. A point is right when it is proved from
    this layout: its layout here is that of the canonical passes (the same HTML before it and,
    by induction over the points already found right, the same place), and

    * a table: :func:`_table_verdict` runs the table's own passes on a model of its rows read
      from this layout; a table without an entry that fits its page, or whose entry came by the
      literal rule (:func:`_table_step`) on layouts where it was the first point asking for a
      change (``state["literal"]``), is checked by that rule directly;
    * a figure without an entry: :func:`_figure_fix_at` does not trigger, or triggers and no
      later entry lies before the end of what it read (the layout it read is then the
      canonical one), or gave none on the layout with the later entries held back and gives
      none with them (``state["clean_none"]``: both layouts agree, so it is not held back again,
      which would alternate the two layouts without end); a figure with one:
      :func:`_figure_verdict`. A decided figure's entry holds for the later passes
      (``state["proven"]``, dropped when a point before it changes).

    At the first point not proved right: its canonical entry when known (a table whose right
    entry ends where this one does leaves the later layout as it is, so the walk goes on),
    else one literal step of its rule when its layout here is the canonical one up to it, else
    the point is set back to none (with the later entries before the end of what its rule
    reads held back, restored once it is decided), so that the next layout is. The later
    points are then guessed from this layout where they have no entry (a table spanning pages
    cut where its pages start, a figure by its rule; the tables after a landscape figure given
    text moved before it, entry or not, where they will start: :func:`_shifted_guesses`): the
    first pass of a note guesses every decision at once, and a guess costs at most the pass
    that finds it wrong.

    ``state`` is kept between the passes of one layout (plain data: it crosses processes)."""
    proven = state.setdefault("proven", {})
    held = state.setdefault("held", {})
    rows, boxes = _page_rows(document, with_boxes=True)
    bottoms = _content_bottoms(document)
    tops = [b - getattr(getattr(p, "_page_box", None), "height", 0) if b is not None else None
            for b, p in zip(bottoms, document.pages)]
    table_tops = {}
    for page in document.pages:
        for name, pos in page.anchors.items():
            if name in rows and len(pos) >= 4:
                table_tops.setdefault(name, pos[1])
    points = _decision_order(document, _points(document, rows, boxes), splits)
    new = {k: list(v) for k, v in splits.items()}
    changed = False

    def put(key: str, entry) -> None:
        nonlocal changed
        if entry:
            new[key] = list(entry)
        else:
            new.pop(key, None)
        changed = True

    def hold(keys) -> None:
        for k in keys:
            held[k] = new.pop(k)
        state["held_for"] = key

    def finish(idx: int, guess: bool, guessed: dict | None = None):
        """Drop what was proved after ``idx``, guess the later points (``guessed``: entries already
        guessed for some of them, none meaning none), return the next entries."""
        later = {k for _p, _y, k in points[idx + 1:]}
        for k, v in (guessed or {}).items():
            if k in later and k not in held:
                put(k, v)
        for k in later:
            proven.pop(k, None)
        state["clean_none"] = [k for k in state.get("clean_none", ()) if k not in later]
        if guess:
            guessed = dict(guessed or {})
            for p, _y, k in points[idx + 1:]:
                if _norm(k, new.get(k)) or k in held or k in guessed:
                    continue
                if k.startswith(FIGURE_KEY):
                    fid, fix, _read = _figure_fix_at(document, p, bottoms, new) if p else (None, {}, None)
                    if fix and FIGURE_KEY + fid == k:
                        new.update(fix)
                        shifted = _shifted_guesses(document, p, k, fix[k], rows, boxes, table_tops, tops,
                                                   bottoms, new, min_rows)
                        for t, v in shifted.items():
                            if t in later and t not in held:
                                put(t, v)
                        guessed.update(shifted)
                else:
                    cut = _table_step(rows[k], boxes.get(k, {}), bottoms, (), False, min_rows)
                    if cut:
                        new[k] = cut
        return new

    for idx, (page, _y, key) in enumerate(points):
        cur = _norm(key, splits.get(key))
        if key in proven and proven[key] == cur:
            continue
        if key.startswith(FIGURE_KEY):
            if cur is not None:
                verdict, want = _figure_verdict(document, page, key, cur, bottoms)
                if verdict == "ok":
                    proven[key] = cur
                    continue
                state["literal"] = None
                if verdict == "fix":
                    if want:
                        proven[key] = list(want)
                    put(key, want)
                    return finish(idx, True)
                # not decided here: set back to none, the later entries it may read held back
                hold(_entries_before(points, idx, new, (page + FIGURE_LOOKAHEAD + 2, 0.0)))
                put(key, None)
                return finish(idx, False)
            fid, fix, read = _figure_fix_at(document, page, bottoms, new) if page else (None, {}, None)
            decided = None
            if fid is not None and FIGURE_KEY + fid == key:
                unclean = _entries_before(points, idx, new, read)
                if unclean and not (key in state.get("clean_none", ()) and not fix.get(key)):
                    hold(unclean)
                    put(key, None)
                    return finish(idx, False)
                decided = fix.get(key)
            acted = bool(decided)
            if decided:
                proven[key] = list(decided)
                put(key, decided)
            if state.get("held_for") == key:
                state["held_for"] = None
                if not decided and key not in state.setdefault("clean_none", []):
                    # no entry on the layout without the later entries: where the rule reads
                    # them back in and still gives none, the figure is not held back again
                    state["clean_none"].append(key)
                if held:
                    new.update(held)
                    held.clear()
                    acted = changed = True
            if acted:
                return finish(idx, True, _shifted_guesses(document, page, key, decided, rows, boxes, table_tops,
                                                          tops, bottoms, new, min_rows) if decided else None)
            continue
        where, rb = rows[key], boxes.get(key, {})
        if cur is None:
            step = _table_step(where, rb, bottoms, (), False, min_rows)
            if step is None:
                continue
            state["literal"] = key
            put(key, step)
            return finish(idx, True)
        if state.get("literal") == key:
            # its entry came by the literal rule, which its model may contradict (a model that
            # sends it back to the entry the rule just left would alternate without end)
            step = _table_step(where, rb, bottoms, cur, False, min_rows)
            if step is None:
                proven[key] = cur
                continue
            put(key, step)
            return finish(idx, True)
        p0 = where[min(where)]
        before = _block_before(document, p0, key) if 0 in cur and p0 > 0 else None
        verdict, entry, same_end = _table_verdict(where, rb, table_tops.get(key), tops, bottoms, cur,
                                                  before, min_rows)
        if verdict == "ok":
            continue
        if verdict == "fix":
            state["literal"] = None
            put(key, entry)
            if same_end:
                continue  # the layout after it stays as it is: the walk goes on
            return finish(idx, True)
        state["literal"] = None
        put(key, None)
        return finish(idx, False)
    if held:
        # the figure they were held back for gave no entry without them (as above)
        if state.get("held_for") and state["held_for"] not in state.setdefault("clean_none", []):
            state["clean_none"].append(state["held_for"])
        state["held_for"] = None
        new.update(held)
        held.clear()
        changed = True
    return new if changed else None


_IMAGE_CACHE: dict = {}
_IMAGE_CACHE_MAX = 2000


def _image_cache() -> dict:
    """WeasyPrint's cache of parsed images, kept by the process: shared by the layout passes
    and by every report the process builds (a batch worker meets the same formulas in every
    variant). Images are ``data:`` URLs, so a key is the content itself; WeasyPrint names an
    image in the PDF by the md5 of its URL, so sharing changes no byte of the output."""
    if len(_IMAGE_CACHE) > _IMAGE_CACHE_MAX:
        _IMAGE_CACHE.clear()
    return _IMAGE_CACHE


_HTML_CLASS = None


def _html_class():
    """WeasyPrint's ``HTML`` with a lighter user-agent stylesheet.

    WeasyPrint's own (``html5_ua.css``) gives *every* element cascaded styles for six
    pseudo-elements (``::marker``, ``::footnote-call``, ``::footnote-marker``, ``::note-call``,
    ``::note-marker``, ``::note-callback``), and the cascade then computes a style for each
    of them: seven computed styles per element, most of them for table cells. The note has
    no footnotes or notes, and markers only on list items, so here ``::marker`` applies to
    ``li`` only and the footnote and note rules are left out; the rest of the sheet is
    WeasyPrint's. The PDF is byte for byte the same (checked on every part of ws000); the
    cascade of a part is about a sixth cheaper. Two more savings, each giving the same tree and
    cascade: the HTML is parsed by :func:`~reportgen.report.fasthtml.parse` when it is in the
    subset that parser proves equal to tinyhtml5's (else by WeasyPrint), and the note's own
    stylesheet is parsed once per process (:func:`_shared_sheets`)."""
    global _HTML_CLASS
    if _HTML_CLASS is None:
        from weasyprint import CSS, HTML
        from weasyprint import html as _wp_html
        from weasyprint.css.counters import CounterStyle

        from . import fasthtml, wpfast, wpsplit

        ua = _wp_html.UA.replace("\n::marker {", "\nli::marker {")
        ua = "\n".join(line for line in ua.splitlines()
                       if not line.startswith(("::footnote-", "::note-")))
        sheet = CSS(string=ua, counter_style=CounterStyle())

        class _HTML(HTML):
            def __init__(self, guess=None, *, string=None, base_url=None, url_fetcher=None,
                         media_type="print", **kwargs):
                if guess is not None or kwargs or not fasthtml.init_html(self, string, base_url, url_fetcher,
                                                                         media_type):
                    super().__init__(guess, string=string, base_url=base_url, url_fetcher=url_fetcher,
                                     media_type=media_type, **kwargs)
                self._source = string

            def _ua_stylesheets(self, forms=False):
                return [sheet, _wp_html.UA_FORM_STYLESHEET] if forms else [sheet]

            def render(self, font_config=None, counter_style=None, color_profiles=None, **options):
                shared = _shared_sheets(self, font_config)
                if shared:
                    options["stylesheets"] = [*(options.get("stylesheets") or []), *shared]
                # a text's first line in a width measured once per process; Pango settings made once per
                # font; a style's strut computed once
                with wpsplit.first_lines(), wpfast.text_layouts(), wpfast.line_struts():
                    return super().render(font_config, counter_style, color_profiles, **options)

        _HTML_CLASS = _HTML
    return _HTML_CLASS


_SHEETS: dict = {}  # (stylesheet text, base URL, media type) -> (font configuration, parsed CSS)
SHEETS_PARSED = [0]  # stylesheets parsed by _shared_sheets in this process (tests)


def _shared_sheets(html, font_config) -> list:
    """The document's own stylesheet (the ``<style>`` of gost.css and math.css), parsed once per
    process and handed to WeasyPrint as a parsed sheet: the ~10 documents of a note (its parts,
    the title page, the contents) carry the same stylesheet text, which WeasyPrint would parse
    again for each (0.024–0.027 s CPU). The ``<style>`` element is emptied, and its rules come
    back as a *user* sheet, the only one: the cascade is the same as long as nothing else but
    the user agent's sheet sets properties (the other ``<style>``, of ``@font-face`` rules, is
    left to WeasyPrint) and no ``!important`` outside it would meet one of its own (checked on
    the HTML text). Anything else (``@import``, ``@font-face``, ``@counter-style``, children,
    a ``media`` or ``type`` attribute) keeps WeasyPrint's own way."""
    from weasyprint import CSS

    source = getattr(html, "_source", None)
    if font_config is None or not isinstance(source, str):
        return []
    found = []
    for el in html.etree_element.iter("style"):
        text = el.text or ""
        if len(el) or el.get("media") is not None or el.get("type") is not None or len(text) < 1000 \
                or any(w in text for w in ("@import", "@font-face", "@counter-style")):
            continue
        found.append((el, text))
    if len(found) != 1 or source.count("!important") != found[0][1].count("!important"):
        return []
    el, text = found[0]
    key = (text, html.base_url, html.media_type)
    kept = _SHEETS.get(key)
    if kept is None or kept[0] is not font_config:
        if len(_SHEETS) > 8:
            _SHEETS.clear()
        kept = _SHEETS[key] = (font_config, CSS(string=text, base_url=html.base_url, url_fetcher=html.url_fetcher,
                                                media_type=html.media_type, font_config=font_config))
        SHEETS_PARSED[0] += 1
    el.text = ""
    return [kept[1]]


def _layout(report: Report, font_config):
    """Lay out the print HTML, splitting tables until stable. Returns the document."""
    from . import svgops
    from .relayout import incremental
    from .safety import url_fetcher

    HTML = _html_class()

    fetcher = url_fetcher()
    image_cache = _image_cache()  # parsed images (figures, formulas) shared by the passes and the process
    _quiet_weasyprint()
    splits: dict[str, list[int]] = {}
    stats = RenderStats()
    document = None
    key, guesses = None, ()
    start = ""
    views = _views(report, for_print=True, splits=splits)
    state: dict = {}  # of the fast passes (_settle_step)
    laid: list = []  # the last pass's layout (relayout.Laid)
    for i in range(MAX_PASSES):
        t0 = time.perf_counter()
        views.builder.resplit(splits)  # (numbering and rows do not depend on the split points)
        html = _checked_html(views)
        if i == 0:
            # The same report laid out again (batch re-runs, determinism checks), or a similar
            # one (another variant, a changed length), starts from split points remembered;
            # they are kept only when the passes from none provably give them.
            key, guesses, splits, start = _start_splits(html)
            if start:
                views.builder.resplit(splits)
                html = _checked_html(views)
        t1 = time.perf_counter()
        svgops.prime(image_cache, html)  # figures drawn from precompiled PDF operators
        with incremental(laid[-1] if laid else None, laid):  # the pages before the change taken over
            document = HTML(string=html, base_url=str(TEMPLATES_DIR), url_fetcher=fetcher).render(
                font_config=font_config, cache=image_cache)
        del laid[:-1]
        t2 = time.perf_counter()
        stats.passes += 1
        stats.seconds_html += t1 - t0
        stats.seconds_layout += t2 - t1
        new, start = _next_pass(document, splits, start, state)
        if new is None:
            break
        splits = new
    else:
        log.warning("Разбиение таблиц не сошлось за %d проходов", MAX_PASSES)
    if key is not None:
        _remember_result(key, guesses, splits, start)
    stats.pages = len(document.pages)
    stats.splits = splits
    return document, stats


_FONT_CONFIG = None


def _font_config():
    """One WeasyPrint font configuration per process: @font-face files are
    loaded once (the same files for every report)."""
    global _FONT_CONFIG
    if _FONT_CONFIG is None:
        from weasyprint.text.fonts import FontConfiguration

        _FONT_CONFIG = FontConfiguration()
    return _FONT_CONFIG


# fontTools stamps the ``head.modified`` field of every font subset it writes with the
# current time unless SOURCE_DATE_EPOCH is set (reproducible-builds.org); WeasyPrint subsets
# with fontTools when HarfBuzz-Subset is missing, so without a fixed stamp two PDFs of the
# same report differ in their embedded fonts. A date given by the user is kept.
PDF_SOURCE_DATE_EPOCH = "0"


@contextlib.contextmanager
def _fixed_font_timestamp():
    """``SOURCE_DATE_EPOCH`` set for the duration of ``write_pdf`` (restored after)."""
    if "SOURCE_DATE_EPOCH" in os.environ:
        yield
        return
    os.environ["SOURCE_DATE_EPOCH"] = PDF_SOURCE_DATE_EPOCH
    try:
        yield
    finally:
        os.environ.pop("SOURCE_DATE_EPOCH", None)


def _parts_job(report: Report, jobs: int | None = None):
    """A :class:`~reportgen.report.parallel.PartsJob` for ``report`` when the note can be laid
    out in parts (see :func:`~reportgen.report.parallel.can_split`), else ``None``."""
    from . import parallel

    if os.environ.get("REPORTGEN_PARTS", "1") == "0" or not parallel.can_split(resolve_options(report.options)):
        return None
    return parallel.PartsJob(report, parallel.note_jobs() if jobs is None else jobs)


def _finish_parts(job, path) -> Path:
    global last_stats
    pdf = job.finish()
    st = job.stats
    last_stats = RenderStats(passes=st.passes, pages=st.pages, seconds_html=st.seconds_html,
                             seconds_layout=st.seconds_layout, seconds_pdf=st.seconds_write + st.seconds_join,
                             splits=st.splits, parts=st)
    return _atomic_write(Path(path), pdf)


def write_pdf(report: Report, path, *, jobs: int | None = None) -> Path:
    """Write the PDF atomically (WeasyPrint; «Продолжение таблицы» in passes): laid out in
    parts by ``jobs`` processes (default :func:`~reportgen.report.parallel.note_jobs`) and
    joined when the note allows it, else as one document."""
    global last_stats
    job = _parts_job(report, jobs)
    if job is not None:
        return _finish_parts(job, path)
    document, stats = _layout(report, _font_config())
    t0 = time.perf_counter()
    from .wpfast import writing
    with _fixed_font_timestamp(), writing():
        pdf = document.write_pdf()
    stats.seconds_pdf = time.perf_counter() - t0
    last_stats = stats
    return _atomic_write(Path(path), pdf)


@contextlib.contextmanager
def _older_objects_frozen():
    """The objects alive on entry (the study, the report, the imported modules: some hundred
    thousand) left out of the garbage collector's passes until exit (``gc.freeze``): rendering
    the HTML allocates enough to start several full collections, each of which would walk them
    all again. On exit they are collected as before (``gc.unfreeze``); nothing is done when
    something else has frozen objects already."""
    import gc

    if gc.get_freeze_count():
        yield
        return
    gc.freeze()
    try:
        yield
    finally:
        gc.unfreeze()


def build_outputs(report: Report, out_dir, stem: str,
                  formats=("pdf", "html")) -> dict[str, Path]:
    """Write ``out_dir/stem.pdf`` and/or ``out_dir/stem.html``; returns the paths. The parts of
    the PDF are laid out by the workers while this process writes the HTML."""
    with _build_scope():
        return _build_outputs(report, out_dir, stem, formats)


@contextlib.contextmanager
def _build_scope():
    """What one build's HTML stages share: the older objects left out of the garbage
    collector's passes, the tables' cells formatted once."""
    with _older_objects_frozen(), _cells_shared():
        yield


def _build_outputs(report: Report, out_dir, stem: str, formats) -> dict[str, Path]:
    from .safety import write_together
    for f in formats:
        if f not in ("pdf", "html"):
            raise ValueError(f"Неизвестный формат вывода: {f!r} (допустимы pdf, html)")
    writers = {}
    job = _parts_job(report) if "pdf" in formats else None
    if "html" in formats:
        writers["html"] = lambda p: write_html(report, p)
    if "pdf" in formats:
        writers["pdf"] = (lambda p: _finish_parts(job, p)) if job is not None else (lambda p: write_pdf(report, p))
    try:
        written = write_together(Path(out_dir), stem, writers)
        return {f: written[f] for f in formats if f in written}
    finally:
        if job is not None:
            job.close()
