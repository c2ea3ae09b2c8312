"""Class III groups (Newton) stay on one assembly branch (issue #8, item 4).

* a single position (``Study.at``, the report positions) is continued from the nearest solved
  cycle position, never solved by a Newton restarted from the sketch: ``--at "180 deg"`` equals
  report position 6, ``--at "14.7 deg"`` equals the cycle row at 14.7° (x_C = 0,901, the sketch's assembly, not the
  other assemblies at 0,963 or 1,458), a q beyond one turn equals the cycle at q − 2π;
* a coarse grid (10° steps) gives the same branch as the fine one: the kernel detects a Newton
  correction large against the predicted step and refines the step;
* a sketch a few centimetres off the assembly still assembles (Levenberg–Marquardt from the
  sketch before an assembly error is claimed);
* an unassemblable group reports its shortfall as a joint gap in metres (least squares), not a
  Newton residual;
* a dead point is reported as a singular position with its transmission angle, never as
  «не хватает 0 м».
"""
from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from reportgen.analysis.study import Study
from reportgen.case.load import CaseSpec
from reportgen.errors import AssemblyError

ROOT = Path(__file__).resolve().parents[1]
TRIAD = ROOT / "cases" / "class3_triad.toml"


def _data(path: Path) -> dict:
    return tomllib.loads(path.read_text(encoding="utf-8"))


def _study(data: dict) -> Study:
    return Study(CaseSpec(Path("variant.toml"), data))


def _numeric(df):
    return df.drop(columns=[c for c in ("pos",) if c in df.columns]).to_numpy(dtype=float)


def _assert_rows_equal(a, b, tol=1e-11):
    a, b = _numeric(a), _numeric(b)
    err = np.abs(a - b) / np.maximum(1.0, np.abs(b))
    assert err.max() <= tol, err.max()


@pytest.fixture(scope="module")
def triad():
    return Study(TRIAD)


def test_at_180_deg_is_report_position_6(triad):
    row = triad.at([math.pi])
    _assert_rows_equal(row, triad.kinematics.iloc[[6]])


def test_at_14_7_deg_is_on_the_cycle_branch(triad):
    row = triad.at([math.radians(14.7)])
    cyc = triad.cycle
    i = int(np.argmin(np.abs(cyc["q_deg"].to_numpy() - 14.7)))
    assert abs(row["x_C"].iloc[0] - 0.901) < 1e-3
    _assert_rows_equal(row.drop(columns=[c for c in row.columns if c.startswith("phi_")]),
                       cyc.iloc[[i]].drop(columns=[c for c in cyc.columns if c.startswith("phi_")]))


def test_at_beyond_one_turn_is_periodic(triad):
    a = triad.at([math.radians(725.0)])
    b = triad.at([math.radians(5.0)])
    cols = [c for c in a.columns if c[:2] in ("x_", "y_") or c.startswith(("vq", "aq", "wq", "eq"))]
    _assert_rows_equal(a[cols], b[cols])


def test_coarse_grid_follows_the_same_branch(triad):
    data = _data(TRIAD)
    data["grid"]["cycle_points"] = 36
    coarse = _study(data).cycle
    fine = triad.cycle.iloc[::100].reset_index(drop=True)
    cols = [c for c in coarse.columns if c[:2] in ("x_", "y_")]
    _assert_rows_equal(coarse[cols], fine[cols])


@pytest.mark.parametrize("offset", [(0.016, 0.0), (-0.03, 0.02), (0.0, -0.04)])
def test_sketch_off_the_assembly_still_assembles(triad, offset):
    """The sketch is the solved assembly at q = 0 moved by a few centimetres."""
    data = _data(TRIAD)
    row = triad.cycle.iloc[0]
    data["sketch"]["points"] = {p: [float(row["x_" + p]) + offset[0], float(row["y_" + p]) + offset[1]]
                                for p in data["sketch"]["points"]}
    cols = [c for c in triad.cycle.columns if c[:2] in ("x_", "y_")]
    _assert_rows_equal(_study(data).cycle[cols], triad.cycle[cols])


def test_unassemblable_group_reports_a_distance():
    data = _data(TRIAD)
    data["parameters"]["l_AB"] = "0.2 m"
    with pytest.raises(AssemblyError) as ei:
        _study(data).cycle
    e = ei.value
    assert 0.0 < e.amount < 0.4
    text = str(e)
    assert "не хватает" in text and "Ньютон" not in text and "зазор" in text


def _four_bar(a, b, c, d) -> dict:
    data = _data(ROOT / "cases" / "four_bar.toml")
    data["parameters"].update(l_OA=f"{a} m", l_AB=f"{b} m", l_CB=f"{c} m", l_OC=f"{d} m")
    data.pop("dynamics", None)
    data.pop("forces", None)
    return data


def test_dead_point_is_a_singular_position_with_its_transmission_angle():
    # change-point four-bar a + d = b + c: at q = 180° the dyad is exactly stretched
    data = _four_bar(0.1, 0.3, 0.2, 0.4)
    data.pop("sketch", None)
    with pytest.raises(AssemblyError) as ei:
        _study(data).cycle
    text = str(ei.value)
    assert "не хватает 0" not in text
    assert "Особое положение" in text and "угол передачи μ = 0,00°" in text
