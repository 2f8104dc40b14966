"""A bound for any evenly sampled error series: :func:`bound_series`.

The GNSS pipeline (:func:`psdbound.fit`) isolates multipath, screens it and
cuts it into stationary windows; from there on it uses the code below. Any
other error (an INS, a clock, a residual) sampled evenly can enter here
directly: stationary stretches in, a Gauss-Markov + white-noise bound with a
stated confidence, a verdict and the band it holds on out.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.common.options import Number
from psdbound.errors import InputError
from psdbound.spectra.bands import BandSpectra, resolved_from_hz
from psdbound.spectra.bound import BoundFit
from psdbound.spectra.cells import CellCheck
from psdbound.spectra.estimators import MIN_SAMPLES, PSDEstimate, estimate_psd, real_samples
from psdbound.spectra.intervals import ModelSet
from psdbound.spectra.lowest import LowestFrequencies
from psdbound.spectra.lowfreq import POLICIES, TAU_MAX_S, LowFrequency, low_frequency_reasons
from psdbound.spectra.models import INTERVAL_S, GaussMarkovWhiteNoise
from psdbound.spectra.names import METHODS
from psdbound.spectra.options import check_estimator_options
from psdbound.spectra.ordinates import lowest_ordinates
from psdbound.spectra.pooled import PooledLimits
from psdbound.spectra.stated import fit_stated_bound, statement
from psdbound.spectra.unresolved import UnresolvedGroups

__all__ = ["SeriesBound", "bound_series", "split_stretches"]

#: Shortest stretch used by default, samples (shorter ones are reported, not used).
MIN_STRETCH = 64
#: Verdicts.
BOUNDED, NOT_BOUNDED = "bounded", "not-bounded"


@dataclass(frozen=True)
class SeriesBound:
    """Result of :func:`bound_series`.

    Attributes
    ----------
    bound : GaussMarkovWhiteNoise
        The bound (``psd``, ``sampled_psd``, ``variance_m2``, ...).
    verdict : {"bounded", "not-bounded"}
        Whether the statement :attr:`covers` can be relied on.
    verdict_reasons : tuple of str
        Why not (empty when bounded).
    f_min_hz : float
        Lowest frequency the bound is stated for, Hz (it holds up to Nyquist).
    covers : str
        The statement, in words.
    fit : BoundFit
        The fitted bound with its search trace and tightness figures.
    psds : tuple of PSDEstimate
        One estimate per stretch used.
    bands : BandSpectra
        Band averages of the estimates.
    limits : PooledLimits
        The limits the bound lies above.
    notes : tuple of str
        Input that was not used, and why.
    model_set : ModelSet or None
        GM + white-noise models consistent with the main group's pooled
        spectrum, widened to contain the bound
        (:func:`psdbound.spectra.intervals.model_set`); None with too few
        bands.
    low_frequency : LowFrequency or None
        What the bound covers below ``f_min_hz``, down to 0 Hz
        (:mod:`psdbound.spectra.lowfreq`).
    lowest_frequencies : LowestFrequencies or None
        The bound's expected estimate at the windows' lowest Fourier
        frequencies against each shape group's upper limit
        (:mod:`psdbound.spectra.lowest`); None when no window has a Fourier
        frequency below ``f_min_hz``.
    cells : CellCheck or None
        The groups' mean spectra on cells of the estimator's resolution
        against the bound (:mod:`psdbound.spectra.cells`); None for an
        estimator other than the multitaper.
    unresolved : UnresolvedGroups or None
        The shape groups none of whose windows resolves ``f_min_hz``, and
        the envelope the bound was held above between ``f_min_hz`` and
        where they resolve (:mod:`psdbound.spectra.unresolved`).
    """

    bound: GaussMarkovWhiteNoise
    verdict: str
    verdict_reasons: tuple[str, ...]
    f_min_hz: float
    covers: str
    fit: BoundFit
    psds: tuple[PSDEstimate, ...]
    bands: BandSpectra
    limits: PooledLimits
    notes: tuple[str, ...] = field(default_factory=tuple)
    model_set: ModelSet | None = None
    low_frequency: LowFrequency | None = None
    lowest_frequencies: LowestFrequencies | None = None
    cells: CellCheck | None = None
    unresolved: UnresolvedGroups | None = None

    @property
    def n_windows(self) -> int:
        """Stretches bounded."""
        return len(self.psds)

    def summary(self) -> str:
        """Return a text summary: verdict, bound, band, statement and notes."""
        b = self.bound
        lines = [
            "=" * 72,
            "Gauss-Markov + white-noise bound of an error series".center(72),
            "=" * 72,
            f"{'verdict':<28}{self.verdict}",
            f"{'sigma_GM':<28}{b.sigma_gm_m:.4g} m",
            f"{'tau':<28}{b.tau_s:.4g} s",
            f"{'sigma_WN (per sample)':<28}{b.sigma_wn_m:.4g} m",
            f"{'sampling interval':<28}{b.dt_s:g} s (Nyquist {b.nyquist_hz:.4g} Hz)",
            f"{'stated from':<28}{self.f_min_hz:.4g} Hz to Nyquist",
            f"{'windows':<28}{self.n_windows} in {self.limits.n_groups} shape group(s)",
            f"{'bound over limits (median)':<28}{self.fit.gap_db_median:.1f} dB above the limits",
            *self._check_lines(),
            "-" * 72,
            self.covers,
        ]
        lines += [f"not bounded: {r}" for r in self.verdict_reasons]
        lines += [f"note: {n}" for n in self.notes + self.limits.notes]
        return "\n".join(lines + ["=" * 72])

    def _check_lines(self) -> list[str]:
        """One line each for the checks below ``f_min`` and on resolution cells."""
        out = []
        if self.low_frequency is not None:
            out.append(f"{'below f_min':<28}{self.low_frequency.status}")
        low = self.lowest_frequencies
        if low is not None:
            what = (
                f"raised (its expectation was {low.before.min():.2f} x the limit)"
                if low.raised
                else "met (no raise)"
            )
            out.append(f"{'lowest frequencies (j/T)':<28}{what}")
        c = self.cells
        if c is not None:
            what = (
                f"peak(s) in {c.shaped_hz.size} band(s) from {c.shaped_hz.min():.3g} Hz, held"
                if c.shaped_hz.size
                else "no peak"
            )
            what += f"; {c.refuted_hz.size} refuted cell(s)" if c.refuted_hz.size else ""
            out.append(f"{'resolution cells':<28}{what}")
        return out


#: A frequency: a finite number > 0 Hz.
_FREQUENCY_HZ = Number(lo=0.0, lo_open=True, unit="Hz")
#: The numeric options of :func:`bound_series` and what each allows.
_NUMBERS = {
    "confidence_level": Number(lo=0.0, hi=1.0, lo_open=True, hi_open=True),
    "coverage": Number(lo=0.5, hi=1.0, lo_open=True),
    "shape_alpha": Number(lo=0.0, hi=1.0, lo_open=True, hi_open=True),
    "bands_per_decade": Number(lo=1, hi=100, integer=True),
    "min_samples": Number(lo=MIN_SAMPLES, integer=True),
    "cluster_correlation": Number(lo=0.0, hi=1.0),
}


def _check_options(
    dt_s: object,
    tau_max_s: object,
    f_min_hz: object,
    low_frequency_policy: str,
    numbers: dict[str, Any],
) -> tuple[float, float, float | None, dict[str, Any]]:
    """Return the sampling interval, tau_max_s, f_min_hz and numeric options, checked.

    Raises
    ------
    InputError
        A value of the wrong type or out of its range (naming the option).
    """
    dt = float(INTERVAL_S("sampling interval dt_s", dt_s))
    tau_max = float(INTERVAL_S("tau_max_s", tau_max_s))  # >= dt / 2: fit_stated_bound
    f_min = None if f_min_hz is None else float(_FREQUENCY_HZ("f_min_hz", f_min_hz))
    if low_frequency_policy not in POLICIES:
        raise InputError(
            f"low_frequency_policy must be one of {POLICIES}, got {low_frequency_policy!r}"
        )
    checked = {k: _NUMBERS[k](k, v) for k, v in numbers.items()}
    return dt, tau_max, f_min, checked


def _estimator_options(estimator: str, options: object) -> dict[str, Any]:
    """Return the estimator's options checked by their schema (``'k': 2.5`` is refused).

    Raises
    ------
    InputError
        An unknown estimator, options that are not a dict, or an option it
        does not have or of the wrong type or range
        (:func:`psdbound.spectra.options.check_estimator_options`).
    """
    if estimator not in METHODS:
        raise InputError(f"estimator must be one of {', '.join(METHODS)}, got {estimator!r}")
    if options is not None and not isinstance(options, Mapping):
        raise InputError(
            f"estimator_options must be a dict of the estimator's options, got {options!r}"
        )
    return check_estimator_options(estimator, dict(options or {}))


def _stretches(
    series: ArrayLike | Sequence[ArrayLike], min_samples: int
) -> tuple[list[NDArray[np.float64]], tuple[str, ...]]:
    """Return the stretches of :func:`split_stretches`; refuse an input with none."""
    stretches, notes = split_stretches(series, min_samples=min_samples)
    if not stretches:
        raise InputError(
            f"no stretch of at least {min_samples} finite samples to bound"
            + (f" ({notes[0]})" if notes else "")
        )
    return stretches, notes


def _mean_note(stretches: Sequence[NDArray[np.float64]]) -> tuple[str, ...]:
    """Say when a stretch's removed mean is large next to its fluctuation (a bias not bounded)."""
    ratios = [abs(float(np.mean(x))) / max(float(np.std(x)), 1e-300) for x in stretches]
    k = int(np.argmax(ratios))
    if ratios[k] <= 0.25:
        return ()
    n = sum(r > 0.25 for r in ratios)
    return (
        f"{n} of {len(stretches)} stretch(es) have a mean above a quarter of their standard "
        f"deviation (stretch {k}: mean {float(np.mean(stretches[k])):.4g}, {ratios[k]:.3g} "
        "times its standard deviation); each stretch's mean is removed before its spectrum, "
        "so the bound covers the fluctuation about it, not that bias",
    )


def _cluster_labels(
    clusters: ArrayLike | None, cluster_correlation: float
) -> NDArray[np.int64] | None:
    """Integer cluster labels, or None; a correlation without labels is an error (no effect)."""
    if clusters is None:
        if cluster_correlation:
            raise InputError(
                f"cluster_correlation {cluster_correlation!r} needs clusters (one label per "
                "stretch used): without them it would change nothing"
            )
        return None
    labels = np.asarray(clusters)
    if labels.dtype.kind not in "iu" and not (
        labels.dtype.kind == "f" and np.all(np.isfinite(labels)) and np.all(labels % 1 == 0)
    ):
        raise InputError(f"clusters must be integer labels, one per stretch used, got {clusters!r}")
    return labels.astype(np.int64)


def _f_min_note(given_hz: float | None, stated_hz: float) -> tuple[str, ...]:
    """Return a note when a given ``f_min_hz`` lies below where the bound is stated from."""
    if given_hz is None or stated_hz <= given_hz * (1.0 + 1e-9):
        return ()
    return (
        f"f_min_hz {given_hz:.4g} Hz lies below what the windows' estimates resolve: the bound "
        f"is stated from {stated_hz:.4g} Hz (resolved_from_hz of each estimate: below it an "
        "estimate is not an average of the PSD near its frequency)",
    )


def _unresolved_note(resolved_hz: list[float], stated_hz: float) -> tuple[str, ...]:
    """Return a note when some windows do not resolve the lowest stated frequency.

    ``resolved_hz``: where each window's estimate resolves from. Measured
    (``slowuneq`` of ``benchmarks/bound_coverage.py``): a slow reflector in
    such a short window that the shape tests leave in a longer windows' group
    can lie above the bound there, unseen.
    """
    resolved = np.asarray(resolved_hz)
    short = resolved > stated_hz * (1.0 + 1e-9)
    if not short.any():
        return ()
    return (
        f"{int(short.sum())} of {resolved.size} windows resolve only from "
        f"{resolved.max():.4g} Hz, above the lowest stated frequency {stated_hz:.4g} Hz (set by "
        "the longest windows): between the two the statement rests on the longer windows of "
        "their shape group (a group of short windows alone is carried down by its admitted "
        "models), and a short window of another shape that no test separates is not seen "
        f"there; to state the bound only where every window resolves, give "
        f"f_min_hz={resolved.max():.4g}",
    )


def _is_one_series(series: object) -> bool:
    """Whether the input is one series (an array or a flat list of numbers).

    Raises
    ------
    InputError
        Not an array or a sequence (None, a number, a dict), or a list that
        mixes numbers and arrays.
    """
    if isinstance(series, np.ndarray):
        return series.ndim == 1
    if isinstance(series, Mapping) or not isinstance(series, Sequence) or isinstance(series, str):
        raise InputError(
            "series must be a 1-D array or a list of 1-D arrays (one per stretch), got "
            f"{type(series).__name__}"
        )
    scalars = [bool(np.isscalar(x)) for x in series]
    if any(scalars) and not all(scalars):
        raise InputError(
            f"series mixes numbers and arrays (item {scalars.index(not scalars[0])}): give one "
            "1-D series, or a list of 1-D arrays"
        )
    return bool(scalars) and scalars[0]


def split_stretches(
    series: ArrayLike | Sequence[ArrayLike], *, min_samples: int = MIN_STRETCH
) -> tuple[list[NDArray[np.float64]], tuple[str, ...]]:
    """Split the input at NaN gaps into finite stretches; report what is not used.

    Parameters
    ----------
    series : array_like or sequence of array_like
        One 1-D series or several; NaN (or a masked sample of a
        :class:`numpy.ma.MaskedArray`) marks a gap.
    min_samples : int, default 64
        Shortest stretch kept.

    Returns
    -------
    stretches : list of ndarray
    notes : tuple of str
        The stretches left out (too short), counted.

    Raises
    ------
    InputError
        An item that is not 1-D, or an infinite value.
    """
    if isinstance(series, Iterator):  # a generator of stretches: read once
        series = list(series)
    items = [series] if _is_one_series(series) else list(series)  # type: ignore[arg-type]
    out, short, short_n = [], 0, 0
    for k, item in enumerate(items):
        x = real_samples(item, name=f"series {k}")
        if x.ndim != 1:
            raise InputError(f"series {k}: must be 1-D, got shape {x.shape}")
        if np.isinf(x).any():
            raise InputError(f"series {k}: infinite value at index {int(np.argmax(np.isinf(x)))}")
        finite = np.isfinite(x)
        edges = np.flatnonzero(np.diff(np.r_[0, finite.astype(int), 0]))
        for a, b in zip(edges[::2], edges[1::2], strict=True):
            if b - a >= min_samples:
                out.append(x[a:b])
            else:
                short, short_n = short + 1, short_n + int(b - a)
    notes = (
        ((f"{short} stretch(es) shorter than {min_samples} samples left out ({short_n} samples)"),)
        if short
        else ()
    )
    return out, notes


def _verdict(
    fit: BoundFit, limits: PooledLimits, low: LowFrequency, policy: str
) -> tuple[str, ...]:
    reasons = []
    if not np.isfinite(fit.objective_value) or fit.total_variance_m2 <= 0.0:
        reasons.append("no positive bound could be fitted")
    if not np.isfinite(limits.upper_m2_hz).any():
        reasons.append("no frequency band has data")
    reasons += low_frequency_reasons(low.to_dict(), policy)
    return tuple(reasons)


def bound_series(
    series: ArrayLike | Sequence[ArrayLike],
    dt_s: float,
    *,
    confidence_level: float = 0.95,
    coverage: float = 0.99,
    estimator: str = "multitaper",
    estimator_options: dict[str, Any] | None = None,
    f_min_hz: float | None = None,
    min_samples: int = MIN_STRETCH,
    bands_per_decade: int = 10,
    shape_alpha: float = 0.05,
    clusters: ArrayLike | None = None,
    cluster_correlation: float = 0.0,
    deviation_model: str = "auto",
    objective: str = "variance",
    tau_max_s: float = TAU_MAX_S,
    low_frequency_policy: str = "prior",
) -> SeriesBound:
    """Bound evenly sampled error series by a Gauss-Markov + white-noise PSD.

    Parameters
    ----------
    series : array_like or sequence of array_like
        Stationary stretches of an error, metres (or any unit: the bound is
        in the same unit); NaN gaps, and masked samples of a masked array,
        split a stretch. Each stretch is one window. A 2-D array is read as
        one stretch per row. Each stretch's mean is removed before its
        spectrum: the bound covers the fluctuation about it, not a constant
        bias (``notes`` says when a mean exceeds a quarter of its stretch's
        standard deviation).
    dt_s : float
        Sampling interval, seconds.
    confidence_level : float, default 0.95
        Confidence of the statement.
    coverage : float, default 0.99
        Fraction of the windows whose true PSD the bound covers.
    estimator : {"multitaper", "welch", "blackman-tukey"}, default "multitaper"
        PSD estimator (:func:`psdbound.spectra.estimate_psd`).
    estimator_options : dict, optional
        Its keyword options.
    f_min_hz : float, optional
        Lowest frequency to state the bound for, Hz; default: where the
        longest window's estimate resolves (multitaper: ``(NW + 1) / T``).
    min_samples : int, default 64
        Shortest stretch used (shorter ones are reported in ``notes``).
    bands_per_decade : int, default 10
        Frequency bands per decade.
    shape_alpha : float, default 0.05
        Family-wise level of the tests that give a window of another spectral
        shape a group of its own: its bands above its group's shape, or its
        narrow estimate at its lowest Fourier frequencies above the other
        windows' of about its length, jointly with its lowest band (a slow
        strong reflector, :func:`psdbound.spectra.groups.low_end_p`). A significant tilt
        also does, at its own family-wise level
        (:data:`psdbound.spectra.groups.TILT_ALPHA`, 0.05). A test that misses
        such a window costs coverage; one that splits a window off by chance
        costs tightness only (measured on homogeneous windows,
        ``benchmarks/bound_coverage.py``, 200 truths each: 2.5-5.5 % of runs
        split, all tests together).
    clusters : array_like of int, optional
        One label per stretch used: stretches that share an error source
        (their pooled degrees of freedom are reduced).
    cluster_correlation : float, default 0
        Intra-cluster correlation, in [0, 1].
    deviation_model : {"auto", "tilt", "level"}, default "auto"
        Each window's deviation from its group's shape
        (:func:`psdbound.spectra.pooled.pool_bands`).
    objective : {"variance", "area"}, default "variance"
        Tightness objective.
    tau_max_s : float, default 900
        Prior upper limit of the time constant, seconds: where the data do
        not bound it, the bound covers the admitted models with time
        constants up to this below the lowest band
        (:mod:`psdbound.spectra.lowfreq`). The default is carrier-phase
        multipath's (raw time constants of 10-900 s); for another error (an
        inertial sensor's, a clock's) give the longest time constant it can
        have. Where the data admit only longer ones the verdict is
        ``"not-bounded"`` and its reason names this option.
    low_frequency_policy : {"prior", "refuse"}, default "prior"
        ``"refuse"``: not bounded when the statement below the lowest band
        would rest on the prior.

    Returns
    -------
    SeriesBound

    Raises
    ------
    InputError
        No stretch of ``min_samples`` samples, a bad sampling interval, or an
        option out of range.

    See Also
    --------
    psdbound.fit : The GNSS pipeline, which ends in the same code.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(1)
    >>> x = [rng.normal(0.0, 0.002, 512) for _ in range(12)]
    >>> res = bound_series(x, 1.0)
    >>> res.verdict
    'bounded'
    """
    num = {
        "confidence_level": confidence_level,
        "coverage": coverage,
        "shape_alpha": shape_alpha,
        "bands_per_decade": bands_per_decade,
        "min_samples": min_samples,
        "cluster_correlation": cluster_correlation,
    }
    dt_s, tau_max_s, f_min_hz, num = _check_options(
        dt_s, tau_max_s, f_min_hz, low_frequency_policy, num
    )
    opts = _estimator_options(estimator, estimator_options)
    stretches, notes = _stretches(series, num["min_samples"])
    psds = tuple(estimate_psd(x, dt_s, method=estimator, **opts) for x in stretches)
    given_f_min_hz = f_min_hz
    resolved_hz = [resolved_from_hz(p) for p in psds]
    if f_min_hz is None:
        f_min_hz = min(resolved_hz)
    cl = _cluster_labels(clusters, cluster_correlation)
    sb = fit_stated_bound(
        psds,
        dt_s,
        f_min_hz=f_min_hz,
        confidence_level=num["confidence_level"],
        coverage=num["coverage"],
        shape_alpha=num["shape_alpha"],
        bands_per_decade=num["bands_per_decade"],
        clusters=cl,
        cluster_correlation=num["cluster_correlation"],
        deviation_model=deviation_model,
        objective=objective,
        tau_max_s=tau_max_s,
        lowest=lowest_ordinates(stretches, dt_s, f_min_hz),
    )
    fit, bands, limits, ms, low = sb.fit, sb.bands, sb.limits, sb.model_set, sb.low_frequency
    reasons = _verdict(fit, limits, low, low_frequency_policy)

    return SeriesBound(
        bound=fit.model,
        verdict=NOT_BOUNDED if reasons else BOUNDED,
        verdict_reasons=reasons,
        f_min_hz=float(fit.f_min_hz),
        covers=statement(limits, bands, low, sb.lowest, sb.cells, sb.unresolved),
        fit=fit,
        psds=psds,
        bands=bands,
        limits=limits,
        notes=notes
        + _mean_note(stretches)
        + _f_min_note(given_f_min_hz, float(fit.f_min_hz))
        + _unresolved_note(resolved_hz, float(fit.f_min_hz)),
        model_set=ms,
        low_frequency=low,
        lowest_frequencies=sb.lowest,
        cells=sb.cells,
        unresolved=sb.unresolved,
    )
