"""Scenes of the cam section: the diagrams s″, s′, s at stated scales, the phase portrait with the
tangent rays and the allowed region, the pressure angle over the cycle and the profile at a
standard scale (ГОСТ 2.302) with the follower in a few positions.  They draw ``study.cam`` only."""
from __future__ import annotations

import math

import numpy as np
from matplotlib.patches import Circle, Polygon

from ..style import mplstyle
from .draw import GREY, INK, LIGHT, Canvas, centre_cross, nice_scale
from .labels import LabelPlacer, place_on_chart
from .mechanism import Drawing

__all__ = ["LawDiagrams", "PhasePortrait", "FlatRockerSize", "PressureAngleGraph", "ProfileDrawing", "gost_scale",
           "follower_positions"]

_NEEDS = ("cam",)
# ГОСТ 2.302 scales as metres of the part per printed millimetre: 10:1 … 1:10
_GOST = ((0.0001, "10:1"), (0.0002, "5:1"), (0.00025, "4:1"), (0.0004, "2,5:1"), (0.0005, "2:1"),
         (0.001, "1:1"), (0.002, "1:2"), (0.0025, "1:2,5"), (0.004, "1:4"), (0.005, "1:5"), (0.01, "1:10"))
PLOT_W = 120.0          # mm of the φ axis: 360° at 3°/мм
PLOT_H = 36.0           # mm of each diagram


def gost_scale(extent_m: float, avail_mm: float) -> tuple[float, str]:
    """The largest standard scale (ГОСТ 2.302) at which ``extent_m`` fits into ``avail_mm``."""
    for mu, name in _GOST:
        if extent_m / mu <= avail_mm:
            return mu, name
    return _GOST[-1]


def follower_positions(cam) -> list[float]:
    """Cam angles of the follower drawn on the profile: start and middle of the rise, the far
    dwell, the middle of the return."""
    r, d, v = cam.phases[0], cam.phases[1], cam.phases[2]
    out = [0.0, r.start + r.length / 2, d.start + d.length / 2 if d.length > 0 else r.length,
           v.start + v.length / 2]
    return out


def _rocker(cam) -> bool:
    return cam.follower == "rocker"


def _unit(cam) -> tuple[float, str]:
    """Factor and unit of the displacement in the diagrams (mm, or degrees for a rocker)."""
    return (180 / math.pi, "°") if _rocker(cam) else (1000.0, "мм")


def _axis(fig, row: int, nrows: int, top_mm: float, total_h: float, left_mm: float, fig_w: float):
    bottom = total_h - top_mm - (row + 1) * PLOT_H - row * 9.0
    return fig.add_axes((left_mm / fig_w, bottom / total_h, PLOT_W / fig_w, PLOT_H / total_h))


def _scaled_ylim(ax, y: np.ndarray) -> float:
    """Limits of an exact-scale axis: μ units per mm from the standard row, 0 on a gridline."""
    lo, hi = float(min(y.min(), 0.0)), float(max(y.max(), 0.0))
    mu = nice_scale((hi - lo) * 1.08 or 1.0, PLOT_H)
    for _ in range(8):
        step = 5 * mu
        a = math.floor(lo / step) * step
        if a + PLOT_H * mu >= hi:
            ax.set_ylim(a, a + PLOT_H * mu)
            return mu
        mu = nice_scale(mu * 1.01 * PLOT_H, PLOT_H)
    ax.set_ylim(lo, lo + PLOT_H * mu)
    return mu


class LawDiagrams:
    """s″(φ), s′(φ), s(φ) one under another at exact scales; the true a, v on the right axis."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        cam = study.cam
        g = cam.grid
        s, s1, s2, _ = cam.law(g)
        f, unit = _unit(cam)
        names = (("s″", s2 * f, unit), ("s′", s1 * f, unit), ("s", s * f, unit))
        if _rocker(cam):
            names = (("ψ″", s2, ""), ("ψ′", s1, ""), ("ψ", s * f, "°"))
        fig_w, left, top = 160.0, 18.0, 4.0
        total_h = top + 3 * PLOT_H + 2 * 9.0 + 12.0
        fig = mplstyle.figure(fig_w, total_h, layout=None)
        self.scales = []
        x = np.degrees(g)
        for i, (lab, y, u) in enumerate(names):
            ax = _axis(fig, i, 3, top, total_h, left, fig_w)
            ax.plot(x, y, color=INK, lw=1.2)
            ax.axhline(0, color=GREY, lw=0.6)
            for ph in cam.phases:
                ax.axvline(math.degrees(ph.start), color=GREY, lw=0.5, ls=":")
            ax.set_xlim(0, 360)
            ax.set_xticks(np.arange(0, 361, 30))
            if i < 2:
                ax.set_xticklabels([])
            mu = _scaled_ylim(ax, y)
            ax.set_ylabel(f"{lab}, {u}" if u else lab)
            mplstyle.localize_axes(ax)
            if cam.omega is not None and i < 2:
                # the true acceleration and velocity on the right: a = ω²s″, v = ωs′
                w = cam.omega ** (2 - i) / (1.0 if _rocker(cam) else 1000.0)
                tw = ax.twinx()
                lo_, hi_ = ax.get_ylim()
                tw.set_ylim(lo_ * w, hi_ * w)
                tw.set_ylabel(("ε₂, рад/с²", "ω₂, рад/с")[i] if _rocker(cam) else ("a, м/с²", "v, м/с")[i])
                mplstyle.localize_axes(tw)
            self.scales.append((lab, mu, u))
        ax.set_xlabel("φ, град")
        self.mu_phi = 360.0 / PLOT_W
        return Drawing(mplstyle.to_svg(fig), fig_w, self.mu_phi)


class PhasePortrait:
    """The phase portrait in the plane of the cam centre: the points D = B − k v′ r (translating:
    (∓s′, s)), the rays touching it at the allowed angles, the allowed region (hatched), the
    approximate rays through the points of s′max (dashed), the centre O and B₀."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        cam = study.cam
        syn = cam.synthesis
        O = cam._O_synth
        pts_all, curves = [O], []
        for ph in (cam.rise, cam.ret):
            p = np.linspace(ph.start, ph.start + ph.length, 241)
            D = np.array([self._D(cam, x) for x in p])
            curves.append(D)
            pts_all.append(D)
        B = np.array([cam._geom(x, 1, O)["B"] for x in np.linspace(0, 2 * math.pi, 181)])
        pts_all.append(B)
        if cam.follower == "rocker":
            pts_all.append(np.zeros((1, 2)))     # the pivot A
        P = np.vstack([np.atleast_2d(a) for a in pts_all])
        span = P.max(axis=0) - P.min(axis=0)
        lo, hi = P.min(axis=0) - 0.12 * span.max(), P.max(axis=0) + 0.12 * span.max()
        mu = max(nice_scale(hi[0] - lo[0], 150), nice_scale(hi[1] - lo[1], 150))
        cv = Canvas(lo[0], hi[0], lo[1], hi[1], mu, margin_mm=6)
        ax = cv.ax
        # the allowed region: the box clipped by the two governing half-planes
        box = np.array([[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]]])
        reg = box
        for which, phi in ((1, syn.phi_rise), (2, syn.phi_return)):
            reg = _clip(reg, *cam.halfplane(which, phi))
        if len(reg) >= 3:
            ax.add_patch(Polygon(reg, closed=True, facecolor=LIGHT, edgecolor="none", hatch="///", zorder=0))
        for D in curves:
            ax.plot(D[:, 0], D[:, 1], color=INK, lw=1.3)
        if cam.follower == "rocker":
            ax.plot(B[:, 0], B[:, 1], color=GREY, lw=0.8, ls="--")
        else:   # the axes of the portrait through B₀: s up, ∓s′ across (sign by the sense of rotation)
            ax.axhline(0, color=GREY, lw=0.6)
            ax.axvline(0, color=GREY, lw=0.6)
            cv.labels.add(0, hi[1], "s", prefer=(4, -12))
            cv.labels.add(hi[0], 0, "−s′" if cam.k > 0 else "s′", prefer=(-16, 4))
        for D, nm in zip(curves, ("удаление", "возвращение")):
            i = int(np.argmax(np.hypot(*(D - D[0]).T)))
            cv.labels.add(*D[i], nm, prefer=(0, 1), fontsize=9)
        for which, phi in ((1, syn.phi_rise), (2, syn.phi_return)):
            self._ray(ax, cam, which, phi, lo, hi, "-")
            D = self._D(cam, phi)
            cv.labels.add(*D, "$K_у$" if which == 1 else "$K_в$", prefer=(5, -4), point=True)
        for which, phi in ((1, self._vmax(cam, cam.rise, 1)), (2, self._vmax(cam, cam.ret, -1))):
            self._ray(ax, cam, which, phi, lo, hi, "--", lw=0.7)
        ax.plot(*O, "o", color=INK, ms=4, zorder=5)
        cv.labels.add(*O, "O", prefer=(4, -10), point=True)
        B0 = cam._geom(0.0, 1, O)["B"]
        ax.plot(*B0, "o", color=INK, ms=3, zorder=5)
        cv.labels.add(*B0, "$B_0$", prefer=(4, 4), point=True)
        ax.plot([O[0], B0[0]], [O[1], B0[1]], color=INK, lw=0.8)
        if cam.follower == "rocker":
            ax.plot(0, 0, "o", color=INK, ms=4, zorder=5)
            cv.labels.add(0, 0, "A", prefer=(4, 4), point=True)
            ax.plot([0, O[0]], [0, O[1]], color=INK, lw=0.8, ls="-.")
            ax.plot([0, B0[0]], [0, B0[1]], color=INK, lw=1.4)
        self.mu = mu
        return Drawing(cv.svg(), cv.width_mm, mu)

    @staticmethod
    def _D(cam, phi):
        g = cam._geom(phi, 1, np.zeros(2))
        return g["B"] - cam.k * g["v1"] * g["r"]

    def _ray(self, ax, cam, which, phi, lo, hi, ls, lw=1.0):
        n, c = cam.halfplane(which, phi)
        D = self._D(cam, phi)
        d = np.array([-n[1], n[0]]) / np.hypot(*n)
        L = float(np.hypot(*(hi - lo))) * 2
        seg = np.array([D - L * d, D + L * d])
        ax.plot(seg[:, 0], seg[:, 1], color=INK, lw=lw, ls=ls)
        ax.set_xlim(ax.get_xlim())
        ax.set_ylim(ax.get_ylim())
        ax.plot(*D, "o", color=INK, ms=2.5)

    @staticmethod
    def _vmax(cam, ph, sign):
        return cam.phase_extreme(ph, lambda p, sd: sign * cam._at(p, sd)[1], lambda p, sd: sign * cam._at(p, sd)[2])[1]


def _flat_hull(cam, g, W) -> np.ndarray:
    """The cam of a flat-faced follower is the intersection of the half-planes n(φ)·X ≤ p(φ)
    bounded by the face in every position (n = R(−kφ)u the face's normal in the cam frame, p = P·u
    its distance from O: r₀ + s for a translating face, a_w sin(ψ₀ + ψ) − d for a rocker); the
    envelope points outside it (a swallowtail where the contact jumps backwards) are not on the
    real profile and are left out of the drawing."""
    f = cam.frames(g)
    k = cam.k
    c, sn = np.cos(k * g), np.sin(k * g)
    u = f["u"]
    n = np.column_stack([c * u[:, 0] + sn * u[:, 1], -sn * u[:, 0] + c * u[:, 1]])   # R(−kφ)u
    lim = np.einsum("ij,ij->i", f["P"], u)
    viol = (W @ n.T - lim[None, :]).max(axis=1)
    return W[viol <= 1e-9 * cam.synthesis.r0]


def _clip(poly: np.ndarray, n: np.ndarray, c: float) -> np.ndarray:
    """Sutherland–Hodgman: the part of a convex polygon with n·x ≤ c."""
    out = []
    m = len(poly)
    for i in range(m):
        a, b = poly[i], poly[(i + 1) % m]
        fa, fb = n @ a - c, n @ b - c
        if fa <= 0:
            out.append(a)
        if fa * fb < 0:
            out.append(a + (b - a) * fa / (fa - fb))
    return np.array(out)


class FlatRockerSize:
    """Flat-faced rocker: the centre distance a_w required at each initial angle ψ₀ by the convexity
    of the profile (ρ ≥ ρ_min) and by the allowed pressure angles (tg ϑ = d/μ ≤ tg[ϑ]), the region
    of allowed (ψ₀, a_w) above both (hatched) and the accepted point."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        cam = study.cam
        syn = cam.synthesis
        x = np.linspace(0.0, math.pi / 2 - cam.h, 91)[1:-1]
        need = [cam.fr_need(v) for v in x]
        top = 2.5 * max(syn.a_w, cam.fr["a"]) * 1000
        ac = np.array([n["a_conv"] for n in need]) * 1000
        ap = np.array([n["a_press"] for n in need]) * 1000
        fig = mplstyle.figure(160, 90)
        ax = fig.add_subplot()
        X = np.degrees(x)
        ax.fill_between(X, np.minimum(np.maximum(ac, ap), top), top, facecolor=LIGHT, edgecolor=GREY,
                        hatch="///", lw=0.0)
        ax.plot(X, np.where(ac < 2 * top, ac, np.inf), color=INK, lw=1.3, label="выпуклость: ρ ≥ ρ$_{min}$")
        if ap.max() > 0:
            ax.plot(X, np.where(ap < 2 * top, ap, np.inf), color=INK, lw=1.3, ls="--",
                    label="угол давления: ϑ ≤ [ϑ]")
        ax.plot(math.degrees(syn.psi0), syn.a_w * 1000, "o", color=INK, ms=5, zorder=5)
        label = LabelPlacer(ax)        # clear of the curves and the hatching
        label.add(math.degrees(syn.psi0), syn.a_w * 1000, "$a_w$, $\\psi_0$", prefer=(-1, -0.5), point=True)
        ax.set_xlim(0, math.degrees(math.pi / 2 - cam.h))
        ax.set_ylim(0, top)
        ax.set_xlabel("ψ$_0$, град")
        ax.set_ylabel("a$_w$, мм")
        mplstyle.localize_axes(ax)
        ax.legend(loc="upper center", fontsize=9)
        place_on_chart(label)
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)


class PressureAngleGraph:
    """ϑ(φ) over the cycle with the allowed angles on the rise and on the return."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        cam = study.cam
        g = cam.grid
        th = np.degrees(cam.pressure_angle(g))
        fig = mplstyle.figure(160, 80)
        ax = fig.add_subplot()
        ax.plot(np.degrees(g), th, color=INK, lw=1.3, label="ϑ")
        r, v = cam.rise, cam.ret
        # a flat-faced rocker has ϑ = arctg(d/μ) > 0 on both phases: both limits above the axis
        sg = 1.0 if cam.flat_rocker else -1.0
        lab = "допустимый угол"
        for ph, y in ((r, math.degrees(r.allowed)), (v, sg * math.degrees(v.allowed))):
            if ph.allowed > 0:
                ax.plot([math.degrees(ph.start), math.degrees(ph.start + ph.length)], [y] * 2, color=INK,
                        lw=1.0, ls="--", label=lab)
                lab = None
        ax.axhline(0, color=GREY, lw=0.6)
        ax.set_xlim(0, 360)
        ax.set_xticks(np.arange(0, 361, 30))
        ax.set_xlabel("φ, град")
        ax.set_ylabel("ϑ, град")
        mplstyle.localize_axes(ax)
        ax.legend(loc="upper right", fontsize=9)
        return Drawing(mplstyle.to_svg(fig), 160, 0.0)


class ProfileDrawing:
    """The cam at its initial position (cam frame), working and centre profiles, the base circle,
    and the follower in the positions of :func:`follower_positions` by inversion."""

    needs = _NEEDS

    def draw(self, study) -> Drawing:
        cam = study.cam
        syn = cam.synthesis
        g = cam.grid
        pr = cam.profile(g)
        W, C = pr["W"], pr["C"]
        k = cam.k
        # a rocker's arm whole with its pivot in both extreme positions (ψ = 0 and the far dwell, ψ_max),
        # as the textbook drawing; a piece of it at the roller in the others
        whole = (0, 2) if _rocker(cam) else (0,)
        fol = [self._follower(cam, p, full=(i in whole)) for i, p in enumerate(follower_positions(cam))]
        # the drawing's extent holds the rollers (and pivots) whole, not only their centres
        rims = [np.asarray(c) + rad * np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])
                for seg in fol for c, rad in seg["circles"]]
        xs = np.concatenate([W[:, 0], C[:, 0]] + [f[:, 0] for seg in fol for f in seg["lines"] + rims])
        ys = np.concatenate([W[:, 1], C[:, 1]] + [f[:, 1] for seg in fol for f in seg["lines"] + rims])
        ext = max(xs.max() - xs.min(), ys.max() - ys.min())
        self.mu, self.scale = gost_scale(ext, 160)
        self.refused = None
        if cam.scale is not None:
            mu = dict((n, m) for m, n in _GOST)[cam.scale]
            if ext / mu <= 160:
                self.mu, self.scale = mu, cam.scale
            else:   # the asked scale does not fit on the sheet: the largest one that does
                self.refused = cam.scale
        if cam.contact == "flat":
            W = _flat_hull(cam, g, W)
        cv = Canvas(xs.min(), xs.max(), ys.min(), ys.max(), self.mu, margin_mm=8)
        ax = cv.ax
        ax.fill(W[:, 0], W[:, 1], facecolor=LIGHT, edgecolor=INK, lw=1.6, zorder=2)
        if cam.contact != "flat":
            ax.plot(C[:, 0], C[:, 1], color=INK, lw=0.7, ls="-.", zorder=3)
        ax.add_patch(Circle((0, 0), syn.r0, fill=False, color=GREY, lw=0.6, ls="--", zorder=3))
        if _rocker(cam):      # the arc of the pivot's positions in the inverted motion (radius a_w)
            a0 = math.atan2(-syn.O[1], -syn.O[0])
            arc = a0 - k * np.linspace(0.0, max(follower_positions(cam)), 60)
            ax.plot(syn.a_w * np.cos(arc), syn.a_w * np.sin(arc), color=GREY, lw=0.6, ls="-.", zorder=3)
        ax.plot(0, 0, "o", color=INK, ms=4, zorder=6)
        R = float(np.max(np.hypot(W[:, 0], W[:, 1])))      # the cam's centre lines, 5 mm past the profile
        centre_cross(cv, 0.0, 0.0, R / self.mu + 5.0)
        cv.labels.add(0, 0, "O", prefer=(-1, -1), point=True)
        for i, seg in enumerate(fol):
            for line in seg["lines"]:
                ax.plot(line[:, 0], line[:, 1], color=INK, lw=1.1, zorder=4)
            for c, rad in seg["circles"]:
                ax.add_patch(Circle(c, rad, facecolor="white", edgecolor=INK, lw=1.0, zorder=5))
            cv.labels.add(*seg["label"], str(i), prefer=(3, 3), fontsize=9)
        # the sense of rotation of the cam: an arc arrow
        a = np.linspace(0, k * 0.6, 20) + math.pi / 2 + 0.3 * k
        R = 0.35 * syn.r0
        ax.plot(R * np.cos(a), R * np.sin(a), color=INK, lw=0.8)
        ax.annotate("", xy=(R * math.cos(a[-1]), R * math.sin(a[-1])),
                    xytext=(R * math.cos(a[-3]), R * math.sin(a[-3])),
                    arrowprops=dict(arrowstyle="-|>", color=INK, lw=0.8))
        cv.labels.add(R * math.cos(a[10]), R * math.sin(a[10]), "ω", prefer=(math.cos(a[10]), math.sin(a[10])))
        self.followers, self.limits = fol, (ax.get_xlim(), ax.get_ylim())   # what is drawn and the sheet's window
        return Drawing(cv.svg(), cv.width_mm, self.mu)

    @staticmethod
    def _follower(cam, phi: float, full: bool = True) -> dict:
        """Lines and circles of the follower at the cam angle φ, turned back into the cam frame."""
        f = cam.frames(np.array([phi]))
        k = cam.k
        c, s = math.cos(k * phi), math.sin(k * phi)

        def rot(v):
            v = np.atleast_2d(v)
            return np.column_stack([c * v[:, 0] + s * v[:, 1], -s * v[:, 0] + c * v[:, 1]])

        P, u, r = f["P"][0], f["u"][0], f["r"][0]
        syn = cam.synthesis
        rr = cam.roller
        lines, circles = [], []
        if cam.follower == "translating":
            if cam.contact == "flat":
                w = 0.5 * cam.scalars["cam_face_width"] + 0.1 * syn.r0
                x0 = np.array([0.0, P[1]])
                lines.append(rot(np.array([x0 - w * r, x0 + w * r])))
                lines.append(rot(np.array([x0, x0 + 0.4 * syn.r0 * u])))
                label = rot(x0 + 0.4 * syn.r0 * u)[0]
            else:
                L = 0.4 * syn.r0 + rr
                lines.append(rot(np.array([P + rr * u, P + (rr + L) * u])))
                label = rot(P + (rr + L) * u)[0]
        elif cam.flat_rocker:
            # the face from a little before the nearest to a little past the farthest contact point,
            # the arm A–F (F the foot of the perpendicular from the pivot A on the face)
            A = -syn.O
            F = A - cam.face_offset * u
            lo, hi = cam.face
            m = 0.15 * (hi - lo)
            end = F + (hi + m) * r
            lines.append(rot(np.array([F + (lo - m) * r, end])))
            lines.append(rot(np.array([A, F, F + (lo - m) * r])))
            circles.append((rot(A)[0], 0.02 * syn.a_w))
            label = rot(end)[0]
        else:
            A = -syn.O
            if full:   # the whole arm with its pivot A in the first position, a piece of it in the others
                lines.append(rot(np.array([A, P])))
                circles.append((rot(A)[0], 0.02 * cam.arm))
                label = rot(A)[0]
            else:
                end = P + (A - P) * min(1.0, 0.5 * syn.r0 / cam.arm)
                lines.append(rot(np.array([end, P])))
                label = rot(end)[0]
        if cam.contact == "roller":
            circles.append((rot(P)[0], rr))
        elif cam.contact == "knife" and cam.follower == "translating":
            pass
        return {"lines": lines, "circles": circles, "label": label}
