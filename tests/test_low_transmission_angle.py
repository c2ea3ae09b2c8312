"""A least transmission angle below 40° is remarked under its table (ws000 corrected: Table 2.14 printed
μ_min = 35,7° for group (2,3) and the chapter went on without a word; only the conclusion spoke of it)."""
import html

from notehelpers import plain
from test_note_review_i import _section


def _text(stem):
    from reportgen.report.render import render_fragment
    from reportgen.report.sections import kinematics
    return html.unescape(plain(render_fragment(_section(stem, kinematics)))).replace("\xa0", " ")


def test_low_angle_remarked_under_its_table():
    t = _text("ws000_six_bar_corrected")
    i = t.index("Наименьшие углы передачи движения")
    after = t[i:]
    assert ("Наименьший угол передачи в группе (2,3) — 35,7° (при φ = 219,1°) — меньше рекомендуемого 40°"
            in after), after[:600]


def test_no_remark_when_every_angle_passes():
    t = _text("slider_crank")
    assert "меньше рекомендуемого" not in t
