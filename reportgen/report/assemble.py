"""Assemble the whole «пояснительная записка» of a Study from its section builders.

Each section module declares ``NEEDS`` (the Study results it reads) and ``build(study)``; the
report runs only the sections requested or present in the case, so e.g. a report without a
dynamics section never runs the dynamics kernels.
"""
from __future__ import annotations

import importlib
import math
import re
from collections.abc import Mapping
from typing import Iterable

import pandas as pd
from markupsafe import Markup, escape

from ..case import units as U
from ..errors import CaseError
from ..registry import KINDS
from ..style.numbers import fmt, fmt_given
from .document import Column, Paragraph, Report, Table
from .russian import genitive, param_parts, param_symbol, param_title, plural
from .safety import validate_report
from .sections import kinematics as sec_kin
from .sections import structure as sec_struct
from .sections import synthesis
from .sections.common import as_written, swing_text, value_with_unit


def _has_linkage(study) -> bool:
    return study.has_linkage


# name → (module with NEEDS/build, predicate: does the case have it); the linkage's own two
# sections, then one per registered task kind (reportgen/report/sections/<name>.py), in order
SECTIONS: dict[str, tuple] = {
    "structure": (sec_struct, _has_linkage),
    "kinematics": (sec_kin, _has_linkage),
}
for _kind in KINDS:
    _mod = importlib.import_module(f"{__package__}.sections.{_kind.name}")
    SECTIONS[_kind.name] = (_mod, _mod.present)
# the synthesis finds the sizes the linkage's analysis uses: its chapter comes first
SECTIONS = {"synthesis": SECTIONS.pop("synthesis"), **SECTIONS}
ORDER = list(SECTIONS)

REFERENCES = [
    "Артоболевский, И. И. Теория механизмов и машин : учебник для втузов / И. И. Артоболевский. — "
    "4-е изд., перераб. и доп. — Москва : Наука, 1988. — 640 с.",
    "Попов, С. А. Курсовое проектирование по теории механизмов и механике машин : учебное пособие / "
    "С. А. Попов, Г. А. Тимофеев ; под ред. К. В. Фролова. — 5-е изд., перераб. и доп. — Москва : "
    "Высшая школа, 2004. — 411 с.",
    "Теория механизмов и машин : учебник для втузов / К. В. Фролов, С. А. Попов, А. К. Мусатов [и др.] ; "
    "под ред. К. В. Фролова. — Москва : Высшая школа, 1987. — 496 с.",
    "Кореняко, А. С. Курсовое проектирование по теории механизмов и машин / А. С. Кореняко, "
    "Л. И. Кременштейн, С. Д. Петровский [и др.]. — 5-е изд., перераб. — Киев : Вища школа, 1970. — 332 с.",
    "ГОСТ 2.770–68. Единая система конструкторской документации. Обозначения условные графические "
    "в схемах. Элементы кинематики. — Москва : Стандартинформ, 2007. — 15 с.",
    "ГОСТ 7.32–2017. Система стандартов по информации, библиотечному и издательскому делу. Отчёт о "
    "научно-исследовательской работе. Структура и правила оформления. — Москва : Стандартинформ, 2017. — 32 с.",
]


def _typeset(entry: str) -> str:
    """Non-breaking spaces in a reference (ГОСТ 7.0.100 entry): between initials and before the
    surname («И.\u00a0И.\u00a0Артоболевский»), in «640\u00a0с.» and «ГОСТ\u00a02.770»; and before the
    prescribed punctuation of the entry's areas and elements (« : », « / », « ; », « — »), which
    never begins a line (a browser's narrow column broke «[и др.] | ; под ред.»)."""
    entry = re.sub(r" ([:/;—])(?= )", "\u00a0\\1", entry)
    entry = re.sub(r"\b([А-ЯЁA-Z]\.) (?=[А-ЯЁA-Z])", "\\1\u00a0", entry)
    entry = re.sub(r"(\d+) с\.", "\\1\u00a0с.", entry)
    return re.sub(r"ГОСТ (\d)", "ГОСТ\u00a0\\1", entry)


REFERENCES = [_typeset(r) for r in REFERENCES]


def chosen_sections(study, names: Iterable[str] | None) -> list[str]:
    """The note's sections: ``--sections``, else ``[report] sections`` of the case, else every
    section the case has."""
    if not names:
        asked = validate_report(study.root.table("report"))
        if asked is not None:
            return asked
    if names:
        unknown = [n for n in names if n not in SECTIONS]
        if unknown:
            from ..errors import CaseError
            raise CaseError(f"неизвестный раздел отчёта «{unknown[0]}»", key="--sections",
                            expected="один из: " + ", ".join(n for n in ORDER if n in SECTIONS))
        return [n for n in ORDER if n in names]
    return [n for n in ORDER if n in SECTIONS and SECTIONS[n][1](study)]


def needs(study, names: Iterable[str] | None = None) -> set[str]:
    out: set[str] = set()
    for n in chosen_sections(study, names):
        out |= set(SECTIONS[n][0].NEEDS)
    if study.has_linkage and not study.has_cycle:     # [grid] cycle = false: the sections do without it
        out.discard("cycle")
    return out


def build_report(study, sections: Iterable[str] | None = None, options: dict | None = None) -> Report:
    from .render import DEFAULT_OPTIONS
    node = study.root.table("report")
    validate_report(node)
    node.table("options").check_keys(list(DEFAULT_OPTIONS))
    names = chosen_sections(study, sections)
    built = _build_sections(study, names)
    meta = dict(study.meta)
    meta.setdefault("topic", "Структурный и кинематический анализ рычажного механизма")
    # no [meta] variant: no «Вариант» line (the case file's name is not a student's text)
    opts = dict(study.root.table("report").raw("options", {}) or {})
    opts.update(options or {})
    return Report(meta=meta, assignment=_assignment(study, names), introduction=_introduction(study, names, built),
                  sections=built, conclusion=_conclusion(study, names), references=REFERENCES, options=opts)


_STUDY = None  # the study whose sections are being built: inherited by the forked workers


def _build_one(name: str):
    """In a worker: the section, or ``None`` when building it failed (the parent builds it
    again itself and so raises the error as a build in one process does: an exception
    carried between processes may not survive pickling)."""
    from .document import freeze
    try:
        return freeze(SECTIONS[name][0].build(_STUDY))
    except Exception:
        return None


def _freeze_inherited() -> None:
    """In a forked worker: the objects inherited from the parent (the study, its tables, the
    imported modules: about 260 000) are moved out of the garbage collector's sight, so its
    collections while the figures are drawn scan only the worker's own objects (a tenth of a
    section's CPU time otherwise) and do not copy the parent's pages."""
    import gc
    gc.freeze()


def _build_sections(study, names: list[str]) -> list:
    """Every chosen section built (``build(study)``: its text, tables and figures), in a pool
    of forked processes when more than one may lay out a note
    (:func:`~reportgen.report.parallel.note_jobs`): the figures of the sections are drawn
    at the same time. The results the sections read are computed here first (``NEEDS``), so
    the workers inherit them; a worker sends its section back made picklable
    (:func:`~reportgen.report.document.freeze`)."""
    global _STUDY
    from .parallel import note_jobs
    jobs = min(note_jobs(), len(names))
    if jobs < 2:
        return [SECTIONS[n][0].build(study) for n in names]
    for need in sorted(needs(study, names)):
        getattr(study, need)
    import multiprocessing
    _STUDY = study
    try:
        with multiprocessing.get_context("fork").Pool(jobs, initializer=_freeze_inherited) as pool:
            # the heaviest sections first (figures, tables): the order of the registry's tasks
            order = sorted(range(len(names)), key=lambda i: (-_WEIGHT.get(names[i], 1), i))
            done = dict(zip(order, pool.map(_build_one, [names[i] for i in order], chunksize=1)))
    finally:
        _STUDY = None
    return [done[i] if done[i] is not None else SECTIONS[names[i]][0].build(study) for i in range(len(names))]


# relative cost of building a section of ws000 (figures): the longest first in the pool
_WEIGHT = {"dynamics": 4, "kinematics": 4, "forces": 3, "structure": 1}


def _assignment(study, names) -> list:
    tasks = _assignment_tasks(study, names)
    lead = ("Требуется: " if not study.has_linkage else "По заданной схеме механизма и исходным данным: "
            if "synthesis" in names else "По заданной схеме и размерам механизма: ")
    out = [Paragraph(lead + "; ".join(tasks) + ".")] if tasks else []
    out += _given_parameters(study)
    if study.has_linkage:
        out += _linkage_data(study)
    # the data of the other tasks (cam, gears, train, dynamics, …) as their sections state them
    given = [SECTIONS[n][0].given(study) for n in names if hasattr(SECTIONS[n][0], "given")]
    if given and study.has_linkage and isinstance(out[-1], Paragraph) and 'class="as-given"' in out[-1].html:
        # the driver's sentence and the other data in one compact paragraph (fewer half-empty lines)
        given[0] = out.pop().html.removeprefix('<p class="as-given">').removesuffix("</p>") + " " + given[0]
    out += [_given_paragraph(g) for g in given]
    return out


def _given_paragraph(html: str) -> Paragraph:
    """A sentence of given data on the assignment page, set compactly like its tables (so that the
    assignment with its signature lines stays on one page where it can)."""
    return Paragraph(f'<p class="as-given">{html}</p>')


_TASKS = {"structure": "выполнить структурный анализ механизма",
          "kinematics": "выполнить кинематический анализ (план положений, аналоги скоростей и ускорений, "
                        "планы скоростей и ускорений, кинематические диаграммы)",
          "dynamics": "определить закон движения машины и рассчитать маховик по заданному коэффициенту "
                      "неравномерности хода"}


def _assignment_tasks(study, names) -> list[str]:
    """One clause per chosen section: the section module's ``TASK`` (a task kind's own wording) or
    the linkage's clauses above; only what the note contains (no plans of velocities without a
    given speed of the driving link)."""
    out = []
    for n in names:
        text = getattr(SECTIONS[n][0], "TASK", None) or _TASKS.get(n)
        if callable(text):          # a clause depending on what the case asks
            text = text(study)
        if n == "kinematics" and study.mechanism.driver.omega is None:
            text = ("выполнить кинематический анализ (план положений, аналоги скоростей и ускорений, "
                    "кинематические диаграммы)")
        if text:
            out.append(text)
    return out


def _given_parameters(study) -> list:
    out = []
    rows = []
    raw = study.root.table("parameters").data
    texts = study.spec.parameter_texts()
    fitted = {f.name for f in study.fits}
    for name, q in study.params.items():
        if name not in raw or name in fitted:
            continue
        v, unit = value_with_unit(q)
        title, symbol = texts.get(name, (None, None))
        given = raw[name]["value"] if isinstance(raw[name], Mapping) else raw[name]
        text = given if isinstance(given, str) else ""
        if text and not _literal(text):     # computed from other parameters: 4 significant digits
            v = float(f"{v:.4g}")
        rows.append({"title": (title or _link_length_title(study, name) or synthesis.input_title(study, name)
                               or param_title(name, unit)),
                     "name": symbol or param_symbol(name), "value": v,
                     "unit": unit, "given": text[:60] if _imperial(text) else ""})
    if rows:
        cols = [Column("title", "Параметр", fmt=_cell_html), Column("name", "Обозначение", fmt=_cell_html),
                Column("value", "Значение", fmt=as_written), Column("unit", "Единица")]
        if any(r["given"] for r in rows):      # a published example in inches, pounds: as it was given
            cols.append(Column("given", "Задано", fmt=lambda s: Markup(escape(s.replace("*", "·")))))
        out.append(Table("Исходные данные", cols, pd.DataFrame(rows), id="tab-given"))
    return out


def _link_length_title(study, name: str) -> str | None:
    """«длина звена 1 (кривошип)» for a length named by a link's number (l_1, l3); «длина стойки»
    for l_0 — instead of the bare «длина 1»."""
    letter, index, ru = param_parts(name)
    if ru != "длина" or not study.has_linkage:
        return None
    if not index.isdigit():
        return _segment_title(study.mechanism, index)
    if index == "0":
        return "длина стойки (расстояние между опорами)"
    link = next((l for l in study.mechanism.links if l.name == index), None)
    if link is None:
        return None
    title = Markup(link.title).striptags() if link.title else ""
    return f"длина звена {index}" + (f" ({title})" if title else "")


def _segment_title(mech, index: str) -> str | None:
    """The textbook name of a length between two points of the mechanism (l_OA, l_AS2):
    «длина кривошипа OA», «расстояние от точки A до центра масс шатуна», «расстояние между
    опорами O и C»; the link's number where its name is not known («длина звена 2 AB»)."""
    names = sorted({p for l in mech.links for p in l.points}, key=len, reverse=True)
    pts, rest = [], index
    while rest and len(pts) < 3:
        p = next((n for n in names if rest.startswith(n)), None)
        if p is None:
            return None
        pts.append(p)
        rest = rest[len(p):]
    if rest or len(pts) != 2:
        return None
    a, b = pts
    link = next((l for l in mech.links if a in l.points and b in l.points and not l.is_frame), None)
    if link is None:
        frame = next((l for l in mech.links if l.is_frame), None)
        return f"расстояние между опорами {a} и {b}" if frame and {a, b} <= set(frame.points) else None
    title = Markup(link.title).striptags() if link.title else ""
    whose = genitive(title) or f"звена {link.name}"
    shared = {p for l in mech.links if l is not link for p in l.points}
    own = [p for p in (a, b) if p not in shared]       # a point of this link only (no joint)
    if len(own) == 1:
        joint, pt = (b, a) if own[0] == a else (a, b)
        if pt == link.com:
            return f"расстояние от точки {joint} до центра масс {whose}"
        return f"расстояние от точки {joint} до точки {pt} {whose}"
    return f"длина {whose} {index}" if genitive(title) else f"длина {index} звена {link.name}"


def _literal(text: str) -> bool:
    """The parameter is given as a number with a unit (``"0.38 m"``), not computed by an
    expression over other parameters (``"h*l_1/sqrt(l_0^2 - l_1^2)"``)."""
    try:
        U.parse_quantity(text)
    except (CaseError, ValueError):
        return False
    return True


def _cell_html(x) -> Markup:
    """A cell already made safe HTML (a case title or symbol through ``inline_html``, or the
    derived symbol); plain derived titles are escaped."""
    return x if isinstance(x, Markup) else escape(x)


_IMPERIAL = {"in", "ft", "yd", "lb", "lbm", "lbf", "kip", "slug", "psi", "hp"}


def _imperial(text: str) -> bool:
    """A value written in British (US customary) units (``"2 in"``, ``"250 lbf"``)."""
    return any(t in _IMPERIAL for t in re.findall(r"[A-Za-z]+", text))


def _linkage_data(study) -> list:
    out = []
    mech = study.mechanism
    lrows = [{"n": l.name, "title": l.title or "—", "m": l.mass, "G": l.weight, "J": l.J_S}
             for l in mech.moving if l.mass is not None or l.weight is not None or l.J_S is not None]
    if lrows:
        out.append(Table("Массы и моменты инерции звеньев", [
            Column("n", "Звено"), Column("title", "Название"), Column("m", "Масса", "кг", sig=4),
            Column("G", "Вес", "Н", sig=4), Column("J", "<i>J</i><sub>S</sub>", "кг·м²", sig=4)],
            pd.DataFrame(lrows), id="tab-masses"))
    d = mech.driver
    if d.swing:
        text = (f"Ведущее звено — входное коромысло {d.link}, качающееся в диапазоне {swing_text(d)}: "
                f"прямой ход — {'по часовой стрелке' if d.direction < 0 else 'против часовой стрелки'} "
                f"от первого крайнего положения ко второму, обратный ход — в обратном направлении")
        if d.omega:
            text += f"; угловая скорость по модулю постоянна, ω<sub>1</sub>&nbsp;=&nbsp;{fmt(d.omega, digits=3)}&nbsp;рад/с"
        out.append(Paragraph(text + "."))
    elif d.rotary:
        # an input link the case names otherwise (a driving slotted link «кулиса», an eccentric
        # shaft): the note calls it «кривошип» by its role, said once here
        title = Markup(mech.link(d.link).title or "").striptags()
        named = title and not any(w in title.lower() for w in ("кривош", "ведущ"))
        head = Markup("Ведущее звено {0} — {1}; совершая полный оборот, оно служит кривошипом (далее — кривошип "
                      "{0})").format(d.link, title) if named else f"Ведущее звено — кривошип {d.link}"
        text = (f"{head}; начальный угол φ<sub>0</sub>&nbsp;=&nbsp;"
                f"{fmt_given(math.degrees(d.phi0) % 360.0)}°, вращение "
                f"{'по часовой стрелке' if d.direction < 0 else 'против часовой стрелки'}")
        if d.omega:
            text += (f", угловая скорость ω<sub>1</sub>&nbsp;=&nbsp;{fmt_given(d.omega)}&nbsp;рад/с "
                     f"(n<sub>1</sub>&nbsp;=&nbsp;{fmt_given(d.omega * 30 / math.pi)}&nbsp;об/мин)")
        out.append(_given_paragraph(text + "."))
    else:
        lo, hi = d.q_range
        out.append(_given_paragraph(f"Ведущее звено — гидроцилиндр {d.link}–{d.rod}; длина изменяется от "
                                    f"{fmt(lo, digits=3)} до {fmt(hi, digits=3)}&nbsp;м."))
    return out


def _determined(study, names) -> str:
    """What the note determines, from the sections it holds (a note without a force analysis
    does not promise the forces in the pairs); dimensions fitted to the case's conditions are
    parameters that give the required operation."""
    what = []
    if "structure" in names:
        what.append("его строение")
    if "kinematics" in names:
        what.append("движение звеньев")
    if "forces" in names:
        what.append("силы, действующие в кинематических парах")
    if not what or set(names) - {"structure", "kinematics", "forces"} or (study.has_linkage and study.fits):
        what.append("параметры, обеспечивающие требуемый режим работы")
    if len(what) == 1:
        return what[0]
    # a participial phrase («силы, действующие в кинематических парах») is closed by a comma before «и»
    return ", ".join(what[:-1]) + (", и " if "," in what[-2] else " и ") + what[-1]


def _cite(start: str) -> int:
    """The number [n] of the reference whose entry begins with ``start`` (the list's order)."""
    start = _typeset(start)
    return next(k for k, r in enumerate(REFERENCES, 1) if r.startswith(start))


def _introduction(study, names, built) -> list:
    st = study.structure if study.has_linkage else None
    parts = [Paragraph(
        "Теория механизмов и машин изучает строение, кинематику и динамику механизмов и общие методы их "
        "анализа и синтеза [1, 3]. Курсовой проект закрепляет эти методы на примере конкретного механизма [2, 4]: "
        f"определяются {_determined(study, names)}.")]
    what = ", ".join(s.title.lower() for s in built)
    if st is not None:
        from .sections.structure import decomposition
        mech = (f" Исследуемый механизм имеет {plural(st.n, 'подвижное звено', 'подвижных звена', 'подвижных звеньев')}"
                f" и структурную формулу {decomposition(study)[1]}.")
        method = (" Аналитические расчёты выполнены точно (положения групп Ассура — в замкнутом виде, аналоги — "
                  "из линейных систем групп); графические построения выполнены в масштабе и сопоставлены с "
                  "аналитическими результатами.")
    else:
        mech = ""
        method = (" Расчёты выполнены аналитически по точным формулам; графические построения выполнены в "
                  "масштабе и сопоставлены с аналитическими результатами.")
    rules = (f" Схемы выполнены условными графическими обозначениями по ГОСТ\u00a02.770 [{_cite('ГОСТ 2.770')}], "
             f"записка оформлена по ГОСТ\u00a07.32 [{_cite('ГОСТ 7.32')}].")
    done = f"выполнен раздел «{built[0].title}»" if len(built) == 1 else f"выполнены: {what}"   # «выполнены: синтез …» of one
    parts.append(Paragraph(f"В пояснительной записке {done}.{mech}{method}{rules}"))
    if "dynamics" in names:
        chain = SECTIONS["dynamics"][0].drive_chain(study)
        if chain:
            parts.append(Paragraph(chain))
    return parts


def _conclusion(study, names) -> list:
    """ЗАКЛЮЧЕНИЕ: the key results, contributed by each section module (``conclusion_lines``)."""
    out = []
    for n in names:
        mod = SECTIONS[n][0]
        if hasattr(mod, "conclusion_lines"):
            out += [Paragraph(line) for line in mod.conclusion_lines(study)]
    return out
