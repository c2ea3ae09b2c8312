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
from ...scenes.draw import mu_text
from ...scenes.synthesis import SynthesisConstruction
from ...style.numbers import fmt, tex_num
from ..document import Column, Formula, Section, ref
from ..formulas import inline_math
from ..russian import plural
from .common import as_written

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
             "side": ("—", "положение ползуна относительно точки B")}


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
    """A given datum of the synthesis as the case writes it (K = 1,25, ψ = 50°, 0,35 м); the
    slider's side of a six-bar in words (a sign is no quantity of a student's note)."""
    if k == "side":
        return "левее" if x < 0 else "правее"
    dim = SY.dim_of(k)
    if dim == SY.U.ANGLE:
        return as_written(math.degrees(x)) + "°"
    if dim == SY.U.LENGTH:
        return as_written(x) + "&nbsp;м"
    return as_written(x)


MU_ALLOWED = 40.0           # [μ], degrees: the least transmission angle allowed (Попов, Тимофеев [2])


def given(study) -> str:
    """The synthesis data in one sentence for the assignment page."""
    sy = study.synthesis
    parts = ", ".join(f"ползун {_val(k, v)} точки B" if k == "side" else
                      f"{_INPUT_RU[k][1]} {_INPUT_RU[k][0]}&nbsp;=&nbsp;{_val(k, v)}" for k, v in sy.inputs.items())
    return f"Синтез: {SY.TITLES[sy.kind]}; {parts}."


def input_title(study, name: str) -> str | None:
    """The Russian name of a case parameter that is given as an input of the synthesis
    («d = "d"» → «расстояние от центра кривошипа до опоры коромысла»), for the assignment's table
    of given data, where a bare letter would be guessed (d → «диаметр»); None otherwise."""
    if not study.root.has("synthesis"):
        return None
    raw = study.root.table("synthesis").data
    return next((_INPUT_RU[k][1] for k, v in raw.items()
                 if k in _INPUT_RU and k != "side" and isinstance(v, str) and v.strip() == name), None)


def _w(x) -> str:
    """A given value as written, for TeX (the decimal comma braced)."""
    return as_written(x).replace(",", "{,}")


def _datum(x: dict, key: str, value: float) -> str:
    """A datum in the text: as written when it is a given input (d = 0,6 м), else to 5 digits."""
    return as_written(x[key]) if key in x else fmt(value, sig=5)


def _g(x: dict, key: str, value: float, sig: int = 5) -> str:
    """A datum in a substituted formula: as written when it is a given input (its magnitude, as
    ``value`` is), else to ``sig`` digits."""
    return _w(abs(x[key]) if value >= 0 else x[key]) if key in x else _t(value, sig)


def _t(x, sig=5) -> str:
    return tex_num(x, sig=sig)


def _deg(rad: float) -> str:
    """An angle of the construction (θ, θ/2, ψ/2) in degrees for TeX, to 0,001° without padding
    zeros: θ = 180°·(1,25 − 1)/(1,25 + 1) is «20°», not «20,000°»; 16,364°, 8,182°."""
    return as_written(round(math.degrees(rad), 3)).replace(",", "{,}")


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
    where = ("в крайних положениях кулисы кривошип перпендикулярен ей" if kind == "slotted_lever" else
             "в крайних положениях выходного звена кривошип и шатун располагаются на одной прямой")
    sec.paragraph("За время рабочего хода кривошип поворачивается на угол 180°&nbsp;+&nbsp;θ, за время холостого "
                  f"хода — на 180°&nbsp;−&nbsp;θ; {where}. Угол θ между этими положениями кривошипа:")
    sec.formula(r"\theta = 180^{\circ} \frac{K - 1}{K + 1}",
                rf"180^{{\circ}} \cdot \frac{{{_w(x['K'])} - 1}}{{{_w(x['K'])} + 1}}",
                _deg(th) + r"^{\circ}", label="eq-syn-theta")
    _construction(sec, study, kind, x, v)
    _variants(sec, kind, x, v, vs, sy.transmission)
    _transmission(sec, kind, x, v, sy.transmission)
    _check(sec, study, sy)
    return sec


def _construction(sec, study, kind, x, v) -> None:
    d = SynthesisConstruction().draw(study)
    mu = inline_math(r"\mu_l")
    th2 = v["theta"] / 2
    if kind == "slotted_lever":
        sec.paragraph("В крайних положениях кулиса касается окружности, описываемой концом кривошипа, "
                      "поэтому угол размаха кулисы равен θ, а кривошип перпендикулярен кулисе:")
        sec.formula(r"a = d \sin\frac{\theta}{2}", rf"{_g(x, 'd', v['d'])} \cdot \sin {_deg(th2)}^{{\circ}}",
                    tex_num(v["a"], sig=5, unit="м"), label="eq-syn-a")
        sec.formula(r"l_{CD} = \frac{H}{2 \sin(\theta/2)}",
                    rf"\frac{{{_g(x, 'H', v['H'])}}}{{2 \sin {_deg(th2)}^{{\circ}}}}",
                    tex_num(v["l"], sig=5, unit="м"), label="eq-syn-l")
    else:
        P = "C" if kind == "slider_crank" else "B"
        ends = "C₁ и C₂ ползуна" if kind == "slider_crank" else "B₁ и B₂ конца коромысла"
        sec.paragraph(
            f"Построены крайние положения {ends}; центр вращения кривошипа O видит хорду между ними под углом θ, "
            "т.&nbsp;е. лежит на окружности, для которой эта хорда стягивает вписанный угол θ: её радиус "
            f"{inline_math(_R.replace('B', P))}, центр — на серединном перпендикуляре к хорде "
            f"на расстоянии {inline_math(_RC)} от неё:")
        _chord(sec, kind, v, P)
        sec.paragraph(
            "Центр O находится пересечением этой окружности с заданным геометрическим местом: "
            + _locus_ru(kind, x) + ". В крайних положениях "
            f"{inline_math(f'|O{P}_{{дальн}}| = b + a')}, {inline_math(f'|O{P}_{{ближн}}| = b - a')}"
            + (":" if kind == "slider_crank" and "lam" in x else ", откуда"))
        if kind == "slider_crank" and "lam" in x:
            sec.paragraph("По теореме косинусов для треугольника OC₁C₂ (стороны b − a, b + a, H, угол θ при O) "
                          "и λ&nbsp;=&nbsp;a/b:")
            sec.formula(r"b = \frac{H}{\sqrt{2(1 + \lambda^2) - 2(1 - \lambda^2)\cos\theta}}",
                        rf"\frac{{{_w(x['H'])}}}{{\sqrt{{2(1 + {_w(x['lam'])}^2) - 2(1 - "
                        rf"{_w(x['lam'])}^2)\cos {_deg(v['theta'])}^{{\circ}}}}}}",
                        tex_num(v["b"], sig=5, unit="м"), label="eq-syn-b-lam")
            sec.formula(r"a = \lambda b", rf"{_w(x['lam'])} \cdot {_t(v['b'])}",
                        tex_num(v["a"], sig=5, unit="м"), label="eq-syn-a-lam")
            sec.formula(r"e = \frac{(b^2 - a^2)\sin\theta}{H}",
                        rf"\frac{{({_t(v['b'])}^2 - {_t(v['a'])}^2)\sin {_deg(v['theta'])}^{{\circ}}}}"
                        rf"{{{_w(x['H'])}}}", tex_num(v["e"], sig=5, unit="м"), label="eq-syn-e")
            sec.paragraph("Те же длины по построению (расстояния от O до крайних положений ползуна):")
        far = math.hypot(v.get("x_far", v.get("x_C2", 0)) - v["x_O"], v.get("y_far", 0.0) - v["y_O"])
        near = math.hypot(v.get("x_near", v.get("x_C1", 0)) - v["x_O"], v.get("y_near", 0.0) - v["y_O"])
        sec.formula(rf"a = \frac{{|O{P}_{{дальн}}| - |O{P}_{{ближн}}|}}{{2}}", rf"\frac{{{_t(far)} - {_t(near)}}}{{2}}",
                    tex_num(v["a"], sig=5, unit="м"), label="eq-syn-a")
        sec.formula(rf"b = \frac{{|O{P}_{{дальн}}| + |O{P}_{{ближн}}|}}{{2}}", rf"\frac{{{_t(far)} + {_t(near)}}}{{2}}",
                    tex_num(v["b"], sig=5, unit="м"), label="eq-syn-b")
    sec.figure("Построение при синтезе механизма", d.svg, d.width_mm, id="fig-syn")
    sec.paragraph(f"Построение выполнено в масштабе {mu}&nbsp;=&nbsp;{mu_text(d.mu)}&nbsp;м/мм "
                  f"(рисунок {ref('fig-syn')}); длины найдены аналитически, без измерений на чертеже.")


def _chord(sec, kind, v, P) -> None:
    """The chord of the extreme positions and the θ-circle's radius with numbers."""
    if kind == "slider_crank":
        sec.paragraph(f"Хорда |C₁C₂|&nbsp;=&nbsp;H&nbsp;=&nbsp;{as_written(v['H'])}&nbsp;м, радиус окружности:")
        chord = v["H"]
    elif kind == "six_bar":
        # the swing is found from the stroke before the chord uses it (H = 2 l₃ sin(ψ/2))
        sec.paragraph("Звено 3 перпендикулярно траектории ползуна в середине хода, поэтому крайние положения "
                      "коромысла симметричны, а ход ползуна равен хорде дуги точки B: "
                      f"{inline_math(_H6)}, |B₁B₂|&nbsp;=&nbsp;H&nbsp;=&nbsp;{as_written(v['H'])}&nbsp;м. "
                      "Размах коромысла:")
        sec.formula(r"\psi = 2\arcsin\frac{H}{2 l_3}", rf"2\arcsin\frac{{{_w(v['H'])}}}{{2 \cdot {_w(v['l3'])}}}",
                    _deg(v["psi"]) + r"^{\circ}", label="eq-syn-psi6")
        sec.paragraph("Радиус окружности:")
        chord = v["H"]
    else:
        chord = math.hypot(v["x_B2"] - v["x_B1"], v["y_B2"] - v["y_B1"])
        sec.formula(r"|B_1B_2| = 2 l_{CB} \sin\frac{\psi}{2}",
                    rf"2 \cdot {_w(v['c'])} \cdot \sin {_deg(v['psi'] / 2)}^{{\circ}}",
                    tex_num(chord, sig=5, unit="м"), label="eq-syn-chord")
    th = v["theta"]
    if th > 1e-9:
        shown = _w(chord) if kind == "slider_crank" else _t(chord)
        sec.formula(_R.replace("B", P), rf"\frac{{{shown}}}{{2 \sin {_deg(th)}^{{\circ}}}}",
                    tex_num(chord / (2 * math.sin(th)), sig=5, unit="м"), label="eq-syn-R")


def _locus_ru(kind, x) -> str:
    if kind == "slider_crank":
        return f"прямой, параллельной направляющей, на расстоянии e&nbsp;=&nbsp;{as_written(x['e'])}&nbsp;м" \
            if "e" in x else "условием λ = a/b (решение в замкнутом виде по теореме косинусов для треугольника OC₁C₂)"
    if "d" in x or "o1_d" in x:
        return f"окружностью радиуса d&nbsp;=&nbsp;{as_written(x.get('d', x.get('o1_d')))}&nbsp;м вокруг опоры коромысла"
    if "o1_path_dist" in x:
        return (f"прямыми, параллельными траектории ползуна, на расстоянии h&nbsp;=&nbsp;{as_written(x['o1_path_dist'])}"
                "&nbsp;м от неё (по обе стороны)")
    return f"прямой y&nbsp;=&nbsp;{as_written(x['o1_y'])}&nbsp;м"


def _variants(sec, kind, x, v, vs, tr) -> None:
    if kind == "slotted_lever":
        return
    if len(vs) == 1:
        if kind == "slider_crank":
            sec.paragraph(f"Задача имеет единственное решение: кривошип a&nbsp;=&nbsp;{fmt(v['a'], sig=5)}&nbsp;м, "
                          f"шатун b&nbsp;=&nbsp;{fmt(v['b'], sig=5)}&nbsp;м, смещение e&nbsp;=&nbsp;"
                          f"{_datum(x, 'e', v['e'])}&nbsp;м (λ&nbsp;=&nbsp;{_val('lam', x['lam']) if 'lam' in x else fmt(v['lam'], sig=4)}).")
        else:
            sec.paragraph(f"Задача имеет единственное решение: кривошип a&nbsp;=&nbsp;{fmt(v['a'], sig=5)}&nbsp;м, "
                          f"шатун b&nbsp;=&nbsp;{fmt(v['b'], sig=5)}&nbsp;м.")
        return
    why = ""
    if tr is not None:
        mu = tr["mu"]
        best = max(mu)
        if mu[v["variant"] - 1] >= best - 1e-9 and min(mu) < best - math.radians(0.05):
            why = " — у него наибольший наименьший угол передачи"
    sec.paragraph(f"Задача имеет {plural(len(vs), 'вариант', 'варианта', 'вариантов')} решения (таблица {ref('tab-syn-var')}); "
                  f"варианты, симметричные относительно оси, дают одинаковые длины. Принят вариант {v['variant']}{why}.")
    df = pd.DataFrame(vs)
    df["mark"] = ["принят" if w == v["variant"] else "" for w in df["variant"]]
    cols = [Column("variant", "№", sig=None, digits=0), Column("a", "<i>a</i>", "м", sig=5),
            Column("b", "<i>b</i>", "м", sig=5), Column("x_O", "<i>x</i><sub>O</sub>", "м", sig=5),
            Column("y_O", "<i>y</i><sub>O</sub>", "м", sig=5)]
    if tr is not None:
        df["mu"] = [math.degrees(m) for m in tr["mu"]]
        cols.append(Column("mu", "μ<sub>min</sub>", "°", digits=1, sig=None))
    sec.table("Варианты решения", cols + [Column("mark", "Примечание")], df, id="tab-syn-var")


def _transmission(sec, kind, x, v, tr) -> None:
    """The least transmission angle of the accepted variant in closed form with numbers, against
    [μ] = 40°; when it is short, the best the free datum gives at the same K and stroke."""
    if tr is None:
        return
    mu = math.degrees(tr["mu_min"])
    if kind == "crank_rocker":
        sec.paragraph("Угол передачи μ между шатуном AB и коромыслом CB наименьший или наибольший, когда "
                      "кривошип лежит на линии центров OC, |AC|&nbsp;=&nbsp;d&nbsp;∓&nbsp;a [2]; расстояние между "
                      f"центрами вращения кривошипа и коромысла d&nbsp;=&nbsp;|OC|&nbsp;=&nbsp;{_datum(x, 'd', v['d'])}&nbsp;м:")
        forms = [Formula(r"\cos\mu_{1,2} = \frac{b^2 + l_{CB}^2 - (d \mp a)^2}{2 b\, l_{CB}}")]
        for i, s_ in ((1, v["d"] - v["a"]), (2, v["d"] + v["a"])):
            cg = (v["b"] ** 2 + v["c"] ** 2 - s_ * s_) / (2 * v["b"] * v["c"])
            c_ = _g(x, "c", v["c"], 4)
            forms.append(Formula(rf"\cos\mu_{i}", rf"\frac{{{_t(v['b'], 4)}^2 + {c_}^2 - {_t(s_, 4)}^2}}"
                                 rf"{{2 \cdot {_t(v['b'], 4)} \cdot {c_}}}",
                                 rf"{tex_num(cg, sig=4)},\quad \mu_{i} = "
                                 rf"{tex_num(math.degrees(math.acos(max(-1.0, min(1.0, cg)))), digits=1)}^{{\circ}}"))
        sec.formula(*forms)
        sec.paragraph(f"Наименьший угол передачи (угол больше 90° заменяется смежным) μ<sub>min</sub>&nbsp;=&nbsp;"
                      f"{fmt(mu, digits=1)}°.")
        change = "межосевое расстояние"
    else:
        sec.paragraph("Угол передачи μ между шатуном и нормалью к направляющей наименьший, когда кривошип "
                      "перпендикулярен направляющей со стороны смещения [2]:")
        sec.formula(r"\cos\mu_{\min} = \frac{a + e}{b}",
                    rf"\frac{{{_t(v['a'])} + {_g(x, 'e', abs(v['e']))}}}{{{_t(v['b'])}}}",
                    rf"{tex_num((v['a'] + abs(v['e'])) / v['b'], sig=4)};\ \mu_{{\min}} = "
                    rf"{tex_num(mu, digits=1)}^{{\circ}}")
        change = "отношение λ&nbsp;=&nbsp;a/b"
    if mu >= MU_ALLOWED:
        sec.paragraph(f"μ<sub>min</sub>&nbsp;=&nbsp;{fmt(mu, digits=1)}° ≥ [μ]&nbsp;=&nbsp;{fmt(MU_ALLOWED, digits=0)}°: "
                      "условие передачи движения выполнено.")
        return
    bm, bv = math.degrees(tr["best_mu"]), tr["best"]
    text = (f"μ<sub>min</sub>&nbsp;=&nbsp;{fmt(mu, digits=1)}° &lt; [μ]&nbsp;=&nbsp;{fmt(MU_ALLOWED, digits=0)}°: "
            f"механизм с такими размерами работает с большими реакциями в парах и опасностью заклинивания. "
            f"При тех же K и {'ψ, l<sub>CB</sub>' if kind == 'crank_rocker' else 'H'} свободно только "
            f"{change}; наибольший μ<sub>min</sub>&nbsp;=&nbsp;{fmt(bm, digits=1)}° получается при ")
    if kind == "crank_rocker":
        text += (f"d&nbsp;=&nbsp;{fmt(bv['d'], sig=3)}&nbsp;м (a&nbsp;=&nbsp;{fmt(bv['a'], sig=3)}&nbsp;м, "
                 f"b&nbsp;=&nbsp;{fmt(bv['b'], sig=3)}&nbsp;м)")
    else:
        text += (f"λ&nbsp;=&nbsp;{fmt(bv['lam'], sig=3)} (a&nbsp;=&nbsp;{fmt(bv['a'], sig=3)}&nbsp;м, "
                 f"b&nbsp;=&nbsp;{fmt(bv['b'], sig=3)}&nbsp;м, e&nbsp;=&nbsp;{fmt(bv['e'], sig=3)}&nbsp;м)")
    text += ((": это положение центра кривошипа и рекомендуется принять." if kind == "crank_rocker" else
              ": эти размеры и рекомендуется принять.") if bm >= MU_ALLOWED else
             f"; и этого мало, поэтому условие μ ≥ {fmt(MU_ALLOWED, digits=0)}° требует уменьшить "
             f"{'K или размах ψ' if kind == 'crank_rocker' else 'K (при заданных K и H угол μ зависит только от λ)'}.")
    sec.paragraph(text)


def _check(sec, study, sy) -> None:
    chk = sy.check
    if not chk or chk.get("extremes") != 2:
        return
    angular = chk["column"].startswith("phi_")
    target = sy.target_stroke()
    what = "размах" if angular else "ход"
    deg = math.degrees if angular else (lambda z: z)
    unit = "°" if angular else "&nbsp;м"
    dev = max(abs(chk["stroke"] - target) / abs(target), abs(chk["K"] - sy.inputs["K"]) / sy.inputs["K"]) * 100
    sec.paragraph(
        f"Проверка. Механизм с найденными размерами рассчитан кинематическим анализом; крайние положения "
        f"выходного звена ({escape(chk['title'])}) — положения, где его аналог скорости обращается в нуль. "
        f"Получены {what} {_like(deg(chk['stroke']), deg(target))}{unit} (задан {as_written(deg(target))}{unit}) и "
        f"K&nbsp;=&nbsp;{_like(chk['K'], sy.inputs['K'])} "
        f"(задан {as_written(sy.inputs['K'])}); расхождение "
        + ("менее 10<sup>−6</sup>&nbsp;%" if dev < 1e-6 else f"{fmt(dev, sig=2)}&nbsp;%") + ": синтез выполнен верно.")


def _like(value: float, given: float) -> str:
    """A checked value to the given's own decimals when it agrees with it to a twentieth of the
    last digit (размах 50° at ψ = 50°, not 50,0000°), else to four significant digits, so that a
    discrepancy shows."""
    written = as_written(given)
    decimals = len(written.split(",")[1]) if "," in written else 0
    if abs(value - given) < 0.05 * 10.0 ** -decimals:
        return fmt(value, digits=decimals, sig=None)
    return fmt(value, sig=4)


def conclusion_lines(study) -> list[str]:
    sy = study.synthesis
    v = sy.chosen
    if sy.kind == "slotted_lever":
        s = (f"Синтез кулисного механизма: a&nbsp;=&nbsp;{fmt(v['a'], sig=4)}&nbsp;м, "
             f"l<sub>CD</sub>&nbsp;=&nbsp;{fmt(v['l'], sig=4)}&nbsp;м.")
    else:
        s = (f"Синтез ({SY.TITLES[sy.kind]}, K&nbsp;=&nbsp;{as_written(sy.inputs['K'])}): кривошип "
             f"a&nbsp;=&nbsp;{fmt(v['a'], sig=4)}&nbsp;м, шатун b&nbsp;=&nbsp;{fmt(v['b'], sig=4)}&nbsp;м"
             + (f" (вариант {v['variant']} из {len(sy.variants)})." if len(sy.variants) > 1 else "."))
    tr = sy.transmission
    if tr is not None and math.degrees(tr["mu_min"]) < MU_ALLOWED and tr["best_mu"] > tr["mu_min"]:
        bv = tr["best"]
        datum = (f"межосевое расстояние d&nbsp;=&nbsp;{fmt(bv['d'], sig=3)}&nbsp;м" if sy.kind == "crank_rocker"
                 else f"λ&nbsp;=&nbsp;{fmt(bv['lam'], sig=3)}")
        s += (f" Наименьший угол передачи синтезированного механизма {fmt(math.degrees(tr['mu_min']), digits=1)}° "
              f"меньше допускаемого {fmt(MU_ALLOWED, digits=0)}°; при тех же K и "
              f"{'размахе' if sy.kind == 'crank_rocker' else 'ходе'} его можно поднять до "
              f"{fmt(math.degrees(tr['best_mu']), digits=1)}°, приняв {datum} (раздел {ref('sec-synthesis')})"
              + ("." if math.degrees(tr["best_mu"]) >= MU_ALLOWED else
                 f", но не до {fmt(MU_ALLOWED, digits=0)}°: нужно уменьшить "
                 f"{'K или размах ψ' if sy.kind == 'crank_rocker' else 'K'}."))
    return [s]
