"""Assemble the result document (``result.json``, schema 1) from the stage results."""

from __future__ import annotations

import datetime as _dt
import platform
from collections.abc import Sequence
from typing import Any

import numpy as np

from psdbound.common import package_versions
from psdbound.ionosphere.policy import CutoffChoice
from psdbound.kalman.error_model import Component, error_model_section
from psdbound.pipeline.config import FitConfig
from psdbound.pipeline.products import CodeOverbound
from psdbound.pipeline.stages import InputData, Isolated, Screened, Validated, Windowed
from psdbound.pipeline.verdict import (
    VerdictCheck,
    VerdictFacts,
    physical_note,
    verdict_checks,
    verdict_facts,
    verdict_of,
)
from psdbound.reports import figure_data
from psdbound.results import SCHEMA_VERSION, to_jsonable
from psdbound.results.headline import headline
from psdbound.spectra import BoundResults, GaussMarkovWhiteNoise

__all__ = ["build_document", "stage_warnings"]

_WHITE_CONVENTION = (
    "sigma_wn_m is the per-sample standard deviation at dt_s; the one-sided white PSD level "
    "is 2 sigma_wn^2 dt (m^2/Hz); the thesis's two-sided N_WN = sigma_wn^2 dt"
)


def stage_warnings(
    inputs: InputData,
    cutoff: CutoffChoice | None,
    isolated: Isolated,
    screened: Screened,
    windowed: Windowed,
    bounded: BoundResults,
    validated: Validated,
    interval_s: float,
    code: CodeOverbound | None = None,
    verdict_notes: Sequence[str] = (),
) -> list[dict[str, Any]]:
    """Return every stage's warnings, grouped by stage, in pipeline order.

    ``verdict_notes`` (what the verdict's facts say beside the rules, e.g.
    :func:`~psdbound.pipeline.verdict.physical_note`) are the bound's.

    Returns
    -------
    list of dict
        ``{"stage": name, "warnings": [...]}`` for every stage with warnings
        (``reading``, ``cutoff``, ``isolation``, ``screening``, ``windows``,
        ``bound``, ``validation``, ``code multipath``).
    """
    bound: list[str] = []
    if bounded.bound.sigma_wn_m == 0.0:
        bound.append(
            f"no white-noise floor resolved at {interval_s:g} s sampling (Nyquist "
            f"{0.5 / interval_s:.4g} Hz): sigma_WN = 0; the bound says nothing above Nyquist"
        )
    bound += _bound_notes(bounded) + list(verdict_notes)
    groups = [
        ("reading", inputs.warnings),
        ("cutoff", cutoff.warnings if cutoff is not None else ()),
        ("isolation", isolated.warnings),
        ("screening", screened.warnings),
        ("windows", windowed.warnings),
        ("bound", bound),
        ("validation", validated.warnings),
        ("code multipath", code.warnings if code is not None else ()),
    ]
    return [{"stage": name, "warnings": list(w)} for name, w in groups if w]


def _bound_notes(res: BoundResults) -> list[str]:
    """Warnings of the pooled rule: loose bands, and a time constant the data do not bound."""
    out = [] if res.pooled is None else [f"pooled limits: {n}" for n in res.pooled.notes]
    ms, low = res.model_set, res.low_frequency
    if low is not None and low.prior_binding:
        b = low.before or {}
        out.append(
            f"the data do not bound the time constant above (the models consistent with them "
            f"reach the search's end): the Gauss-Markov plateau lies below the lowest stated "
            f"frequency {res.bound.f_min_hz:.3g} Hz. Below it the bound covers the admitted "
            f"models with tau up to the prior {low.tau_max_s:g} s (bound.tau_max_s); it was "
            f"raised for that from {1000 * b.get('sigma_gm_m', np.nan):.2f} mm / "
            f"{b.get('tau_s', np.nan):.4g} s (the tightest bound over the bands alone)"
            if low.raised
            else "the data do not bound the time constant above: below the lowest stated "
            f"frequency {res.bound.f_min_hz:.3g} Hz the statement rests on the prior tau <= "
            f"{low.tau_max_s:g} s (bound.tau_max_s)"
        )
    if low is not None and low.status == "unchecked":
        out.append(
            f"below the lowest stated frequency {res.bound.f_min_hz:.3g} Hz the bound is "
            f"an extrapolation not checked against the data ({low.reason})"
        )
    if ms is not None and ms.widening > 1.0:
        out.append(
            f"no Gauss-Markov + white-noise model fits every band's "
            f"{100 * ms.confidence_level:g} % interval: the model set's intervals were widened "
            f"{ms.widening:.3g} times (bound.model_set.widening)"
        )
    return out


def _bound_section(res: BoundResults) -> dict[str, Any]:
    b = res.bound
    return {
        "sigma_gm_m": b.sigma_gm_m,
        "tau_s": b.tau_s,
        "sigma_wn_m": b.sigma_wn_m,
        "n_wn_two_sided_m2_hz": b.n_wn_two_sided_m2_hz,
        "white_noise_convention": _WHITE_CONVENTION,
        "psd_convention": "one-sided, per hertz, sampled (aliased) AR(1) + white noise",
        "dt_s": b.dt_s,
        "total_variance_m2": b.total_variance_m2,
        "applies_to": "elevation-mapped error: multiply sigma by m(el) for elevation el",
        "rule": res.rule,
        "confidence_level": b.level if res.rule == "pooled" else None,
        "covers": res.confidence_statement(),
        "objective": b.objective,
        "objective_value_m2": b.objective_value,
        "target": b.target,
        "level": b.level,
        "estimator": res.estimator,
        "estimator_options": res.estimator_options,
        "min_margin": float(b.margins.min()),
        "median_margin": float(np.median(b.margins)),
        "margin_note": (
            "per group of windows: bound / pooled upper limit (>= 1)"
            if res.rule == "pooled"
            else "per window: bound / bounded estimate (>= 1)"
        ),
        "pooled": _pooled_section(res),
        **_model_set_section(res),
        "low_frequency": None if res.low_frequency is None else res.low_frequency.to_dict(),
        "cells": None if res.cells is None else res.cells.to_dict(),
        "lowest_frequencies": (
            None if res.lowest_frequencies is None else res.lowest_frequencies.to_dict()
        ),
        "unresolved": None if res.unresolved is None else res.unresolved.to_dict(),
        "gap_db_median": b.gap_db_median,
        "gap_db_p05": b.gap_db_p05,
        "over_data_db": res.over_data_db(),
        "band_hz": [b.f_min_hz, b.f_max_hz],
        "tau_grid_s": b.tau_grid_s,
        "objective_grid_m2": b.objective_grid,
    }


def _demo_truth(scenario: dict[str, Any], res: BoundResults, interval_s: float) -> dict[str, Any]:
    """Return the injected truth as the pipeline sees it at zenith, and the bound against it."""
    mp = scenario["multipath"]
    wn = float(np.hypot(mp["sigma_wn_m"], scenario.get("receiver_noise_m", 0.0)))
    truth = GaussMarkovWhiteNoise(
        sigma_gm_m=mp["sigma_gm_m"], tau_s=mp["tau_s"], sigma_wn_m=wn, dt_s=interval_s
    )
    b = res.bound
    f = np.geomspace(b.f_min_hz, 0.5 / interval_s, 400)
    f_all = np.r_[0.0, np.geomspace(1e-4 * b.f_min_hz, 0.5 / interval_s, 800)]
    return {
        "truth_model": {
            **truth.params(),
            "note": "mapped DF error at zenith: GM + white "
            "noise (multipath white noise and receiver noise combined)",
        },
        "truth_curve": {"f_hz": f, "psd_m2_hz": truth.sampled_psd(f)},
        "variance_ratio": b.total_variance_m2 / truth.total_variance_m2,
        "min_psd_ratio": float(np.min(b.psd(f) / truth.sampled_psd(f))),
        "min_psd_ratio_all_f": float(np.min(b.psd(f_all) / truth.sampled_psd(f_all))),
        "psd_convention": "both sampled at the data interval (aliased), one-sided",
    }


def _mapping_section(
    windowed: Windowed, res: BoundResults, screened: Screened, facts: VerdictFacts
) -> dict[str, Any]:
    """Return the mapping, its uncertainty and the mapped RMS per elevation bin vs the bound."""
    mp = windowed.mapping
    el = screened.series.elevation_deg
    x = windowed.windows.mapped_m
    sigma = float(np.sqrt(res.bound.total_variance_m2))
    rows = []
    for lo in range(0, 90, 10):
        sel = (el >= lo) & (el < lo + 10) & np.isfinite(x)
        if sel.sum() < 30:
            continue
        rms = float(np.sqrt(np.mean(x[sel] ** 2)))
        mid = lo + 5.0
        rows.append(
            {
                "elevation_deg": [lo, lo + 10],
                "n": int(sel.sum()),
                "mapped_rms_m": rms,
                "rms_over_bound_sigma": rms / sigma if sigma > 0 else None,
                "factor": float(mp.factor(mid)),
                "factor_rel_sigma": float(mp.factor_sigma(mid) / mp.factor(mid)),
            }
        )
    out = mp.to_dict()
    if facts.lowest_elevation_deg is not None:
        out["lowest_elevation_deg"] = facts.lowest_elevation_deg
        out["factor_at_lowest"] = facts.mapping_factor_lowest
    ok = np.isfinite(el)
    rms_factor = float(np.sqrt(np.mean(mp.factor(el[ok]) ** 2))) if ok.any() else 1.0
    out["rms_factor_over_data"] = rms_factor
    out["check"] = {
        "note": "RMS of the mapped data per 10-deg elevation bin against the bound's total "
        "sigma (zenith scale); a ratio above 1 in a bin means the mapping under-scales "
        "that elevation. factor_rel_sigma: relative standard error of m(el) from the fit",
        "bins": rows,
        "max_rms_over_bound_sigma": max((r["rms_over_bound_sigma"] or 0.0) for r in rows)
        if rows
        else None,
    }
    if mp.covariance_bc is not None:
        out["uncertainty_note"] = (
            "the bound is fitted to data mapped with this m(el); a mapping error makes windows "
            "at different elevations differ, which the pooled rule covers as windows' own "
            "deviations from their group (bound.pooled.window_term_log)"
        )
    return out


def _model_set_section(res: BoundResults) -> dict[str, Any]:
    """Return the intervals of the models consistent with the data (pooled rule)."""
    ms = res.model_set
    if ms is None:
        why = res.model_set_note or "envelope rule: no pooled spectrum"
        return {
            "tau_interval_s": None,
            "sigma_gm_interval_m": None,
            "sigma_wn_interval_m": None,
            "model_set": {"reason": why},
        }
    return {
        "tau_interval_s": list(ms.tau_interval_s),
        "sigma_gm_interval_m": list(ms.sigma_gm_interval_m),
        "sigma_wn_interval_m": list(ms.sigma_wn_interval_m),
        "model_set": ms.to_dict(),
    }


def _pooled_section(res: BoundResults) -> dict[str, Any] | None:
    pl = res.pooled
    if pl is None or res.bands is None:
        return None
    return {
        "method": "band-averaged window PSDs; windows grouped by spectral shape (one-sided "
        "residual tests on bands at least the estimator's smoothing wide); per group and band "
        "the exact chi-square upper limit of the group level, raised by every covered window's "
        "own upper deviation (a level, and a tilt in log frequency where significant); "
        "Bonferroni over the parts",
        "coverage": pl.coverage,
        "shape_alpha": res.bound.meta.get("shape_alpha"),
        "band_edges_hz": res.bands.edges_hz,
        "band_centres_hz": pl.f_hz,
        "band_span_hz": pl.band_span_hz,
        "n_groups": pl.n_groups,
        "group_sizes": pl.sizes(),
        "upper_m2_hz": pl.upper_m2_hz,
        "mean_upper_m2_hz": pl.mean_upper_m2_hz,
        "effective_dof": pl.effective_dof,
        "between_window_log_sd": np.sqrt(pl.tau2),
        "spread_upper_log_sd": pl.spread_upper_log_sd,
        "tolerance_factor": pl.tolerance_factor,
        "window_term_log": pl.window_term_log,
        "p_homogeneous": pl.p_homogeneous,
        "heterogeneous_fraction": pl.heterogeneous_fraction(),
        "looseness_db": pl.looseness_db(),
        "looseness_notes": list(pl.notes),
        "dependence": {k: v for k, v in res.dependence.items() if k != "labels"},
    }


def _cutoff_section(cutoff: CutoffChoice | None) -> dict[str, Any]:
    if cutoff is None:
        return {"f_c_hz": None, "source": "not applicable (dual-antenna)", "tau_c_min": None}
    return {
        "f_c_hz": cutoff.f_c_hz,
        "source": cutoff.source,
        "tau_c_min": 1.0 / cutoff.f_c_hz / 60.0,
        **{k: v for k, v in cutoff.info.items() if k != "figure"},
    }


def _windows_section(windowed: Windowed, res: BoundResults, screened: Screened) -> dict[str, Any]:
    w = windowed.windows
    per_window = [
        {
            "arc": x.arc_id,
            "sats": x.sats,
            "t_start_gps_s": x.t_start_gps_s,
            "t_stop_gps_s": x.t_stop_gps_s,
            "n": x.n,
            "margin": float(mg),
            "levene_p": x.levene_p,
            "ks_p": x.ks_p,
        }
        for x, mg in zip(w.windows, res.margins, strict=True)
    ]
    data_s = screened.series.data_s
    return {
        "count": len(w),
        "total_duration_s": w.total_duration_s,
        "data_s": data_s,
        "covered_s": w.covered_s,
        "covered_fraction": min(w.covered_s / data_s, 1.0) if data_s > 0 else 0.0,
        "coverage_note": "data after screening that lie in a stationary window the bound is "
        "fitted to (each sample once); the rest never tested stationary (never_stationary), "
        "lay in arcs too short to test (too_short_s) or was trimmed from a window's ends",
        "never_stationary_s": w.uncovered_s,
        "rejected_s": w.rejected_s,
        "too_short_s": w.short_s,
        "too_short_note": "arcs shorter than the minimum window "
        f"({w.params.get('effective_min_length_s', 0) / 60:.0f} min) cannot be tested; they are "
        "outside the bound but not evidence of non-stationarity",
        "never_stationary": [list(u) for u in w.uncovered],
        "n_tests": w.n_tests,
        "params": w.params,
        "per_window": per_window,
    }


def _roti_rule(sc: Any) -> str:
    """Return how the ROTI threshold of a block was set, in words."""
    if sc.null is not None and sc.null.trusted:
        return (
            "max(threshold, the 1 - p quantile of the ROTI the series' own multipath produces "
            "at the block's elevation: a scaled chi-square fitted to the lower part of the "
            "blocks nearest in elevation) per 5-min block, p the block test's share of "
            "false_alarm_per_block (block_test.false_alarm); threshold is the ionospheric "
            "significance level, below which no block is called ionosphere"
        )
    if sc.null is not None:
        return (
            "min(max(threshold, the null's 1 - p quantile), max(threshold, threshold x m(el))) "
            "per 5-min block: the null is heavy-tailed (much of the day disturbed) and the "
            "elevation-scaled fixed threshold applies as well"
        )
    if sc.options.elevation_scaled:
        return "min(threshold x m(el), cap) per 5-min block, m the elevation mapping"
    return "flat threshold"


def _screening_section(screened: Screened) -> dict[str, Any]:
    sc = screened.screening
    return {
        "excluded": [e.to_dict() for e in sc.excluded],
        "excluded_s": sc.excluded_s,
        "input_s": sc.input_s,
        "excluded_fraction": sc.excluded_fraction,
        "counts": sc.counts(),
        "multipath_limit_m": sc.limit_m,
        "multipath_limit_note": "largest possible |carrier multipath| of the isolated series: "
        "scaling x sum of quarter wavelengths of its phase terms",
        "roti_threshold_tecu_min": sc.options.roti_threshold_tecu_min,
        "roti_cap_tecu_min": sc.options.roti_cap_tecu_min,
        "roti_threshold_rule": _roti_rule(sc),
        "multipath_null": None if sc.null is None else sc.null.to_dict(),
        "false_alarm_per_block": sc.options.false_alarm if sc.null is not None else None,
        "block_test": sc.block_test,
        "three_frequency": sc.three_frequency,
        "roti": "5-min blocks of ROT sampled at 30 s (Pi et al. 1997)",
        "options": {
            "guard_s": sc.guard_s,
            "ionosphere": sc.options.ionosphere,
            "plausibility": sc.options.plausibility,
            "elevation_scaled": sc.options.elevation_scaled,
            "multipath_null": sc.options.multipath_null,
            "three_frequency": sc.options.three_frequency,
        },
        "notes": list(sc.notes),
    }


def _error_model(doc: dict[str, Any]) -> dict[str, Any]:
    """Return the ``error_model`` section: the bound's parts and what the high-pass removed."""
    val = doc.get("validation") or {}
    slow, comps = val.get("slow"), []
    if slow and slow["sigma_m"] > 0:
        site = val.get("site_reflection") or {}
        how = "measured from the SNR" if site.get("measured") else "assumed (configuration)"
        comps.append(
            Component(
                "slow",
                "gauss-markov",
                float(slow["sigma_m"]),
                float(slow["tau_s"]),
                False,
                f"multipath the high-pass removes below f_c from {slow['geometry']} along the "
                f"data's arcs ({slow['n_arcs']} arcs, removed RMS "
                f"{1000 * slow['removed_rms_m']:.2f} mm; amplitude ratio {slow['alpha']:.3g}, "
                f"{how}): the least-variance Gauss-Markov process above its spectrum "
                f"(validation.slow)",
            )
        )
    return error_model_section(doc["bound"], mapping=doc.get("mapping"), slow=comps)


def _figures(
    inputs: InputData,
    cutoff: CutoffChoice | None,
    isolated: Isolated,
    screened: Screened,
    windowed: Windowed,
    bounded: BoundResults,
    validated: Validated,
) -> dict[str, Any]:
    """Return the data of the report's figures (section ``figures``)."""
    return figure_data(
        series=screened.series,
        arcs=isolated.arcs,
        windows=windowed.windows,
        bound_results=bounded,
        t_ref_gps_s=inputs.t_ref_gps_s,
        interval_s=inputs.interval_s,
        cutoff_info=None if cutoff is None else cutoff.info,
        validation_report=validated.report,
        screening=screened.screening,
    )


def _data_span_section(isolated: Isolated, screened: Screened) -> dict[str, Any]:
    """Return the span of the isolated series and the number of screened arcs."""
    t_all = isolated.series.t_gps_s
    return {
        "start_gps_s": float(t_all.min()),
        "stop_gps_s": float(t_all.max()),
        "n_samples": int(t_all.size),
        "n_arcs": screened.series.n_arcs,
    }


def _provenance_section(config: FitConfig, inputs: InputData, run_time_s: float) -> dict[str, Any]:
    """Return the inputs, package versions, configuration, time and platform of the run."""
    return {
        "inputs": list(inputs.files),
        "versions": package_versions(),
        "configuration": config.to_dict(),
        "created_utc": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "platform": platform.platform(),
        "run_time_s": run_time_s,
    }


def _demo_section(inputs: InputData, bounded: BoundResults) -> dict[str, Any]:
    """Return the demo's injected truth and how the bound compares with it (section ``demo``)."""
    meta = inputs.demo
    return {
        "note": "simulated demo data (antenna A, dual-frequency); the truth model is "
        "known: compare the bound with the injected multipath",
        "injected": meta["scenario"]["multipath"],
        "seed": meta["seed"],
        "digest": meta["digest"],
        **_demo_truth(meta["scenario"], bounded, inputs.interval_s),
    }


def _verdict_first(doc: dict[str, Any], checks: list[VerdictCheck]) -> dict[str, Any]:
    """Return the document with the verdict after the schema version and the headline last."""
    verdict, reasons = verdict_of(checks)
    out = {
        "schema_version": doc.pop("schema_version"),
        "verdict": verdict,
        "verdict_reasons": reasons,
        "verdict_checks": [c.to_dict() for c in checks],
        **doc,
    }
    out["headline"] = headline(out)
    return out


def build_document(
    *,
    config: FitConfig,
    inputs: InputData,
    cutoff: CutoffChoice | None,
    isolated: Isolated,
    screened: Screened,
    windowed: Windowed,
    bounded: BoundResults,
    validated: Validated,
    run_time_s: float,
    code: CodeOverbound | None = None,
) -> dict[str, Any]:
    """Return the result document of a fit (plain JSON data).

    Parameters
    ----------
    config : FitConfig
        The effective configuration (saved in the provenance).
    inputs, cutoff, isolated, screened, windowed, bounded, validated
        The stage results (see :mod:`psdbound.pipeline.stages`).
    run_time_s : float
        Wall-clock time of the run, s.
    code : CodeOverbound, optional
        The optional code-multipath stage (section ``code_multipath``).

    Returns
    -------
    dict
        The ``result.json`` content, schema :data:`psdbound.results.SCHEMA_VERSION`.
    """
    interval_s = inputs.interval_s
    figures = _figures(inputs, cutoff, isolated, screened, windowed, bounded, validated)
    facts = verdict_facts(
        bounded=bounded,
        windowed=windowed,
        screened=screened,
        isolated=isolated,
        cutoff=cutoff,
        interval_s=interval_s,
    )
    note = physical_note(facts)
    grouped = stage_warnings(
        inputs,
        cutoff,
        isolated,
        screened,
        windowed,
        bounded,
        validated,
        interval_s,
        code,
        verdict_notes=(note,) if note else (),
    )
    doc: dict[str, Any] = {
        "schema_version": SCHEMA_VERSION,
        "method": inputs.method.upper(),
        "bound": _bound_section(bounded),
        "cutoff": _cutoff_section(cutoff),
        "sampling": {"interval_s": interval_s, "nyquist_hz": 0.5 / interval_s},
        "mapping": _mapping_section(windowed, bounded, screened, facts),
        "isolation": isolated.details,
        "screening": _screening_section(screened),
        "data_span": _data_span_section(isolated, screened),
        "windows": _windows_section(windowed, bounded, screened),
        "validation": validated.summary,
        "warnings": [w for g in grouped for w in g["warnings"]],
        "warnings_by_stage": grouped,
        "provenance": _provenance_section(config, inputs, run_time_s),
        "figures": figures,
    }
    doc["error_model"] = _error_model(doc)
    if code is not None:
        doc["code_multipath"] = code.details
    if inputs.demo is not None:
        doc["demo"] = _demo_section(inputs, bounded)
    doc = to_jsonable(doc)
    return _verdict_first(doc, verdict_checks(facts, config.verdict))
