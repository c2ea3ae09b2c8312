"""Internal pairs (ГОСТ 19274-73): the ring's tip correction Δ, the interference checks, the least
z₂ − z₁; the trochoidal (tip) interference condition against an independent simulation that turns
both wheels and measures how deep the pinion's teeth enter the ring's teeth."""
from __future__ import annotations

import math

import numpy as np
import pytest

from reportgen.core import gears as G

R = G.Rack()


def penetration(m, z1, z2, x1, x2, rack=R, n_theta=240):
    """Largest depth (mm) of the pinion's teeth (involute flanks and tip land) inside the ring's
    teeth over one mesh period, carrier held: pinion points in the ring frame against the ring's
    involute space width at their radius."""
    g = G.pair_geometry(m, z1, z2, x1, x2, rack, internal=True)
    al = rack.alpha
    aw, ra1, ra2 = float(g.a_w), float(g.da1) / 2, float(g.da2) / 2
    rb1, rb2, rw1 = g.db1 / 2, g.db2 / 2, float(g.dw1) / 2
    s1 = m * (math.pi / 2 + 2 * x1 * math.tan(al))
    e2 = m * (math.pi / 2 + 2 * x2 * math.tan(al))       # the ring's space width on d₂

    def inv_r(rb, r):
        a = np.arccos(np.clip(rb / r, -1, 1))
        return np.tan(a) - a

    rr = np.linspace(max(rb1, ra2 - aw), ra1, 24)
    psi = s1 / (m * z1) + float(G.inv(al)) - inv_r(rb1, rr)
    pr = np.concatenate([rr, rr, np.full(20, ra1)])
    pp = np.concatenate([psi, -psi, np.linspace(-psi[-1], psi[-1], 20)])
    k = np.arange(z1)[:, None] * 2 * math.pi / z1
    th = np.linspace(-math.pi / z2, math.pi / z2, n_theta)[:, None, None]
    phi = pp[None, None, :] + k[None] - th * aw / rw1    # pinion turns aw/rw1 against the carrier
    X = aw * np.sin(th) + pr * np.sin(phi)
    Y = aw * np.cos(th) + pr * np.cos(phi)
    Rr = np.hypot(X, Y)
    sel = Rr > ra2 + 1e-9
    Rs, Ps = Rr[sel], np.arctan2(X, Y)[sel]
    pitch = 2 * math.pi / z2
    d = np.abs((Ps + pitch / 2) % pitch - pitch / 2)
    eta = e2 / (m * z2) + float(G.inv(al)) - inv_r(rb2, Rs)
    return float(((d - eta) * Rs).max()) if Rs.size else -1.0


def test_ring_tip_correction_and_its_handbook_expansion():
    z = np.array([40.0, 100.0, 1000.0, 1e5])
    d = G.ring_tip_correction(z, 0.0, R)
    k = 1 / math.tan(R.alpha) ** 2                       # 7,5486: d_a2 = d₂ − 2m + 15,2m/z₂
    assert np.all(np.diff(d * z) < 0) and abs(d[-1] * z[-1] - k) < 1e-3 and round(k, 2) == 7.55
    # exact: the tip circle passes through the involute boundary point (ρ_l on the line of action)
    z2, x2 = 60, 0.2
    g = G.pair_geometry(1.0, 20, z2, 0.0, x2, R, internal=True)
    rho_l = z2 / 2 * math.sin(R.alpha) - (R.ha - x2) / math.sin(R.alpha)
    assert float(g.da2) / 2 == pytest.approx(math.hypot(g.db2 / 2, rho_l), abs=1e-12)
    assert G.ring_tip_correction(50, 1.2, R) == 0.0


@pytest.mark.parametrize("x", [0.0, 0.3, 0.5])
def test_ring_tip_reaches_the_pinion_involute_boundary_when_shifts_equal(x):
    g = G.pair_geometry(2.0, 24, 60, x, x, R, internal=True)
    assert float(G.internal_checks(g)["pinion_root"]) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("z1", [17, 20, 30])
@pytest.mark.parametrize("x1,x2", [(0.0, 0.0), (0.5, 0.5), (0.0, 0.5), (0.3, 0.1)])
def test_trochoidal_condition_against_simulation(z1, x1, x2):
    for dz in range(3, 12):
        g = G.pair_geometry(1.0, z1, z1 + dz, x1, x2, R, internal=True)
        t = float(G.internal_checks(g)["trochoid"])
        if abs(t) < 0.02:
            continue                                      # too close to the limit for the sampling
        depth = penetration(1.0, z1, z1 + dz, x1, x2)
        assert (t < 0) == (depth > 1e-3), (z1, dz, x1, x2, t, depth)


def test_least_tooth_difference():
    # standard rack, no shifts: 7 for a 17…20-tooth pinion, 8 from about 30 teeth (cf. the
    # handbook's rule z₂ − z₁ ≥ 8); a positive x₂ − x₁ allows smaller differences
    assert G.dz_min_internal(20, 0.0, 0.0) == 7 and G.dz_min_internal(40, 0.0, 0.0) == 8
    assert G.dz_min_internal(20, 0.0, 0.5) < 7
    for z1, x1, x2 in ((20, 0.0, 0.0), (30, 0.5, 0.5)):
        dz = G.dz_min_internal(z1, x1, x2)
        assert penetration(1.0, z1, z1 + dz, x1, x2) < 1e-6
        assert penetration(1.0, z1, z1 + dz - 1, x1, x2) > 1e-3


def test_internal_case_note_lists_the_gost_19274_checks():
    from pathlib import Path

    from reportgen import load_case
    from reportgen.report.sections import gears as sec
    st = load_case(Path(__file__).resolve().parents[1] / "cases" / "gear_pair_internal.toml")
    text = repr(sec.build(st))
    assert "поправкой Δ = 0,2872" in text and "трохоидальная" in text and "z<sub>2</sub> − z<sub>1</sub> ≥ 7" in text.replace("<i>", "").replace("</i>", "")
    g = st.gears.geo
    assert all(float(v) >= -1e-9 for v in G.internal_checks(g).values())


def test_internal_mesh_drawing_and_ring_outline():
    from pathlib import Path

    from reportgen import load_case
    from reportgen.scenes.gears import internal_mesh_drawing, ring_outline, ring_space_half_angle
    gr = load_case(Path(__file__).resolve().parents[1] / "cases" / "gear_pair_internal.toml").gears
    g = gr.geo
    md = internal_mesh_drawing(gr)
    # the drawn tip circles cut the line of action where ε_α says (B₁ from the ring, B₂ from the pinion)
    B1, B2 = np.array(md.B1), np.array(md.B2)
    assert np.hypot(*(B2 - B1)) / float(g.pb) == pytest.approx(float(g.eps), rel=2e-4)
    assert abs(md.eps_graph - float(g.eps)) / float(g.eps) < 0.02
    # the ring's outline: radii between its tip and root circles, the flanks exact involutes
    ra2, rf2 = float(g.da2) / 2, float(g.df2) / 2
    x, y = ring_outline(gr.m, gr.z2, gr.x2, gr.rack, ra2, rf2, axis=math.pi / 2)
    r = np.hypot(x, y)
    assert r.min() == pytest.approx(ra2, abs=1e-9) and r.max() == pytest.approx(rf2, abs=1e-9)
    # space width on the pitch circle e = m(π/2 + 2x tg α), on the base circle the involute relation
    assert ring_space_half_angle(gr.m, gr.z2, gr.x2, R.alpha, g.d2 / 2) * g.d2 == pytest.approx(
        gr.m * (math.pi / 2 + 2 * gr.x2 * math.tan(R.alpha)), rel=1e-12)
    assert ring_space_half_angle(gr.m, gr.z2, gr.x2, R.alpha, g.db2 / 2) * g.db2 == pytest.approx(
        float(G.base_thickness(gr.m, gr.z2, gr.x2, R.alpha)), rel=1e-12)
