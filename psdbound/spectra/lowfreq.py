"""Below the lowest band: the bound must cover every model the data admit, down to 0 Hz.

The pooled limits hold from the lowest band ``f_min`` to Nyquist. A Kalman
filter uses the error model at every frequency, most of all the low ones it
averages over, so the bound's PSD below ``f_min`` is part of the statement.
Extrapolating the fitted Gauss-Markov plateau is not: above ``f_min`` a slow
process shows only its ``1/f^2`` tail, and the tightest bound over the bands
then has a short time constant whose plateau lies far under the slow truth
(a 600 s truth at 30 s: 0.025 times its PSD at 0 Hz).

**Rule.** The model set (:func:`psdbound.spectra.intervals.model_set`) holds
every GM + white model whose exact band expectations fit the pooled spectrum
at the stated level. Below ``f_min`` the bound is required to lie above the
envelope of that set, each model raised by the largest factor from the group
to a covered window (:attr:`~psdbound.spectra.intervals.ModelSet.window_factor`),
at frequencies from ``f_min`` down to ``1e-4 f_min`` (where every admitted
plateau is flat). The set's PSD at ``f`` is linear in the two variances, so
its largest value per time constant lies at a corner of that time constant's
polygon of admitted variances
(:attr:`~psdbound.spectra.intervals.ModelSet.vertices`): the envelope is the
largest PSD over the corners, exact at the searched time constants. The
bound is refitted with these points as constraints of its linear programs
(:func:`psdbound.spectra.pooled.fit_limits`); where the tightest bound already
lies above them nothing changes.

**Prior.** When the data do not bound ``tau`` above (the set reaches its
search edge), the envelope grows without limit as ``tau`` does: the data
alone cannot state a bound at 0 Hz. The envelope is then taken over
``tau <= tau_max_s``, a stated prior (default :data:`TAU_MAX_S` = 900 s, the
upper end of the raw carrier-multipath time constants, 10-900 s, used for
Kalman-filter ARAIM with uncertain Gauss-Markov errors [1]_), and the result
says so (:attr:`LowFrequency.prior_binding`). With ``policy="refuse"`` such a
case is not bounded instead.

**No model set** (fewer test bands than the three parameters need). The bound
is still held above every GM + white model with ``tau <= tau_max_s`` whose
mean over its group's lowest band lies within that band's limit: each term's
``f^2 S(f)`` rises with ``f``, so such a model is at most ``r = hi / lo`` times
the limit at the band's lower edge, and below it grows by at most the
largest ratio ``S(f) / S(lo)`` of a Gauss-Markov term with ``tau <= tau_max_s``
(:func:`prior_ceiling`). Fewer bands mean a wider set of models, never a
statement left to the fitted model's extrapolation; status ``"unchecked"``
says that the data could not narrow the set, and ``policy="refuse"`` makes
such a case not bounded too.

Why the envelope suffices for a first-order truth: if a GM + white truth lies
under the bound at ``f_min`` and is one of the admitted models, the bound lies
above it at every lower frequency by construction of the envelope. That the
truth *is* first-order GM + white is the model's assumption; a slow component
of another shape is covered only as far as its band averages constrain the
set, and, for data that went through no filter, as far as the windows'
lowest Fourier frequencies show it (:mod:`psdbound.spectra.lowest`).

**Whose models.** The set is identified from the main shape group's pooled
spectrum (group 0). A window of another shape -- another group's, or a
slower reflector the shape tests could not tell from the main group -- is
not one of its models, and below the lowest band the bound lies above such
a window's truth only where it happens to (measured: the column ``lowcov``
of ``benchmarks/bound_coverage.py``, 0.71-0.89 of the runs with a minority
of slow reflectors). The statement's sentence says so.

References
----------
.. [1] Langel, S., Garcia Crespillo, O., & Joerger, M. (2021). Overbounding the
   effect of uncertain Gauss-Markov noise in Kalman filtering. *NAVIGATION*,
   68(2), 259-276 (time constants known only to lie in an interval).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.spectra.bands import BandSpectra
from psdbound.spectra.bound import BoundFit, Floor
from psdbound.spectra.intervals import ModelSet
from psdbound.spectra.models import below_band_ceiling, gm_psd_sampled
from psdbound.spectra.names import POLICIES, TAU_MAX_S
from psdbound.spectra.pooled import PooledLimits, fit_limits, lowest_limit

__all__ = [
    "LowFrequency",
    "POLICIES",
    "TAU_MAX_S",
    "bound_below",
    "envelope_below",
    "low_frequency_reasons",
    "model_envelope",
    "prior_ceiling",
]

#: Envelope frequencies below f_min, as fractions of it (1e-4: every admitted plateau is flat).
_FRACTIONS = np.geomspace(1e-4, 1.0, 41)


@dataclass(frozen=True)
class LowFrequency:
    """What the bound covers below its lowest band.

    Attributes
    ----------
    status : {"covered", "prior", "unchecked"}
        ``"covered"``: the bound lies above every model the data admit, down
        to 0 Hz, with no prior; ``"prior"``: the data do not bound ``tau``
        above and the bound covers the admitted models with
        ``tau <= tau_max_s`` only; ``"unchecked"``: no model set (``reason``):
        the bound covers every model with ``tau <= tau_max_s`` within the
        lowest bands' limits (:func:`prior_ceiling`).
    tau_max_s : float
        Prior upper limit of the time constant, seconds.
    tau_upper_s : float
        Largest time constant the data admit, seconds (``inf`` when the set
        reaches its search edge).
    f_hz, envelope_m2_hz : ndarray
        Envelope of the admitted models below ``f_min`` (raised by the
        window factor; without a model set, :func:`prior_ceiling`), Hz and
        m^2/Hz.
    raised : bool
        Whether the bound had to be raised above the tightest bound over the
        bands to lie above the envelope.
    before : dict
        The tightest bound over the bands alone (``sigma_gm_m``, ``tau_s``,
        ``sigma_wn_m``).
    reason : str
        Why the check could not be made (``"unchecked"``).
    parameter_set : dict or None
        The admitted models with ``tau <= tau_max_s``, raised to the most
        covered window, and the bound, as intervals: ``tau_s`` ``[lo, hi]``
        (s), ``sigma_gm_m`` ``[lo, hi]`` and ``sigma_wn_m`` ``[lo, hi]`` (m).
        The set a Kalman-filter design for uncertain Gauss-Markov errors
        must be safe for (:meth:`psdbound.kalman.ErrorModel.gauss_markov_set`).
    """

    status: str
    tau_max_s: float
    tau_upper_s: float = float("inf")
    f_hz: NDArray[np.float64] | None = None
    envelope_m2_hz: NDArray[np.float64] | None = None
    raised: bool = False
    before: dict[str, float] | None = None
    reason: str = ""
    parameter_set: dict[str, list[float]] | None = None

    def floor(self) -> Floor | None:
        """Return the envelope as constraint points (Hz, m^2/Hz) of a refit; None without one."""
        if self.f_hz is None or self.envelope_m2_hz is None or not self.envelope_m2_hz.size:
            return None
        return self.f_hz, self.envelope_m2_hz

    @property
    def prior_binding(self) -> bool:
        """Whether the statement at 0 Hz rests on the prior ``tau <= tau_max_s``."""
        return self.status == "prior"

    def sentence(self) -> str:
        """Return the low-frequency part of the statement, in words."""
        if self.status == "unchecked" and self.envelope_m2_hz is None:
            return (
                "below the lowest band the bound is the fitted model's extrapolation, "
                f"not checked against the data ({self.reason})"
            )
        if self.status == "unchecked":
            return (
                "below the lowest band, down to 0 Hz, the bound lies above every "
                "Gauss-Markov + white-noise model with a time constant up to the prior "
                f"{self.tau_max_s:g} s whose mean over its group's lowest band lies within "
                f"that band's limit: the data could not narrow these models ({self.reason})"
            )
        what = (
            "above every Gauss-Markov + white-noise model that the main shape group's pooled "
            "spectrum admits at the same confidence (each raised to the most covered window)"
        )
        # the set is the main group's (intervals.model_set, group 0): the other groups'
        # windows, and a slower one left in the main group, are not among its models
        # (benchmarks/bound_coverage.py, column lowcov)
        which = (
            "; a window of another shape (another group's, or a slower one that the shape "
            "tests could not tell from the main group) is not covered by this clause"
        )
        if self.status == "prior":
            return (
                f"below the lowest band, down to 0 Hz, the bound lies {what} with a time "
                f"constant up to the prior {self.tau_max_s:g} s: the data do not bound "
                f"the time constant above{which}"
            )
        return (
            f"below the lowest band, down to 0 Hz, the bound lies {what}; the data bound the "
            f"time constant above at {self.tau_upper_s:.4g} s{which}"
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (``bound.low_frequency`` of result.json)."""
        return {
            "status": self.status,
            "tau_max_s": self.tau_max_s,
            "tau_upper_s": self.tau_upper_s if np.isfinite(self.tau_upper_s) else None,
            "raised": self.raised,
            "before": self.before,
            "envelope_at_0_m2_hz": (
                float(self.envelope_m2_hz[0]) if self.envelope_m2_hz is not None else None
            ),
            "statement": self.sentence(),
            "reason": self.reason,
            "parameter_set": self.parameter_set,
        }


def envelope_below(
    ms: ModelSet, dt_s: float, f_min_hz: float, *, tau_max_s: float = TAU_MAX_S
) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    """Return the envelope of the admitted models below ``f_min_hz``.

    Parameters
    ----------
    ms : ModelSet
        The model set, with its slices.
    dt_s : float
        Sampling interval, seconds.
    f_min_hz : float
        Lowest band edge, Hz.
    tau_max_s : float, default :data:`TAU_MAX_S`
        Only models with ``tau <= tau_max_s`` enter.

    Returns
    -------
    f_hz, envelope_m2_hz : ndarray
        Frequencies from ``1e-4 f_min`` to ``f_min`` and the envelope there
        (empty when no admitted model has ``tau <= tau_max_s``).
    tau_upper_s : float
        Largest admitted time constant (``inf`` at the search edge).
    """
    sl = ms.slices
    open_top = bool(ms.open_ends.get("tau_s", (False, False))[1])
    tau_upper = float("inf") if open_top or sl.size == 0 else float(sl[:, 0].max())
    f = f_min_hz * _FRACTIONS
    return f, model_envelope(ms, dt_s, f, tau_max_s=tau_max_s), tau_upper


def model_envelope(
    ms: ModelSet, dt_s: float, f_hz: NDArray[np.float64], *, tau_max_s: float = TAU_MAX_S
) -> NDArray[np.float64]:
    """Return the largest PSD of the admitted models at ``f_hz``, raised by the window factor.

    Parameters
    ----------
    ms : ModelSet
        The model set, with its vertices.
    dt_s : float
        Sampling interval, seconds.
    f_hz : ndarray
        Frequencies, Hz.
    tau_max_s : float, default :data:`TAU_MAX_S`
        Only models with ``tau <= tau_max_s`` enter (``inf``: all).

    Returns
    -------
    ndarray
        m^2/Hz at ``f_hz``; empty when no admitted model has ``tau <= tau_max_s``.
    """
    vx = ms.vertices
    use = vx[vx[:, 0] <= tau_max_s * (1.0 + 1e-9)] if vx.size else vx
    if use.size == 0:
        return np.zeros(0)
    psd = np.stack([v * gm_psd_sampled(f_hz, 1.0, tau, dt_s) + w * 2.0 * dt_s for tau, v, w in use])
    return psd.max(axis=0) * ms.window_factor


def bound_below(
    fit: BoundFit,
    bands: BandSpectra,
    limits: PooledLimits,
    ms: ModelSet | None,
    dt_s: float,
    *,
    tau_max_s: float = TAU_MAX_S,
    objective: str = "variance",
    n_grid: int = 64,
    reason: str = "",
) -> tuple[BoundFit, LowFrequency]:
    """Raise the bound, where needed, above every admitted model below its lowest band.

    Parameters
    ----------
    fit : BoundFit
        The tightest bound over the pooled limits.
    bands : BandSpectra
        The bands of the limits.
    limits : PooledLimits
        The pooled limits.
    ms : ModelSet or None
        The model set (None: nothing to check; ``reason`` says why).
    dt_s : float
        Sampling interval, seconds.
    tau_max_s : float, default :data:`TAU_MAX_S`
        Prior upper limit of the time constant, seconds.
    objective : {"variance", "area"}, default "variance"
        Tightness objective of the refit.
    n_grid : int, default 64
        ``tau`` grid size of the refit.
    reason : str, optional
        Why there is no model set.

    Returns
    -------
    fit : BoundFit
        The bound (unchanged when it already covers the envelope).
    low : LowFrequency
        What it covers below the lowest band.
    """
    before = {"sigma_gm_m": fit.sigma_gm_m, "tau_s": fit.tau_s, "sigma_wn_m": fit.sigma_wn_m}
    if ms is None or ms.vertices.size == 0:
        why = reason or "no model set"
        ceiling = prior_ceiling(limits, bands, dt_s, tau_max_s=tau_max_s)
        if ceiling is None:
            return fit, LowFrequency("unchecked", tau_max_s, before=before, reason=why)
        f, env = ceiling
        fit, raised = _raised(fit, limits, bands, dt_s, f, env, objective, n_grid)
        return fit, LowFrequency(
            "unchecked",
            tau_max_s,
            f_hz=f,
            envelope_m2_hz=env,
            raised=raised,
            before=before,
            reason=why,
        )
    f_min = float(bands.edges_hz[0])
    f, env, tau_upper = envelope_below(ms, dt_s, f_min, tau_max_s=tau_max_s)
    status = "prior" if tau_upper > tau_max_s else "covered"
    if env.size == 0:
        return fit, LowFrequency(
            status,
            tau_max_s,
            tau_upper,
            before=before,
            reason="no admitted model has tau <= tau_max_s",
        )
    fit, raised = _raised(fit, limits, bands, dt_s, f, env, objective, n_grid)
    return fit, LowFrequency(
        status,
        tau_max_s,
        tau_upper,
        f_hz=f,
        envelope_m2_hz=env,
        raised=raised,
        before=before,
        parameter_set=_parameter_set(ms, fit, tau_max_s),
    )


def _raised(
    fit: BoundFit,
    limits: PooledLimits,
    bands: BandSpectra,
    dt_s: float,
    f: NDArray[np.float64],
    env: NDArray[np.float64],
    objective: str,
    n_grid: int,
) -> tuple[BoundFit, bool]:
    """Refit the bound above ``env`` at ``f`` when it lies below it anywhere."""
    if not np.any(fit.psd(f) < env * (1.0 - 1e-9)):
        return fit, False
    return fit_limits(limits, bands, dt_s, objective=objective, n_grid=n_grid, floor=(f, env)), True


def prior_ceiling(
    limits: PooledLimits, bands: BandSpectra, dt_s: float, *, tau_max_s: float = TAU_MAX_S
) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
    """Return the largest PSD below ``f_min`` of the models within the lowest bands' limits.

    The models are every sum of Gauss-Markov terms with ``tau <= tau_max_s``
    and white noise whose mean over a group's lowest band ``[lo, hi]`` lies
    within the group's upper limit ``U`` there. Each term has ``f^2 S(f)``
    rising in ``f``, so at ``lo`` such a sum is at most ``U hi / lo``
    (:func:`~psdbound.spectra.models.below_band_ceiling`); below ``lo`` each
    term grows by at most the largest ``S(f) / S(lo)`` of a Gauss-Markov
    term with ``tau <= tau_max_s`` (white noise: 1), taken over a grid of
    time constants from ``dt_s`` to ``tau_max_s``.

    Parameters
    ----------
    limits : PooledLimits
        The pooled limits (each group's lowest finite band is used).
    bands : BandSpectra
        Their bands.
    dt_s : float
        Sampling interval, seconds.
    tau_max_s : float, default :data:`TAU_MAX_S`
        Prior upper limit of the time constant, seconds.

    Returns
    -------
    (f_hz, ceiling_m2_hz) or None
        From ``1e-4 f_min`` to ``f_min`` (Hz) and the ceiling there (m^2/Hz),
        the largest over the groups; None without a finite limit.
    """
    f_min = float(bands.edges_hz[0])
    f = f_min * _FRACTIONS
    taus = np.geomspace(dt_s, max(tau_max_s, dt_s), 64)
    out = np.zeros_like(f)
    for g in range(limits.upper_m2_hz.shape[0]):
        lowest = lowest_limit(limits, bands, g)
        if lowest is None:
            continue
        upper, lo, hi = lowest
        at_lo = float(below_band_ceiling(upper, lo, hi, lo))
        shapes = [gm_psd_sampled(f, 1.0, t, dt_s) / gm_psd_sampled(lo, 1.0, t, dt_s) for t in taus]
        ratio = np.max(shapes, axis=0)
        out = np.maximum(out, at_lo * np.maximum(ratio, 1.0))
    return (f, out) if np.any(out > 0) else None


def _parameter_set(ms: ModelSet, fit: BoundFit, tau_max_s: float) -> dict[str, list[float]]:
    """Intervals of the admitted models with ``tau <= tau_max_s`` and the bound (their hull)."""
    sl = ms.slices[ms.slices[:, 0] <= tau_max_s * (1.0 + 1e-9)]
    wf = ms.window_factor
    tau = [min(float(sl[:, 0].min()), fit.tau_s), max(float(sl[:, 0].max()), fit.tau_s)]
    gm = [float(np.sqrt(sl[:, 1].min() / wf)), float(np.sqrt(sl[:, 2].max() * wf))]
    wn = [float(np.sqrt(sl[:, 3].min() / wf)), float(np.sqrt(sl[:, 4].max() * wf))]
    gm = [min(gm[0], fit.sigma_gm_m), max(gm[1], fit.sigma_gm_m)]
    wn = [min(wn[0], fit.sigma_wn_m), max(wn[1], fit.sigma_wn_m)]
    return {"tau_s": tau, "sigma_gm_m": gm, "sigma_wn_m": wn}


def low_frequency_reasons(section: dict[str, Any] | None, policy: str = "prior") -> list[str]:
    """Return why the bound cannot be stated below its lowest band (empty: it can).

    Parameters
    ----------
    section : dict or None
        :meth:`LowFrequency.to_dict` (``bound.low_frequency`` of result.json);
        None: the envelope rule, no check.
    policy : {"prior", "refuse"}, default "prior"
        ``"refuse"``: a statement that rests on the prior ``tau <= tau_max_s``
        is not bounded, and neither is one the data could not check
        (``"unchecked"``: the fitted model's extrapolation below the lowest
        band, which the data do not bound either).

    Returns
    -------
    list of str
        One sentence per reason.
    """
    if not section:
        return []
    if section["status"] == "unchecked":
        if policy != "refuse":
            return []
        why = section.get("reason") or "no model set"
        return [
            f"low frequencies: the data could not narrow the models below the lowest band "
            f"({why}); the bound there rests on the prior tau <= {section['tau_max_s']:g} s "
            f"or on the fitted model's extrapolation, and the low-frequency policy is 'refuse'"
        ]
    tau_max = section["tau_max_s"]
    if section["status"] == "prior" and section.get("envelope_at_0_m2_hz") is None:
        return [
            f"low frequencies: the data admit only time constants above the prior "
            f"maximum {tau_max:g} s (tau_max_s), so nothing bounds the error below the "
            f"lowest band"
        ]
    if section["status"] == "prior" and policy == "refuse":
        return [
            f"low frequencies: the data do not bound the time constant above; below the "
            f"lowest band the bound would rest on the prior tau <= {tau_max:g} s and the "
            f"low-frequency policy is 'refuse'"
        ]
    return []
