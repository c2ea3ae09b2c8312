"""Where the wall time of one ``write_pdf`` of ws000 goes: a timeline of the layout tasks.

Usage (from the repository root)::

    python bench/bench_pdf_parts.py [--runs N] [--jobs J] [--profile DIR] [--case CASE]

The note is written as the CLI writes it (in parts, by J processes, default
``parallel.note_jobs()``) after one warm-up write (the split points are then known). For every
task laid out (body part, title page ``-2``, СОДЕРЖАНИЕ ``-1``, page numbers ``-3``) the worker
records its process, start and end (seconds from the start of ``write_pdf``) and its CPU
(``time.process_time``): the timeline says which worker waits for which and what the front costs
after the parts. ``--profile DIR`` also writes a cProfile of every task (``DIR/task<idx>-<n>.prof``;
``python -m pstats`` reads them). Medians of N runs of the wall and the CPU (this process and the
workers, ``os.times``) are printed with the load average.
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def study_of(case: str):
    """The study of ``case``: a case file, or ``TABLE.csv:N`` — variant N (from 1) of a batch table
    over ``cases/ws000_six_bar.toml`` as a batch worker builds it."""
    from reportgen.analysis.study import Study

    if ".csv:" not in case:
        return Study(ROOT / case)
    from reportgen import batch
    from reportgen.case.load import load_spec

    table, n = case.rsplit(":", 1)
    v = batch.read_variants(ROOT / table, ROOT / "cases/ws000_six_bar.toml")[int(n) - 1]
    spec = load_spec(v.base, v.params)
    spec.meta_overrides = dict(v.meta)
    return Study(spec)


def case_args(argv: list[str]):
    """``--case`` (the note laid out), ``--other`` (a neighbour's note laid out first, as a batch
    worker has) and ``--rounds`` of the benches that compare two ways of laying out a note."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", default="cases/ws000_six_bar.toml")
    ap.add_argument("--other", default="")
    ap.add_argument("--rounds", type=int, default=3)
    return ap.parse_args(argv)


def part_htmls(case: str = "cases/ws000_six_bar.toml") -> dict[int, str]:
    """The print HTML of every document of ``case``'s note (:func:`study_of`) as the workers of
    ``write_pdf`` get it (the second write in this process: the split points known), by task index."""
    from reportgen.report import parallel, render
    from reportgen.report.assemble import build_report

    report = build_report(study_of(case))
    htmls: dict[int, str] = {}
    original = parallel.lay_out_part

    def keep(task):
        htmls[task.index] = task.html
        return original(task)

    parallel.lay_out_part = keep
    try:
        with tempfile.TemporaryDirectory() as d:
            for _ in range(2):  # the second with the split points known
                htmls.clear()
                render.write_pdf(report, Path(d) / "note.pdf", jobs=1)
    finally:
        parallel.lay_out_part = original
    return htmls


def main(argv: list[str]) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=None)
    ap.add_argument("--profile", default="")
    ap.add_argument("--case", default="cases/ws000_six_bar.toml")
    a = ap.parse_args(argv)

    from reportgen.analysis.study import Study
    from reportgen.report import parallel, render
    from reportgen.report.assemble import build_report

    log_dir = Path(tempfile.mkdtemp(prefix="bench-pdf-parts-"))
    original = parallel.lay_out_part
    state = {"t0": 0.0, "run": 0}

    def timed_part(task):  # replaces parallel.lay_out_part (looked up by name, also in the forked workers)
        c0, w0 = time.process_time(), time.perf_counter()
        prof = None
        if a.profile:
            import cProfile

            prof = cProfile.Profile()
            prof.enable()
        laid = None
        try:
            laid = original(task)
            return laid
        finally:
            if prof is not None:
                prof.disable()
                prof.dump_stats(str(Path(a.profile) / f"task{task.index}-{os.getpid()}-{w0:.3f}.prof"))
            rec = {"run": state["run"], "index": task.index, "pid": os.getpid(), "start": w0 - state["t0"],
                   "end": time.perf_counter() - state["t0"], "cpu": time.process_time() - c0,
                   "layout": getattr(laid, "seconds_layout", 0.0), "write": getattr(laid, "seconds_write", 0.0)}
            with open(log_dir / f"{os.getpid()}.jsonl", "a", encoding="utf-8") as f:
                f.write(json.dumps(rec) + "\n")

    parallel.lay_out_part = timed_part
    if a.profile:
        Path(a.profile).mkdir(parents=True, exist_ok=True)
    report = build_report(study_of(a.case))
    walls, cpus = [], []
    with tempfile.TemporaryDirectory() as d:
        for run in range(a.runs + 1):  # run 0: warm-up (split points found)
            state["run"] = run
            c0, t0 = os.times(), time.perf_counter()
            state["t0"] = t0
            render.write_pdf(report, Path(d) / "note.pdf", jobs=a.jobs)
            t1, c1 = time.perf_counter(), os.times()
            st = render.last_stats.parts
            if run:
                walls.append(t1 - t0)
                cpus.append(sum(c1[:4]) - sum(c0[:4]))
            print(f"run {run}: {t1 - t0:.2f} s wall, {sum(c1[:4]) - sum(c0[:4]):.2f} s CPU; "
                  + (f"html {st.seconds_html:.2f}, wait {st.seconds_wait:.2f}, front {st.seconds_front:.2f}, "
                     f"join {st.seconds_join:.2f}; passes {st.part_passes}" if st is not None else ""), flush=True)
    recs = []
    for p in log_dir.glob("*.jsonl"):
        recs += [json.loads(line) for line in p.read_text().splitlines()]
    last = sorted((r for r in recs if r["run"] == a.runs), key=lambda r: r["start"])
    pids = sorted({r["pid"] for r in last})
    print("timeline of the last run (task: worker, start–end s, CPU s, wall of its layout and write):")
    for r in last:
        print(f"  {r['index']:>3}: w{pids.index(r['pid'])} {r['start']:6.2f}–{r['end']:6.2f}  cpu {r['cpu']:.2f} "
              f"(wall: layout {r['layout']:.2f}, write {r['write']:.2f})")
    per = {}
    for r in recs:
        if r["run"]:
            per.setdefault(r["index"], []).append(r["cpu"])
    print("CPU per task, median over runs: " + ", ".join(f"{i}: {statistics.median(v):.2f}" for i, v in sorted(per.items())))
    print(f"write_pdf: median {statistics.median(walls):.2f} s wall, {statistics.median(cpus):.2f} s CPU "
          f"(runs {', '.join(f'{w:.2f}/{c:.2f}' for w, c in zip(walls, cpus))}); load {os.getloadavg()}")


if __name__ == "__main__":
    main(sys.argv[1:])
