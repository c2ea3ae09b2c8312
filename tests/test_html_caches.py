"""What the HTML stage keeps between renders and between processes changes no byte of the note.

The caches of reportgen/report/render.py and formulas.py (bench/bench_html.py measures what
they save): the subset fonts of the screen HTML and the faces' code points (``<cache>/fonts``),
the formulas typeset as HTML (``<cache>/mathhtml``), the text nodes fixed by the typography
(in the process), the print views cut again at other split points instead of being built again.
Each is compared here with the same thing computed afresh.
"""
import json

import pytest

from conftest import ROOT
from reportgen.report import formulas, mathhtml, render
from reportgen.report.demo import build_demo_report
from reportgen.style import fonts


@pytest.fixture
def cache(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv("REPORTGEN_CACHE", str(folder))
    formulas._typeset.cache_clear()
    render._WOFF_MEMO.clear()
    render._CMAP_MEMO.clear()
    render._font_css.cache_clear()
    yield folder
    formulas._typeset.cache_clear()
    render._WOFF_MEMO.clear()
    render._CMAP_MEMO.clear()
    render._font_css.cache_clear()


def test_typeset_formulas_from_the_cache_equal_the_converted(cache):
    corpus = json.loads((ROOT / "tests" / "data" / "formulas_of_cases.json").read_text(encoding="utf-8"))
    items = [(f["tex"], not f["inline"]) for f in corpus]
    first = [formulas._typeset(tex, display) for tex, display in items]   # converted and stored
    assert len(list((cache / "mathhtml").rglob("*.json"))) == len(set(items))
    formulas._typeset.cache_clear()
    again = [formulas._typeset(tex, display) for tex, display in items]   # read back
    for (tex, display), a, b in zip(items, first, again):
        fresh = mathhtml.convert(tex, display)
        assert a == b == fresh, tex
        assert str(b.img("math")) == str(fresh.img("math"))


def test_a_damaged_formula_entry_is_converted_again(cache):
    tex = r"\omega_1 = \frac{\pi n_1}{30}"
    fresh = formulas._typeset(tex, True)
    for f in (cache / "mathhtml").rglob("*.json"):
        f.write_text('{"tex": 1}', encoding="utf-8")
    formulas._typeset.cache_clear()
    assert formulas._typeset(tex, True) == fresh == mathhtml.convert(tex, True)


def test_cached_font_subset_and_code_points_equal_the_computed(cache):
    face = fonts.find_serif().italic
    first = render._embedded_woff(face)
    assert render._is_woff(first) and first == fonts._subset_woff(face)
    render._WOFF_MEMO.clear()
    assert render._embedded_woff(face) == first           # read back
    (stored,) = (cache / "fonts").glob("*.woff")
    stored.write_bytes(first[:-7])                        # a cut file is subset again
    render._WOFF_MEMO.clear()
    assert render._embedded_woff(face) == first
    for path in (face, fonts.find_serif().regular):
        assert render._font_cmap(path) == fonts._cmap(path)
        render._CMAP_MEMO.clear()
        assert render._font_cmap(path) == fonts._cmap(path)


def test_screen_html_with_the_caches_equals_the_one_without(cache, monkeypatch):
    report = build_demo_report(12)
    filled = render.render_html(report, for_print=False)  # fills the cache folder
    render._WOFF_MEMO.clear()
    render._CMAP_MEMO.clear()
    render._font_css.cache_clear()
    formulas._typeset.cache_clear()
    render._FIXED_TEXT.clear()
    assert render.render_html(report, for_print=False) == filled   # from the cache folder
    monkeypatch.setenv("REPORTGEN_CACHE", "off")
    render._WOFF_MEMO.clear()
    render._font_css.cache_clear()
    formulas._typeset.cache_clear()
    render._FIXED_TEXT.clear()
    assert render.render_html(report, for_print=False) == filled   # no cache at all


def test_views_cut_again_equal_views_built_with_the_split_points():
    report = build_demo_report(60)
    views = render._views(report, for_print=True, splits={})
    bare = views.html()
    rows = views.builder.tables
    assert any(n > 20 for n in rows.values())
    for splits in ({t: [10, 25] for t, n in rows.items() if n > 30},
                   {t: [0] for t in rows},
                   {}):
        views.builder.resplit(splits)
        assert views.html() == render._views(report, for_print=True, splits=splits).html()
    assert views.html() == bare


def test_typography_memo_and_shortcut_change_nothing(monkeypatch):
    report = build_demo_report(12)
    views = render._views(report, for_print=False)
    seen = []
    monkeypatch.setattr(render, "_typography", lambda h: seen.append(h) or h)
    views.html()
    monkeypatch.undo()
    (html,) = seen
    render._FIXED_TEXT.clear()
    first = render._typography(html)
    assert first != html and 'class="nobr"' in first             # (the fixes apply to this note)
    assert render._typography(html) == first                  # from the memo
    render._FIXED_TEXT.clear()
    monkeypatch.setattr(render, "_FIXABLE", __import__("re").compile(""))   # every node through every fix
    assert render._typography(html) == first
    render._FIXED_TEXT.clear()


def test_cells_shared_by_the_print_and_screen_views_change_nothing():
    report = build_demo_report(30)
    alone = [render.render_html(report, for_print=p) for p in (True, False)]
    with render._build_scope():
        shared = [render.render_html(report, for_print=p) for p in (True, False)]
        assert render._SHARED_CELLS                               # (the cells were shared)
    assert render._SHARED_CELLS is None
    assert shared == alone


def test_warm_caches_fills_the_cache_folder_with_what_a_build_reads(cache, monkeypatch):
    monkeypatch.setattr(render, "_ENV", None)   # (the templates' environment is made once a process)
    render.warm_caches()
    assert len(list((cache / "fonts").glob("*.woff"))) >= 4
    assert len(list((cache / "fonts").glob("*.cmap.json"))) >= 1
    assert list((cache / "jinja").iterdir())
    family = fonts.find_serif()
    render._WOFF_MEMO.clear()
    render._font_css.cache_clear()
    assert render._font_css(family, True) == fonts.font_face_css(family, embed=True)   # read back
    monkeypatch.setenv("REPORTGEN_CACHE", "off")
    render.warm_caches()                                        # nothing to fill


def test_a_read_only_cache_folder_does_not_fail_the_html(cache, monkeypatch):
    import os
    import stat

    if os.geteuid() == 0:   # (root writes into a read-only folder anyway: the write is made to fail)
        monkeypatch.setattr(render, "_atomic_write", lambda *a: (_ for _ in ()).throw(PermissionError()))
        monkeypatch.setattr("tempfile.NamedTemporaryFile", lambda *a, **k: (_ for _ in ()).throw(PermissionError()))
    for sub in ("fonts", "jinja", "mathhtml"):
        (cache / sub).mkdir(parents=True)
        (cache / sub).chmod(stat.S_IRUSR | stat.S_IXUSR)
    monkeypatch.setattr(render, "_ENV", None)
    try:
        html = render.render_html(build_demo_report(5), for_print=False)
    finally:
        for sub in ("fonts", "jinja", "mathhtml"):
            (cache / sub).chmod(stat.S_IRWXU)
    assert html.startswith("<!DOCTYPE html>")
