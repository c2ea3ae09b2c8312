"""Session 13, helper review11: a teacher's review of notes on mechanisms no earlier case had
(cases/driving_slot_planer.toml — a driving slotted link with the stone on a crank's pin;
cases/hydraulic_lift_platform.toml — an actuator with a given speed driving a ВВП group;
cases/tangent_lever_pump.toml — a rocker-driven tangent mechanism, group ПВП). Each test fails
without its fix."""
from pathlib import Path

import numpy as np
import pytest

from reportgen import load_case
from test_note_review_n import _load, _notes      # a case by stem; a group's «где» notes as plain text

CASES = Path(__file__).resolve().parents[1] / "cases"


@pytest.fixture(scope="module")
def lift():
    return load_case(CASES / "hydraulic_lift_platform.toml")


def test_actuator_plans_are_constructed(lift):
    """An actuator with a given speed: the velocity and acceleration plans are constructed from the
    rod's drawn relative velocity along the cylinder (the driving pair cylinder–rod, which is not
    among the case's joints) — before, every vector of the plans was zero and the note's build
    stopped with KeyError 'delta' on the empty comparison table."""
    from reportgen.analysis.plans import construct_acceleration, construct_velocity, measured_omegas
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.plans import PlanScene
    mech = lift.mechanism
    for _, row in lift.kinematics.iterrows():
        vrow, vplan = construct_velocity(row, lift, 1e-12)
        om = measured_omegas(vrow, vplan, mech, 1e-12)
        arow, _ = construct_acceleration(row, vrow, om, lift, 1e-12, 1e-12)
        vs = max(abs(row[c]) for c in row.index if c.startswith(("vx_", "vy_")))
        acc = max(abs(row[c]) for c in row.index if c.startswith(("ax_", "ay_")))
        assert vs > 0 and acc > 0
        for c in row.index:
            if c.startswith(("vx_", "vy_")):
                assert abs(vrow[c] - row[c]) < 1e-8 * vs, c
            if c.startswith(("ax_", "ay_")):
                assert abs(arow[c] - row[c]) < 1e-7 * acc, c
    lab = chosen_position(lift)
    for kind in ("velocity", "acceleration"):
        t = PlanScene(lab, kind, landscape=True).draw(lift).table
        assert len(t) > 0 and (t["delta"] < 5.0).all(), t


@pytest.fixture(scope="module")
def planer():
    return _load("driving_slot_planer")


@pytest.fixture(scope="module")
def tangent():
    return _load("tangent_lever_pump")


@pytest.mark.parametrize("name,group", [("driving_slot_planer", 1), ("tangent_lever_pump", 1)])
def test_guide_on_the_input_link_is_given_not_found(name, group, request):
    """The stone slides in a slot of the input link itself (a driving slotted link; a tangent
    lever). The note said «известна (звено 1 рассчитано с группой (1))» — link 1 is the driving
    link, no group gives it — and «a^τ_B1O = ε₁·l_OB — по найденному ε₁: точка b′₁ — по теореме
    подобия», though ε₁ is given (0 at a constant ω₁). Now: «звено 1 — ведущее, его угловая
    скорость задана» and a^τ = ε₁·l = 0 with the reason."""
    study = _load(name)
    vn, an = _notes(study, group)
    text_v, text_a = " ".join(vn), " ".join(an)
    assert "группой (1)" not in text_v and "звено 1 — ведущее, его угловая скорость задана" in text_v, text_v
    assert "по найденному ε1" not in text_a, text_a
    assert "aτB1O = ε1lOB = 0 · " in text_a and "угловая скорость ведущего звена постоянна" in text_a, text_a


def test_guide_found_with_a_group_keeps_its_wording():
    """A slot on a link found with an earlier group (the rocker of rocker_slider_lever) keeps
    «рассчитано с группой» and the similarity theorem for its a^τ."""
    study = _load("rocker_slider_lever")
    vn, an = _notes(study, -1)
    assert any("рассчитано с группой (2,3)" in n for n in vn), vn
    assert any("по теореме подобия" in n for n in an), an



def _tex_value(t: str) -> float:
    """The value of a substituted or result part of a printed formula: «15\\,000 \\cdot 2{,}3505 +
    4914{,}9», «\\frac{1 \\cdot 16 \\cdot 10^{6} …}{2{,}3505}», «40\\,171{,}8\\ \\text{Н}»."""
    import re
    t = re.sub(r"\\ \\text\{[^}]*\}$", "", t.strip()).replace("\\,", "").replace("{,}", ".")
    t = t.replace("\\cdot", "*").replace("^{", "**{")
    t = re.sub(r"\\frac\{(.*)\}\{(.*)\}", r"(\1)/(\2)", t)
    return float(eval(t.replace("{", "(").replace("}", ")"), {}))


def test_capacity_formulas_add_up_with_link_weights(lift):
    """Capacity of an actuator-driven lift whose links have weights: the note printed
    «F = Q·i₄₅ = 15 000 · 2,3505 = 40 171,8 Н» (15 000 · 2,3505 = 35 257,5: the result holds the
    weights' share, the formula does not) and «G₄₅ = k·p·η·A/i₄₅ = … = 28 704 Н» (the numbers give
    30 794), and «(в точке 45 и на оси )» with nothing after «оси». Now F = Q·i + F_ост and
    G = (k·p·η·A − F_ост)/i with F_ост's value, and no empty «на оси»."""
    from reportgen.report.document import FormulaBlock, Paragraph
    from reportgen.report.sections import forces
    from notehelpers import blocks, plain
    sec = forces.build(lift)
    cap = next(b for b in blocks(sec) if isinstance(b, Paragraph) and "грузоподъёмность (" in plain(b.html))
    assert "на оси" not in plain(cap.html), plain(cap.html)
    fb = next(b for b in blocks(sec) if isinstance(b, FormulaBlock)
              and any(f.symbolic.startswith("F = ") for f in b.formulas))
    for f in fb.formulas:
        if f.symbolic.startswith(("F = ", "G_")):      # in Н (p is printed in МПа)
            got, printed = _tex_value(f.substituted), _tex_value(f.result)
            # the printed numbers multiply out to the printed result, to its last digit
            # (15 000 · 2,3505 + 4914,9 = 40 172,4 against the printed 40 171,8 was within 1e-4)
            decimals = len(f.result.split("{,}")[1].split("\\")[0]) if "{,}" in f.result else 0
            assert round(got, decimals) == pytest.approx(printed, abs=1e-9), (f.symbolic, f.substituted, f.result)


def test_no_toggle_remark_for_a_cutting_force_over_the_stroke(planer):
    """A constant cutting force over the working stroke of the planer: the note claimed «эффект
    колена … выигрыш в силе не менее чем в 3,79 раза» (the «gain» was only the 400 mm slotted link
    against the cutter's 105 mm per radian, mid-stroke, far from any dead position). The remark is
    kept for a force near a dead position (knuckle press, jaw crusher)."""
    from reportgen.report.sections import dynamics as D
    assert D.toggle_gain(planer) is None
    assert not any("выигрыш в силе" in str(x) for x in D.conclusion_lines(planer))
    for stem in ("knuckle_press", "jaw_crusher"):
        assert D.toggle_gain(_load(stem)) is not None, stem


def test_actuator_initial_mechanism_equations_hold_the_driving_pair(lift):
    """The actuator-driven lift: §2.4 wrote «Скорости, группа Ассура II класса 1-го вида (2,3) ВВВ:
    V̄₂₃ = V̄₂₃₀₃» — chapter 1 calls (1,2,3) the initial mechanism with the driving pair 1–2, and the
    rod's given speed along the swinging cylinder (and its Coriolis acceleration 2·ω₁·v₂₁) never
    appeared, so the plan's intersection had no second line. Now the initial mechanism is named as
    in chapter 1 and its first equations are V̄_23₂ = V̄_23₁ + V̄_23₂23₁ (v₂₁ given) and
    ā_23₂ = āⁿ + ā^τ + ā^k + ā^r with the Coriolis term's value."""
    from reportgen.analysis.plans import read_velocities
    from reportgen.report.document import Section
    from reportgen.report.sections import vectors
    from reportgen.report.sections.common import chosen_position
    from notehelpers import paragraph_text, plain
    k = lift.kinematics
    row = k[k["pos"] == chosen_position(lift)].iloc[0]
    vrow = read_velocities(row, lift, 0.001)
    sec = Section("x", "x")
    vectors.add_velocities(sec, lift, vrow)
    vectors.add_accelerations(sec, lift, vrow)
    text = " ".join(plain(paragraph_text(sec)).split())
    assert "группа Ассура II класса 1-го вида (2,3)" not in text, text
    assert "начальный механизм (1,2,3) с ведущей поступательной парой 1–2" in text, text
    vn, an = _notes(lift, 1)
    assert vn[0].startswith("V231 — скорость точки цилиндра 1") and "v21 = 0,04 м/с — задана" in vn[0], vn[0]
    w, v = abs(vrow["w_1"]), abs(row["vs_21"])
    assert "кориолисово ускорение (цилиндр вращается)" in an[0], an[0]
    assert "ar232231 = a21 = 0 м/с² (шток выдвигается с постоянной скоростью)" in an[0], an[0]
    from reportgen.style.numbers import fmt
    assert fmt(2 * w * v, sig=4).replace("\u00a0", " ") in an[0].replace("\u00a0", " "), (an[0], 2 * w * v)


def test_plan_reading_names_only_what_it_finds(tangent):
    """The tangent pump: the stone turns with the input lever and the plunger translates, so the
    velocity plan gives only the stone's relative velocity; the note announced «найдены угловые
    скорости звеньев и относительная скорость камня:» above that single formula."""
    from reportgen.report.sections import kinematics
    from notehelpers import paragraph_text, plain
    text = " ".join(plain(paragraph_text(kinematics.build(tangent))).split())
    assert "(рисунок ) найдена относительная скорость камня:" in text, text      # refs resolve at render
    assert "найдены угловые скорости звеньев" not in text


def test_actuator_plans_show_the_driving_pair(lift):
    """The plans of the actuator-driven lift: the rod's relative velocity along the cylinder
    (V̄_23₂23₁, the rod's given speed) and, on the acceleration plan, the Coriolis and relative
    terms of the rod on the swinging cylinder are drawn from the cylinder's point 23₁ — before,
    the plans held only the lever's and the coupler's vectors, so the equation V̄_23₂ = V̄_23₁ +
    V̄_23₂23₁ printed above them had no lines on the drawing."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.plans import PlanScene
    lab = chosen_position(lift)
    v = PlanScene(lab, "velocity", landscape=True).draw(lift).plan
    a = PlanScene(lab, "acceleration", landscape=True).draw(lift).plan
    slide = next(s for s in v.segments if s.kind == "slide")
    assert (slide.start, slide.end) == ("231", "23")
    assert abs(slide.length - float(lift.kinematics.iloc[0]["vs_21"])) < 1e-12
    assert {s.kind for s in a.segments if s.link == "2"} >= {"coriolis", "slide"}


def test_conclusion_calls_a_slot_end_a_point_not_a_joint(planer):
    """The driving slotted link's end K is no joint; the conclusion said «Окружная скорость шарнира K».
    A crank pin that is a joint keeps «шарнира»."""
    from reportgen.report.sections import kinematics
    from notehelpers import plain
    lines = " ".join(plain(x) for x in kinematics.conclusion_lines(planer))
    assert "Окружная скорость точки K" in lines and "шарнира K" not in lines, lines
    crank = " ".join(plain(x) for x in kinematics.conclusion_lines(_load("slider_crank")))
    assert "Окружная скорость шарнира A" in crank, crank


def test_assignment_says_which_link_the_note_calls_the_crank(planer):
    """The planer's input link is «кулиса» in the case and table 1.1 (its link 3 is «кривошип
    BCD»), yet the assignment said «Ведущее звено — кривошип 1» and every chapter «кривошип 1»
    without a word: now the assignment names it and says it serves as the crank. A link titled
    «кривошип» keeps the short sentence."""
    from reportgen.report.assemble import _linkage_data
    from notehelpers import plain
    text = " ".join(plain(getattr(b, "html", "")) for b in _linkage_data(planer))
    assert "Ведущее звено 1 — кулиса; совершая полный оборот, оно служит кривошипом (далее — кривошип 1)" in text, text
    other = " ".join(plain(getattr(b, "html", "")) for b in _linkage_data(_load("slider_crank")))
    assert "Ведущее звено — кривошип 1;" in other, other


@pytest.mark.parametrize("name", ["tangent_lever_pump", "driving_slot_planer"])
def test_stone_turning_with_the_input_link_has_no_columns_of_constants(name):
    """The stone in the input link's own slot turns with it: the note printed a table of φ′₂ =
    1,0000 and one of φ″₂ = 0,0000 in every row (the tangent pump's only angular tables), ω₂ =
    1,500 and ε₂ = 0 columns, and for the pump «…» nothing said why. Now one sentence says it turns
    with link 1 (φ′₂ = 1, φ″₂ = 0, ω₂ = ω₁, ε₂ = ε₁) and no table repeats it; with no other turning
    link, «Остальные звенья движутся поступательно»."""
    from reportgen.report.document import Table
    from reportgen.report.sections import kinematics
    from notehelpers import blocks, paragraph_text, plain
    study = _load(name)
    sec = kinematics.build(study)
    keys = {c.key for b in blocks(sec) if isinstance(b, Table) for c in b.columns}
    assert not keys & {"wq_2", "eq_2", "w_2", "e_2", "phi_2"}, keys
    text = " ".join(plain(paragraph_text(sec)).split())
    assert "Звено 2 (камень) поворачивается вместе с ведущим звеном 1: φ′2 = 1, φ″2 = 0, ω2 = ω1, ε2 = ε1" in text, text
    if name == "tangent_lever_pump":
        assert "Остальные звенья движутся поступательно" in text
        assert not any(isinstance(b, Table) and b.id and b.id.startswith(("tab-wq", "tab-eq")) for b in blocks(sec))
