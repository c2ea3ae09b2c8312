"""Synthesis of a cam mechanism (синтез кулачкового механизма) from the case's ``[cam]``.

Method (Артоболевский И. И., «Теория механизмов и машин», гл. 24; Попов С. А., Тимофеев Г. А.,
«Курсовое проектирование по теории механизмов и механике машин», гл. 6; domain.md §1.6):

* laws of the phases of rise and return (:mod:`reportgen.core.cams`), impacts from the jumps of
  s′ (жёсткие) and s″ (мягкие) at the phase boundaries and inside the laws;
* pressure angle of a knife-edge or roller follower by the kinematic inversion: with w = B − O
  (cam centre O, follower point B), u the direction of motion of B on the rise, r = −J u
  (J — rotation by 90°), v′ the velocity analog of B and k = ±1 the sense of rotation
  (counter-clockwise +1)::

      tg ϑ = (v′ − k w·r) / (w·u)        (translating: tg ϑ = (s′ − e)/(s₀ + s))

* the minimum size from the allowed angles [ϑ_у] (rise) and [ϑ_в] (return): every position gives
  a half-plane for O (a ray of the phase portrait); the governing ray touches the portrait where
  d/dφ of the constraint vanishes (translating: s″/s′ = tg[ϑ]), found by root finding.  For a
  translating follower the two families are parallel lines, so O is the point of the region
  nearest to B₀ in closed form; for a rocker the region is found by SLSQP on the exact
  constraint maxima and polished by Newton on the contact conditions;
* flat-faced translating follower: ρ = r₀ + s + s″ ≥ ρ_min, face width s′_max − s′_min;
* flat-faced rocker (the face offset d from the pivot): the profile is the envelope of the face
  lines, contact at μ = a_w cos(ψ₀ + ψ)/(1 − kψ′) along the face, ρ = a_w G − d, tg ϑ = d/μ;
  a_w and ψ₀ from ρ ≥ ρ_min and ϑ ≤ [ϑ] (see the block before :meth:`Cam.fr_G`);
* profile by inversion C(φ) = R(−kφ) B(φ) with analytic C′, C″; the working profile of a roller
  is the exact offset C − r_р n along the unit normal of the centre profile.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any

import numpy as np
import pandas as pd

from ..case import units as U
from ..core import cams as K
from .roots import brentq


def _scipy(name: str):
    """``scipy.optimize.<name>``, imported when a cam is computed (every note imports this
    module for its laws; importing scipy.optimize costs about 0,3 s of CPU)."""
    def call(*args, **kw):
        from scipy import optimize
        return getattr(optimize, name)(*args, **kw)
    return call


fsolve, minimize, minimize_scalar = _scipy("fsolve"), _scipy("minimize"), _scipy("minimize_scalar")

__all__ = ["Cam", "LAWS", "Phase"]

# law name → (Russian name, code)
LAWS = {
    "uniform": ("равномерный (линейный)", K.UNIFORM),
    "parabolic": ("параболический (равноускоренный)", K.PIECEWISE),
    "cosine": ("косинусоидальный", K.COSINE),
    "sine": ("синусоидальный (циклоидальный)", K.SINE),
    "poly345": ("полиномиальный 3-4-5", K.POLY345),
    "poly4567": ("полиномиальный 4-5-6-7", K.POLY4567),
    "trapezoidal": ("трапецеидальный закон ускорения", K.PIECEWISE),
    "table": ("заданный таблицей аналога ускорения", K.PIECEWISE),
}
PHASE_RU = {K.RISE: "удаление", K.DWELL_HIGH: "дальнее стояние", K.RETURN: "возвращение",
            K.DWELL_LOW: "ближнее стояние"}


@dataclass
class Phase:
    """One phase of the cam's cycle (удаление, дальнее стояние, возвращение, ближнее стояние): its
    kind, start and length in cam angle, the law of the follower's motion, the acceleration ratio
    ν = a₂/a₁, the ramp and the allowed pressure angle [ϑ] (domain.md § 1.6)."""
    kind: int
    start: float
    length: float
    law: str = ""
    nu: float = 1.0
    ramp: float = 0.125
    allowed: float = 0.0
    knots: tuple = (np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(2))

    @property
    def x1(self) -> float:
        """The share of the phase before the law's inflection: f₁/β = ν/(1 + ν) for the acceleration
        ratio ν = a₂/a₁ (domain.md § 1.6, asymmetric laws)."""
        return self.nu / (1.0 + self.nu)


@dataclass
class Synthesis:
    """The cam's size found by the synthesis: r₀; for a translating follower the offset e and s₀ (r₀
    = √(s₀² + e²)); for a rocker the centre distance a_w and the initial angle ψ₀; the cam centre
    in the synthesis frame and the tangent points that govern it (Артоболевский § 25; domain.md §
    1.6)."""
    r0: float
    e: float = 0.0          # translating: signed offset (tg ϑ = (s′ − e)/(s₀ + s))
    s0: float = 0.0
    a_w: float = 0.0        # rocker: centre distance and initial angle
    psi0: float = 0.0
    O: np.ndarray = field(default_factory=lambda: np.zeros(2))   # cam centre in the synthesis frame
    phi_rise: float = math.nan   # cam angles of the governing tangent points
    phi_return: float = math.nan
    governing: str = ""     # "rise", "return", "both", "fixed", "convexity"
    r0_approx: float = math.nan
    e_approx: float = math.nan
    a_w_approx: float = math.nan
    exact: "Synthesis | None" = None   # the least sizes before r₀ was rounded up (None: not rounded)


def _piece_knots(name: str, nu: float, ramp: float, table) -> tuple:
    if name == "parabolic":
        x1 = nu / (1 + nu)
        x, a = [0, x1, x1, 1], [1 / x1, 1 / x1, -1 / (1 - x1), -1 / (1 - x1)]
    elif name == "trapezoidal":
        t = ramp
        x, a = [0, t, 0.5 - t, 0.5 + t, 1 - t, 1], [0, 1, 1, -1, -1, 0]
    else:
        x, a = [p[0] for p in table], [p[1] for p in table]
    return K.piecewise_knots(x, a)


class Cam:
    """The cam task of a Study: reads and checks ``[cam]`` on creation."""

    GRID_STEP = math.radians(0.5)

    def __init__(self, study):
        self.study = study
        node = study.root.table("cam")
        self.node = node
        self._read(node, study.params)

    @staticmethod
    def warmup(study) -> None:
        """Compile the law kernels (numba, cached on disk) on a tiny input of every law."""
        x = np.array([0.0, 0.5, 1.0])
        k = K.piecewise_knots(x, np.array([1.0, 0.0, -1.0]))
        for code in (K.UNIFORM, K.COSINE, K.SINE, K.POLY345, K.POLY4567, K.PIECEWISE):
            for side in (1, -1):
                K.cam_cycle(np.array([0.3]), np.array([0.0]), np.array([1.0]), np.array([K.RISE], dtype=np.int64),
                            np.array([code], dtype=np.int64), np.array([0.5]), np.array([0, 3], dtype=np.int64),
                            *k, 0.01, side)

    # ------------------------------------------------------------------ reading
    def _read(self, node, names) -> None:
        node.check_keys(["follower", "contact", "rotation", "speed", "stroke", "swing", "arm",
                         "far_dwell", "rise", "return", "r0", "e", "a_w", "psi0", "roller",
                         "rho_min", "step", "scale", "title", "face_offset", "r0_round"], required=["rise", "return"])
        self.follower = node.string("follower", "translating", choices=["translating", "rocker"])
        self.contact = node.string("contact", "roller", choices=["knife", "roller", "flat"])
        self.k = 1 if node.string("rotation", "ccw", choices=["ccw", "cw"]) == "ccw" else -1
        self.omega = node.quantity("speed", U.ANGULAR_VELOCITY, names, positive=True)
        self.title = node.string("title", "")
        if self.follower == "translating":
            if node.has("swing") or node.has("arm"):
                raise node.error("swing" if node.has("swing") else "arm",
                                 "ход коромысла задаётся только для толкателя-коромысла",
                                 expected="stroke для поступательного толкателя или follower = \"rocker\"")
            self.h = node.quantity("stroke", U.LENGTH, names, required=True, positive=True)
            self.arm = 0.0
        else:
            if node.has("stroke"):
                raise node.error("stroke", "у коромысла задаётся угол размаха, а не ход",
                                 expected="swing = \"20 deg\" и arm = \"100 mm\"")
            self.h = node.quantity("swing", U.ANGLE, names, required=True, positive=True)
            if self.contact == "flat":
                if node.has("arm"):
                    raise node.error("arm", "у коромысла с плоской тарелкой длина плеча не задаётся: рабочая "
                                            "длина тарелки находится по крайним точкам касания",
                                     expected="face_offset — смещение плоскости тарелки от оси качания")
                self.arm = 0.0
            else:
                self.arm = node.quantity("arm", U.LENGTH, names, required=True, positive=True)
            if self.h >= math.pi / 2:
                raise node.error("swing", "слишком большой угол размаха коромысла", expected="угол < 90°")
            if node.has("e"):
                raise node.error("e", "эксцентриситет задаётся только для поступательного толкателя",
                                 expected="a_w и psi0 для коромысла")
        self.flat_rocker = self.follower == "rocker" and self.contact == "flat"
        if node.has("face_offset") and not self.flat_rocker:
            raise node.error("face_offset", "смещение тарелки задаётся только для коромысла с плоской тарелкой",
                             expected="follower = \"rocker\" и contact = \"flat\"")
        self.face_offset = node.quantity("face_offset", U.LENGTH, names, default=0.0, nonnegative=True)
        if self.contact == "flat" and (node.has("e") or node.has("roller")):
            key = "e" if node.has("e") else "roller"
            raise node.error(key, "у плоского толкателя нет смещения и ролика",
                             expected="r0 или rho_min")
        if self.contact != "roller" and node.has("roller"):
            raise node.error("roller", "радиус ролика задаётся только при contact = \"roller\"")
        rise = self._phase(node.table("rise", required=True), K.RISE, 0.0, names)
        dw = node.quantity("far_dwell", U.ANGLE, names, default=0.0, nonnegative=True)
        ret = self._phase(node.table("return", required=True), K.RETURN, rise.length + dw, names)
        near = 2 * math.pi - rise.length - dw - ret.length
        if near < -1e-9:
            raise node.error("return", "сумма углов удаления, дальнего стояния и возвращения больше 360°",
                             got=f"{math.degrees(rise.length + dw + ret.length):.6g}°")
        near = max(near, 0.0)
        self.phases = [rise, Phase(K.DWELL_HIGH, rise.length, dw), ret,
                       Phase(K.DWELL_LOW, ret.start + ret.length, near)]
        self.r0_fixed = node.quantity("r0", U.LENGTH, names, positive=True)
        self.e_fixed = node.quantity("e", U.LENGTH, names)
        self.aw_fixed = node.quantity("a_w", U.LENGTH, names, positive=True)
        self.psi0_fixed = node.quantity("psi0", U.ANGLE, names, positive=True)
        if (self.aw_fixed is None) != (self.psi0_fixed is None) and not self.flat_rocker:
            raise node.error("a_w" if self.aw_fixed is None else "psi0",
                             "межосевое расстояние и начальный угол коромысла задаются вместе",
                             expected="оба ключа a_w и psi0 или ни одного")
        if self.follower == "rocker" and node.has("r0"):
            raise node.error("r0", "для коромысла задайте a_w и psi0, а не r0")
        self.roller_fixed = node.quantity("roller", U.LENGTH, names, positive=True)
        # the least r₀ of the synthesis is rounded up to a multiple of this (a whole millimetre, as
        # the textbook takes it); 0 keeps the exact least size
        self.r0_round = node.quantity("r0_round", U.LENGTH, names, default="1 mm", nonnegative=True)
        self.rho_min = node.quantity("rho_min", U.LENGTH, names, default="5 mm", nonnegative=True)
        self.step = node.quantity("step", U.ANGLE, names, default="10 deg", positive=True)
        self.scale = node.string("scale", None, choices=["10:1", "5:1", "4:1", "2,5:1", "2:1", "1:1", "1:2",
                                                          "1:2,5", "1:4", "1:5", "1:10"])
        if math.degrees(self.step) < 1 or math.degrees(self.step) > 45:
            raise node.error("step", "шаг таблицы координат вне допустимого диапазона", expected="от 1° до 45°")
        if self.contact != "flat":
            for p in (rise, ret):
                if p.allowed <= 0:
                    raise node.error(("rise" if p.kind == K.RISE else "return") + ".allowed",
                                     "не задан допустимый угол давления", expected="угол, например \"30 deg\"")

    def _phase(self, node, kind, start, names) -> Phase:
        node.check_keys(["angle", "law", "nu", "ramp", "table", "allowed"], required=["angle", "law"])
        beta = node.quantity("angle", U.ANGLE, names, required=True, positive=True)
        law = node.string("law", required=True, choices=list(LAWS))
        nu = 1.0
        if node.has("nu"):
            if law not in ("sine", "parabolic"):
                raise node.error("nu", "отношение ускорений ν задаётся только для законов sine и parabolic")
            nu = node.quantity("nu", U.DIMENSIONLESS, names, positive=True)
        ramp = 0.125
        if node.has("ramp"):
            if law != "trapezoidal":
                raise node.error("ramp", "доля нарастания ускорения задаётся только для закона trapezoidal")
            ramp = node.quantity("ramp", U.DIMENSIONLESS, names, positive=True)
            if ramp > 0.25:
                raise node.error("ramp", "доля нарастания ускорения больше 1/4", expected="0 < ramp ≤ 0.25")
        table = None
        if law == "table":
            table = self._table(node)
        elif node.has("table"):
            raise node.error("table", "таблица ускорения задаётся только для law = \"table\"")
        allowed = node.quantity("allowed", U.ANGLE, names, default=0.0, nonnegative=True)
        if allowed >= math.pi / 2:
            raise node.error("allowed", "допустимый угол давления должен быть меньше 90°")
        ph = Phase(kind, start, beta, law, nu, ramp, allowed)
        ph.knots = _piece_knots(law, nu, ramp, table) if LAWS[law][1] == K.PIECEWISE else ph.knots
        if law == "table":
            x, a, v, f = ph.knots
            if not abs(v[-1]) <= 1e-9 * max(1.0, float(np.max(np.abs(v)))):
                raise node.error("table", "площадь под графиком аналога ускорения не равна нулю: "
                                          "в конце фазы скорость толкателя не обращается в нуль",
                                 expected="равные площади положительной и отрицательной частей")
        return ph

    @staticmethod
    def _table(node) -> list:
        t = node.raw("table")
        bad = node.error("table", "ожидалась таблица точек [x, a] аналога ускорения",
                         expected="[[0, 0], [0.25, 1], [0.75, -1], [1, 0]] с x от 0 до 1 по неубыванию")
        if not isinstance(t, list) or len(t) < 2:
            raise bad
        pts = []
        for p in t:
            if (not isinstance(p, list) or len(p) != 2
                    or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in p)):
                raise bad
            pts.append((float(p[0]), float(p[1])))
        xs = [p[0] for p in pts]
        if xs[0] != 0 or xs[-1] != 1 or any(b < a for a, b in zip(xs, xs[1:])) or \
                any(a == b == c for a, b, c in zip(xs, xs[1:], xs[2:])):
            raise bad
        return pts

    # ------------------------------------------------------------------ the laws
    @cached_property
    def _packed(self):
        ph = self.phases
        starts = np.array([p.start for p in ph])
        lengths = np.array([p.length for p in ph])
        kinds = np.array([p.kind for p in ph], dtype=np.int64)
        codes = np.array([LAWS[p.law][1] if p.law else 0 for p in ph], dtype=np.int64)
        x1s = np.array([p.x1 for p in ph])
        kn = [p.knots for p in ph]
        koff = np.cumsum([0] + [len(k[0]) for k in kn]).astype(np.int64)
        cat = [np.concatenate([k[i] for k in kn]) for i in range(4)]
        return starts, lengths, kinds, codes, x1s, koff, *cat

    def law(self, phi, side: int = 1) -> tuple[np.ndarray, ...]:
        """s, s′, s″, s‴ at cam angles φ (rad, 0 … 2π from the start of the rise)."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        return K.cam_cycle(phi, *self._packed, float(self.h), int(side))

    def _at(self, phi: float, side: int = 1) -> tuple[float, float, float, float]:
        return tuple(float(v[0]) for v in self.law(np.array([phi]), side))

    def breaks(self, ph: Phase) -> list[float]:
        """Cam angles of the pieces of a phase (its ends and the knots / inflection inside)."""
        xs = {0.0, 1.0}
        if LAWS[ph.law][1] == K.PIECEWISE:
            xs |= set(float(v) for v in ph.knots[0])
        elif LAWS[ph.law][1] == K.SINE:
            xs.add(ph.x1)
        return [ph.start + x * ph.length for x in sorted(xs)]

    @cached_property
    def impacts(self) -> list[dict]:
        """Jumps of s′ (hard impact) and of s″ (soft impact), with the cam angle."""
        pts = []
        for ph in self.phases:
            if ph.length > 0 and ph.law:
                pts += self.breaks(ph)
        uniq: list[float] = []
        for x in sorted(x % (2 * math.pi) for x in pts):
            if not uniq or x - uniq[-1] > 1e-12:
                uniq.append(x)
        if len(uniq) > 1 and uniq[-1] > 2 * math.pi - 1e-12:
            uniq.pop()
        out = []
        # one-sided limits a hair off the break: the kernel finds the piece of a law by comparing the
        # relative angle x = (φ − φ_start)/β with the knots, and x recomputed from φ = φ_start + x₁β
        # may land one ulp past an interior knot (the parabolic law's x₁ = 1/2 read as the right
        # piece from both sides, its middle soft impact lost); 1e-12 rad changes s″ by s‴·1e-12
        eps = 1e-12
        for p in uniq:
            right = self._at(p + eps, 1)
            left = self._at((p if p > 0 else 2 * math.pi) - eps, -1)
            d1, d2 = right[1] - left[1], right[2] - left[2]
            scale1 = self.h / min(ph.length for ph in self.phases if ph.law)
            if abs(d1) > 1e-9 * scale1:
                out.append({"phi": p % (2 * math.pi), "kind": "hard", "jump": d1})
            elif abs(d2) > 1e-9 * scale1 / min(ph.length for ph in self.phases if ph.law):
                out.append({"phi": p % (2 * math.pi), "kind": "soft", "jump": d2})
        return out

    def phase_extreme(self, ph: Phase, fun, dfun, sign: float = 1.0, vec: bool = False) -> tuple[float, float]:
        """max of sign·fun over the phase: end values (one-sided) and the roots of dfun in each
        piece, bracketed on a grid and found by Brent's method (not by sampling).  With ``vec``
        fun and dfun take an array of angles (one kernel call for the whole bracketing grid)."""
        if vec:
            fv, dv = fun, dfun
            fun = lambda p, sd: float(fv(np.array([p]), sd)[0])      # noqa: E731
            dfun = lambda p, sd: float(dv(np.array([p]), sd)[0])     # noqa: E731
        best = (-math.inf, math.nan)
        b = self.breaks(ph)
        for a0, a1 in zip(b, b[1:]):
            if a1 <= a0:
                continue
            for p, side in ((a0, 1), (a1, -1)):
                v = sign * fun(p, side)
                if v > best[0]:
                    best = (v, p)
            g = np.linspace(a0, a1, 65)
            d = sign * np.asarray(dv(g, 1)) if vec else np.array([sign * dfun(x, 1) for x in g])
            for i in range(len(g) - 1):
                if d[i] > 0 >= d[i + 1]:
                    r = brentq(lambda x: sign * dfun(x, 1), g[i], g[i + 1], xtol=1e-15, rtol=1e-15, maxiter=200)
                    v = sign * fun(r, 1)
                    if v > best[0]:
                        best = (v, r)
        return best

    def analog_max(self, ph: Phase, order: int) -> float:
        """Exact max |s′| (order 1) or |s″| (order 2) over a phase: the end values and the roots
        of the next derivative by :meth:`phase_extreme` (a sampled maximum misses a peak between
        grid points, e.g. the kink of f′ at x₁ of an asymmetric parabolic law)."""
        return max(self.phase_extreme(ph, lambda p, sd: sg * self._at(p, sd)[order],
                                      lambda p, sd: sg * self._at(p, sd)[order + 1])[0] for sg in (1.0, -1.0))

    @property
    def face_width(self) -> float:
        """Flat translating follower: the least face width b = s′max − s′min, the contact point
        being s′ off the follower's axis."""
        lo, hi = self.s1_extremes
        return hi - lo

    @cached_property
    def s1_extremes(self) -> tuple[float, float]:
        """min and max of s′ over the cycle: exact extremes over both phases (0 at a dwell)."""
        hi = max([0.0] + [self.phase_extreme(ph, lambda p, sd: self._at(p, sd)[1],
                                             lambda p, sd: self._at(p, sd)[2])[0] for ph in (self.rise, self.ret)])
        lo = min([0.0] + [-self.phase_extreme(ph, lambda p, sd: -self._at(p, sd)[1],
                                              lambda p, sd: -self._at(p, sd)[2])[0] for ph in (self.rise, self.ret)])
        return lo, hi

    # ------------------------------------------------------------------ synthesis
    @property
    def rise(self) -> Phase:
        """The rise phase (удаление)."""
        return self.phases[0]

    @property
    def ret(self) -> Phase:
        """The return phase (возвращение, сближение)."""
        return self.phases[2]

    def _geom(self, phi: float, side: int, O) -> dict:
        """B, u, r, v′, v″ of the follower point at φ in the synthesis frame (B₀ at (0,0) for a
        translating follower; the rocker pivot A at (0,0), arm along x at the start)."""
        s, s1, s2, s3 = self._at(phi, side)
        if self.follower == "translating":
            B, u, r, v1, v2 = np.array([0.0, s]), np.array([0.0, 1.0]), np.array([1.0, 0.0]), s1, s2
            dB, dr, du = np.array([0.0, s1]), np.zeros(2), np.zeros(2)
        else:
            L = self.arm
            r = np.array([math.cos(s), math.sin(s)])
            u = np.array([-math.sin(s), math.cos(s)])
            B, v1, v2 = L * r, L * s1, L * s2
            dB, dr, du = L * s1 * u, s1 * u, -s1 * r
        w = B - np.asarray(O)
        return dict(B=B, u=u, r=r, v1=v1, v2=v2, w=w, dB=dB, dr=dr, du=du)

    def _h(self, which: int, phi: float, side: int, O) -> tuple[float, float]:
        """Constraint h(φ, O) ≤ 0 of the allowed angle (which = 1 rise, 2 return) and dh/dφ."""
        g = self._geom(phi, side, O)
        k, w, u, r = self.k, g["w"], g["u"], g["r"]
        dw = g["dB"]
        t = math.tan(self.rise.allowed if which == 1 else self.ret.allowed)
        sg = 1.0 if which == 1 else -1.0
        h = sg * (g["v1"] - k * w @ r) - t * (w @ u)
        dh = sg * (g["v2"] - k * (dw @ r + w @ g["dr"])) - t * (dw @ u + w @ g["du"])
        return h, dh

    def halfplane(self, which: int, phi: float) -> tuple[np.ndarray, float]:
        """The ray of the phase portrait at φ as a half-plane n·O ≤ c of allowed centres
        (h(φ, O) is linear in O: h = h(φ, 0) + n·O with n = ±k r + tg[ϑ] u)."""
        g = self._geom(phi, 1, np.zeros(2))
        t = math.tan(self.rise.allowed if which == 1 else self.ret.allowed)
        sg = 1.0 if which == 1 else -1.0
        return sg * self.k * g["r"] + t * g["u"], -self._h(which, phi, 1, np.zeros(2))[0]

    @staticmethod
    def nearest_in_two(B0, hp1, hp2) -> np.ndarray:
        """The point of {n₁·O ≤ c₁, n₂·O ≤ c₂} nearest to B₀: a projection on one line or the vertex."""
        best = None
        for (n, c), (m, d) in ((hp1, hp2), (hp2, hp1)):
            P = B0 - (n @ B0 - c) / (n @ n) * n
            if m @ P <= d + 1e-14 * (abs(d) + 1) and (best is None or np.hypot(*(P - B0)) < np.hypot(*(best - B0))):
                best = P
        if best is None:
            best = np.linalg.solve(np.array([hp1[0], hp2[0]]), np.array([hp1[1], hp2[1]]))
        return best

    def _hmax(self, which: int, O) -> tuple[float, float]:
        ph = self.rise if which == 1 else self.ret
        return self.phase_extreme(ph, lambda p, sd: self._h(which, p, sd, O)[0],
                                  lambda p, sd: self._h(which, p, sd, O)[1])

    @cached_property
    def synthesis(self) -> Synthesis:
        """The accepted cam size: the least one (:meth:`least_size`) with r₀ rounded up to a whole
        millimetre (``r0_round``), as the textbook takes it before building the profile (Попов С. А.,
        Тимофеев Г. А., гл. 6: «принимаем r₀ = … мм»); every later quantity — the profile, the
        pressure angles, the drawings — uses it.  The other sizes follow r₀ so that the centre stays
        in the admissible region: a translating follower keeps its offset e (s₀ = √(r₀² − e²)
        grows, and every ray's condition s₀ ≥ M − e/tg[ϑ] holds with margin); a flat-faced rocker
        keeps ψ₀ (a_w = (r₀ + d)/sin ψ₀ grows, and both conditions are lower bounds on a_w); a
        rocker moves O away from B₀ along the line B₀O (checked against both phases' rays).
        Given sizes are used as given."""
        syn = self.least_size
        step = self.r0_round
        if syn.governing == "fixed" or not step > 0 or (self.flat_rocker and self.aw_fixed is not None):
            return syn
        r0 = math.ceil(syn.r0 / step * (1 - 1e-12)) * step
        if r0 <= syn.r0:
            return syn
        acc = replace(syn, r0=r0, exact=syn)
        if self.flat_rocker:
            acc.a_w = (r0 + self.face_offset) / math.sin(syn.psi0)
            acc.O = self._rocker_O(acc.a_w, syn.psi0)
        elif self.contact == "flat":
            acc.s0 = r0
        elif self.follower == "translating":
            acc.s0 = math.sqrt(r0 * r0 - syn.e * syn.e)
        else:
            B0 = np.array([self.arm, 0.0])
            O = B0 + (syn.O - B0) * (r0 / syn.r0)
            if max(self._hmax(1, O)[0], self._hmax(2, O)[0]) > 1e-9 * self.arm:
                return syn          # the line B₀O leaves the region: the least size stays
            acc.O = O
            acc.a_w = float(np.hypot(*O))
            acc.psi0 = math.atan2(-O[1], O[0])
        return acc

    @cached_property
    def least_size(self) -> Synthesis:
        """The least cam size by the allowed pressure angle (the phase portrait s(s′) and its
        tangent rays, domain.md § 1.6), or by convexity ρ = r₀ + s + s″ > 0 for a flat-faced
        follower; the size given by the case when it gives one."""
        if self.flat_rocker:
            return self._synth_flat_rocker()
        if self.contact == "flat":
            return self._synth_flat()
        if self.follower == "translating":
            return self._synth_translating()
        return self._synth_rocker()

    def _synth_flat(self) -> Synthesis:
        # ρ = r₀ + s + s″ ≥ ρ_min  ⇒  r₀ ≥ ρ_min − min(s + s″)
        mins = []
        for ph in (self.rise, self.ret):
            v, p = self.phase_extreme(ph, lambda x, sd: self._at(x, sd)[0] + self._at(x, sd)[2],
                                      lambda x, sd: self._at(x, sd)[1] + self._at(x, sd)[3], sign=-1.0)
            mins.append((-v, p))
        mins.append((0.0, math.nan) if self.phases[1].length > 0 or self.phases[3].length > 0 else mins[0])
        m, p = min(mins, key=lambda t: t[0])
        r0_min = self.rho_min - m
        self.flat_min = (m, p, r0_min)   # min(s + s″), where, and the r₀ it requires
        if self.r0_fixed is not None:
            return Synthesis(r0=self.r0_fixed, s0=self.r0_fixed, governing="fixed", phi_rise=p)
        return Synthesis(r0=r0_min, s0=r0_min, governing="convexity", phi_rise=p)

    def _synth_translating(self) -> Synthesis:
        t1, t2 = math.tan(self.rise.allowed), math.tan(self.ret.allowed)
        # s₀ ≥ M₁ − e/t₁ (rise), s₀ ≥ M₂ + e/t₂ (return); M by the exact tangent points
        f1 = lambda p, sd: self._at(p, sd)[1] / t1 - self._at(p, sd)[0]          # noqa: E731
        d1 = lambda p, sd: self._at(p, sd)[2] / t1 - self._at(p, sd)[1]          # noqa: E731
        f2 = lambda p, sd: -self._at(p, sd)[1] / t2 - self._at(p, sd)[0]         # noqa: E731
        d2 = lambda p, sd: -self._at(p, sd)[2] / t2 - self._at(p, sd)[1]         # noqa: E731
        M1, p1 = self.phase_extreme(self.rise, f1, d1)
        M2, p2 = self.phase_extreme(self.ret, f2, d2)
        # approximate variant: the rays through the points of s′max and s′min
        q1 = self.phase_extreme(self.rise, lambda p, sd: self._at(p, sd)[1], lambda p, sd: self._at(p, sd)[2])[1]
        q2 = self.phase_extreme(self.ret, lambda p, sd: -self._at(p, sd)[1], lambda p, sd: -self._at(p, sd)[2])[1]
        A1, A2 = f1(q1, 1), f2(q2, 1)
        e, s0, gov = self._nearest(M1, M2, t1, t2)
        ea, s0a, _ = self._nearest(A1, A2, t1, t2)
        if self.r0_fixed is not None:
            e = self.e_fixed if self.e_fixed is not None else 0.0
            if abs(e) >= self.r0_fixed:
                raise self.node.error("e", "смещение толкателя не меньше радиуса r0")
            s0, gov = math.sqrt(self.r0_fixed ** 2 - e * e), "fixed"
        elif self.e_fixed is not None:
            e = self.e_fixed
            s0 = max(M1 - e / t1, M2 + e / t2)
            gov = "rise" if M1 - e / t1 >= M2 + e / t2 else "return"
        if not s0 > 0:
            raise self.node.error("rise.allowed", "допустимые углы давления не ограничивают размеры кулачка",
                                  expected="задайте r0 явно")
        return Synthesis(r0=math.hypot(s0, e), e=e, s0=s0, phi_rise=p1, phi_return=p2, governing=gov,
                         r0_approx=math.hypot(s0a, ea), e_approx=ea)

    @staticmethod
    def _nearest(M1, M2, t1, t2) -> tuple[float, float, str]:
        """The point (e, s₀) of {s₀ ≥ M₁ − e/t₁, s₀ ≥ M₂ + e/t₂} nearest to the origin."""
        for M, n, other, gov in ((M1, (1 / t1, 1.0), lambda e, s: s - M2 - e / t2, "rise"),
                                 (M2, (-1 / t2, 1.0), lambda e, s: s - M1 + e / t1, "return")):
            nn = n[0] ** 2 + n[1] ** 2
            e, s = M * n[0] / nn, M * n[1] / nn
            if other(e, s) >= -1e-15 * (abs(M1) + abs(M2)):
                return e, s, gov
        e = (M1 - M2) / (1 / t1 + 1 / t2)
        return e, M1 - e / t1, "both"

    def _synth_rocker(self) -> Synthesis:
        L = self.arm
        if self.aw_fixed is not None:
            return self._rocker_result(self._rocker_O(self.aw_fixed, self.psi0_fixed), "fixed")
        O = self.synth_generic(np.array([L, 0.0]), L)
        syn = self._rocker_result(O, self._gov)
        # approximate variant: the rays through the points of the largest |ψ′|
        q1 = self.phase_extreme(self.rise, lambda p, sd: self._at(p, sd)[1], lambda p, sd: self._at(p, sd)[2])[1]
        q2 = self.phase_extreme(self.ret, lambda p, sd: -self._at(p, sd)[1], lambda p, sd: -self._at(p, sd)[2])[1]
        Oa = self.nearest_in_two(np.array([L, 0.0]), self.halfplane(1, q1), self.halfplane(2, q2))
        syn.r0_approx = float(np.hypot(L - Oa[0], Oa[1]))
        syn.a_w_approx = float(np.hypot(*Oa))
        return syn

    def synth_generic(self, B0, sc: float) -> np.ndarray:
        """The centre O nearest to B₀ with max h ≤ 0 on the rise and the return: SLSQP on the exact
        maxima (root-found tangent points), then Newton on the contact conditions.  Serves the
        rocker; for a translating follower it is an independent check of the closed form."""
        cons = [{"type": "ineq", "fun": lambda O: -self._hmax(1, O * sc)[0] / sc},
                {"type": "ineq", "fun": lambda O: -self._hmax(2, O * sc)[0] / sc}]
        x0 = (B0 - 2.0 * sc * np.array([0.0, 1.0])) / sc
        res = minimize(lambda O: float((O - B0 / sc) @ (O - B0 / sc)), x0, method="SLSQP",
                       constraints=cons, options={"ftol": 1e-15, "maxiter": 200})
        return self._polish(res.x * sc, B0, sc)

    def _rocker_O(self, a, psi0) -> np.ndarray:
        """Cam centre at distance a_w from the pivot, at angle ψ₀ from the arm's start on the side
        opposite to the motion of B (below the arm)."""
        return np.array([a * math.cos(psi0), -a * math.sin(psi0)])

    def _polish(self, O, B0, sc: float) -> np.ndarray:
        """Newton on the contact conditions of the active rays (h = 0 and dh/dφ = 0 at the tangent
        point, O − B₀ along the ray's normal when one ray governs)."""
        act = []
        for which in (1, 2):
            v, p = self._hmax(which, O)
            if v > -1e-6 * sc:
                act.append((which, p))
        self._gov = {1: "rise", 2: "return"}[act[0][0]] if len(act) == 1 else "both"
        if not act:
            return O

        def grad(which, p):
            g = self._geom(p, 1, O)
            t = math.tan(self.rise.allowed if which == 1 else self.ret.allowed)
            sg = 1.0 if which == 1 else -1.0
            return sg * self.k * g["r"] + t * g["u"]

        if len(act) == 2:
            def F(z):
                O_, p1, p2 = z[:2], z[2], z[3]
                return [self._h(1, p1, 1, O_)[0] / sc, self._h(1, p1, 1, O_)[1] / sc,
                        self._h(2, p2, 1, O_)[0] / sc, self._h(2, p2, 1, O_)[1] / sc]
            z0 = [O[0], O[1], act[0][1], act[1][1]]
        else:
            which, p = act[0]

            def F(z):
                O_, pp, lam = z[:2], z[2], z[3]
                g = self._geom(pp, 1, O_)
                t = math.tan(self.rise.allowed if which == 1 else self.ret.allowed)
                sg = 1.0 if which == 1 else -1.0
                n = sg * self.k * g["r"] + t * g["u"]
                res = (O_ - B0) / sc - lam * n
                return [self._h(which, pp, 1, O_)[0] / sc, self._h(which, pp, 1, O_)[1] / sc, res[0], res[1]]
            n0 = grad(which, p)
            z0 = [O[0], O[1], p, float((O - B0) @ n0 / (n0 @ n0)) / sc]
        z = fsolve(F, z0, xtol=1e-15, full_output=False)
        ok = max(abs(v) for v in F(z)) < 1e-12
        return np.array(z[:2]) if ok else O

    def _rocker_result(self, O, gov) -> Synthesis:
        L = self.arm
        a_w = float(np.hypot(*O))
        psi0 = math.atan2(-O[1], O[0])
        r0 = float(np.hypot(*(np.array([L, 0.0]) - O)))
        p1 = self._hmax(1, O)[1]
        p2 = self._hmax(2, O)[1]
        return Synthesis(r0=r0, a_w=a_w, psi0=psi0, O=np.asarray(O, dtype=float), phi_rise=p1, phi_return=p2,
                         governing=gov)

    # ------------------------------------------------------------------ flat-faced rocker
    # Frame of the pivot A (origin), the arm line along x at the start, turned by ψ = s(φ) with
    # r = (cos ψ, sin ψ) along the face and u = Jr; cam centre O = a_w(cos ψ₀, −sin ψ₀) (ψ₀ — the
    # angle between AO and the face at the start).  The face is the line X·u = −d (d — its offset
    # from the pivot towards the cam).  Derivation (the definitions of Артоболевский И. И., «Теория
    # механизмов и машин», гл. 24, and Фролов К. В. (ред.), «Теория механизмов и машин», 1987: the
    # profile is the envelope of the follower's positions in the inverted motion, the pressure angle
    # is the angle between the common normal and the velocity of the follower's point of contact):
    #
    # * in the cam frame the face has the normal n = R(−kφ)u, turning at dθ/dφ = ψ′ − k = −kq,
    #   q = 1 − kψ′, at the distance p = a_w sin(ψ₀ + ψ) − d from O (the support function);
    # * the envelope point is K = p n + (dp/dθ) dn/dθ; its distance from the foot F of the
    #   perpendicular from A along the face is μ = a_w cos(ψ₀ + ψ)/q.  Second formulation (Kennedy):
    #   the common normal passes through the relative instant centre P₁₂ on AO with
    #   AP₁₂ = a_w/q (ω₁·OP₁₂ = ω₂·AP₁₂), and K is the foot of the perpendicular from P₁₂;
    # * radius of curvature ρ = p + d²p/dθ² = a_w G − d with
    #   G = sin(ψ₀ + ψ)(1 − ψ′²/q²) + cos(ψ₀ + ψ) ψ″/q³ (convex: ρ > 0);
    # * the point K of the rocker moves along J(K − A) = μu + d r, the force acts along u:
    #   tg ϑ = d/μ (ϑ ≡ 0 when the face passes through the pivot).
    def _fr(self, phi, side, psi0):
        s, s1, s2, s3 = self.law(phi, side)
        return s, s1, s2, s3, 1.0 - self.k * s1, np.cos(psi0 + s), np.sin(psi0 + s)

    def fr_G(self, phi, side, psi0):
        """ρ = a_w G − d of the flat-faced rocker's profile: G and dG/dφ (exact, with ψ‴)."""
        s, s1, s2, s3, q, c, sn = self._fr(phi, side, psi0)
        k = self.k
        A, B = 1.0 - s1 ** 2 / q ** 2, s2 / q ** 3
        dA = -2.0 * s1 * s2 / q ** 2 - 2.0 * k * s1 ** 2 * s2 / q ** 3
        dB = s3 / q ** 3 + 3.0 * k * s2 ** 2 / q ** 4
        return sn * A + c * B, c * s1 * A + sn * dA - sn * s1 * B + c * dB

    def fr_m(self, phi, side, psi0):
        """μ = a_w m, the contact point's distance along the face from F: m = cos(ψ₀ + ψ)/q, dm/dφ."""
        s, s1, s2, s3, q, c, sn = self._fr(phi, side, psi0)
        return c / q, (-sn * s1 * q + self.k * c * s2) / q ** 2

    def _fr_ext(self, fn, psi0, sign: float = -1.0, phases=None) -> tuple[float, float]:
        """The exact minimum (sign −1) or maximum of fn over the cycle (or over ``phases``) with
        the dwells, where fn is constant, and the cam angle of it."""
        best = (-math.inf, math.nan)      # the largest sign·fn
        for ph in phases or self.phases:
            if ph.length <= 0:
                continue
            if ph.law:
                v, p = self.phase_extreme(ph, lambda x, sd: fn(x, sd, psi0)[0], lambda x, sd: fn(x, sd, psi0)[1],
                                          sign=sign, vec=True)
            else:
                v, p = sign * float(fn(np.array([ph.start]), 1, psi0)[0][0]), ph.start
            if v > best[0]:
                best = (v, p)
        return sign * best[0], best[1]

    def fr_need(self, psi0: float) -> dict:
        """Centre distances a_w required at ψ₀: by convexity ρ ≥ ρ_min, a ≥ (ρ_min + d)/G_min, and by
        the allowed pressure angles (if the face is offset and [ϑ] given), a ≥ d/(tg[ϑ] m_min)."""
        d = self.face_offset
        G, pG = self._fr_ext(self.fr_G, psi0)
        out = {"psi0": psi0, "G": G, "phi_G": pG, "a_conv": (self.rho_min + d) / G if G > 0 else math.inf,
               "a_press": 0.0}
        for nm, ph in (("rise", self.rise), ("return", self.ret)):
            m, pm = self._fr_ext(self.fr_m, psi0, phases=[ph])
            out["m_" + nm], out["phi_" + nm] = m, pm
            if d > 0 and ph.allowed > 0:
                out["a_press"] = max(out["a_press"], d / (math.tan(ph.allowed) * m) if m > 0 else math.inf)
        out["a"] = max(out["a_conv"], out["a_press"])
        return out

    def _synth_flat_rocker(self) -> Synthesis:
        d, node = self.face_offset, self.node
        hi = math.pi / 2 - self.h
        kmax = max(self.phase_extreme(ph, lambda p, sd: self.k * self._at(p, sd)[1],
                                      lambda p, sd: self.k * self._at(p, sd)[2])[0] for ph in (self.rise, self.ret))
        if kmax >= 1.0:
            raise node.error("swing", "угловая скорость коромысла достигает скорости кулачка (|ψ′| ≥ 1): "
                                      "тарелка не поворачивается относительно кулачка, огибающая вырождается",
                             expected="больший угол фазы или меньший размах коромысла")
        if self.psi0_fixed is not None and not self.psi0_fixed < hi:
            raise node.error("psi0", "начальный угол коромысла слишком велик: точка касания уходит за ось качания",
                             expected=f"ψ0 + ψmax < 90°, т. е. ψ0 < {math.degrees(hi):.4g}°")
        grid = np.linspace(0.0, hi, 49)[1:-1]
        if self.psi0_fixed is not None:
            psi0 = self.psi0_fixed
            need = self.fr_need(psi0)
            if self.aw_fixed is not None:
                a, gov = self.aw_fixed, "fixed"
            else:
                if not math.isfinite(need["a"]):
                    raise node.error("psi0", "при заданном ψ0 профиль не может быть выпуклым ни при каком a_w",
                                     expected="больший начальный угол ψ0")
                a = need["a"]
                gov = "convexity" if need["a_conv"] >= need["a_press"] else "pressure"
        elif self.aw_fixed is not None:
            a = self.aw_fixed

            def F(x):
                G = self._fr_ext(self.fr_G, x)[0]
                return a * G - d - self.rho_min
            v = [F(x) for x in grid]
            i = next((j for j in range(len(v) - 1) if v[j] < 0 <= v[j + 1]), None)
            if i is None:
                raise node.error("a_w", "при заданном a_w профиль не может быть выпуклым ни при каком ψ0",
                                 expected="большее межосевое расстояние")
            psi0 = brentq(F, grid[i], grid[i + 1], xtol=1e-15, rtol=1e-15, maxiter=200)
            need, gov = self.fr_need(psi0), "convexity"
        else:
            if not (d > 0 and self.rise.allowed > 0 and self.ret.allowed > 0):
                raise node.error("psi0", "для коромысла с плоской тарелкой размеры по одному условию выпуклости "
                                         "не определяются: r0 убывает до вырождения (касание у оси качания)",
                                 expected="psi0 или a_w, либо face_offset > 0 вместе с допустимыми углами "
                                          "давления allowed на удалении и возвращении")
            psi0, need, gov = self._fr_optimum(grid)
            a = need["a"]
            if not math.isfinite(a):
                raise node.error("swing", "профиль не может быть выпуклым ни при каком начальном угле коромысла",
                                 expected="больший угол фазы, меньший размах, меньший ρmin или другое направление вращения кулачка")
        r0 = a * math.sin(psi0) - d
        if not r0 > 0:
            raise node.error("a_w", "радиус основной шайбы получается неположительным",
                             expected="a_w·sin ψ0 больше смещения тарелки")
        self.fr = need
        return Synthesis(r0=r0, a_w=a, psi0=psi0, O=self._rocker_O(a, psi0), governing=gov,
                         phi_rise=need["phi_rise"], phi_return=need["phi_return"])

    def _fr_optimum(self, grid) -> tuple[float, dict, str]:
        """ψ₀ of the least r₀ = a(ψ₀) sin ψ₀ − d, a = max(a_conv, a_press): bracketed on a grid of ψ₀,
        Brent's minimisation; at the crossing of the two conditions (the usual optimum: a_conv falls
        and a_press grows with ψ₀) polished as the root of a_conv − a_press."""
        d = self.face_offset

        def r0(x):
            return self.fr_need(x)["a"] * math.sin(x) - d
        v = np.array([r0(x) for x in grid])
        i = int(np.argmin(v))
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
        res = minimize_scalar(r0, bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
        x = float(res.x)
        n = self.fr_need(x)
        gov = "convexity" if n["a_conv"] >= n["a_press"] else "pressure"
        diff = lambda y: (lambda m: m["a_conv"] - m["a_press"])(self.fr_need(y))   # noqa: E731
        if abs(n["a_conv"] - n["a_press"]) <= 1e-6 * n["a"] and diff(lo) > 0 > diff(hi):
            x = brentq(diff, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=200)
            n, gov = self.fr_need(x), "both"
        return x, n, gov

    # ------------------------------------------------------------------ geometry over the cycle
    def frames(self, phi) -> dict[str, np.ndarray]:
        """Follower point P, P′, P″ in the fixed frame with the cam centre at the origin, the
        direction u of the follower's motion, r = −J u, and the law s, s′, s″."""
        phi = np.asarray(phi, dtype=float)
        s, s1, s2, s3 = self.law(phi)
        syn = self.synthesis
        n = phi.size
        extra = {}
        if self.follower == "translating":
            u = np.tile([0.0, 1.0], (n, 1))
            r = np.tile([1.0, 0.0], (n, 1))
            if self.contact == "flat":
                P = np.column_stack([self.k * s1, syn.r0 + s])
                P1 = np.column_stack([self.k * s2, s1])
                P2 = np.column_stack([self.k * s3, s2])
            else:
                P = np.column_stack([np.full(n, self.k * syn.e), syn.s0 + s])
                P1 = np.column_stack([np.zeros(n), s1])
                P2 = np.column_stack([np.zeros(n), s2])
            v1 = s1
        else:
            r = np.column_stack([np.cos(s), np.sin(s)])
            u = np.column_stack([-np.sin(s), np.cos(s)])
            if self.flat_rocker:
                # contact point K = A + μr − d u (A at the origin), μ = a_w cos(ψ₀ + ψ)/q and its
                # exact derivatives: μ′ = a_w N/q², μ″ = a_w (N′q + 2kNψ″)/q³
                k, d, a = self.k, self.face_offset, syn.a_w
                q, c, sn = 1.0 - k * s1, np.cos(syn.psi0 + s), np.sin(syn.psi0 + s)
                N = -sn * s1 * q + k * c * s2
                N1 = -c * s1 ** 2 * q - sn * s2 * q + k * c * s3
                mu = a * c / q
                mu1 = a * N / q ** 2
                mu2 = a * (N1 * q + 2.0 * k * N * s2) / q ** 3
                P = mu[:, None] * r - d * u - syn.O
                P1 = (mu1 + d * s1)[:, None] * r + (mu * s1)[:, None] * u
                P2 = (mu2 - mu * s1 ** 2 + d * s2)[:, None] * r + (2 * mu1 * s1 + mu * s2 + d * s1 ** 2)[:, None] * u
                v1 = mu * s1
                extra = {"mu": mu}
            else:
                L = self.arm
                P = L * r - syn.O
                P1 = L * s1[:, None] * u
                P2 = L * (s2[:, None] * u - (s1 ** 2)[:, None] * r)
                v1 = L * s1
        return dict(phi=phi, s=s, s1=s1, s2=s2, s3=s3, P=P, P1=P1, P2=P2, u=u, r=r, v1=v1, **extra)

    def pressure_angle(self, phi) -> np.ndarray:
        """ϑ(φ), rad: tg ϑ = (v′ − k w·r)/(w·u); flat-faced rocker tg ϑ = d/μ; zero for a flat
        translating follower."""
        f = self.frames(phi)
        if self.flat_rocker:
            return np.arctan2(np.full_like(f["mu"], self.face_offset), f["mu"])
        if self.contact == "flat":
            return np.zeros_like(f["phi"])
        wr = np.einsum("ij,ij->i", f["P"], f["r"])
        wu = np.einsum("ij,ij->i", f["P"], f["u"])
        return np.arctan2(f["v1"] - self.k * wr, wu)

    def profile(self, phi) -> dict[str, np.ndarray]:
        """Centre (theoretical) and working profiles in the cam frame by inversion, C = R(−kφ)P,
        C′ = R(−kφ)(P′ − kJP), C″ = R(−kφ)(P″ − 2kJP′ − P); ρ = −k|C′|³/(C′×C″) (> 0 convex);
        the working profile of a roller is C − r_р n with the outward unit normal n = kJ t."""
        f = self.frames(phi)
        k, phi = self.k, f["phi"]
        c, sn = np.cos(k * phi), np.sin(k * phi)

        def rot(V):  # R(−kφ) V
            return np.column_stack([c * V[:, 0] + sn * V[:, 1], -sn * V[:, 0] + c * V[:, 1]])

        def J(V):
            return np.column_stack([-V[:, 1], V[:, 0]])

        P, P1, P2 = f["P"], f["P1"], f["P2"]
        C, C1, C2 = rot(P), rot(P1 - k * J(P)), rot(P2 - 2 * k * J(P1) - P)
        sp = np.hypot(C1[:, 0], C1[:, 1])
        cross = C1[:, 0] * C2[:, 1] - C1[:, 1] * C2[:, 0]
        if self.flat_rocker:   # the support function: ρ = p + d²p/dθ² = a_w G − d
            rho = self.synthesis.a_w * self.fr_G(phi, 1, self.synthesis.psi0)[0] - self.face_offset
        elif self.contact == "flat":
            # C′ = kρ t with t = R(−kφ)(1, 0) along the face: the sign survives a cusp (ρ < 0)
            rho = k * (C1[:, 0] * c - C1[:, 1] * sn)
        else:
            rho = -k * sp ** 3 / cross
        t = C1 / sp[:, None]
        nrm = k * J(t)
        out = dict(phi=phi, s=f["s"], C=C, rho_c=rho, normal=nrm)
        rr = self.roller if self.contact == "roller" else 0.0
        out["W"] = C - rr * nrm
        out["rho"] = rho - rr
        return out

    @cached_property
    def roller(self) -> float:
        """Roller radius: given, or min(0.7 ρ_min of the convex centre profile, 0.4 r₀) rounded down
        to a whole millimetre (Попов, Тимофеев: r_р ≤ 0.7…0.8 ρ_min, r_р ≈ 0.25…0.4 r₀)."""
        if self.contact != "roller":
            return 0.0
        if self.roller_fixed is not None:
            return self.roller_fixed
        rr = min(0.7 * self.rho_min_centre, 0.4 * self.synthesis.r0)
        return math.floor(rr * 1000) / 1000 if rr >= 1e-3 else rr

    @cached_property
    def rho_min_centre(self) -> float:
        """Smallest radius of curvature of the convex parts of the centre profile: the least grid
        value (every 0.5° and the phase boundaries) refined by bounded Brent's method between the
        neighbouring grid angles."""
        g = self.grid
        rho = self._profile_nr(g)["rho_c"]
        conv = rho > 0
        if not conv.any():
            return math.inf
        i = int(np.argmin(np.where(conv, rho, np.inf)))
        a, b = g[max(i - 1, 0)], g[min(i + 1, len(g) - 1)]

        def f(p):
            v = float(self._profile_nr(np.array([p]))["rho_c"][0])
            return v if v > 0 else math.inf
        r = minimize_scalar(f, bounds=(a, b), method="bounded", options={"xatol": 1e-12})
        return float(min(rho[i], r.fun)) if r.success else float(rho[i])

    def _profile_nr(self, phi):
        save = self.__dict__.get("roller")
        self.__dict__["roller"] = 0.0
        try:
            return self.profile(phi)
        finally:
            if save is None:
                del self.__dict__["roller"]
            else:
                self.__dict__["roller"] = save

    @cached_property
    def grid(self) -> np.ndarray:
        """Cam angles of the cycle tables: the step GRID_STEP over 0…2π with every break of the laws
        added (the ends of the phases and the law's own breaks)."""
        pts = [np.arange(0.0, 2 * math.pi, self.GRID_STEP), [2 * math.pi]]
        for ph in self.phases:
            if ph.law:
                pts.append(self.breaks(ph))
        return np.unique(np.concatenate(pts))

    # ------------------------------------------------------------------ results
    def cycle_table(self, phi) -> pd.DataFrame:
        """The follower's law at the cam angles ``phi``: s and its analogs s′, s″, s‴; with ω given
        the true v = s′ω, a = s″ω², j = s‴ω³ (domain.md § 1.6); and the pressure angle ϑ."""
        s, s1, s2, s3 = self.law(phi)
        d = {"phi": phi, "phi_deg": np.degrees(phi), "s": s, "s1": s1, "s2": s2, "s3": s3}
        if self.omega is not None:
            w = self.omega
            d.update(v=w * s1, a=w * w * s2, j=w ** 3 * s3)
        d["theta"] = self.pressure_angle(phi)
        return pd.DataFrame(d)

    @cached_property
    def table_phi(self) -> np.ndarray:
        """Cam angles of the coordinate table: every ``step`` and the phase boundaries."""
        st = self.step
        pts = list(np.arange(0.0, 2 * math.pi - 1e-9, st)) + [p.start for p in self.phases if p.length > 0]
        return np.unique(np.round(np.array(pts), 12))

    def profile_table(self, phi=None) -> pd.DataFrame:
        """The profile at the cam angles ``phi`` (the table's angles by default), by inversion: the
        centre profile C (a roller's centre) with its radius of curvature, the working profile W
        (the equidistant at r_p, or the flat face's envelope), their polar radii and the pressure
        angle (domain.md § 1.6)."""
        phi = self.table_phi if phi is None else phi
        p = self.profile(phi)
        d = {"phi": phi, "phi_deg": np.degrees(phi), "s": p["s"]}
        if self.contact != "flat":
            d.update(x_c=p["C"][:, 0], y_c=p["C"][:, 1], r_c=np.hypot(*p["C"].T), rho_c=p["rho_c"])
        d.update(x=p["W"][:, 0], y=p["W"][:, 1], r=np.hypot(*p["W"].T), rho=p["rho"],
                 theta=self.pressure_angle(phi))
        return _finite(pd.DataFrame(d))

    def tables(self) -> dict[str, pd.DataFrame]:
        """Export tables: ``cam`` (the law over the cycle grid) and ``cam_profile`` (the profile's
        coordinates)."""
        return {"cam": _finite(self.cycle_table(self.grid)), "cam_profile": self.profile_table()}

    @cached_property
    def required_size(self) -> dict | None:
        """The least size that keeps the pressure angle within the allowed values when the case gives
        the sizes (synthesis replaced by a check) and they fail it: a translating follower with its
        given e — s₀ = max(M₁ − e/tg[ϑ_у], M₂ + e/tg[ϑ_в]) by the exact tangent points, r₀ = √(s₀² + e²);
        a rocker — the centre nearest to B₀ in the region the rays allow (the synthesis the given
        a_w, ψ₀ replaced: r₀ least, Артоболевский §25); along the ray of a given ψ₀ alone the admissible
        a_w may not exist (a longer a_w mends the rise and breaks the return).  None when the sizes are chosen or the check passes."""
        syn = self.synthesis
        if syn.governing != "fixed" or self.contact == "flat" or self.flat_rocker:
            return None
        t1, t2 = self.theta_max
        if t1 <= self.rise.allowed + 1e-9 and t2 <= self.ret.allowed + 1e-9:
            return None
        if self.follower == "translating":
            ta, tb = math.tan(self.rise.allowed), math.tan(self.ret.allowed)
            e = syn.e
            f1 = lambda p, sd: self._at(p, sd)[1] / ta - self._at(p, sd)[0]          # noqa: E731
            d1 = lambda p, sd: self._at(p, sd)[2] / ta - self._at(p, sd)[1]          # noqa: E731
            f2 = lambda p, sd: -self._at(p, sd)[1] / tb - self._at(p, sd)[0]         # noqa: E731
            d2 = lambda p, sd: -self._at(p, sd)[2] / tb - self._at(p, sd)[1]         # noqa: E731
            s0 = max(self.phase_extreme(self.rise, f1, d1)[0] - e / ta, self.phase_extreme(self.ret, f2, d2)[0] + e / tb)
            return {"r0": math.hypot(s0, e), "e": e}
        L = self.arm
        O = self.synth_generic(np.array([L, 0.0]), L)
        return {"a_w": float(np.hypot(*O)), "psi0": math.atan2(-O[1], O[0]),
                "r0": float(np.hypot(*(np.array([L, 0.0]) - O)))}

    @cached_property
    def theta_max(self) -> tuple[float, float]:
        """Largest pressure angle on the rise (signed, ϑ) and on the return (−ϑ), exact maxima."""
        if self.flat_rocker:   # |ϑ| = arctg(d/μ) is largest where μ is least on the phase
            a = self.synthesis.a_w
            return (math.atan2(self.face_offset, a * self.fr["m_rise"]),
                    math.atan2(self.face_offset, a * self.fr["m_return"]))
        if self.contact == "flat":
            return 0.0, 0.0
        O = self._O_synth
        out = []
        for which, ph in ((1, self.rise), (2, self.ret)):
            sg = 1.0 if which == 1 else -1.0

            def f(p, sd, which=which):
                g = self._geom(p, sd, O)
                return math.atan2(sg * (g["v1"] - self.k * g["w"] @ g["r"]), g["w"] @ g["u"])

            # the extremes of ϑ are where d/dφ of tgϑ vanishes: grid-bracketed, Brent-refined
            def df(p, sd, f=f):
                hh = 1e-6
                return (f(p + hh, sd) - f(p - hh, sd)) / (2 * hh)
            v, _ = self.phase_extreme(ph, f, df)
            out.append(v)
        return out[0], out[1]

    @cached_property
    def face(self) -> tuple[float, float]:
        """Flat-faced rocker: the least and the largest distance μ of the contact point along the
        face from the foot F of the perpendicular from the pivot (exact extremes over the cycle)."""
        syn = self.synthesis
        lo = self._fr_ext(self.fr_m, syn.psi0, sign=-1.0)[0]
        hi = self._fr_ext(self.fr_m, syn.psi0, sign=1.0)[0]
        return syn.a_w * lo, syn.a_w * hi

    @cached_property
    def _O_synth(self) -> np.ndarray:
        syn = self.synthesis
        if self.follower == "translating":
            return np.array([-self.k * syn.e, -syn.s0])
        return syn.O

    @cached_property
    def scalars(self) -> dict[str, Any]:
        """Named results ``cam_*``: r₀, the stroke, e and s₀ (and the approximate synthesis beside
        them) or a_w and ψ₀, the face of a flat follower, the greatest pressure angles on the rise
        and on the return, the least radius of curvature, the roller, and the counts of hard and
        soft impacts (domain.md § 1.6)."""
        syn = self.synthesis
        out = {"cam_r0": syn.r0, "cam_stroke": self.h}
        if self.contact != "flat" and syn.exact is not None:
            out["cam_r0_least"] = syn.exact.r0       # before it was taken up to a whole millimetre
        if self.follower == "translating" and self.contact != "flat":
            out.update(cam_e=syn.e, cam_s0=syn.s0, cam_r0_approx=syn.r0_approx, cam_e_approx=syn.e_approx)
        if self.flat_rocker:
            fr, face = self.fr, self.face
            out.update(cam_a_w=syn.a_w, cam_psi0=syn.psi0, cam_face_offset=self.face_offset,
                       cam_a_w_min=fr["a"], cam_r0_min=fr["a"] * math.sin(syn.psi0) - self.face_offset,
                       cam_face_min=face[0], cam_face_max=face[1], cam_face_width=face[1] - face[0],
                       cam_rho_min=syn.a_w * fr["G"] - self.face_offset)
        elif self.follower == "rocker":
            out.update(cam_a_w=syn.a_w, cam_psi0=syn.psi0, cam_arm=self.arm)
            if syn.governing != "fixed":
                out.update(cam_r0_approx=syn.r0_approx, cam_a_w_approx=syn.a_w_approx)
        th1, th2 = self.theta_max
        out.update(cam_theta_rise_max=th1, cam_theta_return_max=th2)
        prof = self.profile(self.grid)
        if self.flat_rocker:
            pass
        elif self.contact == "flat":
            out.update(cam_face_width=self.face_width, cam_rho_min=float(prof["rho"].min()),
                       cam_r0_min=self.flat_min[2])
        else:
            out.update(cam_rho_c_min=self.rho_min_centre)
        if self.contact == "roller":
            out["cam_roller"] = self.roller
            out["cam_rho_min"] = self.rho_min_centre - self.roller
        out["cam_impacts_hard"] = sum(1 for i in self.impacts if i["kind"] == "hard")
        out["cam_impacts_soft"] = sum(1 for i in self.impacts if i["kind"] == "soft")
        return {k: float(v) if not isinstance(v, int) else v for k, v in out.items()}


def _finite(df: pd.DataFrame) -> pd.DataFrame:
    """Never inf/NaN in a table: an infinite radius of curvature (an inflection point of the
    profile exactly on a table angle, C′ × C″ = 0) is written as 0 (documented in outputs.md)."""
    return df.replace([np.inf, -np.inf], np.nan).fillna(0.0)
