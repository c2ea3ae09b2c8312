"""Snapshots of what users script against: numeric tables with tolerances (pytest-regressions)
and rendered table fragments as HTML (syrupy)."""
import pytest

from conftest import normalize_html
from reportgen.report.render import render_fragment
from reportgen.report.sections import kinematics as sec_kin
from reportgen.report.sections import structure as sec_struct

KIN_COLS = ["q", "x_A", "y_A", "x_B", "y_B", "x_H", "phi_2", "phi_3", "phi_4", "wq_2", "wq_3", "wq_4",
            "vqx_H", "aqx_H", "eq_3", "v_H", "a_H"]


def _find(section, table_id):
    for c in section.children:
        if getattr(c, "id", None) == table_id and hasattr(c, "columns"):
            return c
        if hasattr(c, "children"):
            hit = _find(c, table_id)
            if hit is not None:
                return hit
    return None


def test_ws000_kinematics_table(ws000, dataframe_regression):
    df = ws000.kinematics[KIN_COLS].reset_index(drop=True)
    dataframe_regression.check(df, default_tolerance=dict(atol=1e-12, rtol=1e-10))


def test_ws002_fitted_kinematics(ws002, dataframe_regression):
    cols = ["q", "phi_3", "phi_4", "phi_5", "phi_6", "phi_7", "x_56", "y_56", "x_S6", "y_S6", "U43", "IS6"]
    dataframe_regression.check(ws002.kinematics[cols].reset_index(drop=True),
                               default_tolerance=dict(atol=1e-12, rtol=1e-10))


@pytest.mark.parametrize("case,builder,table_id", [
    ("ws000", sec_struct, "tab-pairs"),
    ("ws000", sec_struct, "tab-groups"),
    ("ws004", sec_kin, "tab-angles"),
])
def test_rendered_table_fragment(case, builder, table_id, request, snapshot_html):
    study = request.getfixturevalue(case)
    section = builder.build(study)
    table = _find(section, table_id)
    assert table is not None, table_id
    html = render_fragment(table, chapter="2")
    assert "Таблица 2.1" in html
    assert normalize_html(html) == snapshot_html
