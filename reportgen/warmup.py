"""Cold costs paid once, at setup (``reportgen warmup``, run by ``scripts/setup.sh``) or once per
batch worker: every numba kernel compiled and cached on disk by running a tiny study of each kind
(:func:`warmup`), and the report stack loaded (:func:`warm_report`)."""
from __future__ import annotations

from pathlib import Path

from .case.load import CaseSpec

_TINY = {
    "frame": {"points": {"O": [0, 0], "C": [0.3, 0]}},
    "links": [
        {"name": "1", "points": {"O": [0, 0], "A": [0.1, 0]}, "mass": 1.0, "J_S": 0.01, "com": "A"},
        {"name": "2", "points": {"A": [0, 0], "B": [0.35, 0]}, "mass": 1.0, "J_S": 0.01, "com": "B"},
        {"name": "3", "points": {"C": [0, 0], "B": [0.3, 0]}, "mass": 1.0, "J_S": 0.01, "com": "B"},
    ],
    "joints": [
        {"type": "R", "links": ["0", "1"], "point": "O"},
        {"type": "R", "links": ["1", "2"], "point": "A"},
        {"type": "R", "links": ["2", "3"], "point": "B"},
        {"type": "R", "links": ["0", "3"], "point": "C"},
    ],
    "driver": {"type": "crank", "link": "1", "omega": 10.0},
    "grid": {"positions": 12, "cycle_points": 72},
    # a load switched on the working stroke and a flywheel: the extremum searches of the
    # dynamics are compiled too (the first real note would otherwise compile them)
    "loads": {"g": "10 m/s^2", "force": [
        {"name": "F", "link": "3", "point": "B", "magnitude": "100 N", "direction": "x",
         "against": "motion", "when": "vqx_B >= 0"}]},
    "dynamics": {"n": "60 rpm", "delta": 0.1, "J_O": "0.1 kg*m^2", "method": "mertsalov"},
}


def _tiny_study():
    from .analysis.study import Study
    return Study(CaseSpec(Path("warmup.toml"), _TINY))


def compile_general() -> None:
    """Compile (or load) the general kinematics kernel alone: the largest of the kernels
    (about two thirds of the compile time), so ``reportgen warmup`` compiles it in a second
    process while the first compiles the rest."""
    from .analysis import linkage as L
    s = _tiny_study()
    q = s.grid.cycle[:2]
    L.solve_general(s.model, q, len(s.model.groups), s.model.gsigma, s.model.pose0)


def warmup(general: bool = True) -> None:
    """Run the kinematics and every registered analysis that has a ``warmup(study)`` hook
    (the general kinematics kernel too unless ``general`` is false: :func:`compile_general`
    then runs in another process)."""
    import importlib

    from .analysis import linkage as L
    from .registry import KINDS
    s = _tiny_study()
    s.kinematics
    if general:
        L.compile_kernels(s.model, s.grid.cycle)
    s.cycle
    s.dynamics.tables()
    for kind in KINDS:
        module, cls = kind.analysis.split(":")
        hook = getattr(getattr(importlib.import_module(f"reportgen.analysis.{module}"), cls), "warmup", None)
        if hook is not None:
            hook(s)


def warm_report() -> None:
    """Load what every report needs, so that the first build after setup finds it ready:
    matplotlib's font list (built on its first use and kept in its cache folder), the report's
    serif faces registered with it and the report style, WeasyPrint's font configuration with
    the report's @font-face files, the Jinja templates compiled, the label placer's numba kernels
    (:mod:`reportgen.core.clip`), and the bytecode of the report
    modules written (``__pycache__``). In a batch worker all of it stays loaded for every variant."""
    from .core import clip
    from .report import assemble  # noqa: F401  (sections, formulas, ziamath)
    from .report import render
    from .style import mplstyle

    mplstyle.apply_style()
    render._font_config()
    render.warm_caches()
    clip.warm()        # the label placer's kernels
