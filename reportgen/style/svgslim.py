"""matplotlib's SVG made light for WeasyPrint, drawing the same picture.

With ``svg.fonttype = "path"`` matplotlib writes every glyph outline once in a ``<defs>``
and every character of a text as a ``<use>`` of it, inside two or three levels of ``<g>``;
tick marks and line markers are ``<use>`` of a marker path as well. WeasyPrint draws a
``<use>`` by copying the referenced element, cascading its styles again and parsing its
path data again, and walks every ``<g>``; in ws000's note this was most of the cost of
writing the figures. :func:`slim` rewrites the document so that it draws the same shapes
with far fewer elements:

- every text (a group of glyph ``<use>``, filled, not stroked) becomes one ``<path>``: the
  glyph outlines placed by the ``<use>`` transforms and the glyphs' ``scale``, written in
  the text's own frame (its transform times a power of two chosen so that WeasyPrint
  writes the matrix exactly with its six decimals; the points then need at most six
  decimals too, so the PDF gets the same numbers up to the order of the multiplications);
- any other ``<use>`` of a path (tick marks, markers) becomes that path with the
  ``<use>``'s transform, its ``x``/``y`` and the path's own transform as its transform
  (the path data as they were) and the two styles merged as SVG inherits them;
- groups that carry nothing but an ``id`` are dissolved into their parent (no attribute,
  so no change to what their children inherit); the ``<metadata>`` block is dropped;
- what is left of ``<defs>`` (clip paths, hatch patterns) goes to the start of the
  document, where WeasyPrint's look-up by id (a search of the tree in document order,
  repeated at every level on the way down) finds it at once.

The pages of ws000's note rendered with Cairo (``pdftocairo``) are the same pixels with the
figures as matplotlib wrote them and as rewritten here.

Every other element and attribute is kept as matplotlib wrote it, and so are the comments
that name each text. Whatever this module does not recognise (a ``<use>`` of something
other than a path, relative path commands, a transform it cannot read) is left as it was.
The output is a function of the input alone (deterministic bytes).
"""
from __future__ import annotations

import functools
import re
import xml.etree.ElementTree as ET

__all__ = ["slim"]

SVG_NS = "http://www.w3.org/2000/svg"
XLINK_NS = "http://www.w3.org/1999/xlink"
_S = "{%s}" % SVG_NS
HREF = "{%s}href" % XLINK_NS
_G, _USE, _PATH, _DEFS = _S + "g", _S + "use", _S + "path", _S + "defs"
_METADATA = _S + "metadata"

_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_PATH_TOKEN = re.compile(r"[MLQCZz]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_PATH_OK = re.compile(r"^[\sMLQCZz0-9.eE+-]*$")
_TRANSFORM = re.compile(r"\s*(translate|scale|rotate|matrix)\s*\(([^)]*)\)\s*,?")
_ARITY = {"M": 1, "L": 1, "Q": 2, "C": 3, "Z": 0, "z": 0}

Matrix = tuple  # (a, b, c, d, e, f): x' = a x + c y + e, y' = b x + d y + f
IDENTITY: Matrix = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)


def _mul(m: Matrix, n: Matrix) -> Matrix:
    """The matrix product ``m · n`` (``n`` applied first)."""
    a, b, c, d, e, f = m
    A, B, C, D, E, F = n
    return (a * A + c * B, b * A + d * B, a * C + c * D, b * C + d * D,
            a * E + c * F + e, b * E + d * F + f)


@functools.lru_cache(maxsize=4096)
def _transform(text: str | None) -> Matrix | None:
    """An SVG ``transform`` list as one matrix (``None`` if it cannot be read); cached: the
    same few transforms (a glyph's place in a tick label, the text frames) recur in every
    figure."""
    m = IDENTITY
    if not text:
        return m
    pos = 0
    import math

    for match in _TRANSFORM.finditer(text):
        if match.start() != pos:
            return None
        pos = match.end()
        name = match.group(1)
        args = [float(v) for v in _NUMBER.findall(match.group(2))]
        if name == "translate" and len(args) in (1, 2):
            n = (1.0, 0.0, 0.0, 1.0, args[0], args[1] if len(args) == 2 else 0.0)
        elif name == "scale" and len(args) in (1, 2):
            n = (args[0], 0.0, 0.0, args[-1], 0.0, 0.0)
        elif name == "rotate" and len(args) == 1:
            r = math.radians(args[0])
            cs, sn = math.cos(r), math.sin(r)
            n = (cs, sn, -sn, cs, 0.0, 0.0)
        elif name == "matrix" and len(args) == 6:
            n = tuple(args)
        else:
            return None
        m = _mul(m, n)
    if text[pos:].strip():
        return None
    return m


def _num(v: float) -> str:
    """``v`` as matplotlib writes a coordinate: to 1e-6, without trailing zeros."""
    s = "%f" % v
    s = s.rstrip("0").rstrip(".")
    return "0" if s == "-0" else s


def _parse_path(d: str) -> list | None:
    """Absolute path data (M, L, Q, C, Z: all matplotlib writes) as ``[(cmd, [x, y, …])]``;
    ``None`` for anything else."""
    if not _PATH_OK.match(d):
        return None
    out = []
    cmd = None
    nums: list[float] = []
    for tok in _PATH_TOKEN.findall(d):
        if tok in _ARITY:
            if cmd is not None:
                out.append((cmd, nums))
            cmd, nums = tok, []
        elif cmd is None:
            return None
        else:
            nums.append(float(tok))
    if cmd is not None:
        out.append((cmd, nums))
    for cmd, nums in out:
        k = 2 * _ARITY[cmd]
        if (k == 0 and nums) or (k and (not nums or len(nums) % k)):
            return None
    return out


@functools.lru_cache(maxsize=4096)
def _parsed(d: str) -> list | None:
    """:func:`_parse_path` of a glyph's path data, cached for the process (the glyphs of the
    report's fonts recur in every figure; the result is only read)."""
    return _parse_path(d)


@functools.lru_cache(maxsize=16384)
def _placed(d: str, m: Matrix) -> str:
    """:func:`_write_path` of the glyph path data ``d`` (readable: :func:`_parsed`) mapped by
    ``m``, cached: a character at its place in a string (the digits of tick labels, point
    names) recurs in every figure with the same matrix, so the same text."""
    return _write_path(_parsed(d), m)


def _exact(v: float) -> bool:
    """Whether ``v`` is written exactly with six decimals (as WeasyPrint writes a PDF)."""
    return float("%f" % v) == v


def _frame(outer: Matrix) -> tuple[Matrix, float]:
    """``outer · scale(u)`` for the smallest ``u`` among 1/64 … 1/2, 1 whose matrix WeasyPrint
    writes exactly (six decimals), and that ``u``: text in this frame has short numbers."""
    for k in range(6, 0, -1):
        u = 2.0 ** -k
        m = _mul(outer, (u, 0.0, 0.0, u, 0.0, 0.0))
        if all(_exact(v) for v in m):
            return m, u
    return outer, 1.0


def _matrix(m: Matrix) -> str:
    """A transform attribute for ``m`` (translate and scale when it has no rotation)."""
    a, b, c, d, e, f = (_num(v) for v in m)
    if m[1] == 0.0 and m[2] == 0.0:
        return f"translate({e} {f}) scale({a} {d})"
    return f"matrix({a} {b} {c} {d} {e} {f})"


def _write_path(segments: list, m: Matrix, fmt=_num) -> str:
    """Path data of ``segments`` mapped by ``m`` (numbers as :func:`_num` writes them)."""
    a, b, c, d, e, f = m
    parts = []
    for cmd, nums in segments:
        pts = [fmt(a * nums[i] + c * nums[i + 1] + e) + " " + fmt(b * nums[i] + d * nums[i + 1] + f)
               for i in range(0, len(nums), 2)]
        parts.append(cmd + " ".join(pts))
    return "".join(parts)


_AROUND_COMMAND = re.compile(r"\s*([A-Za-z])\s*")
_SPACES = re.compile(r"\s+")


@functools.lru_cache(maxsize=4096)
def _compact(d: str) -> str:
    """Path data without the blanks around command letters (the numbers as they are)."""
    return _AROUND_COMMAND.sub(r"\1", _SPACES.sub(" ", d)).strip()


def _style(text: str | None) -> dict[str, str]:
    out = {}
    for decl in (text or "").split(";"):
        if ":" in decl:
            k, v = decl.split(":", 1)
            out[k.strip()] = v.strip()
    return out


def _merged_style(outer: str | None, inner: str | None) -> str | None:
    """The style of a ``<use>`` (``outer``) over its referent's own (``inner``): the referent's
    declarations win, the others it inherits."""
    if not outer or outer == inner:
        return inner
    if not inner:
        return outer
    merged = _style(outer)
    merged.update(_style(inner))
    return "; ".join(f"{k}: {v}" for k, v in merged.items())


def _strokes(style: str | None) -> bool:
    s = _style(style)
    return s.get("stroke", "none") != "none"


class _Slimmer:
    def __init__(self, root: ET.Element):
        self.paths: dict[str, ET.Element] = {}
        for el in root.iter(_PATH):
            pid = el.get("id")
            if pid is not None:
                self.paths[pid] = el
        self.parsed: dict[str, list | None] = {}

    def segments(self, pid: str) -> list | None:
        if pid not in self.parsed:
            self.parsed[pid] = _parsed(self.paths[pid].get("d", ""))
        return self.parsed[pid]

    def inline(self, use: ET.Element) -> ET.Element | None | bool:
        """The ``<path>`` drawing what ``use`` draws: the referenced path with the ``<use>``'s
        transform, its ``x``/``y`` offset and the path's own transform, in that order (as SVG
        places a ``<use>``), and the two styles merged; ``None`` when it draws nothing;
        ``False`` when it cannot be inlined."""
        href = use.get(HREF) or use.get("href") or ""
        ref = self.paths.get(href[1:]) if href.startswith("#") else None
        if ref is None or set(use.attrib) - {HREF, "href", "x", "y", "transform", "style"} \
                or set(ref.attrib) - {"id", "d", "transform", "style"}:
            return False
        x, y = use.get("x", "0"), use.get("y", "0")
        try:
            float(x), float(y)
        except ValueError:
            return False
        if not ref.get("d", "").strip():
            return None
        steps = [use.get("transform"), None if float(x) == float(y) == 0 else f"translate({x} {y})",
                 ref.get("transform")]
        path = ET.Element(_PATH)
        path.set("d", _compact(ref.get("d")))
        if any(steps):
            path.set("transform", " ".join(t for t in steps if t))
        style = _merged_style(use.get("style"), ref.get("style"))
        if style:
            path.set("style", style)
        return path

    def text(self, g: ET.Element, stroked: bool) -> list[ET.Element] | None:
        """A text group (transform, maybe a fill; glyph ``<defs>`` and ``<use>``) as one path,
        or ``[]`` for blank text; ``None`` if it is not such a group or may be stroked
        (``stroked``: a stroke inherited; the frame would change its width)."""
        if stroked or set(g.attrib) - {"transform", "style"} or not len(g) \
                or _strokes(g.get("style")):
            return None
        outer = _transform(g.get("transform"))
        if outer is None:
            return None
        uses = []
        for ch in g:
            if ch.tag == _USE:
                uses.append(ch)
            elif ch.tag != _DEFS or any(c.tag != _PATH for c in ch):
                return None
        glyphs = []
        for use in uses:
            href = use.get(HREF) or use.get("href") or ""
            ref = self.paths.get(href[1:]) if href.startswith("#") else None
            if ref is None or set(use.attrib) - {HREF, "href", "transform"} \
                    or set(ref.attrib) - {"id", "d", "transform"}:
                return None
            mu, mr = _transform(use.get("transform")), _transform(ref.get("transform"))
            if mu is None or mr is None:
                return None
            if ref.get("d", "").strip():
                segs = self.segments(ref.get("id"))
                if segs is None:
                    return None
                glyphs.append((_mul(mu, mr), ref.get("d")))
        if not glyphs:
            return []
        frame, unit = _frame(outer)
        inv = (1 / unit, 0.0, 0.0, 1 / unit, 0.0, 0.0)
        path = ET.Element(_PATH)
        path.set("d", "".join(_placed(d, _mul(inv, m)) for m, d in glyphs))
        if unit == 1.0:
            if g.get("transform"):
                path.set("transform", g.get("transform"))
        else:
            path.set("transform", _matrix(frame))
        if g.get("style"):
            path.set("style", g.get("style"))
        return [path]

    def children(self, parent: ET.Element, stroked: bool = False) -> list[ET.Element]:
        """The new children of ``parent`` (rewritten recursively); ``stroked``: whether a
        stroke is inherited from ``parent``."""
        out: list[ET.Element] = []
        for ch in list(parent):
            if ch.tag == _METADATA:
                continue
            if ch.tag == _G:
                text = self.text(ch, stroked)
                if text is not None:
                    out.extend(text)
                    continue
                ch[:] = self.children(ch, stroked or _strokes(ch.get("style")))
                if not ch.attrib or set(ch.attrib) == {"id"}:
                    out.extend(ch)  # a group without attributes: its children in its place
                    continue
                out.append(ch)
            elif ch.tag == _USE:
                p = self.inline(ch)
                if p is not None:
                    out.append(ch if p is False else p)
            else:
                if ch.tag == _PATH and ch.get("d"):
                    ch.set("d", _compact(ch.get("d")))
                if len(ch) and ch.tag != _DEFS:
                    ch[:] = self.children(ch, stroked or _strokes(ch.get("style")))
                out.append(ch)
        return out


def _collect_defs(root: ET.Element) -> list[ET.Element]:
    """Remove every ``<defs>`` from the tree; return their children still needed (all but
    path definitions that no ``<use>`` refers to any more)."""
    found = []
    kept_refs = set()
    for use in root.iter(_USE):
        href = use.get(HREF) or use.get("href") or ""
        kept_refs.add(href[1:])

    def walk(parent):
        for ch in list(parent):
            if ch.tag == _DEFS:
                parent.remove(ch)
                for d in ch:
                    if d.tag == _PATH and d.get("id") not in kept_refs:
                        continue
                    d.tail = None
                    found.append(d)
            elif len(ch):
                walk(ch)

    walk(root)
    return found


def slim(svg: bytes) -> bytes:
    """matplotlib's SVG bytes rewritten to draw the same with far fewer elements (see the
    module's docstring); the input unchanged if it is not one this module can read."""
    parser = ET.XMLParser(target=ET.TreeBuilder(insert_comments=True))
    try:
        root = ET.fromstring(svg, parser=parser)
    except ET.ParseError:
        return svg
    if root.tag != _S + "svg":
        return svg
    s = _Slimmer(root)
    root[:] = s.children(root)
    defs = _collect_defs(root)
    styles = [d for d in defs if d.tag == _S + "style"]
    rest = [d for d in defs if d.tag != _S + "style"]
    if defs:
        block = ET.Element(_DEFS)
        block.extend(styles + rest)
        root.insert(0, block)
    xlink = False
    for el in root.iter():
        el.tail = None
        if el.tag is ET.Comment:
            continue
        if el.text is not None and not el.text.strip() and el.tag != _S + "style":
            el.text = None
        # names written without ElementTree's namespace prefixes (ns0:): the SVG namespace is
        # the default one, xlink's prefix is declared below when a <use> is left
        if el.tag.startswith(_S):
            el.tag = el.tag[len(_S):]
        if HREF in el.attrib:
            el.set("xlink:href", el.attrib.pop(HREF))
            xlink = True
    attrs = dict(root.attrib)
    root.attrib.clear()
    root.set("xmlns", SVG_NS)
    if xlink:
        root.set("xmlns:xlink", XLINK_NS)
    root.attrib.update(attrs)
    body = ET.tostring(root, encoding="unicode")
    return ('<?xml version="1.0" encoding="utf-8" standalone="no"?>\n' + body + "\n").encode("utf-8")
