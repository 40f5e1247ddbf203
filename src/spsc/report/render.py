"""HTML of the report: the Jinja2 templates in ``templates/`` filled with the sections' data.

Autoescaping is on, so every text from a run (labels, error messages) is escaped; numbers are
formatted by the ``num`` filter (``—`` for a missing or non-finite value).
"""

from __future__ import annotations

import math
from pathlib import Path

from spsc.report.page_check import LONG_TABLE_ROWS, outline

__all__ = ["environment", "num", "render_page", "draw_figures", "with_contents", "CONTENTS"]

TEMPLATES = Path(__file__).with_name("templates")


def num(v, fmt: str = ".3g") -> str:
    """``v`` formatted with ``fmt``; ``—`` for None, NaN or ±inf; a value that rounds to
    zero without a sign (``-0``, ``+0.0`` read as a change that is not there)."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "—"
    text = format(v, fmt)
    if text[:1] in "+-" and not text.strip("+-0.%e"):
        return text[1:]
    return text


def environment():
    """The Jinja2 environment of the report's templates (autoescaped, strict undefined)."""
    import jinja2

    env = jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATES),
                             autoescape=jinja2.select_autoescape(["html", "j2"]),
                             undefined=jinja2.StrictUndefined, trim_blocks=True,
                             lstrip_blocks=True)
    env.filters["num"] = num
    env.globals["long_table_rows"] = LONG_TABLE_ROWS
    return env


def render_page(context: dict, template: str = "report.html.j2") -> str:
    """The page of ``template`` from ``context`` (see :func:`~.report.build_report`), with its
    table of contents where the template marks it (:func:`with_contents`)."""
    return with_contents(environment().get_template(template).render(**context))


#: Where a template wants its table of contents.
CONTENTS = "<!-- contents -->"


def with_contents(page: str) -> str:
    """``page`` with :data:`CONTENTS` replaced by a list of links to the ``<h2 id=…>``
    headings that follow it, made from the page itself: every entry has its anchor, every
    section after the contents its entry."""
    if CONTENTS not in page:
        return page
    import html

    at = page.index(CONTENTS)
    heads = [v for k, v in outline(page[at:]).events if k == "h2" and v[0]]
    items = "".join(f'<li><a href="#{html.escape(i)}">{html.escape(text)}</a></li>'
                    for i, text in heads)
    nav = f'<nav id="contents"><p><b>Contents</b></p><ol>{items}</ol></nav>'
    return page.replace(CONTENTS, nav, 1)


def draw_figures(figs: Path, specs) -> tuple[dict, list[str]]:
    """Draw each ``(name, function, *args)`` of ``specs`` as ``function(figs / name.png,
    *args)`` (a function may return None: nothing to draw). Returns ``{name: "figures/FILE"}``
    and a note per figure that could not be drawn (e.g. a render without an OpenGL context):
    a figure is not worth the page it is on."""
    figures, notes = {}, []
    for name, function, *args in specs:
        try:
            p = function(figs / f"{name}.png", *args)
            if p is not None:
                figures[name] = f"figures/{Path(p).name}"
        except Exception as exc:
            notes.append(f"{name} figure not drawn: {type(exc).__name__}: {exc}")
    return figures, notes
