"""Peer measurement for bench/work_precision.py: pylinkage's numba path (``step_fast`` and
``step_fast_with_kinematics``) on the crank-rocker of cases/four_bar.toml.

Runs in a separate virtual environment with pylinkage (and numba) installed, e.g.::

    python -m venv /tmp/peer && /tmp/peer/bin/pip install pylinkage numba
    /tmp/peer/bin/python bench/work_precision_peer.py 3600   # prints JSON

Prints the median warm CPU time (time.process_time) of one cycle and the coordinates, velocities and accelerations of B
at every position (crank at ω = 1 rad/s, so that they are the analogs d/dφ, d²/dφ²)."""
from __future__ import annotations

import json
import math
import statistics
import sys
import time

import numpy as np
import pylinkage as pl

OA, AB, CB, OC = 0.3, 0.9, 0.7, 1.0


def build(n: int):
    O = pl.Ground(0.0, 0.0, name="O")
    C = pl.Ground(OC, 0.0, name="C")
    A = pl.Crank(O, OA, angular_velocity=2 * math.pi / n, initial_angle=0.0, name="A")
    B = pl.RRRDyad(A, C, AB, CB, x=0.88, y=0.69, name="B")
    link = pl.Linkage([O, C, A, B])
    return link, A, B


def main() -> None:
    n = int(sys.argv[1])
    link, A, B = build(n)
    link.compile()
    if hasattr(link, "set_input_velocity"):
        link.set_input_velocity(A, 1.0, 0.0)
    out = {"n": n}
    for name, fn in (("positions", lambda: link.step_fast(iterations=n)),
                     ("with_kinematics", lambda: link.step_fast_with_kinematics(iterations=n))):
        link2, A2, B2 = build(n)
        link2.compile()
        if name == "with_kinematics" and hasattr(link2, "set_input_velocity"):
            link2.set_input_velocity(A2, 1.0, 0.0)
        f = (lambda: link2.step_fast(iterations=n)) if name == "positions" else \
            (lambda: link2.step_fast_with_kinematics(iterations=n))
        f()
        ts = []
        for _ in range(30):
            link2.rebuild() if hasattr(link2, "rebuild") else None
            t0 = time.process_time()
            f()
            ts.append(time.process_time() - t0)
        out[f"time_{name}"] = statistics.median(ts)
    link3, A3, B3 = build(n)
    link3.compile()
    link3.set_input_velocity(A3, 1.0, 0.0)
    pos, vel, acc = link3.step_fast_with_kinematics(iterations=n)
    ia, ib = 2, 3
    out["phi"] = np.arctan2(pos[:, ia, 1], pos[:, ia, 0]).tolist()
    out["B"] = pos[:, ib, :].tolist()
    out["vB"] = vel[:, ib, :].tolist()
    out["aB"] = acc[:, ib, :].tolist()
    print(json.dumps(out))


if __name__ == "__main__":
    main()
