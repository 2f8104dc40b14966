"""A third carrier beside an arc set's phase pair.

Where a satellite is tracked on a third carrier, its phase lets the
screening tell ionosphere from multipath
(:mod:`psdbound.screening.threefreq`): the first-order ionosphere scales as
``1/f^2`` on every carrier, so one geometry-free combination of three
carriers holds none of it. The arcs stay those of the pair
(:func:`psdbound.arcs.find_arcs`); the third phase is read alongside, at the
arcs' epochs, and nothing else changes.

The third signal is chosen like the pair: from a fixed preference list per
system (:data:`THIRD_SIGNALS`), the first code whose band differs from the
pair's and that the file holds with phases. Its own breaks do not break the
arc: a loss of lock (bit 0 of its indicator) or a cycle slip of the
geometry-free phase ``L_a - L_c`` (the same test as the pair's,
:func:`psdbound.arcs.find.detect_slips`) sets the third phase to NaN at the
first epoch after it, so that no difference of consecutive samples spans one.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from psdbound.arcs.find import Arc, ArcSet, detect_slips
from psdbound.io.obs import Observations
from psdbound.io.signals import RINEX2_TO_RINEX3

__all__ = ["THIRD_SIGNALS", "add_third_carrier", "choose_third_signal", "third_candidates"]

#: Third phase signals per system, in order of preference (RINEX 3 codes; RINEX 2 files are
#: matched through their RINEX 3 names, GPS ``L5`` as ``L5X``). Codes of the pair's bands are
#: skipped, so a pair such as GPS L1C-L5Q takes L2 as its third carrier.
THIRD_SIGNALS: dict[str, tuple[str, ...]] = {
    "G": ("L5Q", "L5X", "L5I", "L2W", "L2L", "L2X", "L2S", "L2C", "L1C", "L1W", "L1X"),
    "E": (
        "L7Q",
        "L7X",
        "L7I",
        "L6C",
        "L6X",
        "L6B",
        "L8Q",
        "L8X",
        "L5Q",
        "L5X",
        "L5I",
        "L1C",
        "L1X",
    ),
    "J": ("L5Q", "L5X", "L5I", "L2L", "L2X", "L2S", "L1C", "L1X"),
    "C": ("L6I", "L6X", "L5P", "L5X", "L1P", "L1X", "L7I", "L2I"),
    "R": ("L3Q", "L3X", "L3I"),
}


def third_candidates(system: str, pair: Sequence[str]) -> tuple[str, ...]:
    """Return the third signals that could go with ``pair``, in order of preference.

    Parameters
    ----------
    system : str
        Satellite system letter.
    pair : sequence of str
        The pair's phase codes (RINEX 2 or 3; only the band digit matters).

    Returns
    -------
    tuple of str
        RINEX 3 phase codes of :data:`THIRD_SIGNALS` on another band.
    """
    bands = {str(c)[1:2] for c in pair}
    return tuple(c for c in THIRD_SIGNALS.get(system, ()) if c[1] not in bands)


def choose_third_signal(obs: Observations, system: str, pair: Sequence[str]) -> str | None:
    """Return the file's code of the preferred third signal that has phases (None: none).

    Parameters
    ----------
    obs : Observations
        The observations the arcs were formed from.
    system : str
        Satellite system letter.
    pair : sequence of str
        The pair's phase codes.

    Returns
    -------
    str or None
        The code as stored in the file (RINEX 2 ``L5`` for ``L5X``).
    """
    if system not in obs.blocks:
        return None
    block = obs.blocks[system]
    for code in third_candidates(system, pair):
        stored = _stored(block.codes, code)
        if stored is None:
            continue
        v = block.values[:, :, block.codes.index(stored)]
        if np.any(np.isfinite(v) & (v != 0)):
            return stored
    return None


def _stored(codes: tuple[str, ...], code: str) -> str | None:
    """Return the file's name of ``code``: itself or its RINEX 2 name (None: absent)."""
    if code in codes:
        return code
    return next((v2 for v2, v3 in RINEX2_TO_RINEX3.items() if v3 == code and v2 in codes), None)


def _third_phase(
    arc: Arc, l3: NDArray[np.float64], lost: NDArray[np.bool_], slip_threshold_m: float
) -> NDArray[np.float64]:
    """Return the third phase of one arc, NaN where missing and after each of its breaks.

    A break is a loss of lock at the epoch, or a slip of ``L_a - L_c`` within
    a run of consecutive samples with a third phase.
    """
    out = np.where(lost, np.nan, l3)
    ok = np.isfinite(out)
    edges = np.flatnonzero(np.diff(np.r_[0, ok.astype(np.int8), 0]))
    gf = arc.phase_m[:, 0] - out
    for r0, r1 in zip(edges[::2], edges[1::2], strict=True):
        if r1 - r0 >= 3:
            out[r0:r1][detect_slips(gf[r0:r1], slip_threshold_m)] = np.nan
    return out


def add_third_carrier(
    arcs: ArcSet, obs: Observations, signal: str | None = None, *, slip_threshold_m: float = 0.04
) -> ArcSet:
    """Return the arcs with the phase of a third signal (``Arc.third_m``), where there is one.

    Parameters
    ----------
    arcs : ArcSet
        Arcs of a phase pair from :func:`psdbound.arcs.find_arcs` on ``obs``.
    obs : Observations
        The observations the arcs were formed from.
    signal : str, optional
        The third phase code; by default the first of :data:`THIRD_SIGNALS`
        on another band than the pair's that the file holds.
    slip_threshold_m : float, default 0.04
        Jump of ``L_a - L_c`` (metres) beyond the local rate that counts as a
        slip of the third phase.

    Returns
    -------
    ArcSet
        ``arcs`` unchanged when there is no third signal; else every arc with
        ``third_m`` (all NaN where the satellite has no third phase) and
        ``third_signal`` set.
    """
    code = (
        choose_third_signal(obs, arcs.system, arcs.signals)
        if signal is None
        else (obs.resolve_code(arcs.system, signal))
    )
    if code is None or not arcs.arcs:
        return arcs
    block = obs.blocks[arcs.system]
    k = block.codes.index(code)
    out = []
    for a in arcs:
        i = block.sats.index(a.sat)
        l3 = obs.phase_m(a.sat, code)[a.epoch_index]
        lli = block.lli[a.epoch_index, i, k]
        lost = (lli > 0) & (lli & 1 > 0)
        out.append(replace(a, third_m=_third_phase(a, l3, lost, slip_threshold_m)))
    return replace(arcs, arcs=tuple(out), third_signal=code)
