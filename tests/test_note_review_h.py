"""Defects found reviewing, page by page as a ТММ teacher, the notes of two mechanisms new to
cases/ (session 9, #9): a rocking-cylinder drive «механизм с качающимся цилиндром» (ВПВ group
whose slider is a piston rod with its own centre of mass and piston, the cylinder the output with
a resistance moment on its working swing, the crank turning clockwise about a centre off the
origin) and a knuckle press «коленно-рычажный пресс» (ВВВ + ВВП on the compound knee hinge, a
coining force from a table over the last millimetres of the down stroke, weights of all links).
Each test fails on what the review found:

* the velocity plan and the Жуковский lever of the rocking cylinder print two «p»: the pole and
  the image of the piston's point P;
* §2.4 and the transmission-angle note call the piston rod «камень» («относительная скорость
  камня», «ускорение точки звена 3 под ползуном», «давление камня на кулису»);
* Table 3.2 reads the load condition «при φ′₃ > 0 1» (a dimensionless side printed with the
  unit «1»), where a student writes «при повороте звена 3 против часовой стрелки»;
* §4.2 says the prismatic pair's reaction of a ВПВ group is found «из уравнения моментов сил
  звена относительно его внешнего шарнира»: one equation, while the rod's reaction has an
  unknown point of application too (two unknowns, the moment equations of both links).
"""
import numpy as np
import pytest

from conftest import CASES
from notehelpers import plain

_STUDIES: dict = {}


def _study(stem):
    from reportgen import load_case
    if stem not in _STUDIES:
        _STUDIES[stem] = load_case(CASES / f"{stem}.toml")
    return _STUDIES[stem]


def _owner(mech, point: str) -> str:
    """The link whose points hold ``point`` (independent of the plans' segments)."""
    return next(l.name for l in mech.links if point in l.points)


# ------------------------------------------------------------------ the pole and the point P
def test_image_of_point_P_is_not_labelled_as_the_pole(captured):
    """On the velocity plan and on the Жуковский lever the pole is «p»; the image of a point
    named P carries its link's number (p₂), as the guide's point under a slider carries its own."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import ZhukovskyLever
    from reportgen.scenes.plans import PlanScene
    st = _study("rocking_cylinder")
    mech = st.mechanism
    assert any("P" in l.points for l in mech.links)
    want = "$p_{" + _owner(mech, "P") + "}$"
    lab = chosen_position(st)
    for scene in (PlanScene(lab, "velocity", landscape=True), ZhukovskyLever(lab)):
        captured.clear()
        drawing = scene.draw(st)
        texts = [t.get_text() for fig in captured for ax in fig.axes for t in ax.texts]
        poles_in_views = sum("p" in ins.tips for ins in (getattr(drawing, "insets", None) or []))
        assert texts.count("$p$") == 1 + poles_in_views, (type(scene).__name__, texts)
        assert want in texts, (type(scene).__name__, texts)


def test_tip_label_of_a_point_P_on_the_acceleration_plan_is_unchanged():
    """The acceleration plan's pole is π: the image p′ of P needs no index."""
    from reportgen.analysis.plans import Plan
    from reportgen.scenes.plans import tip_label
    plan = Plan("acceleration", {"P": np.ones(2)}, [], {"P": "P"}, {"P": "2"})
    assert tip_label("P", plan, "acceleration") == "$p′$"
    assert tip_label("P", Plan("velocity", {"P": np.ones(2)}, [], {"P": "P"}, {"P": "2"}), "velocity") == "$p_{2}$"


# ------------------------------------------------------------------ a rod is not a stone
@pytest.fixture(scope="module")
def kin_texts():
    """The paragraphs and the tables' notes of §2 of each case, as plain text."""
    from notehelpers import blocks, paragraph_text
    from reportgen.report.document import Table
    from reportgen.report.sections import kinematics
    out = {}
    for stem in ("rocking_cylinder", "ws004_slotted_lever"):
        sec = kinematics.build(_study(stem))
        notes = " ".join(b.note or "" for b in blocks(sec) if isinstance(b, Table))
        out[stem] = plain(paragraph_text(sec) + " " + notes)
    return out


def test_piston_rod_is_not_called_a_stone(kin_texts):
    """A slider with points of its own (the rod: S₂, the piston P) is named by its number; a
    slider that is only its pin (ws004's камень кулисы) keeps the textbook's «камень»."""
    from reportgen.report.sections.vectors import is_stone
    for stem, text in kin_texts.items():
        mech = _study(stem).mechanism
        moving = [j for j in mech.prismatic if j.links[0] != "0"]
        assert moving
        stones = [is_stone(mech, j) for j in moving]
        assert stones == [len(mech.link(j.links[1]).points) == 1 for j in moving]
        if all(stones):
            assert "камня" in text and "под ползуном" in text, stem
        else:
            assert "камн" not in text and "под ползуном" not in text, stem
            j = moving[0]
            assert (f"ускорение точки звена {j.links[0]}, совпадающей в данный момент с точкой {j.point} "
                    f"звена {j.links[1]}") in text
            assert f"давление звена {j.links[1]} на звено {j.links[0]}" in text
            assert "относительная скорость в поступательной паре" in text


# ------------------------------------------------------------------ the load's condition
def test_condition_on_a_link_turning_reads_as_words():
    from reportgen.report.russian import condition_html
    assert str(condition_html("wq_3 > 0")) == "при повороте звена 3 против часовой стрелки"
    assert str(condition_html("wq_5 <= 0", 0.0, "1")) == "при повороте звена 5 по часовой стрелки"
    # a dimensionless right side has no unit «1»
    from reportgen.style.numbers import fmt
    out = str(condition_html("wq_3 >= 0.25", 0.25, "1"))
    assert out.endswith(fmt(0.25, sig=4)), out


def test_rocking_cylinder_load_table_names_the_working_swing():
    """Table 3.2: the resistance moment acts while the cylinder turns counter-clockwise (φ₃ grows
    with the crank's angle, wq_3 > 0 on the cycle where it is non-zero)."""
    from reportgen.report.sections.dynamics import _law
    st = _study("rocking_cylinder")
    ld = next(l for l in st.loads.loads if l.kind == "moment")
    text = plain(_law(ld))
    # the case's moment as the table prints it (read from the case, not typed), then no stray unit « 1»
    from reportgen.style.numbers import fmt
    moment = fmt(ld.pieces[0].const, sig=4)
    assert moment in text and "при повороте звена 3 против часовой стрелки" in text and " 1" not in text
    dyn = st.dynamics.cycle
    M = dyn["M_" + ld.name].to_numpy()
    wq = st.cycle["wq_3"].to_numpy()
    n = min(len(M), len(wq))
    on = np.abs(M[:n]) > 1e-9
    assert on.any() and (wq[:n][on] > -1e-9).all()


# ------------------------------------------------------------------ ВПВ reaction: two equations
def test_vpv_reaction_text_names_both_moment_equations():
    """The rod's reaction from the cylinder does not pass through the pin A (its moment about A is
    not zero): its magnitude and point need the moment equations of both links."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.report.sections.forces import CONSTRUCTION_TEXT
    st = _study("rocking_cylinder")
    det = st.forces.details(chosen_position(st))
    pri = [p for p in det["pairs"] if "Mp" in p and "F" not in p]
    assert pri and all(abs(p["Mp"]) > 1e-6 * abs(p["N"]) * st.mechanism.size() for p in pri)
    text = CONSTRUCTION_TEXT["links"]
    assert "модуль и точка приложения" in text and "двух звеньев" in text


# ------------------------------------------------------------------ the knuckle press
def test_switching_points_listed_only_where_a_load_changes():
    """The coining force's table corners are crossed again on the way up, where its condition
    (moving down) holds it at zero: those points (and the top dead centre, where the force is
    zero on both sides) are not «points where the loads change their law»."""
    from reportgen.report.sections.dynamics import _breaks_text, law_breaks
    st = _study("knuckle_press")
    d = st.dynamics
    dq = 1e-7 * d.loads.cycle_length
    force = next(l for l in d.loads.loads if l.kind == "force")      # the coining force Pч

    def value(q):
        cols = d.ev(np.array([q]))
        return float(np.hypot(*[np.asarray(c, float)[0] for c in force.components(cols, d.loads.phase(cols))]))

    dead = [q for q in d.breaks if value(q - dq) == 0.0 and value(q + dq) == 0.0]
    assert dead                                   # the defect's condition exists in this case
    kept = law_breaks(d)
    assert kept.size == d.breaks.size - len(dead)
    assert all(value(q - dq) > 0 or value(q + dq) > 0 for q in kept)
    text = plain(_breaks_text(st, kept))
    from reportgen.report.sections.dynamics import _phase_deg
    assert not any(_phase_deg(st, q) in text for q in dead)


def test_slider_has_no_angular_acceleration_in_the_inertia_table():
    """Table 4.1: a link without J_S (the press's slider moving in translation) prints «—» for ε,
    as for M_Φ, not «0,000»."""
    from notehelpers import blocks
    from reportgen.report.document import Table
    from reportgen.report.sections import forces
    st = _study("knuckle_press")
    sec = forces.build(st)
    tab = next(b for b in blocks(sec) if isinstance(b, Table) and b.id == "tab-frc-inertia")
    df = tab.data.set_index("n")
    for l in st.mechanism.links:
        if l.name in df.index:
            assert np.isnan(df.loc[l.name, "e"]) == (not l.J_S), l.name
    assert np.isnan(df.loc["5", "e"])


# ------------------------------------------------------------------ ω of a rocking cylinder
def _formulas(sec):
    from notehelpers import blocks
    from reportgen.report.document import FormulaBlock
    return [f for b in blocks(sec) if isinstance(b, FormulaBlock) for f in b.formulas]


@pytest.mark.parametrize("stem", ["rocking_cylinder", "ws004_slotted_lever", "swing_conveyor"])
def test_every_rotating_link_gets_its_omega_and_epsilon_in_section_2_4(stem):
    """The cylinder 3 (points C, S₃, K: none a pair but its pivot) had no «ω₃ = V/l» in §2.4 while
    aⁿ = ω₃²·l_CA and a^k = 2ω₃V_r used ω₃ = 3,143; the rod 2 turns with it: ω₂ = ω₃, ε₂ = ε₃, one
    number each (not a second, different reading)."""
    import re
    from reportgen.analysis.plans import group_rank, measured_omegas
    from reportgen.report.sections import kinematics
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.plans import PlanScene
    st = _study(stem)
    mech = st.mechanism
    fs = _formulas(kinematics.build(st))
    heads = {}
    for f in fs:
        m = re.match(r"\\(omega|varepsilon)_\{(\w+)\} = ", f.symbolic)
        if m:
            heads.setdefault(m.group(1), {})[m.group(2)] = f.result
    from reportgen.report.sections.vectors import is_stone
    stones = {j.links[1] for j in mech.prismatic if j.links[0] != "0" and is_stone(mech, j)}
    # every rotating link but a stone (its ω, the guide's, enters no formula: no J, no aⁿ of its own)
    rotating = [l.name for l in mech.moving if l.name != mech.driver.link and l.name not in stones
                and float(np.abs(st.cycle["wq_" + l.name]).max()) > 1e-9]
    assert set(rotating) <= set(heads["omega"]), (rotating, heads["omega"])
    for j in mech.prismatic:
        g, s = j.links
        if g != "0" and s in rotating:
            assert heads["omega"][s] == heads["omega"][g]
            if s in heads.get("varepsilon", {}):
                assert heads["varepsilon"][s] == heads["varepsilon"][g]
    # the acceleration plan is drawn with the same ω for the slider and its guide
    lab = chosen_position(st)
    row = st.kinematics[st.kinematics["pos"] == lab].iloc[0]
    from reportgen.analysis.plans import construct_velocity
    mu = PlanScene(lab, "velocity", landscape=True).draw(st).mu
    vrow, vplan = construct_velocity(row, st, mu)
    om = measured_omegas(vrow, vplan, mech, mu, group_rank(st))
    for j in mech.prismatic:
        if j.links[0] != "0":
            assert om[j.links[1]] == om[j.links[0]]


# ------------------------------------------------------------------ the articulated-rod compressor
def test_master_rod_piston_is_an_output_too():
    """The articulated rod's group (4,5) hangs on the master rod's point E, so group (2,3) is not
    terminal; its piston B still compresses air (pressure loads act on it): §2.5 and the
    conclusion give both pistons, as for the V-compressor. A rocker a later group hangs on (ws000)
    stays an intermediate link."""
    from reportgen.analysis.plans import parallel_outputs
    st = _study("articulated_compressor")
    mech = st.mechanism
    loaded = {ld.link for ld in st.loads.loads if ld.kind != "weight"}
    pistons = [j for j in mech.prismatic if j.links[0] == "0" and j.links[1] in loaded]
    assert len(pistons) == 2
    # the defect's condition: the master rod's group carries another group (a pair of link 4 on link 2)
    assert any(set(j.links) == {"2", "4"} for j in mech.joints)
    assert sorted(o[0] for o in parallel_outputs(st)) == sorted(f"s_{j.name}" for j in pistons)
    assert len(parallel_outputs(_study("ws000_six_bar"))) == 1


def test_articulated_compressor_note_gives_both_strokes():
    from notehelpers import paragraph_text
    from reportgen.report.sections import kinematics
    from reportgen.report.sections.kinematics import conclusion_lines
    st = _study("articulated_compressor")
    text = plain(paragraph_text(kinematics.build(st))) + " " + plain(" ".join(map(str, conclusion_lines(st))))
    for j in st.mechanism.prismatic:
        if j.links[0] == "0":
            H = float(st.cycle["s_" + j.name].max() - st.cycle["s_" + j.name].min())
            from reportgen.style.numbers import fmt
            assert fmt(H, sig=4) in text, (j.name, fmt(H, sig=4))


@pytest.mark.parametrize("stem", ["articulated_compressor", "v_compressor"])
def test_outputs_said_parallel_only_when_their_groups_are(stem):
    """«их группы присоединены параллельно» was printed for the articulated-rod compressor, whose
    group (4,5) hangs on the master rod 2 of group (2,3)."""
    from notehelpers import paragraph_text
    from reportgen.report.sections import kinematics
    st = _study(stem)
    mech = st.mechanism
    groups = [g for g in st.structure.groups if "0" not in g.links and len(g.links) > 1]
    text = plain(paragraph_text(kinematics.build(st)))
    serial = [(g, j) for i, g in enumerate(groups) for later in groups[i + 1:] for j in mech.joints
              if len(set(j.links) & set(g.links)) == 1 and len(set(j.links) & set(later.links)) == 1]
    if serial:
        g, j = serial[0]
        link = next(l for l in j.links if l in g.links)
        assert "присоединены параллельно" not in text
        assert f"присоединена к звену {link} группы ({','.join(g.links)})" in text
    else:
        assert "их группы присоединены параллельно" in text


@pytest.mark.parametrize("stem", ["articulated_compressor", "ws000_six_bar", "jaw_crusher"])
def test_point_a_later_group_hangs_on_is_found_by_similarity(stem):
    """«V_EA = ω₂·l_AE — величина находится построением» for the master rod's pin E: E is not found
    by intersecting lines but, once ω₂ and ε₂ are known, by the similarity theorem. A pair of the
    group's own links at the same point (the crusher's compound hinge B) is still constructed."""
    from notehelpers import paragraph_text
    from reportgen.report.sections import kinematics
    st = _study(stem)
    mech = st.mechanism
    text = plain(paragraph_text(kinematics.build(st)))
    groups = [g for g in st.structure.groups if "0" not in g.links and len(g.links) > 1]
    expected = []
    for i, g in enumerate(groups):
        later = {l for h in groups[i + 1:] for l in h.links}
        for j in mech.joints:
            inner = [l for l in j.links if l in g.links]
            if len(inner) == 1 and set(j.links) - set(inner) <= later and set(j.links) - set(inner):
                own = any(k.point == j.point and set(k.links) <= set(g.links) for k in mech.joints)
                expected.append((inner[0], j.point, own))
    assert expected
    for link, p, own in expected:
        phrase = f"по найденной ω{link}: точка {p.lower()} плана — по теореме подобия"
        assert (phrase in text) != own, (link, p, own)


def test_lever_crank_couple_on_the_balancing_force_line_readable(captured):
    """The knuckle press in its coining position: the crank's inertia couple M′_Φ1 (9 Н at a, ⊥ pa)
    lies on the line of F_ур; F_ур's label, placed last, took a leader through M′_Φ1's label."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes import labels as L
    from reportgen.scenes.forces import ZhukovskyLever
    st = _study("knuckle_press")
    lab = chosen_position(st)
    drawing = ZhukovskyLever(lab).draw(st)
    texts = [t.get_text() for fig in captured for ax in fig.axes for t in ax.texts]
    assert any("Phi 1" in t and "M" in t for t in texts)          # the couple is drawn
    assert any("ур" in t for t in texts)
    for fig in captured:
        assert L.check_figure(fig) == []
    m = drawing.moments
    assert list(m["balancing"].astype(bool)) == sorted(m["balancing"].astype(bool))   # F_ур last in the table


def test_prismatic_reaction_arm_says_from_which_point():
    """Table 4.3 printed «h = −0,02553 м» for the rod's reaction with no word of where h is
    measured from: the reaction acts h = M/N from the slider's point along the guide (the point
    the forces table gives as xN, yN)."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.report.sections.forces import _prismatic_text
    from reportgen.style.numbers import fmt
    st = _study("rocking_cylinder")
    f = st.forces
    lab = chosen_position(st)
    det = f.details(lab)
    row = f.row(lab)
    kin = st.kinematics[st.kinematics["pos"] == lab].iloc[0]
    for k, p in enumerate(f.model.pairs):
        pv = det["pairs"][k]
        text = _prismatic_text(p, pv)
        if "h\u00a0=" not in text:
            continue
        # independent: the distance from the slider's point to the reaction's point of application
        d = float(np.hypot(row[f"xN_{p.name}"] - kin[f"x_{p.point}"], row[f"yN_{p.name}"] - kin[f"y_{p.point}"]))
        assert fmt(abs(pv["Mp"] / pv["N"]), sig=4) == fmt(d, sig=4)
        assert f"от точки {p.point} вдоль направляющей" in text
