"""Tests of reportgen.core.quadrature and reportgen.analysis.flywheel.

References are independent of the code under test: closed-form works of analytic load laws,
an ODE integration of the equation of motion (solve_ivp, DOP853), brute-force sampling, and
the printed numbers of worksheet 000.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar
from scipy.special import i0

from reportgen.analysis.flywheel import (
    exact,
    flywheel_dims,
    mertsalov,
    prepare_model,
    solve_dynamics,
    wittenbauer,
    works,
)
from reportgen.core.quadrature import cumulative, gauss_panels, integrate

TWO_PI = 2 * math.pi


# --------------------------------------------------------------------------------------------
# Analytic models
# --------------------------------------------------------------------------------------------
class SmoothModel:
    """J_II = a + b sin²φ + c cos 3φ; M = −P r max(sin φ, 0) − G r cos φ (kink at π)."""

    a, b, c = 2.0, 1.5, 0.3
    Pr, Gr = 1000.0, 80.0
    breaks = [math.pi]
    start, length = 0.0, TWO_PI

    def J2(self, p):
        return self.a + self.b * np.sin(p) ** 2 + self.c * np.cos(3 * p)

    def dJ2(self, p):
        return self.b * np.sin(2 * p) - 3 * self.c * np.sin(3 * p)

    def M(self, p):
        return -self.Pr * np.maximum(np.sin(p), 0.0) - self.Gr * np.cos(p)

    def Ac(self, p):
        """Closed-form ∫_0^φ M for any φ."""
        p = np.asarray(p, dtype=float)
        k = np.floor(p / TWO_PI)
        r = p - k * TWO_PI
        load = np.where(r <= math.pi, -self.Pr * (1 - np.cos(r)), -2 * self.Pr)
        return load + k * (-2 * self.Pr) - self.Gr * np.sin(p)

    @property
    def Ac_cycle(self):
        return -2 * self.Pr

    def Asum(self, p):
        return self.Ac(p) + (-self.Ac_cycle / self.length) * (np.asarray(p) - self.start)


class JumpModel(SmoothModel):
    """Constant resistance F r on (φ1, φ2) only (jumps), weight term; cycle starts at 0.3."""

    F_r = 900.0
    p1, p2 = 1.0, 3.5
    breaks = [1.0, 3.5]
    start = 0.3

    def M(self, p):
        r = np.mod(p, TWO_PI)
        return -self.F_r * ((r > self.p1) & (r < self.p2)) - self.Gr * np.cos(p)

    def Ac(self, p):
        """Closed-form ∫_{0.3}^φ M."""
        p = np.asarray(p, dtype=float)

        def load(q):  # ∫_0^q of the step part, q ≥ 0
            k = np.floor(q / TWO_PI)
            r = q - k * TWO_PI
            one = self.F_r * (self.p2 - self.p1)
            return -(k * one + self.F_r * np.clip(r - self.p1, 0.0, self.p2 - self.p1))

        return (load(p) - load(self.start)) - self.Gr * (np.sin(p) - math.sin(self.start))

    @property
    def Ac_cycle(self):
        return -self.F_r * (self.p2 - self.p1)


class ConstJModel(JumpModel):
    """J_II ≡ const with the jump load: extremes of A_Σ sit exactly at the breaks."""

    Jc = 3.0

    def J2(self, p):
        return np.full(np.shape(p), self.Jc)

    def dJ2(self, p):
        return np.zeros(np.shape(p))


def grid_of(m, n=3600):
    return np.linspace(m.start, m.start + m.length, n + 1)


def ode_omega(m, res_exact, Md, phis, rtol=1e-12):
    """Integrate dω/dφ = (M_Σ − ½J_II′ω²)/((J_I + J_II)ω) over one cycle, split at breaks,
    from the exact solution's ω(φ_a); return ω at the sorted points ``phis``."""
    J = res_exact.J_I

    def rhs(p, y):
        w = y[0]
        return [(m.M(p) + Md - 0.5 * m.dJ2(p) * w * w) / ((J + m.J2(p)) * w)]

    edges = [m.start] + [b for b in m.breaks if m.start < b < m.start + m.length] \
        + [m.start + m.length]
    w0 = float(res_exact.omega_at(np.array([m.start]))[0])
    out = np.empty_like(phis)
    sols = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        sol = solve_ivp(rhs, (lo, hi), [w0], method="DOP853", rtol=rtol,
                        atol=1e-14 * w0, dense_output=True)
        assert sol.success
        sel = (phis >= lo) & (phis <= hi)
        out[sel] = sol.sol(phis[sel])[0]
        sols.append((lo, hi, sol.sol))
        w0 = sol.y[0, -1]
    return out, sols, w0


# --------------------------------------------------------------------------------------------
# Quadrature
# --------------------------------------------------------------------------------------------
def test_gauss_panels_jump_needs_break():
    f = lambda x: np.where(x > 1.3, x * x, -2.0)  # noqa: E731
    ref = (27 - 1.3 ** 3) / 3 - 2 * 1.3
    assert gauss_panels(f, 0.0, 3.0, [1.3], n_panels=1, order=16) == pytest.approx(ref, rel=1e-15, abs=1e-14)
    assert abs(gauss_panels(f, 0.0, 3.0, [], n_panels=4, order=16) - ref) > 1e-4
    # reversed limits
    assert gauss_panels(f, 3.0, 0.0, [1.3]) == pytest.approx(-ref, rel=1e-15)


def test_integrate_converges_with_estimate():
    r = integrate(lambda x: np.exp(np.cos(x)), 0.0, TWO_PI, rtol=1e-14)
    ref = TWO_PI * i0(1.0)
    assert r.converged
    assert abs(r.value - ref) <= 1e-14 * ref
    assert r.error <= 1e-14 * r.scale
    # jump integrand with the breaks given: exact; zero-sum integral converges on ∫|f|
    f = lambda x: np.where((x > 1.0) & (x < 2.5), np.sin(x), 0.0) - 0.3  # noqa: E731
    ref2 = math.cos(1.0) - math.cos(2.5) - 0.3 * 4.0
    r2 = integrate(f, 0.0, 4.0, breaks=[2.5, 1.0], rtol=1e-14)
    assert r2.converged and abs(r2.value - ref2) <= 1e-14 * r2.scale
    r3 = integrate(np.sin, 0.0, TWO_PI)
    assert r3.converged and abs(r3.value) < 1e-14


@pytest.mark.parametrize("model", [SmoothModel(), JumpModel()])
def test_cumulative_closed_form(model):
    m = model
    for g in (grid_of(m, 3600), grid_of(m, 97)):
        A = cumulative(m.M, g, m.breaks)
        ref = m.Ac(g)
        assert np.max(np.abs(A - ref)) <= 1e-13 * np.max(np.abs(ref))
    # irregular grid extending over more than a cycle (switching points repeat; the cycle
    # end is a kink of the smooth model's max(sin φ, 0))
    rng = np.random.default_rng(1)
    g = np.sort(np.concatenate(([m.start], m.start + rng.uniform(0, 1.5 * m.length, 400))))
    brs = [b + k * TWO_PI for b in m.breaks for k in (0, 1)] + [m.start + m.length]
    A = cumulative(m.M, g, brs)
    ref = m.Ac(g)
    assert np.max(np.abs(A - ref)) <= 1e-13 * np.max(np.abs(ref))
    # very coarse grid: exact with max_step subdivision
    g = np.linspace(m.start, m.start + m.length, 13)
    A = cumulative(m.M, g, m.breaks, max_step=m.length / 360)
    assert np.max(np.abs(A - m.Ac(g))) <= 1e-13 * np.max(np.abs(m.Ac(g)))


def test_cumulative_single_vectorised_call():
    calls = []

    def f(x):
        calls.append(np.size(x))
        return np.cos(x)

    g = np.linspace(0, 10, 5001)
    A = cumulative(f, g, [3.3])
    assert len(calls) == 1 and calls[0] == 8 * 5001
    assert np.max(np.abs(A - np.sin(g))) < 1e-14


# --------------------------------------------------------------------------------------------
# Works
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("model", [SmoothModel(), JumpModel()])
def test_works(model):
    m = model
    g = grid_of(m)
    w = works(m.M, None, g, m.breaks, (m.start, m.length))
    assert w.A_c_cycle == pytest.approx(m.Ac_cycle, rel=1e-14)
    assert w.M_drive == pytest.approx(-m.Ac_cycle / m.length, rel=1e-14)
    scale = np.max(np.abs(m.Ac(g)))
    assert np.max(np.abs(w.A_c - m.Ac(g))) <= 1e-13 * scale
    assert np.max(np.abs(w.A_sum - m.Asum(g))) <= 1e-13 * scale
    assert abs(w.A_sum[-1]) <= 1e-13 * scale
    np.testing.assert_allclose(w.A_d, w.M_drive * (g - m.start), rtol=1e-14, atol=1e-12)
    # a driving moment that does not balance the cycle is rejected
    with pytest.raises(ValueError):
        works(m.M, 1.01 * w.M_drive, g, m.breaks, (m.start, m.length))
    # a callable driving moment with zero net work together with M
    Md0 = -m.Ac_cycle / m.length
    w2 = works(m.M, lambda p: Md0 * (1 + 0.5 * np.cos(p)), g, m.breaks, (m.start, m.length))
    ref_d = Md0 * ((g - m.start) + 0.5 * (np.sin(g) - math.sin(m.start)))
    assert np.max(np.abs(w2.A_d - ref_d)) <= 1e-13 * scale


def test_works_four_stroke_cycle():
    """Φ = 4π: resistance on one revolution out of two."""
    M = lambda p: -500.0 * np.where(np.mod(p, 4 * math.pi) < TWO_PI, np.sin(p) ** 2, 0.0)  # noqa: E731
    g = np.linspace(0, 4 * math.pi, 1441)
    w = works(M, None, g, [TWO_PI], (0.0, 4 * math.pi))
    assert w.A_c_cycle == pytest.approx(-500 * math.pi, rel=1e-14)
    assert w.M_drive == pytest.approx(500 * math.pi / (4 * math.pi), rel=1e-14)
    ref = np.where(g < TWO_PI, -500 * (g / 2 - np.sin(2 * g) / 4), -500 * math.pi)
    assert np.max(np.abs(w.A_c - ref)) < 1e-13 * 500 * math.pi


# --------------------------------------------------------------------------------------------
# Exact motion
# --------------------------------------------------------------------------------------------
CASES = [(SmoothModel(), 30.0, 0.05), (SmoothModel(), 7.0, 0.01), (JumpModel(), 20.0, 0.2),
         (SmoothModel(), 12.0, 0.12)]


@pytest.mark.parametrize("m, wm, d", CASES)
def test_exact_motion_against_ode(m, wm, d):
    g = grid_of(m)
    model = prepare_model(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, g)
    ex = exact(model, wm, d)
    assert abs(ex.delta_achieved - d) <= 1e-12
    assert abs(ex.omega_mean_achieved - wm) <= 1e-12 * wm
    Md = -m.Ac_cycle / m.length
    w_ode, sols, w_end = ode_omega(m, ex, Md, g)
    # ODE from the exact initial state reproduces ω(φ) and is periodic
    assert np.max(np.abs(w_ode - ex.omega)) <= 1e-9 * wm
    assert abs(w_end - ex.omega[0]) <= 1e-9 * wm
    # independent δ and ω_ср from the ODE solution: refine sampled extremes
    best = {}
    for lo, hi, sol in sols:
        x = np.linspace(lo, hi, 4001)
        y = sol(x)[0]
        for kind, j in (("max", int(np.argmax(y))), ("min", int(np.argmin(y)))):
            a, b = x[max(j - 1, 0)], x[min(j + 1, x.size - 1)]
            sgn = -1 if kind == "max" else 1
            r = minimize_scalar(lambda t: sgn * sol(t)[0], bounds=(a, b), method="bounded",
                                options={"xatol": 1e-12})
            val = max(sol(r.x)[0], y[j]) if kind == "max" else min(sol(r.x)[0], y[j])
            if kind not in best or (val > best[kind] if kind == "max" else val < best[kind]):
                best[kind] = val
    assert abs((best["max"] - best["min"]) / wm - d) <= 1e-9
    assert abs(0.5 * (best["max"] + best["min"]) - wm) <= 1e-9 * wm
    assert best["max"] == pytest.approx(ex.omega_max, rel=1e-9)
    assert best["min"] == pytest.approx(ex.omega_min, rel=1e-9)


def test_exact_equation_of_motion_residual():
    """J ε + ½J′ω² = M_Σ with ε = ω dω/dφ from 6th-order differences of the exact ω(φ)."""
    m = SmoothModel()
    wm, d = 30.0, 0.05
    g = grid_of(m)
    r = solve_dynamics(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, 0.5, wm, d, g)
    w = r.exact.omega
    h = g[1] - g[0]
    c = np.array([-1, 9, -45, 0, 45, -9, 1]) / (60 * h)
    dw = np.convolve(w, c[::-1], mode="valid")  # points 3 .. n-4
    p = g[3:-3]
    keep = np.abs(p - math.pi) > 4 * h
    Ms = m.M(p) + r.works.M_drive
    J = r.J_I_exact + m.J2(p)
    eps_fd = w[3:-3] * dw
    res = J * eps_fd + 0.5 * m.dJ2(p) * w[3:-3] ** 2 - Ms
    assert np.max(np.abs(res[keep])) <= 1e-8 * np.max(np.abs(Ms))
    assert np.max(np.abs(eps_fd - r.exact.eps[3:-3])[keep]) <= 1e-8 * np.max(np.abs(r.exact.eps))


def test_exact_time_domain_cycle():
    """Time-domain integration of J φ̈ + ½J′φ̇² = M_Σ over one revolution."""
    m = SmoothModel()
    wm, d = 15.0, 0.08
    model = prepare_model(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, 720)
    ex = exact(model, wm, d)
    Md = -m.Ac_cycle / m.length

    def rhs(t, y):
        p, w = y
        return [w, (m.M(p) + Md - 0.5 * m.dJ2(p) * w * w) / (ex.J_I + m.J2(p))]

    def done(t, y):
        return y[0] - TWO_PI
    done.terminal = True
    w0 = float(ex.omega_at(np.array([0.0]))[0])
    sol = solve_ivp(rhs, (0, 10), [0.0, w0], method="DOP853", rtol=1e-12, atol=1e-13,
                    events=done, dense_output=True)
    assert sol.status == 1
    T = sol.t_events[0][0]
    t = np.linspace(0, T, 200)
    p, w = sol.sol(t)
    assert np.max(np.abs(w - ex.omega_at(p))) <= 1e-9 * wm
    assert abs(sol.y_events[0][0][1] - w0) <= 1e-9 * wm


@pytest.mark.parametrize("m", [SmoothModel(), JumpModel()])
def test_energy_balance_arbitrary_positions(m):
    wm, d = 25.0, 0.03
    r = solve_dynamics(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, 0.5, wm, d, 1000)
    rng = np.random.default_rng(7)
    p1 = rng.uniform(m.start - 3, m.start + m.length + 3, 50)
    p2 = rng.uniform(m.start, m.start + 2 * m.length, 50)
    T = lambda p: 0.5 * (r.J_I + m.J2(p)) * r.omega_at(p) ** 2  # noqa: E731
    work = m.Asum(p2) - m.Asum(p1)
    assert np.max(np.abs(T(p2) - T(p1) - work)) <= 1e-9 * np.max(np.abs(m.Asum(grid_of(m))))
    # ε at arbitrary φ agrees with the grid values and the equation of motion
    np.testing.assert_allclose(r.omega_at(r.phi), r.omega, rtol=1e-13)
    np.testing.assert_allclose(r.eps_at(r.phi[1:-1]), r.eps[1:-1], rtol=1e-11,
                               atol=1e-11 * np.max(np.abs(r.eps)))


def test_exact_nested_agrees_with_newton():
    m = JumpModel()
    model = prepare_model(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, 1200)
    a = exact(model, 20.0, 0.1, algorithm="newton")
    b = exact(model, 20.0, 0.1, algorithm="nested")
    assert b.algorithm == "nested"
    assert abs(b.delta_achieved - 0.1) <= 1e-12
    assert b.J_I == pytest.approx(a.J_I, rel=1e-11)
    assert b.T0 == pytest.approx(a.T0, rel=1e-11)


def test_exact_grid_independent():
    """J_I does not depend on the grid (extremes are refined, not read off the grid)."""
    m = SmoothModel()
    J = []
    for n in (90, 360, 3600, 7777):
        model = prepare_model(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, n)
        J.append(exact(model, 30.0, 0.05).J_I)
    assert np.ptp(J) <= 1e-12 * J[0]


# --------------------------------------------------------------------------------------------
# Виттенбауэр and Мерцалов
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("m, wm, d", CASES)
def test_wittenbauer_exact_slopes_is_exact(m, wm, d):
    model = prepare_model(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, grid_of(m, 720))
    ex = exact(model, wm, d, algorithm="nested")
    wi = wittenbauer(model, wm, d)
    assert wi.J_I == pytest.approx(ex.J_I, rel=1e-9)
    assert wi.T0 == pytest.approx(ex.T0, rel=1e-9)
    assert abs(wi.delta_achieved - d) <= 1e-10
    # KL/(ω²δ) and the tangency geometry
    assert wi.J_I == pytest.approx(wi.KL / (wm ** 2 * d), rel=1e-13)
    assert wi.slope_max == pytest.approx(0.5 * (wm * (1 + d / 2)) ** 2, rel=1e-15)
    for tp, s, c in ((wi.tangent_max, wi.slope_max, wi.K), (wi.tangent_min, wi.slope_min, wi.L)):
        assert tp.J == pytest.approx(m.J2(tp.phi), rel=1e-14)
        assert tp.dT == pytest.approx(m.Asum(tp.phi), abs=1e-11 * abs(m.Ac_cycle))
        assert tp.dT - s * tp.J == pytest.approx(c, abs=1e-11 * abs(m.Ac_cycle))
    # the curve lies between the two tangents (sampled densely, closed form)
    p = np.linspace(m.start, m.start + m.length, 200001)
    A, J = m.Asum(p), m.J2(p)
    tol = 1e-11 * abs(m.Ac_cycle)
    assert np.all(A <= wi.K + wi.slope_max * J + tol)
    assert np.all(A >= wi.L + wi.slope_min * J - tol)
    # tangents meet at (−J_I, −T0)
    assert wi.upper_tangent(-wi.J_I) == pytest.approx(-wi.T0, rel=1e-12)
    assert wi.lower_tangent(-wi.J_I) == pytest.approx(-wi.T0, rel=1e-12)
    # linearised slopes: an error of order δ², not zero
    rel = abs(wi.J_I_linear / ex.J_I - 1)
    assert 0 < rel < 2 * d ** 2


MERTSALOV_CASES = [(SmoothModel(), 30.0, 0.05), (SmoothModel(), 7.0, 0.01),
                   (SmoothModel(), 12.0, 0.12), (JumpModel(), 10.0, 0.2),
                   (JumpModel(), 30.0, 0.05), (JumpModel(), 20.0, 0.1)]


@pytest.mark.parametrize("m, wm, d", MERTSALOV_CASES)
def test_mertsalov_deviation_follows_theory(m, wm, d):
    """Theory of the error of Мерцалов's method.

    Exact motion: ω² = ω_ср²(1 + y), y = 2(ΔT_I + C)/(ω_ср²(J_I + J_II)) with
    ΔT_I = A_Σ − J_II ω_ср²/2; at the extremes y = ±δ + δ²/4.  Subtracting the two gives the
    identity J_Мерц − J_exact = [J_II(φ₁)(1 + δ/4) + J_II(φ₂)(1 − δ/4)]/2
    + (R − (ΔT_I(φ₁) − ΔT_I(φ₂)))/(ω_ср² δ), φ₁,₂ = positions of ω_max, ω_min, R = range ΔT_I.
    To first order (positions unchanged): J_Мерц − J_exact ≈ ½(J_II(φ_ΔTmax) + J_II(φ_ΔTmin))
    > 0, i.e. a relative over-size ≈ δ·J_II ω_ср²/R: Мерцалов neglects the kinetic-energy
    change of the linkage J_II ω_ср Δω.
    """
    model = prepare_model(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, grid_of(m))
    ex = exact(model, wm, d)
    me = mertsalov(model, wm, d)
    diff = me.J_I - ex.J_I
    assert diff > 0
    assert me.delta_achieved < d  # over-sized flywheel
    # the exact identity (any case, also when an extreme jumps to another position)
    dT = lambda p: m.Asum(p) - 0.5 * wm ** 2 * m.J2(p)  # noqa: E731
    p1, p2 = ex.phi_omega_max, ex.phi_omega_min
    R = me.dT_I_max - me.dT_I_min
    ident = (m.J2(p1) * (1 + d / 4) + m.J2(p2) * (1 - d / 4)) / 2 \
        + (R - (dT(p1) - dT(p2))) / (wm ** 2 * d)
    assert diff == pytest.approx(ident, rel=1e-8)
    # first-order prediction, where the extremes of ΔT_I and ω are the same stationary points
    if abs(me.phi_dT_min - p2) < 0.1 and abs(me.phi_dT_max - p1) < 0.1:
        pred = 0.5 * (m.J2(me.phi_dT_max) + m.J2(me.phi_dT_min))
        assert diff == pytest.approx(pred, rel=0.1 * d + 0.005)
    else:
        assert (m, wm, d) == MERTSALOV_CASES[-1]  # the case built to switch extremes
    # worksheet formulas on the grid, recomputed from the closed forms
    g = me.phi
    dT = m.Asum(g) - 0.5 * wm ** 2 * m.J2(g)
    scale = np.max(np.abs(dT))
    assert np.max(np.abs(me.dT_I - dT)) <= 1e-12 * scale
    mid = 0.5 * (me.dT_I_max + me.dT_I_min)
    np.testing.assert_allclose(me.omega, wm + (dT - mid) / (wm * me.J_I), rtol=1e-12)
    assert me.omega_max == pytest.approx(wm * (1 + d / 2), rel=1e-14)
    assert me.omega_min == pytest.approx(wm * (1 - d / 2), rel=1e-14)
    Jt = me.J_I + m.J2(g)
    Ms = m.M(g) - m.Ac_cycle / m.length
    np.testing.assert_allclose(me.eps, Ms / Jt - me.omega ** 2 * m.dJ2(g) / (2 * Jt),
                               rtol=1e-12, atol=1e-12 * np.max(np.abs(me.eps)))
    # extremes of ΔT_I against brute force (dense sampling + bounded refinement)
    p = np.linspace(m.start, m.start + m.length, 400001)
    f = m.Asum(p) - 0.5 * wm ** 2 * m.J2(p)
    for j, sgn, ref_val in ((int(np.argmax(f)), -1.0, me.dT_I_max),
                            (int(np.argmin(f)), 1.0, me.dT_I_min)):
        lo, hi = p[max(j - 1, 0)], p[min(j + 1, p.size - 1)]
        r = minimize_scalar(lambda t: sgn * (m.Asum(t) - 0.5 * wm ** 2 * m.J2(t)),
                            bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
        at_breaks = sgn * (m.Asum(np.array(m.breaks)) - 0.5 * wm ** 2 * m.J2(np.array(m.breaks)))
        brute = sgn * min(r.fun, sgn * f[j], at_breaks.min())  # refined, sampled, kinks
        assert ref_val == pytest.approx(brute, abs=1e-10 * scale)
        assert sgn * ref_val <= sgn * brute + 1e-12 * scale  # never worse than brute force


def test_mertsalov_constant_J2_and_extremes_at_breaks():
    """J_II ≡ const: Мерцалов gives exactly the total inertia, J_Мерц = J_exact + J_II, and
    the extremes of ΔT_I and of ω sit exactly at the switching points of the load."""
    m = ConstJModel()
    wm, d = 10.0, 0.1
    model = prepare_model(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, 1000)
    ex = exact(model, wm, d)
    me = mertsalov(model, wm, d)
    assert me.J_I == pytest.approx(ex.J_I + m.Jc, rel=1e-13)
    # exact closed form for constant J: (J_I + J_II) = range(A_Σ)/(ω_ср² δ)
    # M_Σ = Md − F r (on (p1, p2)) − G r cos φ; with Gr small, extremes at the jumps
    assert abs(me.phi_dT_max - m.p1) <= 1e-12
    assert abs(me.phi_dT_min - m.p2) <= 1e-12
    assert abs(ex.phi_omega_max - m.p1) <= 1e-12
    assert abs(ex.phi_omega_min - m.p2) <= 1e-12
    rngA = m.Asum(m.p1) - m.Asum(m.p2)
    assert ex.J_I + m.Jc == pytest.approx(rngA / (wm ** 2 * d), rel=1e-13)
    wi = wittenbauer(model, wm, d)
    assert wi.J_I == pytest.approx(ex.J_I, rel=1e-13)


def test_extremum_at_cycle_end():
    """A ΔT_I extremum exactly at the cycle start (a jump of M there) is found."""
    m = ConstJModel()
    m.start = m.p1  # the cycle now starts at the switching point
    model = prepare_model(m.J2, m.dJ2, m.M, [m.p2], m.start, m.length, 500)
    me = mertsalov(model, 10.0, 0.1)
    assert abs(me.phi_dT_max - m.p1) <= 1e-12
    assert me.dT_I_max == pytest.approx(-0.5 * 100 * m.Jc, abs=1e-9)


# --------------------------------------------------------------------------------------------
# solve_dynamics
# --------------------------------------------------------------------------------------------
def test_solve_dynamics_methods_consistent():
    m = JumpModel()
    g = grid_of(m, 720)
    out = {}
    for method in ("exact", "mertsalov", "wittenbauer"):
        r = solve_dynamics(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, 2.5, 20.0, 0.1, g,
                           method=method)
        out[method] = r
        assert r.method == method
        assert r.J_flywheel == pytest.approx(r.J_I - 2.5, rel=1e-15)
        np.testing.assert_allclose(r.omega_at(g), r.omega, rtol=1e-12)
        assert r.flywheel.needed and r.flywheel.omega_max == r.omega_max
    e, me, wi = out["exact"], out["mertsalov"], out["wittenbauer"]
    assert e.J_I == e.J_I_exact and me.J_I == me.J_I_mertsalov and wi.J_I == wi.J_I_wittenbauer
    assert me.dev_mertsalov_pct == pytest.approx(100 * (me.J_I_mertsalov / e.J_I - 1), rel=1e-9)
    assert me.dev_mertsalov_pct > 0
    assert abs(wi.dev_wittenbauer_pct) < 1e-7
    assert abs(e.delta_achieved - 0.1) < 1e-12 and me.delta_achieved < 0.1
    np.testing.assert_allclose(wi.omega, e.omega, rtol=1e-9)
    assert e.omega_max == pytest.approx(20.0 * 1.05, rel=1e-13)
    assert e.omega_min == pytest.approx(20.0 * 0.95, rel=1e-13)
    # a balanced constant Mdrive given explicitly gives the same result
    r2 = solve_dynamics(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, 2.5, 20.0, 0.1, g,
                        Mdrive=-m.Ac_cycle / m.length)
    assert r2.J_I == pytest.approx(e.J_I, rel=1e-12)
    with pytest.raises(ValueError):
        solve_dynamics(m.J2, m.dJ2, m.M, m.breaks, m.start, m.length, 2.5, 20.0, 0.1, g,
                       method="guess")


def test_four_stroke_exact_and_wittenbauer():
    """Φ = 4π: the periodic solution over two revolutions; ODE check in φ."""
    class FourStroke(SmoothModel):
        length = 4 * math.pi
        breaks = [TWO_PI]

        def M(self, p):
            return -500.0 * np.where(np.mod(p, 4 * math.pi) < TWO_PI, np.sin(p) ** 2, 0.0)

        @property
        def Ac_cycle(self):
            return -500 * math.pi

    m = FourStroke()
    r = solve_dynamics(m.J2, m.dJ2, m.M, m.breaks, 0.0, m.length, 0.0, 10.0, 0.04, 1440)
    assert abs(r.exact.delta_achieved - 0.04) < 1e-12
    assert r.J_I_wittenbauer == pytest.approx(r.J_I_exact, rel=1e-9)
    g = r.phi
    w_ode, _, w_end = ode_omega(m, r.exact, -m.Ac_cycle / m.length, g)
    assert np.max(np.abs(w_ode - r.omega)) <= 1e-9 * 10.0


# --------------------------------------------------------------------------------------------
# Flywheel dimensions (worksheet 000)
# --------------------------------------------------------------------------------------------
def test_flywheel_dims_worksheet_000():
    fw = flywheel_dims(1.459e3, omega_max=6.807 * 1.055)
    # printed: D2 = 1.876, D1 = 1.501, b = 0.375, m = 2.912e3; D = 1.571, b = 0.314, m = 4.773e3
    assert abs(fw.rim.D2 - 1.876) <= 1e-3
    assert abs(fw.rim.D1 - 1.501) <= 1e-3
    assert abs(fw.rim.b - 0.375) <= 1e-3
    assert abs(fw.rim.m - 2.912e3) <= 1.0
    assert abs(fw.disk.D - 1.571) <= 1e-3
    assert abs(fw.disk.b - 0.314) <= 1e-3
    assert abs(fw.disk.m - 4.773e3) <= 1.0
    # physically derived disk and ring reproduce the required inertia
    dp = fw.disk_physical
    assert dp.b == pytest.approx(0.2 * dp.D, rel=1e-15)
    assert math.pi * 7800 * dp.b * dp.D ** 4 / 32 == pytest.approx(1.459e3, rel=1e-13)
    assert dp.m * dp.D ** 2 / 8 == pytest.approx(1.459e3, rel=1e-13)
    rp = fw.rim_physical
    assert math.pi * 7800 * rp.b * (rp.D2 ** 4 - rp.D1 ** 4) / 32 == pytest.approx(1.459e3, rel=1e-13)
    # rim speed: slow press OK, fast machine flagged
    assert fw.rim.v_rim == pytest.approx(6.807 * 1.055 * fw.rim.D2 / 2, rel=1e-15)
    assert not fw.any_exceeds
    fast = flywheel_dims(1.459e3, omega_max=40.0)
    assert fast.rim.v_exceeds and fast.any_exceeds
    assert not flywheel_dims(1.459e3, omega_max=40.0, v_limit=60.0).rim.v_exceeds
    none = flywheel_dims(-1.0, 10.0)
    assert not none.needed and none.rim.m == 0.0
