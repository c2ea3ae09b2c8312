"""Warm run time of the whole-grid kinematics kernel and of the whole numerical analysis.

Usage: ``.venv/bin/python bench/bench_kinematics.py [CASE …] [--repeat N]``
(default case: cases/ws000_six_bar.toml).  For each case: the kernel
``analysis.linkage.run_kernel`` over the 3 600-position cycle grid (positions and both analogs;
median of N warm calls), ``points_cycle``, a fresh Study's ``cycle`` table, and the whole
numerical analysis (kinematics, dynamics, flywheel, forces) of a fresh Study, each stage timed.
The kernel is also timed in CPU time of the process (``time.process_time``), which a shared,
loaded machine inflates less than wall time.  Never part of the tests.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def median_time(fn, repeat: int, clock=time.perf_counter) -> float:
    fn()
    ts = []
    for _ in range(repeat):
        t0 = clock()
        fn()
        ts.append(clock() - t0)
    return statistics.median(ts)


def stages(case: str) -> dict[str, float]:
    """Wall time of each analysis stage of a fresh Study (warm process)."""
    from bench_analysis import stage_times
    from reportgen.analysis.study import Study
    return stage_times(Study(ROOT / case), time.perf_counter)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("cases", nargs="*", default=["cases/ws000_six_bar.toml"])
    ap.add_argument("--repeat", type=int, default=200)
    args = ap.parse_args(argv)
    import numpy as np
    from reportgen.analysis import linkage as L
    from reportgen.analysis.study import Study
    from reportgen.core import kinematics as K
    for case in args.cases:
        s = Study(ROOT / case)
        model = s.model
        q = s.grid.cycle
        t_kernel = median_time(lambda: L.run_kernel(model, q), args.repeat)
        t_kernel_cpu = median_time(lambda: L.run_kernel(model, q), args.repeat, time.process_time)
        pose, d1, d2, _, _ = L.run_kernel(model, q)
        t_pts = median_time(lambda: K.points_cycle(pose, d1, d2, q, model.pbody, model.ploc), args.repeat)
        t_cycle = median_time(lambda: Study(ROOT / case).cycle, max(5, args.repeat // 20))
        stages(case)   # warm every stage once
        st = [stages(case) for _ in range(5)]
        med = {k: statistics.median(x[k] for x in st) for k in st[0]}
        print(f"{case}: N = {len(q)}")
        print(f"  kernel run_kernel (positions + analogs): {t_kernel * 1e3:.3f} ms"
              f" = {t_kernel / len(q) * 1e9:.0f} ns/position (CPU time {t_kernel_cpu * 1e3:.3f} ms)")
        print(f"  points_cycle: {t_pts * 1e3:.3f} ms")
        print(f"  fresh Study.cycle: {t_cycle * 1e3:.2f} ms")
        print("  fresh Study, stages (median of 5): " +
              ", ".join(f"{k} {v * 1e3:.1f} ms" for k, v in med.items()))


if __name__ == "__main__":
    main()
