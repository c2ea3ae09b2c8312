"""Batch rendering for a class: every variant, a manifest, failures reported, others go on."""
import csv
import json

from conftest import CASES
from reportgen.batch import read_variants
from reportgen.cli import main


def test_class_of_thirty_variants_with_one_impossible(tmp_path, capsys):
    variants = read_variants(CASES / "class_six_bar.csv", CASES / "ws000_six_bar.toml")
    assert len(variants) == 31
    rc = main(["batch", str(CASES / "class_six_bar.csv"), "--base", str(CASES / "ws000_six_bar.toml"),
               "-o", str(tmp_path), "--format", "html", "--jobs", "2", "--sections", "structure,kinematics"])
    captured = capsys.readouterr()
    assert rc == 1                                   # one variant failed
    m = json.loads((tmp_path / "manifest.json").read_text(encoding="utf-8"))
    assert m["ok"] == 30 and m["failed"] == 1
    bad = [v for v in m["variants"] if not v["ok"]]
    assert bad[0]["variant"] == "31" and "не собирается" in bad[0]["error"] and "(2,3)" in bad[0]["error"]
    assert "вариант 31" in captured.err
    good = [v for v in m["variants"] if v["ok"]]
    assert len({v["input_hash"] for v in good}) == 30
    for v in good:
        assert len(v["files"]) == 1 and v["files"][0].endswith(".html") and v["seconds"] > 0
    html = (tmp_path / "ws000_six_bar_05.html").read_text(encoding="utf-8")
    assert "Смирнов Д. В." in html
    assert not list(tmp_path.glob(".*"))             # no temporary files left


def test_pdf_batch_from_toml_table(tmp_path):
    rc = main(["batch", str(CASES / "class_six_bar.toml"), "-o", str(tmp_path), "--jobs", "1"])
    assert rc == 0
    m = json.loads((tmp_path / "manifest.json").read_text(encoding="utf-8"))
    assert m["ok"] == 2 and {p.split("/")[-1] for v in m["variants"] for p in v["files"]} == {
        "ws000_six_bar_A.pdf", "ws000_six_bar_A.html", "ws000_six_bar_B.pdf", "ws000_six_bar_B.html"}


def test_folder_of_cases_and_bad_table(tmp_path, capsys):
    vs = read_variants(CASES, None)
    assert {"ws000_six_bar", "ws004_slotted_lever"} <= {v.name for v in vs}
    bad = tmp_path / "v.csv"
    bad.write_text("variant,l_OX\n01,0.3 m\n", encoding="utf-8")
    rc = main(["batch", str(bad), "--base", str(CASES / "ws000_six_bar.toml"), "-o", str(tmp_path / "o"), "--jobs", "1"])
    assert rc == 1
    m = json.loads((tmp_path / "o" / "manifest.json").read_text(encoding="utf-8"))
    assert "l_OX" in m["variants"][0]["error"] and "l_OA" in m["variants"][0]["error"]
