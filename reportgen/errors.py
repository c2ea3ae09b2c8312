"""Exceptions shown to the user without a traceback.

``str(e)`` of every :class:`ReportgenError` is a complete Russian message meant for the user.
"""
from __future__ import annotations

import difflib
import math
from typing import Iterable

__all__ = [
    "ReportgenError",
    "CaseError",
    "AssemblyError",
    "StructureError",
    "did_you_mean",
]


class ReportgenError(Exception):
    """Base of all errors shown to the user without a traceback; str(e) is the Russian message."""


MAX_ECHO = 200  # characters of an input repeated in a message


def _clip(text: str, limit: int) -> str:
    """``text`` cut to ``limit`` characters (``…`` marks the cut): a message never repeats a
    60-kB input in full."""
    return text if len(text) <= limit else text[:limit - 1] + "…"


def _quoted(text: str) -> str:
    """Wrap ``text`` in «» unless it is already quoted (or is a repr of a container)."""
    t = text.strip()
    if t[:1] in ('"', "'", "«", "[", "{") or not t:
        return text
    return f"«{text}»"


class CaseError(ReportgenError):
    """An error in the case file (wrong key, value, unit, expression ...).

    Attributes ``message``, ``file``, ``key``, ``expected``, ``got``, ``hint``. The rendered text is
    ``"<file>: ключ <key>: <message>; ожидается: <expected>; получено: «<got>».\\n  Подсказка: <hint>"``
    where absent parts are omitted, and ``expected``/``got`` are omitted when the message already
    quotes them.
    """

    def __init__(self, message: str, *, file: str | None = None, key: str | None = None,
                 expected: str | None = None, got: str | None = None, hint: str | None = None):
        self.message = message
        self.file = file
        self.key = key
        self.expected = expected
        self.got = got
        self.hint = hint
        super().__init__(message)

    def __str__(self) -> str:
        parts: list[str] = []
        if self.file:
            parts.append(_clip(str(self.file), 200))
        if self.key:
            parts.append(f"ключ {_clip(str(self.key), 120)}")
        body = _clip(self.message.rstrip(), MAX_ECHO + 100).rstrip(".")
        extra: list[str] = []
        if self.expected and self.expected not in body:
            extra.append(f"ожидается: {_clip(self.expected, 4 * MAX_ECHO)}")
        if self.got is not None and str(self.got) not in body:
            extra.append(f"получено: {_quoted(_clip(str(self.got), MAX_ECHO))}")
        if extra:
            body = "; ".join([body, *extra]) if body else "; ".join(extra)
        parts.append(body)
        text = ": ".join(parts)
        if not text.endswith((".", "?", "!", "…")):
            text += "."
        if self.hint:
            text += f"\n  Подсказка: {_clip(self.hint, MAX_ECHO + 100)}"
        return text

    def _copy(self, **changes) -> "CaseError":
        kw = dict(file=self.file, key=self.key, expected=self.expected, got=self.got, hint=self.hint)
        kw.update(changes)
        new = type(self).__new__(type(self))
        CaseError.__init__(new, self.message, **kw)
        return new

    def with_context(self, file: str | None = None, key_prefix: str | None = None) -> "CaseError":
        """A copy with ``file`` set (when given) and ``key`` prefixed by ``key_prefix``.

        ``"links[2]"`` + ``"mass"`` gives ``"links[2].mass"``; an index key (``"[0]"``) is appended
        without a dot.
        """
        key = self.key
        if key_prefix:
            if not key:
                key = key_prefix
            elif key.startswith("["):
                key = f"{key_prefix}{key}"
            else:
                key = f"{key_prefix}.{key}"
        return self._copy(file=file if file is not None else self.file, key=key)

    def __reduce__(self):
        return (_rebuild_case_error, (type(self), self.message, self.file, self.key,
                                      self.expected, self.got, self.hint))


def _rebuild_case_error(cls, message, file, key, expected, got, hint):
    new = cls.__new__(cls)
    CaseError.__init__(new, message, file=file, key=key, expected=expected, got=got, hint=hint)
    return new


_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def _fmt_amount(x: float) -> str:
    """Russian number format with 4 significant digits: ``0,0123``, ``1,234·10⁻⁵``."""
    if not math.isfinite(x):
        return "∞" if x > 0 else ("−∞" if x < 0 else "?")
    ax = abs(x)
    if ax == 0 or 1e-4 <= ax < 1e6:
        return f"{x:.4g}".replace(".", ",").replace("-", "−")
    mant, exp = f"{x:.3e}".split("e")
    mant = mant.rstrip("0").rstrip(".").replace(".", ",").replace("-", "−")
    return f"{mant}·10{str(int(exp)).translate(_SUPERSCRIPT)}"


class AssemblyError(ReportgenError):
    """A group of the mechanism cannot be assembled."""

    def __init__(self, group: str, position: str, amount: float, detail: str = "", hint: str = ""):
        self.group = group
        self.position = position
        self.amount = float(amount)
        self.detail = detail
        self.hint = hint
        super().__init__(str(self))

    def __str__(self) -> str:
        group = self.group.strip()
        if not group.lower().startswith("групп"):
            group = f"группа Ассура {group}"
        if self.amount > 0:
            text = f"Механизм не собирается: {group} в положении {self.position}: " \
                   f"не хватает {_fmt_amount(self.amount)} м"
        else:   # a singular (dead) position: nothing is short, the group loses its mobility
            text = f"Особое положение механизма: {group} в положении {self.position}"
        if self.detail:
            text += f" ({self.detail})"
        if self.hint:
            text += f". {self.hint}"
        return text

    def __reduce__(self):
        return (type(self), (self.group, self.position, self.amount, self.detail, self.hint))


class StructureError(ReportgenError):
    """The chain is not a valid mechanism (W != 1, unattached links, unsolvable group)."""


_LOOKALIKE = str.maketrans({
    "0": "o", "1": "l", "а": "a", "в": "b", "е": "e", "к": "k", "м": "m", "н": "h", "о": "o",
    "р": "p", "с": "c", "т": "t", "у": "y", "х": "x", "ё": "e",
})


def _skeleton(s: str) -> str:
    return s.lower().translate(_LOOKALIKE)


def did_you_mean(word: str, candidates: Iterable[str]) -> str | None:
    """A Russian hint ``возможно, имелось в виду «mass»?`` or ``None`` if nothing is close."""
    cands = [str(c) for c in candidates]
    if not cands or not word:
        return None
    # Exact match ignoring case (and Latin/Cyrillic look-alikes would be too clever).
    lowered: dict[str, str] = {}
    for c in cands:
        lowered.setdefault(c.lower(), c)  # the first candidate wins: callers list preferred ones first
    hit = lowered.get(str(word).lower())
    if hit is not None and hit != word:
        return f"возможно, имелось в виду «{hit}»?"
    # Look-alike characters (0/O, 1/l, Cyrillic/Latin) are a frequent typo: an exact match of
    # the "skeleton" beats any fuzzy match.
    skel = _skeleton(str(word))
    same = [c for c in dict.fromkeys(cands) if _skeleton(c) == skel and c != word]
    if len(same) == 1:
        return f"возможно, имелось в виду «{same[0]}»?"
    matches = difflib.get_close_matches(str(word), cands, n=2, cutoff=0.6)
    if not matches:
        low = difflib.get_close_matches(str(word).lower(), list(lowered), n=2, cutoff=0.6)
        matches = [lowered[m] for m in low]
    matches = list(dict.fromkeys(m for m in matches if m != word))
    if not matches:
        return None
    if len(matches) == 1:
        return f"возможно, имелось в виду «{matches[0]}»?"
    return f"возможно, имелось в виду «{matches[0]}» или «{matches[1]}»?"
