"""The task kinds a case can hold: one line each (DESIGN «Growing past one linkage»).

A kind is enabled by its section in the case file.  Its analysis lives in
``reportgen/analysis/<module>.py`` (a class taking the Study, with ``tables()`` → dict of
DataFrames and ``scalars`` → dict), its drawings in ``reportgen/scenes/``, and its section of the
note in ``reportgen/report/sections/<name>.py`` (``NEEDS``, ``present(study)``, ``build(study)``).
The Study, export, the note and the answer key iterate over :data:`KINDS` in this order, so adding
a kind is its four files and one line here.

This module is pure data: the case reader (below the analyses in the import order) reads the
section names from it; the Study imports the analysis classes lazily by name.
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["TaskKind", "KINDS", "BY_NAME", "LINKAGE_SECTIONS", "TASK_SECTIONS", "STANDALONE_SECTIONS"]


@dataclass(frozen=True)
class TaskKind:
    name: str          # Study attribute, export prefix, note section name
    section: str       # the case section that enables it
    analysis: str      # "module:Class" under reportgen.analysis
    title: str         # Russian title of the task
    linkage: bool      # needs the linkage of the case ([frame], [links], [joints], [driver])


KINDS: tuple[TaskKind, ...] = (
    TaskKind("dynamics", "dynamics", "dynamics:Dynamics", "Динамический анализ и синтез маховика", True),
    TaskKind("forces", "forces", "forces:Forces", "Силовой анализ", True),
    TaskKind("cam", "cam", "cam:Cam", "Синтез кулачкового механизма", False),
)

BY_NAME: dict[str, TaskKind] = {k.name: k for k in KINDS}

# the sections that describe a linkage; a case may hold none of them (a cam or gears only)
LINKAGE_SECTIONS = ("frame", "links", "joints", "driver")
TASK_SECTIONS = tuple(dict.fromkeys(k.section for k in KINDS))
# sections of the kinds that stand without a linkage (a case may hold only these)
STANDALONE_SECTIONS = tuple(dict.fromkeys(k.section for k in KINDS if not k.linkage))
