"""Read a TOML case file: sections, parameters with units, overrides of a batch variant."""
from __future__ import annotations

import hashlib
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from markupsafe import Markup

from ..errors import CaseError
from ..registry import LINKAGE_SECTIONS, STANDALONE_SECTIONS, TASK_SECTIONS
from . import units as U
from . import synthesis as SY
from .expr import _IDENT_RE, Q, free_names, resolve
from .reader import Node
from .text import MAX_TEXT, clip, inline_html

TOP_KEYS = list(dict.fromkeys(["meta", "parameters", *LINKAGE_SECTIONS, "grid", "sketch", "fit", "outputs",
                                "loads", "report", "carrier", "actuator", *TASK_SECTIONS]))


@dataclass
class CaseSpec:
    """A parsed, not yet evaluated case: the raw tables, their source and parameter overrides."""

    path: Path
    data: dict
    overrides: dict[str, Any] = field(default_factory=dict)
    meta_overrides: dict[str, str] = field(default_factory=dict)

    @property
    def root(self) -> Node:
        return Node(self.data, "", str(self.path))

    @property
    def name(self) -> str:
        return self.path.stem

    def digest(self) -> str:
        h = hashlib.sha256(repr((sorted(_flat(self.data)), sorted(self.overrides.items()),
                                 sorted(self.meta_overrides.items()))).encode())
        return h.hexdigest()[:16]

    def parameters(self, fixed: Mapping[str, float] | None = None) -> dict[str, Q]:
        """Evaluate [parameters] (with overrides) to SI; ``fixed`` replaces the named parameters
        by values (used by fitting) keeping their dimensions."""
        node = self.root.table("parameters")
        raw = {k: self._param_value(k, v) for k, v in node.data.items()}
        raw.update(self.overrides)
        for k in raw:
            if not _IDENT_RE.fullmatch(str(k)) or len(str(k)) > 40:
                raise CaseError(f"недопустимое имя параметра «{str(k)[:60]}»", file=str(self.path),
                                key=f"parameters.{str(k)[:60]}",
                                expected="имя из букв, цифр и «_», начинающееся с буквы (не длиннее 40 символов), "
                                         "например l_OA")
        names = self._resolve(raw, {})
        if fixed:
            base = {k: Q(v, names[k].dim) for k, v in fixed.items()}
            names = self._resolve({k: v for k, v in raw.items() if k not in fixed}, base)
            names.update(base)
        return names

    _PARAM_KEYS = ("value", "title", "symbol")

    def _param_value(self, name, v):
        """The expression of a parameter written plainly (``l_OA = "0.1 m"``) or as a table with
        its Russian title and textbook symbol (``l_OA = { value = "0.1 m", title = "длина
        кривошипа", symbol = "l<sub>OA</sub>" }``)."""
        if not isinstance(v, Mapping):
            return v
        key = f"parameters.{str(name)[:60]}"
        extra = [k for k in v if k not in self._PARAM_KEYS]
        if extra or "value" not in v:
            raise CaseError(f"параметр «{str(name)[:60]}» задан таблицей без значения или с лишним ключом"
                            + (f" «{str(extra[0])[:40]}»" if extra else ""), file=str(self.path), key=key,
                            expected='{ value = "0.1 m", title = "длина кривошипа", symbol = "l<sub>OA</sub>" } '
                                     "(title и symbol необязательны)")
        for k in ("title", "symbol"):
            if k in v and (not isinstance(v[k], str) or len(v[k]) > MAX_TEXT):
                raise CaseError(f"«{k}» параметра «{str(name)[:60]}» должно быть строкой", file=str(self.path),
                                key=f"{key}.{k}", expected=f"строка до {MAX_TEXT} символов",
                                got=clip(repr(v[k]), 60))
        return v["value"]

    def parameter_texts(self) -> dict[str, tuple[Markup | None, Markup | None]]:
        """name → (Russian title, symbol) as safe HTML (escaped, inline whitelist) for the
        parameters written as tables; None where the case gives none."""
        out = {}
        for k, v in self.root.table("parameters").data.items():
            if isinstance(v, Mapping):
                self._param_value(k, v)
                out[k] = tuple(inline_html(v[t]) if v.get(t) else None for t in ("title", "symbol"))
        return out

    def _resolve(self, raw: dict, extra: dict[str, Q]) -> dict[str, Q]:
        """Resolve parameters; with ``[synthesis]`` first those it needs, then its results
        (``syn_*`` and aliases), then the parameters that use them."""
        def run(part, known):
            try:
                return resolve(part, extra_names=known)
            except CaseError as e:
                raise e.with_context(file=str(self.path), key_prefix="parameters") from None

        if not self.root.has("synthesis"):
            return run(raw, extra)
        node = SY.node_of(self.root)
        outs = SY.output_names(node)
        for k in outs & set(raw):
            raise node.error(None, f"псевдоним «{k}» совпадает с параметром из [parameters]",
                             expected="имя, не занятое в [parameters] (или удалите параметр)")
        late: set[str] = set()
        grew = True
        while grew:
            grew = False
            for k, v in raw.items():
                if k not in late and any(n.startswith("syn_") or n in outs or n in late for n in free_names(v)):
                    late.add(k)
                    grew = True
        early = run({k: v for k, v in raw.items() if k not in late}, extra)
        known = {**extra, **early}
        known.update(SY.parameters(node, known))
        rest = run({k: v for k, v in raw.items() if k in late}, known)
        out = {**early, **{k: v for k, v in known.items() if k not in extra}, **rest}
        return out

    def gravity(self, names) -> float:
        dyn = self.root.table("loads")
        return dyn.quantity("g", U.ACCELERATION, names, default="9.81 m/s^2", positive=True) if dyn.has("g") else 9.81


def _flat(d, prefix=""):
    if isinstance(d, Mapping):
        for k, v in d.items():
            yield from _flat(v, f"{prefix}.{k}")
    elif isinstance(d, list):
        for i, v in enumerate(d):
            yield from _flat(v, f"{prefix}[{i}]")
    else:
        yield (prefix, repr(d))


MAX_CASE_BYTES = 4 * 1024 * 1024  # a case file is a few kilobytes
MAX_DEPTH = 16  # nesting of tables and arrays in a case file


def read_toml(path: Path, *, what: str = "файл варианта") -> dict:
    """Parse a TOML file of the user (case, batch table) into a dict: every failure (missing
    file, a directory or a device, not UTF-8, too large, syntax, too deeply nested) is a
    :class:`CaseError`."""
    path = Path(path)
    if not path.exists():
        raise CaseError(f"{what} не найден", file=str(path),
                        expected="путь к файлу .toml (например, cases/ws000_six_bar.toml)")
    if not path.is_file():
        raise CaseError(f"{what}: указан не обычный файл (папка или устройство)", file=str(path),
                        expected="путь к файлу .toml")
    try:
        size = path.stat().st_size
        if size > MAX_CASE_BYTES:
            raise CaseError(f"{what} слишком большой ({size} байт)", file=str(path),
                            expected=f"не более {MAX_CASE_BYTES // 1024 // 1024} МБ")
        text = path.read_bytes().decode("utf-8")
    except UnicodeDecodeError:
        raise CaseError("файл не в кодировке UTF-8", file=str(path), expected="текст TOML в UTF-8") from None
    except OSError as e:
        raise CaseError(f"не удалось прочитать файл: {e.strerror or e}", file=str(path)) from None
    try:
        data = tomllib.loads(text)
    except RecursionError:
        raise CaseError("слишком глубокая вложенность таблиц или массивов", file=str(path),
                        expected=f"не более {MAX_DEPTH} уровней") from None
    except tomllib.TOMLDecodeError as e:
        raise CaseError(f"синтаксическая ошибка TOML: {e}", file=str(path),
                        expected="корректный TOML (строки в кавычках, [разделы], key = value)") from None
    _check_depth(data, str(path))
    return data


def _check_depth(data, file: str) -> None:
    """Reject nesting deeper than :data:`MAX_DEPTH` (iteratively: no recursion on the input)."""
    stack = [(data, 0)]
    while stack:
        v, d = stack.pop()
        if d > MAX_DEPTH:
            raise CaseError("слишком глубокая вложенность таблиц или массивов", file=file,
                            expected=f"не более {MAX_DEPTH} уровней")
        if isinstance(v, Mapping):
            stack.extend((x, d + 1) for x in v.values())
        elif isinstance(v, list):
            stack.extend((x, d + 1) for x in v)


def load_spec(path: str | Path, overrides: Mapping[str, Any] | None = None) -> CaseSpec:
    path = Path(path)
    data = read_toml(path, what="файл варианта")
    spec = CaseSpec(path, data, dict(overrides or {}))
    root = spec.root
    has_linkage = any(root.has(k) for k in LINKAGE_SECTIONS)
    only_tasks = [k for k in STANDALONE_SECTIONS if root.has(k)]
    # a linkage needs all four of its sections; a case without one holds at least one other task
    root.check_keys(TOP_KEYS, required=list(LINKAGE_SECTIONS) if has_linkage or not only_tasks else [])
    if overrides:
        params = spec.root.table("parameters").data
        for k in overrides:
            if k not in params:
                from ..errors import did_you_mean
                raise CaseError(f"вариант задаёт неизвестный параметр «{k}»", file=str(path), key=f"parameters.{k}",
                                expected="имя параметра из раздела [parameters] базового варианта",
                                hint=did_you_mean(k, list(params)))
    return spec
