"""The paper's printed bench figures (``data/paper_bench.json``), each with the section it is
printed in and the sentence that prints it: only numbers in the text, never digitised from a
plot (docs/design.md)."""

from __future__ import annotations

import functools
import json
from dataclasses import dataclass
from pathlib import Path

__all__ = ["PaperFigure", "PaperBench", "paper_bench", "DATA_FILE"]

DATA_FILE = Path(__file__).with_name("data") / "paper_bench.json"


@dataclass(frozen=True)
class PaperFigure:
    """One printed number: ``key`` (a :class:`~.metrics.DesignMetrics` field name), ``value``
    in ``unit`` and as ``printed`` in the text, the stiffness ``mode`` it belongs to ("" if
    both), where it is printed (``cite``) and the sentence that prints it (``quote``)."""

    key: str
    value: float
    printed: str
    unit: str
    mode: str
    cite: str
    quote: str


@dataclass(frozen=True)
class PaperBench:
    """The figures, their ``source`` (the paper), the ``conditions`` they were measured under
    and the catalogue ``material`` they apply to."""

    source: str
    conditions: str
    material: str
    figures: tuple[PaperFigure, ...]

    def get(self, key: str) -> PaperFigure | None:
        return next((f for f in self.figures if f.key == key), None)


@functools.lru_cache(maxsize=1)
def paper_bench(path: Path = DATA_FILE) -> PaperBench:
    """The paper's bench figures as frozen records."""
    data = json.loads(Path(path).read_text(encoding="utf-8"))
    return PaperBench(data["source"], data["conditions"], data["material"],
                      tuple(PaperFigure(**f) for f in data["figures"]))
