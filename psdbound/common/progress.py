"""Progress of long commands on stderr: a live counter on a terminal, plain lines in a log.

A carriage-return counter redraws one line on a terminal; written to a file
or a CI log it leaves one long line full of carriage returns. :func:`counter` returns a
``progress(done, total)`` callback that redraws on a terminal and otherwise
prints a plain line at every tenth of the work and at the end.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import TextIO

__all__ = ["counter"]

#: Steps of the work at which a plain (non-terminal) stream gets a line.
LOG_STEPS = 10


def counter(label: str, *, stream: TextIO | None = None) -> Callable[[int, int], None]:
    """Return a ``progress(done, total)`` callback that reports ``label`` on ``stream``.

    Parameters
    ----------
    label : str
        What is counted (``"station-days computed"``).
    stream : text stream, optional
        Where to write (default: ``sys.stderr`` at call time).

    Returns
    -------
    callable
        ``progress(done, total)``: on a terminal, ``done/total label``
        redrawn in place and a newline at the end; elsewhere a line when
        ``done`` crosses each tenth of ``total`` (and at the end).
    """
    last = [-1]

    def progress(done: int, total: int) -> None:
        out = stream or sys.stderr
        if getattr(out, "isatty", lambda: False)():
            print(f"\r  {done}/{total} {label}", end="", file=out, flush=True)
            if done >= total:
                print(file=out)
            return
        step = (LOG_STEPS * done) // max(total, 1)
        if step > last[0] or done >= total:
            last[0] = step
            print(f"  {done}/{total} {label}", file=out, flush=True)

    return progress
