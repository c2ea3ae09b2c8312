"""Composite Gauss–Legendre quadrature for piecewise-smooth integrands.

The works of the reduced moments (A_c, A_дв, A_Σ) are integrals of functions that are smooth
between known switching points (a resistance acting only on the working stroke, a kink of a
load law).  A high-order rule applied on panels that never straddle such a point integrates
them to rounding level; a rule applied across a jump loses all but one or two digits.

Everything here is pure NumPy: every function evaluates the integrand once, vectorised, for
all quadrature points of a call (the integrand is a callable ``f(x: ndarray) -> ndarray``).

Formulas
--------
* Gauss–Legendre rule of n points on [-1, 1] (exact for polynomials of degree 2n − 1),
  mapped to a panel [α, β]:  ∫_α^β f ≈ (β−α)/2 · Σ w_j f((α+β)/2 + (β−α)/2 · t_j)
  (Абрамовиц–Стиган, гл. 25.4.29; Бахвалов–Жидков–Кобельков «Численные методы», §3.6).
* The error of an n-point rule on a panel of width h is
  h^{2n+1}(n!)^4 / ((2n+1)((2n)!)^3) · f^{(2n)}(ξ); for n = 8 and h = 2π/720 this is far
  below the rounding level for the load laws of a linkage.
* Gauss–Lobatto rule of n points (both panel ends are nodes, exact to degree 2n − 3;
  Абрамовиц–Стиган 25.4.32): :class:`Antiderivative` with ``lobatto=n`` uses it on panels that
  touch no break, so the integrand at the grid nodes (where the caller already knows it) is
  shared by neighbouring panels; panels touching a break keep Gauss–Legendre.
* Chebyshev interpolation on a cell (:func:`cell_fit`): values at the N Chebyshev points of
  the first kind x_k = cos(π(k + ½)/N) (interior: a jump at a cell end is never sampled) give
  the coefficients c_j = (2/N) Σ_k f(x_k) T_j(x_k) (c₀ halved); for f analytic in a Bernstein
  ellipse of parameter ρ the interpolant errs by O(ρ^−N) and its last coefficients show it
  (Trefethen, «Approximation Theory and Approximation Practice», SIAM 2013, ch. 3, 8).
* Error estimate of :func:`integrate`: the difference between the results on n and 2n panels
  (Runge's principle; the finer value is returned, so the estimate is conservative).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Callable, Iterable

import numpy as np

__all__ = [
    "gauss_legendre",
    "gauss_lobatto",
    "gauss_panels",
    "integrate",
    "QuadResult",
    "Antiderivative",
    "cumulative",
    "merge_nodes",
    "CHEB_POINTS",
    "cheb_points",
    "cell_fit",
    "cheb_coefficients",
    "cheb_to_monomial",
    "CellPoly",
]

ArrayFunc = Callable[[np.ndarray], np.ndarray]


@lru_cache(maxsize=64)
def _gl_cached(order: int) -> tuple[np.ndarray, np.ndarray]:
    t, w = np.polynomial.legendre.leggauss(order)
    t.setflags(write=False)
    w.setflags(write=False)
    return t, w


def gauss_legendre(order: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes t_j and weights w_j of the ``order``-point Gauss–Legendre rule on [-1, 1].

    Golub–Welsch eigenvalue method as implemented by ``numpy.polynomial.legendre.leggauss``;
    results are cached and read-only.
    """
    order = int(order)
    if order < 1:
        raise ValueError(f"Gauss–Legendre order must be ≥ 1, got {order}")
    return _gl_cached(order)


def _as_breaks(breaks: Iterable[float] | None) -> np.ndarray:
    if breaks is None:
        return np.empty(0)
    b = np.asarray(list(breaks) if not isinstance(breaks, np.ndarray) else breaks, dtype=float)
    return np.unique(b.ravel())


def _eval(f: ArrayFunc, x: np.ndarray) -> np.ndarray:
    """Evaluate a vectorised integrand and check its shape."""
    y = np.asarray(f(x), dtype=float)
    if y.shape != x.shape:
        y = np.broadcast_to(y, x.shape)
    return y


def _panel_sums(f: ArrayFunc, lo: np.ndarray, hi: np.ndarray, order: int,
                with_abs: bool = False):
    """∫_{lo_i}^{hi_i} f for every panel i with one vectorised call of f.

    Returns the array of panel integrals (and, if ``with_abs``, the panel integrals of |f|,
    used as the scale of relative tolerances).
    """
    t, w = gauss_legendre(order)
    half = 0.5 * (hi - lo)
    mid = 0.5 * (hi + lo)
    x = mid[:, None] + half[:, None] * t[None, :]
    y = _eval(f, x.ravel()).reshape(x.shape)
    s = half * (y @ w)
    if with_abs:
        return s, np.abs(half) * (np.abs(y) @ w)
    return s


def gauss_lobatto(order: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of the ``order``-point Gauss–Lobatto rule on [-1, 1] (both ends are
    nodes; exact for polynomials of degree 2·order − 3), order 5 or 6, in closed form
    (Абрамовиц–Стиган, 25.4.32): order 5 — 0, ±√(3/7), weights 32/45, 49/90, ends 1/10;
    order 6 — ±√(1/3 ∓ 2√7/21), weights (14 ± √7)/30, ends 1/15.

    The error on a panel of width h is
    −n(n−1)³((n−2)!)⁴ / ((2n−1)((2n−2)!)³) · h^{2n−1} f^{(2n−2)}(ξ)."""
    if order == 5:
        r = np.sqrt(3.0 / 7.0)
        return (np.array([-1.0, -r, 0.0, r, 1.0]),
                np.array([1 / 10, 49 / 90, 32 / 45, 49 / 90, 1 / 10]))
    if order == 6:
        s7 = np.sqrt(7.0)
        r1 = np.sqrt(1 / 3 - 2 * s7 / 21)
        r2 = np.sqrt(1 / 3 + 2 * s7 / 21)
        w1 = (14 + s7) / 30
        w2 = (14 - s7) / 30
        return (np.array([-1.0, -r2, -r1, r1, r2, 1.0]),
                np.array([1 / 15, w2, w1, w1, w2, 1 / 15]))
    raise ValueError(f"Gauss–Lobatto order must be 5 or 6, got {order}")


def _panel_sums_lobatto(f: ArrayFunc, nodes: np.ndarray, breaks: np.ndarray, order: int,
                        lobatto: int) -> np.ndarray:
    """Panel integrals over consecutive ``nodes`` with one vectorised call of f: a panel with
    neither end at a break nor at an end of the node range by the ``lobatto``-point
    Gauss–Lobatto rule, whose end points are the nodes themselves (f on the nodes is shared by
    two panels, and a caller that already knows f on its grid evaluates only the interior
    points); a panel touching a break or an end (where f may jump, so its value there is not
    the panel's one-sided limit) by the ``order``-point Gauss–Legendre rule as
    :func:`_panel_sums`."""
    lo, hi = nodes[:-1], nodes[1:]
    half = 0.5 * (hi - lo)
    mid = 0.5 * (hi + lo)
    at_break = np.isin(nodes, breaks)
    at_break[0] = at_break[-1] = True
    gl = at_break[:-1] | at_break[1:]
    lb = ~gl
    tl, wl = gauss_lobatto(lobatto)
    tg, wg = gauss_legendre(order)
    il = np.flatnonzero(lb)
    ig = np.flatnonzero(gl)
    xl = (mid[il, None] + half[il, None] * tl[None, 1:-1]).ravel()
    xg = (mid[ig, None] + half[ig, None] * tg[None, :]).ravel()
    y = _eval(f, np.concatenate((nodes, xl, xg)))
    n = nodes.size
    yl = y[n:n + xl.size].reshape(il.size, lobatto - 2)
    yg = y[n + xl.size:].reshape(ig.size, order)
    s = np.empty(lo.size)
    s[il] = half[il] * (wl[0] * y[il] + yl @ wl[1:-1] + wl[-1] * y[il + 1])
    s[ig] = half[ig] * (yg @ wg)
    return s


def _segment_edges(a: float, b: float, breaks) -> np.ndarray:
    """[a, breaks strictly inside (a, b) ..., b] for a < b."""
    br = _as_breaks(breaks)
    br = br[(br > a) & (br < b)]
    return np.concatenate(([a], br, [b]))


def _panels(a: float, b: float, breaks, n_panels: int) -> tuple[np.ndarray, np.ndarray]:
    edges = _segment_edges(a, b, breaks)
    n = int(n_panels)
    if n < 1:
        raise ValueError(f"n_panels must be ≥ 1, got {n_panels}")
    s = np.linspace(0.0, 1.0, n + 1)
    lo_seg, hi_seg = edges[:-1], edges[1:]
    pts = lo_seg[:, None] + (hi_seg - lo_seg)[:, None] * s[None, :]
    pts[:, -1] = hi_seg  # exact segment ends (the breaks themselves)
    return pts[:, :-1].ravel(), pts[:, 1:].ravel()


def gauss_panels(f: ArrayFunc, a: float, b: float, breaks: Iterable[float] | None = (),
                 n_panels: int = 1, order: int = 16) -> float:
    """Composite Gauss–Legendre integral ∫_a^b f(x) dx split at the breaks.

    The interval is first cut at every break strictly inside (a, b); each piece is divided into
    ``n_panels`` equal panels, each integrated with an ``order``-point Gauss–Legendre rule.
    Gauss nodes are interior, so f is never evaluated at a break: a jump of f there is
    integrated exactly (to rounding) as long as the break is listed.  ``b < a`` gives −∫_b^a.
    """
    a = float(a)
    b = float(b)
    if a == b:
        return 0.0
    if b < a:
        return -gauss_panels(f, b, a, breaks, n_panels, order)
    lo, hi = _panels(a, b, breaks, n_panels)
    return float(np.sum(_panel_sums(f, lo, hi, order)))


@dataclass(frozen=True)
class QuadResult:
    """Result of :func:`integrate`.

    value      – the integral (from the finest panel set);
    error      – |I_{2n} − I_n|, the Runge estimate of the error of the coarser value, hence an
                 upper estimate for ``value``;
    scale      – ∫|f| (the scale to which ``rtol`` refers);
    n_panels   – panels per break-free segment in the final rule;
    n_evals    – total evaluations of f;
    converged  – whether error ≤ max(atol, rtol·scale) was reached.
    """

    value: float
    error: float
    scale: float
    n_panels: int
    n_evals: int
    converged: bool


def integrate(f: ArrayFunc, a: float, b: float, breaks: Iterable[float] | None = (),
              rtol: float = 1e-14, atol: float = 0.0, order: int = 16,
              n_start: int = 1, max_panels: int = 4096) -> QuadResult:
    """Adaptive (panel-doubling) composite Gauss–Legendre integral of f over [a, b].

    Starting from ``n_start`` panels per break-free segment, the number of panels is doubled
    until |I_{2n} − I_n| ≤ max(atol, rtol·∫|f|) (Runge's rule).  The tolerance refers to
    ∫|f| rather than |∫f| so that integrals that cancel (the cycle work of M_Σ) still converge.
    """
    a = float(a)
    b = float(b)
    sign = 1.0
    if b < a:
        a, b, sign = b, a, -1.0
    if a == b:
        return QuadResult(0.0, 0.0, 0.0, 0, 0, True)
    n = max(1, int(n_start))
    lo, hi = _panels(a, b, breaks, n)
    s, s_abs = _panel_sums(f, lo, hi, order, with_abs=True)
    prev = float(np.sum(s))
    evals = lo.size * order
    err = np.inf
    scale = float(np.sum(s_abs))
    cur = prev
    converged = False
    while 2 * n <= max_panels:
        n *= 2
        lo, hi = _panels(a, b, breaks, n)
        s, s_abs = _panel_sums(f, lo, hi, order, with_abs=True)
        evals += lo.size * order
        cur = float(np.sum(s))
        scale = float(np.sum(s_abs))
        err = abs(cur - prev)
        if err <= max(atol, rtol * scale):
            converged = True
            break
        prev = cur
    return QuadResult(sign * cur, float(err), scale, n, int(evals), converged)


def merge_nodes(grid: np.ndarray, breaks: Iterable[float] | None = (),
                max_step: float | None = None) -> np.ndarray:
    """Sorted union of the grid and the breaks inside it, with long intervals subdivided.

    Intervals longer than ``max_step`` are cut into the smallest number of equal parts not
    longer than ``max_step``.  The first and last grid values stay the ends.
    """
    g = np.asarray(grid, dtype=float).ravel()
    if g.size < 2:
        raise ValueError("a grid needs at least two nodes")
    if np.any(np.diff(g) < 0):
        raise ValueError("the grid must be non-decreasing")
    a, b = g[0], g[-1]
    br = _as_breaks(breaks)
    br = br[(br > a) & (br < b)]
    nodes = np.unique(np.concatenate((g, br)))
    if max_step is not None and max_step > 0 and nodes.size > 1:
        d = np.diff(nodes)
        k = np.maximum(1, np.ceil(d / max_step * (1 - 1e-12)).astype(np.int64))
        if np.any(k > 1):
            starts = np.repeat(nodes[:-1], k)
            widths = np.repeat(d / k, k)
            offs = np.arange(k.sum()) - np.repeat(np.cumsum(k) - k, k)
            inner = starts + offs * widths
            inner[np.cumsum(k) - k] = nodes[:-1]  # exact original nodes
            nodes = np.concatenate((inner, nodes[-1:]))
    return nodes


class Antiderivative:
    """F(x) = ∫_{x_0}^{x} f(s) ds tabulated on nodes and evaluable at any x in [x_0, x_N].

    The nodes are the sorted union of ``grid`` and ``breaks`` (optionally subdivided to
    ``max_step``); every node interval is integrated with an ``order``-point Gauss–Legendre
    rule (one vectorised call of f; with ``lobatto`` the panels touching no break by the
    Gauss–Lobatto rule of that order, see :func:`_panel_sums_lobatto`), the table is the
    running sum.  At an arbitrary x the
    value is F(x_k) + ∫_{x_k}^{x} f with x_k the nearest node below x, again by Gauss–Legendre
    (no interval crosses a break because the breaks are nodes).
    """

    def __init__(self, f: ArrayFunc, grid, breaks: Iterable[float] | None = (),
                 order: int = 8, max_step: float | None = None, lobatto: int = 0):
        self.f = f
        self.order = int(order)
        self.nodes = merge_nodes(grid, breaks, max_step)
        lo, hi = self.nodes[:-1], self.nodes[1:]
        if lobatto:
            parts = _panel_sums_lobatto(f, self.nodes, _as_breaks(breaks), self.order, lobatto)
        else:
            parts = _panel_sums(f, lo, hi, self.order)
        self.values = np.concatenate(([0.0], np.cumsum(parts)))

    @property
    def total(self) -> float:
        """∫ over the whole node range."""
        return float(self.values[-1])

    def at_nodes(self, x) -> np.ndarray:
        """F at points that are nodes (exact table look-up; raises if one is not a node)."""
        x = np.asarray(x, dtype=float)
        k = np.searchsorted(self.nodes, x)
        k = np.clip(k, 0, self.nodes.size - 1)
        if not np.array_equal(self.nodes[k], x):
            raise ValueError("at_nodes: some points are not nodes")
        return self.values[k]

    def __call__(self, x) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        xs = x.ravel()
        if xs.size and (xs.min() < self.nodes[0] - 1e-12 * max(1.0, abs(self.nodes[0]))
                        or xs.max() > self.nodes[-1] + 1e-12 * max(1.0, abs(self.nodes[-1]))):
            raise ValueError("Antiderivative evaluated outside its node range")
        k = np.searchsorted(self.nodes, xs, side="right") - 1
        k = np.clip(k, 0, self.nodes.size - 2)
        base = self.nodes[k]
        out = self.values[k].copy()
        nz = xs != base
        if np.any(nz):
            out[nz] += _panel_sums(self.f, base[nz], xs[nz], self.order)
        return out.reshape(x.shape)


def cumulative(f: ArrayFunc, grid, breaks: Iterable[float] | None = (), order: int = 8,
               max_step: float | None = None) -> np.ndarray:
    """∫_{grid[0]}^{grid[k]} f(x) dx for every grid node k (cumulative work A(φ)).

    Each grid interval, cut at the breaks it contains (and into parts not longer than
    ``max_step`` if given), is integrated with an ``order``-point Gauss–Legendre rule; f is
    called once for all quadrature points.  For smooth piecewise integrands and intervals of
    a few degrees the result is exact to ~1e-15 relative.  The grid must be non-decreasing.
    """
    g = np.asarray(grid, dtype=float).ravel()
    ad = Antiderivative(f, g, breaks, order=order, max_step=max_step)
    return ad.values[np.searchsorted(ad.nodes, g)]


# --------------------------------------------------------------------------------------------
# Chebyshev interpolants on cells
# --------------------------------------------------------------------------------------------
CHEB_POINTS = 12
_CHEB_X = np.cos(np.pi * (np.arange(CHEB_POINTS) + 0.5) / CHEB_POINTS)
# values at _CHEB_X → Chebyshev coefficients: c_j = (2/N) Σ_k f_k T_j(x_k), c₀ halved
_CHEB_T = (2.0 / CHEB_POINTS) * np.cos(np.outer(np.pi * (np.arange(CHEB_POINTS) + 0.5) / CHEB_POINTS,
                                                np.arange(CHEB_POINTS)))
_CHEB_T[:, 0] *= 0.5
# Chebyshev coefficients → monomial coefficients (row j: T_j in powers of s), one term more
# than the interpolants for their antiderivatives
_CHEB_MONO = np.zeros((CHEB_POINTS + 1, CHEB_POINTS + 1))
for _j in range(CHEB_POINTS + 1):
    _p = np.polynomial.chebyshev.cheb2poly(np.eye(CHEB_POINTS + 1)[_j])
    _CHEB_MONO[_j, :_p.size] = _p
del _j, _p


def cheb_points(lo, hi) -> np.ndarray:
    """The :data:`CHEB_POINTS` Chebyshev points of the first kind of every cell [lo_i, hi_i]:
    an array (cells, N)."""
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    return 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * _CHEB_X[None, :]


class CellPoly:
    """Several functions on one cell by their interpolating polynomials in s = (x − mid)/half
    (Horner in Python floats: the scalar root finding of a caller calls it many times)."""

    __slots__ = ("mid", "ih", "rows")

    def __init__(self, mid: float, ih: float, rows: list[list[float]]):
        self.mid, self.ih, self.rows = mid, ih, rows

    def __call__(self, x: float) -> tuple[float, ...]:
        s = float((x - self.mid) * self.ih)      # Python floats: the same IEEE operations, faster
        out = []
        for row in self.rows:
            acc = 0.0
            for c in row:
                acc = acc * s + c
            out.append(acc)
        return tuple(out)


def cheb_coefficients(vals: np.ndarray) -> np.ndarray:
    """Chebyshev coefficients (…, N) of the interpolants through values at the N Chebyshev
    points of the last axis (:func:`cheb_points`)."""
    return np.asarray(vals, dtype=float) @ _CHEB_T


def cheb_to_monomial(coef: np.ndarray) -> np.ndarray:
    """Monomial coefficients (lowest power first) of Chebyshev series of up to N + 1 terms
    (lowest first)."""
    coef = np.asarray(coef, dtype=float)
    m = coef.shape[-1]
    return coef @ _CHEB_MONO[:m, :m]


def cell_fit(lo, hi, vals: np.ndarray, tol) -> list[CellPoly | None]:
    """Interpolants of m functions on each cell from their values at :func:`cheb_points`
    (``vals``: (m, cells, N)); a cell whose last three coefficients of some function exceed
    ``tol`` (a number, or (m, cells)) is not resolved to that accuracy: None."""
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    coef = vals @ _CHEB_T
    tail = np.max(np.abs(coef[:, :, -3:]), axis=2)
    ok = np.all((tail <= tol) & np.all(np.isfinite(vals), axis=2), axis=0)
    mono = coef @ _CHEB_MONO[:CHEB_POINTS, :CHEB_POINTS]
    mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    out: list[CellPoly | None] = []
    for k in range(lo.size):
        if not ok[k] or not half[k] > 0:
            out.append(None)
            continue
        out.append(CellPoly(float(mid[k]), 1.0 / float(half[k]),
                            [mono[q, k, ::-1].tolist() for q in range(mono.shape[0])]))
    return out
