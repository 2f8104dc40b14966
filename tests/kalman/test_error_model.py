"""The complete error model: components, state-space export, refusals (issue 28, part 3)."""

from __future__ import annotations

import copy
import math
import warnings

import numpy as np
import pytest

import psdbound
from psdbound.kalman import Component, ErrorModel, GaussMarkovBound
from psdbound.spectra.models import gm_psd_sampled


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    res = psdbound.fit()
    path = res.to_json(tmp_path_factory.mktemp("em") / "result.json")
    return res, path


def test_fit_and_loaded_result_give_the_same_model(demo):
    res, path = demo
    em, again = res.error_model, psdbound.load(path).error_model
    assert [c.to_dict() for c in em.components] == [c.to_dict() for c in again.components]
    assert em.dt_s == again.dt_s == res.bound.dt_s
    assert em["gauss_markov"].sigma_m == res.bound.sigma_gm_m
    assert em["white"].sigma_m == res.bound.sigma_wn_m
    assert "below the lowest band" in em.low_frequency
    assert str(path) in again.source
    with pytest.raises(KeyError, match="no component"):
        em["nothing"]


def test_state_space_matches_the_bound_and_carries_p0(demo):
    res, _ = demo
    em = res.error_model
    b = res.bound
    ss = em.to_state_space()
    gm = GaussMarkovBound.from_params(b.sigma_gm_m, b.tau_s, b.sigma_wn_m, b.dt_s)
    phi, qd, r = gm.to_state_space()
    k = ss.states.index("gauss_markov")
    assert ss.phi[k, k] == pytest.approx(phi) and ss.q_m2[k, k] == pytest.approx(qd)
    assert ss.r_m2 == pytest.approx(r)
    assert ss.p0_m2[k, k] == pytest.approx(b.sigma_gm_m**2)
    # stationary: P0 = phi P0 phi + Q for every state
    assert np.allclose(ss.phi @ ss.p0_m2 @ ss.phi.T + ss.q_m2, ss.p0_m2, rtol=1e-12, atol=0)
    assert ss.states == tuple(c.name for c in em.components if c.kind == "gauss-markov")
    assert em.variance_m2() == pytest.approx(np.trace(ss.p0_m2) + ss.r_m2)
    # at an elevation the mapped components scale by m(el)^2, the slow one does not
    low = em.to_state_space(elevation_deg=10.0)
    m = em.factor(em["gauss_markov"], 10.0)
    assert m > 1.0 and low.p0_m2[k, k] == pytest.approx(m**2 * ss.p0_m2[k, k])
    if "slow" in ss.states:
        j = ss.states.index("slow")
        assert low.p0_m2[j, j] == pytest.approx(ss.p0_m2[j, j])


def test_sampled_psd_is_the_sum_of_its_components(demo):
    res, _ = demo
    em = res.error_model
    f = np.linspace(0.0, em.nyquist_hz, 200)
    want = res.bound.sampled_psd(f)
    if "slow" in [c.name for c in em.components]:
        s = em["slow"]
        want = want + gm_psd_sampled(f, s.sigma_m, s.tau_s, em.dt_s)
    assert np.allclose(em.sampled_psd(f), want, rtol=1e-12)
    with pytest.raises(psdbound.InputError):
        em.sampled_psd([2 * em.nyquist_hz])


def test_refusals_and_warnings(demo):
    res, _ = demo
    doc = copy.deepcopy(res.document)
    doc["verdict"], doc["verdict_reasons"] = "not-bounded", ["a stated reason"]
    em = ErrorModel.from_document(doc)
    with pytest.raises(psdbound.InputError, match="a stated reason"):
        em.to_state_space()
    assert em.to_state_space(allow_not_bounded=True).states
    good = res.error_model
    with pytest.warns(UserWarning, match="shorter than the data interval"):
        good.to_state_space(good.dt_s / 2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        good.to_state_space(2 * good.dt_s)  # a longer step is fine
    with pytest.warns(UserWarning, match="Nyquist"):
        good.psd([2 * good.nyquist_hz])
    del doc["error_model"]
    with pytest.raises(psdbound.InputError, match="fit again"):
        ErrorModel.from_document(doc)


def test_components_check_their_numbers():
    with pytest.raises(psdbound.InputError):
        Component("x", "pink", 0.001)
    with pytest.raises(psdbound.InputError):
        Component("x", "random-constant-per-arc", 0.001)
    with pytest.raises(psdbound.InputError):
        Component("x", "gauss-markov", 0.001, None)
    with pytest.raises(psdbound.InputError):
        Component("x", "white", -1.0)
    em = ErrorModel(
        (
            Component("gauss_markov", "gauss-markov", 0.003, 60.0),
            Component("white", "white", 0.001),
        ),
        1.0,
        1e-3,
    )
    ss = em.to_state_space(2.0)
    assert ss.phi[0, 0] == pytest.approx(math.exp(-2.0 / 60.0))
    assert em.variance_m2() == pytest.approx(0.003**2 + 0.001**2)


def test_parameter_set_holds_the_truth_and_the_bound_and_its_design_is_safe(demo):
    """Part 4: the uncertain-GM design is fed a set that contains the bound (and the truth)."""
    from psdbound.kalman import verify_design

    res, _ = demo
    truth = res.document["demo"]["injected"]
    gs = res.error_model.gauss_markov_set()
    b = res.bound
    assert gs.tau_lo_s <= b.tau_s <= gs.tau_hi_s and gs.sigma_hi_m >= b.sigma_gm_m
    assert gs.tau_lo_s <= truth["tau_s"] <= gs.tau_hi_s
    assert gs.sigma_lo_m <= truth["sigma_gm_m"] <= gs.sigma_hi_m
    # a one-state filter estimating a constant through the multipath: safe for every corner
    check = verify_design(
        gs.design(),
        [[1.0]],
        [[0.0]],
        [[1.0]],
        None,
        dt_s=b.dt_s,
        n_steps=int(6 * gs.tau_hi_s / b.dt_s),
        p0_base=[[100.0]],
    )
    assert check.bounded(), check.worst


def test_reading_only_the_bound_warns_about_the_slow_component(demo):
    res, path = demo
    if "slow" not in [c.name for c in res.error_model.components]:
        pytest.skip("this fit has no slow component")
    with pytest.warns(UserWarning, match="slow component"):
        GaussMarkovBound.from_result(path)


@pytest.mark.parametrize("elevation_deg", [-5.0, 90.5, 200.0, math.nan, math.inf])
def test_elevations_outside_0_90_are_refused(demo, elevation_deg):
    em = demo[0].error_model
    for call in (
        lambda: em.to_state_space(elevation_deg=elevation_deg),
        lambda: em.variance_m2(elevation_deg=elevation_deg),
        lambda: em.psd([0.01], elevation_deg=elevation_deg),
    ):
        with pytest.raises(psdbound.InputError, match=r"elevation_deg must lie in \[0, 90\]"):
            call()


@pytest.mark.parametrize("f_hz", [[-1.0], [math.nan], [0.01, math.nan], [math.inf], math.inf])
def test_frequencies_that_are_not_finite_and_non_negative_are_refused(demo, f_hz):
    em = demo[0].error_model
    with pytest.raises(psdbound.InputError, match="frequencies must"):
        em.psd(f_hz)
    with pytest.raises(psdbound.InputError, match="frequencies must"):
        em.sampled_psd(f_hz)


@pytest.mark.parametrize("f_hz", ["a", [0.01 + 1j], 0.01j])
def test_frequencies_that_are_not_real_numbers_are_named(demo, f_hz):
    em = demo[0].error_model
    for call in (em.psd, em.sampled_psd):
        with pytest.raises(psdbound.InputError, match="f_hz must be real numbers in Hz"):
            call(f_hz)
