"""The shortcuts of the whole-analysis speed-up (issue #11) give the numbers of the plain paths,
bit for bit: the points' formula, np.unwrap, the kinematic columns by name, an evaluation on
the cycle grid, and the force scalars without the force tables."""
import math
from pathlib import Path

import numpy as np
import pytest

from reportgen.analysis import linkage as L
from reportgen.analysis.study import Study
from reportgen.core import kinematics as K

CASES = Path(__file__).resolve().parents[1] / "cases"


def _same(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and np.array_equal(a, b, equal_nan=True) and np.array_equal(np.signbit(a), np.signbit(b))


def test_unwrap_equals_numpy():
    rng = np.random.default_rng(11)
    for trial in range(600):
        n = int(rng.integers(1, 40))
        p = np.cumsum(rng.normal(0.0, [0.05, 1.0, 3.5][trial % 3], n))
        if trial % 2:
            p = np.arctan2(np.sin(p), np.cos(p))      # wrapped into (−π, π]
        if trial % 5 == 0:
            p[int(rng.integers(0, n))] = -0.0
        if trial % 13 == 0:
            p[int(rng.integers(0, n))] = math.nan
        assert _same(L.unwrap(p), np.unwrap(p)), p


@pytest.mark.parametrize("case", ["ws000_six_bar.toml", "ws002_tractor_hitch.toml", "whitworth.toml"])
def test_points_formula(case):
    """points_cycle against the formula of its docstring evaluated with numpy (to rounding: numpy's
    sine and cosine need not be the C library's to the last bit)."""
    s = Study(CASES / case)
    m = s.model
    q = s.grid.cycle
    pose, d1, d2, _, _ = L.run_kernel(m, q)
    pts = K.points_cycle(pose, d1, d2, q, m.pbody, m.ploc)
    assert pts.shape == (q.size, len(m.point_names), 6)
    for k, b in enumerate(m.pbody):
        th, w, e = pose[:, b, 2], d1[:, b, 2], d2[:, b, 2]
        c, sn = np.cos(th), np.sin(th)
        px = m.ploc[k, 0] + q * m.ploc[k, 2]
        py = m.ploc[k, 1] + q * m.ploc[k, 3]
        ux, uy = c * px - sn * py, sn * px + c * py
        vx, vy = c * m.ploc[k, 2] - sn * m.ploc[k, 3], sn * m.ploc[k, 2] + c * m.ploc[k, 3]
        want = [pose[:, b, 0] + ux, pose[:, b, 1] + uy, d1[:, b, 0] - uy * w + vx, d1[:, b, 1] + ux * w + vy,
                d2[:, b, 0] - uy * e - ux * w * w - 2.0 * vy * w, d2[:, b, 1] + ux * e - uy * w * w + 2.0 * vx * w]
        for j in range(6):
            scale = max(1.0, float(np.max(np.abs(want[j]))))
            np.testing.assert_allclose(pts[:, k, j], want[j], rtol=0, atol=4e-15 * scale)


def test_grid_evaluation_is_the_cycle():
    """An evaluation on the cycle grid gives the columns of the solved cycle, and those are the
    columns of the grid solved anew (single positions, angles not unwrapped)."""
    s = Study(CASES / "ws000_six_bar.toml")
    d = s.analysis("dynamics")
    q = s.grid.cycle.copy()
    got = d.ev(q)
    fresh = L.columns(s.model, L.solve(s.model, q), grid=False)
    assert list(got) == list(fresh)
    for k in fresh:
        assert _same(got[k], fresh[k]), k


@pytest.mark.parametrize("case", ["ws000_six_bar.toml", "ws002_tractor_hitch.toml", "yoke_pump.toml"])
def test_force_scalars_without_tables(case):
    """Scalars from the few columns they need equal the scalars read from the force tables."""
    light = Study(CASES / case).analysis("forces")
    a = light.scalars
    assert "table" not in light.__dict__ and "cycle" not in light.__dict__
    full = Study(CASES / case).analysis("forces")
    full.tables()
    b = full.scalars
    assert list(a) == list(b)
    for k in a:
        assert a[k] == b[k] or (isinstance(a[k], float) and math.isnan(a[k]) and math.isnan(b[k])), k
