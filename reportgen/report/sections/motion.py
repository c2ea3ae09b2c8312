"""Section «Уравнение движения машины во времени»: J_пр(φ), J_пр′(φ), M_пр(φ, φ̇, t) as given,
Lagrange's equation J_пр φ̈ + ½J_пр′φ̇² = M_пр, its numerical integration (solve_ivp, DOP853)
with φ(t), ω(t), and the source's printed equation integrated beside it.
``present(study)``: the case has ``[motion]``."""
from __future__ import annotations

import numpy as np
import pandas as pd
from markupsafe import Markup

from ...scenes.motion import MotionHistory
from ...style.numbers import fmt
from ..document import Column, Section, ref

NEEDS = ("motion",)
TASK = "составить дифференциальное уравнение движения машины и проинтегрировать его во времени"

_EQ = r"J_{пр}(\varphi)\,\ddot\varphi + \frac{1}{2}\,\frac{dJ_{пр}}{d\varphi}\,\dot\varphi^2 = M_{пр}(\varphi, \dot\varphi, t)"


def present(study) -> bool:
    return study.root.has("motion")


def _code(text: str) -> Markup:
    return Markup("<code>{}</code>").format(text)


def build(study) -> Section:
    mo = study.motion
    sec = Section("Уравнение движения машины во времени", "sec-motion")
    sec.paragraph(Markup("Приведённый момент инерции (кинетическая энергия T = ½J<sub>пр</sub>φ̇²), его производная "
                         "и приведённый момент заданы выражениями: J<sub>пр</sub>(φ) = {}, "
                         "dJ<sub>пр</sub>/dφ = {}, M<sub>пр</sub> = {} (φ̇ обозначена omega). Производная "
                         "проверена центральной разностью: расхождение {} кг·м².").format(
        _code(mo.texts["J"]), _code(mo.texts["dJ"]), _code(mo.texts["M"]), fmt(mo.dJ_check, sig=2)))
    sec.paragraph("По теореме об изменении кинетической энергии в дифференциальной форме dT/dt = ΣN "
                  "(уравнение Лагранжа второго рода) после сокращения на φ̇:")
    sec.formula(_EQ, label="eq-motion")
    d = MotionHistory().draw(study)
    sec.paragraph(f"Уравнение проинтегрировано численно (scipy solve_ivp, метод DOP853, относительная точность "
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
    if mo.texts["printed_eps"]:
        sec.paragraph(Markup(
            "Уравнение, напечатанное в исходном решении, разрешённое относительно φ̈: {}. {} "
            "Интегрирование напечатанного уравнения (штриховые линии на "
            "рисунке {}) расходится с верным решением: наибольшая разность углов {}°, к t = {} с "
            "φ = {}° против {}°.").format(
            _code(mo.texts["printed_eps"]), mo.texts["printed_note"] or "", Markup(ref("fig-motion")),
            fmt(np.degrees(mo.scalars["motion_max_dphi_printed"]), sig=4), fmt(mo.t_end, sig=3),
            fmt(np.degrees(mo.scalars["motion_phi_end_printed"]), sig=4),
            fmt(np.degrees(mo.scalars["motion_phi_end"]), sig=4)))
    return sec


def conclusion_lines(study) -> list[str]:
    s = study.motion.scalars
    return [f"Уравнение движения проинтегрировано до t&nbsp;=&nbsp;{fmt(s['motion_t_end'], sig=3)}&nbsp;с: "
            f"ω изменяется от {fmt(s['motion_omega_min'], sig=4)} до {fmt(s['motion_omega_max'], sig=4)}&nbsp;рад/с."]
