"""Windows shorter than the longest: the stated frequencies they do not resolve.

The statement holds from ``f_min`` to Nyquist for every covered window, and
the default ``f_min`` is where the *longest* windows resolve from
(``W + 1/T``, :func:`psdbound.spectra.bands.resolved_from_hz`). A shorter
window has no band value between ``f_min`` and its own ``W + 1/T_i``: its
limits start higher, and a bound fitted to them says nothing of its PSD
there. When the short window shares its shape with longer ones (one shape
group), their limits speak for it. When it does not (a slow, strong
reflector in a short arc: ``benchmarks/bound_coverage.py``, class
``slowuneq``), nothing did: the bound lay up to 4.4 times under such a
window's true PSD between ``f_min`` and its own resolution, in 6-8 % of runs.

**Rule.** For every shape group none of whose windows resolves ``f_min``,
the group's model set (:func:`psdbound.spectra.intervals.model_set` on its
own windows: every GM + white-noise model whose exact band expectations fit
the group's pooled spectrum at the stated confidence, raised by the largest
factor to a covered window) is carried down from the group's resolved
frequency to ``f_min``, and the bound is held above its envelope there (the
points are a ``floor`` of the refit, :func:`psdbound.spectra.pooled.fit_limits`).
No prior on the time constant enters: between ``f_min`` and ``f_g`` the
envelope is finite for every admitted model, and the data of a short window
do not bound the time constant. Where the group's data admit only a flat
spectrum at its lowest bands the envelope stays flat; where they admit a
steep one, it rises towards ``f_min``.

**Without a model set** (too few bands, or no GM + white model fits the
group): every Gauss-Markov and white-noise term has ``f^2 S(f)`` increasing
in ``f``, so for any sum of them ``S(f) <= S(f_g) (f_g / f)^2`` below
``f_g``; the group's limit at its lowest band, times the band's edge ratio
``r`` (at its lower edge such a sum is at most ``r`` times its band mean, for
the same reason), is carried down along ``f^-2``. It holds for any such truth
and may be loose where the truth is flat.

**Said, not raised.** A short window in a group with windows that resolve
``f_min`` is covered between ``f_min`` and its own resolution through that
group's limits, as far as the shape tests tell it from the group: a slow
reflector in a short window that no test sees is the known weak point
(``docs/method/bound.rst``). :attr:`UnresolvedGroups.n_short` counts such
windows, and the statement names their number.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.spectra.bands import BandSpectra
from psdbound.spectra.bound import BoundFit, Floor, join_floors
from psdbound.spectra.intervals import model_set
from psdbound.spectra.lowfreq import model_envelope
from psdbound.spectra.models import GaussMarkovWhiteNoise, below_band_ceiling
from psdbound.spectra.pooled import PooledLimits, fit_limits, lowest_limit

__all__ = ["UnresolvedGroups", "cover_unresolved"]

#: Points of each group's envelope between ``f_min`` and its resolved frequency.
_N_POINTS = 25


@dataclass(frozen=True)
class UnresolvedGroups:
    """The groups of windows that do not resolve the lowest stated frequency.

    Attributes
    ----------
    groups : tuple of int
        The shape groups (:attr:`PooledLimits.groups`) none of whose windows
        resolves ``f_min``.
    resolved_from_hz : tuple of float
        Each such group's lowest resolved frequency, Hz.
    how : tuple of str
        How each was carried down to ``f_min``: ``"model set"`` or
        ``"f^-2"`` (no model set; :mod:`psdbound.spectra.unresolved`).
    f_min_hz : float
        The lowest stated frequency, Hz.
    f_hz, envelope_m2_hz : ndarray
        The points the bound is held above (Hz, m^2/Hz).
    raised : bool
        Whether the bound had to be raised to lie above them.
    before : GaussMarkovWhiteNoise or None
        The bound before (None without such groups).
    n_short : int
        Windows that resolve only above ``f_min`` but share a shape group
        with windows that resolve it: between ``f_min`` and their own
        resolution the statement covers them through that group's limits,
        as far as the shape tests tell them from it.
    n_windows : int
        All windows.
    """

    groups: tuple[int, ...]
    resolved_from_hz: tuple[float, ...]
    how: tuple[str, ...]
    f_min_hz: float
    f_hz: NDArray[np.float64]
    envelope_m2_hz: NDArray[np.float64]
    raised: bool = False
    before: GaussMarkovWhiteNoise | None = None
    n_short: int = 0
    n_windows: int = 0

    def floor(self) -> Floor | None:
        """Return the points as constraints (Hz, m^2/Hz) of a refit; None without any."""
        return (self.f_hz, self.envelope_m2_hz) if self.f_hz.size else None

    def sentence(self) -> str:
        """Return this part of the statement, in words (empty when every window resolves f_min)."""
        out = []
        if self.groups:
            parts = ", ".join(
                f"group {g} from {f:.3g} Hz ({how})"
                for g, f, how in zip(self.groups, self.resolved_from_hz, self.how, strict=True)
            )
            out.append(
                f"where a group's windows resolve only above {self.f_min_hz:.3g} Hz, the bound "
                f"lies above the group's admitted models carried down to it: {parts}"
            )
        if self.n_short:
            verb = "resolves" if self.n_short == 1 else "resolve"
            out.append(
                f"{self.n_short} of the {self.n_windows} windows {verb} only above "
                f"{self.f_min_hz:.3g} Hz (each from its own W + 1/T) in a shape group with "
                "windows that resolve it: below their own resolution they are covered through "
                "that group's limits, as far as the shape tests tell them from it"
            )
        return "; ".join(out)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (``bound.unresolved`` of result.json)."""
        b = self.before
        return {
            "groups": list(self.groups),
            "resolved_from_hz": list(self.resolved_from_hz),
            "how": list(self.how),
            "f_min_hz": self.f_min_hz,
            "raised": self.raised,
            "before": None
            if b is None
            else {"sigma_gm_m": b.sigma_gm_m, "tau_s": b.tau_s, "sigma_wn_m": b.sigma_wn_m},
            "short_windows": self.n_short,
            "statement": self.sentence(),
        }


def _f_minus_2(
    limits: PooledLimits, bands: BandSpectra, g: int, f_hz: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Return the group's lowest limit carried down along ``f^-2`` from its band's lower edge."""
    lowest = lowest_limit(limits, bands, g)
    if lowest is None:  # a group without a limit carries nothing down
        return np.zeros_like(np.asarray(f_hz, dtype=float))
    return below_band_ceiling(*lowest, f_hz)


def _group_envelope(
    g: int,
    f_hz: NDArray[np.float64],
    id_bands: BandSpectra,
    bands: BandSpectra,
    limits: PooledLimits,
    dt_s: float,
    smoothing_hz: float,
) -> tuple[NDArray[np.float64], str]:
    """One group's envelope at ``f_hz`` and how it was found."""
    ms, _ = model_set(
        id_bands,
        limits,
        dt_s,
        confidence_level=limits.confidence_level,
        smoothing_hz=smoothing_hz,
        group=g,
    )
    if ms is not None and ms.vertices.size:
        env = model_envelope(ms, dt_s, f_hz, tau_max_s=float("inf"))
        if env.size == f_hz.size and np.all(np.isfinite(env)):
            return env, "model set"
    return _f_minus_2(limits, bands, g, f_hz), "f^-2"


def cover_unresolved(
    fit: BoundFit,
    resolved_hz: Sequence[float],
    bands: BandSpectra,
    limits: PooledLimits,
    dt_s: float,
    *,
    id_bands: BandSpectra | None = None,
    smoothing_hz: float = 0.0,
    floor: Floor | None = None,
    objective: str = "variance",
    n_grid: int = 64,
) -> tuple[BoundFit, UnresolvedGroups]:
    """Raise the bound, where needed, over the stated frequencies a group does not resolve.

    Parameters
    ----------
    fit : BoundFit
        The bound so far.
    resolved_hz : sequence of float
        Where each window's estimate resolves from, Hz
        (:func:`psdbound.spectra.bands.resolved_from_hz`), in the windows' order.
    bands : BandSpectra
        The statement's bands (from ``f_min``).
    limits : PooledLimits
        The pooled limits (groups, confidence level).
    dt_s : float
        Sampling interval, seconds.
    id_bands : BandSpectra, optional
        The bands the model sets are identified on
        (:func:`psdbound.spectra.stated.identification_bands`; default ``bands``).
    smoothing_hz : float, default 0
        Multitaper half-width ``W``, Hz (0: no model set, the ``f^-2`` rule).
    floor : (ndarray, ndarray), optional
        Points the bound already lies above (kept in a refit).
    objective : {"variance", "area"}, default "variance"
        Tightness objective of a refit.
    n_grid : int, default 64
        ``tau`` grid size of a refit.

    Returns
    -------
    fit : BoundFit
        The bound (unchanged when it already lies above every group's envelope).
    UnresolvedGroups
        The groups and the points.
    """
    f_min = float(bands.edges_hz[0])
    resolved = np.asarray(resolved_hz, dtype=float)
    short = _short_in_resolved_groups(resolved, limits.groups, f_min)
    groups, froms, hows, fs, envs = [], [], [], [], []
    for g in range(limits.n_groups):
        rows = limits.groups == g
        f_g = float(resolved[rows].min()) if rows.any() else f_min
        if f_g <= f_min * (1.0 + 1e-9) or not np.isfinite(limits.upper_m2_hz[g]).any():
            continue
        f = np.geomspace(f_min, f_g, _N_POINTS)
        env, how = _group_envelope(
            g, f, bands if id_bands is None else id_bands, bands, limits, dt_s, smoothing_hz
        )
        groups.append(g)
        froms.append(f_g)
        hows.append(how)
        fs.append(f)
        envs.append(env)
    if not groups:
        empty = np.zeros(0)
        return fit, UnresolvedGroups(
            (), (), (), f_min, empty, empty, n_short=short, n_windows=resolved.size
        )
    f_all, env_all = np.concatenate(fs), np.concatenate(envs)
    before = fit.model
    raised = bool(np.any(fit.psd(f_all) < env_all * (1.0 - 1e-9)))
    if raised:
        fit = fit_limits(
            limits,
            bands,
            dt_s,
            objective=objective,
            n_grid=n_grid,
            floor=join_floors(floor, (f_all, env_all)),
        )
    return fit, UnresolvedGroups(
        tuple(groups),
        tuple(froms),
        tuple(hows),
        f_min,
        f_all,
        env_all,
        raised,
        before,
        n_short=short,
        n_windows=resolved.size,
    )


def _short_in_resolved_groups(
    resolved_hz: NDArray[np.float64], groups: NDArray[np.int64], f_min_hz: float
) -> int:
    """Count the windows resolving only above ``f_min`` whose group has one that resolves it."""
    short = resolved_hz > f_min_hz * (1.0 + 1e-9)
    return int(np.isin(groups[short], groups[~short]).sum())
