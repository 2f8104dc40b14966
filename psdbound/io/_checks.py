"""Physical consistency of the observation columns with the header's type list.

A carrier phase in cycles times its wavelength changes like the range, and so
does every pseudorange: over consecutive epochs ``d(L lambda) / dC`` is 1
(within 1e-4 on real files; ionospheric divergence and noise are far below
1 %). A column that holds something else than the header says (another band,
a pseudorange, a Doppler or a signal strength read as a phase, because the
type list was damaged) gives another ratio: such a file is refused, naming
the type list's header line.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from psdbound.errors import InputError
from psdbound.io._body import RawBlock
from psdbound.io._header import ObsHeader
from psdbound.io.signals import RINEX2_TO_RINEX3, wavelength_m

#: Largest accepted departure of the median phase-to-code rate ratio from 1.
RATE_TOLERANCE = 0.01
#: Pairs of epochs needed before a column is judged.
MIN_PAIRS = 20
#: Range rates below this (m/s; geostationary satellites) say nothing about the ratio.
MIN_RANGE_RATE_M_S = 50.0
#: Range rates above this (m/s) are clock jumps or gaps, not satellite motion.
MAX_RANGE_RATE_M_S = 5000.0


def _wavelengths(block: RawBlock, code: str, header: ObsHeader) -> np.ndarray:
    out = np.full(len(block.sats), np.nan)
    name = RINEX2_TO_RINEX3.get(code, code)
    for i, sat in enumerate(block.sats):
        try:
            out[i] = wavelength_m(sat, name, header.glonass_channels)
        except InputError:
            pass  # unknown band or GLONASS channel: not judged
    return out


def range_reference(codes: Sequence[str], phase_code: str) -> str | None:
    """Return the pseudorange a phase is compared with: first of its band, else the first.

    Parameters
    ----------
    codes : sequence of str
        Observation codes, in the file's order.
    phase_code : str
        The phase code (``L..``).

    Returns
    -------
    str or None
        A ``C``/``P`` code of ``codes``; None when there is none.
    """
    ranges = [c for c in codes if c[0] in "CP"]
    return next((c for c in ranges if c[1] == phase_code[1]), ranges[0] if ranges else None)


def check_phase_rates(
    t_gps_s: np.ndarray, blocks: dict[str, RawBlock], header: ObsHeader, path: Path
) -> None:
    """Refuse phase columns whose changes do not follow the pseudorange changes.

    Parameters
    ----------
    t_gps_s : ndarray
        Epochs, s.
    blocks : dict of str to RawBlock
        The observations read, per system.
    header : ObsHeader
        For the GLONASS channels and the type lists' lines.
    path : Path
        The file (for messages).

    Raises
    ------
    InputError
        A phase column that changes ``r`` times as fast as the code
        (``|r - 1| > RATE_TOLERANCE``): the type list does not describe the
        data columns.
    """
    dt = np.diff(t_gps_s)
    for system, b in blocks.items():
        if not any(c[0] in "CP" for c in b.codes) or b.values.shape[0] < 2:
            continue
        for k, code in enumerate(b.codes):
            if code[0] != "L":
                continue
            j = b.codes.index(range_reference(b.codes, code))
            lam = _wavelengths(b, code, header)
            phase = b.values[:, :, k] * lam[None, :]
            rng = b.values[:, :, j]
            with np.errstate(invalid="ignore"):
                phase = np.where(b.values[:, :, k] == 0.0, np.nan, phase)
                rng = np.where(rng == 0.0, np.nan, rng)
                d_phase = np.diff(phase, axis=0)
                d_rng = np.diff(rng, axis=0)
                usable = (
                    np.isfinite(d_phase)
                    & np.isfinite(d_rng)
                    & (np.abs(d_rng) >= MIN_RANGE_RATE_M_S * dt[:, None])
                    & (np.abs(d_rng) <= MAX_RANGE_RATE_M_S * dt[:, None])
                )
            if usable.sum() < MIN_PAIRS:
                continue
            ratio = float(np.median(d_phase[usable] / d_rng[usable]))
            if abs(ratio - 1.0) > RATE_TOLERANCE:
                raise InputError(
                    f"observation {code} of system {system} does not follow the range: it "
                    f"changes {ratio:.4g} times as fast as {b.codes[j]} (expected 1); the "
                    "header's observation types do not describe the data columns (shifted, "
                    "missing or mislabelled types)",
                    path=path,
                    line=header.type_lines.get(system),
                )
