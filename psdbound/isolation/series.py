"""The multipath-series container shared by both isolation methods."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["MultipathSeries", "ArcView"]


@dataclass(frozen=True)
class ArcView:
    """One arc of a :class:`MultipathSeries` (views into its arrays).

    Attributes
    ----------
    arc_id : int
        Arc identifier within the series.
    sats : str
        Satellite (``"G05"``) or satellite pair for double differences
        (``"G05-G12"``: satellite minus reference).
    t_gps_s, value_m, elevation_deg : ndarray
        Epochs (GPS seconds), isolated multipath (metres, scaled to one
        signal) and elevation (degrees; the lower of the pair for DA).
    unfiltered_m : ndarray or None
        Dual-frequency difference after mean removal, before the high-pass
        filter and before scaling (metres); None for dual-antenna series.
    third_m : ndarray or None
        ``L_a - L_c`` with a third carrier ``c`` (metres, unfiltered; NaN
        where there is none); None when the series has no third carrier.
    """

    arc_id: int
    sats: str
    t_gps_s: NDArray[np.float64]
    value_m: NDArray[np.float64]
    elevation_deg: NDArray[np.float64]
    unfiltered_m: NDArray[np.float64] | None
    third_m: NDArray[np.float64] | None = None

    @property
    def rms_m(self) -> float:
        """Root-mean-square of the isolated multipath, metres."""
        return float(np.sqrt(np.mean(self.value_m**2)))

    @property
    def duration_s(self) -> float:
        """First to last epoch, seconds."""
        return float(self.t_gps_s[-1] - self.t_gps_s[0])


@dataclass(frozen=True)
class MultipathSeries:
    """Isolated carrier-phase multipath of many arcs, concatenated.

    All per-sample arrays have the same length; ``arc_id`` says which arc a
    sample belongs to (samples of an arc are contiguous and time-ordered).

    Attributes
    ----------
    method : str
        ``"DF"`` (dual-frequency), ``"DA"`` (dual-antenna double difference),
        ``"CODE"`` (code multipath, MP combination) or ``"CODE-IF"``
        (ionosphere-free code minus carrier); the code series are not
        filtered and may have holes where a pseudorange is missing.
    t_gps_s : ndarray of float64
        Epochs, GPS seconds.
    value_m : ndarray of float64
        Multipath scaled to one signal, metres (DF divided by sqrt(2), DA by 2,
        code series not scaled).
    elevation_deg : ndarray of float64
        Elevation in degrees (DA: the lower of the two satellites).
    arc_id : ndarray of int
        Arc index of each sample.
    arc_sats : tuple of str
        Satellite(s) of each arc (``"G05"`` or ``"G05-G12"``).
    signals : tuple of str
        Signals used (DF: the pair; DA: the one signal).
    scaling : float
        Factor applied to the raw combination (1/sqrt(2) for DF, 1/2 for DA,
        1 for code).
    interval_s : float
        Sampling interval, seconds.
    cutoff_hz : float or None
        High-pass cutoff applied (DF), None when no filter was applied.
    unfiltered_m : ndarray of float64 or None
        DF only: difference after mean removal, before filter and scaling.
    meta : dict
        Provenance: source files, filter design and edge handling,
        reference-satellite choices, counts of dropped arcs, etc.
    third_m : ndarray of float64 or None
        DF with a third carrier ``c`` only: the geometry-free phase ``L_a -
        L_c`` of the pair's first carrier and the third, metres, unfiltered
        and unscaled (an arc's mean removed), NaN where the third phase is
        missing and at the first sample after each of its breaks; for the
        three-frequency screening test (:mod:`psdbound.screening.threefreq`).
    third_signal : str or None
        Phase code of the third carrier (None: no third carrier).
    """

    method: str
    t_gps_s: NDArray[np.float64]
    value_m: NDArray[np.float64]
    elevation_deg: NDArray[np.float64]
    arc_id: NDArray[np.intp]
    arc_sats: tuple[str, ...]
    signals: tuple[str, ...]
    scaling: float
    interval_s: float
    cutoff_hz: float | None = None
    unfiltered_m: NDArray[np.float64] | None = None
    meta: dict[str, Any] = field(default_factory=dict)
    third_m: NDArray[np.float64] | None = None
    third_signal: str | None = None

    @property
    def n_arcs(self) -> int:
        """Number of arcs."""
        return len(self.arc_sats)

    @property
    def nyquist_hz(self) -> float:
        """Nyquist frequency of the sampling, Hz."""
        return 0.5 / self.interval_s

    def arc(self, k: int) -> ArcView:
        """Return arc ``k`` as an :class:`ArcView`."""
        lo, hi = self.arc_bounds()[k]
        return ArcView(
            arc_id=k,
            sats=self.arc_sats[k],
            t_gps_s=self.t_gps_s[lo:hi],
            value_m=self.value_m[lo:hi],
            elevation_deg=self.elevation_deg[lo:hi],
            unfiltered_m=None if self.unfiltered_m is None else self.unfiltered_m[lo:hi],
            third_m=None if self.third_m is None else self.third_m[lo:hi],
        )

    def arcs(self) -> Iterator[ArcView]:
        """Iterate over the arcs."""
        for k in range(self.n_arcs):
            yield self.arc(k)

    def rms_per_arc_m(self) -> NDArray[np.float64]:
        """Root-mean-square multipath of every arc, metres."""
        return np.array([a.rms_m for a in self.arcs()])

    def summary(self) -> str:
        """Describe the series in a few lines (counts, RMS distribution, metadata)."""
        rms_mm = 1e3 * self.rms_per_arc_m()
        lines = [
            f"{self.method} multipath, signals {'-'.join(self.signals)}, {self.n_arcs} arcs, "
            f"{self.t_gps_s.size} samples at {self.interval_s:g} s "
            f"(Nyquist {self.nyquist_hz:.4g} Hz), scaling {self.scaling:.4f}",
        ]
        if self.cutoff_hz is not None:
            lines.append(f"  high-pass cutoff {self.cutoff_hz:.4g} Hz")
        if rms_mm.size:
            lines.append(
                f"  per-arc RMS: median {np.median(rms_mm):.2f} mm, 95th percentile "
                f"{np.percentile(rms_mm, 95):.2f} mm, max {rms_mm.max():.2f} mm"
            )
        return "\n".join(lines)

    @property
    def data_s(self) -> float:
        """Amount of data: samples of every arc times the sampling interval, seconds."""
        return float(self.t_gps_s.size * self.interval_s)

    def arc_bounds(self) -> list[tuple[int, int]]:
        """Return ``[(start, stop), ...]``: each arc's index range in the flat arrays."""
        edges = np.flatnonzero(np.diff(self.arc_id)) + 1
        starts = np.r_[0, edges]
        stops = np.r_[edges, self.arc_id.size]
        return list(zip(starts.tolist(), stops.tolist(), strict=True))

    @classmethod
    def from_arcs(
        cls,
        method: str,
        arcs: list[dict[str, Any]],
        **kwargs: Any,
    ) -> MultipathSeries:
        """Build a series from per-arc dicts.

        Parameters
        ----------
        method : str
            ``"DF"`` or ``"DA"``.
        arcs : list of dict
            Each with keys ``sats``, ``t_gps_s``, ``value_m``, ``elevation_deg``
            and optionally ``unfiltered_m`` and ``third_m``.
        **kwargs
            The remaining :class:`MultipathSeries` fields.
        """

        def cat(key: str) -> NDArray[np.float64]:
            return np.concatenate([a[key] for a in arcs]) if arcs else np.zeros(0)

        unfiltered = cat("unfiltered_m") if arcs and "unfiltered_m" in arcs[0] else None
        if arcs and "third_m" in arcs[0]:
            kwargs.setdefault("third_m", cat("third_m"))
        arc_id = (
            np.concatenate([np.full(a["t_gps_s"].size, k) for k, a in enumerate(arcs)])
            if arcs
            else np.zeros(0, dtype=np.intp)
        )
        return cls(
            method=method,
            t_gps_s=cat("t_gps_s"),
            value_m=cat("value_m"),
            elevation_deg=cat("elevation_deg"),
            arc_id=arc_id,
            arc_sats=tuple(a["sats"] for a in arcs),
            unfiltered_m=unfiltered,
            **kwargs,
        )
