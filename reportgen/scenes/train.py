"""Scenes of the train section: the kinematic scheme in the plane of the axes (radii at scale),
the velocity picture (картина линейных скоростей, треугольники Смирнова) beside it, and the plan
of angular velocities with the graphical ratio.  They draw ``study.train`` results only."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..analysis.train import FRAME, pitch_points
from ..style import mplstyle
from .draw import GREY, INK

__all__ = ["TrainPicture", "train_picture"]

COLORS = ["#b2182b", "#1f4e9c", "#008837", "#7b3294", "#e08214", "#4d4d4d", "#01665e", "#8c510a"]


@dataclass
class TrainPicture:
    fig: object
    segments_mm: dict      # ω plan: member → segment on the paper, mm (to 0,5 mm)
    u_graph: float
    mu_l: float            # mm of the mechanism per mm of the paper (scheme)


def _columns(model):
    """Axial column of every wheel: meshing wheels share a column when one is already placed."""
    col: dict[str, int] = {}
    nxt = 0
    for a, b in model.meshes:
        if a in col or b in col:
            c = col.get(a, col.get(b))
        else:
            c, nxt = nxt, nxt + 1
        col.setdefault(a, c)
        col.setdefault(b, c)
    for w in model.wheels:
        if w not in col:
            col[w], nxt = nxt, nxt + 1
    return col


def train_picture(train) -> TrainPicture:
    m = train.model
    y = train.positions
    w = train.w_willis
    col = _columns(m)
    ncol = max(col.values()) + 1
    fig = mplstyle.figure(170, 150, layout=None)
    ax = fig.add_axes((0.08, 0.30, 0.46, 0.64))
    av = fig.add_axes((0.58, 0.30, 0.40, 0.64), sharey=ax)
    ap = fig.add_axes((0.58, 0.02, 0.40, 0.18))
    dx = 1.0
    colors = {n: COLORS[i % len(COLORS)] for i, n in enumerate(m.members)}
    ytop = max(y[wh.centre] + wh.m * wh.z / 2 for wh in m.wheels.values())
    ybot = min(y[wh.centre] - wh.m * wh.z / 2 for wh in m.wheels.values())
    span = ytop - ybot
    # wheels
    for name, wh in m.wheels.items():
        x = col[name] * dx
        r = wh.m * wh.z / 2
        yc = y[wh.centre]
        c = colors[wh.member]
        if wh.internal:
            for sg in (1, -1):
                ax.plot([x, x], [yc + sg * r, yc + sg * (r - 0.04 * span)], color=c, lw=2.2)
                ax.plot([x - 0.12, x + 0.12], [yc + sg * r] * 2, color=c, lw=1.2)
            ax.plot([x + 0.35, x + 0.35], [yc - r, yc + r], color=c, lw=1.0)
            ax.plot([x, x + 0.35], [yc + r] * 2, color=c, lw=1.0)
            ax.plot([x, x + 0.35], [yc - r] * 2, color=c, lw=1.0)
        else:
            ax.plot([x, x], [yc - r, yc + r], color=c, lw=2.2)
            ax.plot([x - 0.12, x + 0.12], [yc + r] * 2, color=c, lw=1.2)
            ax.plot([x - 0.12, x + 0.12], [yc - r] * 2, color=c, lw=1.2)
        if wh.internal:
            ax.annotate(name, (x, yc - r), xytext=(-10, -11), textcoords="offset points", fontsize=9, color=c)
        else:
            ax.annotate(name, (x, yc + r), xytext=(-10, 2), textcoords="offset points", fontsize=9, color=c)
    # member shafts and carriers
    for mem, axis in m.members.items():
        xs = [col[n] * dx for n, wh in m.wheels.items() if wh.member == mem and wh.centre == axis]
        carried = [a for a, h in m.axes.items() if h == mem]
        c = colors[mem]
        if carried:
            x0 = -0.6 - 0.25 * list(m.members).index(mem) % 1.0
            for a in carried:
                xa = [col[n] * dx for n, wh in m.wheels.items() if wh.centre == a]
                if not xa:
                    continue
                ax.plot([x0, x0], [y[axis], y[a]], color=c, lw=1.6)
                ax.plot([x0, max(xa) + 0.2], [y[a], y[a]], color=c, lw=1.6)
            ax.plot([x0 - 0.4, x0], [y[axis], y[axis]], color=c, lw=1.6)
            ax.annotate(mem, (x0, y[axis]), xytext=(-14, 3), textcoords="offset points", fontsize=9, color=c)
        elif xs:
            ax.plot([min(xs) - 0.3, max(xs) + 0.3], [y[axis], y[axis]], color=c, lw=1.6)
        if mem in m.fixed:
            xf = (min(xs) if xs else 0) + 0.35
            for k in range(4):
                ax.plot([xf + 0.1 * k, xf + 0.1 * k + 0.08], [ybot - 0.02 * span, ybot - 0.06 * span], color=INK, lw=0.8)
            ax.plot([xf, xf + 0.38], [ybot - 0.02 * span] * 2, color=INK, lw=1.0)
    ax.set_xlim(-1.4, ncol * dx + 0.6)
    ax.set_ylim(ybot - 0.1 * span, ytop + 0.06 * span)
    ax.set_xticks([])
    ax.set_ylabel("радиус от центральной оси, мм")
    ax.set_title("Схема механизма", fontsize=10)
    # velocity picture: v(y) of every member over its wheels' y range (per unit ω of the input)
    pp = pitch_points(m)

    def vel(mem, at):
        v = 0.0
        while mem != FRAME:
            axy = y[m.members[mem]]
            v += w[mem] * (at - axy)
            at = axy
            mem = m.axes[m.members[mem]]
        return v

    for mem, axis in m.members.items():
        ys = [y[wh.centre] + s * wh.m * wh.z / 2 for wh in m.wheels.values() if wh.member == mem for s in (-1, 1)]
        ys += [y[a] for a, h in m.axes.items() if h == mem] + [y[axis]]
        lo, hi = min(ys), max(ys)
        yy = np.array([lo, hi])
        av.plot([vel(mem, t) for t in yy], yy, color=colors[mem], lw=1.4, label=f"звено {mem}")
    for (a, b), yp in pp.items():
        vp = vel(m.wheels[a].member, yp)
        av.plot([0, vp], [yp, yp], color=GREY, lw=0.6)
        av.plot([vp], [yp], "o", ms=3, color=INK)
        av.annotate(f"$P_{{{a}{b}}}$", (vp, yp), xytext=(4, 2), textcoords="offset points", fontsize=8)
    for a in set(y.values()):
        av.axhline(a, color=GREY, lw=0.4, ls=":")
    av.axvline(0, color=INK, lw=0.8)
    av.set_xlabel("$v/\\omega_{вх}$, мм")
    av.set_title("Картина линейных скоростей", fontsize=10)
    av.legend(fontsize=7, loc="lower right")
    # plan of angular velocities: rays from the pole parallel to the velocity lines, cut by a base
    # line at the polar distance h; segment ∝ ω.
    wmax = max(abs(v) for v in w.values()) or 1.0
    h = 10.0                                   # polar distance, mm on the paper
    k = 60.0 / (h * wmax)                      # paper mm per unit ω·h, the longest segment 60 mm
    seg = {n: round(h * k * w[n] * 2) / 2 for n in m.members}
    for n in m.members:
        ap.plot([0, seg[n]], [h, 0], color=colors[n], lw=1.2)
        ap.annotate(n, (seg[n], 0), xytext=(0, -10), textcoords="offset points", fontsize=8, color=colors[n],
                    ha="center")
    ap.axhline(0, color=INK, lw=0.8)
    ap.plot([0], [h], "o", ms=3, color=INK)
    ap.annotate("P", (0, h), xytext=(3, 2), textcoords="offset points", fontsize=8)
    ap.set_xlim(-65, 65)
    ap.set_ylim(-6, h + 4)
    ap.axis("off")
    ap.set_title("План угловых скоростей", fontsize=10)
    s_out = seg[m.out]
    u_graph = seg[m.inp] / s_out if s_out else math.inf
    return TrainPicture(fig, seg, u_graph, 1.0)
