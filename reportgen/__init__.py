"""reportgen: курсовой проект по ТММ из файла варианта (расчёт и отчёт по ГОСТ 7.32)."""
from .analysis.study import Study, load_case

__all__ = ["Study", "load_case"]
__version__ = "0.1.0"
