"""The multipath the high-pass removes, end to end on a simulated ground reflection (issue 28).

A day at 30 s with a ground reflection 0.5 m below the antenna (amplitude
ratio 0.2: nearly all its multipath lies below the cutoff) and a twin day
without it (same seed: the difference of the two truth files is the
reflection's multipath). The fit must measure the reflection from the SNR,
model what its high-pass removes, and export a slow component whose PSD lies
above the removed part of the truth at every frequency.
"""

from __future__ import annotations

import gzip
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import psdbound
from psdbound.isolation import DF_SCALING, HighPass
from psdbound.simulate import Reflection, preset, simulate
from psdbound.spectra.models import gm_psd_sampled

DT = 30.0


def _day(out: Path, reflections):
    base = preset("short").replace(
        name="slow", duration_s=86400.0, interval_s=DT, systems="G", dual_antenna=False
    )
    mp = replace(
        base.multipath,
        sigma_gm_m=0.001,
        tau_s=30.0,
        sigma_wn_m=0.001,
        a=1.0,
        b=0.0,
        c_deg=10.0,
        reflections=tuple(reflections),
    )
    return simulate(base.replace(multipath=mp), out)


def _truth(res):
    path = next(Path(res.obs_paths[0]).parent.glob("*_truth.csv.gz"))
    with gzip.open(path, "rt") as fh:
        return np.genfromtxt(fh, delimiter=",", names=True, dtype=None, encoding=None)


def _removed_truth(d1, d0, mask_deg: float, cutoff_hz: float) -> list[np.ndarray]:
    """The reflection's DF multipath per continuous stretch, minus what the high-pass keeps."""
    x = DF_SCALING * ((d1["nu_1_m"] - d1["nu_2_m"]) - (d0["nu_1_m"] - d0["nu_2_m"]))
    hp, out = HighPass(), []
    for sat in np.unique(d1["sat"]):
        k = (d1["sat"] == sat) & (d1["elevation_deg"] >= mask_deg)
        t, v = d1["t_gps_s"][k], x[k]
        cuts = np.flatnonzero(np.diff(t) > 1.5 * DT) + 1
        for a, b in zip(np.r_[0, cuts], np.r_[cuts, t.size], strict=True):
            if b - a >= 60:
                s = v[a:b]
                y, keep = hp.apply(s - s.mean(), DT, cutoff_hz)
                out.append((s - y)[keep])
    return out


@pytest.mark.slow
def test_slow_component_covers_what_the_filter_removes(tmp_path):
    with_r = _day(tmp_path / "with", [Reflection("ground", 0.5, 0.2)])
    without = _day(tmp_path / "without", [])
    res = psdbound.fit(with_r.obs_paths[0], nav=with_r.nav_path)
    val = res.document["validation"]
    site, slow = val["site_reflection"], val["slow"]
    assert res.verdict == "bounded", res.verdict_reasons
    assert site["measured"]
    assert site["ground_height_m"] == pytest.approx(0.5, abs=0.05)
    assert site["alpha"] == pytest.approx(0.2, rel=0.15)
    rem = _removed_truth(
        _truth(with_r),
        _truth(without),
        res.config.arcs.elevation_mask_deg,
        res.document["cutoff"]["f_c_hz"],
    )
    rms_truth = float(np.sqrt(np.mean(np.concatenate(rem) ** 2)))
    assert 0.9 < slow["removed_rms_m"] / rms_truth < 1.4
    # the exported slow component lies above the removed truth's pooled periodogram everywhere
    n_pad = 1 << int(np.ceil(np.log2(2 * max(r.size for r in rem))))
    f = np.fft.rfftfreq(n_pad, DT)
    psd = sum(np.abs(np.fft.rfft(r, n_pad)) ** 2 * 2.0 * DT for r in rem) / sum(r.size for r in rem)
    s = res.error_model["slow"]
    assert s.sigma_m == pytest.approx(slow["sigma_m"]) and not s.elevation_mapped
    assert np.min(gm_psd_sampled(f, s.sigma_m, s.tau_s, DT) / np.maximum(psd, 1e-300)) >= 1.0
