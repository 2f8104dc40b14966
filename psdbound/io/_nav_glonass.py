"""GLONASS navigation records (RINEX 2 file type G, RINEX 3 ``R`` records).

Layout (RINEX 2.11 table A11, RINEX 3.0x table A10): the epoch line holds the
satellite, the epoch ``tb`` in UTC and three fields, ``-tau_n`` (clock bias,
s), ``+gamma_n`` (relative frequency bias) and the message frame time; then
three orbit lines of four fields each::

    X (km)  X velocity (km/s)  X acceleration (km/s^2)  health Bn (0 = OK)
    Y (km)  Y velocity (km/s)  Y acceleration (km/s^2)  frequency number k
    Z (km)  Z velocity (km/s)  Z acceleration (km/s^2)  age of information (days)

RINEX 3.05 adds a fourth orbit line (status flags, group delay, URAI,
health flags), which is not used. :class:`GlonassParser` collects these
records next to the Keplerian ones and builds
:class:`~psdbound.io.glonass.GlonassEphemerides` (metres, GPS seconds).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from psdbound.io._nav_records import DESCRIPTION, Epoch, RecordParser, valid_calendar
from psdbound.io.glonass import GlonassEphemerides
from psdbound.io.timescales import calendar_to_gps_s, utc_to_gps_s

__all__ = ["GLONASS_FIELDS", "GLONASS_LINES", "GlonassParser"]

#: Lines of a GLONASS record that are read (RINEX 3.05 records have one more).
GLONASS_LINES = 4
#: (line, field) -> (attribute, description, required); line 0 is the epoch line.
GLONASS_FIELDS = {
    (0, 1): ("clock_bias_s", "clock bias -TauN", True),
    (0, 2): ("gamma_n", "relative frequency bias GammaN", True),
    (0, 3): ("message_time_s", "message frame time", False),
    (1, 0): ("x_km", "X position", True),
    (1, 1): ("vx_km_s", "X velocity", True),
    (1, 2): ("ax_km_s2", "X acceleration", True),
    (1, 3): ("health", "health Bn", True),
    (2, 0): ("y_km", "Y position", True),
    (2, 1): ("vy_km_s", "Y velocity", True),
    (2, 2): ("ay_km_s2", "Y acceleration", True),
    (2, 3): ("channel", "frequency number", True),
    (3, 0): ("z_km", "Z position", True),
    (3, 1): ("vz_km_s", "Z velocity", True),
    (3, 2): ("az_km_s2", "Z acceleration", True),
    (3, 3): ("age_days", "age of operation information", False),
}
_DESCRIPTION = {attr: what for attr, what, _ in GLONASS_FIELDS.values()}
# plausible geocentric distance of a GLONASS satellite (about 25 500 km), km
_RADIUS_KM = (20000.0, 30000.0)
_CHANNELS = (-7, 13)


class GlonassParser(RecordParser):
    """A navigation record parser that also reads GLONASS records."""

    def __init__(self, path: Path, lines: list[str]) -> None:
        super().__init__(path, lines)
        self.glo_cols: dict[str, list[float]] = {a: [] for a in _DESCRIPTION}
        self.glo_sats: list[str] = []
        self.glo_epochs: list[Epoch] = []

    def describe(self, attr: str) -> str:
        """Name of a record field for messages."""
        return _DESCRIPTION.get(attr) or DESCRIPTION.get(attr, attr)

    def add_glonass(self, sat: str, rec: list[int]) -> None:
        """Read one GLONASS record (line indices ``rec``, at least four lines)."""
        line0 = self.lines[rec[0]]
        try:
            ep = self.epoch(line0)
        except ValueError:
            raise self.error(
                f"cannot parse the epoch (tb, UTC) of {sat} in {self.EPOCH_COLUMNS}: "
                f"{line0[:23].rstrip()!r}; expected 'yyyy mm dd hh mm ss'",
                rec[0],
            ) from None
        values = {
            attr: self.number(rec, k, j, sat, attr, required)
            for (k, j), (attr, _, required) in sorted(GLONASS_FIELDS.items())
        }
        reason = self.glonass_damage(ep, values)
        if reason:
            self.damaged.append((rec[0], sat, reason))
            return
        for attr, v in values.items():
            self.glo_cols[attr].append(v)
        self.glo_sats.append(sat)
        self.glo_epochs.append(ep)

    def glonass_damage(self, ep: Epoch, values: dict[str, float]) -> str:
        """Why a GLONASS record cannot be used (empty when it can)."""
        if not valid_calendar(ep, self.TWO_DIGIT_YEAR):
            return f"impossible epoch {' '.join(f'{v:g}' for v in ep)}"
        bad = [self.describe(a) for a, v in values.items() if not math.isfinite(v)]
        if bad:
            return f"non-finite {bad[0]}"
        r = math.sqrt(values["x_km"] ** 2 + values["y_km"] ** 2 + values["z_km"] ** 2)
        if not _RADIUS_KM[0] <= r <= _RADIUS_KM[1]:
            return (
                f"position {r:.0f} km from the Earth's centre (expected "
                f"{_RADIUS_KM[0]:.0f}-{_RADIUS_KM[1]:.0f} km)"
            )
        k = values["channel"]
        if not (k == round(k) and _CHANNELS[0] <= k <= _CHANNELS[1]):
            return f"frequency number {k:g} (expected an integer from -7 to +13)"
        return ""

    def build_glonass(self) -> GlonassEphemerides | None:
        """The GLONASS records read, or None when there are none."""
        if not self.glo_sats:
            return None
        c = {a: np.asarray(v, dtype=np.float64) for a, v in self.glo_cols.items()}
        ep = np.asarray(self.glo_epochs, dtype=np.float64)
        labels = calendar_to_gps_s(*(ep[:, i].astype(np.int64) for i in range(5)), ep[:, 5])
        km = 1000.0

        def vec(*names: str) -> np.ndarray:
            return km * np.column_stack([c[n] for n in names])

        return GlonassEphemerides(
            sat=np.asarray(self.glo_sats, dtype="<U3"),
            tb_gps_s=utc_to_gps_s(labels),
            xyz_m=vec("x_km", "y_km", "z_km"),
            vel_m_s=vec("vx_km_s", "vy_km_s", "vz_km_s"),
            acc_m_s2=vec("ax_km_s2", "ay_km_s2", "az_km_s2"),
            clock_bias_s=c["clock_bias_s"],
            gamma_n=c["gamma_n"],
            message_time_s=c["message_time_s"],
            health=np.round(c["health"]).astype(np.int64),
            channel=np.round(c["channel"]).astype(np.int64),
            age_days=np.round(c["age_days"]).astype(np.int64),
        )
