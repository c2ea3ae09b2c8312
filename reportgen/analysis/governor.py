"""``[governor]``: a centrifugal governor (Porter type) in quasi-static equilibrium with friction
circles in its six joints (:mod:`reportgen.core.governor`): the speed ω at which the sleeve starts
to move when the shaft speeds up slowly (or slows down), and the frictionless speed beside it."""
from __future__ import annotations

import math

import pandas as pd

from ..case import units as U
from ..core import governor as CG
from .printed_results import PrintedResults

__all__ = ["Governor"]

KEYS = ["pivot_offset", "sleeve_offset", "arm_rod", "arm_ball", "rod", "angle", "ball_mass", "sleeve_mass",
        "f", "joint_diameter", "g", "speeding", "printed"]
DIMS = {"omega": U.ANGULAR_VELOCITY, "omega_up": U.ANGULAR_VELOCITY, "omega_down": U.ANGULAR_VELOCITY,
        "omega_0": U.ANGULAR_VELOCITY, "R": U.FORCE, "P": U.FORCE, "F_i": U.FORCE, "R76": U.FORCE,
        "rho": U.LENGTH, "alpha": U.ANGLE, "R76_angle": U.ANGLE, "phi_f": U.ANGLE, "r_D": U.LENGTH}
SENSE = {"up": 1, "down": -1}


class Governor(PrintedResults):
    """The governor of the case, solved for speeding up (+1), slowing down (−1), no friction (0)."""

    PREFIX, DIMS = "governor", DIMS

    def __init__(self, study):
        self.study = study
        self.node = node = study.root.table("governor")
        node.check_keys(KEYS)
        p = study.params
        q = lambda k, dim, **kw: node.quantity(k, dim, p, required=True, **kw)
        self.inputs = dict(e_H=q("pivot_offset", U.LENGTH, nonnegative=True),
                           e_B=q("sleeve_offset", U.LENGTH, nonnegative=True),
                           l_HF=q("arm_rod", U.LENGTH, positive=True), l_HD=q("arm_ball", U.LENGTH, positive=True),
                           l_BF=q("rod", U.LENGTH, positive=True), theta=q("angle", U.ANGLE, positive=True))
        if not self.inputs["theta"] < math.pi / 2:
            raise node.error("angle", "рычаг должен висеть ниже шарнира", expected="угол от вертикали 0…90°")
        self.m = q("ball_mass", U.MASS, positive=True)
        self.m2 = q("sleeve_mass", U.MASS, nonnegative=True)
        self.f = q("f", U.DIMENSIONLESS, nonnegative=True)
        self.d = q("joint_diameter", U.LENGTH, nonnegative=True)
        self.g = node.quantity("g", U.ACCELERATION, p, default=9.81, positive=True)
        self.speeding = node.string("speeding", "up", choices=list(SENSE))
        try:
            self.geo = CG.geometry(**self.inputs)
        except ValueError:
            raise node.error("rod", "шатун BF короче горизонтального расстояния от F до муфты",
                             expected="rod > x_F − sleeve_offset") from None
        self.rho = CG.friction_radius(self.f, self.d / 2)
        self.phi_f = math.atan(self.f)
        self.Q = self.m2 * self.g
        self.cases = {s: CG.solve(self.geo, self.Q, self.m, self.g, self.rho, s) for s in (1, 0, -1)}
        self.main = self.cases[SENSE[self.speeding]]

    def results(self) -> dict:
        """The named results of the governor: the friction circle ρ = r sin φ_тр, the rod's turn α,
        the reactions, the centrifugal force F_и = m x_D ω² and ω when speeding up, without
        friction and slowing down."""
        r = self.main
        out = {"rho": self.rho, "phi_f": self.phi_f, "alpha": r["alpha"], "R": r["R"],
               "P": math.hypot(*r["P"]), "F_i": r["F_i"], "R76": math.hypot(*r["R76"]),
               "R76_angle": r["R76_angle"], "omega": r["omega"], "r_D": r["r_D"],
               "omega_up": self.cases[1]["omega"], "omega_0": self.cases[0]["omega"],
               "omega_down": self.cases[-1]["omega"]}
        return out

    def tables(self) -> dict[str, pd.DataFrame]:
        """Export table ``governor``: the reactions, F_и and ω when speeding up, without friction
        and slowing down."""
        rows = []
        for s, name in ((1, "разгон"), (0, "без трения"), (-1, "торможение")):
            r = self.cases[s]
            rows.append({"mode": name, "R": r["R"], "P": math.hypot(*r["P"]), "F_i": r["F_i"],
                         "R76": math.hypot(*r["R76"]), "omega": r["omega"]})
        return {"governor": pd.DataFrame(rows)}
