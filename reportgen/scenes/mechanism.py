"""Scenes that draw the mechanism itself: the kinematic scheme at a position, the plan of
positions with the trajectories of the centres of mass, and the Assur groups drawn apart."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..mechanism.model import FRAME
from matplotlib.patches import Circle

from .draw import GREY, INK, Canvas, draw_guide, draw_mechanism, mechanism_points


@dataclass
class Drawing:
    svg: bytes
    width_mm: float
    mu: float            # scale factor μ (units per printed mm)


def _row(study, label: str):
    k = study.kinematics
    return k[k["pos"] == label].iloc[0]


class KinematicScheme:
    """The kinematic scheme at one report position, to scale, with points and links labelled."""

    needs = ("kinematics",)

    def __init__(self, label: str):
        self.label = label

    def draw(self, study) -> Drawing:
        row = _row(study, self.label)
        xs, ys = mechanism_points(study.mechanism, [row])
        cv = Canvas.fit(xs, ys, avail_w=140, avail_h=120, margin_mm=12)
        draw_mechanism(cv, study.mechanism, row)
        return Drawing(cv.svg(), cv.width_mm, cv.mu)


class PositionsPlan:
    """All report positions overlaid (the first drawn bold, the others thin and numbered at the
    crank pin / rod end), the crank circle, both extreme positions of the output link bold and
    labelled (B′, B″), each fixed guide hatched over the whole travel of its slider, and the
    trajectories of the centres of mass over the cycle (dashed)."""

    needs = ("kinematics", "cycle")

    def draw(self, study) -> Drawing:
        from ..analysis.plans import output_quantity
        mech = study.mechanism
        k = study.kinematics
        regular = k[~k["pos"].str.startswith("д")] if k["pos"].dtype == object else k
        rows = [r for _, r in regular.iterrows()]
        cyc = study.cycle
        coms = [l.com for l in mech.moving if l.com]
        xs, ys = mechanism_points(mech, rows)
        for p in coms:
            xs += list(cyc[f"x_{p}"])
            ys += list(cyc[f"y_{p}"])
        cv = Canvas.fit(xs, ys, avail_w=155, avail_h=190, margin_mm=12, gost=True)
        for p in coms:
            cv.ax.plot(cyc[f"x_{p}"], cyc[f"y_{p}"], ls=(0, (5, 3)), lw=0.7, color=INK, zorder=2)
        tip = _tracer_point(study)
        cx, cy = _centre(study, rows)
        if mech.driver.rotary:
            r = float(np.hypot(rows[0][f"x_{tip}"] - cx, rows[0][f"y_{tip}"] - cy))
            cv.ax.add_patch(Circle((cx, cy), r, fill=False, lw=0.6, color=INK, zorder=1))
        for i, row in enumerate(rows[1:], start=1):
            draw_mechanism(cv, mech, row, color=GREY, lw=0.7, labels=False, numbers=False, alpha=0.9,
                           zorder=1, com=False, supports=False)
        s_col = output_quantity(study)[0]
        s = cyc[s_col].to_numpy()
        ext = [cyc.iloc[int(np.argmin(s))], cyc.iloc[int(np.argmax(s))]]
        for row in ext:
            draw_mechanism(cv, mech, row, color=INK, lw=1.2, labels=False, numbers=False, zorder=3, com=False,
                           supports=False)
        draw_mechanism(cv, mech, rows[0], color=INK, lw=1.5, zorder=4, guides=False)
        for j in mech.prismatic:
            if j.links[0] == FRAME:
                u = np.array([np.cos(j.angle), np.sin(j.angle)])
                p0 = np.array([rows[0][f"x_{j.point}"], rows[0][f"y_{j.point}"]])
                t = (np.column_stack([cyc[f"x_{j.point}"], cyc[f"y_{j.point}"]]) - p0) @ u
                draw_guide(cv, mech, rows[0], j, (float(t.min()), float(t.max())))
        out = _output_point(study, s_col)
        for mark, row in zip(("′", "″"), ext):
            for p in dict.fromkeys([out, tip]):
                cv.labels.add(float(row[f"x_{p}"]), float(row[f"y_{p}"]), _marked(p, mark), fontsize=10)
        # position numbers at the driver's moving point; coincident positions share one label
        groups: list[tuple[float, float, list[str]]] = []
        for row in rows:
            x, y = float(row[f"x_{tip}"]), float(row[f"y_{tip}"])
            for gx, gy, names in groups:
                if np.hypot(x - gx, y - gy) < cv.mm(0.5):
                    names.append(str(row["pos"]))
                    break
            else:
                groups.append((x, y, [str(row["pos"])]))
        for x, y, names in groups:
            cv.labels.add(x, y, ", ".join(names), prefer=(x - cx, y - cy), fontsize=8)
        return Drawing(cv.svg(), cv.width_mm, cv.mu)


def _marked(p: str, mark: str) -> str:
    """B with a prime or double prime in mathtext: $B′$, $S″_{2}$."""
    head = p.rstrip("0123456789")
    tail = p[len(head):]
    return "$" + head + mark + (f"_{{{tail}}}" if tail else "") + "$"


def _output_point(study, s_col: str) -> str:
    """The point that shows the output link's extreme positions: the slider's point, or the
    rocker's point farthest from its pivot."""
    mech = study.mechanism
    name = s_col.partition("_")[2]
    for j in mech.prismatic:
        if j.name == name:
            return j.point
    link = mech.link(name) if name in [l.name for l in mech.links] else None
    if link is None:
        return _tracer_point(study)
    fixed = set(mech.link(FRAME).points)
    piv = [p for p in link.points if p in fixed]
    rest = [p for p in link.points if p not in fixed]
    if not piv or not rest:
        return rest[0] if rest else _tracer_point(study)
    c = link.points[piv[0]]
    return max(rest, key=lambda p: np.hypot(link.points[p][0] - c[0], link.points[p][1] - c[1]))


def _tracer_point(study) -> str:
    d = study.mechanism.driver
    if d.rotary:
        link = study.mechanism.link(d.link)
        return [p for p in link.points if p != d.center][0]
    return d.end


def _centre(study, rows):
    d = study.mechanism.driver
    p = d.center
    return float(rows[0][f"x_{p}"]), float(rows[0][f"y_{p}"])


class AssurGroups:
    """The initial mechanism and each Assur group drawn separately at one position, with the
    external pairs marked (the places where the group is attached)."""

    needs = ("kinematics", "structure")

    def __init__(self, label: str):
        self.label = label

    def draw(self, study) -> Drawing:
        from ..style import mplstyle
        mech = study.mechanism
        st = study.structure
        row = _row(study, self.label)
        groups = st.groups
        n = len(groups)
        fig = mplstyle.figure(165, 62 if n <= 4 else 110, layout=None)
        cols = min(n, 4)
        rws = (n + cols - 1) // cols
        for gi, g in enumerate(groups):
            ax = fig.add_subplot(rws, cols, gi + 1)
            ax.set_aspect("equal")
            ax.axis("off")
            links = set(g.links) | ({mech.driver.link} if g.klass == 1 else set())
            if mech.driver.kind == "actuator" and g.klass != 1 and mech.driver.rod in links:
                links.add(mech.driver.rod)
            pts = []
            for ln in links:
                for p in mech.link(ln).points:
                    pts.append((float(row[f"x_{p}"]), float(row[f"y_{p}"])))
            pts = np.array(pts)
            span = max(np.ptp(pts[:, 0]), np.ptp(pts[:, 1]), 1e-3)
            for ln in links:
                link = mech.link(ln)
                P = [(float(row[f"x_{p}"]), float(row[f"y_{p}"])) for p in link.points]
                if len(P) >= 2:
                    P2 = np.array(P)
                    order = np.argsort(P2[:, 0] * 1e-9 + np.arange(len(P2)))
                    ax.plot(P2[order, 0], P2[order, 1], color=INK, lw=1.4, solid_capstyle="round")
                ax.text(np.mean([p[0] for p in P]) + 0.05 * span, np.mean([p[1] for p in P]) + 0.05 * span,
                        ln, fontsize=9, color=INK)
            for j in mech.joints:
                if not (set(j.links) & links):
                    continue
                x, y = float(row[f"x_{j.point}"]), float(row[f"y_{j.point}"])
                external = not set(j.links) <= links
                ax.plot([x], [y], marker="o", ms=5, mfc="white" if not external else INK, mec=INK, zorder=3)
                if j.kind == "P" and set(j.links) <= links | {FRAME}:
                    ax.plot([x - 0.08 * span, x + 0.08 * span], [y, y], color=INK, lw=3, alpha=0.5)
                ax.text(x + 0.04 * span, y - 0.08 * span, j.point, fontsize=8, style="italic")
            ax.set_title(g.label + (" " + g.kind_ru if g.kind_ru else ""), fontsize=9)
            ax.margins(0.18)
        return Drawing(mplstyle.to_svg(fig), 165, 0.0)
