"""Campaigns: many files, days and stations in one run, every bound tested on held-out days.

* :func:`run_campaign` -> :class:`CampaignResult` (per-day bounds, a pooled
  bound per station, held-out tests; Dask tasks cached by input hash);
* :func:`plan_campaign` -> :class:`StationDay` (files grouped by station and
  day, navigation files matched to days by the time they cover:
  :func:`match_nav`, :func:`orbit_span`);
* :func:`pool_station`: a station's bounded days pooled, the pooled bound judged;
* :func:`held_out`: each station-day against the bound of the station's other days;
* :func:`write_campaign`: ``campaign.json``, ``campaign.html``, ``campaign.pdf``,
  ``network.html`` (stations on a map and in one sortable table) and ``days/``
  (each station-day's report).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.campaign.heldout import held_out
    from psdbound.campaign.navmatch import match_nav, orbit_span
    from psdbound.campaign.pool import pool_station
    from psdbound.campaign.report import write_campaign
    from psdbound.campaign.run import CampaignResult, StationDay, plan_campaign, run_campaign

__all__ = [
    "CampaignResult",
    "StationDay",
    "held_out",
    "match_nav",
    "orbit_span",
    "plan_campaign",
    "pool_station",
    "run_campaign",
    "write_campaign",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "held_out": ("psdbound.campaign.heldout", "held_out"),
    "match_nav": ("psdbound.campaign.navmatch", "match_nav"),
    "orbit_span": ("psdbound.campaign.navmatch", "orbit_span"),
    "pool_station": ("psdbound.campaign.pool", "pool_station"),
    "write_campaign": ("psdbound.campaign.report", "write_campaign"),
    "CampaignResult": ("psdbound.campaign.run", "CampaignResult"),
    "StationDay": ("psdbound.campaign.run", "StationDay"),
    "plan_campaign": ("psdbound.campaign.run", "plan_campaign"),
    "run_campaign": ("psdbound.campaign.run", "run_campaign"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
