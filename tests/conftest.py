import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"
os.environ.setdefault("CI", "true")


@pytest.fixture(scope="session")
def ws000():
    from reportgen import load_case
    return load_case(CASES / "ws000_six_bar.toml")


@pytest.fixture(scope="session")
def ws002():
    from reportgen import load_case
    return load_case(CASES / "ws002_tractor_hitch.toml")


@pytest.fixture(scope="session")
def ws004():
    from reportgen import load_case
    return load_case(CASES / "ws004_slotted_lever.toml")
