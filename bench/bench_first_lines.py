"""CPU of laying out a note's documents with and without the first lines of text remembered
(reportgen/report/wpsplit.py), alternately in one process.

Usage (from the repository root)::

    python bench/bench_first_lines.py [--case CASE] [--rounds N] [--other CASE]

Every document of the note (as the workers of ``write_pdf`` get it) is laid out, N rounds, three
ways in turn: WeasyPrint's ``split_first_line`` (``off``; main before this change remembered only
the widths of a text that does not wrap, per document), the remembered lines forgotten before the note (``cold``: a note whose texts
this process has not laid out yet) and kept from the round before (``warm``: the same note again).
``--other`` first lays out another case's note, so that the memory is what a batch worker keeps
from a neighbour (``neighbour``). Minimums of the CPU of this process (``time.process_time``) of the
layout per way (each after a full garbage collection), calls answered from memory and measured,
and the written PDFs compared with ``off``'s.
"""
from __future__ import annotations

import contextlib
import gc
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))
os.environ.setdefault("REPORTGEN_JOBS", "1")


def main(argv: list[str]) -> None:
    from bench_pdf_parts import case_args, part_htmls
    a = case_args(argv)

    from reportgen.report import parallel, render, wpsplit

    htmls = [h for _, h in sorted(part_htmls(a.case).items())]
    others = [h for _, h in sorted(part_htmls(a.other).items())] if a.other else []
    config = render._font_config()
    on = wpsplit.first_lines

    def lay_out(way):
        wpsplit.first_lines = contextlib.nullcontext if way == "off" else on
        if way in ("cold", "neighbour"):
            config.__dict__.pop("_reportgen_splits", None)
            for h in others if way == "neighbour" else []:
                parallel._lay_out(h)
        for k in wpsplit.STATS:
            wpsplit.STATS[k] = 0
        gc.collect()  # every way starts without garbage of the one before
        c0 = time.process_time()
        docs = [parallel._lay_out(h) for h in htmls]
        seconds = time.process_time() - c0
        wpsplit.first_lines = on
        return seconds, docs

    ways = ["off", "cold", "warm"] + (["neighbour"] if others else [])
    cpu: dict = {w: [] for w in ways}
    calls: dict = {}
    ref = None
    lay_out("warm")  # warm-up
    for _ in range(a.rounds):
        for way in ways:
            seconds, docs = lay_out(way)
            cpu[way].append(seconds)
            out = [parallel._write(d) for d in docs]
            if way == "off":
                ref = out
            else:
                assert out == ref, f"{way}: other bytes"
                calls[way] = dict(wpsplit.STATS)
    for way in ways:
        print(f"{way:9s} min {min(cpu[way]):.3f} s CPU  ({', '.join(f'{s:.3f}' for s in cpu[way])})"
              + (f"; calls {calls[way]}" if way in calls else ""))
    print(f"documents {len(htmls)}, same bytes; load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main(sys.argv[1:])
