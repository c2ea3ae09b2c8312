"""The teacher's answer key of a case («Ключ к варианту»), separate from the student's note.

``build_key(study)`` returns a :class:`~reportgen.report.document.Report` rendered by the same
layer as the note (reportgen/report/render.py): the given data, the key results of every section,
the independent checks (rigidity of the links over the cycle — loop closure; Жуковский's lever and
the power balance of the force analysis; the energy balance of the dynamics), the comparison with
the values printed in the worksheet where the case has them (``[dynamics.printed]``, the
``printed`` lists of synthesis, machine, dof, cross and governor), and the
worksheet's own errors the program found.  Nothing of this belongs in the student's note.
"""
from __future__ import annotations

import importlib
import math
import re
from dataclasses import replace

import numpy as np
import pandas as pd
from markupsafe import Markup

from ..case.text import inline_html
from ..registry import KINDS
from ..style.numbers import fmt
from .assemble import REFERENCES, _given_parameters, _linkage_data
from .document import Column, Report, Section, ref
from .key_names import convert, entry, group_title, shown
from .russian import flag_group, position_names
from .sections.common import as_written, pos_fmt, q_degrees

CHECK_COLS = [Column("what", "Проверка", fmt=Markup), Column("value", "Расхождение", fmt=Markup),
              Column("verdict", "Вывод", fmt=Markup)]


def build_key(study, options: dict | None = None) -> Report:
    """The answer key of ``study`` as a Report (no title page, no assignment page)."""
    meta = dict(study.meta)
    # the heading above the contents (templates/key_head.html.j2) says whose variant this is
    meta["key_of"] = meta.get("topic") or ""
    meta["topic"] = "Ключ к варианту (для преподавателя)"
    opts = dict(study.root.table("report").raw("options", {}) or {})
    opts.update(options or {})
    # the teacher's reference, not a ГОСТ 7.32 document: no title page, and the sections run on
    # (a class's keys are printed together: a section of three lines on a page of its own wasted
    # paper thirty times)
    opts.update(title_page=False, assignment_page=False, section_new_page=False)
    sections = [_given(study), _results(study), _checks(study)]
    printed = _printed(study)
    if printed is not None:
        sections.append(printed)
    if "dynamics" in study.tasks() and study.dynamics.settings.compare is not None:
        from .sections.dynamics import comparison_block
        cmp = Section("Сравнение с другим вариантом", "key-compare")
        comparison_block(cmp, study)
        sections.append(cmp)
    errors = _errors(study)
    if errors is not None:
        sections.append(errors)
    intro = []
    return Report(meta=meta, assignment=[], introduction=intro, sections=sections, conclusion=[],
                  references=REFERENCES if _cites(sections) else [], options=opts)


_CITATION = re.compile(r"(?<![\w\]])\[[1-9]\d*(?:[,–]\s*\d+)*(?:,\s*с\.[^\]]*)?\]")


def _cites(sections) -> bool:
    """Whether any paragraph, caption or cell text of the key cites a source as [n] (ГОСТ 7.32:
    the list of sources holds what the text cites; the key usually cites nothing, and a page of
    six uncited sources is only noise to the teacher)."""
    def texts(node):
        for attr in ("title", "html", "caption", "note"):
            v = getattr(node, attr, None)
            if isinstance(v, str):
                yield v
        data = getattr(node, "data", None)
        if isinstance(data, pd.DataFrame):
            for col in data.columns:
                yield from (v for v in data[col] if isinstance(v, str))
        for ch in getattr(node, "children", []) or []:
            yield from texts(ch)
    return any(_CITATION.search(t) for s in sections for t in texts(s))


def _given(study) -> Section:
    sec = Section("Исходные данные", "key-given")
    for block in _given_parameters(study) + (_linkage_data(study) if study.has_linkage else []):
        sec.add(block)
    # the data of every task as the assignment page of the note states them (a cam's phases and
    # laws, a gear pair's m and z, a train's scheme, the dynamics' δ and loads): most of a case
    # without a linkage is given there, not in its parameters
    for kind in KINDS:
        if kind.name in study.tasks():
            given = getattr(importlib.import_module(f".sections.{kind.name}", __package__), "given", None)
            if given is not None:
                sec.paragraph(given(study))
    if not sec.children:
        sec.paragraph("Параметров в файле варианта нет.")
    return sec


RESULT_COLS = [Column("name", "Величина", fmt=Markup), Column("sym", "Обозначение", fmt=Markup),
               Column("value", "Значение", fmt=Markup), Column("unit", "Единица"),
               Column("where", "Где (положение)", fmt=Markup)]


def value_text(e, value, study=None, kind: str = "") -> tuple[str, str] | None:
    """The cell text of a scalar by its glossary entry and its unit; None when a switch has a
    value the glossary does not say in words."""
    if isinstance(value, (bool, np.bool_)):
        return (e.words[0] if value else e.words[1]), ""
    if isinstance(value, str):
        words = e.words.get(value) if isinstance(e.words, dict) else None
        return (words, "") if words else None
    x = float(value)
    if not math.isfinite(x):
        return "—", ""
    x, unit = convert(e, x, study, kind)
    return (as_written(x) if e.given and _short(x) else fmt(x, digits=e.digits, sig=e.sig)), unit


def _short(x: float) -> bool:
    """A value as a case writes it has at most six significant digits; one with more (x₂ = x_Σ − x₁ =
    −0,2209500964 of shifts chosen under a given a_w) was computed, and prints to its entry's digits."""
    return abs(float(f"{x:.6g}") - x) <= 1e-9 * abs(x)


def where_text(study, kind: str, q: float) -> str:
    """«φ = 193,8°» (a crank's angle from the cycle's start, as the note prints it) or
    «S = 0,420 м» (an actuator's stroke) where an extreme occurs."""
    if kind == "dynamics":
        return f"φ&nbsp;=&nbsp;{fmt(math.degrees(float(q) - study.dynamics.settings.cycle_start), digits=2)}°"
    no = position_at(study, q)
    tail = f' <span class="nowrap">(положение&nbsp;{no})</span>' if no is not None else ""   # never «(положе-|ние 0)»
    if study.mechanism.driver.rotary:
        return f"φ&nbsp;=&nbsp;{fmt(q_degrees(study, q), digits=1)}°" + tail
    return f"<i>S</i>&nbsp;=&nbsp;{fmt(q, digits=3)}&nbsp;м" + tail


def position_at(study, q: float) -> str | None:
    """The note's number of the report position at the input coordinate ``q`` (a crank's angle
    modulo a turn), None when the extreme lies between positions."""
    k = study.kinematics
    d = k["q"].to_numpy(float) - float(q)
    if study.mechanism.driver.rotary and not study.mechanism.driver.swing:
        d = (d + math.pi) % (2 * math.pi) - math.pi
    hit = np.flatnonzero(np.abs(d) <= 1e-9 * max(1.0, abs(float(q))))
    return pos_fmt(study)(k["pos"].iloc[hit[0]]) if hit.size else None


SAID = "said in words"     # the group of the switches and yes/no values: a sentence, not a table row


def result_rows(study, kind: str, scalars: dict) -> dict[str, list[dict]]:
    """The rows of the results of one task by the groups of the glossary (``key_names``), in the
    order of the scalars; a position goes into the row of its extreme, a value equal to the one it
    repeats (``same_as``) is left out, a key without an entry is left out (the glossary test
    covers every case); switches and yes/no values go to the group :data:`SAID`."""
    groups: dict[str, list[dict]] = {}
    for key, value in scalars.items():
        e = entry(kind, key)
        if e is None or e.position:
            continue
        if e.same_as is not None and e.same_as in scalars and _same(value, scalars[e.same_as]):
            continue
        if e.hide_if is not None and scalars.get(e.hide_if[0]) == e.hide_if[1]:
            continue                  # the chosen method's value: the row of the result itself
        if isinstance(e.words, dict) and e.words.get(value) == "":
            continue                  # a switch whose value another row already says
        if not e.given and _is_input(study, kind, key, value):
            e = replace(e, given=True)
        cell = value_text(e, value, study, kind)
        if cell is None:
            continue
        where = e.where and scalars.get(e.where)
        name, sym = shown(e, study, kind)
        said = isinstance(value, (str, bool, np.bool_))
        groups.setdefault(SAID if said else e.group, []).append({
            "name": Markup(name), "sym": Markup(sym), "value": Markup(cell[0]), "unit": cell[1],
            "where": Markup(where_text(study, kind, where)) if where is not None and where is not False else ""})
    return groups


def _is_input(study, kind: str, key: str, value) -> bool:
    """Whether the scalar ``key`` repeats a value the case gives its task (a synthesis' ψ, d, l_CB
    among the results: «ψ 55°» as written, not «55,00°»): the task's ``inputs`` (SI) hold it under
    the key's name without the task prefix («syn_psi» → «psi»)."""
    if study is None or kind not in study.tasks():
        return False
    inputs = getattr(study.analysis(kind), "inputs", None)
    if not isinstance(inputs, dict) or isinstance(value, (str, bool, np.bool_)):
        return False
    name = key.split("_", 1)[-1]
    return name in inputs and isinstance(inputs[name], (int, float)) and _same(inputs[name], value)


def _same(a, b) -> bool:
    try:
        return abs(float(a) - float(b)) <= 1e-9 * max(abs(float(a)), abs(float(b)), 1e-300)
    except (TypeError, ValueError):
        return a == b


def _results(study) -> Section:
    sec = Section("Основные результаты по разделам", "key-results")
    if study.has_linkage:
        st = study.structure
        s = sec.subsection("Структура и кинематика", "key-kin")
        from .sections.structure import _roman, decomposition
        rows, formula = decomposition(study)
        s.paragraph(f"Число степеней свободы: {st.chebyshev}; структурная формула {formula}; "
                    f"механизм {_roman(st.mech_class)} класса. " + _groups_text(rows) + ".")
        names = position_names(study.kinematics["pos"])
        extra = [f"{lab} → {num}" for lab, num in names.items() if lab != num]
        if extra:
            s.paragraph("Дополнительные положения в записке пронумерованы: " + ", ".join(extra) + ".")
        # the least transmission angles are found over the cycle: none for a case computed at its
        # given positions only (``cycle = false``), whose key failed here
        flags = list(study.flags.items()) if study.has_cycle else []
        if flags:
            rows = [{"g": flag_group(study, n), "min": math.degrees(fl["min"]),
                     "where": Markup(where_text(study, "kinematics", fl["q_min"])),
                     "low": "ниже 40° — мал" if fl["low"] else "не ниже 40°"} for n, fl in flags]
            s.table("Наименьшие углы передачи по группам", [
                Column("g", "Группа"), Column("min", "μ<sub>min</sub>", "град", digits=1),
                Column("where", "Где (положение)", fmt=Markup), Column("low", "Оценка")],
                pd.DataFrame(rows), id="key-mu")
        out = {k: v for k, v in study.scalars.items() if entry("kinematics", k) is not None}
        for rows in result_rows(study, "kinematics", out).values():
            s.table("Выходное звено", RESULT_COLS[:-1], pd.DataFrame(rows), id="key-output")
        by_position_tables(s, study)
    for kind in KINDS:
        if kind.name not in study.tasks():
            continue
        groups = result_rows(study, kind.name, study.analysis(kind.name).scalars)
        if not groups:
            continue
        s = sec.subsection(kind.title, f"key-{kind.name}")
        said = groups.pop(SAID, [])
        if said:
            s.paragraph(Markup(" ").join(Markup("{}: {}.").format(r["name"], r["value"]) for r in said))
        for n, (group, rows) in enumerate(groups.items()):
            cols = RESULT_COLS if any(r["where"] for r in rows) else RESULT_COLS[:-1]
            head = group_title(group, study, kind.name)
            caption = f"{kind.title}: {head[0].lower() + head[1:]}" if head else kind.title
            s.table(caption, cols, pd.DataFrame(rows), id=f"key-tab-{kind.name}" + (f"-{n}" if n else ""))
        if kind.name == "forces":
            reactions_at_chosen(s, study)
            balance_by_position(s, study)
    return sec


def _deg(x) -> str:
    """A link's angle in degrees in [0°, 360°), as the note's table of angles prints it."""
    v = math.degrees(float(x)) % 360.0
    return fmt(0.0 if round(v, 2) >= 360.0 else v, digits=2)


def _output_columns(study, coord: str) -> list[Column]:
    """The output's displacement and, when ω₁ (or the actuator's rate) is given, its true velocity
    and acceleration, named as in the note's tables (s_H by the slider's point, φ₃, x_E)."""
    from .sections.common import sub
    mech, k = study.mechanism, study.kinematics
    pre, _, name = coord.partition("_")
    known = mech.driver.omega is not None
    if pre == "s":
        pts = [j.point for j in mech.prismatic]
        j = next(j for j in mech.prismatic if j.name == name)
        idx = j.point if pts.count(j.point) == 1 else j.name
        cols = [Column(coord, sub("s", idx), "м", digits=4)]
        if known:
            cols += [Column(f"vs_{name}", sub("V", idx), "м/с", digits=3),
                     Column(f"as_{name}", sub("a", idx), "м/с²", sig=4)]
    elif pre == "phi":
        cols = [Column(coord, sub("φ", name), "град", fmt=_deg)]
        if known:
            cols += [Column(f"w_{name}", sub("ω", name), "рад/с", digits=3),
                     Column(f"e_{name}", sub("ε", name), "рад/с²", sig=4)]
    else:
        cols = [Column(coord, sub(pre, name), "м", digits=4)]
        if known:
            cols += [Column(f"v{pre}_{name}", f"<i>V</i><sub>{name}{pre}</sub>", "м/с", digits=3),
                     Column(f"a{pre}_{name}", f"<i>a</i><sub>{name}{pre}</sub>", "м/с²", sig=4)]
    return [c for c in cols if c.key in k.columns]


def by_position_tables(sec: Section, study) -> None:
    """The values a student computes position by position (the plans of velocities and
    accelerations): the output's displacement, velocity and acceleration and the angular velocity
    and acceleration of every turning link, by the note's position numbers — the row the teacher
    compares with a student's table.  Wide tables are split as in the note."""
    from .sections.common import chunked_tables, position_lead, sub
    from .sections.kinematics import _links
    from ..analysis.plans import parallel_outputs
    k = study.kinematics
    cols: list[Column] = []
    for coord, *_ in parallel_outputs(study):
        cols += [c for c in _output_columns(study, coord) if c.key not in {x.key for x in cols}]
    if study.mechanism.driver.omega is not None:
        shown = {c.key for c in cols}
        d = study.mechanism.driver
        for l in _links(study):
            if d.rotary and l.name == d.link:
                continue
            for c in (Column(f"w_{l.name}", sub("ω", l.name), "рад/с", digits=3),
                      Column(f"e_{l.name}", sub("ε", l.name), "рад/с²", sig=4)):
                if c.key not in k.columns or c.key in shown:
                    continue
                # a link turning with another (a slot's stone and its lever): one column «ω₂ = ω₃»
                twin = next((x for x in cols if x.key[:2] == c.key[:2] and x.key[2:] != c.key[2:]
                             and np.allclose(k[x.key], k[c.key], rtol=1e-12, atol=1e-12)), None)
                if twin is not None:
                    twin.header = f"{twin.header}&nbsp;=&nbsp;{c.header}"
                else:
                    cols.append(c)
    if not cols:
        return
    sec.paragraph("Значения по положениям (номера положений — как в записке):")
    chunked_tables(sec, "Выходное звено и угловые скорости и ускорения звеньев по положениям"
                   if len(cols) > 3 else "Выходное звено по положениям", k, cols, position_lead(study), "key-by-pos")


def balance_by_position(sec: Section, study) -> None:
    """The balancing moment (a crank) or the actuator's force over the positions of the force
    analysis, by the note's position numbers."""
    from .sections.common import position_lead, sub
    f = study.forces
    main = ("M_bal", sub("M", "ур"), "Н·м") if f.rotary else ("F_act", "<i>F</i>", "Н")
    if main[0] not in f.table:
        return
    cols = [Column(main[0], main[1], main[2], sig=5)]
    if f.settings.flywheel and "M_bal_linkage" in f.table:
        # the flywheel's inertia moment on the crank makes M_ур constant; the moment of the linkage
        # alone is the one a student finds group by group (the note's «M_ур без маховика»)
        cols.append(Column("M_bal_linkage", sub("M", "ур") + " без маховика", "Н·м", sig=5))
    sec.table("Уравновешивающий момент по положениям" if f.rotary else "Усилие гидроцилиндра по положениям",
              position_lead(study) + cols, f.table, id="key-bal-by-pos")


def reactions_at_chosen(sec: Section, study) -> None:
    """The reactions in the pairs at the position whose force analysis the note shows group by
    group (the rows a student's tables by groups hold), by the note's position number, to the
    decimals of the note's reaction tables (``sections.forces.reaction_digits``)."""
    from .sections.common import chosen_position, pos_no
    from .sections.forces import _R, _shown_pairs, reaction_digits
    f = study.forces
    lab = chosen_position(study)
    labels = [str(x) for x in f.table["pos"]]
    if lab not in labels:
        return
    row = f.table.iloc[labels.index(lab)]
    rows = [{"pair": _R(k), "Rx": row["Rx_" + k], "Ry": row["Ry_" + k], "R": row["R_" + k]}
            for k in _shown_pairs(f) if "R_" + k in f.table]
    if not rows:
        return
    nd = reaction_digits(f)
    sec.table(f"Реакции в кинематических парах (положение {pos_no(study, lab)})", [
        Column("pair", "Реакция", fmt=Markup), Column("Rx", "<i>R</i><sub>x</sub>", "Н", sig=None, digits=nd),
        Column("Ry", "<i>R</i><sub>y</sub>", "Н", sig=None, digits=nd),
        Column("R", "<i>R</i>", "Н", sig=None, digits=nd)], pd.DataFrame(rows), id="key-react-chosen")


def _groups_text(rows: list[dict]) -> str:
    """«Начальный механизм (0,1); группы: …» from the rows of ``structure.decomposition``: the
    initial mechanism named as in the note's force analysis («Начальный механизм (0,1)»), not as
    one of the groups."""
    head = "начальный механизм"
    init = [r for r in rows if r["title"].startswith(head)]
    rest = [(r["title"] if r["g"] in r["title"] else f"{r['title']} {r['g']}").removeprefix("группа Ассура ")
            for r in rows if r not in init]
    parts = []
    for r in init:
        tail = r["title"][len(head):].strip()
        tail = "" if tail == "I класса" else " " + tail
        parts.append(f"Начальный механизм {r['g']}{tail}")
    if rest:
        parts.append(("группы Ассура: " if parts else "Группы Ассура: ") + "; ".join(rest))
    return "; ".join(parts)


def _verdict(x: float, tol: float) -> Markup:
    """«выполнена» / «НЕ выполнена», never hyphenated in a narrow column."""
    return Markup('<span class="nowrap">{}</span>').format("выполнена" if x <= tol else "НЕ выполнена")


def loop_closure(study) -> float:
    """Largest change over the cycle of a distance between two points of one link, m (rigidity
    of every link = closure of every vector loop; 0 up to round-off for a correct solution)."""
    cyc = study.cycle if study.has_cycle else study.kinematics    # (no cycle: the given positions)
    worst = 0.0
    for link in study.mechanism.moving:
        pts = [p for p in link.points if f"x_{p}" in cyc]
        for i, p in enumerate(pts):
            for q in pts[i + 1:]:
                d = np.hypot(cyc[f"x_{p}"] - cyc[f"x_{q}"], cyc[f"y_{p}"] - cyc[f"y_{q}"]).to_numpy()
                (x0, y0), (x1, y1) = link.points[p], link.points[q]
                worst = max(worst, float(np.max(np.abs(d - math.hypot(x1 - x0, y1 - y0)))))
    return worst


def analog_differences(study) -> tuple[float, float]:
    """Largest relative difference over the cycle between the analogs of the points' velocities
    (accelerations) from the groups' linear systems and the central differences of the points'
    coordinates (of those velocity analogs) over the cycle's grid of the input coordinate:
    x′ ≈ (x_{i+1} − x_{i−1})/(q_{i+1} − q_{i−1}), x″ likewise from x′ (error O(Δq²)), each
    referred to the largest |x′| (|x″|) of the point over the cycle.  A second formulation of the
    velocity and acceleration analogs from the positions alone."""
    cyc = study.cycle
    q = cyc["q"].to_numpy(float)
    dq = q[2:] - q[:-2]
    worst_v = worst_a = 0.0
    for p in {pt for link in study.mechanism.moving for pt in link.points}:
        for ax in ("x", "y"):
            cols = (f"{ax}_{p}", f"vq{ax}_{p}", f"aq{ax}_{p}")
            if not all(c in cyc for c in cols):
                continue
            x, v, a = (cyc[c].to_numpy(float) for c in cols)
            for f, df, worst in ((x, v, "v"), (v, a, "a")):
                scale = float(np.max(np.abs(df)))
                if scale <= 1e-12:
                    continue
                d = float(np.max(np.abs((f[2:] - f[:-2]) / dq - df[1:-1]))) / scale
                if worst == "v":
                    worst_v = max(worst_v, d)
                else:
                    worst_a = max(worst_a, d)
    return worst_v, worst_a


def _checks(study) -> Section:
    sec = Section("Проверки", "key-checks")
    rows = []
    if study.has_linkage:
        err = loop_closure(study)
        rows.append({"what": "Замыкание контуров: расстояния между точками каждого звена "
                             + ("за цикл" if study.has_cycle else "в заданных положениях"),
                     "value": f"{fmt(err, sig=2)} м", "verdict": _verdict(err, 1e-9)})
        if study.has_cycle:
            dv, da = analog_differences(study)
            rows.append({"what": "Аналоги скоростей точек: из систем групп и по разностям координат за цикл",
                         "value": fmt(dv, sig=2), "verdict": _verdict(dv, 1e-4)})
            rows.append({"what": "Аналоги ускорений точек: из систем групп и по разностям аналогов скоростей",
                         "value": fmt(da, sig=2), "verdict": _verdict(da, 1e-4)})
    tasks = study.tasks()
    if "forces" in tasks:
        sc = study.forces.scalars
        rows.append({"what": "Рычаг Жуковского: уравновешивающая сила (момент) по группам и по рычагу",
                     "value": f"{fmt(sc['dev_zhukovsky_max_pct'], sig=2)} %",
                     "verdict": _verdict(sc["dev_zhukovsky_max_pct"], 1e-6)})
        if "dev_power_max" in sc:
            rows.append({"what": "Баланс мощностей (принцип возможных перемещений)",
                         "value": fmt(sc["dev_power_max"], sig=2), "verdict": _verdict(sc["dev_power_max"], 1e-8)})
        for k, title in (("dev_M_bal_M_d_max", "Уравновешивающий момент и движущий момент динамики"),
                         ("dev_M_bal_dyn_max", "Уравновешивающий момент и M<sub>д</sub> − J<sub>I</sub>ε динамики")):
            if k in sc and math.isfinite(sc[k]):
                rows.append({"what": title, "value": fmt(sc[k], sig=2), "verdict": _verdict(sc[k], 1e-6)})
    if "dynamics" in tasks:
        d = study.dynamics
        sc = d.scalars
        A = sc.get("A_d", math.nan) + sc.get("A_c", math.nan)
        scale = max(abs(sc.get("A_c", 0.0)), abs(sc.get("A_d", 0.0)), 1e-12)
        if math.isfinite(A):
            rows.append({"what": "Баланс энергии за цикл: A<sub>д</sub> + A<sub>с</sub> = 0",
                         "value": fmt(abs(A) / scale, sig=2), "verdict": _verdict(abs(A) / scale, 1e-9)})
        dl = abs(sc["delta_achieved"] - sc["delta"]) / sc["delta"]
        exact = sc.get("method") == "exact"
        rows.append({"what": Markup("Коэффициент неравномерности δ при точном движении с принятым "
                                    "<i>J</i><sub>I</sub> и заданный (относительное отличие)"),
                     "value": fmt(dl, sig=2),
                     "verdict": _verdict(dl, 1e-6) if exact else "метод приближённый"})
    rows += _second_formulations(study)
    if rows:
        df = pd.DataFrame(rows)
        sec.table("Независимые проверки", CHECK_COLS, df, id="key-checks-tab")
    else:
        sec.paragraph("Проверок для этого варианта нет.")
    return sec


def _second_formulations(study) -> list[dict]:
    """Checks of the tasks without a linkage by a second formulation of the same result: ε_α by
    the angles of the active profile and by the length of the active line of action (Фролов [3]);
    the train's ratio by Willis's formula and by the velocities at the poles of the meshes; the
    synthesised linkage's K and stroke measured on the mechanism against the given ones."""
    tasks, rows = study.tasks(), []

    def rel(a, b):
        return abs(float(a) - float(b)) / max(abs(float(b)), 1e-300)
    if "cam" in tasks:
        cam = study.cam
        key = "cam_rho_min" if cam.contact == "flat" else "cam_rho_c_min"
        if key in cam.scalars:
            d = rel(cam_rho_by_points(cam), cam.scalars[key])
            rows.append({"what": Markup("Наименьший радиус кривизны " + ("рабочего" if cam.contact == "flat" else
                                                                        "центрового") +
                                        " профиля: по формуле и по окружностям через три соседние точки профиля "
                                        "(через 0,02°)"),
                         "value": fmt(d, sig=2), "verdict": _verdict(d, 1e-3)})
    if "gears" in tasks:
        sc = study.gears.scalars
        if "gears_eps_alpha_line" in sc:
            d = rel(sc["gears_eps_alpha_line"], sc["gears_eps_alpha"])
            rows.append({"what": Markup("Коэффициент перекрытия ε<sub>α</sub> по углам профиля и по длине активной "
                                        "линии зацепления"), "value": fmt(d, sig=2), "verdict": _verdict(d, 1e-9)})
    if "train" in tasks:
        d = float(study.train.scalars["train_u_discrepancy_pct"])
        rows.append({"what": "Передаточное отношение по формуле Виллиса и по скоростям в полюсах зацеплений",
                     "value": f"{fmt(d, sig=2)} %", "verdict": _verdict(abs(d), 1e-7)})
    if "synthesis" in tasks:
        sc = study.synthesis.scalars
        if "check_K" in sc and "syn_K" in sc:
            d = max(rel(sc["check_K"], sc["syn_K"]), rel(sc["check_stroke"], study.synthesis.target_stroke()))
            rows.append({"what": "Синтез: коэффициент K и ход (размах) выходного звена, измеренные на механизме, "
                                 "и заданные",
                         "value": fmt(d, sig=2), "verdict": _verdict(d, 1e-8)})
    return rows


def cam_rho_by_points(cam, step_deg: float = 0.02) -> float:
    """The least radius of curvature of the convex parts of the cam's profile (the centre profile;
    the working one of a flat follower) from its points alone: the circle through three
    neighbouring points C₁, C₂, C₃ has the curvature κ = 2 (C₂ − C₁)×(C₃ − C₂)/(|C₂ − C₁| |C₃ − C₂|
    |C₃ − C₁|) (the circumscribed circle of a triangle, R = abc/4S); ρ = −k/κ with the sign of the
    analytic formula ρ = −k|C′|³/(C′×C″) (> 0 convex).  The profile is sampled every ``step_deg``
    inside each smooth piece of the cycle (phases, knots, inflections), so no triple straddles a
    kink of the law; ρ at a piece's ends is extrapolated from its two nearest circles.  An
    independent formulation of the key's ρ_min, which the analysis finds
    from the derivatives C′, C″ of the inversion."""
    pts = "W" if cam.contact == "flat" else "C"
    ends = sorted({x for ph in cam.phases for x in (cam.breaks(ph) if ph.law else (ph.start, ph.start + ph.length))})
    best = math.inf
    for a, b in zip(ends[:-1], ends[1:]):
        n = max(3, int(math.ceil((b - a) / math.radians(step_deg))) + 1)
        P = cam.profile(np.linspace(a, b, n))[pts]
        d1, d2, d3 = P[1:-1] - P[:-2], P[2:] - P[1:-1], P[2:] - P[:-2]
        cross = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            rho = -cam.k * np.hypot(*d1.T) * np.hypot(*d2.T) * np.hypot(*d3.T) / (2 * cross)
        if rho.size >= 2:   # a piece's least ρ often lies at its end (a knot of s″): the circles give ρ
            # at the inner nodes only, so extend linearly by one step to both ends (error O(h²), not O(h))
            rho = np.concatenate(([2 * rho[0] - rho[1]], rho, [2 * rho[-1] - rho[-2]]))
        convex = rho[np.isfinite(rho) & (rho > 0)]
        if convex.size:
            best = min(best, float(convex.min()))
    return best


def _printed(study) -> Section | None:
    """Every comparison with the values printed in the source: the dynamics' table
    (``[dynamics.printed]``) and, for each task whose note section declares ``printed_angular``
    (synthesis, machine, dof, cross, governor), its analysis' ``printed`` list with the notes on
    why the worksheet differs; a section's own ``key_printed(sec, study)`` adds what is not a table
    (motion: the printed equation integrated beside the correct one)."""
    sec = Section("Сравнение с напечатанными значениями", "key-printed")
    if "dynamics" in study.tasks() and study.dynamics.settings.printed:
        from .sections.dynamics import printed_block
        pr = study.dynamics.printed
        if pr is not None and len(pr):
            printed_block(sec, pr, study)
    for kind in KINDS:
        if kind.name not in study.tasks():
            continue
        mod = importlib.import_module(f".sections.{kind.name}", __package__)
        angular, hook = getattr(mod, "printed_angular", None), getattr(mod, "key_printed", None)
        printed = getattr(study.analysis(kind.name), "printed", None) if angular is not None else None
        if not printed and hook is None:
            continue
        sub = sec.subsection(kind.title, f"key-printed-{kind.name}")
        if printed:
            printed_table(sub, printed, f"tab-{kind.name}-printed", angular)
        if hook is not None:
            hook(sub, study)
        if not sub.children:
            sec.children.remove(sub)
    return sec if sec.children else None


def printed_table(sec, printed: list[dict], tid: str, angular=lambda k: False) -> None:
    """Values printed in the source beside the exact ones, with the notes (why they differ)."""
    if not printed:
        return
    rows, notes = [], []
    for p in printed:
        ang = angular(p["key"])
        f = ((lambda z, n=5: fmt(math.degrees(z), sig=n) + "°") if ang else
             (lambda z, n=5: str(int(z)) if float(z).is_integer() and abs(z) < 1e6 else fmt(z, sig=n)))
        title = inline_html(p["title"])
        rows.append({"name": title, "printed": f(p["printed"], p["digits"]), "computed": f(p["computed"]),
                     "rel": fmt(100 * (p["printed"] - p["computed"]) / p["computed"], sig=2) + "&nbsp;%"})
        if p["note"]:
            notes.append(Markup("Примечание — {}: {}").format(title, p["note"]))
    sec.paragraph(f"Значения, напечатанные в исходном решении, сопоставлены с точными в таблице {ref(tid)}.")
    sec.table("Сравнение с напечатанными значениями",
              [Column("name", "Величина", fmt=Markup), Column("printed", "Напечатано"), Column("computed", "Точно"),
               Column("rel", "Отклонение", fmt=Markup)], pd.DataFrame(rows), id=tid)
    for n in notes:
        sec.paragraph(n)




def _errors(study) -> Section | None:
    """The worksheet's errors the program found (case-driven: printed values out of tolerance,
    the worksheet's formula for the carrier's largest load)."""
    items = []
    if "dynamics" in study.tasks() and study.dynamics.settings.printed:
        from .sections.dynamics import _as_printed
        pr = study.dynamics.printed
        for _, r in pr[~pr["within"]].iterrows():
            items.append(f"{r['title'] or r['key']}: напечатано {_as_printed(r['printed'], r['value'])}, "
                         f"точное значение {fmt(r['computed'], sig=6)}.")
    if "forces" in study.tasks():
        f = study.forces
        if f.settings.carrier is not None and "Gmax_carrier_as_printed" in f.table:
            t = f.table
            items.append("Наибольший груз по условию управляемости: в листе из суммы моментов вычитается сила "
                         "R<sub>A,min</sub> без плеча L (формула неоднородна по размерности); по ней получилось бы "
                         f"{fmt(t['Gmax_carrier_as_printed'].min(), sig=5)}…"
                         f"{fmt(t['Gmax_carrier_as_printed'].max(), sig=5)} Н вместо "
                         f"{fmt(t['Gmax_carrier'].min(), sig=5)}…{fmt(t['Gmax_carrier'].max(), sig=5)} Н.")
    if not items:
        return None
    sec = Section("Ошибки исходного расчёта", "key-errors")
    for it in items:
        sec.paragraph(it)
    return sec


def write_key(study, out_dir, stem: str, formats=("pdf", "html")) -> dict:
    """Write ``out_dir/<stem>-key.pdf`` (and .html); returns {"key-pdf": path, …}."""
    from .render import build_outputs
    files = build_outputs(build_key(study), out_dir, f"{stem}-key", formats)
    return {f"key-{k}": p for k, p in files.items()}
