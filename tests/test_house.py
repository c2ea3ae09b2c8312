"""Code health of the package, read from its source (ast), nothing run.

The import direction of DESIGN.md «What flows through it»: core ← mechanism ← analysis ← scenes ←
report ← cli.  Every import of every module (top-level, inside a function, under TYPE_CHECKING, and
``importlib.import_module`` with a static prefix) must point to its own unit or to a lower layer.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

from conftest import ROOT

PKG = ROOT / "reportgen"

# Lowest first.  A unit (sub-package or top-level module of reportgen) may import only units of a
# lower row; units of one row do not import each other.
LAYERS: tuple[tuple[str, ...], ...] = (
    ("errors", "registry"),   # the one error type; the task kinds as pure data
    ("core", "style"),        # numba kernels; number format, plot style, font metrics
    ("case",),                # the case file read into SI values
    ("mechanism",),           # links, joints, Assur groups
    ("analysis",),            # the Study and its task analyses
    ("scenes",),              # drawings of the Study
    ("report",),              # the note, the answer key, HTML and PDF
    ("export", "warmup"),     # CSV exports; the numba/font warm-up
    ("sheets",),              # drawing sheets A1
    ("batch",),               # many variants
    ("cli",),                 # the command line
)
RANK = {unit: i for i, row in enumerate(LAYERS) for unit in row}


def _module_name(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _package_of(path: Path) -> str:
    name = _module_name(path)
    return name if path.name == "__init__.py" else name.rpartition(".")[0]


def _resolve(package: str, level: int, module: str | None) -> str:
    """The absolute name of ``from <level dots><module> import …`` written in ``package``."""
    if not level:
        return module or ""
    base = package.split(".")
    base = base[: len(base) - level + 1]
    return ".".join(base + ([module] if module else []))


def _static_prefix(node: ast.expr) -> str | None:
    """The text of a module-name argument up to its first formatted field, with ``{__package__}``
    kept as a marker; None when the argument is not a string literal or an f-string."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr):
        out = []
        for v in node.values:
            if isinstance(v, ast.Constant):
                out.append(v.value)
            elif isinstance(v.value, ast.Name) and v.value.id == "__package__" and not out:
                out.append("{__package__}")
            else:
                break
        return "".join(out)
    return None


def imported_modules(source: str, package: str) -> list[tuple[int, str]]:
    """(line, absolute module name) of every import in ``source`` of a module in ``package``."""
    found: list[tuple[int, str]] = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(package, node.level, node.module)
            if node.module:
                found.append((node.lineno, base))
            else:    # from . import x: each name may be a module
                found += [(node.lineno, f"{base}.{a.name}") for a in node.names]
        elif (isinstance(node, ast.Call) and node.args
              and isinstance(node.func, ast.Attribute) and node.func.attr == "import_module"):
            text = _static_prefix(node.args[0])
            if text is None:
                continue
            if text.startswith("{__package__}"):
                text = package + text[len("{__package__}"):]
            elif text.startswith(".") and len(node.args) > 1 and getattr(node.args[1], "id", "") == "__package__":
                dots = len(text) - len(text.lstrip("."))
                text = _resolve(package, dots, text.lstrip(".") or None)
            found.append((node.lineno, text.rstrip(".")))
    return found


def _unit(module: str) -> str | None:
    parts = module.split(".")
    if parts[0] != "reportgen":
        return None
    return parts[1] if len(parts) > 1 else "reportgen"


def layer_violations(path: Path, source: str | None = None) -> list[str]:
    """Imports in the module at ``path`` that point to a unit of the same or a higher row of LAYERS."""
    own = _unit(_module_name(path))
    if own == "reportgen":      # the package's own __init__: a lazy facade over the Study (PEP 562)
        return []
    if source is None:
        source = path.read_text(encoding="utf-8")
    bad = []
    for line, target in imported_modules(source, _package_of(path)):
        unit = _unit(target)
        if unit is None or unit == own:
            continue
        if unit not in RANK or RANK[unit] >= RANK[own]:
            bad.append(f"{path.relative_to(ROOT)}:{line} ({own}) imports {target} ({unit})")
    return bad


def _units_on_disk() -> set[str]:
    return {p.stem if p.is_file() else p.name for p in PKG.iterdir()
            if (p.is_file() and p.suffix == ".py" and p.stem != "__init__")
            or (p.is_dir() and (p / "__init__.py").exists())}


def test_every_unit_has_a_layer():
    """A new sub-package or top-level module must be placed in LAYERS before it may import anything."""
    assert _units_on_disk() - set(RANK) == set()
    assert set(RANK) - _units_on_disk() == set(), "LAYERS names a unit that is gone"


def test_imports_point_down_the_layers():
    bad = [v for path in sorted(PKG.rglob("*.py")) for v in layer_violations(path)]
    assert bad == []


@pytest.mark.parametrize("where, source", [
    ("core/kinematics.py", "from ..analysis import study\n"),
    ("core/kinematics.py", "def f():\n    from reportgen.report import render\n"),
    ("analysis/cam.py", "import reportgen.scenes.cam\n"),
    ("scenes/cam.py", "from .. import report\n"),
    ("core/cams.py", "from ..style import numbers\n"),          # same row: core and style
    ("mechanism/build.py", "import importlib\nimportlib.import_module(f'reportgen.analysis.{m}')\n"),
    ("analysis/study.py", "import importlib\nimportlib.import_module(f'{__package__}.x', 'reportgen.report.x')\n"
                          "importlib.import_module('..report.key', __package__)\n"),
])
def test_the_checker_sees_an_upward_import(where, source):
    assert layer_violations(PKG / where, source)


@pytest.mark.parametrize("where, source", [
    ("report/key.py", "import importlib\nimportlib.import_module(f'.sections.{k}', __package__)\n"),
    ("analysis/study.py", "import importlib\nimportlib.import_module(f'{__package__}.{module}')\n"),
    ("scenes/cam.py", "from ..core import cams\nfrom ..analysis.cam import Cam\nimport numpy\n"),
])
def test_the_checker_lets_downward_imports_pass(where, source):
    assert layer_violations(PKG / where, source) == []


def test_dense_solvers_share_their_pivoting_and_agree_with_numpy():
    """core/linalg.py: solve_dense and lu_factor/lu_solve (one pivot search, one row norm, one back
    substitution) solve the same systems as numpy, and flag a singular one with 0.0."""
    import numpy as np

    from reportgen.core.linalg import lu_factor, lu_solve, solve_dense

    rng = np.random.default_rng(12)
    for n in (2, 3, 6, 9):
        a = rng.normal(size=(n, n))
        a[0, :] *= 1e-3                     # a small first pivot: rows must be interchanged
        b = rng.normal(size=n)
        x = np.linalg.solve(a, b)
        a1, b1 = a.copy(), b.copy()
        q1 = solve_dense(a1, b1, n, 0.0)
        a2, b2, perm = a.copy(), b.copy(), np.zeros(n, np.int64)
        q2 = lu_factor(a2, n, perm)
        lu_solve(a2, perm, b2, n)
        assert q1 > 0.0 and abs(q1 - q2) <= 1e-12 * q1
        assert np.allclose(b1, x, rtol=1e-10, atol=1e-12) and np.allclose(b2, x, rtol=1e-10, atol=1e-12)
        assert perm[0] != 0
    sing = np.array([[1.0, 2.0], [2.0, 4.0]])
    assert solve_dense(sing.copy(), np.ones(2), 2, 1e-12) == 0.0
    assert lu_factor(sing.copy(), 2, np.zeros(2, np.int64)) == 0.0
    assert solve_dense(np.zeros((3, 3)), np.ones(3), 3, 0.0) == 0.0


def test_quantity_operators_coerce_once_both_ways():
    """case/expr.py: every arithmetic operator of Q and its reflected twin (``2 * q``, ``1 / q``,
    ``2 ** q``) take a plain number as dimensionless and leave anything else to Python."""
    from reportgen.case.expr import Q
    from reportgen.case.units import DIMENSIONLESS, LENGTH
    from reportgen.errors import CaseError

    L = Q(2.0, LENGTH)
    one = Q(4.0, DIMENSIONLESS)
    assert (3 * L).value == 6.0 and (3 * L).dim == LENGTH
    assert (L * 3).value == 6.0
    assert (1 / L).dim == tuple(-d for d in LENGTH) and (1 / L).value == 0.5
    assert (10 - one).value == 6.0 and (one - 10).value == -6.0
    assert (1 + one).value == 5.0 and (2 ** Q(3.0, DIMENSIONLESS)).value == 8.0
    assert (one ** 0.5).value == 2.0
    assert Q.__rmul__.__name__ == "__rmul__" and Q.__add__.__name__ == "__add__"
    with pytest.raises(TypeError):
        L + "1 m"
    with pytest.raises(TypeError):
        "1 m" * L
    with pytest.raises(CaseError):
        1 + L                     # a dimensionless number added to a length
    with pytest.raises(CaseError):
        L / Q(0.0, DIMENSIONLESS)


def _public_without_docstring(root: Path) -> list[str]:
    out = []

    def visit(node, where: str, prefix: str = "") -> None:
        for n in node.body:
            if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and not n.name.startswith("_"):
                if ast.get_docstring(n) is None:
                    out.append(f"{where}:{n.lineno} {prefix}{n.name}")
                if isinstance(n, ast.ClassDef):
                    visit(n, where, prefix + n.name + ".")

    for path in sorted(root.rglob("*.py")):
        visit(ast.parse(path.read_text(encoding="utf-8")), str(path.relative_to(ROOT)))
    return out


@pytest.mark.parametrize("package", ["core", "analysis"])
def test_public_functions_of_the_computing_layers_have_docstrings(package):
    """DESIGN.md: «flat topic modules of pure, documented functions (each docstring names the
    formula and the source it comes from)» — every public function, method and class of core/ and
    analysis/ says what it computes."""
    assert _public_without_docstring(PKG / package) == []
