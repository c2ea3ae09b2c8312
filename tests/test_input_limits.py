"""Limits on what a case may hold: every example of issue 8 ends in one Russian message and
exit code 2 (never a traceback, never exit 3), or in a result without NaN/inf."""
from __future__ import annotations

import math
import subprocess
import sys

import pandas as pd
import pytest

from conftest import CASES, ROOT
from reportgen.case.text import meta_value
from reportgen.cli import main
from reportgen.errors import CaseError

BASE = (CASES / "ws000_six_bar.toml").read_text(encoding="utf-8")
SLIDER = (CASES / "slider_crank.toml").read_text(encoding="utf-8")


def run(tmp_path, capsys, text, *args, cmd="check", name="case.toml"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    rc = main([cmd, str(p), *args])
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return rc, out.err


def edit(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


# ------------------------------------------------------------------ non-finite and out of range

@pytest.mark.parametrize("old,new,needles", [
    ("positions = 12", "positions = 12\nstart = inf", ["grid.start", "конечн"]),
    ("positions = 12", "positions = 12\nstart = nan", ["grid.start", "конечн"]),
    ('C = ["X_C", "Y_C"]', 'C = [1.797e308, "Y_C"]', ["frame.points.C[0]", "диапазон"]),
    ('J_S = "0.45 kg*m^2"', "J_S = inf", ["links[1].J_S", "конечн"]),
    ('J_S = "0.45 kg*m^2"', 'J_S = "1e400 kg*m^2"', ["links[1].J_S"]),
    ('mass = "9 kg"', 'mass = "1e300 kg*1e300"', ["links[1].mass"]),
    ('l_OA = "0.347 m"', 'l_OA = "1e308 m"', ["l_OA"]),
    ("delta = 0.11", "delta = 1e-300", ["dynamics.delta"]),
])
def test_non_finite_and_absurd_values_are_rejected(tmp_path, capsys, old, new, needles):
    rc, err = run(tmp_path, capsys, edit(BASE, old, new))
    assert rc == 2, err
    for n in needles:
        assert n in err, (n, err)


@pytest.mark.parametrize("old,new", [
    ('n = "65 rpm"', 'n = "1e9 rpm"'),
    ('J_S = "0.45 kg*m^2"', 'J_S = "1e14 kg*m^2"'),
    ('mass = "22 kg"', 'mass = "1e8 kg"'),
])
def test_extreme_but_allowed_values_give_finite_exports_or_a_clear_error(tmp_path, capsys, old, new):
    rc, err = run(tmp_path, capsys, edit(BASE, old, new), "-o", str(tmp_path / "out"), cmd="export")
    assert rc in (0, 2), err
    if rc == 0:
        for f in (tmp_path / "out").glob("*.csv"):
            num = pd.read_csv(f).select_dtypes("number")
            if f.stem != "links":  # a link without a mass has a blank mass
                assert num.apply(lambda c: c.map(math.isfinite)).all().all(), f
        text = (tmp_path / "out" / "scalars.json").read_text(encoding="utf-8")
        assert "null" not in text and "NaN" not in text and "Infinity" not in text


# ------------------------------------------------------------------ grid sizes

@pytest.mark.parametrize("old,new,key", [
    ("positions = 12", "positions = 100000000", "grid.positions"),
    ("positions = 12", "positions = 12\ncycle_points = 1000000000", "grid.cycle_points"),
    ('extra = [{ q = "99.1 deg", label = "f" }]', "extra = [" + ", ".join(["1"] * 1000) + "]", "grid.extra"),
])
def test_grid_sizes_are_bounded(tmp_path, capsys, old, new, key):
    rc, err = run(tmp_path, capsys, edit(BASE, old, new))
    assert rc == 2 and key in err


# ------------------------------------------------------------------ nesting

def test_deeply_nested_toml(tmp_path, capsys):
    rc, err = run(tmp_path, capsys, BASE + "\n[report]\noptions = { x = " + "[" * 3000 + "]" * 3000 + " }\n")
    assert rc == 2 and ("вложенность" in err or "TOML" in err)


def test_nested_toml_below_the_parser_limit(tmp_path, capsys):
    rc, err = run(tmp_path, capsys, BASE + "\nbogus = " + "[" * 40 + "]" * 40 + "\n")
    assert rc == 2 and "вложенность" in err


@pytest.mark.parametrize("expr", ["(" * 200 + "0.347" + ")" * 200 + " * 1 m",
                                  "0.3 m" + " + 0 m" * 1500,
                                  "-" * 1500 + "0.347 m"])
def test_deeply_nested_expressions(tmp_path, capsys, expr):
    rc, err = run(tmp_path, capsys, edit(BASE, 'l_OA = "0.347 m"', f'l_OA = "{expr}"'))
    assert rc == 2 and "parameters.l_OA" in err
    assert len(err) < 1500  # the 1500-character input is not repeated in full


# ------------------------------------------------------------------ meta

@pytest.mark.parametrize("value,needle", [
    ("['Е. Е.', 'Фёдорова']", "meta.university"),
    ("{ a = 1 }", "meta.university"),
    ("nan", "meta.university"),
    ("true", "meta.university"),
    ('"' + "Ж" * 20000 + '"', "meta.university"),
])
def test_meta_values_must_be_strings(tmp_path, capsys, value, needle):
    text = edit(BASE, 'university = "Технический университет"', f"university = {value}")
    rc, err = run(tmp_path, capsys, text)
    assert rc == 2 and needle in err, err
    assert "Фёдорова']" not in err.split("получено")[0]
    assert len(err) < 1200


def test_meta_scalars_are_plain_text_and_long_words_are_broken():
    assert meta_value(2024, file=None, key="meta.year") == "2024"
    assert meta_value(2024.0, file=None, key="meta.year") == "2024"
    long = meta_value("Ж" * 400, file=None, key="meta.topic")
    assert long.replace("\u200b", "") == "Ж" * 400
    assert max(len(w) for w in long.split("\u200b")) <= 80
    with pytest.raises(CaseError):
        meta_value(float("nan"), file=None, key="meta.year")


# ------------------------------------------------------------------ names

def test_frame_point_with_the_name_of_a_moving_point(tmp_path, capsys):
    # ws000 with H added to [frame] points: the slider's H would silently become fixed
    rc, err = run(tmp_path, capsys, edit(BASE, 'C = ["X_C", "Y_C"] }', 'C = ["X_C", "Y_C"], H = ["1 m", "1 m"] }'))
    assert rc == 2
    assert "«H»" in err and "[frame] points.H" in err and "links[3].points.H" in err


@pytest.mark.parametrize("old,new,key", [
    ("A = [0, 0], S2", 'A = [0, 0], "M<svg onload=alert(1)>" = [0, 0], S2', "links[1].points"),
    ('name = "2"', 'name = "2<b>"', "links[1].name"),
    ('label = "f"', 'label = "f<script>"', "grid.extra[0].label"),
    ('label = "f"', 'label = "' + "f" * 60 + '"', "grid.extra[0].label"),
])
def test_unsafe_names_are_rejected(tmp_path, capsys, old, new, key):
    rc, err = run(tmp_path, capsys, edit(BASE, old, new))
    assert rc == 2 and key in err and "недопустимое" in err, err


def test_names_with_primes_greek_and_cyrillic_are_accepted():
    from reportgen.case.text import check_name
    for n in ["A", "B′", "C''", "S_2", "Ж", "φ1", "K-1", "D.1", "7"]:
        assert check_name(n, file=None, key="k") == n


# ------------------------------------------------------------------ error messages

def test_error_messages_truncate_long_inputs(tmp_path, capsys):
    junk = "q" * 60000
    rc, err = run(tmp_path, capsys, edit(BASE, 'direction = "cw"', f'direction = "{junk}"'))
    assert rc == 2 and len(err) < 2000


# ------------------------------------------------------------------ paths and files

def test_directory_or_device_as_the_case(capsys):
    for path in [str(CASES), "/dev/null"]:
        assert main(["check", path]) == 2
        err = capsys.readouterr().err
        assert "не обычный файл" in err and "Traceback" not in err


def test_missing_case(tmp_path, capsys):
    assert main(["check", str(tmp_path / "nope.toml")]) == 2
    assert "не найден" in capsys.readouterr().err


def test_not_utf8_case(tmp_path, capsys):
    p = tmp_path / "c.toml"
    p.write_bytes(b"# \xcf\xf0\xe8\xe2\xe5\xf2\n" + BASE.encode("utf-8"))  # a cp1251 comment
    assert main(["check", str(p)]) == 2
    assert "UTF-8" in capsys.readouterr().err


def test_output_below_a_file(tmp_path, capsys):
    f = tmp_path / "file"
    f.write_text("x")
    for cmd in (["export", str(CASES / "four_bar.toml"), "-o", str(f / "sub")],
                ["export", str(CASES / "four_bar.toml"), "-o", str(f)],
                ["build", str(CASES / "four_bar.toml"), "-o", str(f / "sub")]):
        assert main(cmd) == 2
        err = capsys.readouterr().err
        assert "-o" in err and "Traceback" not in err


@pytest.mark.parametrize("target", ["dir", "/dev/null"])
def test_compare_pointing_at_a_directory_or_a_device(tmp_path, capsys, target):
    path = str(tmp_path) if target == "dir" else target
    text = edit(BASE, "[dynamics.printed]", f'[dynamics.compare]\ncase = "{path}"\n\n[dynamics.printed]')
    rc, err = run(tmp_path, capsys, text)
    assert rc == 2 and "dynamics.compare.case" in err


@pytest.mark.parametrize("options,key", [
    ('{ font_size_pt = "14pt; } </style><script>alert(1)</script>" }', "font_size_pt"),
    ('{ font = "Comic Nonexistent" }', "font"),
    ('{ toc_depth = "2" }', "toc_depth"),
    ('{ margin_left_mm = 1e9 }', "margin_left_mm"),
    ('{ dash = "url(http://127.0.0.1:9/x)" }', "dash"),
    ('{ eskd_frame = "yes" }', "eskd_frame"),
])
def test_report_options_of_the_wrong_type(tmp_path, capsys, options, key):
    text = SLIDER + f"\n[report]\noptions = {options}\n"
    rc, err = run(tmp_path, capsys, text, "-o", str(tmp_path / "out"), "--format", "html",
                  "--sections", "structure", cmd="build")
    assert rc == 2 and f"report.options.{key}" in err, err
    assert not (tmp_path / "out" / "case.html").exists()


def test_runtime_warnings_never_reach_stderr(tmp_path):
    code = ("import sys, numpy as np\n"
            "from reportgen import cli\n"
            "def noisy(args):\n"
            "    np.log(np.zeros(3)); np.divide(np.zeros(2), np.zeros(2))\n"
            "    return 0\n"
            "cli.cmd_check = noisy\n"
            f"sys.exit(cli.main(['check', {str(CASES / 'four_bar.toml')!r}]))\n")
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "Warning" not in r.stderr and r.stderr == ""


# ------------------------------------------------------------------ outputs replaced together

def test_pdf_and_html_are_replaced_together_and_stale_temps_removed(tmp_path):
    from reportgen.report.safety import write_together
    out = tmp_path / "o"
    out.mkdir()
    (out / "v.pdf").write_text("old pdf")
    (out / "v.html").write_text("old html")
    stale = out / ".v.pdf.abc123.tmp"  # left by a killed run
    stale.write_text("x" * 1000)

    def fail(path):
        raise OSError("disk full")

    with pytest.raises(OSError):
        write_together(out, "v", {"pdf": lambda p: p.write_text("new pdf"), "html": fail})
    assert (out / "v.pdf").read_text() == "old pdf" and (out / "v.html").read_text() == "old html"
    assert not stale.exists()
    assert sorted(p.name for p in out.iterdir()) == ["v.html", "v.pdf"]  # no temporary left
    paths = write_together(out, "v", {"pdf": lambda p: p.write_text("new pdf"),
                                      "html": lambda p: p.write_text("new html")})
    assert {k: v.read_text() for k, v in paths.items()} == {"pdf": "new pdf", "html": "new html"}
    assert sorted(p.name for p in out.iterdir()) == ["v.html", "v.pdf"]


def test_export_refuses_non_finite_results():
    from reportgen.export import check_finite, nonfinite
    tabs = {"cycle": pd.DataFrame({"q": [0.0, 1.0], "x_B": [1.0, math.inf]}),
            "links": pd.DataFrame({"link": ["1"], "mass": [math.nan]})}
    assert nonfinite(tabs, {"a": 1.0, "b": {"c": math.nan}, "d": "text"}) == ["cycle.x_B", "scalars.b.c"]
    with pytest.raises(CaseError, match="cycle.x_B"):
        check_finite(tabs, {})


def test_export_removes_temporaries_of_a_killed_run(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    stale = [out / ".cycle.csv.k1ll3d.tmp", out / ".scalars.json.k1ll3d.tmp", out / ".cycle.csv.old"]
    for p in stale:
        p.write_text("x" * 100)
    assert main(["export", str(CASES / "four_bar.toml"), "-o", str(out)]) == 0
    hidden = sorted(p.name for p in out.iterdir() if p.name.startswith("."))
    assert hidden == [".cycle.csv.old"]  # not a temporary of ours (no .tmp): left alone
