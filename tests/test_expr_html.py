"""Case expressions in textbook notation (report/russian.py expr_html): powers as superscripts,
functions upright in Russian notation, Greek letters, no identifier left."""
import re

from reportgen.report.russian import expr_html


def test_powers_functions_and_greek():
    h = str(expr_html("J_d + m*r^2*cos(phi)^2 - k*tan(phi)*omega"))
    assert h == ("<i>J</i><sub>d</sub> + <i>m</i>·<i>r</i><sup>2</sup>·cos(<i>φ</i>)<sup>2</sup> − "
                 "<i>k</i>·tg(<i>φ</i>)·<i>ω</i>")
    assert not re.search(r"\^|\bphi\b|\bomega\b|_", re.sub(r"<[^>]+>", "", h))


def test_units_and_subscripts_unchanged():
    assert str(expr_html("y_56 = 0.2 m")) == "<i>y</i><sub>56</sub> = 0,2\u00a0м"
    assert str(expr_html("x^(2)")) == "<i>x</i>^(2)"
