"""CPU of WeasyPrint drawing the figures of a note: matplotlib's SVG against the rewritten one.

Usage: python bench/bench_svg_write.py [CASE] [REPEAT]   (default cases/ws000_six_bar.toml, 3)

The sections kinematics, dynamics and forces of CASE are built (their figures captured as
matplotlib wrote them, before :func:`reportgen.style.svgslim.slim`); one document with every
figure on a page of its own is laid out and written, once with the SVG as matplotlib wrote it
and once rewritten, alternately REPEAT times after one warm-up each (the machine may be
shared: the two are measured in turns, in one process, by ``time.process_time``). Prints the
medians, the sizes and the time ``slim`` itself takes.
"""
import base64
import os
import statistics
import sys
import time
from pathlib import Path

os.environ["REPORTGEN_JOBS"] = "1"
sys.path.insert(0, os.getcwd())


def main(argv: list[str]) -> None:
    import weasyprint

    from reportgen.analysis.study import Study
    from reportgen.report.assemble import build_report
    from reportgen.style import svgslim

    case = Path(argv[0]) if argv else Path("cases/ws000_six_bar.toml")
    n = int(argv[1]) if len(argv) > 1 else 3
    raw: list[bytes] = []
    real = svgslim.slim
    svgslim.slim = lambda svg: raw.append(svg) or real(svg)
    try:
        build_report(Study(case), ["kinematics", "dynamics", "forces"])
    finally:
        svgslim.slim = real
    t0 = time.process_time()
    slimmed = [real(s) for s in raw]
    t_slim = time.process_time() - t0

    def html(svgs):
        return "".join('<div style="break-after:page"><img style="width:160mm" src="data:image/svg+xml;base64,'
                       + base64.b64encode(s).decode() + '"></div>' for s in svgs)

    docs = {"matplotlib": html(raw), "rewritten": html(slimmed)}
    times = {k: ([], []) for k in docs}
    for i in range(n + 1):
        for k, h in docs.items():
            t0 = time.process_time()
            doc = weasyprint.HTML(string=h).render()
            t1 = time.process_time()
            doc.write_pdf()
            t2 = time.process_time()
            if i:
                times[k][0].append(t1 - t0)
                times[k][1].append(t2 - t1)
    m = statistics.median
    for k in docs:
        size = sum(len(s) for s in (raw if k == "matplotlib" else slimmed))
        print(f"{k}: {len(raw)} figures, {size // 1024} KB of SVG; layout {m(times[k][0]):.2f} + "
              f"write {m(times[k][1]):.2f} s CPU (median of {n})")
    print(f"slim: {t_slim:.3f} s CPU for the {len(raw)} figures; load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main(sys.argv[1:])
