"""The garbage collector's threshold in a ``reportgen build``: Python's default (700) against the
CLI's (:func:`reportgen.core.memory.collect_less`), the two runs alternated.

Usage: python bench/bench_gc.py [CASE] [--runs 3]  → bench/results/gc.json (and lines on stdout).

Each run is a new process building CASE (default ws000) with ``--format pdf,html`` into a
temporary folder, as a user runs it; the "default" runs keep Python's threshold by making
``GC_THRESHOLD`` equal to it before the CLI starts (``collect_less`` then changes nothing). Per
run: wall seconds, CPU seconds of the process and its workers (``os.wait4`` of the child: the
workers' CPU is counted when the child waits for them), and the collections the parent ran
with their seconds (``gc.callbacks``). Medians over the runs; the load average is recorded.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

CHILD = r"""
import gc, json, sys, time
import reportgen.core.memory as memory
if sys.argv[1] == "default":
    memory.GC_THRESHOLD = gc.get_threshold()
st = {"seconds": 0.0, "collections": [0, 0, 0]}
t0 = [0.0]
def watch(phase, info):
    if phase == "start":
        t0[0] = time.perf_counter()
    else:
        st["seconds"] += time.perf_counter() - t0[0]
        st["collections"][info["generation"]] += 1
gc.callbacks.append(watch)
from reportgen.cli import main
rc = main(["build", sys.argv[2], "--format", "pdf,html", "-o", sys.argv[3]])
gc.callbacks.remove(watch)
print(json.dumps({"rc": rc, "gc": st, "threshold": list(gc.get_threshold())}))
"""


def one(mode: str, case: str) -> dict:
    with tempfile.TemporaryDirectory() as out:
        t = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-c", CHILD, mode, case, out], cwd=ROOT,
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        stdout = proc.stdout.read()
        _pid, _status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t
    got = json.loads(stdout.strip().splitlines()[-1])
    return {"wall_s": round(wall, 2), "cpu_s": round(usage.ru_utime + usage.ru_stime, 2),
            "parent_gc_s": round(got["gc"]["seconds"], 3), "collections": got["gc"]["collections"],
            "threshold": got["threshold"], "rc": got["rc"]}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", nargs="?", default="cases/ws000_six_bar.toml")
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args(argv)
    load0 = os.getloadavg()
    runs: dict[str, list] = {"default": [], "collect_less": []}
    one("collect_less", args.case)  # caches filled (split points, fonts, formulas): not counted
    for _ in range(args.runs):
        for mode in runs:
            runs[mode].append(one(mode, args.case))
    res = {"case": args.case, "runs": runs,
           "median": {m: {k: statistics.median(r[k] for r in rs) for k in ("wall_s", "cpu_s", "parent_gc_s")}
                      for m, rs in runs.items()},
           "machine": {"python": platform.python_version(), "cpus": os.cpu_count(),
                       "load_average_before": [round(x, 2) for x in load0],
                       "load_average_after": [round(x, 2) for x in os.getloadavg()]},
           "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}
    for m, rs in runs.items():
        md = res["median"][m]
        print(f"{m:13s} threshold {rs[0]['threshold']}: wall {md['wall_s']:.2f} s, CPU {md['cpu_s']:.2f} s, "
              f"parent GC {md['parent_gc_s']:.3f} s, collections {rs[0]['collections']} (median of {len(rs)})")
    out = ROOT / "bench" / "results" / "gc.json"
    out.write_text(json.dumps(res, indent=1, ensure_ascii=False), encoding="utf-8")
    print(f"результаты: {out}")
    return res


if __name__ == "__main__":
    main()
