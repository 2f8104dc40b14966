"""``psdbound validate``: does a cutoff remove too much multipath.

Registered by :mod:`psdbound.cli.main` through :func:`add_parser`; the
command checks the options, runs :func:`psdbound.validation.run_validation`
(which, with ``--out``, writes ``validation.csv``, ``validation.json``
(schema ``validation.schema.json``), the figures
``validation_expansion.png`` and, when a direct simulation ran,
``validation_direct.png``, and ``validation.html`` (the verdict, tables and
figures), each atomically) and prints the table. A failing
verdict is a result, not an error: the exit code is 0 unless the input is
bad (2).
"""

from __future__ import annotations

import argparse
import re
from typing import Any

from psdbound.cli.actions import Once
from psdbound.cli.config_file import add_config_option
from psdbound.errors import InputError

__all__ = ["add_parser", "run"]


def add_parser(subparsers: Any) -> None:
    """Add the ``validate`` subcommand to an ``add_subparsers()`` object.

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        From :meth:`argparse.ArgumentParser.add_subparsers`.
    """
    p = subparsers.add_parser(
        "validate",
        help="validate a cutoff with the Jacobi-Anger expansion and direct simulation",
        description="Fraction of geometric multipath power below a high-pass cutoff, "
        "for ground (h) and wall (d) reflections, from the Jacobi-Anger expansion "
        "(thesis model and aircraft attitude oscillations) and from a direct simulation "
        "of the exact phase error along satellite passes or oscillations; pass/fail "
        "against a threshold, in the thesis convention (z = 2D/lambda) and the physical "
        "one (z = 4 pi D/lambda). The verdict uses the physical convention.",
        epilog="example: psdbound validate --cutoff-hz 9.55e-4 --geometry wall:d=25 "
        "--geometry ground:h=1.5 --rate orbit --out out/",
    )
    p.add_argument(
        "--cutoff-hz", type=float, required=True, help="high-pass cutoff f_c, Hz (required)"
    )
    p.add_argument(
        "--geometry",
        action="append",
        default=[],
        metavar="SPEC",
        help="reflection, repeatable: wall:d=METRES or ground:h=METRES (required, at least one)",
    )
    p.add_argument(
        "--rate",
        default="orbit",
        help="geometry rate: orbit (GPS, half a sidereal day), orbit-galileo, orbit-glonass, "
        "orbit-beidou, an aircraft mode (phugoid, spiral, or from --modes), or a frequency "
        "in Hz (default orbit)",
    )
    p.add_argument(
        "--modes", metavar="FILE", help="TOML file adding aircraft modes (default: none)"
    )
    p.add_argument(
        "--theta0-deg",
        type=float,
        default=30.0,
        help="aircraft modes: mean angle of arrival relative to the reflector, deg (default: 30)",
    )
    p.add_argument(
        "--amplitude-deg",
        type=float,
        help="aircraft modes: attitude oscillation amplitude, deg (default: the mode's, 2)",
    )
    p.add_argument(
        "--nav",
        action=Once,
        metavar="FILE",
        help="navigation or SP3 file: simulate real passes (default: none)",
    )
    p.add_argument(
        "--receiver-ecef",
        type=float,
        nargs=3,
        metavar=("X", "Y", "Z"),
        help="receiver ECEF position for --nav, m (required with --nav)",
    )
    p.add_argument("--system", default="G", help="satellite system of the passes (default: G)")
    p.add_argument("--sat", action="append", help="satellite for --nav, repeatable (default all)")
    p.add_argument(
        "--elevation-mask-deg",
        type=float,
        default=5.0,
        help="elevation mask of the passes, deg (default: 5)",
    )
    p.add_argument(
        "--min-pass-min",
        type=float,
        default=60.0,
        help="shortest pass simulated, minutes (default: 60)",
    )
    p.add_argument(
        "--alpha",
        type=float,
        default=0.1,
        help="reflected/direct amplitude ratio, dimensionless (default: 0.1)",
    )
    p.add_argument(
        "--threshold",
        type=float,
        default=0.10,
        help="largest acceptable fraction of multipath power below f_c, fraction (default: 0.10)",
    )
    p.add_argument(
        "--convention",
        choices=("both", "physical", "thesis"),
        default="both",
        help="phase convention(s) to report (default: both)",
    )
    p.add_argument(
        "--wavelength-m", type=float, help="carrier wavelength, m (default GPS L1, 0.190294)"
    )
    p.add_argument(
        "--distance-tolerance-m",
        type=float,
        default=0.0,
        help="also sweep each distance over +- this many metres and judge the worst, m "
        "(default: 0)",
    )
    p.add_argument(
        "--out",
        metavar="DIR",
        help="write the table (CSV), the document (JSON), the PNG figures and the HTML page "
        "here (default: print only)",
    )
    p.add_argument(
        "--no-figures",
        action="store_true",
        help="with --out: skip the PNG figures (the page has no figures)",
    )
    add_config_option(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Run ``psdbound validate``.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options of :func:`add_parser`.

    Returns
    -------
    int
        0 (also when the verdict is a failure).

    Raises
    ------
    InputError
        Bad geometry, distance, cutoff, rate, mode file, navigation file or
        output folder.
    """
    from psdbound.common.options import Number, Tuple
    from psdbound.common.outputs import check_writable_folder
    from psdbound.validation import run_validation

    if not args.geometry:
        raise InputError("give at least one --geometry, e.g. --geometry wall:d=25")
    if not (args.cutoff_hz > 0.0):
        raise InputError(f"--cutoff-hz must be > 0, got {args.cutoff_hz}")
    checks = {
        "--cutoff-hz": (args.cutoff_hz, Number(lo=1e-6, hi=10.0, unit="Hz")),
        "--theta0-deg": (args.theta0_deg, Number(lo=-90.0, hi=90.0, unit="deg")),
        "--amplitude-deg": (
            args.amplitude_deg,
            Number(lo=0.0, hi=90.0, lo_open=True, unit="deg", optional=True),
        ),
        "--elevation-mask-deg": (
            args.elevation_mask_deg,
            Number(lo=0.0, hi=90.0, hi_open=True, unit="deg"),
        ),
        "--min-pass-min": (args.min_pass_min, Number(lo=0.0, hi=1440.0, lo_open=True, unit="min")),
        "--alpha": (args.alpha, Number(lo=0.0, hi=1.0, lo_open=True)),
        "--threshold": (args.threshold, Number(lo=0.0, hi=1.0, lo_open=True, hi_open=True)),
        "--wavelength-m": (
            args.wavelength_m,
            Number(lo=0.0, hi=10.0, lo_open=True, unit="m", optional=True),
        ),
        "--distance-tolerance-m": (args.distance_tolerance_m, Number(lo=0.0, hi=1e4, unit="m")),
        "--receiver-ecef": (
            args.receiver_ecef,
            Tuple(Number(), lengths=(3,), what="X Y Z in m")
            if args.receiver_ecef is not None
            else Number(optional=True),
        ),
    }
    for flag, (value, spec) in checks.items():
        spec(flag, value)
    if args.nav and args.receiver_ecef is None:
        raise InputError("--nav needs --receiver-ecef X Y Z (receiver position, m)")
    if args.out:
        check_writable_folder(args.out, option="--out")
    for sat in args.sat or ():
        if not re.fullmatch(r"[A-Z]\d{2}", sat):
            raise InputError(f"--sat {sat!r}: expected a satellite id such as G05")
    report, written = run_validation(
        args.geometry,
        cutoff_hz=args.cutoff_hz,
        rate=args.rate,
        alpha=args.alpha,
        threshold=args.threshold,
        convention=args.convention,
        wavelength_m=args.wavelength_m,
        modes_file=args.modes,
        theta0_deg=args.theta0_deg,
        amplitude_deg=args.amplitude_deg,
        nav_file=args.nav,
        receiver_ecef_m=args.receiver_ecef,
        sats=args.sat,
        system=args.system,
        elevation_mask_deg=args.elevation_mask_deg,
        min_pass_s=args.min_pass_min * 60.0,
        distance_tolerance_m=args.distance_tolerance_m,
        out_dir=args.out or None,
        figures=not args.no_figures,
    )
    print(report.summary())
    if written:
        print("wrote " + ", ".join(str(p) for p in written))
    return 0
