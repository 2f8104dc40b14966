"""The library's front door: ``psdbound.fit`` -> :class:`FitResults`, ``psdbound.load``.

statsmodels-style: :func:`fit` runs the stage chain of
:mod:`psdbound.pipeline.stages` (through
:func:`~psdbound.pipeline.runner.run_stages`) and returns a results object
with the stage products, the result document, :meth:`FitResults.summary`,
:meth:`FitResults.to_json` and :meth:`FitResults.report`. :func:`load`
reads a ``result.json`` back into a :class:`FitResults` (document only).

Examples
--------
>>> import psdbound
>>> res = psdbound.fit()                     # doctest: +SKIP
>>> print(res.summary())                     # doctest: +SKIP
>>> res.report("reports/demo")               # doctest: +SKIP
"""

from __future__ import annotations

import os
import time
from collections.abc import Sequence
from dataclasses import fields
from pathlib import Path
from typing import Any

from psdbound.common.outputs import check_output_file
from psdbound.errors import InputError
from psdbound.pipeline.config import FitConfig
from psdbound.pipeline.document import build_document
from psdbound.pipeline.inputs import Progress
from psdbound.pipeline.runner import run_stages
from psdbound.results import read_document, write_document
from psdbound.results.headline import headline

__all__ = ["FitResults", "fit", "load"]


class FitResults:
    """The result of a fit: stage products, the result document and its views.

    Attributes
    ----------
    document : dict
        The ``result.json`` content (schema 1).
    config : FitConfig or None
        The configuration that produced it (None when loaded from a file).
    inputs, cutoff, isolated, screened, windowed, bounded, validated : stage results or None
        The products of :mod:`psdbound.pipeline.stages` (None when loaded).
    code : CodeOverbound or None
        The optional code-multipath stage (None when not asked for, or loaded).
    """

    def __init__(
        self, document: dict[str, Any], *, config: FitConfig | None = None, **stage_results: Any
    ) -> None:
        self.document = document
        self.config = config
        self._source = str(stage_results.pop("source", ""))
        self.inputs = stage_results.get("inputs")
        self.cutoff = stage_results.get("cutoff")
        self.isolated = stage_results.get("isolated")
        self.screened = stage_results.get("screened")
        self.windowed = stage_results.get("windowed")
        self.bounded = stage_results.get("bounded")
        self.validated = stage_results.get("validated")
        self.code = stage_results.get("code")

    # ------------------------------------------------------------- views
    @property
    def bound(self) -> Any:
        """The fitted Gauss-Markov + white-noise model (sigma_gm_m, tau_s, sigma_wn_m, dt_s).

        Returns
        -------
        psdbound.spectra.GaussMarkovWhiteNoise
        """
        from psdbound.spectra.models import GaussMarkovWhiteNoise

        b = self.document["bound"]
        return GaussMarkovWhiteNoise(b["sigma_gm_m"], b["tau_s"], b["sigma_wn_m"], b["dt_s"])

    @property
    def error_model(self) -> Any:
        """The complete error model for a Kalman filter (every component, state-space export).

        Returns
        -------
        psdbound.kalman.ErrorModel
            Read from the document's ``error_model`` section, so a loaded
            ``result.json`` gives the same model.
        """
        from psdbound.kalman.error_model import ErrorModel

        return ErrorModel.from_document(self.document, source=self._source)

    def kalman_bound(self, *, allow_not_bounded: bool = False) -> Any:
        """Return the bound as a Kalman-filter model, in memory (no ``result.json`` round trip).

        Parameters
        ----------
        allow_not_bounded : bool, default False
            Also for a ``"not-bounded"`` result (refused otherwise, with its reasons).

        Returns
        -------
        psdbound.kalman.GaussMarkovBound
            The same object :meth:`GaussMarkovBound.from_result` reads from the
            written file (``to_state_space``, ``measurement_covariance``, ...).

        Raises
        ------
        InputError
            A not-bounded result (without ``allow_not_bounded``).
        """
        from psdbound.kalman.bound import GaussMarkovBound

        return GaussMarkovBound.from_document(
            self.document, allow_not_bounded=allow_not_bounded, source=self._source or "fit"
        )

    @property
    def verdict(self) -> str:
        """``"bounded"`` or ``"not-bounded"`` (see :mod:`psdbound.pipeline.verdict`)."""
        return self.document["verdict"]

    @property
    def verdict_reasons(self) -> list[str]:
        """Why the verdict is "not-bounded" (empty when bounded)."""
        return list(self.document["verdict_reasons"])

    @property
    def series(self) -> Any:
        """The screened multipath series the bound was fitted on (None when loaded)."""
        return None if self.screened is None else self.screened.series

    @property
    def windows(self) -> Any:
        """The stationary windows (None when loaded from a file)."""
        return None if self.windowed is None else self.windowed.windows

    @property
    def validation(self) -> dict[str, Any]:
        """The cutoff validation section (verdict, fractions)."""
        return self.document["validation"]

    @property
    def warnings(self) -> list[str]:
        """Every warning of the run, in pipeline order."""
        return list(self.document["warnings"])

    @property
    def provenance(self) -> dict[str, Any]:
        """Input files with SHA-256, versions, configuration, time, platform."""
        return self.document["provenance"]

    # ------------------------------------------------------------- the series as data
    def series_table(self) -> dict[str, Any]:
        """Return every isolated sample with its direction, screening and window.

        Returns
        -------
        dict of str to ndarray
            Columns ``t_gps_s``, ``sat``, ``azimuth_deg``, ``elevation_deg``,
            ``value_m``, ``screened`` (why a sample was screened out, empty
            when kept) and ``window`` (its stationary window, -1: outside the
            bound); see :mod:`psdbound.results.series_table`.

        Raises
        ------
        InputError
            A result read from ``result.json`` (the file holds no per-epoch
            series: fit again).
        """
        from psdbound.results.series_table import series_table

        if self.isolated is None:
            raise InputError(
                "this result was read from a file, which holds no per-epoch "
                "series: fit again (psdbound.fit(...), or fit --series)"
            )
        d = self.document
        return series_table(
            self.isolated.series,
            self.isolated.arcs,
            d["screening"]["excluded"],
            d["windows"]["per_window"],
        )

    def series_csv(self, *, gz: bool = True) -> bytes:
        """Return :meth:`series_table` as CSV bytes (gzip-compressed by default)."""
        from psdbound.results.series_table import series_csv

        return series_csv(self.series_table(), gz=gz)

    def series_dataset(self) -> Any:
        """Return :meth:`series_table` as an :class:`xarray.Dataset` with units and provenance.

        Returns
        -------
        xarray.Dataset
            Variables along ``sample`` with ``units``, ``long_name`` and
            ``description``; global attributes name the input files (with
            SHA-256), the psdbound version, the verdict and the bound
            (:func:`psdbound.results.series_export.series_attrs`).
        """
        from psdbound.results.series_export import series_attrs, series_dataset

        return series_dataset(self.series_table(), attrs=series_attrs(self.document))

    def write_series(self, path: str | os.PathLike[str], *, format: str | None = None) -> Path:
        """Write :meth:`series_table` to a file atomically: CSV or netCDF.

        Parameters
        ----------
        path : str or path-like
            Destination; CSV is gzip-compressed when the name ends in ``.gz``.
        format : {"csv", "netcdf"}, optional
            Default: from the name (``.nc`` netCDF, ``.csv``/``.csv.gz`` CSV).

        Returns
        -------
        Path

        Raises
        ------
        InputError
            A format the name contradicts, or a file that cannot be written
            there (a folder, a folder that cannot be created or written).
        """
        from psdbound.results.series_export import series_attrs, write_series

        check_output_file(path, overwrite=True, option="series file")
        return write_series(
            self.series_table(), path, fmt=format, attrs=series_attrs(self.document)
        )

    # ------------------------------------------------------------- figures
    def plot(self, name: str) -> Any:
        """Return one report figure as a matplotlib Figure (None when the result has no data).

        Parameters
        ----------
        name : str
            A key of :data:`psdbound.reports.figures.FIGURES`: ``"windows"``,
            ``"df_filter"``, ``"screening"``, ``"sky"``, ``"mapped"``,
            ``"psds"``, ``"tau"``, ``"cutoff"``, ``"jacobi_anger"``,
            ``"code_qq"``.

        Returns
        -------
        matplotlib.figure.Figure or None
            Not registered with pyplot (a notebook shows it when it is the
            cell's value; ``fig.savefig(path)`` writes it).

        Raises
        ------
        InputError
            An unknown name (the known ones are listed).
        """
        from psdbound.reports.figures import FIGURES

        funcs = {key: func for key, _, func in FIGURES}
        if name not in funcs:
            raise InputError(f"unknown figure {name!r}; choose from {', '.join(funcs)}")
        return funcs[name](self.document)

    def plot_psd(self) -> Any:
        """Return the figure of the window PSDs, their pooled limits and the bound."""
        return self.plot("psds")

    def plot_windows(self) -> Any:
        """Return the figure of the arcs, screened spans and stationary windows per satellite."""
        return self.plot("windows")

    def plot_sky(self) -> Any:
        """Return the sky view: multipath RMS by azimuth and elevation (None without azimuths)."""
        return self.plot("sky")

    def plot_screening(self) -> Any:
        """Return the screening figure: ROTI against its threshold, largest values."""
        return self.plot("screening")

    def summary(self) -> str:
        """Return the console summary (bound, cutoff, sampling, windows, warnings)."""
        d = self.document
        b, c, s, w = d["bound"], d["cutoff"], d["sampling"], d["windows"]
        fc = "n/a" if c["f_c_hz"] is None else f"{c['f_c_hz']:.4g} Hz ({c['source']})"
        lines = list(d.get("headline") or headline(d))
        hours = w.get("covered_s", w["total_duration_s"]) / 3600
        lines += [
            f"psdbound fit ({d['method']}): sigma_GM = {100 * b['sigma_gm_m']:.3f} cm, "
            f"tau = {b['tau_s']:.1f} s, sigma_WN = {100 * b['sigma_wn_m']:.3f} cm "
            f"(per sample at {s['interval_s']:g} s); rule {b.get('rule', 'envelope')}",
            f"  cutoff {fc}; Nyquist {s['nyquist_hz']:.4g} Hz; {w['count']} stationary windows "
            f"({hours:.2f} h); thesis cutoff criterion (reported, not a "
            f"verdict rule): {d['validation'].get('verdict', 'n/a')}",
        ]
        cm = d.get("code_multipath")
        if cm:
            bins = (cm.get("overbound") or {}).get("bins", [])
            per_bin = ", ".join(
                f"{x['elevation_deg'][0]:g}-{x['elevation_deg'][1]:g} deg "
                f"{100 * x['sigma']:.1f} cm (x{x['inflation']:.2f})"
                for x in bins
            )
            lines.append(
                f"  code multipath {'+'.join(cm['codes'])}: "
                + (f"overbound sigma (inflation) {per_bin}" if bins else cm["status"])
            )
        demo = d.get("demo")
        if demo and demo.get("variance_ratio") is not None:
            lines.append(
                f"  demo truth: bound variance / injected variance = "
                f"{demo['variance_ratio']:.2f}; bound PSD / truth PSD >= "
                f"{demo['min_psd_ratio']:.2f} over the bound's band, >= "
                f"{demo.get('min_psd_ratio_all_f', float('nan')):.2f} from 0 Hz to Nyquist"
            )
        if d["warnings"]:
            lines.append(f"  {len(d['warnings'])} warning(s), by stage:")
            groups = d.get("warnings_by_stage") or [{"stage": "run", "warnings": d["warnings"]}]
            for g in groups:
                lines.append(f"  {g['stage']}:")
                lines += [f"    - {x}" for x in g["warnings"]]
        return "\n".join(lines)

    def __repr__(self) -> str:
        b = self.document["bound"]
        return (
            f"<FitResults {self.document['method']}: sigma_gm_m={b['sigma_gm_m']:.4g}, "
            f"tau_s={b['tau_s']:.4g}, sigma_wn_m={b['sigma_wn_m']:.4g}>"
        )

    # ------------------------------------------------------------- output
    def to_json(self, path: str | os.PathLike[str]) -> Path:
        """Write ``result.json`` atomically (replacing a file there); return its path.

        Raises
        ------
        InputError
            ``path`` is a folder, or its folder cannot be created or written.
        """
        check_output_file(path, overwrite=True, option="result file")
        return write_document(path, self.document)

    def report(
        self, out_dir: str | os.PathLike[str], *, pdf: bool = True, overwrite: bool = False
    ) -> dict[str, Path]:
        """Write ``result.json``, ``report.html`` and (optionally) ``report.pdf`` into a folder.

        The folder is built under a temporary name and renamed when complete.

        Parameters
        ----------
        out_dir : str or path-like
            Destination folder.
        pdf : bool, default True
            Also write the PDF report.
        overwrite : bool, default False
            Write into an existing folder that is not a psdbound output
            (psdbound's files are added; nothing else in it is touched).

        Returns
        -------
        dict of str to Path
            ``{"result": ..., "html": ..., "pdf": ...}``.

        Raises
        ------
        InputError
            The folder is refused (a file, not writable, or a folder with
            other content without ``overwrite``).
        """
        from psdbound.reports import write_report_folder

        return write_report_folder(
            self.document, out_dir, pdf=pdf, overwrite=overwrite, option="out_dir"
        )


def _names(
    paths: Sequence[str | os.PathLike[str]] | str | os.PathLike[str] | None, argument: str
) -> tuple[str, ...]:
    """File names of a path, a sequence of paths or None."""
    if paths is None:
        return ()
    if isinstance(paths, str | os.PathLike):
        paths = [paths]
    try:
        return tuple(os.fspath(p) for p in paths)  # type: ignore[union-attr]
    except TypeError:
        raise InputError(
            f"{argument} must be a file name or a list of file names, got {paths!r}"
        ) from None


def _config_from(
    obs: Sequence[str | os.PathLike[str]] | str | os.PathLike[str],
    nav: Sequence[str | os.PathLike[str]] | str | os.PathLike[str] | None,
    config: FitConfig | None,
    options: dict[str, Any],
) -> FitConfig:
    if config is not None and not isinstance(config, FitConfig):
        raise InputError(
            f"config must be a psdbound.FitConfig (FitConfig.from_dict(...) builds one from a "
            f"dict), got {type(config).__name__}; or give the options as keywords"
        )
    cfg = config if config is not None else FitConfig()
    files = {"obs": _names(obs, "obs"), "nav": _names(nav, "nav")}
    cfg = cfg.updated("inputs", **{k: v for k, v in files.items() if v})
    sections = {f.name for f in fields(FitConfig)}
    owners: dict[str, list[str]] = {}
    for sec in sections:
        for f in fields(getattr(cfg, sec)):
            owners.setdefault(f.name, []).append(sec)
    for key, value in options.items():
        if key in sections:
            if not isinstance(value, dict):
                raise InputError(f"option {key}= must be a dict of {key} options")
            cfg = cfg.updated(key, **value)
        elif len(owners.get(key, [])) == 1:
            cfg = cfg.updated(owners[key][0], **{key: value})
        elif key in owners:
            alts = " or ".join(f"{s}={{{key!r}: ...}}" for s in sorted(owners[key]))
            raise InputError(f"option {key!r} is ambiguous: give it as {alts}")
        else:
            raise InputError(f"unknown option {key!r}; see psdbound.FitConfig for every option")
    return cfg


def fit(
    obs: Sequence[str | os.PathLike[str]] | str | os.PathLike[str] = (),
    nav: Sequence[str | os.PathLike[str]] | str | os.PathLike[str] | None = None,
    *,
    config: FitConfig | None = None,
    progress: Progress | None = None,
    **options: Any,
) -> FitResults:
    """Fit a Gauss-Markov + white-noise PSD bound to carrier-phase multipath.

    Parameters
    ----------
    obs : path or sequence of paths, optional
        One observation file (dual-frequency) or two (dual-antenna). None or
        empty: the embedded demo (simulated, known truth).
    nav : path or sequence of paths, optional
        Navigation (RINEX 2/3/4) or SP3 file; several (e.g. of consecutive
        days) are joined into one orbit. Not needed when ``obs`` is a zip
        archive that also holds the navigation file.
    config : FitConfig, optional
        Every option; ``obs``, ``nav`` and ``options`` override it.
    progress : callable, optional
        Called with a short message at the start of each stage.
    **options
        Either a section of :class:`FitConfig` as a dict
        (``cutoff={"f_c_hz": 1e-3}``) or an option whose name belongs to
        one section only (``estimator="welch"``, ``f_c_hz=1e-3``).

    Returns
    -------
    FitResults

    Raises
    ------
    InputError
        Bad input (files, options); :class:`~psdbound.errors.NoDataError`
        when the data hold no usable arc or window.

    See Also
    --------
    load : Read a ``result.json`` back as the same results object.
    psdbound.pipeline.FitConfig : Every option, with its default, unit and checks.
    psdbound.pipeline.runner.run_stages : The same stages, up to any one of them.

    References
    ----------
    .. [1] Benz, C. (2022). *Carrier Phase Multipath Characterization and
       Frequency-Domain Bounding*. M.S. thesis, Illinois Institute of Technology
       (the method psdbound started from; docs/method/index.rst says where it differs).
    .. [2] docs/method/bound.rst (the pooled bound and its confidence) and
       docs/user_guide/reading_results.rst (what every number means).

    Examples
    --------
    >>> import psdbound
    >>> res = psdbound.fit()                  # the embedded demo: simulated, known truth
    >>> res.verdict
    'bounded'
    >>> res.bound.sigma_gm_m > 0.003           # above the injected sigma_GM, 3 mm
    True
    >>> res.document["demo"]["min_psd_ratio_all_f"] >= 1.0   # above its PSD, 0 Hz to Nyquist
    True
    >>> res.document["windows"]["covered_fraction"] > 0.95
    True
    """
    cfg = _config_from(obs, nav, config, options)
    cfg.check()  # conflicting options and ignored files are errors before anything is read
    if progress is not None and not callable(progress):
        raise InputError(
            f"progress must be a callable taking one message (e.g. print), got {progress!r}"
        )
    t0 = time.perf_counter()
    run = run_stages(cfg, progress=progress)
    products = run.products()
    document = build_document(config=run.config, run_time_s=time.perf_counter() - t0, **products)
    return FitResults(document, config=run.config, **products)


def load(path: str | os.PathLike[str]) -> FitResults:
    """Read a ``result.json`` written by psdbound.

    Parameters
    ----------
    path : str or path-like

    Returns
    -------
    FitResults
        With the document only (stage products are None).

    Raises
    ------
    InputError
        Missing file, invalid JSON, unsupported schema or a missing field.

    See Also
    --------
    fit : Produce the results (and ``result.json``) in the first place.
    psdbound.results.validate : Check a document against the shipped JSON Schema.

    References
    ----------
    .. [1] docs/reference/result_json.rst (every field, with units).

    Examples
    --------
    >>> import os, tempfile
    >>> import psdbound
    >>> res = psdbound.fit()
    >>> path = res.to_json(os.path.join(tempfile.mkdtemp(), "result.json"))
    >>> again = psdbound.load(path)
    >>> again.bound.tau_s == res.bound.tau_s and again.verdict == res.verdict
    True
    """
    if not isinstance(path, str | os.PathLike):
        raise InputError(f"give the path of a result.json, got {type(path).__name__}")
    return FitResults(read_document(path), source=str(path))
