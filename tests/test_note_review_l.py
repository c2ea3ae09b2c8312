"""Linkage notes reviewed as a ТММ teacher grades them, on mechanisms new to cases/ (issue 9,
session 11, helper review6): a power hacksaw (saw frame — a heavy translating link whose centre of
mass and blade lie off its guide), a six-bar whose slider moves along a rocking link (ВВП with a
moving guide: Coriolis term), a coupler-driven six-bar. Each test fails without its fix."""
from pathlib import Path

import numpy as np
import pytest

CASES = Path(__file__).resolve().parents[1] / "cases"


@pytest.fixture(scope="module")
def hacksaw():
    from reportgen import load_case
    return load_case(CASES / "power_hacksaw.toml")


@pytest.fixture(scope="module")
def ws000():
    from reportgen import load_case
    return load_case(CASES / "ws000_six_bar.toml")


def _texts(fig) -> list[str]:
    return [t.get_text() for ax in fig.axes for t in ax.texts if t.get_visible() and t.get_text().strip()]


@pytest.mark.parametrize("case", ["hacksaw", "ws000"])
def test_uniform_crank_has_no_tangential_stub(case, request):
    """The crank turns uniformly (ε₁ = 0, «a^τ_AO = ε₁·l_OA = 0» in the text): the acceleration
    plan draws the crank pin's acceleration as the laid-off aⁿ_AO alone. It drew a stub
    a^τ_AO of 0,15 mm (the rounding of aⁿ_AO) and circled it in an enlarged view."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.plans import PlanScene, _drawn_segments
    study = request.getfixturevalue(case)
    d = PlanScene(chosen_position(study), "acceleration", landscape=True).draw(study)
    crank = study.mechanism.driver.link
    names = [s.name for s, a, b in _drawn_segments(d.plan, d.mu) if s.kind == "tangential" and s.link == crank]
    assert not names, names
    assert not any(n.startswith("a^τ_A") for ins in d.insets for n in ins.segments)


@pytest.mark.parametrize("kind", ["velocity", "acceleration"])
def test_translating_link_points_share_one_label(hacksaw, captured, kind):
    """The images of the saw frame's points B, S₃, T coincide (the frame translates): one label
    «b, s₃, t» at the point, as a student writes it, and no enlarged view (×5 could not part
    them: the view showed three labels piled on one point)."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.plans import PlanScene
    d = PlanScene(chosen_position(hacksaw), kind, landscape=True).draw(hacksaw)
    assert not d.insets, [i.tips for i in d.insets]
    prime = "′" if kind == "acceleration" else ""
    joint = [t for t in _texts(captured[-1]) if f"b{prime}$" in t and "s" in t and f"t{prime}$" in t]
    assert joint == [f"$b{prime}$, $s{prime}_{{3}}$, $t{prime}$"], _texts(captured[-1])


def test_lever_translating_link_one_label(hacksaw, captured):
    """Жуковский's lever of the hacksaw: b, s₃, t labelled once, no enlarged view around them."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import ZhukovskyLever
    lv = ZhukovskyLever(chosen_position(hacksaw), landscape=True).draw(hacksaw)
    assert not lv.insets, [i.tips for i in lv.insets]
    assert "$b$, $s_{3}$, $t$" in _texts(captured[-1])
