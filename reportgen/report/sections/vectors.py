"""The vector equations of the graphic-analytic method, written out group by group for the
chosen position (Артоболевский И. И., «Теория механизмов и машин», гл. 3; Попов С. А.,
Тимофеев Г. А., «Курсовое проектирование по ТММ», кинематический анализ).

For every link of a group the equation of its joint points relative to the point by which the
link is attached (its external pair, else its first pair):

* velocities  V̄_B = V̄_A + V̄_BA,  V̄_BA ⟂ AB,  V_BA = ω·l_AB;
* accelerations  ā_B = ā_A + āⁿ_BA + ā^τ_BA,  aⁿ_BA = ω²·l_AB directed from B to A,
  a^τ_BA = ε·l_AB ⟂ AB;

for a slider P of link s on the guide of link g (point P_g of the guide under it):

* V̄_{P_s} = V̄_{P_g} + V̄_{P_sP_g},  V̄_{P_sP_g} ∥ guide;
* ā_{P_s} = ā_{P_g} + ā^k + ā^r,  a^k = 2·ω_g·V_{P_sP_g} (V̄_r turned by 90° in the sense of ω_g),
  ā^r ∥ guide — the Coriolis term only where the guide rotates (on the frame: ā_P ∥ guide);
  ā_{P_g} = ā_G + āⁿ_{P_gG} + ā^τ_{P_gG} for the point of the guide under the slider, G the
  point by which the guide is attached.

Magnitudes known before the group is solved are given with numbers; the unknown ones are found
by the construction of the plans (their values follow in the text)."""
from __future__ import annotations

import math

from markupsafe import Markup

from ...mechanism.model import FRAME
from ...style.numbers import agreeing_sig, tex_num, trimmed_sig, written
from ..formulas import Formula, inline_math
from .common import tex_given, tex_point


def is_stone(mech, joint) -> bool:
    """Whether the slider of a prismatic pair is a stone (камень кулисы): a block with no point but
    its pin. A slider with points of its own (a piston rod in a rocking cylinder: its centre of
    mass, the piston) is not called a stone; the note names it by its number."""
    return len(mech.link(joint.links[1]).points) <= 1


def _len(row, a: str, b: str) -> float:
    return math.hypot(row[f"x_{a}"] - row[f"x_{b}"], row[f"y_{a}"] - row[f"y_{b}"])


def _attach(mech, link, group_links: set) -> str:
    """The point by which a link of the group is attached: a pair with a link outside the
    group (solved before, or the frame), else the link's first pair."""
    joints = [j for j in mech.joints if link.name in j.links and j.kind == "R"]
    for j in joints:
        other = j.links[0] if j.links[1] == link.name else j.links[1]
        if other not in group_links:
            return j.point
    return joints[0].point if joints else next(iter(link.points))


def _pt(p: str, link: str | None = None) -> str:
    """T of a point; a point of a given link carries its number: A_3 → A_{3}."""
    t = tex_point(p)
    if link is None:
        return t
    return f"{{{t}}}_{{{link}}}" if "_" in t else f"{t}_{{{link}}}"     # S_3 of link 3: {S_{3}}_{3}


def _solved_before(study, g) -> set:
    """Links known when group ``g`` is solved: the frame, the driving link and the links of the
    groups attached before it."""
    out = {FRAME, getattr(study.mechanism.driver, "link", None)} - {None}
    for h in study.structure.groups:
        if h is g:
            break
        out |= set(h.links)
    return out


def _m(tex: str) -> Markup:
    return inline_math(tex)


def _ang(name: str) -> str:
    return name if name.isdigit() else f"{{{name}}}"


def group_equations(study, row, g) -> tuple[list[Formula], list[Markup], list[Formula], list[Markup]]:
    """Velocity and acceleration equations of one group: (formulas, notes) for each."""
    mech = study.mechanism
    d = mech.driver
    links = set(g.links) | ({d.link} if g.klass == 1 else set())
    joint_pts = {j.point for j in mech.joints}
    vf, vn, af, an = [], [], [], []
    # a point by which a later group is attached (B of a slotted lever) is found once the group's
    # own equations (the stone's) have given the link's ω: its equations come after them
    before = _solved_before(study, g) | links | {FRAME}
    late: tuple[list, list, list, list] = ([], [], [], [])
    span = study.cycle if study.has_cycle else study.kinematics
    for name in [l for l in g.links] + ([d.link] if g.klass == 1 and d.link not in g.links else []):
        link = mech.link(name)
        if d.kind == "actuator" and name == d.rod:
            continue
        ref = _attach(mech, link, links)
        w = float(row.get(f"w_{name}", 0.0))
        e = float(row.get(f"e_{name}", 0.0))
        sliding_only = float(span["wq_" + name].abs().max()) < 1e-12    # a slider on the frame
        for p in link.points:
            if p == ref or p not in joint_pts or sliding_only:
                continue
            P, R = tex_point(p), tex_point(ref)
            l = _len(row, p, ref)
            onward = any(not set(j.links) <= before for j in mech.joints if j.point == p)
            out = late if onward else (vf, vn, af, an)
            fixed_ref = ref in mech.link(FRAME).points
            base_v = "" if fixed_ref else rf"\bar{{V}}_{{{R}}} + "
            out[0].append(Formula(rf"\bar{{V}}_{{{P}}} = {base_v}\bar{{V}}_{{{P}{R}}}"))
            known = g.klass == 1 and name == d.link and d.rotary
            # a point a later group hangs on, not a pair of this group's own links (E of a master rod,
            # B of a slotted lever): found after the link's ω and ε, by the similarity theorem
            similar = onward and not known and not any(j.point == p and set(j.links) <= links for j in mech.joints)
            after_v = Markup(" — по найденной {}: точка {} плана — по теореме подобия").format(
                _m(rf"\omega_{{{_ang(name)}}}"), _m(P.lower()))
            after_a = Markup(" — по найденной {}: точка {} плана — по теореме подобия").format(
                _m(rf"\varepsilon_{{{_ang(name)}}}"), _m(P.lower() + "'"))
            mag = (rf"V_{{{P}{R}}} = \omega_{{{_ang(name)}}} l_{{{R}{P}}} = {tex_num(abs(w), sig=4)} \cdot "
                   rf"{tex_num(l, sig=4)} = {tex_num(abs(w) * l, sig=4, unit='м/с')}") if known else \
                rf"V_{{{P}{R}}} = \omega_{{{_ang(name)}}} l_{{{R}{P}}}"
            out[1].append(Markup("{}, {}{}").format(_m(rf"\bar{{V}}_{{{P}{R}}} \;\perp\; {R}{P}"), _m(mag),
                                                "" if known else after_v if similar
                                                else Markup(" — величина находится построением")))
            base_a = "" if fixed_ref else rf"\bar{{a}}_{{{R}}} + "
            out[2].append(Formula(rf"\bar{{a}}_{{{P}}} = {base_a}\bar{{a}}^{{n}}_{{{P}{R}}} + \bar{{a}}^{{\tau}}_{{{P}{R}}}"))
            out[3].append(Markup("{} (направлено от точки {} к точке {}); {}, {}").format(
                _m(rf"a^{{n}}_{{{P}{R}}} = \omega_{{{_ang(name)}}}^{{2}} l_{{{R}{P}}} = "
                   rf"{_factors(lambda f: f[0] ** 2 * written(l), [abs(w)], w * w * l)[0]}^{{2}} \cdot "
                   rf"{tex_num(l, sig=4)} = {tex_num(w * w * l, sig=4, unit='м/с²')}"),
                _m(P), _m(R), _m(rf"\bar{{a}}^{{\tau}}_{{{P}{R}}} \;\perp\; {R}{P}"),
                _m(rf"a^{{\tau}}_{{{P}{R}}} = \varepsilon_{{{_ang(name)}}} l_{{{R}{P}}}"
                   + (rf" = {tex_num(abs(e) * l, sig=4, unit='м/с²')}" if known else "")))
                          + (after_a if similar else ""))
    drive = mech.driving_pair()
    if drive is not None and d.rod in g.links:
        _driving_pair(study, row, drive, (vf, vn, af, an))
    known = _solved_before(study, g) | links
    for j in mech.prismatic:
        guide, slider = j.links
        # a pair of this group: one of its links in the group, the other solved before (or the
        # frame) — not a pair by which a later group is attached to this one
        if not ({guide, slider} & links) or not {guide, slider} <= known or j.driving and g.klass != 1:
            continue
        P = tex_point(j.point)
        Ps, Pg = _pt(j.point, slider), _pt(j.point, guide)
        if guide == FRAME:
            P0 = _pt(j.point, "0")
            v_in, a_in = _inner_pin(mech, g, j, links)
            vf.append(Formula(rf"\bar{{V}}_{{{P}}} = \bar{{V}}_{{{P0}}} + \bar{{V}}_{{{P}{P0}}}"))
            vn.append(v_in + Markup("{}, {} направляющей — скорость ползуна направлена вдоль направляющей").format(
                _m(rf"\bar{{V}}_{{{P0}}} = 0"), _m(rf"\bar{{V}}_{{{P}{P0}}} \;\parallel")))
            af.append(Formula(rf"\bar{{a}}_{{{P}}} = \bar{{a}}_{{{P0}}} + \bar{{a}}^{{r}}_{{{P}{P0}}}"))
            an.append(a_in + Markup("{} (направляющая неподвижна, поэтому кориолисова ускорения нет), {} направляющей").format(
                _m(rf"\bar{{a}}_{{{P0}}} = 0"), _m(rf"\bar{{a}}^{{r}}_{{{P}{P0}}} \;\parallel")))
            continue
        vf.append(Formula(rf"\bar{{V}}_{{{Ps}}} = \bar{{V}}_{{{Pg}}} + \bar{{V}}_{{{Ps}{Pg}}}"))
        gref = _attach(mech, mech.link(guide), links | {guide})
        # a guide solved with an earlier group (a slider on the rocker of a four-bar): its ω and ε
        # are known, the point under the slider is found about the guide's fixed pivot if it has one
        earlier = next((h for h in study.structure.groups if guide in h.links and h is not g), None) \
            if guide not in g.links else None
        pivot = next((p for p in mech.link(guide).points if p in mech.link(FRAME).points), None)
        if earlier is not None and pivot is not None:
            gref = pivot
        G = tex_point(gref)
        if float(study.cycle["wq_" + guide].abs().max()) < 1e-12:      # a guide moving in translation
            G = tex_point(next((o.point for o in mech.prismatic if guide in o.links and o is not j), gref))
            vn.append(Markup("{} — звено {} движется поступательно, все его точки имеют одну скорость; {} "
                             "направляющей — величина находится построением").format(
                _m(rf"\bar{{V}}_{{{Pg}}} = \bar{{V}}_{{{G}}}"), guide, _m(rf"\bar{{V}}_{{{Ps}{Pg}}} \;\parallel")))
            af.append(Formula(rf"\bar{{a}}_{{{Ps}}} = \bar{{a}}_{{{Pg}}} + \bar{{a}}^{{r}}_{{{Ps}{Pg}}}"))
            an.append(Markup("{} (направляющая движется поступательно: "
                             "{}, кориолисова ускорения нет); {} направляющей — величина находится "
                             "построением").format(_m(rf"\bar{{a}}_{{{Pg}}} = \bar{{a}}_{{{G}}}"),
                                                  _m(rf"\omega_{{{_ang(guide)}}} = 0"),
                                                  _m(rf"\bar{{a}}^{{r}}_{{{Ps}{Pg}}} \;\parallel")))
            continue
        pin = next((o for jt in mech.joints if jt.kind == "R" and jt.point == j.point and slider in jt.links
                    for o in jt.links if o != slider and o not in links), None)
        v_pin = a_pin = Markup("")
        if pin is not None:     # the slider's pin on a link solved before: its velocity is known
            Pp = _pt(j.point, pin)
            # a pin on a translating link (a pin E on a slider): every point of that link has the
            # velocity and acceleration of the point of its own prismatic pair, already on the plans
            moving = float(span["wq_" + pin].abs().max()) >= 1e-12 if pin != FRAME else True
            own = None if moving else next((o.point for o in mech.prismatic if pin in o.links and o is not j), None)
            if own is not None and own != j.point:
                Q = tex_point(own)
                v_pin = Markup("{} — известна: шарнир {} соединяет звено {} со звеном {}, а звено {} движется "
                               "поступательно, все его точки имеют скорость точки {}; ").format(
                    _m(rf"\bar{{V}}_{{{Ps}}} = \bar{{V}}_{{{Pp}}} = \bar{{V}}_{{{Q}}}"), _m(P), slider, pin, pin, _m(Q))
                a_pin = Markup("{} — известно (звено {} движется поступательно); ").format(
                    _m(rf"\bar{{a}}_{{{Ps}}} = \bar{{a}}_{{{Pp}}} = \bar{{a}}_{{{Q}}}"), pin)
            else:
                v_pin = Markup("{} — известна: шарнир {} соединяет звено {} со звеном {}; ").format(
                    _m(rf"\bar{{V}}_{{{Ps}}} = \bar{{V}}_{{{Pp}}}"), _m(P), slider, pin)
                a_pin = Markup("{} — известно; ").format(_m(rf"\bar{{a}}_{{{Ps}}} = \bar{{a}}_{{{Pp}}}"))
        wg = abs(float(row.get(f"w_{guide}", 0.0)))
        lg = _len(row, j.point, gref)
        input_guide = d.rotary and guide == d.link
        base = "" if gref in mech.link(FRAME).points else rf"\bar{{V}}_{{{G}}} + "
        if earlier is None:
            vn.append(v_pin + Markup("{} — скорость точки звена {}, совпадающей в данный момент с точкой {} звена {}: "
                             "{}, {}; {} направляющей звена {} — величины находятся построением").format(
                _m(rf"\bar{{V}}_{{{Pg}}}"), guide, _m(P), slider, _m(rf"\bar{{V}}_{{{Pg}}} = {base}\bar{{V}}_{{{Pg}{G}}}"),
                _m(rf"\bar{{V}}_{{{Pg}{G}}} \;\perp\; {G}{P}"), _m(rf"\bar{{V}}_{{{Ps}{Pg}}} \;\parallel"), guide))
        else:
            # the guide is the input link itself (a driving slotted link, a tangent lever): its ω₁ is
            # given, not found with a group
            whence = Markup("звено {} — ведущее, его угловая скорость задана").format(guide) if input_guide \
                else Markup("звено {} рассчитано с группой ({})").format(guide, ",".join(earlier.links))
            vn.append(v_pin + Markup("{} — скорость точки звена {}, совпадающей в данный момент с точкой {} звена {}, "
                             "известна ({}): {}, {}, {}; {} направляющей звена {} — "
                             "величина находится построением").format(
                _m(rf"\bar{{V}}_{{{Pg}}}"), guide, _m(P), slider, whence,
                _m(rf"\bar{{V}}_{{{Pg}}} = {base}\bar{{V}}_{{{Pg}{G}}}"), _m(rf"\bar{{V}}_{{{Pg}{G}}} \;\perp\; {G}{P}"),
                _m(rf"V_{{{Pg}{G}}} = \omega_{{{_ang(guide)}}} l_{{{G}{P}}} = {tex_num(wg, sig=4)} \cdot {tex_num(lg, sig=4)} = "
                   rf"{tex_num(wg * lg, sig=4, unit='м/с')}"),
                _m(rf"\bar{{V}}_{{{Ps}{Pg}}} \;\parallel"), guide))
        af.append(Formula(rf"\bar{{a}}_{{{Ps}}} = \bar{{a}}_{{{Pg}}} + \bar{{a}}^{{k}}_{{{Ps}{Pg}}} + "
                          rf"\bar{{a}}^{{r}}_{{{Ps}{Pg}}}"))
        vr = abs(float(row.get(f"vs_{j.name}", 0.0)))
        base = "" if gref in mech.link(FRAME).points else rf"\bar{{a}}_{{{G}}} + "
        eg = float(row.get(f"e_{guide}", 0.0))
        tau = Markup("") if earlier is None else Markup(", {}{}").format(
            _m(rf"a^{{\tau}}_{{{Pg}{G}}} = \varepsilon_{{{_ang(guide)}}} l_{{{G}{P}}} = {tex_num(abs(eg), sig=4)} \cdot "
               rf"{tex_num(lg, sig=4)} = {tex_num(abs(eg) * lg, sig=4, unit='м/с²')}"),
            Markup(" (угловая скорость ведущего звена постоянна)") if abs(eg) < 1e-12 else "") if input_guide \
            else Markup(", {} — по найденному {}: точка {} плана — по теореме подобия").format(
            _m(rf"a^{{\tau}}_{{{Pg}{G}}} = \varepsilon_{{{_ang(guide)}}} l_{{{G}{P}}}"),
            _m(rf"\varepsilon_{{{_ang(guide)}}}"), _m(rf"{P.lower()}'_{{{guide}}}"))
        an.append(a_pin + Markup("{}: {}, {} (направлено от точки {} к точке {}), {}{}").format(
            _m(rf"\bar{{a}}_{{{Pg}}} = {base}\bar{{a}}^{{n}}_{{{Pg}{G}}} + \bar{{a}}^{{\tau}}_{{{Pg}{G}}}"),
            (Markup("ускорение точки звена {} под ползуном").format(guide) if is_stone(mech, j) else
             Markup("ускорение точки звена {}, совпадающей в данный момент с точкой {} звена {}").format(
                 guide, _m(P), slider)),
            _m(rf"a^{{n}}_{{{Pg}{G}}} = \omega_{{{_ang(guide)}}}^{{2}} l_{{{G}{P}}} = "
               rf"{_factors(lambda f: f[0] ** 2 * written(lg), [wg], wg * wg * lg)[0]}^{{2}} \cdot "
               rf"{tex_num(lg, sig=4)} = {tex_num(wg * wg * lg, sig=4, unit='м/с²')}"), _m(P), _m(G),
            _m(rf"\bar{{a}}^{{\tau}}_{{{Pg}{G}}} \;\perp\; {G}{P}"), tau))
        an.append(Markup("{} — кориолисово ускорение (направляющая вращается), направление — вектор "
                         "относительной скорости {}, повёрнутый на 90° в сторону вращения звена {}; {} "
                         "— величина находится построением").format(
            _m(rf"a^{{k}}_{{{Ps}{Pg}}} = 2 \omega_{{{_ang(guide)}}} V_{{{Ps}{Pg}}} = 2 \cdot "
               + r" \cdot ".join(_factors(lambda f: 2 * f[0] * f[1], [wg, vr], 2 * wg * vr))
               + rf" = {tex_num(2 * wg * vr, sig=4, unit='м/с²')}"),
            _m(rf"\bar{{V}}_{{{Ps}{Pg}}}"), guide,
            _m(rf"\bar{{a}}^{{r}}_{{{Ps}{Pg}}} \;\parallel") + Markup(" направляющей")))
    return vf + late[0], vn + late[1], af + late[2], an + late[3]


def _driving_pair(study, row, j, out) -> None:
    """The equations of the actuator's driving pair, first in its initial mechanism: the rod's end
    P on the cylinder's axis, V̄_P2 = V̄_P1 + V̄_P2P1 with V̄_P1 ⊥ O₁P (the cylinder's point under
    the rod end, ω₁ found by the construction) and V̄_P2P1 ∥ the axis, given (the rod's speed v₂₁);
    ā_P2 = ā^n + ā^τ of P1 about O₁ + ā^k (2·ω₁·v₂₁, the cylinder turns) + ā^r (a₂₁, given)
    (Попов, Тимофеев, гл. 3: a slider on a rotating guide). ``out`` — (vf, vn, af, an), prepended."""
    mech, d = study.mechanism, study.mechanism.driver
    cyl, rod = j.links
    P, O = tex_point(j.point), tex_point(d.center)
    Ps, Pg = _pt(j.point, rod), _pt(j.point, cyl)
    l = _len(row, j.point, d.center)
    w = abs(float(row.get(f"w_{cyl}", 0.0)))
    v = abs(float(row.get(f"vs_{j.name}", 0.0)))
    a = float(row.get(f"as_{j.name}", 0.0))
    vf, vn, af, an = out
    vf.insert(0, Formula(rf"\bar{{V}}_{{{Ps}}} = \bar{{V}}_{{{Pg}}} + \bar{{V}}_{{{Ps}{Pg}}}"))
    vn.insert(0, Markup("{} — скорость точки цилиндра {}, совпадающей в данный момент с точкой {} штока {}: {}, "
                        "{} — величина находится построением; {} оси гидроцилиндра, {} — задана (скорость "
                        "выдвижения штока); {} — шток соединён шарниром {} со звеном {}").format(
        _m(rf"\bar{{V}}_{{{Pg}}}"), cyl, _m(P), rod, _m(rf"\bar{{V}}_{{{Pg}}} \;\perp\; {O}{P}"),
        _m(rf"V_{{{Pg}}} = \omega_{{{cyl}}} l_{{{O}{P}}}"), _m(rf"\bar{{V}}_{{{Ps}{Pg}}} \;\parallel"),
        _m(rf"V_{{{Ps}{Pg}}} = v_{{{rod}{cyl}}} = {tex_given(v)}\ \text{{м/с}}"),
        _m(rf"\bar{{V}}_{{{Ps}}} = \bar{{V}}_{{{P}}}"), _m(P),
        next((o for jt in mech.joints if jt.kind == "R" and jt.point == j.point and rod in jt.links
              for o in jt.links if o != rod), "")))
    af.insert(0, Formula(rf"\bar{{a}}_{{{Ps}}} = \bar{{a}}^{{n}}_{{{Pg}{O}}} + \bar{{a}}^{{\tau}}_{{{Pg}{O}}} + "
                         rf"\bar{{a}}^{{k}}_{{{Ps}{Pg}}} + \bar{{a}}^{{r}}_{{{Ps}{Pg}}}"))
    an.insert(0, Markup("{} (направлено от точки {} к точке {}); {}, {} — величина находится построением; {} — "
                        "кориолисово ускорение (цилиндр вращается), направление — вектор относительной скорости {}, "
                        "повёрнутый на 90° в сторону вращения цилиндра {}; {} оси гидроцилиндра, {}{}").format(
        _m(rf"a^{{n}}_{{{Pg}{O}}} = \omega_{{{cyl}}}^{{2}} l_{{{O}{P}}} = "
           rf"{_factors(lambda f: f[0] ** 2 * written(l), [w], w * w * l)[0]}^{{2}} \cdot "
           rf"{tex_num(l, sig=4)} = {tex_num(w * w * l, sig=4, unit='м/с²')}"), _m(P), _m(O),
        _m(rf"\bar{{a}}^{{\tau}}_{{{Pg}{O}}} \;\perp\; {O}{P}"), _m(rf"a^{{\tau}}_{{{Pg}{O}}} = \varepsilon_{{{cyl}}} l_{{{O}{P}}}"),
        _m(rf"a^{{k}}_{{{Ps}{Pg}}} = 2 \omega_{{{cyl}}} v_{{{rod}{cyl}}} = 2 \cdot "
           rf"{_factors(lambda f: 2 * f[0] * v, [w], 2 * w * v)[0]} \cdot "
           rf"{tex_given(v)} = {tex_num(2 * w * v, sig=4, unit='м/с²')}"),
        _m(rf"\bar{{V}}_{{{Ps}{Pg}}}"), cyl, _m(rf"\bar{{a}}^{{r}}_{{{Ps}{Pg}}} \;\parallel"),
        _m(rf"a^{{r}}_{{{Ps}{Pg}}} = a_{{{rod}{cyl}}} = {tex_num(abs(a), sig=4, unit='м/с²')}"),
        Markup(" (шток выдвигается с постоянной скоростью)") if abs(a) < 1e-12 else Markup(" — задано")))


def _factors(value, factors, result) -> list[str]:
    """The measured factors of ω²l, 2ωV (ω, V from the plans) to as many digits as make the printed
    product the printed result: 32,625² · 0,4000 = 425,8, not 32,63² · 0,4000 = 425,9."""
    sg = agreeing_sig(value, factors, result)
    return [tex_num(x, sig=trimmed_sig(x, sg)) for x in factors]

def _inner_pin(mech, g, j, links: set) -> tuple[Markup, Markup]:
    """A ПВП group's second slider equation is written for the inner joint P (V̄_P = V̄_P0 + V̄_PP0),
    the first for the slider's point P_s on the moving guide: the inner revolute makes them one
    point, V̄_Ps = V̄_Pt = V̄_P (a student joins the two equations by it). Empty for other groups."""
    slider = j.links[1]
    inner = next((jt for jt in mech.joints if jt.kind == "R" and jt.point == j.point and slider in jt.links
                  and set(jt.links) <= links), None)
    if g.kind != "PRP" or inner is None:
        return Markup(""), Markup("")
    other = next(o for o in inner.links if o != slider)
    P = tex_point(j.point)
    P_o, P_s = _pt(j.point, other), _pt(j.point, slider)
    v = Markup("{} — звенья {} и {} соединены шарниром {}; ").format(
        _m(rf"\bar{{V}}_{{{P_o}}} = \bar{{V}}_{{{P_s}}} = \bar{{V}}_{{{P}}}"), other, slider, _m(P))
    a = Markup("{}; ").format(_m(rf"\bar{{a}}_{{{P_o}}} = \bar{{a}}_{{{P_s}}} = \bar{{a}}_{{{P}}}"))
    return v, a


def _where(sec, notes: list) -> None:
    """The explanations of a block of equations as one «где» list (ГОСТ 2.105): «где» before the
    first, each on its own line ending in «;», the last in «.» — not a «где» per equation, and no
    line stretched by a long formula run into the previous explanation."""
    for k, n in enumerate(notes):
        sec.paragraph(Markup("{}{}{}").format("где " if k == 0 else "", n, "." if k == len(notes) - 1 else ";"))


def add_velocities(sec, study, row) -> None:
    """Write the velocity equations of every group of the mechanism into the section (the plan of
    velocities is constructed, and the links' ω read off it, before any acceleration equation)."""
    sec.paragraph("Векторные уравнения скоростей и ускорений составлены для каждой структурной группы в "
                  "порядке присоединения; известные по величине и направлению векторы откладываются на "
                  "планах, неизвестные по величине находятся пересечением линий их направлений.")
    _add(sec, study, row, "Скорости, {}:", 0)


def add_accelerations(sec, study, row) -> None:
    """Write the acceleration equations of every group into the section; ``row`` holds the ω and
    relative velocities read off the velocity plan (``analysis.plans.read_velocities``)."""
    _add(sec, study, row, "Ускорения, {}:", 2)


def _add(sec, study, row, head: str, k: int) -> None:
    """The equations (``k`` = 0: velocities, 2: accelerations) of each group with their «где»."""
    d = study.mechanism.driver
    for g in study.structure.groups:
        eqs = group_equations(study, row, g)
        if not eqs[0] and not eqs[2]:
            continue
        title = g.title
        if d.kind == "actuator" and d.rod in g.links:    # the initial mechanism, as chapter 1 names it
            links = [l for h in study.structure.groups if {d.link, d.rod} & set(h.links) for l in h.links]
            title = (f"начальный механизм ({','.join(dict.fromkeys([d.link, d.rod] + links))}) с ведущей "
                     f"поступательной парой {d.link}–{d.rod}")
        sec.paragraph(Markup(head).format(title))
        sec.formula(*eqs[k])
        _where(sec, eqs[k + 1])
