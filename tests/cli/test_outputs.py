"""``--out`` never deletes or hides anything psdbound did not create.

The folder policy (:mod:`psdbound.common.outputs`) with a stand-in writer,
and ``fit --out`` refusing unsafe destinations before anything is read. The
full report path (``report --out``) is exercised in tests/pipeline/test_fit_cli.py.
"""

from __future__ import annotations

import json
import os

import pytest
from samples import moving_observations

from psdbound.cli import main
from psdbound.common.outputs import check_output_folder, is_report_folder, output_folder
from psdbound.errors import InputError
from psdbound.io.write import write_obs_v3


def _write_outputs(out, *, overwrite=False, pdf=True):
    with output_folder(out, overwrite=overwrite) as tmp:
        (tmp / "result.json").write_text(json.dumps({"schema_version": "1", "run": 2}))
        (tmp / "report.html").write_text("<html>new</html>")
        if pdf:
            (tmp / "report.pdf").write_bytes(b"%PDF-new")


def _hidden(folder):
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


def test_new_folder_is_created_with_parents(tmp_path):
    out = tmp_path / "a" / "b" / "run"
    assert check_output_folder(out) == "create"
    _write_outputs(out)
    assert sorted(p.name for p in out.iterdir()) == ["report.html", "report.pdf", "result.json"]
    assert is_report_folder(out) and not _hidden(out.parent)


def test_previous_output_is_replaced_atomically(tmp_path):
    out = tmp_path / "run"
    _write_outputs(out)
    assert check_output_folder(out) == "replace"
    _write_outputs(out, pdf=False)  # the old PDF was psdbound's: it goes too
    assert sorted(p.name for p in out.iterdir()) == ["report.html", "result.json"]
    assert not _hidden(tmp_path)  # no temporary or old folder left behind


def test_user_file_in_the_folder_survives(tmp_path):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("my notes\n")
    with pytest.raises(
        InputError,
        match=r"mine: output folder is an existing folder that is not "
        r"a psdbound output \(it holds 1 entry: notes.txt\)",
    ):
        _write_outputs(out)
    assert sorted(p.name for p in out.iterdir()) == ["notes.txt"]
    _write_outputs(out, overwrite=True)  # psdbound's files are added, nothing else touched
    assert (out / "notes.txt").read_text() == "my notes\n"
    assert sorted(p.name for p in out.iterdir()) == [
        "notes.txt",
        "report.html",
        "report.pdf",
        "result.json",
    ]
    assert not _hidden(out) and not _hidden(tmp_path)


def test_a_previous_output_with_a_user_file_is_not_replaced(tmp_path):
    out = tmp_path / "run"
    _write_outputs(out)
    (out / "my-analysis.py").write_text("print(1)\n")
    with pytest.raises(InputError, match="not a psdbound output"):
        _write_outputs(out)
    _write_outputs(out, overwrite=True)
    assert (out / "my-analysis.py").is_file()


def test_a_file_is_never_replaced_by_a_folder(tmp_path):
    f = tmp_path / "result"
    f.write_text("precious\n")
    for overwrite in (False, True):
        with pytest.raises(
            InputError,
            match=r"result: output folder is an existing file, not a "
            "folder",
        ):
            _write_outputs(f, overwrite=overwrite)
    assert f.read_text() == "precious\n" and not _hidden(tmp_path)
    with pytest.raises(InputError, match=r"cannot be created: .*result is a file, not a folder"):
        check_output_folder(f / "sub" / "run")


def test_a_folder_that_appears_meanwhile_is_not_overwritten(tmp_path):
    out = tmp_path / "run"
    with pytest.raises(InputError, match="not a psdbound output"):
        with output_folder(out) as tmp:
            (tmp / "result.json").write_text('{"schema_version": "1"}')
            out.mkdir()
            (out / "theirs.txt").write_text("x")  # created while the outputs were built
    assert sorted(os.listdir(out)) == ["theirs.txt"] and not _hidden(tmp_path)


@pytest.fixture
def obs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write_obs_v3(tmp_path / "a.rnx", moving_observations())
    (tmp_path / "nav.rnx").write_text("never read\n")
    return tmp_path


def _fit(capsys, *args):
    code = main(["fit", "a.rnx", "--nav", "nav.rnx", *map(str, args)])
    return code, capsys.readouterr().err.strip()


def test_fit_refuses_a_user_folder_before_the_fit(obs, capsys):
    (obs / "mine").mkdir()
    (obs / "mine" / "keep.txt").write_text("keep\n")
    code, err = _fit(capsys, "--out", "mine")
    assert code == 2 and err.startswith("psdbound fit: error: mine: --out is an existing folder")
    assert "--overwrite" in err and len(err.splitlines()) == 1
    assert "reading" not in err  # refused before the fit started
    assert (obs / "mine" / "keep.txt").read_text() == "keep\n"


def test_fit_refuses_a_file_and_a_path_below_a_file(obs, capsys):
    (obs / "out.txt").write_text("mine\n")
    code, err = _fit(capsys, "--out", "out.txt")
    assert code == 2 and "out.txt: --out is an existing file, not a folder" in err
    code, err = _fit(capsys, "--out", "out.txt/run", "--overwrite")
    assert code == 2 and "--out cannot be created: out.txt is a file, not a folder" in err
    assert (obs / "out.txt").read_text() == "mine\n" and not _hidden(obs)


def test_fit_default_folder_is_checked_too(obs, capsys):
    (obs / "reports" / "a").mkdir(parents=True)
    (obs / "reports" / "a" / "x.csv").write_text("1\n")
    code, err = _fit(capsys)
    assert code == 2
    assert "reports/a: --out is an existing folder that is not a psdbound output" in err


def test_a_folder_the_file_system_refuses_is_named_before_the_fit(obs, capsys, monkeypatch):
    # os.access answers from permissions (yes for root, or on /proc, a read-only
    # or full mount): the probe folder is what the file system really says
    import errno
    import tempfile

    def refuse(*args, **kwargs):
        raise OSError(errno.EROFS, "Read-only file system")

    monkeypatch.setattr(tempfile, "mkdtemp", refuse)
    for out in ("new/run", "."):
        code, err = _fit(capsys, "--out", out, "--overwrite")
        assert code == 2 and "not writable (Read-only file system; nothing was written)" in err
        assert len(err.splitlines()) == 1 and "reading" not in err
    assert sorted(p.name for p in obs.iterdir()) == ["a.rnx", "nav.rnx"]
