"""The energy diagram of a machine given by energy: the running excess work E(φ) of the
turning-moment table (with M(φ) and M_ср), or the running sums of the loop areas."""
from __future__ import annotations

import numpy as np

from ..style import mplstyle
from .mechanism import Drawing


class EnergyDiagram:
    """E(φ) (and M(φ)) or E by loops, with ΔE_max marked."""

    needs = ()

    def draw(self, study) -> Drawing:
        m = study.machine
        if m.table is not None:
            t = m.table
            fig = mplstyle.figure(160, 120)
            ax1, ax2 = fig.subplots(2, 1, sharex=True)
            ax1.plot(np.degrees(t["x"]), t["M"], lw=1.3)
            ax1.axhline(t["M_mean"], color="0.3", lw=0.8, ls="--")
            ax1.set_ylabel("M, Н·м")
            ax2.plot(np.degrees(t["phi"]), t["E"], lw=1.3)
            ax2.set_ylabel("ΔE, Дж")
            ax2.set_xlabel("φ, град")
            e = t["E"]
        else:
            e = m.E_run
            fig = mplstyle.figure(160, 80)
            ax2 = fig.subplots(1, 1)
            ax2.plot(np.arange(len(e)), e, "o-", lw=1.3, ms=3)
            ax2.set_xlabel("номер петли")
            ax2.set_ylabel("ΔE, Дж")
            ax2.set_xticks(np.arange(len(e)))
        for y in (e.max(), e.min()):
            ax2.axhline(y, color="0.5", lw=0.6, ls=":")
        ax2.axhline(0, color="0.3", lw=0.6)
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)
