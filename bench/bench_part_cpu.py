"""CPU of WeasyPrint laying out and writing each part of the ws000 note, in one process.

Usage: python bench/bench_part_cpu.py TAG [REPEAT]   (run in each checkout to compare two versions)

For the parts dynamics, kinematics and forces: the note with that section alone is built, its
print HTML is laid out and written REPEAT times after one warm-up run; the medians of the CPU
seconds of this process (``time.process_time``: the machine may be shared) are printed.
"""
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
    from reportgen.report import render
    from reportgen.report.assemble import build_report

    tag, n = argv[0], int(argv[1]) if len(argv) > 1 else 2
    study = Study(Path("cases/ws000_six_bar.toml"))
    for sec in ("dynamics", "kinematics", "forces"):
        html = render.render_html(build_report(study, [sec]), for_print=True)
        lay, wri = [], []
        for i in range(n + 1):
            t0 = time.process_time()
            doc = weasyprint.HTML(string=html, base_url=str(Path.cwd())).render()
            t1 = time.process_time()
            pdf = doc.write_pdf()
            t2 = time.process_time()
            if i:
                lay.append(t1 - t0)
                wri.append(t2 - t1)
        m = statistics.median
        print(f"{tag} {sec}: {len(doc.pages)} pages, layout {m(lay):.2f} + write {m(wri):.2f} = "
              f"{m(lay) + m(wri):.2f} s CPU (median of {n} after one warm-up); PDF {len(pdf) // 1024} KB, "
              f"HTML {len(html) // 1024} KB; load {os.getloadavg()[0]:.1f}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
