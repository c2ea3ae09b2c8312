"""``[cross]``: velocities in the mechanism with a cross-slider (крестовина) at one position and
the force reduced to the input link (:mod:`reportgen.core.cross`)."""
from __future__ import annotations

import math

import pandas as pd

from ..case import units as U
from ..core import cross as CX
from .printed_results import PrintedResults

__all__ = ["Cross"]

KEYS = ["v_A", "slider_angle", "l_O1B", "l_O1O2", "angle_O1", "l_AB", "M", "printed"]
SPEEDS = ("v_B3", "v_B3B2", "v_C3", "v_C5", "v_C4")
DIMS = {**{k: U.VELOCITY for k in SPEEDS}, "w3": U.ANGULAR_VELOCITY, "w5": U.ANGULAR_VELOCITY,
        "F_red": U.FORCE, "l_O1C": U.LENGTH, "l_O2C": U.LENGTH}


class Cross(PrintedResults):
    """The cross-slider mechanism of the case at its one position."""

    PREFIX, DIMS = "cross", DIMS

    def __init__(self, study):
        self.study = study
        self.node = node = study.root.table("cross")
        node.check_keys(KEYS)
        p = study.params
        q = lambda k, dim: node.quantity(k, dim, p, required=True, positive=True)
        self.inputs = dict(v_A=q("v_A", U.VELOCITY), gamma=q("slider_angle", U.ANGLE), l_O1B=q("l_O1B", U.LENGTH),
                           l_O1O2=q("l_O1O2", U.LENGTH), alpha=q("angle_O1", U.ANGLE),
                           M=node.quantity("M", U.MOMENT, p, default=0.0, nonnegative=True))
        self.l_AB = node.quantity("l_AB", U.LENGTH, p, positive=True)
        if not self.inputs["alpha"] < math.pi / 2:
            raise node.error("angle_O1", "угол при O₁ в прямоугольном треугольнике O₁CO₂ должен быть острым",
                             expected="0 < angle_O1 < 90°")
        self.r = CX.solve(**self.inputs)

    def results(self) -> dict:
        """The named results of the crosshead mechanism: the speeds of its velocity plan, ω₃ = ω₅, the
        distances O₁C and O₂C, and with a moment M given the force reduced to the input link by
        equal powers F_пр = M·|ω₅|/V_A (report/sections/cross.py)."""
        keys = (*SPEEDS, "w3", "w5", "l_O1C", "l_O2C") + (("F_red",) if self.inputs["M"] else ())
        return {k: abs(self.r[k]) for k in keys}

    def tables(self) -> dict[str, pd.DataFrame]:
        """Export table ``cross_velocities``: each vector of the velocity plan (V₁, V_B3, V_B3B2,
        V_C3, V_C5, V_C4) by its components and modulus."""
        r = self.r
        rows = [{"vector": k, "vx": r[k][0], "vy": r[k][1], "v": float((r[k] @ r[k]) ** 0.5)}
                for k in ("v1", "vB3", "vB3B2", "vC3", "vC5", "vC4")]
        return {"cross_velocities": pd.DataFrame(rows)}
