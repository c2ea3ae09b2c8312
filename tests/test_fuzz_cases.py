"""Fuzz: case files mutated from the real cases/ (structure and values) give a result or a clear
error, never another exception and never a non-finite number in a table or a scalar.

Each mutant is written as a TOML file and goes the way of ``reportgen export``/``check``:
``Study(path)``, every table and scalar, then the finiteness check of the export. The grid is
coarse (``cycle_points`` small) so ≥ 500 mutants run in a few minutes; hypothesis is
derandomized (the same mutants on every run).
"""
from __future__ import annotations

import copy
import json
import math
import tomllib
import warnings

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import CASES
from reportgen.analysis.study import Study
from reportgen.errors import ReportgenError
from reportgen.export import check_finite, nonfinite, tables

BASES = {p.name: tomllib.loads(p.read_text(encoding="utf-8"))
         for p in sorted(CASES.glob("*.toml")) if p.name != "class_six_bar.toml"}
MUTANTS = 520
CYCLE_POINTS = 120  # coarse cycle: the fuzz checks robustness, not accuracy

def _nested(depth: int):
    v = [1]
    for _ in range(depth):
        v = [v]
    return v


# values a careless user or an attacker writes
POOL = [
    math.inf, -math.inf, math.nan, 0, -1, 1, 0.0, -0.5, 1e308, 1.797e308, 10 ** 18, -10 ** 18, 1e-300,
    "", " ", "abc", "0", "1 m", "-1 m", "1e400 m", "1e308 m*1e308", "0 m", "1/0", "0/0", "sqrt(-1)",
    "l_OA*1e300", "inf", "nan", "99999 km", "1e-30 m", "2 kg", "3 deg", "1 rad/s", "'", "\"",
    "(" * 80 + "1" + ")" * 80, "1" + "+1" * 1200, "-" * 1500 + "1", "x" * 5000,
    "<script>alert(1)</script>", "M<svg onload=alert(1)>", "sub/../../x", "\x00", "Ё", "A", "0", "1",
    True, False, [], [1, 2], [1, 2, 3], ["1 m", "2 m"], {}, {"a": 1}, {"r": "1 m", "angle": "10 deg"},
    _nested(20),
]


def _leaves(d, path=()):
    """Every (path, value) of a nested dict/list, tables and arrays included."""
    out = []
    if isinstance(d, dict):
        for k, v in d.items():
            out.append((path + (k,), v))
            out.extend(_leaves(v, path + (k,)))
    elif isinstance(d, list):
        for i, v in enumerate(d):
            out.append((path + (i,), v))
            out.extend(_leaves(v, path + (i,)))
    return out


def _parent(d, path):
    for k in path[:-1]:
        d = d[k]
    return d


def _mutate(data: dict, draw) -> None:
    leaves = _leaves(data)
    if not leaves:
        return
    path, value = leaves[draw(st.integers(0, len(leaves) - 1))]
    parent, last = _parent(data, path), path[-1]
    kind = draw(st.sampled_from(["replace", "replace", "replace", "delete", "rename", "swap",
                                 "scale", "duplicate"]))
    if kind == "replace":
        parent[last] = copy.deepcopy(draw(st.sampled_from(POOL)))  # later mutations must not edit POOL
    elif kind == "delete":
        del parent[last]
    elif kind == "rename" and isinstance(parent, dict):
        new = draw(st.sampled_from([str(last) + "x", str(last).upper(), "H", "O", "<b>", "name", "0", "A"]))
        parent[new] = parent.pop(last)
    elif kind == "swap":
        other = leaves[draw(st.integers(0, len(leaves) - 1))][1]
        parent[last] = json.loads(json.dumps(other))
    elif kind == "scale":
        factor = draw(st.sampled_from(["1e6", "1e-6", "-1", "0", "1e12", "1.0001"]))
        if isinstance(value, str) and value.strip():
            parent[last] = f"({value})*{factor}"
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            parent[last] = value * float(factor)
    elif kind == "duplicate" and isinstance(parent, list):
        parent.append(json.loads(json.dumps(value)))


def _toml_key(k) -> str:
    return json.dumps(str(k), ensure_ascii=False)


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(x)}" for k, x in v.items()) + "}"


def to_toml(data: dict) -> str:
    """Every top-level key as ``key = value`` with inline tables (valid TOML for any dict)."""
    return "".join(f"{_toml_key(k)} = {_toml_value(v)}\n" for k, v in data.items())


def run_case(path) -> str:
    """``"result"`` or ``"error"``; any other exception propagates (a failure of the fuzz)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        try:
            study = Study(path)
            tabs = tables(study)
            scalars = study.all_scalars()
            check_finite(tabs, scalars)  # what export does: CaseError on a leak
        except ReportgenError as e:
            text = str(e)
            assert text and "Traceback" not in text and len(text) < 3000
            return "error"
    assert not nonfinite(tabs, scalars)
    return "result"


def test_mutated_cases_give_a_result_or_a_clear_error(tmp_path):
    # the mutants sit beside copies of the real cases ([dynamics.compare] names a neighbour)
    for other in CASES.glob("*.toml"):
        (tmp_path / other.name).write_bytes(other.read_bytes())
    outcomes = {"result": 0, "error": 0}

    @settings(max_examples=MUTANTS, deadline=None, derandomize=True, database=None,
              suppress_health_check=list(HealthCheck))
    @given(st.data())
    def one_mutant(data):
        name = data.draw(st.sampled_from(sorted(BASES)))
        case = json.loads(json.dumps(BASES[name]))
        if "frame" in case and isinstance(case.get("grid", {}), dict):
            case.setdefault("grid", {})["cycle_points"] = CYCLE_POINTS
        for _ in range(data.draw(st.integers(1, 3))):
            _mutate(case, data.draw)
        path = tmp_path / f"mutant_{name}"
        path.write_text(to_toml(case), encoding="utf-8")
        outcomes[run_case(path)] += 1

    one_mutant()
    assert sum(outcomes.values()) >= MUTANTS
    # the mutants are not all rejected (a fuzz that only meets errors tests little)
    assert outcomes["result"] >= 0.2 * sum(outcomes.values()), outcomes


@pytest.mark.parametrize("name", sorted(BASES))
def test_the_real_cases_round_trip_through_the_writer(tmp_path, name):
    """The TOML writer of the fuzz keeps a real case intact (so mutants differ only by the mutation)."""
    path = tmp_path / name
    path.write_text(to_toml(BASES[name]), encoding="utf-8")
    assert tomllib.loads(path.read_text(encoding="utf-8")) == BASES[name]
