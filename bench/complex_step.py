"""Complex-step kinematics: a reference method of the work–precision benchmark (not the engine).

Formulation (the whole mechanism at once, no Assur decomposition, written from the
:class:`~reportgen.mechanism.model.Mechanism` description): unknowns X = (x_k, y_k, θ_k) of every
moving link's frame, constraints Φ(X, q) = 0

* revolute joint at P between links a, b:   r_a + A(θ_a) p_a − r_b − A(θ_b) p_b = 0;
* prismatic joint (guide g, slider s):      θ_s − θ_g − α − 2πk = 0,
                                           n·(r_s + A_s p_s − r_g − A_g l) − e = 0, n = A_g(−sin α, cos α);
* crank:                                   θ_c − φ₀ − direction·q − 2πk = 0,

with the analytic Jacobian Φ_X.  Every function involved is analytic, so Newton's method converges
in complex arithmetic as well (Squire & Trapp, SIAM Review 40 (1998) 110; Martins, Sturdza & Alonso,
ACM TOMS 29 (2003) 245 — the complex-step derivative):

* positions   X(q) = Re X(q + ih) + O(h²),
* first analogs X′(q) = Im X(q + ih)/h + O(h²)    (no subtraction, so h = 1e-20 is allowed),
* second analogs X″(q) = Im X′(q + ih)/h + O(h²), where X′(q + ih) = −Φ_X⁻¹Φ_q is the tangent
  solved at the complex pose (the complex step applied to the first analog).

Points P = r_k + A(θ_k)p follow the same way.  Newton on the whole grid at once (vectorised over the
positions, batched LU of numpy); its starting guesses come from a coarse continuation (72 positions
solved one after another from the assembly at the first position, predictor X + Δq·X′) and cubic
Hermite interpolation between them.  The assembly at the first position (the branch) is taken from
the engine, as the engine takes it from the sketch.  Supports crank-driven mechanisms with revolute
and prismatic pairs (every mechanism of the benchmark)."""
from __future__ import annotations

import math

import numpy as np

H = 1e-20          # complex step
COARSE = 72        # positions of the continuation that provides the starting guesses


class ComplexStepKinematics:
    """Φ(X, q), Φ_X, Φ_q of a crank-driven mechanism, vectorised over positions, real or complex."""

    def __init__(self, study):
        mech = study.mechanism
        if mech.driver.kind != "crank":
            raise ValueError("complex-step benchmark: only crank-driven mechanisms")
        self.study = study
        self.links = [l.name for l in mech.moving]
        self.col = {n: 3 * i for i, n in enumerate(self.links)}
        self.n = 3 * len(self.links)
        self.local = {l.name: {p: (float(x), float(y)) for p, (x, y) in l.points.items()} for l in mech.links}
        self.owner = mech.point_owner()
        self.joints = list(mech.joints)
        d = mech.driver
        self.crank, self.phi0, self.direction = d.link, float(d.phi0), float(d.direction)
        self.turns: dict[str, int] = {}
        rows = sum(2 for _ in self.joints) + 1
        if rows != self.n:
            raise ValueError(f"{rows} equations for {self.n} unknowns")

    # ------------------------------------------------------------------ geometry
    def _pose(self, X, name):
        """(x, y, cos θ, sin θ, θ) of a link; the frame is fixed at the origin."""
        if name not in self.col:
            z = np.zeros(X.shape[0], dtype=X.dtype)
            return z, z, z + 1, z, z
        c = self.col[name]
        th = X[:, c + 2]
        return X[:, c], X[:, c + 1], np.cos(th), np.sin(th), th

    @staticmethod
    def _glob(pose, p):
        x, y, c, s, _ = pose
        return x + c * p[0] - s * p[1], y + s * p[0] + c * p[1]

    @staticmethod
    def _dglob(pose, p):
        """∂(A(θ)p)/∂θ."""
        _, _, c, s, _ = pose
        return -s * p[0] - c * p[1], c * p[0] - s * p[1]

    def _put(self, Jm, r, link, vals):
        """Add the derivatives (∂/∂x, ∂/∂y, ∂/∂θ) of row r with respect to a moving link."""
        if link in self.col:
            c = self.col[link]
            for k, v in enumerate(vals):
                if v is not None:
                    Jm[:, r, c + k] += v

    def system(self, X, q, jacobian=True):
        """Residual Φ (N, n) and, if asked, Φ_X (N, n, n); Φ_q is constant (crank row)."""
        N = X.shape[0]
        F = np.empty((N, self.n), dtype=X.dtype)
        Jm = np.zeros((N, self.n, self.n), dtype=X.dtype) if jacobian else None
        r = 0
        for j in self.joints:
            a, b = j.links
            Pa, Pb = self._pose(X, a), self._pose(X, b)
            if j.kind == "R":
                pa, pb = self.local[a][j.point], self.local[b][j.point]
                ax, ay = self._glob(Pa, pa)
                bx, by = self._glob(Pb, pb)
                F[:, r], F[:, r + 1] = ax - bx, ay - by
                if jacobian:
                    da, db = self._dglob(Pa, pa), self._dglob(Pb, pb)
                    self._put(Jm, r, a, (1.0, None, da[0]))
                    self._put(Jm, r + 1, a, (None, 1.0, da[1]))
                    self._put(Jm, r, b, (-1.0, None, -db[0]))
                    self._put(Jm, r + 1, b, (None, -1.0, -db[1]))
            else:                                   # prismatic: a = guide, b = slider
                alpha = float(j.angle)
                k = self.turns.get(j.name, 0)
                F[:, r] = Pb[4] - Pa[4] - alpha - 2 * math.pi * k
                n0x, n0y = -math.sin(alpha), math.cos(alpha)
                _, _, cg, sg, _ = Pa
                nx, ny = cg * n0x - sg * n0y, sg * n0x + cg * n0y
                pb, pl = self.local[b][j.point], tuple(map(float, j.line_point))
                sx, sy = self._glob(Pb, pb)
                lx, ly = self._glob(Pa, pl)
                F[:, r + 1] = nx * (sx - lx) + ny * (sy - ly) - float(j.offset)
                if jacobian:
                    self._put(Jm, r, b, (None, None, 1.0))
                    self._put(Jm, r, a, (None, None, -1.0))
                    ds, dl = self._dglob(Pb, pb), self._dglob(Pa, pl)
                    self._put(Jm, r + 1, b, (nx, ny, nx * ds[0] + ny * ds[1]))
                    dnx, dny = -sg * n0x - cg * n0y, cg * n0x - sg * n0y
                    self._put(Jm, r + 1, a, (-nx, -ny, dnx * (sx - lx) + dny * (sy - ly) - nx * dl[0] - ny * dl[1]))
            r += 2
        th = self._pose(X, self.crank)[4]
        F[:, r] = th - self.phi0 - self.direction * q - 2 * math.pi * self.turns.get("crank", 0)
        if jacobian:
            self._put(Jm, r, self.crank, (None, None, 1.0))
        return F, Jm

    def phi_q(self, N, dtype):
        Fq = np.zeros((N, self.n), dtype=dtype)
        Fq[:, -1] = -self.direction
        return Fq

    def tangent(self, X, q):
        """X′ = −Φ_X⁻¹Φ_q (at a real or complex pose)."""
        _, Jm = self.system(X, q)
        return np.linalg.solve(Jm, -self.phi_q(X.shape[0], X.dtype)[..., None])[..., 0]

    def newton(self, X, q, maxit=30):
        """Newton on Φ(X, q) = 0 for all positions at once (real or complex).  Stops when the
        real and the imaginary (÷h) parts of the step are at rounding level."""
        scale = 1.0 + float(np.max(np.abs(X.real)))
        prev = math.inf
        for it in range(maxit):
            F, Jm = self.system(X, q)
            dx = np.linalg.solve(Jm, F[..., None])[..., 0]
            X = X - dx
            re = float(np.max(np.abs(dx.real)))
            im = float(np.max(np.abs(dx.imag))) / H if np.iscomplexobj(dx) else 0.0
            size = max(re, im)
            # converged: at rounding level, or no longer decreasing once below 1e-10 (the
            # rounding floor of an ill-conditioned group lies above 4e-16)
            if it >= 1 and (size <= 4e-16 * scale or (size <= 1e-10 * scale and size > 0.25 * prev)):
                return X
            prev = size
        raise RuntimeError("complex-step Newton did not converge")

    # ------------------------------------------------------------------ the method
    def start_pose(self, q0):
        """Link frames at q0 from the engine's assembly (the branch of the sketch)."""
        row = self.study.at([q0]).iloc[0]
        X = []
        for n in self.links:
            th = float(row["phi_" + n])
            p, (lx, ly) = next(iter(self.local[n].items()))
            c, s = math.cos(th), math.sin(th)
            X += [float(row["x_" + p]) - (c * lx - s * ly), float(row["y_" + p]) - (s * lx + c * ly), th]
        X = np.array([X])
        for j in self.joints:
            if j.kind == "P":
                a, b = j.links
                d = self._pose(X, b)[4] - self._pose(X, a)[4] - float(j.angle)
                self.turns[j.name] = int(round(float(d[0]) / (2 * math.pi)))
        d = self._pose(X, self.crank)[4] - self.phi0 - self.direction * q0
        self.turns["crank"] = int(round(float(d[0]) / (2 * math.pi)))
        return X

    def guesses(self, X0, q):
        """Coarse continuation over [q₀, q_end] and cubic Hermite interpolation to every q."""
        qc = np.linspace(q[0], q[-1], COARSE + 1)
        Xc = np.empty((COARSE + 1, self.n))
        Vc = np.empty_like(Xc)
        x = self.newton(X0.astype(float), qc[:1])
        v = self.tangent(x, qc[:1])
        Xc[0], Vc[0] = x[0], v[0]
        for i in range(1, COARSE + 1):
            x = self.newton(x + (qc[i] - qc[i - 1]) * v, qc[i:i + 1])
            v = self.tangent(x, qc[i:i + 1])
            Xc[i], Vc[i] = x[0], v[0]
        k = np.clip(np.searchsorted(qc, q, side="right") - 1, 0, COARSE - 1)
        hc = qc[1] - qc[0]
        t = ((q - qc[k]) / hc)[:, None]
        h00, h10 = 2 * t ** 3 - 3 * t ** 2 + 1, t ** 3 - 2 * t ** 2 + t
        h01, h11 = -2 * t ** 3 + 3 * t ** 2, t ** 3 - t ** 2
        return h00 * Xc[k] + h10 * hc * Vc[k] + h01 * Xc[k + 1] + h11 * hc * Vc[k + 1]

    def points(self, q, names, X0=None):
        """(N, npoints, 6): x, y, x′, y′, x″, y″ of the named points by the complex step."""
        q = np.asarray(q, dtype=float)
        if X0 is None:
            X0 = self.start_pose(float(q[0]))
        G = self.guesses(X0, q)
        qc = q + 1j * H
        X = self.newton(G.astype(complex), qc)
        V = self.tangent(X, qc)
        out = np.empty((q.size, len(names), 6))
        for i, p in enumerate(names):
            link = self.owner[p]
            loc = self.local[link][p]
            pose = self._pose(X, link)
            gx, gy = self._glob(pose, loc)
            if link in self.col:
                c = self.col[link]
                dx, dy = self._dglob(pose, loc)
                vx = V[:, c] + dx * V[:, c + 2]
                vy = V[:, c + 1] + dy * V[:, c + 2]
            else:
                vx = vy = np.zeros(q.size, dtype=complex)
            out[:, i, 0], out[:, i, 1] = gx.real, gy.real
            out[:, i, 2], out[:, i, 3] = gx.imag / H, gy.imag / H
            out[:, i, 4], out[:, i, 5] = vx.imag / H, vy.imag / H
        return out
