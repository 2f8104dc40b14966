"""Exceptions raised by psdbound.

Every error caused by what the user gave us (a file, an option, a value) is an
:class:`InputError`. Its message names the file, and where it helps the line
number, satellite or signal, and says what was expected. The command-line
interface turns an :class:`InputError` into a one-line message and exit code 2.
"""

from __future__ import annotations

from os import PathLike

__all__ = ["InputError", "NoDataError"]


class InputError(ValueError):
    """Bad user input: a file, option or value psdbound cannot use.

    Parameters
    ----------
    message : str
        What is wrong and what was expected.
    path : str or path-like, optional
        The file concerned; prefixed to the message.
    line : int, optional
        1-based line number in the (decompressed) file, when known.
    """

    def __init__(
        self,
        message: str,
        *,
        path: str | PathLike[str] | None = None,
        line: int | None = None,
    ) -> None:
        self.path = None if path is None else str(path)
        self.line = line
        self.reason = message
        where = ""
        if self.path is not None:
            where = self.path if line is None else f"{self.path}, line {line}"
            where += ": "
        super().__init__(where + message)


class NoDataError(InputError):
    """The input is well formed but holds nothing usable for the request.

    Examples: a requested system with no epochs, every arc shorter than the
    minimum length, no satellite above the elevation mask.
    """
