"""Velocity and acceleration plans drawn to scale, and the table of values "measured" on them.

The vectors come from ``analysis.plans`` (exact); the scene draws them with a standard scale μ
and reads every segment back as a student would, to 0,5 mm, so that the report can compare the
graphical values with the analytical ones in %."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..analysis.plans import Plan, acceleration_plan, velocity_plan
from .draw import GREY, INK, SUBSCRIPT, Canvas, arrow

READ_MM = 0.5        # reading accuracy of a length on the drawing, mm
MIN_MM = 5.0         # shorter segments are drawn but not compared (reading error dominates)
STYLE = {"abs": dict(color=INK, lw=1.3, ls="-"), "rel": dict(color=INK, lw=1.0, ls="-"),
         "normal": dict(color=GREY, lw=1.0, ls="--"), "tangential": dict(color=INK, lw=1.0, ls="-."),
         "coriolis": dict(color=GREY, lw=1.0, ls="--"), "slide": dict(color=INK, lw=1.0, ls=":")}


@dataclass
class PlanDrawing:
    svg: bytes
    width_mm: float
    mu: float
    table: pd.DataFrame       # segment, analytic value, length on the plan (mm), graphic value, Δ %
    plan: Plan


def _tip_label(lab: str, plan: Plan, kind: str) -> str:
    """Lower-case plan points (a, b, s₂; a′, b′ on the acceleration plan), n and k for the
    ends of the normal and Coriolis components."""
    if lab.startswith("n") and lab not in plan.point_of_tip:
        return "n" + lab[1:].lower().translate(SUBSCRIPT)
    if lab.startswith("k") and lab not in plan.point_of_tip:
        return "k"
    head = lab.rstrip("0123456789")
    tail = lab[len(head):]
    return head.lower() + ("′" if kind == "acceleration" else "") + tail.translate(SUBSCRIPT)


class PlanScene:
    needs = ("kinematics",)

    def __init__(self, label: str, kind: str):
        self.label = label
        self.kind = kind

    def draw(self, study) -> PlanDrawing:
        k = study.kinematics
        row = k[k["pos"] == self.label].iloc[0]
        mech = study.mechanism
        plan = velocity_plan(row, mech) if self.kind == "velocity" else acceleration_plan(row, mech)
        pts = np.array([[0.0, 0.0]] + [list(v) for v in plan.tips.values()])
        cv = Canvas.fit(pts[:, 0], pts[:, 1], avail_w=140, avail_h=150, margin_mm=10)
        ax = cv.ax
        for seg in plan.segments:
            a = np.zeros(2) if seg.start == "p" else plan.tips[seg.start]
            b = plan.tips[seg.end]
            st = STYLE[seg.kind]
            arrow(ax, a[0], a[1], b[0], b[1], color=st["color"], lw=st["lw"], ls=st["ls"])
        pole = "p" if self.kind == "velocity" else "π"
        ax.plot([0], [0], marker="o", ms=3, color=INK)
        ax.text(-cv.mm(3), -cv.mm(3), pole, fontsize=10, style="italic", ha="center", va="center")
        placed = {}
        for lab, v in plan.tips.items():
            if np.hypot(*v) < 1e-12 and lab in plan.point_of_tip:
                continue
            key = (round(v[0] / cv.mm(1.5)), round(v[1] / cv.mm(1.5)))
            n = placed.get(key, 0)
            placed[key] = n + 1
            d = np.hypot(*v) or 1.0
            ox, oy = v / d * cv.mm(3.2) if d > 1e-12 else (cv.mm(2), cv.mm(2))
            ax.text(v[0] + ox, v[1] + oy + n * cv.mm(3.5), _tip_label(lab, plan, self.kind), fontsize=9,
                    ha="center", va="center")
        table = measure(plan, cv.mu)
        return PlanDrawing(cv.svg(), cv.width_mm, cv.mu, table, plan)


def measure(plan: Plan, mu: float) -> pd.DataFrame:
    """Every segment read off the plan: length rounded to READ_MM, times μ; discrepancy in %."""
    rows = []
    for seg in plan.segments:
        mm = seg.length / mu
        if mm < MIN_MM:
            continue
        read = round(mm / READ_MM) * READ_MM
        graph = read * mu
        rows.append(dict(name=seg.name, kind=seg.kind, link=seg.link, analytic=seg.length, mm=read,
                         graphic=graph, delta=abs(graph - seg.length) / seg.length * 100.0))
    return pd.DataFrame(rows)
