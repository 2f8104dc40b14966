"""Upper envelope of a periodogram: local maxima + high-quantile regression, log-log.

(docs/method/cutoff.rst, step 4.) The envelope is a polynomial in
``x = log10(f)`` (centred and scaled) for ``log10(PSD)``:

1. **Local maxima** of the PSD (strictly above the left neighbour, not below
   the right one).
2. **Thinning in log frequency**: local maxima are evenly spaced in
   frequency, so nine in ten lie in the top decade and a regression through
   all of them would be decided there, not near the peak and the 40 dB
   crossing where the criterion acts. The maxima are grouped in bins of
   ``1 / bins_per_decade`` decade and the highest of each bin is kept (an
   upper hull, evenly spread in ``log10 f``).
3. **Quantile regression** (``method="quantreg"``, default): statsmodels
   ``QuantReg`` at quantile ``q`` (0.99) of ``log10 PSD`` on the polynomial
   basis of degree ``degree`` (3). ``method="linprog"`` solves the q = 1
   case exactly as a linear programme (HiGHS): the polynomial lying on or
   above every kept maximum with the least total gap, i.e. the thesis's
   "100 % quantile regression".
4. **Shift**: the curve is raised by the largest residual over *all* local
   maxima, so the envelope lies on or above every one of them (``shift_dex``
   records by how much, in decades).

Degree 3 is the smallest that follows the bend at the sidereal harmonics
and the f^-2 leakage tail; with the thinning, degrees 3-5 give the same f_c
to a few percent (see the closing note of issue #4).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError

__all__ = ["ENVELOPE_METHODS", "Envelope", "fit_envelope", "local_maxima"]

#: Envelope fitting methods.
ENVELOPE_METHODS = ("quantreg", "linprog")


def local_maxima(values: ArrayLike) -> NDArray[np.intp]:
    """Return the indices of the interior local maxima of a sequence.

    A point is a local maximum when it is strictly greater than its left
    neighbour and not smaller than its right one (plateaus count once, at
    their left end).

    Parameters
    ----------
    values : array_like of float
        Sequence, e.g. a periodogram.

    Returns
    -------
    ndarray of intp
        Increasing indices.
    """
    p = np.asarray(values, dtype=np.float64)
    if p.size < 3:
        return np.empty(0, dtype=np.intp)
    return np.flatnonzero((p[1:-1] > p[:-2]) & (p[1:-1] >= p[2:])) + 1


@dataclass(frozen=True)
class Envelope:
    """Polynomial upper envelope of a PSD in log-log space.

    ``log10 S(f) = sum_k coef[k] * ((log10 f - x_center) / x_scale)^k + shift_dex``

    Attributes
    ----------
    coef : tuple of float
        Polynomial coefficients, increasing powers (before the shift).
    x_center, x_scale : float
        Centring and scaling of ``log10 f``.
    shift_dex : float
        Upward shift applied so the envelope covers every local maximum,
        decades (>= 0).
    f_min_hz, f_max_hz : float
        Frequency range of the local maxima the envelope was fitted on.
    degree : int
        Polynomial degree.
    quantile : float
        Regression quantile (1.0 for ``"linprog"``).
    method : str
        ``"quantreg"`` or ``"linprog"``.
    n_maxima, n_fitted : int
        Number of local maxima, and of those kept after thinning.
    """

    coef: tuple[float, ...]
    x_center: float
    x_scale: float
    shift_dex: float
    f_min_hz: float
    f_max_hz: float
    degree: int
    quantile: float
    method: str
    n_maxima: int
    n_fitted: int

    def log10(self, frequency_hz: ArrayLike) -> NDArray[np.float64]:
        """``log10`` of the envelope at the given frequencies (Hz)."""
        x = (np.log10(np.asarray(frequency_hz, dtype=np.float64)) - self.x_center) / self.x_scale
        return np.polynomial.polynomial.polyval(x, np.asarray(self.coef)) + self.shift_dex

    def __call__(self, frequency_hz: ArrayLike) -> NDArray[np.float64]:
        """Envelope value (PSD units) at the given frequencies (Hz)."""
        return 10.0 ** self.log10(frequency_hz)

    def to_dict(self) -> dict:
        """JSON-ready representation."""
        return {
            "coef": list(self.coef),
            "x_center": self.x_center,
            "x_scale": self.x_scale,
            "shift_dex": self.shift_dex,
            "f_min_hz": self.f_min_hz,
            "f_max_hz": self.f_max_hz,
            "degree": self.degree,
            "quantile": self.quantile,
            "method": self.method,
            "n_maxima": self.n_maxima,
            "n_fitted": self.n_fitted,
        }

    @classmethod
    def from_dict(cls, d: dict) -> Envelope:
        """Inverse of :meth:`to_dict`."""
        return cls(**{**d, "coef": tuple(d["coef"])})


def _thin(x: NDArray[np.float64], z: NDArray[np.float64], per_decade: float) -> NDArray[np.intp]:
    """Index of the highest point in each 1/per_decade-decade bin of x."""
    if per_decade <= 0:
        return np.arange(x.size)
    b = np.floor(x * per_decade).astype(np.int64)
    order = np.lexsort((-z, b))  # by bin, highest first within a bin
    first = np.concatenate([[True], b[order][1:] != b[order][:-1]])
    return np.sort(order[first])


def fit_envelope(
    frequency_hz: ArrayLike,
    psd: ArrayLike,
    *,
    degree: int = 3,
    quantile: float = 0.99,
    method: str = "quantreg",
    bins_per_decade: float = 20.0,
) -> Envelope:
    """Fit the upper envelope of a PSD through its local maxima.

    Parameters
    ----------
    frequency_hz : array_like of float
        Increasing positive frequencies, Hz.
    psd : array_like of float
        PSD values (any positive units, e.g. m^2/Hz).
    degree : int, default 3
        Polynomial degree in ``log10 f``.
    quantile : float, default 0.99
        Regression quantile for ``method="quantreg"``.
    method : {"quantreg", "linprog"}
        statsmodels quantile regression, or the exact q = 1 linear programme.
    bins_per_decade : float, default 20
        Thinning of the local maxima (0: keep all).

    Returns
    -------
    Envelope
        Lies on or above every local maximum.

    Raises
    ------
    InputError
        For mismatched or non-positive input, an unknown method, or fewer
        local maxima than ``degree + 2``.
    """
    f = np.asarray(frequency_hz, dtype=np.float64)
    p = np.asarray(psd, dtype=np.float64)
    if f.shape != p.shape or f.ndim != 1:
        raise InputError(f"frequency and psd must be 1-D of equal length, got {f.shape}, {p.shape}")
    if method not in ENVELOPE_METHODS:
        raise InputError(f"unknown envelope method {method!r}; expected {ENVELOPE_METHODS}")
    if not 0.5 <= quantile <= 1.0:
        raise InputError(f"quantile {quantile} must be in [0.5, 1]")
    if degree < 0:
        raise InputError(f"degree {degree} must be non-negative")
    idx = local_maxima(p)
    idx = idx[(f[idx] > 0) & (p[idx] > 0)]
    if idx.size < degree + 2:
        raise InputError(
            f"the PSD has {idx.size} positive local maxima; need at least {degree + 2} "
            f"for a degree-{degree} envelope"
        )
    x = np.log10(f[idx])
    z = np.log10(p[idx])
    x_center = float(np.mean(x))
    x_scale = float(np.std(x)) or 1.0
    xs = (x - x_center) / x_scale
    keep = _thin(x, z, bins_per_decade)
    if keep.size < degree + 2:
        keep = np.arange(x.size)
    basis = np.vander(xs[keep], degree + 1, increasing=True)
    if method == "quantreg":
        coef = _quantreg(z[keep], basis, quantile)
    else:
        coef = _linprog_upper(z[keep], basis)
        quantile = 1.0
    fit_all = np.vander(xs, degree + 1, increasing=True) @ coef
    shift = float(max(0.0, np.max(z - fit_all)))
    return Envelope(
        coef=tuple(float(c) for c in coef),
        x_center=x_center,
        x_scale=x_scale,
        shift_dex=shift,
        f_min_hz=float(f[idx[0]]),
        f_max_hz=float(f[idx[-1]]),
        degree=int(degree),
        quantile=float(quantile),
        method=method,
        n_maxima=int(idx.size),
        n_fitted=int(keep.size),
    )


def _quantreg(z: NDArray[np.float64], basis: NDArray[np.float64], q: float) -> NDArray[np.float64]:
    from statsmodels.regression.quantile_regression import QuantReg

    if q >= 1.0:
        return _linprog_upper(z, basis)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # IterationLimitWarning / ConvergenceWarning
        res = QuantReg(z, basis).fit(q=q, max_iter=5000, p_tol=1e-8)
    return np.asarray(res.params, dtype=np.float64)


def _linprog_upper(z: NDArray[np.float64], basis: NDArray[np.float64]) -> NDArray[np.float64]:
    """Polynomial on or above every point with the least total gap (q = 1)."""
    from scipy.optimize import linprog

    # minimise sum(basis @ c - z) = (sum of basis rows) @ c + const, s.t. basis @ c >= z
    res = linprog(
        c=basis.sum(axis=0),
        A_ub=-basis,
        b_ub=-z,
        bounds=[(None, None)] * basis.shape[1],
        method="highs",
    )
    if not res.success:  # pragma: no cover - always feasible (a constant works)
        raise InputError(f"envelope linear programme failed: {res.message}")
    return np.asarray(res.x, dtype=np.float64)
