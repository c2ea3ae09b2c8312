"""The one number formatter of the report: tables, formulas, plots and prose.

Russian typographic conventions:

* decimal comma: ``0,347``;
* the minus sign is U+2212 (``−1,5``), never a hyphen;
* a value that rounds to zero prints without a sign (never ``−0,000``);
* numbers with five or more integer digits are grouped by threes with a narrow
  no-break space U+202F: ``12 345``; four-digit numbers are not grouped;
* exponent form ``1,234·10⁵`` (middle dot U+00B7, superscript digits) only for
  ``|x| >= exp_from``, or for tiny ``0 < |x| < 1e-4`` when significant digits
  are asked for (with fixed ``digits`` a tiny value stays in fixed form, so a
  table column is uniform and numerical noise prints as ``0,000``);
* a unit follows after a no-break space U+00A0: ``0,347 м``; angle marks
  (° ′ ″) follow with no space;
* NaN and infinities print as an em dash ``—``.

Rounding is ROUND_HALF_UP of the shortest decimal representation of the float
(``Decimal(repr(x))``), so ``0.1735`` at three decimals is ``0,174``, as a
person (and Mathcad) would round the printed value.

``locale`` is never used (``ru_RU`` is usually absent in containers).
"""

from __future__ import annotations

import math
import numbers as _numbers
from decimal import ROUND_HALF_UP, Decimal

__all__ = [
    "MINUS",
    "NBSP",
    "NNBSP",
    "DASH",
    "fmt",
    "fmt_deg",
    "shared_decimals",
    "written",
    "agreeing_sig",
    "trimmed_sig",
    "fmt_pct",
    "tex_num",
    "mpl_formatter",
    "superscript",
]

MINUS = "\u2212"
NBSP = "\u00a0"
NNBSP = "\u202f"  # narrow no-break space: thousands separator
DASH = "\u2014"  # em dash: "no value"
MIDDOT = "\u00b7"

_SUPERSCRIPT = str.maketrans("0123456789-+", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺")
SUBSCRIPT = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")     # digits as subscripts in plain text (z₁, R₀₁)
_TINY = Decimal("1e-4")
# Units written right after the number without a space.
_ATTACHED_UNITS = ("°", "′", "″")


def superscript(text: str) -> str:
    """Digits and signs as Unicode superscripts: ``"-5"`` → ``"⁻⁵"``."""
    return str(text).translate(_SUPERSCRIPT)


def _to_decimal(x) -> Decimal | None:
    """The shortest decimal representation of ``x``; ``None`` for NaN/inf."""
    if isinstance(x, Decimal):
        return x if x.is_finite() else None
    if isinstance(x, bool):
        return Decimal(int(x))
    if isinstance(x, _numbers.Integral):
        return Decimal(int(x))
    try:
        f = float(x)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"fmt() expects a real number, got {x!r}") from exc
    if not math.isfinite(f):
        return None
    # repr(float) is the shortest string that round-trips (numpy scalars are
    # converted first: repr(np.float64) is "np.float64(...)" in numpy 2).
    return Decimal(repr(f))


def _quantize(d: Decimal, decimals: int) -> Decimal:
    return d.quantize(Decimal(1).scaleb(-decimals), rounding=ROUND_HALF_UP)


def _group(int_digits: str) -> str:
    """Group an unsigned integer string by threes with U+202F if it has 5+ digits."""
    if len(int_digits) < 5:
        return int_digits
    head = len(int_digits) % 3 or 3
    parts = [int_digits[:head]] + [int_digits[i:i + 3] for i in range(head, len(int_digits), 3)]
    return NNBSP.join(parts)


def _plain(d: Decimal, decimals: int, group: bool = True) -> tuple[str, bool]:
    """Fixed-point string of the absolute value (already quantized), and is-zero."""
    s = format(abs(d), "f")
    if "." in s:
        int_part, frac = s.split(".")
    else:
        int_part, frac = s, ""
    frac = frac.ljust(decimals, "0")[:decimals] if decimals > 0 else ""
    if group:
        int_part = _group(int_part)
    text = int_part + ("," + frac if frac else "")
    return text, d == 0


def _sig_decimals(d: Decimal, sig: int) -> int:
    """Decimals that show ``sig`` significant digits of ``d`` (never fewer than 0)."""
    if d == 0:
        return 0
    return max(0, sig - 1 - d.adjusted())


def _sig_round(d: Decimal, sig: int) -> tuple[Decimal, int]:
    """``d`` rounded to ``sig`` significant digits in fixed form, and its decimals."""
    decimals = _sig_decimals(d, sig)
    q = _quantize(d, decimals)
    # Rounding may carry into a new digit (0,99996 → 1,0000): recompute.
    if q != 0 and q.adjusted() != d.adjusted():
        decimals = _sig_decimals(q, sig)
        q = _quantize(d, decimals)
    return q, decimals


def _parts(x, digits: int | None, sig: int | None, exp_from: float):
    """Split a number into (negative, mantissa text, exponent or None).

    Returns ``None`` for NaN/inf.
    """
    d = _to_decimal(x)
    if d is None:
        return None
    if digits is None and sig is None:
        sig = 4
    if digits is not None and digits < 0:
        raise ValueError("digits must be >= 0")
    if sig is not None and sig < 1:
        raise ValueError("sig must be >= 1")

    a = abs(d)
    use_exp = False
    if a != 0:
        if a >= Decimal(repr(float(exp_from))):
            use_exp = True
        elif a < _TINY:
            # Only in significant-digits mode: with fixed decimals the column
            # stays in fixed form (cos 90° = 6e-17 prints as 0,000).
            use_exp = digits is None

    if use_exp:
        exp = a.adjusted()
        mant_decimals = digits if digits is not None else sig - 1
        mant = _quantize(d.scaleb(-exp), mant_decimals)
        if abs(mant) >= 10:  # 9,9996·10⁴ → 1,000·10⁵
            exp += 1
            mant = _quantize(d.scaleb(-exp), mant_decimals)
        text, _ = _plain(mant, mant_decimals, group=False)
        return (d < 0, text, exp)

    if digits is not None:
        decimals = digits
        q = _quantize(d, decimals)
    elif isinstance(x, _numbers.Integral):
        # An exact count (65 об/мин, 12 positions) gets no invented decimals.
        decimals = 0
        q = d
    else:
        q, decimals = _sig_round(d, sig)
    text, is_zero = _plain(q, decimals)
    return (d < 0 and not is_zero, text, None) if not is_zero else (False, text, None)


def _attach_unit(text: str, unit: str | None) -> str:
    if not unit:
        return text
    if unit.startswith(_ATTACHED_UNITS):
        return text + unit
    return text + NBSP + unit


def fmt(
    x,
    *,
    digits: int | None = None,
    sig: int | None = 4,
    unit: str | None = None,
    sign: bool = False,
    exp_from: float = 1e6,
) -> str:
    """Format a number the Russian way (see the module docstring).

    ``digits`` fixes the number of decimals; otherwise ``sig`` significant
    digits are shown (but never fewer than 0 decimals: large numbers print in
    full). Python/numpy integers in ``sig`` mode print without decimals. ``sign=True`` writes "+" before positive values (zero stays
    unsigned). ``unit`` is appended after a no-break space.

    >>> fmt(0.347, digits=3, unit="м")
    '0,347\\xa0м'
    >>> fmt(-0.0001, digits=3)
    '0,000'
    """
    parts = _parts(x, digits, sig, exp_from)
    if parts is None:
        return DASH
    negative, mant, exp = parts
    is_zero = exp is None and mant.strip("0,") == ""
    if negative:
        prefix = MINUS
    elif sign and not is_zero:
        prefix = "+"
    else:
        prefix = ""
    text = prefix + mant
    if exp is not None:
        text += MIDDOT + "10" + superscript(str(exp))
    return _attach_unit(text, unit)


def shared_decimals(values, *, sig: int = 4, most: int = 2) -> int:
    """One number of decimals for a column of measured values (ГОСТ 7.32, 6.6.6: a column's
    numbers to the same decimals): the decimals that give its largest magnitude ``sig``
    significant digits, between 0 and ``most`` — forces 27 500 / 138 350 Н print without
    decimals, 12,35 / 80,40 Н with two.

    >>> shared_decimals([27500.0, 138349.58, 5.2])
    0
    >>> shared_decimals([12.345, 80.4])
    2
    """
    mags = [abs(float(v)) for v in values if math.isfinite(float(v))]
    big = max(mags, default=0.0)
    if big == 0.0:
        return most
    return max(0, min(most, sig - 1 - math.floor(math.log10(big))))


def written(x, sig: int = 4) -> float:
    """The value a reader sees when ``x`` is printed with ``sig`` significant digits (the rounding of
    :func:`fmt`; an exact count, an ``int``, is printed whole)."""
    if isinstance(x, _numbers.Integral):
        return float(x)
    d = _to_decimal(x)
    if d is None or d == 0:
        return float(x)
    return float(_sig_round(d, sig)[0])


def trimmed_sig(x, sig: int, least: int = 4) -> int:
    """The fewest significant digits, from ``least`` up to ``sig``, that print the same value as
    ``sig`` do: an exact 0,1735 among factors printed to 7 digits stays «0,1735», not «0,1735000»."""
    for s in range(least, sig):
        if written(x, s) == written(x, sig):
            return s
    return sig


def agreeing_sig(value, factors, result, *, sig: int = 4, result_sig: int = 4, most: int = 7) -> int:
    """The fewest significant digits, from ``sig`` up to ``most``, to print the measured factors of
    a substituted formula with, so that ``value`` of the factors as printed, rounded as the result
    is printed, is the printed result: a reader who multiplies out the printed numbers gets the
    printed answer (G·y′ = 90·0,1047 = 9,423 is not the printed 9,426; 90·0,10473 is).  ``value``
    takes the list of the factors as printed; given data it uses is written once, as given.  When no
    number of digits up to ``most`` makes them agree, ``sig``."""
    d = _to_decimal(result)
    if d is None or d == 0:
        return sig
    target, decimals = _sig_round(d, result_sig)
    for s in range(sig, most + 1):
        v = _to_decimal(value([written(f, s) for f in factors]))
        if v is not None and _quantize(v, decimals) == target:
            return s
    return sig          # no number of digits makes them agree (not a rounding matter): as before


def fmt_deg(rad, digits: int = 1, **kw) -> str:
    """An angle given in radians, printed in degrees: ``fmt_deg(pi/4)`` → ``"45,0°"``."""
    d = _to_decimal(rad)
    if d is None:
        return DASH
    return fmt(math.degrees(float(rad)), digits=digits, unit="°", **kw)


def fmt_pct(x, digits: int = 2, *, fraction: bool = True, **kw) -> str:
    """A percentage with a no-break space before "%".

    ``x`` is a fraction by default, as in Python's ``"{:%}"``:
    ``fmt_pct(0.0123)`` → ``"1,23 %"``. Pass ``fraction=False`` when ``x`` is
    already in percent: ``fmt_pct(-0.6, 1, fraction=False)`` → ``"−0,6 %"``.
    """
    d = _to_decimal(x)
    if d is None:
        return DASH
    value = d * 100 if fraction else d
    return fmt(value, digits=digits, unit="%", **kw)


def tex_num(
    x,
    *,
    digits: int | None = None,
    sig: int | None = 4,
    unit: str | None = None,
    sign: bool = False,
    exp_from: float = 1e6,
    paren: bool = False,
) -> str:
    """The same number as :func:`fmt`, written for LaTeX (ziamath).

    Decimal comma as ``{,}``, a plain ``-`` (ziamath draws a proper minus;
    a negative number is wrapped in braces, ``{-5{,}792}``, so that the minus
    is unary),
    grouping as ``\\,``, exponent as ``\\cdot 10^{5}``, unit as
    ``\\ \\text{…}``. ``paren=True`` wraps negative values in parentheses,
    as needed when substituting into ``a \\cdot b``.

    >>> tex_num(6.80678, digits=3, unit="рад/с")
    '6{,}807\\\\ \\\\text{рад/с}'
    """
    parts = _parts(x, digits, sig, exp_from)
    if parts is None:
        return r"\text{" + DASH + "}"
    negative, mant, exp = parts
    is_zero = exp is None and mant.strip("0,") == ""
    body = mant.replace(",", "{,}").replace(NNBSP, r"\,")
    if exp is not None:
        body += r" \cdot 10^{" + str(exp) + "}"
    if negative:
        # Braces make the minus a prefix (unary) operator in ziamath, without
        # the spacing of a binary minus after "=" or "\cdot".
        body = "{-" + body + "}"
        if paren:
            body = r"\left(" + body + r"\right)"
    elif sign and not is_zero:
        body = "+" + body
    if unit:
        if unit.startswith(_ATTACHED_UNITS):
            body += "^{\\circ}" if unit == "°" else r"\text{" + unit + "}"
        else:
            body += r"\ \text{" + unit + "}"
    return body


def _mathtext(text: str) -> str:
    """Exponent form for matplotlib: superscripts as mathtext (fonts often lack ⁰ and ⁻)."""
    if MIDDOT + "10" not in text:
        return text
    mant, exp = text.split(MIDDOT + "10", 1)
    exp = exp.translate(str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺", "0123456789−+"))
    return r"$\mathregular{" + mant + r"\cdot10^{" + exp + "}}$"


def _fixed(x, decimals: int) -> str:
    """Plain fixed-point form, never exponent form (tick labels)."""
    d = _to_decimal(x)
    if d is None:
        return DASH
    q = _quantize(d, decimals)
    text, is_zero = _plain(q, decimals)
    return (MINUS if d < 0 and not is_zero else "") + text


def _decimals_needed(value: float, max_decimals: int = 10) -> int:
    """Fewest decimals that represent a tick location exactly (up to noise)."""
    d = _quantize(Decimal(repr(float(value))), max_decimals).normalize()
    exp = d.as_tuple().exponent
    return max(0, -exp) if isinstance(exp, int) else 0


def mpl_formatter(digits: int | None = None):
    """A matplotlib tick formatter with a decimal comma and U+2212.

    With ``digits=None`` all ticks of an axis get the same number of decimals,
    the fewest that show every tick exactly (0; 0,5; 1,0 …).
    """
    from matplotlib.ticker import FuncFormatter

    class _CommaFormatter(FuncFormatter):
        def __init__(self):
            super().__init__(self._format)
            self._auto = 0

        def set_locs(self, locs):
            super().set_locs(locs)
            if digits is None:
                finite = [v for v in locs if math.isfinite(v)]
                self._auto = max((_decimals_needed(v) for v in finite), default=0)

        def _format(self, x, pos=None):
            if digits is not None:
                return _mathtext(fmt(x, digits=digits))
            return _fixed(x, self._auto)

    return _CommaFormatter()


def position_names(labels) -> dict[str, str]:
    """The student's number of every report position: numeric labels stay, the others (extra
    positions named in the case, e.g. "f") get the next numbers in their order."""
    labels = [str(x) for x in labels]
    nums = [int(x) for x in labels if x.isdigit()]
    nxt = (max(nums) + 1) if nums else 1
    out = {}
    for lab in labels:
        if lab.isdigit():
            out[lab] = lab
        else:
            out[lab] = str(nxt)
            nxt += 1
    return out


def fmt_given(x, sig: int = 4) -> str:
    """A given value as an assignment states it: at most ``sig`` significant digits and no
    trailing zeros after the comma (ω₁ = 150 рад/с, 6,807 рад/с; φ₀ = 219,1°, not 219,100°)."""
    s = fmt(x, sig=sig)
    if "," in s and "·" not in s:
        s = s.rstrip("0").rstrip(",")
    return s
