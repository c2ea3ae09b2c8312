"""A case file for each capability of issue #14, item 2, run through ``check``, ``export`` and
``build`` (HTML, the capability's own section: the PDF layout is tested elsewhere), with its
numbers checked independently from the exported files:

* rocker (swinging) input — ``rocker_input_four_bar.toml`` (both strokes exported);
* single positions without the cycle — ``four_bar_positions.toml`` (``[grid] cycle = false``; its
  numbers in tests/test_at_positions_only.py);
* a cycle of three revolutions — ``crank_press_three_turns.toml``;
* the flywheel on the motor shaft, J/u², and ``[parameters]`` in a load table —
  ``crank_press_motor_shaft.toml`` (the same J_доп as ``crank_press.toml``, whose table is numeric);
* the inverse flywheel task on the motor shaft — ``crank_press_inverse.toml``;
* energy-only machines: work per cycle and C_E — ``machine_energy_coefficient.toml``; loop areas —
  ``machine_loops.toml``; a turning-moment table using ``[parameters]`` — ``machine_moment_table.toml``;
* imperial units — ``slider_crank_imperial.toml``;
* exported K, output stroke, power and mean speed — ``ws001_p6_six_bar.toml`` (K, stroke, mean
  speeds) and the press cases (power).

Single positions of ``export --at`` are in tests/test_at_positions_only.py and
tests/test_rocker_input.py, dynamics and forces in the ``--at`` table in tests/test_machines.py.
"""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from reportgen.analysis.study import load_case
from reportgen.cli import main

CASES = Path(__file__).resolve().parent.parent / "cases"

RUNS = [
    ("rocker_input_four_bar", "kinematics", "обратном ходе"),
    ("four_bar_positions", "kinematics", "заданных положениях"),
    ("crank_press_three_turns", "dynamics", "маховик"),
    ("crank_press_motor_shaft", "dynamics", "вал"),
    ("crank_press_inverse", "dynamics", "δ"),
    ("machine_energy_coefficient", "machine", "C"),
    ("machine_loops", "machine", "Площади петель"),
    ("machine_moment_table", "machine", "момент"),
    ("slider_crank_imperial", "kinematics", "ползун"),
    ("ws001_p6_six_bar", "synthesis", "K"),
]


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    """Every case through check, export and build once (the tests below read the files)."""
    root = tmp_path_factory.mktemp("caps")
    out = {}
    for name, section, _ in RUNS:
        case = str(CASES / f"{name}.toml")
        codes = (main(["check", case]),
                 main(["export", case, "-o", str(root / name / "export")]),
                 main(["build", case, "-o", str(root / name / "build"), "--format", "html", "--sections", section]))
        out[name] = (codes, root / name)
    return out


def _scalars(outputs, name) -> dict:
    return json.loads((outputs[name][1] / "export" / "scalars.json").read_text(encoding="utf-8"))


@pytest.mark.parametrize("name, section, phrase", RUNS)
def test_check_export_build(outputs, name, section, phrase):
    codes, d = outputs[name]
    assert codes == (0, 0, 0)
    html = (d / "build" / f"{name}.html").read_text(encoding="utf-8")
    assert phrase in html and re.search(r"[>\s]nan[<\s]", html, re.I) is None
    assert (d / "export" / "scalars.json").exists()


def test_machine_work_and_coefficient(outputs):
    s = _scalars(outputs, "machine_energy_coefficient")
    wm = 1500 * 2 * math.pi / 60
    assert s["machine_dE"] == pytest.approx(0.9 * 2400, rel=1e-15)
    assert s["machine_J"] == pytest.approx(0.9 * 2400 / (wm * wm / 80), rel=1e-14)
    assert s["machine_power"] == pytest.approx(2400 / 0.08, rel=1e-14)
    # J = 2ΔE/(ω_max² − ω_min²) with ω_max,min = ω_ср(1 ± δ/2)
    assert 2 * s["machine_dE"] / (s["machine_omega_max"] ** 2 - s["machine_omega_min"] ** 2) == pytest.approx(
        s["machine_J"], rel=1e-12)


def test_machine_loops(outputs):
    s = _scalars(outputs, "machine_loops")
    # running sums 0.6, −0.4, 0.4, −0.1, 0 kJ: ΔE = 0.6 − (−0.4) = 1 kJ
    assert s["machine_dE"] == pytest.approx(1000.0, rel=1e-14)
    wm = 300 * 2 * math.pi / 60
    assert s["machine_J"] == pytest.approx(1000 / (wm * wm / 40), rel=1e-14)
    assert s["machine_J_fly"] == pytest.approx(s["machine_J"] - 2.0, rel=1e-14)
    e = pd.read_csv(outputs["machine_loops"][1] / "export" / "machine_energy.csv")
    assert e["E"].max() - e["E"].min() == pytest.approx(1000.0, rel=1e-14)


def test_machine_moment_table(outputs):
    s = _scalars(outputs, "machine_moment_table")
    # independent: a dense trapezoid of the same piecewise-linear M(φ) against M_ср
    xs = np.radians([0, 45, 135, 180, 225, 315, 360])
    ys = np.array([0, 1200, 1200, 0, 400, 400, 0.0])
    phi = np.linspace(0, 2 * math.pi, 720_001)
    M = np.interp(phi, xs, ys)
    work = np.concatenate([[0.0], np.cumsum(0.5 * (M[1:] + M[:-1]) * np.diff(phi))])
    Mm = work[-1] / (2 * math.pi)
    E = work - Mm * phi
    assert s["machine_work"] == pytest.approx(0.75 * math.pi * 1600, rel=1e-14)
    assert s["machine_M_mean"] == pytest.approx(Mm, rel=1e-9)
    assert s["machine_dE"] == pytest.approx(E.max() - E.min(), rel=1e-8)
    assert s["machine_omega_max"] == pytest.approx(4 * math.pi, rel=1e-15)
    assert s["machine_power"] == pytest.approx(s["machine_work"] / 0.5, rel=1e-15)


def test_motor_shaft_and_parameters_in_load_table(outputs):
    s = _scalars(outputs, "crank_press_motor_shaft")
    assert s["fw_ratio"] == 4.0
    assert s["J_fly_shaft"] == pytest.approx(s["J_fly"] / 16, rel=1e-14)
    # the same press with the numeric load table and the flywheel on the crank shaft
    direct = load_case(CASES / "crank_press.toml").dynamics.scalars
    assert s["J_fly"] == pytest.approx(direct["J_fly"], rel=1e-12)
    assert s["P_d"] == pytest.approx(direct["P_d"], rel=1e-12) and s["P_d"] > 0


def test_three_turns_and_inverse_exported(outputs):
    s3 = _scalars(outputs, "crank_press_three_turns")
    assert s3["t_cycle"] == pytest.approx(2.0, rel=1e-14)
    inv = _scalars(outputs, "crank_press_inverse")
    assert inv["J_fly"] == pytest.approx(40.0, rel=1e-12) and 0.05 < inv["delta_inverse"] < 0.15


def test_exported_K_stroke_and_mean_speeds(outputs):
    s = _scalars(outputs, "ws001_p6_six_bar")
    assert s["output_stroke"] == pytest.approx(0.2, abs=1e-10) and s["output_K"] == pytest.approx(1.3, abs=1e-10)
    assert s["output_v_return"] / s["output_v_work"] == pytest.approx(1.3, abs=1e-10)
    r = _scalars(outputs, "rocker_input_four_bar")
    st = pd.read_csv(outputs["rocker_input_four_bar"][1] / "export" / "strokes.csv")
    assert st["t"].sum() == pytest.approx(r["t_cycle"], rel=1e-15)


def test_imperial_exported_in_si(outputs):
    k = pd.read_csv(outputs["slider_crank_imperial"][1] / "export" / "kinematics.csv")
    inch = 0.0254
    q = k["q"].to_numpy()
    xb = 2 * inch * np.cos(q) + np.sqrt((8 * inch) ** 2 - (0.5 * inch - 2 * inch * np.sin(q)) ** 2)
    assert np.max(np.abs(k["x_B"] - xb)) < 1e-15


@pytest.mark.parametrize("case, old, new, key", [
    ("rocker_input_four_bar", 'M = "-150 N*m"', 'M = "-150 N"', "loads.moment"),
    ("rocker_input_four_bar", 'mode = "kinetostatic"', 'mode = "kinetic"', "forces.mode"),
    ("crank_press", "delta = 0.1\n", 'delta = "abc"\n', "dynamics.delta"),
    ("crank_press", "[86, 40], [93, 40]", '[86, "P_x"], [93, 40]', "loads.force"),
])
def test_check_rejects_bad_task_sections_as_export_does(tmp_path, capsys, case, old, new, key):
    """``check`` reads [loads], [dynamics] and [forces] exactly as ``export``: the same message."""
    text = (CASES / f"{case}.toml").read_text(encoding="utf-8")
    assert old in text
    p = tmp_path / "bad.toml"
    p.write_text(text.replace(old, new, 1), encoding="utf-8")
    capsys.readouterr()
    assert main(["check", str(p)]) == 2
    err_check = capsys.readouterr().err
    assert main(["export", str(p), "-o", str(tmp_path / "out")]) == 2
    err_export = capsys.readouterr().err
    err_check = err_check[err_check.index("Ошибка:"):]          # after the warnings check prints
    assert key in err_check and err_check == err_export and "Traceback" not in err_check
