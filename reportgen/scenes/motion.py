"""φ(t) and ω(t) of the machine by the correct equation of motion and, for the answer key
(``printed=True``), by the source's printed equation as well."""
from __future__ import annotations

import numpy as np

from ..style import mplstyle
from .mechanism import Drawing


class MotionHistory:
    needs = ()

    def draw(self, study, printed: bool = False) -> Drawing:
        h = study.motion.history
        fig = mplstyle.figure(160, 120)
        ax1, ax2 = fig.subplots(2, 1, sharex=True)
        ax1.plot(h["t"], np.degrees(h["phi"]), lw=1.3, label="верное уравнение")
        ax2.plot(h["t"], h["omega"], lw=1.3)
        if printed and "phi_printed" in h:
            ax1.plot(h["t"], np.degrees(h["phi_printed"]), lw=1.0, ls="--", label="уравнение листа")
            ax2.plot(h["t"], h["omega_printed"], lw=1.0, ls="--")
            ax1.legend()
        ax1.set_ylabel("φ, град")
        ax2.set_ylabel("ω, рад/с")
        ax2.set_xlabel("t, с")
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)
