"""Whole-cycle kinematics of a planar linkage solved group by group (numba kernels).

Model (multibody pose coordinates, e.g. Haug, *Computer-Aided Kinematics and Dynamics of
Mechanical Systems*, ch. 3; Nikravesh, *Planar Multibody Dynamics*, ch. 2-4): every body k has
a pose (x_k, y_k, θ_k) of its local frame; a local point p maps to r_k + A(θ_k) p.
Constraints, all written as Φ(x, q) = 0 with q the generalised coordinate:

* revolute joint (bodies i, j, local points p_i, p_j that may depend on q affinely,
  p = p0 + q p1, which models a linear actuator of length q):
  ``r_i + A_i p_i − r_j − A_j p_j = 0``;
* prismatic joint (guide i with line point g and direction α in its local frame, slider j with
  point s and offset e): ``θ_j − θ_i − α = 0`` and ``n·(r_j + A_j s − r_i − A_i g) − e = 0`` with
  ``n = A_i (−sin α, cos α)``;
* driving rotation: ``θ_j − θ_i − (c0 + c1 q) = 0``.

Positions of the Assur groups of class II are solved in closed form (circle–circle,
circle–line, the rotating-guide equation of the ВПВ group, and a linear solve once every angle
of the group is known: ПВП, ВПП and the initial link); any other group by Newton with the
analytic Jacobian and a second-order predictor.  The first and second analogs (d/dq, d²/dq²)
of every group come from the group's own linear system ``Φ_x x' = −Φ_q`` and
``Φ_x x'' = −γ`` (exact, no differences), one LU factorisation for both.

This is the general kernel: mechanisms made only of the initial link and ВВВ, ВВП, ВПВ dyads
run on the closed-form tape of :mod:`.tape`, which hands a grid over to this kernel when a
position is near a singular one.

The kernels take the whole grid of q at once (one call per cycle) and are compiled with
``cache=True``.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .linalg import lu_factor, lu_solve, solve_dense

# joint kinds
J_REV = 0
J_PRI = 1
J_DRV = 2
# group kinds
G_LIN = 0      # every angle known from angle constraints, positions by a linear solve
G_RRR = 1      # ВВВ: circle–circle
G_RRP = 2      # ВВП: circle–line
G_RPR = 3      # ВПВ: rotating guide
G_NEWTON = 4   # anything else (class III and higher)

# group forms (gspec[g, 5]): a dyad or the initial link (a revolute and the drive) run on the
# closed-form tape (core/tape.py); in this general kernel every group's analogs come from its
# dense system, the initial link's position in closed form; A_DENSE keeps a group off the tape
A_DENSE = 0
A_DYAD = 1
A_SINGLE = 2

# failure kinds reported by the kernel
F_OK = 0
F_ASSEMBLY = 1
F_NEWTON = 2
F_SINGULAR = 3
F_JUMP = 4          # internal: Newton's correction too large against the predicted step

JUMP_RATIO = 0.5    # allowed Newton correction relative to the predicted step (branch tracking)
JUMP_ABS = 1e-9     # … plus this fraction of the size of the mechanism
MAX_HALVINGS = 8
HOMOTOPY_STEPS = 64  # steps of the continuation from the sketch at the first assembly

CLAMP = 2e-9        # relative tolerance for a stretched/folded group (rounding, not failure)
NEWTON_TOL = 1e-12  # residual tolerance relative to the size of the mechanism
NEWTON_MAXIT = 30


@njit(cache=True, error_model="numpy")
def _rot(th, px, py):
    c = np.cos(th)
    s = np.sin(th)
    return c * px - s * py, s * px + c * py


@njit(cache=True, error_model="numpy")
def _local(jf, j, which, q):
    """Local point of revolute joint j on its first (which=0) or second (which=1) body at q."""
    if which == 0:
        return jf[j, 0] + q * jf[j, 4], jf[j, 1] + q * jf[j, 5]
    return jf[j, 2] + q * jf[j, 6], jf[j, 3] + q * jf[j, 7]


@njit(cache=True, error_model="numpy")
def _pri(jf, j, q):
    """Guide line point g (on the guide body) and slider point s (on the slider body) of a
    prismatic joint at q (both may move with q when they belong to an actuator's rod)."""
    return (jf[j, 0] + q * jf[j, 6], jf[j, 1] + q * jf[j, 7],
            jf[j, 2] + q * jf[j, 8], jf[j, 3] + q * jf[j, 9])


@njit(cache=True, error_model="numpy")
def _place(pose, b, th, Px, Py, px, py):
    """Pose of body b turned by θ so that its local point p lies at the global point P:
    r = P − A(θ)·p (A: the rotation matrix)."""
    pose[b, 2] = th
    ux, uy = _rot(th, px, py)
    pose[b, 0] = Px - ux
    pose[b, 1] = Py - uy


@njit(cache=True, error_model="numpy")
def _glob(pose, b, px, py):
    ux, uy = _rot(pose[b, 2], px, py)
    return pose[b, 0] + ux, pose[b, 1] + uy


@njit(cache=True, error_model="numpy")
def _rcs(c, s, px, py):
    return c * px - s * py, s * px + c * py


@njit(cache=True, error_model="numpy")
def _joint_rows(jt, jb, jf, j, q, pose, vel, coef, expl, gam, with_gamma, cs):
    """Rows of joint j: Jacobian blocks (coef[row, 0:3] body i, coef[row, 3:6] body j),
    explicit ∂Φ/∂q and the acceleration term γ (second derivative without x'' terms);
    cs[b] = (cos θ_b, sin θ_b) of the current poses.

    Returns the number of rows (2 for revolute and prismatic, 1 for a drive)."""
    bi = jb[j, 0]
    bj = jb[j, 1]
    wi = vel[bi, 2]
    wj = vel[bj, 2]
    for r in range(2):
        for k in range(6):
            coef[r, k] = 0.0
        expl[r] = 0.0
        gam[r] = 0.0
    kind = jt[j]
    if kind == J_REV:
        ci = cs[bi, 0]
        si = cs[bi, 1]
        cj = cs[bj, 0]
        sj = cs[bj, 1]
        pix, piy = _local(jf, j, 0, q)
        pjx, pjy = _local(jf, j, 1, q)
        uix, uiy = _rcs(ci, si, pix, piy)
        ujx, ujy = _rcs(cj, sj, pjx, pjy)
        vix, viy = _rcs(ci, si, jf[j, 4], jf[j, 5])
        vjx, vjy = _rcs(cj, sj, jf[j, 6], jf[j, 7])
        coef[0, 0] = 1.0
        coef[0, 2] = -uiy
        coef[1, 1] = 1.0
        coef[1, 2] = uix
        coef[0, 3] = -1.0
        coef[0, 5] = ujy
        coef[1, 4] = -1.0
        coef[1, 5] = -ujx
        expl[0] = vix - vjx
        expl[1] = viy - vjy
        if with_gamma:
            gam[0] = -uix * wi * wi + 2.0 * (-viy) * wi - (-ujx * wj * wj + 2.0 * (-vjy) * wj)
            gam[1] = -uiy * wi * wi + 2.0 * vix * wi - (-ujy * wj * wj + 2.0 * vjx * wj)
        return 2
    elif kind == J_PRI:
        ci = cs[bi, 0]
        si = cs[bi, 1]
        cj = cs[bj, 0]
        sj = cs[bj, 1]
        gx, gy, sx, sy = _pri(jf, j, q)
        al = jf[j, 4]
        nx, ny = _rcs(ci, si, -np.sin(al), np.cos(al))
        agx, agy = _rcs(ci, si, gx, gy)
        asx, asy = _rcs(cj, sj, sx, sy)
        g1x, g1y = _rcs(ci, si, jf[j, 6], jf[j, 7])
        s1x, s1y = _rcs(cj, sj, jf[j, 8], jf[j, 9])
        dx = pose[bj, 0] + asx - pose[bi, 0] - agx
        dy = pose[bj, 1] + asy - pose[bi, 1] - agy
        # row 0: relative angle
        coef[0, 2] = -1.0
        coef[0, 5] = 1.0
        # row 1: offset from the guide line
        coef[1, 3] = nx
        coef[1, 4] = ny
        coef[1, 5] = nx * (-asy) + ny * asx
        pnx = -ny
        pny = nx
        coef[1, 0] = -nx
        coef[1, 1] = -ny
        coef[1, 2] = pnx * dx + pny * dy - (nx * (-agy) + ny * agx)
        expl[1] = nx * (s1x - g1x) + ny * (s1y - g1y)
        if with_gamma:
            ddx = vel[bj, 0] + (-asy) * wj + s1x - vel[bi, 0] - (-agy) * wi - g1x
            ddy = vel[bj, 1] + asx * wj + s1y - vel[bi, 1] - agx * wi - g1y
            gam[1] = (-(nx * dx + ny * dy) * wi * wi + 2.0 * (pnx * ddx + pny * ddy) * wi
                      + nx * (-asx * wj * wj + agx * wi * wi) + ny * (-asy * wj * wj + agy * wi * wi)
                      + 2.0 * (nx * (-s1y * wj + g1y * wi) + ny * (s1x * wj - g1x * wi)))
        return 2
    else:
        coef[0, 2] = -1.0
        coef[0, 5] = 1.0
        expl[0] = -jf[j, 1]
        return 1


@njit(cache=True, error_model="numpy")
def _joint_residual(jt, jb, jf, j, q, pose, res):
    bi = jb[j, 0]
    bj = jb[j, 1]
    kind = jt[j]
    if kind == J_REV:
        pix, piy = _local(jf, j, 0, q)
        pjx, pjy = _local(jf, j, 1, q)
        ax, ay = _glob(pose, bi, pix, piy)
        bx, by = _glob(pose, bj, pjx, pjy)
        res[0] = ax - bx
        res[1] = ay - by
        return 2
    elif kind == J_PRI:
        al = jf[j, 4]
        ti = pose[bi, 2]
        nx, ny = _rot(ti, -np.sin(al), np.cos(al))
        lgx, lgy, lsx, lsy = _pri(jf, j, q)
        gx, gy = _glob(pose, bi, lgx, lgy)
        sx, sy = _glob(pose, bj, lsx, lsy)
        d = pose[bj, 2] - ti - al
        res[0] = np.arctan2(np.sin(d), np.cos(d))
        res[1] = nx * (sx - gx) + ny * (sy - gy) - jf[j, 5]
        return 2
    else:
        d = pose[bj, 2] - pose[bi, 2] - jf[j, 0] - jf[j, 1] * q
        res[0] = np.arctan2(np.sin(d), np.cos(d))
        return 1


@njit(cache=True, error_model="numpy")
def _refresh_cs(cs, pose, gb, nbg):
    for k in range(nbg):
        b = gb[k]
        cs[b, 0] = np.cos(pose[b, 2])
        cs[b, 1] = np.sin(pose[b, 2])


@njit(cache=True, error_model="numpy")
def _group_matrix(jt, jb, jf, gj, nj, gb, nbg, q, pose, d1, d2, level, mat, rhs, col_of,
                  coef, expl, gam, res, with_mat, cs):
    """Assemble the group's linear system at velocity (level=1) or acceleration (level=2)
    level, or the Newton Jacobian with the residual as right-hand side (level=0); with
    ``with_mat`` False only the right-hand side (the matrix Φ_x is the same at both levels).

    col_of[b] is the column block of body b in the group or −1 for a known body; coef, expl,
    gam, res are the caller's scratch arrays (no allocation per position); cs[b] holds
    (cos θ_b, sin θ_b), refreshed here for the group's bodies at the Newton level (level 0) and
    by the caller once the positions are solved otherwise."""
    n = 3 * nbg
    if level == 0:
        _refresh_cs(cs, pose, gb, nbg)
    for r in range(n):
        rhs[r] = 0.0
        if with_mat:
            for c in range(n):
                mat[r, c] = 0.0
    row = 0
    for k in range(nj):
        j = gj[k]
        nr = _joint_rows(jt, jb, jf, j, q, pose, d1, coef, expl, gam, level == 2, cs)
        if level == 0:
            _joint_residual(jt, jb, jf, j, q, pose, res)
        for r in range(nr):
            s = 0.0
            for side in range(2):
                b = jb[j, side]
                cb = col_of[b]
                for c in range(3):
                    a = coef[r, 3 * side + c]
                    if cb >= 0:
                        if with_mat:
                            mat[row + r, 3 * cb + c] += a
                    elif level == 1:
                        s += a * d1[b, c]
                    elif level == 2:
                        s += a * d2[b, c]
            if level == 0:
                rhs[row + r] = -res[r]
            elif level == 1:
                rhs[row + r] = -(s + expl[r])
            else:
                rhs[row + r] = -(s + gam[r])
        row += nr
    return row


@njit(cache=True, error_model="numpy")
def _pivot(jf, jb, j, body, q, pose):
    """For revolute joint j attaching ``body`` to an already solved body: the joint's local
    point on ``body`` and its global position (from the solved side)."""
    if jb[j, 0] == body:
        px, py = _local(jf, j, 0, q)
        kx, ky = _local(jf, j, 1, q)
        gx, gy = _glob(pose, jb[j, 1], kx, ky)
    else:
        px, py = _local(jf, j, 1, q)
        kx, ky = _local(jf, j, 0, q)
        gx, gy = _glob(pose, jb[j, 0], kx, ky)
    return px, py, gx, gy


@njit(cache=True, error_model="numpy")
def _inner(jf, jb, j, a, q):
    """Local points of the inner revolute joint j on body a and on the other body."""
    if jb[j, 0] == a:
        ax, ay = _local(jf, j, 0, q)
        bx, by = _local(jf, j, 1, q)
    else:
        ax, ay = _local(jf, j, 1, q)
        bx, by = _local(jf, j, 0, q)
    return ax, ay, bx, by


@njit(cache=True, error_model="numpy")
def _solve_rrr(jf, jb, a, b, jA, jB, jC, sigma, q, pose):
    """ВВВ group: bodies a, b; joint jA (a–known), jB (a–b), jC (b–known)."""
    pax, pay, Ax, Ay = _pivot(jf, jb, jA, a, q, pose)
    pcx, pcy, Cx, Cy = _pivot(jf, jb, jC, b, q, pose)
    pbax, pbay, pbbx, pbby = _inner(jf, jb, jB, a, q)
    La = np.hypot(pbax - pax, pbay - pay)
    Lb = np.hypot(pbbx - pcx, pbby - pcy)
    dx = Cx - Ax
    dy = Cy - Ay
    D = np.hypot(dx, dy)
    if D == 0.0:
        return F_ASSEMBLY, abs(La - Lb), 0.0
    x = (La * La - Lb * Lb + D * D) / (2.0 * D)
    h2 = La * La - x * x
    if h2 < 0.0:
        if h2 < -CLAMP * La * La:
            if D > La + Lb:
                return F_ASSEMBLY, D - (La + Lb), 0.0
            return F_ASSEMBLY, abs(La - Lb) - D, 0.0
        h2 = 0.0
    h = np.sqrt(h2)
    ex = dx / D
    ey = dy / D
    Bx = Ax + x * ex - sigma * h * ey
    By = Ay + x * ey + sigma * h * ex
    ta = np.arctan2(By - Ay, Bx - Ax) - np.arctan2(pbay - pay, pbax - pax)
    tb = np.arctan2(By - Cy, Bx - Cx) - np.arctan2(pbby - pcy, pbbx - pcx)
    _place(pose, a, ta, Ax, Ay, pax, pay)
    _place(pose, b, tb, Cx, Cy, pcx, pcy)
    # sine of the angle between the two links at the inner joint (transmission quality)
    sinmu = ((Bx - Ax) * (By - Cy) - (By - Ay) * (Bx - Cx)) / (La * Lb) if La * Lb > 0 else 0.0
    return F_OK, 0.0, sinmu


@njit(cache=True, error_model="numpy")
def _line_of_body(jf, jb, jP, b, q, pose):
    """A body b whose angle is already known and that is tied by prismatic joint jP to a known
    body can only translate along the guide: r_b = r0 + t·u.  Returns (r0x, r0y, ux, uy)."""
    lgx, lgy, lsx, lsy = _pri(jf, jP, q)
    gi = jb[jP, 0]
    sj = jb[jP, 1]
    al = jf[jP, 4]
    e = jf[jP, 5]
    if sj == b:
        # b is the slider on a known guide gi
        ti = pose[gi, 2]
        nx, ny = _rot(ti, -np.sin(al), np.cos(al))
        ux, uy = _rot(ti, np.cos(al), np.sin(al))
        Gx, Gy = _glob(pose, gi, lgx, lgy)
        sx, sy = _rot(pose[b, 2], lsx, lsy)
        return Gx + e * nx - sx, Gy + e * ny - sy, ux, uy
    # b is the guide, the known body sj carries the slider point
    tb = pose[b, 2]
    nx, ny = _rot(tb, -np.sin(al), np.cos(al))
    ux, uy = _rot(tb, np.cos(al), np.sin(al))
    Sx, Sy = _glob(pose, sj, lsx, lsy)
    gx, gy = _rot(tb, lgx, lgy)
    return Sx - gx - e * nx, Sy - gy - e * ny, ux, uy


@njit(cache=True, error_model="numpy")
def _angle_from_prismatic(jf, jb, jP, b, pose):
    al = jf[jP, 4]
    if jb[jP, 1] == b:
        return pose[jb[jP, 0], 2] + al
    return pose[jb[jP, 1], 2] - al


@njit(cache=True, error_model="numpy")
def _solve_rrp(jf, jb, a, b, jA, jB, jP, sigma, q, pose):
    """ВВП group: body a (revolute jA to a known body, revolute jB to b), body b (prismatic jP
    to a known body).  Circle (centre A, radius |AB| on a) meets the line traced by B."""
    pose[b, 2] = _angle_from_prismatic(jf, jb, jP, b, pose)
    pax, pay, Ax, Ay = _pivot(jf, jb, jA, a, q, pose)
    pbax, pbay, pbbx, pbby = _inner(jf, jb, jB, a, q)
    La = np.hypot(pbax - pax, pbay - pay)
    r0x, r0y, ux, uy = _line_of_body(jf, jb, jP, b, q, pose)
    bx, by = _rot(pose[b, 2], pbbx, pbby)
    wx = r0x + bx - Ax
    wy = r0y + by - Ay
    wu = wx * ux + wy * uy
    disc = wu * wu - (wx * wx + wy * wy) + La * La
    if disc < 0.0:
        if disc < -CLAMP * La * La:
            dist = abs(wx * uy - wy * ux)
            return F_ASSEMBLY, dist - La, 0.0
        disc = 0.0
    root = np.sqrt(disc)
    t = -wu + sigma * root
    pose[b, 0] = r0x + t * ux
    pose[b, 1] = r0y + t * uy
    Bx = pose[b, 0] + bx
    By = pose[b, 1] + by
    ta = np.arctan2(By - Ay, Bx - Ax) - np.arctan2(pbay - pay, pbax - pax)
    _place(pose, a, ta, Ax, Ay, pax, pay)
    sinmu = sigma * root / La if La > 0 else 0.0
    return F_OK, 0.0, sinmu


@njit(cache=True, error_model="numpy")
def _solve_rpr(jf, jb, a, b, jA, jP, jC, sigma, q, pose):
    """ВПВ group: bodies a, b each on a revolute to a known body (jA, jC), joined by the
    prismatic jP.  With G the guide and S the slider body of jP and w = P_S − P_G:
    |w| cos(θ_G + β − ψ) = K  ⇒  θ_G = ψ − β + σ·acos(K/|w|)."""
    G = jb[jP, 0]
    S = jb[jP, 1]
    jG = jA if G == a else jC
    jS = jC if G == a else jA
    pgx, pgy, PGx, PGy = _pivot(jf, jb, jG, G, q, pose)
    psx, psy, PSx, PSy = _pivot(jf, jb, jS, S, q, pose)
    al = jf[jP, 4]
    e = jf[jP, 5]
    lgx, lgy, lsx, lsy = _pri(jf, jP, q)
    nlx = -np.sin(al)
    nly = np.cos(al)
    # slider point relative to the slider's pivot, expressed in the guide frame
    rx, ry = _rot(al, lsx - psx, lsy - psy)
    K = e + nlx * (lgx - pgx) + nly * (lgy - pgy) - (nlx * rx + nly * ry)
    wx = PSx - PGx
    wy = PSy - PGy
    W = np.hypot(wx, wy)
    if W == 0.0:
        return F_ASSEMBLY, abs(K), 0.0
    c = K / W
    if c > 1.0 or c < -1.0:
        if abs(c) - 1.0 > CLAMP:
            return F_ASSEMBLY, abs(K) - W, 0.0
        c = 1.0 if c > 0 else -1.0
    beta = al + 0.5 * np.pi
    psi = np.arctan2(wy, wx)
    tg = psi - beta + sigma * np.arccos(c)
    ts = tg + al
    _place(pose, G, tg, PGx, PGy, pgx, pgy)
    _place(pose, S, ts, PSx, PSy, psx, psy)
    return F_OK, 0.0, sigma * np.sqrt(max(0.0, 1.0 - c * c))


@njit(cache=True, error_model="numpy")
def _solve_crank(jt, jb, jf, gjoint, g, nj, body, q, pose):
    """The initial link (one body on a revolute to a known body, its angle set by the drive)
    in closed form: θ = θ_known ± (c0 + c1·q), then r = P − A(θ)·p with P the pivot's global
    position and p its local point on the body."""
    jr = gjoint[g, 0]
    jd = gjoint[g, 1]
    if jt[jr] != J_REV:
        jr, jd = jd, jr
    bi = jb[jd, 0]
    bj = jb[jd, 1]
    off = jf[jd, 0] + jf[jd, 1] * q
    th = pose[bi, 2] + off if bj == body else pose[bj, 2] - off
    px, py, gx, gy = _pivot(jf, jb, jr, body, q, pose)
    _place(pose, body, th, gx, gy, px, py)
    return F_OK, 0.0, 1.0


@njit(cache=True, error_model="numpy")
def _solve_lin(jt, jb, jf, gjoint, nj, gbody, g, nbg, q, pose, col_of, known, mat, rhs):
    """Group whose angles all follow from angle constraints (prismatic joints to known bodies,
    drives); positions then satisfy linear equations (ПВП, ВПП, the initial link).
    ``known``, ``mat``, ``rhs`` are the caller's scratch arrays."""
    for k in range(nbg):
        known[k] = False
    for it in range(nbg + 1):
        for k in range(nj):
            j = gjoint[g, k]
            if jt[j] == J_REV:
                continue
            bi = jb[j, 0]
            bj = jb[j, 1]
            ci = col_of[bi]
            cj = col_of[bj]
            ki = ci < 0 or known[ci]
            kj = cj < 0 or known[cj]
            if jt[j] == J_PRI:
                off = jf[j, 4]
            else:
                off = jf[j, 0] + jf[j, 1] * q
            if ki and not kj:
                pose[bj, 2] = pose[bi, 2] + off
                known[cj] = True
            elif kj and not ki:
                pose[bi, 2] = pose[bj, 2] - off
                known[ci] = True
    for k in range(nbg):
        if not known[k]:
            return F_SINGULAR, 0.0, 0.0
    n = 2 * nbg
    for r in range(n):
        rhs[r] = 0.0
        for c in range(n):
            mat[r, c] = 0.0
    row = 0
    for k in range(nj):
        j = gjoint[g, k]
        bi = jb[j, 0]
        bj = jb[j, 1]
        ci = col_of[bi]
        cj = col_of[bj]
        if jt[j] == J_REV:
            pix, piy = _local(jf, j, 0, q)
            pjx, pjy = _local(jf, j, 1, q)
            uix, uiy = _rot(pose[bi, 2], pix, piy)
            ujx, ujy = _rot(pose[bj, 2], pjx, pjy)
            for r in range(2):
                s = (uix - ujx) if r == 0 else (uiy - ujy)
                if ci >= 0:
                    mat[row + r, 2 * ci + r] += 1.0
                else:
                    s += pose[bi, r]
                if cj >= 0:
                    mat[row + r, 2 * cj + r] -= 1.0
                else:
                    s -= pose[bj, r]
                rhs[row + r] = -s
            row += 2
        elif jt[j] == J_PRI:
            al = jf[j, 4]
            lgx, lgy, lsx, lsy = _pri(jf, j, q)
            nx, ny = _rot(pose[bi, 2], -np.sin(al), np.cos(al))
            agx, agy = _rot(pose[bi, 2], lgx, lgy)
            asx, asy = _rot(pose[bj, 2], lsx, lsy)
            s = nx * (asx - agx) + ny * (asy - agy) - jf[j, 5]
            if cj >= 0:
                mat[row, 2 * cj] += nx
                mat[row, 2 * cj + 1] += ny
            else:
                s += nx * pose[bj, 0] + ny * pose[bj, 1]
            if ci >= 0:
                mat[row, 2 * ci] -= nx
                mat[row, 2 * ci + 1] -= ny
            else:
                s -= nx * pose[bi, 0] + ny * pose[bi, 1]
            rhs[row] = -s
            row += 1
    if row != n:
        return F_SINGULAR, 0.0, 0.0
    quality = solve_dense(mat, rhs, n, 0.0)
    if quality < 1e-13:
        return F_SINGULAR, 0.0, quality
    for k in range(nbg):
        b = gbody[g, k]
        pose[b, 0] = rhs[2 * k]
        pose[b, 1] = rhs[2 * k + 1]
    return F_OK, 0.0, quality


@njit(cache=True, error_model="numpy")
def _solve_newton(jt, jb, jf, gj, nj, gb, nbg, q, pose, d1, size, col_of, mat, rhs,
                  coef, expl, gam, res, cs):
    n = 3 * nbg
    res_norm = 0.0
    for it in range(NEWTON_MAXIT):
        _group_matrix(jt, jb, jf, gj, nj, gb, nbg, q, pose, d1, d1, 0, mat, rhs, col_of,
                      coef, expl, gam, res, True, cs)
        res_norm = 0.0
        for r in range(n):
            res_norm = max(res_norm, abs(rhs[r]))
        converged = res_norm <= NEWTON_TOL * size
        quality = solve_dense(mat, rhs, n, 0.0)
        if quality == 0.0:
            if converged:
                return F_OK, 0.0, 1.0
            return F_NEWTON, res_norm, 0.0
        for k in range(nbg):
            b = gb[k]
            for c in range(3):
                pose[b, c] += rhs[3 * k + c]
        if converged:
            # one more step after the tolerance is met: quadratic convergence takes the
            # residual to rounding level whatever the starting point
            return F_OK, 0.0, 1.0
    return F_NEWTON, res_norm, 0.0


@njit(cache=True, error_model="numpy")
def _residual_norms(jt, jb, jf, gj, nj, q, pose, res):
    """(max |Φ| over the group's equations, max gap of its revolute joints in metres)."""
    rmax = 0.0
    gap = 0.0
    for k in range(nj):
        j = gj[k]
        nr = _joint_residual(jt, jb, jf, j, q, pose, res)
        for r in range(nr):
            rmax = max(rmax, abs(res[r]))
        if jt[j] == J_REV:
            gap = max(gap, np.hypot(res[0], res[1]))
        elif jt[j] == J_PRI:
            gap = max(gap, abs(res[1]))
    return rmax, gap


@njit(cache=True, error_model="numpy")
def _solve_lsq(jt, jb, jf, gj, nj, gb, nbg, q, pose, d1, size, col_of, mat, rhs,
               coef, expl, gam, res, cs):
    """First assembly of a Newton group far from the sketch: Levenberg–Marquardt on the loop
    equations (Madsen, Nielsen, Tingleff, *Methods for non-linear least squares problems*,
    2004, alg. 3.16), angles scaled by the size of the mechanism.  Converges to an assembly when
    one exists in the basin of the sketch, otherwise to the configuration of least squared
    closure error; returns (status, the largest joint gap there in metres, 1)."""
    n = 3 * nbg
    A = np.zeros((n, n))
    g = np.zeros(n)
    trial = np.zeros((nbg, 3))
    lam = 1e-3
    nu = 2.0
    for it in range(400):
        _group_matrix(jt, jb, jf, gj, nj, gb, nbg, q, pose, d1, d1, 0, mat, rhs, col_of,
                      coef, expl, gam, res, True, cs)
        f0 = 0.0
        for r in range(n):
            f0 += rhs[r] * rhs[r]
        if np.sqrt(f0) <= NEWTON_TOL * size:
            return F_OK, 0.0, 1.0
        # scale the angle columns by the size so that all unknowns are lengths
        for r in range(n):
            for c in range(n):
                if c % 3 == 2:
                    mat[r, c] /= size
        dmax = 0.0
        for r in range(n):
            s = 0.0
            for k in range(n):
                s += mat[k, r] * rhs[k]
            g[r] = s
            for c in range(n):
                s = 0.0
                for k in range(n):
                    s += mat[k, r] * mat[k, c]
                A[r, c] = s
            dmax = max(dmax, A[r, r])
        if it == 0:
            lam = 1e-3 * dmax
        for r in range(n):
            A[r, r] += lam
        for r in range(n):
            rhs[r] = g[r]
        if solve_dense(A, rhs, n, 0.0) == 0.0:
            break
        for k in range(nbg):
            b = gb[k]
            for c in range(3):
                trial[k, c] = pose[b, c]
                pose[b, c] += rhs[3 * k + c] / (size if c == 2 else 1.0)
        f1 = 0.0
        for k in range(nj):
            nr = _joint_residual(jt, jb, jf, gj[k], q, pose, res)
            for r in range(nr):
                f1 += res[r] * res[r]
        if f1 < f0:
            lam = max(lam * 0.3, 1e-30)
            nu = 2.0
        else:
            for k in range(nbg):
                b = gb[k]
                for c in range(3):
                    pose[b, c] = trial[k, c]
            lam *= nu
            nu *= 2.0
            if lam > 1e30:
                break
    for k in range(nbg):
        b = gb[k]
        for c in range(3):
            trial[k, c] = pose[b, c]
    st, a2, q2 = _solve_newton(jt, jb, jf, gj, nj, gb, nbg, q, pose, d1, size, col_of, mat, rhs,
                               coef, expl, gam, res, cs)
    if st == F_OK:
        return F_OK, 0.0, 1.0
    for k in range(nbg):            # a Newton that failed may have wandered off: the gap is
        b = gb[k]                   # measured at the least-squares configuration
        for c in range(3):
            pose[b, c] = trial[k, c]
    rmax, gap = _residual_norms(jt, jb, jf, gj, nj, q, pose, res)
    return F_NEWTON, gap, 0.0


@njit(cache=True, error_model="numpy")
def _solve_homotopy(jt, jb, jf, gj, nj, gb, nbg, q, pose, d1, size, col_of, mat, rhs,
                    coef, expl, gam, res, cs):
    """First assembly of a Newton group by continuation from the sketch (Newton homotopy,
    Allgower & Georg, *Introduction to numerical continuation methods*, 2003, §1):
    H(x, t) = Φ(x) − (1 − t)·Φ(x_sketch), t from 0 (the sketch solves it) to 1, in
    HOMOTOPY_STEPS equal steps, each corrected by Newton.  The path starts at the sketch, so it
    ends on the assembly the sketch draws, not on whichever one a full Newton step reaches.
    Returns (status, amount, quality) as :func:`_solve_newton`."""
    n = 3 * nbg
    _group_matrix(jt, jb, jf, gj, nj, gb, nbg, q, pose, d1, d1, 0, mat, rhs, col_of,
                  coef, expl, gam, res, False, cs)
    r0 = rhs[:n].copy()                      # −Φ(x_sketch)
    for s in range(1, HOMOTOPY_STEPS + 1):
        lam = 1.0 - s / HOMOTOPY_STEPS
        for it in range(NEWTON_MAXIT):
            _group_matrix(jt, jb, jf, gj, nj, gb, nbg, q, pose, d1, d1, 0, mat, rhs, col_of,
                          coef, expl, gam, res, True, cs)
            rn = 0.0
            for r in range(n):
                rhs[r] -= lam * r0[r]
                rn = max(rn, abs(rhs[r]))
            if rn <= NEWTON_TOL * size:
                break
            if solve_dense(mat, rhs, n, 0.0) == 0.0:
                return F_NEWTON, rn, 0.0
            for k in range(nbg):
                b = gb[k]
                for c in range(3):
                    pose[b, c] += rhs[3 * k + c]
    return _solve_newton(jt, jb, jf, gj, nj, gb, nbg, q, pose, d1, size, col_of, mat, rhs,
                         coef, expl, gam, res, cs)


@njit(cache=True, error_model="numpy")
def _pose_distance(a, b, gb, nbg, size):
    """Largest difference of the group's body poses (angles times the size: metres)."""
    d = 0.0
    for k in range(nbg):
        bb = gb[k]
        d = max(d, abs(a[bb, 0] - b[bb, 0]), abs(a[bb, 1] - b[bb, 1]),
                size * abs(np.arctan2(np.sin(a[bb, 2] - b[bb, 2]), np.cos(a[bb, 2] - b[bb, 2]))))
    return d


@njit(cache=True, error_model="numpy")
def _general_analogs(jt, jb, jf, gj, nj, gb, nbg, qi, cur, v, acc, mat, rhs, perm, col_of,
                     coef, expl, gam, res, cs, kind, qual, g, qarr, iq, fail):
    """Analogs of any group from its dense linear systems Φ_x x' = −Φ_q and Φ_x x'' = −γ (one
    LU factorisation for both levels).  Stores the pivot measure in qarr[iq, g] for Newton and
    linear groups; returns False (fail set, F_SINGULAR) when the matrix is singular."""
    n = 3 * nbg
    _group_matrix(jt, jb, jf, gj, nj, gb, nbg, qi, cur, v, acc, 1, mat, rhs, col_of,
                  coef, expl, gam, res, True, cs)
    piv = lu_factor(mat, n, perm)
    if kind == G_NEWTON or kind == G_LIN:
        qual = piv
    if piv < 1e-14:
        fail[0] = F_SINGULAR
        fail[2] = g
        fail[3] = qual      # transmission measure of a dyad, the pivot measure otherwise
        for k in range(nbg):
            col_of[gb[k]] = -1
        return False
    lu_solve(mat, perm, rhs, n)
    for k in range(nbg):
        for c in range(3):
            v[gb[k], c] = rhs[3 * k + c]
    _group_matrix(jt, jb, jf, gj, nj, gb, nbg, qi, cur, v, acc, 2, mat, rhs, col_of,
                  coef, expl, gam, res, False, cs)
    lu_solve(mat, perm, rhs, n)
    for k in range(nbg):
        for c in range(3):
            acc[gb[k], c] = rhs[3 * k + c]
    qarr[iq, g] = qual
    return True


@njit(cache=True, error_model="numpy")
def _solve_position(qi, dq, first, jt, jb, jf, gkind, gspec, gsigma, gjoint, gnj, gbody, gnb,
                    size, cur, v, acc, pp, pv, pa, ip, qarr, iq, fail, mat, rhs, perm, known,
                    coef, expl, gam, res, col_of, cs):
    """Positions and both analogs of every group at qi.  Newton groups start from the
    second-order predictor pp + pv·dq + ½ pa·dq² (the state pp[ip], pv[ip], pa[ip] at the previous
    grid point), or from
    ``cur`` (the sketch) when ``first``.  Returns False on failure (fail[0], fail[2], fail[3] set;
    F_JUMP when Newton's correction is large against the predicted step, i.e. it may have left
    the branch and the caller must refine the step).  The groups' quality measures go to
    qarr[iq]."""
    ng = gkind.shape[0]
    for g in range(ng):
        nbg = gnb[g]
        nj = gnj[g]
        for k in range(nbg):
            col_of[gbody[g, k]] = k
        kind = gkind[g]
        s0 = gspec[g, 0]
        s1 = gspec[g, 1]
        s2 = gspec[g, 2]
        s3 = gspec[g, 3]
        s4 = gspec[g, 4]
        if kind == G_RRR:
            st, amount, qual = _solve_rrr(jf, jb, s0, s1, s2, s3, s4, gsigma[g], qi, cur)
        elif kind == G_RRP:
            st, amount, qual = _solve_rrp(jf, jb, s0, s1, s2, s3, s4, gsigma[g], qi, cur)
        elif kind == G_RPR:
            st, amount, qual = _solve_rpr(jf, jb, s0, s1, s2, s3, s4, gsigma[g], qi, cur)
        elif kind == G_LIN and gspec[g, 5] == A_SINGLE:
            st, amount, qual = _solve_crank(jt, jb, jf, gjoint, g, nj, gbody[g, 0], qi, cur)
        elif kind == G_LIN:
            st, amount, qual = _solve_lin(jt, jb, jf, gjoint, nj, gbody, g, nbg, qi, cur, col_of, known, mat, rhs)
        else:
            gb = gbody[g]
            gj = gjoint[g]
            if first:
                # from the sketch: Newton and damped (Levenberg–Marquardt) steps, which stay
                # near the sketch where a full Newton step may land on another assembly; the
                # converged assembly nearer to the sketch is taken
                sketch = cur.copy()
                st, amount, qual = _solve_newton(jt, jb, jf, gj, nj, gb, nbg, qi, cur, v, size, col_of,
                                                 mat, rhs, coef, expl, gam, res, cs)
                newton = cur.copy()
                cur[:, :] = sketch
                st3, amount3, qual3 = _solve_homotopy(jt, jb, jf, gj, nj, gb, nbg, qi, cur, v, size,
                                                      col_of, mat, rhs, coef, expl, gam, res, cs)
                homot = cur.copy()
                cur[:, :] = sketch
                st2, amount2, qual2 = _solve_lsq(jt, jb, jf, gj, nj, gb, nbg, qi, cur, v, size, col_of,
                                                 mat, rhs, coef, expl, gam, res, cs)
                if st3 == F_OK and (st2 != F_OK or _pose_distance(homot, sketch, gb, nbg, size)
                                    < _pose_distance(cur, sketch, gb, nbg, size)):
                    cur[:, :] = homot
                    st2, amount2, qual2 = st3, amount3, qual3
                if st == F_OK and (st2 != F_OK or _pose_distance(newton, sketch, gb, nbg, size)
                                   <= _pose_distance(cur, sketch, gb, nbg, size)):
                    cur[:, :] = newton
                else:
                    st, amount, qual = st2, amount2, qual2
            else:
                step = 0.0
                for k in range(nbg):
                    b = gb[k]
                    for c in range(3):
                        dx = pv[ip, b, c] * dq + 0.5 * pa[ip, b, c] * dq * dq
                        cur[b, c] = pp[ip, b, c] + dx
                        step = max(step, abs(dx) * (size if c == 2 else 1.0))
                for k in range(nbg):
                    b = gb[k]
                    for c in range(3):
                        rhs[3 * k + c] = cur[b, c]
                pred = rhs[:3 * nbg].copy()
                st, amount, qual = _solve_newton(jt, jb, jf, gj, nj, gb, nbg, qi, cur, v, size, col_of,
                                                 mat, rhs, coef, expl, gam, res, cs)
                if st == F_OK:
                    corr = 0.0
                    for k in range(nbg):
                        b = gb[k]
                        for c in range(3):
                            corr = max(corr, abs(cur[b, c] - pred[3 * k + c]) * (size if c == 2 else 1.0))
                    if corr > JUMP_RATIO * step + JUMP_ABS * size:
                        st = F_JUMP
                        amount = corr
                else:
                    st = F_JUMP
                    amount = -1.0      # Newton did not converge (not a detected jump)
        if st != F_OK:
            fail[0] = st
            fail[2] = g
            fail[3] = amount
            for k in range(nbg):
                col_of[gbody[g, k]] = -1
            return False
        for k in range(nbg):
            b = gbody[g, k]
            cs[b, 0] = np.cos(cur[b, 2])
            cs[b, 1] = np.sin(cur[b, 2])
        if not _general_analogs(jt, jb, jf, gjoint[g], nj, gbody[g], nbg, qi, cur, v, acc, mat, rhs, perm, col_of,
                                  coef, expl, gam, res, cs, kind, qual, g, qarr, iq, fail):
            return False
        elif kind == G_NEWTON or kind == G_LIN:
            qual = qarr[iq, g]
        qarr[iq, g] = qual
        for k in range(nbg):
            col_of[gbody[g, k]] = -1
    return True


@njit(cache=True, error_model="numpy")
def solve_cycle(q, jt, jb, jf, gkind, gspec, gsigma, gjoint, gnj, gbody, gnb,
                pose0, size):
    """Positions, first and second analogs of every body over the grid q.

    Returns (pose, d1, d2, quality, fail) with pose/d1/d2 of shape (N, nbodies, 3) holding
    (x, y, θ) of each body's frame and their d/dq, d²/dq²; quality (N, ngroups) a
    singularity indicator per group (sine of the transmission angle for dyads, normalised pivot
    otherwise); fail = [kind, position index, group, amount] of the first failure (kind 0 = none).

    Groups solved by Newton are continued along the grid from the previous position with a
    second-order predictor; a correction large against the predicted step (a possible jump to
    another branch) or a failure makes the step refined by bisection (up to 2^MAX_HALVINGS
    sub-steps, every group re-solved at each sub-step); if that does not resolve it the position
    is reported singular with the condition measure of the group.
    """
    N = q.shape[0]
    nb = pose0.shape[0]
    ng = gkind.shape[0]
    pose = np.zeros((N, nb, 3))
    d1 = np.zeros((N, nb, 3))
    d2 = np.zeros((N, nb, 3))
    quality = np.zeros((N, ng))
    fail = np.zeros(4)
    maxb = gbody.shape[1]
    mat = np.zeros((3 * maxb, 3 * maxb))
    rhs = np.zeros(3 * maxb)
    perm = np.zeros(3 * maxb, dtype=np.int64)
    known = np.zeros(maxb, dtype=np.bool_)
    coef = np.zeros((2, 6))
    expl = np.zeros(2)
    gam = np.zeros(2)
    res = np.zeros(2)
    col_of = -np.ones(nb, dtype=np.int64)
    cur = pose0.copy()
    v = np.zeros((nb, 3))
    acc = np.zeros((nb, 3))
    sp = np.zeros((1, nb, 3))
    sv = np.zeros((1, nb, 3))
    sa = np.zeros((1, nb, 3))
    qrow = np.zeros((1, ng))
    qfail = 0.0
    cs = np.zeros((nb, 2))
    for b in range(nb):
        cs[b, 0] = np.cos(pose0[b, 2])
        cs[b, 1] = np.sin(pose0[b, 2])
    # the arguments of every _solve_position call have the same (non-literal) types, so that it
    # is compiled once: a literal True/0 would compile a second and third specialisation
    never = N < 0
    zero = N - N
    for i in range(N):
        qi = q[i]
        ip = i - 1 if i > 0 else i
        ok = _solve_position(qi, qi - q[ip], i == 0, jt, jb, jf, gkind, gspec, gsigma, gjoint,
                             gnj, gbody, gnb, size, cur, v, acc, pose, d1, d2, ip,
                             quality, i, fail, mat, rhs, perm, known, coef, expl, gam, res, col_of, cs)
        if i > 0 and not ok and fail[0] == F_JUMP:
            # refine: march from q[i-1] to q[i] in 2, 4, … equal sub-steps
            for h in range(1, MAX_HALVINGS + 1):
                m = 1 << h
                h_q = (qi - q[i - 1]) / m
                sp[0] = pose[i - 1]
                sv[0] = d1[i - 1]
                sa[0] = d2[i - 1]
                ok = True
                for k in range(1, m + 1):
                    qk = q[i - 1] + k * h_q if k < m else qi
                    qfail = qk
                    ok = _solve_position(qk, h_q, never, jt, jb, jf, gkind, gspec, gsigma, gjoint,
                                         gnj, gbody, gnb, size, cur, v, acc, sp, sv, sa, zero, qrow, zero, fail,
                                         mat, rhs, perm, known, coef, expl, gam, res, col_of, cs)
                    if not ok:
                        break
                    sp[0] = cur
                    sv[0] = v
                    sa[0] = acc
                if ok:
                    quality[i, :] = qrow[0]
                    fail[:] = 0.0
                    break
                if fail[0] != F_JUMP:
                    break
            if not ok and fail[0] == F_JUMP:
                g = int(fail[2])
                if fail[3] < 0.0:
                    # Newton fails even on the finest step: least squares from the last
                    # solved sub-step tells an assembly from a gap (reported in metres)
                    cur[:, :] = sp[0]
                    for k in range(gnb[g]):
                        col_of[gbody[g, k]] = k
                    st, amount, qual = _solve_lsq(jt, jb, jf, gjoint[g], gnj[g], gbody[g], gnb[g],
                                                  qfail, cur, v, size, col_of, mat, rhs, coef, expl,
                                                  gam, res, cs)
                    for k in range(gnb[g]):
                        col_of[gbody[g, k]] = -1
                    fail[0] = F_NEWTON if st != F_OK else F_SINGULAR
                    fail[3] = amount if st != F_OK else qrow[0, g]
                else:
                    # the branch cannot be followed through this step: a singular position
                    fail[0] = F_SINGULAR
                    fail[3] = qrow[0, g]
        if not ok:
            fail[1] = i
            return pose, d1, d2, quality, fail
        for b in range(nb):
            for c in range(3):
                pose[i, b, c] = cur[b, c]
                d1[i, b, c] = v[b, c]
                d2[i, b, c] = acc[b, c]
    return pose, d1, d2, quality, fail


@njit(cache=True, error_model="numpy")
def points_cycle(pose, d1, d2, q, pbody, ploc):
    """Global position and analogs of points given by body index and local coordinates
    p = p0 + q·p1 (ploc rows: p0x, p0y, p1x, p1y).

    x = r + A p;  x' = r' + ⊥(A p) θ' + A p1;  x'' = r'' + ⊥(A p) θ'' − A p θ'² + 2 ⊥(A p1) θ'.
    cos θ and sin θ once per body and position (not per point).
    Returns an array (N, npoints, 6): x, y, x', y', x'', y'' — a view of contiguous rows
    (npoints, 6, N), so that the named columns (a row each) are taken without a copy."""
    N = pose.shape[0]
    nb = pose.shape[1]
    npnt = pbody.shape[0]
    out = np.empty((npnt, 6, N))
    used = np.zeros(nb, dtype=np.bool_)
    for k in range(npnt):
        used[pbody[k]] = True
    cs = np.zeros(nb)
    sn = np.zeros(nb)
    for i in range(N):
        qi = q[i]
        for b in range(nb):
            if used[b]:
                th = pose[i, b, 2]
                if th == 0.0:          # the frame: cos(±0) = 1, sin(±0) = ±0 exactly
                    cs[b] = 1.0
                    sn[b] = th
                else:
                    cs[b] = np.cos(th)
                    sn[b] = np.sin(th)
        for k in range(npnt):
            b = pbody[k]
            c = cs[b]
            s = sn[b]
            w = d1[i, b, 2]
            e = d2[i, b, 2]
            px = ploc[k, 0] + qi * ploc[k, 2]
            py = ploc[k, 1] + qi * ploc[k, 3]
            ux = c * px - s * py
            uy = s * px + c * py
            vx = c * ploc[k, 2] - s * ploc[k, 3]
            vy = s * ploc[k, 2] + c * ploc[k, 3]
            out[k, 0, i] = pose[i, b, 0] + ux
            out[k, 1, i] = pose[i, b, 1] + uy
            out[k, 2, i] = d1[i, b, 0] - uy * w + vx
            out[k, 3, i] = d1[i, b, 1] + ux * w + vy
            out[k, 4, i] = d2[i, b, 0] - uy * e - ux * w * w - 2.0 * vy * w
            out[k, 5, i] = d2[i, b, 1] + ux * e - uy * w * w + 2.0 * vx * w
    return out.transpose(2, 0, 1)


@njit(cache=True, error_model="numpy")
def group_jacobians(q, pose, jt, jb, jf, gj, nj, gb, nbg, size):
    """The Jacobian Φ_x of one group at every solved position (N, 3·nbg, 3·nbg), the angle
    columns divided by the size of the mechanism so that every entry is dimensionless
    (rows: the joints' constraint equations in metres; columns: x, y, θ·size of each body)."""
    N = q.shape[0]
    nb = pose.shape[1]
    n = 3 * nbg
    out = np.zeros((N, n, n))
    mat = np.zeros((n, n))
    rhs = np.zeros(n)
    coef = np.zeros((2, 6))
    expl = np.zeros(2)
    gam = np.zeros(2)
    res = np.zeros(2)
    cs = np.zeros((nb, 2))
    col_of = -np.ones(nb, dtype=np.int64)
    for k in range(nbg):
        col_of[gb[k]] = k
    cur = np.zeros((nb, 3))
    for i in range(N):
        for b in range(nb):
            for c in range(3):
                cur[b, c] = pose[i, b, c]
        _group_matrix(jt, jb, jf, gj, nj, gb, nbg, q[i], cur, cur, cur, 0, mat, rhs, col_of,
                      coef, expl, gam, res, True, cs)
        for r in range(n):
            for c in range(n):
                out[i, r, c] = mat[r, c] / (size if c % 3 == 2 else 1.0)
    return out


@njit(cache=True, error_model="numpy")
def group_transmission(q, pose, jt, jb, jf, gj, nj, gb, nbg, size):
    """Hadamard ratio h = |det R⊥| / ∏‖R⊥e_k‖ of a group at every solved position (see
    ``analysis.linkage.equivalent_transmission_sine``): modified Gram–Schmidt on the translation
    columns of the scaled Φ_x (:func:`group_jacobians`), the angle columns projected off them
    (R⊥, norms ν_k) and orthogonalised in turn (residual norms d_k); |det R⊥| = ∏ d_k."""
    J = group_jacobians(q, pose, jt, jb, jf, gj, nj, gb, nbg, size)
    N = q.shape[0]
    n = 3 * nbg
    nt = 2 * nbg
    h = np.zeros(N)
    basis = np.zeros((n, n))
    w = np.zeros(n)
    for i in range(N):
        m = 0
        ratio = 1.0
        for pass_ in range(2):                  # translation columns, then angle columns
            for c in range(n):
                if (c % 3 == 2) != (pass_ == 1):
                    continue
                for r in range(n):
                    w[r] = J[i, r, c]
                nu = 0.0
                for k in range(m):
                    if pass_ == 1 and k == nt:  # ν: the norm of R⊥e_k before its own orthogonalisation
                        nu = np.sqrt(np.sum(w * w))
                    s = 0.0
                    for r in range(n):
                        s += basis[r, k] * w[r]
                    for r in range(n):
                        w[r] -= s * basis[r, k]
                d = np.sqrt(np.sum(w * w))
                if pass_ == 1:
                    if m == nt:
                        nu = d
                    ratio *= d / nu if nu > 0.0 else 0.0
                if d > 0.0:
                    for r in range(n):
                        basis[r, m] = w[r] / d
                    m += 1
        h[i] = min(1.0, ratio)
    return h
