"""Velocities in the mechanism with a cross-slider (крестовина) at one position, in closed form.

Link 1 translates with v_A along a direction at the angle γ to the line O₁B; its slider 2 at B
slides along the rocker 3 (pivot O₁); the cross 4 slides along the rocker 3 (through O₁) and the
rocker 5 (pivot O₂) with its two perpendicular slots, so O₁C ⊥ O₂C: C lies on the circle with
diameter O₁O₂ (Thales), l_O₁C = l_O₁O₂·cos α, l_O₂C = l_O₁O₂·sin α (α the angle at O₁), and C is
on the extension of BO₁ beyond O₁.  Plans of velocities (Артоболевский, § 9; Попов, Тимофеев, гл. 2):
v_B3 = v_B2 + v_B3B2 (v_B3 ⊥ O₁B, v_B3B2 ∥ O₁B) → ω₃ = v_A sin γ / l_O₁B; the right angle at C
is kept, so ω₅ = ω₃ (absolute, same sense); v_C4 = v_C3 + v_C4C3 = v_C5 + v_C4C5 with the slots
perpendicular gives v_C4 = v_C3 + v_C5 (orthogonal), |v_C4| = ω₃·l_O₁O₂ (C runs on the Thales
circle at 2ω₃).  The force reduced to link 1 from the moment M on the shaft O₂, by equal powers:
F_пр = M·ω₅ / v_A."""
from __future__ import annotations

import math

import numpy as np

__all__ = ["solve"]


def _perp(v):
    return np.array([-v[1], v[0]])


def solve(v_A: float, gamma: float, l_O1B: float, l_O1O2: float, alpha: float, M: float) -> dict:
    """Points, velocity vectors and the reduced force; O₁ at the origin, O₂ on +x, C above."""
    O1, O2 = np.zeros(2), np.array([l_O1O2, 0.0])
    uC = np.array([math.cos(alpha), math.sin(alpha)])
    l_O1C, l_O2C = l_O1O2 * math.cos(alpha), l_O1O2 * math.sin(alpha)
    C = l_O1C * uC
    B = -l_O1B * uC
    uB = -uC
    v1 = v_A * (math.cos(gamma) * uB + math.sin(gamma) * _perp(uB))
    r = B - O1
    w3 = float(r[0] * v1[1] - r[1] * v1[0]) / l_O1B ** 2   # (r × v)_z / r²
    vB3 = w3 * _perp(B - O1)
    vB3B2 = vB3 - v1
    w5 = w3
    vC3, vC5 = w3 * _perp(C - O1), w5 * _perp(C - O2)
    vC4 = vC3 + vC5
    return dict(O1=O1, O2=O2, B=B, C=C, v1=v1, w3=w3, w5=w5, vB3=vB3, vB3B2=vB3B2, vC3=vC3, vC5=vC5,
                vC4=vC4, l_O1C=l_O1C, l_O2C=l_O2C, F_red=M * abs(w5) / v_A,
                v_B3=float(np.hypot(*vB3)), v_B3B2=float(np.hypot(*vB3B2)), v_C3=float(np.hypot(*vC3)),
                v_C5=float(np.hypot(*vC5)), v_C4=float(np.hypot(*vC4)))
