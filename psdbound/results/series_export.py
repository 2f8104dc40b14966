"""The series table as a self-describing file: netCDF (via xarray) or CSV, written atomically.

The columnar format is netCDF 3 written by xarray with SciPy's netCDF
writer: every variable carries its ``units``, ``long_name`` and a
``description``; the file carries the provenance (input files with their
SHA-256, the psdbound version, the method, the verdict and the bound). It
opens directly in xarray and pandas (``xarray.open_dataset(path).to_dataframe()``),
Panoply, ncview and MATLAB's ``ncread``, and needs no binary dependency
beyond SciPy, which psdbound already uses. xarray is imported only when a
dataset is built, so that importing psdbound stays quick.

netCDF 3 has no 64-bit integers: ``window`` is stored as ``int32`` (the
dataset that is written holds it as ``int32`` too, so a read-back has the
same types). Strings (``sat``, ``screened``) are stored as character arrays
and read back as Python strings; NaN azimuths stay NaN.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.common.atomic import atomic_write_bytes
from psdbound.common.compression import compression_of
from psdbound.errors import InputError
from psdbound.results.series_table import COLUMNS, series_csv

__all__ = [
    "COLUMN_ATTRS",
    "FORMATS",
    "TITLE",
    "format_of",
    "is_series_file",
    "series_attrs",
    "series_bytes",
    "series_dataset",
    "write_series",
]

#: The ``title`` attribute of a series netCDF file.
TITLE = "psdbound isolated carrier-phase multipath, one row per satellite and epoch"

#: The file formats :func:`write_series` writes.
FORMATS = ("csv", "netcdf")

#: Per column: its unit (``"1"``: dimensionless, ``""``: a label), long name and description.
COLUMN_ATTRS: dict[str, dict[str, str]] = {
    "t_gps_s": {
        "units": "s",
        "long_name": "GPS time",
        "description": "seconds since 1980-01-06T00:00:00 GPS time (no leap seconds)",
    },
    "sat": {
        "units": "",
        "long_name": "satellite",
        "description": "satellite (e.g. G05), or the pair of a double difference",
    },
    "azimuth_deg": {
        "units": "degree",
        "long_name": "azimuth",
        "description": "satellite azimuth from north, clockwise; NaN without an "
        "orbit (or for dual-antenna pairs)",
    },
    "elevation_deg": {
        "units": "degree",
        "long_name": "elevation",
        "description": "satellite elevation above the horizon",
    },
    "value_m": {
        "units": "m",
        "long_name": "isolated carrier-phase multipath",
        "description": "isolated multipath before the elevation mapping",
    },
    "screened": {
        "units": "",
        "long_name": "screening flag",
        "description": "why the sample was screened out (ionosphere, implausible, "
        "short remainder); empty when it was kept",
    },
    "window": {
        "units": "1",
        "long_name": "stationary window index",
        "description": "index into windows.per_window of result.json; -1: in no "
        "window (screened out, or outside the bound)",
    },
}

_SUFFIXES = {".nc": "netcdf", ".csv": "csv", ".gz": "csv"}


def format_of(path: str | os.PathLike[str], fmt: str | None = None) -> str:
    """Return the format to write ``path`` in: ``fmt`` if given, else from its suffix.

    Parameters
    ----------
    path : str or path-like
        Destination (``.nc``: netCDF; ``.csv`` or ``.csv.gz``: CSV).
    fmt : {"csv", "netcdf"}, optional
        The format asked for.

    Returns
    -------
    str

    Raises
    ------
    InputError
        An unknown format, no format and a suffix that names none, or a
        format that the suffix contradicts.
    """
    suffix = Path(path).suffix.lower()
    if fmt is not None:
        if fmt not in FORMATS:
            raise InputError(f"unknown series format {fmt!r}; choose csv or netcdf")
        named = _SUFFIXES.get(suffix)
        if named is not None and named != fmt:
            raise InputError(
                f"the file name {Path(path).name!r} says {named} but the format asked for is "
                f"{fmt}; name the file {'.nc' if fmt == 'netcdf' else '.csv or .csv.gz'} (or "
                "leave out the format)"
            )
        return fmt
    if suffix not in _SUFFIXES:
        raise InputError(
            f"cannot tell the series format from the file name {Path(path).name!r}"
            ": name it .csv, .csv.gz or .nc, or give the format"
        )
    return _SUFFIXES[suffix]


def is_series_file(path: str | os.PathLike[str]) -> bool:
    """Return True if ``path`` is a series file psdbound wrote (CSV, CSV.gz or netCDF).

    A CSV file is one whose first line is the table's header; a netCDF file
    one that starts with the netCDF 3 signature and holds :data:`TITLE`.
    """
    import gzip

    header = (",".join(COLUMNS) + "\n").encode()
    try:
        with open(path, "rb") as fh:
            head = fh.read(1 << 16)
        if compression_of(head) == "gzip":
            with gzip.open(path, "rb") as fh:
                head = fh.read(len(header))
    except (OSError, EOFError, ValueError):
        return False
    return head.startswith(header) or (head[:3] == b"CDF" and TITLE.encode() in head)


def series_attrs(document: dict[str, Any]) -> dict[str, str | float]:
    """Return the provenance attributes of a fit's series (netCDF global attributes).

    Parameters
    ----------
    document : dict
        The result document (``result.json``) of the fit.

    Returns
    -------
    dict of str to str or float
        ``title``, ``source``, ``psdbound_version``, ``method``, ``verdict``,
        ``input_files`` (name and SHA-256 of each, ``; ``-separated), the
        bound ``bound_sigma_gm_m``, ``bound_tau_s``, ``bound_sigma_wn_m``,
        ``bound_dt_s``, ``bound_rule``, ``bound_applies_to``, and
        ``cutoff_f_c_hz`` (NaN without a cutoff).
    """
    prov, b = document.get("provenance", {}), document["bound"]
    files = "; ".join(
        f"{x.get('role', '')} {x.get('name', '')} sha256:{x.get('sha256', '')}"
        for x in prov.get("inputs", [])
    )
    f_c = document.get("cutoff", {}).get("f_c_hz")
    return {
        "title": TITLE,
        "source": "psdbound fit (python -m psdbound export)",
        "psdbound_version": str(prov.get("versions", {}).get("psdbound", "")),
        "method": str(document.get("method", "")),
        "verdict": str(document.get("verdict", "")),
        "input_files": files,
        "bound_sigma_gm_m": float(b["sigma_gm_m"]),
        "bound_tau_s": float(b["tau_s"]),
        "bound_sigma_wn_m": float(b["sigma_wn_m"]),
        "bound_dt_s": float(b["dt_s"]),
        "bound_rule": str(b.get("rule", "")),
        "bound_applies_to": str(b.get("applies_to", "")),
        "cutoff_f_c_hz": float("nan") if f_c is None else float(f_c),
    }


def series_dataset(table: dict[str, NDArray], *, attrs: dict[str, Any] | None = None) -> Any:
    """Return a series table as an :class:`xarray.Dataset` along the dimension ``sample``.

    Parameters
    ----------
    table : dict of str to ndarray
        :func:`psdbound.results.series_table.series_table`.
    attrs : dict, optional
        Global attributes (:func:`series_attrs`).

    Returns
    -------
    xarray.Dataset
        One variable per column with ``units``, ``long_name`` and
        ``description`` attributes; ``window`` as ``int32``.
    """
    import xarray as xr

    data = {}
    for col in COLUMNS:
        values = np.asarray(table[col])
        if col == "window":
            values = values.astype(np.int32)
        elif values.dtype == object:
            values = values.astype(str).astype(object)
        data[col] = xr.Variable(("sample",), values, attrs=dict(COLUMN_ATTRS[col]))
    return xr.Dataset(data, attrs=dict(attrs or {}))


def series_bytes(
    table: dict[str, NDArray], fmt: str, *, gz: bool = False, attrs: dict[str, Any] | None = None
) -> bytes:
    """Return a series table as the bytes of a file in format ``fmt``.

    Parameters
    ----------
    table : dict of str to ndarray
        :func:`psdbound.results.series_table.series_table`.
    fmt : {"csv", "netcdf"}
        File format.
    gz : bool, default False
        CSV only: gzip-compressed.
    attrs : dict, optional
        netCDF only: global attributes (:func:`series_attrs`).

    Returns
    -------
    bytes
    """
    if format_of("", fmt) == "csv":
        return series_csv(table, gz=gz)
    ds = series_dataset(table, attrs=attrs)
    return bytes(ds.to_netcdf(engine="scipy", format="NETCDF3_64BIT"))


def write_series(
    table: dict[str, NDArray],
    path: str | os.PathLike[str],
    *,
    fmt: str | None = None,
    attrs: dict[str, Any] | None = None,
) -> Path:
    """Write a series table to ``path`` atomically (nothing half-written on failure).

    Parameters
    ----------
    table : dict of str to ndarray
        :func:`psdbound.results.series_table.series_table`.
    path : str or path-like
        Destination; CSV is gzip-compressed when the name ends in ``.gz``.
    fmt : {"csv", "netcdf"}, optional
        Default: from the suffix (:func:`format_of`).
    attrs : dict, optional
        netCDF global attributes (:func:`series_attrs`).

    Returns
    -------
    Path
    """
    p = Path(path)
    data = series_bytes(table, format_of(p, fmt), gz=p.name.endswith(".gz"), attrs=attrs)
    return atomic_write_bytes(p, data)
