"""The graphic part of the course project: A1 drawing sheets (ГОСТ 2.301, 2.104, 2.302–2.304)
built from the same scenes as the note, without WeasyPrint."""
from .build import build_sheets

__all__ = ["build_sheets"]
