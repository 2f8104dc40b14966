"""The Gauss-Markov + white-noise bound as an object filter code can use.

A :class:`GaussMarkovBound` is the model
:class:`~psdbound.spectra.models.GaussMarkovWhiteNoise` (the four numbers of
a fitted bound: ``sigma_gm_m``, ``tau_s``, ``sigma_wn_m`` and the data
interval ``dt_s`` they were fitted at, with its PSDs, autocovariance and
variances) plus, optionally, the elevation mapping the bound was fitted
under; it turns them into what a Kalman filter needs.

Conventions (those of :mod:`psdbound.spectra.models`)
------------------------------------------------------
* PSDs are one-sided, per hertz (m^2/Hz). The continuous model is
  ``S(f) = 4 sigma_gm^2 tau / (1 + (2 pi f tau)^2) + 2 N_WN`` with the
  thesis's two-sided white level ``N_WN = sigma_wn^2 dt_s`` (m^2/Hz).
* Sampled at an interval ``dt``, the Gauss-Markov part is the AR(1)
  sequence ``x[k+1] = Phi x[k] + w[k]``; its one-sided PSD on ``[0, 1/(2 dt)]``
  is :func:`psdbound.spectra.models.gm_psd_sampled`.

State-space export (:meth:`GaussMarkovBound.to_state_space`)
-------------------------------------------------------------
For a filter that runs at interval ``dt`` (seconds)::

    Phi = exp(-dt / tau)                  (dimensionless)
    Qd  = sigma_gm^2 (1 - Phi^2)          (m^2, variance of w[k])
    R   = white-noise variance per filter sample (m^2)

The Gauss-Markov part is exact at any ``dt``: the AR(1) sequence has the
continuous autocorrelation ``sigma_gm^2 exp(-|k dt| / tau)`` at every lag
``k dt`` and, as a consequence, the aliased PSD ``gm_psd_sampled``; the
stationary variance ``Qd / (1 - Phi^2) = sigma_gm^2`` is the initial state
variance ``P0``.

``R`` is the variance of the white part of **one filter measurement**,
:meth:`~psdbound.spectra.models.GaussMarkovWhiteNoise.white_variance_m2`. At
the data interval (``dt == dt_s``) it is ``sigma_wn^2``, and then the sampled
state-space model has exactly the sampled bound PSD
``gm_psd_sampled(f, sigma_gm, tau, dt) + 2 sigma_wn^2 dt`` that
:func:`psdbound.spectra.fit_bound` verified against the data. When the filter
runs at another interval, ``white_noise`` (one of :data:`WHITE_NOISE_MODES`:
``"psd"``, ``"per_sample"`` or the default ``"conservative"``) says what the
filter's measurement is -- an average of the data over ``dt`` or a decimated
data sample; the modes are described in :mod:`psdbound.spectra.models`.

Elevation mapping
-----------------
The bound is fitted to the elevation-normalised error ``x / m(el)`` with
``m(el) = a + b exp(-el^2 / (2 c^2))`` (:mod:`psdbound.stationarity.mapping`).
The bound on the raw error at elevation ``el`` therefore has both standard
deviations multiplied by ``m(el)`` (the PSD by ``m(el)^2``); ``tau`` is
unchanged. :meth:`GaussMarkovBound.at_elevation` returns that scaled bound.
For a time-varying elevation, keep the normalised Gauss-Markov state and put
``m(el_k)`` in the measurement matrix instead (see
:func:`psdbound.kalman.augment_gm_states`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace
from os import PathLike
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.signal import lfilter

from psdbound.common.options import Number
from psdbound.errors import InputError
from psdbound.results import read_document
from psdbound.spectra.bound import BoundFit
from psdbound.spectra.models import WHITE_NOISE_MODES, GaussMarkovWhiteNoise
from psdbound.stationarity.mapping import ElevationMapping

__all__ = [
    "WHITE_NOISE_MODES",
    "GaussMarkovBound",
    "GMStateSpace",
]

_REL_TOL = 1e-6
#: The fields of a result file the bound is read from (the rest need not be there):
#: ``read_document``'s check, before the bound's own checks of each value.
RESULT_FIELDS = (
    "schema_version",
    "bound",
    "bound.sigma_gm_m",
    "bound.tau_s",
    "bound.sigma_wn_m",
    "bound.n_wn_two_sided_m2_hz",
    "sampling",
    "sampling.interval_s",
    "sampling.nyquist_hz",
    "mapping",
)


class GMStateSpace(NamedTuple):
    """Discrete state-space model of one Gauss-Markov + white-noise error.

    Unpacks as ``Phi, Qd, R = bound.to_state_space(dt)``. With an array of
    elevations the fields are arrays (one entry per elevation).

    Attributes
    ----------
    phi : float or ndarray
        State transition ``exp(-dt / tau)`` over one filter interval.
    qd_m2 : float or ndarray
        Process-noise variance ``sigma_gm^2 (1 - phi^2)``, m^2.
    r_m2 : float or ndarray
        White measurement-noise variance per filter sample, m^2.
    """

    phi: float | NDArray[np.float64]
    qd_m2: float | NDArray[np.float64]
    r_m2: float | NDArray[np.float64]

    @property
    def p0_m2(self) -> float | NDArray[np.float64]:
        """Initial state variance, m^2: the stationary ``Qd / (1 - Phi^2) = sigma_gm^2``.

        A filter started with less under-states the error until the state
        has converged; the stationary variance is the least that bounds a
        Gauss-Markov error from the first step.
        """
        return self.qd_m2 / -np.expm1(2.0 * np.log(self.phi))


@dataclass(frozen=True)
class GaussMarkovBound(GaussMarkovWhiteNoise):
    """A first-order Gauss-Markov + white-noise PSD bound of multipath.

    Build it with :meth:`from_params`, :meth:`from_fit` or
    :meth:`from_result`. The model (PSDs, autocovariance, variances,
    white-noise modes) is that of
    :class:`~psdbound.spectra.models.GaussMarkovWhiteNoise`; conventions of
    the filter export are in the module docstring of :mod:`psdbound.kalman.bound`.

    Parameters
    ----------
    sigma_gm_m : float
        Gauss-Markov standard deviation, metres (>= 0).
    tau_s : float
        Gauss-Markov time constant, seconds (> 0).
    sigma_wn_m : float
        White-noise standard deviation per data sample, metres (>= 0).
    dt_s : float
        Data sampling interval the bound was fitted at, seconds (> 0). It
        fixes the white PSD level ``N_WN = sigma_wn^2 dt_s``.
    mapping : ElevationMapping or None
        Elevation mapping the bound was fitted under (the bound then applies
        to the normalised error ``x / m(el)``); ``None`` if it applies to the
        raw error.
    source : str
        Where the numbers came from (``"params"``, ``"fit"`` or the result
        file path); informational.

    See Also
    --------
    analyze_covariance : Check a filter built on the bound against true errors.
    augment_gm_states : One Gauss-Markov state per satellite in a filter.
    psdbound.kalman.uncertain.GaussMarkovSet : A design safe for a set of processes.

    References
    ----------
    .. [1] Brown, R. G., & Hwang, P. Y. C. (2012). *Introduction to Random
       Signals and Applied Kalman Filtering* (4th ed.), ch. 2-3. Wiley.
    .. [2] Langel, S., Garcia Crespillo, O., & Joerger, M. (2021). Overbounding
       the effect of uncertain Gauss-Markov noise in Kalman filtering.
       *NAVIGATION*, 68(2), 259-276.

    Examples
    --------
    >>> import numpy as np
    >>> b = GaussMarkovBound.from_params(0.004, 30.0, 0.001, 1.0)
    >>> phi, qd, r = b.to_state_space(1.0)
    >>> bool(np.isclose(phi, np.exp(-1 / 30))), bool(np.isclose(qd, 0.004**2 * (1 - phi**2)))
    (True, True)
    """

    mapping: ElevationMapping | None = None
    source: str = "params"

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.mapping is not None and not isinstance(self.mapping, ElevationMapping):
            raise InputError(
                f"mapping must be an ElevationMapping or None, got {type(self.mapping).__name__}"
            )

    # ------------------------------------------------------------------ build
    @classmethod
    def from_params(
        cls,
        sigma_gm_m: float,
        tau_s: float,
        sigma_wn_m: float,
        dt_s: float,
        *,
        mapping: ElevationMapping | None = None,
    ) -> GaussMarkovBound:
        """Build a bound from its parameters.

        Parameters
        ----------
        sigma_gm_m : float
            Gauss-Markov standard deviation, metres.
        tau_s : float
            Gauss-Markov time constant, seconds.
        sigma_wn_m : float
            White-noise standard deviation per data sample, metres.
        dt_s : float
            Data interval the bound was fitted at, seconds.
        mapping : ElevationMapping, optional
            Elevation mapping the bound was fitted under.

        Returns
        -------
        GaussMarkovBound

        Raises
        ------
        InputError
            For negative standard deviations, or a non-positive ``tau_s`` or ``dt_s``.
        """
        return cls(sigma_gm_m, tau_s, sigma_wn_m, dt_s, mapping=mapping, source="params")

    @classmethod
    def from_fit(
        cls,
        fit: BoundFit | Any,
        *,
        mapping: ElevationMapping | None = None,
        allow_not_bounded: bool = False,
    ) -> GaussMarkovBound:
        """Build a bound from a :class:`psdbound.spectra.BoundFit` or a ``bound_series`` result.

        Parameters
        ----------
        fit : BoundFit or SeriesBound
            Result of :func:`psdbound.spectra.fit_bound`, or of
            :func:`psdbound.bound_series` (its ``fit``; a result whose verdict
            is not ``"bounded"`` is refused, with its reasons, unless
            ``allow_not_bounded``).
        mapping : ElevationMapping, optional
            Elevation mapping the fitted PSDs were normalised with.
        allow_not_bounded : bool, default False
            Accept a not-bounded ``bound_series`` result.

        Returns
        -------
        GaussMarkovBound

        Raises
        ------
        InputError
            Neither a fit nor a ``bound_series`` result, or a not-bounded one.
        """
        verdict = getattr(fit, "verdict", None)
        if verdict is not None and verdict != "bounded" and not allow_not_bounded:
            why = "; ".join(getattr(fit, "verdict_reasons", ())) or "no reason given"
            raise InputError(
                f"the verdict is {verdict!r} ({why}): this bound is not for a filter; pass "
                "allow_not_bounded=True to use it anyway"
            )
        fit = getattr(fit, "fit", fit)  # a bound_series result holds its BoundFit
        m = getattr(fit, "model", None)
        if m is None:
            raise InputError(
                "from_fit takes the result of psdbound.bound_series or spectra.fit_bound, got "
                f"{type(fit).__name__}"
            )
        return cls(m.sigma_gm_m, m.tau_s, m.sigma_wn_m, m.dt_s, mapping=mapping, source="fit")

    @classmethod
    def from_result(
        cls, path: str | PathLike[str], *, allow_not_bounded: bool = False
    ) -> GaussMarkovBound:
        """Read the bound from a ``psdbound fit`` result file (``result.json``).

        A result whose verdict is not ``"bounded"`` is refused (its
        ``verdict_reasons`` are in the message) unless ``allow_not_bounded``:
        a filter built on it would carry a number the fit itself said not to
        trust.

        The file is read and checked by :func:`psdbound.results.read_document`
        (schema version ``"1"`` and its required fields). The bound is read
        from the sections::

            "bound":    {"sigma_gm_m", "tau_s", "sigma_wn_m", "n_wn_two_sided_m2_hz", "dt_s"}
            "sampling": {"interval_s", "nyquist_hz"}
            "mapping":  {"a", "b", "c_deg"}  or null (bound on the raw error)

        Other keys are ignored, but a ``slow`` component of the fit's
        ``error_model`` (multipath the high-pass removed) is warned about: the
        bound alone does not carry it (:class:`psdbound.kalman.ErrorModel`
        does). Redundant numbers must agree to a relative
        1e-6: ``n_wn_two_sided_m2_hz = sigma_wn_m^2 dt_s``,
        ``sampling.interval_s = dt_s`` and ``nyquist_hz = 1 / (2 dt_s)``.

        Parameters
        ----------
        path : str or path-like
            The result file.
        allow_not_bounded : bool, default False
            Read the numbers of a ``"not-bounded"`` result anyway (for study,
            not for a protection level).

        Returns
        -------
        GaussMarkovBound

        Raises
        ------
        InputError
            If the verdict is not "bounded" (and ``allow_not_bounded`` is
            false), the file is missing or not JSON, the schema version is not
            ``"1"``, a field is missing (messages of
            :func:`~psdbound.results.read_document`), or a bound value is not
            a number, negative (or zero for ``tau_s``, ``dt_s``) or
            inconsistent. The message names the file and the key.
        """
        p = Path(path)
        doc = read_document(p, required=RESULT_FIELDS)
        return cls._from_document(doc, p, allow_not_bounded, stacklevel=3)

    @classmethod
    def from_document(
        cls, document: dict[str, Any], *, allow_not_bounded: bool = False, source: str = ""
    ) -> GaussMarkovBound:
        """Return the bound of a result document in memory (``FitResults.document``).

        The same reading and checks as :meth:`from_result`, without a file:
        ``psdbound.fit(...)`` hands its document to a filter directly.

        Parameters
        ----------
        document : dict
            A result document (schema 1), e.g. :attr:`psdbound.FitResults.document`.
        allow_not_bounded : bool, default False
            Read the numbers of a ``"not-bounded"`` result anyway.
        source : str, optional
            What messages name as the origin (default ``"result document"``).

        Returns
        -------
        GaussMarkovBound

        Raises
        ------
        InputError
            As :meth:`from_result`.
        """
        return cls._from_document(
            document, Path(source or "result document"), allow_not_bounded, stacklevel=3
        )

    @classmethod
    def _from_document(
        cls, doc: dict[str, Any], p: Path, allow_not_bounded: bool, *, stacklevel: int
    ) -> GaussMarkovBound:
        """Read and check the bound of a document; ``p`` names its origin in messages."""
        _check_verdict(doc, p, allow_not_bounded)
        b = _section(doc, "bound", p)
        sigma_gm = _number(b, "bound", "sigma_gm_m", p)
        tau = _number(b, "bound", "tau_s", p, positive=True)
        sigma_wn = _number(b, "bound", "sigma_wn_m", p)
        n_wn = _number(b, "bound", "n_wn_two_sided_m2_hz", p)
        dt = _number(b, "bound", "dt_s", p, positive=True)
        s = _section(doc, "sampling", p)
        interval = _number(s, "sampling", "interval_s", p, positive=True)
        nyq = _number(s, "sampling", "nyquist_hz", p, positive=True)
        _check_redundant(n_wn, sigma_wn, dt, interval, nyq, p)
        slow = [
            c
            for c in (doc.get("error_model") or {}).get("components", [])
            if c.get("name") == "slow"
        ]
        if slow:
            warnings.warn(
                f"{p}: the fit's error model also has a slow component the bound does not "
                f"carry (multipath the high-pass removed: {1000 * slow[0]['sigma_m']:.2f} mm, "
                f"tau {slow[0]['tau_s']:.4g} s); the error model exports every component "
                "(FitResults.error_model, or psdbound.load(path).error_model for a file)",
                stacklevel=stacklevel,
            )
        mapping = _read_mapping(doc, p)
        return cls(sigma_gm, tau, sigma_wn, dt, mapping=mapping, source=str(p))

    # ------------------------------------------------------------ filter use
    def mapping_factor(self, elevation_deg: ArrayLike) -> NDArray[np.float64]:
        """Elevation factor ``m(el)`` by which the standard deviations scale (1 without mapping).

        Parameters
        ----------
        elevation_deg : array_like
            Elevations, degrees.

        Returns
        -------
        ndarray

        Raises
        ------
        InputError
            An elevation that is not a number in [0, 90] deg.
        """
        el = np.asarray(elevation_deg, dtype=float)
        if not (np.isfinite(el).all() and ((el >= 0.0) & (el <= 90.0)).all()):
            raise InputError(
                f"elevations must be finite numbers of degrees in [0, 90], got {elevation_deg!r}"
            )
        if self.mapping is None:
            return np.ones_like(el)
        return self.mapping.factor(el)

    def at_elevation(self, elevation_deg: float) -> GaussMarkovBound:
        """Bound on the raw (un-normalised) error at one elevation.

        Both standard deviations are multiplied by ``m(el)`` of the bound's
        mapping; ``tau`` and ``dt_s`` are unchanged; the result has no mapping.

        Parameters
        ----------
        elevation_deg : float
            Satellite elevation, degrees.

        Returns
        -------
        GaussMarkovBound

        Raises
        ------
        InputError
            If the bound has no elevation mapping.
        """
        if self.mapping is None:
            raise InputError(
                "this bound has no elevation mapping; it already applies to the raw error"
            )
        m = float(self.mapping_factor(float(elevation_deg)))
        return replace(
            self,
            sigma_gm_m=self.sigma_gm_m * m,
            sigma_wn_m=self.sigma_wn_m * m,
            mapping=None,
            source=f"{self.source} at {float(elevation_deg):g} deg",
        )

    def to_state_space(
        self,
        dt_s: float | None = None,
        *,
        elevation_deg: ArrayLike | None = None,
        white_noise: str = "conservative",
    ) -> GMStateSpace:
        """Discrete state-space model ``(Phi, Qd, R)`` for a filter interval.

        ``x[k+1] = Phi x[k] + w[k]``, ``w ~ N(0, Qd)``, error sample
        ``e[k] = x[k] + v[k]``, ``v ~ N(0, R)``; initialise ``x`` with the
        stationary variance ``sigma_gm^2`` (times ``m(el)^2``). Definitions of
        ``R`` for ``dt_s != self.dt_s`` are in :mod:`psdbound.spectra.models`.

        Parameters
        ----------
        dt_s : float, optional
            Filter interval, seconds; default the data interval.
        elevation_deg : float or array_like, optional
            Elevation(s), degrees: ``Qd`` and ``R`` are multiplied by
            ``m(el)^2`` (needs a mapping). Arrays give array fields.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            See :meth:`white_variance_m2`.

        Returns
        -------
        GMStateSpace
            ``(phi, qd_m2, r_m2)``; ``.p0_m2`` is the initial state variance.

        Warns
        -----
        UserWarning
            A filter step shorter than the data interval (no white level is
            known above the data's Nyquist frequency).

        Raises
        ------
        InputError
            For a bad interval or mode, or an elevation without a mapping.
        """
        dt = self.filter_dt_s(dt_s, white_noise=white_noise)
        phi = math.exp(-dt / self.tau_s)
        # sigma^2 (1 - phi^2), written without cancellation for dt << tau
        qd = self.sigma_gm_m**2 * -math.expm1(-2.0 * dt / self.tau_s)
        r = self.white_variance_m2(dt, white_noise=white_noise)
        if elevation_deg is None:
            return GMStateSpace(phi, qd, r)
        if self.mapping is None:
            raise InputError(
                "elevation_deg given but this bound has no elevation mapping; "
                "use the bound as it is (it applies to the raw error)"
            )
        m2 = self.mapping_factor(elevation_deg) ** 2
        if m2.ndim == 0:
            return GMStateSpace(phi, float(qd * m2), float(r * m2))
        return GMStateSpace(np.full(m2.shape, phi), qd * m2, r * m2)

    def simulate(
        self,
        n_samples: int,
        dt_s: float | None = None,
        *,
        n_series: int | None = None,
        white_noise: str = "conservative",
        rng: np.random.Generator | int | None = None,
    ) -> NDArray[np.float64]:
        """Draw stationary sample paths of the bound process, metres.

        Parameters
        ----------
        n_samples : int
            Samples per path.
        dt_s : float, optional
            Sampling interval, seconds; default the data interval.
        n_series : int, optional
            Number of independent paths; output shape ``(n_series, n_samples)``
            (``(n_samples,)`` when omitted).
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            See :meth:`white_variance_m2`.
        rng : numpy.random.Generator or int, optional
            Random generator or seed.

        Returns
        -------
        ndarray

        Raises
        ------
        InputError
            ``n_samples`` or ``n_series`` not a whole number >= 1.
        """
        n = Number(lo=1, integer=True)("n_samples", n_samples)
        k = 1 if n_series is None else Number(lo=1, integer=True)("n_series", n_series)
        gen = np.random.default_rng(rng)
        phi, qd, r = self.to_state_space(dt_s, white_noise=white_noise)
        shape = (k, n)
        w = gen.standard_normal(shape) * math.sqrt(qd)
        w[:, 0] = gen.standard_normal(shape[0]) * self.sigma_gm_m
        x = lfilter([1.0], [1.0, -phi], w, axis=1)
        x += gen.standard_normal(shape) * math.sqrt(r)
        return x[0] if n_series is None else x

    def __str__(self) -> str:
        m = (
            ""
            if self.mapping is None
            else (
                f", mapping a={self.mapping.a:g} b={self.mapping.b:g} c={self.mapping.c_deg:g} deg"
            )
        )
        return (
            f"GaussMarkovBound(sigma_gm={100 * self.sigma_gm_m:.3f} cm, tau={self.tau_s:.1f} s, "
            f"sigma_wn={100 * self.sigma_wn_m:.3f} cm at dt={self.dt_s:g} s, "
            f"N_WN={self.n_wn_two_sided_m2_hz:.4g} m^2/Hz{m})"
        )


# ------------------------------------------------------------------ result file


def _check_verdict(doc: dict[str, Any], p: Path, allow_not_bounded: bool) -> None:
    """Refuse a result whose verdict is not "bounded" unless allowed."""
    verdict = doc.get("verdict", "bounded")
    if verdict != "bounded" and not allow_not_bounded:
        why = "; ".join(str(r) for r in doc.get("verdict_reasons", [])) or "no reason given"
        raise InputError(
            f"the verdict is {verdict!r} ({why}): this bound is not for a filter; pass "
            "allow_not_bounded=True to read it anyway",
            path=p,
        )


def _section(doc: dict[str, Any], name: str, p: Path) -> dict[str, Any]:
    """Return the JSON object under ``name`` of a result document."""
    if name not in doc:
        raise InputError(f"missing key {name!r}", path=p)
    sec = doc[name]
    if not isinstance(sec, dict):
        raise InputError(f"key {name!r} must hold a JSON object, got {sec!r}", path=p)
    return sec


def _number(sec: dict[str, Any], sname: str, key: str, p: Path, *, positive: bool = False) -> float:
    """Return ``sec[key]`` checked: a finite number, >= 0 (> 0 when ``positive``)."""
    if key not in sec:
        raise InputError(f"missing key '{sname}.{key}'", path=p)
    v = sec[key]
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise InputError(f"'{sname}.{key}' must be a finite number, got {v!r}", path=p)
    if v < 0 or (positive and v == 0):
        need = "> 0" if positive else ">= 0"
        raise InputError(f"'{sname}.{key}' must be {need}, got {v!r}", path=p)
    return float(v)


def _agree(a: float, b_: float) -> bool:
    """Whether two redundant numbers agree to the relative tolerance."""
    return math.isclose(a, b_, rel_tol=_REL_TOL, abs_tol=0.0) or a == b_


def _check_redundant(
    n_wn: float, sigma_wn: float, dt: float, interval: float, nyq: float, p: Path
) -> None:
    """Check the redundant numbers of a result: white-noise level, interval, Nyquist frequency."""
    if not _agree(n_wn, sigma_wn**2 * dt):
        raise InputError(
            f"'bound.n_wn_two_sided_m2_hz' = {n_wn!r} disagrees with sigma_wn_m^2 * dt_s = "
            f"{sigma_wn**2 * dt!r}",
            path=p,
        )
    if not _agree(interval, dt):
        raise InputError(
            f"'sampling.interval_s' = {interval!r} disagrees with 'bound.dt_s' = {dt!r}", path=p
        )
    if not _agree(nyq, 0.5 / dt):
        raise InputError(
            f"'sampling.nyquist_hz' = {nyq!r} disagrees with 1 / (2 dt_s) = {0.5 / dt!r}",
            path=p,
        )


def _read_mapping(doc: dict[str, Any], p: Path) -> ElevationMapping | None:
    """Return the result's elevation mapping, None for a bound on the raw error."""
    if doc["mapping"] is None:
        return None
    m = _section(doc, "mapping", p)
    a = _number(m, "mapping", "a", p, positive=True)
    bb = _number(m, "mapping", "b", p)
    c = _number(m, "mapping", "c_deg", p, positive=True)
    return ElevationMapping(a, bb, c, str(m.get("source", "fixed")))
