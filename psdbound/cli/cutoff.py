"""The ``cutoff`` subcommand: ionosphere high-pass cutoff for a station, or the world map.

Examples::

    python -m psdbound cutoff --lat 41.84 --lon -87.63 --year 2020 --out out/
    python -m psdbound cutoff --lat 41.84 --lon -87.63 --year 2020 --legacy --out out/
    python -m psdbound cutoff --map --workers 2 --out out/ [--install]
    python -m psdbound cutoff --map --scheduler tcp://host:8786 --out out/
    python -m psdbound cutoff --lat 41.84 --lon -87.63 --days 2020-01-06 --almanac a.yuma

A station run calls :func:`psdbound.ionosphere.run_cutoff`, which writes,
into ``--out``, ``cutoff_<name>.csv`` (one row per series),
``cutoff_<name>.json`` (summary, settings, orbit source, per-series rows;
schema ``cutoff.schema.json``), PNG figures and ``cutoff_<name>.html`` (the
recommended cutoff, tables and figures), each atomically; then prints the
summary. ``--map`` calls :func:`psdbound.ionosphere.workflow.run_world_map`:
the world map (20 reference stations and a grid, a solar-minimum and a
solar-maximum layer) on a local Dask cluster or ``--scheduler``, written to
``--out`` (``cutoff_map.json``, schema ``cutoff_map.schema.json``,
``cutoff_map.csv``, ``cutoff_map.png``, ``cutoff_map.html``) and, with
``--install``, over the shipped package data. Options
named like a :class:`~psdbound.ionosphere.CutoffSettings` field (``dest``)
are the run's settings (:meth:`~psdbound.ionosphere.CutoffSettings.from_mapping`;
not given = the default, or the issue-#4 settings with ``--legacy``). Bad
input raises :class:`psdbound.errors.InputError`, which the command line
turns into exit code 2.
"""

from __future__ import annotations

import argparse
from typing import Any

from psdbound.cli.actions import Once
from psdbound.cli.config_file import add_config_option
from psdbound.common.progress import counter
from psdbound.errors import InputError

__all__ = ["add_parser", "run"]

_DAYS_HELP = (
    "days: first-monday-each-month (default), first-monday-of-MM[,MM...], "
    "first-monday-quarterly, or YYYY-MM-DD[,YYYY-MM-DD...]"
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
        description="Simulate slant ionospheric delays (PyIRI) of every satellite in view and "
        "find, per satellite-day, the lowest cutoff above which the fit's high-pass leaves the "
        "ionosphere MARGIN_DB (40) below MP_SIGMA_M (1 mm) (the residual criterion; the "
        "thesis's 40 dB Lomb-Scargle criterion with --criterion relative or --legacy). "
        "Recommended cutoff = maximum over all series.",
    )
    where = p.add_argument_group("station or map")
    where.add_argument(
        "--lat", type=float, help="station latitude, degrees, -90 to 90 (required without --map)"
    )
    where.add_argument(
        "--lon", type=float, help="station longitude, degrees east (required without --map)"
    )
    where.add_argument("--height-m", type=float, default=0.0, help="station height, m (default: 0)")
    where.add_argument("--name", default="", help="station name for outputs (default: none)")
    where.add_argument(
        "--map",
        action="store_true",
        help="compute the world cutoff map (20 reference stations + grid, solar-minimum "
        "2020 and solar-maximum 2024 layers); with --lat/--lon also print its cutoff there",
    )
    where.add_argument(
        "--grid-step",
        metavar="LAT,LON",
        help="map grid steps, degrees (default: 20,90)",
    )
    where.add_argument(
        "--install",
        action="store_true",
        help="with --map: also replace the shipped map (psdbound/ionosphere/data/cutoff_map.json)",
    )
    when = p.add_argument_group("days")
    when.add_argument(
        "--year", type=int, default=2020, help="year of the day selection, count (default: 2020)"
    )
    when.add_argument("--days", help=_DAYS_HELP + " (--map: first-monday-quarterly)")
    sim = p.add_argument_group("simulation")
    sim.add_argument(
        "--f107",
        dest="f107_sfu",
        metavar="F107",
        type=float,
        help="F10.7 solar flux, sfu (default: 70; the map uses each layer's year)",
    )
    sim.add_argument(
        "--mask-deg",
        dest="elevation_mask_deg",
        metavar="MASK_DEG",
        type=float,
        help="elevation mask, deg (default: 10)",
    )
    sim.add_argument(
        "--method",
        choices=("line-of-sight", "thin-shell"),
        help="slant TEC by line-of-sight integral (default) or thin shell at 350 km",
    )
    sim.add_argument(
        "--iri-model", choices=("ursi", "ccir", "sh"), help="PyIRI model (default: ursi)"
    )
    sim.add_argument(
        "--frequency",
        dest="carrier",
        metavar="FREQUENCY",
        help="carrier: L1, L2, L5, E1, E5a, E5b, a value in MHz, or a pair like L1-L2 "
        "for the dual-frequency difference (default: L1-L2, what the fit filters; --legacy: L1)",
    )
    orbit = sim.add_mutually_exclusive_group()
    orbit.add_argument(
        "--nav", action=Once, help="RINEX navigation file covering the days (default: none)"
    )
    orbit.add_argument(
        "--sp3", action=Once, help="SP3 precise orbit file covering the days (default: none)"
    )
    orbit.add_argument("--almanac", help="YUMA almanac file (default: none; nominal constellation)")
    sim.add_argument(
        "--sampling-s",
        type=float,
        help="sampling interval of the simulated delays, s (default: 30; --legacy: 12)",
    )
    sim.add_argument(
        "--systems",
        help="nominal constellation when no orbit file: G (GPS 24-slot), E (Galileo "
        "Walker 24/3/1) or GE (default: G)",
    )
    crit = p.add_argument_group("criterion")
    crit.add_argument(
        "--criterion",
        choices=("residual", "relative", "absolute"),
        help="residual (default): the ionosphere the fit's high-pass leaves, MARGIN_DB below "
        "MP_SIGMA_M; relative/absolute: the thesis's Lomb-Scargle criteria",
    )
    crit.add_argument(
        "--legacy",
        action="store_true",
        help="the issue-#4 settings: 40 dB Lomb-Scargle criterion at L1, 12 s, fine grids",
    )
    crit.add_argument(
        "--mp-sigma-m",
        type=float,
        help="residual criterion: reference multipath sigma, m (default: 1e-3)",
    )
    crit.add_argument(
        "--margin-db", type=float, help="residual criterion: margin below it, dB (default: 40)"
    )
    crit.add_argument("--drop-db", type=float, help="relative criterion, dB (default: 40)")
    crit.add_argument(
        "--reference",
        choices=("psd", "envelope"),
        help="relative criterion's reference: PSD maximum (default) or envelope peak",
    )
    crit.add_argument(
        "--variance-m2",
        type=float,
        help="absolute criterion: allowed residual variance, m^2 (default: 1e-6)",
    )
    crit.add_argument("--degree", type=int, help="envelope polynomial degree, count (default: 3)")
    crit.add_argument(
        "--quantile", type=float, help="envelope quantile, probability (default: 0.99)"
    )
    run_ = p.add_argument_group("execution and output")
    run_.add_argument(
        "--workers", type=int, default=2, help="local Dask workers, count (default: 2; 0: no Dask)"
    )
    run_.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="use a running Dask scheduler (default: a local cluster)",
    )
    run_.add_argument(
        "--cache-dir", help="cache directory (default: $PSDBOUND_CACHE or ~/.cache/...)"
    )
    run_.add_argument("--no-cache", action="store_true", help="neither read nor write the cache")
    run_.add_argument(
        "--out",
        default=".",
        help="output directory for the CSV table, the JSON document, the PNG figures and "
        "the HTML page (default: .)",
    )
    run_.add_argument(
        "--no-figures", action="store_true", help="write no PNG (the page has no figures)"
    )
    add_config_option(p)
    p.set_defaults(func=run)


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
    from psdbound.ionosphere import SETTING_OPTIONS, CutoffSettings, run_cutoff

    if (args.lat is None) != (args.lon is None):
        raise InputError("--lat and --lon go together")
    if not args.map and args.lat is None:
        raise InputError("give --lat and --lon for a station, or --map for the world map")
    if args.workers < 0:
        raise InputError(f"--workers {args.workers} must be >= 0")
    given = {k: v for k, v in vars(args).items() if k in SETTING_OPTIONS and v is not None}
    settings = CutoffSettings.from_mapping(given)
    if args.legacy:
        legacy = CutoffSettings.legacy()
        settings = CutoffSettings.from_mapping({**legacy.to_dict(), **given})
    execution = {
        "workers": args.workers,
        "scheduler": args.scheduler,
        "cache_dir": args.cache_dir,
        "use_cache": not args.no_cache,
        "progress": counter("station-days computed"),
    }
    if args.map:
        from psdbound.ionosphere.workflow import run_world_map

        outcome = run_world_map(
            settings=settings,
            grid_step_deg=_grid_step(args.grid_step),
            days=args.days,
            lat_deg=args.lat,
            lon_deg=args.lon,
            year=args.year,
            out_dir=args.out,
            figures=not args.no_figures,
            install=args.install,
            **execution,
        )
        _print_world_map(args, outcome)
        return 0
    outcome = run_cutoff(
        lat_deg=args.lat,
        lon_deg=args.lon,
        year=args.year,
        days=args.days or "first-monday-each-month",
        name=args.name,
        height_m=args.height_m,
        settings=settings,
        nav=args.nav,
        sp3=args.sp3,
        almanac=args.almanac,
        out_dir=args.out,
        figures=not args.no_figures,
        **execution,
    )
    _print_station(outcome)
    return 0


def _grid_step(text: str | None) -> tuple[float, float] | None:
    if text is None:
        return None
    try:
        lat, lon = (float(v) for v in text.split(","))
    except ValueError:
        raise InputError(f"--grid-step {text!r}: expected LAT,LON in degrees, e.g. 20,60") from None
    return lat, lon


def _print_station(outcome: Any) -> None:
    res = outcome.result
    s = res.summary()
    st = res.settings
    how = f"{st.criterion} criterion"
    if st.criterion == "residual":
        how += (
            f": residual ionosphere after the fit's high-pass {st.margin_db:g} dB below "
            f"{1e3 * st.mp_sigma_m:g} mm ({1e3 * s['threshold_m']:.3g} mm)"
        )
    print(f"{res.name}: {s['n_series']} series on {s['n_days']} days ({res.orbit_description})")
    print(f"  {how}, F10.7 {st.f107_sfu:g} sfu")
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


def _print_world_map(args: argparse.Namespace, outcome: Any) -> None:
    doc = outcome.doc
    g = doc["grid"]
    c = doc["criterion"]
    print(
        f"cutoff map: {len(doc['layers'][0]['stations'])} reference stations + "
        f"{len(g['lat_deg'])} x {len(g['lon_deg'])} grid, {c['name']} criterion "
        f"({c['margin_db']:g} dB below {1e3 * c['mp_sigma_m']:g} mm), "
        f"{doc['compute']['n_station_days']} station-days in {doc['compute']['elapsed_s']:.0f} s"
    )
    for layer in doc["layers"]:
        print(f"  {layer['name']} ({layer['year']}, F10.7 {layer['f107_sfu']:.1f} sfu):")
        for st in layer["stations"]:
            print(
                f"    {st['name']:6s} {st['lat_deg']:7.2f} {st['lon_deg']:8.2f}  "
                f"recommended f_c {st['recommended_f_c_hz']:.3e} Hz"
            )
    for v in doc["validation"]:
        print(
            f"  grid interpolation at the stations ({v['name']}): median error "
            f"{100 * v['median_abs_rel_error']:.1f} %, worst {100 * v['worst_rel_error']:+.1f} % "
            f"({v['worst_station']})"
        )
    if outcome.at_position is not None:
        f_c, info = outcome.at_position
        print(
            f"at ({args.lat}, {args.lon}), F10.7 {info['f107_sfu']:.1f} sfu ({args.year}): "
            f"f_c {f_c:.3e} Hz"
        )
    for f in outcome.files:
        print(f"  wrote {f}")
