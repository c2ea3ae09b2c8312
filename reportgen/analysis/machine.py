"""``[machine]``: a machine given only by energy (no linkage needed) and its flywheel.

The maximum fluctuation of energy ΔE_max comes from ``dE``, ``C_E``·``work``, the loop areas of
the turning-moment diagram (``loops``) or a table M(φ) (``moment``); with δ and the speed the
flywheel is J = ΔE_max/(δ·ω_ср²) (:mod:`reportgen.core.machine`); the inverse task (``J_fly``
or ``fly_mass`` and ``fly_radius``) gives δ = ΔE_max/(J·ω_ср²).  The mean power is
N = A/t_ц with the work per cycle A and the cycle time t_ц."""
from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..case import units as U
from ..core import machine as CM
from .loads import read_table
from .printed_results import PrintedResults

__all__ = ["Machine"]

KEYS = ["dE", "C_E", "work", "loops", "moment", "n", "omega_m", "n_max", "omega_max", "delta", "J_fly",
        "fly_mass", "fly_radius", "J_O", "cycle_time", "rate", "printed"]
DIMS = {"dE": U.ENERGY, "work": U.ENERGY, "omega_m": U.ANGULAR_VELOCITY, "omega_max": U.ANGULAR_VELOCITY,
        "omega_min": U.ANGULAR_VELOCITY, "J": U.INERTIA, "J_fly": U.INERTIA, "J_O": U.INERTIA,
        "power": U.POWER, "cycle_time": U.TIME, "M_mean": U.MOMENT}


def _one_of(node, keys, what):
    given = [k for k in keys if node.has(k)]
    if len(given) != 1:
        raise node.error(None, "нужно задать ровно один из ключей: " + ", ".join(keys), expected=what)
    return given[0]


class Machine(PrintedResults):
    """The energy-only machine of the case."""

    PREFIX, DIMS = "machine", DIMS

    def __init__(self, study):
        self.study = study
        self.node = node = study.root.table("machine")
        node.check_keys(KEYS)
        p = study.params
        self.source = src = _one_of(node, ["dE", "C_E", "loops", "moment"],
                                    "наибольшее изменение кинетической энергии: dE, C_E с work, loops или moment")
        self.work = node.quantity("work", U.ENERGY, p, positive=True) if node.has("work") else None
        self.E_run = None
        self.table = None
        if src == "dE":
            self.dE = node.quantity("dE", U.ENERGY, p, positive=True)
        elif src == "C_E":
            if self.work is None:
                raise node.error("work", "для C_E нужна работа за цикл", expected='work = "12 kJ"')
            self.dE = node.quantity("C_E", U.DIMENSIONLESS, p, positive=True) * self.work
        elif src == "loops":
            raw = node.raw("loops")
            if not isinstance(raw, list) or len(raw) < 2:
                raise node.error("loops", "ожидался список площадей петель", expected='loops = ["+1.2 kJ", "-0.8 kJ", …]')
            areas = [node.eval_value(v, f"loops[{i}]", U.ENERGY, p) for i, v in enumerate(raw)]
            scale = max(abs(a) for a in areas)
            if abs(sum(areas)) > 1e-9 * scale:
                raise node.error("loops", "сумма площадей петель за цикл не равна нулю",
                                 expected="петли над и под линией среднего момента, сумма = 0",
                                 got=f"{sum(areas):.6g} Дж")
            self.dE, self.E_run = CM.fluctuation_from_loops(areas)
            self.areas = areas
        else:
            mn = node.table("moment")
            mn.check_keys(["table", "units"], required=["table"])
            tab = read_table(mn, "table", U.ANGLE, U.MOMENT, mn.raw("units"), p)
            self.table = CM.fluctuation_from_table(tab.x, tab.y)
            self.table["x"], self.table["M"] = tab.x, tab.y
            self.dE = self.table["dE"]
            if self.work is None:
                self.work = abs(self.table["work"])
        sp = _one_of(node, ["n", "omega_m", "n_max", "omega_max"], "средняя (n, omega_m) или наибольшая "
                     "(n_max, omega_max) скорость вала маховика")
        w = node.quantity(sp, U.ANGULAR_VELOCITY, p, positive=True)
        inverse = any(node.has(k) for k in ("J_fly", "fly_mass", "fly_radius"))
        self.J_O = node.quantity("J_O", U.INERTIA, p, default=0.0, nonnegative=True)
        if inverse:
            if node.has("delta"):
                raise node.error("delta", "задан и маховик, и δ", expected="либо delta, либо J_fly (fly_mass и fly_radius)")
            if node.has("J_fly"):
                Jf = node.quantity("J_fly", U.INERTIA, p, positive=True)
            else:
                Jf = (node.quantity("fly_mass", U.MASS, p, required=True, positive=True)
                      * node.quantity("fly_radius", U.LENGTH, p, required=True, positive=True) ** 2)
            J = Jf + self.J_O
            if sp in ("n", "omega_m"):
                wm = w
            else:   # ω_max given: ΔE = ½J(ω_max² − ω_min²) → ω_min = √(ω_max² − 2ΔE/J)
                disc = w * w - 2 * self.dE / J
                if disc <= 0:
                    raise node.error("J_fly", "маховик слишком мал: энергии ΔE не хватает", expected="больший J")
                wm = 0.5 * (w + math.sqrt(disc))
            self.delta = CM.inverse_delta(self.dE, J, wm)
        else:
            self.delta = node.quantity("delta", U.DIMENSIONLESS, p, required=True, positive=True)
            if not self.delta < 2:
                raise node.error("delta", "δ должен быть меньше 2", expected="например delta = 0.1")
        kw = {"omega_m": w} if sp in ("n", "omega_m") else {"omega_max": w}
        if inverse and sp not in ("n", "omega_m"):
            kw = {"omega_m": wm}
        self.omega_m, self.omega_max, self.omega_min = CM.speeds(self.delta, **kw)
        self.J = CM.flywheel_J(self.dE, self.delta, self.omega_m)
        self.J_fly = self.J - self.J_O
        if node.has("cycle_time") and node.has("rate"):
            raise node.error("rate", "время цикла задано дважды", expected="либо cycle_time, либо rate")
        self.cycle_time = (node.quantity("cycle_time", U.TIME, p, positive=True) if node.has("cycle_time") else
                           1.0 / node.quantity("rate", U.FREQUENCY, p, positive=True) if node.has("rate") else None)
        self.power = (self.work / self.cycle_time if self.work is not None and self.cycle_time else None)

    def results(self) -> dict:
        """The named results of the machine's flywheel: ΔE_max, δ, ω_ср, ω_max, ω_min, J = ΔE/(δ
        ω_ср²), the flywheel's J, the mean moment, the work, the cycle time and the power."""
        out = {"dE": self.dE, "delta": self.delta, "omega_m": self.omega_m, "omega_max": self.omega_max,
               "omega_min": self.omega_min, "J": self.J, "J_fly": self.J_fly, "J_O": self.J_O}
        if self.table is not None:
            out["M_mean"] = self.table["M_mean"]
        for k in ("work", "cycle_time", "power"):
            if getattr(self, k) is not None:
                out[k] = getattr(self, k)
        return out

    def tables(self) -> dict[str, pd.DataFrame]:
        """Export table ``machine_energy``: E(φ) of the turning-moment table, or the energy after
        each loop."""
        if self.table is not None:
            t = self.table
            return {"machine_energy": pd.DataFrame({"phi": t["phi"], "E": t["E"]})}
        if self.E_run is not None:
            return {"machine_energy": pd.DataFrame({"loop": np.arange(len(self.E_run)), "E": self.E_run})}
        return {}
