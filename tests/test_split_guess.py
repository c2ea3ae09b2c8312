"""Split points guessed from a similar note (another variant, a case with one length changed).

The layout made with a guess is kept only when it is proved, on that one layout, to be the
canonical one (render._settle_step: each table's passes run on a model of its rows); a wrong
table entry is set right from the same layout, one the model cannot decide is set back to none.
So a guess saves passes and never changes a byte: (a) a variant laid out after another one
takes fewer passes and gives the PDF of a build with nothing remembered, (b) a guess that
``_next_splits`` accepts but that is not the canonical one (a loose cut, a last part too short)
is set right, (c) a wrong guess costs passes, never a different page.
"""
from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from test_report_render import _FakeDoc, _FakePage, _rows

from reportgen.report import render
from reportgen.report.document import Column, Report, Section

H = 20.0  # row height of the fake documents; pages: content from 75 to 1047 px (48 rows)


def _doc(*pages, head=40.0, table_top=None):
    """A fake laid-out document of table ``t``: ``pages`` are (first row, last row, top of the
    first row); the table's own anchor ``head`` above its first row."""
    doc = _FakeDoc(*(_FakePage(_rows("t", a, b, top, H)) for a, b, top in pages))
    first = pages[0][2]
    doc.pages[0].anchors["t"] = (80.0, first - head if table_top is None else table_top, 700.0, first)
    return doc


def test_tight_guess_is_kept():
    """A guess whose cut is tight (row 30 ends below the page) and whose continuation header is
    as high as the table's own: the table's passes from none, run on its rows, give it."""
    doc = _doc((0, 29, 1047.0 - 30 * H - 10.0), (30, 40, 75.0 + 40.0), head=40.0)
    assert render._next_splits(doc, {"t": [30]}) is None
    assert render._settle_step(doc, {"t": [30]}, {}) is None
    assert render._table_verdict(*_verdict_args(doc, [30])) == ("ok", None, True)


def _verdict_args(doc, cur):
    rows, boxes = render._page_rows(doc, with_boxes=True)
    bottoms = render._content_bottoms(doc)
    tops = [75.0] * len(bottoms)
    return rows["t"], boxes["t"], doc.pages[0].anchors["t"][1], tops, bottoms, cur, None


def test_loose_guess_is_set_right_from_its_own_layout():
    """Cut one row early: the page before keeps 30 px under its last row, room for row 29
    (20 px). Not premature (far less than a quarter of the page), so ``_next_splits`` accepts it,
    but the passes from none keep row 29 on the first page: the canonical cut (30) comes from
    the rows of this layout, without a pass from none."""
    doc = _doc((0, 28, 1047.0 - 29 * H - 30.0), (29, 40, 75.0 + 40.0), head=40.0)
    assert render._next_splits(doc, {"t": [29]}) is None
    assert render._settle_step(doc, {"t": [29]}, {}) == {"t": [30]}
    # a remembered entry of this very HTML was written by the canonical passes: it is kept
    assert render._next_pass(doc, {"t": [29]}, "known", {}) == (None, "known")


def test_rules_that_loosen_cuts_are_followed():
    """A last part kept at MIN_PART_ROWS rows (the canonical cut moves up: _tidy_cuts) is set
    right; a continuation header lower than the table's own (a two-line caption repeated whole
    on the pages of the unsplit table) does not move the cut at the page start, so it is kept;
    a table moved to a new page (split point 0) with nothing known of the text before it is not
    decided here: set back to none, the next layout shows it unsplit."""
    short_last = _doc((0, 37, 1047.0 - 38 * H - 10.0), (38, 39, 75.0 + 40.0))
    assert render._settle_step(short_last, {"t": [38]}, {}) == {"t": [37]}
    two_lines = _doc((0, 29, 1047.0 - 30 * H - 10.0), (30, 40, 75.0 + 40.0), head=62.0)
    assert render._settle_step(two_lines, {"t": [30]}, {}) is None
    moved = _doc((0, 45, 75.0 + 40.0), (46, 60, 75.0 + 40.0))
    assert render._next_splits(moved, {"t": [0, 46]}) is None
    assert render._settle_step(moved, {"t": [0, 46]}, {}) == {}


def test_layout_the_model_does_not_match_is_not_decided():
    """A part of the guess running past its page bottom in the layout (rows the model would put
    on the next page): the rows' model does not hold, so nothing is read from it: the table is
    set back to none (the next layout shows it unsplit, decided by the literal rule)."""
    doc = _doc((0, 29, 1047.0 - 30 * H - 10.0), (30, 79, 75.0 + 40.0), (80, 90, 75.0 + 40.0))
    assert render._table_verdict(*_verdict_args(doc, [30]))[0] == "unknown"
    assert render._settle_step(doc, {"t": [30]}, {}) == {}


def test_row_at_the_page_bottom_is_not_decided_by_the_model():
    """A row of the unsplit table that would end within SIM_MARGIN of the page bottom: which
    page WeasyPrint gives it is not the model's to say."""
    top = 1047.0 - 30 * H  # rows 0-29 end exactly at the bottom
    doc = _doc((0, 29, top), (30, 40, 75.0 + 40.0), head=40.0)
    assert render._table_verdict(*_verdict_args(doc, [30]))[0] == "unknown"


def test_shape_key_ignores_numbers_and_images():
    a = ('<td class="num">12,5</td><td>\u22120,4</td><p>R = 1\u202f234 Н, +0,3 %</p>'
         '<img src="data:image/svg+xml;base64,QUJD" style="width:80.0mm"><h2>2.1 Кинематика</h2>')
    b = ('<td class="num">3,75</td><td>0,5</td><p>R = 987 Н, \u22120,1 %</p>'
         '<img src="data:image/svg+xml;base64,WFla" style="width:80mm"><h2>2.1 Кинематика</h2>')
    assert render._shape_key(a) == render._shape_key(b)
    assert render._shape_key('<meta name="author" content="Иванов И. И.">' + a) == render._shape_key(
        '<meta name="author" content="Петров П. П.">' + b)
    assert render._shape_key(a) != render._shape_key(a.replace("Кинематика", "Динамика"))
    assert render._split_key(a) != render._split_key(b)


def test_skeleton_key_keeps_only_headings_figures_and_tables_in_order():
    """The coarser key of a guess: the same for another text (a paragraph more, other words),
    another for a figure on a page of its own (class ``landscape``), a figure moved past a
    table, or another table."""
    fig = '<figure class="fig" id="fig-a"><img src="data:image/svg+xml;base64,QUJD"></figure>'
    tab = '<table class="tbl"><tr class="cap" id="tab-b"><td>Таблица</td></tr><tr data-row="t__r0"></tr></table>'
    head = '<h2 class="numbered" id="sec-x">2.1 Кинематика</h2>'
    a = head + "<p>Текст.</p>" + fig + "<p>Ещё.</p>" + tab
    key = render._skeleton_key
    assert key(a) == key(head + "<p>Другой текст, длиннее.</p><p>И абзац.</p>" + fig + tab)
    assert key(a) != key(a.replace('class="fig"', 'class="fig landscape"'))
    assert key(a) != key(head + tab + fig)
    assert key(a) != key(a.replace("tab-b", "tab-c"))
    assert render._shape_key(a) != render._shape_key(a.replace("Ещё.", "Ещё.</p><p>Абзац."))


# ---------------------------------------------------------------- real layouts (WeasyPrint)


def _report(scale: float, filler: int = 14, rows: int = 60) -> Report:
    """A note with one section: ``filler`` paragraphs, then a table running over two pages
    whose numbers depend on ``scale`` (another variant of the same case)."""
    df = pd.DataFrame({"a": np.arange(rows) * scale, "b": np.arange(rows) * 0.5 * scale + 1.0})
    s = Section("Раздел", "s")
    for _ in range(filler):
        s.paragraph("Строка текста, которая занимает место на странице перед таблицей.")
    s.table("Проверка", [Column("a", "a", digits=3), Column("b", "b", digits=3)], df, id="t")
    return Report(meta={}, assignment=[], introduction=[], sections=[s], conclusion=[],
                  references=[], options={"title_page": False, "assignment_page": False})


@pytest.fixture
def empty_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("REPORTGEN_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(render, "_SPLIT_MEMO", {})
    return tmp_path


def _pdf(report, path):
    render.write_pdf(report, path, jobs=1)
    st = render.last_stats.parts
    return path.read_bytes(), st.part_passes, dict(st.splits)


def test_variant_after_another_is_laid_out_once_and_equals_a_cold_build(empty_cache):
    """(a) B after A: B starts from A's split points (shape key), lays its table out once and
    gives the bytes of B built with nothing remembered."""
    tmp = empty_cache
    _a, a_passes, a_splits = _pdf(_report(1.0), tmp / "a.pdf")
    assert a_passes == [2] and a_splits["t"]
    guessed, b_passes, b_splits = _pdf(_report(1.37), tmp / "b.pdf")
    assert b_passes == [1]
    render._SPLIT_MEMO.clear()
    (tmp / "cache").rename(tmp / "old")  # nothing remembered on disk either
    cold, cold_passes, cold_splits = _pdf(_report(1.37), tmp / "b-cold.pdf")
    assert cold_passes == [2]
    assert b_splits == cold_splits and guessed == cold


def test_wrong_guess_costs_passes_never_a_page(empty_cache):
    """(c) A guess from a note whose table starts lower (more text before it): the cut it brings
    is loose here, so the table's right cut is read from the rows of that same layout (no pass
    from none): one pass more, the bytes of a cold build. A damaged cache file is no guess at
    all."""
    tmp = empty_cache
    _pdf(_report(1.0, filler=14), tmp / "a.pdf")
    key = next(iter(render._SPLIT_MEMO))
    guess = render._SPLIT_MEMO[key]
    other = _report(1.0, filler=10)
    html = render._views(other, for_print=True, splits={}).html(
        front=False, body=[render._views(other, for_print=True, splits={}).ctx["body"][0]], chunk=True)
    render._SPLIT_MEMO[render._shape_key(html)] = guess  # as if a similar note had left it
    guessed, passes, splits = _pdf(other, tmp / "b.pdf")
    assert passes == [2]  # the wrong guess, then the table's canonical cut
    render._SPLIT_MEMO.clear()
    for f in (tmp / "cache").rglob("*.json"):
        f.write_text("{damaged", encoding="utf-8")
    cold, cold_passes, cold_splits = _pdf(other, tmp / "b-cold.pdf")
    assert cold_passes == [2] and cold_splits == splits and cold == guessed


def _report_with_tail(tail: int) -> Report:
    """:func:`_report` with ``tail`` paragraphs after its table (a note with more text at the end)."""
    report = _report(1.0)
    for _ in range(tail):
        report.sections[0].paragraph("Вывод по таблице, который занимает место после неё.")
    return report


def test_other_text_after_a_table_takes_the_guess_of_the_same_skeleton(empty_cache):
    """A note with a paragraph more after its table (another shape key: the neighbour's split
    points are not found under it) starts from the split points of the note with the same
    headings, figures and tables (the skeleton key): laid out once, where from none it takes
    two layouts, and the bytes of that note built with nothing remembered."""
    tmp = empty_cache
    _a, a_passes, a_splits = _pdf(_report_with_tail(2), tmp / "a.pdf")
    assert a_passes == [2] and a_splits["t"]
    b = _report_with_tail(3)
    one = render._views(b, for_print=True, splits={})
    html = one.html(front=False, body=[one.ctx["body"][0]], chunk=True)
    assert render._recall_splits(render._shape_key(html)) is None
    guessed, b_passes, b_splits = _pdf(b, tmp / "b.pdf")
    assert b_passes == [1]
    render._SPLIT_MEMO.clear()
    (tmp / "cache").rename(tmp / "old")
    cold, cold_passes, cold_splits = _pdf(b, tmp / "b-cold.pdf")
    assert cold_passes == [2]
    assert b_splits == cold_splits and guessed == cold


def test_real_variant_after_another(empty_cache):
    """The one real check: the kinematics of two variants of ws000 (the class table's rows 02
    and 03): the second takes its long tables' split points from the first, lays the part out
    once, and its PDF is the bytes of the second built with nothing remembered."""
    from conftest import CASES

    from reportgen.analysis.study import Study
    from reportgen.case.load import load_spec
    from reportgen.report.assemble import build_report

    tmp = empty_cache

    def note(l_oa: str, l_ab: str, y_h: str):
        spec = load_spec(CASES / "ws000_six_bar.toml", {"l_OA": l_oa, "l_AB": l_ab, "Y_H": y_h})
        return build_report(Study(spec), ["structure", "kinematics"])

    _a, a_passes, a_splits = _pdf(note("0.303 m", "1.410 m", "0.87 m"), tmp / "a.pdf")
    b = note("0.306 m", "1.420 m", "0.89 m")
    guessed, b_passes, b_splits = _pdf(b, tmp / "b.pdf")
    render._SPLIT_MEMO.clear()
    (tmp / "cache").rename(tmp / "old")
    cold, cold_passes, cold_splits = _pdf(b, tmp / "b-cold.pdf")
    long = [i for i, n in enumerate(cold_passes) if n > 1]
    assert long and all(b_passes[i] < cold_passes[i] for i in long), (b_passes, cold_passes)
    assert b_splits == cold_splits and guessed == cold
