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


def _order(runs: "batch._Runs", finishing: list[int]) -> list[tuple[int, str]]:
    """The order the variants are taken in when the workers finish in the order ``finishing``
    (a worker's index each time one finishes a variant)."""
    taken = runs.first()
    for r in finishing:
        nxt = runs.next(r)
        if nxt is None:
            break
        taken.append(nxt)
    return taken


def test_workers_take_the_class_in_runs_of_neighbours():
    """Two workers start on rows 1 and 5 of an 8-row class (not on two neighbours, which found
    the same split points from none at once); each goes on row after row of its run (the row
    before it a guess of its split points), however fast; the one done first takes the last
    rows of the other's run, backwards; every variant once."""
    rows = [f"{i:02d}" for i in range(1, 9)]
    got = _order(batch._Runs(rows, 2), [1, 1, 0, 1, 1, 0, 0, 0])
    assert got == [(0, "01"), (1, "05"), (1, "06"), (1, "07"), (0, "02"), (1, "08"), (1, "04"), (0, "03")]
    assert sorted(v for _r, v in got) == rows
    three = _order(batch._Runs(rows, 3), [0, 1, 2, 0, 1, 2, 0, 1])
    assert [v for _r, v in three] == ["01", "04", "07", "02", "05", "08", "03", "06"]
    assert _order(batch._Runs(rows[:1], 2), [0]) == [(0, "01")]


def test_empty_class_table_gives_an_empty_manifest(tmp_path):
    """A table with a header and no rows: no pool of workers (it failed with an internal error),
    an empty manifest."""
    import json

    from conftest import CASES
    from reportgen.cli import main

    table = tmp_path / "v.csv"
    table.write_text("variant,l_OA\n", encoding="utf-8")
    rc = main(["batch", str(table), "--base", str(CASES / "ws000_six_bar.toml"), "-o", str(tmp_path / "o"),
               "--jobs", "2", "--format", "html"])
    assert rc == 0
    m = json.loads((tmp_path / "o" / "manifest.json").read_text(encoding="utf-8"))
    assert m["variants"] == [] and m["ok"] == 0 and m["failed"] == 0
