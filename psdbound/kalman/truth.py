"""True errors given by their PSD or by sample paths, and the normalisation of a truth argument.

* :class:`SampledPSD` -- one-sided PSD samples of the sampled error; its
  autocovariance is the exact cosine transform of the piecewise-linear PSD.
* :class:`ErrorSequences` -- sample paths (e.g. measured multipath) for a
  Monte Carlo analysis.
* :func:`broadcast_truth` -- one truth per measurement, checked against the
  filter interval, as :func:`psdbound.kalman.analyze_covariance` uses it.

The state-space truth is :class:`psdbound.kalman.process.ErrorProcess`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError
from psdbound.kalman.bound import GaussMarkovBound
from psdbound.kalman.process import ErrorProcess

__all__ = ["ErrorSequences", "SampledPSD", "Truth", "broadcast_truth"]


@dataclass(frozen=True)
class SampledPSD:
    """A true error given as one-sided PSD samples of the sequence at the filter interval.

    The PSD (m^2/Hz, one-sided, aliases already folded in, on
    ``[0, 1/(2 dt)]``) is linearly interpolated between the samples and held
    constant from the first sample down to 0 Hz and from the last up to the
    Nyquist frequency.

    Parameters
    ----------
    f_hz : array_like
        Strictly increasing frequencies in ``[0, 1/(2 dt_s)]``, Hz.
    psd_m2_hz : array_like
        PSD values (>= 0), m^2/Hz.
    dt_s : float
        Sampling interval of the sequence (the filter interval), seconds.
    label : str
        Free text.
    """

    f_hz: NDArray[np.float64]
    psd_m2_hz: NDArray[np.float64]
    dt_s: float
    label: str = "PSD samples"

    def __post_init__(self) -> None:
        f = np.asarray(self.f_hz, dtype=float).reshape(-1)
        s = np.asarray(self.psd_m2_hz, dtype=float).reshape(-1)
        dt = float(self.dt_s)
        if not (math.isfinite(dt) and dt > 0):
            raise InputError(f"SampledPSD: dt_s must be > 0 s, got {self.dt_s!r}")
        if f.size == 0 or f.shape != s.shape:
            raise InputError("SampledPSD: f_hz and psd_m2_hz must be non-empty and of equal size")
        if not (np.isfinite(f).all() and np.isfinite(s).all()):
            raise InputError("SampledPSD: non-finite frequencies or PSD values")
        if (s < 0).any():
            raise InputError("SampledPSD: PSD values must be >= 0")
        if (np.diff(f) <= 0).any():
            raise InputError("SampledPSD: frequencies must be strictly increasing")
        nyq = 0.5 / dt
        if f[0] < 0 or f[-1] > nyq * (1 + 1e-9):
            raise InputError(
                f"SampledPSD: frequencies must lie in [0, {nyq:g}] Hz (Nyquist of dt = {dt:g} s); "
                f"got {f[0]:g} .. {f[-1]:g} Hz. Fold a continuous PSD first."
            )
        object.__setattr__(self, "f_hz", f)
        object.__setattr__(self, "psd_m2_hz", s)
        object.__setattr__(self, "dt_s", dt)

    @classmethod
    def from_process(
        cls,
        process: ErrorProcess | GaussMarkovBound,
        f_hz: ArrayLike,
        *,
        dt_s: float | None = None,
        white_noise: str = "conservative",
    ) -> SampledPSD:
        """Sample the PSD of a process or a bound on a frequency grid.

        Parameters
        ----------
        process : ErrorProcess or GaussMarkovBound
            The process.
        f_hz : array_like
            Frequencies, Hz, in ``[0, 1/(2 dt)]``.
        dt_s : float, optional
            Interval for a bound (default its data interval); for a process it
            must be omitted or equal the process's interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            For a bound: see :meth:`GaussMarkovBound.white_variance_m2`.

        Returns
        -------
        SampledPSD
        """
        f = np.asarray(f_hz, dtype=float)
        if isinstance(process, GaussMarkovBound):
            dt = process.dt_s if dt_s is None else float(dt_s)
            psd = process.sampled_psd(f, dt, white_noise=white_noise)
            return cls(f, psd, dt, f"PSD of {process}")
        if dt_s is not None and not math.isclose(float(dt_s), process.dt_s, rel_tol=1e-12):
            raise InputError(
                f"dt_s = {dt_s} s differs from the process's interval {process.dt_s} s"
            )
        return cls(f, process.psd(f), process.dt_s, f"PSD of {process.label}")

    def _knots(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        nyq = 0.5 / self.dt_s
        f, s = self.f_hz, self.psd_m2_hz
        if f[0] > 0:
            f, s = np.r_[0.0, f], np.r_[s[0], s]
        if f[-1] < nyq:
            f, s = np.r_[f, nyq], np.r_[s, s[-1]]
        else:
            f = f.copy()
            f[-1] = nyq
        return f, s

    def psd(self, f_hz: ArrayLike) -> NDArray[np.float64]:
        """Interpolated one-sided PSD, m^2/Hz.

        Parameters
        ----------
        f_hz : array_like
            Frequencies, Hz.

        Returns
        -------
        ndarray
        """
        f, s = self._knots()
        return np.interp(np.asarray(f_hz, dtype=float), f, s)

    @property
    def variance_m2(self) -> float:
        """Variance, the integral of the PSD over ``[0, f_N]``, m^2."""
        return float(self.acf(1)[0])

    def acf(self, n_lags: int) -> NDArray[np.float64]:
        """Autocovariance at lags ``0 .. n_lags - 1`` samples, m^2.

        ``r(k) = int_0^fN S(f) cos(2 pi f k dt) df``, integrated exactly for
        the piecewise-linear PSD (no quadrature error).

        Parameters
        ----------
        n_lags : int
            Number of lags.

        Returns
        -------
        ndarray, shape (n_lags,)
        """
        f, s = self._knots()
        h = np.diff(f)
        slope = np.diff(s) / h
        out = np.empty(int(n_lags))
        if out.size == 0:
            return out
        out[0] = float(np.sum(0.5 * (s[1:] + s[:-1]) * h))
        k = np.arange(1, out.size)
        if k.size:
            w = 2.0 * np.pi * k * self.dt_s  # rad per Hz
            # int S cos(w f) = [S sin(w f)/w] + slope * [cos(w f)/w^2] per segment;
            # cos(b) - cos(a) = -2 sin((a+b)/2) sin((b-a)/2) (no cancellation).
            ends = (s[-1] * np.sin(w * f[-1]) - s[0] * np.sin(w * f[0])) / w
            mid = 0.5 * (f[1:] + f[:-1])
            dcos = -2.0 * np.sin(np.outer(w, mid)) * np.sin(np.outer(w, 0.5 * h))
            out[1:] = ends + (dcos @ slope) / w**2
        return out


@dataclass(frozen=True)
class ErrorSequences:
    """A true error given as independent sample paths (Monte Carlo).

    Parameters
    ----------
    samples_m : array_like, shape (n_paths, n_steps) or (n_paths, n_steps, m)
        Error sample paths at the filter interval, metres (raw scale at each
        measurement). A 2-D array is split among the ``m`` measurements:
        measurement ``j`` takes paths ``j, j + m, j + 2m, ...``. Paths should
        be zero-mean and independent across measurements; the second moment
        about zero is what is averaged.
    dt_s : float
        Sampling interval, seconds.
    label : str
        Free text.
    """

    samples_m: NDArray[np.float64]
    dt_s: float
    label: str = "sample paths"

    def __post_init__(self) -> None:
        x = np.asarray(self.samples_m, dtype=float)
        if x.ndim not in (2, 3) or x.shape[0] == 0 or x.shape[1] == 0:
            raise InputError(
                f"ErrorSequences: samples_m must have shape (n_paths, n_steps[, m]), got {x.shape}"
            )
        if not np.isfinite(x).all():
            raise InputError("ErrorSequences: samples_m has non-finite values")
        dt = float(self.dt_s)
        if not (math.isfinite(dt) and dt > 0):
            raise InputError(f"ErrorSequences: dt_s must be > 0 s, got {self.dt_s!r}")
        object.__setattr__(self, "samples_m", x)
        object.__setattr__(self, "dt_s", dt)

    def paths(self, n_measurements: int, n_steps: int) -> NDArray[np.float64]:
        """Return the paths as ``(n_paths, n_steps, m)``, metres.

        Parameters
        ----------
        n_measurements : int
            Number of measurements ``m``.
        n_steps : int
            Steps needed.

        Returns
        -------
        ndarray
        """
        x = self.samples_m
        if x.shape[1] < n_steps:
            raise InputError(
                f"ErrorSequences: paths have {x.shape[1]} steps, the analysis needs {n_steps}"
            )
        if x.ndim == 3:
            if x.shape[2] != n_measurements:
                raise InputError(
                    f"ErrorSequences: {x.shape[2]} measurements in the paths, the filter has "
                    f"{n_measurements}"
                )
            return x[:, :n_steps, :]
        n_paths = x.shape[0] // n_measurements
        if n_paths < 2:
            raise InputError(
                f"ErrorSequences: {x.shape[0]} paths give fewer than 2 per measurement for "
                f"{n_measurements} measurements"
            )
        y = x[: n_paths * n_measurements, :n_steps].reshape(n_paths, n_measurements, n_steps)
        return np.transpose(y, (0, 2, 1))


Truth = ErrorProcess | SampledPSD | ErrorSequences


def broadcast_truth(truth: object, m: int, dt_s: float) -> list[Truth] | ErrorSequences:
    """Return one true process per measurement, or the sample paths, checked against ``dt_s``.

    Parameters
    ----------
    truth : ErrorProcess, SampledPSD, ErrorSequences, or sequence
        One process for all measurements (repeated), one per measurement,
        or sample paths (returned as they are).
    m : int
        Number of measurements.
    dt_s : float
        Filter interval, seconds; every truth must be sampled at it.

    Returns
    -------
    list of ErrorProcess or SampledPSD, or ErrorSequences

    Raises
    ------
    InputError
        For a wrong type or count, or another sampling interval.
    """
    if isinstance(truth, ErrorSequences):
        if not math.isclose(truth.dt_s, dt_s, rel_tol=1e-9):
            raise InputError(
                f"true sequences are at dt = {truth.dt_s:g} s, the filter at {dt_s:g} s"
            )
        return truth
    if isinstance(truth, ErrorProcess | SampledPSD):
        items: list[object] = [truth] * m
    elif isinstance(truth, Sequence):
        items = list(truth)
        if len(items) != m:
            raise InputError(f"need one true process per measurement: got {len(items)} for {m}")
    else:
        raise InputError(
            "truth must be an ErrorProcess, a SampledPSD, a sequence of them (one per "
            f"measurement) or ErrorSequences; got {type(truth).__name__}"
        )
    kinds = {type(t) for t in items}
    if not kinds <= {ErrorProcess, SampledPSD}:
        raise InputError("true processes must be ErrorProcess or SampledPSD objects")
    for i, t in enumerate(items):
        if not math.isclose(t.dt_s, dt_s, rel_tol=1e-9):  # type: ignore[attr-defined]
            raise InputError(
                f"true process {i} is sampled at {t.dt_s:g} s, the filter runs at {dt_s:g} s"  # type: ignore[attr-defined]
            )
    return items  # type: ignore[return-value]
