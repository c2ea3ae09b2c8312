"""Keep freed heap memory in the process (glibc only).

glibc's malloc serves a block larger than its mmap threshold (128 KiB at start, raised
dynamically up to 32 MiB) by a fresh ``mmap`` and returns freed memory at the top of the heap
to the system above its trim threshold, so the arrays of a whole-grid kernel (a few hundred KiB
to a few MiB each: positions, analogs, points over 3 600 positions) are new pages at nearly
every call and every page is zeroed by the kernel on its first touch.  On this project's
machine that costs more than the arithmetic (ws000: ``linkage.solve`` over the cycle grid
2,4 ms with fresh pages against 1,0 ms with the pages kept; ``bench/bench_analysis.py``).
``mallopt(M_MMAP_THRESHOLD, 64 MiB)`` and ``mallopt(M_TRIM_THRESHOLD, 128 MiB)`` (glibc
``mallopt(3)``; the same as the environment variables ``MALLOC_MMAP_THRESHOLD_`` and
``MALLOC_TRIM_THRESHOLD_``) make such blocks come from the heap and stay there when freed;
the process keeps at most 128 MiB of free heap.  Nothing happens outside glibc or when the
user has set either variable.
"""
from __future__ import annotations

import ctypes
import os
import sys

M_TRIM_THRESHOLD = -1
M_MMAP_THRESHOLD = -3
MMAP_THRESHOLD = 64 << 20
TRIM_THRESHOLD = 128 << 20


def keep_freed_memory() -> bool:
    """Set the two glibc thresholds; returns whether they were set."""
    if not sys.platform.startswith("linux") or "MALLOC_MMAP_THRESHOLD_" in os.environ \
            or "MALLOC_TRIM_THRESHOLD_" in os.environ:
        return False
    try:
        mallopt = ctypes.CDLL(None).mallopt       # the process's own C library
    except (OSError, AttributeError):
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    return bool(mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and bool(mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD))


GC_THRESHOLD = (20_000, 10, 10)


def collect_less() -> None:
    """Run Python's cyclic garbage collector every 20 000 net allocations of tracked objects
    instead of 700 (``gc.set_threshold``; the older generations keep their ratios 10 and 10).

    A note is built from millions of short-lived objects (matplotlib artists, WeasyPrint boxes,
    DataFrames) of which almost none form cycles worth collecting early. ws000, ``python
    bench/bench_gc.py --runs 3`` (alternated, medians, load 0,2): with the default threshold the
    parent ran 562 young, 51 middle and 4 full collections (0,38 s) and the build took 15,98 s of
    CPU (process and workers); with this one 24, 2 and 0 collections (0,17 s) and 14,51 s. The
    forked workers inherit the setting. Never
    lowers a threshold the user has raised."""
    import gc

    if gc.get_threshold()[0] < GC_THRESHOLD[0]:
        gc.set_threshold(*GC_THRESHOLD)


def freeze_warm_state() -> int:
    """Collect once, then leave every object alive now out of all later collections
    (``gc.freeze``, Python ≥ 3.7); returns how many were frozen.

    For a process that is warmed up once and then does the same job many times (a batch
    worker: imported modules, numba dispatchers, fonts, compiled templates, some 230 000
    objects). Each job ends with one full collection (its WeasyPrint documents are held by
    reference cycles), which would otherwise walk the whole warm state again. Frozen objects
    are never freed by the collector even when they become cyclic garbage, so only state
    that lives as long as the process should be alive here; what a job keeps afterwards
    (caches) stays visible to the collector. While objects are frozen,
    ``render._older_objects_frozen`` leaves them as they are."""
    import gc

    gc.collect()
    gc.freeze()
    return gc.get_freeze_count()
