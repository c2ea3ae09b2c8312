"""Worksheet kinematics reproduced to one unit of the last printed digit."""
import math

import numpy as np
import pytest

from reportgen.case.units import parse_quantity
from worksheet_tables import WS000_AT_F, WS002_T21, WS002_T22, WS002_T31, last_digit_unit, parse_blocks


def _printed(s: str) -> float:
    v, _ = parse_quantity(s)
    return v


def test_ws000_positions_and_analogs_at_f(ws000):
    k = ws000.kinematics
    row = k[k.pos == "f"].iloc[0]
    assert math.isclose(row.q, math.radians(99.1))
    assert math.isclose(math.degrees(row.phi_1), 120.0, abs_tol=1e-12)
    for col, text in WS000_AT_F.items():
        got = row[col]
        want = _printed(text)
        unit = last_digit_unit(text)
        if text.endswith("deg"):
            unit = math.radians(unit)
        assert abs(got - want) <= unit, f"{col}: {got} vs worksheet {text}"


def test_ws000_structure(ws000):
    st = ws000.structure
    assert st.W == 1 and st.n == 5 and st.p5 == 7
    assert [g.kind for g in st.groups] == ["", "RRR", "RRP"]
    assert st.formula == "I(0,1) → II(2,3) → II(4,5)"


def test_ws002_fitted_dimensions(ws002):
    fits = {f.name: f for f in ws002.fits}
    # printed 4-digit values; the program solves them to ~1e-12
    assert abs(fits["L4"].value - 0.6613) <= 1e-4
    assert abs(fits["S_p"].value - 0.4694) <= 1e-4
    assert abs(fits["L7"].value - 0.7585) <= 1e-4
    at = ws002.at([ws002.grid.q[0]])
    assert abs(at.y_56.iloc[0] - 0.2) < 1e-12
    sp = ws002.at([fits["S_p"].value])
    assert abs(sp.y_56.iloc[0] - 0.4) < 1e-12
    assert abs(sp.phi_6.iloc[0] - math.pi / 2) < 1e-12
    for f in fits.values():
        assert abs(f.residual) < 1e-12


def _check_block(k, header, rows, skip=()):
    for r in rows:
        S = float(r[0])
        i = int(np.argmin(np.abs(k.q.to_numpy() - S)))
        assert abs(k.q.iloc[i] - S) < 1e-3
        for col, text in zip(header[1:], r[1:]):
            if col in skip:
                continue
            got = k[col].iloc[i]
            if col.startswith("phi_"):
                got = math.degrees(got)
            assert abs(got - float(text)) <= last_digit_unit(text) + 1e-12, f"S={S} {col}: {got} vs {text}"


def test_ws002_table_2_1_angles(ws002):
    for header, rows in parse_blocks(WS002_T21):
        _check_block(ws002.kinematics, header, rows)


def test_ws002_table_2_2_coordinates_and_checks(ws002):
    k = ws002.kinematics.copy()
    p = ws002.params
    # the worksheet's checks computed the other way round along each loop (they close exactly)
    k["X34s"], k["Y34s"] = k.x_34, k.y_34
    k["X45s"], k["Y45s"] = k.x_45, k.y_45
    k["X67s"], k["Y67s"] = k.x_67, k.y_67
    # the worksheet's X23s/Y23s use a mirrored angle φ12 = φ13 − acos(…): reproduce it as printed …
    X01, Y01, X03, Y03, L3 = (float(p[n].value) for n in ("X01", "Y01", "X03", "Y03", "L3"))
    L13 = math.hypot(X01 - X03, Y01 - Y03)
    phi13 = math.atan((Y03 - Y01) / (X01 - X03))
    S = k.q.to_numpy()
    phi12_ws = phi13 - np.arccos((S ** 2 + L13 ** 2 - L3 ** 2) / (2 * S * L13))
    k["X23s"], k["Y23s"] = X01 + S * np.cos(phi12_ws), Y01 + S * np.sin(phi12_ws)
    for header, rows in parse_blocks(WS002_T22):
        _check_block(k, header, rows)
    # … and show that the correct check closes: the cylinder axis 01→23 has angle π − φ13 − acos(…)
    phi12 = math.pi - phi13 - np.arccos((S ** 2 + L13 ** 2 - L3 ** 2) / (2 * S * L13))
    assert np.allclose(X01 + S * np.cos(phi12), k.x_23, atol=1e-12)
    assert np.allclose(Y01 + S * np.sin(phi12), k.y_23, atol=1e-12)
    assert np.allclose(np.cos(phi12), np.cos(k.phi_1), atol=1e-12)
    assert not np.allclose(k.X23s, k.x_23, atol=1e-2)


def test_ws002_table_3_1_transfer_ratios(ws002):
    for header, rows in parse_blocks(WS002_T31):
        _check_block(ws002.kinematics, header, rows)


def test_ws002_transfer_ratios_are_derivatives(ws002):
    """I56 = dY56/dS and IS6 = dY_S6/dS (the worksheet's product formulas), checked against
    central differences of positions on the cycle grid."""
    c = ws002.cycle
    S = c.q.to_numpy()
    h = S[1] - S[0]
    for ycol, vcol in (("y_56", "I56"), ("y_S6", "IS6"), ("phi_3", "wq_3")):
        y = c[ycol].to_numpy()
        fd = (y[2:] - y[:-2]) / (2 * h)
        assert np.max(np.abs(fd - c[vcol].to_numpy()[1:-1])) < 1e-5


def test_ws004_table(ws004):
    k = ws004.kinematics
    assert len(k) == 13
    l1, l0, w1 = 0.18, 0.6, 15.0
    assert math.isclose(k.phi_1.iloc[0], math.pi + math.asin(l1 / l0), rel_tol=1e-15)
    # position 0 is an extreme position of the rocker: ω3 = 0, S = √(l0² − l1²), V_r = −l1·ω1
    assert abs(k.w_3.iloc[0]) < 1e-12
    assert math.isclose(k.s_23.iloc[0], math.sqrt(l0 ** 2 - l1 ** 2), rel_tol=1e-14)
    assert math.isclose(k.vs_23.iloc[0], -l1 * w1, rel_tol=1e-13)
    # the branch of the worksheet's Newton: link 4 points left
    phi4 = np.degrees(np.mod(k.phi_4.to_numpy(), 2 * np.pi))
    assert ((phi4 > 90) & (phi4 < 180)).all()
    # 13th position = the first; the slider stays on its line y = l0 + a
    cols = ["s_23", "phi_3", "phi_4", "x_D", "vs_23", "w_3", "w_4", "vx_D", "as_23", "e_3", "e_4", "ax_D"]
    assert np.allclose(k[cols].iloc[0], k[cols].iloc[12], atol=1e-10)
    assert np.allclose(k.y_D, 1.0, atol=1e-14)
    # centres of mass at mid-length
    assert np.allclose(k.x_S3, 0.5 * 0.9 * np.cos(k.phi_3), atol=1e-14)
    assert np.allclose(k.x_S4, k.x_B + 0.5 * 0.35 * np.cos(k.phi_4), atol=1e-14)
    # the rocker's extreme angles are at positions with ω3 = 0 and the cycle has exactly two
    c = ws004.cycle
    w = c.wq_3.to_numpy()
    assert int(np.sum(np.sign(w[1:]) != np.sign(w[:-1]))) in (2, 3)


def test_every_assur_group_has_zero_mobility(ws000, ws002, ws004):
    """3n − 2p₅ = 0 for every group (the actuator's driving pair belongs to the rod's group)."""
    for s in (ws000, ws002, ws004):
        st = s.structure
        first, *groups = st.groups
        assert first.klass == 1 and 3 * len(first.links) - 2 * first.pairs == 1
        for g in groups:
            assert 3 * len(g.links) - 2 * g.pairs == 0, (s.name, g.label, g.pairs)
        assert sum(g.pairs for g in st.groups) == st.p5
