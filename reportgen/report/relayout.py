"""Lay out a part again from the first page its new HTML can change (issue #15).

A layout pass of a part after the first changes the print HTML from some element on (a table
cut elsewhere, a figure drawn at another scale or moved after some text); everything before
that element is the same HTML. WeasyPrint lays a document out page by page from a state per
page (``context.page_maker``: where the page resumes, the page type and counters) and can
itself remake a page from that state (``weasyprint.layout.page.remake_page``, used for page
based counters). So a page whose layout never read the changed element is the same page: it
is taken from the previous layout, and the pages are made anew from the first one that may
read it.

Which pages read an element: the page it starts on, and the one before it (WeasyPrint tries
to fit a block on the page before the one it lands on; a kept-together run such as a heading
and the block after it is laid out on one page). A page before those ends on a block before
the element and resumes after it, so it is laid out from the same HTML and the same state:
the same page. The pages taken over are those boxes as laid out before (their elements
mapped to the new document's, so that the split rules read one tree; their page type's
styles set in the new cascade, as ``remake_page`` does), and every page from the first
remade one on is laid out as WeasyPrint would: the PDF is the same, byte for byte, as a
layout from nothing (``tests/test_split_greedy.py`` compares them). Only a layout where
nothing page-based reaches across pages is taken over (no running elements, no
``target-counter`` lookups such as a contents, no named strings): a part of the note; the
note as one document (with its contents) is laid out in full.
"""

from __future__ import annotations

import copy
from contextlib import contextmanager
from dataclasses import dataclass


PAGES_TAKEN = [0]  # pages taken over from a layout before, in this process (tests)


@dataclass
class Laid:
    """What a later layout of the same part takes over from this one."""

    elements: list  # the elements of the HTML in document order
    signatures: list  # (tag, attributes, text, tail) of each element, in the same order
    pages: list  # the page boxes as make_all_pages made them (before their margin boxes)
    children: list  # each page box's children as made (layout_document replaces them)
    page_maker: list  # context.page_maker after the layout
    reused: int = 0  # pages taken over from the layout before
    reusable: bool = False  # its pages may be taken over (nothing page-based reaches across pages)


def _signature(el) -> tuple:
    return el.tag, tuple(sorted(el.attrib.items())), el.text, el.tail


def _first_change(before: list, after: list) -> int:
    """Index (document order) of the first element whose tag, attributes, text or tail differ,
    or of the first element one tree has and the other has not."""
    for i, (a, b) in enumerate(zip(before, after)):
        if a != b:
            return i
    return min(len(before), len(after))


def _elements_of(box) -> set:
    out = set()
    stack = [box]
    while stack:
        b = stack.pop()
        el = getattr(b, "element", None)
        if el is not None:
            out.add(id(el))
        stack.extend(getattr(b, "children", ()) or ())
    return out


def _remap(box, mapping: dict) -> None:
    """Point every box of a page taken over at the new document's element (same place)."""
    stack = [box]
    while stack:
        b = stack.pop()
        el = getattr(b, "element", None)
        if el is not None:
            new = mapping.get(id(el))
            if new is not None:
                b.element = new
        stack.extend(getattr(b, "children", ()) or ())


def _first_page_to_make(prev: Laid, change: int) -> int:
    """The first page whose layout may read element ``change`` (or a later one): the page
    before the first page holding a box of such an element; 0 when none is known."""
    late = {id(el) for el in prev.elements[change:]}
    for i, page in enumerate(prev.pages):
        if _elements_of(page) & late:
            return max(0, i - 1)
    return max(0, len(prev.pages) - 1)


@contextmanager
def incremental(prev: Laid | None, record: list):
    """Within it, WeasyPrint's ``layout_document`` takes over from ``prev`` the pages before the
    first one its new HTML may change, and every layout appends its :class:`Laid` to ``record``."""
    import weasyprint.layout as wl
    from weasyprint.layout.page import set_page_type_computed_styles

    original = wl.make_all_pages

    def make_all_pages(context, root_box, html, pages):
        elements = list(html.etree_element.iter())
        signatures = [_signature(el) for el in elements]
        laid = Laid(elements, signatures, [], [], [])
        if not pages and prev is not None and prev.reusable and len(prev.page_maker) > 1:
            change = _first_change(prev.signatures, signatures)
            first = _first_page_to_make(prev, change) if change < len(signatures) else 0
            if first > 0:
                mapping = {id(a): b for a, b in zip(prev.elements[:change], elements[:change])}
                pages = []
                for i in range(first):
                    page = prev.pages[i]
                    page.children = prev.children[i]
                    _remap(page, mapping)
                    # what remake_page does for a page besides laying it out: the styles of its
                    # page type and margin boxes (its page number) in this document's cascade
                    set_page_type_computed_styles(page.page_type, html, context.style_for)
                    pages.append(page)
                maker = [copy.deepcopy(item[:4]) + ({**item[4], "content_changed": False},)
                         for item in prev.page_maker[:first + 1]]
                maker[first][4]["content_changed"] = True
                context.page_maker = maker
                laid.reused = first
                PAGES_TAKEN[0] += first
        for page in original(context, root_box, html, pages):
            laid.pages.append(page)
            laid.children.append(page.children)
            yield page
        laid.page_maker = context.page_maker
        # what a page taken over would not give the later pages of a new layout: running
        # elements (a margin box showing an element of an earlier page), page counters looked
        # up from elsewhere (target-counter, a contents), named strings
        laid.reusable = not (any(any(v.values()) for v in context.running_elements.values())
                             or context.target_collector.counter_lookup_items
                             or any(any(v.values()) for v in context.string_set.values()))
        record.append(laid)

    wl.make_all_pages = make_all_pages
    try:
        yield
    finally:
        wl.make_all_pages = original
