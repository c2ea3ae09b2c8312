"""Composing a drawing sheet: the frame page drawn with matplotlib, the views overlaid as vector
PDF pages (pypdf), each enlarged by its factor and written with its title and scale.

No WeasyPrint here: a sheet is one matplotlib page plus the views' own PDF pages, so it renders in
about the time the scenes take and byte-identically (no dates, fixed ids, sorted resources).
"""
from __future__ import annotations

import io
import math

import numpy as np
from dataclasses import dataclass, field

from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from ..style import mplstyle
from ..style.numbers import fmt
from . import frame as F
from .layout import Block, Placed, View, block, place
from .views import ACCELERATION, FORCE, LENGTH, VELOCITY, Rendered, SheetSpec, render_view

MM_PER_IN = 25.4
PT_PER_MM = 72.0 / 25.4
GOST_SCALES = (1, 2, 2.5, 4, 5, 10, 15, 20, 25, 40, 50, 75, 100, 200, 400, 500, 800, 1000)
TABLE_ROW_MM = 8.0
TABLE_W_MM = (60.0, 45.0)


@dataclass
class SheetLayout:
    """Where everything went on one sheet (mm, origin at the sheet's lower left corner)."""

    spec: SheetSpec
    placed: list[Placed]
    table_box: tuple[float, float, float, float] | None
    title_boxes: list[tuple[float, float, float, float]]
    # the titles as drawn: (key, (x0, y0, x1, y1) in mm), measured by the renderer in compose()
    title_extents: list[tuple[str, tuple[float, float, float, float]]] = field(default_factory=list)
    # the views of the groups (velocity plans …) as placed inside their blocks, and the common
    # scale each group takes on the sheet
    cells: list[Placed] = field(default_factory=list)
    group_mu: dict[str, float] = field(default_factory=dict)
    # the captions of the cells as drawn: (key, extents in mm)
    caption_extents: list[tuple[str, tuple[float, float, float, float]]] = field(default_factory=list)
    figures: dict = field(default_factory=dict)      # key → the view's figure as composed (for the checks)

    def drawings(self) -> list[Placed]:
        """Every view whose own drawing is on the sheet: the single views and the cells of the
        blocks (not the blocks themselves)."""
        return [p for p in self.placed if not p.view.key.startswith(GROUP)] + self.cells


def _num(x: float) -> str:
    """A scale factor as printed: its significant digits only, decimal comma."""
    return f"{x:.6g}".replace(".", ",").replace("-", "−")


def scale_text(kind: str | None, mu: float | None) -> str:
    """The scale written beside a view: ГОСТ 2.302 «М 1:n» for a mechanism drawn to a standard
    scale, the scale factor μ otherwise (м/мм, (м/с)/мм, (м/с²)/мм, Н/мм)."""
    if kind is None or mu is None:
        return ""
    if kind == LENGTH:
        n = mu * 1000.0
        for s in GOST_SCALES:
            if abs(n - s) < 1e-9 * s:
                return f"М 1:{_num(n)}"
            if s > 1 and abs(n * s - 1.0) < 1e-9:      # enlargement scales 2:1 … 10:1
                return f"М {_num(s)}:1"
        return f"$\\mu_l$ = {_num(mu)} м/мм"
    sym, unit = {VELOCITY: ("\\mu_V", "(м/с)/мм"), ACCELERATION: ("\\mu_a", "(м/с²)/мм"),
                 FORCE: ("\\mu_F", "Н/мм")}[kind]
    return f"${sym}$ = {_num(mu)} {unit}"


def _fig_pdf(fig: Figure) -> bytes:
    buf = io.BytesIO()
    for ax in fig.axes:
        mplstyle.localize_axes(ax)
    fig.savefig(buf, format="pdf", metadata={"CreationDate": None, "ModDate": None, "Producer": None,
                                               "Creator": None})
    return buf.getvalue()


MAIN_FROM_PT = 0.95      # a solid line of the scenes at least this wide is a main line on the sheet
                         # (the other positions of the plan of positions, at 0,91 pt, stay thin)
DASH_DOT_MM = (12.0, 3.0, 0.5, 3.0)   # ГОСТ 2.303: dash-dot thin, dashes 5…30 mm, gaps 3…5 mm
DASHED_MM = (5.0, 2.0)                # dashed: dashes 2…8 mm, gaps 1…2 mm


def gost_lines(fig: Figure, s: float) -> None:
    """Give every line of a view the weight of its type (ГОСТ 2.303) as it will be printed on the
    sheet, enlarged ``s`` times: solid lines the scenes draw at least ``MAIN_FROM_PT`` wide
    (contours, links, vectors, curves) become solid main lines S = 0,7 mm; the others, every
    dashed and dash-dot line, the axes, grids and ticks of the charts become thin lines of
    0,25 mm (S/3 … S/2); dashed and dash-dot lines get the standard dash lengths."""
    from matplotlib.collections import Collection
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    main, thin = F.LW_MAIN_MM * PT_PER_MM / s, F.LW_THIN_MM * PT_PER_MM / s
    aux = set()
    for ax in fig.axes:
        ax.tick_params(which="both", width=thin, grid_linewidth=thin)   # ticks made again at drawing
        aux |= set(ax.spines.values()) | set(ax.get_xgridlines()) | set(ax.get_ygridlines())
        aux |= set(ax.xaxis.get_ticklines(minor=False)) | set(ax.yaxis.get_ticklines(minor=False))
        aux |= set(ax.xaxis.get_ticklines(minor=True)) | set(ax.yaxis.get_ticklines(minor=True))

    def pattern(art) -> tuple | None:
        pat = getattr(art, "_unscaled_dash_pattern", (None, None))[1]
        return tuple(pat) if pat else None

    def restyle(art, pat) -> None:
        mm = DASH_DOT_MM if len(pat) >= 4 else DASHED_MM
        art.set_linestyle((0, tuple(x / F.LW_THIN_MM for x in mm)))

    from matplotlib.text import Annotation
    arts = fig.findobj(lambda a: isinstance(a, (Line2D, Patch, Collection)))
    arts += [a.arrow_patch for a in fig.findobj(Annotation) if a.arrow_patch is not None and a.arrow_patch not in arts]
    for art in arts:
        if isinstance(art, Collection):
            lws = np.atleast_1d(art.get_linewidths()).astype(float)
            if lws.size:
                art.set_linewidths([0.0 if w <= 0 else (main if w >= MAIN_FROM_PT else thin) for w in lws])
            continue
        lw = float(art.get_linewidth() or 0.0)
        pat = pattern(art)
        if isinstance(art, Line2D) and art.get_marker() not in (None, "", "None", " "):
            art.set_markeredgewidth(thin)
        if lw <= 0:
            continue
        art.set_linewidth(main if (lw >= MAIN_FROM_PT and pat is None and art not in aux) else thin)
        if pat is not None:
            restyle(art, pat)


def _size_mm(fig: Figure) -> tuple[float, float]:
    w, h = fig.get_size_inches()
    return float(w * MM_PER_IN), float(h * MM_PER_IN)


def _table_size(rows) -> tuple[float, float]:
    return (sum(TABLE_W_MM), TABLE_ROW_MM * (len(rows) + 1))


TITLE_FS = 3.5 / 0.7 * PT_PER_MM     # lettering 3,5 mm (ГОСТ 2.304) of the views' titles
TABLE_TITLE = F.lettering("Результаты расчёта")


def view_title(r: Rendered, mu: float | None) -> str:
    text = _title(r.spec.title, r.spec.scale, mu)
    if r.mu2 and mu and r.mu:
        text += "   " + F.lettering(scale_text(r.spec.mu2[0], r.mu2 * mu / r.mu))
    return text


def _title(title: str, kind: str | None, mu: float | None) -> str:
    sc = scale_text(kind, mu)
    return F.lettering(title + (f"   {sc}" if sc else ""))


GROUP = "group:"
REDRAW_MAX = 2.5      # a view redrawn at its sheet scale grows at most this much beyond its first drawing
CHART_MIN_S = 1.0     # a chart or the table is not shrunk (its lettering would fall under 2,5 mm)
CAPTION_FS = TITLE_FS          # the captions of the cells of a block (the position numbers)


def _title_widths(texts: list[str], family: str | None) -> list[float]:
    """Rendered widths (mm) of the title lines, plus a margin of 6 mm (the scale's digits may
    change with the enlargement)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    fig = Figure(figsize=(F.SHEET_W / MM_PER_IN, F.SHEET_H / MM_PER_IN))
    renderer = FigureCanvasAgg(fig).get_renderer()
    out = []
    for s in texts:
        t = fig.text(0, 0, s, fontsize=TITLE_FS, fontfamily=family)
        out.append(t.get_window_extent(renderer).width / fig.dpi * MM_PER_IN + 6.0)
    return out


def layout_sheet(spec: SheetSpec, rendered: list[Rendered], table_rows) -> SheetLayout:
    """Place the views, the blocks of the groups and the table.  A group's block is tried with
    rows of several widths; the arrangement that covers most of the field (then lets the group
    grow most) is kept."""
    from .title import drafting_family
    family = drafting_family()
    singles = [r for r in rendered if r.spec.group is None or r.spec.group not in spec.groups]
    members = {g: [r for r in rendered if r.spec.group == g] for g in spec.groups}
    members = {g: m for g, m in members.items() if m}
    gtitles = {g: _title(spec.groups[g].title, spec.groups[g].scale, m[0].mu) for g, m in members.items()}
    widths = _title_widths([view_title(r, r.mu) for r in singles] + [gtitles[g] for g in members] + [TABLE_TITLE],
                           family)
    views = []
    for r, tw in zip(singles, widths):
        w, h = _size_mm(r.fig)
        views.append(View(r.spec.key, w, h, r.mu, priority=r.spec.priority, title_w=tw, mu_only=r.spec.mu_only,
                          group=r.spec.group, min_s=max(r.spec.min_s, CHART_MIN_S if r.mu is None else 0.0),
                          max_s=r.spec.max_s,
                          mu2=r.mu2 if r.spec.redraw is None else None))
    if table_rows:
        tw, th = _table_size(table_rows)
        views.append(View("__table__", tw, th, None, title_h=9.0, title_w=widths[-1], min_s=CHART_MIN_S,
                          max_s=1.25))
    field = F.field_rect()
    # the sheet's own title line takes the top 12 mm of the field
    field = (field[0], field[1], field[2], field[3] - 12.0)
    keepout = F.block_keepout()
    gviews = {}
    for g, m in members.items():
        caps = [w - 6.0 for w in _title_widths([F.lettering(r.spec.title) for r in m], family)]
        mv = [View(r.spec.key, *_size_mm(r.fig), r.mu, min_s=r.spec.min_s, max_s=r.spec.max_s) for r in m]
        # the caption keeps its size while the cell shrinks to min_s: the cell is made wide enough
        capw = [c / mv[0].min_s for c in caps]
        cw = [max(v.width, c) for v, c in zip(mv, capw)]
        lo, hi = max(cw), sum(cw) + 4.0 * len(cw)
        tries = sorted({lo} | ({lo + (hi - lo) * k / 10 for k in range(1, 11)} if len(mv) > 1 else set()))
        gviews[g] = [block(GROUP + g, mv, w, widths[len(singles) + list(members).index(g)], capw,
                           spec.groups[g].priority) for w in tries]
    blocks: dict[str, Block] = {}
    placed = None
    for g in members:                      # the groups one after the other, the best arrangement each
        best = None
        for b in gviews[g]:
            trial = views + [blocks[h].view for h in blocks] + [b.view]
            try:
                res = place(trial, field, keepout)
            except ValueError:
                continue
            s_g = next(p.s for p in res if p.view.key == b.view.key)
            cover = sum(p.w * p.h for p in res)
            if best is None or (cover, s_g) > best[0]:
                best = ((cover, s_g), b, res)
        if best is None:
            raise ValueError("виды не помещаются на листе")
        blocks[g] = best[1]
        placed = best[2]
    if placed is None:
        placed = place(views, field, keepout)
    table_box = None
    out, cells, group_mu = [], [], {}
    for p in placed:
        if p.view.key == "__table__":
            table_box = p
            continue
        out.append(p)
        if p.view.key.startswith(GROUP):
            g = p.view.key[len(GROUP):]
            group_mu[g] = p.mu
            for v, cx, cy in blocks[g].cells:
                cells.append(Placed(v, p.x + cx * p.s, p.y + cy * p.s, p.s))
    titles = [(p.x - p.dx, p.y + p.h, p.x + p.w + p.dx, p.y + p.h + p.view.title_h) for p in placed]
    return SheetLayout(spec, out, table_box, titles, cells=cells, group_mu=group_mu)


def caption_xy(c: Placed) -> tuple[float, float]:
    """Where the caption of a cell is centred: in the strip above the cell's drawing."""
    from .layout import CAPTION_MM
    return c.x + c.w / 2, c.y + c.h + CAPTION_MM * c.s / 2


def _draw_table(ax, p: Placed, rows, family) -> None:
    """A table of results: quantity and value, thin inner lines, main outline (ГОСТ 2.303)."""
    s = p.s
    x0, y0 = p.x, p.y
    w1, w2 = TABLE_W_MM[0] * s, TABLE_W_MM[1] * s
    rh = TABLE_ROW_MM * s
    n = len(rows) + 1
    top = y0 + n * rh
    ax.add_patch(Rectangle((x0, y0), w1 + w2, n * rh, fill=False, lw=F.LW_MAIN_MM * PT_PER_MM, ec="black", zorder=5))
    for i in range(1, n):
        y = top - i * rh
        ax.plot([x0, x0 + w1 + w2], [y, y], color="black",
                lw=(F.LW_MAIN_MM if i == 1 else F.LW_THIN_MM) * PT_PER_MM, zorder=5)
    ax.plot([x0 + w1, x0 + w1], [y0, top], color="black", lw=F.LW_MAIN_MM * PT_PER_MM, zorder=5)
    fs = 3.5 / 0.7 * PT_PER_MM * min(s, 1.5)
    ax.text(x0 + w1 / 2, top - rh / 2, "Величина", ha="center", va="center", fontsize=fs, fontfamily=family)
    ax.text(x0 + w1 + w2 / 2, top - rh / 2, "Значение", ha="center", va="center", fontsize=fs, fontfamily=family)
    for i, (name, value, unit) in enumerate(rows, start=1):
        y = top - (i + 0.5) * rh
        ax.text(x0 + 2 * s, y, F.lettering(name), ha="left", va="center", fontsize=fs, fontfamily=family)
        num = str(value) if isinstance(value, int) else fmt(value, sig=4)     # counts (W, class) as integers
        ax.text(x0 + w1 + w2 / 2, y, F.lettering(num + ("" if unit in ("", "°") else " ") + unit), ha="center",
                va="center", fontsize=fs, fontfamily=family)


def _frame_page(layout: SheetLayout, block: F.TitleBlock, rendered: list[Rendered], table_rows,
                family: str | None) -> tuple[bytes, Figure]:
    mplstyle.apply_style()
    fig = Figure(figsize=(F.SHEET_W / MM_PER_IN, F.SHEET_H / MM_PER_IN))
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, F.SHEET_W)
    ax.set_ylim(0, F.SHEET_H)
    ax.axis("off")
    texts = F.draw_frame(ax, block, family)
    fx0, fy0, fx1, fy1 = F.field_rect()
    texts.append(ax.text((fx0 + fx1) / 2, fy1 - 5.0, F.lettering(layout.spec.title), ha="center", va="center",
                         fontsize=7.0 / 0.7 * PT_PER_MM, fontfamily=family))
    by_key = {r.spec.key: r for r in rendered}
    titles = []
    for p in layout.placed:
        if p.view.key.startswith(GROUP):
            g = layout.spec.groups[p.view.key[len(GROUP):]]
            text = _title(g.title, g.scale, p.mu)
        else:
            text = view_title(by_key[p.view.key], p.mu)
        t = ax.text(p.x + p.w / 2, p.y + p.h + 4.0, text, ha="center", va="center", fontsize=TITLE_FS,
                    fontfamily=family)
        titles.append((p.view.key, t))
    captions = []
    for c in layout.cells:
        x, y = caption_xy(c)
        captions.append((c.view.key, ax.text(x, y, F.lettering(by_key[c.view.key].spec.title), ha="center",
                                             va="center", fontsize=CAPTION_FS, fontfamily=family)))
    if layout.table_box is not None:
        tb = layout.table_box
        t = ax.text(tb.x + tb.w / 2, tb.y + tb.h + 4.0, TABLE_TITLE, ha="center", va="center",
                    fontsize=TITLE_FS, fontfamily=family)
        titles.append(("__table__", t))
        _draw_table(ax, tb, table_rows, family)
    F.fit_texts(fig, texts)
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    renderer = FigureCanvasAgg(fig).get_renderer()
    inv = ax.transData.inverted()
    layout.title_extents = [(k, tuple(float(v) for v in t.get_window_extent(renderer).transformed(inv).extents))
                            for k, t in titles]
    layout.caption_extents = [(k, tuple(float(v) for v in t.get_window_extent(renderer).transformed(inv).extents))
                              for k, t in captions]
    return _fig_pdf(fig), fig


def compose(layouts: list[tuple[SheetLayout, F.TitleBlock, list[Rendered], list]]) -> bytes:
    """All sheets as one PDF (one A1 page per sheet)."""
    from pypdf import PdfReader, PdfWriter, Transformation

    from .title import drafting_family
    family = drafting_family()
    writer = PdfWriter()
    for layout, tblock, rendered, rows in layouts:
        page_pdf, _ = _frame_page(layout, tblock, rendered, rows, family)
        page = writer.add_page(PdfReader(io.BytesIO(page_pdf)).pages[0])
        by_key = {r.spec.key: r for r in rendered}
        for p in layout.drawings():
            fig = by_key[p.view.key].fig
            gost_lines(fig, p.s)
            view = PdfReader(io.BytesIO(_fig_pdf(fig))).pages[0]
            op = Transformation().scale(p.s, p.s).translate(p.x * PT_PER_MM, p.y * PT_PER_MM)
            page.merge_transformed_page(view, op)
    writer.add_metadata({"/Producer": "reportgen", "/Title": layouts[0][1].name if layouts else ""})
    buf = io.BytesIO()
    writer.write(buf)
    return buf.getvalue()


def sheet_scale(rendered: list[Rendered], layout: SheetLayout) -> str:
    """The scale for the title block (ГОСТ 2.104, графа 6): the one ГОСТ 2.302 scale of the
    drawn-to-scale views if they share it, else that of the main view (the highest priority)."""
    by_key = {r.spec.key: r for r in rendered}
    texts = [(by_key[p.view.key].spec.priority, scale_text(LENGTH, p.mu)) for p in layout.placed
             if p.view.key in by_key and by_key[p.view.key].spec.scale == LENGTH]
    gost = [(pr, t[2:]) for pr, t in texts if t.startswith("М ")]
    if not gost:
        return ""
    if len({t for _, t in gost}) == 1:
        return gost[0][1]
    return max(gost, key=lambda x: x[0])[1]


def redrawn(spec: SheetSpec, rendered: list[Rendered], layout: SheetLayout) -> tuple[SheetSpec, set[str]]:
    """The sheet with every view that can be redrawn (``ViewSpec.redraw``) and took another scale
    on the sheet drawn at that scale (no longer to be shrunk: its lettering stays at least at its
    natural size), and the keys of those views.  The views of a group take the group's scale."""
    from dataclasses import replace
    scale = {p.view.key: p for p in layout.placed}
    mus = dict(layout.group_mu)
    views, again = [], set()
    for v, r in zip(spec.views, rendered):
        mu = mus.get(v.group) if v.group in spec.groups else (scale[v.key].mu if v.key in scale else None)
        if v.redraw is not None and mu is not None and r.mu is not None and not math.isclose(mu, r.mu):
            mu = float(f"{mu:.10g}")
            args = (mu, mus) if v.mu2 is None else (mu, mus, r.mu2 * mu / r.mu)
            grown = v.grown * r.mu / mu
            v = replace(v, draw=v.redraw(*args), min_s=1.0, grown=grown, max_s=max(1.0, REDRAW_MAX / grown))
            again.add(v.key)
        views.append(v)
    return replace(spec, views=views), again


def render_sheets(study) -> tuple[bytes, list[SheetLayout]]:
    """Render every sheet of the study: (PDF bytes, layouts for the checks)."""
    from .title import title_block
    from .views import sheets_for

    specs = sheets_for(study)
    items = []
    for i, spec in enumerate(specs, start=1):
        rendered = [render_view(v, study) for v in spec.views]
        rows = spec.table(study) if spec.table else []
        layout = layout_sheet(spec, rendered, rows)
        for _ in range(4):         # a redrawn view may grow again (its margins did not grow): redraw it again
            spec, again = redrawn(spec, rendered, layout)
            if not again:
                break
            rendered = [render_view(v, study) if v.key in again else r for v, r in zip(spec.views, rendered)]
            layout = layout_sheet(spec, rendered, rows)
        layout.figures = {r.spec.key: r.fig for r in rendered}
        tblock = title_block(study, spec, i, len(specs), sheet_scale(rendered, layout))
        items.append((layout, tblock, rendered, rows))
    return compose(items), [it[0] for it in items]

