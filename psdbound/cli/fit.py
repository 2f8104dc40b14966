"""``psdbound fit``: observations -> bound -> result.json, report.html, report.pdf."""

from __future__ import annotations

import argparse
import re
import sys
import time
from pathlib import Path

from psdbound.cli.exit_codes import EXIT_NOT_BOUNDED, EXIT_OK
from psdbound.errors import InputError

__all__ = ["add_parser", "run", "add_output_options"]


def add_output_options(p: argparse.ArgumentParser) -> None:
    """Options shared by the commands that write reports."""
    p.add_argument("--out", help="output folder (default reports/<run-name>)")
    p.add_argument("--name", help="run name (default from the first observation file)")
    p.add_argument("--no-pdf", action="store_true", help="skip the PDF report")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--quiet", action="store_true", help="print only errors and the result")
    g.add_argument("--verbose", action="store_true", help="print stage timings and tracebacks")


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register the ``fit`` subcommand."""
    p = sub.add_parser(
        "fit",
        help="fit a PSD bound to RINEX observations (no files: the demo data)",
        description="Read RINEX observations, isolate carrier-phase multipath (dual-frequency "
        "for one file, dual-antenna for two), window it into stationary pieces, estimate PSDs "
        "and fit the tightest Gauss-Markov + white-noise bound. Writes result.json, "
        "report.html and report.pdf. With no observation file, runs on the embedded demo.",
        epilog="Every option can also be set in --config FILE.toml (sections inputs, arcs, "
        "cutoff, filter, mapping, stationarity, spectra, bound, validation, output); "
        "command-line options win. Exit codes: 0 bounded; 3 ran but no trustworthy bound "
        "(verdict not-bounded: reasons printed, outputs written); 2 bad input (nothing "
        "written); 1 internal error.",
    )
    p.add_argument("obs", nargs="*", help="observation file(s): one (DF) or two (DA)")
    p.add_argument("--nav", help="navigation (RINEX 2/3) or SP3 file")
    p.add_argument("--config", help="TOML configuration file")
    p.add_argument("--method", choices=("auto", "df", "da"), help="isolation method (auto)")
    p.add_argument("--system", help="satellite system letter (G)")
    p.add_argument("--signals", help="DF phase pair, e.g. L1C,L2W or L1C,L5Q")
    p.add_argument("--da-signal", help="DA phase code (L1C)")
    p.add_argument("--cutoff-hz", type=float, help="high-pass cutoff frequency, Hz")
    p.add_argument(
        "--cutoff-source", choices=("auto", "given", "map", "computed"), help="cutoff source"
    )
    p.add_argument("--min-arc-min", type=float, help="minimum arc length, minutes (30)")
    p.add_argument("--elevation-mask-deg", type=float, help="elevation mask, degrees (10)")
    p.add_argument(
        "--roti-threshold",
        type=float,
        help="screening: ROTI above this is ionosphere, TECU/min (0.15)",
    )
    p.add_argument("--filter", choices=("butter", "cheby2", "fir"), help="high-pass design")
    p.add_argument("--filter-order", type=int, help="IIR filter order (4)")
    p.add_argument("--edge", choices=("trim", "pad"), help="filter edge handling (trim)")
    p.add_argument("--mapping", help="elevation mapping: thesis, fit, or a,b,c (c in degrees)")
    p.add_argument("--alpha", type=float, help="stationarity significance level (0.05)")
    p.add_argument("--p-slide", type=float, help="windowing slide coefficient (1.2)")
    p.add_argument("--p-trim", type=float, help="windowing trim coefficient (0.8)")
    p.add_argument("--min-window-s", type=float, help="minimum window length, s (600)")
    p.add_argument(
        "--estimator", choices=("multitaper", "welch", "blackman-tukey"), help="PSD estimator"
    )
    p.add_argument("--objective", choices=("variance", "area"), help="tightness objective")
    p.add_argument("--target", choices=("point", "upper"), help="bound estimates or CI tops")
    p.add_argument("--level", type=float, help="confidence level for --target upper (0.95)")
    p.add_argument(
        "--geometry",
        action="append",
        help="reflection geometry for the cutoff check, e.g. wall:d=25 (repeatable)",
    )
    p.add_argument("--validation-threshold", type=float, help="max fraction below f_c (0.10)")
    add_output_options(p)
    p.set_defaults(func=run)


def _config(args: argparse.Namespace):
    from psdbound.pipeline import FitConfig

    cfg = FitConfig.from_toml(args.config) if args.config else FitConfig()
    mapping: dict = {}
    if args.mapping:
        if args.mapping in ("thesis", "fit"):
            mapping = {"kind": args.mapping}
        else:
            try:
                a, b, c = (float(x) for x in args.mapping.split(","))
            except ValueError:
                raise InputError(
                    f"--mapping must be thesis, fit or a,b,c numbers; got {args.mapping!r}"
                ) from None
            mapping = {"kind": "fixed", "a": a, "b": b, "c_deg": c}
    cfg = cfg.updated(
        "inputs",
        obs=tuple(args.obs) or None,
        nav=args.nav,
        method=args.method,
        system=args.system,
        signals=tuple(args.signals.split(",")) if args.signals else None,
        da_signal=args.da_signal,
    )
    cfg = cfg.updated(
        "arcs",
        min_length_s=None if args.min_arc_min is None else 60.0 * args.min_arc_min,
        elevation_mask_deg=args.elevation_mask_deg,
    )
    cfg = cfg.updated("cutoff", f_c_hz=args.cutoff_hz, source=args.cutoff_source)
    cfg = cfg.updated("filter", kind=args.filter, order=args.filter_order, edge=args.edge)
    cfg = cfg.updated("screening", roti_threshold_tecu_min=args.roti_threshold)
    cfg = cfg.updated("mapping", **mapping)
    cfg = cfg.updated(
        "stationarity",
        alpha=args.alpha,
        p_slide=args.p_slide,
        p_trim=args.p_trim,
        min_window_s=args.min_window_s,
    )
    cfg = cfg.updated("spectra", estimator=args.estimator)
    cfg = cfg.updated("bound", objective=args.objective, target=args.target, level=args.level)
    cfg = cfg.updated(
        "validation",
        geometries=tuple(args.geometry) if args.geometry else None,
        threshold=args.validation_threshold,
    )
    cfg = cfg.updated("output", out=args.out, name=args.name, pdf=False if args.no_pdf else None)
    return cfg


def _run_name(cfg) -> str:
    if cfg.output.name:
        name = cfg.output.name
    elif cfg.inputs.obs:
        stem = Path(cfg.inputs.obs[0]).name.split(".")[0]
        name = f"{stem}-{cfg.inputs.method}" if cfg.inputs.method != "auto" else stem
    else:
        name = "demo"
    if not re.fullmatch(r"[A-Za-z0-9._+-]+", name):
        raise InputError(f"run name {name!r} may only use letters, digits and . _ + -")
    return name


def reporter(args: argparse.Namespace):
    """Return a progress callback honouring --quiet/--verbose."""
    t0 = time.perf_counter()

    def say(msg: str) -> None:
        if getattr(args, "quiet", False):
            return
        stamp = f"{time.perf_counter() - t0:6.1f} s  " if getattr(args, "verbose", False) else ""
        print(f"[psdbound] {stamp}{msg}", file=sys.stderr, flush=True)

    return say


def run(args: argparse.Namespace) -> int:
    """Run the fit and write the outputs; return the exit code."""
    import psdbound

    cfg = _config(args)
    name = _run_name(cfg)
    out = Path(cfg.output.out) if cfg.output.out else Path("reports") / name
    say = reporter(args)
    result = psdbound.fit(config=cfg, progress=say)
    say(f"writing {out}/ (result.json, report.html{', report.pdf' if cfg.output.pdf else ''})")
    paths = result.report(out, pdf=cfg.output.pdf)
    print(result.summary())
    for p in paths.values():
        print(p)
    return EXIT_OK if result.verdict == "bounded" else EXIT_NOT_BOUNDED
