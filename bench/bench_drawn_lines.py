"""CPU of writing a note's laid-out documents with and without the lines of text remembered
(reportgen/report/wptext.py), alternately in one process.

Usage (from the repository root)::

    python bench/bench_drawn_lines.py [--case CASE] [--rounds N] [--other CASE]

Every document of the note (as the workers of ``write_pdf`` get it) is laid out once; then, N
rounds, the whole set is written three ways in turn: WeasyPrint's ``draw_text`` (``off``), the
remembered lines forgotten before the note (``cold``: a note whose texts this process has not
drawn yet) and kept from the round before (``warm``: the same note again). ``--other`` first
writes another case's note, so that ``cold`` starts from what a batch worker keeps from a
neighbour (``neighbour``). Minimums of the CPU of this process (``time.process_time``) per way (each
after a full garbage collection), lines shaped and replayed, and the bytes compared with ``off``.
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

    from reportgen.report import parallel, render, wptext

    def lay_out(case):
        return [parallel._lay_out(h) for _, h in sorted(part_htmls(case).items())]

    docs = lay_out(a.case)
    others = lay_out(a.other) if a.other else []
    config = render._font_config()
    counts = {"shaped": 0}
    real_shape = wptext._shape

    def counted(*args):
        counts["shaped"] += 1
        return real_shape(*args)

    wptext._shape = counted

    def write(way):
        if way in ("cold", "neighbour"):
            config.__dict__.pop("_reportgen_lines", None)
            with render._fixed_font_timestamp(), parallel_writing(True):
                for d in others if way == "neighbour" else []:
                    d.write_pdf()
        counts["shaped"] = 0
        gc.collect()  # every way starts without garbage of the one before
        c0 = time.process_time()
        with render._fixed_font_timestamp(), parallel_writing(way != "off"):
            out = [d.write_pdf() for d in docs]
        return time.process_time() - c0, out

    @contextlib.contextmanager
    def parallel_writing(on):
        from reportgen.report import wpfast

        with wpfast.cell_borders(), wpfast.text_layouts(), (wptext.drawn_lines() if on else contextlib.nullcontext()):
            yield

    ways = ["off", "cold", "warm"] + (["neighbour"] if others else [])
    cpu = {w: [] for w in ways}
    ref = None
    write("warm")  # warm-up
    for _ in range(a.rounds):
        for way in ways:
            seconds, out = write(way)
            cpu[way].append(seconds)
            if way == "off":
                ref = out
            else:
                assert out == ref, f"{way}: other bytes"
            if way != "off":
                cpu[way + " shaped"] = counts["shaped"]
    for way in ways:
        print(f"{way:9s} min {min(cpu[way]):.3f} s CPU  ({', '.join(f'{s:.3f}' for s in cpu[way])})"
              + (f"; lines shaped {cpu[way + ' shaped']}" if way != "off" else ""))
    print(f"documents {len(docs)}, same bytes; load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main(sys.argv[1:])
