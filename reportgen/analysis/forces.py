"""Force (kinetostatic) analysis by Assur groups, its checks, the static capacity of
actuator-driven linkages and the axle loads of a carrier vehicle.

Loads (Артоболевский, «Теория механизмов и машин», гл. «Силовой расчёт механизмов»;
Попов–Тимофеев, «Курсовое проектирование…», «Кинетостатический анализ»; domain map §1.4):

* weights and applied forces and moments: :mod:`reportgen.analysis.loads` (the same load
  descriptions as the dynamics);
* d'Alembert's inertia loads of every link with a mass or a moment of inertia:
  Φ_k = −m_k·a_Sk at the centre of mass, M_Φk = −J_Sk·ε_k, with a = ω²·x″ + ε·x′ and
  ε_k = ω²·φ″_k + ε·φ′_k (:func:`reportgen.analysis.study.true_motion`) for the law of motion
  ω = dq/dt, ε = d²q/dt² chosen by ``[forces] motion``: the true motion of the dynamics
  ("dynamics") or the driver's constant ω₁, ε₁ ("constant"); none in ``mode = "static"``;
* optionally (``flywheel = true``, worksheet 000: M_Φ1 = −J_1пр·ε) the inertia moment of the
  rest of the first group on the crank, −(J_I − J_кр)·ε₁; the balancing moment then equals the
  driving moment M_дв (exactly for the exact law of motion).

Reactions: :func:`reportgen.core.kinetostatics.solve_reactions` (group by group, from the last
attached group to the initial link).  R_ij is the force of link i on link j; both orientations
are exported.  For a prismatic pair the reaction of the guide g on the slider s is the normal
force N_g_s along n = ⊥u (u the guide direction) with the reaction moment Mp_g_s about the
slider point; its point of application is shifted along the guide by h = M_p/N.

Checks of the balancing moment M_ур (or of the actuator force):

* power balance (virtual power; Артоболевский, «Приведение сил»):
  M_ур·φ′₁ + Σ(F_x·x′_P + F_y·y′_P) + Σ M_k·φ′_k = 0  (for an actuator F·1 + … = 0);
* Жуковский's lever: the plan of velocity analogs turned by 90° (p = ⊥v′), every force
  applied at the image of its point, every moment replaced by a couple on two points of its
  link (±M/l² ⊥(B − A)), the sum of the moments about the pole is zero:
  F_ур·(p_A × t) + Σ p_P × F = 0, M_ур^Ж = F_ур·l_OA (t the unit tangent of the crank pin).
  Discrepancy Δ = |M_ур − M_ур^Ж| / max(|M_ур|, |M_ур^Ж|) · 100 % (near a dead centre, where
  both vanish, measured against 10⁻³ of the loads' own scale Σ|F|·l + Σ|M|).

Static capacity of an actuator-driven linkage (worksheet 002, section 4): the actuator force
F(S) for the loads of the case, the transfer ratio i_P = dy_P/dS of a point, the force of the
cylinders F_max = k·p_max·η·π D²/4, the pressure p = F/(k·A·η), the capacity for a vertical
load at a point G_P = (F_max − F_rest)/i_P (F_rest: the actuator force of the other loads; the
virtual work of a vertical load G at P is G·i_P), and the reserve ΔG = (G_S − P)/P·100 % at the
load's own point.

Carrier vehicle (worksheet 002, section 6), moments about the rear axle:
R_A = (P_гр(a + L) + P_в·b − G·x_G)/L, R_B = ΣG − R_A, shares R_A/ΣG, R_B/ΣG; the capacity for
R_A = R_A,min (= k·ΣG with the nominal load): G_max = (P_в·b + P_гр(a + L) − R_A,min·L)/x_G; the
worksheet prints (… − R_A,min)/x_G (a force subtracted from moments) — given "as printed";
and the self-consistent G_max with R_A,min = k·(G + P_в + P_гр):
G_max = (P_в·b + P_гр(a + L) − k·L(P_в + P_гр))/(x_G + k·L).

The results are reached as ``study.forces`` (:class:`Forces`, the «forces» line of
:mod:`reportgen.registry`), exported when the case has ``[forces]``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
import pandas as pd

from ..case import units as U
from ..core import kinetostatics as KS
from ..errors import StructureError, did_you_mean
from ..mechanism.model import FRAME
from ..mechanism.structure import solver_bodies
from .loads import ColumnEvaluator, LazyColumns, com_point
from .study import BlockColumns, TrueMotion, frame_of, norm

__all__ = ["ForceSettings", "ActuatorData", "CapacityData", "CarrierData", "ForceModel",
           "Pair", "ForceGroup", "LoadItem", "Solution", "Forces", "read_settings",
           "build_model", "zhukovsky", "power_balance", "crank_pin", "couple_points", "lever_points"]

FORCES_KEYS = ["mode", "motion", "flywheel", "pairs", "actuator", "capacity"]
ACTUATOR_KEYS = ["diameter", "count", "efficiency", "pressure"]
CAPACITY_KEYS = ["load", "points"]
CARRIER_KEYS = ["title", "load", "rear_axle", "forward", "wheelbase", "weight", "weight_arm",
                "ballast", "ballast_arm", "min_steered_share"]


# --------------------------------------------------------------------------------------------
# Settings
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ActuatorData:
    """``[forces.actuator]``: piston diameter D [m], number of cylinders k, efficiency η of the
    hydraulic system, system pressure p_max [Pa]; A = πD²/4, F_max = k·p_max·η·A."""

    diameter: float
    count: int
    efficiency: float
    pressure: float

    @property
    def area(self) -> float:
        """The piston's area A = πD²/4."""
        return 0.25 * math.pi * self.diameter ** 2

    @property
    def F_max(self) -> float:
        """The greatest force of the cylinders F_max = k·p·η·A (k cylinders, pressure p, efficiency
        η)."""
        return self.count * self.pressure * self.efficiency * self.area


@dataclass(frozen=True)
class CapacityData:
    """``[forces.capacity]``: the lifted load (name of an applied force) and further points
    where the capacity for a vertical load is given."""

    load: str
    point: str
    link: str
    points: tuple[str, ...]


@dataclass(frozen=True)
class CarrierData:
    """``[carrier]`` (SI): rear axle x, forward sign (−1: forward is −x), wheelbase L, vehicle
    weight P_в with its arm b ahead of the rear axle, ballast P_гр ahead of the front axle by a,
    the carried load (applied force name) and the minimum share of the steered axle."""

    title: str
    load: str
    point: str
    rear_axle: float
    forward: float
    wheelbase: float
    weight: float
    weight_arm: float
    ballast: float
    ballast_arm: float
    min_share: float


@dataclass(frozen=True)
class ForceSettings:
    """``[forces]`` (and ``[carrier]``) as read: static or kinetostatic analysis, the law of motion
    (constant ω, the dynamics' ω(φ), or static), the flywheel's inertia included, the orientation
    of the reactions in the report's table, the actuator's, the capacity's and the carrier's
    data."""
    mode: str                         # "kinetostatic" | "static"
    motion: str                       # "constant" | "dynamics" | "static"
    flywheel: bool
    pairs: tuple[str, ...]            # "a_b" orientations for the report's reactions table
    actuator: ActuatorData | None
    capacity: CapacityData | None
    carrier: CarrierData | None


def _load_point(study, node, key: str, name: str) -> tuple[str, str]:
    """Point and link of the applied force ``name`` of [loads]."""
    for ld in study.loads.loads:
        if ld.name == name and ld.kind != "moment":
            return ld.point, ld.link
    raise node.error(key, f"нет силы «{name}» в [loads]", expected="имя силы из [[loads.force]] (или вес G<звено>)",
                     hint=did_you_mean(name, [ld.name for ld in study.loads.loads]))


def read_settings(study) -> ForceSettings:
    """Read and check ``[forces]`` and ``[carrier]`` (keys in docs/case-format.md)."""
    root = study.root
    node = root.table("forces")
    node.check_keys(FORCES_KEYS)
    params = study.params
    mech = study.mechanism
    mode = node.string("mode", "kinetostatic", choices=["kinetostatic", "static"])
    if mode == "static":
        if node.has("motion"):
            raise node.error("motion", "в статическом расчёте силы инерции не учитываются",
                             expected="mode = \"kinetostatic\" с motion или mode = \"static\" без motion")
        motion = "static"
    else:
        motion = node.string("motion", "dynamics" if root.has("dynamics") else "constant",
                             choices=["constant", "dynamics"])
        if motion == "dynamics" and not root.has("dynamics"):
            raise node.error("motion", "закон движения из динамики требует раздела [dynamics]",
                             expected="motion = \"constant\" (ω₁ из [driver]) или раздел [dynamics]")
        if motion == "constant" and mech.driver.omega is None:
            raise node.error("motion", "для сил инерции при постоянной скорости нужна скорость ведущего звена",
                             expected="omega (кривошип) или speed (гидроцилиндр) в [driver], "
                                      "или mode = \"static\"")
    flywheel = node.boolean("flywheel", False)
    if flywheel and motion != "dynamics":
        raise node.error("flywheel", "момент инерции первой группы берётся из динамики",
                         expected="flywheel = true вместе с motion = \"dynamics\"")
    pairs_raw = node.raw("pairs", [])
    if not isinstance(pairs_raw, list) or not all(isinstance(p, str) for p in pairs_raw):
        raise node.error("pairs", "ожидался список пар", expected="pairs = [\"5_6\", \"0_7\", \"5_0\"]",
                         got=repr(pairs_raw))
    known = {f"{j.links[0]}_{j.links[1]}" for j in mech.joints}
    known |= {f"{j.links[1]}_{j.links[0]}" for j in mech.joints}
    d = mech.driver
    if d.kind == "actuator":
        known |= {f"{d.link}_{d.rod}", f"{d.rod}_{d.link}"}
    for i, p in enumerate(pairs_raw):
        if p not in known:
            raise node.error(f"pairs[{i}]", f"нет кинематической пары «{p}»",
                             expected="«i_j»: звенья пары; R_ij — сила звена i на звено j",
                             hint=did_you_mean(p, sorted(known)))
    actuator = None
    an = node.table("actuator")
    if node.has("actuator"):
        if d.kind != "actuator":
            raise an.error(None, "данные гидроцилиндра задаются для механизма с гидроцилиндром",
                           expected="[driver] type = \"actuator\"")
        an.check_keys(ACTUATOR_KEYS, required=["diameter", "pressure"])
        eff = an.quantity("efficiency", U.DIMENSIONLESS, params, default=1.0, positive=True)
        if eff > 1:
            raise an.error("efficiency", "КПД не может быть больше 1", expected="0 < efficiency ≤ 1",
                           got=str(an.raw("efficiency")))
        actuator = ActuatorData(an.quantity("diameter", U.LENGTH, params, required=True, positive=True),
                                an.integer("count", 1, minimum=1), eff,
                                an.quantity("pressure", U.PRESSURE, params, required=True, positive=True))
    capacity = None
    if node.has("capacity"):
        cn = node.table("capacity")
        cn.check_keys(CAPACITY_KEYS, required=["load"])
        if actuator is None:
            raise cn.error(None, "грузоподъёмность определяется по усилию гидроцилиндров",
                           expected="раздел [forces.actuator] с diameter, count, efficiency, pressure")
        load = cn.string("load", required=True)
        point, link = _load_point(study, cn, "load", load)
        pts = cn.raw("points", [])
        if not isinstance(pts, list) or not all(isinstance(p, str) for p in pts):
            raise cn.error("points", "ожидался список точек", expected="points = [\"56\"]", got=repr(pts))
        owner = mech.point_owner()
        for i, p in enumerate(pts):
            if p not in owner:
                raise cn.error(f"points[{i}]", f"нет точки «{p}»", expected="имя точки механизма",
                               hint=did_you_mean(p, list(owner)))
        capacity = CapacityData(load, point, link, tuple(pts))
    carrier = None
    if root.has("carrier"):
        cn = root.table("carrier")
        cn.check_keys(CARRIER_KEYS, required=["load", "wheelbase", "weight", "weight_arm"])
        load = cn.string("load", required=True)
        point, _ = _load_point(study, cn, "load", load)
        share = cn.quantity("min_steered_share", U.DIMENSIONLESS, params, default=0.2, positive=True)
        if not share < 1:
            raise cn.error("min_steered_share", "доля нагрузки на управляемый мост должна быть меньше 1",
                           expected="например 0.2", got=str(cn.raw("min_steered_share")))
        fwd = cn.string("forward", "-x", choices=["-x", "x"])
        carrier = CarrierData(
            cn.text("title", "") or "", load, point,
            cn.quantity("rear_axle", U.LENGTH, params, default=0.0),
            -1.0 if fwd == "-x" else 1.0,
            cn.quantity("wheelbase", U.LENGTH, params, required=True, positive=True),
            cn.quantity("weight", U.FORCE, params, required=True, positive=True),
            cn.quantity("weight_arm", U.LENGTH, params, required=True),
            cn.quantity("ballast", U.FORCE, params, default=0.0, nonnegative=True),
            cn.quantity("ballast_arm", U.LENGTH, params, default=0.0),
            share)
    return ForceSettings(mode, motion, flywheel, tuple(pairs_raw), actuator, capacity, carrier)


# --------------------------------------------------------------------------------------------
# The force model: links, pairs (unknowns), groups in the order of solution
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Pair:
    """A pair of the force analysis; the unknown is the action of ``a`` on ``b``."""

    kind: int                 # KS.K_*
    a: str
    b: str
    name: str                 # column key "a_b"
    point: str                # application point (revolute: the joint; prismatic: slider point;
                              # actuator: the rod end; crank drive: the crank centre)
    joint: int                # index into mech.joints (−1 for the drive)
    angle: float = 0.0        # prismatic: guide direction in the guide's local frame
    base: str = ""            # actuator: base pivot (axis from base to point)

    @property
    def n(self) -> int:
        """The pair's unknowns: a revolute or a prismatic pair 2 (R_x, R_y or N, M_p), an actuator 3
        (F, N, M_p), the driving moment 1 (as core.kinetostatics.n_unknowns)."""
        return 1 if self.kind == KS.K_MOM else (3 if self.kind == KS.K_ACT else 2)


@dataclass(frozen=True)
class ForceGroup:
    """An Assur group (or the initial link) of the force analysis: real links, pairs."""

    label: str
    title: str
    kind: str
    links: tuple[str, ...]
    pairs: tuple[int, ...]     # indices into ForceModel.pairs (unknowns of the group)


@dataclass
class ForceModel:
    """The force model of a linkage: its links (the frame first), the pairs with their unknowns'
    offsets, the groups in the order of solution (the last attached first, domain.md § 1.4) and
    the reference point of each link."""
    links: list[str]                      # index 0 = frame
    pairs: list[Pair]
    groups: list[ForceGroup]              # in the order of solution (last attached first)
    offsets: np.ndarray                   # offset of each pair's unknowns
    ref: dict[str, str] = field(default_factory=dict)   # reference point of each link



def build_model(mech, st) -> ForceModel:
    """Pairs and groups of the force analysis from the mechanism and its Assur structure."""
    d = mech.driver
    links = [FRAME] + [l.name for l in mech.moving]
    pairs: list[Pair] = []
    names: dict[str, int] = {}
    for k, j in enumerate(mech.joints):
        a, b = j.links
        key = f"{a}_{b}"
        if key in names or f"{b}_{a}" in names:
            key = f"{a}_{b}_{j.name}"
        names[key] = k
        kind = KS.K_REV if j.kind == "R" else KS.K_PRI
        pairs.append(Pair(kind, a, b, key, j.point, k, j.angle if j.kind == "P" else 0.0))
    if d.rotary:
        pairs.append(Pair(KS.K_MOM, FRAME, d.link, "drive", d.center, -1))
    else:
        pairs.append(Pair(KS.K_ACT, d.link, d.rod, f"{d.link}_{d.rod}", d.end, -1, 0.0, d.center))
    drive = len(pairs) - 1
    body_of = solver_bodies(mech)
    groups: list[ForceGroup] = []
    for g in reversed(st.groups):
        gl = [l.name for l in mech.moving if body_of[l.name] in g.bodies]
        if not gl:
            continue
        pj = list(g.joints)
        if d.rotary and g.klass == 1:
            pj.append(drive)
        if d.kind == "actuator" and d.link in gl:
            pj.append(drive)
        n_unk = sum(pairs[i].n for i in pj)
        if n_unk != 3 * len(gl):
            raise StructureError(f"Группа {g.label} статически неопределима: {n_unk} неизвестных "
                                 f"реакций при {3 * len(gl)} уравнениях равновесия.")
        label = "(" + ",".join(([FRAME] if g.klass == 1 else []) + gl) + ")"
        title = g.title if not (d.kind == "actuator" and d.link in gl) else \
            f"группа Ассура {label}: гидроцилиндр с рычагом (цилиндр и шток — отдельные звенья)"
        groups.append(ForceGroup(label, title, g.kind_ru, tuple(gl), tuple(pj)))
    offs = np.cumsum([0] + [p.n for p in pairs])[:-1].astype(np.int64)
    ref = {}
    for l in mech.moving:
        ref[l.name] = next(iter(l.points))
    return ForceModel(links, pairs, groups, offs, ref)


# --------------------------------------------------------------------------------------------
# Loads on the links at a set of positions
# --------------------------------------------------------------------------------------------
@dataclass
class LoadItem:
    """One load on a link over the positions: a force (Fx, Fy) at ``point`` or a moment M.
    kind: "G" weight, "F" applied force, "M" applied moment, "Phi" inertia force, "MPhi"
    inertia moment, "Mfly" inertia moment of the first group (flywheel) on the crank."""

    kind: str
    name: str
    link: str
    point: str | None
    Fx: np.ndarray | None = None
    Fy: np.ndarray | None = None
    M: np.ndarray | None = None

    @property
    def is_force(self) -> bool:
        """Whether the load is a force (else a moment)."""
        return self.M is None


@dataclass
class Solution:
    """Everything of one evaluation: positions q, columns (analogs and the true motion),
    loads, kernel inputs and unknowns."""

    q: np.ndarray
    labels: list[str] | None
    cols: dict[str, np.ndarray]
    omega: np.ndarray
    eps: np.ndarray
    loads: list[LoadItem]
    jpt: np.ndarray
    jdir: np.ndarray
    lref: np.ndarray
    lext: np.ndarray
    x: np.ndarray
    quality: np.ndarray

    def index(self, label: str) -> int:
        """The index of the report position ``label`` in the solution."""
        return self.labels.index(label)


def _rot90(x, y):
    return -y, x


# --------------------------------------------------------------------------------------------
# Checks: power balance and Жуковский's lever
# --------------------------------------------------------------------------------------------
def power_balance(loads: list[LoadItem], cols) -> np.ndarray:
    """Σ(F_x x′_P + F_y y′_P) + Σ M_k φ′_k: the virtual power of all loads per unit dq/dt."""
    s = np.zeros(len(cols["q"]))
    for ld in loads:
        if ld.is_force:
            s = s + ld.Fx * cols["vqx_" + ld.point] + ld.Fy * cols["vqy_" + ld.point]
        else:
            s = s + ld.M * cols["wq_" + ld.link]
    return s


def couple_points(mech, link: str) -> tuple[str, str | None]:
    """Two points of a link for replacing a moment by a couple (the farthest apart of its
    points; a link whose points coincide gets a virtual point at 1 m along its local x axis:
    None)."""
    pts = list(mech.link(link).points.items())
    best, pair = 1e-9 * mech.size(), (pts[0][0], None)
    for i in range(len(pts)):
        for k in range(i + 1, len(pts)):
            dd = math.hypot(pts[i][1][0] - pts[k][1][0], pts[i][1][1] - pts[k][1][1])
            if dd > best:
                best, pair = dd, (pts[i][0], pts[k][0])
    return pair


def lever_points(cols, mech, link: str):
    """Positions and velocity analogs of the two couple points of a link (A, B)."""
    a, b = couple_points(mech, link)
    xa, ya = cols["x_" + a], cols["y_" + a]
    va = (cols["vqx_" + a], cols["vqy_" + a])
    if b is not None:
        xb, yb = cols["x_" + b], cols["y_" + b]
        vb = (cols["vqx_" + b], cols["vqy_" + b])
    else:
        phi, w = cols["phi_" + link], cols["wq_" + link]
        xb, yb = xa + np.cos(phi), ya + np.sin(phi)
        vb = (va[0] - w * np.sin(phi), va[1] + w * np.cos(phi))
    return (xa, ya, va), (xb, yb, vb)


def zhukovsky(loads: list[LoadItem], cols, mech) -> dict[str, np.ndarray]:
    """Жуковский's lever on the plan of velocity analogs turned by 90° counter-clockwise
    (image of point P: p = ⊥v′_P); moments replaced by couples ±(M/l²)·⊥(B − A) at B and A.

    Returns the moment of all loads about the pole (``lever``) and the balancing load: for a
    crank the force F_ур at the crank pin along the counter-clockwise tangent and
    M_ур^Ж = F_ур·l_OA; for an actuator its axial force (rod pushed out positive)."""
    s = np.zeros(len(cols["q"]))

    def moment(vx, vy, fx, fy):
        px, py = _rot90(vx, vy)
        return px * fy - py * fx

    for ld in loads:
        if ld.is_force:
            s = s + moment(cols["vqx_" + ld.point], cols["vqy_" + ld.point], ld.Fx, ld.Fy)
        else:
            (xa, ya, va), (xb, yb, vb) = lever_points(cols, mech, ld.link)
            dx, dy = xb - xa, yb - ya
            l2 = dx * dx + dy * dy
            fx, fy = _rot90(dx, dy)
            fx, fy = ld.M * fx / l2, ld.M * fy / l2
            s = s + moment(vb[0], vb[1], fx, fy) - moment(va[0], va[1], fx, fy)
    d = mech.driver
    out = {"lever": s}
    if d.rotary:
        pin = crank_pin(mech)
        ox, oy = cols["x_" + d.center], cols["y_" + d.center]
        ax, ay = cols["x_" + pin], cols["y_" + pin]
        l = np.hypot(ax - ox, ay - oy)
        tx, ty = _rot90((ax - ox) / l, (ay - oy) / l)
        arm = moment(cols["vqx_" + pin], cols["vqy_" + pin], tx, ty)
        F = -s / arm
        out.update(F_bal=F, M_bal=F * l, arm=arm)
    else:
        ex, ey = cols["x_" + d.end], cols["y_" + d.end]
        bx, by = cols["x_" + d.center], cols["y_" + d.center]
        L = np.hypot(ex - bx, ey - by)
        ux, uy = (ex - bx) / L, (ey - by) / L
        wc = cols["wq_" + d.link]
        vcx = cols["vqx_" + d.center] - wc * (ey - by)
        vcy = cols["vqy_" + d.center] + wc * (ex - bx)
        arm = moment(cols["vqx_" + d.end], cols["vqy_" + d.end], ux, uy) - moment(vcx, vcy, ux, uy)
        F = -s / arm
        out.update(F_bal=F, arm=arm)
    return out


def crank_pin(mech) -> str:
    """The crank's point joined to the next link (the crank pin A)."""
    return mech.crank_pin()


# --------------------------------------------------------------------------------------------
# The analysis
# --------------------------------------------------------------------------------------------
class Forces:
    """Force analysis of one case (``study.forces``).

    Attributes: ``settings``, ``model`` (:class:`ForceModel`), ``positions``/``labels``.
    Cached: ``solution`` (report positions), ``cycle_solution``, ``table`` and ``cycle``
    (columns in docs/outputs.md «Силовой анализ»), ``scalars``.  ``details(label)`` gives the
    loads and reactions at one report position for the drawings.
    """

    def __init__(self, study):
        self.study = study
        self.settings = read_settings(study)
        self.mech = study.mechanism
        self.model = build_model(self.mech, study.structure)
        s = self.settings
        self.ev = ColumnEvaluator(study, size=4)
        if s.motion == "dynamics":
            dyn = study.dynamics
            # the dynamics has evaluated the kinematics on the same grid and report positions
            # (ω(φ), ε(φ) there): its evaluator's cache serves them (the same columns)
            self.ev = dyn.ev
            self.positions, self.labels = dyn.positions, list(dyn.labels)
            self.grid = dyn.grid
        else:
            g = study.grid
            self.positions, self.labels = g.q, list(g.labels)
            self.grid = g.cycle
        self.inertial = []
        for l in self.mech.moving:
            m, J = float(l.mass or 0.0), float(l.J_S or 0.0)
            if (m or J) and s.motion != "static":
                self.inertial.append((l.name, m, J, com_point(study, l) if m else None))

    # ---------------------------------------------------------------------------- motion
    @property
    def rotary(self) -> bool:
        """Whether the input link turns (a crank or a rocker, the balancing moment M_ур) rather than
        an actuator (the balancing force)."""
        return self.mech.driver.rotary

    def motion_law(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """ω = dq/dt and ε = d²q/dt² of the chosen law (zero in the static mode)."""
        s = self.settings
        if s.motion == "dynamics":
            r = self.study.dynamics.result
            return r.omega_at(q), r.eps_at(q)
        if s.motion == "constant":
            d = self.mech.driver
            return np.full(q.shape, float(d.omega)), np.full(q.shape, float(d.epsilon))
        return np.zeros(q.shape), np.zeros(q.shape)

    # ---------------------------------------------------------------------------- loads
    def _loads(self, cols, q) -> list[LoadItem]:
        study = self.study
        out: list[LoadItem] = []
        kinds = {ld.name: ld.kind for ld in study.loads.loads}
        for f in study.loads.forces(cols):
            out.append(LoadItem("G" if kinds.get(f.name) == "weight" else "F", f.name, f.link, f.point,
                                np.asarray(f.Fx, float), np.asarray(f.Fy, float)))
        for m in study.loads.moments(cols):
            out.append(LoadItem("M", m.name, m.link, None, M=np.asarray(m.M, float)))
        for name, m, J, S in self.inertial:
            if m:
                out.append(LoadItem("Phi", f"Φ{name}", name, S, -m * cols["ax_" + S], -m * cols["ay_" + S]))
            if J:
                out.append(LoadItem("MPhi", f"MΦ{name}", name, None, M=-J * cols["e_" + name]))
        if self.settings.flywheel:
            dyn = self.study.dynamics
            J = float(dyn.result.J_I - dyn.J_crank)
            crank = self.mech.driver.link
            out.append(LoadItem("Mfly", f"MΦ{crank}", crank, None, M=-J * cols["e_" + crank]))
        return out

    # ---------------------------------------------------------------------------- solve
    def at(self, q) -> pd.DataFrame:
        """Reactions, balancing moment and checks at arbitrary positions q (``export --at``)."""
        return self.frame(self.solve(np.atleast_1d(np.asarray(q, dtype=float))))

    def solve(self, q, labels: list[str] | None = None, all_points: bool = True) -> Solution:
        """Loads, reactions and checks at the positions q (one kernel call); ``all_points``: the
        true velocities and accelerations of every point among the columns (for the drawings),
        else only of the centres of mass."""
        q = np.ascontiguousarray(np.atleast_1d(np.asarray(q, dtype=float)))
        model = self.model
        base = self.ev(q)
        w, e = self.motion_law(q)
        # the true velocities and accelerations beside the evaluator's columns (which stay
        # unchanged), each computed when first used
        tm = TrueMotion(base, w, e, None if all_points else {S for _, _, _, S in self.inertial if S})
        cols = LazyColumns(list(base) + [k for k in tm.names if k not in base],
                           lambda k: tm[k] if k in tm else base[k])
        loads = self._loads(cols, q)
        N = q.size
        nl = len(model.links)
        lidx = {l: i for i, l in enumerate(model.links)}
        lref = np.zeros((N, nl, 2))
        lext = np.zeros((N, nl, 3))
        for l, p in model.ref.items():
            lref[:, lidx[l], 0] = cols["x_" + p]
            lref[:, lidx[l], 1] = cols["y_" + p]
        for ld in loads:
            k = lidx[ld.link]
            if ld.is_force:
                dx = cols["x_" + ld.point] - lref[:, k, 0]
                dy = cols["y_" + ld.point] - lref[:, k, 1]
                lext[:, k, 0] += ld.Fx
                lext[:, k, 1] += ld.Fy
                lext[:, k, 2] += dx * ld.Fy - dy * ld.Fx
            else:
                lext[:, k, 2] += ld.M
        npair = len(model.pairs)
        jpt = np.zeros((N, npair, 2))
        jdir = np.zeros((N, npair, 2))
        for i, p in enumerate(model.pairs):
            jpt[:, i, 0], jpt[:, i, 1] = cols["x_" + p.point], cols["y_" + p.point]
            if p.kind == KS.K_PRI:
                th = (cols["phi_" + p.a] if p.a != FRAME else 0.0) + p.angle
                jdir[:, i, 0], jdir[:, i, 1] = np.cos(th), np.sin(th)
            elif p.kind == KS.K_ACT:
                dx = cols["x_" + p.point] - cols["x_" + p.base]
                dy = cols["y_" + p.point] - cols["y_" + p.base]
                L = np.hypot(dx, dy)
                jdir[:, i, 0], jdir[:, i, 1] = dx / L, dy / L
        ng = len(model.groups)
        maxl = max(len(g.links) for g in model.groups)
        maxj = max(len(g.pairs) for g in model.groups)
        glink = -np.ones((ng, maxl), np.int64)
        gjoint = -np.ones((ng, maxj), np.int64)
        gnl = np.zeros(ng, np.int64)
        gnj = np.zeros(ng, np.int64)
        for gi, g in enumerate(model.groups):
            glink[gi, :len(g.links)] = [lidx[l] for l in g.links]
            gjoint[gi, :len(g.pairs)] = g.pairs
            gnl[gi], gnj[gi] = len(g.links), len(g.pairs)
        jkind = np.array([p.kind for p in model.pairs], np.int64)
        jlink = np.array([[lidx[p.a], lidx[p.b]] for p in model.pairs], np.int64)
        x, quality, fail = KS.solve_reactions(jkind, jlink, model.offsets, glink, gnl, gjoint, gnj,
                                              jpt, jdir, lref, lext)
        if fail[0] != KS.F_OK:
            from .linkage import describe_position
            i, g = int(fail[1]), int(fail[2])
            where = describe_position(self.study.model, float(q[i]),
                                      labels[i] if labels is not None else None)
            raise StructureError(f"Силовой расчёт: система уравнений равновесия группы {model.groups[g].label} "
                                 f"вырождена в положении {where} (особое положение: реакции не определяются "
                                 f"из уравнений статики).")
        return Solution(q, labels, cols, w, e, loads, jpt, jdir, lref, lext, x, quality)

    @cached_property
    def solution(self) -> Solution:
        """The kinetostatic solution at the report positions."""
        return self.solve(self.positions, self.labels)

    @cached_property
    def cycle_solution(self) -> Solution:
        """The kinetostatic solution over the cycle grid (the diagrams and the extremes of the
        reactions)."""
        return self.solve(self.grid, all_points=False)

    # ---------------------------------------------------------------------------- columns
    def pair_vectors(self, sol: Solution, p: Pair, i: int | None = None) -> dict[str, np.ndarray]:
        """The force (x, y) of ``a`` on ``b`` and, for prismatic and actuator pairs, N, M_p, F."""
        k = self.model.pairs.index(p)
        off = int(self.model.offsets[k])
        sl = slice(None) if i is None else i
        X = sol.x[sl, off:off + p.n]
        ux, uy = sol.jdir[sl, k, 0], sol.jdir[sl, k, 1]
        out: dict[str, np.ndarray] = {}
        if p.kind == KS.K_REV:
            out["Rx"], out["Ry"] = X[..., 0], X[..., 1]
        elif p.kind == KS.K_PRI:
            N, M = X[..., 0], X[..., 1]
            out.update(Rx=-N * uy, Ry=N * ux, N=N, Mp=M)
        elif p.kind == KS.K_ACT:
            F, N, M = X[..., 0], X[..., 1], X[..., 2]
            out.update(Rx=F * ux - N * uy, Ry=F * uy + N * ux, F=F, N=N, Mp=M)
        else:
            out["M"] = X[..., 0]
        return out

    def frame(self, sol: Solution) -> pd.DataFrame:
        """The columns of the force analysis for a solution (docs/outputs.md «Силовой анализ»)."""
        return frame_of(self._columns(sol), sol.labels)

    def _columns(self, sol: Solution, full: bool = True):
        """The columns of :meth:`frame` (``full``), or only those :attr:`scalars` reads: the
        balancing load, |R| of each pair, the checks and what is derived from them (the same
        numbers, without the inertia loads, the reversed reactions and their angles)."""
        mech, model, s = self.mech, self.model, self.settings
        cols = sol.cols
        q = sol.q
        # the columns go straight into the table's block as they are made
        out = (BlockColumns(q.size, {"q": q}, capacity=32 + 8 * len(self.inertial) + 13 * len(model.pairs))
               if full else {"q": q})
        if full:
            self._inertia_columns(sol, out)
        for k, p in enumerate(model.pairs):
            v = self.pair_vectors(sol, p)
            if p.kind == KS.K_MOM:
                out["M_bal"] = v["M"]
                continue
            R = norm(v["Rx"], v["Ry"])          # |R| of both directions (even in each argument)
            if full:
                self._pair_columns(sol, k, p, v, R, out)
            else:
                out[f"R_{p.name}"] = R
            if p.kind == KS.K_ACT:
                out["F_act"] = v["F"]
        # checks
        P = power_balance(sol.loads, cols)
        zh = zhukovsky(sol.loads, cols, mech)
        floor = 1e-3 * self._load_scale(sol)
        if self.rotary:
            d = mech.driver
            main = out["M_bal"]
            out["M_bal_power"] = -P / float(d.direction)
            out["M_bal_zhukovsky"] = zh["M_bal"]
            out["F_bal_zhukovsky"] = zh["F_bal"]
            other = zh["M_bal"]
            out["dev_power"] = _rel(main, out["M_bal_power"], floor)
        else:
            main = out["F_act"]
            out["F_act_power"] = -P
            out["F_act_zhukovsky"] = zh["F_bal"]
            other = zh["F_bal"]
            out["dev_power"] = _rel(main, out["F_act_power"], floor)
        out["dev_zhukovsky_pct"] = 100.0 * _rel(main, other, floor)
        if s.flywheel:
            dyn = self.study.dynamics
            Md = float(dyn.scalars["M_d"]) if dyn.balance == "drive" else math.nan
            out["M_d_dyn"] = np.full(q.shape, float(mech.driver.direction) * Md)
            # the balancing moment of the linkage alone (without the inertia of the first group):
            # the flywheel's moment acts on the crank only and changes no reaction
            if full:
                out["M_bal_linkage"] = out["M_bal"] + out["MPhi_fly"]
        elif self.rotary and s.motion == "dynamics" and self.study.dynamics.balance == "drive":
            # the course's check of the balancing moment against the dynamics: with the inertia
            # loads of the true motion, the linkage is balanced on the crank by what the drive gives
            # minus what the first group (rotor, gear, flywheel) takes to accelerate,
            # M_ур(φ) = M_д − (J_I − J_кр)·ε(φ) (Артоболевский, гл. 14; equation of motion in the
            # differential form, J_II and its derivative being carried by the linkage's own inertia loads)
            dyn = self.study.dynamics
            sgn = float(mech.driver.direction)
            J = float(dyn.result.J_I - dyn.J_crank)
            out["M_d_dyn"] = np.full(q.shape, sgn * float(dyn.scalars["M_d"]))
            out["M_bal_dyn"] = out["M_d_dyn"] - J * cols["e_" + mech.driver.link]
        if s.actuator is not None:
            A = s.actuator
            out["p_act"] = out["F_act"] / (A.count * A.area * A.efficiency)
        if s.capacity is not None:
            c = s.capacity
            A = s.actuator
            Pld = self._load_magnitude(sol, c.load)
            iS = cols["vqy_" + c.point]
            rest = out["F_act"] - Pld * iS
            for pt in list(c.points) + [c.point]:
                ip = cols["vqy_" + pt]
                out[f"i_{pt}"] = ip
                out[f"Gcap_{pt}"] = (A.F_max - rest) / ip
            out["reserve_pct"] = (out[f"Gcap_{c.point}"] - Pld) / Pld * 100.0
        if s.carrier is not None:
            out.update(self._carrier(sol))
        return out

    def _inertia_columns(self, sol: Solution, out) -> None:
        """Angles in degrees, ω, ε and the inertia loads of every link and the flywheel."""
        cols, q = sol.cols, sol.q
        if self.rotary:
            out["q_deg"] = np.degrees(q)
        out["omega"], out["eps"] = sol.omega, sol.eps
        for name, m, J, S in self.inertial:
            if m:
                ax, ay = cols["ax_" + S], cols["ay_" + S]
                a = norm(ax, ay)
                out[f"aSx_{name}"], out[f"aSy_{name}"], out[f"aS_{name}"] = ax, ay, a
                out[f"Phix_{name}"], out[f"Phiy_{name}"] = -m * ax, -m * ay
                out[f"Phi_{name}"] = m * a
            out[f"eps_{name}"] = cols["e_" + name]
            out[f"MPhi_{name}"] = -J * cols["e_" + name]
        for ld in sol.loads:
            if ld.kind == "Mfly":
                out["MPhi_fly"] = ld.M

    @staticmethod
    def _pair_columns(sol: Solution, k: int, p: Pair, v, R, out) -> None:
        """The reaction of pair k in both directions (components, |R|, angle) and, for a
        prismatic or actuator pair, N, M_p, the arm h = M_p/N and the point where N acts."""
        for sgn in (1.0, -1.0):
            key = p.name if sgn > 0 else _reverse(p.name)
            rx, ry = sgn * v["Rx"], sgn * v["Ry"]
            out[f"Rx_{key}"], out[f"Ry_{key}"] = rx, ry
            out[f"R_{key}"] = R
            out[f"Rphi_{key}"] = np.arctan2(ry, rx)
        if p.kind in (KS.K_PRI, KS.K_ACT):
            N, M = v["N"], v["Mp"]
            with np.errstate(divide="ignore", invalid="ignore"):
                h = np.where(N != 0, M / np.where(N != 0, N, 1.0), 0.0)
            out[f"N_{p.name}"], out[f"Mp_{p.name}"], out[f"hN_{p.name}"] = N, M, h
            out[f"xN_{p.name}"] = sol.jpt[:, k, 0] + h * sol.jdir[:, k, 0]
            out[f"yN_{p.name}"] = sol.jpt[:, k, 1] + h * sol.jdir[:, k, 1]

    def _load_scale(self, sol: Solution) -> np.ndarray:
        """Magnitude of the loads in the unit of the balancing load: Σ|F|·l + Σ|M| for a crank
        (l the size of the mechanism), Σ|F| + Σ|M|/l for an actuator (where a balancing value
        is zero, the discrepancy is measured against this scale)."""
        size = self.mech.size()
        f = sum((norm(ld.Fx, ld.Fy) for ld in sol.loads if ld.is_force), np.zeros(sol.q.size))
        m = sum((np.abs(ld.M) for ld in sol.loads if not ld.is_force), np.zeros(sol.q.size))
        return f * size + m if self.rotary else f + m / size

    def _load_magnitude(self, sol: Solution, name: str) -> np.ndarray:
        """Weight-like magnitude of a vertical load: −F_y."""
        for ld in sol.loads:
            if ld.name == name:
                return -ld.Fy
        raise KeyError(name)

    def _carrier(self, sol: Solution) -> dict[str, np.ndarray]:
        c = self.settings.carrier
        G = self._load_magnitude(sol, c.load)
        x = c.forward * -(sol.cols["x_" + c.point] - c.rear_axle)   # arm behind the rear axle
        L, a, b = c.wheelbase, c.ballast_arm, c.weight_arm
        Pb, Pv = c.ballast, c.weight
        total = G + Pv + Pb
        moment0 = Pb * (a + L) + Pv * b
        RA = (moment0 - G * x) / L
        RB = total - RA
        Rmin = c.min_share * total
        return {"x_load": x, "R_front": RA, "R_rear": RB,
                "front_share_pct": RA / total * 100.0, "rear_share_pct": RB / total * 100.0,
                "R_front_min": Rmin,
                "Gmax_carrier": (moment0 - Rmin * L) / x,
                "Gmax_carrier_as_printed": (moment0 - Rmin) / x,
                "Gmax_carrier_consistent": (moment0 - c.min_share * L * (Pv + Pb)) / (x + c.min_share * L)}

    @cached_property
    def table(self) -> pd.DataFrame:
        """Force analysis on the report positions."""
        return self.frame(self.solution)

    @cached_property
    def cycle(self) -> pd.DataFrame:
        """Force analysis on the cycle grid (a crank's cycle or the actuator's stroke)."""
        return self.frame(self.cycle_solution)

    def row(self, label: str) -> pd.Series:
        """The row of the report position ``label`` in the forces table."""
        t = self.table
        return t[t["pos"] == label].iloc[0]

    # ---------------------------------------------------------------------------- details
    def details(self, label: str) -> dict[str, Any]:
        """Loads and reactions at one report position for the drawings: ``loads`` (LoadItem
        values as floats), ``pairs`` (each Pair with the force of a on b at its point, N, M_p,
        F), ``cols`` (the columns at that position)."""
        sol = self.solution
        i = sol.index(label)
        loads = []
        for ld in sol.loads:
            if ld.is_force:
                loads.append(dict(kind=ld.kind, name=ld.name, link=ld.link, point=ld.point,
                                  Fx=float(ld.Fx[i]), Fy=float(ld.Fy[i]), M=None))
            else:
                loads.append(dict(kind=ld.kind, name=ld.name, link=ld.link, point=None, Fx=None, Fy=None,
                                  M=float(ld.M[i])))
        pairs = []
        for k, p in enumerate(self.model.pairs):
            v = {n: float(a) for n, a in self.pair_vectors(sol, p, i).items()}
            v.update(pair=p, x=float(sol.jpt[i, k, 0]), y=float(sol.jpt[i, k, 1]),
                     ux=float(sol.jdir[i, k, 0]), uy=float(sol.jdir[i, k, 1]))
            pairs.append(v)
        cols = {k: float(v[i]) for k, v in sol.cols.items()}
        return {"loads": loads, "pairs": pairs, "cols": cols, "index": i}

    # ---------------------------------------------------------------------------- scalars
    def tables(self) -> dict[str, pd.DataFrame]:
        """The tables of ``reportgen export`` (columns in docs/outputs.md «Силовой анализ»)."""
        return {"forces": self.table, "forces_cycle": self.cycle}

    @staticmethod
    def warmup(study) -> None:
        """Compile the kinetostatics kernel on the warm-up study (``reportgen warmup``)."""
        Forces(study).solve(study.grid.q)

    def _scalar_columns(self, name: str):
        """The columns :attr:`scalars` reads on the report positions (``table``) or the cycle
        (``cycle``): the table itself when it is already made, else only those columns."""
        if name in self.__dict__:
            return _FrameColumns(self.__dict__[name])
        return self._columns(self.solution if name == "table" else self.cycle_solution, full=False)

    @cached_property
    def scalars(self) -> dict[str, Any]:
        """Named scalars (docs/outputs.md «Силовой анализ»)."""
        s = self.settings
        tab, cyc = self._scalar_columns("table"), self._scalar_columns("cycle")
        q = cyc["q"]
        out: dict[str, Any] = {"forces_mode": s.mode, "forces_motion": s.motion}
        main = "M_bal" if self.rotary else "F_act"
        v = cyc[main]
        i = int(np.argmax(np.abs(v)))
        out[f"{main}_absmax"] = float(abs(v[i]))
        out[f"q_{main}_absmax"] = float(q[i])
        out["dev_zhukovsky_max_pct"] = float(max(_max(tab["dev_zhukovsky_pct"]), _max(cyc["dev_zhukovsky_pct"])))
        out["dev_power_max"] = float(max(_max(tab["dev_power"]), _max(cyc["dev_power"])))
        for p in self.model.pairs:
            if p.kind == KS.K_MOM:
                continue
            r = cyc["R_" + p.name]
            k = int(np.argmax(r))
            out[f"R_{p.name}_max"] = float(r[k])
            out[f"q_R_{p.name}_max"] = float(q[k])
        if s.actuator is not None:
            A = s.actuator
            out.update(A_piston=A.area, F_cyl_max=A.F_max, p_system=A.pressure,
                       act_count=A.count, act_efficiency=A.efficiency)
            p = cyc["p_act"]
            k = int(np.argmax(p))
            out["p_act_max"] = float(p[k])
            out["q_p_act_max"] = float(q[k])
            out["pressure_exceeded"] = bool(max(p.max(), _max(tab["p_act"])) > A.pressure)
        if s.capacity is not None:
            r = cyc["reserve_pct"]
            k = int(np.argmin(r))
            out["reserve_min_pct"] = float(r[k])
            out["q_reserve_min"] = float(q[k])
        if s.carrier is not None:
            r = cyc["R_front"]
            k = int(np.argmin(r))
            out["R_front_min_value"] = float(r[k])
            out["q_R_front_min"] = float(q[k])
        if "M_bal_dyn" in tab:
            out["dev_M_bal_dyn_max"] = float(np.max(np.abs(tab["M_bal"] - tab["M_bal_dyn"]))
                                             / np.max(np.abs(tab["M_bal"])))
        if s.flywheel:
            out["dev_M_bal_M_d_max"] = float(np.max(np.abs(tab["M_bal"] - tab["M_d_dyn"])
                                                    / np.abs(tab["M_d_dyn"])))
        return out


class _FrameColumns:
    """The columns of a DataFrame as arrays, each taken when asked for."""

    __slots__ = ("df",)

    def __init__(self, df: pd.DataFrame):
        self.df = df

    def __getitem__(self, k: str) -> np.ndarray:
        return self.df[k].to_numpy()

    def __contains__(self, k) -> bool:
        return k in self.df.columns


def _max(a: np.ndarray) -> float:
    """The largest value of a column, NaN skipped (as ``Series.max``)."""
    return float(np.nanmax(a)) if not np.isnan(a).all() else math.nan


def _reverse(key: str) -> str:
    a, b, *rest = key.split("_")
    return "_".join([b, a] + rest)


def _rel(a, b, floor=0.0) -> np.ndarray:
    """|a − b| / max(|a|, |b|, floor) (0 where all vanish)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    den = np.maximum(np.maximum(np.abs(a), np.abs(b)), floor)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0, np.abs(a - b) / np.where(den > 0, den, 1.0), 0.0)
