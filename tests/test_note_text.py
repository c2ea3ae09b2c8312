"""The student's note reads as a student's text: Russian agreement, textbook symbols, no program
or worksheet identifiers, positions by number, no page left short without a reason."""
import re
import subprocess

import pytest

from conftest import CASES
from pagefill import pages, short_pages
from reportgen.cli import main
from reportgen.report.russian import (condition_text, param_symbol, param_title, plural, plural_form,
                                      position_names)

NOUN = ("уравнение", "уравнения", "уравнений")


@pytest.mark.parametrize("n, text", [(1, "1 уравнение"), (3, "3 уравнения"), (5, "5 уравнений"),
                                     (11, "11 уравнений"), (12, "12 уравнений"), (21, "21 уравнение"),
                                     (22, "22 уравнения"), (25, "25 уравнений"), (0, "0 уравнений"),
                                     (111, "111 уравнений"), (104, "104 уравнения")])
def test_plural(n, text):
    assert plural(n, *NOUN).replace("\u00a0", " ") == text


def test_plural_form_every_ending():
    # cross-check against the rule written differently: by the last two digits
    for n in range(0, 250):
        last2, last = n % 100, n % 10
        want = NOUN[2] if 11 <= last2 <= 19 else NOUN[0] if last == 1 else NOUN[1] if last in (2, 3, 4) else NOUN[2]
        assert plural_form(n, *NOUN) == want, n


@pytest.mark.parametrize("name, html, title", [
    ("l_AB", "<i>l</i><sub>AB</sub>", "длина AB"),
    ("L34", "<i>l</i><sub>34</sub>", "длина 34"),
    ("X_C", "<i>x</i><sub>C</sub>", "координата по оси x точки C"),
    ("YP56", "<i>y</i><sub>P56</sub>", "координата по оси y точки P56"),
    ("phiBD", "<i>φ</i><sub>BD</sub>", "угол BD"),
    ("phi_P6", "<i>φ</i><sub>P6</sub>", "угол P6"),
    ("S_min", "<i>S</i><sub>min</sub>", "ход (длина) ведущего звена, наименьшее значение"),
])
def test_parameter_symbol_and_name(name, html, title):
    assert str(param_symbol(name)) == html
    assert param_title(name) == title


def test_parameter_symbol_escapes_case_text():
    assert "<script>" not in str(param_symbol("a_<script>"))


def test_condition_in_words():
    assert condition_text("vqx_H >= 0") == "при движении точки H в положительном направлении оси x"
    assert condition_text("vqy_B < 0") == "при движении точки B в отрицательном направлении оси y"
    assert "_" not in condition_text("phi_3 >= 1")


def test_positions_by_number():
    assert position_names(["0", "1", "11", "f"]) == {"0": "0", "1": "1", "11": "11", "f": "12"}


# --------------------------------------------------------------------------------------------
# the whole note of worksheet 000 (the default case of `make report`)
# --------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def note(tmp_path_factory):
    out = tmp_path_factory.mktemp("note")
    assert main(["build", str(CASES / "ws000_six_bar_corrected.toml"), "-o", str(out), "--format", "pdf"]) == 0
    pdf = out / "ws000_six_bar_corrected.pdf"
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True,
                          check=True).stdout
    return pdf, text


def test_no_program_or_worksheet_identifiers(note):
    _, text = note
    assert not re.findall(r"\b\w+_\w+\b", text)
    assert not re.search(r"\b(phi|omega|eps)\w*", text, re.I)
    for bad in ("as printed", "лист", "сетк", "Mathcad", "Совпадает", "напечатанн", "исходном расчёте"):
        assert bad not in text, bad
    assert not re.search(r"положени[еяю] f\b", text)


def test_agreement_in_sentences(note):
    _, text = note
    flat = re.sub(r"\s+", " ", text.replace("\u00a0", " ").replace("‐ ", ""))
    for n, word in re.findall(r"\b(\d+) (уравнени\w*)", flat):
        assert word == plural_form(int(n), *NOUN), (n, word)
    assert "Наибольший по модулю усилие" not in flat
    # ws000 has neither a stone in a slot nor a cylinder–rod pair
    for bad in ("Кориолис", "камн", "цилиндр–шток"):
        assert bad not in flat, bad


def test_balancing_moment_compared_with_dynamics(note):
    _, text = note
    flat = re.sub(r"\s+", " ", text)
    assert "Уравновешивающий момент переменен по положениям" in flat
    assert "истинному закону движения" in flat


def test_page_fill(note):
    pdf, _ = note
    assert short_pages(pdf) == []
    # the signature lines of the assignment are on the assignment's page, never alone
    for p in pages(pdf):
        if "исполнению" in p["text"]:
            assert "ЗАДАНИЕ" in p["text"]


UNIT = r"(?:Н·м|Н·мм|кг·м²|кг|мм|м/с²?|м|Н|рад/с²?|об/мин|Дж|Вт|МПа|Па)"


def test_no_line_break_inside_a_number_unit_pair(note):
    """Units are never split from their number or inside themselves («Н·|м», «12,5|Н·м»)."""
    _, text = note
    lines = [ln.strip() for ln in text.splitlines()]
    for prev, nxt in zip(lines, lines[1:]):
        assert not prev.endswith("·"), prev
        if re.search(r"\d$", prev):
            assert not re.match(UNIT + r"(?![\wа-яё])", nxt), (prev, nxt)
    # initials stay with the surname
    assert not re.search(r"\b[А-ЯЁ]\.\s*\n", text.replace("Рис.", ""))
