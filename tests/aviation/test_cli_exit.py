"""``psdbound overbound`` / ``budget`` through the main CLI: outputs, and exit 2 naming the bin."""

from __future__ import annotations

import json

import numpy as np

from psdbound.cli import main


def test_overbound_writes_inflation_per_bin_and_qq_figure(tmp_path, capsys):
    rng = np.random.default_rng(3)
    el = rng.uniform(5, 90, 20000)
    err = rng.standard_t(5, el.size) * 0.01 * (1 + 2 * np.exp(-el / 15))
    f = tmp_path / "mp.csv"
    np.savetxt(f, np.column_stack([err, el]), delimiter=",", header="error,elevation", comments="")
    out = tmp_path / "ob"
    assert main(["overbound", str(f), "--out", str(out)]) == 0
    d = json.loads((out / "overbound.json").read_text())
    text = json.dumps(d)
    assert "inflation" in text
    assert (out / "overbound_qq.png").stat().st_size > 10_000
    capsys.readouterr()


def test_overbound_too_few_samples_in_a_bin_exits_2_naming_it(tmp_path, capsys):
    rng = np.random.default_rng(4)
    el = np.concatenate([rng.uniform(5, 60, 3000), rng.uniform(60, 90, 20)])
    f = tmp_path / "few.csv"
    np.savetxt(
        f,
        np.column_stack([rng.normal(size=el.size), el]),
        delimiter=",",
        header="error,elevation",
        comments="",
    )
    code = main(["overbound", str(f), "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert code == 2
    assert "[60, 90)" in err and err.strip().count("\n") == 0
    assert not (tmp_path / "o").exists()


def test_budget_prints_vpl(capsys):
    sats = ["0,80", "60,45", "120,30", "180,60", "240,25", "300,40", "30,15"]
    args = ["budget", "--k-md-e", "5"] + [a for s in sats for a in ("--sat", s)]
    assert main(args) == 0
    assert "VPL" in capsys.readouterr().out
