"""Peer measurement for bench/work_precision.py on the crank-rocker of cases/four_bar.toml and the
offset slider-crank of cases/slider_crank.toml:

* ``pylinkage`` — its numba path (``step_fast`` and ``step_fast_with_kinematics``; RRR and RRP
  dyads);
* ``mechanism`` — the PyPI package ``mechanism`` (vector loop equations solved by
  ``scipy.optimize.fsolve`` at every position, for positions, velocities and accelerations).

Runs in a separate virtual environment with the peers installed (``bench/work_precision.py
--peers`` creates it under ``output/bench/peer-venv``), e.g.::

    output/bench/peer-venv/bin/python bench/work_precision_peer.py 3600 mechanism four_bar  # JSON

Prints the median warm CPU time (time.process_time) of one cycle, positions only and with the
analogs, and the coordinates, velocities and accelerations of B at every position q_j = 2πj/N
(crank at ω = 1 rad/s, ε = 0, so that they are the analogs d/dφ, d²/dφ²)."""
from __future__ import annotations

import json
import math
import statistics
import sys
import time

import numpy as np

# the dimensions of the two cases (m)
FOUR_BAR = dict(OA=0.3, AB=0.9, CB=0.7, OC=1.0)          # cases/four_bar.toml
SLIDER = dict(OA=0.1, AB=0.4, e=0.02)                     # cases/slider_crank.toml


def build(n: int, mech: str):
    """pylinkage model; returns (linkage, crank, index of B among the joints)."""
    import pylinkage as pl
    O = pl.Ground(0.0, 0.0, name="O")
    if mech == "four_bar":
        d = FOUR_BAR
        C = pl.Ground(d["OC"], 0.0, name="C")
        A = pl.Crank(O, d["OA"], angular_velocity=2 * math.pi / n, initial_angle=0.0, name="A")
        B = pl.RRRDyad(A, C, d["AB"], d["CB"], x=0.88, y=0.69, name="B")
        return pl.Linkage([O, C, A, B]), A, 3
    d = SLIDER
    L1, L2 = pl.Ground(0.0, d["e"], name="L1"), pl.Ground(1.0, d["e"], name="L2")
    A = pl.Crank(O, d["OA"], angular_velocity=2 * math.pi / n, initial_angle=0.0, name="A")
    B = pl.RRPDyad(A, L1, L2, d["AB"], x=0.49, y=d["e"], name="B")
    return pl.Linkage([O, L1, L2, A, B]), A, 4


def pylinkage_run(n: int, mech: str) -> dict:
    """pylinkage: sample j of step_fast is the position after j + 1 crank steps; rolled so that
    row j is q_j = 2πj/N like the other methods."""
    out = {"n": n}
    for name in ("positions", "with_kinematics"):
        link, A, _ = build(n, mech)
        link.compile()
        link.set_input_velocity(A, 1.0, 0.0)
        f = (lambda: link.step_fast(iterations=n)) if name == "positions" else \
            (lambda: link.step_fast_with_kinematics(iterations=n))
        f()
        ts = []
        for _ in range(30):
            t0 = time.process_time()
            f()
            ts.append(time.process_time() - t0)
        out[f"time_{name}"] = statistics.median(ts)
    link, A, ib = build(n, mech)
    link.compile()
    link.set_input_velocity(A, 1.0, 0.0)
    pos, vel, acc = link.step_fast_with_kinematics(iterations=n)
    out["B"] = np.roll(pos[:, ib, :], 1, axis=0).tolist()
    out["vB"] = np.roll(vel[:, ib, :], 1, axis=0).tolist()
    out["aB"] = np.roll(acc[:, ib, :], 1, axis=0).tolist()
    return out


def mechanism_run(n: int, mech: str) -> dict:
    """mechanism: vector loops, unknowns the angles (and the slider's length); the same loop
    function serves positions, velocities (input ω = 1) and accelerations (input ε = 0).
    Four-bar: OA + AB − CB − OC = 0 (angles of AB, CB); slider-crank: OA + AB − OP − PB = 0 with
    the offset OP = e (vertical) and PB along the guide (angle of AB, length PB)."""
    from mechanism import Mechanism, Vector, get_joints

    def make(kin: bool):
        q = 2 * math.pi * np.arange(n) / n
        if mech == "four_bar":
            d = FOUR_BAR
            O, A, B, C = get_joints("O A B C")
            a, b = Vector((O, A), r=d["OA"]), Vector((A, B), r=d["AB"])
            c, g = Vector((C, B), r=d["CB"]), Vector((O, C), r=d["OC"], theta=0.0, style="ground")

            def loops(x, inp):
                return a(inp) + b(x[0]) - c(x[1]) - g()
            guess = (np.array([0.87, 1.74]), np.ones(2), np.ones(2))
        else:
            d = SLIDER
            O, A, B, P = get_joints("O A B P")
            a, b = Vector((O, A), r=d["OA"]), Vector((A, B), r=d["AB"])
            g, c = Vector((O, P), r=d["e"], theta=math.pi / 2, style="ground"), Vector((P, B), theta=0.0)

            def loops(x, inp):
                return a(inp) + b(x[0]) - g() - c(x[1])
            guess = (np.array([0.05, 0.5]), np.ones(2), np.ones(2))
        m = Mechanism(vectors=(a, b, c, g), origin=O, loops=loops, pos=q,
                      vel=np.ones(n) if kin else None, acc=np.zeros(n) if kin else None, guess=guess)
        return m, B

    out = {"n": n}
    runs = 3 if n <= 3600 else 1
    for name, kin in (("positions", False), ("with_kinematics", True)):
        ts = []
        for _ in range(runs):
            m, B = make(kin)
            t0 = time.process_time()
            m.iterate()
            ts.append(time.process_time() - t0)
        out[f"time_{name}"] = statistics.median(ts)
    out["B"] = np.column_stack([B.x_positions, B.y_positions]).tolist()
    out["vB"] = np.column_stack([B.x_velocities, B.y_velocities]).tolist()
    out["aB"] = np.column_stack([B.x_accelerations, B.y_accelerations]).tolist()
    return out


def main() -> None:
    n = int(sys.argv[1])
    package = sys.argv[2] if len(sys.argv) > 2 else "pylinkage"
    mech = sys.argv[3] if len(sys.argv) > 3 else "four_bar"
    run = {"pylinkage": pylinkage_run, "mechanism": mechanism_run}[package]
    print(json.dumps(run(n, mech)))


if __name__ == "__main__":
    main()
