"""Structural analysis: Chebyshev's W, Assur groups in solve order, structural formula.

W = 3n − 2p₅ − p₄ (Chebyshev; Артоболевский, «Теория механизмов и машин», §2).  The
decomposition detaches, starting from the initial mechanism, the smallest sets of links whose
pairs to already-known links make them statically determinate (3·n_g = 2·p_g), which are the
Assur groups; their order of detachment is the order in which kinematics is solved.  A
linear actuator's driving pair (cylinder–rod) is counted as a lower pair; for the solution the
cylinder and the rod are one body of variable length.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from itertools import combinations

from ..errors import StructureError
from .model import FRAME, Mechanism

# Russian names of the five kinds of class II groups (external – internal – external pair)
DYAD_KINDS = {"RRR": "ВВВ", "RRP": "ВВП", "RPR": "ВПВ", "PRP": "ПВП", "RPP": "ВПП"}
DYAD_ORDER = {"RRR": 1, "RRP": 2, "RPR": 3, "PRP": 4, "RPP": 5}
MOTION = {"crank": "вращательное (кривошип)", "rocker": "качательное (коромысло, кулиса)",
          "coupler": "плоскопараллельное (шатун)", "slider": "поступательное (ползун)",
          "cylinder": "качательное (гидроцилиндр)", "rod": "плоскопараллельное (шток)",
          "block": "плоскопараллельное (камень кулисы)",
          "input_rocker": "качательное (входное коромысло)"}


@dataclass
class Group:
    """An Assur group (or the initial mechanism) in the order of solution."""

    links: list[str]                  # real links of the group (names)
    bodies: list[str]                 # solver bodies (the actuator is one body)
    joints: list[int]                 # indices into Mechanism.joints (+ drive handled apart)
    external: list[int] = field(default_factory=list)
    internal: list[int] = field(default_factory=list)
    klass: int = 2                    # 1 for the initial mechanism
    order: int = 2
    kind: str = ""                    # "RRR", … for dyads; "" otherwise
    solver: str = "NEWTON"            # LIN, RRR, RRP, RPR, NEWTON
    pairs: int = 0                    # lower pairs of the group (to earlier links and inside)
    spec: list[int] = field(default_factory=list)   # solver body/joint indices (set by assembly)

    @property
    def label(self) -> str:
        return "(" + ",".join(([FRAME] if self.klass == 1 else []) + self.links) + ")"

    @property
    def kind_ru(self) -> str:
        return DYAD_KINDS.get(self.kind, "")

    @property
    def title(self) -> str:
        if self.klass == 1:
            return f"начальный механизм I{self.label}"
        if self.kind:
            return f"группа Ассура II класса {DYAD_ORDER[self.kind]}-го вида {self.label} {self.kind_ru}"
        return f"группа Ассура {_roman(self.klass)} класса {self.order}-го порядка {self.label}"

    @property
    def name(self) -> str:
        """Short identifier used in column names: links joined by '_'."""
        return "_".join(self.links)


@dataclass
class Structure:
    n: int                    # moving links
    p5: int                   # lower pairs
    p4: int                   # higher pairs
    W: int
    groups: list[Group]
    link_motion: dict[str, str]
    pairs: list[dict]         # rows of the pairs table
    formula: str
    mech_class: int

    @property
    def chebyshev(self) -> str:
        return f"W = 3·{self.n} − 2·{self.p5} − {self.p4} = {self.W}"


def _roman(k: int) -> str:
    return ["", "I", "II", "III", "IV", "V", "VI"][k] if k < 7 else str(k)


def solver_bodies(mech: Mechanism) -> dict[str, str]:
    """Real link → solver body (the actuator's rod is merged into the cylinder)."""
    m = {l.name: l.name for l in mech.links}
    if mech.driver.kind == "actuator":
        m[mech.driver.rod] = mech.driver.link
    return m


def analyse(mech: Mechanism) -> Structure:
    body_of = solver_bodies(mech)
    drv = mech.driver
    links = [l.name for l in mech.moving]
    n = len(links)
    p5 = len(mech.joints) + (1 if drv.kind == "actuator" else 0)
    W = 3 * n - 2 * p5
    if W != 1:
        raise StructureError(
            f"Механизм с одним ведущим звеном должен иметь W = 1, а по формуле Чебышева "
            f"W = 3·{n} − 2·{p5} = {W}. Проверьте список звеньев и пар "
            + ("(лишнее звено или не хватает пары)." if W > 1 else "(лишняя пара или не хватает звена)."))
    # attachment check: every link must be reachable from the frame
    adj: dict[str, set[str]] = {l.name: set() for l in mech.links}
    for j in mech.joints:
        adj[j.links[0]].add(j.links[1])
        adj[j.links[1]].add(j.links[0])
    if drv.kind == "actuator":
        adj[drv.link].add(drv.rod)
        adj[drv.rod].add(drv.link)
    seen, todo = {FRAME}, [FRAME]
    while todo:
        for nb in adj[todo.pop()]:
            if nb not in seen:
                seen.add(nb)
                todo.append(nb)
    loose = [l for l in links if l not in seen]
    if loose:
        raise StructureError("Звенья не присоединены к стойке: " + ", ".join(loose) + ".")

    # equations per joint in solver terms; the drive adds one equation to the initial link
    sj = [(body_of[j.links[0]], body_of[j.links[1]]) for j in mech.joints]
    known = {FRAME}
    bodies = [b for b in dict.fromkeys(body_of[l] for l in links)]
    groups: list[Group] = []
    # the initial mechanism
    first = drv.link
    if drv.rotary:
        init_j = [k for k, (a, b) in enumerate(sj) if {a, b} == {first, FRAME}]
        groups.append(Group([first], [first], init_j, external=init_j, klass=1, order=1, solver="LIN"))
        known.add(first)
        remaining = [b for b in bodies if b != first]
    else:
        # the cylinder with the frame is the initial mechanism; it is solved with its group
        groups.append(Group([first], [], [], klass=1, order=1, solver="NONE"))
        remaining = list(bodies)
    while remaining:
        found = None
        for size in range(1, len(remaining) + 1):
            for combo in combinations(remaining, size):
                cs = set(combo)
                js = [k for k, (a, b) in enumerate(sj)
                      if (a in cs or b in cs) and a in cs | known and b in cs | known]
                touched = {x for k in js for x in sj[k]} & cs
                if touched != cs:
                    continue
                eqs = 2 * len(js)
                if eqs == 3 * size:
                    found = (list(combo), js)
                    break
                if eqs > 3 * size:
                    raise StructureError(
                        "Избыточные связи: звенья " + ", ".join(combo) + " связаны со стойкой и ранее "
                        "присоединёнными звеньями большим числом пар, чем нужно для группы Ассура.")
            if found:
                break
        if not found:
            raise StructureError(
                "Не удалось выделить группы Ассура для звеньев " + ", ".join(remaining)
                + ": цепь не является механизмом с W = 1 или содержит неразрешимую группу.")
        combo, js = found
        groups.append(_classify(mech, combo, js, sj, known, body_of))
        known |= set(combo)
        remaining = [b for b in remaining if b not in combo]
    _count_pairs(mech, groups)
    motion = _link_motion(mech, groups)
    pairs = _pairs_table(mech)
    mech_class = max(g.klass for g in groups)
    formula = " → ".join(("I" if g.klass == 1 else _roman(g.klass)) + g.label for g in groups)
    return Structure(n, p5, 0, W, groups, motion, pairs, formula, mech_class)


def _classify(mech: Mechanism, combo, js, sj, known, body_of) -> Group:
    inv: dict[str, list[str]] = {}
    for l, b in body_of.items():
        inv.setdefault(b, []).append(l)
    real = [l for b in combo for l in sorted(inv[b], key=lambda x: [m.name for m in mech.links].index(x))]
    if mech.driver.kind == "actuator" and mech.driver.link in combo:
        # the worksheet convention: the cylinder forms the initial mechanism, its group is (rod, …)
        real = [l for l in real if l != mech.driver.link]
    internal = [k for k in js if sj[k][0] in combo and sj[k][1] in combo]
    external = [k for k in js if k not in internal]
    g = Group(real, list(combo), js, external=external, internal=internal)
    if len(combo) == 2:
        a, b = combo
        ja = [k for k in external if a in sj[k]]
        jc = [k for k in external if b in sj[k]]
        if len(ja) == 1 and len(jc) == 1 and len(internal) == 1:
            kinds = mech.joints[ja[0]].kind + mech.joints[internal[0]].kind + mech.joints[jc[0]].kind
            if kinds == "PPP":
                raise StructureError(f"Группа {g.label} из трёх поступательных пар не определяет положение звеньев.")
            canon = {"RRR": "RRR", "RRP": "RRP", "PRR": "RRP", "RPR": "RPR", "PRP": "PRP",
                     "RPP": "RPP", "PPR": "RPP"}[kinds]
            g.kind = canon
            g.order = 2
            g.solver = {"RRR": "RRR", "RRP": "RRP", "RPR": "RPR"}.get(canon, "LIN")
            return g
    g.klass = 3 if len(combo) == 4 else len(combo) // 2 + 1
    g.order = len(external)
    g.solver = "NEWTON"
    return g


def _count_pairs(mech: Mechanism, groups: list[Group]) -> None:
    """p₅ of every group in structural terms: pairs joining its links to each other or to links
    attached before it (the actuator's driving pair belongs to the rod's group)."""
    pairs = [j.links for j in mech.joints]
    if mech.driver.kind == "actuator":
        pairs.append((mech.driver.link, mech.driver.rod))
    known = {FRAME}
    for g in groups:
        own = set(g.links)
        g.pairs = sum(1 for a, b in pairs if (a in own or b in own) and a in own | known and b in own | known)
        known |= own


def _link_motion(mech: Mechanism, groups) -> dict[str, str]:
    out = {}
    for l in mech.moving:
        js = [j for j in mech.joints if l.name in j.links]
        on_frame = [j for j in js if FRAME in j.links]
        if mech.driver.kind == "actuator" and l.name == mech.driver.link:
            out[l.name] = MOTION["cylinder"]
        elif mech.driver.kind == "actuator" and l.name == mech.driver.rod:
            out[l.name] = MOTION["rod"]
        elif mech.driver.kind == "crank" and l.name == mech.driver.link:
            out[l.name] = MOTION["crank"]
        elif mech.driver.kind == "rocker" and l.name == mech.driver.link:
            out[l.name] = MOTION["input_rocker"]
        elif any(j.kind == "P" and j.links[1] == l.name and j.links[0] == FRAME for j in on_frame):
            out[l.name] = MOTION["slider"]
        elif any(j.kind == "R" for j in on_frame):
            out[l.name] = MOTION["rocker"]
        elif len(l.points) == 1 and any(j.kind == "P" and j.links[1] == l.name for j in js):
            out[l.name] = MOTION["block"]
        else:
            out[l.name] = MOTION["coupler"]
    return out


def _pairs_table(mech: Mechanism) -> list[dict]:
    rows = []
    for j in mech.joints:
        rows.append(dict(name=j.name, links=f"{j.links[0]}–{j.links[1]}", point=j.point,
                         kind="вращательная" if j.kind == "R" else "поступательная",
                         klass=5, level="низшая"))
    if mech.driver.kind == "actuator":
        d = mech.driver
        rows.append(dict(name=f"{d.link}{d.rod}", links=f"{d.link}–{d.rod}", point="—",
                         kind="поступательная (ведущая)", klass=5, level="низшая"))
    return rows


def decomposition(st, d) -> tuple[list[dict], str]:
    """Rows of the structural table and the structural formula. For an actuator-driven linkage
    the initial mechanism is the cylinder, the rod and the link the rod drives, with the driving
    prismatic pair inside (n = 3, p5 = 4, W = 1; Попов, Тимофеев, гл. 2), not a crank I(0,1).
    ``st``: the structure; ``d``: the mechanism's driver."""
    rows = [{"g": g.label, "title": "начальный механизм I класса" if g.klass == 1 else g.title,
             "n": len(g.links), "p": g.pairs, "W": 3 * len(g.links) - 2 * g.pairs} for g in st.groups]
    parts = st.formula.split(" → ")
    if d.kind != "actuator":
        return rows, st.formula
    ic = next(i for i, g in enumerate(st.groups) if d.link in g.links)
    ir = next(i for i, g in enumerate(st.groups) if d.rod in g.links)
    if ic == ir:
        return rows, st.formula
    gc, gr = st.groups[ic], st.groups[ir]
    links = list(dict.fromkeys([d.link, d.rod] + list(gc.links) + list(gr.links)))
    label = "(" + ",".join(links) + ")"
    head = {"g": label, "title": f"начальный механизм с ведущей поступательной парой {d.link}–{d.rod} "
                                 f"(гидроцилиндр)", "n": len(links), "p": gc.pairs + gr.pairs,
            "W": 3 * len(links) - 2 * (gc.pairs + gr.pairs)}
    rest = [r for i, r in enumerate(rows) if i not in (ic, ir)]
    rest_parts = [p for i, p in enumerate(parts) if i not in (ic, ir)]
    return [head] + rest, " → ".join([f"I{label}"] + rest_parts)
