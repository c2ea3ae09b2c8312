"""reportgen: курсовой проект по ТММ из файла варианта (расчёт и отчёт по ГОСТ 7.32)."""
from __future__ import annotations

__all__ = ["Study", "load_case"]
__version__ = "0.1.0"


def __getattr__(name: str):
    """``reportgen.Study`` and ``reportgen.load_case`` imported on first use (PEP 562), so
    that ``reportgen --help`` does not load numba, pandas and scipy."""
    if name in __all__:
        from .analysis import study

        return getattr(study, name)
    raise AttributeError(f"module 'reportgen' has no attribute {name!r}")
