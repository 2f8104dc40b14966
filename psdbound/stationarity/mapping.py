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

__all__ = ["ElevationMapping", "THESIS_MAPPING", "fit_mapping"]


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
    """

    a: float = 1.0
    b: float = 29.0
    c_deg: float = 10.0
    source: str = "fixed"

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

    def apply(self, value_m: ArrayLike, elevation_deg: ArrayLike) -> NDArray[np.float64]:
        """Return the mapped (normalised) error ``x / m(el)``, metres at zenith scale."""
        el = np.asarray(elevation_deg, dtype=float)
        if not np.isfinite(el).all():
            raise InputError("elevation mapping needs finite elevations for every sample")
        return np.asarray(value_m, dtype=float) / self.factor(el)

    def as_dict(self) -> dict[str, Any]:
        """Parameters for result files."""
        d = asdict(self)
        d["function"] = "a + b*exp(-el^2/(2*c^2)), el and c in degrees"
        return d


THESIS_MAPPING = ElevationMapping(1.0, 29.0, 10.0, "fixed")


def fit_mapping(
    value_m: ArrayLike,
    elevation_deg: ArrayLike,
    *,
    bin_deg: float = 5.0,
    min_per_bin: int = 30,
) -> ElevationMapping:
    """Fit ``a, b, c`` to the RMS of the data in elevation bins.

    The RMS per bin is modelled as ``s * (1 + beta exp(-el^2/(2 c^2)))``; the
    returned mapping is ``a = 1, b = beta, c`` (so zenith values keep their
    scale ``s``).

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
    centres, rms = [], []
    for k in range(edges.size - 1):
        sel = x[ok][idx == k]
        if sel.size >= min_per_bin:
            centres.append(0.5 * (edges[k] + edges[k + 1]))
            rms.append(np.sqrt(np.mean(sel**2)))
    if len(centres) < 4:
        raise InputError(
            f"cannot fit the elevation mapping: only {len(centres)} elevation bins of "
            f"{bin_deg:g} deg hold >= {min_per_bin} samples (need 4)"
        )
    c_arr, r_arr = np.array(centres), np.array(rms)

    def model(e: NDArray[np.float64], s: float, beta: float, c: float):
        return s * (1.0 + beta * np.exp(-(e**2) / (2.0 * c**2)))

    try:
        p, _ = curve_fit(
            model,
            c_arr,
            r_arr,
            p0=(r_arr.min(), max(r_arr.max() / r_arr.min() - 1.0, 0.1), 15.0),
            bounds=([0.0, 0.0, 1.0], [np.inf, 1e4, 90.0]),
            maxfev=20000,
        )
    except RuntimeError as exc:
        raise InputError(f"elevation mapping fit did not converge: {exc}") from None
    return ElevationMapping(1.0, float(p[1]), float(p[2]), "fitted")
