"""Defects found reviewing, page by page as a ТММ teacher, the cam, gear, planetary-train and synthesis
notes of four variants new to cases/ (session 12, #9): a translating flat-faced follower of a cw cam
with a 3-4-5 rise and an asymmetric parabolic return (cam_translating_flat), a gear pair z₁ = 12,
z₂ = 61 with a given a_w = 92 mm (gear_pair_large_ratio), a 2K-H train with a double satellite and two
internal meshes driven by its carrier (train_2kh_two_internal) and a crank-rocker synthesised by K, a
wide swing ψ = 55° and a given d (synth_crank_rocker_wide).  Each test fails on what the review found:

* the assignment of a translating flat-faced cam: «определить основные размеры по допустимым углам
  давления» — its pressure angle is 0 and r₀ comes from the convexity ρ = r₀ + s + s″ ≥ ρ_min;
* the knot of the asymmetric parabolic return (140° + 0,375·90° = 173,75°) printed «173,7°» among the
  soft impacts and «173,75°» as the place of (s + s″)_min one paragraph later (the float 173,7499…);
* given data padded in the formulas: «6,000 − (−24,58)» for ρ_min = 6 мм, «a_w = 92,0000 мм»,
  «m = 2,500 мм»;
* a negative shift substituted after a plus: d_a2 = 152,50 + 2(1 + −0,221 − 0,009050)·2,5;
* the train's direct check «u = 30,75000000» (ten significant digits beside Willis's 30,75000).
"""
import math
import re

import pytest

from notehelpers import blocks, plain
from test_note_review_i import _formulas, _section, _study   # the session-10 review's cached builders


def _pl(html) -> str:
    """Plain text with no-break spaces as spaces."""
    return plain(html).replace("\xa0", " ")


def _paragraphs(sec) -> list[str]:
    from reportgen.report.document import Paragraph
    return [_pl(b.html) for b in blocks(sec) if isinstance(b, Paragraph)]


def _substituted(sec) -> list[str]:
    return [f.substituted or "" for f in _formulas(sec)]


# ------------------------------------------------------------------ cams
def test_flat_translating_cam_is_sized_by_convexity_not_pressure_angles():
    """ϑ ≡ 0 for a flat face on a translating follower: the assignment names the convexity of the
    profile; roller and knife followers keep «по допустимым углам давления»; a flat rocker with an
    offset face and allowed angles names both."""
    from reportgen.report.sections import cam
    flat = cam.TASK(_study("cam_translating_flat"))
    assert "выпуклости профиля" in flat and "углам давления" not in flat, flat
    assert "по допустимым углам давления" in cam.TASK(_study("cam_translating_roller"))
    both = cam.TASK(_study("cam_rocker_flat"))
    assert "выпуклости профиля" in both and "углам давления" in both, both


def test_cam_knot_angle_printed_alike_everywhere():
    """One angle, one spelling: the knot x₁β of an asymmetric parabolic phase (173,75°) is not cut to
    173,7° in the impacts and kept as 173,75° at the convexity minimum."""
    from reportgen.report.sections import cam
    stem = "cam_translating_flat"
    text = " ".join(_paragraphs(_section(stem, cam)))
    lines = " ".join(_pl(x) for x in cam.conclusion_lines(_study(stem)))
    assert "173,7°" not in text + lines and "173,75°" in text and "173,75°" in lines, (text, lines)
    assert re.search(r"мягкие удары — в 3 положениях \(φ = 140°, 173,75°, 230°\)", lines), lines


def test_flat_cam_convexity_formula_writes_rho_min_as_given():
    from reportgen.report.sections import cam
    subs = _substituted(_section("cam_translating_flat", cam))
    row = next(s for s in subs if r"\left(" in s and "24{,}58" in s)
    assert row.startswith("6 -"), row


def test_flat_rocker_formulas_write_rho_min_offset_and_allowed_angle_as_given():
    from reportgen.report.sections import cam
    subs = " ".join(_substituted(_section("cam_rocker_flat", cam)))
    assert r"5 + 10}" in subs and r"\operatorname{tg}\,30^\circ" in subs, subs
    assert "5{,}000" not in subs and "10{,}00" not in subs and "30{,}00" not in subs, subs


# ------------------------------------------------------------------ gears
def test_given_centre_distance_and_module_as_written():
    from reportgen.report.sections import gears
    stem = "gear_pair_large_ratio"
    sec = _section(stem, gears)
    text = " ".join(_paragraphs(sec))
    assert "a w = 92 мм" in text.replace("aw", "a w") and "92,0000" not in text, text
    cosw = next(s for s in _substituted(sec) if r"\cos" in s and "91{,}25" in s)
    assert cosw.rstrip("}").endswith("{92"), cosw
    lines = " ".join(_pl(x) for x in gears.conclusion_lines(_study(stem)))
    assert "m = 2,5 мм" in lines and "a w = 92 мм" in lines.replace("aw", "a w"), lines


@pytest.mark.parametrize("stem", ("gear_pair_large_ratio", "gear_pair_alpha25", "gear_pair_center_distance"))
def test_negative_shift_is_subtracted_not_added(stem):
    """«1 − 0,221», never «+ -0,221» (a negative number after a binary plus or minus)."""
    from reportgen.report.sections import gears
    for s in _substituted(_section(stem, gears)):
        assert not re.search(r"[+-]\s*\{?-", s), s
    gr = _study(stem).gears
    if min(gr.x1, gr.x2) < 0:
        subs = " ".join(_substituted(_section(stem, gears)))
        x = min(gr.x1, gr.x2)
        assert f"1 - {abs(x):.3f}".replace(".", "{,}") in subs, subs


# ------------------------------------------------------------------ trains
@pytest.mark.parametrize("stem", ("train_2kh_two_internal", "train_2kh_double_select"))
def test_direct_ratio_check_not_printed_to_ten_digits(stem):
    from reportgen.report.sections import train
    text = " ".join(_paragraphs(_section(stem, train)))
    m = re.search(r"даёт u = (−?[\d,]+)", text)
    assert m and len(re.sub(r"\D", "", m.group(1))) <= 7, (m and m.group(0), text)


def test_two_internal_meshes_ratio_by_hand():
    """u_H1 = z1 z2′/(z1 z2′ − z2 z3) for 41/17/18/42: 738/24 = 30,75 (Willis, both meshes «+»)."""
    tr = _study("train_2kh_two_internal").train
    z = {n: w.z for n, w in tr.model.wheels.items()}
    assert (z["1"], z["2"], z["2'"], z["3"]) == (41, 17, 18, 42)
    assert tr.ratio == pytest.approx(z["1"] * z["2'"] / (z["1"] * z["2'"] - z["2"] * z["3"]), rel=1e-12)
    assert z["1"] - z["2"] == z["3"] - z["2'"]
    assert (z["2'"] * z["1"] - z["2"] * z["3"]) % (2 * math.gcd(z["2"], z["2'"])) == 0


@pytest.mark.parametrize("stem", ("gear_pair_large_ratio", "gear_pair_alpha25", "gear_pair_internal"))
def test_sliding_legend_clear_of_the_curves(stem):
    """The legend of the sliding diagram covers no point of λ₁, λ₂ (at u = 5,08 the steep λ₂ ran
    through a legend fixed at the lower centre)."""
    import numpy as np
    from reportgen.scenes.gears import sliding_diagram
    fig = sliding_diagram(_study(stem).gears)
    fig.canvas.draw()
    ax = fig.axes[0]
    box = ax.get_legend().get_window_extent()
    for line in ax.get_lines()[:2]:
        pts = ax.transData.transform(line.get_xydata())
        inside = (pts[:, 0] > box.x0) & (pts[:, 0] < box.x1) & (pts[:, 1] > box.y0) & (pts[:, 1] < box.y1)
        assert not inside.any(), (stem, line.get_label(), int(inside.sum()))


@pytest.mark.parametrize("stem", ("cam_translating_flat", "cam_rocker_flat", "ws001_cam_2013_2", "cam_translating_roller"))
def test_key_curvature_check_holds_at_a_knot(stem):
    """The key's independent ρ_min (circles through three neighbouring profile points, 0,02° apart)
    agrees with the formula to 1e-3 also when ρ_min falls at a knot of s″ (the asymmetric parabolic
    return: ρ = 6 мм at 173,75°, the nearest circle one step before gave 6,007 — «НЕ выполнена»)."""
    from reportgen.report.key import cam_rho_by_points
    cam = _study(stem).cam
    key = "cam_rho_min" if cam.contact == "flat" else "cam_rho_c_min"
    ref = cam.scalars[key]
    assert abs(cam_rho_by_points(cam) - ref) / ref < 1e-4, (stem, cam_rho_by_points(cam), ref)


def test_key_prints_a_computed_shift_to_its_digits():
    """x₂ = x_Σ − x₁ (shifts chosen under a given a_w) is computed: «−0,221», not «−0,2209500964»
    (the glossary marks the shifts «as written» for the cases that give them); a given shift stays
    as written."""
    from reportgen.report.key import value_text
    from reportgen.report.key_names import GEARS
    gr = _study("gear_pair_large_ratio").gears
    assert value_text(GEARS["gears_x2"], gr.x2)[0] == "−0,221", value_text(GEARS["gears_x2"], gr.x2)
    assert value_text(GEARS["gears_x1"], gr.x1)[0] == "0,53"
    assert value_text(GEARS["gears_x1"], 0.25)[0] == "0,25"


@pytest.mark.parametrize("stem, want", (("cam_translating_flat", "16"), ("cam_rocker_flat", "20")))
def test_key_writes_the_given_stroke_as_written(stem, want):
    """The key's stroke h (swing ψ_max of a rocker) is a datum: «16 мм», not «16,00 мм»."""
    from reportgen.report.key import value_text
    from reportgen.report.key_names import CAM
    st = _study(stem)
    assert value_text(CAM["cam_stroke"], st.cam.scalars["cam_stroke"], st, "cam")[0] == want


@pytest.mark.parametrize("stem", ("gear_pair_large_ratio", "gear_pair_shifted"))
def test_rack_shift_label_reads_as_the_text(stem):
    """The generating-rack drawing labels the shift x₁m as the text of 1.5 writes it (1,325 мм, not a
    label «1,33 мм» beside «1,325 мм» in the text)."""
    from reportgen.report.sections import gears
    from reportgen.scenes.gears import rack_drawing
    gr = _study(stem).gears
    fig = rack_drawing(gr)[0]
    labels = [t.get_text() for ax in fig.axes for t in ax.texts if "xm" in t.get_text()]
    text = next(p for p in _paragraphs(_section(stem, gears)) if "нарезается рейкой" in p)
    value = re.search(r"x1m = ([−\d,]+) мм", text).group(1)
    assert labels and labels[0].endswith(f"= {value} мм"), (labels, value)
