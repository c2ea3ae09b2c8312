"""Section «Синтез эвольвентного зубчатого зацепления»: the shift from a measured tooth (inverse
problem), the geometry of the pair (ГОСТ 16532-70) with formulas and numbers, the geometry table,
the choice of shifts by the blocking contour, the mesh drawn at scale with the graphical ε_α, the
generating (rack) mesh and the specific sliding diagrams.

``conclusion_lines(study)`` gives the lines of the ЗАКЛЮЧЕНИЕ about the gearing."""
from __future__ import annotations

import math

import numpy as np
import pandas as pd
from markupsafe import Markup

from ...analysis.gears import admissible
from ...core import gears as G
from ...scenes import gears as S
from ...scenes.draw import gost_ratio, mu_text
from ...style.numbers import fmt, fmt_given, tex_num
from .common import as_written, tex_given
from ..document import Column, Formula, Section, ref

NEEDS = ("gears",)
TASK = "выполнить синтез эвольвентного зубчатого зацепления"


def _eps(eps: float, limit: float) -> str:
    """ε_α to 0,001, or to as many decimals as tell it from the given limit [ε_α] (1,2004 ≥ 1,2 printed
    «1,200 ≥ 1,200» read as a tie)."""
    d = 3
    while d < 6 and round(eps, d) == limit and eps != limit:
        d += 1
    return fmt(eps, digits=d)


def present(study) -> bool:
    """The section is built when the case has [gears]."""
    return study.root.has("gears")


def _t(x, sig=5, digits=None) -> str:
    return tex_num(float(x), sig=sig, digits=digits)


def _w(x) -> str:
    """A datum of the case (module, h_a*) in a formula as written: 3,5, not 3,5000."""
    return tex_given(x)


def _term(op: str, x, sig=3) -> str:
    """A substituted term after a binary «+»/«−» with its sign folded into the operator:
    «1 − 0,221», not «1 + −0,221» (``op`` is "+" or "-")."""
    x = float(x)
    if x < 0:
        op, x = ("-" if op == "+" else "+"), -x
    return f"{op} {_t(x, sig)}"


def _adeg(rad) -> str:
    """The given profile angle α in a formula as written (25°, not 25,0000°)."""
    return tex_given(round(math.degrees(float(rad)), 6)) + r"^{\circ}"


# ГОСТ 13755-81: the standard basic rack of involute gears
GOST_RACK = {"alpha": 20.0, "ha": 1.0, "c": 0.25, "rho_f": 0.38}


def contour_words(rack) -> str:
    """The basic rack in words: «исходный контур по ГОСТ 13755-81 (α = 20°, …)» when it is the
    standard one, otherwise its data and what departs from the standard (α = 25° is not ГОСТ 13755-81's
    contour, whose α = 20°, h_a* = 1, c* = 0,25, ρ_f* = 0,38)."""
    vals = {"alpha": round(math.degrees(rack.alpha), 6), "ha": rack.ha, "c": rack.c, "rho_f": rack.rho_f}
    sym = {"alpha": "α", "ha": "<i>h</i><sub>a</sub><sup>*</sup>", "c": "<i>c</i><sup>*</sup>",
           "rho_f": "ρ<sub>f</sub><sup>*</sup>"}
    unit = {"alpha": "°"}
    data = ", ".join(f"{sym[k]}&nbsp;=&nbsp;{as_written(v)}{unit.get(k, '')}" for k, v in vals.items())
    off = [k for k, v in vals.items() if abs(v - GOST_RACK[k]) > 1e-9]
    if not off:
        return f"исходным контуром по ГОСТ&nbsp;13755-81: {data}"
    std = ", ".join(f"{sym[k]}&nbsp;=&nbsp;{as_written(GOST_RACK[k])}{unit.get(k, '')}" for k in off)
    return f"исходным контуром {data} (нестандартный: по ГОСТ&nbsp;13755-81 {std})"


def _deg(rad) -> str:
    return tex_num(math.degrees(float(rad)), digits=4) + r"^{\circ}"


def given(study) -> str:
    """The gear pair's data in one sentence for the assignment page."""
    gr = study.gears
    text = (f"Зубчатая передача{' внутреннего зацепления' if gr.internal else ''}: модуль "
            f"<i>m</i>&nbsp;=&nbsp;{as_written(gr.m)}&nbsp;мм, числа зубьев <i>z</i><sub>1</sub>&nbsp;=&nbsp;{gr.z1}")
    if gr.z2:
        text += (f", <i>z</i><sub>2</sub>&nbsp;=&nbsp;{gr.z2} (передаточное отношение "
                 f"<i>u</i><sub>12</sub>&nbsp;=&nbsp;{as_written(round(gr.z2 / gr.z1, 4))})")
    text += "; колёса нарезаются инструментом реечного типа с " + contour_words(gr.rack)
    if gr.omega1 is not None:
        text += f"; частота вращения шестерни {fmt_given(gr.omega1 * 30 / math.pi)}&nbsp;об/мин"
    return text + "."


def build(study) -> Section:
    gr = study.gears
    sec = Section("Синтез эвольвентного зубчатого зацепления", "sec-gears")
    al = gr.rack.alpha
    sec.paragraph(
        f"Колёса нарезаются инструментом реечного типа с {contour_words(gr.rack)}; "
        f"модуль <i>m</i>&nbsp;=&nbsp;{as_written(gr.m)}&nbsp;мм. Расчёт геометрии ведётся по ГОСТ 16532-70.")
    if gr.inverse:
        _inverse(sec, gr)
    # the geometry table goes where the geometry is computed (it stood after «Удельное скольжение»)
    geo_sec = _geometry(sec, gr) if gr.geo is not None else sec
    geo_sec.paragraph(f"Размеры {'колёс' if gr.z2 else 'колеса'} и зубьев сведены в таблицу {ref('tab-gears-geo')}.")
    _table(geo_sec, gr)
    if gr.geo is not None:
        if gr.chosen or gr.node.has("x1"):
            _contour(sec, gr)
        _mesh(sec, gr)
        _sliding(sec, gr)
    if gr.geo is None or not gr.internal:
        _rack(sec, gr)
    return sec


def _inverse(sec: Section, gr) -> None:
    s = sec.subsection("Коэффициент смещения по измерениям зуба", "sec-gears-inverse")
    me, inv = gr.measure, gr.inverse
    m, al = gr.m, gr.rack.alpha
    if "x_chord" in inv:
        d = m * me.z
        s.paragraph(f"Штангензубомером измерены толщина зуба по хорде s̄<sub>y</sub> = {fmt(me.chord)} мм и "
                    f"высота до хорды h̄<sub>ay</sub> = {fmt(me.chord_height)} мм; диаметр вершин "
                    f"<i>d</i><sub>a</sub> = {fmt(me.d_a)} мм, <i>z</i> = {me.z}. Концы хорды лежат на "
                    f"окружности <i>d</i><sub>y</sub>, для которой <i>d</i><sub>y</sub> cos ψ<sub>y</sub> = "
                    f"<i>d</i><sub>a</sub> − 2h̄<sub>ay</sub> и <i>d</i><sub>y</sub> sin ψ<sub>y</sub> = "
                    f"s̄<sub>y</sub> (ψ<sub>y</sub> — половина угловой толщины зуба).")
        s.formula(
            Formula(r"\mathrm{tg}\,\psi_y = \frac{\bar s_y}{d_a - 2\bar h_{ay}}",
                    rf"\frac{{{_t(me.chord)}}}{{{_t(me.d_a)} - 2 \cdot {_t(me.chord_height)}}}",
                    rf"{_t(math.tan(inv['psi']), 5)};\quad \psi_y = {_t(inv['psi'], 5)}\ \text{{рад}}"),
            Formula(r"d_y = \sqrt{\bar s_y^2 + (d_a - 2\bar h_{ay})^2}", None, rf"{_t(inv['d_y'], 7)}\ \text{{мм}}"),
            Formula(r"\cos\alpha_y = \frac{d\cos\alpha}{d_y}",
                    rf"\frac{{{_t(d)} \cdot \cos {_adeg(al)}}}{{{_t(inv['d_y'], 7)}}}",
                    rf"{_t(math.cos(inv['alpha_y']), 5)};\quad \alpha_y = {_deg(inv['alpha_y'])}"),
            Formula(r"s = d(\psi_y + \mathrm{inv}\,\alpha_y - \mathrm{inv}\,\alpha)",
                    rf"{_t(d)}({_t(inv['psi'], 5)} + {_t(G.inv(inv['alpha_y']), 5)} - {_t(G.inv(al), 5)})",
                    rf"{_t(inv['s_chord'], 5)}\ \text{{мм}}"),
            Formula(r"x = \frac{s - \pi m/2}{2m\,\mathrm{tg}\,\alpha}",
                    rf"\frac{{{_t(inv['s_chord'], 5)} - \pi \cdot {_w(m)}/2}}{{2 \cdot {_w(m)} \cdot \mathrm{{tg}}\,{_adeg(al)}}}",
                    rf"{_t(inv['x_chord'], 4)}"))
        pr = gr.printed
        if pr:
            parts = []
            for key, val, name in (("d_y", inv["d_y"], "<i>d</i><sub>y</sub>"), ("s", inv["s_chord"], "<i>s</i>"),
                                   ("x", inv["x_chord"], "<i>x</i>")):
                if key in pr:
                    parts.append(f"{name} = {fmt(val, sig=7)} (в решении {pr[key]:g})".replace(".", ","))
            s.paragraph("Сравнение с опубликованным решением: " + "; ".join(parts) + ". Промежуточный "
                        "диаметр <i>d</i><sub>y</sub> решения отличается потому, что там sin ψ<sub>y</sub> "
                        "вычислен по углу, округлённому до 2,579°; окончательные <i>s</i> и <i>x</i> "
                        "совпадают после округления.")
    if "x_span" in inv:
        s.formula(r"x = \frac{W/(m\cos\alpha) - \pi(k - 0{,}5) - z\,\mathrm{inv}\,\alpha}{2\,\mathrm{tg}\,\alpha}",
                  rf"\frac{{{_t(me.span)}/({_w(m)}\cos{_adeg(al)}) - \pi({me.k} - 0{{,}}5) - {me.z} \cdot {_t(G.inv(al), 5)}}}"
                  rf"{{2\,\mathrm{{tg}}\,{_adeg(al)}}}", _t(inv["x_span"], 4))


def _geometry(sec: Section, gr) -> Section:
    s = sec.subsection("Геометрический расчёт передачи", "sec-gears-geo")
    g, m, al = gr.geo, gr.m, gr.rack.alpha
    z1, z2, x1, x2 = gr.z1, gr.z2, gr.x1, gr.x2
    kind = "внутреннего" if gr.internal else "внешнего"
    s.paragraph(f"Передача {kind} зацепления: <i>z</i><sub>1</sub> = {z1}, <i>z</i><sub>2</sub> = {z2}, "
                f"<i>x</i><sub>1</sub> = {fmt(x1, sig=3)}, <i>x</i><sub>2</sub> = {fmt(x2, sig=3)}.")
    pm = "-" if gr.internal else "+"
    if gr.a_w_required is not None:
        _given_centre_distance(s, gr, pm)
    s.formula(
        Formula(rf"\mathrm{{inv}}\,\alpha_w = \frac{{2(x_2 {pm} x_1)\,\mathrm{{tg}}\,\alpha}}{{z_2 {pm} z_1}} + \mathrm{{inv}}\,\alpha",
                rf"\frac{{2({_t(x2, 3)} {_term(pm, x1)}) \cdot {_t(math.tan(al), 5)}}}{{{z2} {pm} {z1}}} + {_t(G.inv(al), 5)}",
                _t(G.inv(g.alpha_w), 6)),
        Formula(r"\alpha_w", None, _deg(g.alpha_w)),
        Formula(rf"a = \frac{{m(z_2 {pm} z_1)}}{{2}}", rf"\frac{{{_w(m)}({z2} {pm} {z1})}}{{2}}", rf"{_t(g.a)}\ \text{{мм}}"),
        Formula(r"a_w = \frac{a\cos\alpha}{\cos\alpha_w}", rf"\frac{{{_t(g.a)} \cdot \cos{_adeg(al)}}}{{\cos{_deg(g.alpha_w)}}}",
                rf"{_t(g.a_w, 6)}\ \text{{мм}}"),
        Formula(r"y = \frac{a_w - a}{m}", None, _t(g.y, 4)),
        Formula(r"\Delta y = x_1 + x_2 - y", None, _t(g.dy, 4)) if not gr.internal else
        Formula(r"\Delta y", None, "0"),
        Formula(r"d_{a1} = d_1 + 2(h_a^* + x_1 - \Delta y)m",
                rf"{_t(g.d1)} + 2({_w(gr.rack.ha)} {_term('+', x1)} {_term('-', g.dy, 4)}) \cdot {_w(m)}",
                rf"{_t(g.da1, 6)}\ \text{{мм}}"),
        *([] if gr.internal else [
            Formula(r"d_{a2} = d_2 + 2(h_a^* + x_2 - \Delta y)m",
                    rf"{_t(g.d2)} + 2({_w(gr.rack.ha)} {_term('+', x2)} {_term('-', g.dy, 4)}) \cdot {_w(m)}",
                    rf"{_t(g.da2, 6)}\ \text{{мм}}")]),
    )
    s.paragraph("Толщина зуба на окружности вершин (α<sub>a</sub> — угол профиля на окружности вершин, "
                "cos α<sub>a</sub> = <i>d</i><sub>b</sub>/<i>d</i><sub>a</sub>):")
    s.formula(*[f for i, (z, da, db, sz, sa) in enumerate(((z1, g.da1, g.db1, g.s1, g.sa1), (z2, g.da2, g.db2, g.s2, g.sa2)), 1)
                for f in _tip_thickness(i, m * z, float(da), float(db), float(sz), float(sa), al,
                                        ring=gr.internal and i == 2)])
    sign = "-" if gr.internal else "+"
    s.formula(
        Formula(rf"\varepsilon_\alpha = \frac{{z_1(\mathrm{{tg}}\,\alpha_{{a1}} - \mathrm{{tg}}\,\alpha_w) {sign} "
                rf"z_2(\mathrm{{tg}}\,\alpha_{{a2}} - \mathrm{{tg}}\,\alpha_w)}}{{2\pi}}", None, _t(g.eps, 5)),
        Formula(r"\varepsilon_\alpha = \frac{B_1B_2}{p_b} = \frac{\rho_{a1} - \rho_{p1}}{\pi m \cos\alpha}",
                rf"\frac{{{_t(g.rho_a1, 5)} - {_t(g.rho_p1, 5)}}}{{{_t(g.pb, 5)}}}", _t(g.eps_line, 5)))
    checks = []
    xm1 = float(G.x_min_undercut(z1, gr.rack))
    checks.append(f"подрезание шестерни: <i>x</i><sub>1</sub> = {fmt(x1, sig=3)} "
                  f"{'≥' if x1 >= xm1 - 1e-12 else '<'} <i>x</i><sub>1min</sub> = {fmt(xm1, digits=3)} — "
                  f"{'подрезания нет' if x1 >= xm1 - 1e-12 else 'зуб подрезан'}")
    for i, sa in ((1, g.sa1), (2, g.sa2)):
        okk = float(sa) >= gr.s_a_min * m
        checks.append(f"заострение: <i>s</i><sub>a{i}</sub> = {fmt(float(sa), sig=4)} мм "
                      f"{'≥' if okk else '<'} {as_written(gr.s_a_min)}<i>m</i> = {fmt(gr.s_a_min * m, sig=4)} мм")
    okε = float(g.eps) >= gr.eps_min
    checks.append(f"плавность: ε<sub>α</sub> = {_eps(float(g.eps), gr.eps_min)} {'≥' if okε else '<'} "
                  f"{as_written(gr.eps_min)}")
    interf = float(g.rho_p1) < float(g.rho_l1) or (not gr.internal and float(g.rho_p2) < float(g.rho_l2))
    checks.append(f"интерференция: ρ<sub>p1</sub> = {fmt(float(g.rho_p1), sig=4)} мм, ρ<sub>l1</sub> = "
                  f"{fmt(float(g.rho_l1), sig=4)} мм" + ("" if gr.internal else
                  f"; ρ<sub>p2</sub> = {fmt(float(g.rho_p2), sig=4)} мм, ρ<sub>l2</sub> = {fmt(float(g.rho_l2), sig=4)} мм")
                  + (" — есть" if interf else " — нет (ρ<sub>p</sub> ≥ ρ<sub>l</sub>)"))
    if gr.internal:
        _internal_checks(checks, gr, g)
    s.paragraph("Проверки качества зацепления:")
    s.paragraph("<ul>" + "".join(f"<li>{c}{'.' if i == len(checks) - 1 else ';'}</li>" for i, c in enumerate(checks))
                + "</ul>")  # a list is no part of a <p>
    return s


def _given_centre_distance(s, gr, pm: str) -> None:
    """A required centre distance a_w: the working angle from cos α_w = a cos α / a_w, then the sum of
    the shifts x_Σ = (inv α_w − inv α)(z₂ ± z₁)/(2 tg α) (ГОСТ 16532-70, табл. 1, п. 3)."""
    m, al, z1, z2 = gr.m, gr.rack.alpha, gr.z1, gr.z2
    zs = z2 - z1 if gr.internal else z1 + z2
    a = m * zs / 2
    aw = gr.a_w_required
    alw = math.acos(a * math.cos(al) / aw)
    xs = G.xsum_from_centre_distance(m, z1, z2, al, aw, gr.internal)
    s.paragraph(f"Задано межосевое расстояние <i>a</i><sub>w</sub> = {as_written(aw)} мм; по нему находятся угол "
                "зацепления и сумма коэффициентов смещения:")
    s.formula(
        Formula(r"\cos\alpha_w = \frac{a\cos\alpha}{a_w}",
                rf"\frac{{{_t(a)} \cdot \cos{_adeg(al)}}}{{{_w(aw)}}}",
                rf"{_t(math.cos(alw), 6)};\quad \alpha_w = {_deg(alw)}"),
        Formula(rf"x_\Sigma = \frac{{(\mathrm{{inv}}\,\alpha_w - \mathrm{{inv}}\,\alpha)(z_2 {pm} z_1)}}{{2\,\mathrm{{tg}}\,\alpha}}",
                rf"\frac{{({_t(G.inv(alw), 6)} - {_t(G.inv(al), 5)})({z2} {pm} {z1})}}{{2 \cdot {_t(math.tan(al), 5)}}}",
                _t(xs, 4)))
    s.paragraph(f"Сумма распределена между колёсами: <i>x</i><sub>1</sub> = {fmt(gr.x1, sig=3)}, "
                f"<i>x</i><sub>2</sub> = <i>x</i><sub>Σ</sub> − <i>x</i><sub>1</sub> = {fmt(gr.x2, sig=3)} "
                f"(раздел {ref('sec-gears-contour')}); проверка — по формулам ниже.")


def _tip_thickness(i: int, d: float, da: float, db: float, s: float, sa: float, al: float, ring: bool = False) -> list:
    """s_a = d_a(s/d + inv α − inv α_a), cos α_a = d_b/d_a, with this wheel's numbers; a ring's
    (internal) tooth widens outwards: s_a = d_a(s/d − inv α + inv α_a)."""
    ala = math.acos(db / da)
    a, b = ("-", "+") if ring else ("+", "-")
    return [Formula(rf"\cos\alpha_{{a{i}}} = \frac{{d_{{b{i}}}}}{{d_{{a{i}}}}}", rf"\frac{{{_t(db, 6)}}}{{{_t(da, 6)}}}",
                    rf"{_t(math.cos(ala), 5)};\quad \alpha_{{a{i}}} = {_deg(ala)}"),
            Formula(rf"s_{{a{i}}} = d_{{a{i}}}\left(\frac{{s_{i}}}{{d_{i}}} {a} \mathrm{{inv}}\,\alpha {b} "
                    rf"\mathrm{{inv}}\,\alpha_{{a{i}}}\right)",
                    rf"{_t(da, 6)}\left(\frac{{{_t(s, 5)}}}{{{_t(d, 5)}}} {a} {_t(G.inv(al), 5)} {b} {_t(G.inv(ala), 5)}\right)",
                    rf"{_t(sa, 4)}\ \text{{мм}}")]


def _internal_checks(checks: list, gr, g) -> None:
    """The checks of an internal pair by ГОСТ 19274-73 (margins of ``G.internal_checks``)."""
    c = {k: float(v) for k, v in G.internal_checks(g).items()}
    tol = 1e-9 * gr.m
    dlt = float(G.ring_tip_correction(gr.z2, gr.x2, gr.rack))
    okr = c["base"] >= -tol
    checks.append(f"внутреннее колесо: <i>d</i><sub>a2</sub> = <i>d</i><sub>2</sub> − 2(<i>h</i><sub>a</sub><sup>*</sup> − "
                  f"<i>x</i><sub>2</sub> − Δ)<i>m</i> = {fmt(float(g.da2), sig=6)} мм с поправкой Δ = "
                  f"{fmt(dlt, sig=4)} (окружность вершин проходит через граничную точку эвольвенты; при "
                  f"<i>x</i><sub>2</sub> = 0 приближённо Δ = 7,55/<i>z</i><sub>2</sub>), "
                  f"{'&gt;' if okr else '≤'} <i>d</i><sub>b2</sub> = {fmt(g.db2, sig=6)} мм — "
                  f"{'эвольвента у вершины существует' if okr else 'вершина зуба внутри основной окружности'}")
    okp = c["ring_root"] >= -tol
    checks.append(f"вершина шестерни на эвольвенте колеса: ρ<sub>p2</sub> = {fmt(float(g.rho_p2), sig=4)} мм "
                  f"{'≤' if okp else '&gt;'} ρ<sub>l2</sub> = {fmt(float(g.rho_l2), sig=4)} мм — "
                  f"{'интерференции нет' if okp else 'интерференция у ножки колеса'}")
    okt = c["trochoid"] >= -tol
    checks.append(f"интерференция вершин (трохоидальная): <i>z</i><sub>1</sub>(inv α<sub>a1</sub> + δ<sub>1</sub>) + "
                  f"(<i>z</i><sub>2</sub> − <i>z</i><sub>1</sub>) inv α<sub>w</sub> − <i>z</i><sub>2</sub>(inv α<sub>a2</sub> + "
                  f"δ<sub>2</sub>) = {fmt(c['trochoid'], sig=3)} {'≥' if okt else '&lt;'} 0 — "
                  f"{'нет' if okt else 'есть'}")
    dz = G.dz_min_internal(gr.z1, float(gr.x1), float(gr.x2), gr.rack, gr.eps_min)
    if dz is not None:
        okz = gr.z2 - gr.z1 >= dz
        checks.append(f"наименьшая разность чисел зубьев при данных смещениях (все проверки и ε<sub>α</sub> ≥ "
                      f"{as_written(gr.eps_min)}): <i>z</i><sub>2</sub> − <i>z</i><sub>1</sub> ≥ {dz}; принято "
                      f"{gr.z2 - gr.z1} — {'выполнено' if okz else 'не выполнено'}")


def _sym_html(sym: str) -> Markup:
    """«d_b» → <i>d</i><sub>b</sub> (the program's own symbols, never case text)."""
    base, _, idx = str(sym).partition("_")
    out = Markup("<i>{}</i>").format(base)
    return out + Markup("<sub>{}</sub>").format(idx) if idx else out


class _RowValue(float):
    """A number of the geometry table with the decimals of its row: the table has a row per
    quantity, so one number of decimals holds along a row (ГОСТ 7.32, 6.6.6), not down a column."""

    digits = 3

    def __new__(cls, v, digits=3):   # the default lets pickle rebuild it (digits comes back in __dict__)
        obj = super().__new__(cls, v)
        obj.digits = digits
        return obj


# counts are whole; lengths in mm to 0,001 mm; shift coefficients to 0,001
_ROW_DIGITS = {"z": 0, "k": 0}


def _cell(v) -> str:
    return fmt(float(v), digits=getattr(v, "digits", 3))


def _table(sec: Section, gr) -> None:
    df = gr.wheel_rows()
    df = df.assign(label=[f"{n}, {u}" if u else n for n, u in zip(df["name"], df["unit"])])
    for col in ("wheel1", "wheel2"):
        df[col] = pd.Series([None if v is None or v != v else _RowValue(v, _ROW_DIGITS.get(k, 3))
                             for k, v in zip(df["key"], df[col])], dtype=object, index=df.index)
    cols = [Column("label", "Параметр", fmt=str), Column("symbol", "Обозначение", fmt=_sym_html),
            Column("wheel1", "Колесо 1", fmt=_cell)]
    if gr.z2 is not None:
        cols.append(Column("wheel2", "Колесо 2", fmt=_cell))
    sec.table(f"Геометрические параметры {'колёс' if gr.z2 else 'колеса'}", cols, df, id="tab-gears-geo")


def _contour(sec: Section, gr) -> None:
    s = sec.subsection("Выбор коэффициентов смещения", "sec-gears-contour")
    where = ("на прямой <i>x</i><sub>1</sub> + <i>x</i><sub>2</sub> = <i>x</i><sub>Σ</sub> (заданное "
             "<i>a</i><sub>w</sub>) с шагом 0,01 по <i>x</i><sub>1</sub>" if gr.a_w_required is not None else
             "на сетке с шагом 0,01")
    rule = (f"Смещения выбраны так: из точек {where} внутри блокирующего "
            "контура (нет подрезания, нет интерференции, <i>s</i><sub>a</sub> ≥ "
            f"{as_written(gr.s_a_min)}<i>m</i>, ε<sub>α</sub> ≥ {as_written(gr.eps_min)}) взята точка с наименьшим "
            "наибольшим удельным скольжением у ножек зубьев, т. е. с выравненным износом "
            + ("(λ<sub>1max</sub> ≈ λ<sub>2max</sub>)." if _wear_equal(gr) else
               "там, где это позволяет контур: изолиния λ<sub>1max</sub> = λ<sub>2max</sub> проходит вне "
               f"допустимой области, и выбранная точка лежит на границе контура ({_binding(gr)}).")
            if gr.chosen else
            "Заданная точка (<i>x</i><sub>1</sub>, <i>x</i><sub>2</sub>) показана на блокирующем контуре; она лежит "
            + ("внутри контура: подрезания, интерференции и заострения нет, ε<sub>α</sub> ≥ "
               f"{as_written(gr.eps_min)}." if bool(np.all(admissible(gr.geo, gr.s_a_min, gr.eps_min))) else
               "<b>вне контура</b>: одно из ограничений нарушено (см. проверки в разделе "
               f"{ref('sec-gears-geo')})."))
    s.paragraph(f"Блокирующий контур передачи <i>z</i><sub>1</sub> = {gr.z1}, <i>z</i><sub>2</sub> = {gr.z2} "
                f"приведён на рисунке {ref('fig-gears-contour')}. {rule}")
    s.figure(f"Блокирующий контур <i>z</i><sub>1</sub> = {gr.z1}, <i>z</i><sub>2</sub> = {gr.z2} с "
             f"{'выбранной' if gr.chosen else 'заданной'} точкой",
             S.blocking_contour(gr), 160, id="fig-gears-contour")


def _mesh(sec: Section, gr) -> None:
    s = sec.subsection("Картина зацепления", "sec-gears-mesh")
    md = S.internal_mesh_drawing(gr) if gr.internal else S.mesh_drawing(gr)
    g = gr.geo
    d = (md.eps_graph - float(g.eps)) / float(g.eps) * 100
    s.paragraph(f"Зацепление построено на рисунке {ref('fig-gears-mesh')} в масштабе {gost_ratio(md.mu / 1000)} "
                f"(μ<sub>l</sub> = {mu_text(md.mu)} мм/мм); профили зубьев шестерни — эвольвенты с переходными кривыми, "
                "огибаемыми скруглением головки рейки"
                + ("; впадины колеса с внутренними зубьями ограничены эвольвентами от окружности вершин до "
                   "окружности впадин (переходная кривая долбяка не показана: долбяк в задании не задан)"
                   if gr.internal else "")
                + ". Активная часть линии зацепления B<sub>1</sub>B<sub>2</sub> ограничена окружностями вершин.")
    s.figure(f"Картина эвольвентного зацепления (М {gost_ratio(md.mu / 1000)})", md.fig, md.width_mm, id="fig-gears-mesh")
    s.formula(r"\varepsilon_\alpha^{граф} = \frac{B_1B_2\,\mu_l}{p_b}",
              rf"\frac{{{_t(md.B1B2_mm, 4)} \cdot {_t(md.mu, 3)}}}{{{_t(g.pb, 5)}}}", _t(md.eps_graph, 4))
    s.paragraph(f"Расхождение графического и аналитического значений: {fmt(d, sig=2)} %.")


def _sliding(sec: Section, gr) -> None:
    s = sec.subsection("Удельное скольжение", "sec-gears-sliding")
    g = gr.geo
    s.paragraph(f"Удельные скольжения профилей в точках активной части линии зацепления (таблица "
                f"{ref('tab-gears-sliding')}, диаграммы — на рисунке {ref('fig-gears-sliding')}) вычислены по "
                "радиусам кривизны профилей ρ<sub>1</sub> и ρ<sub>2</sub> в точке контакта:")
    s.formula(Formula(r"\lambda_1 = 1 - \frac{\rho_2}{u\,\rho_1},\quad \lambda_2 = 1 - \frac{u\,\rho_1}{\rho_2},"
                      rf"\quad u = \frac{{z_2}}{{z_1}} = {tex_given(round(float(g.u), 4))}"))
    s.figure("Диаграммы удельного скольжения", S.sliding_diagram(gr), 160, id="fig-gears-sliding")
    t = gr.sliding_table
    cols = [Column("rho1", "ρ<sub>1</sub>", "мм", sig=5), Column("rho2", "ρ<sub>2</sub>", "мм", sig=5),
            Column("lambda1", "λ<sub>1</sub>", digits=3), Column("lambda2", "λ<sub>2</sub>", digits=3)]
    if "vs" in t:
        cols.append(Column("vs", "<i>v</i><sub>ск</sub>", "м/с", sig=4))
    s.table("Удельное скольжение на активной части линии зацепления", cols, t, id="tab-gears-sliding")


def _rack(sec: Section, gr) -> None:
    s = sec.subsection("Станочное зацепление", "sec-gears-rack")
    fig, w, mu = S.rack_drawing(gr)
    xm = float(G.x_min_undercut(gr.z1, gr.rack))
    s.paragraph(f"Колесо 1 нарезается рейкой, смещённой на <i>x</i><sub>1</sub><i>m</i> = {fmt(gr.x1 * gr.m, sig=4)} мм "
                f"(рисунок {ref('fig-gears-rack')}). Граница подрезания: прямая головок рейки не должна "
                f"пересекать линию станочного зацепления ниже точки <i>N</i>, что даёт "
                f"<i>x</i><sub>min</sub> = <i>h</i><sub>a</sub><sup>*</sup> − <i>z</i> sin²α/2 = {fmt(xm, digits=3)}.")
    s.figure("Станочное зацепление колеса 1 с производящей рейкой", fig, w, id="fig-gears-rack")


def _foot_sliding(gr) -> tuple[float, float]:
    """|λ₁| at B₁ and |λ₂| at B₂: the greatest specific sliding at the feet of the teeth."""
    t = gr.sliding_table
    return abs(float(t["lambda1"].iloc[0])), abs(float(t["lambda2"].iloc[-1]))


def _wear_equal(gr) -> bool:
    """The wear of the feet counts as equalised when the greater λ at the feet exceeds the smaller
    by at most 15 %."""
    l1, l2 = _foot_sliding(gr)
    return max(l1, l2) <= 1.15 * min(l1, l2)


def _binding(gr) -> str:
    """The limits of the blocking contour the chosen point stands on, in words with numbers: those
    whose margin is within about one step of the 0,01 grid (ε_α, s_a, undercut, interference)."""
    g, m = gr.geo, gr.m
    out = []
    if float(g.eps) - gr.eps_min < 0.02:
        out.append(f"ε<sub>α</sub> = {_eps(float(g.eps), gr.eps_min)} ≈ {as_written(gr.eps_min)}")
    for i, sa in ((1, float(g.sa1)), (2, float(g.sa2))):
        if sa - gr.s_a_min * m < 0.02 * m:
            out.append(f"<i>s</i><sub>a{i}</sub> = {fmt(sa, sig=4)} мм ≈ {as_written(gr.s_a_min)}<i>m</i>")
    for i, (z, x) in enumerate(((gr.z1, gr.x1), (gr.z2, gr.x2)), 1):
        if (i == 1 or not gr.internal) and x - float(G.x_min_undercut(z, gr.rack)) < 0.015:
            out.append(f"<i>x</i><sub>{i}</sub> ≈ <i>x</i><sub>{i}min</sub> — граница подрезания")
    for i, (rp, rl) in enumerate(((g.rho_p1, g.rho_l1), (g.rho_p2, g.rho_l2)), 1):
        if (i == 1 or not gr.internal) and float(rp) - float(rl) < 0.02 * m:
            out.append(f"ρ<sub>p{i}</sub> ≈ ρ<sub>l{i}</sub> — граница интерференции")
    return "; ".join(out) or "ограничения контура"


def _judgement(gr, g) -> list[str]:
    """The quality of the designed pair in words (Попов, Тимофеев, гл. 4; ГОСТ 16532-70): undercut of
    the pinion, the tips' thickness, the contact ratio against its allowed value and the wear of the
    feet by the specific sliding at B₁ (λ₁) and B₂ (λ₂)."""
    xm1 = float(G.x_min_undercut(gr.z1, gr.rack))
    under = (f"подрезания зубьев шестерни нет (<i>x</i><sub>1</sub> = {fmt(gr.x1, sig=3)} ≥ <i>x</i><sub>1min</sub> = "
             f"{fmt(xm1, digits=3)})" if gr.x1 >= xm1 - 1e-12 else
             f"<b>зубья шестерни подрезаны</b> (<i>x</i><sub>1</sub> = {fmt(gr.x1, sig=3)} &lt; <i>x</i><sub>1min</sub> = "
             f"{fmt(xm1, digits=3)}): смещение шестерни нужно увеличить")
    sa = min(float(g.sa1), float(g.sa2))
    sharp = (f"наименьшая толщина зуба на вершине {fmt(sa, sig=3)} мм = {fmt(sa / gr.m, sig=2)}<i>m</i> "
             + ("— заострения нет" if sa >= gr.s_a_min * gr.m else "— <b>зуб заострён</b>"))
    eps = float(g.eps)
    if eps < gr.eps_min:
        smooth = (f"<b>ε<sub>α</sub> = {_eps(eps, gr.eps_min)} меньше допустимого {as_written(gr.eps_min)}</b>: плавность "
                  "зацепления не обеспечена, смещения нужно уменьшить")
    else:
        smooth = (f"ε<sub>α</sub> = {_eps(eps, gr.eps_min)} ≥ {as_written(gr.eps_min)}"
                  + (" — плавность обеспечена с малым запасом (менее 5 %)" if eps < 1.05 * gr.eps_min else
                     " — плавность обеспечена"))
    out = ["Качество зацепления: " + "; ".join((under, sharp, smooth)) + "."]
    l1, l2 = _foot_sliding(gr)
    faster = f"ножка {'шестерни' if l1 > l2 else 'колеса'} изнашивается быстрее; "
    wear = ("износ ножек практически выровнен" if _wear_equal(gr) else
            faster + "выровнять износ в пределах блокирующего контура нельзя: выбранная точка лежит на его "
            f"границе ({_binding(gr)}), изолиния λ<sub>1max</sub> = λ<sub>2max</sub> — вне допустимой области"
            if gr.chosen else
            faster + "износ можно выровнять, "
            "перераспределив смещения к изолинии λ<sub>1max</sub> = λ<sub>2max</sub> блокирующего контура")
    out.append(f"Наибольшие удельные скольжения у ножек зубьев |λ<sub>1</sub>| = {fmt(l1, digits=2)} (точка "
               f"B<sub>1</sub>) и |λ<sub>2</sub>| = {fmt(l2, digits=2)} (точка B<sub>2</sub>): {wear}.")
    return out


def conclusion_lines(study) -> list[str]:
    gr = study.gears
    out = []
    if gr.geo is not None:
        g = gr.geo
        out.append(f"Спроектирована зубчатая передача <i>z</i><sub>1</sub> = {gr.z1}, <i>z</i><sub>2</sub> = {gr.z2}, "
                   f"<i>m</i> = {as_written(gr.m)} мм, <i>x</i><sub>1</sub> = {fmt(gr.x1, sig=3)}, <i>x</i><sub>2</sub> = "
                   f"{fmt(gr.x2, sig=3)}: <i>a</i><sub>w</sub> = "
                   f"{as_written(gr.a_w_required) if gr.a_w_required is not None else fmt(float(g.a_w), sig=6)} мм, α<sub>w</sub> = "
                   f"{fmt(math.degrees(float(g.alpha_w)), digits=4)}°, ε<sub>α</sub> = {fmt(float(g.eps), sig=4)}.")
        out += _judgement(gr, g)
    if "x_chord" in gr.inverse:
        out.append(f"По измерениям зубомером коэффициент смещения <i>x</i> = {fmt(gr.inverse['x_chord'], sig=3)}, "
                   f"делительная толщина зуба <i>s</i> = {fmt(gr.inverse['s_chord'], sig=4)} мм.")
    return out

