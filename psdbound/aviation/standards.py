"""Constants of the GBAS standards and the seeds, each with where it comes from.

Every number the error budget and the protection levels take from a standard
is a :class:`Sourced` value: the value and a sentence naming the document and
section it was read from, or saying plainly that it was entered from a seed
(or from memory) and not checked against the standard. ``psdbound budget``
prints these sources and writes them into its JSON output.

Sections of ICAO Annex 10 Vol. I were located in a public copy of the 2006
edition (Amendment 81, "23/11/06" pages); the section numbering of later
editions may differ. RTCA documents were not available: where the seeds cite
them, the citation is the seed's.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = [
    "AAD_A_MULTIPATH",
    "AAD_A_NOISE",
    "GAD_PARAMETERS",
    "GAD_SOURCE",
    "K_FFMD",
    "K_MD",
    "K_MD_E_SOURCE",
    "K_TABLE_SOURCE",
    "L5_TO_L1_SIGMA",
    "P_EPH",
    "Sourced",
    "sources",
]


@dataclass(frozen=True)
class Sourced:
    """A constant and the source it was taken from.

    Attributes
    ----------
    value : Any
        The number (or tuple of numbers); units in the name of the constant.
    source : str
        Document and section, or how the value was entered when no source
        could be checked.
    """

    value: Any
    source: str

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready ``{"value": ..., "source": ...}``."""
        v = list(self.value) if isinstance(self.value, tuple) else self.value
        return {"value": v, "source": self.source}


#: GAD curve parameters per designator: (a0 m, a1 m, theta0 deg, a2 m); GAD-C flat 0.24 m
#: below 35 deg.
GAD_PARAMETERS: dict[str, tuple[float, float, float, float]] = {
    "A": (0.50, 1.65, 14.3, 0.08),
    "B": (0.16, 1.07, 15.5, 0.08),
    "C": (0.15, 0.84, 15.5, 0.04),
}
GAD_SOURCE = (
    "ICAO Annex 10 Vol. I App. B Table B-74 (GBAS GPS accuracy requirement parameters, "
    "sec. 3.6.7.1.1.1), checked against a public copy of the 2006 edition; seed 004 cites "
    "RTCA DO-245A for the same curves"
)

#: Fault-free multiplier K_ffmd by number of reference receivers M (H0).
K_FFMD: dict[int, float] = {2: 5.762, 3: 5.810, 4: 5.847}
#: Missed-detection multiplier K_md of the single-reference-receiver fault (H1); NOT the
#: ephemeris multiplier K_md_e.
K_MD: dict[int, float] = {2: 2.935, 3: 2.898, 4: 2.878}
K_TABLE_SOURCE = (
    "entered from memory when the budget was written (issue 21); not verified against the "
    "standard: the K_ffmd / K_md table belongs to the protection levels of ICAO Annex 10 "
    "Vol. I App. B sec. 3.6.5.5 (section located, table not seen) and RTCA DO-253; "
    "seed 004 prints no value, and a search of public copies of Annex 10, DO-245/DO-253 "
    "extracts and papers for issue 33 found no table to quote. Check it against the "
    "edition you certify to, or pass k_ffmd"
)
K_MD_E_SOURCE = (
    "user-supplied: K_md_e is broadcast by the ground station in the Type 2 message "
    "(ICAO Annex 10 Vol. I App. B sec. 3.6.4.3, parameter 'ephemeris missed detection "
    "parameter, Category I precision approach and APV'), derived from the probability of "
    "missed detection given an ephemeris error; the standard fixes no value and seed 004 "
    "prints none"
)

AAD_A_MULTIPATH = Sourced(
    (0.13, 0.53, 10.0),
    "airborne multipath a0 m, a1 m, theta0 deg: seed 000 eq. (2) and seed 001 eq. (1) "
    "(which credit RTCA DO-208 and McGraw et al. 2000); ICAO Annex 10 Vol. I Att. D "
    "sec. 7.5.8 places the airframe multipath model in App. B sec. 3.6.5.5.1. Entered from "
    "the seeds; not verified against the standard",
)
AAD_A_NOISE = Sourced(
    (0.15, 0.43, 6.9),
    "airborne receiver noise (AAD-A) a0 m, a1 m, theta0 deg: seed 001 eq. (1) (credited "
    "to RTCA DO-208 and McGraw et al. 2000). Entered from seed 001; not verified against "
    "the standard",
)
L5_TO_L1_SIGMA = Sourced(
    0.7,
    "L5 / L1 code error sigma ratio: seed 004 Table 2 (the seed's own, more "
    "conservative than its reference Circiu et al. 2015)",
)
P_EPH = Sourced(
    0.00018,
    "ephemeris decorrelation parameter P_k, m/m: seed 004 sec. 3.2 (its ref. [4], "
    "Park, Pullen & Enge 2010); broadcast per satellite by a real ground station",
)


def sources() -> dict[str, str]:
    """Return the source of every constant of this module, by name (for a result file)."""
    return {
        "GAD_PARAMETERS": GAD_SOURCE,
        "K_FFMD": K_TABLE_SOURCE,
        "K_MD": K_TABLE_SOURCE,
        "K_MD_E": K_MD_E_SOURCE,
        "AAD_A_MULTIPATH": AAD_A_MULTIPATH.source,
        "AAD_A_NOISE": AAD_A_NOISE.source,
        "L5_TO_L1_SIGMA": L5_TO_L1_SIGMA.source,
        "P_EPH": P_EPH.source,
    }
