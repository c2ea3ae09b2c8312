"""Section «Динамический анализ и синтез маховика»: the dynamic model, the loads, the reduced
moment of inertia and moments with numbers at the chosen position, works and kinetic energy,
the flywheel by three methods (Мерцалов, Виттенбауэр, exact) and its dimensions, the law of
motion ω(φ), ε(φ) and the true velocities and accelerations.

``conclusion_lines(study)`` gives the lines of the ЗАКЛЮЧЕНИЕ about the dynamics."""
from __future__ import annotations

import math
import re

import numpy as np
import pandas as pd
from markupsafe import Markup, escape

from ...analysis.dynamics import DELTA_RANGES
from ...case import units as U
from ...case.text import inline_html
from ...scenes.draw import gost_ratio
from ...scenes.forces import html_label
from ...scenes.dynamics import (EnergyCurves, FlywheelDrawing, InertiaCurves, LoadLaws, MomentCurves,
                                MotionCurves, WittenbauerDiagram, WorkCurves, law_units, shown_laws)
from ...style.numbers import agreeing_sig, fmt, fmt_given, fmt_pct, shared_decimals, tex_num, trimmed_sig, written
from ..document import Column, Formula, Section, ref
from ..formulas import inline_math
from ..russian import condition_html, expr_html, plural
from .common import (as_written, chosen_position, chunked_tables, html_point, sub, tex_point, pos_fmt,
                     pos_no)
from .kinematics import motion_points

NEEDS = ("kinematics", "cycle", "dynamics")

METHOD_RU = {"exact": "точное решение уравнения движения", "mertsalov": "метод Н. И. Мерцалова",
             "wittenbauer": "метод Ф. Виттенбауэра"}


METHOD_INSTR = {"exact": "точным решением уравнения движения", "mertsalov": "методом Н. И. Мерцалова",
                "wittenbauer": "методом Ф. Виттенбауэра"}

TEX = {
    "J2": r"J_{II}(\varphi)",
    "JO": r"J_{O}",
    "Msum0": r"M_{\Sigma}(\varphi) = 0",
    "delta": r"\delta = (\omega_{max} - \omega_{min})/\omega_{ср}",
    "wm": r"\omega_{ср} = (\omega_{max} + \omega_{min})/2",
    "mert_ext": r"M_{\Sigma} = \frac{1}{2} J_{II}^{\prime} \omega_{\text{ср}}^2",
    "exact_ext": r"M_{\Sigma} = \frac{1}{2} J_{II}^{\prime} \omega^2",
    "vrim": r"v = \omega_{max} D/2",
    "vrim_u": r"v = u\,\omega_{max} D/2",
    "v": r"v = \omega x^{\prime}",
    "a": r"a = \omega^2 x^{\prime\prime} + \varepsilon x^{\prime}",
    "wk": r"\omega_k = \omega \varphi_k^{\prime}",
    "ek": r"\varepsilon_k = \omega^2 \varphi_k^{\prime\prime} + \varepsilon \varphi_k^{\prime}",
}


def TASK(study) -> str:
    """The assignment clause: the flywheel from δ (direct task) or δ from the given flywheel."""
    if study.dynamics.inverse is not None:
        return ("определить закон движения машины и коэффициент неравномерности хода при заданном маховике "
                "(обратная задача)")
    return "определить закон движения машины и рассчитать маховик по заданному коэффициенту неравномерности хода"


def _im(key: str):
    """Inline math of a named LaTeX snippet (f-string expressions cannot hold backslashes)."""
    return inline_math(TEX[key])


def present(study) -> bool:
    """The section is built when the case has [dynamics]."""
    return study.root.has("dynamics")


# --------------------------------------------------------------------------------------------
# small helpers
# --------------------------------------------------------------------------------------------
def _t(x, sig=4, digits=None, paren=False, unit=None) -> str:
    """LaTeX of a number; with ``paren`` it is safe as a factor or a base of a power (negative
    or exponent-form numbers in parentheses, rounding noise below 1e-13 written as 0)."""
    if paren and abs(float(x)) < 1e-13:
        x = 0.0
    t = tex_num(x, sig=sig, digits=digits, paren=paren, unit=unit)
    if paren and r"\cdot 10" in t and not t.startswith(r"\left("):
        t = r"\left(" + t + r"\right)"
    return t



def _ts(x, sig: int, **kw) -> str:
    """A measured factor printed to ``sig`` digits from :func:`agreeing_sig`, no padding zeros."""
    return _t(x, sig=trimmed_sig(x, sig), **kw)

def _tx(text: str) -> str:
    """LaTeX of a load/link name in a subscript."""
    return r"\text{" + text + "}"


def _cycle_k(study) -> int:
    """The cycle length Φ = k·π of the dynamics (k ≥ 1, any whole number)."""
    return max(1, round(study.dynamics.settings.cycle_length / math.pi))


def _cycle_tex(study) -> str:
    k = _cycle_k(study)
    return r"\pi" if k == 1 else rf"{k}\pi"


def _cycle_words(study) -> str:
    """«один оборот кривошипа, Φ = 2π», «один двойной оборот …, Φ = 4π», «три оборота …, Φ = 6π»,
    «1,5 оборота …, Φ = 3π»."""
    k = _cycle_k(study)
    Phi = "π" if k == 1 else f"{k}π"
    if k == 2:
        turns = "один оборот"
    elif k == 4:
        turns = "один двойной оборот"
    elif k % 2 == 0:
        turns = plural(k // 2, "оборот", "оборота", "оборотов")
    else:
        turns = f"{fmt(k / 2, digits=1)} оборота"
    return f"{turns} кривошипа, Φ&nbsp;=&nbsp;{Phi}"


def _h(sym: str, idx: str) -> str:
    return f"<i>{sym}</i><sub>{idx}</sub>"


def _clean(df: pd.DataFrame) -> pd.DataFrame:
    """A copy for printing: values that are rounding noise against their column (|x| below
    1e-12 of the column's largest value, e.g. V_qy of a slider on a horizontal guide) become 0."""
    out = df.copy()
    for c in out.columns:
        if pd.api.types.is_float_dtype(out[c]):
            v = out[c].to_numpy()
            big = float(np.nanmax(np.abs(v))) if v.size else 0.0
            out[c] = np.where(np.abs(v) <= 1e-12 * big, 0.0, v)
    return out


def _ratio(u: float) -> str:
    """A gear ratio as the case gives it: «15», «2,5» (a computed 6,0000000001 → «6»)."""
    return as_written(round(float(u), 6))


def drive_chain(study) -> str | None:
    """The drive of the crank in words with the ratios, when the case gives the flywheel's shaft
    ratio u and the gear pair and/or the planetary train of the drive whose ratios multiply to u:
    «электродвигатель → планетарный редуктор (u = 6) → зубчатая передача (u = 2,5) → кривошип».
    The stage whose given input speed is the crank's speed times its ratio drives the crank."""
    st = study.dynamics.settings
    u = st.ratio
    stages = []
    if study.root.has("train"):
        tr = study.train
        stages.append(("планетарный редуктор", abs(tr.ratio), None))
    if study.root.has("gears") and study.gears.z2 and not study.gears.internal:
        gr = study.gears
        stages.append((f"зубчатая передача <i>z</i><sub>1</sub>&nbsp;=&nbsp;{gr.z1}, "
                       f"<i>z</i><sub>2</sub>&nbsp;=&nbsp;{gr.z2}", gr.z2 / gr.z1, gr.omega1))
    if u == 1.0 or not stages or abs(math.prod(x[1] for x in stages) / u - 1) > 1e-6:
        return None
    w = st.omega_m
    stages.sort(key=lambda x: x[2] is not None and abs(x[2] / (w * x[1]) - 1) < 1e-3)   # the crank's stage last
    rpm = 30 / math.pi
    chain = " → ".join([f"электродвигатель (n<sub>дв</sub>&nbsp;=&nbsp;{fmt(w * u * rpm, sig=4)}&nbsp;об/мин)"]
                       + [f"{name} (u&nbsp;=&nbsp;{_ratio(r)})" for name, r, _ in stages]
                       + [f"кривошип (n<sub>1</sub>&nbsp;=&nbsp;{fmt(w * rpm, sig=4)}&nbsp;об/мин)"])
    prod = "·".join(_ratio(r) for _, r, _ in stages)
    total = f"u&nbsp;=&nbsp;{prod}&nbsp;=&nbsp;{_ratio(u)}" if len(stages) > 1 else f"u&nbsp;=&nbsp;{_ratio(u)}"
    return (f"Привод кривошипа: {chain}; общее передаточное отношение от вала двигателя к кривошипу {total}. "
            "Маховик устанавливается на валу двигателя.")


def given(study) -> str:
    """The machine's dynamic data in one sentence for the assignment page."""
    st = study.dynamics.settings
    text = (f"Динамика машины: средняя частота вращения кривошипа {fmt_given(st.omega_m * 30 / math.pi)}&nbsp;об/мин, "
            f"коэффициент неравномерности хода δ&nbsp;=&nbsp;{as_written(st.delta)}")
    if st.J_O:
        text += f", приведённый момент инерции ротора и передачи J<sub>O</sub>&nbsp;=&nbsp;{fmt_given(st.J_O)}&nbsp;кг·м²"
    work = [ld for ld in study.dynamics.loads.loads if ld.kind != "weight"]
    if work:
        text += "; нагрузки: " + ", ".join(inline_html(ld.title or ld.name) for ld in work)
    chain = drive_chain(study)
    if not chain and st.ratio != 1.0:
        # the given shaft of the flywheel (no drive stages in the case to name it by)
        text += (f"; маховик устанавливается на другом валу, передаточное отношение от него к кривошипу "
                 f"<span class=\"nowrap\">u&nbsp;=&nbsp;ω<sub>м</sub>/ω<sub>1</sub>&nbsp;=&nbsp;{_ratio(st.ratio)}</span>")
    text += "."
    return text + (" " + chain if chain else "")


def _c(x) -> str:
    """LaTeX of an empirical constant as written (0.437, 6123): shortest representation."""
    return tex_num(x, sig=len(repr(float(x)).replace("-", "").replace(".", "").lstrip("0").rstrip("0")) or 1)


def _deg(x) -> str:
    return fmt(math.degrees(float(x)), digits=2)


def _phase_deg(study, q) -> str:
    """A place in the cycle to 0,1° as the tables' φ and the kinematics chapter's extreme positions
    (one angle, one spelling: not 357,28° in §3.1 beside 357,3° in §2.5)."""
    return fmt(math.degrees(float(q) - study.dynamics.settings.cycle_start), digits=1) + "°"


def _two(a, b, unit: str) -> tuple[str, str]:
    """Two values of one sentence (the extremes of ΔT, K and L) to one number of decimals, as the
    column they come from (ГОСТ 7.32: 656,1 and −6799,7 Дж, not 656,14 and −6799,7 Дж)."""
    nd = shared_decimals([a, b], sig=5)
    return fmt(a, digits=nd, unit=unit), fmt(b, digits=nd, unit=unit)


def mertsalov_extremes_text(study) -> str:
    """Where ΔT_I = ΔT − T_II (Мерцалов; Артоболевский [1]) has its extremes over the cycle, and
    that only their difference, the greatest change of the first group's kinetic energy
    ΔT_I нб = ΔT_I max − ΔT_I min, enters J_I. ΔT_I starts at −T_II < 0 (ΔT = 0 at the start of
    the cycle): both extremes negative are said to be so, not left to read as a «negative maximum»."""
    me = study.dynamics.result.mertsalov
    both = (" (оба значения отрицательны: в начальном положении Δ<i>T</i>&nbsp;=&nbsp;0 и "
            "Δ<i>T</i><sub>I</sub>&nbsp;=&nbsp;−<i>T</i><sub>II</sub>, а за цикл Δ<i>T</i> нигде не превышает "
            "<i>T</i><sub>II</sub>; постоянное слагаемое в разность экстремумов не входит)" if me.dT_I_max < 0 else "")
    return (f"Экстремумы Δ<i>T</i><sub>I</sub> найдены по всему циклу решением уравнения {_im('mert_ext')}: "
            f"наибольшее значение — при φ&nbsp;=&nbsp;{_phase_deg(study, me.phi_dT_max)}, наименьшее — при "
            f"φ&nbsp;=&nbsp;{_phase_deg(study, me.phi_dT_min)}{both}. Момент инерции первой группы звеньев "
            f"определяется наибольшим изменением её кинетической энергии за цикл — разностью экстремумов:")


# --------------------------------------------------------------------------------------------
# build
# --------------------------------------------------------------------------------------------
def build(study) -> Section:
    d = study.dynamics
    sec = Section("Динамический анализ и синтез маховика", "sec-dynamics")
    tab, mot = _clean(d.table), _clean(d.motion)
    lab = chosen_position(study)
    row = d.row(lab)
    cols = d.ev(np.array([row["q"]]))
    kv = {k: float(v[0]) for k, v in cols.items()}
    lead = [Column("pos", "№", fmt=pos_fmt(study)), Column("q_deg", "<i>φ</i>", "град", digits=1)]
    _model(sec, study, d)
    _inertia(sec, study, d, tab, lab, row, kv, lead)
    _moments(sec, study, d, tab, lab, row, kv, lead)
    _works(sec, study, d, tab, lead)
    _flywheel(sec, study, d)
    _dimensions(sec, study, d)
    _motion(sec, study, d, tab, mot, lab, row, lead)
    return sec


def _model(sec: Section, study, d) -> None:
    s = sec.subsection("Динамическая модель машины", "sec-dyn-model")
    st = d.settings
    crank = study.mechanism.driver.link
    Jpr = inline_math(r"J_{\text{пр}}(\varphi) = J_I + J_{II}(\varphi)")
    Mpr = inline_math(r"M_{\text{пр}}(\varphi) = M_{\text{д}}(\varphi) + M_{\text{с}}(\varphi)")
    s.paragraph(
        f"Звеном приведения служит кривошип {crank}, обобщённая координата — угол его поворота φ. "
        f"Машина заменяется динамической моделью — звеном приведения с приведённым моментом инерции "
        f"{Jpr} и приведённым моментом сил {Mpr}. Первая группа звеньев (ротор двигателя, передачи, "
        f"кривошип и маховик) имеет постоянный приведённый момент инерции {inline_math('J_I')}; "
        f"вторая группа (звенья рычажного механизма) — переменный {_im('J2')}. "
        f"Цикл установившегося движения — {_cycle_words(study)}.")
    s.paragraph("Уравнение движения машины в энергетической и дифференциальной формах "
                "(уравнение Лагранжа второго рода для звена приведения):")
    s.formula(Formula(r"\frac{J_{\text{пр}}(\varphi)\,\omega^2}{2} - \frac{J_{\text{пр}}(\varphi_0)\,\omega_0^2}{2}"
                      r" = \int_{\varphi_0}^{\varphi} M_{\text{пр}}\,d\varphi", label="eq-dyn-energy"),
              Formula(r"J_{\text{пр}}\,\varepsilon + \frac{1}{2}\frac{dJ_{\text{пр}}}{d\varphi}\,\omega^2 = M_{\text{пр}}",
                      where=[(r"\omega = d\varphi/dt", "угловая скорость звена приведения, рад/с"),
                             (r"\varepsilon = d\omega/dt", "его угловое ускорение, рад/с²")],
                      label="eq-dyn-lagrange"))
    rows = []
    for il in d.model.links:
        rows.append({"n": il.name, "title": il.title or "—", "m": il.m or math.nan,
                     "J": il.J_S or math.nan, "S": il.S or "—", "group": "II"})
    if d.model.crank is not None:
        c = d.model.crank
        rows.append({"n": c.name, "title": c.title or "—", "m": c.m or math.nan, "J": c.J_S or math.nan,
                     "S": c.S or "—", "group": "I"})
    if rows:
        s.table("Инерционные параметры звеньев в динамической модели", [
            Column("n", "Звено"), Column("title", "Название"), Column("m", "<i>m</i>", "кг", sig=4),
            Column("J", _h("J", "S"), "кг·м²", sig=4), Column("S", "Центр масс",
                                                                  fmt=lambda v: Markup(html_point(escape(v))) if v[:1].isalpha() else v),
            Column("group", "Группа")],
            pd.DataFrame(rows), id="tab-dyn-links")
    JO = fmt(st.J_O, sig=4, unit="кг·м²")
    extra = ""
    if d.J_crank:
        extra = (f" и момент инерции кривошипа {fmt(d.J_crank, sig=4, unit='кг·м²')}, итого "
                 f"{inline_math('J_{I,0}')}&nbsp;=&nbsp;{fmt(d.J_I_const, sig=4, unit='кг·м²')}")
    s.paragraph(f"Постоянная часть первой группы без маховика: приведённый момент инерции ротора и передачи "
                f"{_im('JO')}&nbsp;=&nbsp;{JO}{extra}.")
    # loads
    lrows = []
    for ld in d.loads.loads:
        lrows.append({"name": ld.name, "what": Markup(ld.title).striptags(),
                      "where": (Markup("{}, звено {}").format(Markup(html_point(escape(ld.point))), ld.link)
                                if ld.point else Markup("звено {}").format(ld.link)),
                      "law": _law(ld, _slide_names(study), param_symbols(study))})
    if lrows:
        s.paragraph(f"Внешние нагрузки машины перечислены в таблице {ref('tab-dyn-loads')}. Силы тяжести "
                    f"вычислены при <i>g</i>&nbsp;=&nbsp;{fmt_given(d.loads.g)}&nbsp;м/с².")
        s.table("Нагрузки, действующие на звенья", [
            Column("name", "Обозначение", fmt=lambda v: Markup(html_label(v))), Column("what", "Нагрузка"), Column("where", "Точка приложения", fmt=Markup),
            Column("law", "Закон изменения", fmt=Markup)], pd.DataFrame(lrows), id="tab-dyn-loads")
    live = law_breaks(d)
    if live.size:
        s.paragraph(_breaks_text(study, live))
    laws = shown_laws(study)
    if laws:
        fig = LoadLaws().draw(study)
        args: dict[str, list[str]] = {}      # the table's argument → the loads it is written for
        drawn = {n for names, _, _ in laws for n in names}
        for ld in d.loads.loads:
            for p in ld.pieces:
                if ld.name in drawn and p.table is not None:
                    a = (str(expr_html(_slides_as_named(p.of.text, _slide_names(study)), param_symbols(study)))
                         if p.of is not None else "φ")
                    if ld.name not in args.setdefault(a, []):
                        args[a].append(ld.name)
        xs = "; ".join(f"<i>x</i> = {a}" + (f" ({', '.join(html_label(n) for n in ns)})" if len(args) > 1 else "")
                       for a, ns in args.items())
        s.paragraph(f"Нагрузки, заданные таблицами, показаны на рисунке {ref('fig-dyn-laws')} так, как они заданы: "
                    f"по оси абсцисс — величина <i>x</i>, от которой задана таблица ({xs}), точки — строки таблиц.")
        s.figure("Законы изменения нагрузок, заданных таблицами", fig.svg, fig.width_mm, id="fig-dyn-laws")


def law_breaks(d) -> np.ndarray:
    """The switching points of the dynamics (``d.breaks``) at which some given load (not a weight)
    changes its own law while it is non-zero on at least one side: a table's corner crossed while
    the load's condition holds it at zero (a press's coining diagram passed again on the way up, a
    pump's delivery diagram on the suction stroke) changes no law a student can see, though
    another load acts there. The integrals still use every switching point."""
    b = np.asarray(d.breaks, dtype=float)
    if b.size == 0:
        return b
    n = b.size
    dq = 1e-7 * d.loads.cycle_length
    cols = d.ev(np.concatenate([b - dq, b + dq]))
    ph = d.loads.phase(cols)
    at = np.mod(b - d.loads.cycle_start, d.loads.cycle_length)
    live = np.zeros(n, dtype=bool)
    for ld in d.loads.loads:
        if ld.kind == "weight":
            continue
        acts = np.zeros(2 * n, dtype=bool)
        for c in ld.components(cols, ph):
            acts |= np.abs(np.broadcast_to(np.asarray(c, dtype=float), acts.shape)) > 0.0
        own = np.zeros(n, dtype=bool)          # the point is one of this load's own switching points
        for f, fph in ld.switching_functions():
            g = np.asarray(f(cols), dtype=float) >= 0
            on = np.ones(n, dtype=bool) if fph is None else (at >= fph[0] - 2 * dq) & (at <= fph[1] + 2 * dq)
            own |= (g[:n] != g[n:]) & on
        for p in ld.phase_breaks():
            own |= np.abs(at - p) <= 2 * dq
        live |= own & (acts[:n] | acts[n:])
    return b[live]


def _breaks_text(study, breaks) -> str:
    """Where the loads change their law: the angles listed, or (a table law's every corner) counted."""
    if breaks.size > MAX_BREAKS:
        return (f"Нагрузки меняют закон действия (изломы и скачки заданных диаграмм, начало и конец "
                f"действия сил) в точках цикла, найденных решением уравнений (всего "
                f"{plural(breaks.size, 'точка', 'точки', 'точек')}). Интегралы работ вычисляются по участкам "
                "между ними квадратурой Гаусса–Лежандра, поэтому изломы и разрывы нагрузок не вносят погрешности.")
    pts = ", ".join(_phase_deg(study, q) for q in breaks)
    return (f"Нагрузки меняют закон действия (точки переключения, найденные решением уравнений) при "
            f"φ&nbsp;=&nbsp;{pts}. Интегралы работ вычисляются по участкам между ними квадратурой "
            "Гаусса–Лежандра, поэтому разрывы нагрузок не вносят погрешности.")


def _slide_names(study) -> dict[str, str]:
    """A prismatic pair's name → the name its displacement s carries in the note's tables: the
    slider's point where no other pair slides at it (s_30 → s_B, as table «Углы звеньев и
    перемещения в поступательных парах» heads its column)."""
    pairs = study.mechanism.prismatic
    points = [j.point for j in pairs]
    return {j.name: j.point for j in pairs if points.count(j.point) == 1}


def _slides_as_named(text: str, names: dict[str, str]) -> str:
    """``text`` with the columns of prismatic pairs (s_J, vqs_J, aqs_J) renamed by ``names``,
    for display only."""
    if not names:
        return text
    return re.sub(r"\b(s|vqs|aqs)_(\w+)\b",
                  lambda m: f"{m.group(1)}_{names.get(m.group(2), m.group(2))}", text)


MAX_BREAKS = 12      # more switching angles than this are counted, not listed


def param_symbols(study) -> dict[str, Markup]:
    """The symbols the case gives its parameters (``[parameters]`` ``symbol``, safe HTML), for the
    expressions the note writes out (a table's argument «x = s<sub>B</sub> − s<sub>н</sub>»)."""
    texts = getattr(study.spec, "parameter_texts", None)
    return {k: sym for k, (_, sym) in texts().items() if sym} if texts else {}


def _law(ld, names: dict[str, str] | None = None, symbols: dict[str, Markup] | None = None) -> Markup:
    """Russian description of a load law (escaped HTML with no-break spaces): expressions and
    conditions in textbook symbols, parameters by their values (:func:`condition_html`); the
    displacement in a prismatic pair named as the tables name it (``names``, :func:`_slide_names`)."""
    names = names or {}
    if ld.kind == "weight":
        return Markup(escape(f"G\u00a0=\u00a0{fmt(-ld.vector[1], sig=4)}\u00a0Н, вертикально вниз"))
    parts = []
    if ld.vector is not None:
        parts.append(f"F\u00a0=\u00a0({fmt(ld.vector[0], sig=4)}; {fmt(ld.vector[1], sig=4)})\u00a0Н")
    for p in ld.pieces:
        head = (f"на фазе {fmt(math.degrees(p.phase[0]), digits=0)}…{fmt(math.degrees(p.phase[1]), digits=0)}°"
                f"{' (' + p.name + ')' if p.name else ''}: " if p.phase is not None else "")
        unit, k = law_units(ld, p)
        if p.table is not None:
            parts.append(Markup("{}таблица {} от {}, {}…{}\u00a0{}").format(
                head, plural(len(p.table.x), "точка", "точки", "точек"),
                expr_html(_slides_as_named(p.of.text, names), symbols),
                fmt(p.table.y.min() / k, sig=3), fmt(p.table.y.max() / k, sig=3), unit))
        else:
            parts.append(head + f"{fmt(p.const / k, sig=4)}\u00a0{unit}")
    if ld.area is not None:
        parts.append(f"площадь {fmt(ld.area, sig=4)}\u00a0м²")
    if ld.kind == "force" and ld.vector is None:
        parts.append(_direction_words(ld))
    if ld.against:
        parts.append("против движения")
    for c in ld.when:
        parts.append(_condition(c, names))
    return Markup("; ").join(parts)


def _direction_words(ld) -> Markup:
    """The line of action of a load in words, not the case's "x" / "-y" / "30 deg": «в направлении
    оси x», «в обратном направлении оси y», «вдоль оси x» (against the motion), «под углом 30° к оси x»."""
    t = ld.direction_text.strip()
    if t in ("x", "+x", "y", "+y", "-x", "-y"):
        if ld.against:                # the sign follows the motion: only the line is given
            return Markup("вдоль оси <i>{}</i>").format(t[-1])
        return Markup("{} направлении оси <i>{}</i>").format("в обратном" if t.startswith("-") else "в", t[-1])
    ang = math.degrees(math.atan2(ld.u[1], ld.u[0]))
    whole = abs(ang - round(ang)) < 1e-9        # a given angle as written: «−45°», not «−45,00°»
    return Markup("под углом {}° к оси <i>x</i>").format(fmt(ang, digits=0) if whole else fmt(ang, sig=4))


def _condition(c, names: dict[str, str] | None = None) -> Markup:
    """A load condition with the right side evaluated when it holds only parameters: an angle in
    degrees, anything else in its SI unit."""
    text = _slides_as_named(c.text, names or {})
    if c.rhs.used or c.lhs.used == []:
        return condition_html(text)
    value = float(np.asarray(c.rhs._eval({}).value, dtype=float).reshape(-1)[0])
    if tuple(c.lhs.dim) == U.ANGLE:
        return condition_html(text, math.degrees(value), "°")
    return condition_html(text, value, U.format_dim(c.lhs.dim))


def _inertia(sec, study, d, tab, lab, row, kv, lead) -> None:
    s = sec.subsection("Приведённый момент инерции", "sec-dyn-inertia")
    s.paragraph("Приведённый момент инерции второй группы найден из равенства кинетических энергий "
                "звеньев механизма и звена приведения; аналоги скоростей вычислены точно:")
    s.formula(Formula(r"J_{II}(\varphi) = \sum_k \left[ m_k \left( x_{S_k}^{\prime 2} + y_{S_k}^{\prime 2} \right)"
                      r" + J_{S_k}\, \varphi_k^{\prime 2} \right]",
                      where=[(r"m_k, J_{S_k}", "масса звена k и его момент инерции относительно центра масс"),
                             (r"x^{\prime}_{S_k}, y^{\prime}_{S_k}", "аналоги скорости центра масс, м"),
                             (r"\varphi^{\prime}_k", "аналог угловой скорости звена")],
                      label="eq-J2"),
              Formula(r"\frac{dJ_{II}}{d\varphi} = 2\sum_k \left[ m_k \left( x^{\prime}_{S_k} x^{\prime\prime}_{S_k}"
                      r" + y^{\prime}_{S_k} y^{\prime\prime}_{S_k} \right) + J_{S_k}\,\varphi^{\prime}_k"
                      r" \varphi^{\prime\prime}_k \right]", label="eq-dJ2"))
    s.paragraph(f"Для положения {pos_no(study, lab)} (φ&nbsp;=&nbsp;{fmt(row['q_deg'], digits=1)}°):")
    fs = []
    for il in d.model.links:
        terms_s, terms_n = [], []
        k = il.name
        # the analogues to as many digits as make the printed sum the printed J_II,k
        m, J = written(il.m or 0.0), written(il.J_S or 0.0)
        S = il.S
        an = [kv["vqx_" + S], kv["vqy_" + S]] if il.m else [0.0, 0.0]
        sg = agreeing_sig(lambda f: m * (f[0] ** 2 + f[1] ** 2) + J * f[2] ** 2,
                          an + [kv["wq_" + k] if il.J_S else 0.0], row["J_II_" + k], result_sig=5)
        if il.m:
            terms_s.append(rf"m_{{{k}}} \left( x_{{{tex_point(S)}}}^{{\prime 2}} + y_{{{tex_point(S)}}}^{{\prime 2}} \right)")
            terms_n.append(rf"{_t(il.m)} \cdot \left( {_ts(an[0], sg, paren=True)}^2 + {_ts(an[1], sg, paren=True)}^2 \right)")
        if il.J_S:
            terms_s.append(rf"J_{{S{k}}} \varphi_{{{k}}}^{{\prime 2}}")
            terms_n.append(rf"{_t(il.J_S)} \cdot {_ts(kv['wq_' + k], sg, paren=True)}^2")
        fs.append(Formula(rf"J_{{II,{k}}} = " + " + ".join(terms_s), " + ".join(terms_n),
                          _t(row["J_II_" + k], sig=5, unit="кг·м²")))
    names = " + ".join(rf"J_{{II,{il.name}}}" for il in d.model.links) or "0"
    vals = " + ".join(_t(row["J_II_" + il.name], sig=5) for il in d.model.links) or "0"
    fs.append(Formula(rf"J_{{II}} = {names}", vals, _t(row["J_II"], sig=5, unit="кг·м²")))
    s.formula(*fs)
    cols = [Column("J_II_" + il.name, _h("J", "II," + il.name), "кг·м²", sig=4) for il in d.model.links]
    cols += [Column("J_II", _h("J", "II"), "кг·м²", sig=5), Column("dJ_II", "<i>dJ</i><sub>II</sub>/<i>dφ</i>", "кг·м²", sig=4)]
    ids = chunked_tables(s, "Приведённый момент инерции второй группы звеньев", tab, cols, lead, "tab-dyn-J")
    fig = InertiaCurves().draw(study)
    s.paragraph(f"Значения по положениям — в таблице {ref(ids[0])}, график {_im('J2')} "
                f"с вкладом каждого звена — на рисунке {ref('fig-dyn-J')}.")
    s.figure("Приведённый момент инерции второй группы звеньев и вклад звеньев", fig.svg, fig.width_mm,
             id="fig-dyn-J")


def _moments(sec, study, d, tab, lab, row, kv, lead) -> None:
    s = sec.subsection("Приведённые моменты сил", "sec-dyn-moments")
    s.paragraph("Приведённый момент каждой силы найден из равенства мощностей (по существу — рычаг "
                "Н.&nbsp;Е.&nbsp;Жуковского), отнесённых к угловой скорости звена приведения:")
    s.formula(Formula(r"M_{\text{пр}} = \sum_i \left( F_{ix}\, x^{\prime}_i + F_{iy}\, y^{\prime}_i \right) + \sum_k M_k \varphi^{\prime}_k",
                      where=[(r"F_{ix}, F_{iy}", "проекции силы на оси координат, Н"),
                             (r"x^{\prime}_i, y^{\prime}_i", "аналоги скорости точки приложения силы, м"),
                             (r"M_k, \varphi^{\prime}_k", "момент, приложенный к звену k, Н·м, и аналог его угловой скорости")],
                      label="eq-Mpr"))
    fs = []
    working = [ld for ld in d.loads.loads if ld.name not in d.idle_loads]
    for ld in working:
        name = _tx(ld.name)
        val = row["M_" + ld.name]
        if ld.kind == "moment":
            Mv = val / kv["wq_" + ld.link] if kv["wq_" + ld.link] else 0.0
            fs.append(Formula(rf"M_{{{name}}} = M\, \varphi^{{\prime}}_{{{ld.link}}}",
                              rf"{_t(Mv, paren=True)} \cdot {_t(kv['wq_' + ld.link], paren=True)}",
                              _t(val, sig=4, unit="Н·м")))
            continue
        P = ld.point
        ph = d.loads.phase({"q": np.array([row["q"]])})
        Fx, Fy = ld.force({k: np.array([v]) for k, v in kv.items()}, ph)
        Fx, Fy = float(Fx[0]), float(Fy[0])
        # the analogues to as many digits as make the printed product the printed moment
        if ld.kind == "weight":
            G = written(-ld.vector[1])
            sg = agreeing_sig(lambda f: -G * f[0], [kv["vqy_" + P]], val)
            fs.append(Formula(rf"M_{{{name}}} = -G_{{{ld.link}}}\, y^{{\prime}}_{{{tex_point(P)}}}",
                              rf"-{_t(-ld.vector[1])} \cdot {_ts(kv['vqy_' + P], sg, paren=True)}",
                              _t(val, sig=4, unit="Н·м")))
        else:
            wx, wy = written(Fx), written(Fy)
            sg = agreeing_sig(lambda f: wx * f[0] + wy * f[1], [kv["vqx_" + P], kv["vqy_" + P]], val)
            fs.append(Formula(rf"M_{{{name}}} = F_x\, x^{{\prime}}_{{{tex_point(P)}}} + F_y\, y^{{\prime}}_{{{tex_point(P)}}}",
                              rf"{_t(Fx, paren=True)} \cdot {_ts(kv['vqx_' + P], sg, paren=True)} + "
                              rf"{_t(Fy, paren=True)} \cdot {_ts(kv['vqy_' + P], sg, paren=True)}",
                              _t(val, sig=4, unit="Н·м")))
    side = "с" if d.balance == "drive" else "д"
    names = " + ".join(rf"M_{{{_tx(ld.name)}}}" for ld in working) or "0"
    vals = " + ".join(_t(row["M_" + ld.name], sig=4, paren=True) for ld in working) or "0"
    fs.append(Formula(rf"M_{{\text{{{side}}}}} = {names}", vals,
                      _t(row["M_c" if d.balance == "drive" else "M_d"], sig=4, unit="Н·м")))
    if d.idle_loads:
        idle = ", ".join(html_label(n) for n in d.idle_loads)
        if len(d.idle_loads) == 1:      # agreement in number: «нагрузка G5 … не совершает»
            s.paragraph(f"Нагрузка {idle} работы не совершает (её приведённый момент равен нулю во всём цикле) "
                        "и далее не учитывается.")
        else:
            s.paragraph(f"Нагрузки {idle} работы не совершают (их приведённые моменты равны нулю во всём цикле) "
                        "и далее не учитываются.")
    s.paragraph(f"Для положения {pos_no(study, lab)}:")
    s.formula(*fs)
    cols = [Column("M_" + ld.name, _h("M", ld.name), "Н·м", sig=4) for ld in working]
    cols += [Column("M_c", _h("M", "с"), "Н·м", sig=4), Column("M_d", _h("M", "д"), "Н·м", sig=4),
             Column("M_sum", _h("M", "Σ"), "Н·м", sig=4)]
    ids = chunked_tables(s, "Приведённые моменты сил", tab, cols, lead, "tab-dyn-M")
    fig = MomentCurves().draw(study)
    s.paragraph(f"Приведённые моменты по положениям — в таблице {ref(ids[0])}, их графики — на рисунке "
                f"{ref('fig-dyn-M')}.")
    s.figure("Приведённые моменты сил", fig.svg, fig.width_mm, id="fig-dyn-M")
    toggle = toggle_gain(study)
    if toggle is not None:
        s.paragraph(str(_toggle_text(toggle)))


TOGGLE_GAIN = 3.0         # a force this many times the crank pin's tangential force balancing it: the toggle effect
TOGGLE_ZONE = 0.005       # the share of the cycle the force keeps its largest value at least (not a spike at a dead point)
TOGGLE_NEAR_DEAD = 0.3    # the force point's speed along the force over that stretch, at most this share of its cycle's largest


def toggle_gain(study) -> dict | None:
    """The force amplification of a mechanism whose output nears a dead (toggle) position while a
    working force is at its largest (a knuckle press, a jaw crusher). Over the crank angles where
    a resisting force F of the case's loads is within 0,1 % of its largest value F_max (at least
    TOGGLE_ZONE of the cycle), its reduced moment M (the power balance F·v = M·ω, eq. of §3.3,
    Артоболевский гл. «Силовой расчёт») is at most M_max; the tangential force at the crank pin
    that balances F there is F_t = M_max/r (r — the crank's length) and the gain F_max/F_t =
    F_max·r/M_max — the least over that stretch: it grows without bound towards the dead position,
    where the output's analog is zero. None for a mechanism without a crank or without such a force
    (gain under TOGGLE_GAIN, or a stretch away from a dead position: the point's speed along the
    force there over TOGGLE_NEAR_DEAD of its largest over the cycle)."""
    mech = study.mechanism
    d = study.dynamics
    if mech.driver.kind != "crank":
        return None
    cyc = study.cycle
    pin, cen = mech.crank_pin(), mech.driver.center
    r = float(np.hypot(cyc[f"x_{pin}"] - cyc[f"x_{cen}"], cyc[f"y_{pin}"] - cyc[f"y_{cen}"]).iloc[0])
    cols = {c: cyc[c].to_numpy() for c in cyc.columns}
    ph = d.loads.phase({"q": cols["q"]})
    best = None
    for ld in d.loads.loads:
        if ld.kind != "force" or ld.name in d.idle_loads:
            continue
        Fx, Fy = ld.force(cols, ph)
        F = np.hypot(Fx, Fy)
        M = d.cycle["M_" + ld.name].to_numpy()
        n = min(len(F), len(M))
        F, M = F[:n], M[:n]
        if not F.max() > 0:
            continue
        zone = F >= 0.999 * F.max()
        if zone.mean() < TOGGLE_ZONE or (M[zone] > 0).any():      # a spike, or a force that drives
            continue
        M_max = float(np.abs(M[zone]).max())
        # near a dead position: over the stretch the point's analog along the force (|M|/F by the
        # power balance) is a small share of its largest over the cycle — not a constant working
        # force over a whole stroke (a cutting force), whose «gain» is only a long input link
        u = np.array([Fx[:n][zone].mean(), Fy[:n][zone].mean()])
        u = u / np.hypot(*u)
        along = np.abs(cols["vqx_" + ld.point][:n] * u[0] + cols["vqy_" + ld.point][:n] * u[1])
        if M_max / float(F.max()) > TOGGLE_NEAR_DEAD * float(along.max()):
            continue
        gain = float(F.max()) * r / M_max if M_max > 0 else math.inf
        if math.isfinite(gain) and gain >= TOGGLE_GAIN and (best is None or gain > best["gain"]):
            best = dict(load=ld, F=float(F.max()), M=M_max, r=r, gain=gain, pin=pin, centre=cen)
    return best


def _toggle_text(t: dict) -> str:
    """The engineering remark on the toggle effect (:func:`toggle_gain`)."""
    name = Markup(html_label(t["load"].name))     # escaped by html_label
    return Markup(
        "Наибольшее значение силы {0} ({1}&nbsp;кН) приходится на положения, близкие к мёртвому положению "
        "механизма (эффект колена): приведённый к кривошипу момент этой силы там не превышает {2}&nbsp;Н·м, "
        "уравновешивающая её окружная сила на пальце кривошипа <i>F</i><sub>t</sub>&nbsp;=&nbsp;<i>M</i>/<i>l</i><sub>{3}{4}</sub>"
        "&nbsp;=&nbsp;{5}&nbsp;кН, т.&nbsp;е. механизм даёт выигрыш в силе не менее чем в {6} раза. К мёртвому положению "
        "аналог скорости выходного звена стремится к нулю и выигрыш неограниченно растёт; на деле его ограничивают "
        "упругие деформации звеньев, зазоры и трение в шарнирах, поэтому звенья и опоры рассчитывают на полную "
        "силу {0}.").format(name, fmt(t["F"] / 1e3, sig=4), fmt(t["M"], sig=4), t["centre"], t["pin"],
                             fmt(t["M"] / t["r"] / 1e3, sig=3), fmt(t["gain"], sig=3))


def _works(sec, study, d, tab, lead) -> None:
    s = sec.subsection("Работы сил и изменение кинетической энергии", "sec-dyn-works")
    sc = d.scalars
    st = d.settings
    C = _cycle_tex(study)
    if d.balance == "drive":
        s.formula(Formula(rf"A_{{\text{{с}}}} = \int_0^{{{C}}} M_{{\text{{с}}}}\, d\varphi", None,
                          _t(sc["A_c"], sig=5, unit="Дж"), label="eq-Ac"))
        if st.drive is None:
            s.paragraph("Движущий момент принят постоянным; из условия равенства нулю работы всех сил за цикл "
                        "установившегося движения:")
            s.formula(Formula(rf"M_{{\text{{д}}}} = -\frac{{A_{{\text{{с}}}}}}{{{C}}}",
                              rf"-\frac{{{_t(sc['A_c'], sig=5, paren=True)}}}{{{_t(st.cycle_length, sig=5)}}}",
                              _t(sc["M_d"], sig=5, unit="Н·м"), label="eq-Md"))
        else:
            s.paragraph(f"Движущий момент задан; его работа за цикл {fmt(sc['A_d'], sig=5, unit='Дж')} "
                        "уравновешивает работу сил сопротивления.")
    else:
        s.formula(Formula(rf"A_{{\text{{д}}}} = \int_0^{{{C}}} M_{{\text{{д}}}}\, d\varphi", None,
                          _t(sc["A_d"], sig=5, unit="Дж"), label="eq-Ad"))
        s.paragraph("Момент сил сопротивления потребителя принят постоянным; из условия равенства нулю работы "
                    "всех сил за цикл:")
        s.formula(Formula(rf"M_{{\text{{с}}}} = -\frac{{A_{{\text{{д}}}}}}{{{C}}}",
                          rf"-\frac{{{_t(sc['A_d'], sig=5)}}}{{{_t(st.cycle_length, sig=5)}}}",
                          _t(sc["M_c"], sig=5, unit="Н·м"), label="eq-Mc"))
    s.paragraph("Изменение кинетической энергии машины равно работе всех сил:")
    s.formula(Formula(r"\Delta T(\varphi) = A_{\Sigma}(\varphi) = A_{\text{д}}(\varphi) + A_{\text{с}}(\varphi)"
                      r" = \int_{0}^{\varphi} \left( M_{\text{д}} + M_{\text{с}} \right) d\varphi", label="eq-dT"))
    hi, lo = _two(sc["dT_max"], sc["dT_min"], "Дж")
    s.paragraph(f"Наибольшее и наименьшее значения ΔT за цикл: {hi} при "
                f"φ&nbsp;=&nbsp;{_phase_deg(study, sc['q_dT_max'])} и {lo} при "
                f"φ&nbsp;=&nbsp;{_phase_deg(study, sc['q_dT_min'])} (найдены решением уравнения "
                f"{_im('Msum0')}).")
    cols = [Column("A_c", _h("A", "с"), "Дж", sig=5), Column("A_d", _h("A", "д"), "Дж", sig=5),
            Column("A_sum", "Δ<i>T</i>", "Дж", sig=5), Column("T_II", _h("T", "II"), "Дж", sig=5),
            Column("dT_I", "Δ" + _h("T", "I"), "Дж", sig=5)]
    ids = chunked_tables(s, "Работы сил и изменение кинетической энергии", tab, cols, lead, "tab-dyn-A")
    f1 = WorkCurves().draw(study)
    f2 = EnergyCurves().draw(study)
    s.paragraph(f"Работы по положениям — в таблице {ref(ids[0])}; графики работ — на рисунке {ref('fig-dyn-A')}, "
                f"изменения кинетической энергии — на рисунке {ref('fig-dyn-T')}.")
    s.figure("Работы сил сопротивления, движущих сил и суммарная работа", f1.svg, f1.width_mm, id="fig-dyn-A")
    s.figure("Изменение кинетической энергии машины и первой группы звеньев", f2.svg, f2.width_mm,
             id="fig-dyn-T")


def _flywheel(sec, study, d) -> None:
    s = sec.subsection("Момент инерции маховика", "sec-dyn-flywheel")
    sc = d.scalars
    st = d.settings
    r = d.result
    me, wi, ex = r.mertsalov, r.wittenbauer, r.exact
    w, dl = st.omega_m, st.delta
    # a given δ substituted as the case writes it (0,04, not 0,04000); a found one to 4 digits
    dl_w = as_written(dl)
    dl_tex = (_t(dl, sig=4) if d.inverse is not None else dl_w if "/" in dl_w
              else _t(dl, sig=None, digits=len(dl_w.split(",")[1]) if "," in dl_w else 0))
    if d.inverse is not None:
        inv, u = d.inverse, st.ratio
        shaft = (f"на валу, вращающемся в u&nbsp;=&nbsp;{_ratio(u)} раза быстрее кривошипа; приведённый к валу "
                 f"кривошипа момент инерции маховика u²J&nbsp;=&nbsp;{fmt(u * u * st.J_given, sig=5)}&nbsp;кг·м²"
                 if u != 1 else "на валу кривошипа")
        s.paragraph(f"<b>Обратная задача.</b> Маховик задан: момент инерции J&nbsp;=&nbsp;{fmt(st.J_given, sig=5)}&nbsp;кг·м² "
                    f"{shaft}. С постоянной частью приведённого момента инерции {inline_math('J_I')} без маховика "
                    f"({fmt(d.J_I_const, sig=5)}&nbsp;кг·м²) {inline_math('J_I')}&nbsp;=&nbsp;{fmt(inv.J_I, sig=5)}&nbsp;кг·м². "
                    f"Точное установившееся движение машины с этим моментом инерции (периодическое решение уравнения "
                    f"движения в форме энергий за цикл) даёт ω<sub>max</sub>&nbsp;=&nbsp;{fmt(inv.omega_max, sig=5)}&nbsp;рад/с, "
                    f"ω<sub>min</sub>&nbsp;=&nbsp;{fmt(inv.omega_min, sig=5)}&nbsp;рад/с и коэффициент неравномерности хода "
                    f"δ&nbsp;=&nbsp;(ω<sub>max</sub>&nbsp;−&nbsp;ω<sub>min</sub>)/ω<sub>ср</sub>&nbsp;=&nbsp;{fmt(dl, sig=4)}. "
                    "Для проверки ниже решена прямая задача с этим δ: точный способ возвращает заданный маховик.")
    s.paragraph(f"{'Найденный' if d.inverse is not None else 'Требуемый'} коэффициент неравномерности хода δ&nbsp;=&nbsp;{fmt(dl, sig=4) if d.inverse is not None else as_written(dl)} при средней угловой "
                f"скорости ω<sub>ср</sub>&nbsp;=&nbsp;{fmt(w, digits=3)}&nbsp;рад/с "
                f"(<i>n</i>&nbsp;=&nbsp;{fmt_given(w * 30 / math.pi)}&nbsp;об/мин); "
                f"{_im('delta')}, "
                f"{_im('wm')}. "
                f"Момент инерции {inline_math('J_I')} найден тремя способами; в дальнейших расчётах принято "
                f"значение, найденное {METHOD_INSTR[st.method]}.")
    # Мерцалов
    s.paragraph("<b>Метод Мерцалова.</b> Кинетическая энергия второй группы приближённо вычисляется по средней "
                "скорости, изменение кинетической энергии первой группы — как разность:")
    s.formula(Formula(r"T_{II}(\varphi) \approx \frac{J_{II}(\varphi)\,\omega_{\text{ср}}^2}{2}, \quad"
                      r" \Delta T_I(\varphi) = \Delta T(\varphi) - T_{II}(\varphi)", label="eq-mertsalov"))
    s.paragraph(mertsalov_extremes_text(study))
    dT_range = me.dT_I_max - me.dT_I_min
    s.formula(Formula(r"\Delta T_{I\,max}", None, _t(me.dT_I_max, sig=5, unit="Дж")),
              Formula(r"\Delta T_{I\,min}", None, _t(me.dT_I_min, sig=5, unit="Дж")),
              Formula(r"\Delta T_{I\,\text{нб}} = \Delta T_{I\,max} - \Delta T_{I\,min}",
                      rf"{_t(me.dT_I_max, sig=5)} - {_t(me.dT_I_min, sig=5, paren=True)}",
                      _t(dT_range, sig=5, unit="Дж")),
              Formula(r"J_I = \frac{\Delta T_{I\,\text{нб}}}{\omega_{\text{ср}}^2\,\delta}",
                      rf"\frac{{{_t(dT_range, sig=5)}}}{{{_t(w, digits=3)}^2 \cdot {dl_tex}}}",
                      _t(me.J_I, sig=5, unit="кг·м²"), label="eq-JI-mertsalov"))
    # Виттенбауэр
    fig = WittenbauerDiagram().draw(study)
    s.paragraph(f"<b>Метод Виттенбауэра.</b> Строится диаграмма энергия–масса ΔT(J<sub>II</sub>) (рисунок "
                f"{ref('fig-dyn-witt')}); к ней проводятся касательные под углами ψ<sub>max</sub> и ψ<sub>min</sub>, "
                "тангенсы которых (в масштабах диаграммы μ<sub>J</sub>, μ<sub>T</sub>) пропорциональны "
                "ω<sub>max</sub>²/2 и ω<sub>min</sub>²/2; касательные отсекают на оси ΔT отрезок KL:")
    s.formula(Formula(r"\mathrm{tg}\,\psi_{max} = \frac{\mu_J}{2\mu_T}\,\omega_{\text{ср}}^2 \left(1 + \frac{\delta}{2}\right)^2,"
                      r"\quad \mathrm{tg}\,\psi_{min} = \frac{\mu_J}{2\mu_T}\,\omega_{\text{ср}}^2 \left(1 - \frac{\delta}{2}\right)^2",
                      label="eq-witt-slopes"),
              Formula(r"J_I = \frac{KL}{\omega_{\text{ср}}^2\,\delta}",
                      rf"\frac{{{_t(wi.KL, sig=5)}}}{{{_t(w, digits=3)}^2 \cdot {dl_tex}}}",
                      _t(wi.J_I, sig=5, unit="кг·м²"), label="eq-JI-witt"))
    s.figure("Диаграмма энергия–масса (диаграмма Виттенбауэра) с касательными", fig.svg, fig.width_mm,
             id="fig-dyn-witt")
    s.paragraph(f"Точки касания: φ&nbsp;=&nbsp;{_phase_deg(study, wi.tangent_max.phi)} (верхняя) и "
                f"{_phase_deg(study, wi.tangent_min.phi)} (нижняя); K&nbsp;=&nbsp;{_two(wi.K, wi.L, 'Дж')[0]}, "
                f"L&nbsp;=&nbsp;{_two(wi.K, wi.L, 'Дж')[1]}. С точными наклонами (1&nbsp;±&nbsp;δ/2)² метод "
                "Виттенбауэра точен: касание означает, что в этих положениях ω&nbsp;=&nbsp;ω<sub>max</sub> и "
                "ω<sub>min</sub>. С упрощёнными наклонами ω<sub>ср</sub>²(1&nbsp;±&nbsp;δ)/2 получается "
                f"J<sub>I</sub>&nbsp;=&nbsp;{fmt(wi.J_I_linear, sig=6, unit='кг·м²')}.")
    # exact
    s.paragraph(f"<b>Точное решение.</b> Если моменты сил зависят только от положения звена приведения, "
                f"уравнение движения {ref('eq-dyn-energy')} интегрируется точно:")
    s.formula(Formula(r"\omega(\varphi) = \sqrt{\frac{2\left(T_0 + A_{\Sigma}(\varphi)\right)}{J_I + J_{II}(\varphi)}}",
                      label="eq-omega-exact"))
    s.paragraph(f"Постоянная {_s('T_0')} и момент инерции {_s('J_I')} подобраны (метод Ньютона) так, чтобы "
                f"(ω<sub>max</sub>&nbsp;+&nbsp;ω<sub>min</sub>)/2&nbsp;=&nbsp;ω<sub>ср</sub> и "
                f"(ω<sub>max</sub>&nbsp;−&nbsp;ω<sub>min</sub>)/ω<sub>ср</sub>&nbsp;=&nbsp;δ; экстремумы ω "
                f"найдены из уравнения {_im('exact_ext')}: "
                f"{_s('J_I')}&nbsp;=&nbsp;{fmt(ex.J_I, sig=6, unit='кг·м²')}, "
                f"{_s('T_0')}&nbsp;=&nbsp;{fmt(ex.T0, sig=6, unit='Дж')}.")
    rows = [{"m": "точное решение", "J": r.J_I_exact, "dev": 0.0, "delta": sc["delta_achieved_exact"]},
            {"m": "Мерцалов", "J": r.J_I_mertsalov, "dev": r.dev_mertsalov_pct,
             "delta": sc["delta_achieved_mertsalov"]},
            {"m": "Виттенбауэр (наклоны (1 ± δ/2)²)", "J": r.J_I_wittenbauer, "dev": r.dev_wittenbauer_pct,
             "delta": sc["delta_achieved_wittenbauer"]},
            {"m": "Виттенбауэр (наклоны 1 ± δ)", "J": r.J_I_wittenbauer_linear,
             "dev": r.dev_wittenbauer_linear_pct, "delta": sc["delta_achieved_wittenbauer_linear"]}]
    s.paragraph(f"Сравнение методов — в таблице {ref('tab-dyn-methods')}: для каждого J<sub>I</sub> указан "
                "коэффициент неравномерности, который фактически получится при точном движении машины.")
    s.table("Момент инерции первой группы звеньев по трём методам", [
        Column("m", "Метод"), Column("J", _h("J", "I"), "кг·м²", sig=7),
        Column("dev", "Отклонение от точного", "%", fmt=lambda x: fmt(x, digits=4)),
        Column("delta", "Фактический δ", None, digits=5)], pd.DataFrame(rows), id="tab-dyn-methods",
        highlight_rows=[["exact", "mertsalov", "wittenbauer"].index(st.method)])
    Jc = d.J_I_const
    s.paragraph("Момент инерции маховика (дополнительной маховой массы):")
    # the constant part by the symbol §3.1 introduced: J_O (rotor and transmission), J_I,0 with the crank
    J0_tex = "J_{I,0}" if d.J_crank else "J_O"
    s.formula(Formula(rf"J_{{\text{{доп}}}} = J_I - {J0_tex}", rf"{_t(r.J_I, sig=6)} - {_t(Jc, sig=4)}",
                      _t(r.J_flywheel, sig=6, unit="кг·м²"), label="eq-Jdop"))
    if not r.flywheel.needed:
        s.paragraph("J<sub>доп</sub>&nbsp;≤&nbsp;0: собственной инерции машины достаточно, маховик не нужен.")


def printed_name(study, key: str, title: str) -> Markup:
    """The name of a printed value ``column@label`` at the note's position number: the source's
    own mark of the position («ω(f)») written «ω (положение 13)» — the key's tables speak of the
    note's positions; a scalar's title as it is."""
    name = Markup(title) if title else Markup(escape(key))
    col, _, lab = key.partition("@")
    if not lab:
        return name
    mark = str(Markup("({})").format(lab))
    if str(name).endswith(mark):
        name = Markup(str(name)[:-len(mark)].rstrip())
    return Markup("{}&nbsp;(положение&nbsp;{})").format(name, pos_no(study, lab))


def printed_block(s, pr: pd.DataFrame, study) -> None:
    """The comparison with the values printed in the worksheet (the answer key, report/key.py),
    positions by the note's numbers (:func:`printed_name`)."""
    bad = pr[~pr["within"]]
    s.paragraph(f"Значения, напечатанные в исходном расчёте, сопоставлены с вычисленными в таблице "
                f"{ref('tab-dyn-printed')} (допуск — единица последнего напечатанного разряда). Совпадают "
                f"{int(pr['within'].sum())} из {len(pr)}.")
    df = pr.copy()
    df["name"] = [printed_name(study, k, t) for t, k in zip(df["title"], df["key"])]
    df["ok"] = ["да" if w else "нет" for w in df["within"]]
    # each exact value to two digits more than printed, so the row compares digit by digit
    df["exact"] = [fmt(c, sig=_printed_sig(t) + 2, exp_from=1e9) for t, c in zip(df["printed"], df["computed"])]
    df["rel"] = [fmt(100 * (v - c) / c, sig=2) if c else "—" for v, c in zip(df["value"], df["computed"])]
    df["printed"] = [_as_printed(t, v) for t, v in zip(df["printed"], df["value"])]
    s.table("Сравнение с напечатанными значениями", [
        Column("name", "Величина", fmt=Markup), Column("printed", "Напечатано"),
        Column("exact", "Вычислено", fmt=str), Column("rel", "Отклонение", "%", fmt=str),
        Column("ok", "Совпадает")], df, id="tab-dyn-printed",
        highlight_rows=[int(i) for i in np.flatnonzero(~pr["within"].to_numpy())])
    for _, r in bad.iterrows():
        title = printed_name(study, r["key"], r["title"])
        note = r["note"] or "расхождение превышает единицу последнего напечатанного разряда."
        s.paragraph(Markup("Примечание — {}: напечатано {}, точное значение {}. ").format(
            title, _as_printed(r["printed"], r["value"]), fmt(r["computed"], sig=6)) + Markup(note))


def _printed_sig(text: str) -> int:
    """Significant digits of a number as printed: "-6.1e3" → 2, "0.375" → 3."""
    mant = str(text).lower().split("e")[0].lstrip("+-−")
    return len(mant.replace(".", "").replace(",", "").lstrip("0") or "0")


def _as_printed(text: str, value: float) -> str:
    """A printed number in the report's style with its printed digits: "-6.1e3" → "−6,1·10³"."""
    return fmt(value, sig=_printed_sig(text), exp_from=1e3 if "e" in str(text).lower() else 1e6)


def _dimensions(sec, study, d) -> None:
    s = sec.subsection("Размеры маховика", "sec-dyn-dims")
    fw = d.result.flywheel
    kw = d.settings.flywheel_kw
    u = d.settings.ratio
    J = d.result.J_flywheel / u ** 2
    if not fw.needed:
        s.paragraph("Маховик не требуется.")
        return
    sym = r"J_{\text{доп}}"
    if u != 1.0:
        # equal kinetic energy on both shafts: J_shaft·(u·ω)²/2 = J_доп·ω²/2 (Артоболевский [1], приведение масс)
        sym = r"J_{\text{м}}"
        chain = drive_chain(study)
        if chain:
            s.paragraph(chain)
        s.paragraph(f"Маховик устанавливается на другом валу; передаточное отношение от него к кривошипу "
                    f"u&nbsp;=&nbsp;ω<sub>м</sub>/ω<sub>1</sub>&nbsp;=&nbsp;{_ratio(u)}. Из равенства кинетических энергий "
                    "маховика на его валу и приведённого к кривошипу, J<sub>м</sub>(uω)²&nbsp;=&nbsp;J<sub>доп</sub>ω², "
                    "момент инерции маховика на его валу:")
        s.formula(Formula(rf"{sym} = \frac{{J_{{\text{{доп}}}}}}{{u^2}}",
                          rf"\frac{{{_t(d.result.J_flywheel, sig=6)}}}{{{_ratio(u)}^2}}",
                          _t(J, sig=5, unit="кг·м²"), label="eq-Jshaft"))
    r5 = rf"\sqrt[5]{{{_t(J, sig=6)}}}"
    s.paragraph(f"Маховик в виде обода со спицами и ступицей (рисунок {ref('fig-dyn-flywheel')}; эмпирические зависимости курсового пособия, "
                f"ψ<sub>b</sub>&nbsp;=&nbsp;{as_written(kw['psi_b'])}, ψ<sub>h</sub>&nbsp;=&nbsp;{as_written(kw['psi_h'])}, "
                f"ρ&nbsp;=&nbsp;{fmt(kw['rho'], sig=4)}&nbsp;кг/м³):")
    rim, disk = fw.rim, fw.disk
    s.formula(Formula(rf"D_2 = {_c(kw['rim_coef'])} \sqrt[5]{{{sym}}}", rf"{_c(kw['rim_coef'])} \cdot {r5}",
                      _t(rim.D2, digits=3, unit="м")),
              Formula(rf"D_1 = {_c(kw['rim_inner_ratio'])}\, D_2", None, _t(rim.D1, digits=3, unit="м")),
              Formula(rf"b = {_c(kw['rim_width_ratio'])}\, D_2", None, _t(rim.b, digits=3, unit="м")),
              Formula(rf"m = {_c(kw['rim_mass_coef'])} \left( D_2^2 - D_1^2 \right) b",
                      rf"{_c(kw['rim_mass_coef'])} \cdot \left( {_t(rim.D2, digits=3)}^2 - {_t(rim.D1, digits=3)}^2 \right) \cdot {_t(rim.b, digits=3)}",
                      _t(rim.m, sig=4, unit="кг")))
    s.paragraph("Маховик в виде сплошного диска:")
    s.formula(Formula(rf"D = {_c(kw['disk_coef'])} \sqrt[5]{{{sym}}}", rf"{_c(kw['disk_coef'])} \cdot {r5}",
                      _t(disk.D, digits=3, unit="м")),
              Formula(rf"b = {_c(kw['disk_width_ratio'])}\, D", None, _t(disk.b, digits=3, unit="м")),
              Formula(rf"m = {_c(kw['disk_mass_coef'])}\, D^3", rf"{_c(kw['disk_mass_coef'])} \cdot {_t(disk.D, digits=3)}^3",
                      _t(disk.m, sig=4, unit="кг")))
    fig = FlywheelDrawing().draw(study)
    s.figure(f"Маховик: обод со спицами и сплошной диск (размеры в мм, масштаб {gost_ratio(fig.mu)})",
             fig.svg, fig.width_mm, id="fig-dyn-flywheel")
    rows = [
        {"v": "обод со спицами (эмпирически)", "D": rim.D2, "d": rim.D1, "b": rim.b, "m": rim.m, "u": rim.v_rim},
        {"v": "сплошной диск (эмпирически)", "D": disk.D, "d": math.nan, "b": disk.b, "m": disk.m, "u": disk.v_rim},
        {"v": "диск, J = mD²/8", "D": fw.disk_physical.D, "d": math.nan, "b": fw.disk_physical.b,
         "m": fw.disk_physical.m, "u": fw.disk_physical.v_rim},
        {"v": "кольцо без спиц, J = m(D₂² + D₁²)/8", "D": fw.rim_physical.D2, "d": fw.rim_physical.D1,
         "b": fw.rim_physical.b, "m": fw.rim_physical.m, "u": fw.rim_physical.v_rim},
    ]
    s.paragraph(f"Варианты маховика сопоставлены в таблице {ref('tab-dyn-fw')}; окружная скорость обода "
                f"{_im('vrim_u') if u != 1.0 else _im('vrim')} сравнивается с допускаемой "
                f"[v]&nbsp;=&nbsp;{fmt_given(fw.v_limit)}&nbsp;м/с.")
    s.table("Размеры и масса маховика", [
        Column("v", "Вариант"), Column("D", "<i>D</i>", "м", digits=3), Column("d", "<i>D</i><sub>1</sub>", "м", digits=3),
        Column("b", "<i>b</i>", "м", digits=3), Column("m", "<i>m</i>", "кг", sig=4),
        Column("u", "<i>v</i>", "м/с", digits=2)], pd.DataFrame(rows), id="tab-dyn-fw")
    if fw.any_exceeds:
        s.paragraph(f"<b>Внимание:</b> окружная скорость обода превышает допускаемую "
                    f"{fmt_given(fw.v_limit)}&nbsp;м/с — маховик следует установить на более медленный вал "
                    "или выполнить из более прочного материала.")
    else:
        s.paragraph("Окружная скорость обода всех вариантов меньше допускаемой.")


def _motion(sec, study, d, tab, mot, lab, row, lead) -> None:
    s = sec.subsection("Закон движения машины", "sec-dyn-motion")
    st = d.settings
    r = d.result
    sc = d.scalars
    w, e = row["omega"], row["eps"]
    Jt = r.J_I + row["J_II"]
    s.paragraph(f"Угловая скорость и угловое ускорение звена приведения ({METHOD_RU[st.method]}) для положения {pos_no(study, lab)}:")
    fs = []
    if st.method == "mertsalov":
        me = r.mertsalov
        mid = 0.5 * (me.dT_I_max + me.dT_I_min)
        fs.append(Formula(r"\omega = \omega_{\text{ср}} + \frac{\Delta T_I - (\Delta T_{I\,max} + \Delta T_{I\,min})/2}"
                          r"{\omega_{\text{ср}} J_I}",
                          rf"{_t(st.omega_m, digits=3)} + \frac{{{_t(row['dT_I'], sig=5, paren=True)} - "
                          rf"{_t(mid, sig=5, paren=True)}}}{{{_t(st.omega_m, digits=3)} \cdot {_t(r.J_I, sig=5)}}}",
                          _t(w, sig=5, unit="рад/с")))
    else:
        T0 = r.exact.T0 if st.method == "exact" else r.wittenbauer.T0
        fs.append(Formula(r"\omega = \sqrt{\frac{2\left(T_0 + A_{\Sigma}\right)}{J_I + J_{II}}}",
                          rf"\sqrt{{\frac{{2 \cdot \left({_t(T0, sig=7)} + {_t(row['A_sum'], sig=5, paren=True)}\right)}}"
                          rf"{{{_t(r.J_I, sig=6)} + {_t(row['J_II'], sig=5)}}}}}",
                          _t(w, sig=5, unit="рад/с")))
    fs.append(Formula(r"\varepsilon = \frac{M_{\Sigma} - \frac{1}{2} J_{II}^{\prime}\,\omega^2}{J_I + J_{II}}",
                      rf"\frac{{{_t(row['M_sum'], sig=5, paren=True)} - 0{{,}}5 \cdot {_t(row['dJ_II'], sig=4, paren=True)}"
                      rf" \cdot {_t(w, sig=5)}^2}}{{{_t(Jt, sig=6)}}}",
                      _t(e, sig=4, unit="рад/с²"), label="eq-eps"))
    s.formula(*fs)
    cols = [Column("omega", "ω", "рад/с", sig=5), Column("eps", "ε", "рад/с²", sig=4)]
    if st.method != "exact":
        cols += [Column("omega_exact", "ω<sub>точн</sub>", "рад/с", sig=5),
                 Column("eps_exact", "ε<sub>точн</sub>", "рад/с²", sig=4)]
    ids = chunked_tables(s, "Угловая скорость и угловое ускорение звена приведения", tab, cols, lead, "tab-dyn-w")
    fig = MotionCurves().draw(study)
    s.paragraph(f"За цикл ω<sub>max</sub>&nbsp;=&nbsp;{fmt(sc['omega_max'], sig=5)}&nbsp;рад/с при "
                f"φ&nbsp;=&nbsp;{_phase_deg(study, sc['q_omega_max'])}, ω<sub>min</sub>&nbsp;=&nbsp;"
                f"{fmt(sc['omega_min'], sig=5)}&nbsp;рад/с при φ&nbsp;=&nbsp;{_phase_deg(study, sc['q_omega_min'])}; "
                f"коэффициент неравномерности точного движения с принятым J<sub>I</sub> — "
                f"{fmt(r.delta_achieved, digits=5)} (задан {as_written(st.delta)}). Значения по положениям — в "
                f"таблице {ref(ids[0])}, графики — на рисунке {ref('fig-dyn-w')}.")
    s.figure("Угловая скорость и угловое ускорение звена приведения", fig.svg, fig.width_mm, id="fig-dyn-w")
    # true motion
    mech = study.mechanism
    pts, _ = motion_points(study)      # a translating link by one point (§ 2.2 says so)
    links = [l.name for l in mech.moving if l.name != mech.driver.link
             and float(np.abs(study.cycle["wq_" + l.name]).max()) > 1e-12]
    s.paragraph("Истинные скорости и ускорения точек и звеньев вычислены с найденными ω(φ) и ε(φ): "
                f"{_im('v')}, "
                f"{_im('a')}, "
                f"{_im('wk')}, "
                f"{_im('ek')}.")
    tv = [Column(f"v_{p}", sub("V", p), "м/с", sig=4) for p in pts]
    tv += [Column(f"w_{k}", sub("ω", k), "рад/с", sig=4) for k in links]
    chunked_tables(s, "Истинные скорости точек и угловые скорости звеньев", mot, tv, lead, "tab-dyn-v")
    ta = [Column(f"a_{p}", sub("a", p), "м/с²", sig=4) for p in pts]
    ta += [Column(f"e_{k}", sub("ε", k), "рад/с²", sig=4) for k in links]
    chunked_tables(s, "Истинные ускорения точек и угловые ускорения звеньев", mot, ta, lead, "tab-dyn-a")


def comparison_block(sec, study) -> None:
    """The comparison with another variant of the case (the answer key, report/key.py)."""
    d = study.dynamics
    cmp = d.comparison
    title = d.settings.compare[1]
    s = sec.subsection("Сравнение с исходным вариантом", "sec-dyn-compare")
    at = cmp.attrs
    s.paragraph(f"Результаты сопоставлены с вариантом «{title}» (таблица {ref('tab-dyn-compare')}); сравниваются "
                "одинаковые методы. Наибольшее за цикл различие угловых скоростей точного движения — "
                f"{fmt(at['omega_diff_max'], sig=3)}&nbsp;рад/с ({fmt_pct(at['omega_diff_rel'], digits=3)} от "
                f"ω<sub>ср</sub>), угловых ускорений — {fmt(at['eps_diff_max'], sig=3)}&nbsp;рад/с²; "
                f"угловые скорости, принятые в расчётах вариантов, различаются не более чем на "
                f"{fmt(at['omega_diff_chosen'], sig=3)}&nbsp;рад/с.")
    df = cmp.copy()
    df["title"] = [Markup(t) for t in df["title"]]
    s.table("Сравнение с исходным вариантом", [
        Column("title", "Величина", fmt=Markup), Column("unit", "Единица"),
        Column("this", "Данный вариант", None, sig=6), Column("other", "Исходный вариант", None, sig=6),
        Column("change_pct", "Изменение", "%", fmt=lambda x: fmt(x, digits=3, sign=True))], df,
        id="tab-dyn-compare")


# --------------------------------------------------------------------------------------------
# ЗАКЛЮЧЕНИЕ
# --------------------------------------------------------------------------------------------
def _delta_judgement(st) -> list[str]:
    """δ of the case against the usual range for its kind of machine (``DELTA_RANGES``). The
    ranges could not be checked against a source in this project (see the note at
    ``DELTA_RANGES``), so the sentence cites none and calls the range approximate."""
    if st.machine is None:
        return []
    name, lo, hi = DELTA_RANGES[st.machine]
    rng = (f"ориентировочный диапазон для машин этого типа ({name}) — δ&nbsp;=&nbsp;{as_written(round(lo, 4))}…"
           f"{as_written(round(hi, 4))} (1/{round(1 / lo)}…1/{round(1 / hi)})")
    d = st.delta
    if d > hi * (1 + 1e-9):
        verdict = ("заданный δ больше: ход машины менее равномерен, чем обычно для таких машин; "
                   "при δ из этого диапазона маховик был бы в "
                   f"{fmt(d / hi, sig=2)} раза больше ({_s('J_I')} обратно пропорционален δ)")
    elif d < lo * (1 - 1e-9):
        verdict = ("заданный δ меньше: маховик больше, чем обычно требуется для таких машин; "
                   f"при δ&nbsp;=&nbsp;{fmt(lo, sig=2)} он был бы в {fmt(lo / d, sig=2)} раза меньше")
    else:
        verdict = "заданный δ в этом диапазоне"
    return [f"Коэффициент неравномерности хода δ&nbsp;=&nbsp;{as_written(d)}: {rng}; {verdict}."]


SMALL_FLYWHEEL = 0.05     # J_доп below this share of J_I: the machine's own rotating masses nearly suffice


def _small_flywheel(r, delta: float, u: float) -> list[str]:
    """Engineering judgement on a flywheel that is a small part of the required J_I (a sewing
    machine's crank and motor rotor already give nearly all of it): without it, by J_I·δ ≈ const
    (J_I = ΔT_нб/(ω_ср²·δ), Мерцалов [2]), δ₀ ≈ δ·J_I/(J_I − J_доп) — a few per cent above the
    given δ, so no separate flywheel is needed when the shaft's rotating parts give J_доп."""
    if not 0 < r.J_flywheel < SMALL_FLYWHEEL * r.J_I:
        return []
    d0 = delta * r.J_I / (r.J_I - r.J_flywheel)
    share = fmt(100 * r.J_flywheel / r.J_I, sig=2)
    need = _s("J_m") if u != 1.0 else _s("J_dop")
    return [f"Маховик мал: {_s('J_dop')} составляет {share}&nbsp;% требуемого {_s('J_I')}, заданную неравномерность "
            f"почти полностью обеспечивают звенья и вращающиеся массы привода; без маховика δ&nbsp;≈&nbsp;{_s('d0')}"
            f"&nbsp;=&nbsp;{fmt(d0, sig=3)}. Отдельный маховик можно не ставить, "
            f"если детали, вращающиеся на этом валу (шкив, муфта), имеют момент инерции не менее {need}."]


# the symbols of the conclusion in TeX, set by inline_math as the text sets them (italic letters,
# upright word subscripts): «J<sub>I</sub>» typed by hand came out upright beside the text's italic
SYM = {"A_c": r"A_{\text{с}}", "A_d": r"A_{\text{д}}", "M_d": r"M_{\text{д}}", "M_c": r"M_{\text{с}}", "J_I": "J_I",
       "J_dop": r"J_{\text{доп}}", "J_m": r"J_{\text{м}}", "J_dv": r"J_{\text{дв}}", "u": "u", "D_2": "D_2",
       "b": "b", "m": "m", "D": "D", "v": "v", "[v]": "[v]", "T_0": "T_0",
       "J_m=": r"J_{\text{м}} = J_{\text{доп}}/u^2", "J_dv=": r"J_{\text{дв}} = J_{\text{доп}}/u^2",
       "v=u": r"v = u\,\omega_{\max} D/2", "v=": r"v = \omega_{\max} D/2",
       "d0": r"\delta \cdot J_I/(J_I - J_{\text{доп}})"}


def _s(key: str) -> str:
    """The conclusion's symbol ``key`` of :data:`SYM` as inline math (HTML)."""
    return str(inline_math(SYM[key]))


def conclusion_lines(study) -> list[str]:
    """HTML lines about the dynamics for the ЗАКЛЮЧЕНИЕ (assemble._conclusion)."""
    d = study.dynamics
    sc = d.scalars
    r = d.result
    st = d.settings
    out = []
    if d.balance == "drive":
        out.append(f"Работа сил сопротивления за цикл {_s('A_c')}&nbsp;=&nbsp;{fmt(sc['A_c'], sig=5)}&nbsp;Дж; "
                   f"{'постоянный ' if st.drive is None else 'средний '}приведённый движущий момент "
                   f"{_s('M_d')}&nbsp;=&nbsp;{fmt(sc['M_d'], sig=5)}&nbsp;Н·м.")
    else:
        out.append(f"Работа движущих сил за цикл {_s('A_d')}&nbsp;=&nbsp;{fmt(sc['A_d'], sig=5)}&nbsp;Дж; "
                   f"постоянный приведённый момент сопротивления {_s('M_c')}&nbsp;=&nbsp;{fmt(sc['M_c'], sig=5)}&nbsp;Н·м.")
    # the inverse task (a given flywheel): δ is found, printed as the text prints it (4 digits), not as given
    head = (f"Для δ&nbsp;=&nbsp;{as_written(st.delta)} при ω<sub>ср</sub>&nbsp;=&nbsp;{fmt(st.omega_m, digits=3)}&nbsp;рад/с "
            "требуется " if d.inverse is None else
            f"С заданным маховиком коэффициент неравномерности хода δ&nbsp;=&nbsp;{fmt(st.delta, sig=4)} при "
            f"ω<sub>ср</sub>&nbsp;=&nbsp;{fmt(st.omega_m, digits=3)}&nbsp;рад/с; ему соответствует ")
    out.append(f"{head}{_s('J_I')}&nbsp;=&nbsp;{fmt(r.J_I, sig=5)}&nbsp;кг·м² ({METHOD_RU[st.method]}); "
               + ("" if st.method == "exact" else
                  f"точное значение {fmt(r.J_I_exact, sig=6)}&nbsp;кг·м², ")
               + "относительно точного решения метод Мерцалова даёт отклонение "
               f"{fmt(r.dev_mertsalov_pct, digits=3, sign=True)}&nbsp;%, метод Виттенбауэра "
               f"{fmt(r.dev_wittenbauer_pct, digits=3, sign=True)}&nbsp;%.")
    toggle = toggle_gain(study)
    if toggle is not None:
        out.append(str(Markup("Вблизи мёртвого положения механизм даёт выигрыш в силе не менее чем в {} раза: сила {} "
                              "в {}&nbsp;кН уравновешивается там моментом на кривошипе не более {}&nbsp;Н·м.").format(
            fmt(toggle["gain"], sig=3), Markup(html_label(toggle["load"].name)), fmt(toggle["F"] / 1e3, sig=4),
            fmt(toggle["M"], sig=4))))
    out += _delta_judgement(st)
    fw = r.flywheel
    if fw.needed:
        u = d.settings.ratio
        shaft = ("" if u == 1.0 else f"; на валу маховика ({_s('u')}&nbsp;=&nbsp;{_ratio(u)} к кривошипу) "
                 f"{_s('J_m=')}&nbsp;=&nbsp;{fmt(r.J_flywheel / u ** 2, sig=5)}&nbsp;кг·м²")
        out.append(f"Момент инерции маховика {_s('J_dop')}&nbsp;=&nbsp;{fmt(r.J_flywheel, sig=5)}&nbsp;кг·м²{shaft}: обод "
                   f"{_s('D_2')}&nbsp;=&nbsp;{fmt(fw.rim.D2, digits=3)}&nbsp;м, {_s('b')}&nbsp;=&nbsp;{fmt(fw.rim.b, digits=3)}&nbsp;м, "
                   f"{_s('m')}&nbsp;=&nbsp;{fmt(fw.rim.m, sig=4)}&nbsp;кг или диск {_s('D')}&nbsp;=&nbsp;{fmt(fw.disk.D, digits=3)}&nbsp;м, "
                   f"{_s('m')}&nbsp;=&nbsp;{fmt(fw.disk.m, sig=4)}&nbsp;кг"
                   + ".")
        out += _small_flywheel(r, st.delta, u)
        v = max(fw.rim.v_rim, fw.disk.v_rim)
        if math.isfinite(v):
            formula = _s("v=u") if u != 1.0 else _s("v=")
            # the advice of §3.6 («на более медленный вал или из более прочного материала»), not another one
            verdict = (f"превышает допускаемую {_s('[v]')}&nbsp;=&nbsp;{fmt_given(fw.v_limit)}&nbsp;м/с: маховик следует "
                       "установить на более медленный вал или выполнить из более прочного материала (либо сделать "
                       "обод меньшего диаметра и большей ширины)" if fw.any_exceeds else
                       f"не превышает допускаемой {_s('[v]')}&nbsp;=&nbsp;{fmt_given(fw.v_limit)}&nbsp;м/с")
            where = f" (маховик на валу, вращающемся в {_s('u')} раз быстрее кривошипа)" if u != 1.0 else ""
            out.append(f"Наибольшая окружная скорость обода{where} {formula}&nbsp;=&nbsp;"
                       f"{fmt(v, sig=3)}&nbsp;м/с {verdict}.")
        if u == 1.0 and min(fw.rim.m, fw.disk.m) > 500:
            out.append(f"Маховик массой {fmt(min(fw.rim.m, fw.disk.m) / 1000, digits=1)}&nbsp;т на валу кривошипа "
                       "громоздок. Его целесообразно установить на быстроходный вал (вал двигателя): при "
                       f"передаточном отношении {_s('u')} от этого вала к кривошипу требуемый момент инерции "
                       f"уменьшается в {_s('u')}² раз, {_s('J_dv=')} (кинетическая энергия "
                       f"маховика та же), а масса при том же диаметре — примерно в {_s('u')}² раз.")
    else:
        out.append("Собственной инерции машины достаточно для заданного δ: маховик не нужен.")
    out.append(f"Угловая скорость кривошипа изменяется от {fmt(sc['omega_min'], sig=5)} до "
               f"{fmt(sc['omega_max'], sig=5)}&nbsp;рад/с; фактический коэффициент неравномерности "
               f"{fmt(r.delta_achieved, digits=5)}.")
    return out
