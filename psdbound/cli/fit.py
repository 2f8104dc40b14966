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
from psdbound.errors import InputError, NoDataError

__all__ = [
    "DefaultsFormatter",
    "add_day_options",
    "add_input_options",
    "add_output_options",
    "add_parser",
    "build_config",
    "output_dir",
    "reporter",
    "run",
    "run_name",
    "with_files",
]

#: (section, option) -> command-line flag
FLAGS: dict[tuple[str, str], str] = {
    ("inputs", "obs"): "OBS",
    ("inputs", "nav"): "--nav",
    ("inputs", "method"): "--method",
    ("inputs", "system"): "--system",
    ("inputs", "signals"): "--signals",
    ("inputs", "da_signal"): "--da-signal",
    ("inputs", "pair"): "--pair",
    ("inputs", "position_a_m"): "--position-a",
    ("inputs", "position_b_m"): "--position-b",
    ("inputs", "baseline"): "--baseline",
    ("inputs", "baseline_tolerance_m"): "--baseline-tolerance-m",
    ("arcs", "min_length_s"): "--min-arc-min",
    ("arcs", "elevation_mask_deg"): "--elevation-mask-deg",
    ("cutoff", "f_c_hz"): "--cutoff-hz",
    ("cutoff", "source"): "--cutoff-source",
    ("filter", "kind"): "--filter",
    ("filter", "order"): "--filter-order",
    ("filter", "edge"): "--edge",
    ("screening", "roti_threshold_tecu_min"): "--roti-threshold",
    ("mapping", "kind"): "--mapping",
    ("mapping", "a"): "--mapping",
    ("mapping", "b"): "--mapping",
    ("mapping", "c_deg"): "--mapping",
    ("stationarity", "test"): "--stationarity",
    ("stationarity", "windows"): "--windows",
    ("stationarity", "alpha"): "--alpha",
    ("stationarity", "p_slide"): "--p-slide",
    ("stationarity", "p_trim"): "--p-trim",
    ("stationarity", "min_window_s"): "--min-window-s",
    ("spectra", "estimator"): "--estimator",
    ("bound", "rule"): "--rule",
    ("bound", "confidence_level"): "--confidence-level",
    ("bound", "coverage"): "--coverage",
    ("bound", "objective"): "--objective",
    ("bound", "target"): "--target",
    ("bound", "level"): "--level",
    ("bound", "tau_max_s"): "--tau-max-s",
    ("verdict", "low_frequency"): "--low-frequency",
    ("validation", "geometries"): "--geometry",
    ("validation", "threshold"): "--validation-threshold",
    ("code_multipath", "codes"): "--code-multipath",
    ("code_multipath", "edges_deg"): "--code-edges-deg",
    ("code_multipath", "method"): "--code-overbound",
    ("output", "out"): "--out",
    ("output", "name"): "--name",
    ("output", "pdf"): "--no-pdf",
    ("output", "overwrite"): "--overwrite",
    ("output", "series"): "--series",
}


def add_output_options(p: argparse.ArgumentParser) -> None:
    """Options shared by the commands that write reports."""
    g = p.add_argument_group("outputs")
    g.add_argument("-o", "--out", help="output folder (default reports/<run-name>)")
    g.add_argument("--name", help="run name (default from the first observation file)")
    g.add_argument("--no-pdf", action="store_true", help="skip the PDF report")
    g.add_argument("--series", action="store_true",
                   help="also write series.csv.gz: every isolated sample with its time, "
                   "satellite, azimuth, elevation, value, screening and window")  # fmt: skip
    g.add_argument(
        "--overwrite",
        action="store_true",
        help="write into an existing folder that is not a psdbound output (psdbound's files "
        "are replaced, nothing else is touched); a previous psdbound output is always replaced",
    )
    talk = g.add_mutually_exclusive_group()
    talk.add_argument("-q", "--quiet", action="store_true",
                      help="print only errors and the result")  # fmt: skip
    talk.add_argument("-v", "--verbose", action="store_true",
                      help="print stage timings and tracebacks")  # fmt: skip


#: Command-line options in other units than their configuration field: (factor, unit).
_CLI_UNITS = {"--min-arc-min": (1 / 60.0, "min")}


def _default_text(flag: str) -> str | None:
    """Return the default of a ``fit`` option from :class:`FitConfig` (so they never differ)."""
    from psdbound.common.options import spec_of
    from psdbound.pipeline import FitConfig

    keys = [k for k, f in FLAGS.items() if f == flag]
    if len(keys) != 1:
        return None
    section, name = keys[0]
    obj = getattr(FitConfig(), section)
    value = getattr(obj, name)
    if value is None or value == () or isinstance(value, bool):
        return None
    unit = getattr(spec_of(obj, name), "unit", "") or ""
    if flag in _CLI_UNITS:
        factor, unit = _CLI_UNITS[flag]
        value = value * factor
    if isinstance(value, float):
        text = f"{value:g}"
    elif isinstance(value, tuple):
        text = ",".join(map(str, value))
    else:
        text = str(value)
    return f"{text} {unit}".strip()


def help_text(action: argparse.Action) -> str:
    """Return an option's help with its default appended (from :class:`FitConfig`) if unstated.

    Evaluated when the help is printed, so that commands other than ``fit``
    do not import the pipeline to build their parsers.
    """
    text = action.help or ""
    if action.option_strings and "default" not in text:
        default = _default_text(action.option_strings[0])
        if default is not None:
            text = f"{text} (default: {default})"
    return text


class DefaultsFormatter(argparse.HelpFormatter):
    """Help formatter that states every ``fit`` option's default (see :func:`help_text`)."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        return help_text(action)


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``fit`` subcommand."""
    p = sub.add_parser(
        "fit",
        formatter_class=DefaultsFormatter,
        usage="psdbound fit [OBS ...] [--nav NAV] [-o OUT] [-q | -v] [options]",
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
    g_code = p.add_argument_group("code multipath (optional)")
    # fmt: off
    g_code.add_argument("--code-multipath", metavar="CODES",
                   help="also estimate code multipath by carrier levelling and overbound it per "
                   "elevation bin: one pseudorange code (C1C: MP combination) or two (C1C,C5Q: "
                   "ionosphere-free); result.json code_multipath and a report section "
                   "(default: off)")
    g_code.add_argument("--code-edges-deg", metavar="EDGES",
                   help="elevation bin edges of the code-multipath overbound, deg")
    g_code.add_argument("--code-overbound", choices=("two_step", "cdf"),
                   help="Gaussian overbound construction of the code multipath")
    # fmt: on
    add_output_options(p)
    p.set_defaults(func=run)


def add_input_options(p: argparse.ArgumentParser) -> None:
    """Add ``fit``'s inputs: OBS, ``--nav``, the day options and the dual-antenna options.

    ``fit`` and ``export`` take the same inputs and method options (every
    ``fit`` option but code multipath and the outputs).
    """
    # fmt: off
    p.add_argument("obs", nargs="*",
                   help="observation file(s) of one station (consecutive files are merged), or "
                   "of the two antennas named by --pair (default: none, the embedded demo)")
    p.add_argument("--nav", action="append", metavar="NAV",
                   help="navigation (RINEX 2/3/4) or SP3 file, repeatable: several (e.g. of "
                   "consecutive days, or a zip of them) are joined (required with OBS, unless "
                   "OBS is a zip archive that also holds the navigation file)")
    # fmt: on
    add_day_options(p)
    g_da = p.add_argument_group("isolation method and dual-antenna pairs")
    # fmt: off
    g_da.add_argument("--method", choices=("auto", "df", "da"),
                   help="isolation method: df dual-frequency, da dual-antenna, auto by the inputs")
    g_da.add_argument("--da-signal", help="dual-antenna phase code")
    g_da.add_argument("--pair", nargs=2, metavar=("A", "B"),
                   help="dual-antenna pair: antenna A and antenna B, each a station (marker) "
                   "name among OBS or an observation file (default: none)")
    g_da.add_argument("--position-a", nargs=3, type=float, metavar=("X", "Y", "Z"),
                   help="ECEF position of the (first) antenna, m (default: the header's)")
    g_da.add_argument("--position-b", nargs=3, type=float, metavar=("X", "Y", "Z"),
                   help="ECEF position of antenna B of a pair, m (default: the header's)")
    g_da.add_argument("--baseline", choices=("auto", "estimate", "given"),
                   help="dual-antenna baseline: auto uses the estimate from the double "
                   "differences when it moves antenna B by more than --baseline-tolerance-m and "
                   "3 standard errors; estimate always; given keeps the positions")
    g_da.add_argument("--baseline-tolerance-m", type=float,
                   help="correction above which --baseline auto uses the estimate, m")
    # fmt: on


def add_day_options(p: argparse.ArgumentParser) -> None:
    """Add the options of one station-day's fit (``fit`` and ``campaign`` share them).

    These are every ``fit`` option except the input files, the
    dual-antenna pair, the isolation method, code multipath and the outputs:
    ``--config``, the system and signals, cutoff, arcs, screening, filter,
    mapping, stationarity, spectra, bound, verdict and validation options.
    """
    g_in = p.add_argument_group("configuration and signals")
    g_cut = p.add_argument_group("cutoff, arcs and high-pass filter")
    g_scr = p.add_argument_group("screening and elevation mapping")
    g_win = p.add_argument_group("stationary windows")
    g_bnd = p.add_argument_group("spectra and bound")
    g_ver = p.add_argument_group("verdict and cutoff validation")
    # fmt: off
    g_in.add_argument("--config", help="TOML configuration file (default: none)")
    g_in.add_argument("--system", help="satellite system letter")
    g_in.add_argument("--signals", help="dual-frequency phase pair, e.g. L1C,L2W or L1C,L5Q "
                   "(default: the system's usual pair, GPS L1C,L2W)")
    g_cut.add_argument("--cutoff-hz", type=float, help="high-pass cutoff frequency, Hz (default: "
                   "none; the cutoff comes from --cutoff-source)")
    g_cut.add_argument("--cutoff-source", choices=("auto", "given", "map", "computed", "thesis"),
                   help="cutoff source (auto: --cutoff-hz if given, else the shipped world map)")
    g_cut.add_argument("--min-arc-min", type=float, help="minimum arc length, min")
    g_cut.add_argument("--elevation-mask-deg", type=float, help="elevation mask, deg")
    g_scr.add_argument("--roti-threshold", type=float,
                   help="screening: ROTI above this is ionosphere, TECU/min")
    g_cut.add_argument("--filter", choices=("butter", "cheby2", "fir"), help="high-pass design")
    g_cut.add_argument("--filter-order", type=float,
                       help="IIR filter order, 1 to 20 (dimensionless)")
    g_cut.add_argument("--edge", choices=("trim", "pad"), help="filter edge handling")
    g_scr.add_argument("--mapping", help="elevation mapping: thesis, fit, or a,b,c (a, b "
                   "dimensionless, c in deg) (default: fit, fitted to the data)")
    g_win.add_argument("--stationarity", choices=("spectral", "thesis"),
                   help="stationarity test: spectral homogeneity of the window halves, valid "
                   "for correlated samples, or thesis (Levene then K-S)")
    g_win.add_argument("--windows", choices=("disjoint", "slide"),
                   help="windows: disjoint tiles (needed by --rule pooled) or the thesis's "
                   "overlapping slide rule")
    g_win.add_argument("--alpha", type=float, help="stationarity significance level (probability)")
    g_win.add_argument("--p-slide", type=float, help="windowing slide coefficient (dimensionless)")
    g_win.add_argument("--p-trim", type=float, help="windowing trim coefficient (dimensionless)")
    g_win.add_argument("--min-window-s", type=float,
                   help="minimum window length, s; the spectral test needs at least 68 samples "
                   "(34 min at 30 s), a shorter value is an error")
    g_bnd.add_argument("--estimator", choices=("multitaper", "welch", "blackman-tukey"),
                   help="PSD estimator")
    g_bnd.add_argument("--rule", choices=("pooled", "envelope"),
                   help="bound pooled confidence limits of the windows' spectra or the thesis's "
                   "envelope of every window's PSD (use with --windows slide)")
    g_bnd.add_argument("--confidence-level", type=float,
                   help="family-wise confidence of the pooled bound (probability)")
    g_bnd.add_argument("--coverage", type=float,
                   help="pooled rule: fraction of differing windows covered (probability)")
    g_bnd.add_argument("--objective", choices=("variance", "area"), help="tightness objective")
    g_bnd.add_argument("--target", choices=("point", "upper"),
                   help="envelope rule: bound the estimates or their confidence-interval tops")
    g_bnd.add_argument("--level", type=float,
                   help="envelope rule: confidence level for --target upper (probability)")
    g_bnd.add_argument("--tau-max-s", type=float,
                   help="pooled rule: prior upper limit of the multipath time constant, s, used "
                   "below the lowest band where the data do not bound it")
    g_ver.add_argument("--low-frequency", choices=("prior", "refuse"),
                   help="when the data do not bound the time constant: state the bound on the "
                   "prior --tau-max-s, or refuse (exit 3)")
    g_ver.add_argument("--geometry", action="append",
                   help="reflection geometry for the cutoff check, e.g. wall:d=25 (d, h in m; "
                   "repeatable)")
    g_ver.add_argument("--validation-threshold", type=float,
                   help="largest fraction of reflector multipath power below f_c (fraction)")
    # fmt: on


def _mapping(text: str | None) -> dict[str, Any]:
    if not text:
        return {}
    if text in ("thesis", "fit"):
        return {"kind": text}
    try:
        a, b, c = (float(x) for x in text.split(","))
    except ValueError:
        raise InputError(
            f"--mapping must be thesis, fit or three numbers a,b,c (c in degrees), got {text!r}"
        ) from None
    return {"kind": "fixed", "a": a, "b": b, "c_deg": c}


def _cli_values(args: argparse.Namespace) -> list[tuple[str, dict[str, Any], dict[str, Any]]]:
    """Per section: the options given on the command line, and their values as typed."""
    from psdbound.common.options import Number

    min_len = None
    if args.min_arc_min is not None:
        Number(lo=0.0, hi=1440.0, lo_open=True, unit="min")("--min-arc-min", args.min_arc_min)
        min_len = 60.0 * args.min_arc_min
    mapping = _mapping(args.mapping)
    return [
        ("inputs", dict(obs=tuple(args.obs) or None,
                        nav=tuple(args.nav) if args.nav else None, method=args.method,
                        system=args.system, signals=args.signals, da_signal=args.da_signal,
                        pair=tuple(args.pair) if args.pair else None,
                        position_a_m=tuple(args.position_a) if args.position_a else None,
                        position_b_m=tuple(args.position_b) if args.position_b else None,
                        baseline=args.baseline,
                        baseline_tolerance_m=args.baseline_tolerance_m),
         dict(signals=args.signals)),
        ("arcs", dict(min_length_s=min_len, elevation_mask_deg=args.elevation_mask_deg),
         dict(min_length_s=args.min_arc_min)),
        ("cutoff", dict(f_c_hz=args.cutoff_hz, source=args.cutoff_source), {}),
        ("filter", dict(kind=args.filter, order=args.filter_order, edge=args.edge), {}),
        ("screening", dict(roti_threshold_tecu_min=args.roti_threshold), {}),
        ("mapping", mapping, {}),
        ("stationarity", dict(test=args.stationarity, windows=args.windows, alpha=args.alpha,
                              p_slide=args.p_slide, p_trim=args.p_trim,
                              min_window_s=args.min_window_s), {}),
        ("spectra", dict(estimator=args.estimator), {}),
        ("bound", dict(rule=args.rule, confidence_level=args.confidence_level,
                       coverage=args.coverage, objective=args.objective, target=args.target,
                       level=args.level, tau_max_s=args.tau_max_s), {}),
        ("verdict", dict(low_frequency=args.low_frequency), {}),
        ("validation", dict(geometries=tuple(args.geometry) if args.geometry else None,
                            threshold=args.validation_threshold), {}),
        ("code_multipath", dict(codes=args.code_multipath, edges_deg=args.code_edges_deg,
                                method=args.code_overbound), {}),
        ("output", dict(out=args.out, name=args.name, pdf=False if args.no_pdf else None,
                        overwrite=True if getattr(args, "overwrite", False) else None,
                        series=True if getattr(args, "series", False) else None), {}),
    ]  # fmt: skip


def _toml_names(path: str | None) -> set[tuple[str, str]]:
    if not path:
        return set()
    try:
        data = tomllib.loads(Path(path).read_text())
    except (OSError, ValueError):
        return set()
    return {(s, k) for s, v in data.items() if isinstance(v, dict) for k in v}


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
    from psdbound.common.options import OptionError
    from psdbound.pipeline import FitConfig
    from psdbound.pipeline.config import default_label

    cfg = FitConfig.from_toml(args.config) if args.config else FitConfig()
    given: set[tuple[str, str]] = set()
    for section, values, typed in _cli_values(args):
        values = {k: v for k, v in values.items() if v is not None}
        given |= {(section, k) for k in values}
        try:
            cfg = cfg.updated(section, **values)
        except OptionError as exc:
            flag = FLAGS.get((section, exc.name))
            if flag is None:
                raise
            if flag == "--mapping":
                flag = f"--mapping {exc.name}"
            raise exc.relabel(flag, value=typed.get(exc.name, exc.value)) from None
    from_toml = _toml_names(args.config)

    def label(section: str, name: str) -> str:
        flag = FLAGS.get((section, name))
        if (section, name) in from_toml and (section, name) not in given:
            return f"{default_label(section, name)} (in {args.config})"
        if flag == "OBS":
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
    names = ["result.json", "report.html", *(["report.pdf"] if cfg.output.pdf else []),
             *(extra or {})]  # fmt: skip
    say(f"writing {out}/ ({', '.join(names)})")
    paths = write_report_folder(result.document, out, pdf=cfg.output.pdf,
                                overwrite=cfg.output.overwrite, option="--out",
                                extra=extra)  # fmt: skip
    print(result.summary())
    for p in paths.values():
        print(p)
    return EXIT_OK if result.verdict == "bounded" else EXIT_NOT_BOUNDED
