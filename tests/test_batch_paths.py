"""Batch outputs stay inside -o; a broken table or row is one Russian message against the row."""
from __future__ import annotations

import json

import pytest

from conftest import CASES
from reportgen.batch import Variant, read_variants, run_variant, safe_stem
from reportgen.cli import main
from reportgen.errors import CaseError

BASE = CASES / "ws000_six_bar.toml"


@pytest.mark.parametrize("name,stem", [
    ("sub/../../../x", "sub_.._.._.._x"),
    ("../../etc/passwd", "_.._etc_passwd"),
    ("/abs/path", "_abs_path"),
    ("..", "_"),
    (".hidden", "hidden"),
    ("a\\b", "a_b"),
    ("нормальное имя 01", "нормальное_имя_01"),
    ("x" * 500, "x" * 80),
    ("C:\\win", "C_win"),
    ("a\x00b", "a_b"),
])
def test_safe_stem(name, stem):
    assert safe_stem(name) == stem
    assert "/" not in stem and "\\" not in stem and not stem.startswith(".")


def _csv(tmp_path, text: str, name="v.csv"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_variant_names_never_lead_outside_the_output(tmp_path):
    out = tmp_path / "deep" / "out"
    p = _csv(tmp_path, "variant,l_OA\nsub/../../../x,0.33 m\n/tmp/abs,0.34 m\n")
    vs = read_variants(p, BASE)
    for v in vs:
        target = (out / f"{v.stem}.html").resolve()
        assert target.parent == out.resolve()


def test_batch_writes_only_inside_o(tmp_path):
    out = tmp_path / "a" / "b" / "out"
    p = tmp_path / "t.toml"
    p.write_text(f'base = "{BASE}"\n[[variant]]\nname = "sub/../../../x"\nl_OA = "0.33 m"\n', encoding="utf-8")
    rc = main(["batch", str(p), "-o", str(out), "--jobs", "1", "--format", "html", "--sections", "structure"])
    assert rc == 0
    files = sorted(f.relative_to(tmp_path).as_posix() for f in tmp_path.rglob("*") if f.is_file())
    assert files == ["a/b/out/manifest.json", "a/b/out/ws000_six_bar_sub_.._.._.._x.html", "t.toml"]
    m = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    assert m["variants"][0]["variant"] == "sub/../../../x"


def test_two_variants_with_one_file_name_are_an_error(tmp_path):
    p = _csv(tmp_path, "variant,l_OA\na/b,0.33 m\na_b,0.34 m\n")
    with pytest.raises(CaseError, match="одно имя файла"):
        read_variants(p, BASE)
    p = _csv(tmp_path, "variant,l_OA\nA,0.33 m\na,0.34 m\n", "w.csv")  # case-insensitive file systems
    with pytest.raises(CaseError, match="одно имя файла"):
        read_variants(p, BASE)


@pytest.mark.parametrize("text,needle", [
    ('base = 5\n[[variant]]\nname = "A"\n', "base"),
    ('base = ["a.toml"]\n[[variant]]\nname = "A"\n', "base"),
    (f'base = "{BASE}"\nvariant = [1, 2]\n', "variant[0]"),
    (f'base = "{BASE}"\nvariant = "A"\n', "variant"),
    (f'base = "{BASE}"\n[[variant]]\nname = ["A"]\n', "variant[0].name"),
    (f'base = "{BASE}"\n[[variant]]\nname = "A"\nl_OA = ["0.3 m"]\n', "variant[0].l_OA"),
    (f'base = "{BASE}"\n[[variant]]\nname = "A"\nl_OA = inf\n', "variant[0].l_OA"),
    (f'base = "{BASE}"\n[[variant]]\nname = "A"\nstudent = ["Е. Е.", "Фёдорова"]\n', "variant[0].student"),
    ('base = "nope.toml"\n[[variant]]\nname = "A"\n', "base"),
    (f'base = "{CASES}"\n[[variant]]\nname = "A"\n', "base"),
    ("[[variant]\n", "TOML"),
])
def test_bad_toml_tables(tmp_path, capsys, text, needle):
    p = tmp_path / "t.toml"
    p.write_text(text, encoding="utf-8")
    rc = main(["batch", str(p), "-o", str(tmp_path / "o"), "--jobs", "1"])
    err = capsys.readouterr().err
    assert rc == 2 and needle in err and "Traceback" not in err, err
    assert not (tmp_path / "o" / "manifest.json").exists()


def test_non_utf8_csv(tmp_path, capsys):
    p = tmp_path / "v.csv"
    p.write_bytes("variant,student\n01,Иванов\n".encode("cp1251"))
    rc = main(["batch", str(p), "--base", str(BASE), "-o", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert rc == 2 and "UTF-8" in err and "Traceback" not in err


def test_csv_with_a_bom_and_a_ragged_row(tmp_path, capsys):
    p = tmp_path / "v.csv"
    p.write_bytes("\ufeffvariant,l_OA\n01,0.33 m\n".encode("utf-8"))
    assert [v.name for v in read_variants(p, BASE)] == ["01"]
    p.write_text("variant,l_OA\n01,0.33 m,extra\n", encoding="utf-8")
    with pytest.raises(CaseError, match="строка 2"):
        read_variants(p, BASE)


@pytest.mark.parametrize("path", ["/dev/null", "dir"])
def test_table_that_is_a_device_or_an_empty_folder(tmp_path, capsys, path):
    target = "/dev/null" if path == "/dev/null" else str(tmp_path)
    rc = main(["batch", target, "--base", str(BASE), "-o", str(tmp_path / "o")])
    assert rc == 2 and "Traceback" not in capsys.readouterr().err


def test_a_bad_value_is_reported_against_its_row(tmp_path):
    p = _csv(tmp_path, "variant,l_OA,l_AB\n01,0.33 m,1.4 m\n02,0.33 kg,1.4 m\n03,0.33 m,(((\n")
    vs = read_variants(p, BASE)
    outcomes = [run_variant(v, str(tmp_path / "o"), ("html",), ["structure"]) for v in vs[1:]]
    for o, line, key in zip(outcomes, ("строка 3", "строка 4"), ("l_OA", "l_AB")):
        assert not o.ok
        assert o.error.startswith(f"{p}: ключ {line}.{key}"), o.error
        assert o.error.count(str(p)) == 1


def test_an_unknown_parameter_is_reported_against_the_table(tmp_path):
    p = _csv(tmp_path, "variant,l_OX\n01,0.3 m\n")
    o = run_variant(read_variants(p, BASE)[0], str(tmp_path / "o"), ("html",), ["structure"])
    assert not o.ok and o.error.startswith(f"{p}: ключ строка 2.l_OX") and "l_OA" in o.error


def test_variant_names_in_folder_mode_are_safe(tmp_path):
    d = tmp_path / "cases"
    d.mkdir()
    (d / "a b.toml").write_bytes(BASE.read_bytes())
    (d / "a_b.toml").write_bytes(BASE.read_bytes())
    with pytest.raises(CaseError, match="одно имя файла"):
        read_variants(d, None)


def test_stem_of_a_variant_keeps_the_base_name():
    v = Variant("A", BASE, {"l_OA": "0.3 m"}, {"variant": "A"})
    from reportgen.batch import _stem
    assert safe_stem(_stem(v)) == "ws000_six_bar_A"
