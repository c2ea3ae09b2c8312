"""What the PDF of a note no longer does twice (issue #15, the PDF ratio): СОДЕРЖАНИЕ laid out
once when its page numbers are remembered, the note's stylesheet parsed once per process, the
HTML parsed by reportgen/report/fasthtml.py into tinyhtml5's very tree. And what it no longer asks
(session 9): no OpenType feature on the tables' text (none of the note's fonts has 'tnum', whose
request cost a Pango attribute list per text box), and the parts' PDFs parsed for the join as they
come back from the workers. Each keeps the bytes."""
from __future__ import annotations

import re
from pathlib import Path
from xml.etree import ElementTree

import pytest
import tinyhtml5
from conftest import CASES

from reportgen.report import fasthtml, parallel, render
from reportgen.style import fonts

SECTIONS = ["structure", "kinematics"]


@pytest.fixture(scope="module")
def report():
    from reportgen.analysis.study import Study
    from reportgen.report.assemble import build_report

    parallel.set_note_jobs(1)
    try:
        return build_report(Study(CASES / "ws004_slotted_lever.toml"), SECTIONS)
    finally:
        parallel.set_note_jobs(None)


def _tree(el) -> tuple:
    return (el.tag, list(el.attrib.items()), el.text or "", el.tail or "", [_tree(c) for c in el])


def _documents(report) -> list[str]:
    """Every document WeasyPrint is given for the note, and the whole print and screen HTML."""
    views = render._views(report, for_print=True, splits={})
    docs = [views.html(front=False, body=[node], chunk=True) for node in views.ctx["body"]]
    docs.append(views.html(body=[], toc=False, toc_pages={}, chunk=True))  # title page and assignment
    docs.append(views.html(head=False, body=[], toc_pages={e["id"]: "7" for e in views.builder.toc}, chunk=True))
    docs.append(parallel._numbers_html(views, 4, {2}))
    docs.append(views.html())
    docs.append(render.render_html(report, for_print=False))
    return docs


def test_fast_parse_builds_tinyhtml5s_tree_for_every_document(report):
    for i, html in enumerate(_documents(report)):
        root = fasthtml.parse(html)
        assert root is not None, f"документ {i} вне подмножества быстрого разбора"
        assert _tree(root) == _tree(tinyhtml5.parse(html, namespace_html_elements=False)), f"документ {i}"


DOC = '<!DOCTYPE html>\n<html lang="ru">\n<head>\n<meta charset="utf-8">\n<title>{title}</title>\n</head>\n<body>{body}</body>\n</html>\n'


@pytest.mark.parametrize("body", [
    '<p class=a data-x=\'1 2\' hidden>x&nbsp;&#160;&#x2212;&amp;&lt;y</p>\n',
    '<DIV Class="A" class="B"><BR/><img src="data:image/png;base64,AAAA" alt=""></DIV>',
    '<table class="where">\n<tr><td>a</td><td> b </td></tr>\n<tr><td>c</td></tr>\n</table>\ntail',
    '<table><thead><tr><th>h</th></tr></thead>\n<tbody>\n<tr><td><p>x</p><table><tr><td>y</td></tr></table></td></tr>\n</tbody></table>',
    '<ul><li>a<ul><li>b</li></ul></li><li>c</li></ul><h1>t<span>s</span></h1>',
    '<p>a<a href="#x">b<sub>c</sub></a> d</p>',
    '<p>&#9;&#x41;&#1040;&#x1F600;&#160;</p>',
])
def test_fast_parse_equals_tinyhtml5(body):
    html = DOC.format(title="A &amp; B", body=body)
    root = fasthtml.parse(html)
    assert root is not None
    assert _tree(root) == _tree(tinyhtml5.parse(html, namespace_html_elements=False))


@pytest.mark.parametrize("html", [
    DOC.format(title="t", body="<p>a<div>b</div></p>"),  # a <div> closes the <p>
    DOC.format(title="t", body="<p>a<!-- c --></p>"),  # comments
    DOC.format(title="t", body="<p>a &amp b</p>"),  # a reference without its «;»
    DOC.format(title="t", body="<p>a &notit; b</p>"),  # an unknown name (HTML5 decodes «&not»)
    DOC.format(title="t", body="<table>x<tr><td>a</td></tr></table>"),  # foster-parented text
    DOC.format(title="t", body="<table><tr><span>a</span></tr></table>"),  # an element out of place
    DOC.format(title="t", body="<ul><li>a<li>b</li></ul>"),  # an implied </li>
    DOC.format(title="t", body="<p>a</span></p>"),  # an end tag that closes nothing open
    DOC.format(title="t", body="<svg><path d=''/></svg>"),  # foreign content
    DOC.format(title="t", body="<pre>\na</pre>"),  # elements with rules of their own
    DOC.format(title="t", body="<h1>a<h2>b</h2></h1>"),
    DOC.format(title="t", body="<p>a</p>").replace("<!DOCTYPE html>", ""),  # quirks mode
    DOC.format(title="t", body="<p>a\r\nb</p>"),
    DOC.format(title="t", body="<p>a < b</p>"),
    DOC.format(title="t", body="<p>a&#1;b&#x80;</p>"),  # controls: html.unescape drops or maps them
    DOC.format(title="t", body="<p>a</p>").replace("</title>", "</title x>"),  # an end tag with attributes
])
def test_fast_parse_leaves_the_rest_to_tinyhtml5(html):
    assert fasthtml.parse(html) is None


def _pdf(html: str) -> bytes:
    HTML = render._html_class()
    doc = HTML(string=html, base_url=str(render.TEMPLATES_DIR))
    return doc.render(font_config=render._font_config()).write_pdf()


def test_stylesheet_parsed_once_and_same_bytes(report, monkeypatch):
    """Two documents of the note share one parsed stylesheet; the PDF is the same as with the
    stylesheet left in the document and the HTML parsed by tinyhtml5."""
    views = render._views(report, for_print=True, splits={})
    a, b = (views.html(front=False, body=[node], chunk=True) for node in views.ctx["body"][:2])
    render._SHEETS.clear()
    before, fast = render.SHEETS_PARSED[0], fasthtml.PARSED["fast"]
    with render._fixed_font_timestamp():
        shared = [_pdf(a), _pdf(b)]
    assert render.SHEETS_PARSED[0] == before + 1
    assert fasthtml.PARSED["fast"] == fast + 2
    monkeypatch.setattr(render, "_shared_sheets", lambda html, font_config: [])
    monkeypatch.setattr(fasthtml, "parse", lambda source: None)
    with render._fixed_font_timestamp():
        plain = [_pdf(a), _pdf(b)]
    assert shared == plain


def test_shared_sheet_keeps_wider_importance_to_weasyprint():
    """A ``!important`` outside the stylesheet (here in a style attribute) would meet the sheet's
    own at another precedence: the sheet stays in the document."""
    css = "p { color: red !important; }" + " " * 1000
    html = (f'<!DOCTYPE html><html><head><style>{css}</style></head>'
            '<body><p style="color: blue !important">a</p></body></html>')
    HTML = render._html_class()
    assert render._shared_sheets(HTML(string=html), render._font_config()) == []
    ok = html.replace(' style="color: blue !important"', "")
    assert len(render._shared_sheets(HTML(string=ok), render._font_config())) == 1


def test_contents_laid_out_once_when_its_numbers_are_remembered(report, tmp_path, monkeypatch):
    monkeypatch.setenv("REPORTGEN_CACHE", str(tmp_path / "cache"))
    parallel._TOC_MEMO.clear()
    first = render.write_pdf(report, tmp_path / "a.pdf", jobs=1).read_bytes()
    assert render.last_stats.parts.toc_layouts == 2  # placeholder numbers, then the real ones
    assert len(list((tmp_path / "cache" / "toc").glob("*.json"))) == 1
    parallel._TOC_MEMO.clear()  # a new process: the numbers come from the cache folder
    assert render.write_pdf(report, tmp_path / "b.pdf", jobs=1).read_bytes() == first
    assert render.last_stats.parts.toc_layouts == 1
    # a wrong guess (another variant's page numbers) is laid out, found different and redone
    key, (count, pages) = next(iter(parallel._TOC_MEMO.items()))
    parallel._TOC_MEMO[key] = (count, {k: str(int(v) + 1) for k, v in pages.items()})
    assert render.write_pdf(report, tmp_path / "c.pdf", jobs=1).read_bytes() == first
    assert render.last_stats.parts.toc_layouts == 2
    assert parallel._TOC_MEMO[key] == (count, pages)


def test_toc_key_ignores_title_and_meta():
    a = '<html><head><meta name="author" content="A"><title>A</title></head><body>x</body></html>'
    b = '<html><head><meta name="author" content="B"><title>B</title></head><body>x</body></html>'
    assert parallel._toc_key(a) == parallel._toc_key(b)
    assert parallel._toc_key(a) != parallel._toc_key(a.replace(">x<", ">y<"))
    assert isinstance(fasthtml.parse("<!DOCTYPE html><html><head></head><body></body></html>"), ElementTree.Element)


def test_atomic_write_leaves_a_special_file_in_place(tmp_path):
    """A path that is not a regular file (``/dev/null``, here a pipe) is written into, not
    replaced by a renamed regular file (a bench's warm-up once replaced ``/dev/null`` so)."""
    import os
    import stat
    import threading

    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    got = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()))
    reader.start()
    render._atomic_write(fifo, b"%PDF-")
    reader.join(10)
    assert got == [b"%PDF-"] and stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert render._atomic_write(tmp_path / "a" / "b.pdf", b"x").read_bytes() == b"x"


def test_gear_note_is_inside_the_fast_subset():
    """The gear section's list of checks is a list after its paragraph, not inside it (HTML5 closes
    a ``<p>`` at ``<ul>``: the note's HTML said one thing and the browser built another)."""
    from reportgen.analysis.study import Study
    from reportgen.report.assemble import build_report

    parallel.set_note_jobs(1)
    try:
        rep = build_report(Study(CASES / "gear_pair_shifted.toml"), ["gears"])
    finally:
        parallel.set_note_jobs(None)
    for i, html in enumerate(_documents(rep)):
        assert "<p>Проверки качества зацепления: <ul>" not in html
        assert fasthtml.parse(html) is not None, f"документ {i} вне подмножества быстрого разбора"


@pytest.fixture(scope="module")
def kinematics_html(report):
    """The print HTML of the kinematics part (its tables of numbers), as a worker lays it out."""
    views = render._views(report, for_print=True, splits={})
    html = max((views.html(front=False, body=[node], chunk=True) for node in views.ctx["body"]),
               key=lambda h: h.count("<td"))
    assert html.count("<td") > 200
    return html


def _part_pdf(html: str) -> bytes:
    with render._fixed_font_timestamp():
        return parallel._write(parallel._lay_out(html))


def _features(path) -> set[str]:
    from fontTools.ttLib import TTFont

    with TTFont(str(path), lazy=True) as font:
        return {rec.FeatureTag for tag in ("GSUB", "GPOS") if tag in font
                for rec in font[tag].table.FeatureList.FeatureRecord}


def _digit_advances(path) -> set[int]:
    from fontTools.ttLib import TTFont

    with TTFont(str(path), lazy=True) as font:
        cmap, hmtx = font.getBestCmap(), font["hmtx"]
        return {hmtx[cmap[ord(d)]][0] for d in "0123456789"}


def test_note_fonts_have_tabular_digits_without_a_tnum_feature():
    """Why gost.css asks no ``tabular-nums``: every family the note can use (and its symbol
    family) draws the digits 0–9 at one width and has no 'tnum' feature, so the request selected
    no other glyph. A family added with proportional digits fails here (and needs the rule back)."""
    fams = [f for f in fonts.candidates() if all(p.is_file() for p in f.faces().values())]
    assert fams
    for fam in fams:
        for face, path in fam.faces().items():
            assert "tnum" not in _features(path), (fam.name, face)
            assert len(_digit_advances(path)) == 1, (fam.name, face)


def test_print_tables_ask_no_font_feature(report, kinematics_html):
    """The print stylesheet sets no ``font-variant-numeric`` on tables (formulas reset it to
    ``normal``), and putting ``tabular-nums`` back gives the very same PDF bytes."""
    views = render._views(report, for_print=True, splits={})
    css = render._get_env().get_template("gost.css").render(**views.ctx["css_ctx"])
    assert "tabular-nums" not in re.sub(r"/\*.*?\*/", "", css, flags=re.S)
    back = kinematics_html.replace("</style>\n</head>", "table.tbl { font-variant-numeric: tabular-nums; }"
                                   "</style>\n</head>", 1)
    assert back != kinematics_html
    assert _part_pdf(back) == _part_pdf(kinematics_html)


def test_parts_parsed_as_they_come_back_join_the_same(report, tmp_path, monkeypatch):
    """With workers, every document of the note (title page, contents, body parts) is parsed by
    :func:`parallel.prepare` as it comes back, and the join takes those readers; the note is
    the same bytes as laid out in one process (no reader prepared) and as joined from the bytes."""
    prepared, joins = [], []
    real_prepare, real_join = parallel.prepare, parallel.join

    def spy_prepare(part):
        prepared.append(part.index)
        return real_prepare(part)

    def spy_join(parts, numbers, first_numbered, readers=None):
        given = dict(readers or {})
        assert all(given[id(p)][0] is p for p in parts if id(p) in given)
        joins.append(({p.index for p in parts}, {part.index for part, _ in given.values()}))
        out = real_join(parts, numbers, first_numbered, readers)
        assert not readers, "the join takes the readers it was given"
        assert real_join(parts, numbers, first_numbered) == out  # from the bytes: the same
        # a reader kept for another document (the contents laid out again) is not taken for this one
        swapped = {id(p): (q, real_prepare(q)) for p, q in zip(parts, parts[1:] + parts[:1])}
        assert real_join(parts, numbers, first_numbered, swapped) == out
        return out

    monkeypatch.setattr(parallel, "prepare", spy_prepare)
    monkeypatch.setattr(parallel, "join", spy_join)
    two = render.write_pdf(report, tmp_path / "two.pdf", jobs=2).read_bytes()
    (indexes, given), = joins
    assert given == indexes and set(prepared) >= indexes
    assert parallel.NUMBERS not in prepared
    prepared.clear()
    one = render.write_pdf(report, tmp_path / "one.pdf", jobs=1).read_bytes()
    assert prepared == [] and joins[1][1] == set()
    assert one == two


def test_workers_forked_for_a_note_collect_as_the_cli_does(report, tmp_path, monkeypatch):
    """A note written through the API (``write_pdf`` with its own pool, as bench/bench_cli.py
    writes it) lays its parts out in workers whose garbage collector runs as the CLI's
    (``memory.collect_less``) and never scans what they inherited (``gc.freeze``); the
    parent's own setting is left as it was."""
    import gc
    import json
    import os

    from reportgen.core.memory import GC_THRESHOLD

    log = tmp_path / "gc.jsonl"
    real = parallel.lay_out_part

    def spy(task):  # looked up by name in the forked worker
        with open(log, "a", encoding="utf-8") as f:
            f.write(json.dumps([os.getpid(), gc.get_threshold()[0], gc.get_freeze_count()]) + "\n")
        return real(task)

    before = gc.get_threshold()
    gc.set_threshold(700, 10, 10)
    try:
        monkeypatch.setattr(parallel, "lay_out_part", spy)
        render.write_pdf(report, tmp_path / "note.pdf", jobs=2)
        assert gc.get_threshold() == (700, 10, 10)
    finally:
        gc.set_threshold(*before)
    seen = [json.loads(line) for line in log.read_text().splitlines()]
    workers = [s for s in seen if s[0] != os.getpid()]
    assert workers and all(s[1] >= GC_THRESHOLD[0] and s[2] > 0 for s in workers), seen


def test_cell_borders_written_directly_are_weasyprints_bytes(report, tmp_path, monkeypatch):
    """The table cells' borders (solid, on two or three sides) are written by
    ``wpfast._draw_border`` without WeasyPrint's general routine, and the note is the same bytes
    as with WeasyPrint's own routine; boxes of other borders (all four sides, a dashed side,
    another colour per side, a rounded corner) are left to WeasyPrint, also the same bytes."""
    import contextlib

    from reportgen.report import wpfast

    drawn = []
    real, borders = wpfast._draw_border, wpfast.cell_borders

    def spy(stream, box, general):
        calls = []
        real(stream, box, lambda s, b: calls.append(b) or general(s, b))
        if not calls:
            drawn.append(box.element_tag)

    monkeypatch.setattr(wpfast, "_draw_border", spy)
    fast = render.write_pdf(report, tmp_path / "fast.pdf", jobs=1).read_bytes()
    assert drawn.count("td") > 100, set(drawn)
    monkeypatch.setattr(wpfast, "cell_borders", contextlib.nullcontext)
    assert render.write_pdf(report, tmp_path / "weasyprint.pdf", jobs=1).read_bytes() == fast

    html = ('<html><head><style>td { padding: 2pt; } table { border-collapse: separate; }'
            '.a { border-right: 1pt solid #000; border-bottom: 1pt solid #000; }'
            '.b { border: 1pt solid #000; } .c { border-right: 1pt dashed #000; border-bottom: 1pt solid #000; }'
            '.d { border-right: 1pt solid red; border-bottom: 1pt solid #000; }'
            '.e { border-right: 2pt solid #000; border-left: 1pt solid #000; border-bottom-right-radius: 3pt; }'
            '.f { border-top: 0.75pt solid #000; border-left: 1.5pt solid #000; }'
            '</style></head><body><table><tr><td class="a">1</td><td class="b">2</td><td class="c">3</td>'
            '<td class="d">4</td><td class="e">5</td><td class="f">6</td></tr></table></body></html>')
    document = render._html_class()(string=html).render()
    with render._fixed_font_timestamp():
        plain = document.write_pdf()
        tagged = document.write_pdf(pdf_tags=True)  # each side marked as an artifact
        drawn.clear()
        with borders():
            assert document.write_pdf() == plain
            assert document.write_pdf(pdf_tags=True) == tagged
    assert drawn == ["td", "td"] * 2  # .a and .f; the others went to WeasyPrint


def test_first_lines_measured_once_same_bytes(report, tmp_path, monkeypatch):
    """While a document is laid out, a text's first line in a width is measured once per process
    (``wpsplit.first_lines``: the inline layout and the min- and max-content widths ask the same
    texts again and again): most calls are answered from memory, all of them when the same note is
    laid out again (as a batch worker lays out the next variant's same words), and the note is the
    same bytes as with WeasyPrint measuring each."""
    import contextlib

    from reportgen.report import wpsplit

    render._font_config().__dict__.pop("_reportgen_splits", None)  # made by earlier tests of this process
    for key in wpsplit.STATS:
        monkeypatch.setitem(wpsplit.STATS, key, 0)
    fast = render.write_pdf(report, tmp_path / "fast.pdf", jobs=1).read_bytes()
    hits, misses = wpsplit.STATS["hits"], wpsplit.STATS["misses"]
    assert hits > 1000 and hits > misses > 0, wpsplit.STATS
    assert render.write_pdf(report, tmp_path / "again.pdf", jobs=1).read_bytes() == fast
    assert wpsplit.STATS["misses"] == misses and wpsplit.STATS["hits"] > 2 * hits  # nothing measured again
    monkeypatch.setattr(wpsplit, "first_lines", contextlib.nullcontext)
    assert render.write_pdf(report, tmp_path / "weasyprint.pdf", jobs=1).read_bytes() == fast


def test_first_lines_same_bytes_on_other_text():
    """Text the note never has — automatic and soft hyphens in a narrow column, a long word broken
    (``overflow-wrap: break-word``, ``anywhere``, ``word-break: break-all``), preserved white space and
    tabs, text that does not wrap, letter and word spacing, justified lines, an underline, right to
    left, small caps, table cells and inline blocks measured for their widths, the same words with
    other spacing or hyphenation — is the same bytes with ``wpsplit.first_lines`` as with WeasyPrint's
    own ``split_first_line``, the second document entirely from memory."""
    from weasyprint import HTML

    from reportgen.report import wpsplit

    words = "Теория механизмов и машин: кинематический анализ рычажного механизма, 1,234 м/с"
    html = ('<html lang="ru"><body style="width: 40mm">'
            f'<p style="hyphens: auto">{words}</p><p style="hyphens: manual">сверх\u00adпрочный '
            'электро\u00adмеханический</p><p>{0}</p>'
            '<p style="overflow-wrap: break-word; width: 15mm">Непереносимоедлинноеслово и ещё</p>'
            '<p style="overflow-wrap: anywhere; width: 15mm">Непереносимоедлинноеслово и ещё</p>'
            '<p style="word-break: break-all; width: 15mm">Непереносимоедлинноеслово и ещё</p>'
            '<table><tr><td style="overflow-wrap: break-word">Непереносимоедлинноеслово</td><td>{0}</td></tr></table>'
            '<pre>a\tb  c\nвторая   строка</pre><p style="white-space: pre-wrap">a  b\tc   d e f g h i j k</p>'
            '<p style="white-space: pre-line">одна\nдве   три</p><p style="white-space: pre-wrap">{0}</p><p style="white-space: nowrap">не переносится никогда '
            'эта строка</p><p style="letter-spacing: 1pt">{0}</p><p style="word-spacing: 3pt">{0}</p>'
            '<p style="text-align: justify">{0} {0}</p><p style="text-decoration: underline">{0}</p>'
            '<p dir="rtl">שלום עולם abc</p><p style="font-variant: small-caps">{0}</p>'
            '<table><tr><td>12,5</td><td>текст ячейки подлиннее</td><td style="white-space: nowrap">1 234,5</td></tr>'
            '<tr><td>12,5</td><td style="hyphens: auto">механизм</td><td>м/с</td></tr></table>'
            '<p>a <span style="display: inline-block">блок в строке</span> b <span style="letter-spacing: 2pt">'
            'разрядка</span> c</p></body></html>').format(words)
    config = render._font_config()
    with render._fixed_font_timestamp():
        own = HTML(string=html).render(font_config=config).write_pdf()
        config.__dict__.pop("_reportgen_splits", None)
        for key in wpsplit.STATS:
            wpsplit.STATS[key] = 0
        fast = []
        for _ in range(2):
            with wpsplit.first_lines():
                document = HTML(string=html).render(font_config=config)
            fast.append(document.write_pdf())
            if not _:
                first = dict(wpsplit.STATS)
    assert fast == [own, own]
    assert first["misses"] > 20 and wpsplit.STATS["misses"] == first["misses"], (first, wpsplit.STATS)
    assert wpsplit.STATS["hits"] > 2 * first["hits"], (first, wpsplit.STATS)


def test_text_layouts_share_pango_context_same_bytes(report, tmp_path, monkeypatch):
    """Every piece of text laid out or drawn gets its Pango layout from a context, a font
    description and a feature string made once per font (``wpfast.text_layouts``), not a new
    context and description each: thousands of layouts are set up without WeasyPrint's own
    ``setup``, only a few settings are made, and the note is the same bytes as with
    WeasyPrint's ``setup`` for every layout."""
    import contextlib

    from reportgen.report import wpfast

    made, general_calls = [], []
    real_setting, real_setup = wpfast._text_setting, wpfast._layout_setup

    def counting_setting(style, contexts):
        made.append(1)
        return real_setting(style, contexts)

    def counting_setup(general):
        def counted(self, style):
            general_calls.append(1)
            return general(self, style)
        fast = real_setup(counted)

        def setup(self, style):
            layouts.append(1)
            return fast(self, style)
        return setup

    layouts: list = []
    render._font_config().__dict__.pop("_reportgen_text", None)  # made by earlier tests of this process
    monkeypatch.setattr(wpfast, "_text_setting", counting_setting)
    monkeypatch.setattr(wpfast, "_layout_setup", counting_setup)
    fast = render.write_pdf(report, tmp_path / "fast.pdf", jobs=1).read_bytes()
    assert len(layouts) > 1000 and not general_calls, (len(layouts), len(general_calls))
    assert 0 < len(made) < len(layouts) / 20, (len(made), len(layouts))
    monkeypatch.setattr(wpfast, "text_layouts", contextlib.nullcontext)
    assert render.write_pdf(report, tmp_path / "weasyprint.pdf", jobs=1).read_bytes() == fast


def test_text_layouts_same_bytes_on_other_text_styles():
    """Text the note never has — another language and a language override, small caps,
    kerning and ligatures switched off, a feature setting, right to left, an underline and
    font variations (these two left to WeasyPrint's ``setup``) — is the same bytes with
    ``wpfast.text_layouts`` as without it, and the two left to WeasyPrint are counted there."""
    from weasyprint.text.line_break import Layout

    from reportgen.report import wpfast

    html = ('<html lang="ru"><body><p>Обычный текст и 1,234 м/с</p><p lang="en">English text, fi ffl</p>'
            '<p style="font-language-override: \'TRK\'">Türkçe</p><p style="font-variant: small-caps">Капитель</p>'
            '<p style="font-kerning: none; font-variant-ligatures: none">AV To fi</p>'
            '<p style="font-feature-settings: \'onum\' 1">0123456789</p><p dir="rtl">שלום abc</p>'
            '<p style="text-decoration: underline">подчёркнуто</p>'
            '<p style="font-variation-settings: \'wght\' 500">вариации</p>'
            '<table><tr><td style="white-space: nowrap">12,5</td><td>текст ячейки</td></tr></table></body></html>')
    general = Layout.setup
    fallbacks = []

    def counted(self, style):
        fallbacks.append(style["text_decoration_line"] != "none" or style["font_variation_settings"] != "normal")
        return general(self, style)

    with render._fixed_font_timestamp():
        from weasyprint import HTML  # WeasyPrint's own class: its render does not set the fast setup up
        own = HTML(string=html).render(font_config=render._font_config()).write_pdf()
        Layout.setup = counted
        try:
            with wpfast.text_layouts():
                fast = HTML(string=html).render(font_config=render._font_config()).write_pdf()
        finally:
            Layout.setup = general
    assert fast == own
    assert fallbacks and all(fallbacks), fallbacks  # only the underline and the variations went to WeasyPrint


def test_line_struts_once_per_style_same_bytes(report, tmp_path, monkeypatch):
    """The inline layout asks for the strut of a style (``strut``: line height and baseline)
    once per line box and inline box; ``wpfast.line_struts`` answers again from memory for the
    same style object: most calls never reach WeasyPrint's ``strut``, and the note is the same
    bytes as with WeasyPrint answering each."""
    import contextlib

    from reportgen.report import wpfast

    asked, computed = [], []
    real = wpfast._struts

    def counting(general):
        def counted(style):
            computed.append(1)
            return general(style)
        fast = real(counted)

        def strut(style):
            asked.append(1)
            return fast(style)
        return strut

    monkeypatch.setattr(wpfast, "_struts", counting)
    fast = render.write_pdf(report, tmp_path / "fast.pdf", jobs=1).read_bytes()
    assert len(asked) > 500 and len(computed) < len(asked) / 4, (len(asked), len(computed))
    monkeypatch.setattr(wpfast, "line_struts", contextlib.nullcontext)
    assert render.write_pdf(report, tmp_path / "weasyprint.pdf", jobs=1).read_bytes() == fast


def test_drawn_lines_shaped_once_same_bytes(report, tmp_path, monkeypatch):
    """A line of text is shaped when drawn once per process (``wptext._shape``) and its
    operators replayed for every box that draws the same line (``wptext.drawn_lines``): far
    fewer lines are shaped than boxes drawn, none the second time the note is written, and the
    note is the same bytes as with WeasyPrint's ``draw_text`` shaping every box again."""
    import contextlib

    from reportgen.report import wptext

    shaped, drawn = [], []
    real_shape, real_draw = wptext._shape, wptext._draw_text

    def counting_shape(*args):
        shaped.append(1)
        return real_shape(*args)

    def counting_draw(general):
        fast = real_draw(general)

        def draw_text(*args, **kw):
            drawn.append(1)
            return fast(*args, **kw)
        return draw_text

    render._font_config().__dict__.pop("_reportgen_lines", None)  # made by earlier tests of this process
    monkeypatch.setattr(wptext, "_shape", counting_shape)
    monkeypatch.setattr(wptext, "_draw_text", counting_draw)
    fast = render.write_pdf(report, tmp_path / "fast.pdf", jobs=1).read_bytes()
    assert len(drawn) > 1000 and 0 < len(shaped) < len(drawn) * 3 / 4, (len(drawn), len(shaped))
    shaped.clear()
    assert render.write_pdf(report, tmp_path / "again.pdf", jobs=1).read_bytes() == fast
    assert not shaped  # every line of the same note replayed
    monkeypatch.setattr(wptext, "drawn_lines", contextlib.nullcontext)
    assert render.write_pdf(report, tmp_path / "weasyprint.pdf", jobs=1).read_bytes() == fast


def test_drawn_lines_same_bytes_on_other_text():
    """Text the note never has — justified lines (word spacing per line), letter and word
    spacing, a ligature, right to left, a tab, a glyph missing from every font, a superscript
    feature, small caps, an underline, an ellipsis, hidden text, spaces only, one text drawn
    again after the document's fonts learnt its glyphs from another document — is the same bytes
    with ``wptext.drawn_lines`` as with WeasyPrint's ``draw_text``, and what it must leave to
    WeasyPrint (the underline, the ellipsis, the tab, the missing glyph) goes there."""
    from weasyprint import HTML, draw

    from reportgen.report import wptext

    html = ('<html lang="ru"><body style="width: 60mm"><p style="text-align: justify">Обычный текст, который '
            'переносится на несколько строк и выравнивается по ширине, 1,234 м/с и ещё раз 1,234 м/с.</p>'
            '<p style="letter-spacing: 1pt">разрядка</p><p style="word-spacing: 3pt">слова через пробел</p>'
            '<p lang="en">fi ffl office</p><p dir="rtl">שלום abc</p><pre>a\tb</pre><p>\u4e2d\u6587 ☃</p>'
            '<p style="font-variant-position: super">x2</p><p style="font-variant: small-caps">Капитель</p>'
            '<p style="text-decoration: underline">подчёркнуто</p>'
            '<p style="white-space: nowrap; overflow: hidden; text-overflow: ellipsis; width: 10mm">'
            'очень длинная строка</p><p style="visibility: hidden">скрыто</p><p><span> </span> <b>x</b></p>'
            '<p>1,234 м/с</p></body></html>')
    general = draw.draw_text
    fallbacks = []

    def counted(stream, box, *args):
        fallbacks.append(box.text)
        return general(stream, box, *args)

    config = render._font_config()
    with render._fixed_font_timestamp():
        own = [HTML(string=html).render(font_config=config).write_pdf()] * 2
        config.__dict__.pop("_reportgen_lines", None)
        draw.draw_text = counted
        try:
            with wptext.drawn_lines():
                fast = [HTML(string=h).render(font_config=config).write_pdf() for h in (html, html)]
        finally:
            draw.draw_text = general
    assert fast == own
    assert {"подчёркнуто", "очень длинная строка", "a\tb", "скрыто"} <= set(fallbacks), fallbacks
    assert any("\u4e2d" in t for t in fallbacks), fallbacks
    assert not any("1,234" in t or t == "разрядка" for t in fallbacks), fallbacks
