"""Page 1 of every output: the verdict, each rule with its two numbers, coverage and looseness.

One home for what a reader sees first. The console summary
(:meth:`psdbound.FitResults.summary`), the HTML and PDF reports
(:mod:`psdbound.reports.render`) and ``result.json`` (``headline``) all print
these lines from the result document, so they cannot tell different stories:

1. the verdict, and on a not-bounded result "do not use this bound";
2. every verdict rule (``verdict_checks``): what it measured, what it
   allows, pass or FAIL, and the reason of each that failed;
3. the data the bound covers (screened data inside a stationary window);
4. how loose the bound is: its band mean over the pooled data of the
   windows, median and worst band, dB (``bound.over_data_db``);
5. the statement: what the bound covers with which confidence, only when
   bounded (a not-bounded result states nothing).

The thesis's cutoff-validation criterion is not a verdict rule and is not
on page 1; the reports show it in the validation section, labelled as the
thesis's.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

__all__ = ["DO_NOT_USE", "check_line", "headline"]

#: What a not-bounded result says first, in every output.
DO_NOT_USE = "do not use this bound: no trustworthy bound can be given from these data"


def _verdict_line(d: dict[str, Any]) -> str:
    if d["verdict"] == "bounded":
        return "VERDICT: BOUNDED"
    return f"VERDICT: NOT-BOUNDED - {DO_NOT_USE}"


def check_line(check: Mapping[str, Any]) -> str:
    """Return ``rule: measured (limit) pass|FAIL``: one verdict rule as every output prints it.

    Parameters
    ----------
    check : mapping
        An entry of ``verdict_checks`` (``rule``, ``measured``, ``limit``, ``passed``).

    Returns
    -------
    str
    """
    verdict = "pass" if check["passed"] else "FAIL"
    return f"{check['rule']}: {check['measured']} ({check['limit']}) {verdict}"


def _rule_lines(d: dict[str, Any]) -> list[str]:
    checks = d.get("verdict_checks") or []
    n_pass = sum(bool(c["passed"]) for c in checks)
    lines = [f"rules: {n_pass} of {len(checks)} passed"]
    lines += [f"  {check_line(c)}" for c in checks]
    return lines + [f"reason: {x}" for x in d.get("verdict_reasons") or []]


def _coverage_line(d: dict[str, Any]) -> str | None:
    w = d.get("windows") or {}
    if w.get("covered_fraction") is None:
        return None
    return (
        f"data covered by the bound: {w['covered_s'] / 3600:.2f} h of "
        f"{w['data_s'] / 3600:.2f} h screened data ({100 * w['covered_fraction']:.1f} %)"
    )


def _looseness_line(d: dict[str, Any]) -> str | None:
    o = (d.get("bound") or {}).get("over_data_db")
    if not o or not o.get("n_bands"):
        return None
    return (
        f"bound above the pooled data: median {o['median_db']:.1f} dB, worst "
        f"{o['max_db']:.1f} dB (at {o['f_max_hz']:.3g} Hz) over {o['n_bands']} bands; above "
        f"the highest window: median {o.get('over_highest_median_db', float('nan')):.1f} dB"
    )


def _statement_line(d: dict[str, Any]) -> str:
    if d["verdict"] != "bounded":
        return "statement: none (not bounded; the numbers are what the fit produced)"
    covers = (d.get("bound") or {}).get("covers")
    return f"statement: {covers}" if covers else "statement: none"


def headline(document: dict[str, Any]) -> list[str]:
    """Return the page-1 lines of a result document (the same in every output).

    Parameters
    ----------
    document : dict
        The result document (``verdict``, ``verdict_checks``, ``windows``,
        ``bound``).

    Returns
    -------
    list of str
        The verdict, the rules (one line each, indented), the data covered,
        the looseness and the statement; lines without data are left out.
    """
    d = document
    lines = [
        _verdict_line(d),
        *_rule_lines(d),
        _coverage_line(d),
        _looseness_line(d),
        _statement_line(d),
    ]
    return [x for x in lines if x]
