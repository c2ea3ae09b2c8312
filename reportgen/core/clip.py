"""Numba kernels of the label placer's clipping (``scenes.labels._Segs``): how many drawn
segments meet a rectangle (Liang–Barsky clipping, Foley, van Dam et al., «Computer Graphics»,
§ 3.12.4) and how many a leader line crosses (the sign test of the two segments' ends).

The placer asks these questions some thousands of times per figure with a different rectangle
each time; done with NumPy each question cost some fifteen array operations on a few hundred
rows, most of a label's placing. Here one pass over the segments that can reach the rectangle
does the same arithmetic, operation for operation, as the NumPy and Python forms
(``labels._meets``, ``labels._crossings_few``, ``labels._Segs.cuts`` before these kernels), so
the counts are the same (tests/test_sections_speed.py checks them on random segments with
vertical, horizontal, degenerate and non-finite ones). No ``fastmath``: no operation is
reordered or fused.

The segments are given as the placer indexes them: ``short`` — finite segments at most
``short_px`` wide, sorted by their left end (``short_x``: those left ends), so the ones that can
reach a rectangle are one slice found by bisection; ``rest`` — the others, always tested, with
``rest_odd`` marking those with a non-finite end (never passed over by their bounding box, as
the NumPy form never did).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

PAR = 1e-12    # |p| below this: the segment is parallel to that edge (as labels._meets)


@njit(cache=True, error_model="numpy")
def _edge(k, sx, sy, dx, dy, x0, y0, x1, y1):
    """Liang–Barsky's (p, q) of edge ``k``: left, right, bottom, top (the order of labels._meets)."""
    if k == 0:
        return -dx, sx - x0
    if k == 1:
        return dx, x1 - sx
    if k == 2:
        return -dy, sy - y0
    return dy, y1 - sy


@njit(cache=True, error_model="numpy")
def _lb_finite(sx, sy, ex, ey, x0, y0, x1, y1):
    """Liang–Barsky for a finite segment, as ``labels._crossings_few`` (max/min of floats)."""
    dx = ex - sx
    dy = ey - sy
    t0 = 0.0
    t1 = 1.0
    for k in range(4):
        p, q = _edge(k, sx, sy, dx, dy, x0, y0, x1, y1)
        if abs(p) < PAR:
            if q < 0:
                return False
        elif p < 0:
            r = q / p
            if r > t0:
                t0 = r
        else:
            r = q / p
            if r < t1:
                t1 = r
    return t0 <= t1


@njit(cache=True, error_model="numpy")
def _lb_any(sx, sy, ex, ey, x0, y0, x1, y1):
    """Liang–Barsky as ``labels._meets`` computes it element by element (NaN propagates through
    NumPy's maximum and minimum): for a segment with a non-finite end."""
    dx = ex - sx
    dy = ey - sy
    t0 = 0.0
    t1 = 1.0
    ok = True
    for k in range(4):
        p, q = _edge(k, sx, sy, dx, dy, x0, y0, x1, y1)
        par = abs(p) < PAR
        if par and q < 0:
            ok = False
        if not par:
            r = q / p
            if p < 0:
                t0 = math.nan if math.isnan(t0) or math.isnan(r) else max(t0, r)
            elif p > 0:
                t1 = math.nan if math.isnan(t1) or math.isnan(r) else min(t1, r)
    return ok and t0 <= t1


@njit(cache=True, error_model="numpy")
def _slice(short_x, lo_x, hi_x):
    lo = np.searchsorted(short_x, lo_x, side="left")
    hi = np.searchsorted(short_x, hi_x, side="right")
    return lo, hi


@njit(cache=True, error_model="numpy")
def crossings(short, short_x, short_px, rest, rest_odd, x0, y0, x1, y1):
    """How many segments meet the rectangle [x0, x1] × [y0, y1] (already padded)."""
    n = 0
    lo, hi = _slice(short_x, x0 - short_px, x1)
    for i in range(lo, hi):
        sx, sy, ex, ey = short[i, 0], short[i, 1], short[i, 2], short[i, 3]
        if max(sx, ex) >= x0 and min(sx, ex) <= x1 and max(sy, ey) >= y0 and min(sy, ey) <= y1:
            n += _lb_finite(sx, sy, ex, ey, x0, y0, x1, y1)
    for i in range(rest.shape[0]):
        sx, sy, ex, ey = rest[i, 0], rest[i, 1], rest[i, 2], rest[i, 3]
        if rest_odd[i]:
            n += _lb_any(sx, sy, ex, ey, x0, y0, x1, y1)
        elif max(sx, ex) >= x0 and min(sx, ex) <= x1 and max(sy, ey) >= y0 and min(sy, ey) <= y1:
            n += _lb_finite(sx, sy, ex, ey, x0, y0, x1, y1)
    return n


@njit(cache=True, error_model="numpy")
def _cut(s, i, ax_, ay_, bx_, by_, x0, y0, x1, y1):
    sx, sy, ex, ey = s[i, 0], s[i, 1], s[i, 2], s[i, 3]
    if not (max(sx, ex) >= x0 and min(sx, ex) <= x1 and max(sy, ey) >= y0 and min(sy, ey) <= y1):
        return False
    dx = bx_ - ax_
    dy = by_ - ay_
    s1 = dx * (sy - ay_) - dy * (sx - ax_)
    s2 = dx * (ey - ay_) - dy * (ex - ax_)
    gx = ex - sx
    gy = ey - sy
    t1 = gx * (ay_ - sy) - gy * (ax_ - sx)
    t2 = gx * (by_ - sy) - gy * (bx_ - sx)
    return s1 * s2 <= 0 and t1 * t2 <= 0


@njit(cache=True, error_model="numpy")
def cuts(short, short_x, short_px, rest, rest_odd, ax_, ay_, bx_, by_):
    """How many finite segments the segment (ax_, ay_)–(bx_, by_) crosses (a leader line)."""
    x0, x1 = min(ax_, bx_), max(ax_, bx_)
    y0, y1 = min(ay_, by_), max(ay_, by_)
    n = 0
    lo, hi = _slice(short_x, x0 - short_px, x1)
    for i in range(lo, hi):
        n += _cut(short, i, ax_, ay_, bx_, by_, x0, y0, x1, y1)
    for i in range(rest.shape[0]):
        if not rest_odd[i]:
            n += _cut(rest, i, ax_, ay_, bx_, by_, x0, y0, x1, y1)
    return n


def warm() -> None:
    """Compile (or load) both kernels for the argument types ``labels._Segs`` passes, so that
    the first note after setup does not compile them in each of its section workers."""
    segs, xs, odd = np.zeros((0, 4)), np.zeros(0), np.zeros(0, dtype=np.bool_)
    crossings(segs, xs, 24.0, segs, odd, 0.0, 0.0, 1.0, 1.0)
    cuts(segs, xs, 24.0, segs, odd, 0.0, 0.0, 1.0, 1.0)
