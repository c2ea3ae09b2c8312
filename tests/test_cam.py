"""Cam mechanisms: laws, synthesis by the allowed pressure angle, the profile, worksheet 001/2013-2."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from reportgen.analysis.study import Study
from reportgen.errors import CaseError

ROOT = Path(__file__).resolve().parents[1]


def make(tmp_path, body: str, name="c.toml") -> Study:
    p = tmp_path / name
    p.write_text("[meta]\ntitle = \"t\"\n" + body, encoding="utf-8")
    return Study(p)


def trans(law_rise="sine", law_ret="sine", extra_rise="", extra_ret="", head="", contact="roller"):
    return f"""
[cam]
follower = "translating"
contact = "{contact}"
r0_round = "0 mm"
stroke = "30 mm"
far_dwell = "30 deg"
{head}
[cam.rise]
angle = "120 deg"
law = "{law_rise}"
allowed = "30 deg"
{extra_rise}
[cam.return]
angle = "100 deg"
law = "{law_ret}"
allowed = "45 deg"
{extra_ret}
"""


# ---------------------------------------------------------------- laws
# law, extra keys, s′max·β/h, s″max·β²/h, the highest continuous analog at the ends (1: s′, 2: s″)
LAWS = [
    ("uniform", "", 1.0, 0.0, 0),
    ("parabolic", "", 2.0, 4.0, 1),
    ("cosine", "", math.pi / 2, math.pi ** 2 / 2, 1),
    ("sine", "", 2.0, 2 * math.pi, 2),
    ("poly345", "", 15 / 8, 10 / math.sqrt(3), 2),
    ("poly4567", "", 35 / 16, 84 / (5 * math.sqrt(5)), 2),
    ("sine", "nu = 1.5", 2.0, math.pi / 0.4, 2),   # x₁ = ν/(1+ν) = 0.6, A₂ = π/(1 − x₁) = ν A₁
    ("parabolic", "nu = 3", 2.0, 2 / 0.25, 1),   # a₂ = 2/(1 − x₁) = ν a₁
    # linear ramps t = 1/8: f″max = 1/(1/4 − t/2) from f(1) = 1, f′max = f″max (1/2 − t)
    ("trapezoidal", "", 2.0, 16 / 3, 2),
]


@pytest.mark.parametrize("law,extra,v1,v2,cont", LAWS, ids=[f"{a}-{b}" for a, b, *_ in LAWS])
def test_law_extremes_and_continuity(tmp_path, law, extra, v1, v2, cont):
    c = make(tmp_path, trans(law, law, extra, extra)).cam
    h, b = c.h, c.rise.length
    x = np.linspace(0, b, 20001)
    s, s1, s2, s3 = c.law(x)
    assert s[0] == pytest.approx(0, abs=1e-15) and c.law([b], -1)[0][0] == pytest.approx(h, rel=1e-13)
    assert s1.max() * b / h == pytest.approx(v1, rel=1e-6)
    if law != "uniform":
        assert np.abs(s2).max() * b * b / h == pytest.approx(v2, rel=1e-6)
    # s is continuous everywhere; s′ unless uniform; s″ where the law claims it
    kinds = {i["kind"] for i in c.impacts}
    assert kinds == ({"hard"} if cont == 0 else {"soft"} if cont == 1 else set())
    # the analogs are the derivatives of each other (central differences inside the pieces)
    ph = np.linspace(0.05, 2 * math.pi - 0.05, 301)
    d = 1e-6
    for lo, hi in ((0, 1), (1, 2), (2, 3)):
        num = (c.law(ph + d)[lo] - c.law(ph - d)[lo]) / (2 * d)
        ok = np.ones_like(ph, dtype=bool)
        for p in c.phases:
            for q in c.breaks(p) if p.law else [p.start]:
                ok &= np.abs(ph - q) > 10 * d
        scale = np.abs(c.law(ph)[hi]).max() + h / b ** hi
        assert np.allclose(num[ok], c.law(ph)[hi][ok], atol=1e-5 * scale)


def test_sine_symmetric_closed_form(tmp_path):
    c = make(tmp_path, trans()).cam
    b, h = c.rise.length, c.h
    x = np.linspace(0, 1, 101)
    s = c.law(x * b)[0]
    assert np.allclose(s, h * (x - np.sin(2 * np.pi * x) / (2 * np.pi)), atol=1e-15)
    # return mirrors the rise: s = h(1 − f)
    r = c.ret
    sr = c.law(r.start + x[:-1] * r.length)[0]
    assert np.allclose(sr, h * (1 - (x[:-1] - np.sin(2 * np.pi * x[:-1]) / (2 * np.pi))), atol=1e-15)


def test_table_law_integrated_exactly(tmp_path):
    # the modified trapezoid given as a table equals the trapezoidal law
    tab = "table = [[0, 0], [0.125, 1], [0.375, 1], [0.625, -1], [0.875, -1], [1, 0]]"
    a = make(tmp_path, trans("table", "sine", tab), "a.toml").cam
    b = make(tmp_path, trans("trapezoidal", "sine"), "b.toml").cam
    x = np.linspace(0, a.rise.length, 777)
    for u, v in zip(a.law(x), b.law(x)):
        assert np.allclose(u, v, atol=1e-14)
    # exact: the trapezoid's s at the end of the first ramp (a = A·x/t): f = A t²/6
    A = b.law([0.0625 * b.rise.length])[2][0] * b.rise.length ** 2 / b.h * 2
    f = b.law([0.125 * b.rise.length])[0][0] / b.h
    assert f == pytest.approx(A * 0.125 ** 2 / 6, rel=1e-13)


def test_table_law_unbalanced_is_case_error(tmp_path):
    with pytest.raises(CaseError) as e:
        make(tmp_path, trans("table", "sine", "table = [[0, 1], [0.5, 1], [0.5, -0.5], [1, -0.5]]")).cam
    assert "площадь" in str(e.value)


@pytest.mark.parametrize("body,key", [
    (trans("spline"), "law"),
    (trans("cosine", "sine", "nu = 2"), "nu"),
    (trans().replace('allowed = "30 deg"', ""), "allowed"),
    (trans().replace('stroke = "30 mm"', 'stroke = "30 kg"'), "stroke"),
    (trans().replace('angle = "120 deg"', 'angle = "300 deg"'), "return"),
])
def test_case_errors(tmp_path, body, key):
    with pytest.raises(CaseError) as e:
        make(tmp_path, body).cam
    assert key in str(e.value)


# ---------------------------------------------------------------- synthesis
def _theta_limits_ok(c, r0_scale=1.0):
    th = c.pressure_angle(c.grid)
    rise = (c.grid >= c.rise.start) & (c.grid <= c.rise.start + c.rise.length)
    ret = (c.grid >= c.ret.start) & (c.grid <= c.ret.start + c.ret.length)
    return th[rise].max(), (-th[ret]).max()


@pytest.mark.parametrize("laws", [("sine", "poly345"), ("cosine", "cosine"), ("poly4567", "parabolic")])
def test_translating_min_r0_by_pressure_angle(tmp_path, laws):
    st = make(tmp_path, trans(*laws))
    c = st.cam
    syn = c.synthesis
    t1, t2 = c.theta_max
    a1, a2 = c.rise.allowed, c.ret.allowed
    # governing phase: the maximum equals the allowed angle to 1e-9; never above elsewhere
    if syn.governing in ("rise", "both"):
        assert t1 == pytest.approx(a1, abs=1e-9)
    if syn.governing in ("return", "both"):
        assert t2 == pytest.approx(a2, abs=1e-9)
    g1, g2 = _theta_limits_ok(c)
    assert g1 <= a1 + 1e-12 and g2 <= a2 + 1e-12
    # tg ϑ = (s′ − e)/(s₀ + s) at the tangent point of the rise ray: s″/s′ = tg[ϑ] …
    s, s1, s2, _ = c.law([syn.phi_rise])
    if syn.governing in ("rise", "both"):
        assert s2[0] / s1[0] == pytest.approx(math.tan(a1), rel=1e-9)
    # … and a smaller r₀ (same e) violates it
    small = make(tmp_path, trans(*laws, head=f'r0 = {syn.r0 * 0.99}\ne = {syn.e}'), "s.toml").cam
    b1, b2 = small.theta_max
    assert b1 > a1 + 1e-4 or b2 > a2 + 1e-4
    # the approximate variant (rays through s′max) is no larger than the exact one
    assert syn.r0_approx <= syn.r0 + 1e-15


def test_translating_fixed_e_central(tmp_path):
    c = make(tmp_path, trans(head="e = 0")).cam
    syn = c.synthesis
    assert syn.e == 0 and syn.r0 == pytest.approx(syn.s0)
    t1, t2 = c.theta_max
    assert max(t1 - c.rise.allowed, t2 - c.ret.allowed) == pytest.approx(0, abs=1e-9)


@pytest.mark.parametrize("rot", ["cw", "ccw"])
def test_rocker_synthesis(tmp_path, rot):
    src = (ROOT / "cases/cam_rocker_roller.toml").read_text(encoding="utf-8").replace(
        'rotation = "cw"', f'rotation = "{rot}"').replace("[cam]", '[cam]\nr0_round = "0 mm"', 1)
    (tmp_path / "r.toml").write_text(src, encoding="utf-8")
    st = Study(tmp_path / "r.toml")
    c = st.cam
    syn = c.synthesis
    t1, t2 = c.theta_max
    assert syn.governing == "both"
    assert t1 == pytest.approx(c.rise.allowed, abs=1e-9)
    assert t2 == pytest.approx(c.ret.allowed, abs=1e-9)
    g1, g2 = _theta_limits_ok(c)
    assert g1 <= c.rise.allowed + 1e-12 and g2 <= c.ret.allowed + 1e-12
    # r₀ = |O B₀|, a_w = |O A|, consistent with the law of cosines and ψ₀
    l = c.arm
    assert syn.r0 ** 2 == pytest.approx(syn.a_w ** 2 + l * l - 2 * syn.a_w * l * math.cos(syn.psi0), rel=1e-12)
    # the same centre given as a_w, ψ₀ reproduces the angles; moving it 1 % closer to B₀ violates them
    body = src.split("[cam]", 1)[1]
    fixed = make(tmp_path, "[cam]\n" + f"a_w = {syn.a_w}\npsi0 = \"{math.degrees(syn.psi0)!r} deg\"\n" + body).cam
    assert fixed.theta_max[0] == pytest.approx(t1, abs=1e-9)
    Ob = syn.O + 0.01 * (np.array([l, 0]) - syn.O)
    aw, ps = float(np.hypot(*Ob)), math.atan2(-Ob[1], Ob[0])
    near = make(tmp_path, "[cam]\n" + f"a_w = {aw}\npsi0 = \"{math.degrees(ps)!r} deg\"\n" + body, "n.toml").cam
    b1, b2 = near.theta_max
    assert b1 > c.rise.allowed + 1e-5 or b2 > c.ret.allowed + 1e-5


def test_flat_face_convexity(tmp_path):
    body = trans("sine", "cosine", contact="flat").replace('allowed = "30 deg"', "").replace('allowed = "45 deg"', "")
    c = make(tmp_path, body).cam
    r0 = c.synthesis.r0
    m, p, need = c.flat_min
    assert r0 == pytest.approx(c.rho_min - m, rel=1e-14)
    rho = c.profile(c.grid)["rho"]
    assert rho.min() >= c.rho_min - 1e-12           # convex with ρ ≥ ρ_min
    s, s1, s2, _ = c.law(c.grid)
    assert np.allclose(rho, r0 + s + s2, atol=1e-12)   # ρ = r₀ + s + s″ (inversion formula vs textbook)
    smaller = make(tmp_path, body.replace("[cam.rise]", f"r0 = {r0 - c.rho_min - 1e-4}\n[cam.rise]"), "s.toml").cam
    assert smaller.profile(np.array([p]))["rho"][0] == pytest.approx(-1e-4, abs=1e-12)   # at the exact minimum
    assert c.scalars["cam_face_width"] == pytest.approx(s1.max() - s1.min())


# ---------------------------------------------------------------- profile
@pytest.mark.parametrize("case,change", [
    ("cam_translating_roller.toml", None), ("cam_rocker_roller.toml", None),
    ("cam_rocker_roller.toml", ('rotation = "cw"', 'rotation = "ccw"')),
    ("cam_translating_roller.toml", ('contact = "roller"\nrotation = "ccw"', 'contact = "knife"\nrotation = "cw"'))])
def test_profile_normal_gives_pressure_angle(tmp_path, case, change):
    src = (ROOT / "cases" / case).read_text(encoding="utf-8")
    if change:
        assert change[0] in src
        src = src.replace(*change)
    (tmp_path / case).write_text(src, encoding="utf-8")
    c = Study(tmp_path / case).cam
    phi = np.linspace(0.01, 2 * math.pi - 0.01, 997)
    d = 1e-6
    for key in ("C", "W"):
        t = (c.profile(phi + d)[key] - c.profile(phi - d)[key]) / (2 * d)
        n = np.column_stack([-t[:, 1], t[:, 0]])       # a normal of the profile in the cam frame
        k = c.k
        cph, sph = np.cos(k * phi), np.sin(k * phi)     # back to the fixed frame: R(kφ)
        N = np.column_stack([cph * n[:, 0] - sph * n[:, 1], sph * n[:, 0] + cph * n[:, 1]])
        f = c.frames(phi)
        # the pressure angle: between the normal and the follower's velocity u
        th = c.pressure_angle(phi)
        cosang = np.abs(np.einsum("ij,ij->i", N, f["u"])) / np.hypot(*N.T)
        assert np.allclose(cosang, np.cos(th), atol=2e-7)
    # the working profile is the exact offset: at distance r_р along the normal
    p = c.profile(phi)
    assert np.allclose(np.hypot(*(p["C"] - p["W"]).T), c.roller, atol=1e-15)


def test_worksheet_001_2013_2():
    """Olympiad 2013, problem 2: flat face, S = aφ, H = 40 mm on 180°, r0 = 40 mm:
    r = √((S + r₀)² + S′²), the worksheet prints 41,98; 46,77; 51,6; 56,45; 61,34 mm."""
    c = Study(ROOT / "cases/ws001_cam_2013_2.toml").cam
    phi = np.array([0, 1, 2, 3, 4]) * math.pi / 8
    r = c.profile_table(phi)["r"].to_numpy() * 1000
    assert np.round(r, 2).tolist() == [41.98, 46.77, 51.60, 56.45, 61.34]
    a = 40 / math.pi
    s = 40 * phi / math.pi
    assert np.allclose(r, np.sqrt((s + 40) ** 2 + a ** 2), atol=1e-12)
    assert c.scalars["cam_impacts_hard"] == 2


# ---------------------------------------------------------------- export / check of a cam-only case
def test_cli_check_and_export(tmp_path, capsys):
    from reportgen.cli import main
    case = str(ROOT / "cases/cam_translating_roller.toml")
    assert main(["check", case]) == 0
    assert main(["export", case, "-o", str(tmp_path)]) == 0
    names = {p.name for p in tmp_path.rglob("*")}
    assert {"cam.csv", "cam_profile.csv", "scalars.json"} <= names
    import json
    sc = json.loads(next(tmp_path.rglob("scalars.json")).read_text())
    # r₀ taken up to 29 мм: the pressure angle stays below the allowed 30° (28,62 мм reaches it)
    assert sc["cam_r0"] == pytest.approx(0.029, abs=1e-12)
    assert math.radians(29) < sc["cam_theta_rise_max"] < math.radians(30)
    bad = tmp_path / "bad.toml"
    bad.write_text((ROOT / "cases/cam_translating_roller.toml").read_text(encoding="utf-8")
                   .replace('law = "sine"', 'law = "sinus"'), encoding="utf-8")
    assert main(["check", str(bad)]) == 2
    assert "sinus" in capsys.readouterr().err


@pytest.mark.parametrize("laws,rot", [(("sine", "poly345"), "ccw"), (("cosine", "poly4567"), "cw")])
def test_translating_closed_form_vs_generic_solver(tmp_path, laws, rot):
    """The closed form (two families of parallel rays) and the general solver used for the rocker
    (SLSQP on the exact constraint maxima + Newton on the contact conditions) give one centre."""
    c = make(tmp_path, trans(*laws, head=f'rotation = "{rot}"')).cam
    O = c.synth_generic(np.zeros(2), c.h)
    assert np.allclose(O, c._O_synth, atol=1e-10 * c.h)


def test_central_knife_r0_by_brute_force(tmp_path):
    """Independent of the root finding: for e = 0 the least s₀ is max over a dense sampling of
    (s′/tg[ϑ_у] − s) on the rise and (−s′/tg[ϑ_в] − s) on the return."""
    c = make(tmp_path, trans("sine", "cosine", head="e = 0", contact="knife")).cam
    t1, t2 = math.tan(c.rise.allowed), math.tan(c.ret.allowed)
    p1 = np.linspace(c.rise.start, c.rise.start + c.rise.length, 200001)
    p2 = np.linspace(c.ret.start, c.ret.start + c.ret.length, 200001)
    s, s1 = c.law(p1)[:2]
    u, u1 = c.law(p2)[:2]
    brute = max((s1 / t1 - s).max(), (-u1 / t2 - u).max())
    assert c.synthesis.r0 == pytest.approx(brute, rel=1e-9)
    assert c.synthesis.r0 >= brute


def test_roller_radius_rule():
    c = Study(ROOT / "cases/cam_translating_roller.toml").cam
    rc = c.rho_min_centre
    rho = c.profile(c.grid)["rho_c"]
    assert rc <= rho[rho > 0].min() + 1e-15
    assert c.roller <= min(0.7 * rc, 0.4 * c.synthesis.r0) and c.roller > min(0.7 * rc, 0.4 * c.synthesis.r0) - 1e-3
    assert (c.profile(c.grid)["rho"][rho > 0] > 0).all()       # no undercut: ρ − r_р > 0 on convex parts
    tab = c.tables()
    assert all(np.isfinite(df.select_dtypes("number").to_numpy()).all() for df in tab.values())


def test_profile_scale_requested_or_refused(tmp_path):
    from reportgen.scenes.cam import ProfileDrawing
    st = Study(ROOT / "cases/ws001_cam_2013_2.toml")        # asks 2:1, the whole cam needs 1:1
    d = ProfileDrawing()
    d.draw(st)
    assert d.refused == "2:1" and d.scale == "1:1"
    body = (ROOT / "cases/cam_translating_roller.toml").read_text(encoding="utf-8").replace(
        'step = "10 deg"', 'step = "10 deg"\nscale = "1:2"')
    p = tmp_path / "c.toml"
    p.write_text(body, encoding="utf-8")
    d = ProfileDrawing()
    d.draw(Study(p))
    assert d.refused is None and d.scale == "1:2" and d.mu == 0.002


def _texts(block):
    from reportgen.report.document import Figure, FormulaBlock, Paragraph, Section, Table
    if isinstance(block, Section):
        yield block.title
        for c in block.children:
            yield from _texts(c)
    elif isinstance(block, Paragraph):
        yield str(block.html)
    elif isinstance(block, Table):
        yield block.caption
        yield " ".join(c.header for c in block.columns)
        yield block.data.to_string(header=False, index=False)
    elif isinstance(block, Figure):
        yield block.caption
    elif isinstance(block, FormulaBlock):
        for f in block.formulas:
            yield f.latex()


@pytest.mark.parametrize("case", ["cam_translating_roller.toml", "ws001_cam_2013_2.toml"])
def test_note_section_text(case):
    from reportgen.report.sections import cam as S
    st = Study(ROOT / "cases" / case)
    assert S.present(st)
    sec = S.build(st)
    text = "\n".join(_texts(sec))
    for bad in ("nan", "None", "inf", "cam_", "synthesis", "rho_c", "phi_deg"):
        assert bad not in text, bad
    ids = [c.id for c in sec.children]
    assert ids[0] == "sec-cam-data" and ids[-1] == "sec-cam-profile"
    lines = " ".join(S.conclusion_lines(st))
    if st.cam.contact == "flat":
        assert "40,00" in lines and "жёсткие удары — в&nbsp;2\u00a0положениях" in lines
    else:
        assert "28,62" in lines and "мягких" not in lines


def test_linkage_and_cam_in_one_case(tmp_path):
    cam = (ROOT / "cases/cam_translating_roller.toml").read_text(encoding="utf-8").split("[cam]", 1)[1]
    link = (ROOT / "cases/four_bar.toml").read_text(encoding="utf-8")
    p = tmp_path / "both.toml"
    p.write_text(link + "\n[cam]" + cam, encoding="utf-8")
    st = Study(p)
    assert st.has_linkage and "cam" in st.tasks()
    sc = st.all_scalars()
    assert sc["cam_r0"] == pytest.approx(Study(ROOT / "cases/cam_translating_roller.toml").cam.synthesis.r0)
    assert "W" in sc


def test_approximate_variant_two_formulations(tmp_path):
    """The approximate variant (rays through the points of s′max) in (e, s₀) closed form equals the
    nearest point of the two half-planes in the plane of the centre; the same holds for the exact
    tangent rays when both govern."""
    c = make(tmp_path, trans("sine", "poly345")).cam
    syn = c.synthesis
    q1 = c.phase_extreme(c.rise, lambda p, sd: c._at(p, sd)[1], lambda p, sd: c._at(p, sd)[2])[1]
    q2 = c.phase_extreme(c.ret, lambda p, sd: -c._at(p, sd)[1], lambda p, sd: -c._at(p, sd)[2])[1]
    Oa = c.nearest_in_two(np.zeros(2), c.halfplane(1, q1), c.halfplane(2, q2))
    assert -c.k * Oa[0] == pytest.approx(syn.e_approx, abs=1e-13)
    assert float(np.hypot(*Oa)) == pytest.approx(syn.r0_approx, rel=1e-12)
    assert syn.governing == "both"
    O = c.nearest_in_two(np.zeros(2), c.halfplane(1, syn.phi_rise), c.halfplane(2, syn.phi_return))
    assert np.allclose(O, c._O_synth, atol=1e-13)
