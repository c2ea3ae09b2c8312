"""Machines beyond the crank cycle: any cycle length k·π or n revolutions, the flywheel on a
faster shaft (J on that shaft = J_доп/u²), the inverse flywheel task (given J or m·ρ² → δ and
the speed extremes; it returns the δ the direct task was given)."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from reportgen.analysis.study import load_case
from reportgen.errors import CaseError

SRC = (Path(__file__).resolve().parent.parent / "cases" / "crank_press.toml").read_text(encoding="utf-8")


def _variant(tmp_path, extra: str, drop_delta: bool = False, name: str = "m"):
    text = SRC.replace("delta = 0.1\n", "" if drop_delta else "delta = 0.1\n")
    text = text.replace('method = "exact"\n', 'method = "exact"\n' + extra)
    p = tmp_path / f"{name}.toml"
    p.write_text(text, encoding="utf-8")
    return load_case(p)


@pytest.fixture(scope="module")
def direct():
    return load_case(Path(__file__).resolve().parent.parent / "cases" / "crank_press.toml").dynamics.scalars


def test_inverse_returns_delta_of_direct(tmp_path, direct):
    J = direct["J_fly"]
    inv = _variant(tmp_path, f'J_fly = "{J!r} kg*m^2"\n', drop_delta=True).dynamics.scalars
    assert inv["delta_inverse"] == pytest.approx(0.1, abs=1e-10)
    assert inv["omega_max_inverse"] == pytest.approx(direct["omega_max"], rel=1e-10)
    assert inv["omega_min_inverse"] == pytest.approx(direct["omega_min"], rel=1e-10)
    assert inv["J_fly"] == pytest.approx(J, rel=1e-10)


def test_inverse_from_mass_and_radius_of_gyration(tmp_path, direct):
    rho = 0.4
    m = direct["J_fly"] / rho ** 2
    inv = _variant(tmp_path, f'fly_mass = "{m!r} kg"\nfly_radius = "{rho} m"\n', drop_delta=True).dynamics.scalars
    assert inv["delta_inverse"] == pytest.approx(0.1, abs=1e-10)


def test_inverse_with_ratio(tmp_path, direct):
    u = 3.0
    J_motor = direct["J_fly"] / u ** 2
    inv = _variant(tmp_path, f'J_fly = "{J_motor!r} kg*m^2"\nflywheel_ratio = {u}\n', drop_delta=True)
    assert inv.dynamics.scalars["delta_inverse"] == pytest.approx(0.1, abs=1e-10)


def test_flywheel_on_motor_shaft(tmp_path, direct):
    s = _variant(tmp_path, "flywheel_ratio = 4\n").dynamics.scalars
    assert s["J_fly"] == pytest.approx(direct["J_fly"], rel=1e-12)
    assert s["J_fly_shaft"] == pytest.approx(direct["J_fly"] / 16, rel=1e-12)
    assert s["omega_max_shaft"] == pytest.approx(4 * direct["omega_max"], rel=1e-12)
    # the rim on the motor shaft: J ∝ m·D² with m ∝ D³ (fixed proportions) → D ∝ J^(1/5)
    assert s["fw_rim_D2"] == pytest.approx(direct["fw_rim_D2"] * 16 ** (-0.2), rel=1e-9)


@pytest.mark.parametrize("cycle", ["3", '"6pi"', '"1080 deg"', '"6*pi"'])
def test_cycle_of_three_revolutions(tmp_path, direct, cycle):
    d = _variant(tmp_path, f"cycle = {cycle}\n").dynamics
    assert d.settings.cycle_length == pytest.approx(6 * math.pi, abs=1e-12)
    assert len(d.positions) == 3 * 12
    # a periodic machine over three revolutions needs the same flywheel
    assert d.scalars["J_fly"] == pytest.approx(direct["J_fly"], rel=1e-7)


def test_cycle_errors(tmp_path):
    with pytest.raises(CaseError, match="кратна π"):
        _variant(tmp_path, 'cycle = "100 deg"\n').dynamics
    with pytest.raises(CaseError, match="положительным"):
        _variant(tmp_path, "cycle = 0\n").dynamics
    with pytest.raises(CaseError, match="δ"):
        _variant(tmp_path, 'J_fly = "10 kg*m^2"\n').dynamics


def test_parameters_in_load_table(tmp_path, direct):
    """Cells of a load table may use [parameters] (with their own units)."""
    text = SRC.replace("[parameters]\n", '[parameters]\nF_max = "40 kN"\n', 1)
    text = text.replace("[86, 40], [93, 40]", '[86, "F_max"], [93, "F_max"]')
    assert '"F_max"' in text
    p = tmp_path / "tab.toml"
    p.write_text(text, encoding="utf-8")
    assert load_case(p).dynamics.scalars["J_fly"] == pytest.approx(direct["J_fly"], rel=1e-12)


@pytest.mark.parametrize("text, si, dim", [
    ("1 in", 0.0254, "LENGTH"), ("2 ft", 0.6096, "LENGTH"), ("1 lbf", 4.4482216152605, "FORCE"),
    ("1 lbf*ft", 1.3558179483314004, "MOMENT"), ("1 lb*ft^2", 0.0421401100938048, "INERTIA"),
    ("1 slug*ft^2", 1.3558179483314004, "INERTIA"), ("1 psi", 6894.757293168361, "PRESSURE"),
    ("1 hp", 745.6998715822702, "POWER"), ("1 in/s", 0.0254, "VELOCITY"),
])
def test_imperial_units(text, si, dim):
    from reportgen.case import units as U
    v, d = U.parse_quantity(text)
    assert d == getattr(U, dim)
    assert v == pytest.approx(si, rel=1e-14)


def test_exported_K_stroke_and_power(direct):
    """Scalars of every linkage: output stroke and K (exact extreme positions); power of the
    machine: P_d = A_d·ω_ср/Φ = M_d·ω_ср for a constant driving moment."""
    st = load_case(Path(__file__).resolve().parent.parent / "cases" / "ws001_p6_six_bar.toml")
    sc = st.scalars
    assert sc["output_stroke"] == pytest.approx(0.2, abs=1e-12)
    assert sc["output_K"] == pytest.approx(1.3, abs=1e-12)
    w = st.mechanism.driver.omega
    t_work = max(sc["output_q2"] - sc["output_q1"], 2 * math.pi - (sc["output_q2"] - sc["output_q1"])) / w
    assert sc["output_v_work"] == pytest.approx(0.2 / t_work, rel=1e-12)
    assert direct["P_d"] == pytest.approx(direct["M_d"] * direct["omega_m"], rel=1e-12)
    assert direct["P_d"] == pytest.approx(-direct["P_c"], rel=1e-9)


def test_at_table_has_dynamics_columns(direct):
    """``export --at``: dynamics and true-motion columns at arbitrary positions equal the
    dynamics tables at the report positions."""
    from reportgen.export import tables
    st = load_case(Path(__file__).resolve().parent.parent / "cases" / "crank_press.toml")
    d = st.dynamics
    q = [float(d.positions[3]), float(d.positions[3]) + 2 * math.pi]
    at = tables(st, q)["at"]
    row = d.table.iloc[3]
    for c in ("J_II", "M_c", "omega", "eps"):
        assert at[c].iloc[0] == pytest.approx(row[c], rel=1e-12, abs=1e-12)
        assert at[c].iloc[1] == pytest.approx(row[c], rel=1e-9, abs=1e-9)
    assert at["true_v_B"].iloc[0] == pytest.approx(d.motion.iloc[3]["v_B"], rel=1e-12)


def test_at_table_has_force_columns():
    """``export --at``: the force analysis at arbitrary positions equals its table at the
    report positions."""
    from reportgen.export import tables
    st = load_case(Path(__file__).resolve().parent.parent / "cases" / "ws000_six_bar.toml")
    assert "forces" in st.tasks()
    f = st.forces
    row = f.table.iloc[2]
    at = tables(st, [float(row["q"])])["at"]
    cols = [c for c in f.table.columns if c.startswith("R")]
    assert cols and set(cols) <= set(at.columns)
    for c in cols:
        assert at[c].iloc[0] == pytest.approx(row[c], rel=1e-10, abs=1e-9)
