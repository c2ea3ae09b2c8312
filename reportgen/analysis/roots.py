"""Brent's root finding of a Python function, as SciPy's ``scipy.optimize.brentq`` computes it.

Brent, R. P. «Algorithms for Minimization without Derivatives», Prentice-Hall, 1973, ch. 4:
inverse quadratic interpolation or the secant step where it stays well inside the bracket,
bisection otherwise. The iteration is the one of SciPy's C routine
(``scipy/optimize/Zeros/brentq.c``, BSD licence) step for step, as the project's compiled
transcription in :func:`reportgen.core.extremum.cell_roots` is: the same iterates, so the same
root to the last bit for the same function values (tests/test_sections_speed.py compares it
with SciPy's on many functions and brackets). It exists so that importing the analysis does not
import ``scipy.optimize`` (about 0,3 s of CPU — a quarter of ``reportgen export``'s imports —
for the few roots a linkage's note needs: the extreme positions, the loads' switching points).

The checks of SciPy's wrapper are kept: ``xtol`` > 0, ``rtol`` ≥ 4ε, a NaN value of ``f`` is a
``ValueError``, a bracket without a sign change a ``ValueError``, no convergence in ``maxiter``
iterations a ``RuntimeError``.
"""
from __future__ import annotations

import math

_EPS = 2.220446049250313e-16
_RTOL = 4 * _EPS


def brentq(f, a: float, b: float, xtol: float = 2e-12, rtol: float = _RTOL, maxiter: int = 100) -> float:
    """A root of ``f`` in [a, b] (f(a)·f(b) ≤ 0) to ``xtol + rtol·|x|``, as SciPy's ``brentq``."""
    if xtol <= 0:
        raise ValueError(f"xtol too small ({xtol:g} <= 0)")
    if rtol < _RTOL:
        raise ValueError(f"rtol too small ({rtol:g} < {_RTOL:g})")

    def value(x: float) -> float:
        fx = float(f(x))
        if math.isnan(fx):
            raise ValueError(f"The function value at x={x:f} is NaN; solver cannot continue.")
        return fx

    xpre, xcur = float(a), float(b)
    xblk = fblk = spre = scur = 0.0
    fpre, fcur = value(xpre), value(xcur)
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    if (fpre < 0) == (fcur < 0):
        raise ValueError("f(a) and f(b) must have different signs")
    for _ in range(maxiter):
        if fpre != 0 and fcur != 0 and (fpre < 0) != (fcur < 0):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:        # interpolate
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:                   # extrapolate
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre, scur = scur, stry         # good short step
            else:
                spre = scur = sbis              # bisect
        else:
            spre = scur = sbis                  # bisect
        xpre, fpre = xcur, fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0 else -delta
        fcur = value(xcur)
    raise RuntimeError(f"Failed to converge after {maxiter} iterations, value is {xcur}")
