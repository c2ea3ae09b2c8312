"""What the text shortcuts of reportgen/report/wpfast.py save on ws000's parts: calls and CPU per call.

Usage (from the repository root)::

    python bench/bench_wpfast.py [--case CASE] [--loops N]

The parts are laid out and written as the workers of ``write_pdf`` get them (their print HTML with
the split points known: the second write in one process). Counted over all parts: the calls of
``Layout.setup`` (a Pango layout for every piece of text laid out or drawn) and of the inline
layout's ``strut``, and the distinct styles they see. Then, on every style seen, WeasyPrint's own
routine and the shortcut (``wpfast.text_layouts``, ``wpfast.line_struts``) are each called N times
in a loop (CPU of this process, ``time.process_time``): the CPU per call of each, weighted by how
often the parts meet each style, times the calls gives the CPU saved per note. Per-call figures
in a loop are much steadier than whole-part timings on a shared machine; the whole-part effect is
measured by ``bench/bench_pdf_parts.py``. Last, the parts are written again without the shortcuts
and the PDFs compared byte for byte.
"""
from __future__ import annotations

import argparse
import collections
import contextlib
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def _write_all(htmls) -> dict[int, bytes]:
    from reportgen.report import parallel, render

    out = {}
    for i, html in sorted(htmls.items()):
        with render._fixed_font_timestamp():
            out[i] = parallel._write(parallel._lay_out(html))
    return out


def _per_call(fn, styles: list, loops: int) -> float:
    """CPU seconds per call of ``fn(style)``, each style (of the pairs (style, calls)) weighted
    by how often the parts met it."""
    total = 0.0
    for style, count in styles:
        c0 = time.process_time()
        for _ in range(loops):
            fn(style)
        total += (time.process_time() - c0) / loops * count
    return total / sum(count for _, count in styles)


def main(argv: list[str]) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", default="cases/ws000_six_bar.toml")
    ap.add_argument("--loops", type=int, default=200)
    a = ap.parse_args(argv)

    from weasyprint.layout import inline
    from weasyprint.text.line_break import Layout

    from reportgen.report import wpfast

    from bench_pdf_parts import part_htmls

    htmls = part_htmls(a.case)
    setups: collections.Counter = collections.Counter()
    struts: collections.Counter = collections.Counter()
    by_id: dict = {}
    real_setup, real_struts = wpfast._layout_setup, wpfast._struts

    def spy_setup(general):
        fast = real_setup(general)

        def setup(self, style):
            setups[id(style)] += 1
            by_id[id(style)] = style
            return fast(self, style)
        return setup

    def spy_struts(general):
        fast = real_struts(general)

        def strut(style):
            struts[id(style)] += 1
            by_id[id(style)] = style
            return fast(style)
        return strut

    wpfast._layout_setup, wpfast._struts = spy_setup, spy_struts
    try:
        fast_pdfs = _write_all(htmls)
    finally:
        wpfast._layout_setup, wpfast._struts = real_setup, real_struts
    setup_styles = [(by_id[k], v) for k, v in setups.items()]
    strut_styles = [(by_id[k], v) for k, v in struts.items()]

    general_setup, general_strut = Layout.setup, inline.strut
    layout = Layout.__new__(Layout)
    fast_setup, fast_strut = real_setup(general_setup), real_struts(general_strut)
    rows = [("Layout.setup", setups, setup_styles, lambda s: general_setup(layout, s), lambda s: fast_setup(layout, s)),
            ("strut (inline layout)", struts, strut_styles, general_strut, fast_strut)]
    print(f"{a.case}: {len(htmls)} documents")
    for name, calls, styles, general, fast in rows:
        _per_call(fast, styles, 1)  # the shortcut's memory filled, as after the first call in a part
        g, f = _per_call(general, styles, a.loops), _per_call(fast, styles, a.loops)
        n = sum(calls.values())
        print(f"  {name}: {n} calls, {len(styles)} styles; WeasyPrint {g * 1e6:.2f} µs/call, shortcut "
              f"{f * 1e6:.2f} µs/call; saved {n * (g - f):.3f} s CPU per note")

    stack = contextlib.ExitStack()
    for name in ("text_layouts", "line_struts"):
        stack.enter_context(_without(wpfast, name))
    with stack:
        plain = _write_all(htmls)
    print("same PDF bytes without the shortcuts: " + ", ".join(f"{i}: {plain[i] == fast_pdfs[i]}" for i in sorted(plain)))
    print(f"load {os.getloadavg()}")


@contextlib.contextmanager
def _without(module, name):
    real = getattr(module, name)
    setattr(module, name, contextlib.nullcontext)
    try:
        yield
    finally:
        setattr(module, name, real)


if __name__ == "__main__":
    main(sys.argv[1:])
