"""Elevation mapping: remove the elevation dependence of multipath before testing.

The mapped (normalised) error is ``x / m(el)`` with

    m(el) = a + b exp(-el^2 / (2 c^2))          (thesis eq. 3.3; el, c in degrees)

The thesis used ``a = 1, b = 29, c = 10 deg``. Because the bound is fitted to
the normalised error, a bound on the error at elevation ``el`` is the bound
times ``m(el)^2`` in PSD (``m(el)`` in standard deviation); with ``a = 1`` the
mapped error at zenith is the error itself.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import curve_fit

from psdbound.errors import InputError

__all__ = ["ElevationMapping", "MAX_FIT_B", "MAX_FIT_C_DEG", "THESIS_MAPPING", "fit_mapping"]


@dataclass(frozen=True)
class ElevationMapping:
    """Mapping function ``m(el) = a + b exp(-el^2 / (2 c^2))``.

    Parameters
    ----------
    a : float
        Dimensionless floor (1 keeps zenith values unchanged).
    b : float
        Dimensionless low-elevation amplification.
    c_deg : float
        Elevation scale, degrees.
    source : str
        ``"fixed"`` or ``"fitted"`` (recorded in results).
    covariance_bc : tuple of tuple of float, optional
        Covariance of ``(b, c_deg)`` for a fitted mapping (deg for c).
    """

    a: float = 1.0
    b: float = 29.0
    c_deg: float = 10.0
    source: str = "fixed"
    covariance_bc: tuple[tuple[float, float], tuple[float, float]] | None = None

    def __post_init__(self) -> None:
        if self.a <= 0 or self.b < 0 or self.c_deg <= 0:
            raise InputError(
                f"mapping parameters must satisfy a > 0, b >= 0, c > 0; got a={self.a}, "
                f"b={self.b}, c={self.c_deg} deg"
            )

    def factor(self, elevation_deg: ArrayLike) -> NDArray[np.float64]:
        """Return ``m(el)`` (dimensionless) for elevations in degrees."""
        el = np.asarray(elevation_deg, dtype=float)
        return self.a + self.b * np.exp(-(el**2) / (2.0 * self.c_deg**2))

    def factor_sigma(self, elevation_deg: ArrayLike) -> NDArray[np.float64]:
        """Return the standard error of ``m(el)`` from the fit (0 for a fixed mapping).

        Delta method with the covariance of ``(b, c)``:
        ``dm/db = g``, ``dm/dc = b g el^2 / c^3``, ``g = exp(-el^2 / (2 c^2))``.
        """
        el = np.asarray(elevation_deg, dtype=float)
        if self.covariance_bc is None:
            return np.zeros_like(el)
        g = np.exp(-(el**2) / (2.0 * self.c_deg**2))
        jac = np.stack([g, self.b * g * el**2 / self.c_deg**3], axis=-1)
        cov = np.asarray(self.covariance_bc, dtype=float)
        return np.sqrt(np.maximum(np.einsum("...i,ij,...j->...", jac, cov, jac), 0.0))

    def apply(self, value_m: ArrayLike, elevation_deg: ArrayLike) -> NDArray[np.float64]:
        """Return the mapped (normalised) error ``x / m(el)``, metres at zenith scale."""
        el = np.asarray(elevation_deg, dtype=float)
        if not np.isfinite(el).all():
            raise InputError("elevation mapping needs finite elevations for every sample")
        return np.asarray(value_m, dtype=float) / self.factor(el)

    def to_dict(self) -> dict[str, Any]:
        """Parameters for result files."""
        d = asdict(self)
        d["function"] = "a + b*exp(-el^2/(2*c^2)), el and c in degrees"
        if self.covariance_bc is not None:
            cov = np.asarray(self.covariance_bc)
            d["b_sigma"] = float(np.sqrt(cov[0, 0]))
            d["c_deg_sigma"] = float(np.sqrt(cov[1, 1]))
        return d


THESIS_MAPPING = ElevationMapping(1.0, 29.0, 10.0, "fixed")

#: Limits of the fitted mapping: the low-elevation amplification ``b`` and the
#: elevation scale ``c`` (deg). Beyond them the RMS does not follow the
#: low-elevation bump the model describes (e.g. flat RMS at every elevation),
#: and an unbounded fit runs off to meaningless values (b = 1e4, c = 52 deg
#: on a disturbed polar day).
MAX_FIT_B, MAX_FIT_C_DEG = 100.0, 40.0


def fit_mapping(
    value_m: ArrayLike,
    elevation_deg: ArrayLike,
    *,
    bin_deg: float = 5.0,
    min_per_bin: int = 30,
) -> ElevationMapping:
    """Fit ``a, b, c`` to the RMS of the data in elevation bins.

    The RMS per bin is modelled as ``s * (1 + beta exp(-el^2/(2 c^2)))`` with
    ``0 <= beta <= MAX_FIT_B`` and ``1 <= c <= MAX_FIT_C_DEG``; the returned
    mapping is normalised at zenith, ``m(90 deg) = 1`` (``a = 1 / m90``,
    ``b = beta / m90``), so the bound is stated at zenith scale. Bins are
    weighted by ``sqrt(n) / rms`` (relative weights);
    the covariance of ``(b, c)`` is scaled by the bins' actual scatter about
    the curve (``absolute_sigma=False``), so it includes what the model does
    not describe (azimuth-dependent multipath, correlated samples) rather
    than assuming independent samples.

    Parameters
    ----------
    value_m : array_like
        Isolated multipath, metres.
    elevation_deg : array_like
        Elevation of each sample, degrees.
    bin_deg : float, default 5
        Width of the elevation bins, degrees.
    min_per_bin : int, default 30
        Bins with fewer samples are ignored.

    Returns
    -------
    ElevationMapping
        With ``source="fitted"``.

    Raises
    ------
    InputError
        If fewer than four bins are populated or the fit does not converge.
    """
    x = np.asarray(value_m, dtype=float)
    el = np.asarray(elevation_deg, dtype=float)
    ok = np.isfinite(x) & np.isfinite(el)
    edges = np.arange(0.0, 90.0 + bin_deg, bin_deg)
    idx = np.digitize(el[ok], edges) - 1
    centres, rms, counts = [], [], []
    for k in range(edges.size - 1):
        sel = x[ok][idx == k]
        if sel.size >= min_per_bin:
            centres.append(0.5 * (edges[k] + edges[k + 1]))
            rms.append(np.sqrt(np.mean(sel**2)))
            counts.append(sel.size)
    if len(centres) < 4:
        raise InputError(
            f"cannot fit the elevation mapping: only {len(centres)} elevation bins of "
            f"{bin_deg:g} deg hold >= {min_per_bin} samples (need 4)"
        )
    c_arr, r_arr = np.array(centres), np.array(rms)

    def model(e: NDArray[np.float64], s: float, beta: float, c: float):
        return s * (1.0 + beta * np.exp(-(e**2) / (2.0 * c**2)))

    se = r_arr / np.sqrt(np.asarray(counts, dtype=float))
    try:
        p, pcov = curve_fit(
            model,
            c_arr,
            r_arr,
            p0=(r_arr.min(), max(r_arr.max() / r_arr.min() - 1.0, 0.1), 15.0),
            sigma=se,
            absolute_sigma=False,
            bounds=([0.0, 0.0, 1.0], [np.inf, MAX_FIT_B, MAX_FIT_C_DEG]),
            maxfev=20000,
        )
    except RuntimeError as exc:
        raise InputError(f"elevation mapping fit did not converge: {exc}") from None
    # normalise at zenith: m(90 deg) = 1, so the bound is stated at zenith scale
    beta, c = float(p[1]), float(p[2])
    m90 = 1.0 + beta * np.exp(-(90.0**2) / (2.0 * c**2))
    scale = np.diag([1.0 / m90, 1.0])  # (beta, c) -> (b = beta / m90, c), m90 held fixed
    cov = scale @ pcov[1:, 1:] @ scale
    cov_bc = None
    if np.all(np.isfinite(cov)):
        cov_bc = ((float(cov[0, 0]), float(cov[0, 1])), (float(cov[1, 0]), float(cov[1, 1])))
    return ElevationMapping(1.0 / m90, beta / m90, c, "fitted", cov_bc)
