"""The first stage: read the observation and orbit files and decide what they are.

One station (its consecutive files merged in time) is a dual-frequency run;
a dual-antenna pair is named explicitly (``--pair A B`` or ``[inputs] pair``,
or ``method = "da"`` with the files of exactly two antennas). Files of
anything else are an error that names the stations, never a silent drop.
"""

from __future__ import annotations

import tempfile
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np

from psdbound.common import file_sha256
from psdbound.errors import InputError
from psdbound.io import Observations, orbit_coverage, read_obs, read_orbit
from psdbound.io.archive import extract_zip, zip_members
from psdbound.io.geometry import ecef_to_geodetic
from psdbound.io.merge import merge_observations, same_station, station_key
from psdbound.pipeline.config import InputsConfig
from psdbound.pipeline.products import InputData

__all__ = ["Progress", "quiet", "read_inputs"]

Progress = Callable[[str], None]


def quiet(msg: str) -> None:
    """Default progress callback: say nothing."""


def _method(inputs: InputsConfig, n_stations: int) -> str:
    """Return the isolation method from the options and the number of antennas."""
    m = inputs.method.lower()
    if inputs.pair:
        if m == "df":
            raise InputError("--pair names a dual-antenna pair but --method is df")
        m = "da"
    if m == "auto":
        return "df"
    if m not in ("df", "da"):
        raise InputError(f"--method must be df, da or auto, got {inputs.method!r}")
    if m == "da" and n_stations != 2:
        raise InputError(
            f"--method da needs the files of two antennas, got {n_stations} station(s)"
        )
    return m


def _read_observations(
    paths: Sequence[Path], system: str, codes: Sequence[str] | None = None
) -> list[Observations]:
    """Read every observation file; a zip archive of several files gives one per member.

    ``codes``: the only observation codes kept (a dual-frequency run needs its
    phase pair only: a third of the memory of a typical file), with the first
    carrier's SNR where the file has it.
    """
    from psdbound.validation.site import snr_signal

    optional = (snr_signal(codes[0]),) if codes else ()
    out = []
    for p in paths:
        if len(zip_members(p)) > 1:
            with tempfile.TemporaryDirectory(prefix="psdbound-zip-") as tmp:
                for member in extract_zip(p, tmp):
                    o = read_obs(member, systems=system, codes=codes, optional_codes=optional)
                    out.append(replace(o, path=f"{p}:{member.name}"))
        else:
            out.append(read_obs(p, systems=system, codes=codes, optional_codes=optional))
    return out


def _codes_needed(options: InputsConfig) -> tuple[str, ...] | None:
    """Return the codes a run reads: the phase pair for dual-frequency, everything for a pair."""
    from psdbound.io import DEFAULT_SIGNALS

    if options.pair or options.method.lower() != "df" and options.method.lower() != "auto":
        return None  # dual-antenna: the clock estimate may use any pseudorange
    signals = tuple(options.signals) or DEFAULT_SIGNALS.get(options.system)
    return tuple(signals) if signals else None


def _name(group: list[Observations]) -> str:
    """Marker name of a station group (or its first file's name)."""
    o = group[0]
    return (o.header.marker_name or "").strip() or Path(o.path).name


def _label(group: list[Observations]) -> str:
    """Name of a station group for messages: marker name (or file) and file count."""
    return f"{_name(group)} ({len(group)} file{'s' if len(group) > 1 else ''})"


def _is_file(item: str, obs: Observations) -> bool:
    path = str(obs.path)
    base = path.split(":", 1)[0] if not Path(path).exists() else path
    try:
        return Path(item).resolve() in (Path(path).resolve(), Path(base).resolve())
    except OSError:
        return False


def _matches(item: str, obs: Observations) -> bool:
    """Whether a ``--pair`` item (file name or station name) designates this file."""
    if Path(item).is_file():
        return _is_file(item, obs)
    marker = (obs.header.marker_name or "").strip().upper()
    return item.strip().upper() in (marker, station_key(obs))


def _group_stations(
    obs: Sequence[Observations], pair: Sequence[str] = ()
) -> list[list[Observations]]:
    """Return the files grouped by antenna (the pair's antennas first, A then B)."""
    groups: list[list[Observations]] = []
    if pair:
        seeds = []
        for item in pair:
            hits = [o for o in obs if _matches(item, o)]
            if not hits:
                names = ", ".join(_label(g) for g in _group_stations(obs))
                raise InputError(
                    f"--pair {item!r}: no observation file of that station or name among the "
                    f"inputs (stations: {names}); name a station or give its file"
                )
            seeds.append(hits)
        if any(o in seeds[1] for o in seeds[0]):
            raise InputError(f"--pair {pair[0]!r} {pair[1]!r} names the same files twice")
        groups = [list(seeds[0]), list(seeds[1])]
    for o in obs:
        if any(o in g for g in groups):
            continue
        home = [g for g in groups if same_station(g[0], o)]
        if len(home) > 1 and pair:
            raise InputError(
                f"{o.path} could belong to either antenna of --pair {pair[0]} {pair[1]} "
                "(same marker name, close positions): give each antenna's files by name"
            )
        if home:
            home[0].append(o)
        else:
            groups.append([o])
    return groups


def _check_stations(groups: list[list[Observations]], options: InputsConfig) -> None:
    """Refuse stations the run would not use, with their names and a remedy."""
    names = ", ".join(_label(g) for g in groups)
    if options.pair and len(groups) > 2:
        extra = ", ".join(_label(g) for g in groups[2:])
        raise InputError(
            f"observation files of {extra} are not part of --pair {options.pair[0]} "
            f"{options.pair[1]}: remove them (a campaign fits many stations)"
        )
    if len(groups) > 2:
        raise InputError(
            f"observation files of {len(groups)} stations: {names}; fit one station (its "
            "consecutive files are merged) or a dual-antenna pair (--pair A B); "
            "`psdbound campaign` fits many stations"
        )
    if len(groups) == 2 and not options.pair and options.method.lower() != "da":
        a, b = (_name(g) for g in groups)
        if a.upper() == b.upper() or " " in a + b:  # same marker: name the files
            a, b = (str(g[0].path) for g in groups)
        if options.method.lower() == "df":
            raise InputError(
                f"--method df needs the files of one station, got two: {names}"
            )
        raise InputError(
            f"observation files of two stations: {names}; fit one station's files, or name "
            f"a dual-antenna pair explicitly: --pair {a} {b} (or [inputs] pair in TOML)"
        )


def _positions(options: InputsConfig, n: int) -> tuple[tuple[float, float, float] | None, ...]:
    """Antenna positions given by the user (None: the header's), one per antenna."""
    given = [tuple(x) for x in options.receiver_xyz_m] + [None] * n
    rx = given[:n]
    for k, p in enumerate((options.position_a_m, options.position_b_m)[:n]):
        if p is not None:
            rx[k] = tuple(p)
    if options.position_b_m is not None and n < 2:
        raise InputError(
            "--position-b is the position of antenna B of a dual-antenna pair, but the run "
            "has one station; use --position-a"
        )
    return tuple(rx)


def read_inputs(options: InputsConfig, *, progress: Progress = quiet,
                extra_codes: tuple[str, ...] = ()) -> InputData:  # fmt: skip
    """Read the observation and orbit files (or the embedded demo when none are given).

    Parameters
    ----------
    options : InputsConfig
        Files, method, pair, system, antenna positions.
    progress : callable, optional
        Called with a short message.
    extra_codes : tuple of str, optional
        Pseudorange codes another stage needs (the code-multipath stage);
        when given, every observation code is read (that stage picks its
        carriers itself).

    Returns
    -------
    InputData

    Raises
    ------
    InputError
        A missing file, files of stations the run would not use (named), a
        pair that names no input, orbits that do not cover the observations.
    """
    obs_paths = [Path(p) for p in options.obs]
    for item in options.pair:  # pair members given as files are inputs too
        if Path(item).is_file() and Path(item).resolve() not in [q.resolve() for q in obs_paths]:
            obs_paths.append(Path(item))
    nav_path = Path(options.nav) if options.nav else None
    demo = None
    method_options = options
    if not obs_paths:
        from psdbound.simulate import demo_data

        progress("demo data (simulated on first use)")
        data = demo_data()
        obs_paths, nav_path = [data.obs_paths[0]], data.nav_path
        demo = data.truth_meta()
        method_options = InputsConfig(method="df")
    for p in obs_paths:
        if not p.is_file():
            raise InputError("observation file not found", path=p)
    if nav_path is None:
        raise InputError("a navigation (or SP3) file is needed for elevations: give --nav")
    progress(f"reading {len(obs_paths)} observation file(s) and {nav_path.name}")
    codes = None if extra_codes else _codes_needed(method_options)
    groups = _group_stations(_read_observations(obs_paths, options.system, codes), options.pair)
    _check_stations(groups, method_options)
    method = _method(method_options, len(groups))
    if method == "df":
        default = InputsConfig()
        for key in ("baseline", "baseline_tolerance_m"):
            if getattr(options, key) != getattr(default, key):
                raise InputError(
                    f"{key} = {getattr(options, key)!r} is a dual-antenna option, but the files "
                    f"are one station ({_label(groups[0])}): name a pair or remove it"
                )
    obs = tuple(merge_observations(g) for g in groups)
    merged = [f"{station_key(g[0])}: {len(g)} observation files merged in time order into one "
              f"data set ({len(obs[k].t_gps_s)} epochs)"
              for k, g in enumerate(groups) if len(g) > 1]  # fmt: skip
    if merged:
        progress("; ".join(merged))
    orbit = read_orbit(nav_path)
    coverage_notes: list[str] = []
    for o in obs:  # orbits of another day or without the system: one clear error (exit 2)
        cov = orbit_coverage(orbit, o, options.system)
        cov.require(options.system)
        coverage_notes += [f"{nav_path.name}: {w}" for w in cov.warnings(options.system)]
    rx = _positions(options, len(obs))
    pos = obs[0].header.approx_position_m if rx[0] is None else np.asarray(rx[0])
    lat = lon = None
    if pos is not None:
        la, lo, _ = ecef_to_geodetic(np.asarray(pos))
        lat, lon = float(la), float(lo)
    files = tuple(
        {"role": role, "name": p.name, "path": str(p), "sha256": file_sha256(p)}
        for role, p in [*(("obs", q) for q in obs_paths), ("nav", nav_path)]
    )
    year = int(str(obs[0].times[0])[:4])
    notes = tuple(str(w) for o in (*obs, orbit) for w in getattr(o, "warnings", ()) or ())
    notes += tuple(merged) + tuple(coverage_notes)
    return InputData(method, obs, orbit, files, rx, lat, lon, year, demo, notes)
