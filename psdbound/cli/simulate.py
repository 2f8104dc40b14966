"""``psdbound simulate``: write a simulated data set (RINEX 3 obs + nav + truth).

Its options are its flags, so ``--config FILE.toml`` sets them as for the
other such commands (:mod:`psdbound.cli.config_file`); ``--scenario
FILE.toml`` is something else, the scenario's own fields (a ``[multipath]``
table, durations in s), layered over the preset before the flags.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from psdbound.cli.actions import Once
from psdbound.cli.config_file import add_config_option

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``simulate`` subcommand."""
    p = sub.add_parser(
        "simulate",
        help="simulate observations with known multipath (RINEX 3 + ground truth)",
        description="Simulate carrier-phase and code observations with known multipath and "
        "write RINEX 3 observation/navigation files and the ground truth. "
        "'--preset demo' regenerates the embedded demo data set in its cache. "
        "Parameters are layered: the preset, then --scenario FILE.toml (the scenario's "
        "fields, in its units), then the other flags; --config FILE.toml sets those flags "
        "(keys are the long flags, e.g. preset, duration_h, single_antenna, scenario, out).",
        epilog="example: psdbound simulate --preset demo --duration-h 6 --single-antenna "
        "--multipath sigma_gm_m=0.003,tau_s=120,sigma_wn_m=0.001,mapping=1,12,10 --out sim/",
    )
    p.add_argument("--preset", default="demo", help="named scenario: demo, short (default demo)")
    p.add_argument("--out", help="output folder (default: the demo cache for the demo preset)")
    p.add_argument("--seed", type=int, help="random seed, count (default: the preset's)")
    p.add_argument("--duration-h", type=float, help="duration, hours (default: the preset's)")
    p.add_argument(
        "--interval-s", type=float, help="sampling interval, seconds (default: the preset's)"
    )
    p.add_argument(
        "--lat-deg", type=float, help="latitude of antenna A, degrees (default: the preset's)"
    )
    p.add_argument(
        "--lon-deg", type=float, help="longitude of antenna A, degrees (default: the preset's)"
    )
    p.add_argument("--start", help="start epoch, ISO date-time in GPS time (default: the preset's)")
    p.add_argument(
        "--nav", action=Once, help="navigation file for the geometry (default: nominal GPS)"
    )
    p.add_argument("--single-antenna", action="store_true", help="write antenna A only")
    p.add_argument(
        "--scenario",
        metavar="FILE",
        help="TOML file of scenario fields, with a [multipath] table (overrides the preset; "
        "default: none)",
    )
    p.add_argument(
        "--multipath",
        metavar="SPEC",
        help="injected multipath, any of sigma_gm_m=M,tau_s=S,sigma_wn_m=M,mapping=A,B,C_DEG "
        "(zenith scale; sigmas <= 0.05 m, 0 < tau_s <= 86400 s; default: the preset's)",
    )
    p.add_argument(
        "--receiver-noise-m",
        type=float,
        help="white receiver phase noise per signal, metres (default: the preset's)",
    )
    add_config_option(p)
    p.set_defaults(func=run)


#: Scenario fields set by a flag of their own (error messages name the flag).
_FLAGS = {
    "start_gps": "--start",
    "nav_path": "--nav",
    "receiver_noise_m": "--receiver-noise-m",
    "duration_s": "--duration-h",
    "interval_s": "--interval-s",
    "seed": "--seed",
}


def _warn_beyond_limit(sc: Any, args: argparse.Namespace) -> None:
    """Warn when the multipath breaks the carrier-multipath limit at the elevation mask."""
    from psdbound.common.notices import warn
    from psdbound.simulate.simulator import multipath_limit_problem

    if args.multipath is not None:
        label = "--multipath"
    elif args.scenario:
        label = f"[multipath] of {args.scenario}"
    else:
        label = f"the {args.preset} preset's multipath"
    problem = multipath_limit_problem(sc, label)
    if problem:
        warn(problem)


def run(args: argparse.Namespace) -> int:
    """Simulate and print the written files; return the exit code."""
    from psdbound.common.options import Number, OptionError
    from psdbound.common.outputs import check_writable_folder
    from psdbound.simulate import (
        MAX_MULTIPATH_M,
        MultipathModel,
        Scenario,
        demo_data,
        preset,
        simulate,
    )

    checks = {
        "--seed": (args.seed, Number(lo=0, hi=2**63 - 1, integer=True, optional=True)),
        "--duration-h": (
            args.duration_h,
            Number(lo=0, hi=24 * 366, lo_open=True, unit="h", optional=True),
        ),
        "--interval-s": (
            args.interval_s,
            Number(lo=0, hi=3600, lo_open=True, unit="s", optional=True),
        ),
        "--lat-deg": (args.lat_deg, Number(lo=-90, hi=90, unit="deg", optional=True)),
        "--lon-deg": (args.lon_deg, Number(lo=-180, hi=360, unit="deg", optional=True)),
        "--receiver-noise-m": (
            args.receiver_noise_m,
            Number(lo=0, hi=MAX_MULTIPATH_M, unit="m", optional=True),
        ),
    }
    for flag, (value, spec) in checks.items():
        spec(flag, value)
    if args.out:
        check_writable_folder(args.out, option="--out")
    sc = preset(args.preset)
    if args.scenario:
        sc = Scenario.from_toml(args.scenario, base=sc)
    multipath = None
    if args.multipath is not None:
        multipath = MultipathModel.from_spec(args.multipath, base=sc.multipath, label="--multipath")
    changes = {
        "seed": args.seed,
        "duration_s": None if args.duration_h is None else args.duration_h * 3600.0,
        "interval_s": args.interval_s,
        "lat_deg": args.lat_deg,
        "lon_deg": args.lon_deg,
        "start_gps": args.start,
        "nav_path": args.nav,
        "dual_antenna": False if args.single_antenna else None,
        "multipath": multipath,
        "receiver_noise_m": args.receiver_noise_m,
    }
    changes = {k: v for k, v in changes.items() if v is not None}
    if args.preset == "demo" and not changes and not args.scenario:
        data = demo_data(regenerate=True, folder=args.out)
        files = [*data.obs_paths, data.nav_path, data.truth_path, data.truth_json_path]
    else:
        try:
            sc = sc.replace(**changes)
        except OptionError as exc:  # a flag's value the scenario's schema refuses
            raise exc.relabel(_FLAGS.get(exc.name, exc.label)) from None
        _warn_beyond_limit(sc, args)
        out = Path(args.out) if args.out else Path("simulated") / sc.name
        res = simulate(sc, out)
        files = [*res.obs_paths, res.nav_path, res.truth_path, res.truth_json_path]
    for f in files:
        print(f)
    return 0
