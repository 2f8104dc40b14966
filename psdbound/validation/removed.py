"""What the high-pass removes from a reflector's multipath: a slow Gauss-Markov component.

The ionosphere high-pass of dual-frequency isolation removes, with the
ionosphere, the part of the multipath below its cutoff: for a low ground
reflector, almost all of it. The bound never sees that part, so it is
carried as a component of its own (``error_model`` ``slow``), computed
along the data's satellite passes:

1. For every pass simulated by the cutoff validation
   (:func:`psdbound.validation.direct_check`, physical convention), the
   phase error's periodogram times what the filter removes,
   ``1 - |H(f)|^2``, in m^2/Hz (times ``(lambda / 2 pi)^2``, averaged over the
   two carriers of the dual-frequency combination, whose reflections have
   independent phases; the periodogram scaled to the whole pass's variance, as
   the Hann taper weights its middle), and the pass's mean (an offset per arc, which the
   filter removes too; it is put at the lowest frequency ``1 / (2 T)`` with
   the density ``mean^2 T`` of a constant over ``T`` seconds).
2. The passes' removed spectra, interpolated on one frequency grid, are
   averaged: the spectrum of the pooled removed series.
3. The slow component is the first-order Gauss-Markov process of least
   variance whose sampled PSD lies above that spectrum at every frequency
   of the grid (for each time constant the variance is the largest ratio;
   the time constant minimises it).

Its size rests on the reflection model: the amplitude ratio ``alpha`` and
the reflector (height or distance). Measured from the SNR where the file
has it (:mod:`psdbound.validation.reflectors`), assumed otherwise; the
result says which.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import trapezoid

from psdbound.spectra.models import gm_psd_sampled
from psdbound.validation.results import DirectCheck

__all__ = ["RemovedMultipath", "removed_multipath", "slow_gauss_markov"]

#: Frequencies of the common grid.
_N_GRID = 240
#: Time constants searched for the slow component.
_N_TAU = 160


@dataclass(frozen=True)
class RemovedMultipath:
    """The multipath a high-pass removes from one reflector, and its slow GM bound.

    Attributes
    ----------
    geometry : str
        The reflector (e.g. ``"ground:h=1.5"``).
    alpha : float
        Amplitude ratio used.
    n_passes : int
        Satellite passes averaged.
    f_hz, psd_m2_hz : ndarray
        The removed spectrum (one-sided, sampled at ``dt_s``), Hz and m^2/Hz.
    rms_m : float
        Its RMS, m (offsets included).
    sigma_m, tau_s : float
        The slow Gauss-Markov component above it: standard deviation (m) and
        time constant (s).
    dt_s : float
        Sampling interval, s.
    """

    geometry: str
    alpha: float
    n_passes: int
    f_hz: NDArray[np.float64]
    psd_m2_hz: NDArray[np.float64]
    rms_m: float
    sigma_m: float
    tau_s: float
    dt_s: float

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready form (no arrays)."""
        return {
            "geometry": self.geometry,
            "alpha": self.alpha,
            "n_passes": self.n_passes,
            "removed_rms_m": self.rms_m,
            "sigma_m": self.sigma_m,
            "tau_s": self.tau_s,
        }


def slow_gauss_markov(
    f_hz: NDArray[np.float64], psd_m2_hz: NDArray[np.float64], dt_s: float
) -> tuple[float, float]:
    """Return the least-variance first-order GM whose sampled PSD lies above a spectrum.

    Parameters
    ----------
    f_hz : ndarray
        Frequencies, Hz (> 0, at most Nyquist).
    psd_m2_hz : ndarray
        The spectrum, m^2/Hz (one-sided, sampled at ``dt_s``).
    dt_s : float
        Sampling interval, s.

    Returns
    -------
    sigma_m, tau_s : float
        Standard deviation (m) and time constant (s); ``(0, dt_s)`` for a
        zero spectrum.
    """
    s = np.asarray(psd_m2_hz, dtype=float)
    f = np.asarray(f_hz, dtype=float)
    if not np.any(s > 0):
        return 0.0, float(dt_s)
    taus = np.geomspace(dt_s, 100.0 / float(f.min()), _N_TAU)
    var = np.array([np.max(s / gm_psd_sampled(f, 1.0, t, dt_s)) for t in taus])
    k = int(np.argmin(var))
    return float(np.sqrt(var[k])), float(taus[k])


def _removed_on_grid(
    c: DirectCheck,
    f: NDArray[np.float64],
    scale_m2_rad2: float,
    power_response: Callable[[NDArray[np.float64]], NDArray[np.float64]],
) -> NDArray[np.float64]:
    """One pass's removed spectrum on ``f``, m^2/Hz, with its offset at ``1 / (2 T)``."""
    fp, sp = c.frequencies_hz[1:], c.psd_rad2_hz[1:]
    if c.variance_rad2 is not None:  # the taper weights the middle: the whole record's variance
        sp = sp * c.variance_rad2 / max(float(trapezoid(sp, fp)), 1e-300)
    # the pass is sampled finer than the data when psi needs it; what the filter removes
    # lies far below either Nyquist frequency
    gain = power_response(np.minimum(fp, f[-1]))
    removed = sp * np.clip(1.0 - gain, 0.0, 1.0) * scale_m2_rad2
    out = np.interp(f, fp, removed, left=0.0, right=0.0)
    dc = c.mean_rad**2 * scale_m2_rad2 * c.duration_s  # a constant over T, density mean^2 T
    out[f <= 0.5 / c.duration_s] += dc
    return out


def removed_multipath(
    checks: Sequence[DirectCheck],
    *,
    wavelengths_m: Sequence[float],
    power_response: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    dt_s: float,
) -> RemovedMultipath | None:
    """Average the removed spectra of one reflector's passes and bound them by a slow GM.

    Parameters
    ----------
    checks : sequence of DirectCheck
        The passes of one geometry (physical convention), at the data
        interval.
    wavelengths_m : sequence of float
        Carrier wavelengths of the dual-frequency combination, m.
    power_response : callable
        ``|H(f)|^2`` of the high-pass.
    dt_s : float
        Data interval, s.

    Returns
    -------
    RemovedMultipath or None
        None without passes.
    """
    if not checks:
        return None
    scale = float(np.mean([(lam / (2.0 * np.pi)) ** 2 for lam in wavelengths_m]))
    t_max = max(c.duration_s for c in checks)
    f = np.geomspace(0.25 / t_max, 0.5 / dt_s, _N_GRID)
    weights = np.array([c.duration_s for c in checks])
    spectra = np.array([_removed_on_grid(c, f, scale, power_response) for c in checks])
    psd = spectra.max(axis=0)
    low = f <= 0.5 / t_max  # the offsets' stand-in density: counted by their variance instead
    offsets_m2 = float(weights @ np.array([c.mean_rad**2 for c in checks]) / weights.sum()) * scale
    rms = float(np.sqrt(trapezoid(np.where(low, 0.0, psd), f) + offsets_m2))
    sigma, tau = slow_gauss_markov(f, psd, dt_s)
    c0 = checks[0]
    return RemovedMultipath(c0.geometry.label, c0.alpha, len(checks), f, psd, rms, sigma, tau, dt_s)
