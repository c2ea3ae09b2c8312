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

CASES = Path(__file__).resolve().parents[1] / "cases"
PT_PER_MM = 72 / 25.4


@pytest.fixture(scope="module", params=["ws000_six_bar", "ws002_tractor_hitch", "ws004_slotted_lever",
                                         "slider_crank"])
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
