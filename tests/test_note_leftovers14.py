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
