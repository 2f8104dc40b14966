"""Results of batch cutoff runs: one station over its days, and the station map.

:class:`StationCutoffs` holds the per-series cutoffs of one station with
their summary (mean, min and max f_c; the recommended cutoff is the maximum,
the thesis's choice: it removes the fastest ionospheric dynamics met);
:class:`CutoffMap` holds one per station with nearest-station lookup. Both
give a CSV table and a JSON-ready dict.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from psdbound.ionosphere.envelope import Envelope
from psdbound.ionosphere.settings import CutoffSettings
from psdbound.ionosphere.stations import Station, nearest_station

__all__ = ["CutoffMap", "StationCutoffs"]


@dataclass
class StationCutoffs:
    """Per-series cutoffs of one station over its days, and their summary.

    Attributes
    ----------
    name : str
        Station name.
    lat_deg, lon_deg, height_m : float
        Station position.
    rows : list of dict
        One per analysed series: ``date``, ``sat``, ``f_c_hz``,
        ``tau_c_min``, ``reached``, ``n_samples``, ``variance_m2`` and, for
        the residual criterion, ``floor``, ``threshold_m``, ``scale``,
        ``n_arcs``, ``f_c_by_threshold`` and the scanned curve
        (``curve_f_hz``, ``curve_rms_m``); for a periodogram criterion
        ``peak_hz``, ``peak_psd_m2_hz``, ``threshold_m2_hz``,
        ``residual_m2`` and the ``envelope`` (dict).
    skipped : list of dict
        Series not analysed (``date``, ``sat``, ``reason``), and days
        without any satellite above the mask.
    settings : CutoffSettings
        The run's settings.
    orbit_source, orbit_description : str
        What gave the satellite positions (recorded with the results).
    days : list of str
        Days requested (``YYYY-MM-DD``).
    from_cache : list of bool
        Per day, whether the result came from the cache.
    elapsed_s : float
        Wall time of the run, s.
    series_by_date : dict
        Per day, the simulated delays (``t_gps_s``, ``sats``, ``delay_m``
        with NaN below the mask) when kept, else None.
    """

    name: str
    lat_deg: float
    lon_deg: float
    height_m: float
    rows: list[dict]
    skipped: list[dict]
    settings: CutoffSettings
    orbit_source: str
    orbit_description: str
    days: list[str]
    from_cache: list[bool] = field(default_factory=list)
    elapsed_s: float = 0.0
    series_by_date: dict[str, dict | None] = field(default_factory=dict, repr=False)

    @property
    def f_c_hz(self) -> np.ndarray:
        """Cutoffs of all series, Hz."""
        return np.array([r["f_c_hz"] for r in self.rows], dtype=float)

    @property
    def envelopes(self) -> list[Envelope]:
        """Envelopes of all series (periodogram criteria; empty for the residual criterion)."""
        return [Envelope.from_dict(r["envelope"]) for r in self.rows if "envelope" in r]

    def by_margin(self) -> list[dict[str, Any]]:
        """Cutoffs at every recorded margin (residual criterion; empty otherwise).

        Returns
        -------
        list of dict
            Per margin (dB below ``settings.mp_sigma_m``): ``margin_db``,
            ``threshold_m``, ``mean_f_c_hz``, ``max_f_c_hz`` (= the
            recommended cutoff at that margin).
        """
        if not self.rows or "f_c_by_threshold" not in self.rows[0]:
            return []
        out = []
        margins = self.settings.margins_db()
        for k, (m, thr) in enumerate(zip(margins, self.settings.thresholds_m(), strict=True)):
            fc = np.array([r["f_c_by_threshold"][k][1] for r in self.rows], dtype=float)
            out.append(
                {
                    "margin_db": m,
                    "threshold_m": thr,
                    "mean_f_c_hz": float(fc.mean()),
                    "max_f_c_hz": float(fc.max()),
                }
            )
        return sorted(out, key=lambda d: d["margin_db"])

    def summary(self) -> dict[str, Any]:
        """Mean, min, max and recommended (= max) f_c, with counts and provenance."""
        fc = self.f_c_hz
        out: dict[str, Any] = {
            "name": self.name,
            "lat_deg": self.lat_deg,
            "lon_deg": self.lon_deg,
            "n_days": len(self.days),
            "n_series": int(fc.size),
            "n_skipped": len(self.skipped),
            "criterion": self.settings.criterion,
            "orbit_source": self.orbit_source,
        }
        if fc.size:
            out.update(
                mean_f_c_hz=float(fc.mean()),
                min_f_c_hz=float(fc.min()),
                max_f_c_hz=float(fc.max()),
                recommended_f_c_hz=float(fc.max()),
                recommended_tau_c_min=float(1.0 / fc.max() / 60.0),
                n_not_reached=int(sum(not r["reached"] for r in self.rows)),
                n_floor=int(sum(bool(r.get("floor", False)) for r in self.rows)),
            )
            if self.settings.criterion == "residual":
                out.update(
                    mp_sigma_m=self.settings.mp_sigma_m,
                    margin_db=self.settings.margin_db,
                    threshold_m=self.settings.thresholds_m()[0],
                    by_margin=self.by_margin(),
                )
        else:
            out.update(
                mean_f_c_hz=float("nan"),
                min_f_c_hz=float("nan"),
                max_f_c_hz=float("nan"),
                recommended_f_c_hz=float("nan"),
                recommended_tau_c_min=float("nan"),
                n_not_reached=0,
                n_floor=0,
            )
        return out

    def table_csv(self) -> str:
        """Per-series table as CSV text."""
        if self.settings.criterion == "residual":
            cols = [
                "date",
                "sat",
                "f_c_hz",
                "tau_c_min",
                "reached",
                "floor",
                "n_samples",
                "n_arcs",
                "threshold_m",
                "scale",
                "variance_m2",
            ]
        else:
            cols = [
                "date",
                "sat",
                "f_c_hz",
                "tau_c_min",
                "reached",
                "n_samples",
                "peak_hz",
                "peak_psd_m2_hz",
                "threshold_m2_hz",
                "residual_m2",
                "variance_m2",
            ]
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(cols)
        for r in self.rows:
            w.writerow([_fmt(r[c]) for c in cols])
        return buf.getvalue()

    def to_dict(self) -> dict[str, Any]:
        """Everything as a JSON-ready dict (summary, settings, provenance, rows)."""
        return {
            "summary": self.summary(),
            "station": {
                "name": self.name,
                "lat_deg": self.lat_deg,
                "lon_deg": self.lon_deg,
                "height_m": self.height_m,
            },
            "days": self.days,
            "orbit_source": self.orbit_source,
            "orbit_description": self.orbit_description,
            "settings": self.settings.to_dict(),
            "from_cache": self.from_cache,
            "elapsed_s": self.elapsed_s,
            "rows": self.rows,
            "skipped": self.skipped,
        }


@dataclass
class CutoffMap:
    """Recommended cutoffs over a set of stations, with nearest-station lookup.

    Attributes
    ----------
    stations : list of StationCutoffs
        One per station, in input order.
    elapsed_s : float
        Wall time of the run, s.
    """

    stations: list[StationCutoffs]
    elapsed_s: float = 0.0

    def rows(self) -> list[dict[str, Any]]:
        """One summary dict per station."""
        return [s.summary() for s in self.stations]

    def nearest(self, lat_deg: float, lon_deg: float) -> tuple[dict[str, Any], float]:
        """Summary of the station nearest a position, and its distance (deg).

        Parameters
        ----------
        lat_deg, lon_deg : float
            Position, degrees.

        Returns
        -------
        summary : dict
            The nearest station's summary (``recommended_f_c_hz`` ...).
        distance_deg : float
            Great-circle distance, degrees.
        """
        cands = [Station(s.name, s.lat_deg, s.lon_deg) for s in self.stations]
        st, d = nearest_station(lat_deg, lon_deg, cands)
        return self.stations[cands.index(st)].summary(), d

    def table_csv(self) -> str:
        """Station table as CSV text."""
        cols = [
            "name",
            "lat_deg",
            "lon_deg",
            "n_series",
            "mean_f_c_hz",
            "min_f_c_hz",
            "max_f_c_hz",
            "recommended_f_c_hz",
            "recommended_tau_c_min",
            "n_skipped",
        ]
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(cols)
        for r in self.rows():
            w.writerow([_fmt(r[c]) for c in cols])
        return buf.getvalue()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: station summaries, settings and provenance."""
        first = self.stations[0] if self.stations else None
        return {
            "stations": self.rows(),
            "days": first.days if first else [],
            "settings": first.settings.to_dict() if first else {},
            "orbit_source": first.orbit_source if first else "",
            "orbit_description": first.orbit_description if first else "",
            "elapsed_s": self.elapsed_s,
        }


def _fmt(v: Any) -> Any:
    if isinstance(v, float):
        return f"{v:.6g}"
    return v
