"""Benchmark: render the synthetic report (reportgen.report.demo) to PDF and HTML.

    python bench/bench_render.py [--rows 60] [--repeat 3]

Writes the figures (median of the repeats, wall and CPU seconds; the first,
cold run separately) to bench/results/render.json. Every run lays the report
out in full (the remembered split points are cleared). Tests never assert
times; this file is the record.
"""

from __future__ import annotations

import argparse
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


def _timed(fn):
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w, time.process_time() - c


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, default=60, help="rows of the long kinematics table")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default=str(ROOT / "bench" / "results" / "render.json"))
    args = ap.parse_args(argv)

    t0w, t0c = time.perf_counter(), time.process_time()
    import weasyprint  # noqa: F401  (import cost measured below)

    from reportgen.report import render
    from reportgen.report.demo import build_demo_report

    imports = (time.perf_counter() - t0w, time.process_time() - t0c)

    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(args.repeat):
            render._SPLIT_MEMO.clear()  # measure the full split passes every time
            report, bw, bc = _timed(lambda: build_demo_report(args.rows))
            _, pw, pc = _timed(lambda: render.write_pdf(report, Path(tmp) / f"r{i}.pdf"))
            stats = render.last_stats
            _, hw, hc = _timed(lambda: render.write_html(report, Path(tmp) / f"r{i}.html"))
            runs.append({
                "build_wall": bw, "build_cpu": bc,
                "pdf_wall": pw, "pdf_cpu": pc,
                "html_wall": hw, "html_cpu": hc,
                "passes": stats.passes, "pages": stats.pages,
                "layout_wall": stats.seconds_layout, "write_pdf_wall": stats.seconds_pdf,
                "pdf_bytes": (Path(tmp) / f"r{i}.pdf").stat().st_size,
                "html_bytes": (Path(tmp) / f"r{i}.html").stat().st_size,
            })

    def med(key):
        return round(statistics.median(r[key] for r in runs), 3)

    result = {
        "benchmark": "render synthetic report (reportgen.report.demo)",
        "rows": args.rows,
        "repeat": args.repeat,
        "pages": runs[-1]["pages"],
        "passes": runs[-1]["passes"],
        "imports_wall_s": round(imports[0], 3),
        "imports_cpu_s": round(imports[1], 3),
        "first_run": {k: round(v, 3) if isinstance(v, float) else v for k, v in runs[0].items()},
        "median": {k: med(k) for k in runs[0] if k.endswith(("_wall", "_cpu"))},
        "pdf_cpu_s_per_page": round(med("pdf_cpu") / runs[-1]["pages"], 3),
        "pdf_bytes": runs[-1]["pdf_bytes"],
        "html_bytes": runs[-1]["html_bytes"],
        "machine": {"python": platform.python_version(), "cpus": os.cpu_count(),
                    "load_avg": os.getloadavg() if hasattr(os, "getloadavg") else None},
        "versions": _versions(),
    }
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(result, ensure_ascii=False, indent=2) + "\n", encoding="utf-8")
    os.replace(tmp, out)
    print(json.dumps(result["median"], indent=2), f"\npages={result['pages']} "
          f"passes={result['passes']} -> {out}")
    return result


def _versions() -> dict:
    from importlib.metadata import PackageNotFoundError, version

    out = {}
    for name in ("weasyprint", "pydyf", "ziamath", "ziafont", "matplotlib", "jinja2", "pyphen"):
        try:
            out[name] = version(name)
        except PackageNotFoundError:
            out[name] = None
    return out


if __name__ == "__main__":
    main()
