"""``[dof]``: the number of degrees of freedom of a mechanism with higher pairs and passive rollers
before and after replacing the higher pairs by links with two lower pairs (:mod:`reportgen.core.dof`),
and (``[dof.zero_speed]``) the positions where the output slider stops while the input link moves.

The zero-speed positions (worksheet 001, problem 2013-1, question 3).  A block M slides in a
straight slot of the rotating link 1 (pivot O) and drives the output slider; by the theorem of the
addition of velocities (Артоболевский, § 16)

    V̄_M = V̄_M1 + V̄_M6M1,   V̄_M1 = ω̄₁ × OM (⊥ OM),   V̄_M6M1 ∥ the slot ML.

Projected on the normal n̄ of the slot, V̄_M·n̄ = ω₁ (k̄ × OM)·n̄, so the output stops (V̄_M = 0, the
output being guided across the slot) when ω₁ = 0 (an extreme position of a swinging link 1) or when
(k̄ × OM) ∥ ML, i.e. ML ⊥ MO: the block sits at the foot of the perpendicular from O to the slot.
The engine finds these positions independently of that criterion, as the zeros of the output's first
analog S′(φ₁) (Brent's method on the exact position solution), and the criterion is then measured
at them (the angle OML and the distance from O to the slot line)."""
from __future__ import annotations

import math
from functools import cached_property

import numpy as np
import pandas as pd

from ..case import units as U
from ..core import dof as CD
from .printed_results import PrintedResults

__all__ = ["Dof"]

TYPES = {"R": "вращательная", "P": "поступательная", "H": "высшая"}


class Dof(PrintedResults):
    """Chebyshev's count of the case's structure, before and after the replacement."""

    PREFIX = "dof"
    DIMS = {"zero_q": U.ANGLE, "angle_OML": U.ANGLE, "zero_s": U.LENGTH, "zero_OM": U.LENGTH}

    def __init__(self, study):
        self.study = study
        self.node = node = study.root.table("dof")
        node.check_keys(["links", "pairs", "rollers", "printed", "zero_speed"], required=["links", "pairs"])
        self.zero_spec = self._read_zero(node.table("zero_speed")) if node.has("zero_speed") else None
        links = node.raw("links")
        if not isinstance(links, list) or not links or not all(isinstance(x, str) for x in links):
            raise node.error("links", "ожидался список названий подвижных звеньев 1…n",
                             expected='links = ["кривошип", "шатун", …]')
        self.links = ["стойка", *links]
        self.n = n = len(links)
        raw = node.raw("pairs")
        if not isinstance(raw, list) or not raw:
            raise node.error("pairs", "ожидался список пар", expected='pairs = [{ links = [0, 1], type = "R", name = "O" }, …]')
        self.pairs, self.names = [], []
        for pn in node.tables("pairs"):
            pn.check_keys(["links", "type", "name"], required=["links", "type"])
            ij = pn.raw("links")
            if (not isinstance(ij, list) or len(ij) != 2 or not all(isinstance(x, int) and not isinstance(x, bool)
                                                                   and 0 <= x <= n for x in ij) or ij[0] == ij[1]):
                raise pn.error("links", "ожидались номера двух разных звеньев", expected=f"[i, j], 0 ≤ i, j ≤ {n}")
            t = pn.string("type", required=True, choices=list(TYPES))
            self.pairs.append((ij[0], ij[1], t))
            self.names.append(pn.string("name", f"{ij[0]}–{ij[1]}"))
        rollers = node.raw("rollers", [])
        if not isinstance(rollers, list) or not all(isinstance(x, int) and 1 <= x <= n for x in rollers):
            raise node.error("rollers", "ожидался список номеров роликов", expected=f"rollers = [4], 1…{n}")
        for r in rollers:
            kinds = sorted(t for i, j, t in self.pairs if r in (i, j))
            if kinds not in (["H", "R"],):
                raise node.error("rollers", f"звено {r} — не ролик: у ролика одна вращательная и одна высшая пара",
                                 expected="ролик с одной вращательной и одной высшей парой")
        for r in range(1, n + 1):
            if not any(r in (i, j) for i, j, _ in self.pairs):
                raise node.error("pairs", f"звено {r} не входит ни в одну пару", expected="каждое звено в паре")
        self.rollers = list(rollers)
        self.before = CD.count(n, self.pairs, self.rollers)
        self.n_after, self.pairs_after, self.new_links = CD.replace_higher(n, self.pairs, self.rollers)
        self.after = CD.count(self.n_after, self.pairs_after)
        # names after: the pairs kept by name; a replaced higher pair's revolutes are primed
        it = iter(self.names)
        self.names_after = []
        for i, j, t in self.pairs:
            nm = next(it)
            if t != "H":
                self.names_after.append(nm)
            elif i in self.rollers or j in self.rollers:
                self.names_after.append(nm + "′")
            else:
                self.names_after += [nm + "₁′", nm + "₂′"]

    # ------------------------------------------------------------------ zero speed of the output
    def _read_zero(self, zn) -> dict:
        """``[dof.zero_speed]``: ``point`` M (the block in the slot of the driving link), ``line``
        L (a point of that slot), ``output`` (the output's name for the note)."""
        zn.check_keys(["point", "line", "output"], required=["point", "line"])
        st = self.study
        if not st.has_linkage:
            raise zn.error(None, "положение остановки выходного звена находится по рычажному механизму варианта",
                           expected="разделы [frame], [[links]], [[joints]], [driver] выходной части механизма")
        mech = st.mechanism
        d = mech.driver
        if not d.rotary:
            raise zn.error(None, "звено с прорезью должно быть ведущим вращающимся звеном",
                           expected="[driver] type = \"crank\" или \"rocker\"")
        M = zn.string("point", required=True)
        slot = [j for j in mech.prismatic if j.links[0] == d.link and j.point == M]
        if not slot:
            raise zn.error("point", f"точка «{M}» не скользит по прорези ведущего звена {d.link}",
                           expected="точка ползуна (камня) поступательной пары с направляющей — ведущим звеном")
        L = zn.string("line", required=True)
        if L not in mech.link(d.link).points or L == d.center:
            raise zn.error("line", f"точка «{L}» не принадлежит прорези ведущего звена {d.link}",
                           expected="точка звена " + d.link + ": " + ", ".join(p for p in mech.link(d.link).points
                                                                            if p != d.center))
        return dict(point=M, line=L, pivot=d.center, link=d.link, joint=slot[0], output=zn.text("output", "выходное звено"))

    @cached_property
    def zero(self) -> pd.DataFrame | None:
        """The positions where the output stops while link 1 moves (roots of the output's first
        analog inside the range), with the criterion measured there: the angle OML between the
        slot ML and MO, |OM| and the distance from O to the slot line, the analogs of V̄_M1 and
        V̄_M6M1 (per unit ω₁)."""
        z = self.zero_spec
        if z is None:
            return None
        from .plans import output_quantity
        from .synthesis import analog_roots
        st = self.study
        d = st.mechanism.driver
        s_col, v_col = output_quantity(st)[:2]
        roots = analog_roots(st, v_col)
        if d.q_range is not None:
            lo, hi = d.q_range
            roots = [r for r in roots if lo < r < hi]
        rows = []
        M, L, O = z["point"], z["line"], z["pivot"]
        if roots:
            at = st.at(np.array(roots))
            for r, (_, row) in zip(roots, at.iterrows()):
                m = np.array([row["x_" + M], row["y_" + M]])
                ml = np.array([row["x_" + L], row["y_" + L]]) - m
                mo = np.array([row["x_" + O], row["y_" + O]]) - m
                cosang = float(ml @ mo) / (np.linalg.norm(ml) * np.linalg.norm(mo))
                w1 = float(row["wq_" + d.link])
                v1 = w1 * np.array([mo[1], -mo[0]])           # ω̄₁ × OM with OM = −MO
                vm = np.array([row["vqx_" + M], row["vqy_" + M]])
                rows.append({"q": r, "q_deg": math.degrees(r), "s": float(row[s_col]),
                             "angle_OML": math.acos(max(-1.0, min(1.0, cosang))),
                             "OM": float(np.linalg.norm(mo)),
                             "h": abs(float(ml[0] * mo[1] - ml[1] * mo[0])) / float(np.linalg.norm(ml)),
                             "vqx_M1": v1[0], "vqy_M1": v1[1], "vqx_rel": vm[0] - v1[0], "vqy_rel": vm[1] - v1[1],
                             "vq_out": float(row[v_col])})
        return pd.DataFrame(rows, columns=["q", "q_deg", "s", "angle_OML", "OM", "h", "vqx_M1", "vqy_M1",
                                           "vqx_rel", "vqy_rel", "vq_out"])

    def _counts(self) -> dict:
        b, a = self.before, self.after
        return {"n": b["n"], "p5": b["p5"], "p4": b["p4"], "W": b["W"], "q": b["q"], "W_true": b["W_true"],
                "n_after": a["n"], "p5_after": a["p5"], "p4_after": a["p4"], "W_after": a["W"]}

    def results(self) -> dict:
        """Chebyshev's count W = 3n − 2p₅ − p₄ with its terms (the passive q and the true W) before
        and after replacing the higher pairs, and, with ``[dof.zero_speed]``, how many positions
        stop the output (roots of its first analog) with the first one's q, s, angle OML and OM."""
        out = self._counts()
        z = self.zero
        if z is not None:
            out["zero_count"] = len(z)
            if len(z):
                r = z.iloc[0]
                out.update(zero_q=r["q"], zero_s=r["s"], angle_OML=r["angle_OML"], zero_OM=r["OM"])
        return out

    # ``export --at``: the counts and the pairs; the zero-speed positions are searched over the
    # whole range of the input link (its cycle), so they are left out there
    def position_scalars(self) -> dict:
        """The counts of Chebyshev's formula as named scalars ``dof_*``."""
        return {f"{self.PREFIX}_{k}": float(v) for k, v in self._counts().items()}

    def position_tables(self) -> dict[str, pd.DataFrame]:
        """Export table ``dof_pairs``: each kinematic pair with its two links and its class."""
        return {"dof_pairs": pd.DataFrame([{"pair": nm, "i": i, "j": j, "type": t}
                                           for nm, (i, j, t) in zip(self.names, self.pairs)])}

    def tables(self) -> dict[str, pd.DataFrame]:
        """Export tables: ``dof_pairs`` and, when computed, ``dof_zero`` (the positions where the
        output stops)."""
        out = self.position_tables()
        if self.zero is not None:
            out["dof_zero"] = self.zero
        return out
