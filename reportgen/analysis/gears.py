"""The [gears] task: geometry of an involute pair with profile shift (ГОСТ 16532-70), the blocking
contour and the choice of shifts, the inverse problems (shift from a measured tooth).

Choice of shifts when x is "choose" (documented rule, docs/case-format.md): over the grid
x ∈ [x_lo, x_hi] with step 0,01 the admissible points are those without undercut (x ≥ x_min),
with tip thickness s_a ≥ s_a,min·m on both wheels, with ε_α ≥ ε_min and without interference
(ρ_p ≥ ρ_l on both wheels); among them the point with the least peak specific sliding
max(λ₁(ρ_p1), λ₂(ρ_a1)) is taken (equal wear of the roots; on the isoline λ₁max = λ₂max when it
crosses the contour).  A given x_Σ (from a required a_w) or a given x₁ restricts the search to
that line.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import pandas as pd

from ..case import units as U
from ..core import gears as G

__all__ = ["Gears", "blocking_grid", "choose_shifts"]

KEYS = ["module", "z1", "z2", "x1", "x2", "internal", "alpha", "ha", "c", "rho_f", "a_w", "s_a_min",
        "eps_min", "omega1", "measure", "printed", "x_range"]
CHOOSE = "choose"


def blocking_grid(m, z1, z2, rack: G.Rack, internal=False, lo=-0.6, hi=1.6, step=0.01, lo2=None):
    """The (x₁, x₂) grid of the blocking contour with the quality functions on it; ``lo2`` — the
    lower end of x₂ when it differs from x₁'s (each wheel's shift from its own undercut limit)."""
    xs = np.round(np.arange(lo, hi + step / 2, step), 10)
    ys = xs if lo2 is None else np.round(np.arange(lo2, hi + step / 2, step), 10)
    X1, X2 = np.meshgrid(xs, ys)
    with np.errstate(invalid="ignore", divide="ignore"):
        geo = G.pair_geometry(m, z1, z2, X1, X2, rack, internal)
        lam1, _, _ = G.sliding(geo, geo.rho_p1)
        _, lam2, _ = G.sliding(geo, geo.rho_a1)
    return X1, X2, geo, np.abs(lam1), np.abs(lam2)


def admissible(geo: G.PairGeometry, s_a_min, eps_min, X1=None, X2=None):
    """Boolean mask of the points inside the blocking contour (with the given margins)."""
    m, r = geo.m, geo.rack
    ok = (geo.sa1 >= s_a_min * m) & (geo.sa2 >= s_a_min * m) & (geo.eps >= eps_min)
    ok &= geo.x1 >= G.x_min_undercut(geo.z1, r) - 1e-12
    ok &= geo.rho_p1 >= geo.rho_l1
    if not geo.internal:
        ok &= geo.x2 >= G.x_min_undercut(geo.z2, r) - 1e-12
        ok &= geo.rho_p2 >= geo.rho_l2
    else:                                # ГОСТ 19274-73: the ring's tip on its involute, no interference
        for v in G.internal_checks(geo).values():
            ok &= v >= -1e-9 * m
    return ok & np.isfinite(geo.eps)


def choose_shifts(m, z1, z2, rack, internal, s_a_min, eps_min, *, x1=None, xsum=None, lo=-0.6, hi=1.6):
    """The rule of the module docstring; returns (x₁, x₂) or None when the contour is empty."""
    step = 0.01
    xs = np.round(np.arange(lo, hi + step / 2, step), 10)
    if x1 is not None:
        X1, X2 = np.full_like(xs, x1), xs
    elif xsum is not None:
        X1, X2 = xs, xsum - xs
    else:
        X1, X2 = np.meshgrid(xs, xs)
    with np.errstate(invalid="ignore", divide="ignore"):
        geo = G.pair_geometry(m, z1, z2, X1, X2, rack, internal)
        l1, _, _ = G.sliding(geo, geo.rho_p1)
        _, l2, _ = G.sliding(geo, geo.rho_a1)
        ok = admissible(geo, s_a_min, eps_min)
        peak = np.where(ok, np.maximum(np.abs(l1), np.abs(l2)), np.inf)
    if not np.any(np.isfinite(peak)):
        return None
    i = np.unravel_index(np.argmin(peak), peak.shape)
    return float(X1[i]), float(X2[i])


@dataclass
class Measure:
    """A measured wheel of the pair (wheel 1 by default): results of the inverse problems."""

    z: int
    d_a: float | None
    chord: float | None
    chord_height: float | None
    span: float | None
    k: int | None


class Gears:
    """Geometry of the pair of the case, its blocking contour and chosen shifts."""

    def __init__(self, study):
        self.study = study
        node = study.root.table("gears")
        node.check_keys(KEYS, required=["module", "z1"])
        names = study.spec.parameters()
        self.node = node
        self.m = node.quantity("module", U.LENGTH, names, required=True, positive=True) * 1000.0
        self.z1 = node.integer("z1", required=True, minimum=5)
        self.z2 = node.integer("z2", minimum=5)
        self.internal = node.boolean("internal", False)
        self.rack = G.Rack(node.quantity("alpha", U.ANGLE, names, default="20 deg", positive=True),
                           node.quantity("ha", U.DIMENSIONLESS, names, default=1.0, positive=True),
                           node.quantity("c", U.DIMENSIONLESS, names, default=0.25, nonnegative=True),
                           node.quantity("rho_f", U.DIMENSIONLESS, names, default=0.38, nonnegative=True))
        self.s_a_min = node.quantity("s_a_min", U.DIMENSIONLESS, names, default=0.25, nonnegative=True)
        self.eps_min = node.quantity("eps_min", U.DIMENSIONLESS, names, default=1.2, positive=True)
        self.omega1 = node.quantity("omega1", U.ANGULAR_VELOCITY, names, positive=True) if node.has("omega1") else None
        ext = (self.z1,) if self.internal or not self.z2 else (self.z1, self.z2)
        lo = math.floor(10 * min(-0.6, *(float(G.x_min_undercut(z, self.rack)) - 0.1 for z in ext))) / 10
        self.x_range_given = node.has("x_range")
        rng = node.raw("x_range", [lo, 1.6])
        if not (isinstance(rng, list) and len(rng) == 2 and all(isinstance(v, (int, float)) for v in rng)
                and rng[0] < rng[1]):
            raise node.error("x_range", "ожидалась пара чисел [от, до]", expected="[-0.6, 1.6]")
        self.x_range = (float(rng[0]), float(rng[1]))
        self.printed = {k: float(v) for k, v in node.table("printed").data.items()
                        if isinstance(v, (int, float)) and not isinstance(v, bool)}
        self.measure = self._read_measure(node.table("measure"), names)
        self.a_w_required = node.quantity("a_w", U.LENGTH, names, positive=True) * 1000.0 if node.has("a_w") else None
        self.chosen = False
        self.x1, self.x2 = self._shifts(names)

    # ------------------------------------------------------------------ reading
    def _read_measure(self, mn, names):
        if not mn.data:
            return None
        mn.check_keys(["z", "d_a", "chord", "chord_height", "span", "k"])
        mm = lambda k: mn.quantity(k, U.LENGTH, names, positive=True) * 1000.0 if mn.has(k) else None  # noqa: E731
        me = Measure(mn.integer("z", self.z1, minimum=5), mm("d_a"), mm("chord"), mm("chord_height"),
                     mm("span"), mn.integer("k", minimum=1))
        if (me.chord is None) != (me.chord_height is None) or (me.chord is not None and me.d_a is None):
            raise mn.error(None, "для зубомера нужны chord, chord_height и d_a вместе",
                           expected='chord = "18.1 mm", chord_height = "9.1 mm", d_a = "420 mm"')
        if (me.span is None) != (me.k is None):
            raise mn.error(None, "для длины общей нормали нужны span и k вместе",
                           expected='span = "…mm", k = 5')
        return me

    def _x(self, key, names):
        v = self.node.raw(key)
        if v is None:
            return 0.0 if key == "x1" or self.z2 else None
        if v == CHOOSE:
            return CHOOSE
        return self.node.quantity(key, U.DIMENSIONLESS, names)

    def _shifts(self, names):
        x1, x2 = self._x("x1", names), self._x("x2", names)
        if self.measure is not None and self.measure.z == self.z1 and self.node.raw("x1") is None:
            if self.inverse.get("x_chord") is not None:
                x1 = self.inverse["x_chord"]
            elif self.inverse.get("x_span") is not None:
                x1 = self.inverse["x_span"]
        if self.z2 is None:
            if x1 == CHOOSE:
                raise self.node.error("x1", "выбор смещения возможен только для пары колёс",
                                      expected="z2 и x2")
            return float(x1), None
        x2 = 0.0 if x2 is None else x2
        xsum = self.xsum_required
        if CHOOSE in (x1, x2):
            self.chosen = True
            got = choose_shifts(self.m, self.z1, self.z2, self.rack, self.internal, self.s_a_min, self.eps_min,
                                x1=None if x1 == CHOOSE else x1, xsum=xsum, lo=self.x_range[0], hi=self.x_range[1])
            if got is None:
                raise self.node.error("x1", "блокирующий контур пуст: нет допустимых смещений",
                                      expected="меньшие s_a_min/eps_min или другие z1, z2, a_w")
            return got
        if xsum is not None and abs(x1 + x2 - xsum) > 1e-6:
            raise self.node.error("a_w", f"x₁ + x₂ = {x1 + x2:.4f} не даёт заданного a_w (нужно x_Σ = {xsum:.4f})",
                                  expected="x1 или x2 = \"choose\"")
        return float(x1), float(x2)

    # ------------------------------------------------------------------ results
    @cached_property
    def xsum_required(self):
        """x₁ + x₂ for a given centre distance a_w: inv α_w = 2(x₁ + x₂) tg α/(z₁ ± z₂) + inv α with
        cos α_w = a cos α/a_w (ГОСТ 16532-70; domain.md § 1.7); None when the case gives no a_w."""
        if self.a_w_required is None:
            return None
        if self.z2 is None:
            raise self.node.error("a_w", "межосевое расстояние задаётся для пары колёс", expected="z2")
        a = self.m * (self.z2 - self.z1 if self.internal else self.z1 + self.z2) / 2
        if not self.a_w_required > a * math.cos(self.rack.alpha):
            raise self.node.error("a_w", "межосевое расстояние слишком мало", expected=f"a_w > {a * math.cos(self.rack.alpha):.3f} мм")
        return G.xsum_from_centre_distance(self.m, self.z1, self.z2, self.rack.alpha, self.a_w_required, self.internal)

    @cached_property
    def inverse(self) -> dict:
        """Shifts from the measurements (worksheet 001, 2013-4)."""
        me = self.measure
        out: dict = {}
        if me is None:
            return out
        al = self.rack.alpha
        if me.chord is not None:
            if not me.chord < me.d_a - 2 * me.chord_height or me.chord_height * 2 >= me.d_a:
                raise self.node.error("measure", "измерения зубомером несовместны", expected="s̄ < d_a − 2h̄")
            try:
                x, s, psi, d_y, ay = G.x_from_chordal(self.m, me.z, al, me.d_a, me.chord, me.chord_height)
            except ValueError:
                raise self.node.error("measure", "хорда лежит внутри основной окружности",
                                      expected="измерения на эвольвентной части зуба") from None
            out.update(x_chord=x, s_chord=s, psi=psi, d_y=d_y, alpha_y=ay)
        if me.span is not None:
            out["x_span"] = G.x_from_span(self.m, me.z, al, me.k, me.span)
        return out

    @cached_property
    def geo(self) -> G.PairGeometry | None:
        """The pair's geometry by ГОСТ 16532-70 табл. 1 (core.gears.pair_geometry), checked: a
        finite ε_α and positive tip thicknesses s_a; None for a single wheel."""
        if self.z2 is None:
            return None
        geo = G.pair_geometry(self.m, self.z1, self.z2, self.x1, self.x2, self.rack, self.internal)
        if not np.isfinite(geo.eps) or not geo.sa1 > 0 or not geo.sa2 > 0:
            raise self.node.error("x1", "при заданных смещениях зацепление невозможно (заострение зуба "
                                        "или отрицательный inv α_w)", expected="другие x1, x2")
        return geo

    @cached_property
    def grid(self):
        """The blocking contour's grid over (x₁, x₂) in steps of 0,01 (Болотовский, Кудрявцев;
        domain.md § 1.7)."""
        lo, hi = self.x_range
        if self.x_range_given:
            return blocking_grid(self.m, self.z1, self.z2, self.rack, self.internal, lo, hi, 0.01)
        # each shift from its own wheel's undercut limit x_min = h_a* − z sin²α/2 (a ring: the
        # common range): one range for both drew x₁ down to the wheel's −2,6, far from any x₁ ≥ x₁min
        own = [math.floor(10 * min(-0.6, float(G.x_min_undercut(z, self.rack)) - 0.1)) / 10 for z in (self.z1, self.z2)]
        return blocking_grid(self.m, self.z1, self.z2, self.rack, self.internal, own[0], hi, 0.01,
                             lo2=lo if self.internal else own[1])

    def wheel_rows(self) -> pd.DataFrame:
        """The geometry table: one row per quantity, a column per wheel."""
        m, al = self.m, self.rack.alpha
        rows = []
        g = self.geo

        ring_na = {"s_chord", "h_chord", "k", "W", "xmin"} if self.internal else set()

        def add(key, name, sym, unit, v1, v2=None):
            # chordal size, span and the rack undercut limit do not apply to a ring (internal teeth)
            rows.append({"key": key, "name": name, "symbol": sym, "unit": unit, "wheel1": float(v1),
                         "wheel2": None if v2 is None or key in ring_na else float(v2)})

        zs = [self.z1] + ([self.z2] if self.z2 else [])
        xs = [self.x1] + ([self.x2] if self.z2 else [])
        add("z", "Число зубьев", "z", "", *zs)
        add("x", "Коэффициент смещения", "x", "", *xs)
        add("d", "Делительный диаметр", "d", "мм", *[m * z for z in zs])
        add("db", "Основной диаметр", "d_b", "мм", *[m * z * math.cos(al) for z in zs])
        if g is not None:
            add("dw", "Начальный диаметр", "d_w", "мм", g.dw1, g.dw2)
            add("da", "Диаметр вершин", "d_a", "мм", g.da1, g.da2)
            add("df", "Диаметр впадин", "d_f", "мм", g.df1, g.df2)
            add("s", "Делительная толщина зуба", "s", "мм", g.s1, g.s2)
            add("sa", "Толщина зуба на окружности вершин", "s_a", "мм", g.sa1, g.sa2)
            add("sb", "Толщина зуба на основной окружности", "s_b", "мм",
                *[G.base_thickness(m, z, x, al) for z, x in zip(zs, xs)])
            ch = [G.chordal(m, z, x, al, da) for z, x, da in zip(zs, xs, (g.da1, g.da2))]
            add("s_chord", "Толщина по хорде (делительная)", "s̄", "мм", ch[0][0], ch[1][0])
            add("h_chord", "Высота до хорды", "h̄_a", "мм", ch[0][1], ch[1][1])
        else:
            d_a = self.measure.d_a if self.measure and self.measure.d_a else m * (self.z1 + 2 * (self.rack.ha + self.x1))
            add("da", "Диаметр вершин", "d_a", "мм", d_a)
            add("s", "Делительная толщина зуба", "s", "мм", m * (math.pi / 2 + 2 * self.x1 * math.tan(al)))
            add("sb", "Толщина зуба на основной окружности", "s_b", "мм", G.base_thickness(m, self.z1, self.x1, al))
        ks = [G.span_teeth(z, x, al) for z, x in zip(zs, xs)]
        add("k", "Число зубьев в длине общей нормали", "k", "", *ks)
        add("W", "Длина общей нормали", "W", "мм", *[G.span(m, z, x, al, k) for z, x, k in zip(zs, xs, ks)])
        add("xmin", "Наименьшее смещение без подрезания", "x_min", "", *[G.x_min_undercut(z, self.rack) for z in zs])
        return pd.DataFrame(rows)

    @cached_property
    def sliding_table(self) -> pd.DataFrame | None:
        """The specific sliding along the active line of action at 11 points: λ₁ = 1 − ρ₂/(ρ₁u),
        λ₂ = 1 − ρ₁u/ρ₂, and the sliding speed v_s = (ω₁ ± ω₂)·|PK| per unit ω₁ (in m/s too when
        ω₁ is given) (domain.md § 1.7)."""
        g = self.geo
        if g is None:
            return None
        rho = np.linspace(float(g.rho_p1), float(g.rho_a1), 11)
        l1, l2, vs = G.sliding(g, rho)
        df = pd.DataFrame({"rho1": rho, "rho2": (float(g.g) - rho) if not g.internal else rho + float(g.g),
                           "lambda1": l1, "lambda2": l2, "vs_per_omega": vs})
        if self.omega1 is not None:
            df["vs"] = vs * self.omega1 / 1000.0
        return df

    def tables(self) -> dict[str, pd.DataFrame]:
        # exported per wheel: a quantity that does not apply (one wheel measured, a ring's chord
        # and span) is absent, never a blank cell
        """Export tables: ``gears_geometry`` (a row per quantity and wheel, absent where it does not
        apply) and ``gears_sliding``."""
        rows = self.wheel_rows()
        geo = rows.melt(id_vars=["key", "name", "symbol", "unit"], value_vars=["wheel1", "wheel2"],
                        var_name="wheel", value_name="value").dropna(subset=["value"])
        geo["wheel"] = geo["wheel"].str[-1].astype(int)
        geo["value"] = geo["value"].astype(float)
        out = {"gears_geometry": geo.reset_index(drop=True)}
        if self.sliding_table is not None:
            out["gears_sliding"] = self.sliding_table
        return out

    @property
    def scalars(self) -> dict:
        """Named results: m, x₁, x₂, α_w, a, a_w, y, Δy, p = πm, p_b = p cos α, ε_α (by the angles
        and by the line of action), the undercut and interference flags (domain.md § 1.7)."""
        out = {"m": self.m, "x1": self.x1}
        g = self.geo
        if g is not None:
            out.update({"x2": self.x2, "alpha_w_deg": math.degrees(float(g.alpha_w)), "a": g.a,
                        "a_w": float(g.a_w), "y": float(g.y), "dy": float(g.dy), "p": g.p, "pb": g.pb,
                        "eps_alpha": float(g.eps), "eps_alpha_line": float(g.eps_line),
                        "undercut1": bool(float(g.rho_l1) < 0), "undercut2": bool(float(g.rho_l2) < 0),
                        "interference": bool(float(g.rho_p1) < float(g.rho_l1) or
                                             (not g.internal and float(g.rho_p2) < float(g.rho_l2)))})
        for k, v in self.inverse.items():
            out[k + "_deg" if k in ("psi", "alpha_y") else k] = math.degrees(v) if k in ("psi", "alpha_y") else v
        if self.xsum_required is not None:
            out["xsum_required"] = self.xsum_required
        return {"gears_" + k: v for k, v in out.items()}
