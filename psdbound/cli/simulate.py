"""``psdbound simulate``: write a simulated data set (RINEX 3 obs + nav + truth).

Its options are its flags, so ``--config FILE.toml`` sets them as for the
other such commands (:mod:`psdbound.cli.config_file`); ``--scenario
FILE.toml`` is something else, the scenario's own fields (a ``[multipath]``
table, durations in s), layered over the preset before the flags.
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from psdbound.cli.actions import Once
from psdbound.cli.config_file import add_config_option
from psdbound.cli.schema import (
    CliOption,
    Schema,
    SchemaHelpFormatter,
    add_options,
    flag_of,
    read_options,
)

__all__ = ["OPTIONS", "SCHEMA", "SimulateOptions", "add_parser", "run"]


@dataclass(frozen=True)
class SimulateOptions:
    """The options of ``psdbound simulate`` that are not a scenario field.

    The others are :class:`~psdbound.simulate.Scenario`'s own fields (section
    ``scenario`` of :data:`SCHEMA`: the same checks as a scenario file); their
    defaults are the preset's.
    """

    preset: str = "demo"
    out: str | None = None
    scenario: str | None = None
    multipath: str | None = None
    overwrite: bool = False


#: The schema of ``simulate``'s options: its own, and the scenario's fields.
SCHEMA = Schema(
    {
        "command": "psdbound.cli.simulate:SimulateOptions",
        "scenario": "psdbound.simulate.scenario:Scenario",
    }
)

_O = CliOption
_C, _S = "command", "scenario"
_PRESETS = "(default: the preset's)"
#: Every ``simulate`` option: its schema field, flag and help (all in ``options``).
OPTIONS: tuple[CliOption, ...] = (
    _O(_C, "preset", ("--preset",), "named scenario: demo, short (default demo)", None),
    _O(
        _C,
        "out",
        ("--out",),
        "output folder: new, empty, or an earlier simulation's, replaced as a whole (default: "
        "the demo cache for the demo preset, else simulated/<scenario name>)",
        None,
    ),
    _O(
        _C,
        "overwrite",
        ("--overwrite",),
        "write into an --out folder that holds other files: the files of earlier simulations "
        "in it are removed, nothing else is touched",
        None,
        {"action": "store_true"},
    ),
    _O(_S, "seed", ("--seed",), f"random seed, count {_PRESETS}", None),
    _O(
        _S,
        "duration_s",
        ("--duration-h",),
        f"duration, hours {_PRESETS}",
        None,
        scale=3600.0,
        unit="h",
    ),
    _O(_S, "interval_s", ("--interval-s",), f"sampling interval, seconds {_PRESETS}", None),
    _O(_S, "lat_deg", ("--lat-deg",), f"latitude of antenna A, degrees {_PRESETS}", None),
    _O(_S, "lon_deg", ("--lon-deg",), f"longitude of antenna A, degrees {_PRESETS}", None),
    _O(_S, "start_gps", ("--start",), f"start epoch, ISO date-time in GPS time {_PRESETS}", None),
    _O(
        _S,
        "nav_path",
        ("--nav",),
        "navigation file for the geometry (default: nominal GPS)",
        None,
        {"action": Once},
    ),
    _O(
        _S,
        "dual_antenna",
        ("--single-antenna",),
        "write antenna A only",
        None,
        {"action": "store_true"},
        convert=lambda given: {"dual_antenna": False} if given else {},
    ),
    _O(
        _C,
        "scenario",
        ("--scenario",),
        "TOML file of scenario fields, with a [multipath] table (overrides the preset; "
        "default: none)",
        None,
        {"metavar": "FILE"},
    ),
    _O(
        _C,
        "multipath",
        ("--multipath",),
        "injected multipath, any of sigma_gm_m=M,tau_s=S,sigma_wn_m=M,mapping=A,B,C_DEG "
        "(zenith scale; sigmas <= 0.05 m, 0 < tau_s <= 86400 s; default: the preset's)",
        None,
        {"metavar": "SPEC"},
    ),
    _O(
        _S,
        "receiver_noise_m",
        ("--receiver-noise-m",),
        f"white receiver phase noise per signal, metres {_PRESETS}",
        None,
    ),
)


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``simulate`` subcommand."""
    p = sub.add_parser(
        "simulate",
        formatter_class=SchemaHelpFormatter,
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
    add_options(p, OPTIONS, SCHEMA.spec, groups=(None,), defaults=SCHEMA.default)
    add_config_option(p)
    p.set_defaults(func=run)


def _warn_beyond_limit(sc: Any, opts: SimulateOptions) -> None:
    """Warn when the multipath breaks the carrier-multipath limit at the elevation mask."""
    from psdbound.common.notices import warn
    from psdbound.simulate.simulator import multipath_limit_problem

    if opts.multipath is not None:
        label = "--multipath"
    elif opts.scenario:
        label = f"[multipath] of {opts.scenario}"
    else:
        label = f"the {opts.preset} preset's multipath"
    problem = multipath_limit_problem(sc, label)
    if problem:
        warn(problem)


def _scenario(opts: SimulateOptions, changes: dict[str, Any]) -> Any:
    """Return the preset, then the scenario file, then the flags' ``changes`` (errors name them)."""
    from psdbound.common.options import OptionError
    from psdbound.simulate import MultipathModel, Scenario, preset

    sc = preset(opts.preset)
    if opts.scenario:
        sc = Scenario.from_toml(opts.scenario, base=sc)
    if opts.multipath is not None:
        changes["multipath"] = MultipathModel.from_spec(
            opts.multipath, base=sc.multipath, label="--multipath"
        )
    try:
        return sc.replace(**changes)
    except OptionError as exc:  # a flag's value the scenario's schema refuses
        raise exc.relabel(flag_of(OPTIONS, _S, exc.name) or exc.label) from None


def _is_demo(opts: SimulateOptions, changes: dict[str, Any]) -> bool:
    """Tell whether the run regenerates the demo data set in its cache (no option changes it)."""
    plain = not changes and not opts.scenario and opts.multipath is None
    return opts.preset == "demo" and plain and not opts.out


def run(args: argparse.Namespace) -> int:
    """Simulate and print the written files; return the exit code.

    Every input (options, scenario file, navigation file, the ``--out``
    folder) is checked before anything is written; the files are built in a
    hidden folder and installed when all are complete
    (``psdbound.simulate.folder.simulate_folder``).
    """
    from psdbound.simulate import demo_data, simulate
    from psdbound.simulate.folder import check_simulate_folder, simulate_folder

    given = read_options(args, OPTIONS, SCHEMA.spec)
    opts = SCHEMA.build(_C, given.get(_C, {}))
    changes = dict(given.get(_S, {}))
    if opts.out:
        check_simulate_folder(opts.out, overwrite=opts.overwrite, option="--out")
    if _is_demo(opts, changes):
        if opts.overwrite:
            from psdbound.common.notices import warn

            warn("--overwrite is not used: without --out the demo is written to its cache")
        data = demo_data(regenerate=True)
        files = [*data.obs_paths, data.nav_path, data.truth_path, data.truth_json_path]
    else:
        sc = _scenario(opts, changes)
        _warn_beyond_limit(sc, opts)
        out = Path(opts.out) if opts.out else Path("simulated") / sc.name
        with simulate_folder(out, overwrite=opts.overwrite, option="--out") as tmp:
            res = simulate(sc, tmp)
        files = [out / p.name for p in (*res.obs_paths, res.nav_path, res.truth_path)]
        files.append(out / res.truth_json_path.name)
    for f in files:
        print(f)
    return 0
