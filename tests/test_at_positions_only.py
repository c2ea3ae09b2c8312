"""``export --at`` solves only the requested positions, and an input rocker's return stroke is
tabulated (issue #14, the gaps left in session 3).

* a class III mechanism (the triad of ``cases/class3_triad.toml`` with the crank lengthened to
  0,3 m) assembles only in part of the turn: the cycle fails, while ``--at`` reaches each
  requested position from the sketch (first assembly at the sketch, continued along a path) and
  never solves the cycle; the loops close there, the analogs equal central differences of the
  positions, a q beyond one turn equals q − 2π, a position reached from the sketch the other way
  round is on the same branch as the cycle of the full triad;
* ``[dof.zero_speed]`` and the synthesis check are left out under ``--at`` (they search the whole
  range), the rest of those tasks is exported;
* the forward and return strokes of ``cases/rocker_input_four_bar.toml``: the return velocities are
  the time derivatives of the closed-form positions along q(t) = q_max − ω₁t, the accelerations
  are those of the forward stroke, the strokes table gives the times, the output's ends, range and
  path, and the files are exported.
"""
from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from reportgen.analysis.study import Study
from reportgen.case.load import CaseSpec
from reportgen.cli import main
from reportgen.errors import AssemblyError, CaseError
from reportgen.export import tables

CASES = Path(__file__).resolve().parent.parent / "cases"
TRIAD = CASES / "class3_triad.toml"
ROCKER = CASES / "rocker_input_four_bar.toml"
AT_DEG = [0.0, 60.0, 120.0, 300.0, 330.0, 725.0]


def _partial_triad_text() -> str:
    text = TRIAD.read_text(encoding="utf-8")
    assert 'r = "0.1 m"' in text
    return text.replace('r = "0.1 m"', 'r = "0.3 m"')


@pytest.fixture(scope="module")
def partial(tmp_path_factory) -> Path:
    p = tmp_path_factory.mktemp("c3") / "partial_triad.toml"
    p.write_text(_partial_triad_text(), encoding="utf-8")
    return p


def _closure(row, par) -> float:
    """Largest error of the loop lengths: |AB| = l_AB, |EC| = l_EC, |FD| = l_FD, |OA| = r and the
    base triangle BCD rigid (its sketch lengths)."""
    def d(p, q):
        return math.hypot(row["x_" + p] - row["x_" + q], row["y_" + p] - row["y_" + q])
    want = {("A", "B"): 0.51, ("E", "C"): 0.4, ("F", "D"): math.hypot(0.45, 0.05), ("O", "A"): par,
            ("B", "C"): math.hypot(0.3, 0.2), ("B", "D"): math.hypot(0.3, 0.25), ("C", "D"): 0.45}
    return max(abs(d(*k) - v) for k, v in want.items())


def test_class3_at_without_the_cycle(partial):
    st = Study(partial)
    q = np.radians(AT_DEG)
    at = st.at(q)
    assert "_cycle_solution" not in st.__dict__ and "cycle" not in st.computed
    for _, row in at.iterrows():
        assert _closure(row, 0.3) < 1e-12
    # the analogs: central differences of the positions (h = 1e-6 rad, error O(h²))
    h = 1e-6
    plus, minus = st.at(q + h), st.at(q - h)
    for c in ("C", "D", "B"):
        for ax in ("x", "y"):
            fd = (plus[f"{ax}_{c}"] - minus[f"{ax}_{c}"]) / (2 * h)
            assert np.max(np.abs(at[f"vq{ax}_{c}"] - fd)) < 1e-7
            fd2 = (plus[f"vq{ax}_{c}"] - minus[f"vq{ax}_{c}"]) / (2 * h)
            assert np.max(np.abs(at[f"aq{ax}_{c}"] - fd2)) < 1e-6
    # beyond one turn: the same as q − 2π
    cols = [c for c in at.columns if c[:2] in ("x_", "y_") or c.startswith(("vq", "aq", "wq", "eq"))]
    a5 = st.at([math.radians(5.0)])[cols].to_numpy()
    assert np.max(np.abs(at[cols].iloc[[5]].to_numpy() - a5)) < 1e-11
    # the whole cycle does not assemble (a singular position near 126°)
    with pytest.raises(AssemblyError):
        Study(partial).cycle


def test_class3_at_is_on_the_cycle_branch():
    """The full triad: positions from the sketch (both ways round) equal the solved cycle's."""
    fresh = Study(TRIAD)
    q = np.radians([14.7, 180.0, 300.0, 725.0])
    at = fresh.at(q)
    assert "_cycle_solution" not in fresh.__dict__
    ref = Study(TRIAD)
    ref.cycle
    cont = ref.at(q)
    a = at.drop(columns="pos").to_numpy(dtype=float)
    b = cont.drop(columns="pos").to_numpy(dtype=float)
    assert np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b))) < 1e-11


def test_class3_no_path_assembles_directly_from_the_sketch(partial):
    """150° is not reached from the sketch's position either way round (singular near 126° and
    near 265°); it is assembled directly from the sketch, the loops closing; 200° does not
    assemble at all and the error names that position."""
    st = Study(partial)
    row = st.at([math.radians(150.0)]).iloc[0]
    assert _closure(row, 0.3) < 1e-12
    with pytest.raises(AssemblyError) as ei:
        st.at([math.radians(200.0)])
    assert "200°" in str(ei.value) and "не хватает" in str(ei.value)


def test_class3_cli_at_and_full_export(partial, tmp_path, capsys):
    out = tmp_path / "at"
    assert main(["export", str(partial), "-o", str(out), "--at", "0 deg,60 deg,330 deg"]) == 0
    at = pd.read_csv(out / "at.csv")
    assert len(at) == 3 and at["q_deg"].tolist() == pytest.approx([0, 60, 330])
    capsys.readouterr()
    assert main(["export", str(partial), "-o", str(tmp_path / "full")]) == 2
    err = capsys.readouterr().err
    assert "Особое положение" in err or "не собирается" in err
    assert "Traceback" not in err


# ----------------------------------------------------------------- tasks searching the whole range
def test_dof_zero_speed_not_solved_under_at():
    st = Study(CASES / "ws001_p1_dof.toml")
    tabs = tables(st, [math.radians(-40.0)])
    sc = st.all_scalars(positions_only=True)
    assert "_cycle_solution" not in st.__dict__ and "cycle" not in st.computed
    assert "dof_pairs" in tabs and "dof_zero" not in tabs and "at" in tabs
    assert sc["dof_W"] == 2 and sc["dof_W_after"] == 1 and "dof_zero_q" not in sc
    # the full export still finds the zero (ML ⊥ MO)
    full = Study(CASES / "ws001_p1_dof.toml")
    assert full.all_scalars()["dof_angle_OML"] == pytest.approx(math.pi / 2, abs=1e-12)


def test_synthesis_check_not_solved_under_at():
    st = Study(CASES / "synth_crank_rocker.toml")
    tables(st, [0.3])
    sc = st.all_scalars(positions_only=True)
    assert "_cycle_solution" not in st.__dict__
    assert "syn_variants" in sc and "check_K" not in sc


# ----------------------------------------------------------------- the rocker's return stroke
L1, L2, L3, D = 0.8, 0.6, 0.7, 1.0
W1 = 2.0


def _B(q):
    """B of the rocker four-bar by circle intersection (the sketch's branch, as in
    test_rocker_input.closed_form_B)."""
    ax, ay = L1 * np.cos(q), L1 * np.sin(q)
    ux, uy = D - ax, -ay
    r = np.hypot(ux, uy)
    a = (L2 * L2 - L3 * L3 + r * r) / (2 * r)
    hh = np.sqrt(L2 * L2 - a * a)
    ex, ey = ux / r, uy / r
    return ax + a * ex - hh * ey, ay + a * ey + hh * ex


@pytest.fixture(scope="module")
def rocker():
    return Study(ROCKER)


def test_return_stroke_velocities_are_time_derivatives(rocker):
    kr = rocker.kinematics_return
    k = rocker.kinematics
    q = kr["q"].to_numpy()
    assert np.all(np.diff(q) < 0) and q[0] == pytest.approx(math.radians(85)) and q[-1] == pytest.approx(math.radians(25))
    assert kr["pos"].tolist() == k["pos"].tolist()[::-1]
    # along the return stroke q(t) = q_max − ω₁t: V_B = dB/dt by central differences in time
    t = (math.radians(85) - q) / W1
    h = 1e-6

    def at_t(tt):
        return _B(math.radians(85) - W1 * tt)
    (xp, yp), (xm, ym) = at_t(t + h), at_t(t - h)
    assert np.max(np.abs(kr["vx_B"] - (xp - xm) / (2 * h))) < 1e-8
    assert np.max(np.abs(kr["vy_B"] - (yp - ym) / (2 * h))) < 1e-8
    x0, y0 = at_t(t)
    assert np.max(np.abs(kr["ax_B"] - (xp - 2 * x0 + xm) / h ** 2)) < 1e-3
    # the same accelerations, the opposite angular velocities, as on the forward stroke
    fwd = k.iloc[::-1].reset_index(drop=True)
    for c in ("ax_B", "ay_B", "e_2", "e_3", "a_B"):
        assert np.max(np.abs(kr[c] - fwd[c])) < 1e-12
    for c in ("w_2", "w_3", "vx_B", "vs_B" if "vs_B" in kr else "vy_B"):
        assert np.max(np.abs(kr[c] + fwd[c])) < 1e-12


def test_strokes_table(rocker):
    s = rocker.strokes
    sc = rocker.scalars
    assert s["stroke"].tolist() == ["forward", "return"]
    assert s["q_from_deg"].tolist() == pytest.approx([25, 85]) and s["q_to_deg"].tolist() == pytest.approx([85, 25])
    assert s["t"].tolist() == pytest.approx([math.radians(60) / W1] * 2, rel=1e-15)
    assert s["omega"].tolist() == [W1, -W1]
    # the output's ends and path: from the closed form at 25°, the reversal and 85°
    qr = sc["output_q_reversal_1"]
    bx, by = _B(np.array([math.radians(25), qr, math.radians(85)]))
    th = np.unwrap(np.arctan2(by, bx - D))
    assert s["s_from"].iloc[0] == pytest.approx(th[0], abs=1e-12) and s["s_to"].iloc[0] == pytest.approx(th[2], abs=1e-12)
    path = abs(th[1] - th[0]) + abs(th[2] - th[1])
    assert s["s_path"].iloc[1] == pytest.approx(path, abs=1e-12) and path > s["s_range"].iloc[0]
    assert s["v_mean"].iloc[0] == pytest.approx(path / s["t"].iloc[0], rel=1e-14)
    assert sc["t_cycle"] == pytest.approx(2 * math.radians(60) / W1, rel=1e-15) and sc["output_K"] == 1.0
    assert sc["output_path"] == pytest.approx(path, abs=1e-12)


def test_rocker_export_has_both_strokes(tmp_path):
    assert main(["export", str(ROCKER), "-o", str(tmp_path / "x")]) == 0
    names = {p.name for p in (tmp_path / "x").iterdir()}
    assert {"strokes.csv", "kinematics_return.csv", "kinematics.csv"} <= names
    s = pd.read_csv(tmp_path / "x" / "strokes.csv")
    assert s["stroke"].tolist() == ["forward", "return"]
    sc = json.loads((tmp_path / "x" / "scalars.json").read_text(encoding="utf-8"))
    assert sc["t_return"] == pytest.approx(sc["t_stroke"]) and "t_cycle" in sc


# ----------------------------------------------------------------- [grid] cycle = false
POSITIONS = CASES / "four_bar_positions.toml"


def test_positions_case_without_the_cycle(tmp_path, capsys):
    """``cases/four_bar_positions.toml``: the non-Grashof four-bar driven as a crank, analysed at
    the five positions of ``[grid] at``: positions and analogs equal the closed form, the cycle is
    never solved, export writes the kinematics and structure only, check passes."""
    st = Study(POSITIONS)
    k = st.kinematics
    q = np.radians([-80.0, -40.0, 0.0, 40.0, 80.0])
    assert k["q"].to_numpy() == pytest.approx(q, abs=1e-15) and k["pos"].tolist() == ["0", "1", "2", "3", "4"]
    bx, by = _B(q)
    assert np.max(np.abs(k["x_B"] - bx)) < 1e-13 and np.max(np.abs(k["y_B"] - by)) < 1e-13
    assert "_cycle_solution" not in st.__dict__ and not st.has_cycle
    assert set(tables(st)) == {"kinematics", "links", "pairs", "groups"}
    assert st.all_scalars() == {"W": 1, "n": 3, "p5": 4, "p4": 0, "mech_class": 2}
    with pytest.raises(CaseError) as ei:
        st.cycle
    assert "grid.cycle" in str(ei.value)
    assert main(["check", str(POSITIONS)]) == 0
    assert "в заданных положениях" in capsys.readouterr().out


def test_positions_case_class3_from_the_sketch(partial, tmp_path):
    """The partial triad with ``cycle = false``: its report positions are reached from the sketch
    (the same rows as ``at``), the loops close; dynamics needs the cycle and says so."""
    text = partial.read_text(encoding="utf-8").replace("[grid]\npositions = 12\n",
                                                       '[grid]\ncycle = false\nat = ["0 deg", "60 deg", "330 deg"]\n')
    assert "cycle = false" in text
    p = tmp_path / "triad_positions.toml"
    p.write_text(text, encoding="utf-8")
    st = Study(p)
    k = st.kinematics
    for _, row in k.iterrows():
        assert _closure(row, 0.3) < 1e-12
    ref = Study(partial).at(np.radians([0.0, 60.0, 330.0]))
    assert np.max(np.abs(k["x_C"].to_numpy() - ref["x_C"].to_numpy())) < 1e-13
    p2 = tmp_path / "triad_dyn.toml"
    p2.write_text(text + '\n[dynamics]\ndelta = 0.05\n', encoding="utf-8")
    with pytest.raises(CaseError) as ei:
        Study(p2).dynamics.scalars
    assert "grid.cycle" in str(ei.value)


@pytest.mark.parametrize("grid, key", [
    ("cycle = false\n", "grid.at"),
    ('cycle = false\nat = ["0 deg"]\npositions = 5\n', "grid.positions"),
    ('at = ["0 deg"]\n', "grid.at"),
    ("cycle = false\nat = []\n", "grid.at"),
])
def test_positions_grid_errors(tmp_path, grid, key):
    text = POSITIONS.read_text(encoding="utf-8")
    old = 'cycle = false\nat = ["-80 deg", "-40 deg", "0 deg", "40 deg", "80 deg"]\n'
    assert old in text
    p = tmp_path / "bad.toml"
    p.write_text(text.replace(old, grid), encoding="utf-8")
    with pytest.raises(CaseError) as ei:
        Study(p).kinematics
    assert key in str(ei.value)
