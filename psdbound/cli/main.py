"""Argument parsing and dispatch for ``python -m psdbound``."""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import warnings
from collections.abc import Sequence

from psdbound.cli.config_file import apply_config
from psdbound.cli.exit_codes import EXIT_BAD_INPUT, EXIT_INTERNAL, EXIT_NOT_BOUNDED, EXIT_OK
from psdbound.errors import InputError
from psdbound.version import __version__

__all__ = [
    "main",
    "console",
    "build_parser",
    "EXIT_OK",
    "EXIT_BAD_INPUT",
    "EXIT_INTERNAL",
    "EXIT_NOT_BOUNDED",
]


# subcommand modules psdbound.cli.<name>, each with add_parser(sub) and run(args)
_COMMANDS = (
    "inspect",
    "fit",
    "export",
    "campaign",
    "cutoff",
    "validate",
    "simulate",
    "report",
    "overbound",
    "budget",
)


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose usage errors are one line and exit code 2."""

    #: The commands' parsers by name (set on the top-level parser by :func:`build_parser`).
    commands: dict[str, argparse.ArgumentParser]

    def options(self) -> list[argparse.Action]:
        """Return every argument of this parser (what ``--config`` keys may name)."""
        return list(self._actions)

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message}\n")


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """Return the ``psdbound`` argument parser.

    Parameters
    ----------
    command : str, optional
        Build only this subcommand (what :func:`main` does for a command
        line that names one: a usage error or ``--help`` then imports and
        builds one command's options, not all ten); None builds them all.

    Returns
    -------
    argparse.ArgumentParser
    """
    parser = _Parser(
        prog="psdbound",
        description="Gauss-Markov + white-noise PSD bounds of GNSS carrier-phase multipath, "
        "each with a stated confidence and a verdict.",
        epilog="Exit codes: 0 ok (fit: bounded); 3 fit ran but gives no trustworthy bound "
        "(verdict not-bounded, reasons printed, outputs written); 2 bad input (one line, "
        "nothing written); 1 internal error.",
    )
    parser.add_argument("--version", action="version", version=f"psdbound {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    import importlib

    for name in (command,) if command in _COMMANDS else _COMMANDS:
        importlib.import_module(f"psdbound.cli.{name}").add_parser(sub)
    parser.commands = dict(sub.choices)
    for p in parser.commands.values():  # every command can show an internal error's traceback
        with contextlib.suppress(argparse.ArgumentError):  # the command has its own --verbose
            p.add_argument(
                "--verbose", action="store_true", help="print the traceback of an internal error"
            )
    return parser


def _parse(parser: argparse.ArgumentParser, argv: list[str]) -> argparse.Namespace:
    """Parse ``argv``; arguments a command does not know are that command's usage error.

    (``parse_args`` reports them as the top-level program's, ``psdbound: error:``,
    without the command's name or usage.)
    """
    args, extra = parser.parse_known_args(argv)
    if extra:
        commands = getattr(parser, "commands", {})
        sub = commands.get(getattr(args, "command", None) or "", parser)
        sub.error(f"unrecognized arguments: {' '.join(extra)}")
    return args


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def _show_warnings(command: str, caught: list[warnings.WarningMessage], quiet: bool) -> None:
    """Print each distinct warning once, on one line (psdbound's own without a category)."""
    from psdbound.common.notices import PsdboundWarning

    if quiet:
        return
    seen = set()
    for w in caught:
        text = _one_line(w.message)
        if not issubclass(w.category, PsdboundWarning):
            text = f"{w.category.__name__}: {text}"
        if text not in seen:
            seen.add(text)
            print(f"psdbound {command}: warning: {text}", file=sys.stderr)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the process exit code.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 on success (``fit``: bounded), 3 (``fit``: not bounded), 2 on bad
        input (one line on stderr, nothing written), 1 on an internal error.
        Warnings are printed after the command, one line each (not on bad
        input, where the error line is the only output, nor with
        ``--quiet``).
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(argv[0] if argv else None)
    args = _parse(parser, argv)  # a usage error: one line and SystemExit(2)
    if not getattr(args, "command", None):
        parser.print_help()
        return EXIT_OK
    try:
        with warnings.catch_warnings(record=True) as caught:
            apply_config(args, argv)
            code = int(args.func(args))
        _show_warnings(args.command, caught, getattr(args, "quiet", False))
        return code
    except InputError as exc:
        print(f"psdbound {args.command}: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("psdbound: interrupted", file=sys.stderr)
        return EXIT_INTERNAL
    except RecursionError as exc:  # deeply nested input (e.g. TOML) is bad input, not a bug
        print(f"psdbound {args.command}: error: input nested too deeply ({exc})", file=sys.stderr)
        return EXIT_BAD_INPUT
    except Exception as exc:  # an internal error: one line, traceback with --verbose
        if getattr(args, "verbose", False):
            import traceback

            traceback.print_exc()
        print(
            f"psdbound {args.command}: internal error: {type(exc).__name__}: "
            f"{_one_line(exc)} (run with --verbose for the traceback; please report it)",
            file=sys.stderr,
        )
        return EXIT_INTERNAL


#: Commands that may leave helper processes (Dask) whose clean-up runs at interpreter exit.
_FULL_EXIT = frozenset({"campaign"})


def console(argv: Sequence[str] | None = None) -> None:
    """Run :func:`main` as a process and end it: the ``psdbound`` script and ``python -m``.

    Every output is written and closed when :func:`main` returns, so the
    process leaves with :func:`os._exit` after flushing its streams instead of
    the interpreter's teardown of the ~1,700 modules a fit loads (0.4 s of
    CPU on a station day). ``campaign``, whose Dask cluster cleans up at
    exit, leaves the ordinary way.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).
    """
    args = list(sys.argv[1:] if argv is None else argv)
    code = main(args)
    if _FULL_EXIT.intersection(args[:1]):
        sys.exit(code)
    import logging

    logging.shutdown()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe: nothing more can be said
            pass
    os._exit(code)
