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


def test_mathtext_cache_is_larger_and_gives_the_same_parse(monkeypatch):
    from matplotlib import mathtext
    from matplotlib.font_manager import FontProperties

    monkeypatch.setattr(mathtext.MathTextParser, "_parse_cached", mathtext.MathTextParser._parse_cached)
    small = mathtext.MathTextParser("path")
    before = small.parse(r"$\omega_{2}$", 72, FontProperties(size=10))
    batch._share_mathtext()
    info = mathtext.MathTextParser._parse_cached.cache_info()
    assert info.maxsize == batch.MATHTEXT_CACHE
    batch._share_mathtext()  # idempotent: not wrapped twice
    assert not hasattr(mathtext.MathTextParser._parse_cached.__wrapped__, "cache_info")  # one cache, not two
    assert mathtext.MathTextParser._parse_cached.cache_info().maxsize == batch.MATHTEXT_CACHE
    parser = mathtext.MathTextParser("path")
    labels = [f"$x_{{{i}}}$" for i in range(200)]
    for s in labels + labels:
        parser.parse(s, 72, FontProperties(size=10))
    assert mathtext.MathTextParser._parse_cached.cache_info().hits >= len(labels)
    after = parser.parse(r"$\omega_{2}$", 72, FontProperties(size=10))
    assert (after.width, after.height, after.depth) == (before.width, before.height, before.depth)
