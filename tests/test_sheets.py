"""The A1 drawing sheets: format, frame, title block from [meta], views inside the field, clear of
the title block and of each other, standard scales, byte-identical rebuilds."""
from __future__ import annotations

import hashlib
import subprocess
from pathlib import Path

import pytest
from pypdf import PdfReader

from reportgen import load_case
from reportgen.sheets import frame as F
from reportgen.sheets.compose import render_sheets, scale_text
from reportgen.sheets.layout import View, _overlap, is_nice, place
from reportgen.sheets.views import cam_results, sheets_for

CASES = Path(__file__).resolve().parents[1] / "cases"
PT_PER_MM = 72 / 25.4


CAM_CASES = ["cam_translating_roller", "cam_rocker_roller", "ws001_cam_2013_2", "cam_rocker_flat"]


@pytest.fixture(scope="module", params=["ws000_six_bar", "ws002_tractor_hitch", "ws004_slotted_lever",
                                         "slider_crank", "gear_pair_shifted", "gear_pair_internal",
                                         "train_2kh_three_planets", "train_2kh_double_select", "train_3k_select"] + CAM_CASES)
def built(request):
    study = load_case(CASES / f"{request.param}.toml")
    pdf, layouts = render_sheets(study)
    return study, pdf, layouts


def test_a1_pages_one_per_sheet(built, tmp_path):
    study, pdf, layouts = built
    path = tmp_path / "s.pdf"
    path.write_bytes(pdf)
    reader = PdfReader(path)
    assert len(reader.pages) == len(layouts) >= 1
    for page in reader.pages:
        w, h = float(page.mediabox.width) / PT_PER_MM, float(page.mediabox.height) / PT_PER_MM
        assert abs(w - 841) < 0.5 and abs(h - 594) < 0.5


def test_views_inside_field_clear_of_block_and_each_other(built):
    _, _, layouts = built
    field = F.field_rect()
    for lay in layouts:
        boxes = [p.box() for p in lay.placed] + ([lay.table_box.box()] if lay.table_box else [])
        for b in boxes:
            assert field[0] - 1e-6 <= b[0] and b[2] <= field[2] + 1e-6
            assert field[1] - 1e-6 <= b[1] and b[3] <= field[3] + 1e-6
            assert not _overlap(b, F.BLOCK)
        for i in range(len(boxes)):
            for j in range(i + 1, len(boxes)):
                assert not _overlap(boxes[i], boxes[j]), (lay.spec.key, i, j)


def test_scales_stay_standard(built):
    _, _, layouts = built
    for lay in layouts:
        for p in lay.placed:
            if p.view.mu is not None:
                assert is_nice(p.mu), (p.view.key, p.mu)


def test_title_block_from_meta(built, tmp_path):
    study, pdf, layouts = built
    path = tmp_path / "s.pdf"
    path.write_bytes(pdf)
    text = subprocess.run(["pdftotext", "-layout", str(path), "-"], capture_output=True, text=True,
                          check=True).stdout
    m = study.meta
    for key in ("student", "supervisor", "group"):
        if m.get(key):
            assert m[key].split()[-1] in text, key
    assert f"Листов {len(layouts)}" in text
    assert "Разраб." in text and "Пров." in text and "Масштаб" in text


def test_view_titles_clear_of_views_and_each_other(built):
    """The titles as the renderer draws them (text extents, mm) lie in the field, above their own
    drawing, and touch no drawing, no table, no title block and no other title."""
    _, _, layouts = built
    field = F.field_rect()
    for lay in layouts:
        drawings = [(p.view.key, p.box(with_title=False)) for p in lay.placed]
        if lay.table_box is not None:
            drawings.append(("__table__", lay.table_box.box(with_title=False)))
        assert len(lay.title_extents) == len(drawings)
        own = dict(drawings)
        for i, (key, t) in enumerate(lay.title_extents):
            assert field[0] - 1e-6 <= t[0] and t[2] <= field[2] + 1e-6 and t[3] <= F.FRAME[3], (lay.spec.key, key)
            assert t[1] >= own[key][3] - 1e-6, (lay.spec.key, key)
            assert not _overlap(t, F.BLOCK), key
            for k2, d in drawings:
                assert not _overlap(t, d), (lay.spec.key, key, k2)
            for k2, t2 in lay.title_extents[i + 1:]:
                assert not _overlap(t, t2), (lay.spec.key, key, k2)


def test_cam_sheet_present_and_last(built):
    """A case with [cam] has the cam sheet, after the linkage sheets, with the profile drawn at a
    ГОСТ 2.302 scale and the results in the table."""
    study, pdf, layouts = built
    keys = [lay.spec.key for lay in layouts]
    assert ("cam" in keys) == study.root.has("cam")
    if "cam" not in keys:
        return
    assert keys[-1] == "cam"
    lay = layouts[-1]
    placed = {p.view.key: p for p in lay.placed}
    assert {"profile", "laws"} <= set(placed)
    assert scale_text("l", placed["profile"].mu).startswith("М ")
    assert lay.table_box is not None
    rows = dict((r[0], r[1]) for r in cam_results(study))
    assert rows["$r_0$"] == pytest.approx(study.cam.synthesis.r0 * 1000)
    if study.cam.contact == "roller":
        assert rows[r"$r_{\mathrm{р}}$"] == pytest.approx(study.cam.roller * 1000)
    if study.cam.scale is not None:     # the scale the case asks for, when the profile fits at it
        assert scale_text("l", placed["profile"].mu) == "М " + study.cam.scale
    assert ("portrait" in placed) == (study.cam.contact != "flat")
    assert ("size" in placed) == study.cam.flat_rocker


def test_linkage_and_cam_sheets_order(tmp_path):
    cam = (CASES / "cam_translating_roller.toml").read_text(encoding="utf-8").split("[cam]", 1)[1]
    link = (CASES / "four_bar.toml").read_text(encoding="utf-8")
    p = tmp_path / "both.toml"
    p.write_text(link + "\n[cam]" + cam, encoding="utf-8")
    keys = [s.key for s in sheets_for(load_case(p))]
    assert keys[0] == "kinematics" and keys[-1] == "cam" and keys.count("cam") == 1


def test_ws000_sheets_use_the_field(built):
    """Each view grows while it fits: the views and the table cover at least 35 % of the field on
    every sheet of ws000."""
    study, _, layouts = built
    if study.name != "ws000_six_bar":
        return
    field = F.field_rect()
    area = (field[2] - field[0]) * (field[3] - field[1])
    for lay in layouts:
        boxes = [p.box(with_title=False) for p in lay.placed]
        if lay.table_box is not None:
            boxes.append(lay.table_box.box(with_title=False))
        cover = sum((b[2] - b[0]) * (b[3] - b[1]) for b in boxes) / area
        assert cover >= 0.35, (lay.spec.key, cover)


def test_views_grow_individually():
    """A small main view and small charts on an empty field: each grows to its own factor, the main
    one the most, scales stay standard, and the placement is the same on a second call."""
    field = F.field_rect()
    views = [View("main", 100.0, 80.0, 0.002, priority=2.0), View("a", 120.0, 60.0, None),
             View("b", 120.0, 60.0, 0.05)]
    out = place(views, field, F.block_keepout())
    s = {p.view.key: p.s for p in out}
    assert s["main"] >= s["a"] and s["main"] >= s["b"] and s["main"] > 1.0
    assert is_nice(out[0].mu) and is_nice(out[2].mu)
    again = place(views, field, F.block_keepout())
    assert [(p.x, p.y, p.s) for p in again] == [(p.x, p.y, p.s) for p in out]


def test_group_grows_together():
    """The views of one group (the velocity plans) take their steps together: equal views of a
    group end with equal factors, while a lone view beside them may grow on its own."""
    field = F.field_rect()
    views = [View("p1", 90.0, 60.0, 0.02, group="v"), View("p2", 90.0, 60.0, 0.02, group="v"),
             View("p3", 90.0, 60.0, 0.02, group="v"), View("chart", 160.0, 90.0, None)]
    out = place(views, field, F.block_keepout())
    assert len({p.s for p in out[:3]}) == 1 and out[0].s > 1.0
    assert all(is_nice(p.mu) for p in out[:3])


def test_rebuild_is_byte_identical():
    study = load_case(CASES / "ws004_slotted_lever.toml")
    a, _ = render_sheets(study)
    b, _ = render_sheets(load_case(CASES / "ws004_slotted_lever.toml"))
    assert hashlib.sha256(a).digest() == hashlib.sha256(b).digest()


def test_layout_refuses_what_does_not_fit():
    with pytest.raises(ValueError):
        place([View("x", 2000.0, 2000.0, None)], F.field_rect(), F.block_keepout())


def test_scale_text():
    assert scale_text("l", 0.002) == "М 1:2"
    assert scale_text("l", 0.0025) == "М 1:2,5"
    assert "μ" in scale_text("v", 0.02) or "mu" in scale_text("v", 0.02)
    assert scale_text(None, None) == ""


def test_cli_writes_sheets(tmp_path):
    from reportgen.cli import main
    assert main(["build", str(CASES / "slider_crank.toml"), "-o", str(tmp_path), "--format", "html",
                 "--sheets"]) == 0
    assert (tmp_path / "slider_crank-sheets.pdf").exists()


def _text_boxes(lay):
    """Every lettering of the views as placed on the sheet: (view key, text, (x0, y0, x1, y1) mm),
    from the rendered extents of the texts of each view's figure, enlarged and moved as composed."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text
    out = []
    for p in lay.drawings():
        fig = lay.figures[p.view.key]
        renderer = FigureCanvasAgg(fig).get_renderer()
        fig.draw_without_rendering()
        k = 25.4 / fig.dpi * p.s
        for t in _drawn_texts(fig):
            if not isinstance(t, Text) or not t.get_visible() or not t.get_text().strip():
                continue
            bb = t.get_window_extent(renderer)
            out.append((p.view.key, t.get_text(), (p.x + bb.x0 * k, p.y + bb.y0 * k, p.x + bb.x1 * k, p.y + bb.y1 * k)))
    return out


def _drawn_texts(fig):
    """The texts matplotlib draws: free texts, titles, axis labels, legends and the labels of
    the ticks inside the axes' limits (the others exist but are not drawn)."""
    out = list(fig.texts)
    for ax in fig.axes:
        out += list(ax.texts) + [ax.title, ax._left_title, ax._right_title]
        if not ax.axison:
            continue
        for axis in (ax.xaxis, ax.yaxis):
            out += [axis.label, axis.offsetText]
            for tick in axis._update_ticks():
                out += [tick.label1, tick.label2]
        if ax.get_legend() is not None:
            out += list(ax.get_legend().get_texts())
    for lg in fig.legends:
        out += list(lg.get_texts())
    return out


def _meet(a, b, tol):
    return a[0] < b[2] - tol and b[0] < a[2] - tol and a[1] < b[3] - tol and b[1] < a[3] - tol


def test_labels_on_the_sheet_clear(built):
    """The labels inside the views, as placed on the sheet: each inside its own view's drawing,
    none on another label (of its view or another), on a view title, a caption or the title
    block (0,3 mm tolerance for the glyphs' side bearings)."""
    _, _, layouts = built
    for lay in layouts:
        boxes = _text_boxes(lay)
        own = {p.view.key: p.box(with_title=False) for p in lay.drawings()}
        others = [b for _, b in lay.title_extents + lay.caption_extents] + [F.BLOCK]
        for key, text, b in boxes:
            o = own[key]
            assert o[0] - 0.5 <= b[0] and b[2] <= o[2] + 0.5 and o[1] - 0.5 <= b[1] and b[3] <= o[3] + 0.5, \
                (lay.spec.key, key, text)
            assert not any(_meet(b, t, 0.3) for t in others), (lay.spec.key, key, text)
        bad = [(boxes[i][:2], boxes[j][:2]) for i in range(len(boxes)) for j in range(i + 1, len(boxes))
               if _meet(boxes[i][2], boxes[j][2], 0.3)]
        assert not bad, (lay.spec.key, bad[:5])


def _stroke_widths(pdf: bytes) -> dict[float, int]:
    """The width (mm on the sheet) of every stroke drawn on the pages: the content streams are
    interpreted with the transformation matrix (q, Q, cm, form XObjects), each stroke's line
    width scaled by it."""
    import collections
    import io

    from pypdf.generic import ContentStream
    reader = PdfReader(io.BytesIO(pdf))
    out: dict[float, int] = collections.Counter()

    def mul(m, c):
        a, b, c_, d, e, f = m
        A, B, C, D, E, G = c
        return (a * A + b * C, a * B + b * D, c_ * A + d * C, c_ * B + d * D, e * A + f * C + E, e * B + f * D + G)

    def walk(content, res, ctm, lw=1.0):
        stack = []
        for operands, op in ContentStream(content, reader).operations:
            if op == b"q":
                stack.append((ctm, lw))
            elif op == b"Q":
                ctm, lw = stack.pop()
            elif op == b"cm":
                ctm = mul([float(x) for x in operands], ctm)
            elif op == b"w":
                lw = float(operands[0])
            elif op in (b"S", b"s", b"B", b"B*", b"b", b"b*"):
                scale = abs(ctm[0] * ctm[3] - ctm[1] * ctm[2]) ** 0.5
                out[round(lw * scale / PT_PER_MM, 3)] += 1
            elif op == b"Do":
                xo = res["/XObject"][operands[0]].get_object()
                if xo.get("/Subtype") == "/Form":
                    m = [float(x) for x in xo.get("/Matrix", [1, 0, 0, 1, 0, 0])]
                    walk(xo, xo.get("/Resources", res), mul(m, ctm), lw)   # a form inherits the state

    for page in reader.pages:
        walk(page.get_contents(), page["/Resources"], (1.0, 0.0, 0.0, 1.0, 0.0, 0.0))
    return out


def test_line_weights_gost_2_303(built):
    """Every stroke of every sheet, as printed: a solid main line S = 0,7 mm or a thin line
    0,25 mm (S/3 … S/2, also the dashed and dash-dot ones), nothing else; both are used."""
    _, pdf, _ = built
    widths = _stroke_widths(pdf)
    assert widths
    for w, n in widths.items():
        assert abs(w - F.LW_MAIN_MM) <= 0.01 or abs(w - F.LW_THIN_MM) <= 0.01 or w == 0.0, (w, n)
    assert any(abs(w - F.LW_MAIN_MM) <= 0.01 for w in widths) and any(abs(w - F.LW_THIN_MM) <= 0.01 for w in widths)


def test_every_sheet_has_a_table_of_results(built):
    _, _, layouts = built
    for lay in layouts:
        assert lay.table_box is not None, lay.spec.key


def test_velocity_plans_in_order_at_one_scale(built):
    """The kinematics sheet: the velocity plans of every regular position, in the order of their
    numbers, all at one μ_V (a round value), captioned with the position's number; one μ_a."""
    study, _, layouts = built
    lay = next((l for l in layouts if l.spec.key == "kinematics"), None)
    if lay is None or study.mechanism.driver.omega is None:
        return
    from reportgen.report.russian import position_names
    names = position_names(study.kinematics["pos"])
    cells = [c for c in lay.cells if c.view.key.startswith("v")]
    nums = [int(names[c.view.key[1:]]) for c in cells]
    assert nums == sorted(nums) and len(nums) == sum(1 for p in study.kinematics["pos"] if not str(p).startswith("д"))
    assert len({round(c.mu, 12) for c in cells}) == 1 and is_nice(cells[0].mu)
    assert lay.group_mu["velocity"] == pytest.approx(cells[0].mu)
    assert len({round(c.mu, 12) for c in lay.cells if c.view.key.startswith("a")}) == 1
    # rows in reading order: each cell is right of the one before or starts a lower row
    for a, b in zip(cells, cells[1:]):
        assert b.x > a.x or b.y + b.h < a.y + a.h
    caps = dict(lay.caption_extents)
    assert all(c.view.key in caps for c in lay.cells)


def test_forces_sheet_shows_the_loaded_mechanism(built):
    """The force sheet's first view is the whole mechanism at the position with its loads, at a
    ГОСТ 2.302 scale."""
    study, _, layouts = built
    lay = next((l for l in layouts if l.spec.key == "forces"), None)
    if lay is None:
        return
    p = next(p for p in lay.placed if p.view.key == "scheme")
    assert scale_text("l", p.mu).startswith("М ")
    texts = {t for k, t, _ in _text_boxes(lay) if k == "scheme"}
    loads = study.forces.details(study.forces.labels[0])["loads"]
    from reportgen.scenes.forces import load_label, math_label
    assert {math_label(load_label(ld)) for ld in loads if ld["kind"] == "G"} <= texts
    assert any("ур" in t for t in texts) or study.mechanism.driver.kind != "crank"
