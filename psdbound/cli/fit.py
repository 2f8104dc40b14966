"""``psdbound fit``: observations -> bound -> result.json, report.html, report.pdf.

Every option is checked before anything is read (types, ranges, conflicts;
:class:`psdbound.pipeline.FitConfig`), and so is the output folder: an
existing file, a folder below a file or a folder that is not a psdbound
output (unless ``--overwrite``) is refused before the fit starts.
"""

from __future__ import annotations

import argparse
import re
import sys
import time
import tomllib
from pathlib import Path
from typing import Any

from psdbound.cli.exit_codes import EXIT_NOT_BOUNDED, EXIT_OK
from psdbound.cli.schema import (
    CliOption,
    SchemaHelpFormatter,
    add_options,
    flag_of,
    given_values,
    help_text,
)
from psdbound.errors import InputError, NoDataError

__all__ = [
    "DAY_GROUPS",
    "OPTIONS",
    "DefaultsFormatter",
    "add_day_options",
    "add_input_options",
    "add_output_options",
    "add_parser",
    "build_config",
    "help_text",
    "output_dir",
    "reporter",
    "run",
    "run_name",
    "with_files",
]

_G_IN = "configuration and signals"
_G_CUT = "cutoff, arcs and high-pass filter"
_G_SCR = "screening and elevation mapping"
_G_WIN = "stationary windows"
_G_BND = "spectra and bound"
_G_VER = "verdict and cutoff validation"
_G_DA = "isolation method and dual-antenna pairs"
_G_CODE = "code multipath (optional)"
_G_OUT = "outputs"
#: The groups of one station-day's options (``fit`` and ``campaign``), in help order.
DAY_GROUPS = (_G_IN, _G_CUT, _G_SCR, _G_WIN, _G_BND, _G_VER)


def _mapping(text: str) -> dict[str, Any]:
    """Return the mapping section's fields of ``--mapping thesis|fit|a,b,c``."""
    if text in ("thesis", "fit"):
        return {"kind": text}
    try:
        a, b, c = (float(x) for x in text.split(","))
    except ValueError:
        raise InputError(
            f"--mapping must be thesis, fit or three numbers a,b,c (c in degrees), got {text!r}"
        ) from None
    return {"kind": "fixed", "a": a, "b": b, "c_deg": c}


def _minutes(value: float) -> dict[str, Any]:
    """Return ``min_length_s`` of ``--min-arc-min`` (checked in minutes)."""
    from psdbound.common.options import Number

    Number(lo=0.0, hi=1440.0, lo_open=True, unit="min")("--min-arc-min", value)
    return {"min_length_s": 60.0 * value}


_O = CliOption
#: Every ``fit`` option on the command line: its configuration field, flag, help and group.
#: Types, choices, ranges, units and defaults come from the schema (psdbound.pipeline.FitConfig).
OPTIONS: tuple[CliOption, ...] = (
    _O(
        "inputs",
        "obs",
        ("obs",),
        "observation file(s) of one station (consecutive files are "
        "merged), or of the two antennas named by --pair (default: none, the embedded demo)",
        "inputs",
        {"nargs": "*"},
    ),
    _O(
        "inputs",
        "nav",
        ("--nav",),
        "navigation (RINEX 2/3/4) or SP3 file(s): several "
        "(e.g. of consecutive days or systems, or a zip of them) are joined (required with OBS, "
        "unless OBS is a zip archive that also holds the navigation file)",
        "inputs",
        {"action": "extend", "nargs": "+", "metavar": "NAV"},
    ),
    _O("inputs", "system", ("--system",), "satellite system letter", _G_IN),
    _O(
        "inputs",
        "signals",
        ("--signals",),
        "dual-frequency phase pair, e.g. L1C,L2W or "
        "L1C,L5Q (default: the system's usual pair, GPS L1C,L2W)",
        _G_IN,
    ),
    _O(
        "cutoff",
        "f_c_hz",
        ("--cutoff-hz",),
        "high-pass cutoff frequency, Hz (default: none; the cutoff comes from --cutoff-source)",
        _G_CUT,
        {"type": float},
    ),
    _O(
        "cutoff",
        "source",
        ("--cutoff-source",),
        "cutoff source (auto: --cutoff-hz if given, else the shipped world map)",
        _G_CUT,
        {"choices": ("auto", "given", "map", "computed", "thesis")},
    ),
    _O(
        "arcs",
        "min_length_s",
        ("--min-arc-min",),
        "minimum arc length, min",
        _G_CUT,
        {"type": float},
        convert=_minutes,
        scale=60.0,
        unit="min",
    ),
    _O("arcs", "elevation_mask_deg", ("--elevation-mask-deg",), "elevation mask, deg", _G_CUT),
    _O("filter", "kind", ("--filter",), "high-pass design", _G_CUT),
    _O(
        "filter",
        "order",
        ("--filter-order",),
        "IIR filter order, 1 to 20 (dimensionless)",
        _G_CUT,
        {"type": float},
    ),
    _O("filter", "edge", ("--edge",), "filter edge handling", _G_CUT),
    _O(
        "screening",
        "roti_threshold_tecu_min",
        ("--roti-threshold",),
        "screening: ROTI above this is ionosphere, TECU/min",
        _G_SCR,
    ),
    _O(
        "mapping",
        "kind",
        ("--mapping",),
        "elevation mapping: thesis, fit, or a,b,c (a, b "
        "dimensionless, c in deg) (default: fit, fitted to the data)",
        _G_SCR,
        {"choices": None},
        convert=_mapping,
        sets=("a", "b", "c_deg"),
    ),
    _O(
        "stationarity",
        "test",
        ("--stationarity",),
        "stationarity test: spectral homogeneity "
        "of the window halves, valid for correlated samples, or thesis (Levene then K-S)",
        _G_WIN,
    ),
    _O(
        "stationarity",
        "windows",
        ("--windows",),
        "windows: disjoint tiles (needed by --rule pooled) or the thesis's overlapping slide rule",
        _G_WIN,
    ),
    _O(
        "stationarity",
        "alpha",
        ("--alpha",),
        "stationarity significance level (probability)",
        _G_WIN,
    ),
    _O(
        "stationarity",
        "p_slide",
        ("--p-slide",),
        "windowing slide coefficient (dimensionless)",
        _G_WIN,
    ),
    _O(
        "stationarity",
        "p_trim",
        ("--p-trim",),
        "windowing trim coefficient (dimensionless)",
        _G_WIN,
    ),
    _O(
        "stationarity",
        "min_window_s",
        ("--min-window-s",),
        "minimum window length, s; the "
        "spectral test needs at least 68 samples (34 min at 30 s), a shorter value is an error",
        _G_WIN,
    ),
    _O("spectra", "estimator", ("--estimator",), "PSD estimator", _G_BND),
    _O(
        "bound",
        "rule",
        ("--rule",),
        "bound pooled confidence limits of the windows' spectra "
        "or the thesis's envelope of every window's PSD (use with --windows slide)",
        _G_BND,
    ),
    _O(
        "bound",
        "confidence_level",
        ("--confidence-level",),
        "family-wise confidence of the pooled bound (probability)",
        _G_BND,
    ),
    _O(
        "bound",
        "coverage",
        ("--coverage",),
        "pooled rule: fraction of differing windows covered (probability)",
        _G_BND,
    ),
    _O("bound", "objective", ("--objective",), "tightness objective", _G_BND),
    _O(
        "bound",
        "target",
        ("--target",),
        "envelope rule: bound the estimates or their confidence-interval tops",
        _G_BND,
    ),
    _O(
        "bound",
        "level",
        ("--level",),
        "envelope rule: confidence level for --target upper (probability)",
        _G_BND,
    ),
    _O(
        "bound",
        "tau_max_s",
        ("--tau-max-s",),
        "pooled rule: prior upper limit of the "
        "multipath time constant, s, used below the lowest band where the data do not bound it",
        _G_BND,
    ),
    _O(
        "verdict",
        "low_frequency",
        ("--low-frequency",),
        "when the data do not bound the time "
        "constant: state the bound on the prior --tau-max-s, or refuse (exit 3)",
        _G_VER,
    ),
    _O(
        "validation",
        "geometries",
        ("--geometry",),
        "reflection geometry for the cutoff check, e.g. wall:d=25 (d, h in m; repeatable)",
        _G_VER,
        {"action": "append"},
    ),
    _O(
        "validation",
        "threshold",
        ("--validation-threshold",),
        "largest fraction of reflector multipath power below f_c (fraction)",
        _G_VER,
    ),
    _O(
        "inputs",
        "method",
        ("--method",),
        "isolation method: df dual-frequency, da dual-antenna, auto by the inputs",
        _G_DA,
    ),
    _O("inputs", "da_signal", ("--da-signal",), "dual-antenna phase code", _G_DA),
    _O(
        "inputs",
        "pair",
        ("--pair",),
        "dual-antenna pair: antenna A and antenna B, each a "
        "station (marker) name among OBS or an observation file (default: none)",
        _G_DA,
        {"nargs": 2, "metavar": ("A", "B")},
    ),
    _O(
        "inputs",
        "position_a_m",
        ("--position-a",),
        "ECEF position of the (first) antenna, m (default: the header's)",
        _G_DA,
        {"nargs": 3, "type": float, "metavar": ("X", "Y", "Z")},
    ),
    _O(
        "inputs",
        "position_b_m",
        ("--position-b",),
        "ECEF position of antenna B of a pair, m (default: the header's)",
        _G_DA,
        {"nargs": 3, "type": float, "metavar": ("X", "Y", "Z")},
    ),
    _O(
        "inputs",
        "baseline",
        ("--baseline",),
        "dual-antenna baseline: auto uses the estimate "
        "from the double differences when it moves antenna B by more than "
        "--baseline-tolerance-m and 3 standard errors; estimate always; given keeps the "
        "positions",
        _G_DA,
    ),
    _O(
        "inputs",
        "baseline_tolerance_m",
        ("--baseline-tolerance-m",),
        "correction above which --baseline auto uses the estimate, m",
        _G_DA,
    ),
    _O(
        "code_multipath",
        "codes",
        ("--code-multipath",),
        "also estimate code multipath by "
        "carrier levelling and overbound it per elevation bin: one pseudorange code (C1C: MP "
        "combination) or two (C1C,C5Q: ionosphere-free); result.json code_multipath and a "
        "report section (default: off)",
        _G_CODE,
        {"metavar": "CODES"},
    ),
    _O(
        "code_multipath",
        "edges_deg",
        ("--code-edges-deg",),
        "elevation bin edges of the code-multipath overbound, deg",
        _G_CODE,
        {"metavar": "EDGES"},
    ),
    _O(
        "code_multipath",
        "method",
        ("--code-overbound",),
        "Gaussian overbound construction of the code multipath",
        _G_CODE,
    ),
    _O("output", "out", ("-o", "--out"), "output folder (default reports/<run-name>)", _G_OUT),
    _O("output", "name", ("--name",), "run name (default from the first observation file)", _G_OUT),
    _O(
        "output",
        "pdf",
        ("--no-pdf",),
        "skip the PDF report",
        _G_OUT,
        {"action": "store_true"},
        convert=lambda given: {"pdf": not given},
    ),
    _O(
        "output",
        "report",
        ("--no-report",),
        "write result.json only: no report.html or report.pdf, no figures drawn "
        "(render them later with 'psdbound report OUT/result.json')",
        _G_OUT,
        {"action": "store_true"},
        convert=lambda given: {"report": not given},
    ),
    _O(
        "output",
        "series",
        ("--series",),
        "also write series.csv.gz: every isolated sample "
        "with its time, satellite, azimuth, elevation, value, screening and window",
        _G_OUT,
        {"action": "store_true"},
    ),
    _O(
        "output",
        "overwrite",
        ("--overwrite",),
        "write into an existing folder that is not a "
        "psdbound output (psdbound's files are replaced, nothing else is touched); a previous "
        "psdbound output is always replaced",
        _G_OUT,
        {"action": "store_true"},
    ),
)


def _spec(section: str, name: str) -> Any:
    """Return the schema entry of a field (the configuration is imported with the parser)."""
    from psdbound.pipeline.config import section_spec

    return section_spec(section, name)


def _options(groups: tuple[str, ...]) -> tuple[CliOption, ...]:
    return tuple(o for o in OPTIONS if o.group in groups)


def add_output_options(p: argparse.ArgumentParser) -> None:
    """Options shared by the commands that write reports (outputs, ``-q``/``-v``)."""
    g = add_options(p, _options((_G_OUT,)), _spec, groups=(_G_OUT,), defaults=_default)[_G_OUT]
    talk = g.add_mutually_exclusive_group()
    talk.add_argument("-q", "--quiet", action="store_true", help="print only errors and the result")
    talk.add_argument(
        "-v", "--verbose", action="store_true", help="print stage timings and tracebacks"
    )


def _default(section: str, name: str) -> Any:
    """Return a field's default in :class:`~psdbound.pipeline.FitConfig` (imported for --help)."""
    from psdbound.pipeline import FitConfig

    return getattr(getattr(FitConfig(), section), name)


#: The help formatter of ``fit``, ``export`` and ``campaign``: every default from FitConfig.
DefaultsFormatter = SchemaHelpFormatter


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``fit`` subcommand."""
    p = sub.add_parser(
        "fit",
        formatter_class=DefaultsFormatter,
        usage="psdbound fit [OBS ...] [--nav NAV ...] [-o OUT] [-q | -v] [options]",
        help="fit a PSD bound to RINEX observations (no files: the demo data)",
        description="Read RINEX observations, isolate carrier-phase multipath (dual-frequency "
        "for one file, dual-antenna for two), window it into stationary pieces, estimate PSDs "
        "and fit the tightest Gauss-Markov + white-noise bound. Writes result.json, "
        "report.html and report.pdf. With no observation file, runs on the embedded demo.",
        epilog="Every option can also be set in --config FILE.toml (sections inputs, arcs, "
        "cutoff, filter, screening, mapping, stationarity, spectra, bound, validation, "
        "verdict, code_multipath, output); command-line options win, and options that "
        "conflict are an error. "
        "Exit codes: 0 bounded; 3 ran but no trustworthy bound (verdict not-bounded: reasons "
        "printed, outputs written); 2 bad input (nothing written); 1 internal error.",
    )
    add_input_options(p)
    add_options(p, _options((_G_CODE,)), _spec, groups=(_G_CODE,), defaults=_default)
    add_output_options(p)
    p.set_defaults(func=run)


def add_input_options(p: argparse.ArgumentParser) -> None:
    """Add ``fit``'s inputs: OBS, ``--nav``, the day options and the dual-antenna options.

    ``fit`` and ``export`` take the same inputs and method options (every
    ``fit`` option but code multipath and the outputs).
    """
    for opt in _options(("inputs",)):
        kw = {**opt.kwargs, **({"default": None} if opt.flags[0].startswith("-") else {})}
        p.add_argument(*opt.flags, help=opt.help, **kw)
    add_day_options(p)
    add_options(p, _options((_G_DA,)), _spec, groups=(_G_DA,), defaults=_default)


def add_day_options(p: argparse.ArgumentParser) -> None:
    """Add the options of one station-day's fit (``fit`` and ``campaign`` share them).

    These are every ``fit`` option except the input files, the
    dual-antenna pair, the isolation method, code multipath and the outputs:
    ``--config``, the system and signals, cutoff, arcs, screening, filter,
    mapping, stationarity, spectra, bound, verdict and validation options.
    """
    groups = add_options(p, _options(DAY_GROUPS), _spec, groups=DAY_GROUPS, defaults=_default)
    groups[_G_IN].add_argument("--config", help="TOML configuration file (default: none)")


def _toml_names(path: str | None) -> set[tuple[str, str]]:
    if not path:
        return set()
    try:
        data = tomllib.loads(Path(path).read_text())
    except (OSError, ValueError):
        return set()
    return {(s, k) for s, v in data.items() if isinstance(v, dict) for k in v}


def _updated(
    cfg: Any, section: str, given: list[tuple[CliOption, dict[str, Any]]], args: argparse.Namespace
) -> Any:
    """Return ``cfg`` with one section's command-line values; errors name the flag."""
    from psdbound.common.options import OptionError

    values = {k: v for _, fields_ in given for k, v in fields_.items()}
    try:
        return cfg.updated(section, **values)
    except OptionError as exc:
        opt = next((o for o, f in given if exc.name in f), None)
        if opt is None:
            raise
        flag = f"--mapping {exc.name}" if opt.convert is _mapping else opt.flag
        raw = getattr(args, opt.dest)
        raise exc.relabel(flag, value=exc.value if opt.convert is _mapping else raw) from None


def build_config(args: argparse.Namespace):
    """Return the checked :class:`~psdbound.pipeline.FitConfig` of the command line.

    TOML values come first, command-line values override them; every value
    is checked against its schema and the rules between options are
    checked on the result. Messages name options by their flag (or by
    ``[section] name`` and the file for values from ``--config``).

    Raises
    ------
    InputError
        A bad value or conflicting options.
    """
    from psdbound.pipeline import FitConfig
    from psdbound.pipeline.config import default_label

    cfg = FitConfig.from_toml(args.config) if args.config else FitConfig()
    given_by_section = given_values(args, OPTIONS)
    given: set[tuple[str, str]] = set()
    for section, given_opts in given_by_section.items():
        given |= {(section, k) for _, f in given_opts for k in f}
        cfg = _updated(cfg, section, given_opts, args)
    from_toml = _toml_names(args.config)

    def label(section: str, name: str) -> str:
        flag = flag_of(OPTIONS, section, name)
        if (section, name) in from_toml and (section, name) not in given:
            return f"{default_label(section, name)} (in {args.config})"
        if flag == "obs":
            return "the observation files"
        return flag or default_label(section, name)

    return cfg.check(label)


def run_name(cfg) -> str:
    """Return the run name: ``--name``, else from the first observation file (checked)."""
    if cfg.output.name:
        name = cfg.output.name
    elif cfg.inputs.pair:
        a, b = (Path(p).name.split(".")[0] for p in cfg.inputs.pair)
        name = f"{a}-{b}-da"
    elif cfg.inputs.obs:
        stem = Path(cfg.inputs.obs[0]).name.split(".")[0]
        name = f"{stem}-{cfg.inputs.method}" if cfg.inputs.method != "auto" else stem
    else:
        name = "demo"
    if not re.fullmatch(r"[A-Za-z0-9._+-]+", name) or name in (".", ".."):
        raise InputError(
            f"run name {name!r} (from the observation file name) may only use letters, digits "
            "and . _ + -; give --name"
        )
    return name


def output_dir(cfg) -> Path:
    """Return the output folder of a configuration, checked (refused before the fit).

    Raises
    ------
    InputError
        The folder would replace a file, lies below a file, is not writable,
        or is a folder that is not a psdbound output (without ``--overwrite``).
    """
    from psdbound.common.outputs import check_output_folder

    out = Path(cfg.output.out) if cfg.output.out else Path("reports") / run_name(cfg)
    check_output_folder(out, overwrite=cfg.output.overwrite, option="--out")
    return out


def reporter(args: argparse.Namespace):
    """Return a progress callback honouring --quiet/--verbose."""
    t0 = time.perf_counter()

    def say(msg: str) -> None:
        if getattr(args, "quiet", False):
            return
        stamp = f"{time.perf_counter() - t0:6.1f} s  " if getattr(args, "verbose", False) else ""
        print(f"[psdbound] {stamp}{msg}", file=sys.stderr, flush=True)

    return say


def with_files(exc: InputError, obs: tuple[str, ...]) -> InputError:
    """Return a data error that names no file with the observation file(s) named."""
    if exc.path is not None or not obs or type(exc) not in (InputError, NoDataError):
        return exc
    return type(exc)(exc.reason, path=" + ".join(obs))


def run(args: argparse.Namespace) -> int:
    """Run the fit and write the outputs; return the exit code."""
    import psdbound
    from psdbound.reports import write_report_folder

    cfg = build_config(args)
    out = output_dir(cfg)
    say = reporter(args)
    try:
        result = psdbound.fit(config=cfg, progress=say)
    except InputError as exc:
        raise with_files(exc, cfg.inputs.obs) from None
    extra = {"series.csv.gz": result.series_csv()} if cfg.output.series else None
    reports = ["report.html", *(["report.pdf"] if cfg.output.pdf else [])]
    names = ["result.json", *(reports if cfg.output.report else []), *(extra or {})]
    say(f"writing {out}/ ({', '.join(names)})")
    paths = write_report_folder(
        result.document,
        out,
        pdf=cfg.output.pdf,
        report=cfg.output.report,
        overwrite=cfg.output.overwrite,
        option="--out",
        extra=extra,
    )
    print(result.summary())
    for p in paths.values():
        print(p)
    return EXIT_OK if result.verdict == "bounded" else EXIT_NOT_BOUNDED
