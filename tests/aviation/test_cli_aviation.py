"""The overbound and budget subcommands, driven through their own parsers."""

from __future__ import annotations

import argparse
import json

import numpy as np
import pytest

from psdbound.cli import budget, overbound
from psdbound.errors import InputError


def _parse(mod, argv):
    parser = argparse.ArgumentParser(prog="psdbound")
    mod.add_parser(parser.add_subparsers(dest="command"))
    return parser.parse_args(argv)


def _csv(path, err, el):
    rows = "\n".join(f"{float(e)!r},{float(a)!r}" for e, a in zip(err, el, strict=True))
    path.write_text("error,elevation\n" + rows + "\n")
    return path


def test_overbound_writes_json_and_qq_figure(tmp_path, capsys):
    rng = np.random.default_rng(2)
    el = rng.uniform(5, 90, 3000)
    f = _csv(tmp_path / "e.csv", rng.standard_normal(el.size), el)
    args = _parse(
        overbound, ["overbound", str(f), "--edges", "5", "30", "90", "--out", str(tmp_path / "out")]
    )
    assert overbound.run(args) == 0
    doc = json.loads((tmp_path / "out" / "overbound.json").read_text())
    bins = doc["overbound"]["bins"]
    assert [b["elevation_deg"] for b in bins] == [[5.0, 30.0], [30.0, 90.0]]
    assert all(0.9 < b["inflation"] < 1.3 for b in bins)
    assert (tmp_path / "out" / "overbound_qq.png").stat().st_size > 1000
    assert "inflation" in capsys.readouterr().out


def test_overbound_too_few_samples_names_file_and_bin(tmp_path):
    f = _csv(tmp_path / "e.csv", np.arange(150.0), np.r_[np.full(140, 10.0), np.full(10, 70.0)])
    args = _parse(overbound, ["overbound", str(f), "--edges", "5", "30", "90"])
    with pytest.raises(InputError, match=r"e\.csv: elevation bin \[30, 90\) deg: 10 sample"):
        overbound.run(args)


def test_overbound_nan_is_input_error(tmp_path):
    f = tmp_path / "e.csv"
    f.write_text("error,elevation\n" + "1.0,20\n" * 200 + "nan,20\n")
    args = _parse(overbound, ["overbound", str(f)])
    with pytest.raises(InputError, match=r"column 'error': 1 of 201 .* sample 201, counted"):
        overbound.run(args)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("", r"e\.csv: file is empty; expected a header line"),
        ("error,elevation\n", r"e\.csv: no samples: the file has its header line only"),
        (  # a cell that is not a number was read as NaN and used: now named
            "error,elevation\n0.1,30\n0.2,abc\n",
            r"column 'elevation': 1 of 2 samples are missing, not numbers .* sample 2,",
        ),
        ("error,elevation\n0.1,30\n,40\n", r"column 'error': 1 of 2 .* sample 2,"),
    ],
)
def test_overbound_unusable_tables_are_named(tmp_path, text, match):
    f = tmp_path / "e.csv"
    f.write_text(text)
    with pytest.raises(InputError, match=match):
        overbound.run(_parse(overbound, ["overbound", str(f)]))


def test_overbound_nan_in_npy_is_named(tmp_path):
    a = np.column_stack([np.ones(300), np.full(300, 50.0)])
    a[7, 0] = np.inf
    np.save(tmp_path / "e.npy", a)
    with pytest.raises(InputError, match=r"column 'error': 1 of 300 .* sample 8,"):
        overbound.run(_parse(overbound, ["overbound", str(tmp_path / "e.npy")]))


def test_budget_prints_vpl(capsys):
    sats = ["10,12", "80,25", "150,38", "200,47", "260,60", "320,75"]
    argv = [
        "budget",
        "--k-md-e",
        "5",
        *[a for s in sats for a in ("--sat", s)],
        "--tau-gnd",
        "30",
        "--tau-air",
        "30",
    ]
    assert budget.run(_parse(budget, argv)) == 0
    assert "VPL_H0 =" in capsys.readouterr().out


def test_budget_bad_sat():
    with pytest.raises(InputError, match="AZ,EL"):
        budget.run(_parse(budget, ["budget", "--sat", "10"]))
    with pytest.raises(InputError, match="at least 4"):
        budget.run(_parse(budget, ["budget", "--sat", "10,20"]))
