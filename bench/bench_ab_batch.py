"""The 30-variant batch of issue #15 measured on two checkouts in turn, so that a change of code is
told from the drift of the machine (this machine's speed changes between runs by as much as a
session's gains: the plain WeasyPrint document took 2,97 s in one session and 2,72 s in the next).

Usage (from the repository root)::

    python bench/bench_ab_batch.py --a /tmp/old-checkout [--b .] [--variants 30] [--rounds 1]
    python bench/bench_ab_batch.py --a /tmp/old-checkout --build 4 --variants 0   # the warm build only

``--a`` and ``--b`` are checkouts of reportgen (``git worktree add`` or ``git archive … | tar -x``);
both run with this interpreter (the same installed packages). For each checkout: a new cache folder,
``reportgen warmup`` and one build of the base case (numba's cache next to that checkout's sources,
fonts), not measured. Then, alternating A, B, A, B …: the class as never built before (the first
round: no split points of any variant) and then ``--rounds`` times again (every variant's split
points known), as ``bench/bench_cli.py --only batch`` measures one checkout. Prints a table and writes
``bench/results/ab_batch.json`` (wall and CPU seconds, CPU per variant, peak memory per worker, the
load average before and after each run). ``--build N``: first the warm build of ws000 (``reportgen build
cases/ws000_six_bar.toml --format pdf,html``, as ``bench_cli.py --only build``) N times in each checkout,
alternating, after one unmeasured build each; medians of wall and CPU seconds.
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_cli import CASE, CLASS, CPU, ROOT, _batch_run, class_table, machine, run  # noqa: E402


def _prepare(tree: Path, tmp: Path) -> dict:
    cache = tmp / "cache"
    cache.mkdir(parents=True)
    env = {"XDG_CACHE_HOME": str(cache), "REPORTGEN_CACHE": str(cache / "reportgen")}
    run(["warmup"], tree, **env)
    run(["build", CASE, "--format", "pdf,html", "-o", str(tmp / "base")], tree, **env)
    return env


def _summary(runs: list[dict]) -> dict:
    walls = [r["wall_s"] for r in runs]
    return {"wall_median_s": round(statistics.median(walls), 1), "wall_runs_s": walls,
            "cpu_runs_s": [r["cpu_s"] for r in runs],
            "variant_cpu_median_s": [r["variant_cpu_median_s"] for r in runs]}


def ab_build(trees: dict, tmp: Path, n: int) -> dict:
    """The warm build of :data:`CASE` ``n`` times per checkout, A and B alternating (one unmeasured
    build each first: numba's cache, fonts, split points)."""
    runs: dict = {k: [] for k in trees}
    args = lambda k: ["build", CASE, "--format", "pdf,html", "-o", str(tmp / f"build-{k}")]  # noqa: E731
    for k, tree in trees.items():
        run(args(k), tree)
    for _ in range(n):
        for k, tree in trees.items():
            wall = run(args(k), tree)
            runs[k].append({"wall_s": round(wall, 2), "cpu_s": round(CPU[-1], 2),
                            "load": round(os.getloadavg()[0], 2)})
            print(f"{k} сборка: {runs[k][-1]}", flush=True)
    return {k: {"runs": r, "wall_median_s": round(statistics.median(x["wall_s"] for x in r), 2),
                "cpu_median_s": round(statistics.median(x["cpu_s"] for x in r), 2)} for k, r in runs.items()}


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--a", type=Path, required=True, help="первая копия (например, до изменений)")
    ap.add_argument("--b", type=Path, default=ROOT, help="вторая копия (по умолчанию эта)")
    ap.add_argument("--variants", type=int, default=30)
    ap.add_argument("--rounds", type=int, default=1, help="сколько раз пересобрать класс после первой сборки")
    ap.add_argument("--build", type=int, default=0, help="сколько раз собрать ws000 в каждой копии (0 — не собирать)")
    a = ap.parse_args(argv)
    trees = {"A": a.a.resolve(), "B": a.b.resolve()}
    with tempfile.TemporaryDirectory(prefix="ab-batch-") as td:
        tmp = Path(td)
        builds = ab_build(trees, tmp, a.build) if a.build else {}
        table, n = class_table(tmp, max(a.variants, 1))
        envs = {k: _prepare(t, tmp / k) for k, t in trees.items()}
        res: dict = {k: {"tree": str(t), "new": [], "again": []} for k, t in trees.items()}
        for rnd in range(1 + a.rounds if a.variants else 0):
            for k, tree in trees.items():
                out = tmp / k / "batch"
                args = ["batch", str(table), "--base", str(tree / CASE), "-o", str(out), "--jobs", "2"]
                r = _batch_run(args, out, n, tree, **envs[k])
                res[k]["new" if rnd == 0 else "again"].append(r)
                print(f"{k} {'новый класс' if rnd == 0 else 'ещё раз'}: {r['wall_s']} с стен., {r['cpu_s']} с ЦП, "
                      f"ЦП варианта (медиана) {r['variant_cpu_median_s']} с, load {r['load_average']}", flush=True)
    out = {"machine": machine(), "variants": n if a.variants else 0, "build": builds, "class": CLASS, "rounds": a.rounds,
           "command": "python bench/bench_ab_batch.py " + " ".join(sys.argv[1:] if argv is None else argv)}
    for k in trees if a.variants else ():
        out[k] = res[k] | {"new_summary": _summary(res[k]["new"]),
                           "again_summary": _summary(res[k]["again"]) if res[k]["again"] else {}}
    path = ROOT / "bench" / "results" / ("ab_batch.json" if a.variants else "ab_build.json")
    path.write_text(json.dumps(out, ensure_ascii=False, indent=1), encoding="utf-8")
    for k in builds:
        print(k, trees[k], "сборка ws000: медиана", builds[k]["wall_median_s"], "с стен.,", builds[k]["cpu_median_s"], "с ЦП")
    for k in trees if a.variants else ():
        print(k, trees[k], "новый:", out[k]["new_summary"], "ещё раз:", out[k]["again_summary"])
    print("записано:", path.relative_to(ROOT), "| load average сейчас:", [round(x, 2) for x in os.getloadavg()])


if __name__ == "__main__":
    main()
