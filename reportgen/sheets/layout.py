"""Placing the views of a drawing sheet: standard enlargements, no overlap, clear of the title block.

A view has a natural size in millimetres (the size the note prints it at) and, when it is drawn to
a scale, its scale factor μ (units per millimetre).  On the sheet a view may be enlarged by a factor
s; a drawn-to-scale view only by factors that keep μ/s a standard value (1; 1,5; 2; 2,5; 4; 5 · 10ᵏ,
the series of the note's scenes, which holds the ГОСТ 2.302-68 scales), so the scale written
beside the view stays a round number.  Charts (no μ) may be enlarged by any factor of the series.

Placement is a first-fit, largest view first, on candidate corners (every combination of the
field's edges and the edges of the views already placed), topmost then leftmost, with a gap between
views.  First the largest common enlargement for which every view finds a place is taken; then the
main views (priority > 1: the plan of positions, the energy–mass diagram, the group drawings, the cam
profile) are enlarged as far as the others still fit (these may step down to ``SHRINK`` of the common
enlargement), up to ``priority`` times further than the others; then every view grows one step at a
time, in rounds in its order on the sheet, while everything still fits (the views of one group, the
velocity plans, take their steps together, so their scales stay alike).  Every step is a fixed
sequence of trials, so the placement is deterministic.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

NICE = (1.0, 1.5, 2.0, 2.5, 4.0, 5.0)
FACTORS = (4.0, 3.0, 2.5, 2.0, 1.6, 1.5, 1.25, 1.0, 0.8, 0.75, 0.6, 0.5, 0.4)
GAP_MM = 12.0
GROWTH = 1.6          # a view grows at most GROWTH·priority times beyond the common enlargement
                      # (a drawn view at least to its next standard scale)
SHRINK = 0.75         # the others may shrink to this share of the common enlargement for the main view
MAX_CHART = 2.0       # a chart (its lettering grows with it) is enlarged at most MAX_CHART·priority


@dataclass
class View:
    """A view to place: its natural size (mm), title line and μ (None for a chart)."""

    key: str
    width: float
    height: float
    mu: float | None = None
    title_h: float = 9.0          # room for the view's title and scale above it
    priority: float = 1.0         # > 1 for the sheet's main view: it is enlarged first and most
    title_w: float = 0.0          # width of the title line: a narrow view is placed as wide as its title
    mu_only: float | None = None  # the one scale the view may take (asked by the case), if set
    group: str | None = None      # views of one group grow together, step by step
    min_s: float = 0.4            # the view is not shrunk below this (its lettering stays legible)
    max_s: float | None = None    # nor enlarged above this
    mu2: float | None = None      # a second scale of the view (the force polygon's μ_F beside the group)


@dataclass
class Placed:
    view: View
    x: float                      # lower left corner of the view's drawing (mm on the sheet)
    y: float
    s: float                      # enlargement of the natural size

    @property
    def w(self) -> float:
        return self.view.width * self.s

    @property
    def h(self) -> float:
        return self.view.height * self.s

    @property
    def mu(self) -> float | None:
        return None if self.view.mu is None else self.view.mu / self.s

    @property
    def dx(self) -> float:
        """Half the excess of the title's width over the drawing's (the title is centred on it)."""
        return max(0.0, (self.view.title_w - self.w) / 2)

    def box(self, with_title: bool = True) -> tuple[float, float, float, float]:
        """The view's footprint: the drawing, and with the title the strip above it as wide as the
        wider of the two."""
        if not with_title:
            return (self.x, self.y, self.x + self.w, self.y + self.h)
        top = self.y + self.h + self.view.title_h
        return (self.x - self.dx, self.y, self.x + self.w + self.dx, top)


def is_nice(mu: float) -> bool:
    """μ = n·10ᵏ with n from the standard series."""
    if not (mu > 0 and math.isfinite(mu)):
        return False
    k = math.floor(math.log10(mu))
    m = mu / 10.0 ** k
    return any(abs(m - n) < 1e-9 * n or abs(m - 10 * n) < 1e-9 for n in NICE)


def factors_for(view: View) -> list[float]:
    """The enlargements a view may take, largest first: the series FACTORS for a chart; for a
    drawn-to-scale view every factor between the ends of FACTORS that makes μ/s a standard value
    (so 1:25 may become 1:20, 1:15, 1:10 … and not only what FACTORS happens to hold); none
    below the view's ``min_s`` (the largest of them if all are)."""
    fs = [f for f in _factors(view) if (view.max_s is None or f <= view.max_s + 1e-12)
          and (view.mu2 is None or is_nice(view.mu2 / f))] or [1.0]
    return [f for f in fs if f >= view.min_s - 1e-12] or fs[:1]


def _factors(view: View) -> list[float]:
    if view.mu is None:
        return list(FACTORS)
    lo, hi = FACTORS[-1], FACTORS[0]
    if view.mu_only is not None and lo - 1e-12 <= view.mu / view.mu_only <= hi + 1e-12:
        return [view.mu / view.mu_only]
    k0 = math.floor(math.log10(view.mu / hi)) - 1
    out = set()
    for k in range(k0, k0 + 4):
        for n in NICE:
            f = view.mu / (n * 10.0 ** k)
            if lo - 1e-12 <= f <= hi + 1e-12:
                out.add(round(f, 12))
    return sorted(out, reverse=True)


def allowed_factor(view: View, target: float) -> float:
    """The largest factor ≤ target that keeps the view's scale standard (any for a chart)."""
    fs = factors_for(view)
    for f in fs:
        if f <= target + 1e-12:
            return f
    return fs[-1]


def next_factor(view: View, f: float) -> float | None:
    """The smallest factor above ``f`` that keeps the view's scale standard (None at the top)."""
    up = [g for g in factors_for(view) if g > f + 1e-12]
    return min(up) if up else None


def _overlap(a, b, gap=0.0) -> bool:
    return not (a[2] + gap <= b[0] or b[2] + gap <= a[0] or a[3] + gap <= b[1] or b[3] + gap <= a[1])


def _inside(a, field) -> bool:
    return a[0] >= field[0] - 1e-9 and a[1] >= field[1] - 1e-9 and a[2] <= field[2] + 1e-9 and a[3] <= field[3] + 1e-9


def _try(views: list[View], factors: list[float], field, keepout) -> list[Placed] | None:
    order = sorted(range(len(views)), key=lambda i: -(views[i].width * views[i].height * factors[i] ** 2))
    placed: list[Placed] = []
    for i in order:
        v, s = views[i], factors[i]
        dx = max(0.0, (v.title_w - v.width * s) / 2)
        w, h = v.width * s + 2 * dx, v.height * s + v.title_h
        xs = [field[0]] + [p.box()[2] + GAP_MM for p in placed] + [field[2] - w]
        tops = [field[3]] + [p.box()[1] - GAP_MM for p in placed] + [field[1] + h]
        cands = [(x, top) for x in xs for top in tops]
        best = None
        for (x, top) in cands:
            box = (x, top - h, x + w, top)
            if not _inside(box, field) or _overlap(box, keepout):
                continue
            if any(_overlap(box, p.box(), GAP_MM - 1e-9) for p in placed):
                continue
            key = (-top, x)
            if best is None or key < best[0]:
                best = (key, box)
        if best is None:
            return None
        box = best[1]
        placed.append(Placed(v, box[0] + dx, box[1], s))
    placed.sort(key=lambda p: views.index(p.view))
    return placed


def place(views: list[View], field, keepout) -> list[Placed]:
    """Place every view (largest common enlargement, then each view grown while it fits); raise
    ValueError if none fits.  A scale asked by the case (``mu_only``) is kept when the views fit
    with it and dropped otherwise."""
    if any(v.mu_only is not None for v in views):
        try:
            return _place(views, field, keepout)
        except ValueError:
            views = [replace(v, mu_only=None) for v in views]
    if any(v.min_s > FACTORS[-1] or v.max_s is not None for v in views):
        try:
            return _place(views, field, keepout)
        except ValueError:     # legible lettering is given up before a view is left out
            views = [replace(v, min_s=FACTORS[-1], max_s=None) for v in views]
    return _place(views, field, keepout)


@dataclass
class Block:
    """Views of one group drawn at one scale as a block, in their order, row by row; each cell
    is its view with a caption strip of ``CAPTION_MM`` above it."""

    view: View                                      # the whole block as one view to place
    cells: list[tuple[View, float, float]]          # member, lower left corner in the block (mm)


CAPTION_MM = 8.0
CELL_GAP_MM = 4.0


def block(key: str, members: list[View], width: float, title_w: float, caption_w: list[float],
          priority: float = 1.0) -> Block:
    """The members in their order, row by row, a row filled while it stays within ``width``
    (at least one member a row); a row as high as its highest member plus the caption strip,
    the members of a row top-aligned under their captions and the rows centred."""
    rows: list[list[int]] = [[]]
    used = 0.0
    cw = [max(v.width, c) for v, c in zip(members, caption_w)]
    for i, w in enumerate(cw):
        if rows[-1] and used + CELL_GAP_MM + w > width + 1e-9:
            rows.append([])
            used = 0.0
        used += (CELL_GAP_MM if rows[-1] else 0.0) + w
        rows[-1].append(i)
    row_w = [sum(cw[i] for i in r) + CELL_GAP_MM * (len(r) - 1) for r in rows]
    W = max(row_w)
    rh = [max(members[i].height for i in r) + CAPTION_MM for r in rows]
    H = sum(rh) + CELL_GAP_MM * (len(rows) - 1)
    cells, top = [], H
    for r, row in enumerate(rows):
        x = (W - row_w[r]) / 2
        for i in row:
            v = members[i]
            cells.append((v, x + (cw[i] - v.width) / 2, top - CAPTION_MM - v.height))
            x += cw[i] + CELL_GAP_MM
        top -= rh[r] + CELL_GAP_MM
    mu = members[0].mu
    return Block(View(key, W, H, mu, title_w=title_w, min_s=members[0].min_s, max_s=members[0].max_s,
                      priority=priority), cells)


def _place(views: list[View], field, keepout) -> list[Placed]:
    for f in FACTORS:
        factors = [allowed_factor(v, f) for v in views]
        out = _try(views, factors, field, keepout)
        if out is not None:
            return _grow(views, factors, out, f, field, keepout)
    raise ValueError("виды не помещаются на листе")


def _grow(views, factors, out, common, field, keepout) -> list[Placed]:
    """Enlarge the views while all of them still fit (see the module doc): each main view first,
    to the largest allowed factor for which the others still fit at no less than ``SHRINK`` of
    the common enlargement; then every view one step at a time, in rounds."""
    def cap(v: View) -> float:
        c = common * GROWTH * v.priority
        if v.mu is None:
            return min(c, MAX_CHART * v.priority)
        # a drawn view may always take the next standard scale above the common enlargement
        return max(c, next_factor(v, common) or c)

    main = sorted((i for i in range(len(views)) if views[i].priority > 1.0), key=lambda i: -views[i].priority)
    fixed: set[int] = set()
    for i in main:
        fixed.add(i)
        ups = [g for g in factors_for(views[i]) if factors[i] + 1e-12 < g <= cap(views[i]) + 1e-12]
        done = False
        for g in ups:                                   # from the largest down
            for f in (f for f in FACTORS if SHRINK * common - 1e-12 <= f <= common + 1e-12):
                trial = [factors[j] if j in fixed else allowed_factor(views[j], f) for j in range(len(views))]
                trial[i] = g
                res = _try(views, trial, field, keepout)
                if res is not None:
                    factors, out, done = trial, res, True
                    break
            if done:
                break

    units: list[list[int]] = []          # a view alone, or all the views of its group
    for i, v in enumerate(views):
        unit = next((u for u in units if v.group is not None and views[u[0]].group == v.group), None)
        if unit is None:
            units.append([i])
        else:
            unit.append(i)

    def step() -> bool:
        nonlocal factors, out
        changed = False
        for unit in units:
            trial = list(factors)
            for i in unit:
                g = next_factor(views[i], factors[i])
                if g is not None and g <= cap(views[i]) + 1e-12:
                    trial[i] = g
            if trial == factors:
                continue
            res = _try(views, trial, field, keepout)
            if res is not None:
                factors, out, changed = trial, res, True
        return changed

    while step():
        pass
    return out
