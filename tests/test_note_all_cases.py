"""Issue 9, «Done when», over EVERY case in cases/ (not a hand-picked subset): the student's note of
each case is built once (a session fixture, ``build --jobs 2`` per case) and every check reads
that output:

* every figure drawn for the notes (each scene, each chart) has no two labels overlapping and
  none clipped (matplotlib's rendered extents, ``scenes.labels.check_figure``), and its labels
  are in textbook notation (no bare «nbc», «S2»);
* the PDF text holds no identifier of the program or the case (``\\w+_\\w+``, Latin phi/omega/eps,
  «as printed», «лист»);
* numerals agree with their nouns in the generated sentences;
* no page is less than half full without a reason (``pagefill.short_pages``).

The figures are checked as they are drawn: ``mplstyle.to_svg`` is wrapped for the session, and
the section workers are forked, so they inherit the wrapper and append what they find to a log."""
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
NAMES = [p.stem for p in CASE_FILES]
BARE = re.compile(r"[a-zA-Z]+\d+|n[a-z]{2,}")      # a point label not in textbook notation


@pytest.fixture(scope="session")
def notes(tmp_path_factory):
    """{case: (pdf, text)} and the log of figure problems [(case, problem)], for every case."""
    from reportgen.cli import main
    from reportgen.scenes import labels as L
    from reportgen.style import mplstyle
    out = tmp_path_factory.mktemp("all-notes")
    log = out / "figures.jsonl"
    orig = mplstyle.to_svg

    def checked(fig):
        problems = L.check_figure(fig)
        problems += [f"plain label: {t.get_text()!r}" for ax in fig.axes for t in ax.texts
                     if BARE.fullmatch(t.get_text())]
        if problems:
            with open(log, "a", encoding="utf-8") as fh:
                fh.write(json.dumps({"problems": problems}, ensure_ascii=False) + "\n")
        return orig(fig)

    built = {}
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(mplstyle, "to_svg", checked)
        for path in CASE_FILES:
            with open(log, "a", encoding="utf-8") as fh:
                fh.write(json.dumps({"case": path.stem}) + "\n")
            assert main(["build", str(path), "-o", str(out), "--format", "pdf", "--jobs", "2"]) == 0, path.stem
            pdf = out / f"{path.stem}.pdf"
            text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True,
                                  check=True).stdout
            built[path.stem] = (pdf, text)
    found, case = [], None
    for line in log.read_text(encoding="utf-8").splitlines():
        rec = json.loads(line)
        if "case" in rec:
            case = rec["case"]
        else:
            found += [(case, p) for p in rec["problems"]]
    return built, found


def test_every_case_has_its_note(notes):
    built, _ = notes
    assert sorted(built) == sorted(NAMES) and len(NAMES) >= 30


def test_no_label_overlaps_or_clipping_in_any_figure(notes):
    _, found = notes
    assert found == []


def test_no_program_or_worksheet_identifiers(notes):
    built, _ = notes
    bad = {}
    for name, (_, text) in built.items():
        hits = re.findall(r"\b\w+_\w+\b", text)
        hits += re.findall(r"\b(?:phi|omega|eps)\w*", text, re.I)
        hits += [w for w in ("as printed", "лист", "Mathcad", "Совпадает") if w in text]
        if hits:
            bad[name] = sorted(set(hits))[:8]
    assert bad == {}


# nouns whose form the generators choose by the number before them
NOUNS = [("уравнение", "уравнения", "уравнений"), ("положение", "положения", "положений"),
         ("звено", "звена", "звеньев"), ("группа", "группы", "групп"), ("пара", "пары", "пар"),
         ("неизвестная", "неизвестные", "неизвестных"), ("зуб", "зуба", "зубьев"), ("точка", "точки", "точек"),
         ("сателлит", "сателлита", "сателлитов"), ("оборот", "оборота", "оборотов")]


def test_numerals_agree_with_nouns(notes):
    built, _ = notes
    bad = []
    for name, (_, text) in built.items():
        flat = re.sub(r"\s+", " ", text.replace("\u00a0", " "))
        for forms in NOUNS:
            stem = forms[2][:3]
            for n, word in re.findall(rf"(?<![\d,.])(\d+) ({stem}\w*)", flat):
                if word in forms and word != plural_form(int(n), *forms):
                    bad.append((name, n, word))
    assert bad == []


def test_page_fill(notes):
    built, _ = notes
    short = {name: short_pages(pdf) for name, (pdf, _) in built.items()}
    assert {k: v for k, v in short.items() if v} == {}
