"""Section «Маховик машины по энергии цикла»: ΔE_max (given, C_E·A, loop areas or the
turning-moment table), the speeds from δ, J = 2ΔE/(ω_max² − ω_min²) = ΔE/(δ·ω_ср²) with
numbers, or δ from a given flywheel (inverse task), the mean power (the values printed in the
source: answer key).  ``present(study)``: the case has ``[machine]``."""
from __future__ import annotations

import numpy as np
import pandas as pd

from ...scenes.machine import EnergyDiagram
from ...style.numbers import fmt, tex_num
from ..document import Column, Section, ref

NEEDS = ("machine",)
TASK = "определить момент инерции маховика и мощность двигателя по энергии рабочего цикла"


def printed_angular(key: str) -> bool:
    """Whether the printed value ``key`` is an angle (the comparison table of the answer key,
    reportgen/report/key.py: the student's note holds no printed values)."""
    return False


def present(study) -> bool:
    return study.root.has("machine")


def _t(x, unit=None, sig=5) -> str:
    return tex_num(x, sig=sig, unit=unit)


def build(study) -> Section:
    m = study.machine
    sec = Section("Маховик машины по энергии цикла", "sec-machine")
    src = {"dE": "задано непосредственно (за время операции энергию отдаёт маховик)",
           "C_E": "как произведение коэффициента колебания энергии на работу за цикл",
           "loops": "по площадям петель диаграммы движущего момента над и под линией среднего момента",
           "moment": "по диаграмме движущего момента <i>M</i>(<i>φ</i>): наибольший размах работы избыточного момента <i>M</i>&nbsp;−&nbsp;<i>M</i><sub>ср</sub>"}
    sec.paragraph(f"Наибольшее изменение кинетической энергии за цикл ΔE<sub>max</sub> найдено {src[m.source]}: "
                  f"ΔE<sub>max</sub>&nbsp;=&nbsp;{fmt(m.dE, sig=5)}&nbsp;Дж.")
    if m.source == "C_E":
        sec.formula(r"\Delta E_{max} = C_E A", None, _t(m.dE, "Дж"))
    if m.source == "loops":
        df = pd.DataFrame({"k": np.arange(1, len(m.areas) + 1), "A": m.areas, "E": m.E_run[1:]})
        sec.paragraph(f"Площади петель в порядке их следования за цикл (над линией среднего момента — со знаком «+») и "
                      f"нарастающая сумма E<sub>k</sub> = A<sub>1</sub> + … + A<sub>k</sub> (E<sub>0</sub> = 0) — в таблице "
                      f"{ref('tab-machine-loops')}; сумма площадей за цикл равна нулю.")
        sec.table("Площади петель диаграммы момента и нарастающая энергия",
                  [Column("k", "№ петли"), Column("A", "<i>A</i><sub><i>k</i></sub>", "Дж", sig=5),
                   Column("E", "<i>E</i><sub><i>k</i></sub>", "Дж", sig=5)], df, id="tab-machine-loops")
    if m.source == "moment":
        t = m.table
        sec.paragraph("Средний движущий момент за цикл (работа за цикл — точный интеграл кусочно-линейной диаграммы):")
        sec.formula(r"M_{ср} = \frac{1}{\Phi}\int_0^{\Phi} M\,d\varphi = \frac{A}{\Phi}",
                    rf"\frac{{{_t(t['work'])}}}{{{_t(t['phi'][-1] - t['phi'][0])}}}", _t(t["M_mean"], "Н·м"))
    if m.source in ("loops", "moment"):
        d = EnergyDiagram().draw(study)
        sec.figure("Изменение энергии за цикл", d.svg, d.width_mm, id="fig-machine-energy")
        sec.paragraph(f"Нарастающая работа избыточного момента показана на рисунке {ref('fig-machine-energy')}; "
                      "ΔE<sub>max</sub> — разность её наибольшего и наименьшего значений.")
    sec.paragraph("Скорости вала маховика при коэффициенте неравномерности δ "
                  "(ω<sub>ср</sub> = (ω<sub>max</sub> + ω<sub>min</sub>)/2, δ = (ω<sub>max</sub> − ω<sub>min</sub>)/ω<sub>ср</sub>):")
    sec.formula(r"\omega_{max} = \omega_{ср}(1 + \delta/2)", None, _t(m.omega_max, "рад/с"))
    sec.formula(r"\omega_{min} = \omega_{ср}(1 - \delta/2) = \omega_{max}\frac{2 - \delta}{2 + \delta}", None,
                _t(m.omega_min, "рад/с"))
    if study.root.table("machine").has("delta"):
        sec.paragraph("Из теоремы об изменении кинетической энергии между положениями наибольшей и наименьшей скорости "
                      "(½J(ω<sub>max</sub>² − ω<sub>min</sub>²) = ΔE<sub>max</sub>) момент инерции маховика:")
        sec.formula(r"J = \frac{2\Delta E_{max}}{\omega_{max}^2 - \omega_{min}^2} = \frac{\Delta E_{max}}{\delta\,\omega_{ср}^2}",
                    rf"\frac{{2 \cdot {_t(m.dE)}}}{{{_t(m.omega_max)}^2 - {_t(m.omega_min)}^2}}", _t(m.J, "кг·м²"),
                    label="eq-machine-J")
        if m.J_O > 0:
            sec.paragraph("Часть этого момента инерции дают остальные вращающиеся массы вала; момент инерции маховика:")
            sec.formula(r"J_м = J - J_O", rf"{_t(m.J)} - {_t(m.J_O)}", _t(m.J_fly, "кг·м²"))
    else:
        sec.paragraph("Задан маховик (обратная задача); коэффициент неравномерности хода:")
        sec.formula(r"\delta = \frac{\Delta E_{max}}{J\,\omega_{ср}^2}",
                    rf"\frac{{{_t(m.dE)}}}{{{_t(m.J)} \cdot {_t(m.omega_m)}^2}}", _t(m.delta, sig=4),
                    label="eq-machine-delta")
    if m.power is not None:
        sec.paragraph("Средняя мощность двигателя — работа за цикл, делённая на время цикла:")
        sec.formula(r"N = \frac{A}{t_ц}", rf"\frac{{{_t(m.work)}}}{{{_t(m.cycle_time)}}}", _t(m.power, "Вт"),
                    label="eq-machine-N")
    return sec


def conclusion_lines(study) -> list[str]:
    m = study.machine
    s = (f"Маховик по энергии цикла: ΔE<sub>max</sub>&nbsp;=&nbsp;{fmt(m.dE, sig=4)}&nbsp;Дж, "
         f"δ&nbsp;=&nbsp;{fmt(m.delta, sig=4)}, J&nbsp;=&nbsp;{fmt(m.J, sig=4)}&nbsp;кг·м²")
    if m.power is not None:
        s += f", мощность N&nbsp;=&nbsp;{fmt(m.power, sig=4)}&nbsp;Вт"
    return [s + "."]
