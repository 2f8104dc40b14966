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
from typing import Any

from psdbound.cli.actions import Once
from psdbound.cli.config_file import add_config_option
from psdbound.errors import InputError

__all__ = ["add_parser", "run"]

#: Most epochs one run evaluates (--hours * 3600 / --step-s).
MAX_EPOCHS = 100_000
_SERIES_OPTIONS = {
    "position": "--position",
    "start": "--start",
    "hours": "--hours",
    "step_s": "--step-s",
    "mask_deg": "--mask-deg",
    "val_m": "--val-m",
    "systems": "--systems",
}
_SYSTEM_NAMES = {"G": "GPS (G)", "E": "Galileo (E)"}


def add_parser(subparsers: Any) -> None:
    """Add the ``budget`` subcommand to an ``add_subparsers()`` object.

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        From :meth:`argparse.ArgumentParser.add_subparsers`.
    """
    p = subparsers.add_parser(
        "budget",
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
    mode = p.add_mutually_exclusive_group()
    mode.add_argument(
        "--sat",
        action="append",
        default=[],
        metavar="AZ,EL",
        help="satellite azimuth,elevation in deg, repeatable (required, at least 4, "
        "unless --nominal or --nav)",
    )
    mode.add_argument(
        "--nominal",
        choices=("G", "E", "GE"),
        help="VPL over time for the nominal GPS 24-slot / Galileo Walker 24/3/1 "
        "constellations (default: none)",
    )
    mode.add_argument(
        "--nav",
        action=Once,
        metavar="FILE",
        help="VPL over time for the orbits of a RINEX navigation or SP3 file (default: none)",
    )
    p.add_argument(
        "--process",
        choices=("SF", "DF", "IF"),
        default="SF",
        help="smoothing process (default: SF)",
    )
    p.add_argument(
        "--frequency",
        choices=("L1", "L5"),
        default="L1",
        help="base frequency of SF/DF (default: L1)",
    )
    p.add_argument(
        "--tau-gnd", type=float, default=100.0, help="ground smoothing, s (default: 100)"
    )
    p.add_argument(
        "--tau-air", type=float, default=100.0, help="airborne smoothing, s (default: 100)"
    )
    p.add_argument(
        "--gad", choices=("A", "B", "C"), default="B", help="ground designator (default: B)"
    )
    p.add_argument(
        "--receivers", type=int, default=3, help="reference receivers M, count (default: 3)"
    )
    p.add_argument(
        "--rho",
        type=float,
        default=0.1,
        help="ground multipath correlation, dimensionless (default: 0.1)",
    )
    p.add_argument(
        "--x-air-km", type=float, default=5.0, help="distance to reference, km (default: 5)"
    )
    p.add_argument(
        "--k-md-e",
        type=float,
        help="ephemeris missed-detection multiplier K_md_e of VPL_eph, dimensionless "
        "(required: broadcast by the ground station in Message Type 2; no standard value)",
    )
    p.add_argument(
        "--k-ffmd",
        type=float,
        help="fault-free multiplier K_ffmd, dimensionless (default: the table for --receivers, "
        "entered from memory and not verified against the standard; its source is printed)",
    )
    p.add_argument(
        "--xi-formula",
        choices=("exact", "seed", "steady_state"),
        default="exact",
        help="smoothing-time ratio xi: exact variance of seed 004's smoother, the seed's "
        "printed eq. A6 (reproduces its Table 1), or the converged Hatch filter "
        "(default: exact)",
    )
    p.add_argument(
        "--out",
        help="folder for budget.json (--sat) or vpl.json and vpl.png (--nominal, --nav) "
        "(default: none)",
    )
    s = p.add_argument_group("over time (--nominal, --nav)")
    s.add_argument(
        "--position",
        metavar="LAT,LON,H",
        help="user position: geodetic latitude and longitude in deg, WGS84 height in m "
        "(required with --nominal/--nav)",
    )
    s.add_argument(
        "--systems",
        choices=("G", "E", "GE"),
        help="systems of the --nav file to use (default: GE; --nominal names its own)",
    )
    s.add_argument(
        "--start",
        metavar="ISO",
        help="first epoch, ISO date-time in GPS time (default: 2009-01-01T00:00:00, seed "
        "004's, for --nominal; for --nav 00:00 of the first whole day the file covers, "
        "else its first record time)",
    )
    s.add_argument("--hours", type=float, help="duration, h (default: 24)")
    s.add_argument("--step-s", type=float, help="time between epochs, s (default: 300)")
    s.add_argument("--mask-deg", type=float, help="elevation mask, deg (default: 5)")
    s.add_argument(
        "--val-m",
        type=float,
        help="vertical alert limit, m: prints the availability (default: none)",
    )
    add_config_option(p)
    p.set_defaults(func=run)


def _budget_options(args: argparse.Namespace) -> dict[str, Any]:
    return {
        "process": args.process,
        "base_frequency": args.frequency,
        "tau_gnd_s": args.tau_gnd,
        "tau_air_s": args.tau_air,
        "gad": args.gad,
        "rho": args.rho,
        "x_air_m": 1000.0 * args.x_air_km,
        "xi_formula": args.xi_formula,
    }


def _k_options(args: argparse.Namespace) -> dict[str, Any]:
    """``k_md_e``, ``k_ffmd``, ``n_receivers`` checked once (exit 2 naming the option)."""
    from psdbound.aviation import multipliers

    if args.k_md_e is None:
        raise InputError(
            "--k-md-e is required: the ephemeris missed-detection multiplier K_md_e of VPL_eph "
            "is broadcast by the ground station (Message Type 2) and no standard fixes its "
            "value; give the one of the station you analyse (e.g. --k-md-e 5.0)"
        )
    if args.receivers < 1:
        raise InputError(f"--receivers must be >= 1, got {args.receivers}")
    try:
        multipliers(n_receivers=args.receivers, k_ffmd=args.k_ffmd, k_md_e=args.k_md_e)
    except InputError as exc:
        msg = exc.reason.replace("k_md_e", "--k-md-e").replace("k_ffmd", "--k-ffmd")
        raise InputError(msg.replace("M = ", "--receivers ")) from None
    return {"k_md_e": args.k_md_e, "k_ffmd": args.k_ffmd, "n_receivers": args.receivers}


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
    if getattr(args, "nominal", None) or getattr(args, "nav", None):
        return _run_series(args)
    given = [f for name, f in _SERIES_OPTIONS.items() if getattr(args, name, None) is not None]
    if given:
        verb = "applies" if len(given) == 1 else "apply"
        raise InputError(f"{', '.join(given)} {verb} only to --nominal / --nav, not to --sat")
    from psdbound.aviation import budget_document, budget_report

    az, el = [], []
    for s in args.sat:
        try:
            a, e = (float(v) for v in s.split(","))
        except ValueError:
            raise InputError(f"--sat {s!r}: expected AZ,EL in degrees, e.g. 80,25") from None
        az.append(a)
        el.append(e)
    if len(el) < 4:
        more = "" if el else ", or --nominal / --nav with --position for the VPL over time"
        raise InputError(f"give at least 4 --sat AZ,EL (got {len(el)}){more}")
    kopts = _k_options(args)
    if args.out:
        from psdbound.common.outputs import check_writable_folder

        check_writable_folder(args.out, option="--out")
    print(budget_report(az, el, **kopts, **_budget_options(args)))
    if args.out:
        from pathlib import Path

        from psdbound.results import write_json

        doc = budget_document(az, el, **kopts, **_budget_options(args))
        path = write_json(Path(args.out) / "budget.json", {"budget": doc})
        print(f"wrote {path}")
        print(f"wrote {_budget_page(Path(args.out) / 'budget.html', doc)}")
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


def _positive(value: float | None, default: float, flag: str, unit: str) -> float:
    """``value`` (or the default when None) if finite and > 0, else an error naming ``flag``."""
    v = default if value is None else value
    if not (math.isfinite(v) and v > 0):
        raise InputError(f"{flag} must be > 0 {unit}, got {v:g}")
    return v


def _nav_orbit(path: str, systems: str, start: str | None) -> tuple[Any, tuple[float, float]]:
    """Read ``--nav``, check the systems and the start; return the orbit, (start, span end)."""
    from psdbound.io import PreciseOrbit, read_orbit

    orbit = read_orbit(path)
    missing = [c for c in systems if c not in orbit.systems]
    if not missing and not isinstance(orbit, PreciseOrbit):
        missing = [c for c in systems if orbit.reference_times_gps_s(c).size == 0]
    if missing:
        names = ", ".join(_SYSTEM_NAMES[c] for c in missing)
        raise InputError(
            f"no {names} orbits for --systems {systems}; the file has "
            f"{', '.join(orbit.systems) or 'none'} (use --systems)",
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


def _run_series(args: argparse.Namespace) -> int:
    """``--nominal`` / ``--nav``: the VPL over time."""
    from psdbound.aviation import (
        SEED004_START_GPS_S,
        nominal_orbit,
        sky_over,
        vpl_series,
        write_vpl_series,
    )
    from psdbound.common.notices import warn
    from psdbound.common.outputs import check_writable_folder
    from psdbound.io.geometry import geodetic_to_ecef

    lat, lon, h = _position(args.position)
    kopts = _k_options(args)
    hours = _positive(args.hours, 24.0, "--hours", "h")
    step = _positive(args.step_s, 300.0, "--step-s", "s")
    mask = 5.0 if args.mask_deg is None else args.mask_deg
    if not 0.0 <= mask < 90.0:
        raise InputError(f"--mask-deg must be in [0, 90) deg, got {mask:g}")
    if args.val_m is not None:
        _positive(args.val_m, 0.0, "--val-m", "m")
    n_epochs = math.ceil(hours * 3600.0 / step)
    if n_epochs > MAX_EPOCHS:
        raise InputError(
            f"--hours {hours:g} at --step-s {step:g} gives {n_epochs} epochs; at most "
            f"{MAX_EPOCHS} (raise --step-s)"
        )
    if args.out:
        check_writable_folder(args.out, option="--out")
    if args.nominal:
        if args.systems:
            raise InputError("--systems applies to --nav; --nominal names the constellations")
        systems = args.nominal
        t0 = SEED004_START_GPS_S if args.start is None else _start(args.start)
        orbit, end = nominal_orbit(systems, start_gps_s=t0, duration_s=hours * 3600.0), math.inf
    else:
        systems = args.systems or "GE"
        orbit, (t0, end) = _nav_orbit(args.nav, systems, args.start)
    t = [t0 + step * k for k in range(n_epochs)]
    if t[-1] > end:
        warn(
            f"epochs after {_label(end)} GPS are beyond the --nav file's span: no orbit, "
            f"they count as unavailable"
        )
    rx = geodetic_to_ecef(lat, lon, h)
    sky = sky_over(orbit, rx, t, systems=systems, elevation_mask_deg=mask)
    series = vpl_series(sky, **kopts, **_budget_options(args))
    print(
        f"user at {lat:.4f} deg N, {lon:.4f} deg E, {h:g} m; {args.process} "
        f"{args.frequency}, tau {args.tau_gnd:g}/{args.tau_air:g} s, GAD-{args.gad}, "
        f"M = {args.receivers}, rho = {args.rho:g}, x_air = {args.x_air_km:g} km, "
        f"xi {args.xi_formula}"
    )
    k = series.options["multipliers"]
    print(f"K_ffmd = {k['k_ffmd']['value']:.3f} ({k['k_ffmd']['source']})")
    print(f"K_md_e = {k['k_md_e']['value']:.3f} ({k['k_md_e']['source']})")
    print(series.summary(val_m=args.val_m))
    if args.out:
        for f in write_vpl_series(series, args.out, val_m=args.val_m):
            print(f"wrote {f}")
    return 0
