"""The tightest Gauss-Markov + white-noise PSD bound (docs/method/bound.rst).

Model (one-sided, per hertz, sampled at ``dt`` -- see
:mod:`psdbound.spectra.models`)::

    S_model(f) = sigma_gm^2 g_tau(f) + sigma_wn^2 * 2 dt,
    g_tau(f)   = 2 dt (1 - phi^2) / (1 - 2 phi cos(2 pi f dt) + phi^2),  phi = exp(-dt/tau)

For a fixed ``tau`` the constraints ``S_model(f) >= S_data(f)`` (every PSD,
every frequency) are linear in ``(sigma_gm^2, sigma_wn^2)``, so the best
bound for that ``tau`` is a linear program (scipy HiGHS). The tightness
objective is stated and linear:

``"variance"`` (default)
    total variance of the bound process, ``sigma_gm^2 + sigma_wn^2``
    (equal to the integral of ``S_model`` over ``[0, f_N]``);
``"area"``
    integral of ``S_model`` over the data band ``[f_min, f_N]``.

An outer 1-D search over ``tau`` (a log-spaced grid, then a bounded Brent
refinement around the best grid point) gives the optimum. Because
``g_tau`` decreases with ``f``, a data point is implied by any point at a
higher or equal frequency with a higher or equal PSD; only the remaining
"staircase" points enter the LPs. The result is then checked against every
data point and scaled up by the solver's residual, so the bound holds
exactly (minimum margin >= 1).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import linprog, minimize_scalar

from psdbound.errors import InputError
from psdbound.spectra.models import GaussMarkovWhiteNoise, gm_psd_sampled
from psdbound.spectra.names import OBJECTIVES, RULES

#: Further linear constraints of a time constant: ``tau -> (a, b)``, ``a @ variances >= b``.
ExtraRows = Callable[[float], tuple[NDArray[np.float64], NDArray[np.float64]]]

__all__ = ["BoundFit", "ExtraRows", "Floor", "fit_bound", "join_floors", "OBJECTIVES", "RULES"]


#: Points (Hz, m^2/Hz) a bound must lie above that are not data: the envelopes of
#: the low-frequency rules and the cells a refit keeps (:func:`fit_bound`, ``floor``).
Floor = tuple[NDArray[np.float64], NDArray[np.float64]]


def join_floors(*floors: Floor | None) -> Floor | None:
    """Return the points of several floors as one (None when there are none)."""
    have = [f for f in floors if f is not None]
    if not have:
        return None
    return np.concatenate([f for f, _ in have]), np.concatenate([s for _, s in have])


class _PSDLike(Protocol):
    f_hz: NDArray[np.float64]
    psd_m2_hz: NDArray[np.float64]


@dataclass(frozen=True)
class BoundFit:
    """A fitted GMRP + white-noise PSD bound (statsmodels-style results).

    The four model numbers live in :attr:`model`; ``sigma_gm_m``, ``tau_s``,
    ``sigma_wn_m``, ``dt_s`` and the derived quantities are read-only views of it.

    Attributes
    ----------
    model : GaussMarkovWhiteNoise
        The bound: ``sigma_gm_m`` (Gauss-Markov standard deviation, metres),
        ``tau_s`` (time constant, seconds), ``sigma_wn_m`` (white-noise
        standard deviation per sample, metres) and ``dt_s`` (sampling
        interval the bound is stated for, seconds).
    objective : str
        Tightness objective minimised.
    objective_value : float
        Its value at the optimum (m^2).
    target : str
        ``"point"`` (PSD estimates bounded), ``"upper"`` (their upper
        confidence limits at ``level``) or ``"pooled"`` (pooled limits of
        :mod:`psdbound.spectra.pooled` at the family-wise ``level``).
    level : float or None
        Confidence level of the upper limits, when used.
    margins : ndarray
        Per PSD bounded (per window, or per group of windows for the pooled
        rule), the minimum over frequency of ``S_model / S_data`` (>= 1).
    tau_grid_s, objective_grid : ndarray
        The outer search: ``tau`` values tried and the LP optimum at each.
    n_constraints : int
        Staircase points that entered the LPs (of ``n_points`` in total).
    n_points : int
        All (frequency, PSD) data points bounded.
    f_min_hz, f_max_hz : float
        Frequency band of the data.
    gap_db_median, gap_db_p05 : float
        Tightness: median and 5th percentile over all data points of
        ``10 log10(S_model / S_data)`` (0 dB = touching).
    """

    model: GaussMarkovWhiteNoise
    objective: str
    objective_value: float
    target: str
    level: float | None
    margins: NDArray[np.float64]
    tau_grid_s: NDArray[np.float64]
    objective_grid: NDArray[np.float64]
    n_constraints: int
    n_points: int
    f_min_hz: float
    f_max_hz: float
    gap_db_median: float = float("nan")
    gap_db_p05: float = float("nan")
    meta: dict[str, Any] = field(default_factory=dict)

    @property
    def sigma_gm_m(self) -> float:
        """Gauss-Markov standard deviation, metres."""
        return self.model.sigma_gm_m

    @property
    def tau_s(self) -> float:
        """Gauss-Markov time constant, seconds."""
        return self.model.tau_s

    @property
    def sigma_wn_m(self) -> float:
        """White-noise standard deviation per sample, metres."""
        return self.model.sigma_wn_m

    @property
    def dt_s(self) -> float:
        """Sampling interval the bound is stated for, seconds."""
        return self.model.dt_s

    @property
    def nyquist_hz(self) -> float:
        """Nyquist frequency of the sampling, Hz."""
        return self.model.nyquist_hz

    @property
    def total_variance_m2(self) -> float:
        """Variance of the bound process, ``sigma_gm^2 + sigma_wn^2``, m^2."""
        return self.model.total_variance_m2

    @property
    def n_wn_two_sided_m2_hz(self) -> float:
        """Thesis's white-noise level ``N_WN`` (two-sided), ``sigma_wn^2 dt``, m^2/Hz."""
        return self.model.n_wn_two_sided_m2_hz

    def psd(self, f_hz: NDArray[np.float64]) -> NDArray[np.float64]:
        """One-sided sampled bound PSD at ``f_hz``, m^2/Hz.

        ``gm_psd_sampled(f, sigma_gm, tau, dt) + 2 sigma_wn^2 dt`` at the data
        interval ``dt = dt_s``.
        """
        m = self.model
        f = np.asarray(f_hz, dtype=float)
        return gm_psd_sampled(f, m.sigma_gm_m, m.tau_s, m.dt_s) + 2.0 * m.n_wn_two_sided_m2_hz

    def params(self) -> dict[str, float]:
        """Parameters with units in their names."""
        return self.model.params()

    def summary(self) -> str:
        """Return a statsmodels-like text table of the bound."""
        m = self.margins
        rows = [
            "=" * 66,
            "GMRP + white-noise PSD bound (one-sided, sampled)".center(66),
            "=" * 66,
            f"{'sigma_GM':<28}{100 * self.sigma_gm_m:>12.3f} cm",
            f"{'tau_GM':<28}{self.tau_s:>12.1f} s",
            f"{'sigma_WN (per sample)':<28}{100 * self.sigma_wn_m:>12.3f} cm",
            f"{'N_WN (two-sided)':<28}{self.n_wn_two_sided_m2_hz:>12.4g} m^2/Hz",
            f"{'sampling interval':<28}{self.dt_s:>12.4g} s   (Nyquist {self.nyquist_hz:.4g} Hz)",
            "-" * 66,
            f"{'objective':<28}{self.objective:>12s}  = {self.objective_value:.4g} m^2",
            f"{'target':<28}{self.target:>12s}"
            + (f"  (level {self.level:g})" if self.level else ""),
            f"{'PSDs bounded':<28}{m.size:>12d}   ({self.n_points} points, "
            f"{self.n_constraints} active candidates)",
            f"{'band':<28}{self.f_min_hz:>12.4g} - {self.f_max_hz:.4g} Hz",
            f"{'min margin (bound/data)':<28}{m.min() if m.size else np.nan:>12.4f}",
            f"{'median of per-PSD margins':<28}{np.median(m) if m.size else np.nan:>12.4f}",
            f"{'gap bound/data (dB)':<28}{self.gap_db_median:>12.2f}   median "
            f"(5th percentile {self.gap_db_p05:.2f})",
            "=" * 66,
        ]
        return "\n".join(rows)


def _as_arrays(
    psds: Sequence[_PSDLike], target: str, level: float
) -> list[tuple[NDArray[np.float64], NDArray[np.float64]]]:
    out = []
    for k, p in enumerate(psds):
        f = np.asarray(p.f_hz, dtype=float)
        if target == "upper":
            if not hasattr(p, "confidence_interval"):
                raise InputError(f"PSD {k} has no confidence interval; use target='point'")
            s = np.asarray(p.confidence_interval(level)[1], dtype=float)
        else:
            s = np.asarray(p.psd_m2_hz, dtype=float)
        if f.shape != s.shape or not np.isfinite(s).all() or not np.isfinite(f).all():
            raise InputError(f"PSD {k}: frequencies and values must be finite arrays of equal size")
        keep = (f > 0) & (s > 0)
        out.append((f[keep], s[keep]))
    return out


def _staircase(f: NDArray[np.float64], s: NDArray[np.float64]):
    """Points not implied by another with higher-or-equal f and PSD."""
    order = np.lexsort((-s, -f))  # by f descending, then s descending
    fs, ss = f[order], s[order]
    runmax = np.maximum.accumulate(ss)
    keep = np.r_[True, ss[1:] > runmax[:-1]]
    return fs[keep], ss[keep]


def fit_bound(
    psds: Sequence[_PSDLike],
    dt_s: float,
    *,
    objective: str = "variance",
    target: str = "point",
    level: float = 0.95,
    tau_range_s: tuple[float, float] | None = None,
    n_grid: int = 64,
    floor: Floor | None = None,
    extra: ExtraRows | None = None,
) -> BoundFit:
    """Fit the tightest GMRP + white-noise bound over a set of PSD estimates.

    Parameters
    ----------
    psds : sequence of PSD estimates
        Objects with ``f_hz`` and ``psd_m2_hz`` (one-sided, m^2/Hz), e.g.
        :class:`psdbound.spectra.PSDEstimate`; with ``target="upper"`` they
        also need ``confidence_interval(level)``.
    dt_s : float
        Sampling interval of the data, seconds (the model is aliased to it).
    objective : {"variance", "area"}, default "variance"
        Tightness objective (see the module docstring).
    target : {"point", "upper"}, default "point"
        Bound the point estimates, or their upper confidence limits.
    level : float, default 0.95
        Confidence level for ``target="upper"``.
    tau_range_s : (float, float), optional
        Search range for ``tau``; default ``(dt/2, 20 / f_min)``.
    n_grid : int, default 64
        Log-spaced ``tau`` grid size before refinement.
    floor : (ndarray, ndarray), optional
        Frequencies (Hz, > 0) and PSD values (m^2/Hz) the bound must also lie
        on or above that are not data (e.g. the models the data admit below
        the lowest band, :mod:`psdbound.spectra.lowfreq`): constraints of the
        linear programs, left out of the margins and the gap figures.
    extra : callable, optional
        Further linear constraints that are not PSD values: ``extra(tau)``
        returns ``(a, b)``, ``a`` of shape (R, 2) and ``b`` of shape (R,),
        requiring ``a @ (sigma_gm^2, sigma_wn^2) >= b`` (m^2 and the units of
        ``b``), e.g. expected estimates above data limits
        (:mod:`psdbound.spectra.lowest`).

    Returns
    -------
    BoundFit
        The optimum, with per-PSD margins and the ``tau`` search trace.

    Raises
    ------
    InputError
        For no usable PSD values, an unknown objective/target, or a bad range.
    """
    _check_options(objective, target, dt_s)
    data = _as_arrays(psds, target, level)
    f_all, s_all = _pooled(data, dt_s)
    nyq = 0.5 / dt_s
    f_min = float(f_all.min())
    f_max = float(f_all.max())
    f_con, s_con = f_all, s_all
    if floor is not None:
        f_con = np.concatenate([f_all, np.asarray(floor[0], dtype=float)])
        s_con = np.concatenate([s_all, np.asarray(floor[1], dtype=float)])
    fc, sc = _staircase(f_con, s_con)
    scale = float(sc.max())
    cost = _cost_function(objective, dt_s, f_min, nyq)
    solve = _lp_solver(fc, sc / scale, dt_s, cost, extra=extra, scale=scale)
    lo, hi = tau_range_s if tau_range_s is not None else (0.5 * dt_s, 20.0 / f_min)
    if not 0 < lo < hi:
        raise InputError(f"bad tau range {lo, hi}")
    grid, vals, best_tau = _search_tau(solve, lo, hi, n_grid)
    _, x = solve(best_tau)
    if not np.all(np.isfinite(x)):
        raise InputError(
            f"no bound could be fitted: the linear program failed at tau = "
            f"{best_tau:.4g} s (data of {s_all.size} points)"
        )
    var_gm, var_wn = _enforce_bound(x, scale, f_con, s_con, best_tau, dt_s)
    if extra is not None:
        var_gm, var_wn = _enforce_extra(extra(best_tau), var_gm, var_wn)
    gap_db = 10.0 * np.log10(_model_psd(f_all, var_gm, var_wn, best_tau, dt_s) / s_all)
    margins = []
    for f, s in data:
        mod = _model_psd(f, var_gm, var_wn, best_tau, dt_s)
        margins.append(float(np.min(mod / s)) if f.size else np.inf)
    obj = (
        (var_gm + var_wn)
        if objective == "variance"
        else float(cost(best_tau) @ np.array([var_gm, var_wn]))
    )
    return BoundFit(
        model=GaussMarkovWhiteNoise(
            sigma_gm_m=float(np.sqrt(var_gm)),
            tau_s=float(best_tau),
            sigma_wn_m=float(np.sqrt(var_wn)),
            dt_s=dt_s,
        ),
        objective=objective,
        objective_value=float(obj),
        target=target,
        level=level if target == "upper" else None,
        margins=np.asarray(margins),
        tau_grid_s=grid,
        objective_grid=vals * scale,
        n_constraints=int(fc.size),
        n_points=int(f_all.size),
        f_min_hz=f_min,
        f_max_hz=f_max,
        gap_db_median=float(np.median(gap_db)),
        gap_db_p05=float(np.percentile(gap_db, 5)),
    )


def _check_options(objective: str, target: str, dt_s: float) -> None:
    """Check the objective, the target and the sampling interval (s)."""
    if objective not in OBJECTIVES:
        raise InputError(f"unknown objective {objective!r}; choose from {OBJECTIVES}")
    if target not in ("point", "upper"):
        raise InputError(f"unknown target {target!r}; choose 'point' or 'upper'")
    if not dt_s > 0:
        raise InputError(f"sampling interval must be > 0 s, got {dt_s}")


def _pooled(
    data: list[tuple[NDArray[np.float64], NDArray[np.float64]]], dt_s: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """All PSDs' frequencies (Hz) and values (m^2/Hz) in one pair, checked against Nyquist."""
    f_all = np.concatenate([d[0] for d in data]) if data else np.zeros(0)
    s_all = np.concatenate([d[1] for d in data]) if data else np.zeros(0)
    if f_all.size == 0:
        raise InputError("no positive PSD values to bound")
    nyq = 0.5 / dt_s
    if f_all.max() > nyq * (1 + 1e-9):
        raise InputError(
            f"PSD frequencies reach {f_all.max():g} Hz, above the Nyquist frequency {nyq:g} Hz "
            f"of dt = {dt_s:g} s"
        )
    return f_all, s_all


def _cost_function(
    objective: str, dt_s: float, f_min: float, nyq: float
) -> Callable[[float], NDArray[np.float64]]:
    """Return the objective's coefficients of ``(sigma_gm^2, sigma_wn^2)`` as a function of tau."""
    white = 2.0 * dt_s
    if objective == "variance":

        def cost(tau: float) -> NDArray[np.float64]:
            return np.array([1.0, 1.0])
    else:

        def cost(tau: float) -> NDArray[np.float64]:
            phi = np.exp(-dt_s / tau)
            # integral of g_tau over [f_min, f_N], closed form of the AR(1) PSD
            x = np.pi * f_min * dt_s
            ang = 2.0 * np.arctan((1.0 + phi) / (1.0 - phi) * np.tan(x))
            g_int = 1.0 - ang / np.pi
            return np.array([g_int, white * (nyq - f_min)])

    return cost


def _lp_solver(
    fc: NDArray[np.float64],
    s_norm: NDArray[np.float64],
    dt_s: float,
    cost: Callable[[float], NDArray[np.float64]],
    *,
    extra: ExtraRows | None = None,
    scale: float = 1.0,
) -> Callable[[float], tuple[float, NDArray[np.float64]]]:
    """Return the linear program of one tau: its optimum and ``(sigma_gm^2, sigma_wn^2)``.

    The values are normalised by the PSD scale (``extra`` rows, in absolute
    units, by ``scale``); the optimum is inf when the program fails.
    """
    white = 2.0 * dt_s

    def solve(tau: float) -> tuple[float, NDArray[np.float64]]:
        g = gm_psd_sampled(fc, 1.0, tau, dt_s)
        a_ub = -np.column_stack([g, np.full(fc.size, white)])
        b_ub = -s_norm
        if extra is not None:
            a_x, b_x = extra(tau)
            a_ub, b_ub = np.vstack([a_ub, -a_x]), np.concatenate([b_ub, -b_x / scale])
        res = linprog(
            cost(tau), A_ub=a_ub, b_ub=b_ub, bounds=[(0, None), (0, None)], method="highs"
        )
        if res.status != 0:
            return np.inf, np.array([np.nan, np.nan])
        return float(res.fun), res.x

    return solve


def _search_tau(
    solve: Callable[[float], tuple[float, NDArray[np.float64]]],
    lo: float,
    hi: float,
    n_grid: int,
) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    """Search tau (s): a log grid, then a bounded Brent refinement; return grid, values, best."""
    grid = np.geomspace(lo, hi, n_grid)
    vals = np.array([solve(t)[0] for t in grid])
    k = int(np.argmin(vals))
    a, b = grid[max(k - 1, 0)], grid[min(k + 1, n_grid - 1)]
    best_tau, best_val = grid[k], vals[k]
    if b > a:
        r = minimize_scalar(
            lambda u: solve(float(np.exp(u)))[0],
            bounds=(np.log(a), np.log(b)),
            method="bounded",
            options={"xatol": 1e-6},
        )
        if r.fun < best_val:
            best_tau, best_val = float(np.exp(r.x)), float(r.fun)
    return grid, vals, best_tau


def _model_psd(
    f: NDArray[np.float64], var_gm: float, var_wn: float, tau: float, dt_s: float
) -> NDArray[np.float64]:
    """Return the bound's sampled PSD at ``f`` (Hz), m^2/Hz."""
    return var_gm * gm_psd_sampled(f, 1.0, tau, dt_s) + var_wn * (2.0 * dt_s)


def _enforce_extra(
    rows: tuple[NDArray[np.float64], NDArray[np.float64]], var_gm: float, var_wn: float
) -> tuple[float, float]:
    """Return the variances (m^2), scaled up so the ``extra`` rows hold exactly."""
    a_x, b_x = rows
    need = b_x > 0
    if not need.any():
        return var_gm, var_wn
    worst = float(np.min((a_x[need] @ np.array([var_gm, var_wn])) / b_x[need]))
    if worst < 1.0:
        up = (1.0 + 1e-12) / max(worst, 1e-300)
        var_gm, var_wn = var_gm * up, var_wn * up
    return var_gm, var_wn


def _enforce_bound(
    x: NDArray[np.float64],
    scale: float,
    f_con: NDArray[np.float64],
    s_con: NDArray[np.float64],
    tau: float,
    dt_s: float,
) -> tuple[float, float]:
    """Return the variances (m^2), scaled up so the bound holds on every constraint point."""
    # HiGHS may return -1e-18 for a variance at its bound of 0: a variance is not negative
    var_gm, var_wn = max(float(x[0]), 0.0) * scale, max(float(x[1]), 0.0) * scale
    # enforce the bound exactly on every data point (and floor point)
    worst = float(np.min(_model_psd(f_con, var_gm, var_wn, tau, dt_s) / s_con))
    if worst < 1.0:  # solver tolerance: scale up so the bound holds (1e-12 for rounding)
        up = (1.0 + 1e-12) / worst
        var_gm, var_wn = var_gm * up, var_wn * up
    return var_gm, var_wn
