"""One runner for the stage chain: :func:`run_stages` -> :class:`StageProducts`.

:func:`psdbound.fit`, the campaign's per-day task (through ``fit``), the
benchmarks and the tests all run the stages of :mod:`psdbound.pipeline.stages`
through this function, so the chain is wired once. ``until`` stops after a
named stage (a test of the screening needs no bound).

The order::

    inputs -> code -> cutoff -> isolated -> screened -> windowed -> bounded -> validated

``code`` (the optional code-multipath overbound) needs only the inputs;
``validated`` (the cutoff validation) needs the inputs and the isolated series.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields, replace
from typing import Any

from psdbound.errors import InputError
from psdbound.pipeline import stages
from psdbound.pipeline.code_stage import code_overbound
from psdbound.pipeline.config import FitConfig
from psdbound.pipeline.inputs import Progress
from psdbound.stationarity.options import MappingOptions

__all__ = ["STAGES", "StageProducts", "run_stages"]


@dataclass(frozen=True)
class StageProducts:
    """What the stages produced, by stage name (None: not run, or not applicable).

    Attributes
    ----------
    config : FitConfig
        The effective configuration (the method resolved from the inputs; for
        the demo, the simulator's elevation mapping).
    inputs, code, cutoff, isolated, screened, windowed, bounded, validated
        The products of :mod:`psdbound.pipeline.stages` (``code`` and
        ``cutoff`` are None when not asked for or not applicable).
    """

    config: FitConfig
    inputs: Any = None
    code: Any = None
    cutoff: Any = None
    isolated: Any = None
    screened: Any = None
    windowed: Any = None
    bounded: Any = None
    validated: Any = None

    def products(self) -> dict[str, Any]:
        """Return the stage products as a dict (everything but ``config``)."""
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name != "config"}


def _inputs(run: StageProducts, say: Progress) -> StageProducts:
    cfg = run.config
    inputs = stages.read_inputs(cfg.inputs, progress=say, extra_codes=cfg.code_multipath.codes)
    cfg = cfg.updated("inputs", method=inputs.method)  # the effective method (auto resolved)
    if inputs.demo is not None and cfg.mapping == MappingOptions():
        # the demo's data follow the simulator's mapping: fit with it (known truth)
        mp = inputs.demo["scenario"]["multipath"]
        cfg = cfg.updated("mapping", kind="fixed", a=mp["a"], b=mp["b"], c_deg=mp["c_deg"])
    return replace(run, config=cfg, inputs=inputs)


def _code(run: StageProducts, say: Progress) -> StageProducts:
    cfg = run.config
    code = code_overbound(
        run.inputs,
        options=cfg.code_multipath,
        arcs=cfg.arcs,
        system=cfg.inputs.system,
        progress=say,
    )
    return replace(run, code=code)


def _cutoff(run: StageProducts, say: Progress) -> StageProducts:
    inp = run.config.inputs
    choice = stages.choose_cutoff(
        run.inputs, run.config.cutoff, system=inp.system, signals=tuple(inp.signals)
    )
    return replace(run, cutoff=choice)


def _isolated(run: StageProducts, say: Progress) -> StageProducts:
    cfg = run.config
    isolated = stages.isolate(
        run.inputs, run.cutoff, arcs=cfg.arcs, highpass=cfg.filter, options=cfg.inputs, progress=say
    )
    return replace(run, isolated=isolated)


def _screened(run: StageProducts, say: Progress) -> StageProducts:
    cfg = run.config
    provisional = stages.map_elevation(run.isolated.series, cfg.mapping)
    screened = stages.screen(
        run.isolated,
        options=cfg.screening,
        mapping=provisional,
        min_length_s=cfg.stationarity.min_window_s,
        progress=say,
    )
    return replace(run, screened=screened)


def _windowed(run: StageProducts, say: Progress) -> StageProducts:
    cfg = run.config
    mapping = stages.map_elevation(run.screened.series, cfg.mapping)
    windowed = stages.window(run.screened, mapping=mapping, options=cfg.stationarity, progress=say)
    return replace(run, windowed=windowed)


def _bounded(run: StageProducts, say: Progress) -> StageProducts:
    cfg = run.config
    bounded = stages.bound(
        run.windowed,
        spectra=cfg.spectra,
        options=cfg.bound,
        cutoff=run.cutoff,
        highpass=cfg.filter,
        progress=say,
    )
    return replace(run, bounded=bounded)


def _validated(run: StageProducts, say: Progress) -> StageProducts:
    cfg = run.config
    validated = stages.validate(
        run.cutoff,
        inputs=run.inputs,
        isolated=run.isolated,
        arcs=cfg.arcs,
        options=cfg.validation,
        highpass=cfg.filter,
        progress=say,
    )
    return replace(run, validated=validated)


#: The stages in the order they run, each with the step that runs it.
_STEPS: tuple[tuple[str, Callable[[StageProducts, Progress], StageProducts]], ...] = (
    ("inputs", _inputs),
    ("code", _code),
    ("cutoff", _cutoff),
    ("isolated", _isolated),
    ("screened", _screened),
    ("windowed", _windowed),
    ("bounded", _bounded),
    ("validated", _validated),
)

#: Stage names in running order (the ``until`` values of :func:`run_stages`).
STAGES: tuple[str, ...] = tuple(name for name, _ in _STEPS)


def run_stages(
    config: FitConfig, *, until: str | None = None, progress: Progress | None = None
) -> StageProducts:
    """Run the fit's stages in order and return their products.

    Parameters
    ----------
    config : FitConfig
        Every option (checked with :meth:`FitConfig.check` by the caller).
    until : str, optional
        Stop after this stage (one of :data:`STAGES`); None runs them all.
    progress : callable, optional
        Called with a short message at the start of each stage.

    Returns
    -------
    StageProducts
        The products of the stages that ran (the rest None) and the
        effective configuration.

    Raises
    ------
    InputError
        An unknown ``until``; bad input in any stage.
    NoDataError
        A stage found nothing to work on.

    Examples
    --------
    >>> from psdbound.pipeline import FitConfig
    >>> from psdbound.pipeline.runner import run_stages
    >>> run = run_stages(FitConfig(), until="screened")   # the demo, up to the screening
    >>> run.windowed is None and run.screened.series.n_arcs > 0
    True
    """
    if until is not None and until not in STAGES:
        raise InputError(f"unknown stage {until!r} for until=; choose from {', '.join(STAGES)}")
    say = progress or (lambda msg: None)
    run = StageProducts(config)
    for name, step in _STEPS:
        run = step(run, say)
        if name == until:
            break
    return run
