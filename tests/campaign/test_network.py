"""The campaign's network page on two simulated stations: map, sortable table, links (#32)."""

from __future__ import annotations

import json
import re
from html.parser import HTMLParser

import numpy as np
import pytest
from browser import chromium, needs_browser, not_blank

from psdbound.campaign import run_campaign, write_campaign
from psdbound.campaign.network import day_report_name, station_positions
from psdbound.simulate import preset, simulate

pytestmark = pytest.mark.slow

#: Two stations 5 deg apart (Chicago area and further west), two days each.
STATIONS = {"NETA": (41.84, -87.63), "NETB": (39.0, -94.5)}


@pytest.fixture(scope="module")
def network(tmp_path_factory):
    root = tmp_path_factory.mktemp("network")
    obs, nav = [], []
    for s, (name, (lat, lon)) in enumerate(STATIONS.items()):
        for k, start in enumerate(("2020-11-24T06:00:00", "2020-11-25T06:00:00")):
            sc = preset("demo").replace(
                name=name,
                start_gps=start,
                duration_s=12 * 3600.0,
                interval_s=30.0,
                dual_antenna=False,
                lat_deg=lat,
                lon_deg=lon,
                seed=31 + 2 * s + k,
            )
            res = simulate(sc, root / f"{name}{k}")
            obs.append(res.obs_paths[0])
            if s == 0:  # one broadcast file per day serves every station
                nav.append(res.nav_path)
    result = run_campaign(obs, nav, workers=0, cache_dir=root / "cache")
    out = root / "out"
    files = write_campaign(result, out, pdf=False)
    return result, out, files


class _Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.links, self.images, self.tables, self.scripts = [], [], [], 0

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "a":
            self.links.append(a["href"])
        elif tag == "img":
            self.images.append(a)
        elif tag == "table":
            self.tables.append(a)
        elif tag == "script":
            self.scripts += 1


def test_network_page_has_every_station_the_map_the_table_and_working_links(network):
    result, out, files = network
    assert files["network"] == out / "network.html"
    text = files["network"].read_text()
    page = _Page()
    page.feed(text)
    doc = json.loads(files["json"].read_text())
    # positions from the headers (APPROX POSITION XYZ -> WGS84) are where the stations were put
    pos = station_positions(doc)
    for name, (lat, lon) in STATIONS.items():
        assert np.allclose(pos[name], (lat, lon), atol=1e-6)
        assert f"<td data-sort='{name}'>{name}</td>" in text
    assert {i["alt"] for i in page.images} == {"station map", "bound over time"}
    assert all(
        i["src"].startswith("data:image/png;base64,") and len(i["src"]) > 5000 for i in page.images
    )
    assert {"class": "sortable", "id": "stations"} in page.tables and page.scripts == 1
    assert "addEventListener('click'" in text and "http" not in text  # no CDN, nothing fetched
    # one link per station-day report, every relative link resolves to a file
    days = [(d["station"], d["day"]) for d in doc["days"]]
    assert len(days) == 4
    reports = [day_report_name(*sd) for sd in days]
    assert set(reports) <= set(page.links) and "campaign.html" in page.links
    for href in page.links:
        assert (out / href).is_file(), href
    day = (out / reports[0]).read_text()
    assert "<html" in day and days[0][0] in day
    assert "network.html" in files["html"].read_text()  # the campaign page links to it
    # the sort keys are numbers where the column is numeric
    bounds = re.findall(r"<td data-sort='([0-9.e+-]+)'>", text)
    assert len(bounds) >= 2 * 3


def test_rewriting_the_campaign_replaces_the_day_reports(network, tmp_path):
    result, out, _ = network
    files = write_campaign(result, out, pdf=False)  # an earlier campaign folder: replaced
    assert sorted(p.name for p in out.iterdir()) == [
        "campaign.html",
        "campaign.json",
        "days",
        "network.html",
    ]
    assert len(list((out / "days").iterdir())) == 4 and files["network"].is_file()


@needs_browser
def test_network_page_as_a_person_sees_it(network, tmp_path):
    """Render network.html in headless Chromium: a page with the map, table and figure."""
    _, out, _ = network
    shot = tmp_path / "network.png"
    page = out / "network.html"
    chromium(page, tmp_path / "ud", "--window-size=1200,1800", f"--screenshot={shot}")
    assert shot.stat().st_size > 20_000 and not_blank(shot) > 0.05
    dom = chromium(page, tmp_path / "ud2", "--dump-dom")
    assert all(name in dom for name in STATIONS) and "station-map" in dom


def test_one_day_campaign_time_figure_spans_that_day_without_thousands_of_ticks():
    # a campaign of one station-day: matplotlib widened the single date to about four
    # years and the day locator asked for 1,461 ticks (33 MAXTICKS warnings in the log)
    import datetime as dt
    import warnings

    from matplotlib.dates import num2date

    from psdbound.campaign.network import _time_figure

    day = {"station": "ESBC", "day": "2020-06-25", "fitted": True}
    doc = {
        "stations": [{"station": "ESBC", "n_pooled": 1, "sigma_gm_m": 0.0067, "tau_s": 288.8}],
        "days": [{**day, "sigma_gm_m": 0.0067, "tau_s": 288.8, "sigma_wn_m": 0.0}],
    }
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fig = _time_figure(doc)
    for ax in fig.axes:
        lo, hi = (num2date(x).replace(tzinfo=None) for x in ax.get_xlim())
        assert hi - lo == dt.timedelta(days=1)
        assert len(ax.get_xticks()) == 1
