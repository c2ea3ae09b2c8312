"""Section «Уравнение движения машины во времени»: J_пр(φ), J_пр′(φ), M_пр(φ, φ̇, t) as given,
Lagrange's equation J_пр φ̈ + ½J_пр′φ̇² = M_пр, its numerical integration (explicit Runge–Kutta
of order 8, Dormand–Prince, as the analysis integrates it) with φ(t), ω(t); the case's expressions
in textbook notation.  The source's printed equation integrated beside it goes to the answer key
(:func:`key_printed`).
``present(study)``: the case has ``[motion]``."""
from __future__ import annotations

import numpy as np
from markupsafe import Markup

from ...scenes.motion import MotionHistory
from ...style.numbers import fmt
from ..document import Column, Section, ref
from ..russian import expr_html

NEEDS = ("motion",)
TASK = "составить дифференциальное уравнение движения машины и проинтегрировать его во времени"

_EQ = r"J_{пр}(\varphi)\,\ddot\varphi + \frac{1}{2}\,\frac{dJ_{пр}}{d\varphi}\,\dot\varphi^2 = M_{пр}(\varphi, \dot\varphi, t)"


def present(study) -> bool:
    return study.root.has("motion")


def build(study) -> Section:
    mo = study.motion
    sec = Section("Уравнение движения машины во времени", "sec-motion")
    sec.paragraph(Markup("Приведённый момент инерции (кинетическая энергия T = ½J<sub>пр</sub>φ̇²), его производная "
                         "и приведённый момент заданы выражениями: J<sub>пр</sub>(φ) = {}, "
                         "dJ<sub>пр</sub>/dφ = {}, M<sub>пр</sub> = {} (ω = φ̇). Производная "
                         "проверена центральной разностью: расхождение {} кг·м².").format(
        expr_html(mo.texts["J"]), expr_html(mo.texts["dJ"]), expr_html(mo.texts["M"]), fmt(mo.dJ_check, sig=2)))
    sec.paragraph("По теореме об изменении кинетической энергии в дифференциальной форме dT/dt = ΣN "
                  "(уравнение Лагранжа второго рода) после сокращения на φ̇:")
    sec.formula(_EQ, label="eq-motion")
    d = MotionHistory().draw(study)
    sec.paragraph(f"Уравнение движения, записанное как система двух уравнений первого порядка dφ/dt = ω, "
                  f"dω/dt = (M<sub>пр</sub> − ½J′<sub>пр</sub>ω²)/J<sub>пр</sub>, проинтегрировано численно явным "
                  f"методом Рунге–Кутты восьмого порядка (метод Дорманда–Принса) с автоматическим выбором шага "
                  f"по оценке локальной погрешности (относительная погрешность шага не более "
                  f"{fmt(mo.rtol, sig=2)}) от φ = {fmt(np.degrees(mo.phi0), sig=4)}°, "
                  f"φ̇ = {fmt(mo.omega0, sig=4)} рад/с до t = {fmt(mo.t_end, sig=4)} с (рисунок {ref('fig-motion')}).")
    sec.figure("Закон движения φ(t), ω(t)", d.svg, d.width_mm, id="fig-motion")
    h = mo.history
    idx = np.unique(np.linspace(0, len(h) - 1, 11).round().astype(int))
    tab = h.iloc[idx].copy()
    tab["phi_deg"] = np.degrees(tab["phi"])
    cols = [Column("t", "<i>t</i>", "с", sig=4), Column("phi_deg", "φ", "град", sig=5),
            Column("omega", "ω", "рад/с", sig=5), Column("eps", "ε", "рад/с²", sig=5),
            Column("J", "<i>J</i><sub>пр</sub>", "кг·м²", sig=5), Column("M", "<i>M</i><sub>пр</sub>", "Н·м", sig=5)]
    sec.table("Закон движения", cols, tab, id="tab-motion")
    return sec


def key_printed(sec: Section, study) -> None:
    """For the answer key: the equation printed in the source, integrated beside the correct one
    (the figure with both laws of motion), and how far it drifts."""
    mo = study.motion
    if not mo.texts["printed_eps"]:
        return
    d = MotionHistory().draw(study, printed=True)
    sec.figure("Закон движения по верному уравнению и по уравнению исходного решения (штриховые линии)",
               d.svg, d.width_mm, id="fig-motion-printed")
    sec.paragraph(Markup(
        "Уравнение, напечатанное в исходном решении, разрешённое относительно φ̈: {}. {} "
        "Интегрирование напечатанного уравнения (штриховые линии на "
        "рисунке {}) расходится с верным решением: наибольшая разность углов {}°, к t = {} с "
        "φ = {}° против {}°.").format(
        expr_html(mo.texts["printed_eps"]), mo.texts["printed_note"] or "", Markup(ref("fig-motion-printed")),
        fmt(np.degrees(mo.scalars["motion_max_dphi_printed"]), sig=4), fmt(mo.t_end, sig=3),
        fmt(np.degrees(mo.scalars["motion_phi_end_printed"]), sig=4),
        fmt(np.degrees(mo.scalars["motion_phi_end"]), sig=4)))


def conclusion_lines(study) -> list[str]:
    s = study.motion.scalars
    return [f"Уравнение движения проинтегрировано до t&nbsp;=&nbsp;{fmt(s['motion_t_end'], sig=3)}&nbsp;с: "
            f"ω изменяется от {fmt(s['motion_omega_min'], sig=4)} до {fmt(s['motion_omega_max'], sig=4)}&nbsp;рад/с."]
