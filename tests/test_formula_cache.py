"""The on-disk formula cache returns exactly what ziamath renders, and can be switched off."""
from reportgen.report import formulas


def test_disk_cache_roundtrip(tmp_path, monkeypatch):
    tex = r"\omega_1 = \frac{\pi n_1}{30} = 6{,}807\ \text{рад/с}"
    monkeypatch.setenv("REPORTGEN_CACHE", "off")
    formulas.render_latex.cache_clear()
    fresh = formulas.render_latex(tex)
    monkeypatch.setenv("REPORTGEN_CACHE", str(tmp_path))
    formulas.render_latex.cache_clear()
    first = formulas.render_latex(tex)
    files = list(tmp_path.rglob("*.svg"))
    assert len(files) == 1 and files[0].read_text(encoding="utf-8") == fresh[0]
    formulas.render_latex.cache_clear()
    second = formulas.render_latex(tex)       # served from disk
    assert first == fresh == second
    assert not list(tmp_path.rglob("*.tmp"))
    formulas.render_latex.cache_clear()
