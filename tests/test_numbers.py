"""The one number formatter: decimal comma, U+2212, rounding, units, exponents."""

import math
from decimal import Decimal

import numpy as np
import pytest

from reportgen.style.numbers import (
    MINUS,
    NBSP,
    NNBSP,
    fmt,
    fmt_deg,
    fmt_pct,
    mpl_formatter,
    superscript,
    tex_num,
)

M = MINUS


@pytest.mark.parametrize(
    "x, kw, expected",
    [
        # fixed decimals
        (0.347, dict(digits=3), "0,347"),
        (0.347, dict(digits=3, unit="м"), "0,347\u00a0м"),
        (6.80678, dict(digits=3), "6,807"),
        (-6.80678, dict(digits=3), M + "6,807"),
        (2, dict(digits=2), "2,00"),
        (2.5, dict(digits=0), "3"),
        (-2.5, dict(digits=0), M + "3"),
        (1234.5678, dict(digits=1), "1234,6"),
        (12345.678, dict(digits=1), "12" + NNBSP + "345,7"),
        (-1234567.0, dict(digits=0, exp_from=1e9), M + "1" + NNBSP + "234" + NNBSP + "567"),
        # ROUND_HALF_UP of the decimal representation (not of the binary float)
        (0.1735, dict(digits=3), "0,174"),
        (0.1725, dict(digits=3), "0,173"),
        (2.675, dict(digits=2), "2,68"),
        (1.005, dict(digits=2), "1,01"),
        (0.125, dict(digits=2), "0,13"),
        (-0.125, dict(digits=2), M + "0,13"),
        (0.0005, dict(digits=3), "0,001"),
        (0.00049999, dict(digits=3), "0,000"),
        (599.8149999, dict(digits=3), "599,815"),
        # negative zero and values rounding to zero: never "−0,000"
        (-0.0, dict(digits=3), "0,000"),
        (-0.0004, dict(digits=3), "0,000"),
        (-0.00049, dict(digits=3, sign=True), "0,000"),
        (0.0, dict(digits=3, sign=True), "0,000"),
        (-1e-17, dict(digits=3), "0,000"),
        (6.123233995736766e-17, dict(digits=4), "0,0000"),  # cos 90°
        (-0.4, dict(digits=0), "0"),
        # forced sign
        (2.5, dict(digits=1, sign=True), "+2,5"),
        (-2.5, dict(digits=1, sign=True), M + "2,5"),
        # significant digits (default sig=4)
        (0.347215, {}, "0,3472"),
        (3.14159, {}, "3,142"),
        (31.4159, {}, "31,42"),
        (314.159, {}, "314,2"),
        (3141.59, {}, "3142"),
        (31415.9, {}, "31" + NNBSP + "416"),
        (314159.0, {}, "314" + NNBSP + "159"),
        (0.000123456, {}, "0,0001235"),
        (0.001, {}, "0,001000"),
        (12.0, {}, "12,00"),
        (0.99996, {}, "1,000"),  # carry into a new digit keeps 4 significant digits
        (9.99996, {}, "10,00"),
        (99999.6, {}, "100" + NNBSP + "000"),
        (9999.6, {}, "10" + NNBSP + "000"),
        (1.5, dict(sig=2), "1,5"),
        (1.55, dict(sig=2), "1,6"),
        (0.0, {}, "0"),
        (-0.0, {}, "0"),
        # integers are exact counts: no invented decimals in sig mode
        (65, {}, "65"),
        (np.int64(12), {}, "12"),
        (65, dict(digits=1), "65,0"),
        # exponent form: |x| >= exp_from, or 0 < |x| < 1e-4 in sig mode
        (1234567.0, {}, "1,235·10⁶"),
        (-1234567.0, {}, M + "1,235·10⁶"),
        (999999.0, {}, "999" + NNBSP + "999"),
        (1e6, {}, "1,000·10⁶"),
        (123456.0, dict(exp_from=1e5), "1,235·10⁵"),
        (1.2345e-5, {}, "1,235·10⁻⁵"),
        (-1.2345e-5, {}, M + "1,235·10⁻⁵"),
        (9.99996e-5, {}, "1,000·10⁻⁴"),  # mantissa carry
        (1e-4, {}, "0,0001000"),
        (2.5e-7, dict(sig=2), "2,5·10⁻⁷"),
        (1.5e7, dict(digits=2), "1,50·10⁷"),
        (3e-5, dict(digits=6), "0,000030"),
        (-3e-5, dict(digits=4), "0,0000"),
        (1234567.0, dict(unit="Н"), "1,235·10⁶\u00a0Н"),
        # NaN and infinities
        (float("nan"), {}, "—"),
        (float("nan"), dict(unit="м"), "—"),
        (float("inf"), {}, "—"),
        (-math.inf, dict(digits=2), "—"),
        (np.nan, {}, "—"),
        # numpy scalars and Decimal
        (np.float64(0.1735), dict(digits=3), "0,174"),
        (np.float32(0.5), dict(digits=2), "0,50"),
        (Decimal("0.1735"), dict(digits=3), "0,174"),
        # units
        (99.1, dict(digits=1, unit="°"), "99,1°"),
        (65, dict(unit="об/мин"), "65\u00a0об/мин"),
        (-9.81, dict(digits=2, unit="м/с²"), M + "9,81\u00a0м/с²"),
    ],
)
def test_fmt(x, kw, expected):
    assert fmt(x, **kw) == expected


def test_fmt_never_uses_hyphen_or_point():
    for x in np.linspace(-1000, 1000, 401):
        s = fmt(float(x) / 7, digits=3)
        assert "-" not in s and "." not in s
        assert not s.startswith(M + "0,000")


def test_fmt_unit_uses_no_break_space():
    s = fmt(0.347, digits=3, unit="м")
    assert s[-2] == NBSP and " " not in s


def test_fmt_rejects_non_numbers():
    with pytest.raises(TypeError):
        fmt("abc")
    with pytest.raises(ValueError):
        fmt(1.0, digits=-1)
    with pytest.raises(ValueError):
        fmt(1.0, digits=None, sig=0)


def test_fmt_deg_and_pct():
    assert fmt_deg(math.pi / 4) == "45,0°"
    assert fmt_deg(-math.pi / 2, digits=2) == M + "90,00°"
    assert fmt_deg(math.radians(197.458), digits=3) == "197,458°"
    assert fmt_deg(-1e-18) == "0,0°"
    assert fmt_deg(float("nan")) == "—"
    assert fmt_pct(0.0123) == "1,23\u00a0%"
    assert fmt_pct(0.11, 0) == "11\u00a0%"
    assert fmt_pct(-0.006, 1) == M + "0,6\u00a0%"
    assert fmt_pct(-0.6, 1, fraction=False) == M + "0,6\u00a0%"
    assert fmt_pct(float("nan")) == "—"


@pytest.mark.parametrize(
    "x, kw, expected",
    [
        (6.80678, dict(digits=3, unit="рад/с"), r"6{,}807\ \text{рад/с}"),
        (-5.792, dict(digits=3), r"{-5{,}792}"),
        (-5.792, dict(digits=3, paren=True), r"\left({-5{,}792}\right)"),
        (0.1735, dict(digits=3), r"0{,}174"),
        (-0.0001, dict(digits=3), r"0{,}000"),
        (65, {}, "65"),
        (1234567.0, {}, r"1{,}235 \cdot 10^{6}"),
        (1.2345e-5, {}, r"1{,}235 \cdot 10^{-5}"),
        (12345.6, dict(digits=1), r"12\,345{,}6"),
        (2.5, dict(digits=1, sign=True), r"+2{,}5"),
        (99.1, dict(digits=1, unit="°"), r"99{,}1^{\circ}"),
        (float("nan"), {}, r"\text{—}"),
    ],
)
def test_tex_num(x, kw, expected):
    assert tex_num(x, **kw) == expected


def test_tex_num_renders_with_ziamath():
    from reportgen.report.formulas import render_latex

    svg, w, h, _ = render_latex(tex_num(-1234.5678, digits=2, unit="Н·м"))
    assert svg.startswith("<svg") and w > 0 and h > 0


def test_superscript():
    assert superscript("-5") == "⁻⁵"
    assert superscript(12) == "¹²"


def test_mpl_formatter_auto_decimals():
    f = mpl_formatter()
    locs = [-1.0, -0.5, 0.0, 0.5, 1.0]
    assert f.format_ticks(locs) == [M + "1,0", M + "0,5", "0,0", "0,5", "1,0"]
    assert f.format_ticks([0, 90, 180, 270, 360]) == ["0", "90", "180", "270", "360"]
    # float noise in tick locations does not add decimals
    assert f.format_ticks([0.1, 0.2, 0.30000000000000004]) == ["0,1", "0,2", "0,3"]
    # large ticks are grouped, never in exponent form
    assert f.format_ticks([0, 2_500_000]) == ["0", "2" + NNBSP + "500" + NNBSP + "000"]


def test_mpl_formatter_fixed_digits():
    f = mpl_formatter(2)
    assert f.format_ticks([-0.001, 1.5]) == ["0,00", "1,50"]
    # exponent form becomes mathtext (fonts lack ⁰ and ⁻)
    assert mpl_formatter(1).format_ticks([2e7]) == [r"$\mathregular{2,0\cdot10^{7}}$"]
