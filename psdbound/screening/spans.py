"""Excluded spans of an arc: merging flagged blocks, the reason in words, what is kept.

Helpers of :func:`psdbound.screening.screen_series`: consecutive flagged
5-min blocks are merged into spans, each span gets the test that flagged it
with its statistic and threshold, and the remainders between spans are kept
or, shorter than a window, excluded as "short remainder".
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.screening.threefreq import ThreeFrequencyTest

__all__ = ["TESTS", "ExcludedSpan", "block_spans", "excluded_span", "kept_pieces"]

#: The tests a span can be excluded by (``ExcludedSpan.test``).
TESTS = ("block", "persistence", "coherence", "three-frequency", "limit", "length")


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
    test : str
        The test that flagged the span (:data:`TESTS`): ``"block"`` (one
        block's ROTI against its threshold), ``"persistence"`` (15 min of
        blocks), ``"coherence"`` (several satellites in one 5-min slot),
        ``"three-frequency"``, ``"limit"`` (the carrier-multipath limit) or
        ``"length"`` (a short remainder).
    false_alarm : float or None
        Stated false-alarm probability of that test under the series'
        multipath null: its share of ``ScreeningOptions.false_alarm`` (per
        block, per 15-min run or per 5-min slot); None where no probability
        applies (``"limit"``, ``"length"``, the fixed threshold without a
        null).
    false_alarm_at_threshold : float or None
        For the ``"block"`` test: the probability that a block of multipath
        alone at that elevation exceeds the threshold the statistic was
        compared with, under the fitted null. Equal to ``false_alarm`` where
        the null's quantile sets the threshold, smaller where the ionospheric
        significance level (``roti_threshold_tecu_min``) lies above it,
        larger where an untrusted null's threshold is lowered to the
        elevation-scaled fixed one. None for the other tests.
    """

    sat: str
    start_gps_s: float
    stop_gps_s: float
    reason: str
    kind: str
    statistic: float
    threshold: float
    test: str = ""
    false_alarm: float | None = None
    false_alarm_at_threshold: float | None = None

    @property
    def duration_s(self) -> float:
        """Length of the span, s."""
        return self.stop_gps_s - self.start_gps_s

    def to_dict(self) -> dict[str, Any]:
        """Return the entry of ``screening.excluded`` in result.json."""
        return {
            "sat": self.sat,
            "start_gps_s": self.start_gps_s,
            "stop_gps_s": self.stop_gps_s,
            "reason": self.reason,
            "kind": self.kind,
            "statistic": self.statistic,
            "threshold": self.threshold,
            "test": self.test,
            "false_alarm": self.false_alarm,
            "false_alarm_at_threshold": self.false_alarm_at_threshold,
        }


def block_spans(flags: NDArray[np.bool_], start: NDArray[np.float64], stop: NDArray[np.float64]):
    """Merge consecutive flagged blocks into (first block, last block) index pairs."""
    idx = np.flatnonzero(flags)
    if idx.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(idx) > 1)
    firsts = np.r_[idx[0], idx[breaks + 1]]
    lasts = np.r_[idx[breaks], idx[-1]]
    return list(zip(firsts.tolist(), lasts.tolist(), strict=True))


def _iono_reason(
    roti: NDArray, thr: NDArray, persist: NDArray, share: float, b0: int, b1: int
) -> tuple[str, float, float, str, int]:
    """Why a span of blocks is ionosphere: the reason, statistic, limit, test and its block.

    The block whose ROTI is highest over its threshold names the span: above
    the threshold, the single-block test; below it, the persistence test when
    it flagged a block of the span, else the coherence test.
    """
    ratio = roti[b0 : b1 + 1] / thr[b0 : b1 + 1]
    j = b0 + int(np.nanargmax(ratio))
    stat, th = float(roti[j]), float(thr[j])
    if stat > th:
        return f"ROTI {stat:.2f} TECU/min > {th:.2f}", stat, th, "block", j
    if np.any(persist[b0 : b1 + 1]):
        why = (
            f"ROTI up to {stat:.2f} TECU/min over 15 min, improbable under this series' "
            f"multipath (false-alarm probability {share:.2g} per 15-min run)"
        )
        return why, stat, th, "persistence", j
    why = (
        f"ROTI up to {stat:.2f} TECU/min on several satellites in the same 5 min, "
        f"improbable under this series' multipath, which is satellite-specific "
        f"(false-alarm probability {share:.2g} per 5-min slot)"
    )
    return why, stat, th, "coherence", j


def _three_reason(
    bk: dict[str, Any],
    by_roti: NDArray[np.bool_],
    tf: ThreeFrequencyTest,
    opt: Any,
    b0: int,
    b1: int,
) -> tuple[str, float, float] | None:
    """Return the three-frequency part of a span's reason (None: the test said nothing there)."""
    sel = slice(b0, b1 + 1)
    hit = np.flatnonzero(bk["named"][sel] == "ionosphere")
    if hit.size == 0:
        return None
    j = b0 + int(hit[np.argmax(bk["ratio"][sel][hit])])
    t, lvl = float(bk["ratio"][j]), float(tf.null.level(bk["el"][j], tf.false_alarm))
    what = (
        f"the rate of the ionosphere combination {np.sqrt(t):.1f} times that of the "
        f"ionosphere-free one (three-frequency ratio {t:.1f} > {lvl:.1f})"
    )
    if np.any(by_roti[sel]):
        return f"; confirmed by three carriers: {what}", float("nan"), float("nan")
    stat = float(np.nanmax(bk["roti"][sel]))
    return (
        f"ROTI up to {stat:.2f} TECU/min with {what}, improbable under this series' "
        f"multipath (false-alarm probability {tf.false_alarm:.2g} per block)",
        stat,
        opt.roti_threshold_tecu_min,
    )


def _block_false_alarm(
    ctx: Mapping[str, Any], test: str, threshold: float, elevation_deg: float
) -> tuple[float | None, float | None]:
    """Return a span's stated false-alarm probability and, for one block, that at its threshold.

    None without a multipath null (the fixed threshold states no probability).
    """
    null = ctx["null"]
    if null is None:
        return None, None
    if test == "three-frequency":
        return float(ctx["tf"].false_alarm), None
    if test != "block":
        return float(ctx["share"]), None
    return float(ctx["share"]), float(null.exceedance(threshold, elevation_deg))


def excluded_span(
    t: NDArray,
    sats: str,
    sel: NDArray,
    bk: dict[str, Any],
    flags: tuple,
    b0: int,
    b1: int,
    ctx: Mapping[str, Any],
) -> ExcludedSpan:
    """Return the excluded span of blocks ``b0..b1`` of one arc, with its reason and test."""
    thr, flagged, persist, iono, implaus = flags
    limit, opt, vmax = ctx["limit"], ctx["opt"], bk["vmax"]
    t_a, t_b = float(t[sel][0]), float(t[sel][-1])
    if np.any(implaus[b0 : b1 + 1]) and not np.any(iono[b0 : b1 + 1]):
        stat = float(vmax[b0 : b1 + 1].max())
        return ExcludedSpan(
            sats,
            t_a,
            t_b,
            f"implausible: {100 * stat:.1f} cm > {100 * limit:.1f} cm carrier-multipath limit",
            "implausible",
            stat,
            limit,
            "limit",
        )
    by_roti = flagged & (bk["named"] != "multipath")
    three = None if ctx["tf"] is None else _three_reason(bk, by_roti, ctx["tf"], opt, b0, b1)
    if three is not None and not np.any(by_roti[b0 : b1 + 1]):
        (why, stat, th), test, j = three, "three-frequency", b0
    else:
        why, stat, th, test, j = _iono_reason(bk["roti"], thr, persist, ctx["share"], b0, b1)
        why += "" if three is None else three[0]
    if np.any(implaus[b0 : b1 + 1]):  # a disturbance drives the series off limits too
        why += (
            f"; values up to {100 * float(vmax[b0 : b1 + 1].max()):.1f} cm beyond "
            f"the {100 * limit:.1f} cm carrier-multipath limit"
        )
    fa, fa_thr = _block_false_alarm(ctx, test, th, float(bk["el"][j]))
    return ExcludedSpan(
        sats, t_a, t_b, f"ionosphere: {why}", "ionosphere", stat, th, test, fa, fa_thr
    )


def kept_pieces(
    t: NDArray, keep: NDArray[np.bool_], arc: dict[str, Any], ctx: Mapping[str, Any]
) -> tuple[list[dict[str, Any]], list[ExcludedSpan], NDArray[np.bool_]]:
    """Return the kept pieces of one arc, the short remainders excluded, the samples used.

    Remainders too short for a window (``ctx["min_length_s"]``) are excluded
    with that reason.
    """
    dt, min_length_s = ctx["dt"], ctx["min_length_s"]
    edges = np.flatnonzero(np.diff(np.r_[0, keep.astype(np.int8), 0]))
    used = np.zeros(t.size, bool)
    kept, excluded = [], []
    for p0, p1 in zip(edges[::2], edges[1::2], strict=True):
        dur = (p1 - p0) * dt
        if keep.all() or dur >= min_length_s:
            kept.append({k: (v if k == "sats" else v[p0:p1]) for k, v in arc.items()})
            used[p0:p1] = True
        else:
            excluded.append(
                ExcludedSpan(
                    arc["sats"],
                    float(t[p0]),
                    float(t[p1 - 1]),
                    f"short remainder: {dur / 60:.1f} min between excluded spans < "
                    f"{min_length_s / 60:g} min window",
                    "short remainder",
                    dur,
                    min_length_s,
                    "length",
                )
            )
    return kept, excluded, used
