"""Placing the views of a drawing sheet: standard enlargements, no overlap, clear of the title block.

A view has a natural size in millimetres (the size the note prints it at) and, when it is drawn to
a scale, its scale factor μ (units per millimetre).  On the sheet a view may be enlarged by a factor
s; a drawn-to-scale view only by factors that keep μ/s a standard value (1; 1,5; 2; 2,5; 4; 5 · 10ᵏ,
the series of the note's scenes, which holds the ГОСТ 2.302-68 scales), so the scale written
beside the view stays a round number.  Charts (no μ) may be enlarged by any factor of the series.

Placement is a first-fit, largest view first, on candidate corners (every combination of the
field's edges and the edges of the views already placed), topmost then leftmost, with a gap between
views.  First the largest common enlargement for which every view finds a place is taken; then the
views grow one by one, each to its next allowed factor, while everything still fits: the main views
(priority > 1: the plan of positions, the energy–mass diagram, the group drawings, the cam profile)
first and up to ``priority`` times further than the others, the rest in rounds in their order on the
sheet.  Every step is a fixed sequence of trials, so the placement is deterministic.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

NICE = (1.0, 1.5, 2.0, 2.5, 4.0, 5.0)
FACTORS = (4.0, 3.0, 2.5, 2.0, 1.6, 1.5, 1.25, 1.0, 0.8, 0.75, 0.6, 0.5, 0.4)
GAP_MM = 12.0
GROWTH = 1.6          # a view grows at most GROWTH·priority times beyond the common enlargement
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


def allowed_factor(view: View, target: float) -> float:
    """The largest factor ≤ target that keeps the view's scale standard (any for a chart)."""
    for f in FACTORS:
        if f <= target + 1e-12 and (view.mu is None or is_nice(view.mu / f)):
            return f
    return FACTORS[-1]


def next_factor(view: View, f: float) -> float | None:
    """The smallest factor above ``f`` that keeps the view's scale standard (None at the top)."""
    up = [g for g in FACTORS if g > f + 1e-12 and (view.mu is None or is_nice(view.mu / g))]
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
    ValueError if none fits."""
    for f in FACTORS:
        factors = [allowed_factor(v, f) for v in views]
        out = _try(views, factors, field, keepout)
        if out is not None:
            return _grow(views, factors, out, f, field, keepout)
    raise ValueError("виды не помещаются на листе")


def _grow(views, factors, out, common, field, keepout) -> list[Placed]:
    """Enlarge the views one step at a time while all of them still fit (see the module doc)."""
    def cap(v: View) -> float:
        c = common * GROWTH * v.priority
        return min(c, MAX_CHART * v.priority) if v.mu is None else c

    def step(order) -> bool:
        nonlocal factors, out
        changed = False
        for i in order:
            g = next_factor(views[i], factors[i])
            if g is None or g > cap(views[i]) + 1e-12:
                continue
            trial = list(factors)
            trial[i] = g
            res = _try(views, trial, field, keepout)
            if res is not None:
                factors, out, changed = trial, res, True
        return changed

    main = [i for i in range(len(views)) if views[i].priority > 1.0]
    main.sort(key=lambda i: -views[i].priority)
    while main and step(main):
        pass
    while step(range(len(views))):
        pass
    return out
