"""``psdbound overbound``: Gaussian overbounds of an error distribution per elevation bin.

Registered by :mod:`psdbound.cli.main` through :func:`add_parser`. Reads the
samples with :func:`psdbound.aviation.read_samples`, runs
:func:`psdbound.aviation.overbound_by_elevation`, prints the summary and,
with ``--out``, writes ``result.json`` (sigma, bias and inflation factor per
bin) and ``overbound_qq.png``. Bad input (NaN, too few samples in a bin,
the bin is named) is exit 2.
"""

from __future__ import annotations

import argparse
from typing import Any

from psdbound.errors import InputError

__all__ = ["add_parser", "run"]


def add_parser(subparsers: Any) -> None:
    """Add the ``overbound`` subcommand to an ``add_subparsers()`` object.

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        From :meth:`argparse.ArgumentParser.add_subparsers`.
    """
    p = subparsers.add_parser(
        "overbound",
        help="Gaussian overbound (two-step or CDF) of error samples per elevation bin",
        description="Overbound the distribution of error samples (code or carrier "
        "multipath, normalised errors, ...) by a Gaussian in each elevation bin; print "
        "sigma and the inflation factor sigma/std per bin.",
        epilog="example: psdbound overbound errors.csv --edges 5 15 30 60 90 --out out/",
    )
    p.add_argument(
        "samples", help="CSV/text with 'error' [and 'elevation'] columns, or .npy (required)"
    )
    p.add_argument(
        "--method",
        choices=("two_step", "cdf"),
        default="two_step",
        help="overbound construction (default: two_step)",
    )
    p.add_argument(
        "--edges",
        type=float,
        nargs="+",
        default=[5.0, 15.0, 30.0, 45.0, 60.0, 90.0],
        help="elevation bin edges, deg (default: 5 15 30 45 60 90)",
    )
    p.add_argument(
        "--bias",
        type=float,
        default=0.0,
        help="paired bias of --method cdf, in the samples unit, m by default (default: 0)",
    )
    p.add_argument(
        "--min-abs-z",
        type=float,
        default=0.25,
        help="ignore the core where the normal quantile of the tail is below "
        "this, dimensionless (default: 0.25)",
    )
    p.add_argument(
        "--min-samples",
        type=int,
        default=100,
        help="fewest samples per non-empty bin, count (default: 100)",
    )
    p.add_argument("--unit", default="m", help="unit of the samples, for display (default: m)")
    p.add_argument("--out", help="folder for result.json and overbound_qq.png (default: none)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Run ``psdbound overbound``.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options of :func:`add_parser`.

    Returns
    -------
    int
        0.

    Raises
    ------
    InputError
        Unreadable samples, NaN, a bin with too few samples, bad options.
    """
    from psdbound.aviation import overbound_by_elevation, read_samples, write_overbound
    from psdbound.common.outputs import check_writable_folder

    if args.min_samples < 2:
        raise InputError(f"--min-samples must be >= 2, got {args.min_samples}")
    if args.out:
        check_writable_folder(args.out, option="--out")
    errors, elevation = read_samples(args.samples)
    try:
        res = overbound_by_elevation(
            errors,
            elevation,
            edges_deg=args.edges,
            method=args.method,
            bias=args.bias,
            min_abs_z=args.min_abs_z,
            min_samples=args.min_samples,
            unit=args.unit,
        )
    except InputError as exc:
        raise InputError(exc.reason, path=args.samples) from None
    print(res.summary())
    if args.out:
        for f in write_overbound(res, args.out):
            print(f"wrote {f}")
    return 0
