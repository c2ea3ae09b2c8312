"""The PDF laid out in parts (reportgen/report/parallel.py) against the same note laid out as
one document: same text page by page (contents numbers and footers included), right page
count, outline and links pointing at the pages of the headings, the same bytes with one
worker and with two, sections built in worker processes equal to sections built here."""
from __future__ import annotations

import re
import subprocess

import pytest
from conftest import CASES
from pypdf import PdfReader

from reportgen.report import parallel, render

SECTIONS = ["structure", "kinematics"]


def _norm(text: str) -> str:
    return re.sub(r"\s+", " ", text.replace("\u00a0", " ")).strip()


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    from reportgen.analysis.study import Study
    from reportgen.report.assemble import build_report

    out = tmp_path_factory.mktemp("parts")
    mp = pytest.MonkeyPatch()
    mp.setenv("REPORTGEN_CACHE", str(tmp_path_factory.mktemp("cache")))
    try:
        study = Study(CASES / "ws004_slotted_lever.toml")
        parallel.set_note_jobs(2)
        report2 = build_report(study, SECTIONS)  # sections built by two processes
        parallel.set_note_jobs(1)
        report1 = build_report(Study(CASES / "ws004_slotted_lever.toml"), SECTIONS)
        parallel.set_note_jobs(None)
        paths = {"two": render.write_pdf(report2, out / "two.pdf", jobs=2)}
        stats = render.last_stats
        paths["one"] = render.write_pdf(report1, out / "one.pdf", jobs=1)
        paths["again"] = render.write_pdf(report2, out / "again.pdf", jobs=2)
        mp.setenv("REPORTGEN_PARTS", "0")
        paths["whole"] = render.write_pdf(report1, out / "whole.pdf")
        paths["html1"] = render.write_html(report1, out / "one.html")
        paths["html2"] = render.write_html(report2, out / "two.html")
    finally:
        parallel.set_note_jobs(None)
        mp.undo()
    return paths | {"stats": stats}


def _pages(path, layout=False) -> list[str]:
    cmd = ["pdftotext", "-enc", "UTF-8"] + (["-layout"] if layout else []) + [str(path), "-"]
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout.split("\f")[:-1]


def test_laid_out_in_parts(built):
    st = built["stats"].parts
    assert st is not None and st.jobs == 2
    assert st.parts == 5  # ВВЕДЕНИЕ, two sections, ЗАКЛЮЧЕНИЕ, the references
    assert st.pages == len(PdfReader(built["two"]).pages)


def test_one_worker_equals_two_and_builds_repeat(built):
    two = built["two"].read_bytes()
    assert built["one"].read_bytes() == two
    assert built["again"].read_bytes() == two


def test_sections_built_in_workers_render_the_same(built):
    assert built["html1"].read_bytes() == built["html2"].read_bytes()


def test_same_text_as_one_document(built):
    parts, whole = _pages(built["two"], layout=True), _pages(built["whole"], layout=True)
    assert len(parts) == len(whole)
    for i, (a, b) in enumerate(zip(parts, whole)):
        assert _norm(a) == _norm(b), f"страница {i + 1}"


def test_footer_numbers_are_consecutive(built):
    pages = _pages(built["two"], layout=True)
    for i, text in enumerate(pages[1:], start=2):  # the title page has no number
        last = [ln for ln in text.splitlines() if ln.strip()][-1].strip()
        assert last == str(i), (i, last)


def _toc(pages: list[str]) -> list[tuple[str, int]]:
    toc_page = next(p for p in pages if p.lstrip().startswith("СОДЕРЖАНИЕ"))
    out = []
    for line in toc_page.splitlines()[1:]:
        m = re.match(r"^\s*(.+?)\s*\.{3,}\s*(\d+)\s*$", line)
        if m:
            out.append((_norm(m.group(1)), int(m.group(2))))
    return out


def test_contents_numbers_are_the_pages_of_the_headings(built):
    reader = PdfReader(built["two"])
    texts = [_norm(p.extract_text()) for p in reader.pages]
    entries = _toc(_pages(built["two"], layout=True))
    assert len(entries) >= 6
    for title, page in entries:
        assert title[:25] in texts[page - 1], (title, page)


def _outline(reader, items=None, depth=0):
    out = []
    for it in reader.outline if items is None else items:
        if isinstance(it, list):
            out += _outline(reader, it, depth + 1)
        else:
            out.append((depth, _norm(it.title), reader.get_destination_page_number(it), round(float(it.top))))
    return out


def test_outline_points_at_the_headings(built):
    parts, whole = PdfReader(built["two"]), PdfReader(built["whole"])
    outline = _outline(parts)
    assert outline == _outline(whole)
    texts = [_norm(p.extract_text()) for p in parts.pages]
    assert any(d == 1 for d, *_ in outline)  # subsections nested under their sections
    for _depth, title, page, _top in outline:
        assert title.split(" ", 1)[-1][:20] in texts[page], (title, page)


def test_contents_entries_link_to_their_pages(built):
    reader = PdfReader(built["two"])
    entries = _toc(_pages(built["two"], layout=True))
    toc_index = next(i for i, p in enumerate(reader.pages) if _norm(p.extract_text()).startswith("СОДЕРЖАНИЕ"))
    targets = []
    for annot in reader.pages[toc_index].get("/Annots", []):
        a = annot.get_object()
        if a.get("/Subtype") == "/Link":
            dest = a["/Dest"]
            assert not isinstance(dest, str)  # explicit destinations: the parts' names are gone
            targets.append((round(float(a["/Rect"][1])), reader.get_page_number(dest[0].indirect_reference)))
    # an entry is several boxes (number, title, leader), each a link: one line, one target
    lines = {}
    for y, page in targets:
        assert lines.setdefault(y, page) == page
    assert [lines[y] + 1 for y in sorted(lines, reverse=True)] == [page for _, page in entries]


def test_cross_references_between_parts_are_links(built):
    """A link in a section to a figure of another part keeps pointing at its page."""
    reader = PdfReader(built["two"])
    count = 0
    for i, page in enumerate(reader.pages):
        for annot in page.get("/Annots", []):
            a = annot.get_object()
            if a.get("/Subtype") == "/Link" and "/Dest" in a:
                count += 1
                assert 0 <= reader.get_page_number(a["/Dest"][0].indirect_reference) < len(reader.pages)
    whole = PdfReader(built["whole"])
    links = sum(1 for p in whole.pages for a in p.get("/Annots", []) if a.get_object().get("/Subtype") == "/Link")
    assert count == links


def test_note_jobs_setting(monkeypatch):
    monkeypatch.setattr(parallel, "_JOBS", None)
    monkeypatch.setenv("REPORTGEN_JOBS", "3")
    assert parallel.note_jobs() == 3
    parallel.set_note_jobs(1)
    assert parallel.note_jobs() == 1
    parallel.set_note_jobs(None)
    monkeypatch.delenv("REPORTGEN_JOBS")
    assert 1 <= parallel.note_jobs() <= 2


def test_options_that_need_one_document():
    opts = render.resolve_options({})
    assert parallel.can_split(opts)
    assert not parallel.can_split(render.resolve_options({"section_new_page": False}))
    assert not parallel.can_split(render.resolve_options({"eskd_frame": True}))


def test_an_error_in_a_worker_is_raised_as_in_one_process(monkeypatch):
    """A section that fails in a worker is built again in the parent: the user sees the
    same CaseError (exit 2), never a pickling error or a hung pool."""
    from reportgen.analysis.study import Study
    from reportgen.errors import CaseError
    from reportgen.report import assemble

    def broken(study):
        raise CaseError("сломанный раздел", key="kinematics")

    monkeypatch.setattr(assemble.SECTIONS["kinematics"][0], "build", broken)
    parallel.set_note_jobs(2)
    try:
        with pytest.raises(CaseError, match="сломанный раздел"):
            assemble.build_report(Study(CASES / "ws004_slotted_lever.toml"), SECTIONS)
    finally:
        parallel.set_note_jobs(None)


def test_pages_look_the_same_as_one_document(built, tmp_path):
    """Every page rendered at 30 dpi is the same image as the page of the one-document PDF
    (footer numbers drawn by the overlay included)."""
    from PIL import Image, ImageChops

    for name in ("two", "whole"):
        subprocess.run(["pdftoppm", "-r", "30", "-gray", str(built[name]), str(tmp_path / name)], check=True)
    pages = sorted(tmp_path.glob("two-*.pgm"))
    assert len(pages) == len(list(tmp_path.glob("whole-*.pgm"))) > 5
    for p in pages:
        other = tmp_path / p.name.replace("two-", "whole-")
        assert ImageChops.difference(Image.open(p), Image.open(other)).getbbox() is None, p.name


def test_build_jobs_must_be_positive(tmp_path, capsys):
    from reportgen.cli import main

    assert main(["build", str(CASES / "ws004_slotted_lever.toml"), "--jobs", "0", "-o", str(tmp_path)]) == 2
    assert "--jobs" in capsys.readouterr().err


def test_early_workers_give_the_same_bytes(built, tmp_path, monkeypatch):
    """Workers started before the report exists (the CLI's ``start_pool``) get the HTML with
    each task; with no split points remembered (a new cache folder, nothing in the process) the
    parts come back for another pass and are rendered again here: the same bytes all the same."""
    from reportgen.analysis.study import Study
    from reportgen.report.assemble import build_report

    monkeypatch.setenv("REPORTGEN_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(render, "_SPLIT_MEMO", {})
    parallel.set_note_jobs(1)  # the sections built here: only the layout goes to the workers
    parallel.start_pool(2)
    try:
        report = build_report(Study(CASES / "ws004_slotted_lever.toml"), SECTIONS)
        path = render.write_pdf(report, tmp_path / "early.pdf", jobs=2)
        passes = render.last_stats.passes
    finally:
        parallel.stop_pool()
        parallel.set_note_jobs(None)
    assert passes > 1  # the parent-driven passes were exercised
    assert path.read_bytes() == built["two"].read_bytes()


def test_data_urls_stashed_and_restored():
    html = ('<p>см. <a class="ref" href="#f1"></a></p><img src="data:image/svg+xml;base64,QUJD">'
            '<style>@font-face{src:url("data:font/ttf;base64,AAAA")}</style>')
    stashed, urls = render._stash_data_urls(html)
    assert urls == ["data:image/svg+xml;base64,QUJD", "data:font/ttf;base64,AAAA"]
    assert "data:" not in stashed
    assert render._restore_data_urls(stashed, urls) == html
    assert render._stash_data_urls("a\x00b") == ("a\x00b", [])
