"""``overbound`` on psdbound's own series files, binary files, and ``--edges`` it cannot use.

The series files are written by the exporter itself
(:func:`psdbound.results.series_export.write_series`: ``fit --series`` writes
``series.csv.gz``, ``export`` writes ``.csv``, ``.csv.gz`` or ``.nc``), small,
with rows screened out as ionosphere whose values are ten times the kept ones.
"""

from __future__ import annotations

import gzip
import json

import numpy as np
import pytest

from psdbound.aviation.files import read_sample_file
from psdbound.cli import main
from psdbound.common.notices import PsdboundWarning
from psdbound.errors import InputError
from psdbound.results.series_export import write_series

KEPT_SIGMA_M = 0.003
SCREENED_SIGMA_M = 0.05


def _series(n_sat: int = 2, n: int = 500, screened_share: float = 0.84, seed: int = 5) -> dict:
    """A series table of ``n_sat`` satellites at 1 s; ``screened_share`` of it ionosphere."""
    rng = np.random.default_rng(seed)
    size = n_sat * n
    screened = np.full(size, "", dtype=object)
    hit = rng.uniform(size=size) < screened_share
    screened[hit] = "ionosphere"
    screened[np.flatnonzero(hit)[:3]] = "implausible"
    value = rng.normal(0.0, KEPT_SIGMA_M, size)
    value[hit] = rng.normal(0.0, SCREENED_SIGMA_M, int(hit.sum()))
    return {
        "t_gps_s": np.tile(np.arange(n, dtype=float), n_sat) + 1.3e9,
        "sat": np.repeat([f"G{k + 1:02d}" for k in range(n_sat)], n).astype(object),
        "azimuth_deg": np.full(size, np.nan),
        "elevation_deg": rng.uniform(20.0, 80.0, size),
        "value_m": value,
        "screened": screened,
        "window": np.where(hit, -1, 0),
    }


def _overbound(path, tmp_path, *extra):
    out = tmp_path / "ob"
    code = main(["overbound", str(path), "--edges", "10", "90", "--out", str(out), *extra])
    if code:
        return code, {}
    return code, json.loads((out / "overbound.json").read_text())["overbound"]["bins"][0]


@pytest.mark.parametrize("name", ["series.csv.gz", "export.csv", "export.nc"])
def test_series_files_of_fit_and_export_are_read(tmp_path, capsys, name):
    table = _series(screened_share=0.0)
    path = write_series(table, tmp_path / name)
    code, b = _overbound(path, tmp_path)
    assert code == 0, capsys.readouterr().err
    assert b["n"] == table["value_m"].size
    assert 0.8 * KEPT_SIGMA_M < b["std"] < 1.2 * KEPT_SIGMA_M


@pytest.mark.parametrize("name", ["series.csv.gz", "export.csv", "export.nc"])
def test_screened_rows_are_left_out_with_a_warning(tmp_path, capsys, name):
    table = _series()
    n_kept = int(np.count_nonzero(table["screened"] == ""))
    n_iono = int(np.count_nonzero(table["screened"] == "ionosphere"))
    path = write_series(table, tmp_path / name)
    code, b = _overbound(path, tmp_path)
    err = capsys.readouterr().err
    assert code == 0, err
    assert b["n"] == n_kept
    assert b["sigma"] < 2 * KEPT_SIGMA_M  # not the screened rows' 5 cm
    warning = [line for line in err.splitlines() if "left out" in line]
    assert len(warning) == 1
    assert f"{table['value_m'].size - n_kept} of {table['value_m'].size} rows" in warning[0]
    assert f"implausible 3, ionosphere {n_iono}" in warning[0]
    assert "--include-screened" in warning[0] and name in warning[0]


def test_include_screened_uses_every_row_and_says_so(tmp_path, capsys):
    table = _series()
    path = write_series(table, tmp_path / "series.csv.gz")
    code, b = _overbound(path, tmp_path, "--include-screened")
    out = capsys.readouterr()
    assert code == 0, out.err
    assert b["n"] == table["value_m"].size
    assert b["sigma"] > 5 * KEPT_SIGMA_M
    assert "left out" not in out.err
    assert "rows the fit screened out (implausible 3, ionosphere" in out.out


def test_every_row_screened_is_bad_input(tmp_path, capsys):
    path = write_series(_series(screened_share=1.0), tmp_path / "series.csv.gz")
    assert main(["overbound", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "every one of the 1000 rows was screened out" in err


def test_read_sample_file_counts_left_out_rows_and_splits_pieces(tmp_path):
    f = tmp_path / "s.csv"
    f.write_text(
        "t_gps_s,sat,azimuth_deg,elevation_deg,value_m,screened,window\n"
        "1.0,G01,,30.00,0.001,,0\n"
        "2.0,G01,,30.10,0.002,,0\n"
        "3.0,G01,,30.20,0.500,ionosphere,-1\n"  # left out: the piece ends
        "4.0,G01,,30.30,0.003,,0\n"
        "9.0,G01,,30.40,0.004,,0\n"  # a gap: a new piece
        "1.0,G02,,40.00,0.005,,-1\n"  # another satellite
        "2.0,G02,,40.10,0.006,,-1\n"
    )
    with pytest.warns(PsdboundWarning, match=r"1 of 7 rows left out: .*\(ionosphere 1\)"):
        s = read_sample_file(f)
    np.testing.assert_allclose(s.errors, [0.001, 0.002, 0.003, 0.004, 0.005, 0.006])
    np.testing.assert_allclose(s.elevation_deg, [30.0, 30.1, 30.3, 30.4, 40.0, 40.1])
    assert s.segment_id.tolist() == [0, 0, 1, 2, 3, 3]
    assert s.left_out == {"ionosphere": 1}
    assert s.notes and s.notes[0].startswith("2 of the 6 rows used")


def test_a_binary_file_of_no_supported_format_is_refused(tmp_path, capsys):
    f = tmp_path / "blob.bin"
    f.write_bytes(np.random.default_rng(1).integers(0, 256, 3000, dtype=np.uint8).tobytes())
    assert main(["overbound", str(f), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "blob.bin" in err
    assert "gzip" in err and ".npy" in err and "netCDF" in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    ("name", "cut", "match"),
    [
        ("series.csv.gz", 40, r"series\.csv\.gz: cannot read samples"),
        ("export.nc", 3000, r"export\.nc: cannot read this netCDF file"),
    ],
)
def test_truncated_series_files_are_bad_input(tmp_path, name, cut, match):
    path = write_series(_series(), tmp_path / name)
    path.write_bytes(path.read_bytes()[:cut])
    with pytest.raises(InputError, match=match):
        read_sample_file(path)


def test_a_gzip_compressed_table_is_read_whatever_its_name(tmp_path):
    f = tmp_path / "errors.txt"
    f.write_bytes(gzip.compress(b"error elevation\n0.1 30\n0.2 40\n"))
    s = read_sample_file(f)
    assert s.errors.tolist() == [0.1, 0.2] and s.elevation_deg.tolist() == [30.0, 40.0]
    assert s.segment_id is None


@pytest.mark.parametrize("edges", [["30", "5", "90"], ["5", "5", "90"], ["30"]])
def test_edges_not_increasing_are_bad_input(tmp_path, capsys, edges):
    f = tmp_path / "err.txt"
    f.write_text("error\n" + "\n".join(f"{x:.5f}" for x in np.linspace(-1, 1, 500)) + "\n")
    assert main(["overbound", str(f), "--edges", *edges]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert f"--edges {' '.join(edges)}: elevation bin edges must be" in err
    assert "increasing order" in err


def test_edges_for_a_file_without_elevations_are_bad_input(tmp_path, capsys):
    f = tmp_path / "err.txt"
    f.write_text("error\n" + "\n".join(f"{x:.5f}" for x in np.linspace(-1, 1, 500)) + "\n")
    assert main(["overbound", str(f), "--edges", "5", "30", "90"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "err.txt: --edges 5 30 90 asks for elevation bins" in err
    assert "leave out --edges" in err
    assert main(["overbound", str(f)]) == 0  # without --edges: one bin of all samples
    assert "[-inf, inf)" in capsys.readouterr().out


def test_include_screened_with_code_is_refused(capsys):
    argv = ["overbound", "x.rnx", "--code", "C1C", "--nav", "n.rnx", "--include-screened"]
    assert main(argv) == 2
    assert "--include-screened applies to a series file" in capsys.readouterr().err
