"""``psdbound export``: observations -> the isolated multipath series as one CSV or netCDF file.

The inputs and method options are ``fit``'s (:func:`psdbound.cli.fit.add_input_options`,
checked by :func:`psdbound.cli.fit.build_config`); the fit runs through
:func:`psdbound.fit` and only the series table is written
(:meth:`psdbound.pipeline.FitResults.write_series`), atomically. The output
file is checked before the fit starts. ``export``'s own options (the output
file, its format, the run name and ``--overwrite``) are listed in
:data:`OPTIONS` over :data:`SCHEMA` (:class:`ExportOptions`, and fit's
``[output] name``), as every command's (:mod:`psdbound.cli.schema`).
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from pathlib import Path

from psdbound.cli.exit_codes import EXIT_NOT_BOUNDED, EXIT_OK
from psdbound.cli.schema import CliOption, Schema, add_options, read_options
from psdbound.common.options import Boolean, Choice, Text, check_fields, option

__all__ = ["OPTIONS", "SCHEMA", "ExportOptions", "add_parser", "output_file", "run"]

#: File name suffix of each format (the default output is reports/<run-name>-series<suffix>).
_SUFFIX = {"csv": ".csv", "netcdf": ".nc"}


@dataclass(frozen=True)
class ExportOptions:
    """The options of ``psdbound export`` besides the fit's.

    Attributes
    ----------
    out : str or None
        Output file (None: ``reports/<run-name>-series.csv``, or ``.nc``).
    format : str or None
        ``"csv"`` or ``"netcdf"`` (None: from the name of ``out``).
    overwrite : bool
        Replace an existing file that psdbound did not write.
    """

    out: str | None = option(None, Text(what="a file name", paths=True, optional=True))
    format: str | None = option(None, Choice(("csv", "netcdf"), optional=True, noun="format"))
    overwrite: bool = option(False, Boolean())

    def __post_init__(self) -> None:
        check_fields(self)


#: The schema of ``export``'s own options: the output file, and the fit's run name.
SCHEMA = Schema(
    {
        "export": "psdbound.cli.export:ExportOptions",
        "output": "psdbound.pipeline.config:OutputConfig",
    }
)

_G_OUT = "outputs"
_O = CliOption
#: Every option of ``export`` that is not ``fit``'s input or method option.
OPTIONS: tuple[CliOption, ...] = (
    _O(
        "export",
        "out",
        ("-o", "--out"),
        "output file (default: reports/<run-name>-series.csv, or .nc with "
        "--format netcdf); .csv.gz is gzip-compressed CSV",
        _G_OUT,
        {"metavar": "FILE"},
    ),
    _O(
        "export",
        "format",
        ("--format",),
        "file format (default: from the name of -o: .nc netCDF, .csv or "
        ".csv.gz CSV; csv without -o)",
        _G_OUT,
    ),
    _O("output", "name", ("--name",), "run name (default from the first observation file)", _G_OUT),
    _O(
        "export",
        "overwrite",
        ("--overwrite",),
        "replace an existing file that psdbound did not write (an earlier "
        "series file is always replaced)",
        _G_OUT,
        {"action": "store_true"},
    ),
)


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
    g = add_options(p, OPTIONS, SCHEMA.spec, groups=(_G_OUT,), defaults=SCHEMA.default)[_G_OUT]
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

    opts = SCHEMA.build("export", read_options(args, OPTIONS, SCHEMA.spec).get("export", {}))
    if opts.out:
        path = Path(opts.out)
        fmt = format_of(path, opts.format)
    else:
        fmt = opts.format or "csv"
        path = Path("reports") / f"{run_name(cfg)}-series{_SUFFIX[fmt]}"
    check_output_file(path, overwrite=opts.overwrite, option="-o/--out", ours=is_series_file)
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
