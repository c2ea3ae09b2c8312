"""CPU time of the kinematics kernel and of the whole numerical analysis of a case (warm process).

Usage: ``.venv/bin/python bench/bench_analysis.py [CASE …] [--repeat N]`` (default case:
cases/ws000_six_bar.toml).  For each case:

* the whole-grid kernel ``analysis.linkage.run_kernel`` on the cycle grid (positions, first and
  second analogs): median and minimum CPU time (``time.process_time``) of N warm calls;
* the closed-form tape (``core/tape.py``: what ``run_kernel`` runs when every group is the initial
  link or a ВВВ/ВВП/ВПВ dyad) against the general kernel ``core.kinematics.solve_cycle`` (every
  group's Φ_x assembled and LU-solved), alternated in one process: minimum CPU time of N calls each;
* the kernel solving only the first k groups, k = 0 … number of groups (the cost of the loop
  itself — allocating and filling the outputs — and of each group in order);
* the whole numerical analysis of a fresh Study (kinematics, the cycle, every task of the case —
  dynamics with the flywheel, forces — with all their export tables and scalars, and again with
  the scalars only): median and minimum CPU time of 7 fresh Studies after one warm-up, the time
  of each stage, the CPU time inside the kernel and outside it; the number of kernel calls and
  of positions they solved.

CPU time is used because the machine is shared: a loaded machine inflates wall time several
times, CPU time much less.  Never part of the tests.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def kernel_times(case: str, repeat: int) -> tuple[float, float, int]:
    from reportgen.analysis import linkage as L
    from reportgen.analysis.study import Study
    s = Study(ROOT / case)
    model, q = s.model, s.grid.cycle
    L.run_kernel(model, q)
    ts = []
    for _ in range(repeat):
        t0 = time.process_time()
        L.run_kernel(model, q)
        ts.append(time.process_time() - t0)
    return statistics.median(ts), min(ts), len(q)


def group_costs(case: str, repeat: int) -> list[float]:
    """Minimum CPU time of the kernel solving only the first k groups, k = 0 … all."""
    from reportgen.analysis import linkage as L
    from reportgen.analysis.study import Study
    s = Study(ROOT / case)
    model, q = s.model, s.grid.cycle
    out = []
    for k in range(len(model.groups) + 1):
        L.run_kernel(model, q, k)
        ts = []
        for _ in range(repeat):
            t0 = time.process_time()
            L.run_kernel(model, q, k)
            ts.append(time.process_time() - t0)
        out.append(min(ts))
    return out


def analog_paths(case: str, repeat: int) -> tuple[float, float]:
    """(tape, general kernel) minimum CPU time over the cycle grid, calls alternated in one
    process (the tape time is ``inf`` when the case has a group the tape does not take)."""
    from reportgen.analysis import linkage as L
    from reportgen.analysis.study import Study
    s = Study(ROOT / case)
    model, q = s.model, s.grid.cycle
    ng = len(model.groups)
    runs = (lambda: L.run_kernel(model, q),
            lambda: L.solve_general(model, q, ng, model.gsigma, model.pose0))
    best = {0: [], 1: []}
    for _ in range(repeat):
        for k, fn in enumerate(runs):
            t0 = time.process_time()
            fn()
            best[k].append(time.process_time() - t0)
    return (min(best[0]) if L.tape(model) is not None else float("inf")), min(best[1])


def stage_times(s, clock=time.process_time, tables: bool = True) -> dict[str, float]:
    """Time by ``clock`` of each stage of the fresh Study ``s``: the model, the kinematics at the
    report positions, the cycle table, every task (its scalars, and its export tables when
    ``tables``), and the total."""
    out = {}
    t0 = clock()
    s.model
    out["model"] = clock() - t0
    for name in ("kinematics", "cycle"):
        t = clock()
        getattr(s, name)
        out[name] = clock() - t
    for name in s.tasks():
        t = clock()
        a = s.analysis(name)
        if tables:
            a.tables()
        a.scalars
        out[name] = clock() - t
    out["total"] = clock() - t0
    return out


def analysis_stages(case: str, tables: bool = True) -> tuple[dict[str, float], int, int]:
    """CPU time of each stage of a fresh Study, the number of kernel calls and positions.

    ``tables``: every task's export tables (pandas DataFrames) are built too, as ``reportgen
    export`` does; otherwise only what the numbers of the note need (the kinematics at the
    report positions, the cycle table and every task's scalars).  ``kernel`` is the CPU time
    spent inside ``run_kernel`` over all stages (the part the kernel rewrite addresses)."""
    from reportgen.analysis import linkage as L
    from reportgen.analysis.study import Study
    calls = [0, 0, 0.0]
    orig = L.run_kernel

    def counted(model, q, *a, **k):
        calls[0] += 1
        calls[1] += len(q)
        t = time.process_time()
        try:
            return orig(model, q, *a, **k)
        finally:
            calls[2] += time.process_time() - t

    L.run_kernel = counted
    try:
        out = stage_times(Study(ROOT / case), time.process_time, tables)
        out["kernel"] = calls[2]
    finally:
        L.run_kernel = orig
    return out, calls[0], calls[1]


def whole_analysis(case: str, tables: bool, runs: int = 7) -> None:
    analysis_stages(case, tables)          # warm every stage once
    res = [analysis_stages(case, tables) for _ in range(runs)]
    st = [r[0] for r in res]
    med = {k: statistics.median(x[k] for x in st) for k in st[0]}
    best = {k: min(x[k] for x in st) for k in st[0]}
    what = "with every export table" if tables else "numbers only (scalars, no export tables)"
    print(f"  whole analysis of a fresh Study, {what}, CPU: median {med['total'] * 1e3:.1f} ms, "
          f"min {best['total'] * 1e3:.1f} ms (of {runs}); inside the kernel: median "
          f"{med['kernel'] * 1e3:.1f} ms; outside it: median {(med['total'] - med['kernel']) * 1e3:.1f} ms; "
          f"{res[0][1]} kernel calls over {res[0][2]} positions")
    print("    stages (median): " + ", ".join(f"{k} {v * 1e3:.1f} ms" for k, v in med.items()
                                            if k not in ("total", "kernel")))


def main(argv=None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("cases", nargs="*", default=["cases/ws000_six_bar.toml"])
    ap.add_argument("--repeat", type=int, default=200)
    args = ap.parse_args(argv)
    import os
    print(f"load average before: {os.getloadavg()[0]:.2f}; "
          f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")
    for case in args.cases:
        med, best, n = kernel_times(case, args.repeat)
        print(f"{case}: kernel over {n} positions (positions + both analogs), CPU: "
              f"median {med * 1e3:.3f} ms, min {best * 1e3:.3f} ms ({med / n * 1e9:.0f} ns a position)")
        fast, dense = analog_paths(case, args.repeat)
        print(f"  paths: tape {fast * 1e3:.3f} ms, general kernel (dense LU) {dense * 1e3:.2f} ms "
              f"(minimum CPU time, {args.repeat} alternated calls each)")
        gc = group_costs(case, max(20, args.repeat // 4))
        print("  kernel with the first k groups (minimum CPU time): "
              + ", ".join(f"k = {k}: {t * 1e3:.3f} ms" for k, t in enumerate(gc)))
        whole_analysis(case, tables=True)
        whole_analysis(case, tables=False)
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
