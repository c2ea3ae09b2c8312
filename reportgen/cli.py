"""Command line: ``reportgen build | batch | export | check | warmup``.

Thin: parsing arguments and printing; the work is done by the library.  Every error caused by
the input is printed in Russian without a traceback (exit code 2).
"""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from .errors import CaseError, ReportgenError


def _parse_at(study, text: str) -> list[float]:
    from .case.expr import evaluate
    vals = []
    if text.count(",") >= 10_000:
        raise CaseError("слишком много значений в --at", key="--at", expected="не более 10000 значений")
    for i, part in enumerate(p.strip() for p in text.split(",") if p.strip()):
        try:
            vals.append(float(evaluate(part, study.params, expected=study.qdim, bare_is=study.qdim).value))
        except CaseError as e:
            raise CaseError(f"значение «{part}» в --at: {e.message}", key=f"--at[{i}]") from None
    if not vals:
        raise CaseError("пустой список --at", key="--at", expected="значения через запятую, например --at \"30 deg,99.1 deg\"")
    d = study.mechanism.driver if study.has_linkage else None
    if d is not None and d.swing:
        import math
        lo, hi = d.q_range
        for i, v in enumerate(vals):
            if not lo - 1e-12 <= v <= hi + 1e-12:
                raise CaseError(f"положение {math.degrees(v):.6g}° вне диапазона качания входного звена",
                                key=f"--at[{i}]", expected=f"угол от {math.degrees(lo):.6g}° до {math.degrees(hi):.6g}°")
    return vals


def cmd_export(args) -> int:
    from .analysis.study import Study
    from .export import export
    study = Study(args.case)
    at = _parse_at(study, args.at) if args.at else None
    out = _out_dir(Path(args.output) if args.output else Path("output") / study.name)
    files = export(study, out, at)
    print(f"Записано файлов: {len(files)} в {out}/")
    return 0


def _formats(text: str) -> tuple[str, ...]:
    fm = tuple(f.strip().lower() for f in text.split(",") if f.strip())
    bad = [f for f in fm if f not in ("pdf", "html")]
    if bad or not fm:
        raise CaseError(f"неизвестный формат «{bad[0] if bad else text}»", key="--format", expected="pdf, html или pdf,html")
    return fm


def _sections(text: str | None):
    return [s.strip() for s in text.split(",") if s.strip()] if text else None


def cmd_build(args) -> int:
    import time
    t0 = time.perf_counter()
    from .report import parallel
    if args.jobs is not None:
        if args.jobs < 1:
            raise CaseError("число процессов должно быть не меньше 1", key="--jobs", got=str(args.jobs),
                            expected="целое число ≥ 1")
        parallel.set_note_jobs(args.jobs)
    formats = _formats(args.format)
    out = _out_dir(Path(args.output))
    if "pdf" in formats:
        # the layout workers import WeasyPrint while this process imports the rest
        parallel.start_pool()
    try:
        return _build(args, formats, out, t0)
    finally:
        parallel.stop_pool()


def _build(args, formats, out: Path, t0: float) -> int:
    import time
    from .analysis.study import Study
    from .report.assemble import build_report
    from .report.render import build_outputs
    from .style.numbers import fmt
    study = Study(args.case)
    report = build_report(study, _sections(args.sections))
    _check_finite(study, partial=args.sections is not None)
    files = build_outputs(report, out, study.name, formats)
    if args.key:
        from .report.key import write_key
        files.update(write_key(study, out, study.name, formats))
    for kind, path in files.items():
        print(f"{kind.upper()}: {path}")
    if args.sheets:
        from .sheets import build_sheets
        print(f"Чертежи (A1): {build_sheets(study, out, study.name)}")
    print(f"Готово за {fmt(time.perf_counter() - t0, digits=1)} с.")
    return 0


def cmd_batch(args) -> int:
    from .batch import read_variants, run_batch
    variants = read_variants(Path(args.variants), Path(args.base) if args.base else None)
    results = run_batch(variants, _out_dir(Path(args.output)), args.jobs, _formats(args.format), _sections(args.sections),
                        key=args.key, sheets=args.sheets)
    ok = [r for r in results if r.ok]
    bad = [r for r in results if not r.ok]
    print(f"Отчётов построено: {len(ok)} из {len(results)}; манифест: {Path(args.output) / 'manifest.json'}")
    for r in bad:
        print(f"  вариант {r.variant}: {r.error}", file=sys.stderr)
    return 1 if bad else 0


def cmd_check(args) -> int:
    from .analysis.study import Study
    study = Study(args.case)
    study.meta  # [meta] values are checked as the note reads them
    from .report.safety import validate_report
    validate_report(study.root.table("report"))  # [report] as build reads it
    print(f"Вариант: {study.name}")
    if study.has_linkage:
        _check_linkage(study)
    for name in study.tasks():
        study.analysis(name).scalars  # every task reads and checks its section as build and export do
        print(f"Раздел [{name}] проверен.")
    _check_finite(study)
    return 0


def _check_finite(study, partial: bool = False) -> None:
    """No NaN/inf in the computed tables and scalars (an overflow is the case's fault);
    ``partial``: only what has been computed already (a note of some sections)."""
    from .export import check_finite, tables
    from .registry import BY_NAME
    if not partial:
        check_finite(tables(study), study.all_scalars(), str(study.spec.path))
        return
    tabs = {k: getattr(study, k) for k in ("kinematics", "cycle") if k in study.computed}
    scalars = {k: study.analysis(k).scalars for k in sorted(study.computed) if k in BY_NAME}
    check_finite(tabs, scalars, str(study.spec.path))


def _out_dir(path: Path) -> Path:
    """The output folder: an existing folder or a path that can be created (no file on the way)."""
    for p in [path, *path.parents]:
        if p.exists():
            if not p.is_dir():
                raise CaseError("папку вывода нельзя создать: на этом пути находится файл" if p != path
                                else "путь вывода указывает на файл, а нужна папка",
                                key="-o", got=str(p), expected="путь к папке")
            break
    return path


def _check_linkage(study) -> None:
    from .mechanism.structure import decomposition
    from .style.numbers import fmt
    st = study.structure
    rows, formula = decomposition(st, study.mechanism.driver)   # as the note and the key write it
    print(f"Число степеней свободы (Чебышев): {st.chebyshev}")
    roman = {1: "I", 2: "II", 3: "III", 4: "IV"}.get(st.mech_class, str(st.mech_class))
    print(f"Структурная формула: {formula}; механизм {roman} класса")
    for r in rows:
        print(f"  {r['title'] if r['g'] in r['title'] else r['g'] + ' — ' + r['title']}")
    for f in study.fits:
        print(f"Подобран параметр {f.name} = {fmt(f.value, sig=12)} (условие {f.condition} при {f.at})")
    if not study.has_cycle:
        study.kinematics  # [grid] cycle = false: the given positions must assemble
        print("Проверка пройдена: механизм собирается в заданных положениях (цикл не рассчитывается).")
        return
    study.cycle  # the whole cycle must assemble
    from .report.russian import flag_group, flag_where   # groups named as the note names them
    for name, fl in study.flags.items():
        if fl["singular"]:
            print(f"Внимание: особое положение {flag_where(study, name)}", file=sys.stderr)
        elif fl["low"]:
            import math
            print(f"Внимание: угол передачи {flag_where(study, name)} падает до "
                  f"{fmt(math.degrees(fl['min']), digits=1)}° (< 40°)", file=sys.stderr)
    for name, fl in study.guide_flags.items():
        if fl["singular"]:
            a, b = fl["points"]
            print(f"Внимание: группа {flag_group(study, 'mu_' + name)} проходит особое положение: шарнир {b} "
                  "проходит через ось "
                  f"кулисы {a} (наименьшее расстояние {fmt(fl['min'], sig=3)} м), аналог угловой скорости кулисы "
                  "неограниченно растёт", file=sys.stderr)
    print("Проверка пройдена: механизм собирается во всех положениях цикла.")


def cmd_warmup(args) -> int:
    import subprocess
    from .warmup import warmup
    # the report stack (font list, fonts, templates, bytecode) is loaded by a second process while
    # this one compiles the numba kernels: the two do not depend on each other
    report = subprocess.Popen([sys.executable, "-c", "from reportgen.warmup import warm_report; warm_report()"])
    # the general kinematics kernel (two thirds of the numba compile time) in a third process
    general = subprocess.Popen([sys.executable, "-c", "from reportgen.warmup import compile_general; "
                                "compile_general()"])
    warmup(general=False)
    failed = [text for proc, text in ((general, "скомпилировать общее ядро кинематики"),
                                      (report, "загрузить шрифты и шаблоны отчёта")) if proc.wait() != 0]
    for text in failed:
        print(f"Не удалось {text} (см. сообщение выше).", file=sys.stderr)
    if failed:
        return 1
    print("Ядра numba скомпилированы и сохранены в кэше; шрифты и шаблоны отчёта загружены.")
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="reportgen", description="Курсовой проект по ТММ: расчёт и отчёт по файлу варианта.")
    p.add_argument("--debug", action="store_true", help="показывать трассировку внутренних ошибок")
    sub = p.add_subparsers(dest="cmd", required=True, metavar="команда")
    e = sub.add_parser("export", help="все таблицы в CSV и скаляры в scalars.json")
    e.add_argument("case", help="файл варианта .toml")
    e.add_argument("-o", "--output", help="папка вывода (по умолчанию output/<вариант>)")
    e.add_argument("--at", help="значения обобщённой координаты через запятую, с единицами: \"30 deg,99.1 deg\"")
    e.set_defaults(func=cmd_export)
    c = sub.add_parser("check", help="проверить вариант: структура, подбор размеров, сборка во всём цикле")
    c.add_argument("case")
    c.set_defaults(func=cmd_check)
    b = sub.add_parser("build", help="отчёт по варианту: PDF и автономный HTML")
    b.add_argument("case", help="файл варианта .toml")
    b.add_argument("-o", "--output", default="output", help="папка вывода (по умолчанию output/)")
    b.add_argument("--format", default="pdf,html", help="pdf, html или pdf,html")
    b.add_argument("--sections", help="разделы через запятую: structure,kinematics,dynamics,forces")
    b.add_argument("--key", action="store_true", help="также ключ для преподавателя: <вариант>-key.pdf/.html")
    b.add_argument("--sheets", action="store_true", help="также листы графической части A1: <вариант>-sheets.pdf")
    b.add_argument("--jobs", type=int, default=None,
                   help="число процессов вёрстки PDF (по умолчанию — не больше двух, по числу ядер; "
                        "или переменная REPORTGEN_JOBS)")
    b.set_defaults(func=cmd_build)
    bt = sub.add_parser("batch", help="отчёты по всем вариантам группы и манифест")
    bt.add_argument("variants", help="таблица вариантов (.csv, .toml) или папка с файлами вариантов")
    bt.add_argument("-o", "--output", required=True, help="папка вывода")
    bt.add_argument("--base", help="базовый вариант для таблицы CSV")
    bt.add_argument("--jobs", type=int, default=None, help="число параллельных процессов (по умолчанию — число ядер)")
    bt.add_argument("--format", default="pdf,html")
    bt.add_argument("--sections")
    bt.add_argument("--key", action="store_true", help="также ключи для преподавателя (<вариант>-key.pdf/.html)")
    bt.add_argument("--sheets", action="store_true", help="также листы графической части A1 (<вариант>-sheets.pdf)")
    bt.set_defaults(func=cmd_batch)
    w = sub.add_parser("warmup", help="скомпилировать ядра numba (один раз после установки)")
    w.set_defaults(func=cmd_warmup)
    for hook in _PARSER_HOOKS:
        hook(sub)
    return p


_PARSER_HOOKS: list = []


def main(argv: list[str] | None = None) -> int:
    import warnings
    parser = build_parser()
    args = parser.parse_args(argv)
    debug = args.debug or os.environ.get("REPORTGEN_DEBUG")
    if not debug:
        # numpy's RuntimeWarnings (with source lines) are not for the user: a non-finite result
        # is reported as a CaseError by the finiteness checks
        warnings.simplefilter("ignore", RuntimeWarning)
    from .core.memory import collect_less
    collect_less()
    try:
        return args.func(args)
    except ReportgenError as e:
        print(f"Ошибка: {e}", file=sys.stderr)
        return 2
    except RecursionError:
        if debug:
            raise
        print("Ошибка: слишком глубокая вложенность данных варианта (таблиц, массивов или выражений).",
              file=sys.stderr)
        return 2
    except MemoryError:
        print("Ошибка: недостаточно памяти; уменьшите [grid] positions или cycle_points.", file=sys.stderr)
        return 2
    except OSError as e:
        if debug:
            raise
        if e.filename is None and e.strerror is None:  # e.g. a font named by REPORTGEN_FONT is not installed
            print(f"Ошибка: {str(e)[:300]}", file=sys.stderr)
        else:
            what = f" «{str(e.filename)[:200]}»" if e.filename else ""
            print(f"Ошибка: не удалось прочитать или записать файл{what}: {(e.strerror or str(e))[:300]}.",
                  file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("Прервано.", file=sys.stderr)
        return 130
    except Exception as e:  # a bug, not the user's input
        if debug:
            raise
        print(f"Внутренняя ошибка программы: {type(e).__name__}: {str(e)[:300]}\n"
              "Запустите с --debug и сообщите разработчикам.", file=sys.stderr)
        return 3


if __name__ == "__main__":
    sys.exit(main())
