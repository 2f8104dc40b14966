"""The fit pipeline as a chain of typed stages.

Each stage takes the previous stage's product and its own options object and
returns a small frozen dataclass that pickles (so a campaign can run the
per-day stages as Dask tasks) and carries its warnings::

    read_inputs -> InputData
    choose_cutoff(InputData) -> CutoffChoice | None        (None: dual-antenna)
    isolate(InputData, CutoffChoice) -> Isolated           (DF and DA differ only here)
    map_elevation(series) -> ElevationMapping              (provisional: before screening)
    screen(Isolated, ElevationMapping) -> Screened         (residual ionosphere, plausibility)
    map_elevation(series) -> ElevationMapping              (the bound's: on the kept data)
    window(Screened, ElevationMapping) -> Windowed
    bound(Windowed) -> BoundResults
    validate(CutoffChoice) -> Validated
    code_overbound(InputData) -> CodeOverbound | None     (optional: psdbound.pipeline.code_stage)

:func:`psdbound.pipeline.runner.run_stages` composes them, for
:func:`psdbound.fit`, the campaign's tasks and the tests alike. The
elevation mapping is estimated twice on purpose: the screening needs one
before it can run, and residual ionosphere in the unscreened series biases it
(NYA1, 2024: c = 40 deg unscreened, 31 deg screened), so the bound's mapping
is fitted again on what the screening kept. Every stage calls only the
public surface of its stage package.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from psdbound.arcs import DEFAULT_SIGNALS, ArcSet, add_third_carrier, default_pair, find_arcs
from psdbound.arcs.options import ArcOptions
from psdbound.errors import InputError, NoDataError
from psdbound.io import Observations
from psdbound.io.signals import carrier_frequency_hz, wavelength_m
from psdbound.ionosphere.policy import CutoffChoice, CutoffOptions
from psdbound.ionosphere.policy import choose_cutoff as _choose_cutoff
from psdbound.isolation import (
    HighPass,
    baseline_note,
    filter_safety_check,
    isolate_dual_antenna,
    isolate_dual_frequency,
    long_baseline_note,
)
from psdbound.pipeline.config import InputsConfig
from psdbound.pipeline.inputs import Progress, quiet, read_inputs
from psdbound.pipeline.products import InputData, Isolated, Screened, Validated, Windowed
from psdbound.screening import ScreeningOptions, screen_series
from psdbound.spectra import BoundModel, BoundResults
from psdbound.spectra.options import BoundOptions, SpectraOptions
from psdbound.stationarity import find_stationary_windows, min_samples
from psdbound.stationarity.mapping import ElevationMapping
from psdbound.stationarity.options import MappingOptions, StationarityOptions, choose_mapping
from psdbound.validation.options import ValidationOptions

__all__ = [
    "InputData",
    "Isolated",
    "Screened",
    "Validated",
    "Windowed",
    "bound",
    "choose_cutoff",
    "isolate",
    "map_elevation",
    "read_inputs",
    "screen",
    "validate",
    "window",
]


def choose_cutoff(
    inputs: InputData,
    options: CutoffOptions,
    *,
    system: str = "G",
    signals: Sequence[str] = (),
) -> CutoffChoice | None:
    """Choose the high-pass cutoff (dual-frequency only; None for dual-antenna).

    Parameters
    ----------
    inputs : InputData
        Receiver position and year.
    options : CutoffOptions
        Given cutoff and source.
    system : str, default "G"
        The satellite system analysed.
    signals : sequence of str, optional
        The phase pair given (default: the pair the isolation will use):
        its carriers set the ionosphere a computed cutoff is for.

    Returns
    -------
    CutoffChoice or None
    """
    if inputs.method == "da":
        return None
    date = str(inputs.observations[0].times[0])[:10]
    return _choose_cutoff(
        options,
        lat_deg=inputs.lat_deg,
        lon_deg=inputs.lon_deg,
        year=inputs.year,
        date=date,
        interval_s=inputs.interval_s,
        carriers_hz=_carriers_hz(inputs, system, signals),
        system=system,
    )


def _carriers_hz(
    inputs: InputData, system: str, signals: Sequence[str]
) -> tuple[float, float] | None:
    """Return the carrier frequencies of the pair the isolation uses, Hz (GLONASS: channel 0)."""
    try:
        pair = tuple(signals[:2]) if signals else default_pair(inputs.observations[0], system)
        sat = f"{system}01"
        channels = {sat: 0} if system == "R" else None
        fa, fb = (carrier_frequency_hz(sat, code, channels) for code in pair)
    except (InputError, KeyError, ValueError):  # the isolation says what is wrong
        return None
    return float(fa), float(fb)


def _xyz(rx: tuple[float, float, float] | None) -> np.ndarray | None:
    return None if rx is None else np.asarray(rx, dtype=float)


def _offered(arcs: ArcSet, interval_s: float) -> dict[str, float] | None:
    """Return what the data offered before arcs were formed (both phases, above the mask).

    Samples without an orbit position count as offered (and lost): a navigation
    file that covers part of the day loses the rest.
    """
    n = arcs.samples
    if not n:
        return None
    offered = n["both_signals"] - n["below_mask"]
    return {
        "samples_both_signals": n["both_signals"],
        "samples_without_orbit": n["without_orbit"],
        "samples_below_mask": n["below_mask"],
        "offered_s": offered * interval_s,
    }


def _isolate_df(
    inputs: InputData,
    cutoff: CutoffChoice,
    arcs_opt: ArcOptions,
    highpass: HighPass,
    signals: tuple[str, ...],
    system: str,
    progress: Progress,
) -> Isolated:
    progress("arcs (gaps, loss of lock, cycle slips, elevations)")
    arcs = find_arcs(
        inputs.observations[0],
        signals or None,
        system=system,
        orbit=inputs.orbit,
        receiver_xyz_m=_xyz(inputs.receiver_xyz_m[0]),
        min_length_s=arcs_opt.min_length_s,
        slip_threshold_m=arcs_opt.slip_threshold_m,
        elevation_mask_deg=arcs_opt.elevation_mask_deg,
    )
    arcs = add_third_carrier(
        arcs, inputs.observations[0], slip_threshold_m=arcs_opt.slip_threshold_m
    )
    progress(f"dual-frequency isolation (high-pass {cutoff.f_c_hz:.4g} Hz)")
    series = isolate_dual_frequency(arcs, cutoff.f_c_hz, highpass=highpass)
    safety = filter_safety_check(series)
    n_dropped = int(sum(arcs.dropped.values()))
    details = {
        "signals": list(series.signals),
        "scaling": series.scaling,
        "scaling_note": "DF difference / sqrt(2): two independent per-carrier terms",
        "filter": series.meta["filter"],
        "n_arcs": series.n_arcs,
        "arc_breaks": dict(arcs.breaks),
        "short_stretches_dropped": n_dropped,
        "short_stretches_dropped_s": arcs.dropped_s,
        "arcs_dropped_after_trim": series.meta["arcs_dropped_after_trim"],
        "offered": _offered(arcs, inputs.interval_s),
        "third_signal": arcs.third_signal,
        "arcs_with_third": series.meta.get("arcs_with_third", 0),
        "safety": {
            "removed_below_fc_median": float(np.nanmedian(safety.removed_below)),
            "removed_below_fc_min": float(np.nanmin(safety.removed_below)),
            "removed_above_fc_median": float(np.nanmedian(safety.removed_above)),
            "removed_above_fc_max": float(np.nanmax(safety.removed_above)),
        },
    }
    warnings: tuple[str, ...] = ()
    if not signals:
        warnings += _pair_note(inputs.observations[0], system)
    if n_dropped:
        warnings += (
            f"{n_dropped} tracking stretches shorter than {arcs_opt.min_length_s / 60:g} min "
            f"dropped ({arcs.dropped_s / 3600:.2f} h)",
        )
    return Isolated(series, arcs, details, warnings)


def _pair_note(obs: Observations, system: str) -> tuple[str, ...]:
    """Say which pair was used when the file does not hold the system's default pair."""
    chosen, default = default_pair(obs, system), DEFAULT_SIGNALS[system]
    if chosen == default:
        return ()
    return (
        f"signals {','.join(chosen)}: the file has no phases of the default pair "
        f"{','.join(default)}; per carrier the first signal it holds is used "
        "(psdbound.arcs.SIGNAL_CANDIDATES; choose with --signals)",
    )


def _isolate_da(
    inputs: InputData, arcs_opt: ArcOptions, options: InputsConfig, progress: Progress
) -> Isolated:
    progress(
        "dual-antenna double differences (receiver clocks, geometry, re-referencing, baseline)"
    )
    rx = inputs.receiver_xyz_m
    series = isolate_dual_antenna(
        inputs.observations[0],
        inputs.observations[1],
        inputs.orbit,
        signal=options.da_signal,
        system=options.system,
        receiver1_xyz_m=_xyz(rx[0]),
        receiver2_xyz_m=_xyz(rx[1]) if len(rx) > 1 else None,
        min_length_s=min(arcs_opt.min_length_s, 600.0),
        elevation_mask_deg=arcs_opt.elevation_mask_deg,
        baseline=options.baseline,
        baseline_tolerance_m=options.baseline_tolerance_m,
    )
    m = series.meta
    details = {
        "signals": list(series.signals),
        "scaling": series.scaling,
        "scaling_note": "double difference / 2: four independent per-signal terms",
        "n_arcs": series.n_arcs,
        "baseline_m": m.get("baseline_m"),
        "positions_m": m.get("positions_m"),
        "position_sources": m.get("position_sources"),
        "baseline_estimate": m.get("baseline_estimate"),
        "reference_periods": m.get("reference_periods"),
        "receiver_clock": m.get("receiver_clock"),
    }
    warnings = [
        "dual-antenna differences cancel the multipath common to both antennas "
        f"({m.get('baseline_m', float('nan')):.1f} m baseline): the bound may be "
        "optimistic for a single antenna; the dual-frequency method is preferred"
    ]
    for note in (
        long_baseline_note(m.get("baseline_m")),
        baseline_note(m.get("baseline_estimate"), m.get("markers")),
    ):
        if note:
            warnings.append(note)
    return Isolated(series, None, details, tuple(warnings))


def isolate(
    inputs: InputData,
    cutoff: CutoffChoice | None,
    *,
    arcs: ArcOptions,
    highpass: HighPass,
    options: InputsConfig,
    progress: Progress = quiet,
) -> Isolated:
    """Isolate the multipath: dual-frequency (with the high-pass) or dual-antenna.

    Parameters
    ----------
    inputs : InputData
    cutoff : CutoffChoice or None
        The cutoff (dual-frequency); None for dual-antenna.
    arcs : ArcOptions
        Minimum arc length, elevation mask, slip threshold.
    highpass : HighPass
        Filter design (dual-frequency).
    options : InputsConfig
        Signals and system.
    progress : callable, optional

    Returns
    -------
    Isolated
    """
    if inputs.method == "df":
        if cutoff is None:
            raise InputError("dual-frequency isolation needs a cutoff frequency")
        return _isolate_df(
            inputs, cutoff, arcs, highpass, tuple(options.signals), options.system, progress
        )
    return _isolate_da(inputs, arcs, options, progress)


def map_elevation(series: Any, options: MappingOptions) -> ElevationMapping:
    """Return the multipath elevation mapping the options ask for, fitted on a series.

    Parameters
    ----------
    series : MultipathSeries
        The isolated (or screened) multipath, m, with its elevations, deg.
    options : MappingOptions
        ``fit`` (fitted here), ``thesis`` or ``fixed``.

    Returns
    -------
    ElevationMapping
    """
    return choose_mapping(options, series.value_m, series.elevation_deg)


def screen(
    isolated: Isolated,
    *,
    options: ScreeningOptions,
    mapping: ElevationMapping,
    min_length_s: float,
    progress: Progress = quiet,
) -> Screened:
    """Exclude residual ionosphere (ROTI) and physically implausible values.

    Parameters
    ----------
    isolated : Isolated
    options : ScreeningOptions
        ROTI threshold, guard, which tests.
    mapping : ElevationMapping
        The provisional multipath elevation mapping (:func:`map_elevation`
        of the isolated series; scales the fixed ROTI threshold).
    min_length_s : float
        Remainders shorter than this (the minimum window, s) are excluded.
    progress : callable, optional

    Returns
    -------
    Screened

    Raises
    ------
    NoDataError
        Everything was excluded.
    """
    progress("screening (ROTI of the geometry-free phase, carrier-multipath limit)")
    s = isolated.series
    channels = isolated.arcs.glonass_channels if isolated.arcs is not None else None
    sc = screen_series(
        s, options, min_length_s=min_length_s, mapping=mapping, glonass_channels=channels
    )
    if sc.series.n_arcs == 0:
        raise NoDataError(
            f"screening excluded all {sc.input_s / 3600:.2f} h of data "
            f"({len(sc.excluded)} spans: {sc.counts()}); nothing is left to bound"
        )
    warnings: tuple[str, ...] = ()
    if sc.excluded:
        counts = ", ".join(f"{n} {k}" for k, n in sc.counts().items())
        warnings = (
            f"screening excluded {sc.excluded_s / 3600:.2f} h ({100 * sc.excluded_fraction:.1f} %"
            f" of the data; {counts}): see screening.excluded",
        )
    return Screened(sc, mapping, warnings + sc.notes)


def _check_min_window(options: StationarityOptions, interval_s: float) -> str:
    """Refuse a minimum window the spectral test cannot use; say when the default is raised.

    The spectral test needs ``min_samples()`` samples: a shorter minimum window
    the user asked for is an error naming the option and what to give instead
    (it used to fail late, inside the PSD estimator); the default is raised
    with a warning.
    """
    if options.test != "spectral":
        return ""
    need_s = (min_samples() - 1) * interval_s
    if options.min_window_s >= need_s:
        return ""
    if options.min_window_s != StationarityOptions().min_window_s:
        raise InputError(
            f"--min-window-s ([stationarity] min_window_s) = {options.min_window_s:g} s is "
            f"shorter than the spectral stationarity test needs at {interval_s:g} s sampling "
            f"({min_samples()} samples = {need_s:g} s): give --min-window-s {need_s:g} or "
            "more, or --stationarity thesis"
        )
    return (
        f"minimum window raised from the default {options.min_window_s:g} s to {need_s:g} s: "
        f"the spectral stationarity test needs {min_samples()} samples at {interval_s:g} s"
    )


def window(
    screened: Screened,
    *,
    mapping: ElevationMapping,
    options: StationarityOptions,
    progress: Progress = quiet,
) -> Windowed:
    """Map the series by elevation and cut it into stationary windows.

    Parameters
    ----------
    screened : Screened
    mapping : ElevationMapping
        The bound's elevation mapping (:func:`map_elevation` of the screened series).
    options : StationarityOptions
    progress : callable, optional

    Returns
    -------
    Windowed

    Raises
    ------
    NoDataError
        No stationary window of the minimum length.
    """
    series = screened.series
    test = "Levene, then K-S" if options.test == "thesis" else "spectral homogeneity"
    progress(f"elevation mapping and stationarity windows ({test}, {options.windows})")
    raised = _check_min_window(options, series.interval_s)
    m = mapping
    windows = find_stationary_windows(
        series,
        mapping=m,
        alpha=options.alpha,
        p_slide=options.p_slide,
        p_trim=options.p_trim,
        min_length_s=options.min_window_s,
        center=options.levene_center,
        test=options.test,
        overlap=options.windows == "slide",
    )
    if len(windows) == 0:
        raise NoDataError(
            f"no stationary window of at least {options.min_window_s:g} s in {series.n_arcs} "
            f"arcs ({windows.n_tests} tests)"
        )
    warnings: tuple[str, ...] = (raised,) if raised else ()
    if windows.rejected_s > 0:
        warnings += (
            f"{windows.rejected_s / 60:.1f} min of data failed every stationarity test and are "
            "not covered by the bound (windows.rejected_s; windows.never_stationary lists "
            "these stretches together with any arcs too short to test)",
        )
    if windows.short_s > 0:
        warnings += (
            f"{windows.short_s / 60:.1f} min of data lie in arcs shorter than the minimum window "
            f"({windows.params['effective_min_length_s'] / 60:.0f} min): not tested, not covered "
            "by the bound",
        )
    if m.source.startswith("thesis (fit impossible"):
        warnings += (f"elevation mapping: {m.source}",)
    return Windowed(m, windows, warnings)


def bound(
    windowed: Windowed,
    *,
    spectra: SpectraOptions,
    options: BoundOptions,
    cutoff: CutoffChoice | None = None,
    highpass: HighPass | None = None,
    progress: Progress = quiet,
) -> BoundResults:
    """Estimate every window's PSD and fit the tightest GM + white-noise bound.

    Parameters
    ----------
    windowed : Windowed
    spectra : SpectraOptions
    options : BoundOptions
    cutoff : CutoffChoice, optional
        The high-pass cutoff (None: dual-antenna, no filter).
    highpass : HighPass, optional
        The filter design; the pooled rule bounds from where it passes 90 %
        of the power (:meth:`~psdbound.isolation.HighPass.passband_start_hz`)
        and divides the band averages by its power response ``|H(f)|^2``.
        Without cutoff: from twice the lowest frequency of the longest window.
    progress : callable, optional

    Returns
    -------
    BoundResults
    """
    progress(
        f"{len(windowed.windows)} windows: PSDs ({spectra.estimator}) and the {options.rule} bound"
    )
    model = BoundModel(windowed.windows, estimator=spectra.estimator, **spectra.options)
    f_min_hz = gain = None
    if cutoff is not None:
        hp, dt, fc = highpass or HighPass(), windowed.windows.interval_s, cutoff.f_c_hz
        f_min_hz = hp.passband_start_hz(dt, fc)

        def gain(f: np.ndarray) -> np.ndarray:
            return hp.response(f, dt, fc) ** 2

    return model.fit(
        power_response=gain if options.rule == "pooled" else None,
        rule=options.rule,
        objective=options.objective,
        f_min_hz=f_min_hz,
        confidence_level=options.confidence_level,
        coverage=options.coverage,
        shape_alpha=options.shape_alpha,
        tau_max_s=options.tau_max_s,
        bands_per_decade=options.bands_per_decade,
        target=options.target,
        level=options.level,
    )


def _resolve_geometries(
    inputs: InputData, options: ValidationOptions, measured_h_m: float | None = None
) -> tuple[list[str], str]:
    """Replace ``ground:h=header`` by the SNR-measured height, the header's, or the fallback."""
    out, note = [], ""
    for g in options.geometries:
        if g.replace(" ", "").lower() == "ground:h=header":
            h = float(inputs.observations[0].header.antenna_delta_hen_m[0])
            if measured_h_m is not None:
                h, note = (
                    measured_h_m,
                    (
                        f"ground reflector height {measured_h_m:.3g} m "
                        "measured from the SNR (validation.site_reflection)"
                    ),
                )
            elif h > 0:
                note = f"ground reflector height {h:g} m from the RINEX header (ANTENNA: DELTA H)"
            else:
                h = options.ground_height_m
                note = (
                    f"the RINEX header gives no antenna height (DELTA H = 0): ground "
                    f"reflector height {h:g} m from the configuration"
                )
            g = f"ground:h={h:.3g}"
        out.append(g)
    return out, note


def _slow_component(
    series: Any,
    geoms: Sequence[str],
    site: Any,
    lams: Sequence[float],
    hp: HighPass,
    cutoff_hz: float,
) -> list[dict[str, Any]]:
    """Per geometry: the removed multipath along the data's arcs and its slow GM (largest first).

    A ground height measured from the SNR is taken with its tolerance
    (:data:`psdbound.validation.site.HEIGHT_TOLERANCE_M`, relative
    ``HEIGHT_TOLERANCE``): the envelope over ``h - d, h, h + d``.
    """
    from psdbound.validation import parse_geometry
    from psdbound.validation.removed import envelope, removed_along_arcs
    from psdbound.validation.site import height_tolerance_m

    def removed(label: str) -> Any:
        return removed_along_arcs(
            series.elevation_deg,
            series.arc_id,
            geometry=parse_geometry(label),
            alpha=site.alpha,
            wavelengths_m=lams,
            highpass=hp,
            dt_s=series.interval_s,
            cutoff_hz=cutoff_hz,
        )

    rows = []
    for geom in dict.fromkeys(geoms):
        rm = removed(geom)
        h = site.ground_height_m
        if rm is not None and h is not None and geom == f"ground:h={h:.3g}":
            d = height_tolerance_m(h)
            rm = envelope(
                [rm, removed(f"ground:h={max(h - d, 0.05):.4g}"), removed(f"ground:h={h + d:.4g}")],
                geom,
            )
        if rm is not None:
            rows.append(rm.to_dict())
    return sorted(rows, key=lambda r: -r["sigma_m"])


def _site(
    inputs: InputData,
    series: Any,
    sats: Sequence[str],
    pos: Any,
    options: ValidationOptions,
    cutoff_hz: float,
    lam_m: float,
) -> Any:
    """Return the ground height and alpha: from the SNR when the options ask and it can."""
    from psdbound.validation.site import SiteReflection, removed_weight, site_reflection

    if not options.snr or not sats:
        return SiteReflection(
            options.alpha, None, False, note=f"alpha {options.alpha:g} assumed (configuration)"
        )
    weight = removed_weight(
        series.elevation_deg, series.t_gps_s, series.arc_id, wavelength_m=lam_m, cutoff_hz=cutoff_hz
    )
    return site_reflection(
        inputs.observations[0],
        inputs.orbit,
        phase_signal=series.signals[0],
        system=sats[0][0],
        receiver_xyz_m=pos,
        alpha=options.alpha,
        weight=weight,
    )


def _removed_rms(
    report: Any, lams: Sequence[float], alpha: float, slow: Sequence[dict[str, Any]] = ()
) -> list[dict]:
    """Per geometry: fraction of its power below f_c and the RMS the filter removes, m.

    The RMS is the slow component's (the removed series along the data's arcs,
    exact phase error: :mod:`psdbound.validation.removed`) where it was
    computed, so that every output quotes one number; else the fraction times
    the small-alpha variance of the reflection.
    """
    # small-alpha phase error alpha sin(psi): variance alpha^2/2 rad^2 per carrier;
    # the DF series (e_a - e_b)/sqrt(2) has the mean of the two carriers' variances
    var_m2 = float(np.mean([(lam / (2 * np.pi)) ** 2 * alpha**2 / 2 for lam in lams]))
    along = {row["geometry"]: row["removed_rms_m"] for row in slow}
    rows = []
    for geom in dict.fromkeys(c.geometry.label for c in report.expansion):
        direct = [
            d.fraction_below_cutoff
            for d in report.direct
            if d.geometry.label == geom and d.convention == "physical"
        ]
        exp = [
            c.fraction_below_cutoff
            for c in report.expansion
            if c.geometry.label == geom and c.convention == "physical"
        ]
        frac = float(np.median(direct)) if direct else float(max(exp))
        rows.append(
            {
                "geometry": geom,
                "fraction_below_fc": frac,
                "fraction_source": "passes of the data" if direct else "orbit-rate expansion",
                "n_passes": len(direct),
                "removed_rms_m": float(along.get(geom, np.sqrt(frac * var_m2))),
                "rms_source": "the removed series along the data's arcs (validation.slow)"
                if geom in along
                else "fraction below f_c times the reflection's small-alpha variance",
            }
        )
    return rows


def validate(
    cutoff: CutoffChoice | None,
    *,
    inputs: InputData,
    isolated: Isolated,
    arcs: ArcOptions,
    options: ValidationOptions,
    highpass: HighPass | None = None,
    progress: Progress = quiet,
) -> Validated:
    """Check how much multipath the cutoff removes, for reflectors around this antenna.

    The geometries are those of the options, with ``ground:h=header`` taken
    from the observation header. The fraction of each reflector's multipath
    power below the cutoff is computed along the satellite passes of the
    data (the satellites used, above the elevation mask, with the data's
    orbit and receiver position) and, as the thesis does, from the
    Jacobi-Anger expansion at the orbit rate. The RMS multipath the filter
    removes (``sqrt(fraction * alpha^2/2) * lambda / 2 pi``, DF-combined) is
    what the verdict compares with the bound.

    Parameters
    ----------
    cutoff : CutoffChoice or None
        None (dual-antenna: no high-pass, not applicable).
    inputs : InputData
        Header (antenna height), orbit and receiver position.
    isolated : Isolated
        Satellites and signals used.
    arcs : ArcOptions
        The elevation mask.
    options : ValidationOptions
        Geometries, amplitude ratio, threshold, rate.
    progress : callable, optional

    Returns
    -------
    Validated
    """
    if cutoff is None:
        summary = {
            "applicable": False,
            "verdict": "not applicable",
            "reason": "dual-antenna isolation applies no high-pass filter",
        }
        return Validated(None, summary)
    from psdbound.validation import validate_cutoff

    progress("cutoff validation (reflectors around this antenna, along the data's passes)")
    series = isolated.series
    sats = sorted(set(series.arc_sats))
    pos = inputs.receiver_xyz_m[0]
    pos = inputs.observations[0].header.approx_position_m if pos is None else np.asarray(pos)
    channels = isolated.arcs.glonass_channels if isolated.arcs is not None else None
    lams = [wavelength_m(sats[0] if sats else "G01", sg, channels) for sg in series.signals[:2]]
    site = _site(inputs, series, sats, pos, options, cutoff.f_c_hz, lams[0])
    geoms, note = _resolve_geometries(inputs, options, site.ground_height_m)
    report = validate_cutoff(
        geoms,
        cutoff_hz=cutoff.f_c_hz,
        rate=options.rate,
        alpha=site.alpha,
        threshold=options.threshold,
        orbit=inputs.orbit if pos is not None else None,
        receiver_xyz_m=pos,
        sats=sats,
        system=sats[0][0] if sats else "G",
        elevation_mask_deg=arcs.elevation_mask_deg,
    )
    slow = _slow_component(series, geoms, site, lams, highpass or HighPass(), cutoff.f_c_hz)
    removed = _removed_rms(report, lams, site.alpha, slow)
    summary = report.to_dict()
    summary.update(
        {
            "applicable": True,
            "geometries_used": geoms,
            "geometry_note": note,
            "site_reflection": site.to_dict(),
            "removed": removed,
            "max_removed_rms_m": max(r["removed_rms_m"] for r in removed),
            "slow": slow[0] if slow else None,
            "slow_by_geometry": slow,
            "summary": (
                f"{'pass' if report.passed else 'fail'} (thesis criterion): largest fraction of "
                f"multipath power below f_c over {', '.join(geoms)} vs threshold "
                f"{100 * options.threshold:g} %; the filter removes up to "
                f"{1000 * max(r['removed_rms_m'] for r in removed):.2f} mm RMS "
                f"(alpha {site.alpha:.3g}, {'measured' if site.measured else 'assumed'})"
            ),
        }
    )
    warnings = ()
    if not report.passed:
        worst = max(removed, key=lambda r: r["fraction_below_fc"])
        warnings = (
            f"cutoff validation (thesis criterion) failed: {worst['geometry']} puts "
            f"{100 * worst['fraction_below_fc']:.0f} % of its multipath power below f_c "
            f"(threshold {100 * options.threshold:g} %); the filter removes about "
            f"{1000 * worst['removed_rms_m']:.2f} mm RMS of it, which the bound does not "
            "see: it is the error model's slow component (error_model, validation.slow)",
        )
    return Validated(report, summary, warnings + ((note,) if note else ()))
