"""Wall-clock figures of the commands a user runs, as issue #15 states its targets.

Usage (from the repository root; ``make bench`` runs it)::

    python bench/bench_cli.py            # everything (about 10 minutes on 2 quiet cores)
    python bench/bench_cli.py --only help,export,build,first,batch,pdf,fresh
    python bench/bench_cli.py --batch-variants 10   # a smaller class

Writes ``bench/results/cli.json`` and ``docs/performance.md``. Every command runs in a fresh
interpreter (``python -m reportgen.cli …`` with this checkout first on ``sys.path``), so the
figures include imports, numba's on-disk cache and the fonts, as a user sees them. ``fresh``
clones this checkout into a temporary folder and runs ``make setup`` there (a new .venv from
PyPI with pip's cache off, new user caches), then the first and a second ``reportgen build`` of
the default case: ``make report`` on a fresh machine, timed in its two steps (the Debian
packages of ``scripts/setup.sh`` are installed once per machine and are not re-installed).
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CASE = "cases/ws000_six_bar.toml"
CLASS = "cases/class_six_bar.csv"
DEFAULT_CASE = "cases/ws000_six_bar_corrected.toml"  # what `make report` builds (Makefile CASE)
PARTS = ("help", "export", "build", "first", "batch", "pdf", "fresh")
TARGETS = {"help": 0.5, "export": 2.0, "build": 8.0, "first": 15.0, "batch": 120.0, "pdf_ratio": 1.3,
           "fresh": 90.0, "first_over_warm": 2.0}


def machine() -> dict:
    cpu = ""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        cpu = platform.processor()
    ram = 0.0
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemTotal"):
                ram = round(int(line.split()[1]) / 1024 ** 2, 1)
    except OSError:
        pass
    import weasyprint
    return {"nproc": os.cpu_count(), "cpu": cpu, "ram_gb": ram, "python": platform.python_version(),
            "platform": platform.platform(), "weasyprint": weasyprint.__version__}


def _env(root: Path = ROOT, **extra) -> dict:
    env = dict(os.environ, PYTHONPATH=str(root), CI="1")
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # a user's Python keeps the bytecode of reportgen
    env.update(extra)
    return env


def run(args: list[str], root: Path = ROOT, **env) -> float:
    """Wall seconds of ``python -m reportgen.cli ARGS`` in the checkout ``root`` (exit code 0 or 1
    accepted: a batch with a failing variant exits 1); its CPU seconds (user + sys of the command
    and of the worker processes it waited for) are appended to :data:`CPU`."""
    import resource
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "reportgen.cli", *args], cwd=root, env=_env(root, **env),
                       capture_output=True, text=True)
    dt = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    CPU.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    if p.returncode not in (0, 1):
        raise SystemExit(f"reportgen {' '.join(args)} failed:\n{p.stderr}")
    return dt


CPU: list[float] = []


def median_of(n: int, args: list[str], **env) -> dict:
    times, cpu = [], []
    for _ in range(n):
        times.append(run(args, **env))
        cpu.append(CPU[-1])
    return {"median_s": round(statistics.median(times), 2), "runs_s": [round(t, 2) for t in times],
            "cpu_median_s": round(statistics.median(cpu), 2), "cpu_runs_s": [round(t, 2) for t in cpu],
            "load_average": [round(x, 2) for x in os.getloadavg()]}


def _batch_run(args: list[str], out: Path, n: int, root: Path = ROOT, **env) -> dict:
    load = os.getloadavg()[0]
    dt = run(args, root, **env)
    m = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    # The workers are children of multiprocessing's fork server, not counted in RUSAGE_CHILDREN
    # of the command: their CPU time per variant is in the manifest (cpu_seconds).
    ok = [v for v in m["variants"] if v["ok"]]
    cpu = [v.get("cpu_seconds", 0.0) for v in ok]
    passes = [v.get("layout_passes", []) for v in ok]
    parts = max((len(p) for p in passes), default=0)
    return {"variants": n, "ok": m["ok"], "wall_s": round(dt, 1), "jobs": 2,
            "load_average": [round(load, 2), round(os.getloadavg()[0], 2)],
            "per_variant_s": round(dt / max(1, n), 2),
            "cpu_s": round(sum(cpu) + CPU[-1], 1),  # the workers' variants + the command itself
            "variant_cpu_median_s": round(statistics.median(cpu), 2) if cpu else None,
            "variant_cpu_first_s": cpu[0] if cpu else None,
            # layout passes of each body part: (first variant, the most of any later one)
            "layout_passes_first": passes[0] if passes else [],
            "layout_passes_later_max": [max((p[i] for p in passes[1:] if i < len(p)), default=0)
                                        for i in range(parts)],
            "workers": m.get("workers", [])}


def class_table(tmp: Path, n: int) -> tuple[Path, int]:
    """The first ``n`` assembling rows of :data:`CLASS` written to ``tmp/class.csv``; (path, rows)."""
    with open(ROOT / CLASS, encoding="utf-8", newline="") as f:
        rows = list(csv.DictReader(f))
    good = [r for r in rows if r.get("variant", r.get("name")) != "31"][:n]  # 31 cannot assemble
    table = tmp / "class.csv"
    with table.open("w", encoding="utf-8", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(good)
    return table, len(good)


def bench_batch(tmp: Path, n: int) -> dict:
    """The class of ``n`` variants twice: first as a teacher builds a class never built before (a
    new cache folder with only what `reportgen warmup` and one build of the base case put in it:
    no split points of any variant), then again (every variant's split points remembered)."""
    table, n = class_table(tmp, n)
    cache = tmp / "class-cache"
    cache.mkdir()
    env = {"XDG_CACHE_HOME": str(cache), "REPORTGEN_CACHE": str(cache / "reportgen")}
    run(["warmup"], **env)
    run(["build", CASE, "--format", "pdf,html", "-o", str(tmp / "base")], **env)
    out = tmp / "batch"
    args = ["batch", str(table), "--base", str(ROOT / CASE), "-o", str(out), "--jobs", "2"]
    new = _batch_run(args, out, n, **env)
    again = _batch_run(args, out, n, **env)
    command = f"reportgen batch <первые {n} строк {CLASS}> --base {CASE} -o out --jobs 2"
    return again | {"command": command, "new_class": new | {
        "command": "XDG_CACHE_HOME=$(mktemp -d) (reportgen warmup; reportgen build " + CASE + "; " + command + ")"}}


def _timed(cmd: list[str], cwd: Path, env: dict) -> tuple[float, float]:
    """Wall and CPU seconds (user + sys of the command and its children) of ``cmd``."""
    import resource
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stdout[-2000:]}\n{p.stderr[-4000:]}")
    return dt, after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


def bench_fresh(tmp: Path) -> dict:
    """``make report`` on a fresh clone: ``make setup`` (new .venv, every wheel downloaded with
    pip's cache off, numba kernels compiled, font list built), then the first ``reportgen
    build`` of the default case, then a second one (warm) for the ratio."""
    clone = tmp / "fresh"
    subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
    cache = tmp / "fresh-cache"  # a new user: no matplotlib font list, formulas, split points
    cache.mkdir()
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONDONTWRITEBYTECODE", "REPORTGEN_CACHE", "MPLCONFIGDIR",
                        "NUMBA_CACHE_DIR", "SOURCE_DATE_EPOCH")}
    env.update(XDG_CACHE_HOME=str(cache), PIP_NO_CACHE_DIR="1", CI="1")
    env["PATH"] = os.pathsep.join(p for p in env.get("PATH", "").split(os.pathsep) if ".venv" not in p)
    load0 = os.getloadavg()[0]
    setup_s, setup_cpu = _timed(["make", "setup"], clone, env)
    build = [str(clone / ".venv" / "bin" / "reportgen"), "build", DEFAULT_CASE]
    first_s, first_cpu = _timed(build, clone, env)
    warm_s, warm_cpu = _timed(build, clone, env)
    return {"setup_s": round(setup_s, 1), "setup_cpu_s": round(setup_cpu, 1),
            "first_build_s": round(first_s, 1), "first_build_cpu_s": round(first_cpu, 1),
            "warm_build_s": round(warm_s, 1), "warm_build_cpu_s": round(warm_cpu, 1),
            "make_report_s": round(setup_s + first_s, 1),
            "first_over_warm": round(first_s / warm_s, 2) if warm_s else None,
            "load_average": [round(load0, 2), round(os.getloadavg()[0], 2)],
            "case": DEFAULT_CASE,
            "command": "git clone . /tmp/x && cd /tmp/x && PIP_NO_CACHE_DIR=1 XDG_CACHE_HOME=$(mktemp -d) "
                       "/usr/bin/time make report"}


def bench_pdf_vs_plain() -> dict:
    """ws000's PDF against WeasyPrint alone on a plain document of the same page count (running
    text only; same fonts, page setup, CSS), both with their table split points known (second
    write). The note is written as the CLI writes it (in parts, by note_jobs() processes); the
    plain document is laid out and written by WeasyPrint as one document. Wall and CPU seconds
    (this process and the workers) of ``write_pdf``; the median of three of each."""
    sys.path.insert(0, str(ROOT))
    from reportgen.analysis.study import Study
    from reportgen.report import parallel, render
    from reportgen.report.assemble import build_report
    from reportgen.report.document import Report, Section

    def timed(report, path, runs=3, **kw) -> tuple[float, float, int]:
        render.write_pdf(report, path, **kw)  # the first layout finds the split points
        walls, cpus = [], []
        for _ in range(runs):
            c0, t0 = os.times(), time.perf_counter()
            render.write_pdf(report, path, **kw)
            t1, c1 = time.perf_counter(), os.times()
            walls.append(t1 - t0)
            cpus.append(sum(c1[:4]) - sum(c0[:4]))
        return statistics.median(walls), statistics.median(cpus), render.last_stats.pages

    def plain(n_par: int) -> Report:
        text = ("Механизм раскладывается на начальный механизм и группы Ассура; для каждой группы "
                "записываются уравнения замкнутого векторного контура и решаются в замкнутом виде. ") * 3
        sections = []
        for k in range(0, max(1, n_par), 20):
            s = Section(f"Раздел {k // 20 + 1}", f"s{k}")
            for _ in range(min(20, n_par - k)):
                s.paragraph(text)
            sections.append(s)
        return Report(meta={}, assignment=[], introduction=[], sections=sections, conclusion=[],
                      references=[], options={"title_page": False, "assignment_page": False,
                                              "section_new_page": False})  # one document

    def weasyprint_alone(report, path, runs=3) -> tuple[float, float]:
        """The plain document's print HTML laid out and written by WeasyPrint's own ``HTML``
        (its HTML parser, its stylesheet handling, no reportgen shortcut): the issue's «WeasyPrint
        alone». The plain document through ``render.write_pdf`` profits from reportgen's own
        shortcuts (the parsed stylesheet, fasthtml), so it is reported beside, not as the base."""
        from weasyprint import HTML
        from weasyprint.text.fonts import FontConfiguration

        from reportgen.report.safety import url_fetcher
        html = render.render_html(report, for_print=True)
        walls, cpus = [], []
        for _ in range(runs + 1):
            c0, t0 = os.times(), time.perf_counter()
            HTML(string=html, base_url=str(render.TEMPLATES_DIR), url_fetcher=url_fetcher()).write_pdf(
                path, font_config=FontConfiguration())
            t1, c1 = time.perf_counter(), os.times()
            walls.append(t1 - t0)
            cpus.append(sum(c1[:4]) - sum(c0[:4]))
        return statistics.median(walls[1:]), statistics.median(cpus[1:])  # the first warms the fonts

    with tempfile.TemporaryDirectory() as d:
        report = build_report(Study(ROOT / CASE))
        jobs = parallel.note_jobs()
        t_note, c_note, pages = timed(report, Path(d) / "note.pdf")
        t_one, c_one, _ = timed(report, Path(d) / "note1.pdf", runs=1, jobs=1)
        _, _, p20 = timed(plain(20), Path(d) / "probe.pdf", runs=1)
        n = max(1, round(20 * pages / p20))
        _, _, pn = timed(plain(n), Path(d) / "probe.pdf", runs=1)
        n = max(1, round(n * pages / pn))
        t_plain, c_plain, plain_pages = timed(plain(n), Path(d) / "plain.pdf")
        t_alone, c_alone = weasyprint_alone(plain(n), Path(d) / "alone.pdf")
    return {"note_pdf_s": round(t_note, 2), "note_pdf_cpu_s": round(c_note, 2), "note_jobs": jobs,
            "note_pdf_one_worker_s": round(t_one, 2), "note_pdf_one_worker_cpu_s": round(c_one, 2),
            "note_pages": pages, "plain_pdf_s": round(t_plain, 2), "plain_pdf_cpu_s": round(c_plain, 2),
            "plain_pages": plain_pages, "plain_weasyprint_s": round(t_alone, 2),
            "plain_weasyprint_cpu_s": round(c_alone, 2), "ratio": round(t_note / t_alone, 2),
            "ratio_own_pipeline": round(t_note / t_plain, 2),
            "load_average": [round(x, 2) for x in os.getloadavg()]}


def _fmt(x: float) -> str:
    return f"{x:.2f}".replace(".", ",")


def write_doc(res: dict) -> Path:
    """docs/performance.md from the recorded figures (Russian, each with its command)."""
    m = res["machine"]
    rows = []

    def row(name, key, value, target, command, r=None):
        ok = "да" if value <= target else "нет"
        r = r if r is not None else res[key]
        cpu = r.get("cpu_median_s", r.get("cpu_s"))
        load = r.get("load_average")
        when = ([f"load {_fmt(load[0])}"] if load else []) + ([r["date"]] if r.get("date") else [])
        extra = (f"{_fmt(cpu)} с" if cpu is not None else "—") + (f" ({', '.join(when)})" if when else "")
        rows.append(f"| {name} | {_fmt(value)} с | {extra} | ≤ {_fmt(target)} с | {ok} | `{command}` |")

    if "help" in res:
        row("`reportgen --help` (медиана 5)", "help", res["help"]["median_s"], TARGETS["help"], res["help"]["command"])
    if "export" in res:
        row(f"`reportgen export` ws000 (медиана {len(res['export'].get('runs_s', [])) or 3})", "export", res["export"]["median_s"], TARGETS["export"],
            res["export"]["command"])
    if "build" in res:
        row(f"`reportgen build` ws000, PDF и HTML, тёплый (медиана {len(res['build'].get('runs_s', [])) or 3}: "
            + ", ".join(_fmt(v) for v in res["build"].get("runs_s", [])) + " с)", "build", res["build"]["median_s"],
            TARGETS["build"], res["build"]["command"])
    if "first" in res:
        row("первая сборка с пустым кэшем", "first", res["first"]["wall_s"], TARGETS["first"],
            res["first"]["command"])
    if "batch" in res and res["batch"].get("new_class"):
        b = res["batch"]["new_class"]
        row(f"пакет из {b['variants']} вариантов нового класса (в кэше только `warmup` и сборка {CASE}), "
            "2 процесса", "batch", b["wall_s"], TARGETS["batch"], b["command"], b | {"date": res["batch"].get("date")})
    if "batch" in res:
        b = res["batch"]
        row("тот же пакет ещё раз (точки разрыва всех вариантов известны), 2 процесса", "batch", b["wall_s"],
            TARGETS["batch"], b["command"])
    if "fresh" in res:
        f = res["fresh"]
        r = res["fresh"]
        rows.append(f"| `make report` на новой копии (установка {_fmt(f['setup_s'])} с + первая сборка "
                    f"{_fmt(f['first_build_s'])} с) | {_fmt(f['make_report_s'])} с | "
                    f"{_fmt(f['setup_cpu_s'] + f['first_build_cpu_s'])} с (load {_fmt(r['load_average'][0])}"
                    f"{', ' + r['date'] if r.get('date') else ''}) | "
                    f"≤ {_fmt(TARGETS['fresh'])} с | {'да' if f['make_report_s'] <= TARGETS['fresh'] else 'нет'} | "
                    f"`{f['command']}` |")
        ratio = f.get("first_over_warm") or 0.0
        rows.append(f"| первая сборка после установки / повторная ({f['case']}) | {_fmt(f['first_build_s'])} с / "
                    f"{_fmt(f['warm_build_s'])} с = {_fmt(ratio)} | {_fmt(f['first_build_cpu_s'])} с / "
                    f"{_fmt(f['warm_build_cpu_s'])} с | ≤ {_fmt(TARGETS['first_over_warm'])} | "
                    f"{'да' if ratio <= TARGETS['first_over_warm'] else 'нет'} | то же, затем ещё раз "
                    f"`.venv/bin/reportgen build {f['case']}` |")
    lines = [
        BEGIN,
        "",
        "Все цифры этой таблицы измерены командой `make bench` (`python bench/bench_cli.py`; результаты в",
        "`bench/results/cli.json`), каждая команда запускается в новом процессе `python -m reportgen.cli`,",
        "как её запускает пользователь. Поэтапные времена внутри процесса: `python bench/bench_build.py`",
        "(`bench/results/build.json`).",
        "",
        f"Машина: {m['nproc']} ядра, {m['cpu']}, ОЗУ {_fmt(m['ram_gb'])} ГБ; Python {m['python']},",
        f"WeasyPrint {m['weasyprint']}; {m['platform']}. Дата последнего замера: {res.get('date', '')} (у каждой строки — своя дата в столбце ЦП).",
        f"Средняя загрузка (load average 1/5/15 мин) до замера: {res['load_average_before']}, после: "
        f"{res['load_average_after']}."
        + (" **Замер сделан под нагрузкой** (машину делили другие процессы): времена завышены."
           if max(res["load_average_before"][0], res["load_average_after"][0]) > (m["nproc"] or 1) else ""),
        "",
        "| Что | Время (стен.) | ЦП (user+sys, с рабочими процессами) | Цель (стен.) | Достигнута | Команда |",
        "|---|---|---|---|---|---|",
        *rows,
    ]
    if "batch" in res and res["batch"].get("workers"):
        b = res["batch"]
        peaks = ", ".join(f"{_fmt(w['peak_rss_mb'])} МБ ({w['variants']} вар.)" for w in b["workers"])
        lines += ["", f"Пиковая память рабочих процессов пакета (из `manifest.json`, поле `workers`): {peaks}."]
        nb = b.get("new_class")
        if nb and nb.get("variant_cpu_median_s") is not None:
            lines += [f"Новый класс: процессорное время варианта медиана {_fmt(nb['variant_cpu_median_s'])} с "
                      f"(первый {_fmt(nb['variant_cpu_first_s'])} с); проходов вёрстки по частям записки "
                      f"(`layout_passes`): первый вариант {nb.get('layout_passes_first')}, наибольшее у "
                      f"остальных {nb.get('layout_passes_later_max')}."]
        if b.get("variant_cpu_median_s") is not None:
            lines += [f"Процессорное время одного варианта в рабочем процессе (`cpu_seconds` в `manifest.json`): "
                      f"медиана {_fmt(b['variant_cpu_median_s'])} с, первый вариант {_fmt(b['variant_cpu_first_s'])} с; "
                      f"всего {_fmt(b['cpu_s'])} с ЦП за {_fmt(b['wall_s'])} с стен."]
    if "pdf" in res:
        p = res["pdf"]
        lines += ["", "PDF записки ws000 против WeasyPrint на простом документе того же объёма (только текст, те же",
                  "шрифты и поля, один документ; вёрстка + запись, точки разрыва таблиц известны, медиана трёх):",
                  f"{p['note_pages']} стр. записки — {_fmt(p['note_pdf_s'])} с стен. ({_fmt(p.get('note_pdf_cpu_s', 0))} с ЦП, "
                  f"вёрстка по частям в {p.get('note_jobs', 1)} процессах; в одном процессе — "
                  f"{_fmt(p.get('note_pdf_one_worker_s', 0))} с), {p['plain_pages']} стр. текста — "
                  f"{_fmt(p.get('plain_weasyprint_s', p['plain_pdf_s']))} с стен. у самого WeasyPrint "
                  f"(`weasyprint.HTML(...).write_pdf` на печатном HTML документа; "
                  f"{_fmt(p.get('plain_weasyprint_cpu_s', 0))} с ЦП), {_fmt(p['plain_pdf_s'])} с стен. через "
                  f"`render.write_pdf` ({_fmt(p.get('plain_pdf_cpu_s', 0))} с ЦП; с сокращениями reportgen: "
                  f"разобранная таблица стилей, fasthtml; отношение к этому — {_fmt(p.get('ratio_own_pipeline', 0))}); "
                  f"отношение {_fmt(p['ratio'])} (цель ≤ {_fmt(TARGETS['pdf_ratio'])}). "
                  + (f"Load average при замере: {_fmt(p['load_average'][0])}. " if p.get("load_average") else "")
                  + f"Команда: `{p['command']}`."]
    lines += ["", END]
    dest = ROOT / "docs" / "performance.md"
    text = dest.read_text(encoding="utf-8") if dest.exists() else "# Производительность\n\n"
    block = "\n".join(lines)
    if BEGIN in text and END in text:  # only this generated block is replaced, the rest is kept
        head, rest = text.split(BEGIN, 1)
        text = head + block + rest.split(END, 1)[1]
    else:
        text = text.rstrip("\n") + "\n\n" + block + "\n"
    dest.write_text(text, encoding="utf-8")
    return dest


BEGIN = "<!-- bench/bench_cli.py: начало (этот блок пишет `make bench`) -->"
END = "<!-- bench/bench_cli.py: конец -->"


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default=",".join(PARTS), help="что мерить: " + ",".join(PARTS))
    ap.add_argument("--batch-variants", type=int, default=30)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--doc-only", action="store_true", help="только пересобрать docs/performance.md из JSON")
    a = ap.parse_args(argv)
    parts = [p.strip() for p in a.only.split(",") if p.strip()]
    dest = ROOT / "bench" / "results" / "cli.json"
    res = json.loads(dest.read_text(encoding="utf-8")) if dest.exists() else {}
    if a.doc_only:
        print(write_doc(res))
        return
    res["machine"] = machine()
    res["load_average_before"] = [round(x, 2) for x in os.getloadavg()]
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        build = ["build", CASE, "--format", "pdf,html", "-o", str(tmp / "out")]
        if "help" in parts:
            run(["--help"])
            res["help"] = median_of(5, ["--help"]) | {"command": "reportgen --help"}
        if "export" in parts:
            run(["export", CASE, "-o", str(tmp / "exp")])
            res["export"] = median_of(a.runs, ["export", CASE, "-o", str(tmp / "exp")]) | {
                "command": f"reportgen export {CASE}"}
        if "build" in parts:
            run(build)  # warm: numba cache, formulas, split points, matplotlib font list
            res["build"] = median_of(a.runs, build) | {
                "command": f"reportgen build {CASE} --format pdf,html"}
        if "first" in parts:
            cache = tmp / "empty-cache"
            cache.mkdir()
            res["first"] = {"wall_s": round(run(build, XDG_CACHE_HOME=str(cache)), 2), "cpu_s": round(CPU[-1], 2),
                            "load_average": [round(x, 2) for x in os.getloadavg()],
                            "command": f"XDG_CACHE_HOME=$(mktemp -d) reportgen build {CASE} --format pdf,html"}
            shutil.rmtree(cache, ignore_errors=True)
        if "batch" in parts:
            res["batch"] = bench_batch(tmp, a.batch_variants)
        if "pdf" in parts:
            res["pdf"] = bench_pdf_vs_plain() | {"command": "python bench/bench_cli.py --only pdf"}
        if "fresh" in parts:
            try:
                res["fresh"] = bench_fresh(tmp)
            except (SystemExit, subprocess.CalledProcessError, OSError) as e:  # keep the other figures
                print(f"fresh: не измерено: {e}", file=sys.stderr)
    res["load_average_after"] = [round(x, 2) for x in os.getloadavg()]
    res["date"] = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    for part in parts:  # the date of each figure: a partial run keeps the older ones
        if isinstance(res.get(part), dict):
            res[part]["date"] = res["date"]
    dest.parent.mkdir(parents=True, exist_ok=True)
    dest.write_text(json.dumps(res, ensure_ascii=False, indent=2) + "\n", encoding="utf-8")
    print(json.dumps({k: v for k, v in res.items() if k != "machine"}, ensure_ascii=False, indent=1))
    print(f"результаты: {dest}; отчёт: {write_doc(res)}")


if __name__ == "__main__":
    main()
