"""Dual-frequency (DF) multipath isolation (docs/method/isolation.rst).

For each continuous arc of a satellite tracked on two carriers ``a`` and
``b`` (phases in metres),

    d = L_a - L_b = -(I_a - I_b) + (ambiguity terms) + (nu_a - nu_b),

the ambiguity terms are constant over the arc and removed with the arc
mean; the ionospheric term, slower than multipath, is removed by a zero-phase
high-pass filter at ``cutoff_hz``; what is left is the difference of two
independent per-carrier multipath + noise terms, divided by sqrt(2) to
compare with one signal (thesis appendix B).

Where the arcs carry a third carrier ``c`` (:func:`psdbound.arcs.add_third_carrier`),
``L_a - L_c`` is kept unfiltered beside ``L_a - L_b`` (``MultipathSeries.third_m``)
for the three-frequency screening test; the isolated series itself is unchanged.
"""

from __future__ import annotations

import numpy as np

from psdbound.arcs.find import ArcSet
from psdbound.errors import NoDataError
from psdbound.isolation.filters import HighPass
from psdbound.isolation.series import MultipathSeries

__all__ = ["isolate_dual_frequency", "DF_SCALING"]

#: DF difference -> one-signal multipath: 1/sqrt(2).
DF_SCALING = 1.0 / np.sqrt(2.0)


def isolate_dual_frequency(
    arcs: ArcSet,
    cutoff_hz: float,
    *,
    highpass: HighPass | None = None,
    min_length_s: float = 600.0,
) -> MultipathSeries:
    """Isolate carrier-phase multipath from dual-frequency arcs.

    Parameters
    ----------
    arcs : ArcSet
        Arcs of one system and signal pair from :func:`psdbound.arcs.find_arcs`,
        preferably with elevations (an orbit given to ``find_arcs``).
    cutoff_hz : float
        High-pass cutoff frequency, Hz (e.g. 9.55e-4 Hz, the thesis's
        Chicago 2020 value).
    highpass : HighPass, optional
        Filter design and edge handling; default 4th-order Butterworth,
        zero-phase, odd padding, ``1/f_c`` trimmed at each end.
    min_length_s : float, default 600
        Minimum arc duration after edge trimming, seconds. (Arcs entering
        already passed the ``find_arcs`` minimum; trimming removes ``1/f_c``
        at each end, about 17.5 min at the thesis cutoff.)

    Returns
    -------
    MultipathSeries
        ``method="DF"``, values scaled by 1/sqrt(2), with the unfiltered
        mean-removed difference kept in ``unfiltered_m`` for safety checks.

    Raises
    ------
    NoDataError
        If no arc is long enough (the message gives the counts).
    InputError
        For a cutoff outside (0, Nyquist).

    See Also
    --------
    isolate_dual_antenna : The double-difference alternative for two antennas.
    HighPass : The zero-phase high-pass designs.
    filter_safety_check : How much power the filter removed below and above f_c.

    References
    ----------
    .. [1] Benz, C. (2022). *Carrier Phase Multipath Characterization and
       Frequency-Domain Bounding*. M.S. thesis, Illinois Institute of Technology
       (the method psdbound started from; docs/method/index.rst says where it differs).
    .. [2] docs/method/isolation.rst (scaling, filter, edges).

    Examples
    --------
    >>> from psdbound.arcs import find_arcs
    >>> from psdbound.io import read_obs, read_orbit
    >>> from psdbound.simulate import demo_data
    >>> d = demo_data()
    >>> arcs = find_arcs(read_obs(d.obs_paths[0], systems="G"), ("L1C", "L2W"),
    ...                  orbit=read_orbit(d.nav_path))
    >>> series = isolate_dual_frequency(arcs, 1.5e-3)
    >>> series.method, round(series.scaling, 4)
    ('DF', 0.7071)
    """
    hp = HighPass() if highpass is None else highpass
    interval_s = arcs.interval_s
    min_len = min_length_s
    if len(arcs) == 0:
        if not arcs.dropped:
            # no satellite on both signals, or none above the mask / with an orbit
            raise NoDataError(arcs.empty_reason(), path=arcs.path)
        raise NoDataError(
            f"no arc long enough: all {sum(arcs.dropped.values())} tracking stretches of "
            f"{arcs.system} {arcs.signals[0]}-{arcs.signals[1]} are shorter than "
            f"{arcs.min_length_s / 60:g} min",
            path=arcs.path,
        )
    hp.check_cutoff(cutoff_hz, interval_s)
    third = arcs.third_signal is not None
    out = []
    too_short = 0
    for arc in arcs:
        d = arc.geometry_free_m
        d = d - d.mean()
        y, keep = hp.apply(d, interval_s, cutoff_hz)
        t = arc.t_gps_s[keep]
        if t.size < 2 or t[-1] - t[0] < min_len:
            too_short += 1
            continue
        el = np.full(t.size, np.nan) if arc.elevation_deg is None else arc.elevation_deg[keep]
        out.append(
            {
                "sats": arc.sat,
                "t_gps_s": t,
                "value_m": DF_SCALING * y[keep],
                "elevation_deg": el,
                "unfiltered_m": d[keep],
            }
        )
        if third:
            out[-1]["third_m"] = _third_gf(arc.phase_m[:, 0], arc.third_m)[keep]
    if not out:
        raise NoDataError(
            f"no arc long enough after trimming filter edges ({too_short} arcs shorter than "
            f"{min_len / 60:g} min)",
            path=arcs.path,
        )
    meta = {
        "source": arcs.path,
        "system": arcs.system,
        "filter": hp.describe(interval_s, cutoff_hz),
        "arcs_in": len(arcs),
        "arcs_dropped_after_trim": too_short,
        "arc_breaks": dict(arcs.breaks),
        "stretches_dropped_short": int(sum(arcs.dropped.values())),
        "has_elevation": all(a.elevation_deg is not None for a in arcs),
        "scaling_note": "DF difference divided by sqrt(2): two independent per-carrier terms",
    }
    if third:
        meta["third_signal"] = arcs.third_signal
        meta["arcs_with_third"] = sum(bool(np.isfinite(a["third_m"]).any()) for a in out)
    return MultipathSeries.from_arcs(
        "DF",
        out,
        signals=arcs.signals,
        scaling=float(DF_SCALING),
        interval_s=interval_s,
        cutoff_hz=cutoff_hz,
        meta=meta,
        third_signal=arcs.third_signal,
    )


def _third_gf(l_a: np.ndarray, l_c: np.ndarray | None) -> np.ndarray:
    """``L_a - L_c`` of one arc with its mean removed, metres (all NaN without a third phase)."""
    if l_c is None or not np.isfinite(l_c).any():
        return np.full(l_a.size, np.nan)
    g = l_a - l_c
    return g - np.nanmean(g)
