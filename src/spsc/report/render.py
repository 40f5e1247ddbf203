"""HTML of the report: the Jinja2 templates in ``templates/`` filled with the sections' data.

Autoescaping is on, so every text from a run (labels, error messages) is escaped; numbers are
formatted by the ``num`` filter (``—`` for a missing or non-finite value).
"""

from __future__ import annotations

import math
from pathlib import Path

__all__ = ["environment", "num", "render_page", "draw_figures"]

TEMPLATES = Path(__file__).with_name("templates")


def num(v, fmt: str = ".3g") -> str:
    """``v`` formatted with ``fmt``; ``—`` for None, NaN or ±inf."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "—"
    return format(v, fmt)


def environment():
    """The Jinja2 environment of the report's templates (autoescaped, strict undefined)."""
    import jinja2

    env = jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATES),
                             autoescape=jinja2.select_autoescape(["html", "j2"]),
                             undefined=jinja2.StrictUndefined, trim_blocks=True,
                             lstrip_blocks=True)
    env.filters["num"] = num
    return env


def render_page(context: dict, template: str = "report.html.j2") -> str:
    """The report page from ``context`` (see :func:`~.report.build_report`)."""
    return environment().get_template(template).render(**context)


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
