"""The Gauss-Markov + white-noise bound as an object filter code can use.

A :class:`GaussMarkovBound` holds the four numbers of a fitted bound
(``sigma_gm_m``, ``tau_s``, ``sigma_wn_m`` and the data interval ``dt_s``
they were fitted at), optionally the elevation mapping the bound was fitted
under, and turns them into what a Kalman filter needs.

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

``R`` is the variance of the white part of **one filter measurement**. At the
data interval (``dt == dt_s``) it is ``sigma_wn^2``, and then the sampled
state-space model has exactly the sampled bound PSD
``gm_psd_sampled(f, sigma_gm, tau, dt) + 2 sigma_wn^2 dt`` that
:func:`psdbound.spectra.fit_bound` verified against the data (a white
sequence of variance ``R`` has the flat one-sided PSD ``2 R dt``). When the
filter runs at another interval, ``white_noise`` says what the filter's
measurement is:

``"psd"``
    ``R = N_WN / dt = sigma_wn^2 dt_s / dt``. The white **PSD level**
    ``2 N_WN`` is kept, i.e. the white noise is band-limited to the filter's
    Nyquist frequency. Right when a filter sample is the average of the data
    over ``dt`` (``dt`` a multiple of ``dt_s``: the mean of ``n`` white samples
    has variance ``sigma_wn^2 / n``). For ``dt < dt_s`` it extrapolates the
    flat level above the data's Nyquist frequency, where the bound was never
    checked.
``"per_sample"``
    ``R = sigma_wn^2``. Right when the filter uses every ``n``-th data sample
    unaveraged (decimation): decimating white noise keeps its per-sample
    variance (its folded PSD is ``2 sigma_wn^2 dt``). With ``"psd"`` such a
    filter would under-state the white noise by the factor ``dt / dt_s``.
``"conservative"`` (default)
    ``R = max(sigma_wn^2, N_WN / dt)``: safe for both readings; equal to both
    at the data interval.

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

import json
import math
from dataclasses import dataclass, replace
from os import PathLike
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.signal import lfilter

from psdbound.errors import InputError
from psdbound.spectra.bound import BoundFit
from psdbound.spectra.models import gm_psd_continuous, gm_psd_sampled
from psdbound.stationarity.mapping import ElevationMapping

__all__ = [
    "RESULT_SCHEMA_VERSION",
    "WHITE_NOISE_MODES",
    "GaussMarkovBound",
    "GMStateSpace",
]

RESULT_SCHEMA_VERSION = "1"
WHITE_NOISE_MODES = ("psd", "per_sample", "conservative")

_REL_TOL = 1e-6


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


def _check_mode(white_noise: str) -> None:
    if white_noise not in WHITE_NOISE_MODES:
        raise InputError(
            f"unknown white_noise mode {white_noise!r}; choose from {WHITE_NOISE_MODES}"
        )


def _check_dt(dt_s: float, what: str = "filter interval dt_s") -> float:
    dt = float(dt_s)
    if not (math.isfinite(dt) and dt > 0):
        raise InputError(f"{what} must be a finite number > 0 s, got {dt_s!r}")
    return dt


@dataclass(frozen=True)
class GaussMarkovBound:
    """A first-order Gauss-Markov + white-noise PSD bound of multipath.

    Build it with :meth:`from_params`, :meth:`from_fit` or
    :meth:`from_result`. Conventions are in the module docstring of
    :mod:`psdbound.kalman.bound`.

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
    """

    sigma_gm_m: float
    tau_s: float
    sigma_wn_m: float
    dt_s: float
    mapping: ElevationMapping | None = None
    source: str = "params"

    def __post_init__(self) -> None:
        for name in ("sigma_gm_m", "tau_s", "sigma_wn_m", "dt_s"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int | float | np.floating | np.integer):
                raise InputError(f"bound parameter {name} must be a number, got {v!r}")
            if not math.isfinite(float(v)):
                raise InputError(f"bound parameter {name} must be finite, got {v!r}")
            object.__setattr__(self, name, float(v))
        if self.sigma_gm_m < 0:
            raise InputError(f"sigma_gm_m must be >= 0 m, got {self.sigma_gm_m}")
        if self.sigma_wn_m < 0:
            raise InputError(f"sigma_wn_m must be >= 0 m, got {self.sigma_wn_m}")
        if self.tau_s <= 0:
            raise InputError(f"tau_s must be > 0 s, got {self.tau_s}")
        if self.dt_s <= 0:
            raise InputError(f"dt_s must be > 0 s, got {self.dt_s}")
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
        cls, fit: BoundFit, *, mapping: ElevationMapping | None = None
    ) -> GaussMarkovBound:
        """Build a bound from a :class:`psdbound.spectra.BoundFit`.

        Parameters
        ----------
        fit : BoundFit
            Result of :func:`psdbound.spectra.fit_bound`.
        mapping : ElevationMapping, optional
            Elevation mapping the fitted PSDs were normalised with.

        Returns
        -------
        GaussMarkovBound
        """
        return cls(
            fit.sigma_gm_m, fit.tau_s, fit.sigma_wn_m, fit.dt_s, mapping=mapping, source="fit"
        )

    @classmethod
    def from_result(cls, path: str | PathLike[str]) -> GaussMarkovBound:
        """Read the bound from a ``psdbound fit`` result file (``result.json``).

        The file must hold ``schema_version == "1"`` and the sections::

            "bound":    {"sigma_gm_m", "tau_s", "sigma_wn_m", "n_wn_two_sided_m2_hz", "dt_s"}
            "sampling": {"interval_s", "nyquist_hz"}
            "mapping":  {"a", "b", "c_deg"}  or null (bound on the raw error)

        Other keys are ignored. Redundant numbers must agree to a relative
        1e-6: ``n_wn_two_sided_m2_hz = sigma_wn_m^2 dt_s``,
        ``sampling.interval_s = dt_s`` and ``nyquist_hz = 1 / (2 dt_s)``.

        Parameters
        ----------
        path : str or path-like
            The result file.

        Returns
        -------
        GaussMarkovBound

        Raises
        ------
        InputError
            If the file cannot be read or is not JSON, the schema version is
            not ``"1"``, a key is missing, a value is not a number, negative
            (or zero for ``tau_s``, ``dt_s``) or inconsistent. The message
            names the file and the key.
        """
        p = Path(path)
        try:
            text = p.read_text(encoding="utf-8")
        except OSError as exc:
            raise InputError(f"cannot read result file: {exc.strerror or exc}", path=p) from None
        except UnicodeDecodeError:
            raise InputError("result file is not UTF-8 text (expected JSON)", path=p) from None
        try:
            doc = json.loads(text)
        except json.JSONDecodeError as exc:
            raise InputError(
                f"result file is not valid JSON ({exc.msg} at line {exc.lineno}, "
                f"column {exc.colno})",
                path=p,
                line=exc.lineno,
            ) from None
        if not isinstance(doc, dict):
            raise InputError("result file must hold a JSON object at top level", path=p)
        if "schema_version" not in doc:
            raise InputError("missing key 'schema_version'", path=p)
        if str(doc["schema_version"]) != RESULT_SCHEMA_VERSION or not isinstance(
            doc["schema_version"], str
        ):
            raise InputError(
                f"unsupported schema_version {doc['schema_version']!r}; this psdbound reads "
                f"{RESULT_SCHEMA_VERSION!r}",
                path=p,
            )

        def section(name: str) -> dict[str, Any]:
            if name not in doc:
                raise InputError(f"missing key {name!r}", path=p)
            sec = doc[name]
            if not isinstance(sec, dict):
                raise InputError(f"key {name!r} must hold a JSON object, got {sec!r}", path=p)
            return sec

        def number(sec: dict[str, Any], sname: str, key: str, *, positive: bool = False) -> float:
            if key not in sec:
                raise InputError(f"missing key '{sname}.{key}'", path=p)
            v = sec[key]
            if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
                raise InputError(f"'{sname}.{key}' must be a finite number, got {v!r}", path=p)
            if v < 0 or (positive and v == 0):
                need = "> 0" if positive else ">= 0"
                raise InputError(f"'{sname}.{key}' must be {need}, got {v!r}", path=p)
            return float(v)

        b = section("bound")
        sigma_gm = number(b, "bound", "sigma_gm_m")
        tau = number(b, "bound", "tau_s", positive=True)
        sigma_wn = number(b, "bound", "sigma_wn_m")
        n_wn = number(b, "bound", "n_wn_two_sided_m2_hz")
        dt = number(b, "bound", "dt_s", positive=True)
        s = section("sampling")
        interval = number(s, "sampling", "interval_s", positive=True)
        nyq = number(s, "sampling", "nyquist_hz", positive=True)

        def agree(a: float, b_: float) -> bool:
            return math.isclose(a, b_, rel_tol=_REL_TOL, abs_tol=0.0) or a == b_

        if not agree(n_wn, sigma_wn**2 * dt):
            raise InputError(
                f"'bound.n_wn_two_sided_m2_hz' = {n_wn!r} disagrees with sigma_wn_m^2 * dt_s = "
                f"{sigma_wn**2 * dt!r}",
                path=p,
            )
        if not agree(interval, dt):
            raise InputError(
                f"'sampling.interval_s' = {interval!r} disagrees with 'bound.dt_s' = {dt!r}", path=p
            )
        if not agree(nyq, 0.5 / dt):
            raise InputError(
                f"'sampling.nyquist_hz' = {nyq!r} disagrees with 1 / (2 dt_s) = {0.5 / dt!r}",
                path=p,
            )
        if "mapping" not in doc:
            raise InputError("missing key 'mapping' (null when no elevation mapping)", path=p)
        mapping = None
        if doc["mapping"] is not None:
            m = section("mapping")
            a = number(m, "mapping", "a", positive=True)
            bb = number(m, "mapping", "b")
            c = number(m, "mapping", "c_deg", positive=True)
            mapping = ElevationMapping(a, bb, c, str(m.get("source", "fixed")))
        return cls(sigma_gm, tau, sigma_wn, dt, mapping=mapping, source=str(p))

    # ------------------------------------------------------------- properties
    @property
    def n_wn_two_sided_m2_hz(self) -> float:
        """Thesis's two-sided white level ``N_WN = sigma_wn^2 dt_s``, m^2/Hz."""
        return self.sigma_wn_m**2 * self.dt_s

    @property
    def nyquist_hz(self) -> float:
        """Nyquist frequency ``1 / (2 dt_s)`` of the data the bound was fitted on, Hz."""
        return 0.5 / self.dt_s

    @property
    def total_variance_m2(self) -> float:
        """Variance of the bound process at the data interval, ``sigma_gm^2 + sigma_wn^2``, m^2."""
        return self.sigma_gm_m**2 + self.sigma_wn_m**2

    def params(self) -> dict[str, float]:
        """Return the parameters with units in their names (as in the result file)."""
        return {
            "sigma_gm_m": self.sigma_gm_m,
            "tau_s": self.tau_s,
            "sigma_wn_m": self.sigma_wn_m,
            "n_wn_two_sided_m2_hz": self.n_wn_two_sided_m2_hz,
            "dt_s": self.dt_s,
        }

    # ---------------------------------------------------------------- models
    def white_variance_m2(
        self, dt_s: float | None = None, *, white_noise: str = "conservative"
    ) -> float:
        """White-noise variance of one sample at interval ``dt_s`` (the ``R`` of the export), m^2.

        Parameters
        ----------
        dt_s : float, optional
            Filter interval, seconds; default the data interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            How a filter sample relates to the data (module docstring):
            ``N_WN / dt``, ``sigma_wn^2``, or the larger of the two.

        Returns
        -------
        float
        """
        _check_mode(white_noise)
        dt = self.dt_s if dt_s is None else _check_dt(dt_s)
        psd_level = self.n_wn_two_sided_m2_hz / dt
        if white_noise == "psd":
            return psd_level
        if white_noise == "per_sample":
            return self.sigma_wn_m**2
        return max(psd_level, self.sigma_wn_m**2)

    def variance_m2(self, dt_s: float | None = None, *, white_noise: str = "conservative") -> float:
        """Total variance of one sample at interval ``dt_s``: ``sigma_gm^2 + R``, m^2.

        Parameters
        ----------
        dt_s : float, optional
            Filter interval, seconds; default the data interval (then this is
            :attr:`total_variance_m2`).
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            See :meth:`white_variance_m2`.

        Returns
        -------
        float
        """
        return self.sigma_gm_m**2 + self.white_variance_m2(dt_s, white_noise=white_noise)

    def psd(self, f_hz: ArrayLike) -> NDArray[np.float64]:
        """Continuous-time one-sided bound PSD, m^2/Hz.

        ``4 sigma_gm^2 tau / (1 + (2 pi f tau)^2) + 2 N_WN`` -- the thesis's
        model (eq. 3.6, two-sided) doubled. This is the PSD before sampling;
        the PSD the bound was checked against is :meth:`sampled_psd`.

        Parameters
        ----------
        f_hz : array_like
            Frequencies, Hz (>= 0).

        Returns
        -------
        ndarray
        """
        f = np.asarray(f_hz, dtype=float)
        return gm_psd_continuous(f, self.sigma_gm_m, self.tau_s) + 2.0 * self.n_wn_two_sided_m2_hz

    def sampled_psd(
        self, f_hz: ArrayLike, dt_s: float | None = None, *, white_noise: str = "conservative"
    ) -> NDArray[np.float64]:
        """One-sided PSD of the bound sampled at interval ``dt_s`` (aliases folded in), m^2/Hz.

        ``gm_psd_sampled(f, sigma_gm, tau, dt) + 2 R dt`` on ``[0, 1/(2 dt)]``,
        with ``R`` from :meth:`white_variance_m2`. At the data interval this
        equals :meth:`psdbound.spectra.BoundFit.psd`; it is also the PSD of
        the state-space model of :meth:`to_state_space`.

        Parameters
        ----------
        f_hz : array_like
            Frequencies, Hz, in ``[0, 1/(2 dt)]``.
        dt_s : float, optional
            Sampling interval, seconds; default the data interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            See :meth:`white_variance_m2`.

        Returns
        -------
        ndarray
        """
        dt = self.dt_s if dt_s is None else _check_dt(dt_s)
        f = np.asarray(f_hz, dtype=float)
        r = self.white_variance_m2(dt, white_noise=white_noise)
        return gm_psd_sampled(f, self.sigma_gm_m, self.tau_s, dt) + 2.0 * r * dt

    def acf(
        self, lag_s: ArrayLike, dt_s: float | None = None, *, white_noise: str = "conservative"
    ) -> NDArray[np.float64]:
        """Autocovariance of the bound process sampled at ``dt_s``, m^2.

        ``sigma_gm^2 exp(-|lag| / tau)``, plus the white variance ``R`` at
        lag 0 (the white part of the continuous model is a delta function;
        sampled at ``dt_s`` it is ``R`` at lag 0 and 0 elsewhere). Lags within
        ``1e-9 dt_s`` of zero count as zero.

        Parameters
        ----------
        lag_s : array_like
            Lags, seconds.
        dt_s : float, optional
            Sampling interval, seconds; default the data interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            See :meth:`white_variance_m2`.

        Returns
        -------
        ndarray
        """
        dt = self.dt_s if dt_s is None else _check_dt(dt_s)
        lag = np.abs(np.asarray(lag_s, dtype=float))
        r = self.white_variance_m2(dt, white_noise=white_noise)
        return self.sigma_gm_m**2 * np.exp(-lag / self.tau_s) + np.where(lag < 1e-9 * dt, r, 0.0)

    def mapping_factor(self, elevation_deg: ArrayLike) -> NDArray[np.float64]:
        """Elevation factor ``m(el)`` by which the standard deviations scale (1 without mapping).

        Parameters
        ----------
        elevation_deg : array_like
            Elevations, degrees.

        Returns
        -------
        ndarray
        """
        el = np.asarray(elevation_deg, dtype=float)
        if not np.isfinite(el).all():
            raise InputError("elevations must be finite numbers of degrees")
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
        ``R`` for ``dt_s != self.dt_s`` are in the module docstring.

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
            ``(phi, qd_m2, r_m2)``.

        Raises
        ------
        InputError
            For a bad interval or mode, or an elevation without a mapping.
        """
        dt = self.dt_s if dt_s is None else _check_dt(dt_s)
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
        """
        if int(n_samples) < 1:
            raise InputError(f"n_samples must be >= 1, got {n_samples}")
        gen = np.random.default_rng(rng)
        phi, qd, r = self.to_state_space(dt_s, white_noise=white_noise)
        shape = (1 if n_series is None else int(n_series), int(n_samples))
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
