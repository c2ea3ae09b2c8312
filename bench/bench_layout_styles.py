"""Computed styles and layout CPU of WeasyPrint for the heavy parts of the ws000 note.

Usage: python bench/bench_layout_styles.py TAG [REPEAT]   (run in each checkout to compare two versions)

For the parts dynamics, kinematics and forces: the note with that section alone is built and its
print HTML laid out (``HTML(...).render()``) once while counting what the cascade makes — the
computed styles (``ComputedStyle`` objects: one per element whose style is not shared) and the
style properties computed in them (``ComputedStyle.__missing__``) — then REPEAT times for the CPU
seconds of this process (``time.process_time``, median after one warm-up; the machine may be
shared). The counts do not depend on the machine. An element with an id, and every element
inside it, gets a style of its own in WeasyPrint 70 (the id is the ``-weasy-anchor`` property).
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
    import weasyprint.css as wcss

    from reportgen.analysis.study import Study
    from reportgen.report import render
    from reportgen.report.assemble import build_report

    tag, n = argv[0], int(argv[1]) if len(argv) > 1 else 3
    counts = {"styles": 0, "props": 0}
    init, missing = wcss.ComputedStyle.__init__, wcss.ComputedStyle.__missing__

    def counting_init(self, *a, **k):
        counts["styles"] += 1
        init(self, *a, **k)

    def counting_missing(self, key):
        counts["props"] += 1
        return missing(self, key)

    study = Study(Path("cases/ws000_six_bar.toml"))
    for sec in ("dynamics", "kinematics", "forces"):
        html = render.render_html(build_report(study, [sec]), for_print=True)
        lay = render._html_class()  # the note's lighter user-agent stylesheet, as the CLI lays out
        base = str(render.TEMPLATES_DIR)
        lay(string=html, base_url=base).render()  # warm-up (fonts, images)
        wcss.ComputedStyle.__init__, wcss.ComputedStyle.__missing__ = counting_init, counting_missing
        counts.update(styles=0, props=0)
        try:
            doc = lay(string=html, base_url=base).render()
        finally:
            wcss.ComputedStyle.__init__, wcss.ComputedStyle.__missing__ = init, missing
        cpu = []
        for _ in range(n):
            t0 = time.process_time()
            lay(string=html, base_url=base).render()
            cpu.append(time.process_time() - t0)
        print(f"{tag} {sec}: {len(doc.pages)} pages, {html.count('<') - html.count('</')} tags, "
              f"{counts['styles']} computed styles, {counts['props']} style properties computed; "
              f"layout {statistics.median(cpu):.2f} s CPU (median of {n}); "
              f"load {os.getloadavg()[0]:.1f} (weasyprint {weasyprint.__version__})", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
