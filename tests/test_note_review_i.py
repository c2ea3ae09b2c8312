"""Defects found reviewing, page by page as a ТММ teacher, the cam and gear chapters on four variants
new to cases/ (session 10, #9): a translating knife-edge follower with a trapezoidal acceleration
rise and an asymmetric parabolic return (ν = 2) turning clockwise (cam_translating_knife_trapezoid),
a roller rocker with a 35° swing (cam_rocker_roller_wide), a gear pair z₁ = 14 with unequal given
shifts (gear_pair_unequal_shift) and a pair with a required centre distance a_w
(gear_pair_center_distance).  Each test fails on what the review found:

* «На удалении — закон трапецеидальный закон ускорения» (the law's name already says «закон»);
* |s′|max of the asymmetric parabolic law printed as h·1,9995/β: a maximum sampled on a grid
  misses the kink of f′ at x₁ (the closed form is 2 for every ν);
* the profile coordinates x = e cos φ + … «(при вращении по часовой стрелке знаки при sin φ
  меняются)» — for a cw cam the table's x_C(0) = −e contradicts the printed formula;
* the knife-edge table's note explains columns x, y the table does not have;
* the rocker's profile drawing cut the rollers of positions 2 and 3 at the sheet's edge;
* «жёстких — 0, мягких — 3»: the impacts without the angles where they occur;
* ϑ_max = 30,000° next to [ϑ] = 30,00°;
* gears: «s_a = d_a(…) = 2,165; 3,737 мм» — one formula, two results, no numbers substituted, and
  d_a2 never computed;
* the geometry table's rows mix decimals (d_a 84,4701 | 135,470);
* «μ_l = 0,000400 м/мм» where ГОСТ 2.302 writes 2,5:1, and ``gost_ratio`` printed 2,5:1 as «2:1»;
* with a required a_w the note computes a_w from the shifts (circular): α_w and x_Σ from a_w are
  never written, the blocking contour lacks the line x₁ + x₂ = x_Σ, and the rule says «выбраны
  программой»; given shifts are labelled «выбрано»;
* the conclusion gives a_w, α_w, ε_α and no judgement (undercut, tips, ε_α vs its allowed value,
  the wear of the feet by λ at B₁ and B₂).
"""
import math
import re

import numpy as np
import pytest

from conftest import CASES
from notehelpers import blocks, plain

_STUDIES: dict = {}
CAMS = ("cam_translating_knife_trapezoid", "cam_rocker_roller_wide", "cam_translating_roller", "cam_rocker_roller",
        "ws001_cam_2013_2")
GEARS = ("gear_pair_unequal_shift", "gear_pair_center_distance", "gear_pair_shifted", "gear_pair_internal")


def _study(stem):
    from reportgen import load_case
    if stem not in _STUDIES:
        _STUDIES[stem] = load_case(CASES / f"{stem}.toml")
    return _STUDIES[stem]


def _section(stem, module):
    key = (stem, module.__name__)
    if key not in _STUDIES:
        _STUDIES[key] = module.build(_study(stem))
    return _STUDIES[key]


def _paragraphs(sec) -> list[str]:
    from reportgen.report.document import Paragraph
    return [plain(b.html) for b in blocks(sec) if isinstance(b, Paragraph)]


def _formulas(sec) -> list:
    from reportgen.report.document import FormulaBlock
    return [f for b in blocks(sec) if isinstance(b, FormulaBlock) for f in b.formulas]


def _num(tex: str) -> float:
    """The first number of a LaTeX result («3{,}019\\ \\text{мм}» → 3.019)."""
    m = re.search(r"-?\d+(?:\{,\}\d+)?", tex.replace(r"\,", ""))
    return float(m.group(0).replace("{,}", "."))


# ------------------------------------------------------------------ cams
@pytest.mark.parametrize("stem", CAMS)
def test_law_sentence_says_zakon_once(stem):
    """The law's Russian name may itself hold «закон» (трапецеидальный закон ускорения): the
    sentence naming it must not say «закон … закон» with one word between."""
    from reportgen.report.sections import cam
    for p in _paragraphs(_section(stem, cam)):
        assert not re.search(r"\bзакон\s+\S+\s+закон", p, re.I), p


@pytest.mark.parametrize("stem", CAMS)
def test_analog_maxima_are_exact(stem):
    """|s′|max and |s″|max of each phase are the exact extremes: not below any value of a dense
    independent sampling, and for the parabolic law (any ν) the closed form C_v = 2 (the velocity
    analog is a triangle of unit area over a unit base)."""
    st = _study(stem)
    cam = st.cam
    for ph in (cam.rise, cam.ret):
        g = ph.start + np.linspace(0.0, ph.length, 4001)
        v = cam.law(g)
        for order in (1, 2):
            got = cam.analog_max(ph, order)
            assert got >= np.abs(v[order]).max() * (1 - 1e-12)
        if ph.law == "parabolic":
            assert cam.analog_max(ph, 1) * ph.length / cam.h == pytest.approx(2.0, rel=1e-12)


def test_asymmetric_parabolic_law_prints_its_closed_form_coefficient():
    """The note prints h·C_v/β with C_v = 2,0000 for the ν = 2 parabolic return (was 1,9995)."""
    from reportgen.report.sections import cam
    st = _study("cam_translating_knife_trapezoid")
    assert st.cam.ret.law == "parabolic" and st.cam.ret.nu != 1
    sub = [f.substituted for f in _formulas(_section("cam_translating_knife_trapezoid", cam))
           if f.symbolic.startswith("|s^{\\prime}|")]
    assert len(sub) == 2 and all("2{,}0000" in s for s in sub), sub


@pytest.mark.parametrize("stem", ("cam_translating_knife_trapezoid", "cam_translating_roller", "ws001_cam_2013_2"))
def test_inversion_formula_matches_the_table(stem):
    """The printed x(φ), y(φ) of the centre profile, evaluated with the case's e, s₀ (or s′, r₀ of a
    flat follower), give the table's coordinates at every table angle, whatever the rotation."""
    from reportgen.report.sections import cam
    st = _study(stem)
    c = st.cam
    f = next(f for f in _formulas(_section(stem, cam)) if f.label == "eq-cam-profile")
    assert "знаки" not in " ".join(_paragraphs(_section(stem, cam)))
    tex = f.symbolic.replace(r"\quad", "").replace(r"\cos\varphi", "*cos(p)").replace(r"\sin\varphi", "*sin(p)")
    flat = c.contact == "flat"
    lateral, base = (r"s^{\prime}", "r_0") if flat else ("e", "s_0")
    tex = tex.replace(lateral, "L").replace(base, "B")
    xs, ys = (part.split("=")[1] for part in tex.split(","))
    syn = c.synthesis
    df = c.profile_table()
    for _, row in df.iterrows():
        p = float(np.radians(row["phi_deg"]))
        s, s1 = (float(v[0]) for v in c.law(np.array([p]))[:2])
        env = dict(cos=math.cos, sin=math.sin, p=p, s=s, L=s1 if flat else syn.e, B=syn.r0 if flat else syn.s0)
        x, y = eval(xs, env), eval(ys, env)                     # noqa: S307  (the note's own formula)
        kx, ky = ("x", "y") if flat else ("x_c", "y_c")
        assert x == pytest.approx(row[kx], abs=1e-9) and y == pytest.approx(row[ky], abs=1e-9), (row["phi_deg"], x, y)


def test_knife_edge_table_note_names_only_its_columns():
    """A knife-edge follower's profile table has no x, y (its working profile is the centre one):
    the note under the table must not explain them."""
    from reportgen.report.document import Table
    from reportgen.report.sections import cam
    sec = _section("cam_translating_knife_trapezoid", cam)
    tab = next(b for b in blocks(sec) if isinstance(b, Table) and b.id == "tab-cam-coords")
    keys = {c.key for c in tab.columns}
    assert "x" not in keys
    assert not re.search(r"(^|; )x, y", plain(tab.note)), tab.note


@pytest.mark.parametrize("stem", ("cam_rocker_roller_wide", "cam_rocker_roller", "cam_translating_roller"))
def test_profile_drawing_holds_every_roller(stem):
    """Every roller (and pivot) drawn in the follower's positions lies wholly inside the drawing."""
    from reportgen.scenes.cam import ProfileDrawing
    d = ProfileDrawing()
    d.draw(_study(stem))
    (x0, x1), (y0, y1) = d.limits
    for seg in d.followers:
        for (cx, cy), r in seg["circles"]:
            assert x0 <= cx - r and cx + r <= x1 and y0 <= cy - r and cy + r <= y1, (stem, cx, cy, r)


@pytest.mark.parametrize("stem", CAMS)
def test_conclusion_names_the_impacts_where_they_occur(stem):
    """The conclusion names the angles of the impacts (no bare «— 0» count)."""
    from reportgen.report.sections import cam
    from reportgen.report.sections.common import as_written
    st = _study(stem)
    text = plain(" ".join(cam.conclusion_lines(st)))
    assert "— 0" not in text
    for imp in st.cam.impacts:     # at most two decimals, no padding zeros (session 12: 140°, 173,75°)
        assert as_written(round(math.degrees(imp["phi"]), 2)) + "°" in text, (imp, text)


@pytest.mark.parametrize("stem", ("cam_translating_knife_trapezoid", "cam_rocker_roller_wide"))
def test_pressure_maximum_and_allowed_value_share_decimals(stem):
    from reportgen.report.sections import cam
    p = next(p for p in _paragraphs(_section(stem, cam)) if "Наибольшие значения" in p and "ϑ" in p)
    decs = {len(m) for m in re.findall(r"=\s?\d+,(\d+)°", p)}
    assert len(decs) == 1, p


# ------------------------------------------------------------------ gears
@pytest.mark.parametrize("stem", GEARS)
def test_tip_thickness_written_per_wheel_with_numbers(stem):
    """s_a1 and s_a2 each in a formula of their own, with numbers substituted and the geometry's
    result; d_a2 of an external pair computed as d_a1 is."""
    from reportgen.report.sections import gears
    g = _study(stem).gears.geo
    fs = _formulas(_section(stem, gears))
    for i, sa in ((1, g.sa1), (2, g.sa2)):
        f = next(f for f in fs if f.symbolic.startswith(f"s_{{a{i}}}"))
        assert f.substituted and _num(f.result) == pytest.approx(float(sa), abs=6e-4)
    assert not any(";" in (f.result or "") and "s_a" in f.symbolic for f in fs)
    if not g.internal:
        f = next(f for f in fs if f.symbolic.startswith("d_{a2}"))
        assert _num(f.result) == pytest.approx(float(g.da2), rel=1e-5)


@pytest.mark.parametrize("stem", GEARS)
def test_geometry_table_rows_keep_one_number_of_decimals(stem):
    """The table has a row per quantity: along a row both wheels' numbers have the same decimals,
    counts (z, k) are whole."""
    from reportgen.report.document import Table
    from reportgen.report.sections import gears
    sec = _section(stem, gears)
    tab = next(b for b in blocks(sec) if isinstance(b, Table) and b.id == "tab-gears-geo")
    wheels = [c for c in tab.columns if c.key.startswith("wheel")]
    for i, key in enumerate(tab.data["key"]):
        vals = [c.format(v) for c in wheels if (v := tab.data[c.key].iloc[i]) is not None and v == v]
        decs = {len(v.split(",")[1]) if "," in v else 0 for v in vals}
        assert len(decs) <= 1 and (key not in ("z", "k") or decs <= {0}), (key, vals)


def test_gost_ratio_round_trips_every_standard_scale():
    """The scale written as ГОСТ 2.302 does, read back, is the scale (2,5:1 was printed «2:1»)."""
    from reportgen.scenes.draw import GOST_K, gost_ratio
    for mu in [k / 1000.0 for k in GOST_K] + [0.0004]:
        a, b = (float(v.replace(",", ".")) for v in gost_ratio(mu).split(":"))
        assert b / a / 1000.0 == pytest.approx(mu, rel=1e-12), gost_ratio(mu)


@pytest.mark.parametrize("stem", GEARS)
def test_mesh_drawn_at_a_gost_scale_written_as_gost_does(stem):
    from reportgen.report.sections import gears
    from reportgen.scenes import gears as S
    from reportgen.scenes.draw import GOST_K, gost_ratio
    gr = _study(stem).gears
    md = S.internal_mesh_drawing(gr) if gr.internal else S.mesh_drawing(gr)
    assert any(abs(md.mu - k) < 1e-9 for k in GOST_K), md.mu
    text = " ".join(_paragraphs(_section(stem, gears)))
    assert f"масштабе {gost_ratio(md.mu / 1000)}" in text
    assert not re.search(r"(?<!м)м/мм", text)    # μ in metres per mm was printed


def test_required_centre_distance_gives_alpha_w_and_x_sum_first():
    """With a_w given the note derives cos α_w = a cos α/a_w and x_Σ from it before the geometry,
    and the x_Σ printed is x₁ + x₂ of the pair."""
    from reportgen.report.sections import gears
    stem = "gear_pair_center_distance"
    gr = _study(stem).gears
    assert gr.a_w_required is not None
    fs = _formulas(_section(stem, gears))
    i_cos = next(i for i, f in enumerate(fs) if f.symbolic.startswith(r"\cos\alpha_w"))
    i_x = next(i for i, f in enumerate(fs) if f.symbolic.startswith(r"x_\Sigma"))
    i_inv = next(i for i, f in enumerate(fs) if f.symbolic.startswith(r"\mathrm{inv}\,\alpha_w"))
    assert i_cos < i_x < i_inv
    assert _num(fs[i_x].result) == pytest.approx(gr.x1 + gr.x2, abs=6e-5)
    assert math.degrees(math.acos(_num(fs[i_cos].result))) == pytest.approx(math.degrees(float(gr.geo.alpha_w)),
                                                                           abs=1e-3)


def test_contour_rule_in_a_students_words_and_the_a_w_line_drawn(captured):
    from reportgen.report.sections import gears
    from reportgen.scenes import gears as S
    stem = "gear_pair_center_distance"
    gr = _study(stem).gears
    text = " ".join(_paragraphs(_section(stem, gears)))
    assert "программ" not in text and "x<sub>Σ</sub>" not in text and "xΣ" in text.replace("\u00a0", "")
    fig = S.blocking_contour(gr)
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    line = next(t for t in legend if "x_1 + x_2" in t)
    assert "a_w" in line
    xs = float(gr.xsum_required)
    drawn = [ln for ln in fig.axes[0].lines if len(ln.get_xdata()) == 2
             and np.allclose(np.add(ln.get_xdata(), ln.get_ydata()), xs)]
    assert drawn


def test_given_shifts_are_labelled_given():
    from reportgen.report.document import Figure
    from reportgen.report.sections import gears
    from reportgen.scenes import gears as S
    stem = "gear_pair_unequal_shift"
    gr = _study(stem).gears
    assert not gr.chosen
    fig = S.blocking_contour(gr)
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert any(t.startswith("задано") for t in texts) and not any("выбрано" in t for t in texts)
    cap = next(b.caption for b in blocks(_section(stem, gears)) if isinstance(b, Figure) and b.id == "fig-gears-contour")
    assert "выбранной" not in cap


@pytest.mark.parametrize("stem", GEARS)
def test_checks_list_ends_with_a_full_stop(stem):
    from reportgen.report.sections import gears
    ul = next(p for p in _paragraphs(_section(stem, gears)) if "плавность" in p and "интерференция" in p)
    html = next(str(b.html) for b in blocks(_section(stem, gears)) if "<ul>" in str(getattr(b, "html", "")))
    items = re.findall(r"<li>(.*?)</li>", html)
    assert items[-1].endswith(".") and all(i.endswith(";") for i in items[:-1]), ul


@pytest.mark.parametrize("stem", GEARS)
def test_gear_conclusion_judges_the_pair(stem):
    """The conclusion says whether the pinion is undercut, whether ε_α reaches its allowed value and
    which foot wears faster, with λ at B₁ and B₂ from the sliding table."""
    from reportgen.report.sections import gears
    from reportgen.style.numbers import fmt
    gr = _study(stem).gears
    text = plain(" ".join(gears.conclusion_lines(_study(stem))))
    assert "подрез" in text and "ε" in text and "плавность" in text
    t = gr.sliding_table
    for v in (t["lambda1"].iloc[0], t["lambda2"].iloc[-1]):
        assert fmt(abs(float(v)), digits=2) in text, (v, text)


def test_introduction_of_a_one_section_note_agrees():
    """«В пояснительной записке выполнены: синтез кулачкового механизма.» — a plural verb and a
    colon before one item; one section is named as one section."""
    from reportgen.report import assemble
    from reportgen.report.sections import cam
    st = _study("cam_translating_knife_trapezoid")
    sec = _section("cam_translating_knife_trapezoid", cam)
    text = " ".join(plain(p.html) for p in assemble._introduction(st, ["cam"], [sec]))
    assert "выполнены:" not in text and f"выполнен раздел «{sec.title}»" in text


@pytest.mark.parametrize("stem", GEARS)
def test_mesh_marks_the_working_pressure_angle(stem):
    """The mesh shows the common tangent t–t of the working circles at P and the angle α_w between
    it and the line of action (the textbook's picture of the pair); it had neither."""
    from reportgen.scenes import gears as S
    gr = _study(stem).gears
    md = S.internal_mesh_drawing(gr) if gr.internal else S.mesh_drawing(gr)
    ax = md.fig.axes[0]
    texts = [t.get_text() for t in ax.texts]
    assert "$\\alpha_w$" in texts and texts.count("t") == 2
    yP = float(gr.geo.dw1) / 2
    assert any(len(ln.get_ydata()) == 2 and np.allclose(ln.get_ydata(), yP) and np.ptp(ln.get_xdata()) > 0
               for ln in ax.lines)


@pytest.mark.parametrize("stem", GEARS + ("ws001_gear_2013_4",))
def test_geometry_table_referenced_and_inside_the_geometry(stem):
    """The table of the wheels' sizes is referred to in the text (ГОСТ 7.32, 6.6.3) and stands in
    «Геометрический расчёт передачи», not after the specific sliding."""
    from reportgen.report.document import Paragraph, Section, Table
    from reportgen.report.sections import gears
    sec = _section(stem, gears)
    home = next((c for c in sec.children if isinstance(c, Section) and c.id == "sec-gears-geo"), sec)
    kids = home.children
    i_tab = next(i for i, b in enumerate(kids) if isinstance(b, Table) and b.id == "tab-gears-geo")
    assert any(isinstance(b, Paragraph) and "tab-gears-geo" in str(b.html) for b in kids[:i_tab])


def test_flat_face_width_from_exact_extremes(tmp_path):
    """b = s′max − s′min of a flat follower from the exact extremes: with a ν = 2 parabolic rise
    (peak of s′ at x₁ = 2/3, between grid angles) and a cosine return the closed forms are
    s′max = 2h/β_у and s′min = −(π/2)h/β_в."""
    from reportgen.analysis.study import Study
    p = tmp_path / "flat.toml"
    p.write_text('[meta]\ntitle = "t"\n[cam]\nfollower = "translating"\ncontact = "flat"\nstroke = "20 mm"\n'
                 'far_dwell = "20 deg"\n[cam.rise]\nangle = "101 deg"\nlaw = "parabolic"\nnu = 2\n'
                 '[cam.return]\nangle = "97 deg"\nlaw = "cosine"\n', encoding="utf-8")
    c = Study(p).cam
    want = 0.02 * (2 / c.rise.length + (math.pi / 2) / c.ret.length)
    assert c.face_width == pytest.approx(want, rel=1e-12)
    assert c.scalars["cam_face_width"] == pytest.approx(want, rel=1e-12)


@pytest.mark.parametrize("x1, inside", [(0.5, True), (0.0, False)])
def test_given_shifts_judged_against_the_contour(tmp_path, x1, inside):
    """Given shifts: the text says whether the point lies inside the blocking contour (it only said
    the point «показана»); x₁ = 0 with z₁ = 14 undercuts the pinion."""
    from reportgen.analysis.study import Study
    from reportgen.report.sections import gears
    p = tmp_path / "g.toml"
    p.write_text(f'[meta]\ntitle = "t"\n[gears]\nmodule = "5 mm"\nz1 = 14\nz2 = 25\nx1 = {x1}\nx2 = 0.1\n', encoding="utf-8")
    text = " ".join(_paragraphs(gears.build(Study(p))))
    assert ("лежит внутри контура" in text) is inside and ("вне контура" in text) is not inside


@pytest.mark.parametrize("stem", ("cam_translating_knife_trapezoid", "cam_rocker_roller_wide", "cam_translating_roller"))
def test_cam_conclusion_judges_against_the_limits(stem):
    """The conclusion compares ϑ_max with [ϑ] on both phases and, for a roller, r_р with 0,7ρ_min
    (it printed the numbers alone)."""
    from reportgen.report.sections import cam
    from reportgen.report.sections.common import as_written
    st = _study(stem)
    c = st.cam
    text = plain(" ".join(cam.conclusion_lines(st)))
    for a in (c.rise.allowed, c.ret.allowed):
        # the allowed angle as given («30°»): «30,00°» was found only because ϑ_max reached it
        # exactly at the least r₀ (now taken up to a whole millimetre, ϑ_max < [ϑ])
        assert "допустимых " in text and as_written(math.degrees(a)) + "°" in text
    ok = all(t <= a + 1e-9 for t, a in zip(c.theta_max, (c.rise.allowed, c.ret.allowed)))
    assert ("не превышает допустимых" in text) is ok
    if c.contact == "roller":
        assert ("0,7ρmin" in text.replace("\u00a0", "")) and (("≤" in text) is (c.roller <= 0.7 * c.rho_min_centre))
