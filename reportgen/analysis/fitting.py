"""Fitted dimensions: an unknown parameter chosen so that a condition holds at a position.

Each ``[[fit]]`` of the case names a parameter, a condition ``lhs = rhs`` over kinematic
columns and parameters, and the value of the generalised coordinate at which it must hold.  The
fits are solved in the order written (worksheet 002: L4, then S_p, then L7), each by the secant
method polished to |f| ≤ 1e-12·scale, with a bracketing fallback (Brent) when the secant
iteration leaves the assembly range.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..case.expr import evaluate
from ..case.reader import Node
from ..errors import AssemblyError, CaseError


@dataclass
class FitResult:
    """One dimension fitted by ``[[fit]]``: its value, the condition it satisfies, at which
    position, the residual left and the iterations it took."""
    name: str
    value: float
    condition: str
    at: str
    residual: float
    iterations: int
    dim: tuple


def split_condition(node: Node) -> tuple[str, str]:
    """The two sides of a fit condition «expression = value» of ``[[fit]]``."""
    text = node.string("condition", required=True)
    if text.count("=") != 1:
        raise node.error("condition", "условие подбора должно иметь вид «выражение = значение»",
                         expected="например condition = \"y_56 = 0.2 m\"", got=text)
    lhs, rhs = (s.strip() for s in text.split("="))
    return lhs, rhs


def solve_fit(node: Node, name: str, guess: float, residual: Callable[[float], float],
              scale: float) -> tuple[float, float, int]:
    """Root of residual(x) near ``guess``; returns (x, residual, evaluations)."""
    from scipy import optimize      # only a case with [fit] needs it (its import costs 0,3 s)
    count = [0]

    def f(x: float) -> float:
        count[0] += 1
        try:
            return residual(x)
        except AssemblyError:
            return math.nan

    tol = 1e-12 * max(scale, 1e-300)
    step = 1e-3 * (abs(guess) if guess != 0 else 1.0)
    root = None
    try:
        x = optimize.newton(f, guess, x1=guess + step, tol=1e-15 * max(abs(guess), 1e-9), maxiter=100)
        if math.isfinite(x) and abs(f(x)) <= tol:
            root = float(x)
    except (RuntimeError, OverflowError, ValueError, ZeroDivisionError):
        root = None
    if root is None:
        # bracket search outward from the guess, then Brent
        f0 = f(guess)
        a = guess
        for k in range(1, 60):
            for sgn in (1.0, -1.0):
                b = guess + sgn * step * (1.5 ** k)
                fb = f(b)
                if math.isfinite(f0) and math.isfinite(fb) and f0 * fb < 0:
                    root = float(optimize.brentq(f, min(a, b), max(a, b), xtol=1e-15, rtol=4.5e-16, maxiter=200))
                    break
            if root is not None:
                break
    if root is None:
        raise node.error("unknown", f"не удалось подобрать параметр «{name}»: условие не выполняется ни при каком значении вблизи начального",
                         expected="достижимое условие и начальное приближение guess рядом с решением")
    return root, f(root), count[0]


def evaluate_condition(lhs: str, rhs: str, names: dict, node: Node) -> float:
    """The residual lhs − rhs of a fit condition, both sides evaluated with the case's names (the
    right side in the left side's unit); the root finder drives it to zero."""
    try:
        a = evaluate(lhs, names)
        b = evaluate(rhs, names, expected=a.dim)
    except CaseError as e:
        raise e.with_context(file=node.file, key_prefix=node.key("condition")) from None
    return float(np.asarray(a.value).ravel()[0]) - float(np.asarray(b.value).ravel()[0])
