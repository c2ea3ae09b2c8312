"""Energy-only machines ([machine]) and worksheet 001 problem 8 (press flywheel):
J = 1,895 exactly against the printed 1,89 (rounded speeds); N = 4241 W."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from reportgen.analysis.study import load_case
from reportgen.core import machine as CM
from reportgen.errors import CaseError

CASES = Path(__file__).resolve().parent.parent / "cases"


def test_problem_2013_8():
    st = load_case(CASES / "ws001_p8_press.toml")
    m = st.machine
    F = math.pi * 0.05 * 0.03 * 60e6
    assert F == pytest.approx(282.7e3, abs=50)                      # printed 282,7 кН
    E = F * 0.03 / 2
    assert m.dE == pytest.approx(E, rel=1e-14)
    assert m.power == pytest.approx(4241, abs=0.5)                 # printed 4241 Вт
    assert m.omega_max == pytest.approx(50 * math.pi, rel=1e-15)   # printed 157
    assert m.omega_min == pytest.approx(19 / 21 * 50 * math.pi, rel=1e-14)   # printed 142
    # the worksheet's formula with exact speeds, and with its rounded speeds
    J_exact = 2 * E / (m.omega_max ** 2 - m.omega_min ** 2)
    assert m.J == pytest.approx(J_exact, rel=1e-13)
    assert round(m.J, 3) == 1.895
    assert round(2 * 4241 / (157 ** 2 - 142 ** 2), 2) == 1.89
    assert [p["key"] for p in m.printed] == ["power", "omega_max", "omega_min", "J"]
    assert set(st.all_scalars()) >= {"machine_J", "machine_power", "machine_delta"}


def test_inverse_returns_delta(tmp_path):
    st = load_case(CASES / "ws001_p8_press.toml")
    J = st.machine.J
    text = (CASES / "ws001_p8_press.toml").read_text(encoding="utf-8")
    text = text.replace("delta = 0.1\n", f'fly_mass = "{J / 0.25 ** 2!r} kg"\nfly_radius = "0.25 m"\n')
    text = text.split("[machine.printed]")[0]
    p = tmp_path / "inv.toml"
    p.write_text(text, encoding="utf-8")
    m = load_case(p).machine
    assert m.delta == pytest.approx(0.1, abs=1e-12)
    assert m.omega_max == pytest.approx(50 * math.pi, rel=1e-12)


def test_loops_and_table_agree():
    """A turning-moment table and the loop areas of the same diagram give the same ΔE_max;
    the table's running work is exact at the zeros of M − M_ср (independent: dense trapezoid)."""
    phi = np.radians([0, 60, 120, 180, 240, 300, 360])
    M = np.array([0.0, 300.0, 0.0, 150.0, 0.0, 150.0, 0.0])
    t = CM.fluctuation_from_table(phi, M)
    x = np.linspace(0, 2 * np.pi, 600001)
    f = np.interp(x, phi, M) - t["M_mean"]
    E = np.concatenate([[0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(x))])
    assert t["dE"] == pytest.approx(E.max() - E.min(), rel=1e-9)
    # loop areas between the crossings of the mean line
    xs, es = t["phi"], t["E"]
    cross = [0.0] + [e for e, xx in zip(es, xs) if abs(np.interp(xx, phi, M) - t["M_mean"]) < 1e-9] + [es[-1]]
    areas = np.diff(cross)
    dE, _ = CM.fluctuation_from_loops(areas[np.abs(areas) > 0])
    assert dE == pytest.approx(t["dE"], rel=1e-12)


def test_machine_case_errors(tmp_path):
    base = '[machine]\nn = "1500 rpm"\ndelta = 0.1\n'
    for body, msg in [('dE = "1 kJ"\nC_E = 0.1\n', "ровно один"),
                      ('loops = ["1 kJ", "-0.5 kJ"]\n', "не равна нулю"),
                      ('C_E = 0.1\n', "работа за цикл")]:
        p = tmp_path / "m.toml"
        p.write_text(base + body, encoding="utf-8")
        with pytest.raises(CaseError, match=msg):
            load_case(p).machine
