"""Argument parsing and dispatch for ``python -m psdbound``."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from psdbound import __version__
from psdbound.errors import InputError

__all__ = ["main", "build_parser", "EXIT_OK", "EXIT_BAD_INPUT", "EXIT_INTERNAL"]

EXIT_OK = 0
EXIT_INTERNAL = 1
EXIT_BAD_INPUT = 2

# subcommands whose pipeline stage has not landed yet, and the issue that brings it
_PENDING = {
    "fit": ("fit a PSD bound to RINEX observations (or the demo data)", 8),
    "cutoff": ("select the ionosphere high-pass cutoff frequency", 4),
    "validate": ("validate a cutoff with the Jacobi-Anger expansion", 6),
    "simulate": ("simulate observations with known multipath", 7),
    "report": ("re-render a report from a result file", 8),
}


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose usage errors are one line and exit code 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    """Return the ``psdbound`` argument parser with all subcommands."""
    parser = _Parser(
        prog="psdbound",
        description="Provable Gauss-Markov + white-noise PSD bounds of GNSS "
        "carrier-phase multipath.",
        epilog="Exit codes: 0 ok, 2 bad input, 1 internal error.",
    )
    parser.add_argument("--version", action="version", version=f"psdbound {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    p = sub.add_parser(
        "inspect",
        help="read observation files and list systems, signals and tracking arcs",
        description="Read RINEX observation files (2.x/3.x, gzip, Hatanaka) and "
        "print their content and the continuous dual-signal tracking arcs.",
    )
    p.add_argument("obs", nargs="+", help="RINEX observation file(s)")
    p.add_argument("--nav", help="navigation (RINEX) or SP3 file for elevations")
    p.add_argument("--system", default="G", help="satellite system letter (default G)")
    p.add_argument(
        "--signals", help="phase signal pair, e.g. L1C,L2W (default: per-system default)"
    )
    p.add_argument(
        "--min-arc-min", type=float, default=30.0, help="minimum arc length, minutes (30)"
    )
    p.add_argument(
        "--elevation-mask-deg", type=float, default=0.0, help="elevation mask, degrees (0)"
    )
    p.set_defaults(func=_cmd_inspect)

    for name, (text, issue) in _PENDING.items():
        sp = sub.add_parser(name, help=f"{text} (not available yet)", description=text)
        sp.add_argument("args", nargs=argparse.REMAINDER, help=argparse.SUPPRESS)
        sp.set_defaults(func=_pending(name, issue))
    return parser


def _pending(name: str, issue: int):  # noqa: ANN202
    def run(args: argparse.Namespace) -> int:
        print(
            f"psdbound {name}: not available yet (this pipeline stage arrives with issue "
            f"#{issue}); nothing was computed.",
            file=sys.stderr,
        )
        return EXIT_INTERNAL

    return run


def _cmd_inspect(args: argparse.Namespace) -> int:
    from psdbound.io import find_arcs, read_obs, read_orbit

    orbit = read_orbit(args.nav) if args.nav else None
    signals = args.signals.split(",") if args.signals else None
    for path in args.obs:
        obs = read_obs(path)
        print(obs.summary())
        if args.system not in obs.blocks:
            raise InputError(
                f"no observations of system {args.system!r}; present: {' '.join(obs.systems)}",
                path=path,
            )
        arcs = find_arcs(
            obs,
            signals,
            system=args.system,
            orbit=orbit,
            min_length_s=args.min_arc_min * 60.0,
            elevation_mask_deg=args.elevation_mask_deg,
        )
        print(arcs.summary())
        for a in arcs:
            el = ""
            if a.elevation_deg is not None:
                el = f"  elevation {a.elevation_deg.min():5.1f}-{a.elevation_deg.max():5.1f} deg"
            print(
                f"  arc {a.arc_id:3d} {a.sat}  {a.n:6d} epochs  {a.duration_s / 60:7.1f} min"
                f"  starts on {a.start_reason}{el}"
            )
    return EXIT_OK


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the process exit code.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 on success, 2 on bad input, 1 on an internal error.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "command", None):
        parser.print_help()
        return EXIT_OK
    try:
        return int(args.func(args))
    except InputError as exc:
        print(f"psdbound {args.command}: error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("psdbound: interrupted", file=sys.stderr)
        return EXIT_INTERNAL
