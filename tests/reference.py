"""Independent high-precision reference kinematics for the tests of the numba engine.

The reference is written directly from the :class:`~reportgen.mechanism.model.Mechanism`
description (links with local points, joints, driver) and shares no code with
``reportgen.core.kinematics`` / ``reportgen.analysis.linkage`` apart from reading the kernel's
float solution as a starting guess.

Formulation (deliberately different from the kernel's group-by-group solution):

* unknowns: the pose (x_k, y_k, θ_k) of EVERY moving link, the whole mechanism at once (no Assur
  decomposition); an actuator's cylinder and rod are two separate links (the kernel merges them);
* revolute joint at point P between links a, b:  r_a + A(θ_a) p_a − r_b − A(θ_b) p_b = 0;
* prismatic joint (guide g, slider s, slider point p_s, guide line through l with direction α
  in the guide's frame, offset e):  θ_s − θ_g − α − 2πk = 0  and
  n·(r_s + A_s p_s − r_g − A_g l) − e = 0 with n = A(θ_g)(−sin α, cos α);
* crank drive:  θ_c − (φ0 + direction·q) − 2πk = 0;
* actuator (cylinder c, rod r, base pivot b on c, rod-end pivot e on r): a prismatic pair along the
  cylinder's local x axis plus the driving condition "relative displacement = q":
  θ_r − θ_c − 2πk = 0,  (−sin θ_c, cos θ_c)·d = 0,  (cos θ_c, sin θ_c)·d − q = 0,
  d = r_r + A_r p_e − r_c − A_c p_b.

The float data of the mechanism are converted to mpf exactly, so the reference is the exact
kinematics of exactly the same mechanism.  The system Φ(X, q) = 0 is solved by Newton's method in
mpmath at ``DPS`` = 50 digits with the Jacobian Φ_X (and Φ_q) obtained by the complex-step
derivative in mpmath (step 1e-30, truncation error ~1e-60, no cancellation), so no hand-written
derivative of the constraints is involved.

Outputs (points, link angles, slider displacements) are evaluated at q + k·h, k = −2…2 with
h = 1e-12 and differentiated with the 5-point central stencils

    f'  = (f₋₂ − 8 f₋₁ + 8 f₁ − f₂) / (12 h)                 truncation h⁴ f⁽⁵⁾/30  ~ 1e-48
    f'' = (−f₋₂ + 16 f₋₁ − 30 f₀ + 16 f₁ − f₂) / (12 h²)      truncation h⁴ f⁽⁶⁾/90  ~ 1e-50

with rounding errors ~ 10⁻⁵⁰/h ~ 1e-38 and ~ 10⁻⁵⁰/h² ~ 1e-26 respectively.  As a self-check of the
reference itself, the first analogs of all poses are also obtained from the linear system
Φ_X X' = −Φ_q and must agree with the stencil to 1e-25 (otherwise ``ReferenceError`` is raised).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from mpmath import mp, mpc, mpf

DPS = 50
H_STENCIL = "1e-12"
H_COMPLEX = "1e-30"
SELF_CHECK = "1e-25"


class ReferenceError(AssertionError):
    """The reference solver itself failed (no convergence, singular Jacobian, self-check)."""


# ----------------------------------------------------------------------------- small mp linalg

def _lu(a: list[list]) -> tuple[list[list], list[int]]:
    """LU factorisation with partial pivoting of a square list-of-lists matrix (copied)."""
    n = len(a)
    a = [row[:] for row in a]
    perm = list(range(n))
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c]))
        if a[p][c] == 0:
            raise ReferenceError("reference Jacobian is singular")
        if p != c:
            a[c], a[p] = a[p], a[c]
            perm[c], perm[p] = perm[p], perm[c]
        piv = a[c][c]
        for r in range(c + 1, n):
            f = a[r][c] / piv
            if f:
                a[r][c] = f
                rr, rc = a[r], a[c]
                for k in range(c + 1, n):
                    rr[k] -= f * rc[k]
            else:
                a[r][c] = f
    return a, perm


def _lu_solve(lu: tuple[list[list], list[int]], b: list) -> list:
    a, perm = lu
    n = len(a)
    y = [b[perm[i]] for i in range(n)]
    for i in range(n):
        s = y[i]
        ai = a[i]
        for k in range(i):
            s -= ai[k] * y[k]
        y[i] = s
    for i in range(n - 1, -1, -1):
        s = y[i]
        ai = a[i]
        for k in range(i + 1, n):
            s -= ai[k] * y[k]
        y[i] = s / ai[i]
    return y


# ----------------------------------------------------------------------------- the model

@dataclass
class _Eq:
    kind: str            # "R", "P", "crank", "actuator"
    a: str               # first link (R: a; P: guide; crank: crank; actuator: cylinder)
    b: str               # second link (R: b; P: slider; actuator: rod)
    pa: tuple = ()       # local point on a (P: line point in the guide frame)
    pb: tuple = ()       # local point on b
    alpha: object = 0    # P: guide direction in the guide's frame (mpf)
    e: object = 0        # P: offset (mpf)
    phi0: object = 0     # crank
    direction: int = 1   # crank
    turns: int = 0       # 2πk of the angle equation (fixed from the starting guess)
    name: str = ""


class ReferenceMechanism:
    """The constraint system Φ(X, q) of a Mechanism in mpmath (see the module docstring)."""

    def __init__(self, mech, line_angles: dict | None = None):
        self.mech = mech
        self.line_angles = dict(line_angles or {})   # [outputs.angles]: name → (P, R)
        self.links = [l.name for l in mech.moving]
        self.index = {n: i for i, n in enumerate(self.links)}
        self.n = 3 * len(self.links)
        with mp.workdps(DPS):
            self.local = {l.name: {p: (mpf(x), mpf(y)) for p, (x, y) in l.points.items()}
                          for l in mech.links}
            self.owner = mech.point_owner()
            eqs: list[_Eq] = []
            for j in mech.joints:
                a, b = j.links
                if j.kind == "R":
                    eqs.append(_Eq("R", a, b, self.local[a][j.point], self.local[b][j.point], name=j.name))
                else:
                    eqs.append(_Eq("P", a, b, (mpf(j.line_point[0]), mpf(j.line_point[1])),
                                   self.local[b][j.point], alpha=mpf(j.angle), e=mpf(j.offset), name=j.name))
            d = mech.driver
            if d.kind == "crank":
                eqs.append(_Eq("crank", d.link, "0", phi0=mpf(d.phi0), direction=int(d.direction)))
            else:
                eqs.append(_Eq("actuator", d.link, d.rod, self.local[d.link][d.center],
                               self.local[d.rod][d.end], name=f"{d.rod}{d.link}"))
            self.eqs = eqs
            self.m = sum(1 if e.kind == "crank" else 3 if e.kind == "actuator" else 2 for e in eqs)
        if self.m != self.n:
            raise ReferenceError(f"{self.m} equations for {self.n} unknowns: not a W = 1 mechanism")

    # ---------------------------------------------------------------- geometry helpers
    def _poses(self, X):
        """Link name → (x, y, cos θ, sin θ, θ) for the frame and every moving link."""
        out = {"0": (0, 0, 1, 0, 0)}
        for i, n in enumerate(self.links):
            th = X[3 * i + 2]
            out[n] = (X[3 * i], X[3 * i + 1], mp.cos(th), mp.sin(th), th)
        return out

    @staticmethod
    def _glob(pose, p):
        x, y, c, s, _ = pose
        return x + c * p[0] - s * p[1], y + s * p[0] + c * p[1]

    # ---------------------------------------------------------------- constraints
    def residual(self, X, q) -> list:
        P = self._poses(X)
        twopi = 2 * mp.pi
        res = []
        for e in self.eqs:
            if e.kind == "R":
                ax, ay = self._glob(P[e.a], e.pa)
                bx, by = self._glob(P[e.b], e.pb)
                res += [ax - bx, ay - by]
            elif e.kind == "P":
                g, s = P[e.a], P[e.b]
                res.append(s[4] - g[4] - e.alpha - twopi * e.turns)
                sa, ca = mp.sin(e.alpha), mp.cos(e.alpha)
                nx0, ny0 = -sa, ca
                nx, ny = g[2] * nx0 - g[3] * ny0, g[3] * nx0 + g[2] * ny0
                sx, sy = self._glob(s, e.pb)
                lx, ly = self._glob(g, e.pa)
                res.append(nx * (sx - lx) + ny * (sy - ly) - e.e)
            elif e.kind == "crank":
                res.append(P[e.a][4] - e.phi0 - e.direction * q - twopi * e.turns)
            else:
                c, r = P[e.a], P[e.b]
                bx, by = self._glob(c, e.pa)
                ex, ey = self._glob(r, e.pb)
                dx, dy = ex - bx, ey - by
                res.append(r[4] - c[4] - twopi * e.turns)
                res.append(-c[3] * dx + c[2] * dy)
                res.append(c[2] * dx + c[3] * dy - q)
        return res

    def set_turns(self, X, q) -> None:
        """Fix the 2πk of every angle equation from a (float) starting guess."""
        P = self._poses(X)
        for e in self.eqs:
            if e.kind == "P":
                d = P[e.b][4] - P[e.a][4] - e.alpha
            elif e.kind == "crank":
                d = P[e.a][4] - e.phi0 - e.direction * q
            elif e.kind == "actuator":
                d = P[e.b][4] - P[e.a][4]
            else:
                continue
            e.turns = int(round(float(d) / (2 * math.pi)))

    def jacobian(self, X, q):
        """Φ_X (list of rows) and Φ_q by the complex-step derivative."""
        h = mpf(H_COMPLEX)
        cols = []
        Xc = [mpc(x) for x in X]
        for j in range(self.n):
            old = Xc[j]
            Xc[j] = old + mpc(0, h)
            cols.append([mp.im(f) / h for f in self.residual(Xc, q)])
            Xc[j] = old
        fq = [mp.im(f) / h for f in self.residual(X, mpc(q, h))]
        J = [[cols[c][r] for c in range(self.n)] for r in range(self.n)]
        return J, fq

    def newton(self, X, q, lu=None, maxit=60):
        """Solve Φ(X, q) = 0 to full precision by the chord method: the Jacobian is factorised once
        (at the starting point, or ``lu`` given: the Jacobian at a nearby solution) and refreshed
        only if the convergence is slow.  From a float guess (error ~1e-16) or a stencil point
        (error ~1e-24, Jacobian from 1e-12 away) the contraction per step is ~1e-16 or ~1e-12.
        Stops when the step is below 1e-46·size; the remaining error is then far smaller."""
        X = list(X)
        tol = mpf(10) ** (-(DPS - 4)) * max(1, self.mech.size())
        if lu is None:
            lu = _lu(self.jacobian(X, q)[0])
        prev = None
        for _ in range(maxit):
            dx = _lu_solve(lu, self.residual(X, q))
            X = [x - d for x, d in zip(X, dx)]
            size = max(abs(d) for d in dx)
            if size <= tol:
                break
            if prev is not None and size > mpf("1e-3") * prev:
                lu = _lu(self.jacobian(X, q)[0])      # slow: refresh (plain Newton step)
            prev = size
        else:
            raise ReferenceError(f"reference Newton did not converge at q = {float(q)!r}")
        worst = max(abs(f) for f in self.residual(X, q))
        if worst > tol:
            raise ReferenceError(f"reference residual {float(worst)!r} at q = {float(q)!r}")
        return X

    # ---------------------------------------------------------------- outputs
    def outputs(self, X, q) -> dict:
        """Column name → value of positions: x_P, y_P, phi_k, s_J at the solution X."""
        P = self._poses(X)
        out = {}
        for p, link in self.owner.items():
            out["x_" + p], out["y_" + p] = self._glob(P[link], self.local[link][p])
        for n in self.links:
            out["phi_" + n] = P[n][4]
        for e in self.eqs:
            if e.kind == "P":
                g, s = P[e.a], P[e.b]
                ca, sa = mp.cos(e.alpha), mp.sin(e.alpha)
                ux, uy = g[2] * ca - g[3] * sa, g[3] * ca + g[2] * sa
                sx, sy = self._glob(s, e.pb)
                lx, ly = self._glob(g, e.pa)
                out["s_" + e.name] = ux * (sx - lx) + uy * (sy - ly)
            elif e.kind == "actuator":
                out["s_" + e.name] = mpf(q)
        for name, (p, r) in self.line_angles.items():
            base = name[4:] if name.startswith("phi_") else name
            out["phi_" + base] = mp.atan2(out["y_" + r] - out["y_" + p], out["x_" + r] - out["x_" + p])
        return out

    def evaluate(self, q, guess) -> dict:
        """Positions and first/second analogs of every output at q (mpf), from a float guess of X."""
        with mp.workdps(DPS):
            q = mpf(q)
            X0 = [mpf(float(v)) for v in guess]
            self.set_turns(X0, q)
            X0 = self.newton(X0, q)
            J, fq = self.jacobian(X0, q)
            lu = _lu(J)
            Xq = _lu_solve(lu, [-f for f in fq])           # exact first analogs of the poses
            h = mpf(H_STENCIL)
            sols = {0: X0}
            for k in (-2, -1, 1, 2):
                start = [x + k * h * v for x, v in zip(X0, Xq)]
                sols[k] = self.newton(start, q + k * h, lu=lu)
            vals = {k: self.outputs(X, q + k * h) for k, X in sols.items()}
            out = {}
            twopi = 2 * mp.pi
            for name in vals[0]:
                f = {k: vals[k][name] for k in vals}
                if name.startswith("phi_"):   # atan2 of a line may jump by 2π inside the stencil
                    f = {k: f[0] + (v - f[0]) - twopi * mp.nint((v - f[0]) / twopi) for k, v in f.items()}
                d1 = (f[-2] - 8 * f[-1] + 8 * f[1] - f[2]) / (12 * h)
                d2 = (-f[-2] + 16 * f[-1] - 30 * f[0] + 16 * f[1] - f[2]) / (12 * h * h)
                out[name] = (f[0], d1, d2)
            # self-check: stencil derivative of the poses against the linear solve
            for i in range(self.n):
                d1 = (sols[-2][i] - 8 * sols[-1][i] + 8 * sols[1][i] - sols[2][i]) / (12 * h)
                if abs(d1 - Xq[i]) > mpf(SELF_CHECK) * max(1, abs(Xq[i])):
                    raise ReferenceError(f"reference self-check failed at q = {float(q)!r}: "
                                         f"{float(abs(d1 - Xq[i]))!r}")
            return out


# ----------------------------------------------------------------------------- public helpers

PREFIX = {"x_": ("vqx_", "aqx_"), "y_": ("vqy_", "aqy_"), "phi_": ("wq_", "eq_"), "s_": ("vqs_", "aqs_")}


def _guess_from_row(ref: ReferenceMechanism, row) -> list[float]:
    """The kernel's float solution as poses of every link: θ_k = phi_k and the origin from the
    column of the link's first point (r_k = x_P − A(θ_k) p)."""
    X = []
    for n in ref.links:
        th = float(row["phi_" + n])
        p, (lx, ly) = next(iter(ref.mech.link(n).points.items()))
        c, s = math.cos(th), math.sin(th)
        X += [float(row["x_" + p]) - (c * lx - s * ly), float(row["y_" + p]) - (s * lx + c * ly), th]
    return X


def reference_columns(study, q_values, frame=None) -> dict[str, list]:
    """High-precision reference of the kinematic columns at q_values (SI: rad or m).

    Returns column → list of mpf for ``q``, every ``x_P y_P vqx_P vqy_P aqx_P aqy_P``,
    ``phi_k wq_k eq_k``, ``s_J vqs_J aqs_J`` and the line angles of ``[outputs.angles]``.  The starting guesses come from the kernel's float
    solution ``study.at(q_values)`` (or ``frame`` if given)."""
    q_values = [float(q) for q in np.atleast_1d(np.asarray(q_values, dtype=float))]
    angles = {k: tuple(v) for k, v in study.root.table("outputs").table("angles").data.items()}
    ref = ReferenceMechanism(study.mechanism, angles)
    df = study.at(q_values) if frame is None else frame
    cols: dict[str, list] = {"q": [mpf(q) for q in q_values]}
    for i, q in enumerate(q_values):
        vals = ref.evaluate(q, _guess_from_row(ref, df.iloc[i]))
        for name, (f0, f1, f2) in vals.items():
            for pre, (p1, p2) in PREFIX.items():
                if name.startswith(pre):
                    base = name[len(pre):]
                    cols.setdefault(name, []).append(f0)
                    cols.setdefault(p1 + base, []).append(f1)
                    cols.setdefault(p2 + base, []).append(f2)
                    break
    return cols


def column_kind(col: str) -> str:
    """'position' (x, y, phi, s), 'first' (vq*, wq) or 'second' (aq*, eq)."""
    pre = col.split("_", 1)[0]
    if pre in ("x", "y", "phi", "s"):
        return "position"
    if pre in ("vqx", "vqy", "wq", "vqs"):
        return "first"
    if pre in ("aqx", "aqy", "eq", "aqs"):
        return "second"
    return "other"


def scaled_errors(df, ref: dict[str, list]) -> dict[str, tuple[float, str, int]]:
    """Max scaled error |x − x_ref| / max(1, |x_ref|) per kind (position, first, second):
    kind → (error, column, row).  Angles (phi_*) are compared modulo 2π."""
    worst = {"position": (0.0, "", -1), "first": (0.0, "", -1), "second": (0.0, "", -1)}
    with mp.workdps(DPS):
        twopi = 2 * mp.pi
        for col, vals in ref.items():
            kind = column_kind(col)
            if kind == "other":
                continue
            if col not in df.columns:
                raise AssertionError(f"column {col} of the reference is missing in the engine's frame")
            got = df[col].to_numpy()
            for i, r in enumerate(vals):
                d = mpf(float(got[i])) - r
                if col.startswith("phi_"):
                    d = d - twopi * mp.nint(d / twopi)
                    r = r - twopi * mp.nint(r / twopi)
                err = abs(d) / max(1, abs(r))
                err = float(err)
                if math.isnan(err):
                    err = math.inf
                if err > worst[kind][0]:
                    worst[kind] = (err, col, i)
    return worst


# ----------------------------------------------------------------------------- loop closure

def closure_residuals(mech, df) -> tuple[float, str]:
    """Maximum violation of the joints recomputed from a DataFrame's point columns and link angles,
    using each link's local geometry (float, vectorised over the rows).

    * every link with ≥ 2 points: each point P seen from the link's first point Q,
      x_Q + A(φ_k)(p_P − p_Q), must coincide with the column x_P (which the engine took from the
      point's owner link) — for a revolute point this is "coincident as seen from both links";
    * frame points stay at their global coordinates;
    * prismatic pair: angle φ_s − φ_g − α ≡ 0 (mod 2π), offset of the slider point from the guide
      line (the guide's line point placed through the guide's first point);
    * actuator: rod and cylinder parallel, rod-end pivot at distance q along the cylinder axis;
    * crank: φ_crank ≡ φ0 + direction·q.
    Returns (max residual, where)."""
    worst, where = 0.0, ""

    def upd(v, label):
        nonlocal worst, where
        m = float(np.max(np.abs(v)))
        if not m <= worst:
            worst, where = (m if not math.isnan(m) else math.inf), label

    def wrap(a):
        return (a + np.pi) % (2 * np.pi) - np.pi

    def xy(p):
        return df["x_" + p].to_numpy(), df["y_" + p].to_numpy()

    def seen_from(link, p):
        """Global position of local point p of link as seen from the link's first point."""
        if link == "0":
            return np.full(len(df), p[0]), np.full(len(df), p[1])
        pts = mech.link(link).points
        qn, (qx, qy) = next(iter(pts.items()))
        th = df["phi_" + link].to_numpy()
        c, s = np.cos(th), np.sin(th)
        X, Y = xy(qn)
        dx, dy = p[0] - qx, p[1] - qy
        return X + c * dx - s * dy, Y + s * dx + c * dy

    q = df["q"].to_numpy()
    for l in mech.links:
        for p, loc in l.points.items():
            X, Y = xy(p)
            sx, sy = seen_from(l.name, loc)
            upd(np.hypot(X - sx, Y - sy), f"point {p} seen from link {l.name}")
    for j in mech.joints:
        if j.kind != "P":
            continue
        g, s = j.links
        tg = np.zeros(len(df)) if g == "0" else df["phi_" + g].to_numpy()
        ts = np.zeros(len(df)) if s == "0" else df["phi_" + s].to_numpy()
        upd(wrap(ts - tg - j.angle), f"angle of prismatic pair {j.name}")
        lx, ly = seen_from(g, j.line_point)
        px, py = xy(j.point)
        nx, ny = -np.sin(tg + j.angle), np.cos(tg + j.angle)
        upd(nx * (px - lx) + ny * (py - ly) - j.offset, f"offset of prismatic pair {j.name}")
    d = mech.driver
    if d.kind == "crank":
        upd(wrap(df["phi_" + d.link].to_numpy() - d.phi0 - d.direction * q), "crank angle")
    else:
        tc = df["phi_" + d.link].to_numpy()
        upd(wrap(df["phi_" + d.rod].to_numpy() - tc), "actuator rod angle")
        bx, by = xy(d.center)
        ex, ey = xy(d.end)
        upd((ex - bx) - q * np.cos(tc), "actuator length x")
        upd((ey - by) - q * np.sin(tc), "actuator length y")
    return worst, where
