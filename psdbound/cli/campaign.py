"""``psdbound campaign``: many files, days and stations; every bound tested on held-out days.

A day's options are ``fit``'s own (:func:`psdbound.cli.fit.add_day_options`,
checked by :func:`psdbound.cli.fit.build_config` as for ``fit`` on the first
observation file); the observation and navigation files, the isolation
method (dual-frequency), code multipath and the outputs are the campaign's.
"""

from __future__ import annotations

import argparse
from dataclasses import fields
from typing import Any

from psdbound.cli.exit_codes import EXIT_NOT_BOUNDED, EXIT_OK

__all__ = ["add_parser", "day_options", "run"]

#: FitConfig options a campaign sets itself (files, method) or does not use (outputs).
_CAMPAIGN_OWNS = {("inputs", "obs"), ("inputs", "nav"), ("inputs", "method")}
#: Sections a campaign takes for every day (inputs only ``system`` and ``signals``).
_DAY_SECTIONS = (
    "arcs",
    "cutoff",
    "filter",
    "screening",
    "mapping",
    "stationarity",
    "spectra",
    "bound",
    "verdict",
    "validation",
)
_DAY_INPUTS = ("system", "signals")


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``campaign`` subcommand."""
    from psdbound.cli.fit import DefaultsFormatter, add_day_options

    p = sub.add_parser(
        "campaign",
        formatter_class=DefaultsFormatter,
        help="fit many station-days on Dask and test each day against the others' bound",
        description="Group observation files by station and day, match each day's navigation "
        "file by its content (the time it covers for the system fitted), fit every station-day "
        "as `psdbound fit` does (a Dask task, cached by input hash: a re-run computes only what "
        "changed) with its verdict, pool each station's bounded days into one bound with its "
        "own verdict, and test every pooled day against the bound of the station's other days. "
        "Writes campaign.json, campaign.html, campaign.pdf, network.html (every station on a "
        "map and in one sortable table, with its bound over the days) and days/ (each "
        "station-day's report).",
        epilog="The day options are fit's (same names, defaults and checks; --config takes "
        "fit's TOML sections except [output] and [code_multipath], and of [inputs] only "
        "system and signals). Exit codes: 0 every station's pooled bound is bounded; 3 some "
        "station's pooled bound is not bounded (reasons printed, outputs written); 2 bad input "
        "(nothing written); 1 internal error.",
    )
    p.add_argument("obs", nargs="+", help="observation files (any stations and days; required)")
    p.add_argument(
        "--nav",
        nargs="+",
        action="extend",
        required=True,
        help="navigation/SP3 files, any names: each day takes the one file that covers its "
        "observations' time span for the system fitted (required)",
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
    p.add_argument(
        "--no-sidereal-keep",
        action="store_true",
        help="do not fit again, keeping them as multipath, the days whose spans screened as "
        "ionosphere repeat one sidereal day later on a neighbouring day (default: fit again)",
    )
    add_day_options(p)
    p.set_defaults(func=run)


def _as_fit_args(args: argparse.Namespace) -> argparse.Namespace:
    """Return ``fit``'s arguments for the campaign's day options on its first observation file."""
    from psdbound.cli.fit import add_parser as add_fit_parser

    parser = argparse.ArgumentParser()
    add_fit_parser(parser.add_subparsers())
    fit_args = parser.parse_args(["fit"])
    day = {k: v for k, v in vars(args).items() if hasattr(fit_args, k)}
    day.update(obs=args.obs[:1], nav=list(args.nav), out=None, no_pdf=False)
    return argparse.Namespace(**{**vars(fit_args), **day})


def _changed(obj: Any) -> dict[str, Any]:
    """Return the options of a configuration section that differ from their defaults."""
    default = type(obj)()
    return {
        f.name: getattr(obj, f.name)
        for f in fields(obj)
        if getattr(obj, f.name) != getattr(default, f.name)
    }


def day_options(args: argparse.Namespace) -> dict[str, dict[str, Any]]:
    """Return the FitConfig sections every station-day uses (only options that differ).

    The options (flags and ``--config``) are checked exactly as ``fit``
    checks them, on the first observation file.

    Raises
    ------
    InputError
        A bad value, conflicting options, or an option a campaign does not
        take (outputs, code multipath, the dual-antenna inputs).
    """
    from psdbound.cli.fit import build_config
    from psdbound.errors import InputError

    cfg = build_config(_as_fit_args(args))
    out: dict[str, dict[str, Any]] = {}
    for section in ("inputs", *_DAY_SECTIONS, "code_multipath", "output"):
        for name, value in _changed(getattr(cfg, section)).items():
            if (section, name) in _CAMPAIGN_OWNS:
                continue
            if section not in _DAY_SECTIONS and name not in _DAY_INPUTS:
                raise InputError(
                    f"[{section}] {name} (in {args.config}) is not a campaign "
                    "option: a campaign fits every day dual-frequency from its own "
                    "files and writes its own outputs; remove it"
                )
            out.setdefault(section, {})[name] = value
    return out


def run(args: argparse.Namespace) -> int:
    """Run the campaign, write its outputs, print the summary; return the exit code."""
    from psdbound.campaign import run_campaign, write_campaign
    from psdbound.common.options import Number
    from psdbound.common.outputs import check_writable_folder
    from psdbound.common.progress import counter

    Number(lo=0, hi=256, integer=True)("--workers", args.workers)
    check_writable_folder(args.out, option="--out")
    options = day_options(args)

    res = run_campaign(
        args.obs,
        args.nav,
        workers=args.workers,
        scheduler=args.scheduler,
        cache_dir=args.cache_dir,
        options=options,
        progress=counter("station-days computed"),
        sidereal_keep=not args.no_sidereal_keep,
    )
    files = write_campaign(res, args.out, pdf=not args.no_pdf)
    print(res.summary())
    for f in files.values():
        print(f)
    return EXIT_OK if res.verdict == "bounded" else EXIT_NOT_BOUNDED
