"""Defects left open at session 7's review of the notes (#9, /work/note_s7.md), each test failing
on what the review found: a paragraph leading into formulas («Маховик в виде сплошного диска:»)
at a page foot with its formulas on the next page; the Жуковский table listing forces whose
moment is zero and a balancing row whose printed F·h was not its printed product."""
import numpy as np

import pytest

from conftest import CASES
from notehelpers import blocks as _blocks


def _layout_pages(sec):
    from reportgen.report import render
    from reportgen.report.document import Report
    r = Report(meta={}, assignment=[], introduction=[], sections=[sec], conclusion=[],
               references=[], options={"title_page": False, "assignment_page": False})
    doc, _ = render._layout(r, render._font_config())
    return [" ".join(b.text for b in page._page_box.descendants() if getattr(b, "text", None))
            for page in doc.pages]


def _where(pages, word):
    return [i for i, p in enumerate(pages) if word in p]


def _lead_in_section(lines: int, heading: bool):
    """``lines`` one-line paragraphs, then (under a subsection heading, if asked) a paragraph
    leading into formulas."""
    from reportgen.report.document import Section
    s = Section("Раздел", "s")
    for k in range(lines):
        s.paragraph(f"Строка текста номер {k} для заполнения страницы.")
    t = s.subsection("ПОДЗАГОЛОВОК раздела", "s-sub") if heading else s
    t.paragraph("ВВОДНЫЙ абзац перед формулами:")
    t.formula(r"\xi = \zeta + 1", r"\eta = 2")
    return s


# --------------------------------------------------------------------------------------------
# 1. a paragraph leading into formulas is never the last line of a page without them
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("heading", [False, True])
def test_paragraph_leading_into_formulas_keeps_with_them(heading):
    """The lead-in is moved down the page line by line; as it crosses the page foot it goes to
    the next page with its formulas (and the heading over it) instead of staying alone."""
    pages_of = []
    for n in range(26, 34):
        pages = _layout_pages(_lead_in_section(n, heading))
        lead, formula = _where(pages, "ВВОДНЫЙ"), _where(pages, "ζ")
        assert lead == formula, (n, lead, formula)
        if heading:
            assert max(_where(pages, "ПОДЗАГОЛОВОК")) == lead[0], n   # (the first mention: contents)
        pages_of.append(lead[0])
    assert len(set(pages_of)) == 2     # the range crosses the page foot


def test_lead_in_class_only_before_formulas():
    """The template marks a paragraph followed by formulas (``p.intro``), not one followed by
    text; a paragraph before a short table keeps ``p.lead``."""
    from reportgen.report import render
    from reportgen.report.document import Report, Section
    s = Section("Раздел", "s")
    s.paragraph("ТЕКСТ до формул.")
    s.paragraph("ВВОДНЫЙ абзац:")
    s.formula(r"x = 1")
    s.paragraph("ПОСЛЕ формулы.")
    r = Report(meta={}, assignment=[], introduction=[], sections=[s], conclusion=[],
               references=[], options={"title_page": False, "assignment_page": False})
    html = render.render_html(r, for_print=True)
    assert '<p class="intro">ВВОДНЫЙ абзац:</p>' in html
    assert "<p>ТЕКСТ до формул.</p>" in html and "<p>ПОСЛЕ формулы.</p>" in html


# --------------------------------------------------------------------------------------------
# 2. the Жуковский table: no zero terms; every printed product is the printed F times h
# --------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def ws000_lever():
    from reportgen import load_case
    from reportgen.report.document import Table
    from reportgen.report.sections import forces
    st = load_case(CASES / "ws000_six_bar.toml")
    sec = forces.build(st)
    return next(b for b in _blocks(sec) if isinstance(b, Table) and b.id == "tab-frc-lever")


def test_lever_table_has_no_zero_moment_rows(ws000_lever):
    """ws000, position 12: G₅ (through the pole), M″Φ3 and M″Φ1 were listed with h = 0,0 and
    F·h = 0,0; now they are named under the table as passing through the pole."""
    df = ws000_lever.data
    assert (df["Fh"] != 0.0).all() and (df["h"] != 0.0).all() and (df["F"] != 0.0).all()
    note = str(ws000_lever.note)
    assert "<i>G</i><sub>5</sub>" in note and "проходят через полюс p" in note
    assert "в таблицу они не включены" in note
    assert "G₅" not in list(df["label"])


def test_lever_table_products_are_the_printed_numbers(ws000_lever):
    """Every row's ±F·h is the printed F times the printed h (to the product's printed
    decimals); the balancing row too (it printed F_ур = 6494 Н beside −626 667,5 Н·мм for an arm
    96,5 мм: 6494 · 96,5 = 626 671)."""
    df = ws000_lever.data
    cols = {c.key: c for c in ws000_lever.columns}

    def printed(key, v):
        return float("".join(ch for ch in cols[key].format(v).replace(",", ".").replace("−", "-")
                             if ch.isdigit() or ch in ".-"))
    for _, r in df.iterrows():
        assert printed("F", r["F"]) * printed("h", r["h"]) == pytest.approx(abs(printed("Fh", r["Fh"])), abs=1e-6), \
            r["label"]
    bal = df["balancing"].astype(bool)
    assert bal.sum() == 1
    # the column sums to zero up to the rounding of F_ур
    assert abs(float(df["Fh"].sum())) <= 0.5 * float(df.loc[bal, "h"].iloc[0])


@pytest.mark.parametrize("at_pole, zero, text", [
    (["<i>G</i><sub>5</sub>"], [], " Сила <i>G</i><sub>5</sub> проходит через полюс p (плечо равно нулю): её момент "
                                   "относительно полюса равен нулю, в таблицу она не включена."),
    (["a", "b", "c"], ["d"], " Силы a, b и c проходят через полюс p (плечо равно нулю); сила d в этом положении "
                             "равна нулю: их моменты относительно полюса равны нулю, в таблицу они не включены."),
    ([], [], "")])
def test_nil_note_agrees_in_number(at_pole, zero, text):
    from reportgen.report.sections.forces import _nil_note
    assert _nil_note((at_pole, zero)) == text


# --------------------------------------------------------------------------------------------
# 3. groups hung in parallel (V-compressor): the diagrams of each output, not of piston C only
#    (the velocity and acceleration plans already held both pistons' points)
# --------------------------------------------------------------------------------------------
def _diagrams_section(name):
    from reportgen import load_case
    from reportgen.report.document import Section
    from reportgen.report.sections import kinematics
    st = load_case(CASES / f"{name}.toml")
    sec = kinematics.build(st)
    return st, next(b for b in sec.children if isinstance(b, Section) and b.id == "sec-diagrams")


def test_parallel_outputs():
    from reportgen import load_case
    from reportgen.analysis.plans import output_quantity, parallel_outputs
    st = load_case(CASES / "v_compressor.toml")
    outs = parallel_outputs(st)
    assert [o[0] for o in outs] == ["s_30", "s_50"]          # piston B, then piston C (group order)
    assert output_quantity(st)[0] in [o[0] for o in outs]
    for name in ("ws000_six_bar", "swing_conveyor", "slider_crank"):   # a chain of groups: one output
        st = load_case(CASES / f"{name}.toml")
        assert parallel_outputs(st) == [output_quantity(st)]


def test_v_compressor_diagrams_of_both_pistons():
    from reportgen.report.document import Figure, Paragraph
    st, s5 = _diagrams_section("v_compressor")
    figs = [b for b in s5.children if isinstance(b, Figure)]
    assert [f.id for f in figs] == ["fig-diagrams", "fig-diagrams-2"]
    assert "поршень B" in figs[0].caption and "поршень C" in figs[1].caption
    text = " ".join(b.html for b in s5.children if isinstance(b, Paragraph))
    assert "<i>s</i>₃" in text and "<i>s</i>₅" in text
    assert s5.title == "Кинематические диаграммы выходных звеньев"
    from reportgen.report.sections.kinematics import conclusion_lines
    lines = " ".join(map(str, conclusion_lines(st)))
    assert "поршень B (звено 3); его ход" in lines and "поршень C (звено 5); его ход" in lines
    # each piston's mean speed (central slider-crank: K = 1, v = 2H·n = H·ω/π), not one «выходного звена»
    v = 0.1 * float(st.mechanism.driver.omega) / np.pi
    assert lines.count(f"средняя скорость на прямом и обратном ходах одинакова: {v:.2f}".replace(".", ",")) == 2
    assert "Средняя скорость выходного звена" not in lines


def test_single_output_diagrams_unchanged():
    from reportgen.report.document import Figure
    _, s5 = _diagrams_section("ws000_six_bar")
    figs = [b for b in s5.children if isinstance(b, Figure)]
    assert [(f.id, f.caption) for f in figs] == [("fig-diagrams", "Кинематические диаграммы выходного звена")]
    assert s5.title == "Кинематические диаграммы выходного звена"


# --------------------------------------------------------------------------------------------
# 4. a fast working stroke (slotting machine): the note says why and which way the crank
#    should turn; the strokes' angles and K in §2.5 are the conclusions' (exact) ones
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("direction, other", [(1, "по часовой стрелке"), (-1, "против часовой стрелки")])
def test_fast_working_stroke_says_which_way_to_turn(direction, other):
    from reportgen.report.sections.kinematics import _quick_return
    text = _quick_return(165.4, 1.177, "fast", direction)
    assert "при заданном направлении вращения кривошипа рабочим оказался быстрый ход" in text
    assert "те же положения в обратном порядке" in text
    assert f"кривошип целесообразно вращать {other}" in text
    assert "вращать" not in _quick_return(163.4, 1.203, "slow", direction)


def _strokes_paragraph(name):
    _, s5 = _diagrams_section(name)
    from reportgen.report.document import Paragraph
    return next(b.html for b in s5.children if isinstance(b, Paragraph) and "Крайние положения" in b.html)


def test_slotting_machine_fast_working_stroke_judged():
    from reportgen import load_case
    from reportgen.report.sections.kinematics import conclusion_lines
    text = _strokes_paragraph("slotting_machine")
    assert "кривошип целесообразно вращать по часовой стрелке" in text       # given: ccw
    st = load_case(CASES / "slotting_machine.toml")
    lines = " ".join(map(str, conclusion_lines(st)))
    assert "рабочий ход выходного звена — быстрый" in lines and "при вращении по часовой стрелке" in lines


def test_strokes_text_uses_the_exact_extremes():
    """ws000 printed K = 1,202 in §2.5 (extremes on the cycle's 0,1° grid) and K = 1,203 in the
    conclusions (the exact extremes)."""
    import math
    from reportgen import load_case
    from reportgen.style.numbers import fmt
    st = load_case(CASES / "ws000_six_bar.toml")
    K = float(st.scalars["output_K"])
    text = _strokes_paragraph("ws000_six_bar")
    assert f"<i>K</i>&nbsp;=&nbsp;{fmt(K, digits=3)}." in text
    work = 360.0 / (1.0 + K)
    assert f"другой — {fmt(work, digits=1)}°" in text and f"занимает {fmt(360 - work, digits=1)}°" in text
    assert math.isclose(K, (360 - work) / work)


# --------------------------------------------------------------------------------------------
# 5. ws002 read as a teacher: the introduction's comma, the fitted sizes in one sentence, what
#    to change when the pressure is exceeded, ΣF·h written as the table's column
# --------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def hitch():
    from reportgen import load_case
    return load_case(CASES / "ws002_tractor_hitch.toml")


def test_participial_phrase_closed_before_and(hitch):
    from reportgen.report.assemble import _determined
    assert _determined(hitch, ["structure", "kinematics", "forces"]) == (
        "его строение, движение звеньев, силы, действующие в кинематических парах, и параметры, обеспечивающие "
        "требуемый режим работы")
    assert _determined(hitch, ["structure", "kinematics"]).endswith("движение звеньев и параметры, обеспечивающие "
                                                                    "требуемый режим работы")


def test_fitted_sizes_in_one_sentence(hitch):
    from reportgen.report.sections.structure import conclusion_lines
    lines = [str(x) for x in conclusion_lines(hitch)]
    fitted = [x for x in lines if x.startswith("Подобран")]
    assert len(fitted) == 1 and fitted[0].startswith("Подобраны размеры: <i>l</i><sub>4</sub>")
    assert fitted[0].count("условие") == 3


def test_exceeded_pressure_says_what_bore_or_pressure_is_needed(hitch):
    """ws002: p = 17,597 МПа > 17,5 МПа at S = 0,420 м; the bore that gives F_max at 17,5 МПа is
    D·√(p_req/p) (a second formulation of √(4F/(πkpη)))."""
    import math
    from reportgen.report.sections.forces import conclusion_lines
    sc = hitch.forces.scalars
    A = hitch.forces.settings.actuator
    D = A.diameter * math.sqrt(sc["p_act_max"] / A.pressure)
    text = " ".join(map(str, conclusion_lines(hitch)))
    want = f"{math.ceil(D * 1e4) / 10:.1f}".replace(".", ",")
    assert f"&nbsp;=&nbsp;{want}&nbsp;мм (задан 80&nbsp;мм)" in text, text
    assert "давление в гидросистеме не менее 17,6&nbsp;МПа" in text


def test_lever_sum_written_as_the_column(hitch):
    from reportgen.report.document import FormulaBlock, Table
    from reportgen.report.sections import forces
    blocks = list(_blocks(forces.build(hitch)))
    f = next(f for b in blocks if isinstance(b, FormulaBlock) for f in b.formulas if f.symbolic.startswith("F^{Ж}"))
    assert r"\cdot 10" not in f.substituted and r"5\,527\,500{,}0" in f.substituted
    tab = next(b for b in blocks if isinstance(b, Table) and b.id == "tab-frc-lever")
    loads = tab.data[~tab.data["balancing"].astype(bool)]
    assert float(loads["Fh"].sum()) == 5527500.0


def test_flywheel_inertia_printed_as_substituted_later():
    """ws000 printed J_доп = 1461,59 − 2,500 = 1459,1 кг·м² and then D₂ = 0,437·⁵√1459,09: the
    result is printed to the digits the next formulas substitute (and 1461,59 − 2,500 = 1459,09)."""
    import re
    from reportgen import load_case
    from reportgen.report.document import FormulaBlock
    from reportgen.report.sections import dynamics
    st = load_case(CASES / "ws000_six_bar.toml")
    forms = [f for b in _blocks(dynamics.build(st)) if isinstance(b, FormulaBlock) for f in b.formulas]
    jd = next(f for f in forms if f.label == "eq-Jdop")
    value = re.match(r"[\d,{}]+", jd.result).group(0)
    assert value == r"1459{,}09", jd.result
    D2 = next(f for f in forms if f.symbolic.startswith("D_2 ="))
    assert r"\sqrt[5]{" + value + "}" in D2.substituted


def test_position_number_not_parted_from_its_word_in_headings():
    """ws002's contents printed «3.3 Реакции … по группам Ассура (положение» and «1) ……15» on the
    next line: the headings keep «положение 1» / «положения 12» together."""
    from reportgen import load_case
    from reportgen.report.document import Section
    from reportgen.report.sections import forces, kinematics
    st = load_case(CASES / "ws000_six_bar.toml")
    titles = [b.title for sec in (kinematics.build(st), forces.build(st)) for b in sec.children
              if isinstance(b, Section)]
    assert "Реакции в кинематических парах по группам Ассура (положение\u00a012)" in titles
    assert "Планы скоростей и ускорений для положения\u00a012" in titles
