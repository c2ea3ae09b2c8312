"""A figure's SVG bytes depend on the figure only: not on matplotlib's font cache, not on
what the process drew before.

Every drawing runs in a fresh interpreter (subprocess), so nothing of pytest's process
(fonts already looked up, parsed mathtext, text extents) can hide or cause a difference.

matplotlib's font list (``~/.cache/matplotlib/fontlist-*.json``) is in the order of a
Python ``set`` when the cache was built, and ``findfont`` takes the first of the best
matches: with two files of one family installed (Debian's ``fonts-liberation`` and
``fonts-liberation2`` are both "Liberation Serif", with different outlines and the same
PostScript name) the glyphs of a figure came from one file or the other depending on
the cache, and a variant built by a batch worker was not the bytes of the same variant
built by another. :func:`reportgen.style.mplstyle._settle_font_list` fixes the choice.
"""
import os
import subprocess
import sys

from conftest import CASES, ROOT

# Draws the figures of a section for each listed variant of the class table, in order, and
# writes the SVG of the last variant's figures. The font list can be put into another order
# first, as a cache built by another process would have it:
#   reversed  - the list reversed
#   impostor  - first, an entry of another file (DejaVu Serif) under the report's family name
_DRAW = r"""
import sys
from pathlib import Path
from matplotlib import font_manager as fm
order, section, *names = sys.argv[1:]
if order == "reversed":
    fm.fontManager.ttflist.reverse()
elif order == "impostor":
    from dataclasses import replace
    from reportgen.style import fonts
    family = fonts.find_serif()
    entry = next(e for e in fm.fontManager.ttflist if e.name == family.name
                 and e.style == "normal" and e.weight in (400, "normal", "regular"))
    other = next(e for e in fm.fontManager.ttflist if e.name == "DejaVu Serif" and e.style == "normal"
                 and e.weight in (400, "normal", "regular"))
    fm.fontManager.ttflist.insert(0, replace(entry, fname=other.fname))
import importlib
from reportgen.analysis.study import Study
from reportgen.batch import read_variants
from reportgen.case.load import load_spec
from reportgen.style import mplstyle
variants = {v.name: v for v in read_variants(Path("cases/class_six_bar.csv"), Path("cases/ws000_six_bar.toml"))}
build = importlib.import_module(f"reportgen.report.sections.{section}").build
svgs, to_svg = [], mplstyle.to_svg
mplstyle.to_svg = lambda fig: svgs.append(to_svg(fig)) or svgs[-1]
for name in names:
    svgs.clear()
    build(Study(load_spec(variants[name].base, variants[name].params)))
assert svgs
sys.stdout.buffer.write(b"\n<!-- next figure -->\n".join(svgs))
"""


def _draw(order: str, section: str, *names: str) -> bytes:
    env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONWARNINGS="ignore")
    env.pop("MPLCONFIGDIR", None)
    done = subprocess.run([sys.executable, "-c", _DRAW, order, section, *names], cwd=ROOT, env=env,
                          check=True, capture_output=True)
    return done.stdout


def test_svg_does_not_depend_on_the_order_of_the_font_list():
    assert (CASES / "class_six_bar.csv").is_file()
    plain = _draw("plain", "structure", "03")
    # texts are drawn as glyph outlines (the comments name them): the font file decides the bytes
    assert b"<!-- " in plain and b"<text" not in plain
    assert _draw("reversed", "structure", "03") == plain
    assert _draw("impostor", "structure", "03") == plain


def test_svg_does_not_depend_on_what_the_process_drew_before():
    alone = _draw("plain", "structure", "03")
    assert _draw("plain", "structure", "01", "03") == alone
