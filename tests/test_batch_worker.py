"""What a kept batch worker shares between variants, and what it lets go after each one."""
from __future__ import annotations

from reportgen import batch


def test_image_cache_keeps_what_the_last_variant_used():
    cache = batch._TouchedCache({"formula": 1, "old figure": 2})
    cache.keep_touched()  # the entries of before the first variant are kept once
    assert set(cache) == {"formula", "old figure"}
    # variant 1 uses the formula (WeasyPrint: `url in cache`, then `cache[url]`) and adds a figure
    assert "formula" in cache and cache["formula"] == 1
    assert "missing" not in cache
    cache["figure 1"] = 3
    assert cache.keep_touched() == 1  # the figure of the variant before is dropped
    assert set(cache) == {"formula", "figure 1"}
    # variant 2: the formula again (through get), a figure of its own
    assert cache.get("formula") == 1 and cache.get("nothing", 0) == 0
    cache["figure 2"] = 4
    cache.keep_touched()
    assert set(cache) == {"formula", "figure 2"}


def test_mathtext_cache_is_shared_and_gives_the_same_parse(monkeypatch):
    """One parse cache for the process, whichever parser (renderer) asks: a label measured by
    the label placer's Agg renderer and drawn by each SVG renderer of savefig is parsed once per
    dpi, size and font, with the same result as matplotlib's own parse."""
    from matplotlib import mathtext
    from matplotlib.font_manager import FontProperties

    from reportgen.style import mplstyle

    own = getattr(mathtext.MathTextParser._parse_cached, "__wrapped__", None)
    own = own or mathtext.MathTextParser._parse_cached
    monkeypatch.setattr(mathtext.MathTextParser, "_parse_cached", own)   # matplotlib's, uncached
    before = mathtext.MathTextParser("path").parse(r"$\omega_{2}$", 72, FontProperties(size=10))
    batch._share_mathtext()
    shared = mathtext.MathTextParser._parse_cached
    batch._share_mathtext()  # idempotent: not wrapped twice
    assert mathtext.MathTextParser._parse_cached is shared
    assert shared.cache_info().maxsize == mplstyle.MATHTEXT_CACHE
    labels = [f"$x_{{{i}}}$" for i in range(200)]
    hits = shared.cache_info().hits
    for s in labels + labels:   # a new parser for every call, as a new renderer makes
        mathtext.MathTextParser("path").parse(s, 72, FontProperties(size=10))
    assert shared.cache_info().hits - hits >= len(labels)
    after = mathtext.MathTextParser("path").parse(r"$\omega_{2}$", 72, FontProperties(size=10))
    assert (after.width, after.height, after.depth) == (before.width, before.height, before.depth)
    assert [g[1:] for g in after.glyphs] == [g[1:] for g in before.glyphs]
    raster = mathtext.MathTextParser("agg").parse(r"$\omega_{2}$", 72, FontProperties(size=10))
    assert type(raster).__name__ == "RasterParse"   # the output type is part of the key


def test_workers_take_the_class_from_different_runs_of_neighbours():
    """Two workers start on rows 1 and 5 of an 8-row class (not on neighbours, which found the
    same split points from none at once), and each run goes on row after row (a neighbour's
    split points a guess for the next); every variant once, a short last run included."""
    rows = [f"{i:02d}" for i in range(1, 9)]
    assert batch._interleaved(rows, 2) == ["01", "05", "02", "06", "03", "07", "04", "08"]
    assert batch._interleaved(rows, 3) == ["01", "04", "07", "02", "05", "08", "03", "06"]
    assert batch._interleaved(rows[:7], 2) == ["01", "05", "02", "06", "03", "07", "04"]
    assert batch._interleaved(rows, 1) == rows and batch._interleaved(rows[:1], 2) == ["01"]
