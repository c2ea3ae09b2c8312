"""The report's serif font, found by file path (never by fontconfig name).

Preference order (docs/reporting.md §2.6):

1. Liberation Serif (Debian ``fonts-liberation2`` or ``fonts-liberation``),
   metric-compatible with Times New Roman, full Cyrillic and Greek;
2. STIXGeneral, bundled with matplotlib (Times-like, no apt needed);
3. DejaVu Serif, bundled with matplotlib.

The same files are used by WeasyPrint (``@font-face`` with a ``file://`` URL,
or a ``data:`` URL for the self-contained HTML), by matplotlib (registered with
its font manager, see :mod:`reportgen.report.mplstyle`) and by ziamath for
``\\text{…}``.
"""

from __future__ import annotations

import base64
import functools
import io
import logging
import os
import unicodedata
from dataclasses import dataclass
from pathlib import Path

__all__ = [
    "FontFamily",
    "CSS_FAMILY",
    "candidates",
    "find_serif",
    "missing_glyphs",
    "check_text",
    "font_face_css",
]

# The family name used in CSS; only this family appears in the stylesheets.
CSS_FAMILY = "Report Serif"

_FACES = ("regular", "bold", "italic", "bold_italic")


@dataclass(frozen=True)
class FontFamily:
    """Four TTF files of one family."""

    name: str
    regular: Path
    bold: Path
    italic: Path
    bold_italic: Path

    def faces(self) -> dict[str, Path]:
        return {face: getattr(self, face) for face in _FACES}


def _mpl_font_dir() -> Path | None:
    try:
        import matplotlib
    except ImportError:  # pragma: no cover - matplotlib is a dependency
        return None
    return Path(matplotlib.get_data_path()) / "fonts" / "ttf"


def candidates() -> list[FontFamily]:
    """All known serif families, in order of preference (existing or not)."""
    out = []
    for base in ("/usr/share/fonts/truetype/liberation2", "/usr/share/fonts/truetype/liberation"):
        b = Path(base)
        out.append(FontFamily(
            "Liberation Serif",
            b / "LiberationSerif-Regular.ttf",
            b / "LiberationSerif-Bold.ttf",
            b / "LiberationSerif-Italic.ttf",
            b / "LiberationSerif-BoldItalic.ttf",
        ))
    mpl = _mpl_font_dir()
    if mpl is not None:
        out.append(FontFamily(
            "STIXGeneral",
            mpl / "STIXGeneral.ttf",
            mpl / "STIXGeneralBol.ttf",
            mpl / "STIXGeneralItalic.ttf",
            mpl / "STIXGeneralBolIta.ttf",
        ))
        out.append(FontFamily(
            "DejaVu Serif",
            mpl / "DejaVuSerif.ttf",
            mpl / "DejaVuSerif-Bold.ttf",
            mpl / "DejaVuSerif-Italic.ttf",
            mpl / "DejaVuSerif-BoldItalic.ttf",
        ))
    return out


@functools.lru_cache(maxsize=None)
def find_serif(prefer: str | None = None) -> FontFamily:
    """The first available family (all four faces present).

    ``prefer`` is a family name ("Liberation Serif", "STIXGeneral",
    "DejaVu Serif"); the environment variable ``REPORTGEN_FONT`` does the same.
    """
    prefer = prefer or os.environ.get("REPORTGEN_FONT") or None
    fams = [f for f in candidates() if all(p.is_file() for p in f.faces().values())]
    if prefer:
        chosen = [f for f in fams if f.name.lower() == prefer.lower()]
        if not chosen:
            raise FileNotFoundError(f"Шрифт «{prefer}» не найден; доступны: "
                                    + ", ".join(f.name for f in fams))
        return chosen[0]
    if not fams:
        raise FileNotFoundError("Не найден ни один шрифт с засечками (Liberation Serif, "
                                "STIXGeneral, DejaVu Serif)")
    return fams[0]


@functools.lru_cache(maxsize=None)
def _cmap(path: Path) -> frozenset[int]:
    from fontTools.ttLib import TTFont

    with TTFont(str(path), lazy=True) as font:
        return frozenset(font.getBestCmap())


def _ignorable(ch: str) -> bool:
    # Control and format characters (soft hyphen, zero-width spaces, BOM),
    # line breaks and plain ASCII spaces are never drawn from the font.
    return unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp") or ch in " \t\r\n"


def missing_glyphs(text: str, family: FontFamily | None = None,
                   faces: tuple[str, ...] = _FACES, cmap=None) -> dict[str, list[str]]:
    """Characters of ``text`` missing from the given faces: ``{face: [chars]}``. ``cmap(path)``
    gives a face's code points (default :func:`_cmap`; the report passes one that keeps them
    in its cache folder)."""
    family = family or find_serif()
    chars = sorted({c for c in text if not _ignorable(c)})
    out: dict[str, list[str]] = {}
    for face in faces:
        cmap_ = (cmap or _cmap)(getattr(family, face))
        miss = [c for c in chars if ord(c) not in cmap_]
        if miss:
            out[face] = miss
    return out


def check_text(text: str, family: FontFamily | None = None, cmap=None) -> list[str]:
    """Characters of ``text`` absent from the regular face of the family and of the bundled
    symbols family (:func:`symbol_family`, which the note's stylesheets name second): those
    would be drawn by a fallback font of the host; empty when all are present."""
    missing = missing_glyphs(text, family, faces=("regular",), cmap=cmap).get("regular", [])
    symbols = symbol_family()
    if missing and symbols is not None:
        missing = missing_glyphs("".join(missing), symbols, faces=("regular",), cmap=cmap).get("regular", [])
    return missing


# Characters kept in the subset embedded into the self-contained HTML.
_SUBSET_RANGES = (
    (0x0020, 0x007E), (0x00A0, 0x017F), (0x0370, 0x03FF), (0x0400, 0x045F),
    (0x2000, 0x206F), (0x2070, 0x209F), (0x2100, 0x214F), (0x2190, 0x21FF),
    (0x2200, 0x22FF), (0x25A0, 0x25FF),
)


@functools.lru_cache(maxsize=None)
def _subset_woff(path: Path) -> bytes:
    """The font reduced to Latin, Cyrillic, Greek and common symbols, as WOFF.

    Deterministic: same input file → same bytes (no timestamps are updated).
    """
    from fontTools import subset
    from fontTools.ttLib import TTFont

    options = subset.Options()
    options.flavor = "woff"
    options.name_IDs = ["*"]
    options.notdef_outline = True
    options.hinting = False  # screen rendering only; halves the size
    options.recalc_timestamp = False
    logging.getLogger("fontTools.subset").setLevel(logging.ERROR)
    font = TTFont(str(path), recalcTimestamp=False)
    unicodes = [u for lo, hi in _SUBSET_RANGES for u in range(lo, hi + 1)]
    sub = subset.Subsetter(options)
    sub.populate(unicodes=unicodes)
    sub.subset(font)
    buf = io.BytesIO()
    font.flavor = "woff"
    font.save(buf)
    return buf.getvalue()


SYMBOLS_SUFFIX = " Symbols"


def symbol_family() -> FontFamily | None:
    """STIXGeneral (bundled with matplotlib): the second family of the note, for the few math
    symbols the body face lacks (∥, ⊥, ∓ in Liberation Serif), so that no glyph comes from
    whatever fontconfig finds on the machine."""
    stix = next((f for f in candidates() if f.name == "STIXGeneral" and f.regular.exists()), None)
    if stix is None:
        return None
    # its italic faces lack the operators; operators are upright anyway, so the upright faces
    # serve the italic styles too
    return FontFamily(stix.name, stix.regular, stix.bold, stix.regular, stix.bold)


def font_face_css(family: FontFamily | None = None, *, embed: bool = False,
                  css_family: str = CSS_FAMILY, woff=None) -> str:
    """``@font-face`` rules for the four faces.

    ``embed=False``: ``file://`` URLs (for WeasyPrint, which subsets itself);
    ``embed=True``: subset WOFF fonts as ``data:`` URLs (self-contained HTML), from
    ``woff(path)`` (default :func:`_subset_woff`; the report passes one that keeps the
    subsets in its cache folder).
    """
    family = family or find_serif()
    rules = []
    styles = {
        "regular": ("normal", "normal"),
        "bold": ("bold", "normal"),
        "italic": ("normal", "italic"),
        "bold_italic": ("bold", "italic"),
    }
    faces = [(css_family, family)]
    symbols = symbol_family()
    if symbols is not None and symbols.name != family.name:
        faces.append((css_family + SYMBOLS_SUFFIX, symbols))
    for (name, fam), (face, (weight, style)) in ((f, st) for f in faces for st in styles.items()):
        path = getattr(fam, face)
        if embed:
            data = base64.b64encode((woff or _subset_woff)(path)).decode("ascii")
            src = f'url("data:font/woff;base64,{data}") format("woff")'
        else:
            src = f'url("{path.resolve().as_uri()}")'
        rules.append(
            "@font-face { font-family: \"%s\"; src: %s; font-weight: %s; font-style: %s; }"
            % (name, src, weight, style)
        )
    return "\n".join(rules)
