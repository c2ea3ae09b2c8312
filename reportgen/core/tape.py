"""Whole-cycle kinematics of linkages made of closed-form groups, compiled into a flat "tape".

A mechanism whose groups are all the initial link (a revolute and the drive) and dyads ВВВ,
ВВП, ВПВ with constant local geometry — except the actuator's rod end as the inner joint of a
ВВВ group (its point p = p0 + q·p1 on the cylinder's body) — is compiled once into two arrays: an int
row per group (operation, its bodies, the known bodies it hangs on) and a float row of
constants (local points, link lengths, guide angles, offsets).  One kernel, :func:`run_tape`,
loops over the positions and the groups doing only scalar arithmetic and writes positions,
first and second analogs straight into the output arrays: no per-position allocation, no
per-group call with array arguments.

Positions are those of :mod:`.kinematics` (the same closed forms, the same expressions for the
angles); the cosine and sine of each body's angle come from direction vectors, not from the
angle.  The analogs are the group's vector loop equation differentiated once and twice, written
out as a 2×2 system in two scalars solved by Cramer's rule (Артоболевский, «Теория механизмов и
машин», §§ 3.5–3.8: the velocity and acceleration equations of a group projected on two axes):

* ВВВ, inner joint B on bodies a, b hanging on A and C:
  ``A′ + ω_a ⊥(B−A) + v = C′ + ω_b ⊥(B−C)`` and
  ``A″ + ε_a ⊥(B−A) − ω_a²(B−A) + 2ω_a ⊥v = C″ + ε_b ⊥(B−C) − ω_b²(B−C)``, v = A(θ_a)p1 the rod's
  own rate (zero without an actuator);
* ВВП (b slides along a guide fixed to the known body k, direction u):
  ``A′ + ω_a ⊥(B−A) = V_k(B) + τ u`` and
  ``A″ + ε_a ⊥(B−A) − ω_a²(B−A) = W_k(B) + 2ω_k τ ⊥u + τ′ u`` with V_k, W_k the velocity and
  acceleration analogs of the point of k coinciding with B (Coriolis term 2ω_k τ ⊥u);
* ВПВ (guide body G, slider S, w = P_S − P_G between their pivots):
  ``ω ⊥w + τ u = P_S′ − P_G′`` and ``ε ⊥w + τ′ u = P_S″ − P_G″ + ω² w − 2ωτ ⊥u``.

Near a singular position (the group's measure below MEAS_MIN, or an assembly failure) the kernel
stops and reports ``fail[0] = NEED_GENERAL``: the caller then solves the whole grid with the
general kernel :func:`.kinematics.solve_cycle`, which judges singular positions, clamps stretched
groups and reports failures exactly as before.  Newton groups (class III), ПВП/ВПП dyads and any
other point moving with q always take the general kernel.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from . import kinematics as K

OP_CRANK = 1
OP_RRR = 2
OP_RRP = 3
OP_RPR = 4
NEED_GENERAL = -1.0
MEAS_MIN = 1e-6     # above the general kernel's FAST_MIN: near-singular positions are left to it
NI = 6              # int columns: op, body a, body b, known body 1, known body 2, flag
NF = 24             # float columns (constants of the group)


PIO2 = 1.5707963267948966
PIO4 = 0.7853981633974483
MOREBITS = 6.123233995736765886130e-17     # π/2 − PIO2


@njit(cache=True, error_model="numpy")
def _atan2(y, x):
    """atan2(y, x) in (−π, π] by the Cephes arctangent (S. L. Moshier, Cephes Mathematical
    Library, atan.c: the argument min(|x|,|y|)/max(|x|,|y|) ≤ 1 reduced by the π/4 shift above
    0.66, then a 4/5 rational in its square, error about 1e-16), the octant restored from the
    signs; about a third of libm's cost and within 2 ulp of it."""
    ay = abs(y)
    ax = abs(x)
    hi = max(ax, ay)
    lo = min(ax, ay)
    if hi == 0.0:
        return 0.0
    big = lo > 0.66 * hi
    if big:
        t = (lo - hi) / (lo + hi)       # (t − 1)/(t + 1) for t = lo/hi, one division
    else:
        t = lo / hi
    z = t * t
    p = (((-8.750608600031904122785e-1 * z - 1.615753718733365076637e1) * z
          - 7.500855792314704667340e1) * z - 1.228866684490136173410e2) * z - 6.485021904942025371773e1
    qq = ((((z + 2.485846490142306297962e1) * z + 1.650270098316988542046e2) * z
           + 4.328810604912902668951e2) * z + 4.853903996359136964868e2) * z + 1.945506571482613964425e2
    a = t + t * z * p / qq
    if big:
        a = PIO4 + (a + 0.5 * MOREBITS)
    if ay > ax:
        a = PIO2 - a + MOREBITS
    if x < 0.0:
        a = 2.0 * PIO2 - a + 2.0 * MOREBITS
    return -a if y < 0.0 else a


@njit(cache=True, error_model="numpy")
def _inv_norm(x, y):
    """1/|(x, y)|, or 0 for the zero vector."""
    n2 = x * x + y * y
    return 1.0 / np.sqrt(n2) if n2 > 0.0 else 0.0


@njit(cache=True, error_model="numpy")
def _point(x, y, c, s, vx, vy, w, ax, ay, e, px, py):
    """Global position and analogs of local point p of a body with pose (x, y, θ) (c, s =
    cos θ, sin θ) and analogs: P = r + u, P′ = r′ + θ′⊥u, P″ = r″ + θ″⊥u − θ′²u, u = A(θ)p."""
    ux = c * px - s * py
    uy = s * px + c * py
    return (x + ux, y + uy, vx - w * uy, vy + w * ux,
            ax - e * uy - w * w * ux, ay + e * ux - w * w * uy)


@njit(cache=True, error_model="numpy")
def run_tape(q, top, tf, sigma, ng, pose0):
    """Positions, first and second analogs of the bodies over the grid q for the first ``ng``
    groups of the tape (top, tf); the same outputs as :func:`.kinematics.solve_cycle`
    (pose, d1, d2, quality, fail).  fail[0] = NEED_GENERAL (fail[1] the position, fail[2] the
    group) when a position needs the general kernel."""
    N = q.shape[0]
    nb = pose0.shape[0]
    # every entry is written below (fixed bodies here, the others by their group)
    pose = np.empty((N, nb, 3))
    d1 = np.empty((N, nb, 3))
    d2 = np.empty((N, nb, 3))
    quality = np.empty((N, ng))
    fail = np.zeros(4)
    cs = np.zeros((nb, 2))
    solved = np.zeros(nb, dtype=np.bool_)
    for g in range(ng):
        solved[top[g, 1]] = True
        if top[g, 0] != OP_CRANK:
            solved[top[g, 2]] = True
    nfix = 0
    fixed = np.zeros(nb, dtype=np.int64)
    for b in range(nb):
        cs[b, 0] = np.cos(pose0[b, 2])
        cs[b, 1] = np.sin(pose0[b, 2])
        if not solved[b]:
            fixed[nfix] = b
            nfix += 1
    for i in range(N):
        qi = q[i]
        for kk in range(nfix):
            b = fixed[kk]
            for c in range(3):
                pose[i, b, c] = pose0[b, c]
                d1[i, b, c] = 0.0
                d2[i, b, c] = 0.0
        for g in range(ng):
            op = top[g, 0]
            a = top[g, 1]
            b = top[g, 2]
            k1 = top[g, 3]
            k2 = top[g, 4]
            sg = sigma[g]
            if op == OP_CRANK:
                # θ = θ_m ± (c0 + c1 q); r = P − A(θ)p with P the pivot on the known body k2
                th = pose[i, k1, 2] + tf[g, 0] * (tf[g, 1] + tf[g, 2] * qi)
                w = d1[i, k1, 2] + tf[g, 0] * tf[g, 2]
                e = d2[i, k1, 2]
                c = np.cos(th)
                s = np.sin(th)
                Px, Py, Pvx, Pvy, Pax, Pay = _point(pose[i, k2, 0], pose[i, k2, 1], cs[k2, 0], cs[k2, 1], d1[i, k2, 0], d1[i, k2, 1],
                                                    d1[i, k2, 2], d2[i, k2, 0], d2[i, k2, 1], d2[i, k2, 2], tf[g, 3], tf[g, 4])
                pose[i, a, 2] = th
                _body_about(pose, d1, d2, i, cs, a, c, s, Px, Py, Pvx, Pvy, Pax, Pay, w, e, tf[g, 5], tf[g, 6])
                ux = c * tf[g, 5] - s * tf[g, 6]
                uy = s * tf[g, 5] + c * tf[g, 6]
                # Hadamard's ratio of the link's 3×3 system (rows of the revolute and the drive)
                quality[i, g] = 1.0 / np.sqrt((1.0 + uy * uy) * (1.0 + ux * ux))
                continue
            # the pivot of body a on the known body k1 (every dyad kind has one)
            Ax, Ay, Avx, Avy, Aax, Aay = _point(pose[i, k1, 0], pose[i, k1, 1], cs[k1, 0], cs[k1, 1], d1[i, k1, 0], d1[i, k1, 1],
                                                d1[i, k1, 2], d2[i, k1, 0], d2[i, k1, 1], d2[i, k1, 2], tf[g, 0], tf[g, 1])
            if op == OP_RRR:
                Cx, Cy, Cvx, Cvy, Cax, Cay = _point(pose[i, k2, 0], pose[i, k2, 1], cs[k2, 0], cs[k2, 1], d1[i, k2, 0], d1[i, k2, 1],
                                                    d1[i, k2, 2], d2[i, k2, 0], d2[i, k2, 1], d2[i, k2, 2], tf[g, 4], tf[g, 5])
                La = tf[g, 8]
                Lb = tf[g, 9]
                ba = tf[g, 10]
                cba = tf[g, 11]
                sba = tf[g, 12]
                iLa = tf[g, 17]
                moving = top[g, 5] == 1
                if moving:
                    # the inner joint's point on a moves with q (an actuator's rod): p = p0 + q p1
                    lx = tf[g, 19] + qi * tf[g, 21] - tf[g, 2]
                    ly = tf[g, 20] + qi * tf[g, 22] - tf[g, 3]
                    La = np.sqrt(lx * lx + ly * ly)
                    iLa = 1.0 / La
                    ba = _atan2(ly, lx)
                    cba = lx * iLa
                    sba = ly * iLa
                dx = Cx - Ax
                dy = Cy - Ay
                iD = _inv_norm(dx, dy)
                if iD == 0.0:
                    fail[0] = NEED_GENERAL
                    break
                x = 0.5 * (La * La - Lb * Lb + dx * dx + dy * dy) * iD
                h2 = La * La - x * x
                if h2 <= 0.0:
                    fail[0] = NEED_GENERAL
                    break
                h = np.sqrt(h2)
                ex = dx * iD
                ey = dy * iD
                Bx = Ax + x * ex - sg * h * ey
                By = Ay + x * ey + sg * h * ex
                rax = Bx - Ax
                ray = By - Ay
                rbx = Bx - Cx
                rby = By - Cy
                det = ray * rbx - rax * rby
                sinmu = -det * (iLa * tf[g, 18])
                if abs(sinmu) < MEAS_MIN:
                    fail[0] = NEED_GENERAL
                    break
                quality[i, g] = sinmu
                # body a about A, body b about C: θ = atan2(ρ) − β, (cos θ, sin θ) from ρ/L
                ca = (rax * cba + ray * sba) * iLa
                sa = (ray * cba - rax * sba) * iLa
                pose[i, a, 2] = _atan2(ray, rax) - ba
                # ω_a ⊥ρa − ω_b ⊥ρb = C′ − A′ − v, then the same matrix for ε with
                # −2ω_a ⊥v; v = A(θ_a) p1 is the rod's own rate (zero without an actuator)
                vx = 0.0
                vy = 0.0
                if moving:
                    vx = ca * tf[g, 21] - sa * tf[g, 22]
                    vy = sa * tf[g, 21] + ca * tf[g, 22]
                wx = Cvx - Avx - vx
                wy = Cvy - Avy - vy
                idet = 1.0 / det
                wa = (-wx * rbx - rby * wy) * idet
                wb = (-ray * wy - rax * wx) * idet
                wx = Cax - Aax + wa * wa * rax - wb * wb * rbx + 2.0 * wa * vy
                wy = Cay - Aay + wa * wa * ray - wb * wb * rby - 2.0 * wa * vx
                ea = (-wx * rbx - rby * wy) * idet
                eb = (-ray * wy - rax * wx) * idet
                cb = (rbx * tf[g, 14] + rby * tf[g, 15]) * tf[g, 18]
                sb = (rby * tf[g, 14] - rbx * tf[g, 15]) * tf[g, 18]
                pose[i, b, 2] = _atan2(rby, rbx) - tf[g, 13]
                _body_about(pose, d1, d2, i, cs, b, cb, sb, Cx, Cy, Cvx, Cvy, Cax, Cay, wb, eb, tf[g, 6], tf[g, 7])
            elif op == OP_RRP:
                # body b slides along a guide fixed to the known body k2 (its angle locked to k2's)
                ck = cs[k2, 0]
                sk = cs[k2, 1]
                pose[i, b, 2] = pose[i, k2, 2] + tf[g, 11]
                cb = ck * tf[g, 12] - sk * tf[g, 13]
                sb = sk * tf[g, 12] + ck * tf[g, 13]
                if top[g, 5] == 0:
                    ux = cb
                    uy = sb
                else:
                    ux = ck
                    uy = sk
                nx = -uy
                ny = ux
                # the line traced by body b's frame origin: r_b = r0 + t u
                r0x = pose[i, k2, 0] + ck * tf[g, 6] - sk * tf[g, 7] + tf[g, 10] * nx - (cb * tf[g, 8] - sb * tf[g, 9])
                r0y = pose[i, k2, 1] + sk * tf[g, 6] + ck * tf[g, 7] + tf[g, 10] * ny - (sb * tf[g, 8] + cb * tf[g, 9])
                bx = cb * tf[g, 4] - sb * tf[g, 5]
                by = sb * tf[g, 4] + cb * tf[g, 5]
                La = tf[g, 14]
                wx = r0x + bx - Ax
                wy = r0y + by - Ay
                wu = wx * ux + wy * uy
                disc = wu * wu - (wx * wx + wy * wy) + La * La
                if disc <= 0.0:
                    fail[0] = NEED_GENERAL
                    break
                root = np.sqrt(disc)
                t = -wu + sg * root
                sinmu = sg * root * tf[g, 18]
                if abs(sinmu) < MEAS_MIN:
                    fail[0] = NEED_GENERAL
                    break
                quality[i, g] = sinmu
                Bx = r0x + t * ux + bx
                By = r0y + t * uy + by
                rax = Bx - Ax
                ray = By - Ay
                # τ u − ω_a ⊥ρa = A′ − V_k(B), then τ′ u − ε_a ⊥ρa = A″ − ω_a²ρa − W_k(B) − 2ω_kτ⊥u
                wk = d1[i, k2, 2]
                ek = d2[i, k2, 2]
                dBx = Bx - pose[i, k2, 0]
                dBy = By - pose[i, k2, 1]
                idet = -1.0 / (ux * rax + uy * ray)
                wx = Avx - (d1[i, k2, 0] - wk * dBy)
                wy = Avy - (d1[i, k2, 1] + wk * dBx)
                tau = (-wx * rax - ray * wy) * idet
                wa = (ux * wy - uy * wx) * idet
                wx = Aax - wa * wa * rax - (d2[i, k2, 0] - ek * dBy - wk * wk * dBx) + 2.0 * wk * tau * uy
                wy = Aay - wa * wa * ray - (d2[i, k2, 1] + ek * dBx - wk * wk * dBy) - 2.0 * wk * tau * ux
                ea = (ux * wy - uy * wx) * idet
                # body b: B′ = A′ + ω_a ⊥ρa, B″ = A″ + ε_a ⊥ρa − ω_a²ρa; r_b = B − A(θ_b)p_B
                _body_about(pose, d1, d2, i, cs, b, cb, sb, Bx, By, Avx - wa * ray, Avy + wa * rax,
                            Aax - ea * ray - wa * wa * rax, Aay + ea * rax - wa * wa * ray, wk, ek, tf[g, 4], tf[g, 5])
                ca = (rax * tf[g, 16] + ray * tf[g, 17]) * tf[g, 18]
                sa = (ray * tf[g, 16] - rax * tf[g, 17]) * tf[g, 18]
                pose[i, a, 2] = _atan2(ray, rax) - tf[g, 15]
            else:
                # ВПВ: a is the guide body G, b the slider S; both angles from the guide equation
                Sx, Sy, Svx, Svy, Sax, Say = _point(pose[i, k2, 0], pose[i, k2, 1], cs[k2, 0], cs[k2, 1], d1[i, k2, 0], d1[i, k2, 1],
                                                    d1[i, k2, 2], d2[i, k2, 0], d2[i, k2, 1], d2[i, k2, 2], tf[g, 4], tf[g, 5])
                rax = Sx - Ax
                ray = Sy - Ay
                iW = _inv_norm(rax, ray)
                if iW == 0.0:
                    fail[0] = NEED_GENERAL
                    break
                c = tf[g, 11] * iW
                if c >= 1.0 or c <= -1.0:
                    fail[0] = NEED_GENERAL
                    break
                sn = np.sqrt(1.0 - c * c)
                if sn < MEAS_MIN:
                    fail[0] = NEED_GENERAL
                    break
                quality[i, g] = sg * sn
                # θ_G = ψ − β + σ acos(K/|w|), ψ = atan2(w); θ_S = θ_G + α
                pose[i, a, 2] = _atan2(ray, rax) - tf[g, 12] + sg * np.arccos(c)
                pose[i, b, 2] = pose[i, a, 2] + tf[g, 8]
                cp = rax * iW
                sp = ray * iW
                cy = cp * c - sp * sg * sn
                sy = sp * c + cp * sg * sn
                ca = cy * tf[g, 13] + sy * tf[g, 14]
                sa = sy * tf[g, 13] - cy * tf[g, 14]
                cb = ca * tf[g, 9] - sa * tf[g, 10]
                sb = sa * tf[g, 9] + ca * tf[g, 10]
                ux = cb
                uy = sb
                # ω ⊥w + τ u = P_S′ − P_G′, then ε ⊥w + τ′ u = P_S″ − P_G″ + ω²w − 2ωτ⊥u
                idet = -1.0 / (ray * uy + rax * ux)
                wx = Svx - Avx
                wy = Svy - Avy
                wa = (wx * uy - ux * wy) * idet
                tau = (-ray * wy - rax * wx) * idet
                wx = Sax - Aax + wa * wa * rax + 2.0 * wa * tau * uy
                wy = Say - Aay + wa * wa * ray - 2.0 * wa * tau * ux
                ea = (wx * uy - ux * wy) * idet
                _body_about(pose, d1, d2, i, cs, b, cb, sb, Sx, Sy, Svx, Svy, Sax, Say, wa, ea, tf[g, 6], tf[g, 7])
            _body_about(pose, d1, d2, i, cs, a, ca, sa, Ax, Ay, Avx, Avy, Aax, Aay, wa, ea, tf[g, 2], tf[g, 3])
        if fail[0] != 0.0:
            fail[1] = i
            fail[2] = g
            return pose, d1, d2, quality, fail
    return pose, d1, d2, quality, fail


@njit(cache=True, error_model="numpy", inline="always")
def _body_about(pose, d1, d2, i, cs, b, c, s, Px, Py, Pvx, Pvy, Pax, Pay, w, e, px, py):
    """Pose and analogs of body b turning by (cos θ, sin θ) = (c, s), θ′ = w, θ″ = e about its
    point p (local) whose global position and analogs are P, P′, P″:
    r = P − u, r′ = P′ − w⊥u, r″ = P″ − e⊥u + w²u, u = A(θ)p (θ itself is set by the caller)."""
    ux = c * px - s * py
    uy = s * px + c * py
    pose[i, b, 0] = Px - ux
    pose[i, b, 1] = Py - uy
    d1[i, b, 0] = Pvx + w * uy
    d1[i, b, 1] = Pvy - w * ux
    d1[i, b, 2] = w
    d2[i, b, 0] = Pax + e * uy + w * w * ux
    d2[i, b, 1] = Pay - e * ux + w * w * uy
    d2[i, b, 2] = e
    cs[b, 0] = c
    cs[b, 1] = s


def _pivot_points(jb, jf, j, body):
    """(local point on ``body``, known body, local point on the known body) of revolute j."""
    if jb[j, 0] == body:
        return (jf[j, 0], jf[j, 1]), int(jb[j, 1]), (jf[j, 2], jf[j, 3])
    return (jf[j, 2], jf[j, 3]), int(jb[j, 0]), (jf[j, 0], jf[j, 1])


def build_tape(jt, jb, jf, gkind, gspec, gjoint, gnj, gbody):
    """Compile the groups into (top, tf) for :func:`run_tape`, or None when some group needs the
    general kernel (Newton, ПВП/ВПП, a forced dense path, a local point moving with q)."""
    ng = len(gkind)
    top = np.zeros((ng, NI), np.int64)
    tf = np.zeros((ng, NF))
    for g in range(ng):
        js = [int(j) for j in gjoint[g, :gnj[g]]]
        kind, spec = int(gkind[g]), [int(x) for x in gspec[g]]
        rod = None         # ВВВ with an actuator's rod: the inner joint's point on a moves with q
        for j in js:
            moving = jf[j, 4:8] if jt[j] == K.J_REV else jf[j, 6:10] if jt[j] == K.J_PRI else ()
            if np.any(np.asarray(moving) != 0.0):
                a_side = 4 if jb[j, 0] == spec[0] else 6
                if (kind != K.G_RRR or spec[5] != K.A_DYAD or j != spec[3]
                        or np.any(jf[j, 10 - a_side:12 - a_side] != 0.0)):
                    return None
                rod = (jf[j, a_side], jf[j, a_side + 1])
        if kind == K.G_LIN and spec[5] == K.A_SINGLE:
            body = int(gbody[g, 0])
            jr, jd = (js[0], js[1]) if jt[js[0]] == K.J_REV else (js[1], js[0])
            sgn, m = (1.0, int(jb[jd, 0])) if jb[jd, 1] == body else (-1.0, int(jb[jd, 1]))
            pb, k, pk = _pivot_points(jb, jf, jr, body)
            top[g, :5] = (OP_CRANK, body, 0, m, k)
            tf[g, :7] = (sgn, jf[jd, 0], jf[jd, 1], pk[0], pk[1], pb[0], pb[1])
            continue
        if spec[5] != K.A_DYAD or kind not in (K.G_RRR, K.G_RRP, K.G_RPR):
            return None
        a, b, jA, jI, jC = spec[:5]
        if kind == K.G_RPR:
            # a := the guide body G, b := the slider S of the prismatic jI
            G, S = int(jb[jI, 0]), int(jb[jI, 1])
            jG, jS = (jA, jC) if G == a else (jC, jA)
            pg, kG, pkG = _pivot_points(jb, jf, jG, G)
            ps, kS, pkS = _pivot_points(jb, jf, jS, S)
            al, e = jf[jI, 4], jf[jI, 5]
            nlx, nly = -math.sin(al), math.cos(al)
            lx, ly = jf[jI, 2] - ps[0], jf[jI, 3] - ps[1]
            rx, ry = math.cos(al) * lx - math.sin(al) * ly, math.sin(al) * lx + math.cos(al) * ly
            Kc = e + nlx * (jf[jI, 0] - pg[0]) + nly * (jf[jI, 1] - pg[1]) - (nlx * rx + nly * ry)
            beta = al + 0.5 * np.pi
            top[g, :5] = (OP_RPR, G, S, kG, kS)
            tf[g, :15] = (pkG[0], pkG[1], pg[0], pg[1], pkS[0], pkS[1], ps[0], ps[1],
                          al, math.cos(al), math.sin(al), Kc, beta, math.cos(beta), math.sin(beta))
            continue
        paA, ka, pkA = _pivot_points(jb, jf, jA, a)
        pIa, _, pIb = _pivot_points(jb, jf, jI, a)          # inner joint: point on a, point on b
        La = math.hypot(pIa[0] - paA[0], pIa[1] - paA[1])
        ba = math.atan2(pIa[1] - paA[1], pIa[0] - paA[0])
        if kind == K.G_RRR:
            pbC, kc, pkC = _pivot_points(jb, jf, jC, b)
            Lb = math.hypot(pIb[0] - pbC[0], pIb[1] - pbC[1])
            bb = math.atan2(pIb[1] - pbC[1], pIb[0] - pbC[0])
            if (La == 0.0 and rod is None) or Lb == 0.0:
                return None
            top[g, :6] = (OP_RRR, a, b, ka, kc, 0 if rod is None else 1)
            tf[g, :19] = (pkA[0], pkA[1], paA[0], paA[1], pkC[0], pkC[1], pbC[0], pbC[1], La, Lb,
                          ba, math.cos(ba), math.sin(ba), bb, math.cos(bb), math.sin(bb),
                          0.0, 1.0 / La if La else 0.0, 1.0 / Lb)
            if rod is not None:
                tf[g, 19:23] = (pIa[0], pIa[1], rod[0], rod[1])
            continue
        # ВВП: b on the prismatic jC to a known body kp (b the slider on kp's guide, or b the guide)
        al, e = jf[jC, 4], jf[jC, 5]
        if jb[jC, 1] == b:
            kp, pk, pb, se, off, case = int(jb[jC, 0]), jf[jC, 0:2], jf[jC, 2:4], e, al, 0
        else:
            kp, pk, pb, se, off, case = int(jb[jC, 1]), jf[jC, 2:4], jf[jC, 0:2], -e, -al, 1
        if La == 0.0:
            return None
        top[g, :6] = (OP_RRP, a, b, ka, kp, case)
        tf[g, :19] = (pkA[0], pkA[1], paA[0], paA[1], pIb[0], pIb[1], pk[0], pk[1], pb[0], pb[1],
                      se, off, math.cos(off), math.sin(off), La, ba, math.cos(ba), math.sin(ba), 1.0 / La)
    return top, tf
