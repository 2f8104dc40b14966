"""Closed-form PSDs of the bounding model: first-order Gauss-Markov + white noise.

Conventions (used everywhere in psdbound):

* PSDs are **one-sided, per hertz**, on ``0 <= f <= f_N = 1/(2 dt)`` for
  sampled data: the variance is the integral of the PSD from 0 to ``f_N``
  (from 0 to infinity for a continuous process). Units: m^2/Hz.
* Gauss-Markov (GMRP) autocorrelation ``R(t) = sigma^2 exp(-|t|/tau)``.
  Its two-sided continuous PSD is ``2 sigma^2 tau / (1 + (2 pi f tau)^2)``
  -- the thesis's expression ``(2 sigma^2/tau) / (1/tau^2 + 4 pi^2 f^2)``
  (eq. 3.6) -- and the one-sided PSD is twice that for ``f > 0``.
* Sampled at interval ``dt``, the GMRP is an AR(1) sequence with
  ``phi = exp(-dt/tau)`` whose one-sided PSD (the continuous PSD with every
  alias folded in) is
  ``2 sigma^2 dt (1 - phi^2) / (1 - 2 phi cos(2 pi f dt) + phi^2)``.
* White noise of per-sample standard deviation ``sigma_wn`` has the flat
  one-sided PSD ``2 sigma_wn^2 dt`` on ``[0, f_N]``. (The thesis's
  ``N_WN`` is the two-sided level ``sigma_wn^2 dt``.)

The model as an object
----------------------
:class:`GaussMarkovWhiteNoise` holds the four numbers of the model
(``sigma_gm_m``, ``tau_s``, ``sigma_wn_m`` and the data interval ``dt_s``
they are stated at) and gives its PSDs, autocovariance and variances. The
fitted bound (:class:`psdbound.spectra.BoundFit`) and the Kalman-filter bound
(:class:`psdbound.kalman.GaussMarkovBound`) are built on it.

White noise at another sampling interval
----------------------------------------
``sigma_wn`` is the white-noise standard deviation of one **data** sample
(interval ``dt_s``). At that interval the white variance of one sample is
``R = sigma_wn^2`` and the sampled model PSD is
``gm_psd_sampled(f, sigma_gm, tau, dt_s) + 2 sigma_wn^2 dt_s`` (a white
sequence of variance ``R`` has the flat one-sided PSD ``2 R dt``). At another
interval ``dt``, the ``white_noise`` mode (:data:`WHITE_NOISE_MODES`) says
what one sample is:

``"psd"``
    ``R = N_WN / dt = sigma_wn^2 dt_s / dt``. The white **PSD level**
    ``2 N_WN`` is kept, i.e. the white noise is band-limited to the new
    Nyquist frequency. Right when a sample is the average of the data over
    ``dt`` (``dt`` a multiple of ``dt_s``: the mean of ``n`` white samples
    has variance ``sigma_wn^2 / n``). For ``dt < dt_s`` it extrapolates the
    flat level above the data's Nyquist frequency, where the model was never
    checked.
``"per_sample"``
    ``R = sigma_wn^2``. Right when every ``n``-th data sample is used
    unaveraged (decimation): decimating white noise keeps its per-sample
    variance (its folded PSD is ``2 sigma_wn^2 dt``). With ``"psd"`` such a
    use would under-state the white noise by the factor ``dt / dt_s``.
``"conservative"`` (default)
    ``R = max(sigma_wn^2, N_WN / dt)``: safe for both readings; equal to both
    at the data interval.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.common.options import Number
from psdbound.errors import InputError

__all__ = [
    "INTERVAL_S",
    "WHITE_NOISE_MODES",
    "GaussMarkovWhiteNoise",
    "gm_psd_continuous",
    "gm_psd_sampled",
    "white_psd",
    "gm_acf",
    "below_band_ceiling",
]

#: How the white noise of one sample is read at another interval (module docstring).
WHITE_NOISE_MODES = ("psd", "per_sample", "conservative")


def gm_psd_continuous(f_hz: ArrayLike, sigma_m: float, tau_s: float) -> NDArray[np.float64]:
    """One-sided PSD of a continuous first-order Gauss-Markov process, m^2/Hz.

    Parameters
    ----------
    f_hz : array_like
        Frequencies, Hz (>= 0).
    sigma_m : float
        Standard deviation, metres.
    tau_s : float
        Time constant, seconds.

    Returns
    -------
    ndarray
        ``4 sigma^2 tau / (1 + (2 pi f tau)^2)``.
    """
    f = np.asarray(f_hz, dtype=float)
    return 4.0 * sigma_m**2 * tau_s / (1.0 + (2.0 * np.pi * f * tau_s) ** 2)


def gm_psd_sampled(
    f_hz: ArrayLike, sigma_m: float, tau_s: float, dt_s: float
) -> NDArray[np.float64]:
    """One-sided PSD of a Gauss-Markov process sampled every ``dt_s`` (aliased), m^2/Hz.

    Parameters
    ----------
    f_hz : array_like
        Frequencies, Hz, in ``[0, 1/(2 dt)]``.
    sigma_m : float
        Standard deviation, metres.
    tau_s : float
        Time constant, seconds.
    dt_s : float
        Sampling interval, seconds.

    Returns
    -------
    ndarray
        ``2 sigma^2 dt (1 - phi^2) / (1 - 2 phi cos(2 pi f dt) + phi^2)``,
        ``phi = exp(-dt/tau)``; integrates to ``sigma^2`` over ``[0, f_N]``.
    """
    f = np.asarray(f_hz, dtype=float)
    phi = np.exp(-dt_s / tau_s)
    return (
        2.0
        * sigma_m**2
        * dt_s
        * (1.0 - phi**2)
        / (1.0 - 2.0 * phi * np.cos(2.0 * np.pi * f * dt_s) + phi**2)
    )


def white_psd(f_hz: ArrayLike, sigma_wn_m: float, dt_s: float) -> NDArray[np.float64]:
    """One-sided PSD of sampled white noise with per-sample std ``sigma_wn_m``, m^2/Hz."""
    f = np.asarray(f_hz, dtype=float)
    return np.full(f.shape, 2.0 * sigma_wn_m**2 * dt_s)


def below_band_ceiling(
    band_mean_m2_hz: float, lo_hz: float, hi_hz: float, f_hz: ArrayLike
) -> NDArray[np.float64]:
    """Largest PSD below a band that a sum of Gauss-Markov and white terms allows, m^2/Hz.

    Each term has ``f^2 S(f)`` rising with ``f`` (sampled ones too), so at the band's
    lower edge ``l`` such a sum is at most ``r = h / l`` times its band mean over
    ``[l, h]``, and below it at most that times ``(l / f)^2``.

    Parameters
    ----------
    band_mean_m2_hz : float
        The PSD's mean over the band (or an upper limit of it), m^2/Hz.
    lo_hz, hi_hz : float
        The band's edges, Hz.
    f_hz : array_like
        Frequencies at or below ``lo_hz``, Hz.

    Returns
    -------
    ndarray
        ``band_mean r (l / f)^2``.
    """
    return band_mean_m2_hz * (hi_hz / lo_hz) * (lo_hz / np.asarray(f_hz, dtype=float)) ** 2


def gm_acf(lag_s: ArrayLike, sigma_m: float, tau_s: float) -> NDArray[np.float64]:
    """Autocorrelation ``sigma^2 exp(-|lag|/tau)`` of a Gauss-Markov process, m^2."""
    lag = np.asarray(lag_s, dtype=float)
    return sigma_m**2 * np.exp(-np.abs(lag) / tau_s)


def _check_mode(white_noise: str) -> None:
    if white_noise not in WHITE_NOISE_MODES:
        raise InputError(
            f"unknown white_noise mode {white_noise!r}; choose from {WHITE_NOISE_MODES}"
        )


#: A sampling or filter interval: a finite number > 0 s.
INTERVAL_S = Number(lo=0.0, lo_open=True, unit="s")


def _check_dt(dt_s: float, what: str = "filter interval dt_s") -> float:
    return float(INTERVAL_S(what, dt_s))


@dataclass(frozen=True)
class GaussMarkovWhiteNoise:
    """First-order Gauss-Markov + white-noise model stated at a data interval.

    Conventions are in the module docstring (one-sided PSDs per hertz; the
    white-noise modes for another interval).

    Parameters
    ----------
    sigma_gm_m : float
        Gauss-Markov standard deviation, metres (>= 0).
    tau_s : float
        Gauss-Markov time constant, seconds (> 0).
    sigma_wn_m : float
        White-noise standard deviation per data sample, metres (>= 0).
    dt_s : float
        Data sampling interval the model is stated at, seconds (> 0). It
        fixes the white PSD level ``N_WN = sigma_wn^2 dt_s``.

    Raises
    ------
    InputError
        For a parameter that is not a finite number, a negative standard
        deviation, or a non-positive ``tau_s`` or ``dt_s``.
    """

    sigma_gm_m: float
    tau_s: float
    sigma_wn_m: float
    dt_s: float

    def __post_init__(self) -> None:
        for name in ("sigma_gm_m", "tau_s", "sigma_wn_m", "dt_s"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int | float | np.floating | np.integer):
                raise InputError(f"bound parameter {name} must be a number, got {v!r}")
            if not math.isfinite(float(v)):
                raise InputError(f"bound parameter {name} must be finite, got {v!r}")
            object.__setattr__(self, name, float(v))
        if self.sigma_gm_m < 0:
            raise InputError(f"sigma_gm_m must be >= 0 m, got {self.sigma_gm_m}")
        if self.sigma_wn_m < 0:
            raise InputError(f"sigma_wn_m must be >= 0 m, got {self.sigma_wn_m}")
        if self.tau_s <= 0:
            raise InputError(f"tau_s must be > 0 s, got {self.tau_s}")
        if self.dt_s <= 0:
            raise InputError(f"dt_s must be > 0 s, got {self.dt_s}")

    # ------------------------------------------------------------- properties
    @property
    def n_wn_two_sided_m2_hz(self) -> float:
        """Thesis's two-sided white level ``N_WN = sigma_wn^2 dt_s``, m^2/Hz."""
        return self.sigma_wn_m**2 * self.dt_s

    @property
    def nyquist_hz(self) -> float:
        """Nyquist frequency ``1 / (2 dt_s)`` of the data interval, Hz."""
        return 0.5 / self.dt_s

    @property
    def total_variance_m2(self) -> float:
        """Variance of the model process at the data interval, ``sigma_gm^2 + sigma_wn^2``, m^2."""
        return self.sigma_gm_m**2 + self.sigma_wn_m**2

    def params(self) -> dict[str, float]:
        """Return the parameters with units in their names (as in the result file)."""
        return {
            "sigma_gm_m": self.sigma_gm_m,
            "tau_s": self.tau_s,
            "sigma_wn_m": self.sigma_wn_m,
            "n_wn_two_sided_m2_hz": self.n_wn_two_sided_m2_hz,
            "dt_s": self.dt_s,
        }

    def checked_dt_s(self, dt_s: float | None = None) -> float:
        """Return a checked sampling interval, seconds; the data interval when ``dt_s`` is None.

        Parameters
        ----------
        dt_s : float, optional
            Sampling interval, seconds.

        Returns
        -------
        float

        Raises
        ------
        InputError
            If ``dt_s`` is not a finite number > 0.
        """
        return self.dt_s if dt_s is None else _check_dt(dt_s)

    def filter_dt_s(self, dt_s: float | None = None, *, white_noise: str = "conservative") -> float:
        """Return a checked filter interval, seconds, warning when it is shorter than the data's.

        Below the data interval the data say nothing above their Nyquist
        frequency, so the white variance ``R`` of a filter sample
        (:meth:`white_variance_m2`) is an extrapolation there.

        Parameters
        ----------
        dt_s : float, optional
            Filter interval, seconds; default the data interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            The white-noise mode the filter uses (named in the warning).

        Returns
        -------
        float

        Warns
        -----
        UserWarning
            A filter interval shorter than the data interval.
        """
        dt = self.checked_dt_s(dt_s)
        if dt < self.dt_s * (1.0 - 1e-9):
            warnings.warn(
                f"filter step {dt:g} s is shorter than the data interval {self.dt_s:g} s the "
                f"bound was fitted at: the data say nothing above their Nyquist frequency "
                f"{self.nyquist_hz:g} Hz, so R ({white_noise!r} white-noise mode) is an "
                "extrapolation there",
                stacklevel=3,
            )
        return dt

    # ---------------------------------------------------------------- models
    def white_variance_m2(
        self, dt_s: float | None = None, *, white_noise: str = "conservative"
    ) -> float:
        """White-noise variance ``R`` of one sample at interval ``dt_s``, m^2.

        Parameters
        ----------
        dt_s : float, optional
            Sampling interval, seconds; default the data interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            What one sample is (module docstring): ``N_WN / dt``,
            ``sigma_wn^2``, or the larger of the two.

        Returns
        -------
        float

        Raises
        ------
        InputError
            For an unknown mode or a bad interval.
        """
        _check_mode(white_noise)
        dt = self.checked_dt_s(dt_s)
        psd_level = self.n_wn_two_sided_m2_hz / dt
        if white_noise == "psd":
            return psd_level
        if white_noise == "per_sample":
            return self.sigma_wn_m**2
        return max(psd_level, self.sigma_wn_m**2)

    def variance_m2(self, dt_s: float | None = None, *, white_noise: str = "conservative") -> float:
        """Total variance of one sample at interval ``dt_s``: ``sigma_gm^2 + R``, m^2.

        Parameters
        ----------
        dt_s : float, optional
            Sampling interval, seconds; default the data interval (then this
            is :attr:`total_variance_m2`).
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            See :meth:`white_variance_m2`.

        Returns
        -------
        float
        """
        return self.sigma_gm_m**2 + self.white_variance_m2(dt_s, white_noise=white_noise)

    def psd(self, f_hz: ArrayLike) -> NDArray[np.float64]:
        """Continuous-time one-sided model PSD, m^2/Hz.

        ``4 sigma_gm^2 tau / (1 + (2 pi f tau)^2) + 2 N_WN`` -- the thesis's
        model (eq. 3.6, two-sided) doubled. This is the PSD before sampling;
        the PSD of the sampled model is :meth:`sampled_psd`.

        Parameters
        ----------
        f_hz : array_like
            Frequencies, Hz (>= 0).

        Returns
        -------
        ndarray
        """
        f = np.asarray(f_hz, dtype=float)
        return gm_psd_continuous(f, self.sigma_gm_m, self.tau_s) + 2.0 * self.n_wn_two_sided_m2_hz

    def sampled_psd(
        self, f_hz: ArrayLike, dt_s: float | None = None, *, white_noise: str = "conservative"
    ) -> NDArray[np.float64]:
        """One-sided PSD of the model sampled at interval ``dt_s`` (aliases folded in), m^2/Hz.

        ``gm_psd_sampled(f, sigma_gm, tau, dt) + 2 R dt`` on ``[0, 1/(2 dt)]``,
        with ``R`` from :meth:`white_variance_m2`. At the data interval this
        is the bound PSD :meth:`psdbound.spectra.BoundFit.psd` (to rounding).

        Parameters
        ----------
        f_hz : array_like
            Frequencies, Hz, in ``[0, 1/(2 dt)]``.
        dt_s : float, optional
            Sampling interval, seconds; default the data interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            See :meth:`white_variance_m2`.

        Returns
        -------
        ndarray
        """
        dt = self.checked_dt_s(dt_s)
        f = np.asarray(f_hz, dtype=float)
        r = self.white_variance_m2(dt, white_noise=white_noise)
        return gm_psd_sampled(f, self.sigma_gm_m, self.tau_s, dt) + 2.0 * r * dt

    def acf(
        self, lag_s: ArrayLike, dt_s: float | None = None, *, white_noise: str = "conservative"
    ) -> NDArray[np.float64]:
        """Autocovariance of the model process sampled at ``dt_s``, m^2.

        ``sigma_gm^2 exp(-|lag| / tau)``, plus the white variance ``R`` at
        lag 0 (the white part of the continuous model is a delta function;
        sampled at ``dt_s`` it is ``R`` at lag 0 and 0 elsewhere). Lags within
        ``1e-9 dt_s`` of zero count as zero.

        Parameters
        ----------
        lag_s : array_like
            Lags, seconds.
        dt_s : float, optional
            Sampling interval, seconds; default the data interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            See :meth:`white_variance_m2`.

        Returns
        -------
        ndarray
        """
        dt = self.checked_dt_s(dt_s)
        lag = np.abs(np.asarray(lag_s, dtype=float))
        r = self.white_variance_m2(dt, white_noise=white_noise)
        return self.sigma_gm_m**2 * np.exp(-lag / self.tau_s) + np.where(lag < 1e-9 * dt, r, 0.0)
