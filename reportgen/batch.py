"""Reports for a whole class: one report per variant, in parallel, with a manifest.

Variants come from a CSV or TOML table of values that vary over a base case, or from a folder of
case files.  A failing variant is recorded and does not stop the others; every output is written
atomically; the manifest lists variant, input hash, output files and seconds.
"""
from __future__ import annotations

import csv
import json
import multiprocessing
import os
import sys
import time
import tomllib
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import asdict, dataclass, field
from pathlib import Path

from .case.load import load_spec
from .errors import CaseError, ReportgenError
from .export import atomic_write

META_KEYS = {"variant", "student", "group", "supervisor", "topic", "university", "department", "city", "year"}


@dataclass
class Variant:
    name: str
    base: Path
    params: dict = field(default_factory=dict)
    meta: dict = field(default_factory=dict)


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


def read_variants(src: Path, base: Path | None) -> list[Variant]:
    src = Path(src)
    if src.is_dir():
        files = sorted(src.glob("*.toml"))
        if not files:
            raise CaseError("в папке нет файлов вариантов .toml", file=str(src))
        return [Variant(f.stem, f) for f in files]
    if not src.exists():
        raise CaseError("таблица вариантов не найдена", file=str(src), expected="файл .csv или .toml, или папка с вариантами")
    if src.suffix.lower() == ".toml":
        try:
            data = tomllib.loads(src.read_text(encoding="utf-8"))
        except tomllib.TOMLDecodeError as e:
            raise CaseError(f"синтаксическая ошибка TOML: {e}", file=str(src)) from None
        b = base or (src.parent / data["base"] if "base" in data else None)
        rows = data.get("variant", [])
        if not isinstance(rows, list):
            raise CaseError("ожидался массив [[variant]]", file=str(src), key="variant")
    elif src.suffix.lower() == ".csv":
        with src.open(encoding="utf-8", newline="") as f:
            rows = list(csv.DictReader(f))
        b = base
        if b is None and rows and "base" in rows[0]:
            b = src.parent / rows[0]["base"]
    else:
        raise CaseError("неизвестный формат таблицы вариантов", file=str(src), expected="расширение .csv или .toml")
    if b is None:
        raise CaseError("не указан базовый вариант", file=str(src),
                        expected="ключ base = \"…toml\" в таблице, столбец base в CSV или опция --base")
    out = []
    for i, row in enumerate(rows):
        row = {str(k).strip(): v for k, v in row.items() if k is not None}
        name = str(row.pop("name", row.get("variant", f"{i + 1:02d}")))
        row.pop("base", None)
        meta = {k: str(v) for k, v in row.items() if k in META_KEYS}
        meta.setdefault("variant", name)
        params = {k: v for k, v in row.items() if k not in META_KEYS and v not in ("", None)}
        out.append(Variant(name, Path(b), params, meta))
    names = [v.name for v in out]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise CaseError(f"повторяются имена вариантов: {', '.join(sorted(dup))}", file=str(src))
    return out


def _init_worker() -> None:
    """Warm-up, once per worker process (the pool keeps its workers for the whole class):
    heavy imports, numba kernels from the on-disk cache, the report's fonts registered with
    matplotlib and loaded by WeasyPrint, the templates compiled. Every variant a worker
    builds afterwards reuses them, and the parsed formula images (see ``render._layout``)."""
    from .report import assemble  # noqa: F401  (sections, formulas, ziamath)
    from .report import render
    from .style import mplstyle
    from .warmup import warmup
    mplstyle.apply_style()
    render._font_config()
    render._get_env()
    warmup()


def _peak_rss_mb() -> float:
    """Peak resident memory of this process so far, MB (Linux reports KB, macOS bytes)."""
    import resource
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return round(peak / (1024 * 1024 if sys.platform == "darwin" else 1024), 1)


def run_variant(v: Variant, out_dir: str, formats: tuple[str, ...], sections) -> Outcome:
    t0 = time.perf_counter()
    try:
        from .analysis.study import Study
        from .report.assemble import build_report
        from .report.render import build_outputs
        spec = load_spec(v.base, v.params)
        spec.meta_overrides = dict(v.meta)
        study = Study(spec)
        report = build_report(study, sections)
        files = build_outputs(report, Path(out_dir), _stem(v), formats)
        out = Outcome(v.name, True, spec.digest(), [str(p) for p in files.values()], time.perf_counter() - t0)
    except ReportgenError as e:
        out = Outcome(v.name, False, "", [], time.perf_counter() - t0, str(e))
    except Exception as e:  # one broken variant must not stop the class
        out = Outcome(v.name, False, "", [], time.perf_counter() - t0, f"внутренняя ошибка: {type(e).__name__}: {e}")
    out.worker = os.getpid()
    out.peak_rss_mb = _peak_rss_mb()
    return out


def _stem(v: Variant) -> str:
    return f"{v.base.stem}_{v.name}" if v.params or v.meta.get("variant") != v.base.stem else v.base.stem


def _progress(total: int):
    if os.environ.get("CI", "").lower() in ("1", "true", "yes") or not sys.stderr.isatty():
        return None
    from tqdm import tqdm
    return tqdm(total=total, file=sys.stderr, unit="вар.", desc="Отчёты")


def run_batch(variants: list[Variant], out_dir: Path, jobs: int | None = None,
              formats: tuple[str, ...] = ("pdf", "html"), sections=None) -> list[Outcome]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    jobs = max(1, jobs or os.cpu_count() or 1)
    bar = _progress(len(variants))
    results: list[Outcome] = []
    if jobs == 1 or len(variants) == 1:
        for v in variants:
            results.append(run_variant(v, str(out_dir), formats, sections))
            if bar:
                bar.update()
    else:
        # Workers are started once and kept for the whole class (no max_tasks_per_child):
        # the warm-up in _init_worker is paid once per worker, not once per variant.
        ctx = multiprocessing.get_context("forkserver")
        with ProcessPoolExecutor(max_workers=min(jobs, len(variants)), mp_context=ctx,
                                 initializer=_init_worker) as ex:
            futs = [ex.submit(run_variant, v, str(out_dir), formats, sections) for v in variants]
            for f in as_completed(futs):
                results.append(f.result())
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
                             "peak_rss_mb": peak} for pid, peak in sorted(peaks.items())]}
    atomic_write(out_dir / "manifest.json", json.dumps(manifest, ensure_ascii=False, indent=2) + "\n")
    return results
