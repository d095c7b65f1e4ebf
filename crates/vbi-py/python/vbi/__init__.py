"""vbi: vehicle–bridge interaction dynamics from Python.

The library pipeline of the Rust crate ``vbi``, bound with pyo3: bridges, vehicles and roads
from presets, TOML files or dicts; modes; one crossing and its DAF analysis; parametric studies; load-test records;
static lifetime block maxima under a traffic file, and their extreme-value fits and return levels.
SI units throughout (m, s, N, kg, Hz); names carry the unit where it is not SI base (``_kmh``).
Inputs are read and refused exactly as the ``vbi`` command reads them: a bad input raises
:class:`InputError` with the command's located message ``file:line:column: field `…`: message``.
See docs/python.md.
"""

from __future__ import annotations

from ._vbi import (
    Bridge,
    DetailFatigue,
    InputError,
    PreparedBridge,
    Road,
    RunResult,
    Scenario,
    StationDaf,
    VbiError,
    Vehicle,
    __version__,
    count_cycles,
    fatigue_outputs,
    modes,
    prepare,
    rainflow,
    run,
    station_outputs,
    vehicle_presets,
)
from ._lifetime import (
    fit_block_maxima,
    fit_extreme_value,
    lifetime,
    lifetime_fatigue,
    lifetime_return_levels,
    merge_lifetime,
)
from ._measure import ChannelSignals, MeasurementResult, measure
from ._study import study, study_case_count, study_columns, study_tables

__all__ = [
    "Bridge",
    "ChannelSignals",
    "DetailFatigue",
    "InputError",
    "MeasurementResult",
    "PreparedBridge",
    "Road",
    "RunResult",
    "Scenario",
    "StationDaf",
    "VbiError",
    "Vehicle",
    "__version__",
    "count_cycles",
    "fatigue_outputs",
    "lifetime",
    "lifetime_fatigue",
    "lifetime_return_levels",
    "merge_lifetime",
    "fit_block_maxima",
    "fit_extreme_value",
    "measure",
    "modes",
    "prepare",
    "rainflow",
    "run",
    "station_outputs",
    "study",
    "study_case_count",
    "study_columns",
    "study_tables",
    "vehicle_presets",
]
