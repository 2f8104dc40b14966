"""``psdbound report``: re-render the HTML and PDF reports from a result file."""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``report`` subcommand."""
    p = sub.add_parser(
        "report",
        help="re-render report.html and report.pdf from a result.json",
        description="Redraw every figure and the reports from a result file alone.",
    )
    p.add_argument("result", help="result.json written by psdbound fit")
    p.add_argument("--out", help="output folder (default: the result file's folder)")
    p.add_argument("--no-pdf", action="store_true", help="skip the PDF report")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--quiet", action="store_true", help="print only errors")
    g.add_argument("--verbose", action="store_true", help="print tracebacks on errors")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Re-render; return the exit code."""
    import psdbound

    result = psdbound.load(args.result)
    out = Path(args.out) if args.out else Path(args.result).resolve().parent
    paths = result.report(out, pdf=not args.no_pdf)
    if not args.quiet:
        for p in paths.values():
            print(p)
    return 0
