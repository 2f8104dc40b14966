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
from psdbound.io.archive import extract_zip, file_kind, member_label, relabel, zip_members
from psdbound.io.geometry import ecef_to_geodetic
from psdbound.io.merge import merge_observations, same_station, station_key
from psdbound.io.obs import SYSTEM_NAMES
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


Source = tuple[Path, str | None]  # a file to read, and its name as an archive member


def _unpack(paths: Sequence[Path], tmp: Path) -> tuple[list[Source], list[Path]]:
    """Extract the zip archives of several files among the observation files.

    Parameters
    ----------
    paths : sequence of Path
        The observation files as given.
    tmp : Path
        An empty folder for the members (one sub-folder per archive).

    Returns
    -------
    sources : list of (Path, str or None)
        The files to read as observations: the files given, and the members
        of each archive that are not navigation or SP3 files (with their
        ``archive.zip:member`` names).
    with_orbits : list of Path
        The archives that also hold navigation or SP3 members (a station's
        download of observations and navigation together).

    Raises
    ------
    InputError
        An archive that holds no observation file.
    """
    sources: list[Source] = []
    with_orbits: list[Path] = []
    for k, p in enumerate(paths):
        if len(zip_members(p)) <= 1:
            sources.append((p, None))
            continue
        folder = tmp / str(k)
        folder.mkdir()
        members = extract_zip(p, folder)
        kinds = [file_kind(m) for m in members]
        obs = [
            (m, member_label(p, m))
            for m, kind in zip(members, kinds, strict=True)
            if kind not in ("nav", "sp3")
        ]
        if not obs:
            raise InputError(
                f"the archive holds no observation file ({len(members)} navigation/SP3 files: "
                f"{', '.join(m.name for m in members[:4])}{', ...' if len(members) > 4 else ''})"
                "; give the observation files, and this archive as --nav",
                path=p,
            )
        if len(obs) < len(members):
            with_orbits.append(p)
        sources += obs
    return sources, with_orbits


def _read_observations(
    sources: Sequence[Source], system: str, codes: Sequence[str | tuple[str, ...]] | None = None
) -> list[Observations]:
    """Read every observation file (archive members named ``archive.zip:member``).

    ``codes``: the only observation codes kept (a dual-frequency run needs its
    phase pair only, or each carrier's candidates: a third of the memory of a
    typical file), with the first carrier's SNR and the phases that could be a
    third carrier
    (:func:`psdbound.arcs.third.third_candidates`) where the file has them.
    """
    from psdbound.arcs.third import third_candidates
    from psdbound.validation.site import snr_signal

    optional: tuple[str, ...] = ()
    if codes:
        first = (codes[0],) if isinstance(codes[0], str) else codes[0]
        pair = [c if isinstance(c, str) else c[0] for c in codes]
        optional = (*(snr_signal(c) for c in first), *third_candidates(system, pair))
    out = []
    for path, label in sources:
        try:
            o = read_obs(path, systems=system, codes=codes, optional_codes=optional)
        except InputError as exc:
            raise (relabel(exc, label) if label else exc) from None
        out.append(o if label is None else replace(o, path=label))
    return out


def _orbit_sources(
    nav: Sequence[Path], with_orbits: Sequence[Path]
) -> tuple[list[Path], list[str]]:
    """Return the orbit files: ``--nav``, else the observation archives that hold them.

    Returns the files and notes (archives whose navigation members are not
    used because ``--nav`` is given).
    """
    if nav:
        notes = [
            f"{p.name}: its navigation/SP3 members are not used (--nav given)" for p in with_orbits
        ]
        return list(nav), notes
    if with_orbits:
        return list(with_orbits), []
    raise InputError("a navigation (or SP3) file is needed for elevations: give --nav")


def _refuse_repeats(paths: Sequence[Path]) -> None:
    """Refuse an observation file given twice (by two names, or two copies of one file).

    Parameters
    ----------
    paths : sequence of Path
        The observation files, as given.

    Raises
    ------
    InputError
        Naming the file and the other name it was given under.
    """
    seen: dict[object, Path] = {}
    sizes: dict[int, list[Path]] = {}
    for p in paths:
        key = p.resolve()
        if key in seen:
            how = "twice" if str(seen[key]) == str(p) else f"twice (also as {seen[key]})"
            raise InputError(
                f"observation file given {how}: give each file once (the files of one "
                "station are merged in time order)",
                path=p,
            )
        seen[key] = p
        sizes.setdefault(p.stat().st_size, []).append(p)
    for same_size in (g for g in sizes.values() if len(g) > 1):
        digests: dict[str, Path] = {}
        for p in same_size:
            other = digests.setdefault(file_sha256(p), p)
            if other is not p:
                raise InputError(
                    f"observation file with the same content as {other}: the same "
                    "observations given twice; give each file once",
                    path=p,
                )


def _codes_needed(options: InputsConfig) -> tuple[str | tuple[str, ...], ...] | None:
    """Return the codes a run reads: the phase pair for dual-frequency, everything for a pair.

    Without given signals, each carrier's candidates (the file's pair is chosen among them
    once read: :func:`psdbound.arcs.default_pair`).
    """
    from psdbound.arcs import SIGNAL_CANDIDATES

    if options.pair or options.method.lower() != "df" and options.method.lower() != "auto":
        return None  # dual-antenna: the clock estimate may use any pseudorange
    if options.signals:
        return tuple(options.signals)
    return SIGNAL_CANDIDATES.get(options.system)


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


def _among(o: Observations, group: Sequence[Observations]) -> bool:
    """Whether ``o`` is one of the objects of ``group`` (identity: == compares arrays)."""
    return any(o is x for x in group)


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
        if any(_among(o, seeds[1]) for o in seeds[0]):
            raise InputError(f"--pair {pair[0]!r} {pair[1]!r} names the same files twice")
        groups = [list(seeds[0]), list(seeds[1])]
    for o in obs:
        if any(_among(o, g) for g in groups):
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
            raise InputError(f"--method df needs the files of one station, got two: {names}")
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


def read_inputs(
    options: InputsConfig, *, progress: Progress = quiet, extra_codes: tuple[str, ...] = ()
) -> InputData:
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
    obs_paths, nav_paths, demo = _given_files(options, progress)
    method_options = InputsConfig(method="df") if demo is not None else options
    with tempfile.TemporaryDirectory(prefix="psdbound-zip-") as tmp:
        sources, with_orbits = _unpack(obs_paths, Path(tmp))
        orbit_paths, notes = _orbit_sources(nav_paths, with_orbits)
        progress(
            f"reading {len(obs_paths)} observation file(s) and "
            f"{', '.join(p.name for p in orbit_paths)}"
        )
        codes = None if extra_codes else _codes_needed(method_options)
        groups = _group_stations(_read_observations(sources, options.system, codes), options.pair)
    _check_stations(groups, method_options)
    method = _method(method_options, len(groups))
    if method == "df":
        _refuse_pair_options(options, groups)
    obs = tuple(merge_observations(g) for g in groups)
    merged = [
        f"{station_key(g[0])}: {len(g)} observation files merged in time order into one "
        f"data set ({len(obs[k].t_gps_s)} epochs)"
        for k, g in enumerate(groups)
        if len(g) > 1
    ]
    if merged:
        progress("; ".join(merged))
    orbit, coverage_notes = _orbit_for(orbit_paths, obs, options.system)
    rx = _positions(options, len(obs))
    lat, lon = _lat_lon(obs[0], rx[0])
    files = tuple(
        {"role": role, "name": p.name, "path": str(p), "sha256": file_sha256(p)}
        for role, p in [*(("obs", q) for q in obs_paths), *(("nav", q) for q in orbit_paths)]
    )
    year = int(str(obs[0].times[0])[:4])
    notes += [str(w) for o in (*obs, orbit) for w in getattr(o, "warnings", ()) or ()]
    notes += merged + coverage_notes + _unanalysed(obs, options.system)
    return InputData(method, obs, orbit, files, rx, lat, lon, year, demo, tuple(notes))


def _unanalysed(obs: Sequence[Observations], system: str) -> list[str]:
    """Say which systems the files hold besides the one analysed (never left out silently)."""
    notes = []
    for o in obs:
        others = [s for s in o.systems_in_file if s != system]
        if others:
            names = ", ".join(f"{SYSTEM_NAMES.get(s, s)} ({s})" for s in others)
            notes.append(
                f"{Path(o.path.split(' + ')[0]).name}: the file also holds {names} "
                f"observations, not analysed: a fit analyses one system, here "
                f"{SYSTEM_NAMES.get(system, system)} ({system}); give another with --system "
                "(system= in psdbound.fit)"
            )
    return notes


def _given_files(
    options: InputsConfig, progress: Progress
) -> tuple[list[Path], list[Path], dict | None]:
    """Return the observation and orbit files of a run (the demo's when none are given).

    Returns the observation files (with ``pair`` members given as files), the
    orbit files and the demo's truth metadata (None for real files).
    """
    obs_paths = [Path(p) for p in options.obs]
    for item in options.pair:  # pair members given as files are inputs too
        if Path(item).is_file() and Path(item).resolve() not in [q.resolve() for q in obs_paths]:
            obs_paths.append(Path(item))
    if not obs_paths:
        from psdbound.simulate import demo_data

        progress("demo data (simulated on first use)")
        data = demo_data()
        return [data.obs_paths[0]], [data.nav_path], data.truth_meta()
    for p in obs_paths:
        if p.is_dir():
            raise InputError("is a folder, not an observation file", path=p)
        if not p.is_file():
            raise InputError("observation file not found", path=p)
    _refuse_repeats(obs_paths)
    return obs_paths, [Path(p) for p in options.nav], None


def _refuse_pair_options(options: InputsConfig, groups: list[list[Observations]]) -> None:
    """Dual-antenna options with the files of one station are errors."""
    default = InputsConfig()
    for key in ("baseline", "baseline_tolerance_m"):
        if getattr(options, key) != getattr(default, key):
            raise InputError(
                f"{key} = {getattr(options, key)!r} is a dual-antenna option, but the files "
                f"are one station ({_label(groups[0])}): name a pair or remove it"
            )


def _orbit_for(
    paths: Sequence[Path], obs: Sequence[Observations], system: str
) -> tuple[object, list[str]]:
    """Read the orbit files; refuse orbits that do not cover the observations (one clear error).

    Returns the orbit and the coverage warnings.
    """
    orbit = read_orbit(paths)
    name = Path(str(orbit.path)).name
    notes: list[str] = []
    for o in obs:  # orbits of another day or without the system: one clear error (exit 2)
        cov = orbit_coverage(orbit, o, system)
        cov.require(system)
        notes += [f"{name}: {w}" for w in cov.warnings(system)]
    return orbit, notes


def _lat_lon(
    obs: Observations, given: tuple[float, float, float] | None
) -> tuple[float | None, float | None]:
    """Geodetic latitude and longitude of the (first) antenna, deg (None without a position)."""
    pos = obs.header.approx_position_m if given is None else np.asarray(given)
    if pos is None:
        return None, None
    la, lo, _ = ecef_to_geodetic(np.asarray(pos))
    return float(la), float(lo)
