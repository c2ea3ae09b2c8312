"""«Skip what a scene doesn't need», measured: time and computed stages of a note by sections.

Usage: ``.venv/bin/python bench/bench_sections.py [CASE] [--runs 3] [--pdf]``;
``--figures``: instead, the CPU of building each section (its figures, tables and text) of a
Study whose results are computed — *cold*, the first build in a process forked from the one that
computed (as the CLI's section workers: ``report.assemble._build_sections``), and *warm*, the
median of ``--runs`` builds after it in one process; written to ``output/bench/section_cpu.csv``
(default case cases/ws000_six_bar_corrected.toml; also run by ``bench/work_precision.py``);
writes ``output/bench/sections.csv`` and ``sections.md`` (with ``--pdf``: ``sections_pdf.*``) and
prints a table.

For each choice of sections (the CLI's ``--sections``): structure+kinematics; + dynamics;
+ dynamics + forces; every section of the case.  In one warm process (numba kernels compiled,
formula cache filled by a first full build), each run takes a fresh Study and measures

* ``compute`` — only the analysis stages the sections declare in ``NEEDS``
  (``report.assemble.needs``), nothing drawn;
* ``note`` — ``build_report`` (stages, tables, figures, text) plus the HTML file; with ``--pdf``
  also the PDF (WeasyPrint layout, the dominant cost);

as CPU time of the process (``time.process_time``) and wall time; the medians of ``--runs`` runs.
The stages that ran are ``study.computed`` after the note (the test
``tests/test_report_build.py::test_report_computes_only_what_its_sections_need`` asserts them for
structure and structure+kinematics; the benchmark lists them for every choice).
"""
from __future__ import annotations

import argparse
import csv
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
OUT = ROOT / "output" / "bench"
DEFAULT_CASE = "cases/ws000_six_bar_corrected.toml"

CHOICES = [("структура + кинематика", ["structure", "kinematics"]),
           ("+ динамика", ["structure", "kinematics", "dynamics"]),
           ("+ динамика + силовой расчёт", ["structure", "kinematics", "dynamics", "forces"]),
           ("все разделы случая", None)]


def _clock(fn):
    c0, w0 = time.process_time(), time.perf_counter()
    out = fn()
    return time.process_time() - c0, time.perf_counter() - w0, out


def compute_only(case: Path, sections) -> tuple[float, float, list[str]]:
    """Fresh Study; run only the stages the sections need."""
    from reportgen.analysis.study import Study
    from reportgen.registry import BY_NAME
    from reportgen.report.assemble import needs
    study = Study(case)

    def run():
        for name in sorted(needs(study, sections)):
            if name in BY_NAME:
                a = study.analysis(name)
                a.tables()
                a.scalars
            else:
                getattr(study, name)
        return sorted(study.computed)

    c, w, stages = _clock(run)
    return c, w, stages


def note(case: Path, sections, pdf: bool, out: Path) -> tuple[float, float, list[str]]:
    """Fresh Study; the note of the sections (HTML, and PDF if asked)."""
    from reportgen.analysis.study import Study
    from reportgen.report.assemble import build_report
    from reportgen.report.render import build_outputs
    study = Study(case)

    def run():
        build_outputs(build_report(study, sections), out, study.name, ("pdf", "html") if pdf else ("html",))
        return sorted(study.computed)

    return _clock(run)


def rows(case: Path, runs: int, pdf: bool) -> list[dict]:
    out = []
    with tempfile.TemporaryDirectory(prefix="bench-sections-") as tmp:
        tmp = Path(tmp)
        note(case, None, False, tmp)                       # warm-up: kernels, formula cache
        for title, sections in CHOICES:
            comp = [compute_only(case, sections) for _ in range(runs)]
            nt = [note(case, sections, pdf, tmp) for _ in range(runs)]
            r = dict(sections=title, arg=",".join(sections) if sections else "(все)",
                     compute_cpu_s=statistics.median(x[0] for x in comp),
                     compute_wall_s=statistics.median(x[1] for x in comp),
                     note_cpu_s=statistics.median(x[0] for x in nt),
                     note_wall_s=statistics.median(x[1] for x in nt),
                     pdf=pdf, runs=runs, stages=" ".join(nt[-1][2]))
            out.append(r)
            print(f"{title:32s} расчёт {r['compute_cpu_s']:6.2f} с ЦП ({r['compute_wall_s']:6.2f} с)  "
                  f"записка {r['note_cpu_s']:6.2f} с ЦП ({r['note_wall_s']:6.2f} с)  этапы: {r['stages']}",
                  flush=True)
    return out


_STUDY = None  # the study whose sections are built: inherited by the forked process


def _cold(name: str) -> float:
    from reportgen.report.assemble import SECTIONS
    c0 = time.process_time()
    SECTIONS[name][0].build(_STUDY)
    return time.process_time() - c0


def section_cpu(case: Path, runs: int) -> list[dict]:
    """CPU seconds of ``build(study)`` of every section of the case, cold and warm."""
    global _STUDY
    import multiprocessing

    from reportgen.analysis.study import Study
    from reportgen.report.assemble import SECTIONS, _freeze_inherited, chosen_sections, needs
    _STUDY = study = Study(case)
    names = chosen_sections(study, None)
    for need in sorted(needs(study, names)):
        getattr(study, need)
    out = []
    for name in names:
        with multiprocessing.get_context("fork").Pool(1, initializer=_freeze_inherited) as pool:
            cold = pool.apply(_cold, (name,))
        SECTIONS[name][0].build(study)                        # warm-up of this process
        warm = [_cold(name) for _ in range(runs)]
        out.append(dict(case=case.name, section=name, cold_cpu_s=round(cold, 3),
                        warm_cpu_s=round(statistics.median(warm), 3), runs=runs))
        print(f"{name:12s} холодный {cold:6.3f} с ЦП   тёплый (медиана {runs}) {statistics.median(warm):6.3f} с ЦП",
              flush=True)
    return out


def write(rows_: list[dict], path: Path) -> None:
    with path.open("w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(rows_[0]))
        w.writeheader()
        w.writerows(rows_)


def markdown(rows_: list[dict], case: str) -> str:
    base = rows_[0]
    lines = [f"## Разделы записки и вычисленные этапы ({case})", "",
             "| разделы (`--sections`) | этапы расчёта | расчёт, с ЦП | записка, с ЦП | записка / без динамики и сил |",
             "|---|---|---:|---:|---:|"]
    for r in rows_:
        lines.append(f"| {r['sections']} (`{r['arg']}`) | {r['stages']} | {r['compute_cpu_s']:.2f} | "
                     f"{r['note_cpu_s']:.2f} | {r['note_cpu_s'] / base['note_cpu_s']:.1f}× |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> list[dict]:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case", nargs="?", default=DEFAULT_CASE)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--pdf", action="store_true", help="записка с PDF (долго: 10–40 с на сборку)")
    ap.add_argument("--figures", action="store_true",
                    help="время ЦП построения каждого раздела (рисунки, таблицы, текст): холодное и тёплое")
    args = ap.parse_args(argv)
    OUT.mkdir(parents=True, exist_ok=True)
    if args.figures:
        r = section_cpu(ROOT / args.case, args.runs)
        write(r, OUT / "section_cpu.csv")
        return r
    r = rows(ROOT / args.case, args.runs, args.pdf)
    stem = "sections_pdf" if args.pdf else "sections"
    write(r, OUT / f"{stem}.csv")
    (OUT / f"{stem}.md").write_text(markdown(r, args.case), encoding="utf-8")
    return r


if __name__ == "__main__":
    main()
