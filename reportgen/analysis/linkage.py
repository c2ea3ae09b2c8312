"""From a Mechanism to the numba kernel's arrays, and from the kernel's poses to named columns.

Column names are a public contract (see docs/outputs.md): for a point P ``x_P y_P`` with first
analogs ``vqx_P vqy_P`` and second analogs ``aqx_P aqy_P``; for a link k ``phi_k wq_k eq_k``;
for a prismatic pair J ``s_J vqs_J aqs_J``; ``mu_<group>`` the transmission angle of a dyad, and the equivalent transmission angle of a
class III (Newton) group (:func:`equivalent_transmission_sine`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from ..core import kinematics as K
from ..core import tape as T
from ..errors import AssemblyError
from ..mechanism.model import FRAME, Mechanism
from ..mechanism.structure import Structure, solver_bodies

SOLVER_KIND = {"LIN": K.G_LIN, "RRR": K.G_RRR, "RRP": K.G_RRP, "RPR": K.G_RPR, "NEWTON": K.G_NEWTON}
SINGULAR_SIN = 1e-6          # |sin μ| below this: singular (dead-centre) position of a group
LOW_TRANSMISSION = math.radians(40.0)


@dataclass
class SolverModel:
    """The linkage as the numba kernel takes it: solver bodies (the actuator's rod merged into its
    cylinder), joints as arrays (kind, bodies, local points), the groups in the order of solution
    with their kinds and branches, and the points to report."""
    mech: Mechanism
    structure: Structure
    bodies: list[str]                       # solver body names, index 0 = frame
    jt: np.ndarray
    jb: np.ndarray
    jf: np.ndarray
    groups: list                            # structure groups solved by the kernel, in order
    gkind: np.ndarray
    gspec: np.ndarray
    gsigma: np.ndarray
    gjoint: np.ndarray
    gnj: np.ndarray
    gbody: np.ndarray
    gnb: np.ndarray
    pose0: np.ndarray
    size: float
    point_names: list[str] = field(default_factory=list)
    pbody: np.ndarray | None = None
    ploc: np.ndarray | None = None
    body_group: dict[int, int] = field(default_factory=dict)
    _tape: tuple = field(default=(None, None), repr=False)
    _colspec: dict = field(default_factory=dict, repr=False)
    _body_index: dict[str, int] = field(default_factory=dict, repr=False)

    def body(self, link: str) -> int:
        """The index of the solver body that carries ``link``."""
        b = self._body_index.get(link)
        if b is None:
            b = self._body_index[link] = self.bodies.index(solver_bodies(self.mech)[link])
        return b

    def local_point(self, link: str, p: str) -> tuple[float, float, float, float]:
        """Local coordinates p0, p1 (p = p0 + q·p1) of point p of a link in its solver body."""
        return self.local_coords(link, self.mech.link(link).points[p])

    def local_coords(self, link: str, xy) -> tuple[float, float, float, float]:
        """Coordinates given in a link's own frame, in its solver body: the actuator's rod is
        merged into the cylinder, its frame origin sitting at distance q along the axis."""
        x, y = xy
        d = self.mech.driver
        if d.kind == "actuator" and link == d.rod:
            return x, y, 1.0, 0.0
        return x, y, 0.0, 0.0


def assemble(mech: Mechanism, st: Structure) -> SolverModel:
    """The kernel's model of a mechanism: its bodies, joints and Assur groups (in the order of the
    structure) laid out as arrays for core.kinematics."""
    body_of = solver_bodies(mech)
    bodies = [FRAME] + [b for b in dict.fromkeys(body_of[l.name] for l in mech.moving)]
    bidx = {b: i for i, b in enumerate(bodies)}
    model = SolverModel(mech, st, bodies, *([None] * 12), size=mech.size())
    rows_t, rows_b, rows_f = [], [], []

    def lp(link, p):
        return model.local_point(link, p)

    for j in mech.joints:
        a, b = j.links
        if j.kind == "R":
            pa, pb = lp(a, j.point), lp(b, j.point)
            rows_t.append(K.J_REV)
            rows_b.append((bidx[body_of[a]], bidx[body_of[b]]))
            rows_f.append([pa[0], pa[1], pb[0], pb[1], pa[2], pa[3], pb[2], pb[3], 0.0, 0.0])
        else:
            s = lp(b, j.point)
            g = model.local_coords(a, j.line_point)
            rows_t.append(K.J_PRI)
            rows_b.append((bidx[body_of[a]], bidx[body_of[b]]))
            rows_f.append([g[0], g[1], s[0], s[1], j.angle, j.offset, g[2], g[3], s[2], s[3]])
    drive_index = None
    if mech.driver.rotary:
        drive_index = len(rows_t)
        rows_t.append(K.J_DRV)
        rows_b.append((0, bidx[mech.driver.link]))
        rows_f.append([mech.driver.phi0, float(mech.driver.direction)] + [0.0] * 8)
    model.jt = np.array(rows_t, dtype=np.int64)
    model.jb = np.array(rows_b, dtype=np.int64).reshape(-1, 2)
    model.jf = np.array(rows_f, dtype=np.float64).reshape(-1, 10)

    groups = [g for g in st.groups if g.solver != "NONE"]
    ng = len(groups)
    maxb = max(len(g.bodies) for g in groups)
    maxj = max(len(g.joints) + 1 for g in groups)
    gkind = np.zeros(ng, np.int64)
    gspec = -np.ones((ng, 6), np.int64)
    gjoint = -np.ones((ng, maxj), np.int64)
    gbody = -np.ones((ng, maxb), np.int64)
    gnj = np.zeros(ng, np.int64)
    gnb = np.zeros(ng, np.int64)
    for gi, g in enumerate(groups):
        js = list(g.joints) + ([drive_index] if g.klass == 1 and drive_index is not None else [])
        gkind[gi] = SOLVER_KIND[g.solver]
        gjoint[gi, :len(js)] = js
        gnj[gi] = len(js)
        bs = [bidx[b] for b in g.bodies]
        gbody[gi, :len(bs)] = bs
        gnb[gi] = len(bs)
        for b in bs:
            model.body_group[b] = gi
        if g.order == 2 and len(bs) == 2:
            # a dyad (any kind): closed-form position for ВВВ, ВВП, ВПВ, analogs by its 2×2 system
            gspec[gi, :5] = _dyad_spec(g, model, bidx)
            gspec[gi, 5] = K.A_DYAD
        elif len(bs) == 1 and sorted(model.jt[j] for j in js) == [K.J_REV, K.J_DRV]:
            gspec[gi, 5] = K.A_SINGLE
        else:
            gspec[gi, 5] = K.A_DENSE
    model.groups = groups
    model.gkind, model.gspec, model.gjoint, model.gbody = gkind, gspec, gjoint, gbody
    model.gnj, model.gnb = gnj, gnb
    model.gsigma = np.ones(ng)
    model.pose0 = _pose_from_sketch(model)
    _collect_points(model)
    return model


def _dyad_spec(g, model: SolverModel, bidx) -> list[int]:
    a, b = (bidx[x] for x in g.bodies)
    jb = model.jb
    jt = model.jt
    (jint,) = g.internal
    ext_a = [k for k in g.external if a in jb[k]]
    ext_b = [k for k in g.external if b in jb[k]]
    if g.solver == "RRP":
        # a must carry the revolute to the known side, b the prismatic one
        if jt[ext_a[0]] == K.J_PRI:
            a, b, ext_a, ext_b = b, a, ext_b, ext_a
    return [a, b, ext_a[0], jint, ext_b[0]]


def _pose_from_sketch(model: SolverModel) -> np.ndarray:
    """Initial body poses from the sketch (used by Newton groups at the first position).

    A link is placed by two of its points whose global positions are known: fixed points, the
    sketch's points, and the points of links placed before (so a coupler drawn only by its far
    end takes its angle from the crank's pin, not 0).  The driver link takes the driver's angle
    at the sketch position; a link with one known point keeps its angle 0."""
    pose = np.zeros((len(model.bodies), 3))
    mech = model.mech
    known = dict(mech.link(FRAME).points)      # fixed points are known exactly
    known.update(mech.sketch)
    d = mech.driver
    q0 = mech.sketch_q if mech.sketch_q is not None else default_q0(mech)
    todo = list(mech.moving)
    while todo:
        placed = [lk for lk in todo if sum(p in known for p in lk.points) >= 2]
        if not placed:
            placed = [lk for lk in todo if any(p in known for p in lk.points)][:1] or todo[:1]
        for link in placed:
            todo.remove(link)
            bi = model.body(link.name)
            sk = [(p, known[p]) for p in link.points if p in known]
            if not sk:
                continue
            if len(sk) >= 2:
                (p1, g1), (p2, g2) = sk[0], sk[1]
                l1, l2 = link.points[p1], link.points[p2]
                th = math.atan2(g2[1] - g1[1], g2[0] - g1[0]) - math.atan2(l2[1] - l1[1], l2[0] - l1[0])
            else:
                th = d.phi0 + d.direction * q0 if d.rotary and link.name == d.link else pose[bi, 2]
                p1, g1 = sk[0]
                l1 = link.points[p1]
            c, s = math.cos(th), math.sin(th)
            pose[bi] = (g1[0] - (c * l1[0] - s * l1[1]), g1[1] - (s * l1[0] + c * l1[1]), th)
            for p, lp in link.points.items():
                known.setdefault(p, (pose[bi, 0] + c * lp[0] - s * lp[1], pose[bi, 1] + s * lp[0] + c * lp[1]))
    return pose


def _collect_points(model: SolverModel) -> None:
    names, pb, pl = [], [], []
    seen = set()
    mech = model.mech
    for link in mech.links:
        for p in link.points:
            if p in seen:
                continue
            seen.add(p)
            names.append(p)
            pb.append(model.body(link.name))
            pl.append(model.local_point(link.name, p))
    model.point_names = names
    model.pbody = np.array(pb, dtype=np.int64)
    model.ploc = np.array(pl, dtype=np.float64).reshape(-1, 4)


def tape(model: SolverModel):
    """The model's groups compiled for :func:`core.tape.run_tape` (cached; rebuilt when gkind or
    gspec change), or None when some group needs the general kernel."""
    key = (model.gkind.tobytes(), model.gspec.tobytes())
    if model._tape[0] != key:
        model._tape = (key, T.build_tape(model.jt, model.jb, model.jf, model.gkind, model.gspec,
                                         model.gjoint, model.gnj, model.gbody))
    return model._tape[1]


def run_kernel(model: SolverModel, q: np.ndarray, ngroups: int | None = None, sigma=None, pose0=None):
    """Positions and both analogs over the grid q (optionally only the first ``ngroups`` groups;
    Newton groups start from ``pose0``, by default the sketch): the tape kernel when every group
    is in closed form and no position is near a singular one, otherwise the general kernel
    :func:`core.kinematics.solve_cycle` on the whole grid.  Returns (pose, d1, d2, quality, fail)."""
    ng = len(model.groups) if ngroups is None else ngroups
    sig = model.gsigma if sigma is None else sigma
    p0 = model.pose0 if pose0 is None else np.ascontiguousarray(pose0, dtype=np.float64)
    q = np.ascontiguousarray(q, dtype=np.float64)
    tp = tape(model)
    if tp is not None:
        out = T.run_tape(q, tp[0], tp[1], np.ascontiguousarray(sig, dtype=np.float64), ng, p0)
        if out[4][0] != T.NEED_GENERAL:
            return out
    return solve_general(model, q, ng, sig, p0)


def solve_general(model: SolverModel, q: np.ndarray, ng: int, sig, p0):
    """The general kernel (dense and Newton groups, singular positions judged)."""
    return K.solve_cycle(q, model.jt, model.jb, model.jf,
                         model.gkind[:ng], model.gspec[:ng], sig[:ng], model.gjoint[:ng],
                         model.gnj[:ng], model.gbody[:ng], model.gnb[:ng], p0, model.size)


def compile_kernels(model: SolverModel, q: np.ndarray) -> None:
    """Compile (or load from numba's cache) both kernels on two positions: the tape and the
    general kernel, which only singular positions, Newton groups, ПВП/ВПП and actuators need."""
    q = np.ascontiguousarray(q[:2], dtype=np.float64)
    run_kernel(model, q)
    solve_general(model, q, len(model.groups), model.gsigma, model.pose0)


def has_newton(model: SolverModel) -> bool:
    """Whether some group is solved by Newton (class III and higher): its branch is then defined
    by continuation along the cycle, not by a closed-form sign."""
    return bool((model.gkind == K.G_NEWTON).any())


def describe_position(model: SolverModel, q: float, index: int | None) -> str:
    """The position q in the note's words: «q = 40°» for a turning input, «q = 0,45 м» for an
    actuator, with its number when it is a report position."""
    if model.mech.driver.rotary:
        s = f"q = {math.degrees(q):.4g}°".replace(".", ",")
    else:
        s = f"q = {q:.5g} м".replace(".", ",")
    return s + (f" (положение № {index})" if index is not None else "")


def check_failure(model: SolverModel, q: np.ndarray, fail: np.ndarray, labels=None) -> None:
    """Raise AssemblyError for the first failure the kernel reports: a group that cannot be
    assembled (by how much), a closure with no exact solution, or a singular group (the
    transmission angle μ or the matrix's conditioning)."""
    kind = int(fail[0])
    if kind == K.F_OK:
        return
    i, g, amount = int(fail[1]), int(fail[2]), float(fail[3])
    grp = model.groups[g]
    pos = describe_position(model, float(q[i]), labels[i] if labels is not None else None)
    if kind == K.F_ASSEMBLY:
        detail = ("звенья группы не дотягиваются друг до друга" if amount > 0 else "")
        raise AssemblyError(grp.title, pos, amount, detail)
    if kind == K.F_NEWTON:
        raise AssemblyError(grp.title, pos, amount,
                            "замыкание контура невозможно: это наибольший зазор в шарнирах при "
                            "наилучшем по методу наименьших квадратов положении группы")
    if grp.kind in ("RRR", "RRP"):
        mu = math.degrees(math.asin(min(1.0, abs(amount))))
        measure = f"угол передачи μ = {mu:.2f}°".replace(".", ",")
    else:
        measure = f"мера обусловленности матрицы группы {amount:.1e}".replace(".", ",")
    raise AssemblyError(grp.title, pos, 0.0,
                        f"определитель системы группы равен нулю, аналоги скоростей не определены; {measure}")


def choose_branches(model: SolverModel) -> None:
    """Fix the assembly branch σ = ±1 of each closed-form dyad from the sketch (nearest
    solution at the sketch position); groups without sketched points keep σ = +1."""
    mech = model.mech
    if not mech.sketch:
        return
    q0 = np.array([mech.sketch_q if mech.sketch_q is not None else default_q0(mech)])
    for g, grp in enumerate(model.groups):
        if model.gkind[g] not in (K.G_RRR, K.G_RRP, K.G_RPR):
            continue
        pts = [(p, xy) for l in grp.links for p, xy in
               ((p, mech.sketch.get(p)) for p in mech.link(l).points) if xy is not None]
        if not pts:
            continue
        best, best_sig = None, 1.0
        for sig in (1.0, -1.0):
            trial = model.gsigma.copy()
            trial[g] = sig
            pose, d1, d2, qual, fail = run_kernel(model, q0, g + 1, trial)
            if fail[0] != K.F_OK:
                continue
            err = 0.0
            for p, xy in pts:
                k = model.point_names.index(p)
                b = model.pbody[k]
                x0, y0, x1, y1 = model.ploc[k]
                th = pose[0, b, 2]
                px, py = x0 + q0[0] * x1, y0 + q0[0] * y1
                gx = pose[0, b, 0] + math.cos(th) * px - math.sin(th) * py
                gy = pose[0, b, 1] + math.sin(th) * px + math.cos(th) * py
                err += (gx - xy[0]) ** 2 + (gy - xy[1]) ** 2
            if best is None or err < best:
                best, best_sig = err, sig
        model.gsigma[g] = best_sig


def default_q0(mech: Mechanism) -> float:
    """The generalised coordinate where the cycle starts: 0 for a crank, the lower end of the range
    for a rocker or an actuator."""
    return 0.0 if mech.driver.periodic else mech.driver.q_range[0]


@dataclass
class KinematicsResult:
    """The kernel's result at positions q: the poses of the bodies with their first and second
    analogs, the quality of each group's system, and the points' positions and analogs (N,
    npoints, 6)."""
    q: np.ndarray
    pose: np.ndarray
    d1: np.ndarray
    d2: np.ndarray
    quality: np.ndarray
    points: np.ndarray          # (N, npoints, 6)


def solve(model: SolverModel, q, labels=None, ngroups: int | None = None) -> KinematicsResult:
    """Positions, first and second analogs of every body and point at the positions ``q`` (closed
    form for class II groups, Newton for class III; numerics.md), AssemblyError at the first
    failure."""
    q = np.atleast_1d(np.asarray(q, dtype=np.float64))
    pose, d1, d2, qual, fail = run_kernel(model, q, ngroups)
    check_failure(model, q, fail, labels)
    pts = K.points_cycle(pose, d1, d2, q, model.pbody, model.ploc)
    return KinematicsResult(q, pose, d1, d2, qual, pts)


def solve_continued(model: SolverModel, q, base: KinematicsResult, period: float | None,
                    labels=None) -> KinematicsResult:
    """Positions at arbitrary q on the branch of an already solved grid ``base`` (the cycle):
    each q is reached from the nearest grid position by the kernel's continuation (Newton from
    the exact grid pose with its predictor, the step refined if a jump is detected), never by
    a Newton restarted from the sketch, which may converge to another assembly.  ``period`` is
    the period of the motion in q (2π for a crank) or None."""
    q = np.atleast_1d(np.asarray(q, dtype=np.float64))
    bq = base.q
    rows = []
    for i, qt in enumerate(q):
        shift = 0.0
        if period:
            shift = math.floor((qt - bq[0]) / period) * period
        k = int(np.clip(np.searchsorted(bq, qt - shift), 1, len(bq) - 1))
        k = k - 1 if abs(bq[k - 1] - (qt - shift)) <= abs(bq[k] - (qt - shift)) else k
        pair = np.array([bq[k], qt - shift])
        pose, d1, d2, qual, fail = run_kernel(model, pair, pose0=base.pose[k])
        check_failure(model, q[i:i + 1], np.array([fail[0], 0.0, fail[2], fail[3]]),
                      None if labels is None else [labels[i]])
        rows.append((pose[1], d1[1], d2[1], qual[1]))
    return _from_rows(model, q, rows)


def _from_rows(model: SolverModel, q: np.ndarray, rows: list) -> KinematicsResult:
    """The result of positions solved one by one: rows of (pose, first analogs, second analogs,
    quality) at ``q``, with the points' coordinates and analogs."""
    pose, d1, d2, qual = (np.array([r[j] for r in rows]) for j in range(4))
    pts = K.points_cycle(pose, d1, d2, q, model.pbody, model.ploc)
    return KinematicsResult(q, pose, d1, d2, qual, pts)


def solve_from_sketch(model: SolverModel, q, q0: float, step: float, period: float | None,
                      labels=None) -> KinematicsResult:
    """Positions at arbitrary q of a mechanism with Newton groups without solving its cycle
    (``export --at``): the first assembly at the sketch's position q0 (Newton and
    Levenberg–Marquardt from the sketch, the assembly nearer to the sketch) is continued along
    a path of steps ≤ ``step`` to each q (the kernel's predictor with jump detection), so the
    branch is the sketch's and only the path from q0 to q has to assemble, not the whole cycle.
    For a crank (``period``) each q is first reached the shorter way round, then the other way;
    a q that no path reaches is assembled directly from the sketch (the first-assembly path at
    q itself), and where that fails too, the assembly error names that q."""
    q = np.atleast_1d(np.asarray(q, dtype=np.float64))
    n = len(q)
    rows: list = [None] * n
    if period:
        near = q - np.round((q - q0) / period) * period        # the representative nearest to q0
        tries = [near, near - np.sign(near - q0 + 1e-300) * period]
    else:
        tries = [q]
    for target in tries:
        todo = [i for i in range(n) if rows[i] is None]
        for side in (1.0, -1.0):
            idx = [i for i in todo if (target[i] - q0) * side >= 0]
            if not idx:
                continue
            far = max(abs(target[i] - q0) for i in idx)
            m = max(1, math.ceil(far / step))
            path = np.unique(np.concatenate([q0 + side * far * np.arange(m + 1) / m, target[idx]]))
            path = path[::-1] if side < 0 else path
            pose, d1, d2, qual, fail = run_kernel(model, path)
            reached = len(path) if fail[0] == K.F_OK else int(fail[1])
            for i in idx:
                k = int(np.nonzero(path == target[i])[0][0])
                if k < reached:
                    rows[i] = (pose[k], d1[k], d2[k], qual[k])
    for i in range(n):
        if rows[i] is None:
            qt = np.array([tries[0][i]])
            pose, d1, d2, qual, fail = run_kernel(model, qt)
            check_failure(model, q[i:i + 1], fail, None if labels is None else [labels[i]])
            rows[i] = (pose[0], d1[0], d2[0], qual[0])
    return _from_rows(model, q, rows)


def _unwrap(th: np.ndarray, grid: bool) -> np.ndarray:
    th = np.arctan2(np.sin(th), np.cos(th))
    return unwrap(th) if grid and th.size > 1 else th


def unwrap(p: np.ndarray) -> np.ndarray:
    """``np.unwrap(p)`` of angles along a grid, the same numbers: where no step reaches π the
    correction np.unwrap adds to p[1:] is a cumulative sum of zeros, so the result is p[0],
    p[1:] + 0.0 — made here without its intermediate arrays (a rocker's angle)."""
    if p.size > 1 and (np.abs(np.diff(p)) < np.pi).all():
        out = p.copy()
        out[1:] += 0.0
        return out
    return np.unwrap(p)


def columns(model: SolverModel, res: KinematicsResult, grid: bool = True) -> dict[str, np.ndarray]:
    """Named columns of the kinematic analogs (see module docstring)."""
    names, make = column_maker(model, res, grid)
    return {k: make(k) for k in names}


# kinds of columns (:func:`_column_spec`)
_C_Q, _C_QDEG, _C_POINT, _C_PHI_DRIVER, _C_PHI, _C_W, _C_E, _C_SLIDER, _C_ACT, _C_MU, _C_MU_NEWTON = range(11)


def _column_spec(model: SolverModel, ngroups: int) -> tuple[list[str], dict[str, tuple]]:
    """The names of :func:`columns`, in their order, and how each is made (kind, two
    arguments), for results of the first ``ngroups`` groups: made once per model."""
    got = model._colspec.get(ngroups)
    if got is not None:
        return got
    mech = model.mech
    spec: dict[str, tuple] = {"q": (_C_Q, None, None)}
    if mech.driver.rotary:
        spec["q_deg"] = (_C_QDEG, None, None)
    for k, p in enumerate(model.point_names):
        for c, pre in enumerate(("x_", "y_", "vqx_", "vqy_", "aqx_", "aqy_")):
            spec[pre + p] = (_C_POINT, k, c)
    for l in mech.moving:
        b = model.body(l.name)
        spec["phi_" + l.name] = ((_C_PHI_DRIVER, None, None) if mech.driver.rotary and l.name == mech.driver.link
                                 else (_C_PHI, b, None))
        spec["wq_" + l.name] = (_C_W, b, None)
        spec["eq_" + l.name] = (_C_E, b, None)
    for j in mech.prismatic:
        for i, pre in enumerate(("s_", "vqs_", "aqs_")):
            spec[pre + j.name] = (_C_SLIDER, j, i)
    if mech.driver.kind == "actuator":
        d = mech.driver
        for i, pre in enumerate(("s_", "vqs_", "aqs_")):
            spec[f"{pre}{d.rod}{d.link}"] = (_C_ACT, i, None)
    for g, grp in enumerate(model.groups[:ngroups]):
        if grp.kind in ("RRR", "RRP"):     # a ВПВ group has no transmission angle of its own
            spec["mu_" + grp.name] = (_C_MU, g, None)
        elif model.gkind[g] == K.G_NEWTON:
            spec["mu_" + grp.name] = (_C_MU_NEWTON, g, None)
    got = model._colspec[ngroups] = (list(spec), spec)
    return got


def column_maker(model: SolverModel, res: KinematicsResult, grid: bool = True) -> tuple[list[str], Callable[[str], np.ndarray]]:
    """The names of :func:`columns`, in their order, and a function that makes the column of a
    name (the same numbers): a caller that needs a few columns of an evaluation makes only those."""
    names, spec = _column_spec(model, res.quality.shape[1])
    d = model.mech.driver
    q = res.q
    shared: dict[Any, Any] = {}

    def make(name: str) -> np.ndarray:
        kind, a, b = spec[name]
        if kind == _C_POINT:
            P = shared.get("P")
            if P is None:          # the points as rows (points_cycle's own layout: no copy)
                P = shared["P"] = np.ascontiguousarray(res.points.transpose(1, 2, 0))
            return P[a, b]
        if kind == _C_Q:
            return q
        if kind == _C_QDEG:
            return np.degrees(q)
        if kind == _C_PHI_DRIVER:
            return d.phi0 + d.direction * q
        if kind == _C_PHI:
            return _unwrap(res.pose[:, a, 2], grid)
        if kind == _C_W:
            return res.d1[:, a, 2].copy()
        if kind == _C_E:
            return res.d2[:, a, 2].copy()
        if kind == _C_SLIDER:
            v = shared.get(a.name)
            if v is None:
                v = shared[a.name] = slider_displacement(model, res, a)
            return v[b]
        if kind == _C_ACT:
            return q.copy() if a == 0 else (np.ones_like(q) if a == 1 else np.zeros_like(q))
        if kind == _C_MU:
            return np.arcsin(np.minimum(1.0, np.abs(res.quality[:, a])))
        return np.arcsin(equivalent_transmission_sine(model, res, a))

    return names, make


def equivalent_transmission_sine(model: SolverModel, res: KinematicsResult, g: int) -> np.ndarray:
    """Transmission measure of a group solved in body coordinates (class III), per position.

    Φ_x = [T | R]: T the translation columns of the group's bodies, R their angle columns.
    The angle columns are projected on the orthogonal complement of span T (eliminating the
    translations; independent of where each body's frame is), R⊥ = Q⊥ᵀR, and

        h = |det R⊥| / ∏ ‖R⊥ e_k‖        (Hadamard ratio, 0 ≤ h ≤ 1),

    invariant to the units and the frame.  For a ВВВ dyad h = |sin μ| exactly (checked to 1e-15
    on ws000, tests/test_class3_flags.py); h → 0 at a singular position of the group (det Φ_x = 0,
    Артоболевский, «Теория механизмов и машин», особые положения групп III класса), so
    μ = arcsin h is reported as the group's equivalent transmission angle and judged by the same
    thresholds as a dyad's."""
    return K.group_transmission(res.q, res.pose, model.jt, model.jb, model.jf, model.gjoint[g], model.gnj[g],
                                model.gbody[g], model.gnb[g], model.size)


def slider_displacement(model: SolverModel, res: KinematicsResult, j):
    """s = u·(P − G) along the guide direction u (guide point G, slider point P), with
    s' = u'·(P−G) + u·(P'−G'), s'' = u''·(P−G) + 2u'·(P'−G') + u·(P''−G''),
    u' = ⊥u·θ', u'' = ⊥u·θ'' − u·θ'² (θ the guide's angle)."""
    guide, slider = j.links
    gb = model.body(guide)
    g = model.local_coords(guide, j.line_point)
    sl = model.local_point(slider, j.point)
    pts = K.points_cycle(res.pose, res.d1, res.d2, res.q,
                         np.array([gb, model.body(slider)], np.int64), np.array([g, sl], dtype=np.float64))
    G, P = pts[:, 0, :], pts[:, 1, :]
    th = res.pose[:, gb, 2] + j.angle
    w = res.d1[:, gb, 2]
    e = res.d2[:, gb, 2]
    ux, uy = np.cos(th), np.sin(th)
    px, py = -uy, ux
    dx, dy = P[:, 0] - G[:, 0], P[:, 1] - G[:, 1]
    dvx, dvy = P[:, 2] - G[:, 2], P[:, 3] - G[:, 3]
    dax, day = P[:, 4] - G[:, 4], P[:, 5] - G[:, 5]
    s = ux * dx + uy * dy
    vs = w * (px * dx + py * dy) + ux * dvx + uy * dvy
    as_ = ((px * e - ux * w * w) * dx + (py * e - uy * w * w) * dy
           + 2 * w * (px * dvx + py * dvy) + ux * dax + uy * day)
    return s, vs, as_
