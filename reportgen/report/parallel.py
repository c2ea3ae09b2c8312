"""The PDF of a note laid out in parts, in parallel processes, and joined with pypdf.

ГОСТ 7.32 starts every structural element and every section on a new page
(``section_new_page``), so each top-level part of the body (ВВЕДЕНИЕ, every
section, ЗАКЛЮЧЕНИЕ, the references, every appendix) is an independent layout
unit. The parts are laid out by WeasyPrint in a pool of worker processes (each
with its own «Продолжение таблицы» passes and its own remembered split points),
written to PDF there, and joined in order:

1. every body part is laid out and written without a page number in its footer
   (its first page number is not known until the parts before it are laid out);
2. the title page with the assignment is one more such part (laid out once), and
   СОДЕРЖАНИЕ is laid out meanwhile with placeholder numbers, to learn its page
   count; then again with the page numbers of the headings as text
   (``data-page``), taken from the anchors of the headings in the parts;
3. the page numbers come from a third small document with as many empty pages
   as the note, the same ``@page`` rules (no number on the first page) and the
   usual ``counter(page)`` footer: each of its pages is drawn over the note's
   page of the same number;
4. internal links (contents entries, cross-references) and the outline
   (bookmarks, from WeasyPrint's own bookmark tree of each part) are written by
   pypdf with explicit destinations, so they point across parts.

The workers are forked (POSIX): they inherit the imports, the fonts, the parsed
images and the report itself, so a pool costs milliseconds. The CLI starts them
before anything else (:func:`start_pool`): they import WeasyPrint on the second
core while the parent imports the rest, computes and builds the sections, and
the parent never imports WeasyPrint; such workers get each part's HTML with its
task. The joined bytes do
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
import re
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the CLI imports this module before anything heavy (start_pool)
    from .document import Report

__all__ = ["note_jobs", "set_note_jobs", "can_split", "PartsJob", "start_pool", "stop_pool"]

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


# ---------------------------------------------------------------- the workers

_POOL = None  # workers started early by the CLI (start_pool), used by every PartsJob of the process
_POOL_JOBS = 0


def start_pool(jobs: int | None = None) -> None:
    """Start the layout workers now, before the report exists: the CLI calls it first thing,
    so the workers import WeasyPrint and load the fonts while the parent imports the rest,
    computes the case and builds the sections (the second core is idle meanwhile). Such
    workers get each part's HTML with its task (they have no report to render it from); a
    part whose tables need another layout pass is rendered again here and sent back. Nothing
    happens with one process or without ``fork``; :func:`stop_pool` ends the workers."""
    global _POOL, _POOL_JOBS
    n = note_jobs() if jobs is None else max(1, int(jobs))
    if _POOL is not None or n < 2 or "fork" not in multiprocessing.get_all_start_methods():
        return
    if os.environ.get("REPORTGEN_PARTS", "1") == "0":
        return
    _POOL = multiprocessing.get_context("fork").Pool(n, initializer=_warm_worker)
    _POOL_JOBS = n


def stop_pool() -> None:
    """End the workers of :func:`start_pool` (if any)."""
    global _POOL, _POOL_JOBS
    if _POOL is not None:
        _POOL.terminate()
        _POOL.join()
    _POOL, _POOL_JOBS = None, 0


def _warm_worker() -> None:
    """Initializer of an early worker: WeasyPrint imported, the fonts loaded, the user-agent
    stylesheet parsed. A failure here is left to the first task (which then fails, and the
    parent lays the part out itself and reports the error as a build in one process does)."""
    try:
        from .render import _font_config, _html_class, _quiet_weasyprint

        _quiet_weasyprint()
        _html_class()
        _font_config()
    except Exception:
        pass


def _forked_worker() -> None:
    """Initializer of a worker forked by :class:`PartsJob` (the API's way, not the CLI's early
    workers): the collector set as the CLI sets it for its whole process
    (:func:`~reportgen.core.memory.collect_less`), and the objects inherited from the parent
    (the study, the report, the imported modules) moved out of its sight (``gc.freeze``, as
    the section workers do: ``assemble._freeze_inherited``), so the collections while a part
    is laid out scan only the worker's own objects. ws000 in a process holding its study
    (``python bench/bench_pdf_parts.py --runs 2``, alternated, load 8–12): the three heavy parts
    2,06/2,23/1,41 → 1,63–1,76/1,75–1,91/1,14–1,29 s CPU; ``write_pdf`` 7,1–7,4 → 5,9–6,5 s CPU."""
    import gc

    from ..core.memory import collect_less

    gc.freeze()
    collect_less()


# ---------------------------------------------------------------- one part (in a worker)

HEAD = -2  # task index of the title page and the assignment (laid out once, no numbers of its own)
TOC = -1  # task index of СОДЕРЖАНИЕ
NUMBERS = -3  # task index of the page-number document (_numbers_html)


@dataclass
class _Task:
    """One document to lay out: body part ``index`` (0, 1, …) or :data:`HEAD`, :data:`TOC`,
    :data:`NUMBERS` (laid out once: their tables are never split)."""

    index: int
    html: str
    splits: dict
    key: str = ""
    start: str = ""  # the split points are remembered: "known" (this HTML) or "guess" (render._start_splits)
    passes: int = 0  # layout passes made before (by an early worker, see start_pool)
    shape: tuple = ()  # the keys its split points are remembered under as a guess (render._start_splits)
    state: dict = field(default_factory=dict)  # of the fast passes (render._settle_step)


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
    start: str = ""  # the remembered split points kept ("known", "guess") or none ("")
    refused: list = field(default_factory=list)  # URLs the fetcher refused (safety.refused)
    resplit: dict | None = None  # an early worker asks for the part rendered with these split points
    shape: tuple = ()
    state: dict = field(default_factory=dict)  # of the fast passes, sent back with a resplit


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


def _part_html(report, index: int, splits: dict, views=None) -> str:
    """The print HTML of body part ``index`` with ``splits``, from ``views`` (the print views of
    ``report``, cut again at ``splits``) or views made here."""
    from .render import _views

    if views is None:
        views = _views(report, for_print=True, splits=splits)
    else:
        views.builder.resplit(splits)
    return views.html(front=False, body=[views.ctx["body"][index]], chunk=True)


def _lay_out(html: str, prev=None, record=None):
    """The WeasyPrint document of ``html``; with ``prev`` (a :class:`~.relayout.Laid` of the same
    part's layout before) its pages before the first one the changed HTML may read are taken
    over (:func:`~.relayout.incremental`: the same pages); ``record`` gets this layout's."""
    from . import svgops
    from .relayout import incremental
    from .render import TEMPLATES_DIR, _font_config, _html_class, _image_cache, _quiet_weasyprint
    from .safety import url_fetcher

    _quiet_weasyprint()
    cache = _image_cache()
    svgops.prime(cache, html)  # figures drawn from precompiled PDF operators
    with incremental(prev, record if record is not None else []):
        return _html_class()(string=html, base_url=str(TEMPLATES_DIR), url_fetcher=url_fetcher()).render(
            font_config=_font_config(), cache=cache)


def _write(document) -> bytes:
    from .render import _fixed_font_timestamp
    from .wpfast import writing

    with _fixed_font_timestamp(), writing():
        return document.write_pdf()


_RESPLIT_FROM: dict = {}  # part index -> this process's last layout of it, sent back for a resplit


def _lay_out_in_worker(task: _Task) -> _Laid | None:
    """:func:`lay_out_part` in a worker; ``None`` when it failed (the parent lays the part out
    again itself, so the error is raised there as in a build in one process)."""
    try:
        return lay_out_part(task)
    except Exception:
        return None


def lay_out_part(task: _Task) -> _Laid:
    """Lay out one document of the note (a body part with its table split passes) and write it.
    The passes are :func:`~reportgen.report.render._next_pass`'s: a part starting from
    remembered split points (``task.start``) keeps them only where they are proved to be the
    canonical ones, and the passes end only on those. In an early worker (no report here) a part that needs another
    pass comes back with ``resplit``: the parent renders it with those split points and sends
    it again."""
    from . import safety
    from .render import MAX_PASSES, _next_pass, _page_rows, split_target

    index, html, splits, start = task.index, task.html, dict(task.splits), task.start
    seen = len(safety.refused)
    t0 = time.perf_counter()
    passes = task.passes
    state = dict(task.state)  # of the fast passes (render._settle_step), carried by a resplit
    # each pass's layout, whose pages before the first change the next one takes over; a resplit
    # (the next pass of a part sent back by the parent) takes this process's layout of that part
    # when it made it (any earlier layout is safe: the pages are compared, relayout.incremental)
    laid: list = [_RESPLIT_FROM.pop(index)] if task.passes and index in _RESPLIT_FROM else []
    _RESPLIT_FROM.clear()
    while True:
        document = _lay_out(html, laid[-1] if laid else None, laid)
        del laid[:-1]
        passes += 1
        if index < 0:
            new = None
        else:
            new, start = _next_pass(document, splits, start, state)
        if new is None or passes >= MAX_PASSES:
            break
        if _REPORT is None:
            _RESPLIT_FROM[index] = laid[-1]
            return _Laid(index, b"", [], {}, [], [], {}, passes, time.perf_counter() - t0, 0.0,
                         task.key, start, resplit=new, shape=task.shape, state=state)
        splits = new
        html = _part_html(_REPORT, index, splits)
    t1 = time.perf_counter()
    pdf = _write(document)
    t2 = time.perf_counter()
    heights, anchors, links, outline = _facts(document)
    own = set(_page_rows(document)) | {name for page in document.pages for name in page.anchors}
    mine = {k: list(v) for k, v in splits.items() if k in own or split_target(k) in own}
    refused = list(safety.refused[seen:] if len(safety.refused) >= seen else safety.refused)
    return _Laid(index, pdf, heights, anchors, links, outline, mine, passes, t1 - t0, t2 - t1,
                 task.key, start, refused, shape=task.shape)


# ---------------------------------------------------------------- the whole note (parent)


@dataclass
class PartsStats:
    parts: int = 0
    jobs: int = 1
    pages: int = 0
    passes: int = 0  # the most layout passes of a part
    part_passes: list = field(default_factory=list)  # layout passes of each body part, in order
    splits: dict = field(default_factory=dict)
    seconds_html: float = 0.0
    seconds_layout: float = 0.0  # summed over the parts (CPU of the workers)
    seconds_write: float = 0.0
    seconds_front: float = 0.0  # title page, assignment and contents (layout + write)
    seconds_join: float = 0.0
    seconds_wait: float = 0.0  # the parent waiting for the workers in finish()
    toc_layouts: int = 0  # СОДЕРЖАНИЕ laid out this many times (1 when its numbers were remembered right)
    part_seconds: list = field(default_factory=list)


class PartsJob:
    """``PartsJob(report, jobs)`` starts laying out the parts (in the background when
    ``jobs > 1``); :meth:`finish` returns the joined PDF bytes. Between the two the caller
    may do other work (the screen HTML).

    The documents laid out: the title page with the assignment (:data:`HEAD`, laid out once:
    no page number of its own), every body part, and СОДЕРЖАНИЕ (:data:`TOC`) twice, first with
    placeholder numbers (its page count) and then, when the parts are laid out, with the page
    numbers of the headings. The workers are those of :func:`start_pool` when the CLI started
    them, else a pool forked here (the workers inherit the report)."""

    def __init__(self, report: Report, jobs: int):
        import queue

        from .render import _check_glyphs, _start_splits, _views, split_target

        global _REPORT
        t0 = time.perf_counter()
        self.report = report
        views = _views(report, for_print=True, splits={})
        body = views.ctx["body"]
        bare = [views.html(front=False, body=[node], chunk=True) for node in body]
        starts = [_start_splits(h) for h in bare]  # (key, guess keys, split points, start) per part
        known = [{tid: cuts for tid, cuts in s[2].items() if f'id="{split_target(tid)}"' in h}  # its own tables and figures
                 for s, h in zip(starts, bare)]
        splits = {tid: cuts for part in known for tid, cuts in part.items()}
        if splits:
            views.builder.resplit(splits)  # (the same views: numbering and rows do not change)
            htmls = [views.html(front=False, body=[node], chunk=True) if known[i] else bare[i]
                     for i, node in enumerate(body)]
        else:
            htmls = bare
        self.views = views
        # (``toc_pages`` given: no empty <main> after the assignment, which would be a blank page)
        head = views.html(body=[], toc=False, toc_pages={}, chunk=True) \
            if views.ctx["title_page"] or views.ctx["show_assignment"] else None
        placeholder = {e["id"]: PLACEHOLDER for e in views.builder.toc}
        toc = self._toc_html(placeholder)
        _check_glyphs((head or "") + toc + "".join(htmls), views.family)
        # СОДЕРЖАНИЕ laid out once when its page numbers are remembered (see _recall_toc)
        self.toc_key = _toc_key(toc)
        self.toc_guess = _recall_toc(self.toc_key, [e["id"] for e in views.builder.toc])
        if self.toc_guess is not None:
            toc = self._toc_html(self.toc_guess[1])
        self.stats = PartsStats(parts=len(body), jobs=jobs, seconds_html=time.perf_counter() - t0)
        tasks = [_Task(i, htmls[i], dict(splits), starts[i][0], starts[i][3] if known[i] else "", shape=starts[i][1])
                 for i in range(len(body))]
        if head is not None:
            tasks.append(_Task(HEAD, head, {}))
        tasks.append(_Task(TOC, toc, {}))
        # the largest documents first: with a pool that takes the next task when a worker is
        # free, this is the longest-processing-time-first schedule
        tasks.sort(key=lambda t: (-_cost(t.html), t.index))
        _REPORT = report
        self.done: dict[int, _Laid] = {}
        self.readers: dict = {}  # id(part) -> (part, its PDF parsed as it came back: prepare)
        self.waiting: set[int] = set()
        self.results: queue.Queue = queue.Queue()
        self.own_pool = None
        self.pool = None
        if _POOL is not None and jobs > 1:
            self.pool = _POOL
        elif jobs > 1 and len(tasks) > 1:
            from .render import _font_config

            _font_config()  # loaded once, inherited by the workers
            self.own_pool = self.pool = multiprocessing.get_context("fork").Pool(min(jobs, len(tasks)),
                                                                                 initializer=_forked_worker)
        self.tasks = tasks
        for t in tasks:
            self._submit(t)

    def _toc_html(self, toc_pages: dict) -> str:
        return self.views.html(head=False, body=[], toc_pages=toc_pages, chunk=True)

    def _submit(self, task: _Task) -> None:
        self.waiting.add(task.index)
        if self.pool is None:
            self.results.put((task, None, False))  # laid out here, in finish()
            return
        self.pool.apply_async(_lay_out_in_worker, (task,),
                              callback=lambda r, t=task: self.results.put((t, r, True)),
                              error_callback=lambda e, t=task: self.results.put((t, None, True)))

    def _collect(self, index: int | None = None) -> None:
        """Wait for the tasks (all, or until ``index`` is done): a failed one is laid out here
        (its error raised as in one process), a part asking for other split points rendered
        again and sent back."""
        t0 = time.perf_counter()
        while self.waiting and (index is None or index in self.waiting):
            task, laid, remote = self.results.get()
            if laid is None:
                if remote:
                    task = _Task(task.index, task.html, task.splits, task.key, task.start, shape=task.shape)
                laid = lay_out_part(task)
            if laid.resplit is not None:
                self.waiting.discard(task.index)
                self._submit(_Task(task.index, _part_html(self.report, task.index, laid.resplit, self.views),
                                   laid.resplit, task.key, laid.start, laid.passes, task.shape, laid.state))
                continue
            self.waiting.discard(task.index)
            self.done[task.index] = laid
            if self.pool is not None and task.index != NUMBERS:  # (while a worker lays out another part)
                self.readers[id(laid)] = (laid, prepare(laid))
        self.stats.seconds_wait += time.perf_counter() - t0

    def _run(self, task: _Task) -> _Laid:
        self._submit(task)
        self._collect(task.index)
        return self.done.pop(task.index)

    def _results(self) -> list[_Laid]:
        from . import safety

        try:
            self._collect()
        except BaseException:
            self.close()
            raise
        parts = sorted((r for i, r in self.done.items() if i >= 0), key=lambda r: r.index)
        if self.pool is not None:
            for p in sorted(self.done.values(), key=lambda r: r.index):  # what the workers refused
                safety.refused.extend(p.refused)
            del safety.refused[:-100]
        return parts

    def close(self) -> None:
        """Stop the workers forked here (after :meth:`finish`, or when the build failed before
        it); those of :func:`start_pool` stay for the next note of the process."""
        global _REPORT
        if self.own_pool is not None:
            self.own_pool.terminate()
            self.own_pool.join()
            self.own_pool = None
        self.pool = None
        _REPORT = None

    def finish(self) -> bytes:
        from .render import _remember_result

        try:
            parts = self._results()
            st = self.stats
            for p in parts:
                st.seconds_layout += p.seconds_layout
                st.seconds_write += p.seconds_write
                st.passes = max(st.passes, p.passes)
                st.splits.update(p.splits)
                st.part_seconds.append(round(p.seconds_layout + p.seconds_write, 3))
                st.part_passes.append(p.passes)
                _remember_result(p.key, p.shape, p.splits, p.start)
            head = self.done.get(HEAD)
            toc = self.done[TOC]
            front = [head] if head is not None else []
            st.seconds_front = sum(p.seconds_layout + p.seconds_write for p in front + [toc])
            t0 = time.perf_counter()
            n_head = len(head.heights) if head is not None else 0
            # The contents' page count starts as the placeholder contents' (remembered with
            # a guess of the numbers, whose contents was laid out instead: kept if it is the one
            # the passes below ask for — the same HTML, so the same layout)
            laid = {}
            if self.toc_guess is not None:
                n_toc = self.toc_guess[0]
                laid[self._toc_html(self.toc_guess[1])] = toc
            else:
                n_toc = len(toc.heights)
            first_count = n_toc
            st.toc_layouts = 1
            for _ in range(MAX_FRONT_PASSES):
                starts, n = [], n_head + n_toc
                for p in parts:
                    starts.append(n)
                    n += len(p.heights)
                toc_pages = {}
                for e in self.views.builder.toc:
                    for p, s in zip(parts, starts):
                        if e["id"] in p.anchors:
                            toc_pages[e["id"]] = str(s + p.anchors[e["id"]][0] + 1)
                            break
                html = self._toc_html(toc_pages)
                toc = laid.pop(html, None)
                if toc is None:
                    toc = self._run(_Task(TOC, html, {}))
                    st.toc_layouts += 1
                if len(toc.heights) == n_toc:
                    break
                n_toc = len(toc.heights)
            _remember_toc(self.toc_key, first_count, toc_pages)
            # the pages turned to landscape (a wide figure) get their footer number on a landscape page
            turned = {i for i, h in enumerate(h for p in front + [toc] + parts for h in p.heights)
                      if h < LANDSCAPE_BELOW}
            numbers = _numbers_pdf(self.views, n, turned, self._run)
            st.seconds_front += time.perf_counter() - t0
            t0 = time.perf_counter()
            # every page gets its number from the page-number document, whose first page (as
            # the note's first page, ``@page :first``) has none
            pdf = join(front + [toc] + parts, numbers, first_numbered=1, readers=self.readers)
            st.seconds_join = time.perf_counter() - t0
            st.pages = n
            return pdf
        finally:
            self.close()


def _cost(html: str) -> float:
    """A rough layout cost of a part, for the order of the tasks: table cells dominate
    (about 1 ms each), then text and images."""
    import re

    text = re.sub(r"data:[^\"')]+", "", html)
    return html.count("<td") + 0.5 * html.count("<img") + len(text) / 2000


_TOC_DROP = re.compile(r"<title>[^<]*</title>|<meta [^>]*>")
_TOC_MEMO: dict[str, tuple[int, dict]] = {}
_TOC_CACHE_VERSION = 1


def _toc_key(placeholder_html: str) -> str:
    """Key of СОДЕРЖАНИЕ with placeholder numbers: its HTML without the document's title and
    meta data (they do not lay anything out: the variants of a class share the key), and the
    WeasyPrint version."""
    import hashlib

    from .render import weasyprint_version

    text = _TOC_DROP.sub("", placeholder_html)
    return hashlib.sha256(f"{_TOC_CACHE_VERSION}|{weasyprint_version()}|{text}".encode("utf-8")).hexdigest()


def _toc_file(key: str):
    from .formulas import _cache_dir

    folder = _cache_dir()
    return None if folder is None else folder.parent / "toc" / f"{key}.json"


def _recall_toc(key: str, ids: list[str]) -> tuple[int, dict] | None:
    """``(page count of the placeholder contents, page numbers of the headings)`` remembered for
    ``key`` (in the process, else in ``<cache>/toc``), or ``None``. The count is a function of
    the key (the placeholder contents' HTML); the numbers are a guess (the last note with that
    contents), used only when :meth:`PartsJob.finish` asks for the very same contents' HTML, so
    the PDF does not depend on them."""
    import json

    got = _TOC_MEMO.get(key)
    if got is None:
        path = _toc_file(key)
        if path is None:
            return None
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
            got = (int(data["count"]), {str(k): str(v) for k, v in data["pages"].items()})
        except (OSError, ValueError, KeyError, TypeError, AttributeError):
            return None
    count, pages = got
    if count < 1 or any(i not in pages for i in ids):
        return None
    return count, {i: pages[i] for i in ids}


def _remember_toc(key: str, count: int, pages: dict) -> None:
    import json

    from .render import _atomic_write

    if _TOC_MEMO.get(key) == (count, pages):
        return
    if len(_TOC_MEMO) > 64:
        _TOC_MEMO.clear()
    _TOC_MEMO[key] = (count, dict(pages))
    path = _toc_file(key)
    if path is not None:
        try:
            _atomic_write(path, json.dumps({"count": count, "pages": pages}, ensure_ascii=False,
                                           sort_keys=True).encode("utf-8"))
        except OSError:
            pass  # a read-only cache folder is no reason to fail a report


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


def _numbers_pdf(views, n: int, turned: frozenset | set = frozenset(), run=None) -> bytes:
    """The PDF of :func:`_numbers_html`, remembered in the process and in the cache folder
    (``<cache>/pages``): it depends on the page setup and the count only, and WeasyPrint
    writes it byte for byte the same, so a remembered one changes nothing in the note.
    ``run`` lays a task out (a worker of the job); by default here."""
    import hashlib

    from .formulas import _cache_dir
    from .render import _atomic_write, weasyprint_version

    html = _numbers_html(views, n, turned)
    key = hashlib.sha256(f"{weasyprint_version()}|{html}".encode("utf-8")).hexdigest()
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
        pdf = (run or lay_out_part)(_Task(NUMBERS, html, {})).pdf
        if path is not None:
            try:
                _atomic_write(path, pdf)
            except OSError:
                pass  # a read-only cache folder is no reason to fail a report
    if len(_NUMBERS_MEMO) > 16:
        _NUMBERS_MEMO.clear()
    _NUMBERS_MEMO[key] = pdf
    return pdf


def _walk_objects(reader) -> int:
    """Resolve every object reachable from the pages of ``reader`` (not through ``/Parent``:
    what pypdf's ``add_page`` copies); the count of indirect objects resolved."""
    from pypdf.generic import ArrayObject, DictionaryObject, IndirectObject

    seen: set = set()
    refs = [page.indirect_reference for page in reader.pages]
    while refs:
        ref = refs.pop()
        if ref.idnum in seen:
            continue
        seen.add(ref.idnum)
        todo = [reader.get_object(ref)]
        while todo:
            obj = todo.pop()
            if isinstance(obj, DictionaryObject):
                values = [v for k, v in obj.items() if k != "/Parent"]
            elif isinstance(obj, ArrayObject):
                values = list(obj)
            else:
                continue
            for v in values:
                if isinstance(v, IndirectObject):
                    refs.append(v)
                elif isinstance(v, (DictionaryObject, ArrayObject)):
                    todo.append(v)
    return len(seen)


def prepare(part: _Laid):
    """A pypdf reader of ``part``'s PDF with what :func:`join` copies of it (its pages and every
    object they reach) parsed now: pypdf keeps the objects it parsed, so a join given the reader
    only copies them. :meth:`PartsJob._collect` prepares each part as it comes back, while a
    worker still lays out another one, and the join after the last part does about half its
    work (``python bench/bench_join.py``). The joined bytes are the same: the same objects,
    copied in the same order."""
    from pypdf import PdfReader

    reader = PdfReader(io.BytesIO(part.pdf))
    _walk_objects(reader)
    return reader


def join(parts: list[_Laid], numbers: bytes, first_numbered: int, readers: dict | None = None) -> bytes:
    """One PDF of the laid-out parts in order: pages, the footer numbers of ``numbers`` drawn
    on every page from ``first_numbered`` (0-based), internal links and the outline with
    explicit destinations, the document information of the first part. ``readers``:
    ``{id(part): (part, reader)}``, the readers of :func:`prepare` (taken: the join changes their
    pages' links); a part without one is read from its bytes."""
    from pypdf import PdfReader, PdfWriter
    from pypdf.annotations import Link
    from pypdf.generic import ArrayObject, Fit, NameObject

    writer = PdfWriter()
    starts = []
    meta = None
    for p in parts:
        kept = (readers or {}).pop(id(p), None)
        reader = kept[1] if kept is not None and kept[0] is p else PdfReader(io.BytesIO(p.pdf))
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
