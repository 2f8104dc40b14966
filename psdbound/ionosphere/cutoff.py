"""Cutoff frequency of one series: LS PSD -> envelope -> criterion (docs/method/cutoff.rst, step 5).

Two criteria on the envelope ``E(f)`` of the one-sided LS PSD (m^2/Hz):

* **relative** (thesis): ``f_c`` is the lowest frequency above which ``E``
  stays ``drop_db`` (40 dB) below the reference level. The reference is
  the periodogram's largest value (``reference="psd"``, default: the
  thesis's "maximal power peak") or the envelope's own peak over the range
  of the local maxima (``reference="envelope"``, the original specification's wording). The
  default is the periodogram maximum because a polynomial envelope through
  a few low harmonics followed by a long decay overshoots them: on Chicago
  2020 the envelope peak lies 5 dB (median; up to 14 dB) above the
  periodogram maximum, which would lower f_c for a fitting reason. The
  crossing is
  solved on the polynomial, between the last grid frequency where ``E`` is
  at or above the threshold and the next one. If ``E`` is still above at
  the top of the grid, ``f_c`` is the top of the grid and ``reached`` is
  False.
* **absolute**: ``f_c`` is the frequency where the ionosphere left after
  filtering, ``integral_{f_c}^{f_N} E(f) df``, falls to ``variance_m2``
  (default :data:`DEFAULT_VARIANCE_M2` = (1 mm)^2). Because ``E`` bounds
  the PSD, this is an upper bound on the residual ionospheric variance of
  the series (for the frequency the delay was computed at).

What the periodogram of a gappy series measures: satellite passes are
windows a few hours long, and the Lomb-Scargle periodogram of a windowed
smooth signal leaks power at about ``f^-2`` (the arc edges). For GPS seen
from mid-latitudes this leakage, not the ionosphere's own dynamics, decides
where the envelope falls 40 dB: a pure once-per-sidereal-day cosine sampled
on the same passes already gives f_c = 2.6-5.5 mHz, and the metre-level tail
makes the absolute criterion with millimetre allowances return cutoffs near
Nyquist. See the closing note of issue #4 for the numbers.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.constants import SIDEREAL_DAY_S
from psdbound.errors import InputError
from psdbound.ionosphere.envelope import Envelope, fit_envelope
from psdbound.ionosphere.names import (
    CRITERIA,
    DEFAULT_DROP_DB,
    DEFAULT_VARIANCE_M2,
    MIN_ARC_S,
    MIN_SERIES_SAMPLES,
    REFERENCES,
)
from psdbound.periodogram import frequency_grid, lomb_scargle, to_one_sided_density

__all__ = [
    "MIN_ARC_S",
    "REPLICAS",
    "one_day_series",
    "CRITERIA",
    "DEFAULT_DROP_DB",
    "DEFAULT_VARIANCE_M2",
    "MIN_SERIES_SAMPLES",
    "REFERENCES",
    "SeriesCutoff",
    "absolute_cutoff",
    "relative_cutoff",
    "series_cutoff",
]

#: Default number of sidereal-day copies (the one-day series and six replicas).
REPLICAS = 7


def one_day_series(
    t_gps_s: ArrayLike,
    delay_m: ArrayLike,
    *,
    period_s: float = SIDEREAL_DAY_S,
    min_arc_s: float = MIN_ARC_S,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """One satellite's one-period series, starting in a visibility gap, without short arcs.

    Sidereal replication puts copy ``r + 1`` right after copy ``r``. If the
    one-day window started while the satellite is in view, the arc crossing
    the window edge would be joined to its own beginning one period earlier,
    where the ionosphere differs by the ~4 min between a solar and a
    sidereal day: a spurious step inside an arc, whose spectrum (a short
    boxcar) reaches up to Nyquist. The window therefore starts in the middle
    of the satellite's first visibility gap (or at the first epoch if it is
    never out of view, or if the simulated span is too short), so every join
    falls in a gap. Arcs shorter than ``min_arc_s`` are then dropped, as the
    dual-frequency isolation drops them (docs/method/isolation.rst).

    Parameters
    ----------
    t_gps_s : array_like of float
        Regular epochs, s, spanning at least one period (a margin beyond it
        lets the window start in a gap).
    delay_m : array_like of float
        Delays, NaN where the satellite is below the mask.
    period_s : float, default one sidereal day
        Window length (the replication period), s.
    min_arc_s : float, default 1800
        Shortest arc kept, s (0 keeps every arc).

    Returns
    -------
    t_s, y_m : ndarray of float64
        Epochs and delays of the kept samples in the window.
    """
    t = np.asarray(t_gps_s, dtype=np.float64)
    d = np.asarray(delay_m, dtype=np.float64)
    vis = np.isfinite(d)
    start = 0
    in_first = t < t[0] + period_s
    gaps = np.flatnonzero(~vis & in_first)
    if gaps.size and vis.any():
        run_end = gaps[0]
        while run_end + 1 < t.size and not vis[run_end + 1]:
            run_end += 1
        mid = (gaps[0] + run_end) // 2
        if t[mid] + period_s <= t[-1] + 1e-6:
            start = mid
    window = (t >= t[start]) & (t < t[start] + period_s) & vis
    idx = np.flatnonzero(window)
    if idx.size and min_arc_s > 0:
        step = float(np.min(np.diff(t))) if t.size > 1 else 1.0
        runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
        idx = np.concatenate(
            [r for r in runs if (r.size - 1) * step + step >= min_arc_s] or [idx[:0]]
        )
    return t[idx], d[idx]


def relative_cutoff(
    envelope: Envelope,
    frequency_hz: ArrayLike,
    *,
    drop_db: float = DEFAULT_DROP_DB,
    reference_level: float | None = None,
) -> tuple[float, float, float, bool]:
    """Lowest frequency above which the envelope stays ``drop_db`` below the reference.

    Parameters
    ----------
    envelope : Envelope
        Upper envelope of the PSD.
    frequency_hz : array_like of float
        The PSD's frequency grid, Hz (increasing).
    drop_db : float, default 40
        Drop below the reference, dB (power).
    reference_level : float, optional
        Reference PSD level; default the envelope's peak over the range of
        the local maxima it was fitted on.

    Returns
    -------
    f_c_hz : float
        Cutoff frequency, Hz.
    threshold : float
        ``reference / 10^(drop_db / 10)``, PSD units.
    reference : float
        Reference level, PSD units.
    reached : bool
        False if the envelope is still above the threshold at the top of the
        grid (``f_c_hz`` is then the top of the grid).
    """
    f = np.asarray(frequency_hz, dtype=np.float64)
    if drop_db <= 0:
        raise InputError(f"drop_db = {drop_db} must be positive")
    inside = (f >= envelope.f_min_hz) & (f <= envelope.f_max_hz)
    log_env = envelope.log10(f)
    j_peak = int(np.flatnonzero(inside)[np.argmax(log_env[inside])])
    if reference_level is None:
        log_ref = float(log_env[j_peak])
    else:
        log_ref = float(np.log10(reference_level))
    log_thr = log_ref - drop_db / 10.0
    above = np.flatnonzero(log_env[j_peak:] >= log_thr) + j_peak
    if above.size == 0:  # envelope below the threshold from its peak on
        return float(f[j_peak]), 10.0**log_thr, 10.0**log_ref, True
    j = int(above[-1])
    if j == f.size - 1:
        return float(f[-1]), 10.0**log_thr, 10.0**log_ref, False
    from scipy.optimize import brentq

    def g(x: float) -> float:
        return float(envelope.log10(10.0**x)) - log_thr

    x = brentq(g, np.log10(f[j]), np.log10(f[j + 1]), xtol=1e-12)
    return float(10.0**x), 10.0**log_thr, 10.0**log_ref, True


def absolute_cutoff(
    envelope: Envelope,
    *,
    f_low_hz: float,
    nyquist_hz: float,
    variance_m2: float = DEFAULT_VARIANCE_M2,
    n_points: int = 4000,
) -> tuple[float, float]:
    """Frequency above which the envelope integrates to ``variance_m2``.

    Parameters
    ----------
    envelope : Envelope
        Upper envelope of a one-sided PSD in m^2/Hz.
    f_low_hz : float
        Lowest frequency considered (the bottom of the PSD grid), Hz.
    nyquist_hz : float
        Upper integration limit, Hz.
    variance_m2 : float, default 1e-6
        Allowed residual variance, m^2.
    n_points : int, default 4000
        Log-spaced quadrature points.

    Returns
    -------
    f_c_hz : float
        Cutoff, Hz (``f_low_hz`` if the whole band already integrates below
        the allowance).
    residual_m2 : float
        ``integral_{f_c}^{f_N} E(f) df``, m^2.
    """
    if variance_m2 <= 0:
        raise InputError(f"variance_m2 = {variance_m2} must be positive")
    if not 0 < f_low_hz < nyquist_hz:
        raise InputError(f"need 0 < f_low_hz < nyquist_hz, got {f_low_hz}, {nyquist_hz}")
    x = np.linspace(np.log10(f_low_hz), np.log10(nyquist_hz), n_points)
    fx = 10.0**x
    integrand = envelope(fx) * fx * np.log(10.0)  # dE/dx with f = 10^x
    seg = 0.5 * (integrand[1:] + integrand[:-1]) * np.diff(x)
    tail = np.concatenate([np.cumsum(seg[::-1])[::-1], [0.0]])  # integral from x_i to x_end
    if tail[0] <= variance_m2:
        return float(fx[0]), float(tail[0])
    j = int(np.flatnonzero(tail > variance_m2)[-1])
    # tail decreases from tail[j] > V to tail[j+1] <= V: interpolate in log(tail)
    lt0, lt1 = np.log(tail[j]), np.log(max(tail[j + 1], 1e-300))
    frac = (lt0 - np.log(variance_m2)) / (lt0 - lt1) if lt0 != lt1 else 1.0
    xc = x[j] + frac * (x[j + 1] - x[j])
    return float(10.0**xc), float(variance_m2)


@dataclass(frozen=True, eq=False)
class SeriesCutoff:
    """Cutoff frequency of one (replicated) series and how it was found.

    Attributes
    ----------
    f_c_hz : float
        Cutoff frequency, Hz.
    criterion : str
        ``"relative"`` or ``"absolute"``.
    reached : bool
        False if the relative criterion's threshold was not reached below
        the top of the grid.
    envelope : Envelope
        Upper envelope of the one-sided PSD (m^2/Hz).
    peak_hz : float
        Frequency of the periodogram's largest value, Hz.
    peak_psd_m2_hz : float
        Largest periodogram value, m^2/Hz.
    reference_m2_hz, threshold_m2_hz : float
        Relative criterion's reference level and threshold (NaN for the
        absolute criterion).
    residual_m2 : float
        Envelope integral from ``f_c_hz`` to Nyquist, m^2.
    n_samples : int
        Samples in the one-day series (before replication).
    variance_m2 : float
        Sample variance of the series, m^2.
    settings : dict
        Criterion and spectrum settings.
    frequency_hz, psd_m2_hz : ndarray or None
        The periodogram (one-sided, m^2/Hz), when requested.
    """

    f_c_hz: float
    criterion: str
    reached: bool
    envelope: Envelope
    peak_hz: float
    peak_psd_m2_hz: float
    reference_m2_hz: float
    threshold_m2_hz: float
    residual_m2: float
    n_samples: int
    variance_m2: float
    settings: dict = field(default_factory=dict)
    frequency_hz: NDArray[np.float64] | None = None
    psd_m2_hz: NDArray[np.float64] | None = None

    @property
    def tau_c_min(self) -> float:
        """Time constant ``1 / f_c``, minutes."""
        return 1.0 / self.f_c_hz / 60.0

    def to_dict(self) -> dict:
        """JSON-ready scalar summary (no arrays)."""
        return {
            "f_c_hz": self.f_c_hz,
            "tau_c_min": self.tau_c_min,
            "criterion": self.criterion,
            "reached": self.reached,
            "peak_hz": self.peak_hz,
            "peak_psd_m2_hz": self.peak_psd_m2_hz,
            "reference_m2_hz": self.reference_m2_hz,
            "threshold_m2_hz": self.threshold_m2_hz,
            "residual_m2": self.residual_m2,
            "n_samples": self.n_samples,
            "variance_m2": self.variance_m2,
            "envelope": self.envelope.to_dict(),
            "settings": dict(self.settings),
        }


def _check_criterion(criterion: str, reference: str) -> None:
    """Refuse an unknown criterion or reference."""
    if criterion not in CRITERIA:
        raise InputError(f"unknown criterion {criterion!r}; expected one of {', '.join(CRITERIA)}")
    if reference not in REFERENCES:
        raise InputError(
            f"unknown reference {reference!r}; expected one of {', '.join(REFERENCES)}"
        )


def _apply_criterion(
    env: Envelope,
    f: NDArray[np.float64],
    nyq: float,
    criterion: str,
    drop_db: float,
    ref_level: float | None,
    variance_m2: float,
) -> tuple[float, float, float, bool, float]:
    """Return the cutoff (Hz), threshold and reference (m^2/Hz), reached, residual (m^2)."""
    if criterion == "relative":
        f_c, thr, ref, reached = relative_cutoff(env, f, drop_db=drop_db, reference_level=ref_level)
        residual = absolute_cutoff_tail(env, f_c, nyq)
    else:
        f_c, residual = absolute_cutoff(
            env, f_low_hz=float(f[0]), nyquist_hz=nyq, variance_m2=variance_m2
        )
        thr = ref = float("nan")
        reached = True
    return f_c, thr, ref, reached, residual


def series_cutoff(
    t_s: ArrayLike,
    y_m: ArrayLike,
    *,
    dt_s: float = 12.0,
    copies: int = REPLICAS,
    period_s: float = SIDEREAL_DAY_S,
    oversample: float = 1.0,
    nyquist_fraction: float = 0.99,
    criterion: str = "relative",
    drop_db: float = DEFAULT_DROP_DB,
    reference: str = "psd",
    variance_m2: float = DEFAULT_VARIANCE_M2,
    degree: int = 3,
    quantile: float = 0.99,
    envelope_method: str = "quantreg",
    bins_per_decade: float = 20.0,
    ls_method: str = "auto",
    keep_spectrum: bool = False,
) -> SeriesCutoff:
    """Cutoff frequency of one gappy series, replicated ``copies`` times.

    Parameters
    ----------
    t_s : array_like of float
        Sample times, s (on a ``dt_s`` grid for the fast exact periodogram).
    y_m : array_like of float
        Delay, m.
    dt_s : float, default 12
        Sampling interval, s.
    copies : int, default 7
        Copies at ``period_s`` spacing (sidereal replication over 7 days).
    period_s : float, default one sidereal day
        Replication spacing, s.
    oversample : float, default 1
        Frequency grid points per 1/T (T = copies * period).
    nyquist_fraction : float, default 0.99
        Top of the frequency grid as a fraction of Nyquist.
    criterion : {"relative", "absolute"}
        Cutoff criterion.
    drop_db : float, default 40
        Relative criterion's drop, dB.
    reference : {"psd", "envelope"}
        Relative criterion's reference: periodogram maximum (default) or
        envelope peak.
    variance_m2 : float, default 1e-6
        Absolute criterion's allowed residual variance, m^2.
    degree, quantile, envelope_method, bins_per_decade
        Envelope settings (see :func:`~psdbound.ionosphere.envelope.fit_envelope`).
    ls_method : {"auto", "gridfft", "astropy"}
        Lomb-Scargle implementation.
    keep_spectrum : bool, default False
        Keep the frequency grid and the PSD in the result.

    Returns
    -------
    SeriesCutoff

    Raises
    ------
    InputError
        For an unknown criterion or reference, too short a series, or bad
        spectrum/envelope settings.
    """
    _check_criterion(criterion, reference)
    t = np.asarray(t_s, dtype=np.float64)
    y = np.asarray(y_m, dtype=np.float64)
    if t.size < 3:
        raise InputError(f"series has {t.size} samples; need at least 3")
    f = frequency_grid(
        dt_s, copies * period_s, oversample=oversample, nyquist_fraction=nyquist_fraction
    )
    power = lomb_scargle(t, y, f, method=ls_method, copies=copies, period_s=period_s, dt_s=dt_s)
    psd = to_one_sided_density(power, dt_s)
    env = fit_envelope(
        f,
        psd,
        degree=degree,
        quantile=quantile,
        method=envelope_method,
        bins_per_decade=bins_per_decade,
    )
    j_max = int(np.argmax(psd))
    ref_level = float(psd[j_max]) if reference == "psd" else None
    f_c, thr, ref, reached, residual = _apply_criterion(
        env, f, 0.5 / dt_s, criterion, drop_db, ref_level, variance_m2
    )
    settings = {
        "dt_s": dt_s,
        "copies": copies,
        "period_s": period_s,
        "oversample": oversample,
        "nyquist_fraction": nyquist_fraction,
        "drop_db": drop_db if criterion == "relative" else None,
        "reference": reference if criterion == "relative" else None,
        "variance_m2": variance_m2 if criterion == "absolute" else None,
        "ls_method": ls_method,
    }
    return SeriesCutoff(
        f_c_hz=float(f_c),
        criterion=criterion,
        reached=bool(reached),
        envelope=env,
        peak_hz=float(f[j_max]),
        peak_psd_m2_hz=float(psd[j_max]),
        reference_m2_hz=float(ref),
        threshold_m2_hz=float(thr),
        residual_m2=float(residual),
        n_samples=int(t.size),
        variance_m2=float(np.var(y)),
        settings=settings,
        frequency_hz=f if keep_spectrum else None,
        psd_m2_hz=psd if keep_spectrum else None,
    )


def absolute_cutoff_tail(envelope: Envelope, f_c_hz: float, nyquist_hz: float) -> float:
    """Envelope integral from ``f_c_hz`` to ``nyquist_hz``, m^2 (0 if f_c >= Nyquist)."""
    if f_c_hz >= nyquist_hz:
        return 0.0
    x = np.linspace(np.log10(f_c_hz), np.log10(nyquist_hz), 2000)
    fx = 10.0**x
    return float(np.trapezoid(envelope(fx) * fx * np.log(10.0), x))
