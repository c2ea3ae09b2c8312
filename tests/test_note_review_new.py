"""Review of the note on mechanisms first met outside the worksheets (#9): a shaper with a
swinging slotted lever and a stone-and-slider group ПВП, a Scotch-yoke pump (ВПП, the slotted
link only translates), a walking conveyor driven by a coupler point, a six-bar press.  Every test
fails on the text or the drawing the review found wrong."""
import math

import numpy as np
import pytest

from conftest import CASES
from reportgen.report.document import Column, Section, Table
from notehelpers import blocks as _blocks, paragraph_text as _text


@pytest.fixture(scope="module")
def shaper():
    from reportgen import load_case
    return load_case(CASES / "shaper_swinging_lever.toml")


@pytest.fixture(scope="module")
def yoke():
    from reportgen import load_case
    return load_case(CASES / "yoke_pump.toml")


@pytest.fixture(scope="module")
def conveyor():
    from reportgen import load_case
    return load_case(CASES / "conveyor_four_bar.toml")


# ------------------------------------------------------------------ loads table (§3.1)
def test_load_condition_written_with_values_not_parameter_names(shaper):
    """«при x(D) > -X_max + x(run)» printed the case's parameter names; the bound is now the value
    of the right side in metres and the column in textbook notation."""
    from reportgen.report.sections.dynamics import _law
    law = str(_law(next(ld for ld in shaper.dynamics.loads.loads if ld.name == "Pрез")))
    assert "X_max" not in law and "x_run" not in law and "x(" not in law
    assert "<i>x</i><sub>D</sub> &gt; −0,1705\u00a0м" in law
    assert "<i>x</i><sub>D</sub> &lt; 0,1705\u00a0м" in law


def test_load_table_abscissa_in_symbols():
    """The abscissa of a load table was printed as the case wrote it («l_OA + l_AB - y_B»)."""
    from reportgen import load_case
    from reportgen.report.sections.dynamics import _law
    st = load_case(CASES / "crank_press.toml")
    law = str(_law(next(ld for ld in st.dynamics.loads.loads if ld.name == "Pв")))
    assert "l_OA" not in law and "y_B" not in law
    assert "<i>l</i><sub>OA</sub> + <i>l</i><sub>AB</sub> − <i>y</i><sub>B</sub>" in law
    assert "6\u00a0точек" in law


# ------------------------------------------------------------------ assignment
def _given(study) -> dict:
    from reportgen.report.assemble import _given_parameters
    (tab,) = _given_parameters(study)
    return {str(r["name"]): (r["value"], r["unit"]) for _, r in tab.data.iterrows()}


def test_derived_parameter_rounded_in_given_data(shaper):
    """A parameter computed from others (X_max = h·l₁/√(l₀² − l₁²)) was printed 0,1905125343."""
    v, unit = _given(shaper)["<i>x</i><sub>max</sub>"]
    assert v == 0.1905 and unit == "м"


def test_pressure_given_in_megapascals(yoke):
    """1,2 МПа was printed «1·10⁶ Па» (the exponent form dropped the digit 2)."""
    given = _given(yoke)
    assert given["<i>p</i><sub>н</sub>"] == (pytest.approx(1.2), "МПа")
    assert given["<i>p</i><sub>вс</sub>"] == (pytest.approx(0.06), "МПа")


def test_as_written_keeps_every_digit_of_a_large_value():
    from reportgen.report.sections.common import as_written
    assert as_written(1.2e6).replace("\u202f", " ") == "1 200 000"


# ------------------------------------------------------------------ vector equations (§2.4)
def _equations(study):
    from reportgen.report.sections import vectors
    from reportgen.report.sections.common import chosen_position
    row = study.kinematics[study.kinematics["pos"] == chosen_position(study)].iloc[0]
    return {g.label: vectors.group_equations(study, row, g) for g in study.structure.groups}


def test_group_gets_only_its_own_pairs(shaper):
    """Group (2,3) was given the equations of the pair 3–4 by which group (4,5) is attached to it
    (the «где» lines printed twice, V_D4 before link 4 is solved)."""
    eqs = _equations(shaper)
    g23 = next(v for k, v in eqs.items() if "2" in k and "3" in k and "4" not in k)
    g45 = next(v for k, v in eqs.items() if "4" in k and "5" in k)
    vf23 = " ".join(f.symbolic for f in g23[0])
    assert "D" not in vf23 and "A_{2}" in vf23
    assert len(g23[0]) == len(g23[1]) == 1
    vf45 = " ".join(f.symbolic for f in g45[0])
    assert "D_{4}" in vf45 and "D_{3}" in vf45
    # the stone on the swinging lever has a Coriolis term, the slider on the frame has none
    assert "^{k}" in " ".join(f.symbolic for f in g45[2])


def test_no_coriolis_on_a_translating_guide(yoke):
    """The yoke only translates: a^k = 2ω₃V_r was written with ω₃ = 0 «в сторону вращения звена 3»."""
    eqs = _equations(yoke)
    acc = " ".join(f.symbolic for v in eqs.values() for f in v[2])
    notes = " ".join(str(n) for v in eqs.values() for n in v[3])
    assert "^{k}" not in acc and "^{r}" in acc
    assert "вращения звена 3" not in notes
    assert "движется поступательно" in notes


# ------------------------------------------------------------------ kinematics section
@pytest.fixture(scope="module")
def yoke_kinematics(yoke):
    from reportgen.report.sections import kinematics
    return kinematics.build(yoke)


def test_no_empty_angular_analogue_tables(yoke_kinematics):
    """Tables 2.3/2.4 of the yoke had only the position columns and Fig. 2.2 an empty plot."""
    caps = [b.caption for b in _blocks(yoke_kinematics) if hasattr(b, "caption")]
    assert not any(c.startswith("Аналоги угловых") for c in caps)
    assert "движутся поступательно" in _text(yoke_kinematics)


def test_summary_mentions_coriolis_only_where_the_guide_turns(yoke_kinematics):
    text = _text(yoke_kinematics)
    assert "с кориолисовым ускорением" not in text
    assert "без кориолисова ускорения" in text


def test_link_angles_in_one_turn(yoke_kinematics):
    """The crank's angle was printed 390…510° after one turn."""
    (tab,) = [b for b in _blocks(yoke_kinematics) if isinstance(b, Table) and b.id == "tab-angles"]
    col = next(c for c in tab.columns if c.key == "phi_1")
    vals = [float(col.format(v).replace(",", ".").replace("−", "-")) for v in tab.data["phi_1"]]
    assert min(vals) >= 0 and max(vals) < 360


# ------------------------------------------------------------------ tables: one number of decimals
def test_column_printed_to_one_number_of_decimals():
    """Table 2.7 printed 0,9455 / 5,014 / 10,03 and 1,547·10⁻¹⁵ in one column."""
    from reportgen.report.render import column_decimals
    col = Column("a", "a", sig=4)
    assert column_decimals(col, [0.9455, 5.014, 10.03, 1.547e-15]) == 2
    assert column_decimals(col, [25.58, 1947.7]) == 0
    assert column_decimals(Column("a", "a", digits=3), [1.0]) is None
    assert column_decimals(col, [1, 2, 3]) is None
    assert column_decimals(col, [5.9e-13, -1.1e-14]) == 3          # noise of an exact zero: 0,000


# ------------------------------------------------------------------ plan of positions
def test_coupler_point_traced_and_marked(conveyor, yoke):
    """The conveyor's output is the coupler point M: its trajectory (the coupler curve) is drawn and
    its extreme positions are M′, M″ (they were put at the crank pin A)."""
    from reportgen.scenes.mechanism import _output_point, traced_points
    assert "M" in traced_points(conveyor)
    assert _output_point(conveyor, "x_M") == "M"
    assert "P" not in traced_points(yoke)          # a point of a translating link: a straight line


def test_ghost_positions_not_tinted(conveyor):
    from reportgen.scenes.mechanism import PositionsPlan
    svg = PositionsPlan().draw(conveyor).svg
    svg = svg.decode() if isinstance(svg, bytes) else svg
    # one tinted plate: the drawn position (the others and the extreme positions in outline)
    from reportgen.scenes.draw import LIGHT
    from matplotlib.colors import to_hex
    assert svg.count(f"fill: {to_hex(LIGHT)}") == 1


# ------------------------------------------------------------------ conclusion
def test_transmission_angle_judged(conveyor):
    from reportgen.report.sections.kinematics import conclusion_lines
    lines = " ".join(conclusion_lines(conveyor))
    assert "не меньше допускаемого 40°" in lines
    assert "Выходное звено — захват M; его ход" in lines
    assert "(2, 3)" not in lines


# ------------------------------------------------------------------ force polygons (§4.2)
def test_construction_text_without_tangential_components():
    """The polygon of the group ПВП (two prismatic outer pairs) was described with «касательные
    составляющие R^τ … нормальная составляющая R^n — вдоль звена», which it has not."""
    from types import SimpleNamespace
    from reportgen.report.sections.forces import _construction_text
    from reportgen.scenes.forces import Constructed, Vector
    found = [Constructed("R34", 6400.0, 6418.8), Constructed("R05", 1300.0, 1314.6)]
    plain = SimpleNamespace(vectors=[Vector("R34", np.zeros(2), (0, 0), "unknown")], constructed=found,
                            method="intersection")
    text = _construction_text(plain, "fig", set())
    assert "R</i><sup>τ" not in text and "R</i><sup>n" not in text and "перпендикулярно направляющей" in text
    tau = SimpleNamespace(vectors=[Vector("R12", np.zeros(2), (0, 0), "known", tex="$R^{\\tau}_{12}$")],
                          constructed=found, method="intersection")
    assert "<i>R</i><sup>τ</sup>" in _construction_text(tau, "fig", set())
    # a group constructed the other way is described in full, not «так же»
    assert "так же" not in _construction_text(tau, "fig", {"lines"})
    assert "так же" in _construction_text(tau, "fig", {"intersection"})


def test_load_law_cell_rendered_as_markup(conveyor):
    """The law with the textbook symbol was printed as text «<i>y</i><sub>M</sub> &gt; 0,4000 м»."""
    from reportgen.report.render import render_fragment
    from reportgen.report.sections.dynamics import _model
    sec = Section("Динамика", "sec-dyn")
    _model(sec, conveyor, conveyor.dynamics)
    (tab,) = [b for b in _blocks(sec) if isinstance(b, Table) and b.id == "tab-dyn-loads"]
    html = render_fragment(tab, chapter="3")
    assert "<i>y</i><sub>M</sub> &gt; 0,4000" in html
    assert "&lt;i&gt;" not in html


def test_two_prismatic_pairs_at_one_point_told_apart(shaper):
    """Table 1.2 and the incidence table had two columns «D (П)» (stone 4 on the lever, slider 5 on
    the frame)."""
    from reportgen.report.sections import structure
    (tab,) = [b for b in _blocks(structure.build(shaper)) if isinstance(b, Table) and b.id == "tab-pairs"]
    names = list(tab.data["name"])
    assert len(set(names)) == len(names)
    assert "D<sub>34</sub> (П)" in names and "D<sub>05</sub> (П)" in names and "A (П)" in names


def test_transmission_angle_group_named_as_in_chapter_1(ws002):
    """Table 2.9 of ws002 named the dyad of the initial mechanism «2,3»; chapter 1 calls it (1,2,3)."""
    from reportgen.report.russian import flag_group as _flag_group
    assert _flag_group(ws002, "mu_2_3") == "(1,2,3)"
    assert _flag_group(ws002, "mu_4_5") == "(4,5)"


def test_cylinders_numeral_in_words():
    """«давление в 2 гидроцилиндрах» → «в двух гидроцилиндрах»."""
    from reportgen.report.sections.forces import _in_cylinders
    assert _in_cylinders(2) == "в двух гидроцилиндрах"
    assert _in_cylinders(1) == "в гидроцилиндре"


def test_positions_numbered_along_the_longer_path(ws002, conveyor):
    """ws002's ten positions were numbered at the rod end 23, whose short stroke piled the numbers
    on the labels of the pivots; they go along the path of the hitch axis 56."""
    from reportgen.scenes.mechanism import _tracer_point, numbered_point
    rows = [r for _, r in ws002.kinematics.iterrows()]
    assert numbered_point(ws002.mechanism, rows, _tracer_point(ws002), "56") == "56"
    rows = [r for _, r in conveyor.kinematics.iterrows()]
    assert numbered_point(conveyor.mechanism, rows, _tracer_point(conveyor), "M") == "A"


def test_link_lengths_named_by_their_links(ws004):
    """ws004's given data read «длина 1», «длина 0», «длина 3»."""
    from reportgen.report.assemble import _given_parameters
    (tab,) = _given_parameters(ws004)
    titles = list(tab.data["title"])
    assert "длина звена 1 (кривошип)" in titles and "длина звена 3 (кулиса)" in titles
    assert any(t.startswith("длина стойки") for t in titles)
    assert "длина 1" not in titles


def test_quick_return_judged_only_when_the_strokes_differ():
    """The shaper's K = 1,49 was printed with no word on which stroke works; a crank with K ≈ 1
    gets no such sentence."""
    from reportgen.report.sections.kinematics import _quick_return
    text = _quick_return(145.2, 214.8 / 145.2)
    assert "рабочим назначается медленный ход" in text and "214,8°" in text and "1,48 раза" in text
    assert _quick_return(178.5, 181.5 / 178.5) == ""


def test_group_at_one_point_not_enlarged_tenfold(shaper):
    """The group (4,5) — a stone and a slider at one point D — was drawn at μ_l = 0,0001 м/мм
    (10:1): its joints span nothing, the scale now follows the mechanism's size."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import GroupForces
    lab = chosen_position(shaper)
    mus = [GroupForces(lab, gi).draw(shaper).mu for gi in range(len(shaper.structure.groups))]
    assert min(mus) >= 0.001
