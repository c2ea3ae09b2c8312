"""Linkage synthesis by K: closed forms checked by independent geometry, and the synthesised
linkages put back into the engine reproduce their stroke (swing) and K to 1e-10."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from reportgen.analysis.study import load_case
from reportgen.case.load import CaseSpec
from reportgen.core import synthesis as S
from reportgen.errors import CaseError

CASES = Path(__file__).resolve().parent.parent / "cases"


def _dist(p, q):
    return math.hypot(p[0] - q[0], p[1] - q[1])


@pytest.mark.parametrize("name", ["synth_crank_rocker", "synth_slider_crank", "synth_slotted_lever",
                                  "synth_shaper", "ws001_p6_six_bar"])
def test_engine_reproduces_stroke_and_K(name):
    st = load_case(CASES / f"{name}.toml")
    sy = st.synthesis
    chk = sy.check
    assert chk["extremes"] == 2
    assert chk["stroke"] == pytest.approx(sy.target_stroke(), abs=1e-10)
    assert chk["K"] == pytest.approx(sy.inputs["K"], abs=1e-10)


def test_problem_2013_6_answer():
    """Worksheet 001, problem 6: l1 = 0,065 m, l2 = 0,383 m measured on a drawing at
    0,005 m/mm; Θ = 23,5°; four variants."""
    st = load_case(CASES / "ws001_p6_six_bar.toml")
    sy = st.synthesis
    assert len(sy.variants) == 4
    v = sy.chosen
    assert math.degrees(v["theta"]) == pytest.approx(23.5, abs=0.05)
    # the drawing's segments O1B1 = 89,5 mm, O1B0 = 63,5 mm (exact 89,30 and 63,62)
    assert (v["b"] + v["a"]) / 0.005 == pytest.approx(89.5, abs=0.3)
    assert (v["b"] - v["a"]) / 0.005 == pytest.approx(63.5, abs=0.3)
    assert v["a"] == pytest.approx(0.065, rel=0.015)
    assert v["b"] == pytest.approx(0.383, rel=0.005)
    # independent check: O1 on the line through O2 (distance a from the path y = a), the chord
    # B0B1 = H seen under Θ (law of cosines in the triangle O1B0B1)
    assert v["y_O"] == 0.0
    r1, r2 = v["b"] - v["a"], v["b"] + v["a"]
    assert r1 * r1 + r2 * r2 - 2 * r1 * r2 * math.cos(v["theta"]) == pytest.approx(0.2 ** 2, abs=1e-14)
    # the parameters of the case are the chosen variant
    assert float(st.params["l_1"].value) == v["a"]
    # the other two variants: O1 on the line y = 2a (the other side of the path)
    assert {round(w["y_O"], 12) for w in sy.variants} == {0.0, 0.6}


def test_crank_rocker_geometry_independent():
    K, psi, c, d = 1.25, math.radians(45), 0.4, 0.55
    vs = S.crank_rocker(K, psi, c, d=d)
    assert vs
    th = S.theta_of_K(K)
    for v in vs:
        o = (v["x_O"], v["y_O"])
        b1, b2 = (v["x_B1"], v["y_B1"]), (v["x_B2"], v["y_B2"])
        assert _dist(o, (0, 0)) == pytest.approx(d, abs=1e-14)
        assert sorted([_dist(o, b1), _dist(o, b2)]) == pytest.approx([v["b"] - v["a"], v["b"] + v["a"]], abs=1e-14)
        # angle at O by the law of cosines
        r1, r2, ch = _dist(o, b1), _dist(o, b2), _dist(b1, b2)
        assert math.acos((r1 * r1 + r2 * r2 - ch * ch) / (2 * r1 * r2)) == pytest.approx(th, abs=1e-12)
    # the same centre found from the line y = y_O
    v0 = vs[0]
    again = S.crank_rocker(K, psi, c, line_y=v0["y_O"])
    assert any(abs(w["x_O"] - v0["x_O"]) < 1e-12 and abs(w["a"] - v0["a"]) < 1e-12 for w in again)


def test_K_equal_one_is_collinear():
    vs = S.crank_rocker(1.0, math.radians(40), 0.5, d=0.9)
    assert vs
    for v in vs:
        assert v["a"] == pytest.approx(0.5 * math.sin(math.radians(20)), abs=1e-14)   # a = c·sin(ψ/2)


def test_slider_crank_e_and_lambda_agree():
    v = S.slider_crank(1.4, 0.3, e=0.05)[0]
    w = S.slider_crank(1.4, 0.3, lam=v["lam"])[0]
    assert (w["a"], w["b"], w["e"]) == pytest.approx((v["a"], v["b"], 0.05), abs=1e-14)
    # stroke from the extreme positions x = √((b ± a)² − e²)
    assert v["x_C2"] - v["x_C1"] == pytest.approx(0.3, abs=1e-14)
    # too large an offset: no solution (e ≤ H / (2 tan(θ/2)))
    emax = 0.3 / (2 * math.tan(S.theta_of_K(1.4) / 2))
    assert S.slider_crank(1.4, 0.3, e=1.01 * emax) == []


def test_slotted_lever_formulas():
    v = S.slotted_lever(1.5, 0.4, d=0.5)[0]
    th = math.pi * 0.5 / 2.5
    assert v["a"] == pytest.approx(0.5 * math.sin(th / 2), abs=1e-15)
    assert 2 * v["l"] * math.sin(v["psi"] / 2) == pytest.approx(0.4, abs=1e-15)
    assert S.K_of_theta(v["theta"]) == pytest.approx(1.5, abs=1e-14)


def _spec(tmp_path, text):
    p = tmp_path / "c.toml"
    p.write_text(text, encoding="utf-8")
    from reportgen.case.load import load_spec
    return load_spec(p)


def test_errors_are_case_errors(tmp_path):
    base = '[parameters]\nH = "0.3 m"\n[synthesis]\ntype = "slider_crank"\nK = 1.4\nH = "H"\n'
    spec = _spec(tmp_path, base + 'e = "0.05 m"\nvariant = 3\n')
    with pytest.raises(CaseError, match="вариант 3"):
        spec.parameters()
    spec = _spec(tmp_path, base + 'e = "0.05 m"\nlam = 0.3\n')
    with pytest.raises(CaseError, match="ровно один"):
        spec.parameters()
    spec = _spec(tmp_path, base + 'e = "5 m"\n')
    with pytest.raises(CaseError, match="не имеет решения"):
        spec.parameters()
    spec = _spec(tmp_path, base.replace("K = 1.4", "K = 0.5") + 'e = "0.05 m"\n')
    with pytest.raises(CaseError, match="K"):
        spec.parameters()


def test_parameters_may_use_results(tmp_path):
    spec = _spec(tmp_path, '[parameters]\nH = "0.3 m"\nl_AS2 = "0.5*l_AB"\n'
                           '[synthesis]\ntype = "slider_crank"\nK = 1.4\nH = "H"\nlam = 0.25\n'
                           'names = { b = "l_AB" }\n')
    assert isinstance(spec, CaseSpec)
    p = spec.parameters()
    assert float(p["l_AS2"].value) == pytest.approx(0.5 * float(p["syn_b"].value), abs=0)
    st = load_case(spec.path)
    assert not st.has_linkage and st.tasks() == ["synthesis"]
    assert st.synthesis.check is None
    assert set(st.synthesis.tables()) == {"synthesis_variants"}


@pytest.mark.parametrize("name, n", [("synth_crank_rocker", 4), ("ws001_p6_six_bar", 4)])
def test_every_variant_reproduces(tmp_path, name, n):
    """Every listed variant, put back into the engine, has the asked swing (stroke) and K."""
    import re
    text = (CASES / f"{name}.toml").read_text(encoding="utf-8")
    for k in range(1, n + 1):
        p = tmp_path / f"{name}_{k}.toml"
        p.write_text(re.sub(r"(?m)^variant = \d+", f"variant = {k}", text, count=1), encoding="utf-8")
        sy = load_case(p).synthesis
        assert sy.chosen["variant"] == k
        assert sy.check["stroke"] == pytest.approx(sy.target_stroke(), abs=1e-10)
        assert sy.check["K"] == pytest.approx(sy.inputs["K"], abs=1e-10)


def test_K_one_slider_crank(tmp_path):
    base = '[parameters]\nH = "0.3 m"\n[synthesis]\ntype = "slider_crank"\nK = 1\nH = "H"\n'
    with pytest.raises(CaseError, match="K = 1"):
        _spec(tmp_path, base + 'e = "0.05 m"\n').parameters()
    p = _spec(tmp_path, base + "lam = 0.25\n").parameters()
    assert float(p["syn_a"].value) == pytest.approx(0.15, abs=1e-15)     # H = 2a
    assert float(p["syn_e"].value) == pytest.approx(0.0, abs=1e-15)


def test_shaper_ram_stroke_is_the_chord_of_the_lever_end():
    """The shaper (slotted lever, coupler, ram): independent closed form of the ram's position in
    the lever's extreme positions ±θ/2 from the vertical, x_E = l·sin(±θ/2) + √(l₄² − (y_E − l·cos(θ/2))²),
    whose difference is the chord 2l·sin(θ/2) = H; the engine's ram stroke and K equal H and K."""
    st = load_case(CASES / "synth_shaper.toml")
    v = st.synthesis.chosen
    l, th = v["l"], v["theta"]
    l4 = 0.3 * l
    yE = l * (1 + math.cos(th / 2)) / 2
    xs = [l * math.sin(s * th / 2) + math.sqrt(l4 ** 2 - (yE - l * math.cos(th / 2)) ** 2) for s in (-1, 1)]
    chk = st.synthesis.check
    assert chk["column"] == "s_50"
    assert xs[1] - xs[0] == pytest.approx(0.4, abs=1e-15)
    assert chk["stroke"] == pytest.approx(xs[1] - xs[0], abs=1e-12) and chk["K"] == pytest.approx(1.5, abs=1e-10)
    assert max(chk["s1"], chk["s2"]) == pytest.approx(xs[1], abs=1e-12)


def test_shaper_construction_draws_the_ram_at_both_extremes():
    """The synthesis drawing of the shaper shows the coupler and the ram in both extreme
    positions: the ram's points E₁, E₂ lie on the synthesised guide y_E = l(1 + cos(θ/2))/2 (the
    middle of the sag of the arc of D), the lever's end at the synthesised D₁, D₂, E₁E₂ = H, the
    coupler length |DE| = 0,3·l, and the labels E₁, E₂ and the dimensions H, f are drawn."""
    from reportgen.scenes.synthesis import SynthesisConstruction
    st = load_case(CASES / "synth_shaper.toml")
    v = st.synthesis.chosen
    l, h = v["l"], v["theta"] / 2
    ram = SynthesisConstruction._ram(st)
    assert ram is not None and (ram["D"], ram["E"]) == ("D", "E")
    y_E = l * (1 + math.cos(h)) / 2
    es = [(r["x_E"], r["y_E"]) for r in ram["rows"]]
    ds = [(r["x_D"], r["y_D"]) for r in ram["rows"]]
    for (xd, yd), s in zip(ds, (-1.0, 1.0)):
        assert xd == pytest.approx(s * l * math.sin(h), abs=1e-9) and yd == pytest.approx(l * math.cos(h), abs=1e-9)
    for p, q in zip(ds, es):
        assert q[1] == pytest.approx(y_E, abs=1e-9)
        assert _dist(p, q) == pytest.approx(0.3 * l, abs=1e-12)
    assert es[1][0] - es[0][0] == pytest.approx(v["H"], abs=1e-9)
    svg = SynthesisConstruction().draw(st).svg.decode()
    for name in ("E₁", "E₂", "D₁", "D₂", "<!-- H -->", "<!-- f -->"):
        assert name in svg


def test_slotted_lever_alone_has_no_ram():
    from reportgen.scenes.synthesis import SynthesisConstruction
    st = load_case(CASES / "synth_slotted_lever.toml")
    assert SynthesisConstruction._ram(st) is None
