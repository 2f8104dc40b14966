"""Paired overbounds, effective sample size, and the bias carried to the VPL and the filter."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import signal, stats

from psdbound.aviation import (
    bias_bound_response,
    effective_sample_size,
    los_from_az_el,
    overbound_by_elevation,
    paired_bounding_functions,
    paired_overbound,
    projection_matrix,
    vpl,
)
from psdbound.aviation.sample_size import upper_tail
from psdbound.errors import InputError

N = 20_000


def _ar1(rng, phi, n):
    e = rng.normal(size=n)
    x = np.empty(n)
    x[0] = e[0] / np.sqrt(1 - phi**2)
    for k in range(1, n):
        x[k] = phi * x[k - 1] + e[k]
    return x


@pytest.mark.parametrize("phi", [0.0, 0.5, 0.9])
def test_effective_sample_size_of_ar1_matches_closed_form(phi):
    rng = np.random.default_rng(11)
    n = 60_000
    n_eff, tau = effective_sample_size(_ar1(rng, phi, n))
    expect = n * (1 - phi) / (1 + phi)
    assert n_eff == pytest.approx(expect, rel=0.10)  # Monte Carlo error of tau_int: a few %
    assert tau == pytest.approx(n / n_eff)


def test_effective_sample_size_never_crosses_segments():
    rng = np.random.default_rng(3)
    pieces = [_ar1(rng, 0.8, 2000) + 50.0 * k for k in range(10)]  # offsets between pieces
    x, ids = np.concatenate(pieces), np.repeat(np.arange(10), 2000)
    n_seg, _ = effective_sample_size(x, segment_id=ids)
    assert n_seg == pytest.approx(20_000 * 0.2 / 1.8, rel=0.15)
    n_one, _ = effective_sample_size(x)  # joined: the offsets look like a long correlation
    assert n_one < 0.2 * n_seg


def _ar1_batch(rng, phi, n, m):
    """``m`` stationary AR(1) series of ``n`` unit-variance Gaussian samples (rows)."""
    e = rng.normal(size=(m, n))
    e[:, 0] /= np.sqrt(1.0 - phi**2)
    return signal.lfilter([1.0], [1.0, -phi], e, axis=1) * np.sqrt(1.0 - phi**2)


@pytest.mark.parametrize("phi", [0.9, 0.98])
def test_upper_tail_with_n_eff_covers_the_true_tail_of_ar1_series(phi):
    # coverage of the 95 % upper bound of a tail probability t from n correlated samples:
    # with n_eff it must cover t at least 95 % of the time; counting the n samples as
    # independent must not (the check can fail)
    rng = np.random.default_rng(int(1000 * phi))
    n, draws = 5000, 1000
    hit = {t: [] for t in (1e-2, 1e-3)}
    naive = {t: [] for t in hit}
    for _ in range(draws // 100):
        for x in _ar1_batch(rng, phi, n, 100):
            n_eff, _ = effective_sample_size(x)
            for t in hit:
                k = np.count_nonzero(x > stats.norm.isf(t)) / n
                hit[t].append(upper_tail(k, n_eff, 0.95) >= t)
                naive[t].append(upper_tail(k, n, 0.95) >= t)
    slack = 3.0 * np.sqrt(0.95 * 0.05 / draws)
    for t in hit:
        assert np.mean(hit[t]) >= 0.95 - slack
        assert np.mean(naive[t]) < 0.9


MIXTURE = (0.9, 1.0, 0.1, 3.0)  # weight, sigma of a narrow and a wide zero-mean component


def _mixture_cdf(x, shift=0.0):
    w1, s1, w2, s2 = MIXTURE
    return w1 * stats.norm.cdf(x - shift, scale=s1) + w2 * stats.norm.cdf(x - shift, scale=s2)


def _mixture_draw(rng, n, shift=0.0):
    w1, s1, _, s2 = MIXTURE
    wide = rng.random(n) > w1
    return shift + np.where(wide, s2, s1) * rng.normal(size=n)


CASES = {
    "student_t3": (lambda rng, n: 0.4 * rng.standard_t(3, n), lambda x: stats.t.cdf(x / 0.4, 3)),
    "mixture_biased": (lambda rng, n: _mixture_draw(rng, n, 0.3), lambda x: _mixture_cdf(x, 0.3)),
}


def _holds(cdf, x, b, s):
    """Both conditions of the pair ``(b, s)`` against a CDF at the points x (whole line)."""
    g_left, g_right = paired_bounding_functions(x, b, s)
    f = cdf(x)
    return f <= g_left + 1e-12, (1.0 - f) <= g_right + 1e-12


@pytest.mark.parametrize("case", sorted(CASES))
def test_paired_overbound_holds_against_the_true_cdf(case):
    draw, cdf = CASES[case]
    res = overbound_by_elevation(draw(np.random.default_rng(5), N), min_samples=10)
    (bin_,) = res.bins
    assert res.method == "paired" and res.min_abs_z == 0.0
    assert bin_.n_eff == pytest.approx(N, rel=0.1)  # independent draws
    # the bound at 95 % confidence holds on both sides of the whole line wherever the
    # sample had support (probabilities >= 1/n on either side)
    grid = np.linspace(-40.0, 40.0, 8001)
    f = cdf(grid)
    inside = (f >= 1.0 / N) & (f <= 1.0 - 1.0 / N)
    left, right = _holds(cdf, grid, bin_.bias_upper, bin_.sigma_upper)
    assert left[inside].all() and right[inside].all()
    # a plain Gaussian pair with the same numbers does not: its CDFs never reach 0 or 1
    plain_left = f <= stats.norm.cdf((grid + bin_.bias_upper) / bin_.sigma_upper)
    assert not plain_left[inside].all()
    assert bin_.sigma_upper >= bin_.sigma and bin_.inflation_upper >= bin_.inflation > 1.0


def _half_gaussian_atom(rng, n, scale):
    """Half the probability at 0, half a left half-Gaussian ``-|Z| scale``."""
    return np.where(rng.random(n) < 0.5, 0.0, -scale * np.abs(rng.normal(size=n)))


def _half_gaussian_atom_cdf(x, scale):
    return np.where(x < 0.0, stats.norm.cdf(x / scale), 1.0)


def _mc_exceeds(y, bias, sigma, probs=(1e-2, 1e-3, 1e-4, 1e-5)):
    """Tail levels at which a Monte Carlo sample ``y`` is significantly beyond the pair.

    At each probability ``p`` (resolved: ``p n >= 10``) the left threshold of
    ``N(-bias, sigma)`` and the right one of ``N(+bias, sigma)`` are counted; a count
    above the binomial 1 - 1e-6 quantile means the convolved pair does not bound ``y``.
    """
    n = y.size
    bad = []
    for p in probs:
        if p * n < 10:
            continue
        limit = stats.binom.ppf(1.0 - 1e-6, n, p)
        low = np.count_nonzero(y <= -bias + sigma * stats.norm.ppf(p))
        high = np.count_nonzero(y >= bias + sigma * stats.norm.isf(p))
        bad += [("left", p)] * int(low > limit) + [("right", p)] * int(high > limit)
    return bad


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_half_gaussian_with_point_mass_survives_convolution(sign):
    # an error with half its probability at 0 and a left half-Gaussian: checked on half the
    # line, the pair (0, sigma) passes, and the sum of two such errors is not bounded by the
    # convolved pair; checked on the whole line, the point mass needs a plateau wide enough
    rng = np.random.default_rng(33)
    scales = (1.0, 0.3)
    pairs = [paired_overbound(_half_gaussian_atom(rng, N, s)) for s in scales]
    for (b, s), scale in zip(pairs, scales, strict=True):
        assert b >= s / (2.0 * stats.norm.pdf(0.0)) * (1.0 - 1e-9)  # G_L(0) = 1 needs it
        grid = np.linspace(-6.0 * scale, 1.0, 2001)
        left, right = _holds(lambda x, sc=scale: _half_gaussian_atom_cdf(x, sc), grid, b, s)
        f = _half_gaussian_atom_cdf(grid, scale)
        assert left[f >= 1.0 / N].all() and right.all()
    m = 1_000_000
    y = _half_gaussian_atom(rng, m, scales[0]) + sign * _half_gaussian_atom(rng, m, scales[1])
    bias = pairs[0][0] + pairs[1][0]
    sigma = float(np.hypot(pairs[0][1], pairs[1][1]))
    assert _mc_exceeds(y, bias, sigma) == []
    if sign > 0:
        # the half-line pair of the exact distribution, (0, scale), fails the same check
        assert ("left", 1e-2) in _mc_exceeds(y, 0.0, float(np.hypot(*scales)))
        # and the whole-line conditions reject it: F(0) = 1 but G_L(0) = 1/2
        left, _ = _holds(lambda x: _half_gaussian_atom_cdf(x, 1.0), np.array([0.0]), 0.0, 1.0)
        assert not left.all()


def test_paired_overbound_survives_convolution_monte_carlo():
    rng = np.random.default_rng(21)
    (t_draw, _), (m_draw, _) = CASES["student_t3"], CASES["mixture_biased"]
    up = {}
    for name, draw in (("t", t_draw), ("m", m_draw)):
        (b,) = overbound_by_elevation(draw(rng, N), min_samples=10).bins
        up[name] = (b.bias, b.sigma)
    bias = up["t"][0] + up["m"][0]
    sigma = float(np.hypot(up["t"][1], up["m"][1]))
    n = 1_000_000
    for sign in (1.0, -1.0):  # a sum and a difference (a negative projection coefficient)
        assert _mc_exceeds(t_draw(rng, n) + sign * m_draw(rng, n), bias, sigma) == []


@pytest.mark.parametrize("m0", [-0.7, 0.4])
def test_shifted_sample_bias_grows_by_the_shift(m0):
    base = 0.5 * np.random.default_rng(4).standard_t(4, N)
    base -= np.median(base)
    b0, s0 = paired_overbound(base)
    b1, s1 = paired_overbound(base + m0)
    assert b1 == pytest.approx(b0 + abs(m0), abs=1e-9)
    assert s1 == pytest.approx(s0, rel=1e-9)


def test_biased_samples_move_the_vpl_by_sum_abs_s_abs_m():
    rng = np.random.default_rng(8)
    az = np.array([0.0, 72.0, 144.0, 216.0, 288.0, 40.0])
    el = np.array([15.0, 30.0, 45.0, 60.0, 75.0, 88.0])
    base = 0.5 * rng.standard_t(5, 5000)
    base -= np.median(base)
    m = np.array([0.4, -0.25, 0.0, 0.1, -0.6, 0.3])  # one bias per satellite
    b0, s0 = paired_overbound(base)
    pairs = [paired_overbound(base + mi) for mi in m]
    assert [b for b, _ in pairs] == pytest.approx(b0 + np.abs(m), abs=1e-12)
    assert [s for _, s in pairs] == pytest.approx(np.full(m.size, s0), rel=1e-12)
    u = los_from_az_el(az, el)
    sig = np.full(el.size, s0)
    sv = projection_matrix(u, sig)[2]
    h0, eph = vpl(u, sig, k_md_e=5.0, bias_m=np.full(el.size, b0))
    h0m, ephm = vpl(u, sig, k_md_e=5.0, bias_m=[b for b, _ in pairs])
    shift = float(np.sum(np.abs(sv) * np.abs(m)))
    assert h0m - h0 == pytest.approx(shift, rel=1e-9)
    assert ephm - eph == pytest.approx(shift, rel=1e-9)
    with pytest.raises(InputError, match="bias_m"):
        vpl(u, sig, k_md_e=5.0, bias_m=[-1.0] * el.size)


def test_bias_bound_through_the_filter_equals_least_squares_at_first_epoch():
    # static position + clock, no process noise, diffuse prior: the first update is least
    # squares, so the worst-case mean error of each state is sum_i |S_ji| B_i
    az = np.array([0.0, 90.0, 180.0, 270.0, 45.0])
    el = np.array([20.0, 35.0, 50.0, 65.0, 80.0])
    u = los_from_az_el(az, el)
    g = np.column_stack([-u, np.ones(el.size)])
    sig = np.array([0.9, 0.7, 0.5, 0.4, 0.3])
    bound = np.array([0.3, 0.0, 0.2, 0.1, 0.25])
    w = bias_bound_response(
        np.eye(4), np.zeros((4, 4)), g, np.diag(sig**2), bound, n_steps=3, p0=1e10 * np.eye(4)
    )
    s = projection_matrix(u, sig)
    assert w[0] == pytest.approx(np.abs(s) @ bound, rel=1e-6)
    assert w[-1] == pytest.approx(np.abs(s) @ bound, rel=1e-6)  # constant bias: stays


def test_bad_options():
    with pytest.raises(InputError, match="confidence"):
        overbound_by_elevation(np.zeros(200) + np.arange(200), confidence=1.0)
    with pytest.raises(InputError, match="k_weight"):
        paired_overbound(np.arange(10.0), k_weight=0.0)
