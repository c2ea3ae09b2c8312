"""Every LaTeX string the notes of cases/ typeset, for tests/test_mathhtml.py.

Usage: python tests/formula_corpus.py [CASE …]  → tests/data/formulas_of_cases.json

Builds the note of each case (sections and the screen HTML, no PDF) in one process and records
what reaches :func:`reportgen.report.formulas._math` (display lines and inline math) with the
cases that use it. Run it again when a section writes new formulas; the test then checks that
the HTML typesetter handles all of them without the ziamath fallback.
"""
from __future__ import annotations

import glob
import json
import os
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "tests" / "data" / "formulas_of_cases.json"


def main(argv: list[str]) -> None:
    os.environ["REPORTGEN_JOBS"] = "1"  # sections in this process, so that the hook sees them
    sys.path.insert(0, str(ROOT))
    from reportgen.analysis.study import Study
    from reportgen.errors import CaseError
    from reportgen.report import formulas, render
    from reportgen.report.assemble import build_report

    seen: dict[tuple[str, bool], set[str]] = {}
    current = [""]
    original = formulas._math

    def record(tex: str, inline: bool = False):
        seen.setdefault((tex, inline), set()).add(current[0])
        return original(tex, inline)

    formulas._math = record
    cases = argv or sorted(glob.glob(str(ROOT / "cases" / "*.toml")))
    for case in cases:
        current[0] = Path(case).stem
        try:
            study = Study(Path(case))
            report = build_report(study)
        except CaseError:  # a base for batch variants, not a case of its own
            continue
        with tempfile.TemporaryDirectory() as d:
            render.write_html(report, Path(d) / "note.html")
        print(f"{current[0]}: {len(seen)}", file=sys.stderr)
    rows = [{"tex": tex, "inline": inline, "cases": sorted(c)} for (tex, inline), c in sorted(seen.items())]
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps(rows, ensure_ascii=False, indent=0) + "\n", encoding="utf-8")
    print(f"{len(rows)} формул: {OUT}")


if __name__ == "__main__":
    main(sys.argv[1:])
