"""Paired Gaussian overbound of a sample: a bias ``b`` and a sigma ``s`` ([Rife2006]_).

The pair ``N(-b, s)`` (left bound) and ``N(+b, s)`` (right bound) overbounds a
distribution ``F`` when ``F(x) <= Phi((x + b) / s)`` on the left and ``F(x) >=
Phi((x - b) / s)`` on the right: the left bound puts at least as much
probability below every ``x`` as ``F``, the right bound at least as much above.
Checked here at every sample point -- the empirical CDF at the unfavourable
side of each jump, the core included (no point is exempt; ``b`` must reach the
median) -- the left condition for the points below the median and the right
one for those above.

Construction: the samples are centred on their median ``m``; for a core
half-width ``c >= 0`` the smallest ``s(c)`` meeting both conditions for
``N(-+c, s)`` about ``m`` is the largest ``d / Phi^-1(1 - t)`` over the points
beyond ``m -+ c`` (``d`` the distance beyond ``c``, ``t`` the empirical tail);
``c`` is chosen on a grid from 0 to the half-width holding the central
``core_fraction`` of the samples (default 20 %: the core the two-step bound
exempts is *covered* here, by the bias) to minimise ``k_weight s(c) + c`` (what
the pair costs a protection level ``K sigma + b``), and the bias is ``b = |m| +
c``. The cap matters: a wider core lets a thin Gaussian with a large bias pass
through the few extreme samples and then fall short beyond them, where the
data say nothing. So a
sample shifted by ``m0`` keeps its ``c`` and ``s``, and its bias grows by
exactly ``|m0|`` when the median moves away from 0 by it.

``tail_map`` lets the caller replace the empirical tails by upper confidence
bounds (:func:`psdbound.aviation.sample_size.upper_tail`), which gives the pair
at that confidence.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.stats import norm

from psdbound.errors import InputError

__all__ = ["DEFAULT_CORE_FRACTION", "DEFAULT_K_WEIGHT", "paired_overbound"]

#: Weight of ``s`` against ``b`` in the choice of the pair: the VPL multiplier ``K_ffmd``
#: for M = 3 (a trade-off weight, not a safety parameter).
DEFAULT_K_WEIGHT = 5.81
#: Core half-widths tried, as fractions of the largest one allowed.
_GRID = np.linspace(0.0, 1.0, 61)
#: Default fraction of the samples (about the median) the bias may cover.
DEFAULT_CORE_FRACTION = 0.2

TailMap = Callable[[NDArray[np.float64]], NDArray[np.float64]]


def _side(
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


def paired_overbound(
    samples: ArrayLike,
    *,
    k_weight: float = DEFAULT_K_WEIGHT,
    core_fraction: float = DEFAULT_CORE_FRACTION,
    tail_map: TailMap | None = None,
) -> tuple[float, float]:
    """Bias and sigma of a paired Gaussian overbound of ``samples`` (no exempted core).

    Parameters
    ----------
    samples : array_like
        Errors, any unit (at least 2, finite).
    k_weight : float, default 5.81
        Weight of the sigma against the bias when choosing the pair (> 0).
    core_fraction : float, default 0.2
        Largest fraction of the samples, about the median, the core half-width
        ``c`` may span (in [0, 1)).
    tail_map : callable, optional
        Maps the empirical tail probabilities to the ones to cover (e.g. upper
        confidence bounds); default: the empirical tails.

    Returns
    -------
    bias : float
        ``b >= |median|``, unit of the samples.
    sigma : float
        ``s``, unit of the samples (``inf`` if no core width on the grid works).
    """
    x = np.sort(np.asarray(samples, dtype=float).reshape(-1))
    if x.size < 2 or not np.isfinite(x).all():
        raise InputError("a paired overbound needs at least 2 finite samples")
    if not k_weight > 0:
        raise InputError(f"k_weight must be > 0, got {k_weight}")
    if not 0.0 <= core_fraction < 1.0:
        raise InputError(f"core_fraction must be in [0, 1), got {core_fraction}")
    n = x.size
    m = float(np.median(x))
    y = x - m
    i = np.arange(1, n + 1)
    left, right = y < 0, y > 0
    t_left, t_right = i[left] / n, (n - i[right] + 1) / n
    if tail_map is not None:
        t_left, t_right = tail_map(t_left), tail_map(t_right)
    c = _GRID * float(np.quantile(np.abs(y), core_fraction))
    s = np.maximum(_side(-y[left], t_left, c), _side(y[right], t_right, c))
    cost = k_weight * s + c
    best = int(np.argmin(cost))
    return abs(m) + float(c[best]), float(s[best])
