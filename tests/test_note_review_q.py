"""Session 13, helper review11: a teacher's review of notes on mechanisms no earlier case had
(cases/driving_slot_planer.toml — a driving slotted link with the stone on a crank's pin;
cases/hydraulic_lift_platform.toml — an actuator with a given speed driving a ВВП group;
cases/tangent_lever_pump.toml — a rocker-driven tangent mechanism, group ПВП). Each test fails
without its fix."""
from pathlib import Path

import numpy as np
import pytest

from reportgen import load_case

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


def _load(name):
    return load_case(CASES / f"{name}.toml")


@pytest.fixture(scope="module")
def planer():
    return _load("driving_slot_planer")


@pytest.fixture(scope="module")
def tangent():
    return _load("tangent_lever_pump")


def _notes(study, group_index=-1):
    """The «где» explanations of a group's velocity and acceleration equations as plain text."""
    import re
    from reportgen.analysis.plans import read_velocities
    from reportgen.report.sections import vectors
    from reportgen.report.sections.common import chosen_position
    k = study.kinematics
    row = k[k["pos"] == chosen_position(study)].iloc[0]
    vrow = read_velocities(row, study, 0.01)
    vf, vn, af, an = vectors.group_equations(study, vrow, study.structure.groups[group_index])
    plain = lambda xs: [" ".join(re.sub(r"<[^>]+>", "", str(x)).split()) for x in xs]
    return plain(vn), plain(an)


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
