"""A Study: one case with lazily computed, cached results (pandas DataFrames and scalars).

Asking for ``kinematics`` solves the linkage only; the task analyses (``dynamics``, ``forces``, …,
one line each in :mod:`reportgen.registry`) are created on first use by name and compute what they
need first.  ``computed`` records which stages ran, so a report can be checked to compute only what
its scenes need.
"""
from __future__ import annotations

import importlib
import math
from contextlib import contextmanager
from dataclasses import dataclass
from functools import cached_property, lru_cache
from pathlib import Path
from collections.abc import MutableMapping
from typing import Any, Mapping

import numpy as np
import pandas as pd

from ..case import units as U
from ..case.expr import Q, evaluate
from ..case.load import CaseSpec, load_spec
from ..case.reader import MAX_CYCLE_POINTS, MAX_POSITIONS, Node
from ..errors import AssemblyError, CaseError
from ..mechanism.build import build_mechanism
from ..mechanism.model import Mechanism
from ..mechanism.structure import Structure, analyse
from ..registry import BY_NAME, KINDS, LINKAGE_SECTIONS
from . import linkage as L
from .fitting import FitResult, evaluate_condition, solve_fit, split_condition


@dataclass
class Grid:
    """The positions of a Study: the report positions and their labels, the fine cycle grid, the
    cycle's start and length (2π for a crank, the stroke for an actuator)."""
    q: np.ndarray             # report positions
    labels: list[str]         # their labels ("0", "1", …, extra labels)
    cycle: np.ndarray         # fine grid over one cycle (ends included)
    start: float
    length: float             # cycle length (2π for a crank, stroke for an actuator)
    solved: bool = True       # False: ``[grid] cycle = false``, only the report positions are solved


def column_dims(name: str, qdim: U.Dim) -> U.Dim:
    """The dimension of a kinematics column by its prefix (x_, vqx_, w_, …) for a generalised
    coordinate of dimension ``qdim``."""
    if name == "q_deg":
        return U.DIMENSIONLESS
    return _dims_by_prefix(qdim).get(name.split("_", 1)[0], U.DIMENSIONLESS)


@lru_cache(maxsize=8)
def _dims_by_prefix(qdim: U.Dim) -> dict[str, U.Dim]:
    """The dimension of a column by the prefix of its name, for a generalised coordinate of
    dimension ``qdim`` (one table per qdim: a Study asks for hundreds of columns)."""
    L_, A_ = U.LENGTH, U.ANGLE
    return {
        "q": qdim, "x": L_, "y": L_, "s": L_, "phi": A_, "mu": A_,
        "vqx": U.dim_div(L_, qdim), "vqy": U.dim_div(L_, qdim), "vqs": U.dim_div(L_, qdim),
        "aqx": U.dim_div(L_, U.dim_pow(qdim, 2)), "aqy": U.dim_div(L_, U.dim_pow(qdim, 2)),
        "aqs": U.dim_div(L_, U.dim_pow(qdim, 2)),
        "wq": U.dim_div(A_, qdim), "eq": U.dim_div(A_, U.dim_pow(qdim, 2)),
        "vx": U.VELOCITY, "vy": U.VELOCITY, "v": U.VELOCITY, "vs": U.VELOCITY,
        "ax": U.ACCELERATION, "ay": U.ACCELERATION, "a": U.ACCELERATION, "as": U.ACCELERATION,
        "w": U.ANGULAR_VELOCITY, "e": U.ANGULAR_ACCELERATION,
    }


class Study:
    """One case. ``Study(path)`` or ``load_case(path)``."""

    def __init__(self, spec: CaseSpec | str | Path, overrides: Mapping[str, Any] | None = None):
        if not isinstance(spec, CaseSpec):
            spec = load_spec(spec, overrides)
        self.spec = spec
        self.computed: set[str] = set()
        self._analyses: dict[str, Any] = {}

    # ----------------------------------------------------------------- task analyses (registry)
    def analysis(self, name: str):
        """The analysis of the task kind ``name`` (created on first use, then cached)."""
        try:
            return self._analyses[name]
        except KeyError:
            pass
        kind = BY_NAME[name]
        module, cls = kind.analysis.split(":")
        obj = getattr(importlib.import_module(f"{__package__}.{module}"), cls)(self)
        self._analyses[name] = obj
        self.computed.add(name)
        return obj

    def __getattr__(self, name: str):
        # study.dynamics, study.forces, … : the registered analyses by name
        if not name.startswith("_") and name in BY_NAME:
            return self.analysis(name)
        raise AttributeError(f"{type(self).__name__!s} has no attribute {name!r}")

    @property
    def has_linkage(self) -> bool:
        """Does the case describe a linkage (a case may hold only a cam, gears, …)."""
        return any(self.root.has(k) for k in LINKAGE_SECTIONS)

    def tasks(self) -> list[str]:
        """The registered task kinds the case enables, in registry order."""
        return [k.name for k in KINDS if self.root.has(k.section)]

    @cached_property
    def loads(self):
        """The applied loads of the case (weights and ``[loads]``); computes no kinematics."""
        from .loads import read_loads
        return read_loads(self)

    @property
    def flywheel(self):
        """Flywheel dimensions (:class:`~reportgen.analysis.flywheel.FlywheelDims`)."""
        return self.analysis("dynamics").result.flywheel

    # ----------------------------------------------------------------- inputs
    @property
    def name(self) -> str:
        """The variant's name (the case file's stem)."""
        return self.spec.name

    @property
    def root(self) -> Node:
        """The case file's root table."""
        return self.spec.root

    @cached_property
    def meta(self) -> dict:
        """``[meta]`` of the case (title, student, group …) with the overrides of a batch."""
        from ..case.text import meta_value
        m = self.root.table("meta")
        out = {k: meta_value(v, file=m.file, key=m.key(k)) for k, v in m.data.items()}
        out.update({k: meta_value(v, file=m.file, key=m.key(k)) for k, v in self.spec.meta_overrides.items()})
        return out

    def _build(self, fixed: Mapping[str, float]) -> tuple[dict, Mechanism, Structure, L.SolverModel]:
        names = self.spec.parameters(fixed)
        g = self.spec.gravity(names)
        mech = build_mechanism(self.root, names, g)
        st = analyse(mech)
        model = L.assemble(mech, st)
        L.choose_branches(model)
        return names, mech, st, model

    @cached_property
    def _fitted(self) -> tuple[dict, list[FitResult]]:
        fixed: dict[str, float] = {}
        results: list[FitResult] = []
        fits = self.root.tables("fit")
        if fits:
            self.computed.add("fit")
        for node in fits:
            node.check_keys(["unknown", "condition", "at", "guess"], required=["unknown", "condition", "at"])
            unknown = node.string("unknown", required=True)
            names0 = self.spec.parameters(fixed)
            if unknown not in names0:
                from ..errors import did_you_mean
                raise node.error("unknown", f"параметр «{unknown}» не задан в [parameters]",
                                 expected="имя параметра с начальным значением",
                                 hint=did_you_mean(unknown, list(names0)))
            dim = names0[unknown].dim
            guess = node.quantity("guess", dim, names0) if node.has("guess") else float(names0[unknown].value)
            lhs, rhs = split_condition(node)
            at_text = node.raw("at")

            def residual(x: float, unknown=unknown, lhs=lhs, rhs=rhs, at_text=at_text, node=node) -> float:
                trial = dict(fixed)
                trial[unknown] = x
                names, mech, st, model = self._build(trial)
                qdim = U.ANGLE if mech.driver.rotary else U.LENGTH
                qa = node.eval_value(at_text, "at", qdim, names)
                cols = self._columns_at(mech, model, np.array([qa]), needed=lhs)
                env = dict(names)
                env.update({k: Q(v, column_dims(k, qdim)) for k, v in cols.items()})
                return evaluate_condition(lhs, rhs, env, node)

            scale = abs(guess) if guess else 1.0
            x, res, its = solve_fit(node, unknown, guess, residual, scale)
            fixed[unknown] = x
            results.append(FitResult(unknown, x, node.raw("condition"), str(at_text), res, its, dim))
        return fixed, results

    def _columns_at(self, mech, model, q, needed: str | None = None) -> dict[str, np.ndarray]:
        """Columns at q, solving only the groups the expression ``needed`` depends on."""
        ng = None
        if needed is not None:
            from ..case.expr import free_names
            used = free_names(needed)
            gmax = -1
            for nm in used:
                parts = nm.split("_", 1)
                if len(parts) != 2:
                    continue
                key = parts[1]
                body = None
                if key in model.point_names:
                    body = int(model.pbody[model.point_names.index(key)])
                elif key in [l.name for l in mech.links]:
                    body = model.body(key)
                if body is not None and body in model.body_group:
                    gmax = max(gmax, model.body_group[body])
            ng = gmax + 1 if gmax >= 0 else None
        res = L.solve(model, q, ngroups=ng)
        return L.columns(model, res, grid=False)

    @cached_property
    def fits(self) -> list[FitResult]:
        """The dimensions fitted by ``[[fit]]``."""
        return self._fitted[1]

    @cached_property
    def _final(self) -> tuple[dict, Mechanism, Structure, L.SolverModel]:
        fixed, _ = self._fitted
        names, mech, st, model = self._build(fixed)
        if mech.deferred:
            for link, pname, frm, (dx, dy), qat in mech.deferred:
                res = L.solve(model, np.array([qat]))
                b = model.body(link)
                th = res.pose[0, b, 2]
                if frm not in mech.link(link).points:
                    raise CaseError(f"точка «{frm}» не принадлежит звену «{link}»", file=str(self.spec.path),
                                    key=f"links.{link}.points.{pname}.from",
                                    expected="точка того же звена: " + ", ".join(mech.link(link).points))
                fx, fy = mech.link(link).points[frm]
                c, s = math.cos(th), math.sin(th)
                mech.link(link).points[pname] = (fx + c * dx + s * dy, fy - s * dx + c * dy)
            model = L.assemble(mech, st)
            L.choose_branches(model)
        return names, mech, st, model

    @property
    def params(self) -> dict:
        """The case's parameters in SI (with fitted values when the linkage has fits)."""
        if not self.has_linkage:
            return self.spec.parameters()
        return self._final[0]

    @property
    def mechanism(self) -> Mechanism:
        """The mechanism with its fitted dimensions and its deferred points placed."""
        return self._final[1]

    @property
    def structure(self) -> Structure:
        """The structural analysis: Chebyshev's W, the Assur groups in the order of solution, the
        structural formula (domain.md § 1.2)."""
        self.computed.add("structure")
        return self._final[2]

    @property
    def model(self) -> L.SolverModel:
        """The kernel's model of the linkage (analysis.linkage.SolverModel)."""
        return self._final[3]

    @property
    def qdim(self) -> U.Dim:
        """The dimension of the generalised coordinate: an angle for a crank or a rocker, a length
        for an actuator."""
        return U.ANGLE if self.mechanism.driver.rotary else U.LENGTH

    @cached_property
    def grid(self) -> Grid:
        """The report positions and the cycle grid from ``[grid]``: n positions equally spaced from
        the start over a crank's turn (or over a rocker's or an actuator's range, both ends
        included), the ``extra`` positions added (labelled д1, д2 … unless named), the fine grid
        of cycle_points + 1 points over the cycle (ends included)."""
        node = self.root.table("grid")
        node.check_keys(["positions", "closed", "extra", "cycle_points", "start", "cycle", "at"])
        names = self.params
        d = self.mechanism.driver
        if not node.boolean("cycle", True):
            return self._positions_grid(node, names)
        if node.has("at"):
            raise node.error("at", "список положений задаётся только без расчёта цикла",
                             expected="cycle = false и at = [\"0 deg\", \"40 deg\"]; иначе positions и extra")
        n = node.integer("positions", 12, minimum=2, maximum=MAX_POSITIONS)
        m = node.integer("cycle_points", 3600, minimum=36, maximum=MAX_CYCLE_POINTS)
        closed = node.boolean("closed", False)
        if d.periodic:
            start = node.quantity("start", U.ANGLE, names, default=0.0)
            length = 2 * math.pi
            q = start + length * np.arange(n + (1 if closed else 0)) / n
        else:
            # an actuator's stroke or an input rocker's swing: positions from one end of the range
            # to the other, both ends included (the return stroke passes the same positions)
            if node.has("start"):
                raise node.error("start", "начало цикла задаётся только кривошипу",
                                 expected="для качающегося звена и гидроцилиндра положения идут по [driver] range")
            lo, hi = d.q_range
            start, length = lo, hi - lo
            q = np.linspace(lo, hi, n)
        labels = [str(i) for i in range(len(q))]
        extra = node.raw("extra", [])
        if not isinstance(extra, list) or len(extra) > MAX_POSITIONS:
            raise node.error("extra", "ожидался список дополнительных положений",
                             expected=f"extra = [\"99.1 deg\"], не более {MAX_POSITIONS} значений")
        xs = []
        for i, e in enumerate(extra):
            if isinstance(e, Mapping):
                sub = Node(e, node.key(f"extra[{i}]"), node.file)
                sub.check_keys(["q", "label"], required=["q"])
                xs.append(sub.quantity("q", self.qdim, names))
                labels.append(sub.name("label", f"д{i + 1}", what="имя положения"))
            else:
                xs.append(node.eval_value(e, f"extra[{i}]", self.qdim, names))
                labels.append(f"д{i + 1}")
        if d.swing:
            for i, x in enumerate(xs):
                if not d.q_range[0] - 1e-12 <= x <= d.q_range[1] + 1e-12:
                    raise node.error(f"extra[{i}]", "дополнительное положение вне диапазона качания входного звена",
                                     expected=f"угол от {math.degrees(d.q_range[0]):.6g}° до "
                                              f"{math.degrees(d.q_range[1]):.6g}°")
        q = np.concatenate([q, np.array(xs, dtype=float)])
        cycle = start + length * np.arange(m + 1) / m
        return Grid(q, labels, cycle, start, length)

    def _positions_grid(self, node: Node, names) -> Grid:
        """``[grid] cycle = false``: the mechanism is analysed at the positions ``at`` only (a
        mechanism that assembles in part of the turn, or a task that asks for single positions);
        the cycle is not solved, so nothing that needs it (diagrams, dynamics, forces over the
        cycle) is available."""
        for k in ("positions", "closed", "extra", "cycle_points", "start"):
            if node.has(k):
                raise node.error(k, "без расчёта цикла (cycle = false) положения задаются списком at",
                                 expected="at = [\"0 deg\", \"40 deg\"]")
        raw = node.raw("at")
        if not isinstance(raw, list) or not 1 <= len(raw) <= MAX_POSITIONS:
            raise node.error("at", "ожидался список положений", expected=f"at = [\"0 deg\", \"40 deg\"], "
                                                                       f"от 1 до {MAX_POSITIONS} значений")
        q = np.array([node.eval_value(v, f"at[{i}]", self.qdim, names) for i, v in enumerate(raw)], dtype=float)
        d = self.mechanism.driver
        if d.q_range is not None:
            for i, x in enumerate(q):
                if not d.q_range[0] - 1e-12 <= x <= d.q_range[1] + 1e-12:
                    raise node.error(f"at[{i}]", "положение вне диапазона входного звена",
                                     expected=f"от {d.q_range[0]:.6g} до {d.q_range[1]:.6g}")
        start = d.q_range[0] if d.q_range is not None else 0.0
        length = (d.q_range[1] - d.q_range[0]) if d.q_range is not None else 2 * math.pi
        return Grid(q, [str(i) for i in range(len(q))], q.copy(), start, length, solved=False)

    @property
    def has_cycle(self) -> bool:
        """Whether the cycle is solved (not ``[grid] cycle = false``)."""
        return self.grid.solved

    def _no_cycle(self) -> CaseError:
        node = self.root.table("grid")
        return node.error("cycle", "в варианте не рассчитывается цикл механизма, а эта величина или раздел его требует",
                          expected="cycle = true (по умолчанию) с механизмом, собирающимся во всём цикле")

    # ----------------------------------------------------------------- kinematics
    def motion_law(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
        """dq/dt and d²q/dt² at q: the driver's constant values (dynamics may replace this)."""
        d = self.mechanism.driver
        if d.omega is None:
            return None
        return np.full_like(q, d.omega), np.full_like(q, d.epsilon)

    def _frame(self, q: np.ndarray, labels=None, grid=True, res=None, cols=None, law=None) -> pd.DataFrame:
        if cols is None:
            if res is None:
                res = self._solve_on_branch(q, labels) if not grid else L.solve(self.model, q, labels)
            cols = L.columns(self.model, res, grid=grid)
        cols.update(self._extra_angles(cols))
        if law is None:
            law = self.motion_law(q)
        if law is not None:
            cols.update(true_motion(cols, self.mechanism, *law))
        cols.update(self._derived(cols))
        return frame_of(cols, labels)

    def _extra_angles(self, cols) -> dict[str, np.ndarray]:
        out = {}
        node = self.root.table("outputs").table("angles")
        for name, pair in node.data.items():
            if not (isinstance(pair, list) and len(pair) == 2 and all(f"x_{p}" in cols for p in pair)):
                raise node.error(name, "угол линии задаётся двумя точками механизма",
                                 expected=f"{name} = [\"A\", \"B\"]", got=repr(pair))
            out.update(line_angle(cols, name, *pair))
        return out

    def _derived(self, cols) -> dict[str, np.ndarray]:
        node = self.root.table("outputs").table("derived")
        out = {}
        if not node.data:
            return out
        env = dict(self.params)
        env.update({k: Q(v, column_dims(k, self.qdim)) for k, v in cols.items()})
        for name, text in node.data.items():
            try:
                val = evaluate(text, env)
            except CaseError as e:
                raise e.with_context(file=node.file, key_prefix=node.key(name)) from None
            out[name] = np.broadcast_to(np.asarray(val.value, dtype=float), cols["q"].shape).copy()
            env[name] = Q(out[name], val.dim)
        return out

    @cached_property
    def kinematics(self) -> pd.DataFrame:
        """Positions, analogs and true velocities/accelerations at the report positions."""
        self.computed.add("kinematics")
        g = self.grid
        with _cycle_hint():
            return self._frame(g.q, g.labels, grid=False)

    @cached_property
    def kinematics_return(self) -> pd.DataFrame | None:
        """An input rocker's return stroke (q_max → q_min at dq/dt = −ω₁; None for other drivers or
        without ω₁): the report positions in the order they are passed, the same positions and
        analogs, the velocities v = −ω₁x′ of the opposite sign, the same accelerations a = ω₁²x″."""
        d = self.mechanism.driver
        if not d.swing or d.omega is None:
            return None
        k = self.kinematics
        order = np.argsort(-k["q"].to_numpy(), kind="stable")
        q = k["q"].to_numpy()[order]
        return self._frame(q, [k["pos"].iloc[i] for i in order], grid=False,
                           law=(np.full_like(q, -d.omega), np.zeros_like(q)))

    @cached_property
    def strokes(self) -> pd.DataFrame | None:
        """An input rocker's forward and return strokes (analysis/synthesis.py ``swing_strokes``)."""
        if not self.mechanism.driver.swing:
            return None
        from .synthesis import swing_strokes
        return swing_strokes(self)

    @cached_property
    def cycle(self) -> pd.DataFrame:
        """The same columns on the fine grid over one cycle (for curves and integrals)."""
        if not self.has_cycle:
            raise self._no_cycle()
        self.computed.add("cycle")
        return self._frame(self.grid.cycle, grid=True, cols=self._grid_columns())

    def _grid_columns(self) -> dict[str, np.ndarray]:
        """The columns of ``L.columns(grid=True)`` on the cycle grid, from those of single
        positions (:attr:`_cycle_columns`, already computed for the evaluations at grid points):
        the link angles, there in (−π, π], are unwrapped along the grid — the same numbers."""
        cols = dict(self._cycle_columns)
        d = self.mechanism.driver
        for link in self.mechanism.moving:
            if (d.rotary and link.name == d.link) or cols["q"].size < 2:
                continue
            cols["phi_" + link.name] = L.unwrap(cols["phi_" + link.name])
        return cols

    @cached_property
    def _cycle_solution(self) -> L.KinematicsResult:
        if not self.has_cycle:
            raise self._no_cycle()
        with _cycle_hint():
            return L.solve(self.model, self.grid.cycle)

    @cached_property
    def _cycle_columns(self) -> dict[str, np.ndarray]:
        """The kinematic columns of single positions (angles not unwrapped) on the cycle grid:
        evaluations at grid points are taken from here (loads.ColumnEvaluator)."""
        return L.columns(self.model, self._cycle_solution, grid=False)

    def _solve_on_branch(self, q: np.ndarray, labels=None) -> L.KinematicsResult:
        """Kinematics at single positions.  Closed-form groups keep their sign σ; a mechanism
        with Newton groups (class III) is continued from the nearest position of the solved
        cycle, so that every position lies on the cycle's branch (never a Newton restarted from
        the sketch)."""
        if not L.has_newton(self.model):
            return L.solve(self.model, q, labels)
        if not self.has_cycle:
            return self._from_sketch(q, labels)
        period = self.grid.length if self.mechanism.driver.periodic else None
        return L.solve_continued(self.model, q, self._cycle_solution, period, labels)

    def _from_sketch(self, q: np.ndarray, labels) -> L.KinematicsResult:
        """Newton groups reached from the sketch (:func:`~reportgen.analysis.linkage.solve_from_sketch`)."""
        mech = self.mechanism
        g = self.grid
        q0 = mech.sketch_q if mech.sketch_q is not None else g.start
        step = g.length / 3600 if not g.solved else g.length / (len(g.cycle) - 1)
        return L.solve_from_sketch(self.model, q, q0, step, g.length if mech.driver.periodic else None, labels)

    def at(self, q) -> pd.DataFrame:
        """Exact evaluation at the given values of the generalised coordinate (SI), on the
        branch of the cycle.  A mechanism with Newton groups (class III) whose cycle has not been
        solved is not solved over it (``export --at``): each position is reached from the sketch
        (:func:`~reportgen.analysis.linkage.solve_from_sketch`), so a mechanism that assembles
        only in part of the turn is analysed where it does; once the cycle is solved, positions
        are continued from it (the same branch, fewer steps)."""
        q = np.atleast_1d(np.asarray(q, dtype=float))
        labels = [f"q{i}" for i in range(len(q))]
        res = None
        if L.has_newton(self.model) and "_cycle_solution" not in self.__dict__:
            res = self._from_sketch(q, labels)
        return self._frame(q, labels, grid=False, res=res)

    @cached_property
    def flags(self) -> dict:
        """Singular positions and low transmission angles over the cycle: of every dyad (ВВВ, ВВП)
        and of every class III group by its equivalent transmission angle
        (``linkage.equivalent_transmission_sine``, equal to μ for a dyad), same thresholds."""
        cyc = self.cycle
        out = {}
        for c in cyc.columns:
            if c.startswith("mu_"):
                mu = cyc[c].to_numpy()
                out[c] = dict(min=float(mu.min()), q_min=float(cyc["q"].to_numpy()[mu.argmin()]),
                              singular=bool((np.sin(mu) < L.SINGULAR_SIN).any()),
                              low=bool((mu < L.LOW_TRANSMISSION).any()))
        return out

    @cached_property
    def guide_flags(self) -> dict:
        """ВПВ groups (a slider on a rotating guide, кулиса): the distance between the guide's pivot
        and the slider's pin over the cycle.  It is the group's transmission measure: the guide's
        angular velocity analog is ω′ = (slider pin's velocity across the guide)/ρ, unbounded as
        ρ → 0, where the pin passes through the guide's pivot (особое положение).  ``singular`` when
        min ρ < 10⁻⁶ of the mechanism's size."""
        out = {}
        cyc = None
        mech = self.mechanism
        for g in self.structure.groups:
            if g.kind != "RPR":
                continue
            rev = [mech.joints[j] for j in g.joints if mech.joints[j].kind == "R"]
            pri = [mech.joints[j] for j in g.joints if mech.joints[j].kind == "P"]
            if len(rev) != 2 or len(pri) != 1:
                continue
            guide = pri[0].links[0]
            rev.sort(key=lambda j: guide not in j.links)   # the guide's pivot first, then the pin
            if cyc is None:
                cyc = self.cycle
            a, b = rev[0].point, rev[1].point
            rho = np.hypot(cyc["x_" + a] - cyc["x_" + b], cyc["y_" + a] - cyc["y_" + b]).to_numpy()
            i = int(np.argmin(rho))
            out["_".join(g.links)] = dict(min=float(rho[i]), q_min=float(cyc["q"].iloc[i]), points=(a, b),
                                          singular=bool(rho[i] < 1e-6 * self.model.size))
        return out

    @cached_property
    def slide_flags(self) -> dict:
        """ПВП and ВПП groups with one sliding pair on a fixed guide (the driven link slides along it):
        the transmission angle over the cycle. The group's other link presses on the driven one along
        the normal to the guide of the group's other sliding pair (through the hinge in ПВП, in the
        pair itself in ВПП; friction and the links' inertia neglected), the driven link moves along
        its fixed guide, so the pressure angle is 90° less the angle between the two guides and
        μ = arcsin|sin(θ₀ − θ)|, the acute angle between them (Артоболевский, гл. 4, угол давления).
        ``guides``: the sliding pairs (fixed, other); ``const``: μ the same in every position."""
        from ..mechanism.model import FRAME
        out = {}
        mech = self.mechanism
        for g in self.structure.groups:
            if g.kind not in ("PRP", "RPP"):
                continue
            pri = [mech.joints[j] for j in g.joints if mech.joints[j].kind == "P"]
            fixed = [j for j in pri if j.links[0] == FRAME and j.links[1] in g.links]
            if len(pri) != 2 or len(fixed) != 1:
                continue
            other = next(j for j in pri if j is not fixed[0])
            cyc = self.cycle
            th = other.angle + (cyc["phi_" + other.links[0]].to_numpy() if other.links[0] != FRAME else 0.0)
            mu = np.arcsin(np.clip(np.abs(np.sin(fixed[0].angle - th)), 0.0, 1.0)) * np.ones(len(cyc))
            i = int(np.argmin(mu))
            out["_".join(g.links)] = dict(min=float(mu[i]), q_min=float(cyc["q"].iloc[i]), guides=(fixed[0], other),
                                          const=bool(np.ptp(mu) < 1e-9), singular=bool(np.sin(mu[i]) < L.SINGULAR_SIN),
                                          low=bool(mu[i] < L.LOW_TRANSMISSION))
        return out

    @cached_property
    def scalars(self) -> dict[str, float]:
        """Named results of the linkage: the structure's, the least transmission angle μ over the
        cycle of each group (``mu_*_min``) and the output's stroke."""
        out = dict(self.structure_scalars)
        if not self.has_cycle:
            return out
        for c, v in self.flags.items():
            out[c + "_min"] = v["min"]
        out.update(self._output_stroke())
        return out

    def _output_stroke(self) -> dict[str, float]:
        """Stroke (swing) of the output link, its time-ratio coefficient K and mean speeds of
        the working (longer) and return strokes (analysis/synthesis.py ``output_extremes``)."""
        d = self.mechanism.driver
        if d.swing:
            return self._swing_scalars()
        if not d.periodic:
            return {}
        from .synthesis import output_extremes
        x = output_extremes(self)
        if x.get("extremes") != 2:
            return {}
        out = {"output": x["column"], "output_stroke": x["stroke"], "output_K": x["K"],
               "output_q1": x["q1"], "output_q2": x["q2"]}
        w = self.mechanism.driver.omega
        if w is not None:
            out["output_v_work"] = x["stroke"] * w / max(x["phi_a"], x["phi_b"])
            out["output_v_return"] = x["stroke"] * w / min(x["phi_a"], x["phi_b"])
        return out


    def _swing_scalars(self) -> dict[str, float]:
        """An input rocker: the swing q_max − q_min, the output's range over it (with its interior
        reversals), the time of one stroke t = (q_max − q_min)/ω₁ and K = 1 (both strokes at the
        same |ω₁| take the same time)."""
        from .synthesis import swing_output
        d = self.mechanism.driver
        x = swing_output(self)
        out = {"swing": d.q_range[1] - d.q_range[0], "output": x["column"], "output_stroke": x["stroke"],
               "output_reversals": len(x["reversals"]), "output_K": 1.0}
        for i, r in enumerate(x["reversals"]):
            out[f"output_q_reversal_{i + 1}"] = r
        st = self.strokes
        out["output_path"] = float(st["s_path"].iloc[0])
        if d.omega is not None:
            out["t_stroke"] = out["swing"] / d.omega
            out["t_return"] = float(st["t"].iloc[1])
            out["t_cycle"] = float(st["t"].sum())
        return out

    # ------------------------------------------------------------- export
    def _tasks_for(self, positions_only: bool) -> list[str]:
        """The case's tasks; ``positions_only``: those that need no linkage (a linkage task, such
        as dynamics, works over the cycle)."""
        return [n for n in self.tasks() if not (positions_only and BY_NAME[n].linkage)]

    def extra_tables(self, positions_only: bool = False) -> dict[str, pd.DataFrame]:
        """Tables beyond kinematics and structure: fits, then each task analysis of the case
        (``positions_only``: without the linkage tasks, which need the cycle)."""
        out = {}
        if self.fits:
            out["fits"] = pd.DataFrame([{"name": f.name, "value": f.value, "condition": f.condition,
                                         "at": f.at, "residual": f.residual} for f in self.fits])
        for name in self._tasks_for(positions_only):
            out.update(self._task_part(name, "tables", positions_only)())
        return out

    def _task_part(self, name: str, part: str, positions_only: bool):
        """A task's ``tables`` (method) or ``scalars``; ``positions_only`` (``export --at``): its
        ``position_tables()`` / ``position_scalars()`` when it has them (the part that needs no
        solution of the linkage over the cycle)."""
        obj = self.analysis(name)
        fn = getattr(obj, "position_" + part, None) if positions_only else None
        if fn is not None:
            return fn
        return getattr(obj, part) if part == "tables" else (lambda: obj.scalars)

    @property
    def structure_scalars(self) -> dict[str, Any]:
        """W, n, p₅, p₄, the class and the fitted parameters: nothing solved over the cycle."""
        st = self.structure
        out: dict[str, Any] = {"W": st.W, "n": st.n, "p5": st.p5, "p4": st.p4, "mech_class": st.mech_class}
        for f in self.fits:
            out[f.name] = f.value
        return out

    def all_scalars(self, positions_only: bool = False) -> dict:
        """Every scalar of the case; ``positions_only`` (``export --at``): only those that need
        no solution over the cycle."""
        out = {}
        if self.has_linkage:
            out.update(self.structure_scalars if positions_only else self.scalars)
        for name in self._tasks_for(positions_only):
            out.update(self._task_part(name, "scalars", positions_only)())
        return out


CYCLE_HINT = ("Отчёт, проверка и полный экспорт требуют сборки во всех положениях цикла. Механизм, "
              "собирающийся лишь в части оборота, рассчитывается в отдельных положениях: reportgen export "
              "ВАРИАНТ --at \"0 deg\"; входное звено, качающееся в части оборота, задаётся в [driver] как "
              "type = \"rocker\" с range = [\"φ_min\", \"φ_max\"]")


@contextmanager
def _cycle_hint():
    """An assembly failure over the report positions or the cycle says how to analyse the
    mechanism where it does assemble."""
    try:
        yield
    except AssemblyError as e:
        if e.amount > 0 and not e.hint:
            raise AssemblyError(e.group, e.position, e.amount, e.detail, CYCLE_HINT) from None
        raise


class BlockColumns(MutableMapping):
    """Named float columns of one length written into the rows of one 2-D block as they are
    set (a column is copied while it is still in the cache, right after it is computed), so
    that :func:`frame_of` makes the table from the block itself, without stacking hundreds of
    columns at the end.  Reading a column gives its row (a view); setting an existing name
    overwrites its row.  A value that is not a float column of the length is kept aside and
    the table is then stacked as for a dict."""

    __slots__ = ("n", "_block", "_rows", "_other")

    def __init__(self, n: int, cols: Mapping[str, Any] | None = None, capacity: int = 64):
        self.n = int(n)
        self._rows: dict[str, int] = {}
        self._other: dict[str, Any] = {}
        self._block = np.empty((max(capacity, len(cols) if cols is not None else 0), self.n))
        if cols is not None:
            for k, v in cols.items():
                self[k] = v

    def __setitem__(self, k: str, v) -> None:
        r = self._rows.get(k)
        if (isinstance(v, np.ndarray) and v.dtype == np.float64 and v.shape == (self.n,)
                and k not in self._other):
            if r is None:
                r = len(self._rows)
                if r == self._block.shape[0]:
                    grown = np.empty((2 * r + 16, self.n))
                    grown[:r] = self._block
                    self._block = grown
                self._rows[k] = r
            self._block[r] = v
            return
        if r is not None:            # a float column replaced by something else: keep the order
            self._other[k] = v
            return
        self._rows[k] = -1
        self._other[k] = v

    def __getitem__(self, k: str):
        r = self._rows[k]
        if k in self._other:
            return self._other[k]
        return self._block[r]

    def __delitem__(self, k: str) -> None:
        raise TypeError("BlockColumns: a column is not removed")

    def __contains__(self, k) -> bool:
        return k in self._rows

    def __iter__(self):
        return iter(self._rows)

    def __len__(self) -> int:
        return len(self._rows)

    def block(self) -> np.ndarray | None:
        """The (columns × n) block in column order, or None when some value is kept aside."""
        if self._other:
            return None
        return self._block[:len(self._rows)]


def frame_of(cols: Mapping[str, Any], labels=None) -> pd.DataFrame:
    """The DataFrame of named columns (with the labels as the first column «pos»).  Equal-length
    float columns are stacked into one 2-D block first: a dict of columns goes through pandas'
    per-column checks and consolidation, several times slower for the hundreds of columns of a
    cycle table.  The values are the same.  :class:`BlockColumns` are their own block."""
    blk = cols.block() if isinstance(cols, BlockColumns) else None
    if blk is not None:
        df = pd.DataFrame(blk.T, columns=list(cols), copy=False)
        if labels is not None:
            df.insert(0, "pos", labels)
        return df
    vals = list(cols.values())
    n = len(vals[0]) if vals else 0
    if vals and all(isinstance(v, np.ndarray) and v.dtype == np.float64 and v.shape == (n,) for v in vals):
        # one C-level copy into the block (np.stack checks and reshapes every column first)
        df = pd.DataFrame(np.concatenate(vals).reshape(len(vals), n).T, columns=list(cols), copy=False)
    else:
        df = pd.DataFrame(cols)
    if labels is not None:
        df.insert(0, "pos", labels)
    return df


def true_motion(cols, mech: Mechanism, w: np.ndarray, e: np.ndarray,
                points=None) -> dict[str, np.ndarray]:
    """v = ω·x′, a = ω²·x″ + ε·x′ for every point, link and slider (ω = dq/dt, ε = d²q/dt²);
    ``points``: only those points (links and sliders all the same)."""
    tm = TrueMotion(cols, w, e, points)
    return {k: tm[k] for k in tm.names}


class TrueMotion:
    """The columns of :func:`true_motion`, each made when first asked for (``tm[name]``, then
    kept): vx_P, vy_P, v_P, ax_P, ay_P, a_P of the points, w_k, e_k of the links, vs_k, as_k of
    the sliders; ``names`` in the order of :func:`true_motion`.  A caller that needs a few of
    them over the cycle (the centres of mass of the force analysis) computes only those."""

    def __init__(self, cols, w: np.ndarray, e: np.ndarray, points=None):
        # a constant law (ω₁ = const) as scalars: the same products, without reading ω and ε
        # arrays or forming ω² again for every column
        w, e = _constant(w), _constant(e)
        self.cols, self.w, self.e = cols, w, e
        self._spec: dict[str, tuple[str, str]] = {}
        self._vals: dict[str, np.ndarray] = {}
        for k in list(cols):
            if k.startswith("vqx_"):
                p = k[4:]
                if points is not None and p not in points:
                    continue
                for kind in ("vx", "vy", "v", "ax", "ay", "a"):
                    self._spec[kind + "_" + p] = (kind, p)
            elif k.startswith("wq_"):
                self._spec["w_" + k[3:]] = ("w", k[3:])
                self._spec["e_" + k[3:]] = ("e", k[3:])
            elif k.startswith("vqs_"):
                self._spec["vs_" + k[4:]] = ("vs", k[4:])
                self._spec["as_" + k[4:]] = ("as", k[4:])
        self.names = list(self._spec)

    def __contains__(self, k) -> bool:
        return k in self._spec

    def __getitem__(self, k: str) -> np.ndarray:
        v = self._vals.get(k)
        if v is None:
            v = self._vals[k] = self._make(*self._spec[k])
        return v

    def _make(self, kind: str, p: str) -> np.ndarray:
        cols, w, e = self.cols, self.w, self.e
        if kind == "vx":
            return w * cols["vqx_" + p]
        if kind == "vy":
            return w * cols["vqy_" + p]
        if kind == "v":
            return np.hypot(self["vx_" + p], self["vy_" + p])
        if kind == "ax":
            return w * w * cols["aqx_" + p] + e * cols["vqx_" + p]
        if kind == "ay":
            return w * w * cols["aqy_" + p] + e * cols["vqy_" + p]
        if kind == "a":
            return np.hypot(self["ax_" + p], self["ay_" + p])
        if kind == "w":
            return w * cols["wq_" + p]
        if kind == "e":
            return w * w * cols["eq_" + p] + e * cols["wq_" + p]
        if kind == "vs":
            return w * cols["vqs_" + p]
        return w * w * cols["aqs_" + p] + e * cols["vqs_" + p]


def norm(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """|(x, y)| = √(x² + y²) of column arrays: within one rounding of ``np.hypot`` (≤ 2.2e-16
    relative) and several times faster (no scaling against overflow, which the forces of a
    mechanism, far below 1e150, never need).  The force tables use it; the kinematic and
    motion tables keep ``np.hypot`` (their speeds are compared with printed values, where a
    last-digit change would show in the difference)."""
    r = x * x
    r += y * y
    return np.sqrt(r, out=r)


def _constant(v):
    """A float array whose elements are all equal as that float (else the array itself)."""
    if isinstance(v, np.ndarray) and v.ndim == 1 and v.size and v.dtype == np.float64:
        x = v[0]
        if x == x and (v == x).all():
            return float(x)
    return v


def line_angle(cols, name: str, p: str, r: str) -> dict[str, np.ndarray]:
    """Angle of the line p→r with its analogs: θ = atan2(dy, dx), θ' = (dx·dy' − dy·dx')/ρ²,
    θ'' = (dx·dy'' − dy·dx'')/ρ² − 2(dx·dx' + dy·dy')(dx·dy' − dy·dx')/ρ⁴."""
    dx = cols["x_" + r] - cols["x_" + p]
    dy = cols["y_" + r] - cols["y_" + p]
    d1x = cols["vqx_" + r] - cols["vqx_" + p]
    d1y = cols["vqy_" + r] - cols["vqy_" + p]
    d2x = cols["aqx_" + r] - cols["aqx_" + p]
    d2y = cols["aqy_" + r] - cols["aqy_" + p]
    r2 = dx * dx + dy * dy
    cr = dx * d1y - dy * d1x
    th = np.arctan2(dy, dx)
    if th.size > 1:
        th = L.unwrap(th)
    base = name[4:] if name.startswith("phi_") else name
    return {("phi_" + base): th, ("wq_" + base): cr / r2,
            ("eq_" + base): (dx * d2y - dy * d2x) / r2 - 2 * (dx * d1x + dy * d1y) * cr / (r2 * r2)}


def load_case(path: str | Path, overrides: Mapping[str, Any] | None = None) -> Study:
    """Load a case file and return its :class:`Study` (nothing is computed yet)."""
    return Study(path, overrides)
