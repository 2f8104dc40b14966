"""The optional code-multipath stage of a fit: carrier levelling and the Gaussian overbound.

::

    code_overbound(InputData) -> CodeOverbound | None      (None: not asked for)

It runs beside the carrier-phase chain, on the same observations, orbit and
arc options, and never changes the carrier-phase bound. An elevation bin
with too few samples is reported and skipped (a fit does not stop for it;
``psdbound overbound`` on a samples file does).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from psdbound.arcs.options import ArcOptions
from psdbound.aviation.code_samples import describe_code_series, overbound_code_series
from psdbound.aviation.options import CodeMultipathOptions
from psdbound.errors import InputError, NoDataError
from psdbound.isolation import isolate_code_multipath
from psdbound.pipeline.inputs import Progress, quiet
from psdbound.pipeline.products import CodeOverbound, InputData

__all__ = ["code_overbound"]

#: Q-Q points kept per elevation bin in the result document (the extremes always).
QQ_POINTS = 400


def code_overbound(
    inputs: InputData,
    *,
    options: CodeMultipathOptions,
    arcs: ArcOptions,
    system: str = "G",
    progress: Progress = quiet,
) -> CodeOverbound | None:
    """Code multipath of the first observation file and its overbound per elevation bin.

    Parameters
    ----------
    inputs : InputData
        What :func:`~psdbound.pipeline.stages.read_inputs` read (the codes
        must have been read: ``read_inputs(..., extra_codes=options.codes)``).
    options : CodeMultipathOptions
        Codes, elevation edges, overbound method, shortest arc, fewest samples per bin.
    arcs : ArcOptions
        Elevation mask and slip threshold of the fit (the arc length is ``options``').
    system : str, default "G"
        Satellite system letter.
    progress : callable, optional

    Returns
    -------
    CodeOverbound or None
        None when no code was asked for.

    Raises
    ------
    InputError
        A code or its carriers not in the file (the message lists what is).
    """
    if not options.enabled:
        return None
    codes = options.codes
    progress(f"code multipath ({'+'.join(codes)}, carrier levelling) and its overbound")
    obs = inputs.observations[0]
    rx = inputs.receiver_xyz_m[0]
    try:
        series = isolate_code_multipath(
            obs,
            codes,
            orbit=inputs.orbit,
            receiver_xyz_m=None if rx is None else np.asarray(rx, dtype=float),
            system=system,
            elevation_mask_deg=arcs.elevation_mask_deg,
            min_length_s=options.min_length_s,
            slip_threshold_m=arcs.slip_threshold_m,
        )
    except NoDataError as exc:
        note = f"code multipath not computed: {exc}"
        return CodeOverbound(None, None, {"codes": list(codes), "status": note}, (note,))
    mask = arcs.elevation_mask_deg
    edges = tuple(options.edges_deg)
    if mask > edges[0]:  # no sample below the mask: the first bin starts at it (honest labels)
        edges = (mask, *(e for e in edges if e > mask))
    details: dict[str, Any] = {
        **describe_code_series(series, min_length_s=options.min_length_s),
        "codes": list(codes),
        "status": "computed",
        "edges_deg": list(edges),
    }
    try:
        result, sparse = overbound_code_series(
            series, edges, method=options.method, min_samples=options.min_samples
        )
    except InputError as exc:  # no bin full enough: said, not fatal to the carrier-phase fit
        note = f"code multipath not overbounded: {exc.reason}"
        details["status"] = note
        return CodeOverbound(series, None, details, (note,))
    details["overbound"] = result.to_dict()
    details["qq"] = result.qq_points(QQ_POINTS)
    notes = [f"code multipath: {x}" for x in sparse]
    return CodeOverbound(series, result, details, tuple(notes))
