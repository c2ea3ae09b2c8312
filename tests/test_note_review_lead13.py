"""Lead's review of session 13: the degrees-of-freedom section's sentences (ws001_p1_dof)."""
from __future__ import annotations

import copy
from pathlib import Path

import pytest

from reportgen.analysis.study import Study
from reportgen.report.sections import dof

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def study():
    return Study(ROOT / "cases" / "ws001_p1_dof.toml")


def _text(lines) -> str:
    return " ".join(str(x) for x in lines)


def test_dof_conclusion_agrees_the_passive_count_and_rounds_the_right_angle(study):
    text = _text(dof.conclusion_lines(study))
    assert "(в том числе 1\u00a0пассивная)" in text
    assert "90,000°" in text and "90,00000" not in text  # the check's angle to the φ's decimals
    assert "угол MOL" not in text and "угол OML" in text.replace("&nbsp;", " ").replace("\u00a0", " ")
    assert "<i>W</i>" in text or "math-inline" in text  # W set as the body sets symbols


def test_dof_conclusion_passive_count_agrees_with_its_number(study, monkeypatch):
    d = copy.copy(study.dof)
    d.before = dict(d.before, q=2)
    monkeypatch.setattr(type(study), "dof", property(lambda self: d), raising=False)
    assert "(в том числе 2\u00a0пассивные)" in _text(dof.conclusion_lines(study))
    d.before = dict(d.before, q=0)
    assert "в том числе" not in _text(dof.conclusion_lines(study))
