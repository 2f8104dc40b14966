"""Process exit codes of ``python -m psdbound``."""

from __future__ import annotations

__all__ = ["EXIT_BAD_INPUT", "EXIT_INTERNAL", "EXIT_NOT_BOUNDED", "EXIT_OK"]

#: Success (``fit``: the verdict is "bounded").
EXIT_OK = 0
#: Internal error (a bug: please report it).
EXIT_INTERNAL = 1
#: Bad input: one line naming the file/option, nothing written.
EXIT_BAD_INPUT = 2
#: ``fit`` ran but gives no trustworthy bound (verdict "not-bounded"); outputs written.
EXIT_NOT_BOUNDED = 3
