"""``reportgen build CASE --sheets``: write ``DIR/<case>-sheets.pdf`` atomically."""
from __future__ import annotations

from pathlib import Path


def build_sheets(study, out_dir: Path, stem: str) -> Path:
    from ..export import atomic_write
    from .compose import render_sheets

    pdf, _ = render_sheets(study)
    path = Path(out_dir) / f"{stem}-sheets.pdf"
    atomic_write(path, pdf)
    return path
