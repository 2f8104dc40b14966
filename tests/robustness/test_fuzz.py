"""Seeded mutation fuzzing of the readers through the command line.

A few hundred mutated copies of the shared station files (cut down so that
each run takes a fraction of a second) go through ``psdbound inspect``
in-process: observation files (RINEX 3 and 2, plain, gzip, Hatanaka), the
navigation files and an SP3 file. Every run must end with exit 0 or 2,
without a traceback or a numpy warning; a bad input gives exactly one line
naming the file; a run that succeeds prints a physical interval and span.
The same is checked for a few ``fit`` runs, for real subprocesses, and for
``fit`` runs on several files at once (two observation files of one station
merged, the same file twice, a station's zip of observations and navigation,
a zip of navigation files, ``--nav`` twice), one of them mutated.

The cases are generated from fixed seeds: a failure names its case, and the
case can be rebuilt with :func:`make_case`.
"""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys

import numpy as np
import pytest
from fuzzbases import bases  # noqa: F401 - the fixture
from fuzzlib import (
    NAV_MUTATIONS,
    OBS_MUTATIONS,
    SP3_MUTATIONS,
    bound_sane,
    check_run,
    container,
    inspect_sane,
    run_cli,
    split_obs,
    write,
    zip_of,
)

pytestmark = pytest.mark.realdata

N_OBS_ESBC = 11  # cases per observation mutation, ESBC (RINEX 3)
N_OBS_UPC = 5  # cases per observation mutation, UPC (RINEX 2)
N_NAV = 6
N_SP3 = 5
_CONTAINERS = ("plain", "plain", "gz", "crx", "crx.gz")

CASES = (
    [("esbc", k, i) for k in OBS_MUTATIONS for i in range(N_OBS_ESBC)]
    + [("upc", k, i) for k in OBS_MUTATIONS for i in range(N_OBS_UPC)]
    + [("esbc-nav", k, i) for k in NAV_MUTATIONS for i in range(N_NAV)]
    + [("upc-nav", k, i) for k in NAV_MUTATIONS for i in range(N_NAV // 2)]
    + [("sp3", k, i) for k in SP3_MUTATIONS for i in range(N_SP3)]
    + [("esbc-container", k, i) for k in ("bad.gz", "cut.gz", "bad-crx") for i in range(4)]
)


def _seed(*parts: object) -> int:
    return int.from_bytes(hashlib.sha256("/".join(map(str, parts)).encode()).digest()[:8], "little")


def make_case(b, family: str, kind: str, index: int):
    """Write the mutated file of a case; return (args of inspect, file name, description)."""
    rng = np.random.default_rng(_seed(family, kind, index))
    folder = b.folder
    if family in ("esbc", "upc"):
        base = b.esbc if family == "esbc" else b.upc
        data, what = OBS_MUTATIONS[kind](base, rng)
        box = _CONTAINERS[int(rng.integers(0, len(_CONTAINERS)))]
        if family == "upc" and box.startswith("crx"):
            box = "gz"
        try:
            blob = container(data, box)
        except Exception:  # rnx2crx refuses some damaged text: give it plain
            box, blob = "plain", data
        ext = {"plain": "rnx", "gz": "rnx.gz", "crx": "crx", "crx.gz": "crx.gz"}[box]
        name = f"{family}-{kind}-{index}.{ext}"
        path = write(folder / name, blob)
        nav = b.esbc_nav_path if family == "esbc" else b.upc_nav_path
        return ["inspect", path, "--nav", nav], name, f"{what} ({box})"
    if family == "esbc-container":
        if kind == "bad-crx":
            crx = bytearray(container(b.esbc, "crx"))
            k = int(rng.integers(200, len(crx) - 100))
            crx[k : k + 20] = bytes(rng.integers(32, 127, 20).astype(np.uint8))
            blob, what = bytes(crx), "Hatanaka stream damaged"
        else:
            blob, what = container(b.esbc, kind, rng), kind
        name = f"{family}-{kind}-{index}.crx.gz" if kind != "bad-crx" else f"{family}-{index}.crx"
        path = write(folder / name, blob)
        return ["inspect", path, "--nav", b.esbc_nav_path], name, what
    if family in ("esbc-nav", "upc-nav"):
        base = b.esbc_nav if family == "esbc-nav" else b.upc_nav
        data, what = NAV_MUTATIONS[kind](base, rng)
        box = "gz" if rng.random() < 0.3 else "plain"
        name = f"{family}-{kind}-{index}.rnx" + (".gz" if box == "gz" else "")
        path = write(folder / name, container(data, box))
        obs = folder / ("base-esbc.rnx" if family == "esbc-nav" else "base-upc.10o")
        if not obs.exists():
            obs.write_bytes(b.esbc if family == "esbc-nav" else b.upc)
        return ["inspect", obs, "--nav", path], name, what
    data, what = SP3_MUTATIONS[kind](b.sp3, rng)
    name = f"sp3-{kind}-{index}.sp3"
    path = write(folder / name, data)
    obs = folder / "base-esbc.rnx"
    if not obs.exists():
        obs.write_bytes(b.esbc)
    return ["inspect", obs, "--nav", path], name, what


@pytest.mark.parametrize(
    ("family", "kind", "index"), CASES, ids=[f"{f}-{k}-{i}" for f, k, i in CASES]
)
def test_fuzz_inspect(bases, family, kind, index):  # noqa: F811
    args, name, what = make_case(bases, family, kind, index)
    r = run_cli(args, timeout_s=60)
    problem = check_run(r, name, allowed=(0, 2))
    if problem is None and r.code == 0:
        problem = inspect_sane(r.out)
    assert problem is None, f"{name} ({what}): {problem}"


def test_fuzz_bases_are_clean(bases):  # noqa: F811
    """The unmutated bases read without warnings (so every warning above comes from a mutation)."""
    for name, data, nav in (
        ("clean-esbc.rnx", bases.esbc, bases.esbc_nav_path),
        ("clean-upc.10o", bases.upc, bases.upc_nav_path),
    ):
        r = run_cli(["inspect", write(bases.folder / name, data), "--nav", nav])
        assert r.code == 0 and not r.err and not r.warnings, r.err


# ------------------------------------------------------------------ fit, in process

FIT_CASES = [
    ("epoch_order", 1),
    ("interval", 0),
    ("crlf", 0),
    ("obs_types", 0),
    ("column_shift", 2),
    ("byte_flip", 3),
    ("epoch_date", 1),
]


@pytest.mark.slow
@pytest.mark.parametrize(("kind", "index"), FIT_CASES, ids=[f"{k}-{i}" for k, i in FIT_CASES])
def test_fuzz_fit(bases, tmp_path, kind, index):  # noqa: F811
    rng = np.random.default_rng(_seed("fit", kind, index))
    data, what = OBS_MUTATIONS[kind](bases.esbc_fit, rng)
    name = f"fit-{kind}-{index}.rnx"
    path = write(tmp_path / name, data)
    out = tmp_path / "out"
    r = run_cli(
        [
            "fit",
            path,
            "--nav",
            bases.esbc_nav_path,
            "--out",
            out,
            "--no-pdf",
            "--quiet",
            "--cutoff-hz",
            "9.55e-4",
        ],
        timeout_s=300,
    )
    problem = check_run(r, name)
    if problem is None and r.code in (0, 3):
        problem = bound_sane(json.loads((out / "result.json").read_text()))
    if problem is None and r.code == 2:
        assert not out.exists(), "a refused fit left an output folder"
    assert problem is None, f"{name} ({what}): {problem}"


# ------------------------------------------------------------------ real processes

SUBPROCESS_CASES = [
    ("esbc", "obs_types", 2),
    ("esbc", "interval", 1),
    ("upc", "epoch_date", 0),
    ("esbc-container", "bad.gz", 0),
    ("esbc-nav", "nav_value", 0),
]


@pytest.mark.parametrize(
    ("family", "kind", "index"),
    SUBPROCESS_CASES,
    ids=[f"{f}-{k}-{i}" for f, k, i in SUBPROCESS_CASES],
)
def test_fuzz_subprocess(bases, family, kind, index):  # noqa: F811
    args, name, what = make_case(bases, family, kind, index)
    r = subprocess.run(
        [sys.executable, "-W", "error::RuntimeWarning", "-m", "psdbound", *map(str, args)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode in (0, 2), f"{name} ({what}): exit {r.returncode}: {r.stderr[-500:]}"
    assert "Traceback" not in r.stderr
    if r.returncode == 2:
        lines = r.stderr.strip().splitlines()
        assert len(lines) == 1 and name in lines[0], r.stderr


# ------------------------------------------------------------------ several files, in process

MULTI_KINDS = ("two-obs", "station-zip", "nav-zip", "nav-twice")
MULTI_CASES = [(k, i) for k in MULTI_KINDS for i in range(3)] + [("same-twice", 0)]
_MULTI_OBS = (
    "byte_flip",
    "truncate",
    "epoch_order",
    "epoch_date",
    "interval",
    "obs_types",
    "column_shift",
    "satellite_id",
)


def _mutated_half(b, rng) -> tuple[list[bytes], str]:
    """The two halves of the ESBC base, one of them mutated."""
    halves = list(split_obs(b.esbc, b"> 2020 06 25 00 15 "))
    mut = _MULTI_OBS[int(rng.integers(0, len(_MULTI_OBS)))]
    which = int(rng.integers(0, 2))
    halves[which], what = OBS_MUTATIONS[mut](halves[which], rng)
    return halves, f"half {which + 1}: {what}"


def make_multi_case(b, kind: str, index: int, folder):
    """Write the files of a several-file case; return (fit arguments, name stem, description).

    Every file of a case is named ``<stem>-...``, so that an error naming any
    of them (or the archive member ``<stem>-....zip:member``) names the case.
    """
    rng = np.random.default_rng(_seed("multi", kind, index))
    stem = f"multi-{kind}-{index}"
    nav = b.esbc_nav_path
    if kind in ("two-obs", "station-zip", "same-twice"):
        (h1, h2), what = _mutated_half(b, rng)
        if kind == "two-obs":
            return (
                [
                    write(folder / f"{stem}-a.rnx", h1),
                    write(folder / f"{stem}-b.rnx", h2),
                    "--nav",
                    nav,
                ],
                stem,
                what,
            )
        if kind == "same-twice":
            obs = write(folder / f"{stem}.rnx", h1)
            return [obs, obs, "--nav", nav], stem, what
        blob = zip_of({f"{stem}-obs.rnx": h1, f"{stem}-nav.rnx": b.esbc_nav})
        return [write(folder / f"{stem}.zip", blob)], stem, what
    mut = list(NAV_MUTATIONS)[int(rng.integers(0, len(NAV_MUTATIONS)))]
    bad, what = NAV_MUTATIONS[mut](b.esbc_nav, rng)
    obs = write(folder / f"{stem}-obs.rnx", split_obs(b.esbc, b"> 2020 06 25 00 15 ")[0])
    if kind == "nav-zip":
        blob = zip_of({f"{stem}-a.rnx": bad, f"{stem}-b.rnx": b.esbc_nav})
        return [obs, "--nav", write(folder / f"{stem}-nav.zip", blob)], stem, what
    return [obs, "--nav", write(folder / f"{stem}-nav.rnx", bad), "--nav", nav], stem, what


@pytest.mark.parametrize(("kind", "index"), MULTI_CASES, ids=[f"{k}-{i}" for k, i in MULTI_CASES])
def test_fuzz_several_files(bases, tmp_path, kind, index):  # noqa: F811
    args, stem, what = make_multi_case(bases, kind, index, tmp_path)
    out = tmp_path / "out"
    r = run_cli(
        ["fit", *args, "--out", out, "--no-pdf", "--quiet", "--cutoff-hz", "9.55e-4"], timeout_s=120
    )
    problem = check_run(r, stem)
    if problem is None and r.code in (0, 3):
        problem = bound_sane(json.loads((out / "result.json").read_text()))
    if problem is None and r.code == 2:
        assert not out.exists(), "a refused fit left an output folder"
    if kind == "same-twice":
        assert r.code == 2 and "given twice" in r.err, r.err
    assert problem is None, f"{stem} ({what}): {problem}"
