"""The ``python -m psdbound`` command line.

Exit codes: 0 success, 2 bad input (a file, option or value), 1 internal error.
"""

from __future__ import annotations

from psdbound.cli.main import EXIT_BAD_INPUT, EXIT_INTERNAL, EXIT_OK, main

__all__ = ["main", "EXIT_OK", "EXIT_BAD_INPUT", "EXIT_INTERNAL"]
