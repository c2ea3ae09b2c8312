"""Session 12's «noticed and left», linkage items (issue 9): the Assur groups at one common scale,
the plan of positions of a small crank, the transmission angles of groups with a sliding pair in
the conclusion, the conclusion's symbols set as the text sets them."""
from pathlib import Path

import pytest

from reportgen.scenes import labels as L
from reportgen.scenes.draw import GOST_K
from reportgen.style import mplstyle

CASES = Path(__file__).resolve().parents[1] / "cases"


def _study(name):
    from reportgen import load_case
    return load_case(CASES / f"{name}.toml")


@pytest.fixture
def figures(monkeypatch):
    """The matplotlib figures the scenes write."""
    figs = []
    orig = mplstyle.to_svg

    def keep(fig):
        figs.append(fig)
        return orig(fig)
    monkeypatch.setattr(mplstyle, "to_svg", keep)
    return figs


def _groups(name):
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.mechanism import AssurGroups
    st = _study(name)
    return st, AssurGroups(chosen_position(st)).draw(st)


# --- 1. the Assur groups at one common scale ----------------------------------------------------

@pytest.mark.parametrize("name", ["slider_crank", "ws004_slotted_lever", "slider_stone_rocker"])
def test_groups_at_one_common_scale(name, figures):
    """slider_crank's crank (0,1) was drawn at 0,002 м/мм and its coupler group at 0,01 м/мм: the
    0,1 m crank looked longer than the 0,4 m coupler. Where one ГОСТ 2.302 scale keeps every
    group's joints ≥ 10 mm apart and the row fits the text width, all groups are drawn at it,
    the scale written once under the row."""
    _, d = _groups(name)
    mus = {mu for _, mu, _ in d.panels}
    assert len(mus) == 1, d.panels
    assert any(abs(min(mus) * 1000 - k) < 1e-9 for k in GOST_K)
    assert d.width_mm <= 165.0 + 1e-9
    fig = figures[-1]
    assert L.check_figure(fig) == []
    assert len([t for t in fig.texts if "м/мм" in t.get_text()]) == 1


def test_slider_crank_crank_shorter_than_coupler():
    """The proportions kept: the crank (0,1) is drawn shorter than the group (2,3)."""
    _, d = _groups("slider_crank")
    (_, _, crank), (_, _, coupler) = d.panels
    assert crank < coupler / 2


@pytest.mark.parametrize("name", ["ws002_tractor_hitch", "ws000_six_bar"])
def test_groups_fall_back_to_own_scales(name, figures):
    """ws002's cylinder group (1,2,3) and ws000's crank would be under 10 mm at any scale the
    whole row fits: each group keeps its own scale, written under it."""
    _, d = _groups(name)
    assert len({mu for _, mu, _ in d.panels}) > 1
    assert len([t for t in figures[-1].texts if "м/мм" in t.get_text()]) == len(d.panels)


def test_structure_text_names_the_common_scale():
    """The text says what the figure does: one scale (and which) or each its own."""
    from notehelpers import paragraph_text, plain
    from reportgen.report.sections import structure
    html = plain(paragraph_text(structure.build(_study("slider_crank"))))
    assert "все группы вычерчены в одном масштабе" in html and "1:5" in html
    assert "в своём масштабе" not in html
