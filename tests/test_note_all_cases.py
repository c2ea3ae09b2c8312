"""Issue 9, «Done when», over EVERY case in cases/ (not a hand-picked subset). The student's note of
each case is built once in the session (``build --format pdf --jobs 2``, on the first test that
asks for that case) and every check of that case reads the same output:

* every figure drawn for the note (each scene, each chart) has no two labels overlapping and
  none clipped (matplotlib's rendered extents, ``scenes.labels.check_figure``), and its labels
  are in textbook notation (no bare «nbc», «S2»);
* the PDF text holds no identifier of the program or the case (``\\w+_\\w+``, Latin phi/omega/eps,
  «as printed», a worksheet («лист», except «лист формата А4»));
* numerals agree with their nouns in the generated sentences;
* no page is less than half full without a reason (``pagefill.short_pages``).

The figures are checked as they are drawn: ``mplstyle.to_svg`` is wrapped while the case is
built, and the section workers are forked, so they inherit the wrapper and append what they find
to the case's log. Tests of one case (``-k ws004``) build that case only."""
from __future__ import annotations

import json
import re
import subprocess

import pytest

from conftest import CASES
from pagefill import short_pages
from reportgen.report.russian import plural_form


def _cases() -> list:
    from reportgen import load_case
    from reportgen.errors import CaseError
    out = []
    for path in sorted(CASES.glob("*.toml")):
        try:
            load_case(path)
        except CaseError:          # a table of variants (``base = …``) is built by batch, not alone
            continue
        out.append(path)
    return out


CASE_FILES = _cases()
BARE = re.compile(r"[a-zA-Z]+\d+|n[a-z]{2,}")      # a point label not in textbook notation
IDENTIFIER = re.compile(r"\b\w+_\w+\b|\b(?:phi|omega|eps)\w*|\bлист(?!\s+формата)\w*|as printed|Mathcad", re.I)
FIGURE_TEXT = "figure text: "


def figure_identifiers(fig) -> list[str]:
    """Every visible text of a figure holding an identifier-like token outside mathtext."""
    from matplotlib.text import Text
    texts = (t.get_text() for t in fig.findobj(Text) if t.get_visible())
    return [t for t in texts if t and IDENTIFIER.search(re.sub(r"\$[^$]*\$", " ", t))]

def _param(path, marks=()):
    return pytest.param(path, id=path.stem, marks=marks)


ALL = [_param(p) for p in CASE_FILES]


@pytest.fixture(scope="session")
def notes(tmp_path_factory):
    """Build a case's note on first use: case → (pdf, text, figure problems)."""
    from reportgen.cli import main
    from reportgen.scenes import labels as L
    from reportgen.style import mplstyle
    out = tmp_path_factory.mktemp("all-notes")
    built: dict = {}

    def get(path):
        if path.stem in built:
            return built[path.stem]
        log = out / f"{path.stem}.figures.jsonl"
        orig = mplstyle.to_svg

        def checked(fig):
            problems = L.check_figure(fig)
            problems += [f"plain label: {t.get_text()!r}" for ax in fig.axes for t in ax.texts
                         if BARE.fullmatch(t.get_text())]
            problems += [f"{FIGURE_TEXT}{t!r}" for t in figure_identifiers(fig)]
            if problems:
                with open(log, "a", encoding="utf-8") as fh:
                    fh.write(json.dumps(problems, ensure_ascii=False) + "\n")
            return orig(fig)

        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(mplstyle, "to_svg", checked)
            assert main(["build", str(path), "-o", str(out), "--format", "pdf,html", "--jobs", "2"]) == 0, path.stem
        pdf = out / f"{path.stem}.pdf"
        text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True,
                              check=True).stdout
        found = [p for line in log.read_text(encoding="utf-8").splitlines() for p in json.loads(line)] \
            if log.exists() else []
        built[path.stem] = (pdf, text, found)
        return built[path.stem]

    return get


def test_every_case_is_checked():
    assert len(CASE_FILES) >= 30


@pytest.mark.parametrize("path", ALL)
def test_no_label_overlaps_or_clipping_in_any_figure(path, notes):
    _, _, found = notes(path)
    assert [p for p in found if not p.startswith(FIGURE_TEXT)] == []


@pytest.mark.parametrize("path", ALL)
def test_no_program_or_worksheet_identifiers_in_figures(path, notes):
    """A figure's texts (labels, legends, axis titles) are drawn as outlines, so the PDF text
    test above never saw them: ws002's figure 3.7 printed «R_A/ΣG», «G_max (исправлено)» and a
    curve «как в листе». Outside mathtext ($…$) no text holds an identifier or a worksheet."""
    _, _, found = notes(path)
    assert [p for p in found if p.startswith(FIGURE_TEXT)] == []


def case_notation(path) -> dict[str, str]:
    """The case's own names rendered as a letter with a subscript («Y_P56» → «yP56» in the PDF
    text): parameters the case titles but gives no symbol, whose subscript is not made of the
    mechanism's point and link names (l_AB, h_1 are textbook; P56 is not) → their titles."""
    from markupsafe import Markup
    from reportgen import load_case
    from reportgen.report.russian import param_symbol
    study = load_case(path)
    mech = study.mechanism if study.has_linkage else None
    names = ({p for l in mech.links for p in l.points} | {l.name for l in mech.links}) if mech else set()
    if not names:           # no linkage: no points to tell a textbook subscript by
        return {}
    textbook = re.compile("(?:%s)+" % "|".join(sorted(map(re.escape, names), key=len, reverse=True)))
    out = {}
    for name, (title, symbol) in study.spec.parameter_texts().items():
        sub = name.partition("_")[2]
        if title and not symbol and sub and not textbook.fullmatch(sub):
            out[Markup(param_symbol(name)).striptags()] = Markup(title).striptags()
    return out


def notation_hits(path, text: str) -> list[str]:
    """Lines of the note's text writing a case's own name (:func:`case_notation`) anywhere but its
    row of the given data (the line holding its title)."""
    return [line.strip() for rendered, title in case_notation(path).items() for line in text.splitlines()
            if re.search(r"(?<!\w)%s(?!\w)" % re.escape(rendered), line) and title[:24] not in line]


@pytest.mark.parametrize("path", ALL)
def test_no_program_or_worksheet_identifiers(path, notes):
    _, text, _ = notes(path)
    hits = notation_hits(path, text)
    hits += re.findall(r"\b\w+_\w+\b", text)
    hits += re.findall(r"\b(?:phi|omega|eps)\w*", text, re.I)
    hits += re.findall(r"\bлист(?!\s+формата)\w*", text, re.I)
    hits += [w for w in ("as printed", "Mathcad", "Совпадает") if w in text]
    assert sorted(set(hits)) == []


# nouns whose form the generators choose by the number before them
NOUNS = [("уравнение", "уравнения", "уравнений"), ("положение", "положения", "положений"),
         ("звено", "звена", "звеньев"), ("группа", "группы", "групп"), ("пара", "пары", "пар"),
         ("неизвестная", "неизвестные", "неизвестных"), ("зуб", "зуба", "зубьев"), ("точка", "точки", "точек"),
         ("сателлит", "сателлита", "сателлитов"), ("оборот", "оборота", "оборотов")]


@pytest.mark.parametrize("path", ALL)
def test_numerals_agree_with_nouns(path, notes):
    _, text, _ = notes(path)
    # without the page numbers: «Уравнение сил | 28 | группы» across a page break is no numeral
    text = re.sub(r"(?m)^[ \t]*\d+[ \t]*\n?(?=\f)", "", text)
    flat = re.sub(r"\s+", " ", text.replace("\u00a0", " "))
    bad = []
    for forms in NOUNS:
        for n, word in re.findall(rf"(?<![\w,.])(\d+) ({forms[2][:3]}\w*)", flat):
            if word in forms and word != plural_form(int(n), *forms):
                bad.append((n, word))
    assert bad == []


@pytest.mark.parametrize("path", ALL)
def test_every_table_column_has_a_header(path, notes):
    """synth_crank_rocker's table of solutions had a last column «принят» with an empty header."""
    pdf, _, _ = notes(path)
    html = pdf.with_suffix(".html").read_text(encoding="utf-8")
    assert re.findall(r"<th[^>]*>\s*</th>", html) == []


@pytest.mark.parametrize("path", ALL)
def test_page_fill(path, notes):
    pdf, _, _ = notes(path)
    assert short_pages(pdf) == []


@pytest.mark.parametrize("path", ALL)
def test_every_source_of_the_list_is_cited(path, notes):
    """ГОСТ 7.32: each source of the list is cited in the text as [n] (ГОСТ 2.770 and ГОСТ 7.32
    stood in every list and were cited nowhere)."""
    from reportgen.report.assemble import REFERENCES
    _, text, _ = notes(path)
    body = text.rsplit("СПИСОК ИСПОЛЬЗОВАННЫХ ИСТОЧНИКОВ", 1)[0]
    cited = {int(n) for g in re.findall(r"\[(\d+(?:,\s*\d+)*)\]", body) for n in re.split(r",\s*", g)}
    assert cited == set(range(1, len(REFERENCES) + 1))
