"""Reports for a whole class: one report per variant, in parallel, with a manifest.

Variants come from a CSV or TOML table of values that vary over a base case, or from a folder of
case files.  A failing variant is recorded and does not stop the others; every output is written
atomically; the manifest lists variant, input hash, output files and seconds.
"""
from __future__ import annotations

import csv
import functools
import io
import json
import multiprocessing
import os
import sys
import time
import re
from collections.abc import Mapping
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import asdict, dataclass, field
from pathlib import Path

from .case.load import load_spec, read_toml
from .case.text import meta_value
from .errors import CaseError, ReportgenError
from .export import atomic_write

META_KEYS = {"variant", "student", "group", "supervisor", "topic", "university", "department", "city", "year"}


@dataclass
class Variant:
    name: str
    base: Path
    params: dict = field(default_factory=dict)
    meta: dict = field(default_factory=dict)
    stem: str = ""  # safe file stem of the outputs (set by read_variants)
    source: str = ""  # the table file the row comes from ("" for a folder of cases)
    row: str = ""  # where in it: "variant[2]" (TOML) or "строка 4" (CSV)


@dataclass
class Outcome:
    variant: str
    ok: bool
    input_hash: str = ""
    files: list[str] = field(default_factory=list)
    seconds: float = 0.0
    error: str = ""
    worker: int = 0  # process id of the worker that built it
    peak_rss_mb: float = 0.0  # that worker's peak memory after this variant
    cpu_seconds: float = 0.0  # CPU time (user + sys) of the worker for this variant
    layout_passes: list[int] = field(default_factory=list)  # WeasyPrint layouts of each part of the PDF


MAX_VARIANTS = 1000  # rows of one table
MAX_STEM = 80  # characters of an output file name (without the extension)
_UNSAFE = re.compile(r"[^\w.\-]+")


def safe_stem(name: str) -> str:
    """A file name stem made of ``name``: letters, digits, ``_``, ``-``, ``.`` only (every other
    run of characters — ``/``, ``\\``, spaces, ``..`` at the start — becomes ``_``), never empty,
    never hidden, at most :data:`MAX_STEM` characters. So ``sub/../../x`` gives ``sub_.._.._x``: a
    name can never lead out of the output folder."""
    stem = _UNSAFE.sub("_", str(name)).lstrip(".") or "_"
    return stem[:MAX_STEM]


def _row_value(v, *, file: str, key: str):
    """A parameter value of a row: a string or a finite number (arrays, tables, booleans and
    non-finite numbers are an error against the row)."""
    import math
    if isinstance(v, bool) or not isinstance(v, (str, int, float)) or (isinstance(v, float) and not math.isfinite(v)):
        raise CaseError("значение параметра в таблице вариантов должно быть числом или строкой с единицами",
                        file=file, key=key, expected="например \"0.33 m\"", got=repr(v)[:80])
    return v


def read_variants(src: Path, base: Path | None) -> list[Variant]:
    src = Path(src)
    if src.is_dir():
        files = sorted(src.glob("*.toml"))
        if not files:
            raise CaseError("в папке нет файлов вариантов .toml", file=str(src))
        out = [Variant(f.stem, f, stem=safe_stem(f.stem)) for f in files]
        _check_stems(out, src)
        return out
    if not src.exists():
        raise CaseError("таблица вариантов не найдена", file=str(src), expected="файл .csv или .toml, или папка с вариантами")
    if not src.is_file():
        raise CaseError("таблица вариантов: указан не обычный файл (устройство)", file=str(src),
                        expected="файл .csv или .toml, или папка с вариантами")
    where: list[str]
    if src.suffix.lower() == ".toml":
        data = read_toml(src, what="таблица вариантов")
        b = base
        if b is None and "base" in data:
            if not isinstance(data["base"], str) or not data["base"].strip():
                raise CaseError("базовый вариант задаётся путём к файлу", file=str(src), key="base",
                                expected="base = \"ws000_six_bar.toml\"", got=repr(data["base"])[:80])
            b = src.parent / data["base"]
        rows = data.get("variant", [])
        if isinstance(rows, Mapping):
            rows = [rows]
        if not isinstance(rows, list):
            raise CaseError("ожидался массив [[variant]]", file=str(src), key="variant",
                            expected="[[variant]] name = \"A\" …")
        for i, row in enumerate(rows):
            if not isinstance(row, Mapping):
                raise CaseError("строка таблицы вариантов должна быть таблицей", file=str(src),
                                key=f"variant[{i}]", expected="[[variant]] name = \"A\", l_OA = \"0.33 m\"",
                                got=repr(row)[:80])
        where = [f"variant[{i}]" for i in range(len(rows))]
    elif src.suffix.lower() == ".csv":
        try:
            text = src.read_bytes().decode("utf-8-sig")
        except UnicodeDecodeError:
            raise CaseError("таблица вариантов не в кодировке UTF-8", file=str(src),
                            expected="CSV в UTF-8 (в Excel: «Сохранить как» → «CSV UTF-8»)") from None
        try:
            reader = csv.DictReader(io.StringIO(text, newline=""))
            rows = []
            for row in reader:
                if None in row:
                    raise CaseError("в строке больше значений, чем столбцов в заголовке", file=str(src),
                                    key=f"строка {reader.line_num}", expected="по одному значению на столбец")
                rows.append(row)
                if len(rows) > MAX_VARIANTS:
                    break
        except csv.Error as e:
            raise CaseError(f"ошибка чтения CSV: {e}", file=str(src)) from None
        lines = [f"строка {i + 2}" for i in range(len(rows))]  # line 1 is the header
        where = lines
        b = base
        if b is None and rows and rows[0].get("base"):
            b = src.parent / rows[0]["base"]
    else:
        raise CaseError("неизвестный формат таблицы вариантов", file=str(src), expected="расширение .csv или .toml")
    if len(rows) > MAX_VARIANTS:
        raise CaseError(f"слишком много вариантов в таблице (больше {MAX_VARIANTS})", file=str(src),
                        expected=f"не более {MAX_VARIANTS} строк")
    if b is None:
        raise CaseError("не указан базовый вариант", file=str(src),
                        expected="ключ base = \"…toml\" в таблице, столбец base в CSV или опция --base")
    b = Path(b)
    if not b.is_file():
        raise CaseError("базовый вариант не найден или не является файлом", file=str(src), key="base",
                        got=str(b), expected="путь к файлу .toml")
    out = []
    for i, row in enumerate(rows):
        row = {str(k).strip(): v for k, v in row.items() if k is not None}
        at = where[i]
        raw_name = row.pop("name", row.get("variant", f"{i + 1:02d}"))
        if isinstance(raw_name, bool) or not isinstance(raw_name, (str, int)) or not str(raw_name).strip():
            raise CaseError("имя варианта должно быть непустой строкой", file=str(src), key=f"{at}.name",
                            expected="name = \"A\" или столбец variant", got=repr(raw_name)[:80])
        name = str(raw_name).strip()
        row.pop("base", None)
        meta = {k: meta_value(v, file=str(src), key=f"{at}.{k}") for k, v in row.items() if k in META_KEYS}
        meta.setdefault("variant", meta_value(name, file=str(src), key=f"{at}.name"))
        params = {k: _row_value(v, file=str(src), key=f"{at}.{k}")
                  for k, v in row.items() if k not in META_KEYS and v not in ("", None)}
        v = Variant(name, b, params, meta, source=str(src), row=at)
        v.stem = safe_stem(_stem(v))
        out.append(v)
    names = [v.name for v in out]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise CaseError(f"повторяются имена вариантов: {', '.join(sorted(dup))[:200]}", file=str(src))
    _check_stems(out, src)
    return out


def _check_stems(variants: list[Variant], src: Path) -> None:
    """Two variants whose names give one file name would overwrite each other: an error."""
    seen: dict[str, str] = {}
    for v in variants:
        key = v.stem.lower()  # case-insensitive file systems
        if key in seen:
            raise CaseError(f"варианты «{seen[key][:60]}» и «{v.name[:60]}» дают одно имя файла «{v.stem}»",
                            file=str(src), expected="имена вариантов, различающиеся буквами или цифрами")
        seen[key] = v.name


def _init_worker() -> None:
    """Warm-up, once per worker process (the pool keeps its workers for the whole class):
    heavy imports, numba kernels from the on-disk cache, the report's fonts registered with
    matplotlib and loaded by WeasyPrint, the templates compiled. Every variant a worker
    builds afterwards reuses them, the parsed images (see ``render._layout``,
    :class:`_TouchedCache`) and the parsed mathtext labels (:func:`_share_mathtext`). The warm
    state is then frozen (:func:`~reportgen.core.memory.freeze_warm_state`), so the collection
    after each variant (:func:`_after_variant`) walks what the variants leave, not the imports."""
    from .core.memory import collect_less, freeze_warm_state
    from .report.parallel import set_note_jobs
    from .warmup import warm_report, warmup
    collect_less()  # (a forkserver's child: the CLI's setting is not inherited)
    set_note_jobs(1)  # the workers are the parallelism: no pool of layout processes inside one
    warm_report()
    _share_between_variants()
    warmup()
    freeze_warm_state()  # the collection after each variant walks only what variants leave


def _share_between_variants() -> None:
    """Caches of this process kept from one variant to the next (idempotent)."""
    from .report import render
    _share_mathtext()
    if not isinstance(render._IMAGE_CACHE, _TouchedCache):
        render._IMAGE_CACHE = _TouchedCache(render._IMAGE_CACHE)


def _share_mathtext() -> None:
    """The parsed mathtext labels kept for the worker's life (one cache for the process:
    :func:`reportgen.style.mplstyle.share_mathtext`): the labels of the next variant are the
    same strings (ω₂, ε₃, V_B …)."""
    from .style.mplstyle import share_mathtext
    share_mathtext()


class _TouchedCache(dict):
    """WeasyPrint's image cache of a batch worker (a dict keyed by the image's ``data:`` URL)
    that remembers which keys the current variant used. After a variant, :meth:`keep_touched`
    drops what it did not use: the previous variant's figures (never seen again, the geometry
    differs) go, images every variant shows stay. (ws000's formulas are HTML now, so after each
    of its variants the cache holds that variant's 19 figures; ``tests/test_batch_memory.py``
    checks that the count does not grow.) Without it the cache holds the parsed figures of every
    variant built so far, up to 2000 entries, and is then emptied whole. What is kept is cut
    loose from its document after each variant (:func:`_detach_images`)."""

    def __init__(self, *args):
        super().__init__(*args)
        self.touched: set = set(self)

    def __contains__(self, key):
        hit = super().__contains__(key)
        if hit:
            self.touched.add(key)
        return hit

    def __getitem__(self, key):
        self.touched.add(key)
        return super().__getitem__(key)

    def __setitem__(self, key, value):
        self.touched.add(key)
        super().__setitem__(key, value)

    def get(self, key, default=None):
        if super().__contains__(key):
            self.touched.add(key)
        return super().get(key, default)

    def keep_touched(self) -> int:
        """Drop the entries not used since the last call; returns how many were dropped."""
        stale = [k for k in self if k not in self.touched]
        for k in stale:
            del self[k]
        self.touched = set()
        return len(stale)


class _DetachedContext:
    """What a kept SVG image reads of its WeasyPrint layout context when it is drawn again
    (WeasyPrint 70: ``svg/text.py`` reads ``dictionaries`` to break a ``<text>``,
    ``svg/images.py`` calls ``get_image_from_uri`` for an ``<image>`` inside), and nothing more.

    WeasyPrint's ``SVGImage`` keeps the ``LayoutContext`` of the document that parsed it, and its
    ``SVG`` the context and page stream of the last draw; a layout context holds the computed
    style of every element of its document and the stream the content of a page. A formula image
    kept in the worker's image cache therefore kept an earlier note alive: after a variant of
    ws000 the worker held 404 887 tracked objects instead of 265 135 (``python
    bench/bench_gc.py --batch``: policies ``before`` and ``detach``), each walked again by every
    full collection, and its peak memory was 532 instead of 472 MB."""

    def __init__(self, context):
        self.font_config = getattr(context, "font_config", None)
        self.dictionaries = {}
        get = context.get_image_from_uri
        self.get_image_from_uri = functools.partial(get.func, *get.args, **{**get.keywords, "context": self})


def _detach_images(cache: dict) -> int:
    """Cut every kept image loose from the document that last used it (:class:`_DetachedContext`);
    returns how many were cut. The draw sets the stream and context again, so a detached image
    draws the same operators."""
    n = 0
    for image in cache.values():
        context = getattr(image, "_context", None)
        if context is not None and not isinstance(context, _DetachedContext):
            image._context = _DetachedContext(context)
            n += 1
        svg = getattr(image, "_svg", None)
        if svg is not None:
            for attr in ("stream", "context"):
                if getattr(svg, attr, None) is not None:
                    setattr(svg, attr, None)
    return n


def _after_variant() -> None:
    """Release what one variant left behind in a kept worker: unused parsed images, the
    documents the kept ones point to, closed matplotlib figures, WeasyPrint documents held by
    reference cycles."""
    import gc

    from .report import render
    cache = render._IMAGE_CACHE
    if isinstance(cache, _TouchedCache):
        cache.keep_touched()
        _detach_images(cache)
    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close("all")
    gc.collect()


def _peak_rss_mb() -> float:
    """Peak resident memory of this process so far, MB (Linux reports KB, macOS bytes)."""
    import resource
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return round(peak / (1024 * 1024 if sys.platform == "darwin" else 1024), 1)


def run_variant(v: Variant, out_dir: str, formats: tuple[str, ...], sections, key: bool = False,
                sheets: bool = False) -> Outcome:
    t0 = time.perf_counter()
    c0 = time.process_time()
    try:
        from .analysis.study import Study
        from .report.assemble import build_report
        from .report.render import build_outputs
        spec = load_spec(v.base, v.params)
        spec.meta_overrides = dict(v.meta)
        study = Study(spec)
        report = build_report(study, sections)
        stem = v.stem or safe_stem(_stem(v))
        files = build_outputs(report, Path(out_dir), stem, formats)
        if key:
            from .report.key import write_key
            files.update(write_key(study, Path(out_dir), stem, formats))
        if sheets:
            from .sheets import build_sheets
            files["sheets"] = build_sheets(study, Path(out_dir), stem)
        out = Outcome(v.name, True, spec.digest(), [str(p) for p in files.values()], time.perf_counter() - t0)
        if "pdf" in formats:
            from .report import render
            st = render.last_stats
            out.layout_passes = list(st.parts.part_passes) if st.parts is not None else [st.passes]
    except CaseError as e:
        out = Outcome(v.name, False, "", [], time.perf_counter() - t0, str(_against_row(e, v)))
    except ReportgenError as e:
        out = Outcome(v.name, False, "", [], time.perf_counter() - t0, str(e))
    except Exception as e:  # one broken variant must not stop the class
        out = Outcome(v.name, False, "", [], time.perf_counter() - t0, f"внутренняя ошибка: {type(e).__name__}: {e}")
    _after_variant()
    out.cpu_seconds = round(time.process_time() - c0, 2)
    out.worker = os.getpid()
    out.peak_rss_mb = _peak_rss_mb()
    return out


def _against_row(e: CaseError, v: Variant) -> CaseError:
    """An error in a value the row gives is reported against the row (table file + row),
    not against the base case."""
    if not v.source or not e.key:
        return e
    for k in v.params:
        if e.key == f"parameters.{k}" or e.key.startswith(f"parameters.{k}.") or e.key.startswith(f"parameters.{k}["):
            return e._copy(file=v.source, key=f"{v.row}.{k}" + e.key[len(f"parameters.{k}"):])
    # the value is read fine but does not fit where the base case uses it ("0.33 kg" for a length)
    text = f"{e.message} {e.got or ''}"
    for k, val in v.params.items():
        if re.search(rf"(?<![\w.]){re.escape(k)}(?![\w.])", text):
            where = f"{e.file}: ключ {e.key}" if e.file else f"ключ {e.key}"
            return CaseError(f"значение «{str(val)[:80]}» не подходит базовому варианту ({where}: {e.message})",
                             file=v.source, key=f"{v.row}.{k}", expected=e.expected, hint=e.hint)
    return e


def _stem(v: Variant) -> str:
    return f"{v.base.stem}_{v.name}" if v.params or v.meta.get("variant") != v.base.stem else v.base.stem


def _progress(total: int):
    if os.environ.get("CI", "").lower() in ("1", "true", "yes") or not sys.stderr.isatty():
        return None
    from tqdm import tqdm
    return tqdm(total=total, file=sys.stderr, unit="вар.", desc="Отчёты")


class _Runs:
    """The order the workers take a class in: the table cut into one run of neighbouring rows
    per worker; a worker that finished a variant takes the next of its run, and when its run is
    done, the last of the longest run left (working backwards from there).

    A class table varies its rows gradually, so a variant's neighbour shares its note's
    sequence of headings, figures and tables, and the split points the neighbour's layout found
    are a guess for its own (``render._start_splits``): a worker that builds a run row after
    row takes every such guess from the row before. Taken in table order, two workers built
    two neighbours at once, both finding the same split points from none."""

    def __init__(self, variants: list, workers: int):
        size = -(-len(variants) // max(1, workers))
        self.runs = [list(variants[i:i + size]) for i in range(0, len(variants), size)]

    def first(self) -> list[tuple[int, object]]:
        """``(run, variant)`` for each worker to start with."""
        return [(r, run.pop(0)) for r, run in enumerate(self.runs)]

    def next(self, r: int) -> tuple[int, object] | None:
        """``(run, variant)`` after a variant of run ``r`` is done, or ``None`` when all are taken."""
        if self.runs[r]:
            return r, self.runs[r].pop(0)
        longest = max(range(len(self.runs)), key=lambda i: len(self.runs[i]))
        return (r, self.runs[longest].pop()) if self.runs[longest] else None


def run_batch(variants: list[Variant], out_dir: Path, jobs: int | None = None,
              formats: tuple[str, ...] = ("pdf", "html"), sections=None, key: bool = False,
              sheets: bool = False) -> list[Outcome]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    jobs = max(1, jobs or os.cpu_count() or 1)
    bar = _progress(len(variants))
    results: list[Outcome] = []
    if jobs == 1 or len(variants) <= 1:  # (an empty table: no pool, an empty manifest)
        from .report import parallel
        from .report.parallel import set_note_jobs
        if jobs == 1:
            saved = parallel._JOBS
            set_note_jobs(1)  # --jobs 1: one process in all
        _share_between_variants()
        try:
            for v in variants:
                results.append(run_variant(v, str(out_dir), formats, sections, key, sheets))
                if bar:
                    bar.update()
        finally:
            if jobs == 1:
                set_note_jobs(saved)
    else:
        # Workers are started once and kept for the whole class (no max_tasks_per_child):
        # the warm-up in _init_worker is paid once per worker, not once per variant.
        ctx = multiprocessing.get_context("forkserver")
        # One variant in flight per worker, so the next one submitted goes to the worker that
        # just finished one: the next variant of its run (_Runs).
        workers = min(jobs, len(variants))
        runs = _Runs(variants, workers)
        with ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_init_worker) as ex:
            def submit(task):
                r, v = task
                pending[ex.submit(run_variant, v, str(out_dir), formats, sections, key, sheets)] = r

            pending: dict = {}
            for task in runs.first():
                submit(task)
            while pending:
                done, _ = wait(pending, return_when=FIRST_COMPLETED)
                for f in done:
                    results.append(f.result())
                    task = runs.next(pending.pop(f))
                    if task is not None:
                        submit(task)
                    if bar:
                        bar.update()
    if bar:
        bar.close()
    order = {v.name: i for i, v in enumerate(variants)}
    results.sort(key=lambda r: order[r.variant])
    peaks: dict[int, float] = {}
    for r in results:
        peaks[r.worker] = max(peaks.get(r.worker, 0.0), r.peak_rss_mb)
    manifest = {"tool": "reportgen", "variants": [asdict(r) for r in results],
                "ok": sum(r.ok for r in results), "failed": sum(not r.ok for r in results),
                "workers": [{"pid": pid, "variants": sum(r.worker == pid for r in results),
                             "peak_rss_mb": peak,
                             "cpu_seconds": round(sum(r.cpu_seconds for r in results if r.worker == pid), 2)}
                            for pid, peak in sorted(peaks.items())]}
    atomic_write(out_dir / "manifest.json", json.dumps(manifest, ensure_ascii=False, indent=2) + "\n")
    return results
