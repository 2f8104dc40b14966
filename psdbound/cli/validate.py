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
from dataclasses import dataclass
from typing import Any

from psdbound.cli.actions import Once
from psdbound.cli.config_file import add_config_option
from psdbound.cli.schema import CliOption, Schema, SchemaHelpFormatter, add_options, read_options
from psdbound.common.options import Choice, Number, Tuple, check_fields, option
from psdbound.errors import InputError

__all__ = ["OPTIONS", "SCHEMA", "ValidateOptions", "add_parser", "run"]


@dataclass(frozen=True)
class ValidateOptions:
    """The options of ``psdbound validate`` besides the fit's (``alpha``, ``threshold``).

    Those two are :class:`~psdbound.validation.ValidationOptions`' (section
    ``validation`` of :data:`SCHEMA`): the same defaults and checks as the
    fit's cutoff validation. The other names are the keywords of
    :func:`psdbound.validation.run_validation`.
    """

    cutoff_hz: float | None = option(None, Number(lo=1e-6, hi=10.0, unit="Hz", optional=True))
    geometries: tuple[str, ...] = ()
    rate: str = "orbit"
    modes_file: str | None = None
    theta0_deg: float = option(30.0, Number(lo=-90.0, hi=90.0, unit="deg"))
    amplitude_deg: float | None = option(
        None, Number(lo=0.0, hi=90.0, lo_open=True, unit="deg", optional=True)
    )
    nav_file: str | None = None
    receiver_ecef_m: tuple[float, ...] | None = option(
        None, Tuple(Number(), lengths=(3,), what="X Y Z in m", optional=True)
    )
    system: str = "G"
    sats: tuple[str, ...] = ()
    elevation_mask_deg: float = option(5.0, Number(lo=0.0, hi=90.0, hi_open=True, unit="deg"))
    min_pass_s: float = option(3600.0, Number(lo=0.0, hi=86400.0, lo_open=True, unit="s"))
    convention: str = option("both", Choice(("both", "physical", "thesis"), noun="convention"))
    wavelength_m: float | None = option(
        None, Number(lo=0.0, hi=10.0, lo_open=True, unit="m", optional=True)
    )
    distance_tolerance_m: float = option(0.0, Number(lo=0.0, hi=1e4, unit="m"))
    out_dir: str | None = None
    figures: bool = True

    def __post_init__(self) -> None:
        check_fields(self)


#: The schema of ``validate``'s options: its own, and the fit's cutoff-validation options.
SCHEMA = Schema(
    {
        "check": "psdbound.cli.validate:ValidateOptions",
        "validation": "psdbound.validation.options:ValidationOptions",
    }
)

_O = CliOption
_FILE = {"metavar": "FILE"}
#: Every ``validate`` option: its schema field, flag, help and group (None: ``options``).
OPTIONS: tuple[CliOption, ...] = (
    _O(
        "check",
        "cutoff_hz",
        ("--cutoff-hz",),
        "high-pass cutoff f_c, Hz (required)",
        None,
        {"required": True},
    ),
    _O(
        "check",
        "geometries",
        ("--geometry",),
        "reflection, repeatable: wall:d=METRES or ground:h=METRES (required, at least one)",
        None,
        {"action": "append", "metavar": "SPEC"},
    ),
    _O(
        "check",
        "rate",
        ("--rate",),
        "geometry rate: orbit (GPS, half a sidereal day), orbit-galileo, orbit-glonass, "
        "orbit-beidou, an aircraft mode (phugoid, spiral, or from --modes), or a frequency in Hz",
        None,
    ),
    _O(
        "check",
        "modes_file",
        ("--modes",),
        "TOML file adding aircraft modes (default: none)",
        None,
        _FILE,
    ),
    _O(
        "check",
        "theta0_deg",
        ("--theta0-deg",),
        "aircraft modes: mean angle of arrival relative to the reflector, deg",
        None,
    ),
    _O(
        "check",
        "amplitude_deg",
        ("--amplitude-deg",),
        "aircraft modes: attitude oscillation amplitude, deg (default: the mode's, 2)",
        None,
    ),
    _O(
        "check",
        "nav_file",
        ("--nav",),
        "navigation or SP3 file: simulate real passes (default: none)",
        None,
        {"action": Once, **_FILE},
    ),
    _O(
        "check",
        "receiver_ecef_m",
        ("--receiver-ecef",),
        "receiver ECEF position for --nav, m (required with --nav)",
        None,
        {"type": float, "nargs": 3, "metavar": ("X", "Y", "Z")},
    ),
    _O("check", "system", ("--system",), "satellite system of the passes", None),
    _O(
        "check",
        "sats",
        ("--sat",),
        "satellite for --nav, repeatable (default all)",
        None,
        {"action": "append"},
    ),
    _O(
        "check",
        "elevation_mask_deg",
        ("--elevation-mask-deg",),
        "elevation mask of the passes, deg",
        None,
    ),
    _O(
        "check",
        "min_pass_s",
        ("--min-pass-min",),
        "shortest pass simulated, minutes",
        None,
        scale=60.0,
        unit="min",
    ),
    _O(
        "validation", "alpha", ("--alpha",), "reflected/direct amplitude ratio, dimensionless", None
    ),
    _O(
        "validation",
        "threshold",
        ("--threshold",),
        "largest acceptable fraction of multipath power below f_c, fraction",
        None,
    ),
    _O("check", "convention", ("--convention",), "phase convention(s) to report", None),
    _O(
        "check",
        "wavelength_m",
        ("--wavelength-m",),
        "carrier wavelength, m (default GPS L1, 0.190294)",
        None,
    ),
    _O(
        "check",
        "distance_tolerance_m",
        ("--distance-tolerance-m",),
        "also sweep each distance over +- this many metres and judge the worst, m",
        None,
    ),
    _O(
        "check",
        "out_dir",
        ("--out",),
        "write the table (CSV), the document (JSON), the PNG figures and the HTML page here "
        "(default: print only)",
        None,
        {"metavar": "DIR"},
    ),
    _O(
        "check",
        "figures",
        ("--no-figures",),
        "with --out: skip the PNG figures (the page has no figures)",
        None,
        {"action": "store_true"},
        convert=lambda given: {"figures": not given},
    ),
)


def add_parser(subparsers: Any) -> None:
    """Add the ``validate`` subcommand to an ``add_subparsers()`` object.

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        From :meth:`argparse.ArgumentParser.add_subparsers`.
    """
    p = subparsers.add_parser(
        "validate",
        formatter_class=SchemaHelpFormatter,
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
    add_options(p, OPTIONS, SCHEMA.spec, groups=(None,), defaults=SCHEMA.default)
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
    from psdbound.common.outputs import check_writable_folder
    from psdbound.validation import run_validation

    if not args.geometry:
        raise InputError("give at least one --geometry, e.g. --geometry wall:d=25")
    if not (args.cutoff_hz > 0.0):
        raise InputError(f"--cutoff-hz must be > 0, got {args.cutoff_hz}")
    given = read_options(args, OPTIONS, SCHEMA.spec)
    opts = SCHEMA.build("check", given.get("check", {}))
    fit_opts = SCHEMA.build("validation", given.get("validation", {}))
    if opts.nav_file and opts.receiver_ecef_m is None:
        raise InputError("--nav needs --receiver-ecef X Y Z (receiver position, m)")
    if opts.out_dir:
        check_writable_folder(opts.out_dir, option="--out")
    for sat in opts.sats:
        if not re.fullmatch(r"[A-Z]\d{2}", sat):
            raise InputError(f"--sat {sat!r}: expected a satellite id such as G05")
    report, written = run_validation(
        list(opts.geometries),
        cutoff_hz=opts.cutoff_hz,
        rate=opts.rate,
        alpha=fit_opts.alpha,
        threshold=fit_opts.threshold,
        convention=opts.convention,
        wavelength_m=opts.wavelength_m,
        modes_file=opts.modes_file,
        theta0_deg=opts.theta0_deg,
        amplitude_deg=opts.amplitude_deg,
        nav_file=opts.nav_file,
        receiver_ecef_m=opts.receiver_ecef_m,
        sats=list(opts.sats) or None,
        system=opts.system,
        elevation_mask_deg=opts.elevation_mask_deg,
        min_pass_s=opts.min_pass_s,
        distance_tolerance_m=opts.distance_tolerance_m,
        out_dir=opts.out_dir,
        figures=opts.figures,
    )
    print(report.summary())
    if written:
        print("wrote " + ", ".join(str(p) for p in written))
    return 0
