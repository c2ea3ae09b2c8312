"""Section «Синтез кулачкового механизма» of the note (Артоболевский, гл. 24; Попов, Тимофеев,
гл. 6): the assignment, the laws with the diagrams, the minimum size by the phase portrait, the
pressure angle, the profile by inversion with its coordinate table, the conclusions."""
from __future__ import annotations

import math

import pandas as pd
from markupsafe import Markup

from ...analysis.cam import LAWS
from ...core import cams as K
from ...scenes.cam import (FlatRockerSize, LawDiagrams, PhasePortrait, PressureAngleGraph, ProfileDrawing,
                           follower_positions)
from ...scenes.draw import mu_text
from ...style.numbers import fmt, fmt_given, tex_num
from .common import as_written, tex_given
from ..russian import plural
from ..document import Column, Formula, Section, ref
from ..formulas import inline_math

NEEDS = ("cam",)
def TASK(study) -> str:
    """The assignment's clause: what sizes the cam by — the allowed pressure angles, or, for a flat
    face (ϑ ≡ 0 on a translating follower), the convexity of the profile ρ ≥ ρ_min (Артоболевский §26)."""
    cam = study.cam
    if cam.contact != "flat":
        by = "по допустимым углам давления"
    elif cam.flat_rocker and cam.face_offset > 0 and any(ph.allowed > 0 for ph in (cam.rise, cam.ret)):
        by = "по условию выпуклости профиля и допустимым углам давления"
    else:
        by = "по условию выпуклости профиля"
    return f"спроектировать кулачковый механизм: определить основные размеры {by} и построить профиль кулачка"

NORM_TEX = {  # normalised law f(x), x = φ/β
    "uniform": r"f = x",
    "cosine": r"f = \frac{1 - \cos \pi x}{2}",
    "sine": r"f = x - \frac{\sin 2\pi x}{2\pi}",
    "poly345": r"f = 10x^3 - 15x^4 + 6x^5",
    "poly4567": r"f = 35x^4 - 84x^5 + 70x^6 - 20x^7",
    "parabolic": r"f = 2x^2\ (x \le 1/2),\quad f = 1 - 2(1 - x)^2\ (x > 1/2)",
}


X_TEX = r"x = \varphi / \beta"
X1_TEX = r"x_1 = \nu/(1+\nu)"
R_TEX = r"r = \sqrt{(r_0 + s)^2 + s^{\prime 2}}"


def present(study) -> bool:
    """The section is built when the case has [cam]."""
    return study.root.has("cam")


def given(study) -> str:
    """The cam's data in one sentence for the assignment page."""
    cam = study.cam
    kind = "поступательным" if cam.follower == "translating" else "качающимся"
    contact = {"knife": "острием", "roller": "роликом", "flat": "плоской тарелкой"}[cam.contact]
    stroke = (f"ход толкателя h&nbsp;=&nbsp;{as_written(round(cam.h * 1000, 6))}&nbsp;мм" if cam.follower == "translating"
              else f"угол размаха коромысла ψ<sub>max</sub>&nbsp;=&nbsp;{_dg(cam.h)}, длина {_mg(cam.arm)}")
    names = {K.RISE: "удаления", K.DWELL_HIGH: "дальнего стояния", K.RETURN: "возвращения",
             K.DWELL_LOW: "ближнего стояния"}
    angles = ", ".join(f"{names[ph.kind]} {_dg(ph.length)}" for ph in cam.phases)
    text = (f"Кулачковый механизм с {kind} толкателем и {contact}: {stroke}; фазовые углы {angles}; "
            f"законы движения толкателя: на удалении — {_law_name(cam.rise)}, на возвращении — {_law_name(cam.ret)}")
    if cam.contact != "flat":
        text += (f"; допустимые углы давления {_dg(cam.rise.allowed)} и {_dg(cam.ret.allowed)}")
    if cam.omega is not None:
        text += f"; частота вращения кулачка {fmt_given(cam.omega * 30 / math.pi)}&nbsp;об/мин"
    return text + "."


def _mm(x, sig=4) -> str:
    return fmt(x * 1000, sig=sig, unit="мм")


def _mg(x) -> str:
    """A given length as the case writes it, in mm (18 мм, not 18,00 мм)."""
    return as_written(round(x * 1000, 6)) + "&nbsp;мм"


def _dg(x) -> str:
    """A given angle as the case writes it (100°, 22,5°; not 100,00°, nor 22,5° rounded to 22°)."""
    return as_written(round(math.degrees(x), 6)) + "°"


def _deg(x, digits=2) -> str:
    return fmt(math.degrees(x), digits=digits) + "°"


def _tmm(x) -> str:
    """A given length (m) in a TeX formula, in mm as the case writes it: «6», not «6{,}000»."""
    return tex_given(round(x * 1000, 6))


def _at(x) -> str:
    """A cam angle where something happens (an impact, an extremum): at most two decimals and no
    padding zeros, the float noise of ν/(1 + ν)·β rounded off first — 140°, 173,75° (not 173,7° in one
    sentence and 173,75° in the next), 177,06°."""
    return as_written(round(math.degrees(x), 2)) + "°"


def _t(x, sig=4, digits=None, unit=None) -> str:
    return tex_num(x, sig=sig, digits=digits, unit=unit)


def _im(tex: str):
    return inline_math(tex)


def build(study) -> Section:
    cam = study.cam
    sec = Section("Синтез кулачкового механизма", "sec-cam")
    _assignment(sec, cam)
    _laws(sec, study, cam)
    _size(sec, study, cam)
    if cam.contact != "flat" or (cam.flat_rocker and cam.face_offset > 0):
        _pressure(sec, study, cam)
    _profile(sec, study, cam)
    return sec


# ------------------------------------------------------------------------------------------
def _law_name(ph) -> str:
    name = LAWS[ph.law][0]
    if ph.law in ("sine", "parabolic") and ph.nu != 1:
        name += f", несимметричный (ν&nbsp;=&nbsp;{as_written(ph.nu)})"
    if ph.law == "trapezoidal":
        name += f" (доля участков нарастания {as_written(ph.ramp)})"
    return name


def _assignment(sec, cam) -> None:
    s = sec.subsection("Исходные данные", "sec-cam-data")
    kind = "поступательным толкателем" if cam.follower == "translating" else "качающимся толкателем (коромыслом)"
    contact = {"knife": "острием", "roller": "роликом", "flat": "плоской тарелкой"}[cam.contact]
    rot = "против хода часовой стрелки" if cam.k > 0 else "по ходу часовой стрелки"
    s.paragraph(f"Проектируется кулачковый механизм с {kind}, контактирующим с кулачком "
                f"{contact}. Кулачок вращается равномерно {rot}. Исходные данные приведены в таблице "
                f"{ref('tab-cam-data')}.")
    rows = []
    if cam.follower == "translating":
        rows.append(("Ход толкателя", "h", _mg(cam.h)))
    else:
        rows.append(("Угол размаха коромысла", "ψ<sub>max</sub>", _dg(cam.h)))
        if cam.flat_rocker:
            rows.append(("Смещение плоскости тарелки от оси качания", "d", _mg(cam.face_offset)))
        else:
            rows.append(("Длина коромысла", "l", _mg(cam.arm)))
    if cam.omega is not None:
        rows.append(("Угловая скорость кулачка", "ω", f"{fmt_given(cam.omega)}&nbsp;рад/с"
                     + f" ({fmt_given(cam.omega * 30 / math.pi)}&nbsp;об/мин)"))
    names = {K.RISE: ("Угол удаления", "φ<sub>у</sub>"), K.DWELL_HIGH: ("Угол дальнего стояния", "φ<sub>дс</sub>"),
             K.RETURN: ("Угол возвращения", "φ<sub>в</sub>"), K.DWELL_LOW: ("Угол ближнего стояния", "φ<sub>бс</sub>")}
    for ph in cam.phases:
        rows.append((*names[ph.kind], _dg(ph.length)))
    rows.append(("Закон движения на удалении", "—", _law_name(cam.rise)))
    rows.append(("Закон движения на возвращении", "—", _law_name(cam.ret)))
    if cam.contact != "flat" or (cam.flat_rocker and cam.face_offset > 0):
        for ph, nm, sym in ((cam.rise, "удалении", "у"), (cam.ret, "возвращении", "в")):
            if ph.allowed > 0:
                rows.append((f"Допустимый угол давления на {nm}", f"[ϑ<sub>{sym}</sub>]", _dg(ph.allowed)))
    if cam.contact == "flat":
        rows.append(("Наименьший радиус кривизны профиля", "ρ<sub>min</sub>", _mg(cam.rho_min)))
    if cam.r0_fixed is not None:
        rows.append(("Заданный радиус основной шайбы", "r<sub>0</sub>", _mg(cam.r0_fixed)))
    if cam.e_fixed is not None:
        rows.append(("Заданный эксцентриситет", "e", _mg(cam.e_fixed)))
    if cam.aw_fixed is not None:
        rows.append(("Заданное межосевое расстояние", "a<sub>w</sub>", _mg(cam.aw_fixed)))
    if cam.psi0_fixed is not None:
        rows.append(("Заданный начальный угол коромысла", "ψ<sub>0</sub>", _dg(cam.psi0_fixed)))
    if cam.roller_fixed is not None:
        rows.append(("Радиус ролика", "r<sub>р</sub>", _mg(cam.roller_fixed)))
    s.table("Исходные данные для синтеза кулачкового механизма",
            [Column("a", "Величина"), Column("b", "Обозначение", fmt=Markup), Column("c", "Значение", fmt=Markup)],
            pd.DataFrame(rows, columns=["a", "b", "c"]), id="tab-cam-data")


def _laws(sec, study, cam) -> None:
    s = sec.subsection("Законы движения толкателя", "sec-cam-laws")
    rocker = cam.follower == "rocker"
    S, H = (r"\psi", r"\psi_{max}") if rocker else ("s", "h")
    s.paragraph("Закон движения задан на каждой фазе безразмерной функцией f(x) относительного угла "
                f"{_im(X_TEX)} (β — угол фазы), f(0)&nbsp;=&nbsp;0, f(1)&nbsp;=&nbsp;1. "
                + ("Угол поворота коромысла" if rocker else "Перемещение толкателя")
                + " и его аналоги скорости и ускорения на удалении и возвращении:")
    s.formula(Formula(rf"{S} = {H}\, f(x),\quad {S}^{{\prime}} = \frac{{{H}}}{{\beta}} f^{{\prime}}(x),\quad "
                      rf"{S}^{{\prime\prime}} = \frac{{{H}}}{{\beta^2}} f^{{\prime\prime}}(x)",
                      where=[(r"\beta", "угол фазы удаления φ<sub>у</sub> или возвращения φ<sub>в</sub>, рад")],
                      label="eq-cam-law"),
              Formula(rf"{S} = {H}\,[1 - f(x)],\quad {S}^{{\prime}} = -\frac{{{H}}}{{\beta}} f^{{\prime}}(x),\quad "
                      rf"{S}^{{\prime\prime}} = -\frac{{{H}}}{{\beta^2}} f^{{\prime\prime}}(x)", label="eq-cam-law-ret"))
    fac, unit = (1.0, "") if rocker else (1000.0, "мм")
    for ph, title in ((cam.rise, "удалении"), (cam.ret, "возвращении")):
        beta = ph.length
        s1 = cam.analog_max(ph, 1) * fac
        s2 = cam.analog_max(ph, 2) * fac
        hh = cam.h * fac if not rocker else cam.h
        txt = (f"Закон движения на {title} — {_law_name(ph)}")
        if ph.law in NORM_TEX and not (ph.law in ("sine", "parabolic") and ph.nu != 1):
            txt += f": {_im(NORM_TEX[ph.law])}"
        elif ph.law in ("sine", "parabolic"):
            txt += (f"; точка перегиба при {_im(X1_TEX)}&nbsp;=&nbsp;{fmt(ph.x1, sig=4)}")
        s.paragraph(txt + f". Угол фазы β&nbsp;=&nbsp;{_dg(beta)}&nbsp;=&nbsp;{fmt(beta, sig=5)}&nbsp;рад. "
                    "Наибольшие значения аналогов:")
        u = r"\ \text{мм}" if not rocker else ""
        hw = _t(hh) if rocker else tex_given(round(hh, 6))     # the stroke as given; ψ_max in rad is computed
        fs = [Formula(rf"|{S}^{{\prime}}|_{{max}}", rf"{hw}{u} \cdot {_t(s1 * beta / hh, sig=5)} / {_t(beta, sig=5)}",
                      _t(s1, sig=4) + u),
              Formula(rf"|{S}^{{\prime\prime}}|_{{max}}",
                      rf"{hw}{u} \cdot {_t(s2 * beta * beta / hh, sig=5)} / {_t(beta, sig=5)}^2",
                      _t(s2, sig=4) + u)]
        if ph.law == "uniform":
            fs = fs[:1]
        s.formula(*fs)
    hard = [i for i in cam.impacts if i["kind"] == "hard"]
    soft = [i for i in cam.impacts if i["kind"] == "soft"]
    if not cam.impacts:
        s.paragraph("Аналоги скорости и ускорения непрерывны на всём цикле: удары отсутствуют.")
    if hard:
        s.paragraph("Аналог скорости терпит разрыв (ускорение бесконечно велико) при φ&nbsp;=&nbsp;"
                    + ", ".join(_at(i["phi"]) for i in hard) + ": в этих положениях возникают "
                    "<b>жёсткие удары</b>.")
    if soft:
        s.paragraph("Аналог ускорения терпит конечный разрыв при φ&nbsp;=&nbsp;"
                    + ", ".join(_at(i["phi"]) for i in soft) + ": в этих положениях возникают "
                    "<b>мягкие удары</b>.")
    sc = LawDiagrams()
    fig = sc.draw(study)
    scales = "; ".join(f"μ<sub>{lab}</sub>&nbsp;=&nbsp;{mu_text(mu)}&nbsp;{u or 'ед.'}/мм"
                       for lab, mu, u in sc.scales)
    s.paragraph(f"Диаграммы аналогов ускорения, скорости и перемещения построены на рисунке {ref('fig-cam-laws')} "
                f"в масштабах μ<sub>φ</sub>&nbsp;=&nbsp;{mu_text(sc.mu_phi)}&nbsp;град/мм; {scales}.")
    s.figure("Диаграммы аналогов ускорения, скорости и " + ("угла поворота коромысла" if rocker else
                                                            "перемещения толкателя"), fig.svg, fig.width_mm,
             id="fig-cam-laws")
    if cam.omega is not None:
        w = cam.omega
        v1m = max(cam.analog_max(ph, 1) for ph in (cam.rise, cam.ret))
        v2m = max(cam.analog_max(ph, 2) for ph in (cam.rise, cam.ret))
        vm, am = v1m * w, v2m * w * w
        vu, au = ("рад/с", "рад/с²") if rocker else ("м/с", "м/с²")
        s.paragraph("Истинные " + ("угловые скорость и ускорение коромысла" if rocker else
                                   "скорость и ускорение толкателя") + " при ω&nbsp;=&nbsp;const:")
        s.formula(Formula(r"v_{max} = \omega\,|s^{\prime}|_{max}" if not rocker else r"\omega_{2,max} = \omega\,|\psi^{\prime}|_{max}",
                          rf"{_t(w)} \cdot {_t(v1m, sig=4)}", _t(vm, sig=4, unit=vu)),
                  Formula(r"a_{max} = \omega^2 |s^{\prime\prime}|_{max}" if not rocker else r"\varepsilon_{2,max} = \omega^2 |\psi^{\prime\prime}|_{max}",
                          rf"{_t(w)}^2 \cdot {_t(v2m, sig=4)}", _t(am, sig=4, unit=au)))


def _size(sec, study, cam) -> None:
    s = sec.subsection("Определение основных размеров механизма", "sec-cam-size")
    syn = cam.synthesis
    if cam.flat_rocker:
        _size_flat_rocker(s, study, cam)
        return
    if cam.contact == "flat":
        m, p, need = cam.flat_min
        s.paragraph("Для толкателя с плоской тарелкой угол давления постоянен (ϑ&nbsp;=&nbsp;0), а размер кулачка "
                    "ограничивается условием выпуклости профиля: радиус кривизны профиля")
        s.formula(Formula(r"\rho = r_0 + s + s^{\prime\prime} \ge \rho_{min}", label="eq-cam-rho"),
                  Formula(r"r_0 \ge \rho_{min} - (s + s^{\prime\prime})_{min}",
                          rf"{_tmm(cam.rho_min)} - \left({_t(m * 1000)}\right)",
                          _t(need * 1000, unit="мм")))
        s.paragraph(f"Наименьшее значение (s&nbsp;+&nbsp;s″) достигается при φ&nbsp;=&nbsp;{_at(p)}. "
                    + (f"Принят заданный радиус r<sub>0</sub>&nbsp;=&nbsp;{_mm(syn.r0)}"
                       + (" — условие выпуклости выполнено." if syn.r0 >= need - 1e-12 else
                          " — условие выпуклости <b>не выполнено</b>.")
                       if syn.governing == "fixed" else _accepted_words(cam) + "."))
        hard = [i for i in cam.impacts if i["kind"] == "hard"]
        if hard:
            s.paragraph("В положениях жёсткого удара (φ&nbsp;=&nbsp;" + ", ".join(_at(i["phi"]) for i in hard)
                        + ") аналог скорости терпит разрыв: точка касания перескакивает по тарелке, и профиль имеет "
                          "там прямолинейный участок или излом; условие выпуклости проверено между ними.")
        lo, hi = cam.s1_extremes
        s.paragraph("Точка касания тарелки с кулачком смещена от оси толкателя на s′, поэтому ширина тарелки "
                    "должна быть не меньше")
        s.formula(Formula(r"b \ge s^{\prime}_{max} - s^{\prime}_{min}",
                          rf"{_t(hi * 1000)} - \left({_t(lo * 1000)}\right)",
                          _t(cam.face_width * 1000, unit="мм")))
        return
    if cam.follower == "translating":
        s.paragraph("Угол давления ϑ — угол между нормалью к профилю в точке контакта и скоростью толкателя. "
                    "Из плана скоростей обращённого движения")
        s.formula(Formula(r"\operatorname{tg} \vartheta = \frac{s^{\prime} - e}{s_0 + s},\qquad r_0 = \sqrt{s_0^2 + e^2}",
                          where=[("e", "эксцентриситет (смещение оси толкателя), мм"),
                                 ("s_0", "расстояние от центра кулачка до начального положения толкателя вдоль его оси, мм")],
                          label="eq-cam-theta"))
        s.paragraph("Условия ϑ&nbsp;≤&nbsp;[ϑ<sub>у</sub>] на удалении и −ϑ&nbsp;≤&nbsp;[ϑ<sub>в</sub>] на возвращении "
                    "означают, что центр кулачка лежит на фазовом портрете s(s′) ниже лучей, проведённых через каждую "
                    "точку портрета под допустимыми углами к оси s. Определяющие лучи касаются портрета; точка касания "
                    "находится как корень уравнения")
        s.formula(Formula(r"s^{\prime\prime} = s^{\prime} \operatorname{tg}[\vartheta_у]\ \ \text{(удаление)},\qquad "
                          r"s^{\prime\prime} = -s^{\prime} \operatorname{tg}[\vartheta_в]\ \ \text{(возвращение)}",
                          label="eq-cam-tangent"))
        for nm, ph, p in (("у", cam.rise, syn.phi_rise), ("в", cam.ret, syn.phi_return)):
            v = cam._at(p)
            s.paragraph(f"Касание на {'удалении' if nm == 'у' else 'возвращении'}: φ&nbsp;=&nbsp;{_deg(p, 3)}, "
                        f"s&nbsp;=&nbsp;{_mm(v[0])}, s′&nbsp;=&nbsp;{_mm(v[1])}, s″&nbsp;=&nbsp;{_mm(v[2])}.")
        if syn.governing == "fixed":
            s.paragraph(_fixed_sizes(cam, "радиус основной шайбы и эксцентриситет"))
        else:
            gov = {"rise": "луч удаления", "return": "луч возвращения",
                   "both": "точка пересечения лучей удаления и возвращения"}[syn.governing]
            s.paragraph(f"Наименьший радиус r<sub>0</sub> даёт ближайшая к точке B<sub>0</sub> точка допустимой "
                        f"области ({gov}), рисунок {ref('fig-cam-portrait')}:")
        ex = syn.exact or syn
        s.formula(Formula("e", None, _t(ex.e * 1000, unit="мм")),
                  Formula("s_0", None, _t(ex.s0 * 1000, unit="мм")),
                  Formula(r"r_0 = \sqrt{s_0^2 + e^2}", rf"\sqrt{{{_t(ex.s0 * 1000)}^2 + {_t(ex.e * 1000)}^2}}",
                          _t(ex.r0 * 1000, unit="мм")))
        s.paragraph(f"Приближённый способ (лучи через точки наибольшего аналога скорости) даёт "
                    f"r<sub>0</sub>&nbsp;=&nbsp;{_mm(syn.r0_approx)}, e&nbsp;=&nbsp;{_mm(syn.e_approx)}; отличие от точного "
                    f"решения {fmt((syn.r0_approx / ex.r0 - 1) * 100, digits=2, sign=True)}&nbsp;%: при этих размерах "
                    "угол давления превысил бы допустимый.")
        _accept(s, cam)
    else:
        s.paragraph("Для коромысла точки фазового портрета D строятся на линии коромысла: от точки B откладывается "
                    "отрезок, равный аналогу скорости lψ′. Через каждую точку D проводится луч под углом (90° − [ϑ]) "
                    "к коромыслу; центр кулачка должен лежать по ту сторону всех лучей, где угол давления")
        s.formula(Formula(r"\operatorname{tg}\vartheta = \frac{l\psi^{\prime} \mp \overline{OB}\cdot\overline{r}}"
                          r"{\overline{OB}\cdot\overline{u}} \le \operatorname{tg}[\vartheta]",
                          where=[(r"\overline{r}, \overline{u}", "единичные векторы вдоль коромысла и по скорости точки B"),
                                 ("l", "длина коромысла, мм")], label="eq-cam-theta-rocker"))
        fixed = syn.governing == "fixed"
        if fixed:
            s.paragraph("Определяющие лучи касаются портрета; точки касания найдены из условия стационарности "
                        "ограничения по углу поворота кулачка. "
                        + _fixed_sizes(cam, "межосевое расстояние и начальный угол коромысла"))
        else:
            s.paragraph("Определяющие лучи касаются портрета; точки касания найдены из условия стационарности "
                        f"ограничения по углу поворота кулачка, центр O выбран как ближайшая к B<sub>0</sub> точка "
                        f"допустимой области (рисунок {ref('fig-cam-portrait')}):")
        ex = syn.exact or syn
        aw = tex_given(round(ex.a_w * 1000, 6)) if fixed else _t(ex.a_w * 1000)
        p0 = tex_given(round(math.degrees(ex.psi0), 6)) if fixed else _t(math.degrees(ex.psi0), sig=5)
        l_ = tex_given(round(cam.arm * 1000, 6))
        s.formula(*([] if fixed else [Formula("a_w", None, _t(ex.a_w * 1000, unit="мм")),
                                      Formula(r"\psi_0", None, _t(math.degrees(ex.psi0), sig=5, unit="°"))]),
                  Formula(r"r_0 = \sqrt{a_w^2 + l^2 - 2 a_w l \cos\psi_0}",
                          rf"\sqrt{{{aw}^2 + {l_}^2 - 2 \cdot {aw} \cdot {l_} \cos {p0}^\circ}}",
                          _t(ex.r0 * 1000, unit="мм")))
        s.paragraph(f"Точки касания: на удалении φ&nbsp;=&nbsp;{_deg(syn.phi_rise, 3)}, на возвращении "
                    f"φ&nbsp;=&nbsp;{_deg(syn.phi_return, 3)}.")
        if syn.governing != "fixed":
            s.paragraph(f"Приближённый способ (лучи через точки наибольшего аналога скорости, штриховые линии) даёт "
                        f"r<sub>0</sub>&nbsp;=&nbsp;{_mm(syn.r0_approx)}, a<sub>w</sub>&nbsp;=&nbsp;{_mm(syn.a_w_approx)}; "
                        f"отличие r<sub>0</sub> от точного решения "
                        f"{fmt((syn.r0_approx / ex.r0 - 1) * 100, digits=2, sign=True)}&nbsp;%.")
        _accept(s, cam)
    sc = PhasePortrait()
    fig = sc.draw(study)
    s.figure(f"Фазовый портрет, определяющие лучи и область допустимого расположения центра кулачка "
             f"(μ&nbsp;=&nbsp;{fmt(fig.mu * 1000, sig=3)}&nbsp;мм/мм)", fig.svg, fig.width_mm, id="fig-cam-portrait")


def _accepted_words(cam) -> str:
    """«Принимаем r₀ = 29 мм (наименьший 28,62 мм, округлён в бо́льшую сторону до целого
    миллиметра)»: the size the profile is built with (analysis.cam.Cam.synthesis)."""
    syn = cam.synthesis
    if syn.exact is None:
        return f"Принят r<sub>0</sub>&nbsp;=&nbsp;{_mm(syn.r0)}"
    step = ("целого миллиметра" if abs(cam.r0_round - 0.001) < 1e-12 else
            f"значения, кратного {_mg(cam.r0_round)}")
    return (f"Принимаем r<sub>0</sub>&nbsp;=&nbsp;{_mg(syn.r0)} (наименьший {_mm(syn.exact.r0)}, округлён в "
            f"бо́льшую сторону до {step})")


def _accept(s, cam) -> None:
    """The accepted r₀ and the sizes that follow it (analysis.cam.Cam.synthesis says how each
    kind keeps its centre in the admissible region); nothing when r₀ is the least one."""
    syn = cam.synthesis
    if syn.exact is None:
        return
    r0 = tex_given(round(syn.r0 * 1000, 6))
    if cam.flat_rocker:
        s.paragraph(_accepted_words(cam) + "; при том же ψ<sub>0</sub> межосевое расстояние увеличивается (оба "
                    "условия ограничивают a<sub>w</sub> снизу):")
        s.formula(Formula(r"a_w = \frac{r_0 + d}{\sin\psi_0}",
                          rf"\frac{{{r0} + {_tmm(cam.face_offset)}}}{{\sin {_t(math.degrees(syn.psi0), sig=5)}^\circ}}",
                          _t(syn.a_w * 1000, unit="мм")))
    elif cam.follower == "translating":
        s.paragraph(_accepted_words(cam) + f"; при том же e&nbsp;=&nbsp;{_mm(syn.e)} центр кулачка отодвигается "
                    "вдоль оси толкателя вглубь допустимой области:")
        s.formula(Formula(r"s_0 = \sqrt{r_0^2 - e^2}", rf"\sqrt{{{r0}^2 - {_t(syn.e * 1000)}^2}}",
                          _t(syn.s0 * 1000, unit="мм")))
    else:
        s.paragraph(_accepted_words(cam) + "; центр O отодвигается от B<sub>0</sub> по прямой B<sub>0</sub>O "
                    "вглубь допустимой области:")
        s.formula(Formula("a_w", None, _t(syn.a_w * 1000, unit="мм")),
                  Formula(r"\psi_0", None, _t(math.degrees(syn.psi0), sig=5, unit="°")))
    s.paragraph("С принятыми размерами построены профиль кулачка, углы давления и чертёж механизма.")


def _fixed_sizes(cam, what: str) -> str:
    """The given sizes of a cam checked, not chosen: where their centre O lies with respect to the
    region the rays allow (the pressure-angle check of the next subsection says by how much)."""
    inside = cam.required_size is None
    return (f"Размеры заданы ({what}), поэтому синтез заменяется проверкой: центр O, построенный по ним "
            f"(рисунок {ref('fig-cam-portrait')}), лежит "
            + ("внутри допустимой области." if inside else "<b>вне допустимой области</b> — угол давления "
               "превысит допустимый (подраздел " + ref("sec-cam-theta") + ")."))


def _required_words(cam) -> str:
    """What the sizes must become when the given ones fail the pressure-angle check, with numbers."""
    req = cam.required_size
    if req is None:
        return "размеры механизма нужно увеличить"
    if cam.follower == "translating":
        return (f"при заданном e&nbsp;=&nbsp;{_mm(req['e'])} радиус основной шайбы нужно увеличить до "
                f"r<sub>0</sub>&nbsp;≥&nbsp;{_mm(req['r0'])} (заданный {_mg(cam.synthesis.r0)})")
    return (f"нужно принять наименьшие по допустимым углам давления размеры a<sub>w</sub>&nbsp;=&nbsp;"
            f"{_mm(req['a_w'])}, ψ<sub>0</sub>&nbsp;=&nbsp;{_deg(req['psi0'])}, r<sub>0</sub>&nbsp;=&nbsp;{_mm(req['r0'])} "
            f"вместо заданных {_mg(cam.synthesis.a_w)}, {_dg(cam.synthesis.psi0)} (r<sub>0</sub>&nbsp;=&nbsp;"
            f"{_mm(cam.synthesis.r0)})")


def _q_tex(cam) -> str:
    """q = 1 − kψ′ with the sign of this cam's rotation."""
    return r"1 - \psi^{\prime}" if cam.k > 0 else r"1 + \psi^{\prime}"


def _flat_rocker_failures(cam) -> list[str]:
    """What a given a_w of a flat-faced rocker fails: convexity, the allowed pressure angle."""
    a, fr = cam.synthesis.a_w, cam.fr
    out = []
    if a < fr["a_conv"] * (1 - 1e-12):
        out.append("профиль невыпуклый (ρ&nbsp;&lt;&nbsp;ρ<sub>min</sub>)")
    if a < fr["a_press"] * (1 - 1e-12):
        out.append("угол давления превышает допустимый")
    return out


def _size_flat_rocker(s, study, cam) -> None:
    """The flat-faced rocker: envelope, contact point, curvature, pressure angle, a_w and ψ₀."""
    syn, fr, d = cam.synthesis, cam.fr, cam.face_offset
    q = _q_tex(cam)
    rot = "против" if cam.k > 0 else "по ходу"
    s.paragraph("Тарелка коромысла — прямая, отстоящая от оси качания A на d; при ψ&nbsp;=&nbsp;0 она образует угол "
                "ψ<sub>0</sub> с линией центров AO (a<sub>w</sub>&nbsp;=&nbsp;AO). В обращённом движении кулачок "
                "неподвижен, а тарелка занимает последовательные положения; профиль кулачка — их огибающая. "
                "Расстояние от центра кулачка до тарелки")
    s.formula(Formula(r"p = a_w \sin(\psi_0 + \psi) - d", label="eq-cam-flat-p"))
    s.paragraph(f"Кулачок вращается {rot} хода часовой стрелки, тарелка поворачивается относительно него с угловой "
                f"скоростью ω({_im(q)}). По теореме о трёх мгновенных центрах [1] общая нормаль в точке касания K "
                "проходит через мгновенный центр относительного вращения P<sub>12</sub> на линии центров, "
                f"AP<sub>12</sub>&nbsp;=&nbsp;a<sub>w</sub>/({_im(q)}); K — основание перпендикуляра, опущенного из "
                "P<sub>12</sub> на тарелку. Расстояние точки касания вдоль тарелки от основания F перпендикуляра, "
                "опущенного на тарелку из оси A:")
    s.formula(Formula(rf"\mu = \frac{{a_w \cos(\psi_0 + \psi)}}{{{q}}}", label="eq-cam-flat-mu"))
    s.paragraph("Радиус кривизны огибающей равен p&nbsp;+&nbsp;d²p/dθ² (θ — угол нормали тарелки в системе кулачка, "
                f"dθ/dφ&nbsp;=&nbsp;−({_im(q)})):")
    s.formula(Formula(rf"\rho = a_w G - d,\qquad G = \sin(\psi_0 + \psi)\left[1 - \frac{{\psi^{{\prime 2}}}}"
                      rf"{{({q})^2}}\right] + \frac{{\cos(\psi_0 + \psi)\,\psi^{{\prime\prime}}}}{{({q})^3}}",
                      label="eq-cam-flat-rho"))
    s.paragraph("Профиль выпуклый, если ρ&nbsp;≥&nbsp;ρ<sub>min</sub> на всём цикле; так как ρ линейно зависит от "
                "a<sub>w</sub>, при данном ψ<sub>0</sub>")
    s.formula(Formula(r"a_w \ge \frac{\rho_{min} + d}{G_{min}}", label="eq-cam-flat-conv"))
    s.paragraph("Угол давления — угол между нормалью к профилю в точке контакта и скоростью точки толкателя [1, 3]. "
                "Сила действует по нормали к тарелке, а точка K коромысла движется перпендикулярно AK, поэтому")
    s.formula(Formula(r"\operatorname{tg}\vartheta = \frac{d}{\mu}", label="eq-cam-flat-theta"))
    if d > 0:
        s.paragraph("Угол давления растёт по мере приближения точки касания к оси качания; условие "
                    "ϑ&nbsp;≤&nbsp;[ϑ] даёт второе ограничение")
        s.formula(Formula(r"a_w \ge \frac{d}{\operatorname{tg}[\vartheta]\,"
                          r"\left[\cos(\psi_0 + \psi)/(" + q + r")\right]_{min}}", label="eq-cam-flat-press"))
    else:
        s.paragraph("Тарелка проходит через ось качания (d&nbsp;=&nbsp;0), поэтому угол давления равен нулю во всех "
                    "положениях, а размеры ограничиваются только выпуклостью профиля.")
    G, pG = fr["G"], fr["phi_G"]
    psi0 = syn.psi0
    s.paragraph(f"Наименьшее значение G при ψ<sub>0</sub>&nbsp;=&nbsp;{_deg(psi0, 3)} найдено из условия "
                f"dG/dφ&nbsp;=&nbsp;0 (с аналогом ψ‴): G<sub>min</sub>&nbsp;=&nbsp;{fmt(G, sig=5)} при "
                f"φ&nbsp;=&nbsp;{_deg(pG, 3)}.")
    fs = [Formula(r"a_{w,\rho}", rf"\frac{{{_tmm(cam.rho_min)} + {_tmm(d)}}}{{{_t(G, sig=5)}}}",
                  _t(fr["a_conv"] * 1000, unit="мм"))]
    if fr["a_press"] > 0:
        for nm, ph in (("rise", cam.rise), ("return", cam.ret)):
            if ph.allowed > 0:
                sym = "у" if nm == "rise" else "в"
                fs.append(Formula(rf"a_{{w,\vartheta {sym}}}",
                                  rf"\frac{{{_tmm(d)}}}{{\operatorname{{tg}}\,{tex_given(round(math.degrees(ph.allowed), 6))}^\circ"
                                  rf"\cdot {_t(fr['m_' + nm], sig=5)}}}",
                                  _t(d / (math.tan(ph.allowed) * fr["m_" + nm]) * 1000, unit="мм")))
    s.formula(*fs)
    if cam.psi0_fixed is None and cam.aw_fixed is None:
        how = ("в точке пересечения двух границ; ψ<sub>0</sub> найден как корень уравнения "
               "a<sub>w,ρ</sub>(ψ<sub>0</sub>)&nbsp;=&nbsp;a<sub>w,ϑ</sub>(ψ<sub>0</sub>)" if syn.governing == "both" else
               "на границе допустимой области; ψ<sub>0</sub> найден минимизацией r<sub>0</sub>(ψ<sub>0</sub>) "
               "методом Брента")
        s.paragraph("С ростом ψ<sub>0</sub> условие выпуклости допускает меньшее a<sub>w</sub>, а условие угла давления "
                    "требует большего (точка касания приближается к оси качания). Радиус основной шайбы "
                    "r<sub>0</sub>&nbsp;=&nbsp;a<sub>w</sub>&nbsp;sin&nbsp;ψ<sub>0</sub>&nbsp;−&nbsp;d наименьший "
                    f"{how} (рисунок {ref('fig-cam-flat-size')}).")
    elif cam.aw_fixed is not None and cam.psi0_fixed is None:
        s.paragraph(f"При заданном a<sub>w</sub> наименьший r<sub>0</sub> даёт наименьший ψ<sub>0</sub>, при котором "
                    f"профиль выпуклый: корень уравнения a<sub>w</sub>G<sub>min</sub>(ψ<sub>0</sub>)&nbsp;−&nbsp;d&nbsp;=&nbsp;"
                    f"ρ<sub>min</sub> (рисунок {ref('fig-cam-flat-size')}).")
    elif syn.governing == "fixed":
        bad = _flat_rocker_failures(cam)
        s.paragraph(f"Заданное a<sub>w</sub>&nbsp;=&nbsp;{_mm(syn.a_w)} "
                    + ("не меньше требуемого: условия выполнены." if not bad else
                       "<b>меньше требуемого</b>: " + " и ".join(bad) + "."))
    elif fr["a_press"] > 0:
        s.paragraph(f"При заданном ψ<sub>0</sub> принято наибольшее из требуемых значений (рисунок "
                    f"{ref('fig-cam-flat-size')}).")
    else:
        s.paragraph(f"При заданном ψ<sub>0</sub> принято a<sub>w</sub>&nbsp;=&nbsp;a<sub>w,ρ</sub> (рисунок "
                    f"{ref('fig-cam-flat-size')}).")
    ex = syn.exact or syn
    s.formula(Formula("a_w", None, _t(ex.a_w * 1000, unit="мм")),
              Formula(r"\psi_0", None, _t(math.degrees(psi0), sig=5, unit="°")),
              Formula(r"r_0 = a_w \sin\psi_0 - d",
                      rf"{_t(ex.a_w * 1000)} \sin {_t(math.degrees(psi0), sig=5)}^\circ - {_tmm(d)}",
                      _t(ex.r0 * 1000, unit="мм")))
    _accept(s, cam)
    lo, hi = cam.face
    s.paragraph(f"Точка касания перемещается по тарелке от μ<sub>min</sub>&nbsp;=&nbsp;{_mm(lo)} до "
                f"μ<sub>max</sub>&nbsp;=&nbsp;{_mm(hi)} (точные экстремумы μ за цикл); рабочая длина тарелки не меньше "
                f"μ<sub>max</sub>&nbsp;−&nbsp;μ<sub>min</sub>&nbsp;=&nbsp;{_mm(hi - lo)}.")
    fig = FlatRockerSize().draw(study)
    s.figure("Межосевое расстояние, требуемое условием выпуклости профиля"
             + (" и допустимым углом давления," if fr["a_press"] > 0 else ",")
             + " в зависимости от начального угла коромысла", fig.svg, fig.width_mm, id="fig-cam-flat-size")


def _pressure(sec, study, cam) -> None:
    s = sec.subsection("Проверка угла давления", "sec-cam-theta")
    t1, t2 = cam.theta_max
    if cam.flat_rocker:
        lim = [(t, ph) for t, ph in ((t1, cam.rise), (t2, cam.ret))]
        ok = all(t <= ph.allowed + 1e-9 for t, ph in lim if ph.allowed > 0)
        s.paragraph(f"Угол давления ϑ&nbsp;=&nbsp;arctg(d/μ) на всём цикле построен на рисунке {ref('fig-cam-theta')}. "
                    "Он наибольший там, где точка касания ближе всего к оси качания: на удалении "
                    f"ϑ<sub>max</sub>&nbsp;=&nbsp;{_deg(t1, 3)}, на возвращении ϑ<sub>max</sub>&nbsp;=&nbsp;{_deg(t2, 3)}"
                    + ("".join(f", [ϑ<sub>{sym}</sub>]&nbsp;=&nbsp;{_dg(ph.allowed)}" for sym, ph in
                               (("у", cam.rise), ("в", cam.ret)) if ph.allowed > 0))
                    + ". " + ("" if not any(ph.allowed > 0 for ph in (cam.rise, cam.ret)) else
                              "Угол давления нигде не превышает допустимого." if ok else
                              "<b>Угол давления превышает допустимый</b>: размеры механизма нужно увеличить."))
        fig = PressureAngleGraph().draw(study)
        s.figure("Угол давления за цикл", fig.svg, fig.width_mm, id="fig-cam-theta")
        return
    s.paragraph(f"Угол давления на всём цикле построен на рисунке {ref('fig-cam-theta')}. Наибольшие значения: "
                f"на удалении ϑ<sub>max</sub>&nbsp;=&nbsp;{_deg(t1)} при [ϑ<sub>у</sub>]&nbsp;=&nbsp;{_dg(cam.rise.allowed)}, "
                f"на возвращении <span class=\"nobr\">|ϑ|<sub>max</sub></span>&nbsp;=&nbsp;{_deg(t2)} при [ϑ<sub>в</sub>]&nbsp;=&nbsp;{_dg(cam.ret.allowed)}. "
                + ("Угол давления нигде не превышает допустимого."
                   if t1 <= cam.rise.allowed + 1e-9 and t2 <= cam.ret.allowed + 1e-9
                   else f"<b>Угол давления превышает допустимый</b>: {_required_words(cam)}."))
    fig = PressureAngleGraph().draw(study)
    s.figure("Угол давления за цикл и допустимые значения", fig.svg, fig.width_mm, id="fig-cam-theta")


def _profile(sec, study, cam) -> None:
    s = sec.subsection("Профилирование кулачка", "sec-cam-profile")
    s.paragraph("Профиль построен методом обращения движения: кулачок неподвижен, а толкатель вместе со стойкой "
                "вращается вокруг центра O с угловой скоростью −ω. "
                + ("Профиль — огибающая положений тарелки; координаты точек касания в системе кулачка:"
                   if cam.contact == "flat" else "Координаты центрового (теоретического) профиля в системе кулачка:"))
    if cam.follower == "translating" and cam.contact != "flat":
        s.formula(Formula(_inversion_tex(cam, "e", "s_0"), label="eq-cam-profile"))
    elif cam.flat_rocker:
        s.formula(Formula(r"\overline{OK} = \overline{OA} + \mu\,\overline{r} - d\,\overline{u},\qquad "
                          r"\overline{r}_K = R(-\varphi)\,\overline{OK}", label="eq-cam-profile",
                          where=[(r"\overline{r}, \overline{u}", "единичные векторы вдоль тарелки и по нормали к ней"),
                                 (r"R(-\varphi)", "поворот на угол −φ (обращённое движение)")]))
        s.paragraph("Профиль — точная огибающая положений тарелки (не ломаная): точки касания найдены в замкнутом виде "
                    f"по формуле {ref('eq-cam-flat-mu')}, радиус кривизны — по формуле {ref('eq-cam-flat-rho')}.")
    elif cam.contact == "flat":
        s.formula(Formula(_inversion_tex(cam, r"s^{\prime}", "r_0"), label="eq-cam-profile"))
        s.paragraph("Точка касания смещена по тарелке на s′ от оси толкателя, радиус-вектор профиля "
                    f"{_im(R_TEX)}, радиус кривизны ρ&nbsp;=&nbsp;r<sub>0</sub>&nbsp;+&nbsp;s&nbsp;+&nbsp;s″.")
    else:
        s.formula(Formula(r"\overline{r}_C = R(-\varphi)\,\overline{OB}(\varphi)", label="eq-cam-profile",
                          where=[(r"R(-\varphi)", "поворот на угол −φ (обращённое движение)"),
                                 (r"\overline{OB}", "положение центра ролика при неподвижной стойке")]))
    if cam.contact == "roller":
        rc = cam.rho_min_centre
        s.paragraph("Радиус кривизны центрового профиля ρ = |r′|³/(r′ × r″) вычислен по точным производным. "
                    f"Наименьший радиус кривизны выпуклой части ρ<sub>min</sub>&nbsp;=&nbsp;{_mm(rc)}. Радиус ролика "
                    "из условий отсутствия заострения и прочности (r<sub>р</sub>&nbsp;≤&nbsp;0,7ρ<sub>min</sub>, "
                    "r<sub>р</sub>&nbsp;≤&nbsp;0,4r<sub>0</sub>)"
                    + (f" принят r<sub>р</sub>&nbsp;=&nbsp;{_mm(cam.roller)}." if cam.roller_fixed is None
                       else f" — задан r<sub>р</sub>&nbsp;=&nbsp;{_mm(cam.roller)}"
                       + (" (условие выполнено)." if cam.roller < rc else " (<b>условие не выполнено</b>).")))
        s.paragraph("Рабочий (действительный) профиль — эквидистанта центрового, отстоящая от него на r<sub>р</sub> "
                    "по нормали: " + str(_im(r"\overline{r} = \overline{r}_C - r_р\,\overline{n}")) + ".")
    elif cam.contact == "knife":
        s.paragraph("У толкателя с острием рабочий профиль совпадает с центровым. Радиус кривизны профиля "
                    "ρ = |r′|³/(r′ × r″) вычислен по точным производным; наименьший радиус кривизны выпуклой "
                    f"части ρ<sub>min</sub>&nbsp;=&nbsp;{_mm(cam.rho_min_centre)}.")
    fig = ProfileDrawing()
    d = fig.draw(study)
    pos = ", ".join(f"{i}&nbsp;— φ&nbsp;=&nbsp;{_deg(p, 1)}" for i, p in enumerate(follower_positions(cam)))
    if fig.refused:
        s.paragraph(f"В заданном масштабе {fig.refused} профиль не помещается на лист формата А4, поэтому принят "
                    f"наибольший помещающийся стандартный масштаб {fig.scale} (ГОСТ 2.302).")
    arm = (" (в крайних положениях 0 и 2 — целиком, с опорой; штрихпунктирная дуга — положения опоры при "
           "обращении движения)" if cam.follower == "rocker" and not cam.flat_rocker else "")
    s.paragraph(f"Профиль кулачка вычерчен на рисунке {ref('fig-cam-profile')} в масштабе {fig.scale}; толкатель "
                f"показан в положениях {pos}{arm}. Координаты профиля приведены в таблице {ref('tab-cam-coords')}.")
    s.figure(f"Профиль кулачка (М {fig.scale})", d.svg, d.width_mm, id="fig-cam-profile")
    df = cam.profile_table().copy()
    for c in ("s", "x_c", "y_c", "r_c", "x", "y", "r", "rho_c", "rho"):
        if c in df:
            df[c] = df[c] * (1000 if c != "s" or cam.follower == "translating" else 180 / math.pi)
    df["theta"] = df["theta"] * 180 / math.pi
    cols = [Column("phi_deg", "φ", "град", digits=1),
            Column("s", "ψ" if cam.follower == "rocker" else "s", "град" if cam.follower == "rocker" else "мм", digits=3)]
    if cam.contact != "flat":
        cols += [Column("x_c", "x<sub>C</sub>", "мм", digits=2), Column("y_c", "y<sub>C</sub>", "мм", digits=2)]
    if cam.contact != "knife":
        cols += [Column("x", "x", "мм", digits=2), Column("y", "y", "мм", digits=2)]
    cols += [Column("r", "r", "мм", digits=2), Column("rho", "ρ", "мм", digits=2)]
    if cam.contact != "flat" or (cam.flat_rocker and cam.face_offset > 0):
        cols.append(Column("theta", "ϑ", "град", digits=2))
    s.table("Координаты профиля кулачка", cols, df, id="tab-cam-coords",
            note="x<sub>C</sub>, y<sub>C</sub> — центровой профиль; x, y, r — рабочий профиль; ρ — радиус кривизны "
                 "рабочего профиля (отрицательный — вогнутый участок)." if cam.contact == "roller" else
            "x<sub>C</sub>, y<sub>C</sub>, r — профиль кулачка (центровой и рабочий профили совпадают); ρ — радиус "
            "кривизны профиля (отрицательный — вогнутый участок)." if cam.contact == "knife" else
            "x, y — точки касания тарелки с профилем; r — радиус-вектор профиля; ρ — радиус кривизны профиля"
            + ("; ϑ — угол давления." if cam.flat_rocker and cam.face_offset > 0 else "."))


def _inversion_tex(cam, lateral: str, base: str) -> str:
    """x, y of the translating follower's point (lateral, base + s) turned back by −φ into the cam
    frame, C = R(−kφ)(k·lateral, base + s), written for this cam's sense of rotation (k = ±1):
    x = k[lateral·cos φ + (base + s) sin φ], y = −lateral·sin φ + (base + s) cos φ."""
    x = rf"{lateral}\cos\varphi + ({base} + s)\sin\varphi"
    x = x if cam.k > 0 else rf"-{lateral}\cos\varphi - ({base} + s)\sin\varphi"
    return rf"x = {x},\quad y = -{lateral}\sin\varphi + ({base} + s)\cos\varphi"


def _r0_text(cam, least: bool = True) -> str:
    """The accepted r₀ as taken (a whole millimetre) with the least one beside it, «29 мм
    (наименьший 28,62 мм)»; the least alone when it was not rounded."""
    syn = cam.synthesis
    if syn.exact is None:
        return _mm(syn.r0)
    return _mg(syn.r0) + (f" (наименьший {_mm(syn.exact.r0)})" if least else "")


def conclusion_lines(study) -> list[str]:
    cam = study.cam
    syn = cam.synthesis
    out = []
    if cam.flat_rocker:
        out.append(f"Кулачковый механизм с коромыслом с плоской тарелкой: a<sub>w</sub>&nbsp;=&nbsp;{_mm(syn.a_w)}, "
                   f"ψ<sub>0</sub>&nbsp;=&nbsp;{_deg(syn.psi0)}, r<sub>0</sub>&nbsp;=&nbsp;{_r0_text(cam)}; рабочая длина "
                   f"тарелки не менее {_mm(cam.face[1] - cam.face[0])}"
                   + (f"; наибольший угол давления {_deg(cam.theta_max[0], 2)} на удалении и "
                      f"{_deg(cam.theta_max[1], 2)} на возвращении." if cam.face_offset > 0 else
                      "; угол давления равен нулю (тарелка проходит через ось качания)."))
        bad = _flat_rocker_failures(cam)
        if bad:
            out.append("При заданных размерах " + " и ".join(bad) + ": межосевое расстояние нужно увеличить.")
    elif cam.contact == "flat":
        out.append(f"Кулачковый механизм с плоским толкателем: радиус основной шайбы r<sub>0</sub>&nbsp;=&nbsp;{_r0_text(cam, least=False)} "
                   f"(по выпуклости профиля требуется не менее {_mm(cam.flat_min[2])}), ширина тарелки не менее "
                   f"{_mm(cam.scalars['cam_face_width'])}.")
    elif cam.follower == "translating":
        fixed = syn.governing == "fixed"
        out.append(("Кулачковый механизм: заданы r<sub>0</sub>&nbsp;=&nbsp;" + _mg(syn.r0) if fixed else
                    f"Кулачковый механизм: по допустимым углам давления r<sub>0</sub>&nbsp;=&nbsp;{_r0_text(cam)}")
                   + f", e&nbsp;=&nbsp;{_mg(syn.e) if fixed else _mm(syn.e)}; {_theta_phrase(cam)}.")
    else:
        fixed = syn.governing == "fixed"
        out.append(f"Кулачковый механизм с коромыслом: {'заданы ' if fixed else ''}a<sub>w</sub>&nbsp;=&nbsp;"
                   f"{_mg(syn.a_w) if fixed else _mm(syn.a_w)}, ψ<sub>0</sub>&nbsp;=&nbsp;"
                   f"{_dg(syn.psi0) if fixed else _deg(syn.psi0)}, r<sub>0</sub>&nbsp;=&nbsp;{_r0_text(cam)}; "
                   f"{_theta_phrase(cam)}.")
    if cam.contact == "roller":
        ok = cam.roller <= 0.7 * cam.rho_min_centre + 1e-12
        out.append(f"Радиус ролика r<sub>р</sub>&nbsp;=&nbsp;{_mm(cam.roller)} при наименьшем радиусе кривизны "
                   f"центрового профиля {_mm(cam.rho_min_centre)}: "
                   + ("r<sub>р</sub>&nbsp;≤&nbsp;0,7ρ<sub>min</sub>, рабочий профиль без заострений и срезов."
                      if ok else "r<sub>р</sub>&nbsp;&gt;&nbsp;0,7ρ<sub>min</sub> — <b>возможно заострение рабочего "
                      "профиля</b>, радиус ролика нужно уменьшить."))
    if cam.contact == "knife":
        out.append(f"Рабочий профиль совпадает с центровым; наименьший радиус кривизны выпуклой части профиля "
                   f"ρ<sub>min</sub>&nbsp;=&nbsp;{_mm(cam.rho_min_centre)}.")
    out.append(_impacts_sentence(cam))
    return out


def _theta_phrase(cam) -> str:
    """«наибольший угол давления 30,00° на удалении и 40,00° на возвращении при допустимых 30° и
    40° — не превышает допустимых» (the allowed angles as given) (the exact maxima of :attr:`Cam.theta_max`)."""
    t1, t2 = cam.theta_max
    a1, a2 = cam.rise.allowed, cam.ret.allowed
    ok = t1 <= a1 + 1e-9 and t2 <= a2 + 1e-9
    return (f"наибольший угол давления {_deg(t1)} на удалении и {_deg(t2)} на возвращении при допустимых "
            f"{_dg(a1)} и {_dg(a2)} — " + ("не превышает допустимых" if ok else
                                              f"<b>превышает допустимый</b>: {_required_words(cam)}"))


def _impacts_sentence(cam) -> str:
    """The impacts in words with the cam angles where they occur: «жёстких ударов нет; мягкие удары —
    в 3 положениях (φ = 140°, …)» (Артоболевский, §24: a jump of s′ — hard, of s″ — soft impact)."""
    parts = []
    for kind, adj, adj_gen in (("hard", "жёсткие", "жёстких"), ("soft", "мягкие", "мягких")):
        phis = [i["phi"] for i in cam.impacts if i["kind"] == kind]
        parts.append(f"{adj_gen} ударов нет" if not phis else
                     f"{adj} удары — в&nbsp;{plural(len(phis), 'положении', 'положениях', 'положениях')} "
                     f"(φ&nbsp;=&nbsp;" + ", ".join(_at(p) for p in phis) + ")")
    if not cam.impacts:
        return "Аналоги скорости и ускорения толкателя непрерывны: ударов в кулачковом механизме нет."
    # Попов, Тимофеев, гл. 6: laws with hard impacts only at low speeds, with soft ones at moderate speeds
    use = (" Закон с жёсткими ударами допустим лишь при малой скорости кулачка." if any(i["kind"] == "hard" for i in cam.impacts)
           else " Законы с мягкими ударами применяют при умеренной скорости кулачка.")
    return "Удары в кулачковом механизме: " + "; ".join(parts) + "." + use

