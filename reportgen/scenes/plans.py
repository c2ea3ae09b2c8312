"""Velocity and acceleration plans constructed to scale, and the table of values read off them.

The plan is *constructed* (``analysis.plans.construct_velocity`` / ``construct_acceleration``):
the known vectors are laid off with lengths rounded to 0,5 mm at a round scale μ, the unknown
points are the intersections of the lines of the vector equations; the segments of the
construction are then read to 0,5 mm and compared with the analytic values in %. The
discrepancy is the real error of the graphical solution (drawing and reading), not a rounding
of the analytic answer.

Where vectors shorter than MIN_MM or points closer than CROWD_MM crowd a place of the plan, the
place is circled and drawn again k times larger in a free place of the drawing, with its labels
(a «выносной элемент», ГОСТ 2.305: letter on the plan, «А (×k)» over the view); every label
keeps LABEL_GAP_MM from the others (:func:`find_insets`)."""
from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..analysis.plans import (READ_MM, Plan, acceleration_plan, construct_acceleration, construct_velocity,
                              drawn, group_rank, measured_omegas, velocity_plan)
from .draw import GREY, INK, Canvas, arrow, nice_scale
from .mechanism import LANDSCAPE_GAIN, LANDSCAPE_W, LANDSCAPE_H

MIN_MM = 5.0         # shorter segments are drawn but not compared (reading error dominates)
AVAIL_MM = (140.0, 150.0)
STYLE = {"abs": dict(color=INK, lw=1.3, ls="-"), "rel": dict(color=INK, lw=1.0, ls="-"),
         "normal": dict(color=GREY, lw=1.0, ls="--"), "tangential": dict(color=INK, lw=1.0, ls="-."),
         "coriolis": dict(color=GREY, lw=1.0, ls="--"), "slide": dict(color=INK, lw=1.0, ls=":")}
CONSTRUCTION_MM = 8.0     # construction lines extended past the intersection, mm
MARGIN_MM = 12.0          # around the plan, for the labels
CROWD_MM = 3.0            # plan points closer than this crowd their labels: shown in an enlarged view
JOIN_MM = 8.0             # crowded points closer than this are shown in one view
LABEL_GAP_MM = 2.5        # least printed gap between two labels of a plan
INSET_D_MM = 64.0         # diameter of an enlarged view at most, mm
MAX_H_MM = 225.0          # a portrait plan at most: with its caption within the text height (257 mm)
INSET_K = (2.0, 2.5, 3.0, 4.0, 5.0, 10.0, 20.0, 25.0, 40.0, 50.0, 100.0, 200.0)


@dataclass
class PlanDrawing:
    svg: bytes
    width_mm: float
    mu: float
    table: pd.DataFrame       # segment, analytic value, length on the plan (mm), graphic value, Δ %
    plan: Plan                # the constructed plan
    landscape: bool = False   # drawn for a landscape page (scenes.mechanism.LANDSCAPE_GAIN)
    insets: list = None       # the enlarged views: :class:`Inset` each


_POINT_NAMES = re.compile(r"[A-Z][0-9]*")


def _pair_index(index: str) -> str:
    """The index of n_BO2 in mathtext with each point's own digits as its index (n_{BO₂}, as the
    formulas write a^n_{BO₂}), not «BO2» read as one word; an index not made of capital letters
    each with its digits (a pair «34») as it is."""
    parts = _POINT_NAMES.findall(index)
    if not parts or "".join(parts) != index or not any(len(p) > 1 for p in parts):
        return index
    return "".join(p[0] + (f"_{{{p[1:]}}}" if len(p) > 1 else "") for p in parts)


def tip_label(lab: str, plan: Plan, kind: str) -> str:
    """Plan point in textbook notation (mathtext): a, b, s₂ on the velocity plan; a′, b′, s′₂ on
    the acceleration plan; n_BA, k for the ends of the normal and Coriolis components. The image
    of a point named P on the velocity plan (and the Жуковский lever) is p with its link's number,
    p₂: a bare p is the pole."""
    if lab.startswith("n") and lab not in plan.point_of_tip:
        return "$n_{" + _pair_index(lab[1:]) + "}$"
    if lab.startswith("k") and lab not in plan.point_of_tip:
        return "$k_{" + _pair_index(lab[1:]) + "}$"
    if lab not in plan.point_of_tip or plan.point_of_tip[lab] != lab:
        # the guide's point under the slider: b₃ (lower-case point, guide link as index)
        p = plan.point_of_tip.get(lab, lab[0])
        link = lab[len(p):]
        return "$" + p.lower() + ("′" if kind == "acceleration" else "") + "_{" + link + "}$"
    head = lab.rstrip("0123456789")
    tail = lab[len(head):]
    if not head:                       # a point named by a number (a pair 34): the number itself
        head, tail = lab, ""
    if kind == "velocity" and head.lower() == "p" and not tail:
        # the image of a point P would read as the pole p: its link as the index (p₂), as b₃ above
        tail = plan.owner.get(lab) or next((s.link for s in plan.segments if s.end == lab and s.link), "")
    return "$" + head.lower() + ("′" if kind == "acceleration" else "") + (f"_{{{tail}}}" if tail else "") + "$"


SAME_MM = 0.05            # plan points closer than this are one point of the drawing (one label)


def coincident(tips: dict, labs, tol: float) -> dict[str, list[str]]:
    """The points of ``labs`` that lie at one place (``tips``: label → vector, closer than ``tol``):
    each group under its first point (plan order), the others absent. The images of all points of
    a translating link coincide (b, s₃, t of a saw frame): a student writes them at one point,
    «b, s₃, t»; no enlarged view can tell them apart."""
    out: dict[str, list[str]] = {}
    for lab in labs:
        head = next((h for h in out if np.hypot(*(tips[h] - tips[lab])) < tol), None)
        if head is None:
            out[lab] = [lab]
        else:
            out[head].append(lab)
    return out


def joint_label(group: list[str], plan: Plan, kind: str) -> str:
    """One label for the coincident points of ``group``: «b, s₃, t»."""
    return ", ".join(tip_label(lab, plan, kind) for lab in group)


def plan_scale(plan: Plan, landscape: bool = False) -> float:
    """The round scale μ at which the plan fits the space (1; 1,5; 2; 2,5; 4; 5·10ᵏ per mm) of a
    portrait page, or of a landscape one."""
    pts = np.array([[0.0, 0.0]] + [list(v) for v in plan.tips.values()])
    w, h = (LANDSCAPE_W - 2 * MARGIN_MM, LANDSCAPE_H - 2 * MARGIN_MM) if landscape else AVAIL_MM
    return max(nice_scale(np.ptp(pts[:, 0]), w), nice_scale(np.ptp(pts[:, 1]), h))


LANDSCAPE_FILL = 0.5      # a landscape page of its own is taken only by a plan this tall at least (share of its height)


def page_scale(plan: Plan) -> tuple[float, bool]:
    """(μ, landscape): the plan goes onto a landscape page when that enlarges it at least
    LANDSCAPE_GAIN times (a wide, flat plan), as the plan of positions does — unless it would
    fill less than LANDSCAPE_FILL of that page's height even so (a flat strip on a page of its
    own, mostly empty): then it stays on the portrait page, with the text, at its portrait scale."""
    mu, mu_l = plan_scale(plan), plan_scale(plan, landscape=True)
    if mu < LANDSCAPE_GAIN * mu_l:
        return mu, False
    pts = np.array([[0.0, 0.0]] + [list(v) for v in plan.tips.values()])
    if np.ptp(pts[:, 1]) / mu_l < LANDSCAPE_FILL * (LANDSCAPE_H - 2 * MARGIN_MM):
        return mu, False
    return mu_l, True


class PlanScene:
    needs = ("kinematics",)

    def __init__(self, label: str, kind: str, mu_v: float | None = None, mu_a: float | None = None,
                 landscape: bool = False):
        """``mu_v``, ``mu_a``: scales given by the caller (one μ_V for all the velocity plans of a
        drawing sheet, one μ_a for its acceleration plans); by default each plan takes the round
        scale that fits it (:func:`plan_scale`), on a landscape page where that pays if
        ``landscape`` (the note: :func:`page_scale`)."""
        self.label = label
        self.kind = kind
        self.mu_v = mu_v
        self.mu_a = mu_a
        self.landscape = landscape

    def _scale(self, plan: Plan) -> tuple[float, bool]:
        return page_scale(plan) if self.landscape else (plan_scale(plan), False)

    def construct(self, study, mu_a: float | None = None):
        """(constructed plan, analytic plan, μ, landscape) of this scene's kind; ``mu_a`` — the
        acceleration plan's scale chosen by :meth:`draw` (portrait, to fit the page height)."""
        k = study.kinematics
        row = k[k["pos"] == self.label].iloc[0]
        mech = study.mechanism
        v_exact = velocity_plan(row, mech)
        mu_v, land_v = (self.mu_v, False) if self.mu_v else self._scale(v_exact)
        vrow, vplan = construct_velocity(row, study, mu_v)
        if self.kind == "velocity":
            return vplan, v_exact, mu_v, land_v
        a_exact = acceleration_plan(row, mech)
        mu_a, land_a = (self.mu_a, False) if self.mu_a else (mu_a, False) if mu_a else self._scale(a_exact)
        om = measured_omegas(vrow, vplan, mech, mu_v, group_rank(study))
        _, aplan = construct_acceleration(row, vrow, om, study, mu_a, mu_v)
        return aplan, a_exact, mu_a, land_a

    def draw(self, study) -> PlanDrawing:
        """The plan at its scale; a portrait acceleration plan whose enlarged views, stacked under
        it, would make it taller than MAX_H_MM (then it and its caption no longer share a page:
        the caption went to the next one) is drawn at the next coarser round scales until it fits.
        (The velocity plan keeps its scale: the acceleration plan is constructed from the
        velocities read off it at that scale.)"""
        out, height = self._draw(study)
        if self.kind == "acceleration" and self.mu_a is None and not out.landscape:
            mu = out.mu
            for _ in range(3):
                if height <= MAX_H_MM:
                    break
                mu = nice_scale(mu * 1.01, 1.0)        # the next coarser standard scale
                out, height = self._draw(study, mu)
        return out

    def _draw(self, study, mu_a: float | None = None) -> tuple[PlanDrawing, float]:
        plan, exact, mu, landscape = self.construct(study, mu_a)
        plan = similarity_only(plan, study.mechanism)
        pts = np.array([[0.0, 0.0]] + [list(v) for v in plan.tips.values()])
        given = self.mu_v if self.kind == "velocity" else self.mu_a
        max_w = 1e4 if given is not None else LANDSCAPE_W if landscape else 165.0
        # the sheets give one μ to all their plans and lay the views out themselves: their plans
        # are drawn without enlarged views (a view beside a plan would change its size on the sheet)
        insets = [] if given is not None else find_insets(plan, mu, max_w - 2 * MARGIN_MM)
        box = np.vstack([pts] + [[i.at - i.radius * i.k - i.pad, i.at + i.radius * i.k + i.pad] for i in insets])
        cv = Canvas(box[:, 0].min(), box[:, 0].max(), box[:, 1].min(), box[:, 1].max(), mu, margin_mm=MARGIN_MM,
                    max_w=max_w)
        cv.labels.gap_mm = LABEL_GAP_MM
        ax = cv.ax
        for seg, a, b in _drawn_segments(plan, mu):
            if seg.kind in ("rel", "tangential", "slide"):
                c0, c1 = _construction_line(a, b, mu)
                ax.plot([c0[0], c1[0]], [c0[1], c1[1]], lw=0.35, color=GREY, zorder=1)
            st = STYLE[seg.kind]
            arrow(ax, a[0], a[1], b[0], b[1], color=st["color"], lw=st["lw"], ls=st["ls"])
        ax.plot([0], [0], marker="o", ms=3, color=INK)
        hidden = {lab for i in insets for lab in i.tips}
        pole = "$p$" if self.kind == "velocity" else r"$\pi$"
        if "p" not in hidden:
            cv.labels.add(0.0, 0.0, pole, prefer=(-1, -1), fontsize=11)
        shown = [lab for lab in plan.tips if lab not in hidden and self._labelled(plan, lab, cv.mm(2.0))]
        for lab, group in coincident(plan.tips, shown, cv.mm(SAME_MM)).items():
            v = plan.tips[lab]
            d = np.hypot(*v)
            cv.labels.add(v[0], v[1], joint_label(group, plan, self.kind), prefer=(v[0], v[1]) if d > 1e-12 else (1, 1),
                          fontsize=10)
        for n, ins in enumerate(insets):
            ins.mark = INSET_MARKS[n % len(INSET_MARKS)]
            self._draw_inset(cv, plan, ins, pole)
        table = measure(plan, exact, mu)
        return PlanDrawing(cv.svg(), cv.width_mm, mu, table, plan, landscape, insets), cv.height_mm

    @staticmethod
    def _labelled(plan: Plan, lab: str, dist: float) -> bool:
        """Whether a plan point gets a label: not the pole's image of a point at rest, not the end
        of a component lying on its point (the arrow says enough)."""
        if np.hypot(*plan.tips[lab]) < 1e-12 and lab in plan.point_of_tip:
            return False
        return lab in plan.point_of_tip or _apart(plan, lab, dist)

    def _draw_inset(self, cv: Canvas, plan: Plan, ins: "Inset", pole: str) -> None:
        """The enlarged view (ГОСТ 2.305 «выносной элемент»): the region circled on the plan (thin
        dashed, with its letter) drawn ×k in a free place, its vectors and their labels."""
        ax, mu = cv.ax, cv.mu
        c, r, k = ins.centre, ins.radius, ins.k
        view_frame(cv, c, r, ins.at, r * k)
        to_view = lambda p: ins.at + (np.asarray(p) - c) * k  # noqa: E731 - the view's similarity
        for seg, a, b in _drawn_segments(plan, mu):
            if seg.kind in ("rel", "tangential", "slide"):
                part = _clip(*_construction_line(a, b, mu), c, r)
                if part is not None:
                    p0, p1 = to_view(part[0]), to_view(part[1])
                    ax.plot([p0[0], p1[0]], [p0[1], p1[1]], lw=0.35, color=GREY, zorder=1)
            part = _clip(a, b, c, r)
            if part is None:
                continue
            p0, p1 = to_view(part[0]), to_view(part[1])
            st = STYLE[seg.kind]
            if np.hypot(*(b - part[1])) < 1e-12 * max(1.0, np.hypot(*b)):
                arrow(ax, p0[0], p0[1], p1[0], p1[1], color=st["color"], lw=st["lw"], ls=st["ls"])
            else:                    # the head lies outside the view: the shaft only
                ax.plot([p0[0], p1[0]], [p0[1], p1[1]], color=st["color"], lw=st["lw"], ls=st["ls"], zorder=3)
        if "p" in ins.tips:
            o = to_view(np.zeros(2))
            ax.plot([o[0]], [o[1]], marker="o", ms=3, color=INK)
            cv.labels.add(o[0], o[1], pole, prefer=(-1, -1), fontsize=11)
        shown = [lab for lab in ins.tips if lab != "p" and self._labelled(plan, lab, cv.mm(2.0) / k)]
        for lab, group in coincident(plan.tips, shown, cv.mm(SAME_MM) / k).items():
            v = to_view(plan.tips[lab])
            cv.labels.add(v[0], v[1], joint_label(group, plan, self.kind), prefer=v - ins.at, fontsize=10)
        view_marks(cv, c, r, ins.at, r * k, ins.mark, f"{ins.mark} (×{ins.k:g})".replace(".", ","))


def view_frame(cv: Canvas, c, r: float, at, r_view: float) -> None:
    """The frame of a «выносной элемент» (ГОСТ 2.305): the region (``c``, ``r``) circled thin
    dashed, the view's circle (``at``, ``r_view``)."""
    from matplotlib.patches import Circle
    cv.ax.add_patch(Circle(c, r, fill=False, lw=0.5, ls=(0, (4, 2)), color=GREY, zorder=2))
    cv.ax.add_patch(Circle(at, r_view, fill=False, lw=0.5, color=GREY, zorder=2))


def view_marks(cv: Canvas, c, r: float, at, r_view: float, mark: str, title: str) -> None:
    """The letter ``mark`` of a view at its circled region (``c``, ``r``) and its ``title``
    («А (5:1)», ГОСТ 2.305) over the view's circle (``at``, ``r_view``)."""
    corner = np.asarray(c) + r * np.array([0.7071, 0.7071])
    cv.labels.add(corner[0], corner[1], mark, prefer=(1, 1), fontsize=10)
    top = np.asarray(at) + np.array([0.0, r_view])
    cv.labels.add(top[0], top[1], title, prefer=(0, 1), fontsize=10)


INSET_MARKS = ("А", "Б", "В", "Г", "Д", "Е")   # letters of the enlarged views (ГОСТ 2.305)


@dataclass
class Inset:
    """An enlarged view of a crowded region of a plan: the circle (``centre``, ``radius``, plan
    units) drawn ``k`` times larger around ``at``; ``segments`` are the plan's vectors shorter than
    MIN_MM shown in it, ``tips`` the plan points labelled in it (not on the plan)."""
    centre: np.ndarray
    radius: float
    k: float
    at: np.ndarray
    pad: float
    segments: list
    tips: list
    mark: str = ""


def _drawn_segments(plan: Plan, mu: float):
    """(segment, start, end) of every vector drawn: a zero component (a^τ of a uniformly turning
    crank) is left out, so that no stray arrowhead is drawn."""
    for seg in plan.segments:
        a = np.zeros(2) if seg.start == "p" else plan.tips[seg.start]
        b = plan.tips[seg.end]
        if np.hypot(*(b - a)) >= 0.05 * mu:
            yield seg, a, b


def _construction_line(a, b, mu: float):
    """The thin line of a vector of known direction, extended past both ends."""
    u = (b - a) / np.hypot(*(b - a))
    e = CONSTRUCTION_MM * mu
    return a - u * e * 0.4, b + u * e


def _clip(a, b, c, r):
    """The part of the segment ab inside the circle (c, r), or None."""
    d = b - a
    f = a - c
    A, B, C = d @ d, 2 * f @ d, f @ f - r * r
    disc = B * B - 4 * A * C
    if A <= 0 or disc <= 0:
        return None
    q = np.sqrt(disc)
    t0, t1 = max((-B - q) / (2 * A), 0.0), min((-B + q) / (2 * A), 1.0)
    if t1 - t0 < 1e-9:
        return None
    return a + t0 * d, a + t1 * d


def _crowded(plan: Plan, mu: float) -> list[np.ndarray]:
    """Clusters of crowded plan points (mm coordinates): the ends of vectors shorter than MIN_MM
    and labelled points closer than CROWD_MM to another, joined when closer than JOIN_MM."""
    pos = {"p": np.zeros(2), **{k: v / mu for k, v in plan.tips.items()}}
    hot = set()
    for seg, a, b in _drawn_segments(plan, mu):
        if np.hypot(*(b - a)) / mu < MIN_MM:
            hot |= {seg.start, seg.end}
    names = [n for n in pos if n == "p" or PlanScene._labelled(plan, n, 2.0 * mu)]
    for i, m in enumerate(names):
        for n in names[i + 1:]:
            # points at one place share one label (:func:`coincident`): they crowd nothing
            if SAME_MM <= np.hypot(*(pos[m] - pos[n])) < CROWD_MM:
                hot |= {m, n}
    clusters: list[set] = []
    for h in sorted(hot):
        near = [c for c in clusters if any(np.hypot(*(pos[h] - pos[o])) < JOIN_MM for o in c)]
        merged = {h}.union(*near) if near else {h}
        clusters = [c for c in clusters if c not in near] + [merged]
    return [np.array([pos[n] for n in sorted(c)]) for c in clusters]


def _free(sq, segs: np.ndarray, pts: np.ndarray, taken) -> bool:
    """Whether the square (x0, y0, x1, y1) in mm holds no plan point, meets no drawn line and no
    view already placed."""
    from matplotlib.transforms import Bbox
    from .labels import _crossings
    x0, y0, x1, y1 = sq
    if np.any((pts[:, 0] > x0) & (pts[:, 0] < x1) & (pts[:, 1] > y0) & (pts[:, 1] < y1)):
        return False
    if any(x0 < t[2] and t[0] < x1 and y0 < t[3] and t[1] < y1 for t in taken):
        return False
    return _crossings(segs, Bbox([[x0, y0], [x1, y1]])) == 0


def find_insets(plan: Plan, mu: float, avail_w_mm: float) -> list[Inset]:
    """The enlarged views a plan needs: each cluster of crowded points (:func:`_crowded`) circled
    (radius: its extent + 2 mm, at least 4 mm) and drawn at the largest magnification k of INSET_K
    that keeps the view within INSET_D_MM, in a free place on or around the plan (no point, no
    line) that enlarges the drawing least, else below it."""
    clusters = _crowded(plan, mu)
    if not clusters:
        return []
    tips_mm = np.array([[0.0, 0.0]] + [list(v / mu) for v in plan.tips.values()])
    segs = []
    for seg, a, b in _drawn_segments(plan, mu):
        segs.append(np.concatenate([a, b]) / mu)
        if seg.kind in ("rel", "tangential", "slide"):
            segs.append(np.concatenate(_construction_line(a, b, mu)) / mu)
    segs = np.array(segs).reshape(-1, 4)
    lo, hi = tips_mm.min(axis=0), tips_mm.max(axis=0)
    out, taken = [], []
    pad = 7.0                              # mm around a view, for its labels
    for cl in clusters:
        c = (cl.min(axis=0) + cl.max(axis=0)) / 2
        r = max(float(np.max(np.hypot(*(cl - c).T))) + 2.0, 4.0)
        ks = [k for k in INSET_K if 2 * r * k <= INSET_D_MM]
        if not ks:
            continue
        k = ks[-1]
        h = r * k + pad
        circle = (c[0] - r - 2, c[1] - r - 2, c[0] + r + 2, c[1] + r + 2)
        at = free_place(c, h, segs, tips_mm, lo, hi, taken, circle, avail_w_mm)
        taken.append((at[0] - h, at[1] - h, at[0] + h, at[1] + h))
        inside = lambda p: np.hypot(*(p - c)) <= r  # noqa: E731
        tips = (["p"] if inside(np.zeros(2)) else []) + [n for n, v in plan.tips.items() if inside(v / mu)]
        short = [seg.name for seg, a, b in _drawn_segments(plan, mu)
                 if np.hypot(*(b - a)) / mu < MIN_MM and inside(a / mu) and inside(b / mu)]
        out.append(Inset(c * mu, r * mu, k, at * mu, pad * mu, short, tips))
    return out


def free_place(c, h: float, segs: np.ndarray, pts: np.ndarray, lo, hi, taken: list, circle, avail_w_mm: float):
    """The centre (mm) of a free square of half-side ``h`` for the enlarged view of the region
    around ``c``: of the candidate places on the drawing (``lo``…``hi``, points ``pts``, lines
    ``segs``) and around it within the width, the free one (:func:`_free`, clear of the views
    ``taken`` and of the ``circle``d region) that enlarges the drawing least, the nearest to the
    region among equals; else below the drawing."""
    ext = np.vstack([lo, hi] + [[t[:2], t[2:]] for t in taken])
    grid = [np.array([x, y]) for y in np.linspace(lo[1] - h, hi[1] + h, 11)
            for x in np.linspace(ext[:, 0].max() - avail_w_mm + h, ext[:, 0].min() + avail_w_mm - h, 15)]
    grid = [p for p in grid if max(ext[:, 0].max(), p[0] + h) - min(ext[:, 0].min(), p[0] - h) <= avail_w_mm]

    def cost(p):
        b = np.vstack([ext, p - h, p + h])
        return round(float(np.prod(np.ptp(b, axis=0))), 3), float(np.hypot(*(p - c)))
    free = [p for p in grid if _free((p[0] - h, p[1] - h, p[0] + h, p[1] + h), segs, pts, taken + [circle])]
    return min(free, key=cost) if free else np.array([lo[0] + h, ext[:, 1].min() - h])


def similarity_only(plan: Plan, mech) -> Plan:
    """The plan without the component construction of points that are not pairs (centres of
    mass): a student finds them by the similarity theorem (s₂ divides ab as S₂ divides AB)."""
    joints = {j.point for j in mech.joints}
    sim = {p for p in plan.point_of_tip if plan.point_of_tip[p] == p and p not in joints}
    drop = set(sim) | {t for t in plan.tips if t not in plan.point_of_tip and t.startswith("n")
                       and any(t[1:].startswith(p) and t[1 + len(p):] in plan.tips for p in sim)}
    out = Plan(plan.kind, {k: v for k, v in plan.tips.items() if k in sim or k not in drop},
               [s for s in plan.segments if s.kind == "abs" or s.end not in drop], dict(plan.point_of_tip),
               {**plan.owner, **{s.end: s.link for s in plan.segments if s.link}})
    return out


def _apart(plan: Plan, lab: str, dist: float) -> bool:
    """Whether the end of a component lies farther than ``dist`` from the point its next
    segment leads to (otherwise its label would only crowd the point's)."""
    for s in plan.segments:
        if s.start == lab:
            return bool(np.hypot(*(plan.tips[s.end] - plan.tips[lab])) > dist)
    return True


def measure(plan: Plan, exact: Plan, mu: float) -> pd.DataFrame:
    """Every segment of the construction read to READ_MM, times μ, against the analytic value of
    the same segment; discrepancy in %."""
    ref = {s.name: s.length for s in exact.segments}
    rows = []
    for seg in plan.segments:
        mm = seg.length / mu
        if mm < MIN_MM or seg.name not in ref:
            continue
        read = round(mm / READ_MM) * READ_MM
        graph = drawn(seg.length, mu)
        an = ref[seg.name]
        rows.append(dict(name=seg.name, kind=seg.kind, link=seg.link, analytic=an, mm=read,
                         graphic=graph, delta=abs(graph - an) / an * 100.0))
    return pd.DataFrame(rows)
