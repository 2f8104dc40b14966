"""Screen an isolated multipath series: drop residual ionosphere and implausible values.

For every arc, consecutive 5-min blocks are tested:

* **ionosphere** (dual-frequency only): ROTI of the geometry-free phase
  (:mod:`psdbound.screening.rot`) above ``roti_threshold_tecu_min``;
* **implausible**: any sample of the isolated series beyond the physical
  carrier-multipath limit (:mod:`psdbound.screening.plausibility`).

Where a third carrier exists, the three-frequency test
(:mod:`psdbound.screening.threefreq`) names blocks ionosphere or multipath,
flags the first and keeps ROTI-flagged blocks it names multipath.

Flagged blocks are merged into spans, widened by a guard on each side and
cut out of the arc. The guard is the memory of the high-pass filter: the
isolated value at time t is the filter's response to the geometry-free phase
within about half a cutoff period of t, so a disturbance contaminates the
isolated series ``0.5 / f_c`` beyond the blocks where ROTI sees it (by
default the guard is ``0.5 / f_c``: 524 s at 9.55e-4 Hz; none for
dual-antenna series, which are not filtered). On a simulated day with two
disturbances (ROTI 1.0 and 0.6 TECU/min, 45 and 30 min) the bound is 39 %
too high without a guard, 15 % with 300 s and exact (within 0.1 %) with
600 s. Remainders shorter than ``min_length_s``
cannot hold a stationary window and are excluded too, with that reason.
Nothing is dropped silently: every excluded span is listed with its
satellite, times, reason, statistic and threshold.

Why ROTI, and the threshold
---------------------------
The high-pass filter removes the slow ionosphere, not the fast fluctuations
of disturbed periods (auroral and cusp irregularities at high latitude,
equatorial plasma bubbles, travelling disturbances); those pass for
multipath. ROTI measures exactly these fluctuations and is the standard
index for them (Pi et al., 1997; the IGS ROTI product, Cherniak et al.,
2018). Published thresholds range from about 0.1 TECU/min (mid-latitude
irregularity studies) to 0.5 TECU/min and more (strong high-latitude and
equatorial activity). The base threshold is the mid-latitude level of Paul
et al. (2024), who found range spread-F (irregularities seen by ionosondes)
in every case with ROTI above 0.15 TECU/min over European stations.

Multipath moves the geometry-free phase too, and excluding real multipath
makes the bound optimistic exactly where multipath is strong. By default
(``multipath_null``) the threshold of a block is the larger of the base level
(0.15 TECU/min, not scaled) and the ROTI that the series' own multipath
exceeds with the stated false-alarm probability at that elevation
(:mod:`psdbound.screening.null`, default 1e-3 per block, shared between the
tests): strong multipath raises its own threshold, low satellites are
screened at the same false-alarm probability as high ones, and no elevation
mapping is assumed. When the null itself is disturbed (a heavy-tailed fit:
much of the day is ionosphere) the elevation-scaled fixed threshold below
applies as well, and a note says so.

The base level is a significance level, not a false-alarm device: no block
below it is called ionosphere, whatever the null says (the persistence,
coherence and three-frequency tests apply it too). It stays because on real
quiet days ROTI's far tail is much heavier than the chi-square the null
extrapolates from its lower quantiles (at 1e-3 per block the null's quantile
is exceeded by 2.3 % of ESBC's blocks and 1.2 % of ZIMM's): without it ESBC
loses 7.3 % of its data instead of 0.35 % (136 blocks against 0.6 expected)
for a bound 1 % lower, the ZIMM days 79-134 blocks instead of 8-13. It does
not guard against a null fitted on a disturbed series (that null is too
high; the base level only raises thresholds). The false-alarm probability of
the single-block test is therefore ``min(p / k, P_null(ROTI > 0.15))`` at
each elevation (``Screening.block_test``; per cut span
``ExcludedSpan.false_alarm_at_threshold``): the stated share where the
series' own quantile is above the base level (strong multipath, low
satellites), smaller where the base level sets the threshold (ESBC at every
elevation). Where the null's quantile sets it on real data, the realised rate
exceeds the stated one (1.6-4.8 % of ZIMM's blocks below 20 deg are cut on
quiet days, about half of that time repeating one sidereal day later):
``docs/method/screening.rst``.

The fixed threshold (``multipath_null=False``, or the fallback): multipath's
ROTI contribution scales with the elevation mapping ``m(el)`` the fit assumes
for multipath, so the threshold is ``0.15 m(el)`` TECU/min per block, with an
optional cap (``roti_cap_tecu_min``). It cut strong multipath as ionosphere (a
6 mm zenith multipath day lost every arc) and let disturbances of low
satellites through (about 2.8 TECU/min at 10 deg), which is why it is no
longer the default.

Measured with the defaults (``psdbound fit``): the quiet mid-latitude ESBC day
(2020-06-25, 30 s) has 5 blocks flagged (0.45 % of the data excluded, the
bound within 1.5 % of the fixed threshold's; L5Q keeps one of them: 0.35 %);
NYA1 (78.9 N, 2024-05-03) has a disturbed null (dof 1.9) and 20.4 % excluded
(19.1 % with the fixed threshold); a simulated 12-h day with 6 mm / 30 s zenith multipath and no
ionosphere (``psdbound simulate --preset demo --single-antenna --duration-h
12 --interval-s 30 --multipath sigma_gm_m=0.006,tau_s=30,sigma_wn_m=0.001,
mapping=1,2,15``) has nothing excluded and is bounded (the fixed threshold:
exit 2, every arc cut). ``benchmarks/screening.py`` measures both sides on
simulated days.

References
----------
Pi, X., Mannucci, A. J., Lindqwister, U. J., Ho, C. M. (1997). Monitoring of
global ionospheric irregularities using the worldwide GPS network.
Geophysical Research Letters 24(18), 2283-2286.

Cherniak, I., Krankowski, A., Zakharenkova, I. (2018). ROTI maps: a new IGS
ionospheric product characterizing the ionospheric irregularities
occurrence. GPS Solutions 22, 69.

Efron, B. (2004). Large-scale simultaneous hypothesis testing: the choice of
a null hypothesis. Journal of the American Statistical Association 99(465),
96-104.

Paul, K. S., Rafi, M. H., Haralambous, H., Mostafa, M. G. (2024). Correlation
of Rate of TEC Index and spread F over European ionosondes. Atmosphere 15(3),
331. doi:10.3390/atmos15030331
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import InputError
from psdbound.io.signals import carrier_frequency_hz, wavelength_m
from psdbound.isolation import MultipathSeries
from psdbound.screening.blocktest import block_test, tail_note
from psdbound.screening.coherence import coherent_blocks
from psdbound.screening.null import NU_DISTURBED, MultipathNull, fit_null
from psdbound.screening.options import ScreeningOptions
from psdbound.screening.plausibility import multipath_limit_m
from psdbound.screening.rot import (
    ROTI_BLOCK_S,
    geometry_free_m_per_tecu,
    rate_of_tec,
    roti_blocks,
)
from psdbound.screening.spans import ExcludedSpan, block_spans, excluded_span, kept_pieces
from psdbound.screening.threefreq import (
    POOL_BLOCKS,
    RATIO_MAX,
    RatioNull,
    ThreeFrequencyTest,
    TripleCombination,
    block_rates,
    empty_names,
    fit_ratio_null,
    pooled_ratio,
    summary,
    triple_combination,
)

__all__ = ["ExcludedSpan", "N_TESTS", "Screening", "ScreeningOptions", "screen_series"]

#: Tests of the multipath null that share the false-alarm probability (Bonferroni): the block
#: alone, the 15-min persistence and the coherence across satellites.
N_TESTS = 3


@dataclass(frozen=True)
class Screening:
    """The screened series and what was excluded.

    Attributes
    ----------
    series : MultipathSeries
        The kept pieces (arcs split where spans were cut out).
    excluded : tuple of ExcludedSpan
    limit_m : float
        Physical carrier-multipath limit of the series, metres.
    input_s, excluded_s : float
        Data time before screening and excluded time, s.
    roti : list of dict
        Per arc and 5-min block (for the screening figure): ``sats``, block
        mid-times ``t_gps_s``, ``roti_tecu_min`` (NaN for dual-antenna),
        ``threshold_tecu_min``, ``value_max_m`` (largest absolute isolated
        value) and ``excluded`` (block touched by an excluded span).
    options : ScreeningOptions
    notes : tuple of str
    guard_s : float
        The guard applied around flagged blocks, s.
    null : MultipathNull or None
        The ROTI of multipath alone per elevation band the test used (None:
        the fixed threshold).
    three_frequency : dict or None
        What the three-frequency test did (:func:`psdbound.screening.threefreq.summary`;
        None: the series has no third carrier). Where the test ran, the figure
        entries of ``roti`` also carry ``ratio_3f`` (the block's ratio),
        ``named_3f`` (its name) and ``roti_d_tecu_min`` (the RMS 30-s rate of the
        ionosphere-free combination D, TECU/min-equivalent).
    """

    series: MultipathSeries
    excluded: tuple[ExcludedSpan, ...]
    limit_m: float
    input_s: float
    excluded_s: float
    roti: list[dict[str, Any]] = field(default_factory=list)
    options: ScreeningOptions = field(default_factory=ScreeningOptions)
    notes: tuple[str, ...] = ()
    guard_s: float = 0.0
    null: MultipathNull | None = None
    three_frequency: dict[str, Any] | None = None
    block_test: dict[str, Any] | None = None

    @property
    def excluded_fraction(self) -> float:
        """Excluded time over input time (0 when there is no input)."""
        return self.excluded_s / self.input_s if self.input_s > 0 else 0.0

    def counts(self) -> dict[str, int]:
        """Return the number of excluded spans by kind."""
        out: dict[str, int] = {}
        for e in self.excluded:
            out[e.kind] = out.get(e.kind, 0) + 1
        return out


def _limit(series: MultipathSeries, channels: Mapping[str, int] | None = None) -> float:
    sat = series.arc_sats[0] if series.arc_sats else "G01"
    sat = sat.split("-")[0]
    if series.method == "DF":
        lams = [wavelength_m(sat, s, channels) for s in series.signals[:2]]
    else:
        lams = [wavelength_m(sat, series.signals[0], channels)] * 4
    return multipath_limit_m(lams, series.scaling)


def _arc_blocks(
    t: NDArray[np.float64],
    v: NDArray[np.float64],
    el: NDArray[np.float64],
    gf: NDArray[np.float64] | None,
    m_per_tecu: float | None,
    third: NDArray[np.float64] | None = None,
    comb: TripleCombination | None = None,
) -> dict[str, Any]:
    """Per 5-min block of one arc: limits, ROTI, mean elevation, largest |value|, 3F ratio."""
    t0, t1 = float(t[0]), float(t[-1])
    n_blocks = max(1, int(np.ceil((t1 - t0) / ROTI_BLOCK_S - 1e-9)))
    start = t0 + ROTI_BLOCK_S * np.arange(n_blocks)
    bi = np.clip(((t - t0) // ROTI_BLOCK_S).astype(int), 0, n_blocks - 1)
    vmax = np.zeros(n_blocks)
    np.maximum.at(vmax, bi, np.abs(v))
    el_mean = np.bincount(bi, weights=el, minlength=n_blocks) / np.maximum(
        np.bincount(bi, minlength=n_blocks), 1
    )
    roti = np.full(n_blocks, np.nan)
    if gf is not None and m_per_tecu is not None:
        tm, rot = rate_of_tec(t, gf, m_per_tecu)
        roti = roti_blocks(tm, rot, t0_gps_s=t0, t1_gps_s=max(t1, t0 + 1.0)).roti_tecu_min
        roti = np.r_[roti, np.full(max(0, n_blocks - roti.size), np.nan)][:n_blocks]
    roti_d = ratio = np.full(n_blocks, np.nan)
    if gf is not None and third is not None and comb is not None and np.isfinite(third).any():
        roti_i, roti_d = block_rates(t, gf, third, comb, n_blocks=n_blocks)
        ratio = pooled_ratio(roti_i, roti_d, blocks=POOL_BLOCKS)
    return {
        "start": start,
        "stop": start + ROTI_BLOCK_S,
        "roti": roti,
        "el": el_mean,
        "vmax": vmax,
        "ratio": ratio,
        "roti_d": roti_d,
        "named": empty_names(n_blocks),
    }


def _combination(
    series: MultipathSeries, sats: str, channels: Mapping[str, int] | None
) -> TripleCombination | None:
    """Return the three-frequency combinations of an arc's satellite (None: no third carrier)."""
    if series.method != "DF" or series.third_m is None or series.third_signal is None:
        return None
    sat = sats.split("-")[0]
    try:
        fa, fb, fc = (
            carrier_frequency_hz(sat, c, channels)
            for c in (*series.signals[:2], series.third_signal)
        )
    except InputError:
        return None
    return triple_combination(fa, fb, fc)


def _threshold(
    el_mean: NDArray[np.float64],
    opt: ScreeningOptions,
    mapping: Any,
    null: MultipathNull | None,
    share: float,
) -> NDArray[np.float64]:
    """ROTI threshold per block, TECU/min: the null's quantile and the base, or the scaled base."""
    base = np.full(el_mean.size, opt.roti_threshold_tecu_min)
    scaled = base
    if opt.elevation_scaled and mapping is not None:
        scaled = base * mapping.factor(el_mean)
        if opt.roti_cap_tecu_min is not None:
            scaled = np.minimum(scaled, opt.roti_cap_tecu_min)
    if null is None:
        return scaled
    thr = np.maximum(base, null.threshold(el_mean, share))
    return thr if null.trusted else np.minimum(thr, np.maximum(base, scaled))


def _series_null(blocks: list[dict[str, Any]], opt: ScreeningOptions) -> MultipathNull | None:
    """Return the multipath null of the series' ROTI (None: not asked for, or too few blocks)."""
    if not (opt.multipath_null and opt.ionosphere) or not blocks:
        return None
    return fit_null(
        np.concatenate([b["roti"] for b in blocks]), np.concatenate([b["el"] for b in blocks])
    )


def _ratio_null(
    blocks: list[dict[str, Any]], opt: ScreeningOptions, null: MultipathNull | None
) -> RatioNull | None:
    """Return the null of the three-frequency ratio (None: no third carrier or not asked for)."""
    if null is None or not opt.three_frequency or not blocks:
        return None
    return fit_ratio_null(
        np.concatenate([b["ratio"] for b in blocks]), np.concatenate([b["el"] for b in blocks])
    )


def _share(opt: ScreeningOptions, null: MultipathNull, three: bool = False) -> float:
    """False-alarm probability of each test of the null: ``p`` split between those applied.

    A trusted null runs :data:`N_TESTS` tests (block, persistence, coherence); an untrusted
    one only the block test; the three-frequency test, where it runs, is one more.
    """
    return opt.false_alarm / ((N_TESTS if null.trusted else 1) + int(three))


def _coherent(
    blocks: list[dict[str, Any]], opt: ScreeningOptions, null: MultipathNull | None, share: float
) -> list[NDArray[np.bool_]]:
    """Blocks flagged by the coherence test across satellites (none without a trusted null)."""
    if not opt.ionosphere or null is None or not null.trusted:
        return [np.zeros(b["roti"].size, bool) for b in blocks]
    return coherent_blocks(
        [0.5 * (b["start"] + b["stop"]) for b in blocks],
        [b["roti"] for b in blocks],
        [b["el"] for b in blocks],
        null,
        false_alarm=share,
        floor_tecu_min=opt.roti_threshold_tecu_min,
    )


def _arc_flags(
    bk: dict[str, Any], coherent: NDArray[np.bool_], ctx: dict[str, Any]
) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """One arc's ionosphere flags: threshold, ROTI tests' flags, persistence, final flags."""
    opt, null, tf = ctx["opt"], ctx["null"], ctx["tf"]
    roti = bk["roti"]
    thr = _threshold(bk["el"], opt, ctx["mapping"], null, ctx["share"])
    iono = (roti > thr) & ~np.isnan(roti) if opt.ionosphere else np.zeros(roti.size, bool)
    persist = np.zeros(roti.size, bool)
    if opt.ionosphere and null is not None and null.trusted:
        persist = null.persistent(
            roti, bk["el"], false_alarm=ctx["share"], floor_tecu_min=opt.roti_threshold_tecu_min
        )
    flagged = iono | persist | coherent
    if tf is None or not opt.ionosphere:
        return thr, flagged, persist, flagged
    bk["named"] = tf.name(bk["ratio"], bk["el"], roti)
    return thr, flagged, persist, tf.decide(flagged, bk["named"])


def _keep_known_multipath(
    iono: NDArray[np.bool_],
    sats: str,
    start: NDArray[np.float64],
    stop: NDArray[np.float64],
    ctx: dict[str, Any],
) -> NDArray[np.bool_]:
    """Unflag the blocks inside spans known to hold multipath (``keep_spans``); count them."""
    spans = [(a, b) for sat, a, b in ctx["opt"].keep_spans if sat == sats]
    if not spans or not iono.any():
        return iono
    known = np.zeros(iono.size, bool)
    for a, b in spans:
        known |= (start < b) & (stop > a)
    ctx["kept_known"] += int((iono & known).sum())
    return iono & ~known


def _screen_arc(
    series: MultipathSeries,
    lo: int,
    hi: int,
    k: int,
    bk: dict[str, Any],
    coherent: NDArray[np.bool_],
    ctx: dict[str, Any],
) -> dict[str, Any]:
    """Screen one arc: its flags, excluded spans, kept pieces and figure entry."""
    sats, t = series.arc_sats[k], series.t_gps_s[lo:hi]
    arc = {
        "sats": sats,
        "t_gps_s": t,
        "value_m": series.value_m[lo:hi],
        "elevation_deg": series.elevation_deg[lo:hi],
    }
    for key in ("unfiltered_m", "third_m"):
        if getattr(series, key) is not None:
            arc[key] = getattr(series, key)[lo:hi]
    start, stop = bk["start"], bk["stop"]
    thr, flagged, persist, iono = _arc_flags(bk, coherent, ctx)
    iono = _keep_known_multipath(iono, sats, start, stop, ctx)
    opt = ctx["opt"]
    implaus = (bk["vmax"] > ctx["limit"]) if opt.plausibility else np.zeros(start.size, bool)
    keep = np.ones(t.size, bool)
    excluded = []
    for b0, b1 in block_spans(iono | implaus, start, stop):
        sel = (t >= start[b0] - ctx["guard_s"]) & (t < stop[b1] + ctx["guard_s"])
        keep &= ~sel
        flags = (thr, flagged, persist, iono, implaus)
        excluded.append(excluded_span(t, sats, sel, bk, flags, b0, b1, ctx))
    kept, short, used = kept_pieces(t, keep, arc, ctx)
    blk = np.clip(((t - t[0]) // ROTI_BLOCK_S).astype(int), 0, start.size - 1)
    fig = {
        "sats": sats,
        "t_gps_s": 0.5 * (start + stop),
        "roti_tecu_min": bk["roti"],
        "threshold_tecu_min": thr,
        "value_max_m": bk["vmax"],
        "excluded": np.bincount(blk, weights=~used, minlength=start.size) > 0,
    }
    if ctx["tf"] is not None:
        fig.update(ratio_3f=bk["ratio"], named_3f=bk["named"], roti_d_tecu_min=bk["roti_d"])
    return {
        "kept": kept,
        "excluded": excluded + short,
        "fig": fig,
        "flagged": flagged,
        "input_s": t.size * ctx["dt"],
    }


def _m_per_tecu(series: MultipathSeries, channels: Mapping[str, int] | None) -> float | None:
    """Metres of the series' geometry-free phase per TECU (None: no ionosphere test)."""
    if series.method != "DF" or series.unfiltered_m is None:
        return None
    sat = series.arc_sats[0] if series.arc_sats else "G01"
    fa, fb = (carrier_frequency_hz(sat, s, channels) for s in series.signals[:2])
    return geometry_free_m_per_tecu(fa, fb)


def _notes(
    m_per_tecu: float | None,
    null: MultipathNull | None,
    rnull: RatioNull | None,
    tf: ThreeFrequencyTest | None,
) -> tuple[str, ...]:
    """Return the notes: no ionosphere test, a disturbed null, no three-frequency test."""
    notes = (
        ()
        if m_per_tecu is not None
        else (
            "no ionosphere test: dual-antenna differences cancel the ionosphere common to "
            "both antennas (all of it on a short baseline; over kilometres a differential "
            "part remains, which the bound covers as multipath)",
        )
    )
    if null is not None and not null.trusted:
        notes += (
            f"the ROTI of multipath alone could not be told from the data: its fitted "
            f"shape is heavy-tailed (dof {null.dof:.2g} < {NU_DISTURBED:g}), so much of "
            f"the day is disturbed; the elevation-scaled threshold applies as well",
        )
    if rnull is not None and tf is None:
        med = rnull.median()
        notes += (
            f"no three-frequency test: the rate of the ionosphere combination over that of "
            f"the ionosphere-free one is {med.min():.2g}-{med.max():.2g} in the median "
            f"block (multipath alone: about 1 or less, at most {RATIO_MAX:g}), its shape's "
            f"dof {rnull.dof:.2g} (heavy-tailed below {NU_DISTURBED:g}): "
            + (
                "the typical block holds ionosphere, so the three carriers name the day disturbed"
                if med.max() > RATIO_MAX
                else "the null is heavy-tailed"
            )
            + "; no block is kept or flagged by it",
        )
    return notes


def screen_series(
    series: MultipathSeries,
    options: ScreeningOptions | None = None,
    *,
    min_length_s: float = 600.0,
    mapping: Any = None,
    glonass_channels: Mapping[str, int] | None = None,
) -> Screening:
    """Exclude residual ionosphere and physically implausible values from a series.

    Parameters
    ----------
    series : MultipathSeries
        Isolated multipath (DF series carry the unfiltered geometry-free
        phase used for ROTI, and ``L_a - L_c`` where a third carrier exists;
        DA series get the plausibility test only).
    options : ScreeningOptions, optional
        Threshold, guard and which tests to run.
    min_length_s : float, default 600
        Remainders shorter than this (the minimum stationary window) are
        excluded as "short remainder".
    mapping : ElevationMapping, optional
        Elevation mapping of the multipath (anything with a
        ``factor(elevation_deg)`` method) for the elevation-scaled ROTI
        threshold; None uses the flat threshold.
    glonass_channels : mapping, optional
        GLONASS FDMA frequency numbers per satellite (``{"R01": 1}``), for
        the wavelengths of a GLONASS series.

    Returns
    -------
    Screening
    """
    opt = options or ScreeningOptions()
    guard_s = _guard_s(series, opt)
    m_per_tecu = _m_per_tecu(series, glonass_channels)
    bounds = series.arc_bounds()
    blocks = _series_blocks(series, bounds, m_per_tecu, glonass_channels)
    null = _series_null(blocks, opt) if m_per_tecu is not None else None
    rnull = _ratio_null(blocks, opt, null)
    three = rnull is not None and rnull.trusted
    share = _share(opt, null, three) if null is not None else opt.false_alarm
    tf = ThreeFrequencyTest(rnull, share, opt.roti_threshold_tecu_min) if three else None
    ctx = {
        "opt": opt,
        "null": null,
        "tf": tf,
        "share": share,
        "mapping": mapping,
        "limit": _limit(series, glonass_channels),
        "guard_s": guard_s,
        "dt": series.interval_s,
        "min_length_s": min_length_s,
        "kept_known": 0,
    }
    coherent = _coherent(blocks, opt, null, share)
    arcs = [
        _screen_arc(series, lo, hi, k, blocks[k], coherent[k], ctx)
        for k, (lo, hi) in enumerate(bounds)
    ]
    kept = [p for a in arcs for p in a["kept"]]
    input_s = float(sum(a["input_s"] for a in arcs))
    excluded_s = input_s - sum(p["t_gps_s"].size for p in kept) * series.interval_s
    out = _kept_series(series, kept, ctx)
    three_freq = _three_frequency(series, bounds, blocks, arcs, null, rnull, tf)
    notes = _notes(m_per_tecu, null, rnull, tf)
    test = block_test(
        null,
        lambda el: _threshold(el, opt, mapping, null, share),
        blocks,
        share,
        opt.roti_threshold_tecu_min,
    )
    notes += tuple(n for n in (tail_note(test),) if n)
    if tf is not None and three_freq is not None:
        notes += (_three_frequency_note(three_freq),)
    if ctx["kept_known"]:
        notes += (
            f"{ctx['kept_known']} block(s) flagged as ionosphere kept as multipath: they lie "
            "in spans known to repeat one sidereal day later (screening.options.keep_spans)",
        )
    return Screening(
        out,
        tuple(e for a in arcs for e in a["excluded"]),
        ctx["limit"],
        input_s,
        excluded_s,
        [a["fig"] for a in arcs],
        opt,
        notes,
        guard_s,
        null,
        three_freq,
        test,
    )


def _guard_s(series: MultipathSeries, opt: ScreeningOptions) -> float:
    """Return the guard around flagged blocks, s: the option, else half a cutoff period or 0."""
    guard_s = opt.guard_s
    if guard_s is None:
        guard_s = 0.5 / series.cutoff_hz if series.cutoff_hz else 0.0
    return guard_s


def _series_blocks(
    series: MultipathSeries,
    bounds: list[tuple[int, int]],
    m_per_tecu: float | None,
    glonass_channels: Mapping[str, int] | None,
) -> list[dict[str, Any]]:
    """Per arc of the series, its 5-min blocks (:func:`_arc_blocks`)."""
    return [
        _arc_blocks(
            series.t_gps_s[lo:hi],
            series.value_m[lo:hi],
            series.elevation_deg[lo:hi],
            _part(series.unfiltered_m, lo, hi),
            m_per_tecu,
            _part(series.third_m, lo, hi),
            _combination(series, series.arc_sats[k], glonass_channels),
        )
        for k, (lo, hi) in enumerate(bounds)
    ]


def _kept_series(
    series: MultipathSeries, kept: list[dict[str, Any]], ctx: dict[str, Any]
) -> MultipathSeries:
    """Return the series of the kept pieces, its meta with the screening's limit and guard."""
    meta = dict(series.meta)
    meta["screening"] = {
        "limit_m": ctx["limit"],
        "guard_s": ctx["guard_s"],
        "roti_threshold_tecu_min": ctx["opt"].roti_threshold_tecu_min,
    }
    return MultipathSeries.from_arcs(
        series.method,
        kept,
        signals=series.signals,
        scaling=series.scaling,
        interval_s=series.interval_s,
        cutoff_hz=series.cutoff_hz,
        meta=meta,
        third_signal=series.third_signal,
    )


def _three_frequency(
    series: MultipathSeries,
    bounds: list[tuple[int, int]],
    blocks: list[dict[str, Any]],
    arcs: list[dict[str, Any]],
    null: MultipathNull | None,
    rnull: RatioNull | None,
    tf: ThreeFrequencyTest | None,
) -> dict[str, Any] | None:
    """Return what the three-frequency test did (None: the series has no third carrier)."""
    if rnull is None and (null is None or series.third_m is None):
        return None
    return summary(
        tf,
        rnull,
        series.third_signal,
        len(bounds),
        sum(bool(np.isfinite(b["ratio"]).any()) for b in blocks),
        blocks,
        [a["flagged"] for a in arcs],
    )


def _three_frequency_note(f: dict[str, Any]) -> str:
    """Say what the three-frequency test kept, confirmed and added."""
    return (
        f"three-frequency test ({f['signal']} on {f['arcs_with_third']} of "
        f"{f['arcs']} arcs): {f['kept_as_multipath']} blocks flagged by ROTI kept as "
        f"multipath, {f['confirmed']} confirmed and {f['added']} added as ionosphere "
        "(screening.three_frequency)"
    )


def _part(a: NDArray[np.float64] | None, lo: int, hi: int) -> NDArray[np.float64] | None:
    """``a[lo:hi]``, or None."""
    return None if a is None else a[lo:hi]
