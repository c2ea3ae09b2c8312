"""Helpers shared by the section builders: symbols, chosen position, chunked tables."""
from __future__ import annotations

import math
from itertools import accumulate

import pandas as pd
from markupsafe import Markup

from ...case import units as U
from ...style.numbers import fmt
from ..document import Column, Section
from ..russian import column_html, expr_html, position_names

MAX_COLS = 8


def tex_point(p: str) -> str:
    """LaTeX of a point name: S2 → S_{2}, 23 → 23, O1 → O_{1}."""
    head = p.rstrip("0123456789")
    tail = p[len(head):]
    return f"{head}_{{{tail}}}" if head and tail else p


def html_point(p: str) -> str:
    head = p.rstrip("0123456789")
    tail = p[len(head):]
    return f"<i>{head}</i><sub>{tail}</sub>" if head and tail else f"<i>{p}</i>"


def sub(sym: str, index: str) -> str:
    """HTML symbol with subscript: sub('φ', '3') → φ<sub>3</sub>."""
    return f"<i>{sym}</i><sub>{index}</sub>"


def chosen_position(study) -> str:
    """The report position for which plans and formulas are shown ([report] position)."""
    node = study.root.table("report")
    labels = list(study.kinematics["pos"])
    lab = node.string("position")
    if lab is None:
        return "f" if "f" in labels else (labels[1] if len(labels) > 1 else labels[0])
    if lab not in labels:
        raise node.error("position", f"нет положения «{lab}»", expected="подпись положения: " + ", ".join(labels))
    return lab


def pos_no(study, lab: str) -> str:
    """The student's number of a report position (extra positions named in the case, e.g. "f",
    are numbered after the regular ones: report/russian.position_names)."""
    return position_names(study.kinematics["pos"]).get(str(lab), str(lab))


def pos_fmt(study):
    """Column formatter printing positions by number."""
    names = position_names(study.kinematics["pos"])
    return lambda lab: names.get(str(lab), str(lab))


def position_lead(study) -> list[Column]:
    """The lead columns of a table by positions: «№» (the position's number) and φ (or S)."""
    qkey, qhead, qunit, qfmt = q_header(study)
    return [Column("pos", "№", fmt=pos_fmt(study)), Column(qkey, qhead, qunit, **qfmt)]


def input_word(driver, case: str = "nom") -> str:
    """The rotating input link in a Russian case: «кривошип» or, for an input link swung over a
    range, «входное коромысло» (nom, gen, dat)."""
    words = {"nom": ("кривошип", "входное коромысло"), "gen": ("кривошипа", "входного коромысла"),
             "dat": ("кривошипу", "входному коромыслу")}
    return words[case][1 if driver.swing else 0]


def q_degrees(study, q: float) -> float:
    """An input angle as the note prints it: a crank's angle from the cycle's start, an input
    rocker's own angle φ (its range is given in these angles)."""
    d = study.mechanism.driver
    return math.degrees(q) if d.swing else math.degrees(q - study.grid.start)


def swing_text(driver) -> str:
    """«φ = 25…85° (размах 60°)» of an input rocker."""
    from ...style.numbers import fmt
    lo, hi = (math.degrees(x) for x in driver.q_range)
    return f"φ&nbsp;=&nbsp;{fmt(lo, digits=1)}…{fmt(hi, digits=1)}° (размах {fmt(hi - lo, digits=1)}°)"


def q_header(study) -> tuple[str, str, str, dict]:
    """Column key, header and unit of the generalised coordinate for tables."""
    if study.mechanism.driver.rotary:
        return "q_deg", "<i>φ</i>", "град", dict(digits=1)
    return "q", "<i>S</i>", "м", dict(digits=3)


def balanced_parts(n: int, most: int = MAX_COLS) -> list[int]:
    """Widths of the parts when ``n`` columns split into the fewest parts of at most ``most``
    columns: nearly equal, the wider first (13 at 6 → 5, 4, 4)."""
    parts = max(1, math.ceil(n / max(1, most)))
    return [n // parts + (1 if k < n % parts else 0) for k in range(parts)]


def chunked_tables(sec: Section, caption: str, df: pd.DataFrame, columns: list[Column], lead: list[Column],
                   id_prefix: str, per: int = MAX_COLS, note: str | None = None) -> list[str]:
    """Split a wide table into tables of at most ``per`` data columns, each with the lead
    columns repeated; returns the ids. ``note`` goes under the last part. The parts are of
    nearly equal width (9 columns at
    ``per`` = 8 → 5 + 4, never 8 + a part of one column)."""
    ids = []
    ends = list(accumulate([0] + balanced_parts(len(columns), per)))
    chunks = [columns[a:b] for a, b in zip(ends[:-1], ends[1:])] or [[]]
    for k, ch in enumerate(chunks):
        tid = f"{id_prefix}-{k + 1}" if len(chunks) > 1 else id_prefix
        cap = caption if len(chunks) == 1 else f"{caption} (часть\u00a0{k + 1})"  # «1)» never alone on a line
        sec.table(cap, lead + ch, df, id=tid, note=note if k == len(chunks) - 1 else None)
        ids.append(tid)
    return ids


UNIT_RU = {
    U.LENGTH: "м", U.MASS: "кг", U.FORCE: "Н", U.MOMENT: "Н·м", U.INERTIA: "кг·м²",
    U.VELOCITY: "м/с", U.ACCELERATION: "м/с²", U.ANGULAR_VELOCITY: "рад/с", U.PRESSURE: "Па",
    U.TIME: "с", U.DENSITY: "кг/м³", U.ANGULAR_ACCELERATION: "рад/с²",
    (0, 1, -2, 0): "Н/м", (0, 1, -1, 0): "Н·с/м",        # stiffness of a spring, viscous damping
}


def value_with_unit(q) -> tuple[float, str]:
    """A parameter (expr.Q) in the unit it is usually printed in."""
    dim = tuple(q.dim)
    v = float(q.value)
    if dim == U.ANGLE:
        return math.degrees(v), "°"
    if dim[:3] == (0, 0, 0):
        return v, "—"
    if dim == U.PRESSURE and abs(v) >= 1e4:      # pressures of machines in МПа (1,2 МПа, not 1,2·10⁶ Па)
        return v / 1e6, "МПа"
    return v, UNIT_RU.get(dim, U.format_dim(dim))


def as_written(x) -> str:
    """A given value as the case writes it (shortest representation, no padding zeros):
    0.11 → «0,11», 8.0 → «8», 20.0000001 → «20»; a value no one writes as a decimal (a case's
    «1/15», a repeating fraction of 8 or more significant digits) as the simple fraction it is:
    «1/15», not «0,06666666667»."""
    t = f"{float(x):.10g}"
    if "e" not in t and len(t.lstrip("-0.").replace(".", "")) >= 8:
        from fractions import Fraction
        f = Fraction(float(x)).limit_denominator(1000)
        if f.denominator > 1 and abs(float(f) - float(x)) <= 1e-12 * abs(float(x)):
            return f"{'−' if f < 0 else ''}{abs(f.numerator)}/{f.denominator}"
    return fmt(float(t), digits=len(t.split(".")[1]) if "." in t and "e" not in t else 0, sig=None,
               exp_from=1e10 if "e" not in t else 1e6)


def fit_condition(study, fit) -> tuple[Markup, Markup | None, Markup]:
    """A fitted dimension's condition as the assignment table writes its data, its title, the position:
    the left side in textbook symbols (:func:`russian.column_html`), a right side that is one
    parameter of the case by its value and unit, and that parameter's Russian title when the case
    gives one («высота шарнира 56 в рабочем положении», «y<sub>56</sub> = 0,4 м», not the case's
    own name «Y_P56»; else None); the position ``at`` in the symbols the case gives (S_min → S<sub>min</sub>)."""
    texts = study.spec.parameter_texts()
    symbols = {k: sym for k, (_, sym) in texts.items() if sym}
    lhs, _, rhs = (x.strip() for x in fit.condition.partition("="))
    title = None
    left = column_html(lhs) or expr_html(lhs, symbols)
    cond = Markup("{}&nbsp;=&nbsp;{}").format(left, expr_html(rhs, symbols))
    if rhs in study.params:
        v, unit = value_with_unit(study.params[rhs])
        unit = "" if unit == "—" else unit if unit == "°" else "\u00a0" + unit
        cond = Markup("{}&nbsp;=&nbsp;{}{}").format(left, as_written(v), unit)
        title = texts.get(rhs, (None, None))[0]
    return cond, title, expr_html(fit.at, symbols)


def tex_given(x) -> str:
    """A given value as written, for a TeX formula (the decimal comma braced): 3.5 → «3{,}5»."""
    return as_written(x).replace(",", "{,}")


def pair_label(point: str, mark: str, a: str, b: str, clash: bool) -> str:
    """The designation of a pair in the note's tables: «D (П)» by its point and kind mark; where
    two pairs would read the same (a stone and a slider at one point D), the point carries the
    numbers of the pair's links: «D<sub>34</sub> (П)»."""
    head = f"{point}<sub>{a}{b}</sub>" if clash else point
    return f"{head} ({mark})" if mark else head

