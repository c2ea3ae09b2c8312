"""Degrees of freedom of a planar mechanism by Chebyshev, W = 3n − 2p₅ − p₄ (Артоболевский, § 3;
Попов, Тимофеев, гл. 1), the passive (local) freedoms of rollers, and the replacement of each
higher pair by a link with two lower pairs (revolutes at the centres of curvature of the two
contacting profiles).  A roller (a link with one revolute and one higher pair) turns freely about
its axis: a passive freedom.  Its profile's centre of curvature is its axis, so in the replacement
the roller itself becomes the replacing link (n unchanged, p₅ + 1, p₄ − 1) and the passive freedom
disappears; any other higher pair gets a new link (n + 1, p₅ + 2, p₄ − 1)."""
from __future__ import annotations

__all__ = ["count", "replace_higher", "LOWER", "HIGHER"]

LOWER = ("R", "P")
HIGHER = ("H",)


def count(n: int, pairs: list[tuple[int, int, str]], rollers=()) -> dict:
    """n moving links, pairs (i, j, type) with type R, P (p₅) or H (p₄): W, the passive freedoms
    and the mechanism's freedom W − q."""
    p5 = sum(1 for *_, t in pairs if t in LOWER)
    p4 = sum(1 for *_, t in pairs if t in HIGHER)
    W = 3 * n - 2 * p5 - p4
    q = len(rollers)
    return dict(n=n, p5=p5, p4=p4, W=W, q=q, W_true=W - q)


def replace_higher(n: int, pairs: list[tuple[int, int, str]], rollers=()) -> tuple[int, list[tuple[int, int, str]], list]:
    """The mechanism after the replacement: (n', pairs', new links).  A higher pair with a roller
    becomes a revolute between the roller and the other link; otherwise a new link n + k joins the
    two links by two revolutes."""
    out, new = [], []
    for i, j, t in pairs:
        if t not in HIGHER:
            out.append((i, j, t))
        elif i in rollers or j in rollers:
            out.append((i, j, "R"))
        else:
            k = n + len(new) + 1
            new.append(k)
            out += [(i, k, "R"), (k, j, "R")]
    return n + len(new), out, new
