"""Helpers shared by the tests that read built sections and drawn figures."""
from __future__ import annotations

import re

import numpy as np


def plain(html) -> str:
    """The text of an HTML fragment: tags dropped, ``&nbsp;`` as the no-break space."""
    return re.sub(r"<[^>]+>", "", str(html)).replace("&nbsp;", "\u00a0")


def blocks(sec):
    """Every block of a section and its subsections, in order."""
    from reportgen.report.document import Section
    for b in sec.children:
        if isinstance(b, Section):
            yield from blocks(b)
        else:
            yield b


def paragraph_text(sec) -> str:
    """The HTML of every paragraph of a section, joined."""
    from reportgen.report.document import Paragraph
    return " ".join(b.html for b in blocks(sec) if isinstance(b, Paragraph))


def record_labels(monkeypatch) -> list[str]:
    """Record every text a scene hands to the label placer (in the order handed)."""
    from reportgen.scenes.labels import LabelPlacer
    seen: list[str] = []
    orig = LabelPlacer.add

    def add(self, x, y, text, prefer=None, **kw):
        seen.append(text)
        return orig(self, x, y, text, prefer=prefer, **kw)
    monkeypatch.setattr(LabelPlacer, "add", add)
    return seen


def arrows_mm(fig) -> list[tuple[np.ndarray, np.ndarray]]:
    """Every arrow of the figure's first axes as a segment in printed millimetres."""
    from matplotlib.patches import FancyArrowPatch
    ax = fig.axes[0]
    px_mm = fig.dpi / 25.4
    out = []
    for p in ax.patches:
        if isinstance(p, FancyArrowPatch):
            a, b = (ax.transData.transform(q) / px_mm for q in p._posA_posB)
            out.append((a, b))
    return out


def share_near(a0, a1, b0, b1, near=0.7, n=81) -> float:
    """The share of the segment a0a1 within ``near`` mm of the segment b0b1 (independent of the
    scenes' own geometry)."""
    t = np.linspace(0, 1, n)
    pts = a0[None, :] + t[:, None] * (a1 - a0)[None, :]
    d = b1 - b0
    u = np.clip(((pts - b0) @ d) / (d @ d), 0, 1)
    return float(np.mean(np.linalg.norm(pts - (b0 + u[:, None] * d), axis=1) < near))
