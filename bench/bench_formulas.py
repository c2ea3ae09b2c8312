"""Cost of the note's formulas in WeasyPrint: typeset as HTML text against drawn by ziamath.

Usage: python bench/bench_formulas.py [--case CASE] [--repeat N] [SECTION …]
       → bench/results/formulas.json (and a table on stdout)

For each section (default: kinematics, dynamics, forces of ws000) the note with that section
alone is built once; its print HTML is made twice, with the formulas typeset as text
(reportgen/report/mathhtml.py, the default) and drawn as ziamath SVG images
(``REPORTGEN_MATH=svg``), with the same stylesheet; then WeasyPrint lays out and writes each
``--repeat`` times, alternating. The figures are CPU seconds of this process
(``time.process_time``: the machine may be shared), medians over the repeats.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def _html(study, section: str, mode: str) -> str:
    from reportgen.report import formulas, mathhtml, render
    from reportgen.report.assemble import build_report

    os.environ["REPORTGEN_MATH"] = mode
    formulas.render_latex.cache_clear()
    mathhtml.convert.cache_clear()
    try:
        return render.render_html(build_report(study, [section]), for_print=True)
    finally:
        os.environ.pop("REPORTGEN_MATH", None)


def _once(html: str) -> tuple[float, float, int, int]:
    import weasyprint

    t0 = time.process_time()
    doc = weasyprint.HTML(string=html, base_url=str(ROOT)).render()
    t1 = time.process_time()
    pdf = doc.write_pdf()
    t2 = time.process_time()
    return t1 - t0, t2 - t1, len(doc.pages), len(pdf)


def main(argv: list[str]) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sections", nargs="*", default=["kinematics", "dynamics", "forces"])
    ap.add_argument("--case", default="cases/ws000_six_bar.toml")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    os.environ.setdefault("REPORTGEN_JOBS", "1")
    from reportgen.analysis.study import Study

    study = Study(ROOT / args.case)
    out = {"machine": {"python": platform.python_version(), "cpus": os.cpu_count(),
                       "load_average_before": os.getloadavg(), "platform": platform.platform()},
           "case": args.case, "repeat": args.repeat, "sections": {}}
    for sec in args.sections:
        htmls = {mode: _html(study, sec, mode) for mode in ("html", "svg")}
        runs = {mode: [] for mode in htmls}
        _once(htmls["html"])  # fonts and caches loaded once, not in the first figure
        for _ in range(args.repeat):
            for mode, html in htmls.items():
                runs[mode].append(_once(html))
        res = {}
        for mode, rs in runs.items():
            lay = statistics.median(r[0] for r in rs)
            wri = statistics.median(r[1] for r in rs)
            res[mode] = {"layout_cpu": lay, "write_cpu": wri, "total_cpu": lay + wri,
                         "pages": rs[0][2], "pdf_bytes": rs[0][3], "html_bytes": len(htmls[mode].encode())}
        out["sections"][sec] = res
        h, s = res["html"], res["svg"]
        print(f"{sec}: текст {h['layout_cpu']:.2f} + {h['write_cpu']:.2f} = {h['total_cpu']:.2f} с ЦП "
              f"({h['pages']} стр., PDF {h['pdf_bytes'] // 1024} КБ); SVG {s['layout_cpu']:.2f} + "
              f"{s['write_cpu']:.2f} = {s['total_cpu']:.2f} с ЦП ({s['pages']} стр., PDF {s['pdf_bytes'] // 1024} КБ)",
              flush=True)
    out["machine"]["load_average_after"] = os.getloadavg()
    dest = ROOT / "bench" / "results" / "formulas.json"
    dest.parent.mkdir(parents=True, exist_ok=True)
    dest.write_text(json.dumps(out, ensure_ascii=False, indent=2) + "\n", encoding="utf-8")
    print(f"load average {out['machine']['load_average_before'][0]:.1f} → "
          f"{out['machine']['load_average_after'][0]:.1f}; результаты: {dest}")


if __name__ == "__main__":
    main(sys.argv[1:])
