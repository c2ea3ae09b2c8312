"""The figures' SVG rewritten for WeasyPrint (reportgen/style/svgslim.py) draws the same shapes.

The cross-check is a small independent SVG flattener: it resolves ``<use>``, ``<g>`` transforms
and inherited styles of both documents and lists, in painting order, every drawn path as
its points in the coordinates of the page with the style it is painted with. The lists of
matplotlib's SVG and of the rewritten one must agree (points to 1e-6 pt: six decimals in the text frames)."""
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from reportgen.style import mplstyle
from reportgen.style.svgslim import slim

S = "{http://www.w3.org/2000/svg}"
HREF = "{http://www.w3.org/1999/xlink}href"
INHERITED = ("fill", "stroke", "stroke-width", "stroke-dasharray", "stroke-linecap",
             "stroke-linejoin", "opacity", "fill-opacity", "stroke-opacity", "clip-path")


def _matrix(text):
    m = np.eye(3)
    for name, args in re.findall(r"(\w+)\s*\(([^)]*)\)", text or ""):
        v = [float(a) for a in re.split(r"[\s,]+", args.strip())]
        if name == "translate":
            n = np.array([[1, 0, v[0]], [0, 1, v[1] if len(v) > 1 else 0], [0, 0, 1]])
        elif name == "scale":
            n = np.diag([v[0], v[-1], 1.0])
        elif name == "rotate":
            c, s = math.cos(math.radians(v[0])), math.sin(math.radians(v[0]))
            n = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        else:
            a, b, c, d, e, f = v
            n = np.array([[a, c, e], [b, d, f], [0, 0, 1]])
        m = m @ n
    return m


def _style(el, inherited):
    out = dict(inherited)
    for k in INHERITED:
        if el.get(k) is not None:
            out[k] = el.get(k)
    for decl in (el.get("style") or "").split(";"):
        if ":" in decl:
            k, v = decl.split(":", 1)
            out[k.strip()] = v.strip()
    return out


def _points(d):
    cmds = re.findall(r"[A-Za-z]|[-+]?(?:\d+\.?\d*|\.\d+)(?:e[-+]?\d+)?", d)
    letters = "".join(c for c in cmds if c.isalpha())
    nums = np.array([float(c) for c in cmds if not c.isalpha()]).reshape(-1, 2)
    return letters, nums


def drawn(svg: bytes):
    """[(style, commands, points on the page)] in painting order."""
    root = ET.fromstring(svg)
    ids = {el.get("id"): el for el in root.iter() if el.get("id")}
    out = []

    def walk(el, m, inherited):
        if el.tag in (S + "defs", S + "metadata", S + "clipPath", S + "style"):
            return
        m = m @ _matrix(el.get("transform"))
        style = _style(el, inherited)
        if el.tag == S + "use":
            m = m @ _matrix(f"translate({el.get('x', 0)} {el.get('y', 0)})")
            walk(ids[el.get(HREF)[1:]], m, style)
        elif el.tag == S + "path":
            letters, pts = _points(el.get("d") or "")
            if len(pts):
                page = (m @ np.c_[pts, np.ones(len(pts))].T).T[:, :2]
                out.append((tuple(sorted(style.items())), letters, page, m[:2, :2]))
        elif el.tag == S + "rect":
            out.append((tuple(sorted(style.items())), "rect",
                        np.array([[float(el.get(k)) for k in ("x", "y", "width", "height")]]), m[:2, :2]))
        for ch in el:
            walk(ch, m, style)

    walk(root, np.eye(3), {})
    return out


@pytest.fixture(scope="module")
def figure_svg():
    fig = mplstyle.figure(120, 80)
    ax = fig.add_subplot()
    x = np.linspace(0, 360, 37)
    ax.plot(x, np.sin(np.radians(x)), marker="o", markevery=6, label="ω₁, рад/с")
    ax.plot(x, np.cos(np.radians(x)), "--", label=r"$\frac{d\omega}{d\varphi}$")
    ax.bar([60, 120], [0.5, -0.4], width=20, hatch="//", fill=False)
    ax.annotate(r"$J_{II} = \sqrt{2}$", (180, 0.2), color="tab:red")
    ax.set_xlabel("φ, град")
    ax.set_ylabel("$M_{пр}$, Н·м")
    ax.legend()
    fig.canvas.draw()
    with mplstyle.matplotlib.rc_context({"svg.fonttype": "path", "svg.hashsalt": mplstyle.SVG_HASHSALT}):
        import io

        buf = io.BytesIO()
        fig.savefig(buf, format="svg", metadata={"Date": None})
    return buf.getvalue()


def test_slim_draws_the_same_shapes(figure_svg):
    before, after = drawn(figure_svg), drawn(slim(figure_svg))
    # a text's glyphs become one path: compare the concatenated glyph runs
    def runs(items):
        merged = []
        for style, letters, pts, lin in items:
            fill_only = dict(style).get("stroke", "none") == "none" and letters != "rect"
            if merged and fill_only and merged[-1][0] == style and merged[-1][4]:
                merged[-1] = (style, merged[-1][1] + letters, np.vstack([merged[-1][2], pts]), lin, True)
            else:
                merged.append((style, letters, pts, lin, fill_only))
        return merged

    a, b = runs(before), runs(after)
    assert len(a) == len(b)
    for (s1, l1, p1, m1, _), (s2, l2, p2, m2, _) in zip(a, b):
        assert s1 == s2 and l1 == l2
        assert np.abs(p1 - p2).max() < 1e-6
        if dict(s1).get("stroke", "none") != "none":
            assert np.allclose(m1, m2)  # a stroke is drawn at the same width


def test_slim_has_no_use_and_fewer_elements(figure_svg):
    out = slim(figure_svg)
    assert out.startswith(b"<?xml") and b"<use" not in out and b"<metadata" not in out
    count = lambda s: len(ET.fromstring(s).findall(".//*"))
    assert count(out) * 3 < count(figure_svg)
    # the comments naming each text are kept (tests look for labels in them)
    assert b"<!-- \xcf\x86, \xd0\xb3\xd1\x80\xd0\xb0\xd0\xb4 -->" in out
    # clip paths and the hatch pattern are defined before anything is drawn
    root = ET.fromstring(out)
    assert root[0].tag == S + "defs" and {c.tag for c in root[0]} >= {S + "clipPath", S + "pattern", S + "style"}


def test_slim_is_deterministic_and_idempotent(figure_svg):
    once = slim(figure_svg)
    assert slim(figure_svg) == once
    assert slim(once) == once


def test_slim_leaves_what_it_does_not_know():
    other = b'<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10"><circle r="1"/></svg>'
    assert drawn(slim(other)) == [] and b"<circle" in slim(other)
    assert slim(b"not xml") == b"not xml"
    rel = (b'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink">'
           b'<defs><path id="a" d="m 0 0 l 1 1"/></defs>'
           b'<g transform="scale(0.1)"><use xlink:href="#a"/></g></svg>')
    out = slim(rel)
    assert b"m0 0l1 1" in out  # relative path data: kept, placed by the use's transforms
