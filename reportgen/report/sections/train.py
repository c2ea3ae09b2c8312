"""Section «Синтез планетарного механизма»: the tooth-number selection with every condition (when
asked), the ratio by Willis (stage by stage, each mesh's carrier held), the check by the velocity
picture and the plan of angular velocities, the graphical ratio against Willis in %.

``conclusion_lines(study)`` gives the lines of the ЗАКЛЮЧЕНИЕ about the train."""
from __future__ import annotations

import math
from fractions import Fraction

import pandas as pd
from markupsafe import Markup, escape

from ...analysis.train import FRAME
from ...analysis.train_select import assembly, k_of, poly_tex
from ...scenes.train import POLE_MM, SHORT_MM, stage_plans, train_picture
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


def _exact_tex(q: Fraction) -> str:
    """An exact ratio's value in a formula: an integer as it is («6», not «6,000000»), else to 7 digits."""
    return str(q.numerator) if q.denominator == 1 else tex_num(float(q), sig=7)


def _exact_text(q: Fraction) -> str:
    """An exact ratio's value in prose: an integer as it is, else to 7 digits."""
    return str(q.numerator).replace("-", "−") if q.denominator == 1 else fmt(float(q), sig=7)


def _direct_text(u: float, exact: Fraction) -> str:
    """The ratio by the poles' velocities (floating point) in prose: whole, as the exact ratio, where it
    agrees with a whole exact ratio to 10⁻⁹; else to 7 digits as the rest of the note."""
    if exact.denominator == 1 and abs(u - exact.numerator) <= 1e-9 * max(1.0, abs(u)):
        return _exact_text(exact)
    return fmt(u, sig=7)


def _ratio_column(rows) -> dict:
    """The format of the ratios' column: whole numbers when every set gives a whole ratio, else 6 digits."""
    whole = rows and all(abs(r["u"] - round(r["u"])) < 1e-12 for r in rows)
    return {"digits": 0, "sig": None} if whole else {"sig": 6}


def _z(name: str) -> str:
    return rf"z_{{{name}}}"


def prime(name: str) -> str:
    """A wheel's name in text as the textbook writes it: the case's «2'» as «2′» (TeX sets its
    own prime in the formulas)."""
    return name.replace("'", "′")


def _zh(name: str) -> str:
    """z with the wheel's name as a subscript in the note's text: <i>z</i><sub>2′</sub>."""
    return f"<i>z</i><sub>{prime(name)}</sub>"


def given(study) -> str:
    """The planetary train's data in one sentence for the assignment page."""
    tr = study.train
    m = tr.model
    text = Markup("Планетарный механизм: входное звено {}, выходное {}, {}").format(
        m.inp, m.out, _fixed_text(m.fixed))
    if tr.candidates:
        text += Markup("; передаточное отношение <i>u</i>&nbsp;=&nbsp;{}, число сателлитов {}; числа зубьев "
                       "подбираются").format(as_written(tr.opts['target']), _k_text(tr.opts['planets']))
    else:
        text += "; числа зубьев колёс заданы"
    return text + "."


def _fixed_text(fixed) -> Markup:
    """«неподвижное звено 3» / «неподвижные звенья 3, 6» / «неподвижных звеньев нет»."""
    if not fixed:
        return Markup("неподвижных звеньев нет")
    return Markup("{} {}").format("неподвижное звено" if len(fixed) == 1 else "неподвижные звенья",
                                  ", ".join(fixed))


def build(study) -> Section:
    tr = study.train
    m = tr.model
    sec = Section("Синтез планетарного механизма", "sec-train")
    moving = [n for n in m.members if n not in m.fixed]
    k = tr.opts["planets"]
    many = any(k_of(k, h) > 1 for h in set(m.axes.values()) if h != FRAME)
    sec.paragraph(Markup("Входное звено — {}, выходное — {}, {}. Механизм состоит из {} и {}{}; {}.").format(
        m.inp, m.out, _fixed_text(m.fixed), plural(len(m.wheels), "колеса", "колёс", "колёс"),
        plural(len(moving), "подвижного звена", "подвижных звеньев", "подвижных звеньев"),
        " (одинаковые сателлиты водила считаются одним звеном)" if many else "",
        plural(len(m.meshes), "зацепление", "зацепления", "зацеплений")))
    if tr.candidates:
        _selection(sec, tr)
    _wheels(sec, tr)
    _willis(sec, tr)
    _picture(sec, tr)
    return sec


def _selection(sec: Section, tr) -> None:
    """Tooth-number selection: the conditions written for this train (ratio as a function of the
    tooth numbers, coaxiality, assembly, neighbourhood, undercut and internal meshes), the table
    of sets with the checks, the accepted set's checks with numbers."""
    s = sec.subsection("Подбор чисел зубьев", "sec-train-select")
    sel, m, k = tr.selector, tr.model, tr.opts["planets"]
    ktext = _k_text(k)
    opt = tr.opts["select"]
    acc = tr.candidates[0]
    z = {w.name: w.z for w in m.wheels.values()}
    chosen = ", ".join(_zh(w) for w in sel.unknown)
    s.paragraph(
        f"Числа зубьев {chosen} подбираются перебором под передаточное отношение "
        f"<i>u</i><sub>{m.inp}{m.out}</sub> = {as_written(tr.opts['target'])} (допуск "
        f"{as_written(tr.opts['tolerance'] * 100)} %) при числе сателлитов {ktext}. Передаточное "
        f"отношение как функция чисел зубьев — совместное решение уравнений Виллиса всех зацеплений "
        f"(подраздел {ref('sec-train-willis')}) по правилу Крамера:")
    s.formula(rf"u_{{{m.inp}\,{m.out}}} = \frac{{{poly_tex(sel.num, sel.order)}}}{{{poly_tex(sel.den, sel.order)}}}")
    if sel.equations:
        s.paragraph("Условия соосности — равенство межосевых расстояний в каждом замкнутом контуре осей "
                    "(модуль сокращён):")
        s.formula(*[Formula(rf"{_form(p, sel.order)} = {_form(c, sel.order)}") for _, p, c in sel.equations])
    if sel.dependent:
        s.paragraph("Из них выражаются числа зубьев " + ", ".join(_zh(d) for d in sel.dependent)
                    + "; остальные перебираются от " + f"{sel.z_from} до {sel.z_max}:")
        s.formula(*[Formula(rf"z_{{{d}}} = {_affine(c0, cf, sel.order)}") for d, (c0, cf) in sel.dependent.items()])
    _assembly_text(s, tr, k)
    s.paragraph(
        f"Условие соседства: окружности вершин соседних сателлитов не пересекаются, "
        f"sin(π/<i>k</i>) &gt; (<i>z</i><sub>с</sub> + 2<i>h</i><sub>a</sub><sup>*</sup>)/(2<i>a</i><sub>w</sub>/<i>m</i>), "
        f"где <i>z</i><sub>с</sub> — наибольшее колесо сателлита, <i>a</i><sub>w</sub> — радиус его оси. "
        f"Подрезание: у колёс с внешними зубьями <i>z</i> ≥ {opt['z_min']}; внутреннее зацепление: "
        f"<i>z</i><sub>вн</sub> − <i>z</i> ≥ {opt['dz_internal']} и проверки ГОСТ 19274-73 для колёс без "
        f"смещения (вершина колеса вне основной окружности, нет интерференции у ножек и вершин). "
        f"Наборы, удовлетворяющие соосности и допуску, упорядочены по габариту — наибольшему диаметру, "
        f"занимаемому колёсами, max(2|<i>y</i><sub>ц</sub>| + <i>z</i>) в модулях (<i>y</i><sub>ц</sub> — "
        f"расстояние центра колеса от центральной оси), затем по сумме чисел зубьев; принят первый "
        f"набор, выдержавший все проверки. В таблице {ref('tab-train-select')} — принятые наборы и "
        f"отвергнутые (ближайшие к принятым по габариту, по каждой причине) с причинами отказа.")
    rows = []
    for c in tr.candidates + tr.rejected:
        rows.append({"set": "/".join(str(c.z[w]) for w in sel.unknown), "u": c.u,
                     "du": (c.u - tr.opts["target"]) / tr.opts["target"] * 100, "size": c.size,
                     "asm": "; ".join(_asm_value(ok, qs) for _, ok, qs in c.assembly) or "—",
                     "nb": ("; ".join(f"{fmt(sv, sig=3)} {'>' if ok else '≤'} {fmt(r, sig=3)}"
                                      for *_, sv, r, ok in c.neighbours) or "—"),
                     "verdict": "годится" if c.ok else "; ".join(c.fails)})
    s.table("Наборы чисел зубьев и проверка условий", [
        Column("set", "/".join(_zh(w) for w in sel.unknown), fmt=str),
        Column("u", f"<i>u</i><sub>{m.inp}{m.out}</sub>", **_ratio_column(rows)), Column("du", "Δ<i>u</i>", "%", sig=2),
        Column("size", "Габарит, модулей", digits=0, sig=None), Column("asm", "Сборка", fmt=str),
        Column("nb", "Соседство, sin(π/<i>k</i>)", fmt=str), Column("verdict", "Заключение", fmt=str)],
        pd.DataFrame(rows), id="tab-train-select", highlight_rows=[0])
    s.paragraph("Проверка принятого набора (" + ", ".join(f"{_zh(w)} = {acc.z[w]}" for w in sel.unknown)
                + "):")
    fr = acc.u_exact
    # the ratio with the numbers of teeth substituted into the closed form (1.1), then as a fraction
    forms = [Formula(rf"u_{{{m.inp}\,{m.out}}}",
                     rf"\frac{{{poly_tex(sel.num, sel.order, z)}}}{{{poly_tex(sel.den, sel.order, z)}}}",
                     (rf"\frac{{{fr.numerator}}}{{{fr.denominator}}} = " if fr.denominator != 1 else "")
                     + _exact_tex(fr))]
    for (_, p, c) in sel.equations:
        forms.append(Formula(rf"{_form(p, sel.order)} = {_form(c, sel.order)}", rf"{_value(p, z)} = {_value(c, z)}"))
    for pl, (_, ok, qs) in zip(sel.planets, acc.assembly):
        for (c0, p0, s0), (cj, pj, sj), q in zip([pl.meshes[0]] * len(qs), pl.meshes[1:], qs):
            sym, num = _asm_tex(c0, p0, s0, cj, pj, sj, z, k_of(k, pl.carrier))
            forms.append(Formula(sym, num, _frac_tex(q)))
    for h, ax, sv, r, ok in acc.neighbours:
        forms.append(_neighbour_formula(tr, h, ax, sv, r, k_of(k, h)))
    s.formula(*forms)
    s.paragraph("Все условия выполнены; по принятым числам зубьев ниже построены схема и планы скоростей.")


def _neighbour_formula(tr, h: str, ax: str, sv: float, r: float, kh: int) -> Formula:
    """The neighbourhood condition of the satellites on axis ``ax`` of carrier ``h`` with the
    numbers substituted: sin(π/k) > (z_с + 2h_a*)/(2a_w/m), z_с the satellite's largest wheel
    (by tip diameter), a_w the radius of its axis (Попов, Тимофеев [2])."""
    m, y = tr.model, tr.positions
    ws = [w for w in m.wheels.values() if w.centre == ax]
    ha = tr.selector.ha
    w = max(ws, key=lambda w: w.m * (w.z + 2 * ha))
    two_a = 2 * abs(y[ax] - y[m.members[h]]) / w.m
    num = rf"\frac{{{w.z} + 2 \cdot {as_written(ha).replace(',', '{,}')}}}{{{_num(Fraction(two_a).limit_denominator(1000))}}}"
    rel = ">" if r < sv else r"\le"
    return Formula(rf"\sin\frac{{\pi}}{{{kh}}} = {tex_num(sv, sig=4)} {rel} "
                   rf"\frac{{z_{{{w.name}}} + 2h_a^*}}{{2a_w/m}}", num, tex_num(r, sig=4))


def _affine(c0, cf: dict, order: list) -> str:
    """z_dep = c0 + Σ c z as TeX."""
    t = _form(cf, order)
    if c0:
        t += (" + " if c0 > 0 else " - ") + _num(abs(c0))
    return t


def _value(form: dict, z: dict) -> str:
    return _num(sum(c * z[w] for w, c in form.items()))


def _asm_value(ok, qs) -> str:
    if ok is None:
        return "не проверялось"
    return ", ".join(str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}" for q in qs) or "—"


def _frac_tex(q) -> str:
    return str(q.numerator) if q.denominator == 1 else rf"\frac{{{q.numerator}}}{{{q.denominator}}}"


def _asm_tex(c0, p0, s0, cj, pj, sj, z, k) -> tuple[str, str]:
    """Кудрявцев's assembly quantity of one satellite with the central wheels c0 and cj (its wheels
    p0, pj; σ = ±1): symbolic and with numbers."""
    a, b = sj, -s0
    if a < 0:
        a, b = -a, -b
    op = "+" if b > 0 else "-"
    # a difference is written larger term first, so that it reads as the whole number it is (the
    # quantity's sign does not matter, the table prints its modulus): 3550 − 3430, not 3430 − 3550
    if op == "-" and (z[c0] < z[cj] if p0 == pj else z[pj] * z[c0] < z[p0] * z[cj]):
        c0, cj, p0, pj = cj, c0, pj, p0
    if p0 == pj:
        return (rf"\frac{{z_{{{c0}}} {op} z_{{{cj}}}}}{{k}}", rf"\frac{{{z[c0]} {op} {z[cj]}}}{{{k}}}")
    g = math.gcd(z[p0], z[pj])
    return (rf"\frac{{z_{{{pj}}}\,z_{{{c0}}} {op} z_{{{p0}}}\,z_{{{cj}}}}}{{k\cdot \mathrm{{НОД}}(z_{{{p0}}}, z_{{{pj}}})}}",
            rf"\frac{{{z[pj]} \cdot {z[c0]} {op} {z[p0]} \cdot {z[cj]}}}{{{k} \cdot {g}}}")


def _k_text(k) -> Markup:
    """«<i>k</i> = 3» or, per carrier, «<i>k</i><sub>H1</sub> = 3, <i>k</i><sub>H2</sub> = 4»."""
    if isinstance(k, int):
        return Markup("<i>k</i> = {}").format(k)
    return Markup(", ").join(Markup("<i>k</i><sub>{}</sub> = {}").format(h, v) for h, v in k.items())


def _assembly_text(s: Section, tr, k) -> None:
    sel = tr.selector
    if all(k_of(k, pl.carrier) <= 1 for pl in sel.planets):
        s.paragraph("Сателлит один (<i>k</i> = 1): условия сборки и соседства не накладываются.")
        return
    s.paragraph(
        "Условие сборки <i>k</i> сателлитов, равномерно расположенных по окружности: "
        "центральные колёса неподвижны, фаза зацепления венца сателлита <i>z</i><sub>c</sub> с центральным "
        "колесом <i>z</i><sub>a</sub> при переходе к соседнему месту (поворот линии центров на 2π/<i>k</i>) "
        "меняется на <i>z</i><sub>a</sub>/<i>k</i> шага; одинаковый блок сателлита встаёт на место, если "
        "поворотом на целое число зубьев обоих венцов можно согласовать все его зацепления: "
        "(<i>z</i><sub>d</sub><i>z</i><sub>a</sub> ± <i>z</i><sub>c</sub><i>z</i><sub>b</sub>)/(<i>k</i>·НОД(<i>z</i><sub>c</sub>, "
        "<i>z</i><sub>d</sub>)) — целое («+», когда одно из зацеплений внутреннее); для одновенцового сателлита "
        "(<i>c</i> = <i>d</i>) это (<i>z</i><sub>a</sub> ± <i>z</i><sub>b</sub>)/<i>k</i>, что совпадает с условием "
        "<i>z</i><sub>1</sub><i>u</i><sub>1H</sub>(1 + <i>kp</i>)/<i>k</i> — целое схемы 2K-H [2].")
    bad = [pl.member for pl in sel.planets if pl.coupled]
    if bad:
        s.paragraph("Для сателлитов " + ", ".join(bad) + ", зацепляющихся с другими сателлитами или несущих "
                    "свои сателлиты, условие сборки не проверяется.")


def _wheels(sec: Section, tr) -> None:
    m = tr.model
    df = pd.DataFrame([{"wheel": prime(w.name), "z": w.z, "m": w.m, "d": w.m * w.z, "member": w.member,
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


def _form(t: dict, order: list | None = None) -> str:
    """A linear form in the tooth numbers as TeX, positive terms first (then by ``order`` when
    given): «z_{2} - z_{1}»."""
    out = ""
    rank = (lambda w: order.index(w)) if order else (lambda w: 0)  # noqa: E731
    for w, c in sorted(t.items(), key=lambda wc: (wc[1] < 0, rank(wc[0]))):
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
                tail = (" Напечатанные в решении " + ", ".join(f"{_zh(w)} = {tr.model.wheels[w].z}" for w in same)
                        + f" совпадают с найденными: в численной подстановке ({nums}) части взяты в верном порядке, "
                          "ошибка только в буквенной записи.")
            sec.paragraph(f"При найденных числах зубьев обе части равны {_num(v)}." + tail)


def _willis(sec: Section, tr) -> None:
    s = sec.subsection("Передаточное отношение по формуле Виллиса", "sec-train-willis")
    m = tr.model
    frame = [m.mesh_carrier(a, b) == FRAME for a, b in m.meshes]
    held = ("водила" if not any(frame) else "стойки" if all(frame)
            else "водила; у колёс с неподвижными осями — стойки, и отношение угловых скоростей прямое")
    s.paragraph(f"Для каждого зацепления движение обращается относительно звена, на котором неподвижны оси "
                f"обоих колёс ({held}); внешнее зацепление даёт знак «−», внутреннее «+»:")
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
    s.paragraph(Markup("Совместное решение при ω<sub>{}</sub> = 1 и {} даёт:").format(
        m.inp, _fixed_text(m.fixed).replace("неподвижное звено", "неподвижном звене")
        .replace("неподвижные звенья", "неподвижных звеньях")))
    s.formula(rf"u_{{{m.inp}\,{m.out}}} = \frac{{\omega_{{{m.inp}}}}}{{\omega_{{{m.out}}}}}", frac,
              _exact_tex(fr))
    _willis_whole(s, tr)
    pr = tr.opts.get("printed", {})
    if "u" in pr:
        s.paragraph(f"В опубликованном решении напечатано <i>u</i> = {fmt(pr['u'], sig=6)}: там перемножены "
                    f"округлённые множители ступеней (например, 1 + 74/22 = 4,364), точное значение "
                    f"{fr.numerator}/{fr.denominator} = {_exact_text(fr)}, расхождение "
                    f"{fmt((pr['u'] - tr.ratio) / tr.ratio * 100, sig=2)} %.")
    if tr.opts["target"] is not None:
        s.paragraph(f"Отклонение от заданного <i>u</i> = {as_written(tr.opts['target'])}: "
                    f"{_pct(tr.scalars['train_u_error_pct'])} %.")


def whole_train_willis(tr) -> tuple[str, str, str, Fraction] | None:
    """The textbook form for a train with one carrier H as the output, one fixed central member
    b and a central input a: u_aH^(b) = 1 − u_ab^(H), u_ab^(H) = (ω_a − ω_H)/(ω_b − ω_H) the ratio
    of the train with the carrier held (Артоболевский [1], Попов, Тимофеев [2]).  Returns (a, b,
    H, u_ab^(H) exact) or None when the train is not of that shape."""
    m = tr.model
    carriers = {h for h in m.axes.values() if h != FRAME}
    if len(carriers) != 1 or len(m.fixed) != 1:
        return None
    h, b, a = next(iter(carriers)), m.fixed[0], m.inp
    if m.out != h or m.axes.get(m.members[h]) != FRAME or a == h:
        return None
    if m.members[a] != m.members[h] or m.members[b] != m.members[h]:
        return None
    return a, b, h, 1 - tr.ratio_fraction


def _willis_whole(s: Section, tr) -> None:
    w = whole_train_willis(tr)
    if w is None:
        return
    a, b, h, u = w

    def frac(q: Fraction) -> str:
        return rf"\frac{{{abs(q.numerator)}}}{{{q.denominator}}}" if q.denominator != 1 else str(abs(q.numerator))

    sign = "-" if u < 0 else ""
    s.paragraph(Markup("Тот же результат по формуле Виллиса для механизма в целом: при остановленном водиле {} "
                       "механизм становится рядовым, его передаточное отношение от {} к {} — произведение "
                       "отношений зацеплений со знаками, а при остановленном колесе {}:").format(h, a, b, b))
    s.formula(Formula(rf"u_{{{a}\,{b}}}^{{({h})}} = \frac{{\omega_{{{a}}} - \omega_{{{h}}}}}{{\omega_{{{b}}} - \omega_{{{h}}}}}",
                      rf"{sign}{frac(u)}", _exact_tex(u)),
              Formula(rf"u_{{{a}\,{h}}}^{{({b})}} = 1 - u_{{{a}\,{b}}}^{{({h})}}",
                      rf"1 {'+' if u < 0 else '-'} {frac(u)}",
                      (rf"\frac{{{tr.ratio_fraction.numerator}}}{{{tr.ratio_fraction.denominator}}} = " if
                       tr.ratio_fraction.denominator != 1 else "") + _exact_tex(tr.ratio_fraction)))


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
    far = [(x, fx) for (a, b, *_), fs in zip(st.stages, st.depths) for x, fx in zip((a, b), fs) if fx > 1]
    if far:
        s.paragraph(
            "Отрезок, который на горизонтали, удалённой от полюса на <i>h</i>&nbsp;=&nbsp;"
            f"{fmt(POLE_MM, digits=0)}&nbsp;мм, вышел бы короче {fmt(SHORT_MM, digits=0)}&nbsp;мм, отсекается на "
            "горизонтали, удалённой в <i>f</i> раз дальше (" + ", ".join(
                f"звено {escape(x)}: <i>f</i>&nbsp;=&nbsp;{fx}" for x, fx in far) + "): отрезки пропорциональны угловой "
            "скорости и полюсному расстоянию, поэтому каждый отрезок делится на своё <i>f</i>, а короткий отрезок "
            "читается с той же точностью 0,5&nbsp;мм, но в <i>f</i> раз длиннее.")
    s.figure("Планы угловых скоростей по ступеням", st.fig, 170, id="fig-train-stages")
    forms = [Formula(rf"u_{{{a}\,{b}}} = \frac{{(0{a})}}{{(0{b})}}",
                     rf"\frac{{{tex_num(sa, digits=1)}}}{{{tex_num(sb, digits=1)}}}", tex_num(sa / sb, sig=5))
             if fa == fb == 1 else
             Formula(rf"u_{{{a}\,{b}}} = \frac{{(0{a})/f_{{{a}}}}}{{(0{b})/f_{{{b}}}}}",
                     rf"\frac{{{tex_num(sa, digits=1)}/{fa}}}{{{tex_num(sb, digits=1)}/{fb}}}",
                     tex_num((sa / fa) / (sb / fb), sig=5))
             for (a, b, sa, sb), (fa, fb) in zip(st.stages, st.depths)]
    s.formula(*forms)
    prod = r" \cdot ".join(rf"u_{{{a}\,{b}}}" for a, b, *_ in st.stages)
    s.formula(rf"u^{{граф}}_{{{m.inp}\,{m.out}}} = {prod}", tex_num(st.u_graph, sig=5))
    s.paragraph(f"Расхождение графического и аналитического значений: {_pct(d)} % (отрезки планов "
                f"измерены с точностью 0,5 мм). Прямой расчёт по равенству скоростей в полюсах даёт "
                f"<i>u</i> = {_direct_text(tr.ratio_direct, tr.ratio_fraction)}, отличие от формулы Виллиса "
                f"{_pct(tr.scalars['train_u_discrepancy_pct'])} %.")


def conclusion_lines(study) -> list[str]:
    tr = study.train
    m = tr.model
    fr = tr.ratio_fraction
    zs = ", ".join(f"{_zh(w.name)} = {w.z}" for w in m.wheels.values())
    frac = f"{fr.numerator}/{fr.denominator}".replace("-", "−") if fr.denominator != 1 else None
    out = [f"Передаточное отношение планетарного механизма <i>u</i><sub>{m.inp}{m.out}</sub> = "
           + (f"{frac} = " if frac else "") + f"{_exact_text(fr)} ({zs})."]
    if tr.candidates:
        acc = tr.candidates[0]
        out.append(f"Числа зубьев подобраны перебором под <i>u</i> = {as_written(tr.opts['target'])} (отклонение "
                   f"{_pct(tr.scalars['train_u_error_pct'])} %) при {_k_text(tr.opts['planets'])}: выполнены условия "
                   f"соосности, сборки, соседства, отсутствия подрезания и интерференции; набор — наименьший "
                   f"по габариту (наибольший занимаемый колёсами диаметр {_size_text(tr, acc.size)}).")
        out += _judgement(tr)
    return out


def _size_text(tr, size: float) -> str:
    """The overall size in modules, and in mm when the wheels share one module: «59<i>m</i> = 147,5 мм»."""
    mods = {w.m for w in tr.model.wheels.values()}
    text = f"{_num(Fraction(size).limit_denominator(2))}<i>m</i>"
    return text + (f" = {as_written(size * mods.pop())}&nbsp;мм" if len(mods) == 1 else "")


def _judgement(tr) -> list[str]:
    """Engineering judgement on the selection: a suitable set nearer the target ratio at a larger
    size (the price of accuracy), and what the neighbourhood condition leaves for one satellite
    more (sin(π/(k + 1)) against the same (z_с + 2h_a*)/(2a_w/m))."""
    acc, target = tr.candidates[0], tr.opts["target"]
    out = []
    err = abs(acc.u - target)
    better = [c for c in tr.candidates[1:] if c.ok and abs(c.u - target) < err - 1e-12 * abs(target)]
    if better:
        c = min(better, key=lambda c: (abs(c.u - target), c.size))
        sel = tr.selector
        out.append(
            f"Точнее заданное отношение даёт набор {'/'.join(str(c.z[w]) for w in sel.unknown)} "
            f"(Δ<i>u</i> = {_pct((c.u - target) / target * 100)} %), но его габарит {_size_text(tr, c.size)} "
            f"больше на {fmt((c.size - acc.size) / acc.size * 100, digits=0)} %; отклонение принятого набора "
            f"{_pct(tr.scalars['train_u_error_pct'])} % в пределах допуска {as_written(tr.opts['tolerance'] * 100)} %, "
            f"поэтому принят меньший механизм.")
    k = tr.opts["planets"]
    z = {w.name: w.z for w in tr.model.wheels.values()}
    for h, ax, sv, r, ok in acc.neighbours:
        kh = k_of(k, h)
        nxt = math.sin(math.pi / (kh + 1))
        who = Markup(" водила {}").format(h) if not isinstance(k, int) else ""
        one = plural(kh + 1, "сателлит", "сателлита", "сателлитов")
        if nxt <= r:
            out.append(f"Число сателлитов{who} <i>k</i> = {kh} — наибольшее при этих колёсах: для {one} "
                       f"не выполняется условие соседства (sin(π/{kh + 1}) = {fmt(nxt, sig=3)} ≤ {fmt(r, sig=3)}).")
            continue
        asm = [assembly(pl, z, {h: kh + 1}) for pl in tr.selector.planets if pl.carrier == h]
        if all(a is not False for a, _ in asm):
            out.append(f"Условие соседства выполнено с запасом: при тех же числах зубьев можно поставить {one}{who} "
                       f"(sin(π/{kh + 1}) = {fmt(nxt, sig=3)} &gt; {fmt(r, sig=3)}, условие сборки при "
                       f"<i>k</i> = {kh + 1} выполнено) и снизить нагрузку на зуб сателлита в "
                       f"{fmt((kh + 1) / kh, sig=3)} раза.")
        else:
            q = "; ".join(_asm_value(a, qs) for a, qs in asm)
            out.append(f"Соседство допускает и {one}{who} (sin(π/{kh + 1}) = {fmt(nxt, sig=3)} &gt; "
                       f"{fmt(r, sig=3)}), но при <i>k</i> = {kh + 1} не выполнено условие сборки ({q} — не "
                       f"целое): для большего числа сателлитов нужен другой набор чисел зубьев.")
    return out
