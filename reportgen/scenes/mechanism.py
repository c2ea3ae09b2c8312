"""Scenes that draw the mechanism itself: the kinematic scheme at a position, the plan of
positions with the trajectories of the centres of mass, and the Assur groups drawn apart."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..mechanism.model import FRAME
from ..style.numbers import position_names
from matplotlib.patches import Circle, Polygon

from .draw import (GREY, INK, NUMBER_GAP_MM, Canvas, draw_guide, draw_mechanism, mechanism_centre_lines,
                   mechanism_points)


@dataclass
class Drawing:
    svg: bytes
    width_mm: float
    mu: float            # scale factor μ (units per printed mm)
    # drawn for a landscape page (wider than the portrait text width); keyword-only so that the
    # subclasses' positional fields stay where they are
    landscape: bool = field(default=False, kw_only=True)
    # the scale (m/mm) of an enlarged view of a small crank on the plan of positions, if drawn
    detail_mu: float | None = field(default=None, kw_only=True)
    detail_mark: str = field(default="", kw_only=True)     # its letter (ГОСТ 2.305)


# a landscape A4 page (ГОСТ 7.32 margins turned with the sheet): text 257 × 165 mm, less the caption
LANDSCAPE_W, LANDSCAPE_H = 257.0, 140.0
LANDSCAPE_GAIN = 1.5     # a drawing goes landscape when that enlarges it at least this much
POSITION_NUMBER = "position-number"   # the artist label of a position number on the plan of positions


def fit_canvas(xs, ys, mu: float | None, *, avail_w: float, avail_h: float, margin_mm: float) -> Canvas:
    """The canvas of the points at the scale ``mu`` if given (the page may then be wider than
    the note's), else at the ГОСТ 2.302 scale that fits ``avail_w`` × ``avail_h`` mm."""
    if mu is None:
        return Canvas.fit(xs, ys, avail_w=avail_w, avail_h=avail_h, margin_mm=margin_mm, gost=True)
    return Canvas(min(xs), max(xs), min(ys), max(ys), mu, margin_mm, max_w=1e4)


def _row(study, label: str):
    k = study.kinematics
    return k[k["pos"] == label].iloc[0]


class KinematicScheme:
    """The kinematic scheme at one report position, to scale, with points and links labelled."""

    needs = ("kinematics",)

    def __init__(self, label: str, centre_lines: bool = False, mu: float | None = None):
        """``centre_lines``: the pivots' centre lines and the guides' axes (ГОСТ 2.303 dash-dot);
        ``mu``: the scale (m/mm) asked by the caller (a drawing sheet), else the ГОСТ 2.302 scale
        that fits the page."""
        self.label = label
        self.centre_lines = centre_lines
        self.mu = mu

    def draw(self, study) -> Drawing:
        row = _row(study, self.label)
        xs, ys = mechanism_points(study.mechanism, [row])
        cv = fit_canvas(xs, ys, self.mu, avail_w=140, avail_h=120, margin_mm=12)
        draw_mechanism(cv, study.mechanism, row)
        if self.centre_lines:
            mechanism_centre_lines(cv, study.mechanism, row)
        return Drawing(cv.svg(), cv.width_mm, cv.mu)


class PositionsPlan:
    """All report positions overlaid (the first drawn bold, the others thin and numbered at the
    crank pin / rod end), the crank circle, both extreme positions of the output link bold and
    labelled (B′, B″), each fixed guide hatched over the whole travel of its slider, and the
    trajectories of the centres of mass over the cycle (dashed)."""

    needs = ("kinematics", "cycle")

    def __init__(self, centre_lines: bool = False, mu: float | None = None):
        """``centre_lines``: the centre lines of the crank circle and the pivots and the axes of
        the guides (ГОСТ 2.303 thin dash-dot), as on a drawing sheet; ``mu``: the scale (m/mm)
        asked by the caller, else the ГОСТ 2.302 scale that fits the page."""
        self.centre_lines = centre_lines
        self.mu = mu

    def draw(self, study) -> Drawing:
        from ..analysis.plans import output_quantity
        from .labels import tex_point
        mech = study.mechanism
        k = study.kinematics
        regular = k[~k["pos"].str.startswith("д")] if k["pos"].dtype == object else k
        rows = [r for _, r in regular.iterrows()]
        # the trajectories over the cycle (none drawn when only single positions are solved)
        cyc = study.cycle if study.has_cycle else None
        coms = traced_points(study) if cyc is not None else []
        xs, ys = mechanism_points(mech, rows)
        for p in coms:
            xs += list(cyc[f"x_{p}"])
            ys += list(cyc[f"y_{p}"])
        wide = dict(avail_w=LANDSCAPE_W, avail_h=LANDSCAPE_H - 24, margin_mm=12, gost=True, page_w=LANDSCAPE_W)
        landscape = self.mu is None and (Canvas.scale(xs, ys, avail_w=155, avail_h=190, margin_mm=12, gost=True)
                                         >= LANDSCAPE_GAIN * Canvas.scale(xs, ys, **wide))
        cv = (Canvas.fit(xs, ys, **wide) if landscape
              else fit_canvas(xs, ys, self.mu, avail_w=155, avail_h=190, margin_mm=12))
        tip = _tracer_point(study)
        cx, cy = _centre(study, rows)
        s_col = output_quantity(study)[0]
        out = _output_point(study, s_col)
        # position numbers at the crank pin; for a cylinder or a rocker at its moving point or at the
        # output point, whichever travels farther (the numbers of a short stroke pile up)
        num = numbered_point(mech, rows, tip, out)
        # (on a sheet too: at the sheet's scale, whose redrawing makes room for a view that appears)
        view = crank_view(study, rows, cv, (cx, cy), num, coms)
        if view is not None:         # the canvas grown, at its scale, to hold the enlarged view
            h = view.r_view + VIEW_PAD_MM * cv.mu
            cv = Canvas(min(min(xs), view.at[0] - h), max(max(xs), view.at[0] + h), min(min(ys), view.at[1] - h),
                        max(max(ys), view.at[1] + h), cv.mu, 12,
                        max_w=1e4 if self.mu is not None else LANDSCAPE_W if landscape else 165.0)
        thin = len(cv.ax.lines)
        for p in coms:
            cv.ax.plot(cyc[f"x_{p}"], cyc[f"y_{p}"], ls=(0, (5, 3)), lw=0.7, color=INK, zorder=2)
        _thin_lines(cv.ax, thin)
        if mech.driver.swing:
            # the input rocker's tip moves on an arc between the extreme positions of the swing
            r = float(np.hypot(rows[0][f"x_{tip}"] - cx, rows[0][f"y_{tip}"] - cy))
            tr = cyc if cyc is not None else k
            th = np.unwrap(np.arctan2(tr[f"y_{tip}"].to_numpy() - cy, tr[f"x_{tip}"].to_numpy() - cx))
            cv.ax.plot(cx + r * np.cos(th), cy + r * np.sin(th), lw=0.6, color=INK, zorder=1)
        elif mech.driver.rotary:
            r = float(np.hypot(rows[0][f"x_{tip}"] - cx, rows[0][f"y_{tip}"] - cy))
            cv.ax.add_patch(Circle((cx, cy), r, fill=False, lw=0.6, color=INK, zorder=1))
        thin, plates = len(cv.ax.lines), len(cv.ax.patches)
        for i, row in enumerate(rows[1:], start=1):
            draw_mechanism(cv, mech, row, color=GREY, lw=0.7, labels=False, numbers=False, alpha=0.9,
                           zorder=1, com=False, supports=False, tint=False)
        _thin_lines(cv.ax, thin, plates)
        if cyc is not None:       # the output's extreme positions over the cycle
            s = cyc[s_col].to_numpy()
            ext = [cyc.iloc[int(np.argmin(s))], cyc.iloc[int(np.argmax(s))]]
        else:
            ext = []
        for row in ext:
            draw_mechanism(cv, mech, row, color=INK, lw=1.2, labels=False, numbers=False, zorder=3, com=False,
                           supports=False, tint=False)
        draw_mechanism(cv, mech, rows[0], color=INK, lw=1.5, zorder=4, guides=False)
        spans = {}
        for j in mech.prismatic:
            if j.links[0] == FRAME:
                u = np.array([np.cos(j.angle), np.sin(j.angle)])
                p0 = np.array([rows[0][f"x_{j.point}"], rows[0][f"y_{j.point}"]])
                tr = cyc if cyc is not None else k
                t = (np.column_stack([tr[f"x_{j.point}"], tr[f"y_{j.point}"]]) - p0) @ u
                spans[j.name] = (float(t.min()), float(t.max()))
                draw_guide(cv, mech, rows[0], j, spans[j.name])
        if self.centre_lines:
            radii = {mech.driver.center: r} if mech.driver.rotary else {}
            mechanism_centre_lines(cv, mech, rows[0], spans=spans, radii=radii)
        first_mark = len(cv.labels.items)
        # every joint of a turning link in the extreme positions marked (B′, C′ …, as a textbook
        # plan), not only the output's and the crank's: their lines are drawn as boldly as the main
        # ones; a link in translation is left to its output point (its marks would only pile up
        # along its own line, as a yoke's K′, P′)
        fixed = set(mech.link(FRAME).points)
        motion = study.structure.link_motion
        turning = {l for l in motion if not motion[l].startswith("поступательное")}
        marked = dict.fromkeys([out, tip] + [j.point for j in mech.joints if j.point not in fixed
                                             and set(j.links) & turning])
        for mark, row in zip(("′", "″"), ext):
            for p in marked:
                if view is None or p != view.tip:       # the numbered point's marks in its view
                    cv.labels.add(float(row[f"x_{p}"]), float(row[f"y_{p}"]), _marked(p, mark), fontsize=10,
                                  point=True)
        if view is not None:         # numbered in the enlarged view, not at the tiny crank
            view.draw(cv, study, rows, ext)
            return Drawing(cv.svg(), cv.width_mm, cv.mu, landscape=landscape, detail_mu=view.mu,
                           detail_mark=view.mark)
        groups = _position_groups(k, rows, num, cv.mm(0.5))
        path = np.array([[float(r[f"x_{num}"]), float(r[f"y_{num}"])] for r in rows])
        mid = np.array([np.mean(xs), np.mean(ys)])
        own = next((it for it in cv.labels.items if num.rstrip("0123456789") and it.text == tex_point(num)
                    and (it.x, it.y) == groups[0][:2]), None)
        if own is not None:
            # the drawn position's pin named once, by its number (A₀ for A: one label fewer in the
            # crowd at a small crank), keeping its place in the placer's order
            own.text = position_text(num, groups[0][2])
            own.kw.update(fontsize=8, label=POSITION_NUMBER)
            own.gap_mm = NUMBER_GAP_MM
            groups = groups[1:]
        for x, y, names in groups:
            prefer = (x - cx, y - cy)
            if num != tip and len(path) > 1:
                # across the output point's path, on the side away from the mechanism
                i = int(np.argmin(np.hypot(*(path - [x, y]).T)))
                t = path[min(i + 1, len(path) - 1)] - path[max(i - 1, 0)]
                n = np.array([-t[1], t[0]])
                prefer = tuple(n if n @ (np.array([x, y]) - mid) >= 0 else -n)
            # a character's width clear of every other label: «1» beside «3» reads as «13»
            cv.labels.add(x, y, position_text(num, names), prefer=prefer, fontsize=8, gap_mm=NUMBER_GAP_MM,
                          label=POSITION_NUMBER)
        # the position numbers placed before the extreme positions' marks A′, A″ (which take the
        # room of the neighbouring numbers at a small crank: the screen shaker's A₁ went 23 mm off)
        items, n = cv.labels.items, len(groups)
        if n:
            items[first_mark:] = items[-n:] + items[first_mark:-n]
        return Drawing(cv.svg(), cv.width_mm, cv.mu, landscape=landscape)


def _thin_lines(ax, lines: int, patches: int | None = None) -> None:
    """The thin lines drawn since ``ax.lines[lines]`` (the other positions, the trajectories) made
    ``breakable``: a label may interrupt them (ГОСТ 2.307, as hatching and centre lines at a
    number) rather than sit far from its point on a leader; the unfilled plates drawn since
    ``ax.patches[patches]`` redrawn as such lines (their outlines, same look)."""
    if patches is not None:
        for pt in list(ax.patches[patches:]):
            if isinstance(pt, Polygon) and pt.get_facecolor()[3] == 0:
                v = pt.get_xy()
                ax.plot(v[:, 0], v[:, 1], color=pt.get_edgecolor(), lw=pt.get_linewidth(), zorder=pt.get_zorder(),
                        solid_joinstyle="miter")
                pt.remove()
    for ln in ax.lines[lines:]:
        ln.breakable = True


def _position_groups(k, rows, p: str, near: float) -> list[tuple[float, float, list[str]]]:
    """The positions of the point ``p`` as numbered on a plan: (x, y, numbers), the positions
    closer than ``near`` (data units) in one group («0, 12»)."""
    groups: list[tuple[float, float, list[str]]] = []
    number = position_names(k["pos"])          # positions by number, as the tables print them
    for row in rows:
        x, y = float(row[f"x_{p}"]), float(row[f"y_{p}"])
        no = number.get(str(row["pos"]), str(row["pos"]))
        for gx, gy, names in groups:
            if np.hypot(x - gx, y - gy) < near:
                names.append(no)
                break
        else:
            groups.append((x, y, [no]))
    return groups


def position_text(p: str, names) -> str:
    """The label of the numbered point ``p``'s positions ``names`` on a plan of positions, as
    textbooks number a crank pin's positions (Артоболевский И. И. Теория механизмов и машин,
    план положений): the point's letter with the position number as its index, A₀, A₁ … (coinciding
    positions together, A₀,₁₂), so that a position is never read as a link number (plain digits on
    the same drawing); a point with an index of its own (O₃) takes the numbers as an upper index in
    brackets, O₃⁽⁵⁾; a point named by digits only (a joint named by its links, «56») has no letter:
    the number alone in brackets, (5), apart from the link numbers."""
    no = ",".join(names)
    head = p.rstrip("0123456789")
    sub = p[len(head):]
    if not head:
        return f"({', '.join(names)})"
    return f"${head}_{{{sub}}}^{{({no})}}$" if sub else f"${head}_{{{no}}}$"


def position_gap_mm(groups, mu: float) -> float:
    """The least printed distance (mm) between two numbered positions at the scale μ."""
    pts = np.array([g[:2] for g in groups])
    if len(pts) < 2:
        return np.inf
    d = np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))
    return float(d[np.triu_indices(len(pts), 1)].min()) / mu


POSITION_GAP_MM = 2.5   # crank pin positions closer than this on paper are numbered in an enlarged view
VIEW_R_MM = 12.0        # the crank circle's radius in the enlarged view at least, mm
CRANK_R_MIN_MM = 10.0   # a crank circle smaller than this on paper is numbered in an enlarged view
VIEW_LABELS_MM = 7.0    # room for the position labels around the crank circle in the view, mm
HINGE_MM = 3.5          # the region circled on the main view: the crank circle and its joints' symbols
VIEW_PAD_MM = 7.0       # around the view, for its title
LATIN_LOOK = {"А": "A", "В": "B", "Е": "E"}   # letters of the views that read as Latin point names


@dataclass
class CrankView:
    """The enlarged view of an input too small for its position marks (ГОСТ 2.305 «выносной
    элемент», as the plans' views, :func:`scenes.plans.view_frame`): the region (``centre``,
    ``radius``, data units; clear of the pile of joint symbols) drawn ``k`` times larger in the
    circle (``at``, ``r_view``), at the ГОСТ 2.302 scale ``mu`` (m/mm) written over it («Б (1:2)»).
    ``tip``: the numbered point (a crank's or an input rocker's pin, a cylinder's rod end or the
    output point); ``path``: its trajectory (data units) when it does not run round the whole
    circle of a crank (a rocker's arc, a point driven by a cylinder), else None."""
    centre: np.ndarray
    radius: float
    r_view: float
    k: float
    at: np.ndarray
    mu: float
    tip: str
    mark: str            # the view's letter
    path: np.ndarray | None = None

    def draw(self, cv: Canvas, study, rows, ext) -> None:
        """The crank circle (a rocker's arc, a driven point's path), the crank or rocker in
        position 0 (bold), the numbered point's positions as hinges, numbered A₀ … A₁₁ (coinciding
        ones together), the extreme positions A′, A″, and the frame."""
        from .draw import gost_ratio
        from .labels import tex_point
        from .plans import view_frame, view_marks
        ax, c, k, tip = cv.ax, self.centre, self.k, self.tip
        to_view = lambda p: self.at + (np.asarray(p, float) - c) * k  # noqa: E731 - the view's similarity
        groups = _position_groups(study.kinematics, rows, tip, cv.mm(0.5) / k)
        r = float(np.hypot(*(np.array(groups[0][:2]) - c)))
        if self.path is None:
            ax.add_patch(Circle(self.at, r * k, fill=False, lw=0.6, color=INK, zorder=1))
        else:
            v = to_view(self.path)
            ax.plot(v[:, 0], v[:, 1], lw=0.6, color=INK, zorder=1)
        a0 = to_view(groups[0][:2])
        if study.mechanism.driver.rotary:        # the crank or rocker from its pivot, the view's centre
            ax.plot([self.at[0], a0[0]], [self.at[1], a0[1]], lw=1.5, color=INK, zorder=4)
            ax.plot([self.at[0]], [self.at[1]], marker="o", ms=4, mfc="white", mec=INK, mew=0.8, zorder=5)
            cv.labels.add(self.at[0], self.at[1], tex_point(study.mechanism.driver.center), prefer=self.at - a0,
                          fontsize=10, point=True)
        for x, y, names in groups:
            v = to_view((x, y))
            ax.plot([v[0]], [v[1]], marker="o", ms=3.5, mfc="white", mec=INK, mew=0.7, zorder=5)
            cv.labels.add(v[0], v[1], position_text(tip, names), prefer=v - self.at, fontsize=8,
                          gap_mm=NUMBER_GAP_MM, label=POSITION_NUMBER)
        for mark, row in zip(("′", "″"), ext):
            v = to_view((float(row[f"x_{tip}"]), float(row[f"y_{tip}"])))
            ax.plot([v[0]], [v[1]], marker="o", ms=3.5, mfc=INK, mec=INK, zorder=5)
            cv.labels.add(v[0], v[1], _marked(tip, mark), prefer=v - self.at, fontsize=10, point=True)
        view_frame(cv, c, self.radius, self.at, self.r_view)
        view_marks(cv, c, self.radius, self.at, self.r_view, self.mark, f"{self.mark} ({gost_ratio(self.mu)})")


def crank_view(study, rows, cv: Canvas, centre, tip: str, coms) -> CrankView | None:
    """The enlarged view an input needs when the positions of its numbered point ``tip``
    (:func:`numbered_point`) are closer than POSITION_GAP_MM on paper: at the ГОСТ 2.302 scale of
    least enlargement that draws the crank circle (a rocker's arc about its pivot; for a cylinder
    the point's path about the middle of its extent) with a radius of VIEW_R_MM at least and its
    positions 2·POSITION_GAP_MM apart, in the free place of the drawing found as for the plans'
    views (:func:`scenes.plans.free_place`)."""
    from .draw import GOST_K
    from .plans import INSET_MARKS, free_place
    mech = study.mechanism
    groups = _position_groups(study.kinematics, rows, tip, cv.mm(0.5))
    gap = position_gap_mm(groups, cv.mu)
    tr = study.cycle if study.has_cycle else study.kinematics
    path = None if mech.driver.periodic else np.column_stack([tr[f"x_{tip}"], tr[f"y_{tip}"]]).astype(float)
    if mech.driver.rotary:
        c = np.asarray(centre, float)
        r_m = float(np.hypot(*(np.array(groups[0][:2]) - c)))
    else:
        c = (path.min(axis=0) + path.max(axis=0)) / 2
        r_m = float(np.hypot(*(path - c).T).max())
    # a crank circle under CRANK_R_MIN_MM on paper has no room around it for its numbers even when its
    # positions are far enough apart (the sewing machine's 7,5 mm circle put A₅ 23 mm off on a leader)
    if gap >= POSITION_GAP_MM and not (mech.driver.rotary and r_m / cv.mu < CRANK_R_MIN_MM):
        return None
    fine = [q / 1000.0 for q in GOST_K if q / 1000.0 < cv.mu * (1 - 1e-9)
            and r_m / (q / 1000.0) >= VIEW_R_MM and gap * cv.mu / (q / 1000.0) >= 2 * POSITION_GAP_MM]
    if not fine:
        return None
    mu_v = max(fine)
    k = cv.mu / mu_v
    radius = r_m + HINGE_MM * cv.mu                      # the region circled, data units
    r_view = (r_m / mu_v + VIEW_LABELS_MM) * cv.mu       # the view's circle
    # the drawing in mm: every link's sides at every position, the traced paths, the joints
    segs, pts = [], []
    for row in rows:
        for link in mech.moving:
            names = list(link.points)
            xy = [(float(row[f"x_{p}"]) / cv.mu, float(row[f"y_{p}"]) / cv.mu) for p in names]
            pts += xy
            segs += [(*xy[i], *xy[j]) for i in range(len(xy)) for j in range(i + 1, len(xy))]
    cyc = study.cycle if coms else None
    segs = [np.array(segs, dtype=float).reshape(-1, 4)]
    for p in coms:     # the traced path's consecutive points as segments (x₀, y₀, x₁, y₁)
        v = np.column_stack([cyc[f"x_{p}"], cyc[f"y_{p}"]]) / cv.mu
        segs.append(np.column_stack([v[:-1], v[1:]]))
    pts = np.array(pts)
    r_mm, c_mm = radius / cv.mu, c / cv.mu
    h = r_view / cv.mu + VIEW_PAD_MM
    circle = (c_mm[0] - r_mm - 2, c_mm[1] - r_mm - 2, c_mm[0] + r_mm + 2, c_mm[1] + r_mm + 2)
    at = free_place(c_mm, h, np.concatenate(segs), pts, pts.min(axis=0), pts.max(axis=0), [], circle,
                    cv.width_mm - 2 * cv.margin)
    # the first view letter that cannot be read as a point of the mechanism (not А beside a point A)
    names = {p for link in mech.links for p in link.points}
    mark = next((m for m in INSET_MARKS if LATIN_LOOK.get(m) not in names), INSET_MARKS[0])
    return CrankView(c, radius, r_view, k, at * cv.mu, mu_v, tip, mark, path)


def numbered_point(mech, rows, tip: str, out: str) -> str:
    """Where the plan of positions numbers the positions: the crank pin; for a cylinder or an input
    rocker its moving point or the output point, whichever travels farther over the positions."""
    if mech.driver.rotary:
        return tip

    def travel(p):
        return float(np.hypot(np.diff([r[f"x_{p}"] for r in rows]), np.diff([r[f"y_{p}"] for r in rows])).sum())
    return max((tip, out), key=travel)


def traced_points(study) -> list[str]:
    """The points whose trajectories the plan of positions shows: the centres of mass and the
    output point when the output is a coordinate of a point of a link (a coupler point)."""
    from ..analysis.plans import output_quantity
    mech = study.mechanism
    out = [l.com for l in mech.moving if l.com]
    s_col = output_quantity(study)[0]
    head, _, p = s_col.partition("_")
    turning = [l for l in mech.moving if p in l.points
               and float(np.abs(study.cycle["wq_" + l.name]).max()) > 1e-12]
    if head in ("x", "y") and p not in out and turning and p not in mech.link(FRAME).points:
        out.append(p)
    return out


def _marked(p: str, mark: str) -> str:
    """B with a prime or double prime in mathtext: $B′$, $S″_{2}$."""
    head = p.rstrip("0123456789")
    tail = p[len(head):]
    if not head:
        head, tail = p, ""
    return "$" + head + mark + (f"_{{{tail}}}" if tail else "") + "$"


def _output_point(study, s_col: str) -> str:
    """The point that shows the output link's extreme positions: the slider's point, or the
    rocker's point farthest from its pivot."""
    mech = study.mechanism
    head, _, name = s_col.partition("_")
    if head in ("x", "y") and any(name in l.points for l in mech.moving):
        return name                     # the output is a coordinate of this point
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
        return study.mechanism.crank_pin()
    return d.end


def _centre(study, rows):
    d = study.mechanism.driver
    p = d.center
    return float(rows[0][f"x_{p}"]), float(rows[0][f"y_{p}"])


def _guide_angle(row, j) -> float:
    """Direction of a prismatic pair's guide line at a position: the line's angle in the guide
    link's own axes plus the link's angle (0 for the frame)."""
    return j.angle + (float(row[f"phi_{j.links[0]}"]) if j.links[0] != FRAME else 0.0)


@dataclass
class GroupsDrawing(Drawing):
    """The Assur groups drawn apart: per panel (the initial mechanism, then each group) its title,
    its scale μ_l (m/mm) and its drawn extent on paper (mm, the larger of width and height)."""
    panels: list[tuple[str, float, float]] = field(default_factory=list, kw_only=True)


class AssurGroups:
    """The initial mechanism and each Assur group drawn apart at one position, side by side, with
    the mechanism symbols (supports hatched, sliders and guides), the external pairs shown black
    and every label placed clear. All at one common ГОСТ 2.302 scale written under the row (the
    links keep their proportions: a crank is not drawn longer than its coupler) when at that scale
    every group's joints stand at least JOINT_MM apart; else each at its own scale written under
    it (so that each fills a comparable area and its labels are as readable as the others': a
    short crank or a small cylinder group is not dwarfed by a long group)."""

    needs = ("kinematics", "structure")
    PAGE_W = 165.0       # the text width, mm
    MAX_H = 95.0         # the tallest drawing with the room around it, mm
    PAD_MM = 14.0        # room around a group's links (both sides): labels, support symbols
    GUIDE_MM = 34.0      # a fixed guide reaches 14 mm past its slider each side (draw._guide), and hatch
    CAPTION_MM = 11.0    # two lines under each drawing: the group and its scale
    CAPTION_W = 32.0     # «μl = 0,0025 м/мм» at 9 pt, with a gap to the next
    STUB_MM = 12.0       # the element of a moving guide reaches this far each side of its slider
    JOINT_MM = 10.0      # two joints of a group closer than this on paper: their labels and symbols crowd

    def __init__(self, label: str):
        self.label = label

    def _links(self, study, g) -> set[str]:
        mech = study.mechanism
        links = set(g.links) | ({mech.driver.link} if g.klass == 1 else set())
        if mech.driver.kind == "actuator" and mech.driver.rod in links | {mech.driver.link}:
            links |= {mech.driver.rod, mech.driver.link} & (set(g.links) | ({mech.driver.link} if g.klass == 1 else set()))
        return links

    def _units(self, study) -> list[tuple[str, set[str]]]:
        """(title, links) of the initial mechanism and of each group, in the order of attachment."""
        mech = study.mechanism
        groups = study.structure.groups
        units = [(g.label + (" " + g.kind_ru if g.kind_ru else ""), self._links(study, g)) for g in groups]
        d = mech.driver
        if d.kind == "actuator":
            # the cylinder, the rod and the link it drives form one initial mechanism with the driving
            # prismatic pair inside (as the note's structural table and formula say)
            ic = next((i for i, (_, ls) in enumerate(units) if d.link in ls), None)
            ir = next((i for i, (_, ls) in enumerate(units) if d.rod in ls), None)
            if ic is not None and ir is not None and ic != ir:
                order = list(dict.fromkeys([d.link, d.rod] + [l for i in (ic, ir) for g in [groups[i]]
                                                                  for l in g.links]))
                merged = ("(" + ",".join(order) + ")", units[ic][1] | units[ir][1])
                units = [merged] + [u for i, u in enumerate(units) if i not in (ic, ir)]
        return units

    @staticmethod
    def _joint_gap(mech, row, links: set) -> float:
        """The least distance (m) between two joints of the group that do not coincide."""
        pts = sorted({j.point for j in mech.joints if set(j.links) & links})
        xy = np.array([(float(row[f"x_{p}"]), float(row[f"y_{p}"])) for p in pts])
        d = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
        d = d[d > 1e-6]
        return float(d.min()) if d.size else np.inf

    def _guide_elements(self, pn, mech, row, links: set) -> None:
        """An external prismatic pair whose guide is a moving link of an earlier group (a stone in
        the slot of a rocker): the group is drawn with that pair's element, a piece of the guide's
        line through the slider (as a frame guide is drawn with its hatched piece); without it the
        stone hung in the air and the pair by which the group is attached was not shown."""
        for j in mech.prismatic:
            if j.links[1] not in links or j.links[0] in links or j.links[0] == FRAME or j.driving:
                continue
            a = _guide_angle(row, j)
            x, y = float(row[f"x_{j.point}"]), float(row[f"y_{j.point}"])
            r = pn.mm(self.STUB_MM)
            pn.ax.plot([x - r * np.cos(a), x + r * np.cos(a)], [y - r * np.sin(a), y + r * np.sin(a)],
                       color=INK, lw=1.0, zorder=1, solid_capstyle="butt")

    def draw(self, study) -> GroupsDrawing:
        from ..style import mplstyle
        from .draw import Panel, common_panel_scale, mu_text, panel_scales
        mech = study.mechanism
        row = _row(study, self.label)
        allp = sorted({p for l in mech.moving for p in l.points})
        # a group whose joints nearly coincide (a stone and a slider at one point) is sized as a
        # sixth of the whole mechanism, not enlarged until its symbols pile up
        floor = max(np.ptp([float(row[f"x_{p}"]) for p in allp]), np.ptp([float(row[f"y_{p}"]) for p in allp])) / 6
        parts = []
        for g, links in self._units(study):
            # sorted: the same drawing whatever the hash seed
            pts = sorted({p for ln in sorted(links) for p in mech.link(ln).points})
            xs = [float(row[f"x_{p}"]) for p in pts]
            ys = [float(row[f"y_{p}"]) for p in pts]
            pw = ph = self.PAD_MM
            for j in mech.prismatic:
                if j.links[0] == FRAME and j.links[1] in links:
                    pw = max(pw, self.GUIDE_MM * abs(np.cos(j.angle)))
                    ph = max(ph, self.GUIDE_MM * abs(np.sin(j.angle)))
                elif j.links[1] in links and j.links[0] not in links:      # the element of a moving guide
                    a = _guide_angle(row, j)
                    pw = max(pw, 2 * self.STUB_MM * abs(np.cos(a)) + 4)
                    ph = max(ph, 2 * self.STUB_MM * abs(np.sin(a)) + 4)
            centre = ((min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2)
            parts.append((g, links, centre, max(np.ptp(xs), floor), max(np.ptp(ys), floor), pw, ph))
        mu = common_panel_scale([p[3:] for p in parts], self.PAGE_W, self.MAX_H, self.CAPTION_W)
        common = mu is not None and all(self._joint_gap(mech, row, p[1]) / mu >= self.JOINT_MM for p in parts)
        mus = [mu] * len(parts) if common else \
            panel_scales([p[3:] for p in parts], self.PAGE_W, self.MAX_H, self.CAPTION_W)
        widths = [max(w / mu + pw, self.CAPTION_W) for (*_, w, h, pw, ph), mu in zip(parts, mus)]
        height = max(h / mu + ph for (*_, w, h, pw, ph), mu in zip(parts, mus))
        total_w, total_h = sum(widths), height + self.CAPTION_MM
        fig = mplstyle.figure(total_w, total_h, layout=None)
        panels, x0, info = [], 0.0, []
        for (g, links, centre, w, h, pw, ph), mu, wi in zip(parts, mus, widths):
            pn = Panel(fig, (x0, self.CAPTION_MM, wi, height), centre, mu)
            draw_mechanism(pn, mech, row, only=links, lw=1.4)
            self._guide_elements(pn, mech, row, links)
            for j in mech.joints:
                if j.kind == "R" and set(j.links) & links and not set(j.links) <= links | {FRAME}:
                    x, y = float(row[f"x_{j.point}"]), float(row[f"y_{j.point}"])
                    pn.ax.add_patch(Circle((x, y), pn.mm(1.3), facecolor=INK, edgecolor=INK, zorder=6))
            xc = (x0 + wi / 2) / total_w
            fig.text(xc, (self.CAPTION_MM - 1.0) / total_h, g, ha="center", va="top", fontsize=10)
            if not common:
                fig.text(xc, (self.CAPTION_MM - 6.0) / total_h, rf"$\mu_l$ = {mu_text(mu)} м/мм", ha="center",
                         va="top", fontsize=9)
            panels.append(pn)
            info.append((g, mu, max(w, h) / mu))
            x0 += wi
        if common:      # the one scale under the whole row
            fig.text(0.5, (self.CAPTION_MM - 6.0) / total_h, rf"$\mu_l$ = {mu_text(mus[0])} м/мм", ha="center",
                     va="top", fontsize=9)
        for pn in panels:
            pn.labels.place()
        return GroupsDrawing(mplstyle.to_svg(fig), total_w, max(mus), panels=info)
