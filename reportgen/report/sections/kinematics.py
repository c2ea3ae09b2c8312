"""Section «Кинематический анализ механизма»: plan of positions, analogs, velocity and
acceleration plans with the graphical/analytical comparison, kinematic diagrams, true
velocities, and the formulas of the chosen position."""
from __future__ import annotations

import math

import numpy as np
import pandas as pd
from markupsafe import Markup

from ...analysis.plans import drawn, group_rank, omega_segment, output_quantity, parallel_outputs, read_velocities
from ...mechanism.model import FRAME
from ...scenes.diagrams import AnalogCurves, OutputDiagrams, output_displacement, output_index
from ...scenes.mechanism import PositionsPlan, traced_points
from ...scenes.plans import MIN_MM, READ_MM, PlanScene
from ...scenes.draw import gost_ratio, mu_text
from ...style.numbers import fmt, fmt_given, fmt_pct, tex_num
from ..document import Column, Formula, Section, ref
from ..formulas import inline_math
from ..russian import expr_html, flag_group, flag_where
from . import vectors
from .common import (chosen_position, chunked_tables, fit_condition, html_point, input_word, pos_fmt, pos_no, q_degrees, q_header, sub,
                     swing_text, tex_point)

NEEDS = ("kinematics", "cycle")


def _moving_points(study) -> list[str]:
    fixed = set(study.mechanism.link(FRAME).points)
    seen, out = set(), []
    for l in study.mechanism.moving:
        for p in l.points:
            if p not in fixed and p not in seen:
                seen.add(p)
                out.append(p)
    return out


def motion_points(study) -> tuple[list[str], str]:
    """The moving points of the velocity and acceleration tables and the sentence that says which
    are left out: all points of a link that only translates (a saw frame: B, its centre of mass S₃,
    the blade T) have one velocity and one acceleration (Артоболевский [1], поступательное
    движение), so the link is represented by its first joint, not by identical columns."""
    mech = study.mechanism
    cyc = study.cycle if study.has_cycle else study.kinematics
    joints = {j.point for j in mech.joints}
    pts, lines = _moving_points(study), []
    for l in mech.moving:
        own = [p for p in l.points if p in pts]
        if len(own) < 2 or float(np.abs(cyc["wq_" + l.name]).max()) > 1e-12:
            continue
        ref = next((p for p in own if p in joints), own[0])
        same = [p for p in own if p != ref]
        pts = [p for p in pts if p not in same]
        lines.append(f"звено {l.name} движется поступательно: скорости и ускорения всех его точек равны "
                     f"скоростям и ускорениям точки {html_point(ref)}, поэтому "
                     f"{'точка' if len(same) == 1 else 'точки'} {', '.join(html_point(p) for p in same)} в "
                     "таблицы скоростей и ускорений не " + ("включена" if len(same) == 1 else "включены"))
    text = "; ".join(lines)
    return pts, (text[0].upper() + text[1:] + ".") if text else ""


def _links(study):
    """Links whose angle changes (a slider on a fixed guide only translates), except those turning
    with a rotating input link (:func:`_with_input`: their columns would repeat φ₁, 1, 0, ω₁, ε₁)."""
    d = study.mechanism.driver
    cyc = study.cycle if study.has_cycle else study.kinematics
    twins = set(_with_input(study))
    return [l for l in study.mechanism.moving if not (d.kind == "actuator" and l.name == d.rod)
            and float(np.abs(cyc["wq_" + l.name]).max()) > 1e-12 and l.name not in twins]


def _with_input(study) -> list[str]:
    """Links other than a rotating input link that turn with it (φ′ = 1, φ″ = 0 everywhere: a stone
    sliding in the input link's own slot)."""
    d = study.mechanism.driver
    if not d.rotary:
        return []
    cyc = study.cycle if study.has_cycle else study.kinematics
    return [l.name for l in study.mechanism.moving if l.name != d.link
            and float(np.abs(cyc["wq_" + l.name] - 1.0).max()) <= 1e-12
            and float(np.abs(cyc["eq_" + l.name]).max()) <= 1e-12]


def _with_input_text(study) -> str:
    """«Звено 2 (камень) поворачивается вместе с ведущим звеном 1: φ₂ = φ₁ + const, φ′₂ = 1, φ″₂ = 0,
    ω₂ = ω₁, ε₂ = ε₁ (в таблицы не включены).» — empty without such links."""
    twins = _with_input(study)
    if not twins:
        return ""
    mech, d = study.mechanism, study.mechanism.driver
    one = len(twins) == 1
    named = ", ".join(str(Markup("{} ({})").format(n, Markup(mech.link(n).title).striptags()) if mech.link(n).title
                          else n) for n in twins)
    eqs = "; ".join(f"{sub('φ′', n)}&nbsp;=&nbsp;1, {sub('φ″', n)}&nbsp;=&nbsp;0, {sub('ω', n)}&nbsp;=&nbsp;"
                    f"{sub('ω', d.link)}, {sub('ε', n)}&nbsp;=&nbsp;{sub('ε', d.link)}" for n in twins)
    return (f"{'Звено' if one else 'Звенья'} {named} {'поворачивается' if one else 'поворачиваются'} вместе с "
            f"ведущим звеном {d.link}: {eqs} во всех положениях (в таблицы не {'включено' if one else 'включены'}).")


def _turning_link(study, key: str) -> str | None:
    """The link of the dyad of a transmission-angle flag ``mu_2_3`` hinged to the frame that makes
    whole turns (a double-crank linkage's driven crank), or None: the advice on a low angle for
    a rocker (its extreme positions) does not apply to it."""
    from ...analysis.link_motion import turns_fully
    mech = study.mechanism
    for link in key[3:].split("_"):
        hinged = any(j.kind == "R" and FRAME in j.links and link in j.links for j in mech.joints)
        if hinged and turns_fully(study, link):
            return link
    return None


def _attached_to(study, key: str) -> str:
    """«звено 1»: the moving link the dyad of a flag ``mu_2_3`` is attached to (besides the frame),
    or «звено, к которому присоединена группа» where there are several."""
    links = set(key[3:].split("_"))
    before: set[str] = set()            # the links of the groups attached before this one
    for g in study.structure.groups:
        if links & set(g.links):
            break
        before |= set(g.links)
    other = {l for j in study.mechanism.joints if len(links & set(j.links)) == 1
             for l in j.links if l in before}
    return f"звено {other.pop()}" if len(other) == 1 else "звено, к которому присоединена группа,"


def _slider_advice(study, key: str) -> str | None:
    """How to raise a low transmission angle of a dyad with a slider (ВВП, flag ``mu_4_5``): the
    guide's force on the slider is normal to the guide and the slider's pin moves ⊥ the link hinged
    to it, so μ is largest where that link lies along the guide (Артоболевский [1], угол давления):
    on a fixed guide a longer rod or a smaller offset; on a moving guide (a slider on a rocker) the
    length of the link or the place of its pivot. None for a dyad without a slider."""
    mech = study.mechanism
    links = set(key[3:].split("_"))
    for j in mech.prismatic:
        guide, slider = j.links
        if slider not in links:
            continue
        rod = next((o for jt in mech.joints if jt.kind == "R" and slider in jt.links
                    for o in jt.links if o != slider and o in links), None)
        if rod is None:
            return None
        if guide == FRAME:
            return (f"Угол передачи можно увеличить, удлинив звено {rod} (уменьшив отношение длины кривошипа "
                    f"к его длине) или уменьшив смещение направляющей ползуна {slider}: звено {rod} тогда "
                    "ближе к направлению направляющей (повторить синтез с ограничением μ ≥ 40°)")
        pivot = any(FRAME in jt.links and rod in jt.links for jt in mech.joints)
        return (f"Угол передачи можно увеличить, изменив длину звена {rod} или положение "
                f"{'его опоры' if pivot else 'его шарниров'} так, чтобы в этих положениях звено {rod} было ближе "
                f"к направлению направляющей звена {guide}, по которой скользит ползун {slider} (повторить "
                "синтез с ограничением μ ≥ 40°)")
    return None


def _strokes(study, s, exact: bool = True) -> tuple[float, float, float, float]:
    """Crank coordinates of the output's extreme positions (lowest, highest), the crank angle of
    the shorter stroke (°) and the coefficient of change of the mean speed K = (360° − that
    angle)/that angle ≥ 1.  The extremes are the exact roots of the output's analog (study
    ``output_q1``/``output_q2``, the ones K of the conclusion and the load switching angles are
    counted from), not the nearest nodes of the cycle grid; the grid where they are absent or
    ``s`` is another output than the one they belong to (``exact`` false: a second piston)."""
    q = study.cycle["q"].to_numpy()
    lo, hi = float(q[int(np.argmin(s))]), float(q[int(np.argmax(s))])
    sc = study.scalars
    if exact and "output_q1" in sc and "output_q2" in sc:
        q1, q2 = float(sc["output_q1"]), float(sc["output_q2"])
        lo, hi = (q1, q2) if np.interp(q1, q, s) < np.interp(q2, q, s) else (q2, q1)
    th = abs(math.degrees(hi - lo))
    work = min(th, 360 - th)
    K = (360 - work) / work if work > 0 else float("nan")
    return lo, hi, work, K


QUICK_RETURN_K = 1.05     # below it the strokes take practically the same time: no slow and fast stroke


def _quick_return(fast: float, K: float, working: str | None = None, direction: int = 1, idle: bool = True,
                  share: float | None = None) -> str:
    """Engineering reading of K > 1 (Артоболевский, гл. «Синтез»): the slow stroke is the working one.
    ``working`` — which stroke the case's loads resist (:func:`_working_stroke`): where it is the
    fast one the note says so and what to change: the crank turned the other way (``direction``:
    +1 counter-clockwise as given, −1 clockwise) goes through the same positions in the reverse
    order, so the output makes each stroke over the other arc of the crank's turn and the working
    stroke becomes the slow one. ``idle`` — whether the other stroke is idle (:func:`_return_idle`):
    only then is the fast return said to shorten the cycle (at the working stroke's speed, the
    productivity argument of a shaper); otherwise it is the return stroke (обратный), whose
    resistance the case gives too (a compressor's suction stroke). ``share`` — the part of the
    working stroke over which the loads act (:func:`_working_share`): under :data:`SHORT_LOAD_SHARE`
    (a loom's beat-up at the end of the swing) a slow stroke gains nothing, its mean speed does not
    set the speed at which the short load is overcome, and no other direction is advised."""
    if not K > QUICK_RETURN_K:
        return ""
    head = (f" Один ход выходного звена занимает {fmt(360 - fast, digits=1)}°, другой — {fmt(fast, digits=1)}° "
            f"поворота кривошипа: ")
    if working == "fast" and share is not None and share < SHORT_LOAD_SHARE:
        return head + (f"силы сопротивления действуют на быстром ходе, но лишь на {fmt(100 * share, digits=0)}&nbsp;% "
                       f"его ({fmt(share * fast, digits=0)}° поворота кривошипа из {fmt(fast, digits=1)}°); такая кратковременная нагрузка преодолевается со скоростью, "
                       "которую выходное звено имеет в этих положениях, а не со средней скоростью хода, поэтому "
                       "медленный рабочий ход выигрыша не дал бы и направление вращения кривошипа оставлено "
                       "заданным.")
    if working == "fast":
        other = "по часовой стрелке" if direction > 0 else "против часовой стрелки"
        return head + (f"силы сопротивления действуют на быстром ходе, т. е. при заданном направлении вращения "
                       f"кривошипа рабочим оказался быстрый ход, хотя рабочим выгоднее назначать медленный "
                       f"({'холостой' if idle else 'обратный'} ход тогда выполняется в {fmt(K, digits=2)} раза быстрее). При обратном направлении вращения "
                       f"кривошипа механизм проходит те же положения в обратном порядке, и каждый ход выходного звена "
                       f"совершается за другую часть оборота: ход в направлении нынешнего быстрого становится "
                       f"медленным. Поэтому кривошип целесообразно вращать {other} (расчёты записки выполнены для "
                       f"заданного направления вращения).")
    lead = ("рабочий ход (на нём действуют силы сопротивления) — медленный" if working == "slow"
            else "рабочим назначается медленный ход")
    if not idle:
        return head + f"{lead}, обратный выполняется в {fmt(K, digits=2)} раза быстрее."
    return head + (f"{lead}, холостой выполняется в {fmt(K, digits=2)} раза быстрее, что при той же скорости "
                   f"рабочего хода сокращает время цикла.")


IDLE_SHARE = 0.02     # a stroke with less than this share of the other stroke's resistance is idle (холостой)


def _stroke_resistances(study) -> tuple[float, float, bool] | None:
    """(resistance on the stroke from the extreme position q₁ to q₂, on the other stroke, whether
    the first is the slow one): R = −∫ min(ΣM_i, 0) dφ over each stroke (M_i — the reduced moments
    of the case's ``[loads]``, weights left out: a counterweight that rises on one stroke and falls
    on the other is no technological resistance; a load that helps the motion, as the weight of a
    pump's rod string on the down stroke, resists nothing). None without [dynamics] or for a
    longer cycle."""
    sc = study.scalars
    if not study.root.has("dynamics") or "output_q1" not in sc:
        return None
    cyc = study.dynamics.cycle
    q = cyc["q"].to_numpy()
    period = study.grid.length
    if abs((q[-1] - q[0]) - period) > 1e-9 * period:
        return None
    cols = ["M_" + ld.name for ld in study.dynamics.loads.loads if ld.kind != "weight"]
    if not cols:
        return None
    m = np.minimum(sum(cyc[c].to_numpy() for c in cols), 0.0)
    R = np.concatenate(([0.0], np.cumsum(np.diff(q) * 0.5 * (m[1:] + m[:-1]))))   # ∫ of the resisting part
    q1, q2 = sorted((sc["output_q1"], sc["output_q2"]))
    a = float(np.interp(q1, q, R) - np.interp(q2, q, R))      # the stroke from q₁ to q₂ (≥ 0)
    b = float(R[0] - R[-1]) - a
    return a, b, (q2 - q1) > period / 2


SHORT_LOAD_SHARE = 1 / 3   # a resistance acting over less than this share of its stroke is a short load


def _working_share(study) -> float | None:
    """The share of the working stroke's crank turn over which the case's loads resist (the
    reduced moment of the loads, weights left out, below zero; :func:`_stroke_resistances`): 1
    for a cutting force over the whole stroke, ≈ 0,1 for a beat-up force at its end.  None where
    the working stroke is not told."""
    res = _stroke_resistances(study)
    if res is None or _working_stroke(study) is None:
        return None
    a, b, _ = res
    cyc = study.dynamics.cycle
    q = cyc["q"].to_numpy()
    cols = ["M_" + ld.name for ld in study.dynamics.loads.loads if ld.kind != "weight"]
    total = sum(cyc[c].to_numpy() for c in cols)
    m = np.minimum(total, 0.0)
    resisting = m < -1e-9 * max(float(np.abs(total).max()), 1e-300)
    q1, q2 = sorted((study.scalars["output_q1"], study.scalars["output_q2"]))
    inside = (q >= q1) & (q <= q2)
    stroke = inside if a >= b else ~inside
    dq = np.diff(q)
    mid = 0.5 * (q[1:] + q[:-1])
    inner = (mid >= q1) & (mid <= q2)
    on = (stroke[1:] & stroke[:-1]) & (inner if a >= b else ~inner)
    length = float(dq[on].sum())
    if length <= 0:
        return None
    return float(dq[on & resisting[1:] & resisting[:-1]].sum()) / length


def _working_stroke(study) -> str | None:
    """Which stroke of the output the case's loads resist (:func:`_stroke_resistances`): "slow"/"fast"
    where one stroke takes at least twice the other's resistance, None without [dynamics], for a
    longer cycle or a load on both strokes alike."""
    res = _stroke_resistances(study)
    if res is None:
        return None
    a, b, slow_is_a = res
    if max(a, b) <= 0 or max(a, b) < 2 * max(min(a, b), 0.0):
        return None
    return "slow" if (a > b) == slow_is_a else "fast"


def _return_idle(study) -> bool:
    """Whether the stroke other than the working one is idle (холостой): its resistance under
    IDLE_SHARE of the working stroke's (a shaper's return; not a compressor's suction stroke, whose
    gas forces resist too). True where the case gives no loads to tell (the textbook convention of
    a working and an idle stroke)."""
    res = _stroke_resistances(study)
    if res is None or _working_stroke(study) is None:
        return True
    a, b, _ = res
    return max(min(a, b), 0.0) < IDLE_SHARE * max(a, b)


def _in_tables(ids: list[str]) -> str:
    """«таблице 2.1» for one table, «таблицах 2.1 и 2.2» (or «2.1–2.3») for the parts of a wide one."""
    if len(ids) == 1:
        return f"таблице {ref(ids[0])}"
    return f"таблицах {ref(ids[0])}{' и ' if len(ids) == 2 else '–'}{ref(ids[-1])}"


def _rotates(study, link: str) -> bool:
    """The link turns somewhere in the cycle (a guide on it gives a Coriolis acceleration)."""
    return float(np.abs(study.cycle["wq_" + link]).max()) > 1e-12


def build(study) -> Section:
    mech = study.mechanism
    k = study.kinematics.copy()
    sec = Section("Кинематический анализ механизма", "sec-kinematics")
    qkey, qhead, qunit, qfmt = q_header(study)
    lead = [Column("pos", "№", fmt=pos_fmt(study)), Column(qkey, qhead, qunit, **qfmt)]
    pts = _moving_points(study)
    rotary = mech.driver.rotary
    w_known = mech.driver.omega is not None

    # ----- plan of positions
    s1 = sec.subsection("План положений механизма", "sec-positions")
    plan = PositionsPlan().draw(study)
    traced_all = traced_points(study)
    extra = [p for p in traced_all if p not in {l.com for l in mech.moving}]
    traced = "".join(f" и точки {p}" for p in extra)       # a coupler point given as the output
    # what the dashed lines are: centres of mass only where the case gives them
    paths = ("траектории центров масс звеньев" + traced if len(extra) < len(traced_all) else
             f"траектория точки {extra[0]}" if len(extra) == 1 else
             "траектории точек " + ", ".join(extra) if extra else "")
    shown = (f"Штриховой линией показана {paths}" if paths.startswith("траектория ") else
             f"Штриховыми линиями показаны {paths}")
    ncount = int((~k["pos"].astype(str).str.startswith("д")).sum()) if k["pos"].dtype == object else len(k)
    mu_l = inline_math(r"\mu_l")
    phi0_m = inline_math(r"\varphi_0")
    w1_m = inline_math(r"\omega_1")
    # true motion from the analogs: the generalized speed is ω₁ of a crank, the rate Ṡ at which an
    # actuator's length changes (Ṡ, S̈ of the cylinder), not an angular speed
    d_ = mech.driver
    rel = "" if rotary else f"{d_.rod}{d_.link}"       # the rod relative to the cylinder: v₂₁, a₂₁
    v_m = inline_math(r"v = \omega_1 x^{\prime}" if rotary else rf"v = v_{{{rel}}} x^{{\prime}}")
    a_m = inline_math(r"a = \omega_1^2 x^{\prime\prime} + \varepsilon_1 x^{\prime}" if rotary
                      else rf"a = v_{{{rel}}}^2 x^{{\prime\prime}} + a_{{{rel}}} x^{{\prime}}")
    # the scale, then the dashed lines and the figure; with no dashed lines the figure follows the
    # scale in the same sentence («(1:10), рисунок 2.1», not «(1:10). (рисунок 2.1).»)
    scale = f"Масштаб {mu_l}&nbsp;=&nbsp;{mu_text(plan.mu)}&nbsp;м/мм ({gost_ratio(plan.mu)})"
    scale_tail = (f"{scale}. {shown} (рисунок {ref('fig-positions')})." if paths else
                  f"{scale}, рисунок {ref('fig-positions')}.")
    if not study.has_cycle:
        s1.paragraph(f"Механизм рассчитан в {ncount} заданных положениях {input_word(mech.driver, 'gen')} "
                     f"(углы φ в таблицах); цикл не рассчитывается — механизм собирается не во всех положениях "
                     f"цикла, поэтому траектории, диаграммы и крайние положения выходного звена не строятся. "
                     f"{scale}, рисунок {ref('fig-positions')}.")
    elif mech.driver.swing:
        s1.paragraph(f"План положений построен для {ncount} положений входного коромысла {mech.driver.link} в "
                     f"диапазоне его качания {swing_text(mech.driver)}, от одного крайнего положения до другого; "
                     f"на обратном ходе звенья проходят те же положения в обратном порядке. "
                     + scale_tail)
    elif rotary:
        s1.paragraph(f"План положений построен для {ncount} положений кривошипа, начиная с положения "
                     f"{phi0_m}&nbsp;=&nbsp;{fmt(math.degrees(mech.driver.phi0), digits=1)}°, "
                     f"при вращении {'по часовой стрелке' if mech.driver.direction < 0 else 'против часовой стрелки'}. "
                     + scale_tail
                     # a crank too small for its position numbers: numbered on its enlarged view
                     + (f" Кривошип в этом масштабе мал, поэтому положения шарнира {Markup('<i>{}</i>').format(mech.crank_pin())} "
                        f"пронумерованы на выносном элементе {plan.detail_mark}, вычерченном в масштабе "
                        f"{gost_ratio(plan.detail_mu)}."
                        if plan.detail_mu else ""))
    else:
        lo, hi = mech.driver.q_range
        s1.paragraph(f"План положений построен для {ncount} значений длины гидроцилиндра от "
                     f"{fmt(lo, digits=3)} до {fmt(hi, digits=3)}&nbsp;м; масштаб {mu_l}&nbsp;=&nbsp;"
                     f"{mu_text(plan.mu)}&nbsp;м/мм ({gost_ratio(plan.mu)}), рисунок {ref('fig-positions')}."
                     + (f" {shown}." if paths else ""))
    fig = s1.figure("План положений механизма" + (" и " + paths.replace(" звеньев", "") if study.has_cycle and paths else ""), plan.svg, plan.width_mm,
                    id="fig-positions", landscape=plan.landscape)
    if plan.landscape:      # its own page follows the first table of coordinates (not a near-empty page)
        s1.children.remove(fig)
    if study.fits:
        s1.paragraph("Неизвестные размеры подобраны из условий задания (решение уравнений с точностью 10⁻¹²):")
        rows = [(f, *fit_condition(study, f)) for f in study.fits]
        fdf = pd.DataFrame([{"name": f.name, "cond": Markup("{} ({})").format(c, t) if t else c, "at": at,
                             "value": f.value} for f, c, t, at in rows])
        s1.table("Подобранные размеры", [Column("name", "Величина", fmt=expr_html),
                                          Column("cond", "Условие", fmt=Markup),
                                          Column("at", "Положение", fmt=Markup),
                                          Column("value", "Значение", "м", digits=4)],
                 fdf, id="tab-fits")
    cols = []
    for p in pts:
        cols += [Column(f"x_{p}", f"<i>x</i><sub>{p}</sub>", "м", digits=3),
                 Column(f"y_{p}", f"<i>y</i><sub>{p}</sub>", "м", digits=3)]
    ids = chunked_tables(s1, "Координаты точек механизма", k, cols, lead, "tab-coords")
    if plan.landscape:
        first = next(i for i, b in enumerate(s1.children) if getattr(b, "id", None) == ids[0])
        s1.children.insert(first + 1, fig)
    angle_cols = []
    for l in _links(study):
        if qkey == "q_deg" and l.name == mech.driver.link and f"phi_{l.name}" in k and \
                all(_deg(a) == fmt(q, digits=2) for a, q in zip(k[f"phi_{l.name}"], k["q_deg"])):
            continue      # the crank's angle equals φ of the lead column (φ₀ = 0, counter-clockwise)
        angle_cols.append(Column(f"phi_{l.name}", sub("φ", l.name), "град", fmt=_deg))
    points = [j.point for j in mech.prismatic]
    for j in mech.prismatic:          # s_H by the slider's point, not the pair's name (unless shared)
        angle_cols.append(Column(f"s_{j.name}", sub("s", j.point if points.count(j.point) == 1 else j.name),
                                 "м", digits=4))
    for c in k.columns:
        if c.startswith("phi_") and c[4:] not in [l.name for l in mech.links]:
            angle_cols.append(Column(c, sub("φ", c[4:]), "град", fmt=_deg))
    a_ids = chunked_tables(s1, "Углы звеньев" + (" и перемещения в поступательных парах" if mech.prismatic else ""),
                           k, angle_cols, lead, "tab-angles")
    s1.paragraph(f"Координаты точек приведены в {_in_tables(ids)}, углы звеньев — в {_in_tables(a_ids)}.")

    # ----- analogs
    s2 = sec.subsection("Аналоги скоростей и ускорений", "sec-analogs")
    qs = "φ" if rotary else "S"
    # units of the analogs follow the generalized coordinate: d/dφ keeps a length a length and an
    # angle dimensionless; d/dS makes a point's analog dimensionless and a link's 1/м
    u_w, u_e, u_x = (None, None, "м") if rotary else ("1/м", "1/м²", None)   # as the diagrams (rad dimensionless)
    wcols = [Column(f"wq_{l.name}", sub("φ′", l.name), u_w, digits=4) for l in _links(study)
             if not (rotary and l.name == mech.driver.link)]
    ecols = [Column(f"eq_{l.name}", sub("φ″", l.name), u_e, digits=4) for l in _links(study)
             if not (rotary and l.name == mech.driver.link)]
    angular = bool(wcols)   # no table of angular analogues where every other link only translates
    if angular:
        wcols, wzero = zero_columns(k, wcols)
        ecols, ezero = zero_columns(k, ecols)
    curves_named = bool(wcols) and study.has_cycle
    s2.paragraph(
        f"Положения звеньев найдены в замкнутом виде для каждой группы Ассура; аналоги скоростей "
        f"и ускорений (производные по обобщённой координате {qs}) получены точно из линейных систем "
        f"групп, без численного дифференцирования. Истинные скорости и ускорения: "
        f"{v_m}, {a_m}" + ("" if rotary else f", где {inline_math('v_{' + rel + '}')} и "
                           f"{inline_math('a_{' + rel + '}')} — скорость и ускорение штока {d_.rod} "
                           f"относительно цилиндра {d_.link} (первая и вторая производные длины S по времени)") + "."
        # the curves named before them (ГОСТ 7.32), in this paragraph: a line of its own just before
        # the figure was left alone at a page foot (ws004)
        + (f" Графики аналогов угловых скоростей звеньев — на рисунке {ref('fig-analogs')}." if curves_named else ""))
    if _with_input_text(study):
        s2.paragraph(_with_input_text(study))
    if angular:
        chunked_tables(s2, "Аналоги угловых скоростей звеньев", k, wcols, lead, "tab-wq", note=_zero_note(wzero))
        chunked_tables(s2, "Аналоги угловых ускорений звеньев", k, ecols, lead, "tab-eq", note=_zero_note(ezero))
    elif _with_input(study):
        s2.paragraph("Остальные звенья движутся поступательно: их угловые скорости и ускорения равны нулю.")
    else:
        s2.paragraph("Все звенья механизма, кроме ведущего, движутся поступательно: их угловые скорости "
                     "и ускорения равны нулю.")
    pts_v, same_text = motion_points(study)
    if same_text:
        s2.paragraph(same_text)
    vcols = []
    for p in pts_v:
        vcols += [Column(f"vqx_{p}", f"<i>x′</i><sub>{p}</sub>", u_x, digits=4),
                  Column(f"vqy_{p}", f"<i>y′</i><sub>{p}</sub>", u_x, digits=4)]
    vcols, zero = zero_columns(k, vcols)
    chunked_tables(s2, "Аналоги скоростей точек", k, vcols, lead, "tab-vq", note=_zero_note(zero))
    if curves_named:
        curves = AnalogCurves().draw(study)
        s2.figure("Аналоги угловых скоростей звеньев " + ("в диапазоне качания входного звена" if mech.driver.swing
                                                           else "за цикл" if rotary else "по ходу гидроцилиндра"), curves.svg, curves.width_mm, id="fig-analogs")

    # ----- true velocities
    if w_known:
        s3 = sec.subsection("Скорости и ускорения точек и звеньев", "sec-true")
        w1 = mech.driver.omega
        if mech.driver.swing:
            s3.paragraph(f"Входное коромысло качается с постоянной по модулю угловой скоростью "
                         f"{w1_m}&nbsp;=&nbsp;{fmt(w1, digits=3)}&nbsp;рад/с; значения в таблицах — для прямого хода.")
        elif rotary:
            # short enough for one line: a justified first line stretched before an unbreakable
            # «ω₁ = 15,000 рад/с» read badly
            s3.paragraph(f"Угловая скорость {'кривошипа' if study.has_cycle else 'ведущего звена'} постоянна: "
                         f"{w1_m}&nbsp;=&nbsp;{fmt_given(w1)}&nbsp;рад/с.")
        tv = [Column(f"v_{p}", sub("V", p), "м/с", digits=3) for p in pts_v]
        tv += [Column(f"w_{l.name}", sub("ω", l.name), "рад/с", digits=3) for l in _links(study)
               if not (rotary and l.name == mech.driver.link)]
        chunked_tables(s3, "Скорости точек и угловые скорости звеньев", k, tv, lead, "tab-v")
        if mech.driver.swing:
            _return_velocities(s3, study, lead)
        ta = [Column(f"a_{p}", sub("a", p), "м/с²", sig=4) for p in pts_v]
        ta += [Column(f"e_{l.name}", sub("ε", l.name), "рад/с²", sig=4) for l in _links(study)
               if not (rotary and l.name == mech.driver.link)]
        chunked_tables(s3, "Ускорения точек и угловые ускорения звеньев", k, ta, lead, "tab-a")

        # ----- plans at the chosen position
        lab = chosen_position(study)
        s4 = sec.subsection(f"Планы скоростей и ускорений для положения\u00a0{pos_no(study, lab)}", "sec-plans")
        row = k[k["pos"] == lab].iloc[0]
        vplan = PlanScene(lab, "velocity", landscape=True).draw(study)
        aplan = PlanScene(lab, "acceleration", landscape=True).draw(study)
        # the equations' aⁿ = ω²·l and a^k = 2·ω·V_r with ω and V_r as read off the velocity plan
        # (the values the acceleration plan is drawn from and §(ω = V/l) prints), not the analytic ones;
        # those ω and V_r are derived between the velocity and the acceleration equations
        vrow = read_velocities(row, study, vplan.mu)
        reads = []
        ws, es = _plan_formulas(s4, study, row, vrow, vplan, aplan, reads)
        vtab, atab = _with_reads(_once(vplan.table), reads, "omega"), _with_reads(_once(aplan.table), reads, "eps")
        # each plan follows the text that reads it (ГОСТ 7.32: a figure after its first mention), so
        # the text after a plan on a landscape page of its own can fill the page before it
        vectors.add_velocities(s4, study, vrow)
        if ws:
            slides = sum(f.symbolic.startswith("V") for f in ws)
            word = ("камня", "камней") if all(vectors.is_stone(study.mechanism, j)
                                              for j in study.mechanism.prismatic) else ("в поступательной паре", "в поступательных парах")
            rel = ("относительная скорость " + word[0] if slides == 1 else "относительные скорости " + word[1]) \
                if slides else ""
            # only relative velocities read (a tangent mechanism: the stone turns with the input link,
            # no other link turns): no «угловые скорости» announced that the formulas do not give
            found = (("найдена " if slides == 1 else "найдены ") + rel) if slides == len(ws) else \
                "найдены угловые скорости звеньев" + (" и " + rel if slides else "")
            s4.paragraph(f"По отрезкам плана скоростей (рисунок {ref('fig-vplan')}) {found}:")
            s4.formula(*ws)
        else:
            s4.paragraph(f"План скоростей построен на рисунке {ref('fig-vplan')}.")
        s4.figure(f"План скоростей для положения {pos_no(study, lab)} (μ<sub>v</sub> = {mu_text(vplan.mu)} м·с⁻¹/мм)",
                  vplan.svg, vplan.width_mm, id="fig-vplan", landscape=vplan.landscape)
        vectors.add_accelerations(s4, study, vrow)
        if es:
            s4.paragraph(f"По отрезкам плана ускорений (рисунок {ref('fig-aplan')}) найдены угловые ускорения звеньев:")
            s4.formula(*es)
        else:
            s4.paragraph(f"План ускорений построен на рисунке {ref('fig-aplan')}.")
        s4.figure(f"План ускорений для положения {pos_no(study, lab)} (μ<sub>a</sub> = {mu_text(aplan.mu)} м·с⁻²/мм)",
                  aplan.svg, aplan.width_mm, id="fig-aplan", landscape=aplan.landscape)
        cmp_cols = [Column("name", "Величина" if reads else "Вектор", fmt=_vec_name),
                    Column("mm", "Длина на плане", "мм", digits=1),
                    Column("graphic", "По плану", None, sig=4), Column("analytic", "Аналитически", None, sig=4),
                    Column("delta", "Расхождение", "%", digits=2)]
        s4.paragraph(f"Планы построены графически: известные векторы отложены отрезками, округлёнными до "
                     f"{fmt(READ_MM, digits=1)}&nbsp;мм, неизвестные найдены пересечением линий их направлений; "
                     f"отрезки построенных планов измерены с той же точностью (отрезки короче "
                     f"{fmt(MIN_MM, digits=0)}&nbsp;мм не сравниваются); сравнение с "
                     f"аналитическим решением — в таблицах {ref('tab-vplan')} и {ref('tab-aplan')}. Наибольшее "
                     f"расхождение: по скоростям {fmt_pct(vtab['delta'].max() / 100)}, по ускорениям "
                     f"{fmt_pct(atab['delta'].max() / 100)} (допускается до {fmt(PLAN_TOL_PCT, digits=0)}&nbsp;%)."
                     + _short_reads_text(vtab, vplan) + _short_reads_text(atab, aplan)
                     + _insets_text(vplan, "скоростей", "v", "м·с⁻¹/мм") + _insets_text(aplan, "ускорений", "a", "м·с⁻²/мм"))
        # the rows of ω and ε carry their unit (рад/с, рад/с²) after their name, the caption the vectors' one
        s4.table(f"Скорости по плану и аналитически (положение {pos_no(study, lab)}), м/с", cmp_cols, vtab, id="tab-vplan")
        s4.table(f"Ускорения по плану и аналитически (положение {pos_no(study, lab)}), м/с²", cmp_cols, atab, id="tab-aplan")

    # ----- kinematic diagrams
    if not study.has_cycle:        # [grid] cycle = false: single positions, no diagrams over the cycle
        return sec
    outputs = parallel_outputs(study)
    several = len(outputs) > 1
    s5 = sec.subsection("Кинематические диаграммы выходных звеньев" if several else
                        "Кинематические диаграммы выходного звена", "sec-diagrams")
    figs = ["fig-diagrams"] + [f"fig-diagrams-{k + 1}" for k in range(1, len(outputs))]
    if several:
        # groups hung on the input link in parallel (a V-compressor's two pistons): each has its output
        names = [str(o[3]) for o in outputs]
        hung = _hung_on_outputs(study, outputs)
        how = ("их группы присоединены параллельно, каждая ведёт своё звено" if not hung else
               "на каждое из них действуют рабочие нагрузки (" + "; ".join(
                   f"группа ({','.join(later.links)}) присоединена к звену {link} группы ({','.join(g.links)})"
                   for g, link, later in hung) + ")")
        s5.paragraph(f"Выходные звенья — {', '.join(names[:-1])} и {names[-1]}: {how}; диаграммы построены для "
                     f"каждого из них (рисунки {', '.join(ref(f) for f in figs[:-1])} и {ref(figs[-1])}).")
    main = output_quantity(study)[0]
    for out, fig_id in zip(outputs, figs):
        _output_diagrams(s5, study, out, fig_id, several, out[0] == main)
    flags = study.flags
    guides, guide_note = _guide_transmission(study)
    slides, slide_note = _slide_transmission(study)
    guides, guide_note = guides + slides, " ".join(t for t in (guide_note, slide_note) if t)
    if flags or guides:
        # the input's coordinate as the other tables count it (a crank's angle from the cycle's start)
        rows = [{"g": flag_group(study, c), "mu": v["min"],
                 "q": q_degrees(study, v["q_min"]) % 360.0 if rotary else v["q_min"]} for c, v in flags.items()]
        for r in guides:
            if r["q"] is not None:
                r["q"] = q_degrees(study, r["q"]) % 360.0 if rotary else r["q"]
        from .structure import decomposition
        order = [r["g"] for r in decomposition(study)[0]]
        rows = sorted(rows + guides, key=lambda r: order.index(r["g"]) if r["g"] in order else len(order))
        mdf = pd.DataFrame([{k: r[k] for k in ("g", "mu", "q")} for r in rows])
        triad = (" (у группы III класса — эквивалентный угол по её матрице Якоби)"
                 if any(g.klass >= 3 for g in study.structure.groups) else "")
        s5.paragraph(f"Наименьшие {'за цикл' if rotary else 'по ходу гидроцилиндра'} углы передачи движения в группах{triad} приведены в таблице {ref('tab-mu')}; "
                     "рекомендуемое значение — не менее 40°.")
        s5.table("Наименьшие углы передачи движения", [
            Column("g", "Группа"), Column("mu", "μ<sub>min</sub>", "град", fmt=_deg1),
            Column("q", qhead + " (μ<sub>min</sub>)", qunit,
                   fmt=(lambda x: "—" if x is None or x != x else (_turn1(x) if rotary else fmt(x, digits=3))))],
            mdf, id="tab-mu", note=guide_note or None)
        low = [r for r in rows if r["mu"] is not None and r["mu"] == r["mu"] and math.degrees(r["mu"]) < MU_MIN_DEG]
        if low:
            s5.paragraph(_low_mu_sentence(low, qhead, rotary))
    return sec


MU_MIN_DEG = 40.0    # the recommended least transmission angle of a linkage [1, 3]


def _low_mu_sentence(low: list[dict], qhead: str, rotary: bool) -> str:
    """Under the table of least transmission angles, where one is below 40°: «Наименьший угол передачи в
    группе (2,3) — 35,7° (при φ = 219,1°) — меньше рекомендуемого 40°: …» — the reader is told at once,
    not only in the conclusion (which says how to raise it)."""
    def where(r):
        if r["q"] is None or r["q"] != r["q"]:
            return ""
        at = f"{_turn1(r['q'])}°" if rotary else f"{fmt(r['q'], digits=3)}&nbsp;м"
        return f" (при {qhead}&nbsp;=&nbsp;{at})"
    one = len(low) == 1
    parts = ", ".join(f"{r['g']} — {_deg1(r['mu'])}°{where(r)}" for r in low)
    return (f"{'Наименьший угол передачи в группе' if one else 'Наименьшие углы передачи в группах'} {parts} — "
            f"меньше рекомендуемого {fmt(MU_MIN_DEG, digits=0)}°: {'в этом положении' if one else 'в этих положениях'} "
            "растут реакции в парах группы и возможно заклинивание; как увеличить угол передачи, сказано в "
            "заключении.")


ZERO_REL = 1e-12     # a column of a kinematic table this small against the table's largest value is zero


def zero_columns(df: pd.DataFrame, cols: list[Column]) -> tuple[list[Column], list[Column]]:
    """The columns of a kinematic table split into those printed and those identically zero over
    the table (|x| ≤ 10⁻¹² of the table's largest value, or exactly 0): y′ of a point moving along
    a horizontal line is 0 in every position, a column of zeros tells the reader nothing.  At least
    one column is kept."""
    peak = max((float(np.max(np.abs(df[c.key].to_numpy(dtype=float)))) for c in cols), default=0.0)
    zero = [c for c in cols if float(np.max(np.abs(df[c.key].to_numpy(dtype=float)))) <= ZERO_REL * peak]
    if len(zero) == len(cols):
        return cols, []
    return [c for c in cols if c not in zero], zero


def _zero_note(zero: list[Column]) -> str | None:
    """«y′<sub>D</sub> = 0 во всех положениях (в таблицу не включены).» under the table."""
    if not zero:
        return None
    names = ", ".join(c.header for c in zero)
    return (f"{names}&nbsp;=&nbsp;0 во всех положениях ("
            + ("в таблицу не включён" if len(zero) == 1 else "в таблицу не включены") + ").")


def _hung_on_outputs(study, outputs) -> list[tuple]:
    """(group, link, later group) for each output's group that a later group hangs on (the master
    rod of an articulated-rod compressor carries the articulated rod at its point E): such outputs
    are not «attached in parallel»."""
    mech = study.mechanism
    groups = [g for g in study.structure.groups if FRAME not in g.links and len(g.links) > 1]
    out_links = set()
    for col, *_ in outputs:
        pre, _, name = col.partition("_")
        out_links |= {j.links[1] for j in mech.prismatic if j.name == name} if pre == "s" else {name}
    hung = []
    for i, g in enumerate(groups):
        if not out_links & set(g.links):
            continue
        for later in groups[i + 1:]:
            link = next((a if a in g.links else b for j in mech.joints for a, b in [j.links]
                         if (a in g.links and b in later.links) or (b in g.links and a in later.links)), None)
            if link is not None:
                hung.append((g, link, later))
    return hung


def _guide_transmission(study) -> tuple[list[dict], str]:
    """Rows of the transmission-angle table for the ВПВ groups (a stone in a rotating кулиса) and
    the note that explains them. The stone presses on the кулиса along the guide's normal; the
    point of the кулиса under the stone moves perpendicular to its radius ρ from the кулиса's pivot.
    With e the distance from the pivot to the line the stone's pin travels along (parallel to the
    guide), the pressure angle is arcsin(e/ρ), so μ = 90° − arcsin(e/ρ) and its least value is at
    the least ρ (Артоболевский, гл. 4); e = 0 (the guide through the pivot): μ = 90° always."""
    mech = study.mechanism
    rows, told = [], []
    for key, fl in study.guide_flags.items():
        g = next(g for g in study.structure.groups if "_".join(g.links) == key)
        pri = next(mech.joints[j] for j in g.joints if mech.joints[j].kind == "P")
        pivot, pin = fl["points"]
        px, py = mech.link(pri.links[0]).points[pivot]
        dx, dy = math.cos(pri.angle), math.sin(pri.angle)
        e = abs(pri.offset - (dx * (py - pri.line_point[1]) - dy * (px - pri.line_point[0])))
        label = flag_group(study, 'mu_' + key)
        name = f"{label} {g.kind_ru}".strip()
        if e <= 1e-9 * mech.size() or fl["min"] <= e:
            if e <= 1e-9 * mech.size():
                rows.append({"g": label, "mu": math.pi / 2, "q": None, "key": key})
                if vectors.is_stone(mech, pri):
                    told.append(f"В группе {name} давление камня на кулису направлено по нормали к кулисе, а "
                                f"точка кулисы под камнем движется перпендикулярно её радиусу {pivot}{pin}, "
                                f"лежащему на оси кулисы: угол передачи равен 90° во всех положениях.")
                else:            # a piston rod in a rocking cylinder: no stone, the links by number
                    s_, g_ = pri.links[1], pri.links[0]
                    told.append(f"В группе {name} давление звена {s_} на звено {g_} в поступательной паре "
                                f"направлено по нормали к направляющей, а точка звена {g_}, совпадающая с "
                                f"точкой {pin}, движется перпендикулярно радиусу {pivot}{pin}, лежащему на оси "
                                f"направляющей: угол передачи равен 90° во всех положениях.")
            continue
        rows.append({"g": label, "mu": math.pi / 2 - math.asin(e / fl["min"]), "q": fl["q_min"], "key": key})
        told.append(f"В группе {name} угол передачи μ&nbsp;=&nbsp;90°&nbsp;−&nbsp;arcsin(<i>e</i>/ρ), где "
                    f"<i>e</i>&nbsp;=&nbsp;{fmt(e, sig=4)}&nbsp;м — расстояние от опоры {pivot} кулисы до линии "
                    f"движения шарнира {pin} по кулисе, ρ&nbsp;=&nbsp;{pivot}{pin}; наименьший — при "
                    f"наименьшем ρ&nbsp;=&nbsp;{fmt(fl['min'], sig=4)}&nbsp;м.")
    return rows, " ".join(told)


def _slide_transmission(study) -> tuple[list[dict], str]:
    """Rows of the transmission-angle table for the ПВП and ВПП groups (``study.slide_flags``:
    μ, the acute angle between the fixed guide of the driven slider and the guide of the group's
    other sliding pair) and the note that explains them."""
    rows, told = [], []
    for key, fl in study.slide_flags.items():
        g = next(g for g in study.structure.groups if "_".join(g.links) == key)
        fixed, other = fl["guides"]
        driven = fixed.links[1]
        pusher = next((l for l in other.links if l in g.links and l != driven), other.links[1])
        label = flag_group(study, "mu_" + key)
        name = f"{label} {g.kind_ru}".strip()
        const = fl["const"]
        rows.append({"g": label, "mu": fl["min"], "q": None if const else fl["q_min"], "key": key})
        told.append(f"В группе {name} звено {pusher} давит на звено {driven} по нормали к направляющей "
                    f"поступательной пары {other.links[0]}–{other.links[1]}, а звено {driven} движется вдоль "
                    "неподвижной направляющей: угол передачи равен углу между этими направляющими"
                    + (f", {_deg1(fl['min'])}° во всех положениях." if const else "."))
    return rows, " ".join(told)


def _sliding_transmission(study) -> list[tuple[str, float, str]]:
    """(«в группе (4,5)», μ_min in degrees, how to raise it) of each group with a sliding pair whose
    transmission angle is not a flag of the cycle (ВПВ: :func:`_guide_transmission`; ПВП, ВПП:
    :func:`_slide_transmission`), judged in the conclusion by the same rule μ_min ≥ 40°."""
    out = []
    for r in _guide_transmission(study)[0]:
        pivot, pin = study.guide_flags[r["key"]]["points"]
        out.append((flag_where(study, "mu_" + r["key"]), math.degrees(r["mu"]),
                    f"Угол передачи можно увеличить, уменьшив расстояние <i>e</i> от опоры {pivot} кулисы до линии "
                    f"движения шарнира {pin} или увеличив наименьшее расстояние {pivot}{pin} (повторить синтез с "
                    "ограничением μ ≥ 40°)"))
    for r in _slide_transmission(study)[0]:
        fixed, other = study.slide_flags[r["key"]]["guides"]
        out.append((flag_where(study, "mu_" + r["key"]), math.degrees(r["mu"]),
                    f"Угол передачи можно увеличить, изменив наклон направляющей пары {other.links[0]}–"
                    f"{other.links[1]} или неподвижной направляющей звена {fixed.links[1]} так, чтобы в этих "
                    "положениях угол между ними был ближе к прямому (повторить синтез с ограничением μ ≥ 40°)"))
    return out


def _turn(q: float) -> str:
    """A crank angle from the start of the cycle in [0°, 360°) to 0,1° (the end of the cycle, 360°,
    is the start position 0°)."""
    d = round(math.degrees(q) % 360.0, 1)
    return fmt(0.0 if d >= 360.0 else d, digits=1)


def _deg(x, digits: int = 2) -> str:
    """A link's angle in degrees reduced to [0°, 360°), as it is measured on the drawing."""
    v = math.degrees(float(x)) % 360.0
    return fmt(0.0 if round(v, digits) >= 360.0 else v, digits=digits)


def _deg1(x) -> str:
    """An angle to 0,1° (the transmission angle and the crank angle, as the conclusion and the
    position tables print them)."""
    return _deg(x, 1)


def _turn1(deg: float) -> str:
    """A crank angle already in degrees from the cycle's start (:func:`q_degrees`) to 0,1°, in
    [0°, 360°) as the position tables count it (not through :func:`_deg1`, which takes radians)."""
    v = float(deg) % 360.0
    return fmt(0.0 if round(v, 1) >= 360.0 else v, digits=1)


def swing_strokes_text(study) -> str:
    """The forward and return strokes of an input rocker: the output's reversals inside the swing,
    the time of a stroke, why the tables show the forward stroke only, and K = 1."""
    d = study.mechanism.driver
    sc = study.scalars
    parts = []
    revs = [sc[f"output_q_reversal_{i + 1}"] for i in range(sc["output_reversals"])]
    if revs:
        where = ", ".join(f"{fmt(math.degrees(r), digits=2)}°" for r in revs)
        parts.append(f"Внутри диапазона качания выходное звено останавливается и меняет направление движения "
                     f"при φ&nbsp;=&nbsp;{where} (первая передаточная функция обращается в нуль; найдено "
                     f"решением уравнения по точному положению механизма), поэтому его размах за ход больше "
                     f"разности значений в крайних положениях входного звена.")
    parts.append("Цикл состоит из прямого и обратного ходов входного звена. Положения звеньев и аналоги скоростей и "
                 "ускорений зависят только от угла φ и на обоих ходах одинаковы; при обратном ходе с той же по модулю "
                 "угловой скоростью (ω<sub>1</sub> заменяется на −ω<sub>1</sub>) скорости всех точек и звеньев "
                 "v&nbsp;=&nbsp;ω<sub>1</sub>x′ меняют знак, а ускорения a&nbsp;=&nbsp;ω<sub>1</sub><sup>2</sup>x″ не меняются. "
                 "Поэтому таблицы положений, аналогов и ускорений, диаграммы и силовой расчёт приведены для прямого "
                 f"хода, угловые скорости на обратном ходе — в таблице {ref('tab-v-return')}, оба хода — в таблице "
                 f"{ref('tab-strokes')}. В крайних положениях скорость входного "
                 "звена меняет знак мгновенно (принятая идеализация привода); действительный привод разгоняет и "
                 "тормозит звено за конечное время, что добавляет силы инерции вблизи крайних положений.")
    if d.omega is not None:
        parts.append(f"Время одного хода t&nbsp;=&nbsp;(φ<sub>max</sub>&nbsp;−&nbsp;φ<sub>min</sub>)/ω<sub>1</sub>&nbsp;=&nbsp;"
                     f"{fmt(sc['t_stroke'], sig=4)}&nbsp;с, время цикла {fmt(2 * sc['t_stroke'], sig=4)}&nbsp;с; прямой и "
                     "обратный ходы длятся одинаково, коэффициент изменения средней скорости <i>K</i>&nbsp;=&nbsp;1.")
    return " ".join(parts)


def _return_velocities(sec: Section, study, lead: list[Column]) -> None:
    """An input rocker's return stroke: the positions in the order they are passed, the angular
    velocities of the links (and the output slider's velocity) with their signs."""
    mech = study.mechanism
    kr = study.kinematics_return
    cols = [Column(f"w_{l.name}", sub("ω", l.name), "рад/с", digits=3) for l in _links(study)]
    cols += [Column(f"vs_{j.name}", sub("V", j.point), "м/с", digits=3) for j in mech.prismatic if j.links[0] == FRAME]
    lo, hi = (fmt(math.degrees(x), digits=1) for x in mech.driver.q_range)
    sec.paragraph(f"На обратном ходе (φ от {hi}° до {lo}°) входное коромысло вращается с угловой "
                  f"скоростью −ω<sub>1</sub>; модули скоростей точек и все ускорения те же, что на прямом ходе, "
                  f"угловые скорости звеньев и скорости ползунов меняют знак (таблица {ref('tab-v-return')}).")
    chunked_tables(sec, "Угловые скорости звеньев на обратном ходе входного коромысла", kr, cols, lead, "tab-v-return")


def _strokes_table(sec: Section, study, s_col: str) -> None:
    """The forward and return strokes of an input rocker: the input's angles, the output at the
    start and end, its range and path, the time and the output's mean speed."""
    df = study.strokes.copy()
    df["name"] = df["stroke"].map({"forward": "прямой", "return": "обратный"})
    ang = s_col.startswith("phi_")
    conv = math.degrees if ang else (lambda x: x)
    for c in ("s_from", "s_to", "s_range", "s_path"):
        df[c] = df[c].map(conv)
    unit = "град" if ang else "м"
    sym = sub("φ", s_col[4:]) if ang else sub("s", s_col.split("_", 1)[1])
    cols = [Column("name", "Ход"), Column("q_from_deg", "φ<sub>нач</sub>", "град", digits=1),
            Column("q_to_deg", "φ<sub>кон</sub>", "град", digits=1),
            Column("s_from", f"{sym} в начале", unit, digits=2 if ang else 4),
            Column("s_to", f"{sym} в конце", unit, digits=2 if ang else 4),
            Column("s_path", "путь выходного звена", unit, digits=2 if ang else 4)]
    if "t" in df:
        df["v_mean"] = df["v_mean"].map(conv)
        cols += [Column("t", "<i>t</i>", "с", sig=4),
                 Column("v_mean", "средняя скорость выхода", unit + "/с", sig=4)]
    sec.table("Прямой и обратный ходы входного коромысла", cols, df, id="tab-strokes")


def _once(tab: pd.DataFrame) -> pd.DataFrame:
    """The comparison table without a component that is the absolute vector itself (V_AO of a
    crank about a fixed centre is V_A, a^n_AO is a_A when ε₁ = 0): one row per vector on the plan."""
    if tab.empty:
        return tab
    absolute = {(m, round(a, 9)) for m, a, k in zip(tab["mm"], tab["analytic"], tab["kind"]) if k == "abs"}
    keep = [k == "abs" or (m, round(a, 9)) not in absolute for m, a, k in zip(tab["mm"], tab["analytic"], tab["kind"])]
    return tab[keep].reset_index(drop=True)


def _insets_text(drawing, what: str, sym: str, unit: str) -> str:
    """The sentence naming a plan's enlarged views (ГОСТ 2.305 выносные элементы) with their
    scales μ/k; empty when the plan has none."""
    if not drawing.insets:
        return ""
    parts = [f"{i.mark} (<span class=\"nowrap\">μ<sub>{sym}</sub>/{mu_text(i.k)}</span> = {mu_text(drawing.mu / i.k)}&nbsp;{unit})"
             for i in drawing.insets]
    what_el = "выносным элементом" if len(parts) == 1 else "выносными элементами"
    return (f" Короткие векторы и близко лежащие точки плана {what} обведены и показаны крупнее "
            f"{what_el} {', '.join(parts[:-1]) + ' и ' + parts[-1] if len(parts) > 1 else parts[0]}.")


def _read_symbol(name: str) -> Markup:
    """ω₃ or ε₃ of a read row's name (:func:`_add_read`)."""
    kind, link = name.split(":")[:2]
    return Markup("{}<sub>{}</sub>").format("ω" if kind == "omega" else "ε", link)


def _vec_name(name: str) -> Markup:
    """V_BA → V<sub>BA</sub>; a^n_BA → a<sup>n</sup><sub>BA</sub>; a read ω or ε (:func:`_add_read`)
    → «ω₃ = V_KC/l_CK, рад/с», «ε₃ = a^τ_KC/l_CK, рад/с²» (the unit of the row: the caption gives the vectors')."""
    if name.startswith(("omega:", "eps:")):
        kind, _, seg, rq = name.split(":")
        return Markup("{} = {}/<i>l</i><sub>{}</sub>, {}").format(_read_symbol(name), _vec_name(seg), rq,
                                                                  "рад/с" if kind == "omega" else "рад/с²")
    if "^" in name:
        head, rest = name.split("^", 1)
        sup_, _, idx = rest.partition("_")
        return Markup("<i>{}</i><sup>{}</sup><sub>{}</sub>").format(head, sup_, idx)
    head, _, idx = name.partition("_")
    return Markup("<i>{}</i><sub>{}</sub>").format(head, idx)


def _plan_formulas(sec: Section, study, row, vrow, vplan, aplan,
                   reads: list | None = None) -> tuple[list[Formula], list[Formula]]:
    """The paragraph on the kinds of vector equations, and the formulas with numbers at the chosen
    position: (ω of the links and the stones' relative velocities V_r read off the velocity plan
    — ``vrow``, what the acceleration equations use —, ε of the links read off the acceleration plan).
    ``reads`` (if given) gets one row per ω and ε so found, in the form of :func:`scenes.plans.measure`'s
    table (kind "omega"/"eps", the segment read and its length, the link's length), for the
    comparison tables: ω = V/l and ε = a^τ/l against the analytic ω, ε of the kinematics table."""
    mech = study.mechanism
    d = mech.driver
    # the crank's V_A = ω₁·l_OA and a_A = ω₁²·l_OA are written with the vector equations (vectors.add_velocities, add_accelerations),
    # and so is a^k = 2ω·V_r of a stone on a rotating guide; here the angular velocities and
    # accelerations read off the constructed plans, each result the quotient of the printed plan
    # value and length (ω = V/l of the same numbers, not the analytic ω next to a drawn V)
    fs, es = [], []
    aseg = {s.name: s for s in aplan.plan.segments}
    # a link's ω from the relative velocity its own group's equations give (ω₃ = V_BC/l_CB of the
    # rocker of group (2,3)), not from a point of a later group's pair found from it (V_DC)
    # (the choice is plans.omega_segment, the one the acceleration plan's ω are read from too)
    rank = group_rank(study)
    full = []       # the plans as constructed, before the similarity points' components are dropped

    def constructed():
        if not full:
            lab_ = row["pos"]
            full.append(PlanScene(lab_, "velocity", mu_v=vplan.mu).construct(study)[0])
            full.append({s.name: s for s in PlanScene(lab_, "acceleration", mu_v=vplan.mu, mu_a=aplan.mu)
                         .construct(study)[0].segments})
        return full
    # a slider with points of its own on a moving guide (a piston rod in a rocking cylinder) turns
    # with the guide: ω and ε written as the guide's, not read a second time (plans.measured_omegas)
    twins = {j.links[1]: j.links[0] for j in mech.prismatic
             if j.links[0] != FRAME and len(mech.link(j.links[1]).points) > 1}
    w_read, e_read = {}, {}
    for link in mech.moving:
        if d.rotary and link.name == d.link or link.name in twins:
            continue
        s0 = omega_segment(vplan.plan, mech, link.name, rank)
        if s0 is None:
            # a link whose points besides its pairs' are only found by similarity (a rocking
            # cylinder: its pivot C, the rod's point under it, its end K): its ω is read, as
            # plans.measured_omegas reads it for the acceleration plan, from the segment the
            # construction drew to such a point (V_KC) — not left out while aⁿ = ω²·l uses it
            s0 = omega_segment(constructed()[0], mech, link.name, rank)
        if s0 is None or abs(row[f"w_{link.name}"]) < 1e-12 and float(np.abs(study.cycle["wq_" + link.name]).max()) < 1e-12:
            continue
        q_, r_ = s0.end, s0.start
        lq = math.hypot(row[f"x_{q_}"] - row[f"x_{r_}"], row[f"y_{q_}"] - row[f"y_{r_}"])
        Q, R = tex_point(q_), tex_point(r_)
        # the segment as measured on the drawing (to READ_MM, as in the table «по плану» and as
        # the acceleration plan's normal terms use it: plans.measured_omegas), not the construction
        v_read = drawn(s0.length, vplan.mu)
        fs.append(_rate_formula(r"\omega", "V", "рад/с", link.name, Q, R, v_read, lq))
        w_read[link.name] = v_read / lq
        _add_read(reads, "omega", link.name, s0, v_read, vplan.mu, lq, row[f"w_{link.name}"], q_, r_)
        tn = aseg.get(f"a^τ_{q_}{r_}") or (constructed()[1].get(f"a^τ_{q_}{r_}") if full else None)
        if tn is not None:
            a_read = drawn(tn.length, aplan.mu)
            es.append(_rate_formula(r"\varepsilon", r"a^{\tau}", "рад/с²", link.name, Q, R, a_read, lq))
            e_read[link.name] = a_read / lq
            _add_read(reads, "eps", link.name, tn, a_read, aplan.mu, lq, row[f"e_{link.name}"], q_, r_)
    for s_, g_ in twins.items():
        if g_ in w_read:
            fs.append(Formula(rf"\omega_{{{s_}}} = \omega_{{{g_}}}", None, tex_num(w_read[g_], sig=4, unit="рад/с")))
        if g_ in e_read:
            es.append(Formula(rf"\varepsilon_{{{s_}}} = \varepsilon_{{{g_}}}", None,
                              tex_num(e_read[g_], sig=4, unit="рад/с²")))
    # only what the mechanism has: a slider on the frame, a stone on a moving guide (Coriolis)
    kinds = ["для точки, общей двум звеньям, — относительное вращательное движение вокруг соседних шарниров"]
    if any(j.links[0] == FRAME for j in mech.prismatic):
        kinds.append("для ползуна на неподвижной направляющей — скорость и ускорение вдоль направляющей")
    moving = [j for j in mech.prismatic if j.links[0] != FRAME]
    if any(_rotates(study, j.links[0]) for j in moving):
        kinds.append(("для камня на вращающейся направляющей" if all(vectors.is_stone(mech, j) for j in moving
                                                                     if _rotates(study, j.links[0]))
                      else "для звена, скользящего по вращающейся направляющей,")
                     + " — переносное и относительное движение с кориолисовым ускорением")
    if mech.driving_pair() is not None:
        kinds.append("для штока гидроцилиндра — переносное движение вместе с качающимся цилиндром и "
                     "относительное вдоль его оси с заданной скоростью, с кориолисовым ускорением")
    if any(not _rotates(study, j.links[0]) for j in moving):
        kinds.append("для ползуна на поступательно движущейся направляющей — переносное и относительное "
                     "движение без кориолисова ускорения")
    for j in moving:                 # a^k = 2·ω·V_r: the stone's V_r as read off the velocity plan
        if _rotates(study, j.links[0]) and f"vs_{j.name}" in vrow:
            Ps, Pg = vectors._pt(j.point, j.links[1]), vectors._pt(j.point, j.links[0])
            fs.append(Formula(rf"V_{{{Ps}{Pg}}}", None, tex_num(abs(float(vrow[f"vs_{j.name}"])), sig=4, unit="м/с")))
    sec.paragraph("Скорости и ускорения определены построением планов по векторным уравнениям групп Ассура ("
                  + "; ".join(kinds) + ").")
    return fs, es


PLAN_TOL_PCT = 5.0      # the discrepancy a graphical plan is allowed against the analytic solution, %


def _with_reads(tab: pd.DataFrame, reads: list, kind: str) -> pd.DataFrame:
    """The comparison table of a plan with the ω (``kind`` "omega") or ε ("eps") read off it appended."""
    rows = [r for r in reads if r["kind"] == kind]
    return pd.concat([tab, pd.DataFrame(rows)], ignore_index=True) if rows else tab


def _short_reads_text(tab: pd.DataFrame, drawing) -> str:
    """The sentence for the rows of a comparison table whose discrepancy exceeds PLAN_TOL_PCT: the
    segment each was read from is short, and its absolute error in mm (a few tenths — what laying
    off and reading to READ_MM give) is a large share of it; the plan's scale is set by the page
    (its longest segment named), so the accuracy is that of the drawing. Empty when none exceeds."""
    over = tab[tab["delta"] > PLAN_TOL_PCT] if not tab.empty else tab
    if over.empty:
        return ""
    longest = max(drawing.plan.segments, key=lambda s_: s_.length)
    parts = []
    for r in over.itertuples():
        seg = r.seg if isinstance(getattr(r, "seg", None), str) else r.name
        exact_mm = r.mm_exact if r.kind in ("omega", "eps") else r.analytic / drawing.mu
        parts.append(Markup("{} ({}): отрезок {} длиной {}&nbsp;мм отличается от точной длины {}&nbsp;мм на {}&nbsp;мм").format(
            _read_symbol(r.name) if r.kind in ("omega", "eps") else _vec_name(r.name),
            fmt_pct(r.delta / 100), _vec_name(seg), fmt(r.mm, digits=1), fmt(exact_mm, digits=2),
            fmt(abs(r.mm - exact_mm), digits=2)))
    # a str like the paragraph it ends (Markup + str would escape the paragraph's own markup)
    return str(Markup(" Больше допустимого расхождение ") + Markup("; ").join(parts)
               + Markup(" — ошибка построения по векторам, отложенным с точностью {}&nbsp;мм, для короткого отрезка "
                        "велика в процентах, а масштаб плана выбран по размерам страницы (его наибольший отрезок {} — "
                        "{}&nbsp;мм): точность {} ограничена чертежом.").format(
                   fmt(READ_MM, digits=1), _vec_name(longest.name), fmt(longest.length / drawing.mu, digits=0),
                   "этого значения" if len(parts) == 1 else "этих значений"))


def _rate_formula(rate: str, vector: str, unit: str, link: str, Q: str, R: str, value: float,
                  l: float) -> Formula:
    """ω_k = V_QR/l_RQ or ε_k = a^τ_QR/l_RQ with the segment read off the plan (``value``) and
    the link's length (Артоболевский, гл. 3: the relative vector over the distance)."""
    return Formula(rf"{rate}_{{{link}}} = \frac{{{vector}_{{{Q}{R}}}}}{{l_{{{R}{Q}}}}}",
                   rf"\frac{{{tex_num(value, sig=4)}}}{{{tex_num(l, digits=4)}}}",
                   tex_num(value / l, sig=4, unit=unit))


def _add_read(reads: list | None, kind: str, link: str, seg, value: float, mu: float, l: float,
              analytic: float, q: str, r: str) -> None:
    """One ω = V_QR/l_RQ or ε = a^τ_QR/l_RQ read off a plan as a row of the comparison table, when
    its segment is long enough to be compared (MIN_MM, the rule the tables state)."""
    if reads is None or seg.length / mu < MIN_MM or abs(analytic) < 1e-12:
        return
    graph = value / l
    reads.append(dict(name=f"{kind}:{link}:{seg.name}:{r}{q}", kind=kind, link=link, seg=seg.name,
                      mm=round(seg.length / mu / READ_MM) * READ_MM, mm_exact=abs(analytic) * l / mu,
                      analytic=abs(analytic), graphic=graph, delta=abs(graph - abs(analytic)) / abs(analytic) * 100.0))


def _output_diagrams(s5: Section, study, out: tuple, fig_id: str, several: bool, main: bool) -> None:
    """The kinematic diagrams of one output (``out``: an ``output_quantity`` tuple) with their
    text: stroke, extreme positions, origin of the displacement. ``main``: the output the rest of
    the note follows (the working stroke is judged for it)."""
    diag = OutputDiagrams(out).draw(study)
    s_col, v_col, a_col, title = out
    mech = study.mechanism
    rotary = mech.driver.rotary
    cyc = study.cycle
    s = cyc[s_col].to_numpy()
    stroke = float(s.max() - s.min())
    n = output_index(study, s_col)
    _, i0 = output_displacement(study, s_col)
    q0 = cyc["q"].iloc[i0]
    at = (f"φ&nbsp;=&nbsp;{fmt(math.degrees(q0), digits=1)}°" if mech.driver.swing
          else f"φ&nbsp;=&nbsp;{_turn(q0 - study.grid.start)}°" if rotary
          else f"<i>S</i>&nbsp;=&nbsp;{fmt(q0, digits=4)}&nbsp;м")
    if s_col.startswith("phi_"):
        s5.paragraph(f"Выходное звено — {title}; размах качания {fmt(math.degrees(stroke), digits=2)}° "
                     f"(рисунок {ref(fig_id)}).")
        origin = (f"Угол поворота ψ{n}&nbsp;=&nbsp;φ{n}&nbsp;−&nbsp;φ{n}<sub>min</sub> на диаграмме отсчитывается "
                  f"от крайнего положения при {at}, угловые скорость и ускорение — в направлении отсчёта угла φ{n}.")
    else:
        s5.paragraph(f"Выходное звено — {title}; ход <i>H</i>&nbsp;=&nbsp;{fmt(stroke, digits=4)}&nbsp;м "
                     f"(рисунок {ref(fig_id)}).")
        origin = (f"Перемещение <i>s</i>{n} на диаграмме отсчитывается от крайнего положения при {at} "
                  f"(0&nbsp;≤&nbsp;<i>s</i>{n}&nbsp;≤&nbsp;<i>H</i>), скорость и ускорение — в том же направлении.")
    if mech.driver.swing:
        if main:
            s5.paragraph(swing_strokes_text(study))
            _strokes_table(s5, study, s_col)
    elif rotary:
        q_min, q_max, work, K = _strokes(study, s, exact=main)
        s5.paragraph(f"Крайние положения выходного звена соответствуют углам поворота кривошипа "
                     f"{_turn(q_min - study.grid.start)}° и "
                     f"{_turn(q_max - study.grid.start)}°; угол перекрытия "
                     f"θ&nbsp;=&nbsp;{fmt(abs(180 - work), digits=1)}°, коэффициент изменения средней скорости "
                     f"<i>K</i>&nbsp;=&nbsp;{fmt(K, digits=3)}."
                     + _quick_return(work, K, _working_stroke(study) if main else None, mech.driver.direction,
                                     _return_idle(study) if main else True, _working_share(study) if main else None))
    s5.paragraph(origin)
    s5.figure(f"Кинематические диаграммы выходного звена: {title}" if several else
              "Кинематические диаграммы выходного звена", diag.svg, diag.width_mm, id=fig_id)


def output_v_limit(study) -> float | None:
    """``[report] output_v_limit``: the admissible speed of the output link given by the case (a
    slider's m/s, a rocker's rad/s), or None."""
    from ...case import units as U
    s_col = output_quantity(study)[0]
    dim = U.ANGULAR_VELOCITY if s_col.startswith("phi_") else U.VELOCITY
    return study.root.table("report").quantity("output_v_limit", dim, study.params, positive=True)


def _speed_verdict(study) -> list[str]:
    """The output's largest speed over the cycle against the admissible one the case gives
    (``output_v_limit``); since every speed of the mechanism is proportional to ω₁, an exceeded
    limit is met by ω₁ ≤ ω₁·[v]/v_max. Nothing when the case gives no limit (no invented norm)."""
    lim = output_v_limit(study)
    d = study.mechanism.driver
    if lim is None or d.omega is None or not d.rotary or d.swing:
        return []
    s_col, _, _, _ = output_quantity(study)
    pre, _, name = s_col.partition("_")
    vcol = {"phi": "w", "s": "vs", "x": "vx", "y": "vy"}[pre] + "_" + name
    vmax = float(study.cycle[vcol].abs().max())
    unit = "рад/с" if pre == "phi" else "м/с"
    what = "угловая скорость выходного звена" if pre == "phi" else "скорость выходного звена"
    # a slider's largest speed is stated in the line before (conclusion_lines)
    head = "Эта скорость" if pre == "s" else f"Наибольшая {what} {fmt(vmax, sig=3)}&nbsp;{unit}"
    limit = f"[<i>v</i>]&nbsp;=&nbsp;{fmt_given(lim)}&nbsp;{unit}"
    if vmax <= lim:
        return [f"{head} не превышает допускаемой {limit} ({fmt(100 * vmax / lim, digits=0)}&nbsp;% от неё)."]
    w = abs(float(d.omega))
    return [f"{head} превышает допускаемую {limit} в {fmt(vmax / lim, sig=3)} раза: все скорости механизма "
            f"пропорциональны ω<sub>1</sub>, поэтому угловую скорость {input_word(d, 'gen')} следует уменьшить до "
            f"ω<sub>1</sub>&nbsp;≤&nbsp;{fmt(w * lim / vmax, sig=3)}&nbsp;рад/с (или изменить размеры механизма)."]


def _speed_lines(study) -> list[str]:
    """The speeds a designer weighs, stated with their values: the mean speeds of the output's two
    strokes v = H·ω₁/φ (φ — the crank's turn over the stroke, study ``output_v_work`` /
    ``output_v_return``) and the peripheral speed of the crank pin v_A = ω₁·l_OA.  The case gives
    no admissible values for them, so they are stated, not judged."""
    d = study.mechanism.driver
    if d.omega is None or d.swing or not d.rotary:
        return []
    sc = study.scalars
    out = []
    if "output_v_work" in sc and len(parallel_outputs(study)) == 1:   # (several: each output's own line)
        ang = str(sc["output"]).startswith("phi_")
        unit = "рад/с" if ang else "м/с"
        what = "Средняя угловая скорость выходного звена" if ang else "Средняя скорость выходного звена"
        slow, fast = fmt(sc['output_v_work'], sig=3), fmt(sc['output_v_return'], sig=3)
        K = f"(коэффициент изменения средней скорости <i>K</i>&nbsp;=&nbsp;{fmt(sc['output_K'], digits=3)})"
        if slow == fast:        # K = 1: no slow and fast stroke to tell apart
            out.append(f"{what} на прямом и обратном ходах одинакова: {slow}&nbsp;{unit} {K}.")
        elif sc["output_K"] <= QUICK_RETURN_K:     # as §2.5: no quick return to speak of
            out.append(f"{what} на прямом и обратном ходах практически одинакова: {slow} и {fast}&nbsp;{unit} {K}.")
        else:
            out.append(f"{what} на медленном ходе (больший угол поворота {input_word(d, 'gen')}) "
                       f"{slow}&nbsp;{unit}, на быстром — {fast}&nbsp;{unit} {K}.")
            share = _working_share(study)
            if _working_stroke(study) == "fast" and not (share is not None and share < SHORT_LOAD_SHARE):
                other = "по часовой стрелке" if d.direction > 0 else "против часовой стрелки"
                out.append(f"При заданном направлении вращения {input_word(d, 'gen')} рабочий ход выходного звена — "
                           f"быстрый (подраздел {ref('sec-diagrams')}); при вращении {other} рабочим станет "
                           f"медленный ход, а {'холостой' if _return_idle(study) else 'обратный'} будет выполняться в {fmt(sc['output_K'], digits=2)} раза "
                           f"быстрее — такое направление вращения предпочтительнее.")
    pin = study.mechanism.crank_pin()
    col = "v_" + str(pin)
    if pin and col in study.cycle:
        # a pin that is a joint is a «шарнир»; the end of a driving slotted link (no joint there) a point
        joint = any(j.point == pin and j.kind == "R" for j in study.mechanism.joints)
        out.append(Markup("Окружная скорость {4} {0} {1} <i>v</i><sub>{0}</sub>&nbsp;=&nbsp;ω<sub>1</sub>"
                          "<i>l</i><sub>{2}{0}</sub>&nbsp;=&nbsp;{3}&nbsp;м/с.").format(
            pin, input_word(d, "gen"), d.center, fmt(float(study.cycle[col].abs().max()), sig=3),
            "шарнира" if joint else "точки"))
    return out


def conclusion_lines(study) -> list[str]:
    """Key kinematic results for the ЗАКЛЮЧЕНИЕ."""
    out = []
    s_col, v_col, a_col, title = output_quantity(study)
    if not study.has_cycle:
        return [f"Механизм рассчитан в {len(study.kinematics)} заданных положениях (цикл не рассчитывается: "
                f"механизм собирается не во всех его положениях); положения, скорости и ускорения — в таблицах "
                f"раздела {ref('sec-kinematics')}."]
    cyc = study.cycle
    s = cyc[s_col]
    outputs = parallel_outputs(study)
    if len(outputs) > 1:
        # several outputs (groups in parallel): each with its stroke and largest speed and acceleration
        for o_s, _, _, o_title in outputs:
            line = f"Выходное звено — {o_title}; его ход <i>H</i>&nbsp;=&nbsp;{fmt(np.ptp(cyc[o_s]), digits=4)}&nbsp;м" \
                if o_s.startswith("s_") else \
                f"Выходное звено — {o_title}; размах его качания {fmt(math.degrees(np.ptp(np.unwrap(cyc[o_s]))), digits=2)}°"
            w = study.mechanism.driver.omega
            if w is not None and o_s.startswith("s_"):
                line += (f", наибольшая скорость {fmt(cyc['vs_' + o_s[2:]].abs().max(), digits=3)}&nbsp;м/с, "
                         f"наибольшее ускорение {fmt(cyc['as_' + o_s[2:]].abs().max(), sig=4)}&nbsp;м/с²")
                if study.mechanism.driver.rotary and not study.mechanism.driver.swing:
                    # mean speeds of its two strokes v = H·ω₁/φ (φ — the crank's turn over the stroke)
                    _, _, fast_deg, K = _strokes(study, cyc[o_s].to_numpy(), exact=o_s == s_col)
                    H = float(np.ptp(cyc[o_s]))
                    slow = fmt(H * abs(w) / math.radians(360.0 - fast_deg), sig=3)
                    fast = fmt(H * abs(w) / math.radians(fast_deg), sig=3)
                    line += (f"; средняя скорость на прямом и обратном ходах одинакова: {slow}&nbsp;м/с" if slow == fast else
                             f"; средняя скорость на медленном ходе {slow}&nbsp;м/с, на быстром — {fast}&nbsp;м/с "
                             f"(<i>K</i>&nbsp;=&nbsp;{fmt(K, digits=3)})")
            out.append(line + ".")
    elif s_col.startswith("phi_"):
        out.append(f"Выходное звено — {title}; размах его качания {fmt(math.degrees(s.max() - s.min()), digits=2)}°.")
    else:
        out.append(f"Выходное звено — {title}; его ход <i>H</i>&nbsp;=&nbsp;{fmt(s.max() - s.min(), digits=4)}&nbsp;м.")
    if study.mechanism.driver.omega is not None and s_col.startswith("s_") and len(outputs) == 1:
        n = s_col[2:]
        out.append(f"Наибольшая скорость выходного звена {fmt(cyc['vs_' + n].abs().max(), digits=3)}&nbsp;м/с, "
                   f"наибольшее ускорение {fmt(cyc['as_' + n].abs().max(), sig=4)}&nbsp;м/с².")
    out += _speed_verdict(study)
    out += _speed_lines(study)
    fine = []       # groups whose μ_min ≥ 40°: one sentence for all of them, not one each
    low = []        # groups below 40°
    for c, v in study.flags.items():
        mu = math.degrees(v["min"])
        if mu >= 40:
            fine.append(f"{flag_where(study, c)} {fmt(mu, digits=1)}°")
            continue
        low.append(c)
        crank = _turning_link(study, c)
        note = (" — меньше допускаемого 40°: в этих положениях растут реакции в парах группы и опасно "
                "заклинивание. " + (
                    f"Звено {crank} группы совершает полный оборот (ведомый кривошип), крайних положений у "
                    f"него нет: угол передачи наименьший, когда {_attached_to(study, c)} и "
                    "стойка лежат на одной прямой. Увеличить его можно, уменьшив расстояние между опорами "
                    "по сравнению с длинами кривошипов или приблизив угол между шатуном и ведомым "
                    "кривошипом в этих положениях к прямому подбором их длин (повторить расчёт с "
                    "ограничением μ ≥ 40°)" if crank else _slider_advice(study, c) or
                    "Угол передачи можно увеличить, удлинив шатун группы или сместив опору выходного звена "
                    "так, чтобы в крайних положениях шатун был ближе к перпендикуляру к выходному звену "
                    "(повторить синтез с ограничением μ ≥ 40°)"))
        out.append(f"Наименьший угол передачи {flag_where(study, c)} — {fmt(mu, digits=1)}°{note}.")
    for where, mu, advice in _sliding_transmission(study):
        if mu >= 40:
            fine.append(f"{where} {fmt(mu, digits=1)}°")
            continue
        low.append(where)
        out.append(f"Наименьший угол передачи {where} — {fmt(mu, digits=1)}° — меньше допускаемого 40°: в этих "
                   f"положениях растут реакции в парах группы и опасно заклинивание. {advice}.")
    if fine:
        from .structure import decomposition       # the groups in the order of chapter 1
        order = [r["g"] for r in decomposition(study)[0]]
        fine.sort(key=lambda t: next((i for i, g in enumerate(order) if f"{g} " in t), len(order)))
        # «работоспособен» only of a mechanism no group of which is below 40°
        out.append(("Наименьший угол передачи (" if len(fine) == 1 else "Наименьшие углы передачи (")
                   + ", ".join(fine) + ") не меньше допускаемого 40°"
                   + (", механизм работоспособен без заклинивания." if not low else
                      f"; {'в этой группе' if len(fine) == 1 else 'в этих группах'} заклинивания нет."))
    for g, fl in study.guide_flags.items():
        if fl["singular"]:
            pivot, pin = fl["points"]
            out.append(f"Группа ({g.replace('_', ',')}) проходит особое положение: шарнир {pin} проходит через "
                       f"ось кулисы {pivot}, аналог угловой скорости кулисы неограниченно растёт; в этом "
                       "положении механизм неработоспособен — нужно изменить размеры (например, длину "
                       "кривошипа или расстояние между опорами).")
    return out
