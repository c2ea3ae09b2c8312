"""Centrifugal governor (Porter type) in quasi-static equilibrium with friction in its joints.

Right half in the plane rotating with the shaft (axis x = 0, y up): the arm 6 is hinged to the
shaft cross-piece 7 at H = (e_H, 0) and hangs at the angle θ from the vertical; the rod 3 joins
F on the arm (HF) to B on the sleeve 2 (B = (e_B, y_B), below F); the ball of mass m at D on the
arm line (HD).  The left half is the mirror image.  By d'Alembert the ball carries the
centrifugal force F_и = m·x_D·ω² (outwards) and its weight; the sleeve carries Q = m₂g.

Friction in a revolute joint (Артоболевский, § 16; Попов, Тимофеев, гл. 5): the reaction is
tangent to the friction circle of radius ρ = r·sin φ_тр = r·f/√(1 + f²) (φ_тр = arctg f), on the
side where its moment about the joint centre opposes the relative rotation:
M_C(R_ji) = −sgn(ω_ij)·ρ·|R_ji| (R_ji: on link i from link j).  The relative angular velocities
come from the exact velocity analysis of the half (dφ₆/dθ = 1, dφ₃/dθ from the loop closure),
times the sense of the slow speed change (s = +1 speeding up, −1 slowing down, 0 no friction).

Equilibrium, in closed form:
- rod 3 (weightless, two forces): (F − B) × R₂₃ = −(s_B + s_F)·ρ·|R|, i.e. the line of action is
  turned by α from BF with sin α = (s_B + s_F)ρ/l_BF (both circles on opposite sides: sin α = 2ρ/l);
- sleeve 2: two mirror reactions carry Q: R₃₂,y = Q/2;
- arm 6: R₇₆ = −(R₃₆ + G + F_и·e_x) and the moment about H
  A + B·F_и = s_H·ρ·|R₃₆ + G + F_и·e_x| (A: moments of the known forces, B = y_H − y_D),
  a quadratic in F_и after squaring; the root with the right sign of both sides is kept.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["friction_radius", "geometry", "solve"]


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def friction_radius(f: float, r: float) -> float:
    """ρ = r·sin(arctg f) = r·f/√(1 + f²)."""
    return r * f / math.sqrt(1.0 + f * f)


def geometry(e_H: float, e_B: float, l_HF: float, l_HD: float, l_BF: float, theta: float) -> dict:
    """Points H, F, D, B of the right half and the rates dφ₆/dθ, dφ₃/dθ, dy_B/dθ."""
    H = np.array([e_H, 0.0])
    u = np.array([math.sin(theta), -math.cos(theta)])
    F, D = H + l_HF * u, H + l_HD * u
    dx = F[0] - e_B
    if abs(dx) >= l_BF:
        raise ValueError("rod BF shorter than the horizontal distance from F to the sleeve joint")
    B = np.array([e_B, F[1] - math.sqrt(l_BF ** 2 - dx ** 2)])
    BF = F - B
    dF = l_HF * np.array([math.cos(theta), math.sin(theta)])
    dyB = float(BF @ dF) / BF[1]          # (F − B)·(dF − dB) = 0, dB = (0, dy_B)
    dphi3 = _cross(BF, dF - np.array([0.0, dyB])) / l_BF ** 2
    return dict(H=H, F=F, D=D, B=B, dphi6=1.0, dphi3=dphi3, dyB=dyB)


def _line_point(C, R, M) -> np.ndarray:
    """A point of the line of action of force R whose moment about C is M."""
    e = R / np.hypot(*R)
    return C + (M / np.hypot(*R)) * np.array([e[1], -e[0]])


def _meet(p, d, q, e) -> np.ndarray:
    """Intersection of the lines p + t·d and q + s·e."""
    t = _cross(q - p, e) / _cross(d, e)
    return p + t * d


def solve(geo: dict, Q: float, m: float, g: float, rho: float, s: int) -> dict:
    """Forces and ω of the half with friction sense s (+1, −1 or 0)."""
    H, F, D, B = geo["H"], geo["F"], geo["D"], geo["B"]
    w6, w3 = s * geo["dphi6"], s * geo["dphi3"]     # absolute angular rates; 2 and 7 do not turn
    sB, sF, sH = np.sign(w3 - 0.0), np.sign(w3 - w6), np.sign(w6 - 0.0)   # ω₃₂, ω₃₆, ω₆₇
    if s == 0:
        rho = 0.0
    l = float(np.hypot(*(F - B)))
    k = -(sB + sF) * rho / l
    phi = math.atan2(F[1] - B[1], F[0] - B[0])
    R23 = None
    for gam in (phi + math.asin(k), phi + math.pi - math.asin(k)):
        e = np.array([math.cos(gam), math.sin(gam)])
        R = -0.5 * Q / e[1]                          # R₃₂,y = −R₂₃,y = Q/2
        if R > 0:
            R23 = R * e
            break
    R36 = R23.copy()                                 # the rod transmits its one force
    M_F6 = -np.sign(w6 - w3) * rho * R               # friction moment at F on the arm
    G = np.array([0.0, -m * g])
    P = R36 + G
    A = _cross(F - H, R36) + M_F6 + _cross(D - H, G)
    Bc = _cross(D - H, np.array([1.0, 0.0]))
    if rho == 0.0:
        Fi = -A / Bc
    else:
        a, b, c = Bc * Bc - rho * rho, 2 * A * Bc - 2 * rho * rho * P[0], A * A - rho * rho * float(P @ P)
        cands = [r.real for r in np.roots([a, b, c]) if abs(r.imag) < 1e-12 * (1 + abs(r.real)) and r.real > 0]
        res = [abs(A + Bc * x - sH * rho * math.hypot(P[0] + x, P[1])) for x in cands]
        Fi = cands[int(np.argmin(res))]
    Fv = np.array([Fi, 0.0])
    R76 = -(P + Fv)
    M_H = -sH * rho * float(np.hypot(*R76))
    omega = math.sqrt(Fi / (m * D[0]))
    # lines of action: the rod's, P's (through the meeting of the rod line and the weight's
    # vertical through D), the three-force point K on the horizontal through D, R₇₆ through K
    pF = _line_point(F, R36, M_F6)
    Qp = _meet(pF, R36, D, np.array([0.0, 1.0]))
    K = _meet(Qp, P, D, np.array([1.0, 0.0]))
    return dict(rho=rho, alpha=math.asin(abs(k)), R=R, R23=R23, R36=R36, G=G, P=P, F_i=Fi, R76=R76,
                M_F6=M_F6, M_H=M_H, omega=omega, r_D=float(D[0]), K=K, Q_point=Qp, rod_point=pF,
                R76_angle=math.atan2(abs(R76[1]), abs(R76[0])), signs=(int(sB), int(sF), int(sH)))
