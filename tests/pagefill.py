"""Page fill of a PDF from the word boxes of ``pdftotext -bbox`` (poppler): how far down each page
the text reaches, and which pages are less than half full without a reason (ГОСТ 7.32 layout:
a page is left short only before a new chapter or a figure that does not fit)."""
from __future__ import annotations

import re
import subprocess
from pathlib import Path

_PAGE = re.compile(r'<page width="([\d.]+)" height="([\d.]+)">(.*?)</page>', re.S)
_WORD = re.compile(r'<word xMin="([\d.]+)" yMin="([\d.]+)" xMax="([\d.]+)" yMax="([\d.]+)">(.*?)</word>')
STRUCTURAL = ("СОДЕРЖАНИЕ", "ВВЕДЕНИЕ", "ЗАКЛЮЧЕНИЕ", "СПИСОК", "ПРИЛОЖЕНИЕ", "ЗАДАНИЕ")


def pages(pdf: Path) -> list[dict]:
    """Per page: height, words [(yMin, yMax, text)] without the page number, first line text."""
    xml = subprocess.run(["pdftotext", "-bbox", str(pdf), "-"], capture_output=True, text=True,
                         check=True).stdout
    out = []
    for w, h, body in _PAGE.findall(xml):
        words = [(float(y0), float(y1), float(x0), t) for x0, y0, _, y1, t in _WORD.findall(body)]
        H = float(h)
        # the page number: a bare number in the bottom margin
        words = [x for x in words if not (x[0] > 0.9 * H and x[3].isdigit())]
        words.sort()
        top_line = sorted((x0, t) for y0, _, x0, t in words if abs(y0 - words[0][0]) < 3) if words else []
        first = " ".join(t for _, t in top_line)
        out.append({"height": H, "width": float(w), "words": words, "first": first,
                    "top": words[0][0] / H if words else 1.0,
                    "fill": max(w[1] for w in words) / H if words else 0.0,
                    "text": " ".join(w[3] for w in words)})
    return out


def short_pages(pdf: Path, min_fill: float = 0.5) -> list[int]:
    """1-based numbers of pages filled less than ``min_fill`` of the height with no excuse: the
    next page does not start a chapter (a numbered level-1 heading or a structural heading) and
    does not start with a figure (text first appears low on the page). The title page, the
    last page and the landscape pages of wide figures are exempt."""
    ps = pages(pdf)
    bad = []
    for i, p in enumerate(ps[:-1]):
        if i == 0 or p["fill"] >= min_fill or p["width"] > p["height"]:
            continue              # a landscape page holds one wide figure (ГОСТ 7.32), however flat
        nxt = ps[i + 1]
        first = nxt["first"]
        chapter = bool(re.match(r"^\d+ [А-ЯЁ]", first)) or first.startswith(STRUCTURAL)
        figure = nxt["top"] > 0.3
        if not (chapter or figure):
            bad.append(i + 1)
    return bad
