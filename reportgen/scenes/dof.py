"""Structure graphs of a mechanism before and after replacing its higher pairs: links as circles
(the frame hatched-grey), lower pairs as solid edges, higher pairs dashed, replacing links and their
pairs in colour, passive rollers marked."""
from __future__ import annotations

import math

from matplotlib.patches import Circle

from ..style import mplstyle
from .draw import INK
from .labels import LabelPlacer, place_on_chart
from .mechanism import Drawing

_FS = 8
_NODE_R = 0.17          # a link's circle


def _layout(n: int) -> dict[int, tuple[float, float]]:
    """The frame below, the moving links on an arc above it."""
    pos = {0: (0.0, -1.3)}
    for k in range(1, n + 1):
        a = math.pi * (1.0 - (k - 1) / max(n - 1, 1))
        pos[k] = (1.4 * math.cos(a), -0.45 + 1.5 * math.sin(a))
    return pos


def _graph(ax, n, pairs, names, rollers, new, title) -> LabelPlacer:
    """One graph; the pairs' labels are registered with the returned placer (placed beside
    their edges once the figure's layout is done), the edges end at the links' circles."""
    pos = _layout(n)
    labels = LabelPlacer(ax, fontsize=_FS - 1)
    for (i, j, t), nm in zip(pairs, names):
        (x0, y0), (x1, y1) = pos[i], pos[j]
        col = "tab:green" if i in new or j in new or nm.endswith("′") else INK
        u = _NODE_R / max(math.hypot(x1 - x0, y1 - y0), 1e-12)
        ax.plot([x0 + u * (x1 - x0), x1 - u * (x1 - x0)], [y0 + u * (y1 - y0), y1 - u * (y1 - y0)],
                color="tab:red" if t == "H" else col, lw=1.2, ls="--" if t == "H" else "-", zorder=1)
        mx, my = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        out = (mx, my + 0.45) if i and j else (-(y1 - y0), x1 - x0)    # outside the arc / beside the edge
        labels.add(mx, my, f"{nm} ({t})", prefer=out)
    for k, (x, y) in pos.items():
        fc = "0.8" if k == 0 else ("#cfe8cf" if k in new else ("#f6d5d5" if k in rollers else "white"))
        ax.add_patch(Circle((x, y), _NODE_R, fc=fc, ec=INK, lw=1.0, zorder=3))
        ax.text(x, y, str(k), fontsize=_FS, ha="center", va="center", zorder=4)
    ax.set_title(title, fontsize=_FS + 1)
    ax.set_aspect("equal")
    ax.set_xlim(-1.6, 1.6)
    ax.set_ylim(-1.6, 1.3)
    ax.axis("off")
    return labels


class DofGraphs:
    """Before (with the higher pairs and rollers) and after the replacement."""

    needs = ()

    def draw(self, study) -> Drawing:
        d = study.dof
        fig = mplstyle.figure(165, 80)
        ax, bx = fig.subplots(1, 2)
        before = _graph(ax, d.n, d.pairs, d.names, d.rollers, [], f"до замены: W = {d.before['W']}")
        names_after = d.names_after
        after = _graph(bx, d.n_after, d.pairs_after, names_after, [], d.new_links + d.rollers,
                       f"после замены: W = {d.after['W']}")
        place_on_chart(before)
        after.place()
        return Drawing(mplstyle.to_svg(fig), 165, 0.0)


class ZeroSpeedScene:
    """The output part of the mechanism at the first position where the output stops while the
    slotted link moves: the links drawn to a ГОСТ 2.302 scale, OM dashed, the slot ML, the right
    angle at M, and the velocity V̄_M1 ⊥ OM with the block's relative velocity V̄_M6M1 = −V̄_M1
    along the slot (arrows of equal length, per unit ω₁ at an arbitrary scale)."""

    needs = ("dof",)

    def draw(self, study) -> Drawing:
        import numpy as np

        from .draw import Canvas, arrow, draw_mechanism, mechanism_points
        d = study.dof
        zs, z = d.zero_spec, d.zero
        mech = study.mechanism
        row = study.at([float(z["q"].iloc[0])]).iloc[0]
        xs, ys = mechanism_points(mech, [row])
        M, L, O = zs["point"], zs["line"], zs["pivot"]
        slider = zs["joint"].links[1]
        m = np.array([row["x_" + M], row["y_" + M]])
        lpt = np.array([row["x_" + L], row["y_" + L]])
        o = np.array([row["x_" + O], row["y_" + O]])
        om = float(np.linalg.norm(m - o))
        v1 = np.array([z["vqx_M1"].iloc[0], z["vqy_M1"].iloc[0]])
        v1 = v1 / float(np.linalg.norm(v1)) * 0.6 * om
        ends = [m + v1, m - v1]
        xs += [p[0] for p in ends]
        ys += [p[1] for p in ends]
        cv = Canvas.fit(xs, ys, avail_w=140, avail_h=120, margin_mm=14, gost=True)
        draw_mechanism(cv, mech, row, color=INK, lw=1.4, zorder=3)
        ax = cv.ax
        ax.plot([o[0], m[0]], [o[1], m[1]], ls=(0, (5, 3)), lw=0.9, color=INK, zorder=6)
        # right-angle mark at M between MO and ML
        u = (o - m) / om
        w = (lpt - m) / float(np.linalg.norm(lpt - m))
        r = cv.mm(6.0)
        sq = [m + r * u, m + r * (u + w), m + r * w]
        ax.plot([p[0] for p in sq], [p[1] for p in sq], lw=0.9, color=INK, zorder=6)
        arrow(ax, m[0], m[1], *(m + v1), color="tab:blue", lw=1.3, zorder=5)
        arrow(ax, m[0], m[1], *(m - v1), color="tab:red", lw=1.3, zorder=5)
        k = zs["link"]
        cv.labels.add(*(m + v1), f"$V_{{{M}{k}}}$", prefer=tuple(v1 / np.linalg.norm(v1)), color="tab:blue", fontsize=10)
        cv.labels.add(*(m - v1), f"$V_{{{M}{slider}{M}{k}}}$", prefer=tuple(-v1 / np.linalg.norm(v1)), color="tab:red",
                      fontsize=10)
        return Drawing(cv.svg(), cv.width_mm, cv.mu)
