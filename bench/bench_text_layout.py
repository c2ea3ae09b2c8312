"""CPU of matplotlib's ``Text._get_layout`` (the box of a text, asked for every tick label,
legend entry and label at each layout pass and draw) with the report style's kept font lookups
(``reportgen.style.fontheights``) and with matplotlib's own, alternated in one process.

Usage: ``python bench/bench_text_layout.py [--rounds R]``. Prints µs per call for each, the
boxes' equality and the machine load (``os.getloadavg``); writes nothing.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=5)
    a = ap.parse_args()
    from matplotlib import text as mtext
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from reportgen.style import mplstyle
    fig = mplstyle.figure(100, 60)
    ax = fig.add_subplot()
    texts = [ax.text(0.1 * i, 0.5, f"{i},5") for i in range(10)]
    FigureCanvasAgg(fig)
    renderer = fig.canvas.get_renderer()
    kept = (mtext.fontManager, mtext.get_font)
    own = (mtext.fontManager._manager, mtext.get_font.__wrapped__)
    res: dict = {"kept": [], "matplotlib": []}
    boxes: dict = {}
    for r in range(a.rounds):
        order = (("kept", kept), ("matplotlib", own)) if r % 2 == 0 else (("matplotlib", own), ("kept", kept))
        for name, state in order:
            mtext.fontManager, mtext.get_font = state
            c = time.process_time()
            for _ in range(300):
                for t in texts:
                    t._get_layout(renderer)
            res[name].append((time.process_time() - c) / (300 * len(texts)) * 1e6)
            boxes[name] = [t._get_layout(renderer)[0].bounds for t in texts]
    mtext.fontManager, mtext.get_font = kept
    for name, ts in res.items():
        print(f"{name}: {statistics.median(ts):.1f} µs per _get_layout ({' '.join(f'{t:.1f}' for t in ts)})")
    print(f"same boxes: {boxes['kept'] == boxes['matplotlib']}; load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
