"""Defects left by the session-5 page-by-page review of the notes (#9): each test fails on what the
review found (the crank's force analysis titled «Группа (0,1)», force arrows of a group drawing's
inset lying on each other, a kinematic column identically zero, reaction forces printed with
varying decimals, the Жуковский formula with signed arms next to a table of unsigned ones)."""
import math
import re

import numpy as np
import pytest

from conftest import CASES
from reportgen.report.document import Figure, Paragraph, Table
from notehelpers import blocks as _blocks, arrows_mm as _arrows_mm, share_near as _share_near


from notehelpers import plain as _plain  # noqa: E402


@pytest.fixture(scope="module")
def six_bar():
    from reportgen import load_case
    return load_case(CASES / "ws000_six_bar_corrected.toml")


@pytest.fixture(scope="module")
def six_bar_forces(six_bar):
    from reportgen.report.sections import forces
    return forces.build(six_bar)


# --------------------------------------------------------------------------------------------
# 1. the crank with the frame is the initial mechanism, not «Группа (0,1)»
# --------------------------------------------------------------------------------------------
def test_crank_force_analysis_named_initial_mechanism(six_bar_forces):
    blocks = list(_blocks(six_bar_forces))
    texts = ([_plain(b.html) for b in blocks if isinstance(b, Paragraph)]
             + [_plain(b.caption) for b in blocks if isinstance(b, (Figure, Table))])
    everything = " ".join(texts)
    assert "Группа (0,1)" not in everything and "группы (0,1)" not in everything
    caps = [_plain(b.caption) for b in blocks if isinstance(b, Figure)]
    assert any(c.startswith("Начальный механизм (0,1): схема нагружения") for c in caps), caps
    assert any(c.startswith("Группа (2,3)") for c in caps), caps
    tabs = [_plain(b.caption) for b in blocks if isinstance(b, Table)]
    assert any(c.startswith("Реакции в парах начального механизма (0,1)") for c in tabs), tabs
    head = next(t for t in texts if "R01" in t.replace("₀₁", "01") and "Неизвестные" in t and "Mур" in t)
    assert head.startswith("Начальный механизм (0,1).") and "Уравнение сил начального механизма" in head, head


def test_sheet_view_and_key_name_the_initial_mechanism(six_bar):
    from reportgen.report.key import _groups_text
    from reportgen.report.sections.structure import decomposition
    from reportgen.scenes.forces import group_name
    f = six_bar.forces
    names = [group_name(f, g) for g in f.model.groups]
    assert "Начальный механизм (0,1)" in names and "Группа (2,3)" in names
    text = _groups_text(decomposition(six_bar)[0])
    assert text.startswith("Начальный механизм (0,1); группы Ассура: II класса"), text
    assert "группы Ассура: группа" not in text


# --------------------------------------------------------------------------------------------
# 2. no two force arrows of a group drawing lie on each other, in the insets too
# --------------------------------------------------------------------------------------------
def test_ws000_group_23_arrows_apart_in_insets(six_bar, captured):
    """ws000 (corrected) group (2,3): G₃ and Φ₃ (×10) and G₂, Φ₂ (×20) fold back on each other in
    the enlarged insets; no two force arrows (polygon, insets, scheme) run within 0,7 mm of each
    other along more than 25 % of the shorter one; no label overlaps or is clipped. Arrows under
    2 mm are the heads of the moments' arcs."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import GroupForces
    from reportgen.scenes.labels import check_figure
    gi = next(i for i, g in enumerate(six_bar.forces.model.groups) if set(g.links) == {"2", "3"})
    d = GroupForces(chosen_position(six_bar), gi, landscape=True).draw(six_bar)
    fig = captured[-1]
    arrows = [s for s in _arrows_mm(fig) if np.linalg.norm(s[1] - s[0]) > 2.0]
    assert len(arrows) >= len(d.vectors)
    bad = []
    for i, (a0, a1) in enumerate(arrows):
        for j, (b0, b1) in enumerate(arrows):
            if i != j and np.linalg.norm(a1 - a0) <= np.linalg.norm(b1 - b0) and _share_near(a0, a1, b0, b1) > 0.25:
                bad.append((i, j, round(_share_near(a0, a1, b0, b1), 2)))
    assert not bad, bad
    assert check_figure(fig) == []


def test_inset_side_folding_back_moved_aside():
    """A chain folding back at 20° gets its second side moved beside the first and joined by thin
    lines; a chain turning at a right angle is drawn as is."""
    from reportgen.scenes.forces import _inset_sides, covered
    pts = np.array([[0.0, 10.0], [0.0, 0.0], [-3.4, 9.4]])
    segs = _inset_sides(pts, 3.5, 1.2)
    assert [m for *_, m in segs] == [False, True]
    (a0, a1, _), (b0, b1, _) = segs
    assert covered(b0, b1, a0, a1, 1.2) < 0.05 and np.isclose(np.linalg.norm(b0 - pts[1]), 3.5)
    assert b0[0] < 0                      # moved away from the first side
    segs = _inset_sides(np.array([[0.0, 10.0], [0.0, 0.0], [10.0, 0.0]]), 3.5, 1.2)
    assert not any(m for *_, m in segs)


# --------------------------------------------------------------------------------------------
# 3. ws004: the ВПВ group in the transmission-angle table; a column of zeros left out
# --------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def slotted():
    from reportgen import load_case
    from reportgen.report.sections import kinematics
    st = load_case(CASES / "ws004_slotted_lever.toml")
    return st, kinematics.build(st)


def test_vpv_group_in_transmission_table(slotted):
    """The кулиса's guide passes through its pivot C: the stone's pressure (normal to the guide)
    and the velocity of the кулиса's point under it (normal to CA, along the guide) are parallel,
    μ = 90° in every position; the group is in the table, and the note says why."""
    st, sec = slotted
    tab = next(b for b in _blocks(sec) if isinstance(b, Table) and b.id == "tab-mu")
    assert list(tab.data["g"]) == ["(2,3)", "(4,5)"]
    mu = dict(zip(tab.data["g"], tab.data["mu"]))
    assert mu["(2,3)"] == pytest.approx(np.pi / 2, abs=1e-15)
    qcol = next(c for c in tab.columns if c.key == "q")
    assert qcol.fmt(tab.data["q"].iloc[0]) == "—"
    assert "(2,3) ВПВ" in _plain(tab.note) and "90°" in _plain(tab.note)
    # independent check: the angle between CA and the guide CB is zero at every position
    cyc = st.cycle
    ca = np.column_stack([cyc["x_A"] - cyc["x_C"], cyc["y_A"] - cyc["y_C"]])
    cb = np.column_stack([cyc["x_B"] - cyc["x_C"], cyc["y_B"] - cyc["y_C"]])
    cross = (ca[:, 0] * cb[:, 1] - ca[:, 1] * cb[:, 0]) / np.linalg.norm(ca, axis=1) / np.linalg.norm(cb, axis=1)
    assert np.max(np.abs(cross)) < 1e-12


def test_offset_guide_transmission_angle(tmp_path):
    """A stone's pin offset by e from the кулиса's axis through its pivot: μ_min = 90° − arcsin(e/ρ_min),
    against the angle between the guide's normal and the velocity of the кулиса's point under the
    stone (⊥ CA) computed from the positions."""
    from reportgen import load_case
    from reportgen.report.sections.kinematics import _guide_transmission
    text = (CASES / "ws004_slotted_lever.toml").read_text(encoding="utf-8")
    line = 'line = { from = "C", to = "B" }'
    assert text.count(line) == 1
    case = tmp_path / "offset.toml"
    case.write_text(text.replace(line, line + '\noffset = "0.05 m"'), encoding="utf-8")
    st = load_case(case)
    rows, note = _guide_transmission(st)
    assert len(rows) == 1 and "arcsin" in note
    cyc = st.cycle
    t = np.column_stack([cyc["x_B"] - cyc["x_C"], cyc["y_B"] - cyc["y_C"]])
    t /= np.linalg.norm(t, axis=1)[:, None]                       # the guide's direction
    r = np.column_stack([cyc["x_A"] - cyc["x_C"], cyc["y_A"] - cyc["y_C"]])
    v = np.column_stack([-r[:, 1], r[:, 0]]) / np.linalg.norm(r, axis=1)[:, None]   # ⊥ CA
    # pressure angle α between the pressure (along the guide's normal) and the velocity; μ = 90° − α
    alpha = np.arccos(np.clip(np.abs(v[:, 0] * t[:, 1] - v[:, 1] * t[:, 0]), 0, 1))
    assert rows[0]["mu"] == pytest.approx(np.pi / 2 - alpha.max(), abs=1e-9)
    assert np.degrees(rows[0]["mu"]) < 89.0


def test_identically_zero_column_left_out(slotted):
    """y′_D of the slider moving along a horizontal line is 0 at every position: not a column of
    zeros in the table of point analogs, but one note under it."""
    from reportgen.report.document import Column
    from reportgen.report.sections.kinematics import zero_columns
    st, sec = slotted
    tabs = [b for b in _blocks(sec) if isinstance(b, Table) and str(b.id).startswith("tab-vq")]
    keys = [c.key for t in tabs for c in t.columns]
    assert "vqx_D" in keys and "vqy_D" not in keys
    assert "y′</i><sub>D</sub>&nbsp;=&nbsp;0 во всех положениях" in tabs[-1].note
    assert all(t.note is None for t in tabs[:-1])
    import pandas as pd
    df = pd.DataFrame({"a": [1.0, -2.0], "b": [1e-13, 0.0], "c": [3e-12, 0.0]})
    cols = [Column(x, x) for x in "abc"]
    kept, zero = zero_columns(df, cols)
    assert [c.key for c in kept] == ["a", "c"] and [c.key for c in zero] == ["b"]
    assert zero_columns(df[["b"]], cols[1:2]) == (cols[1:2], [])


# --------------------------------------------------------------------------------------------
# 4. the forces of the reaction tables to one number of decimals over the note
# --------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def hitch_forces():
    from reportgen import load_case
    from reportgen.report.sections import forces
    st = load_case(CASES / "ws002_tractor_hitch.toml")
    return st, forces.build(st)


def _printed_decimals(tab: Table, col) -> set[int]:
    """Decimals of the column's cells as the note prints them (render's own rule)."""
    from reportgen.report.render import column_decimals
    from reportgen.style.numbers import fmt
    vals = list(tab.data[col.key])
    nd = column_decimals(col, vals)
    out = set()
    for v in vals:
        text = col.fmt(v) if col.fmt else fmt(v, digits=col.digits if nd is None else nd,
                                                sig=None if (col.digits is not None or nd is not None) else col.sig)
        out.add(len(text.split(",")[1]) if "," in text else 0)
    return out


@pytest.mark.parametrize("which", ["hitch", "six_bar"])
def test_reaction_forces_one_number_of_decimals(which, hitch_forces, six_bar_forces):
    """ws002's table 3.6 printed R₀₁ₓ = 2304,0 Н and R₀₃ₓ = −6593,6 Н beside 138 350 Н and whole
    newtons in every other reaction table; ws000's group table 6912,5 Н beside 17 007 Н. Every force
    column of every reaction table of a note prints the same number of decimals."""
    sec = hitch_forces[1] if which == "hitch" else six_bar_forces
    tabs = [b for b in _blocks(sec) if isinstance(b, Table)
            and re.match(r"(Реакции в парах|Составляющие реакций|Модули реакций|Наибольшие реакции)", _plain(b.caption))]
    assert len(tabs) >= 5
    seen = set()
    for t in tabs:
        for c in t.columns:
            if c.unit == "Н":
                seen |= _printed_decimals(t, c)
    assert seen == {0}, seen
    # the normal force of a sliding pair and the actuator's force in the tables' remarks too
    notes = [str(v) for t in tabs if "extra" in t.data for v in t.data["extra"] if v]
    forces = re.findall(r"[NF]\u00a0=\u00a0([−\d\u00a0 ,]+)\u00a0Н", " ".join(notes))
    assert forces and not any("," in x for x in forces), forces


# --------------------------------------------------------------------------------------------
# 5. the Жуковский formula of an actuator with the table's (unsigned) arms
# --------------------------------------------------------------------------------------------
def test_actuator_lever_formula_uses_the_tables_arms(hitch_forces):
    """ws002 printed F(h₂ − h₁) with h₂ − h₁ = −40,0 beside a table of arms 40,0 and 0,0 мм: the
    formula now writes each printed arm with the sign of its moment, −h₂ + h₁ = −40,0 + 0,0, and the
    result is −ΣF_ih_i over that signed sum of the printed numbers."""
    from reportgen.report.document import FormulaBlock
    from reportgen.style.numbers import fmt
    st, sec = hitch_forces
    blocks = list(_blocks(sec))
    tab = next(b for b in blocks if isinstance(b, Table) and b.id == "tab-frc-lever")
    bal = tab.data[tab.data["balancing"].astype(bool)]
    forms = [f for b in blocks if isinstance(b, FormulaBlock) for f in b.formulas]
    law = next(f for f in forms if f.label == "eq-frc-lever")
    res = next(f for f in forms if f.symbolic.startswith("F^{Ж}"))
    assert "h_{2} - h_{1}" not in law.symbolic and "h_{2}" in law.symbolic and "h_{1}" in law.symbolic
    # every printed arm of the force's rows appears, unsigned, in the substitution
    den = res.substituted.split("}{", 1)[1]
    nums = re.findall(r"(-?)\s*(\d+\{,\}\d)", den.replace(" + ", " ").replace(" - ", " -"))
    printed = sorted(fmt(h, digits=1, sig=None).replace(",", "{,}") for h in bal["h"])
    assert sorted(n for _, n in nums) == printed, (den, printed)
    # the result is −Σ(±F·h) over the signed sum of the printed arms
    S = sum((-1.0 if sg else 1.0) * float(n.replace("{,}", ".")) for sg, n in nums)
    total = float(tab.data.loc[~tab.data["balancing"].astype(bool), "Fh"].sum())
    F = -total / S
    assert float(re.sub(r"[^\d.-]", "", res.result.replace("{,}", "."))) == pytest.approx(F, abs=0.5)
    # and the table's products of the force's rows are F, as printed (session 8: to the column's
    # decimals, as every row), times those signed arms
    for (sg, n), fh, Fp in zip(nums, bal["Fh"], bal["F"]):
        assert Fp == pytest.approx(abs(F), abs=0.5)
        assert fh == pytest.approx(math.copysign(Fp, F) * (-1.0 if sg else 1.0) * float(n.replace("{,}", ".")),
                                   rel=1e-12, abs=1e-9)


def test_crank_polygon_sides_apart(six_bar, captured):
    """The crank's polygon R₂₁ + R₀₁ = 0 is a side and its way back: R₀₁ was drawn on top of R₂₁;
    now beside it, so that both arrows and labels are seen."""
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import GroupForces
    from reportgen.scenes.labels import check_figure
    gi = next(i for i, g in enumerate(six_bar.forces.model.groups) if list(g.links) == ["1"])
    GroupForces(chosen_position(six_bar), gi, landscape=True).draw(six_bar)
    fig = captured[-1]
    arrows = [s for s in _arrows_mm(fig) if np.linalg.norm(s[1] - s[0]) > 2.0]
    assert len(arrows) >= 4                      # two on the scheme, two in the polygon
    for i, (a0, a1) in enumerate(arrows):
        for j, (b0, b1) in enumerate(arrows):
            if i != j:
                assert _share_near(a0, a1, b0, b1) <= 0.25, (i, j)
    assert check_figure(fig) == []


def test_hitch_initial_mechanism_arrows_apart(captured):
    """ws002's initial mechanism: R₀₁ runs back along R₄₃ and the dashed R₂₃ closes along R₀₁: the
    three are drawn side by side (R₂₃ was on top of R₀₁ with both labels stacked); the scheme's Φ₅,
    P_пс of a slider stay apart too (ws000 corrected, group (4,5))."""
    from reportgen import load_case
    from reportgen.report.sections.common import chosen_position
    from reportgen.scenes.forces import GroupForces
    from reportgen.scenes.labels import check_figure
    for case, links in (("ws002_tractor_hitch.toml", {"1", "2", "3"}), ("ws000_six_bar_corrected.toml", {"4", "5"})):
        st = load_case(CASES / case)
        gi = next(i for i, g in enumerate(st.forces.model.groups) if set(g.links) == links)
        GroupForces(chosen_position(st), gi, landscape=True).draw(st)
        fig = captured[-1]
        arrows = [s for s in _arrows_mm(fig) if np.linalg.norm(s[1] - s[0]) > 2.0]
        for i, (a0, a1) in enumerate(arrows):
            for j, (b0, b1) in enumerate(arrows):
                if i != j and np.linalg.norm(a1 - a0) <= np.linalg.norm(b1 - b0):
                    assert _share_near(a0, a1, b0, b1) <= 0.25, (case, i, j)
        assert check_figure(fig) == []
