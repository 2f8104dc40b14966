"""Reading RINEX observation files into :class:`Observations`.

One front function, :func:`read_obs`, dispatches on the RINEX version found in
the header (2.1x, or 3.0x and 4.00-4.02, which share the data layout) and
accepts plain, gzip/Z/bz2/zip and Hatanaka (compact RINEX) files.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from psdbound.common.notices import warn
from psdbound.errors import InputError, NoDataError
from psdbound.io._body import RawBlock, parse_v2, parse_v3
from psdbound.io._checks import check_phase_rates, range_reference
from psdbound.io._header import SYSTEM_NAMES as _SYSTEM_NAMES
from psdbound.io._header import ObsHeader, missing_systems
from psdbound.io._header import parse_header as _parse_header
from psdbound.io._source import read_bytes
from psdbound.io.signals import RINEX2_TO_RINEX3, wavelength_m
from psdbound.io.timescales import gps_s_to_datetime64

__all__ = [
    "Observations",
    "ObsHeader",
    "SYSTEM_NAMES",
    "SystemBlock",
    "epoch_interval_s",
    "read_obs",
]

#: Name of each satellite system letter, e.g. ``SYSTEM_NAMES['R'] == 'GLONASS'``.
SYSTEM_NAMES: Mapping[str, str] = _SYSTEM_NAMES


@dataclass(frozen=True)
class SystemBlock:
    """All observations of one satellite system.

    Attributes
    ----------
    system : str
        System letter (``G``, ``E``, ...).
    sats : tuple of str
        Satellites, e.g. ``("G01", "G02")``; axis 1 of the arrays.
    codes : tuple of str
        Observation codes as written in the file (``L1C``; RINEX 2 ``L1``);
        axis 2 of the arrays.
    values : ndarray of float64, shape (n_epoch, n_sat, n_code)
        Observations in RINEX units (phase in cycles, code in metres, SNR in
        dB-Hz, Doppler in Hz). NaN where the field is blank or the satellite
        is not in the epoch; receiver-written zeros are kept as zeros.
    lli : ndarray of int8, same shape
        Loss-of-lock indicator digit (bit 0 = lost lock); -1 where blank.
    ssi : ndarray of int8, same shape
        Signal strength indicator digit; -1 where blank.
    """

    system: str
    sats: tuple[str, ...]
    codes: tuple[str, ...]
    values: NDArray[np.float64]
    lli: NDArray[np.int8]
    ssi: NDArray[np.int8]


@dataclass(frozen=True)
class Observations:
    """Observations of one RINEX observation file.

    Attributes
    ----------
    path : str
        The file read.
    header : ObsHeader
        Header information (station, receiver, approximate position...).
    t_gps_s : ndarray of float64, shape (n_epoch,)
        Epochs in GPS seconds since 1980-01-06 (GPS time scale), whatever
        the file's time system.
    epoch_flag : ndarray of int8, shape (n_epoch,)
        RINEX epoch flag (0 OK, 1 power failure since the previous epoch).
    blocks : mapping of str to SystemBlock
        Observations per satellite system.
    warnings : tuple of str
        What the reader repaired or ignored (repeated epochs dropped, header
        values that disagree with the data), one line each, naming the file
        and line; also issued as :class:`~psdbound.common.notices.PsdboundWarning`.
    systems_in_file : tuple of str
        System letters of every satellite record in the file, sorted, read or
        not (``systems=`` of :func:`read_obs` reads some); empty when not known.
    """

    path: str
    header: ObsHeader
    t_gps_s: NDArray[np.float64]
    epoch_flag: NDArray[np.int8]
    blocks: Mapping[str, SystemBlock]
    warnings: tuple[str, ...] = ()
    systems_in_file: tuple[str, ...] = ()

    @property
    def systems(self) -> tuple[str, ...]:
        """System letters present, in file order."""
        return tuple(self.blocks)

    @property
    def satellites(self) -> tuple[str, ...]:
        """All satellites with at least one epoch, sorted."""
        return tuple(sorted(s for b in self.blocks.values() for s in b.sats))

    @property
    def times(self) -> NDArray[np.datetime64]:
        """Epochs as GPS-time calendar labels (``datetime64[ns]``, not UTC)."""
        return gps_s_to_datetime64(self.t_gps_s)

    @property
    def interval_s(self) -> float:
        """Sampling interval in seconds, from the epochs.

        The median step between consecutive epochs; the header's ``INTERVAL``
        when it agrees within 0.1 % (the nominal value, free of clock
        jitter), or when there are fewer than two epochs.

        Raises
        ------
        NoDataError
            Fewer than two epochs and no usable ``INTERVAL`` record.
        """
        return epoch_interval_s(self.t_gps_s, self.header.interval_s, self.path)

    def codes(self, system: str) -> tuple[str, ...]:
        """Observation codes read for a system."""
        return self._block(system).codes

    def resolve_code(self, system: str, code: str) -> str:
        """Return the code as stored in the file for a requested signal.

        RINEX 3 names (``L1C``, ``L2W``) are accepted for RINEX 2 files and
        mapped with :data:`psdbound.io.signals.RINEX2_TO_RINEX3`.

        Raises
        ------
        InputError
            If the signal is not in the file, listing the codes that are.
        """
        block = self._block(system)
        if code in block.codes:
            return code
        for v2, v3 in RINEX2_TO_RINEX3.items():
            if v3 == code and v2 in block.codes:
                return v2
        raise InputError(
            f"signal {code!r} is not in the file for {_SYSTEM_NAMES.get(system, system)}; "
            f"available: {' '.join(block.codes)}",
            path=self.path,
        )

    def file_code(self, system: str, code: str) -> str | None:
        """Return the code as stored in the file, as :meth:`resolve_code`; None when absent."""
        if system not in self.blocks:
            return None
        try:
            return self.resolve_code(system, code)
        except InputError:
            return None

    def phase_count(self, system: str, code: str) -> int:
        """Return how many observations of a code the file holds for a system (0: none).

        ``code`` as for :meth:`resolve_code` (RINEX 3 names also for RINEX 2
        files); a code the file does not have counts 0. Receiver-written zero
        phases do not count.
        """
        stored = self.file_code(system, code)
        if stored is None:
            return 0
        block = self._block(system)
        v = block.values[:, :, block.codes.index(stored)]
        return int(np.count_nonzero(np.isfinite(v) & (v != 0.0)))

    def get(self, sat: str, code: str) -> NDArray[np.float64]:
        """Observation series of one satellite and code (NaN where absent)."""
        block, i, k = self._locate(sat, code)
        return block.values[:, i, k]

    def lli(self, sat: str, code: str) -> NDArray[np.int8]:
        """Loss-of-lock indicator series (-1 where blank)."""
        block, i, k = self._locate(sat, code)
        return block.lli[:, i, k]

    def phase_m(self, sat: str, code: str) -> NDArray[np.float64]:
        """Carrier phase of a satellite in metres (cycles times wavelength).

        Receiver-written zero phases are returned as NaN (not tracked).
        """
        if not self.resolve_code(sat[0], code).startswith("L"):
            raise InputError(f"{code!r} is not a carrier-phase code", path=self.path)
        cycles = self.get(sat, code)
        lam = wavelength_m(sat, RINEX2_TO_RINEX3.get(code, code), self.header.glonass_channels)
        out = cycles * lam
        out[cycles == 0.0] = np.nan
        return out

    def with_glonass_channels(self, channels: Mapping[str, int]) -> Observations:
        """Return these observations with GLONASS frequency numbers added.

        The header's own ``GLONASS SLOT / FRQ #`` values are kept; ``channels``
        fills the satellites it lacks (e.g. RINEX 2 files, which have no such
        record, with the numbers of a GLONASS navigation file).

        Parameters
        ----------
        channels : mapping of str to int
            FDMA frequency number ``k`` per satellite (``{'R01': 1, ...}``),
            e.g. :attr:`psdbound.io.Navigation.glonass_channels`.

        Returns
        -------
        Observations
            ``self`` when nothing is added, else a copy whose
            :meth:`phase_m` can convert the GLONASS FDMA phases to metres.

        """
        own = self.header.glonass_channels
        extra = {str(k): int(v) for k, v in channels.items() if k not in own}
        if not extra:
            return self
        header = replace(self.header, glonass_channels={**extra, **own})
        return replace(self, header=header)

    def summary(self) -> str:
        """Describe the file content in a few lines of text."""
        h = self.header
        span = (self.t_gps_s[-1] - self.t_gps_s[0]) if self.t_gps_s.size else 0.0
        try:
            interval = f"{self.interval_s:g} s"
        except NoDataError:
            interval = "unknown (one epoch)"
        out = [
            f"{Path(self.path).name}: RINEX {h.version:.2f}, station {h.marker_name or '?'}, "
            f"receiver {h.receiver_type or '?'}",
            f"  epochs: {self.t_gps_s.size}, span {span / 3600:.2f} h, interval "
            f"{interval}, first {self.times[0] if self.t_gps_s.size else '-'} GPST",
        ]
        for sys_, b in self.blocks.items():
            out.append(
                f"  {_SYSTEM_NAMES.get(sys_, sys_)} ({sys_}): {len(b.sats)} satellites; "
                f"codes {' '.join(b.codes)}"
            )
        return "\n".join(out)

    def _block(self, system: str) -> SystemBlock:
        try:
            return self.blocks[system]
        except KeyError:
            raise NoDataError(
                f"no {_SYSTEM_NAMES.get(system, system)} ({system}) observations in the file; "
                f"systems present: {' '.join(self.blocks) or 'none'}",
                path=self.path,
            ) from None

    def _locate(self, sat: str, code: str) -> tuple[SystemBlock, int, int]:
        block = self._block(sat[0])
        code = self.resolve_code(sat[0], code)
        try:
            i = block.sats.index(sat)
        except ValueError:
            raise NoDataError(f"satellite {sat} has no observations", path=self.path) from None
        return block, i, block.codes.index(code)


def _with_reference_codes(
    header: ObsHeader, systems: set[str] | None, codes: set[str] | None
) -> set[str] | None:
    """Return the codes to read: the wanted ones and the pseudoranges the column check uses.

    :func:`psdbound.io._checks.check_phase_rates` compares every phase with
    the pseudorange :func:`~psdbound.io._checks.range_reference` picks from
    the file's type list: reading it too makes a damaged type list as
    detectable with ``codes`` as without.
    """
    if codes is None:
        return None
    out = set(codes)
    for s, types in header.obs_types.items():
        if systems is not None and s not in systems:
            continue
        for c in types:
            ref = range_reference(types, c) if c in codes and c[0] == "L" else None
            if ref is not None:
                out.add(ref)
    return out


def _keep_codes(raw: dict[str, RawBlock], codes: set[str]) -> dict[str, RawBlock]:
    """Drop the columns read only for the column check."""
    out = {}
    for s, b in raw.items():
        k = [i for i, c in enumerate(b.codes) if c in codes]
        if k:
            out[s] = RawBlock(
                s,
                b.sats,
                tuple(b.codes[i] for i in k),
                b.values[:, :, k],
                b.lli[:, :, k],
                b.ssi[:, :, k],
            )
    return out


def _alternatives_in_header(
    code: str | Sequence[str], header: ObsHeader, want_sys: set[str] | None
) -> set[str]:
    """Return the header's codes for ``code``, or for every alternative when a sequence is given.

    A sequence is a carrier's candidates (:data:`psdbound.arcs.SIGNAL_CANDIDATES`): all those
    the header lists are kept, and the caller picks among them by the phases the file holds.
    """
    if isinstance(code, str):
        return _codes_in_header(code, header, want_sys)
    return set().union(*(_codes_in_header(c, header, want_sys) for c in code))


def _codes_in_header(code: str, header: ObsHeader, want_sys: set[str] | None) -> set[str]:
    """Return the header's codes for ``code`` (itself, or its RINEX 2 name), for the systems."""
    out = set()
    for s, types in header.obs_types.items():
        if want_sys is not None and s not in want_sys:
            continue
        if code in types:
            out.add(code)
        elif header.version < 3 and RINEX2_TO_RINEX3.get(code) is None:
            alias = [v2 for v2, v3 in RINEX2_TO_RINEX3.items() if v3 == code and v2 in types]
            out.update(alias[:1])
    return out


def _check_systems(p: Path, want_sys: set[str], header: ObsHeader) -> None:
    """Refuse unknown system letters and systems without observation types in the header."""
    unknown = want_sys - set(_SYSTEM_NAMES)
    if unknown:
        raise InputError(
            f"unknown satellite system {''.join(sorted(unknown))!r}; expected letters "
            f"from {''.join(_SYSTEM_NAMES)}",
            path=p,
        )
    absent = want_sys - set(header.obs_types)
    if absent:
        raise missing_systems(p, absent, header.obs_types, "its header's observation types")


def _wanted_codes(
    p: Path,
    header: ObsHeader,
    want_sys: set[str] | None,
    codes: Iterable[str | Sequence[str]] | None,
    optional_codes: Iterable[str],
) -> set[str] | None:
    """Return the header's codes to keep (None: all); refuse a requested code it lacks."""
    if codes is None:
        return None
    want_codes = set()
    for c in codes:
        found = _alternatives_in_header(c, header, want_sys)
        if not found:
            avail = sorted(
                {
                    t
                    for s, ts in header.obs_types.items()
                    for t in ts
                    if want_sys is None or s in want_sys
                }
            )
            wanted = repr(c) if isinstance(c, str) else "any of " + ", ".join(c)
            raise InputError(
                f"observation code {wanted} is not in the header; available: {' '.join(avail)}",
                path=p,
            )
        want_codes |= found
    for c in optional_codes:
        want_codes |= _codes_in_header(c, header, want_sys)
    return want_codes


def _interval_note(t: NDArray[np.float64], header: ObsHeader, p: Path) -> str | None:
    """Return a note when the header's INTERVAL disagrees with the epochs' spacing."""
    hi = header.interval_s
    if t.size >= 2 and hi:
        dt = epoch_interval_s(t, None, p)
        if abs(hi - dt) > 1e-3 * dt:
            return (
                f"the header's INTERVAL {hi:g} s disagrees with the epochs, {dt:g} s apart; "
                "the epochs' interval is used"
            )
    return None


def _check_found(p: Path, want_sys: set[str] | None, found: Iterable[str]) -> None:
    """Refuse requested systems without any epoch of observations."""
    if want_sys is not None:
        missing = sorted(want_sys - set(found))
        if missing:
            names = ", ".join(f"{_SYSTEM_NAMES[s]} ({s})" for s in missing)
            raise NoDataError(f"no epochs with {names} observations in the file", path=p)


def _issue(notes: list[str], p: Path) -> tuple[str, ...]:
    """Issue the notes as warnings (at read_obs's caller), a leading ``line N:`` as the line."""
    issued: list[str] = []
    for note in notes:
        m = re.match(r"line (\d+): (.*)", note, re.S)
        line, text = (int(m.group(1)), m.group(2)) if m else (None, note)
        issued.append(warn(text, path=p, line=line, stacklevel=3))
    return tuple(issued)


def read_obs(
    path: str | os.PathLike[str],
    *,
    systems: str | Iterable[str] | None = None,
    codes: Iterable[str | Sequence[str]] | None = None,
    optional_codes: Iterable[str] = (),
) -> Observations:
    """Read a RINEX 2.1x, 3.0x or 4.00-4.02 observation file.

    Parameters
    ----------
    path : str or path-like
        Observation file: plain, gzip/Z/bz2/zip, or Hatanaka (``.crx``,
        ``.??d``, possibly compressed).
    systems : str or iterable of str, optional
        System letters to keep (``"GE"`` or ``["G", "E"]``); all by default.
        Each requested system must have observations in the file.
    codes : iterable of str or of sequences of str, optional
        Observation codes to keep (``["L1C", "L2W"]``; for RINEX 2 files the
        RINEX 2 codes or their RINEX 3 equivalents). All by default. Each
        requested code must exist for at least one requested system; an item
        that is a sequence of codes (a carrier's alternatives) keeps every
        one of them the header lists and needs at least one.
    optional_codes : iterable of str, optional
        With ``codes``: further codes kept where the file has them (e.g. an
        SNR), without an error where it does not.

    Returns
    -------
    Observations
        Epochs in GPS seconds, observations per system with loss-of-lock and
        signal-strength indicators for every signal.

    Raises
    ------
    InputError
        For a missing, empty, truncated or corrupted file, a file that is not
        a RINEX observation file or of an unsupported version (before 2, from
        5 on), an unknown code, or a requested system with no epochs.

    Warns
    -----
    PsdboundWarning
        For what was repaired or ignored (also in
        :attr:`Observations.warnings`), e.g. header records of a type no
        RINEX version defines (skipped, counted in one warning) or a version
        newer than 4.02 (read with the 4.02 layout).

    See Also
    --------
    read_orbit : Broadcast or precise orbits for the same period.
    find_arcs : Continuous tracking arcs of a phase pair.
    psdbound.io.merge.merge_observations : Consecutive files of one station as one data set.

    References
    ----------
    .. [1] IGS RINEX Working Group and RTCM-SC104 (2020). RINEX, The Receiver
       Independent Exchange Format, Version 3.05; (2021-2024) Versions 4.00-4.02.
    .. [2] Gurtner, W., & Estey, L. (2007). RINEX, Version 2.11.
    .. [3] Hatanaka, Y. (2008). A compression format and tools for GNSS
       observation data. *Bulletin of the Geographical Survey Institute*, 55.

    Examples
    --------
    >>> from psdbound.simulate import demo_data
    >>> obs = read_obs(demo_data().obs_paths[0], systems="G")
    >>> obs.interval_s, obs.blocks["G"].codes
    (1.0, ('C1C', 'L1C', 'S1C', 'C2W', 'L2W', 'S2W'))
    >>> obs.phase_m("G05", "L1C").shape == obs.t_gps_s.shape   # metres, NaN where absent
    True
    """
    p = Path(path)
    text = read_bytes(p)
    header, start = _parse_header(text, p)
    want_sys = None if systems is None else set(systems)
    if want_sys is not None:
        _check_systems(p, want_sys, header)
    want_codes = _wanted_codes(p, header, want_sys, codes, optional_codes)
    read_codes = _with_reference_codes(header, want_sys, want_codes)
    if header.version >= 3:  # a view, not a copy of the data section (tens of MB a day at 1 Hz)
        parsed = parse_v3(memoryview(text)[start:], header, p, want_sys, read_codes)
    else:
        parsed = parse_v2(text[start:], header, p, want_sys, read_codes)
    t, flags, raw, notes, in_file = parsed
    if t.size == 0:
        raise NoDataError("no observation epochs after the header", path=p)
    check_phase_rates(t, raw, header, p)
    if read_codes != want_codes:
        raw = _keep_codes(raw, want_codes)
    notes = list(header.notes) + list(notes)
    interval = _interval_note(t, header, p)
    if interval is not None:
        notes.append(interval)
    _check_found(p, want_sys, raw)
    blocks = {
        s: SystemBlock(b.system, b.sats, b.codes, b.values, b.lli, b.ssi) for s, b in raw.items()
    }
    return Observations(str(p), header, t, flags, blocks, _issue(notes, p), in_file)


def epoch_interval_s(
    t_gps_s: NDArray[np.float64], header_interval_s: float | None, path: str | os.PathLike[str]
) -> float:
    """Return the sampling interval of epochs (see :attr:`Observations.interval_s`).

    Parameters
    ----------
    t_gps_s : ndarray of float64
        Increasing epochs, s.
    header_interval_s : float or None
        The header's ``INTERVAL``, s.
    path : str or path-like
        The file (for messages).

    Returns
    -------
    float
        Seconds.
    """
    t = np.asarray(t_gps_s, dtype=np.float64)
    steps = np.diff(t)
    steps = steps[steps > 0]
    if steps.size:
        dt = float(np.median(steps))
        if header_interval_s and abs(header_interval_s - dt) <= 1e-3 * dt:
            return float(header_interval_s)
        return round(dt, 6)
    if header_interval_s:
        return float(header_interval_s)
    raise NoDataError("fewer than two epochs: sampling interval unknown", path=path)
