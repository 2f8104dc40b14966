"""The verdict of a fit: whether the bound is one an integrity engineer can use.

``"bounded"`` only when none of the rules below fires; otherwise
``"not-bounded"`` with one reason per rule that fired. The CLI then exits
with code 3 (outputs are still written).

Rules
-----
degenerate bound
    ``sigma_GM = 0`` (a white-noise-only "bound": no time correlation was
    resolved) or ``tau`` at either end of its search grid (the optimum lies
    outside the range searched, so neither tau nor the bound is determined).
too little data for tau
    The stationary data cover less than ``min_tau_multiple * tau`` (default
    50). For a Gauss-Markov process observed over ``T`` seconds the
    variance estimate has a relative standard error of about
    ``sqrt(2 tau / T)`` (Bartlett's formula with ``R(u) = sigma^2
    exp(-|u|/tau)``); ``T >= 50 tau`` keeps it at or below 20 %.
filter loss
    The high-pass removed more than ``max_filter_loss`` (default 50 %) of the
    power above the cutoff (the filter safety check, median over arcs): the
    isolated series then no longer represents the multipath it must bound,
    typically because arcs are short compared with 1/f_c.
band
    The cutoff leaves less than ``min_band_ratio`` (default 4, two octaves)
    between ``f_c`` and the Nyquist frequency: the bound is fitted on a band
    too narrow to resolve a Gauss-Markov corner.
data outside the bound
    More than ``max_never_stationary_fraction`` (default 20 %) of the data
    that passed screening failed every stationarity test, so the bound was
    not fitted to it. (Arcs shorter than the minimum window cannot be
    tested; they are reported as ``windows.too_short_s`` and not counted.)
    A calibrated test at level 5 % rejects about 5 % of stationary data
    (3.3 % measured on a simulated stationary day at 30 s); a fifth means the
    data hold much behaviour the model does not describe. (The share is always reported as
    ``windows.covered_fraction`` and on page 1 of the report.)
most data excluded
    Screening excluded more than ``max_excluded_fraction`` (default 50 %) of
    the data: what remains does not represent the station.
cutoff validation (no longer a rule)
    The multipath the high-pass removes below the cutoff is part of the
    exported error model (``error_model`` component ``slow``: the
    least-variance Gauss-Markov process above the removed spectrum of the
    reflectors around this antenna along the data's passes, with the ground
    height and amplitude ratio measured from the SNR where the file allows;
    :mod:`psdbound.validation.removed`). An earlier rule refused a fit whose
    removed RMS exceeded the bound's sigma_GM: with the fixed amplitude
    ratio 0.1 it was about the same 2.1-2.5 mm on every station, so the
    cleanest stations came closest to refusal, and a refused fit still
    described nothing of the removed part. The thesis's fraction criterion is
    reported (``validation.verdict``), not used.
low frequencies
    Below the lowest band the bound lies above every Gauss-Markov + white
    model the data admit (``bound.low_frequency``,
    :mod:`psdbound.spectra.lowfreq`). Where the data do not bound the time
    constant above, that statement rests on the prior ``tau <= tau_max_s``:
    with ``low_frequency = "refuse"`` (default ``"prior"``) such a bound is
    not bounded; when the data admit only time constants above the prior,
    it is never bounded.

Pooled bounds (campaigns)
-------------------------
A campaign judges every station-day with :func:`judge` (the day's ``fit``)
and pools only the bounded days. The pooled bound of a station is judged by
:func:`judge_pooled`: not bounded when no bounded day is left, when it is
degenerate, when the pooled windows cover less than ``min_tau_multiple``
tau, or by the low-frequency rule. The other rules concern one day's data
and have already kept those days out of the pool.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from psdbound.common.options import Choice, Number, check_fields, option
from psdbound.spectra.lowfreq import POLICIES, low_frequency_reasons

__all__ = [
    "VerdictOptions",
    "degenerate_reasons",
    "judge",
    "judge_pooled",
    "short_data_reasons",
]


@dataclass(frozen=True)
class VerdictOptions:
    """Thresholds of the verdict rules (see the module docstring).

    Parameters
    ----------
    min_tau_multiple : float, default 50
        Stationary data must cover at least this many ``tau``.
    max_filter_loss : float, default 0.5
        Largest median fraction of power above f_c removed by the filter.
    min_band_ratio : float, default 4
        Smallest ``f_Nyquist / f_c``.
    max_excluded_fraction : float, default 0.5
        Largest fraction of the data the screening may exclude.
    max_never_stationary_fraction : float, default 0.2
        Largest fraction of the screened data left outside every stationary
        window.
    low_frequency : {"prior", "refuse"}, default "prior"
        Whether a bound whose statement below its lowest band rests on the
        prior ``tau <= tau_max_s`` (the data do not bound tau above) is
        bounded (``"prior"``, said in the statement and the warnings) or not.

    Raises
    ------
    OptionError
        A value of the wrong type or outside its range (fractions in
        [0, 1], the band ratio at least 1, the tau multiple > 0).
    """

    min_tau_multiple: float = option(50.0, Number(lo=0.0, hi=1e6, lo_open=True))
    max_filter_loss: float = option(0.5, Number(lo=0.0, hi=1.0))
    min_band_ratio: float = option(4.0, Number(lo=1.0, hi=1e6))
    max_excluded_fraction: float = option(0.5, Number(lo=0.0, hi=1.0))
    max_never_stationary_fraction: float = option(0.2, Number(lo=0.0, hi=1.0))
    low_frequency: str = option("prior", Choice(POLICIES, noun="low-frequency policy"))

    def __post_init__(self) -> None:
        check_fields(self)


def _covered_s(per_window: list[dict[str, Any]], interval_s: float) -> float:
    """Time covered by the union of the windows, s."""
    spans = sorted((w["arc"], w["t_start_gps_s"], w["t_stop_gps_s"]) for w in per_window)
    total, cur = 0.0, None
    for arc, t0, t1 in spans:
        t1 = t1 + interval_s
        if cur is None or arc != cur[0] or t0 > cur[2]:
            if cur is not None:
                total += cur[2] - cur[1]
            cur = [arc, t0, t1]
        else:
            cur[2] = max(cur[2], t1)
    if cur is not None:
        total += cur[2] - cur[1]
    return total


def degenerate_reasons(bound: dict[str, Any]) -> list[str]:
    """Apply the "degenerate bound" rule: ``sigma_GM = 0``, or tau at an end of its grid.

    Parameters
    ----------
    bound : dict
        ``sigma_gm_m`` (m), ``tau_s`` (s) and optionally ``tau_grid_s`` (s).

    Returns
    -------
    list of str
        One sentence per degeneracy found (empty when none).
    """
    reasons = []
    grid = bound.get("tau_grid_s") or [bound["tau_s"]]
    if bound["sigma_gm_m"] <= 0.0:
        reasons.append(
            "degenerate bound: sigma_GM = 0, only white noise; no time correlation is "
            "resolved in the band fitted"
        )
    if bound["tau_s"] <= min(grid) * (1 + 1e-6) or bound["tau_s"] >= max(grid) * (1 - 1e-6):
        reasons.append(
            f"degenerate bound: tau = {bound['tau_s']:.3g} s sits at the end of its search grid "
            f"[{min(grid):.3g}, {max(grid):.3g}] s"
        )
    return reasons


def short_data_reasons(bound: dict[str, Any], covered_s: float,
                       options: VerdictOptions | None = None) -> list[str]:  # fmt: skip
    """Apply the "too little data for tau" rule: windows shorter than ``min_tau_multiple`` tau.

    Parameters
    ----------
    bound : dict
        ``sigma_gm_m`` (m) and ``tau_s`` (s).
    covered_s : float
        Time covered by the stationary windows the bound was fitted to, s.
    options : VerdictOptions, optional

    Returns
    -------
    list of str
        The rule's sentence, or empty.
    """
    opt = options or VerdictOptions()
    need_s = opt.min_tau_multiple * bound["tau_s"]
    if bound["sigma_gm_m"] <= 0 or covered_s >= need_s:
        return []
    return [
        f"too little stationary data: {covered_s / 60:.1f} min covered by windows < "
        f"{opt.min_tau_multiple:g} tau = {need_s / 60:.1f} min "
        "(variance uncertainty above 20 %)"
    ]


def judge(document: dict[str, Any], options: VerdictOptions | None = None) -> tuple[str, list[str]]:
    """Apply the verdict rules to a result document.

    Parameters
    ----------
    document : dict
        The result document (bound, windows, sampling, cutoff, isolation,
        screening sections).
    options : VerdictOptions, optional

    Returns
    -------
    verdict : {"bounded", "not-bounded"}
    reasons : list of str
        One sentence per rule that fired (empty when bounded).
    """
    opt = options or VerdictOptions()
    b, s = document["bound"], document["sampling"]
    covered = _covered_s(document["windows"]["per_window"], s["interval_s"])
    reasons = degenerate_reasons(b) + short_data_reasons(b, covered, opt)
    safety = document.get("isolation", {}).get("safety")
    if safety and safety.get("removed_above_fc_median") is not None:
        loss = safety["removed_above_fc_median"]
        if loss > opt.max_filter_loss:
            reasons.append(
                f"filter loss: the high-pass removed a median {100 * loss:.1f} % of the power "
                f"above f_c (limit {100 * opt.max_filter_loss:g} %); arcs are too short for "
                "the cutoff"
            )
    f_c = document["cutoff"].get("f_c_hz")
    if f_c and s["nyquist_hz"] / f_c < opt.min_band_ratio:
        reasons.append(
            f"band: cutoff {f_c:.3g} Hz leaves only a factor {s['nyquist_hz'] / f_c:.2f} below "
            f"the Nyquist frequency {s['nyquist_hz']:.3g} Hz (need {opt.min_band_ratio:g})"
        )
    w = document["windows"]
    rejected = w.get("rejected_s")
    if rejected is not None and w["data_s"] > 0:
        frac = rejected / w["data_s"]
        if frac > opt.max_never_stationary_fraction:
            reasons.append(
                f"data outside the bound: {100 * frac:.1f} % of the screened data "
                f"({rejected / 3600:.2f} h) failed every stationarity test (limit "
                f"{100 * opt.max_never_stationary_fraction:g} %)"
            )
    reasons += low_frequency_reasons(b.get("low_frequency"), opt.low_frequency)
    scr = document.get("screening")
    if scr and scr.get("excluded_fraction", 0.0) > opt.max_excluded_fraction:
        reasons.append(
            f"most data excluded: screening removed {100 * scr['excluded_fraction']:.1f} % of "
            f"the data (limit {100 * opt.max_excluded_fraction:g} %)"
        )
    return ("not-bounded" if reasons else "bounded"), reasons


def judge_pooled(bound: dict[str, Any] | None, *, covered_s: float, n_days: int,
                 options: VerdictOptions | None = None) -> tuple[str, list[str]]:  # fmt: skip
    """Apply the verdict rules that make sense for a campaign station's pooled bound.

    The pool holds only the station's bounded days (each judged by
    :func:`judge`), so the rules on one day's data (filter loss, band, data
    outside the bound, most data excluded) have already kept the bad days
    out. On the pooled bound itself apply: **no bounded day left**,
    **degenerate bound** (:func:`degenerate_reasons`), **too little data for
    tau** over the pooled windows (:func:`short_data_reasons`) and **low
    frequencies** (:func:`psdbound.spectra.lowfreq.low_frequency_reasons`
    with the same policy).

    Parameters
    ----------
    bound : dict or None
        ``sigma_gm_m`` (m), ``tau_s`` (s), ``tau_grid_s`` (s) and
        ``low_frequency`` of the pooled bound; None when nothing was pooled.
    covered_s : float
        Time covered by the pooled days' stationary windows, s.
    n_days : int
        Bounded days in the pool.
    options : VerdictOptions, optional

    Returns
    -------
    verdict : {"bounded", "not-bounded"}
    reasons : list of str
        One sentence per rule that fired (empty when bounded).
    """
    opt = options or VerdictOptions()
    if bound is None or n_days == 0:
        return "not-bounded", [
            "no bounded day left: every day of the station is not-bounded or failed, so there "
            "is nothing to pool"
        ]
    reasons = degenerate_reasons(bound) + short_data_reasons(bound, covered_s, opt)
    reasons += low_frequency_reasons(bound.get("low_frequency"), opt.low_frequency)
    return ("not-bounded" if reasons else "bounded"), reasons
