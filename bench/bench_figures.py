"""How a figure is embedded against WeasyPrint's time: glyph outlines, text as text, PNG.

Usage: python bench/bench_figures.py path|text|png [SECTIONS]  (default: structure,kinematics of ws000)
Prints the time to draw the figures and lay out / write the PDF (the second of two PDFs of the
same report: one layout pass), its CPU time (a figure that holds on a shared machine) and size. Each mode
replaces ``mplstyle.to_svg`` (what every scene calls) for the run only.
"""
from __future__ import annotations

import io
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def main(mode: str, sections: str = "structure,kinematics") -> None:
    import matplotlib

    from reportgen import load_case
    from reportgen.report import render
    from reportgen.report.assemble import build_report
    from reportgen.style import mplstyle

    def serialise(fig):
        for ax in fig.axes:
            mplstyle.localize_axes(ax)
        buf = io.BytesIO()
        if mode == "png":
            fig.savefig(buf, format="png", dpi=200, metadata={"Software": None})
        else:
            with matplotlib.rc_context({"svg.fonttype": "path" if mode == "path" else "none",
                                        "svg.hashsalt": mplstyle.SVG_HASHSALT}):
                fig.savefig(buf, format="svg", metadata={"Date": None})
        return buf.getvalue()

    mplstyle.to_svg = serialise
    study = load_case(ROOT / "cases" / "ws000_six_bar.toml")
    t0 = time.perf_counter()
    report = build_report(study, sections.split(","))
    t_fig = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as d:
        pdf = Path(d) / "r.pdf"
        render.write_pdf(report, pdf)  # finds the split points
        c0 = time.process_time()
        render.write_pdf(report, pdf)  # one pass, as a repeated build
        cpu = time.process_time() - c0
        st = render.last_stats
        size = pdf.stat().st_size
    print(f"{mode}: figures and sections {t_fig:.2f} s, layout {st.seconds_layout:.2f} s "
          f"({st.passes} pass), write {st.seconds_pdf:.2f} s, PDF CPU time {cpu:.2f} s, "
          f"{st.pages} pages, PDF {size // 1024} KB")


if __name__ == "__main__":
    main(*sys.argv[1:])
