"""Whole-cycle kinetostatics of a planar linkage, Assur group by Assur group (numba kernel).

Method (Артоболевский, «Теория механизмов и машин», гл. «Силовой расчёт механизмов»;
Попов–Тимофеев, «Курсовое проектирование…», «Кинетостатический анализ»): by d'Alembert's
principle every link is in equilibrium under the applied loads, its weight, its inertia force
Φ = −m·a_S and inertia moment M_Φ = −J_S·ε, and the reactions of its kinematic pairs.  An
Assur group is statically determinate (3n equations, 3n unknown reaction components), so the
groups are solved one after another from the last attached group to the initial link; each
group's reactions on the links of earlier groups are then known loads.  Per group and position
one small dense linear system (3n × 3n) is solved by Gaussian elimination with partial pivoting
(the analytic kinetostatics of the classical Mathcad course manuals, written generically):

* for every link k of the group, with an arbitrary reference point r_k,
  Σ F = 0 (two rows) and Σ (r_P − r_k) × F + Σ M = 0 (one row);
* unknowns per pair (reaction = action of the pair's first link a on its second link b; b
  receives +R, a receives −R):
  - revolute pair at P: R = (R_x, R_y) at P;
  - prismatic pair (guide a, slider b, guide direction u, normal n = ⊥u): the normal force N·n
    at the slider point P and the reaction moment M_p (its point of application is
    P + (M_p/N)·u, since (t·u) × (N·n) = t·N);
  - the driving prismatic pair of a linear actuator (cylinder a, rod b): the axial (actuator)
    force F·u, the normal force N·n at the rod-end point and the moment M_p;
  - the crank drive: the balancing moment M_ур of the frame on the crank.

Inputs are plain arrays prepared by :mod:`reportgen.analysis.forces`: joint kinds and links,
the groups in the order of solution, and per position the application points, the guide
directions, a reference point of every link and the resultant external load of every link
(F_x, F_y and the moment about its reference point).  One call solves the whole grid.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .linalg import solve_dense

# unknown kinds of a pair
K_REV = 0      # revolute: R_x, R_y
K_PRI = 1      # prismatic: N, M_p
K_ACT = 2      # actuator's driving pair: F, N, M_p
K_MOM = 3      # crank drive: balancing moment

F_OK = 0
F_SINGULAR = 1

SINGULAR_PIVOT = 1e-13


@njit(cache=True)
def n_unknowns(kind):
    """The unknowns of a pair of kind ``kind``: 2 for a revolute (R_x, R_y) or a prismatic pair (N,
    M_p), 3 for an actuator (F, N, M_p), 1 for the driving moment M_ур."""
    if kind == K_REV or kind == K_PRI:
        return 2
    if kind == K_ACT:
        return 3
    return 1


@njit(cache=True)
def _unit(kind, c, ux, uy):
    """Load on the second link of a pair per unit value of its unknown number c:
    (f_x, f_y, pure moment); the force acts at the pair's point."""
    if kind == K_REV:
        if c == 0:
            return 1.0, 0.0, 0.0
        return 0.0, 1.0, 0.0
    if kind == K_PRI:
        if c == 0:
            return -uy, ux, 0.0
        return 0.0, 0.0, 1.0
    if kind == K_ACT:
        if c == 0:
            return ux, uy, 0.0
        if c == 1:
            return -uy, ux, 0.0
        return 0.0, 0.0, 1.0
    return 0.0, 0.0, 1.0


# the same elimination inlined where the size is a constant, so that the compiler unrolls the
# loops of the usual systems (the initial link 3×3, a dyad 6×6): the same operations, the same
# numbers, ~13 % less time over a cycle grid
_solve_inline = njit(inline="always", error_model="numpy")(solve_dense.py_func)


@njit(cache=True, error_model="numpy")
def _solve_sized(mat, rhs, n, tol):
    if n == 6:
        return _solve_inline(mat, rhs, 6, tol)
    if n == 3:
        return _solve_inline(mat, rhs, 3, tol)
    return solve_dense(mat, rhs, n, tol)


@njit(cache=True)
def solve_reactions(jkind, jlink, joff, glink, gnl, gjoint, gnj, jpt, jdir, lref, lext):
    """Reactions of every pair over the grid, group by group.

    jkind (nj) pair kinds K_*; jlink (nj, 2) its links (a, b) as indices into the link arrays
    (0 = frame); joff (nj) offset of its unknowns in the output row; glink/gnl and gjoint/gnj
    the links and the pairs (unknowns) of each group in the order of solution (last attached
    group first); jpt (N, nj, 2) application points; jdir (N, nj, 2) unit guide directions
    (prismatic and actuator pairs); lref (N, nl, 2) reference points of the links; lext
    (N, nl, 3) resultant external load of each link (F_x, F_y, moment about lref).

    Returns (x, quality, fail): x (N, n_unknowns) the unknowns of every pair at joff; quality
    (N, ngroups) the normalised smallest pivot of each group's system; fail = [kind, position,
    group] of the first singular system (kind 0 = none).
    """
    N = jpt.shape[0]
    nj = jkind.shape[0]
    nl = lref.shape[1]
    ng = gnl.shape[0]
    nunk = 0
    for j in range(nj):
        nunk += n_unknowns(jkind[j])
    x = np.zeros((N, nunk))
    quality = np.zeros((N, ng))
    fail = np.zeros(3, dtype=np.int64)
    maxn = 3 * glink.shape[1]
    mat = np.zeros((maxn, maxn))
    rhs = np.zeros(maxn)
    row_of = -np.ones(nl, dtype=np.int64)
    col_of = -np.ones(nj, dtype=np.int64)
    solved = np.zeros(nj, dtype=np.bool_)
    for i in range(N):
        for j in range(nj):
            solved[j] = False
        for g in range(ng):
            nlg = gnl[g]
            n = 3 * nlg
            for r in range(n):
                rhs[r] = 0.0
                for c in range(n):
                    mat[r, c] = 0.0
            for k in range(nlg):
                lk = glink[g, k]
                row_of[lk] = 3 * k
                rhs[3 * k] = -lext[i, lk, 0]
                rhs[3 * k + 1] = -lext[i, lk, 1]
                rhs[3 * k + 2] = -lext[i, lk, 2]
            col = 0
            for m in range(gnj[g]):
                j = gjoint[g, m]
                col_of[j] = col
                col += n_unknowns(jkind[j])
            # every pair touching a link of the group: unknown (matrix) or known (right side)
            for j in range(nj):
                inside = col_of[j] >= 0
                if not inside and not solved[j]:
                    continue
                kind = jkind[j]
                px = jpt[i, j, 0]
                py = jpt[i, j, 1]
                ux = jdir[i, j, 0]
                uy = jdir[i, j, 1]
                for side in range(2):
                    lk = jlink[j, side]
                    r0 = row_of[lk]
                    if r0 < 0:
                        continue
                    sgn = 1.0 if side == 1 else -1.0
                    dx = px - lref[i, lk, 0]
                    dy = py - lref[i, lk, 1]
                    for c in range(n_unknowns(kind)):
                        fx, fy, mz = _unit(kind, c, ux, uy)
                        fx *= sgn
                        fy *= sgn
                        mz = sgn * mz + dx * fy - dy * fx
                        if inside:
                            cc = col_of[j] + c
                            mat[r0, cc] += fx
                            mat[r0 + 1, cc] += fy
                            mat[r0 + 2, cc] += mz
                        else:
                            v = x[i, joff[j] + c]
                            rhs[r0] -= fx * v
                            rhs[r0 + 1] -= fy * v
                            rhs[r0 + 2] -= mz * v
            qual = _solve_sized(mat, rhs, n, SINGULAR_PIVOT)
            quality[i, g] = qual
            if qual == 0.0 and fail[0] == 0:
                fail[0] = F_SINGULAR
                fail[1] = i
                fail[2] = g
            for m in range(gnj[g]):
                j = gjoint[g, m]
                for c in range(n_unknowns(jkind[j])):
                    x[i, joff[j] + c] = rhs[col_of[j] + c] if qual > 0.0 else np.nan
                solved[j] = True
                col_of[j] = -1
            for k in range(nlg):
                row_of[glink[g, k]] = -1
    return x, quality, fail
