"""Curves over the cycle: kinematic diagrams s, v, a of the output link and the analogs."""
from __future__ import annotations

import math

import numpy as np

from ..analysis.plans import output_quantity
from ..style import mplstyle
from ..mechanism.model import FRAME
from .draw import SUBSCRIPT, legend_rows
from .mechanism import Drawing


def q_axis(study, q: np.ndarray) -> np.ndarray:
    """Abscissa of a curve over the cycle: the crank angle from the cycle's start, the input
    rocker's own angle φ over its swing (degrees), or the actuator's length (m, as the tables and
    the force diagrams give it)."""
    d = study.mechanism.driver
    if d.swing:
        return np.degrees(q)
    if d.rotary:
        return np.degrees(q - study.grid.start)
    return q


def angle_ticks(ax, x: np.ndarray, step: float) -> None:
    """Angle axis in whole steps over the curve's range (0…360° for a crank's turn, the swing of
    an input rocker)."""
    lo, hi = step * math.floor(float(np.min(x)) / step + 1e-9), step * math.ceil(float(np.max(x)) / step - 1e-9)
    ax.set_xticks(np.arange(lo, hi + 0.5 * step, step))
    ax.set_xlim(lo, hi)


def _xaxis(study, cyc):
    d = study.mechanism.driver
    if d.swing:
        return q_axis(study, cyc["q"].to_numpy()), "φ, град", 10
    if d.rotary:
        return q_axis(study, cyc["q"].to_numpy()), "φ, град", 30
    return q_axis(study, cyc["q"].to_numpy()), "S, м", None


def output_index(study, s_col: str) -> str:
    """The subscript of the output's symbols: the moving link of a slider's pair (s_J), the rocker
    (phi_L) or the point (x_P, y_P), as the tables name them (s₅, φ₃, s_D)."""
    pre, _, name = s_col.partition("_")
    if pre == "s":
        j = next((j for j in study.mechanism.joints if j.name == name), None)
        name = next((l for l in j.links if l != FRAME), name) if j is not None else name
    return name.translate(SUBSCRIPT) if name.isdigit() else ""


def output_displacement(study, s_col: str) -> tuple[np.ndarray, int]:
    """The output's displacement over the cycle measured from its extreme position of least
    coordinate (s = x − x_min ∈ [0, H], a rocker's ψ = φ − φ_min), as the textbook's kinematic
    diagram plots it (Артоболевский, § «Кинематические диаграммы»), and that position's cycle
    index. The shift keeps v = ds/dt and a equal to the tables' signed values."""
    s = study.cycle[s_col].to_numpy()
    if s_col.startswith("phi_"):
        s = np.unwrap(s)
    i0 = int(np.argmin(s))
    return s - s[i0], i0


class OutputDiagrams:
    """s(φ), v(φ), a(φ) of the output link (true values when ω is known, analogs otherwise),
    s measured from the output's extreme position, with the report positions marked."""

    needs = ("cycle", "kinematics")

    def __init__(self, output: tuple[str, str, str, str] | None = None):
        """``output``: which output (an :func:`~reportgen.analysis.plans.output_quantity` tuple;
        one of ``parallel_outputs`` for a mechanism with several); by default the output."""
        self.output = output

    def draw(self, study) -> Drawing:
        cyc = study.cycle
        s_col, v_col, a_col, title = self.output or output_quantity(study)
        x, xlabel, step = _xaxis(study, cyc)
        angular = s_col.startswith("phi_")
        true = study.mechanism.driver.omega is not None
        pre, _, name = s_col.partition("_")
        if true:
            vname, aname = {"phi": ("w", "e"), "s": ("vs", "as"), "x": ("vx", "ax"), "y": ("vy", "ay")}[pre]
            v, a = cyc[f"{vname}_{name}"], cyc[f"{aname}_{name}"]
        else:
            v, a = cyc[v_col], cyc[a_col]
        s, i0 = output_displacement(study, s_col)
        if angular:
            s = np.degrees(s)
        rotary = study.mechanism.driver.rotary
        n = output_index(study, s_col)
        if true:
            units = ((f"ψ{n}, град", f"ω{n}, рад/с", f"ε{n}, рад/с²") if angular
                     else (f"s{n}, м", f"v{n}, м/с", f"a{n}, м/с²"))
        elif angular:
            # the radian is dimensionless: d/dφ keeps the unit (as the tables of analogs print it)
            units = (f"ψ{n}, град", f"ψ′{n}" + ("" if rotary else ", 1/м"), f"ψ″{n}" + ("" if rotary else ", 1/м²"))
        else:
            units = (f"s{n}, м", f"s′{n}" + (", м" if rotary else ""), f"s″{n}" + (", м" if rotary else ", 1/м"))
        fig = mplstyle.figure(160, 175)
        axs = fig.subplots(3, 1, sharex=True)
        kin = study.kinematics
        kq = kin["q"].to_numpy()
        kx = q_axis(study, kq)
        for ax, y, lab in zip(axs, (s, np.asarray(v), np.asarray(a)), units):
            ax.plot(x, y, lw=1.3)
            ax.axhline(0, color="0.3", lw=0.6)
            ax.set_ylabel(lab)
            yi = np.interp(kx, x, y) if np.all(np.diff(x) > 0) else None
            if yi is not None:
                ax.plot(kx, yi, "o", ms=3)
        axs[-1].set_xlabel(xlabel)
        if step:
            angle_ticks(axs[-1], x, step)
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)


class AnalogCurves:
    """First analogs of the angular velocities of all links over the cycle."""

    needs = ("cycle",)

    def draw(self, study) -> Drawing:
        cyc = study.cycle
        x, xlabel, step = _xaxis(study, cyc)
        fig = mplstyle.figure(160, 80)
        ax = fig.add_subplot()
        d = study.mechanism.driver
        for link in study.mechanism.moving:
            if d.rotary and link.name == d.link:
                continue
            if d.kind == "actuator" and link.name == d.rod:
                continue
            col = "wq_" + link.name
            if np.ptp(cyc[col].to_numpy()) < 1e-12 and abs(cyc[col].iloc[0]) < 1e-12:
                continue
            ax.plot(x, cyc[col], lw=1.2, label="φ′" + link.name.translate(SUBSCRIPT))
        ax.axhline(0, color="0.3", lw=0.6)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("аналог угловой скорости φ′" + ("" if d.rotary else ", 1/м"))   # dφ/dS has 1/м
        legend_rows(ax, 4, fontsize=9, loc="best")
        if step:
            angle_ticks(ax, x, step)
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)
