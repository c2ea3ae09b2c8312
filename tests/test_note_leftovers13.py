"""Session 12's «noticed and left», linkage items (issue 9): the Assur groups at one common scale,
the plan of positions of a small crank, the transmission angles of groups with a sliding pair in
the conclusion, the conclusion's symbols set as the text sets them."""
from pathlib import Path

import numpy as np
import pytest

from reportgen.scenes import labels as L
from reportgen.scenes.draw import GOST_K

CASES = Path(__file__).resolve().parents[1] / "cases"


def _study(name):
    from reportgen import load_case
    return load_case(CASES / f"{name}.toml")


def _groups(name):
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.mechanism import AssurGroups
    st = _study(name)
    return st, AssurGroups(chosen_position(st)).draw(st)


# --- 1. the Assur groups at one common scale ----------------------------------------------------

@pytest.mark.parametrize("name", ["slider_crank", "ws004_slotted_lever", "slider_stone_rocker"])
def test_groups_at_one_common_scale(name, captured):
    """slider_crank's crank (0,1) was drawn at 0,002 м/мм and its coupler group at 0,01 м/мм: the
    0,1 m crank looked longer than the 0,4 m coupler. Where one ГОСТ 2.302 scale keeps every
    group's joints ≥ 10 mm apart and the row fits the text width, all groups are drawn at it,
    the scale written once under the row."""
    _, d = _groups(name)
    mus = {mu for _, mu, _ in d.panels}
    assert len(mus) == 1, d.panels
    assert any(abs(min(mus) * 1000 - k) < 1e-9 for k in GOST_K)
    assert d.width_mm <= 165.0 + 1e-9
    fig = captured[-1]
    assert L.check_figure(fig) == []
    assert len([t for t in fig.texts if "м/мм" in t.get_text()]) == 1


def test_slider_crank_crank_shorter_than_coupler():
    """The proportions kept: the crank (0,1) is drawn shorter than the group (2,3)."""
    _, d = _groups("slider_crank")
    (_, _, crank), (_, _, coupler) = d.panels
    assert crank < coupler / 2


@pytest.mark.parametrize("name", ["ws002_tractor_hitch", "ws000_six_bar"])
def test_groups_fall_back_to_own_scales(name, captured):
    """ws002's cylinder group (1,2,3) and ws000's crank would be under 10 mm at any scale the
    whole row fits: each group keeps its own scale, written under it."""
    _, d = _groups(name)
    assert len({mu for _, mu, _ in d.panels}) > 1
    assert len([t for t in captured[-1].texts if "м/мм" in t.get_text()]) == len(d.panels)


def test_structure_text_names_the_common_scale():
    """The text says what the figure does: one scale (and which) or each its own."""
    from notehelpers import paragraph_text, plain
    from reportgen.report.sections import structure
    html = plain(paragraph_text(structure.build(_study("slider_crank"))))
    assert "все группы вычерчены в одном масштабе" in html and "1:5" in html
    assert "в своём масштабе" not in html


# --- 3. the transmission angles of groups with sliding pairs judged -------------------------------

def _plain(html) -> str:
    from notehelpers import plain
    return plain(html)


def test_pvp_transmission_angle_from_the_guides():
    """rocker_plunger_pvp's ПВП group (4,5): the stone 4 presses on the plunger 5 along the normal
    to the slot CK of the rocker 3, the plunger moves along its vertical guide, so μ is the acute
    angle between CK and the vertical — computed here from the points over the cycle."""
    import numpy as np
    st = _study("rocker_plunger_pvp")
    fl = st.slide_flags["4_5"]
    cyc = st.cycle
    slot = np.arctan2(cyc["y_K"] - cyc["y_C"], cyc["x_K"] - cyc["x_C"]).to_numpy()
    mu = np.arcsin(np.abs(np.sin(np.pi / 2 - slot)))
    assert fl["min"] == pytest.approx(mu.min(), abs=1e-9)
    assert not fl["const"]


def test_pvp_group_in_table_and_conclusion():
    """The ПВП group's μ_min was neither in the table of transmission angles nor in the conclusion
    (only the ВВВ group (2,3) was judged). Now both, with the same rule μ_min ≥ 40°."""
    import math
    from notehelpers import blocks
    from reportgen.report.document import Table
    from reportgen.report.sections import kinematics as K
    st = _study("rocker_plunger_pvp")
    mu45 = math.degrees(st.slide_flags["4_5"]["min"])
    txt = " ".join(_plain(l) for l in K.conclusion_lines(st))
    assert f"в группе (4,5) {mu45:.1f}°".replace(".", ",") in txt
    assert "в группе (2,3)" in txt and "не меньше допускаемого 40°" in txt
    sec = K.build(st)
    tab = next(b for b in blocks(sec) if isinstance(b, Table) and b.id == "tab-mu")
    assert "(4,5)" in list(tab.data["g"])
    assert "ПВП" in (_plain(tab.note) if tab.note else "")


def test_vpv_group_judged_in_conclusion():
    """ws004's ВПВ group (2,3) (a stone on the кулиса's axis: μ = 90° always) is judged too."""
    from reportgen.report.sections import kinematics as K
    txt = " ".join(_plain(l) for l in K.conclusion_lines(_study("ws004_slotted_lever")))
    assert "в группе (2,3) 90,0°, в группе (4,5)" in txt


def test_low_sliding_group_angle_gets_advice():
    """A ПВП group below 40° is told so, with what to change, and the mechanism is not called
    «работоспособен»."""
    from reportgen.report.sections import kinematics as K
    st = _study("rocker_plunger_pvp")
    fl = dict(st.slide_flags["4_5"], min=0.5)        # 28,6°
    st.__dict__["slide_flags"] = {"4_5": fl}
    txt = " ".join(_plain(l) for l in K.conclusion_lines(st))
    assert "Наименьший угол передачи в группе (4,5) — 28,6° — меньше допускаемого 40°" in txt
    assert "изменив наклон направляющей пары 3–4 или неподвижной направляющей звена 5" in txt
    assert "работоспособен" not in txt


# --- 4. the conclusion's symbols set as the text sets them ------------------------------------------

# a Latin letter typed by hand before a subscript or «=» (upright), not inside <i>…</i>
UPRIGHT = r"(?<![\w>/;])[A-Za-z](?:<sub>|&nbsp;=)"


@pytest.mark.parametrize("name", ["ws000_six_bar", "sewing_needle_takeup", "engine_four_stroke",
                                  "ws002_tractor_hitch"])
def test_conclusion_symbols_italic(name):
    """The conclusion set M<sub>д</sub>, J<sub>I</sub>, A<sub>с</sub>, J<sub>доп</sub>, D<sub>2</sub>, b, m,
    u, v, S, W upright while the text sets them italic (inline math): now by inline_math too. ws000:
    a big flywheel; sewing: a small flywheel on a motor shaft (u); engine: A<sub>д</sub>, M<sub>с</sub>;
    ws002: a cylinder's length S."""
    import re
    from reportgen.report.assemble import _conclusion, chosen_sections
    st = _study(name)
    lines = [p.html for p in _conclusion(st, chosen_sections(st, None))]
    text = " ".join(str(h) for h in lines)
    bad = [text[max(0, m.start() - 40):m.end() + 10] for m in re.finditer(UPRIGHT, text)]
    assert bad == []
    assert 'class="mx math-inline"><i>W</i>' in text


# --- 5. the conclusions read through ---------------------------------------------------------------

def test_inverse_task_delta_printed_as_found():
    """crank_press_inverse (a given flywheel, δ found) said «Для δ = 0,09751300009 … требуется J_I»: a
    found δ printed with 11 digits as if given, and «требуется» of a flywheel that is given. Now δ to
    4 significant digits, as the text prints it, and what the given flywheel gives."""
    from reportgen.report.sections.dynamics import conclusion_lines
    text = _plain(" ".join(conclusion_lines(_study("crank_press_inverse"))))
    assert "С заданным маховиком коэффициент неравномерности хода δ\u00a0=\u00a00,09751 при" in text, text
    assert "0,097513" not in text and "требуется" not in text


# --- 2. the plan of positions of a small crank ------------------------------------------------------

@pytest.mark.parametrize("name", ["sewing_needle_takeup", "screen_shaker", "class3_triad"])
def test_small_crank_numbered_in_view_readably(name, captured):
    """The sewing machine's 7,5 mm crank circle at 1:2 crowded A₀…A₁₁ on the main drawing (A₅ went
    23 mm off on a leader). No larger ГОСТ scale fits the page (the mechanism is 0,23 m tall), so
    the positions are numbered in the enlarged view only: no two labels overlap and the numbers
    stand ≥ 5 mm apart on paper."""
    import itertools
    import re
    from reportgen.scenes.mechanism import PositionsPlan
    st = _study(name)
    d = PositionsPlan().draw(st)
    assert d.detail_mu is not None and d.detail_mu < d.mu
    fig = captured[-1]
    assert L.check_figure(fig) == []
    ax, r = fig.axes[0], fig.canvas.get_renderer()
    mm = 25.4 / fig.dpi
    nums = []
    for t in ax.texts:
        if re.fullmatch(r"\$[A-Z]_\{\d+(?:,\s*\d+)*\}\$", t.get_text()):
            bb = t.get_window_extent(r)
            nums.append(np.array([(bb.x0 + bb.x1) / 2, (bb.y0 + bb.y1) / 2]) * mm)
    assert len(nums) >= 8
    gaps = [float(np.hypot(*(a - b))) for a, b in itertools.combinations(nums, 2)]
    assert min(gaps) >= 5.0, min(gaps)


def test_low_vpv_angle_gets_advice(monkeypatch):
    """A ВПВ group below 40° (the stone's line far from the кулиса's pivot) is told what to change."""
    from reportgen.report.sections import kinematics as K
    st = _study("ws004_slotted_lever")
    monkeypatch.setattr(K, "_guide_transmission", lambda s: ([{"g": "(2,3)", "mu": 0.5, "q": 0.0, "key": "2_3"}], ""))
    txt = " ".join(_plain(l) for l in K.conclusion_lines(st))
    pivot, pin = st.guide_flags["2_3"]["points"]
    assert "Наименьший угол передачи в группе (2,3) — 28,6° — меньше допускаемого 40°" in txt
    assert f"уменьшив расстояние e от опоры {pivot} кулисы до линии движения шарнира {pin}" in txt
    assert "работоспособен" not in txt
