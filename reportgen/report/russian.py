"""Russian wording helpers for the generated text: numeral–noun agreement, the textbook symbol
and the Russian name of a case parameter, the student's number of a report position.

Agreement rule (Розенталь Д. Э. Справочник по правописанию и стилистике, §185): the noun after a
numeral takes the nominative singular after 1 (but not 11), the genitive singular after 2–4 (but
not 12–14), the genitive plural otherwise: «21 уравнение», «3 уравнения», «5 уравнений».
"""
from __future__ import annotations

import re

from markupsafe import Markup, escape

from ..style.numbers import fmt, position_names  # noqa: F401  (re-exported)

NBSP = "\u00a0"


def plural_form(n: int, one: str, few: str, many: str) -> str:
    """The noun form agreeing with the integer ``n`` (one: 1, 21; few: 2–4, 22; many: 0, 5–20)."""
    n = abs(int(n))
    if n % 10 == 1 and n % 100 != 11:
        return one
    if 2 <= n % 10 <= 4 and not 12 <= n % 100 <= 14:
        return few
    return many


def plural(n: int, one: str, few: str, many: str) -> str:
    """«n noun» with agreement and a non-breaking space: plural(3, "уравнение", "уравнения",
    "уравнений") → "3 уравнения"."""
    return f"{int(n)}{NBSP}{plural_form(n, one, few, many)}"


# leading part of a parameter name → (textbook letter, Russian name); checked longest first
_HEADS = {
    "Omega": ("Ω", "угловая частота"),
    "Om": ("Ω", "угловая частота"),
    "omega": ("ω", "угловая скорость"),
    "om": ("ω", "угловая скорость"),
    "sigma": ("σ", "напряжение"),
    "tau": ("τ", "касательное напряжение"),
    "lambda": ("λ", "отношение"),
    "lam": ("λ", "отношение"),
    "kappa": ("κ", "коэффициент"),
    "zeta": ("ζ", "коэффициент"),
    "nu": ("ν", "коэффициент"),
    "Phi": ("Φ", "сила инерции"),
    "Psi": ("Ψ", "угол"),
    "Delta": ("Δ", "приращение"),
    "delta": ("δ", "коэффициент"),
    "alpha": ("α", "угол"),
    "beta": ("β", "угол"),
    "gamma": ("γ", "угол"),
    "theta": ("θ", "угол"),
    "phi": ("φ", "угол"),
    "psi": ("ψ", "угол"),
    "eps": ("ε", "угловое ускорение"),
    "rho": ("ρ", "плотность"),
    "mu": ("μ", "коэффициент"),
    "eta": ("η", "коэффициент полезного действия"),
    "l": ("l", "длина"),
    "L": ("l", "длина"),
    "X": ("x", "координата по оси x"),
    "x": ("x", "координата по оси x"),
    "Y": ("y", "координата по оси y"),
    "y": ("y", "координата по оси y"),
    "S": ("S", "ход (длина) ведущего звена"),
    "H": ("H", "ход"),
    "m": ("m", "масса"),
    "J": ("J", "момент инерции"),
    "G": ("G", "вес"),
    "F": ("F", "сила"),
    "P": ("P", "сила"),
    "M": ("M", "момент"),
    "n": ("n", "частота вращения"),
    "D": ("D", "диаметр"),
    "d": ("d", "диаметр"),
    "e": ("e", "эксцентриситет"),
    "h": ("h", "размер"),
    "a": ("a", "размер"),
    "b": ("b", "размер"),
    "c": ("c", "размер"),
    "r": ("r", "радиус"),
    "R": ("R", "радиус"),
}
_SUFFIX_RU = {"min": "наименьшее значение", "max": "наибольшее значение", "p": "рабочее значение"}
_NAME = re.compile(r"^([A-Za-z]+?)_?([A-Za-z0-9]*)$")


def _split(name: str) -> tuple[str, str, str]:
    """(head, index, Russian name) of a parameter name: "l_AB" → ("l", "AB", …), "phiBD" →
    ("φ", "BD", …), "X01" → ("x", "01", …), "S_min" → ("S", "min", …)."""
    head, _, tail = name.partition("_")
    for key in sorted(_HEADS, key=len, reverse=True):
        rest = head[len(key):]
        if head.startswith(key) and (not rest or rest[0].isupper() or rest[0].isdigit()):
            letter, ru = _HEADS[key]
            return letter, rest + tail, ru
    return head, tail.replace("_", ""), "параметр"


def param_parts(name: str) -> tuple[str, str, str]:
    """(letter, index, Russian name of the letter) of a parameter name: l_3 → ("l", "3", "длина")."""
    return _split(name)


def param_symbol(name: str) -> Markup:
    """Textbook symbol of a parameter in HTML: l_AB → <i>l</i><sub>AB</sub>, phi_P6 → φ<sub>P6</sub>;
    a spelled capital Greek letter upright (Om, Omega → Ω: ГОСТ 2.321 writes capital Greek upright)."""
    letter, index, _ = _split(name)
    head = Markup("{}") if "\u0391" <= letter <= "\u03a9" else Markup("<i>{}</i>")
    if index:
        return (head + Markup("<sub>{}</sub>")).format(letter, index)
    return head.format(letter)


# the Russian name of a parameter with no name of its own («размер», «параметр») told by its unit
_BY_UNIT = {"кг/с²": "жёсткость", "Н/м": "жёсткость", "кг/с": "коэффициент вязкого сопротивления",
            "Н·с/м": "коэффициент вязкого сопротивления", "рад/с": "угловая скорость",
            "рад/с²": "угловое ускорение", "об/мин": "частота вращения", "Дж": "энергия", "кДж": "энергия",
            "Па": "давление", "кПа": "давление", "МПа": "напряжение", "Н": "сила", "кН": "сила",
            "кг": "масса", "кг·м²": "момент инерции", "с": "время", "Вт": "мощность", "кВт": "мощность",
            "Гц": "частота"}


# genitive singular of the nouns and adjectives of textbook link names (кривошип → кривошипа)
_GEN = {"кривошип": "кривошипа", "шатун": "шатуна", "коромысло": "коромысла", "ползун": "ползуна",
        "кулиса": "кулисы", "камень": "камня", "шток": "штока", "поршень": "поршня", "цилиндр": "цилиндра",
        "толкатель": "толкателя", "раскос": "раскоса", "рычаг": "рычага", "поводок": "поводка",
        "балансир": "балансира", "тяга": "тяги", "кулачок": "кулачка", "звено": "звена", "стойка": "стойки",
        "вал": "вала", "ползушка": "ползушки", "серьга": "серьги", "гидроцилиндр": "гидроцилиндра"}
_ADJ_GEN = (("ое", "ого"), ("ее", "его"), ("ый", "ого"), ("ой", "ого"), ("ий", "его"), ("ая", "ой"), ("яя", "ей"))


def genitive(title: str) -> str | None:
    """The genitive of a link's name up to its first noun, the rest kept («камень кулисы» →
    «камня кулисы», «выходное коромысло» → «выходного коромысла», «кривошип (эксцентриковый вал)»
    → «кривошипа»); None when a word is not known."""
    words = re.split(r"\s*\(", title.strip(), maxsplit=1)[0].split()
    out = []
    for i, w in enumerate(words):
        low = w.lower()
        if low in _GEN:
            return " ".join(out + [_GEN[low]] + [x for x in words[i + 1:] if not x[:1].isupper()])
        end = next((g for a, g in _ADJ_GEN if low.endswith(a)), None)
        if end is None:
            return None
        out.append(low[:-2] + end)
    return None


def param_title(name: str, unit: str | None = None) -> str:
    """Russian name of a parameter derived from its symbol: l_AB → «длина звена AB»,
    X_C → «координата по оси x точки C», S_min → «ход (длина) ведущего звена, наименьшее значение»;
    a letter with no name of its own (a, c, k, A) named by its ``unit`` when that tells
    (c in кг/с² → «жёсткость»)."""
    letter, index, ru = _split(name)
    if ru in ("размер", "параметр") and unit in _BY_UNIT:
        ru = _BY_UNIT[unit]
    if not index:
        return ru
    if index in _SUFFIX_RU:
        return f"{ru}, {_SUFFIX_RU[index]}"
    if ru.startswith("координата"):
        return f"{ru} точки {index}"
    if ru == "угол":
        return f"угол {index}"
    return f"{ru} {index}"


_COND = re.compile(r"^\s*vq([xy])_(\w+)\s*(>=|>|<=|<)\s*0\s*$")
_COND_S = re.compile(r"^\s*vqs_(\w+)\s*(>=|>|<=|<)\s*0\s*$")
_COND_W = re.compile(r"^\s*wq_(\w+)\s*(>=|>|<=|<)\s*0\s*$")
_OPS = {">=": "≥", "<=": "≤", "!=": "≠", "==": "="}
_TOKEN = re.compile(r"\b(vq|aq|v|a|x|y|phi|wq|eq|w|e)([xy]?)_(\w+)\b")


def condition_text(text: str) -> str:
    """A load's condition written for a student (plain text, no identifiers): "vqx_H >= 0" →
    «при движении точки H в положительном направлении оси x»; other expressions get Greek
    letters and ≥/≤ with the point as a subscript-like suffix («φ(3) ≥ …»)."""
    m = _COND.match(text)
    if m:
        axis, point, op = m.groups()
        sense = "положительном" if op in (">=", ">") else "отрицательном"
        return f"при движении точки {point} в {sense} направлении оси {axis}"
    out = text
    for op, sym in _OPS.items():
        out = out.replace(op, sym)
    plain = {"vq": "Vq", "aq": "aq", "wq": "ωq", "eq": "εq", "phi": "φ", "w": "ω", "e": "ε"}
    out = _TOKEN.sub(lambda m: f"{plain.get(m.group(1), m.group(1))}{m.group(2)}({m.group(3)})", out)
    return "при " + out


_COLUMN = re.compile(r"^(vq|aq|wq|eq|phi|x|y|s)([xys]?)_(\w+)$")
_PRIME = {"vq": "′", "aq": "″", "wq": "′", "eq": "″"}
_CMP = re.compile(r"(<=|>=|<|>)")


def column_html(name: str) -> Markup | None:
    """Textbook symbol of a kinematic column: x_D → <i>x</i><sub>D</sub>, vqx_H → <i>x</i>′<sub>H</sub>
    (analogue: derivative with respect to the generalized coordinate), phi_3 → φ<sub>3</sub>,
    wq_3 → φ′<sub>3</sub>, s_50 → <i>s</i><sub>50</sub>; None for a name that is not a column."""
    m = _COLUMN.match(name.strip())
    if not m:
        return None
    head, axis, sub = m.groups()
    if head in ("vq", "aq"):
        if axis not in ("x", "y", "s"):
            return None
        return Markup("<i>{}</i>{}<sub>{}</sub>").format(axis, _PRIME[head], sub)
    if axis:
        return None
    if head in ("wq", "eq"):
        return Markup("φ{}<sub>{}</sub>").format(_PRIME[head], sub)
    if head == "phi":
        return Markup("φ<sub>{}</sub>").format(sub)
    return Markup("<i>{}</i><sub>{}</sub>").format(head, sub)


def condition_html(text: str, rhs_value: float | None = None, unit: str = "") -> Markup:
    """A load's condition for a student (escaped HTML, no identifiers).  A sign condition on a
    velocity analogue reads «при движении точки H в положительном направлении оси x»; a bound on
    one column whose right side holds only parameters reads «при <i>x</i><sub>D</sub> &gt; −0,171 м»
    with the right side's value ``rhs_value`` (already in ``unit``) instead of the parameter names;
    anything else is written with :func:`expr_html`."""
    if _COND.match(text):
        return Markup(escape(condition_text(text)))
    m = _COND_S.match(text)
    if m:           # the sign of a slide's analog: the slider moves one way along its guide
        name, op = m.groups()
        return Markup("при {} <i>s</i><sub>{}</sub>").format(
            "возрастании" if op in (">=", ">") else "убывании", name)
    m = _COND_W.match(text)
    if m:           # the sign of a link's angular analog: the link turns one way (angles ccw-positive)
        name, op = m.groups()
        return Markup("при повороте звена {} {} часовой стрелки").format(
            name, "против" if op in (">=", ">") else "по")
    parts = _CMP.split(text)
    if len(parts) == 3:
        lhs, op, rhs = (x.strip() for x in parts)
        left = column_html(lhs) or expr_html(lhs)
        if rhs_value is not None:
            unit = "" if unit == "1" else unit          # a dimensionless side has no unit
            right = Markup(escape(fmt(rhs_value, sig=4))) + (Markup(NBSP) + unit if unit and unit != "°"
                                                             else Markup(unit))
        else:
            right = expr_html(rhs)
        return Markup("при {} {} {}").format(left, _OPS.get(op, op), right)
    return Markup("при {}").format(expr_html(text))


_EXPR_TOKEN = re.compile(r"(\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)|([A-Za-z_][A-Za-z0-9_]*)|(>=|<=|!=|==|\*|[^\sA-Za-z0-9_])|(\s+)")
_UNITS_RU = {"m": "м", "mm": "мм", "cm": "см", "deg": "°", "rad": "рад", "kg": "кг", "N": "Н", "s": "с",
             "Pa": "Па", "MPa": "МПа", "rpm": "об/мин"}


_FUNCS_RU = {"sin": "sin", "cos": "cos", "tan": "tg", "cot": "ctg", "asin": "arcsin", "acos": "arccos",
             "atan": "arctg", "atan2": "arctg", "exp": "exp", "log": "ln", "ln": "ln", "sqrt": "√",
             "abs": "abs", "sinh": "sh", "cosh": "ch", "tanh": "th"}


def expr_html(text: str, symbols: dict[str, Markup] | None = None) -> Markup:
    """A case expression in textbook notation (escaped HTML): "phi_6 = phi_P6" → φ<sub>6</sub> =
    φ<sub>P6</sub>, "y_56 = 0.2 m" → <i>y</i><sub>56</sub> = 0,2 м; ``*`` → ·, ``>=`` → ≥, a power
    ``r^2`` → <i>r</i><sup>2</sup>, functions upright in Russian notation (cos, tg, arctg, √).
    ``symbols``: a parameter's own symbol given by the case (``symbol`` of ``[parameters]``, safe
    HTML) written instead of the one read from its name (S_LOW → <i>s</i><sub>н</sub>, not S<sub>LOW</sub>)."""
    out = []
    prev_number = pending = power = False
    for num, ident, op, space in _EXPR_TOKEN.findall(text):
        if space:
            if prev_number:
                pending = True
            else:
                out.append(Markup(" "))
            continue
        if ident and prev_number and ident in _UNITS_RU:
            unit = _UNITS_RU[ident]
            out.append(Markup(unit if unit == "°" else NBSP + unit))
            prev_number = pending = False
            continue
        if op == "^":
            power = True
            continue
        if pending:
            out.append(Markup(" "))
        prev_number, pending = bool(num), False
        if num:
            piece = escape(num.replace(".", ","))
        elif ident in _FUNCS_RU:
            piece = Markup(_FUNCS_RU[ident])
        elif ident:
            piece = symbols[ident] if symbols and ident in symbols else param_symbol(ident)
        else:
            piece = escape(_OPS.get(op, {"*": "·", "-": "−"}.get(op, op)))
        if power:
            piece = Markup("<sup>{}</sup>").format(piece) if (num or ident) else Markup("^") + piece
            power = False
        out.append(piece)
    return Markup("").join(out)


def flag_group(study, key: str) -> str:
    """The structural group a transmission-angle flag ``mu_2_3`` belongs to, as chapter 1 names it:
    «(2,3)», or «(1,2,3)» for the dyad of an actuator's initial mechanism."""
    from ..mechanism.structure import decomposition
    links = set(key[3:].split("_"))
    for row in decomposition(study.structure, study.mechanism.driver)[0]:
        if links <= set(row["g"].strip("()").split(",")):
            return row["g"]
    return "(" + ",".join(key[3:].split("_")) + ")"


def flag_where(study, key: str) -> str:
    """«в группе (4,5)», or «в начальном механизме (1,2,3)» where the flagged dyad lies in an
    actuator's initial mechanism (chapter 1 calls it so, not a group)."""
    from ..mechanism.structure import decomposition
    g = flag_group(study, key)
    initial = study.mechanism.driver.kind == "actuator" and \
        g == decomposition(study.structure, study.mechanism.driver)[0][0]["g"]
    return ("в начальном механизме " if initial else "в группе ") + g
