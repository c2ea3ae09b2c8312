"""Rendering layer: a synthetic report to PDF and HTML, checked through
poppler (pdftotext, pdffonts), determinism, self-contained HTML, and an HTML
snapshot of one table fragment (syrupy, single .html file)."""

from __future__ import annotations

import hashlib
import math
import re
import subprocess
import warnings

import numpy as np
import pandas as pd
import pytest
from conftest import normalize_html

from reportgen.report import render
from reportgen.style import fonts, mplstyle
from reportgen.report.demo import build_demo_report
from reportgen.report.document import (
    Column,
    Figure,
    Formula,
    FormulaBlock,
    Paragraph,
    Report,
    Section,
    Table,
    ref,
)
from reportgen.report.formulas import (
    MATH_SCALE,
    formula_images,
    inline_math,
    render_latex,
)



# ---------------------------------------------------------------- fixtures


@pytest.fixture(scope="module")
def demo():
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)  # e.g. missing glyphs
        return build_demo_report()


@pytest.fixture(scope="module")
def outputs(demo, tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    # the split points found by an earlier build (this process or the disk cache) would spare
    # the passes this fixture is about: lay the demo out with nothing remembered
    render._SPLIT_MEMO.clear()
    mp = pytest.MonkeyPatch()
    mp.setenv("REPORTGEN_CACHE", str(tmp_path_factory.mktemp("cache")))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", RuntimeWarning)
            paths = render.build_outputs(demo, out, "demo")
    finally:
        mp.undo()
    return paths | {"stats": render.last_stats}


def pdftotext(path, first=None, last=None, layout=False) -> str:
    cmd = ["pdftotext", "-enc", "UTF-8"]
    if layout:
        cmd.append("-layout")
    if first:
        cmd += ["-f", str(first)]
    if last:
        cmd += ["-l", str(last)]
    return subprocess.run(cmd + [str(path), "-"], check=True, capture_output=True,
                          text=True).stdout


def pdf_pages(path) -> list[str]:
    return pdftotext(path).split("\f")[:-1]


# ---------------------------------------------------------------- PDF


def test_page_count_and_passes(outputs):
    pages = pdf_pages(outputs["pdf"])
    assert 10 <= len(pages) <= 15
    stats = outputs["stats"]
    assert stats.pages == len(pages)
    assert 2 <= stats.passes <= 4
    # the 60-row table was split, and no part is a stub
    cuts = [c for c in stats.splits["tab-kin"] if c]
    bounds = [0] + cuts + [60]
    assert all(b - a >= 10 for a, b in zip(bounds, bounds[1:]))


def test_toc_lines_with_page_numbers(outputs):
    pages = pdf_pages(outputs["pdf"])
    toc_page = next(i for i, p in enumerate(pages) if "СОДЕРЖАНИЕ" in p)
    toc = pages[toc_page]
    entries = {}
    for line in toc.splitlines():
        m = re.match(r"^(.*?)\s*\.{5,}\s*(\d+)$", line.strip())
        if m:
            entries[m.group(1)] = int(m.group(2))
    expected = ["ВВЕДЕНИЕ", "1 Структурный и кинематический анализ механизма",
                "1.1 Степень подвижности механизма", "1.2 Скорости и ускорения ползуна",
                "2 Анализ результатов", "ЗАКЛЮЧЕНИЕ", "СПИСОК ИСПОЛЬЗОВАННЫХ ИСТОЧНИКОВ",
                "Приложение А Исходный текст расчёта"]
    assert list(entries) == expected
    # page numbers increase and point at the pages that carry the headings
    numbers = list(entries.values())
    assert numbers == sorted(numbers) and numbers[0] > toc_page + 1
    assert "ВВЕДЕНИЕ" in pages[entries["ВВЕДЕНИЕ"] - 1]
    assert "2 Анализ результатов" in pages[entries["2 Анализ результатов"] - 1]
    assert "ЗАКЛЮЧЕНИЕ" in pages[entries["ЗАКЛЮЧЕНИЕ"] - 1]


def test_captions_numbers_and_commas(outputs):
    text = pdftotext(outputs["pdf"]).replace("\u00a0", " ")
    for needle in ["ПОЯСНИТЕЛЬНАЯ ЗАПИСКА", "ЗАДАНИЕ", "Таблица 1.1 — Кинематические",
                   "Продолжение таблицы 1.1", "Рисунок 1.1 —", "Рисунок 1.2 — Перемещение",
                   "Таблица 2.1 — Экстремальные значения", "(1.1)", "(1.5)",
                   "Примечание — Наибольшая скорость ползуна 0,701 м/с",
                   "ПРИЛОЖЕНИЕ А", "где"]:
        assert needle in text, needle
    # decimal commas and U+2212 in the table, no hyphen-minus before digits
    assert re.search(r"0,5000\s", text) and "−5,792" in text
    assert not re.search(r"(?<![\w.])-\d", text)
    assert not re.search(r"\d\.\d{3}\b", text.split("СПИСОК ИСПОЛЬЗОВАННЫХ")[0]
                         .split("ЗАДАНИЕ")[1])
    # cross-references resolved to numbers
    assert "по формуле (1.1)" in text
    assert "в таблице 1.1" in text
    # the assignment's table is not numbered
    assert "Исходные данные" in text and "Таблица 1 —" not in text
    # no line holding only a hyphenated fragment of a word (WeasyPrint 70 does
    # that when a no-break space precedes an inline element; see _typography)
    for line in text.splitlines():
        assert not re.fullmatch(r"\s*[А-Яа-яЁё]{1,8}\u2010", line), line


def test_every_continuation_page_starts_with_label(outputs):
    pages = pdf_pages(outputs["pdf"])
    cont = [p for p in pages if "Продолжение таблицы 1.1" in p]
    assert len(cont) == len([c for c in outputs["stats"].splits["tab-kin"] if c])
    for p in cont:
        first = [line for line in p.splitlines() if line.strip()][0]
        assert first.strip() == "Продолжение таблицы 1.1"
        assert "№" in p  # the header is repeated


def test_no_number_on_title_page(outputs):
    pages = pdf_pages(outputs["pdf"])
    title = [line.strip() for line in pages[0].splitlines() if line.strip()]
    assert "1" not in title
    assert title[-1] == "Москва 2025"
    second = [line.strip() for line in pages[1].splitlines() if line.strip()]
    assert "2" in second


def test_only_the_report_serif_is_embedded(outputs):
    out = subprocess.run(["pdffonts", str(outputs["pdf"])], check=True, capture_output=True,
                         text=True).stdout.splitlines()[2:]
    names = [line.split()[0] for line in out if line.strip()]
    assert names, "no fonts embedded"
    for name in names:
        assert re.fullmatch(r"[A-Z]{6}\+Report-Serif(-Bold|-Italic|-BoldItalic)?", name), name
    for line in out:
        assert " yes yes " in line  # embedded and subset


def test_pdf_and_html_are_deterministic(demo, outputs, tmp_path):
    again = render.build_outputs(demo, tmp_path, "again")
    # the split points are remembered: the same report is laid out in one pass
    assert render.last_stats.passes == 1
    assert render.last_stats.splits == outputs["stats"].splits
    for kind in ("pdf", "html"):
        a = outputs[kind].read_bytes()
        b = again[kind].read_bytes()
        assert hashlib.sha256(a).hexdigest() == hashlib.sha256(b).hexdigest(), kind
    # atomic writers leave no temporary files behind
    assert sorted(p.name for p in tmp_path.iterdir()) == ["again.html", "again.pdf"]


@pytest.mark.parametrize("filler", [29, 33])
def test_no_stub_parts_when_a_table_starts_low_on_a_page(filler):
    """Whatever the position of a table, no part of it holds fewer than
    MIN_PART_ROWS rows: either the table moves to a new page or the last
    split point moves up."""
    df = pd.DataFrame({"a": np.arange(40) * 1.0, "b": np.arange(40) * 0.5})
    s = Section("Раздел", "s")
    for _ in range(filler):
        s.paragraph("Строка текста для заполнения страницы.")
    s.table("Проверка", [Column("a", "a", digits=1), Column("b", "b", digits=2)], df, id="t")
    r = Report(meta={}, assignment=[], introduction=[], sections=[s], conclusion=[],
               references=[], options={"title_page": False, "assignment_page": False})
    doc, stats = render._layout(r, render._font_config())
    rows = render._page_rows(doc)["t"]
    per_page = {}
    for row, page in rows.items():
        per_page[page] = per_page.get(page, 0) + 1
    assert min(per_page.values()) >= render.MIN_PART_ROWS, (stats.splits, per_page)
    assert stats.passes <= 3


def test_tidy_cuts_keeps_rows_in_the_last_part():
    assert render._tidy_cuts([30, 59], 60, 3) == [30, 57]
    assert render._tidy_cuts([30], 60, 3) == [30]
    assert render._tidy_cuts([2], 4, 3) == [2]  # cannot help: leave as is
    assert render._tidy_cuts([], 10, 3) == []


# ---------------------------------------------------------------- HTML


def test_html_is_self_contained(outputs):
    html = outputs["html"].read_text("utf-8")
    assert html.startswith("<!DOCTYPE html>") and '<html lang="ru">' in html
    for bad in ("http://", "https://", "file://", "src=\"/", "url(/"):
        assert bad not in html, bad
    assert 'src="data:image/svg+xml;base64,' in html
    assert "data:font/woff;base64," in html
    for caption in ["Рисунок 1.1 — Скорость и ускорение ползуна",
                    "Рисунок 1.2 — Перемещение ползуна",
                    "Таблица 1.1 — Кинематические характеристики",
                    "Таблица 2.1 — Экстремальные значения",
                    ">(1.1)<", ">(1.5)<", "ПРИЛОЖЕНИЕ А"]:
        assert caption in html, caption
    # the screen flavour keeps the table whole
    assert "Продолжение таблицы" not in html
    assert 'таблице<a class="ref" href="#tab-kin">&#160;1.1</a>' in html


def test_print_html_uses_font_files_and_counters(demo):
    html = render.render_html(demo, for_print=True)
    assert "file://" in html  # fonts by path for WeasyPrint
    assert "target-counter(attr(data-href), page)" in html   # the contents: on the title's last word
    assert "@page" in html and "size: A4" in html
    assert 'data-row="tab-kin__r59"' in html  # rows named for the split passes (not by ids)
    # no no-break space right before an inline element (WeasyPrint 70 bug)
    assert not re.search(r"(&nbsp;|&#160;|\u00a0)<(a|img|span|i|b)\b", html)


# ---------------------------------------------------------------- snapshot


def _sample_table() -> Table:
    df = pd.DataFrame({
        "q_deg": [0.0, 30.0, 60.0, 90.0, 120.0],
        "x_B": [0.5, 0.48349, 0.43009, 0.3873, 0.33301],
        "v_B": [0.0, -0.41462, -0.66502, -0.68067, -0.51402],
        "F": [1234567.0, 12345.6, -0.00049, float("nan"), 1e-6],
        "link": ["OA", "AB", "B", "—", "C & D"],
    })
    return Table(
        "Положения и скорости ползуна",
        [Column("q_deg", "φ<sub>1</sub>", unit="град", digits=0),
         Column("x_B", "<i>x</i><sub>B</sub>", unit="м", digits=3),
         Column("v_B", r"v_B", unit="м/с", digits=3, latex=True),
         Column("F", "<i>F</i>", unit="Н", sig=3),
         Column("link", "Звено")],
        df, id="tab-sample", index_header="№", highlight_rows=[2],
        note="Значения округлены.",
    )


def test_table_fragment_snapshot(snapshot_html):
    html = render.render_fragment(_sample_table(), chapter="2")
    assert "Таблица 2.1 — Положения и скорости ползуна" in html
    assert "0,483" in html and "−0,415" in html and "−0,000<" not in html
    assert "−0,000490" in html and "1,00·10<sup>−6</sup>" in html
    assert "1,23·10<sup>6</sup>" in html and "12\u202f346" in html
    assert "C &amp; D" in html and ">—<" in html
    assert normalize_html(html) == snapshot_html


def test_units_row_and_options():
    t = _sample_table()
    t.units_row = True
    html = render.render_fragment(t, options={"table_word": "Табл.", "dash": "."})
    assert "Табл. 1.1. Положения" in html
    assert '<tr class="units">' in html and "<th>м/с</th>" in html


# ---------------------------------------------------------------- formulas


def test_render_latex_cyrillic_and_cache():
    svg, w, h, depth = render_latex(r"\omega_1 = 6{,}807\ \text{рад/с}")
    assert svg.startswith("<svg") and "<symbol" not in svg and "<use" not in svg
    assert w > h > 0 and 0 <= depth < h
    # Cyrillic text is drawn (as paths): the unit widens the image
    w0 = render_latex(r"\omega_1 = 6{,}807")[1]
    assert w > w0 + 20
    assert render_latex(r"\omega_1 = 6{,}807\ \text{рад/с}")[0] is svg  # cached


def test_long_formula_is_wrapped_or_scaled_to_fit():
    long = Formula(
        r"J_{\text{пр}} = " + " + ".join(rf"m_{{{i}}} \left(\frac{{v_{{S{i}}}}}{{\omega_1}}\right)^2"
                                       for i in range(1, 5)),
        " + ".join(rf"{i}{{,}}5 \cdot 0{{,}}{i}^2" for i in range(1, 5)),
        r"12{,}34\ \text{кг·м}^2",
    )
    lines = formula_images(long, 20.0)
    assert len(lines) >= 2
    assert all(img.width_em <= 20.0 + 1e-9 for img in lines)
    assert lines[-1].tex.startswith("= ")
    short = Formula(r"\lambda = \frac{l_{OA}}{l_{AB}}", r"\frac{0{,}1}{0{,}4}", "0{,}25")
    (one,) = formula_images(short, 30.0)
    assert one.tex == r"\lambda = \frac{l_{OA}}{l_{AB}} = \frac{0{,}1}{0{,}4} = 0{,}25"


def test_inline_math_markup(monkeypatch):
    # typeset as HTML text (reportgen/report/mathhtml.py) …
    html = str(inline_math(r"\varphi_3"))
    assert html == '<span class="mx math-inline"><i>φ</i><sub class="msub">3</sub></span>'
    # … and as a ziamath image when asked for (REPORTGEN_MATH=svg), the fallback
    monkeypatch.setenv("REPORTGEN_MATH", "svg")
    html = str(inline_math(r"\varphi_3"))
    assert html.startswith('<img class="math-inline"')
    assert "vertical-align:-" in html and "data:image/svg+xml;base64," in html
    assert 0.5 < MATH_SCALE <= 1.0


def test_formula_block_with_where_list():
    block = FormulaBlock([Formula(r"\omega_1 = \frac{\pi n_1}{30}", r"\frac{3{,}1416 \cdot 65}{30}",
                                  r"6{,}807\ \text{рад/с}",
                                  where=[(r"\omega_1", "угловая скорость, рад/с"),
                                         ("n_1", "частота вращения, об/мин")],
                                  label="eq-w")])
    html = render.render_fragment(block, chapter="3")
    assert '<div class="eq eq-where" id="eq-w">' in html and ">(3.1)<" in html
    assert html.count('class="w-sym"') == 2
    assert "угловая скорость, рад/с;" in html and "частота вращения, об/мин." in html
    assert ">где<" in html


# ---------------------------------------------------------------- model errors


def _tiny_report(**kw) -> Report:
    s = Section("Раздел", "s1")
    s.paragraph("Текст со ссылкой на " + kw.pop("target", ref("s1")) + ".")
    return Report(meta={"topic": "Тест"}, assignment=[], introduction=[], sections=[s],
                  conclusion=[], references=[], **kw)


def test_unknown_reference_is_an_error():
    with pytest.raises(KeyError, match="нет-такого"):
        render.render_html(_tiny_report(target=ref("нет-такого")), for_print=False)


def test_duplicate_id_is_an_error():
    r = _tiny_report()
    r.sections[0].subsection("Повтор", "s1")
    with pytest.raises(ValueError, match="дважды"):
        render.render_html(r, for_print=False)


def test_unknown_option_is_an_error():
    with pytest.raises(ValueError, match="margin_lef"):
        render.render_html(_tiny_report(options={"margin_lef_mm": 25}), for_print=True)


def test_numbering_of_levels_and_appendices():
    s1 = Section("Первый", "a")
    s11 = s1.subsection("Подраздел", "a1")
    s111 = s11.subsection("Пункт", "a11")
    s111.figure("Схема", b"<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'/>",
                id="f1")
    with pytest.raises(ValueError):
        s111.subsection("Четвёртый уровень", "x")
    app = Section("Листинг", "app")
    app.table("Данные", [Column("x", "x", digits=1)], pd.DataFrame({"x": [1.0]}), id="t-app")
    r = Report(meta={}, assignment=[], introduction=[Paragraph(ref("a11") + " " + ref("f1")
                                                                + " " + ref("t-app"))],
               sections=[Section("Ноль", "z"), s1], conclusion=[], references=[],
               appendices=[app], options={"toc_depth": 3})
    html = render.render_html(r, for_print=False)
    assert '<span class="secno">2.1.1</span>' in html
    assert "Рисунок 2.1 — Схема" in html and "Таблица А.1 — Данные" in html
    assert '>2.1.1</a> <a class="ref" href="#f1">2.1</a> <a class="ref" href="#t-app">А.1</a>' \
        in html
    assert 'class="toc-l3 toc-numbered"' in html


# ---------------------------------------------------------------- ЕСКД frame


def test_eskd_frame_and_stamp(tmp_path):
    s = Section("Раздел", "s1")
    s.paragraph("Текст раздела. " * 40)
    r = Report(meta={"topic": "Штамп", "doc_code": "ТММ.КП.01.00.000 ПЗ", "city": "Омск",
                     "year": 2025},
               assignment=[], introduction=[Paragraph("Введение.")], sections=[s],
               conclusion=[], references=[], options={"eskd_frame": True})
    path = render.write_pdf(r, tmp_path / "eskd.pdf")
    pages = pdf_pages(path)
    assert "ТММ.КП.01.00.000 ПЗ" in pages[0]  # on the title page only as the code line
    assert "Лист" not in pages[0]
    for i, page in enumerate(pages[1:], start=2):
        assert "ТММ.КП.01.00.000 ПЗ" in page and "Лист" in page and "Изм." in page
        assert re.search(rf"(^|\n)\s*{i}\s*(\n|$)", page), i


# ---------------------------------------------------------------- fonts, figures


def test_fonts_cover_russian_and_greek():
    family = fonts.find_serif()
    alphabet = ("АБВГДЕЁЖЗИЙКЛМНОПРСТУФХЦЧШЩЪЫЬЭЮЯабвгдеёжзийклмнопрстуфхцчшщъыьэюя"
                "αβγδεζηθικλμνξοπρστυφχψωΔΣΦΩ«»—–№°±×·−\u00a0\u202f²³")
    assert fonts.missing_glyphs(alphabet, family) == {}
    css = fonts.font_face_css(family, embed=False)
    # four faces of the body family, and four of the bundled STIXGeneral for the math symbols the
    # body face lacks (∥, ⊥, ∓), so that no glyph comes from fontconfig
    symbols = fonts.symbol_family()
    assert symbols is not None and fonts.missing_glyphs("∥⊥∓", symbols) == {}
    assert fonts.check_text("∥⊥∓", family) == [] and fonts.check_text("\U0001F600", family) == ["\U0001F600"]
    assert css.count("@font-face") == 8 and "file://" in css
    assert css.count(f'"{fonts.CSS_FAMILY}{fonts.SYMBOLS_SUFFIX}"') == 4


def test_matplotlib_svg_is_deterministic_with_comma_ticks():
    def make():
        fig = mplstyle.figure(100, 60)
        ax = fig.add_subplot()
        x = np.linspace(0, 2 * math.pi, 50)
        ax.plot(x, np.sin(x))
        ax.set_xlabel("φ, рад")
        return fig, mplstyle.to_svg(fig)

    fig, a = make()
    _, b = make()
    assert a == b and b"<dc:date>" not in a and b"<text" not in a
    assert b'width="283.464567pt"' in a  # 100 mm
    ax = fig.axes[0]
    labels = ax.yaxis.get_major_formatter().format_ticks([-1.0, -0.5, 0.0, 0.5, 1.0])
    assert labels == ["−1,0", "−0,5", "0,0", "0,5", "1,0"]


def test_figure_accepts_matplotlib_figure_and_png():
    fig = mplstyle.figure(80, 40)
    fig.add_subplot().plot([0, 1], [0, 1])
    s = Section("Р", "r")
    f = s.figure("График", fig)
    assert isinstance(f, Figure) and f.svg.startswith(b"<?xml")
    png = b"\x89PNG\r\n\x1a\n" + b"\0" * 16
    html = render.render_fragment(Figure("Растр", png, width_mm=500))
    assert "data:image/png;base64," in html and "width:165mm" in html


class _FakeBox:
    def __init__(self, bottom):
        self.bottom = bottom
        self.height = bottom - 75.0

    def content_box_y(self):
        return 75.0


class _FakePage:
    def __init__(self, rows, bottom=1047.0):
        """``rows``: {(table id, row): (top, bottom)} on this page."""
        self.anchors = {f"{t}__r{r}": (80.0, top, 700.0, low) for (t, r), (top, low) in rows.items()}
        self._page_box = _FakeBox(bottom)


class _FakeDoc:
    def __init__(self, *pages):
        self.pages = list(pages)


def _rows(tid, first, last, top, h=20.0):
    return {(tid, r): (top + (r - first) * h, top + (r - first + 1) * h) for r in range(first, last + 1)}


def test_short_table_across_a_page_break_moves_whole():
    """A 2-row table straddling a page break was cut after its first row (one row on each page):
    a table of at most MIN_PART_ROWS rows starts on the next page instead."""
    doc = _FakeDoc(_FakePage(_rows("t", 0, 0, 1000.0)), _FakePage(_rows("t", 1, 1, 75.0)))
    assert render._next_splits(doc, {}) == {"t": [0]}


def test_cut_that_leaves_a_page_largely_empty_is_dropped():
    """Split points decided while an earlier table pushed this one lower: the first part now ends
    a third of the way down its page, so the cut (and the later ones) are dropped and the table is
    cut afresh in the next pass."""
    doc = _FakeDoc(_FakePage(_rows("t", 0, 3, 75.0)), _FakePage(_rows("t", 4, 40, 75.0)),
                   _FakePage(_rows("t", 41, 50, 75.0)))
    assert render._next_splits(doc, {"t": [4, 41]}) == {"t": []}
    full = _FakeDoc(_FakePage(_rows("t", 0, 47, 75.0)), _FakePage(_rows("t", 48, 50, 75.0)))
    assert render._next_splits(full, {"t": [48]}) is None     # a full page: the cut stays


def test_last_part_is_cut_at_each_of_its_pages_at_once():
    """The last part running over several pages gets a split point at each of them in one pass."""
    doc = _FakeDoc(_FakePage(_rows("t", 0, 47, 75.0)), _FakePage(_rows("t", 48, 95, 75.0)),
                   _FakePage(_rows("t", 96, 143, 75.0)), _FakePage(_rows("t", 144, 150, 75.0)))
    assert render._next_splits(doc, {"t": [48]}) == {"t": [48, 96, 144]}
