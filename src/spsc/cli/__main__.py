"""``python -m spsc.cli``: the ``spsc`` command."""

import sys

from .main import main

sys.exit(main())
