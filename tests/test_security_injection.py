"""Case text reaches the note only escaped, and building the note fetches nothing from outside.

One hostile variant of ws000 puts the same payload (a script, an image from a local server, an
event handler, a link that would embed a local file into the PDF) into every free-text field:
every [meta] value the templates print, link titles, load titles, the printed values' titles and
notes, the comparison title, the output quantity's title. Names (points, links, pairs,
positions) and [report] options must not hold markup at all: they are rejected at input.
"""
from __future__ import annotations

import re
from html.parser import HTMLParser

import pytest

from conftest import CASES
from reportgen.analysis.study import Study
from reportgen.cli import main
from reportgen.report import render, safety
from reportgen.report.assemble import build_report
from reportgen.report.document import Paragraph, Report, Section

PAYLOAD = ('<script>alert(1)</script><img src="http://127.0.0.1:9/x" onload=alert(1)>'
           '<a rel="attachment" href="file:///etc/passwd">x</a><style>@import url(http://127.0.0.1:9/c);</style>')


class _Elements(HTMLParser):
    """Tags with their attributes, and the text of <style> elements, as a browser parses them."""

    def __init__(self, html: str):
        super().__init__(convert_charrefs=True)
        self.tags: list[tuple[str, dict]] = []
        self.styles: list[str] = []
        self._in_style = False
        self.feed(html)

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        self._in_style = tag == "style"

    def handle_endtag(self, tag):
        self._in_style = False

    def handle_data(self, data):
        if self._in_style:
            self.styles.append(data)


def hostile_markup(html: str) -> list[str]:
    """Elements and attributes that could run code or load something from outside."""
    doc = _Elements(html)
    bad = []
    for tag, attrs in doc.tags:
        if tag in ("script", "iframe", "object", "embed", "link", "base", "meta") and not (
                tag == "meta" and set(attrs) <= {"charset", "name", "content"}):
            bad.append(f"<{tag}>")
        for k, v in attrs.items():
            if k.startswith("on"):
                bad.append(f"<{tag} {k}=>")
            if k in ("src", "href") and v and not v.startswith(("data:", "#")):
                bad.append(f"<{tag} {k}={v[:40]}>")
            if k == "rel" and v == "attachment":
                bad.append(f"<{tag} rel=attachment>")
    for css in doc.styles:
        for m in re.finditer(r"url\(\s*[\"']?([^\"')]*)", css):
            if not m.group(1).startswith(("data:", "file:")):
                bad.append(f"url({m.group(1)[:40]})")
        if "@import" in css:
            bad.append("@import")
    return bad


META_KEYS = ["ministry", "university", "faculty", "department", "discipline", "topic", "variant",
             "student", "group", "supervisor", "supervisor_title", "city", "year", "doc_code",
             "document", "work", "issue_date", "due_date", "assignment_subtitle"]


def _toml_str(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def hostile_case(tmp_path):
    text = (CASES / "ws000_six_bar.toml").read_text(encoding="utf-8")
    p = _toml_str(PAYLOAD)
    start = text.index("[meta]")
    end = text.index("\n[", start + 1)
    meta = "[meta]\n" + "".join(f"{k} = {_toml_str(k + PAYLOAD)}\n" for k in META_KEYS)
    text = text[:start] + meta + text[end:]
    text = text.replace('title = "кривошип"', f"title = {p}", 1)
    text = text.replace('title = "сила полезного сопротивления Pп.с"', f"title = {p}", 1)
    text = text.replace('title = "J<sub>1пр</sub>"', f"title = {_toml_str('J<sub>1пр</sub>' + PAYLOAD)}, "
                        f"note = {p}", 1)
    # a printed value off by far, so that its note is printed
    text = re.sub(r'omega_m = \{ value = "6\.807"', 'omega_m = { value = "9.999"', text, count=1)
    text = text.replace('omega_m = { value = "9.999", title = "ω<sub>1ср</sub>" }',
                        f'omega_m = {{ value = "9.999", title = {p}, note = {p} }}', 1)
    text = text.replace("[dynamics.printed]",
                        f'[dynamics.compare]\ncase = "ws000_six_bar_corrected.toml"\ntitle = {p}\n\n[dynamics.printed]', 1)
    text += f'\n[report]\noutput = "x_H"\noutput_title = {p}\n'
    for other in CASES.glob("*.toml"):  # the compared case and its own comparison
        (tmp_path / other.name).write_bytes(other.read_bytes())
    path = tmp_path / "hostile.toml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def hostile_html(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("hostile")
    study = Study(hostile_case(tmp))
    report = build_report(study)
    from reportgen.report.key import build_key
    key = build_key(study)   # the printed values and their titles are in the teacher's key
    return {"screen": render.render_html(report, for_print=False),
            "print": render.render_html(report, for_print=True),
            "key": render.render_html(key, for_print=False)}


@pytest.mark.parametrize("flavour", ["screen", "print", "key"])
def test_no_markup_from_the_case_reaches_the_html(hostile_html, flavour):
    assert hostile_markup(hostile_html[flavour]) == []


def test_the_checker_sees_raw_markup():
    assert sorted(hostile_markup(PAYLOAD)) == sorted([
        "<script>", "<img src=http://127.0.0.1:9/x>", "<img onload=>", "<a href=file:///etc/passwd>",
        "<a rel=attachment>", "url(http://127.0.0.1:9/c)", "@import"])


def test_every_text_field_arrived_escaped(hostile_html):
    html = hostile_html["screen"]
    escaped = "&lt;script&gt;alert(1)&lt;/script&gt;"
    # every [meta] value the templates print (the title page, the assignment, the stamp)
    for key in ["ministry", "university", "faculty", "department", "topic", "student", "group",
                "supervisor", "city"]:
        assert f"{key}{escaped}" in html, key
    # link title, load title, output title in the note; printed titles and notes and the
    # comparison title in the teacher's key
    assert html.count(escaped) >= len(META_KEYS) // 2 + 3
    key = hostile_html["key"]
    assert key.count(escaped) >= 3
    # the whitelisted inline markup of printed titles still works
    assert "J<sub>1пр</sub>&lt;script&gt;" in key


def test_the_screen_html_has_no_external_reference(hostile_html):
    doc = _Elements(hostile_html["screen"])
    for tag, attrs in doc.tags:
        for k in ("src", "href"):
            assert not attrs.get(k) or attrs[k].startswith(("data:", "#")), (tag, attrs)
    for css in doc.styles:
        assert not re.search(r"url\(\s*(?![\"']?data:)", css)


@pytest.mark.parametrize("old,new,key", [
    ("A = [0, 0], S2", '"M<svg onload=alert(1)>" = [0, 0], A = [0, 0], S2', "links[1].points"),
    ('C = ["X_C", "Y_C"]', 'C = ["X_C", "Y_C"], "<img src=x>" = [0, 0]', "frame.points"),
    ('name = "2"', 'name = "<b>2</b>"', "links[1].name"),
    ("[parameters]", '[parameters]\n"P<img src=x>" = "1 m"', "parameters.P<img"),
    ('label = "f"', "label = \"f\\\" onload=\\\"alert(1)\"", "grid.extra[0].label"),
])
def test_names_with_markup_are_rejected(tmp_path, capsys, old, new, key):
    text = (CASES / "ws000_six_bar.toml").read_text(encoding="utf-8")
    assert old in text
    p = tmp_path / "c.toml"
    p.write_text(text.replace(old, new, 1), encoding="utf-8")
    assert main(["check", str(p)]) == 2
    err = capsys.readouterr().err
    assert key in err and "недопустимое" in err


def test_joint_name_with_markup_is_rejected(tmp_path, capsys):
    text = (CASES / "ws000_six_bar.toml").read_text(encoding="utf-8")
    old = 'links = ["0", "1"]\npoint = "O"'
    assert old in text
    p = tmp_path / "c.toml"
    p.write_text(text.replace(old, old + '\nname = "O<i onmouseover=x>"', 1), encoding="utf-8")
    assert main(["check", str(p)]) == 2
    assert "joints[0].name" in capsys.readouterr().err


@pytest.mark.parametrize("value", [
    '"14pt; } </style><script>alert(1)</script><style>"',
    '"url(http://127.0.0.1:9/x)"',
    '"x</style><img src=http://127.0.0.1:9/y>"',
])
@pytest.mark.parametrize("key", ["font_size_pt", "dash", "toc_title", "font"])
def test_report_options_cannot_break_out_of_style(key, value):
    import tomllib
    opts = tomllib.loads(f"{key} = {value}")
    with pytest.raises(safety.OptionError):
        safety.validate_options(opts, file="c.toml")
    with pytest.raises(ValueError):
        render.render_html(_tiny(opts), for_print=True)


def _tiny(options=None, html="") -> Report:
    s = Section("Раздел", "s1")
    s.paragraph("Текст." + html)
    return Report(meta={"topic": "Тест"}, assignment=[], introduction=[], sections=[s], conclusion=[],
                  references=[], options={"title_page": False, "assignment_page": False, **(options or {})})


def test_url_fetcher_refuses_everything_but_data_and_own_files():
    from reportgen.style import fonts
    for url in ["http://127.0.0.1:9/x", "https://example.org/a.png", "ftp://127.0.0.1/x",
                "file:///etc/passwd", "file://host/etc/passwd", "file:///proc/self/environ",
                (render.TEMPLATES_DIR / ".." / "pyproject.toml").resolve().as_uri(), "gopher://x"]:
        with pytest.raises(safety.FetchRefused):
            safety.check_url(url)
        assert safety.refused[-1] == url
    safety.check_url("data:image/png;base64,iVBORw0KGgo=")
    safety.check_url(fonts.find_serif().regular.resolve().as_uri())
    safety.check_url((render.TEMPLATES_DIR / "gost.css").resolve().as_uri())


def test_a_pdf_build_fetches_nothing_and_embeds_no_local_file(tmp_path):
    """Markup that would slip through (here put in by code, not by a case) cannot make
    WeasyPrint read the network or attach a local file: the fetcher refuses."""
    hostile = ('<img src="http://127.0.0.1:9/x"><a rel="attachment" href="file:///etc/passwd">f</a>'
               '<img src="file:///etc/hostname">')
    before = len(safety.refused)
    out = render.build_outputs(_tiny(html=hostile), tmp_path, "t", formats=("pdf",))
    new = safety.refused[before:]
    assert "http://127.0.0.1:9/x" in new and "file:///etc/passwd" in new and "file:///etc/hostname" in new
    pdf = out["pdf"].read_bytes()
    assert b"/EmbeddedFile" not in pdf and b"root:" not in pdf


def test_output_link_title_reaches_the_output_name_escaped(tmp_path):
    """The output link named by its case title (``plans._link_named``): a hostile title with a
    bracketed remark (the branch that splits the title) arrives escaped."""
    from reportgen import load_case
    from reportgen.analysis.plans import output_quantity
    text = (CASES / "slider_crank.toml").read_text(encoding="utf-8")
    assert 'title = "ползун"' in text
    text = text.replace('title = "ползун"', f"title = {_toml_str('ползун (' + PAYLOAD + ')')}", 1)
    case = tmp_path / "hostile_slider.toml"
    case.write_text(text, encoding="utf-8")
    name = str(output_quantity(load_case(case))[3])
    assert name.startswith("ползун ") and "&lt;script&gt;" in name
    assert "<script" not in name and "<img" not in name and "<a " not in name


def test_link_titles_of_a_driving_slot_and_its_stone_arrive_escaped(tmp_path):
    """The assignment names a driving link by its case title («Ведущее звено 1 — …; … служит
    кривошипом») and the kinematics names a stone turning with it («Звено 2 (…) поворачивается вместе
    с ведущим звеном 1»): both titles, hostile here, arrive escaped (driving_slot_planer)."""
    text = (CASES / "driving_slot_planer.toml").read_text(encoding="utf-8")
    p = _toml_str(PAYLOAD)
    for old in ('title = "кулиса"', 'title = "камень"'):
        assert old in text
        text = text.replace(old, f"title = {p}", 1)
    path = tmp_path / "hostile_planer.toml"
    path.write_text(text, encoding="utf-8")
    html = render.render_html(build_report(Study(path)), for_print=False)
    assert hostile_markup(html) == []
    escaped = "&lt;script&gt;alert(1)&lt;/script&gt;"
    assert "служит кривошипом" in html and "поворачивается вместе" in html
    assert html.count(escaped) >= 2
