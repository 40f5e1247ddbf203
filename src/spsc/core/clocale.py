"""The C library's locale, kept across a call into a library that sets it.

lib3mf sets the process's locale to ``"C"`` when it writes or reads a 3MF (so numbers print with
a point) and leaves it there; with ``LC_CTYPE`` at ``"C"``, Python's default text encoding falls
to ASCII and a later ``open()`` or ``Path.write_text`` without an encoding fails on a "Δ" or a
"≤" (found in the tests: a JSON read after a 3MF was written in the same process).
"""

from __future__ import annotations

import functools
import locale

__all__ = ["keeps_locale"]


def keeps_locale(func):
    """``func`` with the locale of every category restored when it returns or raises."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        saved = locale.setlocale(locale.LC_ALL)
        try:
            return func(*args, **kwargs)
        finally:
            locale.setlocale(locale.LC_ALL, saved)

    return wrapper
