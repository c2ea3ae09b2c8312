"""Planetary trains: Willis equations against the direct velocity analysis (pitch-point
velocities), worksheet 001 problem 2013-5, and the tooth-number selection with all conditions."""
from __future__ import annotations

from fractions import Fraction

import pytest

from reportgen.analysis.train import TrainModel, Wheel, check_2kh, direct, place_axes, select_2kh, willis


def model(wheels, meshes, members, axes, fixed, inp, out, m=1.0):
    ws = {}
    for name, z, member, internal, *centre in wheels:
        ws[name] = Wheel(name, z, member, centre[0] if centre else members[member], internal, m)
    ax = dict(axes)
    for w in ws.values():
        ax.setdefault(w.centre, "0")
    for a in members.values():
        ax.setdefault(a, "0")
    return TrainModel(members, ax, ws, meshes, tuple(fixed), inp, out)


def two_kh(z1, z2, z3):
    return model([("1", z1, "1", False), ("2", z2, "2", False), ("3", z3, "3", True)],
                 [("1", "2"), ("2", "3")], {"1": "O", "2": "A", "3": "O", "H": "O"}, {"A": "H"},
                 ["3"], "1", "H")


def double_planet(z1, z2, z2b, z3, ring_internal=True):
    return model([("1", z1, "1", False), ("2", z2, "2", False), ("2'", z2b, "2", False),
                  ("3", z3, "3", ring_internal)],
                 [("1", "2"), ("2'", "3")], {"1": "O", "2": "A", "3": "O", "H": "O"}, {"A": "H"},
                 ["3"], "1", "H")


def ws001_2013_5():
    """Worksheet 001, 2013-5: 1 (z=20) drives ring 2 (z=100) on carrier H2; 2 and sun 5 (22) are
    one block; planets 6 (26) on carrier H1 roll in ring 7 (74), fixed to H2; H1 carries 4 (20),
    meshing the fixed central wheel 3 (60).  z4, z7 from coaxiality."""
    return model([("1", 20, "1", False), ("2", 100, "25", True), ("5", 22, "25", False),
                  ("6", 26, "6", False), ("7", 74, "H2", True, "B"), ("4", 20, "H1", False),
                  ("3", 60, "3", False)],
                 [("1", "2"), ("5", "6"), ("6", "7"), ("4", "3")],
                 {"1": "O", "3": "O", "H2": "O", "25": "B", "H1": "B", "6": "C"},
                 {"B": "H2", "C": "H1"}, ["3"], "1", "H2")


@pytest.mark.parametrize("build", [
    lambda: two_kh(17, 34, 85), lambda: two_kh(20, 25, 70), lambda: double_planet(20, 40, 20, 80),
    lambda: double_planet(18, 30, 24, 72), ws001_2013_5,
    # 2K-H with two external meshes (David–Brown type): ring replaced by an external wheel
    lambda: double_planet(40, 20, 21, 39, ring_internal=False),
])
def test_willis_equals_direct_velocity_analysis(build):
    m = build()
    for fixed, inp in ((m.fixed, m.inp), ((m.inp,), m.out)):
        wa, wd = willis(m, fixed, inp), direct(m, fixed, inp)
        for k in wa:
            assert wa[k] == pytest.approx(wd[k], rel=1e-12, abs=1e-12)


def test_textbook_2kh_ratio():
    m = two_kh(17, 34, 85)
    assert 1 / willis(m)["H"] == pytest.approx(1 + 85 / 17, rel=1e-14)
    # any member held: the ring driving the carrier with the sun held, u_3H = 1 + z1/z3
    w = willis(m, fixed=("1",), inp="3")
    assert 1 / w["H"] == pytest.approx(1 + 17 / 85, rel=1e-14)
    # carrier held: u_13 = −z3/z1
    w = willis(m, fixed=("H",), inp="1")
    assert 1 / w["3"] == pytest.approx(-85 / 17, rel=1e-14)


def test_worksheet_001_2013_5():
    m = ws001_2013_5()
    u = 1 / willis(m)["H2"]
    assert Fraction(u).limit_denominator(1000) == Fraction(731, 11)
    assert u == pytest.approx(66.4545454545, abs=1e-9)
    # the worksheet multiplies the rounded 4,364 and prints 66,46
    assert round(1 - 5 * 4.364 * (-3), 2) == 66.46
    assert 1 / direct(m)["H2"] == pytest.approx(u, rel=1e-12)
    _, resid = place_axes(m)
    assert resid and all(abs(r) < 1e-12 for _, r in resid)      # z4 = 20, z7 = 74 are coaxial


def test_selection_conditions_and_textbook_set():
    ok, bad = select_2kh(6.0, 3, tol=0.0)
    assert ok[0].z == {"1": 17, "2": 34, "3": 85}
    assert any(c.z == {"1": 18, "2": 36, "3": 90} for c in ok)
    for c in ok:
        z1, z2, z3 = c.z["1"], c.z["2"], c.z["3"]
        assert z3 == z1 + 2 * z2 and (z1 + z3) % 3 == 0 and c.u == 1 + z3 / z1
        import math
        assert math.sin(math.pi / 3) > (z2 + 2) / (z1 + z2) and min(z1, z2) >= 17
    assert all(c.fails for c in bad)


def test_selection_rejects_khurmi_assembly():
    # Khurmi Ex. 13.9: 14/21/56 with 3 planets violates assembly (and undercut of z = 14)
    c = check_2kh(14, 21, 56, 3, None, 0.03)
    assert any("сборки" in f for f in c.fails) and any("подрезание" in f for f in c.fails)
    c = check_2kh(16, 24, 64, 3, None, 0.03)
    assert any("сборки" in f for f in c.fails)


def test_double_planet_selection_all_conditions():
    ok, _ = select_2kh(12.0, 3, tol=0.02, double=True, z_max=110, limit=5)
    assert ok
    for c in ok:
        z1, z2, z2b, z3 = c.z["1"], c.z["2"], c.z["2'"], c.z["3"]
        assert z1 + z2 == z3 - z2b
        m = double_planet(z1, z2, z2b, z3)
        assert 1 / willis(m)["H"] == pytest.approx(c.u, rel=1e-12)
        assert abs(c.u - 12) <= 0.02 * 12


def test_tooth_numbers_from_coaxiality():
    from reportgen.analysis.train import solve_coaxial
    m = ws001_2013_5()
    for w in ("4", "7"):
        old = m.wheels[w]
        m.wheels[w] = Wheel(w, 0, old.member, old.centre, old.internal, old.m)
    got = {w: z for w, _, _, z in solve_coaxial(m)}
    assert got == {"4": 20, "7": 74}
    assert Fraction(1 / willis(m)["H2"]).limit_denominator(1000) == Fraction(731, 11)


TRAIN_CASES = sorted(p.stem for p in __import__("pathlib").Path(__file__).resolve().parents[1].glob("cases/*.toml")
                     if "[train]" in p.read_text(encoding="utf-8"))


def test_ratio_chain_telescopes():
    from reportgen.analysis.train import ratio_chain
    m = ws001_2013_5()
    w = willis(m)
    chain = ratio_chain(w, "1", "H2")
    assert chain[0] == "1" and chain[-1] == "H2" and "3" not in chain
    mags = [abs(w[n]) for n in chain]
    assert mags == sorted(mags, reverse=True)
    prod = 1.0
    for a, b in zip(chain, chain[1:]):
        prod *= w[a] / w[b]
    assert prod == pytest.approx(1 / w["H2"], rel=1e-12)


@pytest.mark.parametrize("case", TRAIN_CASES)
def test_graphical_ratio_by_stages_and_labels(case):
    """Stage-by-stage plans read to 0,5 mm give the ratio within 2 %; no two labels (nor a label
    and a title) overlap in the scheme, the velocity picture, the plans."""
    from pathlib import Path

    from reportgen import load_case
    from reportgen.scenes.train import READ_MM, stage_plans, text_overlaps, train_picture
    tr = load_case(Path(__file__).resolve().parents[1] / "cases" / f"{case}.toml").train
    st = stage_plans(tr)
    assert abs(st.u_graph - tr.ratio) / abs(tr.ratio) < 0.02
    for (a, b, sa, sb), (fa, fb) in zip(st.stages, st.depths):
        # a short segment is read f polar distances from the pole (session 11): (0a)/f_a : (0b)/f_b
        assert sa % READ_MM == 0 and sb % READ_MM == 0 and max(abs(sa), abs(sb)) >= 50
        assert (sa / fa) / (sb / fb) == pytest.approx(tr.w_willis[a] / tr.w_willis[b], rel=0.02)
    pic = train_picture(tr)
    for fig in (pic.fig, st.fig):
        titles = [a.title for a in fig.axes if a.title.get_text()]
        for ax in fig.axes:
            assert ax.texts
            assert text_overlaps(fig, ax.texts + titles) == []


@pytest.mark.parametrize("case", TRAIN_CASES)
def test_scheme_symmetric_about_central_axis(case):
    """Every line of the scheme has its mirror image about the central axis (planets on both
    sides, as in the textbook schemes), except the lines of a parallel frame shaft off the central
    axis (a simple stage's pinion: one shaft, drawn once)."""
    from pathlib import Path

    import numpy as np

    from reportgen import load_case
    from reportgen.scenes.train import train_picture
    tr = load_case(Path(__file__).resolve().parents[1] / "cases" / f"{case}.toml").train
    ax = train_picture(tr).fig.axes[0]
    leaders = {id(t.leader) for t in ax.texts if getattr(t, "leader", None) is not None}   # a label's, not the scheme's
    lines = [np.round(np.c_[ln.get_xdata(), ln.get_ydata()].astype(float), 6) for ln in ax.lines
             if len(ln.get_xdata()) == 2 and ln.get_linestyle() == "-" and id(ln) not in leaders]
    keys = {tuple(map(tuple, ln)) for ln in lines} | {tuple(map(tuple, ln[::-1])) for ln in lines}
    m, y = tr.model, tr.positions
    single = [(y[a], max(w.m * w.z / 2 for w in m.wheels.values() if w.centre == a) + 1e-6)
              for a, h in m.axes.items() if h == "0" and abs(y[a]) > 1e-9
              and any(w.centre == a for w in m.wheels.values())]
    for ln in lines:
        mir = ln * np.array([1.0, -1.0]) + 0.0
        if any(np.all(np.abs(ln[:, 1] - ya) <= r) for ya, r in single):
            continue
        assert tuple(map(tuple, mir)) in keys
    off = [w for w in tr.model.wheels.values() if abs(tr.positions[w.centre]) > 1e-9]
    assert off            # both cases have wheels off the axis, drawn twice


def test_printed_coaxiality_judged():
    """Worksheet 2013-5 writes z1 − z2 = z4 + z3 (a difference the wrong way round: −80 = 80);
    the train's own condition is z2 − z1 = z4 + z3; z7 − z6 = z5 + z6 is right."""
    from reportgen.analysis.train import coaxiality_equations, judge_printed_coaxiality, parse_linear
    m = ws001_2013_5()
    eqs = {mesh: (p, c) for mesh, p, c in coaxiality_equations(m)}
    assert eqs[("4", "3")] == ({"2": 1, "1": -1}, {"4": 1, "3": 1})
    assert eqs[("6", "7")] == ({"5": 1, "6": 1}, {"7": 1, "6": -1})
    j = judge_printed_coaxiality(m, "z1 - z2 = z4 + z3")
    assert not j["ok"] and j["flipped"] and (j["lhs"], j["rhs"]) == (-80, 80)
    assert judge_printed_coaxiality(m, "z7 − z6 = z5 + z6")["ok"]
    assert judge_printed_coaxiality(m, "z_{4} + z_3 = z2 - z1")["ok"]
    assert judge_printed_coaxiality(m, "2z7 - 2z6 = 2z5 + 2z6")["ok"]
    # 2K-H: z3 − z2 = z1 + z2 (i.e. z3 = z1 + 2z2)
    (mesh, p, c), = coaxiality_equations(two_kh(17, 34, 85))
    assert p == {"1": 1, "2": 1} and c == {"3": 1, "2": -1}
    for bad in ("z1 - z9 = z4", "z1 z2 = z3", "z1 = z2 = z3"):
        with pytest.raises(ValueError):
            parse_linear(bad, m.wheels)


def test_note_says_where_the_worksheet_coaxiality_is_wrong():
    from pathlib import Path

    from reportgen import load_case
    from reportgen.report.sections import train as sec
    st = load_case(Path(__file__).resolve().parents[1] / "cases" / "ws001_train_2013_5.toml")
    html = repr(sec.build(st))
    assert "«z1 - z2 = z4 + z3»" in html and "−80" in html and "обратном порядке" in html
    assert "z_{2} - z_{1} = z_{4} + z_{3}" in html and "«z7 - z6 = z5 + z6» верно" in html
