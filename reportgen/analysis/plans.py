"""Vector polygons of the graphic-analytic method (план скоростей и план ускорений).

For a position of the mechanism, built from the analytic solution so that every vector of the
plan is exact; the scenes draw them to scale and "measure" them.

* Velocities: V_Q = V_R + V_QR for every point Q of a link with reference point R
  (V_QR ⊥ RQ, |V_QR| = ω·l_RQ); for a slider on a moving guide V_P(slider) = V_P(guide) + V_rel
  (V_rel ∥ guide).
* Accelerations: a_Q = a_R + aⁿ_QR + a^τ_QR (aⁿ = ω²·l toward R, a^τ = ε·l ⊥ RQ); for a slider on
  a moving guide a_P(slider) = a_P(guide) + a^k + a^r, a^k = 2·ω_guide × V_rel (Coriolis),
  a^r ∥ guide.  (Артоболевский, гл. 3; Попов–Тимофеев, «Кинематический анализ».)
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..mechanism.model import FRAME, Mechanism


@dataclass
class Segment:
    start: str           # plan point label at the start ("p" is the pole)
    end: str
    kind: str            # "abs", "rel", "normal", "tangential", "coriolis", "slide"
    name: str            # e.g. "V_BA", "a^n_BA"
    link: str = ""
    length: float = 0.0  # physical length of the vector (m/s or m/s²)


@dataclass
class Plan:
    kind: str                                  # "velocity" or "acceleration"
    tips: dict[str, np.ndarray] = field(default_factory=dict)    # label → vector from the pole
    segments: list[Segment] = field(default_factory=list)
    point_of_tip: dict[str, str] = field(default_factory=dict)   # tip label → mechanism point


def _vec(row, pre: str, p: str) -> np.ndarray:
    return np.array([row[f"{pre}x_{p}"], row[f"{pre}y_{p}"]], dtype=float)


def _rot90(v: np.ndarray) -> np.ndarray:
    return np.array([-v[1], v[0]])


def _reference(mech: Mechanism, link) -> str:
    """The point of a link through which it is attached to the links solved before it: the
    first of its points that is a joint with another link."""
    joined = {j.point for j in mech.joints if link.name in j.links}
    for p in link.points:
        if p in joined:
            return p
    return next(iter(link.points))


def _coincident(row, mech: Mechanism, guide: str, p: str):
    """Velocity and acceleration of the guide's material point under point p."""
    if guide == FRAME:
        return np.zeros(2), np.zeros(2)
    link = mech.link(guide)
    ref = _reference(mech, link)
    r = _vec(row, "", p) - _vec(row, "", ref)
    w, e = row["w_" + guide], row["e_" + guide]
    v = _vec(row, "v", ref) + w * _rot90(r)
    a = _vec(row, "a", ref) + e * _rot90(r) - w * w * r
    return v, a


def _start(kind: str, row, mech: Mechanism) -> tuple[Plan, set]:
    """A plan with the absolute vectors of all points (fixed points at the pole)."""
    plan = Plan(kind)
    pre = "v" if kind == "velocity" else "a"
    fixed = set(mech.link(FRAME).points)
    for link in mech.links:
        for p in link.points:
            if p not in plan.tips:
                plan.tips[p] = np.zeros(2) if p in fixed else _vec(row, pre, p)
                plan.point_of_tip[p] = p
    return plan, fixed


def _seg(plan: Plan, start: str, end: str, kind: str, name: str, link: str = "") -> None:
    """Add the segment start→end of the plan ("p" is the pole); its length is read off the tips."""
    a = np.zeros(2) if start == "p" else plan.tips[start]
    plan.segments.append(Segment(start, end, kind, name, link, float(np.hypot(*(plan.tips[end] - a)))))


def _finish(plan: Plan, fixed: set, prefix: str) -> Plan:
    """Absolute vectors from the pole to every moving point."""
    for p, v in list(plan.tips.items()):
        if plan.point_of_tip.get(p) == p and p not in fixed:
            _seg(plan, "p", p, "abs", f"{prefix}_{p}")
    return plan


def velocity_plan(row: pd.Series, mech: Mechanism) -> Plan:
    plan, fixed = _start("velocity", row, mech)
    for link in mech.moving:
        ref = _reference(mech, link)
        for p in link.points:
            if p == ref:
                continue
            _seg(plan, ref, p, "rel", f"V_{p}{ref}", link.name)
    for j in mech.prismatic:
        guide, slider = j.links
        if guide == FRAME:
            continue
        v, _ = _coincident(row, mech, guide, j.point)
        lab = f"{j.point}{guide}"
        plan.tips[lab] = v
        plan.point_of_tip[lab] = j.point
        _seg(plan, lab, j.point, "slide", f"V_{j.point}{slider}{j.point}{guide}", slider)
    return _finish(plan, fixed, "V")


def acceleration_plan(row: pd.Series, mech: Mechanism) -> Plan:
    plan, fixed = _start("acceleration", row, mech)
    for link in mech.moving:
        ref = _reference(mech, link)
        w, e = row["w_" + link.name], row["e_" + link.name]
        for p in link.points:
            if p == ref:
                continue
            r = _vec(row, "", p) - _vec(row, "", ref)
            an = -w * w * r
            lab = f"n{p}{ref}"
            plan.tips[lab] = plan.tips[ref] + an
            _seg(plan, ref, lab, "normal", f"a^n_{p}{ref}", link.name)
            _seg(plan, lab, p, "tangential", f"a^τ_{p}{ref}", link.name)
    for j in mech.prismatic:
        guide, slider = j.links
        if guide == FRAME:
            continue
        v_g, a_g = _coincident(row, mech, guide, j.point)
        lab = f"{j.point}{guide}"
        plan.tips[lab] = a_g
        plan.point_of_tip[lab] = j.point
        v_rel = _vec(row, "v", j.point) - v_g
        ak = 2.0 * row["w_" + guide] * _rot90(v_rel)
        klab = f"k{j.point}"
        plan.tips[klab] = a_g + ak
        _seg(plan, lab, klab, "coriolis", f"a^k_{j.point}{slider}{j.point}{guide}", slider)
        _seg(plan, klab, j.point, "slide", f"a^r_{j.point}{slider}{j.point}{guide}", slider)
    return _finish(plan, fixed, "a")


def output_quantity(study) -> tuple[str, str, str, str]:
    """The output link's displacement column and its analog columns, with a Russian name:
    a slider on the frame (s_J), otherwise the last rocker pivoted on the frame (phi_k)."""
    mech = study.mechanism
    node = study.root.table("report")
    chosen = node.string("output")
    if chosen:
        pre, _, name = chosen.partition("_")
        title = node.text("output_title", chosen)
        if chosen not in study.kinematics.columns:
            raise node.error("output", f"нет столбца «{chosen}»",
                             expected="столбец кинематики: s_<пара>, phi_<звено>, x_<точка> или y_<точка>")
        if pre == "s":
            return chosen, f"vqs_{name}", f"aqs_{name}", title
        if pre == "phi":
            return chosen, f"wq_{name}", f"eq_{name}", title
        if pre in ("x", "y"):
            return chosen, f"vq{pre}_{name}", f"aq{pre}_{name}", title
        raise node.error("output", f"столбец «{chosen}» не является перемещением",
                         expected="s_<пара>, phi_<звено>, x_<точка> или y_<точка>")
    for j in reversed(mech.prismatic):
        if j.links[0] == FRAME:
            return f"s_{j.name}", f"vqs_{j.name}", f"aqs_{j.name}", f"ползун {j.links[1]}"
    groups = study.structure.groups
    for g in reversed(groups):
        for l in g.links:
            if any(FRAME in jt.links and l in jt.links for jt in mech.joints):
                return f"phi_{l}", f"wq_{l}", f"eq_{l}", f"звено {l}"
    l = groups[-1].links[-1]
    return f"phi_{l}", f"wq_{l}", f"eq_{l}", f"звено {l}"
