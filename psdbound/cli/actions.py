"""Argument actions shared by the subcommands."""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import Any

__all__ = ["Once"]


class Once(argparse.Action):
    """Store an option's value; given twice it is a usage error (argparse keeps the last).

    For options of commands that take one file (``--nav`` of ``cutoff``,
    ``validate``, ``overbound``, ``budget``, ``simulate``): a second file
    would otherwise replace the first without a word.
    """

    def __call__(
        self,
        parser: argparse.ArgumentParser,
        namespace: argparse.Namespace,
        values: str | Sequence[Any] | None,
        option_string: str | None = None,
    ) -> None:
        """Store ``values``, or refuse a second occurrence (exit 2, one line)."""
        before = getattr(namespace, self.dest, self.default)
        if before is not self.default and before != self.default:
            parser.error(
                f"{option_string} given twice ({before} and {values}): this command takes one "
                f"file; give {option_string} once"
            )
        setattr(namespace, self.dest, values)
