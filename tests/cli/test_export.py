"""``psdbound export`` and the series file formats: CSV and netCDF round trips (#32)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import xarray as xr

import psdbound
from psdbound.cli.main import main
from psdbound.results.series_export import (
    COLUMN_ATTRS,
    format_of,
    is_series_file,
    series_dataset,
    write_series,
)
from psdbound.results.series_table import COLUMNS


def _table():
    """A small table with what real ones hold: NaN azimuths, screened rows, no window."""
    return {
        "t_gps_s": np.array([1.29e9, 1.29e9 + 30.0, 1.29e9 + 60.0, 1.29e9 + 90.0]),
        "sat": np.array(["G01", "G01", "G02-G05", "G02-G05"], dtype=object),
        "azimuth_deg": np.array([12.5, 13.25, np.nan, np.nan]),
        "elevation_deg": np.array([15.0, 15.5, 40.25, 41.0]),
        "value_m": np.array([0.001234, -0.004321, 0.0, 0.012]),
        "screened": np.array(["", "ionosphere", "", "short remainder"], dtype=object),
        "window": np.array([0, -1, 1, -1], dtype=np.int64),
    }


def test_netcdf_round_trip_keeps_values_types_nan_and_units(tmp_path):
    tab = _table()
    attrs = {"title": "t", "bound_tau_s": 55.5, "input_files": "obs a.rnx sha256:0"}
    path = write_series(tab, tmp_path / "s.nc", attrs=attrs)
    assert format_of(path) == "netcdf" and is_series_file(path) is False  # not our title
    written = series_dataset(tab, attrs=attrs)
    back = xr.load_dataset(path)
    assert set(back.data_vars) == set(COLUMNS)
    for col in COLUMNS:
        assert back[col].dtype == written[col].dtype, col
        assert back[col].attrs == COLUMN_ATTRS[col], col
        if back[col].dtype.kind == "f":
            np.testing.assert_array_equal(back[col].values, tab[col])  # NaN where it was
        else:
            assert list(back[col].values) == list(tab[col]), col
    assert back.attrs == attrs
    assert back["value_m"].attrs["units"] == "m" and back["azimuth_deg"].attrs["units"] == "degree"
    df = back.to_dataframe()  # the pandas view a data scientist starts from
    assert list(df["screened"]) == list(tab["screened"]) and df["window"].dtype == np.int32


def test_csv_round_trip_with_pandas(tmp_path):
    tab = _table()
    for name in ("s.csv", "s.csv.gz"):
        path = write_series(tab, tmp_path / name)
        assert is_series_file(path)
        df = pd.read_csv(path, keep_default_na=False, na_values={"azimuth_deg": [""]})
        assert list(df.columns) == list(COLUMNS)
        for col in COLUMNS:
            if tab[col].dtype == object:  # text: pandas' string dtype (object before pandas 3)
                assert pd.api.types.is_string_dtype(df[col]), col
            else:
                assert df[col].dtype == tab[col].dtype, col
        np.testing.assert_array_equal(df["azimuth_deg"].to_numpy(), tab["azimuth_deg"])
        np.testing.assert_allclose(df["value_m"], tab["value_m"], atol=5e-7)  # 1 um written
        assert list(df["screened"]) == list(tab["screened"]) and list(df["sat"]) == list(tab["sat"])
        assert list(df["window"]) == list(tab["window"])


def test_unknown_suffix_and_format_are_input_errors(tmp_path):
    with pytest.raises(psdbound.InputError, match="name it .csv"):
        format_of(tmp_path / "s.txt")
    with pytest.raises(psdbound.InputError, match="csv or netcdf"):
        format_of(tmp_path / "s.nc", "parquet")


@pytest.fixture(scope="module")
def demo():
    return psdbound.fit()


def test_results_dataset_carries_units_and_provenance(demo):
    ds = demo.series_dataset()
    for col in COLUMNS:
        assert {"units", "long_name", "description"} <= set(ds[col].attrs)
    b = demo.document["bound"]
    assert ds.attrs["bound_sigma_gm_m"] == b["sigma_gm_m"] and ds.attrs["bound_tau_s"] == b["tau_s"]
    assert ds.attrs["psdbound_version"] == psdbound.__version__
    assert "psdbound-demo-A_MO.rnx.gz sha256:" in ds.attrs["input_files"]
    assert ds.sizes["sample"] == demo.isolated.series.t_gps_s.size


def test_export_cli_on_the_demo_writes_netcdf_atomically(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["export", "-q", "--format", "netcdf"]) == 0
    path = tmp_path / "reports" / "demo-series.nc"
    assert str(path.relative_to(tmp_path)) in capsys.readouterr().out
    back = xr.load_dataset(path)
    assert back.attrs["verdict"] == "bounded" and back.sizes["sample"] > 10_000
    assert back["window"].max() >= 0 and (back["screened"] == "").all()
    assert is_series_file(path)
    assert main(["export", "-q", "--format", "netcdf"]) == 0  # an earlier series: replaced
    assert [p.name for p in (tmp_path / "reports").iterdir()] == ["demo-series.nc"]  # no temp


def test_export_cli_refuses_before_the_fit_and_writes_nothing(tmp_path, capsys):
    mine = tmp_path / "mine.csv"
    mine.write_text("my own data\n")
    assert main(["export", "-q", "-o", str(mine)]) == 2
    assert "did not write" in capsys.readouterr().err and mine.read_text() == "my own data\n"
    assert main(["export", "-q", "-o", str(tmp_path / "s.parquet")]) == 2
    assert main(["export", "-q", "-o", str(tmp_path)]) == 2  # a folder
    assert main(["export", "-q", "--alpha", "2", "-o", str(tmp_path / "s.csv")]) == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.csv"]


def test_export_help_names_the_formats_and_exit_codes(capsys):
    with pytest.raises(SystemExit):
        main(["export", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "--format {csv,netcdf}" in text and "3 written" in text and "--pair" in text
    assert "--code-multipath" not in text


def test_a_format_the_file_name_contradicts_is_refused():
    """-o x.csv --format netcdf wrote netCDF named .csv; now bad input."""
    from psdbound.errors import InputError
    from psdbound.results.series_export import format_of

    assert format_of("x.nc") == "netcdf" and format_of("x.csv.gz") == "csv"
    assert format_of("x.dat", "netcdf") == "netcdf"  # a name that says nothing
    with pytest.raises(InputError, match="says csv but the format asked for is netcdf"):
        format_of("x.csv", "netcdf")
    with pytest.raises(InputError, match="says netcdf but the format asked for is csv"):
        format_of("x.nc", "csv")
