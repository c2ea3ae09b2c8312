"""Tests of reportgen.errors, reportgen.case.units and reportgen.case.expr."""
from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

from reportgen.errors import AssemblyError, CaseError, ReportgenError, StructureError, did_you_mean
from reportgen.case import units as U
from reportgen.case.units import (
    ACCELERATION, ANGLE, ANGULAR_ACCELERATION, ANGULAR_VELOCITY, DENSITY, DIMENSIONLESS, ENERGY,
    FORCE, FREQUENCY, INERTIA, LENGTH, MASS, MOMENT, POWER, PRESSURE, TIME, VELOCITY,
    check_dim, dim_name, example_for, parse_quantity, parse_unit,
)
from reportgen.case.expr import Q, evaluate, free_names, resolve

DEG = math.pi / 180


def close(a, b, rel=1e-12):
    return math.isclose(a, b, rel_tol=rel, abs_tol=0.0)


# =============================================================================================
# errors


class TestErrors:
    def test_hierarchy(self):
        assert issubclass(CaseError, ReportgenError)
        assert issubclass(AssemblyError, ReportgenError)
        assert issubclass(StructureError, ReportgenError)

    def test_case_error_full(self):
        e = CaseError("ожидалась масса (например, «9 kg»), получено «9 m»", file="cases/x.toml",
                      key="links[2].mass", expected="масса (например, «9 kg»)", got="9 m",
                      hint="укажите единицу массы")
        s = str(e)
        first, second = s.split("\n")
        assert first == ("cases/x.toml: ключ links[2].mass: ожидалась масса (например, «9 kg»), "
                         "получено «9 m».")
        assert second == "  Подсказка: укажите единицу массы"
        assert (e.file, e.key, e.expected, e.got, e.hint) == (
            "cases/x.toml", "links[2].mass", "масса (например, «9 kg»)", "9 m", "укажите единицу массы")

    def test_case_error_parts_appended_and_omitted(self):
        s = str(CaseError("ожидалась строка", expected="строка в кавычках", got="12"))
        assert s == "ожидалась строка; ожидается: строка в кавычках; получено: «12»."
        assert str(CaseError("плохо")) == "плохо."
        assert str(CaseError("плохо", key="a")) == "ключ a: плохо."
        assert "\n" not in str(CaseError("плохо", file="f.toml"))
        # already quoted values are not quoted twice
        assert "получено: \"x\"" in str(CaseError("m", got="\"x\""))
        # question mark ends a sentence
        assert str(CaseError("возможно, «a»?")).endswith("?")

    def test_with_context(self):
        e = CaseError("неверно", key="mass", got="9 m")
        e2 = e.with_context(file="c.toml", key_prefix="links[2]")
        assert e2 is not e and isinstance(e2, CaseError)
        assert e2.key == "links[2].mass" and e2.file == "c.toml" and e2.got == "9 m"
        assert e.key == "mass" and e.file is None  # the original is untouched
        assert CaseError("x").with_context(key_prefix="a.b").key == "a.b"
        assert CaseError("x", key="[0]").with_context(key_prefix="pos").key == "pos[0]"
        assert CaseError("x", file="a.toml").with_context(key_prefix="k").file == "a.toml"
        assert str(e2).startswith("c.toml: ключ links[2].mass: неверно")

    def test_pickle(self):
        e = CaseError("m", file="f", key="k", expected="e", got="g", hint="h")
        e2 = pickle.loads(pickle.dumps(e))
        assert str(e2) == str(e)
        a = AssemblyError("(2,3) ВВВ", "q = 99,1° (№ 4)", 0.0123)
        assert str(pickle.loads(pickle.dumps(a))) == str(a)

    def test_assembly_error(self):
        e = AssemblyError("(2,3) ВВВ", "q = 99,1° (№ 4)", 0.0123, "звенья 2 и 3 слишком коротки")
        assert str(e) == ("Механизм не собирается: группа Ассура (2,3) ВВВ в положении q = 99,1° (№ 4): "
                          "не хватает 0,0123 м (звенья 2 и 3 слишком коротки)")
        e = AssemblyError("группа Ассура (4,5) ВВП", "q = 10° (№ 1)", 1.2345e-5)
        assert str(e).startswith("Механизм не собирается: группа Ассура (4,5) ВВП в положении")
        assert "1,234·10⁻⁵ м" in str(e) or "1,235·10⁻⁵ м" in str(e)
        assert not str(e).endswith(")")  # no empty detail

    def test_did_you_mean(self):
        assert did_you_mean("mas", ["mass", "length"]) == "возможно, имелось в виду «mass»?"
        assert did_you_mean("zzz", ["mass", "length"]) is None
        assert did_you_mean("Mass", ["mass"]) == "возможно, имелось в виду «mass»?"
        assert did_you_mean("l_0A", ["l_0", "l_OA", "l_AB"]) == "возможно, имелось в виду «l_OA»?"
        assert did_you_mean("x", []) is None
        assert did_you_mean("mass", ["mass"]) is None


# =============================================================================================
# units


SIMPLE_UNITS = [
    # text, factor, dim
    ("m", 1.0, LENGTH), ("mm", 1e-3, LENGTH), ("cm", 1e-2, LENGTH), ("dm", 0.1, LENGTH),
    ("km", 1e3, LENGTH), ("µm", 1e-6, LENGTH), ("μm", 1e-6, LENGTH), ("um", 1e-6, LENGTH),
    ("kg", 1.0, MASS), ("g", 1e-3, MASS), ("t", 1e3, MASS),
    ("s", 1.0, TIME), ("ms", 1e-3, TIME), ("min", 60.0, TIME), ("h", 3600.0, TIME),
    ("rad", 1.0, ANGLE), ("deg", DEG, ANGLE), ("°", DEG, ANGLE), ("град", DEG, ANGLE),
    ("rev", 2 * math.pi, ANGLE), ("об", 2 * math.pi, ANGLE),
    ("rpm", 2 * math.pi / 60, ANGULAR_VELOCITY), ("об/мин", 2 * math.pi / 60, ANGULAR_VELOCITY),
    ("Hz", 1.0, FREQUENCY),
    ("N", 1.0, FORCE), ("kN", 1e3, FORCE), ("MN", 1e6, FORCE),
    ("Pa", 1.0, PRESSURE), ("kPa", 1e3, PRESSURE), ("MPa", 1e6, PRESSURE), ("GPa", 1e9, PRESSURE),
    ("bar", 1e5, PRESSURE),
    ("J", 1.0, ENERGY), ("kJ", 1e3, ENERGY), ("W", 1.0, POWER), ("kW", 1e3, POWER),
    ("м", 1.0, LENGTH), ("мм", 1e-3, LENGTH), ("см", 1e-2, LENGTH), ("кг", 1.0, MASS),
    ("г", 1e-3, MASS), ("т", 1e3, MASS), ("с", 1.0, TIME), ("мин", 60.0, TIME),
    ("Н", 1.0, FORCE), ("кН", 1e3, FORCE), ("Па", 1.0, PRESSURE), ("кПа", 1e3, PRESSURE),
    ("МПа", 1e6, PRESSURE), ("Дж", 1.0, ENERGY), ("Вт", 1.0, POWER), ("рад", 1.0, ANGLE),
]


@pytest.mark.parametrize("text,factor,dim", SIMPLE_UNITS)
def test_simple_units(text, factor, dim):
    f, d = parse_unit(text)
    assert d == dim
    assert close(f, factor, 1e-15)


COMPOUND_UNITS = [
    ("kg*m^2", 1.0, INERTIA), ("kg·m²", 1.0, INERTIA), ("kg*m**2", 1.0, INERTIA),
    ("kg m^2", 1.0, INERTIA), ("кг·м²", 1.0, INERTIA), ("N*m", 1.0, MOMENT), ("Н·м", 1.0, MOMENT),
    ("N m", 1.0, MOMENT), ("kN*m", 1e3, MOMENT), ("m/s", 1.0, VELOCITY), ("м/с", 1.0, VELOCITY),
    ("m/s^2", 1.0, ACCELERATION), ("m/s²", 1.0, ACCELERATION), ("m*s^-2", 1.0, ACCELERATION),
    ("m·s⁻²", 1.0, ACCELERATION), ("m*s^(-2)", 1.0, ACCELERATION),
    ("rad/s", 1.0, ANGULAR_VELOCITY), ("рад/с", 1.0, ANGULAR_VELOCITY),
    ("rad/s^2", 1.0, ANGULAR_ACCELERATION), ("kg/m^3", 1.0, DENSITY), ("kg/m³", 1.0, DENSITY),
    ("g/cm^3", 1e3, DENSITY), ("mm/s", 1e-3, VELOCITY), ("1/s", 1.0, FREQUENCY),
    ("s^-1", 1.0, FREQUENCY), ("kg/(m*s^2)", 1.0, PRESSURE), ("N/mm^2", 1e6, PRESSURE),
    ("deg/s", DEG, ANGULAR_VELOCITY), ("rev/min", 2 * math.pi / 60, ANGULAR_VELOCITY),
    ("об/с", 2 * math.pi, ANGULAR_VELOCITY), ("kW*h", 3.6e6, ENERGY),
    # "per minute" of a rotation is rpm, not 1/60 s^-1 (ГОСТ: n, мин⁻¹)
    ("мин⁻¹", 2 * math.pi / 60, ANGULAR_VELOCITY), ("min^-1", 2 * math.pi / 60, ANGULAR_VELOCITY),
    ("1/min", 2 * math.pi / 60, ANGULAR_VELOCITY),
]


@pytest.mark.parametrize("text,factor,dim", COMPOUND_UNITS)
def test_compound_units(text, factor, dim):
    f, d = parse_unit(text)
    assert d == dim
    assert close(f, factor, 1e-14)


QUANTITIES = [
    ("0.347 m", 0.347, LENGTH), ("347 mm", 0.347, LENGTH), ("99.1 deg", 99.1 * DEG, ANGLE),
    ("99.1°", 99.1 * DEG, ANGLE), ("99,1°", 99.1 * DEG, ANGLE),
    ("65 rpm", 65 * 2 * math.pi / 60, ANGULAR_VELOCITY), ("17.5 MPa", 17.5e6, PRESSURE),
    ("0.45 kg*m^2", 0.45, INERTIA), ("0.45 kg·m²", 0.45, INERTIA), ("1.5e-3 m", 1.5e-3, LENGTH),
    ("-5 deg", -5 * DEG, ANGLE), ("7800 kg/m^3", 7800.0, DENSITY), ("10 m/s^2", 10.0, ACCELERATION),
    ("15 rad/s", 15.0, ANGULAR_VELOCITY), ("0,347 m", 0.347, LENGTH), ("1,5e-3 m", 1.5e-3, LENGTH),
    ("9 kg", 9.0, MASS), ("9кг", 9.0, MASS), ("3 кН", 3e3, FORCE), ("120 Н·м", 120.0, MOMENT),
    ("−2 mm", -2e-3, LENGTH), ("+2 mm", 2e-3, LENGTH), (".5 m", 0.5, LENGTH),
    ("5 µm", 5e-6, LENGTH), ("2 t", 2000.0, MASS), ("50 Hz", 50.0, FREQUENCY),
    ("1 bar", 1e5, PRESSURE), ("2 kW", 2e3, POWER), ("1 kJ", 1e3, ENERGY),
    ("42", 42.0, DIMENSIONLESS), ("0,5", 0.5, DIMENSIONLESS), ("1e3", 1e3, DIMENSIONLESS),
    ("  0.2   m  ", 0.2, LENGTH),
]


@pytest.mark.parametrize("text,value,dim", QUANTITIES)
def test_parse_quantity(text, value, dim):
    v, d = parse_quantity(text)
    assert d == dim
    assert close(v, value, 1e-14)


def test_exact_decimal_conversion():
    assert parse_quantity("347 mm")[0] == 0.347
    assert parse_quantity("5 µm")[0] == 5e-6
    assert parse_quantity("12 cm")[0] == 0.12


def test_rpm_precision():
    v, d = parse_quantity("65 rpm")
    assert d == ANGULAR_VELOCITY
    assert abs(v - 65 * 2 * math.pi / 60) <= 1e-15 * v
    v2, _ = parse_quantity("65 об/мин")
    assert abs(v2 - 65 * 2 * math.pi / 60) <= 1e-15 * v2


def test_deg_value():
    assert close(parse_quantity("99.1 deg")[0], 1.7296212887263804, 1e-15)


@pytest.mark.parametrize("text,fragment", [
    ("0.3 xyz", "«xyz»"),
    ("1 Mpa", "MPa"),        # did-you-mean
    ("1 m2", "m^2"),         # power hint
    ("1 kg*", "обрывается"),
    ("1 (m", "не закрыта скобка"),
    ("1 m)", "лишняя закрывающая скобка"),
    ("1 m^x", "показатель"),
    ("abc", "не удалось прочитать"),
    ("1 m $", "недопустимый символ"),
])
def test_unit_errors(text, fragment):
    with pytest.raises(CaseError) as ei:
        parse_quantity(text)
    assert fragment in str(ei.value)
    assert ei.value.expected  # describes the syntax


def test_unknown_unit_has_expected_and_hint():
    with pytest.raises(CaseError) as ei:
        parse_unit("kgg")
    e = ei.value
    assert "единица измерения" in e.expected
    assert e.hint and "kg" in e.hint


def test_check_dim_ignores_angle():
    assert check_dim(ANGLE, DIMENSIONLESS)
    assert check_dim(ANGULAR_VELOCITY, FREQUENCY)
    assert check_dim(LENGTH, LENGTH)
    assert not check_dim(LENGTH, ANGLE)
    assert not check_dim(MOMENT, INERTIA)


@pytest.mark.parametrize("dim,name", [
    (LENGTH, "длина"), (MASS, "масса"), (ANGLE, "угол"), (FORCE, "сила"), (MOMENT, "момент силы"),
    (INERTIA, "момент инерции"), (PRESSURE, "давление"), (ANGULAR_VELOCITY, "угловая скорость"),
    (DIMENSIONLESS, "безразмерная величина"), (TIME, "время"), (VELOCITY, "скорость"),
    (ACCELERATION, "ускорение"), (ANGULAR_ACCELERATION, "угловое ускорение"),
    (DENSITY, "плотность"), (FREQUENCY, "частота"), (POWER, "мощность"),
])
def test_dim_name(dim, name):
    assert dim_name(dim) == name


def test_dim_name_fallback_formula():
    assert dim_name((1, 1, -4, 0)) == "м·кг/с⁴"
    assert dim_name((-1, 0, 0, 0)) == "1/м"


@pytest.mark.parametrize("dim", [LENGTH, MASS, TIME, ANGLE, DIMENSIONLESS, FORCE, MOMENT, INERTIA,
                                 VELOCITY, ANGULAR_VELOCITY, PRESSURE, ENERGY, DENSITY, ACCELERATION,
                                 ANGULAR_ACCELERATION, FREQUENCY, POWER, (1, 1, -4, 0), (2, 1, -2, 1)])
def test_example_for_parses_back(dim):
    ex = example_for(dim)
    _, d = parse_quantity(ex)
    assert check_dim(d, dim)


def test_examples_spec():
    assert example_for(LENGTH) == "0.347 m"
    assert example_for(MASS) == "9 kg"
    assert example_for(ANGLE) == "99.1 deg"
    assert example_for(ANGULAR_VELOCITY) == "65 rpm"


# =============================================================================================
# Q


class TestQ:
    def test_arithmetic(self):
        a, b = Q(2.0, LENGTH), Q(3.0, LENGTH)
        assert (a + b).value == 5.0 and (a + b).dim == LENGTH
        assert (a - b).value == -1.0
        assert (a * b).dim == (2, 0, 0, 0)
        assert (a / b).dim == DIMENSIONLESS
        assert (a ** 2).dim == (2, 0, 0, 0) and (a ** 2).value == 4.0
        assert (-a).value == -2.0
        assert abs(Q(-2.0, LENGTH)).value == 2.0
        assert (2 * a).value == 4.0 and (a * 2).dim == LENGTH
        assert (1 / a).dim == (-1, 0, 0, 0)
        assert float(a) == 2.0

    def test_incompatible(self):
        with pytest.raises(CaseError, match="несовместимые единицы: длина \\+ угол"):
            Q(1.0, LENGTH) + Q(1.0, ANGLE)
        with pytest.raises(CaseError, match="несовместимые единицы"):
            Q(1.0, LENGTH) < Q(1.0, MASS)

    def test_angle_component_ignored(self):
        s = Q(1.0, DIMENSIONLESS) + Q(DEG, ANGLE)
        assert s.dim == ANGLE  # the angular summand wins
        assert (Q(2.0, ANGULAR_VELOCITY) + Q(1.0, FREQUENCY)).dim == ANGULAR_VELOCITY

    def test_rational_power(self):
        q = Q(16.0, (4, 0, 0, 0)) ** 0.5
        assert q.value == 4.0 and q.dim == (2, 0, 0, 0)
        with pytest.raises(CaseError, match="дробная размерность"):
            Q(2.0, LENGTH) ** 0.5
        q = Q(8.0, (3, 0, -3, 0)) ** (1 / 3)
        assert close(q.value, 2.0) and q.dim == VELOCITY

    def test_comparisons_return_bool_arrays(self):
        a = Q(np.array([1.0, 2.0, 3.0]), LENGTH)
        r = a > Q(1.5, LENGTH)
        assert isinstance(r, np.ndarray) and r.dtype == bool
        assert r.tolist() == [False, True, True]
        assert (a == a).all()
        assert isinstance(Q(1.0) < Q(2.0), np.ndarray)

    def test_arrays_and_numpy_left_operand(self):
        a = Q(np.array([1.0, 2.0]), LENGTH)
        r = np.array([3.0, 4.0]) * a
        assert isinstance(r, Q) and r.dim == LENGTH and r.value.tolist() == [3.0, 8.0]

    def test_to(self):
        assert close(Q(0.347, LENGTH).to("mm"), 347.0)
        assert close(Q(math.pi, ANGLE).to("deg"), 180.0)
        with pytest.raises(CaseError):
            Q(1.0, LENGTH).to("kg")

    def test_unhashable(self):
        with pytest.raises(TypeError):
            hash(Q(1.0))


# =============================================================================================
# evaluate

NAMES = {
    "S_min": Q(0.1, LENGTH), "S_max": Q(0.3, LENGTH), "l_1": Q(0.1, LENGTH), "l_0": Q(0.2, LENGTH),
    "l_OA": Q(0.05, LENGTH), "X6": Q(3.0, LENGTH), "Y6": Q(4.0, LENGTH), "L4": Q(0.7, LENGTH),
    "P": Q(1000.0, FORCE), "g": Q(9.81, ACCELERATION), "m_2": Q(5.0, MASS), "e": Q(0.02, LENGTH),
}


@pytest.mark.parametrize("text,value,dim", [
    ("0.5*(S_min + S_max)", 0.2, LENGTH),
    ("180 deg + asin(l_1/l_0)", math.pi + math.asin(0.5), ANGLE),
    ("2*l_OA", 0.1, LENGTH),
    ("sqrt(X6^2 + Y6^2)", 5.0, LENGTH),
    ("sqrt(X6**2 + Y6**2)", 5.0, LENGTH),
    ("sqrt(X6² + Y6²)", 5.0, LENGTH),
    ("L4", 0.7, LENGTH),
    ("0.347 m", 0.347, LENGTH),
    ("-P*0.2", -200.0, FORCE),
    ("m_2*g", 49.05, FORCE),
    ("3 mm + 0.2 m", 0.203, LENGTH),
    ("2 m/s^2 * 3 kg", 6.0, FORCE),
    ("10 m/s^2", 10.0, ACCELERATION),
    ("65 rpm", 65 * 2 * math.pi / 60, ANGULAR_VELOCITY),
    ("65 об/мин", 65 * 2 * math.pi / 60, ANGULAR_VELOCITY),
    ("0.45 kg*m^2", 0.45, INERTIA),
    ("0.45 kg·m²", 0.45, INERTIA),
    ("0.45 kg m^2", 0.45, INERTIA),
    ("99.1°", 99.1 * DEG, ANGLE),
    ("-5 deg", -5 * DEG, ANGLE),
    ("0,5*l_OA", 0.025, LENGTH),
    ("2^-1", 0.5, DIMENSIONLESS),
    ("-2^2", -4.0, DIMENSIONLESS),
    ("2^3^2", 512.0, DIMENSIONLESS),
    ("(1 + 2)*3", 9.0, DIMENSIONLESS),
    ("8/4/2", 1.0, DIMENSIONLESS),
    ("pi/2", math.pi / 2, DIMENSIONLESS),
    ("2*π", 2 * math.pi, DIMENSIONLESS),
    ("sin(30 deg)", 0.5, DIMENSIONLESS),
    ("cos(pi)", -1.0, DIMENSIONLESS),
    ("tan(45 deg)", 1.0, DIMENSIONLESS),
    ("tg(45 deg)", 1.0, DIMENSIONLESS),
    ("acos(0.5)", math.pi / 3, ANGLE),
    ("arcsin(0.5)", math.pi / 6, ANGLE),
    ("atan(1)", math.pi / 4, ANGLE),
    ("atan2(Y6, X6)", math.atan2(4, 3), ANGLE),
    ("hypot(X6, Y6)", 5.0, LENGTH),
    ("abs(-P)", 1000.0, FORCE),
    ("min(S_min, S_max, 5 mm)", 0.005, LENGTH),
    ("max(S_min, S_max)", 0.3, LENGTH),
    ("exp(0)", 1.0, DIMENSIONLESS),
    ("log(exp(2))", 2.0, DIMENSIONLESS),
    ("atan2(l_1, 0.1 m)", math.pi / 4, ANGLE),
    ("1.5e-3 m", 1.5e-3, LENGTH),
    ("2 m**2", 2.0, (2, 0, 0, 0)),
    ("e*2", 0.04, LENGTH),  # a parameter named e, not Euler's number
    ("l_OA/2 mm", 25.0, DIMENSIONLESS),
    ("0.2 m / 2", 0.1, LENGTH),
    ("3 > 2", 1.0, DIMENSIONLESS),
])
def test_evaluate_values(text, value, dim):
    q = evaluate(text, NAMES)
    assert q.dim == dim, (text, q.dim)
    assert close(float(q.value), value, 1e-12), (text, q.value)


def test_bare_numbers():
    q = evaluate("1.5", {}, bare_is=ANGLE)
    assert q.value == 1.5 and q.dim == ANGLE  # bare numbers are SI: radians
    assert evaluate(1.5, {}, bare_is=ANGLE).dim == ANGLE
    assert evaluate(3, {}, bare_is=LENGTH, expected=LENGTH).value == 3.0
    assert evaluate("0,347", {}, bare_is=LENGTH).value == 0.347
    assert evaluate("-2", {}, bare_is=FORCE).value == -2.0
    assert evaluate("2", {}).dim == DIMENSIONLESS
    # a bare number inside an expression stays dimensionless
    assert evaluate("2*3", {}, bare_is=LENGTH).dim == DIMENSIONLESS
    with pytest.raises(CaseError, match="длина"):
        evaluate("2*3", {}, bare_is=LENGTH, expected=LENGTH)


def test_expected_dimension_mismatch():
    with pytest.raises(CaseError) as ei:
        evaluate("99.1 deg", {}, expected=LENGTH)
    e = ei.value
    assert "длина" in str(e)
    assert "угол" in str(e)
    assert e.got == "99.1 deg"
    assert "длина" in e.expected and "0.347 m" in e.expected


def test_expected_sets_dim():
    q = evaluate("pi/2", {}, expected=ANGLE)
    assert q.dim == ANGLE
    q = evaluate("asin(1)", {}, expected=ANGLE)
    assert close(q.value, math.pi / 2)


def test_expected_hint_for_dimensionless_expression():
    with pytest.raises(CaseError) as ei:
        evaluate("0.3*2", {}, expected=LENGTH)
    assert "безразмерн" in (ei.value.hint or "")


def test_incompatible_units_message():
    with pytest.raises(CaseError) as ei:
        evaluate("l_OA + 5 deg", NAMES)
    assert "несовместимые единицы: длина + угол" in str(ei.value)
    assert "l_OA + 5 deg" in str(ei.value)
    with pytest.raises(CaseError) as ei:
        evaluate("l_OA + 0.1", NAMES)
    assert "длина + безразмерная величина" in str(ei.value)
    assert "0.347 m" in ei.value.hint
    with pytest.raises(CaseError, match="несовместимые единицы: сила − масса"):
        evaluate("P - m_2", NAMES)
    with pytest.raises(CaseError, match="несовместимые единицы"):
        evaluate("P > m_2", NAMES)


def test_unknown_name():
    with pytest.raises(CaseError) as ei:
        evaluate("2*l_0A", NAMES)
    s = str(ei.value)
    assert "неизвестное имя «l_0A»; возможно, имелось в виду «l_OA»" in s
    with pytest.raises(CaseError) as ei:
        evaluate("qqq", {"a": Q(1.0)})
    assert "неизвестное имя «qqq»" in str(ei.value) and "a" in ei.value.hint


@pytest.mark.parametrize("text,fragment", [
    ("2*(l_OA", "синтаксическая ошибка в выражении «2*(l_OA»: не закрыта скобка"),
    ("sqrt(l_OA", "не закрыта скобка"),
    ("l_OA)", "лишняя закрывающая скобка"),
    ("2*", "выражение обрывается"),
    ("()", "пустые скобки"),
    ("2 3", "пропущен знак операции"),
    ("2 pi", "после числа «2» стоит «pi»"),
    ("0.3 xyz", "«xyz»"),
    ("3 $", "недопустимый символ «$»"),
    ("a,b", "запятая вне вызова функции"),
    ("(l_OA + l_1) mm", "пропущен знак операции перед «mm»"),
    ("", "пустое выражение"),
    ("   ", "пустое выражение"),
    ("sin", "функция"),
    ("foo(1)", "неизвестная функция «foo»"),
    ("l_OA(2)", "не является функцией"),
    ("atan2(1)", "atan2"),
    ("sqrt(l_OA)", "нечётная степень"),
    ("sin(l_OA)", "функция sin"),
    ("asin(2)", "вне области определения"),
    ("log(0)", "вне области определения"),
    ("1/0", "деление на ноль"),
    ("l_OA^l_OA", "показатель степени"),
    ("P^0.5", "дробная размерность"),
    ("exp(l_OA)", "exp"),
    ("atan2(l_OA, P)", "одинаковую размерность"),
    ("max(l_OA, P)", "одинаковую размерность"),
    ("2 Mpa", "MPa"),
    ("1 m2", "m^2"),
])
def test_expression_errors(text, fragment):
    with pytest.raises(CaseError) as ei:
        evaluate(text, NAMES)
    s = str(ei.value)
    assert fragment in s, s


def test_syntax_error_position():
    with pytest.raises(CaseError) as ei:
        evaluate("l_OA + * 2", NAMES)
    assert "позиция 8" in str(ei.value)


def test_non_scalar_inputs_rejected():
    with pytest.raises(CaseError):
        evaluate(True, {})
    with pytest.raises(CaseError):
        evaluate([1, 2], {})  # type: ignore[arg-type]


def test_evaluate_q_passthrough():
    q = evaluate(Q(2.0, LENGTH), {}, expected=LENGTH)
    assert q.value == 2.0


def test_cached_constants_are_not_shared():
    q1 = evaluate("2 m", {})
    q1.value = 99.0
    assert evaluate("2 m", {}).value == 2.0


def test_no_eval_injection():
    for text in ["__import__('os')", "l_OA.__class__", "[1]", "lambda: 1", "a; b", "x if y else z"]:
        with pytest.raises(CaseError):
            evaluate(text, NAMES)


# =============================================================================================
# arrays


def test_arrays_elementwise():
    n = {"wq_4": Q(np.array([1.0, 2.0, 3.0])), "wq_3": Q(np.array([2.0, 4.0, 0.0])),
         "s": Q(np.array([0.1, 0.2, 0.3]), LENGTH), "phi": Q(np.array([0.0, 30.0, 90.0]) * DEG, ANGLE)}
    r = evaluate("wq_4 / wq_3", n)  # division by zero in an array gives inf, no exception
    assert r.value[:2].tolist() == [0.5, 0.5] and np.isinf(r.value[2])
    r = evaluate("s*1000/1 m", n)
    assert np.allclose(r.value, [100, 200, 300]) and r.dim == DIMENSIONLESS
    r = evaluate("sin(phi)", n)
    assert np.allclose(r.value, [0.0, 0.5, 1.0])
    r = evaluate("s > 0.15 m", n)
    assert r.value.tolist() == [False, True, True]
    r = evaluate("max(s, 0.25 m)", n, expected=LENGTH)
    assert np.allclose(r.value, [0.25, 0.25, 0.3])
    r = evaluate("sqrt(s^2)", n)
    assert np.allclose(r.value, [0.1, 0.2, 0.3]) and r.dim == LENGTH
    r = evaluate("asin(wq_4 - 2.5)", n)  # out-of-domain elements become NaN for arrays
    assert np.isnan(r.value[0]) and close(r.value[2], math.pi / 6)


# =============================================================================================
# free_names and resolve


def test_free_names():
    assert free_names("0.5*(S_min + S_max)") == {"S_min", "S_max"}
    assert free_names("180 deg + asin(l_1/l_0)") == {"l_1", "l_0"}
    assert free_names("2*pi*r + 3 mm + sqrt(x)") == {"r", "x"}
    assert free_names("10 m/s^2") == set()
    assert free_names("0.45 kg m^2") == set()
    assert free_names(3.5) == set()
    assert free_names("L4") == {"L4"}


def test_resolve_dependency_order():
    params = {"a": "2*b", "b": "c + 1 m", "c": 0.5, "phi": "180 deg + asin(c/b)", "n": "65 rpm"}
    out = resolve(params, expected={"c": LENGTH, "phi": ANGLE, "n": ANGULAR_VELOCITY})
    assert list(out) == list(params)
    assert out["c"].value == 0.5 and out["c"].dim == LENGTH
    assert out["b"].value == 1.5 and out["a"].value == 3.0
    assert close(out["phi"].value, math.pi + math.asin(0.5 / 1.5))
    assert close(out["n"].value, 65 * 2 * math.pi / 60)


def test_resolve_extra_names():
    out = resolve({"x": "2*L"}, extra_names={"L": Q(1.5, LENGTH)}, expected={"x": LENGTH})
    assert out == {"x": out["x"]} and out["x"].value == 3.0


def test_resolve_bare_number_without_expected_is_dimensionless():
    assert resolve({"k": 2})["k"].dim == DIMENSIONLESS


def test_resolve_cycles():
    with pytest.raises(CaseError) as ei:
        resolve({"a": "b + 1", "b": "a + 1"})
    assert "циклическая зависимость параметров: a → b → a" in str(ei.value)
    with pytest.raises(CaseError) as ei:
        resolve({"x": 1, "a": "b", "b": "c", "c": "a"})
    assert "a → b → c → a" in str(ei.value)
    with pytest.raises(CaseError, match="a → a"):
        resolve({"a": "a*2"})


def test_resolve_unknown_name_with_hint():
    with pytest.raises(CaseError) as ei:
        resolve({"l_OA": "0.1 m", "x": "2*l_0A"})
    e = ei.value
    assert e.key == "x"
    assert "неизвестное имя «l_0A»; возможно, имелось в виду «l_OA»" in str(e)


def test_resolve_expected_mismatch_has_key():
    with pytest.raises(CaseError) as ei:
        resolve({"l": "5 deg"}, expected={"l": LENGTH})
    e = ei.value
    assert e.key == "l" and "длина" in str(e) and str(e).startswith("ключ l:")
    e2 = e.with_context(file="cases/a.toml", key_prefix="params")
    assert str(e2).startswith("cases/a.toml: ключ params.l:")


def test_resolve_syntax_error_has_key():
    with pytest.raises(CaseError) as ei:
        resolve({"a": "1 m", "b": "2*(a"})
    assert ei.value.key == "b" and "не закрыта скобка" in str(ei.value)


def test_resolve_q_values():
    out = resolve({"a": Q(2.0, LENGTH), "b": "a*a"})
    assert out["b"].dim == (2, 0, 0, 0) and out["b"].value == 4.0
