"""`reportgen --help`, `check` and `export` never load WeasyPrint or matplotlib (nor, for
--help, numba and pandas): each command runs in a fresh interpreter and its sys.modules is read."""
import json
import os
import subprocess
import sys

import pytest

from conftest import CASES, ROOT

PROBE = """
import contextlib, io, json, sys
from reportgen.cli import main
with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
    try:
        rc = main(sys.argv[1:])
    except SystemExit as e:
        rc = e.code
heavy = ("weasyprint", "matplotlib", "numba", "pandas", "scipy", "jinja2", "ziamath")
print(json.dumps({"rc": rc, "loaded": [m for m in heavy if m in sys.modules]}))
"""


def _loaded(args: list[str]) -> tuple[int, set[str]]:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    out = subprocess.run([sys.executable, "-c", PROBE, *args], cwd=ROOT, env=env,
                         capture_output=True, text=True, check=True).stdout
    data = json.loads(out.strip().splitlines()[-1])
    return data["rc"], set(data["loaded"])


def test_help_imports_nothing_heavy():
    rc, loaded = _loaded(["--help"])
    assert rc == 0
    assert loaded == set()


@pytest.mark.parametrize("cmd", ["check", "export"])
def test_check_and_export_do_not_load_the_report_stack(cmd, tmp_path):
    args = [cmd, str(CASES / "ws004_slotted_lever.toml")]
    if cmd == "export":
        args += ["-o", str(tmp_path)]
    rc, loaded = _loaded(args)
    assert rc == 0
    assert not loaded & {"weasyprint", "matplotlib", "jinja2", "ziamath"}, loaded
    if cmd == "export":
        assert (tmp_path / "scalars.json").exists()
