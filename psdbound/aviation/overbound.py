"""Gaussian overbounds of sample error distributions, per elevation bin.

The default is the paired overbound (:mod:`psdbound.aviation.paired`: a bias
and a sigma whose left and right bounding functions cover the sample on the
whole line, every point constrained, so that the bound carries through
convolution for independent errors). Two further constructions, both
computed from the empirical CDF ``F_n`` of the samples of one bin (``n``
samples, sorted ``x_(1) <= ... <= x_(n)``):

CDF overbound (DeCleene 2000, [DeCleene2000]_), optionally with a bias
    The Gaussian ``G`` of mean 0 (or ``N(-b, s)`` on the left tail and
    ``N(+b, s)`` on the right one) must put at least as much probability in
    each tail as the samples: ``G(x) >= F_n(x)`` on the left, ``G(x) <=
    F_n(x^-)`` on the right. At the sample points that is ``Phi((x_(i) + b)
    / s) >= i / n`` for the left tail and ``Phi((x_(i) - b) / s) <= (i - 1)
    / n`` for the right tail, which gives a lower limit on ``s`` per point;
    ``s`` is the largest. The empirical CDF is taken at its least favourable
    side of each jump, so the bound holds for the step function itself, not
    only at the plotting positions. Each tail is checked on its own half of
    the line only: with a bias this is not the paired overbound of
    [Rife2006]_ (:mod:`psdbound.aviation.paired`), and carrying it through a
    convolution needs DeCleene's symmetric-unimodal condition.

Two-step overbound (named in seed 000, which cites [BlanchWalterEnge2019]_ for it)
    Step 1 centres the samples on their median ``m`` (the bias of the
    overbound, close to the distribution's own centre) and replaces the two
    tails by the heavier of the two at each distance ``d`` from ``m``:
    ``T(d) = max(P(x - m >= d), P(x - m <= -d))`` -- the tail function of a
    symmetric distribution about ``m`` that overbounds the sample in the
    CDF sense on both sides. Step 2 finds the smallest zero-mean Gaussian
    whose tail ``Q(d / s)`` lies above ``T(d)`` for every ``d``. The result
    ``N(m, s)`` carries over to sums of errors by DeCleene's theorem only when
    the *true* error distributions are symmetric and unimodal; that the bound
    is a Gaussian does not make it so (for other errors use the paired
    overbound). Seed 000 only
    names the method and its two properties (stable through convolution like
    paired overbounding, biases close to the sample distribution's); this is
    our construction with those properties, documented in
    ``docs/method/aviation.rst``.

These two (not the paired overbound) ignore the core of the distribution where ``Phi^-1(1 - tail) <
min_abs_z`` (default 0.25: the central 20 % of probability). A finite
sample cannot be bounded there at all: its empirical tail reaches 1/2 at a
non-zero distance from the centre (the atoms of ``F_n``), which no Gaussian
of finite sigma covers, and just outside it the ratio ``d / z`` is sampling
noise divided by a near-zero ``z``. Pass ``min_abs_z=0`` to constrain every
point (the sigma is then ``inf`` whenever such a point exists).

The inflation factor of a bin is ``sigma_overbound / std(samples)`` (1 for
an exactly Gaussian sample, larger for heavier tails). Every bin also has its
effective sample size and the overbound at a confidence level
(:mod:`psdbound.aviation.sample_size`).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.stats import norm

from psdbound.aviation.options import DEFAULT_EDGES_DEG, METHODS
from psdbound.aviation.paired import DEFAULT_K_WEIGHT, TailMap, paired_overbound
from psdbound.aviation.sample_size import effective_sample_size, upper_tail
from psdbound.common.notices import warn
from psdbound.errors import InputError

__all__ = [
    "DEFAULT_MIN_ABS_Z",
    "METHODS",
    "BinOverbound",
    "OverboundResult",
    "cdf_overbound_sigma",
    "overbound_by_elevation",
    "samples_in_full_bins",
    "two_step_overbound",
]

DEFAULT_MIN_ABS_Z = 0.25


#: Largest magnitude of a sample: beyond it its square overflows (no error sample is that large).
MAX_ABS_SAMPLE = 1e150


def _check_elevations(el: NDArray[np.float64]) -> None:
    """Elevations must be numbers between -90 and 90 degrees."""
    if np.isnan(el).any():
        raise InputError(f"{int(np.isnan(el).sum())} elevation(s) are NaN")
    bad = ~((el >= -90.0) & (el <= 90.0))
    if bad.any():
        raise InputError(
            f"{int(bad.sum())} elevation(s) outside [-90, 90] deg (e.g. "
            f"{float(el[bad][0]):g}): not an elevation in degrees"
        )


def _note_outside(el: NDArray[np.float64], edges: NDArray[np.float64], binned: bool) -> None:
    """Say how many samples lie outside the elevation bins (they are left out)."""
    out = ~((el >= edges[0]) & (el <= edges[-1]))
    if binned and out.any():
        warn(
            f"{int(out.sum())} of {el.size} sample(s) lie outside the elevation bins "
            f"[{edges[0]:g}, {edges[-1]:g}] deg and are left out",
            stacklevel=3,
        )


def _clean(samples: ArrayLike, where: str, min_samples: int) -> NDArray[np.float64]:
    x = np.asarray(samples, dtype=float).reshape(-1)
    if np.isnan(x).any() or not np.isfinite(x).all():
        bad = int(np.count_nonzero(~np.isfinite(x)))
        raise InputError(f"{where}: {bad} sample(s) are NaN or infinite; remove them first")
    if np.abs(x).max(initial=0.0) > MAX_ABS_SAMPLE:
        raise InputError(
            f"{where}: sample(s) up to {np.abs(x).max():.3g} in magnitude, beyond "
            f"{MAX_ABS_SAMPLE:g}: not error samples"
        )
    if x.size < min_samples:
        raise InputError(
            f"{where}: {x.size} sample(s), need at least {min_samples} "
            "(merge bins or lower min_samples)"
        )
    return np.sort(x)


def _tail_sigma(
    d: NDArray[np.float64],
    tail: NDArray[np.float64],
    min_abs_z: float,
    tail_map: TailMap | None = None,
) -> float:
    """Smallest ``s`` with ``Q(d / s) >= tail`` at every constraining point (``d > 0``)."""
    if tail_map is not None:
        tail = tail_map(tail)
    if d.size == 0:
        return 0.0
    if min_abs_z <= 0 and ((d > 0) & (tail >= 0.5)).any():
        return math.inf  # a tail of 1/2 away from the centre: no finite Gaussian bounds it
    with np.errstate(divide="ignore"):
        z = norm.isf(tail)  # > 0 where tail < 1/2
    keep = (d > 0) & (tail < 0.5) & (z >= min_abs_z)
    if not keep.any():
        return 0.0
    return float(np.max(d[keep] / z[keep]))


def cdf_overbound_sigma(
    samples: ArrayLike,
    *,
    bias: float = 0.0,
    min_abs_z: float = DEFAULT_MIN_ABS_Z,
    min_samples: int = 2,
    tail_map: TailMap | None = None,
) -> float:
    """Sigma of the smallest CDF Gaussian overbound, zero-mean or with a bias on each tail.

    Parameters
    ----------
    samples : array_like
        Errors, any unit (the sigma comes out in the same unit).
    bias : float, default 0
        Bias ``b >= 0`` (same unit): the left tail is bounded by
        ``N(-b, s)``, the right ``N(+b, s)``. 0 is DeCleene's zero-mean bound.
    min_abs_z : float, default 0.25
        Only points whose empirical tail has ``Phi^-1(1 - tail) >= min_abs_z``
        constrain ``s``.
    min_samples : int, default 2
        Fewer samples raise :class:`~psdbound.errors.InputError`.
    tail_map : callable, optional
        Replaces the empirical tails (e.g. by upper confidence bounds).

    Returns
    -------
    float
        ``s`` (``inf`` if the core cannot be bounded: median beyond ``b``).
    """
    if not bias >= 0:
        raise InputError(f"bias must be >= 0, got {bias}")
    x = _clean(samples, "samples", min_samples)
    n = x.size
    i = np.arange(1, n + 1)
    left = x < -bias
    right = x > bias
    s_left = _tail_sigma(-(x[left] + bias), i[left] / n, min_abs_z, tail_map)
    s_right = _tail_sigma(x[right] - bias, (n - i[right] + 1) / n, min_abs_z, tail_map)
    # a point on the wrong side of the bias (e.g. x in [-b, b]) is always bounded
    return max(s_left, s_right)


def two_step_overbound(
    samples: ArrayLike,
    *,
    min_abs_z: float = DEFAULT_MIN_ABS_Z,
    min_samples: int = 2,
    tail_map: TailMap | None = None,
) -> tuple[float, float]:
    """Two-step Gaussian overbound ``N(m, s)``: median-centred, symmetrised, Gaussian-bounded.

    Parameters
    ----------
    samples : array_like
        Errors, any unit.
    min_abs_z : float, default 0.25
        As in :func:`cdf_overbound_sigma`.
    min_samples : int, default 2
        Fewer samples raise :class:`~psdbound.errors.InputError`.
    tail_map : callable, optional
        Replaces the empirical tails (e.g. by upper confidence bounds).

    Returns
    -------
    bias : float
        The centre ``m`` (sample median), same unit as the samples.
    sigma : float
        ``s``, same unit.
    """
    x = _clean(samples, "samples", min_samples)
    n = x.size
    m = float(np.median(x))
    i = np.arange(1, n + 1)
    d = np.abs(x - m)
    # P(x - m >= d) for points right of m, P(x - m <= -d) for points left of m
    tail_own = np.where(x > m, (n - i + 1) / n, i / n)
    # the opposite tail at the same distance: count of samples beyond m -/+ d
    right_at = (n - np.searchsorted(x, m + d, side="left")) / n
    left_at = np.searchsorted(x, m - d, side="right") / n
    tail = np.maximum(tail_own, np.maximum(right_at, left_at))
    off = d > 0
    return m, _tail_sigma(d[off], tail[off], min_abs_z, tail_map)


@dataclass(frozen=True)
class BinOverbound:
    """The overbound of one elevation bin.

    Attributes
    ----------
    low_deg, high_deg : float
        Bin edges, degrees (``low <= el < high``; the last bin includes ``high``).
    n : int
        Number of samples.
    mean, std : float
        Sample mean and standard deviation (ddof 1), unit of the samples.
    bias : float
        Overbound mean (two-step: the median) or paired bias, unit of the samples.
    sigma : float
        Overbounding sigma, unit of the samples.
    inflation : float
        ``sigma / std`` (dimensionless).
    n_eff : float
        Effective number of independent samples (``n / tau_int``,
        :func:`~psdbound.aviation.sample_size.effective_sample_size`).
    tau_int : float
        Integrated autocorrelation time, samples.
    confidence : float
        Confidence level of ``bias_upper``, ``sigma_upper``, ``inflation_upper``.
    bias_upper, sigma_upper, inflation_upper : float
        The overbound when every empirical tail is replaced by its upper
        confidence bound with ``n_eff`` independent samples (unit of the
        samples; dimensionless).
    """

    low_deg: float
    high_deg: float
    n: int
    mean: float
    std: float
    bias: float
    sigma: float
    inflation: float
    n_eff: float = math.nan
    tau_int: float = math.nan
    confidence: float = math.nan
    bias_upper: float = math.nan
    sigma_upper: float = math.nan
    inflation_upper: float = math.nan

    @property
    def label(self) -> str:
        """``"[low, high) deg"``, as used in error messages and tables."""
        return f"[{self.low_deg:g}, {self.high_deg:g}) deg"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (floats, ints)."""
        return {
            "elevation_deg": [self.low_deg, self.high_deg],
            "n": self.n,
            "mean": self.mean,
            "std": self.std,
            "bias": self.bias,
            "sigma": self.sigma,
            "inflation": self.inflation,
            "n_eff": self.n_eff,
            "tau_int": self.tau_int,
            "confidence": self.confidence,
            "bias_upper": self.bias_upper,
            "sigma_upper": self.sigma_upper,
            "inflation_upper": self.inflation_upper,
        }


@dataclass(frozen=True)
class OverboundResult:
    """Per-bin Gaussian overbounds of a sample distribution.

    Attributes
    ----------
    method : str
        ``"paired"``, ``"two_step"`` or ``"cdf"``.
    bins : tuple of BinOverbound
        One per non-empty elevation bin, in elevation order.
    unit : str
        Unit of the samples (for display).
    min_abs_z : float
        Core excluded from the bound (see :func:`cdf_overbound_sigma`; 0 for
        ``"paired"``, which constrains every point).
    samples : dict
        ``label -> sorted samples`` of each bin (for the Q-Q figure).
    """

    method: str
    bins: tuple[BinOverbound, ...]
    unit: str = "m"
    min_abs_z: float = DEFAULT_MIN_ABS_Z
    samples: dict[str, NDArray[np.float64]] = field(default_factory=dict, repr=False)

    @property
    def sigma(self) -> NDArray[np.float64]:
        """Overbounding sigma per bin, unit of the samples."""
        return np.array([b.sigma for b in self.bins])

    @property
    def inflation(self) -> NDArray[np.float64]:
        """Inflation factor ``sigma / std`` per bin."""
        return np.array([b.inflation for b in self.bins])

    @property
    def counts(self) -> NDArray[np.int64]:
        """Samples per bin."""
        return np.array([b.n for b in self.bins], dtype=np.int64)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: method, unit, ``min_abs_z`` and one entry per bin."""
        return {
            "method": self.method,
            "unit": self.unit,
            "min_abs_z": self.min_abs_z,
            "bins": [b.to_dict() for b in self.bins],
        }

    def qq_points(self, max_points: int = 400) -> dict[str, dict[str, list[float]]]:
        """Q-Q points of each bin, thinned for plotting: every tail point is kept.

        The plotting positions are ``z_i = Phi^-1((i - 1/2) / n)``. Points
        are chosen evenly in ``z`` (not in rank), so the few extreme samples
        that decide the overbound are always drawn while the dense core is
        thinned.

        Parameters
        ----------
        max_points : int, default 400
            Points per bin at most (about; the extremes are always kept).

        Returns
        -------
        dict
            ``label -> {"z": [...], "x": [...]}`` (``x`` in :attr:`unit`).
        """
        out: dict[str, dict[str, list[float]]] = {}
        for b in self.bins:
            x = np.sort(self.samples[b.label])
            z = norm.ppf((np.arange(1, x.size + 1) - 0.5) / x.size)
            if x.size > max_points:
                grid = np.linspace(z[0], z[-1], max_points)
                idx = np.unique(np.r_[0, np.searchsorted(z, grid).clip(0, x.size - 1), x.size - 1])
                z, x = z[idx], x[idx]
            out[b.label] = {"z": z.tolist(), "x": x.tolist()}
        return out

    def summary(self) -> str:
        """Return a fixed-width table: bin, n, n_eff, std, bias, sigma, inflation and its bound."""
        core = (
            "no core exempted" if self.min_abs_z == 0 else f"core |z| < {self.min_abs_z:g} ignored"
        )
        conf = next((b.confidence for b in self.bins), math.nan)
        rows = [
            f"Gaussian overbound ({self.method}, {core}), unit {self.unit}; 'upper': every "
            f"tail at its {100 * conf:g} % upper confidence bound with n_eff samples",
            f"{'elevation':>16} {'n':>7} {'n_eff':>8} {'std':>8} {'bias':>8} {'sigma':>8} "
            f"{'inflation':>9} {'bias_up':>8} {'sigma_up':>8} {'infl_up':>8}",
        ]
        for b in self.bins:
            rows.append(
                f"{b.label:>16} {b.n:>7d} {b.n_eff:>8.1f} {b.std:>8.4g} {b.bias:>8.4g} "
                f"{b.sigma:>8.4g} {b.inflation:>9.4f} {b.bias_upper:>8.4g} "
                f"{b.sigma_upper:>8.4g} {b.inflation_upper:>8.4f}"
            )
        return "\n".join(rows)


def _bins(
    el: NDArray[np.float64], edges: Sequence[float]
) -> Iterator[tuple[float, float, NDArray[np.bool_]]]:
    """``(low, high, mask)`` of each bin: ``low <= el < high``, the last bin closed."""
    last = len(edges) - 2
    for k in range(len(edges) - 1):
        lo, hi = float(edges[k]), float(edges[k + 1])
        yield lo, hi, (el >= lo) & ((el <= hi) if k == last else (el < hi))


def samples_in_full_bins(
    elevation_deg: ArrayLike, edges_deg: Sequence[float], min_samples: int
) -> tuple[NDArray[np.bool_], list[str]]:
    """Mask of the samples in elevation bins that hold at least ``min_samples``.

    For samples computed by psdbound itself (code multipath of a station),
    where a sparse bin is a property of the sky, not bad input: a station at
    79 deg N sees few GPS satellites above 60 deg. The sparse bins are named
    so that the caller can report them; :func:`overbound_by_elevation` on
    a user's samples still refuses them.

    Parameters
    ----------
    elevation_deg : array_like, shape (n,)
        Elevation of each sample, degrees.
    edges_deg : sequence of float
        Increasing bin edges, degrees (``low <= el < high``, the last bin closed).
    min_samples : int
        Fewest samples a bin must hold.

    Returns
    -------
    keep : ndarray of bool, shape (n,)
        True for samples in bins with enough samples.
    notes : list of str
        One sentence per non-empty bin left out (its edges and count).
    """
    el = np.asarray(elevation_deg, dtype=float).reshape(-1)
    keep = np.zeros(el.size, dtype=bool)
    notes = []
    for lo, hi, sel in _bins(el, edges_deg):
        n = int(sel.sum())
        if n >= min_samples:
            keep |= sel
        elif n:
            notes.append(
                f"elevation bin [{lo:g}, {hi:g}) deg holds {n} samples, fewer than "
                f"{min_samples}: not overbounded"
            )
    return keep, notes


def _one_bin(
    xs: NDArray[np.float64],
    raw: NDArray[np.float64],
    seg: NDArray[Any] | None,
    method: str,
    opts: dict[str, Any],
) -> dict[str, float]:
    """Bias, sigma and their confidence bounds of one bin (``xs`` sorted, ``raw`` in time order)."""
    n_eff, tau = effective_sample_size(raw, segment_id=seg)
    conf = float(opts["confidence"])

    def upper(t: NDArray[np.float64]) -> NDArray[np.float64]:
        return upper_tail(t, n_eff, conf)

    def fit(tail_map: TailMap | None) -> tuple[float, float]:
        if method == "paired":
            return paired_overbound(xs, k_weight=opts["k_weight"], tail_map=tail_map)
        if method == "two_step":
            return two_step_overbound(xs, min_abs_z=opts["min_abs_z"], tail_map=tail_map)
        b = float(opts["bias"])
        return b, cdf_overbound_sigma(xs, bias=b, min_abs_z=opts["min_abs_z"], tail_map=tail_map)

    b, s = fit(None)
    b_up, s_up = fit(upper)
    return {
        "bias": b,
        "sigma": s,
        "bias_upper": b_up,
        "sigma_upper": s_up,
        "n_eff": n_eff,
        "tau_int": tau,
        "confidence": conf,
    }


def _grid(
    x: NDArray[np.float64], elevation_deg: ArrayLike | None, edges_deg: Sequence[float]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Elevations and edges (one open bin without elevations), checked."""
    edges = np.asarray(edges_deg, dtype=float)
    if edges.size < 2 or not (np.diff(edges) > 0).all():
        raise InputError(f"edges_deg must increase, at least 2 values: {list(edges_deg)}")
    if elevation_deg is None:
        return np.full(x.size, 0.0), np.array([-math.inf, math.inf])
    el = np.asarray(elevation_deg, dtype=float).reshape(-1)
    if el.size != x.size:
        raise InputError(f"{x.size} samples but {el.size} elevations")
    _check_elevations(el)
    return el, edges


def overbound_by_elevation(
    samples: ArrayLike,
    elevation_deg: ArrayLike | None = None,
    *,
    edges_deg: Sequence[float] = DEFAULT_EDGES_DEG,
    method: str = "paired",
    bias: float = 0.0,
    min_abs_z: float = DEFAULT_MIN_ABS_Z,
    min_samples: int = 100,
    unit: str = "m",
    confidence: float = 0.95,
    segment_id: ArrayLike | None = None,
    k_weight: float = DEFAULT_K_WEIGHT,
) -> OverboundResult:
    """Gaussian overbound of ``samples`` in each elevation bin, with sample sizes and confidence.

    Parameters
    ----------
    samples : array_like, shape (n,)
        Errors (code or carrier multipath, normalised errors, ...), ``unit``, in
        time order (the effective sample size reads their autocorrelation).
    elevation_deg : array_like, shape (n,), optional
        Elevation of each sample, degrees. ``None``: one bin for all samples.
    edges_deg : sequence of float, default (5, 15, 30, 45, 60, 90)
        Increasing bin edges, degrees. Samples outside are left out (a
        :class:`~psdbound.common.notices.PsdboundWarning` counts them); empty
        bins are skipped.
    method : {"paired", "two_step", "cdf"}, default "paired"
        See the module docstring and :mod:`psdbound.aviation.paired`.
    bias : float, default 0
        Bias of the ``"cdf"`` method, ``unit``.
    min_abs_z : float, default 0.25
        Core excluded from the ``"two_step"`` and ``"cdf"`` bounds (the
        ``"paired"`` bound constrains every point and ignores it).
    min_samples : int, default 100
        A non-empty bin with fewer samples raises
        :class:`~psdbound.errors.InputError` naming the bin.
    unit : str, default "m"
        For display only.
    confidence : float, default 0.95
        Confidence level of the ``*_upper`` bounds, in (0, 1).
    segment_id : array_like, shape (n,), optional
        Continuous pieces of the series (e.g. carrier-levelling arcs): the
        autocorrelation is never taken across a change. None: one series.
    k_weight : float, default 5.81
        Sigma-against-bias weight of the ``"paired"`` construction.

    Returns
    -------
    OverboundResult

    Raises
    ------
    InputError
        NaN samples or elevations (the bin is named), a bin with too few
        samples, mismatched lengths, bad edges, method or confidence.
    """
    if method not in METHODS:
        raise InputError(f"unknown method {method!r}; choose from {METHODS}")
    if not 0.0 < confidence < 1.0:
        raise InputError(f"confidence must be in (0, 1), got {confidence}")
    x = np.asarray(samples, dtype=float).reshape(-1)
    el, edges = _grid(x, elevation_deg, edges_deg)
    seg = None if segment_id is None else np.asarray(segment_id).reshape(-1)
    if seg is not None and seg.size != x.size:
        raise InputError(f"{x.size} samples but {seg.size} segment ids")
    _note_outside(el, edges, elevation_deg is not None)
    opts = {"confidence": confidence, "k_weight": k_weight, "min_abs_z": min_abs_z, "bias": bias}
    out: list[BinOverbound] = []
    kept: dict[str, NDArray[np.float64]] = {}
    for lo, hi, sel in _bins(el, edges):
        if not sel.any():
            continue
        where = "all samples" if elevation_deg is None else f"elevation bin [{lo:g}, {hi:g}) deg"
        xs = _clean(x[sel], where, min_samples)
        fit = _one_bin(xs, x[sel], None if seg is None else seg[sel], method, opts)
        std = float(np.std(xs, ddof=1))
        ob = BinOverbound(
            low_deg=lo,
            high_deg=hi,
            n=int(xs.size),
            mean=float(xs.mean()),
            std=std,
            inflation=float(fit["sigma"] / std) if std > 0 else math.inf,
            inflation_upper=float(fit["sigma_upper"] / std) if std > 0 else math.inf,
            **fit,
        )
        out.append(ob)
        kept[ob.label] = xs
    if not out:
        raise InputError(f"no sample has an elevation inside the edges {list(edges_deg)} deg")
    core = 0.0 if method == "paired" else float(min_abs_z)
    return OverboundResult(method, tuple(out), unit, core, kept)
