"""Linkage synthesis by the time-ratio coefficient K (``[synthesis]``) and its check by the engine.

The synthesis is solved when the case's parameters are resolved
(:mod:`reportgen.case.synthesis`, formulas in :mod:`reportgen.core.synthesis`), so its results
``syn_*`` size the linkage of the same case.  This analysis lists every solution variant and,
when the case has a linkage, measures on it what the synthesis was asked for: the extreme
positions of the output link (roots of its first analog, s′(φ) = 0, by Brent's method on the
exact position solution), its stroke (or swing) and the time-ratio coefficient

    K = φ_раб / φ_хх,   φ_раб + φ_хх = 2π

(Артоболевский, «Теория механизмов и машин», § 25).
"""
from __future__ import annotations

import math
from functools import cached_property

import numpy as np
import pandas as pd
from .roots import brentq

from ..case import synthesis as SY
from ..case.printed import read_printed
from .plans import output_quantity

__all__ = ["Synthesis", "output_extremes", "swing_output", "swing_strokes"]


def output_extremes(study) -> dict:
    """Extreme positions of the output link over one crank cycle, found exactly:
    the sign changes of its first analog on the cycle grid, refined by ``brentq`` on
    :meth:`Study.at`.  Returns the output column, the crank coordinates q₁, q₂ of the extremes,
    the stroke |s(q₂) − s(q₁)|, the crank angles of the two strokes and K = max/min of them."""
    s_col, v_col, _, title = output_quantity(study)
    period = study.grid.length if study.mechanism.driver.periodic else None
    roots = analog_roots(study, v_col)
    if len(roots) != 2:
        return dict(column=s_col, title=title, extremes=len(roots))
    q1, q2 = roots
    s = study.at(np.array(roots))[s_col].to_numpy()
    d1 = q2 - q1
    d2 = (period - d1) if period else float("nan")
    return dict(column=s_col, title=title, extremes=2, q1=q1, q2=q2, s1=float(s[0]), s2=float(s[1]),
                stroke=abs(float(s[1] - s[0])), phi_a=d1, phi_b=d2,
                K=max(d1, d2) / min(d1, d2) if period else float("nan"))


def swing_output(study) -> dict:
    """The output link over the swing of an input rocker (or the stroke of an actuator): its
    value at both ends of the range and at every interior reversal (a root of its first analog,
    where the output stops and turns back while the input keeps moving), and its range
    s_max − s_min over the swing, taken from these exact values."""
    s_col, v_col, _, title = output_quantity(study)
    lo, hi = study.mechanism.driver.q_range
    roots = analog_roots(study, v_col)
    inner = [r for r in roots if lo < r < hi]
    qs = np.array([lo, *inner, hi])
    s = study.at(qs)[s_col].to_numpy()
    return dict(column=s_col, title=title, q=qs, s=s, reversals=inner,
                stroke=float(s.max() - s.min()), s_first=float(s[0]), s_last=float(s[-1]))


def swing_strokes(study) -> pd.DataFrame:
    """The forward (q_min → q_max, dq/dt = +ω₁) and return (q_max → q_min, dq/dt = −ω₁) strokes
    of an input rocker: the input's angles at the start and end of each, the output's values
    there, its range s_max − s_min and its path Σ|Δs| over the stroke (the ends and the interior
    reversals of :func:`swing_output`; the path exceeds the range when the output turns back
    inside the swing), and with ω₁ given the time of the stroke t = (q_max − q_min)/|ω₁| and the
    output's mean speed over it, path/t."""
    d = study.mechanism.driver
    lo, hi = d.q_range
    x = swing_output(study)
    s = x["s"]
    path = float(np.abs(np.diff(s)).sum())
    rows = []
    for name, a, b, sa, sb, sign in (("forward", lo, hi, s[0], s[-1], 1.0), ("return", hi, lo, s[-1], s[0], -1.0)):
        row = dict(stroke=name, q_from=a, q_to=b, q_from_deg=math.degrees(a), q_to_deg=math.degrees(b),
                   output=x["column"], s_from=float(sa), s_to=float(sb), s_range=x["stroke"], s_path=path)
        if d.omega is not None:
            t = (hi - lo) / d.omega
            row.update(omega=sign * d.omega, t=t, v_mean=path / t)
        rows.append(row)
    return pd.DataFrame(rows)


def analog_roots(study, v_col: str) -> list[float]:
    """The zeros of the first analog ``v_col`` over the cycle grid (sign changes refined by
    Brent's method on :meth:`Study.at`; a zero at a node is bracketed around it)."""
    cyc = study.cycle
    q = cyc["q"].to_numpy()
    v = cyc[v_col].to_numpy()

    def f(x: float) -> float:
        return float(study.at([x])[v_col].iloc[0])

    period = study.grid.length if study.mechanism.driver.periodic else None
    # nodes of the cycle (the last node repeats the first for a rotary driver); a zero of the
    # analog at a node (an extreme position at the start of the cycle) is bracketed around it
    if period:
        q, v = q[:-1], v[:-1]
    n = len(q)
    tiny = 1e-9 * float(np.max(np.abs(v)))
    roots: list[float] = []

    def add(x: float) -> None:
        x = float(x)
        if period:
            x = q[0] + (x - q[0]) % period
        if all(abs(x - r) > 1e-9 and (not period or abs(abs(x - r) - period) > 1e-9) for r in roots):
            roots.append(x)

    last = n if period else n - 1
    for i in range(last):
        j = (i + 1) % n
        a, b = q[i], q[j] + (period if j == 0 else 0.0)
        if abs(v[i]) <= tiny:
            if not period and i == 0:     # at the end of a range: the end itself
                add(a)
                continue
            h = 0.5 * (b - a)
            lo, hi = a - h, a + h
            flo, fhi = f(lo), f(hi)
            add(brentq(f, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
                if flo * fhi < 0 else a)
        elif v[i] * v[j] < 0 and abs(v[j]) > tiny:
            add(brentq(f, a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200))
    return sorted(roots)


class Synthesis:
    """The ``[synthesis]`` task: inputs, all variants, the chosen one and the engine's check."""

    def __init__(self, study):
        self.study = study
        self.node = SY.node_of(study.root)

    @cached_property
    def solved(self) -> tuple[str, dict, list[dict], int]:
        """The synthesis of ``[synthesis]`` (analysis.synthesis kinds): its kind, its inputs, the
        variants found and the index of the chosen one."""
        names = dict(self.study.params)
        return SY.solve(self.node, names)

    @property
    def kind(self) -> str:
        """The kind of linkage synthesised."""
        return self.solved[0]

    @property
    def inputs(self) -> dict:
        """The synthesis' given values (SI)."""
        return self.solved[1]

    @property
    def variants(self) -> list[dict]:
        """Every variant of the synthesis (one row each in the export)."""
        return self.solved[2]

    @property
    def chosen(self) -> dict:
        """The variant chosen by ``[synthesis] variant`` (the first by default)."""
        _, _, vs, i = self.solved
        return vs[i]

    @cached_property
    def check(self) -> dict | None:
        """What the engine measures on the synthesised linkage (None without a linkage)."""
        if not self.study.has_linkage:
            return None
        return output_extremes(self.study)

    def tables(self) -> dict[str, pd.DataFrame]:
        """Export table ``synthesis_variants`` with the chosen variant marked."""
        df = pd.DataFrame(self.variants)
        df.insert(0, "chosen", df["variant"] == self.chosen["variant"])
        return {"synthesis_variants": df}

    @cached_property
    def printed(self) -> list[dict]:
        """``[synthesis.printed]`` with the exact values (read here so that ``check`` sees the
        mistakes ``build`` would)."""
        return read_printed(self.node.table("printed"), self.chosen, SY.dim_of)

    def position_scalars(self) -> dict[str, float]:
        """``export --at``: the synthesis without its check on the linkage (which needs the cycle)."""
        out = {f"syn_{k}": float(v) for k, v in self.chosen.items()}
        out["syn_variants"] = len(self.variants)
        return out

    @cached_property
    def scalars(self) -> dict[str, float]:
        """Named results: the chosen variant's dimensions and, with a linkage, the stroke and the
        coefficient of the output's mean speed K measured on it."""
        self.printed
        out = self.position_scalars()
        chk = self.check
        if chk and chk.get("extremes") == 2:
            out.update(check_stroke=chk["stroke"], check_K=chk["K"], check_q1=chk["q1"], check_q2=chk["q2"])
        return out

    @cached_property
    def transmission(self) -> dict | None:
        """Least transmission angle of every variant (closed form, ``transmission_min``) and the
        best one the free datum of the problem allows at the same K and stroke or swing: the
        centre distance d = |OC| of a crank-rocker (any locus of O), λ = a/b of a slider-crank.
        None for the other kinds.  The best value: a log grid of the datum refined by a bounded
        scalar search around the grid's best point."""
        kind, x = self.kind, self.inputs
        if kind not in ("crank_rocker", "slider_crank"):
            return None
        from scipy.optimize import minimize_scalar

        from ..core import synthesis as core

        mus = [core.transmission_min(kind, v) for v in self.variants]
        if kind == "crank_rocker":
            lo, hi, name = 0.05 * x["c"], 20.0 * x["c"], "d"

            def solve(p):
                return core.crank_rocker(x["K"], x["psi"], x["c"], d=p)
        else:
            lo, hi, name = 0.01, 0.99, "lam"

            def solve(p):
                return core.slider_crank(x["K"], x["H"], lam=p)

        def best(p) -> tuple[float, dict | None]:
            vs = solve(p)
            if not vs:
                return -1.0, None
            v = max(vs, key=lambda w: core.transmission_min(kind, w))
            return core.transmission_min(kind, v), v

        grid = np.geomspace(lo, hi, 241)
        vals = [best(p)[0] for p in grid]
        i = int(np.argmax(vals))
        res = minimize_scalar(lambda p: -best(p)[0], bounds=(grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]),
                              method="bounded", options={"xatol": 1e-10 * hi})
        p = float(res.x) if -res.fun >= vals[i] else float(grid[i])
        mu_best, v_best = best(p)
        return {"mu": mus, "mu_min": mus[self.solved[3]], "param": name, "best_value": p,
                "best_mu": mu_best, "best": v_best}

    def target_stroke(self) -> float:
        """The stroke (m) or swing (rad) the synthesis was asked for: a crank-rocker's swing ψ; a
        slotted lever's swing when the lever is the output, the stroke H of its end when a slider
        driven by the end is (the shaper: in the lever's extreme positions its end D is at one
        height, so a coupler to a slider on a straight line transfers the chord H and K)."""
        x = self.inputs
        chk = self.check
        lever_out = chk is None or str(chk.get("column", "")).startswith("phi_")
        if self.kind == "crank_rocker" or (self.kind == "slotted_lever" and lever_out):
            return self.chosen["psi"]
        return x["H"]
