"""Read ``[synthesis]``: the inputs of the linkage synthesis (expressions of ``[parameters]``)
and its results as parameters ``syn_<key>`` of the same case (plus aliases from ``names``).

The synthesis itself is :mod:`reportgen.core.synthesis`; this module only maps the case keys
to its arguments, checks them and returns every variant, so that the case reader, ``check``,
the analysis and the note see the same numbers."""
from __future__ import annotations

import math
from typing import Mapping

from ..core import synthesis as S
from ..errors import did_you_mean
from . import units as U
from .expr import Q
from .reader import Node

# type → (required keys, one-of groups, optional keys); dimension of every input key
TYPES: dict[str, tuple[tuple[str, ...], tuple[str, ...], tuple[str, ...]]] = {
    "crank_rocker": (("K", "psi", "c"), ("d", "o1_y"), ()),
    "slider_crank": (("K", "H"), ("e", "lam"), ()),
    "slotted_lever": (("K", "H"), ("d", "a"), ()),
    "six_bar": (("K", "H", "l3", "l4", "path_y"), ("o1_y", "o1_d", "o1_path_dist"), ("side",)),
}
TITLES = {"crank_rocker": "кривошипно-коромысловый механизм",
          "slider_crank": "кривошипно-ползунный механизм",
          "slotted_lever": "кулисный механизм с качающейся кулисой",
          "six_bar": "шестизвенный механизм с коромыслом и ползуном"}
_ANGLES = {"psi", "theta", "theta_check", "phi_far", "phi_near", "phi_left", "phi_right"}
_PLAIN = {"K", "lam", "variant", "side"}


def dim_of(key: str) -> U.Dim:
    """Dimension of an input or result key of the synthesis."""
    if key in _ANGLES:
        return U.ANGLE
    if key in _PLAIN:
        return U.DIMENSIONLESS
    return U.LENGTH


def node_of(root: Node) -> Node:
    return root.table("synthesis")


def inputs(node: Node, names: Mapping[str, Q]) -> tuple[str, dict[str, float]]:
    """The synthesis type and its inputs in SI (checked)."""
    kind = node.string("type", required=True, choices=list(TYPES))
    req, one_of, opt = TYPES[kind]
    node.check_keys(["type", "variant", "names", "printed", *req, *one_of, *opt], required=["type", *req])
    given = [k for k in one_of if node.has(k)]
    if len(given) != 1:
        raise node.error(None, "нужно задать ровно один из ключей: " + ", ".join(one_of),
                         expected="одно условие, задающее положение центра кривошипа"
                         if kind != "slider_crank" else "смещение e или отношение λ = a/b")
    out: dict[str, float] = {}
    for k in (*req, *given, *(o for o in opt if node.has(o))):
        positive = k not in ("o1_y", "path_y", "side")
        out[k] = node.quantity(k, dim_of(k), names, required=True, positive=positive)
    if out["K"] < 1 or out["K"] >= 3:
        raise node.error("K", "коэффициент изменения средней скорости вне допустимых пределов",
                         expected="1 ≤ K < 3 (угол θ = 180°·(K − 1)/(K + 1) < 90°)", got=str(out["K"]))
    if kind == "slider_crank" and out["K"] == 1 and "lam" not in out:
        raise node.error("e", "при K = 1 (θ = 0) смещение e не определяет длину шатуна",
                         expected="отношение lam = a/b (центральный механизм: H = 2a)")
    if kind == "crank_rocker" and not out["psi"] < math.pi:
        raise node.error("psi", "угол размаха коромысла слишком велик", expected="0 < ψ < 180°")
    return kind, out


def variants(kind: str, x: Mapping[str, float]) -> list[dict]:
    """Every solution variant of the synthesis ``kind`` for the inputs ``x``."""
    K = x["K"]
    if kind == "crank_rocker":
        return S.crank_rocker(K, x["psi"], x["c"], d=x.get("d"), line_y=x.get("o1_y"))
    if kind == "slider_crank":
        return S.slider_crank(K, x["H"], e=x.get("e"), lam=x.get("lam"))
    if kind == "slotted_lever":
        return S.slotted_lever(K, x["H"], d=x.get("d"), a=x.get("a"))
    return S.six_bar(K, x["H"], x["l3"], x["l4"], path_y=x["path_y"], o1_y=x.get("o1_y"), o1_d=x.get("o1_d"),
                     o1_path_dist=x.get("o1_path_dist"), side=1.0 if x.get("side", 1.0) >= 0 else -1.0)


def solve(node: Node, names: Mapping[str, Q]) -> tuple[str, dict[str, float], list[dict], int]:
    """Type, inputs, all variants and the chosen variant's index (0-based); a synthesis
    without a solution is a CaseError."""
    kind, x = inputs(node, names)
    vs = variants(kind, x)
    if not vs:
        raise node.error(None, "синтез не имеет решения при заданных условиях",
                         expected="условия, при которых центр кривошипа существует "
                                  "(проверьте ход, K, длины и положение центра кривошипа)")
    n = node.integer("variant", 1, minimum=1)
    if n > len(vs):
        raise node.error("variant", f"вариант {n} не существует",
                         expected=f"номер варианта от 1 до {len(vs)}", got=str(n))
    return kind, x, vs, n - 1


def result_names(node: Node) -> dict[str, str]:
    """Aliases ``names = { a = "l_OA", … }``: result key → parameter name."""
    raw = node.raw("names", {})
    if not isinstance(raw, Mapping) or not all(isinstance(v, str) for v in raw.values()):
        raise node.error("names", "ожидалась таблица псевдонимов",
                         expected='names = { a = "l_OA", b = "l_AB" }')
    return dict(raw)


def parameters(node: Node, names: Mapping[str, Q]) -> dict[str, Q]:
    """The results of the chosen variant as parameters: ``syn_<key>`` and the aliases."""
    _, _, vs, i = solve(node, names)
    v = vs[i]
    out = {f"syn_{k}": Q(float(val), dim_of(k)) for k, val in v.items()}
    for k, alias in result_names(node).items():
        if k not in v:
            raise node.error(f"names.{k}", f"синтез не даёт результата «{k}»",
                             expected="один из результатов: " + ", ".join(v), hint=did_you_mean(k, list(v)))
        out[alias] = Q(float(v[k]), dim_of(k))
    return out


def output_names(node: Node) -> set[str]:
    """Names the synthesis defines (without solving it): ``syn_*`` are recognised by prefix."""
    return set(result_names(node).values())
