"""Small dense linear systems inside numba kernels (the 2×2 … 12×12 systems of Assur groups)."""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, error_model="numpy")
def solve_dense(a, b, n, tol):
    """Gaussian elimination with partial pivoting on the leading n×n block of ``a`` (in place;
    the solution replaces ``b``).

    Returns the smallest |pivot| divided by the largest row norm, a conditioning indicator of
    the system; 0.0 when the matrix is zero or a pivot is ≤ tol·(largest row norm), in which
    case ``b`` is left partly reduced and must not be used."""
    scale = 0.0
    for i in range(n):
        s = 0.0
        for k in range(n):
            s += a[i, k] * a[i, k]
        if s > scale:
            scale = s
    scale = np.sqrt(scale)
    if scale == 0.0:
        return 0.0
    minpiv = 1e300
    for c in range(n):
        p = c
        best = abs(a[c, c])
        for r in range(c + 1, n):
            if abs(a[r, c]) > best:
                best = abs(a[r, c])
                p = r
        if best < minpiv:
            minpiv = best
        if best <= tol * scale or best == 0.0:
            return 0.0
        if p != c:
            for k in range(n):
                t = a[c, k]
                a[c, k] = a[p, k]
                a[p, k] = t
            t = b[c]
            b[c] = b[p]
            b[p] = t
        for r in range(c + 1, n):
            f = a[r, c] / a[c, c]
            if f != 0.0:
                for k in range(c, n):
                    a[r, k] -= f * a[c, k]
                b[r] -= f * b[c]
    for c in range(n - 1, -1, -1):
        s = b[c]
        for k in range(c + 1, n):
            s -= a[c, k] * b[k]
        b[c] = s / a[c, c]
    return minpiv / scale


@njit(cache=True, error_model="numpy")
def lu_factor(a, n, perm):
    """LU factorisation with partial pivoting of the leading n×n block of ``a`` in place
    (multipliers below the diagonal, U on and above it; row interchanges in ``perm``), so that
    one factorisation serves several right-hand sides (the velocity and acceleration systems of
    a group share the matrix Φ_x).

    Returns the smallest |pivot| divided by the largest row norm (0.0 for a singular matrix)."""
    scale = 0.0
    for i in range(n):
        s = 0.0
        for k in range(n):
            s += a[i, k] * a[i, k]
        if s > scale:
            scale = s
    scale = np.sqrt(scale)
    if scale == 0.0:
        return 0.0
    minpiv = 1e300
    for c in range(n):
        p = c
        best = abs(a[c, c])
        for r in range(c + 1, n):
            if abs(a[r, c]) > best:
                best = abs(a[r, c])
                p = r
        perm[c] = p
        if best < minpiv:
            minpiv = best
        if best == 0.0:
            return 0.0
        if p != c:
            for k in range(n):
                t = a[c, k]
                a[c, k] = a[p, k]
                a[p, k] = t
        inv = 1.0 / a[c, c]
        for r in range(c + 1, n):
            f = a[r, c] * inv
            a[r, c] = f
            if f != 0.0:
                for k in range(c + 1, n):
                    a[r, k] -= f * a[c, k]
    return minpiv / scale


@njit(cache=True, error_model="numpy")
def lu_solve(a, perm, b, n):
    """Solve with the factors of :func:`lu_factor` (the solution replaces ``b``)."""
    for c in range(n):
        p = perm[c]
        if p != c:
            t = b[c]
            b[c] = b[p]
            b[p] = t
    for c in range(n):
        f = b[c]
        if f != 0.0:
            for r in range(c + 1, n):
                b[r] -= a[r, c] * f
    for c in range(n - 1, -1, -1):
        s = b[c]
        for k in range(c + 1, n):
            s -= a[c, k] * b[k]
        b[c] = s / a[c, c]
