"""Coherence across satellites: a disturbance moves through several lines of sight at once.

Multipath is satellite-specific: each line of sight has its own reflection
geometry, so under multipath alone the blocks of different satellites are
independent, each ``nu ROTI^2 / s^2(el)`` a chi-square with ``nu`` degrees of
freedom (the multipath null, :mod:`psdbound.screening.null`). An ionospheric
disturbance (a travelling disturbance, auroral or equatorial irregularities)
covers a region of the sky and is seen on several satellites in the same
minutes. The satellites' scaled ``ROTI^2`` summed over one 5-min time slot
is then, under multipath alone, a chi-square with ``k nu`` degrees of freedom
for ``k`` satellites; a slot above its ``1 - p`` quantile holds a disturbance
common to the satellites, even when no satellite's block crosses its own
threshold (the per-block test must hold ``p`` for every block of every
satellite; the slot test pools the evidence of ``k`` lines of sight).

In a significant slot the satellites that carry the excess are flagged, and
only they: the largest blocks are taken out one at a time, largest first,
until the rest of the slot is consistent with multipath alone at the
conventional 10 % level (:data:`REST_LEVEL`: its sum below the chi-square's
90th percentile for the satellites left); those taken out whose ROTI also
exceeds the ionospheric significance are flagged. The level trades the
disturbed blocks found against quiet satellites carried along. Measured
(``tests/screening/test_coherence.py``: 0.16 TECU/min for 30 min on 5 of 10
satellites at 10-14 deg, 12 seeds, share of the disturbed blocks found;
``benchmarks/screening.py``, 0.3 TECU/min for 60 min on 6 satellites at
30-74 deg: ionosphere spans touching no disturbed satellite, 1 without the
slot test, and the bound's change from the clean day): taking out until the
rest lies below its quantile at ``p`` finds 33-53 %; at 5 %, 60-93 %, 3
spans, 3.0 %; at 10 %, 70-97 %, 3 spans, 3.0 %; at 25 % (the null's upper
quartile, the persistence test's member rule), 87-100 %, 11 spans, 6.6 %.

This is the network analogue of the ROTI maps' use of many receivers
(Cherniak et al., 2018) applied to the lines of sight of one receiver; the
combination of independent chi-square statistics under the null is exact,
so the false-alarm probability per slot is the stated one as far as the
null's shape is (``tests/screening/test_coherence.py``).

References
----------
Cherniak, I., Krankowski, A., Zakharenkova, I. (2018). ROTI maps: a new IGS
ionospheric product characterizing the ionospheric irregularities
occurrence. GPS Solutions 22, 69.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray
from scipy import stats

from psdbound.screening.null import MultipathNull
from psdbound.screening.rot import ROTI_BLOCK_S

__all__ = ["MIN_SATELLITES", "REST_LEVEL", "coherent_blocks"]

#: Fewest satellites in a slot for the slot test (one satellite is the per-block test).
MIN_SATELLITES = 2
#: Level at which the rest of a significant slot is consistent with multipath alone (the
#: satellites that carry the excess are taken out until it is).
REST_LEVEL = 0.1


def _slots(mid_gps_s: NDArray[np.float64], slot_s: float) -> NDArray[np.int64]:
    """Index of the common time slot of each block (by its mid-time)."""
    return np.floor(mid_gps_s / slot_s).astype(np.int64)


def coherent_blocks(
    mid_gps_s: Sequence[NDArray[np.float64]],
    roti_tecu_min: Sequence[NDArray[np.float64]],
    elevation_deg: Sequence[NDArray[np.float64]],
    null: MultipathNull,
    *,
    false_alarm: float,
    floor_tecu_min: float = 0.0,
    slot_s: float = ROTI_BLOCK_S,
) -> list[NDArray[np.bool_]]:
    """Flag the blocks of time slots whose ROTI, over all satellites, is improbable.

    Parameters
    ----------
    mid_gps_s, roti_tecu_min, elevation_deg : sequence of ndarray
        Per arc (one satellite or pair each), its blocks' mid-times (GPS s),
        ROTI (TECU/min, NaN: no estimate) and mean elevation (degrees).
    null : MultipathNull
        The ROTI of multipath alone.
    false_alarm : float
        False-alarm probability per slot under multipath alone.
    floor_tecu_min : float, default 0
        Smallest ROTI of a flagged block (the ionospheric significance).
    slot_s : float, default 300
        Length of the common time slots, s.

    Returns
    -------
    list of ndarray of bool
        Per arc, the flagged blocks.
    """
    out = [np.zeros(np.size(r), bool) for r in roti_tecu_min]
    if not out:
        return out
    arc = np.concatenate([np.full(np.size(r), k) for k, r in enumerate(roti_tecu_min)])
    pos = np.concatenate([np.arange(np.size(r)) for r in roti_tecu_min])
    r = np.concatenate([np.asarray(x, dtype=float) for x in roti_tecu_min])
    el = np.concatenate([np.asarray(x, dtype=float) for x in elevation_deg])
    slot = _slots(np.concatenate([np.asarray(x, dtype=float) for x in mid_gps_s]), slot_s)
    ok = np.isfinite(r) & np.isfinite(el) & (r > 0)
    arc, pos, r, el, slot = arc[ok], pos[ok], r[ok], el[ok], slot[ok]
    z = null.dof * r**2 / null.scale2(el)  # chi-square with nu dof under the null
    ids, inv, k = np.unique(slot, return_inverse=True, return_counts=True)
    total = np.bincount(inv, weights=z, minlength=ids.size)
    crit = np.where(k >= MIN_SATELLITES, stats.chi2.isf(false_alarm, k * null.dof), np.inf)
    for g in np.flatnonzero(total > crit):
        members = np.flatnonzero(inv == g)
        for i in _carriers(z[members], null.dof):
            b = members[i]
            if r[b] > floor_tecu_min:
                out[arc[b]][pos[b]] = True
    return out


def _carriers(z: NDArray[np.float64], dof: float) -> NDArray[np.int64]:
    """Return the largest ``z`` (indices) whose removal leaves the rest of a slot typical."""
    order = np.argsort(z)[::-1]
    rest = np.cumsum(z[order][::-1])[::-1]  # sum of z[order][i:]
    left = z.size - np.arange(z.size)  # satellites in that rest
    significant = rest > stats.chi2.isf(REST_LEVEL, left * dof)
    n_out = int(np.argmin(significant)) if not significant.all() else z.size
    return order[:n_out]
