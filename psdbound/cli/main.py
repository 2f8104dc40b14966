"""Argument parsing and dispatch for ``python -m psdbound``."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from psdbound import __version__
from psdbound.errors import InputError

__all__ = ["main", "build_parser", "EXIT_OK", "EXIT_BAD_INPUT", "EXIT_INTERNAL"]

EXIT_OK = 0
EXIT_INTERNAL = 1
EXIT_BAD_INPUT = 2

# subcommand modules psdbound.cli.<name>, each with add_parser(sub) and run(args)
_COMMANDS = ("inspect", "fit", "cutoff", "validate", "simulate", "report")

# subcommands whose pipeline stage has not landed yet, and the issue that brings it
_PENDING = {
    "fit": ("fit a PSD bound to RINEX observations (or the demo data)", 8),
    "cutoff": ("select the ionosphere high-pass cutoff frequency", 4),
    "validate": ("validate a cutoff with the Jacobi-Anger expansion", 6),
    "simulate": ("simulate observations with known multipath", 7),
    "report": ("re-render a report from a result file", 8),
}


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose usage errors are one line and exit code 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    """Return the ``psdbound`` argument parser with all subcommands."""
    parser = _Parser(
        prog="psdbound",
        description="Provable Gauss-Markov + white-noise PSD bounds of GNSS "
        "carrier-phase multipath.",
        epilog="Exit codes: 0 ok, 2 bad input, 1 internal error.",
    )
    parser.add_argument("--version", action="version", version=f"psdbound {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    import importlib

    for name in _COMMANDS:
        try:
            module = importlib.import_module(f"psdbound.cli.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"psdbound.cli.{name}":
                raise
            continue
        module.add_parser(sub)
    for name, (text, issue) in _PENDING.items():
        if name in sub.choices:
            continue
        sp = sub.add_parser(
            name, help=f"{text} (not available yet)", description=f"{text} (not available yet)"
        )
        sp.add_argument("args", nargs=argparse.REMAINDER, help=argparse.SUPPRESS)
        sp.set_defaults(func=_pending(name, issue))
    return parser


def _pending(name: str, issue: int):  # noqa: ANN202
    def run(args: argparse.Namespace) -> int:
        print(
            f"psdbound {name}: not available yet (this pipeline stage arrives with issue "
            f"#{issue}); nothing was computed.",
            file=sys.stderr,
        )
        return EXIT_INTERNAL

    return run


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the process exit code.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 on success, 2 on bad input, 1 on an internal error.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "command", None):
        parser.print_help()
        return EXIT_OK
    try:
        return int(args.func(args))
    except InputError as exc:
        print(f"psdbound {args.command}: error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("psdbound: interrupted", file=sys.stderr)
        return EXIT_INTERNAL
    except Exception as exc:  # an internal error: one line, traceback with --verbose
        if getattr(args, "verbose", False):
            import traceback

            traceback.print_exc()
        print(
            f"psdbound {args.command}: internal error: {type(exc).__name__}: {exc} "
            "(run with --verbose for the traceback; please report it)",
            file=sys.stderr,
        )
        return EXIT_INTERNAL
