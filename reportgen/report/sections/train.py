"""Section «Синтез планетарного механизма»: the tooth-number selection with every condition (when
asked), the ratio by Willis (stage by stage, each mesh's carrier held), the check by the velocity
picture and the plan of angular velocities, the graphical ratio against Willis in %.

``conclusion_lines(study)`` gives the lines of the ЗАКЛЮЧЕНИЕ about the train."""
from __future__ import annotations

import math

import pandas as pd
from markupsafe import Markup

from ...analysis.train import FRAME
from ...scenes.train import stage_plans, train_picture
from ...style.numbers import fmt, tex_num
from .common import as_written
from ..russian import plural
from ..document import Column, Formula, Section, ref

NEEDS = ("train",)
TASK = "выполнить кинематический синтез и анализ планетарного механизма"


def present(study) -> bool:
    """The section is built when the case has [train]."""
    return study.root.has("train")


def _pct(x: float) -> str:
    """A discrepancy in %, rounding noise (below 10⁻⁹ %) written as 0."""
    return "0" if abs(x) < 1e-9 else fmt(x, sig=2)


def _z(name: str) -> str:
    return rf"z_{{{name}}}"


def given(study) -> str:
    """The planetary train's data in one sentence for the assignment page."""
    tr = study.train
    m = tr.model
    text = (f"Планетарный механизм: входное звено {m.inp}, выходное {m.out}, неподвижное "
            f"{', '.join(m.fixed) or '—'}")
    if tr.candidates:
        text += (f"; передаточное отношение <i>u</i>&nbsp;=&nbsp;{as_written(tr.opts['target'])}, число сателлитов "
                 f"<i>k</i>&nbsp;=&nbsp;{tr.opts['planets']}; числа зубьев подбираются")
    else:
        text += "; числа зубьев колёс заданы"
    return text + "."


def build(study) -> Section:
    tr = study.train
    m = tr.model
    sec = Section("Синтез планетарного механизма", "sec-train")
    fixed = ", ".join(m.fixed) or "нет"
    sec.paragraph(f"Входное звено — {m.inp}, выходное — {m.out}, неподвижные звенья: {fixed}. "
                  f"Механизм состоит из {plural(len(m.wheels), 'колеса', 'колёс', 'колёс')} и "
                  f"{plural(len(m.members), 'подвижного звена', 'подвижных звеньев', 'подвижных звеньев')}; "
                  f"зацеплений {len(m.meshes)}.")
    if tr.candidates:
        _selection(sec, tr)
    _wheels(sec, tr)
    _willis(sec, tr)
    _picture(sec, tr)
    return sec


def _selection(sec: Section, tr) -> None:
    s = sec.subsection("Подбор чисел зубьев", "sec-train-select")
    k = tr.opts["planets"]
    sel = tr.opts["select"]
    s.paragraph(
        f"Числа зубьев подбираются перебором под передаточное отношение <i>u</i><sub>1H</sub> = "
        f"{fmt(tr.opts['target'], sig=5)} (допуск {fmt(tr.opts['tolerance'] * 100, sig=3)} %) при числе "
        f"сателлитов <i>k</i> = {k}. Проверяются условия: соосности (<i>z</i><sub>3</sub> = <i>z</i><sub>1</sub> + "
        f"2<i>z</i><sub>2</sub> для однорядной схемы), сборки (<i>z</i><sub>1</sub><i>u</i><sub>1H</sub>(1 + <i>kp</i>)/<i>k</i> "
        f"— целое), соседства (sin(π/<i>k</i>) &gt; (<i>z</i><sub>2</sub> + 2<i>h</i><sub>a</sub><sup>*</sup>)/"
        f"(<i>z</i><sub>1</sub> + <i>z</i><sub>2</sub>)), отсутствия подрезания (<i>z</i> ≥ {sel['z_min']}) и "
        f"интерференции во внутреннем зацеплении (<i>z</i><sub>3</sub> − <i>z</i><sub>2</sub> ≥ {sel['dz_internal']}). "
        f"Наборы упорядочены по габариту max(<i>z</i><sub>3</sub>, <i>z</i><sub>1</sub> + 2<i>z</i><sub>2</sub>); "
        f"принят первый.")
    rows = []
    for c in tr.candidates + tr.rejected:
        rows.append({"set": " / ".join(str(v) for v in c.z.values()), "u": c.u, "size": c.size,
                     "verdict": "годится" if c.ok else "; ".join(c.fails)})
    df = pd.DataFrame(rows)
    names = " / ".join(f"z{n}" for n in tr.candidates[0].z)
    s.table("Наборы чисел зубьев и проверка условий", [
        Column("set", names, fmt=str), Column("u", "<i>u</i><sub>1H</sub>", sig=5),
        Column("size", "Габарит, модулей", sig=4), Column("verdict", "Заключение", fmt=str)], df,
        id="tab-train-select", highlight_rows=[0])
    c = tr.candidates[0]
    z1, z2 = c.z["1"], c.z["2"]
    zr = c.z.get("2'", z2)
    s.paragraph("Проверка условия соседства для принятого набора:")
    s.formula(Formula(rf"\sin\frac{{\pi}}{{{k}}} = {tex_num(math.sin(math.pi / k), sig=4)} > "
                      rf"\frac{{z_2 + 2h_a^*}}{{z_1 + z_2}} = \frac{{{max(z2, zr)} + 2}}{{{z1} + {z2}}} = "
                      rf"{tex_num((max(z2, zr) + 2) / (z1 + z2), sig=4)}"))


def _wheels(sec: Section, tr) -> None:
    m = tr.model
    df = pd.DataFrame([{"wheel": w.name, "z": w.z, "m": w.m, "d": w.m * w.z, "member": w.member,
                        "kind": "внутреннее" if w.internal else "внешнее"} for w in m.wheels.values()])
    sec.table("Колёса механизма", [Column("wheel", "Колесо", fmt=str), Column("z", "<i>z</i>", sig=4),
                                     Column("m", "<i>m</i>", "мм", sig=3), Column("d", "<i>d</i>", "мм", sig=5),
                                     Column("member", "Звено", fmt=str), Column("kind", "Венец", fmt=str)],
              df, id="tab-train-wheels")
    if tr.coaxial_solved:
        sec.paragraph("Недостающие числа зубьев найдены из условия соосности: межосевое расстояние "
                      "<i>a</i> зацепления задано остальными зацеплениями того же контура осей.")
        forms = []
        for w, p, d, z in tr.coaxial_solved:
            ww, wp = m.wheels[w], m.wheels[p]
            if ww.internal:
                sym, num = rf"z_{{{p}}} + \frac{{2a}}{{m}}", rf"{wp.z} + \frac{{2 \cdot {tex_num(d, sig=6)}}}{{{tex_num(ww.m, sig=4)}}}"
            elif wp.internal:
                sym, num = rf"z_{{{p}}} - \frac{{2a}}{{m}}", rf"{wp.z} - \frac{{2 \cdot {tex_num(d, sig=6)}}}{{{tex_num(ww.m, sig=4)}}}"
            else:
                sym, num = rf"\frac{{2a}}{{m}} - z_{{{p}}}", rf"\frac{{2 \cdot {tex_num(d, sig=6)}}}{{{tex_num(ww.m, sig=4)}}} - {wp.z}"
            forms.append(Formula(rf"z_{{{w}}} = {sym}", num, str(z)))
        sec.formula(*forms)
    _printed_coaxiality(sec, tr)
    bad = [(n, r) for n, r in tr.coaxiality if abs(r) > 1e-9]
    if tr.coaxiality:
        text = ("Условие соосности выполнено для всех замкнутых контуров осей." if not bad else
                "Условие соосности нарушено: " + "; ".join(f"зацепление {n}: {fmt(r, sig=3)} мм" for n, r in bad) + ".")
        sec.paragraph(text)


def _form(t: dict) -> str:
    """A linear form in the tooth numbers as TeX, positive terms first: «z_{2} - z_{1}»."""
    out = ""
    for w, c in sorted(t.items(), key=lambda wc: wc[1] < 0):
        k = "" if abs(c) == 1 else str(abs(c))
        out += (" - " if c < 0 else (" + " if out else "")) + k + _z(w)
    return out.strip()


def _num(v) -> str:
    """A value of a linear form in tooth numbers (a Fraction): whole numbers as integers."""
    return fmt(float(v), digits=0) if v == int(v) else fmt(float(v), sig=6)


def _printed_coaxiality(sec: Section, tr) -> None:
    """The published solution's coaxiality equations checked against the train's own."""
    for text, j in tr.printed_coaxiality:
        if j["ok"]:
            sec.paragraph(Markup("Записанное в опубликованном решении условие соосности «{}» верно.").format(text))
            continue
        msg = Markup("В опубликованном решении условие соосности записано как «{}»: при подстановке чисел "
                     "зубьев левая часть равна {}, правая {}.").format(text, _num(j["lhs"]),
                                                                     _num(j["rhs"]))
        if j["flipped"]:
            msg += Markup(" Разность в одной из частей взята в обратном порядке (знак части неверен): "
                          "межосевое расстояние — величина положительная.")
        if j["correct"]:
            msg += Markup(" Верная запись (равенство межосевых расстояний замыкающего контура, модуль сокращён):")
        sec.paragraph(msg)
        if j["correct"]:
            path, close = j["correct"]
            sec.formula(Formula(rf"{_form(path)} = {_form(close)}"))
            v = sum(c * tr.model.wheels[w].z for w, c in path.items())
            pr = tr.opts.get("printed", {})
            same = [w for w in set(path) | set(close) if f"z{w}" in pr and pr[f"z{w}"] == tr.model.wheels[w].z]
            tail = ""
            if same:
                nums = " − ".join(str(tr.model.wheels[w].z) for w, c in sorted(path.items(), key=lambda wc: wc[1] < 0))
                tail = (" Напечатанные в решении " + ", ".join(f"z<sub>{w}</sub> = {tr.model.wheels[w].z}" for w in same)
                        + f" совпадают с найденными: в численной подстановке ({nums}) части взяты в верном порядке, "
                          "ошибка только в буквенной записи.")
            sec.paragraph(f"При найденных числах зубьев обе части равны {_num(v)}." + tail)


def _willis(sec: Section, tr) -> None:
    s = sec.subsection("Передаточное отношение по формуле Виллиса", "sec-train-willis")
    m = tr.model
    s.paragraph("Для каждого зацепления движение обращается относительно звена, на котором неподвижны оси "
                "обоих колёс (водила); внешнее зацепление даёт знак «−», внутреннее «+»:")
    forms = []
    for a, b in m.meshes:
        wa, wb = m.wheels[a], m.wheels[b]
        h = m.mesh_carrier(a, b)
        sign = "" if (wa.internal or wb.internal) else "-"
        if h == FRAME:
            lhs = rf"\frac{{\omega_{{{wa.member}}}}}{{\omega_{{{wb.member}}}}}"
        else:
            lhs = rf"\frac{{\omega_{{{wa.member}}} - \omega_{{{h}}}}}{{\omega_{{{wb.member}}} - \omega_{{{h}}}}}"
        forms.append(Formula(lhs, rf"{sign}\frac{{{_z(b)}}}{{{_z(a)}}}", rf"{sign}\frac{{{wb.z}}}{{{wa.z}}}"))
    s.formula(*forms)
    fr = tr.ratio_fraction
    frac = rf"\frac{{{fr.numerator}}}{{{fr.denominator}}}" if fr.denominator != 1 else str(fr.numerator)
    s.paragraph(f"Совместное решение при ω<sub>{m.inp}</sub> = 1 и неподвижных звеньях ({', '.join(m.fixed)}) даёт:")
    s.formula(rf"u_{{{m.inp}\,{m.out}}} = \frac{{\omega_{{{m.inp}}}}}{{\omega_{{{m.out}}}}}", frac,
              tex_num(tr.ratio, sig=7))
    pr = tr.opts.get("printed", {})
    if "u" in pr:
        s.paragraph(f"В опубликованном решении напечатано <i>u</i> = {fmt(pr['u'], sig=6)}: там перемножены "
                    f"округлённые множители ступеней (например, 1 + 74/22 = 4,364), точное значение "
                    f"{fr.numerator}/{fr.denominator} = {fmt(tr.ratio, sig=7)}, расхождение "
                    f"{fmt((pr['u'] - tr.ratio) / tr.ratio * 100, sig=2)} %.")
    if tr.opts["target"] is not None:
        s.paragraph(f"Отклонение от заданного <i>u</i> = {fmt(tr.opts['target'], sig=5)}: "
                    f"{_pct(tr.scalars['train_u_error_pct'])} %.")


def _picture(sec: Section, tr) -> None:
    s = sec.subsection("Кинематическое исследование графическим методом", "sec-train-graph")
    pic = train_picture(tr)
    m = tr.model
    s.paragraph(f"Скорости точек каждого звена распределены по прямой; в полюсах зацепления скорости колёс "
                f"равны (рисунок {ref('fig-train')}; схема симметрична относительно центральной оси, "
                f"картина скоростей построена для её верхней половины в том же масштабе). Прямые из полюса "
                f"плана угловых скоростей, параллельные линиям скоростей звеньев, отсекают на горизонтали "
                f"отрезки, пропорциональные угловым скоростям.")
    s.figure("Схема механизма, картина линейных скоростей и план угловых скоростей", pic.fig, 170, id="fig-train")
    st = stage_plans(tr)
    d = (st.u_graph - tr.ratio) / tr.ratio * 100
    s.paragraph(
        f"На общем плане отрезки звеньев с малой угловой скоростью коротки, и их отношение читается грубо. "
        f"Поэтому передаточное отношение определяется графически по ступеням: звенья упорядочены по "
        f"модулю угловой скорости ({' → '.join(a for a, *_ in st.stages)} → {m.out}), и для каждой пары "
        f"соседних звеньев построен свой план угловых скоростей в своём масштабе (рисунок "
        f"{ref('fig-train-stages')}); искомое отношение равно произведению отношений ступеней.")
    s.figure("Планы угловых скоростей по ступеням", st.fig, 170, id="fig-train-stages")
    forms = [Formula(rf"u_{{{a}\,{b}}} = \frac{{(0{a})}}{{(0{b})}}",
                     rf"\frac{{{tex_num(sa, digits=1)}}}{{{tex_num(sb, digits=1)}}}", tex_num(sa / sb, sig=5))
             for a, b, sa, sb in st.stages]
    s.formula(*forms)
    prod = r" \cdot ".join(rf"u_{{{a}\,{b}}}" for a, b, *_ in st.stages)
    s.formula(rf"u^{{граф}}_{{{m.inp}\,{m.out}}} = {prod}", tex_num(st.u_graph, sig=5))
    s.paragraph(f"Расхождение графического и аналитического значений: {_pct(d)} % (отрезки планов "
                f"измерены с точностью 0,5 мм). Прямой расчёт по равенству скоростей в полюсах даёт "
                f"<i>u</i> = {fmt(tr.ratio_direct, sig=10)}, отличие от формулы Виллиса "
                f"{_pct(tr.scalars['train_u_discrepancy_pct'])} %.")


def conclusion_lines(study) -> list[str]:
    tr = study.train
    m = tr.model
    fr = tr.ratio_fraction
    zs = ", ".join(f"z<sub>{w.name}</sub> = {w.z}" for w in m.wheels.values())
    return [f"Передаточное отношение планетарного механизма <i>u</i><sub>{m.inp}{m.out}</sub> = "
            f"{fr.numerator}/{fr.denominator} = {fmt(tr.ratio, sig=7)} ({zs})."]
