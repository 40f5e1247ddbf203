"""Figures the README and the guides repeat say the same (issue 53, item 6: the README and the
guides disagreed on the stadium curve's time): each repeated figure is written one way, and
this test finds every place that states it."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]

#: figure -> (the one way it is written, a pattern catching any statement of it)
FIGURES = {
    "the wall model's stadium curve": (
        "about 2 s", re.compile(r"([\w.–]+(?: [\w.–]+)?\s+s)\s+(?:a|per) stadium curve")),
    "the wall model's dome curve": (
        "about 0.2 s", re.compile(r"([\w.–]+(?: [\w.–]+)?\s+s)\s+(?:a|per) dome curve")),
}


@pytest.mark.parametrize("figure", sorted(FIGURES))
def test_a_repeated_figure_is_written_one_way(figure):
    canonical, pattern = FIGURES[figure]
    seen = []
    for path in DOCS:
        text = " ".join(path.read_text(encoding="utf-8").split())  # lines joined
        for m in pattern.finditer(text):
            seen.append((path.relative_to(ROOT).as_posix(), m.group(1)))
    assert len(seen) >= 2, f"{figure}: stated {len(seen)} time(s); the test must find them"
    assert [s for s in seen if s[1] != canonical] == []
