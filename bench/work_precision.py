"""Work–precision benchmark of the kinematics (and of the flywheel methods).

Usage (one command, a few minutes on a 2-core machine)::

    .venv/bin/python bench/work_precision.py [--quick] [--peer /path/to/peer-venv/bin/python]

writes ``output/bench/work_precision.csv``, ``work_precision.md``, ``work_precision.png``
(log–log: time per cycle against the maximum error) and ``flywheel_precision.csv``.

Kinematics: a slider-crank, a crank-rocker, the six-bar of worksheet 000 and a class III
mechanism, N = 360, 3 600, 36 000 positions per cycle.  Errors are the maximum scaled error
|x − x_ref| / max(1, |x_ref|) of the point coordinates and their first and second analogs at the
24 positions q = start + k·15° (on every grid), against the 50-digit mpmath reference of
``tests/reference.py`` (Newton on the loop equations at 50 digits, analogs by 5-point stencils
with h = 1e-12; its own error < 1e-25).  Methods:

* ``engine`` — the whole-grid kernel (closed-form class II groups, analogs from the linear
  systems Φ_x x′ = −Φ_q, Φ_x x″ = −γ) and the points;
* ``newton`` — the same kernel with every group solved by Newton on its loop equations
  (second-order predictor from the previous position), analogs as above;
* ``central`` — positions by the engine, analogs by central differences on the same grid
  (the Mathcad d/dφ way): x′ ≈ (x₊ − x₋)/2h, x″ ≈ (x₊ − 2x + x₋)/h²;
* ``forward`` — forward differences x′ ≈ (x₊ − x)/h, x″ ≈ (x₊₊ − 2x₊ + x)/h²;
* with ``--peer PYTHON``: pylinkage's numba path (``step_fast``, ``step_fast_with_kinematics``)
  on the crank-rocker, run by ``bench/work_precision_peer.py`` in that separate environment.

Times are the median CPU time of warm calls (the kernels compiled and cached before timing).

Flywheel: J_I of Мерцалов and Виттенбауэр against the exact periodic solution for δ from 0,01 to
0,2 (worksheet 000), and the run time of each method.
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

OUT = ROOT / "output" / "bench"
CASES = [("кривошипно-ползунный", "cases/slider_crank.toml"),
         ("кривошипно-коромысловый", "cases/four_bar.toml"),
         ("шестизвенный (лист 000)", "cases/ws000_six_bar.toml"),
         ("III класса (триада)", "cases/class3_triad.toml")]
NS = [360, 3600, 36000]
NREF = 24
KINDS = ("position", "first", "second")


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

            def central():
                x = point_arrays(L.solve(model, q).points)[0][:-1]
                xp, xm = np.roll(x, -1, axis=0), np.roll(x, 1, axis=0)
                return x, (xp - xm) / (2 * h), (xp - 2 * x + xm) / (h * h)

            def forward():
                x = point_arrays(L.solve(model, q).points)[0][:-1]
                xp, xpp = np.roll(x, -1, axis=0), np.roll(x, -2, axis=0)
                return x, (xp - x) / h, (xpp - 2 * xp + x) / (h * h)

            for name, fn, is_pts in (("engine", engine, True), ("newton", newton, True),
                                     ("central", central, False), ("forward", forward, False)):
                t, out = timed(fn)
                arrs = point_arrays(out) if is_pts else out
                errs = [scaled_error(a[idx], r) for a, r in zip(arrs, (rx, rv, ra))]
                rows.append(dict(case=title, N=N, method=name, time_ms=t * 1e3,
                                 ns_per_position=t / (N + 1) * 1e9,
                                 err_position=errs[0], err_first=errs[1], err_second=errs[2]))
                print(f"  N={N:6d} {name:8s} {t * 1e3:9.3f} ms  errors {errs[0]:.1e} {errs[1]:.1e} "
                      f"{errs[2]:.1e}", flush=True)
    return rows


def peer_rows(python: str, quick: bool) -> list[dict]:
    """pylinkage (numba path) on the crank-rocker, run by bench/work_precision_peer.py in its own
    virtual environment; errors of point B only (the peer's output joint)."""
    import json
    import subprocess
    from reportgen.analysis.study import Study
    s = Study(ROOT / "cases/four_bar.toml")
    qref = s.grid.start + s.grid.length * np.arange(NREF) / NREF
    rx, rv, ra = reference(s, qref, ["B"])
    rows = []
    for N in (NS[:2] if quick else NS):
        try:
            res = subprocess.run([python, str(ROOT / "bench/work_precision_peer.py"), str(N)],
                                 capture_output=True, text=True, timeout=300, check=True)
        except (OSError, subprocess.SubprocessError) as e:
            print(f"pylinkage: not measured ({e})", flush=True)
            return rows
        out = json.loads(res.stdout)
        # sample j is the position after j + 1 crank steps: q = (j + 1)·2π/N
        idx = (np.arange(NREF) * (N // NREF) - 1) % N
        B, vB, aB = (np.asarray(out[k])[idx] for k in ("B", "vB", "aB"))
        errs = [scaled_error(a, r) for a, r in zip((B, vB, aB), (rx, rv, ra))]
        for name, key in (("pylinkage, положения", "time_positions"),
                          ("pylinkage, с аналогами", "time_with_kinematics")):
            t = out[key]
            rows.append(dict(case="кривошипно-коромысловый", N=N, method=name, time_ms=t * 1e3,
                             ns_per_position=t / N * 1e9, err_position=errs[0],
                             err_first=errs[1] if "аналог" in name else float("nan"),
                             err_second=errs[2] if "аналог" in name else float("nan")))
            print(f"  N={N:6d} {name:24s} {t * 1e3:9.3f} ms  errors {errs[0]:.1e} {errs[1]:.1e} {errs[2]:.1e}",
                  flush=True)
    return rows


def flywheel_rows() -> list[dict]:
    from reportgen.analysis.flywheel import exact, mertsalov, prepare_model, wittenbauer
    from reportgen.analysis.study import Study
    s = Study(ROOT / "cases/ws000_six_bar.toml")
    dyn = s.analysis("dynamics")
    st = dyn.settings
    m = prepare_model(dyn.model.J2, dyn.model.dJ2, dyn.model.M, dyn.breaks, st.cycle_start,
                      st.cycle_length, dyn.grid, dyn._Mdrive)
    rows = []
    for delta in (0.01, 0.02, 0.05, 0.1, 0.2):
        t_ex, ex = timed(lambda: exact(m, st.omega_m, delta), budget=0.3)
        t_me, me = timed(lambda: mertsalov(m, st.omega_m, delta), budget=0.3)
        t_wi, wi = timed(lambda: wittenbauer(m, st.omega_m, delta), budget=0.3)
        for name, t, r in (("exact", t_ex, ex), ("mertsalov", t_me, me), ("wittenbauer", t_wi, wi)):
            rows.append(dict(delta=delta, method=name, J_I=r.J_I, rel_error=abs(r.J_I - ex.J_I) / ex.J_I,
                             delta_achieved=getattr(r, "delta_achieved", float("nan")), time_ms=t * 1e3))
        print(f"δ = {delta}: J_I exact {ex.J_I:.6g}, Мерцалов {me.J_I:.6g}, Виттенбауэр {wi.J_I:.6g}", flush=True)
    return rows


def write_csv(path: Path, rows: list[dict]) -> None:
    with path.open("w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def plot(rows: list[dict], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(18, 5.5), sharey=True)
    markers = {"engine": "o", "newton": "s", "central": "^", "forward": "v", "pylinkage, с аналогами": "x"}
    colors = {c: f"C{i}" for i, (c, _) in enumerate(CASES)}
    for ax, kind, title in zip(axes, ("err_position", "err_first", "err_second"),
                               ("положения", "первые аналоги", "вторые аналоги")):
        for (case, _) in CASES:
            for m, mk in markers.items():
                pts = [(max(r[kind], 1e-17), r["time_ms"]) for r in rows
                       if r["case"] == case and r["method"] == m and math.isfinite(r[kind])]
                if pts:
                    xs, ys = zip(*pts)
                    ax.loglog(xs, ys, marker=mk, color=colors[case], linestyle="-", alpha=0.8,
                              label=f"{case}, {m}")
        ax.set_title(title)
        ax.set_xlabel("наибольшая погрешность (отнесённая к max(1, |x|))")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("время на цикл, мс")
    axes[2].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.suptitle("Время против погрешности: кинематика за цикл (N = 360, 3600, 36000)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def markdown(rows: list[dict], fly: list[dict]) -> str:
    lines = ["# Время против погрешности (bench/work_precision.py)", "",
             "| механизм | N | метод | время на цикл, мс | нс на положение | положения | 1-е аналоги | 2-е аналоги |",
             "|---|---:|---|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['N']} | {r['method']} | {r['time_ms']:.3f} | {r['ns_per_position']:.0f} | "
                     f"{r['err_position']:.1e} | {r['err_first']:.1e} | {r['err_second']:.1e} |")
    if fly:
        lines += ["", "## Маховик (лист 000): J_I методами Мерцалова и Виттенбауэра против точного решения", "",
                  "| δ | метод | J_I, кг·м² | отн. отклонение от точного | достигнутое δ | время, мс |",
                  "|---:|---|---:|---:|---:|---:|"]
        for r in fly:
            lines.append(f"| {r['delta']} | {r['method']} | {r['J_I']:.6g} | {r['rel_error']:.2e} | "
                         f"{r['delta_achieved']:.5g} | {r['time_ms']:.2f} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="N = 360 и 3600 только")
    ap.add_argument("--peer", metavar="PYTHON",
                    help="python of a separate venv with pylinkage and numba (bench/work_precision_peer.py)")
    args = ap.parse_args(argv)
    OUT.mkdir(parents=True, exist_ok=True)
    rows = kinematics_rows(args.quick)
    if args.peer:
        rows += peer_rows(args.peer, args.quick)
    write_csv(OUT / "work_precision.csv", rows)
    fly = flywheel_rows()
    write_csv(OUT / "flywheel_precision.csv", fly)
    (OUT / "work_precision.md").write_text(markdown(rows, fly), encoding="utf-8")
    plot(rows, OUT / "work_precision.png")
    print(f"written: {OUT}")


if __name__ == "__main__":
    main()
