"""The optional code-multipath stage of a fit: section, report, options, errors."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_OBS, shared_file

import psdbound
from psdbound.arcs.options import ArcOptions
from psdbound.aviation.options import CodeMultipathOptions
from psdbound.common.options import OptionError
from psdbound.errors import InputError
from psdbound.pipeline import FitConfig, stages
from psdbound.pipeline.code_stage import code_overbound
from psdbound.pipeline.config import InputsConfig
from psdbound.reports import render_html
from psdbound.results import schema_errors


@pytest.fixture(scope="module")
def demo_pair():
    """The default demo fit and the same fit with the code-multipath stage."""
    return psdbound.fit(), psdbound.fit(code_multipath={"codes": ("C1C",)})


def test_demo_section_schema_and_unchanged_carrier_bound(demo_pair):
    plain, with_code = demo_pair
    assert "code_multipath" not in plain.document and plain.code is None
    doc = with_code.document
    c = doc["code_multipath"]
    assert c["status"] == "computed" and c["codes"] == ["C1C"]
    assert c["n_samples"] == with_code.code.series.value_m.size > 1000
    bins = c["overbound"]["bins"]
    assert bins and all(b["sigma"] >= b["std"] * 0.5 and b["inflation"] > 0 for b in bins)
    assert set(c["qq"]) == {
        f"[{b['elevation_deg'][0]:g}, {b['elevation_deg'][1]:g}) deg" for b in bins
    }
    assert "code multipath C1C: overbound sigma (inflation)" in with_code.summary()
    assert "code multipath" not in plain.summary()
    # the carrier-phase chain does not see the code stage
    assert doc["bound"] == plain.document["bound"]
    assert doc["verdict"] == plain.document["verdict"]
    assert schema_errors(doc) == []
    # per-satellite RMS is the RMS of that satellite's samples
    s = with_code.code.series
    sats = np.array([s.arc_sats[k] for k in s.arc_id])
    for sat, rms in c["rms_by_satellite_m"].items():
        assert rms == pytest.approx(float(np.sqrt(np.mean(s.value_m[sats == sat] ** 2))))


def test_report_has_the_section_and_the_qq_figure(demo_pair):
    plain, with_code = demo_pair
    html = render_html(with_code.document)
    assert "Code multipath and its Gaussian overbound" in html
    assert "Q-Q per elevation bin" in html
    n_bins = len(with_code.document["code_multipath"]["overbound"]["bins"])
    assert html.count("<tr><td>[") >= n_bins
    assert "Code multipath and its Gaussian overbound" not in render_html(plain.document)


def test_reloaded_result_keeps_the_section(demo_pair, tmp_path):
    _, with_code = demo_pair
    again = psdbound.load(with_code.to_json(tmp_path / "r.json"))
    assert (
        again.document["code_multipath"]["overbound"]
        == with_code.document["code_multipath"]["overbound"]
    )


def test_options_checked_and_from_toml(tmp_path):
    with pytest.raises(OptionError, match="code"):
        CodeMultipathOptions(codes=("L1C",))
    with pytest.raises(OptionError, match="edges_deg"):
        CodeMultipathOptions(edges_deg=(30.0, 10.0))
    toml = tmp_path / "c.toml"
    toml.write_text('[code_multipath]\ncodes = ["C1C", "C5Q"]\nedges_deg = [10, 30, 90]\n')
    cfg = FitConfig.from_toml(toml)
    assert cfg.code_multipath.codes == ("C1C", "C5Q")
    assert cfg.code_multipath.edges_deg == (10.0, 30.0, 90.0)
    toml.write_text('[code_multipath]\ncodes = ["C1C"]\nmethod = "gauss"\n')
    with pytest.raises(OptionError, match=r"\[code_multipath\] method"):
        FitConfig.from_toml(toml)


def test_a_code_not_in_the_file_is_bad_input():
    with pytest.raises(InputError, match="C5Q"):
        psdbound.fit(code_multipath={"codes": ("C5Q",)})


def test_campaign_refuses_the_option_instead_of_ignoring_it(tmp_path):
    from psdbound.campaign import run_campaign

    with pytest.raises(InputError, match="code_multipath"):
        run_campaign(
            [tmp_path / "x.rnx"],
            [tmp_path / "n.rnx"],
            options={"code_multipath": {"codes": ["C1C"]}},
        )


def test_fit_cli_bad_code_is_exit_2(tmp_path):
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "psdbound",
            "fit",
            "--code-multipath",
            "L1C",
            "--out",
            str(tmp_path / "o"),
            "--quiet",
        ],
        capture_output=True,
        text=True,
        timeout=300,
        env=dict(os.environ),
    )
    assert r.returncode == 2, r.stderr
    assert "--code-multipath" in r.stderr and "C1C" in r.stderr
    assert not (tmp_path / "o").exists()


@pytest.fixture(scope="module")
def esbc_code():
    """The code stage alone on ESBC (GPS C1C with L1C/L2W), fit's default arc options."""
    obs, nav = shared_file(ESBC_OBS), shared_file(ESBC_NAV)
    inputs = stages.read_inputs(InputsConfig(obs=(str(obs),), nav=str(nav)), extra_codes=("C1C",))
    return code_overbound(inputs, options=CodeMultipathOptions(codes=("C1C",)), arcs=ArcOptions())


def test_esbc_code_multipath_is_physical_and_falls_with_elevation(esbc_code):
    c = esbc_code.details
    assert c["status"] == "computed"
    bins = c["overbound"]["bins"]
    assert len(bins) >= 4
    # a geodetic choke-ring station: decimetre-level C/A code multipath, not metres, not mm
    assert 0.05 < c["rms_m"] < 1.0
    for b in bins:
        assert 0.02 < b["std"] < 2.0
        assert b["inflation"] >= 0.9  # an overbound is not narrower than the core
    # code multipath (and its overbound) shrinks from low to high elevation
    assert bins[0]["sigma"] > 1.5 * bins[-1]["sigma"]
    assert bins[0]["std"] > bins[-1]["std"]
    # the first bin starts at the fit's 10 deg mask, not at the 5 deg edge
    assert min(esbc_code.series.elevation_deg) >= 10.0 - 1e-9
    assert c["edges_deg"][:2] == [10.0, 15.0] and bins[0]["elevation_deg"] == [10.0, 15.0]


def test_overbound_cli_on_esbc(tmp_path):
    obs, nav = shared_file(ESBC_OBS), shared_file(ESBC_NAV)
    out = tmp_path / "ob"
    out.mkdir()
    cmd = [
        sys.executable,
        "-m",
        "psdbound",
        "overbound",
        str(obs),
        "--nav",
        str(nav),
        "--code",
        "C1C",
        "--out",
        str(out),
    ]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600, env=dict(os.environ))
    assert r.returncode == 0, r.stderr
    doc = json.loads((out / "overbound.json").read_text())
    assert schema_errors(doc, schema="overbound") == []
    assert [b["elevation_deg"] for b in doc["overbound"]["bins"]][0] == [5.0, 15.0]
    assert all(b["inflation"] > 0.9 for b in doc["overbound"]["bins"])
    # issue 33: paired by default (no exempted core), per-bin sample sizes and confidence
    ob = doc["overbound"]
    assert ob["method"] == "paired" and ob["min_abs_z"] == 0.0
    for b in ob["bins"]:
        assert 1.0 <= b["n_eff"] <= b["n"] and b["confidence"] == 0.95 and b["bias"] >= 0
        assert b["sigma_upper"] >= b["sigma"] and b["inflation_upper"] >= b["inflation"]
    assert ob["bins"][-1]["n_eff"] < 0.5 * ob["bins"][-1]["n"]  # correlated at high elevation
    assert "n_eff" in r.stdout and "infl_up" in r.stdout
    assert doc["code_multipath"]["codes"] == ["C1C"] and doc["code_multipath"]["n_arcs"] > 20
    assert (out / "overbound_qq.png").stat().st_size > 10_000
    # too few samples in a bin: exit 2, the bin named, nothing written
    out2 = tmp_path / "ob2"
    out2.mkdir()
    r = subprocess.run(
        cmd[:-1] + [str(out2), "--min-samples", "10000000"],
        capture_output=True,
        text=True,
        timeout=600,
        env=dict(os.environ),
    )
    assert r.returncode == 2
    assert "elevation bin [5, 15) deg" in r.stderr
    assert list(out2.iterdir()) == []


def test_rinex2_pair_code_multipath_of_antenna_a():
    """RINEX 2 code names (P2) and a dual-antenna run: the code stage uses the first antenna."""
    from conftest import UPC1_OBS, UPC2_OBS, UPC_NAV

    files = [str(shared_file(n)) for n in (UPC1_OBS, UPC2_OBS)]
    inputs = stages.read_inputs(
        InputsConfig(obs=tuple(files), nav=str(shared_file(UPC_NAV)), pair=("UPC1", "UPC2")),
        extra_codes=("P2",),
    )
    assert inputs.method == "da"
    out = code_overbound(inputs, options=CodeMultipathOptions(codes="P2"), arcs=ArcOptions())
    c = out.details
    assert c["status"] == "computed" and c["signals"][:2] == ["P2", "L2"]
    assert "UPC1" in out.series.meta["source"]
    assert all(0.05 < b["sigma"] < 2.0 for b in c["overbound"]["bins"])


def test_overbound_cli_high_latitude_sparse_bin_is_named_not_fatal(tmp_path):
    """At 78.9 N few GPS satellites rise above 60 deg: that bin is left out and said so."""
    from conftest import NYA1_NAV, NYA1_OBS

    out = tmp_path / "nya"
    out.mkdir()
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "psdbound",
            "overbound",
            str(shared_file(NYA1_OBS)),
            "--nav",
            str(shared_file(NYA1_NAV)),
            "--code",
            "C1C",
            "--out",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=600,
        env=dict(os.environ),
    )
    assert r.returncode == 0, r.stderr
    assert "note: elevation bin [60, 90) deg holds" in r.stdout
    doc = json.loads((out / "overbound.json").read_text())
    assert [b["elevation_deg"] for b in doc["overbound"]["bins"]][-1] == [45.0, 60.0]
    assert doc["code_multipath"]["bins_left_out"][0].startswith("elevation bin [60, 90) deg")
    # the sparse bin is a property of the sky; the other bins still fall with elevation
    sig = [b["std"] for b in doc["overbound"]["bins"]]
    assert sig == sorted(sig, reverse=True)


def test_samples_in_full_bins():
    from psdbound.aviation import samples_in_full_bins

    el = np.r_[np.full(150, 10.0), np.full(20, 70.0), np.full(100, 90.0)]
    keep, notes = samples_in_full_bins(el, (5, 15, 60, 90), 100)
    assert keep.sum() == 270 and notes == []  # 120 in the closed last bin [60, 90]
    keep, notes = samples_in_full_bins(el, (5, 15, 60, 80, 90), 100)
    assert keep.sum() == 250 and notes == [
        "elevation bin [60, 80) deg holds 20 samples, fewer than 100: not overbounded"
    ]
