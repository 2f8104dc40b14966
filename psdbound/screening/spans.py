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

__all__ = ["ExcludedSpan", "block_spans", "excluded_span", "kept_pieces"]


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
        return {
            "sat": self.sat,
            "start_gps_s": self.start_gps_s,
            "stop_gps_s": self.stop_gps_s,
            "reason": self.reason,
            "kind": self.kind,
            "statistic": self.statistic,
            "threshold": self.threshold,
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
    roti: NDArray, thr: NDArray, persist: NDArray, opt: Any, b0: int, b1: int
) -> tuple[str, float, float]:
    """Why a span of blocks is ionosphere: the test that flagged it, its statistic and limit."""
    ratio = roti[b0 : b1 + 1] / thr[b0 : b1 + 1]
    j = b0 + int(np.nanargmax(ratio))
    stat, th = float(roti[j]), float(thr[j])
    if stat > th:
        return f"ROTI {stat:.2f} TECU/min > {th:.2f}", stat, th
    if np.any(persist[b0 : b1 + 1]):
        return (
            (
                f"ROTI up to {stat:.2f} TECU/min over 15 min, improbable under this series' "
                f"multipath (false-alarm probability {opt.false_alarm:g})"
            ),
            stat,
            th,
        )
    return (
        (
            f"ROTI up to {stat:.2f} TECU/min on several satellites in the same 5 min, "
            f"improbable under this series' multipath, which is satellite-specific "
            f"(false-alarm probability {opt.false_alarm:g})"
        ),
        stat,
        th,
    )


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
        f"multipath (false-alarm probability {opt.false_alarm:g})",
        stat,
        opt.roti_threshold_tecu_min,
    )


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
    """Return the excluded span of blocks ``b0..b1`` of one arc, with its reason."""
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
        )
    by_roti = flagged & (bk["named"] != "multipath")
    three = None if ctx["tf"] is None else _three_reason(bk, by_roti, ctx["tf"], opt, b0, b1)
    if three is not None and not np.any(by_roti[b0 : b1 + 1]):
        why, stat, th = three
    else:
        why, stat, th = _iono_reason(bk["roti"], thr, persist, opt, b0, b1)
        why += "" if three is None else three[0]
    if np.any(implaus[b0 : b1 + 1]):  # a disturbance drives the series off limits too
        why += (
            f"; values up to {100 * float(vmax[b0 : b1 + 1].max()):.1f} cm beyond "
            f"the {100 * limit:.1f} cm carrier-multipath limit"
        )
    return ExcludedSpan(sats, t_a, t_b, f"ionosphere: {why}", "ionosphere", stat, th)


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
                )
            )
    return kept, excluded, used
