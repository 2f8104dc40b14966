"""Welch PSD estimate: averaged modified periodograms of overlapping segments.

A thin layer over :func:`scipy.signal.welch` (Hann window, 50 % overlap,
constant detrend per segment, one-sided density scaling) that chooses the
segment length and records the equivalent degrees of freedom.

Default segment length: ``nperseg = min(N, max(64, 2**floor(log2(N / 8))))``,
i.e. the largest power of two giving at least about 8 segments before
overlap (about 15 with 50 % overlap), but never shorter than 64 samples.

Equivalent degrees of freedom, computed exactly from the window (Percival &
Walden 1993, eq. 292b; Welch 1967)::

    nu = 2 K / (1 + 2 sum_{m=1}^{K-1} (1 - m/K) rho_m),
    rho_m = (sum_t h_t h_{t+mS})^2 / (sum_t h_t^2)^2

for ``K`` segments shifted by ``S`` samples. For Hann with 50 % overlap
``sqrt(rho_1) = 1/6 ~ 0.167``, ``rho_m = 0`` for ``m > 1``, so
``nu = 36 K^2 / (19 K - 1) ~ 1.89 K``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import signal

from psdbound.errors import InputError

__all__ = ["welch", "default_nperseg", "welch_dof"]


def default_nperseg(n: int) -> int:
    """Default segment length ``min(n, max(64, 2**floor(log2(n / 8))))``, samples."""
    return int(min(n, max(64, 2 ** int(np.floor(np.log2(max(n, 1) / 8.0))))))


def welch_dof(window: NDArray[np.float64], n_segments: int, step: int) -> float:
    """Equivalent degrees of freedom of Welch's estimate (Percival & Walden eq. 292b).

    Parameters
    ----------
    window : ndarray
        Data taper applied to each segment.
    n_segments : int
        Number of segments ``K``.
    step : int
        Shift between consecutive segments ``S``, samples.

    Returns
    -------
    float
        ``nu``; ``2 K`` without overlap.
    """
    h = np.asarray(window, dtype=float)
    energy = np.sum(h**2)
    total = 0.0
    for m in range(1, n_segments):
        shift = m * step
        if shift >= h.size:
            break
        rho = (np.dot(h[: h.size - shift], h[shift:]) / energy) ** 2
        total += (1.0 - m / n_segments) * rho
    return float(2.0 * n_segments / (1.0 + 2.0 * total))


def welch(
    x: NDArray[np.float64],
    dt_s: float,
    *,
    nperseg: int | None = None,
    noverlap: int | None = None,
    window: str | tuple[Any, ...] = "hann",
    detrend: str | bool = "constant",
    nfft: int | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], float, dict[str, Any]]:
    """One-sided Welch PSD.

    Parameters
    ----------
    x : ndarray
        Finite samples, metres (1-D).
    dt_s : float
        Sampling interval, seconds.
    nperseg : int, optional
        Segment length, samples (``2 <= nperseg <= N``); default
        :func:`default_nperseg`.
    noverlap : int, optional
        Overlap between segments, samples (``0 <= noverlap < nperseg``);
        default ``nperseg // 2``.
    window : str or tuple, default "hann"
        Segment taper, as accepted by :func:`scipy.signal.get_window`
        (periodic form).
    detrend : {"constant", "linear", False}, default "constant"
        Per-segment detrending.
    nfft : int, optional
        FFT length per segment (``>= nperseg``); default ``nperseg``.

    Returns
    -------
    f_hz : ndarray
        Frequencies ``0 .. f_N``, Hz.
    psd_m2_hz : ndarray
        One-sided PSD, m^2/Hz.
    dof : float
        Equivalent degrees of freedom (:func:`welch_dof`).
    params : dict
        ``nperseg``, ``noverlap``, ``n_segments``, ``window``, ``detrend``,
        ``nfft``.
    """
    n = x.size
    nperseg = default_nperseg(n) if nperseg is None else int(nperseg)
    if not 2 <= nperseg <= n:
        raise InputError(f"nperseg must lie in [2, {n}] (the number of samples), got {nperseg}")
    noverlap = nperseg // 2 if noverlap is None else int(noverlap)
    if not 0 <= noverlap < nperseg:
        raise InputError(f"noverlap must lie in [0, nperseg) = [0, {nperseg}), got {noverlap}")
    nfft = nperseg if nfft is None else int(nfft)
    if nfft < nperseg:
        raise InputError(f"nfft must be at least nperseg = {nperseg}, got {nfft}")
    if detrend not in ("constant", "linear", False):
        raise InputError(f"detrend must be 'constant', 'linear' or False, got {detrend!r}")
    try:
        win = signal.get_window(window, nperseg)
    except ValueError as exc:
        raise InputError(f"unusable Welch window {window!r}: {exc}") from None

    f_hz, psd = signal.welch(
        x,
        fs=1.0 / dt_s,
        window=win,
        nperseg=nperseg,
        noverlap=noverlap,
        nfft=nfft,
        detrend=detrend,
        return_onesided=True,
        scaling="density",
    )
    step = nperseg - noverlap
    n_segments = 1 + (n - nperseg) // step
    dof = welch_dof(win, n_segments, step)
    params: dict[str, Any] = {
        "nperseg": nperseg,
        "noverlap": noverlap,
        "n_segments": n_segments,
        "window": window,
        "detrend": detrend,
        "nfft": nfft,
    }
    return f_hz, psd, dof, params
