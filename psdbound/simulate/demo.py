"""The embedded demo data set: generated deterministically on first use into a cache.

The demo is the ``demo`` preset (4 h, 1 Hz, GPS L1C/L2W, two antennas 5 m
apart, nominal constellation, known multipath). Its files are about 9 MB
compressed, too large to commit, so they are simulated (about 6 s) into
``$PSDBOUND_CACHE/demo-<digest>/`` (default cache ``~/.cache/psdbound``)
the first time they are needed; the folder name carries the scenario digest
and the package version, so a changed scenario or simulator regenerates.
Generation writes into a temporary folder that is renamed when complete.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

from psdbound.simulate.scenario import Scenario, preset
from psdbound.simulate.simulator import simulate
from psdbound.version import __version__

__all__ = ["DemoData", "cache_dir", "demo_data", "SIMULATOR_FORMAT"]

#: Bumped whenever the simulator output changes for the same scenario (cache key).
SIMULATOR_FORMAT = "s2"


def cache_dir() -> Path:
    """Return psdbound's cache folder (``$PSDBOUND_CACHE`` or ``~/.cache/psdbound``)."""
    env = os.environ.get("PSDBOUND_CACHE")
    return Path(env) if env else Path.home() / ".cache" / "psdbound"


@dataclass(frozen=True)
class DemoData:
    """Paths of a generated demo data set.

    Attributes
    ----------
    folder : Path
        Where the files are.
    obs_paths : tuple of Path
        Antenna A and B RINEX 3 observation files.
    nav_path : Path
        RINEX 3 navigation file.
    truth_path, truth_json_path : Path
        Ground truth (CSV, gzip) and parameters (JSON).
    scenario : Scenario
        The preset used.
    """

    folder: Path
    obs_paths: tuple[Path, ...]
    nav_path: Path
    truth_path: Path
    truth_json_path: Path
    scenario: Scenario

    def truth_meta(self) -> dict:
        """Return the parameters, seed and injected slips recorded with the truth."""
        return json.loads(self.truth_json_path.read_text())


def _files(folder: Path, sc: Scenario) -> DemoData:
    return DemoData(
        folder=folder,
        obs_paths=(folder / f"{sc.name}-A_MO.rnx.gz", folder / f"{sc.name}-B_MO.rnx.gz"),
        nav_path=folder / f"{sc.name}_MN.rnx.gz",
        truth_path=folder / f"{sc.name}_truth.csv.gz",
        truth_json_path=folder / f"{sc.name}_truth.json",
        scenario=sc,
    )


def demo_data(
    *, regenerate: bool = False, folder: str | os.PathLike[str] | None = None
) -> DemoData:
    """Return the demo data set, simulating it first if it is not cached.

    Parameters
    ----------
    regenerate : bool, default False
        Simulate again even if cached files exist.
    folder : str or path-like, optional
        Where to put the files instead of the cache.

    Returns
    -------
    DemoData
        Paths of the observation, navigation and truth files.
    """
    sc = preset("demo")
    target = (
        Path(folder)
        if folder is not None
        else cache_dir() / f"demo-{sc.digest()[:12]}-{__version__}-{SIMULATOR_FORMAT}"
    )
    data = _files(target, sc)
    complete = all(p.is_file() for p in (*data.obs_paths, data.nav_path, data.truth_json_path))
    if complete and not regenerate:
        return data
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=".demo-", dir=target.parent))
    try:
        simulate(sc, tmp)
        if target.exists():
            shutil.rmtree(target)
        os.replace(tmp, target)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    return data
