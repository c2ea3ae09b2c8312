"""Text of a case file on its way to HTML: names checked against a safe pattern, free text
escaped (a small whitelist of inline tags kept), meta values as plain strings of bounded size.

Everything a section writes into the note is HTML (``Markup`` or a string built from one), so
text that comes from a case must be converted here, once, at input:

* a *name* (point, link, joint, position label) must match :data:`NAME_RE` — letters of any
  alphabet (Latin, Cyrillic, Greek), digits, primes, ``_``, ``-``, ``.``; anything else is a
  :class:`~reportgen.errors.CaseError`. A valid name needs no escaping anywhere (HTML, CSV, SVG).
* free *text* (titles, notes) becomes :class:`markupsafe.Markup` by :func:`inline_html`:
  everything escaped except the inline tags ``<sub> <sup> <i> <b> <br>`` written without
  attributes and properly nested, which the worksheets' printed titles use (``J<sub>1пр</sub>``).
"""
from __future__ import annotations

import math
import re
from typing import Any

from markupsafe import Markup, escape

from ..errors import CaseError

__all__ = ["NAME_RE", "MAX_NAME", "MAX_TEXT", "check_name", "inline_html", "meta_value", "clip"]

MAX_NAME = 40  # characters of a point/link/joint name or a position label
MAX_TEXT = 2000  # characters of a title or a note
MAX_WORD = 80  # longest unbroken run of characters kept in a meta value (a longer one is broken)
MAX_META = 500  # characters of a meta value

NAME_RE = re.compile(r"^[\w'′″‴.\-]+$")
_INLINE_TAGS = ("sub", "sup", "i", "b")
_TAG_RE = re.compile(r"&lt;(/?)(sub|sup|i|b)&gt;|&lt;br\s*/?&gt;")
_CONTROL_RE = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")


def clip(text: Any, limit: int = 200) -> str:
    """``text`` shortened to ``limit`` characters for an error message (``…`` marks the cut)."""
    s = str(text)
    return s if len(s) <= limit else s[:limit - 1] + "…"


def check_name(value: Any, *, file: str | None, key: str, what: str = "имя") -> str:
    """A name of a point, link, joint or position label, checked against :data:`NAME_RE`."""
    if isinstance(value, bool) or not isinstance(value, (str, int)):
        raise CaseError(f"{what} должно быть строкой", file=file, key=key,
                        expected="строка в кавычках, например \"A\"", got=clip(repr(value), 60))
    s = str(value)
    if not s or len(s) > MAX_NAME or not NAME_RE.match(s):
        raise CaseError(f"недопустимое {what} «{clip(s, 60)}»", file=file, key=key,
                        expected=f"до {MAX_NAME} символов: буквы (латинские, русские, греческие), цифры, "
                                 "штрихи (′ или '), «_», «-», «.»; без пробелов и знаков <, >, &, кавычек")
    return s


def inline_html(text: Any) -> Markup:
    """Free text as safe HTML: escaped, except properly nested ``<sub>``, ``<sup>``, ``<i>``,
    ``<b>`` (no attributes) and ``<br>``; control characters dropped."""
    s = _CONTROL_RE.sub("", str(text))
    esc = str(escape(s))
    stack: list[str] = []
    ok = True
    for m in _TAG_RE.finditer(esc):
        if m.group(2) is None:
            continue
        if m.group(1):
            if not stack or stack.pop() != m.group(2):
                ok = False
                break
        else:
            stack.append(m.group(2))
    if not ok or stack:
        return Markup(esc)  # unbalanced: every tag shown literally

    def repl(m: re.Match) -> str:
        return f"<{m.group(1)}{m.group(2)}>" if m.group(2) else "<br>"

    return Markup(_TAG_RE.sub(repl, esc))


def _break_long_words(s: str) -> str:
    """Insert a zero-width space every :data:`MAX_WORD` characters of an unbroken run, so the
    layout engine can wrap it (a 20 000-character word takes WeasyPrint tens of seconds)."""
    return re.sub(r"\S{%d}(?=\S)" % MAX_WORD, lambda m: m.group(0) + "\u200b", s)


def meta_value(value: Any, *, file: str | None, key: str) -> str:
    """A ``[meta]`` value as text: a string, or an integer / finite float (a year); anything
    else (arrays, tables, booleans, nan) is a :class:`CaseError` — never a Python repr."""
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        raise CaseError("значение в [meta] должно быть строкой", file=file, key=key,
                        expected="строка в кавычках, например student = \"Е. Е. Фёдорова\"",
                        got=clip(repr(value), 80))
    if isinstance(value, float):
        if not math.isfinite(value):
            raise CaseError("значение в [meta] должно быть строкой", file=file, key=key,
                            expected="строка в кавычках", got=clip(repr(value), 80))
        value = str(int(value)) if value.is_integer() else str(value)
    s = _CONTROL_RE.sub("", str(value))
    if len(s) > MAX_META:
        raise CaseError(f"слишком длинное значение в [meta] ({len(s)} символов)", file=file, key=key,
                        expected=f"не более {MAX_META} символов", got=clip(s, 60))
    return _break_long_words(s)
