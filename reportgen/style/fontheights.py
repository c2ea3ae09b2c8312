"""The font lookups of matplotlib's text layout done once per font instead of once per text.

``Text._get_layout`` (matplotlib 3.10+) sizes every line of every text from its font's vertical
metrics: it finds the font files for the text's ``FontProperties``
(``fontManager._find_fonts_by_props``), opens the font (``get_font``) and reads its ``OS/2`` or
``hhea`` and ``head`` tables (``FT2Font.get_sfnt_table``, a new dict built in C on each call),
for every tick label, legend entry and label of a figure, in each of the layout engine's two
passes, the draw and the label placer's measures. The answers depend only on the font properties
(and the ``font.*`` settings the search reads) and on the font file: here they are kept, so a
figure is laid out and drawn from the same numbers as before, read once per font
(``tests/test_sections_speed.py``).
"""
from __future__ import annotations

from itertools import repeat

import matplotlib

# the settings ``findfont`` reads besides the properties (matplotlib keys its own cache by them)
_FONT_RC = ("font.family", "font.serif", "font.sans-serif", "font.monospace", "font.cursive",
            "font.fantasy")


def rc_values(keys: tuple[str, ...]) -> tuple:
    """The settings ``keys`` of ``matplotlib.rcParams`` as a hashable tuple (lists as tuples).

    Read as ``RcParams._get`` reads them (``dict.__getitem__``): these keys are neither
    deprecated nor the backend, for which alone ``RcParams.__getitem__`` does more; a cache key
    is built from them for every text measured (about 5 000 times per class variant), so the plain
    read matters: one ``map`` over the keys, a third faster than a comprehension calling
    ``dict.__getitem__`` per key."""
    return tuple([tuple(v) if type(v) is list else v
                  for v in map(dict.__getitem__, repeat(matplotlib.rcParams, len(keys)), keys)])


class _Tables:
    """A font's SFNT tables as ``get_sfnt_table`` returns them, each read once."""

    def __init__(self, font):
        self._font = font
        self._tables: dict = {}

    def get_sfnt_table(self, name):
        try:
            return self._tables[name]
        except KeyError:
            t = self._tables[name] = self._font.get_sfnt_table(name)
            return t


class _Lookups:
    """The font manager as ``matplotlib.text`` sees it: ``_find_fonts_by_props`` of a text's
    properties remembered (keyed as matplotlib compares properties, by their hash, with the
    ``font.*`` settings and the number of fonts known); everything else is the manager's."""

    def __init__(self, manager):
        self._manager = manager
        self._found: dict = {}
        self.searches = 0          # real searches made (a test reads it)

    def __getattr__(self, name):
        return getattr(self._manager, name)

    def _find_fonts_by_props(self, prop, *args, **kw):
        if args or kw or not hasattr(prop, "get_family"):
            return self._manager._find_fonts_by_props(prop, *args, **kw)
        key = (hash(prop), rc_values(_FONT_RC), len(self._manager.ttflist))
        found = self._found.get(key)
        if found is None:
            self.searches += 1
            found = self._found[key] = tuple(self._manager._find_fonts_by_props(prop))
        return list(found)


def share_font_heights() -> None:
    """Put the kept lookups into ``matplotlib.text`` (idempotent): its ``fontManager`` and
    ``get_font`` serve only ``Text._get_layout``'s font height metrics."""
    from matplotlib import font_manager
    from matplotlib import text as mtext

    if isinstance(mtext.fontManager, _Lookups):
        return
    get_font = mtext.get_font
    opened: dict = {}

    def layout_font(paths, *args, **kw):
        if args or kw:
            return get_font(paths, *args, **kw)
        key = tuple(paths)
        t = opened.get(key)
        if t is None:
            t = opened[key] = _Tables(get_font(paths))
        return t

    layout_font.__wrapped__ = get_font
    layout_font.opened = opened
    mtext.fontManager = _Lookups(mtext.fontManager if mtext.fontManager is not None else font_manager.fontManager)
    mtext.get_font = layout_font
