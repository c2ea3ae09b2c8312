"""Flat-faced rocker (коромысло с плоской тарелкой): the envelope profile, the contact point, the
pressure angle tg ϑ = d/μ, convexity, and the synthesis of a_w and ψ₀ — each checked against a
second, independent formulation (tangency of the face lines, the face angle found by touching the
rotated profile, the curvature from the exact derivatives of the profile, a brute-force scan)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from reportgen.analysis.study import Study
from reportgen.errors import CaseError

ROOT = Path(__file__).resolve().parents[1]
CASE = ROOT / "cases" / "cam_rocker_flat.toml"


def make(tmp_path, body: str, name="c.toml") -> Study:
    p = tmp_path / name
    p.write_text("[meta]\ntitle = \"t\"\n" + body, encoding="utf-8")
    return Study(p)


def flat(head="", rot="ccw", rise="sine", ret="cosine", allowed=("30 deg", "30 deg")) -> str:
    al = [f'allowed = "{a}"' if a else "" for a in allowed]
    return f"""
[cam]
follower = "rocker"
contact = "flat"
r0_round = "0 mm"
rotation = "{rot}"
swing = "20 deg"
far_dwell = "20 deg"
{head}
[cam.rise]
angle = "100 deg"
law = "{rise}"
{al[0]}
[cam.return]
angle = "100 deg"
law = "{ret}"
{al[1]}
"""


def _rot(phi, k, V, back=False):
    """R(−kφ)V (into the cam frame) or R(kφ)V (back to the fixed frame), row-wise."""
    c, s = np.cos(k * phi), np.sin(k * phi)
    if back:
        s = -s
    return np.column_stack([c * V[:, 0] + s * V[:, 1], -s * V[:, 0] + c * V[:, 1]])


@pytest.fixture(scope="module")
def case_cam(tmp_path_factory):
    """The case's cam with its least sizes (r₀ not rounded up: the synthesis under test)."""
    p = tmp_path_factory.mktemp("case") / "c.toml"
    p.write_text(CASE.read_text(encoding="utf-8").replace("[cam]", '[cam]\nr0_round = "0 mm"', 1), encoding="utf-8")
    return Study(p).cam


@pytest.fixture(scope="module", params=[("ccw", "10 mm"), ("cw", "10 mm"), ("ccw", "0 mm")])
def variant(request, tmp_path_factory):
    rot, d = request.param
    head = f'face_offset = "{d}"\npsi0 = "62 deg"' if d == "0 mm" else f'face_offset = "{d}"'
    return make(tmp_path_factory.mktemp("v"), flat(head, rot), "v.toml").cam


# ---------------------------------------------------------------- geometry
def test_face_tangent_to_profile(variant):
    """Every face line (built from the pivot, the offset and ψ(φ) alone) leaves the whole profile on
    the cam's side and touches it at the contact point: distance ≥ 0 everywhere, = 0 at contact."""
    c = variant
    syn = c.synthesis
    dense = np.linspace(0.0, 2 * math.pi, 14401)
    X = c.profile(dense)["W"]                                  # cam frame, O at the origin
    phi = np.linspace(0.003, 2 * math.pi - 0.003, 181)
    s = c.law(phi)[0]
    A = -syn.O                                                 # pivot from O in the fixed frame
    u = np.column_stack([-np.sin(s), np.cos(s)])
    F = A - c.face_offset * u                                  # a point of the face line
    Fc, uc = _rot(phi, c.k, F), _rot(phi, c.k, u)              # the face line in the cam frame
    dist = np.einsum("ij,ij->i", Fc, uc)[:, None] - uc @ X.T   # (F − X)·u
    assert dist.min() >= -1e-12
    K = c.profile(phi)["W"]
    at = np.einsum("ij,ij->i", Fc - K, uc)
    assert np.abs(at).max() < 1e-14


def test_face_angle_from_rotated_profile_is_the_law(variant):
    """The rocker's angle found directly: rotate the drawn profile to the cam angle φ and turn the
    face about the pivot until it touches the profile; it equals ψ(φ) of the law."""
    c = variant
    syn, k, d = c.synthesis, c.k, c.face_offset
    X = c.profile(np.linspace(0.0, 2 * math.pi, 40001))["W"]
    A = -syn.O
    for phi in np.linspace(0.05, 2 * math.pi - 0.05, 23):
        Y = _rot(np.full(len(X), phi), k, X, back=True) - A   # profile in the fixed frame, from A

        def gap(psi):
            return float((Y @ np.array([-math.sin(psi), math.cos(psi)])).max()) + d
        psi = brentq(gap, -0.1, c.h + 0.1, xtol=1e-14)
        assert psi == pytest.approx(c._at(phi)[0], abs=2e-7)


def test_profile_normal_gives_pressure_angle(variant):
    """The profile's normal (finite differences of the profile) back in the fixed frame is the face
    normal, and its angle with the velocity of the rocker's point K (⊥ AK) is ϑ = arctg(d/μ)."""
    c = variant
    syn = c.synthesis
    phi = np.linspace(0.01, 2 * math.pi - 0.01, 997)
    h = 1e-6
    t = (c.profile(phi + h)["W"] - c.profile(phi - h)["W"]) / (2 * h)
    N = _rot(phi, c.k, np.column_stack([-t[:, 1], t[:, 0]]), back=True)
    N /= np.hypot(*N.T)[:, None]
    f = c.frames(phi)
    assert np.allclose(np.abs(np.einsum("ij,ij->i", N, f["u"])), 1.0, atol=1e-8)
    K = _rot(phi, c.k, c.profile(phi)["W"], back=True)         # contact point from O, fixed frame
    AK = K + syn.O
    v = np.column_stack([-AK[:, 1], AK[:, 0]])                 # direction of the velocity of K
    cosang = np.abs(np.einsum("ij,ij->i", N, v)) / np.hypot(*v.T)
    th = c.pressure_angle(phi)
    assert np.allclose(cosang, np.cos(th), atol=1e-8)
    # the contact point's distance along the face from the foot of the perpendicular from A
    assert np.allclose(np.einsum("ij,ij->i", AK, f["r"]), f["mu"], atol=1e-15)
    if c.face_offset == 0:
        assert np.abs(th).max() == 0.0


def test_contact_by_instant_centre(variant):
    """Kennedy: the common normal at K passes through P₁₂ on AO where the cam and the rocker have
    equal velocities (ω₁·OP₁₂ = ω₂·AP₁₂, found here by a root of the velocity difference)."""
    c = variant
    syn = c.synthesis
    A = -syn.O
    for phi in np.linspace(0.1, 2 * math.pi - 0.1, 19):
        s1 = c._at(phi)[1]
        e = -A / np.hypot(*A)                                  # from A towards O

        def dv(x):   # velocity of the point A + x e as a cam point minus as a rocker point (ω = 1)
            P = A + x * e
            vc = c.k * np.array([-P[1], P[0]])
            vr = s1 * np.array([-(P - A)[1], (P - A)[0]])
            return float((vc - vr) @ np.array([-e[1], e[0]]))
        x = brentq(dv, -50 * syn.a_w, 50 * syn.a_w, xtol=1e-15)
        P12 = A + x * e
        K = _rot(np.array([phi]), c.k, c.profile(np.array([phi]))["W"], back=True)[0]
        u = c.frames(np.array([phi]))["u"][0]
        assert abs((K - P12) @ np.array([-u[1], u[0]])) < 1e-12    # K − P₁₂ along the normal


def test_curvature_three_ways(variant):
    """ρ = a_w G − d (support function) equals −k|C′|³/(C′ × C″) with the exact derivatives of the
    contact point, and the curvature from finite differences of the profile."""
    c = variant
    phi = np.linspace(0.01, 2 * math.pi - 0.01, 500)
    f, k = c.frames(phi), c.k
    J = lambda V: np.column_stack([-V[:, 1], V[:, 0]])      # noqa: E731
    C1 = _rot(phi, k, f["P1"] - k * J(f["P"]))
    C2 = _rot(phi, k, f["P2"] - 2 * k * J(f["P1"]) - f["P"])
    rho = c.profile(phi)["rho"]
    gen = -k * np.hypot(*C1.T) ** 3 / (C1[:, 0] * C2[:, 1] - C1[:, 1] * C2[:, 0])
    assert np.allclose(gen, rho, rtol=1e-11)
    h = 1e-4
    Cp, C0, Cm = (c.profile(phi + x)["W"] for x in (h, 0.0, -h))
    d1, d2 = (Cp - Cm) / (2 * h), (Cp - 2 * C0 + Cm) / h ** 2
    fd = -k * np.hypot(*d1.T) ** 3 / (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    assert np.allclose(fd, rho, rtol=1e-5)


# ---------------------------------------------------------------- synthesis
def test_case_synthesis_convex_and_pressure(case_cam):
    """The case: both conditions govern — ρ_min reached exactly and the largest ϑ equals [ϑ_в] (to
    1e-9) and is nowhere above the allowed angle; a 1 % smaller r₀ at the same ψ₀ is not convex."""
    c = case_cam
    syn, sc = c.synthesis, c.scalars
    assert syn.governing == "both"
    assert sc["cam_rho_min"] == pytest.approx(c.rho_min, abs=1e-12)
    g = np.linspace(0, 2 * math.pi, 72001)
    assert c.profile(g)["rho"].min() >= c.rho_min - 1e-12
    th = c.pressure_angle(g)
    assert th.max() <= max(c.rise.allowed, c.ret.allowed) + 1e-12
    assert max(c.theta_max) == pytest.approx(math.radians(30), abs=1e-9)
    assert sc["cam_r0"] == pytest.approx(syn.a_w * math.sin(syn.psi0) - c.face_offset, rel=1e-15)
    # exact extremes of μ vs a dense grid
    mu = c.frames(g)["mu"]
    assert mu.min() - 1e-7 * mu.min() <= sc["cam_face_min"] <= mu.min()
    assert mu.max() <= sc["cam_face_max"] <= mu.max() * (1 + 1e-7)


def _smaller(tmp_path, c, factor=0.99):
    """The same ψ₀ with r₀ smaller by the factor: a_w = (r₀ + d)/sin ψ₀."""
    syn = c.synthesis
    a = (factor * syn.r0 + c.face_offset) / math.sin(syn.psi0)
    head = (f'face_offset = "{c.face_offset!r} m"\na_w = "{a!r} m"\npsi0 = "{syn.psi0!r} rad"\n'
            f'rho_min = "{c.rho_min!r} m"')
    return make(tmp_path, flat(head, "ccw" if c.k > 0 else "cw"), "small.toml").cam


def test_smaller_r0_is_not_convex(tmp_path, case_cam):
    sm = _smaller(tmp_path, case_cam)
    assert sm.synthesis.governing == "fixed"
    assert sm.profile(np.linspace(0, 2 * math.pi, 7201))["rho"].min() < case_cam.rho_min - 1e-4
    same = _smaller(tmp_path, case_cam, 1.0)
    assert same.scalars["cam_rho_min"] == pytest.approx(case_cam.rho_min, abs=1e-12)


def test_least_r0_by_brute_force_over_psi0(case_cam):
    """Independent scan: at each ψ₀ the least a_w from the sampled conditions (dense φ grid, no root
    finding); the smallest r₀ over all ψ₀ is not below the synthesised one, and close to it."""
    c = case_cam
    d, g = c.face_offset, np.linspace(0, 2 * math.pi, 20001)
    s, s1, s2, _ = c.law(g)
    q = 1 - c.k * s1
    rise = g <= c.rise.length
    ret = (g >= c.ret.start) & (g <= c.ret.start + c.ret.length)
    best = math.inf
    for psi0 in np.linspace(0.3, math.pi / 2 - c.h - 1e-3, 2000):
        G = np.sin(psi0 + s) * (1 - s1 ** 2 / q ** 2) + np.cos(psi0 + s) * s2 / q ** 3
        m = np.cos(psi0 + s) / q
        if G.min() <= 0:
            continue
        a = max((c.rho_min + d) / G.min(), d / (math.tan(c.rise.allowed) * m[rise].min()),
                d / (math.tan(c.ret.allowed) * m[ret].min()))
        best = min(best, a * math.sin(psi0) - d)
    assert best >= c.synthesis.r0 * (1 - 1e-9)
    assert best <= c.synthesis.r0 * (1 + 2e-3)
    assert 0.99 * c.synthesis.r0 < best


def test_psi0_given_and_a_w_given(tmp_path):
    """ψ₀ given → a_w = (ρ_min + d)/G_min (convexity); a_w given → ψ₀ the least root of
    a_w G_min(ψ₀) − d = ρ_min; each a 1 % smaller r₀ loses convexity."""
    c = make(tmp_path, flat('face_offset = "5 mm"\npsi0 = "55 deg"', allowed=("", ""))).cam
    syn = c.synthesis
    assert syn.governing == "convexity"
    assert syn.a_w == pytest.approx((c.rho_min + 0.005) / c.fr["G"], rel=1e-14)
    assert c.scalars["cam_rho_min"] == pytest.approx(c.rho_min, abs=1e-13)
    assert _smaller(tmp_path, c).scalars["cam_rho_min"] < c.rho_min
    c2 = make(tmp_path, flat(f'face_offset = "5 mm"\na_w = "{syn.a_w!r} m"', allowed=("", "")), "a.toml").cam
    assert c2.synthesis.psi0 == pytest.approx(math.radians(55), abs=1e-12)
    # a smaller r₀ at this a_w means a smaller ψ₀: not convex
    psi = math.asin((0.99 * c2.synthesis.r0 + 0.005) / c2.synthesis.a_w)
    assert c2.synthesis.a_w * c2._fr_ext(c2.fr_G, psi)[0] - 0.005 < c2.rho_min


def test_dG_and_dmu_are_exact(case_cam):
    c = case_cam
    phi = np.linspace(0.02, 2 * math.pi - 0.02, 301)
    h = 1e-6
    for fn in (c.fr_G, c.fr_m):
        v, dv = fn(phi, 1, 0.9)
        fd = (fn(phi + h, 1, 0.9)[0] - fn(phi - h, 1, 0.9)[0]) / (2 * h)
        assert np.allclose(dv, fd, atol=1e-8)


@pytest.mark.parametrize("head,key", [
    ('face_offset = "10 mm"\narm = "100 mm"', "arm"),
    ('', "psi0"),                                     # d = 0 and nothing given: not determined
    ('face_offset = "10 mm"\npsi0 = "80 deg"', "psi0"),
    ('face_offset = "-1 mm"', "face_offset"),
])
def test_case_errors(tmp_path, head, key):
    with pytest.raises(CaseError) as e:
        make(tmp_path, flat(head)).cam.synthesis
    assert key in str(e.value)


def test_fast_rocker_is_case_error(tmp_path):
    body = flat('face_offset = "10 mm"').replace('swing = "20 deg"', 'swing = "60 deg"').replace(
        'angle = "100 deg"', 'angle = "30 deg"', 1)
    with pytest.raises(CaseError) as e:
        make(tmp_path, body).cam.synthesis
    assert "swing" in str(e.value)


def test_face_offset_only_for_flat_rocker(tmp_path):
    body = flat('face_offset = "10 mm"').replace('contact = "flat"', 'contact = "roller"\narm = "100 mm"')
    with pytest.raises(CaseError) as e:
        make(tmp_path, body).cam
    assert "face_offset" in str(e.value)


# ---------------------------------------------------------------- note and export
def test_note_section_and_export(tmp_path, case_cam):
    from reportgen.report.sections import cam as S
    from test_cam import _texts
    st = Study(CASE)
    sec = S.build(st)
    text = "\n".join(_texts(sec))
    for bad in ("nan", "None", "inf", "cam_", "synthesis", "rho_c", "phi_deg", "face_offset", "ролик",
                "фазов", "эксцентриситет"):
        assert bad not in text, bad
    assert "arctg(d/μ)" in text and "тарел" in text
    ids = [c.id for c in sec.children]
    assert ids == ["sec-cam-data", "sec-cam-laws", "sec-cam-size", "sec-cam-theta", "sec-cam-profile"]
    lines = " ".join(S.conclusion_lines(st))
    assert "71&nbsp;мм (наименьший 70,10" in lines and "94,71" in lines     # r₀ taken up to a whole mm
    tabs = case_cam.tables()
    for df in tabs.values():
        assert np.isfinite(df.to_numpy(dtype=float)).all()
    assert {"x", "y", "r", "rho", "theta"} <= set(tabs["cam_profile"].columns)
    assert all(math.isfinite(v) for v in case_cam.scalars.values())


def test_large_centre_distance_tends_to_the_translating_flat_follower(tmp_path):
    """A rocker with a far pivot (a_w → ∞, ψ = s/a_w, ψ₀ → 0) is a translating flat follower: the
    textbook ρ = r₀ + s + s″ (Артоболевский, гл. 24) and the contact offset s′ along the face are
    approached with an error falling as 1/a_w."""
    h, r0 = 0.04, 0.04
    errs = []
    for a in (100.0, 1000.0):
        psi0 = math.asin(r0 / a)
        head = f'a_w = "{a!r} m"\npsi0 = "{psi0!r} rad"'
        body = flat(head, allowed=("", "")).replace('swing = "20 deg"', f'swing = "{h / a!r} rad"')
        c = make(tmp_path, body, f"a{int(a)}.toml").cam
        g = np.linspace(0, 2 * math.pi, 721)
        s, s1, s2, _ = c.law(g)
        rho = c.profile(g)["rho"]
        off = c.frames(g)["mu"] - a * np.cos(psi0 + s)        # from the foot of the perpendicular from O
        errs.append((np.abs(rho - (r0 + a * s + a * s2)).max(), np.abs(off - c.k * a * s1).max()))
    assert errs[1][0] < 1e-5 and errs[1][1] < 1e-5
    assert 7 < errs[0][0] / errs[1][0] < 13 and 7 < errs[0][1] / errs[1][1] < 13


def test_no_convex_profile_at_any_psi0_is_case_error(tmp_path):
    """A short rise turning the rocker with the cam (q = 1 − ψ′ small) admits no convex profile at
    any ψ₀: a clear error, never an infinite a_w; the other sense of rotation works."""
    body = flat('face_offset = "10 mm"').replace('angle = "100 deg"', 'angle = "60 deg"', 1)
    with pytest.raises(CaseError) as e:
        make(tmp_path, body).cam.synthesis
    assert "swing" in str(e.value)
    c = make(tmp_path, body.replace('rotation = "ccw"', 'rotation = "cw"'), "cw.toml").cam
    assert math.isfinite(c.synthesis.a_w) and c.scalars["cam_rho_min"] == pytest.approx(c.rho_min, abs=1e-12)
