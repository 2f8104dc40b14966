"""psdbound's own warnings: one category, one line, naming the file and line.

Readers and stages report what they repaired or ignored (a duplicated epoch
dropped, a header value that disagrees with the data) with :func:`warn`, so
the library user sees a :class:`PsdboundWarning` through Python's warnings
machinery and the command line prints it as one line. Warnings of numpy or
astropy are prevented where they arise or re-issued through :func:`warn`
with what they mean for the user.
"""

from __future__ import annotations

import os
import warnings

__all__ = ["PsdboundWarning", "format_location", "warn"]


class PsdboundWarning(UserWarning):
    """Something psdbound repaired, ignored or could not check; the result is still valid."""


def format_location(path: str | os.PathLike[str] | None, line: int | None = None) -> str:
    """Return ``"file, line N: "`` (or ``"file: "``, or ``""``) to prefix a message."""
    if path is None:
        return ""
    return f"{os.fspath(path)}, line {line}: " if line is not None else f"{os.fspath(path)}: "


def warn(
    message: str,
    *,
    path: str | os.PathLike[str] | None = None,
    line: int | None = None,
    stacklevel: int = 2,
) -> str:
    """Issue a :class:`PsdboundWarning`; return its full one-line text.

    Parameters
    ----------
    message : str
        What was repaired or ignored, and what was done instead.
    path : str or path-like, optional
        The file concerned (prefixed to the message).
    line : int, optional
        1-based line in the (decompressed) file.
    stacklevel : int, default 2
        As for :func:`warnings.warn`.

    Returns
    -------
    str
        The message as issued (also for storing with a result).
    """
    text = format_location(path, line) + " ".join(message.split())
    warnings.warn(text, PsdboundWarning, stacklevel=stacklevel + 1)
    return text
