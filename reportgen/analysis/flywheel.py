"""Steady motion of a machine reduced to its crank and the flywheel that keeps it within δ.

Model (Артоболевский «Теория механизмов и машин», гл. «Динамика машин»; Попов–Тимофеев,
курсовое проектирование по ТММ; worksheet 000 of the project)
------------------------------------------------------------------------------------------
The generalised coordinate φ runs over one cycle [φ_a, φ_a + Φ] (Φ = 2π, or 4π for a
four-stroke engine).  Reduced inertia J_пр(φ) = J_I + J_II(φ): J_I is the constant part (rotors,
crank, flywheel), J_II(φ) the variable part of the linkage.  Reduced moments:
M_Σ(φ) = M_дв(φ) + M_пр.с(φ) (all loads except the driving moment are in M_пр.с).

* Equation of motion in energy form:  ½ J_пр(φ) ω(φ)² = T₀ + A_Σ(φ),  A_Σ(φ) = ∫_{φ_a}^{φ} M_Σ;
  in differential form J_пр ε + ½ J_пр′ ω² = M_Σ (Лагранж; Артоболевский).  For M = M(φ)
  the energy form is exact, so the periodic steady motion is known in closed form once J_I
  and T₀ are fixed.
* Constant driving moment from zero cycle work: M_дв = −A_c/Φ.
* Coefficient of non-uniformity δ = (ω_max − ω_min)/ω_ср with ω_ср = (ω_max + ω_min)/2, i.e.
  ω_max = ω_ср(1 + δ/2), ω_min = ω_ср(1 − δ/2).

Three ways to size J_I are computed side by side (numerics.md §4):

* exact periodic solution of the energy integral (root finding on T₀ and J_I);
* Мерцалов's method as in worksheet 000 (T_II ≈ ½ J_II ω_ср², ΔT_I = A_Σ − T_II,
  J_I = (ΔT_I,max − ΔT_I,min)/(ω_ср² δ)); it over-sizes J_I by about the mean of J_II at the
  two extremes of ΔT_I (first order), exactly by J_II when J_II is constant;
* Виттенбауэр's energy–mass diagram ΔT(J_II): tangents of slopes ω_max²/2 and ω_min²/2 cut
  K and L on the ΔT axis; from the tangency conditions T₀ + K = ½ω_max² J_I and
  T₀ + L = ½ω_min² J_I follows J_I = 2·KL/(ω_max² − ω_min²), which for the exact slopes
  (1 ± δ/2)² is identically KL/(ω_ср² δ) and exact; the textbook slopes ω_ср²(1 ± δ)/2 give
  the same formula with slightly different K and L (error ∝ δ²).

The works of loads constant between switching points are taken in closed form (F·Δr_P,
M·Δφ_k; ``works`` of :class:`DynamicModel`), the others by Gauss–Lobatto/Gauss–Legendre on
intervals split at the switching points (``reportgen.core.quadrature``); the extremes of every
curve are refined by ``brentq`` on the analytic derivative, never read off the grid — on the
Chebyshev interpolants of the model quantities in the node interval where these are resolved to
rounding (:meth:`DynamicModel._build_cells`), else by exact evaluation.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Iterable, NamedTuple, Protocol, Sequence

import numpy as np
from .roots import brentq

from reportgen.core import extremum as XK
from reportgen.core.quadrature import (CHEB_POINTS, Antiderivative, CellPoly, cheb_coefficients, cheb_points,
                                      cheb_to_monomial, gauss_legendre, merge_nodes)

__all__ = [
    "ClosedWork",
    "DynamicModel",
    "prepare_model",
    "Works",
    "works",
    "MertsalovResult",
    "mertsalov",
    "TangentPoint",
    "WittenbauerResult",
    "wittenbauer",
    "ExactMotion",
    "exact",
    "RimFlywheel",
    "DiskFlywheel",
    "FlywheelDims",
    "flywheel_dims",
    "DynamicsResult",
    "solve_dynamics",
]

ArrayFunc = Callable[[np.ndarray], np.ndarray]


class ClosedWork(Protocol):
    """The works of the loads that have a closed form, tabulated on the nodes of a
    :class:`DynamicModel` (built by ``works(nodes, breaks)``).

    values  – ∫_{nodes[0]}^{nodes[k]} of their reduced moment, at every node;
    partial – ``partial(i, x)``: ∫_{nodes[i]}^{x} of it for x inside the node interval i;
    rest    – the reduced moment of the other loads (integrated by quadrature), or None.
    """

    values: np.ndarray
    rest: ArrayFunc | None

    def partial(self, i: np.ndarray, x: np.ndarray) -> np.ndarray:
        """∫ from nodes[i] to x of the closed-form moment, for each x inside its node interval i."""
_EPS = np.finfo(float).eps
# works on node intervals away from breaks by the Gauss–Lobatto rule of this order (its end
# points are the nodes, where the kinematics is the solved cycle grid); 0 — Gauss–Legendre on
# every interval
LOBATTO = 5
# the extremum search on a node interval uses Chebyshev interpolants (core.quadrature.cell_fit)
# when their last coefficients are below CELL_TOL of the size of the quantity (DynamicModel._build_cells)
CELL_TOL = 1e-14
CELL_REACH = 2        # cells built beside each candidate cell
CELL_PREFETCH = 30    # cells built on each side of the extremes of A_Σ by the first search


# --------------------------------------------------------------------------------------------
# Model: loads, works and inertia tabulated once per cycle
# --------------------------------------------------------------------------------------------
class DynamicModel:
    """One cycle of the reduced machine, tabulated once and evaluable at any φ.

    Nodes = user grid (wrapped into the cycle) ∪ breaks ∪ cycle ends, subdivided so that no
    interval exceeds Φ/``min_nodes``.  On the nodes: A_c, A_дв, A_Σ (cumulative; Gauss–Lobatto
    of order ``lobatto`` (default :data:`LOBATTO`) on intervals between two grid nodes,
    Gauss–Legendre of order ``order`` on intervals touching a break or a cycle end) and J_II.  Everything periodic is evaluated at an
    arbitrary φ by reduction into the cycle: A(φ + kΦ) = A(φ) + k·A(cycle).

    Parameters are those of :func:`solve_dynamics`; J2/dJ2 may be None when only the works
    are wanted.  ``works`` (optional): ``works(nodes, breaks)`` → a :class:`ClosedWork`, the
    works of the loads that have a closed form (a force constant between switching points does
    the work F·Δr_P, a moment M·Δφ_k: no quadrature points at all); only its ``rest`` (the loads
    given by tables) is integrated by quadrature.
    """

    def __init__(self, J2: ArrayFunc | None, dJ2: ArrayFunc | None, M: ArrayFunc,
                 breaks: Iterable[float] | None, cycle_start: float, cycle_length: float,
                 grid, Mdrive: float | ArrayFunc | None = None, *, min_nodes: int = 720,
                 order: int = 8, balance_rtol: float = 1e-9, lobatto: int | None = None,
                 works: "Callable[[np.ndarray, np.ndarray], ClosedWork] | None" = None):
        a = float(cycle_start)
        L = float(cycle_length)
        if not (L > 0 and math.isfinite(L)):
            raise ValueError(f"cycle_length must be positive, got {cycle_length}")
        self.a, self.L = a, L
        self._J2, self._dJ2, self._M = J2, dJ2, M
        # breaks reduced into [a, a + L)
        br = np.asarray(list(breaks) if breaks is not None else [], dtype=float).ravel()
        br = a + np.mod(br - a, L)
        br = np.unique(br[(br > a) & (br < a + L)])
        self.breaks = br
        # user grid
        if np.isscalar(grid):
            n = int(grid)
            if n < 2:
                raise ValueError("grid as an int is the number of intervals (≥ 2)")
            phi = np.linspace(a, a + L, n + 1)
        else:
            phi = np.asarray(grid, dtype=float).ravel()
            if phi.size < 1:
                raise ValueError("empty grid")
        self.phi = phi
        red = self._reduce(phi)[0]
        base = np.unique(np.concatenate(([a, a + L], red, br)))
        self.nodes = merge_nodes(base, br, max_step=L / max(int(min_nodes), 2))
        # works on nodes
        lob = LOBATTO if lobatto is None else lobatto
        self._closed = works(self.nodes, br) if works is not None else None
        # the integrand left to quadrature: M, or the part of M without a closed-form work
        self._Q = M if self._closed is None else self._closed.rest
        Ac_vals = np.zeros(self.nodes.size)
        if self._Q is not None:
            Ac_vals = Antiderivative(self._Q, self.nodes, br, order=order, lobatto=lob).values
        if self._closed is not None:
            Ac_vals = Ac_vals + self._closed.values
        self.Ac_total = float(Ac_vals[-1])
        if Mdrive is None or np.isscalar(Mdrive):
            self.Md_const = (-self.Ac_total / L) if Mdrive is None else float(Mdrive)
            self._Ad = None
            self.Ad_total = self.Md_const * L
            Ad_n = self.Md_const * (self.nodes - a)
        else:
            self.Md_const = None
            self._Ad = Antiderivative(Mdrive, self.nodes, br, order=order, lobatto=lob)
            self.Ad_total = self._Ad.total
            Ad_n = self._Ad.values
        self._Mdrive = Mdrive
        self.Ac_n = Ac_vals
        self.Ad_n = Ad_n
        self.A_n = self.Ac_n + self.Ad_n
        scale = float(np.max(np.abs(self.Ac_n)) + np.max(np.abs(self.Ad_n)))
        self.A_total = self.Ac_total + self.Ad_total
        if abs(self.A_total) > balance_rtol * max(scale, 1e-300):
            raise ValueError(
                "the driving moment does not balance the cycle work "
                f"(A_Σ over the cycle = {self.A_total:.6g} J against a scale of {scale:.6g} J): "
                "no periodic steady motion exists; pass Mdrive=None for M_дв = −A_c/Φ")
        self.M_drive_mean = self.Ad_total / L
        # values on the user grid
        idx, k = self._node_index(phi)
        self.Ac_g = self.Ac_n[idx] + k * self.Ac_total
        self.Ad_g = self.Ad_n[idx] + k * self.Ad_total
        self.A_g = self.Ac_g + self.Ad_g
        self.Mc_g = self._call(M, phi)
        self.Md_g = self._md(phi)
        self.M_g = self.Mc_g + self.Md_g
        if J2 is not None:
            if dJ2 is None:
                raise ValueError("dJ2 (the exact derivative of J_II) is required with J2")
            self.J2_n = self._call(J2, self.nodes)
            self.J2_g = self._call(J2, phi)
            self.dJ2_g = self._call(dJ2, phi)
            if np.any(~np.isfinite(self.J2_n)):
                raise ValueError("J_II(φ) is not finite on the cycle")
        self._cache: dict = {}
        # the interpolants of the node intervals (:meth:`_build_cells`) as arrays: Horner
        # coefficients of A_Σ, M_Σ, J_II, J_II′ (highest power first, zero-padded), midpoint and
        # inverse half width; state 0 — not built, 1 — resolved, −1 — evaluated exactly
        ncell = self.nodes.size - 1
        self._tab = np.zeros((ncell, 4, CHEB_POINTS + 1))
        self._mids = np.zeros(ncell)
        self._ihs = np.zeros(ncell)
        self._state = np.zeros(ncell, np.int8)
        self._polys: dict[int, CellPoly] = {}
        self._searched = False
        self._memo_tab: dict = {}
        self._order = int(order)
        self._t, self._w = gauss_legendre(self._order)
        self._Ac_vals = Ac_vals
        self._Ad_vals = None if self._Ad is None else self._Ad.values
        self._has_J = J2 is not None

    # -- helpers ---------------------------------------------------------------------------
    @staticmethod
    def _call(f: ArrayFunc, x: np.ndarray) -> np.ndarray:
        y = np.asarray(f(x), dtype=float)
        return np.broadcast_to(y, np.shape(x)).copy() if y.shape != np.shape(x) else y

    def _md(self, x: np.ndarray) -> np.ndarray:
        if self.Md_const is not None:
            return np.full(np.shape(x), self.Md_const)
        return self._call(self._Mdrive, x)

    def _reduce(self, x) -> tuple[np.ndarray, np.ndarray]:
        """x = r + k·Φ with r in [a, a + Φ)."""
        x = np.asarray(x, dtype=float)
        k = np.floor((x - self.a) / self.L)
        r = x - k * self.L
        hi = r >= self.a + self.L
        lo = r < self.a
        if np.any(hi) or np.any(lo):  # rounding at the ends
            r = np.where(hi, r - self.L, np.where(lo, r + self.L, r))
            k = np.where(hi, k + 1, np.where(lo, k - 1, k))
        return r, k

    def _reduce1(self, t: float) -> tuple[float, int]:
        a, L = self.a, self.L
        k = math.floor((t - a) / L)
        r = t - k * L
        if r >= a + L:
            r -= L
            k += 1
        elif r < a:
            r += L
            k -= 1
        return r, k

    def _node_index(self, x):
        r, k = self._reduce(x)
        idx = np.searchsorted(self.nodes, r)
        idx = np.clip(idx, 0, self.nodes.size - 1)
        if not np.array_equal(self.nodes[idx], r):
            raise RuntimeError("internal: grid point is not a node")
        return idx, k

    # -- evaluation at arbitrary φ --------------------------------------------------------------
    def _ev(self, x):
        """(A_Σ, M_Σ, J_II, J_II′) at arbitrary φ (array).

        A_Σ(φ) = A_Σ(x_i) + ∫_{x_i}^{φ} M_Σ (the closed-form part of the works exactly, the rest
        by Gauss–Legendre from the node x_i below φ; no break inside because the breaks are
        nodes) + k·A_Σ(cycle) for φ reduced by kΦ.  One call of each user function for all
        points.
        """
        x = np.asarray(x, dtype=float)
        shape = x.shape
        r, k = self._reduce(x.ravel())
        i, A, pts, mv, split = self._Ac_from_nodes(r)
        A = A + k * self.Ac_total
        Ms = mv[split:]
        if self._Ad_vals is None:
            A = A + self.Md_const * (r - self.a) + k * self.Ad_total
            Ms = Ms + self.Md_const
        else:
            # the given driving moment (a function of φ alone) by Gauss–Legendre from the node
            n, q = r.size, self._order
            base = self.nodes[i]
            half = 0.5 * (r - base)
            inner = np.flatnonzero(half != 0.0)
            dpts = np.empty(inner.size * q + n)
            dpts[: inner.size * q] = (0.5 * (r + base)[inner, None] + half[inner, None] * self._t).ravel()
            dpts[inner.size * q:] = r
            dv = self._call(self._Mdrive, dpts)
            A = A + self._Ad_vals[i] + k * self.Ad_total
            if inner.size:
                A[inner] += half[inner] * (dv[: inner.size * q].reshape(inner.size, q) @ self._w)
            Ms = Ms + dv[inner.size * q:]
        if self._has_J:
            # on the same array as M (one kinematic evaluation: the columns are cached by the
            # points asked, and J_II is element-wise)
            J = self._call(self._J2, pts)[split:]
            dJ = self._call(self._dJ2, pts)[split:]
        else:
            J = dJ = np.full(r.size, np.nan)
        return A.reshape(shape), Ms.reshape(shape), J.reshape(shape), dJ.reshape(shape)

    def _Ac_from_nodes(self, r: np.ndarray):
        """A_c at points r of the cycle: the node value below each point plus the integral from
        the node (closed form and Gauss–Legendre of the rest).  Returns (node index, A_c,
        the points M was evaluated at, M there, the offset of r in them)."""
        nn = self.nodes.size
        i = np.clip(np.searchsorted(self.nodes, r, side="right") - 1, 0, nn - 2)
        base = self.nodes[i]
        A = self._Ac_vals[i].copy()
        n, q = r.size, self._order
        if self._Q is None:
            pts, split = r, 0
        else:
            # a point on a node needs no quadrature (its integral from the node is 0): the
            # Gauss–Legendre points are placed only for the others (on the cycle grid, none)
            half = 0.5 * (r - base)
            inner = np.flatnonzero(half != 0.0)
            m = inner.size
            hin = half[inner]
            pts = np.empty(m * q + n)
            pts[: m * q] = (0.5 * (r + base)[inner, None] + hin[:, None] * self._t).ravel()
            pts[m * q:] = r
            split = m * q
        mv = self._call(self._M, pts)
        if self._Q is not None:
            qv = mv if self._Q is self._M else self._call(self._Q, pts)
            if m:
                A[inner] += hin * (qv[:split].reshape(m, q) @ self._w)
        if self._closed is not None:
            A += self._closed.partial(i, r)
        return i, A, pts, mv, split

    def _ev1(self, t: float):
        """Scalar form of :meth:`_ev` (used inside brentq); returns Python floats."""
        return tuple(float(v[0]) for v in self._ev(np.array([float(t)])))

    def _memo(self, name: str, x, fn) -> np.ndarray:
        """fn(x) remembered by the values of x: the tables ask for A_Σ, J_II, … on the same grid
        for ω and ε of every method (a copy is returned)."""
        x = np.asarray(x, dtype=float)
        key = (name, x.shape, x.tobytes())
        hit = self._memo_tab.get(key)
        if hit is None:
            hit = fn(x)
            self._memo_tab[key] = hit
            if len(self._memo_tab) > 32:
                self._memo_tab.pop(next(iter(self._memo_tab)))
        return hit.copy()

    def A(self, x) -> np.ndarray:
        """A_Σ(φ) = ∫_{φ_a}^{φ} M_Σ at arbitrary φ (periodic continuation)."""
        return self._memo("A", x, lambda x: self._ev(x)[0])

    def Ac(self, x) -> np.ndarray:
        """A_c(φ) = ∫_{φ_a}^{φ} M_пр.с at arbitrary φ."""
        def f(x):
            r, k = self._reduce(x.ravel())
            return (self._Ac_from_nodes(r)[1] + k * self.Ac_total).reshape(x.shape)
        return self._memo("Ac", x, f)

    def M_sum(self, x) -> np.ndarray:
        """M_Σ(φ) = M_пр.с(φ) + M_дв(φ)."""
        def f(x):
            r, _ = self._reduce(x)
            return self._call(self._M, r) + self._md(r)
        return self._memo("M_sum", x, f)

    def J2(self, x) -> np.ndarray:
        """J_II(φ) at any φ (reduced into the cycle), memoised by the array of angles (domain.md §
        1.5)."""
        return self._memo("J2", x, lambda x: self._call(self._J2, self._reduce(x)[0]))

    def dJ2(self, x) -> np.ndarray:
        """dJ_II/dφ at any φ (reduced into the cycle), memoised by the array of angles."""
        return self._memo("dJ2", x, lambda x: self._call(self._dJ2, self._reduce(x)[0]))

    def wrap(self, x) -> np.ndarray:
        """φ reduced into [φ_a, φ_a + Φ)."""
        return self._reduce(x)[0]

    # -- extremum of a periodic piecewise-smooth function ----------------------------------
    def extremum(self, gn: np.ndarray, combine: Callable, kind: str, max_candidates: int = 8,
                 compiled: tuple[int, float, float] | None = None):
        """Global max/min over the cycle of g(φ) tabulated as ``gn`` on nodes[:-1].

        ``combine(A_Σ, M_Σ, J_II, J_II′) → (g, s·dg/dφ)`` (s > 0 any positive factor) defines
        g and the sign of its derivative from the model quantities at a point; ``compiled`` —
        the same function as (kind, p₀, p₁) of :mod:`reportgen.core.extremum`: when every interval
        the search needs has its interpolant, the whole search runs there (the same operations;
        the Python search below builds the cells and decides for a NaN, a failed convergence or
        an interval evaluated exactly).
        Grid scan (discrete local extrema, cyclic) → in the two cells around each candidate,
        ``brentq`` on the sign change of dg (evaluated one-sidedly inside the cell, so a jump
        of dg at a break is never straddled) → the best of the candidate node and the
        interior roots by exact evaluation of g.  Extrema at breaks (kinks of g) and at the
        cycle ends are therefore found too.
        Returns (φ in the cycle, g(φ), (A_Σ, M_Σ, J_II, J_II′) at φ).
        """
        s = 1.0 if kind == "max" else -1.0
        if compiled is not None and self._searched:
            found = self._search_compiled(gn, s, compiled, combine, max_candidates)
            if found is not None:
                return found
        v = s * np.asarray(gn, dtype=float)
        n = v.size
        vl = np.empty_like(v)
        vl[1:] = v[:-1]
        vl[0] = v[-1]
        vr = np.empty_like(v)
        vr[:-1] = v[1:]
        vr[-1] = v[0]
        loc = np.flatnonzero((v >= vl) & (v >= vr))
        if loc.size == 0:
            loc = np.array([int(np.argmax(v))])
        best = v[loc].max()
        # a cell can overshoot its nodes by ~|Δ²g|/8: keep every candidate that close to best
        margin = 2.0 * float(np.max(np.abs(vr - 2 * v + vl))) + 64 * _EPS * float(np.max(np.abs(v)))
        loc = loc[v[loc] >= best - margin]
        if loc.size > max_candidates:
            loc = loc[np.argsort(-v[loc])[:max_candidates]]
        x = self.nodes
        xm = np.where(loc == 0, x[n - 1] - self.L, x[np.maximum(loc - 1, 0)])
        x0 = x[loc]
        xp = x[loc + 1]
        scale = max(1.0, abs(self.a) + self.L)
        eta_abs = 64 * _EPS * scale
        lo = np.concatenate((xm, x0))
        hi = np.concatenate((x0, xp))
        eta = np.minimum(eta_abs, 0.25 * (hi - lo))
        ends = np.concatenate((lo + eta, hi - eta))
        m = lo.size
        # the cells around the candidates: (A_Σ, M_Σ, J_II, J_II′) by their Chebyshev
        # interpolants where these are resolved to rounding (:meth:`_cell`), else exactly
        cells = np.concatenate((np.where(loc == 0, n - 1, loc - 1), loc))
        shift = np.concatenate((np.where(loc == 0, self.L, 0.0), np.zeros(loc.size)))
        # with their neighbours: the searches that follow (the other method, the next iteration of
        # the exact solution) look near the same extremes
        want = np.mod(cells[:, None] + np.arange(-CELL_REACH, CELL_REACH + 1), n).ravel()
        if not self._searched:
            self._searched = True
            # the first search: the extremes of ΔT_I, of Виттенбауэр's K and L and of ω lie near
            # those of A_Σ (J_II varies less): their cells in the same evaluation
            ext = np.array([np.argmax(self.A_n[:-1]), np.argmin(self.A_n[:-1])])
            want = np.concatenate((want, np.mod(ext[:, None] + np.arange(-CELL_PREFETCH, CELL_PREFETCH + 1),
                                                n).ravel()))
        self._build_cells(want)
        direct = np.flatnonzero(self._state[cells] < 0).tolist()
        if compiled is not None and not direct:
            # the cells are built now: the compiled search decides as it will in the next calls
            found = self._search_compiled(gn, s, compiled, combine, max_candidates)
            if found is not None:
                return found
        fit = [self._cell(int(c)) for c in cells]
        draw = np.empty(2 * m)
        for j in range(m):
            if fit[j] is not None:
                draw[j] = combine(*fit[j](ends[j] + shift[j]))[1]
                draw[m + j] = combine(*fit[j](ends[m + j] + shift[j]))[1]
        if direct:
            sel = np.array(direct + [m + j for j in direct])
            draw[sel] = combine(*self._ev(ends[sel]))[1]
        dv = s * draw
        dlo, dhi = dv[:m], dv[m:]
        roots = []
        seen: dict[float, tuple] = {}    # (A_Σ, M_Σ, J_II, J_II′) at the points brentq evaluated
        for j in range(m):
            if hi[j] - lo[j] <= 4 * eta_abs:
                continue
            if dlo[j] > 0 and dhi[j] < 0:
                a_, b_ = ends[j], ends[m + j]
                fa, fb = float(draw[j]), float(draw[m + j])
                at = (lambda t, f=fit[j], sh=shift[j]: f(t + sh)) if fit[j] is not None else self._ev1

                def fd(t, a_=a_, b_=b_, fa=fa, fb=fb, at=at):
                    # brentq starts with f at both ends: known from the evaluation above
                    if t == a_:
                        return fa
                    if t == b_:
                        return fb
                    tt = min(max(t, a_), b_)
                    val = at(tt)
                    seen[tt] = val
                    return combine(*val)[1]

                # location to ~1e-13 rad: the value at a smooth extremum is then exact to
                # O(1e-26) relative; extremes at kinks are the nodes themselves
                roots.append(brentq(fd, a_, b_, xtol=1e-13 * scale, rtol=4 * _EPS,
                                    maxiter=200))
        return self._best(x0, roots, seen, v, loc, s, combine)

    def _search_compiled(self, gn, s, compiled, combine, max_candidates):
        """:func:`reportgen.core.extremum.search` — the whole search compiled, the same operations
        (scan, candidates, Brent as SciPy's ``brentq``, the best of them) — when every interval it
        needs has its interpolant; None where the Python search must decide.  One compiled entry
        point: a new process loads one cached kernel."""
        kind, p0, p1 = compiled
        st, r, g, q = XK.search(np.ascontiguousarray(gn, dtype=float), s, self.nodes, self.a, self.L, int(kind),
                                float(p0), float(p1), self._state, self._tab, self._mids, self._ihs,
                                max_candidates, CELL_REACH, 1e-13, 200)
        if st == XK.X_DONE:
            return self._reduce1(r)[0], float(g), tuple(q.tolist())
        if st == XK.X_EVALUATE:
            q = self._ev(np.array([r]))
            g, _ = combine(*q)
            return self._reduce1(r)[0], float(g[0]), tuple(float(z[0]) for z in q)
        return None

    def _best(self, x0, roots, seen, v, loc, s, combine):
        """The best of the candidate nodes and the roots (see :meth:`extremum`)."""
        # g at the candidate nodes is the table; at a root brentq returned, the model quantities
        # of its last evaluation (brentq returns a point it evaluated); only the winner's
        # quantities are evaluated anew when they are not known
        cand = np.concatenate((x0, np.asarray(roots, dtype=float)))
        gv = np.concatenate((v[loc], [s * combine(*seen[r])[0] if r in seen else math.inf
                                          for r in roots]))
        unknown = [x0.size + i for i, r in enumerate(roots) if r not in seen]
        if unknown:                 # a root brentq did not evaluate (f = 0 at an end)
            gv[unknown] = s * combine(*self._ev(cand[unknown]))[0]
        j = int(np.argmax(gv))
        r = float(cand[j])
        if j >= x0.size and r in seen:
            q = seen[r]
            g = combine(*q)[0]
            return self._reduce1(r)[0], float(g), tuple(float(z) for z in q)
        q = self._ev(cand[j:j + 1])
        g, _ = combine(*q)
        return self._reduce1(r)[0], float(g[0]), tuple(float(z[0]) for z in q)

    def _cell_scale(self) -> np.ndarray:
        """The largest |A_Σ|, |M_Σ|, J_II, |J_II′| on the grid (the scale of rounding)."""
        if "cell_scale" not in self._cache:
            with np.errstate(invalid="ignore"):
                self._cache["cell_scale"] = np.array([
                    float(np.max(np.abs(self.A_n))), float(np.max(np.abs(self.M_g))),
                    float(np.max(np.abs(self.J2_n))) if self._has_J else math.nan,
                    float(np.max(np.abs(self.dJ2_g))) if self._has_J else math.nan])
        return self._cache["cell_scale"]

    def _build_cells(self, cells) -> None:
        """Chebyshev interpolants of (A_Σ, M_Σ, J_II, J_II′) on the node intervals ``cells``
        that have none yet, from one evaluation of M_Σ, J_II, J_II′ at the Chebyshev points of
        each (interior points: a jump at a break, which is a node, is never straddled); A_Σ is
        its node value plus the antiderivative of M_Σ's interpolant (Clenshaw–Curtis-like,
        no quadrature points of its own).

        The interpolant of degree N − 1 of a function analytic in a Bernstein ellipse of
        parameter ρ errs by O(ρ^−N) (Trefethen, «Approximation Theory and Approximation
        Practice», th. 8.2): on a node interval of a tenth of a degree its last coefficients
        sink to rounding.  A cell is used only if the last three coefficients of every
        quantity are below :data:`CELL_TOL` of its size (there or over the cycle); otherwise (a near-singular
        position, where the analogs change on the scale of the interval) it is marked None and
        the extremum search evaluates exactly there.  The search over the cycle asks about the
        same few cells many times (Мерцалов, Виттенбауэр, each iteration of the exact
        solution): the exact model quantities are computed once per cell."""
        idx = np.asarray(cells, dtype=np.int64)
        idx = idx[self._state[idx] == 0]
        if not idx.size:
            return
        idx = np.unique(idx)
        lo, hi = self.nodes[idx], self.nodes[idx + 1]
        half = 0.5 * (hi - lo)
        pts = cheb_points(lo, hi).ravel()
        Ms = self._call(self._M, pts) + self._md(pts)
        vals = np.stack((Ms, self._call(self._J2, pts), self._call(self._dJ2, pts))).reshape(3, idx.size, CHEB_POINTS)
        coef = cheb_coefficients(vals)
        # the size of a quantity: its largest value on the cell or over the cycle (M_Σ is a
        # sum of the loads' moments, whose rounding is that of the largest of them)
        size = np.maximum(np.max(np.abs(vals), axis=2), self._cell_scale()[1:, None])
        tail = np.max(np.abs(coef[:, :, -3:]), axis=2)
        ok = np.all((tail <= CELL_TOL * size) & np.all(np.isfinite(vals), axis=2), axis=0)
        # A_Σ = A_Σ(node) + ∫ M_Σ: the antiderivative of M_Σ's interpolant, zero at the node
        Aco = np.polynomial.chebyshev.chebint(coef[0], lbnd=-1, axis=-1) * half[:, None]
        Aco[:, 0] += self.A_n[idx]
        monoA = cheb_to_monomial(Aco)
        mono = cheb_to_monomial(coef)
        self._tab[idx, 0, :] = monoA[:, ::-1]
        self._tab[idx, 1:, 1:] = mono[:, :, ::-1].transpose(1, 0, 2)
        self._mids[idx] = 0.5 * (lo + hi)
        self._ihs[idx] = 1.0 / half
        self._state[idx] = np.where(ok, 1, -1)

    def _cell(self, c: int) -> CellPoly | None:
        """The interpolants of node interval c as a :class:`CellPoly` (None: evaluated exactly)."""
        if self._state[c] <= 0:
            return None
        cp = self._polys.get(c)
        if cp is None:
            t = self._tab[c]
            rows = [t[0].tolist()] + [t[q, 1:].tolist() for q in range(1, 4)]
            cp = self._polys[c] = CellPoly(float(self._mids[c]), float(self._ihs[c]), rows)
        return cp

    def line_extremum(self, slope: float, kind: str):
        """max/min over the cycle of A_Σ(φ) − slope·J_II(φ) (Мерцалов ΔT_I, Виттенбауэр K, L);
        derivative M_Σ(φ) − slope·J_II′(φ).  Returns (φ, value, (A_Σ, M_Σ, J_II, J_II′))."""
        gn = self.A_n[:-1] - slope * self.J2_n[:-1]

        def combine(A, Ms, J, dJ):
            return A - slope * J, Ms - slope * dJ

        return self.extremum(gn, combine, kind, compiled=(0, slope, 0.0))

    def energy_extrema(self, J: float, T: float) -> "_Ext":
        """Extremes of ω²/2 = (T₀ + A_Σ)/(J_I + J_II) for given J_I, T₀.

        d(ω²)/dφ = 0 ⇔ M_Σ(J_I + J_II) − (T₀ + A_Σ)·J_II′ = 0 (i.e. M_Σ = ½ J_II′ ω²).
        """
        gn = (T + self.A_n[:-1]) / (J + self.J2_n[:-1])

        def combine(A, Ms, J2, dJ2):
            return (T + A) / (J + J2), Ms * (J + J2) - (T + A) * dJ2

        p1, e1, q1 = self.extremum(gn, combine, "max", compiled=(1, J, T))
        p2, e2, q2 = self.extremum(gn, combine, "min", compiled=(1, J, T))
        return _Ext(p1, e1, p2, e2, q1[0], q2[0], q1[2], q2[2])

    def A_extremum(self, kind: str):
        """Exact max/min of A_Σ over the cycle (root of M_Σ, kinks and ends included): (φ, A_Σ,
        (A_Σ, M_Σ, J_II, J_II′)), remembered (the exact solution needs the minimum, the note both)."""
        key = "A_" + kind
        if key not in self._cache:
            self._cache[key] = self.extremum(self.A_n[:-1], _A_combine, kind, compiled=(2, 0.0, 0.0))
        return self._cache[key]

    def A_min(self) -> float:
        """Exact minimum of A_Σ over the cycle (lower bound of admissible −T₀)."""
        return self.A_extremum("min")[1]


def _A_combine(A, Ms, J, dJ):
    """A_Σ and its derivative M_Σ (for :meth:`DynamicModel.extremum`)."""
    return A, Ms


class _Ext(NamedTuple):
    """Extremes of ω²/2: positions, values e = ω²/2, A_Σ and J_II there."""

    p_max: float
    e_max: float
    p_min: float
    e_min: float
    A_max: float
    A_min: float
    J_max: float
    J_min: float


def prepare_model(J2: ArrayFunc | None, dJ2: ArrayFunc | None, M: ArrayFunc,
                  breaks: Iterable[float] | None, cycle_start: float, cycle_length: float,
                  grid, Mdrive: float | ArrayFunc | None = None, **kw) -> DynamicModel:
    """Build the tabulated :class:`DynamicModel` shared by all methods (see its docstring)."""
    return DynamicModel(J2, dJ2, M, breaks, cycle_start, cycle_length, grid, Mdrive, **kw)


# --------------------------------------------------------------------------------------------
# 1. Works
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Works:
    """Works of the reduced moments on the grid [J].

    phi        – grid φ [rad];
    A_c        – A_c(φ) = ∫_{φ_a}^{φ} M_пр.с dφ (work of resistances and other loads);
    A_d        – A_дв(φ) = ∫ M_дв dφ;
    A_sum      – A_Σ(φ) = A_дв + A_c = ΔT(φ);
    M_c, M_d, M_sum – the moments on the grid [N·m];
    A_c_cycle, A_d_cycle – works over the whole cycle; M_drive – M_дв (mean over the cycle if
    it was given as a function); cycle_start, cycle_length.
    """

    phi: np.ndarray
    A_c: np.ndarray
    A_d: np.ndarray
    A_sum: np.ndarray
    M_c: np.ndarray
    M_d: np.ndarray
    M_sum: np.ndarray
    A_c_cycle: float
    A_d_cycle: float
    M_drive: float
    cycle_start: float
    cycle_length: float


def _works_of(model: DynamicModel) -> Works:
    return Works(phi=model.phi, A_c=model.Ac_g, A_d=model.Ad_g, A_sum=model.A_g,
                 M_c=model.Mc_g, M_d=model.Md_g, M_sum=model.M_g,
                 A_c_cycle=float(model.Ac_total), A_d_cycle=float(model.Ad_total),
                 M_drive=float(model.M_drive_mean), cycle_start=model.a,
                 cycle_length=model.L)


def works(M: ArrayFunc, Mdrive: float | ArrayFunc | None, grid,
          breaks: Iterable[float] | None, cycle: Sequence[float]) -> Works:
    """Works of the loads over one cycle ``cycle = (φ_a, Φ)``.

    A_c(φ) = ∫_{φ_a}^{φ} M_пр.с dφ, A_c = A_c(φ_a + Φ); M_дв = −A_c/Φ (constant driving moment
    from zero cycle work, Артоболевский) unless given; A_Σ = A_дв + A_c.  Integrals split at the
    breaks, Gauss–Legendre (8 points per interval, intervals ≤ Φ/720).
    """
    model = DynamicModel(None, None, M, breaks, cycle[0], cycle[1], grid, Mdrive)
    return _works_of(model)


# --------------------------------------------------------------------------------------------
# 4. Exact periodic motion (needed by the other methods for "δ achieved")
# --------------------------------------------------------------------------------------------
def _on_grid(res, phi) -> bool:
    """Is φ the model's grid itself?  Then ω and ε of a method are its values tabulated there
    (``res.omega``, ``res.eps``: the same formula on the same A_Σ, J_II, J_II′, M_Σ; only the
    cycle's last point differs, at rounding level, by J_II taken at φ_a + Φ instead of φ_a)."""
    grid = res.phi
    return isinstance(phi, np.ndarray) and phi.shape == grid.shape and (phi is grid or np.array_equal(phi, grid))


class _EnergyIntegral:
    """ω and ε of a motion given by the energy integral ½(J_I + J_II(φ))ω² = T₀ + A_Σ(φ)
    (the exact solution, and Виттенбауэр's with T₀ from the upper tangency — Гутьяр's form).
    Needs the attributes ``T0``, ``J_I`` and ``model``."""

    def omega_at(self, phi) -> np.ndarray:
        """ω(φ) = √(2(T₀ + A_Σ(φ))/(J_I + J_II(φ))) at arbitrary φ."""
        if _on_grid(self, phi):
            return self.omega.copy()
        m = self.model
        return np.sqrt(2.0 * (self.T0 + m.A(phi)) / (self.J_I + m.J2(phi)))

    def eps_at(self, phi) -> np.ndarray:
        """ε(φ) = (M_Σ − ½ J_II′ ω²)/(J_I + J_II) at arbitrary φ."""
        if _on_grid(self, phi):
            return self.eps.copy()
        m = self.model
        w = self.omega_at(phi)
        return (m.M_sum(phi) - 0.5 * m.dJ2(phi) * w * w) / (self.J_I + m.J2(phi))


@dataclass(frozen=True, eq=False)
class ExactMotion(_EnergyIntegral):
    """Exact periodic steady motion ½(J_I + J_II)ω² = T₀ + A_Σ(φ).

    J_I [kg·m²], T0 [J] (kinetic energy at φ_a is T0 + A_Σ(φ_a) = T0);
    phi, omega [rad/s], eps [rad/s²] on the grid, ε = (M_Σ − ½J_II′ω²)/(J_I + J_II);
    omega_max/omega_min and where they occur (phi_omega_max/phi_omega_min, in the cycle);
    delta_achieved = (ω_max − ω_min)/ω_ср_target, omega_mean_achieved = (ω_max + ω_min)/2;
    iterations and algorithm of the J_I search ("given" when J_I was prescribed).
    """

    J_I: float
    T0: float
    phi: np.ndarray
    omega: np.ndarray
    eps: np.ndarray
    omega_max: float
    omega_min: float
    phi_omega_max: float
    phi_omega_min: float
    delta_achieved: float
    omega_mean_achieved: float
    iterations: int
    algorithm: str
    model: DynamicModel = field(repr=False)



def _check_targets(omega_m: float, delta: float):
    if not (omega_m > 0 and math.isfinite(omega_m)):
        raise ValueError(f"ω_ср must be positive, got {omega_m}")
    if not (0 < delta < 2):
        raise ValueError(f"δ must lie in (0, 2), got {delta}")


def _motion(model: DynamicModel, J: float, T: float, omega_m: float, it: int,
            algorithm: str, ext=None) -> ExactMotion:
    if ext is None:
        ext = model.energy_extrema(J, T)
    p1, e1, p2, e2 = ext.p_max, ext.e_max, ext.p_min, ext.e_min
    wmax, wmin = math.sqrt(2 * e1), math.sqrt(2 * e2)
    Jt = J + model.J2_g
    w = np.sqrt(2.0 * (T + model.A_g) / Jt)
    eps = (model.M_g - 0.5 * model.dJ2_g * w * w) / Jt
    return ExactMotion(J_I=float(J), T0=float(T), phi=model.phi, omega=w, eps=eps,
                       omega_max=wmax, omega_min=wmin, phi_omega_max=p1, phi_omega_min=p2,
                       delta_achieved=(wmax - wmin) / omega_m,
                       omega_mean_achieved=0.5 * (wmax + wmin), iterations=it,
                       algorithm=algorithm, model=model)


def _solve_T0(model: DynamicModel, J: float, omega_m: float, T_guess: float | None = None,
              maxiter: int = 60):
    """T₀ such that (ω_max + ω_min)/2 = ω_ср for a given J_I.

    Newton with the envelope derivative d ω_ext/dT₀ = 1/(ω_ext (J_I + J_II(φ_ext))); the mean
    is increasing and concave in T₀, so steps below the admissible bound T₀ > −min A_Σ are
    pulled back halfway.  Bisection/brentq fallback.  Returns (T₀, extrema, iterations).
    """
    if J + float(model.J2_n.min()) <= 0:
        raise ValueError("J_I + J_II(φ) must stay positive")
    T_low = -model.A_min()
    Jm = J + float(np.mean(model.J2_n[:-1]))
    if T_guess is None:
        T_guess = 0.5 * omega_m ** 2 * Jm - float(np.mean(model.A_n[:-1]))
    span = max(abs(T_low), 0.5 * omega_m ** 2 * abs(Jm), 1e-300)
    T = max(T_guess, T_low + 1e-3 * span)
    tolf = 1e-14 * omega_m
    for it in range(1, maxiter + 1):
        ext = model.energy_extrema(J, T)
        w1, w2 = math.sqrt(2 * ext.e_max), math.sqrt(max(2 * ext.e_min, 0.0))
        f = 0.5 * (w1 + w2) - omega_m
        if abs(f) <= tolf:
            return T, ext, it
        Jt1 = J + ext.J_max
        Jt2 = J + ext.J_min
        if w2 <= 0:
            T = 0.5 * (T + T_low) if f > 0 else T + 0.5 * span
            continue
        fp = 0.5 * (1.0 / (w1 * Jt1) + 1.0 / (w2 * Jt2))
        Tn = T - f / fp
        if Tn <= T_low:
            Tn = 0.5 * (T + T_low)
        if abs(Tn - T) <= 2 * _EPS * abs(T) + 1e-300:
            return Tn, model.energy_extrema(J, Tn), it
        T = Tn

    # fallback: brentq on the monotone mean
    def f(T):
        e = model.energy_extrema(J, T)
        return 0.5 * (math.sqrt(2 * e.e_max) + math.sqrt(max(2 * e.e_min, 0.0))) - omega_m

    lo = T_low + 1e-14 * span
    hi = max(T, lo) + span
    while f(hi) < 0:
        hi += 2 * (hi - lo)
    T = brentq(f, lo, hi, xtol=1e-15 * span, rtol=4 * _EPS, maxiter=400)
    return T, model.energy_extrema(J, T), maxiter


def _exact_newton(model: DynamicModel, omega_m: float, delta: float, maxiter: int = 60):
    """2-D Newton on ω_max(J_I, T₀) = ω_ср(1 + δ/2), ω_min(J_I, T₀) = ω_ср(1 − δ/2).

    With the envelope Jacobian (∂(ω²/2)/∂T₀ = 1/J_пр, ∂(ω²/2)/∂J_I = −(ω²/2)/J_пр at the
    extreme) one Newton step is the solution of the two tangency equations
    T₀ + A_Σ(φ_k) = ½ω_k²(J_I + J_II(φ_k)) for the current extreme positions φ_k;
    convergence is quadratic.  Returns (J, T, iterations) or None if it fails.
    """
    s1 = 0.5 * (omega_m * (1 + 0.5 * delta)) ** 2
    s2 = 0.5 * (omega_m * (1 - 0.5 * delta)) ** 2
    J2min = float(model.J2_n.min())
    T_low = -model.A_min()
    An = model.A_n[:-1]
    # crude start: ignore J_II's variation (J ≈ range A / (δ ω²)), T₀ from ω² ≈ ω_ср²
    J = float(np.ptp(An)) / (delta * omega_m ** 2) + 1e-12
    J = max(J, -J2min + 1e-6 * (abs(J2min) + 1))
    T = 0.5 * omega_m ** 2 * (J + float(np.mean(model.J2_n[:-1]))) - float(np.mean(An))
    T = max(T, T_low + 1e-6 * abs(T_low) + 1e-12)
    for it in range(1, maxiter + 1):
        ext = model.energy_extrema(J, T)
        Aa = (ext.A_max, ext.A_min)
        Jj = (ext.J_max, ext.J_min)
        Jn = ((Aa[0] - s1 * Jj[0]) - (Aa[1] - s2 * Jj[1])) / (s1 - s2)
        Tn = s1 * (Jn + Jj[0]) - Aa[0]
        # damping keeps the state admissible (J_I + J_II > 0, T₀ + A_Σ > 0)
        lam = 1.0
        while lam > 1e-6 and not (Jn > -J2min and Tn > T_low):
            lam *= 0.5
            Jn = J + lam * (Jn - J)
            Tn = T + lam * (Tn - T)
        if not (Jn > -J2min and Tn > T_low):
            return None
        dJ, dT = abs(Jn - J), abs(Tn - T)
        J, T = float(Jn), float(Tn)
        # quadratic convergence: a step of 1e-9 leaves an error of O(1e-18); exact() checks δ
        if dJ <= 1e-9 * (abs(J) + abs(J2min)) and dT <= 1e-9 * (abs(T) + abs(T_low)):
            return J, T, it
    return J, T, maxiter


def _exact_nested(model: DynamicModel, omega_m: float, delta: float, J_start: float):
    """Nested root finding: inner T₀(J_I) from the mean condition, outer brentq on
    δ(J_I) = (ω_max − ω_min)/ω_ср − [δ] (δ decreases with J_I)."""
    J2min = float(model.J2_n.min())
    state = {"T": None, "J": None, "n": 0}

    def f(J):
        guess = None if state["T"] is None else \
            state["T"] + 0.5 * omega_m ** 2 * (J - state["J"])
        T, ext, _ = _solve_T0(model, J, omega_m, guess)
        state["T"], state["J"] = T, J
        state["n"] += 1
        return (math.sqrt(2 * ext.e_max) - math.sqrt(2 * ext.e_min)) / omega_m - delta

    J0 = max(J_start, -J2min + 1e-9 * (abs(J2min) + abs(J_start) + 1))
    f0 = f(J0)
    lo = hi = J0
    flo = fhi = f0
    step = 0.25 * (abs(J0) + abs(J2min) + 1e-12)
    k = 0
    while flo < 0 and k < 200:  # δ too small: decrease J_I
        hi, fhi = lo, flo
        lo = max(lo - step, -J2min + 0.5 * (lo + J2min))
        step *= 2
        flo = f(lo)
        k += 1
    while fhi > 0 and k < 400:  # δ too large: increase J_I
        lo, flo = hi, fhi
        hi = hi + step
        step *= 2
        fhi = f(hi)
        k += 1
    if flo == 0:
        J = lo
    elif fhi == 0:
        J = hi
    else:
        J = brentq(f, lo, hi, xtol=4 * _EPS * (abs(hi) + abs(J2min)), rtol=4 * _EPS,
                   maxiter=200)
    T, ext, _ = _solve_T0(model, J, omega_m, state["T"] + 0.5 * omega_m ** 2 * (J - state["J"]))
    return J, T, state["n"], ext


def exact(model: DynamicModel, omega_m: float, delta: float, J_I: float | None = None,
          algorithm: str = "newton", T0_guess: float | None = None) -> ExactMotion:
    """Exact periodic steady motion of the machine (energy integral).

    ½(J_I + J_II(φ)) ω² = T₀ + A_Σ(φ) (exact for M = M(φ)).  With ``J_I`` given, T₀ is the
    root of (ω_max + ω_min)/2 = ω_ср; otherwise J_I is found as well so that
    (ω_max − ω_min)/ω_ср = δ.  ω_max/ω_min are located by root finding of
    M_Σ = ½ J_II′ ω² (d(ω²)/dφ = 0) with A_Σ at arbitrary φ.
    ``algorithm``: "newton" (2-D Newton with envelope Jacobian, falls back to "nested" if it
    does not reach δ to 1e-12) or "nested" (brentq on J_I around Newton on T₀).
    ``T0_guess`` only speeds up the T₀ search for a given J_I.
    """
    _check_targets(omega_m, delta)
    if J_I is not None:
        T, ext, it = _solve_T0(model, float(J_I), omega_m, T0_guess)
        return _motion(model, float(J_I), T, omega_m, it, "given", ext)
    if algorithm not in ("newton", "nested"):
        raise ValueError(f"unknown algorithm {algorithm!r}")
    res = _exact_newton(model, omega_m, delta) if algorithm == "newton" else None
    if res is not None:
        J, T, it = res
        mot = _motion(model, J, T, omega_m, it, "newton")
        if (abs(mot.delta_achieved - delta) <= 1e-12 and
                abs(mot.omega_mean_achieved - omega_m) <= 1e-12 * omega_m):
            return mot
        J_start = J
    else:
        J_start = float(np.ptp(model.A_n)) / (delta * omega_m ** 2)
    J, T, n, ext = _exact_nested(model, omega_m, delta, J_start)
    return _motion(model, J, T, omega_m, n, "nested", ext)


# --------------------------------------------------------------------------------------------
# 2. Мерцалов (worksheet 000)
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class MertsalovResult:
    """Мерцалов's method exactly as worksheet 000.

    T_II(φ) = J_II(φ)ω_ср²/2; ΔT_I(φ) = A_Σ(φ) − T_II(φ) (grid arrays T_II, dT_I);
    dT_I_max/dT_I_min at phi_dT_max/phi_dT_min (refined: M_Σ = ½J_II′ω_ср²);
    J_I = (ΔT_I,max − ΔT_I,min)/(ω_ср² δ);
    omega ≈ ω_ср + (ΔT_I − (ΔT_I,max + ΔT_I,min)/2)/(ω_ср J_I) and
    eps = M_Σ/(J_I + J_II) − ω² J_II′/(2(J_I + J_II)) on the grid (worksheet formulas);
    omega_max/omega_min of that approximate curve (= ω_ср(1 ± δ/2));
    delta_achieved – δ of the exact motion with this J_I (T₀ from the mean condition).
    """

    J_I: float
    phi: np.ndarray
    T_II: np.ndarray
    dT_I: np.ndarray
    dT_I_max: float
    dT_I_min: float
    phi_dT_max: float
    phi_dT_min: float
    omega: np.ndarray
    eps: np.ndarray
    omega_max: float
    omega_min: float
    delta_achieved: float
    omega_m: float
    model: DynamicModel = field(repr=False)

    def omega_at(self, phi) -> np.ndarray:
        """ω(φ) ≈ ω_ср + (ΔT_I − ΔT_I,mid)/(ω_ср J_I) with ΔT_I = A_Σ − J_II ω_ср²/2 (Мерцалов;
        domain.md § 1.5), exact on the cycle grid."""
        if _on_grid(self, phi):
            return self.omega.copy()
        m = self.model
        dT = m.A(phi) - 0.5 * self.omega_m ** 2 * m.J2(phi)
        mid = 0.5 * (self.dT_I_max + self.dT_I_min)
        return self.omega_m + (dT - mid) / (self.omega_m * self.J_I)

    def eps_at(self, phi) -> np.ndarray:
        """ε(φ) from the equation of motion: ε = M_Σ/J − ω² J′_II/(2J), J = J_I + J_II (domain.md §
        1.5), with ω of :meth:`omega_at`."""
        if _on_grid(self, phi):
            return self.eps.copy()
        m = self.model
        w = self.omega_at(phi)
        Jt = self.J_I + m.J2(phi)
        return m.M_sum(phi) / Jt - w * w * m.dJ2(phi) / (2 * Jt)


def mertsalov(model: DynamicModel, omega_m: float, delta: float,
              with_delta_achieved: bool = True) -> MertsalovResult:
    """Мерцалов's method (Попов–Тимофеев; worksheet 000, «Рассчитаем момент инерции первой
    группы звеньев»): T_II ≈ J_II ω_ср²/2, ΔT_I = A_Σ − T_II,
    J_I = (ΔT_I,max − ΔT_I,min)/(ω_ср² δ).

    The extremes of ΔT_I are found on the whole cycle (scan + brentq on
    d(ΔT_I)/dφ = M_Σ − ½J_II′ω_ср²; kinks at breaks and cycle ends included).
    """
    _check_targets(omega_m, delta)
    s = 0.5 * omega_m ** 2
    p1, v1, q1 = model.line_extremum(s, "max")
    p2, v2, _ = model.line_extremum(s, "min")
    J = (v1 - v2) / (omega_m ** 2 * delta)
    T_II = s * model.J2_g
    dT = model.A_g - T_II
    mid = 0.5 * (v1 + v2)
    w = omega_m + (dT - mid) / (omega_m * J)
    Jt = J + model.J2_g
    eps = model.M_g / Jt - w * w * model.dJ2_g / (2 * Jt)
    if with_delta_achieved:
        # T₀ guess from the approximate motion at φ_ΔTmax: ½(J_I + J_II)ω_max² − A_Σ
        Tg = 0.5 * (J + q1[2]) * (omega_m * (1 + 0.5 * delta)) ** 2 - q1[0]
        d_ach = exact(model, omega_m, delta, J_I=J, T0_guess=Tg).delta_achieved
    else:
        d_ach = float("nan")
    return MertsalovResult(J_I=float(J), phi=model.phi, T_II=T_II, dT_I=dT, dT_I_max=v1,
                           dT_I_min=v2, phi_dT_max=p1, phi_dT_min=p2, omega=w, eps=eps,
                           omega_max=omega_m + (v1 - mid) / (omega_m * J),
                           omega_min=omega_m + (v2 - mid) / (omega_m * J),
                           delta_achieved=float(d_ach), omega_m=omega_m, model=model)


# --------------------------------------------------------------------------------------------
# 3. Виттенбауэр
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class TangentPoint:
    """Point of tangency on the energy–mass diagram: φ [rad], J = J_II(φ) [kg·m²],
    dT = ΔT = A_Σ(φ) [J]."""

    phi: float
    J: float
    dT: float


@dataclass(frozen=True, eq=False)
class WittenbauerResult(_EnergyIntegral):
    """Energy–mass (Виттенбауэр) diagram ΔT(J_II) and the flywheel it gives.

    Curve: J_curve = J_II(φ), dT_curve = A_Σ(φ) on the grid (phi).
    Exact slopes slope_max = ω_max²/2, slope_min = ω_min²/2, ω_max,min = ω_ср(1 ± δ/2).
    Upper tangent ΔT = K + slope_max·J, lower ΔT = L + slope_min·J;
    K = max(A_Σ − J_II ω_max²/2), L = min(A_Σ − J_II ω_min²/2) at tangent_max, tangent_min.
    J_I = 2(K − L)/(ω_max² − ω_min²) (≡ KL/(ω_ср²δ)); T0 = ½ω_max² J_I − K; the tangents meet at
    origin = (−J_I, −T0), the origin of the absolute (J_пр, T) axes.
    *_linear: the same with the textbook slopes ω_ср²(1 ± δ)/2 (J_I_linear = KL/(ω_ср²δ)).
    delta_achieved, delta_achieved_linear – δ of the exact motion with J_I, J_I_linear.
    """

    J_I: float
    T0: float
    K: float
    L: float
    KL: float
    slope_max: float
    slope_min: float
    omega_max: float
    omega_min: float
    tangent_max: TangentPoint
    tangent_min: TangentPoint
    origin: tuple[float, float]
    J_I_linear: float
    K_linear: float
    L_linear: float
    slope_max_linear: float
    slope_min_linear: float
    tangent_max_linear: TangentPoint
    tangent_min_linear: TangentPoint
    phi: np.ndarray
    J_curve: np.ndarray
    dT_curve: np.ndarray
    omega: np.ndarray
    eps: np.ndarray
    delta_achieved: float
    delta_achieved_linear: float
    model: DynamicModel = field(repr=False)

    def upper_tangent(self, J) -> np.ndarray:
        """ΔT on the tangent of slope ω_max²/2 through K: ΔT = K + J·ω_max²/2 (the energy–mass
        diagram, domain.md § 1.5)."""
        return self.K + self.slope_max * np.asarray(J, dtype=float)

    def lower_tangent(self, J) -> np.ndarray:
        """ΔT on the tangent of slope ω_min²/2 through L: ΔT = L + J·ω_min²/2 (the energy–mass
        diagram, domain.md § 1.5)."""
        return self.L + self.slope_min * np.asarray(J, dtype=float)


def _tangents(model: DynamicModel, s1: float, s2: float):
    p1, K, q1 = model.line_extremum(s1, "max")
    p2, L, q2 = model.line_extremum(s2, "min")
    J = (K - L) / (s1 - s2)
    return J, K, L, TangentPoint(p1, q1[2], q1[0]), TangentPoint(p2, q2[2], q2[0])


def wittenbauer(model: DynamicModel, omega_m: float, delta: float,
                with_delta_achieved: bool = True) -> WittenbauerResult:
    """Виттенбауэр's energy–mass diagram (Артоболевский; domain.md §1.5).

    Tangency conditions of ½ω² J_пр = T₀ + ΔT at the extremes:
    T₀ + K = ½ω_max² J_I and T₀ + L = ½ω_min² J_I ⇒ J_I = 2(K − L)/(ω_max² − ω_min²),
    which equals KL/(ω_ср² δ) exactly for ω_max,min = ω_ср(1 ± δ/2).  K, L are refined by
    root finding of M_Σ = ½ J_II′ ω_max,min² at the tangency.  Also returns the linearised
    variant with slopes ω_ср²(1 ± δ)/2.
    """
    _check_targets(omega_m, delta)
    wmax = omega_m * (1 + 0.5 * delta)
    wmin = omega_m * (1 - 0.5 * delta)
    s1, s2 = 0.5 * wmax ** 2, 0.5 * wmin ** 2
    J, K, L, t1, t2 = _tangents(model, s1, s2)
    T0 = s1 * J - K
    l1, l2 = 0.5 * omega_m ** 2 * (1 + delta), 0.5 * omega_m ** 2 * (1 - delta)
    Jl, Kl, Ll, u1, u2 = _tangents(model, l1, l2)
    Jt = J + model.J2_g
    w = np.sqrt(2.0 * (T0 + model.A_g) / Jt)
    eps = (model.M_g - 0.5 * model.dJ2_g * w * w) / Jt
    if with_delta_achieved:
        da = exact(model, omega_m, delta, J_I=J, T0_guess=T0).delta_achieved
        dl = exact(model, omega_m, delta, J_I=Jl, T0_guess=s1 * Jl - Kl).delta_achieved
    else:
        da = dl = float("nan")
    return WittenbauerResult(
        J_I=float(J), T0=float(T0), K=float(K), L=float(L), KL=float(K - L),
        slope_max=s1, slope_min=s2, omega_max=wmax, omega_min=wmin, tangent_max=t1,
        tangent_min=t2, origin=(-float(J), -float(T0)), J_I_linear=float(Jl),
        K_linear=float(Kl), L_linear=float(Ll), slope_max_linear=l1, slope_min_linear=l2,
        tangent_max_linear=u1, tangent_min_linear=u2, phi=model.phi, J_curve=model.J2_g,
        dT_curve=model.A_g, omega=w, eps=eps, delta_achieved=float(da),
        delta_achieved_linear=float(dl), model=model)


# --------------------------------------------------------------------------------------------
# 5. Flywheel dimensions
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class RimFlywheel:
    """Rim (обод) flywheel: outer D2, inner D1, width b [m], mass m [kg]; v_rim = ω_max·D2/2
    [m/s] (nan if ω_max unknown); v_exceeds – v_rim above the material limit."""

    D2: float
    D1: float
    b: float
    m: float
    v_rim: float
    v_exceeds: bool


@dataclass(frozen=True)
class DiskFlywheel:
    """Solid disk flywheel: diameter D, width b [m], mass m [kg]; v_rim = ω_max·D/2 [m/s]."""

    D: float
    b: float
    m: float
    v_rim: float
    v_exceeds: bool


@dataclass(frozen=True)
class FlywheelDims:
    """Flywheel sized for J_доп = J_I − J_O.пр.

    rim           – worksheet 000 empirical rim with spokes: D2 = 0.437·J^(1/5), D1 = 0.8·D2,
                    b = 0.2·D2, m = 6123·(D2² − D1²)·b (course-manual constants, configurable);
    disk          – worksheet 000 empirical disk: D = 0.366·J^(1/5), b = 0.2·D, m = 1230·D³;
    disk_physical – solid disk from J = mD²/8 = πρbD⁴/32 with ψ_b = b/D:
                    D = (32J/(πρψ_b))^(1/5), m = πρbD²/4;
    rim_physical  – thick ring (spokes and hub neglected), J = πρb(D2⁴ − D1⁴)/32 with
                    D1 = ψ_h D2, b = ψ_b D2: D2 = (32J/(πρψ_b(1 − ψ_h⁴)))^(1/5),
                    m = πρb(D2² − D1²)/4;
    needed        – False when J_доп ≤ 0 (the linkage alone keeps δ; all sizes are 0);
    v_limit [m/s], rho [kg/m³], psi_b, psi_h, omega_max [rad/s] – the inputs;
    any_exceeds   – some variant exceeds the rim-speed limit.
    """

    J_required: float
    needed: bool
    rim: RimFlywheel
    disk: DiskFlywheel
    disk_physical: DiskFlywheel
    rim_physical: RimFlywheel
    omega_max: float
    v_limit: float
    rho: float
    psi_b: float
    psi_h: float

    @property
    def any_exceeds(self) -> bool:
        """Whether a rim or disc flywheel (empirical or exact dimensions) exceeds the allowed rim
        speed ωD/2 (about 30 m/s for cast iron, domain.md § 1.5)."""
        return any(x.v_exceeds for x in (self.rim, self.disk, self.disk_physical,
                                          self.rim_physical))


def flywheel_dims(J_required: float, omega_max: float | None = None, *,
                  rim_coef: float = 0.437, rim_inner_ratio: float = 0.8,
                  rim_width_ratio: float = 0.2, rim_mass_coef: float = 6123.0,
                  disk_coef: float = 0.366, disk_width_ratio: float = 0.2,
                  disk_mass_coef: float = 1230.0, rho: float = 7800.0, psi_b: float = 0.2,
                  psi_h: float = 0.8, v_limit: float = 30.0) -> FlywheelDims:
    """Flywheel dimensions for the required moment of inertia J_доп [kg·m²].

    Empirical rim and disk formulas of the course manual (worksheet 000) and the physically
    derived disk and ring (J = πρbD⁴/32 and J = πρb(D2⁴ − D1⁴)/32).  The rim speed
    ω_max·D/2 is compared with ``v_limit`` (≈ 30 m/s for cast iron; steel allows more).
    """
    J = float(J_required)
    w = float("nan") if omega_max is None else float(omega_max)

    def v_of(D):
        v = w * D / 2
        return v, bool(v > v_limit) if math.isfinite(v) else False

    if not J > 0:
        z = RimFlywheel(0.0, 0.0, 0.0, 0.0, 0.0, False)
        zd = DiskFlywheel(0.0, 0.0, 0.0, 0.0, False)
        return FlywheelDims(J, False, z, zd, zd, z, w, v_limit, rho, psi_b, psi_h)
    r5 = J ** 0.2
    D2 = rim_coef * r5
    D1 = rim_inner_ratio * D2
    b = rim_width_ratio * D2
    m = rim_mass_coef * (D2 ** 2 - D1 ** 2) * b
    rim = RimFlywheel(D2, D1, b, m, *v_of(D2))
    D = disk_coef * r5
    bd = disk_width_ratio * D
    disk = DiskFlywheel(D, bd, disk_mass_coef * D ** 3, *v_of(D))
    Dp = (32 * J / (math.pi * rho * psi_b)) ** 0.2
    bp = psi_b * Dp
    diskp = DiskFlywheel(Dp, bp, math.pi * rho * bp * Dp ** 2 / 4, *v_of(Dp))
    D2p = (32 * J / (math.pi * rho * psi_b * (1 - psi_h ** 4))) ** 0.2
    D1p = psi_h * D2p
    b2p = psi_b * D2p
    rimp = RimFlywheel(D2p, D1p, b2p, math.pi * rho * b2p * (D2p ** 2 - D1p ** 2) / 4,
                       *v_of(D2p))
    return FlywheelDims(J, True, rim, disk, diskp, rimp, w, v_limit, rho, psi_b, psi_h)


# --------------------------------------------------------------------------------------------
# 6. Everything together
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class DynamicsResult:
    """Dynamics of the machine over one cycle and the flywheel.

    method – the method whose J_I, ω(φ), ε(φ) are reported ("exact" | "mertsalov" |
    "wittenbauer"); phi, omega, eps – its curves on the grid; J_I – its J_I [kg·m²] (whole
    first group), J_flywheel = J_I − J1_const (J_доп); delta_achieved – δ of the exact motion
    with that J_I; omega_max/omega_min at phi_omega_max/phi_omega_min – extremes of its ω(φ).
    J_I_exact, J_I_mertsalov, J_I_wittenbauer, J_I_wittenbauer_linear and
    dev_*_pct = 100·(J_I_method/J_I_exact − 1).
    works, exact, mertsalov, wittenbauer – the full results; flywheel – dimensions for
    J_flywheel (default constants; rim speed with the method's ω_max).
    """

    method: str
    phi: np.ndarray
    omega: np.ndarray
    eps: np.ndarray
    J_I: float
    J1_const: float
    J_flywheel: float
    omega_m: float
    delta: float
    delta_achieved: float
    omega_max: float
    omega_min: float
    phi_omega_max: float
    phi_omega_min: float
    J_I_exact: float
    J_I_mertsalov: float
    J_I_wittenbauer: float
    J_I_wittenbauer_linear: float
    dev_mertsalov_pct: float
    dev_wittenbauer_pct: float
    dev_wittenbauer_linear_pct: float
    works: Works
    exact: ExactMotion
    mertsalov: MertsalovResult
    wittenbauer: WittenbauerResult
    flywheel: FlywheelDims
    model: DynamicModel = field(repr=False)

    def _chosen(self):
        return {"exact": self.exact, "mertsalov": self.mertsalov,
                "wittenbauer": self.wittenbauer}[self.method]

    def omega_at(self, phi) -> np.ndarray:
        """ω(φ) of the chosen method at arbitrary φ (periodic)."""
        return self._chosen().omega_at(phi)

    def eps_at(self, phi) -> np.ndarray:
        """ε(φ) of the chosen method at arbitrary φ (periodic)."""
        return self._chosen().eps_at(phi)


def solve_dynamics(J2: ArrayFunc, dJ2: ArrayFunc, M: ArrayFunc,
                   breaks: Iterable[float] | None, cycle_start: float, cycle_length: float,
                   J1_const: float, omega_m: float, delta: float, grid,
                   method: str = "exact", Mdrive: float | ArrayFunc | None = None,
                   flywheel_kw: dict | None = None, works=None) -> DynamicsResult:
    """Dynamic analysis and flywheel synthesis over one cycle.

    J2, dJ2 – J_II(φ) and its exact derivative; M – M_пр.с(φ) (all loads except the driving
    moment); breaks – switching points of M inside the cycle; cycle [cycle_start,
    cycle_start + cycle_length]; J1_const – J_O.пр; omega_m – ω_ср; delta – δ; grid – array of
    φ (or number of intervals over the cycle); Mdrive – M_дв (None: −A_c/Φ, a number, or a
    callable of φ); works – the closed-form works of the loads (see :class:`DynamicModel`).
    Computes the exact motion, Мерцалов and Виттенбауэр (both slopes) and
    reports ``method``'s J_I, ω(φ), ε(φ) with the deviations of all from the exact J_I.
    """
    if method not in ("exact", "mertsalov", "wittenbauer"):
        raise ValueError(f"unknown method {method!r}")
    _check_targets(omega_m, delta)
    model = DynamicModel(J2, dJ2, M, breaks, cycle_start, cycle_length, grid, Mdrive, works=works)
    ex = exact(model, omega_m, delta)
    me = mertsalov(model, omega_m, delta)
    wi = wittenbauer(model, omega_m, delta)
    if method == "exact":
        ch, J, d_ach = ex, ex.J_I, ex.delta_achieved
        wmax, wmin, pmax, pmin = ex.omega_max, ex.omega_min, ex.phi_omega_max, ex.phi_omega_min
    elif method == "mertsalov":
        ch, J, d_ach = me, me.J_I, me.delta_achieved
        wmax, wmin, pmax, pmin = me.omega_max, me.omega_min, me.phi_dT_max, me.phi_dT_min
    else:
        ch, J, d_ach = wi, wi.J_I, wi.delta_achieved
        wmax, wmin = wi.omega_max, wi.omega_min
        pmax, pmin = wi.tangent_max.phi, wi.tangent_min.phi

    def dev(x):
        return 100.0 * (x / ex.J_I - 1.0)

    J1 = float(J1_const)
    fw = flywheel_dims(J - J1, wmax, **(flywheel_kw or {}))
    return DynamicsResult(
        method=method, phi=model.phi, omega=ch.omega, eps=ch.eps, J_I=float(J), J1_const=J1,
        J_flywheel=float(J - J1), omega_m=float(omega_m), delta=float(delta),
        delta_achieved=float(d_ach), omega_max=float(wmax), omega_min=float(wmin),
        phi_omega_max=float(pmax), phi_omega_min=float(pmin), J_I_exact=ex.J_I,
        J_I_mertsalov=me.J_I, J_I_wittenbauer=wi.J_I, J_I_wittenbauer_linear=wi.J_I_linear,
        dev_mertsalov_pct=dev(me.J_I), dev_wittenbauer_pct=dev(wi.J_I),
        dev_wittenbauer_linear_pct=dev(wi.J_I_linear), works=_works_of(model), exact=ex,
        mertsalov=me, wittenbauer=wi, flywheel=fw, model=model)
