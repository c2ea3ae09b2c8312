"""Build time per report, stage by stage: compute, figures/sections, HTML, PDF.

Usage: python bench/bench_build.py [CASE …]  → bench/results/build.json (and a table on stdout).
Each case is built twice in the same process: the first run includes one-time costs
(numba cache load, fonts, formula rendering caches); the second is the warm figure. The PDF is
laid out as the CLI lays it out (in parts, by ``REPORTGEN_JOBS`` / min(2, cores) processes):
``pdf_layout`` and ``pdf_write`` are then summed over the parts (CPU of the workers), ``pdf`` is
the wall time.
"""
from __future__ import annotations

import json
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
DEFAULT = ["cases/ws000_six_bar.toml", "cases/ws004_slotted_lever.toml", "cases/ws002_tractor_hitch.toml"]


def stage_times(case: Path) -> dict:
    from reportgen.analysis.study import Study
    from reportgen.report import render
    from reportgen.report.assemble import build_report, chosen_sections, needs

    t = {}
    t0 = time.perf_counter()
    study = Study(case)
    sections = chosen_sections(study, None)
    for need in sorted(needs(study)):
        getattr(study, need)
    t["compute"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    report = build_report(study)
    t["sections_and_figures"] = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as d:
        t0 = time.perf_counter()
        render.write_html(report, Path(d) / "r.html")
        t["html"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        render.write_pdf(report, Path(d) / "r.pdf")
        t["pdf"] = time.perf_counter() - t0
        st = render.last_stats
        t["pdf_layout"] = st.seconds_layout
        t["pdf_write"] = st.seconds_pdf
        t["pdf_passes"] = st.passes
        t["pages"] = st.pages
        if st.parts is not None:  # laid out in parts (reportgen/report/parallel.py)
            from dataclasses import asdict
            t["pdf_parts"] = asdict(st.parts)
    t["sections"] = sections
    t["total"] = t["compute"] + t["sections_and_figures"] + t["html"] + t["pdf"]
    return t


def main(argv: list[str]) -> None:
    t0 = time.perf_counter()
    import numba  # noqa: F401
    import weasyprint  # noqa: F401

    import reportgen  # noqa: F401
    imports = time.perf_counter() - t0
    cases = argv or DEFAULT
    out = {"machine": {"python": platform.python_version(), "cpus": os.cpu_count(),
                       "load_average": os.getloadavg(), "platform": platform.platform()},
           "imports_seconds": imports, "cases": {}}
    for c in cases:
        cold = stage_times(ROOT / c)
        warm = stage_times(ROOT / c)
        out["cases"][c] = {"cold": cold, "warm": warm}
        print(f"{c}: " + ", ".join(f"{k} {warm[k]:.2f} s" for k in ("compute", "sections_and_figures", "html", "pdf", "total"))
              + f" ({warm['pages']} стр.; холодный запуск {cold['total']:.2f} s)")
    dest = ROOT / "bench" / "results" / "build.json"
    dest.parent.mkdir(parents=True, exist_ok=True)
    dest.write_text(json.dumps(out, ensure_ascii=False, indent=2) + "\n", encoding="utf-8")
    print(f"импорт {imports:.2f} s; результаты: {dest}")


if __name__ == "__main__":
    main(sys.argv[1:])
