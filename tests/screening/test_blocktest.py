"""The single-block test measured on the day's own blocks (issue 29: a stated rate that holds)."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.screening.blocktest import block_test, tail_note
from psdbound.screening.null import fit_null, local_exceedance


def _day(rng, n, nu, heavy_below_deg=None):
    """Blocks of multipath alone: scaled chi-square ROTI, optionally heavy-tailed low down."""
    el = rng.uniform(10.0, 85.0, n)
    s = 0.02 + 0.2 * np.exp(-el / 15.0)  # ROT sd, TECU/min
    u = rng.chisquare(nu, n) / nu
    if heavy_below_deg is not None:  # an F-like tail: the chi-square over a random scale
        low = el < heavy_below_deg
        u[low] = u[low] / (rng.chisquare(3.0, low.sum()) / 3.0)
    return el, s * np.sqrt(u)


def _blocks(el, roti, k=20):
    return [
        {"el": e, "roti": r}
        for e, r in zip(np.array_split(el, k), np.array_split(roti, k), strict=True)
    ]


@pytest.mark.parametrize("p", [0.01, 0.05])
def test_upper_limit_covers_the_true_exceedance(p):
    """Bernoulli exceedances: the one-sided 95 % limit lies above p in >= 95 % of windows."""
    rng = np.random.default_rng(int(1000 * p))
    below = total = 0
    for _ in range(200):
        el = rng.uniform(10.0, 90.0, 600)
        m = local_exceedance(rng.random(el.size) < p, el)
        below += int(np.sum(m["upper"] < p))
        total += m["upper"].size
    assert below / total <= 0.05 + 3 * np.sqrt(0.05 * 0.95 / 200)  # per window, 200 days


def test_no_note_when_the_null_is_the_truth():
    rng = np.random.default_rng(3)
    notes = 0
    for _ in range(20):
        el, roti = _day(rng, 2300, 7.0)
        null = fit_null(roti, el)
        test = block_test(
            null, lambda e, n=null: n.threshold(e, 2.5e-4), _blocks(el, roti), 2.5e-4, 0.0
        )
        assert test["measured"]["blocks"].sum() > 0
        notes += tail_note(test) is not None
    assert notes <= 1  # Bonferroni over the windows, an order of magnitude above the stated


def test_a_heavy_tail_at_low_elevation_is_measured_and_said():
    """As on real quiet days: the null's quantile is exceeded far more often than stated."""
    rng = np.random.default_rng(11)
    el, roti = _day(rng, 2300, 7.0, heavy_below_deg=25.0)
    null = fit_null(roti, el)
    share = 2.5e-4
    test = block_test(null, lambda e: null.threshold(e, share), _blocks(el, roti), share, 0.0)
    m = test["measured"]
    low = m["elevation_deg"] < 20.0
    assert np.all(m["upper"] >= m["exceeded"] / m["blocks"])
    assert m["upper"][low].max() > 10 * share
    note = tail_note(test)
    assert note is not None and "heavier than the null" in note
    assert float(note.split("but at ")[1].split(" ")[0].split("-")[0]) < 25.0


def test_no_note_where_the_significance_level_sets_the_threshold():
    rng = np.random.default_rng(12)
    el, roti = _day(rng, 2300, 7.0, heavy_below_deg=25.0)
    null = fit_null(roti, el)
    level = float(np.quantile(roti, 0.999))  # a significance level above almost every block
    test = block_test(
        null,
        lambda e: np.maximum(level, null.threshold(e, 2.5e-4)),
        _blocks(el, roti),
        2.5e-4,
        level,
    )
    assert tail_note(test) is None


def test_without_a_null_there_is_no_test():
    assert block_test(None, lambda e: e, [], 1e-3, 0.15) is None
    assert tail_note(None) is None


def test_no_note_on_a_disturbed_day():
    """An untrusted (heavy-tailed) null means a disturbed day: exceedances are ionosphere."""
    from dataclasses import replace

    rng = np.random.default_rng(11)
    el, roti = _day(rng, 2300, 7.0, heavy_below_deg=25.0)
    null = replace(fit_null(roti, el), dof=2.0)
    assert not null.trusted
    test = block_test(null, lambda e: null.threshold(e, 2.5e-4), _blocks(el, roti), 2.5e-4, 0.0)
    assert test["measured"]["exceeded"].sum() > 0 and tail_note(test) is None
