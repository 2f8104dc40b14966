"""``psdbound export``: observations -> the isolated multipath series as one CSV or netCDF file.

The inputs and method options are ``fit``'s (:func:`psdbound.cli.fit.add_input_options`,
checked by :func:`psdbound.cli.fit.build_config`); the fit runs through
:func:`psdbound.fit` and only the series table is written
(:meth:`psdbound.pipeline.FitResults.write_series`), atomically. The output
file is checked before the fit starts.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from psdbound.cli.exit_codes import EXIT_NOT_BOUNDED, EXIT_OK

__all__ = ["add_parser", "output_file", "run"]

#: File name suffix of each format (the default output is reports/<run-name>-series<suffix>).
_SUFFIX = {"csv": ".csv", "netcdf": ".nc"}


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``export`` subcommand."""
    from psdbound.cli.fit import DefaultsFormatter, add_input_options

    p = sub.add_parser(
        "export",
        formatter_class=DefaultsFormatter,
        usage="psdbound export [OBS ...] [--nav NAV] [-o FILE] [--format {csv,netcdf}] [options]",
        help="write the isolated multipath series (per epoch and satellite) as CSV or netCDF",
        description="Fit as `psdbound fit` does (same inputs and options; no files: the "
        "embedded demo) and write only the isolated multipath series: one row per satellite "
        "and epoch with GPS time, azimuth, elevation, the isolated value (m), why it was "
        "screened out and its stationary window. CSV, or netCDF 3 with units and long names "
        "on every variable and the input files, psdbound version and bound as attributes "
        "(opens in xarray, pandas, Panoply, ncview, MATLAB).",
        epilog="Exit codes (as fit): 0 written, the fit is bounded; 3 written, but the fit "
        "gives no trustworthy bound (verdict not-bounded: reasons printed; the series is still "
        "the data as isolated); 2 bad input (nothing written); 1 internal error.",
    )
    add_input_options(p)
    g = p.add_argument_group("outputs")
    g.add_argument(
        "-o",
        "--out",
        metavar="FILE",
        help="output file (default: reports/<run-name>-series.csv, or .nc with "
        "--format netcdf); .csv.gz is gzip-compressed CSV",
    )
    g.add_argument(
        "--format",
        choices=("csv", "netcdf"),
        help="file format (default: from the name of -o: .nc netCDF, .csv or "
        ".csv.gz CSV; csv without -o)",
    )
    g.add_argument("--name", help="run name (default from the first observation file)")
    g.add_argument(
        "--overwrite",
        action="store_true",
        help="replace an existing file that psdbound did not write (an earlier "
        "series file is always replaced)",
    )
    talk = g.add_mutually_exclusive_group()
    talk.add_argument("-q", "--quiet", action="store_true", help="print only errors and the result")
    talk.add_argument(
        "-v", "--verbose", action="store_true", help="print stage timings and tracebacks"
    )
    p.set_defaults(func=run)


def _as_fit_args(args: argparse.Namespace) -> argparse.Namespace:
    """Return ``fit``'s arguments for ``export``'s (fit's defaults for what export lacks)."""
    from psdbound.cli.fit import add_parser as add_fit_parser

    parser = argparse.ArgumentParser()
    add_fit_parser(parser.add_subparsers())
    fit_args = parser.parse_args(["fit"])
    given = {k: v for k, v in vars(args).items() if hasattr(fit_args, k)}
    given.update(out=None, no_pdf=False, series=False, overwrite=False)
    return argparse.Namespace(**{**vars(fit_args), **given})


def output_file(args: argparse.Namespace, cfg) -> tuple[Path, str]:
    """Return the checked output file and its format (refused before the fit).

    Raises
    ------
    InputError
        An unknown suffix without ``--format``, an existing file that is not
        an earlier series file without ``--overwrite``, a folder, or a
        folder that cannot be written.
    """
    from psdbound.cli.fit import run_name
    from psdbound.common.outputs import check_output_file
    from psdbound.results.series_export import format_of, is_series_file

    if args.out:
        path = Path(args.out)
        fmt = format_of(path, args.format)
    else:
        fmt = args.format or "csv"
        path = Path("reports") / f"{run_name(cfg)}-series{_SUFFIX[fmt]}"
    check_output_file(path, overwrite=args.overwrite, option="-o/--out", ours=is_series_file)
    return path, fmt


def run(args: argparse.Namespace) -> int:
    """Fit, write the series file; return the exit code (as ``fit``'s)."""
    import psdbound
    from psdbound.cli.fit import build_config, reporter, with_files
    from psdbound.errors import InputError

    cfg = build_config(_as_fit_args(args))
    path, fmt = output_file(args, cfg)
    say = reporter(args)
    try:
        result = psdbound.fit(config=cfg, progress=say)
    except InputError as exc:
        raise with_files(exc, cfg.inputs.obs) from None
    say(f"writing {path} ({fmt})")
    result.write_series(path, format=fmt)
    print(result.summary())
    print(path)
    return EXIT_OK if result.verdict == "bounded" else EXIT_NOT_BOUNDED
