"""The note's print HTML parsed into the tree WeasyPrint's HTML5 parser (tinyhtml5) builds, fast.

WeasyPrint parses every document with tinyhtml5, a pure-Python HTML5 tokenizer and tree builder:
0.07–0.10 s of CPU for each large part of ws000 (most of it scanning the long ``data:`` URLs of
the figures character by character), about 0.3 s per note. The HTML the templates write is a
small, regular subset of HTML5: a doctype, explicit ``html``/``head``/``body``, every element
closed by its own end tag (but a ``tbody`` implied by a row straight in a table). For that subset the HTML5 tree
construction (WHATWG HTML, §13.2.6) reduces to "append the element to the current node, pop at
its end tag" plus the whitespace rules around ``head`` and ``body``, and a regular-expression
tokenizer builds the same ``xml.etree.ElementTree`` tree (tags, attributes in order, text and
tails) in a few milliseconds.

:func:`parse` returns ``None`` for anything outside that subset — a comment, a missing doctype
(quirks mode), an end tag that does not close the current element, a start tag the HTML5
algorithm would treat specially (implied end of a ``p``, ``li``, ``dd``, ``dt``, heading or
``a``; foster parenting of text or elements in a table; an unknown or foreign element; raw text
other than ``style`` and ``title``), an ambiguous character reference, a carriage return or NUL
— and the caller parses with tinyhtml5 as before. ``tests/test_pdf_ratio.py`` compares the two
trees on every document of several notes and on constructed edge cases.
"""
from __future__ import annotations

from html import entities as _entities
from html import unescape as _html_unescape
import re
from xml.etree import ElementTree

__all__ = ["parse"]

_VOID = frozenset("area base br col embed hr img input link meta source track wbr".split())
# elements of the body taken as "ordinary" by the HTML5 tree builder when nested properly
_BODY = frozenset(
    "div p span a b i em strong sub sup br img small u s code abbr cite q mark var wbr "
    "ul ol li dl dt dd h1 h2 h3 h4 h5 h6 section nav main header footer article aside figure figcaption "
    "blockquote hr table caption colgroup col thead tbody tfoot tr td th".split())
_HEAD = frozenset(("meta", "title", "style", "link"))
# start tags that close an open <p> in button scope (no-quirks mode)
_CLOSES_P = frozenset(
    "li dd dt search address article aside blockquote center details dialog dir div dl fieldset figcaption figure "
    "footer header hgroup main menu nav ol p section summary ul h1 h2 h3 h4 h5 h6 pre listing "
    "form table hr xmp plaintext".split())
_BUTTON_SCOPE = frozenset("applet caption html table td th marquee object template button".split())
_SPECIAL = frozenset(
    "address applet area article aside base basefont bgsound blockquote body br button caption center col "
    "colgroup dd details dir div dl dt embed fieldset figcaption figure footer form frame frameset h1 h2 h3 "
    "h4 h5 h6 head header hgroup hr html iframe img input keygen li link listing main marquee menu meta nav "
    "noembed noframes noscript object ol p param plaintext pre script search section select source style "
    "summary table tbody td template textarea tfoot th thead title tr track ul wbr xmp".split())
_HEADINGS = frozenset("h1 h2 h3 h4 h5 h6".split())
# what a table-structure element may hold directly (anything else is foster-parented or implied)
_TABLE_CHILDREN = {
    "table": frozenset(("caption", "colgroup", "thead", "tbody", "tfoot")),
    "thead": frozenset(("tr",)), "tbody": frozenset(("tr",)), "tfoot": frozenset(("tr",)),
    "tr": frozenset(("td", "th")), "colgroup": frozenset(("col",)),
}
_TABLE_ONLY = frozenset(("caption", "colgroup", "col", "thead", "tbody", "tfoot", "tr", "td", "th"))
_TABLE_PARENT = {"caption": "table", "colgroup": "table", "thead": "table", "tbody": "table",
                 "tfoot": "table", "tr": ("thead", "tbody", "tfoot"), "td": "tr", "th": "tr",
                 "col": "colgroup"}

_DOCTYPE = re.compile(r"\A<!DOCTYPE html>", re.I)
_TOKEN = re.compile(
    r"<([a-zA-Z][a-zA-Z0-9]*)((?:\s+[^\s\"'>/=]+(?:\s*=\s*(?:\"[^\"]*\"|'[^']*'|[^\s\"'=<>`]+))?)*)\s*(/?)>"
    r"|</([a-zA-Z][a-zA-Z0-9]*)>"
    r"|([^<]+)"
    r"|(<)")
_ATTR = re.compile(r"\s+([^\s\"'>/=]+)(?:\s*=\s*(?:\"([^\"]*)\"|'([^']*)'|([^\s\"'=<>`]+)))?")
_AMP = re.compile(r"&")
_REF = re.compile(r"&(?:#[0-9]{1,7};|#[xX][0-9a-fA-F]{1,6};|[A-Za-z][A-Za-z0-9]{1,31};)")
_WS = re.compile(r"[ \t\n\f]*\Z")
_RAW_END = {"style": re.compile(r"</style", re.I), "title": re.compile(r"</title", re.I)}
_RAW_CLOSE = re.compile(r"\s*>")


def _unescape(text: str) -> str | None:
    """Character references decoded as HTML5 does, ``None`` where that might differ: every ``&``
    must start a complete numeric reference or a named one that HTML5 knows with its ``;``."""
    if "&" not in text:
        return text
    refs = _REF.findall(text)
    if len(refs) != text.count("&") or not all(_plain_numeric(r) if r[1] == "#" else r[1:] in _entities.html5
                                               for r in refs):
        return None
    return _html_unescape(text)


def _plain_numeric(ref: str) -> bool:
    """A numeric reference to an ordinary character: HTML5 and ``html.unescape`` differ on
    controls, noncharacters and surrogates (one keeps, the other drops or replaces them)."""
    num = int(ref[3:-1], 16) if ref[2] in "xX" else int(ref[2:-1])
    return (num in (9, 10) or 0x20 <= num < 0x7F or 0xA0 <= num <= 0x10FFFF) and not 0xD800 <= num <= 0xDFFF \
        and not 0xFDD0 <= num <= 0xFDEF and (num & 0xFFFE) != 0xFFFE


def _add_text(node, last, text: str) -> None:
    if last is None:
        node.text = (node.text or "") + text
    else:
        last.tail = (last.tail or "") + text


def parse(source: str):
    """The root ``html`` element tinyhtml5 would build from ``source`` (``namespace_html_elements=False``),
    or ``None`` when ``source`` is outside the subset described in the module."""
    if not isinstance(source, str) or "\r" in source or "\x00" in source or "<!--" in source:
        return None
    m = _DOCTYPE.match(source)
    if m is None:
        return None
    pos = m.end()
    n = len(source)
    Element = ElementTree.Element
    root = head = body = None
    stack: list = []  # open elements: [element, last child appended(, "implied")]
    phase = "before"  # before html, in html (before head), in head, after head, in body, after body
    while pos < n:
        tm = _TOKEN.match(source, pos)
        if tm is None or tm.group(6) is not None:
            return None
        pos = tm.end()
        name, attrs, selfclose, end, text = tm.group(1), tm.group(2), tm.group(3), tm.group(4), tm.group(5)
        if text is not None:
            text = _unescape(text)
            if text is None:
                return None
            blank = _WS.match(text) is not None
            if phase in ("before", "html"):
                if not blank:
                    return None
                continue  # ignored before <head>
            if phase == "after head":
                if not blank:
                    return None
                _add_text(root, head, text)
                continue
            if phase in ("after body", "after html"):
                if not blank:
                    return None
                _add_text(body, body[-1] if len(body) else None, text)
                continue
            if phase == "head" and not blank:
                return None
            node = stack[-1]
            if node[0].tag in _TABLE_CHILDREN and not blank:
                return None  # foster parenting
            _add_text(node[0], node[1], text)
            continue
        if end is not None:
            end = end.lower()
            if phase == "head" and end == "head":
                stack.pop()
                phase = "after head"
                continue
            if phase == "body" and end == "body" and len(stack) == 2:
                phase = "after body"
                continue
            if phase == "after body" and end == "html":
                phase = "after html"
                continue
            if end == "table" and len(stack[-1]) > 2:  # the end of a table closes its implied tbody
                stack.pop()
            if phase not in ("head", "body") or len(stack) < 2 or stack[-1][0].tag != end \
                    or end in ("html", "head", "body"):
                return None
            stack.pop()
            continue
        name = name.lower()
        attrib = {}
        for am in _ATTR.finditer(attrs):
            key = am.group(1).lower()
            raw = am.group(2) if am.group(2) is not None else am.group(3) if am.group(3) is not None else am.group(4)
            value = "" if raw is None else _unescape(raw)
            if value is None:
                return None
            attrib.setdefault(key, value)
        if selfclose and name not in _VOID:
            return None
        if phase == "before":
            if name != "html":
                return None
            root = Element("html", attrib)
            stack = [[root, None]]
            phase = "html"
            continue
        if phase == "html":
            if name != "head" or attrib:
                return None
            head = Element("head")
            root.append(head)
            stack[-1][1] = head
            stack.append([head, None])
            phase = "head"
            continue
        if phase == "head":
            if name not in _HEAD:
                return None
            el = Element(name, attrib)
            head.append(el)
            stack[-1][1] = el
            if name in _RAW_END:  # raw text up to the end tag (title: character references decoded)
                em = _RAW_END[name].search(source, pos)  # the first «</style» ends it, as in HTML5
                close = None if em is None else _RAW_CLOSE.match(source, em.end())
                if close is None:
                    return None
                raw = source[pos:em.start()]
                if name == "title":
                    raw = _unescape(raw)
                    if raw is None:
                        return None
                if raw:
                    el.text = raw
                pos = close.end()
            continue
        if phase == "after head":
            if name != "body":
                return None
            body = Element("body", attrib)
            root.append(body)
            stack[-1][1] = body
            stack.append([body, None])
            phase = "body"
            continue
        if phase != "body" or name not in _BODY:
            return None
        if name == "tr" and stack[-1][0].tag == "table":  # a row straight in a table: tbody implied
            el = Element("tbody")
            stack[-1][0].append(el)
            stack[-1][1] = el
            stack.append([el, None, "implied"])
        tags = [entry[0].tag for entry in stack]
        current = tags[-1]
        # the HTML5 tree builder would close or move something here: leave it to tinyhtml5
        if current in _TABLE_CHILDREN:
            if name not in _TABLE_CHILDREN[current]:
                return None
        elif name in _TABLE_ONLY:
            return None
        if name in _TABLE_PARENT:
            want = _TABLE_PARENT[name]
            if (current not in want) if isinstance(want, tuple) else current != want:
                return None
        if name in _CLOSES_P:
            for tag in reversed(tags):
                if tag == "p":
                    return None
                if tag in _BUTTON_SCOPE:
                    break
        if name in ("li", "dd", "dt"):
            for tag in reversed(tags):
                if tag in ("li", "dd", "dt"):
                    return None
                if tag in _SPECIAL and tag not in ("address", "div", "p"):
                    break
        if name in _HEADINGS and current in _HEADINGS:
            return None
        if name == "a" and "a" in tags:
            return None
        el = Element(name, attrib)
        stack[-1][0].append(el)
        stack[-1][1] = el
        if name not in _VOID:
            stack.append([el, None])
    if phase not in ("after body", "after html"):
        return None
    return root


PARSED = {"fast": 0, "tinyhtml5": 0}  # documents of this process parsed each way (tests, bench)


def init_html(doc, string, base_url, url_fetcher, media_type) -> bool:
    """Set up WeasyPrint's ``HTML`` object ``doc`` from ``string`` parsed by :func:`parse`, as
    ``HTML.__init__`` does from tinyhtml5's tree (the document has no ``<base>``: the base URL is
    the one given); ``False`` (nothing done) when ``string`` is outside the subset."""
    root = parse(string) if isinstance(string, str) else None
    if root is None:
        PARSED["tinyhtml5"] += 1
        return False
    import cssselect2
    from weasyprint.urls import URLFetcher, ensure_url

    doc.base_url = None if base_url is None else ensure_url(str(base_url))
    doc.url_fetcher = URLFetcher() if url_fetcher is None else url_fetcher
    doc.media_type = media_type
    doc.wrapper_element = cssselect2.ElementWrapper.from_html_root(root, content_language=None)
    doc.etree_element = doc.wrapper_element.etree_element
    PARSED["fast"] += 1
    return True
