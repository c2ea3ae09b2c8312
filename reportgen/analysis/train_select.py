"""Tooth-number selection for any planetary train of the ``[train]`` graph (2K-H with single or
double satellites and any mix of external and internal meshes, 3K, trains with several carriers).

Conditions (Кудрявцев В. Н. «Планетарные передачи», 1966, гл. 1; Артоболевский И. И. «Теория
механизмов и машин», гл. «Зубчатые механизмы»; Попов С. А., Тимофеев Г. А. «Курсовое
проектирование по теории механизмов и механике машин», разд. «Синтез планетарных механизмов»):

* **ratio**: u_in,out as an exact rational function of the tooth numbers.  Every Willis equation
  (ω_a − ω_H) = ∓(z_b/z_a)(ω_b − ω_H) multiplied by z_a is linear in the ω's with coefficients
  linear in the z's; with ω_in = 1 and the fixed members at 0, Cramer's rule gives
  u = ω_in/ω_out = det A / det A_out, both polynomials in the z's (common monomial factors
  cancelled).  Within ±tolerance of the target.
* **coaxiality** (соосность): one linear equation per mesh closing a loop of axes
  (``train.coaxiality_equations``); the selection solves them for some tooth numbers (Gauss–Jordan
  over the rationals) and enumerates the others; non-integer solutions are not tooth sets.
* **assembly** (сборка) of k equally spaced satellites.  In the frame of the line of centres of a
  satellite at angle Θ the meshing phase of an external pair is z_c(φ_c − Θ) + z_p(ψ − Θ) and of an
  internal pair z_c(φ_c − Θ) − z_p(ψ − Θ), constant mod 2π (one tooth advances it by 2π).  Between
  satellite positions Θ and Θ + 2π/k the central wheels stand still and the identical satellite
  block may take any rotation 2πt: σ_j z_pj t ≡ z_cj/k (mod 1) for every mesh j of the block with a
  central wheel (σ = +1 external, −1 internal).  A t exists iff the congruences are compatible;
  for two meshes this is Кудрявцев's condition (σ₁z_p1 z_c0 − σ₀z_p0 z_c1)/(k·НОД(z_p0, z_p1)) —
  an integer, e.g. (z₁z₂′ + z₂z₃)/(k·НОД(z₂, z₂′)) for the 2K-H with a double satellite, which for a
  single satellite (z₂ = z₂′) is (z₁ + z₃)/k (Попов–Тимофеев: z₁u₁H(1 + kp)/k integer).
* **neighbourhood** (соседство): satellite axes at radius a_w on k equally spaced positions,
  2a_w sin(π/k) > d_a,max of the satellite's largest wheel, d_a = m(z + 2h_a*).
* **undercut and interference**: external wheels z ≥ z_min; internal meshes z_int − z_ext ≥ Δz_min
  (the course rule) and the ГОСТ 19274-73 checks of the uncorrected pair
  (``core.gears.internal_checks``: the ring's tip on its involute, no interference at both roots,
  no tip interference outside the line of action).

Enumeration: the free tooth numbers run over [z_from, z_max] (numpy, one slab per value of the
first) — except one in which the ratio is a Möbius function u = (ax + b)/(cx + d): its admissible
integers lie between the roots of u = target(1 ± tol) and are taken from there — the dependent ones
come from coaxiality, the ratio filters, the survivors are ranked by the
overall size (the largest diameter the wheels occupy, max(2|y_c| + mz) over the wheels, in modules)
then Σz, and checked in that order until ``limit`` sets pass; the sets before them that fail are
kept with their reasons.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from functools import lru_cache

import numpy as np

from ..style.numbers import SUBSCRIPT
from ..core.gears import Rack, internal_checks, pair_geometry
from .train import FRAME, TrainModel, Wheel, coaxiality_equations, place_axes

__all__ = ["Candidate", "Poly", "willis_polynomials", "poly_tex", "Planet", "planets_of", "assembly", "k_of",
           "neighbourhood", "Selector", "select", "check"]

GRID_LIMIT = 6_000_000      # tooth-number combinations enumerated at most (the free ones' grid)
CHECK_LIMIT = 5_000         # candidates within tolerance checked one by one at most (smallest first)
FAILING_SHOWN = 200         # of them, failing the plain tooth-number rules (kept for their reasons)
NAMES = {"base": "вершина колеса внутри основной окружности", "pinion_root": "интерференция у ножки шестерни",
         "ring_root": "интерференция у ножки колеса", "trochoid": "интерференция вершин (трохоидальная)"}


# --------------------------------------------------------------- polynomials in the tooth numbers
Poly = dict   # monomial (sorted tuple of (wheel, power)) → integer coefficient


def _pmul(a: Poly, b: Poly) -> Poly:
    out: Poly = {}
    for ma, ca in a.items():
        for mb, cb in b.items():
            pw = dict(ma)
            for w, p in mb:
                pw[w] = pw.get(w, 0) + p
            key = tuple(sorted(pw.items()))
            out[key] = out.get(key, 0) + ca * cb
    return {k: v for k, v in out.items() if v}


def _padd(a: Poly, b: Poly, sign: int = 1) -> Poly:
    out = dict(a)
    for k, v in b.items():
        out[k] = out.get(k, 0) + sign * v
    return {k: v for k, v in out.items() if v}


def _det(mat: list[list[Poly]]) -> Poly:
    """Determinant by expansion along the rows, memoised on the set of columns left."""
    n = len(mat)

    @lru_cache(maxsize=None)
    def sub(row: int, cols: frozenset) -> tuple:
        if row == n:
            return (((), 1),)
        acc: Poly = {}
        for i, c in enumerate(sorted(cols)):
            if not mat[row][c]:
                continue
            rest = dict(sub(row + 1, cols - {c}))
            acc = _padd(acc, _pmul(mat[row][c], rest), -1 if i % 2 else 1)
        return tuple(acc.items())
    return dict(sub(0, frozenset(range(n))))


def _cancel(num: Poly, den: Poly) -> tuple[Poly, Poly]:
    """Divide out the common monomial factor and integer content; the denominator's leading
    coefficient made positive."""
    terms = list(num) + list(den)
    common = {}
    if terms:
        names = set(dict(terms[0]))
        for t in terms[1:]:
            names &= set(dict(t))
        common = {w: min(dict(t)[w] for t in terms) for w in names}

    def strip(p: Poly) -> Poly:
        return {tuple((w, e - common.get(w, 0)) for w, e in mono if e - common.get(w, 0)): c
                for mono, c in p.items()}
    num, den = strip(num), strip(den)
    g = math.gcd(*num.values(), *den.values()) or 1
    if sum(v < 0 for v in list(num.values()) + list(den.values())) * 2 > len(num) + len(den):
        g = -g                                   # the sign with more positive terms
    return {k: v // g for k, v in num.items()}, {k: v // g for k, v in den.items()}


def willis_polynomials(model: TrainModel, fixed=None, inp=None, out=None) -> tuple[Poly, Poly]:
    """u_in,out = num/den as polynomials in the tooth numbers (wheel names), from the Willis
    equation of every mesh multiplied by z_a:  z_a ω_a − σ z_b ω_b + (σ z_b − z_a) ω_H = 0,
    σ = −1 external, +1 internal (Cramer's rule, see the module docstring).  ValueError when the
    equations do not determine the ratio."""
    fixed = model.fixed if fixed is None else fixed
    inp = model.inp if inp is None else inp
    out = model.out if out is None else out
    unknown = [n for n in model.members if n not in fixed and n != inp]
    if len(model.meshes) != len(unknown) or out not in unknown:
        raise ValueError("the Willis equations do not determine the ratio")
    col = {n: i for i, n in enumerate(unknown)}
    rows, rhs = [], []
    for a, b in model.meshes:
        wa, wb = model.wheels[a], model.wheels[b]
        sg = 1 if (wa.internal or wb.internal) else -1
        za, zb = {((a, 1),): 1}, {((b, 1),): 1}
        coef: dict[str, Poly] = {}
        for mem, p in ((wa.member, za), (wb.member, {k: -sg * v for k, v in zb.items()})):
            coef[mem] = _padd(coef.get(mem, {}), p)
        h = model.mesh_carrier(a, b)
        if h != FRAME:
            coef[h] = _padd(coef.get(h, {}), _padd({k: sg * v for k, v in zb.items()}, za, -1))
        rows.append([coef.get(n, {}) for n in unknown])
        rhs.append({k: -v for k, v in coef.get(inp, {}).items()})
    det_a = _det(rows)
    if not det_a:
        raise ValueError("the Willis equations are singular")
    rows_out = [[(rhs[i] if j == col[out] else r[j]) for j in range(len(unknown))] for i, r in enumerate(rows)]
    det_o = _det(rows_out)
    if not det_o:
        raise ValueError("the output does not turn")
    return _cancel(det_a, det_o)


def poly_eval(p: Poly, z: dict):
    """Value of a polynomial; z maps wheel → int or numpy array (exact with Python ints)."""
    acc = 0
    for mono, c in p.items():
        t = c
        for w, e in mono:
            t = t * z[w] ** e
        acc = acc + t
    return acc


def poly_tex(p: Poly, order: list[str], z: dict | None = None) -> str:
    """«z_{1} z_{2'} + z_{2} z_{3}»: terms by the wheels' order, positive ones first; a monomial
    factor common to all terms of a sum is written in front: «z_{2} z_{4} (z_{1} + z_{3})».  With
    ``z`` the numbers of teeth stand for the letters («70 · 49 − 50 · 71»): the formula with
    numbers substituted."""
    common = {}
    if len(p) > 1:
        names = set.intersection(*(set(dict(m)) for m in p))
        common = {w: min(dict(m)[w] for m in p) for w in names}
    if common:
        rest = {tuple((w, e - common.get(w, 0)) for w, e in m if e - common.get(w, 0)): c for m, c in p.items()}
        return (_terms({tuple(sorted(common.items())): 1}, order, z) + (r" \cdot (" if z else r"\,(")
                + _terms(rest, order, z) + ")")
    return _terms(p, order, z)


def _terms(p: Poly, order: list[str], z: dict | None = None) -> str:
    def key(item):
        mono, c = item
        return (c < 0, [order.index(w) for w, _ in sorted(mono, key=lambda we: order.index(we[0]))])
    out = ""
    for mono, c in sorted(p.items(), key=key):
        mono = sorted(mono, key=lambda we: order.index(we[0]))
        if z is None:
            body = r"\,".join(rf"z_{{{w}}}" + (f"^{{{e}}}" if e > 1 else "") for w, e in mono)
        else:
            body = r" \cdot ".join(f"{z[w]}" + (f"^{{{e}}}" if e > 1 else "") for w, e in mono)
        k = abs(c)
        txt = (str(k) if k != 1 or not body else "") + (r" \cdot " if z is not None and k != 1 and body else "") + body
        out += (" - " if c < 0 else (" + " if out else "")) + txt
    return out or "0"


# ------------------------------------------------------------------------ satellites and carriers
@dataclass(frozen=True)
class Planet:
    """A satellite member of a carrier: its meshes with the central wheels (central wheel, its own
    wheel, σ = +1 external / −1 internal) and whether it also meshes another satellite or itself
    carries satellites (then the assembly condition is not checked)."""
    carrier: str
    member: str
    axis: str
    meshes: tuple[tuple[str, str, int], ...]
    coupled: bool


def planets_of(model: TrainModel) -> list[Planet]:
    """Satellite members of every carrier (members turning about an axis the carrier carries)."""
    out = []
    for h, h_axis in model.members.items():
        for mem, ax in model.members.items():
            if model.axes.get(ax) != h:
                continue
            meshes, coupled = [], any(model.axes.get(a) == mem for a in model.axes)
            for a, b in model.meshes:
                for own, other in ((a, b), (b, a)):
                    if model.wheels[own].member != mem:
                        continue
                    wo = model.wheels[other]
                    sg = -1 if (wo.internal or model.wheels[own].internal) else 1
                    if wo.centre == h_axis:
                        meshes.append((other, own, sg))
                    else:
                        coupled = True
            if meshes:
                out.append(Planet(h, mem, ax, tuple(meshes), coupled))
    return out


def assembly(pl: Planet, z: dict, k) -> tuple[bool | None, list[Fraction]]:
    """Can k identical satellites be put on equally spaced positions?  Exact: the congruences
    σ_j z_pj t ≡ z_cj/k (mod 1) have a common real t (t enumerated over the first mesh's
    solutions).  Returns (verdict or None when not checked, Кудрявцев's quantities of the first
    mesh paired with every other one)."""
    k = k_of(k, pl.carrier)
    if k <= 1:
        return True, []
    if pl.coupled:
        return None, []
    c0, p0, s0 = pl.meshes[0]
    P0, A0 = s0 * z[p0], Fraction(z[c0], k)
    quantities = []
    for c, p, s in pl.meshes[1:]:
        g = math.gcd(z[p0], z[p])
        quantities.append(abs(Fraction(s * z[p] * z[c0] - s0 * z[p0] * z[c], k * g)))
    ok = any(all((Fraction(s * z[p]) * t - Fraction(z[c], k)).denominator == 1 for c, p, s in pl.meshes[1:])
             for t in (Fraction(A0 + n, P0) for n in range(abs(P0))))
    return ok, quantities


def k_of(k, carrier: str) -> int:
    """Number of satellites of a carrier: ``k`` an int (every carrier) or {carrier: k} (1 if absent)."""
    return k if isinstance(k, int) else k.get(carrier, 1)


def neighbourhood(model: TrainModel, y: dict, z: dict, k, ha: float = 1.0):
    """For every satellite axis of a carrier with k > 1 satellites (``k`` an int or {carrier: k}):
    (carrier, axis, sin π/k, (z + 2h_a*)m / 2a_w of the largest wheel on the axis, ok); a satellite
    axis on the central axis (a_w = 0) fails, its ratio written as 2."""
    out = []
    for h, h_axis in model.members.items():
        kh = k_of(k, h)
        if kh <= 1:
            continue
        for ax, host in model.axes.items():
            if host != h:
                continue
            ws = [w for w in model.wheels.values() if w.centre == ax]
            if not ws:
                continue
            a = abs(y[ax] - y[h_axis])
            d_a = max(w.m * (z[w.name] + 2 * ha) for w in ws)
            s = math.sin(math.pi / kh)
            rhs = d_a / (2 * a) if a > 0 else 2.0
            out.append((h, ax, s, rhs, s > rhs))
    return out


# ------------------------------------------------------------------------------ the enumeration
@dataclass
class Candidate:
    """One set of tooth numbers tried by the selection: the ratio u, the size, the reasons it fails,
    the exact ratio, and the assembly and neighbourhood conditions with their quantities."""
    z: dict[str, int]
    u: float
    size: float
    fails: list[str] = field(default_factory=list)
    u_exact: Fraction | None = None
    assembly: list = field(default_factory=list)       # (planet member, ok, [quantities])
    neighbours: list = field(default_factory=list)     # (carrier, axis, sin π/k, rhs, ok)

    @property
    def ok(self) -> bool:
        """Whether the tooth set passes every condition."""
        return not self.fails


@lru_cache(maxsize=4096)
def _internal_margins(z_small: int, z_ring: int) -> dict:
    geo = pair_geometry(1.0, z_small, z_ring, 0.0, 0.0, Rack(), internal=True)
    return {k: float(v) for k, v in internal_checks(geo).items()}


class Selector:
    """The selection problem of one train: unknown wheels (z = 0 in the model), the coaxiality
    equations solved for the dependent ones, the ratio as polynomials."""

    def __init__(self, model: TrainModel, *, k: int | dict = 1, z_min: int = 17, z_max: int = 150,
                 dz_int: int = 8, ha: float = 1.0, z_from: int | None = None, prefer=()):
        self.model, self.k, self.z_min, self.z_max, self.dz_int, self.ha = model, k, z_min, z_max, dz_int, ha
        self.z_from = max(6, z_min // 2) if z_from is None else z_from
        self.order = list(model.wheels)
        self.unknown = [w for w, wh in model.wheels.items() if wh.z == 0]
        self.known = {w: wh.z for w, wh in model.wheels.items() if wh.z}
        probe = self._probe()
        self.num, self.den = willis_polynomials(probe)
        self.equations = coaxiality_equations(probe)
        forms: dict = {}
        place_axes(probe, forms=forms)
        self.axis_forms = forms
        self.dependent, self.free = self._solve(prefer)
        self.planets = planets_of(model)

    def _probe(self) -> TrainModel:
        """The model with stand-in tooth numbers (external 20, internal 80) to derive the forms."""
        ws = {n: Wheel(n, w.z or (80 if w.internal else 20), w.member, w.centre, w.internal, w.m)
              for n, w in self.model.wheels.items()}
        m = self.model
        return TrainModel(m.members, m.axes, ws, m.meshes, m.fixed, m.inp, m.out)

    def _solve(self, prefer):
        """Gauss–Jordan on the coaxiality equations: dependent wheel → (constant, {free: coef})."""
        rows = []
        self.inconsistent = False
        for _, path, close in self.equations:
            row = {w: path.get(w, 0) - close.get(w, 0) for w in set(path) | set(close)}
            const = sum(Fraction(c) * self.known[w] for w, c in row.items() if w in self.known)
            rows.append(({w: Fraction(c) for w, c in row.items() if w not in self.known and c}, const))
        dep: dict[str, tuple[Fraction, dict]] = {}
        for coefs, const in rows:
            for d, (c0, cf) in dep.items():          # substitute earlier pivots
                if d in coefs:
                    a = coefs.pop(d)
                    const += a * c0
                    for w, c in cf.items():
                        coefs[w] = coefs.get(w, 0) + a * c
            coefs = {w: c for w, c in coefs.items() if c}
            if not coefs:
                self.inconsistent |= const != 0      # the given tooth numbers break a loop
                continue
            rank = lambda w: (w not in prefer, not self.model.wheels[w].internal, abs(coefs[w]) != 1,  # noqa: E731
                              -self.order.index(w))
            piv = min(coefs, key=rank)
            a = coefs.pop(piv)
            expr = (-const / a, {w: -c / a for w, c in coefs.items()})
            for d, (c0, cf) in list(dep.items()):   # back-substitute
                if piv in cf:
                    b = cf.pop(piv)
                    c0 += b * expr[0]
                    for w, c in expr[1].items():
                        cf[w] = cf.get(w, 0) + b * c
                    dep[d] = (c0, {w: c for w, c in cf.items() if c})
            dep[piv] = expr
        free = [w for w in self.unknown if w not in dep]
        return dep, free

    # -------------------------------------------------------------------------------- vectorised
    def _linear_free(self) -> str | None:
        """A free wheel in which the ratio's numerator and denominator (the dependent tooth numbers
        substituted) are both of degree ≤ 1 — its admissible values then follow from the target
        (second differences at 0, 1, 2 vanish at several points of the others, exactly)."""
        rs = np.random.default_rng(0)
        for x in reversed(self.free):
            linear = True
            for _ in range(4):
                base = {w: int(rs.integers(self.z_from, self.z_max + 1)) for w in self.free}
                vals = []
                for v in (0, 1, 2):
                    z = {**self.known, **base, x: v}
                    z.update({d: c0 + sum(c * z[w] for w, c in cf.items()) for d, (c0, cf) in self.dependent.items()})
                    vals.append((poly_eval(self.num, z), poly_eval(self.den, z)))
                if any(vals[0][i] - 2 * vals[1][i] + vals[2][i] != 0 for i in (0, 1)):
                    linear = False
                    break
            if linear:
                return x
        return None

    def _slabs(self, target: float, tol: float):
        """Tooth numbers of the free wheels, one slab per value of the first enumerated one.  When
        the ratio is a Möbius function u = (a x + b)/(c x + d) of a free wheel x, x is not
        enumerated: only the integers between the roots of u(x) = target(1 ± tol) are taken (all
        of the range where the preimage is not that interval: the pole in between)."""
        rng = np.arange(self.z_from, self.z_max + 1)
        x = self._linear_free() if len(self.free) > 1 else None
        enum = [w for w in self.free if w != x]
        if not self.free:
            yield {}
            return
        if rng.size ** len(enum) > GRID_LIMIT:
            raise OverflowError(rng.size ** len(enum))
        rest = enum[1:]
        grids = np.meshgrid(*([rng] * len(rest)), indexing="ij") if rest else []
        flat = [g.ravel() for g in grids]
        n = flat[0].size if flat else 1
        total = 0
        for v in rng:
            slab = {enum[0]: np.full(n, v), **dict(zip(rest, flat))}
            if x is not None:
                slab = self._expand(slab, x, rng, target, tol)
                total += slab[x].size
                if total > 4 * GRID_LIMIT:       # a tolerance so wide that x is not restricted
                    raise OverflowError(total * rng.size // max(1, int(v - rng[0] + 1)))
            yield slab

    def _expand(self, slab: dict, x: str, rng: np.ndarray, target: float, tol: float) -> dict:
        n = next(iter(slab.values())).size
        ends = []
        for v in (0.0, 1.0):
            z = {**self.known, **{w: np.asarray(a, float) for w, a in slab.items()}, x: np.full(n, v)}
            for d, (c0, cf) in self.dependent.items():
                z[d] = float(c0) + sum(float(c) * z[w] for w, c in cf.items())
            ends.append((np.broadcast_to(np.asarray(poly_eval(self.num, z), float), (n,)),
                         np.broadcast_to(np.asarray(poly_eval(self.den, z), float), (n,))))
        (b_n, b_d), (n1, d1) = ends
        a_n, a_d = n1 - b_n, d1 - b_d
        lo_t, hi_t = sorted((target * (1 - tol), target * (1 + tol)))
        with np.errstate(divide="ignore", invalid="ignore"):
            r1 = (lo_t * b_d - b_n) / (a_n - lo_t * a_d)
            r2 = (hi_t * b_d - b_n) / (a_n - hi_t * a_d)
            pole_in = (a_d != 0) & (a_n / np.where(a_d != 0, a_d, 1) >= lo_t - 1e-12) & \
                (a_n / np.where(a_d != 0, a_d, 1) <= hi_t + 1e-12)
        full = pole_in | ~np.isfinite(r1) | ~np.isfinite(r2) | ((a_n == 0) & (a_d == 0))
        r1, r2 = np.where(full, 0.0, r1), np.where(full, 0.0, r2)
        r1, r2 = np.clip(r1, -1e9, 1e9), np.clip(r2, -1e9, 1e9)     # beyond the range either way
        eps = 1e-7 * (1 + np.abs(r1) + np.abs(r2))
        lo = np.where(full, rng[0], np.ceil(np.minimum(r1, r2) - eps))
        hi = np.where(full, rng[-1], np.floor(np.maximum(r1, r2) + eps))
        lo, hi = np.maximum(lo, rng[0]).astype(np.int64), np.minimum(hi, rng[-1]).astype(np.int64)
        cnt = np.maximum(hi - lo + 1, 0)
        total = int(cnt.sum())
        row = np.repeat(np.arange(n), cnt)
        start = np.repeat(np.cumsum(cnt) - cnt, cnt)
        out = {w: np.asarray(a)[row] for w, a in slab.items()}
        out[x] = lo[row] + (np.arange(total) - start)
        return out

    def survivors(self, target: float, tol: float, cap: int = CHECK_LIMIT) -> list[dict[str, int]]:
        """Tooth sets (integers, coaxial, in range) with the ratio within tolerance (float
        filter; the exact check follows), sorted by size, Σz and |u − target|; the first ``cap``."""
        found = []
        if self.inconsistent:
            return found
        for slab in self._slabs(target, tol):
            z = {w: np.asarray(v, np.int64) for w, v in slab.items()}
            n = next(iter(z.values())).size if z else 1
            if n == 0:
                continue
            ok = np.ones(n, bool)
            for d, (c0, cf) in self.dependent.items():
                den = math.lcm(c0.denominator, *(c.denominator for c in cf.values()))
                val = np.full(n, int(c0 * den), np.int64)
                for w, c in cf.items():
                    val = val + int(c * den) * z[w]
                ok &= val % den == 0
                z[d] = val // den
                ok &= (z[d] >= 6) & (z[d] <= self.z_max)
            for a, b in self.model.meshes:                 # a ring larger than its partner
                wa, wb = self.model.wheels[a], self.model.wheels[b]
                if wa.internal or wb.internal:
                    ring, small = (a, b) if wa.internal else (b, a)
                    ok &= np.asarray(({**self.known, **z})[ring]) > np.asarray(({**self.known, **z})[small])
            full = {**self.known, **{w: np.asarray(v, float) for w, v in z.items()}}
            with np.errstate(divide="ignore", invalid="ignore"):
                u = poly_eval(self.num, full) / poly_eval(self.den, full)
            u = np.broadcast_to(np.asarray(u, float), (n,))
            ok &= np.isfinite(u) & (np.abs(u - target) <= tol * abs(target) * (1 + 1e-12) + 1e-12 * abs(target))
            if not ok.any():
                continue
            idx = np.nonzero(ok)[0]
            zz = {w: np.broadcast_to(np.asarray(v), (n,))[idx] for w, v in z.items()}
            size = self._size({**self.known, **zz}, idx.size)
            tot = sum(zz[w] for w in self.unknown) if self.unknown else np.zeros(idx.size)
            found.append((size, np.asarray(tot, float) + 0 * size, np.abs(u[idx] - target), self._plain_ok(zz, idx.size),
                          np.column_stack([zz[w] for w in self.unknown]) if self.unknown
                          else np.zeros((idx.size, 0), np.int64)))
        if not found:
            return []
        size, tot, du, plain, zs = (np.concatenate(parts) for parts in zip(*found))
        order = np.lexsort((du, tot, size))
        # every set passing the plain tooth-number rules (undercut, internal Δz) up to the cap, and
        # the first few failing them (their reasons shown): smallest sets are mostly undercut
        pos = np.sort(np.concatenate([np.nonzero(plain[order])[0][:cap], np.nonzero(~plain[order])[0][:FAILING_SHOWN]]))
        return [dict(zip(self.unknown, map(int, zs[i]))) for i in order[pos]]

    def _plain_ok(self, zz: dict, n: int) -> np.ndarray:
        """Vectorised tooth-number rules: external wheels z ≥ z_min, internal meshes Δz ≥ dz_int."""
        z = {**{w: np.full(n, v) for w, v in self.known.items()}, **zz}
        ok = np.ones(n, bool)
        for w in self.model.wheels.values():
            if not w.internal:
                ok &= z[w.name] >= self.z_min
        for a, b in self.model.meshes:
            wa, wb = self.model.wheels[a], self.model.wheels[b]
            if wa.internal or wb.internal:
                ring, small = (a, b) if wa.internal else (b, a)
                ok &= z[ring] - z[small] >= self.dz_int
        return ok

    def _size(self, z: dict, n: int) -> np.ndarray:
        """max over the wheels of (2|y_c| + m z) in modules of the first wheel."""
        m0 = next(iter(self.model.wheels.values())).m
        size = np.zeros(n)
        for w in self.model.wheels.values():
            y = sum(c * np.asarray(z[v], float) for v, c in self.axis_forms.get(w.centre, {}).items())
            size = np.maximum(size, (2 * np.abs(y) + w.m * np.asarray(z[w.name], float)) / m0)
        return size

    # ---------------------------------------------------------------------------- one candidate
    def model_with(self, zs: dict[str, int]) -> TrainModel:
        """The train with the tooth numbers ``zs`` in place of its own."""
        m = self.model
        ws = {n: Wheel(n, zs.get(n, w.z), w.member, w.centre, w.internal, w.m) for n, w in m.wheels.items()}
        return TrainModel(m.members, m.axes, ws, m.meshes, m.fixed, m.inp, m.out)

    def check(self, zs: dict[str, int], target: float | None, tol: float) -> Candidate:
        """Every condition of one tooth set, checked on the train with these tooth numbers
        (exact ratio, coaxiality by placing the axes, assembly, neighbourhood, undercut,
        internal meshes).  Reasons in Russian, one per failed condition."""
        z = {**self.known, **zs}
        u = Fraction(poly_eval(self.num, z), poly_eval(self.den, z))
        model = self.model_with(zs)
        fails = []
        if target is not None and abs(float(u) - target) > tol * abs(target) * (1 + 1e-12) + 1e-12 * abs(target):
            fails.append(f"передаточное отношение {_dec(float(u))} вне допуска ±{_dec(tol * 100, 'g')} %")
        y, resid = place_axes(model)
        bad = [(n, r) for n, r in resid if abs(r) > 1e-9]
        if bad:
            fails.append("не выполнено условие соосности (" + ", ".join(f"зацепление {n}: {_dec(r, '+.3g')} мм" for n, r in bad) + ")")
        asm = []
        for pl in self.planets:
            ok, qs = assembly(pl, z, self.k)
            asm.append((pl.member, ok, qs))
            if ok is False:
                q = ", ".join(_frac(x) for x in qs)
                fails.append(f"не выполнено условие сборки при k = {k_of(self.k, pl.carrier)}"
                             + (f": {q} — не целое" if qs else ""))
        nb = neighbourhood(model, y, z, self.k, self.ha)
        for h, ax, s, rhs, ok in nb:
            if not ok:
                fails.append(f"не выполнено условие соседства при k = {k_of(self.k, h)}: {_dec(s)} ≤ {_dec(rhs)}")
        for w in model.wheels.values():
            if not w.internal and w.z < self.z_min:
                fails.append(f"z{_sub(w.name)} = {w.z} < {self.z_min}: подрезание")
        for a, b in model.meshes:
            wa, wb = model.wheels[a], model.wheels[b]
            if not (wa.internal or wb.internal):
                continue
            ring, small = (wa, wb) if wa.internal else (wb, wa)
            if ring.z - small.z < self.dz_int:
                fails.append(f"z{_sub(ring.name)} − z{_sub(small.name)} = {ring.z - small.z} < {self.dz_int}: "
                             f"интерференция во внутреннем зацеплении")
            elif small.z >= 5:
                worst = [NAMES[c] for c, v in _internal_margins(small.z, ring.z).items() if v < -1e-9]
                if worst:
                    fails.append(f"зацепление {small.name}–{ring.name} (ГОСТ 19274-73): " + ", ".join(worst))
        size = float(self._size(z, 1)[0])
        return Candidate(dict(zs), float(u), size, fails, u, asm, nb)


def _sub(name: str) -> str:
    """A wheel's number as a subscript of z in a plain-text verdict: «z₁₁», not «z11» (letters as they
    are, the case's «2'» as the prime «₂′»)."""
    return name.translate(SUBSCRIPT).replace("'", "′")


def _dec(x: float, spec: str = ".4f") -> str:
    """A number with the decimal comma (Russian text)."""
    return format(x, spec).replace(".", ",").replace("-", "−")


def _frac(x: Fraction) -> str:
    return str(x.numerator) if x.denominator == 1 else f"{x.numerator}/{x.denominator}"


def select(model: TrainModel, target: float, k: int | dict, *, tol: float = 0.03, z_min: int = 17,
           z_max: int = 150, dz_int: int = 8, ha: float = 1.0, limit: int = 6, z_from: int | None = None,
           prefer=()) -> tuple[list[Candidate], list[Candidate], Selector]:
    """Accepted sets (at most ``limit``, smallest first) and at most ``limit`` failing sets: those
    ranked before the first accepted one (every kind of failure represented), then those among
    the accepted ones; with the selector (formulas for the note)."""
    sel = Selector(model, k=k, z_min=z_min, z_max=z_max, dz_int=dz_int, ha=ha, z_from=z_from, prefer=prefer)
    ok, before, after = [], [], []
    for zs in sel.survivors(target, tol):
        c = sel.check(zs, target, tol)
        if c.ok:
            ok.append(c)
            if len(ok) >= limit:
                break
        else:
            (after if ok else before).append(c)
            if len(before) > 50 * limit:
                del before[:25 * limit]
    bad = _variety(before, limit)
    return ok, bad + after[:limit - len(bad)], sel


KINDS = ("допуска", "соосности", "сборки", "соседства", "подрезание", "интерференция", "ГОСТ")


def _variety(bad: list[Candidate], limit: int) -> list[Candidate]:
    """At most ``limit`` rejected sets, every kind of failure represented by the sets ranked
    closest before the accepted ones (round robin over the kinds), in ranking order."""
    by_kind: dict[str, list[Candidate]] = {}
    for c in reversed(bad):
        kind = next((k for k in KINDS if any(k in f for f in c.fails)), "")
        by_kind.setdefault(kind, []).append(c)
    out: list[Candidate] = []
    while len(out) < limit and any(by_kind.values()):
        for lst in by_kind.values():
            if lst and len(out) < limit:
                out.append(lst.pop(0))
    order = {id(c): i for i, c in enumerate(bad)}
    return sorted(out, key=lambda c: order[id(c)])


def check(model: TrainModel, k: int | dict, target: float | None = None, tol: float = 0.03, **kw) -> Candidate:
    """All conditions of the train's own tooth numbers (no unknowns)."""
    return Selector(model, k=k, **kw).check({}, target, tol)
