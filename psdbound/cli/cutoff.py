"""The ``cutoff`` subcommand: ionosphere high-pass cutoff for a station or the station map.

Examples::

    python -m psdbound cutoff --lat 41.84 --lon -87.63 --year 2020 --out out/
    python -m psdbound cutoff --map --year 2020 --workers 2 --out out/
    python -m psdbound cutoff --lat 41.84 --lon -87.63 --days 2020-01-06 --almanac a.yuma

Writes, into ``--out``, a CSV table, a JSON file (summary, settings, orbit
source, per-series rows) and PNG figures, each atomically (temporary name,
then rename). Bad input raises :class:`psdbound.errors.InputError`, which
the command line turns into exit code 2.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path
from typing import Any

import numpy as np

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
    sim.add_argument("--f107", type=float, default=70.0, help="F10.7 solar flux, sfu (70)")
    sim.add_argument("--mask-deg", type=float, default=10.0, help="elevation mask, deg (10)")
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


def _frequencies(text: str) -> tuple[float, float | None]:
    from psdbound.ionosphere.iri import FREQUENCIES_HZ

    def one(tok: str) -> float:
        tok = tok.strip()
        if tok in FREQUENCIES_HZ:
            return FREQUENCIES_HZ[tok]
        try:
            mhz = float(tok)
        except ValueError:
            raise InputError(
                f"unknown carrier {tok!r}: use {', '.join(FREQUENCIES_HZ)} or a value in MHz"
            ) from None
        if not 100.0 <= mhz <= 10000.0:
            raise InputError(f"carrier frequency {mhz} MHz is outside 100-10000 MHz")
        return mhz * 1e6

    parts = text.split("-") if text.count("-") == 1 and not text.startswith("-") else [text]
    if len(parts) == 2:
        f1, f2 = one(parts[0]), one(parts[1])
        if f1 == f2:
            raise InputError(f"the two carriers of {text!r} are the same frequency")
        return f1, f2
    return one(parts[0]), None


def _orbit(args: argparse.Namespace, first_day: Any) -> Any:
    if args.nav or args.sp3:
        from psdbound.io import read_orbit

        return read_orbit(args.nav or args.sp3)
    if args.almanac:
        from psdbound.io.timescales import calendar_to_gps_s
        from psdbound.ionosphere.almanac import read_yuma

        near = float(calendar_to_gps_s(first_day.year, first_day.month, first_day.day, 0, 0, 0))
        return read_yuma(args.almanac, near_gps_s=near)
    return None


def _write_text(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + f".{os.getpid()}.tmp")
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, path)
    return path


def _json(obj: Any) -> str:
    def default(o: Any) -> Any:
        if isinstance(o, np.generic):
            return o.item()
        if isinstance(o, np.ndarray):
            return o.tolist()
        raise TypeError(type(o).__name__)

    return json.dumps(obj, indent=1, default=default, allow_nan=True) + "\n"


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
    from psdbound.ionosphere.batch import (
        CutoffSettings,
        map_cutoffs,
        select_days,
        station_cutoffs,
    )
    from psdbound.ionosphere.iri import validate_station

    if (args.lat is None) != (args.lon is None):
        raise InputError("--lat and --lon go together")
    if not args.map and args.lat is None:
        raise InputError("give --lat and --lon for a station, or --map for the station map")
    if args.lat is not None:
        validate_station(args.lat, args.lon)
    if args.workers < 0:
        raise InputError(f"--workers {args.workers} must be >= 0")
    days = select_days(args.year, args.days)
    f1, f2 = _frequencies(args.frequency)
    settings = CutoffSettings(
        f107_sfu=args.f107,
        elevation_mask_deg=args.mask_deg,
        method=args.method,
        iri_model=args.iri_model,
        frequency_hz=f1,
        second_frequency_hz=f2,
        systems=args.systems.upper(),
        criterion=args.criterion,
        drop_db=args.drop_db,
        reference=args.reference,
        variance_m2=args.variance_m2,
        degree=args.degree,
        quantile=args.quantile,
    )
    settings.validate()
    orbit = _orbit(args, days[0])
    out = Path(args.out)
    common = {
        "orbit": orbit,
        "settings": settings,
        "workers": args.workers,
        "scheduler": args.scheduler,
        "cache_dir": args.cache_dir,
        "use_cache": not args.no_cache,
        "progress": _progress,
    }
    if args.map:
        return _run_map(args, days, out, map_cutoffs(days, **common))
    res = station_cutoffs(
        args.lat, args.lon, days, name=args.name, height_m=args.height_m, **common
    )
    return _report_station(args, res, out)


def _report_station(args: argparse.Namespace, res: Any, out: Path) -> int:
    s = res.summary()
    tag = _safe(res.name)
    files = [
        _write_text(out / f"cutoff_{tag}.csv", res.table_csv()),
        _write_text(out / f"cutoff_{tag}.json", _json(res.to_json_dict())),
    ]
    if not args.no_figures:
        files += _station_figures(res, out, tag)
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
    for f in files:
        print(f"  wrote {f}")
    return 0


def _station_figures(res: Any, out: Path, tag: str) -> list[Path]:
    from psdbound.ionosphere.cutoff import one_day_series, series_cutoff
    from psdbound.ionosphere.figures import plot_series_psd, plot_station_envelopes

    files = []
    rows = res.rows
    top = max(rows, key=lambda r: r["f_c_hz"])
    series = res.series_by_date.get(top["date"])
    if series is not None:
        j = list(series["sats"]).index(top["sat"])
        s = res.settings
        t, y = one_day_series(
            np.asarray(series["t_gps_s"]),
            np.asarray(series["delay_m"][j], dtype=np.float64),
            min_arc_s=s.min_arc_s,
        )
        r = series_cutoff(t, y, **s.series_options(), keep_spectrum=True)
        files.append(
            plot_series_psd(
                r,
                out / f"cutoff_{tag}_psd.png",
                title=f"{res.name} {top['sat']} {top['date']}: LS PSD, envelope, f_c "
                "(largest f_c of the run)",
            )
        )
    envs = res.envelopes
    f_lo = min(e.f_min_hz for e in envs) / 3.0
    f_hi = max(e.f_max_hz for e in envs)
    files.append(
        plot_station_envelopes(
            envs,
            res.f_c_hz,
            out / f"cutoff_{tag}_envelopes.png",
            f_range_hz=(f_lo, f_hi),
            reference_m2_hz=[r["reference_m2_hz"] for r in rows],
            title=f"{res.name}: envelopes of {len(envs)} series on {len(res.days)} days",
        )
    )
    return files


def _run_map(args: argparse.Namespace, days: list, out: Path, cmap: Any) -> int:
    from psdbound.ionosphere.figures import plot_cutoff_map

    rows = cmap.rows()
    files = [
        _write_text(out / "cutoff_map.csv", cmap.table_csv()),
        _write_text(out / "cutoff_map.json", _json(cmap.to_json_dict())),
    ]
    if not args.no_figures:
        files.append(
            plot_cutoff_map(
                [r["name"] for r in rows],
                [r["lat_deg"] for r in rows],
                [r["lon_deg"] for r in rows],
                [r["recommended_f_c_hz"] for r in rows],
                out / "cutoff_map.png",
                title=f"Recommended ionosphere cutoff ({len(days)} days, "
                f"{cmap.stations[0].settings.criterion} criterion)",
            )
        )
    print(f"cutoff map: {len(rows)} stations, {len(days)} days each")
    for r in rows:
        print(
            f"  {r['name']:8s} {r['lat_deg']:7.2f} {r['lon_deg']:8.2f}  "
            f"recommended f_c {r['recommended_f_c_hz']:.3e} Hz  ({r['n_series']} series)"
        )
    if args.lat is not None:
        near, dist = cmap.nearest(args.lat, args.lon)
        print(
            f"nearest station to ({args.lat}, {args.lon}): {near['name']} at "
            f"{dist * 111.195:.0f} km, f_c {near['recommended_f_c_hz']:.3e} Hz"
        )
    for f in files:
        print(f"  wrote {f}")
    return 0


def _safe(name: str) -> str:
    keep = "".join(c if c.isalnum() or c in "-_." else "_" for c in name)
    return keep or "station"
