"""Involute spur gearing with profile shift: vectorised closed forms (ГОСТ 16532-70, ГОСТ 13755).

Every function takes numpy arrays (or scalars) and broadcasts, so the blocking contour evaluates a
whole (x₁, x₂) grid in one call.  Lengths are in the unit of the module (mm in the note).

Sources: ГОСТ 16532-70 «Передачи зубчатые цилиндрические эвольвентные внешнего зацепления.
Расчёт геометрии»; Болотовский И. А. «Справочник по геометрическому расчёту эвольвентных
зубчатых и червячных передач»; Попов С. А., Тимофеев Г. А. «Курсовое проектирование по ТММ».
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Rack", "inv", "inv_inverse", "working_angle", "PairGeometry", "pair_geometry",
           "tooth_thickness", "base_thickness", "chordal", "span", "span_teeth", "x_from_chordal",
           "x_from_span", "xsum_from_centre_distance", "x_min_undercut", "rack_profile",
           "generated_flank", "sliding", "ring_tip_correction", "internal_checks", "dz_min_internal"]


@dataclass(frozen=True)
class Rack:
    """Basic rack (исходный контур), ГОСТ 13755-81 defaults: α = 20°, h_a* = 1, c* = 0,25,
    ρ_f* = 0,38."""

    alpha: float = math.radians(20.0)
    ha: float = 1.0
    c: float = 0.25
    rho_f: float = 0.38


def inv(a):
    """Involute function inv α = tg α − α."""
    return np.tan(a) - a


def inv_inverse(y, tol: float = 4e-16, max_iter: int = 60):
    """α with inv α = y (0 ≤ α < π/2), Newton on f(α) = tg α − α − y, f′ = tg²α.

    Start α₀ = (3y)^{1/3} (first term of the series inv α ≈ α³/3), which lies above the root
    (inv α > α³/3), so Newton decreases monotonically; iterate to machine precision.  A negative
    y (no real working angle: x_Σ too negative) gives NaN."""
    y = np.asarray(y, dtype=float)
    y = np.where(y >= 0, y, np.nan)
    a = np.minimum(np.cbrt(3.0 * y), 1.5)
    for _ in range(max_iter):
        t = np.tan(a)
        f = t - a - y
        d = np.where(t == 0.0, 1.0, t * t)
        step = np.where(t == 0.0, 0.0, f / d)
        a = a - step
        if np.all((np.abs(step) <= tol * np.maximum(np.abs(a), 1e-300)) | np.isnan(step)):
            break
    return a


def working_angle(z1, z2, x1, x2, alpha, internal: bool = False):
    """Working pressure angle α_w: inv α_w = 2(x₂ ± x₁) tg α /(z₂ ± z₁) + inv α (+ external,
    − internal: x_Σ = x₂ − x₁, z_Σ = z₂ − z₁), ГОСТ 16532-70 табл. 1 п. 2."""
    s = -1.0 if internal else 1.0
    zs = np.asarray(z2, float) + s * np.asarray(z1, float)
    xs = np.asarray(x2, float) + s * np.asarray(x1, float)
    return inv_inverse(2.0 * xs * math.tan(alpha) / zs + inv(alpha))


def tooth_thickness(m, z, x, alpha, d_y):
    """Circular tooth thickness on the circle d_y: s_y = d_y (s/d + inv α − inv α_y), cos α_y =
    d_b/d_y, s = m(π/2 + 2x tg α)."""
    d = m * np.asarray(z, float)
    s = m * (math.pi / 2 + 2.0 * np.asarray(x, float) * math.tan(alpha))
    ay = np.arccos(np.clip(d * math.cos(alpha) / d_y, -1.0, 1.0))
    return d_y * (s / d + inv(alpha) - inv(ay))


def base_thickness(m, z, x, alpha):
    """Tooth thickness on the base circle, s_b = m cos α (π/2 + 2x tg α + z inv α)
    (the involute relation written directly, Попов–Тимофеев)."""
    return m * math.cos(alpha) * (math.pi / 2 + 2.0 * np.asarray(x, float) * math.tan(alpha)
                                  + np.asarray(z, float) * inv(alpha))


def chordal(m, z, x, alpha, d_a, d_y=None):
    """Chordal thickness s̄_y = d_y sin ψ_y and height h̄_ay = (d_a − d_y cos ψ_y)/2 on the circle
    d_y (the pitch circle by default), ψ_y = s_y/d_y the half angular thickness."""
    d_y = m * np.asarray(z, float) if d_y is None else d_y
    psi = tooth_thickness(m, z, x, alpha, d_y) / d_y
    return d_y * np.sin(psi), (d_a - d_y * np.cos(psi)) / 2.0


def x_from_chordal(m, z, alpha, d_a, s_chord, h_chord):
    """Shift from a gear-tooth caliper measurement (worksheet 001, 2013-4).

    The measured chord's ends lie on the circle d_y with d_y cos ψ = d_a − 2h̄, d_y sin ψ = s̄, so
    tg ψ = s̄/(d_a − 2h̄), d_y = s̄/sin ψ; then s = d(ψ + inv α_y − inv α) and
    x = (s − πm/2)/(2m tg α).  Returns (x, s, ψ, d_y, α_y)."""
    psi = math.atan2(s_chord, d_a - 2.0 * h_chord)
    d_y = math.hypot(s_chord, d_a - 2.0 * h_chord)
    d = m * z
    ay = math.acos(d * math.cos(alpha) / d_y)
    s = d * (psi + float(inv(ay)) - float(inv(alpha)))
    return (s - math.pi * m / 2) / (2 * m * math.tan(alpha)), s, psi, d_y, ay


def span(m, z, x, alpha, k):
    """Common normal (span) over k teeth, W = m cos α [π(k − 0,5) + z inv α + 2x tg α]."""
    return m * math.cos(alpha) * (math.pi * (np.asarray(k, float) - 0.5) + np.asarray(z, float) * inv(alpha)
                                  + 2.0 * np.asarray(x, float) * math.tan(alpha))


def span_teeth(z, x, alpha) -> int:
    """Number of teeth in the span touching near the pitch circle of the shifted gear:
    k = z/π (tg α_x − 2x tg α/z − inv α) + 0,5, cos α_x = z cos α/(z + 2x), rounded."""
    ax = math.acos(z * math.cos(alpha) / (z + 2 * x))
    return max(1, int(round(z / math.pi * (math.tan(ax) - 2 * x * math.tan(alpha) / z - float(inv(alpha))) + 0.5)))


def x_from_span(m, z, alpha, k, W):
    """Shift from a measured span: x = [W/(m cos α) − π(k − 0,5) − z inv α]/(2 tg α)."""
    return (W / (m * math.cos(alpha)) - math.pi * (k - 0.5) - z * float(inv(alpha))) / (2 * math.tan(alpha))


def xsum_from_centre_distance(m, z1, z2, alpha, a_w, internal: bool = False):
    """x_Σ for a required centre distance: cos α_w = a cos α / a_w,
    x_Σ = (inv α_w − inv α) z_Σ /(2 tg α)."""
    zs = z2 - z1 if internal else z1 + z2
    a = m * zs / 2
    aw = math.acos(a * math.cos(alpha) / a_w)
    return (float(inv(aw)) - float(inv(alpha))) * zs / (2 * math.tan(alpha))


def x_min_undercut(z, rack: Rack):
    """Least shift without undercut by the rack: x_min = h_a* − z sin²α /2
    (= h_a*(z_min − z)/z_min with z_min = 2h_a*/sin²α)."""
    return rack.ha - np.asarray(z, float) * math.sin(rack.alpha) ** 2 / 2


@dataclass
class PairGeometry:
    """Geometry of a pair (arrays broadcast over x₁, x₂).  Radii of curvature ρ are measured along
    the line of action from the tangency points N₁ (gear 1) and N₂ (gear 2)."""

    m: float
    z1: float
    z2: float
    x1: np.ndarray
    x2: np.ndarray
    rack: Rack
    internal: bool
    alpha_w: np.ndarray
    a: float
    a_w: np.ndarray
    y: np.ndarray
    dy: np.ndarray
    d1: float
    d2: float
    db1: float
    db2: float
    dw1: np.ndarray
    dw2: np.ndarray
    da1: np.ndarray
    da2: np.ndarray
    df1: np.ndarray
    df2: np.ndarray
    h: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    sa1: np.ndarray
    sa2: np.ndarray
    eps: np.ndarray          # ε_α by the angles (arc) formula
    eps_line: np.ndarray     # ε_α by the active length of the line of action
    g: np.ndarray            # N₁N₂ = a_w sin α_w
    rho_a1: np.ndarray       # tip of gear 1 on the line of action (from N₁)
    rho_p1: np.ndarray       # lower active point of gear 1 (= g − ρ_a2)
    rho_l1: np.ndarray       # boundary point of the involute of gear 1 (from the rack)
    rho_a2: np.ndarray
    rho_p2: np.ndarray
    rho_l2: np.ndarray

    @property
    def p(self) -> float:
        """The pitch p = πm (domain.md § 1.7)."""
        return math.pi * self.m

    @property
    def pb(self) -> float:
        """The base pitch p_b = πm cos α (domain.md § 1.7)."""
        return math.pi * self.m * math.cos(self.rack.alpha)

    @property
    def u(self) -> float:
        """The gear ratio u = z₂/z₁."""
        return self.z2 / self.z1


def pair_geometry(m, z1, z2, x1, x2, rack: Rack = Rack(), internal: bool = False) -> PairGeometry:
    """All the dimensions of ГОСТ 16532-70 табл. 1 for an external pair; for an internal pair
    (gear 2 the ring, ГОСТ 19274-73) the ring's tip and root are d_a2 = d₂ − 2(h_a* − x₂ − Δ)m
    with the correction Δ of ``ring_tip_correction``, d_f2 = d₂ + 2(h_a* + c* + x₂)m, and Δy = 0.

    ε_α (arc):  [z₁(tg α_a1 − tg α_w) ± z₂(tg α_a2 − tg α_w)]/(2π);
    ε_α (line): (ρ_a1 − ρ_p1)/p_b, the active length of N₁N₂ over the base pitch."""
    al = rack.alpha
    x1 = np.asarray(x1, float)
    x2 = np.asarray(x2, float)
    sg = -1.0 if internal else 1.0
    aw = working_angle(z1, z2, x1, x2, al, internal)
    d1, d2 = m * z1, m * z2
    db1, db2 = d1 * math.cos(al), d2 * math.cos(al)
    a = m * (z2 + sg * z1) / 2
    a_w = a * math.cos(al) / np.cos(aw)
    y = (a_w - a) / m
    dy = np.zeros_like(y) if internal else x1 + x2 - y
    da1 = d1 + 2 * (rack.ha + x1 - dy) * m
    df1 = d1 - 2 * (rack.ha + rack.c - x1) * m
    if internal:
        da2 = d2 - 2 * (rack.ha - x2 - ring_tip_correction(z2, x2, rack)) * m + 0 * x1
        df2 = d2 + 2 * (rack.ha + rack.c + x2) * m + 0 * x1
    else:
        da2 = d2 + 2 * (rack.ha + x2 - dy) * m
        df2 = d2 - 2 * (rack.ha + rack.c - x2) * m
    h = (da1 - df1) / 2
    s1 = m * (math.pi / 2 + 2 * x1 * math.tan(al))
    s2 = m * (math.pi / 2 + sg * 2 * x2 * math.tan(al))
    sa1 = tooth_thickness(m, z1, x1, al, da1)
    # the ring's tooth at its tip: space width of the external gear of the same shift
    sa2 = (tooth_thickness(m, z2, x2, al, da2) if not internal
           else math.pi * da2 / z2 - tooth_thickness(m, z2, x2, al, da2))
    ta1 = np.sqrt(np.maximum((da1 / db1) ** 2 - 1, 0))
    ta2 = np.sqrt(np.maximum((da2 / db2) ** 2 - 1, 0))
    tw = np.tan(aw)
    eps = (z1 * (ta1 - tw) + sg * z2 * (ta2 - tw)) / (2 * math.pi)
    g = a_w * np.sin(aw)
    rho_a1 = db1 / 2 * ta1
    rho_a2 = db2 / 2 * ta2
    rho_p1 = g - rho_a2 if not internal else rho_a2 - g
    rho_p2 = g - rho_a1 if not internal else rho_a1 + g
    pb = math.pi * m * math.cos(al)
    eps_line = (rho_a1 - rho_p1) / pb
    sa = math.sin(al)
    rho_l1 = d1 / 2 * sa - (rack.ha - x1) * m / sa
    rho_l2 = d2 / 2 * sa - (rack.ha - x2) * m / sa if not internal else d2 / 2 * sa + (rack.ha + x2) * m / sa
    return PairGeometry(m, z1, z2, x1, x2, rack, internal, aw, a, a_w, y, dy, d1, d2, db1, db2,
                        d1 * math.cos(al) / np.cos(aw), d2 * math.cos(al) / np.cos(aw), da1, da2, df1,
                        df2, h, s1, s2, sa1, sa2, eps, eps_line, g, rho_a1, rho_p1, rho_l1, rho_a2,
                        rho_p2, rho_l2)


def ring_tip_correction(z2, x2, rack: Rack):
    """Correction Δ of the ring's tip diameter d_a2 = d₂ − 2(h_a* − x₂ − Δ)m (ГОСТ 19274-73).

    The ring's tip circle passes through the boundary point of its involute generated by the
    basic rack, where the rack's line at the depth h = (h_a* − x₂)m crosses the line of action:
    ρ_l = r₂ sin α − h/sin α, r_l² = r_b2² + ρ_l² = r₂² − 2r₂h + h²/sin²α; Δ = (r_l − r₂ + h)/m.
    Its second-order expansion is Δ ≈ (h_a* − x₂)²/(z₂ tg²α), for α = 20°, h_a* = 1, x₂ = 0 the
    handbook's Δ = 7,55/z₂ (d_a2 = d₂ − 2m + 15,2m/z₂).  Taking the exact value the ring's tip
    reaches the pinion's involute boundary exactly when x₁ = x₂ (the rack limit).  Zero when
    x₂ ≥ h_a*."""
    z2 = np.asarray(z2, float)
    h = np.maximum(rack.ha - np.asarray(x2, float), 0.0)          # in modules
    r2 = z2 / 2
    sa = math.sin(rack.alpha)
    rl = np.sqrt(np.maximum(r2 * r2 - 2 * r2 * h + h * h / sa ** 2, 0.0))
    return rl - r2 + h


def internal_checks(geo: PairGeometry) -> dict[str, np.ndarray]:
    """Checks of an internal pair (ГОСТ 19274-73, Болотовский «Справочник…», разд. «Внутреннее
    зацепление»), arrays over the shifts; each entry is a margin, ≥ 0 when the condition holds:

    * ``base``: r_a2 − r_b2, the ring's tip on its involute (tip circle outside the base circle);
    * ``pinion_root``: ρ_p1 − ρ_l1, the ring's tip does not reach the pinion's fillet
      (interference at the pinion root);
    * ``ring_root``: ρ_l2 − ρ_p2, the pinion's tip stays on the ring's involute;
    * ``trochoid``: interference of the tips (трохоидальная интерференция) outside the line of
      action, z₁(inv α_a1 + δ₁) + (z₂ − z₁) inv α_w − z₂(inv α_a2 + δ₂), where δ₁, δ₂ are the
      angles at O₁ and O₂ to the crossing point M of the tip circles:
      cos δ₁ = (r_a2² − r_a1² − a_w²)/(2 r_a1 a_w), cos δ₂ = (r_a2² + a_w² − r_a1²)/(2 r_a2 a_w)."""
    ra1, ra2, aw = geo.da1 / 2, geo.da2 / 2, geo.a_w
    d1 = np.arccos(np.clip((ra2 ** 2 - ra1 ** 2 - aw ** 2) / (2 * ra1 * aw), -1, 1))
    d2 = np.arccos(np.clip((ra2 ** 2 + aw ** 2 - ra1 ** 2) / (2 * ra2 * aw), -1, 1))
    aa1 = np.arccos(np.clip(geo.db1 / geo.da1, -1, 1))
    aa2 = np.arccos(np.clip(geo.db2 / geo.da2, -1, 1))
    tro = geo.z1 * (inv(aa1) + d1) + (geo.z2 - geo.z1) * inv(geo.alpha_w) - geo.z2 * (inv(aa2) + d2)
    return {"base": ra2 - geo.db2 / 2, "pinion_root": geo.rho_p1 - geo.rho_l1,
            "ring_root": geo.rho_l2 - geo.rho_p2, "trochoid": tro}


def dz_min_internal(z1: int, x1: float, x2: float, rack: Rack = Rack(), eps_min: float = 1.0,
                    z2_max: int = 400) -> int | None:
    """Least z₂ − z₁ of an internal pair with the given pinion and shifts for which every check
    of ``internal_checks`` holds and ε_α ≥ eps_min (enumeration over z₂; None if none up to
    z2_max)."""
    z2 = np.arange(z1 + 1, z2_max + 1)
    geo = pair_geometry(1.0, z1, z2.astype(float), x1 + 0 * z2, x2 + 0 * z2, rack, internal=True)
    ok = np.isfinite(geo.eps) & (geo.eps >= eps_min)
    for v in internal_checks(geo).values():
        ok &= v >= -1e-9 * geo.m
    # the conditions are monotone in z₂ for the usual shifts; take the first z₂ from which all hold
    bad = np.nonzero(~ok)[0]
    first = 0 if not bad.size else bad[-1] + 1
    return int(z2[first] - z1) if first < z2.size else None


def sliding(geo: PairGeometry, rho1):
    """Specific sliding at the contact point ρ₁ (from N₁) of an external pair, u = z₂/z₁:
    ρ₂ = N₁N₂ − ρ₁, λ₁ = 1 − ρ₂/(u ρ₁), λ₂ = 1 − u ρ₁/ρ₂ (Попов–Тимофеев); for an internal pair
    ρ₂ = ρ₁ + N₁N₂ and the signs of the relative rolling follow.  Sliding velocity per unit ω₁:
    v_s/ω₁ = (1 ± 1/u)|PK| with PK = ρ₁ − ρ_P (+ external, − internal).
    Returns (λ₁, λ₂, v_s/ω₁)."""
    rho1 = np.asarray(rho1, float)
    u = geo.u
    g = geo.g
    if geo.internal:
        rho2 = rho1 + g
    else:
        rho2 = g - rho1
    with np.errstate(divide="ignore", invalid="ignore"):
        lam1 = 1 - rho2 / (u * rho1)
        lam2 = 1 - u * rho1 / rho2
    rho_P = geo.dw1 / 2 * np.sin(geo.alpha_w)
    vs = (1 + (-1 if geo.internal else 1) / u) * np.abs(rho1 - rho_P)
    return lam1, lam2, vs


# ----------------------------------------------------------------------------------- drawing
def rack_profile(m: float, rack: Rack, n: int = 40):
    """Right flank of one tooth of the generating rack from the middle of its tip to its root:
    points (u, h) with u across the rack (from the tooth axis) and h the depth below the datum
    line toward the gear, and the unit normals (pointing out of the rack tooth)."""
    al, ca, ta = rack.alpha, math.cos(rack.alpha), math.tan(rack.alpha)
    rho = rack.rho_f * m
    hc = (rack.ha + rack.c) * m - rho          # centre of the tip rounding
    uc = math.pi * m / 4 - hc * ta - rho / ca
    # tip flat: u from 0 to uc at depth h = (ha + c) m, normal pointing toward the gear (+h)
    u0 = np.linspace(0.0, max(uc, 0.0), max(2, n // 4))
    pts = [np.column_stack([u0, np.full_like(u0, (rack.ha + rack.c) * m)])]
    nrm = [np.column_stack([np.zeros_like(u0), np.ones_like(u0)])]
    # rounding arc from the tip direction (normal (0,1)) to the flank normal (cos α, sin α)·…
    th = np.linspace(0.0, math.pi / 2 - al, n)
    nv = np.column_stack([np.sin(th), np.cos(th)])
    pts.append(np.column_stack([uc + rho * nv[:, 0], hc + rho * nv[:, 1]]))
    nrm.append(nv)
    # straight flank from the tangency point up to the rack root (h = −(ha + c) m)
    h_t = hc + rho * math.sin(al)
    hs = np.linspace(h_t, -(rack.ha + rack.c) * m, n)
    pts.append(np.column_stack([math.pi * m / 4 - hs * ta, hs]))
    nrm.append(np.tile([ca, math.sin(al)], (n, 1)))
    return np.vstack(pts), np.vstack(nrm)


def generated_flank(m: float, z: int, x: float, rack: Rack, r_tip: float, n: int = 40):
    """One flank of a tooth generated by the rack (envelope by the meshing condition: the
    common normal passes through the pitch point), in the gear frame: polar (r, θ) with θ
    measured from the axis of the tooth space.  The involute part is exact; the fillet is the
    envelope of the rack tip rounding.  Points beyond the tip circle are dropped."""
    r = m * z / 2
    P, N = rack_profile(m, rack, n)
    u, h = P[:, 0], P[:, 1]
    nu, nh = N[:, 0], N[:, 1]
    # fixed frame: gear centre at the origin, pitch point (0, r), rack datum line at Y = r + x m,
    # rack point Q = (u + s, r + x m − h); the normal (nu, −nh) must pass through (0, r)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(np.abs(nh) > 1e-14, -(x * m - h) * nu / nh - u, -u)
    X = u + s
    Y = r + x * m - h
    phi = s / r      # the gear turned clockwise by s/r while the rack moved by s
    c, sn = np.cos(phi), np.sin(phi)
    gx = c * X - sn * Y
    gy = sn * X + c * Y
    rr = np.hypot(gx, gy)
    th = np.arctan2(gx, gy)     # from the +y axis (the tooth space axis), clockwise positive
    keep = rr <= r_tip
    return rr[keep], th[keep]
