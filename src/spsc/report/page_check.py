"""What a reader of an HTML page meets, read back from the page itself: its headings and ids,
its tables (rows, whether collapsed in ``<details>``), its images, its links; and which of its
links point nowhere. The report's, the sweep's and the design's pages are checked with it (a
moved output folder must still resolve every link: every path is relative to the page).

Standard library only (:mod:`html.parser`), so a test reads a page without a browser.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlparse

__all__ = ["Outline", "outline", "broken_links", "LONG_TABLE_ROWS"]

#: A table with more body rows than this is collapsed in ``<details>`` (render.py's macro).
LONG_TABLE_ROWS = 12


@dataclass
class Outline:
    """The page in reading order: ``events`` is a list of ``(kind, value)`` with kind
    ``"h2"``/``"h3"`` (id, text), ``"table"`` (rows, inside ``<details>``), ``"img"`` (src),
    ``"section"`` (id); ``ids`` every id; ``links`` every href and src."""

    events: list = field(default_factory=list)
    ids: set = field(default_factory=set)
    links: list = field(default_factory=list)

    def index(self, kind: str, predicate=lambda v: True) -> int | None:
        """Position of the first event of ``kind`` whose value passes ``predicate``."""
        return next((i for i, (k, v) in enumerate(self.events)
                     if k == kind and predicate(v)), None)

    def tables(self) -> list[tuple[int, bool]]:
        """(rows, collapsed) of every table, in order."""
        return [v for k, v in self.events if k == "table"]


class _Reader(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.out = Outline()
        self.details = 0
        self.tables: list[list] = []  # open tables: [rows, collapsed, event index]
        self.heading: list | None = None  # [tag, id, text parts]

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if a.get("id"):
            self.out.ids.add(a["id"])
        for key in ("href", "src"):
            if a.get(key) is not None:
                self.out.links.append(a[key])
        if tag == "details":
            self.details += 1
        elif tag == "table":
            self.out.events.append(("table", None))
            self.tables.append([0, self.details > 0, len(self.out.events) - 1])
        elif tag == "tr" and self.tables:
            self.tables[-1][0] += 1
        elif tag == "img":
            self.out.events.append(("img", a.get("src")))
        elif tag in ("h2", "h3"):
            self.heading = [tag, a.get("id"), []]
        elif tag in ("section", "nav") and a.get("id"):
            self.out.events.append(("section", a["id"]))

    def handle_endtag(self, tag):
        if tag == "details":
            self.details -= 1
        elif tag == "table" and self.tables:
            rows, collapsed, at = self.tables.pop()
            self.out.events[at] = ("table", (max(rows - 1, 0), collapsed))  # minus the head
        elif tag in ("h2", "h3") and self.heading:
            t, i, parts = self.heading
            self.out.events.append((t, (i, " ".join("".join(parts).split()))))
            self.heading = None

    def handle_data(self, data):
        if self.heading is not None:
            self.heading[2].append(data)


def outline(html: str) -> Outline:
    """The :class:`Outline` of a page's HTML."""
    reader = _Reader()
    reader.feed(html)
    reader.close()
    return reader.out


def broken_links(page) -> list[str]:
    """The links of the page file ``page`` that point nowhere: a ``#id`` not on the page, a
    relative path with no file under the page's folder, or an absolute local path (a page
    that leans on where it was written). Web addresses are not followed."""
    page = Path(page)
    o = outline(page.read_text(encoding="utf-8"))
    bad = []
    for link in o.links:
        u = urlparse(link)
        if u.scheme in ("http", "https", "mailto", "data"):
            continue
        if u.scheme or u.netloc or u.path.startswith("/"):
            bad.append(link)
        elif not u.path:
            if u.fragment and u.fragment not in o.ids:
                bad.append(link)
        elif not (page.parent / unquote(u.path)).exists():
            bad.append(link)
    return bad
