"""Page-by-page review of the ws002 (hydraulic-cylinder-driven hitch) and ws004 (slotted lever)
notes (#9, session 5).  Every test fails on the text the review found wrong: a second structural
formula in the introduction, a static analysis described with inertia forces, weights that do not
exist, the cylinder–rod pair named by the rod's end, ω₁ as the speed of a cylinder, analogs
without units, formulas whose numbers are not the ones their result uses, and so on."""
import math
import re

import pytest

from conftest import CASES
from reportgen.report.document import Figure, FormulaBlock, Paragraph, Section, Table
from notehelpers import blocks as _blocks, paragraph_text as _text


def _sections(sec):
    for b in sec.children:
        if isinstance(b, Section):
            yield b
            yield from _sections(b)


def _plain(html: str) -> str:
    return re.sub(r"<[^>]+>", "", str(html)).replace("&nbsp;", "\u00a0")


@pytest.fixture(scope="module")
def hitch():
    """ws002: structure, kinematics and forces sections built once."""
    from reportgen import load_case
    from reportgen.report.sections import forces, kinematics, structure
    st = load_case(CASES / "ws002_tractor_hitch.toml")
    return st, {"structure": structure.build(st), "kinematics": kinematics.build(st), "forces": forces.build(st)}


@pytest.fixture(scope="module")
def lever():
    """ws004: structure and kinematics sections built once."""
    from reportgen import load_case
    from reportgen.report.sections import kinematics, structure
    st = load_case(CASES / "ws004_slotted_lever.toml")
    return st, {"structure": structure.build(st), "kinematics": kinematics.build(st)}


def _intro(st) -> str:
    from reportgen.report import assemble
    return " ".join(p.html for p in assemble._introduction(st, assemble.chosen_sections(st, None), []))


# ------------------------------------------------------------------ one structure in every chapter
def test_introduction_gives_the_structural_formula_of_chapter_1(hitch):
    """The introduction printed I(0,1) → II(2,3) → … (a crank that ws002 has not) while chapter 1
    and the conclusion say I(1,2,3) → II(4,5) → II(6,7)."""
    st, secs = hitch
    from reportgen.report.sections.structure import decomposition
    formula = decomposition(st)[1]
    assert formula.startswith("I(1,2,3)")
    assert formula in _intro(st) and "I(0,1)" not in _intro(st)
    assert formula in _text(secs["structure"])


def test_key_gives_the_structural_formula_of_chapter_1(hitch):
    from reportgen.report import key
    from reportgen.report.sections.structure import decomposition
    st = hitch[0]
    txt = _text(key._results(st))
    assert decomposition(st)[1] in txt and "I(0,1)" not in txt and "механизм II класса" in txt
    assert "Начальный механизм (1,2,3) с ведущей поступательной парой 1–2 (гидроцилиндр)" in txt


def test_group_dof_sentence_covers_the_initial_mechanism(hitch, lever):
    """«Для каждой группы W = 0» stood above a table whose first row (the initial mechanism) has W = 1."""
    for st, secs in (hitch, lever):
        txt = _plain(_text(secs["structure"]))
        assert "для начального механизма" in txt


def test_introduction_promises_only_what_the_note_holds(lever, hitch):
    """ws004 has no force analysis, yet the introduction said the forces in the pairs are found."""
    assert "силы, действующие в кинематических парах" not in _intro(lever[0])
    assert "силы, действующие в кинематических парах" in _intro(hitch[0])
    # ws002 fits l4, Sp, l7 to the case's conditions
    assert "параметры, обеспечивающие требуемый режим работы" in _intro(hitch[0])
    assert "параметры" not in _intro(lever[0])


def test_scheme_scale_printed_as_elsewhere(lever, hitch):
    """Chapter 1 printed μl = 0,0100 м/мм, chapter 2 0,01 м/мм (1:10)."""
    assert "0,01&nbsp;м/мм, 1:10" in _text(lever[1]["structure"])
    assert "0,015&nbsp;м/мм, 1:15" in _text(hitch[1]["structure"])
    assert "0,0150" not in _text(hitch[1]["structure"])
    assert "1:15" in _text(hitch[1]["kinematics"])


# ------------------------------------------------------------------ kinematics
def test_true_motion_of_an_actuator_not_through_omega1(hitch, lever):
    """«v = ω1 x′» for a linkage whose generalized coordinate is the cylinder's length S."""
    para = next(b.html for b in _blocks(hitch[1]["kinematics"])
                if isinstance(b, Paragraph) and "Истинные скорости" in b.html)
    assert "ω" not in _plain(para) and "скорость и ускорение штока 2 относительно цилиндра 1" in _plain(para)
    assert "dot" not in para        # an accent over a capital S is hidden in the letter in print
    para4 = next(b.html for b in _blocks(lever[1]["kinematics"])
                 if isinstance(b, Paragraph) and "Истинные скорости" in b.html)
    assert "ω" in _plain(para4)


def _table(sec, caption):
    return next(b for b in _blocks(sec) if isinstance(b, Table) and b.caption.startswith(caption))


def test_analogs_carry_units_of_their_generalized_coordinate(hitch, lever):
    """dφ/dS is in 1/м and dx/dS dimensionless; dx/dφ is in м and dφ/dφ dimensionless (the radian
    is dimensionless; the diagrams label them the same way)."""
    w = _table(hitch[1]["kinematics"], "Аналоги угловых скоростей")
    e = _table(hitch[1]["kinematics"], "Аналоги угловых ускорений")
    v = _table(hitch[1]["kinematics"], "Аналоги скоростей точек")
    assert {c.unit for c in w.columns[2:]} == {"1/м"} and {c.unit for c in e.columns[2:]} == {"1/м²"}
    assert {c.unit for c in v.columns[2:]} == {None}
    w4 = _table(lever[1]["kinematics"], "Аналоги угловых скоростей")
    v4 = _table(lever[1]["kinematics"], "Аналоги скоростей точек")
    e4 = _table(lever[1]["kinematics"], "Аналоги угловых ускорений")
    assert {c.unit for c in w4.columns[2:]} == {None} and {c.unit for c in v4.columns[2:]} == {"м"}
    assert {c.unit for c in e4.columns[2:]} == {None}


def test_no_class_three_remark_without_a_triad(hitch, lever):
    for st, secs in (hitch, lever):
        assert "III класса" not in _text(secs["kinematics"])


def test_actuator_stroke_is_not_a_cycle(hitch):
    kin = hitch[1]["kinematics"]
    assert "по ходу гидроцилиндра" in _text(kin)
    assert not any("за цикл" in b.caption for b in _blocks(kin) if isinstance(b, Figure))
    titles = [s.title for s in _sections(hitch[1]["forces"])]
    assert "Реакции по ходу гидроцилиндра" in titles and "Реакции за цикл" not in titles


def test_extreme_positions_in_one_turn(lever):
    """ws004 printed the extreme positions at «360,0° и 145,1°»."""
    from reportgen.report.sections.kinematics import _turn
    assert _turn(2 * math.pi) == "0,0" and _turn(2 * math.pi - 1e-9) == "0,0"
    assert _turn(math.radians(145.1)) == "145,1"
    txt = _plain(_text(lever[1]["kinematics"]))
    assert "360,0°" not in txt and "кривошипа 0,0° и 145,1°" in txt


def _num(tex: str) -> float:
    return float(tex.replace("{,}", ".").replace(" ", ""))


def test_angular_formulas_divide_the_analytic_numerators(lever):
    """ε₃ = 89,27 / 0,9000 = 98,93 рад/с²: the numerator was the constructed segment, the result
    the analytic ε; now every ω = V/l and ε = a^τ/l divides to its printed result."""
    fs = [f for b in _blocks(lever[1]["kinematics"]) if isinstance(b, FormulaBlock) for f in b.formulas
          if f.symbolic.startswith((r"\omega_{", r"\varepsilon_{")) and f.substituted]
    assert len(fs) >= 4
    for f in fs:
        num, den = re.match(r"\\frac\{([^}]*\{,\}[^}]*)\}\{([^}]*\{,\}[^}]*)\}", f.substituted).groups()
        res = _num(f.result.split(r"\ ")[0])
        q = _num(num) / _num(den)
        assert abs(q - res) <= 10 ** (math.floor(math.log10(abs(res))) - 3), (f.symbolic, q, res)   # one unit of the 4th digit


# ------------------------------------------------------------------ forces
def test_static_analysis_not_described_with_inertia_forces(hitch):
    """«прикладываются главный вектор и главный момент сил инерции … силы инерции не учитываются»."""
    first = next(b.html for b in _blocks(hitch[1]["forces"]) if isinstance(b, Paragraph))
    assert "главный вектор" not in first and "Д’Аламбера" not in first
    assert "силы инерции не учитываются" in first


def test_no_weights_mentioned_for_weightless_links(hitch):
    """ws002 gives no masses: «силы тяжести приложены в центрах масс» described loads that do not exist."""
    assert "силы тяжести" not in _text(hitch[1]["forces"]) and "силами тяжести" not in _text(hitch[1]["forces"])


def test_weights_still_mentioned_where_links_have_them():
    from reportgen import load_case
    from reportgen.report.sections.forces import _weighted
    assert _weighted(load_case(CASES / "slider_crank.toml").forces)


def test_cylinder_rod_pair_named_by_its_links(hitch):
    """The incidence matrix headed the cylinder–rod pair «23 (Ц)», the name of the rod–lever joint.
    The matrix is no longer printed (session 7: not what a student hands in); the force chapter
    explains the pair «(Ц)» and names no pair by the rod's end."""
    assert not any(isinstance(b, Table) and b.caption.startswith("Матрица инциденций")
                   for b in _blocks(hitch[1]["forces"]))
    text = _text(hitch[1]["forces"])
    assert "(Ц) — пара цилиндр–шток" in text and "23 (Ц)" not in text


def test_initial_mechanism_table_named_so(hitch):
    caps = [b.caption for b in _blocks(hitch[1]["forces"]) if isinstance(b, Table)]
    assert any(c.startswith("Реакции в парах начального механизма (1,2,3)") for c in caps)
    assert "Уравнение сил начального механизма (рисунок" in _text(hitch[1]["forces"])


def test_rounding_residue_of_the_rod_normal_force_is_zero():
    from reportgen.core import kinetostatics as KS
    from reportgen.report.sections.forces import _prismatic_text

    class P:
        kind = KS.K_ACT
    txt = _prismatic_text(P(), {"F": 138350.0, "N": 2.68e-13, "Mp": -1e-12})
    assert "10" not in txt.split("N")[1] and "N\u00a0=\u00a00\u00a0Н" in txt and "M\u00a0=\u00a00\u00a0Н·м" in txt
    assert "N\u00a0=\u00a012,50\u00a0Н" in _prismatic_text(P(), {"F": 138350.0, "N": 12.5, "Mp": 0.0})


def test_scale_in_captions_not_broken(hitch):
    caps = [b.caption for b in _blocks(hitch[1]["forces"]) if isinstance(b, Figure) and "μ<sub>F</sub>" in b.caption]
    assert caps and all("μ<sub>F</sub>\u00a0=\u00a0" in c and "\u00a0Н/мм" in c for c in caps)


def test_lever_mentions_force_pairs_only_for_moments(hitch):
    """ws002 has no moment load, yet the lever's text and table note spoke of moments replaced by pairs."""
    forces = hitch[1]["forces"]
    assert "парами сил" not in _text(forces)
    t = _table(forces, "Моменты сил относительно полюса")
    assert "парами сил" not in (t.note or "")


def test_capacity_text_in_textbook_notation(hitch):
    txt = _text(hitch[1]["forces"])
    assert "нагрузки <i>P</i><sub>6</sub>" in txt and "в точке <i>S</i><sub>6</sub>" in txt
    assert "груз <i>G</i>&nbsp;=&nbsp;<i>P</i><sub>6</sub>" in txt


def test_russian_indices_upright_in_formulas():
    from reportgen.report.mathhtml import convert
    html = str(convert(r"P_{гр} + M_{ур} + x_G").html)
    assert "<i>г</i>" not in html and "<i>у</i>" not in html and ">гр</sub>" in html
    assert "<i>G</i>" in html and "<i>P</i>" in html


def _vector_part(sec):
    out, on = [], False
    for b in _blocks(sec):
        if isinstance(b, Paragraph) and "Векторные уравнения" in b.html:
            on = True
        if on:
            out.append(b)
    return out


def test_stone_equation_before_the_point_it_gives(lever):
    """ws004 wrote V_B = V_BC before the stone's V_A2 = V_A3 + V_A2A3, which gives ω₃ — and with it V_B."""
    fs = [f.symbolic for b in _vector_part(lever[1]["kinematics"]) if isinstance(b, FormulaBlock) for f in b.formulas]
    i_stone = next(i for i, t in enumerate(fs) if t.startswith(r"\bar{V}_{A_{2}}"))
    i_b = next(i for i, t in enumerate(fs) if t.startswith(r"\bar{V}_{B} = \bar{V}_{BC}"))
    assert i_stone < i_b
    ia_stone = next(i for i, t in enumerate(fs) if t.startswith(r"\bar{a}_{A_{2}}"))
    ia_b = next(i for i, t in enumerate(fs) if t.startswith(r"\bar{a}_{B} ="))
    assert ia_stone < ia_b


def test_one_where_after_each_block_of_equations(lever):
    """Each group printed «где …» once per equation: two «где» paragraphs in a row. Now one «где»
    list: «где» before the first explanation, «;» after each but the last, «.» after the last."""
    seq = ["где" if isinstance(b, Paragraph) and b.html.startswith("где") else type(b).__name__
           for b in _vector_part(lever[1]["kinematics"])]
    assert not any(a == b == "где" for a, b in zip(seq, seq[1:]))
    blocks = _vector_part(lever[1]["kinematics"])
    for i, b in enumerate(blocks):
        if isinstance(b, Paragraph) and b.html.startswith("где"):
            run = [b]
            for c in blocks[i + 1:]:
                if not isinstance(c, Paragraph) or c.html.endswith(":") or c.html.startswith(("Скорости", "Ускорения")):
                    break
                run.append(c)
            assert all(x.html.endswith(";") for x in run[:-1]) and run[-1].html.endswith("."), [x.html[-20:] for x in run]


def test_angular_formulas_hold_no_coriolis_repeat(lever):
    """a^k = 2ω₃V = 13,76 м/с² stood in the vector equations and again as (2.17) under
    «Угловые скорости и ускорения звеньев»."""
    fs = [f for b in _blocks(lever[1]["kinematics"]) if isinstance(b, FormulaBlock) for f in b.formulas]
    assert not any(f.symbolic.startswith("a^k") for f in fs)
    assert "кориолисово ускорение" in _text(lever[1]["kinematics"])


def test_crank_speed_given_once(lever):
    """V_A = ω₁l_OA = 2,700 м/с stood in the vector equations (15,00 · 0,1800) and again under
    «Угловые скорости и ускорения звеньев» (15,000 · 0,1800)."""
    fs = [f for b in _blocks(lever[1]["kinematics"]) if isinstance(b, FormulaBlock) for f in b.formulas]
    assert not any(f.symbolic.startswith(("V_{A} =", "a_{A} =")) for f in fs)
    assert "2,700" in _plain(_text(lever[1]["kinematics"]))


def test_transmission_angle_table_to_a_tenth_of_a_degree(lever):
    """Table 2.12 printed μmin = 66,16 and φ = 0,00 while the conclusion says 66,2° and the
    position tables give φ to 0,1°."""
    t = _table(lever[1]["kinematics"], "Наименьшие углы передачи")
    cells = [t.columns[k].fmt(v) for _, r in t.data.iterrows() for k, v in ((1, r["mu"]), (2, r["q"]))]
    # a ВПВ group with the guide through the pivot: μ = 90° everywhere, no position (test_note_fixes2)
    cells = [c for k, c in enumerate(cells) if not (c == "—" and cells[k - 1] == "90,0")]
    assert cells and all(re.fullmatch(r"\d+,\d", c) for c in cells), cells


def test_angle_table_title_without_sliding_pairs(hitch, lever):
    """ws002's table had no displacement column but was called «… и перемещения в поступательных парах»."""
    assert any(b.caption == "Углы звеньев" for b in _blocks(hitch[1]["kinematics"]) if isinstance(b, Table))
    assert any(b.caption.startswith("Углы звеньев и перемещения") for b in _blocks(lever[1]["kinematics"])
               if isinstance(b, Table))


def test_conclusion_judges_transmission_angles_once(hitch):
    """ws002's conclusion repeated «… не меньше допускаемого 40°, механизм работоспособен без
    заклинивания» for each of three groups and called the initial mechanism a group."""
    from reportgen.report.sections.kinematics import conclusion_lines
    lines = " ".join(conclusion_lines(hitch[0]))
    assert lines.count("работоспособен без заклинивания") == 1
    assert "(в начальном механизме (1,2,3) 48,1°, в группе (4,5) 67,6°, в группе (6,7) 51,6°)" in lines


def test_sliding_pair_rule_only_for_groups_with_one(hitch):
    """Groups (6,7) and (4,5) of ws002 are ВВВ and the initial mechanism has only the cylinder–rod
    pair, yet the construction said «реакция поступательной пары — перпендикулярно направляющей»."""
    assert "поступательной пары — перпендикулярно" not in _text(hitch[1]["forces"])
    from types import SimpleNamespace
    from reportgen.report.sections.forces import _construction_text
    import numpy as np
    from reportgen.scenes.forces import Constructed, Vector
    d = SimpleNamespace(vectors=[Vector("R12", np.zeros(2), (0, 0), "known", tex="$R^{\\tau}_{12}$")],
                        constructed=[Constructed("R34", 6400.0, 6418.8)], method="intersection")
    assert "перпендикулярно направляющей" not in _construction_text(d, "fig", set(), False)
    assert "перпендикулярно направляющей" in _construction_text(d, "fig", set(), True)
    assert "так же" not in _construction_text(d, "fig", {"intersection"}, True)    # the rule not told yet


def test_plan_caption_names_only_the_paths_drawn(hitch, lever):
    """ws002 gives no centres of mass, yet Fig. 2.1 was «… и траектории центров масс и точки 56»."""
    cap = next(b.caption for b in _blocks(hitch[1]["kinematics"]) if isinstance(b, Figure) and b.id == "fig-positions")
    assert cap == "План положений механизма и траектория точки 56"
    assert "Штриховой линией показана траектория точки 56." in _text(hitch[1]["kinematics"])
    # ws004 names points S3, S4 but gives no centre of mass: nothing is traced, nothing is claimed
    cap4 = next(b.caption for b in _blocks(lever[1]["kinematics"]) if isinstance(b, Figure) and b.id == "fig-positions")
    assert cap4 == "План положений механизма" and "Штриховыми линиями" not in _text(lever[1]["kinematics"])
    from reportgen import load_case
    from reportgen.report.sections import kinematics
    kin = kinematics.build(load_case(CASES / "slider_crank.toml"))
    cap = next(b.caption for b in _blocks(kin) if isinstance(b, Figure) and b.id == "fig-positions")
    assert cap == "План положений механизма и траектории центров масс"
    assert "Штриховыми линиями показаны траектории центров масс звеньев (рисунок" in _text(kin)


def test_constant_crank_speed_sentence_fits_one_line(lever):
    """«Кривошип вращается равномерно с угловой скоростью» + an unbreakable «ω₁ = 15,000 рад/с» left
    a justified line with gaps of a centimetre; the sentence now fits one line of the text width."""
    p = next(_plain(b.html) for b in _blocks(lever[1]["kinematics"]) if isinstance(b, Paragraph)
             and "рад/с." in b.html and "постоянна" in b.html)
    assert p.startswith("Угловая скорость кривошипа постоянна: ω") and len(p) <= 60


def test_capacity_figure_legend_in_textbook_notation(hitch, monkeypatch):
    """Fig. 3.1's legend read «P6 = 27,50 кН» and «k·p·η·A» as plain strings."""
    from reportgen.scenes import forces as scenes
    figs = []
    real = scenes.mplstyle.to_svg
    monkeypatch.setattr(scenes.mplstyle, "to_svg", lambda fig: figs.append(fig) or real(fig))
    scenes.CapacityCurves().draw(hitch[0])
    labels = [t.get_text() for ax in figs[0].axes if ax.get_legend() for t in ax.get_legend().get_texts()]
    assert "$P_{6}$ = 27,50 кН" in labels and r"$k \cdot p \cdot \eta \cdot A$" in labels
    assert "$G_{56}$" in labels and not any(l.startswith("P6") for l in labels)
    assert "<i>k</i>·<i>p</i>·<i>η</i>·<i>A</i>" in _text(hitch[1]["forces"])


def test_load_point_in_textbook_notation(hitch):
    """Table 3.2 printed the load's point as «S6»."""
    t = _table(hitch[1]["forces"], "Заданные силы и моменты")
    col = next(c for c in t.columns if c.key == "point")
    assert str(col.fmt("S6")) == "<i>S</i><sub>6</sub>" and col.fmt("—") == "—" and col.fmt("56") == "56"


def test_static_force_analysis_named_and_assigned_as_such(hitch):
    """ws002's chapter «Силовой (кинетостатический) анализ» says the analysis is static; the
    assignment did not ask for the capacity and axle loads the note computes."""
    from reportgen.report import assemble
    from reportgen.report.sections import forces
    assert hitch[1]["forces"].title == "Силовой анализ"
    task = forces.TASK(hitch[0])
    assert "статический расчёт" in task and "грузоподъёмность" in task and "нагрузки на мосты" in task
    tasks = assemble._assignment_tasks(hitch[0], assemble.chosen_sections(hitch[0], None))
    assert task in tasks and not any("кинетостатический" in t for t in tasks)


def test_plan_tables_list_each_vector_once(lever):
    """Table 2.10 listed V_AO and V_A (135,0 mm both), V_BC and V_B; Table 2.11 a^n_AO and a_A."""
    for cap in ("Скорости по плану", "Ускорения по плану"):
        t = _table(lever[1]["kinematics"], cap)
        pairs = list(zip(t.data["mm"], t.data["analytic"].round(9)))
        assert len(pairs) == len(set(pairs)), cap
    names = set(_table(lever[1]["kinematics"], "Скорости по плану").data["name"])
    assert {"V_A", "V_B"} <= names and "V_AO" not in names and "V_BC" not in names


def test_actuator_diagrams_in_metres_like_the_tables(hitch, monkeypatch):
    """Figs. 2.2 and 2.3 of ws002 had «S, мм» (450…650) while every table and Figs. 3.1, 3.6 give S in м."""
    from reportgen.scenes import diagrams
    figs = []
    real = diagrams.mplstyle.to_svg
    monkeypatch.setattr(diagrams.mplstyle, "to_svg", lambda fig: figs.append(fig) or real(fig))
    diagrams.AnalogCurves().draw(hitch[0])
    diagrams.OutputDiagrams().draw(hitch[0])
    for fig in figs:
        ax = fig.axes[-1]
        assert ax.get_xlabel() == "S, м"
        assert 0.4 <= ax.get_xlim()[0] < ax.get_xlim()[1] <= 0.7
    assert figs[0].axes[0].get_ylabel().endswith(", 1/м")



def test_check_prints_the_notes_structural_formula(capsys):
    """`reportgen check` printed the raw decomposition I(0,1) → II(2,3) → … for ws002 while the
    note and the key write the actuator's initial mechanism I(1,2,3) → II(4,5) → II(6,7)."""
    from reportgen.cli import main
    from pathlib import Path
    root = Path(__file__).resolve().parents[1]
    assert main(["check", str(root / "cases" / "ws002_tractor_hitch.toml")]) == 0
    out = capsys.readouterr().out
    assert "Структурная формула: I(1,2,3) → II(4,5) → II(6,7); механизм II класса" in out
    assert "(1,2,3) — начальный механизм с ведущей поступательной парой 1–2 (гидроцилиндр)" in out
