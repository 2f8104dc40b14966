"""Groups of short windows: the stated frequencies they do not resolve (spectra.unresolved)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import lfilter

from psdbound.spectra.bands import resolved_from_hz
from psdbound.spectra.bound import join_floors
from psdbound.spectra.estimators import estimate_psd
from psdbound.spectra.models import gm_psd_sampled
from psdbound.spectra.stated import fit_stated_bound
from psdbound.spectra.unresolved import cover_unresolved

DT = 1.0


def _gm(rng: np.random.Generator, n: int, sigma: float, tau: float) -> np.ndarray:
    """Gauss-Markov process at 1 s, stationary start."""
    phi = np.exp(-DT / tau)
    e = rng.normal(0.0, sigma * np.sqrt(1 - phi**2), n)
    e[0] = rng.normal(0.0, sigma)
    return lfilter([1.0], [1.0, -phi], e)


@pytest.mark.parametrize("seed", range(5))
def test_f2_times_any_gauss_markov_and_white_psd_rises(seed: int) -> None:
    """The premise of the ``f^-2`` rule: ``f^2 S(f)`` never falls, for sampled GM + white sums."""
    rng = np.random.default_rng(seed)
    f = np.linspace(1e-5, 0.5 / DT, 4000)
    s = sum(
        gm_psd_sampled(f, rng.uniform(0.1, 10.0), float(np.exp(rng.uniform(0.0, 8.0))), DT)
        for _ in range(3)
    ) + 2.0 * DT * rng.uniform(0.0, 5.0)
    assert np.all(np.diff(f**2 * s) >= -1e-12 * (f**2 * s)[1:])


def test_join_floors() -> None:
    a = (np.array([1.0, 2.0]), np.array([3.0, 4.0]))
    b = (np.array([5.0]), np.array([6.0]))
    f, s = join_floors(a, None, b)
    np.testing.assert_array_equal(f, [1.0, 2.0, 5.0])
    np.testing.assert_array_equal(s, [3.0, 4.0, 6.0])
    assert join_floors(None, None) is None


def _mixture(seed: int) -> tuple[list[np.ndarray], int]:
    """20 long windows of a fast process and 3 short ones of a slow, strong one."""
    rng = np.random.default_rng(seed)
    xs = [_gm(rng, 3600, 3e-3, 30.0) + rng.normal(0.0, 1e-3, 3600) for _ in range(20)]
    xs += [_gm(rng, 900, 6e-3, 600.0) + rng.normal(0.0, 1e-3, 900) for _ in range(3)]
    return xs, 20


def _stated(xs: list[np.ndarray], **options):
    psds = [estimate_psd(x, DT, method="multitaper") for x in xs]
    f_min = min(resolved_from_hz(p) for p in psds)
    return fit_stated_bound(psds, DT, f_min_hz=f_min, **options), psds


@pytest.mark.parametrize("seed", [0, 1, 4, 5, 6])
def test_a_group_of_short_windows_is_carried_down_to_f_min(seed: int) -> None:
    """Without the lowest-ordinate check, the short group's models hold the bound up.

    When the shape tests give the short windows a group of their own, the
    bound lies above that group's admitted models between ``f_min`` and their
    own resolution ``5 / 900 s``.
    """
    xs, n_long = _mixture(seed)
    sb, _ = _stated(xs)
    u = sb.unresolved
    assert u is not None and u.groups, "the short windows form a group of their own"
    for g, f_g in zip(u.groups, u.resolved_from_hz, strict=True):
        rows = np.flatnonzero(sb.limits.groups == g)
        assert rows.min() >= n_long  # only short windows
        assert f_g == pytest.approx(5.0 / 900.0)
    assert np.all(sb.fit.psd(u.f_hz) >= u.envelope_m2_hz * (1 - 1e-6))
    assert "carried down" in u.sentence()


def test_the_short_windows_truth_is_covered_where_they_do_not_resolve() -> None:
    """The short windows' truth (6 mm / 600 s + 1 mm) over ``[f_min, 5 / 900 s]``.

    Over 16 seeds, those in which the short windows form a group of their own
    (8): before the rule the bound lay under that truth in 3 of them (by up to
    a factor 0.64), after it in 1 (0.91: the model set holds the truth at 95 %,
    not always). Asserted: at least 6 such seeds, the rule covers at least 80 %
    of them, and fewer than the bound before it.
    """
    tried, under_before, under_after = 0, 0, 0
    for seed in range(16):
        xs, _ = _mixture(seed)
        sb, _ = _stated(xs)
        u = sb.unresolved
        if u is None or not u.groups:
            continue
        assert u.before is not None
        f = np.geomspace(float(sb.bands.edges_hz[0]), 5.0 / 900.0, 50)
        truth = gm_psd_sampled(f, 6e-3, 600.0, DT) + 2.0 * DT * 1e-6
        tried += 1
        under_before += bool(np.any(u.before.sampled_psd(f) < truth))
        under_after += bool(np.any(sb.fit.model.sampled_psd(f) < truth))
    assert tried >= 6
    assert under_after <= 0.2 * tried
    assert under_after < under_before


def test_without_a_model_set_the_limit_is_carried_down_along_f_minus_2() -> None:
    """No multitaper half-width given: the group's lowest limit times ``(f_lo / f)^2``."""
    xs, _ = _mixture(0)
    sb, psds = _stated(xs)
    fit, u = cover_unresolved(
        sb.fit, [resolved_from_hz(p) for p in psds], sb.bands, sb.limits, DT, smoothing_hz=0.0
    )
    assert u.groups and set(u.how) == {"f^-2"}
    g = u.groups[0]
    row = sb.limits.upper_m2_hz[g]
    k = int(np.flatnonzero(np.isfinite(row))[0])
    if sb.limits.band_span_hz is None:
        lo, hi = sb.bands.edges_hz[k], sb.bands.edges_hz[k + 1]
    else:
        lo, hi = sb.limits.band_span_hz[g, k]
    first = u.f_hz[: u.f_hz.size // len(u.groups)]
    expected = row[k] * (hi / lo) * (lo / first) ** 2
    np.testing.assert_allclose(u.envelope_m2_hz[: first.size], expected, rtol=1e-12)
    assert np.all(fit.psd(u.f_hz) >= u.envelope_m2_hz * (1 - 1e-6))


def test_equal_windows_have_no_unresolved_group() -> None:
    rng = np.random.default_rng(3)
    xs = [_gm(rng, 1800, 3e-3, 30.0) + rng.normal(0.0, 1e-3, 1800) for _ in range(10)]
    sb, _ = _stated(xs)
    assert sb.unresolved is not None and sb.unresolved.groups == ()
    assert sb.unresolved.floor() is None and sb.unresolved.sentence() == ""


def test_two_short_strong_windows_among_long_ones() -> None:
    """Two 5-min windows of 20 mm / 900 s among ten one-hour windows of 3 mm / 30 s, 1 s.

    Through :func:`psdbound.bound_series` (cut peers and this rule together):
    their truth is covered from ``f_min`` to Nyquist in 17 of 20 seeds (11 of 20
    before both steps, as little as 0.09 of it at ``f_min``; docs/method/bound.rst).
    """
    import psdbound

    covered = 0
    for seed in range(20):
        rng = np.random.default_rng(seed)
        xs = [_gm(rng, 3600, 3e-3, 30.0) + rng.normal(0.0, 1e-3, 3600) for _ in range(10)]
        xs += [_gm(rng, 300, 2e-2, 900.0) + rng.normal(0.0, 1e-3, 300) for _ in range(2)]
        res = psdbound.bound_series(xs, DT)
        f = np.geomspace(res.f_min_hz, 0.5 / DT, 300)
        truth = gm_psd_sampled(f, 2e-2, 900.0, DT) + 2.0 * DT * 1e-6
        covered += bool(np.all(res.bound.sampled_psd(f) >= truth))
    assert covered >= 16


def test_short_windows_in_a_resolving_group_are_counted_and_said() -> None:
    """Homogeneous windows of two lengths share a group: the short ones are counted and named.

    Their PSD between ``f_min`` (from the long windows) and their own resolution is stated
    through the group; the statement says so, with their number.
    """
    rng = np.random.default_rng(11)
    xs = [_gm(rng, 3600, 3e-3, 30.0) + rng.normal(0.0, 1e-3, 3600) for _ in range(12)]
    xs += [_gm(rng, 1200, 3e-3, 30.0) + rng.normal(0.0, 1e-3, 1200) for _ in range(5)]
    sb, psds = _stated(xs)
    u = sb.unresolved
    assert u is not None and sb.limits.n_groups == 1
    f_min = float(sb.bands.edges_hz[0])
    expected = sum(resolved_from_hz(p) > f_min * (1 + 1e-9) for p in psds)
    assert expected == 5
    assert (u.n_short, u.n_windows) == (5, 17)
    assert "5 of the 17 windows resolve only above" in u.sentence()
    assert u.to_dict()["short_windows"] == 5


def test_equal_windows_have_no_short_window() -> None:
    rng = np.random.default_rng(3)
    xs = [_gm(rng, 1800, 3e-3, 30.0) + rng.normal(0.0, 1e-3, 1800) for _ in range(6)]
    sb, _ = _stated(xs)
    assert sb.unresolved is not None and sb.unresolved.n_short == 0
