"""CPU of WeasyPrint laying out and writing ws000's heavy parts with and without one CSS rule.

Usage (from the repository root)::

    python bench/bench_part_css.py [REPEAT] [CSS]

The parts kinematics, dynamics and forces are taken as the workers of ``write_pdf`` get them
(their print HTML with the split points known: the second write in one process). Each is laid
out and written (``parallel._lay_out`` and ``parallel._write``) as it is and with ``CSS``
appended to the note's stylesheet (default: ``table.tbl { font-variant-numeric: tabular-nums; }``,
the rule gost.css had before session 9): part by part, REPEAT rounds after one warm-up round, the
two variants in a shuffled order in each round (fixed seed). Printed: the CPU seconds of this
process (``time.process_time``: the machine may be shared), minimum and median per part and their
sums, and whether the two PDFs of each part are the same bytes.
"""
from __future__ import annotations

import os
import random
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

RULE = "table.tbl { font-variant-numeric: tabular-nums; }"


def main(argv: list[str]) -> None:
    from bench_pdf_parts import part_htmls

    from reportgen.report import parallel, render

    n = int(argv[0]) if argv else 5
    rule = argv[1] if len(argv) > 1 else RULE
    htmls = part_htmls("cases/ws000_six_bar.toml")
    heavy = sorted(htmls, key=lambda i: -htmls[i].count("<td"))[:3]
    variants = {"as is": {i: htmls[i] for i in heavy}, "with the rule": {}}
    for i in heavy:
        html = htmls[i].replace("</style>\n</head>", rule + "</style>\n</head>", 1)
        assert html != htmls[i], "the stylesheet was not found"
        variants["with the rule"][i] = html
    cpu: dict = {}
    pdfs: dict = {}
    order = random.Random(1)
    for i in heavy:  # a part's rounds together (the machine's load drifts), the two in a shuffled order
        for r in range(n + 1):
            names = list(variants)
            order.shuffle(names)
            for name in names:
                c0 = time.process_time()
                with render._fixed_font_timestamp():
                    pdfs[name, i] = parallel._write(parallel._lay_out(variants[name][i]))
                if r:  # the first round warms up
                    cpu.setdefault((name, i), []).append(time.process_time() - c0)
    print(f"parts {heavy} of ws000 (cells {[htmls[i].count('<td') for i in heavy]}); rule: {rule}")
    for name in variants:
        per = [cpu[name, i] for i in heavy]
        print(f"{name:>14}: sum of the parts' minimums {sum(min(v) for v in per):.3f} s CPU, of medians "
              f"{sum(statistics.median(v) for v in per):.3f}; per part min/median "
              + ", ".join(f"{min(v):.3f}/{statistics.median(v):.3f}" for v in per))
    print("same PDF bytes: " + ", ".join(f"part {i}: {pdfs['as is', i] == pdfs['with the rule', i]}" for i in heavy))
    print(f"load {os.getloadavg()}")


if __name__ == "__main__":
    main(sys.argv[1:])
