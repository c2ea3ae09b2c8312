"""The document model of a report: plain dataclasses.

Scenes and section builders fill these; :mod:`reportgen.report.render` numbers
everything (sections, figures, tables, formulas) and formats it with the
templates. Templates only format what they are given.

HTML strings in the model (paragraphs, captions, column headers, «где»
descriptions) are trusted markup written by the project's own code: they may
contain ``<b>``, ``<i>``, ``<sub>``, ``&nbsp;``, inline math
(:func:`reportgen.report.formulas.inline_math`) and cross-references made with
:func:`ref`. Cell values from DataFrames are escaped.

Cross-references: ``ref("fig-kin")`` writes a placeholder that the renderer
replaces by the number of the target: «1.2» for a section, figure or table,
«(1.2)» for a formula, «А» for an appendix. So a paragraph says
``f"Планы скоростей приведены на рисунке {ref('fig-v')}."``. An unknown id is
an error at render time.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

from .formulas import Formula
from ..style.numbers import fmt as _fmt

__all__ = [
    "Column",
    "Table",
    "Figure",
    "Paragraph",
    "FormulaBlock",
    "Section",
    "Report",
    "Formula",
    "ref",
    "freeze",
]


def ref(target_id: str) -> str:
    """A cross-reference placeholder, filled with the target's number at render time."""
    return f'<a class="ref" href="#{target_id}"></a>'


@dataclass
class Column:
    """One table column: which DataFrame column and how to print it."""

    key: str  # DataFrame column
    header: str  # HTML (e.g. "φ<sub>3</sub>"), or LaTeX when latex=True
    unit: str | None = None  # printed in the header as ", град" (or in a units row)
    digits: int | None = None
    sig: int | None = 4
    fmt: Callable[[Any], str] | None = None  # overrides digits/sig
    latex: bool = False  # header is LaTeX, rendered with ziamath

    def format(self, value) -> str:
        """The cell text of ``value`` (numbers through :func:`numbers.fmt`)."""
        if self.fmt is not None:
            return self.fmt(value)
        return _fmt(value, digits=self.digits, sig=self.sig)


@dataclass
class Table:
    """A table with caption above; split across pages with «Продолжение таблицы»."""

    caption: str
    columns: list[Column]
    data: Any  # pandas.DataFrame
    id: str | None = None
    note: str | None = None  # «Примечание — …» under the table (HTML)
    index_header: str | None = None  # show the DataFrame index as the first column
    highlight_rows: list[int] | tuple[int, ...] = ()  # positional row numbers printed bold
    units_row: bool = False  # units in a separate header row instead of ", unit"
    index_fmt: Callable[[Any], str] | None = None  # how to print index values


@dataclass
class Figure:
    """A figure: SVG (matplotlib via mplstyle.to_svg, or any SVG), or PNG bytes."""

    caption: str
    svg: bytes | str
    width_mm: float = 160
    id: str | None = None
    landscape: bool = False  # on a page of its own turned to landscape (ГОСТ 7.32: a wide figure)


@dataclass
class Paragraph:
    """A paragraph of trusted HTML (a block starting with <ul>, <ol>, <div>,
    <table> or <p> is emitted as it is)."""

    html: str


@dataclass
class FormulaBlock:
    """Consecutive numbered display formulas."""

    formulas: list[Formula]


@dataclass
class Section:
    """A numbered section (level 1: «1», level 2: «1.2», level 3: «1.2.1»)."""

    title: str
    id: str
    children: list = field(default_factory=list)
    numbered: bool = True
    level: int = 1

    def add(self, block):
        """Append any block (Paragraph, Figure, Table, FormulaBlock, Section)."""
        self.children.append(block)
        return block

    def paragraph(self, html: str) -> Paragraph:
        return self.add(Paragraph(html))

    def figure(self, caption: str, svg, width_mm: float = 160, id: str | None = None,
               landscape: bool = False) -> Figure:
        """Add a figure; ``svg`` may also be a matplotlib ``Figure`` (converted here);
        ``landscape``: on its own landscape page, up to the landscape text width."""
        if hasattr(svg, "savefig"):
            from ..style.mplstyle import to_svg

            svg = to_svg(svg)
        return self.add(Figure(caption, svg, width_mm, id, landscape))

    def table(self, caption: str, columns: list[Column], data, id: str | None = None,
              **kw) -> Table:
        return self.add(Table(caption, columns, data, id=id, **kw))

    def formula(self, *formulas, **kw) -> FormulaBlock:
        """Add formulas: ``formula(Formula(...), Formula(...))`` or, for one formula,
        ``formula(r"\\omega_1 = …", substituted=…, result=…, where=…, label=…)``.
        """
        if formulas and isinstance(formulas[0], str):
            items = [Formula(formulas[0], *formulas[1:], **kw)]
        else:
            if kw:
                raise TypeError("keyword arguments are only accepted for a single formula "
                                "given as LaTeX")
            items = list(formulas)
        return self.add(FormulaBlock(items))

    def subsection(self, title: str, id: str, numbered: bool = True) -> "Section":
        if self.level >= 3:
            raise ValueError("ГОСТ 7.32: не более трёх уровней рубрикации (раздел, "
                             "подраздел, пункт)")
        return self.add(Section(title, id, numbered=numbered, level=self.level + 1))


@dataclass
class Report:
    """A whole «пояснительная записка».

    ``meta`` keys: ministry, university, faculty, department, discipline,
    topic, variant, student, group, supervisor, supervisor_title, city, year,
    doc_code (ЕСКД designation for the stamp), document (default
    «ПОЯСНИТЕЛЬНАЯ ЗАПИСКА»), work (default «к курсовому проекту»).
    ``options``: see ``render.DEFAULT_OPTIONS``.
    """

    meta: dict
    assignment: list
    introduction: list
    sections: list[Section]
    conclusion: list
    references: list[str]
    appendices: list[Section] | tuple = ()
    options: dict = field(default_factory=dict)


class _Texts:
    """A column's printed texts by value: a formatter that crosses processes (a section
    module's ``fmt`` is often a lambda, which ``pickle`` cannot carry)."""

    def __init__(self, fmt: Callable[[Any], str], values):
        self.texts = {}
        for v in values:
            try:
                missing = v is None or bool(v != v)  # None, NaN: printed as a dash, never formatted
            except TypeError:  # pandas.NA
                missing = True
            if not missing and v not in self.texts:
                self.texts[v] = fmt(v)

    def __call__(self, value) -> str:
        return self.texts[value]


def freeze(block):
    """``block`` (a Section and everything in it) made picklable: every table's ``fmt`` and
    ``index_fmt`` replaced by the texts they give for the table's own values (the same cells
    are printed; columns are copied, as a section may share them between tables). Used to
    send a section built in a worker process back."""
    from dataclasses import replace

    if isinstance(block, Section):
        block.children = [freeze(child) for child in block.children]
    elif isinstance(block, Table):
        cols = []
        for col in block.columns:
            if col.fmt is not None and not isinstance(col.fmt, _Texts):
                values = block.data[col.key].tolist() if col.key in block.data.columns else []
                col = replace(col, fmt=_Texts(col.fmt, values))
            cols.append(col)
        block = replace(block, columns=cols)
        if block.index_fmt is not None and not isinstance(block.index_fmt, _Texts):
            block.index_fmt = _Texts(block.index_fmt, list(block.data.index))
    return block
