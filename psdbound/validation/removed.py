"""What the high-pass removes from a reflector's multipath: a slow Gauss-Markov component.

The ionosphere high-pass of dual-frequency isolation removes, with the
ionosphere, each arc's mean and the part of the multipath below its cutoff:
for a low ground reflector, almost all of it. The bound never sees that
part, so it is carried as a component of its own (``error_model`` ``slow``),
computed along the data's own arcs, like with like:

1. Along every arc of the isolated series (its epochs and elevations), the
   reflection's exact carrier-phase error on each carrier (``atan2(alpha sin
   psi, 1 + alpha cos psi)`` in metres, :func:`psdbound.validation.phase_error_rad`)
   is combined as the isolation combines the carriers,
   ``(m_1 - m_2) / sqrt(2)``, and passed through the same high-pass
   (:meth:`psdbound.isolation.HighPass.apply`, the arc mean removed first);
   what it takes away, ``x - HP(x - mean)``, is the removed series.
2. The removed spectrum is the length-weighted mean of the arcs' raw
   periodograms ``2 dt |X(f)|^2 / N`` (one-sided, 0 Hz included, every sample
   weighted alike; on the grid of a common zero-padded length), the spectrum
   of the pooled removed series; its RMS is that of the removed samples.
3. The slow component is the first-order Gauss-Markov process of least
   variance whose sampled PSD lies above that spectrum at every frequency
   (for each time constant the variance is the largest ratio; the time
   constant minimises it).

Its size rests on the reflection model: the amplitude ratio ``alpha`` and
the reflector (height or distance). Measured from the SNR where the file
has it (:mod:`psdbound.validation.site`), assumed otherwise; the result says
which.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.isolation import DF_SCALING
from psdbound.spectra.models import gm_psd_sampled
from psdbound.validation.direct import phase_error_rad
from psdbound.validation.geometry import Reflection

__all__ = ["RemovedMultipath", "envelope", "removed_along_arcs", "slow_gauss_markov"]

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
    n_arcs : int
        Arcs of the data it was computed along.
    f_hz, psd_m2_hz : ndarray
        The removed spectrum (one-sided, sampled at ``dt_s``), Hz and m^2/Hz.
    rms_m : float
        RMS of the removed samples, m.
    sigma_m, tau_s : float
        The slow Gauss-Markov component above the spectrum: standard
        deviation (m) and time constant (s).
    dt_s : float
        Sampling interval, s.
    """

    geometry: str
    alpha: float
    n_arcs: int
    f_hz: NDArray[np.float64]
    psd_m2_hz: NDArray[np.float64]
    rms_m: float
    sigma_m: float
    tau_s: float
    dt_s: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (no arrays)."""
        return {
            "geometry": self.geometry,
            "alpha": self.alpha,
            "n_arcs": self.n_arcs,
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
        Frequencies, Hz (>= 0, at most Nyquist).
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
    f_lo = float(f[f > 0].min()) if np.any(f > 0) else 0.5 / dt_s
    taus = np.geomspace(dt_s, 100.0 / f_lo, _N_TAU)
    var = np.array([np.max(s / gm_psd_sampled(f, 1.0, t, dt_s)) for t in taus])
    k = int(np.argmin(var))
    return float(np.sqrt(var[k])), float(taus[k])


def _removed_series(
    el_deg: NDArray[np.float64],
    geometry: Reflection,
    alpha: float,
    wavelengths_m: Sequence[float],
    highpass: Any,
    dt_s: float,
    cutoff_hz: float,
) -> NDArray[np.float64]:
    """Return what the high-pass takes from one arc's reflection multipath, m (edges cut)."""
    th = np.radians(el_deg)
    m = [
        lam / (2.0 * np.pi) * phase_error_rad(geometry.phase_rad(th, wavelength_m=lam), alpha)
        for lam in wavelengths_m[:2]
    ]
    x = DF_SCALING * (m[0] - m[1])  # the isolation's combination of the two carriers
    y, keep = highpass.apply(x - x.mean(), dt_s, cutoff_hz)
    return (x - y)[keep]


def removed_along_arcs(
    elevation_deg: NDArray[np.float64],
    arc_id: NDArray[np.int64],
    *,
    geometry: Reflection,
    alpha: float,
    wavelengths_m: Sequence[float],
    highpass: Any,
    dt_s: float,
    cutoff_hz: float,
) -> RemovedMultipath | None:
    """Compute one reflector's removed multipath along the data's arcs and its slow GM bound.

    Parameters
    ----------
    elevation_deg : ndarray
        Elevation of every sample of the isolated series, degrees (NaN where
        unknown: those arcs are skipped).
    arc_id : ndarray of int
        Arc of every sample (consecutive samples at ``dt_s``).
    geometry : Reflection
        The reflector.
    alpha : float
        Amplitude ratio.
    wavelengths_m : sequence of float
        The two carriers' wavelengths, m.
    highpass : HighPass
        The isolation's high-pass.
    dt_s : float
        Sampling interval, s.
    cutoff_hz : float
        Its cutoff, Hz.

    Returns
    -------
    RemovedMultipath or None
        None when no arc has elevations and survives the filter edges.
    """
    arcs = []
    for a in np.unique(arc_id):
        el = elevation_deg[arc_id == a]
        if el.size > 8 and np.isfinite(el).all():
            r = _removed_series(el, geometry, alpha, wavelengths_m, highpass, dt_s, cutoff_hz)
            if r.size > 2:
                arcs.append(r)
    if not arcs:
        return None
    # raw periodograms 2 dt |X(f)|^2 / N on one grid: each arc zero-padded to a common length
    n_pad = 1 << int(np.ceil(np.log2(2 * max(r.size for r in arcs))))
    f = np.fft.rfftfreq(n_pad, dt_s)
    lengths = np.array([r.size for r in arcs], dtype=float)
    psd = sum(np.abs(np.fft.rfft(r, n_pad)) ** 2 * (2.0 * dt_s) for r in arcs) / lengths.sum()
    rms = float(np.sqrt(np.mean(np.concatenate(arcs) ** 2)))
    sigma, tau = slow_gauss_markov(f, psd, dt_s)
    return RemovedMultipath(geometry.label, float(alpha), len(arcs), f, psd, rms, sigma, tau, dt_s)


def envelope(parts: Sequence[RemovedMultipath], label: str) -> RemovedMultipath:
    """Return the pointwise largest of several removed spectra (same arcs), with its slow GM.

    Used over a reflector's measurement uncertainty (e.g. heights ``h - d``,
    ``h``, ``h + d``): the narrow features of a low reflector's removed
    spectrum move with ``h``, and a GM touching the spectrum at one height can
    lie under it at a neighbouring one.

    Parameters
    ----------
    parts : sequence of RemovedMultipath
        Spectra on one frequency grid (the same arcs).
    label : str
        The geometry label of the result.

    Returns
    -------
    RemovedMultipath
    """
    p0 = parts[0]
    psd = np.max([p.psd_m2_hz for p in parts], axis=0)
    sigma, tau = slow_gauss_markov(p0.f_hz, psd, p0.dt_s)
    return RemovedMultipath(
        label,
        max(p.alpha for p in parts),
        p0.n_arcs,
        p0.f_hz,
        psd,
        max(p.rms_m for p in parts),
        sigma,
        tau,
        p0.dt_s,
    )
