"""Files of the aviation commands: read error samples, write the overbound outputs.

Input (:func:`read_samples`): a ``.npy`` array (one column of errors, or two
columns ``error, elevation_deg``) or a text/CSV file with a header naming an
``error`` column (any of ``error``, ``multipath``, ``value``) and optionally an
``elevation`` column (``elevation``, ``elevation_deg``, ``el``). Output
(:func:`write_overbound`): ``overbound.json`` (per-bin sigma, bias, inflation
factor, counts) and ``overbound_qq.png`` (the Q-Q figure: each bin's sample
quantiles against standard-normal quantiles, with its overbound line),
written atomically.
"""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.aviation.overbound import OverboundResult
from psdbound.common.atomic import atomic_write_bytes
from psdbound.errors import InputError
from psdbound.results import write_json

__all__ = ["read_samples", "write_overbound"]

_ERROR_NAMES = ("error", "multipath", "value", "error_m", "multipath_m", "value_m")
_EL_NAMES = ("elevation", "elevation_deg", "el")


def read_samples(path: str | Path) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """Read error samples (and elevations, degrees, when present).

    Parameters
    ----------
    path : str or Path
        ``.npy`` or CSV/whitespace text with a header line.

    Returns
    -------
    errors : ndarray
        Unit of the file.
    elevation_deg : ndarray or None

    Raises
    ------
    InputError
        Missing or unreadable file, no error column (the file is named).
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
        columns = _read_npy(p) if p.suffix == ".npy" else _read_text(p)
    except InputError:
        raise
    except (OSError, ValueError, IndexError) as exc:
        raise InputError(
            f"cannot read samples ({' '.join(str(exc).split())[:160]}); expected a header line "
            f"naming an error column ({', '.join(_ERROR_NAMES)}) and optionally an elevation "
            f"column ({', '.join(_EL_NAMES)}), then one row of numbers per sample, comma- or "
            "whitespace-separated, or a .npy array",
            path=p,
        ) from None
    if columns[0][1].size == 0:
        raise InputError("no samples: the file has its header line only", path=p)
    for name, column in columns:
        _check_numbers(p, name, column)
    return columns[0][1], (columns[1][1] if len(columns) > 1 else None)


_Columns = list[tuple[str, NDArray[np.float64]]]


def _read_npy(p: Path) -> _Columns:
    """Return the error column and, when present, the elevation column of a ``.npy`` array."""
    a = np.load(p, allow_pickle=False).astype(float)
    if a.ndim == 1:
        return [("error", a)]
    if a.ndim == 2 and a.shape[1] in (1, 2):
        return [("error", a[:, 0])] + ([("elevation", a[:, 1])] if a.shape[1] == 2 else [])
    raise InputError(f"array shape {a.shape}: expected (n,), (n, 1) or (n, 2)", path=p)


def _read_text(p: Path) -> _Columns:
    """Return the named error column and, when present, the elevation column of a table."""
    text = p.read_text()
    delim = "," if "," in text.splitlines()[0] else None
    data = np.genfromtxt(io.StringIO(text), delimiter=delim, names=True, dtype=float)
    cols = data.dtype.names or ()
    names = [n.lower() for n in cols]
    err = next((n for n in names if n in _ERROR_NAMES), None)
    if err is None:
        raise InputError(
            f"no error column: header has {names}, expected one of {_ERROR_NAMES}", path=p
        )
    out = [(err, np.atleast_1d(data[cols[names.index(err)]]).astype(float))]
    el = next((n for n in names if n in _EL_NAMES), None)
    if el is not None:
        out.append((el, np.atleast_1d(data[cols[names.index(el)]]).astype(float)))
    return out


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
