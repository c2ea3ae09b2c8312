"""Small dense linear systems inside numba kernels (the 2×2 … 12×12 systems of Assur groups)."""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, error_model="numpy")
def _largest_row_norm(a, n):
    """max over the rows i < n of the Euclidean norm of a[i, :n] (the scale of the pivot test)."""
    scale = 0.0
    for i in range(n):
        s = 0.0
        for k in range(n):
            s += a[i, k] * a[i, k]
        if s > scale:
            scale = s
    return np.sqrt(scale)


@njit(cache=True, error_model="numpy")
def _pivot_row(a, c, n):
    """Partial pivoting: the row p ≥ c with the largest |a[p, c]| (the first of equals) and that value."""
    p = c
    best = abs(a[c, c])
    for r in range(c + 1, n):
        if abs(a[r, c]) > best:
            best = abs(a[r, c])
            p = r
    return p, best


@njit(cache=True, error_model="numpy")
def _swap_rows(a, c, p, n):
    for k in range(n):
        t = a[c, k]
        a[c, k] = a[p, k]
        a[p, k] = t


@njit(cache=True, error_model="numpy")
def _back_substitute(a, b, n):
    """Solve U·x = b for the upper triangle U of a[:n, :n] (x replaces ``b``)."""
    for c in range(n - 1, -1, -1):
        s = b[c]
        for k in range(c + 1, n):
            s -= a[c, k] * b[k]
        b[c] = s / a[c, c]


@njit(cache=True, error_model="numpy")
def solve_dense(a, b, n, tol):
    """Gaussian elimination with partial pivoting on the leading n×n block of ``a`` (in place;
    the solution replaces ``b``).

    Returns the smallest |pivot| divided by the largest row norm, a conditioning indicator of
    the system; 0.0 when the matrix is zero or a pivot is ≤ tol·(largest row norm), in which
    case ``b`` is left partly reduced and must not be used."""
    scale = _largest_row_norm(a, n)
    if scale == 0.0:
        return 0.0
    minpiv = 1e300
    for c in range(n):
        p, best = _pivot_row(a, c, n)
        if best < minpiv:
            minpiv = best
        if best <= tol * scale or best == 0.0:
            return 0.0
        if p != c:
            _swap_rows(a, c, p, n)
            t = b[c]
            b[c] = b[p]
            b[p] = t
        for r in range(c + 1, n):
            f = a[r, c] / a[c, c]
            if f != 0.0:
                for k in range(c, n):
                    a[r, k] -= f * a[c, k]
                b[r] -= f * b[c]
    _back_substitute(a, b, n)
    return minpiv / scale


@njit(cache=True, error_model="numpy")
def lu_factor(a, n, perm):
    """LU factorisation with partial pivoting of the leading n×n block of ``a`` in place
    (multipliers below the diagonal, U on and above it; row interchanges in ``perm``), so that
    one factorisation serves several right-hand sides (the velocity and acceleration systems of
    a group share the matrix Φ_x).

    Returns the smallest |pivot| divided by the largest row norm (0.0 for a singular matrix)."""
    scale = _largest_row_norm(a, n)
    if scale == 0.0:
        return 0.0
    minpiv = 1e300
    for c in range(n):
        p, best = _pivot_row(a, c, n)
        perm[c] = p
        if best < minpiv:
            minpiv = best
        if best == 0.0:
            return 0.0
        if p != c:
            _swap_rows(a, c, p, n)
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
    _back_substitute(a, b, n)
