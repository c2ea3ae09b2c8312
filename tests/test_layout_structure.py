"""The print HTML is shaped so that WeasyPrint shares computed styles between elements.

WeasyPrint 70 makes an element's id a style property (``-weasy-anchor``): an element with an
id, and every element inside it, gets a computed style of its own, each property computed
again. So in the print HTML no element with many descendants carries an id: table rows are
named by ``data-row`` (found in the page boxes by ``render._named_rows``), a table's anchor is
its caption row and a formula's anchor is its empty, out-of-flow ``eq-pad``. The anchors stay
where they were (the link targets of the PDF do not move) and the number of computed styles
of a table no longer grows with its rows. Counts, never times: docs/performance.md measures
the CPU.
"""
from __future__ import annotations

import re

import numpy as np
import pandas as pd
import pytest

from reportgen.report import parallel, render
from reportgen.report.document import Column, Report, Section


def _report(rows: int) -> Report:
    df = pd.DataFrame({"a": np.arange(rows) * 1.5, "b": np.arange(rows) * 0.25 + 1.0})
    s = Section("Раздел", "s")
    s.paragraph("Текст перед формулой (формула [[eq-w]]) и таблицей (таблица [[tab-t]]).")
    s.formula(r"\omega_1 = \frac{\pi n_1}{30}", substituted=r"\frac{3{,}14 \cdot 60}{30}",
              result=r"6{,}28\ \text{рад/с}", where=[(r"n_1", "частота вращения")], label="eq-w")
    s.table("Проверка", [Column("a", "a", digits=3), Column("b", "b", digits=3)], df, id="tab-t")
    return Report(meta={}, assignment=[], introduction=[], sections=[s], conclusion=[],
                  references=[], options={"title_page": False, "assignment_page": False})


def _body(html: str) -> str:
    return html[html.index("<main>"):]


def test_print_html_has_no_id_over_rows_or_formulas():
    html = _body(render.render_html(_report(30), for_print=True))
    assert html.count('data-row="tab-t__r') == 30
    assert not re.search(r"<tr [^>]*\bid=\"[^\"]*__r\d+\"", html)
    assert not re.search(r"<table [^>]*\bid=", html)  # the anchor is the caption row
    assert '<tr class="cap" id="tab-t">' in html
    assert not re.search(r'<div class="eq( eq-where)?" id=', html)
    assert '<div class="eq-pad" id="eq-w"></div>' in html


def test_screen_html_keeps_its_anchors():
    html = _body(render.render_html(_report(30), for_print=False))
    assert '<table class="tbl" id="tab-t">' in html
    assert '<div class="eq eq-where" id="eq-w">' in html or '<div class="eq" id="eq-w">' in html
    assert "data-row" not in html


def _count_styles(monkeypatch):
    """Count the computed styles WeasyPrint creates (one per style that is not shared)."""
    import weasyprint.css as wcss

    seen = {"n": 0}
    init = wcss.ComputedStyle.__init__

    def counting(self, *a, **k):
        seen["n"] += 1
        init(self, *a, **k)

    monkeypatch.setattr(wcss.ComputedStyle, "__init__", counting)
    return seen


@pytest.fixture
def laid_out(monkeypatch):
    seen = _count_styles(monkeypatch)

    def lay_out(rows: int):
        seen["n"] = 0
        doc = parallel._lay_out(render.render_html(_report(rows), for_print=True))
        return doc, seen["n"]

    return lay_out


def test_computed_styles_do_not_grow_with_rows(laid_out):
    """10 and 20 rows (the same pages: contents, then the section): the same number of computed
    styles. With an id per row the 20-row table needed 30 more (the row and its two cells)."""
    doc10, n10 = laid_out(10)
    doc20, n20 = laid_out(20)
    assert len(doc10.pages) == len(doc20.pages)
    assert n20 == n10


def test_rows_found_and_anchors_at_the_table_and_formula_corners(laid_out):
    from weasyprint.formatting_structure import boxes as wb

    doc, _ = laid_out(20)
    rows, where = render._page_rows(doc, with_boxes=True)
    p = rows["tab-t"][0]
    assert rows == {"tab-t": {r: p for r in range(20)}}
    page = doc.pages[p]
    anchors = page.anchors
    found = {}

    def walk(b):
        cls = (b.element.get("class") or "") if getattr(b, "element", None) is not None else ""
        if isinstance(b, wb.TableBox) and "tbl" in cls.split():
            found.setdefault("table", b)
        if isinstance(b, wb.BlockBox) and cls.split()[:1] == ["eq"]:
            found.setdefault("eq", b)
        if isinstance(b, wb.TableRowBox) and b.element.get("data-row") == "tab-t__r0":
            found["row0"] = b
        for c in getattr(b, "children", ()):
            walk(c)

    walk(page._page_box)
    t, e, r0 = found["table"], found["eq"], found["row0"]
    assert anchors["tab-t"][:2] == pytest.approx((t.border_box_x(), t.border_box_y()), abs=1e-9)
    assert anchors["eq-w"][:2] == pytest.approx((e.border_box_x(), e.border_box_y()), abs=1e-9)
    assert where["tab-t"][0] == pytest.approx((r0.border_box_y(), r0.border_box_y() + r0.border_height()))
