"""Safe, unit-aware expressions over named parameters.

Case files may write a value as an expression: ``"0.5*(S_min + S_max)"``,
``"180 deg + asin(l_1/l_0)"``, ``"sqrt(X6^2 + Y6^2)"``, ``"-P*0.2"``. The text is tokenised and
parsed by a small recursive-descent parser into a tuple AST and evaluated on :class:`Q`
quantities (SI value + dimension); there is no ``eval``.

Rules
-----
* A number followed by a unit is a quantity: ``180 deg``, ``0.2 m``, ``3 mm``, ``99.1°``,
  ``10 m/s^2``. Inside an expression a compound unit continues only without spaces around ``*``,
  ``/`` and ``^``: ``"2 m/s"`` is 2 m/s, ``"2 m / s"`` divides 2 m by the parameter ``s``.
* A bare number inside an expression is dimensionless. If the WHOLE text is a bare number (or a
  TOML number) its dimension is ``bare_is`` ("bare numbers are SI").
* ``^`` and ``**`` are both power; unary minus binds looser than power (``-x^2 = -(x^2)``).
* Decimal comma is accepted outside function calls (``"0,5*l"``); inside a call the comma
  separates arguments (``max(0,5)`` has two arguments).
* Values may be numpy arrays; everything works element-wise.
"""
from __future__ import annotations

import math
import re
from fractions import Fraction
from functools import lru_cache, wraps
from typing import Any, Callable, Mapping

import numpy as np

from ..errors import CaseError, did_you_mean
from .units import (
    ANGLE,
    DIMENSIONLESS,
    Dim,
    apply_factor,
    check_dim,
    dim_div,
    dim_mul,
    dim_name,
    example_for,
    is_unit_symbol,
    parse_number,
    parse_quantity,
    parse_unit,
    unit_hint,
)

__all__ = ["Q", "evaluate", "free_names", "resolve", "FUNCTIONS", "CONSTANTS"]


# =============================================================================================
# Quantity


def _is_angle_like(dim: Dim) -> bool:
    return tuple(dim[:3]) == (0, 0, 0)


def _sum_dim(a: Dim, b: Dim) -> Dim:
    """Dimension of a sum of compatible quantities: the angular one wins (``pi + 1 deg`` is an angle)."""
    if a == b or a[3] != 0:
        return a
    return b


def _scalar_bad(result, *inputs) -> bool:
    """A scalar result became NaN/inf although all inputs were finite."""
    if np.ndim(result) != 0:
        return False
    r = float(result)
    if math.isfinite(r):
        return False
    return all(np.ndim(x) == 0 and math.isfinite(float(x)) for x in inputs)


def _coerced(method: Callable) -> Callable:
    """An arithmetic operator of :class:`Q` taking the other operand as a Q (a plain number or
    array is dimensionless); NotImplemented for anything else, so that Python tries the other side."""
    @wraps(method)
    def op(self, other: Any):
        o = Q._coerce(other)
        if o is NotImplemented:
            return NotImplemented
        return method(self, o)
    return op


def _reflected(name: str) -> Callable:
    """The reflected operator (``2 * q``): the other operand made a Q, then its ``name`` with self."""
    def op(self, o: "Q"):
        return getattr(o, name)(self)
    op.__name__ = op.__qualname__ = name[:2] + "r" + name[2:]
    return _coerced(op)


class Q:
    """A quantity: SI ``value`` (float or numpy array) and dimension ``dim`` ``(L, M, T, A)``.

    Arithmetic with other ``Q`` or plain numbers (dimensionless) checks dimensions and raises
    :class:`CaseError` («несовместимые единицы: длина + угол»). Comparisons return numpy bool
    arrays (so ``Q`` is unhashable).
    """

    __slots__ = ("value", "dim")
    __array_ufunc__ = None  # ndarray (op) Q defers to Q's reflected operators
    __hash__ = None  # type: ignore[assignment]

    def __init__(self, value: Any, dim: Dim = DIMENSIONLESS):
        if isinstance(value, Q):
            raise TypeError("Q(value) expects a number or an array, not Q")
        if np.ndim(value) == 0:
            value = float(value)
        else:
            value = np.asarray(value)
            if value.dtype.kind not in "fb":
                value = value.astype(float)
        self.value = value
        d = tuple(int(x) for x in dim)
        if len(d) != 4:
            raise ValueError(f"dimension must have 4 components, got {dim!r}")
        self.dim: Dim = d  # type: ignore[assignment]

    # -- helpers ----------------------------------------------------------------------------
    @staticmethod
    def _coerce(other: Any) -> "Q":
        if isinstance(other, Q):
            return other
        if isinstance(other, (int, float, np.number, np.ndarray, list, tuple)) and not isinstance(other, bool):
            return Q(other, DIMENSIONLESS)
        return NotImplemented  # type: ignore[return-value]

    @property
    def is_scalar(self) -> bool:
        return np.ndim(self.value) == 0

    def to(self, unit: str):
        """The value expressed in ``unit`` (``Q(0.347, LENGTH).to("mm") == 347``)."""
        factor, dim = parse_unit(unit)
        if not check_dim(self.dim, dim):
            raise CaseError(f"нельзя выразить {dim_name(self.dim)} в «{unit}» ({dim_name(dim)})")
        return self.value / factor

    def __float__(self) -> float:
        if not self.is_scalar:
            raise TypeError("only a scalar Q converts to float")
        return float(self.value)

    def __repr__(self) -> str:
        return f"Q({self.value!r}, {self.dim!r})"

    def __str__(self) -> str:
        return f"{self.value} [{dim_name(self.dim)}]"

    # -- arithmetic -------------------------------------------------------------------------
    def _check_same(self, other: "Q", op: str) -> None:
        if not check_dim(self.dim, other.dim):
            hint = None
            if DIMENSIONLESS in (self.dim, other.dim):
                dimensional = other.dim if self.dim == DIMENSIONLESS else self.dim
                hint = ("числа внутри выражения безразмерны; укажите единицу, например "
                        f"«{example_for(dimensional)}»")
            raise CaseError(f"несовместимые единицы: {dim_name(self.dim)} {op} {dim_name(other.dim)}",
                            hint=hint)

    @_coerced
    def __add__(self, o: "Q") -> "Q":
        self._check_same(o, "+")
        return Q(self.value + o.value, _sum_dim(self.dim, o.dim))

    __radd__ = _reflected("__add__")

    @_coerced
    def __sub__(self, o: "Q") -> "Q":
        self._check_same(o, "−")
        return Q(self.value - o.value, _sum_dim(self.dim, o.dim))

    __rsub__ = _reflected("__sub__")

    @_coerced
    def __mul__(self, o: "Q") -> "Q":
        return Q(self.value * o.value, dim_mul(self.dim, o.dim))

    __rmul__ = _reflected("__mul__")

    @_coerced
    def __truediv__(self, o: "Q") -> "Q":
        with np.errstate(divide="ignore", invalid="ignore"):
            v = np.true_divide(self.value, o.value)
        if _scalar_bad(v, self.value, o.value):
            raise CaseError("деление на ноль")
        return Q(v, dim_div(self.dim, o.dim))

    __rtruediv__ = _reflected("__truediv__")

    @_coerced
    def __pow__(self, o: "Q") -> "Q":
        if not _is_angle_like(o.dim):
            raise CaseError(f"показатель степени должен быть безразмерным, а не «{dim_name(o.dim)}»")
        if self.dim == DIMENSIONLESS:
            with np.errstate(all="ignore"):
                v = np.power(np.asarray(self.value, dtype=float), o.value)
            if _scalar_bad(v, self.value, o.value):
                raise CaseError(f"не удалось возвести {_fmt(self.value)} в степень {_fmt(o.value)}")
            return Q(v, DIMENSIONLESS)
        if not o.is_scalar:
            raise CaseError("показатель степени размерной величины должен быть числом, а не массивом")
        x = float(o.value)
        fr = Fraction(x).limit_denominator(64)
        if abs(float(fr) - x) > 1e-12 * max(1.0, abs(x)):
            raise CaseError(f"нельзя возвести величину «{dim_name(self.dim)}» в степень {_fmt(x)}: "
                            "для размерной величины показатель должен быть рациональным")
        new = []
        for k, comp in enumerate(self.dim):
            c = comp * fr
            if c.denominator != 1:
                if k == 3:
                    c = Fraction(0)  # the angle pseudo-dimension cannot be fractional; drop it
                else:
                    raise CaseError(f"нельзя возвести величину «{dim_name(self.dim)}» в степень {fr}: "
                                    "получилась бы дробная размерность")
            new.append(int(c))
        with np.errstate(all="ignore"):
            v = np.power(np.asarray(self.value, dtype=float), float(fr))
        if _scalar_bad(v, self.value):
            raise CaseError(f"не удалось возвести {_fmt(self.value)} в степень {_fmt(x)}")
        return Q(v, tuple(new))  # type: ignore[arg-type]

    __rpow__ = _reflected("__pow__")

    def __neg__(self) -> "Q":
        return Q(-self.value, self.dim)

    def __pos__(self) -> "Q":
        return self

    def __abs__(self) -> "Q":
        return Q(np.abs(self.value), self.dim)

    # -- comparisons (element-wise, numpy bool arrays) -------------------------------------
    def _cmp(self, other: Any, op: str, fn: Callable) -> np.ndarray:
        o = Q._coerce(other)
        if o is NotImplemented:
            raise TypeError(f"cannot compare Q with {type(other).__name__}")
        self._check_same(o, op)
        return np.asarray(fn(self.value, o.value))

    def __lt__(self, other: Any) -> np.ndarray:
        return self._cmp(other, "<", np.less)

    def __le__(self, other: Any) -> np.ndarray:
        return self._cmp(other, "≤", np.less_equal)

    def __gt__(self, other: Any) -> np.ndarray:
        return self._cmp(other, ">", np.greater)

    def __ge__(self, other: Any) -> np.ndarray:
        return self._cmp(other, "≥", np.greater_equal)

    def __eq__(self, other: Any) -> np.ndarray:  # type: ignore[override]
        return self._cmp(other, "=", np.equal)

    def __ne__(self, other: Any) -> np.ndarray:  # type: ignore[override]
        return self._cmp(other, "≠", np.not_equal)


def _fmt(x: Any) -> str:
    if np.ndim(x) != 0:
        return "массив"
    return f"{float(x):g}"


# =============================================================================================
# Functions and constants

CONSTANTS: dict[str, Q] = {"pi": Q(math.pi), "π": Q(math.pi)}


def _need_dimensionless(fname: str, q: Q, *, angle_ok: bool) -> None:
    if angle_ok:
        if _is_angle_like(q.dim):
            return
        what = "угол или безразмерную величину"
    else:
        if check_dim(q.dim, DIMENSIONLESS):
            return
        what = "безразмерную величину"
    raise CaseError(f"функция {fname} ожидает {what}, а получила величину «{dim_name(q.dim)}»")


def _elementwise(fname: str, fn: Callable, q: Q, dim: Dim, domain: str | None = None) -> Q:
    with np.errstate(all="ignore"):
        v = fn(q.value)
    if _scalar_bad(v, q.value):
        where = f" (допустимо: {domain})" if domain else ""
        raise CaseError(f"аргумент функции {fname} вне области определения: {_fmt(q.value)}{where}")
    return Q(v, dim)


def _trig(fname: str, fn: Callable) -> Callable[[list[Q]], Q]:
    def f(args: list[Q]) -> Q:
        _need_dimensionless(fname, args[0], angle_ok=True)
        return _elementwise(fname, fn, args[0], DIMENSIONLESS)
    return f


def _arc(fname: str, fn: Callable, domain: str | None) -> Callable[[list[Q]], Q]:
    def f(args: list[Q]) -> Q:
        _need_dimensionless(fname, args[0], angle_ok=False)
        return _elementwise(fname, fn, args[0], ANGLE, domain)
    return f


def _plain(fname: str, fn: Callable, domain: str | None) -> Callable[[list[Q]], Q]:
    def f(args: list[Q]) -> Q:
        _need_dimensionless(fname, args[0], angle_ok=False)
        return _elementwise(fname, fn, args[0], DIMENSIONLESS, domain)
    return f


def _same_dims(fname: str, args: list[Q]) -> Dim:
    dim = args[0].dim
    for a in args[1:]:
        if not check_dim(a.dim, args[0].dim):
            raise CaseError(f"аргументы функции {fname} должны иметь одинаковую размерность; "
                            f"получено: {dim_name(args[0].dim)} и {dim_name(a.dim)}")
        dim = _sum_dim(dim, a.dim)
    return dim


def _atan2(args: list[Q]) -> Q:
    _same_dims("atan2", args)
    with np.errstate(all="ignore"):
        return Q(np.arctan2(args[0].value, args[1].value), ANGLE)


def _reduce(fname: str, fn: Callable) -> Callable[[list[Q]], Q]:
    def f(args: list[Q]) -> Q:
        dim = _same_dims(fname, args)
        v = args[0].value
        with np.errstate(all="ignore"):
            for a in args[1:]:
                v = fn(v, a.value)
        return Q(v, dim)
    return f


def _sqrt(args: list[Q]) -> Q:
    q = args[0]
    if any(c % 2 for c in q.dim[:3]):
        raise CaseError(f"квадратный корень из величины размерности «{dim_name(q.dim)}» не определён: "
                        "нечётная степень размерности")
    dim = tuple(c // 2 for c in q.dim[:3]) + ((q.dim[3] // 2) if q.dim[3] % 2 == 0 else 0,)
    return _elementwise("sqrt", np.sqrt, q, dim, "аргумент ≥ 0")  # type: ignore[arg-type]


def _abs(args: list[Q]) -> Q:
    return Q(np.abs(args[0].value), args[0].dim)


# name -> (min args, max args or None, implementation)
FUNCTIONS: dict[str, tuple[int, int | None, Callable[[list[Q]], Q]]] = {
    "sin": (1, 1, _trig("sin", np.sin)),
    "cos": (1, 1, _trig("cos", np.cos)),
    "tan": (1, 1, _trig("tan", np.tan)),
    "asin": (1, 1, _arc("asin", np.arcsin, "−1 ≤ x ≤ 1")),
    "acos": (1, 1, _arc("acos", np.arccos, "−1 ≤ x ≤ 1")),
    "atan": (1, 1, _arc("atan", np.arctan, None)),
    "atan2": (2, 2, _atan2),
    "sqrt": (1, 1, _sqrt),
    "abs": (1, 1, _abs),
    "min": (1, None, _reduce("min", np.minimum)),
    "max": (1, None, _reduce("max", np.maximum)),
    "hypot": (1, None, _reduce("hypot", np.hypot)),
    "exp": (1, 1, _plain("exp", np.exp, None)),
    "log": (1, 1, _plain("log", np.log, "x > 0")),
    "log10": (1, 1, _plain("log10", np.log10, "x > 0")),
}
# Russian textbook spellings
_ALIASES = {"tg": "tan", "arcsin": "asin", "arccos": "acos", "arctg": "atan", "arctan": "atan",
            "ln": "log", "lg": "log10"}
for _a, _t in _ALIASES.items():
    FUNCTIONS[_a] = FUNCTIONS[_t]


# =============================================================================================
# Tokenizer

_DIGITS = "0123456789"
_NUM_RE = re.compile(r"(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+\-]?[0-9]+)?")
_NUM_COMMA_RE = re.compile(r"[0-9]+,[0-9]+(?:[eE][+\-]?[0-9]+)?")
_SUPERSCRIPTS = "⁰¹²³⁴⁵⁶⁷⁸⁹⁻"
_SUP_DIGITS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻", "0123456789-")
# identifiers: a letter then letters/digits/underscores; superscripts are powers, not letters
_IDENT_RE = re.compile(rf"(?:(?![{_SUPERSCRIPTS}])[^\W\d])(?:(?![{_SUPERSCRIPTS}])\w)*")
_UNIT_ATOM_RE = re.compile(rf"(?:(?![{_SUPERSCRIPTS}])[^\W\d_])+|°|%")
_SUP_RE = re.compile(rf"[{_SUPERSCRIPTS}]+")
_UNIT_EXP_RE = re.compile(r"(?:\^|\*\*)(?:\(\s*-?\d+\s*\)|-?\d+)|[⁰¹²³⁴⁵⁶⁷⁸⁹⁻]+")
_OPS = ("**", "<=", ">=", "==", "!=", "+", "-", "−", "*", "·", "⋅", "×", "/", "^", "(", ")", ",",
        "<", ">", "≤", "≥", "≠")
_OP_CANON = {"**": "^", "−": "-", "·": "*", "⋅": "*", "×": "*", "≤": "<=", "≥": ">=", "≠": "!="}


class _Tok:
    __slots__ = ("kind", "val", "pos", "text", "q")

    def __init__(self, kind: str, val: Any, pos: int, text: str, q: Q | None = None):
        self.kind = kind   # "num", "name", "op", "end"
        self.val = val     # number token: the plain float; name: str; op: canonical op
        self.pos = pos     # 0-based char position
        self.text = text   # source text of the token
        self.q = q         # number token: the quantity (with its unit)

    def __repr__(self) -> str:  # pragma: no cover - debugging aid
        return f"_Tok({self.kind}, {self.text!r}@{self.pos})"


def _syntax(text: str, detail: str, pos: int | None = None, hint: str | None = None) -> CaseError:
    where = f" (позиция {pos + 1})" if pos is not None else ""
    return CaseError(f"синтаксическая ошибка в выражении «{text}»: {detail}{where}", hint=hint)


def _unit_extent(s: str, start: int) -> int:
    """End of the unit written right after a number at ``start`` (== start if there is none)."""
    k = start
    while k < len(s) and s[k] in " \t":
        k += 1
    m = _UNIT_ATOM_RE.match(s, k)
    if not m:
        return start
    if m.group() not in ("°", "%") and not is_unit_symbol(m.group()):
        return start
    # an identifier continuing with digits/underscore ("m2", "l_1") is not a unit
    ident = _IDENT_RE.match(s, k)
    if ident and ident.end() != m.end():
        return start
    if s.startswith("(", m.end()):
        return start  # "2 min(a, b)": a function call, not a unit
    e = m.end()
    while True:
        ex = _UNIT_EXP_RE.match(s, e)
        if ex:
            e = ex.end()
        if e < len(s) and s[e] in "*/·⋅" and not s.startswith("**", e):
            a = _UNIT_ATOM_RE.match(s, e + 1)
            if a:
                ident = _IDENT_RE.match(s, e + 1)
                if (a.group() in ("°", "%") or is_unit_symbol(a.group())) and \
                        not (ident and ident.end() != a.end()) and not s.startswith("(", a.end()):
                    e = a.end()
                    continue
        return e


@lru_cache(maxsize=4096)
def _tokenize(text: str) -> tuple[_Tok, ...]:
    s = text
    toks: list[_Tok] = []
    stack: list[str] = []  # "call" / "group" for open parentheses
    i = 0
    n = len(s)
    while i < n:
        c = s[i]
        if c.isspace():
            i += 1
            continue
        if c in _DIGITS or (c == "." and i + 1 < n and s[i + 1] in _DIGITS):
            m = None
            if "call" not in stack:
                m = _NUM_COMMA_RE.match(s, i)
            if m is None:
                m = _NUM_RE.match(s, i)
            assert m is not None
            num_text = m.group()
            value = float(num_text.replace(",", "."))
            j = m.end()
            e = _unit_extent(s, j)
            if e > j:
                unit_text = s[j:e].strip()
                try:
                    factor, dim = parse_unit(unit_text)
                except CaseError as err:
                    raise CaseError(f"{err.message} в выражении «{text}»", hint=err.hint) from None
                q = Q(apply_factor(value, factor), dim)
                toks.append(_Tok("num", value, i, s[i:e], q))
                i = e
            else:
                toks.append(_Tok("num", value, i, num_text, Q(value, DIMENSIONLESS)))
                i = j
            continue
        m = _IDENT_RE.match(s, i)
        if m:
            toks.append(_Tok("name", m.group(), i, m.group()))
            i = m.end()
            continue
        m = _SUP_RE.match(s, i)
        if m:  # "X6²" == "X6^2"
            try:
                k = int(m.group().translate(_SUP_DIGITS))
            except ValueError:
                raise _syntax(text, f"непонятный показатель степени «{m.group()}»", i) from None
            toks.append(_Tok("op", "^", i, m.group()))
            toks.append(_Tok("num", float(k), i, m.group(), Q(float(abs(k)))))
            if k < 0:  # "⁻¹": emit "^ -1" as "^", "-", "1"
                toks.insert(len(toks) - 1, _Tok("op", "-", i, "⁻"))
            i = m.end()
            continue
        for op in _OPS:
            if s.startswith(op, i):
                canon = _OP_CANON.get(op, op)
                if canon == "(":
                    stack.append("call" if toks and toks[-1].kind == "name" else "group")
                elif canon == ")" and stack:
                    stack.pop()
                toks.append(_Tok("op", canon, i, op))
                i += len(op)
                break
        else:
            hint = "десятичная дробь записывается через точку или запятую" if c in ";" else None
            raise _syntax(text, f"недопустимый символ «{c}»", i, hint)
    toks.append(_Tok("end", None, n, ""))
    return tuple(toks)


# =============================================================================================
# Parser -> tuple AST
#   ("const", Q, bare)  ("name", str, pos)  ("call", fname, (args...), pos)
#   ("neg", node)  ("bin", op, left, right, pos)  ("cmp", op, left, right, pos)

class _Parser:
    def __init__(self, text: str):
        self.text = text
        self.toks = _tokenize(text)
        self.i = 0

    def peek(self) -> _Tok:
        return self.toks[self.i]

    def take(self) -> _Tok:
        t = self.toks[self.i]
        self.i += 1
        return t

    def is_op(self, *ops: str) -> bool:
        t = self.peek()
        return t.kind == "op" and t.val in ops

    def err(self, detail: str, pos: int | None = None, hint: str | None = None) -> CaseError:
        return _syntax(self.text, detail, pos, hint)

    def parse(self) -> tuple:
        if self.peek().kind == "end":
            raise CaseError("пустое выражение", expected="число с единицей или выражение, например «0.347 m»")
        node = self.comparison()
        t = self.peek()
        if t.kind != "end":
            raise self.trailing(t)
        return node

    def trailing(self, t: _Tok) -> CaseError:
        prev = self.toks[self.i - 1] if self.i > 0 else None
        if t.kind == "op" and t.val == ")":
            return self.err("лишняя закрывающая скобка", t.pos)
        if t.kind == "op" and t.val == ",":
            return self.err("запятая вне вызова функции", t.pos,
                            "аргументы функции перечисляются через запятую внутри скобок: max(a, b); "
                            "десятичная дробь записывается через точку: 0.5")
        if t.kind == "name" and prev is not None and prev.kind == "num":
            hint = unit_hint(t.val)
            if hint:
                hint = f"если «{t.val}» — единица измерения: {hint}"
            else:
                hint = f"если «{t.val}» — множитель, поставьте знак умножения: «{prev.text}*{t.val}»"
            return self.err(f"после числа «{prev.text}» стоит «{t.val}» — это не единица измерения "
                            "и не знак операции", t.pos, hint)
        if t.kind == "name" and prev is not None and prev.kind == "op" and prev.val == ")" \
                and is_unit_symbol(t.val):
            return self.err(f"пропущен знак операции перед «{t.val}»", t.pos,
                            f"единица ставится только после числа; умножьте: «(…)*1 {t.val}»")
        return self.err(f"пропущен знак операции перед «{t.text}»", t.pos,
                        "операции записываются явно: «2*l_OA», а не «2 l_OA»")

    def comparison(self) -> tuple:
        left = self.additive()
        if self.is_op("<", "<=", ">", ">=", "==", "!="):
            t = self.take()
            right = self.additive()
            left = ("cmp", t.val, left, right, t.pos)
        return left

    def _left_assoc(self, operand, ops) -> tuple:
        """operand (op operand)*, grouped from the left: a − b − c = (a − b) − c."""
        left = operand()
        while self.is_op(*ops):
            t = self.take()
            right = operand()
            left = ("bin", t.val, left, right, t.pos)
        return left

    def additive(self) -> tuple:
        return self._left_assoc(self.term, ("+", "-"))

    def term(self) -> tuple:
        return self._left_assoc(self.unary, ("*", "/"))

    def unary(self) -> tuple:
        if self.is_op("-"):
            self.take()
            return ("neg", self.unary())
        if self.is_op("+"):
            self.take()
            return self.unary()
        return self.power()

    def power(self) -> tuple:
        base = self.primary()
        if self.is_op("^"):
            t = self.take()
            exp = self.unary()  # right-associative, allows 2^-1
            return ("bin", "^", base, exp, t.pos)
        return base

    def primary(self) -> tuple:
        t = self.peek()
        if t.kind == "num":
            self.take()
            return ("const", t.q, False)
        if t.kind == "name":
            self.take()
            if self.is_op("("):
                return self.call(t)
            return ("name", t.val, t.pos)
        if t.kind == "op" and t.val == "(":
            self.take()
            if self.is_op(")"):
                raise self.err("пустые скобки", t.pos)
            node = self.comparison()
            if not self.is_op(")"):
                nxt = self.peek()
                if nxt.kind == "end":
                    raise self.err("не закрыта скобка", t.pos)
                raise self.trailing(nxt)
            self.take()
            return node
        if t.kind == "end":
            raise self.err("выражение обрывается, ожидалось число, имя или «(»")
        if t.val == ")":
            prev = self.toks[self.i - 1] if self.i > 0 else None
            if prev is not None and prev.kind == "op" and prev.val in ("(", ","):
                raise self.err("пропущен аргумент", t.pos)
            raise self.err("ожидалось число, имя или «(» перед «)»", t.pos)
        raise self.err(f"неожиданный знак «{t.text}»", t.pos)

    def call(self, name_tok: _Tok) -> tuple:
        open_tok = self.take()  # "("
        args: list[tuple] = []
        if self.is_op(")"):
            self.take()
        else:
            while True:
                args.append(self.comparison())
                if self.is_op(","):
                    self.take()
                    continue
                if self.is_op(")"):
                    self.take()
                    break
                nxt = self.peek()
                if nxt.kind == "end":
                    raise self.err(f"не закрыта скобка после «{name_tok.val}»", open_tok.pos)
                raise self.trailing(nxt)
        return ("call", name_tok.val, tuple(args), name_tok.pos)


MAX_EXPR = 2000  # characters of one expression
MAX_NESTING = 64  # levels of parentheses


@lru_cache(maxsize=4096)
def _parse(text: str) -> tuple:
    """Parse ``text`` into an AST; a whole-text bare number becomes ``("const", Q, True)``."""
    stripped = text.strip()
    if not stripped:
        raise CaseError("пустое выражение", expected="число с единицей или выражение, например «0.347 m»")
    if len(stripped) > MAX_EXPR:
        raise CaseError(f"слишком длинное выражение ({len(stripped)} символов)",
                        expected=f"выражение не длиннее {MAX_EXPR} символов", got=stripped[:60] + "…")
    bare = parse_number(stripped)
    if bare is not None:
        return ("const", Q(bare), True)
    depth = 0
    for ch in stripped:
        depth += 1 if ch == "(" else -1 if ch == ")" else 0
        if depth > MAX_NESTING:
            raise CaseError("слишком глубокая вложенность скобок в выражении",
                            expected=f"не более {MAX_NESTING} уровней скобок", got=stripped[:60] + "…")
    try:
        return _Parser(stripped).parse()
    except RecursionError:
        raise _too_deep(stripped) from None
    except CaseError as err:
        # "0.45 kg m^2" (a unit with spaces) is a valid quantity although not a valid expression
        try:
            value, dim = parse_quantity(stripped)
        except CaseError:
            raise err from None
        return ("const", Q(value, dim), False)


# =============================================================================================
# Evaluation


def _lookup(name: str, names: Mapping[str, Any], text: str) -> Q:
    if name in names:
        v = names[name]
        if isinstance(v, Q):
            return v
        if isinstance(v, bool) or v is None or isinstance(v, str):
            raise CaseError(f"имя «{name}» не является числовой величиной", got=text)
        return Q(v, DIMENSIONLESS)
    if name in CONSTANTS:
        return CONSTANTS[name]
    if name in FUNCTIONS:
        raise CaseError(f"«{name}» — функция, после неё нужны скобки: {name}(…)", got=text)
    hint = did_you_mean(name, [*names.keys(), *CONSTANTS.keys()])
    msg = f"неизвестное имя «{name}»"
    where = f" (в выражении «{text}»)" if text != name else ""
    if hint:
        raise CaseError(f"{msg}; {hint.rstrip('?')}{where}", got=text)
    known = sorted(names.keys())
    shown = ", ".join(known[:12]) + (", …" if len(known) > 12 else "")
    raise CaseError(msg, got=text, hint=f"известные имена: {shown}" if known else None)


def _in_context(err: CaseError, text: str) -> CaseError:
    if f"«{text}»" in err.message:
        return err
    return CaseError(f"{err.message} (в выражении «{text}»)", expected=err.expected, got=None,
                     hint=err.hint)


def _eval(node: tuple, names: Mapping[str, Any], text: str) -> Q:
    kind = node[0]
    if kind == "const":
        return Q(node[1].value, node[1].dim)  # a copy: the AST is cached and shared
    if kind == "name":
        return _lookup(node[1], names, text)
    if kind == "neg":
        return -_eval(node[1], names, text)
    if kind == "bin":
        op, left, right = node[1], _eval(node[2], names, text), _eval(node[3], names, text)
        try:
            if op == "+":
                return left + right
            if op == "-":
                return left - right
            if op == "*":
                return left * right
            if op == "/":
                return left / right
            return left ** right
        except CaseError as e:
            raise _in_context(e, text) from None
    if kind == "cmp":
        op, left, right = node[1], _eval(node[2], names, text), _eval(node[3], names, text)
        fn = {"<": Q.__lt__, "<=": Q.__le__, ">": Q.__gt__, ">=": Q.__ge__,
              "==": Q.__eq__, "!=": Q.__ne__}[op]
        try:
            return Q(fn(left, right), DIMENSIONLESS)
        except CaseError as e:
            raise _in_context(e, text) from None
    if kind == "call":
        fname, arg_nodes = node[1], node[2]
        if fname not in FUNCTIONS:
            if fname in names:
                raise CaseError(f"«{fname}» не является функцией (в выражении «{text}»)",
                                hint=f"если это умножение, поставьте знак «*»: «{fname}*(…)»")
            hint = did_you_mean(fname, FUNCTIONS.keys())
            raise CaseError(f"неизвестная функция «{fname}» (в выражении «{text}»)",
                            hint=hint or "доступны: " + ", ".join(sorted(FUNCTIONS)))
        lo, hi, impl = FUNCTIONS[fname]
        if len(arg_nodes) < lo or (hi is not None and len(arg_nodes) > hi):
            need = str(lo) if lo == hi else (f"{lo}–{hi}" if hi is not None else f"не меньше {lo}")
            raise CaseError(f"функция {fname} принимает {need} арг., передано {len(arg_nodes)} "
                            f"(в выражении «{text}»)")
        args = [_eval(a, names, text) for a in arg_nodes]
        try:
            return impl(args)
        except CaseError as e:
            raise _in_context(e, text) from None
    raise AssertionError(f"unknown node {kind}")  # pragma: no cover


def _show(text: Any) -> str:
    return text if isinstance(text, str) else repr(text)


def evaluate(text: str | float | int, names: Mapping[str, Q], *, expected: Dim | None = None,
             bare_is: Dim | None = None) -> Q:
    """Evaluate a value of the case file.

    ``text`` is an expression string, a TOML number or a :class:`Q`. A whole-text bare number
    (or a TOML number) gets dimension ``bare_is`` (default dimensionless). If ``expected`` is
    given, the result must have that dimension (ignoring the angle component) and is returned
    with ``dim == expected``; otherwise :class:`CaseError` (``expected=`` the Russian name of the
    dimension with an example, ``got=`` the text).
    """
    if isinstance(text, Q):
        q = text
    elif isinstance(text, (bool, np.bool_)):
        raise CaseError("ожидалось число или выражение, получено логическое значение",
                        got=str(text).lower())
    elif isinstance(text, (int, float, np.integer, np.floating)):
        q = Q(float(text), bare_is if bare_is is not None else DIMENSIONLESS)
    elif isinstance(text, str):
        node = _parse(text)
        if node[0] == "const" and node[2]:
            q = Q(node[1].value, bare_is if bare_is is not None else DIMENSIONLESS)
        elif node[0] == "const":
            q = Q(node[1].value, node[1].dim)
        else:
            try:
                q = _eval(node, names, text.strip())
            except RecursionError:
                raise _too_deep(text) from None
    else:
        raise CaseError("ожидалось число или строка с выражением", got=repr(text))

    v = q.value
    if isinstance(v, (int, float, np.integer, np.floating)) and not math.isfinite(v):
        shown = _show(text).strip() if not isinstance(text, Q) else repr(text)
        raise CaseError("значение не является конечным числом (бесконечность или nan)",
                        expected="конечное число", got=shown[:200])
    if expected is not None:
        if not check_dim(q.dim, expected):
            shown = _show(text).strip() if not isinstance(text, Q) else repr(text)
            exp_text = f"{dim_name(expected)} (например, «{example_for(expected)}»)"
            hint = None
            if q.dim == DIMENSIONLESS and isinstance(text, str) and parse_number(text) is None:
                hint = ("числа внутри выражения безразмерны; укажите единицы, например "
                        f"«{example_for(expected)}»")
            raise CaseError(f"ожидается {exp_text}, получено «{shown}» — это {dim_name(q.dim)}",
                            expected=exp_text, got=shown, hint=hint)
        q = Q(q.value, expected)
    return q


def _collect(node: tuple, out: set[str]) -> None:
    kind = node[0]
    if kind == "name":
        out.add(node[1])
    elif kind == "neg":
        _collect(node[1], out)
    elif kind in ("bin", "cmp"):
        _collect(node[2], out)
        _collect(node[3], out)
    elif kind == "call":
        for a in node[2]:
            _collect(a, out)


def _names_in(text: Any) -> set[str]:
    if not isinstance(text, str):
        return set()
    out: set[str] = set()
    try:
        _collect(_parse(text), out)
    except RecursionError:
        raise _too_deep(text) from None
    return out


def _too_deep(text: str) -> CaseError:
    return CaseError("слишком сложное выражение (глубокая вложенность)",
                     expected="более простое выражение", got=text.strip()[:60] + "…")


def free_names(text: Any) -> set[str]:
    """Identifiers used as values in ``text`` (not functions, units or the constant ``pi``)."""
    return {n for n in _names_in(text) if n not in CONSTANTS}


def resolve(params: Mapping[str, object], *, expected: Mapping[str, Dim] | None = None,
            extra_names: Mapping[str, Q] | None = None) -> dict[str, Q]:
    """Evaluate parameter definitions in dependency order.

    ``params`` maps a name to an expression string, a number or a :class:`Q`; ``expected`` gives
    per-key dimensions (also used as ``bare_is``); ``extra_names`` are already known quantities.
    Returns the parameters (in the order of ``params``) as :class:`Q`. Errors are
    :class:`CaseError` with ``key`` = the parameter name: unknown names (with a did-you-mean hint),
    cycles («циклическая зависимость параметров: a → b → a»), dimension mismatches.
    """
    expected = expected or {}
    extra = dict(extra_names or {})
    deps: dict[str, list[str]] = {}
    for key, val in params.items():
        try:
            used = _names_in(val)
        except CaseError as e:
            raise e.with_context(key_prefix=key) from None
        mine: list[str] = []
        for n in sorted(used):
            if n in params:
                mine.append(n)
            elif n in extra or n in CONSTANTS or n in FUNCTIONS:
                continue  # (a bare function name is reported by evaluate)
            else:
                known = [*params.keys(), *extra.keys()]
                hint = did_you_mean(n, known)
                msg = f"неизвестное имя «{n}»" + (f"; {hint.rstrip('?')}" if hint else "")
                if _show(val).strip() != n:
                    msg += f" (в выражении «{_show(val).strip()}»)"
                raise CaseError(msg, key=key, got=_show(val),
                                hint=None if hint else "имя должно быть задано среди параметров варианта")
        deps[key] = mine

    order: list[str] = []
    state: dict[str, int] = {}  # 1 = in progress, 2 = done

    def visit(start: str) -> None:
        # iterative DFS keeping the current path for cycle reports
        path: list[str] = [start]
        iters = [iter(deps[start])]
        state[start] = 1
        while path:
            node = path[-1]
            nxt = next(iters[-1], None)
            if nxt is None:
                state[node] = 2
                order.append(node)
                path.pop()
                iters.pop()
                continue
            st = state.get(nxt, 0)
            if st == 2:
                continue
            if st == 1:
                cycle = path[path.index(nxt):] + [nxt]
                raise CaseError("циклическая зависимость параметров: " + " → ".join(cycle),
                                key=cycle[0],
                                hint="каждый параметр должен выражаться через уже определённые")
            state[nxt] = 1
            path.append(nxt)
            iters.append(iter(deps[nxt]))

    for key in params:
        if state.get(key, 0) == 0:
            visit(key)

    env: dict[str, Q] = dict(extra)
    for key in order:
        dim = expected.get(key)
        try:
            env[key] = evaluate(params[key], env, expected=dim, bare_is=dim)  # type: ignore[arg-type]
        except CaseError as e:
            raise e.with_context(key_prefix=key) from None
    return {key: env[key] for key in params}
