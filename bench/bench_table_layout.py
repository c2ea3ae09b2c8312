"""What ``table-layout: fixed`` would save in WeasyPrint's layout of ws000's heavy parts.

Usage (from the repository root)::

    python bench/bench_table_layout.py [REPEAT]

For the parts kinematics, dynamics and forces (their print HTML with the split points of a
first write), the layout alone (``render()``, no write) with the note's tables as they are
(``table-layout: auto``: WeasyPrint measures every cell's min- and max-content width, i.e. the
cell text goes through Pango three times) and with ``table.tbl { table-layout: fixed }`` added
(the widths come from the first row; here equal columns, so the pages differ — the figure is an
upper bound of what explicit column widths could save). CPU seconds of this process
(``time.process_time``), the two variants alternating, minimum and median of REPEAT each.
"""
from __future__ import annotations

import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
os.environ.setdefault("REPORTGEN_JOBS", "1")

FIXED = "table.tbl { table-layout: fixed; }"


def main(argv: list[str]) -> None:
    from reportgen.analysis.study import Study
    from reportgen.report import render, svgops
    from reportgen.report.assemble import build_report

    n = int(argv[0]) if argv else 3
    report = build_report(Study(ROOT / "cases/ws000_six_bar.toml"))
    with tempfile.TemporaryDirectory() as d:  # (write_pdf writes atomically: never to a device file)
        render.write_pdf(report, Path(d) / "note.pdf", jobs=1)  # the split points
    views = render._views(report, for_print=True, splits=render.last_stats.splits)
    body = views.ctx["body"]
    HTML, fc, cache = render._html_class(), render._font_config(), render._image_cache()

    def lay(html: str):
        svgops.prime(cache, html)
        c0 = time.process_time()
        doc = HTML(string=html, base_url=str(render.TEMPLATES_DIR)).render(font_config=fc, cache=cache)
        return time.process_time() - c0, len(doc.pages)

    total = {"auto": 0.0, "fixed": 0.0}
    for i, node in enumerate(body):
        html = views.html(front=False, body=[node], chunk=True)
        if html.count("<td") < 300:
            continue
        fixed = html.replace("</style>", FIXED + "</style>", 1)
        times = {"auto": [], "fixed": []}
        pages = {}
        for _ in range(n):
            for name, h in (("auto", html), ("fixed", fixed)):
                t, pages[name] = lay(h)
                times[name].append(t)
        for name in times:
            total[name] += min(times[name])
        print(f"part {i}: {html.count('<td')} cells; auto {min(times['auto']):.2f} (median "
              f"{statistics.median(times['auto']):.2f}) s, {pages['auto']} pages; fixed {min(times['fixed']):.2f} "
              f"(median {statistics.median(times['fixed']):.2f}) s, {pages['fixed']} pages", flush=True)
    print(f"layout CPU, sum of minima: auto {total['auto']:.2f} s, fixed {total['fixed']:.2f} s "
          f"({100 * (total['fixed'] / total['auto'] - 1):+.0f} %); load {os.getloadavg()}")


if __name__ == "__main__":
    main(sys.argv[1:])
