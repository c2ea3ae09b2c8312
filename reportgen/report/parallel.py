"""The PDF of a note laid out in parts, in parallel processes, and joined with pypdf.

ГОСТ 7.32 starts every structural element and every section on a new page
(``section_new_page``), so each top-level part of the body (ВВЕДЕНИЕ, every
section, ЗАКЛЮЧЕНИЕ, the references, every appendix) is an independent layout
unit. The parts are laid out by WeasyPrint in a pool of worker processes (each
with its own «Продолжение таблицы» passes and its own remembered split points),
written to PDF there, and joined in order:

1. every body part is laid out and written without a page number in its footer
   (its first page number is not known until the parts before it are laid out);
2. the front matter (title page, assignment, СОДЕРЖАНИЕ) is laid out in the
   parent meanwhile with placeholder numbers, to learn its page count; then
   again with the contents' page numbers as text (``data-page``), taken from
   the anchors of the headings in the parts;
3. the page numbers of the body pages come from a third small document with as
   many empty pages as the note, the same ``@page`` rules and the usual
   ``counter(page)`` footer: each of its pages is drawn over the note's page of
   the same number;
4. internal links (contents entries, cross-references) and the outline
   (bookmarks, from WeasyPrint's own bookmark tree of each part) are written by
   pypdf with explicit destinations, so they point across parts.

The workers are forked (POSIX): they inherit the imports, the fonts, the parsed
images and the report itself, so a pool costs milliseconds. The joined bytes do
not depend on the number of workers (each part is laid out and written alone
either way), and are the same from build to build (fixed font time stamp, no
date, no random file identifier).

Not used (the note is laid out as one document) when sections do not start on
a new page or with the ЕСКД frame, whose stamp holds the page number inside
the page's running element.
"""
from __future__ import annotations

import io
import multiprocessing
import os
import time
from dataclasses import dataclass, field

from .document import Report

__all__ = ["note_jobs", "set_note_jobs", "can_split", "PartsJob"]

PX_PT = 0.75  # CSS px → PDF pt (WeasyPrint: 96 px per inch)
PLACEHOLDER = "00"  # width of a page number in the contents before the numbers are known
MAX_FRONT_PASSES = 4

_JOBS: int | None = None  # set by the CLI (--jobs) or a batch worker (1)
_REPORT: Report | None = None  # the report being laid out: inherited by the forked workers


def set_note_jobs(n: int | None) -> None:
    """Processes for laying out one note (``None``: the default of :func:`note_jobs`)."""
    global _JOBS
    _JOBS = None if n is None else max(1, int(n))


def note_jobs() -> int:
    """Processes laying out one note: :func:`set_note_jobs`, else ``REPORTGEN_JOBS``, else
    min(2, cores). One where ``fork`` is not available (each worker would re-import
    everything)."""
    if "fork" not in multiprocessing.get_all_start_methods():
        return 1
    if _JOBS is not None:
        return _JOBS
    env = os.environ.get("REPORTGEN_JOBS", "").strip()
    if env.isdigit() and int(env) >= 1:
        return int(env)
    return max(1, min(2, os.cpu_count() or 1))


def can_split(opts: dict) -> bool:
    """The note can be laid out in parts: every top-level part starts a page and the page
    number is a plain footer."""
    return bool(opts["section_new_page"]) and not opts["eskd_frame"]


# ---------------------------------------------------------------- one part (in a worker)


@dataclass
class _Laid:
    """What the parent needs of a laid-out part (plain data: it crosses processes)."""

    index: int
    pdf: bytes
    heights: list  # page heights, CSS px
    anchors: dict  # id -> (page, x_pt, y_pt) (first occurrence)
    links: list  # (page, target id, (x1, y1, x2, y2) pt)
    outline: list  # (label, page, x_pt, y_pt, children)
    splits: dict  # split points of the part's tables
    passes: int = 1
    seconds_layout: float = 0.0
    seconds_write: float = 0.0
    key: str = ""
    known: bool = False  # split points were remembered
    refused: list = field(default_factory=list)  # URLs the fetcher refused (safety.refused)


def _outline(tree) -> list:
    return [(label, page, x, y, _outline(children)) for label, (page, x, y), children, _ in tree]


def _facts(document) -> tuple[list, dict, list, list]:
    heights = [p.height for p in document.pages]
    anchors: dict = {}
    links = []
    for i, page in enumerate(document.pages):
        h = page.height
        for name, (x, y, *_rest) in page.anchors.items():
            anchors.setdefault(name, (i, x * PX_PT, (h - y) * PX_PT))
        for kind, target, rect, _box in page.links:
            if kind == "internal":
                x1, y1, x2, y2 = rect
                links.append((i, target, (x1 * PX_PT, (h - y2) * PX_PT, x2 * PX_PT, (h - y1) * PX_PT)))
    outline = _outline(document.make_bookmark_tree(scale=PX_PT, transform_pages=True))
    return heights, anchors, links, outline


def _part_html(report: Report, index: int | None, splits: dict, toc_pages: dict | None = None) -> str:
    """The print HTML of body part ``index`` (``None``: the front matter) with ``splits``."""
    from .render import _views

    views = _views(report, for_print=True, splits=splits)
    if index is None:
        return views.html(body=[], toc_pages=toc_pages)
    return views.html(front=False, body=[views.ctx["body"][index]], chunk=True)


def _lay_out(html: str):
    from weasyprint import HTML

    from .render import TEMPLATES_DIR, _font_config, _image_cache, _quiet_weasyprint
    from .safety import url_fetcher

    _quiet_weasyprint()
    return HTML(string=html, base_url=str(TEMPLATES_DIR), url_fetcher=url_fetcher()).render(
        font_config=_font_config(), cache=_image_cache())


def _write(document) -> bytes:
    from .render import _fixed_font_timestamp

    with _fixed_font_timestamp():
        return document.write_pdf()


def _lay_out_in_worker(task: tuple) -> _Laid | None:
    """:func:`lay_out_part` in a worker; ``None`` when it failed (the parent lays the part out
    again itself, so the error is raised there as in a build in one process)."""
    try:
        return lay_out_part(task)
    except Exception:
        return None


def lay_out_part(task: tuple) -> _Laid:
    """Lay out body part ``index`` (its table split passes included) and write it."""
    from .render import MAX_PASSES, _next_splits, _page_rows

    from . import safety

    index, html, splits, key, known = task
    splits = dict(splits)
    seen = len(safety.refused)
    t0 = time.perf_counter()
    passes = 0
    while True:
        document = _lay_out(html)
        passes += 1
        new = _next_splits(document, splits)
        if new is None or passes >= MAX_PASSES:
            break
        splits = new
        html = _part_html(_REPORT, index, splits)
    t1 = time.perf_counter()
    pdf = _write(document)
    t2 = time.perf_counter()
    heights, anchors, links, outline = _facts(document)
    mine = {tid: list(splits[tid]) for tid in _page_rows(document) if tid in splits}
    refused = list(safety.refused[seen:] if len(safety.refused) >= seen else safety.refused)
    return _Laid(index, pdf, heights, anchors, links, outline, mine, passes, t1 - t0, t2 - t1, key, known, refused)


# ---------------------------------------------------------------- the whole note (parent)


@dataclass
class PartsStats:
    parts: int = 0
    jobs: int = 1
    pages: int = 0
    passes: int = 0
    splits: dict = field(default_factory=dict)
    seconds_html: float = 0.0
    seconds_layout: float = 0.0  # summed over the parts (CPU of the workers)
    seconds_write: float = 0.0
    seconds_front: float = 0.0
    seconds_join: float = 0.0
    part_seconds: list = field(default_factory=list)


class PartsJob:
    """``PartsJob(report, jobs)`` starts laying out the parts (in the background when
    ``jobs > 1``); :meth:`finish` returns the joined PDF bytes. Between the two the caller
    may do other work (the screen HTML)."""

    def __init__(self, report: Report, jobs: int):
        from .render import _check_glyphs, _recall_splits, _split_key, _views

        global _REPORT
        t0 = time.perf_counter()
        self.report = report
        views = _views(report, for_print=True, splits={})
        body = views.ctx["body"]
        bare = [views.html(front=False, body=[node], chunk=True) for node in body]
        keys = [_split_key(h) for h in bare]
        known = [_recall_splits(k) or {} for k in keys]
        splits = {tid: cuts for part in known for tid, cuts in part.items()}
        if splits:
            views = _views(report, for_print=True, splits=splits)
            body = views.ctx["body"]
            htmls = [views.html(front=False, body=[node], chunk=True) if known[i] else bare[i]
                     for i, node in enumerate(body)]
        else:
            htmls = bare
        self.views = views
        self.front_html = lambda toc_pages: views.html(body=[], toc_pages=toc_pages)
        placeholder = {e["id"]: PLACEHOLDER for e in views.builder.toc}
        front = self.front_html(placeholder)
        _check_glyphs(front + "".join(htmls), views.family)
        self.stats = PartsStats(parts=len(body), jobs=jobs, seconds_html=time.perf_counter() - t0)
        # the largest parts first: with a pool that takes the next task when a worker is free,
        # this is the longest-processing-time-first schedule
        tasks = [(i, htmls[i], {t: c for t, c in splits.items()}, keys[i], bool(known[i]))
                 for i in range(len(body))]
        tasks.sort(key=lambda t: (-_cost(t[1]), t[0]))
        _REPORT = report
        self.pool = None
        self.pending = None
        self.tasks = tasks
        if jobs > 1 and len(tasks) > 1:
            from .render import _font_config

            _font_config()  # loaded once, inherited by the workers
            self.pool = multiprocessing.get_context("fork").Pool(min(jobs, len(tasks)))
            self.pending = self.pool.map_async(_lay_out_in_worker, tasks, chunksize=1)
        t1 = time.perf_counter()
        self.front_doc = _lay_out(front)  # page count of the front matter, meanwhile
        self.stats.seconds_front += time.perf_counter() - t1

    def _results(self) -> list[_Laid]:
        from . import safety

        try:
            if self.pending is not None:
                laid = self.pending.get()
                laid = [r if r is not None else lay_out_part(t) for r, t in zip(laid, self.tasks)]
                for p in sorted(laid, key=lambda r: r.index):  # what the workers refused, recorded here
                    safety.refused.extend(p.refused)
                del safety.refused[:-100]
            else:
                laid = [lay_out_part(t) for t in self.tasks]
        finally:
            self.close()
        return sorted(laid, key=lambda r: r.index)

    def close(self) -> None:
        """Stop the workers (after :meth:`finish`, or when the build failed before it)."""
        global _REPORT
        if self.pool is not None:
            self.pool.terminate()
            self.pool.join()
            self.pool = None
        _REPORT = None

    def finish(self) -> bytes:
        from .render import _remember_splits

        parts = self._results()
        st = self.stats
        for p in parts:
            st.seconds_layout += p.seconds_layout
            st.seconds_write += p.seconds_write
            st.passes = max(st.passes, p.passes)
            st.splits.update(p.splits)
            st.part_seconds.append(round(p.seconds_layout + p.seconds_write, 3))
            if p.splits and not (p.known and p.passes == 1):
                _remember_splits(p.key, p.splits)
        t0 = time.perf_counter()
        front_doc = self.front_doc
        for _ in range(MAX_FRONT_PASSES):
            n_front = len(front_doc.pages)
            starts, n = [], n_front
            for p in parts:
                starts.append(n)
                n += len(p.heights)
            toc_pages = {}
            for e in self.views.builder.toc:
                for p, s in zip(parts, starts):
                    if e["id"] in p.anchors:
                        toc_pages[e["id"]] = str(s + p.anchors[e["id"]][0] + 1)
                        break
            front_doc = _lay_out(self.front_html(toc_pages))
            if len(front_doc.pages) == n_front:
                break
        front_pdf = _write(front_doc)
        heights, anchors, links, outline = _facts(front_doc)
        front = _Laid(-1, front_pdf, heights, anchors, links, outline, {})
        # the pages turned to landscape (a wide figure) get their footer number on a landscape page
        turned = {i for i, h in enumerate(h for p in [front] + parts for h in p.heights) if h < LANDSCAPE_BELOW}
        numbers = _numbers_pdf(self.views, n, turned)
        st.seconds_front += time.perf_counter() - t0
        t0 = time.perf_counter()
        pdf = join([front] + parts, numbers, first_numbered=len(front.heights))
        st.seconds_join = time.perf_counter() - t0
        st.pages = n
        return pdf


def _cost(html: str) -> float:
    """A rough layout cost of a part, for the order of the tasks: table cells dominate
    (about 1 ms each), then text and images."""
    import re

    text = re.sub(r"data:[^\"')]+", "", html)
    return html.count("<td") + 0.5 * html.count("<img") + len(text) / 2000


# a page lower than this (CSS px) is an A4 page turned to landscape (595 pt = 793,7 px high)
LANDSCAPE_BELOW = 1000.0


def _numbers_html(views, n: int, turned: frozenset | set = frozenset()) -> str:
    """``n`` empty pages with the note's ``@page`` rules: the page numbers of the footer; the
    pages ``turned`` (0-based) on the landscape page, as in the note."""
    from markupsafe import Markup

    from .render import _get_env

    css = _get_env().get_template("gost.css").render(**views.ctx["css_ctx"])
    pages = "".join('<div style="{}{}"></div>'.format("page: landscape; " if i in turned else "",
                                                    "break-after: page" if i < n - 1 else "") for i in range(n))
    return (f'<!DOCTYPE html><html lang="ru"><head><meta charset="utf-8"><style>{views.ctx["font_css"]}'
            f"</style><style>{Markup(css)}</style></head><body>{pages}</body></html>")


def _overlay(writer, page, over, name: str) -> None:
    """Draw page ``over`` (of another PDF) on ``page`` as a form XObject: the page's own
    content stays as WeasyPrint compressed it, wrapped in q … Q, and one short stream is
    added."""
    from pypdf.generic import (ArrayObject, DecodedStreamObject, DictionaryObject, FloatObject,
                               NameObject)

    form = DecodedStreamObject()
    form.set_data(over.get_contents().get_data())
    form[NameObject("/Type")] = NameObject("/XObject")
    form[NameObject("/Subtype")] = NameObject("/Form")
    form[NameObject("/BBox")] = ArrayObject(FloatObject(v) for v in over.mediabox)
    form[NameObject("/Resources")] = over["/Resources"].clone(writer)
    form = form.flate_encode()
    ref = writer._add_object(form)
    res = page["/Resources"].get_object()
    if "/XObject" not in res:
        res[NameObject("/XObject")] = DictionaryObject()
    res["/XObject"].get_object()[NameObject(name)] = ref
    contents = page.raw_get("/Contents")  # the reference: the stream itself must not be copied inline
    old = list(contents.get_object()) if isinstance(contents.get_object(), ArrayObject) else [contents]
    head, tail = DecodedStreamObject(), DecodedStreamObject()
    head.set_data(b"q\n")
    tail.set_data(f"\nQ q {name} Do Q\n".encode("ascii"))
    page[NameObject("/Contents")] = ArrayObject([writer._add_object(head), *old, writer._add_object(tail)])


_NUMBERS_MEMO: dict[str, bytes] = {}


def _numbers_pdf(views, n: int, turned: frozenset | set = frozenset()) -> bytes:
    """The PDF of :func:`_numbers_html`, remembered in the process and in the cache folder
    (``<cache>/pages``): it depends on the page setup and the count only, and WeasyPrint
    writes it byte for byte the same, so a remembered one changes nothing in the note."""
    import hashlib

    import weasyprint

    from .formulas import _cache_dir
    from .render import _atomic_write

    html = _numbers_html(views, n, turned)
    key = hashlib.sha256(f"{weasyprint.__version__}|{html}".encode("utf-8")).hexdigest()
    if key in _NUMBERS_MEMO:
        return _NUMBERS_MEMO[key]
    folder = _cache_dir()
    path = None if folder is None else folder.parent / "pages" / f"{key}.pdf"
    pdf = None
    if path is not None:
        try:
            pdf = path.read_bytes()
        except OSError:
            pdf = None
    if not pdf or not pdf.startswith(b"%PDF"):
        pdf = _write(_lay_out(html))
        if path is not None:
            try:
                _atomic_write(path, pdf)
            except OSError:
                pass  # a read-only cache folder is no reason to fail a report
    if len(_NUMBERS_MEMO) > 16:
        _NUMBERS_MEMO.clear()
    _NUMBERS_MEMO[key] = pdf
    return pdf


def join(parts: list[_Laid], numbers: bytes, first_numbered: int) -> bytes:
    """One PDF of the laid-out parts in order: pages, the footer numbers of ``numbers`` drawn
    on every page from ``first_numbered`` (0-based), internal links and the outline with
    explicit destinations, the document information of the first part."""
    from pypdf import PdfReader, PdfWriter
    from pypdf.annotations import Link
    from pypdf.generic import ArrayObject, Fit, NameObject

    writer = PdfWriter()
    starts = []
    meta = None
    for p in parts:
        reader = PdfReader(io.BytesIO(p.pdf))
        if meta is None:
            meta = reader.metadata
        starts.append(len(writer.pages))
        for page in reader.pages:
            annots = page.get("/Annots")
            if annots is not None:  # internal links are made below, with explicit destinations
                keep = [a for a in annots if "/Dest" not in a.get_object()]
                if keep:
                    page[NameObject("/Annots")] = ArrayObject(keep)
                else:
                    del page["/Annots"]
            writer.add_page(page)
    num_reader = PdfReader(io.BytesIO(numbers))
    for i in range(first_numbered, len(writer.pages)):
        _overlay(writer, writer.pages[i], num_reader.pages[i], f"/RGnum{i}")
    anchors = {}
    for p, s in zip(parts, starts):
        for name, (page, x, y) in p.anchors.items():
            anchors.setdefault(name, (s + page, x, y))
    for p, s in zip(parts, starts):
        for page, target, rect in p.links:
            if target in anchors:
                tp, x, y = anchors[target]
                writer.add_annotation(s + page, Link(rect=rect, border=[0, 0, 0], target_page_index=tp,
                                                     fit=Fit.xyz(left=x, top=y, zoom=0)))

    def outline(items, start, parent=None):
        for label, page, x, y, children in items:
            node = writer.add_outline_item(title=label, page_number=start + page, parent=parent,
                                           fit=Fit.xyz(left=x, top=y, zoom=0))
            outline(children, start, node)

    for p, s in zip(parts, starts):
        outline(p.outline, s)
    if meta:
        writer.add_metadata({k: v for k, v in meta.items()})
    buf = io.BytesIO()
    writer.write(buf)
    return buf.getvalue()
