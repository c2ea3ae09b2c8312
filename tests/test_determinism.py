"""Byte-identical outputs whatever the state of the user's caches.

Two `reportgen build` runs in fresh interpreters: the first with an empty cache folder
(XDG_CACHE_HOME → a new folder: no rendered formulas, no remembered table split points, no
matplotlib font list), the second with the cache the first one filled. The PDF and the HTML
must be the same bytes. The two runs also use different PYTHONHASHSEED values: nothing in the
output may depend on the order of a set.
"""
import os
import subprocess
import sys

from conftest import CASES, ROOT


def _build(out, cache, seed: str = "0") -> dict[str, bytes]:
    env = dict(os.environ, PYTHONPATH=str(ROOT), XDG_CACHE_HOME=str(cache), PYTHONHASHSEED=seed)
    for var in ("REPORTGEN_CACHE", "SOURCE_DATE_EPOCH", "MPLCONFIGDIR"):
        env.pop(var, None)
    case = CASES / "ws004_slotted_lever.toml"
    subprocess.run([sys.executable, "-m", "reportgen.cli", "build", str(case), "-o", str(out),
                    "--sections", "structure,kinematics"], cwd=ROOT, env=env, check=True,
                   capture_output=True)
    return {kind: (out / f"{case.stem}.{kind}").read_bytes() for kind in ("pdf", "html")}


def test_first_build_with_an_empty_cache_equals_the_next(tmp_path):
    cache = tmp_path / "cache"
    cache.mkdir()
    first = _build(tmp_path / "a", cache)
    # the first build filled the cache: split points of the long tables (formulas are typeset
    # as text, reportgen/report/mathhtml.py: ziamath images, and their cache, only for a fallback)
    assert any((cache / "reportgen" / "splits").glob("*.json"))
    second = _build(tmp_path / "b", cache, seed="12345")
    for kind in ("pdf", "html"):
        assert first[kind] == second[kind], kind


def test_split_points_are_keyed_by_what_the_layout_reads():
    """The remembered split points of a report are found again when only the drawing inside
    a figure differs (the layout reads an SVG's size, not its content), not when its size does."""
    from reportgen.report import render
    from reportgen.report.formulas import data_uri

    def html(text: str, height: str = "5pt") -> str:
        svg = (f'<svg xmlns="http://www.w3.org/2000/svg" width="10pt" height="{height}" '
               f'viewBox="0 0 10 5"><text>{text}</text></svg>')
        return f'<p><img src="{data_uri(svg)}"> текст</p>'

    assert render._split_key(html("a")) == render._split_key(html("b"))
    assert render._split_key(html("a")) != render._split_key(html("a", "6pt"))
    assert render._split_key(html("a")) != render._split_key(html("a").replace("текст", "текст 2"))
