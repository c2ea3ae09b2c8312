"""Section «Число степеней свободы механизма с высшей парой»: Chebyshev's formula before the
replacement (with the passive freedom of each roller), the replacement of each higher pair by a
link with two lower pairs, the formula after it, the structure graphs (printed values: answer key).
``present``: ``[dof]``."""
from __future__ import annotations

import math

import pandas as pd
from markupsafe import Markup

from ...scenes.dof import DofGraphs, ZeroSpeedScene
from ...scenes.draw import gost_ratio
from ...style.numbers import fmt
from ..document import Column, Section, ref
from ..formulas import inline_math
from ..russian import plural, plural_form
from .common import swing_text

NEEDS = ("dof",)


def printed_angular(key: str) -> bool:
    """Whether the printed value ``key`` is an angle (the comparison table of the answer key,
    reportgen/report/key.py: the student's note holds no printed values)."""
    return key in ("angle_OML", "zero_q")


def TASK(study) -> str:
    """The assignment clause: W before and after the replacement, and (``[dof.zero_speed]``) the
    position where the output stops."""
    text = "заменить высшую пару низшими и определить число степеней свободы механизма до и после замены"
    zs = study.dof.zero_spec
    if zs is not None:
        text += f"; определить положение звеньев, при котором скорость выходного звена ({zs['output']}) равна нулю"
    return text


def present(study) -> bool:
    return study.root.has("dof")


def build(study) -> Section:
    d = study.dof
    b, a = d.before, d.after
    sec = Section("Число степеней свободы механизма с высшей парой", "sec-dof")
    rows = [{"pair": nm, "links": f"{i}–{j}", "type": {"R": "вращательная (p₅)", "P": "поступательная (p₅)",
                                                        "H": "высшая (p₄)"}[t]}
            for nm, (i, j, t) in zip(d.names, d.pairs)]
    sec.paragraph("Подвижные звенья: " + ", ".join(Markup("{} — {}").format(k, nm) for k, nm in enumerate(d.links)
                                                    if k) + f"; кинематические пары — в таблице {ref('tab-dof-pairs')}.")
    sec.table("Кинематические пары механизма", [Column("pair", "Пара"), Column("links", "Звенья"),
                                                Column("type", "Вид")], pd.DataFrame(rows), id="tab-dof-pairs")
    sec.paragraph("Число степеней свободы по формуле Чебышева (n — подвижные звенья, p₅ — низшие, p₄ — высшие пары):")
    sec.formula(r"W = 3n - 2p_5 - p_4", rf"3 \cdot {b['n']} - 2 \cdot {b['p5']} - {b['p4']}", str(b["W"]),
                label="eq-dof-before")
    if d.rollers:
        sec.paragraph(Markup("Вращение ролика ({}) вокруг своей оси не влияет на движение остальных звеньев — "
                             "пассивная (местная) степень свободы, q = {}; механизм имеет W − q = {} {} свободы.")
                      .format(", ".join(Markup("звено {}").format(r) for r in d.rollers), b["q"], b["W_true"],
                              plural_form(b["W_true"], "степень", "степени", "степеней")))
    sec.paragraph("При замене высшая пара заменяется звеном с двумя вращательными парами в центрах кривизны "
                  "соприкасающихся профилей. Центр кривизны ролика — его ось, поэтому ролик сам становится "
                  "заменяющим звеном (его вращательная пара сохраняется, высшая заменяется вращательной), и "
                  "пассивная степень свободы исчезает" + ("; для остальных высших пар вводится новое звено." if d.new_links else "."))
    sec.formula(r"W = 3n - 2p_5", rf"3 \cdot {a['n']} - 2 \cdot {a['p5']}", str(a["W"]), label="eq-dof-after")
    g = DofGraphs().draw(study)
    sec.figure("Структурные схемы связей звеньев до и после замены высшей пары (0 — стойка, высшая пара — "
               "штриховая линия, заменяющее звено выделено)", g.svg, g.width_mm, id="fig-dof")
    sec.paragraph(f"Связи звеньев до и после замены показаны на рисунке {ref('fig-dof')}; число степеней свободы "
                  f"после замены W = {a['W']} совпадает с числом степеней свободы исходного механизма без "
                  f"пассивных W − q = {b['W_true']}: замена структурно эквивалентна.")
    if d.zero is not None:
        _zero_speed(sec, study)
    return sec


def _zero_speed(sec: Section, study) -> None:
    """Question 3: the positions where the output stops (vector equation, criterion ML ⊥ MO, the
    positions found from the exact kinematics, the criterion measured there, the drawing)."""
    d = study.dof
    z, zs = d.zero, d.zero_spec
    drv = study.mechanism.driver
    M, L, O, k = zs["point"], zs["line"], zs["pivot"], zs["link"]
    j = zs["joint"]
    slider = j.links[1]
    s = sec.subsection("Положение звеньев, при котором скорость выходного звена равна нулю", "sec-dof-zero")
    s.paragraph(Markup("Выходное звено — {} — шарнирно связано в точке {} с камнем {}, который скользит по прямолинейной "
                       "прорези {}{} звена {}, вращающегося вокруг оси {}. Скорость точки {} выходного звена по теореме "
                       "сложения скоростей:").format(zs["output"], M, slider, M, L, k, O, M))
    s.formula(rf"\vec V_{{{M}}} = \vec V_{{{M}{k}}} + \vec V_{{{M}{slider}{M}{k}}}", label="eq-dof-zero-vec",
              where=[(rf"\vec V_{{{M}{k}}} = \vec\omega_{{{k}}} \times \overline{{{O}{M}}}",
                      f"скорость точки звена {k}, совпадающей с {M}; перпендикулярна {O}{M}"),
                     (rf"\vec V_{{{M}{slider}{M}{k}}}", f"скорость камня относительно звена {k}; параллельна прорези {M}{L}")])
    s.paragraph(Markup("Проецируя равенство на нормаль к прорези (относительная скорость на неё не проецируется), "
                       "получаем, что {} = 0 (выходное звено движется поперёк прорези), когда либо ω<sub>{}</sub> = 0, "
                       "либо скорость {} параллельна прорези, то есть {}{}&nbsp;⊥&nbsp;{}{}: камень находится в основании "
                       "перпендикуляра, опущенного из оси {} на прорезь, и {} = −{}.")
                .format(Markup("<i>V</i><sub>{}</sub>").format(M), k, Markup("<i>V</i><sub>{}{}</sub>").format(M, k),
                        M, L, M, O, O, Markup("<i>V</i><sub>{}{}</sub>").format(M, k),
                        Markup("<i>V</i><sub>{}{}{}{}</sub>").format(M, slider, M, k)))
    if drv.swing:
        s.paragraph(Markup("Звено {} качается в диапазоне {}; в его крайних положениях ω<sub>{}</sub> = 0 и выходное "
                           "звено также останавливается (вместе с ведущим).").format(k, Markup(swing_text(drv)), k))
    if not len(z):
        s.paragraph(f"В рассматриваемом диапазоне движения звена {k} положения с {M}{L}&nbsp;⊥&nbsp;{M}{O} нет.")
        return
    s.paragraph(Markup("Положения с {}&nbsp;=&nbsp;0 при ω<sub>{}</sub>&nbsp;≠&nbsp;0 найдены независимо от этого условия — "
                       "как корни первой передаточной функции выходного звена <i>S</i>′(φ<sub>{}</sub>) = 0 по точному "
                       "решению о положениях (метод Брента); в них измерены угол между {}{} и {}{} и расстояния "
                       "(таблица {}, рисунок {}).").format(Markup("<i>V</i><sub>{}</sub>").format(M), k, k, M, L, M, O,
                                                            Markup(ref("tab-dof-zero")), Markup(ref("fig-dof-zero"))))
    df = z.assign(q_deg=z["q_deg"], ang=[math.degrees(a) for a in z["angle_OML"]])
    s.table("Положения остановки выходного звена", [
        Column("q_deg", f"φ<sub>{k}</sub>", "град", digits=4),
        Column("s", "<i>S</i>", "м", digits=5),
        Column("ang", f"∠{O}{M}{L}", "град", digits=9),
        Column("OM", f"|{O}{M}|", "м", digits=6),
        Column("h", f"расстояние от {O} до прорези", "м", digits=6)], df, id="tab-dof-zero")
    r = z.iloc[0]
    s.paragraph(Markup("Угол {}{}{} = {}°, |{}{}| совпадает с расстоянием от оси {} до прорези: условие решения "
                       "{}{}&nbsp;⊥&nbsp;{}{} подтверждается точным расчётом. Ответ на вопрос 3 (рисунок {}): камень {} — "
                       "в основании перпендикуляра из {} на прорезь, φ<sub>{}</sub> = {}°.")
                .format(O, M, L, fmt(math.degrees(r["angle_OML"]), digits=9), O, M, O, M, L, M, O,
                        Markup(ref("fig-dof-zero")), slider, O, k, fmt(r["q_deg"], digits=3)))
    g = ZeroSpeedScene().draw(study)
    s.figure(Markup("Положение остановки выходного звена: {}{}&nbsp;⊥&nbsp;{}{}, скорость {} равна и противоположна "
                    "относительной скорости камня; масштаб {}").format(
        M, L, M, O, Markup("<i>V</i><sub>{}{}</sub>").format(M, k), gost_ratio(g.mu)), g.svg, g.width_mm, id="fig-dof-zero")


def conclusion_lines(study) -> list[str]:
    d = study.dof
    passive = (f" (в том числе {plural(d.before['q'], 'пассивная', 'пассивные', 'пассивных')})"
               if d.before["q"] else "")
    out = [Markup("Механизм с высшей парой: {} по формуле Чебышева{}, после замены высшей пары {}.").format(
        inline_math(f"W = {d.before['W']}"), passive, inline_math(f"W = {d.after['W']}"))]
    if d.zero is not None and len(d.zero):
        zs, r = d.zero_spec, d.zero.iloc[0]
        out.append(f"Выходное звено останавливается при движущемся звене {zs['link']}, когда "
                   f"{zs['point']}{zs['line']}&nbsp;⊥&nbsp;{zs['point']}{zs['pivot']} "
                   f"(φ<sub>{zs['link']}</sub>&nbsp;=&nbsp;{fmt(r['q_deg'], digits=3)}°; угол "
                   f"{zs['pivot']}{zs['point']}{zs['line']}&nbsp;=&nbsp;{fmt(math.degrees(r['angle_OML']), digits=3)}°).")
    return out
