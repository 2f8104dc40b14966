"""The single-block ROTI test as stated, and as measured on the day's own blocks.

The threshold of a block is the larger of the ionospheric significance level
and the multipath null's ``1 - p`` quantile (:mod:`psdbound.screening.null`).
The probability the null gives to exceeding it is an extrapolation of a
chi-square fitted to the lower quantiles; on real quiet days the far tail is
heavier (ZIMM 2021-01-01..03: 1-5 % of the blocks below 20 deg exceed a
quantile stated at 2.5e-4; ESBC: 1-3 % at every elevation). So the test is
also measured: along elevation, the share of the day's blocks above their
threshold, with a one-sided Clopper-Pearson upper limit
(:func:`psdbound.screening.null.local_exceedance`). That limit holds whatever
the null's shape. Where the measured rate is surely an order of magnitude
above the stated probability and the null's quantile sets the threshold, a
note says so: the screen then cuts more multipath than it states (or weak
ionosphere below the significance level is present; one day cannot tell).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import stats

from psdbound.screening.null import MultipathNull, local_exceedance

__all__ = ["block_test", "tail_note"]

#: One-sided level of the measured exceedance's limits.
LEVEL = 0.95
#: A note needs the measured rate above this many times the stated one (on synthetic
#: multipath nulls the realised rate is 0.3-2.4 times the stated: screening.null).
NOTE_FACTOR = 10.0


def block_test(
    null: MultipathNull | None,
    threshold: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    blocks: list[dict[str, Any]],
    share: float,
    significance_tecu_min: float,
) -> dict[str, Any] | None:
    """Return the single-block test along the null's elevations, stated and measured.

    Parameters
    ----------
    null : MultipathNull or None
        The series' multipath null (None: the fixed threshold, no probability).
    threshold : callable
        Elevation (deg) -> the threshold applied there, TECU/min.
    blocks : list of dict
        Per arc, its 5-min blocks (``roti``, TECU/min; ``el``, deg).
    share : float
        The block test's false-alarm probability (its share of the stated one).
    significance_tecu_min : float
        The ionospheric significance level, TECU/min.

    Returns
    -------
    dict or None
        ``elevation_deg`` (the null's grid, deg), ``threshold_tecu_min``,
        ``false_alarm`` (``share``), ``false_alarm_at_threshold`` (under the
        fitted null), ``by_significance`` (whether the significance level
        sets the threshold), ``null_trusted`` (:attr:`MultipathNull.trusted`)
        and ``measured``: ``elevation_deg``,
        ``exceeded`` and ``blocks`` per local window of the day's blocks,
        ``upper`` (the Clopper-Pearson upper limit of their exceedance) and
        ``by_significance`` there.
    """
    if null is None:
        return None
    el = null.elevation_deg
    thr = threshold(el)
    out: dict[str, Any] = {
        "elevation_deg": el,
        "threshold_tecu_min": thr,
        "false_alarm": share,
        "false_alarm_at_threshold": null.exceedance(thr, el),
        "by_significance": thr <= significance_tecu_min,
        "null_trusted": null.trusted,
        "measured": None,
    }
    roti = np.concatenate([b["roti"] for b in blocks]) if blocks else np.zeros(0)
    b_el = np.concatenate([b["el"] for b in blocks]) if blocks else np.zeros(0)
    ok = np.isfinite(roti) & (roti > 0) & np.isfinite(b_el)  # the blocks the null was fitted on
    b_thr = threshold(b_el[ok])
    measured = local_exceedance(roti[ok] > b_thr, b_el[ok], confidence_level=LEVEL)
    if measured is not None:
        measured["by_significance"] = threshold(measured["elevation_deg"]) <= significance_tecu_min
        out["measured"] = measured
    return out


def tail_note(test: dict[str, Any] | None) -> str | None:
    """Return a note where the day's blocks exceed the null's quantile far more often than stated.

    Where the null is trusted (a quiet day: on a disturbed one the
    exceedances are its ionosphere), the null's quantile sets the threshold
    and the one-sided Clopper-Pearson *lower* limit of the measured
    exceedance (at ``LEVEL``, Bonferroni over the windows) lies above
    :data:`NOTE_FACTOR` times the stated probability; None otherwise. On
    simulated multipath that the null describes, 1 day in 20 or fewer gets
    the note (``tests/screening/test_blocktest.py``).
    """
    m = (test or {}).get("measured")
    if not m or not test["null_trusted"]:  # type: ignore[index]
        return None  # a disturbed day: exceedances are its ionosphere, not false alarms
    k, n, p = m["exceeded"], m["blocks"], float(test["false_alarm"])  # type: ignore[index]
    alpha = (1.0 - LEVEL) / k.size
    lower = np.where(k > 0, stats.beta.ppf(alpha, np.maximum(k, 1.0), n - k + 1.0), 0.0)
    bad = (lower > NOTE_FACTOR * p) & ~m["by_significance"]
    if not bad.any():
        return None
    el = np.round(m["elevation_deg"][bad])
    where = (
        f"at {el[0]:.0f} deg" if el.min() == el.max() else f"at {el.min():.0f}-{el.max():.0f} deg"
    )
    return (
        f"the single-block ROTI test states a false-alarm probability of {p:.2g} per block, "
        f"but {where} elevation "
        f"{int(k[bad].max())} of {int(n[bad][np.argmax(k[bad])])} of the day's blocks exceed "
        f"the null's quantile (up to {m['upper'][bad].max():.2g} at {100 * LEVEL:g} %): "
        "multipath's tail there is heavier than the null fitted to its lower quantiles, or "
        "weak ionosphere is present; up to that share of the multipath there may be cut "
        "(screening.block_test.measured)"
    )
