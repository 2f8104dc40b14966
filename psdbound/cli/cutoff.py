"""The ``cutoff`` subcommand: ionosphere high-pass cutoff for a station or the station map.

Examples::

    python -m psdbound cutoff --lat 41.84 --lon -87.63 --year 2020 --out out/
    python -m psdbound cutoff --map --year 2020 --workers 2 --out out/
    python -m psdbound cutoff --lat 41.84 --lon -87.63 --days 2020-01-06 --almanac a.yuma

Parses the options and calls :func:`psdbound.ionosphere.run_cutoff`, which
writes, into ``--out``, a CSV table, a JSON file (summary, settings, orbit
source, per-series rows) and PNG figures, each atomically; then prints the
summary. Options named like a
:class:`~psdbound.ionosphere.CutoffSettings` field (``dest``) are the run's
settings (:meth:`~psdbound.ionosphere.CutoffSettings.from_mapping`). Bad
input raises :class:`psdbound.errors.InputError`, which the command line
turns into exit code 2.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from psdbound.errors import InputError

__all__ = ["add_parser", "run"]

_DAYS_HELP = (
    "days: first-monday-each-month (default), first-monday-of-MM, or YYYY-MM-DD[,YYYY-MM-DD...]"
)


def add_parser(subparsers: Any) -> None:
    """Register the ``cutoff`` subcommand on an ``add_subparsers()`` object.

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        What ``ArgumentParser.add_subparsers`` returned.
    """
    p = subparsers.add_parser(
        "cutoff",
        help="select the ionosphere high-pass cutoff frequency (station or station map)",
        description="Simulate slant ionospheric delays (PyIRI) of every satellite in view, "
        "take the Lomb-Scargle PSD of each 7-sidereal-day replicated series, fit its upper "
        "envelope and find the cutoff by the 40 dB relative (or the absolute) criterion. "
        "Recommended cutoff = maximum over all series.",
    )
    where = p.add_argument_group("station or map")
    where.add_argument("--lat", type=float, help="station latitude, degrees (-90..90)")
    where.add_argument("--lon", type=float, help="station longitude, degrees east")
    where.add_argument("--height-m", type=float, default=0.0, help="station height, m (0)")
    where.add_argument("--name", default="", help="station name for outputs")
    where.add_argument(
        "--map",
        action="store_true",
        help="run the 20 reference stations of method.md and write the cutoff map "
        "(with --lat/--lon also print the nearest station's cutoff)",
    )
    when = p.add_argument_group("days")
    when.add_argument("--year", type=int, default=2020, help="year of the day selection (2020)")
    when.add_argument("--days", default="first-monday-each-month", help=_DAYS_HELP)
    sim = p.add_argument_group("simulation")
    sim.add_argument(
        "--f107",
        dest="f107_sfu",
        metavar="F107",
        type=float,
        default=70.0,
        help="F10.7 solar flux, sfu (70)",
    )
    sim.add_argument(
        "--mask-deg",
        dest="elevation_mask_deg",
        metavar="MASK_DEG",
        type=float,
        default=10.0,
        help="elevation mask, deg (10)",
    )
    sim.add_argument(
        "--method",
        choices=("line-of-sight", "thin-shell"),
        default="line-of-sight",
        help="slant TEC by line-of-sight integral (default) or thin shell at 350 km",
    )
    sim.add_argument(
        "--iri-model", choices=("ursi", "ccir", "sh"), default="ursi", help="PyIRI model (ursi)"
    )
    sim.add_argument(
        "--frequency",
        dest="carrier",
        metavar="FREQUENCY",
        default="L1",
        help="carrier: L1, L2, L5, E1, E5a, E5b, a value in MHz, or a pair like L1-L2 "
        "for the dual-frequency difference (L1)",
    )
    orbit = sim.add_mutually_exclusive_group()
    orbit.add_argument("--nav", help="RINEX navigation file covering the days")
    orbit.add_argument("--sp3", help="SP3 precise orbit file covering the days")
    orbit.add_argument("--almanac", help="YUMA almanac file")
    sim.add_argument(
        "--systems",
        default="G",
        help="nominal constellation when no orbit file: G (GPS 24-slot), E (Galileo "
        "Walker 24/3/1) or GE (G)",
    )
    crit = p.add_argument_group("criterion")
    crit.add_argument("--criterion", choices=("relative", "absolute"), default="relative")
    crit.add_argument("--drop-db", type=float, default=40.0, help="relative criterion, dB (40)")
    crit.add_argument(
        "--reference",
        choices=("psd", "envelope"),
        default="psd",
        help="relative criterion's reference: PSD maximum (default) or envelope peak",
    )
    crit.add_argument(
        "--variance-m2",
        type=float,
        default=1e-6,
        help="absolute criterion: allowed residual variance, m^2 (1e-6)",
    )
    crit.add_argument("--degree", type=int, default=3, help="envelope polynomial degree (3)")
    crit.add_argument("--quantile", type=float, default=0.99, help="envelope quantile (0.99)")
    run_ = p.add_argument_group("execution and output")
    run_.add_argument("--workers", type=int, default=2, help="local Dask workers (2; 0: no Dask)")
    run_.add_argument("--scheduler", metavar="ADDRESS", help="use a running Dask scheduler")
    run_.add_argument("--cache-dir", help="cache directory ($PSDBOUND_CACHE or ~/.cache/...)")
    run_.add_argument("--no-cache", action="store_true", help="neither read nor write the cache")
    run_.add_argument("--out", default=".", help="output directory (.)")
    run_.add_argument("--no-figures", action="store_true", help="write no PNG")
    p.set_defaults(func=run)


def _progress(done: int, total: int) -> None:
    print(f"\r  {done}/{total} station-days computed", end="", file=sys.stderr, flush=True)
    if done == total:
        print(file=sys.stderr)


def run(args: argparse.Namespace) -> int:
    """Run the ``cutoff`` subcommand; return the exit code (0).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments of the parser built by :func:`add_parser`.

    Returns
    -------
    int
        0 on success.

    Raises
    ------
    InputError
        For bad input (position, dates, options, files); the caller maps it
        to exit code 2.
    """
    from psdbound.ionosphere import SETTING_OPTIONS, run_cutoff

    if (args.lat is None) != (args.lon is None):
        raise InputError("--lat and --lon go together")
    if not args.map and args.lat is None:
        raise InputError("give --lat and --lon for a station, or --map for the station map")
    if args.workers < 0:
        raise InputError(f"--workers {args.workers} must be >= 0")
    outcome = run_cutoff(
        lat_deg=args.lat,
        lon_deg=args.lon,
        station_map=args.map,
        year=args.year,
        days=args.days,
        name=args.name,
        height_m=args.height_m,
        settings={k: v for k, v in vars(args).items() if k in SETTING_OPTIONS},
        nav=args.nav,
        sp3=args.sp3,
        almanac=args.almanac,
        workers=args.workers,
        scheduler=args.scheduler,
        cache_dir=args.cache_dir,
        use_cache=not args.no_cache,
        out_dir=args.out,
        figures=not args.no_figures,
        progress=_progress,
    )
    if args.map:
        _print_map(args, outcome)
    else:
        _print_station(outcome)
    return 0


def _print_station(outcome: Any) -> None:
    res = outcome.result
    s = res.summary()
    print(
        f"{res.name}: {s['n_series']} series on {s['n_days']} days ({res.orbit_description}), "
        f"{res.settings.criterion} criterion"
    )
    print(
        f"  f_c mean {s['mean_f_c_hz']:.3e} Hz, min {s['min_f_c_hz']:.3e} Hz, "
        f"max {s['max_f_c_hz']:.3e} Hz"
    )
    print(
        f"  recommended f_c = {s['recommended_f_c_hz']:.3e} Hz "
        f"(tau_c = {s['recommended_tau_c_min']:.2f} min)"
    )
    if s["n_skipped"]:
        print(f"  {s['n_skipped']} series skipped (see the JSON)")
    for f in outcome.files:
        print(f"  wrote {f}")


def _print_map(args: argparse.Namespace, outcome: Any) -> None:
    rows = outcome.result.rows()
    n_days = len(outcome.days)
    print(f"cutoff map: {len(rows)} stations, {n_days} days each")
    for r in rows:
        print(
            f"  {r['name']:8s} {r['lat_deg']:7.2f} {r['lon_deg']:8.2f}  "
            f"recommended f_c {r['recommended_f_c_hz']:.3e} Hz  ({r['n_series']} series)"
        )
    if outcome.nearest is not None:
        near, dist = outcome.nearest
        print(
            f"nearest station to ({args.lat}, {args.lon}): {near['name']} at "
            f"{dist * 111.195:.0f} km, f_c {near['recommended_f_c_hz']:.3e} Hz"
        )
    for f in outcome.files:
        print(f"  wrote {f}")
