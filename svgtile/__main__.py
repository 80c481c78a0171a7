"""``python -m svgtile``: the same command line as the ``svgtile`` script."""

from __future__ import annotations

import sys

from svgtile.cli.main import main

if __name__ == "__main__":
    sys.exit(main())
