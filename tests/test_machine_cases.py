"""Case files for the machine capabilities of issue #14, item 2 (check and export run on each):

* ``crank_press_inverse.toml`` — the inverse flywheel task with the flywheel on the motor shaft
  (J = 2,5 kg·m² at u = 4): the δ it returns, given back to the direct task, gives J = u²·2,5 back;
* ``crank_press_three_turns.toml`` — a cycle of three revolutions (punching on the first one): the
  work per cycle is the area of the punching diagram once (400 J), t_cycle = 3 rev / 90 rpm = 2 s;
* ``slider_crank_imperial.toml`` — inches, pounds, lb·in², rpm and lbf: the slider's position equals
  the closed form of the offset slider-crank in SI, masses converted exactly, forces balance.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from reportgen.analysis.study import load_case
from reportgen.cli import main

CASES = Path(__file__).resolve().parent.parent / "cases"


@pytest.mark.parametrize("name", ["crank_press_inverse", "crank_press_three_turns", "slider_crank_imperial"])
def test_check_and_export(tmp_path, name, capsys):
    assert main(["check", str(CASES / f"{name}.toml")]) == 0
    assert main(["export", str(CASES / f"{name}.toml"), "-o", str(tmp_path / name)]) == 0
    assert (tmp_path / name / "scalars.json").exists()


def test_inverse_flywheel_on_the_motor_shaft(tmp_path):
    inv = load_case(CASES / "crank_press_inverse.toml").dynamics.scalars
    assert inv["J_fly_given"] == pytest.approx(2.5) and inv["fw_ratio"] == 4.0
    assert inv["J_fly"] == pytest.approx(2.5 * 16, rel=1e-12)
    delta = inv["delta_inverse"]
    assert 0.05 < delta < 0.15
    # the direct task given that δ finds the same flywheel: J_доп = u²·J = 40 kg·m²
    text = (CASES / "crank_press.toml").read_text(encoding="utf-8").replace("delta = 0.1\n", f"delta = {delta!r}\n")
    p = tmp_path / "direct.toml"
    p.write_text(text, encoding="utf-8")
    direct = load_case(p).dynamics.scalars
    assert direct["J_fly"] == pytest.approx(40.0, rel=1e-8)
    assert direct["omega_max"] == pytest.approx(inv["omega_max_inverse"], rel=1e-9)


def test_three_turn_cycle():
    s = load_case(CASES / "crank_press_three_turns.toml").dynamics.scalars
    area = 0.5 * 40e3 * 0.006 + 40e3 * 0.007          # the punching diagram: ramp 80…86 mm, 40 kN to 93 mm
    assert s["A_c"] == pytest.approx(-area, rel=1e-12) and s["A_d"] == pytest.approx(area, rel=1e-12)
    assert s["t_cycle"] == pytest.approx(3 * 60 / 90, rel=1e-14)
    assert s["P_c"] == pytest.approx(-area / 2.0, rel=1e-12)


def test_imperial_units():
    st = load_case(CASES / "slider_crank_imperial.toml")
    k = st.kinematics
    inch = 0.0254
    l1, l2, e = 2 * inch, 8 * inch, 0.5 * inch
    q = k["q"].to_numpy()
    xb = l1 * np.cos(q) + np.sqrt(l2 ** 2 - (e - l1 * np.sin(q)) ** 2)
    assert np.max(np.abs(k["x_B"] - xb)) < 1e-15 and np.allclose(k["y_B"], e, atol=1e-16)
    assert st.mechanism.driver.omega == pytest.approx(1200 * 2 * math.pi / 60, rel=1e-15)
    assert st.mechanism.link("2").mass == pytest.approx(5 * 0.45359237, rel=1e-15)
    assert st.mechanism.link("2").J_S == pytest.approx(100 * 0.45359237 * inch ** 2, rel=1e-15)
    f = st.forces.scalars
    assert f["dev_power_max"] < 1e-9 and f["dev_zhukovsky_max_pct"] < 1e-7
