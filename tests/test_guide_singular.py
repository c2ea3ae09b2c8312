"""A slider on a rotating guide (ВПВ, кулиса) whose pin passes through the guide's pivot: the
guide's angular velocity analog is unbounded there; `check` and the note say so (issue: a
stretched Whitworth 1e-8 from its limit gave ω′ = 2·10⁷ without a warning)."""
from pathlib import Path

from reportgen.case.load import load_spec
from reportgen.analysis.study import Study
from reportgen.cli import main

CASES = Path(__file__).resolve().parents[1] / "cases"


def _whitworth(tmp_path, l1: str) -> Path:
    text = (CASES / "whitworth.toml").read_text(encoding="utf-8").replace('l_1 = "0.2 m"', f'l_1 = "{l1}"')
    p = tmp_path / "w.toml"
    p.write_text(text, encoding="utf-8")
    return p


def test_regular_guide_not_flagged():
    s = Study(load_spec(CASES / "whitworth.toml"))
    (fl,) = s.guide_flags.values()
    assert fl["points"] == ("C", "A") and abs(fl["min"] - 0.1) < 1e-12 and not fl["singular"]


def test_pin_through_the_pivot_is_reported(tmp_path, capsys):
    path = _whitworth(tmp_path, "0.10000001 m")
    s = Study(load_spec(path))
    (fl,) = s.guide_flags.values()
    assert fl["singular"] and fl["min"] < 1e-7
    assert abs(s.cycle["wq_3"]).max() > 1e6          # the analog is indeed unbounded there
    assert main(["check", str(path)]) == 0
    err = capsys.readouterr().err
    assert "особое положение" in err and "оси кулисы C" in err.replace("ось кулисы C", "оси кулисы C")
    from reportgen.report.sections.kinematics import conclusion_lines
    assert any("особое положение" in line for line in conclusion_lines(s))
