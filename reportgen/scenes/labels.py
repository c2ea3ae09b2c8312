"""Label placement for the drawings: no label overlaps another label, a line, an arrowhead or a
joint symbol, and none leaves the figure.

A scene registers each label with its anchor (the point it names) and, optionally, a preferred
direction; :meth:`LabelPlacer.place` is called after everything else is drawn. For every label,
candidate positions on rings around the anchor (radii ``RADII_MM`` from 2,2 to 23 mm; 8–24
directions, beyond ``FAR_MM`` at least one each ``ARC_MM`` of arc, so that a gap between lines
fanning out of a pivot is found) are tried in order of distance and of deviation from the
preferred direction; a candidate is rejected if the rendered extent of the text
(``Text.get_window_extent``) meets a placed label or leaves the axes. Of the others the first
that crosses no drawn segment (lines, arrow shafts and heads at their printed size, outlines of
patches, the leaders drawn so far) wins; a label farther than ``LEADER_MM`` from its anchor (for
the label of a body drawn round its point, a slider's block: ``reach_mm`` + ``REACH_LEAD_MM``)
gets a thin leader line (ГОСТ 2.316 style), which must pass through no placed label and costs
``CUT_MM`` of distance for each line it crosses (past ``LEADER_FREE_MM``, inside its own joint's
circle): a leader across lines is taken only when no nearer free place is. If no candidate is
free, the one with the fewest crossings is taken and gets a white halo round its glyphs
(:func:`check_figure` still reports it).

A label that names a point (``point=True``) must read as that point's: its centre is nearer its
own point than any other named point (more than ``OWN_APART_MM`` from it) by ``OWN_MARGIN_MM``
(a label «23» set down by the support
07 reads as the support's); a label with ``gap_mm`` keeps that clearance from every other label
(position numbers «1» and «3» side by side read as «13»). A candidate that breaks either is
taken only when no other free of lines is; one nearer another point but farther than
``LEADER_MM`` from its own is given a leader (which tells whose it is) and costs ``STRAY_MM``.

No label covers the point another label names (an arrow's tip among several drawn from one point,
as the couples' forces at the pole of Жуковский's lever): its box keeps ``ANCHOR_CLEAR_MM`` from
every other anchor farther than ``SAME_POINT_MM`` from its own, else it counts as crowded; a label
set over the tip of another force would leave that force's label no place a leader can reach
without passing through it.

Thin lines a scene marks ``breakable`` (the other positions and the trajectories on a plan of
positions) may be interrupted under a label, as ГОСТ 2.307 interrupts hatching and centre lines at
a dimension number: a place that crosses at most ``MAX_BREAKS`` of them costs ``BREAK_MM`` each
(a leader across them costs ``CUT_MM`` each, as across any line), and the lines under the chosen
place get a gap ``BREAK_PAD_MM`` round its box (a NaN in their data), so that no line crosses the
label. :func:`label_contours` sets the values of contour lines (``ax.clabel``'s kind) along their
lines where no other line crosses them; contour lines count as drawn lines for the placer and the
check.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from matplotlib import patheffects
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection
from matplotlib.contour import ContourSet
from matplotlib.lines import Line2D
from matplotlib.text import Text

from ..core import clip

MM_PT = 72 / 25.4        # points per millimetre
RADII_MM = (2.2, 3.2, 4.5, 6.0, 8.0, 10.5, 14.0, 18.0, 23.0)
FAR_MM, ARC_MM = 4.0, 1.5
LEADER_MM = 5.5
REACH_LEAD_MM = 3.0      # a label of a body (reach_mm) gets a leader this far beyond the body's reach
STRAY_MM = 4.0           # what a label nearer another point (so given a leader) costs
GRAZE_MM = 4.0           # what a line through the margin of a label's box costs (see LINE_TOL_MM)
CUT_MM = 5.0            # what a leader crossing a line costs, in millimetres of the label's distance
LEADER_FREE_MM = 1.6     # a leader's first part, inside its own joint's circle: lines meet there
PAD_PX = 1.0
OWN_MARGIN_MM = 1.5
OWN_APART_MM = 2.0
HALO_PT = 2.5
ANCHOR_CLEAR_MM = 0.5    # what a label keeps clear of the point another label names
SAME_POINT_MM = 0.5      # anchors nearer than this are one point (their labels share it)
LINE_TOL_MM = 0.3        # check_figure: a line within this of a label's glyph box edge only touches it
BREAK_MM = 2.5           # what interrupting a thin line (``breakable``) under a label costs, mm of distance
MAX_BREAKS = 6           # thin lines a label may interrupt at most
BREAK_PAD_MM = 0.4       # the gap of an interrupted line round the label's box


@dataclass
class _Item:
    x: float
    y: float
    text: str
    prefer: tuple[float, float] | None
    kw: dict = field(default_factory=dict)
    artist: Text | None = None
    point: bool = False
    gap_mm: float = 0.0
    reach_mm: float = 0.0


def _renderer(fig):
    if fig.canvas is None or not hasattr(fig.canvas, "get_renderer"):
        FigureCanvasAgg(fig)
    return fig.canvas.get_renderer()


def _segments(ax, renderer, skip, only=None) -> np.ndarray:
    """All drawn segments of the axes in display coordinates, shape (n, 4); ``only``: of those
    lines only."""
    segs = []

    def add_poly(v):
        v = np.asarray(v, float)
        if len(v) >= 2:
            segs.append(np.hstack([v[:-1], v[1:]]))
    for ln in ax.lines:
        if ln in skip or not ln.get_visible() or (only is not None and ln not in only):
            continue
        v = ln.get_transform().transform(np.column_stack(ln.get_data()).astype(float))
        ok = np.all(np.isfinite(v), axis=1)
        drawn = ln.get_linestyle() not in ("None", "none", "", " ")
        if (np.count_nonzero(ok) == 1 or not drawn) and ln.get_marker() not in (None, "", "None", " "):
            r = ln.get_markersize() / 2 * renderer.points_to_pixels(1)
            for x, y in v[ok]:       # the markers' squares (a marker-only line has no segments between)
                add_poly([(x - r, y - r), (x + r, y - r), (x + r, y + r), (x - r, y + r), (x - r, y - r)])
        if drawn:                    # a run of finite vertices each: a line broken (NaN) has gaps
            for run in np.split(v, np.flatnonzero(~ok)):
                add_poly(run[np.all(np.isfinite(run), axis=1)])
    if only is not None:
        return np.vstack(segs) if segs else np.zeros((0, 4))
    for coll in ax.collections:
        if coll in skip or not coll.get_visible():
            continue
        tr = coll.get_transform()
        if isinstance(coll, LineCollection):
            for s in coll.get_segments():
                add_poly(tr.transform(np.asarray(s, float)))
        elif isinstance(coll, ContourSet) and not coll.filled:      # contour lines (a filled one has no edge)
            for path in coll.get_paths():
                for poly in path.to_polygons(tr, closed_only=False):
                    add_poly(poly)
    for p in ax.patches:
        if p in skip or not p.get_visible():
            continue
        if hasattr(p, "_dpi_cor"):
            # an arrow's head is sized in points when it is drawn: before any drawing its path
            # is that of 72 dpi (matplotlib's FancyArrowPatch), smaller than it prints by the labels
            p._dpi_cor = renderer.points_to_pixels(1.0)
        try:
            path = p.get_path()
            tr = p.get_transform()
            for poly in path.to_polygons(tr, closed_only=False):
                add_poly(poly)
        except (ValueError, AttributeError):
            continue
    return np.vstack(segs) if segs else np.zeros((0, 4))


class _Segs:
    """The drawn segments indexed for clipping many rectangles against them: a rectangle is
    clipped (:func:`_crossings`) against only the segments whose bounding box meets it. Short
    segments (at most ``SHORT_PX`` wide: a trajectory has thousands) are sorted by their left
    end, so those that can reach the rectangle form one slice; long ones and those with a
    non-finite end are always tested. The count is the same as over all the segments."""

    SHORT_PX = 24.0

    def __init__(self, segs: np.ndarray):
        self.segs = segs
        with np.errstate(invalid="ignore"):
            self.xmin = np.minimum(segs[:, 0], segs[:, 2])
            self.xmax = np.maximum(segs[:, 0], segs[:, 2])
            self.ymin = np.minimum(segs[:, 1], segs[:, 3])
            self.ymax = np.maximum(segs[:, 1], segs[:, 3])
            self.odd = ~np.all(np.isfinite(segs), axis=1)
            short = ~self.odd & (self.xmax - self.xmin <= self.SHORT_PX)
        idx = np.flatnonzero(short)
        self.short = idx[np.argsort(self.xmin[idx], kind="stable")]
        self.short_x = self.xmin[self.short]
        self.rest = np.flatnonzero(~short)
        # the same, as the kernels of reportgen.core.clip read them (contiguous float64 rows)
        self._k = (np.ascontiguousarray(segs[self.short], dtype=np.float64), np.ascontiguousarray(self.short_x),
                   float(self.SHORT_PX), np.ascontiguousarray(segs[self.rest], dtype=np.float64),
                   np.ascontiguousarray(self.odd[self.rest]))

    def crossings(self, bb) -> int:
        """:func:`_crossings` of the segments and ``bb`` (counted by :func:`reportgen.core.clip.crossings`,
        the same arithmetic in one compiled pass; :meth:`crossings_numpy` is the NumPy form)."""
        return int(clip.crossings(*self._k, bb.x0 - PAD_PX, bb.y0 - PAD_PX, bb.x1 + PAD_PX, bb.y1 + PAD_PX))

    def crossings_numpy(self, bb) -> int:
        """:meth:`crossings` by NumPy array operations (the reference of the kernel)."""
        x0, y0, x1, y1 = bb.x0 - PAD_PX, bb.y0 - PAD_PX, bb.x1 + PAD_PX, bb.y1 + PAD_PX
        lo = np.searchsorted(self.short_x, x0 - self.SHORT_PX, side="left")
        hi = np.searchsorted(self.short_x, x1, side="right")
        idx = np.concatenate([self.short[lo:hi], self.rest])
        near = ((self.xmax[idx] >= x0) & (self.xmin[idx] <= x1) & (self.ymax[idx] >= y0)
                & (self.ymin[idx] <= y1)) | self.odd[idx]
        idx = idx[near]
        if len(idx) <= 32 and not self.odd[idx].any():
            return _crossings_few(self.segs[idx].tolist(), x0, y0, x1, y1)
        return _crossings(self.segs[idx], bb)

    def cuts(self, lead) -> int:
        """How many segments the segment ``lead`` = [x0, y0, x1, y1] crosses (a leader line;
        :func:`reportgen.core.clip.cuts`, the arithmetic of :meth:`cuts_numpy`)."""
        return int(clip.cuts(*self._k, *map(float, lead)))

    def cuts_numpy(self, lead) -> int:
        """:meth:`cuts` by NumPy array operations (the reference of the kernel)."""
        ax_, ay_, bx_, by_ = lead
        x0, x1 = min(ax_, bx_), max(ax_, bx_)
        y0, y1 = min(ay_, by_), max(ay_, by_)
        lo = np.searchsorted(self.short_x, x0 - self.SHORT_PX, side="left")
        hi = np.searchsorted(self.short_x, x1, side="right")
        idx = np.concatenate([self.short[lo:hi], self.rest])
        idx = idx[(self.xmax[idx] >= x0) & (self.xmin[idx] <= x1) & (self.ymax[idx] >= y0)
                  & (self.ymin[idx] <= y1) & ~self.odd[idx]]
        if not len(idx):
            return 0
        s = self.segs[idx]
        dx, dy = bx_ - ax_, by_ - ay_

        def side(px, py):
            return dx * (py - ay_) - dy * (px - ax_)
        s1, s2 = side(s[:, 0], s[:, 1]), side(s[:, 2], s[:, 3])
        ex, ey = s[:, 2] - s[:, 0], s[:, 3] - s[:, 1]
        t1 = ex * (ay_ - s[:, 1]) - ey * (ax_ - s[:, 0])
        t2 = ex * (by_ - s[:, 1]) - ey * (bx_ - s[:, 0])
        return int(np.count_nonzero((s1 * s2 <= 0) & (t1 * t2 <= 0)))


def _leader_segment(anchor, bb, free: float) -> list:
    """The leader from ``anchor`` to the nearest point of the box ``bb`` (display coordinates),
    less its first ``free`` px (the lines meeting at the anchor's own point start there)."""
    x = min(max(anchor[0], bb.x0), bb.x1)
    y = min(max(anchor[1], bb.y0), bb.y1)
    d = math.hypot(x - anchor[0], y - anchor[1])
    f = min(free / d, 1.0) if d > 0 else 0.0
    return [anchor[0] + (x - anchor[0]) * f, anchor[1] + (y - anchor[1]) * f, x, y]


def _through_boxes(seg: list, placed: list) -> int:
    """How many of the placed label boxes ((box, clearance) pairs) the segment passes through."""
    x0, x1 = min(seg[0], seg[2]), max(seg[0], seg[2])
    y0, y1 = min(seg[1], seg[3]), max(seg[1], seg[3])
    return sum(_crossings_few([seg], b.x0, b.y0, b.x1, b.y1) for b, _ in placed
               if b.x0 <= x1 and x0 <= b.x1 and b.y0 <= y1 and y0 <= b.y1)


def _crossings_few(segs: list, x0: float, y0: float, x1: float, y1: float) -> int:
    """:func:`_crossings` of a few finite segments against the padded rectangle, one by one
    (the same arithmetic, without the cost of 30 array operations on a handful of rows)."""
    n = 0
    for sx, sy, ex, ey in segs:
        dx, dy = ex - sx, ey - sy
        t0, t1 = 0.0, 1.0
        for p, q in ((-dx, sx - x0), (dx, x1 - sx), (-dy, sy - y0), (dy, y1 - sy)):
            if abs(p) < 1e-12:
                if q < 0:
                    break
            elif p < 0:
                t0 = max(t0, q / p)
            else:
                t1 = min(t1, q / p)
        else:
            n += t0 <= t1
    return n


def _crossings(segs: np.ndarray, bb) -> int:
    """How many segments meet the rectangle ``bb`` (Liang–Barsky clipping, vectorized)."""
    if len(segs) == 0:
        return 0
    return int(np.count_nonzero(_meets(segs, bb)))


def _meets(segs: np.ndarray, bb) -> np.ndarray:
    """Which segments meet the rectangle ``bb`` padded by PAD_PX (a segment with a NaN end: none)."""
    x0, y0, x1, y1 = bb.x0 - PAD_PX, bb.y0 - PAD_PX, bb.x1 + PAD_PX, bb.y1 + PAD_PX
    px, py = segs[:, 0], segs[:, 1]
    dx, dy = segs[:, 2] - px, segs[:, 3] - py
    t0 = np.zeros(len(segs))
    t1 = np.ones(len(segs))
    ok = np.ones(len(segs), bool)
    for p, q in ((-dx, px - x0), (dx, x1 - px), (-dy, py - y0), (dy, y1 - py)):
        par = np.abs(p) < 1e-12
        ok &= ~(par & (q < 0))
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(par, 0.0, q / np.where(par, 1.0, p))
        t0 = np.where(~par & (p < 0), np.maximum(t0, r), t0)
        t1 = np.where(~par & (p > 0), np.minimum(t1, r), t1)
    return ok & (t0 <= t1)


def _overlap(a, b, gap: float = 0.0) -> bool:
    """The boxes meet, or come closer than ``gap`` (px)."""
    return a.x0 < b.x1 + gap and b.x0 < a.x1 + gap and a.y0 < b.y1 + gap and b.y0 < a.y1 + gap


class _Extent:
    """The rendered extent of a text at any position, from one layout: what
    ``Text.get_window_extent`` returns (the layout's box moved to the display position), for
    the candidate places of a label without laying its text out again at each."""

    def __init__(self, t: Text, renderer):
        self.t, self.renderer = t, renderer
        self.box = None
        if t.get_visible() and t.get_text() != "":
            t._renderer = renderer
            self.box, _, _ = t._get_layout(renderer)
            self.corners = self.box.get_points().ravel().tolist()
            self.tr = t.get_transform()

    def at_px(self, x: float, y: float, inv) -> "_Box":
        """The extent with the text at the display point (x, y); ``inv``: display → data."""
        if self.box is None:
            return self.at(inv.transform((x, y)))
        bx0, by0, bx1, by1 = self.corners
        return _Box(bx0 + x, by0 + y, bx1 + x, by1 + y)

    def at(self, xy) -> "_Box":
        """The extent with the text at ``xy`` (data coordinates)."""
        if self.box is None:
            self.t.set_position(xy)
            return _Box(*self.t.get_window_extent(self.renderer).get_points().ravel().tolist())
        x, y = self.tr.transform((float(xy[0]), float(xy[1])))
        bx0, by0, bx1, by1 = self.corners
        return _Box(bx0 + x, by0 + y, bx1 + x, by1 + y)


class _Box:
    """A rectangle in display coordinates as four floats (what the placer reads of a ``Bbox``,
    without its transform machinery: each ``Bbox.x0`` is a method call and an array look-up)."""

    __slots__ = ("x0", "y0", "x1", "y1")

    def __init__(self, x0: float, y0: float, x1: float, y1: float):
        self.x0, self.y0, self.x1, self.y1 = x0, y0, x1, y1


def place_on_chart(placer: "LabelPlacer", avoid=()) -> list[Text]:
    """Place the labels of a chart whose figure has a layout engine (constrained layout): the
    layout is done first and then kept, so that the axes do not move under the placed labels;
    an axes of equal aspect is shrunk to its drawn box first (as drawing would). ``avoid``:
    artists (a legend) whose boxes, once laid out, no label may overlap."""
    fig = placer.fig
    engine = fig.get_layout_engine()
    if engine is not None:
        engine.execute(fig)
        fig.set_layout_engine("none")
    for ax in fig.axes:
        ax.apply_aspect()
    placer.avoid_boxes += [a.get_window_extent(_renderer(fig)) for a in avoid]
    return placer.place()


CONTOUR_STEP_MM = 1.5     # label_contours: candidate places along a contour line this far apart
CONTOUR_SPACING_PX = 3   # the contour line's gap beyond the label, each side (matplotlib's inline_spacing)


def label_contours(ax, cs: ContourSet, fmt, *, fontsize: float) -> list[Text]:
    """One inline label per level of the contour lines ``cs`` (what ``ax.clabel`` writes: the value
    along the line, which is cut under it), set where no line crosses it: the places along the
    level's line, ``CONTOUR_STEP_MM`` apart from the middle of each of its pieces outwards (longest
    piece first), are tried in turn; the first whose rendered extent (shrunk as
    :func:`line_problems` reads it) stays in the axes, meets no other text and is crossed by no
    drawn line, no other contour and not by its own line beside the cut wins, else the one crossed
    least. To be called when everything else is drawn and laid out (:func:`place_on_chart`)."""
    renderer = _renderer(ax.figure)
    px_mm = ax.figure.dpi / 25.4
    tol = (LINE_TOL_MM - 0.1) * px_mm + PAD_PX
    frame = ax.get_window_extent(renderer)
    cs.clabel(fmt=fmt, fontsize=fontsize, manual=[])         # the labeller set up, no label yet
    rest = _segments(ax, renderer, skip=(cs,))
    tr = cs.get_transform()
    out = []
    for i in range(len(cs.levels)):
        path = cs.get_paths()[i]
        pieces = [p for p in path.to_polygons(tr, closed_only=False) if len(p) >= 2]
        if not pieces:
            continue
        others = [q for j, p in enumerate(cs.get_paths()) if j != i for q in p.to_polygons(tr, closed_only=False)]
        segs = _Segs(np.vstack([rest] + [np.hstack([q[:-1], q[1:]]) for q in others if len(q) >= 2]))
        boxes = [t.get_window_extent(renderer) for t in ax.texts]
        cands = []
        for piece in sorted(pieces, key=len, reverse=True):
            d = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(piece, axis=0).T))])
            at = np.arange(0.0, d[-1], CONTOUR_STEP_MM * px_mm)
            at = at[np.argsort(np.abs(at - d[-1] / 2), kind="stable")]
            cands += [(np.interp(a, d, piece[:, 0]), np.interp(a, d, piece[:, 1])) for a in at]
        best = None
        for x, y in cands:
            kept = list(cs._paths)
            cs.add_label_near(x, y, inline=True, inline_spacing=CONTOUR_SPACING_PX, transform=False)
            t = cs.labelTexts[-1]
            bb = t.get_window_extent(renderer)
            cs.pop_label()
            own = cs._paths[i]
            cs._paths[:] = kept
            inside = (bb.x0 >= frame.x0 + 1 and bb.x1 <= frame.x1 - 1 and bb.y0 >= frame.y0 + 1
                      and bb.y1 <= frame.y1 - 1)
            if not inside or any(_overlap(bb, o) for o in boxes):
                continue
            box = _Box(bb.x0 + tol, bb.y0 + tol, bb.x1 - tol, bb.y1 - tol)
            mine = [q for q in own.to_polygons(tr, closed_only=False) if len(q) >= 2]
            hits = segs.crossings(box) + sum(_crossings(np.hstack([q[:-1], q[1:]]), box) for q in mine)
            if best is None or hits < best[0]:
                best = (hits, x, y)
            if hits == 0:
                break
        if best is not None:
            cs.add_label_near(best[1], best[2], inline=True, inline_spacing=CONTOUR_SPACING_PX, transform=False)
            out.append(cs.labelTexts[-1])
    return out


class _Thin:
    """The thin lines a label may interrupt (``breakable``) with their vertices in display
    coordinates, stacked as segments so that those under a label's box are found at once."""

    def __init__(self, lines: list):
        self.lines = lines
        self.v = [ln.get_transform().transform(np.column_stack(ln.get_data()).astype(float)) for ln in lines]
        self._stack()

    def _stack(self) -> None:
        parts = [np.hstack([v[:-1], v[1:]]) for v in self.v]
        self.segs = np.vstack(parts) if parts else np.zeros((0, 4))
        self.owner = np.repeat(np.arange(len(self.v)), [len(p) for p in parts])

    def cut(self, box: _Box) -> None:
        """Interrupt the lines where they pass through ``box``: the part of each segment inside
        it (Liang–Barsky) is left out, the line's data get a NaN gap there."""
        touched = np.unique(self.owner[_meets(self.segs, box)]) if len(self.segs) else []
        for i in touched:
            v = _cut_polyline(self.v[i], box)
            if v is not None:
                ln = self.lines[i]
                d = ln.get_transform().inverted().transform(v)
                ln.set_data(d[:, 0], d[:, 1])
                self.v[i] = v
        if len(touched):
            self._stack()


def _cut_polyline(v: np.ndarray, box: _Box) -> np.ndarray | None:
    """The vertices ``v`` (display) less the parts inside ``box``, a NaN row at each gap; None if
    no segment passes through the box."""
    out, changed = [], False
    for i in range(len(v)):
        if i == 0 or not (math.isfinite(v[i - 1][0]) and math.isfinite(v[i][0])):
            out.append(v[i])
            continue
        (sx, sy), (ex, ey) = v[i - 1], v[i]
        dx, dy = ex - sx, ey - sy
        t0, t1 = 0.0, 1.0
        for p, q in ((-dx, sx - box.x0), (dx, box.x1 - sx), (-dy, sy - box.y0), (dy, box.y1 - sy)):
            if abs(p) < 1e-12:
                if q < 0:
                    t0, t1 = 1.0, 0.0
            elif p < 0:
                t0 = max(t0, q / p)
            else:
                t1 = min(t1, q / p)
        if t0 > t1:
            out.append(v[i])
            continue
        changed = True
        if t0 > 0:
            out.append((sx + t0 * dx, sy + t0 * dy))
        if math.isfinite(out[-1][0]):     # one gap for a run of segments cut (a vertex inside the box)
            out.append((math.nan, math.nan))
        if t1 < 1:
            out += [(sx + t1 * dx, sy + t1 * dy), v[i]]
    return np.array(out, float) if changed else None


class LabelPlacer:
    """Collects the labels of one axes and places them after the drawing is complete."""

    def __init__(self, ax, *, fontsize: float = 10.0):
        self.ax = ax
        self.fig = ax.figure
        self.fontsize = fontsize
        self.items: list[_Item] = []
        self.avoid_boxes = []
        self.gap_mm = 0.0          # least printed gap between two labels (0: they may touch)

    def add(self, x: float, y: float, text: str, prefer=None, *, point: bool = False, gap_mm: float = 0.0,
            reach_mm: float = 0.0, **kw) -> None:
        """A label for the point (x, y) in data coordinates; ``prefer``: a direction (dx, dy);
        ``point``: the label names the point (kept nearer it than any other named point);
        ``gap_mm``: the clearance kept from every other label; ``reach_mm``: how far the body
        drawn round the point reaches (a slider's block): a label beside the body needs no
        leader line (one from the point would cross the body's outline)."""
        if prefer is not None:
            n = math.hypot(*prefer)
            prefer = (prefer[0] / n, prefer[1] / n) if n > 1e-12 else None
        self.items.append(_Item(float(x), float(y), text, prefer, kw, point=point, gap_mm=gap_mm, reach_mm=reach_mm))

    def _foreign(self, it: _Item, px_mm: float) -> np.ndarray:
        """The other named points near which a label of ``it`` must not sit (display coordinates);
        points within ``OWN_APART_MM`` of its own (A and its extreme position A′ nearly at one
        place) do not count: no label can be told apart from those by place."""
        if not it.point:
            return np.zeros((0, 2))
        own = self.ax.transData.transform((it.x, it.y))
        pts = [self.ax.transData.transform((o.x, o.y)) for o in self.items if o.point and o is not it]
        pts = np.array(pts).reshape(-1, 2)
        return pts[np.hypot(*(pts - own).T) > OWN_APART_MM * px_mm] if len(pts) else pts

    def place(self) -> list[Text]:
        ax, fig = self.ax, self.fig
        renderer = _renderer(fig)
        thin = [ln for ln in ax.lines if getattr(ln, "breakable", False)]
        segs = _Segs(_segments(ax, renderer, skip=tuple(thin)))
        bsegs = _Segs(_segments(ax, renderer, skip=(), only=thin)) if thin else None
        breaker = None
        frame = ax.get_window_extent(renderer)
        # the axes' limits and place do not change while the labels are placed: one inverse
        inv = ax.transData.inverted()
        figbox = fig.bbox
        # where a label's box may lie: inside the axes and the figure, 1 px in (read once: each
        # ``Bbox.x0`` is a method call)
        in_x0, in_x1 = max(frame.x0, figbox.x0) + 1, min(frame.x1, figbox.x1) - 1
        in_y0, in_y1 = max(frame.y0, figbox.y0) + 1, min(frame.y1, figbox.y1) - 1
        px_mm = fig.dpi / 25.4
        placed = [(_Box(b.x0, b.y0, b.x1, b.y1), 0.0) for b in self.avoid_boxes]      # (box, clearance in px)
        hard = self.gap_mm * px_mm      # the placer's least gap between any two labels (a must)
        # the placed boxes as the hard test reads them (:func:`_overlap` with the gap ``hard``, its
        # sums of a placed box's and the gap done once): x0, y0, x1 + hard, y1 + hard
        hard_rows = [(o.x0, o.y0, o.x1 + hard, o.y1 + hard) for o, _ in placed]
        tol = (LINE_TOL_MM - 0.1) * px_mm + PAD_PX     # the box as check_figure reads it, less 0,1 mm
        out = []
        anchors = self.ax.transData.transform(np.array([(o.x, o.y) for o in self.items]).reshape(-1, 2))
        clear = ANCHOR_CLEAR_MM * px_mm
        pad = BREAK_PAD_MM * px_mm      # a thin line interrupted this far round a label's box
        leaders: list = []              # the leader lines drawn so far: x0, y0, x1, y1, then their box
        for it in self.items:
            kw = dict(fontsize=self.fontsize, ha="center", va="center", zorder=10)
            kw.update(it.kw)
            t = ax.text(it.x, it.y, it.text, **kw)
            extent = _Extent(t, renderer)
            ax0 = ax.transData.transform((it.x, it.y))
            foreign = self._foreign(it, px_mm)
            gap = it.gap_mm * px_mm
            lead_px = max(LEADER_MM, it.reach_mm + REACH_LEAD_MM) * px_mm
            # the points the other labels name, near enough for one of its boxes to reach
            dist = np.hypot(*(anchors - ax0).T)
            size = max(map(abs, extent.corners)) if extent.box is not None else 40.0 * px_mm
            reach = RADII_MM[-1] * px_mm + size * math.sqrt(2) + clear
            others = anchors[(dist > SAME_POINT_MM * px_mm) & (dist < reach)].tolist()
            best = None
            # the placed boxes with this label's clearance from each (max(gap, g)) added once
            soft_rows = [(o.x0, o.y0, o.x1, o.y1, max(gap, g)) for o, g in placed]
            for k, (cx, cy) in enumerate(self._candidates(it, px_mm)):
                r_mm = math.hypot(cx, cy) / px_mm
                clean = best is not None and best[0][:4] == (False, False, False, 0)
                if clean and r_mm >= best[0][4]:
                    break       # a clean place found: none farther out can be nearer by its score
                bb = extent.at_px(ax0[0] + cx, ax0[1] + cy, inv)
                x0, y0, x1, y1 = bb.x0, bb.y0, bb.x1, bb.y1
                if not (x0 >= in_x0 and x1 <= in_x1 and y0 >= in_y0 and y1 <= in_y1):
                    continue        # not inside the axes and the figure
                x1h, y1h = x1 + hard, y1 + hard
                if any(x0 < ox1 and ox0 < x1h and y0 < oy1 and oy0 < y1h for ox0, oy0, ox1, oy1 in hard_rows):
                    continue
                crowded = (any(x0 < ox1 + gg and ox0 < x1 + gg and y0 < oy1 + gg and oy0 < y1 + gg
                               for ox0, oy0, ox1, oy1, gg in soft_rows)
                           or any(bb.x0 - clear < x < bb.x1 + clear and bb.y0 - clear < y < bb.y1 + clear
                                  for x, y in others))
                # nearer another named point than its own (by the margin): reads as that point's
                centre = ((bb.x0 + bb.x1) / 2, (bb.y0 + bb.y1) / 2)
                own = math.hypot(centre[0] - ax0[0], centre[1] - ax0[1])
                stray = bool(len(foreign)) and float(np.hypot(*(foreign - centre).T).min()) < own + OWN_MARGIN_MM * px_mm
                hits = segs.crossings(bb)
                graze = 0
                if hits and clean and r_mm + GRAZE_MM >= best[0][4]:
                    continue    # crossed or grazed: no better than the clean place found
                if hits:        # lines only in the box's margin, where check_figure lets them be
                    graze, hits = hits, segs.crossings(_Box(bb.x0 + tol, bb.y0 + tol, bb.x1 - tol, bb.y1 - tol))
                    graze -= hits
                if leaders:     # the leaders drawn so far, by their boxes first
                    near = [ld for ld in leaders if ld[4] <= bb.x1 + PAD_PX and bb.x0 - PAD_PX <= ld[5]
                            and ld[6] <= bb.y1 + PAD_PX and bb.y0 - PAD_PX <= ld[7]]
                    if near:
                        hits += _crossings_few([ld[:4] for ld in near], bb.x0 - PAD_PX, bb.y0 - PAD_PX,
                                               bb.x1 + PAD_PX, bb.y1 + PAD_PX)
                # the thin lines it would interrupt (ГОСТ 2.307: thin lines break at a number)
                brk = bsegs.crossings(_Box(bb.x0 - pad, bb.y0 - pad, bb.x1 + pad, bb.y1 + pad)) if thin and not hits else 0
                if brk > MAX_BREAKS:
                    hits += brk
                # a stray label far enough for a leader to be seen gets one: the leader tells whose
                led = r_mm * px_mm > lead_px or (stray and r_mm > LEADER_MM)
                cut = 0
                if led and hits == 0:
                    # its leader: through no label (a must), across as few lines as may be
                    hits += _through_boxes(_leader_segment(ax0, bb, 0.0), placed)
                    if hits == 0:
                        lead = _leader_segment(ax0, bb, LEADER_FREE_MM * px_mm)
                        cut = segs.cuts(lead) + (bsegs.cuts(lead) if thin else 0)
                # a leader across a line is worth CUT_MM more of distance
                score = (r_mm + CUT_MM * cut + GRAZE_MM * graze + BREAK_MM * brk
                         + (STRAY_MM if stray and led else 0.0))
                cost = (hits > 0, stray and not led, crowded, hits, score, k)
                if best is None or cost < best[0]:
                    best = (cost, (cx, cy), bb, led, brk)
                if hits == 0 and not stray and not crowded and cut == 0 and graze == 0 and brk == 0:
                    break
            if best is None:       # nowhere free inside: nearest candidate inside the figure
                cands = list(self._candidates(it, px_mm))
                for cx, cy in cands:
                    bb = extent.at(inv.transform((ax0[0] + cx, ax0[1] + cy)))
                    if bb.x0 >= figbox.x0 and bb.x1 <= figbox.x1 and bb.y0 >= figbox.y0 and bb.y1 <= figbox.y1:
                        best = ((True, 99), (cx, cy), bb, False, 0)
                        break
                else:
                    best = ((True, 99), cands[0], extent.at(inv.transform((ax0[0] + cands[0][0], ax0[1] + cands[0][1]))),
                            False, 0)
            cost, (cx, cy), bb, led, brk = best
            t.set_position(inv.transform((ax0[0] + cx, ax0[1] + cy)))
            t.anchor = (it.x, it.y)        # what the label names (data coordinates), for the checks
            t.lead_mm = lead_px / px_mm       # and from how far it gets a leader
            if cost[0]:
                # no free place: the lines under the label are broken by a white halo round its glyphs
                t.set_path_effects([patheffects.withStroke(linewidth=HALO_PT, foreground="white")])
            placed.append((bb, gap))
            hard_rows.append((bb.x0, bb.y0, bb.x1 + hard, bb.y1 + hard))
            if brk and not cost[0]:        # the thin lines under it interrupted
                if breaker is None:
                    breaker = _Thin(thin)
                breaker.cut(_Box(bb.x0 - pad, bb.y0 - pad, bb.x1 + pad, bb.y1 + pad))
                bsegs = _Segs(breaker.segs[np.all(np.isfinite(breaker.segs), axis=1)])
            if led or math.hypot(cx, cy) > lead_px:
                t.leader = self._leader(ax0, bb)
                ld = _leader_segment(ax0, bb, 0.0)
                leaders.append(ld + [min(ld[0], ld[2]), max(ld[0], ld[2]), min(ld[1], ld[3]), max(ld[1], ld[3])])
            out.append(t)
        return out

    def _candidates(self, it: _Item, px_mm: float):
        """The candidate offsets (display px), ring by ring, made as the search reaches them."""
        a0 = math.atan2(it.prefer[1], it.prefer[0]) if it.prefer is not None else math.pi / 4
        for r in RADII_MM:
            n = 8 if r < 5 else 16 if r < 12 else 24
            if r > FAR_MM:      # past the usual rings: a free spot between lines, at ARC_MM steps
                n = max(n, int(2 * math.pi * r / ARC_MM))
            angs = [2 * math.pi * i / n + (math.pi / n if r in RADII_MM[1::2] else 0.0) for i in range(n)]
            angs.sort(key=lambda a: abs(math.remainder(a - a0, 2 * math.pi)))
            yield from [(r * px_mm * math.cos(a), r * px_mm * math.sin(a)) for a in angs]

    def _leader(self, anchor, bb) -> Line2D:
        """A thin line from the anchor to the nearest point of the label's box."""
        x0, y0, x1, y1 = _leader_segment(anchor, bb, 0.0)
        inv = self.ax.transData.inverted()
        (x0, y0), (x1, y1) = inv.transform((x0, y0)), inv.transform((x1, y1))
        return self.ax.add_line(Line2D([x0, x1], [y0, y1], lw=0.4, color="#444444", zorder=9))


def check_figure(fig) -> list[str]:
    """Problems with the texts of a figure: pairs of overlapping labels, labels clipped by
    the figure (from matplotlib's rendered extents) and placed labels crossed by a line
    (:func:`line_problems`). An empty list means the figure is clean."""
    renderer = _renderer(fig)
    fig.draw_without_rendering()
    texts = []
    for ax in fig.axes:
        texts += [t for t in ax.texts if t.get_visible() and t.get_text().strip()]
        texts += [t for t in (ax.title, ax._left_title, ax._right_title) if t.get_visible() and t.get_text().strip()]
    texts += [t for t in fig.texts if t.get_visible() and t.get_text().strip()]
    boxes = [(t.get_text(), t.get_window_extent(renderer)) for t in texts]
    problems = []
    fb = fig.bbox
    for name, bb in boxes:
        if bb.x0 < fb.x0 - 0.5 or bb.x1 > fb.x1 + 0.5 or bb.y0 < fb.y0 - 0.5 or bb.y1 > fb.y1 + 0.5:
            problems.append(f"clipped: {name!r}")
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            a, b = boxes[i][1], boxes[j][1]
            if a.x0 < b.x1 - 0.5 and b.x0 < a.x1 - 0.5 and a.y0 < b.y1 - 0.5 and b.y0 < a.y1 - 0.5:
                problems.append(f"overlap: {boxes[i][0]!r} / {boxes[j][0]!r}")
    return problems + line_problems(fig, renderer)


def line_problems(fig, renderer=None, *, every: bool = False) -> list[str]:
    """Labels of the axes crossed by a drawn line (those set by a :class:`LabelPlacer`; with
    ``every`` all the texts of the axes): a text whose rendered extent, shrunk by
    ``LINE_TOL_MM`` on every side (a line merely touching the glyph box, which is wider than the
    glyphs, is no fault), meets a segment of a line, an arrow (shaft or head), a patch's outline
    (a link's plate, a joint's circle, a slider's block, a support's hatch) or another label's
    leader; its own leader line does not count. A textbook drawing has no line through a letter
    (a white halo does not make one acceptable)."""
    renderer = renderer or _renderer(fig)
    shrink = LINE_TOL_MM * fig.dpi / 25.4 + PAD_PX       # _Segs pads the box by PAD_PX
    problems = []
    for ax in fig.axes:
        texts = [t for t in ax.texts if t.get_visible() and t.get_text().strip()
                 and (every or hasattr(t, "anchor"))]
        if not texts:
            continue
        own = [getattr(t, "leader", None) for t in ax.texts]
        base = _Segs(_segments(ax, renderer, skip=tuple(ln for ln in own if ln is not None)))
        for t in texts:
            ln = getattr(t, "leader", None)
            bb = t.get_window_extent(renderer)
            box = _Box(bb.x0 + shrink, bb.y0 + shrink, bb.x1 - shrink, bb.y1 - shrink)
            if box.x0 >= box.x1 or box.y0 >= box.y1:
                continue
            n = base.crossings(box)
            # the other labels' leaders
            n += sum(_crossings_few(_segments_of(o), box.x0 - PAD_PX, box.y0 - PAD_PX, box.x1 + PAD_PX,
                                    box.y1 + PAD_PX) for o in own if o is not None and o is not ln)
            if n:
                problems.append(f"crossed by {n} line(s): {t.get_text()!r}")
    return problems


def _segments_of(line) -> list:
    """The segments of a line (a leader) in display coordinates, as lists."""
    v = line.get_transform().transform(np.column_stack(line.get_data()).astype(float))
    return np.hstack([v[:-1], v[1:]]).tolist()


def tex_point(p: str, prime: bool = False, lower: bool = False) -> str:
    """A point name in mathtext: S2 → $S_{2}$, with ``lower`` and ``prime`` the plan point
    s′₂ → $s'_{2}$ (textbook notation of the plans)."""
    head = p.rstrip("0123456789")
    tail = p[len(head):]
    if not head:
        head, tail = p, ""
    if lower:
        head = head.lower()
    return "$" + head + ("′" if prime else "") + (f"_{{{tail}}}" if tail else "") + "$"
