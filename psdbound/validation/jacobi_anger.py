"""Jacobi-Anger expansions of the geometric multipath phase error.

The carrier-phase error of one specular reflection with amplitude ratio
``alpha < 1`` and multipath phase ``psi`` (thesis eq. 2.9) is

    dphi = atan2(alpha sin psi, 1 + alpha cos psi)
         = sum_{m >= 1} c_m sin(m psi),   c_m = (-1)^(m+1) alpha^m / m,

the Taylor series of ``arg(1 + alpha e^{i psi})``. ``order = M`` keeps
``m <= M``: ``M = 1`` is the thesis's first-order form ``alpha sin psi``
(eq. 2.10), ``M = 2`` its second-order form ``alpha sin psi - (alpha^2 / 2)
sin 2 psi`` (eq. 2.15); the omitted part is at most
``sum_{m > M} alpha^m / m`` (``alpha^3 / 3 + ...`` for ``M = 2``).

Two models of how the geometry angle ``theta`` moves:

:func:`rotating_harmonics` (thesis eqs. 2.11-2.16)
    ``theta`` is the expansion variable itself, ``psi = z sin(theta)``
    (ground) or ``z cos(theta)`` (wall), and

        sin(z sin t) =  2 sum_n J_{2n-1}(z) sin((2n-1) t)
        sin(z cos t) = -2 sum_n (-1)^n J_{2n-1}(z) cos((2n-1) t),

    so harmonic ``2n-1`` of ``dphi`` has amplitude
    ``sum_m c_m 2 J_{2n-1}(m z)`` (for ``M = 2``:
    ``alpha (2 J_{2n-1}(z) - alpha J_{2n-1}(2 z))``, thesis eq. 2.16). With
    ``theta = 2 pi f_geom t`` harmonic ``2n-1`` lies at ``(2n-1) f_geom``.
    This is the thesis's model: the angle turns uniformly at the geometry
    rate (a static antenna: once per half sidereal day for GPS).

:func:`oscillation_harmonics`
    ``theta = theta0 + A sin(phi)`` oscillates about ``theta0`` with
    amplitude ``A`` at the phase ``phi = 2 pi f_mode t`` of an aircraft
    attitude mode. ``psi(phi) = z g(theta0 + A sin phi)`` is first expanded
    by Jacobi-Anger into tones ``n phi`` with amplitudes ``2 z J_n(A)``
    times ``sin theta0`` or ``cos theta0``; then ``exp(i m psi)`` is the
    product of the Jacobi-Anger series of every tone, computed by
    convolution. Harmonic ``q`` lies at ``q f_mode``; ``q = 0`` is a constant
    offset. For a ground reflection with ``theta0 = 0`` and small ``A`` this
    is the thesis form ``sin(z_osc sin phi)`` with ``z_osc = z A`` (to
    ``O(A^3)`` in the argument).

Truncation is chosen from ``z`` with a rigorous bound: Kapteyn's
inequality (DLMF 10.14.5) ``|J_k(k x)| <= (x e^{sqrt(1-x^2)} /
(1 + sqrt(1-x^2)))^k`` for ``0 < x <= 1``, and the log of that bound is
concave in ``k``, so for ``K > |z|`` the tail ``sum_{j >= 0} |J_{K + s j}(z)|``
is at most ``b_K / (1 - r^s)`` with ``b_K`` the bound at ``K`` and
``r = z / (K + sqrt(K^2 - z^2))``. The number of terms needed is
``|z| / 2 + O(|z|^(1/3))`` odd harmonics at ``1e-12``: 73 for ``z = 100``,
549 for ``z = 1000``, 1062 (orders up to 2123) for ``z = 2000``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import jv

from psdbound.errors import InputError

__all__ = [
    "Harmonics",
    "bessel_tail_bound",
    "closed_form_power_rad2",
    "oscillation_harmonics",
    "rotating_harmonics",
    "series_coefficients",
    "terms_for_tolerance",
    "truncation_bound",
]

_CHUNK = 128  # harmonics per block when synthesising


@dataclass(frozen=True)
class Harmonics:
    """Line spectrum of a periodic phase error in its geometry angle.

    The signal is ``x(phi) = Re(X_0 + 2 sum_{q >= 1} X_q exp(i q phi))`` for
    the harmonic numbers ``q`` in :attr:`orders`.

    Attributes
    ----------
    orders : ndarray of int64
        Harmonic numbers ``q >= 0`` of the geometry rate (0: constant).
    coefficients : ndarray of complex128
        ``X_q``, rad.
    truncation_bound_rad : float
        Upper bound of ``sup |x_exact - x|`` over the angle for the terms
        left out (Bessel orders and, for oscillations, omitted tones), rad.
        The alpha-order truncation is not included (see ``order``).
    n_terms : int
        Largest Bessel order kept.
    order : int
        Alpha order ``M`` of the phase-error series.
    """

    orders: NDArray[np.int64]
    coefficients: NDArray[np.complex128]
    truncation_bound_rad: float
    n_terms: int
    order: int

    @property
    def amplitude_rad(self) -> NDArray[np.float64]:
        """Peak amplitude per harmonic, rad (``|X_0|`` at ``q = 0``, else ``2 |X_q|``)."""
        a = 2.0 * np.abs(self.coefficients)
        return np.where(self.orders == 0, a / 2.0, a)

    @property
    def power_rad2(self) -> NDArray[np.float64]:
        """Mean-square contribution per harmonic, rad^2 (``X_0^2`` or ``2 |X_q|^2``)."""
        p = 2.0 * np.abs(self.coefficients) ** 2
        return np.where(self.orders == 0, p / 2.0, p)

    @property
    def variance_rad2(self) -> float:
        """Sum of :attr:`power_rad2` over ``q >= 1`` (the constant left out), rad^2."""
        return float(self.power_rad2[self.orders > 0].sum())

    def synthesize(self, phi_rad: ArrayLike) -> NDArray[np.float64]:
        """Evaluate the truncated series at angles ``phi``.

        Parameters
        ----------
        phi_rad : array_like of float
            Geometry angle (rotating model) or oscillation phase, rad.

        Returns
        -------
        ndarray of float64
            ``x(phi)``, rad, same shape as ``phi_rad``.
        """
        phi = np.asarray(phi_rad, dtype=np.float64)
        flat = phi.ravel()
        out = np.zeros(flat.shape, dtype=np.float64)
        w = np.where(self.orders == 0, 1.0, 2.0)
        for i in range(0, self.orders.size, _CHUNK):
            q = self.orders[i : i + _CHUNK].astype(np.float64)
            c = self.coefficients[i : i + _CHUNK] * w[i : i + _CHUNK]
            arg = np.multiply.outer(q, flat)
            out += c.real @ np.cos(arg) - c.imag @ np.sin(arg)
        return out.reshape(phi.shape)


def series_coefficients(alpha: float, order: int) -> NDArray[np.float64]:
    """Coefficients ``c_m`` of ``dphi = sum_m c_m sin(m psi)``, ``m = 1..order``.

    Parameters
    ----------
    alpha : float
        Reflected-to-direct amplitude ratio, ``0 < alpha < 1`` (``alpha = 1``
        is accepted with ``order = 1`` to get the plain Bessel identity).
    order : int
        Alpha order ``M >= 1``.

    Returns
    -------
    ndarray of float64, shape (order,)
        ``(-1)^(m+1) alpha^m / m``.
    """
    _check_alpha_order(alpha, order)
    m = np.arange(1, order + 1, dtype=np.float64)
    return (-1.0) ** (m + 1.0) * float(alpha) ** m / m


def bessel_tail_bound(z: float, k_min: int, *, step: int = 1) -> float:
    """Rigorous bound of ``sum_{j >= 0} |J_{k_min + step j}(z)|``.

    Parameters
    ----------
    z : float
        Bessel argument (any sign).
    k_min : int
        First order of the tail, ``>= 1``.
    step : int, default 1
        Order spacing (2 for odd-only tails).

    Returns
    -------
    float
        The bound (see the module docstring); ``inf`` when
        ``k_min <= |z|``, where Kapteyn's inequality gives nothing useful.
    """
    a = abs(float(z))
    k = int(k_min)
    if a == 0.0:
        return 0.0
    if k <= a:
        return math.inf
    x = a / k
    s = math.sqrt((1.0 - x) * (1.0 + x))
    log_b = k * (s - math.log1p(s) + math.log(x))
    r = x / (1.0 + s)
    return math.exp(log_b) / (1.0 - r**step)


def truncation_bound(z: float, n_terms: int) -> float:
    """Bound of the error of the Jacobi-Anger series truncated after ``n_terms``.

    Parameters
    ----------
    z : float
        Bessel argument.
    n_terms : int
        Number ``N`` of odd harmonics kept (orders ``1, 3, ..., 2N - 1``).

    Returns
    -------
    float
        ``2 sum_{n > N} |J_{2n-1}(z)|``, an upper bound of
        ``sup_t |sin(z sin t) - S_N(t)|`` (and likewise for ``sin(z cos t)``).
    """
    return 2.0 * bessel_tail_bound(z, 2 * int(n_terms) + 1, step=2)


def terms_for_tolerance(z: float, *, tol: float = 1e-12) -> int:
    """Smallest number of odd harmonics whose truncation error is ``<= tol``.

    Parameters
    ----------
    z : float
        Bessel argument.
    tol : float, default 1e-12
        Tolerance on :func:`truncation_bound`, rad (> 0).

    Returns
    -------
    int
        ``N >= 1`` with ``truncation_bound(z, N) <= tol``.
    """
    if not tol > 0.0:
        raise InputError(f"truncation tolerance must be > 0, got {tol}")
    lo = max(1, int(math.floor((abs(z) - 1.0) / 2.0)) + 1)  # first with 2N + 1 > |z|
    if truncation_bound(z, lo) <= tol:
        return lo
    hi = lo + 1
    while truncation_bound(z, hi) > tol:
        hi = lo + 2 * (hi - lo)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if truncation_bound(z, mid) <= tol:
            hi = mid
        else:
            lo = mid
    return hi


def _first_order_for_tail(z: float, eps: float) -> int:
    """Smallest ``K >= 1`` with ``bessel_tail_bound(z, K + 1) <= eps``."""
    lo = int(math.floor(abs(z)))  # K + 1 > |z|
    lo = max(lo, 0)
    if bessel_tail_bound(z, lo + 1) <= eps:
        return max(lo, 1)
    hi = lo + 1
    while bessel_tail_bound(z, hi + 1) > eps:
        hi = lo + 2 * (hi - lo)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if bessel_tail_bound(z, mid + 1) <= eps:
            hi = mid
        else:
            lo = mid
    return max(hi, 1)


def _check_alpha_order(alpha: float, order: int) -> None:
    if int(order) != order or order < 1:
        raise InputError(f"expansion order must be an integer >= 1, got {order}")
    a = float(alpha)
    if not (math.isfinite(a) and 0.0 < a <= 1.0) or (a == 1.0 and order > 1):
        raise InputError(
            f"reflection amplitude ratio alpha must be in (0, 1), got {alpha} "
            "(alpha = 1 only with order 1)"
        )


def _check_kind(kind: str) -> None:
    if kind not in ("ground", "wall"):
        raise InputError(f"unknown reflection geometry {kind!r}; expected 'ground' or 'wall'")


def rotating_harmonics(
    z: float,
    *,
    kind: str,
    alpha: float = 1.0,
    order: int = 1,
    tol: float = 1e-12,
) -> Harmonics:
    """Harmonics of ``dphi`` in a uniformly turning geometry angle (thesis model).

    Parameters
    ----------
    z : float
        Bessel argument, rad (:meth:`Reflection.z
        <psdbound.validation.geometry.Reflection.z>`).
    kind : {"ground", "wall"}
        ``psi = z sin(theta)`` or ``z cos(theta)``.
    alpha : float, default 1.0
        Amplitude ratio. With the defaults (``alpha = 1``, ``order = 1``)
        the series is the plain identity ``sin(z sin t)`` / ``sin(z cos t)``.
    order : int, default 1
        Alpha order of the phase-error series (1: eq. 2.12, 2: eq. 2.16).
    tol : float, default 1e-12
        Bound on the truncation error of the series, rad; the number of
        odd harmonics is chosen from ``order * z`` to meet it.

    Returns
    -------
    Harmonics
        Odd orders ``1, 3, ..., 2N - 1``.
    """
    _check_kind(kind)
    c = series_coefficients(alpha, order)
    weight = float(np.abs(c).sum())
    n = terms_for_tolerance(order * z, tol=tol / weight)
    k = 2 * np.arange(1, n + 1, dtype=np.int64) - 1
    a = np.zeros(n, dtype=np.float64)
    for m, cm in enumerate(c, start=1):
        a += cm * 2.0 * jv(k, m * z)
    if kind == "ground":  # a_k sin(k t) = 2 Re(-i a_k / 2 e^{ikt})
        coef = -0.5j * a
    else:  # a_k (-1)^((k-1)/2) cos(k t)
        coef = 0.5 * a * np.where(((k - 1) // 2) % 2 == 0, 1.0, -1.0) + 0j
    bound = sum(abs(cm) * truncation_bound(m * z, n) for m, cm in enumerate(c, start=1))
    return Harmonics(k, coef.astype(np.complex128), float(bound), int(k[-1]), int(order))


def closed_form_power_rad2(z: float, *, alpha: float = 1.0, order: int = 1) -> float:
    """Exact mean square of the alpha-truncated series in the rotating model.

    ``mean_t[sin(a z sin t) sin(b z sin t)] = (J_0((a - b) z) - J_0((a + b) z)) / 2``,
    so the power is ``sum_{a,b} c_a c_b (J_0((a-b) z) - J_0((a+b) z)) / 2``;
    for ``order = 1``: ``alpha^2 (1 - J_0(2 z)) / 2``, the closed form of
    ``sum_n (2 alpha J_{2n-1}(z))^2 / 2``. Used to check truncation.

    Parameters
    ----------
    z : float
        Bessel argument, rad.
    alpha : float, default 1.0
        Amplitude ratio.
    order : int, default 1
        Alpha order.

    Returns
    -------
    float
        Mean square over a turn of the geometry angle, rad^2 (same for the
        ground and wall forms).
    """
    c = series_coefficients(alpha, order)
    m = np.arange(1, order + 1, dtype=np.float64)
    d = np.subtract.outer(m, m) * z
    s = np.add.outer(m, m) * z
    return float(0.5 * (np.outer(c, c) * (jv(0, d) - jv(0, s))).sum())


def oscillation_harmonics(
    z: float,
    *,
    kind: str,
    theta0_rad: float,
    amplitude_rad: float,
    alpha: float = 1.0,
    order: int = 1,
    tol: float = 1e-12,
) -> Harmonics:
    """Harmonics of ``dphi`` when the geometry angle oscillates (aircraft mode).

    ``theta(phi) = theta0 + A sin(phi)``, ``psi = z sin(theta)`` (ground) or
    ``z cos(theta)`` (wall); see the module docstring for the composition
    of Jacobi-Anger expansions.

    Parameters
    ----------
    z : float
        Bessel argument of the geometry, rad (``4 pi D / lambda`` or the
        thesis's ``2 D / lambda``).
    kind : {"ground", "wall"}
        Reflection geometry.
    theta0_rad : float
        Mean angle of arrival over the oscillation, rad.
    amplitude_rad : float
        Oscillation amplitude ``A`` of the angle, rad (> 0).
    alpha : float, default 1.0
        Amplitude ratio.
    order : int, default 1
        Alpha order of the phase-error series.
    tol : float, default 1e-12
        Target bound on the truncation error, rad.

    Returns
    -------
    Harmonics
        Orders ``0, 1, ..., Q`` of the oscillation frequency.
    """
    _check_kind(kind)
    c = series_coefficients(alpha, order)
    amp = float(amplitude_rad)
    if not (math.isfinite(amp) and amp > 0.0):
        raise InputError(f"oscillation amplitude must be > 0 rad, got {amplitude_rad}")
    th0 = float(theta0_rad)
    weight = float(sum(abs(cm) * m for m, cm in enumerate(c, start=1)))
    # tones of psi / z: mean + sum_n (a_n sin n phi + b_n cos n phi)
    eps_tone = tol / (4.0 * weight * max(abs(z), 1.0))
    n_tones = _first_order_for_tail(amp, eps_tone / 2.0)
    omitted_phase = 2.0 * abs(z) * bessel_tail_bound(amp, n_tones + 1)
    n = np.arange(0, n_tones + 1)
    jn = jv(n, amp)
    if kind == "ground":
        mean = jn[0] * math.sin(th0)
        odd_amp, even_amp = 2.0 * math.cos(th0), 2.0 * math.sin(th0)
    else:
        mean = jn[0] * math.cos(th0)
        odd_amp, even_amp = -2.0 * math.sin(th0), 2.0 * math.cos(th0)
    tones = [(k, float(jn[k] * (odd_amp if k % 2 else even_amp)), bool(k % 2)) for k in n[1:]]
    tones = [t for t in tones if t[1] != 0.0]
    n_factors = max(len(tones), 1)

    total_x = np.zeros(1, dtype=np.complex128)
    bound = 0.0
    n_terms = 0
    for m, cm in enumerate(c, start=1):
        seq = np.ones(1, dtype=np.complex128)
        err_m = m * omitted_phase
        for step, t_amp, is_sin in tones:
            x = m * z * t_amp
            kmax = _first_order_for_tail(x, tol / (8.0 * n_factors * weight))
            n_terms = max(n_terms, kmax)
            err_m += 2.0 * bessel_tail_bound(x, kmax + 1)
            kk = np.arange(0, kmax + 1)
            jpos = jv(kk, x)
            jneg = jpos * np.where(kk % 2 == 0, 1.0, -1.0)  # J_{-k} = (-1)^k J_k
            vals = np.concatenate([jneg[:0:-1], jpos]).astype(np.complex128)
            if not is_sin:  # exp(i x cos) = sum i^k J_k(x) e^{ik.}
                kall = np.arange(-kmax, kmax + 1)
                vals *= 1j ** (kall % 4)
            tone_seq = np.zeros(2 * kmax * step + 1, dtype=np.complex128)
            tone_seq[::step] = vals
            seq = np.convolve(seq, tone_seq)
        seq *= np.exp(1j * m * z * mean)
        half = (seq.size - 1) // 2
        cq = seq[half:]  # C_q, q >= 0
        cmq = seq[half::-1]  # C_{-q}
        s = (cq - np.conj(cmq)) / 2j  # coefficients of sin(m psi)
        if s.size > total_x.size:
            total_x = np.concatenate([total_x, np.zeros(s.size - total_x.size, np.complex128)])
        total_x[: s.size] += cm * s
        bound += abs(cm) * err_m
    orders = np.arange(total_x.size, dtype=np.int64)
    return Harmonics(orders, total_x, float(bound), int(n_terms), int(order))
