"""Makes the verification models in ``tests/verify/`` importable as ``verify`` (they are not
part of the installed package)."""

import sys
from pathlib import Path

_TESTS = str(Path(__file__).resolve().parent)
if _TESTS not in sys.path:
    sys.path.insert(0, _TESTS)
