"""Dynamics of the machine: reduced model, flywheel by three methods, true motion.

Dynamic model (Артоболевский «Теория механизмов и машин», гл. «Динамика машин»; Попов–Тимофеев,
курсовое проектирование; worksheet 000).  The crank is the link of reduction, φ = q.

* Reduced moment of inertia of the variable part (group II), each link separately
  (kinetic-energy equivalence):
      J_II(φ) = Σ_k [m_k (x′²_Sk + y′²_Sk) + J_Sk φ′²_k],
  and its exact derivative (from the second analogs, no differencing)
      J_II′(φ) = 2 Σ_k [m_k (x′_Sk x″_Sk + y′_Sk y″_Sk) + J_Sk φ′_k φ″_k].
  The crank itself (φ′ = ±1, |V_S|/ω constant) belongs to group I: J_I,const = J_O + J_crank,
  with J_O the given reduced inertia of rotors and gears (worksheet J_O.пр).
* Reduced moment of each load by virtual power (:mod:`reportgen.analysis.loads`):
  M_пр = Σ(F_x x′ + F_y y′) + Σ M_k φ′_k.
* One moment is unknown and constant, from zero work over the cycle Φ (2π or 4π):
  ``balance = "drive"`` (a working machine): M_дв = −A_c/Φ;
  ``balance = "resistance"`` (an engine: the loads drive, the consumer resists): M_c = −A_дв/Φ;
  or the driving moment is given (``drive``) and must balance the cycle.
* Works A_c(φ), A_дв(φ), A_Σ(φ) = ΔT(φ), the flywheel J_I by the exact periodic solution,
  Мерцалов and Виттенбауэр, ω(φ), ε(φ): :func:`reportgen.analysis.flywheel.solve_dynamics`
  (works in closed form for loads constant between switching points, quadrature split at the
  switching points for table loads; extremes by root finding).  J_доп = J_I − J_I,const.
* True motion: v = ω x′, a = ω² x″ + ε x′ (and the same for link angles and sliders) with ω(φ),
  ε(φ) of the chosen method, :func:`reportgen.analysis.study.true_motion`.

The results are reached as ``study.dynamics`` (the «dynamics» line of :mod:`reportgen.registry`;
``study.loads`` and ``study.flywheel`` beside it), exported through the Study's table
and scalar hooks when the case has ``[dynamics]``.  ``study.kinematics`` stays the kinematic
analysis at ω₁ = const.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from decimal import Decimal, InvalidOperation
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..case import units as U
from ..case.reader import Node
from ..case.text import inline_html
from ..errors import CaseError, did_you_mean
from .flywheel import DynamicModel, DynamicsResult, exact, flywheel_dims, solve_dynamics
from .loads import (ColumnEvaluator, Loads, LoadWorks, Table1D, com_point, cycle_of,
                    read_table, switching_points)
from .study import frame_of, true_motion

__all__ = ["Settings", "ReducedModel", "Dynamics", "Printed", "read_settings", "METHODS"]

METHODS = ("exact", "mertsalov", "wittenbauer")
DYN_KEYS = ["cycle", "omega_m", "n", "delta", "J_O", "method", "drive", "balance", "flywheel",
            "points", "printed", "compare", "flywheel_ratio", "J_fly", "fly_mass", "fly_radius", "machine"]

# usual coefficients of speed fluctuation by kind of machine, key → (Russian name, δ_min, δ_max).
# Source: the project's domain notes (/work/shared/docs/domain.md, «Coefficient of non-uniformity»):
# 1/20–1/50 machine tools, 1/80–1/150 internal combustion engines, 1/5–1/30 pumps and presses (one
# range for both). Only these are kept: searches of the stored reference pages for a textbook table
# (Артоболевский «Теория механизмов и машин», Попов «Курсовое проектирование по ТММ», Фролов,
# Кореняко; sessions 4 and 7, queries in Russian and English) found none, and the ranges once given
# here from memory for crushers, compressors and generators had no source at all. The note calls
# the range approximate and cites no textbook for it (report.sections.dynamics._delta_judgement).
DELTA_RANGES = {
    "press": ("прессы", 1 / 30, 1 / 5),
    "pump": ("насосы", 1 / 30, 1 / 5),
    "machine_tool": ("металлорежущие станки", 1 / 50, 1 / 20),
    "engine": ("двигатели внутреннего сгорания", 1 / 150, 1 / 80),
}
# flywheel constants: key → (dimension or None for a plain number, default)
FLYWHEEL_KEYS = {
    "rho": (U.DENSITY, 7800.0), "psi_b": (None, 0.2), "psi_h": (None, 0.8),
    "v_limit": (U.VELOCITY, 30.0), "rim_coef": (None, 0.437), "rim_inner_ratio": (None, 0.8),
    "rim_width_ratio": (None, 0.2), "rim_mass_coef": (None, 6123.0), "disk_coef": (None, 0.366),
    "disk_width_ratio": (None, 0.2), "disk_mass_coef": (None, 1230.0),
}


# --------------------------------------------------------------------------------------------
# Settings
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Printed:
    """A value printed in the source (worksheet) to compare with: ``key`` is a scalar name or
    ``column@position``; ``unit`` is one unit of the last printed digit."""

    key: str
    text: str
    value: float
    unit: float
    note: str
    title: str


@dataclass(frozen=True)
class Settings:
    """The ``[dynamics]`` table, in SI."""

    cycle_start: float
    cycle_length: float
    omega_m: float
    delta: float
    J_O: float
    method: str
    balance: str                      # "drive" | "resistance"
    drive: float | Table1D | None     # given driving moment (constant or table vs phase)
    flywheel_kw: dict
    points: int
    printed: tuple[Printed, ...]
    compare: tuple[Path, str] | None
    # the flywheel's shaft turns u times faster than the crank: J on that shaft = J_доп/u²
    ratio: float = 1.0
    # inverse task: the flywheel's J on its shaft is given (J_fly, or m·ρ²); δ is found
    J_given: float | None = None
    machine: str | None = None        # kind of machine (a key of DELTA_RANGES) for the judgement of δ


def _last_digit(text: str) -> tuple[float, float]:
    """Value and one unit of the last printed digit: "1.462e3" → (1462, 1); "6.94" → (6.94, 0.01)."""
    t = text.strip().replace("−", "-").replace(",", ".").replace("×10^", "e").replace("*10^", "e")
    try:
        d = Decimal(t)
    except InvalidOperation:
        raise ValueError(text) from None
    if not d.is_finite() or not math.isfinite(float(d)) or abs(d.as_tuple().exponent) > 300:
        raise ValueError(text)  # "inf", "nan", "1e999": not a printed number
    return float(d), float(Decimal(1).scaleb(d.as_tuple().exponent))


def read_settings(study) -> Settings:
    """Read and check ``[dynamics]`` (keys in docs/case-format.md)."""
    if not study.root.has("dynamics"):
        raise CaseError("в файле варианта нет раздела [dynamics]", file=str(study.spec.path),
                        key="dynamics", expected="[dynamics] с ключами delta и n (или omega_m)")
    node = study.root.table("dynamics")
    inverse = node.has("J_fly") or node.has("fly_mass") or node.has("fly_radius")
    node.check_keys(DYN_KEYS, required=[] if inverse else ["delta"])
    params = study.params
    mech = study.mechanism
    if mech.driver.swing:
        raise node.error(None, "динамический анализ с маховиком выполняется для машины с кривошипом: качающееся "
                               "входное звено в крайних положениях останавливается (ω₁ = 0) и меняет направление, "
                               "установившегося движения с периодом в оборот нет, маховик на нём не применяется",
                         expected="[driver] type = \"crank\"; для качающегося звена — силовой расчёт при постоянной "
                                  "скорости ([forces] motion = \"constant\" или mode = \"static\")")
    if not mech.driver.rotary:
        raise node.error(None, "динамический анализ выполняется для машины с кривошипом (звено приведения — кривошип)",
                         expected="[driver] type = \"crank\"")
    start, length = cycle_of(study)
    if node.has("omega_m") and node.has("n"):
        raise node.error("n", "средняя скорость задана дважды", expected="либо n, либо omega_m")
    if node.has("n"):
        raw = node.raw("n")
        if isinstance(raw, (int, float)) and not isinstance(raw, bool):
            if not raw > 0:
                raise node.error("n", "частота вращения должна быть положительной", expected="n = 65 (об/мин)",
                                 got=str(raw))
            w = float(raw) * math.pi / 30
        else:
            w = node.quantity("n", U.ANGULAR_VELOCITY, params, positive=True)
    elif node.has("omega_m"):
        w = node.quantity("omega_m", U.ANGULAR_VELOCITY, params, positive=True)
    elif mech.driver.omega is not None:
        w = float(mech.driver.omega)
    else:
        raise node.error("n", "не задана средняя угловая скорость кривошипа",
                         expected="n = \"65 rpm\" или omega_m = \"6.807 rad/s\" (или omega в [driver])")
    ratio = node.quantity("flywheel_ratio", U.DIMENSIONLESS, params, default=1.0, positive=True)
    J_given = _given_flywheel(node, params) if inverse else None
    delta = node.quantity("delta", U.DIMENSIONLESS, params, default=0.1 if inverse else None, required=not inverse,
                          positive=True)
    if not 1e-4 <= delta < 1:
        raise node.error("delta", "коэффициент неравномерности хода должен быть не меньше 0,0001 и меньше 1",
                         expected="δ от 1/150 до 1/5, например delta = 0.11 или \"1/80\"", got=str(node.raw("delta")))
    J_O = node.quantity("J_O", U.INERTIA, params, default=0.0, nonnegative=True)
    method = node.string("method", "exact", choices=list(METHODS))
    balance = node.string("balance", "drive", choices=["drive", "resistance"])
    drive: float | Table1D | None = None
    if node.has("drive"):
        if balance != "drive":
            raise node.error("drive", "движущий момент задан, а постоянным назначен момент сопротивления",
                             expected="либо drive, либо balance = \"resistance\"")
        raw = node.raw("drive")
        if isinstance(raw, dict):
            dn = node.table("drive")
            dn.check_keys(["table", "units"], required=["table"])
            drive = read_table(dn, "table", U.ANGLE, U.MOMENT, dn.raw("units"), params)
        else:
            drive = node.quantity("drive", U.MOMENT, params)
    fw = node.table("flywheel")
    fw.check_keys(list(FLYWHEEL_KEYS))
    kw = {}
    for k, (dim, dflt) in FLYWHEEL_KEYS.items():
        kw[k] = fw.quantity(k, dim or U.DIMENSIONLESS, params, default=dflt, positive=True)
    for k in ("psi_h", "rim_inner_ratio"):
        if not kw[k] < 1:
            raise fw.error(k, "отношение внутреннего диаметра обода к наружному должно быть меньше 1",
                           expected=f"0 < {k} < 1", got=str(fw.raw(k)))
    m = len(study.grid.cycle) - 1
    points = node.integer("points", int(round(m * length / (2 * math.pi))), minimum=72, maximum=100_000)
    # printed values belong to the source of this very case: a batch variant (parameters
    # overridden) is a different machine, so they are not compared there
    printed = _read_printed(node) if not study.spec.overrides else ()
    compare = None
    if node.has("compare"):
        cn = node.table("compare")
        cn.check_keys(["case", "title"], required=["case"])
        path = Path(cn.string("case", required=True))
        if not path.is_absolute():
            path = Path(study.spec.path).parent / path
        if not path.is_file():
            raise cn.error("case", f"файл варианта для сравнения не найден или не является файлом: {path}",
                           expected="путь к файлу .toml относительно этого файла")
        compare = (path, cn.text("title", None) or inline_html(path.stem))
    machine = node.string("machine", None, choices=list(DELTA_RANGES))
    return Settings(start, length, w, float(delta), float(J_O), method, balance, drive, kw,
                    points, printed, compare, float(ratio), J_given, machine)


def _given_flywheel(node: Node, params) -> float:
    """Inverse task: the flywheel's moment of inertia on its own shaft, J_fly or m·ρ²
    (mass and radius of gyration); δ must not be given as well."""
    if node.has("delta"):
        raise node.error("delta", "задан и маховик, и коэффициент неравномерности δ",
                         expected="либо delta (прямая задача), либо J_fly / fly_mass с fly_radius (обратная)")
    if node.has("J_fly"):
        if node.has("fly_mass") or node.has("fly_radius"):
            raise node.error("J_fly", "момент инерции маховика задан дважды",
                             expected="либо J_fly, либо fly_mass и fly_radius")
        return float(node.quantity("J_fly", U.INERTIA, params, required=True, positive=True))
    m = node.quantity("fly_mass", U.MASS, params, required=True, positive=True)
    rho = node.quantity("fly_radius", U.LENGTH, params, required=True, positive=True)
    return float(m * rho * rho)


_PRINTED_CACHE: dict[str, tuple[Printed, ...]] = {}


def _read_printed(node: Node) -> tuple[Printed, ...]:
    """The ``[dynamics.printed]`` values.  Reading them (number of printed digits, the notes
    as inline HTML) is a pure function of the table's text: the result is kept per process,
    keyed by that text, so the Studies of one case (a batch, the benchmark) read it once."""
    pn = node.table("printed")
    key = repr(pn.data)
    hit = _PRINTED_CACHE.get(key)
    if hit is None:
        hit = _parse_printed(pn)
        if len(_PRINTED_CACHE) >= 64:
            _PRINTED_CACHE.pop(next(iter(_PRINTED_CACHE)))
        _PRINTED_CACHE[key] = hit
    return hit


def _parse_printed(pn: Node) -> tuple[Printed, ...]:
    out = []
    for key, raw in pn.data.items():
        note, title = "", ""
        if isinstance(raw, dict):
            sub = pn.table(key)
            sub.check_keys(["value", "note", "title"], required=["value"])
            note = sub.text("note", "") or ""
            title = sub.text("title", "") or ""
            raw = sub.raw("value")
        if isinstance(raw, bool) or not isinstance(raw, (str, int, float)):
            raise pn.error(key, "напечатанное значение — число или строка с числом",
                           expected="\"1.462e3\" (строкой, чтобы сохранить число напечатанных знаков)",
                           got=repr(raw))
        text = raw if isinstance(raw, str) else repr(raw)
        try:
            v, unit = _last_digit(text)
        except ValueError:
            raise pn.error(key, "не удалось прочитать напечатанное число", expected="например \"-6.85e3\" или \"599.736\"",
                           got=text) from None
        out.append(Printed(str(key), text, v, unit, note, title))
    return tuple(out)


# --------------------------------------------------------------------------------------------
# Reduced model
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class InertialLink:
    """A link with mass or moment of inertia: m [kg] at point S, J_S [kg·m²]."""

    name: str
    title: str
    m: float
    J_S: float
    S: str | None


class ReducedModel:
    """J_II(φ), J_II′(φ) and the reduced moments as vectorised callables of φ (one kinematic
    evaluation per array, shared through the evaluator's cache)."""

    def __init__(self, study, loads: Loads, evaluator: ColumnEvaluator):
        mech = study.mechanism
        self.loads = loads
        self.ev = evaluator
        crank = mech.driver.link
        self.links: list[InertialLink] = []
        self.crank: InertialLink | None = None
        for l in mech.moving:
            m = float(l.mass or 0.0)
            J = float(l.J_S or 0.0)
            if m == 0.0 and J == 0.0:
                continue
            S = com_point(study, l) if m > 0 else None
            il = InertialLink(l.name, l.title or "", m, J, S)
            if l.name == crank:
                self.crank = il
            else:
                self.links.append(il)

    @staticmethod
    def link_inertia(il: InertialLink, cols) -> tuple[np.ndarray, np.ndarray]:
        """(J_k, J_k′): m(x′² + y′²) + J_S φ′² and 2[m(x′x″ + y′y″) + J_S φ′φ″]."""
        w, e = cols["wq_" + il.name], cols["eq_" + il.name]
        J = il.J_S * w * w
        dJ = 2 * il.J_S * w * e
        if il.m:
            vx, vy = cols["vqx_" + il.S], cols["vqy_" + il.S]
            ax, ay = cols["aqx_" + il.S], cols["aqy_" + il.S]
            J = J + il.m * (vx * vx + vy * vy)
            dJ = dJ + 2 * il.m * (vx * ax + vy * ay)
        return J, dJ

    def parts(self, cols) -> dict[str, tuple[np.ndarray, np.ndarray]]:
        """The contribution of each link to J_II and dJ_II/dφ: m(X′² + Y′²) + J_S φ′² and its
        derivative (domain.md § 1.5), at the columns ``cols``."""
        return {il.name: self.link_inertia(il, cols) for il in self.links}

    def J_crank(self) -> float:
        """Constant contribution of the crank J_S + m·|V_S/ω|² (group I)."""
        if self.crank is None:
            return 0.0
        J, _ = self.link_inertia(self.crank, self.ev(np.array([self.loads.cycle_start])))
        return float(J[0])

    def _sums(self, q) -> tuple[np.ndarray, np.ndarray]:
        """(J_II, J_II′) at q; the last pair is kept for the same column table (J2 and dJ2 are
        asked at the same points: one sum over the links for both)."""
        cols = self.ev(q)
        last = getattr(self, "_last", None)
        if last is not None and last[0] is cols:
            return last[1]
        J2 = np.zeros(len(cols["q"]))
        dJ2 = np.zeros(len(cols["q"]))
        for J, dJ in self.parts(cols).values():
            J2 = J2 + J
            dJ2 = dJ2 + dJ
        self._last = (cols, (J2, dJ2))
        return J2, dJ2

    def J2(self, q) -> np.ndarray:
        """J_II(q) = Σ [m_i (X′²_Si + Y′²_Si) + J_Si φ′_i²] of the links of variable inertia (group
        II; domain.md § 1.5)."""
        return self._sums(q)[0].copy()

    def dJ2(self, q) -> np.ndarray:
        """dJ_II/dq = Σ [2m_i (X′_Si X″_Si + Y′_Si Y″_Si) + 2J_Si φ′_i φ″_i], the term ½J′ω² of the
        equation of motion J ε + ½J′ω² = M (domain.md § 1.5)."""
        return self._sums(q)[1].copy()

    def works(self, nodes: np.ndarray, breaks: np.ndarray) -> LoadWorks:
        """The closed-form works of the loads on the nodes of the dynamic model."""
        return LoadWorks(self.loads, self.ev, nodes, breaks)

    def M(self, q) -> np.ndarray:
        """Σ of the reduced moments of all given loads (the last sum is kept for the same column
        table: A_Σ and M_Σ at the same points each ask for it)."""
        cols = self.ev(q)
        last = getattr(self, "_last_M", None)
        if last is not None and last[0] is cols:
            return last[1].copy()
        out = np.zeros(len(cols["q"]))
        for v in self.loads.reduced(cols).values():
            out = out + v
        self._last_M = (cols, out)
        return out.copy()


# --------------------------------------------------------------------------------------------
# The analysis
# --------------------------------------------------------------------------------------------
class Dynamics:
    """Dynamic analysis and flywheel synthesis of one case (``study.dynamics``).

    Attributes: ``settings``, ``loads``, ``model`` (:class:`ReducedModel`), ``breaks`` (switching
    points), ``result`` (:class:`~reportgen.analysis.flywheel.DynamicsResult`), ``J_crank``,
    ``J_I_const`` (= J_O + J_crank), ``grid`` (cycle grid), ``positions``/``labels`` (report
    positions over the cycle).  Tables (cached): ``table`` and ``cycle`` (dynamics columns),
    ``motion`` and ``motion_cycle`` (true motion); ``scalars``; ``printed`` (comparison with the
    printed values of the source), ``comparison`` (with the case of ``compare``).
    """

    def __init__(self, study):
        self.study = study
        self.settings = s = read_settings(study)
        self.loads = study.loads
        self.ev = ColumnEvaluator(study, size=8)
        a, Phi = s.cycle_start, s.cycle_length
        self.grid = a + Phi * np.arange(s.points + 1) / s.points
        cols = self.ev(self.grid)
        bad = self.loads.table_ranges(cols)
        if bad:
            ld, piece, d = bad[0]
            n = piece.node
            raise n.error("table", f"абсцисса «{piece.of.text}» нагрузки «{ld.name}» выходит за пределы таблицы "
                          f"на {d:.6g} (СИ)", expected="таблица, охватывающая весь ход на своей фазе",
                          got=f"[{piece.table.x[0]:.6g}; {piece.table.x[-1]:.6g}]")
        self.breaks = switching_points(study, self.loads, self.grid, self.ev)
        self.model = ReducedModel(study, self.loads, self.ev)
        self.J_crank = self.model.J_crank()
        self.J_I_const = s.J_O + self.J_crank
        Mdrive: Any = None
        if isinstance(s.drive, Table1D):
            tab = s.drive

            def table_drive(q, tab=tab):
                return tab(np.mod(np.asarray(q, dtype=float) - a, Phi))
            Mdrive = table_drive
        elif s.drive is not None:
            Mdrive = float(s.drive)
        self._Mdrive = Mdrive
        try:
            if s.J_given is not None:
                # inverse task: the exact steady motion with J_I = J_I,const + u²·J_fly gives δ;
                # the direct task below is then solved for that δ (its exact J_I is the given one)
                dm = DynamicModel(self.model.J2, self.model.dJ2, self.model.M, self.breaks, a, Phi, self.grid,
                                  Mdrive, works=self.model.works)
                self.inverse = exact(dm, s.omega_m, s.delta, J_I=self.J_I_const + s.ratio ** 2 * s.J_given)
                self.settings = s = replace(s, delta=float(self.inverse.delta_achieved))
            else:
                self.inverse = None
            self.result: DynamicsResult = solve_dynamics(
                self.model.J2, self.model.dJ2, self.model.M, self.breaks, a, Phi, self.J_I_const,
                s.omega_m, s.delta, self.grid, s.method, Mdrive, s.flywheel_kw, works=self.model.works)
            if s.ratio != 1.0:
                r = self.result
                self.result = replace(r, flywheel=flywheel_dims(r.J_flywheel / s.ratio ** 2, r.omega_max * s.ratio,
                                                                **s.flywheel_kw))
        except ValueError as e:
            if "does not balance" not in str(e):
                raise
            w = _works_probe(self.model.M, Mdrive, self.grid, self.breaks, a, Phi)
            raise CaseError("заданный движущий момент не уравновешивает работу сил сопротивления за цикл: "
                            f"A_д = {w[1]:.6g} Дж, A_с = {w[0]:.6g} Дж; установившегося движения нет",
                            file=str(study.spec.path), key="dynamics.drive",
                            expected="движущий момент с работой за цикл −A_с, или без ключа drive "
                                     "(M_дв = −A_с/Φ)") from None
        self.positions, self.labels = self._positions()

    # -------------------------------------------------------------------------- positions
    def _positions(self) -> tuple[np.ndarray, list[str]]:
        """Report positions over the cycle: the [grid] positions, repeated each 2π for a longer
        cycle (numbered on), only those inside the cycle (a cycle of k·π, k odd, ends within a
        revolution); extra positions only in the first revolution."""
        g = self.study.grid
        end = self.settings.cycle_start + self.settings.cycle_length * (1 - 1e-12)
        keep = [i for i, x in enumerate(g.q) if x < end]
        q, labels = [float(g.q[i]) for i in keep], [g.labels[i] for i in keep]
        turns = math.ceil(self.settings.cycle_length / (2 * math.pi) - 1e-12)
        regular = [i for i, lab in enumerate(g.labels) if lab == str(i)]
        nreg = len(regular)
        for t in range(1, turns):
            for i in regular:
                x = g.q[i] + 2 * math.pi * t
                if x < end:
                    q.append(x)
                    labels.append(str(i + t * nreg))
        return np.asarray(q, dtype=float), labels

    # -------------------------------------------------------------------------- evaluation
    @property
    def balance(self) -> str:
        """``[dynamics] balance``: "drive" (a working machine, M_дв = −A_c/Φ over the cycle Φ) or
        "resistance" (an engine, M_c = −A_дв/Φ)."""
        return self.settings.balance

    def _const_moment(self, q) -> np.ndarray:
        """The moment that is not a sum of loads: the balancing constant or the given drive."""
        q = np.asarray(q, dtype=float)
        if callable(self._Mdrive):
            return self._Mdrive(q)
        return np.full(q.shape, self.result.model.Md_const)

    def frame(self, q, labels: list[str] | None = None) -> pd.DataFrame:
        """Dynamics columns at q (exact evaluation; see docs/outputs.md «Динамика»)."""
        q = np.atleast_1d(np.asarray(q, dtype=float))
        r = self.result
        cols = self.ev(q)
        out: dict[str, np.ndarray] = {"q": q, "q_deg": np.degrees(q)}
        parts = self.model.parts(cols)
        J2 = np.zeros(q.size)
        dJ2 = np.zeros(q.size)
        for name, (J, dJ) in parts.items():
            out["J_II_" + name] = J
            J2 = J2 + J
            dJ2 = dJ2 + dJ
        out["J_II"] = J2
        out["dJ_II"] = dJ2
        Ml = np.zeros(q.size)
        for name, v in self.loads.reduced(cols).items():
            out["M_" + name] = v
            Ml = Ml + v
        Mk = self._const_moment(q)
        A = r.model.A(q)
        Al = r.model.Ac(q)
        Ak = A - Al
        if self.balance == "drive":
            out.update(M_c=Ml, M_d=Mk, A_c=Al, A_d=Ak)
        else:
            out.update(M_c=Mk, M_d=Ml, A_c=Ak, A_d=Al)
        out["M_sum"] = Ml + Mk
        out["A_sum"] = A
        out["T_II"] = 0.5 * self.settings.omega_m ** 2 * J2
        out["dT_I"] = A - out["T_II"]
        out["omega"] = r.omega_at(q)
        out["eps"] = r.eps_at(q)
        for meth in METHODS:
            res = getattr(r, meth)
            out["omega_" + meth] = res.omega_at(q)
            out["eps_" + meth] = res.eps_at(q)
        return frame_of(out, labels)

    def at(self, q) -> pd.DataFrame:
        """Dynamics and true-motion columns at arbitrary positions q (for ``export --at``);
        q is taken modulo the cycle."""
        q = np.atleast_1d(np.asarray(q, dtype=float))
        s = self.settings
        qc = s.cycle_start + np.mod(q - s.cycle_start, s.cycle_length)
        a, b = self.frame(qc), self.motion_frame(qc)
        # true velocities and accelerations (with ω(φ), ε(φ)) beside the kinematics' columns
        b = b.drop(columns=[c for c in ("q", "q_deg", "omega", "eps") if c in a.columns or c.startswith("q")])
        b = b.rename(columns=lambda c: c if c in ("omega", "eps") else "true_" + c)
        df = pd.concat([a, b], axis=1)
        df["q"], df["q_deg"] = q, np.degrees(q)
        return df

    def motion_frame(self, q, labels: list[str] | None = None) -> pd.DataFrame:
        """True velocities and accelerations with ω(φ), ε(φ) of the chosen method."""
        q = np.atleast_1d(np.asarray(q, dtype=float))
        cols = self.ev(q)
        w = self.result.omega_at(q)
        e = self.result.eps_at(q)
        out = {"q": q, "q_deg": np.degrees(q), "omega": w, "eps": e}
        out.update(true_motion(cols, self.study.mechanism, w, e))
        return frame_of(out, labels)

    @cached_property
    def table(self) -> pd.DataFrame:
        """Dynamics columns on the report positions."""
        return self.frame(self.positions, self.labels)

    @cached_property
    def cycle(self) -> pd.DataFrame:
        """Dynamics columns on the cycle grid."""
        return self.frame(self.grid)

    @cached_property
    def motion(self) -> pd.DataFrame:
        """True motion on the report positions."""
        return self.motion_frame(self.positions, self.labels)

    @cached_property
    def motion_cycle(self) -> pd.DataFrame:
        """True motion on the cycle grid."""
        return self.motion_frame(self.grid)

    @cached_property
    def idle_loads(self) -> list[str]:
        """Loads that do no work: their reduced moment vanishes on the whole cycle grid (the
        weight of a slider on a horizontal guide)."""
        cyc = self.cycle
        scale = max(1.0, max(float(np.max(np.abs(cyc["M_" + n]))) for n in self.loads.names)) \
            if self.loads.names else 1.0
        return [n for n in self.loads.names if float(np.max(np.abs(cyc["M_" + n]))) <= 1e-12 * scale]

    def row(self, label: str) -> pd.Series:
        """The row of the report position ``label`` in the dynamics table."""
        t = self.table
        return t[t["pos"] == label].iloc[0]

    # -------------------------------------------------------------------------- scalars
    def A_sum_extrema(self) -> tuple[float, float, float, float]:
        """(φ_max, A_Σ,max, φ_min, A_Σ,min): extremes of ΔT(φ) = A_Σ(φ), by root finding of M_Σ."""
        m = self.result.model
        pmax, vmax, _ = m.A_extremum("max")
        pmin, vmin, _ = m.A_extremum("min")
        return pmax, vmax, pmin, vmin

    def tables(self) -> dict[str, pd.DataFrame]:
        """The tables of ``reportgen export`` (columns in docs/outputs.md)."""
        out = {"dynamics": self.table, "dynamics_cycle": self.cycle, "motion": self.motion,
               "motion_cycle": self.motion_cycle}
        if self.settings.printed:
            out["dynamics_printed"] = self.printed
        return out

    @cached_property
    def scalars(self) -> dict[str, Any]:
        """Named scalars (docs/outputs.md «Динамика»)."""
        r, s = self.result, self.settings
        w = r.works
        me, wi, ex = r.mertsalov, r.wittenbauer, r.exact
        if self.balance == "drive":
            Ac, Ad = w.A_c_cycle, w.A_d_cycle
            Mc, Md = (Ac / s.cycle_length), w.M_drive
        else:
            Ac, Ad = w.A_d_cycle, w.A_c_cycle
            Mc, Md = w.M_drive, Ad / s.cycle_length
        pmax, vmax, pmin, vmin = self.A_sum_extrema()
        fw = r.flywheel
        out: dict[str, Any] = {
            "cycle_length": s.cycle_length, "omega_m": s.omega_m, "delta": s.delta,
            "n_switching": int(len(self.breaks)),
            "balance": s.balance, "A_c": Ac, "A_d": Ad, "M_c": Mc, "M_d": Md,
            "dT_max": vmax, "q_dT_max": pmax, "dT_min": vmin, "q_dT_min": pmin,
            "dT_I_max": me.dT_I_max, "q_dT_I_max": me.phi_dT_max,
            "dT_I_min": me.dT_I_min, "q_dT_I_min": me.phi_dT_min,
            "dT_I_range": me.dT_I_max - me.dT_I_min,
            "J_O": s.J_O, "J_crank": self.J_crank, "J_I_const": self.J_I_const,
            "method": s.method, "J_I": r.J_I, "J_fly": r.J_flywheel,
            "J_I_exact": r.J_I_exact, "J_I_mertsalov": r.J_I_mertsalov,
            "J_I_wittenbauer": r.J_I_wittenbauer, "J_I_wittenbauer_linear": r.J_I_wittenbauer_linear,
            "dev_mertsalov_pct": r.dev_mertsalov_pct, "dev_wittenbauer_pct": r.dev_wittenbauer_pct,
            "dev_wittenbauer_linear_pct": r.dev_wittenbauer_linear_pct,
            "delta_achieved": r.delta_achieved, "delta_achieved_exact": ex.delta_achieved,
            "delta_achieved_mertsalov": me.delta_achieved,
            "delta_achieved_wittenbauer": wi.delta_achieved,
            "delta_achieved_wittenbauer_linear": wi.delta_achieved_linear,
            "omega_max": r.omega_max, "omega_min": r.omega_min,
            "q_omega_max": r.phi_omega_max, "q_omega_min": r.phi_omega_min,
            "omega_max_exact": ex.omega_max, "omega_min_exact": ex.omega_min,
            "T0_exact": ex.T0,
            "wittenbauer_K": wi.K, "wittenbauer_L": wi.L, "wittenbauer_KL": wi.KL,
            "fw_needed": fw.needed,
            "fw_rim_D2": fw.rim.D2, "fw_rim_D1": fw.rim.D1, "fw_rim_b": fw.rim.b,
            "fw_rim_m": fw.rim.m, "fw_rim_v": fw.rim.v_rim,
            "fw_disk_D": fw.disk.D, "fw_disk_b": fw.disk.b, "fw_disk_m": fw.disk.m,
            "fw_disk_v": fw.disk.v_rim,
            "fw_disk_phys_D": fw.disk_physical.D, "fw_disk_phys_b": fw.disk_physical.b,
            "fw_disk_phys_m": fw.disk_physical.m,
            "fw_ring_phys_D2": fw.rim_physical.D2, "fw_ring_phys_D1": fw.rim_physical.D1,
            "fw_ring_phys_b": fw.rim_physical.b, "fw_ring_phys_m": fw.rim_physical.m,
            "fw_v_limit": fw.v_limit, "fw_v_exceeds": fw.any_exceeds,
            # mean powers over the cycle: P = A/t_ц, t_ц = Φ/ω_ср
            "P_d": Ad * s.omega_m / s.cycle_length, "P_c": Ac * s.omega_m / s.cycle_length,
            "t_cycle": s.cycle_length / s.omega_m,
            "fw_ratio": s.ratio, "J_fly_shaft": r.J_flywheel / s.ratio ** 2,
            "omega_max_shaft": r.omega_max * s.ratio, "omega_min_shaft": r.omega_min * s.ratio,
        }
        if self.inverse is not None:
            inv = self.inverse
            out.update(J_fly_given=s.J_given, delta_inverse=inv.delta_achieved, omega_max_inverse=inv.omega_max,
                       omega_min_inverse=inv.omega_min, J_I_inverse=inv.J_I)
        return out

    # -------------------------------------------------------------------------- comparisons
    def lookup(self, key: str) -> float:
        """A scalar by name or a table cell ``column@position`` (dynamics or motion table)."""
        if "@" in key:
            col, lab = key.split("@", 1)
            for t, rows in self._cells_index:
                if col in t.columns and lab in rows:
                    return float(t[col].to_numpy()[rows[lab]])
            raise KeyError(key)
        v = self.scalars[key]
        if isinstance(v, str):
            raise KeyError(key)
        return float(v)

    @cached_property
    def _cells_index(self) -> list[tuple[pd.DataFrame, dict[str, int]]]:
        """The dynamics and motion tables with the row of each position label (its first row)."""
        out = []
        for t in (self.table, self.motion):
            rows: dict[str, int] = {}
            for i, lab in enumerate(t["pos"]):
                rows.setdefault(lab, i)
            out.append((t, rows))
        return out

    @cached_property
    def printed(self) -> pd.DataFrame:
        """The printed values of the source beside the computed ones: key, title, printed (text),
        value, computed, diff = computed − printed, unit (one unit of the last printed digit),
        within (|diff| ≤ unit), note."""
        rows = []
        node = self.study.root.table("dynamics").table("printed")
        for p in self.settings.printed:
            try:
                c = self.lookup(p.key)
            except KeyError:
                cands = [k for k, v in self.scalars.items() if not isinstance(v, str)]
                cands += [f"{c}@{lab}" for c in self.table.columns if c not in ("pos",) for lab in self.labels[:1]]
                raise node.error(p.key, f"нет величины «{p.key}» для сравнения",
                                 expected="имя скаляра из docs/outputs.md (J_I, dT_I_max …) или "
                                          "«столбец@положение» (omega@f, v_H@f …)",
                                 hint=did_you_mean(p.key, cands)) from None
            d = c - p.value
            rows.append({"key": p.key, "title": p.title, "printed": p.text, "value": p.value,
                         "computed": c, "diff": d, "unit": p.unit,
                         "within": bool(abs(d) <= p.unit * (1 + 1e-9)), "note": p.note})
        return pd.DataFrame(rows, columns=["key", "title", "printed", "value", "computed", "diff",
                                           "unit", "within", "note"])

    @cached_property
    def other(self) -> "Dynamics | None":
        """Dynamics of the case named in ``[dynamics.compare]`` (None if none)."""
        if self.settings.compare is None:
            return None
        from .study import Study
        return Study(self.settings.compare[0]).dynamics

    @cached_property
    def comparison(self) -> pd.DataFrame | None:
        """This case against the ``compare`` case, like with like: key, title, this, other, unit,
        change_pct.  Rows: J_II (mean, max), J_I of each method, J_доп of the exact solution,
        J_I of the method each case has chosen, ω and ε of the exact motion at the report
        position ``[report] position`` (default f or 1).  ``attrs``: the largest differences
        over the cycle of the exact ω(φ) and ε(φ) (omega_diff_max [rad/s], omega_diff_rel
        (to ω_ср), eps_diff_max [rad/s²]) and of the chosen methods' ω (omega_diff_chosen)."""
        o = self.other
        if o is None:
            return None
        if abs(o.settings.cycle_length - self.settings.cycle_length) > 1e-12:
            raise CaseError("сравниваемые варианты имеют разную длину цикла", file=str(self.study.spec.path),
                            key="dynamics.compare.case", expected="вариант с тем же циклом (2π или 4π)")
        a, b = self.scalars, o.scalars
        rows = []

        def add(key, title, x, y, unit):
            rows.append({"key": key, "title": title, "this": x, "other": y, "unit": unit,
                         "change_pct": 100.0 * (x / y - 1.0) if y else math.nan})

        ob = o.frame(self.grid)
        mine = self.cycle
        J2a, J2b = mine["J_II"].to_numpy(), ob["J_II"].to_numpy()
        add("J_II_mean", "средний за цикл J<sub>II</sub>", float(J2a.mean()), float(J2b.mean()), "кг·м²")
        add("J_II_max", "наибольший J<sub>II</sub>", float(J2a.max()), float(J2b.max()), "кг·м²")
        for k, t in (("J_I_exact", "J<sub>I</sub> (точное решение)"),
                     ("J_I_mertsalov", "J<sub>I</sub> (метод Мерцалова)"),
                     ("J_I_wittenbauer", "J<sub>I</sub> (метод Виттенбауэра)")):
            add(k, t, a[k], b[k], "кг·м²")
        add("J_fly_exact", "J<sub>доп</sub> (точное решение)", a["J_I_exact"] - self.J_I_const,
            b["J_I_exact"] - o.J_I_const, "кг·м²")
        add("J_I", f"J<sub>I</sub>, принятый в расчёте ({_METHOD_SHORT[a['method']]} / "
                   f"{_METHOD_SHORT[b['method']]})", a["J_I"], b["J_I"], "кг·м²")
        lab = _report_position(self.study, self.labels)
        i = self.labels.index(lab)
        qa = self.positions[i:i + 1]
        fa, fb = self.frame(qa), o.frame(qa)
        add("omega_exact@" + lab, f"ω({lab}), точное решение", float(fa["omega_exact"].iloc[0]),
            float(fb["omega_exact"].iloc[0]), "рад/с")
        add("eps_exact@" + lab, f"ε({lab}), точное решение", float(fa["eps_exact"].iloc[0]),
            float(fb["eps_exact"].iloc[0]), "рад/с²")
        df = pd.DataFrame(rows)
        wa, wb = mine["omega_exact"].to_numpy(), ob["omega_exact"].to_numpy()
        ea, eb = mine["eps_exact"].to_numpy(), ob["eps_exact"].to_numpy()
        df.attrs["position"] = lab
        df.attrs["omega_diff_max"] = float(np.max(np.abs(wa - wb)))
        df.attrs["omega_diff_rel"] = float(np.max(np.abs(wa - wb)) / self.settings.omega_m)
        df.attrs["eps_diff_max"] = float(np.max(np.abs(ea - eb)))
        df.attrs["omega_diff_chosen"] = float(np.max(np.abs(mine["omega"].to_numpy() - ob["omega"].to_numpy())))
        return df


_METHOD_SHORT = {"exact": "точно", "mertsalov": "Мерцалов", "wittenbauer": "Виттенбауэр"}


def _report_position(study, labels: list[str]) -> str:
    """[report] position, or f, or the second position (as the report sections choose)."""
    lab = study.root.table("report").string("position")
    if lab is not None and lab in labels:
        return lab
    return "f" if "f" in labels else (labels[1] if len(labels) > 1 else labels[0])


def _works_probe(M, Mdrive, grid, breaks, a, Phi) -> tuple[float, float]:
    """Cycle works (A_c, A_д) of the loads and of a given driving moment (for a message)."""
    from .flywheel import prepare_model
    A_c = prepare_model(None, None, M, breaks, a, Phi, grid, None).Ac_total
    if callable(Mdrive):
        A_d = prepare_model(None, None, Mdrive, breaks, a, Phi, grid, None).Ac_total
    else:
        A_d = float(Mdrive) * Phi
    return A_c, A_d
