"""External loads of the machine from the case file's ``[loads]`` table.

What is read (docs/case-format.md, «Нагрузки и динамика»):

* weights G_k of the links (``[[links]] weight``, default m_k·g, g from ``[loads] g`` or
  9.81 m/s²), acting at the link's centre of mass downwards (−y);
* ``[[loads.force]]`` on a point of a link: a constant vector ``F = [Fx, Fy]``; or a scalar law
  along ``direction`` ("x", "y", "-x", "-y" or an angle): a constant ``magnitude``, a ``table``
  [[s, F], …] interpolated piecewise linearly against an expression ``of`` over the kinematic
  columns (indicator or cutting diagram; with ``area`` the table gives a pressure and F = p·A),
  or several ``[[loads.force.stroke]]`` laws, each on its own ``phase`` of the cycle (the four
  strokes of an engine over 4π);
* ``[[loads.moment]]`` on a link: constant ``M``, a table against ``of`` (default q), strokes;
* ``against = "motion"``: the load opposes the motion of its point along ``direction`` (of its
  link for a moment): F = −|F|·sign(u·V_q), as F_сопр = −P·[V_qHx ≥ 0] of worksheet 000;
* ``when`` — one condition or a list of conditions (all must hold) over the kinematic columns,
  e.g. "vqx_H >= 0": the load acts only where they hold.

Everything is evaluated for a table of kinematic columns (dict of arrays, the columns of
:func:`reportgen.analysis.linkage.columns` plus ``[outputs.angles]``), vectorised:
:meth:`Loads.forces` and :meth:`Loads.moments` return every applied force (link, point, Fx, Fy)
and moment (link, M); :meth:`Loads.reduced` the reduced moment of each load by the principle of
virtual power (Жуковский; Артоболевский, гл. «Приведение сил»):

    M_пр = Σ (F_x x′_P + F_y y′_P) + Σ M_k φ′_k,     x′ = dx/dφ, φ′_k = dφ_k/dφ.

:func:`switching_points` gives the points of the cycle where a load law is not smooth (a condition
changes its value, ``against`` changes sign, a table breakpoint or jump is crossed, a stroke
begins): all brackets found on the cycle grid are refined together by the Illinois variant of
regula falsi (Dowell & Jarratt, BIT 11, 1971) with a bisection step every third iteration, one
vectorised kinematic evaluation per iteration, to ~4ε·|q|.
"""
from __future__ import annotations

import math
import re
from collections import OrderedDict
from collections.abc import MutableMapping
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, NamedTuple

import numpy as np

from ..case import units as U
from ..case.expr import Q, evaluate, free_names
from ..case.reader import Node
from ..errors import AssemblyError, CaseError, did_you_mean
from . import linkage as L

__all__ = [
    "ColumnEvaluator",
    "ColumnExpr",
    "Condition",
    "Table1D",
    "Piece",
    "Load",
    "Loads",
    "AppliedForce",
    "AppliedMoment",
    "read_loads",
    "LoadWorks",
    "cycle_of",
    "switching_points",
    "reduced_moment",
]

LOADS_KEYS = ["g", "weights", "force", "moment"]
FORCE_KEYS = ["name", "title", "link", "point", "F", "magnitude", "direction", "against", "when",
              "table", "of", "units", "area", "stroke", "phase"]
MOMENT_KEYS = ["name", "title", "link", "M", "table", "of", "units", "against", "when", "stroke",
               "phase"]
_NAME_RE = re.compile(r"^[^\W\d][\w.]*$")
_CMP_RE = re.compile(r"(<=|>=|<|>)")


# --------------------------------------------------------------------------------------------
# Kinematic columns at arbitrary q
# --------------------------------------------------------------------------------------------
class LazyColumns(MutableMapping):
    """Named kinematic columns made on first access by ``make(name)`` (then kept): a caller
    taking a few columns of a grid evaluation (a load's point, the centres of mass) does not
    pay for gathering the hundreds of others.  Columns may be added and replaced as in a
    dict."""

    __slots__ = ("_names", "_known", "_vals", "_make")

    def __init__(self, names, make: Callable[[str], np.ndarray]):
        self._names = list(names)
        self._known = set(self._names)
        self._vals: dict[str, np.ndarray] = {}
        self._make = make

    def __getitem__(self, k: str) -> np.ndarray:
        try:
            return self._vals[k]
        except KeyError:
            if k not in self._known:
                raise
        v = self._vals[k] = self._make(k)
        return v

    def __setitem__(self, k: str, v) -> None:
        if k not in self._known:
            self._known.add(k)
            self._names.append(k)
        self._vals[k] = v

    def __delitem__(self, k: str) -> None:
        self._known.remove(k)
        self._names.remove(k)
        self._vals.pop(k, None)

    def __contains__(self, k) -> bool:
        return k in self._known

    def __iter__(self):
        return iter(self._names)

    def __len__(self) -> int:
        return len(self._names)


class ColumnEvaluator:
    """Kinematic columns at arbitrary q: the columns of ``Study.at`` up to the analogs (points,
    links, prismatic pairs, ``[outputs.angles]``) without building a DataFrame.

    One kernel call per array of q; the last few results are cached by value, so J_II, J_II′
    and M_пр asked at the same points share one solution.
    """

    def __init__(self, study, size: int = 6):
        self.study = study
        self.model = study.model
        self._cache: OrderedDict = OrderedDict()
        self._size = size
        self.calls = 0

    def __call__(self, q) -> dict[str, np.ndarray]:
        q = np.ascontiguousarray(np.atleast_1d(np.asarray(q, dtype=np.float64)).ravel())
        key = (q.size, q.tobytes())
        hit = self._cache.get(key)
        if hit is not None:
            self._cache.move_to_end(key)
            return hit
        self.calls += 1
        cols = self._columns(q)
        cols.update(self.study._extra_angles(cols))
        self._cache[key] = cols
        if len(self._cache) > self._size:
            self._cache.popitem(last=False)
        return cols

    def _columns(self, q: np.ndarray) -> dict[str, np.ndarray]:
        """Columns of L.columns at q: points of the solved cycle grid are taken from it (the
        columns are element-wise, so a grid point gives the same numbers), the others solved on
        the branch of the cycle (a class III group is continued from the solved cycle, the same
        kinematics as Study.at and the report positions)."""
        gq = self.study.grid.cycle
        whole = q.size == gq.size and np.array_equal(q, gq)
        if whole:
            idx = None
            nhit = q.size
        else:
            idx = np.minimum(np.searchsorted(gq, q), gq.size - 1)
            hit = gq[idx] == q
            nhit = int(np.count_nonzero(hit))
        grid = None
        if nhit:
            try:
                grid = self.study._cycle_columns
            except AssemblyError:       # the whole cycle does not assemble: the points alone
                grid = None
        if grid is None:
            return self._solved(q)
        if whole:                       # the cycle grid itself: its columns (not copied)
            cols = LazyColumns(grid, grid.__getitem__)
            cols["q"] = q.copy()
            return cols
        if nhit == q.size:
            cols = LazyColumns(grid, lambda k: grid[k][idx])
            cols["q"] = q.copy()
            return cols
        miss = ~hit
        if nhit == 0:
            return self._solved(q)
        rest = self._solved(q[miss])
        hidx = idx[hit]

        def merged(k):
            c = np.empty(q.size)
            c[miss] = rest[k]
            c[hit] = grid[k][hidx]
            return c

        return LazyColumns(rest, merged)

    def _solved(self, q: np.ndarray) -> LazyColumns:
        """The columns of ``L.columns`` at positions solved on the branch, each made when first
        asked for (``L.column_maker``: the same numbers)."""
        names, make = L.column_maker(self.model, self.study._solve_on_branch(q), grid=False)
        return LazyColumns(names, make)

    def names(self) -> list[str]:
        """Names of the columns (evaluated at the start of the grid)."""
        return list(self(np.array([self.study.grid.start])))


def _column_dims(study) -> Callable[[str], U.Dim]:
    from .study import column_dims
    qdim = study.qdim
    return lambda name: column_dims(name, qdim)


# --------------------------------------------------------------------------------------------
# Expressions and conditions over the columns
# --------------------------------------------------------------------------------------------
class ColumnExpr:
    """A unit-aware expression over the kinematic columns and the parameters
    (``"x_B"``, ``"l_OA + l_AB - x_B"``), evaluated element-wise on arrays."""

    def __init__(self, text: Any, node: Node, key: str, params: Mapping[str, Q],
                 columns: list[str], dim_of: Callable[[str], U.Dim], bare_is: U.Dim | None = None):
        if isinstance(text, bool) or not isinstance(text, (str, int, float)):
            raise node.error(key, "ожидалось выражение над столбцами кинематики",
                             expected="например \"vqx_H\" или \"l_OA + l_AB - x_B\"", got=repr(text))
        self.text = text if isinstance(text, str) else repr(text)
        self.raw = text
        self.node, self.key = node, key
        self.params = params
        self.bare_is = bare_is
        try:
            used = free_names(text) if isinstance(text, str) else set()
        except CaseError as e:
            raise e.with_context(file=node.file, key_prefix=node.key(key)) from None
        self.used = sorted(n for n in used if n not in params)
        for n in self.used:
            if n not in columns:
                raise node.error(key, f"неизвестное имя «{n}» в выражении «{self.text}»",
                                 expected="столбец кинематики (x_P, vqx_P, phi_k, wq_k, s_J …) "
                                          "или параметр из [parameters]",
                                 hint=did_you_mean(n, list(columns) + list(params)))
        self._dims = {n: dim_of(n) for n in self.used}
        probe = {n: np.full(1, 0.5) for n in self.used}
        with np.errstate(all="ignore"):
            self.dim = self._eval(probe).dim

    def _eval(self, cols: Mapping[str, np.ndarray]) -> Q:
        env = dict(self.params)
        for n in self.used:
            env[n] = Q(cols[n], self._dims[n])
        try:
            return evaluate(self.raw, env, bare_is=self.bare_is)
        except CaseError as e:
            raise e.with_context(file=self.node.file, key_prefix=self.node.key(self.key)) from None

    def __call__(self, cols: Mapping[str, np.ndarray]) -> np.ndarray:
        n = len(cols["q"])
        v = np.asarray(self._eval(cols).value, dtype=float)
        return np.broadcast_to(v, (n,)).astype(float, copy=True) if v.shape != (n,) else v


class Condition:
    """``lhs op rhs`` with op one of >=, >, <=, <.  g = lhs − rhs (or rhs − lhs for < and <=)
    is continuous where the columns are, so its sign changes are the switching points; the
    condition holds where g ≥ 0 (g > 0 for a strict inequality)."""

    def __init__(self, text: Any, node: Node, key: str, params, columns, dim_of):
        if not isinstance(text, str):
            raise node.error(key, "условие задаётся строкой", expected="например \"vqx_H >= 0\"",
                             got=repr(text))
        parts = _CMP_RE.split(text)
        if len(parts) != 3:
            raise node.error(key, "условие должно содержать одно сравнение (>=, >, <=, <)",
                             expected="например \"vqx_H >= 0\" или \"x_H > 2.2 m\"", got=text)
        lhs, op, rhs = (p.strip() for p in parts)
        self.text, self.op = text, op
        self.lhs = ColumnExpr(lhs, node, key, params, columns, dim_of)
        self.rhs = ColumnExpr(rhs, node, key, params, columns, dim_of, bare_is=self.lhs.dim)
        if not U.check_dim(self.lhs.dim, self.rhs.dim):
            raise node.error(key, f"в условии «{text}» сравниваются величины разной размерности",
                             expected=f"{U.dim_name(self.lhs.dim)} справа и слева",
                             got=f"{U.dim_name(self.lhs.dim)} и {U.dim_name(self.rhs.dim)}")
        self.sign = 1.0 if op in (">=", ">") else -1.0
        self.strict = op in (">", "<")

    def g(self, cols) -> np.ndarray:
        """The switching function sign·(lhs − rhs) of a ``when`` condition: the load acts where it
        is positive (zero included unless strict)."""
        return self.sign * (self.lhs(cols) - self.rhs(cols))

    def holds(self, cols) -> np.ndarray:
        """Where the condition holds: g > 0 (strict) or g ≥ 0."""
        g = self.g(cols)
        return g > 0 if self.strict else g >= 0


# --------------------------------------------------------------------------------------------
# Tables
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Table1D:
    """Piecewise-linear y(x) through the rows (x nondecreasing); a repeated x is a jump (the
    value right of it is the later row).  Outside [x₀, x_n] the end values are kept, and
    :meth:`outside` tells by how much an abscissa leaves the table."""

    x: np.ndarray
    y: np.ndarray

    def __call__(self, s) -> np.ndarray:
        s = np.asarray(s, dtype=float)
        x, y = self.x, self.y
        i = np.clip(np.searchsorted(x, s, side="right") - 1, 0, x.size - 2)
        x0, x1 = x[i], x[i + 1]
        h = x1 - x0
        t = np.where(h > 0, (s - x0) / np.where(h > 0, h, 1.0), 1.0)
        t = np.clip(t, 0.0, 1.0)
        return y[i] + t * (y[i + 1] - y[i])

    @property
    def breakpoints(self) -> np.ndarray:
        """The table's distinct arguments (its corners: breaks of the piecewise-linear law)."""
        return np.unique(self.x)

    def outside(self, s) -> float:
        """How far the arguments ``s`` reach beyond the table's range (0 inside)."""
        s = np.asarray(s, dtype=float)
        if s.size == 0:
            return 0.0
        return float(max(self.x[0] - s.min(), s.max() - self.x[-1], 0.0))


def _unit_factor(node: Node, key: str, text: Any, dim: U.Dim) -> float:
    try:
        q = evaluate(f"1 {text}" if isinstance(text, str) else text, {})
    except CaseError as e:
        raise e.with_context(file=node.file, key_prefix=node.key(key)) from None
    if not U.check_dim(q.dim, dim):
        raise node.error(key, f"единица «{text}» не подходит", expected=U.dim_name(dim) +
                         f", например «{U.example_for(dim).split(' ', 1)[-1]}»", got=str(text))
    return float(q.value)


def read_table(node: Node, key: str, xdim: U.Dim, ydim: U.Dim, units: Any = None,
               names: Mapping[str, Q] | None = None) -> Table1D:
    """Rows [[x, y], …]: numbers (SI, or in ``units = [ux, uy]``) or strings with units, which
    may use the case's ``[parameters]`` (``names``): ``["180 deg", "T_e"]``."""
    rows = node.raw(key)
    if not isinstance(rows, list) or not 2 <= len(rows) <= 100_000:
        raise node.error(key, "таблица должна содержать не менее двух строк [x, y]",
                         expected=f"{key} = [[x1, y1], [x2, y2], …]", got=repr(rows)[:60])
    fx = fy = 1.0
    if units is not None:
        if not (isinstance(units, list) and len(units) == 2):
            raise node.error("units", "ожидались единицы двух столбцов таблицы",
                             expected="units = [\"mm\", \"MPa\"]", got=repr(units))
        fx = _unit_factor(node, "units[0]", units[0], xdim)
        fy = _unit_factor(node, "units[1]", units[1], ydim)
    xs, ys = [], []
    for i, r in enumerate(rows):
        if not (isinstance(r, list) and len(r) == 2):
            raise node.error(f"{key}[{i}]", "строка таблицы — пара значений [x, y]",
                             expected="[0.0, 1200]", got=repr(r))
        vals = []
        for j, (cell, dim, f) in enumerate(((r[0], xdim, fx), (r[1], ydim, fy))):
            if isinstance(cell, (int, float)) and not isinstance(cell, bool):
                # through eval_value too: a finite number within the range of its kind
                vals.append(node.eval_value(float(cell) * f, f"{key}[{i}][{j}]", dim, {}))
            else:
                vals.append(node.eval_value(cell, f"{key}[{i}][{j}]", dim, names or {}))
        xs.append(vals[0])
        ys.append(vals[1])
    x, y = np.array(xs), np.array(ys)
    if np.any(np.diff(x) < 0):
        k = int(np.flatnonzero(np.diff(x) < 0)[0]) + 1
        raise node.error(f"{key}[{k}]", "абсциссы таблицы должны идти по неубыванию "
                         "(повтор абсциссы — скачок)", expected=f"x ≥ {x[k - 1]:.6g}", got=f"{x[k]:.6g}")
    if np.any((x[2:] == x[1:-1]) & (x[1:-1] == x[:-2])):
        raise node.error(key, "одна абсцисса повторена более двух раз", expected="не более двух строк с одним x (скачок)")
    if x[-1] == x[0]:
        raise node.error(key, "все абсциссы таблицы одинаковы", expected="возрастающие значения x")
    return Table1D(x, y)


# --------------------------------------------------------------------------------------------
# Loads
# --------------------------------------------------------------------------------------------
@dataclass
class Piece:
    """One law of a scalar load: on ``phase`` = [φ_a, φ_b) of the cycle (relative to its start;
    None: everywhere) the value is ``const`` or ``table(of)``."""

    name: str
    phase: tuple[float, float] | None
    const: float | None = None
    table: Table1D | None = None
    of: ColumnExpr | None = None
    node: Node | None = field(default=None, repr=False)

    def value(self, cols) -> np.ndarray:
        """The piece's value at the columns: its table at its argument, or its constant."""
        if self.table is not None:
            return self.table(self.of(cols))
        return np.full(len(cols["q"]), float(self.const))


class AppliedForce(NamedTuple):
    """An applied force over the positions: its name, link, point and components F_x, F_y."""
    name: str
    link: str
    point: str
    Fx: np.ndarray
    Fy: np.ndarray


class AppliedMoment(NamedTuple):
    """An applied moment over the positions: its name, link and value M."""
    name: str
    link: str
    M: np.ndarray


@dataclass
class Load:
    """One applied load.  kind: "weight" | "force" | "moment".

    Force: a constant ``vector`` (Fx, Fy), or a scalar law (``pieces``) times ``area`` along the
    unit vector ``u``.  Moment: a scalar law.  ``against``: the value is −|v|·sign(u·V_q) (force)
    or −|v|·sign(φ′_k) (moment).  ``when``: conditions that must all hold.
    """

    name: str
    title: str
    kind: str
    link: str
    point: str | None = None
    vector: tuple[float, float] | None = None
    u: tuple[float, float] | None = None
    pieces: list[Piece] = field(default_factory=list)
    area: float | None = None
    against: bool = False
    when: list[Condition] = field(default_factory=list)
    node: Node | None = field(default=None, repr=False)
    direction_text: str = ""

    def scalar(self, cols, phase: np.ndarray) -> np.ndarray:
        """The scalar law (value along u for a force, the moment for a moment)."""
        v = np.zeros(len(cols["q"]))
        for p in self.pieces:
            if p.phase is None:
                v = p.value(cols)
            else:
                m = (phase >= p.phase[0]) & (phase < p.phase[1])
                if np.any(m):
                    v = np.where(m, p.value(cols), v)
        if self.area is not None:
            v = v * self.area
        if self.against:
            v = -np.abs(v) * np.sign(self.motion(cols))
        return v

    def motion(self, cols) -> np.ndarray:
        """u·V_q of the point (force) or φ′_k (moment): the sign of the motion the load opposes."""
        if self.kind == "moment":
            return cols["wq_" + self.link]
        return self.u[0] * cols["vqx_" + self.point] + self.u[1] * cols["vqy_" + self.point]

    def mask(self, cols) -> np.ndarray | None:
        """Where the load acts: all its ``when`` conditions hold (None: everywhere)."""
        if not self.when:
            return None
        m = np.ones(len(cols["q"]), dtype=bool)
        for c in self.when:
            m &= c.holds(cols)
        return m

    def force(self, cols, phase) -> tuple[np.ndarray, np.ndarray]:
        """F_x, F_y of the load at the columns: its constant vector, or its value along its
        direction u; zero where it does not act."""
        n = len(cols["q"])
        if self.vector is not None:
            Fx, Fy = np.full(n, self.vector[0]), np.full(n, self.vector[1])
        else:
            v = self.scalar(cols, phase)
            Fx, Fy = v * self.u[0], v * self.u[1]
        m = self.mask(cols)
        if m is not None:
            Fx, Fy = np.where(m, Fx, 0.0), np.where(m, Fy, 0.0)
        return Fx, Fy

    def moment(self, cols, phase) -> np.ndarray:
        """The moment M of the load at the columns, zero where it does not act."""
        M = self.scalar(cols, phase)
        m = self.mask(cols)
        return M if m is None else np.where(m, M, 0.0)

    def reduced(self, cols, phase) -> np.ndarray:
        """M_пр of this load: F_x x′ + F_y y′ (force) or M φ′_k (moment)."""
        if self.kind == "moment":
            return self.moment(cols, phase) * cols["wq_" + self.link]
        if self.vector is not None and not self.when:
            # a constant vector (a weight): the same products without arrays of it
            return self.vector[0] * cols["vqx_" + self.point] + self.vector[1] * cols["vqy_" + self.point]
        Fx, Fy = self.force(cols, phase)
        return Fx * cols["vqx_" + self.point] + Fy * cols["vqy_" + self.point]

    # switching functions: continuous g(cols) whose sign changes are the points where the law
    # is not smooth, each with the phase interval where it matters (None: everywhere)
    def switching_functions(self) -> list[tuple[Callable, tuple[float, float] | None]]:
        """The functions whose zeros break the load's law (its conditions, the reversal of motion it
        resists, the corners of its tables), each with its phase, so that the integrals over the
        cycle split there."""
        out: list[tuple[Callable, tuple[float, float] | None]] = []
        for c in self.when:
            out.append((c.g, None))
        if self.against:
            out.append((self.motion, None))
        for p in self.pieces:
            if p.table is not None:
                for xb in p.table.breakpoints:
                    out.append((lambda cols, of=p.of, xb=xb: of(cols) - xb, p.phase))
        return out

    @property
    def closed_form(self) -> bool:
        """Is the load constant between its switching points (a vector, or constant laws with
        ``when``/``against``/phases), so that its work has a closed form (:class:`LoadWorks`)?"""
        return self.vector is not None or all(p.table is None for p in self.pieces)

    def work_coordinates(self, cols) -> list[np.ndarray]:
        """The coordinates whose differences times the load give its work: x_P, y_P of the
        force's point, φ_k of the moment's link."""
        if self.kind == "moment":
            return [cols["phi_" + self.link]]
        return [cols["x_" + self.point], cols["y_" + self.point]]

    def components(self, cols, phase) -> list[np.ndarray]:
        """The load's components along :meth:`work_coordinates`: Fx, Fy or M."""
        if self.kind == "moment":
            return [self.moment(cols, phase)]
        return list(self.force(cols, phase))

    def phase_breaks(self) -> list[float]:
        """The generalised coordinates where the load's pieces (its strokes or phases) begin and
        end."""
        out = []
        for p in self.pieces:
            if p.phase is not None:
                out += [p.phase[0], p.phase[1]]
        return out


@dataclass
class Loads:
    """All loads of a case; ``cycle_start``/``cycle_length`` define the phase of a stroke."""

    g: float
    loads: list[Load]
    cycle_start: float
    cycle_length: float
    params: Mapping[str, Q] = field(default_factory=dict, repr=False)
    _last_phase: tuple | None = field(default=None, init=False, repr=False, compare=False)

    def phase(self, cols) -> np.ndarray:
        """q reduced into [0, Φ) relative to the start of the cycle (the last one is kept: the
        forces, the moments and the reduced moments of one column table ask for the same)."""
        q = cols["q"]
        last = self._last_phase
        if last is not None and last[0] is q:
            return last[1]
        ph = np.mod(np.asarray(q, dtype=float) - self.cycle_start, self.cycle_length)
        self._last_phase = (q, ph)
        return ph

    @property
    def names(self) -> list[str]:
        """The loads' names in the case's order."""
        return [ld.name for ld in self.loads]

    def forces(self, cols) -> list[AppliedForce]:
        """Every applied force (weights included): name, link, point, Fx, Fy arrays [N]."""
        ph = self.phase(cols)
        return [AppliedForce(ld.name, ld.link, ld.point, *ld.force(cols, ph))
                for ld in self.loads if ld.kind != "moment"]

    def moments(self, cols) -> list[AppliedMoment]:
        """Every applied moment: name, link, M array [N·m] (counter-clockwise positive)."""
        ph = self.phase(cols)
        return [AppliedMoment(ld.name, ld.link, ld.moment(cols, ph))
                for ld in self.loads if ld.kind == "moment"]

    def reduced(self, cols) -> dict[str, np.ndarray]:
        """Reduced moment of each load [N·m] (virtual power, see the module docstring)."""
        ph = self.phase(cols)
        return {ld.name: ld.reduced(cols, ph) for ld in self.loads}

    def table_ranges(self, cols) -> list[tuple[Load, Piece, float]]:
        """Loads whose table abscissa leaves the table on its phase: (load, piece, by how much)."""
        if all(p.table is None for ld in self.loads for p in ld.pieces):
            return []
        ph = self.phase(cols)
        out = []
        for ld in self.loads:
            for p in ld.pieces:
                if p.table is None:
                    continue
                s = p.of(cols)
                if p.phase is not None:
                    s = s[(ph >= p.phase[0]) & (ph < p.phase[1])]
                if ld.when:
                    m = ld.mask(cols)
                    if p.phase is not None:
                        m = m[(ph >= p.phase[0]) & (ph < p.phase[1])]
                    s = s[m]
                d = p.table.outside(s)
                span = float(p.table.x[-1] - p.table.x[0])
                if d > 1e-9 * span:
                    out.append((ld, p, d))
        return out


class LoadWorks:
    """Works of the loads that are constant between their switching points, in closed form,
    on the nodes of a dynamic model (:class:`reportgen.analysis.flywheel.ClosedWork`).

    On a node interval [x_p, x_p+1] that contains no switching point such a force is a
    constant vector F_p and its reduced moment F_p·r_P′(φ) integrates exactly to
    F_p·(r_P(x_p+1) − r_P(x_p)) (the work of a constant force is the scalar product with the
    displacement of its point; a moment M_p·Δφ_k).  F_p is the load at the interval's ends when
    both agree and neither is a switching point (nor a cycle end); otherwise at its midpoint.
    The running sum is taken in Abel's form, A_k = F_k−1·r_k − F_0·r_0 − Σ_{p=1}^{k−1}(F_p −
    F_p−1)·r_p, so that between switches it is one difference, F·(r_k − r_0), not a sum of k
    rounded increments.  Loads given by tables are left to quadrature (``rest``).
    """

    def __init__(self, loads: Loads, evaluator, nodes: np.ndarray, breaks: np.ndarray):
        self.loads = loads
        self.ev = evaluator
        self.closed = [ld for ld in loads.loads if ld.closed_form]
        self.other = [ld for ld in loads.loads if not ld.closed_form]
        self.rest = self._rest if self.other else None
        nodes = np.asarray(nodes, dtype=float)
        n = nodes.size
        self.values = np.zeros(n)
        if not self.closed:
            self.Fp = np.zeros((0, n - 1))
            self.R = np.zeros((0, n))
            return
        cols = evaluator(nodes)
        V = self._components(cols)
        R = np.array([c for ld in self.closed for c in ld.work_coordinates(cols)])
        # link angles of single positions lie in (−π, π]: continuous along the nodes
        self._angle = np.array([ld.kind == "moment" for ld in self.closed for _ in ld.work_coordinates(cols)])
        if self._angle.any():
            R[self._angle] = np.unwrap(R[self._angle], axis=1)
        edge = np.isin(nodes, breaks)
        edge[0] = edge[-1] = True
        amb = edge[:-1] | edge[1:] | np.any(V[:, :-1] != V[:, 1:], axis=0)
        Fp = V[:, :-1].copy()
        if amb.any():
            mid = 0.5 * (nodes[:-1][amb] + nodes[1:][amb])
            Fp[:, amb] = self._components(evaluator(mid))
        self.Fp, self.R = Fp, R
        jumps = (Fp[:, 1:] - Fp[:, :-1]) * R[:, 1:-1]
        C = np.concatenate((np.zeros((Fp.shape[0], 1)), np.cumsum(jumps, axis=1)), axis=1)
        W = Fp * R[:, 1:] - (Fp[:, :1] * R[:, :1]) - C
        self.values[1:] = W.sum(axis=0)

    def _components(self, cols) -> np.ndarray:
        ph = self.loads.phase(cols)
        return np.array([c for ld in self.closed for c in ld.components(cols, ph)])

    def partial(self, i: np.ndarray, x: np.ndarray) -> np.ndarray:
        """∫_{nodes[i]}^{x} of the reduced moment of the closed-form loads (x in interval i)."""
        x = np.asarray(x, dtype=float)
        if not self.closed:
            return np.zeros(x.size)
        cols = self.ev(x)
        R = np.array([c for ld in self.closed for c in ld.work_coordinates(cols)])
        d = R - self.R[:, i]
        if self._angle.any():
            d[self._angle] = np.mod(d[self._angle] + math.pi, 2 * math.pi) - math.pi
        return np.einsum("ij,ij->j", self.Fp[:, i], d)

    def _rest(self, q) -> np.ndarray:
        """Reduced moment of the loads given by tables (integrated by quadrature)."""
        cols = self.ev(q)
        ph = self.loads.phase(cols)
        out = np.zeros(len(cols["q"]))
        for ld in self.other:
            out = out + ld.reduced(cols, ph)
        return out


def reduced_moment(loads: Loads, cols) -> dict[str, np.ndarray]:
    """M_пр of each load for a table of kinematic columns (see :meth:`Loads.reduced`)."""
    return loads.reduced(cols)


def cycle_of(study) -> tuple[float, float]:
    """Start and length of the machine cycle: the grid start and [dynamics] ``cycle``: k·π
    ("2pi", "4pi", "3*pi", "1080 deg", any angle that is a whole multiple of π) or a whole
    number of crank revolutions (``cycle = 3``)."""
    node = study.root.table("dynamics")
    raw = node.raw("cycle", "2pi")
    if isinstance(raw, int) and not isinstance(raw, bool):
        if raw < 1:
            raise node.error("cycle", "число оборотов за цикл должно быть положительным",
                             expected="целое число оборотов ≥ 1 или угол k·π", got=str(raw))
        return float(study.grid.start), 2.0 * math.pi * raw
    text = raw.strip() if isinstance(raw, str) else raw
    m = re.fullmatch(r"(\d+)\s*\*?\s*pi", text) if isinstance(text, str) else None
    if m:
        k = int(m.group(1))
    else:
        x = node.quantity("cycle", U.ANGLE, study.params, positive=True)
        k = int(round(x / math.pi))
        if k < 1 or abs(x - k * math.pi) > 1e-9 * max(x, 1.0):
            raise node.error("cycle", "длина цикла должна быть кратна π",
                             expected="\"2pi\", \"4pi\", \"3*pi\", \"1080 deg\" или число оборотов (cycle = 3)",
                             got=str(raw))
    if k < 1:
        raise node.error("cycle", "длина цикла должна быть положительной", expected="k·π, k ≥ 1", got=str(raw))
    return float(study.grid.start), k * math.pi


# --------------------------------------------------------------------------------------------
# Reading
# --------------------------------------------------------------------------------------------
def _link_node(study, name: str) -> Node | None:
    for ln in study.root.tables("links"):
        if str(ln.raw("name")) == name:
            return ln
    return None


def com_point(study, link) -> str:
    """Centre of mass of a link: ``com`` or its only point."""
    if link.com:
        return link.com
    if len(link.points) == 1:
        return next(iter(link.points))
    ln = _link_node(study, link.name)
    raise CaseError(f"у звена «{link.name}» задана масса или вес, но не указан центр масс",
                    file=str(study.spec.path), key=(ln.key("com") if ln else f"links.{link.name}.com"),
                    expected="com = имя одной из точек звена: " + ", ".join(link.points))


def _direction(node: Node, params) -> tuple[tuple[float, float], str]:
    raw = node.raw("direction")
    if raw is None:
        raise node.error("direction", "для силы, заданной величиной или таблицей, нужно направление",
                         expected="direction = \"x\", \"y\", \"-x\", \"-y\" или угол \"30 deg\"")
    if isinstance(raw, str) and raw.strip() in ("x", "+x", "-x", "y", "+y", "-y"):
        t = raw.strip()
        s = -1.0 if t.startswith("-") else 1.0
        return ((s, 0.0) if t.endswith("x") else (0.0, s)), t
    a = node.quantity("direction", U.ANGLE, params)
    return (math.cos(a), math.sin(a)), str(raw)


def _pieces(node: Node, kind: str, params, columns, dim_of, cycle_length: float,
            ydim: U.Dim, default_of: str | None) -> list[Piece]:
    vkey = "magnitude" if kind == "force" else "M"
    strokes = node.tables("stroke") if node.has("stroke") else []
    have = [k for k in (vkey, "table", "stroke") if node.has(k)]
    if kind == "force" and node.has("F"):
        if have:
            raise node.error("F", "сила задаётся либо вектором F, либо величиной/таблицей по направлению",
                             expected="F = [\"0 N\", \"-500 N\"] или magnitude/table + direction")
        return []
    if len(have) != 1:
        raise node.error(None if have else vkey,
                         "нужно ровно одно из: " + ", ".join((vkey, "table", "stroke")) +
                         (" (задано: " + ", ".join(have) + ")" if have else ""),
                         expected=f"{vkey} = постоянное значение, table = [[x, y], …] "
                                  "или [[…stroke]] с фазами цикла")

    def of_expr(n: Node) -> ColumnExpr:
        of = n.raw("of", default_of)
        if of is None:
            raise n.error("of", "для таблицы нужна абсцисса: выражение над столбцами кинематики",
                          expected="of = \"s_50\", \"x_H\" или \"l_OA + l_AB - x_B\"")
        return ColumnExpr(of, n, "of", params, columns, dim_of)

    def phase_of(n: Node) -> tuple[float, float] | None:
        ph = n.raw("phase")
        if ph is None:
            return None
        if not (isinstance(ph, list) and len(ph) == 2):
            raise n.error("phase", "фаза цикла задаётся двумя углами", expected="phase = [\"0 deg\", \"180 deg\"]",
                          got=repr(ph))
        a = n.eval_value(ph[0], "phase[0]", U.ANGLE, params)
        b = n.eval_value(ph[1], "phase[1]", U.ANGLE, params)
        tol = 1e-12 * cycle_length
        if not (-tol <= a < b <= cycle_length + tol):
            raise n.error("phase", "фаза должна лежать внутри цикла и иметь положительную длину",
                          expected=f"0 ≤ начало < конец ≤ {math.degrees(cycle_length):.0f}°",
                          got=f"[{math.degrees(a):.6g}°, {math.degrees(b):.6g}°]")
        return (max(a, 0.0), min(b, cycle_length))

    def piece(n: Node, name: str, parent_units) -> Piece:
        ph = phase_of(n)
        if n.has("table"):
            of = of_expr(n if n.has("of") else node)
            tab = read_table(n, "table", of.dim, ydim, n.raw("units", parent_units), params)
            return Piece(name, ph, table=tab, of=of, node=n)
        if n.has(vkey):
            return Piece(name, ph, const=n.quantity(vkey, ydim, params), node=n)
        raise n.error(vkey, f"для этапа не задан закон: {vkey} или table",
                      expected=f"{vkey} = постоянное значение или table = [[x, y], …]")

    if strokes:
        if node.has("phase"):
            raise node.error("phase", "при нескольких этапах (stroke) фаза задаётся у каждого этапа",
                             expected="phase внутри [[…stroke]]")
        out = []
        for i, sn in enumerate(strokes):
            sn.check_keys(["name", "title", "phase", "table", vkey, "units", "of"],
                          required=["phase"])
            out.append(piece(sn, sn.text("name", None) or sn.text("title", None) or f"{i + 1}",
                             node.raw("units")))
        out.sort(key=lambda p: p.phase[0])
        for a, b in zip(out, out[1:]):
            if b.phase[0] < a.phase[1] - 1e-12 * cycle_length:
                raise node.error("stroke", f"фазы этапов «{a.name}» и «{b.name}» перекрываются",
                                 expected="непересекающиеся интервалы phase")
        return out
    return [piece(node, "", None)]


def read_loads(study) -> Loads:
    """All loads of the case (weights of the links and ``[loads]``), with checked keys."""
    root = study.root
    node = root.table("loads")
    node.check_keys(LOADS_KEYS)
    params = study.params
    mech = study.mechanism
    start, length = cycle_of(study)
    g = node.quantity("g", U.ACCELERATION, params, default=9.81, positive=True)
    evaluator = ColumnEvaluator(study)
    columns = evaluator.names()
    dim_of = _column_dims(study)
    loads: list[Load] = []
    if node.boolean("weights", True):
        for link in mech.moving:
            if link.weight:
                loads.append(Load(f"G{link.name}", f"вес звена {link.name}", "weight", link.name,
                                  com_point(study, link), vector=(0.0, -float(link.weight)),
                                  direction_text="-y"))
    links = {l.name: l for l in mech.links}
    for kind, keys, default_prefix in (("force", FORCE_KEYS, "F"), ("moment", MOMENT_KEYS, "M")):
        for i, fn in enumerate(node.tables(kind)):
            fn.check_keys(keys, required=["link"] + (["point"] if kind == "force" else []))
            lname = fn.string("link", required=True)
            if lname not in links:
                raise fn.error("link", f"нет звена «{lname}»", expected="имя подвижного звена из [[links]]",
                               hint=did_you_mean(lname, [l.name for l in mech.moving]))
            if lname == "0":
                raise fn.error("link", "нагрузка на стойку не совершает работы", expected="подвижное звено")
            link = links[lname]
            name = fn.string("name", f"{default_prefix}{i + 1}")
            if not _NAME_RE.match(name):
                raise fn.error("name", f"имя нагрузки «{name}» не годится для имени столбца",
                               expected="буквы, цифры, «_» или «.», начиная с буквы (например \"Pпс\")")
            point = None
            if kind == "force":
                point = fn.string("point", required=True)
                if point not in link.points:
                    raise fn.error("point", f"точка «{point}» не принадлежит звену «{lname}»",
                                   expected="одна из точек: " + ", ".join(link.points),
                                   hint=did_you_mean(point, list(link.points)))
            area = fn.quantity("area", U.AREA, params, positive=True) if kind == "force" else None
            ydim = (U.PRESSURE if area is not None else U.FORCE) if kind == "force" else U.MOMENT
            pieces = _pieces(fn, kind, params, columns, dim_of, length, ydim,
                             "q" if kind == "moment" else None)
            vector = None
            u, dtext = None, ""
            if kind == "force" and fn.has("F"):
                vector = fn.vector("F", fn.raw("F"), U.FORCE, params)
                if area is not None:
                    raise fn.error("area", "площадь используется только с таблицей давления",
                                   expected="table давления и area")
            elif kind == "force":
                u, dtext = _direction(fn, params)
            against = fn.string("against", None, choices=["motion"]) == "motion"
            if against and vector is not None:
                raise fn.error("against", "против движения направляется сила, заданная величиной",
                               expected="magnitude (или table) + direction + against = \"motion\"")
            when_raw = fn.raw("when", [])
            when_list = when_raw if isinstance(when_raw, list) else [when_raw]
            when = [Condition(w, fn, f"when[{j}]" if isinstance(when_raw, list) else "when",
                              params, columns, dim_of) for j, w in enumerate(when_list)]
            title = fn.text("title", None) or (
                f"сила {name} в точке {point} звена {lname}" if kind == "force" else
                f"момент {name} на звене {lname}")
            if any(ld.name == name for ld in loads):
                raise fn.error("name", f"нагрузка «{name}» уже задана", expected="уникальное имя нагрузки")
            loads.append(Load(name, title, kind, lname, point, vector=vector, u=u, pieces=pieces,
                              area=area, against=against, when=when, node=fn, direction_text=dtext))
    return Loads(float(g), loads, start, length, params)


# --------------------------------------------------------------------------------------------
# Switching points
# --------------------------------------------------------------------------------------------
def _refine(evaluator, fns, which, a, b, fa, fb, maxiter: int = 200) -> np.ndarray:
    """Roots of fns[which[i]] in the brackets [a_i, b_i] (fa·fb ≤ 0), all at once."""
    a, b, fa, fb = (np.array(v, dtype=float) for v in (a, b, fa, fb))
    which = np.asarray(which)
    root = np.where(fa == 0, a, np.where(fb == 0, b, np.nan))
    done = ~np.isnan(root)
    tol = 4 * np.finfo(float).eps * np.maximum(np.abs(a), 1.0)
    for it in range(maxiter):
        act = np.flatnonzero(~done)
        if act.size == 0:
            break
        A, B, FA, FB = a[act], b[act], fa[act], fb[act]
        if it % 3 == 2:
            c = 0.5 * (A + B)
        else:
            c = B - FB * (B - A) / (FB - FA)
            lo, hi = np.minimum(A, B), np.maximum(A, B)
            bad = ~((c > lo) & (c < hi))
            c = np.where(bad, 0.5 * (A + B), c)
        cols = evaluator(c)
        fc = np.empty(act.size)
        for k in np.unique(which[act]):
            sel = which[act] == k
            fc[sel] = fns[k](cols)[sel]
        flip = fc * FB < 0
        A = np.where(flip, B, A)
        FA = np.where(flip, FB, np.where(it % 3 == 2, FA, 0.5 * FA))
        B, FB = c, fc
        a[act], b[act], fa[act], fb[act] = A, B, FA, FB
        zero = fc == 0
        conv = np.abs(B - A) <= tol[act]
        fin = zero | conv
        root[act[fin]] = B[fin]
        done[act[fin]] = True
    if not np.all(done):
        # cannot happen for a continuous function in a sign-change bracket
        rest = ~done
        root[rest] = 0.5 * (a[rest] + b[rest])
    return root


def _roots_in_cells(evaluator, fns, which, a, b, fa, fb, grid_cols) -> np.ndarray:
    """Roots of fns[which[i]] in the grid cells [a_i, b_i] (fa·fb ≤ 0).  A switching function is
    smooth inside a cell (the kinematic columns are): one evaluation at the Chebyshev points of
    every cell gives its interpolant (:func:`reportgen.core.quadrature.cell_fit`), resolved to
    rounding when its last coefficients are below 10⁻¹⁴ of the function's size on the grid, and
    the root of that polynomial is found by ``brentq`` to ~4ε·|q| without evaluating the
    kinematics again.  Cells not resolved so (a non-smooth expression, a near-singular position)
    and roots on a grid point go to :func:`_refine`."""
    from .roots import brentq
    from ..core.quadrature import CHEB_POINTS, cell_fit, cheb_points
    a, b, fa, fb = (np.asarray(v, dtype=float) for v in (a, b, fa, fb))
    which = np.asarray(which)
    root = np.full(a.size, np.nan)
    strict = np.flatnonzero(fa * fb < 0)
    if strict.size:
        cols = evaluator(cheb_points(a[strict], b[strict]).ravel())
        vals = np.empty((1, strict.size, CHEB_POINTS))
        tol = np.empty((1, strict.size))
        for k in np.unique(which[strict]):
            sel = which[strict] == k
            vals[0, sel] = fns[k](cols).reshape(strict.size, CHEB_POINTS)[sel]
            tol[0, sel] = 1e-14 * float(np.max(np.abs(fns[k](grid_cols))))
        for j, fit in zip(strict, cell_fit(a[strict], b[strict], vals, tol)):
            if fit is None:
                continue
            g0, g1 = fit(a[j])[0], fit(b[j])[0]
            if not g0 * g1 < 0:
                continue
            root[j] = brentq(lambda t, fit=fit: fit(t)[0], a[j], b[j],
                             xtol=4 * np.finfo(float).eps * max(abs(a[j]), 1.0), rtol=4 * np.finfo(float).eps)
    rest = np.flatnonzero(np.isnan(root))
    if rest.size:
        root[rest] = _refine(evaluator, fns, which[rest], a[rest], b[rest], fa[rest], fb[rest])
    return root


def switching_points(study, loads: Loads | None = None, grid: np.ndarray | None = None,
                     evaluator: ColumnEvaluator | None = None) -> np.ndarray:
    """Sorted q in [start, start + Φ) where some load law is not smooth.

    Sign changes of every switching function (conditions, ``against``, table breakpoints on
    their phases) on ``grid`` (default: the cycle grid with [grid] cycle_points per 2π) are
    refined by vectorised bracketed root finding; phase boundaries of strokes are added as they
    are.  A function that only touches zero changes no law and is ignored.
    """
    loads = loads if loads is not None else read_loads(study)
    evaluator = evaluator or ColumnEvaluator(study)
    a0, Phi = loads.cycle_start, loads.cycle_length
    if grid is None:
        m = len(study.grid.cycle) - 1
        n = int(round(m * Phi / (2 * math.pi)))
        grid = a0 + Phi * np.arange(n + 1) / n
    fns, phases = [], []
    extra: list[float] = []
    for ld in loads.loads:
        for f, ph in ld.switching_functions():
            fns.append(f)
            phases.append(ph)
        extra += [a0 + p for p in ld.phase_breaks()]
    out = list(extra)
    if fns:
        cols = evaluator(grid)
        ph_grid = np.mod(grid - a0, Phi)
        A, B, FA, FB, W = [], [], [], [], []
        for k, (f, ph) in enumerate(zip(fns, phases)):
            gv = f(cols)
            pos = gv >= 0
            idx = np.flatnonzero(pos[:-1] != pos[1:])
            if ph is not None and idx.size:
                lo, hi = ph
                keep = (ph_grid[idx] <= hi) & (ph_grid[idx] + (grid[idx + 1] - grid[idx]) >= lo)
                idx = idx[keep]
            if np.all(np.abs(gv) <= 1e-14 * max(1.0, float(np.max(np.abs(gv))))):
                continue
            A.append(grid[idx])
            B.append(grid[idx + 1])
            FA.append(gv[idx])
            FB.append(gv[idx + 1])
            W.append(np.full(idx.size, k))
        if A:
            A, B, FA, FB, W = (np.concatenate(v) for v in (A, B, FA, FB, W))
            if A.size:  # a grid point where g == 0 exactly is itself the root
                out += list(_roots_in_cells(evaluator, fns, W, A, B, FA, FB, cols))
    r = np.asarray(out, dtype=float)
    if r.size == 0:
        return r
    r = a0 + np.mod(r - a0, Phi)
    r = np.unique(r)
    r = r[(r > a0 + 1e-13 * Phi) & (r < a0 + Phi - 1e-13 * Phi)]
    # merge roots closer than rounding
    if r.size > 1:
        keep = np.concatenate(([True], np.diff(r) > 1e-13 * Phi))
        r = r[keep]
    return r
