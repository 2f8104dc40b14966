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
from dataclasses import dataclass
from typing import Any

from psdbound.cli.actions import Once
from psdbound.cli.config_file import add_config_option
from psdbound.cli.schema import CliOption, Schema, SchemaHelpFormatter, add_options, read_options
from psdbound.common.options import Number, check_fields, option
from psdbound.errors import InputError

__all__ = ["OPTIONS", "SCHEMA", "CutoffOptions", "add_parser", "run"]

_DAYS_HELP = (
    "days: first-monday-each-month (default), first-monday-of-MM[,MM...], "
    "first-monday-quarterly, or YYYY-MM-DD[,YYYY-MM-DD...]"
)


@dataclass(frozen=True)
class CutoffOptions:
    """The options of ``psdbound cutoff`` besides the run's settings.

    The settings are :class:`~psdbound.ionosphere.CutoffSettings`' fields
    (section ``settings`` of :data:`SCHEMA`). These are the station, days,
    orbit source, execution and outputs: the keywords of
    :func:`psdbound.ionosphere.run_cutoff` and
    :func:`psdbound.ionosphere.workflow.run_world_map` (the station's
    position is checked there, with its own messages).
    """

    lat_deg: float | None = option(None, Number(unit="deg", optional=True))
    lon_deg: float | None = option(None, Number(unit="deg", optional=True))
    height_m: float = option(0.0, Number(unit="m"))
    name: str = ""
    map: bool = False
    grid_step: str | None = None
    install: bool = False
    year: int = option(2020, Number(integer=True))
    days: str | None = None
    nav: str | None = None
    sp3: str | None = None
    almanac: str | None = None
    legacy: bool = False
    workers: int = option(2, Number(lo=0, integer=True))
    scheduler: str | None = None
    cache_dir: str | None = None
    use_cache: bool = True
    out: str = "."
    figures: bool = True

    def __post_init__(self) -> None:
        check_fields(self)


#: The schema of ``cutoff``'s options: its own, and the run's settings (CutoffSettings).
SCHEMA = Schema(
    {
        "command": "psdbound.cli.cutoff:CutoffOptions",
        "settings": "psdbound.ionosphere.settings:CutoffSettings",
    }
)

_O = CliOption
_C, _S = "command", "settings"
_G_WHERE, _G_DAYS, _G_SIM = "station or map", "days", "simulation"
_G_CRIT, _G_RUN = "criterion", "execution and output"
_GROUPS = (_G_WHERE, _G_DAYS, _G_SIM, _G_CRIT, _G_RUN)
#: Every ``cutoff`` option: its schema field, flag, help and group. Options of section
#: ``settings`` are CutoffSettings fields (``carrier``: its ``from_mapping`` name).
OPTIONS: tuple[CliOption, ...] = (
    _O(
        _C,
        "lat_deg",
        ("--lat",),
        "station latitude, degrees, -90 to 90 (required without --map)",
        _G_WHERE,
    ),
    _O(
        _C,
        "lon_deg",
        ("--lon",),
        "station longitude, degrees east (required without --map)",
        _G_WHERE,
    ),
    _O(_C, "height_m", ("--height-m",), "station height, m", _G_WHERE),
    _O(_C, "name", ("--name",), "station name for outputs (default: none)", _G_WHERE),
    _O(
        _C,
        "map",
        ("--map",),
        "compute the world cutoff map (20 reference stations + grid, solar-minimum "
        "2020 and solar-maximum 2024 layers); with --lat/--lon also print its cutoff there",
        _G_WHERE,
        {"action": "store_true"},
    ),
    _O(
        _C,
        "grid_step",
        ("--grid-step",),
        "map grid steps, degrees (default: 20,90)",
        _G_WHERE,
        {"metavar": "LAT,LON"},
    ),
    _O(
        _C,
        "install",
        ("--install",),
        "with --map: also replace the shipped map (psdbound/ionosphere/data/cutoff_map.json)",
        _G_WHERE,
        {"action": "store_true"},
    ),
    _O(_C, "year", ("--year",), "year of the day selection, count", _G_DAYS),
    _O(_C, "days", ("--days",), _DAYS_HELP + " (--map: first-monday-quarterly)", _G_DAYS),
    _O(
        _S,
        "f107_sfu",
        ("--f107",),
        "F10.7 solar flux, sfu",
        _G_SIM,
        {"dest": "f107_sfu", "metavar": "F107"},
        note="the map uses each layer's year",
    ),
    _O(
        _S,
        "elevation_mask_deg",
        ("--mask-deg",),
        "elevation mask, deg",
        _G_SIM,
        {"dest": "elevation_mask_deg", "metavar": "MASK_DEG"},
    ),
    _O(
        _S,
        "method",
        ("--method",),
        "slant TEC by line-of-sight integral or thin shell at 350 km",
        _G_SIM,
    ),
    _O(_S, "iri_model", ("--iri-model",), "PyIRI model", _G_SIM),
    _O(
        _S,
        "carrier",
        ("--frequency",),
        "carrier: L1, L2, L5, E1, E5a, E5b, a value in MHz, or a pair like L1-L2 "
        "for the dual-frequency difference (default: L1-L2, what the fit filters; --legacy: L1)",
        _G_SIM,
        {"dest": "carrier", "metavar": "FREQUENCY"},
    ),
    _O(
        _C,
        "nav",
        ("--nav",),
        "RINEX navigation file covering the days (default: none)",
        _G_SIM,
        {"action": Once},
        exclusive="orbit",
    ),
    _O(
        _C,
        "sp3",
        ("--sp3",),
        "SP3 precise orbit file covering the days (default: none)",
        _G_SIM,
        {"action": Once},
        exclusive="orbit",
    ),
    _O(
        _C,
        "almanac",
        ("--almanac",),
        "YUMA almanac file (default: none; nominal constellation)",
        _G_SIM,
        exclusive="orbit",
    ),
    _O(
        _S,
        "sampling_s",
        ("--sampling-s",),
        "sampling interval of the simulated delays, s",
        _G_SIM,
        note="--legacy: 12",
    ),
    _O(
        _S,
        "systems",
        ("--systems",),
        "nominal constellation when no orbit file: G (GPS 24-slot), E (Galileo "
        "Walker 24/3/1) or GE",
        _G_SIM,
    ),
    _O(
        _S,
        "criterion",
        ("--criterion",),
        "residual: the ionosphere the fit's high-pass leaves, MARGIN_DB below "
        "MP_SIGMA_M; relative/absolute: the thesis's Lomb-Scargle criteria",
        _G_CRIT,
    ),
    _O(
        _C,
        "legacy",
        ("--legacy",),
        "the issue-#4 settings: 40 dB Lomb-Scargle criterion at L1, 12 s, fine grids",
        _G_CRIT,
        {"action": "store_true"},
    ),
    _O(
        _S,
        "mp_sigma_m",
        ("--mp-sigma-m",),
        "residual criterion: reference multipath sigma, m",
        _G_CRIT,
    ),
    _O(_S, "margin_db", ("--margin-db",), "residual criterion: margin below it, dB", _G_CRIT),
    _O(_S, "drop_db", ("--drop-db",), "relative criterion, dB", _G_CRIT),
    _O(
        _S,
        "reference",
        ("--reference",),
        "relative criterion's reference: PSD maximum (psd) or envelope peak (envelope)",
        _G_CRIT,
    ),
    _O(
        _S,
        "variance_m2",
        ("--variance-m2",),
        "absolute criterion: allowed residual variance, m^2",
        _G_CRIT,
    ),
    _O(_S, "degree", ("--degree",), "envelope polynomial degree, count", _G_CRIT),
    _O(_S, "quantile", ("--quantile",), "envelope quantile, probability", _G_CRIT),
    _O(_C, "workers", ("--workers",), "local Dask workers, count", _G_RUN, note="0: no Dask"),
    _O(
        _C,
        "scheduler",
        ("--scheduler",),
        "use a running Dask scheduler (default: a local cluster)",
        _G_RUN,
        {"metavar": "ADDRESS"},
    ),
    _O(
        _C,
        "cache_dir",
        ("--cache-dir",),
        "cache directory (default: $PSDBOUND_CACHE or ~/.cache/...)",
        _G_RUN,
    ),
    _O(
        _C,
        "use_cache",
        ("--no-cache",),
        "neither read nor write the cache",
        _G_RUN,
        {"action": "store_true"},
        convert=lambda given: {"use_cache": not given},
    ),
    _O(
        _C,
        "out",
        ("--out",),
        "output directory for the CSV table, the JSON document, the PNG figures and the HTML page",
        _G_RUN,
    ),
    _O(
        _C,
        "figures",
        ("--no-figures",),
        "write no PNG (the page has no figures)",
        _G_RUN,
        {"action": "store_true"},
        convert=lambda given: {"figures": not given},
    ),
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
        formatter_class=SchemaHelpFormatter,
        help="select the ionosphere high-pass cutoff frequency (station or station map)",
        description="Simulate slant ionospheric delays (PyIRI) of every satellite in view and "
        "find, per satellite-day, the lowest cutoff above which the fit's high-pass leaves the "
        "ionosphere MARGIN_DB (40) below MP_SIGMA_M (1 mm) (the residual criterion; the "
        "thesis's 40 dB Lomb-Scargle criterion with --criterion relative or --legacy). "
        "Recommended cutoff = maximum over all series.",
    )
    add_options(p, OPTIONS, SCHEMA.spec, groups=_GROUPS, defaults=SCHEMA.default)
    add_config_option(p)
    p.set_defaults(func=run)


def _settings(legacy: bool, given: dict[str, Any]) -> Any:
    """Return the run's CutoffSettings: the options given over the defaults (or ``--legacy``'s)."""
    from psdbound.ionosphere import CutoffSettings

    if legacy:
        return CutoffSettings.from_mapping({**CutoffSettings.legacy().to_dict(), **given})
    return CutoffSettings.from_mapping(given)


def _options(args: argparse.Namespace) -> tuple[CutoffOptions, Any]:
    """Return the command's options and the run's settings, checked (errors name the flag)."""
    given = read_options(args, OPTIONS, SCHEMA.spec)
    opts = SCHEMA.build(_C, given.get(_C, {}))
    if (opts.lat_deg is None) != (opts.lon_deg is None):
        raise InputError("--lat and --lon go together")
    if not opts.map and opts.lat_deg is None:
        raise InputError("give --lat and --lon for a station, or --map for the world map")
    return opts, _settings(opts.legacy, given.get(_S, {}))


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
    from psdbound.common.progress import counter
    from psdbound.ionosphere import run_cutoff

    opts, settings = _options(args)
    _check_folders(opts)
    execution = {
        "workers": opts.workers,
        "scheduler": opts.scheduler,
        "cache_dir": opts.cache_dir,
        "use_cache": opts.use_cache,
        "progress": counter("station-days computed"),
    }
    if opts.map:
        from psdbound.ionosphere.workflow import run_world_map

        outcome = run_world_map(
            settings=settings,
            grid_step_deg=_grid_step(opts.grid_step),
            days=opts.days,
            lat_deg=opts.lat_deg,
            lon_deg=opts.lon_deg,
            year=opts.year,
            out_dir=opts.out,
            figures=opts.figures,
            install=opts.install,
            **execution,
        )
        _print_world_map(opts, outcome)
        return 0
    outcome = run_cutoff(
        lat_deg=opts.lat_deg,
        lon_deg=opts.lon_deg,
        year=opts.year,
        days=opts.days or "first-monday-each-month",
        name=opts.name,
        height_m=opts.height_m,
        settings=settings,
        nav=opts.nav,
        sp3=opts.sp3,
        almanac=opts.almanac,
        out_dir=opts.out,
        figures=opts.figures,
        **execution,
    )
    _print_station(outcome)
    return 0


def _check_folders(opts: CutoffOptions) -> None:
    """Refuse an output or cache folder that cannot be written, before any computation."""
    from psdbound.common.outputs import check_writable_folder

    check_writable_folder(opts.out, option="--out")
    if opts.cache_dir is not None and opts.use_cache:
        check_writable_folder(opts.cache_dir, option="--cache-dir")


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


def _print_world_map(opts: CutoffOptions, outcome: Any) -> None:
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
            f"at ({opts.lat_deg}, {opts.lon_deg}), F10.7 {info['f107_sfu']:.1f} sfu "
            f"({opts.year}): "
            f"f_c {f_c:.3e} Hz"
        )
    for f in outcome.files:
        print(f"  wrote {f}")
