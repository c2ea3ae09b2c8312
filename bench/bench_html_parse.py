"""What WeasyPrint's document set-up costs per document of a note, before and after session 8:
the HTML parse (tinyhtml5 against reportgen/report/fasthtml.py) and the note's stylesheet parse.

Usage (from the repository root)::

    python bench/bench_html_parse.py [CASE] [REPEAT]

For every document the PDF of CASE (default ws000) is laid out from — each body part, the title
page with the assignment, СОДЕРЖАНИЕ — CPU seconds (``time.process_time``, minimum of REPEAT) of
``tinyhtml5.parse`` and of ``fasthtml.parse`` (the trees are checked equal), and of parsing the
``<style>`` of gost.css and math.css with ``weasyprint.CSS`` (what each document paid before the
sheet was shared in the process).
"""
from __future__ import annotations

import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def _tree(el) -> tuple:
    return (el.tag, list(el.attrib.items()), el.text or "", el.tail or "", [_tree(c) for c in el])


def main(argv: list[str]) -> None:
    import re

    import tinyhtml5
    from weasyprint import CSS

    from reportgen.analysis.study import Study
    from reportgen.report import fasthtml, render
    from reportgen.report.assemble import build_report

    case = argv[0] if argv else "cases/ws000_six_bar.toml"
    n = int(argv[1]) if len(argv) > 1 else 3
    report = build_report(Study(ROOT / case))
    views = render._views(report, for_print=True, splits={})
    docs = [(f"часть {i}", views.html(front=False, body=[node], chunk=True)) for i, node in enumerate(views.ctx["body"])]
    docs.append(("титул и задание", views.html(body=[], toc=False, toc_pages={}, chunk=True)))
    docs.append(("содержание", views.html(head=False, body=[], toc_pages={e["id"]: "00" for e in views.builder.toc},
                                          chunk=True)))

    def best(f) -> float:
        times = []
        for _ in range(n):
            c0 = time.process_time()
            f()
            times.append(time.process_time() - c0)
        return min(times)

    tot = {"tinyhtml5": 0.0, "fast": 0.0, "css": 0.0}
    fc = render._font_config()
    for name, html in docs:
        fast = fasthtml.parse(html)
        same = fast is not None and _tree(fast) == _tree(tinyhtml5.parse(html, namespace_html_elements=False))
        t_tiny = best(lambda: tinyhtml5.parse(html, namespace_html_elements=False))
        t_fast = best(lambda: fasthtml.parse(html))
        sheet = max(re.findall(r"<style>(.*?)</style>", html, re.S), key=len)
        t_css = best(lambda: CSS(string=sheet, base_url=str(render.TEMPLATES_DIR), font_config=fc))
        tot["tinyhtml5"] += t_tiny
        tot["fast"] += t_fast
        tot["css"] += t_css
        print(f"{name}: {len(html) // 1024} КБ; tinyhtml5 {t_tiny:.3f} s, fasthtml {t_fast:.3f} s "
              f"({'same tree' if same else 'FALLBACK or DIFFERENT'}); stylesheet {t_css:.3f} s", flush=True)
    print(f"{len(docs)} documents: tinyhtml5 {tot['tinyhtml5']:.3f} s, fasthtml {tot['fast']:.3f} s; stylesheet "
          f"{tot['css']:.3f} s in all (now parsed once: {tot['css'] / len(docs):.3f} s); CPU, min of {n}; "
          f"load {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main(sys.argv[1:])
