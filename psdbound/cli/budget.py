"""``psdbound budget``: the LADGNSS error budget and VPL of a satellite geometry (seed 004).

Registered by :mod:`psdbound.cli.main` through :func:`add_parser`. Two modes:

``--sat AZ,EL`` (repeated)
    One geometry: prints :func:`psdbound.aviation.budget_report` (per-satellite
    ground, airborne, ionosphere and troposphere sigmas and the fault-free /
    ephemeris VPLs).
``--nominal {G,E,GE}`` or ``--nav FILE``, with ``--position LAT,LON,H``
    The geometry over time (seed 004 section 4): the satellites above
    ``--mask-deg`` every ``--step-s`` for ``--hours`` from ``--start``
    (:func:`psdbound.aviation.sky_over`), the VPLs per epoch
    (:func:`psdbound.aviation.vpl_series`); prints the summary and, with
    ``--out``, writes ``vpl.json`` and ``vpl.png``.

``--k-md-e`` (the ephemeris missed-detection multiplier of ``VPL_eph``) is
required: the ground station broadcasts it and no standard fixes it. The
output names the multipliers used and their sources (``multipliers``).
"""

from __future__ import annotations

import argparse
import datetime as dt
import math
from dataclasses import dataclass
from typing import Any

from psdbound.cli.actions import Once
from psdbound.cli.config_file import add_config_option
from psdbound.cli.schema import CliOption, Schema, SchemaHelpFormatter, add_options, read_options
from psdbound.common.options import Choice, Number, check_fields, option
from psdbound.errors import InputError

__all__ = ["OPTIONS", "SCHEMA", "BudgetOptions", "add_parser", "run"]

#: Most epochs one run evaluates (--hours * 3600 / --step-s).
MAX_EPOCHS = 100_000
#: The options of the VPL over time (an error naming them with --sat).
_SERIES_OPTIONS = ("position", "start", "hours", "step_s", "mask_deg", "val_m", "systems")
_SYSTEM_NAMES = {"G": "GPS (G)", "E": "Galileo (E)"}
_SYSTEMS = ("G", "E", "GE")


@dataclass(frozen=True)
class BudgetOptions:
    """The options of ``psdbound budget``.

    The model's names and defaults are the keywords of
    :func:`psdbound.aviation.error_budget` (seed 004 Table 4; a test keeps
    them equal) and of :func:`psdbound.aviation.multipliers`; the geometry
    is ``sats`` (one epoch) or ``nominal`` / ``nav`` over time, with the
    options of :func:`psdbound.aviation.sky_over`.
    """

    sats: tuple[str, ...] = ()
    nominal: str | None = option(None, Choice(_SYSTEMS, optional=True, noun="constellation"))
    nav: str | None = None
    process: str = option("SF", Choice(("SF", "DF", "IF"), noun="smoothing process"))
    base_frequency: str = option("L1", Choice(("L1", "L5"), noun="frequency"))
    tau_gnd_s: float = option(100.0, Number(unit="s"))
    tau_air_s: float = option(100.0, Number(unit="s"))
    gad: str = option("B", Choice(("A", "B", "C"), noun="ground designator"))
    n_receivers: int = option(3, Number(integer=True))
    rho: float = option(0.1, Number())
    x_air_m: float = option(5000.0, Number(unit="m"))
    k_md_e: float | None = option(None, Number(optional=True))
    k_ffmd: float | None = option(None, Number(optional=True))
    xi_formula: str = option("exact", Choice(("exact", "seed", "steady_state"), noun="formula"))
    out: str | None = None
    position: str | None = None
    systems: str | None = option(None, Choice(_SYSTEMS, optional=True, noun="systems"))
    start: str | None = None
    hours: float = option(24.0, Number(lo=0.0, lo_open=True, unit="h"))
    step_s: float = option(300.0, Number(lo=0.0, lo_open=True, unit="s"))
    mask_deg: float = option(5.0, Number(unit="deg"))
    val_m: float | None = option(None, Number(lo=0.0, lo_open=True, unit="m", optional=True))

    def __post_init__(self) -> None:
        check_fields(self)

    def budget_options(self) -> dict[str, Any]:
        """Return the keywords of :func:`psdbound.aviation.error_budget` these options set."""
        names = ("process", "base_frequency", "tau_gnd_s", "tau_air_s", "gad", "rho")
        return {
            **{n: getattr(self, n) for n in names},
            "x_air_m": self.x_air_m,
            "xi_formula": self.xi_formula,
        }


#: The schema of ``budget``'s options.
SCHEMA = Schema({"budget": "psdbound.cli.budget:BudgetOptions"})

_O = CliOption
_B = "budget"
_G_TIME = "over time (--nominal, --nav)"
#: Every ``budget`` option: its schema field, flag, help and group (None: ``options``).
OPTIONS: tuple[CliOption, ...] = (
    _O(
        _B,
        "sats",
        ("--sat",),
        "satellite azimuth,elevation in deg, repeatable (required, at least 4, "
        "unless --nominal or --nav)",
        None,
        {"action": "append", "metavar": "AZ,EL"},
        exclusive="geometry",
    ),
    _O(
        _B,
        "nominal",
        ("--nominal",),
        "VPL over time for the nominal GPS 24-slot / Galileo Walker 24/3/1 "
        "constellations (default: none)",
        None,
        exclusive="geometry",
    ),
    _O(
        _B,
        "nav",
        ("--nav",),
        "VPL over time for the orbits of a RINEX navigation or SP3 file (default: none)",
        None,
        {"action": Once, "metavar": "FILE"},
        exclusive="geometry",
    ),
    _O(_B, "process", ("--process",), "smoothing process", None),
    _O(_B, "base_frequency", ("--frequency",), "base frequency of SF/DF", None),
    _O(_B, "tau_gnd_s", ("--tau-gnd",), "ground smoothing, s", None),
    _O(_B, "tau_air_s", ("--tau-air",), "airborne smoothing, s", None),
    _O(_B, "gad", ("--gad",), "ground designator", None),
    _O(_B, "n_receivers", ("--receivers",), "reference receivers M, count", None),
    _O(_B, "rho", ("--rho",), "ground multipath correlation, dimensionless", None),
    _O(_B, "x_air_m", ("--x-air-km",), "distance to reference, km", None, scale=1000.0, unit="km"),
    _O(
        _B,
        "k_md_e",
        ("--k-md-e",),
        "ephemeris missed-detection multiplier K_md_e of VPL_eph, dimensionless "
        "(required: broadcast by the ground station in Message Type 2; no standard value)",
        None,
    ),
    _O(
        _B,
        "k_ffmd",
        ("--k-ffmd",),
        "fault-free multiplier K_ffmd, dimensionless (default: the table for --receivers, "
        "entered from memory and not verified against the standard; its source is printed)",
        None,
    ),
    _O(
        _B,
        "xi_formula",
        ("--xi-formula",),
        "smoothing-time ratio xi: exact variance of seed 004's smoother, the seed's "
        "printed eq. A6 (reproduces its Table 1), or the converged Hatch filter",
        None,
    ),
    _O(
        _B,
        "out",
        ("--out",),
        "folder for budget.json (--sat) or vpl.json and vpl.png (--nominal, --nav) (default: none)",
        None,
    ),
    _O(
        _B,
        "position",
        ("--position",),
        "user position: geodetic latitude and longitude in deg, WGS84 height in m "
        "(required with --nominal/--nav)",
        _G_TIME,
        {"metavar": "LAT,LON,H"},
    ),
    _O(
        _B,
        "systems",
        ("--systems",),
        "systems of the --nav file to use (default: GE; --nominal names its own)",
        _G_TIME,
    ),
    _O(
        _B,
        "start",
        ("--start",),
        "first epoch, ISO date-time in GPS time (default: 2009-01-01T00:00:00, seed "
        "004's, for --nominal; for --nav 00:00 of the first whole day the file covers, "
        "else its first record time)",
        _G_TIME,
        {"metavar": "ISO"},
    ),
    _O(_B, "hours", ("--hours",), "duration, h", _G_TIME),
    _O(_B, "step_s", ("--step-s",), "time between epochs, s", _G_TIME),
    _O(_B, "mask_deg", ("--mask-deg",), "elevation mask, deg", _G_TIME),
    _O(
        _B,
        "val_m",
        ("--val-m",),
        "vertical alert limit, m: prints the availability (default: none)",
        _G_TIME,
    ),
)


def add_parser(subparsers: Any) -> None:
    """Add the ``budget`` subcommand to an ``add_subparsers()`` object.

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        From :meth:`argparse.ArgumentParser.add_subparsers`.
    """
    p = subparsers.add_parser(
        "budget",
        formatter_class=SchemaHelpFormatter,
        help="LADGNSS error budget and vertical protection level for a geometry",
        description="Error budget of a local-area differential GNSS user (ground "
        "reference receivers of accuracy class GAD, an airborne receiver of class AAD-A, "
        "residual ionosphere and troposphere) against elevation and carrier-smoothing time, "
        "and the vertical protection levels under no fault (VPL_H0) and an ephemeris fault "
        "(VPL_eph): for one geometry (--sat), or over time for the nominal constellations "
        "(--nominal) or the satellites of a navigation/SP3 file (--nav) seen from --position. "
        "The models follow the GBAS standards as summarised in the project's source document "
        "004 (docs: method/aviation).",
        epilog="examples: psdbound budget --sat 10,12 --sat 80,25 --sat 150,38 "
        "--sat 200,47 --sat 260,60 --tau-gnd 30 --tau-air 30; "
        "psdbound budget --nominal GE --position 55.49,8.46,59 --val-m 10 --out vpl/",
    )
    add_options(p, OPTIONS, SCHEMA.spec, groups=(None, _G_TIME), defaults=SCHEMA.default)
    add_config_option(p)
    p.set_defaults(func=run)


def _k_options(opts: BudgetOptions) -> dict[str, Any]:
    """``k_md_e``, ``k_ffmd``, ``n_receivers`` checked once (exit 2 naming the option)."""
    from psdbound.aviation import multipliers

    if opts.k_md_e is None:
        raise InputError(
            "--k-md-e is required: the ephemeris missed-detection multiplier K_md_e of VPL_eph "
            "is broadcast by the ground station (Message Type 2) and no standard fixes its "
            "value; give the one of the station you analyse (e.g. --k-md-e 5.0)"
        )
    if opts.n_receivers < 1:
        raise InputError(f"--receivers must be >= 1, got {opts.n_receivers}")
    try:
        multipliers(n_receivers=opts.n_receivers, k_ffmd=opts.k_ffmd, k_md_e=opts.k_md_e)
    except InputError as exc:
        msg = exc.reason.replace("k_md_e", "--k-md-e").replace("k_ffmd", "--k-ffmd")
        raise InputError(msg.replace("M = ", "--receivers ")) from None
    return {"k_md_e": opts.k_md_e, "k_ffmd": opts.k_ffmd, "n_receivers": opts.n_receivers}


def _sats(opts: BudgetOptions) -> tuple[list[float], list[float]]:
    """``--sat AZ,EL`` (at least 4) -> azimuths and elevations, degrees."""
    az, el = [], []
    for s in opts.sats:
        try:
            a, e = (float(v) for v in s.split(","))
        except ValueError:
            raise InputError(f"--sat {s!r}: expected AZ,EL in degrees, e.g. 80,25") from None
        az.append(a)
        el.append(e)
    if len(el) < 4:
        more = "" if el else ", or --nominal / --nav with --position for the VPL over time"
        raise InputError(f"give at least 4 --sat AZ,EL (got {len(el)}){more}")
    return az, el


def run(args: argparse.Namespace) -> int:
    """Run ``psdbound budget``.

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
        Malformed ``--sat`` or ``--position``, fewer than 4 satellites, a
        ``--nav`` file without the systems or a ``--start`` outside its span,
        bad options or geometry.
    """
    given = read_options(args, OPTIONS, SCHEMA.spec).get(_B, {})
    opts = SCHEMA.build(_B, given)
    if opts.nominal or opts.nav:
        return _run_series(opts)
    series = [o.flag for o in OPTIONS if o.name in _SERIES_OPTIONS and o.name in given]
    if series:
        verb = "applies" if len(series) == 1 else "apply"
        raise InputError(f"{', '.join(series)} {verb} only to --nominal / --nav, not to --sat")
    from psdbound.aviation import budget_document, budget_report

    az, el = _sats(opts)
    kopts = _k_options(opts)
    if opts.out:
        from psdbound.common.outputs import check_writable_folder

        check_writable_folder(opts.out, option="--out")
    print(budget_report(az, el, **kopts, **opts.budget_options()))
    if opts.out:
        from pathlib import Path

        from psdbound.results import write_json

        doc = budget_document(az, el, **kopts, **opts.budget_options())
        path = write_json(Path(opts.out) / "budget.json", {"budget": doc})
        print(f"wrote {path}")
        print(f"wrote {_budget_page(Path(opts.out) / 'budget.html', doc)}")
    return 0


def _budget_page(path: Any, doc: dict[str, Any]) -> Any:
    """Write budget.html: the protection levels, the multipliers and each satellite's budget."""
    from psdbound.reports.page import write_page

    m = doc["multipliers"]
    lines = [
        f"VPL_H0 {doc['vpl_h0_m']:.3f} m, VPL_eph {doc['vpl_eph_m']:.3f} m, "
        f"VPL {doc['vpl_m']:.3f} m",
        f"K_ffmd = {m['k_ffmd']['value']:g} ({m['k_ffmd']['source']})",
        f"K_md_e = {m['k_md_e']['value']:g} ({m['k_md_e']['source']})",
    ]
    keys = ("azimuth_deg", "elevation_deg", "ground_m", "air_m", "iono_m", "trop_m", "total_m")
    head = [
        "azimuth [deg]",
        "elevation [deg]",
        "ground [m]",
        "air [m]",
        "iono [m]",
        "trop [m]",
        "total [m]",
    ]
    rows = [[f"{s[k]:.4g}" for k in keys] for s in doc["satellites"]]
    return write_page(
        path,
        command="budget",
        title="error budget and vertical protection level",
        json_name="budget.json",
        lines=lines,
        table=(head, rows),
    )


def _position(text: str | None) -> tuple[float, float, float]:
    """``--position LAT,LON,H`` -> degrees, degrees, metres."""
    if text is None:
        raise InputError("--position LAT,LON,H is required with --nominal / --nav")
    try:
        lat, lon, h = (float(v) for v in text.split(","))
    except ValueError:
        raise InputError(
            f"--position {text!r}: expected LAT,LON,H (deg, deg, m), e.g. 55.49,8.46,59"
        ) from None
    if not (math.isfinite(lat) and -90.0 <= lat <= 90.0):
        raise InputError(f"--position {text!r}: latitude {lat} deg is outside [-90, 90]")
    if not (math.isfinite(lon) and -180.0 <= lon <= 360.0):
        raise InputError(f"--position {text!r}: longitude {lon} deg is outside [-180, 360]")
    if not (math.isfinite(h) and -1000.0 <= h <= 100_000.0):
        raise InputError(f"--position {text!r}: height {h} m is outside [-1000, 100000]")
    return lat, lon, h


def _start(text: str) -> float:
    """``--start ISO`` (GPS time label, no time zone) -> GPS seconds."""
    from psdbound.io.timescales import calendar_to_gps_s

    try:
        t = dt.datetime.fromisoformat(text)
    except ValueError:
        t = None
    if t is None or t.tzinfo is not None:
        raise InputError(
            f"--start {text!r}: expected an ISO date-time in GPS time without a time zone, "
            "e.g. 2009-01-01T00:00:00"
        )
    sec = t.second + t.microsecond * 1e-6
    return float(calendar_to_gps_s(t.year, t.month, t.day, t.hour, t.minute, sec))


def _label(t_gps_s: float) -> str:
    from psdbound.io.timescales import gps_s_to_datetime64

    return str(gps_s_to_datetime64(t_gps_s).astype("datetime64[s]")).replace("T", " ")


def _nav_orbit(path: str, systems: str, start: str | None) -> tuple[Any, tuple[float, float]]:
    """Read ``--nav``, check the systems and the start; return the orbit, (start, span end)."""
    from psdbound.io import PreciseOrbit, read_orbit

    orbit = read_orbit(path)
    missing = [c for c in systems if c not in orbit.systems]
    if not missing and not isinstance(orbit, PreciseOrbit):
        missing = [c for c in systems if orbit.reference_times_gps_s(c).size == 0]
    if missing:
        names = ", ".join(_SYSTEM_NAMES[c] for c in missing)
        usable = "".join(c for c in "GE" if c in orbit.systems)
        hint = (
            f"give --systems {usable}"
            if usable
            else "the budget models GPS and Galileo only: give a navigation file with them"
        )
        raise InputError(
            f"no {names} orbits for --systems {systems}; the file has "
            f"{', '.join(orbit.systems) or 'none'} ({hint})",
            path=path,
        )
    if isinstance(orbit, PreciseOrbit):
        lo, hi = float(orbit.t_gps_s[0]), float(orbit.t_gps_s[-1])
        first, what = lo, "its epochs"
    else:
        toes = [orbit.reference_times_gps_s(c) for c in systems]
        valid = max(orbit.validity_s(c) for c in systems)
        first = min(float(t[0]) for t in toes)
        lo, hi = first - valid, max(float(t[-1]) for t in toes) + valid
        what = f"its healthy records' reference times +- {valid / 3600:g} h validity"
    midnight = math.ceil(lo / 86400.0) * 86400.0  # GPS seconds count from a midnight
    first = midnight if midnight + 86400.0 <= hi else first  # the first whole day covered
    t0 = first if start is None else _start(start)
    if not lo <= t0 <= hi:
        raise InputError(
            f"--start {_label(t0)} is outside the span of the file for systems {systems}: "
            f"{_label(lo)} to {_label(hi)} GPS time ({what})",
            path=path,
        )
    return orbit, (t0, hi)


def _epochs(opts: BudgetOptions) -> int:
    """Check ``--mask-deg``; return the number of epochs (``--hours``, ``--step-s`` > 0: schema)."""
    if not 0.0 <= opts.mask_deg < 90.0:
        raise InputError(f"--mask-deg must be in [0, 90) deg, got {opts.mask_deg:g}")
    n_epochs = math.ceil(opts.hours * 3600.0 / opts.step_s)
    if n_epochs > MAX_EPOCHS:
        raise InputError(
            f"--hours {opts.hours:g} at --step-s {opts.step_s:g} gives {n_epochs} epochs; at "
            f"most {MAX_EPOCHS} (raise --step-s)"
        )
    return n_epochs


def _orbit(opts: BudgetOptions) -> tuple[Any, str, float, float]:
    """Return the orbit of ``--nominal`` or ``--nav``, its systems, first epoch and span end."""
    from psdbound.aviation import SEED004_START_GPS_S, nominal_orbit

    if opts.nominal:
        if opts.systems:
            raise InputError("--systems applies to --nav; --nominal names the constellations")
        t0 = SEED004_START_GPS_S if opts.start is None else _start(opts.start)
        duration_s = opts.hours * 3600.0
        orbit = nominal_orbit(opts.nominal, start_gps_s=t0, duration_s=duration_s)
        return orbit, opts.nominal, t0, math.inf
    systems = opts.systems or "GE"
    orbit, (t0, end) = _nav_orbit(opts.nav, systems, opts.start)
    return orbit, systems, t0, end


def _run_series(opts: BudgetOptions) -> int:
    """``--nominal`` / ``--nav``: the VPL over time."""
    from psdbound.aviation import sky_over, vpl_series, write_vpl_series
    from psdbound.common.notices import warn
    from psdbound.common.outputs import check_writable_folder
    from psdbound.io.geometry import geodetic_to_ecef

    lat, lon, h = _position(opts.position)
    kopts = _k_options(opts)
    n_epochs = _epochs(opts)
    if opts.out:
        check_writable_folder(opts.out, option="--out")
    orbit, systems, t0, end = _orbit(opts)
    t = [t0 + opts.step_s * k for k in range(n_epochs)]
    if t[-1] > end:
        warn(
            f"epochs after {_label(end)} GPS are beyond the --nav file's span: no orbit, "
            f"they count as unavailable"
        )
    rx = geodetic_to_ecef(lat, lon, h)
    sky = sky_over(orbit, rx, t, systems=systems, elevation_mask_deg=opts.mask_deg)
    series = vpl_series(sky, **kopts, **opts.budget_options())
    print(
        f"user at {lat:.4f} deg N, {lon:.4f} deg E, {h:g} m; {opts.process} "
        f"{opts.base_frequency}, tau {opts.tau_gnd_s:g}/{opts.tau_air_s:g} s, GAD-{opts.gad}, "
        f"M = {opts.n_receivers}, rho = {opts.rho:g}, x_air = {opts.x_air_m / 1000.0:g} km, "
        f"xi {opts.xi_formula}"
    )
    k = series.options["multipliers"]
    print(f"K_ffmd = {k['k_ffmd']['value']:.3f} ({k['k_ffmd']['source']})")
    print(f"K_md_e = {k['k_md_e']['value']:.3f} ({k['k_md_e']['source']})")
    print(series.summary(val_m=opts.val_m))
    if opts.out:
        for f in write_vpl_series(series, opts.out, val_m=opts.val_m):
            print(f"wrote {f}")
    return 0
