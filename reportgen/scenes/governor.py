"""The governor with its friction circles and lines of action (left), the force polygons of the
sleeve and of the arm (right): the construction the worksheet draws, from the analytic forces."""
from __future__ import annotations

import numpy as np
from matplotlib.patches import Circle

from ..style import mplstyle
from .draw import GREY, INK, arrow
from .labels import LabelPlacer, place_on_chart
from .mechanism import Drawing

_FS = 8


def _mirror(p):
    return np.array([-p[0], p[1]])


class GovernorScheme:
    """Scheme of both halves and the force polygons for the speed-up (or slow-down) case."""

    needs = ()

    def draw(self, study) -> Drawing:
        gv = study.governor
        geo, r = gv.geo, gv.main
        H, F, D, B = geo["H"], geo["F"], geo["D"], geo["B"]
        fig = mplstyle.figure(165, 95)
        ax, bx = fig.subplots(1, 2, width_ratios=[1.1, 1])
        points, forces = LabelPlacer(ax, fontsize=_FS), LabelPlacer(bx, fontsize=_FS)   # placed clear of the lines
        for side in (lambda p: p, _mirror):
            h, f_, d, b = side(H), side(F), side(D), side(B)
            ax.plot([h[0], d[0]], [h[1], d[1]], color=INK, lw=1.4)
            ax.plot([f_[0], b[0]], [f_[1], b[1]], color=INK, lw=1.4)
            ax.add_patch(Circle(d, 0.012, fc="0.8", ec=INK, lw=0.9))
            for c in (h, f_, b):
                ax.add_patch(Circle(c, max(gv.rho, 1e-4), fill=False, ec="tab:red", lw=0.7))
        ax.plot([-H[0], H[0]], [0, 0], color=INK, lw=2.0)
        ax.plot([-B[0], B[0]], [B[1], B[1]], color=INK, lw=3.0)
        ax.plot([0, 0], [B[1] - 0.04, 0.05], color=GREY, lw=0.8, ls="-.")
        for name, p, dx in (("H", H, 0.008), ("F", F, 0.01), ("D", D, 0.016), ("B", B, 0.008),
                            ("G", _mirror(H), -0.025), ("E", _mirror(F), -0.028), ("C", _mirror(D), -0.035),
                            ("A", _mirror(B), -0.025)):
            points.add(*p, name, prefer=(dx, 0.006), point=True)
        # lines of action: the rod (tangent to the circles at F and B), R76 through K
        e = r["R36"] / np.hypot(*r["R36"])
        p0 = r["rod_point"]
        ax.plot([p0[0] - 0.03 * e[0], p0[0] + 0.2 * e[0]], [p0[1] - 0.03 * e[1], p0[1] + 0.2 * e[1]],
                color="tab:blue", lw=0.7, ls="--")
        K, e76 = r["K"], r["R76"] / np.hypot(*r["R76"])
        ax.plot([K[0] - 0.2 * e76[0], K[0] + 0.05 * e76[0]], [K[1] - 0.2 * e76[1], K[1] + 0.05 * e76[1]],
                color="tab:green", lw=0.7, ls="--")
        ax.plot([r["Q_point"][0], K[0]], [r["Q_point"][1], K[1]], color="tab:purple", lw=0.7, ls="--")
        ax.plot([D[0], K[0]], [D[1], K[1]], color=GREY, lw=0.6, ls=":")
        ax.plot(*K, "o", ms=2.5, color=INK)
        points.add(*K, "K", prefer=(0.006, -0.02), point=True)
        ax.set_aspect("equal")
        ax.set_xlabel("x, м")
        ax.set_ylabel("y, м")
        # force polygons: sleeve (Q, R32, R42) and arm (G, R36, F_i, R76)
        Q = np.array([0.0, -gv.Q])
        R32 = -r["R23"]
        R42 = _mirror(R32)
        off = np.array([min(r["R36"][0], 0.0) - abs(R32[0]) - 0.15 * gv.Q, 0.0])
        pts = [off, off + Q, off + Q + R32, off + Q + R32 + R42]
        for (p, q), lab in zip(zip(pts, pts[1:]), ("Q", "R₃₂", "R₄₂")):
            arrow(bx, *p, *q, color="tab:gray")
            forces.add(*(0.5 * (p + q)), lab, prefer=(1, 0), color="tab:gray")
        vecs = [("G", r["G"]), ("R₃₆", r["R36"]), ("Fи", np.array([r["F_i"], 0.0])), ("R₇₆", r["R76"])]
        p = np.zeros(2)
        for lab, v in vecs:
            arrow(bx, *p, *(p + v), color=INK)
            forces.add(*(p + 0.5 * v), lab, prefer=(1, 1))
            p = p + v
        arrow(bx, 0, 0, *r["P"], color="tab:purple", ls="--")
        forces.add(*(0.5 * r["P"]), "P", prefer=(-12, -4), color="tab:purple")
        bx.set_aspect("equal")
        bx.set_xlabel("Fx, Н")
        bx.set_ylabel("Fy, Н")
        bx.margins(0.12)            # room round the polygons for their labels
        bx.autoscale_view()
        place_on_chart(points)
        forces.place()
        return Drawing(mplstyle.to_svg(fig), 165, 0.0)
