"""From options to output files: a whole cutoff validation as one library call.

:func:`run_validation` is what ``psdbound validate`` does: read the optional
aircraft-mode table and orbit file, run
:func:`~psdbound.validation.validate.validate_cutoff` and, with an output
folder, write the table, document and figures
(:func:`~psdbound.validation.outputs.write_validation_outputs`). A failing
verdict is a result, not an error.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

from psdbound.errors import InputError
from psdbound.validation.cutoff import DEFAULT_THRESHOLD
from psdbound.validation.geometry import CONVENTIONS, GPS_L1_WAVELENGTH_M
from psdbound.validation.modes import mode_table
from psdbound.validation.outputs import write_validation_outputs
from psdbound.validation.results import ValidationReport
from psdbound.validation.validate import DEFAULT_THETA0_DEG, validate_cutoff

__all__ = ["run_validation"]


def run_validation(
    geometries: Sequence[str],
    *,
    cutoff_hz: float,
    rate: str = "orbit",
    alpha: float = 0.1,
    threshold: float = DEFAULT_THRESHOLD,
    convention: str = "both",
    wavelength_m: float | None = None,
    modes_file: str | os.PathLike[str] | None = None,
    theta0_deg: float = DEFAULT_THETA0_DEG,
    amplitude_deg: float | None = None,
    nav_file: str | os.PathLike[str] | None = None,
    receiver_ecef_m: Sequence[float] | None = None,
    sats: list[str] | None = None,
    system: str = "G",
    elevation_mask_deg: float = 5.0,
    min_pass_s: float = 3600.0,
    distance_tolerance_m: float = 0.0,
    out_dir: str | os.PathLike[str] | None = None,
    figures: bool = True,
) -> tuple[ValidationReport, list[Path]]:
    """Validate a cutoff and write the outputs.

    Parameters
    ----------
    geometries : sequence of str
        Reflections, e.g. ``["wall:d=25", "ground:h=1.5"]``.
    cutoff_hz : float
        High-pass cutoff ``f_c``, Hz.
    rate : str, default "orbit"
        Geometry rate: an orbit, an aircraft mode or a frequency in Hz
        (:func:`~psdbound.validation.modes.resolve_rate`).
    alpha : float, default 0.1
        Reflected/direct amplitude ratio.
    threshold : float, default 0.10
        Largest acceptable fraction of multipath power below ``f_c``.
    convention : {"both", "physical", "thesis"}, default "both"
        Phase convention(s).
    wavelength_m : float, optional
        Carrier wavelength, m (default GPS L1).
    modes_file : str or path-like, optional
        TOML file adding aircraft modes.
    theta0_deg : float, default 30
        Aircraft modes: mean angle of arrival relative to the reflector, deg.
    amplitude_deg : float, optional
        Aircraft modes: oscillation amplitude, deg (default: the mode's).
    nav_file : str or path-like, optional
        Navigation or SP3 file: also simulate real satellite passes over
        ``receiver_ecef_m``.
    receiver_ecef_m : sequence of 3 float, optional
        Receiver ECEF position, m (needed with ``nav_file``).
    sats : list of str, optional
        Satellites of the passes (default: all of ``system``).
    system : str, default "G"
        Satellite system of the passes.
    elevation_mask_deg : float, default 5
        Elevation mask of the passes, degrees.
    min_pass_s : float, default 3600
        Shortest pass simulated, s.
    distance_tolerance_m : float, default 0
        Also sweep each distance over +- this many metres and judge the worst.
    out_dir : str or path-like, optional
        Write the outputs here (created first, before the computation).
    figures : bool, default True
        With ``out_dir``: also write the PNG figures.

    Returns
    -------
    report : ValidationReport
        The verdicts.
    files : list of Path
        Output files written (empty without ``out_dir``).

    Raises
    ------
    InputError
        Bad geometry, cutoff, rate, mode file, navigation file or output folder.
    """
    if nav_file is not None and receiver_ecef_m is None:
        raise InputError("a navigation file needs the receiver ECEF position")
    modes = mode_table(modes_file) if modes_file else None
    orbit = None
    if nav_file:
        from psdbound.io import read_orbit

        orbit = read_orbit(nav_file)
    conventions = CONVENTIONS if convention == "both" else (convention,)
    out = Path(out_dir) if out_dir is not None else None
    if out is not None:
        try:
            out.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(f"cannot create output folder: {exc.strerror}", path=out) from None
    report = validate_cutoff(
        geometries,
        cutoff_hz=cutoff_hz,
        rate=rate,
        alpha=alpha,
        threshold=threshold,
        conventions=conventions,
        wavelength_m=GPS_L1_WAVELENGTH_M if wavelength_m is None else wavelength_m,
        modes=modes,
        theta0_deg=theta0_deg,
        amplitude_deg=amplitude_deg,
        orbit=orbit,
        receiver_xyz_m=receiver_ecef_m,
        sats=sats,
        system=system,
        elevation_mask_deg=elevation_mask_deg,
        min_pass_s=min_pass_s,
        distance_tolerance_m=distance_tolerance_m,
    )
    files = [] if out is None else write_validation_outputs(report, out, figures=figures)
    return report, files
