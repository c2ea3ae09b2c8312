"""Scenes of the dynamics section: curves over the cycle, the energy–mass (Виттенбауэр) diagram
and the flywheel drawn with its dimensions.  They draw ``study.dynamics`` results only."""
from __future__ import annotations

import math

import numpy as np
from matplotlib.patches import Circle, Rectangle, Wedge

from ..style import mplstyle
from ..style.numbers import fmt, position_names
from .draw import INK, NUMBER_GAP_MM, Canvas, legend_rows
from .labels import LabelPlacer, place_on_chart
from .forces import math_label
from .mechanism import Drawing

__all__ = ["InertiaCurves", "MomentCurves", "WorkCurves", "EnergyCurves", "WittenbauerDiagram",
           "MotionCurves", "FlywheelDrawing", "LoadLaws", "law_units", "load_label", "shown_laws"]

_NEEDS = ("dynamics",)


def _x(study, q):
    d = study.dynamics
    return np.degrees(np.asarray(q, dtype=float) - d.settings.cycle_start)


def _xaxis(ax, study):
    L = math.degrees(study.dynamics.settings.cycle_length)
    step = 30 if L <= 360 else 60
    ax.set_xticks(np.arange(0, L + 1, step))
    ax.set_xlim(0, L)
    ax.set_xlabel("φ, град")


def _cycle_axes(study, height_mm: float):
    """The cycle table of the dynamics, its φ in degrees from the cycle's start, and a figure
    160 mm wide with one axes for curves over the cycle."""
    cyc = study.dynamics.cycle
    fig = mplstyle.figure(160, height_mm)
    return cyc, _x(study, cyc["q"]), fig, fig.add_subplot()


def _cycle_drawing(fig, ax, study, ylabel: str, per_row: int = 1) -> Drawing:
    """The curves over the cycle finished: the φ axis, the value axis' label, the legend (at most
    ``per_row`` entries a row, read row by row; of several columns, above the axes)."""
    _xaxis(ax, study)
    ax.set_ylabel(ylabel)
    if per_row > 1:
        # a legend of several columns above the axes, as on the reactions' chart: inside, where «best»
        # put it, it hid a piece of M_с (every corner of a cycle of reduced moments holds a curve)
        legend_rows(ax, per_row, fontsize=9, loc="lower center", bbox_to_anchor=(0.5, 1.0), frameon=False)
    else:
        legend_rows(ax, per_row, fontsize=9, loc="best")
    return Drawing(mplstyle.to_svg(fig), 160, 0.0)


def _marks(ax, study, col):
    """Report positions as points on a curve."""
    t = study.dynamics.table
    ax.plot(_x(study, t["q"]), t[col], "o", ms=3, color=INK, zorder=5)


def load_label(name: str) -> str:
    """mathtext label of a reduced moment: G2 → $M_{G2}$."""
    return f"$M_{{\\mathrm{{{name}}}}}$"


def table_laws(study) -> list[tuple[list[str], object, object]]:
    """The load laws the case gives by tables (an indicator diagram, a cutting-force diagram):
    (the loads' names, the load, its piece), a table shared by several loads (two cylinders
    with one indicator diagram) once, with all their names."""
    out: list[tuple[list[str], object, object]] = []
    for ld in study.dynamics.loads.loads:
        for p in ld.pieces:
            if p.table is None:
                continue
            same = next((o for o in out if o[2].name == p.name and np.array_equal(o[2].table.x, p.table.x)
                         and np.array_equal(o[2].table.y, p.table.y) and (o[1].area is None) == (ld.area is None)
                         and o[1].kind == ld.kind), None)
            if same is None:
                out.append(([ld.name], ld, p))
            else:
                same[0].append(ld.name)
    return out


def shown_laws(study) -> list[tuple[list[str], object, object]]:
    """The table laws drawn on one chart: those in the units of the first (value and argument)."""
    laws = table_laws(study)
    if not laws:
        return []

    def key(law):
        return law_units(law[1], law[2])[0], argument_units(law[2])[0], law[1].area is None, law[1].kind
    return [law for law in laws if key(law) == key(laws[0])]


def law_units(ld, p) -> tuple[str, float]:
    """The unit a load law's value is shown in: МПа for a pressure (the law times an area),
    кН or кН·м above 10⁴, else Н or Н·м."""
    big = float(np.max(np.abs(p.table.y))) if p.table is not None else abs(float(p.const))
    if ld.kind == "moment":
        return ("кН·м", 1e3) if big >= 1e4 else ("Н·м", 1.0)
    if ld.area is not None:
        return "МПа", 1e6
    return ("кН", 1e3) if big >= 1e4 else ("Н", 1.0)


def argument_units(p) -> tuple[str, float]:
    """The unit of a table's argument on the drawing: мм for a length, градусы for an angle."""
    from ..case import units as U
    dim = tuple(p.of.dim) if p.of is not None else U.ANGLE
    if dim == tuple(U.LENGTH):
        return "мм", 1e-3
    if dim == tuple(U.ANGLE):
        return "град", math.pi / 180
    return "", 1.0


class LoadLaws:
    """The loads given by tables as the case gives them: the value against the table's argument
    (for an engine or a compressor — the indicator diagram p(s)), one line per law or stroke."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        fig = mplstyle.figure(160, 85)
        ax = fig.add_subplot()
        laws = shown_laws(study)
        ld0, p0 = laws[0][1], laws[0][2]
        vu, k = law_units(ld0, p0)
        xu, kx = argument_units(p0)
        for names, ld, p in laws:
            label = ", ".join(math_label(n) for n in names) + (f" ({p.name})" if p.name else "")
            ax.plot(p.table.x / kx, p.table.y / k, lw=1.2, marker="o", ms=2.5, label=label)
        ax.axhline(0, color="0.3", lw=0.6)
        what = "p" if ld0.area is not None else ("M" if ld0.kind == "moment" else "F")
        ax.set_ylabel(f"${what}$, {vu}")
        ax.set_xlabel(f"$x$, {xu}" if xu else "$x$")
        ax.legend(fontsize=9, loc="best")
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)


class InertiaCurves:
    """J_II(φ) and the contribution of each link."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        cyc, x, fig, ax = _cycle_axes(study, 85)
        ax.plot(x, cyc["J_II"], lw=1.8, color=INK, label="$J_{II}$")
        for il in study.dynamics.model.links:
            ax.plot(x, cyc["J_II_" + il.name], lw=1.0, label=f"звено {il.name}")
        _marks(ax, study, "J_II")
        return _cycle_drawing(fig, ax, study, "$J_{II}$, кг·м²", per_row=4)


class MomentCurves:
    """Reduced moments of each load, M_c (their sum or the constant), M_д and M_Σ."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        d = study.dynamics
        cyc, x, fig, ax = _cycle_axes(study, 95)
        names = ["M_" + n for n in d.loads.names if n not in d.idle_loads]
        for c in names:
            ax.plot(x, cyc[c], lw=0.9, label=load_label(c[2:]))
        ax.plot(x, cyc["M_c"], lw=1.6, color=INK, label="$M_{с}$")
        ax.plot(x, cyc["M_d"], lw=1.6, ls="--", color=INK, label="$M_{д}$")
        ax.plot(x, cyc["M_sum"], lw=1.0, ls=":", color=INK, label="$M_{\\Sigma}$")
        ax.axhline(0, color="0.3", lw=0.6)
        return _cycle_drawing(fig, ax, study, "$M_{пр}$, Н·м", per_row=4)


class WorkCurves:
    """A_c(φ), A_д(φ) and A_Σ(φ)."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        cyc, x, fig, ax = _cycle_axes(study, 85)
        ax.plot(x, cyc["A_c"], lw=1.4, color=INK, label="$A_{с}$")
        ax.plot(x, cyc["A_d"], lw=1.4, ls="--", color=INK, label="$A_{д}$")
        ax.plot(x, cyc["A_sum"], lw=1.4, label="$A_{\\Sigma} = \\Delta T$")
        ax.axhline(0, color="0.3", lw=0.6)
        return _cycle_drawing(fig, ax, study, "$A$, Дж")


class EnergyCurves:
    """ΔT(φ) = A_Σ, T_II ≈ J_II ω_ср²/2 and ΔT_I = ΔT − T_II (Мерцалов) with its extremes."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        sc = study.dynamics.scalars
        cyc, x, fig, ax = _cycle_axes(study, 90)
        ax.plot(x, cyc["A_sum"], lw=1.2, ls="--", color=INK, label="$\\Delta T = A_{\\Sigma}$")
        ax.plot(x, cyc["T_II"], lw=1.0, label="$T_{II} = J_{II}\\,\\omega_{ср}^2/2$")
        ax.plot(x, cyc["dT_I"], lw=1.6, color=INK, label="$\\Delta T_{I} = \\Delta T - T_{II}$")
        notes = LabelPlacer(ax, fontsize=9)      # the extremes' notes clear of the curves and the legend
        for key, up in (("max", 1), ("min", -1)):
            px = _x(study, sc[f"q_dT_I_{key}"])
            v = sc[f"dT_I_{key}"]
            ax.plot([px], [v], "o", color=INK, ms=5)
            ax.axhline(v, color="0.4", lw=0.6, ls=(0, (4, 2)))
            notes.add(px, v, f"$\\Delta T_{{I\\,{key}}}$ = {fmt(v, sig=5)} Дж", prefer=(1, up), point=True)
        ax.axhline(0, color="0.3", lw=0.6)
        ax.margins(y=0.2)             # room for the notes of the extremes inside the axes
        _xaxis(ax, study)
        ax.set_ylabel("Дж")
        # in the lower corner away from the minimum, whose note the legend would hide
        lo, hi = ax.get_xlim()
        left = _x(study, sc["q_dT_I_min"]) < (lo + hi) / 2
        legend = ax.legend(fontsize=9, loc="lower right" if left else "lower left")
        place_on_chart(notes, avoid=[legend])
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)


class WittenbauerDiagram:
    """Energy–mass diagram ΔT(J_II) with the tangents of slopes ω_max²/2, ω_min²/2 and the
    segment KL they cut on the ΔT axis (J_II = 0)."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        d = study.dynamics
        wi = d.result.wittenbauer
        cyc = d.cycle
        J, T = cyc["J_II"].to_numpy(), cyc["A_sum"].to_numpy()
        fig = mplstyle.figure(160, 120)
        ax = fig.add_subplot()
        ax.plot(J, T, lw=1.4, color=INK, label="$\\Delta T(J_{II})$")
        t = d.table
        ax.plot(t["J_II"], t["A_sum"], "o", ms=3, color=INK)
        # positions whose points coincide (the curve passes one point twice) share one label «3, 9»
        scale = np.array([max(np.ptp(J), 1e-300), max(np.ptp(T), 1e-300)])
        groups: list[tuple[np.ndarray, list[str]]] = []
        number = position_names(t["pos"])          # positions by number, as the tables print them
        for _, r in t.iterrows():
            xy = np.array([r["J_II"], r["A_sum"]], dtype=float)
            no = number.get(str(r["pos"]), str(r["pos"]))
            near = next((g for g in groups if np.all(np.abs(g[0] - xy) < 0.005 * scale)), None)
            if near is None:
                groups.append((xy, [no]))
            else:
                near[1].append(no)
        labels = LabelPlacer(ax, fontsize=7)       # clear of the curve, the tangents and each other
        for xy, names in groups:
            labels.add(*xy, ", ".join(names), prefer=(1, 1), gap_mm=NUMBER_GAP_MM)
        jmax = float(J.max()) * 1.08
        jj = np.array([0.0, jmax])
        ax.plot(jj, wi.upper_tangent(jj), lw=1.0, color="#b2182b",
                label="касательная, $\\mathrm{tg}\\,\\psi_{max} \\sim \\omega_{max}^2/2$")
        ax.plot(jj, wi.lower_tangent(jj), lw=1.0, color="#1f4e9c",
                label="касательная, $\\mathrm{tg}\\,\\psi_{min} \\sim \\omega_{min}^2/2$")
        for tp, col in ((wi.tangent_max, "#b2182b"), (wi.tangent_min, "#1f4e9c")):
            ax.plot([tp.J], [tp.dT], "s", ms=5, mfc="white", mec=col, zorder=6)
        ax.axvline(0, color=INK, lw=0.9)
        ax.axhline(0, color="0.3", lw=0.6)
        # the length of KL in the legend: beside the segment it would cover the labels of positions
        ax.plot([0, 0], [wi.L, wi.K], color=INK, lw=3.0, solid_capstyle="butt", zorder=7,
                label=f"отрезок KL = {fmt(wi.KL, sig=5)} Дж")
        labels.add(0, wi.K, "K", prefer=(1, 1), fontsize=11, style="italic", point=True)
        labels.add(0, wi.L, "L", prefer=(1, -1), fontsize=11, style="italic", point=True)
        ax.set_xlim(-0.04 * jmax, jmax)
        ax.set_xlabel("$J_{II}$, кг·м²")
        ax.set_ylabel("$\\Delta T$, Дж")
        legend_rows(ax, 2, fontsize=9, loc="upper center", bbox_to_anchor=(0.5, -0.1))
        place_on_chart(labels)
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)


class MotionCurves:
    """ω(φ) and ε(φ) of the chosen method, the exact motion beside an approximate one."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        d = study.dynamics
        cyc = d.cycle
        s = d.settings
        x = _x(study, cyc["q"])
        fig = mplstyle.figure(160, 130)
        a1, a2 = fig.subplots(2, 1, sharex=True)
        name = {"exact": "точное решение", "mertsalov": "метод Мерцалова",
                "wittenbauer": "метод Виттенбауэра"}
        a1.plot(x, cyc["omega"], lw=1.6, color=INK, label=name[s.method])
        if s.method == "mertsalov":
            a1.plot(x, cyc["omega_exact"], lw=1.0, ls="--", label="точное решение с тем же $J_I$")
        a1.axhline(s.omega_m, color="0.3", lw=0.7, ls=(0, (4, 2)))
        mean = LabelPlacer(a1, fontsize=9)       # at the right end of its line, clear of the curves and the legend
        mean.add(x[-1], s.omega_m, "$\\omega_{ср}$", prefer=(-24, 3), point=True)
        _marks(a1, study, "omega")
        a1.set_ylabel("ω, рад/с")
        legend = a1.legend(fontsize=9, loc="best")
        a2.plot(x, cyc["eps"], lw=1.4, color=INK)
        a2.axhline(0, color="0.3", lw=0.6)
        _marks(a2, study, "eps")
        a2.set_ylabel("ε, рад/с²")
        _xaxis(a2, study)
        place_on_chart(mean, avoid=[legend])
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)


# --------------------------------------------------------------------------------------------
# Flywheel
# --------------------------------------------------------------------------------------------
def _dim(ax, p1, p2, text, off, mu, vertical=False):
    """A dimension line between p1 and p2 shifted by ``off`` (data units, perpendicular), with
    extension lines, arrows and the text on the outer side (away from the part): in the middle of
    a horizontal one, in the middle of the upper half of a vertical one (a diameter)."""
    (x1, y1), (x2, y2) = p1, p2
    if vertical:
        a, b = (x1 + off, y1), (x2 + off, y2)
        ax.plot([x1, a[0]], [y1, y1], color=INK, lw=0.5)
        ax.plot([x2, b[0]], [y2, y2], color=INK, lw=0.5)
    else:
        a, b = (x1, y1 + off), (x2, y2 + off)
        ax.plot([x1, x1], [y1, a[1]], color=INK, lw=0.5)
        ax.plot([x2, x2], [y2, b[1]], color=INK, lw=0.5)
    ax.annotate("", a, b, arrowprops=dict(arrowstyle="<|-|>", lw=0.6, color=INK, mutation_scale=7,
                                          shrinkA=0, shrinkB=0))
    mx, my = 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])
    if vertical:
        # a diameter's middle lies on the part's horizontal centre line: the number goes to the
        # middle of the upper half, so that no line crosses it (ГОСТ 2.307)
        my = a[1] + 0.75 * (b[1] - a[1])
        side = 1.0 if off > 0 else -1.0
        ax.text(mx + side * 1.0 * mu, my, text, rotation=90, ha="left" if side > 0 else "right",
                va="center", fontsize=9)
    else:
        ax.text(mx, my + 1.0 * mu, text, ha="center", va="bottom", fontsize=9)


DIM_GAP_MM = 7.0     # the flywheel's views at least this far apart on paper: dimension line, number, clearance
DIM_TEXT_MM = 1.5    # a vertical dimension's number this far beyond its line (the number's height in the margin)


def _mm(x: float) -> str:
    return fmt(x * 1000, digits=0)


class FlywheelDrawing:
    """The flywheel to scale: a rim with spokes and hub (front view and section) and a solid
    disk (front view and section), with the computed dimensions D₂, D₁, b and D, b in mm.
    The hub and spokes are drawn in the usual proportions (hub 0.25·D₂, six spokes); only the
    dimensioned sizes are computed."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        fw = study.dynamics.result.flywheel
        rim, disk = fw.rim, fw.disk
        R2, R1, b = rim.D2 / 2, rim.D1 / 2, rim.b
        Rd, bd = disk.D / 2, disk.b
        ys = [-R2 - 0.3 * R2, R2 + 0.3 * R2]
        gap, mu = 0.35 * R2, 0.0
        for _ in range(6):
            # layout (m): rim front at (0, 0), rim section at (R2 + gap + b/2, 0),
            # disk front at (x3, 0), disk section at (x4, 0); the last diameter's number right of
            # the disk's section, beyond its dimension line (0,35·gap out) by DIM_TEXT_MM
            xs_rim = R2 + gap + b / 2
            x3 = xs_rim + b / 2 + gap + Rd
            x4 = x3 + Rd + gap + bd / 2
            xs = [-R2 - 0.2 * R2, x4 + bd / 2 + max(0.25 * R2, 0.35 * gap + DIM_TEXT_MM * mu)]
            # the views DIM_GAP_MM apart on paper at least: room for a diameter's dimension and
            # its number between two views (at a small scale 0,35·D₂/2 is a few millimetres)
            fit = Canvas.scale(xs, ys, avail_w=150, avail_h=90, margin_mm=4, gost=True)
            if fit <= mu and gap >= DIM_GAP_MM * mu * (1 - 1e-9):
                break
            mu = max(mu, fit)
            gap = max(gap, DIM_GAP_MM * mu)
        cv = Canvas.fit(xs, ys, avail_w=150, avail_h=90, margin_mm=4, gost=True)
        ax, mu = cv.ax, cv.mu
        hub_R, bore_R = 0.125 * rim.D2, 0.05 * rim.D2
        # rim front view
        ax.add_patch(Wedge((0, 0), R2, 0, 360, width=R2 - R1, fc="#d9d9d9", ec=INK, lw=1.0))
        ax.add_patch(Circle((0, 0), hub_R, fc="#d9d9d9", ec=INK, lw=1.0))
        ax.add_patch(Circle((0, 0), bore_R, fc="white", ec=INK, lw=0.8))
        w = 0.035 * rim.D2
        for k in range(6):
            th = k * math.pi / 3 + math.pi / 6
            c, s = math.cos(th), math.sin(th)
            for sgn in (-1, 1):
                ox, oy = -s * w * sgn, c * w * sgn
                ax.plot([hub_R * c + ox, R1 * c + ox], [hub_R * s + oy, R1 * s + oy], color=INK, lw=0.8)
        ax.plot([-R2 * 1.08, R2 * 1.08], [0, 0], color=INK, lw=0.4, ls=(0, (8, 2, 1, 2)))
        ax.plot([0, 0], [-R2 * 1.08, R2 * 1.08], color=INK, lw=0.4, ls=(0, (8, 2, 1, 2)))
        # rim section
        cx = xs_rim
        for sgn in (1, -1):
            y0 = R1 if sgn > 0 else -R2
            ax.add_patch(Rectangle((cx - b / 2, y0), b, R2 - R1, fc="#bdbdbd", ec=INK, lw=1.0, hatch="////"))
            ax.add_patch(Rectangle((cx - 0.2 * b, hub_R if sgn > 0 else -R1), 0.4 * b, R1 - hub_R, fc="white",
                                   ec=INK, lw=0.6))
        ax.add_patch(Rectangle((cx - 0.6 * b, -hub_R), 1.2 * b, 2 * hub_R, fc="#bdbdbd", ec=INK, lw=1.0, hatch="////"))
        ax.add_patch(Rectangle((cx - 0.6 * b, -bore_R), 1.2 * b, 2 * bore_R, fc="white", ec=INK, lw=0.8))
        ax.plot([cx - b, cx + b], [0, 0], color=INK, lw=0.4, ls=(0, (8, 2, 1, 2)))
        _dim(ax, (cx + b / 2, -R2), (cx + b / 2, R2), f"Ø{_mm(rim.D2)}", 0.35 * gap, mu, vertical=True)
        _dim(ax, (cx - b / 2, -R1), (cx - b / 2, R1), f"Ø{_mm(rim.D1)}", -0.35 * gap, mu, vertical=True)
        _dim(ax, (cx - b / 2, R2), (cx + b / 2, R2), f"{_mm(b)}", 0.12 * R2, mu)
        ax.text(0, -R2 - 0.22 * R2, "обод со спицами", ha="center", va="top", fontsize=9)
        # disk front and section
        ax.add_patch(Circle((x3, 0), Rd, fc="#d9d9d9", ec=INK, lw=1.0))
        ax.add_patch(Circle((x3, 0), bore_R, fc="white", ec=INK, lw=0.8))
        ax.plot([x3 - Rd * 1.08, x3 + Rd * 1.08], [0, 0], color=INK, lw=0.4, ls=(0, (8, 2, 1, 2)))
        ax.plot([x3, x3], [-Rd * 1.08, Rd * 1.08], color=INK, lw=0.4, ls=(0, (8, 2, 1, 2)))
        for sgn in (1, -1):
            y0 = bore_R if sgn > 0 else -Rd
            ax.add_patch(Rectangle((x4 - bd / 2, y0), bd, Rd - bore_R, fc="#bdbdbd", ec=INK, lw=1.0, hatch="////"))
        ax.plot([x4 - bd, x4 + bd], [0, 0], color=INK, lw=0.4, ls=(0, (8, 2, 1, 2)))
        _dim(ax, (x4 + bd / 2, -Rd), (x4 + bd / 2, Rd), f"Ø{_mm(disk.D)}", 0.35 * gap, mu, vertical=True)
        _dim(ax, (x4 - bd / 2, Rd), (x4 + bd / 2, Rd), f"{_mm(bd)}", 0.12 * R2, mu)
        ax.text(x3, -R2 - 0.22 * R2, "сплошной диск", ha="center", va="top", fontsize=9)
        return Drawing(cv.svg(), cv.width_mm, mu)
