"""The A1 drawing sheet: format, frame and the main title block (основная надпись, форма 1).

* Format A1, 841 × 594 mm, landscape (ГОСТ 2.301-68).
* Frame: 20 mm from the left edge (binding), 5 mm from the others (ГОСТ 2.104-2006, п. 4.1).
* Main title block, form 1, 185 × 55 mm in the lower right corner of the frame (ГОСТ 2.104-2006,
  приложение А, форма 1): on the left four revision rows, the header row (Изм., Лист, № докум., Подп.,
  Дата) and six rows of the persons (Разраб., Пров., Т.контр., —, Н.контр., Утв.), all 5 mm
  high, with the columns 7, 10, 23, 15, 10 mm; in the middle and right the
  designation (графа 2, 120 × 15), the name (графа 1, 70 × 25), the material (графа 3, 70 × 15), the
  letter, mass and scale (графы 4–6), sheet and sheets (графы 7–8) and the organisation (графа 9).
* Lines (ГОСТ 2.303-68): the frame and the block's outline and main divisions are solid main lines
  (S = 0,7 mm), the rows of the left part thin solid lines (S/3 ≈ 0,25 mm).
* Lettering (ГОСТ 2.304-81): type B italic; the bundled font is osifont (ISO 3098, the same
  construction as type B), heights 3,5 mm for the fields and 2,5 mm for the captions of the block.

All coordinates here are millimetres on the sheet, origin at its lower left corner.
"""
from __future__ import annotations

from dataclasses import dataclass

from matplotlib.patches import Rectangle

SHEET_W, SHEET_H = 841.0, 594.0
FRAME_LEFT, FRAME_OTHER = 20.0, 5.0
BLOCK_W, BLOCK_H = 185.0, 55.0
LW_MAIN_MM, LW_THIN_MM = 0.7, 0.25
PT_PER_MM = 72.0 / 25.4

# the frame's inner rectangle (x0, y0, x1, y1)
FRAME = (FRAME_LEFT, FRAME_OTHER, SHEET_W - FRAME_OTHER, SHEET_H - FRAME_OTHER)
# the title block's rectangle
BLOCK = (FRAME[2] - BLOCK_W, FRAME[1], FRAME[2], FRAME[1] + BLOCK_H)


@dataclass(frozen=True)
class TitleBlock:
    """The fields of the main title block (all text, already chosen by the caller)."""

    designation: str            # графа 2: обозначение документа
    name: str                   # графа 1: наименование (the project and the sheet's title)
    sheet_title: str            # second line of графа 1
    material: str = ""          # графа 3 (for a course sheet: the discipline)
    letter: str = "У"           # графа 4: литера «У» (учебный документ)
    scale: str = ""             # графа 6: масштаб, when the whole sheet has one
    sheet: int = 1              # графа 7
    sheets: int = 1             # графа 8
    organisation: str = ""      # графа 9: university, group
    developer: str = ""         # Разраб.
    checker: str = ""           # Пров.
    tech_control: str = ""      # Т.контр.
    norm_control: str = ""      # Н.контр.
    approver: str = ""          # Утв.
    date: str = ""              # the date beside Разраб.


def _lw(mm: float) -> float:
    return mm * PT_PER_MM


def _line(ax, x0, y0, x1, y1, main: bool) -> None:
    ax.plot([x0, x1], [y0, y1], color="black", lw=_lw(LW_MAIN_MM if main else LW_THIN_MM),
            solid_capstyle="butt", zorder=5)


def lettering(s: str, literal: bool = False) -> str:
    """Text as osifont can letter it: its «ё», «Ё», «э», «Э» are blank boxes and it has no U+2212,
    so «е» (as drafting lettering writes it) and the hyphen-minus stand for the first and the last;
    «э», «Э» are set by mathtext in the note's upright face (outside the formulas of the text).
    ``literal``: text from the case (the title block's fields) holds no formula: its «$» are
    lettered as they are, never read by mathtext."""
    s = s.replace("ё", "е").replace("Ё", "Е").replace("−", "-")
    if literal:
        s = s.replace("$", r"\$")
    parts = [s] if literal else s.split("$")
    for i in range(0, len(parts), 2):            # the text between formulas
        parts[i] = parts[i].replace("э", r"$\mathrm{э}$").replace("Э", r"$\mathrm{Э}$")
    return "$".join(parts)


def _text(ax, x, y, s, size_mm, ha="center", va="center", family=None, width_mm=None, **kw):
    """Lettering of height ``size_mm`` (capital height ≈ font size · 0,7 for osifont), shrunk to
    ``width_mm`` = (width, height) of its cell if it would not fit."""
    if not s:
        return None
    fs = size_mm / 0.7 * PT_PER_MM
    t = ax.text(x, y, lettering(s, literal=True), fontsize=fs, ha=ha, va=va, fontfamily=family, zorder=6, **kw)
    if width_mm is not None:
        t._reportgen_fit = width_mm  # read by fit_texts after the first draw
    return t


def draw_frame(ax, block: TitleBlock, family: str | None = None) -> list:
    """Draw the frame and the title block on ``ax`` (mm coordinates); return the texts that must
    be fitted to their cells (see :func:`fit_texts`)."""
    x0, y0, x1, y1 = FRAME
    ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, lw=_lw(LW_MAIN_MM), ec="black", zorder=5))
    bx, by = BLOCK[0], BLOCK[1]

    def L(xa, ya, xb, yb, main=True):
        _line(ax, bx + xa, by + ya, bx + xb, by + yb, main)

    texts = []

    def T(x, y, s, h, ha="center", w=None, **kw):
        t = _text(ax, bx + x, by + y, s, h, ha=ha, family=family, width_mm=w, **kw)
        if t is not None:
            texts.append(t)

    # outline and main divisions (solid main lines)
    ax.add_patch(Rectangle((bx, by), BLOCK_W, BLOCK_H, fill=False, lw=_lw(LW_MAIN_MM), ec="black", zorder=5))
    cols = (7, 17, 40, 55, 65)
    for c in cols:
        # Изм. and Лист share one cell (17 mm) in the rows of the persons
        L(c, 30 if c == 7 else 0, c, BLOCK_H)
    L(135, 0, 135, 40)
    L(65, 40, 185, 40)                # under графа 2
    L(65, 15, 185, 15)                # над графой 3 / графой 9
    L(135, 35, 185, 35)
    L(135, 20, 185, 20)
    L(150, 20, 150, 40)
    L(167, 20, 167, 40)
    L(155, 15, 155, 20)
    # left part: 11 rows of 5 mm; the header row (Изм., Лист, …) is bounded by main lines
    for k in range(1, 11):
        y = 5.0 * k
        L(0, y, 65, y, main=k in (6, 7))
    for c in (140, 145):              # the three cells of the letter
        L(c, 20, c, 35, main=False)
    # captions of the block (2,5 mm)
    for (x, s) in zip((3.5, 12, 28.5, 47.5, 60), ("Изм.", "Лист", "№ докум.", "Подп.", "Дата")):
        T(x, 32.5, s, 2.0)
    roles = (("Разраб.", block.developer), ("Пров.", block.checker), ("Т.контр.", block.tech_control),
             ("", ""), ("Н.контр.", block.norm_control), ("Утв.", block.approver))
    for i, (role, person) in enumerate(roles):
        y = 27.5 - 5.0 * i
        T(1.0, y, role, 2.0, ha="left")
        T(18.0, y, person, 2.5, ha="left", w=(21.5, 4.5))
    T(60, 27.5, block.date, 2.0, w=(9.5, 4.5))
    T(142.5, 37.5, "Лит.", 2.0)
    T(158.5, 37.5, "Масса", 2.0)
    T(176, 37.5, "Масштаб", 2.0)
    T(137.5, 27.5, block.letter, 3.5)
    T(176, 27.5, block.scale, 3.5, w=(17, 13))
    T(136, 17.5, f"Лист {block.sheet}", 2.5, ha="left")
    T(157, 17.5, f"Листов {block.sheets}", 2.5, ha="left")
    # the fields
    T(125, 47.5, block.designation, 5.0, w=(115, 13))
    T(100, 33.5, block.name, 2.5, w=(67, 11.5), linespacing=1.15)
    T(100, 21.5, block.sheet_title, 3.5, w=(67, 11), linespacing=1.15)
    T(100, 7.5, block.material, 3.5, w=(67, 13), linespacing=1.15)
    T(160, 7.5, block.organisation, 2.5, w=(48, 13), linespacing=1.15)
    return texts


def fit_texts(fig, texts) -> None:
    """Shrink every text marked with a cell width until its rendered width fits the cell."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    renderer = FigureCanvasAgg(fig).get_renderer()
    ax = texts[0].axes if texts else None
    for t in texts:
        cell = getattr(t, "_reportgen_fit", None)
        if cell is None:
            continue
        w_mm, h_mm = cell
        for _ in range(12):
            bb = t.get_window_extent(renderer).transformed(ax.transData.inverted())
            if bb.width <= w_mm and bb.height <= h_mm:
                break
            t.set_fontsize(t.get_fontsize() * max(0.6, min(w_mm / bb.width, h_mm / bb.height) * 0.98))


def field_rect() -> tuple[float, float, float, float]:
    """The drawing field inside the frame (x0, y0, x1, y1), with a 10 mm clearance."""
    x0, y0, x1, y1 = FRAME
    return (x0 + 10.0, y0 + 10.0, x1 - 10.0, y1 - 10.0)


def block_keepout(clearance: float = 8.0) -> tuple[float, float, float, float]:
    """The title block with a clearance: no view may enter it."""
    x0, y0, x1, y1 = BLOCK
    return (x0 - clearance, y0, x1, y1 + clearance)
