"""Shared fixtures: the real station files in ../shared/data/rinex."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

# tiny matrices everywhere: BLAS threads only add contention on the 2-core machines
# (effective because nothing has loaded numpy's BLAS before conftest is imported)
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

_REPO = Path(__file__).resolve().parents[1]
# tests/ mirrors the packages (tests/io, tests/kalman, ...); shared helpers live here
sys.path.insert(0, str(Path(__file__).resolve().parent))
SHARED_RINEX = (
    Path(os.environ.get("PSDBOUND_SHARED_DATA", _REPO.parent / "shared" / "data")) / "rinex"
)


def shared_file(name: str) -> Path:
    """Path of a file in ../shared/data/rinex; skip the test when absent."""
    p = SHARED_RINEX / name
    if not p.is_file():
        pytest.skip(f"real data not available: {p} (../shared/data is absent)")
    return p


ESBC_OBS = "ESBC00DNK_R_20201770000_01D_30S_MO.crx.gz"
ESBC_NAV = "ESBC00DNK_R_20201770000_01D_MN.rnx.gz"
ESBC_SP3 = "GRG0MGXFIN_20201770000_01D_15M_ORB.SP3.gz"
NYA1_OBS = "NYA100NOR_S_20241240000_01D_30S_MO.crx.gz"
NYA1_NAV = "NYA100NOR_S_20241240000_01D_GN.rnx.gz"
GRAS_OBS = "GRAS00FRA_R_20223151700_15M_01S_MO.crx.gz"
UPC1_OBS = "UPC10770.10o.gz"
UPC2_OBS = "UPC20770.10o.gz"
UPC_NAV = "brdc0770.10n.gz"


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    """Say in one visible line when tests on the shared real data were skipped."""
    skipped = terminalreporter.stats.get("skipped", [])
    real = [r for r in skipped if "real data not available" in str(r.longrepr)]
    if real:
        terminalreporter.write_line(
            f"REAL DATA NOT TESTED: {len(real)} test(s) skipped because {SHARED_RINEX} is absent "
            "(the regression pins on the shared station files did not run)",
            yellow=True,
            bold=True,
        )
