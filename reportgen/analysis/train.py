"""Planetary and compound gear trains: a graph of members, wheels and meshes (Russian ТММ course
method: Попов–Тимофеев «Курсовое проектирование по ТММ», Артоболевский гл. «Зубчатые механизмы»).

Model.  A *member* (звено) is a rigid body turning about its *axis*; an axis is a point carried by
a member (a carrier, водило) or by the frame «0».  A *wheel* (z, module, external or internal)
belongs to a member and is centred on an axis (by default the member's own).  A *mesh* joins two
wheels.  Members held fixed, the input and the output are named in the case.

Two independent formulations of the kinematics:

* **Willis** (метод обращения движения): for every mesh a–b the member H on which both wheel
  centres stand still is found; then (ω_a − ω_H) = ∓(z_b/z_a)(ω_b − ω_H) (− external, + internal).
  Tooth numbers only, no dimensions.
* **Direct velocity analysis** (картина скоростей): the axes are placed at scale on one line
  (distances from the pitch radii r = mz/2); every member's velocity field along that line is
  v(y) = v_host(y_axis) + ω (y − y_axis); at every pitch point the two wheels' velocities are
  equal.  Radii only, no ratios.

Both give linear systems in the angular velocities (the input ω = 1, fixed members ω = 0), solved
and compared.  The placement of the axes also checks coaxiality (соосность): a mesh whose both
centres are already placed must have the distance of its pitch radii.

Tooth-number selection for a target ratio, for any train of this graph (2K-H with single or
double satellites and any mix of external and internal meshes, 3K, several carriers): wheels with
z = "select" (and "coaxial") are found by ``train_select`` with the ratio as an exact function of
the tooth numbers, coaxiality from the loops of axes, assembly of k satellites, neighbourhood,
undercut and internal-mesh checks, enumerated and ranked by the overall size.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property

import numpy as np
import pandas as pd

from ..case import units as U
from ..case.reader import Node
from ..errors import CaseError

__all__ = ["Wheel", "TrainModel", "Train", "willis", "direct", "select_2kh", "ratio_chain",
           "coaxiality_equations", "parse_linear", "judge_printed_coaxiality", "two_kh_model",
           "check_2kh"]

FRAME = "0"


@dataclass(frozen=True)
class Wheel:
    """A toothed wheel of a train: its name, tooth number z, the member it belongs to, its axis,
    internal or external, module m."""
    name: str
    z: int
    member: str
    centre: str
    internal: bool
    m: float


@dataclass
class TrainModel:
    """A gear train: its members and their axes (an axis hosted by the frame or by a carrier), the
    wheels, the meshes, the fixed members, the input and the output."""
    members: dict[str, str]          # member → its rotation axis
    axes: dict[str, str]             # axis → host member (FRAME for the frame)
    wheels: dict[str, Wheel]
    meshes: list[tuple[str, str]]
    fixed: tuple[str, ...]
    inp: str
    out: str

    def depth(self, axis: str) -> int:
        """Nesting of an axis: 0 on the frame, 1 on a carrier turning about a frame axis, …"""
        d, host = 0, self.axes[axis]
        while host != FRAME:
            d += 1
            host = self.axes[self.members[host]]
            if d > len(self.members):
                raise ValueError("carrier cycle")
        return d

    def central_axis(self) -> str:
        """The train's central axis (y = 0 of the scheme): the frame axis a carrier turns about
        (the axis of the central wheels of a planetary stage), else the default axis «O», else the
        first frame axis.  A parallel frame axis of a simple stage (a motor pinion) is placed off
        it, so that the scheme is symmetric about the planetary stage's axis, not the pinion's."""
        frame_axes = [a for a, h in self.axes.items() if h == FRAME]
        carriers = {h for h in self.axes.values() if h != FRAME}
        for a in frame_axes:
            if any(self.members.get(c) == a for c in carriers):
                return a
        return "O" if "O" in frame_axes else frame_axes[0]

    def carries(self, member: str, axis: str) -> bool:
        """Does the axis stand still in the member (carried by it, or its rotation axis with the
        same host)?"""
        return self.axes[axis] == member or self.members[member] == axis

    def mesh_carrier(self, a: str, b: str) -> str:
        """The member in which both wheel centres stand still (Willis: the carrier held)."""
        ca, cb = self.wheels[a].centre, self.wheels[b].centre
        cands = [FRAME] + list(self.members)
        for h in cands:
            if h == FRAME:
                if self.axes[ca] == FRAME and self.axes[cb] == FRAME:
                    return FRAME
            elif self.carries(h, ca) and self.carries(h, cb):
                return h
        raise ValueError(f"mesh {a}-{b}: no member carries both centres")


def _solve(rows, rhs, names):
    A = np.array(rows, float)
    b = np.array(rhs, float)
    if A.shape[0] < A.shape[1] or np.linalg.matrix_rank(A) < A.shape[1]:
        raise ValueError("the train is not determinate (W ≠ 1 for the given input and fixed members)")
    w, *_ = np.linalg.lstsq(A, b, rcond=None)
    if np.max(np.abs(A @ w - b)) > 1e-9 * max(1.0, np.max(np.abs(b))):
        raise ValueError("the velocity constraints are inconsistent")
    return dict(zip(names, w))


def _base_rows(model: TrainModel, names, fixed, inp):
    idx = {n: i for i, n in enumerate(names)}
    rows, rhs = [], []
    for f in fixed:
        r = np.zeros(len(names)); r[idx[f]] = 1; rows.append(r); rhs.append(0.0)
    r = np.zeros(len(names)); r[idx[inp]] = 1; rows.append(r); rhs.append(1.0)
    return idx, rows, rhs


def willis(model: TrainModel, fixed=None, inp=None) -> dict[str, float]:
    """Angular velocities (ω_input = 1) from the Willis equation of every mesh."""
    fixed = model.fixed if fixed is None else fixed
    inp = model.inp if inp is None else inp
    names = list(model.members)
    idx, rows, rhs = _base_rows(model, names, fixed, inp)
    for a, b in model.meshes:
        wa, wb = model.wheels[a], model.wheels[b]
        k = (1.0 if (wa.internal or wb.internal) else -1.0) * wb.z / wa.z
        h = model.mesh_carrier(a, b)
        r = np.zeros(len(names))
        r[idx[wa.member]] += 1.0
        r[idx[wb.member]] -= k
        if h != FRAME:
            r[idx[h]] += k - 1.0
        rows.append(r); rhs.append(0.0)
    return _solve(rows, rhs, names)


def _dist_terms(model: TrainModel, a: str, b: str) -> dict[str, float]:
    """Centre distance of a mesh as a linear form in the tooth numbers, mm per tooth:
    m(z_a + z_b)/2 external, m(z_int − z_ext)/2 internal."""
    wa, wb = model.wheels[a], model.wheels[b]
    if wa.internal or wb.internal:
        big, small = (a, b) if wa.internal else (b, a)
        return {big: wa.m / 2, small: -wa.m / 2}
    return {a: wa.m / 2, b: wa.m / 2}


def place_axes(model: TrainModel, loops: list | None = None,
               forms: dict | None = None) -> tuple[dict[str, float], list[tuple[str, str, float]]]:
    """Axis positions on the scheme's line (breadth-first from the central axis): a
    deeper axis is placed above its partner.  Returns positions and the coaxiality residuals
    (mesh, |Δy| − a) of meshes closing a loop.  With ``loops`` given, it receives for every closing
    mesh the coaxiality equation as two linear forms in the tooth numbers (mm per tooth):
    (mesh, path, closing) with path = y_b − y_a along the placing meshes (made positive) and
    closing = the mesh's own centre distance; the condition is path = closing.  With ``forms``
    given, it receives every placed axis's position as a linear form in the tooth numbers."""
    def dist(a, b):
        wa, wb = model.wheels[a], model.wheels[b]
        if wa.m != wb.m:
            raise ValueError(f"mesh {a}-{b}: different modules")
        return wa.m * (abs(wa.z - wb.z) if (wa.internal or wb.internal) else wa.z + wb.z) / 2
    centre = model.central_axis()
    y = {centre: 0.0}
    sym: dict[str, dict[str, float]] = {centre: {}}
    resid = []
    changed = True
    done = set()
    while changed:
        changed = False
        for a, b in model.meshes:
            if (a, b) in done:
                continue
            ca, cb = model.wheels[a].centre, model.wheels[b].centre
            if model.wheels[a].z == 0 or model.wheels[b].z == 0:
                continue            # a tooth number still to come from coaxiality
            d = dist(a, b)
            if ca in y and cb in y:
                resid.append((f"{a}–{b}", abs(y[ca] - y[cb]) - d))
                if loops is not None:
                    sg = 1.0 if y[cb] >= y[ca] else -1.0
                    path = {w: sg * (sym[cb].get(w, 0.0) - sym[ca].get(w, 0.0))
                            for w in set(sym[ca]) | set(sym[cb])}
                    loops.append(((a, b), {w: c for w, c in path.items() if abs(c) > 1e-12},
                                  _dist_terms(model, a, b)))
                done.add((a, b)); changed = True
            elif ca in y or cb in y:
                k, u = (ca, cb) if ca in y else (cb, ca)
                sgn = 1.0 if model.depth(u) >= model.depth(k) else -1.0
                y[u] = y[k] + sgn * d
                sym[u] = dict(sym[k])
                for w, c in _dist_terms(model, a, b).items():
                    sym[u][w] = sym[u].get(w, 0.0) + sgn * c
                done.add((a, b)); changed = True
        if not changed:
            for a in model.axes:
                if a not in y and model.axes[a] == FRAME:
                    y[a] = max(y.values()) + 1.0  # an unconnected frame axis: never meshes
                    sym[a] = {}
                    changed = True
                    break
    for a in model.axes:
        y.setdefault(a, 0.0)
    if forms is not None:
        forms.update(sym)
    return y, resid


def coaxiality_equations(model: TrainModel) -> list[tuple[tuple[str, str], dict[str, Fraction], dict[str, Fraction]]]:
    """The coaxiality conditions of the train, one per mesh closing a loop of axes, as integer
    linear forms in the tooth numbers (the common factor m/2 divided out): path = closing."""
    loops: list = []
    place_axes(model, loops)
    out = []
    for mesh, path, close in loops:
        unit = min(abs(c) for c in list(path.values()) + list(close.values()))
        f = lambda t: {w: Fraction(c / unit).limit_denominator(1000) for w, c in t.items()}  # noqa: E731
        out.append((mesh, f(path), f(close)))
    return out


_TERM = r"([+-]?)(\d*)\*?z_?(?:\{([^{}]+)\}|([A-Za-z0-9'′]+))"


def _side(text: str, wheels) -> dict[str, Fraction]:
    """One side of a printed equation, «z1 − z2», as {wheel: coefficient}."""
    import re
    body = text.replace("−", "-").replace(" ", "")
    pos, form = 0, {}
    while pos < len(body):
        mt = re.compile(_TERM).match(body, pos)
        if not mt or (pos and not mt.group(1)):
            raise ValueError(f"не разобрано: «{text.strip()}»")
        sg, k, n1, n2 = mt.groups()
        n = (n1 or n2).replace("′", "'")
        if n not in wheels:
            raise ValueError(f"неизвестное колесо «{n}»")
        form[n] = form.get(n, Fraction(0)) + (-1 if sg == "-" else 1) * int(k or 1)
        pos = mt.end()
    if not form:
        raise ValueError(f"пустая часть равенства: «{text.strip()}»")
    return form


def parse_linear(text: str, wheels) -> tuple[dict[str, Fraction], dict[str, Fraction]]:
    """«z1 − z2 = z4 + z3» → (lhs, rhs) as {wheel: coefficient}; ValueError on anything else.
    Terms are [±][integer] z<name> (z_<name>, z_{<name>} also accepted)."""
    if text.count("=") != 1:
        raise ValueError("ожидалось одно равенство")
    left, right = text.split("=")
    return _side(left, wheels), _side(right, wheels)


def _proportional(a: dict, b: dict) -> bool:
    if set(a) != set(b) or not a:
        return False
    w0 = next(iter(a))
    r = a[w0] / b[w0]
    return all(a[w] == r * b[w] for w in a)


def judge_printed_coaxiality(model: TrainModel, text: str) -> dict:
    """Check a printed coaxiality equation against the train's: returns {"ok": bool, "flipped":
    one side written with the wrong sign (a difference the wrong way round), "lhs"/"rhs": the
    printed sides' values with the tooth numbers, "correct": (path, closing) of the matching loop
    or None}."""
    lhs, rhs = parse_linear(text, model.wheels)
    form = {w: lhs.get(w, 0) - rhs.get(w, 0) for w in set(lhs) | set(rhs)}
    form = {w: c for w, c in form.items() if c}
    val = lambda t: sum(c * model.wheels[w].z for w, c in t.items())  # noqa: E731
    out = {"ok": False, "flipped": False, "lhs": val(lhs), "rhs": val(rhs), "correct": None}
    for _, path, close in coaxiality_equations(model):
        true = {w: path.get(w, 0) - close.get(w, 0) for w in set(path) | set(close)}
        true = {w: c for w, c in true.items() if c}
        if set(true) != set(form):
            continue
        out["correct"] = (path, close)
        if _proportional(form, true):
            out["ok"] = True
        else:
            alt = {w: -lhs.get(w, 0) - rhs.get(w, 0) for w in set(lhs) | set(rhs)}
            out["flipped"] = _proportional({w: c for w, c in alt.items() if c}, true)
        break
    return out


def solve_coaxial(model: TrainModel) -> list[tuple[str, str, float, int]]:
    """Tooth numbers given as "coaxial" (z = 0 in the model) from the coaxiality of their mesh:
    the axes are placed through the other meshes, then a = |y_a − y_b| gives
    z = 2a/m − z_p (external), z_p + 2a/m (the wheel internal), z_p − 2a/m (the partner internal).
    Fills the model in place; returns (wheel, partner, a, z) in the order solved."""
    out = []
    while any(w.z == 0 for w in model.wheels.values()):
        y, _ = place_axes(model)
        progress = False
        for a, b in model.meshes:
            for w, p in ((a, b), (b, a)):
                ww, wp = model.wheels[w], model.wheels[p]
                if ww.z == 0 and wp.z != 0 and ww.centre in y and wp.centre in y:
                    placed = _placed(model, ww.centre) and _placed(model, wp.centre)
                    if not placed:
                        continue
                    d = abs(y[ww.centre] - y[wp.centre])
                    n = 2 * d / ww.m
                    z = wp.z + n if ww.internal else (wp.z - n if wp.internal else n - wp.z)
                    if abs(z - round(z)) > 1e-9 or round(z) < 5:
                        raise ValueError(f"wheel {w}: coaxiality gives z = {z}")
                    model.wheels[w] = Wheel(w, int(round(z)), ww.member, ww.centre, ww.internal, ww.m)
                    out.append((w, p, d, int(round(z))))
                    progress = True
        if not progress:
            raise ValueError("coaxiality does not determine the tooth numbers")
    return out


def _placed(model: TrainModel, axis: str) -> bool:
    """Is the axis placed by a mesh of known wheels (or is it the central axis)?"""
    if axis == model.central_axis():
        return True
    return any(model.wheels[a].z and model.wheels[b].z and axis in (model.wheels[a].centre, model.wheels[b].centre)
               for a, b in model.meshes)


def direct(model: TrainModel, fixed=None, inp=None) -> dict[str, float]:
    """Angular velocities (ω_input = 1) from equal velocities at the pitch points."""
    fixed = model.fixed if fixed is None else fixed
    inp = model.inp if inp is None else inp
    y, _ = place_axes(model)
    names = list(model.members)
    idx, rows, rhs = _base_rows(model, names, fixed, inp)

    def field_row(member: str, at: float) -> np.ndarray:
        """Coefficients of v_member(at) in the ω's: v = v_host(y_axis) + ω (at − y_axis)."""
        r = np.zeros(len(names))
        while member != FRAME:
            ax = model.members[member]
            r[idx[member]] += at - y[ax]
            at = y[ax]
            member = model.axes[ax]
        return r

    for a, b in model.meshes:
        wa, wb = model.wheels[a], model.wheels[b]
        ya, yb = y[wa.centre], y[wb.centre]
        # pitch point: on the side of the partner for the smaller wheel of an internal pair
        if wa.internal:
            yp = yb + math.copysign(wb.m * wb.z / 2, yb - ya)
        elif wb.internal:
            yp = ya + math.copysign(wa.m * wa.z / 2, ya - yb)
        else:
            yp = ya + math.copysign(wa.m * wa.z / 2, yb - ya)
        rows.append(field_row(wa.member, yp) - field_row(wb.member, yp)); rhs.append(0.0)
    return _solve(rows, rhs, names)


def pitch_points(model: TrainModel) -> dict[tuple[str, str], float]:
    """Pitch point positions on the scheme's line (for the velocity picture)."""
    y, _ = place_axes(model)
    out = {}
    for a, b in model.meshes:
        wa, wb = model.wheels[a], model.wheels[b]
        ya, yb = y[wa.centre], y[wb.centre]
        if wa.internal:
            out[(a, b)] = yb + math.copysign(wb.m * wb.z / 2, yb - ya)
        elif wb.internal:
            out[(a, b)] = ya + math.copysign(wa.m * wa.z / 2, ya - yb)
        else:
            out[(a, b)] = ya + math.copysign(wa.m * wa.z / 2, yb - ya)
    return out


def ratio_chain(w: dict[str, float], inp: str, out: str) -> list[str]:
    """Members from the input to the output ordered by |ω| (moving members whose |ω| lies between
    those of the input and the output).  The ratio is the product of the stage ratios
    u = Π ω_k/ω_{k+1} along the chain (the product telescopes), each stage ratio being moderate,
    so each stage's plan of angular velocities can be drawn and read at a useful scale."""
    a, b = abs(w[inp]), abs(w[out])
    lo, hi = min(a, b), max(a, b)
    mid = [n for n, v in w.items() if n not in (inp, out) and abs(v) > 1e-12 and lo < abs(v) < hi]
    mid.sort(key=lambda n: abs(w[n]), reverse=bool(a > b))
    return [inp, *mid, out]


# ------------------------------------------------------------------------- tooth-number selection
def two_kh_model(double: bool, z: dict[str, int] | None = None) -> TrainModel:
    """The 2K-H train of Джеймс (sun 1, satellites 2 or blocks 2–2′ on carrier H, fixed ring 3,
    input 1, output H), unit module; tooth numbers from ``z`` (0 = to be selected)."""
    z = z or {}
    spec = [("1", "1", False), ("2", "2", False)] + ([("2'", "2", False)] if double else []) + [("3", "3", True)]
    wheels = {n: Wheel(n, z.get(n, 0), mem, "A" if mem == "2" else "O", internal, 1.0) for n, mem, internal in spec}
    return TrainModel({"1": "O", "2": "A", "3": "O", "H": "O"}, {"O": FRAME, "A": "H"}, wheels,
                      [("1", "2"), ("2'" if double else "2", "3")], ("3",), "1", "H")


def check_2kh(z1, z2, z3, k, target, tol, ha=1.0, z_min=17, dz_int=8, z2b=None):
    """All conditions of a 2K-H set (``z2b`` the second wheel of a double satellite, meshing the
    ring), by the general check of ``train_select``."""
    from .train_select import check
    z = {"1": z1, "2": z2, "3": z3} | ({"2'": z2b} if z2b is not None else {})
    return check(two_kh_model(z2b is not None, z), k, target, tol, ha=ha, z_min=z_min, dz_int=dz_int)


def select_2kh(target: float, k: int, *, tol: float = 0.03, double: bool = False, z_max: int = 150,
               ha: float = 1.0, z_min: int = 17, dz_int: int = 8, limit: int = 10):
    """2K-H sets near the target ratio by the general enumeration of ``train_select``:
    (accepted ranked by size then Σz, rejected ranked before them with their reasons)."""
    from .train_select import select
    ok, bad, _ = select(two_kh_model(double), target, k, tol=tol, z_min=z_min, z_max=z_max,
                        dz_int=dz_int, ha=ha, limit=limit)
    return ok, bad


# --------------------------------------------------------------------------------- case reading
TRAIN_KEYS = ["module", "input", "output", "fixed", "planets", "target", "axes", "member", "wheel",
              "meshes", "select", "tolerance", "printed"]


def read_model(node: Node, names) -> tuple[TrainModel, dict]:
    """[train] of the case → the model (and the selection settings)."""
    node.check_keys(TRAIN_KEYS, required=["wheel", "meshes", "input", "output"])
    m0 = node.quantity("module", U.LENGTH, names, default="1 mm", positive=True) * 1000.0
    axes_node = node.table("axes")
    members: dict[str, str] = {}
    for mn in node.tables("member"):
        mn.check_keys(["name", "axis"], required=["name"])
        members[mn.string("name", required=True)] = mn.string("axis", "O")
    wheels: dict[str, Wheel] = {}
    sel = node.table("select")
    coaxial: list[str] = []
    for wn in node.tables("wheel"):
        wn.check_keys(["name", "z", "member", "centre", "internal", "module"], required=["name", "z"])
        name = wn.string("name", required=True)
        if name in wheels:
            raise wn.error("name", f"колесо «{name}» задано дважды", expected="уникальные имена колёс")
        zraw = wn.raw("z")
        z = 0 if (zraw == "select" and sel.data) or zraw == "coaxial" else wn.integer("z", minimum=5)
        if zraw == "coaxial":
            coaxial.append(wn.string("name", required=True))
        member = wn.string("member", name)
        members.setdefault(member, "O")
        m = wn.quantity("module", U.LENGTH, names, positive=True) * 1000.0 if wn.has("module") else m0
        wheels[name] = Wheel(name, z, member, wn.string("centre", members[member]),
                             wn.boolean("internal", False), m)
    axes: dict[str, str] = {}
    for a, h in axes_node.data.items():
        if not isinstance(h, str) or h not in members:
            raise axes_node.error(a, f"ось «{a}»: неизвестное звено-носитель «{h}»",
                                  expected="имя звена (водила) из [[train.member]]")
        axes[a] = h
    for w in wheels.values():
        axes.setdefault(w.centre, FRAME)
    for ax in members.values():
        axes.setdefault(ax, FRAME)
    meshes = node.raw("meshes")
    if not isinstance(meshes, list) or not all(isinstance(p, list) and len(p) == 2 for p in meshes):
        raise node.error("meshes", "ожидался список пар колёс", expected='[["1", "2"], ["2", "3"]]')
    for p in meshes:
        for w in p:
            if str(w) not in wheels:
                raise node.error("meshes", f"неизвестное колесо «{w}»",
                                 expected="имя из [[train.wheel]]: " + ", ".join(wheels))
    fixed = node.raw("fixed", [])
    fixed = [fixed] if isinstance(fixed, str) else fixed
    if not isinstance(fixed, list) or not all(isinstance(f, str) for f in fixed):
        raise node.error("fixed", "ожидался список имён неподвижных звеньев", expected='fixed = ["3"]')
    for key, val in (("input", node.raw("input")), ("output", node.raw("output"))):
        if str(val) not in members:
            raise node.error(key, f"неизвестное звено «{val}»", expected="одно из: " + ", ".join(members))
    for f in fixed:
        if str(f) not in members:
            raise node.error("fixed", f"неизвестное звено «{f}»", expected="одно из: " + ", ".join(members))
    model = TrainModel(members, axes, wheels, [(str(a), str(b)) for a, b in meshes],
                       tuple(str(f) for f in fixed), str(node.raw("input")), str(node.raw("output")))
    try:
        for a, b in model.meshes:
            model.mesh_carrier(a, b)
        for ax in axes:
            model.depth(ax)
    except ValueError:
        raise node.error("meshes", "центры колёс зацепления не принадлежат одному звену",
                         expected="оси сателлитов на водиле ([train.axes])") from None
    printed = {k: float(v) for k, v in node.table("printed").data.items()
               if isinstance(v, (int, float)) and not isinstance(v, bool)}
    eqs = node.table("printed").data.get("coaxiality", [])
    if isinstance(eqs, str):
        eqs = [eqs]
    if not isinstance(eqs, list) or not all(isinstance(e, str) for e in eqs):
        raise node.error("printed", "coaxiality: ожидался список равенств-строк",
                         expected='coaxiality = ["z1 - z2 = z4 + z3"]')
    opts = {"printed": printed, "printed_coaxiality": eqs, "target": node.quantity("target", U.DIMENSIONLESS, names) if node.has("target") else None,
            "planets": _planets(node, members, axes),
            "tolerance": node.quantity("tolerance", U.DIMENSIONLESS, names, default=0.03, nonnegative=True),
            "coaxial": coaxial}
    if sel.data:
        # sun/planet/planet2/ring: roles of the first version, accepted and not needed (the graph says it)
        sel.check_keys(["scheme", "sun", "planet", "planet2", "ring", "z_max", "z_min", "z_from", "dz_internal",
                        "limit"])
        opts["select"] = {
            "scheme": sel.string("scheme", ""),
            "z_max": sel.integer("z_max", 150, minimum=20, maximum=400),
            "z_min": sel.integer("z_min", 17, minimum=5),
            "z_from": sel.integer("z_from", None, minimum=5),
            "dz_internal": sel.integer("dz_internal", 8, minimum=1),
            "limit": sel.integer("limit", 6, minimum=1, maximum=100)}
        if not any(w.z == 0 for w in wheels.values()):
            raise node.error("select", "для подбора нужны колёса с z = \"select\"",
                             expected='z = "select" у подбираемых колёс')
        if opts["target"] is None:
            raise node.error("target", "для подбора чисел зубьев нужно целевое передаточное отношение",
                             expected="target = 6.0")
    return model, opts


def _planets(node: Node, members: dict, axes: dict):
    """``planets``: k of every carrier (an integer) or a table {carrier = k}."""
    raw = node.raw("planets", 1)
    if not isinstance(raw, dict):
        return node.integer("planets", 1, minimum=1, maximum=24)
    carriers = sorted({h for h in axes.values() if h != FRAME})
    tab = node.table("planets")
    for name in raw:
        if name not in carriers:
            raise tab.error(name, f"«{name}» — не водило", expected="водило из [train.axes]: " + ", ".join(carriers))
    return {name: tab.integer(name, 1, minimum=1, maximum=24) for name in raw}


class Train:
    """The [train] task: ratios by Willis and by the velocity picture, the selection of tooth
    numbers when asked, coaxiality residuals."""

    def __init__(self, study):
        self.study = study
        names = study.spec.parameters() if hasattr(study.spec, "parameters") else {}
        model, self.opts = read_model(study.root.table("train"), names)
        self.candidates: list = []
        self.rejected: list = []
        self.selector = None
        sel = self.opts.get("select")
        if sel:
            model = self._select(model, sel)
        self.model = model
        try:
            self.coaxial_solved = solve_coaxial(model)
        except ValueError:
            raise CaseError("числа зубьев «coaxial» не определяются из условия соосности", file=study.root.file,
                            key="train.wheel", expected="зацепление, замыкающее контур осей") from None
        try:
            self.w_willis = {k: (0.0 if abs(v) < 1e-12 else v) for k, v in willis(model).items()}
            self.w_direct = {k: (0.0 if abs(v) < 1e-12 else v) for k, v in direct(model).items()}
        except ValueError:
            raise CaseError("передаточное отношение не определено: проверьте неподвижные звенья, "
                            "вход и зацепления", file=study.root.file, key="train",
                            expected="механизм с одной степенью свободы") from None
        self.positions, self.coaxiality = place_axes(model)
        self.printed_coaxiality = []
        for text in self.opts["printed_coaxiality"]:
            try:
                self.printed_coaxiality.append((text, judge_printed_coaxiality(model, text)))
            except ValueError as e:
                raise CaseError(f"равенство «{text}»: {e}", file=study.root.file, key="train.printed.coaxiality",
                                expected="z1 - z2 = z4 + z3 (имена колёс из [[train.wheel]])") from None

    def _select(self, model: TrainModel, sel: dict) -> TrainModel:
        """Tooth numbers of the wheels marked "select" (and "coaxial") by ``train_select``."""
        from .train_select import GRID_LIMIT, select
        file = self.study.root.file
        try:
            ok, bad, selector = select(model, self.opts["target"], self.opts["planets"], tol=self.opts["tolerance"],
                                       z_min=sel["z_min"], z_max=sel["z_max"], dz_int=sel["dz_internal"],
                                       limit=sel["limit"], z_from=sel["z_from"], prefer=self.opts["coaxial"])
        except OverflowError as e:
            raise CaseError(f"перебор слишком велик: {e.args[0]} сочетаний чисел зубьев (не более {GRID_LIMIT})",
                            file=file, key="train.select",
                            expected="меньший z_max или допуск tolerance, больший z_from или часть чисел зубьев задана") from None
        except ValueError:
            raise CaseError("подбор невозможен: передаточное отношение или соосность не определяются по схеме",
                            file=file, key="train", expected="механизм с одной степенью свободы, "
                            "все контуры осей замкнуты зацеплениями") from None
        if not ok:
            raise CaseError("подходящих чисел зубьев не найдено", file=file,
                            key="train.select", expected="больший z_max или допуск tolerance")
        self.candidates, self.rejected, self.selector = ok, bad, selector
        return selector.model_with(ok[0].z)

    @property
    def ratio(self) -> float:
        """u_in,out = ω_in/ω_out (Willis)."""
        return 1.0 / self.w_willis[self.model.out]

    @property
    def ratio_direct(self) -> float:
        """u = ω_in/ω_out by the direct solution (equal speeds of the wheels at each pole), the
        check of Willis' value."""
        return 1.0 / self.w_direct[self.model.out]

    @cached_property
    def ratio_fraction(self) -> Fraction:
        """The exact ratio as a fraction of tooth-number products (from the Willis value)."""
        return Fraction(self.ratio).limit_denominator(10 ** 6)

    def tables(self) -> dict[str, pd.DataFrame]:
        """Export tables: ``train_wheels`` (z, m, d = mz of each wheel), ``train_omegas`` (ω of each
        member by Willis and directly) and, for a selection, ``train_candidates``."""
        m = self.model
        wheels = pd.DataFrame([{"wheel": w.name, "z": w.z, "m": w.m, "d": w.m * w.z,
                                "member": w.member, "internal": w.internal}
                               for w in m.wheels.values()])
        omegas = pd.DataFrame([{"member": n, "omega_willis": self.w_willis[n], "omega_direct": self.w_direct[n]}
                               for n in m.members])
        out = {"train_wheels": wheels, "train_omegas": omegas}
        if self.candidates or self.rejected:
            rows = [{**{f"z{k}": v for k, v in c.z.items()}, "u": c.u, "size": c.size,
                     "assembly": "; ".join(" ".join(f"{q.numerator}/{q.denominator}" if q.denominator != 1
                                                    else str(q.numerator) for q in qs) for _, ok, qs in c.assembly if qs),
                     **({"neighbourhood": min(s - r for *_, s, r, _ in c.neighbours)} if c.neighbours else {}),
                     "ok": c.ok, "reasons": "; ".join(c.fails)} for c in self.candidates + self.rejected]
            out["train_candidates"] = pd.DataFrame(rows)
        return out

    @property
    def scalars(self) -> dict:
        """Named results ``train_*``: u by Willis' formula (ω_a − ω_H)/(ω_b − ω_H) = u_ab^(H) and
        directly, their discrepancy, the target ratio and the error from it (domain.md § 1.8)."""
        out = {"u": self.ratio, "u_direct": self.ratio_direct,
               "u_discrepancy_pct": abs(self.ratio - self.ratio_direct) / abs(self.ratio) * 100}
        if self.opts["target"] is not None:
            out["u_target"] = self.opts["target"]
            out["u_error_pct"] = (self.ratio - self.opts["target"]) / self.opts["target"] * 100
        return {"train_" + k: float(v) for k, v in out.items()}
