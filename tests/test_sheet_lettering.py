"""Case text in the title block is lettered as written: a «$» from ``[meta]`` never starts a
mathtext formula (which would misprint the field or fail the sheet on an unknown command)."""
import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from reportgen.sheets import frame as F  # noqa: E402

HOSTILE = ["Иванов $\\undefinedcmd{x}$", "цена $5 и $6", "a\\$b", "Эскиз $", "$$"]


def test_literal_lettering_keeps_every_dollar():
    fig = plt.figure(figsize=(2, 1))
    ax = fig.add_axes([0, 0, 1, 1])
    for s in HOSTILE:
        t = ax.text(0, 0, F.lettering(s, literal=True))
        shown, _ = t._preprocess_math(t.get_text())
        if "Э" not in s:                          # shown exactly as written
            assert shown == s
    fig.savefig(io.BytesIO(), format="pdf")       # no mathtext error
    plt.close(fig)


def test_title_block_with_dollars_in_meta_renders():
    fig = plt.figure(figsize=(841 / 25.4, 594 / 25.4))
    ax = fig.add_axes([0, 0, 1, 1])
    ax.set_xlim(0, 841)
    ax.set_ylim(0, 594)
    block = F.TitleBlock(designation="ТММ $\\frac{1}{0}$", name="Проект $x", sheet_title="Лист $",
                         organisation="МГТУ $\\undefinedcmd$", developer="$Иванов$", checker="$$")
    texts = F.draw_frame(ax, block)
    fig.savefig(io.BytesIO(), format="pdf")
    plt.close(fig)
    shown = [t._preprocess_math(t.get_text())[0] for t in texts]
    assert "МГТУ $\\undefinedcmd$" in shown and "$Иванов$" in shown and "$$" in shown
