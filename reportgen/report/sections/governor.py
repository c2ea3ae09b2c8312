"""Section «Центробежный регулятор с трением в шарнирах»: friction circle ρ = r·sin φ_тр, the rod's
line of action turned by α (sin α = 2ρ/l), the sleeve's force triangle, the arm's moment equation
about H with the friction circle solved exactly for F_и, ω; the frictionless and slowing-down
speeds beside it; the values the worksheet measured: answer key.  ``present``: ``[governor]``."""
from __future__ import annotations

import math

from ...scenes.governor import GovernorScheme
from ...style.numbers import fmt, tex_num
from ..document import Section, ref

NEEDS = ("governor",)
TASK = "определить угловую скорость центробежного регулятора с учётом трения в шарнирах"


def printed_angular(key: str) -> bool:
    """Whether the printed value ``key`` is an angle (the comparison table of the answer key,
    reportgen/report/key.py: the student's note holds no printed values)."""
    return key in ("alpha", "R76_angle", "phi_f")


def present(study) -> bool:
    return study.root.has("governor")


def _t(x, unit=None, sig=5) -> str:
    return tex_num(x, sig=sig, unit=unit)


def build(study) -> Section:
    gv = study.governor
    r = gv.main
    sec = Section("Центробежный регулятор с трением в шарнирах", "sec-governor")
    up = gv.speeding == "up"
    bf = gv.geo["F"] - gv.geo["B"]
    beta = math.degrees(math.atan2(abs(bf[0]), abs(bf[1])))                      # the rod from the vertical
    tilt = math.degrees(math.atan2(abs(r["R23"][0]), abs(r["R23"][1]))) - beta   # ±α
    sec.paragraph("Регулятор рассматривается в системе отсчёта, вращающейся с валом; скорость меняется медленно, "
                  "поэтому к шару прикладывается только центробежная сила инерции F<sub>и</sub> = m·x<sub>D</sub>·ω² "
                  "(принцип Даламбера). Реакция во вращательной паре с трением касается круга трения и "
                  "направлена так, что её момент относительно центра шарнира противодействует относительному "
                  "повороту звеньев; относительные угловые скорости найдены из плана скоростей половины механизма "
                  + ("при разгоне (рычаг отходит от оси, муфта поднимается)." if up else
                     "при торможении (рычаг приближается к оси, муфта опускается)."))
    sec.formula(r"\rho = r \sin\varphi_{тр} = \frac{d}{2}\,\frac{f}{\sqrt{1 + f^2}}",
                rf"\frac{{{_t(gv.d, sig=4)}}}{{2}} \cdot \frac{{{_t(gv.f, sig=4)}}}{{\sqrt{{1 + {_t(gv.f, sig=4)}^2}}}}", _t(gv.rho, "м", 4))
    sec.paragraph("Невесомая тяга BF нагружена двумя силами; их общая линия действия касается кругов трения "
                  "в B и F с разных сторон и повёрнута относительно BF на угол α:")
    sec.formula(r"\alpha = \arcsin\frac{2\rho}{l_{BF}}", rf"\arcsin\frac{{2 \cdot {_t(gv.rho, sig=4)}}}{{{_t(gv.inputs['l_BF'], sig=4)}}}",
                rf"{_t(math.degrees(r['alpha']), sig=4)}^\circ")
    sec.paragraph("Муфта находится в равновесии под действием веса Q = m₂g и двух симметричных реакций тяг; "
                  "вертикальная составляющая каждой равна Q/2 (β — угол тяги BF с вертикалью, знак при α — "
                  "по стороне кругов трения):")
    sec.formula(r"R_{32} = \frac{Q}{2\cos(\beta \pm \alpha)}",
                rf"\frac{{{_t(gv.Q, sig=4)}}}{{2\cos({_t(beta, sig=4)}^\circ {'+' if tilt >= 0 else '-'} {_t(abs(tilt), sig=4)}^\circ)}}", _t(r["R"], "Н"))
    sec.paragraph(f"На рычаг действуют R<sub>36</sub>, вес шара G, сила инерции F<sub>и</sub> и реакция "
                  f"R<sub>76</sub> в шарнире H, касательная к его кругу трения. Уравнение моментов относительно H "
                  f"(A — момент известных сил с моментом трения в F, B = l<sub>HD</sub>·cos θ — плечо силы инерции) "
                  f"вместе с |R<sub>76</sub>| = |P + F<sub>и</sub>| сводится к квадратному уравнению для F<sub>и</sub>; "
                  f"P = G + R<sub>36</sub> = {fmt(math.hypot(*r['P']), sig=4)}&nbsp;Н:")
    sec.formula(r"A + B F_и = \rho\,\sqrt{(P_x + F_и)^2 + P_y^2}", None, _t(r["F_i"], "Н"))
    sec.formula(r"\omega = \sqrt{\frac{F_и}{m\,x_D}}", rf"\sqrt{{\frac{{{_t(r['F_i'])}}}{{{_t(gv.m, sig=4)} \cdot {_t(r['r_D'], sig=4)}}}}}",
                _t(r["omega"], "рад/с", 4), label="eq-governor-omega")
    d = GovernorScheme().draw(study)
    sec.paragraph(f"Построение показано на рисунке {ref('fig-governor')}: линия действия R<sub>76</sub> проходит "
                  f"через точку K пересечения линий P и F<sub>и</sub> (теорема о трёх силах) и наклонена к "
                  f"горизонту под углом {fmt(math.degrees(r['R76_angle']), sig=4)}°. Без трения ω<sub>0</sub> = "
                  f"{fmt(gv.cases[0]['omega'], sig=4)}&nbsp;рад/с; муфта неподвижна при "
                  f"{fmt(gv.cases[-1]['omega'], sig=4)} ≤ ω ≤ {fmt(gv.cases[1]['omega'], sig=4)}&nbsp;рад/с "
                  "(зона нечувствительности регулятора).")
    # (after the text that first names it, ГОСТ 7.32)
    sec.figure("Регулятор с кругами трения и линиями действия реакций; планы сил муфты и рычага",
               d.svg, d.width_mm, id="fig-governor")
    return sec


def conclusion_lines(study) -> list[str]:
    gv = study.governor
    return [f"Центробежный регулятор с трением в шарнирах: ω&nbsp;=&nbsp;{fmt(gv.main['omega'], sig=4)}&nbsp;рад/с "
            f"({'разгон' if gv.speeding == 'up' else 'торможение'}); без трения {fmt(gv.cases[0]['omega'], sig=4)}"
            "&nbsp;рад/с."]
