"""``psdbound inspect``: list systems, signals and tracking arcs of observation files.

With ``--nav`` it also prints the orbit's coverage of each observation file
(systems, time span, observed satellites without a position) and, when no
arc results, why.
"""

from __future__ import annotations

import argparse

from psdbound.errors import InputError

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``inspect`` subcommand."""
    p = sub.add_parser(
        "inspect",
        help="read observation files and list systems, signals and tracking arcs",
        description="Read RINEX observation files (2.x/3.x/4.x, gzip, Hatanaka) and "
        "print their content and the continuous dual-signal tracking arcs. With --nav, "
        "also the orbit file's coverage of the observations (systems, span, satellites "
        "without ephemerides).",
    )
    p.add_argument("obs", nargs="+", help="RINEX observation file(s) (required)")
    p.add_argument(
        "--nav",
        action="extend",
        nargs="+",
        metavar="NAV",
        help="navigation (RINEX) or SP3 file(s) for elevations: several are joined "
        "(default: none, no elevations)",
    )
    p.add_argument("--system", default="G", help="satellite system letter (default G)")
    p.add_argument(
        "--signals", help="phase signal pair, e.g. L1C,L2W (default: per-system default)"
    )
    p.add_argument(
        "--min-arc-min", type=float, default=30.0, help="minimum arc length, minutes (default: 30)"
    )
    p.add_argument(
        "--elevation-mask-deg", type=float, default=0.0, help="elevation mask, degrees (default: 0)"
    )
    p.set_defaults(func=run)


def _options(args: argparse.Namespace) -> tuple[list[str] | None, float, float]:
    """Check the options before any file is read; return (signals, min length s, mask deg)."""
    from psdbound.arcs import ArcOptions
    from psdbound.common.options import Choice, Number, OptionError, Text, Tuple

    Number(lo=0.0, hi=1440.0, lo_open=True, unit="min")("--min-arc-min", args.min_arc_min)
    try:
        arcs = ArcOptions(
            min_length_s=60.0 * args.min_arc_min, elevation_mask_deg=args.elevation_mask_deg
        )
    except OptionError as exc:
        raise exc.relabel("--elevation-mask-deg") from None
    Choice(("G", "E", "R", "C", "J", "S", "I"), noun="satellite system")("--system", args.system)
    signals = None
    if args.signals is not None:
        code = Text(r"L[1-9][A-Z]?", what="a phase code such as 'L1C'")
        signals = list(
            Tuple(
                code,
                lengths=(2,),
                split=",",
                distinct=True,
                what="two phase codes such as 'L1C,L2W'",
            )("--signals", args.signals)
        )
    return signals, arcs.min_length_s, arcs.elevation_mask_deg


def run(args: argparse.Namespace) -> int:
    """Print file summaries and arcs; return the exit code."""
    from psdbound.arcs import find_arcs
    from psdbound.common.notices import warn
    from psdbound.io import orbit_coverage, read_obs, read_orbit

    signals, min_length_s, mask_deg = _options(args)
    orbit = read_orbit(args.nav) if args.nav else None
    if orbit is None and mask_deg > 0:
        warn(
            f"--elevation-mask-deg {mask_deg:g} is not applied: without --nav there are no "
            "elevations (give a navigation or SP3 file)"
        )
    for path in args.obs:
        obs = read_obs(path)
        print(obs.summary())
        if args.system not in obs.blocks:
            raise InputError(
                f"no observations of system {args.system!r}; present: {' '.join(obs.systems)}",
                path=path,
            )
        if orbit is not None:
            # the full reason comes with the error find_arcs raises for --system
            print(orbit_coverage(orbit, obs).summary(reasons=False))
        arcs = find_arcs(  # raises, with the reason, when the orbit covers no satellite
            obs,
            signals,
            system=args.system,
            orbit=orbit,
            min_length_s=min_length_s,
            elevation_mask_deg=mask_deg,
        )
        print(arcs.summary())
        if not len(arcs):
            print(f"  no arc: {arcs.empty_reason()}")
        for a in arcs:
            el = ""
            if a.elevation_deg is not None:
                el = f"  elevation {a.elevation_deg.min():5.1f}-{a.elevation_deg.max():5.1f} deg"
            print(
                f"  arc {a.arc_id:3d} {a.sat}  {a.n:6d} epochs  {a.duration_s / 60:7.1f} min"
                f"  starts on {a.start_reason}{el}"
            )
    return 0
