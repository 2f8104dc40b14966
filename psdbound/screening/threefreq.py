"""Three carriers: ionosphere and multipath told apart by how they scale with frequency.

ROTI of ``L_a - L_b`` moves with the ionosphere and with the multipath of
both carriers, so on its own it cannot say which of the two a high block
holds (:mod:`psdbound.screening.null` bounds how often multipath alone
crosses the threshold, but cannot *name* a block). A third carrier ``c``
can: the first-order ionospheric phase advance is ``40.3 STEC / f^2`` on
every carrier, the same STEC on all, while multipath is a property of each
carrier's own signal.

**The two combinations.** The geometry-free phases ``L_a - L_b`` and
``L_a - L_c`` (metres) span the plane of combinations free of geometry,
clocks and troposphere. In it

* ``D = (L_a - L_c) - r (L_a - L_b)``, ``r = k_ac / k_ab``,
  ``k_xy = 1/f_y^2 - 1/f_x^2`` (GPS L1/L2/L5: ``r = 1.2262``), holds no
  first-order ionosphere: multipath, noise and constant ambiguities only.
  It is the geometry-free, ionosphere-free triple-frequency combination of
  cycle-slip detection and multipath monitoring (Simsky, 2006; Zhao et al.,
  2015).
* ``I = (2 - r)(L_a - L_b) + (2r - 1)(L_a - L_c)`` is the combination of that
  plane orthogonal to ``D`` in per-carrier coefficients (GPS: ``2.226 L1 -
  0.774 L2 - 1.452 L5``): it carries the ionosphere with the best ratio to
  multipath of any geometry-free combination when the carriers' multipath
  is independent and of equal size (2.52 TECU-metres per unit of multipath
  against 1.93 for ``L1 - L2``), and then its multipath is independent of
  ``D``'s.

Both are scaled to unit per-carrier norm and their rates taken like ROT
(samples 30 s apart, the standard deviation over a 5-min block;
:mod:`psdbound.screening.rot`), both expressed in TECU/min through ``I``'s
metres per TECU: ``ROTI_I`` is an ionosphere index, ``ROTI_D`` the same
index of a combination that cannot hold ionosphere ("TECU/min-equivalent";
under equal independent multipath both have the same multipath level).

**The statistic** of a block is ``T = sum ROTI_I^2 / sum ROTI_D^2`` over the
15 min centred on it (:data:`POOL_BLOCKS` blocks of the arc; one block's
variances, from ten 30-s rates each, are too noisy a ratio at the small
false-alarm probabilities used). Under multipath alone ``T`` does not grow
with the multipath: a strong reflection raises both rates together. Under
ionosphere only the numerator grows. Its distribution under multipath alone
is estimated from the series' own blocks as for ROTI (an empirical null,
:func:`psdbound.screening.null.local_scale`): a local scale in elevation (the
30th percentile of ``T`` over the blocks nearest in elevation) and one
shape, ``T / scale ~ F(nu, nu) / F_0.3(nu, nu)`` (a ratio of two variances
of the same samples; ``nu`` fitted to the 10th and 30th percentiles at a
lower bootstrap confidence limit). On simulated multipath alone (independent
Gauss-Markov + white noise per carrier, 8 seeded days of 24 arcs) the
realised exceedance of the fitted quantile is 0.95 times the stated
probability at 1e-2 and 1.19 times at 1e-3.

**When the null is not multipath.** Equal independent multipath on the
three carriers gives a median ``T`` of 1; specular multipath, smaller in
metres on the shorter L1 wavelength, less (measured medians: ESBC 0.59-1.01,
ZIMM 0.71-0.82 across elevations). If the median exceeds :data:`RATIO_MAX`
at some elevation, the typical block holds ionosphere: the polar NYA1 day
has medians 2.4-7.6, the ionosphere combination moving 1.5-2.8 times as
fast as the ionosphere-free one in its typical block. Such a null (or a
heavy-tailed one, ``nu`` below :data:`psdbound.screening.null.NU_DISTURBED`)
is not used: the screening says that the three carriers name the day
disturbed, and neither keeps nor flags a block on their strength.

**How it combines with the ROTI tests** (:mod:`psdbound.screening.screen`):

* a fourth test sharing the false-alarm probability ``p`` (each of the four
  at ``p / 4``, Bonferroni): a block whose ``T`` exceeds the null's
  ``1 - p/4`` quantile and whose ROTI exceeds the ionospheric significance is
  ionosphere, even where strong multipath has raised the ROTI threshold;
* it names blocks: ``T`` in the null's top ``p/4`` tail "ionosphere", ``T``
  below the null's 90th percentile (:data:`KEEP_TAIL`) "multipath";
* a block the ROTI tests flagged but which the three-frequency test names
  multipath is kept: its ROTI is explained by multipath, D moved as much as
  the ionosphere combination did.

Under multipath alone a block is then excluded with a probability of at most
``p`` (the four shares; the keep rule only removes exclusions). Measured on
the simulated days (p = 1e-2): ionosphere spans in 0.3 p of the blocks, 0.6 p
with the ROTI tests alone. A disturbance of 0.3 TECU/min for 45 min on 6 of
24 arcs (3 mm multipath per carrier): 71 of its 72 blocks found with and
without the test; 20-min bursts of multipath three times stronger on every
carrier: 94 of 96 of their blocks cut by the ROTI tests alone, 8 with the
three-frequency test. A disturbed block is kept only when the 15 min around
it look like multipath at the 10 % level, i.e. when its ionospheric rate is
small beside the multipath's: over disturbances of 0.15-1 TECU/min under 3-8
mm multipath (12 seeded days each) the share of disturbed blocks found moved
by -3 to +5 percentage points against the ROTI tests alone (0.15 TECU/min
under 3 mm: 0.65 against 0.68; 0.3 under 8 mm: 0.49 against 0.44).

The test needs the third phase on both sides of each 30-s difference; a
third-carrier slip or loss of lock leaves the difference out (see
:func:`psdbound.arcs.add_third_carrier`). Where a series has no third
carrier, or too few blocks with one to fit the null (fewer than
:data:`psdbound.screening.null.MIN_BLOCKS`), nothing changes, and a series
without a third carrier is screened exactly as before.

References
----------
Simsky, A. (2006). Three's the charm: triple-frequency combinations in
future GNSS. Inside GNSS 1(5), 38-41.

Zhao, Q., Sun, B., Dai, Z., et al. (2015). Real-time detection and repair of
cycle slips in triple-frequency GNSS measurements. GPS Solutions 19(3),
381-391.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import special, stats

from psdbound.screening.null import NU_DISTURBED, Q_HI, Q_LO, local_scale, lower_dof
from psdbound.screening.rot import IONO_CONSTANT_M3_S2, rate_of_tec, roti_blocks

__all__ = [
    "KEEP_TAIL",
    "POOL_BLOCKS",
    "RATIO_MAX",
    "RatioNull",
    "ThreeFrequencyTest",
    "TripleCombination",
    "block_rates",
    "empty_names",
    "fit_ratio_null",
    "pooled_ratio",
    "summary",
    "triple_combination",
]

#: A block whose ratio is consistent with multipath alone at this level (below the null's 90th
#: percentile) is "multipath", and kept when only the ROTI tests flagged it; the conventional
#: 10 % level of the coherence test's rest (:data:`psdbound.screening.coherence.REST_LEVEL`).
KEEP_TAIL = 0.1
#: Blocks whose rates make one ratio (15 min, centred; the persistence test's run length).
POOL_BLOCKS = 3
#: Largest median ratio of a null taken for multipath: equal multipath (metres) on the three
#: carriers gives 1; specular multipath, smaller on the shorter L1 wavelength, less; 2 allows
#: L1's multipath and noise up to 1.6 times L2's and L5's. Above it the typical block itself
#: holds ionosphere (measured median: ESBC 0.64-0.94, ZIMM 0.71-0.82, polar NYA1 2.4-7.1).
RATIO_MAX = 2.0
_TECU = 1e16


@dataclass(frozen=True)
class TripleCombination:
    """The ionosphere combination ``I`` and the ionosphere-free ``D`` of carriers a, b, c.

    Both are ``x (L_a - L_b) + y (L_a - L_c)`` with unit per-carrier norm.

    Attributes
    ----------
    iono : tuple of float
        ``(x, y)`` of ``I`` (sign: positive metres per TECU).
    free : tuple of float
        ``(x, y)`` of ``D``.
    ratio : float
        ``r = k_ac / k_ab`` (GPS L1/L2/L5: 1.2262).
    m_per_tecu : float
        Metres of ``I`` per TECU of slant TEC, m/TECU.
    """

    iono: tuple[float, float]
    free: tuple[float, float]
    ratio: float
    m_per_tecu: float

    def apply(
        self, gf_ab_m: NDArray[np.float64], gf_ac_m: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Return ``I`` and ``D`` (metres) from ``L_a - L_b`` and ``L_a - L_c`` (metres)."""
        (xi, yi), (xd, yd) = self.iono, self.free
        return xi * gf_ab_m + yi * gf_ac_m, xd * gf_ab_m + yd * gf_ac_m


def _unit(x: float, y: float) -> tuple[float, float]:
    """``(x, y)`` scaled so that the carrier coefficients ``(x + y, -x, -y)`` have unit norm."""
    n = float(np.sqrt((x + y) ** 2 + x**2 + y**2))
    return x / n, y / n


def triple_combination(f_a_hz: float, f_b_hz: float, f_c_hz: float) -> TripleCombination:
    """Return the combinations ``I`` and ``D`` of the carriers of frequencies a, b and c.

    Parameters
    ----------
    f_a_hz, f_b_hz, f_c_hz : float
        Carrier frequencies of the pair (``a``, ``b``) and the third (``c``),
        Hz, all different.

    Returns
    -------
    TripleCombination
    """
    k_ab = 1.0 / f_b_hz**2 - 1.0 / f_a_hz**2
    k_ac = 1.0 / f_c_hz**2 - 1.0 / f_a_hz**2
    r = k_ac / k_ab
    xi, yi = _unit(2.0 - r, 2.0 * r - 1.0)
    m_per_tecu = IONO_CONSTANT_M3_S2 * _TECU * (xi * k_ab + yi * k_ac)
    if m_per_tecu < 0:
        xi, yi, m_per_tecu = -xi, -yi, -m_per_tecu
    return TripleCombination((xi, yi), _unit(-r, 1.0), float(r), float(m_per_tecu))


def block_rates(
    t_gps_s: NDArray[np.float64],
    gf_ab_m: NDArray[np.float64],
    gf_ac_m: NDArray[np.float64],
    comb: TripleCombination,
    *,
    n_blocks: int,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Per 5-min block of one arc: the ROTI of ``I`` and of ``D``, TECU/min.

    Parameters
    ----------
    t_gps_s : ndarray
        Sample times of the arc, GPS s.
    gf_ab_m, gf_ac_m : ndarray
        ``L_a - L_b`` and ``L_a - L_c``, metres (NaN: no third phase; a
        difference touching a NaN is left out).
    comb : TripleCombination
    n_blocks : int
        Blocks of the arc (from its first sample, :data:`ROTI_BLOCK_S` each).

    Returns
    -------
    roti_i, roti_d : ndarray
        Standard deviation over each block of the 30-s rate of ``I`` and of
        ``D``, both divided by ``I``'s metres per TECU (TECU/min; for ``D``
        TECU/min-equivalent); NaN for blocks with fewer than half their rates.
    """
    t0 = float(t_gps_s[0])
    t1 = max(float(t_gps_s[-1]), t0 + 1.0)
    out = []
    for series in comb.apply(gf_ab_m, gf_ac_m):
        tm, rot = rate_of_tec(t_gps_s, series, comb.m_per_tecu)
        ok = np.isfinite(rot)
        r = roti_blocks(tm[ok], rot[ok], t0_gps_s=t0, t1_gps_s=t1).roti_tecu_min
        out.append(np.r_[r, np.full(max(0, n_blocks - r.size), np.nan)][:n_blocks])
    return out[0], out[1]


def pooled_ratio(
    roti_i: NDArray[np.float64], roti_d: NDArray[np.float64], *, blocks: int = POOL_BLOCKS
) -> NDArray[np.float64]:
    """Return ``T`` of each block of one arc over the ``blocks`` consecutive blocks centred on it.

    ``T = sum ROTI_I^2 / sum ROTI_D^2`` over the blocks of the window that have
    both (fewer at the arc's ends); NaN where the block itself has none.

    Parameters
    ----------
    roti_i, roti_d : ndarray
        Per block, TECU/min (from :func:`block_rates`).
    blocks : int, default 3
        Window length, blocks (odd).

    Returns
    -------
    ndarray
        Dimensionless.
    """
    ok = np.isfinite(roti_i) & np.isfinite(roti_d) & (roti_d > 0)
    num, den = np.where(ok, roti_i**2, 0.0), np.where(ok, roti_d**2, 0.0)
    kernel, pad = np.ones(blocks), np.zeros(blocks // 2)
    num_w = np.convolve(np.r_[pad, num, pad], kernel, mode="valid")
    den_w = np.convolve(np.r_[pad, den, pad], kernel, mode="valid")
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(ok, num_w / den_w, np.nan)


def _f_ratio(nu: float) -> float:
    """``Q_HI`` over ``Q_LO`` quantile of ``F(nu, nu)``.

    ``fdtri(nu, nu, q)`` is what ``scipy.stats.f.ppf(q, nu, nu)`` computes
    (bit for bit), without the distribution framework's overhead (see
    :func:`psdbound.screening.null._ratio`).
    """
    return float(special.fdtri(nu, nu, Q_HI) / special.fdtri(nu, nu, Q_LO))


@dataclass(frozen=True)
class RatioNull:
    """``T = ROTI_I^2 / ROTI_D^2`` under multipath alone: a local scale and an F shape.

    ``T / q(el) ~ F(nu, nu) / F_Q_HI(nu, nu)``, ``q(el)`` the local ``Q_HI``
    quantile of ``T`` (interpolated in elevation).

    Attributes
    ----------
    elevation_deg : ndarray
        Elevations of the tabulated scale, degrees (increasing).
    q_hi : ndarray
        The local ``Q_HI`` quantile of ``T`` there (dimensionless).
    dof : float
        ``nu``.
    n_blocks : int
        Blocks the null was fitted on.
    """

    elevation_deg: NDArray[np.float64]
    q_hi: NDArray[np.float64]
    dof: float
    n_blocks: int

    @property
    def trusted(self) -> bool:
        """Whether the null looks like multipath alone.

        Its shape not heavy-tailed (``dof >= NU_DISTURBED``) and its median
        at most :data:`RATIO_MAX` at every elevation (a larger median means
        that the typical block holds ionosphere: the null is not multipath).
        """
        return self.dof >= NU_DISTURBED and float(self.median().max()) <= RATIO_MAX

    def median(self) -> NDArray[np.float64]:
        """Return the median of ``T`` at the tabulated elevations (dimensionless)."""
        return self.level(self.elevation_deg, 0.5)

    def level(self, elevation_deg: ArrayLike, tail: float) -> NDArray[np.float64]:
        """Return the ``T`` a block at ``elevation_deg`` exceeds with probability ``tail``.

        Parameters
        ----------
        elevation_deg : array_like
            Mean elevation of each block, degrees.
        tail : float
            Probability under multipath alone.

        Returns
        -------
        ndarray
            Dimensionless.
        """
        q = np.interp(np.asarray(elevation_deg, dtype=float), self.elevation_deg, self.q_hi)
        nu = self.dof
        return q * stats.f.isf(tail, nu, nu) / stats.f.ppf(Q_HI, nu, nu)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {
            "elevation_deg": self.elevation_deg.tolist(),
            "median_ratio": self.median().tolist(),
            "dof": self.dof,
            "n_blocks": self.n_blocks,
            "trusted": self.trusted,
        }


def fit_ratio_null(ratio: ArrayLike, elevation_deg: ArrayLike) -> RatioNull | None:
    """Fit the null of ``T`` from all blocks of a series.

    Parameters
    ----------
    ratio : array_like
        ``T`` of every block (NaN: no third carrier there).
    elevation_deg : array_like
        Mean elevation of every block, degrees.

    Returns
    -------
    RatioNull or None
        None with too few usable blocks (:data:`psdbound.screening.null.MIN_BLOCKS`).
    """
    scale = local_scale(ratio, elevation_deg)
    if scale is None:
        return None
    grid, q, u = scale
    return RatioNull(grid, q, lower_dof(u, _f_ratio), u.size)


@dataclass(frozen=True)
class ThreeFrequencyTest:
    """The three-frequency test of a series: its null and its share of ``p``.

    Attributes
    ----------
    null : RatioNull
    false_alarm : float
        False-alarm probability of this test per block under multipath alone.
    floor_tecu_min : float
        Smallest ROTI of ``L_a - L_b`` of a block it flags (the ionospheric
        significance), TECU/min.
    """

    null: RatioNull
    false_alarm: float
    floor_tecu_min: float

    def name(
        self,
        ratio: NDArray[np.float64],
        elevation_deg: NDArray[np.float64],
        roti_tecu_min: NDArray[np.float64],
    ) -> NDArray[np.str_]:
        """Name each block: "ionosphere", "multipath" or "" (neither, or no third carrier).

        "ionosphere": ``T`` above the null's ``1 - false_alarm`` quantile and
        ROTI above the floor; "multipath": ``T`` below the null's
        ``1 - KEEP_TAIL`` quantile.
        """
        r = np.asarray(ratio, dtype=float)
        ok = np.isfinite(r)
        out = np.full(r.size, "", dtype="<U10")
        high = ok & (r > self.null.level(elevation_deg, self.false_alarm))
        out[high & (np.nan_to_num(roti_tecu_min) > self.floor_tecu_min)] = "ionosphere"
        out[ok & (r <= self.null.level(elevation_deg, KEEP_TAIL))] = "multipath"
        return out

    def decide(self, flagged: NDArray[np.bool_], named: NDArray[np.str_]) -> NDArray[np.bool_]:
        """Return the blocks that are ionosphere, given the ROTI tests' flags and the names.

        A block named "ionosphere" is flagged; one the ROTI tests flagged but
        named "multipath" is kept.
        """
        return (flagged & (named != "multipath")) | (named == "ionosphere")


def summary(
    test: ThreeFrequencyTest | None,
    rnull: RatioNull | None,
    signal: str | None,
    n_arcs: int,
    arcs_with: int,
    blocks: list[dict[str, Any]],
    flagged: list[NDArray[np.bool_]],
) -> dict[str, Any]:
    """Return the ``screening.three_frequency`` section: the signal, the arcs, what was named.

    Parameters
    ----------
    test : ThreeFrequencyTest or None
        None: the test did not run (too few blocks, a null that is not multipath).
    rnull : RatioNull or None
        The fitted null (None: too few blocks, or the test switched off).
    signal : str or None
        The third phase code.
    n_arcs, arcs_with : int
        Arcs screened, and of them those with a third-carrier rate in a block.
    blocks : list of dict
        Per arc, its blocks (``ratio``, ``named``).
    flagged : list of ndarray of bool
        Per arc, the blocks the ROTI tests flagged.
    """
    named = np.concatenate([b["named"] for b in blocks]) if blocks else np.zeros(0, str)
    roti_flag = np.concatenate(flagged) if flagged else np.zeros(0, bool)
    ratio = np.concatenate([b["ratio"] for b in blocks]) if blocks else np.zeros(0)
    return {
        "signal": signal,
        "arcs": n_arcs,
        "arcs_with_third": arcs_with,
        "blocks_with_third": int(np.isfinite(ratio).sum()),
        "blocks_above_multipath_ratio": int((ratio > RATIO_MAX).sum()),
        "applied": test is not None,
        "false_alarm_per_block": None if test is None else test.false_alarm,
        "null": None if rnull is None else rnull.to_dict(),
        "named_ionosphere": int((named == "ionosphere").sum()),
        "named_multipath": int((named == "multipath").sum()),
        "added": int(((named == "ionosphere") & ~roti_flag).sum()),
        "confirmed": int(((named == "ionosphere") & roti_flag).sum()),
        "kept_as_multipath": int(((named == "multipath") & roti_flag).sum()),
    }


def empty_names(n: int) -> NDArray[np.str_]:
    """Return ``n`` empty block names (no three-frequency test)."""
    return np.full(n, "", dtype="<U10")
