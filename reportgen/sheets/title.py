"""The title block's fields from ``[meta]`` and the lettering font of the sheets.

Fields (ГОСТ 2.104-2006, форма 1): designation ``[meta] sheet_code`` (a ``{n}`` in it is replaced
by the sheet number) or «ТММ.КП.<variant>.0n» («ТММ.КП.0n» without a variant); name: the topic and the sheet's title; material:
the discipline; organisation: university and group; Разраб. — student, Пров. — supervisor,
Т.контр. — ``checker``, Н.контр. — ``norm_control``, Утв. — ``approver``; date — ``date`` or
``year``.
"""
from __future__ import annotations

import functools
import textwrap
from pathlib import Path

from . import frame as F

OSIFONT = ("/usr/share/fonts/truetype/osifont/osifont.ttf",
           "/usr/share/fonts/truetype/osifont/osifont-lgpl3fe.ttf")


@functools.lru_cache(maxsize=1)
def drafting_family() -> str | None:
    """osifont (ISO 3098 lettering, the construction of ГОСТ 2.304 type B, Debian fonts-osifont)
    registered with matplotlib; None (the note's serif) when it is not installed."""
    from matplotlib import font_manager
    for p in OSIFONT:
        if Path(p).exists():
            font_manager.fontManager.addfont(p)
            return font_manager.FontProperties(fname=p).get_name()
    return None


def _wrap(text: str, width_chars: int, lines: int) -> str:
    out = textwrap.wrap(text, width_chars)[:lines]
    return "\n".join(out)


def title_block(study, spec, n: int, total: int, scale: str) -> F.TitleBlock:
    m = study.meta
    variant = m.get("variant")
    code = m.get("sheet_code")
    designation = (code.replace("{n}", str(n)) if code
                   else f"ТММ.КП.{variant}.0{n}" if variant else f"ТММ.КП.0{n}")
    org = ", ".join(x for x in (m.get("university", ""), ("гр. " + m["group"]) if m.get("group") else "") if x)
    return F.TitleBlock(
        designation=designation,
        name=_wrap(m.get("topic") or "Курсовой проект по теории механизмов и машин", 34, 3),
        sheet_title=_wrap(spec.title, 34, 2),
        material=_wrap(m.get("discipline", ""), 34, 2),
        scale=scale, sheet=n, sheets=total, organisation=_wrap(org, 26, 3),
        developer=m.get("student", ""), checker=m.get("supervisor", ""),
        tech_control=m.get("checker", ""), norm_control=m.get("norm_control", ""),
        approver=m.get("approver", ""), date=m.get("date") or m.get("year", ""))
