"""Page, contents and text defects of the note (issue #9, session 9).

* СОДЕРЖАНИЕ: a long title wraps, its leader dots and page number stay on its last line (ГОСТ 7.32),
  never alone on a line of their own — in both layouts (one document; in parts, numbers as text);
* §2.4: each plan follows the text that reads it and is named there («рисунок N»), so that the text
  after a plan on a landscape page of its own can fill the page before it (ws000's velocity plan);
* a group's force drawing that fits the portrait text width at the enlarged scales stays on the
  portrait page (the screen shaker's initial mechanism took a landscape page of its own);
* Мерцалов: the extremes of ΔT_I with their positions, both negative said so, and the range
  ΔT_I нб = ΔT_I max − ΔT_I min that J_I uses, checked against the study's own ΔT_I(φ)."""
from __future__ import annotations

import functools
import re
import subprocess

import pytest
from conftest import CASES
from markupsafe import Markup

from notehelpers import blocks, plain


@functools.lru_cache(maxsize=None)
def _study(stem: str):
    from reportgen import load_case
    return load_case(CASES / f"{stem}.toml")


# ------------------------------------------------------------------ СОДЕРЖАНИЕ
def test_last_word_splits_outside_elements_and_escapes_text():
    from reportgen.report.render import last_word
    assert last_word(Markup("Реакции в парах (положение\u00a012)")) == ("Реакции в парах ", "(положение\u00a012)")
    assert last_word(Markup("ВВЕДЕНИЕ")) == ("", "ВВЕДЕНИЕ")
    # a space inside an element is not a place to cut: the element stays whole
    assert last_word(Markup("План для <i>φ = 30</i>")) == ("План для ", "<i>φ = 30</i>")
    assert last_word(Markup("Пара <i>A</i> и <sub>x y</sub>")) == ("Пара <i>A</i> и ", "<sub>x y</sub>")
    assert last_word(Markup("x<br> y")) == ("x<br> ", "y")
    head, tail = last_word("a <b> c")                # plain text is escaped, never trusted as HTML
    assert head == Markup("a &lt;b&gt; ") and tail == Markup("c")


# titles whose last line ends at every width near the right edge: some leave no room for the dots
LONG = "Реакции в кинематических парах по группам Ассура (положение"


def _toc_report():
    from reportgen.report.document import Report, Section
    sections = []
    for k in range(2):
        sec = Section(f"Раздел {k + 1}", f"s{k}")
        for n in range(6):
            sub = sec.subsection(f"{LONG} {'ж' * (6 * k + n + 1)})", f"s{k}-{n}")
            sub.paragraph("Текст подраздела.")
        sections.append(sec)
    return Report(meta={"topic": "Содержание"}, assignment=[], introduction=[], sections=sections,
                  conclusion=[], references=[])


def _toc_lines(pdf) -> list[str]:
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True,
                          check=True).stdout
    page = next(p for p in text.split("\f") if "СОДЕРЖАНИЕ" in p)
    lines = [ln.strip() for ln in page.splitlines() if ln.strip()]
    return lines[1:-1]           # without the heading and the page number


@pytest.mark.parametrize("parts", ["0", "1"])
def test_contents_number_stays_on_the_titles_last_line(tmp_path, monkeypatch, parts):
    from reportgen.report import parallel, render
    monkeypatch.setenv("REPORTGEN_PARTS", parts)
    parallel.set_note_jobs(1)
    try:
        pdf = render.write_pdf(_toc_report(), tmp_path / "toc.pdf")
    finally:
        parallel.set_note_jobs(None)
    lines = _toc_lines(pdf)
    numbered = [ln for ln in lines if re.search(r"\d+$", ln) and "." in ln]
    assert len(numbered) == 2 + 2 * 6, lines
    for ln in numbered:
        # the number ends a line that also holds the end of the title, after the leader dots
        assert re.fullmatch(r".*[\wА-Яа-яё)]\s*\.+\s*\d+", ln), ln
    assert sum(1 for ln in lines if LONG[:20] in ln) == 2 * 6
    # some titles wrapped (the case the rule is for): a title line with no number of its own
    assert any(not re.search(r"\.\s*\d+$", ln) for ln in lines)


# ------------------------------------------------------------------ §2.4 plans after their text
@pytest.mark.parametrize("stem", ["ws000_six_bar", "ws004_slotted_lever"])
def test_each_plan_follows_the_text_that_reads_it(stem):
    from reportgen.report.document import Figure, FormulaBlock, Paragraph
    from reportgen.report.sections import kinematics
    sec = kinematics.build(_study(stem))
    plans = next(s for s in sec.children if getattr(s, "id", None) == "sec-plans")
    items = list(blocks(plans))
    at = {getattr(b, "id", None): i for i, b in enumerate(items) if isinstance(b, Figure)}
    paras = [(i, plain(b.html)) for i, b in enumerate(items) if isinstance(b, Paragraph)]
    first_acc = next(i for i, t in paras if t.startswith("Ускорения,"))
    # the velocity plan after the ω read off it, before the acceleration equations
    omega = next(i for i, t in paras if t.startswith("По отрезкам плана скоростей"))
    assert omega < at["fig-vplan"] < first_acc
    assert all(isinstance(items[j], FormulaBlock) for j in range(omega + 1, at["fig-vplan"]))
    eps = next(i for i, t in paras if t.startswith("По отрезкам плана ускорений"))
    assert first_acc < eps < at["fig-aplan"]
    # each named in the text before it (ГОСТ 7.32: a figure after its first mention)
    for fid in ("fig-vplan", "fig-aplan"):
        mention = next(i for i, b in enumerate(items) if isinstance(b, Paragraph) and f'href="#{fid}"' in str(b.html))
        assert mention < at[fid]


# ------------------------------------------------------------------ group force drawings: page orientation
def _force_label(st) -> str:
    from reportgen.report.sections.common import chosen_position
    lab = chosen_position(st)
    return lab if lab in st.forces.labels else st.forces.labels[1]


@pytest.mark.parametrize("stem, gi", [("screen_shaker", 2), ("ws000_six_bar", 2)])
def test_small_group_drawing_stays_on_the_portrait_page(stem, gi):
    """The initial mechanism of the screen shaker (and of ws000): at the scales a landscape page
    would give it, it still fits the portrait text width: drawn there, no landscape page."""
    from reportgen.scenes.forces import PORTRAIT_W, GroupForces
    st = _study(stem)
    lab = _force_label(st)
    note = GroupForces(lab, gi, landscape=True).draw(st)
    assert not note.landscape
    assert note.width_mm <= PORTRAIT_W
    # not smaller than the drawing made for the portrait page alone: its polygon at least as large
    alone = GroupForces(lab, gi).draw(st)
    assert note.mu_F <= alone.mu_F * (1 + 1e-9)


@pytest.mark.parametrize("stem", ["ws002_tractor_hitch", "yoke_pump"])
def test_a_landscape_group_drawing_needs_the_landscape_width(stem):
    from reportgen.scenes.forces import PORTRAIT_W, GroupForces
    st = _study(stem)
    lab = _force_label(st)
    wide = [d for d in (GroupForces(lab, gi, landscape=True).draw(st) for gi in range(len(st.forces.model.groups)))
            if d.landscape]
    assert wide                                   # the cases still have wide drawings
    assert all(d.width_mm > PORTRAIT_W for d in wide)


# ------------------------------------------------------------------ Мерцалов: extremes, signs, range
def _tex_value(tex: str) -> float:
    """The number of a printed TeX value («-0{,}3353 \\text{ Дж}», «\\left(-6849{,}3\\right)»)."""
    t = tex.replace("{,}", ".").replace("\\left(", "").replace("\\right)", "").replace("−", "-")
    return float(re.search(r"-?\d+(?:\.\d+)?", t).group(0))


@pytest.mark.parametrize("stem", ["screen_shaker", "ws000_six_bar"])
def test_mertsalov_extremes_signs_and_range(stem):
    from reportgen.report.document import FormulaBlock, Paragraph
    from reportgen.report.sections import dynamics
    st = _study(stem)
    me = st.dynamics.result.mertsalov
    # independent of the refined extremes: ΔT_I on the grid from ΔT and T_II of the table
    tab = st.dynamics.table
    grid = tab["A_sum"].to_numpy() - tab["T_II"].to_numpy()
    assert grid.max() <= me.dT_I_max + 1e-9 * abs(me.dT_I_max) + 1e-9
    assert grid.min() >= me.dT_I_min - 1e-9 * abs(me.dT_I_min) - 1e-9
    assert me.dT_I_max == pytest.approx(float(me.dT_I.max()), rel=1e-3, abs=1e-6)
    assert me.dT_I_min == pytest.approx(float(me.dT_I.min()), rel=1e-3, abs=1e-6)
    # the start of the cycle: ΔT = 0, so ΔT_I = −T_II ≤ 0 and the minimum is never positive
    assert me.dT_I_min <= 0.0
    sec = dynamics.build(st)
    fly = next(s for s in sec.children if getattr(s, "id", None) == "sec-dyn-flywheel")
    items = list(blocks(fly))
    lead = next(i for i, b in enumerate(items) if isinstance(b, Paragraph) and plain(b.html).startswith("Экстремумы"))
    text = plain(items[lead].html)
    assert ("оба значения отрицательны" in text) == (me.dT_I_max < 0)
    for q in (me.phi_dT_max, me.phi_dT_min):
        assert dynamics._phase_deg(st, q) in text
    block = items[lead + 1]
    assert isinstance(block, FormulaBlock)
    f_max, f_min, f_rng, f_J = block.formulas
    assert "max" in f_max.symbolic and "min" in f_min.symbolic and r"\text{нб}" in f_rng.symbolic
    printed_max, printed_min, printed_rng = (_tex_value(f.result) for f in (f_max, f_min, f_rng))
    assert (printed_max < 0) == (me.dT_I_max < 0)
    # the range printed is the difference of the printed extremes (to the last printed digit)
    assert printed_rng == pytest.approx(printed_max - printed_min, rel=2e-4)
    assert printed_rng == pytest.approx(me.dT_I_max - me.dT_I_min, rel=1e-4)
    # J_I = ΔT_I нб / (ω² δ) with the range that was printed
    st_d = st.dynamics.settings
    assert _tex_value(f_J.result) == pytest.approx(printed_rng / (st_d.omega_m ** 2 * st_d.delta), rel=1e-3)


# ------------------------------------------------------------------ every figure named before it
@pytest.mark.parametrize("stem, name", [("ws002_tractor_hitch", "forces"), ("ws002_tractor_hitch", "kinematics"),
                                        ("screen_shaker", "dynamics"), ("gear_pair_shifted", "gears"),
                                        ("ws001_p7_governor", "governor")])
def test_every_figure_is_named_in_the_text_before_it(stem, name):
    """ГОСТ 7.32: every figure is referred to in the text, and stands after the text that first
    names it (the analogs' curves, the flywheel drawing, the sliding diagrams were named nowhere;
    the capacity and axle curves and the governor's construction were named after them)."""
    import importlib
    from reportgen.report.document import Figure, Paragraph
    sec = importlib.import_module(f"reportgen.report.sections.{name}").build(_study(stem))
    items = list(blocks(sec))
    figures = [(i, b.id) for i, b in enumerate(items) if isinstance(b, Figure)]
    assert figures
    for i, fid in figures:
        named = [j for j, b in enumerate(items) if isinstance(b, Paragraph) and f'href="#{fid}"' in str(b.html)]
        assert named and named[0] < i, fid
