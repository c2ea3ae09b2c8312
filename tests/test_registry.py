"""The explicit registry of task kinds: no monkey-patching of Study, no import circle, one table
that export, check and the note iterate over."""
import ast
from pathlib import Path

import pytest

from reportgen import load_case
from reportgen.case.load import TOP_KEYS
from reportgen.errors import CaseError
from reportgen.registry import KINDS, LINKAGE_SECTIONS

PKG = Path(__file__).resolve().parents[1] / "reportgen"
CASES = Path(__file__).resolve().parents[1] / "cases"


def test_every_kind_is_a_case_section_and_a_report_section():
    from reportgen.report.assemble import SECTIONS
    for k in KINDS:
        assert k.section in TOP_KEYS
        assert k.name in SECTIONS
        mod = SECTIONS[k.name][0]
        assert callable(mod.build) and callable(mod.present) and hasattr(mod, "NEEDS")


def test_no_setattr_on_study_and_no_import_back():
    for path in (PKG / "analysis").glob("*.py"):
        text = path.read_text(encoding="utf-8")
        assert "setattr(Study" not in text and "_HOOKS" not in text, path
        assert not any(isinstance(n, ast.Assign) and any(isinstance(t, ast.Attribute) and getattr(t.value, "id", "") == "Study"
                                                         for t in n.targets) for n in ast.walk(ast.parse(text))), path
    tree = ast.parse((PKG / "analysis" / "study.py").read_text(encoding="utf-8"))
    imported = {a.name for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) for a in n.names}
    for k in KINDS:
        assert k.analysis.split(":")[0] not in imported


def test_analyses_created_by_name_and_recorded():
    s = load_case(CASES / "ws000_six_bar.toml")
    assert s.tasks() == ["dynamics", "forces"]
    assert "dynamics" not in s.computed
    d = s.dynamics
    assert s.analysis("dynamics") is d and "dynamics" in s.computed
    assert set(d.tables()) >= {"dynamics", "motion"}
    with pytest.raises(AttributeError):
        s.no_such_analysis


def test_linkage_sections_all_or_none(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text('[frame]\npoints = {O = [0, 0]}\n', encoding="utf-8")
    with pytest.raises(CaseError) as e:
        load_case(p)
    assert any(k in str(e.value) for k in LINKAGE_SECTIONS)
