"""CPU of joining ws000's parts (``parallel.join``, pypdf), from the bytes and after
``parallel.prepare`` parsed each part (as ``PartsJob`` does while a worker still lays out another).

Usage (from the repository root)::

    python bench/bench_join.py [REPEAT] [CASE]

The parts are those of a second ``write_pdf`` in 2 processes (split points known). For each of
REPEAT rounds: the join from the bytes, then ``prepare`` of every part and the join after it
(``time.process_time`` of this process); the joined bytes must be the same. Minimum and median
of each, with the load average.
"""
from __future__ import annotations

import os
import pickle
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def main(argv: list[str]) -> None:
    from reportgen.analysis.study import Study
    from reportgen.report import parallel, render
    from reportgen.report.assemble import build_report

    n = int(argv[0]) if argv else 5
    case = argv[1] if len(argv) > 1 else "cases/ws000_six_bar.toml"
    report = build_report(Study(ROOT / case))
    seen = {}
    original = parallel.join

    def keep(parts, numbers, first_numbered, readers=None):
        seen["args"] = pickle.dumps((parts, numbers, first_numbered))
        return original(parts, numbers, first_numbered, readers)

    parallel.join = keep
    try:
        with tempfile.TemporaryDirectory() as d:
            for _ in range(2):  # the second with the split points known
                render.write_pdf(report, Path(d) / "note.pdf", jobs=2)
    finally:
        parallel.join = original
    fresh, prepared, joined = [], [], []
    for _ in range(n):
        parts, numbers, first = pickle.loads(seen["args"])
        c0 = time.process_time()
        a = parallel.join(parts, numbers, first)
        fresh.append(time.process_time() - c0)
        parts, numbers, first = pickle.loads(seen["args"])
        c0 = time.process_time()
        readers = {id(p): (p, parallel.prepare(p)) for p in parts}
        c1 = time.process_time()
        b = parallel.join(parts, numbers, first, readers=readers)
        prepared.append(c1 - c0)
        joined.append(time.process_time() - c1)
        assert a == b, "the joined bytes differ"

    def fmt(v):
        return f"min {min(v):.3f}, median {statistics.median(v):.3f}"

    print(f"{case}: {len(parts)} documents, {len(a)} bytes joined")
    print(f"join from the bytes: {fmt(fresh)} s CPU")
    print(f"prepare (every part): {fmt(prepared)} s CPU; join after it: {fmt(joined)} s CPU")
    print(f"load {os.getloadavg()}")


if __name__ == "__main__":
    main(sys.argv[1:])
