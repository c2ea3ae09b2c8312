"""Section «Силовой (кинетостатический) анализ»: the loads and inertia forces at the chosen
position, each Assur group taken apart with its force polygon and its reactions, the table of
reactions over the report positions, the balancing moment (or the actuator force) with its
checks by power balance and Жуковский's lever, reaction diagrams over the cycle; for an
actuator-driven linkage the capacity, force and pressure of the cylinders (worksheet 002,
table 4.1) and, with ``[carrier]``, the axle loads of the vehicle (table 6.1).

``present(study)``: the case has ``[forces]``.  ``conclusion_lines(study)``: the lines of the
ЗАКЛЮЧЕНИЕ about the force analysis."""
from __future__ import annotations

import math

import numpy as np
import pandas as pd
from markupsafe import Markup, escape

from ...analysis.forces import crank_pin
from ...core import kinetostatics as KS
from ...mechanism.model import FRAME
from ...scenes.forces import (AxleCurves, CapacityCurves, GroupForces, ReactionCurves, ZhukovskyLever, group_name,
                              group_vectors, html_label, is_initial, load_label, shown_key)
from ...scenes.draw import mu_text
from ...style.numbers import agreeing_sig, fmt, shared_decimals, tex_num, trimmed_sig, written
from ..document import Column, Formula, Section, ref
from ..formulas import inline_math
from ..russian import plural
from .kinematics import _insets_text, _zero_note, zero_columns
from .common import (chosen_position, chunked_tables, input_word, pos_no, position_lead, q_degrees, q_header,
                     html_point, sub, tex_point)

NEEDS = ("kinematics", "cycle", "forces")


def present(study) -> bool:
    """The section is built when the case has [forces]."""
    return study.root.has("forces")


# --------------------------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------------------------
def _t(x, sig=4, digits=None, unit=None) -> str:
    """A number substituted into a formula (negative values in parentheses); with ``unit`` a
    result (no parentheses)."""
    if abs(float(x)) < 1e-12:
        x = 0.0
    if unit == "%":          # ziamath cannot set \text{%}
        return tex_num(x, sig=sig, digits=digits) + r"\ \%"
    return tex_num(x, sig=sig, digits=digits, unit=unit, paren=unit is None)



def _ts(x, sig: int, **kw) -> str:
    """A measured factor printed to ``sig`` digits from :func:`agreeing_sig`, no padding zeros."""
    return _t(x, sig=trimmed_sig(x, sig), **kw)

def _R(key: str) -> str:
    """HTML of R_ij for the column key "i_j"."""
    a, b = key.split("_")[:2]
    return sub("R", a + b)


def _load_tex(ld: dict, comp: str = "") -> str:
    r"""LaTeX symbol of a load (or of its projection ``comp`` = "x" | "y"): G_{2}, \Phi_{2y},
    M_{\Phi 2}, or the load's name."""
    k = ld["link"]
    if ld["kind"] == "G":
        return f"G_{{{k}{comp}}}"
    if ld["kind"] == "Phi":
        return rf"\Phi_{{{k}{comp}}}"
    if ld["kind"] in ("MPhi", "Mfly"):
        return rf"M_{{\Phi {k}}}"
    name = _name_tex(ld["name"])
    return rf"\left({name}\right)_{{{comp}}}" if comp else name


def _name_tex(name: str) -> str:
    """A load name with its trailing digits as a subscript: P6 → P_{6}, Pпс → P_{\text{пс}}."""
    head = name.rstrip("0123456789")
    tail = name[len(head):]
    if tail and head:
        return f"{head}_{{{tail}}}"
    if len(name) > 1 and name[0].isascii():
        return rf"{name[0]}_{{\text{{{name[1:]}}}}}"
    return rf"\text{{{name}}}"


def _in(x) -> str:
    """An input value in LaTeX as written (shortest representation: 0.6, 1.62, 56 000)."""
    return tex_num(x, digits=_decimals(x), sig=None, paren=True)


def _decimals(x) -> int:
    t = f"{float(x):.10g}"
    return len(t.split(".")[1]) if "." in t and "e" not in t else 0


def _fin(x, unit=None) -> str:
    """An input value in prose or a table, as written (an em dash for none)."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return fmt(math.nan)
    return fmt(x, digits=_decimals(x), sig=None, unit=unit)


def _deg(x) -> str:
    return fmt(math.degrees(float(x)), digits=1)


def _shown_pairs(f) -> list[str]:
    """The pairs of the reactions tables: ``[forces] pairs`` or every pair as declared."""
    if f.settings.pairs:
        return list(f.settings.pairs)
    return [p.name for p in f.model.pairs if p.kind != KS.K_MOM]


def reaction_digits(f) -> int:
    """One number of decimals for every force of the note's reaction tables (by groups, over the
    positions, the largest): that of the largest reaction to five significant digits, 0 to 2
    (ГОСТ 7.32, 6.6.6) — not 2304,0 Н in one table and 10 543 Н in the next."""
    tab = f.table
    vals = [tab[c].to_numpy(float) for c in tab.columns if c.startswith(("Rx_", "Ry_", "R_", "F_act"))]
    flat = np.concatenate(vals) if vals else np.zeros(0)
    return shared_decimals(flat[np.isfinite(flat)], sig=5, most=2)


def TASK(study) -> str:
    """The assignment's clause: what this section does for this case (static or kinetostatic;
    the actuator's capacity and the machine's axle loads where the case asks them)."""
    st = study.forces.settings
    text = ("выполнить силовой анализ механизма (статический расчёт)" if st.motion == "static" else
            "выполнить силовой (кинетостатический) анализ механизма") + " по группам Ассура с проверкой рычагом Жуковского"
    if st.capacity is not None:
        text += "; определить усилие и давление в гидроцилиндрах и грузоподъёмность механизма"
    if st.carrier is not None:
        text += "; определить нагрузки на мосты машины и проверить её управляемость"
    return text


def _weighted(f) -> bool:
    """Whether any link carries its weight in the force analysis (no «силы тяжести» in the text
    of a mechanism whose links are weightless)."""
    return any(ld["kind"] == "G" for ld in f.details(f.labels[0])["loads"])


def _nil_note(names: tuple[list[str], list[str]]) -> str:
    """The known forces left out of the lever's table of moments (``names``: those whose line of
    action passes through the pole, printed arm 0,0 мм; those printed as zero): their moment about
    the pole is zero, and the Жуковский equation sums the non-zero terms."""
    at_pole, zero = names
    parts = []
    if at_pole:
        one = len(at_pole) == 1
        parts.append(f"{'сила' if one else 'силы'} {_and(at_pole)} {'проходит' if one else 'проходят'} "
                     "через полюс p (плечо равно нулю)")
    if zero:
        one = len(zero) == 1
        parts.append(f"{'сила' if one else 'силы'} {_and(zero)} в этом положении {'равна' if one else 'равны'} нулю")
    if not parts:
        return ""
    text = "; ".join(parts)
    tail = ("её момент относительно полюса равен нулю, в таблицу она не включена" if len(at_pole) + len(zero) == 1
            else "их моменты относительно полюса равны нулю, в таблицу они не включены")
    return f" {text[0].upper()}{text[1:]}: {tail}."


def _and(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " и " + items[-1]


def _lead(study):
    return position_lead(study)


def _motion_text(study, f) -> str:
    s = f.settings
    if s.motion == "static":
        # the loads are named in the method's sentence before this one
        return "Расчёт статический: звенья движутся медленно, силы инерции не учитываются."
    if s.motion == "dynamics":
        a = str(inline_math(r"a = \omega^2 x^{\prime\prime} + \varepsilon x^{\prime}"))
        e = str(inline_math(r"\varepsilon_k = \omega^2 \varphi_k^{\prime\prime} + \varepsilon \varphi_k^{\prime}"))
        return ("Силы инерции вычислены по истинному закону движения машины ω(φ), ε(φ), найденному в "
                f"динамическом анализе: ускорения точек {a}, угловые ускорения звеньев {e}.")
    d = study.mechanism.driver
    return ("Силы инерции вычислены при постоянной скорости ведущего звена "
            f"({'ω₁' if d.rotary else 'v'}&nbsp;=&nbsp;{fmt(d.omega, sig=4)}&nbsp;"
            f"{'рад/с' if d.rotary else 'м/с'}" + (f", ε₁&nbsp;=&nbsp;{fmt(d.epsilon, sig=4)}" if d.epsilon else "") + ").")


# --------------------------------------------------------------------------------------------
# build
# --------------------------------------------------------------------------------------------
def build(study) -> Section:
    f = study.forces
    lab = chosen_position(study)
    if lab not in f.labels:
        lab = f.labels[1] if len(f.labels) > 1 else f.labels[0]
    static = f.settings.motion == "static"
    # a static analysis (no inertia forces) is not called kinetostatic
    sec = Section("Силовой анализ" if static else "Силовой (кинетостатический) анализ", "sec-forces")
    given = "заданных сил и сил тяжести" if _weighted(f) else "заданных сил"
    method = (f"методом статики [1, 3]: каждое звено под действием {given} рассматривается как находящееся "
              "в равновесии" if static else
              f"кинетостатическим методом (принцип Д’Аламбера) [1, 3]: к каждому звену, кроме {given}, "
              "прикладываются главный вектор и главный момент сил инерции, и звено рассматривается как "
              "находящееся в равновесии")
    sec.paragraph(
        f"Силовой расчёт выполнен {method}. Группы Ассура статически определимы (3n уравнений "
        "равновесия при 3n неизвестных составляющих реакций), поэтому реакции находятся по группам, "
        "начиная с группы, присоединённой последней, и заканчивая начальным механизмом. Реакция "
        f"{sub('R', 'ij')} — сила, с которой звено i действует на звено j; {sub('R', 'ji')}&nbsp;=&nbsp;"
        f"−{sub('R', 'ij')}. Трение в кинематических парах не учитывается. " + _motion_text(study, f))
    if f.settings.capacity is not None:
        _capacity(sec, study, f, lab)
    _loads(sec, study, f, lab, static)
    _groups(sec, study, f, lab)
    _reactions(sec, study, f)
    _balance(sec, study, f, lab)
    _cycle(sec, study, f)
    if f.settings.carrier is not None:
        _carrier(sec, study, f, lab)
    return sec


# --------------------------------------------------------------------------------------------
# loads
# --------------------------------------------------------------------------------------------
def _loads(sec: Section, study, f, lab: str, static: bool) -> None:
    s = sec.subsection("Нагрузки звеньев", "sec-frc-loads")
    row = f.row(lab)
    det = f.details(lab)
    mech = study.mechanism
    q = row["q_deg"] if f.rotary else row["q"]
    where = f"φ&nbsp;=&nbsp;{fmt(q, digits=1)}°" if f.rotary else f"S&nbsp;=&nbsp;{fmt(q, digits=3)}&nbsp;м"
    inertial = [(name, m, J, S) for name, m, J, S in f.inertial]
    if inertial:
        cw = f.rotary and mech.driver.direction < 0
        s.paragraph(f"Силы инерции звеньев приводятся к главному вектору, приложенному в центре масс, и "
                    f"главному моменту (положение {pos_no(study, lab)}, {where}"
                    + (f", ω&nbsp;=&nbsp;{fmt(row['omega'], sig=4)}&nbsp;рад/с, ε&nbsp;=&nbsp;"
                       f"{fmt(row['eps'], sig=4)}&nbsp;рад/с²" if f.rotary else "")
                    + (" в направлении вращения кривошипа, т.&nbsp;е. по часовой стрелке; угловые ускорения "
                       "звеньев ε<sub>k</sub> и моменты M<sub>Φk</sub> в формулах и таблице — со знаком, против "
                       "часовой стрелки — плюс" if cw else "") + "):")
        fs = [Formula(r"\Phi_k = -m_k a_{S_k}", where=[(r"m_k", "масса звена k, кг"),
                                                        (r"a_{S_k}", "ускорение его центра масс, м/с²")],
                      label="eq-frc-Phi"),
              Formula(r"M_{\Phi k} = -J_{S_k} \varepsilon_k",
                      where=[(r"J_{S_k}", "момент инерции звена относительно центра масс, кг·м²"),
                             (r"\varepsilon_k", "угловое ускорение звена, рад/с²")], label="eq-frc-MPhi")]
        for name, m, J, S in inertial:
            # a and ε to as many digits as make the printed product the printed load
            if m:
                wm = written(m)
                sg = agreeing_sig(lambda f: wm * f[0], [row["aS_" + name]], row["Phi_" + name])
                fs.append(Formula(rf"\Phi_{{{name}}} = m_{{{name}}} a_{{{tex_point(S)}}}",
                                  rf"{_t(m)} \cdot {_ts(row['aS_' + name], sg)}", _t(row["Phi_" + name], unit="Н")))
            if J:
                # signed, as eq. (MPhi) and the table: ε_k and M_Φk counter-clockwise positive
                wJ = written(J)
                sg = agreeing_sig(lambda f: -wJ * f[0], [row["eps_" + name]], row["MPhi_" + name])
                fs.append(Formula(rf"M_{{\Phi {name}}} = -J_{{S{name}}} \varepsilon_{{{name}}}",
                                  rf"-{_t(J)} \cdot {_ts(row['eps_' + name], sg)}",
                                  _t(row["MPhi_" + name], unit="Н·м")))
        if f.settings.flywheel:
            dyn = study.dynamics
            J1 = dyn.result.J_I - dyn.J_crank
            c = mech.driver.link
            # the first group's moment of inertia by the dynamics chapter's symbol J_I (less the
            # crank's own J_1 when the case gives it); factors to 5 digits so that they multiply
            # to the printed product
            J1_tex = rf"(J_I - J_{{{c}}})" if dyn.J_crank else "J_I"
            # the crank's ε_1 counter-clockwise positive: the machine's ε (along the rotation) times
            # the direction of rotation
            eps_c = row["eps"] * mech.driver.direction
            fs.append(Formula(rf"M_{{\Phi {c}}} = -{J1_tex} \varepsilon_{{{c}}}",
                              rf"-{_t(J1, sig=5)} \cdot {_t(eps_c, sig=5)}",
                              _t(row["MPhi_fly"], unit="Н·м")))
        s.formula(*fs)
        if f.settings.flywheel:
            less = " за вычетом момента инерции самого кривошипа" if study.dynamics.J_crank else ""
            s.paragraph("К кривошипу приложен момент сил инерции первой группы звеньев "
                        f"(ротор, передача, маховик) с приведённым моментом инерции <i>J</i><sub>I</sub>{less}; "
                        "при этом уравновешивающий момент равен движущему"
                        + (f", а движущий момент принят постоянным (формула {ref('eq-Md')}), поэтому "
                           "уравновешивающий момент одинаков во всех положениях; переменный уравновешивающий "
                           f"момент самого рычажного механизма приведён в таблице {ref('tab-frc-checks')} (столбец "
                           f"«{sub('M', 'ур')} без маховика»)."
                           if study.dynamics.balance == "drive" and study.dynamics.settings.drive is None else "."))
        rows = []
        for name, m, J, S in inertial:
            l = mech.link(name)
            rows.append({"n": name, "m": m or math.nan, "a": row.get("aS_" + name, math.nan) if m else math.nan,
                         "Phi": row.get("Phi_" + name, math.nan) if m else math.nan, "J": J or math.nan,
                         # ε only where it makes M_Φ = −J_S·ε (a slider moving in translation: «—», not 0)
                         "e": row["eps_" + name] if J else math.nan, "MPhi": row["MPhi_" + name] if J else math.nan,
                         "G": l.weight or math.nan})
        s.table(f"Массы, ускорения, силы и моменты сил инерции звеньев (положение {pos_no(study, lab)})", [
            Column("n", "Звено"), Column("m", "<i>m</i>", "кг", sig=4), Column("a", sub("a", "S"), "м/с²", sig=4),
            Column("Phi", "Φ", "Н", sig=4), Column("J", sub("J", "S"), "кг·м²", sig=4),
            Column("e", "ε", "рад/с²", sig=4), Column("MPhi", sub("M", "Φ"), "Н·м", sig=4),
            Column("G", "<i>G</i>", "Н", sig=5)], pd.DataFrame(rows), id="tab-frc-inertia")
    lrows = []
    for ld in det["loads"]:
        if ld["kind"] in ("Phi", "MPhi", "Mfly"):
            continue
        if ld["M"] is None:
            lrows.append({"name": load_label(ld), "link": ld["link"], "point": ld["point"], "Fx": ld["Fx"],
                          "Fy": ld["Fy"], "F": math.hypot(ld["Fx"], ld["Fy"]), "M": math.nan})
        else:
            lrows.append({"name": load_label(ld), "link": ld["link"], "point": "—", "Fx": math.nan, "Fy": math.nan,
                          "F": math.nan, "M": ld["M"]})
    if lrows:
        weights = any(ld["kind"] == "G" for ld in det["loads"])
        s.paragraph(f"Заданные нагрузки{' и силы тяжести' if weights else ''} в положении {pos_no(study, lab)} — "
                    f"в таблице {ref('tab-frc-applied')}"
                    + (" (силы тяжести приложены в центрах масс и направлены вниз)." if weights else "."))
        s.table(f"Заданные силы и моменты (положение {pos_no(study, lab)})", [
            Column("name", "Нагрузка", fmt=lambda v: Markup(html_label(v))), Column("link", "Звено"),
            Column("point", "Точка", fmt=lambda v: Markup(html_point(escape(v))) if v[:1].isalpha() else v),
            Column("Fx", sub("F", "x"), "Н", sig=5), Column("Fy", sub("F", "y"), "Н", sig=5),
            Column("F", "<i>F</i>", "Н", sig=5), Column("M", "<i>M</i>", "Н·м", sig=5)],
            pd.DataFrame(lrows), id="tab-frc-applied")
    if not inertial and not lrows:
        s.paragraph("Звенья не нагружены: все реакции равны нулю.")
    _incidence(s, study, f)


def _incidence(s: Section, study, f) -> None:
    """How the reactions are named (Артоболевский [1]: R_ij is the force of link i on link j).
    The links and pairs themselves are listed in chapter 1 (table of kinematic pairs: pair,
    links, kind, class), so no incidence matrix of links and pairs is printed: a program's
    bookkeeping (worksheet 000), not what a student hands in."""
    kinds = {p.kind for p in f.model.pairs}
    legend = []
    if KS.K_PRI in kinds:
        legend.append("(П) — поступательная пара (нормальная сила и реактивный момент)")
    if KS.K_ACT in kinds:
        legend.append("(Ц) — пара цилиндр–шток (усилие гидроцилиндра, нормальная сила и момент)")
    s.paragraph(f"Реакция в кинематической паре звеньев i и j обозначена {sub('R', 'ij')} — сила, с которой "
                f"звено i действует на звено j; звено j действует на звено i с силой "
                f"{sub('R', 'ji')}&nbsp;=&nbsp;−{sub('R', 'ij')}" + "".join("; " + x for x in legend) + ".")


# --------------------------------------------------------------------------------------------
# groups
# --------------------------------------------------------------------------------------------
def _groups(sec: Section, study, f, lab: str) -> None:
    # (no break between «положение» and its number, in the heading and in the contents)
    s = sec.subsection(f"Реакции в кинематических парах по группам Ассура (положение\u00a0{pos_no(study, lab)})",
                       "sec-frc-groups")
    s.paragraph("Для каждой группы составляются уравнения равновесия каждого звена: две проекции сил и "
                "моменты относительно точки звена; неизвестные — составляющие реакций во внешних и "
                "внутренних парах группы (для поступательной пары — нормальная сила и реактивный момент, "
                "определяющий точку её приложения). Реакции со стороны групп, рассчитанных ранее, известны. "
                "Система линейных уравнений группы решается точно; векторные уравнения сил проверяются "
                "построением планов сил в масштабе μ<sub>F</sub> (замкнутые многоугольники).")
    told: set[str] = set()      # the kinds of construction already described in full
    for gi, g in enumerate(f.model.groups):
        draw = GroupForces(lab, gi, landscape=True).draw(study)
        ext, moments, internal = group_vectors(study, lab, gi)
        gid = f"fig-frc-group-{gi + 1}"
        # a load exactly zero in this position (a resistance absent on the idle stroke, the inertia
        # force of a link whose centre of mass lies on its axis) is left out of the equation
        zero = [v for v in ext if v.role == "load" and not np.any(v.F)]
        names = " + ".join(html_label(v.label) for v in ext if all(v is not z for z in zero)) or "0"
        nil = _zero_loads_text(f, zero)
        unknown = [f.model.pairs[k] for k in g.pairs]
        act = next((p for p in unknown if p.kind == KS.K_ACT), None)
        if act is not None:   # the initial mechanism of an actuator-driven linkage (structure.decomposition)
            head = (f"Начальный механизм ({','.join(g.links)}) с ведущей поступательной парой "
                    f"{act.a}–{act.b}")
        elif is_initial(f, g):  # a crank with the frame: the initial mechanism, as in chapter 1
            head = group_name(f, g)
        else:
            head = g.title[0].upper() + g.title[1:]
        ulist = ", ".join(_unknown_text(p) for p in unknown)
        s.paragraph(f"<b>{head}.</b> Неизвестные: {ulist} — {plural(3 * len(g.links), 'уравнение', 'уравнения', 'уравнений')} равновесия. Уравнение сил "
                    f"{'начального механизма' if is_initial(f, g) else 'группы'} (рисунок {ref(gid)}): {names}&nbsp;=&nbsp;0{nil}.")
        s.figure(f"{group_name(f, g)}: схема нагружения (μ<sub>l</sub> = {mu_text(draw.mu)} м/мм, стрелки сил "
                 f"без масштаба) и план сил (μ<sub>F</sub> = {mu_text(draw.mu_F)} Н/мм)",
                 draw.svg, draw.width_mm, id=gid, landscape=draw.landscape)
        if draw.constructed:
            pri = any(p.kind == KS.K_PRI for p in unknown)
            s.paragraph(_construction_text(draw, gid, told, pri))
            told.add(_construction_kind(draw, pri))
        rows = []
        det = f.details(lab)
        for k in g.pairs:
            p = f.model.pairs[k]
            pv = det["pairs"][k]
            if p.kind == KS.K_MOM:
                continue
            rows.append({"pair": _R(p.name), "Rx": pv["Rx"], "Ry": pv["Ry"], "R": math.hypot(pv["Rx"], pv["Ry"]),
                         "ang": math.degrees(math.atan2(pv["Ry"], pv["Rx"])),
                         "extra": _prismatic_text(p, pv, reaction_digits(f))})
        nd = reaction_digits(f)
        gcols = [Column("pair", "Реакция", fmt=lambda v: Markup(v)),
                 Column("Rx", sub("R", "x"), "Н", sig=None, digits=nd), Column("Ry", sub("R", "y"), "Н", sig=None, digits=nd),
                 Column("R", "<i>R</i>", "Н", sig=None, digits=nd), Column("ang", "Угол с осью x", "град", digits=1)]
        if any(r["extra"] for r in rows):
            gcols.append(Column("extra", "Примечание"))
        s.table(f"Реакции в парах {group_name(f, g, 'gen')} (положение {pos_no(study, lab)})", gcols, pd.DataFrame(rows),
                id=f"tab-frc-group-{gi + 1}")
        if any(p.kind == KS.K_MOM for p in unknown):
            _crank_moment(s, study, f, lab, g, det)


def _zero_loads_text(f, zero) -> str:
    """«; P<sub>пс</sub> в этом положении равна нулю» for the loads left out of a group's force
    equation; «в этом положении» only when the load is not zero in every report position."""
    if not zero:
        return ""
    names = {v.label for v in zero}
    always = not any(np.hypot(ld["Fx"], ld["Fy"]) > 0 for lab in f.labels for ld in f.details(lab)["loads"]
                     if ld["M"] is None and load_label(ld) in names)
    verb = "равны нулю" if len(zero) > 1 else "равна нулю"
    return "; " + ", ".join(html_label(v.label) for v in zero) + ("" if always else " в этом положении") + " " + verb


_DIGITS = str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789")


def _in_cylinders(n: int) -> str:
    """«в двух гидроцилиндрах»: the numeral in words in the prepositional case (up to four)."""
    words = {1: "в гидроцилиндре", 2: "в двух гидроцилиндрах", 3: "в трёх гидроцилиндрах",
             4: "в четырёх гидроцилиндрах"}
    return words.get(int(n), f"в {int(n)} гидроцилиндрах")


_LAID = "отложены в масштабе μ<sub>F</sub> с длинами, округлёнными до 0,5&nbsp;мм"
_INTERSECTION = ("Известные силы и касательные составляющие реакций <i>R</i><sup>τ</sup> (из уравнений моментов "
                 "сил каждого звена относительно внутреннего шарнира) " + _LAID + "; через начало и конец цепи "
                 "проведены линии известных направлений (нормальная составляющая <i>R</i><sup>n</sup> — вдоль "
                 "{along}, реакция поступательной пары — перпендикулярно направляющей); точка их пересечения "
                 "замыкает план, реакции измерены на чертеже")
# how each kind of construction (scenes.forces.Construction.method) is done, told once in full
CONSTRUCTION_TEXT = {
    "closing": ("Известные силы " + _LAID + "; замыкающая сторона плана сил — искомая реакция, её длина "
                "измерена на чертеже"),
    "intersection": _INTERSECTION.format(along="звена"),
    "actuated": ("Гидроцилиндр и шток рассматриваются как одно звено переменной длины (усилие цилиндра — "
                 "внутренняя сила этого звена). " + _INTERSECTION.format(
                     along="звена, для цилиндра со штоком — вдоль оси гидроцилиндра")),
    # two unknowns (the force and its point on the guide), two moment equations: a stone's own
    # equation puts the point at its pin only when its inertia moment is zero; a rod in a cylinder
    # needs both
    "links": ("Реакция во внутренней поступательной паре перпендикулярна направляющей; её модуль и точка "
              "приложения найдены из уравнений моментов сил каждого из двух звеньев относительно его "
              "внешнего шарнира. Она и известные силы " + _LAID
              + "; план сил каждого звена замыкается реакцией в его внешнем шарнире (сплошные стороны), "
              "реакция во внутренней паре показана штриховой линией; реакции измерены на чертеже"),
    # both unknown reactions have known lines (prismatic pairs, e.g. ПВП): no R^τ, no R^n
    "lines": ("Известные силы " + _LAID + "; через начало и конец цепи проведены линии известных "
              "направлений реакций (реакция поступательной пары — перпендикулярно направляющей); точка их "
              "пересечения замыкает план, реакции измерены на чертеже"),
    "link_intersection": ("У звена с двумя поступательными парами обе реакции перпендикулярны своим "
                          "направляющим: известные силы этого звена " + _LAID + ", через начало и конец "
                          "цепи проведены линии этих направлений, точка их пересечения замыкает план сил "
                          "звена. Затем план сил второго звена замыкается реакцией в его шарнире; реакции "
                          "измерены на чертеже"),
}


def _construction_kind(draw, prismatic: bool | None = None) -> str:
    """The construction's method, told apart for two lines of known direction without R^τ laid off
    (both unknown reactions in prismatic pairs); «+П» where the group has a sliding pair (its rule
    is then told, and a group without one is not told it)."""
    if draw.method == "intersection" and not any("tau" in v.tex for v in draw.vectors):
        return "lines"
    return draw.method + ("+П" if prismatic is True and draw.method in ("intersection", "actuated") else "")


_PRI_RULE = ", реакция поступательной пары — перпендикулярно направляющей"


def _construction_text(draw, gid: str, told: set[str], prismatic: bool | None = None) -> str:
    """How the polygon of the group was constructed (in full the first time, then by reference)
    and what was read off it, against the exact solution of the group's equations."""
    found = "; ".join(f"{sub('R', c.label[1:].translate(_DIGITS))}&nbsp;=&nbsp;{fmt(c.graphic, sig=4)}&nbsp;Н (аналитически "
                      f"{fmt(c.exact, sig=5)}&nbsp;Н, расхождение {fmt(c.dev_pct, digits=2, sign=True)}&nbsp;%)"
                      for c in draw.constructed)
    kind = _construction_kind(draw, prismatic)
    if kind in told:
        how = "План сил построен так же, реакции измерены на чертеже"
    else:
        how = CONSTRUCTION_TEXT[kind.removesuffix("+П")]
        if prismatic is False and kind in ("intersection", "actuated"):        # no sliding pair here
            how = how.replace(_PRI_RULE, "")
    return f"{how} (рисунок {ref(gid)}): {found}."


def _unknown_text(p) -> str:
    if p.kind == KS.K_REV:
        return f"{_R(p.name)} (2 составляющие)"
    if p.kind == KS.K_PRI:
        return f"{_R(p.name)}, перпендикулярная направляющей, и её точка приложения (реактивный момент)"
    if p.kind == KS.K_ACT:
        return f"усилие гидроцилиндра <i>F</i>, нормальная сила и момент в паре {p.a}–{p.b}"
    return f"уравновешивающий момент {sub('M', 'ур')}"


def _signed_sum(terms: list[tuple[float, str]]) -> str:
    """«-h_{2} + h_{1}» from (sign, term) pairs (LaTeX)."""
    out = ""
    for k, (sg, t) in enumerate(terms):
        out += ("-" if sg < 0 else "") + t if k == 0 else (" - " if sg < 0 else " + ") + t
    return out


def _prismatic_text(p, pv, nd: int | None = None) -> str:
    """The normal force, moment and arm of a sliding pair (the actuator's force); forces to ``nd``
    decimals (those of the reaction columns), else to five significant digits."""
    force = {"sig": 5} if nd is None else {"digits": nd, "sig": None}
    if p.kind == KS.K_PRI:
        # the point of application lies h = M/N from the slider's point along the guide (forces.frame: xN, yN)
        h = pv['Mp'] / pv['N'] if pv['N'] else 0.0
        at = getattr(p, "point", "")
        where = ("" if not at else f" (реакция приложена в точке {at})" if fmt(h, sig=4) in ("0", "−0")
                 else f" — смещение точки приложения от точки {at} вдоль направляющей")
        return (f"N\u00a0=\u00a0{fmt(pv['N'], **force)}\u00a0Н, M\u00a0=\u00a0{fmt(pv['Mp'], sig=4)}\u00a0Н·м, "
                f"h\u00a0=\u00a0M/N\u00a0=\u00a0{fmt(h, sig=4)}\u00a0м{where}")
    if p.kind == KS.K_ACT:
        # the normal force and moment of the cylinder–rod pair vanish when the rod carries no lateral
        # load: rounding residues (1e-13 of F) are printed as the zero they are
        tiny = 1e-9 * max(abs(pv["F"]), 1.0)
        N, M = (0.0 if abs(v) <= tiny else v for v in (pv["N"], pv["Mp"]))
        return (f"F\u00a0=\u00a0{fmt(pv['F'], **force)}\u00a0Н, "
                f"N\u00a0=\u00a0{fmt(N, **({'sig': 4} if nd is None else force))}\u00a0Н, "
                f"M\u00a0=\u00a0{fmt(M, sig=4)}\u00a0Н·м")
    return ""


def _crank_moment(s: Section, study, f, lab, g, det) -> None:
    """M_ур from the moment equation of the crank about its centre.  With one force on the crank
    (R₂₁, the crank's weight and inertia force at its axis) one formula; with more (counterweights:
    the centre of mass off the axis) the moment of each force about the axis is written first,
    M_O(F) = (x − x_O)F_y − (y − y_O)F_x, then their sum: one line of all the projections would
    not fit the text width and was shrunk to an unreadable size."""
    mech = study.mechanism
    d = mech.driver
    cols = det["cols"]
    O = tex_point(d.center)
    ox, oy = cols["x_" + d.center], cols["y_" + d.center]
    terms = []          # (force symbol or None for a moment, symbolic, substituted, value)
    for k, pv in enumerate(det["pairs"]):
        p = pv["pair"]
        if p.kind == KS.K_MOM or d.link not in (p.a, p.b) or FRAME in (p.a, p.b):
            continue
        sgn = 1.0 if p.b == d.link else -1.0
        key = p.name if sgn > 0 else f"{p.b}_{p.a}"
        Fx, Fy = sgn * pv["Rx"], sgn * pv["Ry"]
        dx, dy = pv["x"] - ox, pv["y"] - oy
        P = tex_point(p.point)
        a_, b_ = key.split("_")[:2]
        terms.append((f"R_{{{a_}{b_}}}", rf"(x_{{{P}}} - x_{{{O}}}) R_{{{a_}{b_}y}} - (y_{{{P}}} - y_{{{O}}}) R_{{{a_}{b_}x}}",
                      (dx, Fy, dy, Fx), dx * Fy - dy * Fx))
    for ld in det["loads"]:
        if ld["link"] != d.link:
            continue
        if ld["M"] is not None:
            terms.append((None, _load_tex(ld), (float(ld["M"]),), float(ld["M"])))
        elif ld["point"] != d.center:
            P = tex_point(ld["point"])
            dx, dy = cols["x_" + ld["point"]] - ox, cols["y_" + ld["point"]] - oy
            terms.append((_load_tex(ld), rf"(x_{{{P}}} - x_{{{O}}}) {_load_tex(ld, 'y')} - (y_{{{P}}} - y_{{{O}}}) {_load_tex(ld, 'x')}",
                          (dx, float(ld["Fy"]), dy, float(ld["Fx"])), dx * float(ld["Fy"]) - dy * float(ld["Fx"])))
    Mb = float(f.row(lab)["M_bal"])
    # arms and forces to as many digits as make the printed products the printed moment(s)
    factors = [x for t in terms for x in t[2]]

    def moment(fs):
        out, i = 0.0, 0
        for t in terms:
            if len(t[2]) == 1:
                out, i = out + fs[i], i + 1
            else:
                out, i = out + fs[i] * fs[i + 1] - fs[i + 2] * fs[i + 3], i + 4
        return -out
    sg = agreeing_sig(moment, factors, Mb, result_sig=5)
    terms = [(F, sym, _ts(fs[0], sg) if len(fs) == 1 else
              rf"{_ts(fs[0], sg)} \cdot {_ts(fs[1], sg)} - {_ts(fs[2], sg)} \cdot {_ts(fs[3], sg)}", v)
             for F, sym, fs, v in terms]
    s.paragraph(f"Уравновешивающий момент {sub('M', 'ур')} (момент, который нужно приложить к {input_word(d, 'dat')} {d.link}, "
                f"против часовой стрелки — плюс) — из уравнения моментов сил, действующих на {input_word(d)}, "
                f"относительно оси {d.center}:")
    if sum(t[0] is not None for t in terms) < 2:
        s.formula(Formula(r"M_{ур} = -\left[" + " + ".join(t[1] for t in terms) + r"\right]",
                          r"-\left[" + " + ".join(t[2] for t in terms) + r"\right]", _t(Mb, sig=5, unit="Н·м"),
                          label="eq-frc-Mbal"))
        return
    moments = [Formula(rf"M_{{{O}}}({F}) = {sym}", num, _t(v, sig=5, unit="Н·м"))
               for F, sym, num, v in terms if F is not None]
    names = [rf"M_{{{O}}}({F})" if F is not None else sym for F, sym, _, _ in terms]
    s.formula(*moments,
              Formula(r"M_{ур} = -\left[" + " + ".join(names) + r"\right]",
                      r"-\left[" + " + ".join(_t(t[3], sig=5) for t in terms) + r"\right]",
                      _t(Mb, sig=5, unit="Н·м"), label="eq-frc-Mbal"))


# --------------------------------------------------------------------------------------------
# reactions over the positions
# --------------------------------------------------------------------------------------------
def _reactions(sec: Section, study, f) -> None:
    s = sec.subsection("Реакции в кинематических парах по положениям", "sec-frc-table")
    tab = f.table
    lead = _lead(study)
    pairs = _shown_pairs(f)
    comp = []
    for key in pairs:
        comp += [Column("Rx_" + key, _R(key) + "<sub>x</sub>", "Н", sig=5, digits=None),
                 Column("Ry_" + key, _R(key) + "<sub>y</sub>", "Н", sig=5)]
    mag = [Column("R_" + key, _R(key), "Н", sig=5) for key in pairs]
    if f.rotary:
        mag.append(Column("M_bal", sub("M", "ур"), "Н·м", sig=5))
    else:
        mag.append(Column("F_act", "<i>F</i>", "Н", sig=6))
    nd = reaction_digits(f)
    for c in comp + mag:
        if c.unit == "Н":          # forces: one number of decimals in every reaction table of the note
            c.sig, c.digits = None, nd
    comp, zero = zero_columns(tab, comp)     # R₀₅y of a slider on a vertical guide: 0 in every position
    ids = chunked_tables(s, "Составляющие реакций в кинематических парах", tab, comp, lead, "tab-frc-comp", per=6,
                         note=_zero_note(zero))
    ids2 = chunked_tables(s, "Модули реакций в кинематических парах", tab, mag, lead, "tab-frc-mag", per=6)
    note = ""
    declared = {p.name for p in f.model.pairs}
    reversed_ = [k for k in pairs if k not in declared]
    if reversed_:
        text = "; ".join(f"{_R(k)} — сила звена {_who(k.split('_')[0])} на {_whom(k.split('_')[1])}"
                         for k in reversed_)
        note = f" Направления реакций в таблицах: {text}."
    s.paragraph(f"Составляющие реакций по положениям механизма — в таблице {ref(ids[0])}, их модули — в таблице "
                f"{ref(ids2[0])}.{note}")


# --------------------------------------------------------------------------------------------
# balancing moment and its checks
# --------------------------------------------------------------------------------------------
def _balance(sec: Section, study, f, lab: str) -> None:
    rot = f.rotary
    title = "Уравновешивающий момент и проверка рычагом Жуковского" if rot else \
        "Усилие гидроцилиндра и проверка рычагом Жуковского"
    s = sec.subsection(title, "sec-frc-balance")
    row = f.row(lab)
    mech = study.mechanism
    d = mech.driver
    main = "M_bal" if rot else "F_act"
    unit = "Н·м" if rot else "Н"
    inertia = "" if f.settings.motion == "static" else ", включая силы инерции"
    s.paragraph(f"Проверка по принципу возможных перемещений (равенство нулю суммы мощностей всех сил{inertia}; "
                "аналоги скоростей — производные по обобщённой координате):")
    if rot:
        s.formula(Formula(r"M_{ур} \varphi_1^{\prime} + \sum_i \left( F_{ix} x_i^{\prime} + F_{iy} y_i^{\prime} \right)"
                          r" + \sum_k M_k \varphi_k^{\prime} = 0",
                          where=[(r"\varphi_1^{\prime} = \pm 1", f"аналог угловой скорости {input_word(d, 'gen')} "
                                                                 f"({'−1: вращение по часовой стрелке' if d.direction < 0 else '+1'})")],
                          label="eq-frc-power"))
    else:
        s.formula(Formula(r"F \cdot 1 + \sum_i \left( F_{ix} x_i^{\prime} + F_{iy} y_i^{\prime} \right)"
                          r" + \sum_k M_k \varphi_k^{\prime} = 0",
                          where=[(r"x_i^{\prime}, y_i^{\prime}", "передаточные отношения dx/dS, dy/dS точек приложения сил")],
                          label="eq-frc-power"))
    lever = ZhukovskyLever(lab, landscape=True).draw(study)
    plan = "аналогов скоростей" if lever.analog else "скоростей"
    if lever.forces_turned:
        how = (f"Рычаг Н.&nbsp;Е.&nbsp;Жуковского — план {plan}, повёрнутый на 90°; повёрнутый план получился "
               "бы высоким и узким, поэтому план оставлен без поворота, а все силы повёрнуты на 90° по часовой "
               "стрелке, что даёт те же моменты относительно полюса (рисунок "
               f"{ref('fig-frc-lever')}); силы приложены в одноимённых точках плана, моменты заменены парами сил "
               "на двух точках звена. Сумма моментов всех сил относительно полюса p равна нулю:")
    else:
        how = (f"Рычаг Н.&nbsp;Е.&nbsp;Жуковского — план {plan}, повёрнутый на 90° против часовой стрелки "
               f"(рисунок {ref('fig-frc-lever')}); силы приложены в одноимённых точках плана, моменты заменены "
               "парами сил на двух точках звена. Сумма моментов всех сил относительно полюса p равна нулю:")
    # moments become force pairs (′ and ″) only where the position has a moment load
    paired = any(("′" in str(v) or "″" in str(v)) for v in lever.moments["label"])
    if not paired:
        how = how.replace(", моменты заменены парами сил на двух точках звена", "")
    mu_unit = "м·с⁻¹/мм" if not lever.analog else ("м/мм" if rot else "мм⁻¹")
    tail = " Сумма моментов всех сил относительно полюса p равна нулю:"
    views = _insets_text(lever, plan, "v", mu_unit)
    if lever.in_views:     # the forces at those images are drawn in the view, not on the lever
        where = "на нём" if len(lever.insets) == 1 else "на них"
        views = views[:-1] + f"; силы, приложенные в этих точках, показаны только {where}."
    s.paragraph(how.replace(tail, views + tail))
    mt = lever.moments.copy()
    # the student's arithmetic: forces to four significant digits of the largest one (one
    # number of decimals for the column, at most 0,01 Н), arms as measured to 0,1 mm, products
    # of the printed numbers (so that every printed product equals F·h of its row)
    F_dec = shared_decimals(mt["F"].to_numpy(float))
    F_r = np.round(np.abs(mt["F"].to_numpy(float)), F_dec)
    mt["F"] = F_r
    h_r = np.round(np.abs(mt["h"].to_numpy(float)), 1)
    mt["h"] = h_r
    mt["Fh"] = np.sign(mt["Fh"].to_numpy(float)) * F_r * h_r
    arm = round(abs(float(lever.arm_mm)), 1) * (1.0 if lever.arm_mm >= 0 else -1.0)
    # the balancing force's rows hold the value the lever gives (F_ур = −ΣF_i·h_i / Σ±h of its
    # rows: one row for a crank's force, two for an actuator's pair), so the column of products
    # sums to zero as the lever's equation says, not the analytic F_ур
    bal = mt["balancing"].astype(bool).to_numpy()
    signed_h = np.sign(mt["Fh"].to_numpy(float)) * h_r
    S = float(signed_h[bal].sum()) if bal.any() else 0.0
    if S != 0.0:
        # printed to the column's decimals, and its products are the printed F times the printed
        # arms as every other row's: the column sums to zero up to the rounding of F_ур
        lever_total = float(mt.loc[~bal, "Fh"].sum())
        F_bal = round(abs(lever_total / S), F_dec)
        mt.loc[bal, "F"] = F_bal
        mt.loc[bal, "Fh"] = -np.sign(lever_total / S) * F_bal * signed_h[bal]
    # a known force whose printed moment is zero (its line passes through the pole, or the force
    # itself is zero) is not a term of the student's sum: named under the table, not listed
    nil = ~bal & (mt["Fh"].to_numpy(float) == 0.0)
    at_pole = nil & (mt["h"].to_numpy(float) == 0.0)
    nil_names = ([html_label(v) for v in mt.loc[at_pole, "label"]],
                 [html_label(v) for v in mt.loc[nil & ~at_pole, "label"]])
    mt = mt[~nil]
    if rot:
        pin = tex_point(_pin(mech))
        s.formula(Formula(rf"F_{{ур}} h_{{{pin.lower()}}} + \sum_i F_i h_i = 0", label="eq-frc-lever"))
        arm_sym, arm_num = f"h_{{{pin.lower()}}}", _t(arm, digits=1)
    else:
        # the actuator's pair F (at 2) and −F (at 1): the arms as the table prints them (moduli) with
        # the sign of the moment of F taken positive (counter-clockwise +) written before each, so
        # that F(±h₂ ± h₁) reads off the table and F keeps its sign
        sF = 1.0 if float(row[main]) >= 0 else -1.0
        arms = [((float(np.sign(sh)) or 1.0) * sF, h, str(lab_).lstrip("F").translate(_DIGITS))
                for sh, h, lab_ in zip(signed_h[bal], h_r[bal], mt.loc[bal, "label"])]
        if arms:
            arm = sum(sg * h for sg, h, _ in arms)
            arm_sym = rf"\left({_signed_sum([(sg, f'h_{{{sb}}}') for sg, _, sb in arms])}\right)"
            arm_num = rf"\left({_signed_sum([(sg, _t(h, digits=1)) for sg, h, _ in arms])}\right)"
        else:
            arm_sym, arm_num = r"\left(h_{2} - h_{1}\right)", _t(arm, digits=1)
        s.formula(Formula(rf"F {arm_sym} + \sum_i F_i h_i = 0", label="eq-frc-lever"))
        s.paragraph("Плечи <i>h</i> — расстояния (без знака), как в таблице моментов; знак перед плечом — "
                    "знак момента силы <i>F</i> (против часовой стрелки — плюс).")
    turned = ", силы повёрнуты на 90° по часовой стрелке" if lever.forces_turned else ""
    s.figure(f"Рычаг Жуковского для положения {pos_no(study, lab)} (μ<sub>v</sub> = {mu_text(lever.mu)} {mu_unit}{turned})",
             lever.svg, lever.width_mm, id="fig-frc-lever", landscape=lever.landscape)
    loads = mt[~mt["balancing"].astype(bool)]
    s.table(f"Моменты сил относительно полюса рычага Жуковского (положение {pos_no(study, lab)})", [
        Column("label", "Сила", fmt=lambda v: Markup(html_label(v))), Column("F", "<i>F</i>", "Н", digits=F_dec, sig=None),
        Column("h", "<i>h</i>", "мм", digits=1, sig=None),
        Column("Fh", "±<i>F·h</i>", "Н·мм", fmt=lambda v: fmt(v, digits=F_dec + 1, sig=None, exp_from=1e12))], mt, id="tab-frc-lever",
        note="Плечо h — расстояние от полюса p до линии действия силы на рычаге; знак «+» — момент против "
             "часовой стрелки." + (" Моменты звеньев заменены парами сил (′ и ″) на двух точках звена." if paired else "")
             + _nil_note(nil_names))
    total = float(loads["Fh"].sum())
    # the sum of the table's printed products, written as the column writes them (not 5,52750·10⁶
    # beside 5 527 500,0)
    total_tex = tex_num(total, digits=F_dec + 1, sig=None, exp_from=1e12, paren=True)
    F_graph = -total / arm
    M_graph = F_graph * _crank_length(mech) if rot else F_graph
    exact = float(row[main])
    dev_graph = 100.0 * abs(exact - M_graph) / max(abs(exact), 1e-12)
    if rot:
        pin = tex_point(_pin(mech))
        res = [Formula(rf"F_{{ур}} = -\frac{{\sum F_i h_i}}{{{arm_sym}}}",
                       rf"-\frac{{{total_tex}}}{{{arm_num}}}",
                       _t(F_graph, sig=5, unit="Н")),
               Formula(rf"M_{{ур}}^{{Ж}} = F_{{ур}} l_{{{tex_point(d.center)}{pin}}}",
                       rf"{_t(F_graph, sig=5)} \cdot {_t(_crank_length(mech), sig=4)}",
                       _t(M_graph, sig=5, unit="Н·м")),
               Formula(r"M_{ур}^{кин}", None, _t(row["M_bal"], sig=5, unit="Н·м")),
               Formula(r"\Delta = \frac{\left| M_{ур}^{кин} - M_{ур}^{Ж} \right|}{\left| M_{ур}^{кин} \right|} \cdot 100\%",
                       None, _t(dev_graph, sig=2, unit="%"))]
    else:
        res = [Formula(rf"F^{{Ж}} = -\frac{{\sum F_i h_i}}{{{arm_sym}}}",
                       rf"-\frac{{{total_tex}}}{{{arm_num}}}",
                       _t(F_graph, sig=6, unit="Н")),
               Formula(r"F^{кин}", None, _t(row["F_act"], sig=6, unit="Н")),
               Formula(r"\Delta = \frac{\left| F^{кин} - F^{Ж} \right|}{|F^{кин}|} \cdot 100\%", None,
                       _t(dev_graph, sig=2, unit="%"))]
    s.paragraph(f"Результат для положения {pos_no(study, lab)} (плечи измерены на чертеже с точностью 0,5&nbsp;мм) и "
                "расхождение с силовым расчётом по группам (допускается до 5&nbsp;%):")
    s.formula(*res)
    if dev_graph > LEVER_TOLERANCE_PCT:
        s.paragraph(_lever_accuracy(loads, total, dev_graph, exact, float(f.scalars[main + "_absmax"]), rot))
    # one number of decimals per column; the relative deviations (round-off) are in the answer key
    nd = dict(digits=1 if rot else 0, sig=None)
    cols = [Column(main, (sub("M", "ур") if rot else "<i>F</i>") + " (по группам)", unit, **nd),
            Column(main + "_power", (sub("M", "ур") if rot else "<i>F</i>") + " (мощности)", unit, **nd),
            Column(main + "_zhukovsky", (sub("M", "ур") if rot else "<i>F</i>") + " (Жуковский)", unit, **nd)]
    if f.settings.flywheel:
        cols.append(Column("M_d_dyn", sub("M", "дв") + " (динамика)", "Н·м", **nd))
        cols.append(Column("M_bal_linkage", sub("M", "ур") + " без маховика", "Н·м", **nd))
    dyn_check = "M_bal_dyn" in f.table
    # M_д and ε of the dynamics are along the crank's rotation, the table's moments ccw-positive:
    # for a crank turning clockwise the column is −(M_д − J_I ε), so that its sign is the table's
    cw = study.mechanism.driver.direction < 0
    dyn_head = sub("M", "д") + " − " + sub("J", "I") + "ε"
    if cw:
        dyn_head = "−(" + dyn_head + ")"
    if dyn_check:
        cols.append(Column("M_bal_dyn", dyn_head + " (динамика)", "Н·м", **nd))
    chunked_tables(s, "Уравновешивающий момент и его проверки" if rot else "Усилие гидроцилиндра и его проверки",
                   f.table, cols, _lead(study), "tab-frc-checks")
    text = ("Аналитически три способа (по группам, по балансу мощностей, по рычагу Жуковского) дают одно и то же "
            "значение во всех положениях: различие — в пределах погрешности округления чисел.")
    if f.settings.flywheel:
        text += (f" С учётом момента сил инерции первой группы уравновешивающий момент совпадает с движущим "
                 f"моментом динамического расчёта. Уравновешивающий момент самого рычажного механизма "
                 f"(без момента сил инерции первой группы, {sub('M', 'ур')}&nbsp;+&nbsp;{sub('M', 'Φ1')}) меняется "
                 f"по положениям (последний столбец таблицы); реакции от момента, приложенного к кривошипу, не "
                 f"зависят.")
    if dyn_check:
        dyn = study.dynamics
        J = float(dyn.result.J_I - dyn.J_crank)
        text += (f" Уравновешивающий момент переменен по положениям: силы инерции звеньев вычислены по истинному "
                 f"закону движения ω(φ), ε(φ), момент сил инерции маховика к кривошипу не прикладывается. По "
                 f"уравнению движения машины он равен движущему моменту за вычетом момента, идущего на разгон "
                 f"первой группы звеньев: {sub('M', 'ур')}(φ)&nbsp;=&nbsp;{'−(' if cw else ''}{sub('M', 'д')}&nbsp;−&nbsp;"
                 f"{sub('J', 'I')}·ε(φ){')' if cw else ''}, где {sub('M', 'д')}&nbsp;=&nbsp;{fmt(abs(dyn.scalars['M_d']), sig=5)}"
                 f"&nbsp;Н·м, {sub('J', 'I')}&nbsp;=&nbsp;{fmt(J, sig=5)}&nbsp;кг·м² (без кривошипа)"
                 + ("; движущий момент и угловое ускорение ε(φ) звена приведения считаются положительными в "
                    "направлении вращения кривошипа, моменты в таблице — со знаком (против часовой стрелки — "
                    "плюс), кривошип вращается по часовой стрелке, отсюда знак «−». " if cw
                    else ". ") +
                 "Значения двух расчётов совпадают (последний столбец таблицы).")
    s.paragraph(text)


LEVER_TOLERANCE_PCT = 5.0     # the admissible discrepancy of the graphical check (as the note states it)


def _lever_accuracy(loads, total: float, dev: float, here: float, peak: float, rot: bool) -> str:
    """What a discrepancy of the lever over the admissible 5 % means: every arm is read to
    0,5 mm, i.e. to ±0,25 mm, so the sum of moments is uncertain by up to Σ|F_i|·0,25 mm (the
    bound of the reading error of the drawing). Within that bound the discrepancy is the
    drawing's accuracy (short arms of large forces), and a lever drawn k = bound/5 % times larger
    reads to 5 %, and where the balancing value ``here`` is small against its largest ``peak``
    over the positions, a check at another position is named; beyond the bound the construction
    itself is wrong."""
    err = 0.5 * 0.5 * float(loads["F"].abs().sum())            # N·mm
    bound = 100.0 * err / max(abs(total), 1e-12)
    head = (f"Расхождение {fmt(dev, sig=2)}&nbsp;% больше допускаемых {fmt(LEVER_TOLERANCE_PCT, digits=0)}&nbsp;%. "
            f"Плечи измерены с точностью 0,5&nbsp;мм, т.&nbsp;е. каждое — до ±0,25&nbsp;мм; погрешность суммы "
            f"моментов от этого — до Σ|<i>F<sub>i</sub></i>|·0,25&nbsp;мм&nbsp;=&nbsp;{fmt(err, sig=3)}&nbsp;Н·мм, "
            f"или {fmt(bound, sig=2)}&nbsp;% от |Σ<i>F<sub>i</sub>h<sub>i</sub></i>|&nbsp;=&nbsp;{fmt(abs(total), sig=4)}&nbsp;Н·мм")
    if dev <= bound:
        k = math.ceil(bound / LEVER_TOLERANCE_PCT)
        return (head + ": расхождение объясняется точностью построения (короткие плечи больших сил), а не ошибкой "
                f"силового расчёта. Чтобы проверить уравновешивающий момент с точностью 5&nbsp;%, рычаг следует "
                f"вычертить в масштабе, в {plural(k, 'раз', 'раза', 'раз')} более крупном"
                + (f", или выполнить проверку в положении, где {'уравновешивающий момент' if rot else 'усилие'} "
                   f"больше (здесь {fmt(abs(here), sig=3)}&nbsp;{'Н·м' if rot else 'Н'} при наибольшем по модулю "
                   f"{fmt(peak, sig=3)}&nbsp;{'Н·м' if rot else 'Н'})" if abs(here) < 0.5 * peak else "") + ".")
    return head + ": расхождение больше этой погрешности, построение рычага следует проверить."


def _dev(graphic: float, exact: float) -> float:
    """Discrepancy of a value found on a drawing from the exact one, % of the exact value."""
    return abs(graphic - exact) / abs(exact) * 100.0 if abs(exact) > 1e-12 else 0.0


def _who(link: str) -> str:
    return "стойки" if link == FRAME else link


def _whom(link: str) -> str:
    return "стойку" if link == FRAME else f"звено {link}"


def _pin(mech) -> str:
    return crank_pin(mech)


def _crank_length(mech) -> float:
    """l_OA: distance of the crank pin from the crank's centre."""
    d = mech.driver
    crank = mech.link(d.link)
    (x0, y0), (x1, y1) = crank.points[d.center], crank.points[_pin(mech)]
    return math.hypot(x1 - x0, y1 - y0)


# --------------------------------------------------------------------------------------------
# over the cycle
# --------------------------------------------------------------------------------------------
def _cycle(sec: Section, study, f) -> None:
    span = "за цикл" if f.rotary else "по ходу гидроцилиндра"     # an actuator's stroke is no cycle
    s = sec.subsection(f"Реакции {span}", "sec-frc-cycle")
    fig = ReactionCurves().draw(study)
    sc = f.scalars
    rows = []
    for p in f.model.pairs:
        if p.kind == KS.K_MOM:
            continue
        q = sc[f"q_R_{p.name}_max"]
        rows.append({"pair": _R(shown_key(f, p)), "R": sc[f"R_{p.name}_max"],
                     "q": q_degrees(study, q) if f.rotary else q})
    qkey, qhead, qunit, qfmt = q_header(study)
    main = "M_bal" if f.rotary else "F_act"
    s.paragraph(f"Модули реакций во всех парах и {'уравновешивающий момент' if f.rotary else 'усилие гидроцилиндра'} "
                f"{span} показаны на рисунке {ref('fig-frc-cycle')}, наибольшие значения — в таблице "
                f"{ref('tab-frc-max')}. {'Наибольший по модулю уравновешивающий момент' if f.rotary else 'Наибольшее по модулю усилие'} — "
                f"{fmt(sc[main + '_absmax'], sig=5)}&nbsp;{'Н·м' if f.rotary else 'Н'}.")
    s.figure("Реакции в кинематических парах и " + ("уравновешивающий момент" if f.rotary else "усилие гидроцилиндра")
             + (" в диапазоне качания входного звена" if study.mechanism.driver.swing else " за цикл" if f.rotary else " по ходу гидроцилиндра"), fig.svg, fig.width_mm, id="fig-frc-cycle")
    s.table("Наибольшие реакции в кинематических парах", [
        Column("pair", "Реакция", fmt=lambda v: Markup(v)),
        Column("R", "<i>R</i><sub>max</sub>", "Н", sig=None, digits=reaction_digits(f)), Column("q", qhead, qunit, **qfmt)],
        pd.DataFrame(rows), id="tab-frc-max")


# --------------------------------------------------------------------------------------------
# capacity of an actuator-driven linkage
# --------------------------------------------------------------------------------------------
def _capacity(sec: Section, study, f, lab: str) -> None:
    s = sec.subsection("Усилие, давление и грузоподъёмность гидропривода", "sec-frc-capacity")
    a, c = f.settings.actuator, f.settings.capacity
    row = f.row(lab)
    P = float(-[ld for ld in f.solution.loads if ld.name == c.load][0].Fy[0])
    pt = tex_point(c.point)
    ip = row["i_" + c.point]
    # the actuator force of the other loads (the links' weights): F = Q·i + F_ост, G = (kpηA − F_ост)/i
    # (analysis.forces: rest = F_act − Q·i); without them F = Q·i exactly
    rest = float(row["F_act"]) - P * float(ip)
    others = any(ld.name != c.load for ld in f.solution.loads) and abs(rest) > 1e-9 * max(abs(float(row["F_act"])), 1.0)
    where = f"в точке {html_point(c.point)}" + (" и на оси " + ", ".join(c.points) if c.points else "")
    s.paragraph("Усилие на штоке находится из силового расчёта по группам; по принципу возможных перемещений "
                + (f"оно равно произведению нагрузки {html_label(c.load)} на передаточное число "
                   f"{inline_math(rf'i_{{{pt}}} = dy_{{{pt}}}/dS')} её точки приложения и доли усилия "
                   f"{inline_math('F_{ост}')}, приходящейся на остальные нагрузки (силы тяжести звеньев). "
                   if others else
                   f"для единственной вертикальной нагрузки {html_label(c.load)} оно равно произведению нагрузки на передаточное "
                   f"число {inline_math(rf'i_{{{pt}}} = dy_{{{pt}}}/dS')} её точки приложения. ")
                + f"Площадь поршня, давление {_in_cylinders(a.count)} и грузоподъёмность ({where}"
                f") для положения {pos_no(study, lab)} (S&nbsp;=&nbsp;{fmt(row['q'], digits=3)}&nbsp;м; "
                f"по всем положениям — таблица {ref('tab-frc-capacity')} и рисунок {ref('fig-frc-capacity')}):")
    L_ = _name_tex(c.load)
    # i (and F_ост) to as many digits as make Q·i + F_ост as printed the printed F
    sf = agreeing_sig(lambda f: P * f[0] + (f[1] if others else 0.0), [ip, rest], row["F_act"], sig=5, result_sig=6)
    fs = [Formula(rf"F = {L_} \cdot i_{{{pt}}}" + (r" + F_{ост}" if others else ""),
                  rf"{_in(P)} \cdot {_ts(ip, sf)}" + (rf" + {_ts(rest, sf)}" if others else ""),
                  _t(row["F_act"], sig=6, unit="Н"), label="eq-frc-F"),
          Formula(r"A = \frac{\pi D^2}{4}", rf"\frac{{\pi \cdot {_in(a.diameter)}^2}}{{4}}", _t(a.area, sig=5, unit="м²")),
          # p to the table's 3 decimals; the area and the ratios i to as many digits as make the
          # printed quotients the printed p and G (2·17,5·10⁶·0,84·0,0050265/3,9840 = 37 093, not 37 094)
          Formula(r"p = \frac{F}{k A \eta}", rf"\frac{{{_t(row['F_act'], sig=6)}}}{{{a.count} \cdot "
                  rf"{_ts(a.area, agreeing_sig(lambda f: f[0] / (a.count * f[1] * a.efficiency) / 1e6, [row['F_act'], a.area], row['p_act'] / 1e6, sig=5, result_sig=5))}"
                  rf" \cdot {_in(a.efficiency)}}}",
                  _t(row["p_act"] / 1e6, digits=3, unit="МПа"), label="eq-frc-p")]
    for q in list(c.points) + [c.point]:
        Q = tex_point(q)
        kpe = a.count * a.pressure * a.efficiency
        # the area, the ratio i (and F_ост) to as many digits as make the printed quotient the printed G
        sg = agreeing_sig(lambda f: (kpe * f[0] - (f[2] if others else 0.0)) / f[1],
                          [a.area, row["i_" + q], rest], row["Gcap_" + q], sig=5, result_sig=5)
        fs.append(Formula(rf"G_{{{Q}}} = \frac{{k p_{{max}} \eta A" + (r" - F_{ост}" if others else "") + rf"}}{{i_{{{Q}}}}}",
                          rf"\frac{{{a.count} \cdot {_in(a.pressure / 1e6)} \cdot 10^{{6}} \cdot {_in(a.efficiency)} \cdot {_ts(a.area, sg)}"
                          + (rf" - {_ts(rest, sg)}" if others else "") + rf"}}{{{_ts(row['i_' + q], sg)}}}",
                          _t(row["Gcap_" + q], sig=5, unit="Н")))
    fs.append(Formula(rf"\Delta G = \frac{{G_{{{pt}}} - {L_}}}{{{L_}}} \cdot 100\%",
                      rf"\frac{{{_t(row['Gcap_' + c.point], sig=5)} - {_in(P)}}}{{{_in(P)}}} \cdot 100\%",
                      _t(row["reserve_pct"], digits=1, unit="%")))
    s.formula(*fs)
    cols = [Column("F_act", "<i>F</i>", "Н", digits=0, sig=None),
            Column("p_act", "<i>p</i>", "МПа", fmt=lambda v: fmt(v / 1e6, digits=3, sig=None))]
    cols += [Column("Gcap_" + q, sub("G", q), "Н", digits=0, sig=None) for q in list(c.points) + [c.point]]
    cols += [Column("reserve_pct", "Δ<i>G</i>", "%", digits=1)]
    s.table("Результаты анализа механизма на грузоподъёмность", _lead(study) + cols, f.table, id="tab-frc-capacity")
    s.figure("Грузоподъёмность, усилие и давление в гидроцилиндрах по ходу поршня", CapacityCurves().draw(study).svg,
             160, id="fig-frc-capacity")
    sc = f.scalars
    txt = (f"Результаты — в таблице {ref('tab-frc-capacity')} и на рисунке {ref('fig-frc-capacity')}. Усилие гидроцилиндров "
           f"при давлении в гидросистеме {_fin(a.pressure / 1e6)}&nbsp;МПа: <i>k</i>·<i>p</i>·<i>η</i>·<i>A</i>&nbsp;=&nbsp;{fmt(a.F_max, sig=6)}&nbsp;Н. ")
    if sc["pressure_exceeded"]:
        bad = f.table[f.table["p_act"] > a.pressure]
        where = ", ".join(fmt(v, digits=3) for v in bad["q"]) if len(bad) else fmt(sc["q_p_act_max"], digits=3)
        txt += (f"<b>При S&nbsp;=&nbsp;{where}&nbsp;м требуемое давление ({fmt(sc['p_act_max'] / 1e6, sig=5)}&nbsp;МПа) "
                f"превышает давление в гидросистеме: запас грузоподъёмности отрицателен "
                f"({fmt(sc['reserve_min_pct'], digits=1)}&nbsp;%), груз {html_label(c.load)} в этом положении не поднимается.</b>")
    else:
        txt += f"Наименьший запас грузоподъёмности — {fmt(sc['reserve_min_pct'], digits=1)}&nbsp;%."
    s.paragraph(txt)


# --------------------------------------------------------------------------------------------
# carrier vehicle
# --------------------------------------------------------------------------------------------
def _carrier(sec: Section, study, f, lab: str) -> None:
    c = f.settings.carrier
    s = sec.subsection("Нагрузки на мосты и управляемость " + (c.title or "машины-носителя"), "sec-frc-carrier")
    row = f.row(lab)
    G = float(-[ld for ld in f.solution.loads if ld.name == c.load][0].Fy[0])
    total = G + c.weight + c.ballast
    x = row["x_load"]
    s.paragraph(f"Реакции управляемого (переднего) моста <i>R</i><sub>A</sub> и заднего моста <i>R</i><sub>B</sub> находятся из "
                f"уравнений равновесия машины: суммы сил и моментов относительно оси задних колёс. Вес машины "
                f"<i>P</i><sub>в</sub>&nbsp;=&nbsp;{_fin(c.weight, 'Н')} приложен на расстоянии <i>b</i>&nbsp;=&nbsp;"
                f"{_fin(c.weight_arm, 'м')} впереди задней оси, противовесы <i>P</i><sub>гр</sub>&nbsp;=&nbsp;"
                f"{_fin(c.ballast, 'Н')} — на <i>a</i>&nbsp;=&nbsp;{_fin(c.ballast_arm, 'м')} впереди "
                f"передней оси, база <i>L</i>&nbsp;=&nbsp;{_fin(c.wheelbase, 'м')}, груз <i>G</i>&nbsp;=&nbsp;{html_label(c.load)} — на расстоянии "
                f"<i>x</i><sub>G</sub> (координата его центра масс) позади задней оси. Для положения {pos_no(study, lab)} "
                f"(по всем положениям — таблица {ref('tab-frc-carrier')} и рисунок {ref('fig-frc-carrier')}):")
    RA = row["R_front"]
    m0 = c.ballast * (c.ballast_arm + c.wheelbase) + c.weight * c.weight_arm
    # x_G to as many digits as make both quotients the printed R_A and G_max
    w0, wr, wL, wG = written(m0, 6), written(row["R_front_min"], 5), float(c.wheelbase), float(G)
    sx = max(agreeing_sig(lambda f: (m0 - wG * f[0]) / wL, [x], RA, sig=5, result_sig=5),
             agreeing_sig(lambda f: (w0 - wr * wL) / f[0], [x], row["Gmax_carrier"], sig=5, result_sig=5))
    s.formula(
        Formula(r"R_A = \frac{P_{гр} (a + L) + P_в b - G x_G}{L}",
                rf"\frac{{{_in(c.ballast)} \cdot ({_in(c.ballast_arm)} + {_in(c.wheelbase)}) + {_in(c.weight)} \cdot "
                rf"{_in(c.weight_arm)} - {_in(G)} \cdot {_ts(x, sx)}}}{{{_in(c.wheelbase)}}}",
                _t(RA, sig=5, unit="Н"), label="eq-frc-RA"),
        Formula(r"R_B = P_{гр} + P_в + G - R_A", None, _t(row["R_rear"], sig=5, unit="Н")),
        Formula(r"\Delta R_A = \frac{R_A}{G + P_в + P_{гр}} \cdot 100\%",
                rf"\frac{{{_t(RA, sig=5)}}}{{{_in(total)}}} \cdot 100\%", _t(row["front_share_pct"], digits=1, unit="%")),
        Formula(r"R_{A,min} = k_A (G + P_в + P_{гр})", rf"{_in(c.min_share)} \cdot {_in(total)}",
                _t(row["R_front_min"], sig=5, unit="Н")))
    s.paragraph("Наибольший груз, при котором на управляемый мост приходится не меньше <i>R</i><sub>A,min</sub> "
                "(из того же уравнения моментов):")
    s.formula(
        Formula(r"G_{max} = \frac{P_в b + P_{гр} (a + L) - R_{A,min} L}{x_G}",
                rf"\frac{{{_t(m0, sig=6)} - {_t(row['R_front_min'], sig=5)} \cdot {_in(c.wheelbase)}}}{{{_ts(x, sx)}}}",
                _t(row["Gmax_carrier"], sig=5, unit="Н"), label="eq-frc-Gmax"),
        Formula(r"G_{max}^{*} = \frac{P_в b + P_{гр} (a + L) - k_A L (P_в + P_{гр})}{x_G + k_A L}", None,
                _t(row["Gmax_carrier_consistent"], sig=5, unit="Н")))
    s.paragraph("Здесь <i>R</i><sub>A,min</sub> вычислена "
                "для номинального груза; если условие <i>R</i><sub>A</sub>&nbsp;≥&nbsp;<i>k</i><sub>A</sub>·Σ<i>G</i> относить к "
                "наибольшему грузу, получается <i>G</i><sub>max</sub><sup>*</sup>.")
    cols = [Column("R_front", sub("R", "A"), "Н", digits=0, sig=None), Column("R_rear", sub("R", "B"), "Н", digits=0, sig=None),
            Column("front_share_pct", "Δ" + sub("R", "A"), "%", digits=1),
            Column("rear_share_pct", "Δ" + sub("R", "B"), "%", digits=1),
            Column("Gmax_carrier", sub("G", "max"), "Н", digits=0, sig=None),
            Column("Gmax_carrier_consistent", sub("G", "max") + "<sup>*</sup>", "Н", digits=0, sig=None)]
    s.table("Результаты анализа устойчивости и управляемости", _lead(study) + cols, f.table, id="tab-frc-carrier")
    s.figure("Доля веса на управляемом мосту и наибольший груз по ходу поршня", AxleCurves().draw(study).svg, 160,
             id="fig-frc-carrier")
    sc = f.scalars
    s.paragraph(f"Результаты — в таблице {ref('tab-frc-carrier')} и на рисунке {ref('fig-frc-carrier')}. Наименьшая "
                f"нагрузка на управляемый мост — {fmt(sc['R_front_min_value'], sig=5)}&nbsp;Н "
                f"({fmt(sc['R_front_min_value'] / total * 100, digits=1)}&nbsp;% веса, допускается не менее "
                f"{fmt(100 * c.min_share, digits=0)}&nbsp;%).")


# --------------------------------------------------------------------------------------------
# conclusion
# --------------------------------------------------------------------------------------------
BAL_DYN_TEX = r"M_{\text{д}} - J_I \varepsilon"     # the balancing moment by the equation of motion


def conclusion_lines(study) -> list[str]:
    """Lines of the ЗАКЛЮЧЕНИЕ about the force analysis (HTML); symbols as inline math, as the text sets them."""
    f = study.forces
    sc = f.scalars
    out = []
    big = max((p for p in f.model.pairs if p.kind != KS.K_MOM), key=lambda p: sc[f"R_{p.name}_max"])
    q = sc[f"q_R_{big.name}_max"]
    where = (f"φ&nbsp;=&nbsp;{fmt(q_degrees(study, q), digits=1)}°" if f.rotary
             else f"{inline_math('S')}&nbsp;=&nbsp;{fmt(q, digits=3)}&nbsp;м")
    out.append(f"Силовой расчёт выполнен по группам Ассура; наибольшая реакция — в паре {big.a}–{big.b}: "
               f"{fmt(sc[f'R_{big.name}_max'], sig=5)}&nbsp;Н при {where}.")
    if f.rotary:
        line = (f"Наибольший по модулю уравновешивающий момент — {fmt(sc['M_bal_absmax'], sig=5)}&nbsp;Н·м; "
                "проверки рычагом Жуковского и по балансу мощностей его подтверждают")
        if "dev_M_bal_dyn_max" in sc:
            line += (f", он совпадает с моментом {inline_math(BAL_DYN_TEX)}, найденным из уравнения "
                     "движения машины")
        out.append(line + ".")
    else:
        out.append(f"Наибольшее усилие гидроцилиндра — {fmt(sc['F_act_absmax'], digits=0)}&nbsp;Н; проверка рычагом "
                   "Жуковского его подтверждает.")
    s = f.settings
    if s.capacity is not None:
        if sc["pressure_exceeded"]:
            out.append(f"Требуемое давление в гидроцилиндрах достигает {fmt(sc['p_act_max'] / 1e6, sig=5)}&nbsp;МПа при "
                       f"{inline_math('S')}&nbsp;=&nbsp;{fmt(sc['q_p_act_max'], digits=3)}&nbsp;м и превышает давление в гидросистеме "
                       f"{_fin(s.actuator.pressure / 1e6)}&nbsp;МПа: запас грузоподъёмности "
                       f"{fmt(sc['reserve_min_pct'], digits=1)}&nbsp;%, в начале подъёма груз не поднимается.")
            # what to change: the bore that gives the largest force at the system's pressure,
            # F = k·p·η·πD²/4 → D = √(4F/(π k p η)), or the pressure at the given bore
            A = s.actuator
            D_req = math.sqrt(4.0 * sc["F_act_absmax"] / (math.pi * A.count * A.pressure * A.efficiency))
            out.append(f"Чтобы груз поднимался во всём ходе, нужен диаметр гидроцилиндров не менее "
                       f"<i>D</i>&nbsp;=&nbsp;√(4<i>F</i><sub>max</sub>/(π<i>kp</i>η))&nbsp;=&nbsp;"
                       f"{fmt(math.ceil(D_req * 1e4) / 10, digits=1)}&nbsp;мм (задан {_fin(A.diameter * 1e3)}&nbsp;мм) или "
                       f"давление в гидросистеме не менее {fmt(math.ceil(sc['p_act_max'] / 1e5) / 10, digits=1)}&nbsp;МПа "
                       "(значения округлены в большую сторону).")
        else:
            out.append(f"Наименьший запас грузоподъёмности — {fmt(sc['reserve_min_pct'], digits=1)}&nbsp;%.")
    if s.carrier is not None:
        c = s.carrier
        t = f.table
        out.append(f"Доля веса на управляемом мосту — от {fmt(t['front_share_pct'].min(), digits=1)} до "
                   f"{fmt(t['front_share_pct'].max(), digits=1)}&nbsp;% (не менее {fmt(100 * c.min_share, digits=0)}&nbsp;%); "
                   f"наибольший допустимый груз по условию управляемости — от {fmt(t['Gmax_carrier'].min(), sig=5)} до "
                   f"{fmt(t['Gmax_carrier'].max(), sig=5)}&nbsp;Н по ходу поршня.")
    return out
