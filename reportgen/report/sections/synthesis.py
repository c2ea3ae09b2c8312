"""Section «Синтез рычажного механизма»: the design data, θ = 180°·(K − 1)/(K + 1), the
construction at scale, the lengths of the crank and the coupler with numbers, every solution
variant, the check of the synthesised linkage by the engine (its stroke or swing and K); the
values printed in the source are compared in the answer key.

``present(study)``: the case has ``[synthesis]``."""
from __future__ import annotations

import math

import pandas as pd
from markupsafe import Markup, escape

from ...case import synthesis as SY
from ...scenes.synthesis import SynthesisConstruction
from ...style.numbers import fmt, tex_num
from ..document import Column, Section, ref
from ..formulas import inline_math
from ..russian import plural

NEEDS = ("synthesis",)
TASK = "выполнить синтез рычажного механизма по коэффициенту изменения средней скорости выходного звена"

_INPUT_RU = {"K": ("K", "коэффициент изменения средней скорости"), "psi": ("ψ", "угол размаха коромысла"),
             "c": ("l<sub>CB</sub>", "длина коромысла"), "d": ("d", "расстояние между центрами вращения"),
             "o1_y": ("y<sub>O</sub>", "ордината линии, на которой лежит центр кривошипа"),
             "H": ("H", "ход выходного звена"), "e": ("e", "смещение (дезаксиал)"),
             "lam": ("λ", "отношение длин кривошипа и шатуна"), "a": ("a", "длина кривошипа"),
             "l3": ("l<sub>3</sub>", "длина коромысла"), "l4": ("l<sub>4</sub>", "длина шатуна коромысло — ползун"),
             "path_y": ("y<sub>C</sub>", "расстояние от опоры коромысла до траектории ползуна"),
             "o1_d": ("d", "расстояние от центра кривошипа до опоры коромысла"),
             "o1_path_dist": ("h", "расстояние от центра кривошипа до траектории ползуна"),
             "side": ("±", "сторона ползуна")}


_R = r"R = \frac{|B_1B_2|}{2\sin\theta}"
_RC = r"R\cos\theta"
_H6 = r"H = 2 l_3 \sin(\psi/2)"


def printed_angular(key: str) -> bool:
    """Whether the printed value ``key`` is an angle (the comparison table of the answer key,
    reportgen/report/key.py: the student's note holds no printed values)."""
    return SY.dim_of(key) == SY.U.ANGLE


def present(study) -> bool:
    return study.root.has("synthesis")


def _val(k: str, x: float) -> str:
    dim = SY.dim_of(k)
    if dim == SY.U.ANGLE:
        return fmt(math.degrees(x), sig=5) + "°"
    if dim == SY.U.LENGTH:
        return fmt(x, sig=5) + "&nbsp;м"
    return fmt(x, sig=5)


def _t(x, sig=5) -> str:
    return tex_num(x, sig=sig)


def build(study) -> Section:
    sy = study.synthesis
    kind, x, v, vs = sy.kind, sy.inputs, sy.chosen, sy.variants
    sec = Section("Синтез рычажного механизма", "sec-synthesis")
    sec.paragraph(f"Требуется спроектировать {SY.TITLES[kind]} по заданному коэффициенту изменения средней "
                  f"скорости выходного звена. Исходные данные приведены в таблице {ref('tab-syn-in')}.")
    rows = [{"sym": Markup(_INPUT_RU[k][0]), "name": _INPUT_RU[k][1], "val": Markup(_val(k, val))}
            for k, val in x.items()]
    sec.table("Исходные данные синтеза", [Column("sym", "Обозначение", fmt=Markup), Column("name", "Величина"),
                                          Column("val", "Значение", fmt=Markup)], pd.DataFrame(rows), id="tab-syn-in")
    th = v["theta"]
    sec.paragraph("За время рабочего хода кривошип поворачивается на угол 180°&nbsp;+&nbsp;θ, за время холостого "
                  "хода — на 180°&nbsp;−&nbsp;θ; в крайних положениях выходного звена кривошип и шатун "
                  "располагаются на одной прямой. Угол θ между этими положениями кривошипа:")
    sec.formula(r"\theta = 180^{\circ} \frac{K - 1}{K + 1}",
                rf"180^{{\circ}} \cdot \frac{{{_t(x['K'])} - 1}}{{{_t(x['K'])} + 1}}",
                tex_num(math.degrees(th), sig=5) + r"^{\circ}", label="eq-syn-theta")
    _construction(sec, study, kind, x, v)
    _variants(sec, kind, v, vs)
    _check(sec, study, sy)
    return sec


def _construction(sec, study, kind, x, v) -> None:
    d = SynthesisConstruction().draw(study)
    mu = inline_math(r"\mu_l")
    th2 = v["theta"] / 2
    if kind == "slotted_lever":
        sec.paragraph("В крайних положениях кулиса касается окружности, описываемой концом кривошипа, "
                      "поэтому угол размаха кулисы равен θ, а кривошип перпендикулярен кулисе:")
        sec.formula(r"a = d \sin\frac{\theta}{2}", rf"{_t(v['d'])} \cdot \sin {_t(math.degrees(th2))}^{{\circ}}",
                    tex_num(v["a"], sig=5, unit="м"), label="eq-syn-a")
        sec.formula(r"l_{CD} = \frac{H}{2 \sin(\theta/2)}",
                    rf"\frac{{{_t(v['H'])}}}{{2 \sin {_t(math.degrees(th2))}^{{\circ}}}}",
                    tex_num(v["l"], sig=5, unit="м"), label="eq-syn-l")
    else:
        P = "C" if kind == "slider_crank" else "B"
        ends = "C₁ и C₂ ползуна" if kind == "slider_crank" else "B₁ и B₂ конца коромысла"
        sec.paragraph(
            f"Построены крайние положения {ends}; центр вращения кривошипа O видит хорду между ними под углом θ, "
            "т.&nbsp;е. лежит на окружности, для которой эта хорда стягивает вписанный угол θ: её радиус "
            f"{inline_math(_R.replace('B', P))}, центр — на серединном перпендикуляре к хорде "
            f"на расстоянии {inline_math(_RC)} от неё. Центр O находится пересечением этой окружности "
            "с заданным геометрическим местом: " + _locus_ru(kind, x) + ". В крайних положениях "
            f"{inline_math(f'|O{P}_{{дальн}}| = b + a')}, {inline_math(f'|O{P}_{{ближн}}| = b - a')}, откуда")
        far = math.hypot(v.get("x_far", v.get("x_C2", 0)) - v["x_O"], v.get("y_far", 0.0) - v["y_O"])
        near = math.hypot(v.get("x_near", v.get("x_C1", 0)) - v["x_O"], v.get("y_near", 0.0) - v["y_O"])
        sec.formula(rf"a = \frac{{|O{P}_{{дальн}}| - |O{P}_{{ближн}}|}}{{2}}", rf"\frac{{{_t(far)} - {_t(near)}}}{{2}}",
                    tex_num(v["a"], sig=5, unit="м"), label="eq-syn-a")
        sec.formula(rf"b = \frac{{|O{P}_{{дальн}}| + |O{P}_{{ближн}}|}}{{2}}", rf"\frac{{{_t(far)} + {_t(near)}}}{{2}}",
                    tex_num(v["b"], sig=5, unit="м"), label="eq-syn-b")
        if kind == "six_bar":
            sec.paragraph("Звено 3 перпендикулярно траектории ползуна в середине хода, поэтому крайние положения "
                          "коромысла симметричны, а ход ползуна равен хорде дуги точки B: "
                          f"{inline_math(_H6)}, откуда "
                          f"ψ&nbsp;=&nbsp;{fmt(math.degrees(v['psi']), sig=5)}°.")
    sec.figure("Построение при синтезе механизма", d.svg, d.width_mm, id="fig-syn")
    sec.paragraph(f"Построение выполнено в масштабе {mu}&nbsp;=&nbsp;{fmt(d.mu, sig=3)}&nbsp;м/мм "
                  f"(рисунок {ref('fig-syn')}); длины найдены аналитически, без измерений на чертеже.")


def _locus_ru(kind, x) -> str:
    if kind == "slider_crank":
        return f"прямой, параллельной направляющей, на расстоянии e&nbsp;=&nbsp;{fmt(x.get('e', 0.0), sig=4)}&nbsp;м" \
            if "e" in x else "условием λ = a/b (решение в замкнутом виде по теореме косинусов для треугольника OC₁C₂)"
    if "d" in x or "o1_d" in x:
        return f"окружностью радиуса d&nbsp;=&nbsp;{fmt(x.get('d', x.get('o1_d')), sig=4)}&nbsp;м вокруг опоры коромысла"
    if "o1_path_dist" in x:
        return (f"прямыми, параллельными траектории ползуна, на расстоянии h&nbsp;=&nbsp;{fmt(x['o1_path_dist'], sig=4)}"
                "&nbsp;м от неё (по обе стороны)")
    return f"прямой y&nbsp;=&nbsp;{fmt(x['o1_y'], sig=4)}&nbsp;м"


def _variants(sec, kind, v, vs) -> None:
    if kind == "slotted_lever":
        return
    sec.paragraph(f"Задача имеет {plural(len(vs), 'вариант', 'варианта', 'вариантов')} решения (таблица {ref('tab-syn-var')}); "
                  f"варианты, симметричные относительно оси, дают одинаковые длины. Принят вариант {v['variant']}.")
    df = pd.DataFrame(vs)
    df["mark"] = ["принят" if w == v["variant"] else "" for w in df["variant"]]
    sec.table("Варианты решения", [Column("variant", "№", sig=None, digits=0), Column("a", "<i>a</i>", "м", sig=5),
                                   Column("b", "<i>b</i>", "м", sig=5), Column("x_O", "<i>x</i><sub>O</sub>", "м", sig=5),
                                   Column("y_O", "<i>y</i><sub>O</sub>", "м", sig=5), Column("mark", "")],
              df, id="tab-syn-var")


def _check(sec, study, sy) -> None:
    chk = sy.check
    if not chk or chk.get("extremes") != 2:
        return
    angular = chk["column"].startswith("phi_")
    target = sy.target_stroke()
    what = "размах" if angular else "ход"
    show = (lambda z: fmt(math.degrees(z), sig=10) + "°") if angular else (lambda z: fmt(z, sig=10) + "&nbsp;м")
    sec.paragraph(
        f"Проверка. Механизм с найденными размерами рассчитан по общей программе кинематического анализа; "
        f"крайние положения выходного звена ({escape(chk['title'])}) найдены как корни первой передаточной "
        f"функции (методом Брента, точно). Получены {what} {show(chk['stroke'])} (задан {show(target)}) и "
        f"K&nbsp;=&nbsp;{fmt(chk['K'], sig=10)} (задан {fmt(sy.inputs['K'], sig=10)}): синтез выполнен точно.")


def conclusion_lines(study) -> list[str]:
    sy = study.synthesis
    v = sy.chosen
    if sy.kind == "slotted_lever":
        s = (f"Синтез кулисного механизма: a&nbsp;=&nbsp;{fmt(v['a'], sig=4)}&nbsp;м, "
             f"l<sub>CD</sub>&nbsp;=&nbsp;{fmt(v['l'], sig=4)}&nbsp;м.")
    else:
        s = (f"Синтез ({SY.TITLES[sy.kind]}, K&nbsp;=&nbsp;{fmt(sy.inputs['K'], sig=4)}): кривошип "
             f"a&nbsp;=&nbsp;{fmt(v['a'], sig=4)}&nbsp;м, шатун b&nbsp;=&nbsp;{fmt(v['b'], sig=4)}&nbsp;м "
             f"(вариант {v['variant']} из {len(sy.variants)}).")
    return [s]
