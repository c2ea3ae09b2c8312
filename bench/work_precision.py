"""Work–precision benchmark: kinematics, peers, dynamics, cycle integrals, sections of a note.

Usage (one command; ≈ 10 min on the shared 2-core machine, more with ``--peers``)::

    .venv/bin/python bench/work_precision.py [--quick] [--peers | --peer PYTHON] [--no-sections]

writes into ``output/bench/``: ``work_precision.csv`` (kinematics and peers),
``dynamics_precision.csv``, ``cycle_integrals.csv``, ``sections.csv``, ``work_precision.md`` (every
table) and the log–log plots ``work_precision.png`` (time per cycle against the error) and
``dynamics_precision.png``.

Kinematics: a slider-crank, a crank-rocker, the six-bar of worksheet 000 and a class III
mechanism, N = 360, 3 600, 36 000 positions per cycle.  Errors are the maximum scaled error
|x − x_ref| / max(1, |x_ref|) of the point coordinates and their first and second analogs at the
24 positions q = start + k·15° (on every grid), against the 50-digit mpmath reference of
``tests/reference.py`` computed by this run (Newton on the loop equations at 50 digits, analogs by
5-point stencils with h = 1e-12; its own error < 1e-25).  Methods:

* ``engine`` — the whole-grid kernel (closed-form class II groups, analogs from the linear
  systems Φ_x x′ = −Φ_q, Φ_x x″ = −γ) and the points;
* ``newton`` — the same kernel with every group solved by Newton on its loop equations
  (second-order predictor from the previous position), analogs as above;
* ``complex`` — complex step (``bench/complex_step.py``): the whole mechanism solved by Newton in
  complex arithmetic at q + ih, h = 1e-20; x′ = Im x/h, x″ = Im x′(q + ih)/h;
* ``central`` — positions by the engine, analogs by central differences on the same grid
  (the Mathcad d/dφ way): x′ ≈ (x₊ − x₋)/2h, x″ ≈ (x₊ − 2x + x₋)/h²;
* ``forward`` — forward differences x′ ≈ (x₊ − x)/h, x″ ≈ (x₊₊ − 2x₊ + x)/h²;
* peers in a separate virtual environment (``--peers`` creates ``output/bench/peer-venv`` and
  installs them there; ``--peer PYTHON`` uses an existing one): pylinkage's numba path and the
  package ``mechanism`` on the slider-crank and the crank-rocker (``bench/work_precision_peer.py``);
  pyslvs is tried and its pip error recorded.

Times are the median CPU time (``time.process_time``) of warm calls (kernels compiled before).
Dynamics: ``bench/dynamics_precision.py``; sections of a note: ``bench/bench_sections.py``.
"""
from __future__ import annotations

import argparse
import csv
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "bench"))

OUT = ROOT / "output" / "bench"
CASES = [("кривошипно-ползунный", "cases/slider_crank.toml"),
         ("кривошипно-коромысловый", "cases/four_bar.toml"),
         ("шестизвенный (лист 000)", "cases/ws000_six_bar.toml"),
         ("III класса (триада)", "cases/class3_triad.toml")]
NS = [360, 3600, 36000]
NREF = 24
PEERS = ("pylinkage", "mechanism")
PEER_VENV = OUT / "peer-venv"


def timed(fn, budget: float = 0.6, min_runs: int = 3, max_runs: int = 200):
    """Median CPU time of the process (time.process_time: a shared, loaded machine inflates it
    less than wall time) over warm calls of fn (after one warm-up call), and the last result."""
    out = fn()
    ts = []
    t_start = time.process_time()
    while len(ts) < min_runs or (len(ts) < max_runs and time.process_time() - t_start < budget):
        t0 = time.process_time()
        out = fn()
        ts.append(time.process_time() - t0)
    return statistics.median(ts), out


def point_arrays(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(N, npoints, 6) → positions, first, second analogs as (N, 2·npoints) arrays."""
    n = pts.shape[0]
    return (pts[:, :, 0:2].reshape(n, -1), pts[:, :, 2:4].reshape(n, -1), pts[:, :, 4:6].reshape(n, -1))


def scaled_error(got: np.ndarray, ref: np.ndarray) -> float:
    return float(np.max(np.abs(got - ref) / np.maximum(1.0, np.abs(ref))))


def reference(study, q: np.ndarray, names: list[str]) -> tuple[np.ndarray, ...]:
    from reference import reference_columns
    cols = reference_columns(study, q)
    out = []
    for pre in (("x_", "y_"), ("vqx_", "vqy_"), ("aqx_", "aqy_")):
        out.append(np.array([[float(cols[pre[c] + p][i]) for p in names for c in (0, 1)]
                             for i in range(len(q))]))
    return tuple(out)


def kinematics_rows(quick: bool) -> list[dict]:
    from reportgen.analysis import linkage as L
    from reportgen.analysis.study import Study
    from reportgen.core import kinematics as K
    from complex_step import ComplexStepKinematics
    rows = []
    for title, path in CASES:
        s = Study(ROOT / path)
        model = s.model
        start, length = s.grid.start, s.grid.length
        qref = start + length * np.arange(NREF) / NREF
        t0 = time.perf_counter()
        rx, rv, ra = reference(s, qref, model.point_names)
        print(f"{title}: reference at {NREF} positions in {time.perf_counter() - t0:.1f} s", flush=True)
        gk_newton = np.full_like(model.gkind, K.G_NEWTON)
        for N in (NS[:2] if quick else NS):
            q = start + length * np.arange(N + 1) / N
            h = length / N
            idx = np.arange(NREF) * (N // NREF)
            pose0 = L.run_kernel(model, q[:1])[0][0]

            def engine():
                return L.solve(model, q).points

            def newton():
                pose, d1, d2, qual, fail = K.solve_cycle(
                    q, model.jt, model.jb, model.jf, gk_newton, model.gspec, model.gsigma, model.gjoint,
                    model.gnj, model.gbody, model.gnb, pose0, model.size)
                assert fail[0] == 0
                return K.points_cycle(pose, d1, d2, q, model.pbody, model.ploc)

            cs = ComplexStepKinematics(s)
            X0 = cs.start_pose(float(q[0]))

            def complex_step():
                return cs.points(q, model.point_names, X0)

            def central():
                x = point_arrays(L.solve(model, q).points)[0][:-1]
                xp, xm = np.roll(x, -1, axis=0), np.roll(x, 1, axis=0)
                return x, (xp - xm) / (2 * h), (xp - 2 * x + xm) / (h * h)

            def forward():
                x = point_arrays(L.solve(model, q).points)[0][:-1]
                xp, xpp = np.roll(x, -1, axis=0), np.roll(x, -2, axis=0)
                return x, (xp - x) / h, (xpp - 2 * xp + x) / (h * h)

            for name, fn, is_pts in (("engine", engine, True), ("newton", newton, True),
                                     ("complex", complex_step, True),
                                     ("central", central, False), ("forward", forward, False)):
                t, out = timed(fn, min_runs=1 if name == "complex" and N > 3600 else 3)
                arrs = point_arrays(out) if is_pts else out
                errs = [scaled_error(a[idx], r) for a, r in zip(arrs, (rx, rv, ra))]
                rows.append(dict(case=title, N=N, method=name, time_ms=t * 1e3,
                                 ns_per_position=t / (N + 1) * 1e9,
                                 err_position=errs[0], err_first=errs[1], err_second=errs[2]))
                print(f"  N={N:6d} {name:8s} {t * 1e3:9.3f} ms  errors {errs[0]:.1e} {errs[1]:.1e} "
                      f"{errs[2]:.1e}", flush=True)
    return rows


def make_peer_venv() -> tuple[str, dict[str, str]]:
    """Create ``output/bench/peer-venv`` (output/ is ignored by git) and install the peers there;
    returns its python and, per package that did not install, pip's error lines."""
    import subprocess
    py = PEER_VENV / "bin" / "python"
    if not py.exists():
        subprocess.run([sys.executable, "-m", "venv", str(PEER_VENV)], check=True)
    failed = {}
    for name, pkgs in (("pylinkage", ["pylinkage", "numba"]), ("mechanism", ["mechanism"]), ("pyslvs", ["pyslvs"])):
        log = OUT / f"pip-{name}.log"
        r = subprocess.run([str(py), "-m", "pip", "install", *pkgs], capture_output=True, text=True)
        log.write_text(r.stdout + r.stderr, encoding="utf-8")
        if r.returncode:
            lines = [l.strip() for l in (r.stdout + r.stderr).splitlines()]
            keep = [l for l in lines if l.startswith(("ERROR", "pyslvs/", "Cython.Compiler"))
                    or ": error" in l or "Error compiling" in l]
            failed[name] = " | ".join(dict.fromkeys(keep[:4]))
            print(f"{name}: не устанавливается ({failed[name]}; подробно: {log})", flush=True)
    return str(py), failed


PEER_CASES = [("кривошипно-ползунный", "cases/slider_crank.toml", "slider_crank"),
              ("кривошипно-коромысловый", "cases/four_bar.toml", "four_bar")]


def peer_rows(python: str, quick: bool) -> list[dict]:
    """Peers on the slider-crank and the crank-rocker, run by bench/work_precision_peer.py in
    their own virtual environment; errors of point B (the peers' output joint), rows j ↔
    q_j = 2πj/N."""
    import json
    import subprocess
    from reportgen.analysis.study import Study
    rows = []
    for title, path, mech in PEER_CASES:
        s = Study(ROOT / path)
        if abs(s.grid.start) > 1e-15 or abs(s.grid.length - 2 * math.pi) > 1e-12:
            raise ValueError(f"{path}: the peers are sampled at q = 2πj/N")
        qref = s.grid.start + s.grid.length * np.arange(NREF) / NREF
        rx, rv, ra = reference(s, qref, ["B"])
        for package in PEERS:
            for N in (NS[:2] if quick else NS):
                try:
                    res = subprocess.run([python, str(ROOT / "bench/work_precision_peer.py"), str(N), package, mech],
                                         capture_output=True, text=True, timeout=3600, check=True)
                except (OSError, subprocess.SubprocessError) as e:
                    print(f"{package}: not measured ({e})", flush=True)
                    break
                out = json.loads(res.stdout)
                idx = np.arange(NREF) * (N // NREF)
                B, vB, aB = (np.asarray(out[k])[idx] for k in ("B", "vB", "aB"))
                errs = [scaled_error(a, r) for a, r in zip((B, vB, aB), (rx, rv, ra))]
                for label, key, with_analogs in ((f"{package}, положения", "time_positions", False),
                                                 (f"{package}, с аналогами", "time_with_kinematics", True)):
                    t = out[key]
                    rows.append(dict(case=title, N=N, method=label, time_ms=t * 1e3,
                                     ns_per_position=t / N * 1e9, err_position=errs[0],
                                     err_first=errs[1] if with_analogs else float("nan"),
                                     err_second=errs[2] if with_analogs else float("nan")))
                print(f"  {title}: N={N:6d} {package:10s} {out['time_with_kinematics'] * 1e3:10.3f} ms  errors "
                      f"{errs[0]:.1e} {errs[1]:.1e} {errs[2]:.1e}", flush=True)
    return rows


def read_csv(path: Path) -> list[dict]:
    """Rows of a CSV written by :func:`write_csv`, numbers converted back."""
    def conv(v: str):
        for t in (int, float):
            try:
                return t(v)
            except ValueError:
                pass
        return v
    with path.open(encoding="utf-8") as f:
        return [{k: conv(v) for k, v in r.items()} for r in csv.DictReader(f)]


def write_csv(path: Path, rows: list[dict]) -> None:
    with path.open("w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


METHODS = ("engine", "newton", "complex", "central", "forward")
METHOD_STYLE = {"engine": "o", "newton": "s", "complex": "D", "central": "^", "forward": "v",
                "pylinkage, с аналогами": "x", "mechanism, с аналогами": "+"}


def plot(rows: list[dict], path: Path) -> None:
    """Work–precision: time per cycle against the error, log–log; one colour per method, one line
    per mechanism (N = 360 → 36 000 along it)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(18, 6), sharey=True)
    cases = [c for c, _ in CASES]
    ls = dict(zip(cases, ("-", "--", "-.", ":")))
    for ax, kind, title in zip(axes, ("err_position", "err_first", "err_second"),
                               ("положения", "первые аналоги", "вторые аналоги")):
        for i, (m, mk) in enumerate(METHOD_STYLE.items()):
            for case in cases:
                pts = sorted((r["N"], max(r[kind], 1e-17), r["time_ms"]) for r in rows
                             if r["case"] == case and r["method"] == m and math.isfinite(r[kind]))
                if pts:
                    _, xs, ys = zip(*pts)
                    ax.loglog(xs, ys, marker=mk, color=f"C{i}", linestyle=ls[case], alpha=0.85,
                              label=f"{m}: {case}")
        ax.set_title(title)
        ax.set_xlabel("наибольшая погрешность |x − x_эт| / max(1, |x_эт|)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("процессорное время на цикл, мс")
    axes[2].legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.suptitle("Время против погрешности: кинематика за цикл, N = 360, 3 600, 36 000 "
                 "(по линии время растёт с N)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_dynamics(dyn: list[dict], integ: list[dict], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(14, 5.5))
    methods = list(dict.fromkeys(r["method"] for r in dyn if not r["method"].startswith("эталон")))
    for i, m in enumerate(methods):
        for j, case in enumerate(dict.fromkeys(r["case"] for r in dyn)):
            pts = [(r["delta"], max(r["err_J_I"], 1e-17)) for r in dyn if r["method"] == m and r["case"] == case]
            if pts:
                xs, ys = zip(*pts)
                a1.loglog(xs, ys, marker="os"[j % 2], color=f"C{i}", linestyle="-:"[j % 2], label=f"{m}: {case}")
    a1.set_xlabel("δ")
    a1.set_ylabel("|J_I − J_I,эт| / J_I,эт")
    a1.set_title("J_I против эталона (ОДУ движения)")
    a1.grid(True, which="both", alpha=0.3)
    a1.legend(fontsize=7)
    for i, case in enumerate(dict.fromkeys(r["case"] for r in integ)):
        for j, panels in enumerate(dict.fromkeys(r["panels"] for r in integ)):
            pts = [(r["evaluations"], max(r["err_dT"], 1e-17)) for r in integ if r["case"] == case and r["panels"] == panels]
            xs, ys = zip(*pts)
            a2.loglog(xs, ys, marker="os"[j % 2], color=f"C{i}", linestyle="-:"[j % 2],
                      label=f"{case}, панелей ≥ {panels}")
    a2.set_xlabel("вычислений M(φ) (порядок × число панелей)")
    a2.set_ylabel("max |ΔT − ΔT_эт| / размах ΔT")
    a2.set_title("ΔT(φ) по Гауссу — Лежандру: порядок 1…12")
    a2.grid(True, which="both", alpha=0.3)
    a2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _e(x: float) -> str:
    return "—" if not math.isfinite(x) else f"{x:.1e}"


def machine(load_start: tuple[float, ...]) -> str:
    """One line: cores, Python, numba, the load average at the start and at the end of the run."""
    import os
    import platform
    import numba
    end = os.getloadavg()
    return (f"Машина: {os.cpu_count()} ядра, Python {platform.python_version()}, numba {numba.__version__}, "
            f"numpy {np.__version__}; средняя загрузка (1 мин) в начале {load_start[0]:.1f}, "
            f"в конце {end[0]:.1f}; время — процессорное время процесса, медиана прогретых вызовов.")


def markdown(rows: list[dict], dyn: list[dict], integ: list[dict], sections_md: str,
             peer_failed: dict[str, str], machine_line: str = "") -> str:
    lines = ["# Время против погрешности (bench/work_precision.py)", "", machine_line, "",
             "## Кинематика за цикл", "",
             "| механизм | N | метод | время на цикл, мс ЦП | нс на положение | положения | 1-е аналоги | 2-е аналоги |",
             "|---|---:|---|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['N']} | {r['method']} | {r['time_ms']:.3f} | {r['ns_per_position']:.0f} | "
                     f"{_e(r['err_position'])} | {_e(r['err_first'])} | {_e(r['err_second'])} |")
    for name, err in peer_failed.items():
        lines += ["", f"{name}: не устанавливается в этом Python: `{err}`"]
    if dyn:
        lines += ["", "## Маховик: J_I, ω, ε против периодического решения уравнения движения", "",
                  "| случай | δ | метод | J_I, кг·м² | отн. погрешность J_I | max|Δω|/ω_ср | max|Δε|/max|ε| | время, мс ЦП |",
                  "|---|---:|---|---:|---:|---:|---:|---:|"]
        for r in dyn:
            lines.append(f"| {r['case']} | {r['delta']} | {r['method']} | {r['J_I']:.10g} | {_e(r['err_J_I'])} | "
                         f"{_e(r['err_omega'])} | {_e(r['err_eps'])} | {r['time_ms']:.1f} |")
    if integ:
        lines += ["", "## Интегралы за цикл против порядка квадратуры", "",
                  "| случай | панелей ≥ | порядок | вычислений M | A_c за цикл: отн. погр. | ΔT(φ): погр. / размах | время, мс ЦП |",
                  "|---|---:|---:|---:|---:|---:|---:|"]
        for r in integ:
            lines.append(f"| {r['case']} | {r['panels']} | {r['order']} | {r['evaluations']} | {_e(r['err_work'])} | "
                         f"{_e(r['err_dT'])} | {r['time_ms']:.1f} |")
    if sections_md:
        lines += ["", sections_md]
    return "\n".join(lines) + "\n"


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="N = 360 и 3600 только, δ через одно")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--peers", action="store_true",
                   help="create output/bench/peer-venv with pylinkage, numba, mechanism (and try pyslvs)")
    g.add_argument("--peer", metavar="PYTHON", help="python of an existing venv with the peers")
    ap.add_argument("--no-sections", action="store_true", help="без замера разделов записки")
    ap.add_argument("--only", metavar="ЧАСТИ",
                    help="пересчитать только эти части (kinematics,peers,dynamics,sections через запятую); "
                         "остальные таблицы берутся из CSV прошлого прогона в output/bench/")
    args = ap.parse_args(argv)
    parts = set(args.only.split(",")) if args.only else {"kinematics", "peers", "dynamics", "sections"}
    if args.no_sections:
        parts.discard("sections")
    import os
    load_start = os.getloadavg()
    OUT.mkdir(parents=True, exist_ok=True)
    import bench_sections
    import dynamics_precision
    failed: dict[str, str] = {}
    old = read_csv(OUT / "work_precision.csv") if (OUT / "work_precision.csv").exists() else []
    own = [r for r in old if r["method"] in METHODS]
    peers = [r for r in old if r["method"] not in METHODS]
    if "kinematics" in parts:
        own = kinematics_rows(args.quick)
    python = args.peer
    if "peers" in parts and args.peers:
        python, failed = make_peer_venv()
    if "peers" in parts:
        peers = peer_rows(python, args.quick) if python else []
    rows = own + peers
    write_csv(OUT / "work_precision.csv", rows)
    plot(rows, OUT / "work_precision.png")
    if "dynamics" in parts:
        dyn = dynamics_precision.dynamics_rows(args.quick)
        write_csv(OUT / "dynamics_precision.csv", dyn)
        integ = dynamics_precision.integral_rows()
        write_csv(OUT / "cycle_integrals.csv", integ)
    else:
        dyn, integ = read_csv(OUT / "dynamics_precision.csv"), read_csv(OUT / "cycle_integrals.csv")
    plot_dynamics(dyn, integ, OUT / "dynamics_precision.png")
    sec = []
    if "sections" in parts:
        sec = bench_sections.rows(ROOT / bench_sections.DEFAULT_CASE, 3, False)
        bench_sections.write(sec, OUT / "sections.csv")
    elif not args.no_sections and (OUT / "sections.csv").exists():
        sec = read_csv(OUT / "sections.csv")
    sections_md = bench_sections.markdown(sec, bench_sections.DEFAULT_CASE) if sec else ""
    if sections_md:
        (OUT / "sections.md").write_text(sections_md, encoding="utf-8")
    import json
    failed_file = OUT / "peers_failed.json"
    if "peers" in parts and args.peers:
        failed_file.write_text(json.dumps(failed, ensure_ascii=False), encoding="utf-8")
    elif "peers" not in parts and failed_file.exists():
        failed = json.loads(failed_file.read_text(encoding="utf-8"))
    (OUT / "work_precision.md").write_text(markdown(rows, dyn, integ, sections_md, failed, machine(load_start)),
                                         encoding="utf-8")
    print(f"written: {OUT}")


if __name__ == "__main__":
    main()
