"""Compile (and cache on disk) every numba kernel by running a tiny study of each kind."""
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
