"""Class III groups near their singular configuration (issue #11, item 3).

* the equivalent transmission angle of a group solved in body coordinates
  (``linkage.equivalent_transmission_sine``: Hadamard ratio of the angle columns of Φ_x projected off
  the translation columns) equals the transmission angle μ of a ВВВ dyad to rounding, so the class III
  measure is judged by the same thresholds (singular below sin μ = 10⁻⁶, low below 40°);
* the triad of class3_triad.toml 10⁻⁷ m above its limit length (on its far assembly) is flagged
  (``Study.flags["mu_2_3_4_5"]``: low, μ_min ≈ 0,005°, at q ≈ 205,6°); the case's own triad is not
  singular (μ_min ≈ 34,6°, μ_max ≈ 39,0°: by the 40° rule the whole cycle of this triad is «low»);
* analogs compared with the 50-digit reference: accurate (10⁻¹² first, 10⁻¹¹ second) at the
  best-conditioned position of the case's triad, and at the flagged position of the near-limit
  triad inaccurate only where flagged;
* the first assembly is the one the sketch draws: l_AB = 0,5007182565616336 m and 0,5017 m with the
  case's sketch (C at x = 0,9 when q = 0) start at x_C = 0,900, not at the far assembly (1,445).
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from reportgen.analysis import linkage as L
from reportgen.analysis.study import Study
from reportgen.case.load import CaseSpec
from reportgen.core import kinematics as K
from tests.reference import reference_columns, scaled_errors

ROOT = Path(__file__).resolve().parents[1]
TRIAD = ROOT / "cases" / "class3_triad.toml"
TRIAD_LIMIT = 0.5007181565616337          # on the far assembly (tests/test_stress_families.py)
FAR_SKETCH = {"B": [1.173, -0.336], "C": [1.445, -0.573], "D": [1.502, -0.126]}


def _triad(l_ab: float, sketch: dict | None = None) -> Study:
    data = tomllib.loads(TRIAD.read_text(encoding="utf-8"))
    data["parameters"]["l_AB"] = f"{l_ab!r} m"
    if sketch is not None:
        data["sketch"]["points"] = sketch
    return Study(CaseSpec(Path("variant.toml"), data))


def test_equivalent_measure_is_the_dyad_transmission_angle():
    s = Study(ROOT / "cases" / "ws000_six_bar.toml")
    m, res = s.model, s._cycle_solution
    checked = 0
    for g, grp in enumerate(m.groups):
        if m.gkind[g] != K.G_RRR:
            continue
        h = L.equivalent_transmission_sine(m, res, g)
        assert np.abs(h - np.abs(res.quality[:, g])).max() <= 1e-12
        checked += 1
    assert checked >= 1


def test_equivalent_measure_against_a_qr_formulation():
    """Second formulation: complete QR of the translation columns (numpy), determinant of the projected
    angle columns, against the kernel's Gram–Schmidt."""
    s = Study(TRIAD)
    m, res = s.model, s._cycle_solution
    g = [k for k in range(len(m.groups)) if m.gkind[k] == K.G_NEWTON][0]
    nbg = int(m.gnb[g])
    J = K.group_jacobians(res.q, res.pose, m.jt, m.jb, m.jf, m.gjoint[g], m.gnj[g], m.gbody[g], m.gnb[g], m.size)
    ang = np.arange(3 * nbg) % 3 == 2
    Q, _ = np.linalg.qr(J[:, :, ~ang], mode="complete")
    Rp = np.matmul(np.swapaxes(Q[:, :, 2 * nbg:], 1, 2), J[:, :, ang])
    h = np.abs(np.linalg.det(Rp)) / np.prod(np.linalg.norm(Rp, axis=1), axis=1)
    assert np.abs(h - L.equivalent_transmission_sine(m, res, g)).max() <= 1e-12


@pytest.fixture(scope="module")
def near():
    return _triad(TRIAD_LIMIT + 1e-7, FAR_SKETCH)


def test_near_limit_triad_is_flagged(near):
    fl = near.flags["mu_2_3_4_5"]
    assert fl["low"] and not fl["singular"]
    assert fl["min"] < math.radians(0.05)
    assert abs(math.degrees(fl["q_min"]) - 205.6) < 0.5
    assert np.isfinite(near.cycle["mu_2_3_4_5"]).all()
    assert near.scalars["mu_2_3_4_5_min"] == fl["min"]


def test_regular_triad_is_not_singular():
    fl = Study(TRIAD).flags["mu_2_3_4_5"]
    assert not fl["singular"]
    assert fl["min"] > math.radians(30.0)


def _errors_at(study: Study, i: int) -> dict:
    q = [float(study.cycle["q"].iloc[i])]
    return scaled_errors(study.at(q), reference_columns(study, q))


def test_analogs_accurate_where_not_flagged():
    s = Study(TRIAD)
    mu = s.cycle["mu_2_3_4_5"].to_numpy()
    i = int(np.argmax(mu))
    assert mu[i] >= math.radians(35.0)
    worst = _errors_at(s, i)
    assert worst["position"][0] <= 1e-12
    assert worst["first"][0] <= 1e-12 and worst["second"][0] <= 1e-11


def test_analogs_near_the_singular_position_accurate_or_flagged(near):
    i = int(np.argmin(near.cycle["mu_2_3_4_5"].to_numpy()))
    worst = _errors_at(near, i)
    assert worst["position"][0] <= 1e-11
    if worst["first"][0] > 1e-12 or worst["second"][0] > 1e-11:
        fl = near.flags["mu_2_3_4_5"]
        assert fl["low"] and fl["q_min"] == float(near.cycle["q"].iloc[i])


@pytest.mark.parametrize("l_ab", [0.5007182565616336, 0.5017])
def test_first_assembly_is_the_sketched_one(l_ab):
    s = _triad(l_ab)
    cyc = s.cycle
    assert abs(cyc["x_C"].iloc[0] - 0.900) < 1e-3
    assert abs(cyc["y_C"].iloc[0] + 0.21) < 0.02
    for c in cyc.columns:                       # one branch over the whole turn
        if c.startswith(("x_", "y_")):
            assert abs(cyc[c].iloc[-1] - cyc[c].iloc[0]) <= 1e-9, c
