"""CPU of laying out and writing each part of the ws000 note with the figures drawn by WeasyPrint's
SVG renderer and by reportgen/report/svgops.py, in one process.

Usage: python bench/bench_svgops.py [REPEAT]   (default 3)
       python bench/bench_svgops.py --figures   (every figure of every case in cases/)

For the parts dynamics, kinematics and forces: the note with that section alone is built and its
print HTML laid out and written as a build does (``render._html_class``, the font configuration,
a new image cache each time, so every figure is parsed or compiled again as in a new process;
svgops' memos are emptied too; the garbage of the run before collected outside the timing, the
collector's threshold as in a build), alternately with WeasyPrint drawing the figures and with
svgops, REPEAT times after one warm-up of each. Prints the medians of this process's CPU
seconds (``time.process_time``: the machine may be shared) for "layout" (svgops' compilation
included) and "write", and whether the two PDFs are the same bytes.

``--figures`` builds the note of every case in cases/ and draws each figure on a fresh PDF stream
by WeasyPrint's ``SVGImage`` and by svgops (as tests/test_svg_pdf_ops.py does for two cases):
prints how many were compiled, fell back, drew the same bytes (operators, resources, groups,
patterns), and the CPU of drawing them both ways and of compiling them.
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


def _stream():
    import pydyf
    from tinycss2.color5 import parse_color
    from weasyprint.pdf.stream import Stream

    resources = pydyf.Dictionary({k: pydyf.Dictionary() for k in
                                  ("ExtGState", "XObject", "Pattern", "Shading", "ColorSpace")})
    s = Stream({}, (0, 0, 595, 842), resources, {}, None, {}, None, compress=False)
    s.transform(0.75, 0, 0, -0.75, 0, 841.89)
    s.set_color(parse_color("black"))
    return s


def _drawn(image) -> bytes:
    import pydyf

    def dump(stream):
        out = [b"\n".join(pydyf._to_bytes(i) for i in stream.stream)]
        resources = stream._resources
        out.append(repr(sorted(resources["ExtGState"].items())).encode())
        for kind in ("XObject", "Pattern"):
            for key, sub in resources[kind].items():
                extra = pydyf.Dictionary({k: v for k, v in sub.extra.items() if k != "Resources"})
                out.append(key.encode() + extra.data + dump(sub))
        return b"\n".join(out)

    s = _stream()
    s.push_state()
    s.set_alpha(1)
    s.transform(e=70.866, f=123.4567)
    s.push_state()
    image.draw(s, 453.5433, 300.123, {"image_rendering": "auto"})
    s.pop_state()
    s.pop_state()
    return dump(s)


def figures() -> None:
    from xml.etree import ElementTree

    from weasyprint.images import SVGImage

    from reportgen.analysis.study import Study
    from reportgen.errors import CaseError
    from reportgen.report import svgops
    from reportgen.report.assemble import build_report
    from reportgen.report.document import Figure

    def walk(node, out):
        if isinstance(node, Figure):
            out.append(node.svg if isinstance(node.svg, bytes) else node.svg.encode())
        for attr in ("sections", "children"):
            for child in getattr(node, attr, None) or []:
                walk(child, out)
        return out

    n = same = fallback = cases = 0
    t_weasy = t_fast = t_compile = 0.0
    for case in sorted(Path("cases").glob("*.toml")):
        try:
            report = build_report(Study(case))
        except CaseError:
            continue  # (a class's base case holds no note of its own)
        cases += 1
        for data in walk(report, []):
            if data[:4] == b"\x89PNG":
                continue
            n += 1
            t0 = time.process_time()
            fast = svgops.compile_svg(data)
            t1 = time.process_time()
            t_compile += t1 - t0
            if fast is None:
                fallback += 1
                continue
            ref = SVGImage(ElementTree.fromstring(data), None, None, None)
            t0 = time.process_time()
            a = _drawn(ref)
            t1 = time.process_time()
            b = _drawn(fast)
            t2 = time.process_time()
            t_weasy += t1 - t0
            t_fast += t2 - t1
            same += a == b
    print(f"{cases} cases, {n} SVG figures: {n - fallback} compiled, {fallback} fell back, {same} drawn the "
          f"same bytes; drawing CPU: WeasyPrint {t_weasy:.2f} s, svgops {t_fast:.2f} s (+ compiling "
          f"{t_compile:.2f} s); load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    if sys.argv[1:] == ["--figures"]:
        figures()
    else:
        main(sys.argv[1:])
