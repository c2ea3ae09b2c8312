"""Drawing primitives shared by the scenes: exact-scale canvases and the mechanism symbols
(ГОСТ 2.770: links, revolute joints, supports, sliders, guides, hydraulic cylinder)."""
from __future__ import annotations

import itertools
import math

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.patches import Circle, Polygon, Rectangle
from matplotlib.transforms import Affine2D

from ..mechanism.model import FRAME, Mechanism
from ..style import mplstyle
from ..style.numbers import SUBSCRIPT  # noqa: F401  (the scenes import it from here)
from .labels import LabelPlacer, tex_point

NICE = (1.0, 1.5, 2.0, 2.5, 4.0, 5.0)
INK = "#000000"
GREY = "#7a7a7a"
LIGHT = "#e6e6e6"
# a link or position number keeps a digit's width from other labels: «07» beside «2» reads as «072»
NUMBER_GAP_MM = 1.6


def nice_scale(extent: float, avail_mm: float) -> float:
    """The smallest standard scale factor μ (1, 1.5, 2, 2.5, 4, 5 ·10ᵏ units per mm) with
    extent/μ ≤ avail_mm."""
    need = max(extent, 1e-12) / avail_mm
    k = math.floor(math.log10(need))
    for base in NICE + (10.0,):
        mu = base * 10.0 ** k
        if mu >= need * (1 - 1e-12):
            return mu
    return 10.0 ** (k + 1)


# ГОСТ 2.302-68 scales as the denominator k of 1:k (enlargements 2:1 … 10:1 as 1/2 … 1/10)
GOST_K = (0.1, 0.2, 0.25, 0.5, 1.0, 2.0, 2.5, 4.0, 5.0, 10.0, 15.0, 20.0, 25.0, 40.0, 50.0, 75.0, 100.0,
          200.0, 400.0, 500.0, 800.0, 1000.0)


def gost_scale(extent_m: float, avail_mm: float) -> float:
    """μ_l in m/mm of the smallest-reduction ГОСТ 2.302 scale 1:k with extent/μ ≤ avail_mm
    (μ_l = k/1000 m/mm)."""
    need = max(extent_m, 1e-12) / avail_mm * 1000.0
    for k in GOST_K:
        if k >= need * (1 - 1e-12):
            return k / 1000.0
    return nice_scale(extent_m, avail_mm)


def panel_scales(sizes, avail_w: float, max_h: float, min_w: float = 0.0) -> list[float]:
    """ГОСТ 2.302 scales μ_l (m/mm) of drawings set side by side in one row, each at its own
    scale, so that each fills a comparable area. ``sizes``: [(w, h, pad_w, pad_h)], the extent in
    metres and the room in mm around it (labels, symbols); a drawing takes at least ``min_w`` mm
    (its caption). Each may take the largest scale at which it fits alone (w/μ + pad_w ≤ avail_w,
    h/μ + pad_h ≤ max_h) or one of the next smaller ones; of the choices whose row fits
    ``avail_w``, the one whose smallest drawing (its larger side on paper) is largest wins, then
    the one that draws the most in all."""
    ks = list(GOST_K)
    first = [next((j for j, k in enumerate(ks) if w * 1000.0 / k + pw <= avail_w and h * 1000.0 / k + ph <= max_h),
                  len(ks) - 1) for w, h, pw, ph in sizes]

    def drawn(i, j):
        return max(sizes[i][0], sizes[i][1]) * 1000.0 / ks[j]

    def width(i, j):
        return max(sizes[i][0] * 1000.0 / ks[j] + sizes[i][2], min_w)
    best = None
    for idx in itertools.product(*[range(j, min(j + 6, len(ks))) for j in first]):
        fits = sum(width(i, j) for i, j in enumerate(idx)) <= avail_w
        d = [drawn(i, j) for i, j in enumerate(idx)]
        key = (fits, min(d), sum(d))
        if best is None or key > best[0]:
            best = (key, idx)
    return [ks[j] / 1000.0 for j in best[1]]


def common_panel_scale(sizes, avail_w: float, max_h: float, min_w: float = 0.0) -> float | None:
    """The largest ГОСТ 2.302 scale μ_l (m/mm) at which all the drawings ``sizes`` ([(w, h, pad_w,
    pad_h)] as for :func:`panel_scales`) fit side by side in one row at one common scale:
    Σ max(w/μ + pad_w, min_w) ≤ ``avail_w`` and every h/μ + pad_h ≤ ``max_h``; None if none does."""
    for k in GOST_K:
        mu = k / 1000.0
        if (sum(max(w / mu + pw, min_w) for w, h, pw, ph in sizes) <= avail_w
                and all(h / mu + ph <= max_h for w, h, pw, ph in sizes)):
            return mu
    return None


def gost_ratio(mu_m_per_mm: float) -> str:
    """The scale as ГОСТ 2.302 writes it: μ = 0,04 м/мм → «1:40», μ = 0,0025 → «1:2,5»,
    μ = 0,0005 → «2:1»."""
    k = mu_m_per_mm * 1000.0
    if k >= 1.0 - 1e-9:
        return "1:" + (f"{k:.1f}".replace(".", ",").rstrip("0").rstrip(",") if abs(k - round(k)) > 1e-9 else str(round(k)))
    r = 1.0 / k     # an enlargement: 2:1, 2,5:1 (round() would print 2,5 as «2:1»)
    return (str(round(r)) if abs(r - round(r)) < 1e-9 else f"{r:.1f}".replace(".", ",").rstrip("0").rstrip(",")) + ":1"


def mu_text(mu: float) -> str:
    """A round scale factor as printed: 0,04 (not 0,0400), 0,15, 2,5·10⁻⁴ → 0,00025."""
    txt = f"{mu:.10f}".rstrip("0").rstrip(".")
    return txt.replace(".", ",")


class _ScaleAxes(Axes):
    """The axes of an exact-scale drawing: its limits are set once from the scale and never
    follow the data, so adding a patch does not compute the patch's extent for the data limits
    (``Axes._update_patch_limits``: the Bézier extrema of every circle, arc and arrow, a tenth of
    a drawing's time) — nothing reads those limits."""

    def _update_patch_limits(self, patch):
        pass


class Canvas:
    """A figure whose axes map 1 mm of the printed page to μ units exactly (the figure must be
    placed in the report at ``width_mm``)."""

    def __init__(self, xmin, xmax, ymin, ymax, mu: float, margin_mm: float = 8.0, max_w: float = 165.0):
        self.mu = mu
        self.margin = margin_mm
        w = (xmax - xmin) / mu + 2 * margin_mm
        h = (ymax - ymin) / mu + 2 * margin_mm
        self.width_mm = min(max(w, 40.0), max_w)
        extra_w = (self.width_mm - w) / 2 * mu
        self.height_mm = max(h, 30.0)
        extra_h = (self.height_mm - h) / 2 * mu
        self.fig = mplstyle.figure(self.width_mm, self.height_mm, layout=None)
        self.ax = self.fig.add_axes((0, 0, 1, 1), axes_class=_ScaleAxes)
        self.ax.set_xlim(xmin - margin_mm * mu - extra_w, xmax + margin_mm * mu + extra_w)
        self.ax.set_ylim(ymin - margin_mm * mu - extra_h, ymax + margin_mm * mu + extra_h)
        self.ax.set_aspect("equal")
        self.ax.axis("off")
        self.labels = LabelPlacer(self.ax)

    def mm(self, x: float) -> float:
        """A length given in printed millimetres in data units."""
        return x * self.mu

    @classmethod
    def fit(cls, xs, ys, avail_w=150.0, avail_h=190.0, margin_mm=8.0, gost=False, page_w=165.0):
        """The canvas of the smallest standard scale holding the points (``gost``: a ГОСТ 2.302
        scale for a drawing of the mechanism in metres, else a round μ of a plan) within the
        text width ``page_w`` (257 mm on a landscape page)."""
        xs, ys = np.asarray(xs, float), np.asarray(ys, float)
        mu = cls.scale(xs, ys, avail_w, avail_h, margin_mm, gost, page_w)
        return cls(xs.min(), xs.max(), ys.min(), ys.max(), mu, margin_mm, max_w=page_w)

    @staticmethod
    def scale(xs, ys, avail_w=150.0, avail_h=190.0, margin_mm=8.0, gost=False, page_w=165.0) -> float:
        """The μ :meth:`fit` would choose (no figure made)."""
        xs, ys = np.asarray(xs, float), np.asarray(ys, float)
        pick = gost_scale if gost else nice_scale
        avail_w = min(avail_w, page_w - 2 * margin_mm)
        return max(pick(np.ptp(xs), avail_w), pick(np.ptp(ys), avail_h))

    def svg(self) -> bytes:
        """The drawing as SVG, after the registered labels are placed clear of everything."""
        self.labels.place()
        return mplstyle.to_svg(self.fig)


class Panel:
    """One exact-scale drawing area of a figure that holds several, each at its own scale (the
    Assur groups drawn apart): axes at ``rect_mm`` = (left, bottom, width, height) in printed mm
    from the figure's lower left corner, centred on ``centre`` (data units) at μ units per mm.
    Duck-types :class:`Canvas` for :func:`draw_mechanism` (``ax``, ``mu``, ``mm``, ``labels``)."""

    def __init__(self, fig, rect_mm, centre, mu: float):
        fw, fh = fig.get_figwidth() * 25.4, fig.get_figheight() * 25.4
        left, bottom, w, h = rect_mm
        self.mu = mu
        self.ax = fig.add_axes((left / fw, bottom / fh, w / fw, h / fh), axes_class=_ScaleAxes)
        self.ax.set_xlim(centre[0] - w / 2 * mu, centre[0] + w / 2 * mu)
        self.ax.set_ylim(centre[1] - h / 2 * mu, centre[1] + h / 2 * mu)
        self.ax.axis("off")
        self.labels = LabelPlacer(self.ax)

    def mm(self, x: float) -> float:
        """A length given in printed millimetres in data units."""
        return x * self.mu


def _point(row, p):
    return float(row[f"x_{p}"]), float(row[f"y_{p}"])


def mechanism_points(mech: Mechanism, rows) -> tuple[list[float], list[float]]:
    xs, ys = [], []
    for row in rows:
        for link in mech.links:
            for p in link.points:
                x, y = _point(row, p)
                xs.append(x)
                ys.append(y)
    return xs, ys


def _slider_links(mech: Mechanism) -> dict[str, str]:
    return {j.links[1]: j.point for j in mech.prismatic}


def _cylinder_links(mech: Mechanism) -> dict[str, object]:
    """The cylinder and the rod of each pair drawn as a cylinder (``Joint.cylinder``) → the pair."""
    out = {}
    for j in mech.prismatic:
        if j.cylinder:
            out[j.links[0]] = out[j.links[1]] = j
    return out


def cylinder_parts(mech: Mechanism, row, j):
    """The drawn parts of a cylinder–rod pair (ГОСТ 2.770 hydraulic/pneumatic cylinder): the body
    from the cylinder's closed end to its open end (its points on the pair's line, the end nearer
    the rod's pair point open), the piston (the rod's point on the line deepest in the body) and
    the rod's outer end (the pair's point). None if the cylinder has fewer than two points on the
    line (nothing to draw a body between)."""
    guide, rod = mech.link(j.links[0]), mech.link(j.links[1])
    (lx, ly), ux, uy = j.line_point, math.cos(j.angle), math.sin(j.angle)
    size = max(math.hypot(x, y) for x, y in guide.points.values()) or 1.0
    on = [p for p, (x, y) in guide.points.items() if abs((x - lx) * uy - (y - ly) * ux) < 1e-9 * size]
    if len(on) < 2:
        return None
    a, b = (np.asarray(v, float) for v in _farthest([_point(row, p) for p in on]))
    end = np.asarray(_point(row, j.point), float)
    closed, open_ = (a, b) if np.hypot(*(end - a)) > np.hypot(*(end - b)) else (b, a)
    u = (open_ - closed) / np.hypot(*(open_ - closed))
    # the rod's points on the axis (the slider's own frame: its points on the pair's line through j.point)
    rod_pts = [np.asarray(_point(row, p), float) for p in rod.points]
    on_axis = [q for q in rod_pts if abs(float(u[0] * (q - closed)[1] - u[1] * (q - closed)[0])) < 1e-6 * size]
    piston = min(on_axis or rod_pts, key=lambda q: float(np.dot(q - closed, u)))
    return closed, open_, u, piston, end


def _draw_cylinder_part(cv: Canvas, mech: Mechanism, row, link, j, color, lw, alpha, zorder) -> bool:
    """The cylinder (a rectangle of bore CYL_MM over its body) or the rod (a line from the piston
    to its outer end, the piston a stroke across the bore); False if the pair has no body to draw."""
    parts = cylinder_parts(mech, row, j)
    if parts is None:
        return False
    closed, open_, u, piston, end = parts
    n = np.array([-u[1], u[0]])
    w = cv.mm(CYL_MM) / 2
    if link.name == j.links[0]:
        poly = Polygon([closed + n * w, open_ + n * w, open_ - n * w, closed - n * w], closed=True,
                       facecolor="white", edgecolor=color, lw=lw, alpha=alpha, zorder=zorder - 0.4)
        cv.ax.add_patch(poly)
    else:
        cv.ax.plot([piston[0], end[0]], [piston[1], end[1]], color=color, lw=lw * 1.3, alpha=alpha,
                   zorder=zorder - 0.2, solid_capstyle="butt")
        p0, p1 = piston + n * w * 0.8, piston - n * w * 0.8
        cv.ax.plot([p0[0], p1[0]], [p0[1], p1[1]], color=color, lw=lw * 1.6, alpha=alpha, zorder=zorder - 0.2,
                   solid_capstyle="butt")
    return True


def _cylinder_number_at(mech: Mechanism, row, link, j):
    """Where a cylinder's or a rod's number goes, and the normal: the middle of the body, or of the
    rod's part outside it."""
    closed, open_, u, piston, end = cylinder_parts(mech, row, j)
    mid = (closed + open_) / 2 if link.name == j.links[0] else (
        (open_ + end) / 2 if float(np.dot(end - open_, u)) > 0 else (piston + end) / 2)
    return mid, (-u[1], u[0])


def draw_mechanism(cv: Canvas, mech: Mechanism, row, *, color=INK, lw=1.4, labels=True,
                   numbers=True, alpha=1.0, zorder=2, com=True, supports=True, only=None, guides=True,
                   tint=True) -> None:
    """Draw the mechanism at a position (``only``: a set of link names to draw, e.g. one
    Assur group taken apart; ``tint``: fill plates of three or more joints light grey — off for
    the overlaid positions of a plan, where tinted copies pile up into a blot)."""
    ax = cv.ax
    sliders = _slider_links(mech)
    d = mech.driver
    cyl = {n: j for n, j in _cylinder_links(mech).items() if cylinder_parts(mech, row, j) is not None}
    for link in mech.moving:
        if only is not None and link.name not in only:
            continue
        pts = [_point(row, p) for p in link.points]
        phi = float(row[f"phi_{link.name}"])
        if d.kind == "actuator" and link.name in (d.link, d.rod):
            _draw_actuator_part(cv, mech, row, link, color, lw, alpha, zorder)
        elif link.name in cyl:
            _draw_cylinder_part(cv, mech, row, link, cyl[link.name], color, lw, alpha, zorder)
        elif link.name in sliders:
            x, y = _point(row, sliders[link.name])
            _block(cv, x, y, phi, color, lw, alpha, zorder)
            others = [p for p in link.points if p != sliders[link.name]]
            for p in others:
                ax.plot([x, _point(row, p)[0]], [y, _point(row, p)[1]], color=color, lw=lw, alpha=alpha, zorder=zorder)
        elif len(pts) >= 3 and not _collinear(pts) and (bars := _slotted_bars(mech, row, link)):
            for a, b in bars:        # a slotted link (кулиса): its slot and its arms, no plate
                ax.plot([a[0], b[0]], [a[1], b[1]], color=color, lw=lw * 1.3, alpha=alpha, zorder=zorder + 0.7,
                        solid_capstyle="round")
            if tint:                 # the arms welded to the slot (ГОСТ 2.770 rigid joint): a filled corner
                for corner in _arm_corners(cv, bars):
                    ax.add_patch(Polygon(corner, closed=True, facecolor=color, edgecolor=color, lw=0.5,
                                         alpha=alpha, zorder=zorder + 0.6))
        elif len(pts) >= 3 and not _collinear(pts):
            poly = Polygon(np.array(_hull(pts)), closed=True, facecolor=LIGHT if tint else "none",
                           edgecolor=color, lw=lw,
                           alpha=alpha, zorder=zorder - 0.5)
            ax.add_patch(poly)
        elif len(pts) >= 2:
            a, b = _farthest(pts)
            ax.plot([a[0], b[0]], [a[1], b[1]], color=color, lw=lw * 1.3, alpha=alpha, zorder=zorder + 0.7,
                    solid_capstyle="round")
        if numbers and d.kind == "actuator" and link.name in (d.link, d.rod):
            # the cylinder's or the rod's number by the middle of its drawn part, not at its one pair
            (mx, my), (nx, ny) = _actuator_part_middle(mech, row, link.name)
            cv.labels.add(mx, my, link.name, prefer=(nx, ny), color=color, fontsize=9,
                          gap_mm=NUMBER_GAP_MM)
        elif numbers and link.name in cyl:
            (mx, my), (nx, ny) = _cylinder_number_at(mech, row, link, cyl[link.name])
            cv.labels.add(mx, my, link.name, prefer=(nx, ny), color=color, fontsize=9,
                          gap_mm=NUMBER_GAP_MM, reach_mm=CYL_MM / 2 if link.name == cyl[link.name].links[0] else 0.0)
        elif numbers and len(pts) >= 1 and link.name not in sliders:
            a, b = (bars[0] if (bars := _slotted_bars(mech, row, link)) else
                    _farthest(pts) if len(pts) >= 2 else (pts[0], pts[0]))
            mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
            nx, ny = -(b[1] - a[1]), b[0] - a[0]
            cv.labels.add(mx, my, link.name, prefer=(nx, ny), color=color, fontsize=9,
                          gap_mm=NUMBER_GAP_MM)
        elif numbers and link.name in sliders:
            x, y = _point(row, sliders[link.name])
            cv.labels.add(x, y, link.name, prefer=(0.7, 0.7), color=color, fontsize=9, gap_mm=NUMBER_GAP_MM,
                          reach_mm=BLOCK_REACH_MM)
    for j in mech.joints:
        if only is not None and not set(j.links) & set(only):
            continue
        x, y = _point(row, j.point)
        if j.kind == "R":
            if supports and FRAME in j.links:
                _support(cv, x, y, color, alpha, zorder)
            ax.add_patch(Circle((x, y), cv.mm(1.3), facecolor="white", edgecolor=color, lw=1.0,
                                alpha=alpha, zorder=zorder + 1))
        elif supports and guides and j.links[0] == FRAME:
            _guide(cv, mech, row, j, color, alpha)
    if com:
        for link in mech.moving:
            if only is not None and link.name not in only:
                continue
            if link.com and link.com not in {j.point for j in mech.joints}:
                x, y = _point(row, link.com)
                ax.add_patch(Circle((x, y), cv.mm(0.8), facecolor=color, edgecolor=color, alpha=alpha,
                                    zorder=zorder + 1))
    if labels:
        placed = set()
        blocks = {sliders[n] for n in sliders if not (d.kind == "actuator" and n in (d.link, d.rod)) and n not in cyl}
        for link in mech.links:
            if only is not None and link.name not in only:
                continue
            for p in link.points:
                if p in placed:
                    continue
                placed.add(p)
                x, y = _point(row, p)
                cv.labels.add(x, y, tex_point(p), prefer=_label_offset(mech, row, p), color=color, fontsize=10,
                              point=True, reach_mm=BLOCK_REACH_MM if p in blocks else 0.0)


def _label_offset(mech: Mechanism, row, p: str) -> tuple[float, float]:
    """Unit direction away from the links meeting at p."""
    x, y = _point(row, p)
    sx = sy = 0.0
    for link in mech.links:
        if p in link.points:
            for q in link.points:
                if q != p:
                    qx, qy = _point(row, q)
                    n = math.hypot(qx - x, qy - y)
                    if n > 0:
                        sx += (qx - x) / n
                        sy += (qy - y) / n
    n = math.hypot(sx, sy)
    if n < 1e-9:
        return (0.7, 0.7)
    return (-sx / n, -sy / n)


def _slotted_bars(mech: Mechanism, row, link) -> list:
    """A slotted link (кулиса, the guide of a moving slider) as the course draws it: a bar along
    its slot, over its points on the slot's line and the slider's point, and an arm from the slot
    to each of its other pairs' points (a bell crank: the slot DK and the arm DF at the pivot D);
    empty if the link carries no slot with two points on it. Its centre of mass is no corner: a
    plate spanned over it and the arms would hide the slot."""
    slots = [j for j in mech.prismatic if j.links[0] == link.name and not j.driving]
    if not slots or link.name == FRAME:
        return []
    j = slots[0]
    (lx, ly), ux, uy = j.line_point, math.cos(j.angle), math.sin(j.angle)
    size = max(math.hypot(x, y) for x, y in link.points.values()) or 1.0
    on = [p for p, (x, y) in link.points.items() if abs((x - lx) * uy - (y - ly) * ux) < 1e-9 * size]
    if len(on) < 2:
        return []
    paired = {jj.point for jj in mech.joints if link.name in jj.links}
    a, b = _farthest([_point(row, p) for p in on] + [_point(row, j.point)])
    bars = [(a, b)]
    for p in link.points:
        if p in on or p not in paired:
            continue
        q = _point(row, p)
        near = min(on, key=lambda o: math.hypot(*np.subtract(_point(row, o), q)))
        bars.append((_point(row, near), q))
    return bars


def _arm_corners(cv: Canvas, bars: list, leg_mm: float = 3.5) -> list:
    """The small filled triangles that join each arm of a slotted link to its slot at the arm's
    root (legs ``leg_mm`` along the arm and along the slot towards its far end)."""
    (a, b), out = bars[0], []
    for p, q in bars[1:]:
        far = b if math.hypot(b[0] - p[0], b[1] - p[1]) >= math.hypot(a[0] - p[0], a[1] - p[1]) else a
        legs = []
        for e in (far, q):
            d = math.hypot(e[0] - p[0], e[1] - p[1])
            if d < 1e-12:
                break
            k = min(cv.mm(leg_mm) / d, 0.5)
            legs.append((p[0] + (e[0] - p[0]) * k, p[1] + (e[1] - p[1]) * k))
        else:
            out.append([p, *legs])
    return out


def _collinear(pts) -> bool:
    (x0, y0), (x1, y1) = _farthest(pts)
    L = math.hypot(x1 - x0, y1 - y0) or 1.0
    return all(abs((x1 - x0) * (y - y0) - (y1 - y0) * (x - x0)) / L < 1e-6 * L + 1e-9 for x, y in pts)


def _farthest(pts):
    best, pair = -1.0, (pts[0], pts[-1])
    for i in range(len(pts)):
        for j in range(i + 1, len(pts)):
            d = math.hypot(pts[i][0] - pts[j][0], pts[i][1] - pts[j][1])
            if d > best:
                best, pair = d, (pts[i], pts[j])
    return pair


def _hull(pts):
    pts = sorted(set(pts))
    if len(pts) < 3:
        return pts

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


BLOCK_MM = (9.0, 5.5)                          # a slider's block, printed length × width
BLOCK_REACH_MM = math.hypot(*BLOCK_MM) / 2     # from its point to a corner
CYL_MM = BLOCK_MM[1]                           # a cylinder's bore as drawn (a block's width), mm


def _block(cv: Canvas, x, y, phi, color, lw, alpha, zorder):
    w, h = cv.mm(BLOCK_MM[0]), cv.mm(BLOCK_MM[1])
    rect = Rectangle((-w / 2, -h / 2), w, h, facecolor="white", edgecolor=color, lw=lw, alpha=alpha,
                     zorder=zorder + 0.5)
    rect.set_transform(Affine2D().rotate(phi).translate(x, y) + cv.ax.transData)
    cv.ax.add_patch(rect)


def _support(cv: Canvas, x, y, color, alpha, zorder):
    s = cv.mm(4.0)
    tri = Polygon([(x, y), (x - s * 0.7, y - s), (x + s * 0.7, y - s)], closed=True, facecolor="white",
                  edgecolor=color, lw=1.0, alpha=alpha, zorder=zorder - 1)
    cv.ax.add_patch(tri)
    _hatch(cv, x - s, x + s, y - s, color, alpha)


def _hatch(cv: Canvas, x0, x1, y, color, alpha, angle=0.0):
    ax = cv.ax
    c, s = math.cos(angle), math.sin(angle)

    def tr(u, v):
        return x0 + (u * c - v * s), y + (u * s + v * c)
    L = x1 - x0
    a, b = tr(0, 0), tr(L, 0)
    ax.plot([a[0], b[0]], [a[1], b[1]], color=color, lw=1.0, alpha=alpha)
    step = cv.mm(1.6)
    n = int(L / step)
    segs = [(tr(k * step, 0), tr(k * step - cv.mm(1.5), -cv.mm(1.5))) for k in range(n + 1)]
    ax.add_collection(LineCollection(segs, colors=color, linewidths=0.6, alpha=alpha))


def _guide(cv: Canvas, mech, row, j, color, alpha, span=None):
    """A fixed guide: a hatched line along the guide direction under the slider, around the
    slider point or over ``span`` = (s_min, s_max), the slider point's travel along the guide
    measured from its position in ``row``."""
    x, y = _point(row, j.point)
    ang = j.angle
    ux, uy = math.cos(ang), math.sin(ang)
    nx, ny = -uy, ux
    lo, hi = span if span is not None else (0.0, 0.0)
    lo, hi = lo - cv.mm(14.0), hi + cv.mm(14.0)
    off = cv.mm(2.75)
    x0, y0 = x + ux * lo - nx * off, y + uy * lo - ny * off
    _hatch(cv, x0, x0 + (hi - lo), y0, color, alpha, angle=ang)


def draw_guide(cv: Canvas, mech, row, j, span, color=INK):
    """The whole fixed guide of a slider over its travel ``span`` (for the plan of positions)."""
    _guide(cv, mech, row, j, color, 1.0, span)


def _actuator_axis(mech, row):
    """The cylinder's pivot, its rod's end, the unit vector from the one to the other, and the
    drawn length of the body and of the rod (0,55 of the shortest length of the cylinder)."""
    d = mech.driver
    bx, by = _point(row, d.center)
    ex, ey = _point(row, d.end)
    L = math.hypot(ex - bx, ey - by)
    lo = d.q_range[0] if d.q_range else L
    return (bx, by), (ex, ey), ((ex - bx) / L, (ey - by) / L), 0.55 * lo


def _actuator_part_middle(mech, row, name):
    """Where the number of the cylinder (``name`` = the cylinder) or of the rod goes: the point of
    its drawn part, at 0,3 … 0,7 of it, farthest from every other joint (a support that the rod
    passes over in this position would take the number for its own), and the normal."""
    (bx, by), (ex, ey), (ux, uy), part = _actuator_axis(mech, row)
    if name == mech.driver.link:
        (sx, sy), (dx, dy) = (bx, by), (ux, uy)
    else:
        (sx, sy), (dx, dy) = (ex, ey), (-ux, -uy)
    others = np.array([_point(row, j.point) for j in mech.joints]).reshape(-1, 2)
    cands = [(sx + dx * part * t, sy + dy * part * t) for t in (0.5, 0.4, 0.6, 0.3, 0.7)]
    best = max(cands, key=lambda c: round(float(np.hypot(*(others - c).T).min()) / part, 2))
    return best, (-uy, ux)


def _draw_actuator_part(cv, mech, row, link, color, lw, alpha, zorder):
    d = mech.driver
    (bx, by), (ex, ey), (ux, uy), part = _actuator_axis(mech, row)
    if link.name == d.link:
        body = part
        w = cv.mm(4.0)
        poly = Polygon([(bx - uy * w / 2, by + ux * w / 2), (bx + ux * body - uy * w / 2, by + uy * body + ux * w / 2),
                        (bx + ux * body + uy * w / 2, by + uy * body - ux * w / 2), (bx + uy * w / 2, by - ux * w / 2)],
                       closed=True, facecolor="white", edgecolor=color, lw=lw, alpha=alpha, zorder=zorder)
        cv.ax.add_patch(poly)
    else:
        cv.ax.plot([ex, ex - ux * part], [ey, ey - uy * part], color=color, lw=lw, alpha=alpha, zorder=zorder - 0.2)


def legend_rows(ax, most: int, **kw):
    """A legend of at most ``most`` entries a row, read row by row (matplotlib fills a legend of
    several columns column by column: the pairs of a reactions chart read «R₀₁, R₂₃, R₀₃…, R₁₂»
    with R₁₂ alone in a second row); the rows balanced: 7 entries in rows of 4 and 3, not 6 and 1."""
    handles, labels = ax.get_legend_handles_labels()
    n = len(handles)
    rows = max(1, math.ceil(n / most))
    ncols = math.ceil(n / rows)
    # matplotlib splits n entries into ncols columns of ⌈n/ncols⌉ or ⌊n/ncols⌋ (the longer first)
    # and fills them in order: hand it the entries column by column of the row-wise table
    order = [r * ncols + c for c in range(ncols) for r in range(rows) if r * ncols + c < n]
    return ax.legend([handles[i] for i in order], [labels[i] for i in order], ncols=ncols, **kw)


def arrow(ax, x0, y0, x1, y1, *, color=INK, lw=1.2, ls="-", head_mm=2.2, mu=1.0, zorder=3):
    """An arrow from (x0, y0) to (x1, y1) with a head of fixed printed size."""
    from matplotlib.patches import FancyArrowPatch
    if math.hypot(x1 - x0, y1 - y0) < 1e-15:
        return
    ax.add_patch(FancyArrowPatch((x0, y0), (x1, y1), arrowstyle=f"-|>,head_length={head_mm * 0.35},head_width={head_mm * 0.14}",
                                 mutation_scale=10, color=color, lw=lw, linestyle=ls, shrinkA=0, shrinkB=0,
                                 zorder=zorder))


CENTRE_LW = 0.5                        # thin line (ГОСТ 2.303: S/3 … S/2)
DASH_DOT = (0, (24.0, 6.0, 2.0, 6.0))  # dash-dot in line widths: 4,2 mm dashes, 1 mm gaps at 0,5 pt


def centre_line(cv: Canvas, x0, y0, x1, y1, color=INK) -> None:
    """A thin dash-dot centre line (ГОСТ 2.303) from (x0, y0) to (x1, y1), drawn from its middle
    outwards so that the middle (a centre, a crossing of axes) falls on a dash."""
    xm, ym = (x0 + x1) / 2, (y0 + y1) / 2
    for xe, ye in ((x0, y0), (x1, y1)):
        cv.ax.plot([xm, xe], [ym, ye], color=color, lw=CENTRE_LW, ls=DASH_DOT, zorder=0.5,
                   solid_capstyle="butt", dash_capstyle="butt")


def centre_cross(cv: Canvas, x, y, half_mm: float, color=INK) -> None:
    """The two centre lines of a circle or a pivot at (x, y), ``half_mm`` each side."""
    h = cv.mm(half_mm)
    centre_line(cv, x - h, y, x + h, y, color)
    centre_line(cv, x, y - h, x, y + h, color)


def mechanism_centre_lines(cv: Canvas, mech: Mechanism, row, *, spans=None, radii=None) -> None:
    """The centre lines of a mechanism drawing (ГОСТ 2.303 thin dash-dot): a cross at every pivot
    on the frame (``radii``: the radius of a circle drawn about a pivot, e.g. the crank circle, the
    cross passing 5 mm beyond it) and the axis of every fixed guide over ``spans`` (the travel of
    its slider point along the guide, as for :func:`draw_guide`; 14 mm each side of the slider)."""
    radii = radii or {}
    spans = spans or {}
    for j in mech.joints:
        x, y = _point(row, j.point)
        if j.kind == "R" and FRAME in j.links:
            r = radii.get(j.point)
            centre_cross(cv, x, y, (r / cv.mu + 5.0) if r else 7.0)
        elif j.kind != "R" and j.links[0] == FRAME:
            ux, uy = math.cos(j.angle), math.sin(j.angle)
            lo, hi = spans.get(j.name, (0.0, 0.0))
            lo, hi = lo - cv.mm(16.0), hi + cv.mm(16.0)
            centre_line(cv, x + ux * lo, y + uy * lo, x + ux * hi, y + uy * hi)
