"""Command line: help, placeholders, and bad input -> one line, exit code 2."""

from __future__ import annotations

import gzip
import subprocess
import sys

import pytest
from conftest import ESBC_NAV, ESBC_OBS, GRAS_OBS, shared_file
from samples import NAV3_TEXT, write_small

from psdbound.cli import main
from psdbound.io.write import format_obs_v3


def run(*args, cwd=None):
    return subprocess.run(
        [sys.executable, "-m", "psdbound", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
    )


def test_help_lists_subcommands():
    r = run("--help")
    assert r.returncode == 0
    for name in ("inspect", "fit", "cutoff", "validate", "simulate", "report"):
        assert name in r.stdout


def test_every_subcommand_has_help():
    for name in ("inspect", "fit", "cutoff", "validate", "simulate", "report"):
        r = run(name, "--help")
        assert r.returncode == 0 and "not available" not in r.stdout, name


def test_inspect_synthetic(tmp_path, capsys):
    p = write_small(tmp_path / "a.rnx", n_epoch=200)
    assert main(["inspect", str(p), "--min-arc-min", "10"]) == 0
    out = capsys.readouterr().out
    assert "GPS (G): 2 satellites" in out
    assert "starts on loss of lock" in out  # G05 has an LLI flag at epoch 20


def _bad_files(tmp_path):
    import hatanaka

    files = {}
    (tmp_path / "empty.rnx").write_bytes(b"")
    files["empty"] = (tmp_path / "empty.rnx", "file is empty")
    text = format_obs_v3(__import__("samples").small_observations())
    cut = tmp_path / "cut.rnx"
    cut.write_text(text[: text.index("> 2020 06 25 00 15") + 60])
    files["truncated"] = (cut, "truncated epoch")
    nav = tmp_path / "brdc.rnx"
    nav.write_text(NAV3_TEXT)
    files["nav"] = (nav, "this is a navigation file")
    txt = tmp_path / "readme.txt"
    txt.write_text("just some words\n")
    files["text"] = (txt, "not a RINEX file")
    crx = bytearray(hatanaka.rnx2crx(text.encode()))
    crx[len(crx) // 2 : len(crx) // 2 + 200] = b"#" * 200
    bad = tmp_path / "bad.crx.gz"
    bad.write_bytes(gzip.compress(bytes(crx)))
    files["hatanaka"] = (bad, "corrupted Hatanaka")
    return files


@pytest.mark.parametrize("kind", ["empty", "truncated", "nav", "text", "hatanaka"])
def test_bad_file_exit_2_one_line(tmp_path, kind):
    path, what = _bad_files(tmp_path)[kind]
    r = run("inspect", path)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert path.name in lines[0] and what in lines[0]
    assert "Traceback" not in r.stderr


def test_missing_file_and_unknown_option(tmp_path):
    r = run("inspect", tmp_path / "nothing.rnx")
    assert r.returncode == 2 and "nothing.rnx: file not found" in r.stderr
    r = run("inspect", "--frobnicate", "x")
    assert r.returncode == 2 and "unrecognized arguments: --frobnicate" in r.stderr
    # an argument the command does not take is that command's error, with its name
    assert r.stderr.startswith("psdbound inspect: error:"), r.stderr
    r = run("cutoff", "obs.rnx")
    assert r.returncode == 2 and r.stderr.strip() == (
        "psdbound cutoff: error: unrecognized arguments: obs.rnx"
    )


def test_unknown_signal_and_absent_system(tmp_path):
    p = write_small(tmp_path / "a.rnx")
    r = run("inspect", p, "--signals", "L1C,L9Z")
    assert r.returncode == 2 and "signal 'L9Z' is not in the file for GPS" in r.stderr
    r = run("inspect", p, "--system", "E")
    assert r.returncode == 2 and "no observations of system 'E'" in r.stderr


@pytest.mark.realdata
def test_inspect_real_with_elevations(capsys):
    obs, nav = shared_file(ESBC_OBS), shared_file(ESBC_NAV)
    assert main(["inspect", str(obs), "--nav", str(nav), "--elevation-mask-deg", "10"]) == 0
    out = capsys.readouterr().out
    assert "G L1C-L2W:" in out and "elevation" in out


@pytest.mark.realdata
def test_gras_has_no_arc_long_enough(capsys):
    assert main(["inspect", str(shared_file(GRAS_OBS))]) == 0
    assert "G L1C-L2W: 0 arcs >= 30 min" in capsys.readouterr().out


@pytest.mark.parametrize(
    "command", [["cutoff", "--lat", "56", "--lon", "9.8", "--days", "2020-06-25"], ["campaign"]]
)
@pytest.mark.parametrize("flag", ["--out", "--cache-dir"])
def test_unwritable_folders_are_refused_before_any_work(tmp_path, capsys, command, flag):
    """A file given as the output or cache folder: exit 2 at once, nothing computed or written."""
    afile = tmp_path / "afile"
    afile.write_text("x")
    args = list(command)
    if command == ["campaign"]:
        obs, nav = write_small(tmp_path / "a.rnx", n_epoch=200), tmp_path / "n.rnx"
        nav.write_text(NAV3_TEXT)
        args += [str(obs), "--nav", str(nav)]
    out = tmp_path / "out"
    args += ["--workers", "0", "--out", str(afile if flag == "--out" else out)]
    if flag == "--cache-dir":
        args += ["--cache-dir", str(afile)]
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"{flag} is an existing file" in err[0], err
    assert afile.read_text() == "x" and not out.exists()


def test_every_command_takes_the_verbose_flag_its_internal_error_line_names():
    """An internal error says 'run with --verbose for the traceback': every command has it."""
    from psdbound.cli.main import build_parser

    for name, p in build_parser().commands.items():
        assert any("--verbose" in a.option_strings for a in p._actions), name
