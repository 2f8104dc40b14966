"""Paired Gaussian overbound of a sample: a bias ``b`` and a sigma ``s`` ([Rife2006]_).

The bounding function. From the Gaussian core ``N(0, s)`` and the bias
``b >= 0`` build one symmetric, unimodal function: the core's left half
moved to ``-b``, its right half moved to ``+b``, and the gap between them
filled at the core's peak height ``phi(0) / s``,

    f_b(x) = phi(max(|x| - b, 0) / s) / s,

the upper envelope of every core density ``N(c, s)`` with ``|c| <= b``. Its
area is ``1 + 2 b phi(0) / s``: more than one, so its running integrals can
reach 1 at a finite point, which a Gaussian's never does. The *left*
bounding function is its integral from the left, ``G_L(x) = int_{-inf}^x
f_b``, the *right* one its integral from the right, ``G_R(x) = int_x^{inf}
f_b``. Below ``-b``, ``G_L`` is the Gaussian CDF ``Phi((x + b) / s)``; above
``+b``, ``G_R`` is the Gaussian tail ``Q((x - b) / s)``.

The conditions. The pair overbounds an error of CDF ``F`` when, on the
*whole* real line,

    F(x) <= G_L(x)    and    1 - F(x^-) <= G_R(x):

the bounding function puts at least as much weight below every ``x`` as the
error has probability there, and at least as much above it. Both conditions
bind everywhere: in the error's left tail the first is the familiar
Gaussian tail bound with bias ``-b``, but beyond the centre it still asks
that the error's upper part is covered by the plateau and the right half
(an error whose probability piles up near its centre, a point mass for
instance, needs a plateau wide enough, i.e. a bias large enough, for it).

Why both and everywhere. For independent errors ``X, Y`` the running
integrals of the convolution of their bounding functions bound the
running probabilities of ``X + Y`` on both sides (the bounding functions
are non-negative measures, so Fubini's theorem carries each inequality
through the convolution integral), and a symmetric bounding function
serves for ``-X`` as well. Checking a condition on one half of the line
only (the left one below the median, the right one above, as this module
did before) does not carry through: the half that was not checked enters
the convolution too. What the theorem bounds is the convolution of the
bounding functions; the protection level reads it as the Gaussian pair
``N(-+sum |a_i| b_i, sqrt(sum a_i^2 s_i^2))``, a close but not exact reading
(``docs/method/aviation.rst`` gives how close).

What is checked here. At every sample point, with the empirical CDF at the
unfavourable side of each jump: ``G_L(x_(i)) >= i / n`` and ``G_R(x_(i)) >=
(n - i + 1) / n`` (optionally through ``tail_map``, e.g. upper confidence
bounds, :func:`psdbound.aviation.sample_size.upper_tail`). Nothing is
exempt. A sample says nothing beyond its extremes; there the Gaussian tails
are the assumption.

Construction. The samples are centred on their median ``m``; for a core
half-width ``c`` the smallest ``s(c)`` meeting the tail conditions (the
points beyond ``m -+ c``) is the largest ``d / Phi^-1(1 - t)`` there (``d``
the distance beyond ``c``, ``t`` the tail). The remaining conditions (the
points within ``c`` of the median and the opposite sides) get *harder* as
``s`` grows -- the plateau's height is ``phi(0) / s`` -- so ``s(c)`` is the
only candidate at that ``c``, and whether it passes is monotone in ``c`` (a
wider plateau covers more). The smallest passing half-width ``c_min`` is
found by bisection; ``c`` is then chosen on a grid from ``c_min`` to the
larger of ``c_min`` and the half-width holding the central
``core_fraction`` of the samples to minimise ``k_weight s(c) + c`` (what
the pair costs a protection level ``K sigma + b``); the bias is ``b = |m| +
c`` (the bounding function about 0 with bias ``|m| + c`` covers the one
about ``m`` with ``c``). The cap keeps a thin Gaussian with a large bias
from passing through the few extreme samples and falling short beyond
them, where the data say nothing; it is lifted only as far as the
conditions need. A sample shifted by ``m0`` keeps ``c`` and ``s``, and its
bias grows by ``|m0|`` when the median moves away from 0 by it.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.stats import norm

from psdbound.errors import InputError

__all__ = [
    "DEFAULT_CORE_FRACTION",
    "DEFAULT_K_WEIGHT",
    "paired_bounding_functions",
    "paired_overbound",
]

#: Weight of ``s`` against ``b`` in the choice of the pair: the VPL multiplier ``K_ffmd``
#: for M = 3 (a trade-off weight, not a safety parameter).
DEFAULT_K_WEIGHT = 5.81
#: Core half-widths tried, as fractions of the span from ``c_min`` to the cap.
_GRID = np.linspace(0.0, 1.0, 61)
#: Default fraction of the samples (about the median) the bias may cover beyond what the
#: conditions need.
DEFAULT_CORE_FRACTION = 0.2
#: Peak of the standard normal density, ``1 / sqrt(2 pi)``.
_PHI0 = 1.0 / math.sqrt(2.0 * math.pi)
#: Bisection steps for the smallest passing core half-width (relative step 2^-50).
_BISECT = 50
#: Relative slack of the checks (round-off of ``Phi`` near 1).
_TOL = 1e-12

TailMap = Callable[[NDArray[np.float64]], NDArray[np.float64]]


def _left_integral(x: NDArray[np.float64], c: float, s: float) -> NDArray[np.float64]:
    """``int_{-inf}^x f_c`` of the bounding function with bias ``c`` and scale ``s > 0``."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        low = norm.cdf((np.minimum(x, -c) + c) / s)
        flat = _PHI0 * (np.clip(x, -c, c) + c) / s
        high = norm.cdf((np.maximum(x, c) - c) / s) - 0.5
    return low + np.nan_to_num(flat, nan=0.0) + high


def paired_bounding_functions(
    x: ArrayLike, bias: float, sigma: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Return the bounding functions ``G_L(x)`` and ``G_R(x)`` of the pair ``(b, s)``.

    Parameters
    ----------
    x : array_like
        Points, unit of the errors.
    bias : float
        ``b >= 0``, unit of the errors.
    sigma : float
        ``s > 0``, unit of the errors.

    Returns
    -------
    left : ndarray
        ``G_L(x) = int_{-inf}^x f_b`` (dimensionless; reaches 1 at a finite point when
        ``b > 0``). The pair overbounds an error of CDF ``F`` if ``F <= G_L`` everywhere.
    right : ndarray
        ``G_R(x) = int_x^{inf} f_b``; the second condition is ``P(X >= x) <= G_R(x)``.
    """
    if not bias >= 0 or not sigma > 0:
        raise InputError(f"need bias >= 0 and sigma > 0, got {bias}, {sigma}")
    p = np.asarray(x, dtype=float)
    return _left_integral(p, bias, sigma), _left_integral(-p, bias, sigma)


def _tail_sigma(
    d: NDArray[np.float64], tail: NDArray[np.float64], c: NDArray[np.float64]
) -> NDArray[np.float64]:
    """``s(c)`` of one side: ``max (d - c) / Phi^-1(1 - t)`` over ``d > c`` (inf: a tail >= 1/2)."""
    with np.errstate(divide="ignore"):
        z = norm.isf(tail)
    out = np.zeros(c.size)
    for j, cj in enumerate(c):
        beyond = d > cj
        if not beyond.any():
            continue
        if (tail[beyond] >= 0.5).any():
            out[j] = math.inf
        else:
            out[j] = float(np.max((d[beyond] - cj) / z[beyond]))
    return out


class _Sample:
    """Median-centred sorted sample and its cumulative probabilities to cover."""

    def __init__(self, x: NDArray[np.float64], tail_map: TailMap | None) -> None:
        n = x.size
        self.median = float(np.median(x))
        self.y = x - self.median
        i = np.arange(1, n + 1)
        below, above = i / n, (n - i + 1) / n  # F(x) and P(X >= x), unfavourable sides
        if tail_map is not None:
            below, above = tail_map(below), tail_map(above)
        self.below = np.minimum(np.asarray(below, dtype=float), 1.0)
        self.above = np.minimum(np.asarray(above, dtype=float), 1.0)
        left, right = self.y < 0, self.y > 0
        self.d_left, self.t_left = -self.y[left], self.below[left]
        self.d_right, self.t_right = self.y[right], self.above[right]
        self.span = float(np.max(np.abs(self.y)))

    def sigma(self, c: NDArray[np.float64]) -> NDArray[np.float64]:
        """Smallest ``s`` meeting the tail conditions, per core half-width."""
        return np.maximum(
            _tail_sigma(self.d_left, self.t_left, c), _tail_sigma(self.d_right, self.t_right, c)
        )

    def passes(self, c: float) -> bool:
        """Whether ``(c, s(c))`` about the median meets both conditions at every point."""
        s = float(self.sigma(np.array([c]))[0])
        if not math.isfinite(s):
            return False
        s = max(s, 1e-300 * max(self.span, 1.0))  # s = 0: every point within c (pure bias)
        left = _left_integral(self.y, c, s) >= self.below * (1.0 - _TOL)
        right = _left_integral(-self.y, c, s) >= self.above * (1.0 - _TOL)
        return bool(left.all() and right.all())

    def smallest_core(self) -> float:
        """Smallest passing half-width ``c_min`` (bisection; passing is monotone in ``c``)."""
        if self.passes(0.0):
            return 0.0
        lo, hi = 0.0, 2.0 * self.span
        for _ in range(_BISECT):
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if self.passes(mid) else (mid, hi)
        return hi


def paired_overbound(
    samples: ArrayLike,
    *,
    k_weight: float = DEFAULT_K_WEIGHT,
    core_fraction: float = DEFAULT_CORE_FRACTION,
    tail_map: TailMap | None = None,
) -> tuple[float, float]:
    """Bias and sigma of a paired Gaussian overbound of ``samples`` (both conditions everywhere).

    Parameters
    ----------
    samples : array_like
        Errors, any unit (at least 2, finite).
    k_weight : float, default 5.81
        Weight of the sigma against the bias when choosing the pair (> 0).
    core_fraction : float, default 0.2
        Fraction of the samples, about the median, whose half-width caps the core
        half-width ``c`` where the conditions do not need more (in [0, 1)).
    tail_map : callable, optional
        Maps the empirical cumulative probabilities to the ones to cover (e.g. upper
        confidence bounds); default: the empirical ones.

    Returns
    -------
    bias : float
        ``b >= |median|``, unit of the samples.
    sigma : float
        ``s``, unit of the samples (0 for a sample within ``b`` of 0 everywhere).
    """
    x = np.sort(np.asarray(samples, dtype=float).reshape(-1))
    if x.size < 2 or not np.isfinite(x).all():
        raise InputError("a paired overbound needs at least 2 finite samples")
    if not k_weight > 0:
        raise InputError(f"k_weight must be > 0, got {k_weight}")
    if not 0.0 <= core_fraction < 1.0:
        raise InputError(f"core_fraction must be in [0, 1), got {core_fraction}")
    data = _Sample(x, tail_map)
    if data.span == 0.0:
        return abs(data.median), 0.0
    c_min = data.smallest_core()
    c_cap = max(c_min, float(np.quantile(np.abs(data.y), core_fraction)))
    c = c_min + _GRID * (c_cap - c_min)
    s = data.sigma(c)
    best = int(np.argmin(k_weight * s + c))
    return abs(data.median) + float(c[best]), float(s[best])
