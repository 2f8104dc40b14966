"""Polygons of two non-negative variables: their corners, and so their feasibility.

The model set's variances ``(v, w)`` of one time constant are two unknowns
under two linear inequalities per band. Their feasible set is a polygon of
at most a few dozen sides: every corner is the intersection of two
constraint lines, so enumerating the pairs gives the corners (the set's
projections) and whether the set is empty, with no solver.
``scipy.optimize.linprog`` (HiGHS) gives the same feasibility
(``tests/spectra/test_plane.py``) at about 1 ms a call, which the search for
the smallest widening pays over a hundred times per fit.

The bound's own linear program (the least objective over the same kind of
polygon, :mod:`psdbound.spectra.bound`) stays with HiGHS: its search over
the time constant follows the optimum's value, and the exact corner and
HiGHS's tolerance-level answer differ where a white-noise floor is not
resolved (a floor of 10 micrometres instead of exactly zero on a 30 s day).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["corners"]

#: Relative tolerance of a corner on a constraint (the scaled problem's rounding).
_TOL = 1e-9


def corners(a_ub: NDArray[np.float64], b_ub: NDArray[np.float64]) -> NDArray[np.float64]:
    """Return the corners of ``{x : a_ub @ x <= b_ub, x >= 0}`` in two variables.

    Parameters
    ----------
    a_ub : ndarray, shape (m, 2)
        Constraint coefficients.
    b_ub : ndarray, shape (m,)
        Constraint bounds.

    Returns
    -------
    ndarray, shape (k, 2)
        The corners (``k = 0`` when the set is empty), each clipped at zero.
    """
    a0 = np.asarray(a_ub, dtype=np.float64)
    scale = np.max(np.abs(a0), axis=0)
    scale[scale == 0.0] = 1.0
    a = np.vstack([a0 / scale, [[-1.0, 0.0], [0.0, -1.0]]])  # columns of one size
    b = np.r_[np.asarray(b_ub, dtype=np.float64), 0.0, 0.0]
    i, j = np.triu_indices(b.size, 1)
    det = a[i, 0] * a[j, 1] - a[i, 1] * a[j, 0]
    ok = np.abs(det) > 1e-12
    i, j, det = i[ok], j[ok], det[ok]
    x = (b[i] * a[j, 1] - b[j] * a[i, 1]) / det
    y = (a[i, 0] * b[j] - a[j, 0] * b[i]) / det
    inside = (a @ np.vstack([x, y]) <= (b + _TOL * (1.0 + np.abs(b)))[:, None]).all(axis=0)
    return np.column_stack([np.maximum(x[inside], 0.0), np.maximum(y[inside], 0.0)]) / scale
