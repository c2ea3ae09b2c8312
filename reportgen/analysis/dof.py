"""``[dof]``: the number of degrees of freedom of a mechanism with higher pairs and passive rollers
before and after replacing the higher pairs by links with two lower pairs (:mod:`reportgen.core.dof`)."""
from __future__ import annotations

import pandas as pd

from ..core import dof as CD
from .printed_results import PrintedResults

__all__ = ["Dof"]

TYPES = {"R": "вращательная", "P": "поступательная", "H": "высшая"}


class Dof(PrintedResults):
    """Chebyshev's count of the case's structure, before and after the replacement."""

    PREFIX = "dof"

    def __init__(self, study):
        self.study = study
        self.node = node = study.root.table("dof")
        node.check_keys(["links", "pairs", "rollers", "printed"], required=["links", "pairs"])
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

    def results(self) -> dict:
        b, a = self.before, self.after
        out = {"n": b["n"], "p5": b["p5"], "p4": b["p4"], "W": b["W"], "q": b["q"], "W_true": b["W_true"],
               "n_after": a["n"], "p5_after": a["p5"], "p4_after": a["p4"], "W_after": a["W"]}
        return out

    def tables(self) -> dict[str, pd.DataFrame]:
        return {"dof_pairs": pd.DataFrame([{"pair": nm, "i": i, "j": j, "type": t}
                                           for nm, (i, j, t) in zip(self.names, self.pairs)])}
