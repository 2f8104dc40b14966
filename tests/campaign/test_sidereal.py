"""The sidereal repeat of ionosphere spans over consecutive days (campaign diagnostic)."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.campaign.sidereal import repeat_warnings, sidereal_repeats
from psdbound.constants import SIDEREAL_DAY_S

T0 = 1.293e9  # GPS seconds, a day's start
DAY = 86400.0


def _doc(t0: float, spans: dict[str, list[tuple[float, float]]]) -> dict:
    excluded = [
        {"sat": sat, "start_gps_s": t0 + a, "stop_gps_s": t0 + b, "kind": "ionosphere"}
        for sat, v in spans.items()
        for a, b in v
    ]
    excluded.append({"sat": "G01", "start_gps_s": t0, "stop_gps_s": t0 + 60, "kind": "limit"})
    return {
        "screening": {"excluded": excluded},
        "data_span": {"start_gps_s": t0, "stop_gps_s": t0 + DAY - 30},
    }


def _days(n: int) -> list[dict]:
    return [{"station": "SITE", "day": f"2021-01-0{i + 1}"} for i in range(n)]


def test_spans_that_repeat_with_the_sidereal_day_are_counted():
    spans = {"G05": [(3600.0, 5400.0)], "G12": [(40000.0, 41200.0)]}
    shift = SIDEREAL_DAY_S - DAY  # the same geometry, 236 s earlier in the next day's clock
    later = {s: [(a + shift, b + shift) for a, b in v] for s, v in spans.items()}
    docs = [_doc(T0, spans), _doc(T0 + DAY, later)]
    (r,) = sidereal_repeats(_days(2), docs)
    assert r["days"] == ["2021-01-01", "2021-01-02"]
    assert r["flagged_s"] == pytest.approx(3000.0)
    assert r["repeated_s"] == pytest.approx(3000.0)
    assert r["ratio"] > 20.0
    (w,) = repeat_warnings([r])
    assert "SITE 2021-01-02: 50 of the 50 min" in w and "probably multipath" in w


def test_independent_spans_share_about_what_chance_gives():
    rng = np.random.default_rng(5)
    ratios = []
    for _ in range(200):
        docs = []
        for d in range(2):
            spans = {}
            for sat in ("G02", "G07", "G19", "G24"):
                starts = rng.uniform(0.0, DAY - 1800.0, 3)
                spans[sat] = [(a, a + 900.0) for a in starts]
            docs.append(_doc(T0 + d * DAY, spans))
        (r,) = sidereal_repeats(_days(2), docs)
        ratios.append(r["ratio"])
    assert 0.6 < np.mean(ratios) < 1.6  # near 1: independent sets meet as often as expected
    assert not repeat_warnings(
        [
            {
                "station": "S",
                "days": ["a", "b"],
                "flagged_s": 1e4,
                "repeated_s": 500.0,
                "ratio": 1.1,
                "expected_s": 450.0,
            }
        ]
    )


def test_chance_is_counted_within_the_passes_that_repeat_with_the_sidereal_day():
    """Flags can only fall while a satellite is tracked, and the passes repeat.

    Independent spans that fill much of every pass on both days (a long-lived
    disturbance, the polar ionosphere) must not look like a repeat: against the
    whole day their overlap looked several times above chance.
    """
    rng = np.random.default_rng(11)
    shift = SIDEREAL_DAY_S - DAY
    passes = {"G02": (3000.0, 21000.0), "G07": (30000.0, 52000.0), "G19": (60000.0, 80000.0)}
    ratios, whole_day = [], []
    for _ in range(100):
        docs = []
        for d in range(2):
            spans, arcs = {}, []
            for sat, (a, b) in passes.items():
                a, b = a + d * shift, b + d * shift
                arcs.append({"sat": sat, "t0": T0 + d * DAY + a, "t1": T0 + d * DAY + b})
                starts = rng.uniform(a, b - 3600.0, 3)
                spans[sat] = [(x, x + 3600.0) for x in starts]
            doc = _doc(T0 + d * DAY, spans)
            docs.append(doc | {"figures": {"arcs": arcs}})
        (r,) = sidereal_repeats(_days(2), docs)
        ratios.append(r["ratio"])
        (no_arcs,) = sidereal_repeats(
            _days(2), [{k: v for k, v in x.items() if k != "figures"} for x in docs]
        )
        whole_day.append(no_arcs["ratio"])
    assert 0.8 < np.mean(ratios) < 1.25
    assert np.mean(whole_day) > 2.0  # the whole-day chance: what the passes alone give
    assert not any(r >= 3.0 for r in ratios)


def test_only_consecutive_days_with_documents_are_paired():
    docs = [_doc(T0, {"G05": [(0.0, 600.0)]}), None, _doc(T0 + 2 * DAY, {"G05": [(0.0, 600.0)]})]
    assert sidereal_repeats(_days(3), docs) == []
    quiet = [_doc(T0, {"G05": [(0.0, 600.0)]}), _doc(T0 + DAY, {})]
    assert sidereal_repeats(_days(2), quiet) == []  # nothing flagged on the later day


def test_repeating_spans_of_both_days_are_returned_for_a_warned_pair():
    from psdbound.campaign.sidereal import repeating_spans

    shift = SIDEREAL_DAY_S - DAY
    spans = {"G05": [(3600.0, 5400.0)], "G12": [(40000.0, 41200.0)]}
    later = {s: [(a + shift, b + shift) for a, b in v] for s, v in spans.items()}
    later["G20"] = [(70000.0, 70600.0)]  # not on the day before: stays ionosphere
    docs = [_doc(T0, spans), _doc(T0 + DAY, later)]
    keep = repeating_spans(_days(2), docs)
    assert sorted(keep) == [0, 1]
    assert [s[0] for s in keep[0]] == ["G05", "G12"]
    assert [s[0] for s in keep[1]] == ["G05", "G12"]
    assert keep[1][0][1] == pytest.approx(T0 + DAY + 3600.0 + shift)
    # below the warning's amounts (a single 5-minute repeat): nothing is kept
    small = {"G05": [(3600.0, 3900.0)]}
    small_later = {"G05": [(3600.0 + shift, 3900.0 + shift)]}
    assert repeating_spans(_days(2), [_doc(T0, small), _doc(T0 + DAY, small_later)]) == {}


def test_keep_spans_reach_the_day_s_screening_options():
    from psdbound.campaign.run import _with_keep_spans
    from psdbound.pipeline.config import FitConfig

    item = {"station": "S", "day": "2021-01-02", "options": {"bound": {"coverage": 0.99}}}
    again = _with_keep_spans(item, [("G05", 1.0, 2.0)])
    assert item["options"] == {"bound": {"coverage": 0.99}}  # the first pass's item unchanged
    cfg = FitConfig.from_dict(again["options"])
    assert cfg.screening.keep_spans == (("G05", 1.0, 2.0),) and cfg.bound.coverage == 0.99


def test_campaign_json_schema_describes_the_sidereal_sections():
    pytest.importorskip("jsonschema")
    from psdbound.results import load_schema, schema_errors

    schema = load_schema("campaign")
    props = schema["properties"]
    assert {"sidereal_repeat", "sidereal_kept"} <= set(props)
    doc = {
        "schema": "psdbound-campaign/2",
        "verdict": "bounded",
        "stations": [],
        "days": [],
        "held_out": [],
        "sidereal_repeat": [
            {
                "station": "S",
                "days": ["a", "b"],
                "flagged_s": 1.0,
                "repeated_s": 1.0,
                "expected_s": 0.1,
                "ratio": 10.0,
            }
        ],
        "sidereal_kept": [{"station": "S", "day": "b", "n_spans": 1, "kept_s": 600.0}],
    }
    assert schema_errors(doc, schema="campaign") == []
    doc["sidereal_kept"][0]["n_spans"] = "one"
    assert schema_errors(doc, schema="campaign")
