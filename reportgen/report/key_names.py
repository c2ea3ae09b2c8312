"""The glossary of the answer key: every scalar an analysis returns (``scalars``), by the name a
teacher reads — its Russian name, the textbook symbol (HTML), the unit as the note prints it, the
number format, the key of the position where an extreme occurs, the group of the results table,
and, for a switch or a yes/no value, the words that say it.

The analyses stay free of presentation: this table is the only place where their identifiers meet
Russian text.  Units follow the note (docs/outputs.md gives the SI units of the scalars): angles
in degrees, cam sizes in millimetres (the cam chapter prints mm), gear sizes already in mm,
pressures in MPa.  A key with no entry is an error: ``tests/test_key_names.py`` runs every case in
``cases/`` through :func:`entry`.  The symbols follow Артоболевский И. И., «Теория механизмов и
машин» and the note's own notation.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace

from markupsafe import escape

__all__ = ["Entry", "entry", "GLOSSARY"]


@dataclass(frozen=True)
class Entry:
    name: str                    # Russian name (static HTML)
    sym: str = ""                # textbook symbol (static HTML)
    unit: str = ""               # unit as printed; "" for a dimensionless value
    conv: str = ""               # "deg": rad → °, "mm": m → мм, "MPa": Па → МПа, "stroke": m → мм or rad → °
    sig: int | None = 5          # significant digits (when ``digits`` is None)
    digits: int | None = None    # fixed decimals
    where: str | None = None     # the scalar holding the position of this extreme
    group: str = ""              # heading of the table the row goes to (in the kind's order)
    words: tuple | dict | None = None   # bool → (true, false); str → {value: words, "" — no row}
    same_as: str | None = None   # shown only when it differs from this key's value
    hide_if: tuple | None = None # (key, value): no row when that scalar has that value (the chosen method)
    position: bool = False       # the position of another key's extreme (shown in its row)
    swing: tuple | None = None   # (name, symbol) when a "stroke" is a swing (a rocker's angle)
    given: bool = False          # a value of the case: printed as the case writes it (0,11, not 0,1100)
    actuator: tuple | None = None  # (name, symbol) when the input is an actuator's length (F, not M_ур)
    contact: dict | None = None  # a cam's follower contact → name, when the name depends on it


def _e(name, sym="", unit="", **kw) -> Entry:
    return Entry(name, sym, unit, **kw)


def _pos() -> Entry:
    return Entry("", position=True)


def _i(letter: str, sub: str = "") -> str:
    """An italic Latin symbol with an upright subscript: <i>J</i><sub>I</sub>."""
    return f"<i>{letter}</i>" + (f"<sub>{sub}</sub>" if sub else "")


# ---------------------------------------------------------------------------- dynamics
_DG0 = "Изменение кинетической энергии"
_DG1, _DG2, _DG3, _DG4, _DG5 = ("Работы, моменты и мощности", "Момент инерции маховика",
                                "Скорость звена приведения", "Размеры маховика", "Маховик на валу двигателя")
_METHODS = {"exact": "точный (по уравнению кинетической энергии)", "mertsalov": "метод Мерцалова",
            "wittenbauer": "метод Виттенбауэра", "wittenbauer_linear": "метод Виттенбауэра с наклонами 1 ± δ"}
_MNAME = {"exact": "точно", "mertsalov": "по Мерцалову", "wittenbauer": "по Виттенбауэру",
          "wittenbauer_linear": "по Виттенбауэру с наклонами 1 ± δ"}

DYNAMICS = {
    "cycle_length": _e("Длина цикла", "Φ", "°", conv="deg", digits=0, group=_DG1),
    "omega_m": _e("Средняя угловая скорость звена приведения (задана)", "ω<sub>ср</sub>", "рад/с", group=_DG1),
    "delta": _e("Коэффициент неравномерности хода (задан)", "δ", sig=4, group=_DG1, given=True),
    "n_switching": _e("Число точек переключения нагрузок за цикл", "", sig=None, digits=0, group=_DG1),
    "balance": _e("Постоянный приведённый момент", "", group=_DG1,
                  words={"drive": "движущий (момент сопротивления задан)",
                         "resistance": "сопротивления (движущие силы заданы)"}),
    "A_d": _e("Работа движущих сил за цикл", _i("A", "д"), "Дж", group=_DG1),
    "A_c": _e("Работа сил сопротивления за цикл", _i("A", "с"), "Дж", group=_DG1),
    "M_d": _e("Приведённый движущий момент (средний за цикл)", _i("M", "д"), "Н·м", group=_DG1),
    "M_c": _e("Приведённый момент сил сопротивления (средний за цикл)", _i("M", "с"), "Н·м", group=_DG1),
    "P_d": _e("Средняя мощность движущих сил", _i("P", "д"), "Вт", group=_DG1),
    "P_c": _e("Средняя мощность сил сопротивления", _i("P", "с"), "Вт", group=_DG1),
    "t_cycle": _e("Время цикла", _i("t", "ц"), "с", sig=4, group=_DG1),
    "dT_max": _e("Наибольшее изменение кинетической энергии машины", "Δ" + _i("T", "max"), "Дж",
                 where="q_dT_max", group=_DG0),
    "dT_min": _e("Наименьшее изменение кинетической энергии машины", "Δ" + _i("T", "min"), "Дж",
                 where="q_dT_min", group=_DG0),
    "dT_I_max": _e("Наибольшее изменение кинетической энергии первой группы звеньев", "Δ" + _i("T", "I max"),
                   "Дж", where="q_dT_I_max", group=_DG0),
    "dT_I_min": _e("Наименьшее изменение кинетической энергии первой группы звеньев", "Δ" + _i("T", "I min"),
                   "Дж", where="q_dT_I_min", group=_DG0),
    "dT_I_range": _e("Наибольший перепад кинетической энергии первой группы", "Δ" + _i("T", "I нб"), "Дж",
                     group=_DG0),
    "T0_exact": _e("Постоянная интеграла энергии: ½(" + _i("J", "I") + " + " + _i("J", "II") + ")ω² = "
                   + _i("T", "0") + " + " + _i("A", "Σ"), _i("T", "0"), "Дж", group=_DG0),
    "wittenbauer_K": _e("Отрезок до точки K касательной на оси Δ" + _i("T") + " (Виттенбауэр)", _i("OK"), "Дж",
                        group=_DG2),
    "wittenbauer_L": _e("Отрезок до точки L касательной на оси Δ" + _i("T") + " (Виттенбауэр)", _i("OL"), "Дж",
                        group=_DG2),
    "wittenbauer_KL": _e("Отрезок KL на оси Δ" + _i("T") + " (Виттенбауэр)", _i("KL"), "Дж", group=_DG2),
    "J_O": _e("Заданный приведённый момент инерции вращающихся масс", _i("J", "O"), "кг·м²", group=_DG2, given=True),
    "J_crank": _e("Момент инерции кривошипа", _i("J", "кр"), "кг·м²", group=_DG2),
    "J_I_const": _e("Постоянная часть момента инерции первой группы", _i("J", "I,0"), "кг·м²", group=_DG2),
    "method": _e("Метод расчёта маховика", "", group=_DG2, words=_METHODS),
    "J_I": _e("Требуемый момент инерции первой группы звеньев", _i("J", "I"), "кг·м²", group=_DG2),
    "J_fly": _e("Момент инерции маховика", _i("J", "доп"), "кг·м²", group=_DG2),
    "fw_needed": _e("Маховик", "", group=_DG2, words=("нужен", "не нужен")),
    "delta_achieved": _e("Коэффициент неравномерности при точном движении с принятым " + _i("J", "I"),
                         "δ<sub>факт</sub>", sig=5, group=_DG2),
    "omega_max": _e("Наибольшая угловая скорость звена приведения", "ω<sub>max</sub>", "рад/с",
                    where="q_omega_max", group=_DG3),
    "omega_min": _e("Наименьшая угловая скорость звена приведения", "ω<sub>min</sub>", "рад/с",
                    where="q_omega_min", group=_DG3),
    "omega_max_exact": _e("Наибольшая угловая скорость при точном движении", "ω<sub>max</sub>", "рад/с",
                          same_as="omega_max", group=_DG3),
    "omega_min_exact": _e("Наименьшая угловая скорость при точном движении", "ω<sub>min</sub>", "рад/с",
                          same_as="omega_min", group=_DG3),
    "fw_v_limit": _e("Допускаемая окружная скорость обода", "[" + _i("v") + "]", "м/с", sig=3, group=_DG4, given=True),
    "fw_v_exceeds": _e("Окружная скорость обода выше допускаемой", "", group=_DG4,
                       words=("да — превышена", "нет")),
    "J_fly_given": _e("Заданный момент инерции маховика (обратная задача)", _i("J", "доп"), "кг·м²", group=_DG3),
    "J_I_inverse": _e("Момент инерции первой группы при заданном маховике", _i("J", "I"), "кг·м²", group=_DG3),
    "delta_inverse": _e("Коэффициент неравномерности при заданном маховике", "δ", sig=4, group=_DG3),
    "omega_max_inverse": _e("Наибольшая угловая скорость при заданном маховике", "ω<sub>max</sub>", "рад/с",
                            group=_DG3),
    "omega_min_inverse": _e("Наименьшая угловая скорость при заданном маховике", "ω<sub>min</sub>", "рад/с",
                            group=_DG3),
    "fw_ratio": _e("Передаточное отношение от вала маховика к кривошипу", _i("u"), sig=4, group=_DG5,
                   hide_if=("fw_ratio", 1.0)),           # the flywheel on the crank: nothing to add
    "J_fly_shaft": _e("Момент инерции маховика на валу двигателя", _i("J", "доп") + "/" + _i("u") + "²", "кг·м²",
                      group=_DG5, hide_if=("fw_ratio", 1.0)),
    "omega_max_shaft": _e("Наибольшая угловая скорость вала маховика", "ω<sub>max</sub>", "рад/с", group=_DG5, hide_if=("fw_ratio", 1.0)),
    "omega_min_shaft": _e("Наименьшая угловая скорость вала маховика", "ω<sub>min</sub>", "рад/с", group=_DG5, hide_if=("fw_ratio", 1.0)),
    "q_dT_max": _pos(), "q_dT_min": _pos(), "q_dT_I_max": _pos(), "q_dT_I_min": _pos(),
    "q_omega_max": _pos(), "q_omega_min": _pos(),
}
for _m, _w in _MNAME.items():
    DYNAMICS[f"J_I_{_m}"] = _e(f"Момент инерции первой группы {_w}", _i("J", "I"), "кг·м²", group=_DG2,
                               hide_if=("method", _m))
    DYNAMICS[f"delta_achieved_{_m}"] = _e("Коэффициент неравномерности при точном движении с " + _i("J", "I")
                                          + f" {_w}", "δ<sub>факт</sub>", sig=5, group=_DG2, hide_if=("method", _m))
    if _m != "exact":
        DYNAMICS[f"dev_{_m}_pct"] = _e("Отклонение " + _i("J", "I") + f" {_w} от точного", "Δ" + _i("J", "I"),
                                       "%", sig=3, group=_DG2)
_FW = {"rim": ("обод со спицами", {"D2": ("наружный диаметр", _i("D", "2")), "D1": ("внутренний диаметр", _i("D", "1")),
                                   "b": ("ширина", _i("b")), "m": ("масса", _i("m")), "v": ("окружная скорость", _i("v"))}),
       "disk": ("сплошной диск", {"D": ("диаметр", _i("D")), "b": ("ширина", _i("b")), "m": ("масса", _i("m")),
                                  "v": ("окружная скорость", _i("v"))}),
       "disk_phys": ("диск по " + _i("J") + " = πρ" + _i("bD") + "⁴/32",
                     {"D": ("диаметр", _i("D")), "b": ("ширина", _i("b")), "m": ("масса", _i("m"))}),
       "ring_phys": ("кольцо без спиц по " + _i("J") + " = πρ" + _i("b") + "(" + _i("D", "2") + "⁴ − "
                     + _i("D", "1") + "⁴)/32",
                     {"D2": ("наружный диаметр", _i("D", "2")), "D1": ("внутренний диаметр", _i("D", "1")),
                      "b": ("ширина", _i("b")), "m": ("масса", _i("m"))})}
_FW_UNIT = {"m": ("кг", dict(sig=4)), "v": ("м/с", dict(sig=4))}
for _shape, (_title, _dims) in _FW.items():
    for _k, (_what, _sym) in _dims.items():
        _u, _f = _FW_UNIT.get(_k, ("м", dict(sig=None, digits=3)))
        DYNAMICS[f"fw_{_shape}_{_k}"] = _e(f"Маховик — {_title}: {_what}", _sym, _u, group=_DG4, **_f)

# ---------------------------------------------------------------------------- forces
_FG1, _FG2, _FG3 = "Уравновешивающий момент и проверки", "Наибольшие реакции в кинематических парах", "Гидропривод и грузоподъёмность"
FORCES = {
    "forces_mode": _e("Вид силового расчёта", "", group=_FG1,
                      words={"kinetostatic": "кинетостатический (с силами инерции)",
                             "static": "статический (без сил инерции)"}),
    "forces_motion": _e("Закон движения, по которому найдены силы инерции", "", group=_FG1,
                        words={"dynamics": "истинный, из динамического анализа (ω(φ), ε(φ))",
                               "constant": "ω<sub>1</sub> = const",
                               "static": ""}),            # said by forces_mode
    "M_bal_absmax": _e("Наибольший по модулю уравновешивающий момент", "|" + _i("M", "ур") + "|<sub>max</sub>",
                       "Н·м", where="q_M_bal_absmax", group=_FG1),
    "F_act_absmax": _e("Наибольшее по модулю усилие гидроцилиндра", "|" + _i("F", "ц") + "|<sub>max</sub>", "Н",
                       where="q_F_act_absmax", group=_FG1),
    "dev_zhukovsky_max_pct": _e("Расхождение " + _i("M", "ур") + " по группам Ассура и по рычагу Жуковского, "
                                "наибольшее", "Δ<sub>Ж</sub>", "%", sig=2, group=_FG1,
                                actuator=("Расхождение усилия гидроцилиндра " + _i("F") + " по группам Ассура и по "
                                          "рычагу Жуковского, наибольшее", "Δ<sub>Ж</sub>")),
    "dev_power_max": _e("Относительная невязка баланса мощностей, наибольшая", "Δ" + _i("N"), sig=2, group=_FG1),
    "dev_M_bal_M_d_max": _e("Относительное отличие " + _i("M", "ур") + " от движущего момента "
                            + _i("M", "д") + ", наибольшее", "", sig=2, group=_FG1),
    "dev_M_bal_dyn_max": _e("Относительное отличие " + _i("M", "ур") + " от " + _i("M", "д") + " − "
                            + _i("J", "I") + "ε динамики, наибольшее", "", sig=2, group=_FG1),
    "A_piston": _e("Площадь поршня", _i("A", "п"), "м²", sig=4, group=_FG3),
    "act_count": _e("Число гидроцилиндров", _i("k"), sig=None, digits=0, group=_FG3, given=True),
    "act_efficiency": _e("КПД гидроцилиндра", "η", sig=3, group=_FG3, given=True),
    "p_system": _e("Давление в гидросистеме", _i("p"), "МПа", conv="MPa", sig=4, group=_FG3, given=True),
    "F_cyl_max": _e("Наибольшее усилие гидроцилиндров при этом давлении", _i("F", "ц max"), "Н", group=_FG3),
    "p_act_max": _e("Наибольшее требуемое давление в гидроцилиндрах", _i("p", "max"), "МПа", conv="MPa", sig=4,
                    where="q_p_act_max", group=_FG3),
    "pressure_exceeded": _e("Требуемое давление выше давления в гидросистеме", "", group=_FG3,
                            words=("да — превышено", "нет")),
    "reserve_min_pct": _e("Наименьший запас грузоподъёмности", "", "%", sig=3, where="q_reserve_min", group=_FG3),
    "R_front_min_value": _e("Наименьшая нагрузка на управляемый мост", _i("R", "A min"), "Н",
                            where="q_R_front_min", group=_FG3),
    "q_M_bal_absmax": _pos(), "q_F_act_absmax": _pos(), "q_p_act_max": _pos(), "q_reserve_min": _pos(),
    "q_R_front_min": _pos(),
}
_PAIR = re.compile(r"(q_)?R_([^_]+)_([^_]+)_max")

# ---------------------------------------------------------------------------- cam
_MM = dict(unit="мм", conv="mm", sig=4)
_ANG = dict(unit="°", conv="deg", sig=None, digits=2)     # degrees to 0,01° (a zero stays 0,00)
CAM = {
    "cam_stroke": _e("Ход толкателя", _i("h"), conv="stroke", sig=4, given=True,
                     swing=("Угол размаха коромысла", "ψ<sub>max</sub>")),
    # a roller's base circle belongs to the centre (theoretical) profile; a knife's or a flat face's
    # centre profile is the working profile itself (Артоболевский, гл. 24)
    # accepted (a whole millimetre) or given: printed as taken, «29», not «29,00»
    "cam_r0": _e("Радиус основной шайбы (центрового профиля)", _i("r", "0"), **_MM, given=True,
                 contact={"knife": "Радиус основной шайбы (рабочего профиля)",
                          "flat": "Радиус основной шайбы (рабочего профиля)"}),
    "cam_r0_least": _e("Наименьший радиус основной шайбы по допустимым углам давления", _i("r", "0 min"), **_MM),
    "cam_r0_min": _e("Наименьший радиус основной шайбы по условию выпуклости профиля", _i("r", "0 min"), **_MM),
    "cam_r0_approx": _e("Радиус основной шайбы приближённым способом", _i("r", "0"), **_MM),
    "cam_e": _e("Эксцентриситет (смещение оси толкателя)", _i("e"), **_MM),
    "cam_e_approx": _e("Эксцентриситет приближённым способом", _i("e"), **_MM),
    "cam_s0": _e("Начальное расстояние от центра кулачка вдоль оси толкателя", _i("s", "0"), **_MM),
    "cam_a_w": _e("Межосевое расстояние", _i("a", "w"), **_MM),
    "cam_a_w_min": _e("Наименьшее допустимое межосевое расстояние", _i("a", "w min"), **_MM),
    "cam_a_w_approx": _e("Межосевое расстояние приближённым способом", _i("a", "w"), **_MM),
    "cam_arm": _e("Длина коромысла", _i("l"), **_MM, given=True),
    "cam_psi0": _e("Начальный угол коромысла", "ψ<sub>0</sub>", **_ANG),
    "cam_roller": _e("Радиус ролика", _i("r", "р"), **_MM, given=True),
    "cam_rho_c_min": _e("Наименьший радиус кривизны центрового профиля", "ρ<sub>ц min</sub>", **_MM),
    "cam_rho_min": _e("Наименьший радиус кривизны рабочего профиля", "ρ<sub>min</sub>", **_MM),
    "cam_face_offset": _e("Смещение тарелки от оси качания коромысла", _i("d"), **_MM, given=True),
    "cam_face_min": _e("Наименьшее расстояние точки касания вдоль тарелки", "μ<sub>min</sub>", **_MM),
    "cam_face_max": _e("Наибольшее расстояние точки касания вдоль тарелки", "μ<sub>max</sub>", **_MM),
    "cam_face_width": _e("Ширина (рабочая длина) тарелки", _i("b"), **_MM),
    "cam_theta_rise_max": _e("Наибольший угол давления на фазе удаления", "ϑ<sub>max</sub>", **_ANG),
    "cam_theta_return_max": _e("Наибольший угол давления на фазе возвращения", "ϑ<sub>max</sub>", **_ANG),
    "cam_impacts_hard": _e("Число жёстких ударов за цикл", "", sig=None, digits=0),
    "cam_impacts_soft": _e("Число мягких ударов за цикл", "", sig=None, digits=0),
}

# ---------------------------------------------------------------------------- gears (sizes already in mm)
_GMM = dict(unit="мм", sig=5)
_YESNO = ("есть", "нет")
GEARS = {
    "gears_m": _e("Модуль", _i("m"), **_GMM, given=True),
    "gears_x1": _e("Коэффициент смещения шестерни", _i("x", "1"), sig=3, given=True),
    "gears_x2": _e("Коэффициент смещения колеса", _i("x", "2"), sig=3, given=True),
    "gears_alpha_w_deg": _e("Угол зацепления", "α<sub>w</sub>", "°", sig=5),
    "gears_a": _e("Делительное межосевое расстояние", _i("a"), **_GMM),
    "gears_a_w": _e("Межосевое расстояние", _i("a", "w"), **_GMM),
    "gears_y": _e("Коэффициент воспринимаемого смещения", _i("y"), sig=4),
    "gears_dy": _e("Коэффициент уравнительного смещения", "Δ" + _i("y"), sig=4),
    "gears_p": _e("Шаг по делительной окружности", _i("p"), **_GMM),
    "gears_pb": _e("Основной шаг", _i("p", "b"), **_GMM),
    "gears_eps_alpha": _e("Коэффициент торцового перекрытия", "ε<sub>α</sub>", sig=4),
    "gears_eps_alpha_line": _e("Коэффициент торцового перекрытия по длине активной линии зацепления",
                               "ε<sub>α</sub>", sig=4, same_as="gears_eps_alpha"),
    "gears_undercut1": _e("Подрезание зубьев шестерни", "", words=_YESNO),
    "gears_undercut2": _e("Подрезание зубьев колеса", "", words=_YESNO),
    "gears_interference": _e("Интерференция зубьев", "", words=_YESNO),
    "gears_x_chord": _e("Коэффициент смещения по измеренной толщине зуба по хорде", _i("x"), sig=3),
    "gears_s_chord": _e("Толщина зуба по хорде на окружности концов хорды", _i("s", "y"), **_GMM),
    "gears_psi_deg": _e("Половина центрального угла хорды", "ψ<sub>y</sub>", "°", sig=4),
    "gears_d_y": _e("Диаметр окружности концов хорды", _i("d", "y"), **_GMM),
    "gears_alpha_y_deg": _e("Угол профиля на окружности концов хорды", "α<sub>y</sub>", "°", sig=4),
    "gears_x_span": _e("Коэффициент смещения по длине общей нормали", _i("x"), sig=3),
    "gears_xsum_required": _e("Сумма коэффициентов смещения для заданного межосевого расстояния",
                              _i("x", "Σ"), sig=4),
}

# ---------------------------------------------------------------------------- planetary train
TRAIN = {
    "train_u": _e("Передаточное отношение по формуле Виллиса", _i("u"), sig=5),
    "train_u_direct": _e("Передаточное отношение по скоростям в полюсах зацеплений", _i("u"), sig=5,
                         same_as="train_u"),
    "train_u_discrepancy_pct": _e("Расхождение двух способов", "", "%", sig=2),
    "train_u_target": _e("Заданное передаточное отношение", _i("u", "зад"), sig=5, given=True),
    "train_u_error_pct": _e("Отклонение от заданного", "", "%", sig=2),
}

# ---------------------------------------------------------------------------- machine, motion
MACHINE = {
    "machine_work": _e("Работа движущих сил за цикл", _i("A", "д"), "Дж", sig=5),
    "machine_cycle_time": _e("Время цикла", _i("t", "ц"), "с", sig=4),
    "machine_power": _e("Средняя мощность", _i("P"), "Вт", sig=5),
    "machine_M_mean": _e("Средний движущий момент", _i("M", "д"), "Н·м", sig=5),
    "machine_dE": _e("Наибольшая избыточная работа (перепад кинетической энергии)", "Δ" + _i("E", "нб"), "Дж"),
    "machine_delta": _e("Коэффициент неравномерности хода", "δ", sig=4, given=True),
    "machine_omega_m": _e("Средняя угловая скорость", "ω<sub>ср</sub>", "рад/с"),
    "machine_omega_max": _e("Наибольшая угловая скорость", "ω<sub>max</sub>", "рад/с"),
    "machine_omega_min": _e("Наименьшая угловая скорость", "ω<sub>min</sub>", "рад/с"),
    "machine_J": _e("Требуемый приведённый момент инерции", _i("J", "пр"), "кг·м²"),
    "machine_J_O": _e("Приведённый момент инерции остальных звеньев", _i("J", "O"), "кг·м²"),
    "machine_J_fly": _e("Момент инерции маховика", _i("J", "м"), "кг·м²"),
}
MOTION = {
    "motion_t_end": _e("Время расчёта", _i("t", "к"), "с", sig=4),
    "motion_phi_end": _e("Угол поворота звена приведения в конце расчёта", "φ(" + _i("t", "к") + ")", "рад"),
    "motion_omega_end": _e("Угловая скорость в конце расчёта", "ω(" + _i("t", "к") + ")", "рад/с"),
    "motion_omega_max": _e("Наибольшая угловая скорость", "ω<sub>max</sub>", "рад/с"),
    "motion_omega_min": _e("Наименьшая угловая скорость", "ω<sub>min</sub>", "рад/с"),
    "motion_dJ_check": _e("Проверка производной приведённого момента инерции (невязка)", "", sig=2),
    "motion_phi_end_printed": _e("Угол в конце расчёта по уравнению исходного решения", "φ(" + _i("t", "к") + ")",
                                 "рад"),
    "motion_max_dphi_printed": _e("Наибольшее отличие угла по уравнению исходного решения от точного", "Δφ",
                                  "рад"),
}

# ---------------------------------------------------------------------------- synthesis
_SM = dict(unit="м", sig=5)
SYNTHESIS = {
    "syn_K": _e("Коэффициент изменения средней скорости выходного звена", _i("K"), sig=4, given=True),
    "syn_theta": _e("Угол перекрытия θ = 180°(" + _i("K") + " − 1)/(" + _i("K") + " + 1)", "θ", **_ANG),
    "syn_theta_check": _e("Угол, под которым из центра кривошипа видны крайние положения (проверка θ)", "θ",
                          same_as="syn_theta", **_ANG),
    "syn_H": _e("Ход выходного звена", _i("H"), **_SM),
    "syn_psi": _e("Угол размаха коромысла (кулисы)", "ψ", **_ANG),
    "syn_a": _e("Длина кривошипа", _i("a"), **_SM),
    "syn_b": _e("Длина шатуна", _i("b"), **_SM),
    "syn_c": _e("Длина коромысла", _i("l", "CB"), **_SM),
    "syn_d": _e("Расстояние между центрами вращения", _i("d"), **_SM),
    "syn_l": _e("Длина кулисы", _i("l", "CD"), **_SM),
    "syn_e": _e("Смещение (дезаксиал)", _i("e"), **_SM),
    "syn_lam": _e("Отношение длин кривошипа и шатуна", "λ", sig=4),
    "syn_l3": _e("Длина коромысла", _i("l", "3"), **_SM),
    "syn_l4": _e("Длина шатуна коромысло — ползун", _i("l", "4"), **_SM),
    "syn_path_y": _e("Расстояние от опоры коромысла до траектории ползуна", _i("y", "C"), **_SM),
    "syn_x_O": _e("Центр кривошипа: абсцисса", _i("x", "O"), **_SM),
    "syn_y_O": _e("Центр кривошипа: ордината", _i("y", "O"), **_SM),
    "syn_variant": _e("Номер принятого варианта решения", "", sig=None, digits=0),
    "syn_variants": _e("Число вариантов решения", "", sig=None, digits=0),
    "syn_phi_far": _e("Угол кривошипа в крайнем положении с вытянутым шатуном", "φ<sub>1</sub>", **_ANG),
    "syn_phi_near": _e("Угол кривошипа в крайнем положении со сложенным шатуном", "φ<sub>2</sub>", **_ANG),
    "syn_phi_right": _e("Угол кривошипа в правом крайнем положении кулисы", "φ<sub>пр</sub>", **_ANG),
    "syn_phi_left": _e("Угол кривошипа в левом крайнем положении кулисы", "φ<sub>л</sub>", **_ANG),
    "check_stroke": _e("Проверка по механизму: ход выходного звена", _i("H"), conv="stroke", sig=6,
                       swing=("Проверка по механизму: угол размаха выходного звена", "ψ")),
    "check_K": _e("Проверка по механизму: коэффициент изменения средней скорости", _i("K"), sig=6),
    "check_q1": _e("Проверка по механизму: угол кривошипа в первом крайнем положении", "φ<sub>1</sub>", **_ANG),
    "check_q2": _e("Проверка по механизму: угол кривошипа во втором крайнем положении", "φ<sub>2</sub>", **_ANG),
}
for _p, _what in (("far", "с вытянутым шатуном"), ("near", "со сложенным шатуном")):
    for _ax, _an in (("x", "абсцисса"), ("y", "ордината")):
        SYNTHESIS[f"syn_{_ax}_{_p}"] = _e(f"Конец шатуна в крайнем положении {_what}: {_an}", _i(_ax, "B"), **_SM)
for _n in ("1", "2"):
    for _ax, _an in (("x", "абсцисса"), ("y", "ордината")):
        SYNTHESIS[f"syn_{_ax}_B{_n}"] = _e(f"Крайнее положение B<sub>{_n}</sub> конца коромысла: {_an}",
                                          _i(_ax, "B" + _n), **_SM)
    SYNTHESIS[f"syn_x_C{_n}"] = _e(f"Крайнее положение C<sub>{_n}</sub> ползуна: абсцисса", _i("x", "C" + _n), **_SM)

# ---------------------------------------------------------------------------- dof, cross, governor
_INT = dict(sig=None, digits=0)
DOF = {
    "dof_n": _e("Число подвижных звеньев", _i("n"), **_INT),
    "dof_p5": _e("Число низших пар", _i("p", "5"), **_INT),
    "dof_p4": _e("Число высших пар", _i("p", "4"), **_INT),
    "dof_W": _e("Число степеней свободы по формуле Чебышева", _i("W"), **_INT),
    "dof_q": _e("Число лишних (местных) степеней свободы роликов", _i("q"), **_INT),
    "dof_W_true": _e("Действительное число степеней свободы", _i("W") + " − " + _i("q"), **_INT),
    "dof_n_after": _e("Число подвижных звеньев после замены высшей пары", _i("n") + "′", **_INT),
    "dof_p5_after": _e("Число низших пар после замены высшей пары", _i("p", "5") + "′", **_INT),
    "dof_p4_after": _e("Число высших пар после замены высшей пары", _i("p", "4") + "′", **_INT),
    "dof_W_after": _e("Число степеней свободы заменяющего механизма", _i("W") + "′", **_INT),
    "dof_zero_count": _e("Число положений остановки выходного звена", "", **_INT),
    "dof_zero_q": _e("Угол поворота кривошипа в положении остановки", "φ", **_ANG),
    "dof_zero_s": _e("Выходная величина в положении остановки", _i("s"), "м", sig=4),
    "dof_angle_OML": _e("Угол OML в положении остановки", "∠" + _i("OML"), **_ANG),
    "dof_zero_OM": _e("Расстояние OM в положении остановки", _i("OM"), "м", sig=4),
}
CROSS = {f"cross_v_{p}": _e(f"Скорость {w}", _i("v", p), "м/с", sig=4) for p, w in (
    ("B3", "точки B звена 3"), ("B3B2", "точки B звена 3 относительно звена 2"), ("C3", "точки C звена 3"),
    ("C5", "точки C звена 5"), ("C4", "точки C звена 4"))}
CROSS.update({
    "cross_w3": _e("Угловая скорость звена 3", "ω<sub>3</sub>", "рад/с", sig=4),
    "cross_w5": _e("Угловая скорость звена 5", "ω<sub>5</sub>", "рад/с", sig=4),
    "cross_l_O1C": _e("Расстояние O<sub>1</sub>C", _i("l", "O1C"), "м", sig=4),
    "cross_l_O2C": _e("Расстояние O<sub>2</sub>C", _i("l", "O2C"), "м", sig=4),
    "cross_F_red": _e("Приведённая сила", _i("F", "пр"), "Н", sig=4),
})
GOVERNOR = {
    "governor_rho": _e("Радиус круга трения", "ρ", "м", sig=4),
    "governor_phi_f": _e("Угол трения", "φ<sub>тр</sub>", **_ANG),
    "governor_alpha": _e("Угол отклонения реакции тяги от оси (круг трения)", "α", **_ANG),
    "governor_R": _e("Реакция тяги", _i("R"), "Н", sig=4),
    "governor_P": _e("Сила на муфте с реакцией тяги", _i("P"), "Н", sig=4),
    "governor_F_i": _e("Центробежная сила инерции груза", _i("F", "и"), "Н", sig=4),
    "governor_R76": _e("Реакция в шарнире 7–6", _i("R", "76"), "Н", sig=4),
    "governor_R76_angle": _e("Угол реакции " + _i("R", "76") + " с горизонтом", "", **_ANG),
    "governor_r_D": _e("Радиус вращения центра груза", _i("r", "D"), "м", sig=4),
    "governor_omega": _e("Угловая скорость регулятора в расчётном случае", "ω", "рад/с", sig=4),
    "governor_omega_up": _e("Угловая скорость начала подъёма муфты (разгон)", "ω<sub>1</sub>", "рад/с", sig=4),
    "governor_omega_0": _e("Угловая скорость равновесия без трения", "ω<sub>0</sub>", "рад/с", sig=4),
    "governor_omega_down": _e("Угловая скорость начала опускания муфты (торможение)", "ω<sub>2</sub>", "рад/с",
                              sig=4),
}

# ---------------------------------------------------------------------------- the linkage's output link
# (Study.scalars; the structure numbers, the transmission angles and the fitted parameters are shown
# elsewhere in the key, so only these keys make the table)
_CQ = dict(unit="°", conv="q", sig=None, digits=1)
KINEMATICS = {
    "swing": _e("Угол размаха входного коромысла", "ψ<sub>1</sub>", **_ANG),
    "output_stroke": _e("Ход выходного звена", _i("H"), conv="stroke", sig=5,
                        swing=("Угол размаха выходного звена", "ψ")),
    "output_path": _e("Путь выходного звена за ход", _i("s"), conv="stroke", sig=5,
                      swing=("Угол поворота выходного звена за ход", "Σ|Δψ|")),
    "output_K": _e("Коэффициент изменения средней скорости выходного звена", _i("K"), sig=4),
    "output_q1": _e("Угол кривошипа в первом крайнем положении выходного звена", "φ<sub>1</sub>", **_CQ),
    "output_q2": _e("Угол кривошипа во втором крайнем положении выходного звена", "φ<sub>2</sub>", **_CQ),
    "output_v_work": _e("Средняя скорость рабочего хода", _i("v", "р.х"), conv="speed", sig=4,
                        swing=("Средняя угловая скорость рабочего хода", "ω<sub>р.х</sub>")),
    "output_v_return": _e("Средняя скорость обратного хода", _i("v", "х.х"), conv="speed", sig=4,
                          swing=("Средняя угловая скорость обратного хода", "ω<sub>х.х</sub>")),
    "output_reversals": _e("Число остановок выходного звена внутри хода", "", **_INT),
    "t_stroke": _e("Время прямого хода", _i("t", "пр"), "с", sig=4),
    "t_return": _e("Время обратного хода", _i("t", "обр"), "с", sig=4),
    "t_cycle": _e("Время цикла", _i("t", "ц"), "с", sig=4),
}
_REVERSAL = re.compile(r"output_q_reversal_(\d+)")

GLOSSARY: dict[str, dict[str, Entry]] = {
    "dynamics": DYNAMICS, "forces": FORCES, "cam": CAM, "gears": GEARS, "train": TRAIN, "machine": MACHINE,
    "motion": MOTION, "synthesis": SYNTHESIS, "dof": DOF, "cross": CROSS, "governor": GOVERNOR,
    "kinematics": KINEMATICS,
}


def entry(kind: str, key: str) -> Entry | None:
    """The glossary entry of scalar ``key`` of task ``kind``; families (the reactions R_i_j_max of
    every pair and their positions q_R_i_j_max) by pattern; None if the key has no entry."""
    e = GLOSSARY.get(kind, {}).get(key)
    if e is not None:
        return e
    r = _REVERSAL.fullmatch(key) if kind == "kinematics" else None
    if r is not None:
        return _e(f"Угол входного звена при остановке выходного № {r.group(1)}", "φ", **_CQ)
    m = _PAIR.fullmatch(key) if kind == "forces" else None
    if m is None:
        return None
    if m.group(1):
        return _pos()
    a, b = m.group(2), m.group(3)
    ha, hb = escape(a), escape(b)            # link names come from the case file
    return replace(_e(f"Наибольшая реакция в паре {ha}–{hb}", _i("R", f"{ha}{hb}"), "Н", group=_FG2),
                   where=f"q_R_{a}_{b}_max")


def convert(e: Entry, value: float, study=None, kind: str = "") -> tuple[float, str]:
    """``value`` in the unit the note prints, and that unit."""
    if e.conv == "deg":
        return math.degrees(value), e.unit
    if e.conv == "mm":
        return value * 1000.0, e.unit
    if e.conv == "MPa":
        return value * 1e-6, e.unit
    if e.conv == "stroke":
        angular = _angular_stroke(study, kind)
        return (math.degrees(value), "°") if angular else ((value * 1000.0, "мм") if kind == "cam" else (value, "м"))
    if e.conv == "speed":
        return value, ("рад/с" if _angular_stroke(study, kind) else "м/с")
    if e.conv == "q":
        from .sections.common import q_degrees
        return q_degrees(study, value), e.unit
    return value, e.unit


def shown(e: Entry, study=None, kind: str = "") -> tuple[str, str]:
    """The name and symbol of ``e`` for this case (a swing instead of a stroke; the actuator's
    force instead of the balancing moment)."""
    if e.swing is not None and _angular_stroke(study, kind):
        return e.swing
    if e.actuator is not None and _actuated(study, kind):
        return e.actuator
    if e.contact is not None and kind == "cam" and study is not None:
        return e.contact.get(study.cam.contact, e.name), e.sym
    return e.name, e.sym


# the heading of a group of the force analysis when the input is an actuator (as the note's table
# «Усилие гидроцилиндра и его проверки»): there is no balancing moment to speak of
_ACTUATOR_GROUPS = {_FG1: "Усилие гидроцилиндра и проверки"}


def group_title(group: str, study=None, kind: str = "") -> str:
    """The heading of a results table of ``kind`` for this case."""
    return _ACTUATOR_GROUPS.get(group, group) if _actuated(study, kind) else group


def _actuated(study, kind: str) -> bool:
    """Whether the force analysis of ``study`` balances an actuator's force (no crank moment)."""
    return kind == "forces" and study is not None and study.has_linkage and not study.mechanism.driver.rotary


def _angular_stroke(study, kind: str) -> bool:
    """Whether a stroke is a swing (rad): a rocking cam follower, an output link that turns."""
    if kind == "cam":
        return study.cam.follower == "rocker"
    if kind == "kinematics":
        return str(study.scalars.get("output", "")).startswith("phi_")
    chk = study.synthesis.check or {}
    return str(chk.get("column", "")).startswith("phi_")
