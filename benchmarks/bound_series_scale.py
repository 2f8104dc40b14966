"""Benchmark: ``psdbound.bound_series`` on long stretches and many windows.

A user outside GNSS hands over one long stretch (a day of a 1 Hz error, three
hours at 10 Hz) or many windows of unequal length. Before the lag kernels of
the multitaper expectation took closed forms
(:mod:`psdbound.spectra.expectation`), one day at 1 Hz in one stretch took
109 s on this machine (2 shared cores), the kernels' sum over every
ordinate of a band being O(J N).

Each case is simulated (GM 3 mm / 30 s + white 1 mm, seeded) and timed once,
in this process, after a warm-up call (imports excluded). The kernels of one
window length are also timed side by side with their definition (a
zero-padded FFT autocorrelation of every tapered, mean-removed complex
exponential of a band, as ``tests/spectra/test_expectation.py`` builds
them). Last line: ``RESULT day_1hz_s=... three_h_10hz_s=...
unequal_100_s=... kernels_s=... kernels_by_definition_s=... kernels_speedup=...``.
"""

from __future__ import annotations

import time

import numpy as np
from scipy.signal import lfilter, windows

import psdbound
from psdbound.spectra.expectation import far_lag_kernels, lag_kernels


def _gm(rng: np.random.Generator, n: int, dt_s: float, tau_s: float = 30.0) -> np.ndarray:
    phi = np.exp(-dt_s / tau_s)
    e = rng.normal(0.0, 0.003 * np.sqrt(1.0 - phi**2), n)
    e[0] = rng.normal(0.0, 0.003)
    return lfilter([1.0], [1.0, -phi], e) + rng.normal(0.0, 0.001, n)


def _timed(series: list[np.ndarray], dt_s: float) -> float:
    t0 = time.perf_counter()
    psdbound.bound_series(series, dt_s)
    return time.perf_counter() - t0


def _kernels_by_definition(n: int, lo: np.ndarray, hi: np.ndarray, nw: float) -> None:
    tapers = windows.dpss(n, nw, Kmax=int(np.floor(2.0 * nw)) - 1)
    t = np.arange(n)
    j_all = np.arange(1, n // 2 + 1)
    for a, b in zip(lo, hi, strict=True):
        for j in j_all[(j_all / n >= a) & (j_all / n < b)]:
            for h in tapers:
                x = h * np.exp(-2j * np.pi * j * t / n)
                x -= x.mean()
                np.fft.ifft(np.abs(np.fft.fft(x, 2 * n)) ** 2)


def main() -> int:
    rng = np.random.default_rng(7)
    psdbound.bound_series([_gm(rng, 600, 1.0) for _ in range(4)], 1.0)  # warm-up
    day = _timed([_gm(rng, 86_400, 1.0)], 1.0)
    fast = _timed([_gm(rng, 108_000, 0.1, tau_s=5.0)], 0.1)
    unequal = _timed([_gm(rng, int(n), 1.0) for n in rng.integers(1000, 7200, 100)], 1.0)
    n, nw = 3600, 4.0
    edges = np.geomspace(nw / n, 0.5, 31)
    low = edges[:-1] < 12.0 * nw / n
    t0 = time.perf_counter()
    lag_kernels(n, 1.0, edges[:-1][low], edges[1:][low], nw=nw)
    far_lag_kernels(n, 1.0, edges[:-1][~low], edges[1:][~low], nw=nw)
    ours = time.perf_counter() - t0
    t0 = time.perf_counter()
    _kernels_by_definition(n, edges[:-1], edges[1:], nw)
    ref = time.perf_counter() - t0
    print(
        f"RESULT day_1hz_s={day:.2f} three_h_10hz_s={fast:.2f} unequal_100_s={unequal:.2f} "
        f"kernels_s={ours:.3f} kernels_by_definition_s={ref:.2f} kernels_speedup={ref / ours:.0f}"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
