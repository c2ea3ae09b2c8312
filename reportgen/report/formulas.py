"""Formulas of the note: typeset as HTML text by :mod:`reportgen.report.mathhtml`, or
rendered to SVG in Python with ziamath (WeasyPrint has no MathML/JS) when the HTML
typesetter does not handle a construct (see :data:`fallbacks`).

A :class:`Formula` is one numbered display line in the Mathcad style that
students know: ``symbolic = substituted = result``, for example::

    Formula(
        symbolic=r"\\omega_1 = \\frac{\\pi n_1}{30}",
        substituted=r"\\frac{3{,}1416 \\cdot 65}{30}",
        result=r"6{,}807\\ \\text{рад/с}",
        where=[(r"n_1", "частота вращения кривошипа, об/мин")],
        label="eq-omega1",
    )

Numbers inside the LaTeX should come from :func:`reportgen.style.numbers.tex_num`
so that they match the tables. Formula numbers «(2.1)» are not drawn by
ziamath: the report numbers formulas itself (so that references work).

Sizes: every SVG is rendered at :data:`REF_PX` and placed in the page in
``em`` of the surrounding text, scaled by :data:`MATH_SCALE` (STIX Two Math
looks about 7 % larger than Liberation Serif at the same size). Hence formulas
follow the font-size option of the report automatically.
"""

from __future__ import annotations

import base64
import functools
import hashlib
import os
import re
import tempfile
import warnings
from pathlib import Path
from dataclasses import dataclass, field

from markupsafe import Markup

from ..style import fonts

__all__ = [
    "Formula",
    "FormulaImage",
    "REF_PX",
    "MATH_SCALE",
    "render_latex",
    "inline_math",
    "formula_images",
    "data_uri",
    "where_rows",
]

REF_PX = 18.0  # size ziamath renders at (px)
MATH_SCALE = 0.93  # rendered formula size relative to the text size (em per REF_PX)

_configured = False


def _configure():
    """ziamath, imported on first use (a quarter of a second; most notes set every formula as
    text and never draw one) and configured once."""
    global _configured
    import ziamath as zm
    if _configured:
        return zm
    zm.config.svg2 = False  # plain paths: no <symbol>/<use> ids shared across formulas
    zm.config.decimal_separator = ","
    try:
        # Cyrillic inside \text{} in the same face as the body text.
        zm.config.text.textfont = str(fonts.find_serif().regular)
    except FileNotFoundError:  # pragma: no cover - falls back to STIX Two Math
        pass
    _configured = True
    return zm


@dataclass
class Formula:
    """One numbered display formula: symbolic = substituted = result."""

    symbolic: str
    substituted: str | None = None
    result: str | None = None
    where: list[tuple[str, str]] = field(default_factory=list)
    label: str | None = None

    def parts(self) -> list[str]:
        """The non-empty parts; a part starting with a minus is braced so the
        minus is unary after the inserted "="."""
        out = []
        for p in (self.symbolic, self.substituted, self.result):
            if p is None or not str(p).strip():
                continue
            p = str(p).strip()
            if p.startswith("-"):
                p = "{" + p + "}"
            out.append(p)
        return out

    def latex(self) -> str:
        """The whole line as one LaTeX string."""
        return " = ".join(self.parts())


@dataclass(frozen=True)
class FormulaImage:
    """A rendered piece of math, sized in em of the surrounding text."""

    svg: str
    width_em: float
    height_em: float
    depth_em: float  # baseline to the bottom of the image
    tex: str

    @property
    def src(self) -> str:
        return data_uri(self.svg)

    def scaled(self, max_width_em: float) -> "FormulaImage":
        if self.width_em <= max_width_em:
            return self
        k = max_width_em / self.width_em
        return FormulaImage(self.svg, max_width_em, self.height_em * k, self.depth_em * k, self.tex)

    def img(self, cls: str = "math") -> Markup:
        return Markup(
            '<img class="{cls}" alt="{alt}" src="{src}" style="width:{w:.3f}em;height:{h:.3f}em;'
            'vertical-align:-{d:.3f}em">'
        ).format(cls=cls, alt=self.tex, src=Markup(self.src), w=self.width_em,
                 h=self.height_em, d=self.depth_em)


def data_uri(svg: str | bytes) -> str:
    if isinstance(svg, str):
        svg = svg.encode("utf-8")
    return "data:image/svg+xml;base64," + base64.b64encode(svg).decode("ascii")


_VIEWBOX = re.compile(r'viewBox="([-\d.e]+) ([-\d.e]+) ([-\d.e]+) ([-\d.e]+)"')


# Rendering a formula with ziamath costs ~0.05–0.1 s; the SVG of a given LaTeX string never
# changes for a given ziamath version, so rendered formulas are kept on disk and shared by
# repeated builds and by the worker processes of a batch (REPORTGEN_CACHE, default
# ~/.cache/reportgen; REPORTGEN_CACHE=off disables it).
_CACHE_VERSION = 1


def _cache_dir() -> Path | None:
    root = os.environ.get("REPORTGEN_CACHE")
    if root and root.lower() == "off":
        return None
    base = Path(root) if root else Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "reportgen"
    return base / "formulas"


def _disk_get(key: str) -> str | None:
    d = _cache_dir()
    if d is None:
        return None
    try:
        return (d / key[:2] / f"{key}.svg").read_text(encoding="utf-8")
    except OSError:
        return None


def _disk_put(key: str, svg: str) -> None:
    d = _cache_dir()
    if d is None:
        return
    try:
        sub = d / key[:2]
        sub.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=sub, suffix=".tmp")
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(svg)
        os.replace(tmp, sub / f"{key}.svg")
    except OSError:
        pass  # a read-only home is no reason to fail a report


@functools.lru_cache(maxsize=4096)
def render_latex(tex: str, *, inline: bool = False, size: float | None = None
                 ) -> tuple[str, float, float, float]:
    """LaTeX → ``(svg_text, width_px, height_px, depth_px)``.

    ``depth_px`` is the distance from the baseline to the bottom of the image
    (for ``vertical-align``). Cached; ziamath with ``svg2=False`` and a decimal
    comma.
    """
    zm = _configure()
    size = size or REF_PX
    key = hashlib.sha256(repr((tex, inline, size, zm.__version__, _CACHE_VERSION)).encode()).hexdigest()
    svg = _disk_get(key)
    if svg is None:
        try:
            m = zm.Latex(tex, size=size, inline=inline)
            svg = m.svg()
        except Exception as exc:  # ziamath/latex2mathml raise many kinds
            raise ValueError(f"Не удалось отрисовать формулу {tex!r}: {exc}") from exc
        _disk_put(key, svg)
    match = _VIEWBOX.search(svg)
    if not match:  # pragma: no cover - ziamath always writes a viewBox
        raise ValueError(f"ziamath returned an SVG without viewBox for {tex!r}")
    _x0, y0, w, h = (float(v) for v in match.groups())
    depth = h + y0
    return svg, w, h, depth


def _image(tex: str, inline: bool = False) -> FormulaImage:
    svg, w, h, depth = render_latex(tex, inline=inline)
    k = MATH_SCALE / REF_PX
    return FormulaImage(svg, w * k, h * k, depth * k, tex)


# Formulas are typeset as HTML text (:mod:`reportgen.report.mathhtml`); one the typesetter
# cannot handle is drawn by ziamath instead, and its LaTeX is counted here (a test asserts that
# the notes of cases/ need none). REPORTGEN_MATH=svg draws every formula with ziamath (the
# former way, kept for comparison: bench and docs/performance.md).
fallbacks: dict[str, str] = {}


def _svg_only() -> bool:
    return os.environ.get("REPORTGEN_MATH", "").lower() == "svg"


_TYPESET_CACHE_VERSION = 1


@functools.lru_cache(maxsize=1)
def _typeset_salt() -> bytes:
    """What a typeset formula depends on besides its LaTeX: the typesetter's code (the bytes
    of ``mathhtml.py``), latex2mathml's version and the font files whose advance widths give
    its width."""
    import latex2mathml

    from . import mathhtml

    h = hashlib.sha256(f"{_TYPESET_CACHE_VERSION}|{latex2mathml.__version__}|".encode())
    h.update(Path(mathhtml.__file__).read_bytes())
    fam = fonts.find_serif()
    for face in (fam.regular, fam.italic):
        h.update(Path(face).read_bytes())
    return h.digest()


@functools.lru_cache(maxsize=4096)
def _typeset(tex: str, display: bool):
    """:func:`reportgen.report.mathhtml.convert`, kept in the cache folder too
    (``<cache>/mathhtml``): converting the formulas of a note is a large part of the first
    call of the print HTML in a fresh process (``bench/bench_html.py``) and gives the same markup and extent every time, so a cached formula
    changes no byte of the note. A missing or damaged entry is converted again."""
    import json

    from . import mathhtml

    d = _cache_dir()
    file = None
    if d is not None:
        key = hashlib.sha256(_typeset_salt() + repr((tex, display)).encode("utf-8")).hexdigest()
        file = d.parent / "mathhtml" / key[:2] / f"{key}.json"
        try:
            data = json.loads(file.read_text(encoding="utf-8"))
            if data["tex"] == tex and data["display"] == display:
                return mathhtml.MathHtml(Markup(data["html"]), mathhtml.Box(*map(float, data["box"])), tex)
        except (OSError, ValueError, KeyError, TypeError):
            pass
    out = mathhtml.convert(tex, display)  # raises Unsupported: nothing is kept
    if file is not None:
        b = out.box
        text = json.dumps({"tex": tex, "display": display, "html": str(out.html), "box": [b.w, b.h, b.d]},
                          ensure_ascii=False)
        try:
            file.parent.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(dir=file.parent, suffix=".tmp")
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                f.write(text)
            os.replace(tmp, file)
        except OSError:
            pass  # a read-only cache folder is no reason to fail a report
    return out


def _math(tex: str, inline: bool = False):
    """The formula as :class:`~reportgen.report.mathhtml.MathHtml`, or as a ziamath
    :class:`FormulaImage` when the HTML typesetter does not handle it (counted in
    :data:`fallbacks` with the reason)."""
    if not _svg_only():
        from . import mathhtml

        try:
            return _typeset(tex, not inline)
        except mathhtml.Unsupported as exc:
            if tex not in fallbacks:
                warnings.warn(f"Формула {tex!r} нарисована ziamath (картинкой), а не набрана текстом: {exc}",
                              RuntimeWarning, stacklevel=3)
            fallbacks[tex] = str(exc)
    return _image(tex, inline)


def inline_math(tex: str) -> Markup:
    """Math inside a paragraph, on the text baseline (HTML text, or an ``<img>``)."""
    return _math(tex, inline=True).img("math-inline")


def formula_images(formula: Formula, max_width_em: float) -> list:
    """The display line(s) of a formula that fit ``max_width_em`` (each a
    :class:`~reportgen.report.mathhtml.MathHtml` or a :class:`FormulaImage`: both have
    ``width_em``, ``tex``, ``scaled`` and ``img``).

    The whole line if it fits; otherwise it is broken after an equals sign,
    which is repeated at the start of the next line (ГОСТ 2.105):
    ``symbolic = substituted =`` / ``= result``, then one part per line.
    Whatever still does not fit is scaled down.
    """
    parts = formula.parts()
    whole = _math(" = ".join(parts))
    if whole.width_em <= max_width_em or len(parts) == 1:
        return [whole.scaled(max_width_em)]
    candidates: list[list[str]] = []
    if len(parts) == 3:
        candidates.append([f"{parts[0]} = {parts[1]} =", f"= {parts[2]}"])
    lines = [f"{parts[0]} ="] + [f"= {p} =" for p in parts[1:-1]] + [f"= {parts[-1]}"]
    candidates.append(lines)
    for cand in candidates:
        imgs = [_math(t) for t in cand]
        if all(i.width_em <= max_width_em for i in imgs):
            return imgs
    return [i.scaled(max_width_em) for i in imgs]


def where_rows(formula: Formula) -> list[tuple[Markup, Markup]]:
    """The «где» list: (symbol image, description) rows.

    Each description ends with «;», the last with «.», unless it already
    ends with punctuation.
    """
    rows = []
    n = len(formula.where)
    for i, (sym, desc) in enumerate(formula.where):
        text = str(desc).rstrip()
        if not text.endswith((";", ".", ":", ",")):
            text += "." if i == n - 1 else ";"
        # Descriptions are trusted HTML like paragraphs (may hold <sub>, &nbsp;).
        rows.append((inline_math(sym), Markup(text)))
    return rows
