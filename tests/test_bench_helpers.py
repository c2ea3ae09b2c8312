"""The reference methods of the benchmarks (bench/complex_step.py, bench/dynamics_precision.py)
are themselves checked: against the engine and against a closed-form periodic motion.  No timing."""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))

from complex_step import ComplexStepKinematics  # noqa: E402
from dynamics_precision import MotionODE, PeriodicSolution  # noqa: E402

from reportgen.analysis import linkage as L  # noqa: E402
from reportgen.analysis.flywheel import DynamicModel  # noqa: E402
from reportgen.analysis.study import Study  # noqa: E402


@pytest.mark.parametrize("case", ["slider_crank", "ws000_six_bar", "class3_triad"])
def test_complex_step_agrees_with_the_engine(case):
    """Positions, first and second analogs of every point by the complex step agree with the
    engine's closed forms / linear systems over a coarse cycle (two independent formulations)."""
    s = Study(ROOT / "cases" / f"{case}.toml")
    q = s.grid.start + s.grid.length * np.arange(37) / 36
    got = ComplexStepKinematics(s).points(q, s.model.point_names)
    ref = L.solve(s.model, q).points
    scale = np.maximum(1.0, np.abs(ref))
    for k, tol in ((0, 1e-13), (2, 1e-12), (4, 1e-11)):
        assert np.max(np.abs(got[:, :, k:k + 2] - ref[:, :, k:k + 2]) / scale[:, :, k:k + 2]) < tol, k


def test_periodic_solution_matches_the_closed_form():
    """J_II = 0, M_Σ = A cos φ: ω² = 2(T₀ + A sin φ)/J_I, hence ω_max² − ω_min² = 4A/J_I and
    with ω_max,min = ω_ср(1 ± δ/2): J_I = 2A/(δ ω_ср²) exactly.  The RK4 shooting reproduces it,
    and its ω(φ) is the energy integral."""
    A, wm, delta = 50.0, 10.0, 0.05

    def zero(x):
        return np.zeros_like(np.asarray(x, dtype=float))

    def M(x):
        return A * np.cos(x)

    model = DynamicModel(zero, zero, M, [], 0.0, 2 * math.pi, 72, 0.0)
    ode = MotionODE(model, 4000)
    sol = PeriodicSolution(ode, wm, delta, 1.5 * 2 * A / (delta * wm ** 2))
    J = 2 * A / (delta * wm ** 2)
    assert abs(sol.J_I - J) / J < 1e-10
    T0 = 0.5 * J * sol.w0 ** 2
    w = np.sqrt(2 * (T0 + A * np.sin(sol.phi)) / J)
    assert np.max(np.abs(sol.omega - w)) / wm < 1e-11
    assert sol.periodicity < 1e-12
