"""The shared result protocol of the one-section task kinds: ``scalars`` (``<prefix>_<key>``) and
``printed`` (the values printed in the source, ``[<section>.printed]``, read and checked against
the results by :func:`reportgen.case.printed.read_printed`)."""
from __future__ import annotations

from abc import ABC, abstractmethod
from functools import cached_property

from ..case import units as U
from ..case.printed import read_printed

__all__ = ["PrintedResults"]


class PrintedResults(ABC):
    """Mixin: the class sets ``PREFIX`` and ``DIMS`` (key → dimension, default dimensionless),
    ``self.node`` (its case section) and defines ``results()`` → dict of plain numbers."""

    PREFIX = ""
    DIMS: dict = {}

    @classmethod
    def dim_of(cls, key: str) -> U.Dim:
        """The dimension of the result ``key`` (dimensionless unless listed)."""
        return cls.DIMS.get(key, U.DIMENSIONLESS)

    @abstractmethod
    def results(self) -> dict:
        """The named results of the task as plain numbers (SI)."""

    def scalars_raw(self) -> dict:
        """The results as named scalars ``<prefix>_<key>``, without checking the printed values."""
        return {f"{self.PREFIX}_{k}": float(v) for k, v in self.results().items()}

    @cached_property
    def scalars(self) -> dict:
        """Named results ``<prefix>_*`` (the printed values are checked here too)."""
        self.printed
        return self.scalars_raw()

    @cached_property
    def printed(self) -> list[dict]:
        """The values printed in the source (``[<task>.printed]``) beside the exact ones."""
        return read_printed(self.node.table("printed"), self.results(), self.dim_of)
