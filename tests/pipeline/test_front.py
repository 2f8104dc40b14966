"""The library front door: psdbound.fit / FitResults / psdbound.load, and the stage chain."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys

import pytest

import psdbound
from psdbound.errors import InputError
from psdbound.pipeline import FitConfig, stages
from psdbound.pipeline.front import _config_from
from psdbound.pipeline.runner import run_stages

VOLATILE = ("created_utc", "run_time_s")


def _stable(doc):
    doc = dict(doc)
    prov = {k: v for k, v in doc["provenance"].items() if k not in VOLATILE}
    prov["configuration"] = {k: v for k, v in prov["configuration"].items() if k != "output"}
    doc["provenance"] = prov
    return doc


@pytest.fixture(scope="module")
def demo_fit():
    return psdbound.fit()


def test_library_and_cli_write_the_same_result(demo_fit, tmp_path):
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "psdbound",
            "fit",
            "--out",
            str(tmp_path / "cli"),
            "--no-pdf",
            "--quiet",
        ],
        capture_output=True,
        text=True,
        timeout=600,
        env=dict(os.environ),
    )
    assert r.returncode == 0, r.stderr
    cli = psdbound.load(tmp_path / "cli" / "result.json").document
    lib_path = demo_fit.to_json(tmp_path / "lib.json")
    lib = psdbound.load(lib_path).document
    assert _stable(lib) == _stable(cli)


def test_results_object(demo_fit, tmp_path):
    res = demo_fit
    assert res.bound.sigma_gm_m == res.document["bound"]["sigma_gm_m"] > 0
    assert res.bound.total_variance_m2 == pytest.approx(res.document["bound"]["total_variance_m2"])
    assert res.series is not None and res.series.n_arcs > 0
    assert len(res.windows) == res.document["windows"]["count"]
    text = res.summary()
    assert "sigma_GM" in text
    for w in res.warnings:  # every warning reaches the console summary
        assert w in text
    paths = res.report(tmp_path / "rep", pdf=False)
    assert sorted(p.name for p in (tmp_path / "rep").iterdir()) == ["report.html", "result.json"]
    again = psdbound.load(paths["result"])
    assert again.document == psdbound.load(paths["result"]).document
    assert again.bound == res.bound and again.series is None
    assert again.summary() == text


def test_stage_products_pickle(demo_fit):
    # campaigns ship the per-day stage results between Dask workers
    for name in ("inputs", "cutoff", "isolated", "screened", "windowed", "bounded", "validated"):
        obj = getattr(demo_fit, name)
        back = pickle.loads(pickle.dumps(obj))
        assert type(back) is type(obj)


def test_stages_compose_like_fit(demo_fit):
    # the runner stops where asked, and the stages run by hand give fit's products
    cfg = demo_fit.config
    run = run_stages(cfg, until="screened")
    assert run.windowed is None and run.bounded is None
    assert run.cutoff.f_c_hz == demo_fit.document["cutoff"]["f_c_hz"]
    mapping = stages.map_elevation(run.screened.series, cfg.mapping)
    assert mapping == demo_fit.windowed.mapping
    win = stages.window(run.screened, mapping=mapping, options=cfg.stationarity)
    res = stages.bound(
        win, spectra=cfg.spectra, options=cfg.bound, cutoff=run.cutoff, highpass=cfg.filter
    )
    assert res.bound.sigma_gm_m == demo_fit.bound.sigma_gm_m
    val = stages.validate(
        run.cutoff, inputs=run.inputs, isolated=run.isolated, arcs=cfg.arcs, options=cfg.validation
    )
    assert val.summary["max_removed_rms_m"] == demo_fit.validation["max_removed_rms_m"]
    with pytest.raises(InputError, match="unknown stage 'bound'"):
        run_stages(cfg, until="bound")


def test_options_by_section_or_unique_name():
    cfg = _config_from([], None, None, {"estimator": "welch", "cutoff": {"f_c_hz": 1e-3}})
    assert cfg.spectra.estimator == "welch" and cfg.cutoff.f_c_hz == 1e-3
    cfg = _config_from("a.rnx", "n.rnx", FitConfig(), {"min_window_s": 900.0})
    assert cfg.inputs.obs == ("a.rnx",) and cfg.stationarity.min_window_s == 900.0
    with pytest.raises(InputError, match="'alpha' is ambiguous"):
        _config_from([], None, None, {"alpha": 0.01})
    with pytest.raises(InputError, match="unknown option 'frobnicate'"):
        _config_from([], None, None, {"frobnicate": 1})


@pytest.mark.parametrize(("obs", "nav", "named"), [(1, None, "obs"), ("a.rnx", 123, "nav")])
def test_file_arguments_that_are_not_file_names_are_named(obs, nav, named):
    with pytest.raises(InputError, match=f"{named} must be a file name or a list of file names"):
        _config_from(obs, nav, None, {})


def test_import_psdbound_is_light():
    code = "import sys, psdbound; print('matplotlib' in sys.modules, 'scipy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"]


def test_kalman_bound_in_memory_equals_the_file_s(demo_fit, tmp_path):
    from psdbound.kalman import GaussMarkovBound

    path = demo_fit.to_json(tmp_path / "result.json")
    in_memory = demo_fit.kalman_bound()
    from_file = GaussMarkovBound.from_result(path)
    assert in_memory.to_state_space(1.0) == pytest.approx(from_file.to_state_space(1.0))
    assert (in_memory.sigma_gm_m, in_memory.tau_s, in_memory.sigma_wn_m) == (
        from_file.sigma_gm_m,
        from_file.tau_s,
        from_file.sigma_wn_m,
    )


def test_to_json_names_a_folder_and_replaces_a_file(demo_fit, tmp_path):
    with pytest.raises(InputError, match="result file is an existing folder"):
        demo_fit.to_json(tmp_path)  # was IsADirectoryError from the atomic rename
    target = tmp_path / "r.json"
    target.write_text("old")
    assert psdbound.load(demo_fit.to_json(target)).verdict == demo_fit.verdict


def test_library_misuse_is_an_input_error_before_any_work(tmp_path):
    """fit(config=dict), fit(progress=3), load(None): one clear InputError each."""
    with pytest.raises(InputError, match="config must be a psdbound.FitConfig"):
        psdbound.fit(config={"bound": {}})
    with pytest.raises(InputError, match="progress must be a callable"):
        psdbound.fit(progress=3)
    with pytest.raises(InputError, match="give the path of a result.json"):
        psdbound.load(None)


def test_a_prior_below_half_the_interval_is_refused_by_fit_too():
    """fit shares the bound's code path: tau_max_s below dt/2 (1 s demo) is bad input."""
    with pytest.raises(InputError, match="below the shortest time constant the bound searches"):
        psdbound.fit(tau_max_s=0.1)
