"""``reportgen warmup`` compiles every numba kernel a real note uses: after it, building the
analyses of worksheet 000 and worksheet 004 adds no signature to any compiled function (else the
first report after setup would compile it, seconds of CPU on the user's first build)."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

SCRIPT = r"""
import importlib, json, pkgutil, sys
from pathlib import Path
import reportgen.core as core
from numba.core.registry import CPUDispatcher

def signatures():
    out = {}
    for m in pkgutil.iter_modules(core.__path__):
        mod = importlib.import_module(f"reportgen.core.{m.name}")
        for name, obj in vars(mod).items():
            if isinstance(obj, CPUDispatcher):
                out[f"{m.name}.{name}"] = sorted(str(s) for s in obj.signatures)
    return out

from reportgen.warmup import compile_general, warmup
compile_general()
warmup(general=False)
before = signatures()
from reportgen.analysis.study import Study
from reportgen.report.assemble import needs
for case in sys.argv[1:]:
    s = Study(Path(case))
    for name in sorted(needs(s)):  # what the note of the case computes
        got = getattr(s, name)
        if hasattr(got, "tables"):
            got.tables()
print(json.dumps({"before": before, "after": signatures()}))
"""


def test_warmup_compiles_what_the_worksheets_use():
    cases = [str(ROOT / "cases" / c) for c in ("ws000_six_bar.toml", "ws004_slotted_lever.toml", "ws002_tractor_hitch.toml")]
    out = subprocess.run([sys.executable, "-c", SCRIPT, *cases], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-2000:]
    got = json.loads(out.stdout.strip().splitlines()[-1])
    assert got["before"], "no compiled function found"
    new = {k: sorted(set(v) - set(got["before"].get(k, []))) for k, v in got["after"].items()}
    new = {k: v for k, v in new.items() if v}
    assert not new, f"compiled after the warmup: {new}"
