"""Dynamics of the other cases (corrected worksheet 000, four-stroke engine, crank press), the
loads of the case file and their errors; the report section builds."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from reportgen import load_case
from reportgen.errors import CaseError

CASES = Path(__file__).resolve().parents[1] / "cases"
FOUR_PI = 4 * math.pi


@pytest.fixture(scope="module")
def engine():
    return load_case(CASES / "engine_four_stroke.toml")


@pytest.fixture(scope="module")
def press():
    return load_case(CASES / "crank_press.toml")


@pytest.fixture(scope="module")
def corrected():
    return load_case(CASES / "ws000_six_bar_corrected.toml")


# --------------------------------------------------------------------------------------------
# Corrected worksheet 000
# --------------------------------------------------------------------------------------------
def test_corrected_case_changes(corrected, ws000):
    d = corrected.dynamics
    assert d.settings.method == "exact"
    assert d.result.J_I == d.scalars["J_I_exact"]
    # link 3 with 16 kg at B, the slider's 3.5 kg moving with H
    f = d.table[d.table.pos == "f"].iloc[0]
    k = ws000.kinematics
    kf = k[k.pos == "f"].iloc[0]
    assert f["J_II_3"] == pytest.approx(16 * (kf.vqx_B ** 2 + kf.vqy_B ** 2) + 0.55 * kf.wq_3 ** 2, rel=1e-13)
    assert f["J_II_5"] == pytest.approx(3.5 * (kf.vqx_H ** 2 + kf.vqy_H ** 2), rel=1e-13)
    # loads and works are those of the worksheet (weights 160 N and 35 N by m·g with g = 10)
    assert d.scalars["A_c"] == pytest.approx(ws000.dynamics.scalars["A_c"], rel=1e-13)
    cmp = d.comparison.set_index("key")
    assert cmp.loc["J_I_exact", "other"] == pytest.approx(ws000.dynamics.scalars["J_I_exact"], rel=1e-14)
    assert cmp.loc["J_II_mean", "change_pct"] > 10          # J_II grows by ~20 %
    assert abs(cmp.loc["J_I_exact", "change_pct"]) < 0.1     # the flywheel hardly changes
    assert 0 < d.comparison.attrs["omega_diff_max"] < 0.05
    from reportgen.report.sections.dynamics import conclusion_lines
    text = " ".join(conclusion_lines(corrected))
    # the comparison with the worksheet's variant is the teacher's: in the answer key only
    assert "рабочий лист 000" not in text


# --------------------------------------------------------------------------------------------
# Four-stroke engine (cycle 4π, indicator diagram by strokes)
# --------------------------------------------------------------------------------------------
def _trapezoid(rows):
    x = np.array([r[0] for r in rows]) * 1e-3
    y = np.array([r[1] for r in rows]) * 1e6
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)))


def test_engine_gas_work_and_switching(engine):
    """The cycle work of the gas force equals ∮p dV from the tables (trapezoid over the table
    rows is exact for a piecewise-linear law): intake and expansion with the piston moving away
    from the head, compression and exhaust towards it."""
    import tomllib
    data = tomllib.loads((CASES / "engine_four_stroke.toml").read_text(encoding="utf-8"))
    st = {s["name"]: s["table"] for s in data["loads"]["force"][0]["stroke"]}
    area = math.pi * 0.1 ** 2 / 4
    W = area * (_trapezoid(st["впуск"]) - _trapezoid(st["сжатие"]) + _trapezoid(st["рабочий ход"])
                - _trapezoid(st["выпуск"]))
    d = engine.dynamics
    sc = d.scalars
    assert d.settings.cycle_length == pytest.approx(FOUR_PI)
    assert sc["balance"] == "resistance"
    # weights do no net work over a cycle; the driving work is the gas work
    assert sc["A_d"] == pytest.approx(W, rel=1e-10)
    assert sc["M_c"] == pytest.approx(-W / FOUR_PI, rel=1e-10)
    br = np.degrees(d.breaks)
    for b in (180.0, 360.0, 540.0):
        assert np.min(np.abs(br - b)) < 1e-9
    # force on the piston: suction pulls it towards the head (+x), expansion pushes it away
    cols = d.ev(np.array([math.radians(90), math.radians(360) + 1e-9, math.radians(450)]))
    F = d.loads.forces(cols)
    gas = [f for f in F if f.name == "Pг"][0]
    assert gas.Fx[0] == pytest.approx(0.01e6 * area, rel=1e-12)
    assert gas.Fx[1] == pytest.approx(-4.9e6 * area, rel=1e-6)
    assert gas.Fx[2] < 0 and np.all(gas.Fy == 0)
    assert sc["delta_achieved_exact"] == pytest.approx(1 / 80, abs=1e-12)
    assert sc["J_crank"] == pytest.approx(0.04)
    assert sc["J_I_const"] == pytest.approx(0.09)


def test_engine_tables_over_two_revolutions(engine):
    d = engine.dynamics
    t = d.table
    assert len(t) == 24
    assert t.q_deg.iloc[-1] == pytest.approx(690.0)
    # the kinematics repeats after 2π but the loads do not
    a = t[t.pos == "1"].iloc[0]
    b = t[t.pos == "13"].iloc[0]
    assert a.J_II == pytest.approx(b.J_II, rel=1e-12)
    assert a.M_d != pytest.approx(b.M_d, rel=1e-3)
    assert len(d.cycle) == 2 * len(engine.grid.cycle) - 1
    # energy balance of the exact motion over the whole cycle and ω periodic
    ex = d.result.exact
    w = ex.omega_at(np.array([0.0, FOUR_PI]))
    assert w[1] == pytest.approx(w[0], rel=1e-13)


# --------------------------------------------------------------------------------------------
# Crank press (resistance over part of the downstroke, with a jump)
# --------------------------------------------------------------------------------------------
def test_press_cutting_work(press):
    d = press.dynamics
    sc = d.scalars
    # 40 kN reached over 6 mm (linear), held 7 mm: −(20 kN·6 mm + 40 kN·7 mm) = −400 J
    assert sc["A_c"] == pytest.approx(-400.0, rel=1e-11)
    assert sc["M_d"] == pytest.approx(400.0 / (2 * math.pi), rel=1e-11)
    # switching points: the table corners crossed on the downstroke (s = 80, 86, 93 mm) and
    # the bottom dead centre (V_qy = 0)
    cols = d.ev(d.breaks)
    s = (0.05 + 0.3 - cols["y_B"]) * 1e3
    down = cols["vqy_B"] < 0
    for mm in (80.0, 86.0, 93.0):
        assert np.min(np.abs(s[down] - mm)) < 1e-9
    assert np.min(np.abs(np.degrees(d.breaks) - 180.0)) < 1e-9
    assert sc["J_I_wittenbauer"] == pytest.approx(sc["J_I_exact"], rel=1e-11)
    assert sc["fw_needed"]


def test_batch_variant_skips_printed_values():
    """Printed worksheet values belong to the worksheet case, not to a variant derived from it."""
    v = load_case(CASES / "ws000_six_bar.toml", {"l_OA": "0.3 m"})
    assert v.dynamics.settings.printed == () and v.dynamics.printed.empty
    assert "dynamics_printed" not in v.extra_tables()


def test_report_sections_build(engine, corrected):
    from reportgen.report.assemble import build_report
    from reportgen.report.sections import dynamics as sec
    for s in (engine, corrected):
        rep = build_report(s, ["dynamics"])
        assert rep.sections[0].title == "Динамический анализ и синтез маховика"
        ids = set()

        def walk(node):
            for ch in getattr(node, "children", []):
                if getattr(ch, "id", None):
                    ids.add(ch.id)
                walk(ch)
        walk(rep.sections[0])
        assert {"fig-dyn-J", "fig-dyn-witt", "fig-dyn-flywheel", "tab-dyn-methods"} <= ids
        assert all(isinstance(x, str) and x for x in sec.conclusion_lines(s))
    # the comparison with another variant is for the teacher: in the answer key, not in the note
    assert "tab-dyn-compare" not in ids
    from reportgen.report.key import build_key
    key_ids = set()

    def walk_key(node):
        for ch in getattr(node, "children", []):
            if getattr(ch, "id", None):
                key_ids.add(ch.id)
            walk_key(ch)
    for sec_ in build_key(corrected).sections:
        walk_key(sec_)
    assert "tab-dyn-compare" in key_ids


# --------------------------------------------------------------------------------------------
# Loads and settings read from the case file; errors in Russian
# --------------------------------------------------------------------------------------------
BASE = (CASES / "slider_crank.toml").read_text(encoding="utf-8")


def _case(tmp_path, extra: str, name="c.toml"):
    p = tmp_path / name
    p.write_text(BASE + "\n" + extra, encoding="utf-8")
    return load_case(p)


DYN = """
[dynamics]
n = "600 rpm"
delta = 0.05
"""


LOADS = """
[[loads.moment]]
name = "Mс"
link = "1"
M = "-20 N*m"
against = "motion"

[[loads.force]]
name = "F"
link = "3"
point = "B"
F = ["-300 N", "0 N"]
when = "x_B > 0.45 m"
"""


def test_moment_loads_and_given_drive(tmp_path):
    s = _case(tmp_path, LOADS + DYN)
    d = s.dynamics
    cols = d.ev(np.array([0.3, 2.0]))
    (mom,) = d.loads.moments(cols)
    assert mom.link == "1" and np.all(mom.M == -20.0)     # against the ccw rotation of the crank
    red = d.loads.reduced(cols)
    assert np.all(red["Mс"] == -20.0)
    F = [f for f in d.loads.forces(cols) if f.name == "F"][0]
    assert F.point == "B"
    np.testing.assert_array_equal(F.Fx, np.where(cols["x_B"] > 0.45, -300.0, 0.0))
    # the switching points of the condition x_B = 0.45 m
    xb = d.ev(d.breaks)["x_B"]
    assert np.max(np.abs(xb - 0.45)) < 1e-12
    # a given driving moment equal to the balancing one gives the same motion
    Md = d.scalars["M_d"]
    s2 = _case(tmp_path, LOADS + DYN + f'drive = "{Md!r} N*m"\n', "c2.toml")
    assert s2.dynamics.scalars["J_I_exact"] == pytest.approx(d.scalars["J_I_exact"], rel=1e-9)


@pytest.mark.parametrize("extra, key, words", [
    (DYN + 'drive = "10 N*m"\n', "dynamics.drive", "не уравновешивает"),
    (DYN + "speed = 3\n", "dynamics.speed", "неизвестный ключ"),
    ('[[loads.force]]\nlink = "3"\npoint = "B"\nmagnitude = "100 N"\ndirection = "x"\nwhen = "vqx_Q >= 0"\n' + DYN,
     "loads.force[0].when", "неизвестное имя «vqx_Q»"),
    ('[[loads.force]]\nlink = "3"\npoint = "B"\ndirection = "x"\nof = "x_B"\ntable = [[0.4, 0], [0.45, 100]]\n' + DYN,
     "loads.force[0].table", "выходит за пределы таблицы"),
    ('[[loads.force]]\nlink = "3"\npoint = "Z"\nmagnitude = "100 N"\ndirection = "x"\n' + DYN,
     "loads.force[0].point", "не принадлежит звену"),
    (DYN + '[dynamics.printed]\nJ_X = "1.0"\n', "dynamics.printed.J_X", "нет величины"),
    (DYN.replace("delta = 0.05", "delta = 1.5"), "dynamics.delta", "меньше 1"),
], ids=["drive-unbalanced", "unknown-key", "unknown-column", "table-range", "point", "printed-key", "delta"])
def test_case_errors(tmp_path, extra, key, words):
    s = _case(tmp_path, extra)
    with pytest.raises(CaseError) as e:
        s.dynamics.printed
    assert e.value.key == key, str(e.value)
    assert words in str(e.value)
