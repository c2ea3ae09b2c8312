"""CPU of building the note's sections (text, tables, figures: ``build_report``) as a batch
worker spends it per variant, and of the sections of one case built again and again.

Usage: ``python bench/bench_section_cpu.py [--variants N] [--case CASE] [--runs R]``.

* batch: a process set up as a batch worker (``batch._init_worker``: warm imports, fonts,
  shared caches, frozen warm state), then the first ``N`` variants of ``cases/class_six_bar.csv``
  (base ``cases/ws000_six_bar.toml``, as ``bench/bench_cli.py``): each variant's results computed first (not counted),
  then ``build_report`` timed (``time.process_time``), then the worker's clean-up
  (``batch._after_variant``, not counted); the median and each value are printed.
* case: ``build_report`` of ``CASE`` (default ws000) ``R`` times in one warm process with the
  CLI's collector setting, each on a fresh Study whose results are computed first; median.

Prints the figures and the machine load (``os.getloadavg``); writes nothing.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def _computed(study):
    from reportgen.report.assemble import needs
    for n in sorted(needs(study)):
        getattr(study, n)
    return study


def batch(n: int) -> list[float]:
    from reportgen import batch as B
    from reportgen.analysis.study import Study
    from reportgen.case.load import load_spec
    from reportgen.report.assemble import build_report
    B._init_worker()
    out = []
    for v in B.read_variants(ROOT / "cases/class_six_bar.csv", ROOT / "cases/ws000_six_bar.toml")[:n]:
        spec = load_spec(v.base, v.params)
        study = _computed(Study(spec))
        t = time.process_time()
        build_report(study)
        out.append(time.process_time() - t)
        B._after_variant()
    return out


def case(path: str, runs: int) -> list[float]:
    from reportgen.analysis.study import Study
    from reportgen.core.memory import collect_less
    from reportgen.report.assemble import build_report
    from reportgen.report.parallel import set_note_jobs
    collect_less()
    set_note_jobs(1)
    build_report(_computed(Study(ROOT / path)))       # warm: fonts, caches
    out = []
    for _ in range(runs):
        study = _computed(Study(ROOT / path))
        t = time.process_time()
        build_report(study)
        out.append(time.process_time() - t)
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--variants", type=int, default=0)
    ap.add_argument("--case", default=None)
    ap.add_argument("--runs", type=int, default=5)
    a = ap.parse_args()
    if a.variants:
        ts, what = batch(a.variants), f"batch worker, {a.variants} variants of class_six_bar"
    else:
        ts, what = case(a.case or "cases/ws000_six_bar.toml", a.runs), a.case or "cases/ws000_six_bar.toml"
    print(f"{what}: build_report CPU median {statistics.median(ts):.3f} s "
          f"({' '.join(f'{t:.3f}' for t in ts)}); load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
