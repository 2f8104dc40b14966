"""Groups of windows of one spectral shape (the pooled rule, docs/method/bound.rst).

Within a group the windows share a spectral shape up to a deviation each (a level,
and a tilt in log frequency where significant). A window whose band values lie above
its group's shape, or whose tilt differs significantly from its group's, is another
shape: it is moved to the next group, which is treated the same way.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy import stats

from psdbound.spectra.limits import WindowDeviations, bonferroni_p, window_deviations
from psdbound.spectra.ordinates import LowestOrdinates, low_excess_z

__all__ = [
    "LOW_END_CORRELATION",
    "TILT_ALPHA",
    "low_end_p",
    "log_frequency",
    "shape_groups",
    "tilted",
]

#: Level of the tilt test ("auto" deviation model, and the shape groups): family-wise over
#: the windows of a group (at 5 % per window, real station windows got tilts whose margins at
#: the band ends loosened ESBC from 2.3 to 6.0 mm).
TILT_ALPHA = 0.05
#: Correlation, under a common shape, assumed between a window's excess at its lowest
#: ordinates and its residual in its lowest band (the band's multitaper smooths over
#: +- 4 / T, down to the ordinates). Measured on homogeneous windows (25 per run):
#: 0.23-0.45 over 30 s x 120-480 samples and 1 s x 900-3600 samples; a larger value only
#: makes the joint test more conservative (tests/spectra/test_groups.py).
LOW_END_CORRELATION = 0.5


def log_frequency(
    centres_hz: NDArray[np.float64], reference_hz: NDArray[np.float64] | None = None
) -> NDArray[np.float64]:
    """Return the standardised log frequency (mean 0, unit spread over ``reference_hz``)."""
    ref = np.log(centres_hz if reference_hz is None else reference_hz)
    sd = float(np.std(ref))
    x = np.log(centres_hz) - ref.mean()
    return x / sd if sd > 0 else np.zeros_like(x)


def shape_groups(
    z: NDArray,
    v: NDArray,
    ok: NDArray,
    x: NDArray,
    dof: NDArray,
    shape_alpha: float,
    max_groups: int,
    lowest: LowestOrdinates | None = None,
) -> NDArray[np.int64]:
    """Group the windows by spectral shape: a window that departs from its group moves on.

    A window departs when its bands lie above its group's shape after its own
    level (:attr:`WindowDeviations.shape_p`, two statistics), when its tilt is
    significant (:func:`tilted`), or, given ``lowest`` (the windows' narrow
    estimates below the bands, unfiltered data), when its estimate at its
    lowest Fourier frequencies exceeds its peers' (windows of about its length,
    and longer ones cut to it) more than its level says, jointly with its
    residual in its lowest band (:func:`low_end_p`; the three statistics then
    share ``shape_alpha``, Bonferroni). The tests on the bands miss a minority
    of slow strong reflectors whose excess lies below the lowest band (issue
    27's example: 20 windows of 3 mm / 30 s and 2 of 6 mm / 200 s, 30 min at
    1 s, were covered in 23 of 30 runs).
    """
    n_w = z.shape[0]
    labels = np.full(n_w, -1, dtype=np.int64)
    todo = np.flatnonzero(ok.any(axis=1))
    g = 0
    while todo.size:
        members = todo
        while g < max_groups - 1 and members.size > 1:
            dev = window_deviations(
                z[members], v[members], ok[members], x, model="level", dof=dof[members]
            )
            off = _shape_p(dev, lowest, members) < shape_alpha / n_w
            # a significant tilt (family-wise) is another shape too
            off |= tilted(
                window_deviations(
                    z[members], v[members], ok[members], x, model="tilt", dof=dof[members]
                )
            )
            if not off.any() or off.all():
                break
            members = members[~off]
        labels[members] = g
        todo = np.setdiff1d(todo, members)
        g += 1
    return labels


def _shape_p(
    dev: WindowDeviations, lowest: LowestOrdinates | None, members: NDArray[np.int64]
) -> NDArray[np.float64]:
    """Return each member's p-value of another shape.

    The bands' two statistics, and where ``lowest`` is given the joint excess
    at the lowest ordinates and in the lowest band (the smallest of three
    p-values, times three).
    """
    if lowest is None:
        return dev.shape_p
    assert dev.coef is not None and dev.cov is not None and dev.shape_tests is not None
    z_low = low_excess_z(lowest, members, dev.coef[:, 0], np.sqrt(dev.cov[:, 0, 0]))
    p_joint = low_end_p(z_low, dev.lowest_residual)
    return bonferroni_p(np.column_stack([dev.shape_tests, p_joint]))


def low_end_p(
    z_low: NDArray[np.float64], lowest_residual: NDArray[np.float64] | None
) -> NDArray[np.float64]:
    """p-value of each window's joint excess at its lowest ordinates and in its lowest band.

    A slow reflector lifts both: its excess lies below the lowest band and
    runs into it. Alone, neither reaches the family-wise level as often as
    together: 1 slow window among 20 (1 s, 30 min, tau 30 s, the slow one twice
    sigma_GM and four times tau) was split off by the ordinates alone in 13 of
    20 runs, and is in 17 with this test (``tests/spectra/test_groups.py``).
    Stouffer's sum ``(z_low + e_1) / sqrt(2 (1 + rho))`` with ``rho`` =
    :data:`LOW_END_CORRELATION`, one-sided; a window with no residual to test
    (a single band) keeps the ordinates' ``z_low`` alone.

    Parameters
    ----------
    z_low : ndarray, shape (M,)
        Standardised excess at the lowest ordinates
        (:func:`psdbound.spectra.ordinates.low_excess_z`; NaN: no peer).
    lowest_residual : ndarray, shape (M,), optional
        Standardised residual in the lowest band
        (:attr:`~psdbound.spectra.limits.WindowDeviations.lowest_residual`).

    Returns
    -------
    ndarray, shape (M,)
        1 where the ordinates have no peer.
    """
    e_1 = np.full_like(z_low, np.nan) if lowest_residual is None else lowest_residual
    both = np.isfinite(z_low) & np.isfinite(e_1)
    joint = (np.nan_to_num(z_low) + np.nan_to_num(e_1)) / np.sqrt(2.0 * (1.0 + LOW_END_CORRELATION))
    z = np.where(both, joint, z_low)
    return np.where(np.isfinite(z), stats.norm.sf(np.nan_to_num(z)), 1.0)


def tilted(dev: WindowDeviations) -> NDArray[np.bool_]:
    """Windows whose tilt differs from 0 at :data:`TILT_ALPHA` (two-sided, Bonferroni)."""
    assert dev.coef is not None and dev.cov is not None
    with np.errstate(invalid="ignore", divide="ignore"):
        t = dev.coef[:, 1] / np.sqrt(dev.cov[:, 1, 1])
    level = TILT_ALPHA / (2.0 * max(t.size, 1))
    return (dev.n_params == 2) & (np.abs(np.nan_to_num(t)) > stats.norm.isf(level))
