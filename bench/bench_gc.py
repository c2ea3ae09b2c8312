"""The garbage collector's threshold in a ``reportgen build``: Python's default (700) against the
CLI's (:func:`reportgen.core.memory.collect_less`), the two runs alternated.

Usage: python bench/bench_gc.py [CASE] [--runs 3]  → bench/results/gc.json (and lines on stdout);
       python bench/bench_gc.py --batch [--variants 4] [--runs 1]  → bench/results/gc_batch.json.

Each run is a new process building CASE (default ws000) with ``--format pdf,html`` into a
temporary folder, as a user runs it; the "default" runs keep Python's threshold by making
``GC_THRESHOLD`` equal to it before the CLI starts (``collect_less`` then changes nothing). Per
run: wall seconds, CPU seconds of the process and its workers (``os.wait4`` of the child: the
workers' CPU is counted when the child waits for them), and the collections the parent ran
with their seconds (``gc.callbacks``). Medians over the runs; the load average is recorded.

``--batch`` measures a kept batch worker instead (``bench/results/gc_batch.json``): each run is
a new process that warms up as a worker does (``batch._init_worker``) and builds the first
``--variants`` rows of ``cases/class_six_bar.csv`` over ws000 one after the other (PDF and HTML),
under one of three policies, alternated: ``before`` (what a worker did before: nothing kept
images let go, nothing frozen), ``detach`` (kept images cut loose from their document,
``batch._detach_images``) and ``freeze`` (that, and the warm state frozen,
``core.memory.freeze_warm_state``: the worker's policy now). Per variant: CPU seconds, the
collector's seconds and collections by generation, the objects its passes walked (the tracked
objects of the generations collected, counted at each start: a figure that does not depend on
the machine's load), live tracked objects and resident memory after the variant; per run the
peak resident memory.
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


BATCH_CHILD = r"""
import gc, json, resource, sys, time
from pathlib import Path
import reportgen.core.memory as memory
from reportgen import batch
mode, n, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
if mode == "before":
    batch._detach_images = lambda cache: 0
if mode in ("before", "detach"):
    memory.freeze_warm_state = lambda: 0
rows = [v for v in batch.read_variants(Path("cases/class_six_bar.csv"), Path("cases/ws000_six_bar.toml"))
        if v.name != "31"][:n]
batch._init_worker()
st = {"s": [0.0] * 3, "n": [0] * 3, "walked": 0}
t0 = [0.0]
def watch(phase, info):
    g = info["generation"]
    if phase == "start":
        st["walked"] += sum(len(gc.get_objects(i)) for i in range(g + 1))
        t0[0] = time.perf_counter()
    else:
        st["s"][g] += time.perf_counter() - t0[0]
        st["n"][g] += 1
def rss_mb():
    with open("/proc/self/status") as f:
        return next(int(l.split()[1]) // 1024 for l in f if l.startswith("VmRSS"))
gc.callbacks.append(watch)
for v in rows:
    st.update(s=[0.0] * 3, n=[0] * 3, walked=0)
    o = batch.run_variant(v, out, ("pdf", "html"), None)
    print(json.dumps({"variant": v.name, "ok": o.ok, "cpu_s": o.cpu_seconds, "gc_s": [round(x, 3) for x in st["s"]],
                      "collections": st["n"], "walked": st["walked"], "live": len(gc.get_objects()),
                      "frozen": gc.get_freeze_count(), "rss_mb": rss_mb(), "peak_mb": o.peak_rss_mb}), flush=True)
"""

BATCH_MODES = ("before", "detach", "freeze")


def one_batch(mode: str, variants: int) -> dict:
    with tempfile.TemporaryDirectory() as out:
        proc = subprocess.run([sys.executable, "-c", BATCH_CHILD, mode, str(variants), out], cwd=ROOT,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, check=True)
    rows = [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]
    assert rows and all(r["ok"] for r in rows), proc.stdout[-2000:]
    return {"variants": rows, "peak_mb": max(r["peak_mb"] for r in rows)}


def main_batch(args) -> dict:
    load0 = os.getloadavg()
    runs: dict[str, list] = {m: [] for m in BATCH_MODES}
    for _ in range(args.runs):
        for mode in BATCH_MODES:
            runs[mode].append(one_batch(mode, args.variants))
    median = {}
    for mode, rs in runs.items():
        later = [v for r in rs for v in r["variants"][1:]]  # the first variant of a worker is not typical
        median[mode] = {"cpu_s": statistics.median(v["cpu_s"] for v in later),
                        "gc_s": statistics.median(sum(v["gc_s"]) for v in later),
                        "walked": statistics.median(v["walked"] for v in later),
                        "live": statistics.median(v["live"] for v in later),
                        "peak_mb": statistics.median(r["peak_mb"] for r in rs)}
    res = {"case": "cases/class_six_bar.csv over cases/ws000_six_bar.toml", "variants": args.variants,
           "runs": runs, "median_after_first": median,
           "machine": {"python": platform.python_version(), "cpus": os.cpu_count(),
                       "load_average_before": [round(x, 2) for x in load0],
                       "load_average_after": [round(x, 2) for x in os.getloadavg()]},
           "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}
    for mode, md in median.items():
        print(f"{mode:7s} CPU per variant {md['cpu_s']:.2f} s, GC {md['gc_s']:.2f} s, objects walked by the "
              f"collector {md['walked']:,.0f}, live after {md['live']:,.0f}, peak RSS {md['peak_mb']:.0f} MB "
              f"(medians over variants 2…{args.variants} of {args.runs} runs)")
    out = ROOT / "bench" / "results" / "gc_batch.json"
    out.write_text(json.dumps(res, indent=1, ensure_ascii=False), encoding="utf-8")
    print(f"результаты: {out}")
    return res


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", nargs="?", default="cases/ws000_six_bar.toml")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--batch", action="store_true", help="a kept batch worker (see the module's docstring)")
    ap.add_argument("--variants", type=int, default=4, help="variants per worker with --batch")
    args = ap.parse_args(argv)
    if args.batch:
        return main_batch(args)
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
