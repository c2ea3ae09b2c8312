"""Defects session 11 saw and left (#9, session 12 «leftovers3»), each test failing on the defect.

* ws002's conclusion and table of fitted sizes wrote the conditions in the case's own names
  («y₅₆ = Y_P56», «φ₆ = φ_P6»); the PDF-identifier test now catches such names with a subscript.
* The hacksaw's guide reaction R₀₃ drawn at B while the table gives its arm h.
* The rocker cam's arm drawn whole in position 0 only.
* The train scheme without the frame's bearings.
* The loom beater advised reversing the crank for a short end-of-stroke load.
* The key: a rocker's mean speeds called v; no reactions at the chosen position; «ω(f)».
* `check` printed «в группе 4_5»; the train's direct ratio «−28,58333333».
"""
import re

from markupsafe import Markup

from conftest import CASES

_STUDIES: dict = {}


def _study(stem):
    from reportgen import load_case
    if stem not in _STUDIES:
        _STUDIES[stem] = load_case(CASES / f"{stem}.toml")
    return _STUDIES[stem]


# ------------------------------------------------------------------ 1. fitted sizes
def test_fit_conditions_by_title_and_value():
    """S_p is fitted so that y₅₆ = Y_P56 and l₇ so that φ₆ = φ_P6: the conclusion writes «высота
    шарнира 56 в рабочем положении y₅₆ = 0,4 м», «угол навесной машины … φ₆ = 90°» — the
    parameter's title and value as the given-data table writes them, not the case's name."""
    from reportgen.report.sections.structure import conclusion_lines
    study = _study("ws002_tractor_hitch")
    text = Markup(conclusion_lines(study)[1]).striptags().replace("\xa0", " ")
    assert "P56" not in text and "P6" not in text
    assert "(условие: высота шарнира 56 в рабочем положении y56 = 0,4 м, при Sp)" in text
    assert "(условие: угол навесной машины в рабочем положении φ6 = 90°, при Sp)" in text
    assert "(условие y56 = 0,2 м при Smin)" in text


def test_fit_table_by_value():
    """The table «Подобранные размеры» writes the same conditions with values (y₅₆ = 0,4 м)."""
    from reportgen.report.sections.common import fit_condition
    study = _study("ws002_tractor_hitch")
    cells = [Markup(c).striptags().replace("\xa0", " ") for f in study.fits for c in fit_condition(study, f)[:1]]
    assert cells == ["y56 = 0,2 м", "y56 = 0,4 м", "φ6 = 90°"]


def test_case_notation_found_in_text():
    """The PDF-identifier test of every case also catches a case's name rendered with a
    subscript («yP56» in pdftotext's text) outside its row of the given data."""
    from test_note_all_cases import case_notation, notation_hits
    path = CASES / "ws002_tractor_hitch.toml"
    assert set(case_notation(path)) == {"yP56", "φP6"}
    given = "высота шарнира 56 в рабочем положении                       yP56              0,4 м"
    assert notation_hits(path, given) == []
    assert notation_hits(path, given + "\nSp = 0,4694 м (условие y56 = yP56 при Sp)") != []


# ------------------------------------------------------------------ 8. CLI messages
def test_check_names_groups_as_the_note(capsys):
    """`check` warned «угол передачи в группе 4_5» (the program's key of the flag): the group is
    named as the note names it, «в группе (4,5)», and numbers have a decimal comma."""
    from reportgen.cli import main
    assert main(["check", str(CASES / "rocker_slider_lever.toml")]) == 0
    out = capsys.readouterr()
    assert "угол передачи в группе (4,5) падает до 33,6°" in out.err
    assert re.findall(r"\b\w+_\w+\b", out.err) == []


# ------------------------------------------------------------------ 9. train: decimals
def test_train_direct_ratio_as_the_rest_of_the_note():
    """The direct check of the ratio printed «u = −28,58333333» (ten significant digits) while the
    note writes the ratio −343/12 = −28,58333 everywhere else (seven)."""
    from notehelpers import paragraph_text, plain
    from reportgen.report.sections import train
    study = _study("train_2kh_external_select")
    text = plain(paragraph_text(train.build(study)))
    direct = re.search(r"Прямой расчёт по равенству скоростей в полюсах даёт u = (−?\d+(?:,\d+)?)", text)
    assert direct and direct.group(1) == "−28,58333"
    assert len(re.sub(r"\D", "", direct.group(1))) <= 7


# ------------------------------------------------------------------ 7. the key
def _key_tables(stem):
    from notehelpers import blocks
    from reportgen.report.document import Table
    from reportgen.report.key import build_key
    out = {}
    for sec in build_key(_study(stem)).sections:
        for b in blocks(sec):
            if isinstance(b, Table):
                out[b.id] = b
    return out


def test_key_rocker_mean_speed_is_angular():
    """The loom beater's output is a rocker: its mean speed of the working stroke is in рад/с and
    is called an angular velocity ω, not «средняя скорость … v»."""
    from reportgen.report.key import result_rows
    study = _study("loom_beater")
    rows = [r for g in result_rows(study, "kinematics", study.scalars).values() for r in g]
    speed = {str(r["name"]): (str(r["sym"]), r["unit"]) for r in rows if "рабочего хода" in str(r["name"])}
    assert speed == {"Средняя угловая скорость рабочего хода": ("ω<sub>р.х</sub>", "рад/с")}
    back = [r for r in rows if "обратного хода" in str(r["name"])]
    assert [str(r["sym"]) for r in back] == ["ω<sub>х.х</sub>"]


def test_key_slider_mean_speed_stays_linear():
    from reportgen.report.key import result_rows
    study = _study("ws000_six_bar")
    rows = [r for g in result_rows(study, "kinematics", study.scalars).values() for r in g]
    assert [(str(r["sym"]), r["unit"]) for r in rows if "рабочего хода" in str(r["name"])] == \
        [("<i>v</i><sub>р.х</sub>", "м/с")]


def test_key_reactions_at_the_chosen_position():
    """The key holds the reactions at the position the note analyses group by group (the rows a
    teacher compares with a student's tables), to the decimals of the note's tables."""
    from reportgen.report.sections.common import chosen_position, pos_no
    study = _study("ws000_six_bar")
    tab = _key_tables("ws000_six_bar")["key-react-chosen"]
    lab = chosen_position(study)
    assert f"(положение {pos_no(study, lab)})" in tab.caption
    f = study.forces
    row = f.table[f.table["pos"].astype(str) == lab].iloc[0]
    assert [Markup(p).striptags() for p in tab.data["pair"]] == ["R01", "R12", "R23", "R03", "R34", "R45", "R05"]
    assert list(tab.data["R"]) == [row["R_" + k] for k in ("0_1", "1_2", "2_3", "0_3", "3_4", "4_5", "0_5")]


def test_key_printed_values_by_position_number():
    """ws000's printed-values table kept the worksheet's «ω(f)»: the key names the position by the
    note's number, «ω (положение 12)»."""
    tab = _key_tables("ws000_six_bar")["tab-dyn-printed"]
    names = [Markup(n).striptags().replace("\xa0", " ") for n in tab.data["name"]]
    assert not [n for n in names if "(f)" in n]
    assert "ω (положение 12)" in names and "J2пр (положение 12)" in names


# ------------------------------------------------------------------ 6. the advice to reverse the crank
def test_short_end_of_stroke_load_gets_no_reversing_advice():
    """The loom's beat-up force acts over the last 23 % of the fast stroke: the note advised turning
    the crank the other way (a slow working stroke), which gains nothing for a short load; now it
    says why the direction is kept, in the section and not in the conclusion."""
    from notehelpers import paragraph_text, plain
    from reportgen.report.sections import kinematics as K
    study = _study("loom_beater")
    assert 0 < K._working_share(study) < K.SHORT_LOAD_SHARE
    text = plain(paragraph_text(K.build(study)))
    assert "целесообразно вращать" not in text
    assert "лишь на 23\u00a0% его (36° поворота кривошипа из 154,6°)" in text
    assert not [l for l in K.conclusion_lines(study) if "предпочтительнее" in str(l)]


def test_load_over_the_whole_stroke_keeps_the_advice():
    """A slotting machine's cutting force acts over its whole (fast) working stroke: the advice stays."""
    from notehelpers import paragraph_text, plain
    from reportgen.report.sections import kinematics as K
    study = _study("slotting_machine")
    assert K._working_share(study) > 0.99
    assert "целесообразно вращать" in plain(paragraph_text(K.build(study)))


# ------------------------------------------------------------------ 2. a guide's reaction at its arm
def test_guide_reaction_drawn_where_the_text_puts_it(monkeypatch):
    """The hacksaw's table gives R₀₃ with «h = M/N = −0,1665 м — смещение точки приложения от
    точки B вдоль направляющей», but the group's scheme drew R₀₃ at B: it is drawn at B + h·u
    (u along the guide), with the guide's line from B to it marked h."""
    import numpy as np
    from notehelpers import record_labels
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import GroupForces, group_vectors
    study = _study("power_hacksaw")
    f = study.forces
    lab = chosen_position(study)
    row = f.table[f.table["pos"].astype(str) == lab].iloc[0]
    pri = [p for p in f.model.pairs if p.name == "0_3"]
    assert pri, [p.name for p in f.model.pairs]
    ext, _, _ = group_vectors(study, lab, 0)
    r03 = next(v for v in ext if v.label == "R₀₃")
    assert abs(row["hN_0_3"]) > 0.1
    assert np.allclose(r03.at, (row["xN_0_3"], row["yN_0_3"]), atol=1e-12)
    assert np.allclose(r03.base, (study.kinematics.set_index("pos").loc[lab, ["x_B", "y_B"]]
                                  .to_numpy(float)), atol=1e-12)
    seen = record_labels(monkeypatch)
    GroupForces(lab, 0, landscape=True).draw(study)
    assert "$h$" in seen


# ------------------------------------------------------------------ 4. the rocker cam's drawing
def test_rocker_cam_arm_whole_in_both_extreme_positions():
    """The roller rocker's arm was drawn whole (with its pivot) in position 0 only: it is drawn so
    in both extreme positions (0: ψ = 0, 2: the far dwell, ψ_max), with the arc of the pivot's
    positions in the inverted motion; a piece at the roller in the middle positions."""
    from reportgen.scenes.cam import ProfileDrawing
    study = _study("cam_rocker_roller")
    d = ProfileDrawing()
    d.draw(study)
    assert [len(seg["circles"]) for seg in d.followers] == [2, 1, 2, 1]      # pivot + roller, or roller
    import math
    a_w = math.hypot(*study.cam.synthesis.O)
    pivots = [seg["circles"][0][0] for seg in d.followers if len(seg["circles"]) == 2]
    assert all(abs(math.hypot(*p) - a_w) < 1e-12 for p in pivots)


# ------------------------------------------------------------------ 5. the train scheme's bearings
def test_train_scheme_draws_the_frame_bearings(monkeypatch):
    """The train's scheme had no supports: every moving member on the central axis (the central
    wheel 1, the carrier H) runs in a bearing of the frame (ГОСТ 2.770), the fixed wheel 3 has none."""
    from reportgen.scenes import train as T
    study = _study("train_2kh_external_select")
    m = study.train.model
    colors = {T.COLORS[i % len(T.COLORS)]: n for i, n in enumerate(m.members)}
    calls = []
    orig = T._bearing

    def rec(ax, x, dx, R, color):
        calls.append((ax, colors[color]))
        return orig(ax, x, dx, R, color)
    monkeypatch.setattr(T, "_bearing", rec)
    T.train_picture(study.train)
    assert sorted(_final_scheme(calls)) == ["1", "H"]


def _final_scheme(calls: list) -> list:
    """The members whose bearings the picture's scheme draws: the calls on the last axes (the
    trial schemes of ``disc_sides``, which choose the side of the rings' discs, are not shown)."""
    return [n for ax, n in calls if ax is calls[-1][0]]


def test_nested_carriers_one_frame_bearing(monkeypatch):
    """Two carriers one inside the other: the outer one runs in the frame, the inner in it."""
    from reportgen.scenes import train as T
    study = _study("train_two_carrier_select")
    m = study.train.model
    colors = {T.COLORS[i % len(T.COLORS)]: n for i, n in enumerate(m.members)}
    calls = []
    orig = T._bearing
    monkeypatch.setattr(T, "_bearing", lambda ax, x, dx, R, color: (calls.append((ax, colors[color])),
                                                                    orig(ax, x, dx, R, color)))
    T.train_picture(study.train)
    seen = _final_scheme(calls)
    carriers = [n for n in seen if n in set(m.axes.values())]
    assert len(carriers) == 1 and len(seen) == len(set(seen))


def test_rocker_cam_text_names_the_whole_arm():
    from notehelpers import paragraph_text, plain
    from reportgen.report.sections import cam
    text = plain(paragraph_text(cam.build(_study("cam_rocker_roller"))))
    assert "в крайних положениях 0 и 2 — целиком, с опорой" in text
