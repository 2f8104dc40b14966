"""From stationary windows to a fitted bound: a model/results pair.

:class:`BoundModel` holds the stationary windows and the PSD estimator
choice; :meth:`BoundModel.fit` estimates one PSD per window and returns a
:class:`BoundResults` (in the style of statsmodels' model/results split)
with the tightest GMRP + white-noise bound, the per-window margins and a
``summary()``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import NoDataError
from psdbound.spectra.bound import BoundFit, fit_bound
from psdbound.spectra.estimators import PSDEstimate, estimate_psd
from psdbound.stationarity.windowing import WindowSet

__all__ = ["BoundModel", "BoundResults"]


@dataclass(frozen=True)
class BoundResults:
    """Result of :meth:`BoundModel.fit`.

    Attributes
    ----------
    bound : BoundFit
        The fitted bound (parameters with units, margins, tau search).
    windows : WindowSet
        The stationary windows bounded.
    psds : tuple of PSDEstimate
        One PSD estimate per window (mapped multipath, one-sided, m^2/Hz).
    estimator : str
        PSD estimator used.
    estimator_options : dict
        Its options.
    """

    bound: BoundFit
    windows: WindowSet
    psds: tuple[PSDEstimate, ...]
    estimator: str
    estimator_options: dict[str, Any] = field(default_factory=dict)

    @property
    def margins(self) -> NDArray[np.float64]:
        """Per-window minimum of bound/data over frequency (>= 1)."""
        return self.bound.margins

    def params(self) -> dict[str, float]:
        """Bound parameters with units in their names."""
        return self.bound.params()

    def summary(self) -> str:
        """Return a text summary: bound table, windows, estimator, mapping."""
        ws = self.windows
        mp = ws.mapping
        dof = [float(np.median(np.atleast_1d(p.dof))) for p in self.psds]
        extra = [
            f"{'PSD estimator':<28}{self.estimator:>12s}  (median dof {np.median(dof):.1f})",
            f"{'elevation mapping':<28}{mp.source:>12s}  a={mp.a:.3g} b={mp.b:.3g} "
            f"c={mp.c_deg:.3g} deg",
            f"{'windows':<28}{len(ws):>12d}  ({ws.total_duration_s / 3600:.2f} h, "
            f"never stationary {ws.uncovered_s / 60:.1f} min)",
        ]
        return self.bound.summary() + "\n" + "\n".join(extra)


class BoundModel:
    """PSD bounding of stationary multipath windows.

    Parameters
    ----------
    windows : WindowSet
        Output of :func:`psdbound.stationarity.find_stationary_windows`.
    estimator : {"multitaper", "welch", "blackman-tukey"}, default "multitaper"
        PSD estimator (see :mod:`psdbound.spectra.estimators`). Multitaper is
        the default: the thesis's Blackman-Tukey with an 80 %/20 % lag
        taper leaks, which inflated its DF bound.
    **estimator_options
        Passed to :func:`psdbound.spectra.estimate_psd`.
    """

    def __init__(
        self, windows: WindowSet, *, estimator: str = "multitaper", **estimator_options: Any
    ) -> None:
        if len(windows) == 0:
            raise NoDataError(
                "no stationary window to bound "
                f"({windows.n_tests} stationarity tests; never-stationary time "
                f"{windows.uncovered_s / 60:.1f} min)"
            )
        self.windows = windows
        self.estimator = estimator
        self.estimator_options = estimator_options
        self._psds: tuple[PSDEstimate, ...] | None = None

    def psds(self) -> tuple[PSDEstimate, ...]:
        """Estimate (once) and return the PSD of every window."""
        if self._psds is None:
            self._psds = tuple(
                estimate_psd(
                    self.windows.data(k),
                    self.windows.interval_s,
                    method=self.estimator,
                    **self.estimator_options,
                )
                for k in range(len(self.windows))
            )
        return self._psds

    def fit(
        self,
        *,
        objective: str = "variance",
        target: str = "point",
        level: float = 0.95,
        n_grid: int = 64,
    ) -> BoundResults:
        """Fit the tightest bound over all windows' PSDs.

        Parameters
        ----------
        objective : {"variance", "area"}, default "variance"
            Tightness objective (:func:`psdbound.spectra.fit_bound`).
        target : {"point", "upper"}, default "point"
            Bound the PSD estimates or their upper confidence limits.
        level : float, default 0.95
            Confidence level for ``target="upper"``.
        n_grid : int, default 64
            Size of the log-spaced ``tau`` grid.

        Returns
        -------
        BoundResults
            Bound, windows, PSDs and estimator provenance.
        """
        psds = self.psds()
        bound = fit_bound(
            psds,
            self.windows.interval_s,
            objective=objective,
            target=target,
            level=level,
            n_grid=n_grid,
        )
        return BoundResults(bound, self.windows, psds, self.estimator, dict(self.estimator_options))
