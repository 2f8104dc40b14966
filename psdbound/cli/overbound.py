"""``psdbound overbound``: Gaussian overbounds of an error distribution per elevation bin.

Registered by :mod:`psdbound.cli.main` through :func:`add_parser`. Reads the
samples with :func:`psdbound.aviation.read_samples` -- or, with ``--code``,
computes them from a RINEX observation file: code multipath by carrier
levelling (:func:`psdbound.isolation.isolate_code_multipath`, elevations
from ``--nav``) -- runs
:func:`psdbound.aviation.overbound_by_elevation`, prints the summary and,
with ``--out``, writes ``overbound.json`` (sigma, bias and inflation factor per
bin) and ``overbound_qq.png``. Bad input (NaN, too few samples in a bin,
the bin is named) is exit 2. Each bin reports ``n``, ``n_eff`` and the
overbound at ``--confidence`` (``*_upper``). With ``--code`` a sparse bin is a property of
the station's sky (few satellites above 60 deg at high latitude): it is left
out and named (``note:`` and ``bins_left_out``); exit 2 only when no bin
holds ``--min-samples``.
"""

from __future__ import annotations

import argparse
from typing import Any

from psdbound.cli.actions import Once
from psdbound.cli.config_file import add_config_option
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
        help="Gaussian overbound (paired, two-step or CDF) of error samples per elevation bin",
        description="Overbound the distribution of error samples (code or carrier "
        "multipath, normalised errors, ...) by a Gaussian in each elevation bin; print "
        "bias, sigma and the inflation factor sigma/std per bin, the effective sample size "
        "n_eff of each bin (from the series' autocorrelation; samples in time order) and the "
        "bounds at --confidence.",
        epilog="examples: psdbound overbound errors.csv --edges 5 15 30 60 90 --out out/ ; "
        "psdbound overbound ESBC.crx.gz --nav ESBC_MN.rnx.gz --code C1C --out out/",
    )
    p.add_argument(
        "samples",
        help="CSV/text with 'error' [and 'elevation'] columns, or .npy; with --code a RINEX "
        "observation file (required)",
    )
    p.add_argument(
        "--code",
        help="compute the samples: code multipath of this pseudorange code (C1C: MP "
        "combination) or pair (C1C,C5Q: ionosphere-free) by carrier levelling, from the "
        "RINEX file SAMPLES (default: none, SAMPLES holds the errors)",
    )
    p.add_argument(
        "--nav", action=Once, help="navigation or SP3 file for elevations (required with --code)"
    )
    p.add_argument("--system", default="G", help="satellite system letter with --code (default: G)")
    p.add_argument(
        "--min-arc-s",
        type=float,
        default=600.0,
        help="shortest carrier-levelling arc with --code, s (default: 600)",
    )
    p.add_argument(
        "--method",
        choices=("paired", "two_step", "cdf"),
        default="paired",
        help="overbound construction: paired (bias and sigma per bin, every point "
        "constrained), two_step (about the median; assumes symmetric unimodal true errors) "
        "or cdf (zero-mean or --bias) (default: paired)",
    )
    p.add_argument(
        "--confidence",
        type=float,
        default=0.95,
        help="confidence level of the upper bounds of bias, sigma and inflation, from the "
        "effective sample size of each bin, dimensionless in (0, 1) (default: 0.95)",
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
        default=None,
        help="two_step / cdf only: ignore the core where the normal quantile of the tail "
        "is below this, dimensionless (default: 0.25; paired constrains every point)",
    )
    p.add_argument(
        "--min-samples",
        type=int,
        default=100,
        help="fewest samples per non-empty bin, count (default: 100)",
    )
    p.add_argument("--unit", default="m", help="unit of the samples, for display (default: m)")
    p.add_argument("--out", help="folder for overbound.json and overbound_qq.png (default: none)")
    add_config_option(p)
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
    from psdbound.aviation import write_overbound
    from psdbound.common.outputs import check_writable_folder

    _check_options(args)
    if args.out:
        check_writable_folder(args.out, option="--out")
    res, extra = _code_overbound(args) if args.code else (_samples_overbound(args), {})
    print(res.summary())
    if args.out:
        for f in write_overbound(res, args.out, extra=extra):
            print(f"wrote {f}")
    return 0


def _check_options(args: argparse.Namespace) -> None:
    """Refuse inconsistent options; fill the method-dependent default of ``--min-abs-z``."""
    if args.min_samples < 2:
        raise InputError(f"--min-samples must be >= 2, got {args.min_samples}")
    if not 0.0 < args.confidence < 1.0:
        raise InputError(f"--confidence must be in (0, 1), got {args.confidence}")
    if args.method == "paired" and args.min_abs_z is not None:
        raise InputError(
            "--min-abs-z applies to --method two_step / cdf: the paired overbound exempts no core"
        )
    if args.min_abs_z is None:
        args.min_abs_z = 0.25
    if not args.code and args.nav:
        raise InputError("--nav is only used with --code (SAMPLES is a samples file)")


def _samples_overbound(args: argparse.Namespace) -> Any:
    """Overbound the errors of a samples file (``SAMPLES``)."""
    from psdbound.aviation import overbound_by_elevation, read_samples

    errors, elevation = read_samples(args.samples)
    try:
        return overbound_by_elevation(
            errors,
            elevation,
            edges_deg=args.edges,
            method=args.method,
            bias=args.bias,
            min_abs_z=args.min_abs_z,
            min_samples=args.min_samples,
            unit=args.unit,
            confidence=args.confidence,
        )
    except InputError as exc:
        raise InputError(exc.reason, path=args.samples) from None


def _code_overbound(args: argparse.Namespace) -> tuple[Any, dict[str, Any]]:
    """Overbound the code multipath of ``args.samples`` (a RINEX file); name sparse bins."""
    from psdbound.aviation.code_samples import (
        code_multipath_from_files,
        describe_code_series,
        overbound_code_series,
    )

    if not args.nav:
        raise InputError("--code needs --nav (a navigation or SP3 file) for the elevations")
    if not args.min_arc_s > 0:
        raise InputError(f"--min-arc-s must be > 0 s, got {args.min_arc_s}")
    if not 1 <= len([c for c in args.code.split(",") if c.strip()]) <= 2:
        raise InputError(f"--code takes one code or two separated by a comma, got {args.code!r}")
    series = code_multipath_from_files(
        args.samples,
        args.nav,
        args.code,
        system=args.system,
        elevation_mask_deg=max(0.0, min(args.edges)),
        min_length_s=args.min_arc_s,
    )
    print(series.summary())
    try:
        res, sparse = overbound_code_series(
            series,
            args.edges,
            method=args.method,
            min_samples=args.min_samples,
            min_abs_z=args.min_abs_z,
            bias=args.bias,
            confidence=args.confidence,
        )
    except InputError as exc:
        raise InputError(exc.reason, path=args.samples) from None
    for note in sparse:
        print(f"note: {note}")
    info = describe_code_series(series, min_length_s=args.min_arc_s)
    return res, {"code_multipath": {"source": str(args.samples), **info, "bins_left_out": sparse}}
