"""``psdbound simulate``: write a simulated data set (RINEX 3 obs + nav + truth)."""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``simulate`` subcommand."""
    p = sub.add_parser(
        "simulate",
        help="simulate observations with known multipath (RINEX 3 + ground truth)",
        description="Simulate carrier-phase and code observations with known multipath and "
        "write RINEX 3 observation/navigation files and the ground truth. "
        "'--preset demo' regenerates the embedded demo data set in its cache.",
    )
    p.add_argument("--preset", default="demo", help="named scenario: demo, short (default demo)")
    p.add_argument("--out", help="output folder (default: the demo cache for the demo preset)")
    p.add_argument("--seed", type=int, help="random seed (overrides the preset's)")
    p.add_argument("--duration-h", type=float, help="duration, hours")
    p.add_argument("--interval-s", type=float, help="sampling interval, seconds")
    p.add_argument("--lat-deg", type=float, help="latitude of antenna A, degrees")
    p.add_argument("--lon-deg", type=float, help="longitude of antenna A, degrees")
    p.add_argument("--start", help="start epoch, ISO date-time in GPS time")
    p.add_argument("--nav", help="navigation file for the geometry (default: nominal GPS)")
    p.add_argument("--single-antenna", action="store_true", help="write antenna A only")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Simulate and print the written files; return the exit code."""
    from psdbound.common.options import Number
    from psdbound.common.outputs import check_writable_folder
    from psdbound.simulate import demo_data, preset, simulate

    checks = {
        "--seed": (args.seed, Number(lo=0, hi=2**63 - 1, integer=True, optional=True)),
        "--duration-h": (args.duration_h, Number(lo=0, hi=24 * 366, lo_open=True, unit="h",
                                                 optional=True)),
        "--interval-s": (args.interval_s, Number(lo=0, hi=3600, lo_open=True, unit="s",
                                                 optional=True)),
        "--lat-deg": (args.lat_deg, Number(lo=-90, hi=90, unit="deg", optional=True)),
        "--lon-deg": (args.lon_deg, Number(lo=-180, hi=360, unit="deg", optional=True)),
    }  # fmt: skip
    for flag, (value, spec) in checks.items():
        spec(flag, value)
    if args.out:
        check_writable_folder(args.out, option="--out")
    sc = preset(args.preset)
    changes = {
        "seed": args.seed,
        "duration_s": None if args.duration_h is None else args.duration_h * 3600.0,
        "interval_s": args.interval_s,
        "lat_deg": args.lat_deg,
        "lon_deg": args.lon_deg,
        "start_gps": args.start,
        "nav_path": args.nav,
        "dual_antenna": False if args.single_antenna else None,
    }
    changes = {k: v for k, v in changes.items() if v is not None}
    if args.preset == "demo" and not changes:
        data = demo_data(regenerate=True, folder=args.out)
        files = [*data.obs_paths, data.nav_path, data.truth_path, data.truth_json_path]
    else:
        if changes:
            sc = sc.replace(**changes)
        out = Path(args.out) if args.out else Path("simulated") / sc.name
        res = simulate(sc, out)
        files = [*res.obs_paths, res.nav_path, res.truth_path, res.truth_json_path]
    for f in files:
        print(f)
    return 0
