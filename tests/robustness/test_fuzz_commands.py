"""Seeded mutation fuzzing of the other commands: ``overbound`` and ``budget`` (issue 30).

``overbound`` reads error samples (CSV/text) or, with ``--code``, a RINEX
observation file; ``budget`` reads a navigation file for its geometry. Mutated
copies go through the command line in-process: every run ends with exit 0, 2
or 3, without a traceback or a leaked numpy warning, and a bad input gives one
line naming the file. The cases come from fixed seeds (a failure names its
case).
"""

from __future__ import annotations

import hashlib

import numpy as np
import pytest
from fuzzbases import bases  # noqa: F401 - the fixture
from fuzzlib import NAV_MUTATIONS, OBS_MUTATIONS, check_run, run_cli, write

pytestmark = pytest.mark.realdata


def _rng(*parts: object) -> np.random.Generator:
    seed = int.from_bytes(hashlib.sha256("/".join(map(str, parts)).encode()).digest()[:8], "little")
    return np.random.default_rng(seed)


def _samples_csv(rng: np.random.Generator, n: int = 3000) -> list[str]:
    el = rng.uniform(5.0, 90.0, n)
    err = rng.normal(0.0, 0.3, n) * (1.0 + 2.0 * np.exp(-el / 15.0))
    return ["elevation,error"] + [f"{e:.3f},{x:.5f}" for e, x in zip(el, err, strict=True)]


def _mutate_csv(lines: list[str], kind: str, rng: np.random.Generator) -> tuple[str, str]:
    """One mutation of a samples table: (text, what was done)."""
    body = list(lines)
    k = int(rng.integers(1, len(body)))
    if kind == "token":
        body[k] = body[k].replace(".", rng.choice(["x", ",", ";", " ", "e+"]), 1)
    elif kind == "nan":
        body[k] = rng.choice(["nan,0.1", "45,nan", "inf,1", "45,-inf", ","])
    elif kind == "header":
        body[0] = rng.choice(["", "el,err", "error", "elevation;error", "\ufeffelevation,error"])
    elif kind == "truncate":
        body = body[: int(rng.integers(0, 4))]
    elif kind == "range":
        body[k] = rng.choice(["-30,0.1", "120,0.1", "45,1e308", "45,-1e308"])
    elif kind == "binary":
        return "".join(map(chr, rng.integers(0, 256, 300))), "random bytes"
    return "\n".join(body) + "\n", f"{kind} at line {k + 1}"


def test_overbound_base_samples_are_clean(tmp_path):
    """The unmutated table is overbounded (so every refusal above comes from a mutation)."""
    path = tmp_path / "samples.csv"
    path.write_text("\n".join(_samples_csv(_rng("base"))) + "\n")
    r = run_cli(["overbound", path, "--out", tmp_path / "out"])
    assert r.code == 0 and not r.warnings, r.err
    assert (tmp_path / "out" / "overbound.json").is_file()


CSV_KINDS = ("token", "nan", "header", "truncate", "range", "binary")
CSV_CASES = [(k, i) for k in CSV_KINDS for i in range(3)]


@pytest.mark.parametrize(("kind", "index"), CSV_CASES, ids=[f"{k}-{i}" for k, i in CSV_CASES])
def test_fuzz_overbound_samples(tmp_path, kind, index):
    rng = _rng("overbound", kind, index)
    text, what = _mutate_csv(_samples_csv(rng), kind, rng)
    name = f"samples-{kind}-{index}.csv"
    path = tmp_path / name
    path.write_text(text, encoding="utf-8", errors="surrogateescape")
    out = tmp_path / "out"
    r = run_cli(["overbound", path, "--out", out], timeout_s=60)
    problem = check_run(r, name, allowed=(0, 2, 3))
    if problem is None and r.code == 2:
        assert not out.exists(), "a refused run left an output folder"
    assert problem is None, f"{name} ({what}): {problem}"


OBS_KINDS = ("byte_flip", "obs_types", "epoch_order", "interval")


@pytest.mark.slow
@pytest.mark.parametrize("kind", OBS_KINDS)
def test_fuzz_overbound_code(bases, tmp_path, kind):  # noqa: F811
    rng = _rng("overbound-code", kind)
    data, what = OBS_MUTATIONS[kind](bases.esbc_fit, rng)
    name = f"code-{kind}.rnx"
    path = write(tmp_path / name, data)
    r = run_cli(
        [
            "overbound",
            path,
            "--code",
            "C1C",
            "--nav",
            bases.esbc_nav_path,
            "--out",
            tmp_path / "out",
        ],
        timeout_s=300,
    )
    problem = check_run(r, name, allowed=(0, 2, 3))
    assert problem is None, f"{name} ({what}): {problem}"


NAV_CASES = [(k, i) for k in NAV_MUTATIONS for i in range(2)]


@pytest.mark.parametrize(("kind", "index"), NAV_CASES, ids=[f"{k}-{i}" for k, i in NAV_CASES])
def test_fuzz_budget_nav(bases, tmp_path, kind, index):  # noqa: F811
    rng = _rng("budget", kind, index)
    data, what = NAV_MUTATIONS[kind](bases.esbc_nav, rng)
    name = f"budget-{kind}-{index}.rnx"
    path = write(tmp_path / name, data)
    r = run_cli(
        [
            "budget",
            "--k-md-e",
            "5",
            "--nav",
            path,
            "--position",
            "55.49,8.45,60",
            "--start",
            "2020-06-25T00:00:00",
            "--hours",
            "1",
            "--step-s",
            "900",
            "--out",
            tmp_path / "out",
        ],
        timeout_s=120,
    )
    problem = check_run(r, name, allowed=(0, 2))
    assert problem is None, f"{name} ({what}): {problem}"


@pytest.fixture(scope="module")
def campaign_days(tmp_path_factory):
    """Two simulated 6-h days of one station, as ``simulate`` names them (plain RINEX)."""
    import gzip

    from psdbound.simulate import preset, simulate

    root = tmp_path_factory.mktemp("fuzz-campaign")
    obs, nav = [], []
    for k, start in enumerate(("2020-11-24T06:00:00", "2020-11-25T06:00:00")):
        sc = preset("demo").replace(
            name="FUZZ",
            start_gps=start,
            duration_s=6 * 3600.0,
            interval_s=30.0,
            dual_antenna=False,
            seed=31 + k,
        )
        res = simulate(sc, root / f"sim{k}")
        obs.append(gzip.decompress(res.obs_paths[0].read_bytes()))
        nav.append(res.nav_path)
    return obs, nav


CAMPAIGN_KINDS = ("byte_flip", "truncate", "obs_types", "epoch_date", "interval")


@pytest.mark.slow
@pytest.mark.parametrize("kind", CAMPAIGN_KINDS)
def test_fuzz_campaign_one_day_mutated(campaign_days, tmp_path, kind):
    """A campaign with one damaged day: exit 0, 2 or 3, never a traceback or exit 1."""
    obs, nav = campaign_days
    rng = _rng("campaign", kind)
    data, what = OBS_MUTATIONS[kind](obs[1], rng)
    good = write(tmp_path / "FUZZ00XXX_R_20203290600_06H_30S_MO.rnx", obs[0])
    name = f"campaign-{kind}-FUZZ00XXX_R_20203300600_06H_30S_MO.rnx"
    bad = write(tmp_path / name, data)
    out = tmp_path / "out"
    r = run_cli(
        [
            "campaign",
            good,
            bad,
            "--nav",
            *nav,
            "--out",
            out,
            "--workers",
            "0",
            "--cache-dir",
            tmp_path / "cache",
            "--no-pdf",
        ],
        timeout_s=600,
    )
    problem = check_run(r, name, allowed=(0, 2, 3))
    if problem is None and r.code == 2:
        assert not out.exists(), "a refused campaign left an output folder"
    assert problem is None, f"{name} ({what}): {problem}"
