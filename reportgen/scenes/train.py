"""Scenes of the train section: the kinematic scheme in the plane of the axes (radii at scale,
symmetric about the central axis as in the textbooks: every element off the axis is drawn with its
mirror image), the velocity picture (картина линейных скоростей) beside it, the plan of angular
velocities of the whole train, and the stage plans giving the graphical ratio (each stage's plan
at its own scale, u = product of the stage ratios read off the drawings).  They draw
``study.train`` results only."""
from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass

import numpy as np
from matplotlib.colors import to_hex
from matplotlib.figure import Figure

from ..analysis.train import FRAME, pitch_points, ratio_chain
from ..style import mplstyle
from ..style.numbers import fmt
from .draw import GREY, INK
from .labels import LabelPlacer, tex_point

__all__ = ["TrainPicture", "train_picture", "StagePlans", "stage_plans", "declutter", "text_overlaps"]

COLORS = ["#b2182b", "#1f4e9c", "#008837", "#7b3294", "#e08214", "#4d4d4d", "#01665e", "#8c510a"]


PLAN_MM = 140.0            # width of a stage plan's segments on the paper, mm
READ_MM = 0.5              # a segment is read off the drawing to 0,5 mm


@dataclass
class TrainPicture:
    fig: object
    segments_mm: dict      # ω plan of the whole train: member → segment on the paper, mm (to 0,5 mm)
    mu_l: float            # mm of the mechanism per mm of the paper (scheme)


SHORT_MM = 20.0           # a segment shorter than this is read on a horizontal farther from the pole
DEPTH_MAX = 8              # … at most this many polar distances away
POLE_MM = 12.0             # polar distance of the plans' first horizontal, mm


@dataclass
class StagePlans:
    fig: object
    stages: list           # (member a, member b, segment a, segment b) in mm read to 0,5 mm
    u_graph: float         # product of the stage ratios
    depths: list = None    # per stage (f_a, f_b): the segment is read at f·h from the pole (h = POLE_MM)


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


def _renderer(fig):
    if not hasattr(fig.canvas, "get_renderer"):
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        FigureCanvasAgg(fig)
    return fig.canvas.get_renderer()


def text_overlaps(fig, texts) -> list[tuple[str, str]]:
    """Pairs of the given texts whose rendered bounding boxes overlap (display coordinates)."""
    r = _renderer(fig)
    boxes = [(t.get_text(), t.get_window_extent(r)) for t in texts if t.get_visible() and t.get_text()]
    return [(a, c) for i, (a, b) in enumerate(boxes) for c, d in boxes[i + 1:] if b.overlaps(d)]


def declutter(fig, texts, pad_pt: float = 1.0) -> None:
    """Move annotation labels apart: each label in turn is tried at growing distances (multiples
    of its height up and down, of its width right and left) until its rendered box overlaps none
    placed before it (nor an axes title)."""
    r = _renderer(fig)
    placed = [a.title.get_window_extent(r) for a in fig.axes if a.title.get_text()]
    px = fig.dpi / 72.0
    for t in texts:
        x0, y0 = t.xyann
        bb = t.get_window_extent(r)
        sy, sx = bb.height / px + pad_pt, bb.width / px + pad_pt
        tries = [(0.0, 0.0)] + [(dx * sx * n, dy * sy * n) for n in range(1, 16)
                                for dx, dy in ((0, 1), (0, -1), (1, 0), (-1, 0))]
        for dx, dy in tries:
            t.xyann = (x0 + dx, y0 + dy)
            bb = t.get_window_extent(r).padded(pad_pt * px / 2)
            if not any(bb.overlaps(q) for q in placed):
                break
        placed.append(bb)


def _name(member: str) -> str:
    """A member's label in textbook notation: H1 → H₁ (a letter with its index as a subscript);
    names of another shape (1, 2′, sun) as written, the case's «2'» with the prime «2′»."""
    return tex_point(member) if re.fullmatch(r"[A-Za-z]+\d+", member) else member.replace("'", "′")


def _images(m, y, axis) -> tuple[int, ...]:
    """Images of an element on ``axis``: an axis carried by a carrier (a satellite's) off the
    central axis is drawn at y and mirrored at −y (the k satellites shown by two, as in the
    textbooks); an axis on the frame has one image: a parallel shaft of a simple stage off the
    central axis is a single shaft, not mirrored."""
    if abs(y[axis]) <= 1e-9 or m.depth(axis) == 0:
        return (1,)
    return (1, -1)


def _bearing(ax, x: float, dx: float, R: float, color) -> None:
    """A shaft's support in the frame on the central axis (ГОСТ 2.770-68, подшипник радиальный,
    simplified): two short bars along the shaft on both sides of it, from each a post to the
    frame's hatched line — symmetric about the axis, as the whole scheme."""
    b, half, e, w = 0.03 * R, 0.1 * dx, 0.07 * R, 0.15 * dx
    for s in (1, -1):
        ax.plot([x - half, x + half], [s * b, s * b], color=color, lw=1.4)
        y0 = s * (b + e)
        ax.plot([x, x], [s * b, y0], color=INK, lw=1.0)
        ax.plot([x - w, x + w], [y0, y0], color=INK, lw=1.0)
        for k in range(3):
            x1 = x - w + 0.1 * dx * k
            ax.plot([x1, x1 + 0.1 * dx], [y0, y0 + s * 0.1 * dx], color=INK, lw=0.8)


def scheme_crossings(ax, colors) -> list[tuple]:
    """Where a vertical line of a member (a wheel, a ring's disc, a carrier's arm) crosses a
    horizontal line of another member (a shaft, an axle, a rim) in the scheme, except a wheel on
    its own axle at its centre (the middle of its line): (x, y) of each crossing."""
    own = {to_hex(c): mem for mem, c in colors.items()}
    vert, hor = [], []
    for ln in ax.get_lines():
        mem = own.get(to_hex(ln.get_color()))
        xs, ys = ln.get_data()
        if mem is None or len(xs) != 2:
            continue
        (x0, x1), (y0, y1) = map(float, xs), map(float, ys)
        if x0 == x1 and y0 != y1:
            vert.append((mem, x0, min(y0, y1), max(y0, y1)))
        elif y0 == y1 and x0 != x1:
            hor.append((mem, min(x0, x1), max(x0, x1), y0))
    out = []
    for mv, x, y0, y1 in vert:
        tol = 1e-6 * (y1 - y0)
        out += [(x, y) for mh, x0, x1, y in hor if mh != mv and x0 + tol < x < x1 - tol
                and y0 + tol < y < y1 - tol and abs(y - (y0 + y1) / 2) > tol]
    return out


def disc_sides(m, y, col, colors, dx) -> dict[str, int]:
    """The side (+1 right, −1 left) of each internal wheel's disc: on the right, except a ring in
    the first column whose disc there would be crossed (:func:`scheme_crossings`) and is not on the
    left (a ring whose disc faced the satellites was crossed by their axle: train_2kh_two_internal);
    the scheme with the fewest crossings, all on the right when that is as good."""
    rings = [n for n, wh in m.wheels.items() if wh.internal and col[n] == 0]   # the first column may open right
    best, fewest = None, math.inf
    for signs in itertools.product((1, -1), repeat=len(rings)):
        side = {n: 1 for n, wh in m.wheels.items() if wh.internal} | dict(zip(rings, signs))
        fig = Figure()
        ax = fig.add_subplot()
        _scheme(ax, m, y, col, colors, dx, LabelPlacer(ax, fontsize=9), side)
        n = len(scheme_crossings(ax, colors))
        if n < fewest:
            best, fewest = side, n
        if n == 0:
            break
    return best


def _scheme(ax, m, y, col, colors, dx, labels, side):
    """The scheme in the plane of the axes: every element on a carried axis off the central axis
    (y = 0) is drawn at y and mirrored at −y (``_images``); labels on the upper image only.  The
    shafts of the moving members on the central axis (central wheels, carriers) run in the frame's
    bearings (:func:`_bearing`)."""
    tick = 0.15 * dx
    R = max(abs(y[wh.centre]) + wh.m * wh.z / 2 for wh in m.wheels.values())
    hub = 0.03 * R          # a ring's disc stops at its hub: the shafts inside it pass along the axis
    for name, wh in m.wheels.items():
        x, r, c = col[name] * dx, wh.m * wh.z / 2, colors[wh.member]
        for s in _images(m, y, wh.centre):
            yc = s * y[wh.centre]
            if wh.internal:
                xd = x + side[name] * 0.4 * dx
                for sg in (1, -1):
                    ax.plot([x - tick, x + tick], [yc + sg * r] * 2, color=c, lw=1.2)
                    ax.plot([x, xd], [yc + sg * r] * 2, color=c, lw=1.6)
                if abs(yc) <= 1e-9:
                    for sg in (1, -1):
                        ax.plot([xd] * 2, [sg * hub, sg * r], color=c, lw=1.0)
                else:
                    ax.plot([xd] * 2, [yc - r, yc + r], color=c, lw=1.0)
            else:
                ax.plot([x, x], [yc - r, yc + r], color=c, lw=2.2)
                for sg in (1, -1):
                    ax.plot([x - tick, x + tick], [yc + sg * r] * 2, color=c, lw=1.2)
            if s == 1 and wh.internal:          # beside the rim's back line, inside the ring
                labels.add(x + side[name] * 0.4 * dx, yc + r, _name(name), prefer=(3 * side[name], -11), color=c)
            elif s == 1:
                labels.add(x, yc + r, _name(name), prefer=(-9, 2), color=c)
    order = list(m.members)
    for mem, axis in m.members.items():
        c = colors[mem]
        carried = [a for a, h in m.axes.items() if h == mem]
        # a member's wheels are held at their hubs: a ring by its disc
        xs = [(col[n] + (side[n] * 0.4 if wh.internal else 0.0)) * dx for n, wh in m.wheels.items()
              if wh.member == mem and wh.centre == axis]
        sides = _images(m, y, axis)
        if carried:
            x0 = -(0.7 + 0.35 * order.index(mem)) * dx
            # a ring opening towards the carried wheels (its disc on the left) holds the carrier's arm
            # inside it: the arm rises between the disc and the wheels, never through the disc
            inner = [(col[n] - 0.4) * dx for n, wh in m.wheels.items() if wh.internal and side[n] < 0
                     and abs(y[wh.centre]) <= 1e-9 and any(wh.m * wh.z / 2 > abs(y[a]) for a in carried)]
            if inner:
                x0 = max(inner) + (0.15 + 0.1 * order.index(mem)) * dx
                # its shaft runs out through the ring's hollow shaft, in a bearing beyond it
                for sd in sides:
                    ax.plot([max(inner) - 1.0 * dx, x0], [sd * y[axis]] * 2, color=c, lw=1.6)
                if mem not in m.fixed:
                    _bearing(ax, max(inner) - 0.85 * dx, dx, R, c)
            for a in carried:
                xa = [col[n] * dx for n, wh in m.wheels.items() if wh.centre == a]
                if not xa:
                    continue
                for s in (1, -1):
                    ax.plot([x0, x0], [s * y[axis], s * y[a]], color=c, lw=1.6)
                    ax.plot([x0, max(xa) + 0.25 * dx], [s * y[a]] * 2, color=c, lw=1.6)
            for s in sides:
                ax.plot([x0 - 0.5 * dx, x0], [s * y[axis]] * 2, color=c, lw=1.6)
            labels.add(x0, y[axis], _name(mem), prefer=(-14, 3), color=c)
            outer = [h for h in order[order.index(mem) + 1:] if any(v == h for v in m.axes.values())
                     and abs(y[m.members[h]]) <= 1e-9]
            if mem not in m.fixed and abs(y[axis]) <= 1e-9 and not outer and not inner:
                # (a carrier inside another's hollow shaft runs in that one, not in the frame)
                _bearing(ax, x0 - 0.3 * dx, dx, R, c)
        elif xs and any(wh.internal and side[n] < 0 and abs(y[wh.centre]) <= 1e-9
                        for n, wh in m.wheels.items() if wh.member == mem):
            # a ring opening to the right: a hollow shaft from its disc to the left (the carrier's
            # shaft inside it), in a bearing of the frame; a fixed ring is held at its rim
            if mem not in m.fixed:
                for sg in (1, -1):
                    ax.plot([min(xs) - 0.45 * dx, min(xs)], [sg * hub] * 2, color=c, lw=1.6)
                _bearing(ax, min(xs) - 0.3 * dx, dx, R, c)
        elif xs:
            for s in sides:
                ax.plot([min(xs) - 0.3 * dx, max(xs) + 0.3 * dx], [s * y[axis]] * 2, color=c, lw=1.6)
            if mem not in m.fixed and abs(y[axis]) <= 1e-9:
                # at the end of the shaft farther from the other members' wheels
                near = 0.1 * R + 0.1 * dx        # the symbol's reach from the axis (:func:`_bearing`)
                others = [col[n] * dx for n, wh in m.wheels.items() if wh.member != mem
                          and abs(y[wh.centre]) - wh.m * wh.z / 2 < near] or [math.inf]
                room = {xb: min(abs(xb - xo) for xo in others) for xb in (max(xs) + 0.22 * dx, min(xs) - 0.22 * dx)}
                xb = max(room, key=room.get)
                if room[xb] >= 0.45 * dx:       # (no room between the columns: the symbol left out)
                    _bearing(ax, xb, dx, R, c)
        if mem in m.fixed:
            ws = [wh for wh in m.wheels.values() if wh.member == mem]
            for wh in ws:
                xf, r = col[wh.name] * dx, wh.m * wh.z / 2
                yw = y[wh.centre]
                rims = (r, -r) if abs(yw) <= 1e-9 else [s * yw + math.copysign(r, s * yw)
                                                          for s in _images(m, y, wh.centre)]
                for yf in rims:
                    s = 1 if yf > 0 else -1
                    ax.plot([xf + 0.05 * dx, xf + 0.65 * dx], [yf] * 2, color=INK, lw=1.0)
                    for k in range(4):
                        x1 = xf + 0.05 * dx + 0.15 * dx * k
                        ax.plot([x1, x1 + 0.12 * dx], [yf, yf + s * 0.12 * dx], color=INK, lw=0.8)


def train_picture(train) -> TrainPicture:
    """The scheme (radii at scale, symmetric), the velocity picture beside its upper half (same
    vertical scale) and the plan of angular velocities of the whole train."""
    m = train.model
    y = train.positions
    w = train.w_willis
    col = _columns(m)
    ncol = max(col.values()) + 1
    ext = [abs(y[wh.centre]) + wh.m * wh.z / 2 for wh in m.wheels.values()]
    R = max(ext)
    dx = 0.22 * R                                  # axial spacing of the wheel columns
    colors = {n: COLORS[i % len(COLORS)] for i, n in enumerate(m.members)}
    fig = mplstyle.figure(170, 160, layout=None)
    bottom, top = 0.27, 0.95
    ax = fig.add_axes((0.09, bottom, 0.44, top - bottom))
    ylo, yhi = -1.12 * R, 1.2 * R
    labels = LabelPlacer(ax, fontsize=9)        # placed clear of the lines once all is drawn
    _scheme(ax, m, y, col, colors, dx, labels, disc_sides(m, y, col, colors, dx))
    ax.set_xlim(-(1.4 + 0.35 * len(m.members)) * dx, (ncol + 0.2) * dx)
    ax.set_ylim(ylo, yhi)
    ax.set_xticks([])
    ax.axhline(0, color=GREY, lw=0.5, ls="-.")
    ax.set_ylabel("расстояние от центральной оси, мм")
    ax.set_title("Схема механизма", fontsize=10)
    labels.place()
    # velocity picture: v(y) of every member over its upper image (per unit ω of the input)
    pp = pitch_points(m)
    lo_v = min(min(y[wh.centre] - wh.m * wh.z / 2 for wh in m.wheels.values()), 0.0) - 0.06 * R
    f0 = bottom + (lo_v - ylo) / (yhi - ylo) * (top - bottom)
    av = fig.add_axes((0.60, f0, 0.38, top - f0))
    av.set_ylim(lo_v, yhi)

    def vel(mem, at):
        v = 0.0
        while mem != FRAME:
            axy = y[m.members[mem]]
            v += w[mem] * (at - axy)
            at = axy
            mem = m.axes[m.members[mem]]
        return v

    vlabels = LabelPlacer(av, fontsize=8)
    for mem, axis in m.members.items():
        ys = [y[wh.centre] + s * wh.m * wh.z / 2 for wh in m.wheels.values() if wh.member == mem for s in (-1, 1)]
        ys += [y[a] for a, h in m.axes.items() if h == mem] + [y[axis]]
        yy = np.array([min(ys), max(ys)])
        vv = [vel(mem, t) for t in yy]
        av.plot(vv, yy, color=colors[mem], lw=1.4)
        vlabels.add(vv[1], yy[1], _name(mem), prefer=(2, 2), color=colors[mem])
    for (a, b), yp in pp.items():
        vp = vel(m.wheels[a].member, yp)
        av.plot([0, vp], [yp, yp], color=GREY, lw=0.6)
        av.plot([vp], [yp], "o", ms=3, color=INK)
        vlabels.add(vp, yp, f"$P_{{{a}{b}}}$", prefer=(4, -9), point=True)
    for a in set(y.values()):
        av.axhline(a, color=GREY, lw=0.4, ls=":")
    av.axvline(0, color=INK, lw=0.8)
    av.set_xlabel("$v/\\omega_{вх}$, мм")
    av.set_title("Картина линейных скоростей", fontsize=10)
    vlabels.place()
    # plan of angular velocities of the whole train: rays from the pole parallel to the velocity
    # lines, cut by a base line at the polar distance h; segment ∝ ω.
    ap = fig.add_axes((0.58, 0.02, 0.40, 0.16))
    wmax = max(abs(v) for v in w.values()) or 1.0
    h = 10.0
    seg = {n: round(60.0 * w[n] / wmax / READ_MM) * READ_MM for n in m.members}
    plabels = LabelPlacer(ap, fontsize=8)
    plabels.add(0, h, "P", prefer=(3, 2), point=True)
    for n in m.members:
        ap.plot([0, seg[n]], [h, 0], color=colors[n], lw=1.2)
        plabels.add(seg[n], 0, _name(n), prefer=(0, -1), color=colors[n])
    ap.axhline(0, color=INK, lw=0.8)
    ap.plot([0], [h], "o", ms=3, color=INK)
    ap.set_xlim(-65, 65)
    ap.set_ylim(-12, h + 4)
    ap.axis("off")
    ap.set_title("План угловых скоростей", fontsize=10)
    plabels.place()
    return TrainPicture(fig, seg, 1.0)


def _free_side(seg: dict, f: dict) -> int:
    """The side of the pole's vertical (+1 right, −1 left) where the label of the polar distance h
    (set halfway between the pole and the first horizontal) is clear of the rays: a ray from the pole
    to the end of a segment ``sg`` read f polar distances down passes halfway down the first polar
    distance at ``sg/(2f)`` from the vertical; the label goes where the nearest ray is farthest."""
    room = {1: float("inf"), -1: float("inf")}
    for nm, sg in seg.items():
        if sg:
            side = 1 if sg > 0 else -1
            room[side] = min(room[side], abs(sg) / (2 * f[nm]))
    return 1 if room[1] >= room[-1] else -1


def stage_plans(train) -> StagePlans:
    """The graphical ratio stage by stage: along the chain of members ordered by |ω|
    (``ratio_chain``) every pair of neighbours gets its own plan of angular velocities, the two
    rays from the pole parallel to the members' velocity lines, drawn at the scale that makes the
    segments span PLAN_MM; the segments are read to READ_MM.  A ray whose segment would be shorter
    than SHORT_MM (a stage of a large ratio: 4,5 mm against 135,5 mm reads to ±11 %) is cut by a
    second horizontal f polar distances from the pole (f ≤ DEPTH_MAX, the segment grows f times):
    a segment is proportional to ω times the polar distance, so u = Π ((0a)/f_a)/((0b)/f_b)."""
    m = train.model
    w = train.w_willis
    chain = ratio_chain(w, m.inp, m.out)
    h = POLE_MM
    plans = []
    for a, b in zip(chain, chain[1:]):
        lo, hi = min(0.0, w[a], w[b]), max(0.0, w[a], w[b])
        k = PLAN_MM / (hi - lo)
        f = {x: (min(DEPTH_MAX, max(1, int(0.5 * PLAN_MM // abs(k * w[x]))))
                 if 0 < abs(k * w[x]) < SHORT_MM else 1) for x in (a, b)}
        span = max(0.0, *(f[x] * k * w[x] for x in (a, b))) - min(0.0, *(f[x] * k * w[x] for x in (a, b)))
        k *= min(1.0, PLAN_MM / span)               # the lengthened segment keeps the plan on the page
        seg = {x: round(f[x] * k * w[x] / READ_MM) * READ_MM for x in (a, b)}
        lo = min(0.0, seg[a], seg[b]) / k           # the leftmost end, in the units of ω
        plans.append((a, b, k, lo, f, seg))
    rows = [24.0 + (max(p[4].values()) - 1) * h for p in plans]
    total = sum(rows) + 4
    fig = mplstyle.figure(170, total, layout=None)
    colors = {nm: COLORS[i % len(COLORS)] for i, nm in enumerate(m.members)}
    stages, depths, u, top = [], [], 1.0, 0.0
    for i, ((a, b, k, lo, f, seg), row) in enumerate(zip(plans, rows)):
        top += row
        deep = (max(f.values()) - 1) * h
        x0 = 16.0 - k * lo                          # foot of the pole, mm from the left edge
        ax = fig.add_axes((0.0, 1 - top / total, 1.0, row / total))
        ax.set_xlim(0, 170)
        ax.set_ylim(-9 - deep, row - 9 - deep)
        ax.axis("off")
        ax.plot([x0 + min(0, seg[a] / f[a], seg[b] / f[b]) - 4, x0 + max(0, seg[a] / f[a], seg[b] / f[b]) + 4],
                [0, 0], color=INK, lw=0.8)       # the first horizontal, h from the pole
        ax.plot([x0], [h], "o", ms=3, color=INK)
        texts = [ax.annotate(f"P, ступень {i + 1}: звенья {a} и {b}", (x0, h), xytext=(4, 1),
                             textcoords="offset points", fontsize=8)]
        if deep:
            ax.plot([x0, x0], [h, -deep], color=INK, lw=0.5, ls=(0, (4, 2)))
            side = _free_side(seg, f)
            texts.append(ax.annotate(f"h = {fmt(h, digits=0)} мм", (x0, h / 2), xytext=(3 * side, 0),
                                     textcoords="offset points", fontsize=7,
                                     ha="left" if side > 0 else "right", va="center"))
        for nm, sg in ((a, seg[a]), (b, seg[b])):
            y = h - f[nm] * h
            ax.plot([x0, x0 + sg], [h, y], color=colors[nm], lw=1.2)
            if f[nm] > 1:               # the farther horizontal and its polar distance
                ax.plot([x0 + min(0, sg) - 4, x0 + max(0, sg) + 4], [y, y], color=INK, lw=0.8)
                texts.append(ax.annotate(f"{f[nm]}h = {fmt(f[nm] * h, digits=0)} мм", (x0, y / 2), xytext=(3, 0),
                                         textcoords="offset points", fontsize=7, ha="left", va="center"))
            texts.append(ax.annotate(f"{nm}: {fmt(sg, digits=1)} мм", (x0 + sg, y), xytext=(0, -9),
                                     textcoords="offset points", fontsize=8, color=colors[nm], ha="center"))
        declutter(fig, texts)
        stages.append((a, b, seg[a], seg[b]))
        depths.append((f[a], f[b]))
        u *= (seg[a] / f[a]) / (seg[b] / f[b])
    return StagePlans(fig, stages, u, depths)
