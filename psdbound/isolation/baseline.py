"""Dual-antenna baseline from the carrier phases: float double-difference least squares.

An error ``d`` in the position of antenna 2 (antenna 1 is the reference)
leaves ``(e^s - e^r) . d`` in every double difference of satellite ``s``
against reference ``r`` (``e`` the unit line-of-sight vector from the
antennas to the satellite; the two antennas of a short baseline see the same
direction). Over an arc it changes slowly with the geometry, by up to
``2 |d|``; a header position wrong by a metre makes the double differences
drift by decimetres per hour, which the stationarity test then rejects. The
per-arc ambiguity is a constant, so subtracting each arc's mean removes it
exactly and leaves a linear regression of the demeaned double differences on
the demeaned line-of-sight differences with three unknowns: the float
solution of the double-difference least-squares problem with one ambiguity
per arc (the ambiguities are "profiled out"). The solution is exact to
second order, ``|d|^2 / range``, i.e. below a micrometre for metres of error.

The residuals are multipath: correlated over tens of seconds within an arc
and nearly independent between arcs, so the standard error of ``d`` treats
the arcs, not the samples, as the independent units: a delete-one-arc
jackknife (the "CV3" cluster-robust covariance of [2]_). The ordinary
least-squares error would assume independent samples; the usual sandwich
("CV1", statsmodels ``cov_type="cluster"``) is too small with the ten or so
arcs of a session: on simulated arcs with AR(1) residuals its z-scores had a
standard deviation of 1.4-1.5, the jackknife's 1.0-1.2 (``tests/isolation/
test_baseline.py``). Arcs whose residual RMS is more than five times the
median are left out of a second pass (an undetected slip or a bad
reference).

References
----------
.. [1] Teunissen, P. J. G., & Montenbruck, O. (Eds.) (2017). *Springer
   Handbook of Global Navigation Satellite Systems*, ch. 21 (relative
   positioning, float double-difference solution). Springer.
.. [2] MacKinnon, J. G., Nielsen, M. Ø., & Webb, M. D. (2023). Cluster-robust
   inference: A guide to empirical practice. *Journal of Econometrics*,
   232(2), 272-299.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.io.geometry import ecef_to_geodetic, enu_rotation

__all__ = [
    "LONG_BASELINE_M",
    "BaselineEstimate",
    "baseline_note",
    "estimate_baseline_correction",
    "long_baseline_note",
]

#: Baselines above this (m) leave differential ionosphere and troposphere in the double
#: differences at the millimetre level of the multipath (about 1 mm per km of baseline
#: on L1 for a quiet ionosphere's gradient of 1 ppm, several times that when disturbed).
LONG_BASELINE_M = 1000.0

#: Arcs with a residual RMS above this multiple of the median are left out.
OUTLIER_RMS_FACTOR = 5.0
#: Smallest number of arcs for an estimate (three unknowns, clusters).
MIN_ARCS = 4
#: Smallest eigenvalue of the normal matrix, relative to the largest, for an estimate.
RANK_TOLERANCE = 1e-10


@dataclass(frozen=True)
class BaselineEstimate:
    """Correction of antenna 2's position from the double differences.

    Attributes
    ----------
    correction_m : ndarray, shape (3,)
        Estimated position of antenna 2 minus the position used, ECEF metres.
    correction_enu_m : ndarray, shape (3,)
        The same in east, north, up at antenna 1, metres.
    sigma_enu_m : ndarray, shape (3,)
        One-sigma standard errors (delete-one-arc jackknife), metres.
    rms_before_m, rms_after_m : float
        RMS of the demeaned double differences before and after the
        correction (the arcs of the final fit), metres (unscaled: four signals).
    n_arcs, n_samples : int
        Arcs and samples in the fit.
    n_arcs_excluded : int
        Arcs left out because their residual RMS was more than
        ``OUTLIER_RMS_FACTOR`` times the median.
    """

    correction_m: NDArray[np.float64]
    correction_enu_m: NDArray[np.float64]
    sigma_enu_m: NDArray[np.float64]
    rms_before_m: float
    rms_after_m: float
    n_arcs: int
    n_samples: int
    n_arcs_excluded: int

    @property
    def length_m(self) -> float:
        """Length of the correction, metres."""
        return float(np.linalg.norm(self.correction_m))

    @property
    def sigma_length_m(self) -> float:
        """One-sigma uncertainty of the correction's length (root-sum-square), metres."""
        return float(np.sqrt(np.sum(self.sigma_enu_m**2)))

    def correct(self, los_diff: NDArray[np.float64]) -> NDArray[np.float64]:
        """Return the term to subtract from double differences with these LOS differences, m."""
        return np.asarray(los_diff, dtype=np.float64) @ self.correction_m

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (metres)."""
        return {
            "correction_m": self.correction_m.tolist(),
            "correction_enu_m": self.correction_enu_m.tolist(),
            "sigma_enu_m": self.sigma_enu_m.tolist(),
            "correction_length_m": self.length_m,
            "sigma_length_m": self.sigma_length_m,
            "dd_rms_before_m": self.rms_before_m,
            "dd_rms_after_m": self.rms_after_m,
            "n_arcs": self.n_arcs,
            "n_samples": self.n_samples,
            "n_arcs_excluded": self.n_arcs_excluded,
            "method": "float double-difference least squares, one ambiguity per arc "
            "(arc means removed); standard errors by a delete-one-arc jackknife",
        }


def estimate_baseline_correction(
    dd_m: Sequence[NDArray[np.float64]],
    los_diff: Sequence[NDArray[np.float64]],
    receiver1_xyz_m: NDArray[np.float64],
) -> tuple[BaselineEstimate | None, str]:
    """Estimate the position error of antenna 2 from double-difference arcs.

    Parameters
    ----------
    dd_m : sequence of ndarray, shape (n_k,)
        Double differences of each arc (satellite minus reference), metres,
        with the geometric ranges of the positions used removed; any constant
        (ambiguity) per arc is allowed.
    los_diff : sequence of ndarray, shape (n_k, 3)
        Unit line-of-sight vector to the satellite minus the one to the
        reference, ECEF, at the same epochs.
    receiver1_xyz_m : ndarray, shape (3,)
        Position of antenna 1 (for the east/north/up rotation), ECEF metres.

    Returns
    -------
    estimate : BaselineEstimate or None
        None when the arcs cannot determine three coordinates.
    reason : str
        Why there is no estimate (empty when there is one).

    Notes
    -----
    The correction is for antenna 2; antenna 1 stays where it is (the
    double differences see only the baseline).
    """
    keep = [k for k, v in enumerate(dd_m) if v.size >= 3]
    if len(keep) < MIN_ARCS:
        return None, f"{len(keep)} double-difference arcs, at least {MIN_ARCS} needed"
    y_arcs = [np.asarray(dd_m[k], dtype=np.float64) for k in keep]
    x_arcs = [np.asarray(los_diff[k], dtype=np.float64) for k in keep]
    # per-arc normal equations of the demeaned problem (the ambiguities profiled out)
    xc = [x - x.mean(axis=0) for x in x_arcs]
    yc = [y - y.mean() for y in y_arcs]
    a_k = np.stack([x.T @ x for x in xc])
    b_k = np.stack([x.T @ y for x, y in zip(xc, yc, strict=True)])
    used = np.arange(len(keep))
    for _ in range(2):
        a_sum = a_k[used].sum(axis=0)
        w = np.linalg.eigvalsh(a_sum)
        if w[0] <= RANK_TOLERANCE * max(w[-1], 1e-300):
            return None, (
                "the satellite geometry of the arcs does not change enough to determine "
                "three baseline coordinates"
            )
        d = np.linalg.solve(a_sum, b_k[used].sum(axis=0))
        arc_rms = np.array(
            [np.sqrt(np.mean((y - x @ d) ** 2)) for x, y in zip(xc, yc, strict=True)]
        )
        good = np.flatnonzero(arc_rms <= OUTLIER_RMS_FACTOR * np.median(arc_rms))
        if good.size < MIN_ARCS or np.array_equal(good, used):
            break
        used = good
    a_sum, b_sum = a_k[used].sum(axis=0), b_k[used].sum(axis=0)
    d = np.linalg.solve(a_sum, b_sum)
    # delete-one-arc jackknife: the arcs are the independent units
    loo = np.stack([np.linalg.lstsq(a_sum - a_k[k], b_sum - b_k[k], rcond=None)[0] for k in used])
    g = used.size
    cov = (g - 1) / g * (loo - loo.mean(axis=0)).T @ (loo - loo.mean(axis=0))
    lat, lon, _ = ecef_to_geodetic(np.asarray(receiver1_xyz_m, dtype=np.float64))
    rot = enu_rotation(lat, lon)
    cov_enu = rot @ cov @ rot.T
    before = np.concatenate([yc[k] for k in used])
    after = np.concatenate([yc[k] - xc[k] @ d for k in used])
    est = BaselineEstimate(
        correction_m=d,
        correction_enu_m=rot @ d,
        sigma_enu_m=np.sqrt(np.clip(np.diag(cov_enu), 0.0, None)),
        rms_before_m=float(np.sqrt(np.mean(before**2))),
        rms_after_m=float(np.sqrt(np.mean(after**2))),
        n_arcs=int(used.size),
        n_samples=int(sum(y_arcs[k].size for k in used)),
        n_arcs_excluded=len(keep) - int(used.size),
    )
    return est, ""


def baseline_note(info: dict[str, Any] | None, markers: Sequence[str] | None = None) -> str:
    """Describe the baseline check of a dual-antenna isolation for the user.

    Parameters
    ----------
    info : dict or None
        ``meta["baseline_estimate"]`` of a dual-antenna :class:`MultipathSeries`.
    markers : sequence of str, optional
        Marker names of antennas A and B.

    Returns
    -------
    str
        A warning when the positions were corrected, when a large correction
        was declined (``baseline="given"``) or when no estimate was possible;
        empty when the given positions agree with the data.
    """
    if not info:
        return ""
    b = (markers[1] if markers and len(markers) > 1 else "") or "antenna B"
    est = info.get("estimate")
    if est is None:
        return f"baseline not checked against the carrier phases: {info.get('reason', '')}"
    e, n, u = est["correction_enu_m"]
    size = (
        f"{est['correction_length_m']:.3f} m (east {e:+.3f}, north {n:+.3f}, up {u:+.3f} m; "
        f"standard error {1e3 * est['sigma_length_m']:.1f} mm)"
    )
    rms = (
        f"double-difference RMS {1e3 * est['dd_rms_before_m']:.1f} mm with the given "
        f"positions, {1e3 * est['dd_rms_after_m']:.1f} mm with the estimate"
    )
    if info.get("used"):
        return (
            f"antenna position corrected: the carrier phases put {b} {size} from its given "
            f"position; {rms}; the estimate is used (baseline = 'given' keeps the positions)"
        )
    tol = float(info.get("tolerance_m", 0.0))
    if info.get("mode") == "given" and est["correction_length_m"] > tol:
        return (
            f"the carrier phases put {b} {size} from its given position ({rms}); the given "
            "positions are kept (baseline = 'given'), so the multipath series contains the "
            "drift of this baseline error"
        )
    return ""


def long_baseline_note(baseline_m: float | None) -> str:
    """Warn that a long dual-antenna baseline leaves atmosphere in the double differences.

    Parameters
    ----------
    baseline_m : float or None
        Distance between the two antennas, m.

    Returns
    -------
    str
        A warning above :data:`LONG_BASELINE_M`; empty otherwise.
    """
    if baseline_m is None or not baseline_m > LONG_BASELINE_M:
        return ""
    km = baseline_m / 1e3
    return (
        f"the antennas are {km:.1f} km apart: at that distance the double differences also "
        f"hold differential ionosphere and troposphere (of order {km:.0f} mm on L1 for a "
        "quiet ionosphere's 1 ppm gradient, several times that when disturbed), which the "
        "bound covers as if it were multipath; the dual-frequency method of each station "
        "separates them"
    )
