"""Files of the aviation commands: read error samples, write the overbound outputs.

Input (:func:`read_sample_file`, :func:`read_samples`): a ``.npy`` array (one
column of errors, or two columns ``error, elevation_deg``), a text/CSV file
with a header naming an ``error`` column (any of ``error``, ``multipath``,
``value``, ``value_m``, ...) and optionally an ``elevation`` column
(``elevation``, ``elevation_deg``, ``el``), plain or gzip-compressed (told by
its first bytes), or a netCDF file read through xarray with such variables.
psdbound's own series files (``fit --series``: ``series.csv.gz``; ``export``:
``.csv``, ``.csv.gz``, ``.nc``; columns of
:data:`psdbound.results.series_table.COLUMNS`) are read as they are: the rows
the fit screened out (``screened`` not empty: ionosphere, implausible, short
remainder) are left out with a warning that counts them by reason, unless
asked for, and the continuous pieces of the series (one satellite, evenly
sampled, nothing left out between) bound the autocorrelation of the
effective sample size. Output (:func:`write_overbound`): ``overbound.json``
(per-bin sigma, bias, inflation factor, counts) and ``overbound_qq.png`` (the
Q-Q figure: each bin's sample quantiles against standard-normal quantiles,
with its overbound line), written atomically.
"""

from __future__ import annotations

import gzip
import io
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.aviation.overbound import OverboundResult
from psdbound.common.atomic import atomic_write_bytes
from psdbound.common.compression import compression_of
from psdbound.common.notices import warn
from psdbound.errors import InputError
from psdbound.results import write_json

__all__ = ["SampleFile", "read_sample_file", "read_samples", "write_overbound"]

_ERROR_NAMES = ("error", "multipath", "value", "error_m", "multipath_m", "value_m")
_EL_NAMES = ("elevation", "elevation_deg", "el")
#: Text columns of a series table (the rest are numbers).
_LABELS = ("sat", "screened")
#: The column of a series table saying why a row was screened out (empty: kept).
_FLAG = "screened"
#: A new continuous piece starts where the time step exceeds this many median steps.
_GAP_STEPS = 1.5

_NPY = b"\x93NUMPY"
_NETCDF = (b"CDF\x01", b"CDF\x02", b"CDF\x05")
_HDF5 = b"\x89HDF\r\n\x1a\n"
_FORMATS = (
    "CSV or whitespace-separated text with a header line naming an error column, "
    "plain or gzip-compressed (.csv, .csv.gz, as psdbound fit --series and export "
    "write), a NumPy .npy array, or a netCDF file (.nc, as psdbound export writes)"
)

_Table = dict[str, NDArray[Any]]


@dataclass(frozen=True)
class SampleFile:
    """Error samples read from a file, with what was left out and why.

    Attributes
    ----------
    errors : ndarray
        The samples used, in the unit of the file (``value_m``: m), in file order.
    elevation_deg : ndarray or None
        Their elevations, degrees; None when the file has none.
    segment_id : ndarray or None
        Continuous pieces of the series (equal consecutive values; see
        :func:`psdbound.aviation.effective_sample_size`), from the ``sat``
        and ``t_gps_s`` columns and the rows left out; None without them.
    left_out : dict of str to int
        Rows left out, by the reason the fit screened them out.
    notes : tuple of str
        Sentences on what was included that a reader may not expect.
    """

    errors: NDArray[np.float64]
    elevation_deg: NDArray[np.float64] | None
    segment_id: NDArray[np.int64] | None = None
    left_out: dict[str, int] = field(default_factory=dict)
    notes: tuple[str, ...] = ()


def read_samples(
    path: str | Path, *, include_screened: bool = False
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """Read error samples (and elevations, degrees, when present).

    Parameters
    ----------
    path : str or Path
        See :func:`read_sample_file`.
    include_screened : bool, default False
        See :func:`read_sample_file`.

    Returns
    -------
    errors : ndarray
        Unit of the file.
    elevation_deg : ndarray or None

    Raises
    ------
    InputError
        See :func:`read_sample_file`.
    """
    s = read_sample_file(path, include_screened=include_screened)
    return s.errors, s.elevation_deg


def read_sample_file(path: str | Path, *, include_screened: bool = False) -> SampleFile:
    """Read error samples, their elevations and continuous pieces from a file.

    Parameters
    ----------
    path : str or Path
        ``.npy`` array; CSV/whitespace text with a header line, plain or
        gzip-compressed; or netCDF (through xarray). psdbound's series files
        (``fit --series``, ``export``) are read as written.
    include_screened : bool, default False
        Also use the rows the fit screened out (a ``screened`` column that
        is not empty). By default they are left out, with a
        :class:`~psdbound.common.notices.PsdboundWarning` counting them by
        reason.

    Returns
    -------
    SampleFile
        Errors in the unit of the file, elevations in degrees.

    Raises
    ------
    InputError
        Missing, empty, unreadable or binary file of no supported format, no
        error column, missing or non-numeric cells, every row screened out
        (the file is named).
    """
    p = Path(path)
    if not p.is_file():
        raise InputError("no such file", path=p)
    if p.stat().st_size == 0:
        raise InputError(
            "file is empty; expected a header line naming an error column "
            f"({', '.join(_ERROR_NAMES)}), then one row of numbers per sample, or a .npy array",
            path=p,
        )
    try:
        table = _read_table(p)
    except InputError:
        raise
    except (OSError, ValueError, IndexError, EOFError, zlib.error) as exc:
        raise InputError(
            f"cannot read samples ({' '.join(str(exc).split())[:160]}); expected a header line "
            f"naming an error column ({', '.join(_ERROR_NAMES)}) and optionally an elevation "
            f"column ({', '.join(_EL_NAMES)}), then one row of numbers per sample, comma- or "
            "whitespace-separated, or a .npy array, or a netCDF file with such variables",
            path=p,
        ) from None
    return _samples(p, table, include_screened)


def _read_table(p: Path) -> _Table:
    """Return the columns of a sample file, by lower-case name, in the file's order."""
    raw = p.read_bytes()
    packed = compression_of(raw[:4]) == "gzip"
    if packed:
        raw = gzip.decompress(raw)
    if raw[:6] == _NPY or (p.suffix == ".npy" and not packed):
        return _read_npy(p, raw)
    if raw[:4] in _NETCDF or raw[:8] == _HDF5:
        return _read_netcdf(p, io.BytesIO(raw) if packed else p, hdf5=raw[:8] == _HDF5)
    if b"\x00" in raw[:65536]:
        raise InputError(f"binary file in none of the formats overbound reads: {_FORMATS}", path=p)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(
            f"not UTF-8 text (byte {exc.start + 1}) nor a binary format overbound reads: "
            f"it reads {_FORMATS}",
            path=p,
        ) from None
    first = text.splitlines()[0] if text.strip() else ""
    if "," in first and _FLAG in (c.strip().lower() for c in first.split(",")):
        return _read_series_csv(text)
    return _read_text(text, "," if "," in first else None)


def _read_npy(p: Path, raw: bytes) -> _Table:
    """Return the error column and, when present, the elevation column of a ``.npy`` array."""
    a = np.load(io.BytesIO(raw), allow_pickle=False).astype(float)
    if a.ndim == 1:
        return {"error": a}
    if a.ndim == 2 and a.shape[1] in (1, 2):
        return {"error": a[:, 0]} | ({"elevation": a[:, 1]} if a.shape[1] == 2 else {})
    raise InputError(f"array shape {a.shape}: expected (n,), (n, 1) or (n, 2)", path=p)


def _read_text(text: str, delim: str | None) -> _Table:
    """Return every column of a table of numbers (a cell that is no number: NaN)."""
    data = np.genfromtxt(io.StringIO(text), delimiter=delim, names=True, dtype=float)
    return {n.lower(): np.atleast_1d(data[n]).astype(float) for n in data.dtype.names or ()}


def _read_series_csv(text: str) -> _Table:
    """Return every column of a CSV table with text columns (a series table of psdbound)."""
    import pandas as pd

    head = text.split("\n", 1)[0].split(",")
    labels = {c.strip(): str for c in head if c.strip().lower() in _LABELS}
    df = pd.read_csv(io.StringIO(text), dtype=labels, skipinitialspace=True)
    df.columns = [str(c).strip().lower() for c in df.columns]
    return {
        c: (
            df[c].fillna("").to_numpy(dtype=str)
            if c in _LABELS
            else pd.to_numeric(df[c], errors="coerce").to_numpy(dtype=float)
        )
        for c in df.columns
    }


def _read_netcdf(p: Path, source: Path | io.BytesIO, *, hdf5: bool) -> _Table:
    """Return the one-dimensional variables of a netCDF file (netCDF 3 with SciPy's reader)."""
    import xarray as xr

    if hdf5 and not {"netcdf4", "h5netcdf"} & set(xr.backends.list_engines()):
        raise InputError(
            "netCDF-4 (HDF5) file: reading it needs the netCDF4 or h5netcdf package; "
            "install one, or write the series as netCDF 3 (psdbound export -o x.nc)",
            path=p,
        )
    try:
        with xr.open_dataset(source, engine=None if hdf5 else "scipy") as ds:
            return {str(n).lower(): _values(ds[n].values) for n in ds.variables if ds[n].ndim == 1}
    except (OSError, ValueError, TypeError) as exc:
        raise InputError(
            f"cannot read this netCDF file ({' '.join(str(exc).split())[:160]}): truncated or "
            "corrupt? Write it again (psdbound export -o x.nc)",
            path=p,
        ) from None


def _values(a: NDArray[Any]) -> NDArray[Any]:
    """Return a netCDF variable as floats, or as strings when it holds text."""
    if a.dtype.kind == "S":
        return np.char.decode(a, "utf-8")
    if a.dtype.kind in "OU":
        return np.asarray(a, dtype=str)
    return a.astype(float)


def _samples(p: Path, table: _Table, include_screened: bool) -> SampleFile:
    """Pick the error and elevation columns, check them, leave out the rows screened out."""
    names = list(table)
    err = next((n for n in names if n in _ERROR_NAMES), None)
    if err is None:
        raise InputError(
            f"no error column: header has {names}, expected one of {_ERROR_NAMES}", path=p
        )
    el = next((n for n in names if n in _EL_NAMES), None)
    columns = [(err, table[err])] + ([(el, table[el])] if el is not None else [])
    if columns[0][1].size == 0:
        raise InputError("no samples: the file has its header line only", path=p)
    for name, column in columns:
        if column.size != columns[0][1].size:
            raise InputError(f"{columns[0][1].size} errors but {column.size} {name}", path=p)
        _check_numbers(p, name, column)
    keep, left_out, notes = _kept_rows(p, table, include_screened)
    return SampleFile(
        errors=columns[0][1][keep],
        elevation_deg=columns[1][1][keep] if el is not None else None,
        segment_id=_segments(table, keep),
        left_out=left_out,
        notes=notes,
    )


def _kept_rows(
    p: Path, table: _Table, include_screened: bool
) -> tuple[NDArray[np.bool_], dict[str, int], tuple[str, ...]]:
    """Return the rows to use (not screened out, unless asked), what was left out, and notes."""
    n = next(iter(table.values())).size
    if _FLAG not in table:
        if include_screened:
            warn(
                "no 'screened' column: include_screened has nothing to include",
                path=p,
                stacklevel=4,
            )
        return np.ones(n, dtype=bool), {}, ()
    flag = np.char.strip(np.asarray(table[_FLAG], dtype=str))
    screened = flag != ""
    kinds, counts = np.unique(flag[screened], return_counts=True)
    why = ", ".join(f"{k} {c}" for k, c in zip(kinds, counts, strict=True))
    keep = np.ones(n, dtype=bool) if include_screened else ~screened
    notes = _window_note(table, keep & ~screened, int(keep.sum()))
    if include_screened:
        used = f"{int(screened.sum())} rows the fit screened out ({why}) are used, as asked"
        return keep, {}, notes + ((used,) if screened.any() else ())
    if not keep.any():
        raise InputError(
            f"every one of the {n} rows was screened out by the fit ({why}): nothing to "
            "overbound; include them explicitly (--include-screened) if that is meant",
            path=p,
        )
    if screened.any():
        warn(
            f"{int(screened.sum())} of {n} rows left out: the fit screened them out ({why}); "
            f"the overbound uses the {int(keep.sum())} kept rows (--include-screened, or "
            "include_screened=True, uses them all)",
            path=p,
            stacklevel=4,
        )
    return keep, dict(zip(kinds.tolist(), counts.tolist(), strict=True)), notes


def _window_note(table: _Table, kept: NDArray[np.bool_], used: int) -> tuple[str, ...]:
    """Say how many rows used lie in no stationary window of the fit (outside its bound)."""
    window = table.get("window")
    outside = 0 if window is None else int(np.count_nonzero(kept & (window == -1)))
    if not outside:
        return ()
    return (
        f"{outside} of the {used} rows used were kept by the fit's screening but lie in "
        "none of its stationary windows (window -1: outside its PSD bound); they are used",
    )


def _segments(table: _Table, keep: NDArray[np.bool_]) -> NDArray[np.int64] | None:
    """Return the number of the continuous piece of each row kept.

    A piece ends at a change of satellite (``sat``, text), at a time step
    (``t_gps_s``, s) that is not forward or exceeds ``_GAP_STEPS`` median
    steps, and where rows were left out. None without ``sat`` and ``t_gps_s``.
    """
    idx = np.flatnonzero(keep)
    sat, t = table.get("sat"), table.get("t_gps_s")
    use_sat = sat is not None and sat.dtype.kind == "U"
    use_t = t is not None and t.dtype.kind == "f" and bool(np.isfinite(t[idx]).all())
    if not (use_sat or use_t):
        return None
    new = np.diff(idx) > 1
    if use_sat:
        new |= sat[idx][1:] != sat[idx][:-1]
    if use_t:
        dt = np.diff(t[idx])
        step = float(np.median(dt[dt > 0])) if (dt > 0).any() else np.inf
        new |= ~((dt > 0) & (dt <= _GAP_STEPS * step))
    return np.concatenate([[0], np.cumsum(new)]).astype(np.int64)


def _check_numbers(p: Path, name: str, column: NDArray[np.float64]) -> None:
    """Refuse a column with missing or non-numeric cells (read as NaN), naming the first."""
    bad = np.flatnonzero(~np.isfinite(column))
    if bad.size:
        raise InputError(
            f"column {name!r}: {bad.size} of {column.size} samples are missing, not numbers "
            f"or infinite (the first is sample {int(bad[0]) + 1}, counted from 1 below the "
            "header); fix or remove those rows",
            path=p,
        )


def _qq_png(result: OverboundResult) -> bytes:
    """Return the Q-Q figure of an overbound as PNG (the report's figure and style)."""
    from psdbound.reports.figures_aviation import fig_overbound_qq
    from psdbound.reports.render import rasterize

    title = f"Q-Q plot and {result.method} Gaussian overbounds per elevation bin"
    fig = fig_overbound_qq(result.to_dict(), result.qq_points(), title=title, unit=result.unit)
    return rasterize(title, fig).png


def write_overbound(
    result: OverboundResult, out: str | Path, *, extra: dict[str, Any] | None = None
) -> list[Path]:
    """Write ``overbound.json``, ``overbound_qq.png`` and ``overbound.html`` into ``out``.

    Each file is written atomically; ``overbound.json`` follows
    ``psdbound/results/overbound.schema.json``, ``overbound.html`` shows the
    table and the figure (:func:`psdbound.reports.page.write_page`).

    Parameters
    ----------
    result : OverboundResult
    out : str or Path
        Existing, writable folder.
    extra : dict, optional
        More top-level sections of ``overbound.json`` (e.g. ``code_multipath``:
        how the samples were computed).

    Returns
    -------
    list of Path
        The files written.
    """
    from psdbound.reports.page import write_page

    folder = Path(out)
    doc = {**(extra or {}), "overbound": result.to_dict()}
    j = write_json(folder / "overbound.json", doc)
    qq = _qq_png(result)
    png = atomic_write_bytes(folder / "overbound_qq.png", qq)
    u = result.unit
    rows = [
        [
            b.label,
            str(b.n),
            f"{b.n_eff:.0f}",
            f"{b.bias:.4g}",
            f"{b.sigma:.4g}",
            f"{b.inflation:.2f}",
            f"{b.sigma_upper:.4g}",
            f"{b.inflation_upper:.2f}",
        ]
        for b in result.bins
    ]
    head = [
        "elevation bin",
        "n",
        "n_eff",
        f"bias [{u}]",
        f"sigma [{u}]",
        "inflation",
        f"sigma at {100 * result.bins[0].confidence:g} % [{u}]" if result.bins else "sigma",
        "inflation at confidence",
    ]
    html = write_page(
        folder / "overbound.html",
        command="overbound",
        title=f"{result.method} Gaussian overbounds per elevation bin",
        json_name="overbound.json",
        lines=[result.summary().splitlines()[0]],
        table=(head, rows),
        figures=[
            (
                "Q-Q plot of each bin with its overbound; sigma and sample std per bin.",
                qq,
                "overbound_qq.png",
            )
        ],
    )
    return [Path(j), Path(png), html]
