"""The complete multipath error model a Kalman filter takes from a fit.

:class:`ErrorModel` gathers every component the fit states, each with its
parameters, where it comes from and what a filter needs of it:

``gauss_markov``
    The PSD bound's first-order Gauss-Markov part (``sigma_gm_m``, ``tau_s``;
    elevation-mapped). Below the bound's lowest band it lies above every
    Gauss-Markov + white model the main shape group's pooled spectrum admits
    (``bound.low_frequency``; :mod:`psdbound.spectra.lowfreq`): a statement on
    that group's models, not on a window of another shape.
``slow``
    The multipath the high-pass removed below the cutoff, which the bound
    cannot see: the least-variance first-order Gauss-Markov process above
    the removed spectrum of the reflectors around the antenna along the
    data's passes (``validation.slow``, :mod:`psdbound.validation.removed`;
    height and amplitude ratio from the SNR where measured). It applies at
    every elevation (not mapped). Present only when the validation ran
    (dual-frequency isolation).
``white``
    The bound's white part (``sigma_wn_m`` per sample at the data interval
    ``dt_s``; elevation-mapped).

:meth:`ErrorModel.to_state_space` returns ``(phi, q, r, p0)`` for a filter
interval, with one state per correlated component; it refuses a fit whose
verdict is not ``"bounded"`` unless ``allow_not_bounded=True``, and warns
when the filter step is shorter than the data interval (no white level is
known above the data's Nyquist frequency). The same numbers are in
``result.json`` (``error_model``), so ``psdbound.load(path).error_model``
gives the model of a stored fit.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError
from psdbound.kalman.uncertain import GaussMarkovSet
from psdbound.spectra.models import GaussMarkovWhiteNoise

__all__ = ["Component", "ErrorModel", "ErrorStateSpace", "error_model_section", "integrity_note"]

#: Kinds of component.
KINDS = ("gauss-markov", "white")


@dataclass(frozen=True)
class Component:
    """One component of the error model.

    Attributes
    ----------
    name : str
        ``"gauss_markov"``, ``"slow"`` or ``"white"``.
    kind : {"gauss-markov", "white"}
        Its process.
    sigma_m : float
        Standard deviation, metres (per sample at ``dt_s`` for white noise).
    tau_s : float or None
        Time constant, seconds (Gauss-Markov only).
    elevation_mapped : bool
        Whether ``sigma_m`` is at the zenith scale of the fit's elevation
        mapping (multiply by ``m(el)``) or applies at every elevation.
    source : str
        Where the numbers come from and what they assume.
    """

    name: str
    kind: str
    sigma_m: float
    tau_s: float | None = None
    elevation_mapped: bool = True
    source: str = ""

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise InputError(
                f"component {self.name!r}: kind must be one of {KINDS}, got {self.kind!r}"
            )
        if not (math.isfinite(self.sigma_m) and self.sigma_m >= 0.0):
            raise InputError(f"component {self.name!r}: sigma_m must be >= 0, got {self.sigma_m}")
        if self.kind == "gauss-markov" and not (self.tau_s is not None and self.tau_s > 0.0):
            raise InputError(f"component {self.name!r}: a Gauss-Markov tau_s must be > 0")

    @property
    def variance_m2(self) -> float:
        """Variance, m^2."""
        return self.sigma_m**2

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {
            "name": self.name,
            "kind": self.kind,
            "sigma_m": self.sigma_m,
            "tau_s": self.tau_s,
            "elevation_mapped": self.elevation_mapped,
            "source": self.source,
        }


class ErrorStateSpace(NamedTuple):
    """Discrete state-space model of the error for one filter interval.

    ``x[k+1] = phi x[k] + w[k]``, ``w ~ N(0, q)``; error ``e[k] = sum(x[k]) + v[k]``,
    ``v ~ N(0, r)``; start with ``x[0] ~ N(0, p0)``.

    Attributes
    ----------
    states : tuple of str
        Component name of each state (the correlated components).
    phi : ndarray, shape (n, n)
        State transition (diagonal).
    q_m2 : ndarray, shape (n, n)
        Process-noise covariance, m^2.
    r_m2 : float
        White measurement-noise variance per filter sample, m^2.
    p0_m2 : ndarray, shape (n, n)
        Initial state covariance, m^2: each state's stationary variance, the
        least that bounds it from the first step.
    """

    states: tuple[str, ...]
    phi: NDArray[np.float64]
    q_m2: NDArray[np.float64]
    r_m2: float
    p0_m2: NDArray[np.float64]


@dataclass(frozen=True)
class ErrorModel:
    """Every component of a fit's multipath error model (module docstring).

    Attributes
    ----------
    components : tuple of Component
        The components, Gauss-Markov first.
    dt_s : float
        Data interval the white level and the bound were stated at, seconds.
    f_min_hz : float
        Lowest band of the data, Hz (below it the model rests on
        ``low_frequency``).
    verdict : str
        The fit's verdict.
    verdict_reasons : tuple of str
        Why not bounded.
    low_frequency : str
        What the model covers below ``f_min_hz`` (the fit's statement).
    mapping : dict or None
        Elevation mapping ``{"a", "b", "c_deg"}`` of the elevation-mapped
        components (None: they apply to the raw error).
    source : str
        Where the model was read from.
    parameter_set : dict or None
        Intervals of the Gauss-Markov + white models the data admit (with
        the bound): ``tau_s``, ``sigma_gm_m``, ``sigma_wn_m`` as ``[lo, hi]``
        (:meth:`gauss_markov_set`).
    """

    components: tuple[Component, ...]
    dt_s: float
    f_min_hz: float
    verdict: str = "bounded"
    verdict_reasons: tuple[str, ...] = ()
    low_frequency: str = ""
    mapping: dict[str, float] | None = None
    source: str = ""
    parameter_set: dict[str, list[float]] | None = None
    _by_name: dict[str, Component] = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        if not (math.isfinite(self.dt_s) and self.dt_s > 0):
            raise InputError(f"dt_s must be > 0, got {self.dt_s}")
        object.__setattr__(self, "_by_name", {c.name: c for c in self.components})

    # --------------------------------------------------------------- access
    def __getitem__(self, name: str) -> Component:
        """Return the component called ``name``."""
        try:
            return self._by_name[name]
        except KeyError:
            raise KeyError(f"no component {name!r}; have {sorted(self._by_name)}") from None

    def factor(self, c: Component, elevation_deg: float | None) -> float:
        """Return the scale of a component's sigma at an elevation (1 at zenith scale).

        Parameters
        ----------
        c : Component
            The component.
        elevation_deg : float or None
            Elevation, degrees; None: the zenith scale the model is stated at.

        Returns
        -------
        float
            ``m(el)`` of the fit's mapping for an elevation-mapped component,
            1 otherwise.

        Raises
        ------
        InputError
            An elevation that is not a finite number of degrees in [0, 90].
        """
        if elevation_deg is not None and not 0.0 <= float(elevation_deg) <= 90.0:
            raise InputError(f"elevation_deg must lie in [0, 90] degrees, got {elevation_deg!r}")
        if elevation_deg is None or not c.elevation_mapped or self.mapping is None:
            return 1.0
        from psdbound.stationarity.mapping import ElevationMapping

        mp = self.mapping
        return float(
            ElevationMapping(mp["a"], mp["b"], mp["c_deg"], "fixed").factor(float(elevation_deg))
        )

    def _parts(self, elevation_deg: float | None = None) -> list[GaussMarkovWhiteNoise]:
        """One model per Gauss-Markov component; the white part rides on the first."""
        wn = self._by_name.get("white")
        gms = [c for c in self.components if c.kind == "gauss-markov"]
        out = [
            GaussMarkovWhiteNoise(
                c.sigma_m * self.factor(c, elevation_deg), c.tau_s, 0.0, self.dt_s
            )
            for c in gms
        ] or [GaussMarkovWhiteNoise(0.0, 1.0, 0.0, self.dt_s)]
        if wn is not None:
            m = out[0]
            out[0] = GaussMarkovWhiteNoise(
                m.sigma_gm_m, m.tau_s, wn.sigma_m * self.factor(wn, elevation_deg), self.dt_s
            )
        return out

    @property
    def nyquist_hz(self) -> float:
        """Nyquist frequency of the data, Hz."""
        return 0.5 / self.dt_s

    def variance_m2(
        self,
        dt_s: float | None = None,
        *,
        white_noise: str = "conservative",
        elevation_deg: float | None = None,
    ) -> float:
        """Total variance of one sample at interval ``dt_s`` (all components), m^2.

        Parameters
        ----------
        dt_s : float, optional
            Sampling interval, seconds; default the data interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            The white part's variance at another interval
            (:meth:`psdbound.spectra.GaussMarkovWhiteNoise.white_variance_m2`).
        elevation_deg : float, optional
            Elevation, degrees: the mapped components scaled by ``m(el)``;
            default the zenith scale.

        Returns
        -------
        float
        """
        parts = self._parts(elevation_deg)
        return sum(m.variance_m2(dt_s, white_noise=white_noise) for m in parts)

    @staticmethod
    def _frequencies(f_hz: ArrayLike) -> NDArray[np.float64]:
        """``f_hz`` as floats; non-numeric, negative, NaN or infinite values refused."""
        try:
            if np.iscomplexobj(f_hz):  # numpy would drop the imaginary part with a warning
                raise TypeError
            f = np.asarray(f_hz, dtype=float)
        except (TypeError, ValueError):
            raise InputError(f"f_hz must be real numbers in Hz, got {f_hz!r}") from None
        if not (np.isfinite(f) & (f >= 0)).all():
            raise InputError("frequencies must be finite numbers >= 0 Hz")
        return f

    def _check_band(self, f: NDArray[np.float64], nyquist_hz: float) -> None:
        if (f > nyquist_hz * (1 + 1e-9)).any():
            warnings.warn(
                f"frequencies above the data's Nyquist frequency {nyquist_hz:g} Hz: "
                "the data say nothing there; the model is an extrapolation",
                stacklevel=3,
            )

    def psd(self, f_hz: ArrayLike, *, elevation_deg: float | None = None) -> NDArray[np.float64]:
        """Continuous-time one-sided PSD of every component, m^2/Hz.

        Parameters
        ----------
        f_hz : array_like
            Frequencies, Hz (>= 0; above the data's Nyquist frequency a
            warning: extrapolated).
        elevation_deg : float, optional
            Elevation, degrees (mapped components scaled by ``m(el)``);
            default the zenith scale (``m = 1``; the slow component as it is).

        Returns
        -------
        ndarray
        """
        f = self._frequencies(f_hz)
        self._check_band(f, self.nyquist_hz)
        return sum(m.psd(f) for m in self._parts(elevation_deg))

    def sampled_psd(
        self,
        f_hz: ArrayLike,
        dt_s: float | None = None,
        *,
        white_noise: str = "conservative",
        elevation_deg: float | None = None,
    ) -> NDArray[np.float64]:
        """One-sided PSD of the model sampled at ``dt_s`` (aliases folded in), m^2/Hz.

        Parameters
        ----------
        f_hz : array_like
            Frequencies, Hz, in ``[0, 1/(2 dt_s)]``.
        dt_s : float, optional
            Sampling interval, seconds; default the data interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            The white part at another interval.
        elevation_deg : float, optional
            Elevation, degrees; default the zenith scale.

        Returns
        -------
        ndarray
        """
        parts = self._parts(elevation_deg)
        dt = parts[0].checked_dt_s(dt_s)
        f = self._frequencies(f_hz)
        if not (f <= 0.5 / dt * (1 + 1e-9)).all():
            raise InputError(f"frequencies must lie in [0, {0.5 / dt:g}] Hz for dt = {dt:g} s")
        if dt < self.dt_s * (1 - 1e-9):
            self._check_band(f, self.nyquist_hz)
        return sum(m.sampled_psd(f, dt, white_noise=white_noise) for m in parts)

    # --------------------------------------------------------------- export
    def to_state_space(
        self,
        dt_s: float | None = None,
        *,
        allow_not_bounded: bool = False,
        white_noise: str = "conservative",
        elevation_deg: float | None = None,
    ) -> ErrorStateSpace:
        """Discrete state-space model for a filter interval (one state per correlated part).

        Parameters
        ----------
        dt_s : float, optional
            Filter interval, seconds; default the data interval.
        allow_not_bounded : bool, default False
            Export the model of a fit whose verdict is not ``"bounded"``
            (for study, not for a protection level).
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            The white part's variance at another interval.
        elevation_deg : float, optional
            Elevation, degrees: the mapped components' variances times
            ``m(el)^2``; default the zenith scale.

        Returns
        -------
        ErrorStateSpace

        Warns
        -----
        UserWarning
            A filter step shorter than the data interval.

        Raises
        ------
        InputError
            A not-bounded fit (unless allowed), a bad interval or mode.
        """
        if self.verdict != "bounded" and not allow_not_bounded:
            why = "; ".join(self.verdict_reasons) or "no reason given"
            raise InputError(
                f"the verdict is {self.verdict!r} ({why}): this model is not for "
                "a filter; pass allow_not_bounded=True to export it anyway"
            )
        b = self._parts(elevation_deg)[0]
        dt = b.filter_dt_s(dt_s, white_noise=white_noise)
        states = [c for c in self.components if c.kind == "gauss-markov"]
        var = np.array([c.variance_m2 * self.factor(c, elevation_deg) ** 2 for c in states])
        phi = np.array([math.exp(-dt / c.tau_s) for c in states])
        q = var * -np.expm1(-2.0 * dt / np.array([c.tau_s for c in states]))
        p0 = var
        return ErrorStateSpace(
            tuple(c.name for c in states),
            np.diag(phi),
            np.diag(q),
            b.white_variance_m2(dt, white_noise=white_noise),
            np.diag(p0),
        )

    def gauss_markov_set(self) -> GaussMarkovSet:
        """Return the set of Gauss-Markov processes the data admit, for an uncertain-GM design.

        The intervals hold every model of the fit's model set (with ``tau`` up
        to the prior where the data do not bound it), raised to the most
        covered window, and the bound itself. Design a filter that is safe
        for all of them with :meth:`psdbound.kalman.GaussMarkovSet.design`
        and check it with :func:`psdbound.kalman.verify_design`; the design
        assumes the true error is first-order Gauss-Markov.

        Returns
        -------
        GaussMarkovSet

        Raises
        ------
        InputError
            The fit has no model set (the envelope rule, or too few bands).
        """
        ps = self.parameter_set
        if not ps:
            raise InputError(
                f"{self.source or 'this fit'} has no admitted parameter set "
                "(the envelope rule, or too few bands for a model set)"
            )
        return GaussMarkovSet(
            ps["tau_s"][0],
            ps["tau_s"][1],
            ps["sigma_gm_m"][0],
            ps["sigma_gm_m"][1],
            ps["sigma_wn_m"][1],
            self.dt_s,
        )

    # ----------------------------------------------------------------- I/O
    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (``error_model`` of result.json)."""
        ss = self.to_state_space(allow_not_bounded=True)
        return {
            "components": [c.to_dict() for c in self.components],
            "dt_s": self.dt_s,
            "nyquist_hz": self.nyquist_hz,
            "f_min_hz": self.f_min_hz,
            "low_frequency": self.low_frequency,
            "variance_m2": self.variance_m2(),
            "state_space": {
                "dt_s": self.dt_s,
                "states": list(ss.states),
                "phi": np.diag(ss.phi).tolist(),
                "q_m2": np.diag(ss.q_m2).tolist(),
                "r_m2": ss.r_m2,
                "p0_m2": np.diag(ss.p0_m2).tolist(),
            },
            "mapping": self.mapping,
            "parameter_set": self.parameter_set,
        }

    @classmethod
    def from_document(cls, document: dict[str, Any], *, source: str = "") -> ErrorModel:
        """Read the model of a result document (``psdbound.load(path).document``).

        Parameters
        ----------
        document : dict
            A result document with an ``error_model`` section.
        source : str, optional
            Where it came from (for messages).

        Returns
        -------
        ErrorModel

        Raises
        ------
        InputError
            No ``error_model`` section (a result written before it existed:
            refit), or a malformed component.
        """
        sec = document.get("error_model")
        if not isinstance(sec, dict):
            raise InputError(
                f"{source or 'the result'} has no 'error_model' section (written "
                "by an older psdbound): fit again"
            )
        comps = tuple(
            Component(
                **{
                    k: c.get(k)
                    for k in ("name", "kind", "sigma_m", "tau_s", "elevation_mapped", "source")
                }
            )
            for c in sec["components"]
        )
        return cls(
            comps,
            float(sec["dt_s"]),
            float(sec["f_min_hz"]),
            verdict=str(document.get("verdict", "bounded")),
            verdict_reasons=tuple(document.get("verdict_reasons", ())),
            low_frequency=str(sec.get("low_frequency", "")),
            mapping=sec.get("mapping"),
            source=source,
            parameter_set=sec.get("parameter_set"),
        )

    def summary(self) -> str:
        """Return a text table of the components."""
        rows = [
            f"error model ({self.verdict}; data interval {self.dt_s:g} s, stated from "
            f"{self.f_min_hz:.3g} Hz to Nyquist {self.nyquist_hz:.3g} Hz)"
        ]
        for c in self.components:
            tau = f"tau {c.tau_s:.4g} s" if c.tau_s else c.kind
            rows.append(
                f"  {c.name:<13}{1000 * c.sigma_m:8.3f} mm  {tau}"
                + ("  (x m(el))" if c.elevation_mapped else "")
            )
        rows.append(f"  below {self.f_min_hz:.3g} Hz: {self.low_frequency}")
        return "\n".join(rows)


def integrity_note(confidence_level: float | None, coverage: float | None) -> str:
    """Return what the bound's statement means for a protection level, in words.

    Parameters
    ----------
    confidence_level, coverage : float or None
        The statement's confidence and window coverage (None: the envelope
        rule, which states neither).

    Returns
    -------
    str
    """
    if confidence_level is None or coverage is None:
        return (
            "the envelope rule states no confidence: the model is not one a protection "
            "level can rest on"
        )
    return (
        f"A protection level multiplies the filter's sigma by K for its integrity risk (K = "
        f"5.33 for 1e-7, two-sided Gaussian). That is valid if the model over-bounds the true "
        f"error, which this fit states with {100 * confidence_level:g} % confidence for at "
        f"least {100 * coverage:g} % of the stationary windows of these data: the "
        f"{100 * (1 - confidence_level):g} % and the {100 * (1 - coverage):g} % are not part of "
        f"K's risk and must be budgeted separately. Not covered: data screened out or never "
        f"stationary, other days, antennas and environments, non-Gaussian tails, and time "
        f"constants above the prior where the data do not bound them."
    )


def error_model_section(
    bound: dict[str, Any],
    *,
    mapping: dict[str, Any] | None,
    slow: Sequence[Component] = (),
) -> dict[str, Any]:
    """Build the ``error_model`` section of a result document from its ``bound`` section.

    Parameters
    ----------
    bound : dict
        The ``bound`` section (``sigma_gm_m``, ``tau_s``, ``sigma_wn_m``,
        ``dt_s``, ``band_hz``, ``low_frequency``).
    mapping : dict or None
        The ``mapping`` section.
    slow : sequence of Component
        Slow components estimated elsewhere (the cutoff validation).

    Returns
    -------
    dict
    """
    low = bound.get("low_frequency") or {}
    gm = Component(
        "gauss_markov",
        "gauss-markov",
        float(bound["sigma_gm_m"]),
        float(bound["tau_s"]),
        True,
        "the PSD bound's Gauss-Markov part (bound.sigma_gm_m, bound.tau_s)",
    )
    wn = Component(
        "white",
        "white",
        float(bound["sigma_wn_m"]),
        None,
        True,
        "the PSD bound's white part, per sample at bound.dt_s (bound.sigma_wn_m)",
    )
    mp = None if mapping is None else {k: mapping[k] for k in ("a", "b", "c_deg")}
    pooled = bound.get("pooled") or {}
    model = ErrorModel(
        (gm, *slow, wn),
        float(bound["dt_s"]),
        float(bound["band_hz"][0]),
        low_frequency=str(low.get("statement", "not checked (envelope rule)")),
        mapping=mp,
        parameter_set=low.get("parameter_set"),
    )
    return {
        **model.to_dict(),
        "integrity_note": integrity_note(bound.get("confidence_level"), pooled.get("coverage")),
    }
