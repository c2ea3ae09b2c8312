"""What the print parts of a note no longer ask of WeasyPrint (issue #15, the PDF ratio), each
with the proof that the PDF stays the same: no OpenType feature on the tables' text (none of the
note's fonts has 'tnum', whose request cost a Pango attribute list per text box)."""
from __future__ import annotations

import re

import pytest
from conftest import CASES

from reportgen.report import parallel, render
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


@pytest.fixture(scope="module")
def kinematics_html(report):
    """The print HTML of the kinematics part (its tables of numbers), as a worker lays it out."""
    views = render._views(report, for_print=True, splits={})
    html = max((views.html(front=False, body=[node], chunk=True) for node in views.ctx["body"]),
               key=lambda h: h.count("<td"))
    assert html.count("<td") > 200
    return html


def _pdf(html: str) -> bytes:
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
    assert _pdf(back) == _pdf(kinematics_html)


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
