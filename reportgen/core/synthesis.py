"""Kinematic synthesis of linkages by the time-ratio coefficient K (closed forms, no iteration).

The classic construction (Артоболевский, «Теория механизмов и машин», §§ 25–26; Попов С. А.,
Тимофеев Г. А., «Курсовое проектирование по ТММ», гл. 2): the crank of a mechanism with
time-ratio coefficient K turns between the two extreme positions of the output link through
180° + θ (working stroke) and 180° − θ (return), θ = 180°·(K − 1)/(K + 1).  In the extreme
positions the crank and the coupler are collinear, so the crank centre O sees the two extreme
positions B₁, B₂ of the coupler's end under the angle θ: O lies on a circle through B₁ and B₂
(the «θ-circle», radius R = |B₁B₂|/(2 sin θ), its centre on the perpendicular bisector at the
distance R·cos θ from the chord, on the side of O).  With |OB₁| = b − a (folded) and
|OB₂| = a + b (extended):

    a = (|OB₂| − |OB₁|)/2,   b = (|OB₂| + |OB₁|)/2.

Each function returns every solution variant (a list of dicts of floats in SI, angles in
radians); the caller chooses one.  Pure numpy-free float arithmetic: the results are exact to
rounding.
"""
from __future__ import annotations

import math

__all__ = ["theta_of_K", "K_of_theta", "theta_circles", "crank_from_extremes", "crank_rocker",
           "slider_crank", "slotted_lever", "six_bar", "transmission_min"]

_EPS = 1e-12


def theta_of_K(K: float) -> float:
    """θ = π·(K − 1)/(K + 1) — the angle between the crank's positions at the two extreme
    positions of the output link (the «угол перекрытия»)."""
    return math.pi * (K - 1.0) / (K + 1.0)


def K_of_theta(theta: float) -> float:
    """K = (π + θ)/(π − θ)."""
    return (math.pi + theta) / (math.pi - theta)


def theta_circles(b1, b2, theta: float) -> list[tuple[float, float, float]]:
    """The two circles (xc, yc, R) through b1, b2 from whose major arcs the chord b1b2 is seen
    under the inscribed angle θ (0 < θ < π): R = |b1b2|/(2 sin θ), centre on the perpendicular
    bisector at ±R·cos θ from the chord's midpoint."""
    (x1, y1), (x2, y2) = b1, b2
    ch = math.hypot(x2 - x1, y2 - y1)
    R = ch / (2.0 * math.sin(theta))
    mx, my = 0.5 * (x1 + x2), 0.5 * (y1 + y2)
    nx, ny = -(y2 - y1) / ch, (x2 - x1) / ch
    h = R * math.cos(theta)
    return [(mx + s * h * nx, my + s * h * ny, R) for s in (1.0, -1.0)]


def _inscribed(o, b1, b2) -> float:
    """The angle b1-o-b2 in [0, π]."""
    ux, uy = b1[0] - o[0], b1[1] - o[1]
    vx, vy = b2[0] - o[0], b2[1] - o[1]
    return math.atan2(abs(ux * vy - uy * vx), ux * vx + uy * vy)


def _circle_line(c, p0, d) -> list[tuple[float, float]]:
    """Intersections of the circle c = (xc, yc, R) with the line p0 + t·d (|d| = 1)."""
    xc, yc, R = c
    fx, fy = p0[0] - xc, p0[1] - yc
    bq = fx * d[0] + fy * d[1]
    disc = bq * bq - (fx * fx + fy * fy - R * R)
    if disc < -_EPS * R * R:
        return []
    r = math.sqrt(max(disc, 0.0))
    ts = (-bq - r, -bq + r) if r > 0 else (-bq,)
    return [(p0[0] + t * d[0], p0[1] + t * d[1]) for t in ts]


def _circle_circle(c1, c2) -> list[tuple[float, float]]:
    """Intersections of two circles (xc, yc, R)."""
    x1, y1, r1 = c1
    x2, y2, r2 = c2
    dx, dy = x2 - x1, y2 - y1
    d = math.hypot(dx, dy)
    if d < _EPS or d > r1 + r2 + _EPS * d or d < abs(r1 - r2) - _EPS * d:
        return []
    a = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    h = math.sqrt(max(r1 * r1 - a * a, 0.0))
    px, py = x1 + a * dx / d, y1 + a * dy / d
    pts = [(px - h * dy / d, py + h * dx / d)]
    if h > 0:
        pts.append((px + h * dy / d, py - h * dx / d))
    return pts


def crank_from_extremes(o, b1, b2) -> dict:
    """Crank a and coupler b of the four-bar whose crank centre is o and whose coupler end
    takes the extreme positions b1, b2: a = |(|ob₂| − |ob₁|)|/2, b = (|ob₁| + |ob₂|)/2.
    ``far``/``near`` name the extreme with the extended (a + b) and the folded (b − a) dyad;
    ``phi_far``/``phi_near`` are the crank's angles there (from the x axis)."""
    r1 = math.hypot(b1[0] - o[0], b1[1] - o[1])
    r2 = math.hypot(b2[0] - o[0], b2[1] - o[1])
    far, near = (b2, b1) if r2 >= r1 else (b1, b2)
    a, b = abs(r2 - r1) / 2.0, (r1 + r2) / 2.0
    phi_far = math.atan2(far[1] - o[1], far[0] - o[0])
    phi_near = math.atan2(o[1] - near[1], o[0] - near[0])
    return dict(a=a, b=b, x_O=o[0], y_O=o[1], x_far=far[0], y_far=far[1], x_near=near[0],
                y_near=near[1], phi_far=phi_far, phi_near=phi_near, theta_check=_inscribed(o, b1, b2))


def _crank_centres(b1, b2, theta: float, locus) -> list[tuple[float, float]]:
    """Crank centres seeing b1b2 under θ on the locus ("circle", (xc, yc, R)) or
    ("line", p0, unit direction).  θ = 0 (K = 1): the centre lies on the line b1b2."""
    kind = locus[0]
    if theta < _EPS:
        d = (b2[0] - b1[0], b2[1] - b1[1])
        n = math.hypot(*d)
        line = (b1, (d[0] / n, d[1] / n))
        if kind == "circle":
            pts = _circle_line(locus[1], *line)
        else:
            p0, u = locus[1], locus[2]
            den = u[0] * line[1][1] - u[1] * line[1][0]
            if abs(den) < _EPS:
                return []
            t = ((b1[0] - p0[0]) * line[1][1] - (b1[1] - p0[1]) * line[1][0]) / den
            pts = [(p0[0] + t * u[0], p0[1] + t * u[1])]
        # outside the segment b1b2 (else the coupler end would pass between the extremes)
        return [p for p in pts if (p[0] - b1[0]) * (p[0] - b2[0]) + (p[1] - b1[1]) * (p[1] - b2[1]) > 0]
    out = []
    for circ in theta_circles(b1, b2, theta):
        pts = _circle_circle(circ, locus[1]) if kind == "circle" else _circle_line(circ, locus[1], locus[2])
        for p in pts:
            if abs(_inscribed(p, b1, b2) - theta) < 1e-9:
                out.append(p)
    return out


def _sorted_variants(vs: list[dict]) -> list[dict]:
    vs.sort(key=lambda v: (round(v["y_O"], 12), round(v["x_O"], 12)))
    for i, v in enumerate(vs, 1):
        v["variant"] = i
    return vs


def crank_rocker(K: float, psi: float, c: float, *, d: float | None = None,
                 line_y: float | None = None) -> list[dict]:
    """Crank-rocker OABC from the rocker swing ψ, the rocker length c = |CB| and either the
    centre distance d = |OC| or the height ``line_y`` of a line (parallel to the chord B₁B₂)
    on which O lies.  The rocker pivot C is the origin, its extreme positions are symmetric
    about the y axis: B₁,₂ = c·(∓sin(ψ/2), cos(ψ/2)).  Returns every variant: a, b, the crank
    centre (x_O, y_O) and d = |OC|."""
    h = psi / 2.0
    b1 = (-c * math.sin(h), c * math.cos(h))
    b2 = (c * math.sin(h), c * math.cos(h))
    theta = theta_of_K(K)
    if d is not None:
        locus = ("circle", (0.0, 0.0, d))
    else:
        locus = ("line", (0.0, line_y), (1.0, 0.0))
    vs = []
    for o in _crank_centres(b1, b2, theta, locus):
        v = crank_from_extremes(o, b1, b2)
        v.update(d=math.hypot(*o), c=c, psi=psi, theta=theta, K=K, x_B1=b1[0], y_B1=b1[1],
                 x_B2=b2[0], y_B2=b2[1])
        vs.append(v)
    return _sorted_variants(vs)


def slider_crank(K: float, H: float, *, e: float | None = None, lam: float | None = None) -> list[dict]:
    """Offset slider-crank from the stroke H, K and the offset e (or λ = a/b).

    In the triangle O C₁ C₂ (sides b − a, b + a, H, angle θ at O):
    H² = 2(a² + b²) − 2(b² − a²)·cos θ and H·e = (b² − a²)·sin θ, hence with P = b² − a²,
    S = a² + b² = (H² + 2P cos θ)/2: a² = (S − P)/2, b² = (S + P)/2; from λ:
    b = H/√(2(1 + λ²) − 2(1 − λ²) cos θ).  The guide is the x axis, the crank centre is at
    (0, −e); the slider's extreme positions are x = √((b ∓ a)² − e²)."""
    theta = theta_of_K(K)
    ct, st = math.cos(theta), math.sin(theta)
    if lam is not None:
        b = H / math.sqrt(2 * (1 + lam * lam) - 2 * (1 - lam * lam) * ct)
        a = lam * b
        e = (b * b - a * a) * st / H
    else:
        P = H * e / st if st > _EPS else None
        if P is None:          # K = 1: θ = 0, H = 2a, any b > a + e (λ or e alone does not fix b)
            raise ValueError("K = 1 needs lam")
        S = (H * H + 2 * P * ct) / 2
        if S - P < -_EPS * S:
            return []
        a, b = math.sqrt(max(S - P, 0.0) / 2), math.sqrt((S + P) / 2)
    if b - a <= e:
        return []
    x1, x2 = math.sqrt((b - a) ** 2 - e * e), math.sqrt((b + a) ** 2 - e * e)
    # extended dyad at C₂ (crank along OC₂), folded at C₁ (crank pointing away from C₁)
    return [dict(a=a, b=b, e=e, lam=a / b, H=x2 - x1, theta=theta, K=K, x_C1=x1, x_C2=x2, x_O=0.0, y_O=-e,
                 phi_far=math.atan2(e, x2), phi_near=math.atan2(-e, -x1),
                 theta_check=_inscribed((0.0, -e), (x1, 0.0), (x2, 0.0)), variant=1)]


def slotted_lever(K: float, H: float, *, d: float | None = None, a: float | None = None) -> list[dict]:
    """Crank-slotted-lever (кулисный механизм с качающейся кулисой) from K and the stroke H of
    the lever's end D: the lever's extreme positions are tangent to the crank circle, so its
    swing equals θ, sin(θ/2) = a/d, and |CD| = H/(2 sin(θ/2)).  One of d (crank centre to the
    lever pivot) or a (crank) is given.  The lever pivot C is the origin, the crank centre O is
    at (0, d); in the extreme positions the lever is at ±θ/2 from the y axis and the crank at
    −θ/2 (right) and π + θ/2 (left) from the x axis."""
    theta = theta_of_K(K)
    s = math.sin(theta / 2)
    if d is None:
        d = a / s
    else:
        a = d * s
    l = H / (2 * s)
    return [dict(a=a, d=d, l=l, psi=theta, theta=theta, K=K, H=H, x_O=0.0, y_O=d,
                 phi_right=-theta / 2, phi_left=math.pi + theta / 2, variant=1)]


def six_bar(K: float, H: float, l3: float, l4: float, *, path_y: float, o1_y: float | None = None,
            o1_d: float | None = None, o1_path_dist: float | None = None, side: float = 1.0) -> list[dict]:
    """Six-bar O₁A B O₂ + B C (rod) + slider C (shaper type, problem 2013-6): the rocker O₂B
    (length l₃, pivot O₂ at the origin) is perpendicular to the slider's path (the line
    y = path_y) when the slider is in the middle of its stroke, so its extreme positions are
    symmetric and the stroke is H = 2·l₃·sin(ψ/2) for any rod length l₄ (the slider's extreme
    positions are those of the rocker).  The crank centre O₁ lies on the line y = o1_y or at the
    distance o1_d from O₂ or at the distance o1_path_dist from the slider's path (on either side
    of it: the two lines give the worksheet's four variants); the slider is on the side ``side`` (±1) of B along x; the four-bar O₁ABO₂ is then synthesised by :func:`crank_rocker`."""
    if H > 2 * l3:
        return []
    psi = 2 * math.asin(H / (2 * l3))
    dy = path_y - l3 * math.cos(psi / 2)
    if abs(dy) >= l4:
        return []
    dx = side * math.sqrt(l4 * l4 - dy * dy)
    if o1_path_dist is not None:
        vs = [v for s in (-1.0, 1.0) for v in crank_rocker(K, psi, l3, line_y=path_y + s * o1_path_dist)]
        vs = _sorted_variants(vs)
    else:
        vs = crank_rocker(K, psi, l3, d=o1_d, line_y=o1_y)
    for v in vs:
        v.update(l3=l3, l4=l4, H=H, path_y=path_y, x_C1=v["x_B1"] + dx, x_C2=v["x_B2"] + dx)
    return vs


def transmission_min(kind: str, v: dict) -> float | None:
    """Least transmission angle μ_min (rad) of a synthesised crank-rocker or slider-crank, in
    closed form (Попов С. А., Тимофеев Г. А., «Курсовое проектирование по ТММ», § 2.2).

    Crank-rocker OABC (a, b, c = |CB|, d = |OC|): μ is the angle between the coupler AB and the
    rocker CB, cos μ = (b² + c² − |AC|²)/(2bc); it is extreme where the crank lies on the line of
    centres, |AC| = d ∓ a, so μ_min = min over both of min(μ, 180° − μ).  Offset slider-crank
    (a, b, offset e): μ is the angle between the coupler and the normal to the guide,
    cos μ = |y_A|/b; it is least where the crank stands perpendicular to the guide on the side
    that adds to the offset, cos μ_min = (a + |e|)/b.  Other kinds: None (a slotted lever's stone
    presses along the normal to the slot, μ = 90°)."""
    if kind == "crank_rocker":
        a, b, c, d = v["a"], v["b"], v["c"], v["d"]
        out = []
        for s in (d - a, d + a):
            g = math.acos(max(-1.0, min(1.0, (b * b + c * c - s * s) / (2 * b * c))))
            out.append(min(g, math.pi - g))
        return min(out)
    if kind == "slider_crank":
        return math.acos(max(-1.0, min(1.0, (v["a"] + abs(v["e"])) / v["b"])))
    return None
