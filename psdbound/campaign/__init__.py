"""Campaigns: many files, days and stations in one run, every bound tested on held-out days.

* :func:`run_campaign` -> :class:`CampaignResult` (per-day bounds, a pooled
  bound per station, held-out tests; Dask tasks cached by input hash);
* :func:`plan_campaign` -> :class:`StationDay` (files grouped by station and
  day, navigation files matched to days by the time they cover:
  :func:`match_nav`, :func:`orbit_span`);
* :func:`pool_station`: a station's bounded days pooled, the pooled bound judged;
* :func:`held_out`: each station-day against the bound of the station's other days;
* :func:`write_campaign`: ``campaign.json``, ``campaign.html``, ``campaign.pdf``.
"""

from __future__ import annotations

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
