"""CPU of laying out and writing each part of the ws000 note with the figures drawn by WeasyPrint's
SVG renderer and by reportgen/report/svgops.py, in one process.

Usage: python bench/bench_svgops.py [REPEAT]   (default 3)

For the parts dynamics, kinematics and forces: the note with that section alone is built and its
print HTML laid out and written as a build does (``render._html_class``, the font configuration,
a new image cache each time, so every figure is parsed or compiled again as in a new process;
svgops' memos are emptied too; the garbage of the run before collected outside the timing, the
collector's threshold as in a build), alternately with WeasyPrint drawing the figures and with
svgops, REPEAT times after one warm-up of each. Prints the medians of this process's CPU
seconds (``time.process_time``: the machine may be shared) for "layout" (svgops' compilation
included) and "write", and whether the two PDFs are the same bytes.
"""
import os
import statistics
import sys
import time
from pathlib import Path

os.environ["REPORTGEN_JOBS"] = "1"
sys.path.insert(0, os.getcwd())


def main(argv: list[str]) -> None:
    import gc

    from reportgen.analysis.study import Study
    from reportgen.core.memory import collect_less
    from reportgen.report import render, svgops
    from reportgen.report.assemble import build_report

    n = int(argv[0]) if argv else 3
    collect_less()
    study = Study(Path("cases/ws000_six_bar.toml"))
    HTML = render._html_class()
    render._quiet_weasyprint()
    fonts = render._font_config()
    total = {"weasyprint": [0.0, 0.0], "svgops": [0.0, 0.0]}
    for sec in ("dynamics", "kinematics", "forces"):
        html = render.render_html(build_report(study, [sec]), for_print=True)
        figures = len(set(svgops._DATA_SVG.findall(html)))
        times = {k: ([], []) for k in total}
        pdfs = {}
        for i in range(n + 1):
            for mode in times:
                cache: dict = {}
                for memo in (svgops._PATHS, svgops._TOKENS, svgops._LENGTHS, svgops._TRANSFORMS,
                             svgops._COLORS):
                    memo.clear()
                doc = None
                gc.collect()
                t0 = time.process_time()
                if mode == "svgops":
                    svgops.prime(cache, html)
                doc = HTML(string=html, base_url=str(render.TEMPLATES_DIR)).render(font_config=fonts, cache=cache)
                t1 = time.process_time()
                with render._fixed_font_timestamp():
                    pdfs[mode] = doc.write_pdf()
                t2 = time.process_time()
                if i:
                    times[mode][0].append(t1 - t0)
                    times[mode][1].append(t2 - t1)
        m = statistics.median
        for mode, (lay, wri) in times.items():
            total[mode][0] += m(lay)
            total[mode][1] += m(wri)
            print(f"{sec} ({figures} figures), {mode}: layout {m(lay):.2f} + write {m(wri):.2f} = "
                  f"{m(lay) + m(wri):.2f} s CPU", flush=True)
        print(f"{sec}: PDFs the same bytes: {pdfs['weasyprint'] == pdfs['svgops']}", flush=True)
    for mode, (lay, wri) in total.items():
        print(f"three parts, {mode}: layout {lay:.2f} + write {wri:.2f} = {lay + wri:.2f} s CPU "
              f"(medians of {n} after one warm-up)")
    print(f"load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main(sys.argv[1:])
