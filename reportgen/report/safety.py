"""What the note may take from a case and fetch while it is laid out.

* :func:`validate_options` — ``[report] options`` checked by type and range (a number for a
  size, a boolean for a switch, a short plain text for a word), so a value can neither break
  out of the ``<style>`` element nor bring a ``url()`` into it; a font that is not installed is
  a :class:`~reportgen.errors.CaseError` listing the installed ones.
* :func:`url_fetcher` — the only fetcher WeasyPrint gets: it serves ``data:`` URIs and the
  project's own files (the bundled templates and the serif font files found by
  :mod:`reportgen.style.fonts`) and refuses everything else (``http:``, ``ftp:``, other
  ``file:`` paths), so no build reads the network or embeds a local file.
"""
from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any, Mapping
from urllib.parse import unquote, urlparse

from ..errors import CaseError

__all__ = ["OPTION_RULES", "REPORT_KEYS", "validate_options", "validate_report", "url_fetcher", "check_url", "FetchRefused", "allowed_files"]

# key -> ("number", lo, hi) | ("int", lo, hi) | ("bool",) | ("text", max length) | ("font",)
OPTION_RULES: dict[str, tuple] = {
    "margin_top_mm": ("number", 0.0, 100.0),
    "margin_right_mm": ("number", 0.0, 100.0),
    "margin_bottom_mm": ("number", 0.0, 100.0),
    "margin_left_mm": ("number", 0.0, 100.0),
    "font_size_pt": ("number", 6.0, 24.0),
    "table_font_size_pt": ("number", 6.0, 24.0),
    "line_height": ("number", 1.0, 3.0),
    "indent_mm": ("number", 0.0, 50.0),
    "figure_word": ("text", 40),
    "table_word": ("text", 40),
    "continuation_words": ("text", 60),
    "dash": ("text", 5),
    "eskd_frame": ("bool",),
    "section_new_page": ("bool",),
    "toc_depth": ("int", 1, 3),
    "font": ("font",),
    "title_page": ("bool",),
    "assignment_page": ("bool",),
    "assignment_title": ("text", 80),
    "toc_title": ("text", 80),
    "introduction_title": ("text", 80),
    "conclusion_title": ("text", 80),
    "references_title": ("text", 80),
    "appendix_word": ("text", 40),
    "note_word": ("text", 40),
    "where_word": ("text", 20),
    "eq_number_width_mm": ("number", 5.0, 40.0),
    "screen_max_width_px": ("int", 400, 3000),
}

# plain words only: no markup, CSS or URL syntax, no control characters
_BAD_TEXT = re.compile(r"[<>{}\\;\"'`\x00-\x1f\x7f]|url\s*\(|/\*", re.IGNORECASE)


class OptionError(CaseError, ValueError):
    """A bad ``[report] options`` value (also a ``ValueError`` for callers of the renderer)."""


def _err(key: str, message: str, file: str | None, expected: str, got: Any) -> CaseError:
    return OptionError(message, file=file, key=f"report.options.{key}", expected=expected,
                     got=repr(got)[:80])


def validate_options(options: Mapping[str, Any] | None, *, file: str | None = None) -> dict:
    """``options`` checked against :data:`OPTION_RULES`; returns a plain dict of the values
    (ints for the integer keys, floats for sizes). Unknown keys are an error too."""
    out: dict[str, Any] = {}
    for key, v in dict(options or {}).items():
        rule = OPTION_RULES.get(str(key))
        if rule is None:
            from ..errors import did_you_mean
            raise OptionError(f"неизвестный параметр оформления «{str(key)[:60]}»", file=file,
                            key=f"report.options.{str(key)[:60]}",
                            expected="один из: " + ", ".join(OPTION_RULES),
                            hint=did_you_mean(str(key), list(OPTION_RULES)))
        kind = rule[0]
        if kind in ("number", "int"):
            lo, hi = rule[1], rule[2]
            is_int = isinstance(v, int) and not isinstance(v, bool)
            ok = is_int if kind == "int" else (is_int or isinstance(v, float) and not isinstance(v, bool))
            what = "целое число" if kind == "int" else "число"
            if not ok or not math.isfinite(v) or not lo <= v <= hi:
                raise _err(key, "недопустимое значение параметра оформления", file,
                           f"{what} от {lo:g} до {hi:g}", v)
            out[key] = int(v) if kind == "int" else float(v)
        elif kind == "bool":
            if not isinstance(v, bool):
                raise _err(key, "недопустимое значение параметра оформления", file, "true или false", v)
            out[key] = v
        elif kind == "text":
            if not isinstance(v, str) or len(v) > rule[1] or _BAD_TEXT.search(v):
                raise _err(key, "недопустимое значение параметра оформления", file,
                           f"строка до {rule[1]} символов без знаков < > {{ }} ; \\ кавычек и url(", v)
            out[key] = v
        else:  # font
            if v is None:
                out[key] = None
                continue
            from ..style import fonts
            names = [f.name for f in fonts.candidates() if all(p.is_file() for p in f.faces().values())]
            if not isinstance(v, str) or v.lower() not in [n.lower() for n in names]:
                raise _err(key, "шрифт не найден", file,
                           "один из установленных: " + (", ".join(names) or "нет ни одного"), v)
            out[key] = v
    return out


REPORT_KEYS = ["position", "output", "output_title", "output_v_limit", "options", "sections"]


def section_names() -> list[str]:
    """The note's sections in their order: the linkage's two, then one per registered task kind."""
    from ..registry import KINDS
    return ["structure", "kinematics", *(k.name for k in KINDS)]


def validate_report(node) -> list[str] | None:
    """``[report]`` checked as ``build`` reads it (its keys, ``options``, ``sections``) without
    loading the renderer, so that ``check`` rejects what ``build`` would; returns the sections
    the case asks for, or None."""
    node.check_keys(REPORT_KEYS)
    validate_options(node.table("options").data, file=node.file)
    if not node.has("sections"):
        return None
    raw, ok = node.raw("sections"), section_names()
    if not (isinstance(raw, list) and raw and all(isinstance(x, str) and x in ok for x in raw)):
        raise node.error("sections", "ожидался список разделов записки", expected="sections = [\"dof\"]; разделы: "
                         + ", ".join(ok), got=repr(raw)[:200])
    return [n for n in ok if n in raw]


class FetchRefused(ValueError):
    """Raised by :func:`url_fetcher` for a URL outside the project's own resources
    (WeasyPrint logs it and leaves the resource out)."""


def allowed_files() -> tuple[set[Path], tuple[Path, ...]]:
    """Files and folders the note may load: the serif fonts and the templates folder."""
    from ..style import fonts
    from .render import TEMPLATES_DIR
    files: set[Path] = set()
    for fam in fonts.candidates():
        for p in fam.faces().values():
            try:
                files.add(Path(p).resolve())
            except OSError:
                continue
    return files, (Path(TEMPLATES_DIR).resolve(),)


refused: list[str] = []  # URLs refused in this process (newest last, at most 100): for tests


def check_url(url: str) -> None:
    """Allow ``data:`` URIs and the project's own files; raise :class:`FetchRefused` otherwise."""
    parsed = urlparse(url)
    scheme = parsed.scheme.lower()
    if scheme == "data":
        return
    if scheme == "file" and not parsed.netloc:
        path = Path(unquote(parsed.path)).resolve()
        files, dirs = allowed_files()
        if (path in files or any(d in path.parents for d in dirs)) and path.is_file():
            return
    refused.append(url[:200])
    del refused[:-100]
    raise FetchRefused(f"reportgen: загрузка внешнего ресурса запрещена: {url[:200]}")


def url_fetcher():
    """The WeasyPrint URL fetcher of the note: :func:`check_url` before every fetch, no
    redirects, errors never fatal (a refused resource is left out)."""
    from weasyprint.urls import URLFetcher

    class _SafeFetcher(URLFetcher):
        def fetch(self, url, headers=None):
            check_url(url)
            return super().fetch(url, headers)

    return _SafeFetcher(allowed_protocols=("data", "file"), allow_redirects=False)


# ---------------------------------------------------------------- outputs of one build

STALE_SECONDS = 600.0  # a hidden temporary file this old belongs to a killed run


def clean_stale_temps(out_dir: Path, stem: str | None = None, names: tuple[str, ...] = ()) -> list[Path]:
    """Remove the hidden temporary files left by killed runs in ``out_dir``: those of ``stem``
    (``.<stem>.pdf.*.tmp``, ``.<stem>.html.*.tmp``) and of the file ``names`` about to be
    written (``.<name>.*.tmp``), of any age, and any other ``.*.tmp`` older than
    :data:`STALE_SECONDS`. Returns the removed paths."""
    import time
    out_dir = Path(out_dir)
    removed: list[Path] = []
    if not out_dir.is_dir():
        return removed
    now = time.time()
    for p in out_dir.glob(".*.tmp"):
        try:
            mine = (stem is not None and (p.name.startswith(f".{stem}.pdf.") or p.name.startswith(f".{stem}.html."))
                    or any(p.name.startswith(f".{n}.") for n in names))
            if p.is_file() and (mine or now - p.stat().st_mtime > STALE_SECONDS):
                p.unlink()
                removed.append(p)
        except OSError:
            continue
    return removed


def write_together(out_dir: Path, stem: str, writers: dict) -> dict[str, Path]:
    """Write every format of one build to a hidden temporary file first (``writers[fmt](path)``
    writes it), then rename them all: the PDF and the HTML of one build replace the old ones
    together, and a failure (or a kill before the renames) leaves the old pair untouched. Stale
    temporary files of killed runs are removed first."""
    import os
    import tempfile
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    clean_stale_temps(out_dir, stem)
    temps: dict[str, Path] = {}
    try:
        for fmt, write in writers.items():
            fd, tmp = tempfile.mkstemp(prefix=f".{stem}.{fmt}.", suffix=".tmp", dir=out_dir)
            os.close(fd)
            temps[fmt] = Path(tmp)
            write(Path(tmp))
        result: dict[str, Path] = {}
        for fmt, tmp in temps.items():
            final = out_dir / f"{stem}.{fmt}"
            os.replace(tmp, final)
            result[fmt] = final
        return result
    finally:
        for tmp in temps.values():
            try:
                tmp.unlink()
            except FileNotFoundError:
                pass
