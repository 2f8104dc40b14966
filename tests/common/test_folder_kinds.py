"""One folder policy, two kinds: report folders and simulations (:mod:`psdbound.common.outputs`).

The messages and the everyday cases are covered where each kind is used
(tests/cli/test_outputs.py, tests/simulate/test_simulate_inputs.py); here:
the cases both kinds share through the one implementation.
"""

from __future__ import annotations

import json
import os

import pytest

from psdbound.common.outputs import check_output_folder, output_folder
from psdbound.errors import InputError
from psdbound.simulate.folder import check_simulate_folder, simulate_folder


def _report(folder, *, pdf=True):
    (folder / "result.json").write_text(json.dumps({"schema_version": "1"}))
    (folder / "report.html").write_text("<html></html>")
    if pdf:
        (folder / "report.pdf").write_bytes(b"%PDF")


def _simulation(folder, *, antenna_b=True):
    obs = ["n-A_MO.rnx.gz"] + (["n-B_MO.rnx.gz"] if antenna_b else [])
    files = {"obs": obs, "nav": "n_MN.rnx.gz", "truth": "n_truth.csv.gz"}
    for name in (*obs, files["nav"], files["truth"]):
        (folder / name).write_bytes(b"x")
    meta = {"scenario": {}, "digest": "d", "files": files}
    (folder / "n_truth.json").write_text(json.dumps(meta))


KINDS = {
    "report": (output_folder, check_output_folder, _report, "report.pdf"),
    "simulation": (simulate_folder, check_simulate_folder, _simulation, "n-B_MO.rnx.gz"),
}


def _write(kind, path, *, full=True, overwrite=False):
    folder, _, write, _ = KINDS[kind]
    with folder(path, overwrite=overwrite) as tmp:
        if kind == "report":
            write(tmp, pdf=full)
        else:
            write(tmp, antenna_b=full)


@pytest.mark.parametrize("kind", KINDS)
def test_a_previous_output_behind_a_link_is_updated_in_place(tmp_path, kind):
    _, check, _, dropped = KINDS[kind]
    _write(kind, tmp_path / "real")
    os.symlink("real", tmp_path / "link")
    assert check(tmp_path / "link") == "merge"
    _write(kind, tmp_path / "link", full=False)  # the temporary folder inside is not counted
    assert (tmp_path / "link").is_symlink()
    assert dropped not in os.listdir(tmp_path / "real")  # the earlier run's file is gone
    assert not [e for e in os.listdir(tmp_path / "real") if e.startswith(".")]


@pytest.mark.parametrize("kind", KINDS)
def test_a_failed_build_creates_no_parent(tmp_path, kind):
    with pytest.raises(RuntimeError, match="boom"):
        with KINDS[kind][0](tmp_path / "a" / "b" / "out") as tmp:
            (tmp / "partial").write_bytes(b"x")
            raise RuntimeError("boom")
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("kind", KINDS)
def test_a_folder_emptied_during_a_merge_still_gets_the_files(tmp_path, kind):
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("mine\n")
    folder, _, write, _ = KINDS[kind]
    with folder(out, overwrite=True) as tmp:
        write(tmp)
        (out / "notes.txt").unlink()
    assert len(os.listdir(out)) in (3, 5)  # the report's or the simulation's files


@pytest.mark.parametrize("kind", KINDS)
def test_a_user_file_added_during_a_replace_is_refused(tmp_path, kind):
    out = tmp_path / "out"
    _write(kind, out)
    before = sorted(os.listdir(out))
    with pytest.raises(InputError, match="is an existing folder that is not a"):
        with KINDS[kind][0](out) as tmp:
            KINDS[kind][2](tmp)
            (out / "theirs.txt").write_text("x")
    assert sorted(os.listdir(out)) == sorted([*before, "theirs.txt"])
    assert not [e for e in os.listdir(tmp_path) if e.startswith(".")]


def test_each_kind_owns_only_its_own_files(tmp_path):
    # a report folder is not a simulation's, nor the reverse; --overwrite puts both together
    out = tmp_path / "out"
    _write("report", out)
    with pytest.raises(InputError, match="not a simulation's output"):
        check_simulate_folder(out)
    _write("simulation", out, overwrite=True)
    assert {"result.json", "report.html", "report.pdf", "n_truth.json"} <= set(os.listdir(out))
    with pytest.raises(InputError, match="not a psdbound output"):
        check_output_folder(out)
