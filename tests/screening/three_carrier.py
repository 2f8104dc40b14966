"""Synthetic three-carrier (GPS L1/L2/L5) series for the three-frequency screening tests.

Each carrier's multipath is its own Gauss-Markov process plus white noise,
scaled up at low elevation; the ionosphere is one slant TEC for all carriers,
advancing the phase by ``40.3 STEC / f^2``; a disturbance is a random walk of
TEC whose 30-s increments have the standard deviation ``0.5 ROTI`` (ROT at
30 s has the standard deviation ROTI), as in :mod:`psdbound.simulate`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.signal import lfilter

from psdbound.isolation import MultipathSeries
from psdbound.isolation.dual_frequency import DF_SCALING

F1, F2, F5 = 1575.42e6, 1227.60e6, 1176.45e6
DT = 30.0
T0 = 1.3e9


@dataclass(frozen=True)
class Disturbance:
    """A TEC random walk on some arcs: start and length (s), ROTI (TECU/min), arcs hit."""

    start_s: float
    duration_s: float
    roti_tecu_min: float
    arcs: tuple[int, ...]


@dataclass(frozen=True)
class Burst:
    """Multipath ``factor`` times stronger on every carrier of one arc for a while (s)."""

    arc: int
    start_s: float
    duration_s: float
    factor: float


def _gm(n: int, sigma: float, tau: float, rng: np.random.Generator, k: int) -> np.ndarray:
    a = np.exp(-DT / tau)
    e = rng.normal(0.0, sigma * np.sqrt(1 - a * a), (n, k))
    x = lfilter([1.0], [1.0, -a], e, axis=0)
    return x + (a ** np.arange(1, n + 1))[:, None] * rng.normal(0.0, sigma, k)


def _elevation(n: int, peak_deg: float) -> np.ndarray:
    return 10.0 + (peak_deg - 10.0) * np.sin(np.pi * (np.arange(n) + 0.5) / n)


def three_carrier_series(
    seed: int,
    *,
    n_arcs: int = 24,
    hours: float = 4.0,
    sigma_m: float = 0.003,
    tau_s: float = 30.0,
    wn_m: float = 0.0005,
    disturbances: tuple[Disturbance, ...] = (),
    bursts: tuple[Burst, ...] = (),
    third: bool = True,
    span_h: float = 20.0,
) -> MultipathSeries:
    """Return a DF series of ``n_arcs`` GPS arcs with L1-L2 and (``third``) L1-L5 unfiltered.

    Arcs of ``hours`` start at staggered times over ``span_h`` hours, rise to
    30-85 deg; multipath ``sigma_m`` (x up to 3 below 30 deg) per carrier.
    """
    rng = np.random.default_rng(seed)
    n = int(hours * 3600 / DT)
    out = []
    for k in range(n_arcs):
        t0 = T0 + (span_h - hours) * 3600 * k / max(1, n_arcs - 1)
        t = t0 + DT * np.arange(n)
        el = _elevation(n, rng.uniform(30.0, 85.0))
        scale = 1.0 + 2.0 * np.exp(-((el - 10.0) ** 2) / (2 * 15.0**2))
        mp = scale[:, None] * (_gm(n, sigma_m, tau_s, rng, 3) + rng.normal(0, wn_m, (n, 3)))
        for b in bursts:
            if b.arc == k:
                on = (t - T0 >= b.start_s) & (t - T0 < b.start_s + b.duration_s)
                mp[on] *= b.factor
        stec = 20.0 / np.sin(np.radians(el + 10.0))
        for d in disturbances:
            if k in d.arcs:
                on = (t - T0 >= d.start_s) & (t - T0 < d.start_s + d.duration_s)
                stec = stec + np.cumsum(np.where(on, rng.normal(0, 0.5 * d.roti_tecu_min, n), 0))
        phase = -40.3e16 * stec[:, None] / np.array([F1, F2, F5]) ** 2 + mp
        gf12, gf15 = phase[:, 0] - phase[:, 1], phase[:, 0] - phase[:, 2]
        arc = {
            "sats": f"G{k + 1:02d}",
            "t_gps_s": t,
            "elevation_deg": el,
            "value_m": DF_SCALING * (mp[:, 0] - mp[:, 1]),
            "unfiltered_m": gf12 - gf12.mean(),
        }
        if third:
            arc["third_m"] = gf15 - gf15.mean()
        out.append(arc)
    return MultipathSeries.from_arcs(
        "DF",
        out,
        signals=("L1C", "L2W"),
        scaling=DF_SCALING,
        interval_s=DT,
        cutoff_hz=1e-3,
        third_signal="L5Q" if third else None,
    )


def disturbed_blocks(series: MultipathSeries, d: Disturbance) -> int:
    """Number of 5-min blocks of the disturbed arcs that lie wholly inside the disturbance."""
    n = 0
    for k in d.arcs:
        t = series.arc(k).t_gps_s - T0
        starts = t[0] + 300.0 * np.arange(int((t[-1] - t[0]) // 300))
        n += int(((starts >= d.start_s) & (starts + 300 <= d.start_s + d.duration_s)).sum())
    return n
