"""``psdbound budget``: the LADGNSS error budget and VPL of one satellite geometry (seed 004).

Registered by :mod:`psdbound.cli.main` through :func:`add_parser`; prints
:func:`psdbound.aviation.budget_report` (per-satellite ground, airborne,
ionosphere and troposphere sigmas and the fault-free / ephemeris VPLs).
"""

from __future__ import annotations

import argparse
from typing import Any

from psdbound.errors import InputError

__all__ = ["add_parser", "run"]


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
        description="Seed 004 error budget (GAD ground, AAD-A airborne, ionosphere, "
        "troposphere) vs elevation and smoothing time, and VPL_H0 / VPL_eph.",
        epilog="example: psdbound budget --sat 10,12 --sat 80,25 --sat 150,38 "
        "--sat 200,47 --sat 260,60 --tau-gnd 30 --tau-air 30",
    )
    p.add_argument(
        "--sat",
        action="append",
        default=[],
        metavar="AZ,EL",
        help="satellite azimuth,elevation in deg, repeatable (required, at least 4)",
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
    p.set_defaults(func=run)


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
        Malformed ``--sat``, fewer than 4 satellites, bad options or geometry.
    """
    from psdbound.aviation import budget_report

    az, el = [], []
    for s in args.sat:
        try:
            a, e = (float(v) for v in s.split(","))
        except ValueError:
            raise InputError(f"--sat {s!r}: expected AZ,EL in degrees, e.g. 80,25") from None
        az.append(a)
        el.append(e)
    if len(el) < 4:
        raise InputError(f"give at least 4 --sat AZ,EL (got {len(el)})")
    print(
        budget_report(
            az,
            el,
            n_receivers=args.receivers,
            process=args.process,
            base_frequency=args.frequency,
            tau_gnd_s=args.tau_gnd,
            tau_air_s=args.tau_air,
            gad=args.gad,
            rho=args.rho,
            x_air_m=1000.0 * args.x_air_km,
        )
    )
    return 0
