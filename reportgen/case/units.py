"""Quantities with units; everything is converted to SI.

A dimension is a tuple of exponents ``(L, M, T, A)``: length, mass, time and a pseudo-dimension
``A`` for the plane angle (radian). Compatibility checks ignore ``A`` (the radian is dimensionless in
SI), but it is kept so that messages can say «угол» and «угловая скорость».
"""
from __future__ import annotations

import math
import re
from functools import lru_cache

from ..errors import CaseError, did_you_mean

__all__ = [
    "Dim", "LENGTH", "MASS", "TIME", "ANGLE", "DIMENSIONLESS", "FORCE", "MOMENT", "INERTIA",
    "VELOCITY", "ANGULAR_VELOCITY", "PRESSURE", "ENERGY", "DENSITY", "ACCELERATION",
    "ANGULAR_ACCELERATION", "FREQUENCY", "POWER", "AREA", "VOLUME", "STIFFNESS",
    "dim_name", "example_for", "parse_unit", "parse_quantity", "check_dim", "format_dim",
    "dim_mul", "dim_div", "dim_pow", "is_unit_symbol", "unit_hint", "apply_factor", "parse_number", "UNIT_SYNTAX",
]

Dim = tuple[int, int, int, int]

DIMENSIONLESS: Dim = (0, 0, 0, 0)
LENGTH: Dim = (1, 0, 0, 0)
MASS: Dim = (0, 1, 0, 0)
TIME: Dim = (0, 0, 1, 0)
ANGLE: Dim = (0, 0, 0, 1)
AREA: Dim = (2, 0, 0, 0)
VOLUME: Dim = (3, 0, 0, 0)
FORCE: Dim = (1, 1, -2, 0)
MOMENT: Dim = (2, 1, -2, 0)
ENERGY: Dim = MOMENT  # J = N·m: indistinguishable from a moment of force
POWER: Dim = (2, 1, -3, 0)
INERTIA: Dim = (2, 1, 0, 0)
VELOCITY: Dim = (1, 0, -1, 0)
ACCELERATION: Dim = (1, 0, -2, 0)
ANGULAR_VELOCITY: Dim = (0, 0, -1, 1)
ANGULAR_ACCELERATION: Dim = (0, 0, -2, 1)
FREQUENCY: Dim = (0, 0, -1, 0)
PRESSURE: Dim = (-1, 1, -2, 0)
DENSITY: Dim = (-3, 1, 0, 0)
STIFFNESS: Dim = (0, 1, -2, 0)  # N/m

UNIT_SYNTAX = ("единица измерения, например «m», «mm», «kg», «N», «N*m», «kg*m^2», «m/s^2», "
               "«deg», «rad/s», «rpm», «MPa»")

# ---------------------------------------------------------------------------------------------
# Names and examples

_NAMES: dict[Dim, str] = {
    DIMENSIONLESS: "безразмерная величина",
    LENGTH: "длина",
    MASS: "масса",
    TIME: "время",
    ANGLE: "угол",
    AREA: "площадь",
    VOLUME: "объём",
    FORCE: "сила",
    MOMENT: "момент силы",
    POWER: "мощность",
    INERTIA: "момент инерции",
    VELOCITY: "скорость",
    ACCELERATION: "ускорение",
    ANGULAR_VELOCITY: "угловая скорость",
    ANGULAR_ACCELERATION: "угловое ускорение",
    FREQUENCY: "частота",
    PRESSURE: "давление",
    DENSITY: "плотность",
    STIFFNESS: "жёсткость",
}

_EXAMPLES: dict[Dim, str] = {
    DIMENSIONLESS: "0.5",
    LENGTH: "0.347 m",
    MASS: "9 kg",
    TIME: "0.5 s",
    ANGLE: "99.1 deg",
    AREA: "0.02 m^2",
    VOLUME: "0.001 m^3",
    FORCE: "1200 N",
    MOMENT: "150 N*m",
    POWER: "1.5 kW",
    INERTIA: "0.45 kg*m^2",
    VELOCITY: "1.2 m/s",
    ACCELERATION: "9.81 m/s^2",
    ANGULAR_VELOCITY: "65 rpm",
    ANGULAR_ACCELERATION: "12 rad/s^2",
    FREQUENCY: "50 Hz",
    PRESSURE: "17.5 MPa",
    DENSITY: "7800 kg/m^3",
    STIFFNESS: "2000 N/m",
}

_SUP = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def _as_dim(dim) -> Dim:
    d = tuple(int(x) for x in dim)
    if len(d) != 4:
        raise ValueError(f"dimension must have 4 components, got {dim!r}")
    return d  # type: ignore[return-value]


def format_dim(dim: Dim, *, ascii: bool = False) -> str:
    """SI unit formula of a dimension: ``м·кг/с²`` (or ``m*kg/s^2`` with ``ascii=True``)."""
    dim = _as_dim(dim)
    syms = ("m", "kg", "s", "rad") if ascii else ("м", "кг", "с", "рад")
    mul = "*" if ascii else "·"

    def one(sym: str, e: int) -> str:
        if e == 1:
            return sym
        return f"{sym}^{e}" if ascii else sym + str(e).translate(_SUP)

    num = [one(s, e) for s, e in zip(syms, dim) if e > 0]
    den = [one(s, -e) for s, e in zip(syms, dim) if e < 0]
    if not num and not den:
        return "1"
    text = mul.join(num) if num else "1"
    if den:
        text += "/" + (mul.join(den) if len(den) == 1 or not ascii else f"({mul.join(den)})")
    return text


def dim_name(dim: Dim) -> str:
    """Russian noun phrase for a dimension (``"длина"``, ``"момент инерции"`` ...)."""
    dim = _as_dim(dim)
    if dim in _NAMES:
        return _NAMES[dim]
    return format_dim(dim)


def example_for(dim: Dim) -> str:
    """An example literal of the dimension for messages: ``"0.347 m"``, ``"65 rpm"`` ..."""
    dim = _as_dim(dim)
    if dim in _EXAMPLES:
        return _EXAMPLES[dim]
    for d, ex in _EXAMPLES.items():
        if d[:3] == dim[:3]:
            return ex
    return f"1 {format_dim(dim, ascii=True)}"


def check_dim(got: Dim, expected: Dim) -> bool:
    """Dimensions are compatible: equal ignoring the angle component."""
    return tuple(got[:3]) == tuple(expected[:3])


def dim_mul(a: Dim, b: Dim) -> Dim:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3])


def dim_div(a: Dim, b: Dim) -> Dim:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2], a[3] - b[3])


def dim_pow(a: Dim, n: int) -> Dim:
    return (a[0] * n, a[1] * n, a[2] * n, a[3] * n)


# ---------------------------------------------------------------------------------------------
# Unit table

_PI = math.pi
_SYMBOLS: dict[str, tuple[float, Dim]] = {}

# prefixable base units: symbol -> (factor, dim)
_BASE_LATIN = {
    "m": (1.0, LENGTH), "g": (1e-3, MASS), "s": (1.0, TIME), "N": (1.0, FORCE),
    "Pa": (1.0, PRESSURE), "J": (1.0, ENERGY), "W": (1.0, POWER), "Hz": (1.0, FREQUENCY),
    "rad": (1.0, ANGLE),
}
_BASE_RU = {
    "м": (1.0, LENGTH), "г": (1e-3, MASS), "с": (1.0, TIME), "Н": (1.0, FORCE),
    "Па": (1.0, PRESSURE), "Дж": (1.0, ENERGY), "Вт": (1.0, POWER), "Гц": (1.0, FREQUENCY),
    "рад": (1.0, ANGLE),
}
_PREFIX_LATIN = {"G": 1e9, "M": 1e6, "k": 1e3, "d": 1e-1, "c": 1e-2, "m": 1e-3, "µ": 1e-6,
                 "u": 1e-6, "n": 1e-9}
_PREFIX_RU = {"Г": 1e9, "М": 1e6, "к": 1e3, "д": 1e-1, "с": 1e-2, "м": 1e-3, "мк": 1e-6,
              "н": 1e-9}

for _base, _prefixes in ((_BASE_LATIN, _PREFIX_LATIN), (_BASE_RU, _PREFIX_RU)):
    for _sym, (_f, _d) in _base.items():
        _SYMBOLS[_sym] = (_f, _d)
        for _p, _pf in _prefixes.items():
            # divide by an exact integer for sub-unit prefixes: 1e-3 / 1000 is correctly rounded
            _SYMBOLS.setdefault(_p + _sym, (_pf * _f if _pf >= 1 else _f / round(1 / _pf), _d))

_SYMBOLS.update({
    # time
    "sec": (1.0, TIME), "min": (60.0, TIME), "h": (3600.0, TIME),
    "мин": (60.0, TIME), "ч": (3600.0, TIME),
    # mass
    "t": (1000.0, MASS), "т": (1000.0, MASS),
    # angle
    "deg": (_PI / 180, ANGLE), "degree": (_PI / 180, ANGLE), "degrees": (_PI / 180, ANGLE),
    "°": (_PI / 180, ANGLE), "град": (_PI / 180, ANGLE),
    "rev": (2 * _PI, ANGLE), "об": (2 * _PI, ANGLE),
    # angular velocity
    "rpm": (2 * _PI / 60, ANGULAR_VELOCITY), "rps": (2 * _PI, ANGULAR_VELOCITY),
    # pressure
    "bar": (1e5, PRESSURE), "бар": (1e5, PRESSURE),
    # newton-metre written without a separator
    "Nm": (1.0, MOMENT), "Нм": (1.0, MOMENT),
    # dimensionless
    "%": (0.01, DIMENSIONLESS),
    # imperial (US customary) units of published examples, exact by definition (NIST SP 811):
    # 1 in = 0.0254 m, 1 ft = 12 in, 1 lb = 0.45359237 kg, 1 lbf = 1 lb · 9.80665 m/s²,
    # 1 slug = 1 lbf·s²/ft, 1 psi = 1 lbf/in², 1 hp = 550 ft·lbf/s
    "in": (0.0254, LENGTH), "ft": (0.3048, LENGTH), "yd": (0.9144, LENGTH),
    "lb": (0.45359237, MASS), "lbm": (0.45359237, MASS),
    "lbf": (0.45359237 * 9.80665, FORCE), "kip": (453.59237 * 9.80665, FORCE),
    "slug": (0.45359237 * 9.80665 / 0.3048, MASS),
    "psi": (0.45359237 * 9.80665 / 0.0254 ** 2, PRESSURE),
    "hp": (550 * 0.3048 * 0.45359237 * 9.80665, POWER),
})

# Whole-unit aliases (compared after removing spaces, "**" -> "^", superscripts -> "^n").
# A rotation speed "per minute" in a mechanism always means revolutions per minute (ГОСТ: n, мин⁻¹),
# so "мин^-1" is taken as rpm, not as 1/60 s⁻¹ (which would silently lose the factor 2π).
_WHOLE_ALIASES: dict[str, tuple[float, Dim]] = {
    k: (2 * _PI / 60, ANGULAR_VELOCITY)
    for k in ("об/мин", "rev/min", "r/min", "min^-1", "мин^-1", "1/min", "1/мин", "об./мин")
}

# Preferred candidates for did-you-mean hints (checked first, so "Mpa" suggests "MPa", not "mPa").
_COMMON_UNITS = (
    "m", "mm", "cm", "dm", "km", "µm", "kg", "g", "t", "s", "ms", "min", "h", "rad", "deg", "rev",
    "rpm", "Hz", "N", "kN", "MN", "Pa", "kPa", "MPa", "GPa", "bar", "J", "kJ", "W", "kW",
    "м", "мм", "см", "кг", "г", "т", "с", "мин", "Н", "кН", "Па", "кПа", "МПа", "Дж", "Вт", "рад",
    "об", "град",
)

_SUPERSCRIPT_DIGITS = {"⁰": "0", "¹": "1", "²": "2", "³": "3", "⁴": "4", "⁵": "5", "⁶": "6",
                       "⁷": "7", "⁸": "8", "⁹": "9", "⁻": "-"}
_SUPERSCRIPT_RE = re.compile("[⁰¹²³⁴⁵⁶⁷⁸⁹⁻]+")


def _normalize(text: str) -> str:
    text = text.replace("μ", "µ").replace("**", "^").replace("−", "-")
    text = text.replace("⋅", "·").replace("×", "*")
    return _SUPERSCRIPT_RE.sub(lambda m: "^" + "".join(_SUPERSCRIPT_DIGITS[c] for c in m.group()), text)


def is_unit_symbol(symbol: str) -> bool:
    """``symbol`` is a single known unit (``"mm"``, ``"deg"``, ``"кН"`` ...)."""
    return _normalize(symbol) in _SYMBOLS


def unit_hint(sym: str) -> str | None:
    """A hint for an unknown unit symbol: ``"m2"`` -> use ``m^2``; ``"Mpa"`` -> ``MPa``."""
    m = re.fullmatch(r"([^\W\d_]+)([0-9]+)", sym)
    if m and m.group(1) in _SYMBOLS:
        return f"степень записывается через «^»: «{m.group(1)}^{m.group(2)}»"
    return did_you_mean(sym, [*_COMMON_UNITS, *_SYMBOLS.keys()])


def _unknown_unit(sym: str, whole: str) -> CaseError:
    hint = unit_hint(sym)
    where = f" в «{whole}»" if whole.strip() != sym else ""
    return CaseError(f"неизвестная единица измерения «{sym}»{where}", expected=UNIT_SYNTAX,
                     got=whole, hint=hint)


_UNIT_TOKEN = re.compile(r"\s*(?:(?P<sym>[^\W\d_]+|°|%)|(?P<num>-?[0-9]+)|(?P<op>\^|\*|·|/|\(|\)))")


def _tokenize_unit(norm: str, text: str) -> list[tuple[str, str]]:
    tokens: list[tuple[str, str]] = []
    pos = 0
    while pos < len(norm):
        if norm[pos:].strip() == "":
            break
        m = _UNIT_TOKEN.match(norm, pos)
        if not m:
            bad = norm[pos:].lstrip()[:1]
            raise CaseError(f"недопустимый символ «{bad}» в единице измерения «{text}»",
                            expected=UNIT_SYNTAX, got=text)
        kind = m.lastgroup
        tokens.append((kind, m.group(kind)))  # type: ignore[arg-type]
        pos = m.end()
    return tokens


@lru_cache(maxsize=512)
def parse_unit(text: str) -> tuple[float, Dim]:
    """Parse a unit (``"mm"``, ``"kg*m^2"``, ``"kg·m²"``, ``"N m"``, ``"об/мин"``) into
    ``(factor to SI, dimension)``.

    ``*``, ``·`` and whitespace multiply, ``/`` divides (left to right, like arithmetic),
    ``^n`` / ``**n`` / ``²`` / ``⁻¹`` raise to an integer power, parentheses group.
    Unknown unit -> :class:`CaseError` with a did-you-mean hint.
    """
    if not isinstance(text, str):
        raise TypeError("unit must be a string")
    norm = _normalize(text).strip()
    if not norm:
        raise CaseError("не указана единица измерения", expected=UNIT_SYNTAX, got=text)
    compact = re.sub(r"\s+", "", norm)
    if compact in _WHOLE_ALIASES:
        return _WHOLE_ALIASES[compact]
    if norm in _SYMBOLS:
        return _SYMBOLS[norm]

    tokens = _tokenize_unit(norm, text)
    i = 0

    def peek() -> tuple[str, str] | None:
        return tokens[i] if i < len(tokens) else None

    def syntax(msg: str) -> CaseError:
        return CaseError(f"ошибка в записи единицы измерения «{text}»: {msg}",
                         expected=UNIT_SYNTAX, got=text)

    def exponent() -> int:
        nonlocal i
        paren = peek() == ("op", "(")
        if paren:
            i += 1
        t = peek()
        if t is None or t[0] != "num":
            raise syntax("после «^» ожидается целый показатель степени")
        i += 1
        if paren:
            if peek() != ("op", ")"):
                raise syntax("не закрыта скобка")
            i += 1
        return int(t[1])

    def atom() -> tuple[float, Dim]:
        nonlocal i
        t = peek()
        if t is None:
            raise syntax("запись обрывается")
        kind, val = t
        if kind == "sym":
            i += 1
            nxt = peek()
            if nxt is not None and nxt[0] == "num":
                raise _unknown_unit(val + nxt[1], text)  # "m2" instead of "m^2"
            if val not in _SYMBOLS:
                raise _unknown_unit(val, text)
            f, d = _SYMBOLS[val]
        elif kind == "num" and val == "1":
            i += 1
            f, d = 1.0, DIMENSIONLESS
        elif t == ("op", "("):
            i += 1
            f, d = product()
            if peek() != ("op", ")"):
                raise syntax("не закрыта скобка")
            i += 1
        else:
            raise syntax(f"неожиданный «{val}»")
        if peek() == ("op", "^"):
            i += 1
            n = exponent()
            f, d = f ** n, dim_pow(d, n)
        return f, d

    def product() -> tuple[float, Dim]:
        nonlocal i
        f, d = atom()
        while True:
            t = peek()
            if t is None or t == ("op", ")"):
                return f, d
            if t in (("op", "*"), ("op", "·")):
                i += 1
                f2, d2 = atom()
                f, d = f * f2, dim_mul(d, d2)
            elif t == ("op", "/"):
                i += 1
                f2, d2 = atom()
                f, d = f / f2, dim_div(d, d2)
            elif t[0] == "sym" or t == ("op", "("):
                f2, d2 = atom()  # whitespace multiplies: "N m", "kg m^2"
                f, d = f * f2, dim_mul(d, d2)
            else:
                raise syntax(f"неожиданный «{t[1]}»")

    f, d = product()
    if i != len(tokens):
        raise syntax("лишняя закрывающая скобка" if tokens[i] == ("op", ")")
                     else f"неожиданный «{tokens[i][1]}»")
    return float(f), d


_NUMBER_RE = re.compile(
    r"\s*(?P<num>[+\-−]?(?:[0-9]+(?:[.,][0-9]*)?|[.,][0-9]+)(?:[eE][+\-−]?[0-9]+)?)\s*(?P<unit>.*?)\s*$",
    re.S,
)


def parse_number(text: str) -> float | None:
    """A bare number (decimal comma allowed) or ``None``."""
    m = _NUMBER_RE.fullmatch(text)
    if not m or m.group("unit"):
        return None
    return float(m.group("num").replace(",", ".").replace("−", "-"))


def parse_quantity(text: str) -> tuple[float, Dim]:
    """``"0.347 m"`` -> ``(0.347, LENGTH)``; ``"99.1 deg"`` -> ``(1.7296…, ANGLE)``.

    A bare number has dimension ``DIMENSIONLESS``. Decimal comma is accepted (``"0,347 m"``).
    """
    if not isinstance(text, str):
        raise TypeError("quantity must be a string")
    m = _NUMBER_RE.fullmatch(text)
    if not m:
        raise CaseError(f"не удалось прочитать величину «{text.strip()}»",
                        expected="число с единицей измерения, например «0.347 m», «99.1 deg», «65 rpm»",
                        got=text)
    value = float(m.group("num").replace(",", ".").replace("−", "-"))
    unit = m.group("unit")
    if not unit:
        return value, DIMENSIONLESS
    try:
        factor, dim = parse_unit(unit)
    except CaseError as e:
        msg = e.message if " в «" in e.message else f"{e.message} в «{text.strip()}»"
        raise CaseError(msg, expected=e.expected, got=text.strip(), hint=e.hint) from None
    return apply_factor(value, factor), dim


def apply_factor(value, factor: float):
    """``value * factor``, but divides by an exact integer when ``factor`` is ``1/n`` so that
    ``347 mm`` is exactly ``0.347`` m. Works element-wise on numpy arrays."""
    if 0 < factor < 1:
        inv = 1.0 / factor
        r = round(inv)
        if r > 1 and abs(inv - r) <= 1e-9 * r:
            return value / r
    return value * factor
