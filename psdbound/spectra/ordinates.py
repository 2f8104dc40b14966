"""The lowest Fourier frequencies: narrow estimates, their degrees of freedom, a window's excess.

Each window's narrow estimate at its lowest Fourier frequencies, the degrees of freedom of
their sums, and a window's excess there over the other windows of its shape group.

The statement's multitaper (``NW = 4``) smooths over ``+- 4 / T``: a slow reflector's power,
largest at the lowest Fourier frequencies ``j / T``, shows in no band of its own. A narrow
multitaper (``NW =`` :data:`LOWEST_NW`, :data:`LOWEST_TAPERS` tapers, resolution
``+- 1.5 / T``) of each window (mean removed) at ``j = 1 ..`` :data:`MAX_ORDINATES`
resolves it. Two uses:

* :mod:`psdbound.spectra.lowest` holds the bound's expected estimate above each shape
  group's upper limit at the ordinates below ``f_min`` of every window
  (:attr:`LowestOrdinates.j`);
* :mod:`psdbound.spectra.groups` tests whether a window's estimate at its own lowest
  ordinates (:data:`OWN_J`, all below its own resolution ``5 / T``) exceeds its peers' more
  than its own level says (:func:`low_excess_z`, jointly with its residual in its lowest
  band: :func:`psdbound.spectra.groups.low_end_p`): a minority of slow strong reflectors,
  whose excess lies below the statement's lowest band and which the tests on the bands miss,
  gets its own group. Its peers are the windows of about its length and the longer windows
  cut to its length (:attr:`LowestOrdinates.cut_peers`): without them a short window among
  longer ones had no peer and was never tested (``benchmarks/bound_coverage.py``, class
  ``slowuneq``).

**Degrees of freedom.** Adjacent ordinates ``j / T`` and ``(j + 1) / T`` lie within each
other's resolution ``+- 1.5 / T``, and the mean removal empties part of ``j = 1``: the
estimates are not independent. Counted as ``2 K`` each, four ordinates of one window would
carry 16 degrees of freedom; they carry 7.4 (3.35 for ``j = 1`` alone). The count here is
Satterthwaite's ``tr(Q)^2 / tr(Q^2)`` of the estimate's quadratic form ``Q`` for white noise
([Satterthwaite1946]_; Percival and Walden 1993, section 7.3), exact for a locally flat
spectrum, computed from the Gram matrix of the tapered, mean-removed Fourier vectors
(:func:`ordinate_dof`).

References
----------
.. [Satterthwaite1946] Satterthwaite, F. E. (1946). An approximate distribution of estimates
   of variance components. *Biometrics Bulletin*, 2(6), 110-114.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray
from scipy import special, stats

from psdbound.spectra._multitaper import dpss_tapers
from psdbound.spectra.limits import log_chi2_bias

__all__ = [
    "LENGTH_MATCH",
    "LOWEST_NW",
    "LOWEST_TAPERS",
    "MAX_ORDINATES",
    "LowestOrdinates",
    "low_excess_z",
    "lowest_ordinates",
    "ordinate_dof",
]

#: Time-half-bandwidth product of the lowest-frequency estimate.
LOWEST_NW = 1.5
#: Its DPSS tapers, ``floor(2 NW) - 1`` (as :func:`psdbound.spectra.expectation.lag_kernels`
#: takes for ``nw``): two.
LOWEST_TAPERS = max(1, int(2.0 * LOWEST_NW) - 1)
#: Most Fourier frequencies checked per window.
MAX_ORDINATES = 4
#: Windows compared by :func:`low_excess_z` differ in length by at most this factor (their
#: ordinates ``j / T`` then lie within one resolution half-width of each other).
LENGTH_MATCH = 1.25


#: Most longer windows cut to a shorter window's length to be its peers in
#: :func:`low_excess_z` (its reference is their median: 32 are ample).
MAX_CUT_PEERS = 32
#: The Fourier indices of a window's own excess test: its lowest ``j / T``, all below
#: where the statement's multitaper resolves it (``5 / T``).
OWN_J = tuple(range(1, MAX_ORDINATES + 1))


@dataclass(frozen=True)
class LowestOrdinates:
    """Narrow multitaper estimates of each window at its lowest Fourier frequencies.

    Attributes
    ----------
    n : ndarray of int, shape (M,)
        Window lengths, samples.
    j : ndarray of int, shape (J,)
        Fourier indices ``j`` (frequency ``j / (n dt)`` of each window) below
        ``f_min`` for every window (``J`` may be 0).
    estimate_m2_hz : ndarray, shape (M, J)
        One-sided estimates, m^2/Hz.
    dt_s : float
        Sampling interval, seconds.
    own_m2_hz : ndarray, shape (M,)
        Each window's mean estimate over its own ``j`` in :data:`OWN_J`, m^2/Hz.
    cut_peers : tuple of (ndarray of int, ndarray), one per window
        Windows longer than ``LENGTH_MATCH`` times this one (at most
        :data:`MAX_CUT_PEERS`), each cut to this window's length (its first
        ``n`` samples), and their mean estimate over the same ``j`` (m^2/Hz):
        peers at this window's frequencies.
    """

    n: NDArray[np.int64]
    j: NDArray[np.int64]
    estimate_m2_hz: NDArray[np.float64]
    dt_s: float
    own_m2_hz: NDArray[np.float64] | None = None
    cut_peers: tuple[tuple[NDArray[np.int64], NDArray[np.float64]], ...] = ()

    def dof(self, rows: NDArray[np.int64], run: NDArray[np.int64]) -> float:
        """Degrees of freedom of the sum over windows ``rows`` of their mean over ``run``.

        ``run`` indexes :attr:`j`; the windows are independent (their sum adds them).
        """
        js = tuple(int(v) for v in self.j[run])
        return float(sum(ordinate_dof(int(n), js) for n in self.n[rows]))


def _narrow(y: NDArray[np.float64], js: tuple[int, ...], dt_s: float) -> NDArray[np.float64]:
    """Narrow estimates of mean-removed columns ``y`` (n, P) at ``js``, m^2/Hz, shape (P, J)."""
    y = y - y.mean(axis=0)
    v = _tapered_fourier(y.shape[0], js)
    eig = np.abs(v.reshape(-1, y.shape[0]) @ y) ** 2  # (K J, P)
    return (2.0 * dt_s * eig.reshape(v.shape[0], v.shape[1], -1).mean(axis=0)).T


def _by_length(
    xs: list[NDArray[np.float64]], n: NDArray[np.int64], k: int, dt_s: float
) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.float64]]:
    """Windows of length ``k``: their :data:`OWN_J` estimates; the longer windows cut to ``k``.

    Returns the own estimates (one row per window of length ``k``, in input order), the
    longer windows' rows (at most :data:`MAX_CUT_PEERS`, evenly in input order) and their
    mean estimates. One set of tapers per length: windows of one length share it.
    """
    own = np.flatnonzero(n == k)
    longer = np.flatnonzero(n > k * LENGTH_MATCH)
    if longer.size > MAX_CUT_PEERS:
        longer = longer[np.linspace(0, longer.size - 1, MAX_CUT_PEERS).round().astype(int)]
    cols = np.column_stack([xs[i] for i in own] + [xs[o][:k] for o in longer])
    est = _narrow(cols, OWN_J, dt_s)
    return est[: own.size], longer, est[own.size :].mean(axis=1)


def lowest_ordinates(
    stretches: Sequence[NDArray[np.float64]], dt_s: float, f_min_hz: float
) -> LowestOrdinates:
    """Estimate every window at its lowest Fourier frequencies ``j / T``.

    Parameters
    ----------
    stretches : sequence of ndarray
        The windows (evenly sampled, finite).
    dt_s : float
        Sampling interval, seconds.
    f_min_hz : float
        Lowest frequency of the statement, Hz.

    Returns
    -------
    LowestOrdinates
        ``j = 1 ..`` up to :data:`MAX_ORDINATES`, as far as ``j / T`` lies
        below ``f_min`` for every window (none when not even ``j = 1``
        does); each window's own :data:`OWN_J`; and the longer windows cut to
        each window's length.
    """
    xs = [np.asarray(x, dtype=float) for x in stretches]
    n = np.array([x.size for x in xs], dtype=np.int64)
    n_j = max(0, min(MAX_ORDINATES, int(np.ceil(f_min_hz * float(n.min()) * dt_s)) - 1))
    est = np.zeros((n.size, len(OWN_J)))
    cut: dict[int, tuple[NDArray[np.int64], NDArray[np.float64]]] = {}
    for k in np.unique(n).tolist():
        own, longer, peers = _by_length(xs, n, int(k), dt_s)
        est[n == k] = own
        cut[k] = (longer, peers)
    return LowestOrdinates(
        n,
        np.arange(1, n_j + 1),
        est[:, :n_j],
        float(dt_s),
        est.mean(axis=1),
        tuple(cut[k] for k in n.tolist()),
    )


@lru_cache(maxsize=32)
def _tapered_fourier(n: int, js: tuple[int, ...]) -> NDArray[np.complex128]:
    """Return the estimate's vectors, each taper times ``exp(-2 pi i j t / n)``, (K, J, n).

    Windows of one length share them (read-only).
    """
    tapers = dpss_tapers(n, LOWEST_NW, LOWEST_TAPERS)[0]
    phase = np.exp(-2j * np.pi * np.outer(np.asarray(js), np.arange(n)) / n)
    out = tapers[:, None, :] * phase[None]
    out.setflags(write=False)
    return out


@lru_cache(maxsize=256)
def ordinate_dof(n: int, js: tuple[int, ...]) -> float:
    """Degrees of freedom of one window's mean narrow estimate over Fourier indices ``js``.

    Satterthwaite's ``tr(Q)^2 / tr(Q^2)`` for white noise, ``Q`` the quadratic
    form of the estimate (its tapered, mean-removed Fourier vectors, real and
    imaginary parts): ``2 K len(js)`` for independent ordinates, less for the
    overlapping ones of :func:`lowest_ordinates`.

    Parameters
    ----------
    n : int
        Window length, samples.
    js : tuple of int
        Fourier indices.

    Returns
    -------
    float
    """
    v = _tapered_fourier(n, js).reshape(-1, n)
    v = v - v.mean(axis=1, keepdims=True)  # the estimate's window had its mean removed
    vec = np.vstack([v.real, v.imag])
    gram = vec @ vec.T
    return float(np.trace(gram) ** 2 / np.sum(gram * gram))


def _peers(
    lowest: LowestOrdinates, members: NDArray[np.int64], where: dict[int, int], i: int
) -> tuple[NDArray[np.int64], NDArray[np.float64], NDArray[np.float64]]:
    """Member ``i``'s peers: positions in ``members``, their mean estimates and dof.

    The other members of about its length (within :data:`LENGTH_MATCH`, their own
    estimates) and the longer members cut to its length (:attr:`LowestOrdinates.cut_peers`);
    ``where`` maps a row of ``lowest`` to its position in ``members``.
    """
    assert lowest.own_m2_hz is not None
    n = lowest.n[members].astype(float)
    same = np.flatnonzero(np.abs(np.log(n / n[i])) <= np.log(LENGTH_MATCH))
    same = same[same != i]
    pos, est = [same], [lowest.own_m2_hz[members[same]]]
    nu = [np.array([ordinate_dof(int(k), OWN_J) for k in lowest.n[members[same]]])]
    if lowest.cut_peers:
        rows, values = lowest.cut_peers[int(members[i])]
        keep = [(where[int(r)], v) for r, v in zip(rows, values, strict=True) if int(r) in where]
        if keep:
            pos.append(np.array([k for k, _ in keep]))
            est.append(np.array([v for _, v in keep]))
            nu.append(np.full(len(keep), ordinate_dof(int(lowest.n[members[i]]), OWN_J)))
    p, e, v = np.concatenate(pos), np.concatenate(est), np.concatenate(nu)
    good = e > 0.0
    return p[good], e[good], v[good]


def low_excess_z(
    lowest: LowestOrdinates,
    members: NDArray[np.int64],
    level: NDArray[np.float64],
    level_se: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Standardised excess of each member at its lowest ordinates over its peers, level-adjusted.

    Each member's mean estimate over its own ``j / T`` (:data:`OWN_J`) is
    compared with its peers' at the same frequencies: the other members of
    about its length (within :data:`LENGTH_MATCH`) and the longer members cut
    to its length (:attr:`LowestOrdinates.cut_peers`; without them a short
    window had no peer, and a slow reflector in a short window was never
    tested). The peers are scaled to the member's level, ``exp(d_w - d_o)``;
    their reference is the median of their logs, each less the median of
    ``ln(chi^2_nu / nu)`` (a median, so that a second slow reflector among the
    others does not hide the first). Under a common shape ``ln mean_w - E
    ln(chi^2_nu_w / nu_w) - ref`` is about normal with variance ``psi'(nu_w /
    2) + (pi / 2) mean psi'(nu_o / 2) / n_o + se_w^2`` (the sample median's
    variance; the upper tail of a log chi-square is lighter than the normal's,
    so the upper tail errs small).

    Parameters
    ----------
    lowest : LowestOrdinates
        Every window's narrow estimates.
    members : ndarray of int
        Rows of ``lowest`` in the group being tested.
    level, level_se : ndarray, shape (len(members),)
        Each member's log level deviation and its standard error, from the bands.

    Returns
    -------
    ndarray, shape (len(members),)
        About standard normal under a common shape; NaN for a member without
        a peer.
    """
    assert lowest.own_m2_hz is not None
    mean = lowest.own_m2_hz[members]
    nu = np.array([ordinate_dof(int(k), OWN_J) for k in lowest.n[members]])
    out = np.full(members.size, np.nan)
    where = {int(r): k for k, r in enumerate(members.tolist())}
    for i in range(members.size):
        pos, est, nu_o = _peers(lowest, members, where, i)
        if not pos.size or mean[i] <= 0.0:
            continue
        median_log = np.log(stats.chi2.median(nu_o) / nu_o)
        ref = np.median(np.log(est) - level[pos] - median_log) + level[i]
        excess = np.log(mean[i]) - log_chi2_bias(nu[i]) - ref
        spread = special.polygamma(1, nu_o / 2.0)
        var = special.polygamma(1, nu[i] / 2.0) + 0.5 * np.pi * float(np.mean(spread)) / pos.size
        out[i] = float(excess / np.sqrt(var + level_se[i] ** 2))
    return out
