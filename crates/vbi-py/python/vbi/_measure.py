"""Load tests from Python: ``vbi measure``'s processing of a ``[measurement]`` file."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Union

from . import _vbi

MeasurementSource = Union[str, "os.PathLike[str]", Mapping[str, Any]]


@dataclass(frozen=True)
class ChannelSignals:
    """One channel's signals, in SI (m, strain, N·m or m/s²), one sample per ``time_s``."""

    #: The record after the baseline correction.
    record: Any
    #: Its static part (None for an acceleration channel).
    static: Optional[Any]
    #: The record low-passed above its cut-off mode K1 (None when no K1 was asked).
    filtered_at_k1: Optional[Any]


@dataclass(frozen=True)
class MeasurementResult:
    """What ``vbi measure`` computes: ``summary`` holds the numbers of ``measure.json`` (without
    its provenance and figure list) as a dict, the rest the arrays behind them."""

    #: The numbers of ``measure.json``: channels (DAF, static method, separation check, K1
    #: filtering), rdm, spectra, identified_frequencies, static_separation, preparation, ...
    summary: Dict[str, Any]
    #: The record's CSV file.
    csv: str
    #: Sample times [s].
    time_s: Any
    #: Per channel name.
    channels: Dict[str, ChannelSignals]
    #: Per acceleration channel: ``frequency_hz`` [Hz] and ``density`` [(m/s²)²/Hz] (Welch).
    spectra: Dict[str, Dict[str, Any]]

    def daf(self, channel: str) -> float:
        """The DAF of a channel (dynamic maximum over static maximum, in the static response's
        direction)."""
        for entry in self.summary["channels"]:
            if entry["name"] == channel:
                return entry["daf"]
        names = [entry["name"] for entry in self.summary["channels"]]
        raise KeyError(f"no DAF channel `{channel}`; the DAF channels are {names}")

    @property
    def identified_frequencies_hz(self) -> List[float]:
        """The identified bridge frequencies [Hz], ascending."""
        return [mode["frequency_hz"] for mode in self.summary["identified_frequencies"]]

    @property
    def warnings(self) -> List[str]:
        """What the reader must know before using these numbers (``measure.json``'s
        ``warnings``: a DAF on a static part whose own check failed, frequencies that may be the
        crossing's forced content, implausible damping, a speed the record does not bear out), each
        as ``vbi measure`` prints it."""
        return [warning["message"] for warning in self.summary["warnings"]]

    @property
    def speed_check(self) -> Optional[Dict[str, Any]]:
        """The stated speed against the one the record's response shows (``measure.json``'s
        ``speed_check``: ``stated_speed_m_s``, ``fitted_speed_m_s``, ``explained_variance``,
        ``tolerance``, ``plausible``), or None where the record does not allow the check."""
        return self.summary.get("speed_check")

    @property
    def weighing(self) -> Optional[Dict[str, Any]]:
        """The vehicle weighed from the record, when ``[measurement.weighing]`` asks for it
        (``measure.json``'s ``weighing``: ``axle_loads_n``, ``gross_weight_n``, their
        ``*_fit_std_n`` (the least squares' own standard deviations, without the vehicle's
        dynamic axle forces), ``entry_time_s``, ``channels`` with each one's influence line,
        and ``against_given`` when the axle loads were given); None otherwise."""
        return self.summary.get("weighing")

    def to_dataframe(self) -> Any:
        """The signals as a pandas DataFrame, one row per sample, units in the column names
        (``<channel>_record_si``, ``<channel>_static_si``, ``<channel>_filtered_at_k1_si``)."""
        import pandas as pd

        data: Dict[str, Any] = {"time_s": self.time_s}
        for name, signals in self.channels.items():
            data[f"{name}_record_si"] = signals.record
            if signals.static is not None:
                data[f"{name}_static_si"] = signals.static
            if signals.filtered_at_k1 is not None:
                data[f"{name}_filtered_at_k1_si"] = signals.filtered_at_k1
        return pd.DataFrame(data)


def measure(source: MeasurementSource) -> MeasurementResult:
    """Processes a load test: ``source`` is a ``[measurement]`` TOML file (its CSV, crawl run
    and bridge relative to it) or a dict of its document (paths relative to the working
    directory). Raises :class:`vbi.InputError` with ``vbi measure``'s located message."""
    parts = _vbi.measure_parts(source)
    channels = {
        name: ChannelSignals(entry["record"], entry["static"], entry["filtered_at_k1"])
        for name, entry in parts["channels"].items()
    }
    return MeasurementResult(
        summary=json.loads(parts["summary_json"]),
        csv=parts["csv"],
        time_s=parts["time_s"],
        channels=channels,
        spectra=parts["spectra"],
    )
