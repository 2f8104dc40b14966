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
    p.add_argument("result", help="result.json written by psdbound fit (required)")
    p.add_argument("--out", help="output folder (default: the result file's folder)")
    p.add_argument("--no-pdf", action="store_true", help="skip the PDF report")
    p.add_argument(
        "--overwrite",
        action="store_true",
        help="write into an existing folder that is not a psdbound output (psdbound's files "
        "are replaced, nothing else is touched)",
    )
    g = p.add_mutually_exclusive_group()
    g.add_argument("--quiet", action="store_true", help="print only errors")
    g.add_argument("--verbose", action="store_true", help="print tracebacks on errors")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Re-render; return the exit code.

    The output folder is checked before the result is read and the figures
    drawn: an existing file, or a folder that is not a psdbound output
    (without ``--overwrite``), is refused. Re-rendered in the result file's
    own folder, the run's other files stay: its ``series.csv.gz``, and its
    ``report.pdf`` with ``--no-pdf``.
    """
    import psdbound
    from psdbound.common.outputs import check_output_folder
    from psdbound.reports import write_report_folder

    out = Path(args.out) if args.out else Path(args.result).resolve().parent
    result = psdbound.load(args.result)
    option = "--out" if args.out else "the result file's folder (the default --out)"
    check_output_folder(out, overwrite=args.overwrite, option=option)
    own = out.resolve() == Path(args.result).resolve().parent
    keep = ("series.csv.gz",) + (("report.pdf",) if args.no_pdf else ()) if own else ()
    paths = write_report_folder(
        result.document,
        out,
        pdf=not args.no_pdf,
        overwrite=args.overwrite,
        option=option,
        keep=keep,
    )
    if not args.quiet:
        for p in paths.values():
            print(p)
    return 0
