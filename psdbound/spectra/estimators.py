"""PSD estimates of a multipath series: Blackman-Tukey, Welch and multitaper.

:func:`estimate_psd` dispatches to one algorithm per private module and
returns a :class:`PSDEstimate`: a one-sided, per-hertz PSD on ``0 < f <= f_N``
(the conventions of :mod:`psdbound.spectra.models`), with equivalent degrees
of freedom for chi-square confidence intervals.

``"blackman-tukey"`` (default)
    The thesis's estimate (docs/method/spectra.rst): Fourier transform of the
    biased sample ACF times a Tukey lag window flat over 80 % of the lags.
    Options ``max_lag_fraction`` (default 1.0: every lag), ``alpha`` (0.2),
    ``nfft``. With every lag the degrees of freedom are ~1.1 and the
    confidence intervals very wide; values can be negative (counted in
    ``params["n_negative"]``).
``"welch"``
    :func:`scipy.signal.welch`, Hann, 50 % overlap. Options ``nperseg``,
    ``noverlap``, ``window``, ``detrend``, ``nfft``.
``"multitaper"``
    Thomson's DPSS multitaper. Options ``nw`` (4), ``k`` (``2 nw - 1``),
    ``adaptive`` (False), ``nfft``.

The degrees of freedom hold for frequencies more than a resolution bandwidth
away from 0 and ``f_N``; at ``f_N`` itself (included when the FFT length is
even) the estimate has about half as many.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import stats

from psdbound.errors import InputError
from psdbound.spectra._blackman_tukey import blackman_tukey
from psdbound.spectra._multitaper import multitaper
from psdbound.spectra._welch import welch
from psdbound.spectra.names import METHODS

__all__ = ["PSDEstimate", "estimate_psd", "real_samples", "METHODS", "MIN_SAMPLES"]


MIN_SAMPLES = 16
"""Fewest samples :func:`estimate_psd` accepts."""

_IMPLEMENTATIONS: dict[str, Callable[..., Any]] = {
    "blackman-tukey": blackman_tukey,
    "welch": welch,
    "multitaper": multitaper,
}


@dataclass(frozen=True, eq=False)
class PSDEstimate:
    """A one-sided PSD estimate with its degrees of freedom.

    Parameters
    ----------
    f_hz : ndarray
        Frequencies, Hz, increasing, ``0 < f <= f_N``.
    psd_m2_hz : ndarray
        One-sided PSD, m^2/Hz: its integral over ``[0, f_N]`` is the
        variance. Blackman-Tukey values may be negative.
    dof : float or ndarray
        Equivalent degrees of freedom ``nu`` of the chi-square approximation
        ``nu S_hat / S ~ chi2(nu)``: one value, or one per frequency.
    method : str
        One of :data:`METHODS`.
    params : dict
        The options actually used (defaults resolved) and diagnostics.
    dt_s : float
        Sampling interval, seconds.
    n_samples : int
        Number of samples estimated from.

    Notes
    -----
    The arrays are made read-only. Instances compare by identity.
    """

    f_hz: NDArray[np.float64]
    psd_m2_hz: NDArray[np.float64]
    dof: float | NDArray[np.float64]
    method: str
    params: dict[str, Any] = field(default_factory=dict)
    dt_s: float = 1.0
    n_samples: int = 0

    def __post_init__(self) -> None:
        f = np.array(self.f_hz, dtype=float)
        psd = np.array(self.psd_m2_hz, dtype=float)
        if f.ndim != 1 or f.shape != psd.shape:
            raise InputError(
                f"f_hz and psd_m2_hz must be 1-D of equal length, got {f.shape} and {psd.shape}"
            )
        dof: float | NDArray[np.float64]
        if np.ndim(self.dof) == 0:
            dof = float(self.dof)  # type: ignore[arg-type]
        else:
            dof = np.array(self.dof, dtype=float)
            if dof.shape != f.shape:
                raise InputError(f"dof must be a scalar or match f_hz {f.shape}, got {dof.shape}")
            dof.setflags(write=False)
        if np.any(np.asarray(dof) <= 0.0):
            raise InputError("dof must be positive")
        f.setflags(write=False)
        psd.setflags(write=False)
        object.__setattr__(self, "f_hz", f)
        object.__setattr__(self, "psd_m2_hz", psd)
        object.__setattr__(self, "dof", dof)

    @property
    def nyquist_hz(self) -> float:
        """Nyquist frequency ``1 / (2 dt)``, Hz."""
        return 0.5 / self.dt_s

    def confidence_interval(
        self, level: float = 0.95
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Chi-square confidence interval of the PSD at every frequency.

        Parameters
        ----------
        level : float, default 0.95
            Confidence level, ``0 < level < 1``.

        Returns
        -------
        lower, upper : ndarray
            ``nu S / chi2.ppf(1 - a/2, nu)`` and ``nu S / chi2.ppf(a/2, nu)``,
            ``a = 1 - level``, m^2/Hz. For a negative (Blackman-Tukey)
            estimate the two are swapped so that ``lower <= upper``; such an
            interval lies below zero and only says the estimate is unusable
            there.
        """
        if not 0.0 < level < 1.0:
            raise InputError(f"confidence level must lie in (0, 1), got {level!r}")
        a = 1.0 - level
        nu = np.asarray(self.dof, dtype=float)
        scaled = nu * self.psd_m2_hz
        lo = scaled / stats.chi2.ppf(1.0 - a / 2.0, nu)
        hi = scaled / stats.chi2.ppf(a / 2.0, nu)
        return np.minimum(lo, hi), np.maximum(lo, hi)


def real_samples(x: object, *, name: str = "samples") -> NDArray[np.float64]:
    """Return samples as floats, a masked sample (:mod:`numpy.ma`) as NaN.

    ``numpy.asarray`` would keep a masked sample's value as data and drop an
    imaginary part with a warning only: both are refused or made a gap here.

    Parameters
    ----------
    x : array_like
        Samples (any shape); a masked array's masked samples become NaN.
    name : str, default "samples"
        What the samples are called in the error message (e.g. ``"series 3"``).

    Returns
    -------
    ndarray of float64

    Raises
    ------
    InputError
        Complex or non-numeric samples.
    """
    if np.iscomplexobj(x):
        raise InputError(
            f"{name}: samples must be real numbers, got complex values "
            "(bound the real and imaginary parts as two series)"
        )
    try:
        if np.ma.isMaskedArray(x):
            return np.ma.asarray(x, dtype=float).filled(np.nan)
        return np.asarray(x, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name}: samples must be real numbers ({exc})") from None


def _check_input(x_m: ArrayLike, dt_s: float) -> tuple[NDArray[np.float64], float]:
    x = real_samples(x_m)
    if x.ndim != 1:
        raise InputError(f"samples must be a 1-D series, got shape {x.shape}")
    if x.size < MIN_SAMPLES:
        raise InputError(f"need at least {MIN_SAMPLES} samples for a PSD estimate, got {x.size}")
    bad = ~np.isfinite(x)
    if bad.any():
        raise InputError(
            f"samples contain {int(bad.sum())} NaN, infinite or masked values "
            f"(first at index {int(np.argmax(bad))}); split the series into gap-free windows"
        )
    try:
        dt = float(dt_s)
    except (TypeError, ValueError):
        raise InputError(f"sampling interval must be a number, got {dt_s!r}") from None
    if not (np.isfinite(dt) and dt > 0.0):
        raise InputError(f"sampling interval must be positive and finite, got {dt_s!r} s")
    return x, dt


def estimate_psd(
    x_m: ArrayLike,
    dt_s: float,
    *,
    method: str = "multitaper",
    **options: Any,
) -> PSDEstimate:
    """Estimate the one-sided PSD of an evenly sampled, gap-free series.

    Parameters
    ----------
    x_m : array_like
        Samples, metres (1-D, finite, at least :data:`MIN_SAMPLES`). The
        mean is removed.
    dt_s : float
        Sampling interval, seconds (> 0).
    method : {"multitaper", "welch", "blackman-tukey"}, default "multitaper"
        Estimator (see the module docstring); the default is ``fit``'s.
    **options
        Keyword options of the chosen estimator:

        * blackman-tukey: ``max_lag_fraction`` (float, 1.0), ``alpha``
          (float, 0.2), ``nfft`` (int, next power of two >= 2M + 1);
        * welch: ``nperseg`` (int, ``min(N, max(64, 2**floor(log2(N/8))))``),
          ``noverlap`` (int, ``nperseg // 2``), ``window`` ("hann"),
          ``detrend`` ("constant"), ``nfft`` (int, ``nperseg``);
        * multitaper: ``nw`` (float, 4), ``k`` (int, ``2 nw - 1``),
          ``adaptive`` (bool, False), ``nfft`` (int, N).

    Returns
    -------
    PSDEstimate
        PSD on ``0 < f <= f_N`` (the zero frequency dropped), m^2/Hz, with
        degrees of freedom, options used and diagnostics in ``params``.

    Raises
    ------
    InputError
        Fewer than :data:`MIN_SAMPLES` samples, non-finite samples, a
        non-positive sampling interval, an unknown method or option, or an
        option value out of range.

    See Also
    --------
    psdbound.spectra.BoundModel : Estimate every window and bound them.
    scipy.signal.welch : The segment-averaged periodogram used for ``"welch"``.

    References
    ----------
    .. [1] Thomson, D. J. (1982). Spectrum estimation and harmonic analysis.
       *Proceedings of the IEEE*, 70(9), 1055-1096.
    .. [2] Percival, D. B., & Walden, A. T. (1993). *Spectral Analysis for
       Physical Applications*. Cambridge University Press.
    .. [3] Welch, P. D. (1967). The use of fast Fourier transform for the
       estimation of power spectra. *IEEE Trans. Audio Electroacoustics*, 15(2).

    Examples
    --------
    >>> import numpy as np
    >>> x = np.random.default_rng(0).normal(0.0, 0.01, 4096)
    >>> est = estimate_psd(x, 1.0, method="welch")
    >>> lower, upper = est.confidence_interval(0.95)
    """
    x, dt = _check_input(x_m, dt_s)
    name = str(method).strip().lower()
    if name not in _IMPLEMENTATIONS:
        raise InputError(f"unknown PSD method {method!r}; choose from {', '.join(METHODS)}")
    func = _IMPLEMENTATIONS[name]
    allowed = [
        p.name
        for p in inspect.signature(func).parameters.values()
        if p.kind is inspect.Parameter.KEYWORD_ONLY
    ]
    unknown = sorted(set(options) - set(allowed))
    if unknown:
        raise InputError(
            f"unknown option(s) {', '.join(unknown)} for method {name!r}; "
            f"valid options: {', '.join(allowed)}"
        )
    f_hz, psd, dof, params = func(x, dt, **options)
    keep = f_hz > 0.0
    if np.ndim(dof) > 0:
        dof = np.asarray(dof)[keep]
    return PSDEstimate(
        f_hz=f_hz[keep],
        psd_m2_hz=psd[keep],
        dof=dof,
        method=name,
        params=params,
        dt_s=dt,
        n_samples=int(x.size),
    )
