"""``psdbound campaign``: many files, days and stations; every bound tested on held-out days.

A day's options are ``fit``'s own (:func:`psdbound.cli.fit.add_day_options`,
checked by :func:`psdbound.cli.fit.build_config` as for ``fit`` on the first
observation file); the observation and navigation files, the isolation
method (dual-frequency), code multipath and the outputs are the campaign's:
listed in :data:`OPTIONS` over :data:`SCHEMA` (:class:`CampaignOptions`), as
every command's (:mod:`psdbound.cli.schema`).
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass, fields
from typing import Any

from psdbound.cli.exit_codes import EXIT_NOT_BOUNDED, EXIT_OK
from psdbound.cli.schema import CliOption, Schema, add_options, read_options
from psdbound.common.options import Boolean, Number, Text, Tuple, check_fields, option

__all__ = ["OPTIONS", "SCHEMA", "CampaignOptions", "add_parser", "day_options", "run"]


@dataclass(frozen=True)
class CampaignOptions:
    """The options of ``psdbound campaign`` besides a day's (which are ``fit``'s).

    The names are the keywords of :func:`psdbound.campaign.run_campaign`
    and :func:`psdbound.campaign.write_campaign` (``out``, ``pdf``).
    """

    obs: tuple[str, ...] = option((), Tuple(Text(what="a file name", paths=True)))
    nav: tuple[str, ...] = option((), Tuple(Text(what="a file name", paths=True)))
    out: str = option("reports/campaign", Text(what="a folder name", paths=True))
    workers: int = option(2, Number(lo=0, hi=256, integer=True))
    scheduler: str | None = option(None, Text(what="a scheduler address", optional=True))
    cache_dir: str | None = option(None, Text(what="a folder name", paths=True, optional=True))
    pdf: bool = option(True, Boolean())
    sidereal_keep: bool = option(True, Boolean())

    def __post_init__(self) -> None:
        check_fields(self)


#: The schema of ``campaign``'s own options (a day's are FitConfig's, as ``fit``'s).
SCHEMA = Schema({"campaign": "psdbound.cli.campaign:CampaignOptions"})

_O = CliOption
#: Every ``campaign`` option that is not a day's: files, execution and outputs.
OPTIONS: tuple[CliOption, ...] = (
    _O(
        "campaign",
        "obs",
        ("obs",),
        "observation files (any stations and days; required)",
        None,
        {"nargs": "+"},
    ),
    _O(
        "campaign",
        "nav",
        ("--nav",),
        "navigation/SP3 files, any names: each day takes the one file that covers its "
        "observations' time span for the system fitted (required)",
        None,
        {"nargs": "+", "action": "extend", "required": True},
    ),
    _O("campaign", "out", ("--out",), "output folder", None),
    _O(
        "campaign",
        "workers",
        ("--workers",),
        "local Dask worker processes, count",
        None,
        note="0 runs in this process",
    ),
    _O(
        "campaign",
        "scheduler",
        ("--scheduler",),
        "address of a running Dask scheduler (overrides --workers; default: a local cluster)",
        None,
    ),
    _O(
        "campaign",
        "cache_dir",
        ("--cache-dir",),
        "task cache folder (default: the psdbound cache)",
        None,
    ),
    _O(
        "campaign",
        "pdf",
        ("--no-pdf",),
        "skip campaign.pdf",
        None,
        {"action": "store_true"},
        convert=lambda given: {"pdf": not given},
    ),
    _O(
        "campaign",
        "sidereal_keep",
        ("--no-sidereal-keep",),
        "do not fit again, keeping them as multipath, the days whose spans screened as "
        "ionosphere repeat one sidereal day later on a neighbouring day (default: fit again)",
        None,
        {"action": "store_true"},
        convert=lambda given: {"sidereal_keep": not given},
    ),
)

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
    add_options(p, OPTIONS, SCHEMA.spec, groups=(None,), defaults=SCHEMA.default)
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
    from psdbound.common.outputs import check_writable_folder
    from psdbound.common.progress import counter

    given = read_options(args, OPTIONS, SCHEMA.spec)
    opts = SCHEMA.build("campaign", given.get("campaign", {}))
    check_writable_folder(opts.out, option="--out")
    if opts.cache_dir is not None:
        check_writable_folder(opts.cache_dir, option="--cache-dir")
    options = day_options(args)

    res = run_campaign(
        list(opts.obs),
        list(opts.nav),
        workers=opts.workers,
        scheduler=opts.scheduler,
        cache_dir=opts.cache_dir,
        options=options,
        progress=counter("station-days computed"),
        sidereal_keep=opts.sidereal_keep,
    )
    files = write_campaign(res, opts.out, pdf=opts.pdf)
    print(res.summary())
    for f in files.values():
        print(f)
    return EXIT_OK if res.verdict == "bounded" else EXIT_NOT_BOUNDED
