"""Progress of a long run on stderr, as a user reads it: tqdm's bar on a terminal, plain lines
where stderr is a file or a pipe (a CI log, ``2> run.log``), which tqdm fills with carriage
returns and cursor moves (``ESC[A``) that nothing redraws.

:func:`progress_bar` takes tqdm's keywords and returns either. The plain one says where it is
when it starts, every ``every_s`` seconds while it runs (only after a change) and when it
ends, each a line ``DESC: N/TOTAL UNIT, ELAPSED (POSTFIX)``. A run whose end is not known
(``total`` None: a budget it may stop short of, a search that ends on its goal) gives no
total and no time left, rather than a wrong one.
"""

from __future__ import annotations

import sys
import time

__all__ = ["progress_bar", "PlainProgress", "is_terminal"]


def is_terminal(stream) -> bool:
    """Whether ``stream`` is a terminal a bar can redraw."""
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


def progress_bar(*, desc: str, total=None, unit: str = "it", disable: bool = False,
                 file=None, initial: float = 0, every_s: float = 10.0, **tqdm_kwargs):
    """tqdm's bar on a terminal, :class:`PlainProgress` otherwise (``disable``: neither)."""
    from tqdm import tqdm

    file = sys.stderr if file is None else file
    if disable or is_terminal(file):
        return tqdm(desc=desc, total=total, unit=unit, disable=disable, file=file,
                    initial=initial, **tqdm_kwargs)
    return PlainProgress(desc, total, unit, file, initial, every_s)


def _clock(seconds: float) -> str:
    s = int(round(seconds))
    return f"{s // 60} min {s % 60:02d} s" if s >= 60 else f"{seconds:.1f} s"


class PlainProgress:
    """tqdm's bar API as a plain line now and then: ``n``, ``total`` (settable), ``update``,
    ``set_postfix``, ``set_postfix_str``, ``set_description``, ``write``, ``refresh``,
    ``close``, a context manager."""

    def __init__(self, desc: str, total, unit: str, file, initial: float = 0,
                 every_s: float = 10.0):
        self.desc, self.total, self.unit, self.file = desc, total, unit, file
        self.n, self.postfix, self.every = initial, "", every_s
        self.t0 = time.monotonic()
        self.closed = False
        self._said = None  # n at the last line
        self._last = self.t0
        self._line()

    def _line(self, end: str = "") -> None:
        n = f"{self.n:g}" if isinstance(self.n, float) else str(self.n)
        of = f"/{self.total:g}" if self.total else ""
        post = f" ({self.postfix})" if self.postfix else ""
        print(f"{self.desc}: {n}{of} {self.unit}, {_clock(time.monotonic() - self.t0)}"
              f"{post}{end}", file=self.file, flush=True)
        self._said, self._last = self.n, time.monotonic()

    def update(self, k: float = 1) -> None:
        self.n += k
        if time.monotonic() - self._last >= self.every and self.n != self._said:
            self._line()

    def refresh(self) -> None:
        if self.n != self._said:
            self._line()

    def set_postfix_str(self, s: str = "", refresh: bool = True) -> None:
        self.postfix = str(s)

    def set_postfix(self, ordered_dict=None, refresh: bool = True, **kwargs) -> None:
        """tqdm's ``k=v, ...`` postfix."""
        items = {**(ordered_dict or {}), **kwargs}
        self.postfix = ", ".join(f"{k}={v}" for k, v in items.items())

    def write(self, s: str, file=None) -> None:
        """A line of its own (tqdm's ``write``: a message between the bar's lines)."""
        print(s, file=self.file if file is None else file, flush=True)

    def set_description(self, desc: str, refresh: bool = True) -> None:
        self.desc = str(desc)

    def close(self) -> None:
        if not self.closed:
            self.closed = True
            self._line(" (done)")

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()
