"""Screen an isolated multipath series: drop residual ionosphere and implausible values.

For every arc, consecutive 5-min blocks are tested:

* **ionosphere** (dual-frequency only): ROTI of the geometry-free phase
  (:mod:`psdbound.screening.rot`) above ``roti_threshold_tecu_min``;
* **implausible**: any sample of the isolated series beyond the physical
  carrier-multipath limit (:mod:`psdbound.screening.plausibility`).

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
(:mod:`psdbound.screening.null`, default 1e-3 per block): strong multipath
raises its own threshold, low satellites are screened at the same
false-alarm probability as high ones, and no elevation mapping is assumed.
When the null itself is disturbed (a heavy-tailed fit: much of the day is
ionosphere) the elevation-scaled fixed threshold below applies as well, and
a note says so.

The fixed threshold (``multipath_null=False``, or the fallback): multipath's
ROTI contribution scales with the elevation mapping ``m(el)`` the fit assumes
for multipath, so the threshold is ``0.15 m(el)`` TECU/min per block, with an
optional cap (``roti_cap_tecu_min``). It cut strong multipath as ionosphere (a
6 mm zenith multipath day lost every arc) and let disturbances of low
satellites through (about 2.8 TECU/min at 10 deg), which is why it is no
longer the default.

Measured with the defaults (``psdbound fit``): the quiet mid-latitude ESBC day
(2020-06-25, 30 s) has 5 blocks flagged (0.45 % of the data excluded, the
bound within 1.5 % of the fixed threshold's); NYA1 (78.9 N, 2024-05-03) has a
disturbed null (dof 1.9) and 20.6 % excluded (19.1 % with the fixed
threshold); a simulated 12-h day with 6 mm / 30 s zenith multipath and no
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

from psdbound.io.signals import carrier_frequency_hz, wavelength_m
from psdbound.isolation import MultipathSeries
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

__all__ = ["ExcludedSpan", "N_TESTS", "Screening", "ScreeningOptions", "screen_series"]

#: Tests of the multipath null that share the false-alarm probability (Bonferroni): the block
#: alone, the 15-min persistence and the coherence across satellites.
N_TESTS = 3


@dataclass(frozen=True)
class ExcludedSpan:
    """A stretch of one arc left out of the bound, and why.

    Attributes
    ----------
    sat : str
        Satellite (or satellite pair for double differences).
    start_gps_s, stop_gps_s : float
        First and last excluded sample, GPS seconds.
    reason : str
        E.g. ``"ionosphere: ROTI 1.30 TECU/min > 0.5"``.
    kind : {"ionosphere", "implausible", "short remainder"}
    statistic : float
        Largest ROTI (TECU/min), largest absolute value (m) or the
        remainder's length (s).
    threshold : float
        The limit it was compared with, same unit.
    """

    sat: str
    start_gps_s: float
    stop_gps_s: float
    reason: str
    kind: str
    statistic: float
    threshold: float

    @property
    def duration_s(self) -> float:
        """Length of the span, s."""
        return self.stop_gps_s - self.start_gps_s

    def to_dict(self) -> dict[str, Any]:
        """Return the entry of ``screening.excluded`` in result.json."""
        return {"sat": self.sat, "start_gps_s": self.start_gps_s, "stop_gps_s": self.stop_gps_s,
                "reason": self.reason, "kind": self.kind, "statistic": self.statistic,
                "threshold": self.threshold}  # fmt: skip


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


def _spans(flags: NDArray[np.bool_], start: NDArray[np.float64], stop: NDArray[np.float64]):
    """Merge consecutive flagged blocks into (first block, last block) index pairs."""
    idx = np.flatnonzero(flags)
    if idx.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(idx) > 1)
    firsts = np.r_[idx[0], idx[breaks + 1]]
    lasts = np.r_[idx[breaks], idx[-1]]
    return list(zip(firsts.tolist(), lasts.tolist(), strict=True))


def _arc_blocks(t: NDArray[np.float64], v: NDArray[np.float64], el: NDArray[np.float64],
                gf: NDArray[np.float64] | None,
                m_per_tecu: float | None) -> dict[str, Any]:  # fmt: skip
    """Per 5-min block of one arc: limits, ROTI, mean elevation and largest |value|."""
    t0, t1 = float(t[0]), float(t[-1])
    n_blocks = max(1, int(np.ceil((t1 - t0) / ROTI_BLOCK_S - 1e-9)))
    start = t0 + ROTI_BLOCK_S * np.arange(n_blocks)
    bi = np.clip(((t - t0) // ROTI_BLOCK_S).astype(int), 0, n_blocks - 1)
    vmax = np.zeros(n_blocks)
    np.maximum.at(vmax, bi, np.abs(v))
    el_mean = np.bincount(bi, weights=el, minlength=n_blocks) / np.maximum(
        np.bincount(bi, minlength=n_blocks), 1)  # fmt: skip
    roti = np.full(n_blocks, np.nan)
    if gf is not None and m_per_tecu is not None:
        tm, rot = rate_of_tec(t, gf, m_per_tecu)
        roti = roti_blocks(tm, rot, t0_gps_s=t0, t1_gps_s=max(t1, t0 + 1.0)).roti_tecu_min
        roti = np.r_[roti, np.full(max(0, n_blocks - roti.size), np.nan)][:n_blocks]
    return {"start": start, "stop": start + ROTI_BLOCK_S, "roti": roti, "el": el_mean,
            "vmax": vmax}  # fmt: skip


def _threshold(el_mean: NDArray[np.float64], opt: ScreeningOptions, mapping: Any,
               null: MultipathNull | None) -> NDArray[np.float64]:  # fmt: skip
    """ROTI threshold per block, TECU/min: the null's quantile and the base, or the scaled base."""
    base = np.full(el_mean.size, opt.roti_threshold_tecu_min)
    scaled = base
    if opt.elevation_scaled and mapping is not None:
        scaled = base * mapping.factor(el_mean)
        if opt.roti_cap_tecu_min is not None:
            scaled = np.minimum(scaled, opt.roti_cap_tecu_min)
    if null is None:
        return scaled
    thr = np.maximum(base, null.threshold(el_mean, _share(opt, null)))
    return thr if null.trusted else np.minimum(thr, np.maximum(base, scaled))


def _series_null(blocks: list[dict[str, Any]], opt: ScreeningOptions) -> MultipathNull | None:
    """Return the multipath null of the series' ROTI (None: not asked for, or too few blocks)."""
    if not (opt.multipath_null and opt.ionosphere) or not blocks:
        return None
    return fit_null(np.concatenate([b["roti"] for b in blocks]),
                    np.concatenate([b["el"] for b in blocks]))  # fmt: skip


def _share(opt: ScreeningOptions, null: MultipathNull) -> float:
    """False-alarm probability of each test of the null: ``p`` split between those applied.

    A trusted null runs :data:`N_TESTS` tests (block, persistence, coherence); an untrusted
    one only the block test.
    """
    return opt.false_alarm / (N_TESTS if null.trusted else 1)


def _coherent(blocks: list[dict[str, Any]], opt: ScreeningOptions,
              null: MultipathNull | None) -> list[NDArray[np.bool_]]:  # fmt: skip
    """Blocks flagged by the coherence test across satellites (none without a trusted null)."""
    if not opt.ionosphere or null is None or not null.trusted:
        return [np.zeros(b["roti"].size, bool) for b in blocks]
    return coherent_blocks([0.5 * (b["start"] + b["stop"]) for b in blocks],
                           [b["roti"] for b in blocks], [b["el"] for b in blocks], null,
                           false_alarm=_share(opt, null),
                           floor_tecu_min=opt.roti_threshold_tecu_min)  # fmt: skip


def _iono_reason(roti: NDArray, thr: NDArray, persist: NDArray, opt: ScreeningOptions,
                 b0: int, b1: int) -> tuple[str, float, float]:  # fmt: skip
    """Why a span of blocks is ionosphere: the test that flagged it, its statistic and limit."""
    ratio = roti[b0:b1 + 1] / thr[b0:b1 + 1]
    j = b0 + int(np.nanargmax(ratio))
    stat, th = float(roti[j]), float(thr[j])
    if stat > th:
        return f"ROTI {stat:.2f} TECU/min > {th:.2f}", stat, th
    if np.any(persist[b0:b1 + 1]):
        return (f"ROTI up to {stat:.2f} TECU/min over 15 min, improbable under this series' "
                f"multipath (false-alarm probability {opt.false_alarm:g})"), stat, th
    return (f"ROTI up to {stat:.2f} TECU/min on several satellites in the same 5 min, "
            f"improbable under this series' multipath, which is satellite-specific "
            f"(false-alarm probability {opt.false_alarm:g})"), stat, th


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
        phase used for ROTI; DA series get the plausibility test only).
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
    guard_s = opt.guard_s
    if guard_s is None:
        guard_s = 0.5 / series.cutoff_hz if series.cutoff_hz else 0.0
    limit = _limit(series, glonass_channels)
    dt = series.interval_s
    m_per_tecu = None
    if series.method == "DF" and series.unfiltered_m is not None:
        sat = series.arc_sats[0] if series.arc_sats else "G01"
        fa, fb = (carrier_frequency_hz(sat, s, glonass_channels) for s in series.signals[:2])
        m_per_tecu = geometry_free_m_per_tecu(fa, fb)
    kept: list[dict[str, Any]] = []
    excluded: list[ExcludedSpan] = []
    roti_fig: list[dict[str, Any]] = []
    input_s = 0.0
    bounds = series.arc_bounds()
    blocks = [_arc_blocks(series.t_gps_s[lo:hi], series.value_m[lo:hi],
                          series.elevation_deg[lo:hi],
                          None if series.unfiltered_m is None else series.unfiltered_m[lo:hi],
                          m_per_tecu) for lo, hi in bounds]  # fmt: skip
    null = _series_null(blocks, opt) if m_per_tecu is not None else None
    coherent = _coherent(blocks, opt, null)
    for k, (lo, hi) in enumerate(bounds):
        sats = series.arc_sats[k]
        t, v = series.t_gps_s[lo:hi], series.value_m[lo:hi]
        gf = None if series.unfiltered_m is None else series.unfiltered_m[lo:hi]
        input_s += t.size * dt
        el = series.elevation_deg[lo:hi]
        bk = blocks[k]
        start, stop, roti, vmax = bk["start"], bk["stop"], bk["roti"], bk["vmax"]
        thr = _threshold(bk["el"], opt, mapping, null)
        iono = (roti > thr) & ~np.isnan(roti) if opt.ionosphere else np.zeros(roti.size, bool)
        persist = np.zeros(roti.size, bool)
        if opt.ionosphere and null is not None and null.trusted:
            persist = null.persistent(roti, bk["el"], false_alarm=_share(opt, null),
                                      floor_tecu_min=opt.roti_threshold_tecu_min)  # fmt: skip
        iono |= persist | coherent[k]
        implaus = (vmax > limit) if opt.plausibility else np.zeros(roti.size, bool)
        keep = np.ones(t.size, bool)
        for b0, b1 in _spans(iono | implaus, start, stop):
            s0, s1 = start[b0] - guard_s, stop[b1] + guard_s
            sel = (t >= s0) & (t < s1)
            keep &= ~sel
            if np.any(implaus[b0:b1 + 1]) and not np.any(iono[b0:b1 + 1]):
                stat = float(vmax[b0:b1 + 1].max())
                e = ExcludedSpan(sats, float(t[sel][0]), float(t[sel][-1]),
                                 f"implausible: {100 * stat:.1f} cm > {100 * limit:.1f} cm "
                                 "carrier-multipath limit", "implausible", stat, limit)  # fmt: skip
            else:
                why, stat, th = _iono_reason(roti, thr, persist, opt, b0, b1)
                if np.any(implaus[b0:b1 + 1]):  # a disturbance drives the series off limits too
                    why += (f"; values up to {100 * float(vmax[b0:b1 + 1].max()):.1f} cm beyond "
                            f"the {100 * limit:.1f} cm carrier-multipath limit")
                e = ExcludedSpan(sats, float(t[sel][0]), float(t[sel][-1]),
                                 f"ionosphere: {why}", "ionosphere", stat, th)  # fmt: skip
            excluded.append(e)
        # kept pieces; remainders too short for a window are excluded with that reason
        edges = np.flatnonzero(np.diff(np.r_[0, keep.astype(np.int8), 0]))
        used = np.zeros(t.size, bool)
        for p0, p1 in zip(edges[::2], edges[1::2], strict=True):
            dur = (p1 - p0) * dt
            if keep.all() or dur >= min_length_s:
                piece = {"sats": sats, "t_gps_s": t[p0:p1], "value_m": v[p0:p1],
                         "elevation_deg": el[p0:p1]}  # fmt: skip
                if gf is not None:
                    piece["unfiltered_m"] = gf[p0:p1]
                kept.append(piece)
                used[p0:p1] = True
            else:
                excluded.append(ExcludedSpan(
                    sats, float(t[p0]), float(t[p1 - 1]),
                    f"short remainder: {dur / 60:.1f} min between excluded spans < "
                    f"{min_length_s / 60:g} min window", "short remainder", dur, min_length_s,
                ))  # fmt: skip
        blk = np.clip(((t - t[0]) // ROTI_BLOCK_S).astype(int), 0, start.size - 1)
        roti_fig.append({"sats": sats, "t_gps_s": 0.5 * (start + stop), "roti_tecu_min": roti,
                         "threshold_tecu_min": thr, "value_max_m": vmax,
                         "excluded": np.bincount(blk, weights=~used, minlength=start.size) > 0})
    excluded_s = input_s - sum(p["t_gps_s"].size for p in kept) * dt
    meta = dict(series.meta)
    meta["screening"] = {"limit_m": limit, "roti_threshold_tecu_min": opt.roti_threshold_tecu_min,
                         "guard_s": guard_s}  # fmt: skip
    out = MultipathSeries.from_arcs(
        series.method, kept, signals=series.signals, scaling=series.scaling,
        interval_s=dt, cutoff_hz=series.cutoff_hz, meta=meta,
    )  # fmt: skip
    notes = () if m_per_tecu is not None else (
        "no ionosphere test: dual-antenna differences cancel the ionosphere of a short baseline",
    )  # fmt: skip
    if null is not None and not null.trusted:
        notes += (f"the ROTI of multipath alone could not be told from the data: its fitted "
                  f"shape is heavy-tailed (dof {null.dof:.2g} < {NU_DISTURBED:g}), so much of "
                  f"the day is disturbed; the elevation-scaled threshold applies as well",)
    return Screening(out, tuple(excluded), limit, input_s, excluded_s, roti_fig, opt, notes,
                     guard_s, null)  # fmt: skip
