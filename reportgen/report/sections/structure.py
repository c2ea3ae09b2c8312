"""Section «Структурный анализ механизма»."""
from __future__ import annotations

import pandas as pd
from markupsafe import Markup, escape

from ...analysis.link_motion import link_motion
from ...mechanism.structure import decomposition as _decomposition
from ...scenes.draw import gost_ratio, mu_text
from ...scenes.mechanism import AssurGroups, KinematicScheme
from ..document import Column, Section, ref
from ..formulas import inline_math
from ..russian import expr_html, plural
from .common import fit_condition, html_point, input_word, pair_label

NEEDS = ("structure", "kinematics")


def _ends(links: str) -> tuple[str, str]:
    """The two link numbers of «3–4»."""
    a, _, b = links.partition("–")
    return a, b


def _indexed(name: str) -> Markup:
    """A revolute pair's designation with the digits ending a point's name as its index, as the
    formulas and drawings write the point (O1 → O<sub>1</sub>); a name of digits only («12») as it is."""
    head = name.rstrip("0123456789")
    tail = name[len(head):]
    return Markup("{}<sub>{}</sub>").format(head, tail) if head and tail else Markup(escape(name))


def _compound_hinges(mech) -> list[tuple[str, list[str], list[str]]]:
    """Сложные шарниры: a point where three or more links are joined by revolute pairs, k links
    making k − 1 pairs (Артоболевский [1], гл. 2): (point, its links, its pairs «1–2»)."""
    at: dict[str, list] = {}
    for j in mech.joints:
        if j.kind == "R":
            at.setdefault(j.point, []).append(j)
    out = []
    for p, js in at.items():
        if len(js) > 1:
            ls = sorted({l for j in js for l in j.links}, key=lambda l: (len(l), l))
            out.append((p, ls, [f"{j.links[0]}–{j.links[1]}" for j in js]))
    return out


def _pairs_words(n: int) -> str:
    """«две вращательные пары» (a small count in words, as a student writes it)."""
    words = {2: "две", 3: "три", 4: "четыре"}
    return (f"{words[n]} вращательные пары" if n in words
            else plural(n, "вращательную пару", "вращательные пары", "вращательных пар"))


def build(study) -> Section:
    st = study.structure
    mech = study.mechanism
    sec = Section("Структурный анализ механизма", "sec-structure")
    pos = study.kinematics["pos"].iloc[0]
    scheme = KinematicScheme(pos).draw(study)
    links = [l for l in mech.moving]
    mu_l = inline_math(r"\mu_l")
    sec.paragraph(
        f"Кинематическая схема механизма в положении {pos} приведена на рисунке {ref('fig-scheme')} "
        f"(масштаб {mu_l}&nbsp;=&nbsp;{mu_text(scheme.mu)}&nbsp;м/мм, {gost_ratio(scheme.mu)}). Механизм состоит из стойки 0 и "
        f"{plural(len(links), 'подвижного звена', 'подвижных звеньев', 'подвижных звеньев')}, соединённых "
        f"{plural(st.p5, 'низшей кинематической парой', 'низшими кинематическими парами', 'низшими кинематическими парами')}.")
    sec.figure("Кинематическая схема механизма", scheme.svg, scheme.width_mm, id="fig-scheme")

    s1 = sec.subsection("Звенья и кинематические пары", "sec-links-pairs")
    # the kind of motion; its parenthesised generic name («коромысло, кулиса») only for an untitled link
    ldf = pd.DataFrame([{"n": l.name, "title": l.title or "—",
                         "motion": link_motion(study, l.name).split(" (")[0] if l.title else link_motion(study, l.name)}
                        for l in links])
    s1.paragraph(f"Звенья механизма и виды их движения перечислены в таблице {ref('tab-links')}, "
                 f"кинематические пары — в таблице {ref('tab-pairs')}.")
    s1.table("Звенья механизма", [Column("n", "Номер"), Column("title", "Название"), Column("motion", "Вид движения")],
             ldf, id="tab-links")
    pdf = pd.DataFrame(st.pairs)
    pdf["klass"] = pdf["klass"].astype(str)
    # pairs named by their point, a prismatic pair marked «(П)» as in the incidence table (no
    # program names such as «50»)
    prism = [r.point for r in pdf.itertuples() if r.kind.startswith("поступательная")]
    pdf["name"] = [(pair_label(r.point, "П", *_ends(r.links), prism.count(r.point) > 1) if r.point != "—"
                    else f"{r.links} (П)") if r.kind.startswith("поступательная")
                   else _indexed(r.name) for r in pdf.itertuples()]
    s1.table("Кинематические пары", [Column("name", "Обозначение", fmt=Markup), Column("links", "Звенья"),
                                     Column("kind", "Вид пары"), Column("klass", "Класс"),
                                     Column("level", "Низшая/высшая")], pdf, id="tab-pairs")
    hinges = _compound_hinges(mech)
    if hinges:
        s1.paragraph(" ".join(Markup("В точке {} сходятся звенья {}: это сложный шарнир, он образует {} ({}), "
                                     "каждая из них учтена в числе низших пар <i>p</i><sub>5</sub>.").format(
            Markup(html_point(escape(p))), ", ".join(ls[:-1]) + " и " + ls[-1],
            _pairs_words(len(ps)), ", ".join(ps))
            for p, ls, ps in hinges))

    s2 = sec.subsection("Число степеней свободы", "sec-dof")
    s2.paragraph("Число степеней свободы плоского механизма определяется по формуле П.&nbsp;Л.&nbsp;Чебышева [1]:")
    s2.formula(r"W = 3n - 2p_5 - p_4", rf"3 \cdot {st.n} - 2 \cdot {st.p5} - {st.p4}", str(st.W),
               where=[("n", "число подвижных звеньев"), ("p_5", "число низших (одноподвижных) пар"),
                      ("p_4", "число высших пар")], label="eq-chebyshev")
    driver = (input_word(mech.driver, "gen") + " " + mech.driver.link) if mech.driver.rotary else \
        f"гидроцилиндра (звенья {mech.driver.link} и {mech.driver.rod}, поступательная ведущая пара)"
    s2.paragraph(f"{inline_math('W')}&nbsp;=&nbsp;{st.W}: для определённости движения достаточно одного ведущего звена — {driver}. "
                 "Пассивных связей и лишних степеней свободы нет.")

    s3 = sec.subsection("Группы Ассура и структурная формула", "sec-groups")
    groups = AssurGroups(pos).draw(study)
    mus = {mu for _, mu, _ in groups.panels}
    scales = (f"все группы вычерчены в одном масштабе {gost_ratio(min(mus))}, "
              f"{mu_l}&nbsp;=&nbsp;{mu_text(min(mus))}&nbsp;м/мм") if len(mus) == 1 else "каждая группа вычерчена в своём масштабе, указанном под ней"
    s3.paragraph(f"Механизм раскладывается на начальный механизм и группы Ассура, начиная с группы, "
                 f"наиболее удалённой от ведущего звена (рисунок {ref('fig-groups')}; {scales}). Для каждой группы Ассура "
                 f"{inline_math('W = 3n - 2p_5 = 0')}, для начального механизма {inline_math('W = 1')}:")
    rows, formula = decomposition(study)
    gdf = pd.DataFrame(rows)
    s3.table("Структурные группы механизма (в порядке присоединения)",
             [Column("g", "Звенья"), Column("title", "Группа"), Column("n", "<i>n</i>"),
              Column("p", "<i>p</i><sub>5</sub>"), Column("W", "<i>W</i>")], gdf, id="tab-groups")
    s3.figure("Начальный механизм и группы Ассура", groups.svg, groups.width_mm, id="fig-groups")
    s3.paragraph(f"Структурная формула механизма: <b>{formula}</b>. "
                 f"Класс механизма определяется наивысшим классом входящих в него групп: механизм "
                 f"{_roman(st.mech_class)} класса.")
    if mech.driver.kind == "actuator":
        d = mech.driver
        s3.paragraph(f"Ведущая пара — поступательная пара {d.link}–{d.rod} гидроцилиндра (обобщённая координата — "
                     f"его длина S). Цилиндр {d.link} и шток {d.rod} вместе со звеном, к которому присоединён "
                     "шток, и стойкой образуют начальный механизм с одной степенью свободы; при заданной длине S "
                     "цилиндр и шток составляют одно звено переменной длины, и положения звеньев начального "
                     "механизма находятся как для группы ВВВ. Это же разделение использовано в кинематическом "
                     "и силовом анализе: в силовом расчёте начальный механизм рассчитывается последним, "
                     "неизвестное усилие гидроцилиндра входит в его уравнения равновесия.")
    return sec


def decomposition(study) -> tuple[list[dict], str]:
    """Rows of the structural table and the structural formula (:func:`mechanism.structure.decomposition`)."""
    return _decomposition(study.structure, study.mechanism.driver)


def _roman(k: int) -> str:
    return {1: "I", 2: "II", 3: "III", 4: "IV"}.get(k, str(k))


def conclusion_lines(study) -> list[str]:
    """Structure and fitted dimensions for the ЗАКЛЮЧЕНИЕ."""
    from ...style.numbers import fmt
    st = study.structure
    out = [f"Механизм имеет одну степень свободы ({inline_math('W')}&nbsp;=&nbsp;{st.W}), структурная формула "
           f"{decomposition(study)[1]}, механизм {_roman(st.mech_class)} класса."]
    fits = []
    for f in study.fits:
        cond, title, at = fit_condition(study, f)
        said = Markup(": {} {},").format(title, cond) if title else Markup(" {}").format(cond)
        fits.append(Markup("{}&nbsp;=&nbsp;{}&nbsp;м (условие{} при {})").format(
            expr_html(f.name), fmt(f.value, digits=4), said, at))
    if len(fits) == 1:
        out.append(Markup("Подобран размер {}.").format(fits[0]))
    elif fits:            # one sentence for all of them, not one each
        out.append(Markup("Подобраны размеры: ") + Markup("; ").join(fits) + Markup("."))
    return out
