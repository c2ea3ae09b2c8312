"""The kinematics kernel's paths and the evaluator's reuse of the cycle grid against the general
path (issue #11).

* What ``run_kernel`` gives (the closed-form tape of ``core/tape.py``: dyads' analogs by their
  velocity and acceleration equations as 2×2 systems, or the general kernel for Newton groups)
  equals the analogs of every group's dense system Φ_x x' = −Φ_q, Φ_x x'' = −γ solved by LU in the
  general kernel (``gspec[:, 5] = A_DENSE`` keeps a group off the tape), at every position of the
  cycle grid of each case (a second formulation of the same equations).
* ``ColumnEvaluator`` takes points of the solved cycle grid from the cycle: at a mix of grid and
  off-grid points its columns equal a direct solve of the same points.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from reportgen import load_case
from reportgen.analysis import linkage as L
from reportgen.analysis.loads import ColumnEvaluator
from reportgen.core import kinematics as K

CASES = Path(__file__).resolve().parents[1] / "cases"
NAMES = ["ws000_six_bar", "ws002_tractor_hitch", "ws004_slotted_lever", "whitworth", "four_bar",
         "slider_crank", "crank_press", "class3_triad"]


@pytest.mark.parametrize("name", NAMES)
def test_structured_analogs_equal_dense(name):
    s = load_case(CASES / f"{name}.toml")
    model, q = s.model, s.grid.cycle
    assert (model.gspec[:, 5] != K.A_DENSE).any() or K.G_NEWTON in model.gkind
    fast = L.run_kernel(model, q)
    spec = model.gspec.copy()
    try:
        model.gspec[:, 5] = K.A_DENSE
        dense = L.run_kernel(model, q)
    finally:
        model.gspec = spec
    assert fast[4][0] == K.F_OK and dense[4][0] == K.F_OK
    for a, b, tol in ((fast[0], dense[0], 1e-14), (fast[1], dense[1], 1e-13), (fast[2], dense[2], 1e-13)):
        scale = max(1.0, float(np.max(np.abs(b))))
        assert np.max(np.abs(a - b)) <= tol * scale


@pytest.mark.parametrize("name", ["ws000_six_bar", "ws002_tractor_hitch", "class3_triad"])
def test_evaluator_grid_points_equal_direct_solve(name):
    s = load_case(CASES / f"{name}.toml")
    g = s.grid.cycle
    q = np.concatenate((g[[0, 7, 1200, len(g) - 1]], 0.5 * (g[[3, 2000]] + g[[4, 2001]])))
    cols = ColumnEvaluator(s)(q)
    direct = L.columns(s.model, s._solve_on_branch(q), grid=False)
    assert set(direct) <= set(cols)
    for k, v in direct.items():
        scale = max(1.0, float(np.max(np.abs(v))))
        assert np.max(np.abs(cols[k] - v)) <= 1e-13 * scale, k
