"""Bad input: one clear Russian message with file and key, exit code 2, no traceback."""
import pytest

from conftest import CASES
from reportgen.cli import main

BASE = (CASES / "ws000_six_bar.toml").read_text(encoding="utf-8")


def run(tmp_path, capsys, text, name="bad.toml"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    rc = main(["check", str(p)])
    err = capsys.readouterr().err
    return rc, err, str(p)


@pytest.mark.parametrize("old,new,needles", [
    ('mass = "22 kg"', 'mas = "22 kg"', ["links[3].mas", "неизвестный ключ", "mass"]),
    ('mass = "22 kg"', 'mass = "22 m"', ["links[3].mass", "масса", "22 m"]),
    ('l_AB = "1.445 m"', 'l_AB = "1.445 deg"', ["ключ", "длина"]),
    ('points = { O = [0, 0], A = ["l_OA", 0] }', 'points = { O = [0, 0], A = ["l_0A", 0] }',
     ["links[0].points.A", "l_0A", "l_OA"]),
    ('phi0 = "219.1 deg"', 'phi0 = "219.1 dge"', ["driver.phi0", "dge"]),
    ('direction = "cw"', 'direction = "clockwise"', ["driver.direction", "cw", "ccw"]),
    ('links = ["3", "4"]\npoint = "D"', 'links = ["3", "4"]\npoint = "E"', ["joints[4].point", "«E»"]),
    ('[driver]\ntype = "crank"', '[driver]\ntype = "krank"', ["driver.type", "crank"]),
])
def test_typo_wrong_unit_wrong_name(tmp_path, capsys, old, new, needles):
    assert old in BASE
    rc, err, path = run(tmp_path, capsys, BASE.replace(old, new, 1))
    assert rc == 2
    assert "Traceback" not in err
    assert path in err
    for n in needles:
        assert n in err, (n, err)


def test_missing_section(tmp_path, capsys):
    text = BASE[:BASE.index("[driver]")] + BASE[BASE.index("[grid]"):]
    rc, err, path = run(tmp_path, capsys, text)
    assert rc == 2 and "driver" in err and "обязательный" in err and path in err


def test_toml_syntax(tmp_path, capsys):
    rc, err, path = run(tmp_path, capsys, BASE.replace('l_OA = "0.347 m"', 'l_OA = 0.347 m', 1))
    assert rc == 2 and "TOML" in err and path in err and "Traceback" not in err


def test_missing_file(capsys):
    rc = main(["check", "no/such/case.toml"])
    err = capsys.readouterr().err
    assert rc == 2 and "не найден" in err


def test_impossible_geometry_names_group_and_position(tmp_path, capsys):
    # the coupler is too short to reach the rocker in some positions
    rc, err, _ = run(tmp_path, capsys, BASE.replace('l_AB = "1.445 m"', 'l_AB = "0.7 m"', 1))
    assert rc == 2
    assert "не собирается" in err and "(2,3)" in err and "ВВВ" in err and "в положении q = " in err and " м" in err
    assert "Traceback" not in err


def test_not_a_mechanism(tmp_path, capsys):
    # removing the rocker's pivot leaves W = 3·5 − 2·6 = 3
    text = BASE.replace('[[joints]]\ntype = "R"\nlinks = ["0", "3"]\npoint = "C"\n', "", 1)
    rc, err, _ = run(tmp_path, capsys, text)
    assert rc == 2 and "W = 3·5 − 2·6 = 3" in err and "Чебышев" in err


def test_at_with_wrong_unit(tmp_path, capsys):
    rc = main(["export", str(CASES / "ws000_six_bar.toml"), "-o", str(tmp_path / "x"), "--at", "99.1 m"])
    err = capsys.readouterr().err
    assert rc == 2 and "--at" in err and "угол" in err
    assert not (tmp_path / "x").exists()


def test_unknown_report_option(tmp_path, capsys):
    text = BASE + '\n[report]\noptions = { figure_wrd = "Рис." }\n'
    p = tmp_path / "opt.toml"
    p.write_text(text, encoding="utf-8")
    rc = main(["build", str(p), "-o", str(tmp_path / "out"), "--format", "html"])
    err = capsys.readouterr().err
    assert rc == 2 and "report.options.figure_wrd" in err and "figure_word" in err
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


import pytest  # noqa: E402


@pytest.mark.parametrize("report, key", [
    ('options = { figure_wrd = "Рис." }', "report.options.figure_wrd"),
    ('options = { font_size_pt = 200 }', "report.options.font_size_pt"),
    ('sections = ["kinematic"]', "report.sections"),
    ('sections = []', "report.sections"),
    ('sectons = ["dof"]', "report.sectons"),
])
def test_check_rejects_a_bad_report_section_as_build_does(tmp_path, capsys, report, key):
    """``check`` validates ``[report]`` exactly as ``build`` reads it: same exit code, same key."""
    p = tmp_path / "rep.toml"
    p.write_text(BASE + f"\n[report]\n{report}\n", encoding="utf-8")
    errs = []
    for argv in (["check", str(p)], ["build", str(p), "-o", str(tmp_path / "out"), "--format", "html"]):
        rc = main(argv)
        err = capsys.readouterr().err
        assert rc == 2 and key in err and "Traceback" not in err, (argv[0], err)
        errs.append(err)
    assert errs[0] == errs[1]
