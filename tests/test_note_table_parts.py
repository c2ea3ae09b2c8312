"""A wide table split into parts («часть 1», «часть 2» …) splits into parts of nearly equal
width: never eight columns and then a part holding one column (ws000's ω₄, ε₄ and R₀₅y stood
alone in a table of their own)."""
import re

import pytest

from reportgen.report.sections import dynamics as sec_dyn
from reportgen.report.sections import forces as sec_frc
from reportgen.report.sections import kinematics as sec_kin
from reportgen.report.sections.common import balanced_parts


@pytest.mark.parametrize("n,most", [(n, m) for n in range(1, 30) for m in (1, 4, 6, 8)])
def test_balanced_parts_fewest_parts_of_nearly_equal_width(n, most):
    parts = balanced_parts(n, most)
    assert sum(parts) == n and max(parts) <= most
    assert len(parts) == -(-n // most)              # no more parts than the limit asks
    assert max(parts) - min(parts) <= 1             # the last part is never a stub


def _tables(node):
    for c in getattr(node, "children", []):
        if hasattr(c, "columns") and hasattr(c, "caption"):
            yield c
        yield from _tables(c)


@pytest.mark.parametrize("builder", [sec_kin, sec_dyn, sec_frc], ids=["kinematics", "dynamics", "forces"])
def test_parts_of_a_split_table_are_of_nearly_equal_width(ws000, builder):
    groups: dict[str, list[int]] = {}
    for t in _tables(builder.build(ws000)):
        m = re.fullmatch(r"(.*) \(часть\u00a0(\d+)\)", t.caption)
        if m:
            lead = sum(1 for c in t.columns if c.key in ("no", "q_deg", "q", "pos"))
            groups.setdefault(m.group(1), []).append(len(t.columns) - lead)
    assert groups, "ws000 has split tables"
    for caption, widths in groups.items():
        assert max(widths) - min(widths) <= 1, (caption, widths)
