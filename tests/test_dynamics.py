"""Dynamics of worksheet 000: every printed number, and independent checks of the exact motion.

Independent references: the high-precision kinematics of tests/reference.py (mpmath, a different
formulation) for J_II and J_II′; scipy ``quad`` of the reduced moments for the works; a DOP853
time integration of J φ̈ + ½J′φ̇² = M_Σ; brute-force sampling for the extremes of ω.
"""
from __future__ import annotations

import math
from decimal import Decimal
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import minimize_scalar

from reference import reference_columns

TWO_PI = 2 * math.pi

# worksheet 000, from «G_2 := 90» to the end: key -> printed text (scalar or column@position)
WS000_DYNAMICS = {
    "J_II@f": "12.962", "M_c@f": "-6.1e3", "A_c": "-1.422e4", "M_d": "2.263e3", "omega_m": "6.807",
    "dT_I_min": "-6.85e3", "dT_I_range": "7.449e3", "J_I": "1.462e3", "omega@f": "6.94",
    "eps@f": "-2.742", "J_fly": "1.459e3", "fw_rim_D2": "1.876", "fw_rim_D1": "1.501",
    "fw_rim_b": "0.375", "fw_rim_m": "2.912e3", "fw_disk_D": "1.571", "fw_disk_b": "0.314",
    "fw_disk_m": "4.773e3",
}
# true velocities and accelerations at f (motion table)
WS000_MOTION_F = {
    "w_2": "-0.713", "w_4": "-0.332", "vx_A": "2.086", "vy_A": "1.204", "v_A": "2.408",
    "vx_D": "4.949", "vy_D": "0.499", "v_D": "4.974", "vx_B": "2.474", "vy_B": "0.25",
    "v_B": "2.487", "vx_H": "4.686", "vy_H": "0", "v_H": "4.686", "vx_S4": "4.818", "vy_S4": "0.25",
    "v_S4": "4.824", "vx_S2": "2.28", "vy_S2": "0.727", "v_S2": "2.393", "ax_A": "7.533",
    "ay_A": "-14.95", "a_A": "16.74", "ax_B": "3.485", "ay_B": "-6.962", "a_B": "7.785",
    "ay_S2": "-10.956", "ax_S2": "5.509", "a_S2": "12.263", "ax_D": "6.969", "ay_D": "-13.924",
    "a_D": "15.571", "a_H": "14.082", "a_S4": "12.62", "e_2": "6.176", "e_4": "9.197",
}


def printed(text: str) -> tuple[float, float]:
    d = Decimal(text)
    return float(d), float(Decimal(1).scaleb(d.as_tuple().exponent))


@pytest.fixture(scope="module")
def dyn(ws000):
    return ws000.dynamics


def value(d, key):
    if "@" in key:
        col, lab = key.split("@")
        t = d.table
        return float(t.loc[t.pos == lab, col].iloc[0])
    return float(d.scalars[key])


# --------------------------------------------------------------------------------------------
# Printed numbers
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("key", list(WS000_DYNAMICS))
def test_ws000_printed_dynamics(dyn, key):
    want, unit = printed(WS000_DYNAMICS[key])
    got = value(dyn, key)
    assert abs(got - want) <= unit, f"{key}: {got} vs worksheet {WS000_DYNAMICS[key]}"


def test_ws000_printed_true_motion(dyn):
    m = dyn.motion
    row = m[m.pos == "f"].iloc[0]
    for col, text in WS000_MOTION_F.items():
        want, unit = printed(text)
        assert abs(row[col] - want) <= unit, f"{col}(f): {row[col]} vs worksheet {text}"
    # Δω(f) = ω(f) − ω_ср, printed 0.133
    assert abs(row["omega"] - dyn.settings.omega_m - 0.133) <= 1e-3


def test_ws000_T1max_exact_value(ws000, dyn):
    """T1max: the worksheet prints 599.736 (Mathcad's integration error); the exact value is
    599.81.  Independent recomputation: worksheet formulas on study.at, scipy quad split at the
    switching point of the resistance, bounded maximisation."""
    sc = dyn.scalars
    assert abs(sc["dT_I_max"] - 599.81) <= 5e-3
    assert abs(sc["dT_I_max"] - 599.736) > 0.05          # the printed value is off in the 4th digit
    w = 65 * TWO_PI / 60
    M_d = sc["M_d"]

    def cols(q):
        return ws000.at([q]).iloc[0]

    def M_c(q):
        c = cols(q)
        F = -9000.0 * (c.vqx_H >= 0)
        return -90 * c.vqy_S2 - 160 * c.vqy_B - 220 * c.vqy_S4 + F * c.vqx_H

    def J2(q):
        c = cols(q)
        return (0.45 * c.wq_2 ** 2 + 9 * (c.vqx_S2 ** 2 + c.vqy_S2 ** 2) + 0.55 * c.wq_3 ** 2
                + 9 * (c.vqx_B ** 2 + c.vqy_B ** 2) + 1.61 * c.wq_4 ** 2 + 22 * (c.vqx_S4 ** 2 + c.vqy_S4 ** 2))

    def dT1(q):
        A = quad(M_c, 0.0, q, epsabs=1e-11, epsrel=1e-13, limit=200)[0] + M_d * q
        return A - 0.5 * w * w * J2(q)

    r = minimize_scalar(lambda q: -dT1(q), bounds=(0.45, 0.7), method="bounded", options={"xatol": 1e-9})
    assert abs(-r.fun - sc["dT_I_max"]) <= 1e-10 * 7449
    assert abs(r.x - sc["q_dT_I_max"]) <= 1e-4
    # the report documents the discrepancy: the only printed value outside one unit of its last digit
    pr = dyn.printed
    assert list(pr.loc[~pr.within, "key"]) == ["dT_I_max"]
    assert "погрешность" in pr.loc[~pr.within, "note"].iloc[0]


def test_ws000_switching_points(ws000, dyn):
    """The resistance acts while V_qHx ≥ 0: its two sign changes, located to rounding."""
    br = dyn.breaks
    assert br.size == 2
    v = ws000.at(br)["vqx_H"].to_numpy()
    assert np.max(np.abs(v)) <= 1e-13
    assert np.all((br > 0) & (br < TWO_PI))


# --------------------------------------------------------------------------------------------
# Reduced model against independent formulations
# --------------------------------------------------------------------------------------------
def test_J_II_against_reference_kinematics(ws000, dyn):
    """J_II and J_II′ from the mpmath reference analogs (whole-mechanism Newton, 50 digits)."""
    q = [0.3, 1.7296, 3.383, 4.9]
    ref = reference_columns(ws000, q)
    f = dyn.frame(np.array(q))
    links = {"2": (9.0, 0.45, "S2"), "3": (9.0, 0.55, "B"), "4": (22.0, 1.61, "S4")}
    for i in range(len(q)):
        J = dJ = 0.0
        for k, (m, Js, S) in links.items():
            vx, vy = float(ref["vqx_" + S][i]), float(ref["vqy_" + S][i])
            ax, ay = float(ref["aqx_" + S][i]), float(ref["aqy_" + S][i])
            w, e = float(ref["wq_" + k][i]), float(ref["eq_" + k][i])
            Jk = m * (vx * vx + vy * vy) + Js * w * w
            assert f["J_II_" + k].iloc[i] == pytest.approx(Jk, rel=1e-12, abs=1e-13)
            J += Jk
            dJ += 2 * (m * (vx * ax + vy * ay) + Js * w * e)
        assert f["J_II"].iloc[i] == pytest.approx(J, rel=1e-12)
        assert f["dJ_II"].iloc[i] == pytest.approx(dJ, rel=1e-11, abs=1e-11)


def test_reduced_moment_of_weights_is_derivative_of_potential(ws000, dyn):
    """M_G = −G·dy_S/dφ, checked against a 6th-order difference of y_S(φ) from study.at."""
    q0 = np.array([0.4, 2.0, 5.1])
    h = 1e-3
    c = np.array([-1, 9, -45, 0, 45, -9, 1]) / (60 * h)
    f = dyn.frame(q0)
    for name, S, G in (("G2", "S2", 90.0), ("G3", "B", 160.0), ("G4", "S4", 220.0)):
        for i, q in enumerate(q0):
            y = ws000.at(q + h * np.arange(-3, 4))["y_" + S].to_numpy()
            assert f["M_" + name].iloc[i] == pytest.approx(-G * float(c @ y), rel=1e-8, abs=1e-8)


def test_works_against_quad(ws000, dyn):
    """A_c(φ) against adaptive quadrature of the reduced moments split at the switching points;
    M_d = −A_c/2π; A_Σ(2π) = 0."""
    br = list(dyn.breaks)

    def Mc(q):
        return float(dyn.model.M(np.array([q]))[0])

    qs = np.array([0.7, 2.9, 3.6, 6.0, TWO_PI])
    f = dyn.frame(qs)
    for i, q in enumerate(qs):
        pts = [b for b in br if b < q]
        edges = [0.0] + pts + [q]
        A = sum(quad(Mc, a, b, epsabs=1e-10, epsrel=1e-13, limit=200)[0] for a, b in zip(edges, edges[1:]))
        assert f["A_c"].iloc[i] == pytest.approx(A, rel=1e-10, abs=1e-8)
    sc = dyn.scalars
    assert sc["M_d"] == pytest.approx(-sc["A_c"] / TWO_PI, rel=1e-14)
    assert abs(f["A_sum"].iloc[-1]) <= 1e-10 * abs(sc["A_c"])


# --------------------------------------------------------------------------------------------
# Exact periodic motion (ws000 with method = exact: the same model, J_I chosen exactly)
# --------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def exact_dyn(dyn):
    return dyn.result.exact


def test_exact_delta_by_sampling(dyn, exact_dyn):
    """(ω_max − ω_min)/ω_ср = δ to 1e-10: dense sampling of ω(φ), extremes refined by bounded
    minimisation on the exact ω(φ)."""
    ex = exact_dyn
    g = np.linspace(0, TWO_PI, 4001)
    w = ex.omega_at(g)
    best = {}
    for kind, sgn in (("max", -1.0), ("min", 1.0)):
        i = int(np.argmin(sgn * w))
        a, b = g[max(i - 2, 0)], g[min(i + 2, g.size - 1)]
        r = minimize_scalar(lambda t: sgn * float(ex.omega_at(np.array([t]))[0]), bounds=(a, b),
                            method="bounded", options={"xatol": 1e-12})
        best[kind] = sgn * min(r.fun, sgn * w[i])
    wm, d = dyn.settings.omega_m, dyn.settings.delta
    assert abs((best["max"] - best["min"]) / wm - d) <= 1e-10
    assert abs(0.5 * (best["max"] + best["min"]) - wm) <= 1e-10 * wm
    assert dyn.scalars["delta_achieved_exact"] == pytest.approx(d, abs=1e-12)


def test_exact_equation_of_motion_residual(dyn, exact_dyn):
    """J_пр ε + ½J_пр′ω² = M_Σ with ε = ω·dω/dφ from 8th-order differences of the exact ω(φ)."""
    ex = exact_dyn
    rng = np.random.default_rng(3)
    q = rng.uniform(0.05, TWO_PI - 0.05, 40)
    q = q[np.min(np.abs(q[:, None] - dyn.breaks[None, :]), axis=1) > 0.02]
    h = 2e-3
    c = np.array([3, -32, 168, -672, 0, 672, -168, 32, -3]) / (840 * h)
    pts = (q[:, None] + h * np.arange(-4, 5)[None, :]).ravel()
    w = ex.omega_at(pts).reshape(q.size, 9)
    dw = w @ c
    f = dyn.frame(q)
    Jt = ex.J_I + f["J_II"].to_numpy()
    W = w[:, 4]
    res = Jt * W * dw + 0.5 * f["dJ_II"].to_numpy() * W * W - f["M_sum"].to_numpy()
    scale = np.max(np.abs(dyn.cycle["M_sum"].to_numpy()))
    assert np.max(np.abs(res)) <= 1e-8 * scale
    np.testing.assert_allclose(W * dw, f["eps_exact"].to_numpy(), rtol=0, atol=1e-8 * np.max(np.abs(f["eps_exact"])))


def test_exact_motion_time_integration(dyn, exact_dyn):
    """DOP853 in time over one revolution, restarted at each switching point: ω(φ(t)) equals the
    energy solution to 1e-9·ω_ср and returns to ω(0) (periodic)."""
    ex = exact_dyn
    model = dyn.model
    Md = dyn.scalars["M_d"]

    def rhs(t, y):
        p, w = y
        q = np.array([p])
        return [w, (float(model.M(q)[0]) + Md - 0.5 * float(model.dJ2(q)[0]) * w * w)
                / (ex.J_I + float(model.J2(q)[0]))]

    edges = [0.0] + list(dyn.breaks) + [TWO_PI]
    w0 = float(ex.omega_at(np.array([0.0]))[0])
    y = [0.0, w0]
    t = 0.0
    worst = 0.0
    for b in edges[1:]:
        def hit(t, y, b=b):
            return y[0] - b
        hit.terminal = True
        sol = solve_ivp(rhs, (t, t + 10.0), y, method="DOP853", rtol=1e-11, atol=1e-12, events=hit,
                        dense_output=True)
        assert sol.status == 1
        te = sol.t_events[0][0]
        ts = np.linspace(t, te, 7)
        p, w = sol.sol(ts)
        worst = max(worst, float(np.max(np.abs(w - ex.omega_at(p)))))
        t, y = te, [b, sol.y_events[0][0][1]]
    wm = dyn.settings.omega_m
    assert worst <= 1e-9 * wm
    assert abs(y[1] - w0) <= 1e-9 * wm


def test_kinetic_energy_change_equals_work(dyn, exact_dyn):
    """½(J_I + J_II)ω² between any two positions changes by the work of all loads (exact motion);
    works from scipy quad of M_Σ (split at the switching points)."""
    ex = exact_dyn
    rng = np.random.default_rng(11)
    p = np.sort(rng.uniform(0, TWO_PI, 8))
    f = dyn.frame(p)
    T = 0.5 * (ex.J_I + f["J_II"].to_numpy()) * f["omega_exact"].to_numpy() ** 2

    Md = dyn.scalars["M_d"]

    def Ms(q):
        return float(dyn.model.M(np.array([q]))[0]) + Md

    br = list(dyn.breaks)
    scale = dyn.scalars["dT_max"] - dyn.scalars["dT_min"]
    for i in range(len(p) - 1):
        edges = [p[i]] + [b for b in br if p[i] < b < p[i + 1]] + [p[i + 1]]
        A = sum(quad(Ms, a, b, epsabs=1e-10, epsrel=1e-13)[0] for a, b in zip(edges, edges[1:]))
        assert abs((T[i + 1] - T[i]) - A) <= 1e-9 * scale
        assert abs((T[i + 1] - T[i]) - (f["A_sum"].iloc[i + 1] - f["A_sum"].iloc[i])) <= 1e-10 * scale


def test_wittenbauer_exact_and_mertsalov_deviation(dyn):
    sc = dyn.scalars
    assert sc["J_I_wittenbauer"] == pytest.approx(sc["J_I_exact"], rel=1e-11)
    # Мерцалов over-sizes the flywheel: δ achieved below the target
    assert 0 < sc["dev_mertsalov_pct"] < 1
    assert sc["delta_achieved_mertsalov"] < dyn.settings.delta
    assert sc["J_fly"] == pytest.approx(sc["J_I"] - 2.5, rel=1e-15)


# --------------------------------------------------------------------------------------------
# Tables and laziness
# --------------------------------------------------------------------------------------------
def test_tables_and_hooks(ws000, dyn):
    t = dyn.table
    for c in ["pos", "q", "q_deg", "J_II", "dJ_II", "J_II_2", "J_II_3", "J_II_4", "M_G2", "M_Pпс", "M_c", "M_d",
              "M_sum", "A_c", "A_d", "A_sum", "T_II", "dT_I", "omega", "eps", "omega_exact", "eps_exact",
              "omega_mertsalov", "omega_wittenbauer"]:
        assert c in t.columns, c
    assert list(t.pos) == list(ws000.kinematics.pos)
    np.testing.assert_array_equal(dyn.cycle.q.to_numpy(), ws000.grid.cycle)
    m = dyn.motion
    for c in ["vx_A", "v_H", "a_S4", "w_2", "e_4", "vs_50", "as_50", "omega", "eps"]:
        assert c in m.columns, c
    assert len(dyn.motion_cycle) == len(ws000.grid.cycle)
    tabs = ws000.extra_tables()
    assert {"dynamics", "dynamics_cycle", "motion", "motion_cycle", "dynamics_printed"} <= set(tabs)
    sc = ws000.all_scalars()
    assert sc["J_I"] == dyn.scalars["J_I"] and sc["W"] == 1
    # exact evaluation at an arbitrary position agrees with the table row
    i = int(np.flatnonzero(t.pos == "f")[0])
    again = dyn.frame(np.array([t.q.iloc[i]]))
    for c in ("J_II", "M_c", "A_sum", "omega", "eps"):
        assert again[c].iloc[0] == pytest.approx(t[c].iloc[i], rel=1e-14, abs=1e-12)


def test_kinematics_does_not_run_dynamics():
    from reportgen import load_case
    from reportgen.export import tables
    CASES = Path(__file__).resolve().parents[1] / "cases"
    s = load_case(CASES / "ws000_six_bar.toml")
    s.kinematics
    s.cycle
    assert "dynamics" not in s.computed
    k = load_case(CASES / "slider_crank.toml")
    out = tables(k)
    assert "dynamics" not in out and "dynamics" not in k.computed
    assert "J_I" not in k.all_scalars()
    from reportgen.report.assemble import chosen_sections, needs
    assert "dynamics" not in chosen_sections(k, None)
    assert "dynamics" in chosen_sections(s, None)
    assert "dynamics" not in needs(s, ["structure", "kinematics"])
