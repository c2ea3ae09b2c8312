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


CAM_CASES = ["cam_translating_roller", "cam_rocker_roller", "ws001_cam_2013_2"]


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
