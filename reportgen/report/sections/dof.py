"""Section «Число степеней свободы механизма с высшей парой»: Chebyshev's formula before the
replacement (with the passive freedom of each roller), the replacement of each higher pair by a
link with two lower pairs, the formula after it, the structure graphs; printed values.
``present``: ``[dof]``."""
from __future__ import annotations

import pandas as pd
from markupsafe import Markup

from ...scenes.dof import DofGraphs
from ..document import Column, Section, ref
from .synthesis import printed_table

NEEDS = ("dof",)
TASK = "определить число степеней свободы механизма до и после замены высшей пары низшими"


def present(study) -> bool:
    return study.root.has("dof")


def build(study) -> Section:
    d = study.dof
    b, a = d.before, d.after
    sec = Section("Число степеней свободы механизма с высшей парой", "sec-dof")
    rows = [{"pair": nm, "links": f"{i}–{j}", "type": {"R": "вращательная (p₅)", "P": "поступательная (p₅)",
                                                        "H": "высшая (p₄)"}[t]}
            for nm, (i, j, t) in zip(d.names, d.pairs)]
    sec.paragraph(f"Подвижные звенья: " + ", ".join(Markup("{} — {}").format(k, nm) for k, nm in enumerate(d.links)
                                                    if k) + f"; кинематические пары — в таблице {ref('tab-dof-pairs')}.")
    sec.table("Кинематические пары механизма", [Column("pair", "Пара"), Column("links", "Звенья"),
                                                Column("type", "Вид")], pd.DataFrame(rows), id="tab-dof-pairs")
    sec.paragraph("Число степеней свободы по формуле Чебышева (n — подвижные звенья, p₅ — низшие, p₄ — высшие пары):")
    sec.formula(r"W = 3n - 2p_5 - p_4", rf"3 \cdot {b['n']} - 2 \cdot {b['p5']} - {b['p4']}", str(b["W"]),
                label="eq-dof-before")
    if d.rollers:
        sec.paragraph(Markup("Вращение ролика ({}) вокруг своей оси не влияет на движение остальных звеньев — "
                             "пассивная (местная) степень свободы, q = {}; механизм имеет W − q = {} степень свободы.")
                      .format(", ".join(Markup("звено {}").format(r) for r in d.rollers), b["q"], b["W_true"]))
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
    printed_table(sec, d.printed, "tab-dof-printed")
    return sec


def conclusion_lines(study) -> list[str]:
    d = study.dof
    return [f"Механизм с высшей парой: W&nbsp;=&nbsp;{d.before['W']} по формуле Чебышева (в том числе "
            f"{d.before['q']} пассивная), после замены высшей пары W&nbsp;=&nbsp;{d.after['W']}."]
