"""Defects found reviewing, page by page as a ТММ teacher, the cam, gear, planetary-train and synthesis
notes of five variants new to cases/ (session 11, #9): a translating roller follower of a cw cam with a
cosine rise and an asymmetric cycloidal return (cam_translating_roller_offset), a roller rocker with a
given small a_w and ψ₀ that fail the pressure-angle check (cam_rocker_roller_small), a gear pair
z₁ = 9 with a basic rack α = 25° (gear_pair_alpha25), a 2K-H train with two external meshes driven by
its carrier (train_2kh_external_select) and a six-bar synthesised by H and K with the crank centre at a
given distance from the rocker's pivot and the slider left of B (synth_six_bar_press).  Each test fails
on what the review found:

* the middle soft impact of a parabolic law lost: the kernel read the relative angle one ulp past
  x₁ = 1/2 from both sides, so «мягкие удары — в 2 положениях» for a law that has three;
* the given data padded with zeros: «h = 18,00 мм», «100,00°», «[ϑ] = 28,00°», «ν = 0,6000»,
  «240,0 об/мин»; the gear's «α = 25,00°, h_a* = 1,000, c* = 0,2500, m = 3,500 мм», «3,5000(27 + 9)»,
  «cos 25,0000°», «0,3000m»;
* a basic rack with α = 25° called «исходный контур по ГОСТ 13755-81» (whose α is 20°);
* the shifts said chosen «с выравненным износом (λ1max ≈ λ2max)» at |λ₁| = 1,82, |λ₂| = 1,18, and the
  conclusion advising to move towards the isoline λ1max = λ2max that lies outside the contour;
* given a_w, ψ₀ of a rocker: «центр O выбран как ближайшая к B₀ точка допустимой области», then
  ϑ_max = 46,6° > 40° and only «размеры механизма нужно увеличить» — no sizes that pass;
* the assembly condition (49·70 − 50·71)/(3·1) printed «= 40» (it is −40); the accepted ratio printed
  as −343/12 with no numbers of teeth substituted;
* synthesis: «сторона ползуна ± = −1» in the assignment and its table; a parameter ``d`` that is the
  distance of the crank centre from the rocker's pivot titled «диаметр»; the six-bar's chord written
  as 2·l_CB·sin(ψ/2) with ψ derived only afterwards.
"""
import math
import re
from fractions import Fraction

import pytest

from notehelpers import blocks, plain
from test_note_review_i import _formulas, _section, _study   # the session-10 review's cached builders


def _pl(html) -> str:
    """Plain text with no-break spaces as spaces."""
    return plain(html).replace("\xa0", " ")


def _paragraphs(sec) -> list[str]:
    from reportgen.report.document import Paragraph
    return [_pl(b.html) for b in blocks(sec) if isinstance(b, Paragraph)]


def _tex_eval(tex: str) -> Fraction:
    """An integer expression of a substituted formula: «\\frac{50 \\cdot 71 - 49 \\cdot 70}{3 \\cdot 1}»."""
    t = tex.replace(r"\cdot", "*").replace("{,}", ".").replace(" ", "")
    t = re.sub(r"\\frac\{([^{}]*)\}\{([^{}]*)\}", r"(Fraction(\1)/Fraction(\2))", t)
    t = re.sub(r"(\d+)", r"Fraction(\1)", t).replace("Fraction(Fraction(", "Fraction((")
    return eval(t, {"Fraction": Fraction})   # noqa: S307 — digits and operators of our own formula


# ------------------------------------------------------------------ cams
@pytest.mark.parametrize("stem", ("cam_rocker_roller_small", "cam_rocker_roller_wide", "cam_translating_knife_trapezoid"))
def test_parabolic_law_has_its_middle_soft_impact(stem):
    """Every end and inflection of a parabolic phase is a jump of s″ (Артоболевский §24): a soft
    impact at φ = φ_start + x₁β as well as at both ends."""
    cam = _study(stem).cam
    at = [i["phi"] for i in cam.impacts if i["kind"] == "soft"]
    for ph in cam.phases:
        if ph.law == "parabolic":
            x1 = ph.nu / (1 + ph.nu)
            for x in (0.0, x1, 1.0):
                p = (ph.start + x * ph.length) % (2 * math.pi)
                assert any(abs(p - q) < 1e-9 for q in at), (stem, math.degrees(p), [math.degrees(q) for q in at])


def test_cam_given_data_as_written():
    from reportgen.report.document import Table
    from reportgen.report.sections import cam
    stem = "cam_translating_roller_offset"
    given = _pl(cam.given(_study(stem)))
    for want in ("h = 18 мм", "удаления 100°", "возвращения 80°", "ν = 0,6)", "углы давления 28° и 40°", "240 об/мин"):
        assert want in given, (want, given)
    tab = next(b for b in blocks(_section(stem, cam)) if isinstance(b, Table))
    vals = [_pl(str(v)) for v in tab.data["c"]]
    for want in ("18 мм", "100°", "40°", "28°", "6 мм", "25,13 рад/с (240 об/мин)"):
        assert want in vals, (want, vals)
    assert not any(re.search(r"\d,0+(°| мм)", v) for v in vals), vals
    assert any("Угол фазы β = 100° =" in p for p in _paragraphs(_section(stem, cam)))
    smax = [f for f in _formulas(_section(stem, cam)) if f.symbolic.startswith("|s^")]
    assert smax and all(f.substituted.startswith(r"18\ \text{мм}") for f in smax), [f.substituted for f in smax]


def test_given_rocker_sizes_are_checked_and_the_passing_sizes_given():
    from reportgen.report.sections import cam as sec_cam
    stem = "cam_rocker_roller_small"
    st = _study(stem)
    cam = st.cam
    ps = _paragraphs(_section(stem, sec_cam))
    assert not any("выбран как ближайшая" in p for p in ps)
    assert any("Размеры заданы" in p and "вне допустимой области" in p for p in ps)
    req = cam.required_size
    assert req is not None
    O = cam._rocker_O(req["a_w"], req["psi0"])
    # the sizes offered pass both pressure-angle conditions (the ray conditions h ≤ 0 on both phases)
    assert max(cam._hmax(1, O)[0], cam._hmax(2, O)[0]) < 1e-9 * cam.arm
    from reportgen.style.numbers import fmt
    text = next(p for p in ps if "Наибольшие значения" in p and "ϑ" in p)
    assert f"aw = {fmt(req['a_w'] * 1000, sig=4)} мм" in text, text
    concl = _pl(" ".join(sec_cam.conclusion_lines(st)))
    assert "заданы aw = 80 мм, ψ0 = 20°" in concl and fmt(req["a_w"] * 1000, sig=4) in concl, concl
    r0 = next(f for f in _formulas(_section(stem, sec_cam)) if f.symbolic.startswith("r_0 ="))
    assert r0.substituted.startswith(r"\sqrt{80^2 + 70^2"), r0.substituted


def test_chosen_cam_sizes_offer_no_replacement():
    for stem in ("cam_translating_roller_offset", "cam_rocker_roller", "cam_translating_roller"):
        assert _study(stem).cam.required_size is None


# ------------------------------------------------------------------ gears
def test_nonstandard_basic_rack_is_not_called_gost_13755():
    from reportgen.report.sections import gears
    st = _study("gear_pair_alpha25")
    first = _paragraphs(_section("gear_pair_alpha25", gears))[0]
    assert "по ГОСТ 13755-81:" not in first and "нестандартный: по ГОСТ 13755-81 α = 20°" in first, first
    assert "α = 25°, ha* = 1, c* = 0,25, ρf* = 0,38" in first and "m = 3,5 мм" in first, first
    assert "нестандартный" in _pl(gears.given(st)) and "960 об/мин" in _pl(gears.given(st))
    std = _paragraphs(_section("gear_pair_shifted", gears))[0]
    assert "исходным контуром по ГОСТ 13755-81: α = 20°, ha* = 1, c* = 0,25, ρf* = 0,38" in std, std


def test_gear_formulas_write_the_given_module_and_angle_as_given():
    from reportgen.report.sections import gears
    fs = _formulas(_section("gear_pair_alpha25", gears))
    a = next(f for f in fs if f.symbolic.startswith("a = "))
    aw = next(f for f in fs if f.symbolic.startswith("a_w = "))
    assert a.substituted.startswith(r"\frac{3{,}5(27"), a.substituted
    assert r"\cos25^{\circ}" in aw.substituted, aw.substituted
    checks = next(p for p in _paragraphs(_section("gear_pair_alpha25", gears)) if "заострение" in p)
    assert "≥ 0,3m" in checks, checks


def test_wear_words_agree_with_the_chosen_point():
    """Where the chosen point cannot equalise λ at the feet (it stands on the contour's boundary), neither
    the rule nor the conclusion says the wear is equalised or can be by moving to the isoline."""
    from reportgen.report.sections import gears
    stem = "gear_pair_alpha25"
    st = _study(stem)
    rule = next(p for p in _paragraphs(_section(stem, gears)) if "Смещения выбраны" in p)
    assert "(λ1max ≈ λ2max)" not in rule and "на границе контура" in rule and "εα = 1,101 ≈ 1,1" in rule, rule
    concl = _pl(" ".join(gears.conclusion_lines(st)))
    assert "можно выровнять" not in concl and "нельзя" in concl, concl
    # a pair whose chosen point does equalise it keeps the words
    assert "(λ1max ≈ λ2max)" in next(p for p in _paragraphs(_section("gear_pair_shifted", gears)) if "Смещения выбраны" in p)


# ------------------------------------------------------------------ trains
TRAINS = ("train_2kh_external_select", "train_3k_select", "train_2kh_double_select", "train_gear_stage_2kh",
          "train_two_carrier_select")


@pytest.mark.parametrize("stem", TRAINS)
def test_assembly_and_ratio_formulas_equal_their_printed_results(stem):
    from reportgen.report.sections import train
    fs = _formulas(_section(stem, train))
    asm = [f for f in fs if "НОД" in f.symbolic or (f.symbolic.startswith(r"\frac{z_") and f.symbolic.endswith("{k}"))]
    assert asm
    for f in asm:
        assert _tex_eval(f.substituted) == _tex_eval(f.result), (f.substituted, f.result)
    st = _study(stem)
    fr = st.train.candidates[0].u_exact
    u = next(f for f in fs if re.fullmatch(r"u_\{[^{}]+\\,[^{}]+\}", f.symbolic))
    assert _tex_eval(u.substituted.replace("{ - ", "{-")) == fr, (u.substituted, fr)


# ------------------------------------------------------------------ synthesis
def test_six_bar_slider_side_in_words_and_parameters_named_by_the_synthesis():
    from reportgen.report import assemble
    from reportgen.report.document import Table
    from reportgen.report.sections import synthesis
    stem = "synth_six_bar_press"
    st = _study(stem)
    g = _pl(synthesis.given(st))
    assert "±" not in g and "ползун левее точки B" in g, g
    tab = next(b for b in blocks(_section(stem, synthesis)) if isinstance(b, Table))
    assert "−1" not in [_pl(str(v)) for v in tab.data["val"]] and "левее" in [_pl(str(v)) for v in tab.data["val"]]
    rows = assemble._given_parameters(st)[0].data
    titles = dict(zip(rows["name"].map(lambda s: _pl(str(s))), rows["title"]))
    assert titles["d"] == "расстояние от центра кривошипа до опоры коромысла", titles
    assert titles["yP"] == "расстояние от опоры коромысла до траектории ползуна", titles


@pytest.mark.parametrize("stem", ("synth_six_bar_press", "ws001_p6_six_bar"))
def test_six_bar_swing_found_before_the_chord_uses_it(stem):
    from reportgen.report.sections import synthesis
    sec = _section(stem, synthesis)
    fs = _formulas(sec)
    assert not any("l_{CB}" in f.symbolic for f in fs)
    i = next(i for i, f in enumerate(fs) if f.label == "eq-syn-psi6")
    j = next(i for i, f in enumerate(fs) if f.label == "eq-syn-R")
    assert i < j
    v = _study(stem).synthesis.chosen
    assert abs(float(fs[i].result.split("^")[0].replace("{,}", ".")) - math.degrees(v["psi"])) < 1e-3


@pytest.mark.parametrize("stem", ("cam_rocker_roller_small", "cam_translating_roller_offset"))
def test_modulus_keeps_its_subscript_on_the_line(stem):
    """«|ϑ|» and its «max» were split across lines (a line may break after «|», Unicode class BA)."""
    from reportgen.report.document import Paragraph
    from reportgen.report.sections import cam
    html = " ".join(b.html for b in blocks(_section(stem, cam)) if isinstance(b, Paragraph))
    bars = re.findall(r'(.{0,22})\|ϑ\|<sub>', html)
    assert bars and all(b.endswith('<span class="nobr">') for b in bars), bars


@pytest.mark.parametrize("stem", ("train_2kh_external_select", "train_3k_select"))
def test_large_stage_ratio_read_on_a_farther_horizontal(stem):
    """u_H1 = −28,6 in one stage: at a common polar distance the segment of wheel 1 was 4,5 mm against
    135,5 mm, read to 0,5 mm — 5,3 % off.  A short segment is read f polar distances away."""
    from reportgen.report.sections import train
    from reportgen.scenes.train import SHORT_MM, stage_plans
    tr = _study(stem).train
    st = stage_plans(tr)
    assert abs(st.u_graph / tr.ratio - 1) < 0.01, (st.stages, st.depths)
    for (a, b, sa, sb), (fa, fb) in zip(st.stages, st.depths):
        assert min(abs(sa), abs(sb)) >= SHORT_MM
        assert (sa / fa) / (sb / fb) == pytest.approx(tr.w_willis[a] / tr.w_willis[b], rel=0.02)
    assert any(f > 1 for fs in st.depths for f in fs)
    ps = _paragraphs(_section(stem, train))
    assert any("полюсному расстоянию" in p for p in ps)
    assert any("/f_{" in f.symbolic for f in _formulas(_section(stem, train)))
