"""LADGNSS / GBAS error budget and vertical protection level (seed 004).

Per satellite ``i`` at elevation ``theta_i`` the corrected-range variance is
(seed 004 eq. 13) ``sigma_i^2 = sigma_gnd^2 + sigma_air^2 + sigma_iono^2 +
sigma_trop^2``:

ground (eqs. 16, 18, 19, derived again below)
    ``xi(tau_gnd)^2 k_f^2 sigma_mp*^2 + sigma_SIS^2`` with, for ``M``
    reference receivers whose multipath is correlated with coefficient
    ``rho`` and ``N`` satellites in the correction,
    ``sigma_mp*^2 = c_rho / (M N^2) * ((N - 1)^2 g_i^2 + sum_{j != i} g_j^2)``.
    The exact variance of the receiver average minus the satellite average
    has ``c_rho = 1 + rho (M - 1)``; the seed prints ``1 + 2 rho (M - 1)``
    (``rho_formula="seed"``). ``g`` is the per-receiver GAD curve
    ``a0 + a1 exp(-theta / theta0)`` and ``sigma_SIS`` its ``a2`` term
    (RTCA DO-245A [RTCADO245A]_; the split is our assumption, the seed does
    not print its GAD_mp / GAD_n curves).
airborne (eq. 21)
    ``xi(tau_air)^2 k_f^2 (sigma_mp,air^2 + sigma_n,air^2)``, AAD-A curves of
    :mod:`psdbound.aviation.airborne`.
ionosphere (eqs. 22-27)
    single frequency: ``sqrt((F_pp s_vig (x + 2 tau_air v))^2 + (2 s_rate
    |tau_gnd - tau_air|)^2)``; divergence free ``F_pp s_vig x``; iono free 0;
    times ``(f_L1 / f_L5)^2`` (the seed's 1.79) for L5-based processing.
troposphere (eqs. 28-30)
    ``sigma_N h0 1e-6 / sqrt(0.002 + sin^2 theta) (1 - exp(-dh / h0))`` (the
    seed prints ``exp(+dh / h0)``, a sign slip: the standard form decays)
    combined with ``F_pp s_trop x``.

``k_f`` is 1 (L1-based), 0.7 (L5-based, seed 004 Table 2), or the iono-free
multiplier (:func:`iono_free_multiplier`, 2.4267 for L1/L5 with the Table 2
ratio). ``xi`` is :func:`psdbound.aviation.smoothing.smoothing_time_ratio`
(exact by default; ``xi_formula="seed"`` reproduces seed 004 Table 1).

The VPL (eq. 10, with the square root the seed's print omits) is
``K_ffmd sqrt(sum S_vert,i^2 sigma_i^2)``, ``S`` the weighted-least-squares
projection ``(G^T W G)^-1 G^T W``, ``W = diag(sigma_i^-2)``; the ephemeris
VPL (eqs. 11-12) is ``max_k |S_vert,k| x P_k + K_md_e sqrt(...)``, with the
ephemeris multiplier ``K_md_e`` a required input (broadcast by the ground
station; not the H1 ``K_md`` table). Paired-overbound biases add ``sum
|S_vert,i| b_i`` to both. Constants and their sources:
:mod:`psdbound.aviation.standards`.
"""

from __future__ import annotations

import functools
import inspect
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.stats import norm

from psdbound.aviation.airborne import (
    F_L1_HZ,
    F_L5_HZ,
    sigma_multipath_airborne_m,
    sigma_noise_airborne_m,
)
from psdbound.aviation.smoothing import smoothing_time_ratio
from psdbound.aviation.standards import (
    GAD_PARAMETERS,
    K_FFMD,
    K_MD_E_SOURCE,
    K_TABLE_SOURCE,
    L5_TO_L1_SIGMA,
    P_EPH,
    sources,
)
from psdbound.errors import InputError

__all__ = [
    "PROCESSES",
    "BudgetTerms",
    "budget_document",
    "budget_report",
    "error_budget",
    "ground_sigma_pr_m",
    "iono_free_multiplier",
    "los_from_az_el",
    "multipliers",
    "obliquity_factor",
    "projection_matrix",
    "vpl",
]

PROCESSES = ("SF", "DF", "IF")
R_EARTH_M = 6378136.3
H_IONO_M = 350e3


@functools.lru_cache(maxsize=64)
def _xi(tau_gnd_s: float, tau_air_s: float, tau_corr_s: float, formula: str) -> tuple[float, float]:
    """``xi`` of the ground and airborne smoothing (cached: a VPL series asks per epoch)."""
    g, a = smoothing_time_ratio([tau_gnd_s, tau_air_s], tau_corr_s=tau_corr_s, formula=formula)
    return float(g), float(a)


def _el(elevation_deg: ArrayLike) -> NDArray[np.float64]:
    el = np.asarray(elevation_deg, dtype=float).reshape(-1)
    if el.size == 0 or not np.isfinite(el).all() or (el <= 0).any() or (el > 90).any():
        raise InputError("elevations must be finite, in (0, 90] degrees")
    return el


def ground_sigma_pr_m(elevation_deg: ArrayLike, designator: str = "B") -> NDArray[np.float64]:
    """Per-receiver GAD curve ``a0 + a1 exp(-theta / theta0)``, metres (100 s smoothing).

    Parameters
    ----------
    elevation_deg : array_like
        Elevations, degrees.
    designator : {"A", "B", "C"}, default "B"
        Ground accuracy designator.

    Returns
    -------
    ndarray
    """
    if designator not in GAD_PARAMETERS:
        raise InputError(f"unknown GAD {designator!r}; choose from {sorted(GAD_PARAMETERS)}")
    a0, a1, th0, _ = GAD_PARAMETERS[designator]
    el = _el(elevation_deg)
    g = a0 + a1 * np.exp(-el / th0)
    if designator == "C":
        g = np.where(el < 35.0, 0.24, g)
    return g


def obliquity_factor(elevation_deg: ArrayLike) -> NDArray[np.float64]:
    """Thin-shell ionospheric obliquity ``F_pp = (1 - (R cos theta / (R + h))^2)^-1/2``.

    ``R = 6378.1363 km``, ``h = 350 km`` (DO-245A).

    Parameters
    ----------
    elevation_deg : array_like
        Elevations, degrees.

    Returns
    -------
    ndarray
        Dimensionless, 1 at zenith.
    """
    c = R_EARTH_M * np.cos(np.radians(_el(elevation_deg))) / (R_EARTH_M + H_IONO_M)
    return 1.0 / np.sqrt(1.0 - c * c)


def iono_free_multiplier(
    sigma_ratio_y_to_x: float = L5_TO_L1_SIGMA.value,
    f_x_hz: float = F_L1_HZ,
    f_y_hz: float = F_L5_HZ,
) -> float:
    """Iono-free noise multiplier ``sqrt((1 - 1/a)^2 + r^2 / a^2)``, ``a = 1 - f_x^2 / f_y^2``.

    Seed 004 eq. (9) without the ``sqrt(T / 2 tau)`` smoothing factor, for a
    code sigma on frequency ``y`` that is ``r`` times the one on ``x``.

    Parameters
    ----------
    sigma_ratio_y_to_x : float, default 0.7
        ``sigma_y / sigma_x`` (seed 004 Table 2: L5 = 0.7 L1).
    f_x_hz, f_y_hz : float
        Frequencies, Hz (default L1, L5).

    Returns
    -------
    float
    """
    if not (f_x_hz > 0 and f_y_hz > 0) or f_x_hz == f_y_hz or sigma_ratio_y_to_x < 0:
        raise InputError("need two different positive frequencies and a ratio >= 0")
    a = 1.0 - (f_x_hz / f_y_hz) ** 2
    return math.sqrt((1.0 - 1.0 / a) ** 2 + (sigma_ratio_y_to_x / a) ** 2)


def los_from_az_el(azimuth_deg: ArrayLike, elevation_deg: ArrayLike) -> NDArray[np.float64]:
    """Build unit line-of-sight vectors receiver -> satellite in East-North-Up.

    Parameters
    ----------
    azimuth_deg, elevation_deg : array_like, shape (n,)
        Azimuth (from north, clockwise) and elevation, degrees.

    Returns
    -------
    ndarray, shape (n, 3)
    """
    az = np.radians(np.asarray(azimuth_deg, dtype=float).reshape(-1))
    el = np.radians(np.asarray(elevation_deg, dtype=float).reshape(-1))
    if az.size != el.size or not (np.isfinite(az).all() and np.isfinite(el).all()):
        raise InputError("azimuth and elevation must be finite and of the same length")
    return np.column_stack([np.cos(el) * np.sin(az), np.cos(el) * np.cos(az), np.sin(el)])


def projection_matrix(los_enu: ArrayLike, sigma_m: ArrayLike) -> NDArray[np.float64]:
    """Weighted-least-squares projection ``S = (G^T W G)^-1 G^T W``, shape (4, n).

    Rows: East, North, Up, clock; ``G_i = [-u_i, 1]``, ``W = diag(sigma^-2)``.

    Parameters
    ----------
    los_enu : array_like, shape (n, 3)
        Unit line-of-sight vectors (n >= 4).
    sigma_m : array_like, shape (n,)
        Range error sigmas, metres (> 0).

    Returns
    -------
    ndarray, shape (4, n)
    """
    u = np.asarray(los_enu, dtype=float)
    s = np.asarray(sigma_m, dtype=float).reshape(-1)
    if u.ndim != 2 or u.shape[1] != 3 or u.shape[0] < 4 or s.size != u.shape[0]:
        raise InputError("need n >= 4 line-of-sight vectors (n, 3) and n sigmas")
    if not (s > 0).all():
        raise InputError("sigmas must be > 0")
    g = np.column_stack([-u, np.ones(u.shape[0])])
    w = 1.0 / s**2
    gtw = g.T * w
    a = gtw @ g
    if np.linalg.cond(a) > 1e12:
        raise InputError("singular geometry: the satellites do not fix position and clock")
    return np.linalg.solve(a, gtw)


@dataclass(frozen=True)
class BudgetTerms:
    """Per-satellite sigmas of the LADGNSS budget, metres.

    Attributes
    ----------
    elevation_deg : ndarray
        Elevations, degrees.
    ground, air, iono, trop : ndarray
        Term sigmas, metres.
    """

    elevation_deg: NDArray[np.float64]
    ground: NDArray[np.float64]
    air: NDArray[np.float64]
    iono: NDArray[np.float64]
    trop: NDArray[np.float64]

    @property
    def total(self) -> NDArray[np.float64]:
        """Root-sum-square of the four terms, metres (seed 004 eq. 13)."""
        return np.sqrt(self.ground**2 + self.air**2 + self.iono**2 + self.trop**2)


def error_budget(
    elevation_deg: ArrayLike,
    *,
    process: str = "SF",
    base_frequency: str = "L1",
    tau_gnd_s: float = 100.0,
    tau_air_s: float = 100.0,
    tau_corr_s: float = 30.0,
    xi_formula: str = "exact",
    gad: str = "B",
    n_receivers: int = 3,
    rho: float = 0.1,
    rho_formula: str = "exact",
    x_air_m: float = 5000.0,
    v_air_mps: float = 15.0,
    sigma_vig: float = 4e-6,
    sigma_iono_rate_mps: float = 0.004,
    dh_m: float = 0.0,
    sigma_n_refractivity: float = 23.0,
    h0_m: float = 15730.0,
    sigma_trop_nonnominal: float = 5e-6,
) -> BudgetTerms:
    """Per-satellite ground, airborne, ionosphere and troposphere sigmas (seed 004).

    Defaults are seed 004 Table 4 (first scenario: GAD-B, ``rho = 0.1``,
    ``M = 3``, ``x_air = 5 km``, ``v_air = 15 m/s``, ``sigma_vig = 4 mm/km``).

    Parameters
    ----------
    elevation_deg : array_like, shape (N,)
        Elevations of all satellites of the epoch, degrees (the ground term
        depends on the whole set).
    process : {"SF", "DF", "IF"}, default "SF"
        Single-frequency, divergence-free or iono-free smoothing.
    base_frequency : {"L1", "L5"}, default "L1"
        Frequency of the code (SF, DF): L5 scales noise by 0.7, iono by 1.79.
    tau_gnd_s, tau_air_s : float, default 100
        Ground and airborne smoothing time constants, seconds.
    tau_corr_s : float, default 30
        Code-error correlation time in ``xi``, seconds.
    xi_formula : {"exact", "seed", "steady_state"}, default "exact"
        Passed to :func:`~psdbound.aviation.smoothing.smoothing_time_ratio`:
        ``"exact"`` is the variance of the truncated smoother seed 004 defines;
        ``"seed"`` its eq. (A6) as printed (double-counts the off-diagonal
        terms, up to 1.6 % low here), selectable to reproduce its Table 1.
    gad : {"A", "B", "C"}, default "B"
    n_receivers : int, default 3
        Reference receivers ``M``.
    rho : float, default 0.1
        Ground multipath correlation between receivers.
    rho_formula : {"exact", "seed"}, default "exact"
        ``1 + rho (M - 1)`` or the seed's ``1 + 2 rho (M - 1)``.
    x_air_m : float, default 5000
        User to reference distance, metres.
    v_air_mps : float, default 15
        Horizontal user speed, m/s.
    sigma_vig : float, default 4e-6
        Vertical ionospheric gradient sigma, m/m (4 mm/km).
    sigma_iono_rate_mps : float, default 0.004
        Ionospheric delay-rate sigma, m/s.
    dh_m : float, default 0
        User height above the reference, metres.
    sigma_n_refractivity : float, default 23
        Refractivity uncertainty ``sigma_N`` (N units).
    h0_m : float, default 15730
        Tropospheric scale height, metres.
    sigma_trop_nonnominal : float, default 5e-6
        Anomalous tropospheric gradient sigma, m/m (5 mm/km).

    Returns
    -------
    BudgetTerms
    """
    el = _el(elevation_deg)
    if process not in PROCESSES:
        raise InputError(f"unknown process {process!r}; choose from {PROCESSES}")
    if base_frequency not in ("L1", "L5"):
        raise InputError(f"base_frequency must be 'L1' or 'L5', got {base_frequency!r}")
    if n_receivers < 1 or not 0 <= rho <= 1 or rho_formula not in ("exact", "seed"):
        raise InputError("need n_receivers >= 1, 0 <= rho <= 1, rho_formula 'exact' or 'seed'")
    n = el.size
    if process == "IF":
        k_f, k_iono = iono_free_multiplier(), 0.0
    elif base_frequency == "L5":
        k_f, k_iono = L5_TO_L1_SIGMA.value, (F_L1_HZ / F_L5_HZ) ** 2
    else:
        k_f, k_iono = 1.0, 1.0
    xi_g, xi_a = _xi(float(tau_gnd_s), float(tau_air_s), float(tau_corr_s), xi_formula)
    g = ground_sigma_pr_m(el, gad)
    c_rho = 1.0 + (2.0 if rho_formula == "seed" else 1.0) * rho * (n_receivers - 1)
    others = np.sum(g**2) - g**2
    mp_star2 = c_rho / (n_receivers * n**2) * ((n - 1) ** 2 * g**2 + others)
    sis = GAD_PARAMETERS[gad][3]
    ground = np.sqrt(xi_g**2 * k_f**2 * mp_star2 + sis**2)
    air = xi_a * k_f * np.hypot(sigma_multipath_airborne_m(el), sigma_noise_airborne_m(el))
    fpp = obliquity_factor(el)
    if process == "SF":
        sg = fpp * sigma_vig * (x_air_m + 2.0 * tau_air_s * v_air_mps)
        tg = 2.0 * sigma_iono_rate_mps * abs(tau_gnd_s - tau_air_s)
        iono = k_iono * np.hypot(sg, tg)
    else:
        iono = k_iono * fpp * sigma_vig * x_air_m
    s2 = np.sin(np.radians(el)) ** 2
    nominal = sigma_n_refractivity * h0_m * 1e-6 / np.sqrt(0.002 + s2)
    nominal = nominal * (1.0 - math.exp(-dh_m / h0_m))
    trop = np.hypot(nominal, fpp * sigma_trop_nonnominal * x_air_m)
    return BudgetTerms(el, ground, air, np.broadcast_to(iono, el.shape).copy(), trop)


def multipliers(
    *, n_receivers: int = 3, k_ffmd: float | None = None, k_md_e: float | None
) -> dict[str, dict[str, Any]]:
    """Return the VPL multipliers used, each with its value and source.

    Parameters
    ----------
    n_receivers : int, default 3
        Reference receivers ``M`` (selects the tabulated ``K_ffmd``).
    k_ffmd : float, optional
        User value of the fault-free multiplier (default: the table).
    k_md_e : float
        Ephemeris missed-detection multiplier, user-supplied (> 0).

    Returns
    -------
    dict
        ``{"k_ffmd": {"value", "source"}, "k_md_e": {"value", "source",
        "p_md_e_two_sided_gaussian"}}``; the last is ``2 Q(K_md_e)``, the
        missed-detection probability a zero-mean Gaussian test statistic
        would give (stated for orientation, not a derivation of the standard).

    Raises
    ------
    InputError
        No ``k_md_e``, a multiplier <= 0, or no tabulated ``K_ffmd`` for ``M``.
    """
    if k_md_e is None:
        raise InputError(
            "k_md_e (CLI --k-md-e) is required: the ephemeris missed-detection multiplier is "
            "broadcast by the ground station (Message Type 2) and no standard fixes its value; "
            "give the value of the station you analyse"
        )
    if not (math.isfinite(k_md_e) and k_md_e > 0):
        raise InputError(f"k_md_e must be a number > 0, got {k_md_e}")
    if k_ffmd is None:
        if n_receivers not in K_FFMD:
            raise InputError(
                f"no tabulated K_ffmd for M = {n_receivers} reference receivers "
                f"(table: M = {sorted(K_FFMD)}); pass k_ffmd"
            )
        kf: dict[str, Any] = {
            "value": K_FFMD[n_receivers],
            "source": f"table for M = {n_receivers}: {K_TABLE_SOURCE}",
        }
    elif not (math.isfinite(k_ffmd) and k_ffmd > 0):
        raise InputError(f"k_ffmd must be a number > 0, got {k_ffmd}")
    else:
        kf = {"value": float(k_ffmd), "source": "user-supplied"}
    p_md = float(2.0 * norm.sf(k_md_e))
    return {
        "k_ffmd": kf,
        "k_md_e": {
            "value": float(k_md_e),
            "source": K_MD_E_SOURCE,
            "p_md_e_two_sided_gaussian": p_md,
        },
    }


def vpl(
    los_enu: ArrayLike,
    sigma_m: ArrayLike,
    *,
    k_md_e: float | None,
    n_receivers: int = 3,
    k_ffmd: float | None = None,
    x_air_m: float = 0.0,
    p_eph: float = P_EPH.value,
    bias_m: ArrayLike | None = None,
) -> tuple[float, float]:
    """Fault-free and ephemeris vertical protection levels, metres.

    ``VPL_H0 = K_ffmd sigma_v + B`` and ``VPL_eph = max_k |S_vert,k| x_air P_k
    + K_md_e sigma_v + B`` with ``sigma_v = sqrt(sum S_vert,i^2 sigma_i^2)``
    and ``B = sum |S_vert,i| b_i`` the worst-case vertical shift of paired-
    overbound biases ``b_i`` (0 without ``bias_m``; [Rife2006]_: the position
    error of a linear estimator is paired-overbounded by ``N(+-B, sigma_v)``).

    Parameters
    ----------
    los_enu : array_like, shape (n, 3)
        Unit line-of-sight vectors (ENU).
    sigma_m : array_like, shape (n,)
        Total range sigmas (overbounding sigmas), metres.
    k_md_e : float
        Ephemeris missed-detection multiplier ``K_md_e`` (required: broadcast
        by the ground station, no standard value; see
        :data:`~psdbound.aviation.standards.K_MD_E_SOURCE`).
    n_receivers : int, default 3
        Selects ``K_ffmd`` from :data:`~psdbound.aviation.standards.K_FFMD`.
    k_ffmd : float, optional
        Override the tabulated ``K_ffmd``.
    x_air_m : float, default 0
        User to reference distance, metres.
    p_eph : float, default 0.00018
        Ephemeris decorrelation parameter, m/m (seed 004).
    bias_m : array_like, shape (n,), optional
        Paired-overbound bias ``b_i >= 0`` of each range, metres.

    Returns
    -------
    vpl_h0, vpl_eph : float
        Metres; the user applies the larger.
    """
    used = multipliers(n_receivers=n_receivers, k_ffmd=k_ffmd, k_md_e=k_md_e)
    kf = float(used["k_ffmd"]["value"])
    s = np.asarray(sigma_m, dtype=float).reshape(-1)
    sv = projection_matrix(los_enu, s)[2]
    sd = float(np.sqrt(np.sum(sv**2 * s**2)))
    shift = 0.0
    if bias_m is not None:
        b = np.asarray(bias_m, dtype=float).reshape(-1)
        if b.size != s.size or not (np.isfinite(b).all() and (b >= 0).all()):
            raise InputError(f"bias_m must hold {s.size} finite values >= 0 m, one per range")
        shift = float(np.sum(np.abs(sv) * b))
    km = float(k_md_e)  # type: ignore[arg-type]  # checked by multipliers()
    eph = float(np.max(np.abs(sv)) * x_air_m * p_eph + km * sd) + shift
    return kf * sd + shift, eph


def budget_report(
    azimuth_deg: ArrayLike,
    elevation_deg: ArrayLike,
    *,
    k_md_e: float | None,
    n_receivers: int = 3,
    k_ffmd: float | None = None,
    **options: object,
) -> str:
    """Per-satellite budget table, the two VPLs and the multipliers with their sources, as text.

    Parameters
    ----------
    azimuth_deg, elevation_deg : array_like, shape (n,)
        Satellite azimuths and elevations, degrees (n >= 4).
    k_md_e : float
        Ephemeris missed-detection multiplier (required, see :func:`vpl`).
    n_receivers : int, default 3
        Reference receivers ``M``.
    k_ffmd : float, optional
        Override the tabulated ``K_ffmd``.
    **options
        Passed to :func:`error_budget` (``x_air_m`` also to :func:`vpl`).

    Returns
    -------
    str
    """
    doc = budget_document(
        azimuth_deg, elevation_deg, k_md_e=k_md_e, n_receivers=n_receivers, k_ffmd=k_ffmd, **options
    )
    rows = [f"{'el deg':>7} {'gnd m':>8} {'air m':>8} {'iono m':>8} {'trop m':>8} {'total m':>8}"]
    terms = ("ground_m", "air_m", "iono_m", "trop_m", "total_m")
    for sat in doc["satellites"]:  # type: ignore[attr-defined]
        rows.append(f"{sat['elevation_deg']:>7.1f} " + " ".join(f"{sat[k]:>8.4f}" for k in terms))
    h0, eph = doc["vpl_h0_m"], doc["vpl_eph_m"]
    rows.append(f"VPL_H0 = {h0:.3f} m, VPL_eph = {eph:.3f} m, VPL = {max(h0, eph):.3f} m")
    k = doc["multipliers"]
    rows.append(f"K_ffmd = {k['k_ffmd']['value']:.3f} ({k['k_ffmd']['source']})")
    ke = k["k_md_e"]
    rows.append(
        f"K_md_e = {ke['value']:.3f} (two-sided Gaussian P_md "
        f"{ke['p_md_e_two_sided_gaussian']:.2g}; {ke['source']})"
    )
    rows.append(f"xi formula: {doc['options']['xi_formula']}")
    return "\n".join(rows)


def budget_document(
    azimuth_deg: ArrayLike,
    elevation_deg: ArrayLike,
    *,
    k_md_e: float | None,
    n_receivers: int = 3,
    k_ffmd: float | None = None,
    **options: object,
) -> dict[str, Any]:
    """Return the budget of one geometry as a JSON-ready dict (``budget.json`` of the CLI).

    Parameters
    ----------
    azimuth_deg, elevation_deg : array_like, shape (n,)
        Satellite azimuths and elevations, degrees (n >= 4).
    k_md_e : float
        Ephemeris missed-detection multiplier (required, see :func:`vpl`).
    n_receivers : int, default 3
        Reference receivers ``M``.
    k_ffmd : float, optional
        Override the tabulated ``K_ffmd``.
    **options
        Passed to :func:`error_budget` (``x_air_m`` also to :func:`vpl`).

    Returns
    -------
    dict
        ``satellites`` (per-satellite terms, m), ``vpl_h0_m``, ``vpl_eph_m``,
        ``vpl_m``, ``multipliers`` (value and source of each), ``options``
        (every budget option used) and ``sources`` (of the constants).
    """
    t = error_budget(elevation_deg, n_receivers=n_receivers, **options)  # type: ignore[arg-type]
    x_air = float(options.get("x_air_m", 5000.0))  # type: ignore[arg-type]
    h0, eph = vpl(
        los_from_az_el(azimuth_deg, elevation_deg),
        t.total,
        k_md_e=k_md_e,
        n_receivers=n_receivers,
        k_ffmd=k_ffmd,
        x_air_m=x_air,
    )
    az = np.asarray(azimuth_deg, dtype=float).reshape(-1)
    sats = [
        {
            "azimuth_deg": float(az[i]),
            "elevation_deg": float(t.elevation_deg[i]),
            "ground_m": float(t.ground[i]),
            "air_m": float(t.air[i]),
            "iono_m": float(t.iono[i]),
            "trop_m": float(t.trop[i]),
            "total_m": float(t.total[i]),
        }
        for i in range(t.elevation_deg.size)
    ]
    used = {**_DEFAULTS, **options, "n_receivers": n_receivers}
    return {
        "satellites": sats,
        "vpl_h0_m": h0,
        "vpl_eph_m": eph,
        "vpl_m": max(h0, eph),
        "multipliers": multipliers(n_receivers=n_receivers, k_ffmd=k_ffmd, k_md_e=k_md_e),
        "options": used,
        "sources": sources(),
    }


#: Keyword options of :func:`error_budget` and their defaults (reported with every budget).
_DEFAULTS = {
    name: p.default
    for name, p in inspect.signature(error_budget).parameters.items()
    if p.kind is inspect.Parameter.KEYWORD_ONLY
}
