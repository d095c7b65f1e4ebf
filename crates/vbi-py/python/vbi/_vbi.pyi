"""Typed stubs of the native module ``vbi._vbi`` (re-exported by ``vbi``). SI units."""

import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

#: A TOML file's path, or a dict of its document (top-level tables, as the file holds them).
Source = Union[str, os.PathLike[str], Mapping[str, Any]]
FloatArray = npt.NDArray[np.float64]

class VbiError(Exception):
    """A failure of the library (a bridge without modes, a diverged crossing, ...)."""

class InputError(VbiError):
    """A bad input, with the vbi command's located message ``file:line:column: field `…`: message``."""

    file: str
    line: Optional[int]
    column: Optional[int]
    field: Optional[str]
    message: str

class Bridge:
    """A bridge model: a preset ``paper-NxL`` (N spans of L m), a ``[bridge]`` TOML file, or a
    dict of that file's document (``{"bridge": {...}}``)."""

    def __init__(self, source: Source) -> None: ...
    @property
    def label(self) -> str: ...
    @property
    def span_lengths_m(self) -> List[float]:
        """Span lengths [m]."""
    @property
    def length_m(self) -> float:
        """Length between the end supports [m], along the girders."""
    @property
    def deck_length_m(self) -> float:
        """The deck's extent along x [m]: ``length_m`` plus a skewed grillage's offset."""
    @property
    def support_positions_m(self) -> List[float]:
        """Support positions along the girders [m]."""

class Vehicle:
    """A vehicle: a preset name (:func:`vehicle_presets`), a ``[vehicle]`` TOML file, or a dict
    of that file's document (``{"vehicle": {...}}``)."""

    def __init__(self, source: Source) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def source(self) -> str: ...
    def model(self) -> Dict[str, Any]:
        """``dof_names``, ``mass_matrix`` [kg, kg·m²], ``damping_matrix`` [N·s/m],
        ``stiffness_matrix`` [N/m] (DOFs × DOFs), ``contact_longitudinal_offsets_m``,
        ``contact_lateral_offsets_m``, ``contact_static_loads_n``."""

class Road:
    """A road: an ISO 8608 class (``"medium"``, ``"A"`` … ``"H"``), a ``[road]`` TOML file, or a
    dict of that file's document (``{"road": {...}}``)."""

    def __init__(self, source: Source) -> None: ...
    @property
    def seed(self) -> int: ...
    def profile(
        self, start_m: float, end_m: float, seed: Optional[int] = None
    ) -> Tuple[FloatArray, FloatArray, FloatArray]:
        """Positions x [m], left and right track elevations [m] from ``start_m`` to ``end_m``."""

class Scenario:
    """One crossing (SI units). ``Scenario()`` is the built-in paper scenario (3 × 30 m, five-axle
    truck, 'medium' road, 80 km/h, seed 1, 50 modes); ``Scenario(path)`` reads a ``[scenario]``
    file, ``Scenario(dict)`` the same document as a dict."""

    input_hash: str
    bridge: Bridge
    vehicle: Vehicle
    road: Road
    def __init__(self, source: Optional[Source] = None) -> None: ...
    def set(self, key: str, value: Union[bool, int, float, str, Sequence[Any]]) -> "Scenario":
        """Sets a ``[scenario]`` key as a file writes it (``speed_kmh``, ``seed``, ``modes``,
        ``road``, ...); raises :class:`InputError` as the file would; returns self."""
    def copy(self) -> "Scenario": ...
    @property
    def name(self) -> str: ...
    @property
    def speed_m_s(self) -> float:
        """Speed [m/s]."""
    @property
    def seed(self) -> int: ...
    @property
    def mode_count(self) -> int: ...

class PreparedBridge:
    """FE model, modal basis and static influence lines of a bridge; read-only, shareable."""

    @property
    def mode_count(self) -> int: ...
    @property
    def dof_count(self) -> int: ...
    @property
    def frequencies_hz(self) -> FloatArray:
        """Natural frequencies [Hz], ascending."""
    @property
    def damping_ratios(self) -> FloatArray:
        """Modal damping ratios [-]."""
    @property
    def kinds(self) -> List[str]:
        """``vertical_bending``, ``torsion``, ``lateral`` or ``longitudinal`` per mode."""
    @property
    def station_names(self) -> List[str]: ...
    @property
    def station_deflection(self) -> FloatArray:
        """Stations × modes [m per unit modal coordinate (kg^½·m)]."""
    @property
    def station_moment(self) -> FloatArray:
        """Stations × modes [N·m per unit modal coordinate]."""
    @property
    def shapes(self) -> FloatArray:
        """Deck nodes × modes [m per unit modal coordinate]."""
    @property
    def deck_x_m(self) -> FloatArray: ...
    @property
    def deck_y_m(self) -> FloatArray: ...

class DetailFatigue:
    """The fatigue of one detail under a crossing (docs/fatigue.md); stresses in Pa.

    Its attributes are the rows of the library's table of fatigue outputs
    (``vbi.fatigue_outputs()``: name, label, unit, meaning), in that order.
    """

    @property
    def detail(self) -> str: ...
    @property
    def station(self) -> str: ...
    @property
    def quantity(self) -> str: ...
    @property
    def fibre(self) -> str: ...
    @property
    def curve(self) -> str: ...
    @property
    def fatigue_daf(self) -> Optional[float]:
        """(D_dynamic / D_static)^(1/m) on the detail's curve; None below the cut-off."""
    @property
    def fatigue_daf_straight_line(self) -> Optional[float]: ...
    @property
    def fatigue_daf_change(self) -> Optional[float]:
        """The convergence indicator of ``fatigue_daf`` in the modes."""
    @property
    def fatigue_daf_straight_line_change(self) -> Optional[float]: ...
    @property
    def damage_ratio(self) -> Optional[float]: ...
    @property
    def dynamic_damage(self) -> float: ...
    @property
    def static_damage(self) -> float: ...
    @property
    def crossings_to_failure(self) -> Optional[float]: ...
    @property
    def dynamic_cycles(self) -> float: ...
    @property
    def static_cycles(self) -> float: ...
    @property
    def dynamic_damaging_cycles(self) -> float: ...
    @property
    def dynamic_max_range(self) -> float: ...
    @property
    def static_max_range(self) -> float: ...
    @property
    def dynamic_equivalent_range(self) -> float: ...
    @property
    def static_equivalent_range(self) -> float: ...
    @property
    def dynamic_max_stress(self) -> float: ...
    @property
    def dynamic_min_stress(self) -> float: ...
    @property
    def cut_off(self) -> float: ...
    @property
    def stress_concentration(self) -> float: ...

class StationDaf:
    """DAF analysis of one station and quantity; extremes signed, in m, N·m or N.

    Its attributes are the rows of the library's table of station outputs
    (``vbi.station_outputs()``: name, label, unit, meaning), in that order.
    """

    @property
    def name(self) -> str: ...
    @property
    def quantity(self) -> str:
        """``deflection``, ``bending_moment``, ``shear_force`` or ``support_reaction``."""
    @property
    def static_max(self) -> float: ...
    @property
    def static_max_time_s(self) -> float: ...
    @property
    def dynamic_max(self) -> float:
        """The converged (static-corrected) dynamic extreme."""
    @property
    def dynamic_max_time_s(self) -> float: ...
    @property
    def daf(self) -> Optional[float]:
        """The converged DAF [-]."""
    @property
    def static_max_single_vehicle(self) -> Optional[float]:
        """With two or more vehicles: the largest static extreme of one vehicle alone."""
    @property
    def daf_single_vehicle(self) -> Optional[float]:
        """The DAF against the heaviest single vehicle's static effect [-]."""
    @property
    def impact_factor(self) -> Optional[float]: ...
    @property
    def daf_change(self) -> Optional[float]:
        """The convergence indicator: the DAF's largest change over the last ⌈N/2⌉ modes kept, or twice that over the check modes above them where larger."""
    @property
    def daf_change_dt(self) -> Optional[float]:
        """The convergence indicator in the time step: DAF(Δt) − DAF(2Δt)."""
    @property
    def converged(self) -> Optional[bool]: ...
    @property
    def daf_by_modes(self) -> FloatArray:
        """The converged DAF(K), K = 1…N [-]."""
    @property
    def daf_by_check_modes(self) -> FloatArray:
        """The converged DAF continued over the check modes, K = N + 1…N + C [-] (modes above N, integrated against the contact forces without feeding back; what `daf_change` reads beyond N)."""
    @property
    def convergence_mode(self) -> Optional[int]: ...
    @property
    def static_corrected(self) -> bool: ...
    @property
    def dynamic_max_paper(self) -> float:
        """The paper's plain modal sum of all N modes."""
    @property
    def daf_paper(self) -> Optional[float]: ...
    @property
    def daf_paper_by_modes(self) -> FloatArray: ...
    @property
    def convergence_mode_paper(self) -> Optional[int]: ...
    @property
    def participation(self) -> FloatArray:
        """MPS_k at the station [-]."""
    @property
    def cumulative_participation(self) -> FloatArray: ...
    @property
    def cutoff_k1(self) -> Optional[int]: ...
    @property
    def cutoff_k2(self) -> Optional[int]: ...

class RunResult:
    """One crossing and its DAF analysis."""

    scenario_name: str
    vehicle_name: str
    #: Wall time of the crossing inside Rust (``crossing::run_crossing``) [s].
    crossing_time_s: float
    @property
    def stations(self) -> List[StationDaf]: ...
    @property
    def fatigue(self) -> List[DetailFatigue]:
        """The fatigue of each of the scenario's ``[[fatigue_detail]]`` tables."""
    def daf(self, station: str, quantity: str = "deflection") -> Optional[float]: ...
    @property
    def rdm_station(self) -> Optional[str]: ...
    @property
    def rdm(self) -> Optional[float]: ...
    @property
    def rdm_by_modes(self) -> FloatArray: ...
    @property
    def corrected_rdm(self) -> Optional[float]: ...
    @property
    def corrected_rdm_by_modes(self) -> FloatArray: ...
    @property
    def frequencies_hz(self) -> FloatArray: ...
    @property
    def deck_participation(self) -> Dict[str, FloatArray]: ...
    @property
    def cutoff_modes(self) -> Dict[str, Optional[int]]: ...
    @property
    def contact_losses(self) -> List[Dict[str, Any]]: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def truncated_runs(self) -> List[Dict[str, Any]]: ...
    @property
    def design_codes(self) -> List[Dict[str, Any]]: ...
    @property
    def time_step_s(self) -> float: ...
    @property
    def mode_count(self) -> int: ...
    @property
    def dof_count(self) -> int: ...
    @property
    def exit_step(self) -> int: ...
    @property
    def front_axle_x_m(self) -> FloatArray: ...
    @property
    def modal_displacement(self) -> FloatArray:
        """Steps × modes [kg^½·m]."""
    @property
    def modal_velocity(self) -> FloatArray: ...
    @property
    def contact_force_n(self) -> FloatArray:
        """Steps × contacts [N], compressive positive."""
    @property
    def vehicle_dof_names(self) -> List[str]: ...
    @property
    def vehicle_displacement(self) -> FloatArray: ...
    @property
    def vehicle_acceleration(self) -> FloatArray: ...
    @property
    def histories(self) -> Dict[str, FloatArray]:
        """The columns of ``vbi run``'s histories.csv, units in the names."""
    @property
    def vehicle_histories(self) -> Dict[str, FloatArray]:
        """The columns of ``vbi run``'s vehicles.csv: every vehicle DOF, every contact."""
    def to_dataframe(self) -> Any:
        """``histories`` as a pandas DataFrame."""

def vehicle_presets() -> List[str]: ...
def modes(bridge: Bridge, n: int = 50) -> PreparedBridge:
    """The first ``n`` modes (vertical bending and torsion kept) of a bridge, 1 m mesh."""
def prepare(scenario: Scenario) -> PreparedBridge:
    """The scenario's bridge prepared with its mesh and modal options."""
def station_outputs() -> List[Dict[str, Any]]:
    """The table of a station entry's outputs: name, label, unit, unit_of_quantity, meaning,
    in_run_summary, one dict per row in order."""

def lifetime_fatigue_parts(source: Source) -> Dict[str, Any]: ...
def fatigue_outputs() -> List[Dict[str, Any]]:
    """The table of a fatigue detail's outputs: name, label, unit, meaning, one dict per row."""
def rainflow(series: Sequence[float]) -> List[Tuple[float, float, float]]:
    """Rainflow counting (ASTM E1049-85 §5.4.4): (range, mean, count) in the order counted."""
def count_cycles(series: Sequence[float]) -> List[Tuple[float, float]]:
    """(range, count) summed over equal ranges, sorted: the ``rainflow`` package's form."""
def run(scenario: Scenario, bridge: Optional[PreparedBridge] = None) -> RunResult:
    """One crossing and its DAF analysis; the GIL is released while it runs."""
def study_cells(
    source: Source, *, shard: Optional[str] = None, threads: Optional[int] = None
) -> Dict[str, Any]: ...
def study_case_count(source: Source) -> int: ...
def measure_parts(source: Source) -> Dict[str, Any]:
    """The parts of :func:`vbi.measure`'s result (use ``vbi.measure``)."""
def lifetime_parts(source: Source, shard: Optional[Tuple[int, int]] = None) -> Dict[str, Any]:
    """The parts of :func:`vbi.lifetime`'s result (use ``vbi.lifetime``): ``effect``,
    ``block``, ``static``, ``time_s``, ``trucks`` (numpy columns, the rows of
    ``block_maxima.csv``), ``effects`` (``(station, quantity)`` per effect index) and
    ``summary`` (the numbers of ``lifetime.json``); with ``shard`` = ``(I, N)``, shard I of
    N's, with ``shard`` (its shard.json text); the GIL is released while it runs."""
def lifetime_merge_parts(source: Source, shards: List[str]) -> Dict[str, Any]:
    """The merged parts of the shards' ``shard.json`` texts (use ``vbi.merge_lifetime``):
    ``total`` and ``daf`` with dynamics, and ``summary``."""
def fit_extreme_value(
    values: List[float], model: str = "gev", threshold: Optional[float] = None
) -> Dict[str, float]:
    """The maximum-likelihood fit of ``values`` (use ``vbi.fit_extreme_value``)."""
def fit_block_maxima_parts(
    values: List[float],
    block_days: float = 1.0,
    sense: float = 1.0,
    return_periods_years: List[float] = ...,
    days_per_year: float = 250.0,
    bootstrap_resamples: int = 400,
    seed: int = 0,
) -> Dict[str, Any]:
    """The fits and return levels of block maxima (use ``vbi.fit_block_maxima``)."""
