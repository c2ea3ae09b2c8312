"""build_report CPU per batch variant with and without ``style.mplreuse`` in one process: a batch
worker (``batch._init_worker``) builds variants 02… of ``cases/class_six_bar.csv`` (after 01 as a
warm-up both ways), each once with the reuse and once with matplotlib's own methods
(``mplreuse.unshared``), the order alternating; ``time.process_time`` around ``build_report``.

Usage: ``python bench/bench_mplreuse.py [N] [GROUP...]`` (N variants, default 6; GROUP: only those
reuses switched off, e.g. ``layouts legends`` — see ``mplreuse.unshared``). Prints seconds per
variant, the medians, the ratio of the sums and the load; writes nothing.
"""
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from reportgen import batch as B  # noqa: E402
from reportgen.analysis.study import Study  # noqa: E402
from reportgen.case.load import load_spec  # noqa: E402
from reportgen.report import assemble  # noqa: E402
from reportgen.style import mplreuse  # noqa: E402


def run(v) -> float:
    spec = load_spec(v.base, v.params)
    spec.meta_overrides = dict(v.meta)
    study = Study(spec)
    for need in sorted(assemble.needs(study)):
        getattr(study, need)
    c = time.process_time()
    assemble.build_report(study)
    t = time.process_time() - c
    B._after_variant()
    return t


def main() -> None:
    B._init_worker()
    variants = B.read_variants(ROOT / "cases/class_six_bar.csv", ROOT / "cases/ws000_six_bar.toml")
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 6
    groups = sys.argv[2:]
    run(variants[0])
    with mplreuse.unshared(*groups):
        run(variants[0])
    on, off = [], []
    for i, v in enumerate(variants[1:1 + n]):
        if i % 2:
            on.append(run(v))
            with mplreuse.unshared(*groups):
                off.append(run(v))
        else:
            with mplreuse.unshared(*groups):
                off.append(run(v))
            on.append(run(v))
    print("без  ", " ".join(f"{t:.3f}" for t in off), "медиана %.3f" % statistics.median(off))
    print("с    ", " ".join(f"{t:.3f}" for t in on), "медиана %.3f" % statistics.median(on))
    print("отношение сумм %.3f, load %.2f" % (sum(on) / sum(off), os.getloadavg()[0]))


if __name__ == "__main__":
    main()
