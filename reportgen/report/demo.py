"""A synthetic report (crank–slider mechanism) exercising every feature of the
rendering layer: two numbered sections with subsections, a long table that
splits across pages, two matplotlib figures, formulas with Cyrillic units and
«где» lists, cross-references, an appendix.

Used by tests/test_report_render.py and bench/bench_render.py; also a handy
preview: ``python -m reportgen.report.demo out/`` writes demo.pdf and demo.html.
"""

from __future__ import annotations

import math
import sys

import numpy as np
import pandas as pd

from ..style import mplstyle
from .document import Column, Formula, Paragraph, Report, Section, Table, ref
from .formulas import inline_math
from ..style.numbers import fmt, tex_num

__all__ = ["crank_slider", "build_demo_report"]

R, L, N1 = 0.1, 0.4, 65.0  # crank, coupler (m), crank speed (об/мин)


def crank_slider(n_rows: int = 60) -> pd.DataFrame:
    """Exact kinematics of a central crank–slider over one revolution."""
    w1 = math.pi * N1 / 30
    phi = np.linspace(0.0, 2 * math.pi, n_rows, endpoint=False)
    lam = R / L
    s = np.sin(phi)
    c = np.cos(phi)
    root = np.sqrt(1 - (lam * s) ** 2)
    x = R * c + L * root
    v = -R * w1 * (s + lam * s * c / root)
    a = -R * w1 ** 2 * (c + lam * (c ** 2 - s ** 2) / root + lam ** 3 * s ** 2 * c ** 2 / root ** 3)
    phi2 = np.arcsin(-lam * s)
    w2 = -lam * w1 * c / root
    return pd.DataFrame({
        "pos": np.arange(n_rows),
        "q_deg": np.degrees(phi),
        "x_B": x,
        "v_B": v,
        "a_B": a,
        "phi_2": np.degrees(phi2),
        "w_2": w2,
    }).set_index("pos")


def _figure_motion(df: pd.DataFrame) -> bytes:
    fig = mplstyle.figure(160, 85)
    ax = fig.add_subplot()
    ax.plot(df["q_deg"], df["v_B"], label="$v_B$, м/с")
    ax.plot(df["q_deg"], df["a_B"] / 10, "--", label="$a_B/10$, м/с²")
    ax.set_xlabel("φ, град")
    ax.set_ylabel("Скорость и ускорение ползуна")
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 45))
    fig.legend(loc="outside upper center", ncols=2)
    return mplstyle.to_svg(fig)


def _figure_position(df: pd.DataFrame) -> bytes:
    fig = mplstyle.figure(120, 70)
    ax = fig.add_subplot()
    ax.plot(df["q_deg"], df["x_B"] * 1000, color="black")
    ax.set_xlabel("φ, град")
    ax.set_ylabel("$x_B$, мм")
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 60))
    return mplstyle.to_svg(fig)


def build_demo_report(n_rows: int = 60, options: dict | None = None) -> Report:
    """The synthetic report; ``n_rows`` rows in the kinematics table."""
    df = crank_slider(n_rows)
    w1 = math.pi * N1 / 30
    lam = R / L
    v_max = float(df["v_B"].abs().max())

    assignment = [
        Paragraph("Выполнить структурный и кинематический анализ кривошипно-ползунного "
                  "механизма по заданным размерам звеньев и частоте вращения кривошипа."),
        Table("Исходные данные",
              [Column("name", "Параметр"), Column("value", "Значение", sig=3),
               Column("unit", "Единица")],
              pd.DataFrame({
                  "name": ["Длина кривошипа OA", "Длина шатуна AB", "Частота вращения кривошипа",
                           "Число положений"],
                  "value": pd.Series([R, L, int(N1), n_rows], dtype=object),
                  "unit": ["м", "м", "об/мин", "—"],
              }), id="tab-given"),
    ]

    introduction = [
        Paragraph("Теория механизмов и машин изучает строение, кинематику и динамику "
                  "механизмов. В курсовом проекте выполняются структурный и кинематический "
                  "анализ кривошипно-ползунного механизма: определяются степень подвижности, "
                  "положения звеньев, скорости и ускорения точек на полном обороте кривошипа."),
        Paragraph(f"Расчёт выполнен программой для {n_rows} положений кривошипа; результаты "
                  f"приведены в таблице {ref('tab-kin')} и на рисунках {ref('fig-motion')} "
                  f"и {ref('fig-pos')}."),
    ]

    # Section 1: structure and kinematics — the long table 1.1, figures 1.1 and
    # 1.2, formulas (1.1)–(1.5).
    s1 = Section("Структурный и кинематический анализ механизма", "sec-kin")
    s1.paragraph("Механизм состоит из стойки 0, кривошипа 1, шатуна 2 и ползуна 3. "
                 "Кинематические пары: три вращательные (О, А, В) и одна поступательная "
                 "(ползун – направляющая), все пары пятого класса.")
    s11 = s1.subsection("Степень подвижности механизма", "sec-dof")
    s11.paragraph("Степень подвижности плоского механизма определяется по формуле "
                  "П.&nbsp;Л.&nbsp;Чебышева:")
    s11.formula(
        r"W = 3n - 2p_5 - p_4", r"3 \cdot 3 - 2 \cdot 4 - 0", "1",
        where=[("n", "число подвижных звеньев"),
               ("p_5", "число низших кинематических пар"),
               ("p_4", "число высших кинематических пар")],
        label="eq-w",
    )
    s11.paragraph(f"Полученное по формуле {ref('eq-w')} значение W&nbsp;=&nbsp;1 означает, что "
                  "для определённости движения достаточно одного входного звена – кривошипа. "
                  "Механизм образован присоединением к механизму I класса одной группы "
                  "Ассура II класса 2-го вида (шатун 2 – ползун 3).")

    s12 = s1.subsection("Скорости и ускорения ползуна", "sec-vb")
    omega1, n1 = inline_math(r"\omega_1"), inline_math("n_1")
    s12.paragraph(f"Угловая скорость кривошипа {omega1} при частоте "
                  f"вращения {n1}&nbsp;=&nbsp;{fmt(N1, sig=3)}&nbsp;об/мин:")
    s12.formula(
        Formula(r"\omega_1 = \frac{\pi n_1}{30}",
                r"\frac{3{,}1416 \cdot " + tex_num(N1, digits=0) + "}{30}",
                tex_num(w1, digits=3, unit="рад/с"),
                where=[(r"\omega_1", "угловая скорость кривошипа, рад/с"),
                       (r"n_1", "частота вращения кривошипа, об/мин")],
                label="eq-w1"),
    )
    s12.paragraph(f"Перемещение, скорость и ускорение ползуна найдены по формулам "
                  f"{ref('eq-xb')}–{ref('eq-ab')} при λ&nbsp;=&nbsp;{fmt(lam, digits=3)}; "
                  f"значения для всех положений приведены в таблице {ref('tab-kin')}, "
                  f"графики – на рисунках {ref('fig-motion')} и {ref('fig-pos')}.")
    s12.formula(
        Formula(r"x_B = l_{OA}\cos\varphi_1 + l_{AB}\sqrt{1 - \lambda^2 \sin^2\varphi_1}",
                where=[(r"x_B", "координата ползуна, м"),
                       (r"\varphi_1", "угол поворота кривошипа, рад"),
                       (r"\lambda", "отношение длин кривошипа и шатуна")],
                label="eq-xb"),
        Formula(r"v_B = {-\omega_1 l_{OA}\left(\sin\varphi_1 + \frac{\lambda \sin\varphi_1 "
                r"\cos\varphi_1}{\sqrt{1 - \lambda^2 \sin^2\varphi_1}}\right)}",
                label="eq-vb"),
        Formula(r"a_B \approx {-\omega_1^2 l_{OA}\left(\cos\varphi_1 + \lambda\cos 2\varphi_1\right)}",
                r"-" + tex_num(w1, digits=3) + r"^2 \cdot " + tex_num(R, digits=3)
                + r"\cdot\left(1 + " + tex_num(lam, digits=3) + r"\right)",
                tex_num(-w1 ** 2 * R * (1 + lam), digits=3, unit="м/с²"),
                where=[(r"a_B", "ускорение ползуна при φ<sub>1</sub>&nbsp;=&nbsp;0, м/с²")],
                label="eq-ab"),
    )
    s12.table(
        "Кинематические характеристики ползуна и шатуна",
        [Column("q_deg", "φ<sub>1</sub>", unit="град", digits=1),
         Column("x_B", "<i>x</i><sub>B</sub>", unit="м", digits=4),
         Column("v_B", "<i>v</i><sub>B</sub>", unit="м/с", digits=4),
         Column("a_B", "<i>a</i><sub>B</sub>", unit="м/с²", digits=3),
         Column("phi_2", r"\varphi_2", unit="град", digits=2, latex=True),
         Column("w_2", "ω<sub>2</sub>", unit="рад/с", digits=4)],
        df, id="tab-kin", index_header="№", highlight_rows=[0],
        note=f"Наибольшая скорость ползуна {fmt(v_max, digits=3, unit='м/с')}.",
    )
    s12.figure("Скорость и ускорение ползуна в функции угла поворота кривошипа",
               _figure_motion(df), width_mm=160, id="fig-motion")
    s12.figure("Перемещение ползуна", _figure_position(df), width_mm=120, id="fig-pos")

    # Section 2: a short summary with a small table 2.1.
    s2 = Section("Анализ результатов", "sec-results")
    s2.paragraph(f"Экстремальные значения кинематических характеристик (таблица "
                 f"{ref('tab-ext')}) определены по данным таблицы {ref('tab-kin')}.")
    ext = pd.DataFrame({
        "name": ["Ход ползуна", "Наибольшая скорость ползуна", "Наибольшее ускорение ползуна",
                 "Наибольшая угловая скорость шатуна"],
        "symbol": ["H", "v<sub>B max</sub>", "a<sub>B max</sub>", "ω<sub>2 max</sub>"],
        "value": [2 * R, v_max, float(df["a_B"].abs().max()), float(df["w_2"].abs().max())],
        "unit": ["м", "м/с", "м/с²", "рад/с"],
    })
    s2.table("Экстремальные значения",
             [Column("name", "Величина"),
              Column("value", "Значение", digits=3),
              Column("unit", "Единица")], ext, id="tab-ext")
    s2.paragraph(f"Наибольшая скорость ползуна составляет {fmt(v_max, digits=3, unit='м/с')}, "
                 f"ход ползуна {fmt(2 * R, digits=3, unit='м')}.")

    conclusion = [
        Paragraph("В проекте выполнены структурный и кинематический анализ "
                  "кривошипно-ползунного механизма. Механизм имеет одну степень подвижности "
                  "и относится ко II классу."),
        Paragraph(f"Наибольшая скорость ползуна {fmt(v_max, digits=3, unit='м/с')}, "
                  f"наибольшее ускорение {fmt(float(df['a_B'].abs().max()), digits=2, unit='м/с²')}."),
    ]

    appendix = Section("Исходный текст расчёта", "app-code")
    appendix.paragraph("Расчёт выполнен программой reportgen; численные значения таблицы "
                       f"{ref('tab-kin')} получены по точным формулам.")

    return Report(
        meta={
            "ministry": "Министерство науки и высшего образования Российской Федерации",
            "university": "Федеральное государственное бюджетное образовательное учреждение "
                          "высшего образования «Технический университет»",
            "department": "Кафедра «Теория механизмов и машин»",
            "discipline": "Теория механизмов и машин",
            "topic": "Структурный и кинематический анализ кривошипно-ползунного механизма",
            "variant": 12,
            "student": "И.\u00a0И.\u00a0Иванов",
            "group": "МТ-201",
            "supervisor": "П.\u00a0П.\u00a0Петров",
            "supervisor_title": "доцент кафедры ТММ",
            "city": "Москва",
            "year": 2025,
            "doc_code": "ТММ.КП.12.00.000 ПЗ",
        },
        assignment=assignment,
        introduction=introduction,
        sections=[s1, s2],
        conclusion=conclusion,
        references=[
            "Артоболевский, И. И. Теория механизмов и машин : учебник для втузов / "
            "И. И. Артоболевский. – 4-е изд., перераб. и доп. – Москва : Наука, 1988. – 640 с.",
            "Теория механизмов и машин : учебник / К. В. Фролов, С. А. Попов, А. К. Мусатов "
            "[и др.] ; под ред. К. В. Фролова. – Москва : Высшая школа, 1987. – 496 с.",
        ],
        appendices=[appendix],
        options=dict(options or {}),
    )


def main(argv=None) -> None:  # pragma: no cover - manual preview
    from pathlib import Path

    from .render import build_outputs

    argv = sys.argv[1:] if argv is None else argv
    out = Path(argv[0] if argv else "output")
    paths = build_outputs(build_demo_report(), out, "demo")
    for kind, path in paths.items():
        print(kind, path)


if __name__ == "__main__":  # pragma: no cover
    main()
