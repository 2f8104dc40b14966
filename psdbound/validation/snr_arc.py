"""One satellite arc's reflector height and amplitude ratio from SNR (GNSS-IR).

The height of the antenna above a horizontal reflector, and how strong the
reflection is, measured from the data instead of assumed: GNSS
interferometric reflectometry as done by gnssrefl [1]_ [2]_ [3]_.

For a specular reflection from a horizontal surface a distance ``h`` below
the antenna phase centre, the reflected signal lags the direct one by
``psi = 4 pi h sin(e) / lambda`` (``e`` the elevation, ``lambda`` the
carrier wavelength), so the SNR oscillates in ``x = sin(e)`` with the
constant frequency ``2 h / lambda`` cycles per unit ``sin(e)``. Per rising
or setting satellite arc inside an elevation range (default 5-25 deg):

1. SNR in dB-Hz is converted to linear amplitude units,
   ``v = 10^(SNR / 20)`` ("volts/volt", the units of gnssrefl's periodogram
   amplitudes and amplitude threshold);
2. a polynomial in elevation (default order 4, gnssrefl's ``polyV``), the
   direct-signal trend of the antenna gain pattern, is removed; points more
   than 6 robust standard deviations (1.4826 median absolute deviations)
   from it, isolated tracking glitches, are left out (not in gnssrefl);
3. the Lomb-Scargle periodogram of the residual against ``x = sin(e)``
   [4]_ (astropy's implementation [5]_) is searched over the height range
   (default 0.4-8 m); the highest peak at frequency ``f`` (cycles per unit
   ``sin e``) gives ``h = f lambda / 2``. Amplitudes are those of a
   sinusoid, ``2 sqrt(P / N)`` for the ``"psd"``-normalised power ``P`` of
   ``N`` points, as in gnssrefl;
4. (``joint_refinement``, not in gnssrefl) the peak frequency is refined by
   fitting the polynomial and a sinusoid jointly by least squares to the
   SNR in dB, where the oscillation's amplitude (``~8.7 alpha`` dB) does not
   follow the antenna gain, on a local grid of +-0.5 peak widths. A
   polynomial removed on its own absorbs part of an oscillation with few
   cycles per arc and pulls the peak: by up to ~4 cm at ``h`` = 1 m with
   order 4 over 5-25 deg, ~0.3 cm after (noise-free simulation; ~1-3 cm
   after at 0.6 m).

Quality control, as gnssrefl (its ``e1/e2``, ``ediff``, ``minH/maxH``,
``reqAmp`` and ``PkNoise`` settings): enough points; an arc reaching within
``max_edge_gap_deg`` (default 2 deg) of both ends of the elevation range;
a periodogram maximum not on an edge of the searched heights; a peak
amplitude of at least ``min_peak_amplitude`` (default 6 volts/volt,
gnssrefl's default) and a peak-to-noise ratio of at least
``min_peak_to_noise`` (default 3). The noise is the mean periodogram
amplitude over the searched heights more than two peak widths
(``2 / span(sin e)`` in frequency) from the peak; gnssrefl averages over
the whole noise region, peak included, so the same data give a somewhat
higher ratio here (gnssrefl's default threshold is 2.7, with 3-3.5
recommended for snow). The search stops at the Nyquist height
``lambda / (4 median|d sin e|)`` of the arc's sampling when that is below
the range's top. Arcs failing any test are kept, with every reason, and
``accepted`` false.

Amplitude ratio. With the direct amplitude ``A_d`` and the reflected one
``A_r = alpha A_d`` (``alpha`` includes the reflection coefficient and the
antenna gain towards the reflection relative to the direct gain), the
linear SNR is ``|A_d + A_r e^{i psi}|^2 = A_d^2 (1 + alpha^2 + 2 alpha
cos psi)``: an oscillation of amplitude ``2 A_d A_r`` on the level
``A_d^2 + A_r^2``, so ``alpha ~ (oscillation amplitude) / (2 x trend
level)`` for ``alpha << 1``, with a relative error of ``alpha^2`` (9 % at
0.3) if the trend level includes ``A_r^2``. Here the trend is the
polynomial fitted to SNR in dB (jointly with a sinusoid at the peak
frequency): the mean of ``10 log10(1 + alpha^2 + 2 alpha cos psi)`` over a
cycle is exactly 0 for ``alpha < 1``, so that trend is the direct power
``A_d^2``, the relative residual is ``alpha^2 + 2 alpha cos psi``, and
``alpha`` = half the amplitude of the least-squares sinusoid fitted to it
(astropy's ``LombScargle.model_parameters``), without the ``alpha^2``
error. This assumes ``alpha`` constant along the arc (an average where it
varies with elevation), whole cycles of ``psi`` (a few per arc suffice)
and a direct power the polynomial follows; below ~1 m over 5-25 deg the
trend and the oscillation are hard to separate and ``alpha`` is biased.

Not applied: refraction correction, antenna phase-centre offsets, azimuth
masks, a rate-of-change correction for moving surfaces (tides).

References
----------
.. [1] Roesler, C., & Larson, K. M. (2018). Software tools for GNSS
   interferometric reflectometry (GNSS-IR). *GPS Solutions*, 22, 80.
   doi:10.1007/s10291-018-0744-8
.. [2] Larson, K. M., et al. gnssrefl: an open source software package in
   Python for GNSS interferometric reflectometry applications,
   https://github.com/kristinemlarson/gnssrefl (``gnssir`` documentation:
   quality-control settings ``e1``, ``e2``, ``ediff``, ``reqAmp``,
   ``PkNoise``, ``NReg``, ``polyV``).
.. [3] Larson, K. M., & Nievinski, F. G. (2013). GPS snow sensing: results
   from the EarthScope Plate Boundary Observatory. *GPS Solutions*, 17,
   41-52.
.. [4] Press, W. H., et al. (1992). *Numerical Recipes*, 2nd ed., section
   13.8 (Lomb periodogram).
.. [5] VanderPlas, J. T. (2018). Understanding the Lomb-Scargle periodogram.
   *ApJS*, 236, 16 (``astropy.timeseries.LombScargle``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError

__all__ = [
    "DEFAULT_ELEVATION_RANGE_DEG",
    "DEFAULT_HEIGHT_RANGE_M",
    "MAD_TO_SIGMA",
    "ArcHeight",
    "ArcOptions",
    "amplitude_ratio",
    "analyse_arc",
    "arc_height",
]

#: Elevation range of the arcs analysed, degrees (gnssrefl's ``e1``, ``e2``).
DEFAULT_ELEVATION_RANGE_DEG = (5.0, 25.0)
#: Reflector heights searched, metres.
DEFAULT_HEIGHT_RANGE_M = (0.4, 8.0)
#: Scale of the median absolute deviation to a normal standard deviation.
MAD_TO_SIGMA = 1.482602218505602

_NOISE_EXCLUSION_WIDTHS = 2.0  # peak widths (1 / span of sin e) excluded from the noise mean
_FINE_POINTS = 41  # frequencies of the local periodogram grid around the coarse peak
_REFINE_HALF_WIDTH = 0.5  # peak widths searched either side by the joint refinement
_REFINE_POINTS = 21  # frequencies of the joint refinement's grid
_FAST_ABOVE = 200_000  # points x frequencies above which astropy's O(N log N) method is used
_OUTLIER_SIGMAS = 6.0  # robust standard deviations from the trend beyond which a point is dropped


@dataclass(frozen=True)
class ArcOptions:
    """Settings of the single-arc analysis, checked once (parameters of :func:`arc_height`).

    Attributes
    ----------
    elevation_range_deg, height_range_m : tuple of float
        Elevations analysed, degrees; reflector heights searched, m.
    min_points, poly_order : int
        Fewest points of an accepted arc (at least ``poly_order + 3``); polynomial order.
    max_edge_gap_deg, min_peak_amplitude, min_peak_to_noise, oversampling : float
        In degrees; volts/volt; a ratio; frequency-grid points per peak width.
    joint_refinement : bool
        Refine the peak by the joint fit of polynomial and sinusoid.
    """

    elevation_range_deg: tuple[float, float]
    height_range_m: tuple[float, float]
    min_points: int
    max_edge_gap_deg: float
    poly_order: int
    min_peak_amplitude: float
    min_peak_to_noise: float
    oversampling: float
    joint_refinement: bool

    @classmethod
    def build(
        cls,
        *,
        elevation_range_deg: tuple[float, float] = DEFAULT_ELEVATION_RANGE_DEG,
        height_range_m: tuple[float, float] = DEFAULT_HEIGHT_RANGE_M,
        min_points: int = 40,
        max_edge_gap_deg: float = 2.0,
        poly_order: int = 4,
        min_peak_amplitude: float = 6.0,
        min_peak_to_noise: float = 3.0,
        oversampling: float = 10.0,
        joint_refinement: bool = True,
    ) -> ArcOptions:
        """Check and convert the settings (keywords and defaults as :func:`arc_height`).

        Raises
        ------
        InputError
            For inconsistent ranges, a polynomial order outside 0-8 or an
            oversampling below 2.
        """
        e1, e2 = (float(v) for v in elevation_range_deg)
        h1, h2 = (float(v) for v in height_range_m)
        if not 0.0 <= e1 < e2 <= 90.0:
            raise InputError(f"elevation range {e1:g}-{e2:g} deg: expected 0 <= e1 < e2 <= 90")
        if not 0.0 < h1 < h2:
            raise InputError(f"height range {h1:g}-{h2:g} m: expected 0 < h1 < h2")
        order = int(poly_order)
        if not 0 <= order <= 8:
            raise InputError(f"poly_order {order}: expected 0 to 8")
        if not float(oversampling) >= 2.0:
            raise InputError(f"oversampling {oversampling!r}: expected at least 2")
        return cls(
            (e1, e2),
            (h1, h2),
            max(int(min_points), order + 3),
            float(max_edge_gap_deg),
            order,
            float(min_peak_amplitude),
            float(min_peak_to_noise),
            float(oversampling),
            bool(joint_refinement),
        )


@dataclass(frozen=True)
class ArcHeight:
    """Reflector height of one satellite arc.

    Attributes
    ----------
    height_m : float
        Reflector height, m (NaN when no periodogram could be computed).
    peak_amplitude : float
        Amplitude of the periodogram peak, volts/volt (linear SNR units).
    peak_to_noise : float
        Peak amplitude over the mean amplitude away from the peak.
    alpha : float
        Reflected/direct amplitude ratio (module docstring).
    n_points : int
        Observations inside the elevation range.
    n_outliers : int
        Of those, the points left out as outliers.
    elevation_min_deg, elevation_max_deg : float
        Elevations covered, degrees.
    accepted : bool
        Whether every quality-control test passed.
    reason : str
        Why the arc is rejected (tests failed, ``"; "``-separated); empty if accepted.
    """

    height_m: float
    peak_amplitude: float
    peak_to_noise: float
    alpha: float
    n_points: int
    n_outliers: int
    elevation_min_deg: float
    elevation_max_deg: float
    accepted: bool
    reason: str


@dataclass(frozen=True)
class _Peak:
    frequency: float
    amplitude: float
    noise: float
    at_edge: bool


def _legendre(e_deg: NDArray[np.float64], order: int) -> NDArray[np.float64]:
    """Legendre design matrix of the elevations scaled to [-1, 1] (well conditioned)."""
    lo, hi = float(e_deg.min()), float(e_deg.max())
    u = (2.0 * e_deg - (lo + hi)) / (hi - lo) if hi > lo else np.zeros_like(e_deg)
    return np.polynomial.legendre.legvander(u, order)


def _trend(e_deg: NDArray[np.float64], y: NDArray[np.float64], order: int) -> NDArray[np.float64]:
    """Least-squares polynomial in elevation, evaluated at the points."""
    vander = _legendre(e_deg, order)
    return np.asarray(vander @ np.linalg.lstsq(vander, y, rcond=None)[0], dtype=np.float64)


def _vertex(a: NDArray[np.float64], j: int) -> tuple[float, float]:
    """Offset (in grid steps) and value of the parabola through ``a[j-1:j+2]``."""
    if not 0 < j < a.size - 1:
        return 0.0, float(a[j])
    a0, a1, a2 = (float(v) for v in a[j - 1 : j + 2])
    den = a0 - 2.0 * a1 + a2
    if not den < 0.0:
        return 0.0, a1
    d = 0.5 * (a0 - a2) / den
    return d, a1 - 0.25 * (a0 - a2) * d


def _ls_power(
    x: NDArray[np.float64], y: NDArray[np.float64], freq: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Floating-mean Lomb-Scargle power, astropy's ``"psd"`` normalisation (units of ``y^2``).

    Up to :data:`_FAST_ABOVE` points x frequencies, scipy's exact sum
    (:func:`scipy.signal.lombscargle` with ``floating_mean``, equal to
    astropy's ``"cython"`` method to 1e-12: ``tests/validation``); above it,
    astropy's O(N log N) approximation on the regular grid (astropy is then
    imported, ~0.3 s, which a 30 s station day never pays).
    """
    if x.size * freq.size > _FAST_ABOVE:
        from astropy.timeseries import LombScargle

        ls = LombScargle(x, y, normalization="psd")
        return np.asarray(
            ls.power(freq, method="fast", assume_regular_frequency=True), dtype=np.float64
        )
    from scipy.signal import lombscargle

    return np.asarray(lombscargle(x, y, 2.0 * np.pi * freq, floating_mean=True), dtype=np.float64)


def _amplitudes(
    x: NDArray[np.float64], y: NDArray[np.float64], freq: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Sinusoid amplitudes ``2 sqrt(P / N)`` of the psd-normalised power on a regular grid."""
    power = _ls_power(x, y, freq)
    return 2.0 * np.sqrt(np.clip(power, 0.0, None) / x.size)


def _sinusoid_amplitude(x: NDArray[np.float64], y: NDArray[np.float64], freq: float) -> float:
    """Amplitude of the least-squares sinusoid of one frequency fitted with a constant."""
    arg = 2.0 * np.pi * freq * x
    design = np.column_stack([np.ones_like(x), np.sin(arg), np.cos(arg)])
    theta = np.linalg.lstsq(design, y, rcond=None)[0]
    return float(np.hypot(theta[1], theta[2]))


def _peak(
    x: NDArray[np.float64], y: NDArray[np.float64], f_lo: float, f_hi: float, oversampling: float
) -> _Peak:
    """Highest periodogram peak between two frequencies, refined on a local grid."""
    width = 1.0 / float(np.ptp(x))
    freq = np.linspace(f_lo, f_hi, max(int(np.ceil((f_hi - f_lo) * oversampling / width)) + 1, 3))
    amp = _amplitudes(x, y, freq)
    i = int(np.argmax(amp))
    fine = np.linspace(freq[max(i - 1, 0)], freq[min(i + 1, freq.size - 1)], _FINE_POINTS)
    fine_amp = _amplitudes(x, y, fine)
    j = int(np.argmax(fine_amp))
    d, a_pk = _vertex(fine_amp, j)
    f_pk = float(fine[j] + d * (fine[1] - fine[0]))
    away = np.abs(freq - f_pk) > _NOISE_EXCLUSION_WIDTHS * width
    noise = float(np.mean(amp[away])) if np.any(away) else float("nan")
    return _Peak(f_pk, a_pk, noise, i in (0, freq.size - 1))


def _joint_refine(
    e_deg: NDArray[np.float64],
    x: NDArray[np.float64],
    snr_db: NDArray[np.float64],
    f0: float,
    order: int,
) -> float:
    """Frequency of the sinusoid that, fitted jointly with the polynomial, explains most variance.

    On a local grid around ``f0``, the variance a sinusoid explains after
    both it and the data (SNR in dB) are projected off the polynomial space,
    i.e. the drop in the residual sum of squares of the joint least-squares fit.
    """
    q = np.linalg.qr(_legendre(e_deg, order))[0]
    y = snr_db - q @ (q.T @ snr_db)
    half = _REFINE_HALF_WIDTH / float(np.ptp(x))
    freq = np.linspace(f0 - half, f0 + half, _REFINE_POINTS)
    arg = (2.0 * np.pi * freq)[:, None] * x[None, :]
    s, c = np.sin(arg), np.cos(arg)
    s -= (s @ q) @ q.T
    c -= (c @ q) @ q.T
    ss, cc, sc = (np.einsum("ij,ij->i", a, b) for a, b in ((s, s), (c, c), (s, c)))
    ys, yc = s @ y, c @ y
    gain = (cc * ys**2 + ss * yc**2 - 2.0 * sc * ys * yc) / (ss * cc - sc**2)
    j = int(np.argmax(gain))
    return float(freq[j] + _vertex(gain, j)[0] * (freq[1] - freq[0]))


def _trend_beside_sinusoid(
    e_deg: NDArray[np.float64],
    x: NDArray[np.float64],
    y: NDArray[np.float64],
    frequency: float,
    order: int,
) -> NDArray[np.float64]:
    """Return the polynomial part of a joint least-squares fit of polynomial and sinusoid."""
    vander = _legendre(e_deg, order)
    arg = 2.0 * np.pi * frequency * x
    design = np.column_stack([vander, np.sin(arg), np.cos(arg)])
    coef = np.linalg.lstsq(design, y, rcond=1e-10)[0]
    return np.asarray(vander @ coef[: order + 1], dtype=np.float64)


def amplitude_ratio(
    elevation_deg: ArrayLike, snr_dbhz: ArrayLike, frequency: float, *, poly_order: int = 4
) -> float:
    """Reflected/direct amplitude ratio of an arc at a known oscillation frequency.

    The trend, the polynomial in elevation fitted to the SNR in dB jointly
    with a sinusoid in ``x = sin(e)`` at ``frequency``, is the direct power
    ``A_d^2`` (the dB mean of the interference term over a cycle is 0 for
    ``alpha < 1``); ``alpha`` is half the amplitude of the sinusoid (astropy
    ``LombScargle.model_parameters``) in the relative residual
    ``10^((SNR - trend) / 10) - 1 = alpha^2 + 2 alpha cos(psi)``, without the
    ``alpha^2`` error of a trend including ``A_r^2`` (module docstring).

    Parameters
    ----------
    elevation_deg : array_like of float
        Elevations of one rising or setting arc, degrees.
    snr_dbhz : array_like of float
        SNR, dB-Hz, one per elevation.
    frequency : float
        Oscillation frequency, cycles per unit ``sin(e)`` (``2 h / lambda``).
    poly_order : int, optional
        Order of the trend polynomial.

    Returns
    -------
    float
        ``alpha``, clipped to [0, 1]; NaN with fewer than ``poly_order + 3``
        points or less than one cycle of the oscillation in the arc (trend and
        oscillation are then not separable).

    Examples
    --------
    >>> e = np.linspace(5.0, 25.0, 300)
    >>> psi = 4 * np.pi * 2.0 * np.sin(np.radians(e)) / 0.1903
    >>> snr = 40 + e / 2 + 10 * np.log10(1 + 0.2**2 + 2 * 0.2 * np.cos(psi))
    >>> round(amplitude_ratio(e, snr, 2 * 2.0 / 0.1903), 3)
    0.2
    """
    e = np.asarray(elevation_deg, dtype=np.float64)
    s = np.asarray(snr_dbhz, dtype=np.float64)
    x = np.sin(np.radians(e))
    if e.size < poly_order + 3 or not frequency * float(np.ptp(x)) >= 1.0:
        return float("nan")
    rel = 10.0 ** ((s - _trend_beside_sinusoid(e, x, s, frequency, poly_order)) / 10.0) - 1.0
    return min(0.5 * _sinusoid_amplitude(x, rel, frequency), 1.0)


def _coverage_reasons(e: NDArray[np.float64], qc: ArcOptions) -> list[str]:
    out = []
    if e.size < qc.min_points:
        out.append(f"too few points ({e.size} < {qc.min_points})")
    e1, e2 = qc.elevation_range_deg
    if e.size and (e.min() > e1 + qc.max_edge_gap_deg or e.max() < e2 - qc.max_edge_gap_deg):
        out.append(
            f"elevation coverage {e.min():.1f}-{e.max():.1f} deg does not reach within "
            f"{qc.max_edge_gap_deg:g} deg of {e1:g}-{e2:g} deg"
        )
    return out


def _peak_reasons(pk: _Peak, h_m: float, h_top: float, qc: ArcOptions) -> list[str]:
    out = []
    if pk.at_edge or not qc.height_range_m[0] <= h_m <= h_top:  # refinement may step outside
        out.append(
            f"peak at an edge of the height search range {qc.height_range_m[0]:g}-"
            f"{h_top:.3g} m (h = {h_m:.3f} m)"
        )
    if not pk.amplitude >= qc.min_peak_amplitude:
        out.append(f"peak amplitude {pk.amplitude:.2f} < {qc.min_peak_amplitude:g} volts/volt")
    ratio = pk.amplitude / pk.noise
    if not ratio >= qc.min_peak_to_noise:
        out.append(f"peak-to-noise {ratio:.2f} < {qc.min_peak_to_noise:g}")
    return out


def _nyquist_top_m(e: NDArray[np.float64], lam_m: float, h_hi: float) -> float:
    """Top of the height search: the range's, or the arc's Nyquist height if lower."""
    dx = np.abs(np.diff(np.sin(np.radians(e))))
    dx = dx[dx > 0]
    return min(h_hi, lam_m / (4.0 * float(np.median(dx)))) if dx.size else float("nan")


def _screen(
    e: NDArray[np.float64], v: NDArray[np.float64], order: int
) -> tuple[NDArray[np.bool_], NDArray[np.float64]]:
    """Points within ``_OUTLIER_SIGMAS`` robust sigmas of the trend, and their detrended values."""
    resid = v - _trend(e, v, order)
    dev = np.abs(resid - np.median(resid))
    sigma = MAD_TO_SIGMA * float(np.median(dev))
    keep = dev <= _OUTLIER_SIGMAS * sigma if sigma > 0.0 else np.ones(e.size, dtype=bool)
    if np.all(keep) or np.count_nonzero(keep) < order + 3:
        return np.ones(e.size, dtype=bool), resid
    return keep, v[keep] - _trend(e[keep], v[keep], order)


def _in_range(
    el_deg: ArrayLike, snr_dbhz: ArrayLike, e_range: tuple[float, float]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    el = np.asarray(el_deg, dtype=np.float64)
    snr = np.asarray(snr_dbhz, dtype=np.float64)
    if el.shape != snr.shape or el.ndim != 1:
        raise InputError(f"elevations {el.shape} and SNR {snr.shape}: expected equal 1-D shapes")
    sel = np.isfinite(el) & np.isfinite(snr) & (snr > 0.0)
    sel &= (el >= e_range[0]) & (el <= e_range[1])
    return el[sel], snr[sel]


def analyse_arc(
    elevation_deg: ArrayLike, snr_dbhz: ArrayLike, wavelength_m: float, options: ArcOptions
) -> ArcHeight:
    """Reflector height and amplitude ratio of one arc, settings checked once for many arcs.

    Parameters
    ----------
    elevation_deg, snr_dbhz : array_like of float, shape (n,)
        Elevations of one arc, degrees, and SNR, dB-Hz (as :func:`arc_height`).
    wavelength_m : float
        Carrier wavelength of the SNR's signal, m.
    options : ArcOptions
        From :meth:`ArcOptions.build`.

    Returns
    -------
    ArcHeight
        As :func:`arc_height`.

    Raises
    ------
    InputError
        For a non-positive wavelength or unequal shapes.
    """
    if not wavelength_m > 0.0:
        raise InputError(f"wavelength {wavelength_m!r} m: expected a positive number")
    lam_m, qc = float(wavelength_m), options
    e, s = _in_range(elevation_deg, snr_dbhz, qc.elevation_range_deg)
    reasons = _coverage_reasons(e, qc)
    e_lo, e_hi = (float(e.min()), float(e.max())) if e.size else (np.nan, np.nan)
    h_lo, h_top = qc.height_range_m[0], _nyquist_top_m(e, lam_m, qc.height_range_m[1])
    if e.size < qc.poly_order + 3 or not h_top > h_lo:
        if e.size >= qc.poly_order + 3:
            reasons.append(f"sampling too coarse: Nyquist height {h_top:.2f} m")
        nan = float("nan")
        reasons = reasons or ["no usable observations"]
        return ArcHeight(nan, nan, nan, nan, int(e.size), 0, e_lo, e_hi, False, "; ".join(reasons))
    keep, resid = _screen(e, 10.0 ** (s / 20.0), qc.poly_order)
    e, s = e[keep], s[keep]
    x = np.sin(np.radians(e))
    pk = _peak(x, resid, 2.0 * h_lo / lam_m, 2.0 * h_top / lam_m, qc.oversampling)
    f_m = pk.frequency
    if qc.joint_refinement and f_m * float(np.ptp(x)) >= 1.0:  # at least one cycle
        f_m = _joint_refine(e, x, s, f_m, qc.poly_order)
    h_m = f_m * lam_m / 2.0
    reasons += _peak_reasons(pk, h_m, h_top, qc)
    alpha = amplitude_ratio(e, s, f_m, poly_order=qc.poly_order)
    return ArcHeight(
        height_m=h_m,
        peak_amplitude=pk.amplitude,
        peak_to_noise=pk.amplitude / pk.noise,
        alpha=alpha,
        n_points=int(keep.size),
        n_outliers=int(keep.size - e.size),
        elevation_min_deg=e_lo,
        elevation_max_deg=e_hi,
        accepted=not reasons,
        reason="; ".join(reasons),
    )


def arc_height(
    elevation_deg: ArrayLike,
    snr_dbhz: ArrayLike,
    *,
    wavelength_m: float,
    elevation_range_deg: tuple[float, float] = DEFAULT_ELEVATION_RANGE_DEG,
    height_range_m: tuple[float, float] = DEFAULT_HEIGHT_RANGE_M,
    min_points: int = 40,
    max_edge_gap_deg: float = 2.0,
    poly_order: int = 4,
    min_peak_amplitude: float = 6.0,
    min_peak_to_noise: float = 3.0,
    oversampling: float = 10.0,
    joint_refinement: bool = True,
) -> ArcHeight:
    """Reflector height and amplitude ratio of one rising or setting arc.

    Parameters
    ----------
    elevation_deg : array_like of float, shape (n,)
        Elevations of one arc (monotonic in time), degrees; samples outside
        ``elevation_range_deg`` are ignored.
    snr_dbhz : array_like of float, shape (n,)
        SNR, dB-Hz, one per elevation; NaN or non-positive values (not
        tracked) are ignored.
    wavelength_m : float
        Carrier wavelength of the SNR's signal, m.
    elevation_range_deg : tuple of float, optional
        Elevations analysed, degrees.
    height_range_m : tuple of float, optional
        Reflector heights searched, m; also the noise region.
    min_points : int, optional
        Fewest observations in the elevation range for an accepted arc.
    max_edge_gap_deg : float, optional
        The arc must reach within this of both ends of the elevation range, degrees.
    poly_order : int, optional
        Order of the direct-signal polynomial in elevation (gnssrefl: 4).
    min_peak_amplitude : float, optional
        Smallest accepted peak amplitude, volts/volt.
    min_peak_to_noise : float, optional
        Smallest accepted peak-to-noise ratio.
    oversampling : float, optional
        Frequency-grid points per peak width ``1 / span(sin e)`` before the
        local refinement around the highest peak.
    joint_refinement : bool, optional
        Refine the peak by the joint least-squares fit of polynomial and
        sinusoid (module docstring); False keeps the periodogram's peak, as
        gnssrefl does.

    Returns
    -------
    ArcHeight
        Height, peak amplitude and peak-to-noise ratio, ``alpha``, and the
        quality-control verdict with its reasons.

    Raises
    ------
    InputError
        For inconsistent ranges or shapes, a polynomial order outside 0-8 or
        a non-positive wavelength.

    Examples
    --------
    >>> e = np.linspace(5.0, 25.0, 200)
    >>> psi = 4 * np.pi * 2.0 * np.sin(np.radians(e)) / 0.1903
    >>> snr = 40 + e / 2 + 10 * np.log10(1 + 0.2**2 + 2 * 0.2 * np.cos(psi))
    >>> r = arc_height(e, snr, wavelength_m=0.1903)
    >>> round(r.height_m, 2), round(r.alpha, 2), r.accepted
    (2.0, 0.2, True)
    """
    if not wavelength_m > 0.0:
        raise InputError(f"wavelength {wavelength_m!r} m: expected a positive number")
    qc = ArcOptions.build(
        elevation_range_deg=elevation_range_deg,
        height_range_m=height_range_m,
        min_points=min_points,
        max_edge_gap_deg=max_edge_gap_deg,
        poly_order=poly_order,
        min_peak_amplitude=min_peak_amplitude,
        min_peak_to_noise=min_peak_to_noise,
        oversampling=oversampling,
        joint_refinement=joint_refinement,
    )
    return analyse_arc(elevation_deg, snr_dbhz, float(wavelength_m), qc)
