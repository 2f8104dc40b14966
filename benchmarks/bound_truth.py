"""Benchmark: the fitted bound against known truths, end to end through the public library.

Every run simulates RINEX files with ``psdbound.simulate`` (single antenna,
dual-frequency), fits them with ``psdbound.fit(obs, nav, mapping={"kind":
"fixed", ...})`` using the true elevation mapping, and compares the bound
with the truth model ``psdbound.simulate.truth_model`` (the mapped DF series
at zenith scale: GM(sigma_gm, tau) + white noise of per-sample std
sqrt(sigma_wn^2 + receiver_noise^2)).

Part A, "day": the demo preset, ``--hours`` (default 24) at 1 s, seed 5.
Reported: the bound, total-variance ratio bound/truth, the minimum over the
bound's band ``[f_min, Nyquist]`` of bound PSD / truth PSD (``f_min``: the
fit's ``bound.band_hz[0]``, else 2 f_c), the never-stationary fraction of the
screened data (``windows.uncovered_s`` / data duration) and the verdict.

Part B, "random": ``--n`` (default 100) seeded random truths: sigma_GM
log-uniform 1-10 mm, tau log-uniform 10-900 s, sigma_WN uniform 0.5-3 mm,
mapping a = 1, b uniform 5-20, c uniform 8-20 deg; even runs at 1 s for 6 h,
odd runs at 30 s for 6-24 h (receiver noise 0.5 mm, the preset's). Runs are
Dask tasks (``psdbound.compute.run_tasks``, a local cluster of ``--workers``
processes; ``--workers 1`` runs them one after the other here). Per run:
covered (bound PSD >= truth PSD at every frequency of the band, relative
tolerance 1e-9), variance and tau ratios, verdict, or the error raised. Runs
with verdict "not-bounded" are counted apart (an honest outcome); coverage
is the fraction of "bounded" runs whose bound covers the truth.

PSDs are compared as the bound is fitted: one-sided, sampled (aliases folded
in) at the data interval (``GaussMarkovWhiteNoise.sampled_psd``); the
comparison with the continuous-time PSDs (``.psd``) is printed too.

Outputs in ``--out`` (default ``benchmarks/out/``): ``bound_truth_runs.csv``
(one row per run) and ``bound_truth.png`` (variance ratio and minimum PSD
ratio against the true tau, coloured by sampling). Last line::

    RESULT day_var_ratio=... day_min_psd_ratio=... day_never_stationary_frac=...
    random_n=... random_coverage=... random_median_var_ratio=... random_failures=...

Smoke check: ``python benchmarks/bound_truth.py --n 4 --hours 2``.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one BLAS thread per Dask worker

import argparse  # noqa: E402
import csv  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

DEFAULT_OUT = Path(__file__).resolve().parent / "out"
RTOL = 1e-9
FIELDS = (
    "run",
    "dt_s",
    "hours",
    "seed",
    "true_sigma_gm_mm",
    "true_tau_s",
    "true_sigma_wn_mm",
    "b",
    "c_deg",
    "bound_sigma_gm_mm",
    "bound_tau_s",
    "bound_sigma_wn_mm",
    "var_ratio",
    "tau_ratio",
    "min_psd_ratio",
    "f_at_min_hz",
    "covered",
    "min_psd_ratio_cont",
    "f_min_hz",
    "verdict",
    "never_stationary_frac",
    "confidence_level",
    "run_s",
    "error",
)


# ----------------------------------------------------------------- one run (a Dask task)
def run_one(item: dict[str, Any]) -> dict[str, Any]:
    """Simulate, fit and compare one truth; never raises (errors are recorded).

    Parameters
    ----------
    item : dict
        ``run``, ``dt_s``, ``hours``, ``seed``, ``sigma_gm_m``, ``tau_s``,
        ``sigma_wn_m``, ``a``, ``b``, ``c_deg`` and ``preset``.

    Returns
    -------
    dict
        The item and the outcome (see :func:`evaluate`), or ``error``.
    """
    import psdbound
    from psdbound.simulate import MultipathModel, preset, simulate, truth_model

    t0 = time.perf_counter()
    rec: dict[str, Any] = dict(item)
    try:
        mp = MultipathModel(
            sigma_gm_m=item["sigma_gm_m"],
            tau_s=item["tau_s"],
            sigma_wn_m=item["sigma_wn_m"],
            a=item["a"],
            b=item["b"],
            c_deg=item["c_deg"],
        )
        sc = preset(item["preset"]).replace(
            name=f"bt{item['run']:03d}",
            duration_s=item["hours"] * 3600.0,
            interval_s=item["dt_s"],
            dual_antenna=False,
            seed=item["seed"],
            multipath=mp,
        )
        truth = truth_model(sc)
        rec["true_sigma_wn_total_m"] = truth.sigma_wn_m
        with tempfile.TemporaryDirectory(prefix="psdbound-bt-") as tmp, warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sim = simulate(sc, tmp)
            res = psdbound.fit(
                sim.obs_paths,
                sim.nav_path,
                mapping={"kind": "fixed", "a": mp.a, "b": mp.b, "c_deg": mp.c_deg},
                screening=(
                    {"ionosphere": False, "plausibility": False}
                    if item.get("screening") == "off"
                    else {}
                ),
            )
            rec.update(evaluate(res, truth))
    except Exception as exc:  # a failing run is a result, not a crash
        rec["error"] = f"{type(exc).__name__}: {' '.join(str(exc).split())}"[:300]
    rec["run_s"] = time.perf_counter() - t0
    return rec


def evaluate(res: Any, truth: Any) -> dict[str, Any]:
    """Compare a fit's bound with the truth over ``[f_min, Nyquist]``.

    Parameters
    ----------
    res : psdbound.FitResults
        The fit.
    truth : psdbound.spectra.GaussMarkovWhiteNoise
        The truth model.

    Returns
    -------
    dict
        Bound parameters, ratios, coverage, verdict, never-stationary
        fraction, the coverage keys of the result document when present.
    """
    from psdbound.simulate import compare_to_truth

    doc = res.document
    b_doc = doc.get("bound", {})
    bound = res.bound
    band = b_doc.get("band_hz")
    f_c = doc.get("cutoff", {}).get("f_c_hz")
    f_min = float(band[0]) if band else 2.0 * float(f_c)
    cmp = compare_to_truth(bound, truth, f_min, rtol=RTOL)
    w_doc = doc.get("windows", {})
    data_s = w_doc.get("data_s")
    if data_s is None and res.series is not None:
        s = res.series
        data_s = s.data_s
    uncovered = (
        res.windows.uncovered_s if res.windows is not None else w_doc.get("never_stationary_s")
    )
    return {
        "bound_sigma_gm_m": bound.sigma_gm_m,
        "bound_tau_s": bound.tau_s,
        "bound_sigma_wn_m": bound.sigma_wn_m,
        "var_ratio": cmp.variance_ratio,
        "tau_ratio": cmp.tau_ratio,
        "min_psd_ratio": cmp.min_psd_ratio,
        "f_at_min_hz": cmp.f_at_min_hz,
        "covered": cmp.covered,
        "min_psd_ratio_cont": cmp.min_psd_ratio_continuous,
        "covered_cont": cmp.covered_continuous,
        "f_min_hz": f_min,
        "f_c_hz": f_c,
        "band_hz": band,
        "verdict": res.verdict,
        "verdict_reasons": res.verdict_reasons,
        "never_stationary_s": uncovered,
        "data_s": data_s,
        "never_stationary_frac": (uncovered / data_s)
        if uncovered is not None and data_s
        else float("nan"),
        "confidence_level": b_doc.get("confidence_level"),
        "covers": b_doc.get("covers"),
        "rule": b_doc.get("rule"),
        "pooled_coverage": (b_doc.get("pooled") or {}).get("coverage"),
        "covered_fraction": w_doc.get("covered_fraction"),
    }


# ----------------------------------------------------------------- the two parts
def random_items(n: int, seed: int) -> list[dict[str, Any]]:
    """Draw ``n`` random truths (half at 1 s for 6 h, half at 30 s for 6-24 h)."""
    rng = np.random.default_rng(seed)
    items = []
    for i in range(n):
        one_hz = i % 2 == 0
        hours = 6.0 if one_hz else round(float(rng.uniform(6.0, 24.0)) * 60.0) / 60.0
        items.append(
            {
                "run": i,
                "preset": "demo",
                "dt_s": 1.0 if one_hz else 30.0,
                "hours": hours,
                "seed": 10_000 + i,
                "sigma_gm_m": float(np.exp(rng.uniform(np.log(1e-3), np.log(1e-2)))),
                "tau_s": float(np.exp(rng.uniform(np.log(10.0), np.log(900.0)))),
                "sigma_wn_m": float(rng.uniform(0.5e-3, 3e-3)),
                "a": 1.0,
                "b": float(rng.uniform(5.0, 20.0)),
                "c_deg": float(rng.uniform(8.0, 20.0)),
            }
        )
    return items


def day_item(hours: float) -> dict[str, Any]:
    """Return the demo day: the demo preset's multipath, 1 s, seed 5."""
    from psdbound.simulate import preset

    mp = preset("demo").multipath
    return {
        "run": -1,
        "preset": "demo",
        "dt_s": 1.0,
        "hours": hours,
        "seed": 5,
        "sigma_gm_m": mp.sigma_gm_m,
        "tau_s": mp.tau_s,
        "sigma_wn_m": mp.sigma_wn_m,
        "a": mp.a,
        "b": mp.b,
        "c_deg": mp.c_deg,
    }


def report_day(rec: dict[str, Any]) -> None:
    """Print part A."""
    print(
        f"== A. demo day: {rec['hours']:g} h at 1 s, single antenna, seed 5 ({rec['run_s']:.1f} s)"
    )
    if "error" in rec:
        print(f"  FAILED: {rec['error']}")
        return
    print(
        f"  truth: sigma_GM {1e3 * rec['sigma_gm_m']:.3f} mm, tau {rec['tau_s']:.1f} s, "
        f"sigma_WN {1e3 * rec['true_sigma_wn_total_m']:.3f} mm (with receiver noise)"
    )
    print(
        f"  bound: sigma_GM {1e3 * rec['bound_sigma_gm_m']:.3f} mm, tau "
        f"{rec['bound_tau_s']:.1f} s, sigma_WN {1e3 * rec['bound_sigma_wn_m']:.3f} mm"
    )
    print(f"  variance ratio bound/truth {rec['var_ratio']:.3f}; tau ratio {rec['tau_ratio']:.3f}")
    print(
        f"  min bound/truth PSD over [{rec['f_min_hz']:.4g} Hz, Nyquist]: "
        f"{rec['min_psd_ratio']:.3f} at {rec['f_at_min_hz']:.4g} Hz (sampled PSDs); "
        f"{rec['min_psd_ratio_cont']:.3f} (continuous)"
    )
    print(
        f"  never stationary: {rec['never_stationary_s']:.0f} s of {rec['data_s']:.0f} s "
        f"({100 * rec['never_stationary_frac']:.2f} %); verdict {rec['verdict']}"
        + "".join(f"\n    reason: {r}" for r in rec["verdict_reasons"])
    )
    for key in ("rule", "confidence_level", "pooled_coverage", "covered_fraction", "covers"):
        if rec.get(key) is not None:
            print(f"  {key}: {rec[key]}")


def _fmt(v: Any, scale: float = 1.0, spec: str = ".3f") -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    return format(v * scale, spec)


def table(recs: list[dict[str, Any]]) -> None:
    """Print one row per random run (mm, s; ratios are bound / truth)."""
    print(
        f"{'run':>3} {'dt':>3} {'h':>5} {'sGM':>6} {'tau':>6} {'sWN':>5} {'b':>5} {'c':>5} | "
        f"{'bGM':>6} {'btau':>6} {'bWN':>5} {'var':>6} {'tau':>6} {'minPSD':>7} "
        f"{'cov':>3} {'verdict':>11} {'nonst':>5} {'s':>5}"
    )
    for r in recs:
        truth = (
            f"{r['run']:>3} {r['dt_s']:>3g} {r['hours']:>5.1f} {1e3 * r['sigma_gm_m']:>6.2f} "
            f"{r['tau_s']:>6.1f} {_fmt(r.get('true_sigma_wn_total_m'), 1e3, '.2f'):>5} "
            f"{r['b']:>5.1f} {r['c_deg']:>5.1f}"
        )
        if "error" in r:
            print(f"{truth} | ERROR {r['error']}  ({r['run_s']:.0f} s)")
            continue
        print(
            f"{truth} | {1e3 * r['bound_sigma_gm_m']:>6.2f} {r['bound_tau_s']:>6.1f} "
            f"{1e3 * r['bound_sigma_wn_m']:>5.2f} {_fmt(r['var_ratio']):>6} "
            f"{_fmt(r['tau_ratio']):>6} {_fmt(r['min_psd_ratio']):>7} "
            f"{'yes' if r['covered'] else 'NO':>3} {r['verdict']:>11} "
            f"{_fmt(r['never_stationary_frac'], 1.0, '.2f'):>5} {r['run_s']:>5.0f}"
        )


def summarise(recs: list[dict[str, Any]]) -> dict[str, Any]:
    """Print and return the summary of the random runs (per sampling and all)."""
    out: dict[str, Any] = {}
    levels = {r.get("confidence_level") for r in recs if r.get("confidence_level") is not None}
    stated = ", ".join(f"{x:g}" for x in sorted(levels)) if levels else "not stated"
    print(f"stated confidence level of the bound: {stated}")
    for label, sel in (("1 s", 1.0), ("30 s", 30.0), ("all", None)):
        rs = [r for r in recs if sel is None or r["dt_s"] == sel]
        err = [r for r in rs if "error" in r]
        fitted = [r for r in rs if "error" not in r]
        nb = [r for r in fitted if r["verdict"] != "bounded"]
        bd = [r for r in fitted if r["verdict"] == "bounded"]
        cov = float(np.mean([r["covered"] for r in bd])) if bd else float("nan")
        cov_c = float(np.mean([r["covered_cont"] for r in bd])) if bd else float("nan")
        cov_any = float(np.mean([r["covered"] for r in fitted])) if fitted else float("nan")
        vr = np.array([r["var_ratio"] for r in fitted])
        tr = np.array([r["tau_ratio"] for r in fitted])
        q = lambda a, p: float(np.percentile(a, p)) if a.size else float("nan")  # noqa: E731
        print(
            f"{label:>4}: {len(rs)} runs, {len(err)} errors, {len(nb)} not-bounded, "
            f"{len(bd)} bounded; coverage of bounded runs {_fmt(cov)} (sampled PSD), "
            f"{_fmt(cov_c)} (continuous); of every fitted run {_fmt(cov_any)}; "
            f"variance ratio median {_fmt(q(vr, 50))}, 90th pct {_fmt(q(vr, 90))}; "
            f"tau ratio median {_fmt(q(tr, 50))}"
        )
        out[label] = {
            "n": len(rs),
            "errors": len(err),
            "not_bounded": len(nb),
            "coverage": cov,
            "coverage_all": cov_any,
            "median_var_ratio": q(vr, 50),
        }
    errors: dict[str, int] = {}
    for r in recs:
        if "error" in r:
            errors[r["error"].split(":")[0]] = errors.get(r["error"].split(":")[0], 0) + 1
    if errors:
        print("errors by class: " + ", ".join(f"{k} x{v}" for k, v in errors.items()))
    reasons: dict[str, int] = {}
    for r in recs:
        for x in r.get("verdict_reasons") or ():
            reasons[x[:90]] = reasons.get(x[:90], 0) + 1
    for x, k in sorted(reasons.items(), key=lambda kv: -kv[1]):
        print(f"  not-bounded reason x{k}: {x}")
    return out


def write_outputs(recs: list[dict[str, Any]], out: Path) -> list[Path]:
    """Write the per-run CSV and the PNG figure; return their paths."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.ticker import FormatStrFormatter, NullFormatter

    out.mkdir(parents=True, exist_ok=True)
    csv_path = out / "bound_truth_runs.csv"
    with csv_path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(FIELDS)
        for r in recs:
            row = dict(
                r,
                true_sigma_gm_mm=1e3 * r["sigma_gm_m"],
                true_tau_s=r["tau_s"],
                true_sigma_wn_mm=1e3 * r.get("true_sigma_wn_total_m", float("nan")),
                bound_sigma_gm_mm=1e3 * r.get("bound_sigma_gm_m", float("nan")),
                bound_sigma_wn_mm=1e3 * r.get("bound_sigma_wn_m", float("nan")),
            )
            w.writerow([row.get(k, "") for k in FIELDS])
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), constrained_layout=True)
    for dt, colour in ((1.0, "tab:blue"), (30.0, "tab:orange")):
        for r in (r for r in recs if r["dt_s"] == dt and "error" not in r):
            covered, bounded = r["covered"], r["verdict"] == "bounded"
            kw = dict(
                color=colour,
                marker="o" if bounded else "s",
                ms=6,
                mfc=colour if covered else "none",
                ls="none",
            )
            axes[0].plot(r["tau_s"], r["var_ratio"], **kw)
            axes[1].plot(r["tau_s"], r["min_psd_ratio"], **kw)
        for r in (r for r in recs if r["dt_s"] == dt and "error" in r):
            axes[1].plot(r["tau_s"], 1.0, color=colour, marker="x", ls="none", ms=8)
    for ax, ylabel in zip(
        axes,
        ("bound / truth total variance", "min over band of bound PSD / truth PSD"),
        strict=True,
    ):
        ax.axhline(1.0, color="k", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_formatter(FormatStrFormatter("%g"))
            axis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("true tau, s")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
    handles = [
        Line2D([], [], color="tab:blue", marker="o", ls="none", label="1 s sampling"),
        Line2D([], [], color="tab:orange", marker="o", ls="none", label="30 s sampling"),
        Line2D(
            [],
            [],
            color="grey",
            marker="o",
            mfc="none",
            ls="none",
            label="hollow: truth not covered",
        ),
        Line2D([], [], color="grey", marker="s", ls="none", label="square: not-bounded"),
        Line2D([], [], color="grey", marker="x", ls="none", label="x: run failed"),
    ]
    axes[1].legend(handles=handles, fontsize=8, loc="best")
    n_cov = sum(1 for r in recs if r.get("covered") and r.get("verdict") == "bounded")
    n_bd = sum(1 for r in recs if r.get("verdict") == "bounded")
    axes[0].set_title(f"{len(recs)} random truths: variance ratio")
    axes[1].set_title(f"coverage: {n_cov} of {n_bd} bounded runs cover the truth")
    png = out / "bound_truth.png"
    fig.savefig(png, dpi=120)
    plt.close(fig)
    return [csv_path, png]


def main(argv: list[str] | None = None) -> int:
    """Run part A and part B; print the tables, summaries and the RESULT line."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--hours", type=float, default=24.0, help="part A duration, h (0 skips A)")
    ap.add_argument("--n", type=int, default=100, help="random truths in part B (0 skips B)")
    ap.add_argument("--workers", type=int, default=2, help="Dask workers (1: in this process)")
    ap.add_argument("--seed", type=int, default=2024, help="seed of the random truths")
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT, help="folder for the CSV and PNG")
    ap.add_argument(
        "--screening",
        choices=("off", "on"),
        default="off",
        help="part B: ionosphere and plausibility screening (default off: the random "
        "truths' multipath reaches the ROTI threshold and the quarter-wave limit, "
        "which is the screening's problem, not the bound's)",
    )
    args = ap.parse_args(argv)
    if args.hours < 0 or args.n < 0 or args.workers < 1:
        ap.error("--hours and --n must be >= 0 and --workers >= 1")
    from psdbound.compute import run_tasks

    t0 = time.perf_counter()
    day: dict[str, Any] = {}
    if args.hours > 0:
        day = run_one(day_item(args.hours))
        report_day(day)
    recs: list[dict[str, Any]] = []
    summary: dict[str, Any] = {}
    if args.n > 0:
        items = [dict(it, screening=args.screening) for it in random_items(args.n, args.seed)]
        print(
            f"== B. {args.n} random truths (seed {args.seed}), "
            f"{'sequential' if args.workers == 1 else f'{args.workers} Dask workers'}"
        )
        done = [0]

        def progress(k: int, total: int) -> None:
            done[0] = k
            print(f"  {k}/{total} runs done ({time.perf_counter() - t0:.0f} s)", file=sys.stderr)

        run = run_tasks(
            run_one, items, workers=0 if args.workers == 1 else args.workers, progress=progress
        )
        recs = run.results
        table(recs)
        summary = summarise(recs)
        times = {dt: [r["run_s"] for r in recs if r["dt_s"] == dt] for dt in (1.0, 30.0)}
        print(
            "run time per task: "
            + "; ".join(
                f"{dt:g} s sampling median {np.median(v):.1f} s, max {np.max(v):.1f} s"
                for dt, v in times.items()
                if v
            )
        )
        for p in write_outputs(recs, args.out):
            print(f"wrote {p}")
    print(f"total wall time {time.perf_counter() - t0:.0f} s")
    a = summary.get("all", {})
    nan = float("nan")
    print(
        f"RESULT day_var_ratio={day.get('var_ratio', nan):.4f} "
        f"day_min_psd_ratio={day.get('min_psd_ratio', nan):.4f} "
        f"day_never_stationary_frac={day.get('never_stationary_frac', nan):.4f} "
        f"random_n={len(recs)} random_coverage={a.get('coverage', nan):.4f} "
        f"random_coverage_all_fitted={a.get('coverage_all', nan):.4f} "
        f"random_median_var_ratio={a.get('median_var_ratio', nan):.4f} "
        f"random_failures={a.get('errors', 0)}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
