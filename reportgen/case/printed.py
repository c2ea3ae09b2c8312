"""``[<section>.printed]``: values printed in the source, ``key = { value, title, note }``
(``value`` a string with units, its printed digits kept), read and checked in one place."""
from __future__ import annotations

import re
from typing import Callable, Mapping

from . import units as U
from .reader import Node


def read_printed(node: Node, values: Mapping[str, float], dim_of: Callable[[str], U.Dim]) -> list[dict]:
    """Rows ``key, printed, computed, title, note, digits`` for every entry of ``node``; the key
    must name one of ``values``."""
    out = []
    for k in node.data:
        sub = node.table(k)
        sub.check_keys(["value", "title", "note"], required=["value"])
        if k not in values:
            raise sub.error(None, f"нет результата «{k}»", expected="один из результатов: " + ", ".join(values))
        pv = sub.quantity("value", dim_of(k), {}, required=True)
        text = str(sub.raw("value")).split()[0].lower().split("e")[0]
        digits = max(len(re.sub(r"\D", "", text).lstrip("0")), 1)
        out.append(dict(key=k, printed=pv, computed=float(values[k]), title=sub.string("title", k),
                        note=sub.string("note"), digits=digits))
    return out
