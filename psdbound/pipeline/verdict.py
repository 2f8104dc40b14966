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
data used
    Less than ``min_used_fraction`` (default 50 %) of the data the file
    offered (samples with both phases above the elevation mask, counted with
    or without an orbit position) lies in the bound's windows: every loss
    counted together (no orbit, short stretches and slips, the filter's edge
    trims, screening, stationarity). Each stage's own rule can pass while
    together they leave a bound fitted to a small, selected part of the
    day (a navigation file covering 17 % of it was "bounded" before this
    rule). Dual-frequency series only (the dual-antenna chain does not
    count its input yet).
physical limit
    The bound's standard deviation at zenith, ``sqrt(sigma_GM^2 +
    sigma_WN^2)``, exceeds the largest value carrier multipath can take in
    the isolated series (``screening.multipath_limit_m``: the scaled sum of
    the quarter wavelengths of its phase terms, 7.70 cm for GPS L1/L2 DF).
    (Mapped to the data's lowest elevation the bound may exceed it while the
    data do not: the samples were screened against the limit one by one;
    that is a conservative, loose error model there, which a warning states:
    :func:`physical_note`.)
    A variable bounded by ``L`` has a standard deviation of at most ``L``:
    a larger bound describes something that is not multipath (residual
    ionosphere, slips, a wrong baseline), and a protection level built on
    it would be both loose and meaningless. (A real 1.6 m pair with a
    forced baseline gave 19.7 cm "bounded" before this rule.)

Every rule is a :class:`VerdictCheck` (:func:`verdict_checks`) with the
measured value and its limit, so every output shows the same lines
(``verdict_checks`` of result.json; :mod:`psdbound.results.headline`).

Pooled bounds (campaigns)
-------------------------
A campaign judges every station-day with :func:`judge` (the day's ``fit``)
and pools only the bounded days. The pooled bound of a station is judged by
:func:`judge_pooled`: not bounded when no bounded day is left, when it is
degenerate, when the pooled windows cover less than ``min_tau_multiple``
tau, or by the low-frequency rule. The other rules concern one day's data
and have already kept those days out of the pool.
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
    model the main shape group's pooled spectrum admits (``bound.low_frequency``,
    :mod:`psdbound.spectra.lowfreq`). Where the data do not bound the time
    constant above, that statement rests on the prior ``tau <= tau_max_s``:
    with ``low_frequency = "refuse"`` (default ``"prior"``) such a bound is
    not bounded; when the data admit only time constants above the prior,
    it is never bounded.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from psdbound.common.options import Choice, Number, check_fields, option
from psdbound.results.headline import check_line
from psdbound.spectra.names import POLICIES
from psdbound.stationarity.coverage import covered_time_s

if TYPE_CHECKING:  # the products, for type checkers: this module stays light to import
    from psdbound.ionosphere.policy import CutoffChoice
    from psdbound.pipeline.products import Isolated, Screened, Windowed
    from psdbound.spectra import BoundResults

__all__ = [
    "VerdictCheck",
    "VerdictFacts",
    "VerdictOptions",
    "judge",
    "judge_pooled",
    "physical_note",
    "pooled_checks",
    "verdict_checks",
    "verdict_facts",
    "verdict_of",
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
    min_used_fraction : float, default 0.5
        Smallest fraction of the data offered (both phases above the
        elevation mask, with or without an orbit) that must lie in the
        bound's windows, all losses counted together.
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
    min_used_fraction: float = option(0.5, Number(lo=0.0, hi=1.0))
    low_frequency: str = option("prior", Choice(POLICIES, noun="low-frequency policy"))

    def __post_init__(self) -> None:
        check_fields(self)


@dataclass(frozen=True)
class VerdictFacts:
    """What the verdict rules measure, taken from the typed stage products.

    Built by :func:`verdict_facts` from a fit's products, by
    :meth:`from_document` from a result document (a loaded ``result.json``),
    or directly (a campaign's pooled bound: only the bound and its coverage).
    None: the quantity does not apply (no filter, no screening, ...), and the
    rule that needs it is not applied.

    Attributes
    ----------
    sigma_gm_m, tau_s, sigma_wn_m : float
        The bound (m, s, m).
    tau_grid_s : tuple of float
        The time constants searched, s (empty: only ``tau_s``).
    covered_s : float
        Time covered by the bound's windows, s.
    low_frequency : dict or None
        The bound's low-frequency section (:mod:`psdbound.spectra.lowfreq`).
    filter_loss : float or None
        Median fraction of the power above f_c that the high-pass removed.
    f_c_hz, nyquist_hz : float or None
        The cutoff and the Nyquist frequency, Hz.
    rejected_s, data_s : float or None
        Screened data that failed every stationarity test, and all screened data, s.
    excluded_fraction : float or None
        Fraction of the data the screening excluded.
    offered_s : float or None
        Data the file offered above the elevation mask, s.
    multipath_limit_m : float or None
        The largest standard deviation carrier multipath can reach, m.
    lowest_elevation_deg, mapping_factor_lowest : float or None
        The lowest elevation of the mapped data, deg, and the mapping factor
        ``m(el)`` there: the bound's standard deviation at that elevation is
        this factor times its zenith value (None: no elevations).
    """

    sigma_gm_m: float
    tau_s: float
    sigma_wn_m: float = 0.0
    tau_grid_s: tuple[float, ...] = ()
    covered_s: float = 0.0
    low_frequency: dict[str, Any] | None = None
    filter_loss: float | None = None
    f_c_hz: float | None = None
    nyquist_hz: float | None = None
    rejected_s: float | None = None
    data_s: float | None = None
    excluded_fraction: float | None = None
    offered_s: float | None = None
    multipath_limit_m: float | None = None
    lowest_elevation_deg: float | None = None
    mapping_factor_lowest: float | None = None

    @classmethod
    def from_document(cls, d: dict[str, Any]) -> VerdictFacts:
        """Return the facts of a result document (its bound, windows, screening sections)."""
        b, w, s = d["bound"], d["windows"], d["sampling"]
        iso, scr = d.get("isolation") or {}, d.get("screening") or {}
        spans = [(x["arc"], x["t_start_gps_s"], x["t_stop_gps_s"]) for x in w["per_window"]]
        covered = d.get("covered_s")
        return cls(
            sigma_gm_m=b["sigma_gm_m"],
            tau_s=b["tau_s"],
            sigma_wn_m=b["sigma_wn_m"],
            tau_grid_s=tuple(b.get("tau_grid_s") or ()),
            covered_s=float(covered)
            if covered is not None
            else covered_time_s(spans, s["interval_s"]),
            low_frequency=b.get("low_frequency"),
            filter_loss=(iso.get("safety") or {}).get("removed_above_fc_median"),
            f_c_hz=d["cutoff"].get("f_c_hz"),
            nyquist_hz=s["nyquist_hz"],
            rejected_s=w.get("rejected_s"),
            data_s=w.get("data_s"),
            excluded_fraction=scr.get("excluded_fraction"),
            offered_s=(iso.get("offered") or {}).get("offered_s"),
            multipath_limit_m=scr.get("multipath_limit_m"),
            lowest_elevation_deg=(d.get("mapping") or {}).get("lowest_elevation_deg"),
            mapping_factor_lowest=(d.get("mapping") or {}).get("factor_at_lowest"),
        )


def verdict_facts(
    *,
    bounded: BoundResults,
    windowed: Windowed,
    screened: Screened,
    isolated: Isolated,
    cutoff: CutoffChoice | None,
    interval_s: float,
) -> VerdictFacts:
    """Return the verdict's facts from a fit's stage products.

    Parameters
    ----------
    bounded, windowed, screened, isolated : stage products
        Of :mod:`psdbound.pipeline.stages`.
    cutoff : CutoffChoice or None
        The cutoff (None: dual-antenna).
    interval_s : float
        Sampling interval, s.

    Returns
    -------
    VerdictFacts
    """
    from psdbound.results.jsonfile import to_jsonable

    b, w, sc = bounded.bound, windowed.windows, screened.screening
    details = isolated.details or {}
    low = bounded.low_frequency
    lowest = _lowest_elevation(windowed, screened)
    return VerdictFacts(
        sigma_gm_m=b.sigma_gm_m,
        tau_s=b.tau_s,
        sigma_wn_m=b.sigma_wn_m,
        tau_grid_s=tuple(float(t) for t in b.tau_grid_s),
        covered_s=w.covered_s,
        low_frequency=None if low is None else to_jsonable(low.to_dict()),
        filter_loss=(details.get("safety") or {}).get("removed_above_fc_median"),
        f_c_hz=None if cutoff is None else cutoff.f_c_hz,
        nyquist_hz=0.5 / interval_s,
        rejected_s=w.rejected_s,
        data_s=screened.series.data_s,
        excluded_fraction=sc.excluded_fraction,
        offered_s=(details.get("offered") or {}).get("offered_s"),
        multipath_limit_m=sc.limit_m,
        lowest_elevation_deg=None if lowest is None else lowest[0],
        mapping_factor_lowest=None if lowest is None else lowest[1],
    )


def _lowest_elevation(windowed: Windowed, screened: Screened) -> tuple[float, float] | None:
    """Return the lowest elevation of the mapped data and the mapping factor there.

    The bound is a zenith-scale model: at elevation ``el`` it states a
    standard deviation ``m(el)`` times its own, largest at the lowest
    elevation of the data it was fitted to.

    Parameters
    ----------
    windowed, screened : stage products
        Of :mod:`psdbound.pipeline.stages`.

    Returns
    -------
    (float, float) or None
        Elevation, deg, and ``m(el)`` there (dimensionless); None without
        elevations.
    """
    import numpy as np

    el = np.asarray(screened.series.elevation_deg, dtype=float)
    x = np.asarray(windowed.windows.mapped_m, dtype=float)
    ok = np.isfinite(el) & np.isfinite(x) if x.shape == el.shape else np.isfinite(el)
    if not ok.any():
        return None
    low = float(np.min(el[ok]))
    return low, float(windowed.mapping.factor(low))


@dataclass(frozen=True)
class VerdictCheck:
    """One verdict rule applied to one result: what it measured against what it allows.

    Attributes
    ----------
    rule : str
        Short name (``"physical limit"``).
    passed : bool
        Whether the rule holds.
    measured : str
        The measured value, with its unit.
    limit : str
        What the rule allows (``"<= 7.70 cm"``).
    reason : str
        Why the bound is refused (empty when ``passed``).
    """

    rule: str
    passed: bool
    measured: str
    limit: str
    reason: str = ""

    def line(self) -> str:
        """Return ``rule: measured (limit) pass|FAIL``, the line every output prints."""
        return check_line(self.to_dict())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (an entry of ``verdict_checks`` in result.json)."""
        return {
            "rule": self.rule,
            "passed": self.passed,
            "measured": self.measured,
            "limit": self.limit,
            "reason": self.reason,
        }


def _check(rule: str, passed: bool, measured: str, limit: str, reason: str) -> VerdictCheck:
    return VerdictCheck(rule, bool(passed), measured, limit, "" if passed else reason)


def _degenerate(f: VerdictFacts, opt: VerdictOptions) -> list[VerdictCheck]:
    grid = f.tau_grid_s or (f.tau_s,)
    lo, hi = min(grid), max(grid)
    inside = lo * (1 + 1e-6) < f.tau_s < hi * (1 - 1e-6)
    return [
        _check(
            "time correlation",
            f.sigma_gm_m > 0.0,
            f"sigma_GM {100 * f.sigma_gm_m:.3f} cm",
            "> 0",
            "degenerate bound: sigma_GM = 0, only white noise; no time correlation is "
            "resolved in the band fitted",
        ),
        _check(
            "tau inside its search",
            inside,
            f"tau {f.tau_s:.3g} s",
            f"inside [{lo:.3g}, {hi:.3g}] s",
            f"degenerate bound: tau = {f.tau_s:.3g} s "
            f"sits at the end of its search grid [{lo:.3g}, {hi:.3g}] s",
        ),
    ]


def _data_for_tau(f: VerdictFacts, opt: VerdictOptions) -> list[VerdictCheck]:
    covered = f.covered_s
    need = opt.min_tau_multiple * f.tau_s
    ok = f.sigma_gm_m <= 0 or covered >= need
    return [
        _check(
            "data for tau",
            ok,
            f"{covered / 3600:.2f} h in windows",
            f">= {opt.min_tau_multiple:g} tau = {need / 3600:.2f} h",
            f"too little stationary data: {covered / 60:.1f} min covered by windows < "
            f"{opt.min_tau_multiple:g} tau = {need / 60:.1f} min (variance uncertainty "
            "above 20 %)",
        )
    ]


def _filter(f: VerdictFacts, opt: VerdictOptions) -> list[VerdictCheck]:
    out = []
    if f.filter_loss is not None:
        loss = f.filter_loss
        out.append(
            _check(
                "filter loss",
                loss <= opt.max_filter_loss,
                f"{100 * loss:.1f} %",
                f"<= {100 * opt.max_filter_loss:g} %",
                f"filter loss: the high-pass removed a median {100 * loss:.1f} % of "
                f"the power above f_c (limit {100 * opt.max_filter_loss:g} %); arcs "
                "are too short for the cutoff",
            )
        )
    if f.f_c_hz and f.nyquist_hz is not None:
        ratio = f.nyquist_hz / f.f_c_hz
        out.append(
            _check(
                "band",
                ratio >= opt.min_band_ratio,
                f"Nyquist / f_c {ratio:.3g}",
                f">= {opt.min_band_ratio:g}",
                f"band: cutoff {f.f_c_hz:.3g} Hz leaves only a factor {ratio:.2f} "
                f"below the Nyquist frequency {f.nyquist_hz:.3g} Hz (need "
                f"{opt.min_band_ratio:g})",
            )
        )
    return out


def _data_use(f: VerdictFacts, opt: VerdictOptions) -> list[VerdictCheck]:
    out = []
    if f.rejected_s is not None and f.data_s:
        frac = f.rejected_s / f.data_s
        lim = opt.max_never_stationary_fraction
        out.append(
            _check(
                "data outside the bound",
                frac <= lim,
                f"{100 * frac:.1f} %",
                f"<= {100 * lim:g} %",
                f"data outside the bound: {100 * frac:.1f} % of the screened data "
                f"({f.rejected_s / 3600:.2f} h) failed every stationarity test "
                f"(limit {100 * lim:g} %)",
            )
        )
    if f.excluded_fraction is not None:
        frac, lim = f.excluded_fraction, opt.max_excluded_fraction
        out.append(
            _check(
                "data excluded",
                frac <= lim,
                f"{100 * frac:.1f} %",
                f"<= {100 * lim:g} %",
                f"most data excluded: screening removed {100 * frac:.1f} % of the "
                f"data (limit {100 * lim:g} %)",
            )
        )
    return out


def _data_used(f: VerdictFacts, opt: VerdictOptions) -> list[VerdictCheck]:
    offered = f.offered_s
    if not offered:
        return []
    used = f.covered_s / offered
    lim = opt.min_used_fraction
    return [
        _check(
            "data used",
            used >= lim,
            f"{100 * used:.1f} % of {offered / 3600:.1f} h",
            f">= {100 * lim:g} %",
            f"data used: only {100 * used:.1f} % of the {offered / 3600:.1f} h of data the "
            f"file offered above the elevation mask lie in the bound's windows (limit "
            f"{100 * lim:g} %; every loss counted: no orbit, short arcs, filter edges, "
            "screening, stationarity)",
        )
    ]


def _low_frequency(f: VerdictFacts, opt: VerdictOptions) -> list[VerdictCheck]:
    from psdbound.spectra.lowfreq import low_frequency_reasons  # deferred: the stage is heavy

    reasons = low_frequency_reasons(f.low_frequency, opt.low_frequency)
    status = (f.low_frequency or {}).get("status", "unchecked")
    return [
        VerdictCheck(
            "low frequencies",
            not reasons,
            f"status {status}",
            f"policy {opt.low_frequency}",
            "; ".join(reasons),
        )
    ]


def _physical(f: VerdictFacts, opt: VerdictOptions) -> list[VerdictCheck]:
    lim = f.multipath_limit_m
    if not lim:
        return []
    sigma = math.hypot(f.sigma_gm_m, f.sigma_wn_m)
    measured = f"sigma {100 * sigma:.2f} cm at zenith"
    low = _mapped_at_lowest(f)
    if low is not None:
        measured += f" ({100 * low[1]:.2f} cm mapped to {low[0]:.1f} deg)"
    return [
        _check(
            "physical limit",
            sigma <= lim,
            measured,
            f"<= {100 * lim:.2f} cm carrier-multipath limit",
            f"physical limit: the bound's standard deviation {100 * sigma:.2f} cm exceeds "
            f"the {100 * lim:.2f} cm that carrier multipath of this series can reach at "
            "all (a quarter wavelength per carrier): what it bounds is not multipath "
            "(residual ionosphere, cycle slips, a wrong baseline)",
        )
    ]


def _mapped_at_lowest(f: VerdictFacts) -> tuple[float, float] | None:
    """Return the data's lowest elevation, deg, and the bound's sigma mapped there, m.

    Parameters
    ----------
    f : VerdictFacts

    Returns
    -------
    (float, float) or None
        None without elevations.
    """
    if f.mapping_factor_lowest is None or f.lowest_elevation_deg is None:
        return None
    sigma = math.hypot(f.sigma_gm_m, f.sigma_wn_m) * max(f.mapping_factor_lowest, 1.0)
    return f.lowest_elevation_deg, sigma


def physical_note(f: VerdictFacts) -> str | None:
    """Say when the bound, mapped to the data's lowest elevation, exceeds the physical limit.

    The rule is on the zenith value: the data were screened sample by sample
    against the limit, and a bound above it at zenith bounds something that is
    not multipath. Mapped to low elevations, a bound within the limit at zenith
    can still state more than carrier multipath can reach there: conservative
    (the truth lies below both), but a looser error model than physics needs.

    Parameters
    ----------
    f : VerdictFacts

    Returns
    -------
    str or None
    """
    low = _mapped_at_lowest(f)
    lim = f.multipath_limit_m
    if low is None or not lim or low[1] <= lim:
        return None
    return (
        f"mapped to the data's lowest elevation ({low[0]:.1f} deg, m(el) "
        f"{f.mapping_factor_lowest:.2f}) the bound's standard deviation is "
        f"{100 * low[1]:.2f} cm, above the {100 * lim:.2f} cm carrier multipath can reach: "
        "conservative there (the truth lies below the limit), a looser error model than "
        "physics needs at low elevations"
    )


#: The rules in the order every output lists them.
RULES: tuple[Callable[[VerdictFacts, VerdictOptions], list[VerdictCheck]], ...] = (
    _degenerate,
    _data_for_tau,
    _filter,
    _data_use,
    _data_used,
    _low_frequency,
    _physical,
)


def verdict_checks(
    facts: VerdictFacts | dict[str, Any], options: VerdictOptions | None = None
) -> list[VerdictCheck]:
    """Apply every verdict rule to a fit's facts.

    Parameters
    ----------
    facts : VerdictFacts or dict
        The facts (:func:`verdict_facts` of the stage products), or a result
        document (read through :meth:`VerdictFacts.from_document`).
    options : VerdictOptions, optional

    Returns
    -------
    list of VerdictCheck
        One per rule that applies, in :data:`RULES` order.
    """
    opt = options or VerdictOptions()
    f = facts if isinstance(facts, VerdictFacts) else VerdictFacts.from_document(facts)
    return [c for rule in RULES for c in rule(f, opt)]


def verdict_of(checks: list[VerdictCheck]) -> tuple[str, list[str]]:
    """Return the verdict the checks give and the reason of each that failed.

    Parameters
    ----------
    checks : list of VerdictCheck

    Returns
    -------
    verdict : {"bounded", "not-bounded"}
        ``"bounded"`` only when every check passed.
    reasons : list of str
    """
    reasons = [c.reason for c in checks if not c.passed]
    return ("not-bounded" if reasons else "bounded"), reasons


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
    return verdict_of(verdict_checks(document, options))


def pooled_checks(
    bound: dict[str, Any] | None,
    *,
    covered_s: float,
    n_days: int,
    options: VerdictOptions | None = None,
) -> list[VerdictCheck]:
    """Apply the verdict rules that make sense for a campaign station's pooled bound.

    The pool holds only the station's bounded days (each judged by
    :func:`judge`), so the rules on one day's data (filter loss, band, data
    outside the bound, data excluded, data used) have already kept the bad
    days out. On the pooled bound itself apply: **bounded days** (at least
    one), the **degenerate bound** rules, **data for tau** over the pooled
    windows and **low frequencies** with the same policy.

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
    list of VerdictCheck
    """
    opt = options or VerdictOptions()
    days = _check(
        "bounded days",
        bool(n_days and bound is not None),
        f"{n_days} day(s)",
        ">= 1",
        "no bounded day left: every day of the station is not-bounded or failed, so "
        "there is nothing to pool",
    )
    if not days.passed:
        return [days]
    f = VerdictFacts(
        sigma_gm_m=bound["sigma_gm_m"],
        tau_s=bound["tau_s"],
        tau_grid_s=tuple(bound.get("tau_grid_s") or ()),
        covered_s=covered_s,
        low_frequency=bound.get("low_frequency"),
    )
    return [days, *_degenerate(f, opt), *_data_for_tau(f, opt), *_low_frequency(f, opt)]


def judge_pooled(
    bound: dict[str, Any] | None,
    *,
    covered_s: float,
    n_days: int,
    options: VerdictOptions | None = None,
) -> tuple[str, list[str]]:
    """Return the verdict of a campaign station's pooled bound (:func:`pooled_checks`).

    Parameters
    ----------
    bound : dict or None
        The pooled bound (see :func:`pooled_checks`); None when nothing was pooled.
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
    return verdict_of(pooled_checks(bound, covered_s=covered_s, n_days=n_days, options=options))
