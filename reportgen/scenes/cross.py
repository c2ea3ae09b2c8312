"""The mechanism with a cross-slider at its position (left) and its plan of velocities (right)."""
from __future__ import annotations

import numpy as np
from matplotlib.patches import Rectangle

from ..style import mplstyle
from .draw import GREY, INK, arrow
from .labels import LabelPlacer, place_on_chart
from .mechanism import Drawing

_FS = 8


class CrossScheme:
    """Scheme (rockers 3 and 5 through O₁, O₂, the cross at C, the slider at B) and velocity plan."""

    needs = ()

    def draw(self, study) -> Drawing:
        cx = study.cross
        r = cx.r
        O1, O2, B, C = r["O1"], r["O2"], r["B"], r["C"]
        d = float(np.hypot(*O2))
        fig = mplstyle.figure(165, 85)
        ax, bx = fig.subplots(1, 2)
        points, plan = LabelPlacer(ax, fontsize=_FS), LabelPlacer(bx, fontsize=_FS)    # placed clear of the lines
        ax.plot([B[0] * 1.2, C[0] * 1.25], [B[1] * 1.2, C[1] * 1.25], color=INK, lw=1.4)       # rocker 3
        e5 = (C - O2) / np.hypot(*(C - O2))
        ax.plot([O2[0], C[0] + 0.25 * d * e5[0]], [O2[1], C[1] + 0.25 * d * e5[1]], color=INK, lw=1.4)  # rocker 5
        e1 = r["v1"] / np.hypot(*r["v1"])
        s = 0.35 * d
        ax.plot([B[0] - s * e1[0], B[0] + s * e1[0]], [B[1] - s * e1[1], B[1] + s * e1[1]], color=GREY, lw=0.8, ls="--")
        if cx.l_AB:
            A = B + cx.l_AB * e1
            ax.plot([B[0], A[0]], [B[1], A[1]], color=INK, lw=2.2)
            points.add(*A, "A", prefer=(1, 0), point=True)
        w = 0.05 * d
        for p in (B, C):
            ax.add_patch(Rectangle((p[0] - w / 2, p[1] - w / 2), w, w, fill=False, ec=INK, lw=1.0))
        for name, p in (("O₁", O1), ("O₂", O2), ("B", B), ("C", C)):
            ax.plot(*p, "o", ms=3, color=INK)
            points.add(*p, name, prefer=(0.03, -0.06), point=True)
        ax.set_aspect("equal")
        ax.set_xlabel("x, м")
        ax.set_ylabel("y, м")
        # the plan of velocities from the pole p
        z = np.zeros(2)
        for a, b, lab, col in ((z, r["v1"], "b₂", INK), (z, r["vB3"], "b₃", INK), (r["v1"], r["vB3"], "", GREY),
                               (z, r["vC3"], "c₃", INK), (z, r["vC5"], "c₅", INK), (z, r["vC4"], "c₄", "tab:red"),
                               (r["vC3"], r["vC4"], "", GREY), (r["vC5"], r["vC4"], "", GREY)):
            arrow(bx, *a, *b, color=col)
            if lab:
                plan.add(*b, lab, prefer=b, point=True, color=col)
        plan.add(0, 0, "p", prefer=(-1, 0), point=True)
        bx.set_aspect("equal")
        bx.set_xlabel("Vx, м/с")
        bx.set_ylabel("Vy, м/с")
        bx.margins(0.12)            # room round the plan for its labels
        bx.autoscale_view()
        place_on_chart(points)
        plan.place()
        return Drawing(mplstyle.to_svg(fig), 165, 0.0)
