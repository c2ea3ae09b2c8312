"""A machine given only by energy: the flywheel from the maximum fluctuation of energy.

Steady motion, reduced inertia constant (flywheel dominant): between the speed extremes
½J(ω_max² − ω_min²) = ΔE_max, and with ω_ср = (ω_max + ω_min)/2, δ = (ω_max − ω_min)/ω_ср
this is exactly J = ΔE_max/(δ·ω_ср²) (Артоболевский, § 21; Попов, Тимофеев, гл. 4).
ΔE_max is given directly, as C_E·A (coefficient of fluctuation of energy times the work per
cycle), by the signed loop areas of the turning-moment diagram above/below the mean moment
(ΔE_max = max − min of their running sums, starting at 0), or by a table M(φ) over the cycle
(piecewise linear; the running work of M − M_ср, exact at the nodes and at the sign changes).
"""
from __future__ import annotations

import numpy as np

__all__ = ["fluctuation_from_loops", "fluctuation_from_table", "speeds", "flywheel_J", "inverse_delta"]


def fluctuation_from_loops(areas) -> tuple[float, np.ndarray]:
    """ΔE_max from the signed loop areas (J): running energy E_k = Σ areas[:k], E_0 = 0;
    ΔE_max = max E − min E.  The areas must sum to zero over a cycle (checked by the caller)."""
    e = np.concatenate([[0.0], np.cumsum(np.asarray(areas, dtype=float))])
    return float(e.max() - e.min()), e


def fluctuation_from_table(phi, M) -> dict:
    """From M(φ) given at nodes over one cycle (piecewise linear): the mean moment
    M_ср = ∫M dφ/Φ, the running excess work E(φ) = ∫(M − M_ср)dφ (exact for the linear pieces,
    extremes at the zeros of M − M_ср found exactly on each piece), ΔE_max = max E − min E."""
    phi = np.asarray(phi, dtype=float)
    M = np.asarray(M, dtype=float)
    L = phi[-1] - phi[0]
    work = float(np.sum(0.5 * (M[1:] + M[:-1]) * np.diff(phi)))
    Mm = work / L
    f = M - Mm
    xs, es = [phi[0]], [0.0]
    e = 0.0
    for i in range(len(phi) - 1):
        h = phi[i + 1] - phi[i]
        if f[i] * f[i + 1] < 0:          # zero of the excess moment inside the piece
            t = f[i] / (f[i] - f[i + 1])
            xs.append(phi[i] + t * h)
            es.append(e + 0.5 * f[i] * t * h)
        e += 0.5 * (f[i] + f[i + 1]) * h
        xs.append(phi[i + 1])
        es.append(e)
    es = np.array(es)
    return dict(work=work, M_mean=Mm, phi=np.array(xs), E=es, dE=float(es.max() - es.min()),
                phi_Emax=float(xs[int(es.argmax())]), phi_Emin=float(xs[int(es.argmin())]))


def speeds(delta: float, *, omega_m: float | None = None, omega_max: float | None = None) -> tuple[float, float, float]:
    """(ω_ср, ω_max, ω_min) from δ and either ω_ср or ω_max: ω_max,min = ω_ср(1 ± δ/2);
    from ω_max: ω_ср = ω_max/(1 + δ/2), ω_min = ω_max·(2 − δ)/(2 + δ)."""
    if omega_m is None:
        omega_m = omega_max / (1 + delta / 2)
    return omega_m, omega_m * (1 + delta / 2), omega_m * (1 - delta / 2)


def flywheel_J(dE: float, delta: float, omega_m: float) -> float:
    """J = 2ΔE/(ω_max² − ω_min²) = ΔE/(δ·ω_ср²)."""
    return dE / (delta * omega_m * omega_m)


def inverse_delta(dE: float, J: float, omega_m: float) -> float:
    """The inverse task: δ = ΔE/(J·ω_ср²)."""
    return dE / (J * omega_m * omega_m)
