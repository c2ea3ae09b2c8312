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


@pytest.fixture(scope="module")
def rocker_slider():
    from reportgen import load_case
    return load_case(CASES / "rocker_slider_lever.toml")


def _group_notes(study, links):
    import re
    from reportgen.analysis.plans import read_velocities
    from reportgen.report.sections import vectors
    from reportgen.report.sections.common import chosen_position
    k = study.kinematics
    row = k[k["pos"] == chosen_position(study)].iloc[0]
    vrow = read_velocities(row, study, 0.01)
    g = next(g for g in study.structure.groups if tuple(g.links) == links)
    vf, vn, af, an = vectors.group_equations(study, vrow, g)
    plain = lambda xs: [re.sub("<[^>]+>", "", str(x)) for x in xs]  # noqa: E731
    return [f.symbolic for f in vf], plain(vn), [f.symbolic for f in af], plain(an), vrow


def test_slider_on_rocker_guide_known_from_earlier_group(rocker_slider):
    """ВВП group (4,5) whose slider moves along the rocker 3 of the four-bar solved before it: the
    velocity of the rocker's point under the slider is known (ω₃·l_CE about the rocker's fixed
    pivot C, with numbers), only V_E5E3 is found by the construction. It was written
    V̄_E3 = V̄_B + V̄_E3B «— величины находятся построением», as if ω₃ were unknown."""
    vf, vn, af, an, vrow = _group_notes(rocker_slider, ("4", "5"))
    note = next(n for n in vn if "совпадающей" in n)
    assert "величины находятся построением" not in note, note
    assert "известна" in note and "рассчитано с группой (2,3)" in note, note
    l_ce = np.hypot(vrow["x_E"] - vrow["x_C"], vrow["y_E"] - vrow["y_C"])
    from reportgen.style.numbers import fmt
    assert fmt(abs(vrow["w_3"]) * l_ce, sig=4) in note, note
    acc = next(n for n in an if "под ползуном" in n)
    assert "E3C" in acc and "E3B" not in acc and "теореме подобия" in acc, acc
    assert any(r"\bar{a}^{k}_{E_{5}E_{3}}" in f for f in af), af


def test_low_angle_advice_for_slider_on_moving_guide(rocker_slider):
    """μ_min = 33,6° in the ВВП group (4,5) whose slider runs on the rocker: the advice spoke of
    «удлинив шатун группы … шатун ближе к перпендикуляру к выходному звену» — the group has no
    шатун, and μ of a slider dyad is largest where the link hinged to the slider lies ALONG the
    guide (μ = 90° − the angle between DE and the guide, checked over the cycle here)."""
    from reportgen.report.sections.kinematics import conclusion_lines
    cyc = rocker_slider.cycle
    between = np.degrees(np.abs(cyc["phi_4"] - cyc["phi_3"])) % 180
    between = np.minimum(between, 180 - between)
    assert np.allclose(np.degrees(cyc["mu_4_5"]), 90 - between, atol=1e-6)
    line = next(x for x in conclusion_lines(rocker_slider) if "группе (4,5)" in x and "меньше допускаемого" in x)
    assert "шатун" not in line, line
    assert "звено 4 было ближе к направлению направляющей звена 3" in line and "его опоры" in line, line


@pytest.mark.parametrize("case, same", [("power_hacksaw", {"S3", "T"}), ("yoke_pump", {"S3", "P"})])
def test_translating_link_not_repeated_in_motion_tables(case, same):
    """The saw frame (and the pump's yoke) translates: V, a of B, S₃, T are one value; the analog,
    velocity and acceleration tables printed three identical columns (x′_B = x′_S3 = x′_T, tables
    2.6–2.8, 3.9–3.10). Now one point per translating link and a sentence saying why."""
    from reportgen import load_case
    from reportgen.report.sections.kinematics import build
    from notehelpers import blocks
    from reportgen.report.document import Paragraph, Table
    study = load_case(CASES / f"{case}.toml")
    sec = build(study)
    heads = {c.key for b in blocks(sec) if isinstance(b, Table) for c in b.columns}
    assert not {f"{k}_{p}" for k in ("vqx", "v", "a") for p in same} & heads
    text = " ".join(b.html for b in blocks(sec) if isinstance(b, Paragraph))
    assert "движется поступательно: скорости и ускорения всех его точек равны" in text
