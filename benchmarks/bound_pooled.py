"""Benchmark: the pooled bound on real station days (issue 15).

For each real day (ESBC 2020-177, NYA1 2024-124; shared data) the stages run
to the screened series once; then, with the whole day's fitted elevation
mapping held fixed:

* the pooled bound of the whole day and of its two 12-h halves (arcs cut at
  noon): more data must not give a larger bound than the larger half's;
* the three PSD estimators on the whole day's windows (variance spread);
* the thesis's envelope rule on the same (disjoint) windows.

Last line: ``RESULT esbc_whole_over_max_half=... esbc_estimator_spread=...
esbc_pooled_over_envelope=... nya1_whole_over_max_half=...
nya1_estimator_spread=... nya1_pooled_over_envelope=...`` (variance ratios).
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from psdbound.isolation import MultipathSeries
from psdbound.pipeline import stages
from psdbound.pipeline.config import FitConfig
from psdbound.pipeline.products import Screened
from psdbound.pipeline.runner import run_stages

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "rinex"
DAYS = {
    "esbc": ("ESBC00DNK_R_20201770000_01D_30S_MO.crx.gz", "ESBC00DNK_R_20201770000_01D_MN.rnx.gz"),
    "nya1": ("NYA100NOR_S_20241240000_01D_30S_MO.crx.gz", "NYA100NOR_S_20241240000_01D_GN.rnx.gz"),
}


def _half(series: MultipathSeries, first: bool) -> MultipathSeries:
    """The arcs (or parts of arcs) before (first) or after the series' mid time."""
    t_mid = 0.5 * (series.t_gps_s.min() + series.t_gps_s.max())
    arcs = []
    for k, (lo, hi) in enumerate(series.arc_bounds()):
        t = series.t_gps_s[lo:hi]
        keep = t < t_mid if first else t >= t_mid
        if keep.sum() >= 2:
            arcs.append(
                {
                    "sats": series.arc_sats[k],
                    "t_gps_s": t[keep],
                    "value_m": series.value_m[lo:hi][keep],
                    "elevation_deg": series.elevation_deg[lo:hi][keep],
                }
            )
    return MultipathSeries.from_arcs(
        series.method,
        arcs,
        signals=series.signals,
        scaling=series.scaling,
        interval_s=series.interval_s,
        cutoff_hz=series.cutoff_hz,
        meta=series.meta,
    )


def _bound(cfg: FitConfig, screened: Screened, cutoff, **changes):
    spectra = replace(cfg.spectra, **{k: v for k, v in changes.items() if k == "estimator"})
    bound_opt = replace(cfg.bound, **{k: v for k, v in changes.items() if k == "rule"})
    mapping = stages.map_elevation(screened.series, cfg.mapping)
    windowed = stages.window(screened, mapping=mapping, options=cfg.stationarity)
    return stages.bound(
        windowed, spectra=spectra, options=bound_opt, cutoff=cutoff, highpass=cfg.filter
    ).bound


def run_day(name: str) -> dict[str, float]:
    """Run the comparisons on one day; print a table; return the ratios."""
    obs, nav = DAYS[name]
    cfg = FitConfig().updated("inputs", obs=(str(DATA / obs),), nav=str(DATA / nav))
    run = run_stages(cfg, until="windowed")
    screened, cutoff, m = run.screened, run.cutoff, run.windowed.mapping
    cfg = cfg.updated("mapping", kind="fixed", a=m.a, b=m.b, c_deg=m.c_deg)
    rows = {}
    rows["whole"] = _bound(cfg, screened, cutoff)
    for label, first in (("first half", True), ("second half", False)):
        part = replace(
            screened, screening=replace(screened.screening, series=_half(screened.series, first))
        )
        rows[label] = _bound(cfg, part, cutoff)
    for est in ("welch", "blackman-tukey"):  # the default is multitaper
        rows[est] = _bound(cfg, screened, cutoff, estimator=est)
    rows["envelope (same windows)"] = _bound(cfg, screened, cutoff, rule="envelope")
    print(f"\n{name}: mapping a={m.a:.3g} b={m.b:.3g} c={m.c_deg:.3g} deg")
    print(f"{'case':<26}{'sigma_GM mm':>12}{'tau s':>8}{'sigma_WN mm':>12}{'variance m2':>13}")
    for label, b in rows.items():
        print(
            f"{label:<26}{1e3 * b.sigma_gm_m:>12.3f}{b.tau_s:>8.1f}{1e3 * b.sigma_wn_m:>12.3f}"
            f"{b.total_variance_m2:>13.4g}"
        )
    var = {k: b.total_variance_m2 for k, b in rows.items()}
    est_var = [var["whole"], var["welch"], var["blackman-tukey"]]
    return {
        "whole_over_max_half": var["whole"] / max(var["first half"], var["second half"]),
        "estimator_spread": max(est_var) / min(est_var),
        "pooled_over_envelope": var["whole"] / var["envelope (same windows)"],
    }


def main() -> int:
    """Run every day; print RESULT."""
    if not (DATA / DAYS["esbc"][0]).is_file():
        print(f"real data not found in {DATA}", file=sys.stderr)
        return 2
    out = {}
    for name in DAYS:
        for key, value in run_day(name).items():
            out[f"{name}_{key}"] = value
    print("RESULT " + " ".join(f"{k}={v:.3f}" for k, v in out.items()))
    return 0 if np.all(np.isfinite(list(out.values()))) else 1


if __name__ == "__main__":
    sys.exit(main())
