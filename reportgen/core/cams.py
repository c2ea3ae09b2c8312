"""Laws of follower motion of a cam mechanism over the whole cycle (numba kernels).

A phase of rise (удаление) or return (возвращение) of length β carries a normalised law
f(x), x = φ_ph/β ∈ [0, 1], f(0) = 0, f(1) = 1, f′(0) = f′(1) = 0 (except the uniform law).  The
analogs of the follower displacement are then (Артоболевский И. И., «Теория механизмов и машин»,
гл. 24; Попов С. А., Тимофеев Г. А., «Курсовое проектирование по ТММ», гл. 6)::

    rise:    s = h f,        s′ = h f′/β,   s″ = h f″/β²,   s‴ = h f‴/β³
    return:  s = h (1 − f),  s′ = −h f′/β,  s″ = −h f″/β²,  s‴ = −h f‴/β³

Normalised laws (derivatives in x):

* ``UNIFORM``   f = x (s″ infinite at the ends: hard impacts);
* ``COSINE``    f = (1 − cos πx)/2;
* ``SINE``      the sine (cycloidal) law, asymmetric with the inflection at x₁ = ν/(1 + ν):
  f″ = (π/x₁) sin(πx/x₁) on [0, x₁], f″ = −(π/(1 − x₁)) sin(π(x − x₁)/(1 − x₁)) on [x₁, 1]
  (x₁ = ½ gives f = x − sin 2πx/(2π));
* ``POLY345``   f = 10x³ − 15x⁴ + 6x⁵;
* ``POLY4567``  f = 35x⁴ − 84x⁵ + 70x⁶ − 20x⁷;
* ``PIECEWISE`` the acceleration analog piecewise linear through knots (x_j, a_j), a knot may be
  repeated for a jump; f′ and f are integrated exactly (cubic on each piece).  The parabolic
  (uniform acceleration) law, asymmetric by ν, and the trapezoidal acceleration are of this form.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["DWELL_LOW", "RISE", "DWELL_HIGH", "RETURN", "UNIFORM", "COSINE", "SINE", "POLY345",
           "POLY4567", "PIECEWISE", "law_eval", "cam_cycle", "piecewise_knots"]

# phase kinds
DWELL_LOW = 0
RISE = 1
DWELL_HIGH = 2
RETURN = 3
# law codes
UNIFORM = 1
COSINE = 2
SINE = 3
POLY345 = 4
POLY4567 = 5
PIECEWISE = 6


def piecewise_knots(x, a) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Knots of a piecewise-linear acceleration analog scaled so that f(1) = 1.

    Integrates a(x) exactly piece by piece: v_{j+1} = v_j + (a_j + a_{j+1})Δ/2,
    f_{j+1} = f_j + v_j Δ + (2a_j + a_{j+1})Δ²/6.  Returns (x, a, v, f) after scaling by 1/f(1);
    the caller checks that v(1) = 0 (the velocity analog vanishes at the end of the phase).
    """
    x = np.asarray(x, dtype=float)
    a = np.asarray(a, dtype=float)
    v = np.zeros_like(x)
    f = np.zeros_like(x)
    for j in range(len(x) - 1):
        d = x[j + 1] - x[j]
        v[j + 1] = v[j] + 0.5 * (a[j] + a[j + 1]) * d
        f[j + 1] = f[j] + v[j] * d + (2.0 * a[j] + a[j + 1]) * d * d / 6.0
    k = 1.0 / f[-1] if f[-1] != 0.0 else 0.0
    return x, a * k, v * k, f * k


@njit(cache=True)
def law_eval(code, x, x1, kx, ka, kv, kf, side):
    """Normalised law f, f′, f″, f‴ at x ∈ [0, 1]; at a knot of a piecewise law ``side`` < 0 takes
    the piece on the left (left limits), otherwise the piece on the right."""
    pi = math.pi
    if code == UNIFORM:
        return x, 1.0, 0.0, 0.0
    if code == COSINE:
        return (0.5 * (1.0 - math.cos(pi * x)), 0.5 * pi * math.sin(pi * x),
                0.5 * pi * pi * math.cos(pi * x), -0.5 * pi ** 3 * math.sin(pi * x))
    if code == SINE:
        if x < x1 or (x == x1 and side < 0):
            w = pi / x1
            A = pi / x1
            return (A * x1 / pi * (x - math.sin(w * x) / w), A * x1 / pi * (1.0 - math.cos(w * x)),
                    A * math.sin(w * x), A * w * math.cos(w * x))
        L = 1.0 - x1
        w = pi / L
        A = pi / L
        d = x - x1
        V = 2.0  # the velocity analog at the inflection: 2A₁x₁/π
        F1 = x1  # f(x₁) = A₁x₁²/π
        return (F1 + V * d - A * L / pi * (d - math.sin(w * d) / w), V - A * L / pi * (1.0 - math.cos(w * d)),
                -A * math.sin(w * d), -A * w * math.cos(w * d))
    if code == POLY345:
        x2 = x * x
        return (x2 * x * (10.0 - 15.0 * x + 6.0 * x2), x2 * (30.0 - 60.0 * x + 30.0 * x2),
                x * (60.0 - 180.0 * x + 120.0 * x2), 60.0 - 360.0 * x + 360.0 * x2)
    if code == POLY4567:
        x2 = x * x
        x3 = x2 * x
        return (x3 * x * (35.0 - 84.0 * x + 70.0 * x2 - 20.0 * x3),
                x3 * (140.0 - 420.0 * x + 420.0 * x2 - 140.0 * x3),
                x2 * (420.0 - 1680.0 * x + 2100.0 * x2 - 840.0 * x3),
                x * (840.0 - 5040.0 * x + 8400.0 * x2 - 4200.0 * x3))
    # PIECEWISE
    n = kx.shape[0]
    j = 0
    if side < 0:
        while j < n - 2 and not (x <= kx[j + 1] and kx[j + 1] > kx[j]):
            j += 1
    else:
        while j < n - 2 and not (x < kx[j + 1]):
            j += 1
        while j > 0 and kx[j + 1] == kx[j]:
            j -= 1
    dx = kx[j + 1] - kx[j]
    m = (ka[j + 1] - ka[j]) / dx if dx > 0.0 else 0.0
    d = x - kx[j]
    return (kf[j] + kv[j] * d + 0.5 * ka[j] * d * d + m * d * d * d / 6.0,
            kv[j] + ka[j] * d + 0.5 * m * d * d, ka[j] + m * d, m)


@njit(cache=True)
def cam_cycle(phi, starts, lengths, kinds, codes, x1s, koff, kx, ka, kv, kf, h, side):
    """s, s′, s″, s‴ over the cycle at the cam angles ``phi`` (rad, from the start of the first
    phase).  Phase i spans [starts[i], starts[i] + lengths[i]); its knots (piecewise law) are
    kx[koff[i]:koff[i+1]] …  ``h`` is the stroke (m) or the swing (rad).  A point on a phase
    boundary belongs to the next phase (right limits) unless ``side`` < 0."""
    n = phi.shape[0]
    s = np.zeros(n)
    s1 = np.zeros(n)
    s2 = np.zeros(n)
    s3 = np.zeros(n)
    npb = starts.shape[0]
    for i in range(n):
        p = phi[i]
        k = npb - 1
        for j in range(npb):
            hi = starts[j] + lengths[j]
            if (side >= 0 and p < hi) or (side < 0 and p <= hi):
                k = j
                break
        while k > 0 and lengths[k] <= 0.0:
            k -= 1
        b = lengths[k]
        if kinds[k] == DWELL_LOW or b <= 0.0:
            continue
        if kinds[k] == DWELL_HIGH:
            s[i] = h
            continue
        x = (p - starts[k]) / b
        x = min(max(x, 0.0), 1.0)
        a, o = koff[k], koff[k + 1]
        f, f1, f2, f3 = law_eval(codes[k], x, x1s[k], kx[a:o], ka[a:o], kv[a:o], kf[a:o], side)
        sg = 1.0
        if kinds[k] == RETURN:
            f = f - 1.0
            sg = -1.0
        s[i] = sg * h * f
        s1[i] = sg * h * f1 / b
        s2[i] = sg * h * f2 / (b * b)
        s3[i] = sg * h * f3 / (b * b * b)
    return s, s1, s2, s3
