"""The known truth of a simulation in the pipeline's units, and a bound checked against it.

What the pipeline bounds
------------------------
The simulator's error of one signal is ``m(el) (GM + WN) + receiver noise``
(:class:`~psdbound.simulate.scenario.MultipathModel`). The dual-frequency
(DF) series is ``(nu_1 - nu_2) / sqrt(2)``: the two signals' processes are
independent with equal variances, so the DF series has the same GM
(``sigma_gm_m``, ``tau_s``) and white (``sigma_wn_m``) parameters. Divided by
the true mapping ``m(el)`` (the fit's ``mapping={"kind": "fixed", ...}``)
it is, at zenith scale,

    GM(sigma_gm_m, tau_s) + white noise of per-sample std
    sqrt(sigma_wn_m^2 + (receiver_noise_m / m(el))^2)

The receiver noise is added after the mapping, so the mapped series carries
``receiver_noise_m / m(el)``, largest at zenith where ``m`` is smallest
(``m(90 deg) = a`` to within ``b exp(-8100 / (2 c^2))``: 1.4e-7 for the demo's
``a = 1, b = 9, c = 15 deg``). :func:`truth_model` returns that largest
white level: the PSD a bound must cover at every elevation.

Not part of this truth: deterministic reflections (not Gauss-Markov, so
:func:`truth_model` refuses them), ionospheric disturbances (removed by the
screening, or a failure of it) and the smooth ionosphere and travelling
disturbance (below the high-pass cutoff). The dual-antenna series is a
different combination (the common fraction cancels): not modelled here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from psdbound.errors import InputError
from psdbound.simulate.scenario import Scenario
from psdbound.spectra.models import GaussMarkovWhiteNoise

__all__ = ["TruthComparison", "compare_to_truth", "truth_model"]


def truth_model(scenario: Scenario) -> GaussMarkovWhiteNoise:
    """Return the PSD model a bound on the scenario's mapped DF series must cover.

    Parameters
    ----------
    scenario : Scenario
        A simulated scenario (either antenna; no reflections).

    Returns
    -------
    GaussMarkovWhiteNoise
        ``sigma_gm_m`` (m) and ``tau_s`` (s) of the injected Gauss-Markov
        process, ``sigma_wn_m = sqrt(sigma_wn^2 + (receiver_noise / m(90 deg))^2)``
        (m, per sample) and ``dt_s`` the scenario's sampling interval (s);
        at zenith scale, in the units of the fit's bound.

    Raises
    ------
    InputError
        When the scenario has deterministic reflections (their PSD is not a
        Gauss-Markov + white-noise model).

    Examples
    --------
    >>> from psdbound.simulate import preset, truth_model
    >>> truth_model(preset("demo")).tau_s
    30.0
    """
    mp = scenario.multipath
    if mp.reflections:
        raise InputError(
            "a scenario with deterministic reflections has no Gauss-Markov + white-noise truth"
        )
    white = math.hypot(mp.sigma_wn_m, scenario.receiver_noise_m / mp.factor(90.0))
    return GaussMarkovWhiteNoise(
        sigma_gm_m=mp.sigma_gm_m, tau_s=mp.tau_s, sigma_wn_m=white, dt_s=scenario.interval_s
    )


@dataclass(frozen=True)
class TruthComparison:
    """A bound against the truth over a frequency band (see :func:`compare_to_truth`).

    Attributes
    ----------
    variance_ratio : float
        Bound total variance / truth total variance (``sigma_gm^2 + sigma_wn^2``).
    tau_ratio : float
        Bound ``tau_s`` / truth ``tau_s``.
    min_psd_ratio : float
        Minimum over the band of bound PSD / truth PSD, sampled (aliased)
        PSDs at the data interval (the convention the bound is fitted in).
    f_at_min_hz : float
        Frequency of that minimum, Hz.
    covered : bool
        ``min_psd_ratio >= 1 - rtol``.
    min_psd_ratio_continuous : float
        The same minimum with the continuous-time PSDs
        (:meth:`~psdbound.spectra.GaussMarkovWhiteNoise.psd`).
    covered_continuous : bool
        ``min_psd_ratio_continuous >= 1 - rtol``.
    band_hz : tuple of float
        ``(f_min, f_max)`` compared, Hz.
    """

    variance_ratio: float
    tau_ratio: float
    min_psd_ratio: float
    f_at_min_hz: float
    covered: bool
    min_psd_ratio_continuous: float
    covered_continuous: bool
    band_hz: tuple[float, float]


def compare_to_truth(
    bound: GaussMarkovWhiteNoise,
    truth: GaussMarkovWhiteNoise,
    f_min_hz: float,
    f_max_hz: float | None = None,
    *,
    n: int = 2000,
    rtol: float = 1e-9,
) -> TruthComparison:
    """Compare a bound with the truth: variance ratio and PSD ratio over a band.

    Parameters
    ----------
    bound, truth : GaussMarkovWhiteNoise
        The fitted bound and the truth (:func:`truth_model`), same ``dt_s``.
    f_min_hz : float
        Lower end of the band, Hz (> 0; e.g. the fit's ``band_hz[0]``).
    f_max_hz : float, optional
        Upper end, Hz (default the Nyquist frequency ``1 / (2 dt_s)``).
    n : int, default 2000
        Log-spaced frequencies compared (the ends included).
    rtol : float, default 1e-9
        Relative tolerance of "covered".

    Returns
    -------
    TruthComparison

    Raises
    ------
    InputError
        Different sampling intervals or a band that is empty or not positive.
    """
    if not math.isclose(bound.dt_s, truth.dt_s, rel_tol=1e-9):
        raise InputError(f"bound at {bound.dt_s:g} s and truth at {truth.dt_s:g} s sampling")
    f_max = truth.nyquist_hz if f_max_hz is None else float(f_max_hz)
    if not (0.0 < f_min_hz < f_max <= truth.nyquist_hz * (1 + 1e-12)):
        raise InputError(
            f"band [{f_min_hz:g}, {f_max:g}] Hz must satisfy 0 < f_min < f_max <= Nyquist"
        )
    f = np.geomspace(f_min_hz, f_max, max(int(n), 2))
    ratio = bound.sampled_psd(f) / truth.sampled_psd(f)
    ratio_c = bound.psd(f) / truth.psd(f)
    k = int(np.argmin(ratio))
    return TruthComparison(
        variance_ratio=bound.total_variance_m2 / truth.total_variance_m2,
        tau_ratio=bound.tau_s / truth.tau_s,
        min_psd_ratio=float(ratio[k]),
        f_at_min_hz=float(f[k]),
        covered=bool(ratio[k] >= 1.0 - rtol),
        min_psd_ratio_continuous=float(ratio_c.min()),
        covered_continuous=bool(ratio_c.min() >= 1.0 - rtol),
        band_hz=(float(f_min_hz), float(f_max)),
    )
