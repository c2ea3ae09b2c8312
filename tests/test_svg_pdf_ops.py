"""Figures drawn from precompiled PDF operators (reportgen/report/svgops.py) against WeasyPrint's
own SVG renderer.

The cross-check is WeasyPrint itself: the same SVG is drawn by ``weasyprint.images.SVGImage``
and by :class:`svgops.FigureImage` on two fresh PDF streams, prepared as ``draw_replacedbox``
prepares them (a page matrix, a colour already set, the image's offset); the operators of the
streams, their graphics-state resources and every transparency group or pattern they create
must be the same bytes. Synthetic figures exercise each construct (transforms, clip paths,
dashes, caps and joins, alpha, element opacity, even-odd fill, quadratic segments, hatch
patterns, Z without a drawing command, numbers not in pydyf's form); the real figures of two
cases are all compiled (no fallback) and drawn the same; a note's PDF is the same bytes and the
same pixels with the fast path and without it; an unknown construct falls back to WeasyPrint.
"""
from __future__ import annotations

import base64
import subprocess
from xml.etree import ElementTree

import pydyf
import pytest
from conftest import CASES

from reportgen.report import render, svgops

HEAD = ('<?xml version="1.0" encoding="utf-8" standalone="no"?>\n'
        '<svg xmlns="http://www.w3.org/2000/svg" width="200pt" height="120pt" viewBox="0 0 200 120" '
        'version="1.1"><defs><style type="text/css">*{stroke-linejoin: round; stroke-linecap: butt}</style>'
        '<clipPath id="c1"><rect x="10" y="10" width="150" height="90" /></clipPath>'
        '<clipPath id="c2"><rect x="0" y="0" width="60.5" height="50" /></clipPath>'
        '<pattern id="h1" patternUnits="userSpaceOnUse" x="0" y="0" width="72" height="72">'
        '<rect x="0" y="0" width="73" height="73" fill="#bdbdbd" />'
        '<path d="M -36 36  L 36 -36  M 0 72  L 72 0  M 36 108  L 108 36  " '
        'style="fill: #000000; stroke: #000000; stroke-width: 1.0; stroke-linecap: butt; '
        'stroke-linejoin: miter" /></pattern></defs>'
        '<path d="M0 120L200 120L200 0L0 0z" style="fill: #ffffff" />')

CONSTRUCTS = {
    "transforms": '<path d="M0 0L10 0L10 10z" transform="translate(20 30) rotate(30) scale(2 1.5)" '
                  'style="fill: #1f77b4" /><path d="M0 0L5 5" transform="matrix(0.5 0.2 -0.3 1.1 40.25 7)" '
                  'style="fill: none; stroke: #d62728; stroke-width: 2" />'
                  '<path d="M1 1L3 3" transform="scale(0 1)" style="stroke: #000000" />',
    "clip": '<path d="M5 5L190 5L190 115z" clip-path="url(#c1)" style="fill: #2ca02c; stroke: #000000" />'
            '<g clip-path="url(#c2)"><path d="M0 0L100 100" style="fill: none; stroke: #9467bd; '
            'stroke-width: 3" /><path d="M0 0L9 0L9 9z" transform="translate(50 40)" style="fill: #8c564b" />'
            '</g>',
    "dash": '<path d="M10 10L190 10" style="fill: none; stroke: #000000; stroke-dasharray: 3.7,1.6; '
            'stroke-dashoffset: 0; stroke-width: 0.8" /><path d="M10 20L190 20L100 60" style="fill: none; '
            'stroke: #444444; stroke-dasharray: 6.4,1.6,1,1.6; stroke-dashoffset: -2; stroke-linecap: '
            'round; stroke-linejoin: bevel" /><path d="M10 40L100 45L10 50" style="fill: none; stroke: '
            '#000000; stroke-width: 4; stroke-linecap: square; stroke-linejoin: miter; '
            'stroke-miterlimit: 10" /><path d="M10 70L190 70" style="fill: none; stroke: #000000; '
            'stroke-dasharray: 0,0" /><path d="M10 80L190 80" style="fill: none; stroke: #000000; '
            'stroke-width: 0.5mm; stroke-dasharray: 1mm,2%" />',
    "alpha": '<path d="M10 10L100 10L100 100z" style="fill: #1f77b4; fill-opacity: 0.08; stroke: #ff7f0e; '
             'stroke-opacity: 0.7" /><path d="M50 20L150 20L150 80L50 80z" clip-path="url(#c1)" '
             'style="fill: #ffffff; opacity: 0.9; stroke: #7a7a7a; stroke-width: 0.7; '
             'stroke-linejoin: miter" /><path d="M60 60L70 70" style="fill: none; stroke: #000000; '
             'opacity: 0.1" />',
    "evenodd": '<path d="M10 10L110 10L110 110L10 110zM30 30L90 30L90 90L30 90z" '
               'style="fill: #17becf; fill-rule: evenodd; stroke: #000000" />'
               '<path d="M120 10L190 10L190 80L120 80zM130 20L180 20L180 70L130 70z" style="fill: #17becf" />',
    "quadratic": '<path d="M10 100Q50 10 90 100Q130 190 170 100L170 110C150 115 120 118.5 100 119z" '
                 'transform="translate(2.5 -3) scale(0.015625 0.015625)" style="fill: #000000" />'
                 '<path d="M 10.50 -0 L 1e1 20 Q 30,40 50.0,60 z" style="fill: #bcbd22; stroke: #000000" />',
    "hatch": '<path d="M20 20L80 20L80 60L20 60z" clip-path="url(#c1)" style="fill: url(#h1); '
             'stroke: #000000; stroke-linejoin: miter" /><path d="M100 30L180 30L180 90L100 90z" '
             'style="fill: url(#h1)" /><path d="M20 70L80 70L80 110L20 110z" clip-path="url(#c1)" '
             'style="fill: url(#h1); stroke: #000000; stroke-linejoin: miter" />',
    "close": '<path d="M 1 1 z M 20 20 L 30 30 L 20 40 z z L 50 50 M 60 60 z" '
             'style="fill: #e377c2; stroke: #000000" /><path d="M80 80" style="fill: #000000" />'
             '<path d="" style="stroke: #000000" />',
}


def svg_of(body: str) -> bytes:
    return (HEAD + body + "</svg>\n").encode()


def _stream():
    from tinycss2.color5 import parse_color
    from weasyprint.pdf.stream import Stream

    resources = pydyf.Dictionary({k: pydyf.Dictionary() for k in
                                  ("ExtGState", "XObject", "Pattern", "Shading", "ColorSpace")})
    s = Stream({}, (0, 0, 595, 842), resources, {}, None, {}, None, compress=False)
    s.transform(0.75, 0, 0, -0.75, 0, 841.89)  # a page's matrix
    s.set_color(parse_color("black"))  # left by the text drawn before the image
    return s


def _dump(stream) -> bytes:
    """The stream's operators, its resources and, recursively, its groups and patterns."""
    out = [b"\n".join(pydyf._to_bytes(i) for i in stream.stream)]
    resources = stream._resources
    out.append(repr(sorted(resources["ExtGState"].items(), key=lambda kv: kv[0])).encode())
    for kind in ("XObject", "Pattern"):
        for key, sub in resources[kind].items():
            extra = pydyf.Dictionary({k: v for k, v in sub.extra.items() if k != "Resources"})
            out.append(key.encode() + b":" + extra.data + b"\n" + _dump(sub))
    return b"\n".join(out)


def drawn(image, width=453.5433, height=300.123, x=70.866, y=123.4567) -> bytes:
    """What ``draw_replacedbox`` makes of ``image`` at (x, y) with that size."""
    s = _stream()
    s.push_state()
    s.set_alpha(1)
    s.transform(e=x, f=y)
    s.push_state()
    image.draw(s, width, height, {"image_rendering": "auto"})
    s.pop_state()
    s.pop_state()
    return _dump(s)


def weasyprint_image(data: bytes):
    from weasyprint.images import SVGImage

    return SVGImage(ElementTree.fromstring(data), None, None, None)


def assert_same_drawing(data: bytes) -> None:
    fast = svgops.compile_svg(data)
    assert fast is not None, "fell back to WeasyPrint"
    ref = weasyprint_image(data)
    assert fast.get_intrinsic_size(96, 16) == ref.get_intrinsic_size(96, 16)
    for size in ((453.5433, 300.123), (120.0, 200.0)):  # a box of the figure's ratio, and another
        assert drawn(fast, *size) == drawn(ref, *size)


@pytest.mark.parametrize("name", sorted(CONSTRUCTS))
def test_construct_drawn_as_weasyprint_draws_it(name):
    assert_same_drawing(svg_of(CONSTRUCTS[name]))


def test_all_constructs_in_one_figure():
    assert_same_drawing(svg_of("".join(CONSTRUCTS.values())))


def _html(figures: list[bytes]) -> str:
    return "".join('<p>Рисунок</p><img style="width:160mm" src="data:image/svg+xml;base64,'
                   + base64.b64encode(f).decode() + '">' for f in figures)


def _pdf(html: str, fast: bool) -> bytes:
    from weasyprint import HTML

    cache: dict = {}
    if fast:
        svgops.prime(cache, html)
        assert cache and all(isinstance(v, svgops.FigureImage) for v in cache.values())
    return HTML(string=html).render(cache=cache).write_pdf()


def test_pages_same_bytes_and_pixels_as_weasyprint(tmp_path):
    """The synthetic figures on pages: the PDF is the same bytes with the fast path as without
    it, and (rendered at 40 dpi by poppler) the same pixels."""
    from PIL import Image, ImageChops

    html = _html([svg_of(CONSTRUCTS[k]) for k in sorted(CONSTRUCTS)])
    drawn_before = svgops.STATS["drawn"]
    fast, slow = _pdf(html, True), _pdf(html, False)
    assert svgops.STATS["drawn"] - drawn_before == len(CONSTRUCTS)
    assert fast == slow
    for name, data in (("fast", fast), ("slow", slow)):
        (tmp_path / f"{name}.pdf").write_bytes(data)
        subprocess.run(["pdftoppm", "-r", "40", "-gray", str(tmp_path / f"{name}.pdf"), str(tmp_path / name)],
                       check=True)
    pages = sorted(tmp_path.glob("fast-*.pgm"))
    assert pages
    for p in pages:
        other = Image.open(tmp_path / p.name.replace("fast-", "slow-"))
        assert ImageChops.difference(Image.open(p), other).getbbox() is None


UNKNOWN = {
    "circle": '<circle cx="5" cy="5" r="3" />',
    "text": '<text x="1" y="10">x</text>',
    "use": '<use href="#c1" />',
    "relative path": '<path d="m0 0l5 5" style="stroke: #000000" />',
    "marker": '<path d="M0 0L5 5" style="marker-end: url(#m)" />',
    "group opacity": '<g style="opacity: 0.5"><path d="M0 0L5 5" /></g>',
    "gradient": '<path d="M0 0L5 5z" style="fill: url(#c2)" />',
    "filter": '<path d="M0 0L5 5" filter="url(#f)" />',
    "important": '<path d="M0 0L5 5" style="stroke: #000000 !important" />',
    "display": '<path d="M0 0L5 5" display="none" />',
}


@pytest.mark.parametrize("name", sorted(UNKNOWN))
def test_unknown_construct_falls_back(name):
    data = svg_of(UNKNOWN[name])
    before = svgops.STATS["fallback"]
    assert svgops.compile_svg(data) is None
    assert svgops.STATS["fallback"] == before + 1
    html = _html([data])
    cache: dict = {}
    svgops.prime(cache, html)
    assert cache == {}  # left to WeasyPrint, which parses and draws it as before


def test_fallback_figure_still_drawn_in_a_document():
    html = _html([svg_of(UNKNOWN["circle"]), svg_of(CONSTRUCTS["clip"])])
    fast, slow = _pdf_mixed(html), _pdf(html, False)
    assert fast == slow


def _pdf_mixed(html: str) -> bytes:
    from weasyprint import HTML

    cache: dict = {}
    svgops.prime(cache, html)
    assert len(cache) == 1
    return HTML(string=html).render(cache=cache).write_pdf()


def _figures(case: str) -> list[bytes]:
    from reportgen.analysis.study import Study
    from reportgen.report.assemble import build_report
    from reportgen.report.document import Figure

    out = []

    def walk(node):
        if isinstance(node, Figure):
            out.append(node.svg if isinstance(node.svg, bytes) else node.svg.encode())
            return
        for attr in ("sections", "children"):
            for child in getattr(node, attr, None) or []:
                walk(child)

    walk(build_report(Study(CASES / case)))
    return out


@pytest.mark.parametrize("case", ["ws004_slotted_lever.toml", "ws000_six_bar.toml"])
def test_every_figure_of_a_case_compiled_and_drawn_the_same(case):
    figures = _figures(case)
    assert len(figures) >= 5
    before = svgops.STATS["fallback"]
    for data in figures:
        assert_same_drawing(data)
    assert svgops.STATS["fallback"] == before


def test_a_build_uses_the_fast_path_and_gives_the_same_bytes(tmp_path, monkeypatch):
    """A note laid out and written in this process (one layout job): every figure is drawn by
    svgops (counter), and the PDF is the same bytes as with WeasyPrint drawing the figures."""
    from reportgen.analysis.study import Study
    from reportgen.report.assemble import build_report

    report = build_report(Study(CASES / "slider_crank.toml"), ["kinematics"])
    n_figures = sum(1 for _ in svgops._DATA_SVG.finditer(render.render_html(report, for_print=True)))
    assert n_figures >= 3
    paths = {}
    for fast in (True, False):
        monkeypatch.setattr(render, "_IMAGE_CACHE", {})
        monkeypatch.setattr(svgops, "ENABLED", fast)
        before = dict(svgops.STATS)
        paths[fast] = render.write_pdf(report, tmp_path / f"{fast}.pdf", jobs=1)
        drawn_now = svgops.STATS["drawn"] - before.get("drawn", 0)
        assert drawn_now == (n_figures if fast else 0)
    assert paths[True].read_bytes() == paths[False].read_bytes()


def test_transform_values_are_weasyprints():
    """svgops computes transform lists itself (the same operations as ``svg.utils.transform``)."""
    import random

    from weasyprint.svg.utils import transform

    rng = random.Random(15)
    texts = ["translate(1 2)", "translate(3)", "scale(2)", "scale(0.015625 0.015625)", "rotate(-90)",
             "matrix(0.5 0.2 -0.3 1.1 40.25 7)", "scale(0 1)", "translate(1e1, -0) scale(-1 1)"]
    for _ in range(200):
        x, y, a, r = (round(rng.uniform(-500, 500), rng.randint(0, 6)) for _ in range(4))
        texts.append(f"translate({x} {y}) rotate({r}) scale({a} {round(a * 0.7, 6)})")
    for text in texts:
        ref = transform(text, None, 16.0, 100.0)
        assert svgops._transform_values(text, 16.0, 100.0) == (ref.values if ref.determinant else None), text
