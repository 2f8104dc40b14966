"""``psdbound overbound``: Gaussian overbounds of an error distribution per elevation bin.

Registered by :mod:`psdbound.cli.main` through :func:`add_parser`. Reads the
samples with :func:`psdbound.aviation.files.read_sample_file` -- or, with ``--code``,
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

psdbound's own series files (``fit --series``: ``series.csv.gz``;
``export``: ``.csv``, ``.csv.gz``, ``.nc``) are read as written: the rows the
fit screened out are left out with a warning that counts them by reason
(``--include-screened`` uses them), and the effective sample size never
correlates across satellites, gaps or rows left out. ``--edges`` must
increase; given for a file without elevations it is bad input (exit 2).
"""

from __future__ import annotations

import argparse
import dataclasses
from dataclasses import dataclass
from typing import Any

from psdbound.aviation.options import DEFAULT_EDGES_DEG, METHODS
from psdbound.cli.actions import Once
from psdbound.cli.config_file import add_config_option
from psdbound.cli.schema import CliOption, Schema, SchemaHelpFormatter, add_options, read_options
from psdbound.common.options import Boolean, Choice, Number, Tuple, check_fields, option
from psdbound.errors import InputError

__all__ = ["OPTIONS", "SCHEMA", "OverboundOptions", "add_parser", "run"]


@dataclass(frozen=True)
class OverboundOptions:
    """The options of ``psdbound overbound``.

    The names of the overbound's options are the keywords of
    :func:`psdbound.aviation.overbound_by_elevation` (same defaults);
    ``code``, ``nav``, ``system`` and ``min_length_s`` compute the samples
    from a RINEX file (:mod:`psdbound.aviation.code_samples`).
    """

    samples: str | None = None
    include_screened: bool = option(False, Boolean())
    code: str | None = None
    nav: str | None = None
    system: str = "G"
    min_length_s: float = option(600.0, Number(lo=0.0, lo_open=True, unit="s"))
    method: str = option("paired", Choice(METHODS, noun="overbound method"))
    confidence: float = option(0.95, Number(lo=0.0, hi=1.0, lo_open=True, hi_open=True))
    edges_deg: tuple[float, ...] = option(
        DEFAULT_EDGES_DEG, Tuple(Number(), min_len=1, what="elevation bin edges in deg")
    )
    bias: float = option(0.0, Number())
    min_abs_z: float | None = option(None, Number(lo=0.0, optional=True))
    min_samples: int = option(100, Number(lo=2, integer=True))
    unit: str = "m"
    out: str | None = None

    def __post_init__(self) -> None:
        check_fields(self)


#: The schema of ``overbound``'s options.
SCHEMA = Schema({"command": "psdbound.cli.overbound:OverboundOptions"})

_O = CliOption
_C = "command"
#: Every ``overbound`` option: its schema field, flag and help (all in ``options``).
OPTIONS: tuple[CliOption, ...] = (
    _O(
        _C,
        "samples",
        ("samples",),
        "CSV/text (plain or .gz) with 'error' [and 'elevation'] columns, .npy, or netCDF; "
        "psdbound's series files (fit --series, export: .csv.gz, .nc) as written; with "
        "--code a RINEX observation file (required)",
        None,
    ),
    _O(
        _C,
        "include_screened",
        ("--include-screened",),
        "also overbound the rows of a series file that the fit screened out (its "
        "'screened' column: ionosphere, implausible, short remainder); by default they "
        "are left out with a warning counting them",
        None,
        {"action": "store_true"},
    ),
    _O(
        _C,
        "code",
        ("--code",),
        "compute the samples: code multipath of this pseudorange code (C1C: MP "
        "combination) or pair (C1C,C5Q: ionosphere-free) by carrier levelling, from the "
        "RINEX file SAMPLES (default: none, SAMPLES holds the errors)",
        None,
    ),
    _O(
        _C,
        "nav",
        ("--nav",),
        "navigation or SP3 file for elevations (required with --code)",
        None,
        {"action": Once},
    ),
    _O(_C, "system", ("--system",), "satellite system letter with --code", None),
    _O(_C, "min_length_s", ("--min-arc-s",), "shortest carrier-levelling arc with --code, s", None),
    _O(
        _C,
        "method",
        ("--method",),
        "overbound construction: paired (bias and sigma per bin, every point "
        "constrained), two_step (about the median; assumes symmetric unimodal true errors) "
        "or cdf (zero-mean or --bias)",
        None,
    ),
    _O(
        _C,
        "confidence",
        ("--confidence",),
        "confidence level of the upper bounds of bias, sigma and inflation, from the "
        "effective sample size of each bin, dimensionless in (0, 1)",
        None,
    ),
    _O(
        _C,
        "edges_deg",
        ("--edges",),
        "elevation bin edges, deg",
        None,
        {"type": float, "nargs": "+"},
    ),
    _O(
        _C,
        "bias",
        ("--bias",),
        "paired bias of --method cdf, in the samples unit, m by default",
        None,
    ),
    _O(
        _C,
        "min_abs_z",
        ("--min-abs-z",),
        "two_step / cdf only: ignore the core where the normal quantile of the tail "
        "is below this, dimensionless (default: 0.25; paired constrains every point)",
        None,
    ),
    _O(_C, "min_samples", ("--min-samples",), "fewest samples per non-empty bin, count", None),
    _O(_C, "unit", ("--unit",), "unit of the samples, for display", None),
    _O(
        _C,
        "out",
        ("--out",),
        "folder for overbound.json and overbound_qq.png (default: none)",
        None,
    ),
)


def add_parser(subparsers: Any) -> None:
    """Add the ``overbound`` subcommand to an ``add_subparsers()`` object.

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        From :meth:`argparse.ArgumentParser.add_subparsers`.
    """
    p = subparsers.add_parser(
        "overbound",
        formatter_class=SchemaHelpFormatter,
        help="Gaussian overbound (paired, two-step or CDF) of error samples per elevation bin",
        description="Overbound the distribution of error samples (code or carrier "
        "multipath, normalised errors, ...) by a Gaussian in each elevation bin; print "
        "bias, sigma and the inflation factor sigma/std per bin, the effective sample size "
        "n_eff of each bin (from the series' autocorrelation; samples in time order) and the "
        "bounds at --confidence.",
        epilog="examples: psdbound overbound errors.csv --edges 5 15 30 60 90 --out out/ ; "
        "psdbound overbound ESBC.crx.gz --nav ESBC_MN.rnx.gz --code C1C --out out/",
    )
    add_options(p, OPTIONS, SCHEMA.spec, groups=(None,), defaults=SCHEMA.default)
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
        Unreadable samples (a binary file of no supported format, a truncated
        series file), NaN, every row screened out, a bin with too few samples,
        bad options (``--edges`` not increasing, or given for a file without
        elevations).
    """
    from psdbound.aviation import write_overbound
    from psdbound.common.outputs import check_writable_folder

    opts, edges_given = _options(args)
    if opts.out:
        check_writable_folder(opts.out, option="--out")
    if opts.code:
        res, extra = _code_overbound(opts)
    else:
        res, extra = _samples_overbound(opts, edges_given), {}
    print(res.summary())
    if opts.out:
        for f in write_overbound(res, opts.out, extra=extra):
            print(f"wrote {f}")
    return 0


def _options(args: argparse.Namespace) -> tuple[OverboundOptions, bool]:
    """Return the checked options and whether ``--edges`` was given; refuse inconsistent ones."""
    given = read_options(args, OPTIONS, SCHEMA.spec).get(_C, {})
    opts = SCHEMA.build("command", given)
    if opts.method == "paired" and opts.min_abs_z is not None:
        raise InputError(
            "--min-abs-z applies to --method two_step / cdf: the paired overbound exempts no core"
        )
    if opts.min_abs_z is None:
        opts = dataclasses.replace(opts, min_abs_z=0.25)
    if not opts.code and opts.nav:
        raise InputError("--nav is only used with --code (SAMPLES is a samples file)")
    if opts.code and opts.include_screened:
        raise InputError(
            "--include-screened applies to a series file (SAMPLES); --code computes the samples"
        )
    edges = opts.edges_deg
    if len(edges) < 2 or any(b <= a for a, b in zip(edges, edges[1:], strict=False)):
        raise InputError(
            f"--edges {' '.join(f'{e:g}' for e in edges)}: elevation bin edges must be at "
            "least 2 values in increasing order, deg (e.g. --edges 5 30 90)"
        )
    return opts, "edges_deg" in given


def _samples_overbound(opts: OverboundOptions, edges_given: bool) -> Any:
    """Overbound the errors of a samples file (``SAMPLES``); refuse bins it cannot form."""
    from psdbound.aviation import overbound_by_elevation
    from psdbound.aviation.files import read_sample_file

    samples = read_sample_file(opts.samples, include_screened=opts.include_screened)
    if edges_given and samples.elevation_deg is None:
        raise InputError(
            f"--edges {' '.join(f'{e:g}' for e in opts.edges_deg)} asks for elevation bins, but "
            "the file has no elevations (a column elevation, elevation_deg or el, or a second "
            ".npy column): add them, or leave out --edges to overbound all samples in one bin",
            path=opts.samples,
        )
    try:
        res = overbound_by_elevation(
            samples.errors,
            samples.elevation_deg,
            edges_deg=opts.edges_deg,
            method=opts.method,
            bias=opts.bias,
            min_abs_z=opts.min_abs_z,
            min_samples=opts.min_samples,
            unit=opts.unit,
            confidence=opts.confidence,
            segment_id=samples.segment_id,
        )
    except InputError as exc:
        raise InputError(exc.reason, path=opts.samples) from None
    for note in samples.notes:
        print(f"note: {note}")
    return res


def _code_overbound(opts: OverboundOptions) -> tuple[Any, dict[str, Any]]:
    """Overbound the code multipath of ``opts.samples`` (a RINEX file); name sparse bins."""
    from psdbound.aviation.code_samples import (
        code_multipath_from_files,
        describe_code_series,
        overbound_code_series,
    )

    if not opts.nav:
        raise InputError("--code needs --nav (a navigation or SP3 file) for the elevations")
    if not 1 <= len([c for c in opts.code.split(",") if c.strip()]) <= 2:
        raise InputError(f"--code takes one code or two separated by a comma, got {opts.code!r}")
    series = code_multipath_from_files(
        opts.samples,
        opts.nav,
        opts.code,
        system=opts.system,
        elevation_mask_deg=max(0.0, min(opts.edges_deg)),
        min_length_s=opts.min_length_s,
    )
    print(series.summary())
    try:
        res, sparse = overbound_code_series(
            series,
            opts.edges_deg,
            method=opts.method,
            min_samples=opts.min_samples,
            min_abs_z=opts.min_abs_z,
            bias=opts.bias,
            confidence=opts.confidence,
        )
    except InputError as exc:
        raise InputError(exc.reason, path=opts.samples) from None
    for note in sparse:
        print(f"note: {note}")
    info = describe_code_series(series, min_length_s=opts.min_length_s)
    return res, {"code_multipath": {"source": str(opts.samples), **info, "bins_left_out": sparse}}
