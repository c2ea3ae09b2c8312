"""Typed access to a parsed TOML case with precise Russian error messages.

Every value read through a :class:`Node` knows its key path (``links[2].mass``), so a mistake is
reported with the file, the key, what was expected and a hint, never with a traceback.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterable, Mapping

from markupsafe import Markup

from ..errors import CaseError, did_you_mean
from . import units as U
from .expr import Q, evaluate
from .text import MAX_TEXT, check_name, clip, inline_html


MAX_POSITIONS = 360  # [grid] positions (and extra): report positions, each with plans and tables
MAX_CYCLE_POINTS = 36_000  # [grid] cycle_points (0,01° steps); 3600 by default
MAX_INT = 1_000_000  # any count of a case without its own limit
MAX_ABS = 1e15  # any value of a case in SI units
_LIMITS = {tuple(U.LENGTH[:3]): 1e4, tuple(U.MASS[:3]): 1e9}  # lengths up to 10 km, masses up to 10⁶ t


@dataclass
class Node:
    """A table of the case file together with its key path."""

    data: Mapping[str, Any]
    path: str
    file: str

    def key(self, name: str) -> str:
        return f"{self.path}.{name}" if self.path else name

    def error(self, name: str | None, message: str, **kw) -> CaseError:
        return CaseError(message, file=self.file, key=self.key(name) if name else (self.path or None), **kw)

    def check_keys(self, allowed: Iterable[str], required: Iterable[str] = ()) -> None:
        allowed = list(allowed)
        for k in self.data:
            if k not in allowed:
                raise self.error(k, f"неизвестный ключ «{k}»",
                                 expected="один из ключей: " + ", ".join(allowed),
                                 hint=did_you_mean(k, allowed))
        for k in required:
            if k not in self.data:
                raise self.error(k, f"не задан обязательный ключ «{k}»",
                                 expected=f"ключ «{k}» в разделе [{self.path or 'верхний уровень'}]")

    def has(self, name: str) -> bool:
        return name in self.data

    def raw(self, name: str, default: Any = None) -> Any:
        return self.data.get(name, default)

    def table(self, name: str, required: bool = False) -> "Node":
        v = self.data.get(name)
        if v is None:
            if required:
                raise self.error(name, f"не задан раздел «{name}»", expected="таблица TOML")
            return Node({}, self.key(name), self.file)
        if not isinstance(v, Mapping):
            raise self.error(name, "ожидалась таблица", expected="таблица TOML ({…} или [раздел])",
                             got=_show(v))
        return Node(v, self.key(name), self.file)

    def tables(self, name: str) -> list["Node"]:
        v = self.data.get(name, [])
        if isinstance(v, Mapping):
            v = [v]
        if not isinstance(v, list) or not all(isinstance(x, Mapping) for x in v):
            raise self.error(name, "ожидался массив таблиц", expected=f"[[{name}]] … ", got=_show(v))
        return [Node(x, f"{self.key(name)}[{i}]", self.file) for i, x in enumerate(v)]

    def string(self, name: str, default: str | None = None, *, required: bool = False,
               choices: Iterable[str] | None = None) -> str | None:
        v = self.data.get(name)
        if v is None:
            if required:
                raise self.error(name, f"не задан обязательный ключ «{name}»", expected="строка")
            return default
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            v = _num_to_name(v)
        if not isinstance(v, str):
            raise self.error(name, "ожидалась строка", expected="строка в кавычках", got=_show(v))
        if choices is not None:
            choices = list(choices)
            if v not in choices:
                raise self.error(name, f"недопустимое значение «{v}»",
                                 expected="одно из: " + ", ".join(choices), got=v,
                                 hint=did_you_mean(v, choices))
        return v

    def name(self, name: str, default: str | None = None, *, required: bool = False,
              what: str = "имя") -> str | None:
        """A name (point, link, joint, label) checked against the safe pattern of
        :func:`reportgen.case.text.check_name`."""
        v = self.data.get(name)
        if v is None:
            if required:
                raise self.error(name, f"не задан обязательный ключ «{name}»", expected="строка")
            return default
        if isinstance(v, float) and not isinstance(v, bool):
            v = self.string(name)
        return check_name(v, file=self.file, key=self.key(name), what=what)

    def text(self, name: str, default: str | None = None) -> Markup | None:
        """Free text (a title, a note) as safe HTML (:func:`reportgen.case.text.inline_html`)."""
        v = self.string(name, default)
        if v is None:
            return None
        if len(v) > MAX_TEXT:
            raise self.error(name, f"слишком длинный текст ({len(v)} символов)",
                             expected=f"не более {MAX_TEXT} символов", got=clip(v, 60))
        return inline_html(v)

    def integer(self, name: str, default: int | None = None, *, minimum: int | None = None,
                maximum: int | None = None, required: bool = False) -> int | None:
        v = self.data.get(name)
        if v is None:
            if required:
                raise self.error(name, f"не задан обязательный ключ «{name}»", expected="целое число")
            return default
        if isinstance(v, bool) or not isinstance(v, int):
            raise self.error(name, "ожидалось целое число", expected="целое число, например 12", got=_show(v))
        if minimum is not None and v < minimum:
            raise self.error(name, f"значение {v} меньше допустимого", expected=f"целое число ≥ {minimum}", got=str(v))
        top = MAX_INT if maximum is None else maximum
        if v > top:
            raise self.error(name, f"значение {clip(v, 40)} больше допустимого (ограничение времени и памяти расчёта)",
                             expected=f"целое число ≤ {top}", got=clip(v, 40))
        return v

    def boolean(self, name: str, default: bool) -> bool:
        v = self.data.get(name, default)
        if not isinstance(v, bool):
            raise self.error(name, "ожидалось логическое значение", expected="true или false", got=_show(v))
        return v

    def quantity(self, name: str, dim: U.Dim, names: Mapping[str, Q], default: Any = None, *,
                 required: bool = False, positive: bool = False, nonnegative: bool = False) -> float | None:
        v = self.data.get(name, default)
        if v is None:
            if required:
                raise self.error(name, f"не задан обязательный ключ «{name}»",
                                 expected=f"{U.dim_name(dim)}, например \"{U.example_for(dim)}\"")
            return None
        return self.eval_value(v, name, dim, names, positive=positive, nonnegative=nonnegative)

    def eval_value(self, v: Any, name: str, dim: U.Dim, names: Mapping[str, Q], *,
                   positive: bool = False, nonnegative: bool = False) -> float:
        if isinstance(v, bool) or not isinstance(v, (int, float, str)):
            raise self.error(name, "ожидалось число или строка с единицами",
                             expected=f"{U.dim_name(dim)}, например \"{U.example_for(dim)}\"", got=_show(v))
        try:
            qv = evaluate(v, names, expected=dim, bare_is=dim)
        except CaseError as e:
            raise e.with_context(file=self.file, key_prefix=self.key(name)) from None
        x = float(qv.value)
        limit = _LIMITS.get(tuple(dim[:3]), MAX_ABS)
        if not abs(x) <= limit:
            raise self.error(name, "значение вне разумного диапазона",
                             expected=f"{U.dim_name(dim)} по модулю не больше {limit:g} (в единицах СИ)",
                             got=_show(v))
        if positive and not x > 0:
            raise self.error(name, "значение должно быть положительным",
                             expected=f"{U.dim_name(dim)} > 0", got=_show(v))
        if nonnegative and x < 0:
            raise self.error(name, "значение не может быть отрицательным",
                             expected=f"{U.dim_name(dim)} ≥ 0", got=_show(v))
        return x

    def vector(self, name: str, v: Any, dim: U.Dim, names: Mapping[str, Q]) -> tuple[float, float]:
        if not isinstance(v, list) or len(v) != 2:
            raise self.error(name, "ожидалась пара координат",
                             expected=f"[x, y], например [\"{U.example_for(dim)}\", 0]", got=_show(v))
        return (self.eval_value(v[0], f"{name}[0]", dim, names), self.eval_value(v[1], f"{name}[1]", dim, names))


def _num_to_name(v: float) -> str:
    return str(int(v)) if float(v).is_integer() else str(v)


def _show(v: Any) -> str:
    s = repr(v) if not isinstance(v, str) else f"\"{v}\""
    return s if len(s) < 80 else s[:77] + "…"
