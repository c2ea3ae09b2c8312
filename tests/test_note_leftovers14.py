"""Session 12's «noticed and left» on cams, gears, trains and synthesis (helper leftovers14):
the key's names and given values, the cam's accepted r₀, the gear pair's blocking contour, the
scheme of a train with two internal meshes."""
import html
import re

import pytest

from reportgen.analysis.study import load_case

_STUDIES = {}


def _study(stem):
    if stem not in _STUDIES:
        _STUDIES[stem] = load_case(f"cases/{stem}.toml")
    return _STUDIES[stem]


def _key_rows(stem, kind):
    from reportgen.report.key import result_rows
    st = _study(stem)
    rows = [r for g in result_rows(st, kind, st.analysis(kind).scalars).values() for r in g]
    return {html.unescape(re.sub("<[^>]+>", "", str(r["name"]))): str(r["value"]) for r in rows}


@pytest.mark.parametrize("stem, expected", [
    ("cam_translating_flat", "Радиус основной шайбы (рабочего профиля)"),
    ("cam_translating_knife_trapezoid", "Радиус основной шайбы (рабочего профиля)"),
    ("cam_rocker_roller", "Радиус основной шайбы (центрового профиля)")])
def test_key_names_base_circle_by_follower_contact(stem, expected):
    """«Радиус основной шайбы (центрового профиля)» was printed for knife-edge and flat-faced
    followers too, which have no separate centre profile."""
    rows = _key_rows(stem, "cam")
    assert expected in rows, sorted(rows)
    assert sum(n.startswith("Радиус основной шайбы (") for n in rows) == 1


def test_key_prints_given_synthesis_values_as_given():
    """synth_crank_rocker_wide (ψ = 55°, l_CB = 0,28 м, l_OC = 0,4 м): the key printed «55,00»,
    «0,28000», «0,40000»; a computed value keeps its digits."""
    rows = _key_rows("synth_crank_rocker_wide", "synthesis")
    assert rows["Угол размаха коромысла (кулисы)"] == "55"
    assert rows["Длина коромысла"] == "0,28"
    assert rows["Расстояние между центрами вращения"] == "0,4"
    assert rows["Длина кривошипа"] == "0,12128"
    rows = _key_rows("synth_slider_crank", "synthesis")
    assert rows["Смещение (дезаксиал)"] == "0,05" and rows["Ход выходного звена"] == "0,3"


def test_key_prints_given_rocker_arm_as_given():
    assert _key_rows("cam_rocker_roller", "cam")["Длина коромысла"] == "100"


def _contour_figure(stem):
    from reportgen.scenes.gears import blocking_contour
    return blocking_contour(_study(stem).gears)


@pytest.mark.parametrize("stem", ["gear_pair_large_ratio", "gear_pair_shifted"])
def test_blocking_contour_each_shift_over_its_own_range(stem):
    """One range was drawn for both shifts: gear_pair_large_ratio (z₁ = 12, z₂ = 61) drew x₁ from
    −2,6 (the wheel's undercut limit) though no x₁ < x₁min = 0,30 is admissible."""
    import matplotlib.pyplot as plt
    gr = _study(stem).gears
    fig = _contour_figure(stem)
    ax = fig.axes[0]
    x1min = 1 - gr.z1 * 0.11697777844051097 / 2         # h_a* − z sin²20°/2
    x2min = 1 - gr.z2 * 0.11697777844051097 / 2
    assert ax.get_xlim()[0] >= min(-0.6, x1min - 0.2) and ax.get_xlim()[0] <= x1min
    assert ax.get_ylim()[0] <= x2min
    plt.close(fig)


def test_blocking_contour_limits_labelled_on_their_curves_with_textbook_values():
    """Each limit of the contour named on its curve (s_a = 0 and s_a,min·m of each wheel, ε_α = 1 and
    ε_min, interference, the undercut limits with their values); x_min = (17 − z)/17 for α = 20°,
    h_a* = 1 (textbook, ± 0,02: the exact h_a* − z sin²α/2): z₁ = 12 → 0,29…0,30, z₂ = 30 → −0,75…−0,76."""
    import matplotlib.pyplot as plt
    fig = _contour_figure("gear_pair_shifted")
    texts = [t.get_text() for t in fig.axes[0].texts]
    for want in ("s_{a1}=0$", "s_{a1}=0{,}25m", "s_{a2}=0{,}25m", r"\varepsilon_\alpha=1$",
                 r"\varepsilon_\alpha=1{,}2", "интерф. 1", "интерф. 2"):
        assert any(want in t for t in texts), (want, texts)
    got = {}
    for t in texts:
        m = re.search(r"x_\{(\d)min\}=(-?[\d{},]+)", t)
        if m:
            got[m.group(1)] = float(m.group(2).replace("{,}", "."))
    assert abs(got["1"] - (17 - 12) / 17) <= 0.02 and abs(got["2"] - (17 - 30) / 17) <= 0.02, got
    plt.close(fig)


def test_cam_base_radius_taken_up_to_a_whole_millimetre_and_used():
    """cam_translating_roller: the least r₀ = 28,62 мм was printed and used as it is; the textbook
    takes r₀ = 29 мм and builds everything with it.  Hand check: e = 4,739 мм kept, s₀ = √(29² −
    4,739²) = √818,54 = 28,61 мм; at φ = 0 (s = 0) the centre profile's radius is r₀ = 29 мм; the
    pressure angles fall below [ϑ_у] = 30°, [ϑ_в] = 45° (the least size reaches them)."""
    import math
    import numpy as np
    from reportgen.report.render import render_fragment
    from reportgen.report.sections import cam as S
    st = _study("cam_translating_roller")
    c = st.cam
    syn = c.synthesis
    assert syn.r0 == pytest.approx(0.029, abs=1e-12) and syn.exact.r0 == pytest.approx(0.028622, abs=1e-6)
    assert syn.e == syn.exact.e and syn.s0 * 1000 == pytest.approx(math.sqrt(29 ** 2 - 4.7391 ** 2), abs=1e-3)
    assert float(np.hypot(*c._O_synth)) == pytest.approx(0.029, abs=1e-12)
    t1, t2 = c.theta_max
    assert t1 < c.rise.allowed - 1e-3 and t2 < c.ret.allowed - 1e-3
    assert c.scalars["cam_r0"] == pytest.approx(0.029, abs=1e-12)
    rows = _key_rows("cam_translating_roller", "cam")       # the key: the accepted and the least
    assert rows["Радиус основной шайбы (центрового профиля)"] == "29"
    assert rows["Наименьший радиус основной шайбы по допустимым углам давления"] == "28,62"
    text = html.unescape(re.sub("<[^>]+>", "", render_fragment(S.build(st)))).replace("\xa0", " ")
    assert "Принимаем r0 = 29 мм (наименьший 28,62 мм" in text, text[:500]
    assert "по допустимым углам давления r<sub>0</sub>&nbsp;=&nbsp;29&nbsp;мм" in " ".join(S.conclusion_lines(st))


@pytest.mark.parametrize("stem", ["cam_rocker_roller", "cam_rocker_flat", "cam_translating_flat",
                                  "cam_translating_knife_trapezoid"])
def test_every_cam_kind_takes_a_whole_millimetre_and_stays_admissible(stem):
    """Each kind keeps its centre admissible with the accepted r₀: a rocker moves O along B₀O, a
    flat rocker keeps ψ₀ (a_w = (r₀ + d)/sin ψ₀: cam_rocker_flat 70,10 → 71 мм, a_w = 81/sin 58,783° =
    94,71 мм), a flat translating follower takes r₀ = s₀."""
    import math
    c = _study(stem).cam
    syn = c.synthesis
    assert syn.exact is not None and syn.exact.r0 < syn.r0 < syn.exact.r0 + 0.001
    assert abs(syn.r0 * 1000 - round(syn.r0 * 1000)) < 1e-9
    for t, ph in zip(c.theta_max, (c.rise, c.ret)):
        assert ph.allowed == 0 or t <= ph.allowed + 1e-9
    if c.flat_rocker:
        assert syn.psi0 == syn.exact.psi0
        assert syn.a_w * math.sin(syn.psi0) - c.face_offset == pytest.approx(syn.r0, abs=1e-12)
        assert c.scalars["cam_rho_min"] >= c.rho_min - 1e-12
    elif c.follower == "rocker":
        assert float(math.hypot(c.arm - syn.O[0], syn.O[1])) == pytest.approx(syn.r0, abs=1e-12)


def _crossings(fig):
    """Where a wheel's (or a carrier arm's) vertical line crosses a horizontal line of another
    member in the scheme (the lines' colours are the members'): none may, except a wheel on its
    own axle at its centre (the middle of its line)."""
    import matplotlib.colors as mc
    from reportgen.scenes.train import COLORS
    members = {mc.to_hex(c) for c in COLORS}
    ax = fig.axes[0]
    vert, hor = [], []
    for ln in ax.get_lines():
        col = mc.to_hex(ln.get_color())
        if col not in members:
            continue
        xs, ys = (list(map(float, v)) for v in ln.get_data())
        if len(xs) != 2:
            continue
        if abs(xs[0] - xs[1]) < 1e-9 and abs(ys[0] - ys[1]) > 1e-9:
            vert.append((col, xs[0], min(ys), max(ys)))
        elif abs(ys[0] - ys[1]) < 1e-9 and abs(xs[0] - xs[1]) > 1e-9:
            hor.append((col, min(xs), max(xs), ys[0]))
    out = []
    for cv, x, y0, y1 in vert:
        tol = 1e-6 * (y1 - y0)
        for ch, x0, x1, y in hor:
            if ch == cv or not (x0 + tol < x < x1 - tol and y0 + tol < y < y1 - tol):
                continue
            if abs(y - (y0 + y1) / 2) <= tol:
                continue            # a wheel on its axle
            out.append((cv, x, ch, y))
    return out


@pytest.mark.parametrize("stem", ["train_2kh_two_internal", "train_2kh_three_planets", "train_2kh_double_select",
                                  "train_3k_select", "train_2kh_four_planets", "train_2kh_external_select"])
def test_train_scheme_no_wheel_crosses_a_shaft_it_does_not_sit_on(stem):
    """train_2kh_two_internal: ring 1's disc (drawn on the side of the satellites) crossed the
    satellites' axle; now the ring opens towards them, the carrier's arm rises inside it and its
    shaft runs out through the ring's hollow shaft."""
    import matplotlib.pyplot as plt
    from reportgen.scenes.train import train_picture
    pic = train_picture(_study(stem).train)
    assert _crossings(pic.fig) == []
    plt.close(pic.fig)


def _gear_text(stem):
    from reportgen.report.render import render_fragment
    from reportgen.report.sections import gears as S
    st = _study(stem)
    body = render_fragment(S.build(st)) + " ".join(S.conclusion_lines(st))
    return html.unescape(re.sub("<[^>]+>", "", body)).replace("\xa0", " ")


@pytest.mark.parametrize("stem", ["gear_pair_internal", "gear_pair_shifted"])
def test_gear_note_prints_one_quantity_alike_everywhere(stem):
    """gear_pair_internal: x₁min printed −0,1698 in the checks and −0,170 in the table and the
    conclusion; α_w 20,0000° in the formula and 20,000° in the conclusion; the sliding table's λ₁
    to 3 decimals beside λ₂ to 4."""
    text = _gear_text(stem)
    xs = set(re.findall(r"x1min = (−?\d+,\d+)", text))
    assert len(xs) == 1, xs
    aw = set(re.findall(r"αw = (\d+,\d+)°", text))
    assert len(aw) == 1, aw
    from reportgen.report.sections import gears as S
    from reportgen.report.document import Table
    from notehelpers import blocks
    tab = next(b for b in blocks(S.build(_study(stem))) if isinstance(b, Table) and "lambda1" in b.data)
    digits = {c.key: c.digits for c in tab.columns if c.key in ("lambda1", "lambda2")}
    assert digits["lambda1"] == digits["lambda2"] is not None, digits


def test_train_wheel_names_with_a_prime_not_an_apostrophe():
    """train_2kh_two_internal: the text and tables wrote «z2'», «2'» (the case's ASCII apostrophe)
    while the formulas set z₂′; the conclusion wrote an upright z."""
    import matplotlib.pyplot as plt
    from reportgen.report.render import render_fragment
    from reportgen.report.sections import train as S
    from reportgen.scenes.train import train_picture
    st = _study("train_2kh_two_internal")
    body = render_fragment(S.build(st))
    concl = " ".join(S.conclusion_lines(st))
    text = html.unescape(re.sub("<[^>]+>", "", body + concl))
    assert "'" not in text and "2′" in text
    assert "<i>z</i><sub>2′</sub> = 18" in concl
    pic = train_picture(st.train)
    labels = [t.get_text() for ax in pic.fig.axes for t in ax.texts]
    # (mathtext sets «'» as a prime itself: $P_{2'3}$)
    assert "2′" in labels and not any("'" in t for t in labels if not t.startswith("$")), labels
    plt.close(pic.fig)


@pytest.mark.parametrize("stem, given", [("synth_slider_crank", "0{,}05"), ("synth_crank_rocker", "0{,}5"),
                                         ("synth_crank_rocker_wide", "0{,}28")])
def test_synthesis_transmission_formula_writes_given_data_as_given(stem, given):
    """The least transmission angle's substitution padded the given offset and rocker length:
    «0,14314 + 0,050000», «0,5000²», «2 · 0,2514 · 0,2800»."""
    from notehelpers import blocks
    from reportgen.report.document import FormulaBlock
    from reportgen.report.sections import synthesis as S
    subs = [f.substituted for b in blocks(S.build(_study(stem))) if isinstance(b, FormulaBlock)
            for f in b.formulas if f.substituted and r"\mu" in (f.symbolic or "")]
    assert subs and all(re.search(re.escape(given) + r"(?![\d])", t) for t in subs), subs
    assert not any(re.search(re.escape(given) + r"0+(?![\d])", t) for t in subs), subs
