"""The CLI and the batch workers collect cyclic garbage less often (core.memory.collect_less)."""
from __future__ import annotations

import gc
import subprocess
import sys

from reportgen.core.memory import GC_THRESHOLD, collect_less


def test_cli_sets_the_threshold():
    code = ("import gc\n"
            "from reportgen.cli import main\n"
            "main(['check', '/nonexistent.toml'])\n"   # an error (exit code 2) after the setting
            "print(gc.get_threshold()[0])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.strip().splitlines()[-1] == str(GC_THRESHOLD[0])


def test_never_lowers_a_raised_threshold():
    old = gc.get_threshold()
    try:
        gc.set_threshold(10 * GC_THRESHOLD[0], 5, 5)
        collect_less()
        assert gc.get_threshold() == (10 * GC_THRESHOLD[0], 5, 5)
        gc.set_threshold(700, 10, 10)
        collect_less()
        assert gc.get_threshold() == GC_THRESHOLD
    finally:
        gc.set_threshold(*old)
