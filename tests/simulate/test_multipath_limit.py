"""Injected multipath beyond the carrier-multipath limit at low elevation is said (a warning).

Reported: ``simulate --multipath sigma_gm_m=0.007`` with the default mapping
gives a mapped sigma of several centimetres at the 5-degree elevation mask,
beyond a quarter of the L1 wavelength (4.76 cm), without a word. The limit is
:func:`psdbound.screening.multipath_limit_m`, the one the screening uses.
"""

from __future__ import annotations

import math

import pytest

from psdbound.cli import main
from psdbound.io.signals import wavelength_m
from psdbound.screening import multipath_limit_m
from psdbound.simulate import MULTIPATH_SPEC_EXAMPLE, MultipathModel, preset
from psdbound.simulate.simulator import multipath_limit_problem

SHORT = ["simulate", "--preset", "short", "--duration-h", "0.02", "--single-antenna"]
L1_LIMIT = multipath_limit_m([wavelength_m("G01", "L1C")], 1.0)


def _with(spec: str, **changes):
    sc = preset("short")
    return sc.replace(multipath=MultipathModel.from_spec(spec, base=sc.multipath), **changes)


def test_the_limit_is_the_screening_quarter_wavelength():
    assert L1_LIMIT == pytest.approx(0.25 * 299792458.0 / 1575.42e6)
    assert 0.0475 < L1_LIMIT < 0.0477


@pytest.mark.parametrize("spec", ["tau_s=30", MULTIPATH_SPEC_EXAMPLE])
def test_presets_and_the_documented_example_are_within_the_limit(spec):
    assert multipath_limit_problem(preset("demo")) == ""
    assert multipath_limit_problem(_with(spec)) == ""


def test_beyond_the_limit_names_option_elevation_value_and_limit():
    sc = _with("sigma_gm_m=0.007")
    mp = sc.multipath
    sigma = mp.factor(5.0) * math.hypot(0.007, mp.sigma_wn_m)
    assert sigma > L1_LIMIT
    text = multipath_limit_problem(sc, "--multipath")
    assert text.startswith("--multipath: at 5 deg elevation (the elevation mask) the mapped ")
    assert f"{100 * sigma:.2f} cm, beyond the carrier-multipath limit 4.76 cm" in text
    assert "quarter of the GPS L1C wavelength); below 14.3 deg" in text
    # where the mapping crosses the limit: m(14.3 deg) sigma_z = limit
    c = mp.c_deg * math.sqrt(2 * math.log(mp.b / (L1_LIMIT / math.hypot(0.007, 0.001) - mp.a)))
    assert round(c, 1) == 14.3
    assert "at every elevation" in multipath_limit_problem(_with("sigma_gm_m=0.05"))
    assert multipath_limit_problem(_with("sigma_gm_m=0.007", elevation_mask_deg=20.0)) == ""


def test_simulate_cli_warns_and_still_writes(tmp_path, capsys):
    code = main(
        [str(a) for a in [*SHORT, "--multipath", "sigma_gm_m=0.007", "--out", tmp_path / "sim"]]
    )
    out, err = capsys.readouterr()
    assert code == 0 and len(out.split()) == 4
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("psdbound simulate: warning: --multipath: at 5 ")
    assert "beyond the carrier-multipath limit 4.76 cm" in lines[0]


def test_simulate_cli_within_the_limit_says_nothing(tmp_path, capsys):
    code = main([str(a) for a in [*SHORT, "--out", tmp_path / "sim"]])
    assert code == 0 and capsys.readouterr().err == ""
