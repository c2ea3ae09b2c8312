"""Work–precision of the dynamics: flywheel methods against the periodic solution of the equation
of motion, and the cycle integrals against the quadrature order.

Usage: ``.venv/bin/python bench/dynamics_precision.py`` (also run by ``bench/work_precision.py``);
writes ``output/bench/dynamics_precision.csv`` and ``output/bench/cycle_integrals.csv``.

Reference (independent of the engine's energy integral, its quadrature and its root finding):
the equation of motion in differential form (Лагранж; Артоболевский, «Динамика машин»)

    dω/dφ = (M_Σ(φ) − ½ J_II′(φ) ω²) / ((J_I + J_II(φ)) ω),

integrated by the classical Runge–Kutta method of order 4 on a uniform grid of every interval
between the switching points of the loads (the right-hand side is smooth inside), n = 40 000 steps
per cycle, and again with 2n steps: the difference estimates the reference's own error (printed
in the CSV: J_I and ω on the common nodes).  M_Σ, J_II and J_II′ are the engine's reduced model (``study.dynamics.model``; what is
checked is the flywheel step, not the reduction).  Extremes of ω are located on each step by the
cubic Hermite interpolant of ω and ω′ (error O(h⁴)).  Periodic shooting: (J_I, ω(φ_a)) solve
(ω_max − ω_min)/ω_ср = δ and (ω_max + ω_min)/2 = ω_ср by Newton's method with a finite-difference
Jacobian (three trajectories integrated together); the periodicity ω(φ_a + Φ) = ω(φ_a) holds
because the cycle work is zero, its residual is reported.

Compared: J_I, ω(φ) and ε(φ) of Мерцалов's method (as worksheet 000), of Виттенбауэр's
(exact slopes ω_ср²(1 ± δ/2)²/2 and the textbook ω_ср²(1 ± δ)/2) and of the engine's exact solution
(energy integral), for δ = 0,01…0,2 on the reference cases.

Cycle integrals: the work of the resistances over the cycle A_c and ΔT(φ) = A_Σ(φ) on 36 positions,
computed by the engine's composite Gauss–Legendre rule (``DynamicModel(order=…, min_nodes=…)``,
panels split at the switches) for orders 1…12 and 36 or 720 panels, against
``scipy.integrate.quad`` (adaptive Gauss–Kronrod, epsrel 1e-14) on every piece between positions
and switches.
"""
from __future__ import annotations

import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

CASES = [("лист 000 (исправленный)", "cases/ws000_six_bar_corrected.toml"),
         ("кривошипный пресс", "cases/crank_press.toml"),
         ("четырёхтактный двигатель (цикл 4π)", "cases/engine_four_stroke.toml")]
DELTAS = (0.01, 0.02, 0.05, 0.1, 0.2)
STEPS = 40_000
ORDERS = (1, 2, 3, 4, 6, 8, 12)
PANELS = (36, 720)


def cpu(fn, runs: int = 3):
    """Median CPU time of ``runs`` calls and the last result."""
    ts, out = [], None
    for _ in range(runs):
        t0 = time.process_time()
        out = fn()
        ts.append(time.process_time() - t0)
    return statistics.median(ts), out


# --------------------------------------------------------------------------- the reference ODE
def _rk4_kernel():
    from numba import njit

    @njit(cache=True)
    def rk4(h, S, Mid, E, JI, w0):
        """Classical RK4 of ω′ = (M − ½J′ω²)/((J_I + J)ω) for every (J_I[k], ω0[k]).  S, Mid, E:
        (3, n) values of (M_Σ, J_II, J_II′) at the start (right limit), middle and end (left limit)
        of each step.  Returns ω at the n + 1 nodes and ω′ at the start and end of each step."""
        n = h.size
        K = JI.size
        w = np.empty((n + 1, K))
        d0 = np.empty((n, K))
        d1 = np.empty((n, K))
        for k in range(K):
            x = w0[k]
            J = JI[k]
            for i in range(n):
                f1 = (S[0, i] - 0.5 * S[2, i] * x * x) / ((J + S[1, i]) * x)
                y = x + 0.5 * h[i] * f1
                f2 = (Mid[0, i] - 0.5 * Mid[2, i] * y * y) / ((J + Mid[1, i]) * y)
                y = x + 0.5 * h[i] * f2
                f3 = (Mid[0, i] - 0.5 * Mid[2, i] * y * y) / ((J + Mid[1, i]) * y)
                y = x + h[i] * f3
                f4 = (E[0, i] - 0.5 * E[2, i] * y * y) / ((J + E[1, i]) * y)
                w[i, k] = x
                d0[i, k] = f1
                x = x + h[i] / 6 * (f1 + 2 * f2 + 2 * f3 + f4)
                d1[i, k] = (E[0, i] - 0.5 * E[2, i] * x * x) / ((J + E[1, i]) * x)
            w[n, k] = x
        return w, d0, d1

    return rk4


class MotionODE:
    """The equation of motion on a fixed RK4 grid split at the switching points of the loads; the
    stage values at a step's ends are the one-sided limits from inside the step."""

    def __init__(self, model, steps: int, refine: int = 1):
        """``steps`` per cycle (each interval between switches gets its share, at least 2);
        ``refine`` multiplies the steps of every interval (refine = 2: the nodes of refine = 1
        are the even nodes, for the Runge estimate)."""
        self.model = model
        a, L = model.a, model.L
        self.cuts = np.concatenate(([a], model.breaks, [a + L]))
        lo, hi = [], []
        for x0, x1 in zip(self.cuts[:-1], self.cuts[1:]):
            k = refine * max(2, int(math.ceil(steps * (x1 - x0) / L)))
            t = np.linspace(x0, x1, k + 1)
            lo.append(t[:-1])
            hi.append(t[1:])
        lo, hi = np.concatenate(lo), np.concatenate(hi)
        self.phi = np.append(lo, a + L)
        self.h = hi - lo
        # one-sided limits: 1e-7 of a step inside (one ulp is not enough: a load switched by a
        # kinematic condition, e.g. a table with a vertical jump of s(φ), may flip within the
        # rounding of s); the stage value then errs by 1e-7·h·M′, far below the RK4 error
        eta = 1e-7 * (hi - lo)
        xs = np.concatenate((lo + eta, 0.5 * (lo + hi), hi - eta))
        vals = np.array([model.M_sum(xs), model.J2(xs), model.dJ2(xs)])
        n = lo.size
        self.S, self.Mid, self.E = (np.ascontiguousarray(vals[:, i * n:(i + 1) * n]) for i in range(3))
        self._rk4 = _rk4_kernel()

    def run(self, JI, w0):
        JI, w0 = np.atleast_1d(np.asarray(JI, float)), np.atleast_1d(np.asarray(w0, float))
        return self._rk4(self.h, self.S, self.Mid, self.E, JI, w0)

    def extremes(self, w, d0, d1) -> tuple[np.ndarray, np.ndarray]:
        """max and min of ω for each trajectory: node values and the extremum of the cubic Hermite
        interpolant (ω, ω′ at both ends) on every step where ω′ changes sign."""
        wmax, wmin = w.max(axis=0), w.min(axis=0)
        h = self.h[:, None]
        i, k = np.nonzero(d0 * d1 < 0)
        if i.size:
            w0, w1, a0, a1 = w[i, k], w[i + 1, k], d0[i, k] * h[i, 0], d1[i, k] * h[i, 0]
            # p(t) = h00 w0 + h10 a0 + h01 w1 + h11 a1; p'(t) = A t² + B t + C
            A = 6 * w0 + 3 * a0 - 6 * w1 + 3 * a1
            B = -6 * w0 - 4 * a0 + 6 * w1 - 2 * a1
            C = a0
            disc = np.sqrt(np.maximum(B * B - 4 * A * C, 0.0))
            for sgn in (1.0, -1.0):
                with np.errstate(divide="ignore", invalid="ignore"):
                    t = np.where(np.abs(A) > 1e-300, (-B + sgn * disc) / (2 * A), -C / B)
                ok = (t >= 0) & (t <= 1)
                t = np.where(ok, t, 0.0)
                p = ((2 * t ** 3 - 3 * t ** 2 + 1) * w0 + (t ** 3 - 2 * t ** 2 + t) * a0
                     + (-2 * t ** 3 + 3 * t ** 2) * w1 + (t ** 3 - t ** 2) * a1)
                p = np.where(ok, p, w0)
                np.maximum.at(wmax, k, p)
                np.minimum.at(wmin, k, p)
        return wmax, wmin


class PeriodicSolution:
    """J_I and ω(φ_a) of the periodic motion with the given ω_ср and δ (shooting, see the module
    docstring); ``omega``/``domega`` at the nodes of the ODE grid."""

    def __init__(self, ode: MotionODE, omega_m: float, delta: float, J_start: float):
        J, w0 = float(J_start), float(omega_m)
        eta = 1e-7
        for _ in range(40):
            w, d0, d1 = ode.run([J, J * (1 + eta), J], [w0, w0, w0 * (1 + eta)])
            mx, mn = ode.extremes(w, d0, d1)
            F = np.array([(mx - mn) / omega_m - delta, 0.5 * (mx + mn) - omega_m])   # (2, 3)
            r = F[:, 0]
            if abs(r[0]) <= 1e-15 and abs(r[1]) <= 1e-15 * omega_m:
                break
            Jm = np.column_stack(((F[:, 1] - r) / (J * eta), (F[:, 2] - r) / (w0 * eta)))
            dJ, dw = np.linalg.solve(Jm, -r)
            J, w0 = J + dJ, w0 + dw
            if abs(dJ) <= 1e-15 * abs(J) and abs(dw) <= 1e-15 * w0:
                break
        w, d0, _ = ode.run([J], [w0])
        self.J_I, self.w0 = J, w0
        self.phi = ode.phi
        self.omega = w[:, 0]
        self.eps = np.append(w[:-1, 0] * d0[:, 0], np.nan)       # ε = ω dω/dφ (right limits)
        self.periodicity = abs(w[-1, 0] - w0) / omega_m


def dynamics_rows(quick: bool = False) -> list[dict]:
    from reportgen.analysis.flywheel import exact, mertsalov, wittenbauer
    from reportgen.analysis.study import Study
    rows = []
    for title, path in CASES:
        s = Study(ROOT / path)
        dyn = s.analysis("dynamics")
        model = dyn.result.model
        wm = dyn.settings.omega_m
        t0 = time.process_time()
        ode = MotionODE(model, STEPS)
        ode2 = MotionODE(model, STEPS, refine=2)
        print(f"{title}: ODE grids in {time.process_time() - t0:.1f} s CPU", flush=True)
        # comparison points: every 10th node, not at a switching point (ε jumps there)
        sel = np.arange(0, ode.phi.size - 1, 10)
        sel = sel[~np.isin(ode.phi[sel], ode.cuts)]
        phi = ode.phi[sel]
        for delta in (DELTAS[::2] if quick else DELTAS):
            t_me, me = cpu(lambda: mertsalov(model, wm, delta, with_delta_achieved=False))
            t_wi, wi = cpu(lambda: wittenbauer(model, wm, delta, with_delta_achieved=False))
            t_ex, ex = cpu(lambda: exact(model, wm, delta))
            t_ref, ref = cpu(lambda: PeriodicSolution(ode, wm, delta, me.J_I), runs=1)
            ref2 = PeriodicSolution(ode2, wm, delta, ref.J_I)
            # ε of the reference motion from the equation of motion at the exact φ (the RK4 stage
            # values sit 1e-7 of a step inside the step and would add ≈ 1e-11 of their own)
            w_ref = ref.omega[sel]
            e_ref = (model.M_sum(phi) - 0.5 * model.dJ2(phi) * w_ref ** 2) / (ref.J_I + model.J2(phi))
            e_scale = float(np.max(np.abs(e_ref)))
            common = dict(case=title, delta=delta, J_I_ref=ref.J_I,
                          ref_runge=abs(ref2.J_I - ref.J_I) / ref.J_I,
                          ref_periodicity=ref.periodicity)
            for name, r, t in (("Мерцалов", me, t_me), ("Виттенбауэр", wi, t_wi),
                               ("точное (энергетический интеграл)", ex, t_ex)):
                rows.append(dict(common, method=name, J_I=r.J_I, err_J_I=abs(r.J_I - ref.J_I) / ref.J_I,
                                 err_omega=float(np.max(np.abs(r.omega_at(phi) - w_ref))) / wm,
                                 err_eps=float(np.max(np.abs(r.eps_at(phi) - e_ref))) / e_scale,
                                 time_ms=t * 1e3))
            rows.append(dict(common, method="Виттенбауэр, наклоны ω_ср²(1 ± δ)/2", J_I=wi.J_I_linear,
                             err_J_I=abs(wi.J_I_linear - ref.J_I) / ref.J_I, err_omega=math.nan,
                             err_eps=math.nan, time_ms=t_wi * 1e3))
            rows.append(dict(common, method="эталон: ОДУ, РК4 + пристрелка", J_I=ref.J_I, err_J_I=0.0,
                             err_omega=float(np.max(np.abs(ref2.omega[::2][sel] - w_ref))) / wm,
                             err_eps=math.nan, time_ms=t_ref * 1e3))
            print(f"  δ = {delta}: J_I ref {ref.J_I:.10g} (Runge {common['ref_runge']:.1e}); "
                  + "; ".join(f"{r['method']} {r['err_J_I']:.1e}/{r['err_omega']:.1e}/{r['err_eps']:.1e}"
                              for r in rows[-5:-2]), flush=True)
    return rows


# --------------------------------------------------------------------------- cycle integrals
def _quad_reference(model, grid) -> tuple[float, np.ndarray]:
    """A_c over the cycle and A_Σ at the grid points by scipy's adaptive quadrature on every piece
    between grid points and switches."""
    import warnings
    from scipy.integrate import IntegrationWarning, quad
    warnings.simplefilter("ignore", IntegrationWarning)   # a kink of a load table inside a piece
    a, L = model.a, model.L
    pts = np.unique(np.concatenate((grid, model.breaks)))

    def Mc(x):
        return float(model._call(model._M, np.array([x]))[0])

    pieces = [quad(Mc, x0, x1, epsabs=0.0, epsrel=2e-14, limit=200)[0] for x0, x1 in zip(pts[:-1], pts[1:])]
    cum = np.concatenate(([0.0], np.cumsum(pieces)))
    Ac_total = float(cum[-1])
    Ac = np.interp(grid, pts, cum)          # grid points are among pts: exact lookup
    if model.Md_const is not None:
        Ad = -Ac_total / L * (grid - a) if model._Mdrive is None else model.Md_const * (grid - a)
    else:
        def Md(x):
            return float(model._call(model._Mdrive, np.array([x]))[0])
        dp = [quad(Md, x0, x1, epsabs=0.0, epsrel=2e-14, limit=200)[0] for x0, x1 in zip(pts[:-1], pts[1:])]
        Ad = np.interp(grid, pts, np.concatenate(([0.0], np.cumsum(dp))))
    return Ac_total, Ac + Ad


def integral_rows() -> list[dict]:
    from reportgen.analysis.flywheel import DynamicModel
    from reportgen.analysis.study import Study
    rows = []
    for title, path in CASES:
        s = Study(ROOT / path)
        dyn = s.analysis("dynamics")
        m0 = dyn.result.model
        grid = m0.a + m0.L * np.arange(37) / 36
        t0 = time.process_time()
        Ac_ref, A_ref = _quad_reference(m0, grid)
        t_ref = time.process_time() - t0
        scale = float(np.ptp(A_ref))
        print(f"{title}: quad reference A_c = {Ac_ref:.15g} J in {t_ref:.1f} s CPU", flush=True)
        for panels in PANELS:
            for order in ORDERS:
                def build():
                    return DynamicModel(None, None, m0._M, m0.breaks, m0.a, m0.L, grid, m0._Mdrive,
                                        min_nodes=panels, order=order, balance_rtol=1.0)
                t, m = cpu(build)
                rows.append(dict(case=title, panels=panels, order=order, evaluations=order * (m.nodes.size - 1),
                                 err_work=abs(m.Ac_total - Ac_ref) / abs(Ac_ref),
                                 err_dT=float(np.max(np.abs(m.A_g - A_ref))) / scale, time_ms=t * 1e3))
            print("  панелей ≥ {}: ".format(panels) + ", ".join(
                f"n={r['order']} {r['err_work']:.1e}/{r['err_dT']:.1e}" for r in rows[-len(ORDERS):]), flush=True)
    return rows


def main(argv=None) -> None:
    import argparse
    sys.path.insert(0, str(ROOT / "bench"))
    from work_precision import OUT, write_csv  # noqa: E402  (bench/ on the path)
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args(argv)
    OUT.mkdir(parents=True, exist_ok=True)
    write_csv(OUT / "dynamics_precision.csv", dynamics_rows(args.quick))
    write_csv(OUT / "cycle_integrals.csv", integral_rows())
    print(f"written: {OUT}")


if __name__ == "__main__":
    main()
