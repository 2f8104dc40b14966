"""``psdbound campaign``: many files, days and stations; every bound tested on held-out days."""

from __future__ import annotations

import argparse
import sys

from psdbound.cli.exit_codes import EXIT_NOT_BOUNDED, EXIT_OK

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``campaign`` subcommand."""
    p = sub.add_parser(
        "campaign",
        help="fit many station-days on Dask and test each day against the others' bound",
        description="Group observation files by station and day, fit every station-day as a "
        "Dask task (cached by input hash: a re-run computes only what changed), pool each "
        "station's days, and test every day against the bound of the station's other days. "
        "Writes campaign.json, campaign.html and campaign.pdf.",
    )
    p.add_argument("obs", nargs="+", help="observation files (any stations and days; required)")
    p.add_argument(
        "--nav",
        nargs="+",
        action="extend",
        required=True,
        help="navigation/SP3 files: one, or one per day (matched by day of year; required)",
    )
    p.add_argument(
        "--out", default="reports/campaign", help="output folder (default: reports/campaign)"
    )
    p.add_argument(
        "--workers",
        type=int,
        default=2,
        help="local Dask worker processes, count (default: 2; 0 runs in this process)",
    )
    p.add_argument(
        "--scheduler",
        help="address of a running Dask scheduler (overrides --workers; default: a local cluster)",
    )
    p.add_argument("--cache-dir", help="task cache folder (default: the psdbound cache)")
    p.add_argument("--no-pdf", action="store_true", help="skip campaign.pdf")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Run the campaign, write its outputs, print the summary; return the exit code."""
    from psdbound.campaign import run_campaign, write_campaign
    from psdbound.common.options import Number
    from psdbound.common.outputs import check_writable_folder

    Number(lo=0, hi=256, integer=True)("--workers", args.workers)
    check_writable_folder(args.out, option="--out")

    def progress(done: int, total: int) -> None:
        bar = "#" * int(30 * done / max(total, 1))
        print(f"\r[psdbound] station-days {done}/{total} [{bar:<30}]", end="", file=sys.stderr,
              flush=True)  # fmt: skip
        if done == total:
            print(file=sys.stderr)

    res = run_campaign(args.obs, args.nav, workers=args.workers, scheduler=args.scheduler,
                       cache_dir=args.cache_dir, progress=progress)  # fmt: skip
    files = write_campaign(res, args.out, pdf=not args.no_pdf)
    print(res.summary())
    for f in files.values():
        print(f)
    return EXIT_OK if all(d["ok"] for d in res.days) else EXIT_NOT_BOUNDED
