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
