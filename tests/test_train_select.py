"""Tooth-number selection for any planetary train (analysis/train_select.py), checked by
independent formulations:

* the ratio polynomials against the numeric Willis system and the direct velocity analysis;
* coaxiality by the centre distances written out for each scheme;
* assembly by placing the teeth: at every satellite position the tooth centres of the central
  wheels and of the satellite's wheels are laid out along the common tangents in millimetres, and a
  rotation of the satellite block that puts its teeth into the spaces of every central wheel is
  searched among the block's tooth positions (no congruences);
* neighbourhood by placing the k tip circles of the largest satellite wheel and measuring the
  distances between them;
* undercut and internal meshes by the gear geometry of core/gears.py.
"""
from __future__ import annotations

import itertools
import math
from fractions import Fraction
from pathlib import Path

import pytest

from reportgen.analysis.train import FRAME, TrainModel, Wheel, direct, two_kh_model, willis
from reportgen.analysis.train_select import Selector, assembly, planets_of, select
from reportgen.core.gears import internal_checks, pair_geometry

CASES = Path(__file__).resolve().parents[1] / "cases"


def mk(wheels, meshes, members, axes, fixed, inp, out, z=None):
    z = z or {}
    ws = {n: Wheel(n, z.get(n, 0), mem, c, internal, 1.0) for n, mem, c, internal in wheels}
    ax = {a: FRAME for a in set(members.values())} | axes
    return TrainModel(members, ax, ws, meshes, tuple(fixed), inp, out)


def k3(z=None):
    """3K: sun 1, block 2–2′ on a free carrier H, fixed ring 3, output ring 4."""
    return mk([("1", "1", "O", False), ("2", "2", "A", False), ("3", "3", "O", True), ("2'", "2", "A", False),
               ("4", "4", "O", True)], [("1", "2"), ("2", "3"), ("2'", "4")],
              {"1": "O", "2": "A", "3": "O", "4": "O", "H": "O"}, {"A": "H"}, ["3"], "1", "4", z)


def two_external(z=None):
    """2K-H with a double satellite and two external meshes (Давид): input H, output 1, 3 fixed."""
    return mk([("1", "1", "O", False), ("2", "2", "A", False), ("2'", "2", "A", False), ("3", "3", "O", False)],
              [("1", "2"), ("2'", "3")], {"1": "O", "2": "A", "3": "O", "H": "O"}, {"A": "H"}, ["3"], "H", "1", z)


def two_internal(z=None):
    """2K-H with a double satellite and two internal meshes: rings 1 and 3, input H, output 1."""
    return mk([("1", "1", "O", True), ("2", "2", "A", False), ("2'", "2", "A", False), ("3", "3", "O", True)],
              [("1", "2"), ("2'", "3")], {"1": "O", "2": "A", "3": "O", "H": "O"}, {"A": "H"}, ["3"], "H", "1", z)


def compound(z=None):
    """Two 2K-H stages in series (two carriers): H1 carries the second stage's sun 4."""
    return mk([("1", "1", "O", False), ("2", "2", "A", False), ("3", "3", "O", True), ("4", "H1", "O", False),
               ("5", "5", "B", False), ("6", "3", "O", True)], [("1", "2"), ("2", "3"), ("4", "5"), ("5", "6")],
              {"1": "O", "2": "A", "3": "O", "H1": "O", "5": "B", "H2": "O"}, {"A": "H1", "B": "H2"},
              ["3"], "1", "H2", z)


def james(double, z=None):
    return two_kh_model(double, z)


# scheme → (model builder, centre distances of each loop (in modules·2), satellite spec, size,
#            target, k, options); satellite spec per carrier: (radius·2 in modules, [(central z,
#            satellite wheel, internal)], satellite wheels)
SCHEMES = {
    "2K-H": (lambda z=None: james(False, z), lambda z: [(z["1"] + z["2"], z["3"] - z["2"])],
             lambda z: [(z["1"] + z["2"], [(z["1"], "2", False), (z["3"], "2", True)], ["2"])], 6.0, 3, {}),
    "2K-H double": (lambda z=None: james(True, z), lambda z: [(z["1"] + z["2"], z["3"] - z["2'"])],
                    lambda z: [(z["1"] + z["2"], [(z["1"], "2", False), (z["3"], "2'", True)], ["2", "2'"])],
                    15.0, 3, {"tol": 0.02}),
    "two external": (two_external, lambda z: [(z["1"] + z["2"], z["2'"] + z["3"])],
                     lambda z: [(z["1"] + z["2"], [(z["1"], "2", False), (z["3"], "2'", False)], ["2", "2'"])],
                     -40.0, 2, {"tol": 0.05}),
    "two internal": (two_internal, lambda z: [(z["1"] - z["2"], z["3"] - z["2'"])],
                     lambda z: [(z["1"] - z["2"], [(z["1"], "2", True), (z["3"], "2'", True)], ["2", "2'"])],
                     60.0, 3, {}),
    "3K": (k3, lambda z: [(z["1"] + z["2"], z["3"] - z["2"]), (z["1"] + z["2"], z["4"] - z["2'"])],
           lambda z: [(z["1"] + z["2"], [(z["1"], "2", False), (z["3"], "2", True), (z["4"], "2'", True)],
                       ["2", "2'"])], 50.0, 3, {}),
    "compound": (lambda z=None: compound({"4": 20, "5": 25, "6": 70} | (z or {})),
                 lambda z: [(z["1"] + z["2"], z["3"] - z["2"]), (20 + 25, 70 - 25)],
                 lambda z: [(z["1"] + z["2"], [(z["1"], "2", False), (z["3"], "2", True)], ["2"]),
                            (45, [(20, "5", False), (70, "5", True)], ["5"])], 24.0, 3, {"tol": 0.0}),
    "two carriers": (compound, lambda z: [(z["1"] + z["2"], z["3"] - z["2"]), (z["4"] + z["5"], z["6"] - z["5"])],
                     lambda z: [(z["1"] + z["2"], [(z["1"], "2", False), (z["3"], "2", True)], ["2"]),
                                (z["4"] + z["5"], [(z["4"], "5", False), (z["6"], "5", True)], ["5"])],
                     24.0, 3, {"tol": 0.0}),
}


def placed_teeth_assemble(spec, z, k) -> bool:
    """Tooth centres along the common tangent of every mesh, mm (m = 1, pitch p = π): a central
    wheel's teeth at r_c(φ_c − Θ) + jp, an external satellite wheel's (contact towards the
    centre, its tangent reversed) at −r(ψ − Θ − π) − jp, an internal mesh's satellite wheel at
    r(ψ − Θ) + jp; the satellite's teeth must sit in the central wheel's spaces (offset p/2).
    Satellite 0 fixes the central wheels' phases; every other position must take the identical
    block at one of its tooth positions."""
    a2, meshes, _ = spec
    p = math.pi

    def offsets(psi, theta, phases):
        out = []
        for (zc, w, internal), phi in zip(meshes, phases):
            rc, r = zc / 2, z[w] / 2
            sat = r * (psi - theta) if internal else -r * (psi - theta - math.pi)
            out.append((sat - rc * (phi - theta) - p / 2) % p)
        return out

    # satellite 0 at Θ = 0, ψ = 0: choose every central wheel's phase so that its mesh fits
    phases = []
    for zc, w, internal in meshes:
        r = z[w] / 2
        sat = 0.0 if internal else -r * (-math.pi)
        phases.append(-(sat - p / 2) / (zc / 2))
    assert all(min(o, p - o) < 1e-9 for o in offsets(0.0, 0.0, phases))
    for i in range(1, k):
        theta = 2 * math.pi * i / k
        w0 = meshes[0][1]
        # block rotations that fit the first mesh: solve for ψ then step by the tooth of wheel w0
        internal0 = meshes[0][2]
        r0 = z[w0] / 2
        base = offsets(0.0, theta, phases)[0]
        step = 2 * math.pi / z[w0]
        psi0 = (base / r0) if not internal0 else (-base / r0)
        found = False
        for n in range(z[w0]):
            o = offsets(psi0 + n * step, theta, phases)
            if all(min(x, p - x) < 1e-7 for x in o):
                found = True
                break
        if not found:
            return False
    return True


def tip_circles_clear(spec, z, k) -> bool:
    """k tip circles of the largest satellite wheel on radius a_w: every two apart."""
    a2, _, wheels = spec
    a = abs(a2) / 2
    ra = max(z[w] / 2 + 1.0 for w in wheels)
    pts = [(a * math.cos(2 * math.pi * i / k), a * math.sin(2 * math.pi * i / k)) for i in range(k)]
    return all(math.dist(p, q) > 2 * ra for p, q in itertools.combinations(pts, 2))


def test_ratio_polynomials_equal_willis_and_direct_velocity_analysis():
    """u(z) from the Cramer polynomials equals the numeric Willis system and the velocity
    picture, for every scheme and tooth sets that close the loops."""
    sets = {"2K-H": [{"1": 17, "2": 34, "3": 85}, {"1": 20, "2": 25, "3": 70}],
            "2K-H double": [{"1": 20, "2": 40, "2'": 20, "3": 80}, {"1": 18, "2": 30, "2'": 24, "3": 72}],
            "two external": [{"1": 40, "2": 20, "2'": 21, "3": 39}],
            "two internal": [{"1": 75, "2": 33, "2'": 34, "3": 76}],
            "3K": [{"1": 17, "2": 22, "3": 61, "2'": 19, "4": 58}, {"1": 20, "2": 25, "3": 70, "2'": 22, "4": 67}],
            "compound": [{"1": 18, "2": 30, "3": 78}]}
    for name, zsets in sets.items():
        build = SCHEMES[name][0]
        sel = Selector(build())
        for zs in zsets:
            m = sel.model_with(zs)
            z = {w.name: w.z for w in m.wheels.values()}
            from reportgen.analysis.train_select import poly_eval
            u = Fraction(poly_eval(sel.num, z), poly_eval(sel.den, z))
            assert float(u) == pytest.approx(1 / willis(m)[m.out], rel=1e-12), name
            assert float(u) == pytest.approx(1 / direct(m)[m.out], rel=1e-10), name


def test_textbook_closed_forms():
    """The polynomials reduce to the textbook formulas (Попов–Тимофеев, Артоболевский):
    2K-H u_1H = 1 + z3/z1; double satellite 1 + z2z3/(z1z2′); 3K
    u_14 = (1 + z3/z1)/(1 − z3z2′/(z2z4))."""
    z = {"1": 19, "2": 23, "2'": 20, "3": 65, "4": 62}
    from reportgen.analysis.train_select import poly_eval
    s = Selector(james(False))
    assert Fraction(poly_eval(s.num, z), poly_eval(s.den, z)) == 1 + Fraction(z["3"], z["1"])
    s = Selector(james(True))
    assert Fraction(poly_eval(s.num, z), poly_eval(s.den, z)) == 1 + Fraction(z["2"] * z["3"], z["1"] * z["2'"])
    s = Selector(k3())
    assert Fraction(poly_eval(s.num, z), poly_eval(s.den, z)) == \
        (1 + Fraction(z["3"], z["1"])) / (1 - Fraction(z["3"] * z["2'"], z["2"] * z["4"]))


@pytest.mark.parametrize("name", list(SCHEMES))
def test_every_selected_set_satisfies_every_condition_by_geometry(name):
    build, loops, sats, target, k, kw = SCHEMES[name]
    tol = kw.get("tol", 0.03)
    ok, bad, sel = select(build(), target, k, tol=tol, limit=5)
    assert ok, name
    for c in ok:
        m = sel.model_with(c.z)
        z = {w.name: w.z for w in m.wheels.values()}
        u = 1 / willis(m)[m.out]
        assert abs(u - target) <= tol * abs(target) + 1e-12 and u == pytest.approx(1 / direct(m)[m.out], rel=1e-10)
        for a, b in loops(z):
            assert a == b, (name, c.z)                     # coaxiality (centre distances ·2/m)
        for spec in sats(z):
            assert placed_teeth_assemble(spec, z, k), (name, c.z)
            assert tip_circles_clear(spec, z, k), (name, c.z)
        for w in m.wheels.values():
            assert w.internal or w.z >= 17
        for a, b in m.meshes:
            wa, wb = m.wheels[a], m.wheels[b]
            if wa.internal or wb.internal:
                ring, small = (wa, wb) if wa.internal else (wb, wa)
                assert ring.z - small.z >= 8
                geo = pair_geometry(1.0, small.z, ring.z, 0.0, 0.0, internal=True)
                assert all(float(v) >= -1e-9 for v in internal_checks(geo).values())
        # ranked by size: the sets ranked before the accepted one all fail
    assert [c.size for c in ok] == sorted(c.size for c in ok)
    assert all(c.fails for c in bad)
    assert all(b.size <= ok[0].size for b in bad[:1]) or not bad


@pytest.mark.parametrize("name", ["2K-H", "2K-H double", "3K", "two internal", "two external"])
def test_assembly_condition_equals_placing_the_teeth(name):
    """The congruence verdict (and Кудрявцев's quantity for two meshes) against the teeth laid
    out in millimetres, over a block of tooth sets, k = 2…5; both verdicts occur."""
    build, loops, sats, *_ = SCHEMES[name]
    seen = set()
    rng = range(17, 23)
    for z1, z2, z2b in itertools.product(rng, rng, rng):
        if name == "2K-H" and z2b != z2:
            continue
        z = {"1": z1, "2": z2, "2'": z2b}
        if name == "2K-H":
            z["3"] = z1 + 2 * z2
        elif name == "2K-H double":
            z["3"] = z1 + z2 + z2b
        elif name == "two external":
            z["3"] = z1 + z2 - z2b
        elif name == "two internal":
            z["1"] = z1 + 40
            z["3"] = z["1"] - z2 + z2b
        else:
            z["3"], z["4"] = z1 + 2 * z2, z1 + z2 + z2b
        model = build({w: v for w, v in z.items() if w in build().wheels})
        pl, = planets_of(model)
        zz = {w.name: w.z for w in model.wheels.values()}
        for k in (2, 3, 4, 5):
            verdict, qs = assembly(pl, zz, k)
            geo = placed_teeth_assemble(sats(zz)[0], zz, k)
            assert verdict == geo, (name, zz, k)
            if len(pl.meshes) == 2:
                assert verdict == all(q.denominator == 1 for q in qs)
            seen.add(verdict)
    assert seen == {True, False}


def test_double_satellite_quantity_is_kudryavtsev():
    """(z1 z2′ + z2 z3)/(k·НОД(z2, z2′)) for the 2K-H with a double satellite."""
    z = {"1": 17, "2": 49, "2'": 17, "3": 83}
    pl, = planets_of(james(True, z))
    ok, (q,) = assembly(pl, z, 3)
    assert ok and q == Fraction(17 * 17 + 49 * 83, 3 * math.gcd(49, 17)) == 1452
    z = {"1": 29, "2": 50, "2'": 11, "3": 90}
    ok, (q,) = assembly(pl, z, 3)
    assert not ok and q == Fraction(29 * 11 + 50 * 90, 3)


def test_neighbourhood_verdict_equals_tip_circles():
    from reportgen.analysis.train import place_axes
    from reportgen.analysis.train_select import neighbourhood
    seen = set()
    for z1, z2, z2b, k in itertools.product((17, 20, 30), (17, 30, 45, 60), (17, 25), (3, 4, 5, 6)):
        z = {"1": z1, "2": z2, "2'": z2b, "3": z1 + z2 + z2b}
        m = james(True, z)
        y, _ = place_axes(m)
        (_, _, _, _, ok), = neighbourhood(m, y, z, k)
        spec = SCHEMES["2K-H double"][2](z)[0]
        assert ok == tip_circles_clear(spec, z, k)
        seen.add(ok)
    assert seen == {True, False}


def test_single_2kh_published_sets():
    """Попов–Тимофеев, «Курсовое проектирование по ТММ», пример синтеза 2K-H: u = 6, k = 3 →
    17/34/85.  A published course-project solution (ukrbukva.net, «Поршневой насос…», раздел
    «Синтез планетарного механизма»): u_1H = 7, k = 3 → z1 = 18, z2 = 45, z3 = 108 (z1 = 17 gives
    a non-integer z2).  Both are the smallest sets the enumeration accepts."""
    ok, _, _ = select(james(False), 6.0, 3, tol=0.0)
    assert ok[0].z == {"1": 17, "2": 34, "3": 85}
    ok, _, _ = select(james(False), 7.0, 3, tol=0.0)
    assert ok[0].z == {"1": 18, "2": 45, "3": 108}


def test_double_satellite_agrees_with_a_plain_enumeration():
    """A second, naive formulation (nested loops, textbook formulas written out) finds the same
    smallest accepted 2K-H set with a double satellite."""
    target, tol, k = 15.0, 0.02, 3
    best = None
    for z1, z2, z2b in itertools.product(range(17, 80), range(17, 100), range(17, 60)):
        z3 = z1 + z2 + z2b
        if z3 > 150:
            continue
        u = 1 + z2 * z3 / (z1 * z2b)
        if abs(u - target) > tol * target:
            continue
        if (z1 * z2b + z2 * z3) % (k * math.gcd(z2, z2b)):
            continue
        a = (z1 + z2) / 2
        if not 2 * a * math.sin(math.pi / k) > max(z2, z2b) + 2:
            continue
        if z3 - z2b < 8:
            continue
        size = max(z3, 2 * a + z2, 2 * a + z2b)
        key = (size, z1 + z2 + z2b + z3, abs(u - target))
        if best is None or key < best[0]:
            best = (key, {"1": z1, "2": z2, "2'": z2b, "3": z3})
    ok, _, _ = select(james(True), target, k, tol=tol)
    assert ok[0].z == best[1]


@pytest.mark.parametrize("case", ["train_2kh_double_select", "train_3k_select", "train_two_carrier_select"])
def test_cases_select_and_note(case):
    from reportgen import load_case
    from reportgen.report.sections import train as sec
    st = load_case(CASES / f"{case}.toml")
    tr = st.train
    assert tr.candidates and all(c.ok for c in tr.candidates) and tr.rejected
    assert abs(tr.ratio - tr.opts["target"]) <= tr.opts["tolerance"] * tr.opts["target"] + 1e-9
    assert tr.ratio == pytest.approx(tr.ratio_direct, rel=1e-10)
    html = repr(sec.build(st))
    assert "Наборы чисел зубьев и проверка условий" in html and "НОД" in html and "соседства" in html
    t = tr.tables()["train_candidates"]
    assert t["ok"].any() and (~t["ok"]).any() and t.notna().all().all()


def test_grid_too_large_is_a_case_error(tmp_path):
    from reportgen import load_case
    from reportgen.errors import CaseError
    text = (CASES / "train_two_carrier_select.toml").read_text(encoding="utf-8") + "z_max = 400\nz_from = 5\n"
    p = tmp_path / "big.toml"
    p.write_text(text, encoding="utf-8")
    with pytest.raises(CaseError) as e:
        load_case(p).train
    assert "перебор" in str(e.value)


@pytest.mark.parametrize("name", ["2K-H double", "3K", "two carriers"])
def test_solving_the_linear_wheel_from_the_target_loses_nothing(name):
    """The free wheel whose ratio is a Möbius function is taken from the roots of
    u = target(1 ± tol) instead of enumerated: the same tooth sets as the full enumeration."""
    build, _, _, target, k, kw = SCHEMES[name]
    z_max = 50 if name == "two carriers" else 90
    sel = Selector(build(), k=k, z_max=z_max)
    assert sel._linear_free() is not None
    fast = sel.survivors(target, kw.get("tol", 0.03))
    sel._linear_free = lambda: None
    slow = sel.survivors(target, kw.get("tol", 0.03))
    key = lambda zs: sorted(zs.items())  # noqa: E731
    assert fast and sorted(map(key, fast)) == sorted(map(key, slow))


def test_given_tooth_numbers_checked_with_reasons():
    """A set given whole is checked like a candidate: a non-coaxial set names the mesh and the
    gap (m = 1: z₃ one tooth too many → 0,5 mm), Khurmi's 14/21/56 (k = 3) fails assembly."""
    from reportgen.analysis.train import check_2kh
    c = check_2kh(17, 34, 86, 3, 6.0, 0.03)
    assert any("соосности" in f and "−0,5 мм" in f for f in c.fails)
    c = check_2kh(14, 21, 56, 3, None, 0.03)
    assert any("70/3 — не целое" in f for f in c.fails)


@pytest.mark.parametrize("name", ["two carriers", "two internal"])
def test_no_runtime_warnings(name):
    """Poles of the ratio and roots out of range give no floating-point warnings."""
    import warnings
    build, _, _, target, k, kw = SCHEMES[name]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert select(build(), target, k, tol=kw.get("tol", 0.03), limit=2)[0]


def test_satellites_counted_per_carrier():
    """planets = {H1 = 3, H2 = 4}: each stage's sets assemble and clear with its own k (by
    placing teeth and tip circles), and the case reads the table."""
    from reportgen import load_case
    _, loops, sats, *_ = SCHEMES["two carriers"]
    ok, _, sel = select(compound(), 24.0, {"H1": 3, "H2": 4}, tol=0.0, limit=4)
    assert ok
    for c in ok:
        z = {w.name: w.z for w in sel.model_with(c.z).wheels.values()}
        s1, s2 = sats(z)
        assert placed_teeth_assemble(s1, z, 3) and placed_teeth_assemble(s2, z, 4)
        assert tip_circles_clear(s1, z, 3) and tip_circles_clear(s2, z, 4)
        assert (z["4"] + z["6"]) % 4 == 0 and (z["1"] + z["3"]) % 3 == 0
    tr = load_case(CASES / "train_two_carrier_select.toml").train
    assert tr.opts["planets"] == {"H1": 3, "H2": 4} and tr.candidates[0].z == ok[0].z
