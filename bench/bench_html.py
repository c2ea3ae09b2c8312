"""CPU of rendering a note's HTML: the print parts (the HTML stage of ``PartsJob``) and the
self-contained screen HTML (``render.write_html``).

Usage: python bench/bench_html.py [CASE] [--repeat 5] [--cold-cache]
→ bench/results/html.json (and a line on stdout).

The study and the report are built first (not measured). Then, in this one process:
``first`` is the first call of each stage, as in a ``reportgen build`` (print parts first,
then the screen HTML: the order of ``render.build_outputs``), with the cache folder as it
is (``--cold-cache``: an empty one, as on a fresh machine); ``warm`` is the median and the
minimum of ``--repeat`` later calls. Each pair of calls runs within what
``render.build_outputs`` gives one build (``render._build_scope``: tables formatted once for
both, the older objects out of the garbage collector's passes). CPU seconds of the process (``time.process_time``);
the load average is recorded with them. No layout: ``PartsJob(report, 1)`` renders the
parts and is closed before any is laid out.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import platform
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def _cpu(fn) -> float:
    c = time.process_time()
    fn()
    return time.process_time() - c


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", nargs="?", default="cases/ws000_six_bar.toml")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--cold-cache", action="store_true", help="an empty cache folder (REPORTGEN_CACHE)")
    ap.add_argument("--out", default=str(ROOT / "bench" / "results" / "html.json"))
    args = ap.parse_args(argv)
    tmp = tempfile.TemporaryDirectory()
    if args.cold_cache:
        os.environ["REPORTGEN_CACHE"] = str(Path(tmp.name) / "cache")

    from reportgen.analysis.study import Study
    from reportgen.report import render
    from reportgen.report.assemble import build_report, needs
    from reportgen.report.parallel import PartsJob

    case = Path(args.case)
    if not case.is_absolute():
        case = (Path.cwd() / case) if (Path.cwd() / case).exists() else ROOT / case
    study = Study(case)
    for need in sorted(needs(study)):
        getattr(study, need)
    report = build_report(study)
    html = Path(tmp.name) / "note.html"

    def parts():
        PartsJob(report, 1).close()

    def screen():
        render.write_html(report, html)

    # what render.build_outputs shares between the two stages of one build (where it does)
    scope = getattr(render, "_build_scope", contextlib.nullcontext)

    def build() -> tuple[float, float]:
        with scope():
            return _cpu(parts), _cpu(screen)

    first = dict(zip(("parts_html", "write_html"), build()))
    runs = {"parts_html": [], "write_html": []}
    for _ in range(args.repeat):
        p, s = build()
        runs["parts_html"].append(p)
        runs["write_html"].append(s)
    result = {
        "benchmark": "CPU of the print parts' HTML (PartsJob) and of write_html",
        "case": args.case,
        "cold_cache": args.cold_cache,
        "repeat": args.repeat,
        "first_cpu_s": {k: round(v, 4) for k, v in first.items()},
        "warm_median_cpu_s": {k: round(statistics.median(v), 4) for k, v in runs.items()},
        "warm_min_cpu_s": {k: round(min(v), 4) for k, v in runs.items()},
        "html_bytes": html.stat().st_size,
        "machine": {"python": platform.python_version(), "cpus": os.cpu_count(),
                    "load_avg": os.getloadavg() if hasattr(os, "getloadavg") else None},
    }
    tmp.cleanup()
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(result, ensure_ascii=False, indent=2) + "\n", encoding="utf-8")
    print(json.dumps({k: result[k] for k in ("first_cpu_s", "warm_median_cpu_s", "warm_min_cpu_s")}),
          f"load {result['machine']['load_avg'][0]:.1f} -> {out}")
    return result


if __name__ == "__main__":
    main()
