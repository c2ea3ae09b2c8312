"""The note's figures drawn into the PDF from precompiled operators, not by WeasyPrint's SVG renderer.

WeasyPrint draws an SVG image node by node when it writes the PDF: for every element it
cascades the styles again (tinycss2 parses each ``style`` attribute, cssselect2 matches the
sheet), parses the path data number by number (``svg/utils.size``) and calls the stream's
methods one operator at a time. A figure of the note is drawn the same way in every layout
pass and every build, though it never changes.

:func:`compile_svg` reads a figure once — exactly the restricted SVG that matplotlib writes
after :func:`reportgen.style.svgslim.slim` (``<path>``, ``<g>``, ``<rect>``, ``<clipPath>``, one
``*{…}`` style sheet; absolute ``M L Q C Z`` path data; ``translate``/``scale``/``rotate``/
``matrix`` transforms; colours, stroke width, dashes, caps, joins, miter limit, fill rule,
fill/stroke opacity and element ``opacity``) — and turns it into a short program: byte strings
of PDF operators (paths, line styles, colours) between the few calls whose output depends on
the stream at drawing time. :class:`FigureImage` runs the program through the stream's own
methods (``push_state``/``pop_state``, ``transform``, ``set_alpha``, ``set_color``,
``add_group``), so graphics-state resources (ExtGState for alpha, transparency groups) are
registered by WeasyPrint itself, and the current transformation matrix is tracked as
WeasyPrint tracks it (a clip path's compensating ``cm`` is computed from it, as
``SVG.draw_node`` does).

The program is built by replaying WeasyPrint 70's ``SVG.draw_node`` (``weasyprint/svg/
__init__.py``) for this subset step by step: the same operators in the same order with the
same numbers (pydyf's number format; quadratic segments raised to cubic ones with WeasyPrint's
formula; transforms from WeasyPrint's own ``svg.utils.transform``; the ``0 0 m`` every path
starts with; the transparency group's bounding box from ``svg.bounding_box``). A page drawn
through this module is therefore the same bytes as drawn by WeasyPrint (tests/
test_svg_pdf_ops.py compares the operators figure by figure, and whole PDFs).

Anything else — patterns (hatches), markers, gradients, images, text, ``<use>``, relative path
commands, units other than plain numbers, ``!important``, unknown attributes or properties —
makes :func:`compile_svg` return ``None``: the figure is left to WeasyPrint (never a wrong
drawing). :data:`STATS` counts compiled figures, fallbacks and draws.

Hook: :func:`prime` puts a :class:`FigureImage` into WeasyPrint's image cache (``render.
_image_cache``, keyed by the image's ``data:`` URL) for every figure of an HTML document
before it is laid out; WeasyPrint's ``images.get_image_from_uri`` returns the cached object
and never parses the SVG. The cache belongs to the process, so a forked layout worker or a
batch worker compiles each figure once.
"""
from __future__ import annotations

import base64
import os
import re
import xml.etree.ElementTree as ET
from collections import Counter
from math import cos, hypot, sin, sqrt

__all__ = ["ENABLED", "FigureImage", "STATS", "compile_svg", "prime"]

#: counters: ``compiled`` figures, ``fallback`` (left to WeasyPrint), ``drawn`` (draw calls)
STATS: Counter = Counter()
#: ``False``: :func:`prime` does nothing, every figure is drawn by WeasyPrint (tests; for a
#: benchmark of the CLI the environment variable ``REPORTGEN_SVGOPS=0`` sets it)
ENABLED = os.environ.get("REPORTGEN_SVGOPS", "1") != "0"

_NS = "{http://www.w3.org/2000/svg}"
_DATA_SVG = re.compile(r"data:image/svg\+xml;base64,[A-Za-z0-9+/=]+")

# attributes WeasyPrint does not pass from parent to child (svg/__init__.py NOT_INHERITED_ATTRIBUTES)
_NOT_INHERITED = frozenset((
    "clip", "clip-path", "filter", "height", "id", "mask", "opacity", "overflow", "rotate",
    "stop-color", "stop-opacity", "style", "transform", "transform-origin", "viewBox", "width",
    "x", "y", "dx", "dy", "{http://www.w3.org/1999/xlink}href", "href"))
# presentation attributes and properties whose effect is replayed here; anything else: fallback
_PAINT_KEYS = frozenset((
    "fill", "stroke", "stroke-width", "stroke-dasharray", "stroke-dashoffset", "stroke-linecap",
    "stroke-linejoin", "stroke-miterlimit", "stroke-opacity", "fill-opacity", "fill-rule",
    "opacity", "clip-path"))
_ELEMENT_KEYS = {
    "svg": frozenset(("width", "height", "viewBox", "version")),
    "g": frozenset(("id", "style", "transform")) | _PAINT_KEYS,
    "path": frozenset(("id", "style", "transform", "d")) | _PAINT_KEYS,
    "rect": frozenset(("id", "style", "transform", "x", "y", "width", "height")) | _PAINT_KEYS,
    "defs": frozenset(("id",)),
    "pattern": frozenset(("id", "patternUnits", "x", "y", "width", "height")),
}
_VALUE_OK = re.compile(r"[#\w.,%() +-]*\Z")
_STYLE_SHEET = re.compile(r"\s*\*\s*\{([^{}]*)\}\s*\Z")

_PATH_OK = re.compile(r"[\sMLQCZz0-9.eE+,-]*\Z")
_COMMAND = re.compile(r"([MLQCZz])([^MLQCZz]*)")
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_SEPARATORS = re.compile(r"[\s,]*\Z")
_ARITY = {"M": 2, "L": 2, "C": 6, "Q": 4, "Z": 0, "z": 0}
# a number as pydyf writes float(token): the token itself when it is already in that form
_CANONICAL = re.compile(r"(?!-0\Z)-?(?:0|[1-9]\d{0,8})(?:\.\d{0,5}[1-9])?\Z")

# program operations
_RAW, _PUSH, _POP, _CM, _ALPHA, _COLOR, _CLIP, _GROUP, _END_GROUP, _ROOT, _PATTERN = range(11)


def _is_valid(box) -> bool:
    """``svg/bounding_box.py`` ``is_valid_bounding_box``."""
    from weasyprint.svg.bounding_box import is_valid_bounding_box

    return bool(is_valid_bounding_box(box))


def _matmul(m, n):
    """``weasyprint.matrix.Matrix.__matmul__`` on tuples: the same sums (``sum`` starts at 0)."""
    return tuple(tuple(0 + m[i][0] * n[0][j] + m[i][1] * n[1][j] + m[i][2] * n[2][j] for j in range(3))
                 for i in range(3))


def _mat(a=1, b=0, c=0, d=1, e=0, f=0):
    return ((a, b, 0), (c, d, 0), (e, f, 1))


def _determinant(m) -> float:
    """``Matrix.determinant``."""
    return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[1][0] * (m[0][1] * m[2][2] - m[0][2] * m[2][1])
            + m[2][0] * (m[0][1] * m[1][2] - m[0][2] * m[1][1]))


def _transform_values(text: str, font_size: float, diagonal: float) -> tuple | None:
    """``svg/utils.py`` ``transform(text, None, …)`` for translate, scale, rotate and matrix,
    with the same operations in the same order; its six values, ``None`` if it is singular."""
    from weasyprint.svg.utils import angle, normalize, size

    m = _mat(e=0, f=0)
    for kind, args in re.findall(r"(\w+) ?\( ?(.*?) ?\)", normalize(text)):
        values = [v for v in args.split(" ") if v]
        if kind == "matrix":
            m = _matmul(_mat(*[size(v, font_size, diagonal) for v in values]), m)
        elif kind == "rotate":
            if len(values) != 1:
                raise _Unsupported("rotate about a point")
            r = angle(values[0])
            cos_r, sin_r = cos(r), sin(r)
            m = _matmul(_mat(cos_r, sin_r, -sin_r, cos_r), m)
        elif kind == "translate":
            values = [size(v, font_size, diagonal) for v in values]
            if len(values) == 1:
                values.append(0)
            m = _matmul(_mat(e=values.pop(0)), m)
            m = _matmul(_mat(f=values.pop(0)), m)
        elif kind == "scale":
            values = [size(v, font_size, diagonal) for v in values]
            if len(values) == 1:
                values.append(values[0])
            m = _matmul(_mat(a=values.pop(0)), m)
            m = _matmul(_mat(d=values.pop(0)), m)
        else:
            raise _Unsupported("transform")
    m = _matmul(_mat(e=-0, f=-0), m)
    if not _determinant(m):
        return None
    (a, b), (c, d), (e, f) = [row[:2] for row in m]
    return a, b, c, d, e, f


class _Unsupported(Exception):
    """A construct this module does not replay: the figure goes to WeasyPrint."""


def _num(v) -> str:
    """``v`` as pydyf writes a number (``pydyf._to_bytes``)."""
    if isinstance(v, float):
        if v.is_integer():
            return str(int(v))
        return f"{v:f}".rstrip("0")
    return str(v)


_TOKENS: dict[str, str] = {}
# what WeasyPrint's helpers give for a value, kept for the process (a few hundred entries)
_LENGTHS: dict = {}
_TRANSFORMS: dict = {}
_COLORS: dict = {}
_PATHS: dict = {}  # path data -> operators (a text's path is the same in every figure showing it)


def _tok(t: str) -> str:
    """A path-data number as WeasyPrint writes it: ``float(t)`` in pydyf's format."""
    s = _TOKENS.get(t)
    if s is None:
        if len(_TOKENS) > 500_000:
            _TOKENS.clear()
        s = _TOKENS[t] = t if _CANONICAL.match(t) else _num(float(t))
    return s


_N = r"(?!-0(?![.\d]))-?(?:0|[1-9]\d{0,8})(?:\.\d{0,5}[1-9])?(?![\d.])"
# subpaths of M, L, Q, C (one set of numbers each, already as pydyf writes them) and Z after a
# drawing command
_SIMPLE = re.compile(rf"(?:\s*M\s*{_N}\s+{_N}(?:\s*(?:L\s*{_N}\s+{_N}|Q\s*{_N}(?:\s+{_N}){{3}}"
                     rf"|C\s*{_N}(?:\s+{_N}){{5}}|z))*)*\s*\Z")
_NO_CLOSE = re.compile(rf"M\s*{_N}\s+{_N}\s*z|z\s*z")  # a Z that draws nothing
_LETTER = re.compile(r"[MLQCz]")
_OPS = {"M": "%s %s m", "L": "%s %s l", "Q": "%s %s %s %s %s %s c", "C": "%s %s %s %s %s %s c", "z": "h"}
_ARGS_IN = bytearray(256)
_ARGS_OUT = bytearray(256)
for _c, _i, _o in (("M", 2, 2), ("L", 2, 2), ("Q", 4, 6), ("C", 6, 6)):
    _ARGS_IN[ord(_c)], _ARGS_OUT[ord(_c)] = _i, _o


def _nums(values) -> list:
    """Floats as pydyf writes them, all at once: ``str(int(v))`` for whole numbers, else
    ``f"{v:f}"`` without its trailing zeros."""
    import numpy as np

    t = tuple((values + 0.0).tolist())
    frac = np.char.rstrip(np.array(("%f " * len(t) % t).split()), "0")
    return np.where(values == np.floor(values), ("%.0f " * len(t) % t).split(), frac).tolist()


def _simple_path_ops(d: str) -> str:
    """``path()``'s operators for data :data:`_SIMPLE` accepts (see :func:`_simple_paths_ops`)."""
    if "Q" not in d:
        return "\n".join(["0 0 m", *map(_OPS.__getitem__, _LETTER.findall(d))]) % tuple(_NUMBER.findall(d))
    return _simple_paths_ops([d])[0]


def _simple_paths_ops(paths: list[str]) -> list[str]:
    """``path()``'s operators for path data :data:`_SIMPLE` accepts, all at once: the numbers of
    M, L, C and of a Q's end point as written, a Q's cubic control points computed for all the
    Qs of all the paths together (WeasyPrint's ``x2 * 2 / 3 + x1 / 3``: the same IEEE operations
    in the same order; every path starts with M, so a Q's start never comes from another path)."""
    import numpy as np

    letters = [_LETTER.findall(d) for d in paths]
    tokens = [t for d in paths for t in _NUMBER.findall(d)]
    codes = np.frombuffer("".join("".join(x) for x in letters).encode("ascii"), np.uint8)
    n_in = np.frombuffer(bytes(_ARGS_IN), np.uint8)[codes].astype(np.intp)
    n_out = np.frombuffer(bytes(_ARGS_OUT), np.uint8)[codes].astype(np.intp)
    start_in = np.cumsum(n_in) - n_in
    start_out = np.cumsum(n_out) - n_out
    # the current point after each command: its last pair; after Z the subpath's first point
    end = start_in + n_in - 2
    idx = np.arange(len(codes))
    last_move = np.maximum.accumulate(np.where(codes == ord("M"), idx, 0))
    closes = codes == ord("z")
    end[closes] = start_in[last_move[closes]]
    values = np.array(tokens, dtype=float)
    q = np.flatnonzero(codes == ord("Q"))
    before, s = end[q - 1], start_in[q]
    x1, y1 = values[before], values[before + 1]
    x2, y2, x3, y3 = values[s], values[s + 1], values[s + 2], values[s + 3]
    control = np.stack([x2 * 2 / 3 + x1 / 3, y2 * 2 / 3 + y1 / 3,
                        x2 * 2 / 3 + x3 / 3, y2 * 2 / 3 + y3 / 3], axis=1).ravel()
    out = np.empty(int(n_out.sum()), dtype=object)
    owner = np.repeat(idx, n_in)
    offset = np.arange(len(tokens)) - start_in[owner]
    is_q = codes[owner] == ord("Q")
    keep = ~is_q | (offset >= 2)
    out[(start_out[owner] + offset + np.where(is_q, 2, 0))[keep]] = np.array(tokens, dtype=object)[keep]
    out[(start_out[q][:, None] + np.arange(4)).ravel()] = _nums(control)
    out = out.tolist()
    result, at = [], 0
    for path_letters in letters:
        n = sum(_ARGS_OUT[ord(c)] for c in path_letters)
        result.append("\n".join(["0 0 m", *map(_OPS.__getitem__, path_letters)]) % tuple(out[at:at + n]))
        at += n
    return result


def _prepare_paths(root: ET.Element) -> None:
    """Operators of the document's paths with quadratic segments (its texts), computed together
    into :data:`_PATHS` (one pass of array operations instead of one per text)."""
    todo = []
    for el in root.iter(_NS + "path"):
        d = el.get("d", "")
        if "Q" in d and d not in _PATHS and _SIMPLE.match(d) and not _NO_CLOSE.search(d):
            todo.append(d)
    todo = list(dict.fromkeys(todo))
    if not todo:
        return
    if len(_PATHS) + len(todo) > 2000:
        _PATHS.clear()
    _PATHS.update(zip(todo, _simple_paths_ops(todo)))


def _path_ops(d: str, out: list[str]) -> None:
    """The operators of ``svg/path.py``'s ``path()`` for absolute ``M L Q C Z`` data, appended
    to ``out`` (the ``0 0 m`` WeasyPrint starts every path with included)."""
    ops = _PATHS.get(d)
    if ops is None and _SIMPLE.match(d) and not _NO_CLOSE.search(d):
        if len(_PATHS) > 2000:
            _PATHS.clear()
        ops = _PATHS[d] = _simple_path_ops(d)
    if ops is not None:
        out.append(ops)
        return
    if not _PATH_OK.match(d):
        raise _Unsupported("path data")
    out.append("0 0 m")
    cur = (0, 0)  # WeasyPrint's current point (numbers as float() reads them; ints at first)
    first = None
    last = None
    for letter, args in _COMMAND.findall(d):
        nums = _NUMBER.findall(args)
        if not _SEPARATORS.match(_NUMBER.sub("", args)):
            raise _Unsupported("path numbers")
        k = _ARITY[letter]
        if k == 0:
            if nums:
                raise _Unsupported("numbers after Z")
            groups = ((letter, ()),)
        else:
            if not nums or len(nums) % k:
                raise _Unsupported("path arity")
            groups = [("L" if i and letter == "M" else letter, nums[i:i + k])
                      for i in range(0, len(nums), k)]
        for lt, g in groups:
            if last in (None, "z", "Z") and lt != "M":
                first = cur
            if last in (None, "M", "z", "Z"):
                first = None
            if lt not in "MZz" and first is None:
                first = cur
            if lt == "L":
                out.append(f"{_tok(g[0])} {_tok(g[1])} l")
                cur = g
            elif lt == "Q":
                x1, y1 = float(cur[0]), float(cur[1])
                x2, y2, x3, y3 = float(g[0]), float(g[1]), float(g[2]), float(g[3])
                out.append(f"{_num(x2 * 2 / 3 + x1 / 3)} {_num(y2 * 2 / 3 + y1 / 3)} "
                           f"{_num(x2 * 2 / 3 + x3 / 3)} {_num(y2 * 2 / 3 + y3 / 3)} "
                           f"{_tok(g[2])} {_tok(g[3])} c")
                cur = g[2:]
            elif lt == "M":
                out.append(f"{_tok(g[0])} {_tok(g[1])} m")
                cur = g
            elif lt == "C":
                out.append(" ".join(map(_tok, g)) + " c")
                cur = g[4:]
            elif first:  # Z after a drawing command: close, back to the subpath's start
                out.append("h")
                cur = first
            last = lt


_STYLES: dict = {}


def _style(text: str) -> list[tuple[str, str]]:
    """:func:`_parse_style`, kept for the process."""
    out = _STYLES.get(text)
    if out is None:
        if len(_STYLES) > 5000:
            _STYLES.clear()
        out = _STYLES[text] = _parse_style(text)
    return out


def _parse_style(text: str) -> list[tuple[str, str]]:
    """Declarations of a ``style`` attribute or rule as WeasyPrint's ``parse_declarations``
    gives them (lower-case names, stripped values; names starting with ``-`` dropped), for the
    plain values matplotlib writes; anything else raises :class:`_Unsupported`."""
    out = []
    if "!" in text or "/*" in text or "\\" in text or '"' in text or "'" in text:
        raise _Unsupported("style syntax")
    for decl in text.split(";"):
        if not decl.strip():
            continue
        if ":" not in decl:
            raise _Unsupported("style declaration")
        name, value = decl.split(":", 1)
        name, value = name.strip().lower(), value.strip()
        if not re.fullmatch(r"[a-z-]+", name):
            raise _Unsupported("style name")
        if name.startswith("-"):
            continue
        if not _VALUE_OK.match(value):
            raise _Unsupported("style value")
        out.append((name, value))
    return out


class _Compiler:
    """Replays ``SVG.draw_node`` for one document, writing the program."""

    def __init__(self, root: ET.Element):
        from weasyprint.svg.utils import normalize, size

        self.size = size
        if root.tag != _NS + "svg":
            raise _Unsupported("root")
        self.ids: dict[str, ET.Element] = {}
        self.sheet: list[tuple[str, str]] = []
        for el in root.iter():
            if not isinstance(el.tag, str) or not el.tag.startswith(_NS):
                raise _Unsupported("namespace")
            eid = el.get("id")
            if eid is not None and eid not in self.ids:
                self.ids[eid] = el
            if el.tag == _NS + "style":
                if el.get("type", "text/css") != "text/css" or len(el):
                    raise _Unsupported("style element")
                if el.text:
                    m = _STYLE_SHEET.match(el.text)
                    if not m:
                        raise _Unsupported("style sheet")
                    self.sheet.extend(_style(m.group(1)))
        for key in root.attrib:
            if key not in _ELEMENT_KEYS["svg"]:
                raise _Unsupported(f"svg attribute {key}")
        self.root = root
        _prepare_paths(root)
        attrib = self.cascade(root, {})
        viewbox = attrib.get("viewBox")
        self.viewbox = tuple(float(n) for n in normalize(viewbox).split()) if viewbox else None
        if self.viewbox is None or len(self.viewbox) != 4:
            raise _Unsupported("viewBox")
        self.width, self.height = attrib.get("width", "100%"), attrib.get("height", "100%")
        self.inner_width, self.inner_height = self.viewbox[2], self.viewbox[3]
        self.inner_diagonal = hypot(self.inner_width, self.inner_height) / sqrt(2)
        self.font_size = size("12pt")
        self.program: list = []
        self.raw: list[str] = []
        self.popped = [False]  # per target stream: whether a pop_state reset its colour state
        self.patterns: dict[str, list] = {}
        self.cascaded: dict = {}
        self.states: dict = {}
        self.parents: list = []
        self.parent_of = {ch: el for el in root.iter() for ch in el}
        self.root_attrib = attrib

    # -- program writing
    def flush(self) -> None:
        if self.raw:
            self.program.append((_RAW, "\n".join(self.raw).encode("ascii")))
            self.raw = []

    def op(self, *item) -> None:
        self.flush()
        self.program.append(item)

    # -- cascade (svg/__init__.py Node.cascade)
    def cascade(self, el: ET.Element, parent: dict) -> dict:
        tag = el.tag[len(_NS):]
        attrib = dict(el.attrib)
        for key, value in parent.items():
            if key not in _NOT_INHERITED and key not in attrib:
                attrib[key] = value
        for name, value in self.sheet:
            attrib[name] = value
        if style := attrib.get("style"):
            for name, value in _style(style):
                attrib[name] = value
        keys = _ELEMENT_KEYS[tag]
        for key in el.attrib:
            if key not in keys:
                raise _Unsupported(f"{tag} attribute {key}")
        for name, _ in self.sheet + (_style(style) if style else []):
            if name not in _PAINT_KEYS:
                raise _Unsupported(f"property {name}")
        for key in ("fill", "stroke"):
            if attrib.get(key) in ("currentColor", "inherit"):
                raise _Unsupported("currentColor/inherit")
        if "inherit" in attrib.values():
            raise _Unsupported("inherit")
        return attrib

    def length(self, value) -> float:
        key = (value, self.inner_diagonal)
        v = _LENGTHS.get(key)
        if v is None:
            v = _LENGTHS[key] = self.size(value, self.font_size, self.inner_diagonal)
        return v

    # -- drawing
    def compile(self) -> list:
        self.op(_PUSH)
        self.op(_ROOT)
        for child in self.root:
            self.node(child, self.root_attrib)
        self.op(_POP)
        return self.program

    def node(self, el: ET.Element, parent: dict) -> None:
        tag = el.tag[len(_NS):]
        if tag == "defs":
            return
        if tag not in ("g", "path", "rect"):
            raise _Unsupported(f"element {tag}")
        # elements alike (same parent, same attributes but the path data and transform) cascade
        # alike and set the same graphics state: both are kept for the document
        own = el.attrib
        key = (id(parent), tag, "d" in own, "transform" in own,
               tuple(kv for kv in own.items() if kv[0] != "d" and kv[0] != "transform"))
        base = self.cascaded.get(key)
        if base is None:
            base = self.cascade(el, parent)
            base.pop("d", None)
            base.pop("transform", None)
            if base.get("display") == "none" or base.get("visibility") == "hidden":
                raise _Unsupported("display/visibility")
            self.cascaded[key] = base
            self.parents.append(parent)  # (its id stays its own while the document is compiled)
        attrib = dict(base)
        if "d" in own:
            attrib["d"] = own["d"]
        if "transform" in own:
            attrib["transform"] = own["transform"]
        self.op(_PUSH)
        self.transform(attrib)
        opacity = self.alpha(attrib.get("opacity", 1))
        grouped = 0 <= opacity < 1
        if grouped:
            if tag == "g":
                raise _Unsupported("group opacity")
            self.op(_GROUP)
            self.popped.append(False)
        if tag != "g":
            state_key = (key, self.popped[-1], grouped)
            state = self.states.get(state_key)
            if state is None:
                self.flush()
                start = len(self.program)
                fill, stroke = self.graphical_state(tag, attrib)
                self.clip(attrib)
                state = (fill, stroke, self.program[start:], list(self.raw))
                if "url(" not in attrib.get("fill", ""):
                    self.states[state_key] = state  # (a pattern is placed at the shape's box)
            else:
                self.flush()
                self.program.extend(state[2])
                self.raw.extend(state[3])
            fill, stroke = state[0], state[1]
        else:
            self.clip(attrib)
        if tag == "path":
            _path_ops(attrib.get("d", ""), self.raw)
        elif tag == "rect":
            self.rect(attrib)
        else:
            for child in el:
                self.node(child, attrib)
        if tag != "g":
            even_odd = attrib.get("fill-rule") == "evenodd"
            if fill and stroke:
                self.raw.append("B*" if even_odd else "B")
            elif stroke:
                self.raw.append("S")
            elif fill:
                self.raw.append("f*" if even_odd else "f")
            else:
                self.raw.append("n")
        if grouped:
            self.op(_END_GROUP, self.bounding_box(tag, attrib), opacity)
            self.popped.pop()
        self.op(_POP)
        self.popped[-1] = True

    @staticmethod
    def alpha(value) -> float:
        from weasyprint.svg.utils import alpha_value

        return alpha_value(value)

    def transform(self, attrib: dict) -> None:
        if text := attrib.get("transform"):
            if not re.fullmatch(r"(\s*(translate|scale|rotate|matrix)\s*\([-+\d.eE, ]*\)\s*,?)*\s*", text):
                raise _Unsupported("transform")
            key = (text, self.inner_diagonal)
            values = _TRANSFORMS.get(key, False)
            if values is False:
                if len(_TRANSFORMS) > 5000:
                    _TRANSFORMS.clear()
                values = _TRANSFORMS[key] = _transform_values(text, self.font_size, self.inner_diagonal)
            if values is not None:
                self.op(_CM, values)

    def paint(self, attrib: dict, key: str):
        value = attrib.get(key, "black" if key == "fill" else "").strip()
        if not value or value == "none":
            return None
        if value.startswith("context-"):
            raise _Unsupported("context paint")
        return value

    def pattern_fill(self, tag: str, attrib: dict, value: str, opacity: float) -> bool:
        """``draw_pattern`` (svg/defs.py) for a fill ``url(#id)`` of a ``userSpaceOnUse``
        ``<pattern>`` of rects and paths (matplotlib's hatches): the pattern's content compiled
        once, placed at drawing time by the stream's ``add_pattern`` at the shape's bounding
        box (without the stroke) times the current matrix. ``False``: WeasyPrint fills nothing."""
        from weasyprint.svg.utils import parse_url

        m = re.fullmatch(r"(url\(.+\)) *(.*)", value)
        if not m or m.group(2) or float(attrib.get("opacity", 1)) < 1:
            raise _Unsupported("paint server")
        name = parse_url(m.group(1)).fragment
        ref = self.ids.get(name)
        if ref is None or ref.tag != _NS + "pattern" or ref.get("patternUnits") != "userSpaceOnUse":
            raise _Unsupported("paint server")
        box = self.raw_box(tag, attrib)
        if not (_is_valid(box) and 0 not in box[2:]):
            return False
        width = self.size(ref.get("width", 0), self.font_size, 1)
        height = self.size(ref.get("height", 0), self.font_size, 1)
        if width == 0 or height == 0:
            return False
        if name not in self.patterns:
            self.patterns[name] = self.pattern_program(ref, width, height)
        self.op(_PATTERN, box[0], box[1], width, height, opacity, self.patterns[name])
        return True

    def pattern_program(self, ref: ET.Element, width: float, height: float) -> list:
        """The ops ``Pattern(pattern, svg).draw(group, width, height)`` writes into the
        pattern's group: the pattern as a nested ``<svg>`` clipped to its size, its children."""
        saved = self.program, self.raw, self.inner_width, self.inner_height, self.inner_diagonal
        self.program, self.raw = [], []
        self.inner_width, self.inner_height = width, height
        self.inner_diagonal = hypot(width, height) / sqrt(2)
        self.popped.append(False)
        try:
            parent = self.parent_of[ref]
            if parent.tag != _NS + "defs" or self.parent_of.get(parent) is not self.root:
                raise _Unsupported("pattern outside the top <defs>")
            defs = self.cascade(parent, self.root_attrib)
            attrib = self.cascade(ref, defs)
            size, fs = self.size, self.font_size
            self.op(_PUSH)
            self.op(_CM, (1, 0, 0, 1, size(attrib.get("x"), fs, width), size(attrib.get("y"), fs, height)))
            self.raw += [f"0 0 {_num(width)} {_num(height)} re", "W", "n"]
            self.op(_CM, (1, 0, 0, 1, 0, 0))
            for child in ref:
                self.node(child, attrib)
            self.op(_POP)
            return self.program
        finally:
            self.program, self.raw, self.inner_width, self.inner_height, self.inner_diagonal = saved
            self.popped.pop()

    def set_color(self, value: str, opacity: float, stroke: bool) -> None:
        from weasyprint.svg.utils import color

        key = (value, opacity, stroke)
        known = _COLORS.get(key)
        if known is None:
            c = color(value)
            c.alpha *= opacity
            if c.space != "srgb":
                raise _Unsupported("colour space")
            r, g, b = c.to("srgb").coordinates
            known = _COLORS[key] = (c, f"{_num(r)} {_num(g)} {_num(b)} {'RG' if stroke else 'rg'}")
        c, rgb = known
        if self.popped[-1]:  # the stream's colour state is reset: the operators are known
            self.op(_ALPHA, c.alpha, stroke)
            self.raw.append(rgb)
        else:  # first shape of the figure: the stream decides what it still has to set
            self.op(_COLOR, c, stroke)

    def graphical_state(self, tag: str, attrib: dict):
        """``SVG.set_graphical_state``: colours, width, dashes, cap, join, miter limit."""
        from weasyprint.svg.utils import normalize

        fill = self.paint(attrib, "fill")
        if fill and fill.startswith("url("):
            fill = self.pattern_fill(tag, attrib, fill, self.alpha(attrib.get("fill-opacity", 1)))
        elif fill:
            self.set_color(fill, self.alpha(attrib.get("fill-opacity", 1)), False)
        stroke = None
        if stroke_width := self.length(attrib.get("stroke-width", "1px")):
            stroke = self.paint(attrib, "stroke")
            if stroke and stroke.startswith("url("):
                raise _Unsupported("stroke paint server")
            if stroke:
                self.set_color(stroke, self.alpha(attrib.get("stroke-opacity", 1)), True)
                self.raw.append(f"{_num(stroke_width)} w")
        dash_array = tuple(self.length(v) for v in normalize(attrib.get("stroke-dasharray")).split()
                           if v != "none")
        if dash_array and not all(v == 0 for v in dash_array) and not any(v < 0 for v in dash_array):
            offset = self.length(attrib.get("stroke-dashoffset"))
            if offset < 0:
                total = sum(float(v) for v in dash_array)
                offset = total - abs(offset) % total
            self.raw.append("[" + " ".join(_num(v) for v in dash_array) + f"] {_num(offset)} d")
        else:
            self.raw.append("[] 0 d")
        cap = attrib.get("stroke-linecap", "butt")
        self.raw.append(f"{1 if cap == 'round' else 2 if cap == 'square' else 0} J")
        join = attrib.get("stroke-linejoin", "miter")
        self.raw.append(f"{1 if join == 'round' else 2 if join == 'bevel' else 0} j")
        miter = float(attrib.get("stroke-miterlimit", 4))
        if miter < 0:
            miter = 4
        self.raw.append(f"{_num(miter)} M")
        return fill, stroke

    def clip(self, attrib: dict) -> None:
        """A ``clip-path`` of ``<rect>``/``<path>`` children: their outlines, ``0 0 0 0 re W n``
        and WeasyPrint's compensating transform (computed at drawing time from the stream's CTM)."""
        from weasyprint.svg.utils import parse_url

        name = parse_url(attrib.get("clip-path")).fragment
        if not name:
            return
        ref = self.ids.get(name)
        if ref is None or "path" not in ref.tag[len(_NS):].lower():
            raise _Unsupported("clip reference")
        if ref.tag != _NS + "clipPath" or set(ref.attrib) - {"id"}:
            raise _Unsupported("clip path element")
        ops: list[str] = []
        for child in ref:
            tag = child.tag[len(_NS):]
            if tag == "rect" and not set(child.attrib) - {"x", "y", "width", "height"}:
                self.rect(child.attrib, ops)
            elif tag == "path" and not set(child.attrib) - {"d"}:
                _path_ops(child.get("d", ""), ops)
            else:
                raise _Unsupported("clip path child")
        ops += ["0 0 0 0 re", "W", "n"]
        self.op(_CLIP, "\n".join(ops).encode("ascii"))

    def rect(self, attrib: dict, out: list | None = None) -> None:
        """``svg/shapes.py`` ``rect()`` without rounded corners."""
        if attrib.get("rx") or attrib.get("ry"):
            raise _Unsupported("rounded rect")
        size, fs = self.size, self.font_size
        width = size(attrib.get("width"), fs, self.inner_width)
        height = size(attrib.get("height"), fs, self.inner_height)
        if width <= 0 or height <= 0:
            return
        x = size(attrib.get("x"), fs, self.inner_width)
        y = size(attrib.get("y"), fs, self.inner_height)
        (self.raw if out is None else out).append(f"{_num(x)} {_num(y)} {_num(width)} {_num(height)} re")

    def raw_box(self, tag: str, attrib: dict) -> tuple:
        """``svg/bounding_box.py`` ``bounding_box(…, stroke=False)`` of a path or rect."""
        from weasyprint.svg.bounding_box import EMPTY_BOUNDING_BOX, extend_bounding_box

        box = EMPTY_BOUNDING_BOX
        if tag == "rect":
            size, fs = self.size, self.font_size
            box = (size(attrib.get("x"), fs, self.inner_width), size(attrib.get("y"), fs, self.inner_height),
                   size(attrib.get("width"), fs, self.inner_width),
                   size(attrib.get("height"), fs, self.inner_height))
        else:
            for letter, args in _COMMAND.findall(attrib.get("d", "")):
                nums = [float(t) for t in _NUMBER.findall(args)]
                k = _ARITY[letter]
                for i in range(0, len(nums), max(k, 1)):
                    g = nums[i:i + k]
                    if letter == "C":
                        box = extend_bounding_box(box, ((g[0], g[1]), (g[2], g[3]), (g[4], g[5])))
                    elif letter == "Q":
                        box = extend_bounding_box(box, ((g[0], g[1]), (g[2], g[3])))
                    elif k:
                        box = extend_bounding_box(box, ((g[0], g[1]),))
        return box if _is_valid(box) else EMPTY_BOUNDING_BOX

    def bounding_box(self, tag: str, attrib: dict) -> tuple:
        """``SVG.calculate_bounding_box(node, stroke=True)`` for a path or rect, as the
        transparency group's BBox (x0, y0, x1, y1); the viewBox when it is not valid."""
        box = self.raw_box(tag, attrib)
        if _is_valid(box) and self.paint(attrib, "stroke"):
            sw = self.length(attrib.get("stroke-width", "1px"))
            box = (box[0] - sw / 2, box[1] - sw / 2, box[2] + sw, box[3] + sw)
        if not (_is_valid(box) and 0 not in box[2:]):
            box = (0, 0, self.inner_width, self.inner_height)
        x, y, w, h = box
        return x, y, x + w, y + h


class FigureImage:
    """A compiled figure with WeasyPrint's image interface (``get_intrinsic_size``, ``draw``)."""

    def __init__(self, width: str, height: str, viewbox: tuple, program: list):
        self._width, self._height = width, height
        self._viewbox = viewbox
        self._program = program

    def get_intrinsic_size(self, image_resolution, font_size):
        """``SVGImage.get_intrinsic_size`` (the image resolution does not apply to SVG)."""
        from weasyprint.svg.utils import size

        width = None if "%" in self._width else size(self._width, font_size)
        height = None if "%" in self._height else size(self._height, font_size)
        if None in (width, height):
            vb = self._viewbox
            ratio = None
            if vb[2] and vb[3]:
                ratio = vb[2] / vb[3]
                if width:
                    height = width / ratio
                elif height:
                    width = height * ratio
        elif width and height:
            ratio = width / height
        else:
            ratio = 1
        return width, height, ratio

    def _root_transform(self, width: float, height: float) -> tuple:
        """``preserve_ratio`` of the root ``<svg>`` (viewBox, default ``xMidYMid meet``)."""
        vb = self._viewbox
        vw, vh = vb[2], vb[3]
        scale_x = width / vw if vw else 1
        scale_y = height / vh if vh else 1
        scale_x = scale_y = min(scale_x, scale_y)
        translate_x = (width - vw * scale_x) / 2
        translate_y = 0
        translate_y += (height - vh * scale_y) / 2
        translate_x -= vb[0] * scale_x
        translate_y -= vb[1] * scale_y
        return scale_x, scale_y, translate_x, translate_y

    def draw(self, stream, concrete_width, concrete_height, style):
        STATS["drawn"] += 1
        self._run(stream, self._program, concrete_width, concrete_height, {})

    def _run(self, stream, program, concrete_width, concrete_height, comp_memo) -> None:
        streams = []
        for item in program:
            op = item[0]
            if op == _RAW:
                stream.stream.append(item[1])
            elif op == _PUSH:
                stream.push_state()
            elif op == _POP:
                stream.pop_state()
            elif op == _ALPHA:
                stream.set_alpha(item[1], item[2])
            elif op == _CLIP:
                old = stream.ctm
                stream.stream.append(item[1])
                if old.determinant:
                    key = tuple(old[0] + old[1] + old[2])
                    values = comp_memo.get(key)
                    if values is None:
                        values = comp_memo[key] = (old @ old.invert).values
                    stream.transform(*values)
            elif op == _CM:
                stream.transform(*item[1])
            elif op == _COLOR:
                stream.set_color(item[1], item[2])
            elif op == _GROUP:
                streams.append(stream)
                stream = stream.add_group(0, 0, 0, 0)
            elif op == _END_GROUP:
                stream.extra["BBox"][:] = item[1]
                group_id = stream.id
                stream = streams.pop()
                stream.set_alpha(item[2], stroke=True, fill=True)
                stream.draw_x_object(group_id)
            elif op == _PATTERN:
                from weasyprint.matrix import Matrix

                _, x, y, width, height, opacity, content = item
                pattern = stream.add_pattern(0, 0, width, height, width, height,
                                             Matrix(e=x, f=y) @ stream.ctm)
                pattern.set_alpha(opacity)
                group = pattern.add_group(0, 0, width, height)
                self._run(group, content, width, height, {})
                pattern.draw_x_object(group.id)
                stream.set_color_space("Pattern", stroke=False)
                stream.set_color_special(pattern.id, stroke=False)
            elif op == _ROOT:
                stream.transform(e=0, f=0)
                sx, sy, tx, ty = self._root_transform(concrete_width, concrete_height)
                stream.transform(a=sx, d=sy, e=tx, f=ty)


def compile_svg(data: bytes) -> FigureImage | None:
    """The figure as a :class:`FigureImage`, or ``None`` if it holds anything this module does
    not replay exactly (WeasyPrint then draws it)."""
    try:
        root = ET.fromstring(data)
        c = _Compiler(root)
        program = c.compile()
    except Exception:  # noqa: BLE001 - whatever is not replayed exactly goes to WeasyPrint
        STATS["fallback"] += 1
        return None
    STATS["compiled"] += 1
    return FigureImage(c.width, c.height, c.viewbox, program)


def prime(cache, html: str) -> None:
    """Put a :class:`FigureImage` into WeasyPrint's image ``cache`` for every SVG ``data:`` URL
    of ``html`` not in it yet that :func:`compile_svg` can compile (the others WeasyPrint
    parses as usual and keeps in the same cache, so each URL is tried once)."""
    if not ENABLED:
        return
    for url in dict.fromkeys(_DATA_SVG.findall(html)):
        if url in cache:
            continue
        image = compile_svg(base64.b64decode(url[26:]))
        if image is not None:
            cache[url] = image
