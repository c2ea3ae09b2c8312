"""The gear and train cases through the command line in-process: check and export work on a
gears-only and a train-only case; the worksheet 001 answers; the mesh drawing's tip circles cut
the line of action where ε_α says; bad input gives one Russian message."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from reportgen import load_case
from reportgen.cli import main

CASES = Path(__file__).resolve().parents[1] / "cases"


@pytest.mark.parametrize("case", ["ws001_gear_2013_4", "ws001_train_2013_5", "gear_pair_shifted", "gear_pair_internal",
                                  "train_2kh_three_planets"])
def test_check_and_export(case, tmp_path, capsys):
    assert main(["check", str(CASES / f"{case}.toml")]) == 0
    assert main(["export", str(CASES / f"{case}.toml"), "-o", str(tmp_path)]) == 0
    sc = json.loads((tmp_path / "scalars.json").read_text(encoding="utf-8"))
    assert all(np.isfinite(v) for v in sc.values() if isinstance(v, float))
    assert list(tmp_path.glob("*.csv"))


def test_worksheet_values_through_the_case():
    g = load_case(CASES / "ws001_gear_2013_4.toml").gears.scalars
    assert g["gears_d_y"] == pytest.approx(402.2075, abs=5e-5)
    assert round(g["gears_x_chord"], 2) == 0.43 and round(g["gears_s_chord"], 2) == 18.83
    t = load_case(CASES / "ws001_train_2013_5.toml").train
    assert (t.ratio_fraction.numerator, t.ratio_fraction.denominator) == (731, 11)
    assert t.scalars["train_u_discrepancy_pct"] < 1e-9
    s = load_case(CASES / "train_2kh_three_planets.toml").train
    assert {w.name: w.z for w in s.model.wheels.values()} == {"1": 17, "2": 34, "3": 85}


def test_mesh_drawing_tip_circles_on_line_of_action():
    from reportgen.scenes.gears import mesh_drawing
    gr = load_case(CASES / "gear_pair_shifted.toml").gears
    md = mesh_drawing(gr)
    g = gr.geo
    # the drawn tip circles (polygons) cut N₁N₂ at ρ = ρ_p1 and ρ_a1 from N₁
    B1, B2 = np.array(md.B1), np.array(md.B2)
    assert np.hypot(*(B2 - B1)) / float(g.pb) == pytest.approx(float(g.eps), rel=2e-4)
    assert abs(md.eps_graph - float(g.eps)) / float(g.eps) < 0.02


def test_bad_input_russian_message(tmp_path, capsys):
    p = tmp_path / "bad.toml"
    p.write_text('[gears]\nmodule = "5 mm"\nz1 = 12\nz2 = 30\nx1 = "choose"\nx2 = "choose"\neps_min = 3\n',
                 encoding="utf-8")
    assert main(["check", str(p)]) == 2
    err = capsys.readouterr().err
    assert "блокирующий контур пуст" in err and "Traceback" not in err
    p.write_text('[train]\ninput = "1"\noutput = "H"\nmeshes = [["1", "9"]]\n[[train.wheel]]\nname = "1"\nz = 20\n',
                 encoding="utf-8")
    assert main(["check", str(p)]) == 2
    assert "неизвестное колесо «9»" in capsys.readouterr().err
