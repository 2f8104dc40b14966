"""End to end: `psdbound fit` on RINEX 4 files gives the bound of the RINEX 3 files they come from.

The first 6 h of ESBC (RINEX 3.05 observations, Hatanaka) and the day's mixed
navigation file, converted to RINEX 4 by ``tests/io/rinex4_samples.py``
(observations as Hatanaka, navigation with ``> EPH`` records and STO, EOP,
ION and CNAV records to skip).
"""

from __future__ import annotations

import gzip
import json
import os
import subprocess
import sys
from pathlib import Path

import hatanaka
import pytest
from conftest import ESBC_NAV, ESBC_OBS, shared_file

from psdbound.io._source import read_bytes

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "io"))
from rinex4_samples import cut_obs, nav_to_v4, obs_to_v4  # noqa: E402


def _fit(obs: Path, nav: Path, out: Path) -> dict:
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "psdbound",
            "fit",
            str(obs),
            "--nav",
            str(nav),
            "--out",
            str(out),
            "--no-pdf",
            "--quiet",
        ],
        capture_output=True,
        text=True,
        timeout=600,
        env=dict(os.environ),
    )
    assert r.returncode == 0, r.stderr
    return json.loads((out / "result.json").read_text())


@pytest.mark.realdata
@pytest.mark.slow
def test_fit_on_rinex4_gives_the_rinex3_bound(tmp_path):
    text3 = cut_obs(read_bytes(shared_file(ESBC_OBS)), 720)  # 6 h at 30 s
    obs3 = tmp_path / "ESBC3.rnx"
    obs3.write_bytes(text3)
    obs4 = tmp_path / "ESBC4.crx"
    obs4.write_bytes(hatanaka.rnx2crx(obs_to_v4(text3, "4.01")))
    nav3 = shared_file(ESBC_NAV)
    nav4 = tmp_path / "ESBC4_MN.rnx"
    nav4.write_text(nav_to_v4(gzip.decompress(nav3.read_bytes()).decode()))

    a = _fit(obs3, nav3, tmp_path / "v3")
    b = _fit(obs4, nav4, tmp_path / "v4")
    assert b["bound"] == a["bound"]
    for key in ("sampling", "cutoff", "windows", "verdict_checks", "headline"):
        assert b[key] == a[key], key
    assert 1e-3 < a["bound"]["sigma_gm_m"] < 0.05 and a["bound"]["tau_s"] > 0
    skipped = [w for w in b["warnings"] if "RINEX 4 navigation record(s) skipped" in w]
    assert len(skipped) == 1 and "EPH G CNAV 1" in skipped[0]
    same = [w.replace("ESBC4.crx", "ESBC3.rnx") for w in b["warnings"] if w not in skipped]
    assert same == a["warnings"]  # the files' names aside (the systems not analysed)
