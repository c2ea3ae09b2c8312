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
}


def warmup() -> None:
    """Run the kinematics and every registered analysis that has a ``warmup(study)`` hook."""
    import importlib

    from .analysis import linkage as L
    from .analysis.study import Study
    from .registry import KINDS
    s = Study(CaseSpec(Path("warmup.toml"), _TINY))
    s.kinematics
    L.compile_kernels(s.model, s.grid.cycle)
    s.cycle
    for kind in KINDS:
        module, cls = kind.analysis.split(":")
        hook = getattr(getattr(importlib.import_module(f"reportgen.analysis.{module}"), cls), "warmup", None)
        if hook is not None:
            hook(s)


def warm_report() -> None:
    """Load what every report needs, so that the first build after setup finds it ready:
    matplotlib's font list (built on its first use and kept in its cache folder), the report's
    serif faces registered with it and the report style, WeasyPrint's font configuration with
    the report's @font-face files, the Jinja templates compiled, and the bytecode of the report
    modules written (``__pycache__``). In a batch worker all of it stays loaded for every variant."""
    from .report import assemble  # noqa: F401  (sections, formulas, ziamath)
    from .report import render
    from .style import mplstyle

    mplstyle.apply_style()
    render._font_config()
    render._get_env()
