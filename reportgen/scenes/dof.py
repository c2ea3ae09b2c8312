"""Structure graphs of a mechanism before and after replacing its higher pairs: links as circles
(the frame hatched-grey), lower pairs as solid edges, higher pairs dashed, replacing links and their
pairs in colour, passive rollers marked."""
from __future__ import annotations

import math

from matplotlib.patches import Circle

from ..style import mplstyle
from .draw import INK
from .mechanism import Drawing

_FS = 8


def _layout(n: int) -> dict[int, tuple[float, float]]:
    """The frame below, the moving links on an arc above it."""
    pos = {0: (0.0, -1.3)}
    for k in range(1, n + 1):
        a = math.pi * (1.0 - (k - 1) / max(n - 1, 1))
        pos[k] = (1.4 * math.cos(a), -0.45 + 1.5 * math.sin(a))
    return pos


def _graph(ax, n, pairs, names, rollers, new, title):
    pos = _layout(n)
    for (i, j, t), nm in zip(pairs, names):
        (x0, y0), (x1, y1) = pos[i], pos[j]
        col = "tab:green" if i in new or j in new or nm.endswith("′") else INK
        ax.plot([x0, x1], [y0, y1], color="tab:red" if t == "H" else col, lw=1.2, ls="--" if t == "H" else "-", zorder=1)
        mx, my = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        if i and j:                      # between moving links: the label outside the arc
            r = math.hypot(mx, my + 0.45)
            mx, my = mx * (1 + 0.2 / r), -0.45 + (my + 0.45) * (1 + 0.2 / r)
        ax.text(mx, my, f"{nm} ({t})", fontsize=_FS - 1, ha="center", va="center",
                bbox=dict(fc="white", ec="none", pad=0.5), zorder=2)
    for k, (x, y) in pos.items():
        fc = "0.8" if k == 0 else ("#cfe8cf" if k in new else ("#f6d5d5" if k in rollers else "white"))
        ax.add_patch(Circle((x, y), 0.17, fc=fc, ec=INK, lw=1.0, zorder=3))
        ax.text(x, y, str(k), fontsize=_FS, ha="center", va="center", zorder=4)
    ax.set_title(title, fontsize=_FS + 1)
    ax.set_aspect("equal")
    ax.set_xlim(-1.6, 1.6)
    ax.set_ylim(-1.6, 1.3)
    ax.axis("off")


class DofGraphs:
    """Before (with the higher pairs and rollers) and after the replacement."""

    needs = ()

    def draw(self, study) -> Drawing:
        d = study.dof
        fig = mplstyle.figure(165, 80)
        ax, bx = fig.subplots(1, 2)
        _graph(ax, d.n, d.pairs, d.names, d.rollers, [], f"до замены: W = {d.before['W']}")
        names_after = d.names_after
        _graph(bx, d.n_after, d.pairs_after, names_after, [], d.new_links + d.rollers,
               f"после замены: W = {d.after['W']}")
        return Drawing(mplstyle.to_svg(fig), 165, 0.0)
