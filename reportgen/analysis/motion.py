"""``[motion]``: the equation of motion of a one-degree-of-freedom machine in time, from its
reduced moment of inertia J_пр(φ) and reduced moment M_пр(φ, φ̇, t) given as expressions.

Lagrange's equation of the second kind with the kinetic energy T = ½J_пр(φ)φ̇²
(Артоболевский, § 20; the energy theorem dT/dt = ΣN in the worksheet 001, problem 9):

    J_пр(φ)·φ̈ + ½·J_пр′(φ)·φ̇² = M_пр(φ, φ̇, t),

integrated by ``scipy.integrate.solve_ivp`` (DOP853).  J_пр′ is given analytically
(``dJ``) and checked against a central difference of ``J``.  A source's printed equation can
be given solved for φ̈ (``printed_eps``): it is integrated beside the correct one and its
residual in the correct equation shown."""
from __future__ import annotations

from functools import cached_property

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

from ..case import units as U
from ..case.expr import Q, evaluate

__all__ = ["Motion"]

KEYS = ["J", "dJ", "M", "phi0", "omega0", "t_end", "points", "printed_eps", "printed_note", "rtol"]


# the work of one integration is bounded (the worksheet's valve needs about 3 000 evaluations)
MAX_RHS_CALLS = 12_000


class _TooLong(Exception):
    """The integration would exceed MAX_RHS_CALLS evaluations of the right-hand side."""


class Motion:
    """The time history φ(t), ω(t), ε(t) of the case's ``[motion]``."""

    def __init__(self, study):
        self.study = study
        self.node = node = study.root.table("motion")
        node.check_keys(KEYS, required=["J", "dJ", "M", "t_end"])
        self.params = p = dict(study.params)
        self.texts = {k: node.string(k, required=k in ("J", "dJ", "M"))
                      for k in ("J", "dJ", "M", "printed_eps", "printed_note")}
        self.phi0 = node.quantity("phi0", U.ANGLE, p, default=0.0)
        self.omega0 = node.quantity("omega0", U.ANGULAR_VELOCITY, p, default=0.0)
        self.t_end = node.quantity("t_end", U.TIME, p, required=True, positive=True)
        self.points = node.integer("points", 401, minimum=11)
        self.rtol = node.quantity("rtol", U.DIMENSIONLESS, p, default=1e-10, positive=True)
        # evaluate once on a sample to report bad expressions with their key, and check dJ
        ph = np.linspace(-np.pi, np.pi, 37)
        J = self._ev("J", ph, 0.0 * ph, 0.0, U.INERTIA)
        if not np.all(J > 0):
            raise node.error("J", "приведённый момент инерции должен быть положительным", expected="J(φ) > 0")
        dJ = self._ev("dJ", ph, 0.0 * ph, 0.0, None)
        h = 1e-5
        fd = (self._ev("J", ph + h, 0 * ph, 0.0, U.INERTIA) - self._ev("J", ph - h, 0 * ph, 0.0, U.INERTIA)) / (2 * h)
        err = float(np.max(np.abs(dJ - fd)))
        if err > 1e-6 * max(float(np.max(np.abs(J))), 1e-300):
            raise node.error("dJ", "производная dJ/dφ не согласуется с J(φ)",
                             expected="dJ — производная выражения J по φ",
                             got=f"расхождение {err:.3g} кг·м² (центральная разность)")
        self.dJ_check = err
        self._ev("M", ph, 0 * ph, 0.0, U.MOMENT)
        if self.texts["printed_eps"]:
            self._ev("printed_eps", ph, 0 * ph, 0.0, U.ANGULAR_ACCELERATION)

    def _ev(self, key, phi, omega, t, dim):
        names = dict(self.params)
        names.update(phi=Q(np.asarray(phi, dtype=float), U.ANGLE), omega=Q(np.asarray(omega, dtype=float),
                     U.ANGULAR_VELOCITY), t=Q(np.asarray(t, dtype=float), U.TIME))
        try:
            q = evaluate(self.texts[key], names, expected=dim)
        except Exception as e:          # CaseError: add file and key
            if hasattr(e, "with_context"):
                raise e.with_context(file=self.node.file, key_prefix=self.node.key(key)) from None
            raise
        return np.broadcast_to(np.asarray(q.value, dtype=float), np.shape(phi)).astype(float)

    def eps(self, phi, omega, t) -> np.ndarray:
        """φ̈ = (M_пр − ½J′φ̇²)/J from the correct equation."""
        J = self._ev("J", phi, omega, t, U.INERTIA)
        dJ = self._ev("dJ", phi, omega, t, None)
        M = self._ev("M", phi, omega, t, U.MOMENT)
        return (M - 0.5 * dJ * omega * omega) / J

    def _integrate(self, which: str) -> pd.DataFrame:
        calls = [0]

        def rhs(t, y):
            calls[0] += 1
            if calls[0] > MAX_RHS_CALLS:
                raise _TooLong
            ph, w = np.array([y[0]]), np.array([y[1]])
            e = self.eps(ph, w, t) if which == "correct" else self._ev("printed_eps", ph, w, t, U.ANGULAR_ACCELERATION)
            return [y[1], float(e[0])]

        ts = np.linspace(0.0, self.t_end, self.points)
        try:
            sol = solve_ivp(rhs, (0.0, self.t_end), [self.phi0, self.omega0], method="DOP853", t_eval=ts,
                            rtol=self.rtol, atol=self.rtol * 1e-3, dense_output=False)
        except _TooLong:
            raise self.node.error("t_end", f"интегрирование уравнения движения требует более {MAX_RHS_CALLS} "
                                           "вычислений правой части: уравнение слишком жёсткое или интервал слишком длинен",
                                  expected="меньшие t_end, жёсткость и демпфирование или бóльший rtol") from None
        if not sol.success:
            raise self.node.error(None, f"интегрирование уравнения движения не удалось: {sol.message}",
                                  expected="конечные J(φ) > 0 и M(φ, ω, t) на всём интервале")
        ph, w = sol.y
        e = self.eps(ph, w, ts) if which == "correct" else self._ev("printed_eps", ph, w, ts, U.ANGULAR_ACCELERATION)
        return pd.DataFrame({"t": ts, "phi": ph, "omega": w, "eps": e})

    @cached_property
    def history(self) -> pd.DataFrame:
        """φ, ω, ε against t by the correct equation, with J_пр and M_пр along it."""
        df = self._integrate("correct")
        df["J"] = self._ev("J", df["phi"], df["omega"], 0.0, U.INERTIA)
        df["M"] = np.array([self._ev("M", np.array([p]), np.array([w]), t, U.MOMENT)[0]
                            for p, w, t in zip(df["phi"], df["omega"], df["t"])])
        if self.texts["printed_eps"]:
            pr = self._integrate("printed")
            df["phi_printed"], df["omega_printed"] = pr["phi"], pr["omega"]
        return df

    def tables(self) -> dict[str, pd.DataFrame]:
        """Export table ``motion_time``: φ(t), ω(t) of the integrated equation of motion."""
        return {"motion_time": self.history}

    @cached_property
    def scalars(self) -> dict:
        """Named results ``motion_*``: the end of the integration, ω's extremes, the largest
        difference between the given dJ/dφ and the central difference of J, and the printed
        solution's deviation when given."""
        h = self.history
        out = {"motion_t_end": self.t_end, "motion_phi_end": float(h["phi"].iloc[-1]),
               "motion_omega_end": float(h["omega"].iloc[-1]), "motion_omega_max": float(h["omega"].max()),
               "motion_omega_min": float(h["omega"].min()), "motion_dJ_check": self.dJ_check}
        if "phi_printed" in h:
            out["motion_phi_end_printed"] = float(h["phi_printed"].iloc[-1])
            out["motion_max_dphi_printed"] = float(np.max(np.abs(h["phi_printed"] - h["phi"])))
        return out
