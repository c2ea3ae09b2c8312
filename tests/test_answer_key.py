"""The teacher's answer key (`reportgen build CASE --key`): separate files, the checks all pass,
the comparison with printed values and the worksheet's errors are there and not in the note."""
import re

import numpy as np
import pytest

from conftest import CASES
from reportgen import load_case
from reportgen.cli import main
from reportgen.report.assemble import build_report
from reportgen.report.key import build_key, loop_closure
from reportgen.report.render import render_html


@pytest.fixture(scope="module")
def ws000():
    return load_case(CASES / "ws000_six_bar.toml")


@pytest.fixture(scope="module")
def key_html(ws000):
    return render_html(build_key(ws000), for_print=False)


def _ids(report):
    out = set()

    def walk(node):
        for ch in getattr(node, "children", []):
            if getattr(ch, "id", None):
                out.add(ch.id)
            walk(ch)
    for s in report.sections:
        out.add(s.id)
        walk(s)
    return out


def test_key_sections(ws000):
    ids = _ids(build_key(ws000))
    assert {"key-given", "key-results", "key-checks", "key-printed", "key-errors", "tab-dyn-printed"} <= ids


def test_printed_comparison_only_in_key(ws000):
    note_ids = _ids(build_report(ws000))
    assert "tab-dyn-printed" not in note_ids and "key-printed" not in note_ids


def test_key_checks_pass(key_html):
    text = re.sub(r"<[^>]+>", " ", key_html)
    for needle in ("Замыкание контуров", "Рычаг Жуковского", "Баланс мощностей", "Баланс энергии",
                   "Сравнение с напечатанными значениями", "Ошибки исходного расчёта", "Mathcad"):
        assert needle in text, needle
    assert "НЕ выполнена" not in text


def test_loop_closure_independent(ws000):
    # rigid links: every distance between two points of a link is constant over the cycle
    assert loop_closure(ws000) < 1e-9
    # the check detects a broken loop: shift one point of the cycle table
    cyc = ws000.cycle
    saved = cyc["x_B"].copy()
    try:
        cyc.loc[cyc.index[3], "x_B"] += 1e-3
        assert loop_closure(ws000) == pytest.approx(1e-3, rel=0.5)
    finally:
        cyc["x_B"] = saved
    assert np.isfinite(loop_closure(ws000))


def test_cli_key_files(tmp_path):
    rc = main(["build", str(CASES / "slider_crank.toml"), "-o", str(tmp_path), "--format", "html", "--key"])
    assert rc == 0
    assert (tmp_path / "slider_crank.html").exists()
    key = tmp_path / "slider_crank-key.html"
    assert key.exists()
    assert "Замыкание контуров" in key.read_text(encoding="utf-8")


@pytest.mark.parametrize("stem,kind", [("ws001_p1_dof", "dof"), ("ws001_p3_cross", "cross"),
                                       ("ws001_p6_six_bar", "synthesis"), ("ws001_p7_governor", "governor"),
                                       ("ws001_p8_press", "machine")])
def test_task_printed_values_only_in_key(stem, kind):
    # the printed-value tables of the non-linkage tasks (with the notes why the worksheet differs)
    # are in the key, one subsection per task, and nowhere in the student's note
    st = load_case(CASES / f"{stem}.toml")
    assert {"key-printed", f"key-printed-{kind}", f"tab-{kind}-printed"} <= _ids(build_key(st))
    note = render_html(build_report(st), for_print=False)
    assert "Напечатано" not in note and "Рабочий лист" not in note and "key-printed" not in note


def test_motion_printed_equation_only_in_key():
    # the worksheet's equation of motion integrated beside the correct one: key only; the note
    # writes the method in words and the case's expressions in textbook notation
    st = load_case(CASES / "ws001_p9_valve.toml")
    assert {"key-printed-motion", "fig-motion-printed"} <= _ids(build_key(st))
    note = re.sub(r"<[^>]+>", " ", render_html(build_report(st), for_print=False))
    assert "Рунге–Кутты восьмого порядка" in note and "solve_ivp" not in note and "исходном решении" not in note
    assert not re.search(r"\b(phi|omega|J_d)\b|\w+_\w+", note)
