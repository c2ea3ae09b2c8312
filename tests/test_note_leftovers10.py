"""Defects session 9 saw and left (#9, session 10 «leftovers»), each test failing on the defect:

* ε₃ of the rocking cylinder read off a 5 mm a^τ vector is 8,7 % off the analytic value while the
  comparison tables print neither ω nor ε and the text says the largest discrepancy is under 1 %:
  the tables now hold the ω and ε the note derives from the plans, and a discrepancy over the
  allowed 5 % is stated with the short segment's error in mm (the accuracy of the drawing).
"""
import math

import pytest

from conftest import CASES
from notehelpers import blocks, plain

_STUDIES: dict = {}
_SECTIONS: dict = {}


def _study(stem):
    from reportgen import load_case
    if stem not in _STUDIES:
        _STUDIES[stem] = load_case(CASES / f"{stem}.toml")
    return _STUDIES[stem]


def _kinematics(stem):
    from reportgen.report.sections import kinematics as K
    if stem not in _SECTIONS:
        _SECTIONS[stem] = K.build(_study(stem))
    return _SECTIONS[stem]


def _block(sec, id_):
    return next(b for b in blocks(sec) if getattr(b, "id", None) == id_)


# ------------------------------------------------------------------ ω and ε in the comparison tables
@pytest.mark.parametrize("stem", ["rocking_cylinder", "ws000_six_bar"])
def test_comparison_tables_hold_the_omega_and_epsilon_read_off_the_plans(stem):
    """Every ω and ε the note finds from a plan segment of at least MIN_MM is a row of its plan's
    comparison table (segment read to 0,5 mm, between two points of the link); its «аналитически»
    is the kinematics table's |ω|, |ε| and its discrepancy the one of those two numbers."""
    from reportgen.analysis.plans import READ_MM
    from reportgen.report.sections import kinematics as K
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.plans import MIN_MM
    st = _study(stem)
    sec = _kinematics(stem)
    row = st.kinematics[st.kinematics["pos"] == chosen_position(st)].iloc[0]
    seen = set()
    for tab_id, kind, col in (("tab-vplan", "omega", "w_"), ("tab-aplan", "eps", "e_")):
        tab = _block(sec, tab_id)
        reads = tab.data[tab.data["kind"] == kind]
        assert len(reads), (stem, tab_id)
        for r in reads.itertuples():
            link = r.link
            _, _, seg, rq = r.name.split(":")
            # the segment is one of the link's own (l between two of its points)
            pts = st.mechanism.link(link).points
            assert any(a + b == rq for a in pts for b in pts if a != b), (r.name, list(pts))
            assert r.mm >= MIN_MM and abs(r.mm / READ_MM - round(r.mm / READ_MM)) < 1e-9
            assert r.analytic == pytest.approx(abs(row[col + link]), rel=1e-12)
            assert r.delta == pytest.approx(abs(r.graphic - r.analytic) / r.analytic * 100, rel=1e-9)
            seen.add((kind, link))
            assert plain(K._vec_name(r.name)).endswith(", рад/с" if kind == "omega" else ", рад/с²")
    assert {k for k, _ in seen} == {"omega", "eps"}


def test_rocking_cylinder_epsilon_discrepancy_is_stated_with_its_short_segment():
    """ε₃ is read off a^τ_KC, about 5 mm long: its discrepancy (over 5 %) is the largest of the
    acceleration table, the text says so and gives the segment's error in mm against its exact
    length (|ε₃|·l_CK/μ_a), not «наибольшее расхождение … 0,93 %»."""
    from reportgen.report.document import Paragraph
    from reportgen.style.numbers import fmt, fmt_pct
    st = _study("rocking_cylinder")
    sec = _kinematics("rocking_cylinder")
    tab = _block(sec, "tab-aplan").data
    eps = tab[tab["kind"] == "eps"]
    worst = tab.loc[tab["delta"].idxmax()]
    assert worst["kind"] == "eps" and worst["delta"] > 5.0
    text = plain(next(b.html for b in blocks(sec) if isinstance(b, Paragraph) and "Наибольшее" in b.html))
    assert f"по ускорениям {plain(fmt_pct(worst['delta'] / 100))}" in text
    assert "ограничена чертежом" in text
    assert plain(fmt(worst["mm"], digits=1)) + "\u00a0мм" in text
    assert plain(fmt(abs(worst["mm"] - worst["mm_exact"]), digits=2)) + "\u00a0мм" in text
    assert len(eps) >= 1


def test_no_drawing_limit_remark_when_every_discrepancy_is_allowed():
    """ws000's plans agree within 5 %: no remark on the drawing's accuracy."""
    from reportgen.report.document import Paragraph
    sec = _kinematics("ws000_six_bar")
    for id_ in ("tab-vplan", "tab-aplan"):
        assert _block(sec, id_).data["delta"].max() <= 5.0
    assert "ограничена чертежом" not in " ".join(b.html for b in blocks(sec) if isinstance(b, Paragraph))


# ------------------------------------------------------------------ the quick-return sentence fits the machine
def _resistance_by_stroke(st):
    """−∫ min(ΣM, 0) dφ over the crank angles where the output moves one way and the other
    (split by the sign of the output's analog, not by the extreme positions)."""
    import numpy as np
    from reportgen.analysis.plans import output_quantity
    cyc = st.dynamics.cycle
    q = cyc["q"].to_numpy()
    m = np.minimum(sum(cyc["M_" + ld.name].to_numpy() for ld in st.dynamics.loads.loads if ld.kind != "weight"), 0)
    out = output_quantity(st)[0]
    v = np.gradient(st.cycle[out].to_numpy(), st.cycle["q"].to_numpy())
    v = np.interp(q, st.cycle["q"].to_numpy(), v)
    dq = np.gradient(q)
    return float(-(m * dq)[v > 0].sum()), float(-(m * dq)[v <= 0].sum())


@pytest.mark.parametrize("stem,idle", [("articulated_compressor", False), ("ws000_six_bar", True)])
def test_quick_return_sentence_calls_a_loaded_return_stroke_not_idle(stem, idle):
    """A compressor's suction stroke has gas forces too: no «холостой» stroke and no cycle-time
    claim; ws000's return stroke has no resistance: «холостой … сокращает время цикла» stays."""
    from reportgen.report.document import Paragraph
    st = _study(stem)
    a, b = sorted(_resistance_by_stroke(st))
    assert (a < 0.02 * b) == idle, (a, b)
    text = plain(" ".join(p.html for p in blocks(_kinematics(stem)) if isinstance(p, Paragraph)
                          and "Один ход выходного звена" in p.html))
    assert "раза быстрее" in text
    assert ("холостой" in text) == idle and ("время цикла" in text) == idle, text
    if not idle:
        assert "обратный выполняется" in text


# ------------------------------------------------------------------ the cylinder symbol
def _patches_mm(ax):
    """Every Polygon/Rectangle patch of the axes as its vertices in data coordinates."""
    from matplotlib.patches import Polygon, Rectangle
    out = []
    for p in ax.patches:
        if isinstance(p, (Polygon, Rectangle)):
            v = p.get_transform().transform(p.get_path().vertices)
            out.append((type(p).__name__, ax.transData.inverted().transform(v)))
    return out


@pytest.mark.parametrize("scene", ["scheme", "groups", "positions"])
def test_rocking_cylinder_drawn_as_cylinder_with_piston_and_rod(scene, captured):
    """symbol = "cylinder": no block at the rod's pin A; a body (4-corner polygon) as long as the
    cylinder from its pivot C to its end K, and the rod drawn from A to the piston point P."""
    import numpy as np
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.mechanism import AssurGroups, KinematicScheme, PositionsPlan
    st = _study("rocking_cylinder")
    mech = st.mechanism
    j = next(j for j in mech.prismatic if j.links[0] != "0")
    assert j.cylinder
    lab = chosen_position(st)
    row = st.kinematics[st.kinematics["pos"] == lab].iloc[0]
    drawing = {"scheme": KinematicScheme(lab), "groups": AssurGroups(lab), "positions": PositionsPlan()}[scene]
    captured.clear()
    drawing.draw(st)
    fig = captured[0]
    P = lambda n: np.array([row[f"x_{n}"], row[f"y_{n}"]])
    l_ck, l_ap = np.linalg.norm(P("C") - P("K")), np.linalg.norm(P("A") - P("P"))
    found = False
    for ax in fig.axes:          # the groups: one axes per group, each at its own scale
        patches = _patches_mm(ax)
        # no slider block anywhere (a Rectangle is how a block is drawn)
        assert not any(kind == "Rectangle" for kind, _ in patches), patches
        # a body: a 4-corner polygon with two equal long sides, and the rod: a line from the
        # piston P to the pin A, in the ratio |AP| : |CK| to them
        longs = [np.sort(np.linalg.norm(np.diff(v[:4], axis=0, append=v[:1]), axis=1))[2:] for kind, v in patches
                 if kind == "Polygon" and len(v) in (4, 5)]
        longs = [s_[1] for s_ in longs if abs(s_[1] - s_[0]) < 1e-9 * s_[1]]
        lines = [np.column_stack(l.get_data()).astype(float) for l in ax.lines]
        rods = [np.linalg.norm(l[1] - l[0]) for l in lines if len(l) == 2]
        found |= any(abs(r * l_ck / L - l_ap) < 1e-6 * l_ap for L in longs for r in rods)
    assert found, scene


def test_cylinder_symbol_on_a_frame_guide_is_a_case_error(tmp_path):
    """symbol = "cylinder" names a pair of two moving links; on the frame it is a CaseError with
    the key, not a drawing of something else."""
    from reportgen import load_case
    from reportgen.errors import CaseError
    text = (CASES / "slider_crank.toml").read_text(encoding="utf-8")
    import re
    m = re.search(r'(\[\[joints\]\]\s*\ntype = "P"[^\[]*)', text)
    assert m, "slider_crank.toml has a prismatic pair"
    bad = text.replace(m.group(1), m.group(1).rstrip() + '\nsymbol = "cylinder"\n\n', 1)
    f = tmp_path / "bad.toml"
    f.write_text(bad, encoding="utf-8")
    with pytest.raises(CaseError) as e:
        load_case(f).mechanism
    assert "symbol" in str(e.value)


# ------------------------------------------------------------------ the toggle's force amplification
def test_knuckle_press_toggle_gain_is_the_crank_over_the_output_analog():
    """The gain F·r/M of the coining force over its largest-force stretch equals, by the power
    balance F·v_D = M·ω, the least of r/|y′_D| there (the output's analog, kinematics alone), to
    the 0,1 % by which F may fall short of F_max on that stretch."""
    import numpy as np
    from reportgen.report.sections.dynamics import toggle_gain
    st = _study("knuckle_press")
    t = toggle_gain(st)
    assert t is not None and t["load"].name == "Pч"
    cyc = st.cycle
    r = float(np.hypot(cyc["x_A"] - cyc["x_O"], cyc["y_A"] - cyc["y_O"]).iloc[0])
    cols = {c: cyc[c].to_numpy() for c in cyc.columns}
    Fx, Fy = t["load"].force(cols, st.dynamics.loads.phase({"q": cols["q"]}))
    F = np.hypot(Fx, Fy)
    zone = F >= 0.999 * F.max()
    g_kin = float(np.min(r / np.abs(cols["vqy_D"][zone])))
    # F within 0,1 % of F_max over the stretch: F_max·r/max(F·|y′|) lies between it and it/0,999
    assert g_kin * (1 - 1e-9) <= t["gain"] <= g_kin / 0.999
    assert t["gain"] > 5


@pytest.mark.parametrize("stem,has", [("knuckle_press", True), ("ws000_six_bar", False),
                                      ("articulated_compressor", False)])
def test_toggle_remark_in_the_note_only_for_a_toggle(stem, has):
    """The remark (dynamics §«Приведённые моменты сил» and the conclusion) for the knuckle press;
    not for a shaper-like six-bar (gain under 1) nor a compressor (its gas force peaks only at the
    dead centre, a spike, not a working stretch)."""
    from reportgen.report.document import Paragraph
    from reportgen.report.sections import dynamics as D
    st = _study(stem)
    sec = D.build(st)
    text = plain(" ".join(b.html for b in blocks(sec) if isinstance(b, Paragraph)))
    concl = plain(" ".join(D.conclusion_lines(st)))
    assert ("выигрыш в силе" in text) == has and ("выигрыш в силе" in concl) == has
    if has:
        from reportgen.style.numbers import fmt
        t = D.toggle_gain(st)
        assert plain(fmt(t["gain"], sig=3)) in text and "&lt;" not in text and "&lt;" not in concl


# ------------------------------------------------------------------ a flat plan keeps the portrait page
def test_flat_velocity_plan_of_ws000_stays_on_the_portrait_page():
    """ws000's velocity plan would be 194 × 47 mm on a landscape page of its own (under half its
    height): it is drawn on the portrait page at its portrait scale, and every plan that does go
    landscape fills at least LANDSCAPE_FILL of that page's height."""
    import numpy as np
    from reportgen.analysis.plans import velocity_plan
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.mechanism import LANDSCAPE_GAIN, LANDSCAPE_H
    from reportgen.scenes.plans import LANDSCAPE_FILL, MARGIN_MM, PlanScene, page_scale, plan_scale
    st = _study("ws000_six_bar")
    lab = chosen_position(st)
    row = st.kinematics[st.kinematics["pos"] == lab].iloc[0]
    plan = velocity_plan(row, st.mechanism)
    mu_p, mu_l = plan_scale(plan), plan_scale(plan, landscape=True)
    assert mu_p >= LANDSCAPE_GAIN * mu_l            # the gain alone would take a landscape page
    pts = np.array([[0.0, 0.0]] + [list(v) for v in plan.tips.values()])
    assert np.ptp(pts[:, 1]) / mu_l < LANDSCAPE_FILL * (LANDSCAPE_H - 2 * MARGIN_MM)
    assert page_scale(plan) == (mu_p, False)
    d = PlanScene(lab, "velocity", landscape=True).draw(st)
    assert not d.landscape and d.mu == mu_p


# ------------------------------------------------------------------ the lever's arrowheads clear of other shafts
def test_ws000_lever_heads_clear_of_other_arrows_shafts(captured):
    """On ws000's Жуковский lever no arrowhead lies on another arrow's shaft (G₄'s head sat on
    P_пс's): the head (HEAD_LEN_MM back from the tip) keeps HEAD_CLEAR_MM from the shaft of every
    arrow drawn from another point, measured on the drawn figure."""
    import numpy as np
    from notehelpers import arrows_mm
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import HEAD_CLEAR_MM, HEAD_LEN_MM, ZhukovskyLever, _seg_gap
    st = _study("ws000_six_bar")
    captured.clear()
    ZhukovskyLever(chosen_position(st)).draw(st)
    arrows = [(a, b) for a, b in arrows_mm(captured[0]) if np.hypot(*(b - a)) > HEAD_LEN_MM]
    assert len(arrows) > 5
    bad = []
    for i, (a, b) in enumerate(arrows):
        u = (b - a) / np.hypot(*(b - a))
        for j, (c, d) in enumerate(arrows):
            if i == j or np.hypot(*(a - c)) < 0.05:
                continue
            v = (d - c) / np.hypot(*(d - c))
            g = _seg_gap(b - u * HEAD_LEN_MM, b, c, d - v * HEAD_LEN_MM)
            if g < HEAD_CLEAR_MM - 0.05:
                bad.append((i, j, round(g, 2)))
    assert not bad, bad


# ------------------------------------------------------------------ a label may interrupt more thin lines
def test_conveyor_S2_label_near_its_point_on_the_plan_of_positions(captured):
    """The plan of positions of the conveyor: the thin lines of the other positions are many
    round S₂; a label may interrupt up to MAX_BREAKS of them (ГОСТ 2.307), so S₂'s label sits
    within 7 mm of its point (it was 12 mm off, beyond the bold lines)."""
    import numpy as np
    from reportgen.scenes.mechanism import PositionsPlan
    st = _study("conveyor_four_bar")
    captured.clear()
    PositionsPlan().draw(st)
    fig = captured[0]
    ax = fig.axes[0]
    row = st.kinematics.iloc[0]
    r = fig.canvas.get_renderer()
    px_mm = fig.dpi / 25.4
    t = next(t for t in ax.texts if t.get_text() == "$S_{2}$")
    bb = t.get_window_extent(r)
    p = ax.transData.transform((row["x_S2"], row["y_S2"]))
    gap = np.hypot(max(bb.x0 - p[0], 0, p[0] - bb.x1), max(bb.y0 - p[1], 0, p[1] - bb.y1)) / px_mm
    assert gap < 7.0, gap
