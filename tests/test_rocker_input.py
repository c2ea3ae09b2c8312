"""A rocker (swinging) input and analysis at single positions without the cycle (issue #14, item 2).

* ``[driver] type = "rocker"`` with ``range``: the report positions and the cycle run over the
  swing; positions, first and second analogs of the output rocker equal an independent closed
  form of the four-bar (circle intersection), the analogs by the complex step;
* the extreme positions of the swing are the report positions 0 and n − 1; the output's reversal
  inside the swing (ω₃ = 0) is where O, A and B are collinear (the coupler's instant centre at B);
* the time of a stroke is the swing / ω₁, K = 1; dynamics with a flywheel is refused with a Russian
  message; forces balance (virtual power) over the swing; bad ranges are CaseErrors;
* ``export --at`` on a non-Grashof four-bar driven as a crank (assembles for |φ| < 91,8° only)
  solves the requested positions only, while the full export, ``check`` and ``build`` give the
  assembly error with the hint.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from reportgen.analysis.study import Study
from reportgen.cli import main
from reportgen.errors import AssemblyError, CaseError
from reportgen.export import tables

CASES = Path(__file__).resolve().parent.parent / "cases"
ROCKER = CASES / "rocker_input_four_bar.toml"
L1, L2, L3, D = 0.8, 0.6, 0.7, 1.0


def closed_form_B(q):
    """B of the four-bar O(0,0), A = l₁(cos q, sin q), C = (d, 0): intersection of the circles
    |B − A| = l₂ and |B − C| = l₃ on the side left of A→C (the sketch's branch).  Complex-safe
    (no abs, no atan2), so the complex step differentiates it."""
    ax, ay = L1 * np.cos(q), L1 * np.sin(q)
    ux, uy = D - ax, -ay
    r2 = ux * ux + uy * uy
    r = np.sqrt(r2)
    a = (L2 * L2 - L3 * L3 + r2) / (2 * r)
    h = np.sqrt(L2 * L2 - a * a)
    ex, ey = ux / r, uy / r
    return ax + a * ex - h * ey, ay + a * ey + h * ex


def theta3(q):
    bx, by = closed_form_B(q)
    return np.arctan(by / (bx - D))        # complex-safe; a constant branch offset does not matter


def cstep(f, q, h=1e-30):
    return np.imag(f(q + 1j * h)) / h


@pytest.fixture(scope="module")
def rocker():
    return Study(ROCKER)


def test_swing_positions_and_analogs_against_closed_form(rocker):
    k = rocker.kinematics
    q = k["q"].to_numpy()
    assert q[0] == pytest.approx(math.radians(25), abs=1e-15) and q[-1] == pytest.approx(math.radians(85), abs=1e-15)
    assert len(q) == 7 and np.allclose(np.diff(q), math.radians(10), atol=1e-15)
    bx, by = closed_form_B(q)
    assert np.max(np.abs(k["x_B"] - bx)) < 1e-13 and np.max(np.abs(k["y_B"] - by)) < 1e-13
    w3 = cstep(theta3, q)
    e3 = (cstep(theta3, q + 1e-6) - cstep(theta3, q - 1e-6)) / 2e-6
    assert np.max(np.abs(k["wq_3"] - w3)) < 1e-12
    assert np.max(np.abs(k["eq_3"] - e3)) < 1e-6 * np.max(np.abs(e3))
    # the cycle spans the swing, not a turn
    cyc = rocker.cycle
    assert cyc["q"].iloc[0] == pytest.approx(q[0]) and cyc["q"].iloc[-1] == pytest.approx(q[-1])
    assert np.max(np.abs(cyc["x_B"].to_numpy() - closed_form_B(cyc["q"].to_numpy())[0])) < 1e-13


def test_reversal_and_strokes(rocker):
    sc = rocker.scalars
    assert sc["swing"] == pytest.approx(math.radians(60), abs=1e-15)
    assert sc["t_stroke"] == pytest.approx(math.radians(60) / 2.0, rel=1e-15) and sc["output_K"] == 1.0
    assert sc["output_reversals"] == 1
    qr = sc["output_q_reversal_1"]
    row = rocker.at([qr]).iloc[0]
    assert abs(row["wq_3"]) < 1e-12
    # independent: ω₃ = 0 ⇔ V_B = 0 ⇔ the coupler turns about B ⇔ O, A, B collinear
    cross = row["x_A"] * row["y_B"] - row["y_A"] * row["x_B"]
    assert abs(cross) < 1e-12
    # the output's range over the swing, from the ends and the reversal
    bx, by = closed_form_B(np.array([math.radians(25), qr, math.radians(85)]))
    th = np.unwrap(np.arctan2(by, bx - D))
    assert sc["output_stroke"] == pytest.approx(th.max() - th.min(), abs=1e-12)
    assert sc["output"] == "phi_3"


def test_dynamics_refused_for_a_swinging_input(tmp_path):
    text = ROCKER.read_text(encoding="utf-8") + '\n[dynamics]\ndelta = 0.05\n'
    p = tmp_path / "rk_dyn.toml"
    p.write_text(text, encoding="utf-8")
    with pytest.raises(CaseError) as ei:
        Study(p).dynamics.scalars
    msg = str(ei.value)
    assert "качающееся входное звено" in msg and "маховик" in msg and "dynamics" in msg


def test_forces_over_the_swing(rocker):
    f = rocker.forces
    sc = f.scalars
    assert sc["dev_power_max"] < 1e-9 and sc["dev_zhukovsky_max_pct"] < 1e-7
    assert len(f.tables()["forces"]) == 7


@pytest.mark.parametrize("change, key", [
    (('range = ["25 deg", "85 deg"]', 'range = ["85 deg", "25 deg"]'), "driver.range"),
    (('range = ["25 deg", "85 deg"]', 'range = ["0 deg", "400 deg"]'), "driver.range"),
    (('range = ["25 deg", "85 deg"]\n', ''), "driver.range"),
    (('type = "rocker"', 'type = "crank"'), "driver.range"),
    (('omega = "2 rad/s"', 'omega = "2 rad/s"\nepsilon = "1 rad/s^2"'), "driver.epsilon"),
    (('positions = 7', 'positions = 7\nstart = "10 deg"'), "grid.start"),
    (('positions = 7', 'positions = 7\nextra = ["90 deg"]'), "grid.extra[0]"),
])
def test_bad_swing_input(tmp_path, change, key):
    text = ROCKER.read_text(encoding="utf-8")
    assert change[0] in text
    p = tmp_path / "bad.toml"
    p.write_text(text.replace(change[0], change[1], 1), encoding="utf-8")
    with pytest.raises(CaseError) as ei:
        Study(p).kinematics
    assert key in str(ei.value)


def test_rocker_cli_check_and_export(tmp_path, capsys):
    assert main(["check", str(ROCKER)]) == 0
    assert main(["export", str(ROCKER), "-o", str(tmp_path / "x")]) == 0
    sc = json.loads((tmp_path / "x" / "scalars.json").read_text(encoding="utf-8"))
    assert sc["output_reversals"] == 1 and "M_bal_absmax" in sc
    at = pd.read_csv(tmp_path / "x" / "kinematics.csv")
    assert at["q_deg"].iloc[0] == pytest.approx(25) and at["q_deg"].iloc[-1] == pytest.approx(85)


# --------------------------------------------------------------------------- --at without the cycle
def _non_grashof_crank(tmp_path) -> Path:
    """The same four-bar driven as a crank: OA assembles only for |φ| ≤ 91,79°."""
    text = ROCKER.read_text(encoding="utf-8")
    text = text.replace('type = "rocker"', 'type = "crank"').replace('range = ["25 deg", "85 deg"]\n', '')
    text = text.replace('at = "25 deg"\n', '')
    text = text.split("[[loads.moment]]")[0]
    p = tmp_path / "non_grashof.toml"
    p.write_text(text, encoding="utf-8")
    return p


def test_at_without_the_cycle(tmp_path, capsys):
    p = _non_grashof_crank(tmp_path)
    st = Study(p)
    tabs = tables(st, [0.0, math.radians(40)])
    assert "cycle" not in st.computed and "kinematics" not in st.computed
    assert set(tabs) == {"at", "links", "pairs", "groups"}
    at = tabs["at"]
    bx, by = closed_form_B(np.array([0.0, math.radians(40)]))
    assert np.max(np.abs(at["x_B"] - bx)) < 1e-13 and np.max(np.abs(at["y_B"] - by)) < 1e-13
    assert np.max(np.abs(at["wq_3"] - cstep(theta3, np.array([0.0, math.radians(40)])))) < 1e-12
    # through the command line: at.csv and the structure, no cycle tables, scalars W…
    out = tmp_path / "at"
    assert main(["export", str(p), "-o", str(out), "--at", "0 deg,40 deg"]) == 0
    assert sorted(x.name for x in out.iterdir()) == ["at.csv", "groups.csv", "links.csv", "pairs.csv", "scalars.json"]
    sc = json.loads((out / "scalars.json").read_text(encoding="utf-8"))
    assert sc == {"W": 1, "n": 3, "p5": 4, "p4": 0, "mech_class": 2}
    capsys.readouterr()
    # a position where the mechanism does not assemble: the clear error for that position
    assert main(["export", str(p), "-o", str(tmp_path / "bad"), "--at", "120 deg"]) == 2
    assert "не собирается" in capsys.readouterr().err
    # the cycle-level outputs, when requested, give the Russian error with the hint
    for argv in (["export", str(p), "-o", str(tmp_path / "full")], ["check", str(p)]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert "Механизм не собирается" in err and "--at" in err and "rocker" in err
        assert "Traceback" not in err
    with pytest.raises(AssemblyError):
        Study(p).cycle


def test_at_outside_the_swing_is_refused(tmp_path, capsys):
    assert main(["export", str(ROCKER), "-o", str(tmp_path / "x"), "--at", "40 deg,95 deg"]) == 2
    err = capsys.readouterr().err
    assert "--at[1]" in err and "вне диапазона качания" in err and "85°" in err
    assert main(["export", str(ROCKER), "-o", str(tmp_path / "y"), "--at", "40 deg"]) == 0
    at = pd.read_csv(tmp_path / "y" / "at.csv")
    assert at["x_B"].iloc[0] == pytest.approx(float(closed_form_B(np.array([math.radians(40)]))[0][0]), abs=1e-13)
    # forces at the position too (the force analysis of the case evaluates itself there)
    assert "M_bal" in at.columns
