"""Given data and exact results written as they are, not padded (cam_rocker_flat printed
«a_w,ϑу = 10,00 / (tg 30,00° · …)» and «[ϑ_у] = 30,00°» for d = 10 мм and [ϑ] = 30°)."""
import re

import pytest

from notehelpers import plain
from test_note_review_i import _formulas, _paragraphs, _section


@pytest.mark.parametrize("stem", ["cam_rocker_flat", "cam_rocker_roller", "cam_translating_roller"])
def test_given_cam_values_are_not_padded(stem):
    from reportgen.report.sections import cam
    sec = _section(stem, cam)
    text = " ".join(plain(p) for p in _paragraphs(sec))
    allowed = re.findall(r"\[ϑ[ув]\]\s*=\s*([\d,]+)°|при допустимых ([\d,]+)°", text)
    for got in (g for pair in allowed for g in pair if g):
        assert not re.fullmatch(r"\d+,0+", got), (stem, got)
    for f in _formulas(sec):
        sub = f.substituted or ""
        assert not re.search(r"\\operatorname\{tg\}\\,\d+\{,\}0+\^\\circ", sub), (stem, sub)
        assert not re.search(r"\\frac\{10\{,\}0+\}", sub), (stem, sub)


def test_flat_rocker_formulas_write_d_and_the_allowed_angle_as_given():
    from reportgen.report.sections import cam
    subs = [f.substituted for f in _formulas(_section("cam_rocker_flat", cam)) if f.substituted]
    assert any(r"\frac{10}{\operatorname{tg}\,30^\circ" in s for s in subs), subs
    text = " ".join(plain(p) for p in _paragraphs(_section("cam_rocker_flat", cam)))
    assert "[ϑу] = 30°" in text.replace("\xa0", " ") or "[ϑ у] = 30°" in text.replace("\xa0", " "), text


def test_gear_contact_ratio_told_from_its_given_limit():
    """gear_pair_shifted printed «плавность: ε_α = 1,200 ≥ 1,200» for ε_α = 1,2004 and [ε_α] = 1,2."""
    from reportgen.report.sections import gears
    from reportgen.report.render import render_fragment
    both = plain(render_fragment(_section("gear_pair_shifted", gears))).replace("\xa0", " ")
    assert "1,200 ≥ 1,200" not in both
    assert "1,2004 ≥ 1,2" in both, both[:2000]


def test_gear_limits_and_ratio_not_padded():
    """The blocking-contour choice printed «ε_α ≥ 1,200» and the sliding formula «u = 2,5000»."""
    from reportgen.report.render import render_fragment
    from reportgen.report.sections import gears
    sec = _section("gear_pair_shifted", gears)
    text = plain(render_fragment(sec)).replace("\xa0", " ")
    assert "≥ 1,200)" not in text and "ε α ≥ 1,2)" in text.replace("εα", "ε α"), text[:3000]
    subs = [f.substituted or f.symbolic for f in _formulas(sec)]
    assert any(r"u = \frac{z_2}{z_1} = 2{,}5" in s and "2{,}5000" not in s for s in subs), subs


def test_train_whole_ratios_not_padded_and_wheels_subscripted():
    """train_2kh_three_planets: u₁H = (17 + 85)/17 printed «6,000000», the sets' column «6,00000», the
    rejected sets' verdict «z1 = 11 < 17: подрезание» (a plain «z1»)."""
    from reportgen.report.render import render_fragment
    from reportgen.report.sections import train
    import html
    sec = _section("train_2kh_three_planets", train)
    text = html.unescape(plain(render_fragment(sec))).replace("\xa0", " ")
    assert "z₁ = 11 < 17: подрезание" in text and "z1 = 11" not in text
    assert "6,00000" not in text
    tex = " ".join((f.substituted or "") + " " + (f.result or "") for f in _formulas(sec))
    assert "6{,}000000" not in tex and "6,000000" not in tex, tex


@pytest.mark.parametrize("stem, module", [("cam_rocker_flat", "cam"), ("cam_translating_roller", "cam"),
                                          ("synth_crank_rocker", "synthesis")])
def test_scale_factors_written_round(stem, module):
    """«μ_φ = 3,00 град/мм; μ_ψ′ = 0,0500 ед./мм», «в масштабе μ_l = 0,0150 м/мм»: a round scale factor is
    written as such, as under every other drawing (0,015 м/мм)."""
    import importlib
    import html
    from reportgen.report.render import render_fragment
    sec = _section(stem, importlib.import_module(f"reportgen.report.sections.{module}"))
    text = html.unescape(plain(render_fragment(sec))).replace("\xa0", " ")
    scales = re.findall(r"μ\w*′*\s*=\s*([\d,]+)\s*(?:град|ед\.|°|м)/мм", text)
    assert scales, text[:1500]
    assert not any(re.search(r",\d*0$", v) for v in scales), scales
