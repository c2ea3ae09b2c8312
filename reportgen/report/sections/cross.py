"""Section «Скорости механизма с крестовиной и приведённая сила»: the plan of velocities in closed
form (v_B3, v_B3B2, ω₃ = ω₅, v_C3, v_C5, v_C4 = v_C3 + v_C5 and its check as C runs on the Thales
circle), the force reduced to the input link by equal powers; the printed values are compared in the answer key.
``present``: ``[cross]``."""
from __future__ import annotations

import math

from ...scenes.cross import CrossScheme
from ...style.numbers import fmt, tex_num
from ..document import Section, ref

NEEDS = ("cross",)
TASK = "определить скорости механизма с крестовиной и приведённую силу"


def printed_angular(key: str) -> bool:
    """Whether the printed value ``key`` is an angle (the comparison table of the answer key,
    reportgen/report/key.py: the student's note holds no printed values)."""
    return False


def present(study) -> bool:
    return study.root.has("cross")


def _t(x, unit=None, sig=4) -> str:
    return tex_num(x, sig=sig, unit=unit)


def build(study) -> Section:
    cx = study.cross
    r, i = cx.r, cx.inputs
    sec = Section("Скорости механизма с крестовиной и приведённая сила", "sec-cross")
    gdeg, adeg = math.degrees(i["gamma"]), math.degrees(i["alpha"])
    sec.paragraph("Звено 1 движется поступательно: V<sub>B2</sub> = V<sub>A</sub>. Точка B звена 3: "
                  "V<sub>B3</sub> = V<sub>B2</sub> + V<sub>B3B2</sub>, V<sub>B3</sub> ⊥ O₁B, V<sub>B3B2</sub> ∥ O₁B; "
                  f"скорость звена 1 составляет с O₁B угол γ = {fmt(gdeg, sig=4)}°:")
    sec.formula(r"V_{B3} = V_A \sin\gamma", rf"{_t(i['v_A'])} \cdot \sin {_t(gdeg)}^\circ", _t(r["v_B3"], "м/с"))
    sec.formula(r"V_{B3B2} = V_A |\cos\gamma|", None, _t(r["v_B3B2"], "м/с"))
    sec.formula(r"\omega_3 = \frac{V_{B3}}{l_{O_1B}}", rf"\frac{{{_t(r['v_B3'])}}}{{{_t(i['l_O1B'])}}}",
                _t(abs(r["w3"]), "рад/с"))
    sec.paragraph("Пазы крестовины 4 взаимно перпендикулярны, поэтому O₁C ⊥ O₂C: точка C лежит на окружности "
                  f"с диаметром O₁O₂, угол при O₁ α = {fmt(adeg, sig=4)}°, и прямой угол при C сохраняется — звено 5 "
                  "поворачивается с той же угловой скоростью, что и звено 3:")
    sec.formula(r"l_{O_1C} = l_{O_1O_2}\cos\alpha,\quad l_{O_2C} = l_{O_1O_2}\sin\alpha", None,
                rf"{_t(r['l_O1C'])},\ {_t(r['l_O2C'])}\ \text{{м}}")
    sec.formula(r"V_{C3} = \omega_3 l_{O_1C},\quad V_{C5} = \omega_5 l_{O_2C},\quad \omega_5 = \omega_3", None,
                rf"{_t(r['v_C3'])},\ {_t(r['v_C5'])}\ \text{{м/с}}")
    sec.paragraph("Из систем V<sub>C4</sub> = V<sub>C3</sub> + V<sub>C4C3</sub> (V<sub>C4C3</sub> ∥ O₁C) и "
                  "V<sub>C4</sub> = V<sub>C5</sub> + V<sub>C4C5</sub> (V<sub>C4C5</sub> ∥ O₂C) при O₁C ⊥ O₂C "
                  "вектор V<sub>C4</sub> — диагональ прямоугольника на V<sub>C3</sub> и V<sub>C5</sub>; проверка: "
                  "C движется по окружности радиуса l<sub>O₁O₂</sub>/2 с угловой скоростью 2ω₃:")
    sec.formula(r"V_{C4} = \sqrt{V_{C3}^2 + V_{C5}^2} = \omega_3 l_{O_1O_2}",
                rf"\sqrt{{{_t(r['v_C3'])}^2 + {_t(r['v_C5'])}^2}}", _t(r["v_C4"], "м/с"), label="eq-cross-vc4")
    d = CrossScheme().draw(study)
    sec.figure("Схема механизма с крестовиной и план скоростей", d.svg, d.width_mm, id="fig-cross")
    sec.paragraph(f"Схема и план скоростей показаны на рисунке {ref('fig-cross')}.")
    if i["M"]:
        sec.paragraph("Приведённая к звену 1 сила от момента M на валу O₂ — из равенства мощностей:")
        sec.formula(r"F_{пр} = \frac{M \omega_5}{V_A}", rf"\frac{{{_t(i['M'])} \cdot {_t(abs(r['w5']))}}}{{{_t(i['v_A'])}}}",
                    _t(r["F_red"], "Н"), label="eq-cross-F")
    return sec


def conclusion_lines(study) -> list[str]:
    r = study.cross.r
    s = f"Механизм с крестовиной: V<sub>C4</sub>&nbsp;=&nbsp;{fmt(r['v_C4'], sig=4)}&nbsp;м/с"
    if study.cross.inputs["M"]:
        s += f", приведённая сила F<sub>пр</sub>&nbsp;=&nbsp;{fmt(r['F_red'], sig=4)}&nbsp;Н"
    return [s + "."]
