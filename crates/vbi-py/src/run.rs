//! `vbi.run(scenario)`: one crossing and its DAF analysis (`vbi::crossing::run_crossing`), the
//! GIL released while it runs. The large histories (modal coordinates, contact forces, vehicle
//! responses) become numpy arrays without a copy; the station histories that `vbi run` writes
//! to histories.csv are computed when first asked for.

use std::sync::Arc;
use std::time::Instant;

use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::PyDict;
use pyo3::IntoPyObjectExt;

use vbi::analysis::{DafReport, StationDaf as Entry};
use vbi::crossing::{run_crossing, station_history_columns};
use vbi::outputs::{station_output, STATION_OUTPUTS};
use vbi::solver::ResponseHistory;

use crate::arrays::{copied, table, with_nan};
use crate::bridge_modes::{frequencies, prepare_spec, PreparedBridge};
use crate::errors::library_error;
use crate::output_tables::table_attribute;
use crate::scenario::Scenario;

/// The DAF analysis of one station and quantity; values signed, in m (deflection), N·m
/// (bending moment) or N (shear force, support reaction).
#[pyclass(module = "vbi", frozen)]
pub struct StationDaf {
    entry: Entry,
}

#[pymethods]
impl StationDaf {
    /// An output of the entry by its name: a row of the library's table of station outputs
    /// (`vbi::outputs::STATION_OUTPUTS`, listed with its units and meanings by
    /// `vbi.station_outputs()`), so that every output the table holds is an attribute here.
    /// AttributeError for a name the table does not hold.
    fn __getattr__(&self, py: Python<'_>, name: &str) -> PyResult<Py<PyAny>> {
        let value = station_output(name).map(|row| row.value);
        table_attribute(py, "StationDaf", name, value, &self.entry)
    }
    /// The attributes: the names of the table's rows.
    fn __dir__(&self) -> Vec<&'static str> {
        STATION_OUTPUTS.iter().map(|row| row.name).collect()
    }
    fn __repr__(&self) -> String {
        format!(
            "vbi.StationDaf({:?} {}: DAF {})",
            self.entry.name,
            self.entry.quantity.name(),
            optional(self.entry.converged.daf)
        )
    }
}

/// The table of a station entry's outputs, one dict per row in order: `name` (the attribute of
/// `StationDaf` and the key of `vbi run`'s summary.json), `label`, `unit` (of a deflection
/// entry; `unit_of_quantity` is true where the unit is the entry's quantity's: m, N·m or N),
/// `meaning` and `in_run_summary`.
#[pyfunction]
pub fn station_outputs(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    STATION_OUTPUTS
        .iter()
        .map(|row| {
            let dict = PyDict::new(py);
            dict.set_item("name", row.name)?;
            dict.set_item("label", row.label)?;
            dict.set_item("unit", row.unit.symbol(vbi::modal::Quantity::Deflection))?;
            dict.set_item(
                "unit_of_quantity",
                row.unit == vbi::outputs::Unit::OfQuantity,
            )?;
            dict.set_item("meaning", row.meaning)?;
            dict.set_item("in_run_summary", row.in_run_summary)?;
            Ok(dict)
        })
        .collect()
}

/// The large histories, moved into numpy arrays (steps × modes, steps × contacts, ...).
struct HistoryArrays {
    front_axle_position: Py<PyArray1<f64>>,
    modal_displacement: Py<PyArray2<f64>>,
    modal_velocity: Py<PyArray2<f64>>,
    contact_force: Py<PyArray2<f64>>,
    vehicle_displacement: Py<PyArray2<f64>>,
    vehicle_acceleration: Py<PyArray2<f64>>,
}

/// One crossing and its DAF analysis.
#[pyclass(module = "vbi", frozen)]
pub struct RunResult {
    bridge: Arc<vbi::crossing::PreparedBridge>,
    report: DafReport,
    /// The fatigue of the scenario's details.
    fatigue: Vec<vbi::fatigue::DetailFatigue>,
    /// The history without its large arrays (in `arrays`).
    history: ResponseHistory,
    arrays: HistoryArrays,
    histories: PyOnceLock<Py<PyDict>>,
    #[pyo3(get)]
    scenario_name: String,
    #[pyo3(get)]
    vehicle_name: String,
    /// Wall time of `crossing::run_crossing` inside this call [s], measured in Rust: what the
    /// same crossing costs without Python (the benchmark compares it with the call's time).
    #[pyo3(get)]
    crossing_time_s: f64,
}

/// Moves a row-major history into a 2-D array of `columns` columns.
fn moved(py: Python<'_>, values: &mut Vec<f64>, columns: usize) -> PyResult<Py<PyArray2<f64>>> {
    Ok(table(py, std::mem::take(values), columns)?.unbind())
}

impl RunResult {
    fn new(
        py: Python<'_>,
        bridge: Arc<vbi::crossing::PreparedBridge>,
        scenario: &vbi::crossing::Scenario,
        result: vbi::crossing::RunResult,
        crossing_time_s: f64,
    ) -> PyResult<RunResult> {
        let mut history = result.history;
        let (modes, contacts, dofs) = (
            history.mode_count,
            history.contacts.len(),
            history.vehicle_dof_names.len(),
        );
        let arrays = HistoryArrays {
            front_axle_position: std::mem::take(&mut history.front_axle_position)
                .into_pyarray(py)
                .unbind(),
            modal_displacement: moved(py, &mut history.modal_displacement, modes)?,
            modal_velocity: moved(py, &mut history.modal_velocity, modes)?,
            contact_force: moved(py, &mut history.contact_force, contacts)?,
            vehicle_displacement: moved(py, &mut history.vehicle_displacement, dofs)?,
            vehicle_acceleration: moved(py, &mut history.vehicle_acceleration, dofs)?,
        };
        Ok(RunResult {
            bridge,
            report: result.report,
            fatigue: result.fatigue,
            history,
            arrays,
            histories: PyOnceLock::new(),
            scenario_name: scenario.name.clone(),
            vehicle_name: result.crossing.vehicle_names(),
            crossing_time_s,
        })
    }

    /// The history with its arrays read back from numpy (a copy, for the station histories).
    fn full_history(&self, py: Python<'_>) -> PyResult<ResponseHistory> {
        let read = |array: &Py<PyArray2<f64>>| -> PyResult<Vec<f64>> {
            Ok(array.bind(py).readonly().as_slice()?.to_vec())
        };
        Ok(ResponseHistory {
            front_axle_position: self
                .arrays
                .front_axle_position
                .bind(py)
                .readonly()
                .as_slice()?
                .to_vec(),
            modal_displacement: read(&self.arrays.modal_displacement)?,
            modal_velocity: Vec::new(),
            contact_force: read(&self.arrays.contact_force)?,
            vehicle_displacement: read(&self.arrays.vehicle_displacement)?,
            vehicle_acceleration: read(&self.arrays.vehicle_acceleration)?,
            ..self.history.clone()
        })
    }

    /// The columns of histories.csv, as `vbi run --out` writes them (the library's
    /// `station_history_columns`).
    fn station_histories<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let history = self.full_history(py)?;
        let bridge = &*self.bridge;
        let columns = py
            .detach(|| station_history_columns(bridge, &history))
            .map_err(|e| library_error(&e))?;
        let dict = PyDict::new(py);
        for column in columns {
            if column.name == "front_axle_x_m" {
                // The array that `front_axle_x_m` already hands out: the same values, no copy.
                dict.set_item(column.name, self.arrays.front_axle_position.bind(py))?;
            } else {
                dict.set_item(column.name, column.values.into_pyarray(py))?;
            }
        }
        Ok(dict)
    }
}

impl RunResult {
    /// The columns of vehicles.csv, as `vbi run --out` writes them (the library's
    /// `vehicle_history_columns`).
    fn vehicle_columns<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let history = self.full_history(py)?;
        let dict = PyDict::new(py);
        for column in vbi::crossing::vehicle_history_columns(&history) {
            dict.set_item(column.name, column.values.into_pyarray(py))?;
        }
        Ok(dict)
    }
}

/// An optional number as reprs show it (`-` for None).
fn optional(value: Option<f64>) -> String {
    value.map_or_else(|| "-".to_string(), |v| v.to_string())
}

/// A `{name: value}` dict.
fn dict<'py>(
    py: Python<'py>,
    items: Vec<(&str, Bound<'py, PyAny>)>,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    for (key, value) in items {
        dict.set_item(key, value)?;
    }
    Ok(dict)
}

fn any<'py, T: IntoPyObject<'py>>(py: Python<'py>, value: T) -> PyResult<Bound<'py, PyAny>> {
    value.into_bound_py_any(py)
}

#[pymethods]
impl RunResult {
    /// The fatigue of each of the scenario's `[[fatigue_detail]]`s (docs/fatigue.md), in order;
    /// empty without details.
    #[getter]
    fn fatigue(&self) -> Vec<crate::fatigue::DetailFatigue> {
        self.fatigue
            .iter()
            .map(|entry| crate::fatigue::DetailFatigue {
                entry: entry.clone(),
            })
            .collect()
    }

    /// The DAF analysis of every analysed station and quantity (station order: deflection,
    /// bending moment, then shear force or, at a support, support reaction).
    #[getter]
    fn stations(&self) -> Vec<StationDaf> {
        self.report
            .stations
            .iter()
            .map(|entry| StationDaf {
                entry: entry.clone(),
            })
            .collect()
    }

    /// The DAF [-] of `quantity` (`deflection`, `bending_moment`, `shear_force` or
    /// `support_reaction`) at the station named
    /// `station`; None where it is undefined. KeyError for a station not analysed.
    #[pyo3(signature = (station, quantity = "deflection"))]
    fn daf(&self, station: &str, quantity: &str) -> PyResult<Option<f64>> {
        self.report
            .stations
            .iter()
            .find(|e| e.name == station && e.quantity.name() == quantity)
            .map(|e| e.converged.daf)
            .ok_or_else(|| {
                pyo3::exceptions::PyKeyError::new_err(format!(
                    "no {quantity} analysed at `{station}`; stations: {}",
                    self.report
                        .stations
                        .iter()
                        .map(|e| e.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
            })
    }

    /// Station of the RDM (the largest-moment mid-span).
    #[getter]
    fn rdm_station(&self) -> Option<String> {
        self.report.rdm_station.clone()
    }
    /// The converged RDM = DAF_u / DAF_M at the RDM station [-].
    #[getter]
    fn rdm(&self) -> Option<f64> {
        self.report.rdm
    }
    /// The converged RDM(K), K = 1…N [-] (NaN where undefined).
    #[getter]
    fn rdm_by_modes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        with_nan(py, &self.report.rdm_by_modes)
    }
    /// The paper's RDM (plain modal sums) [-].
    #[getter]
    fn rdm_paper(&self) -> Option<f64> {
        self.report.rdm_paper
    }
    /// The paper's RDM(K) [-] (NaN where undefined).
    #[getter]
    fn rdm_paper_by_modes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        with_nan(py, &self.report.rdm_paper_by_modes)
    }
    /// Natural frequencies of the basis [Hz].
    #[getter]
    fn frequencies_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        frequencies(py, &self.bridge.basis)
    }
    /// Deck-wide modal participation (Eq. 30): `deflection`, `moment` (MPS_k per mode [-]),
    /// their cumulative sums, and the cut-off modes.
    #[getter]
    fn deck_participation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let deck = &self.report.deck_participation;
        dict(
            py,
            vec![
                ("deflection", copied(py, &deck.deflection).into_any()),
                (
                    "deflection_cumulative",
                    copied(py, &deck.deflection_cumulative).into_any(),
                ),
                ("moment", copied(py, &deck.moment).into_any()),
                (
                    "moment_cumulative",
                    copied(py, &deck.moment_cumulative).into_any(),
                ),
            ],
        )
    }
    /// Deck-wide cut-off modes K1, K2 (1-based) of the deflection and the moment, over all
    /// modes and counted among the vertical bending modes only (`bending_*`).
    #[getter]
    fn cutoff_modes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let deck = &self.report.deck_participation;
        let bending = &deck.vertical_bending;
        dict(
            py,
            vec![
                ("deflection_k1", any(py, deck.deflection_k1)?),
                ("deflection_k2", any(py, deck.deflection_k2)?),
                ("moment_k1", any(py, deck.moment_k1)?),
                ("moment_k2", any(py, deck.moment_k2)?),
                ("bending_deflection_k1", any(py, bending.deflection_k1)?),
                ("bending_deflection_k2", any(py, bending.deflection_k2)?),
                ("bending_moment_k1", any(py, bending.moment_k1)?),
                ("bending_moment_k2", any(py, bending.moment_k2)?),
            ],
        )
    }
    /// Intervals of tensile tyre force: `contact` (0-based), `start_time_s`, `end_time_s`,
    /// `minimum_force_n`.
    #[getter]
    fn contact_losses<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.report
            .contact_losses
            .iter()
            .map(|loss| {
                dict(
                    py,
                    vec![
                        ("contact", any(py, loss.contact)?),
                        ("start_time_s", any(py, loss.start_time)?),
                        ("end_time_s", any(py, loss.end_time)?),
                        ("minimum_force_n", any(py, loss.minimum_force)?),
                    ],
                )
            })
            .collect()
    }
    /// The solver's warnings, one sentence each.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.report.warnings.iter().map(|w| w.to_string()).collect()
    }
    /// Re-runs with only the first K modes (`rerun_modes`): `mode_count`, `rdm` and `stations`
    /// (`name`, `quantity`, `daf`).
    #[getter]
    fn truncated_runs<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let entry = |e: &vbi::analysis::TruncatedStationDaf| {
            dict(
                py,
                vec![
                    ("name", any(py, e.name.as_str())?),
                    ("quantity", any(py, e.quantity.name())?),
                    ("daf", any(py, e.daf)?),
                ],
            )
        };
        self.report
            .truncated_runs
            .iter()
            .map(|run| {
                let stations = run
                    .stations
                    .iter()
                    .map(entry)
                    .collect::<PyResult<Vec<_>>>()?;
                dict(
                    py,
                    vec![
                        ("mode_count", any(py, run.mode_count)?),
                        ("rdm", any(py, run.rdm)?),
                        ("stations", any(py, stations)?),
                    ],
                )
            })
            .collect()
    }
    /// The design codes' impact factors of every station and quantity of the report, beside
    /// the computed DAF (docs/design-codes.md): one dict per station, quantity and code case
    /// with `station`, `quantity`, `code` (name and edition), `provision`, `clause`, `basis`,
    /// `impact_factor` (IM), `code_daf` (1 + IM) and `computed_daf` (the converged DAF).
    #[getter]
    fn design_codes<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let mut rows = Vec::new();
        for codes in &self.report.design_codes {
            let computed = self
                .report
                .entry(codes.station_index, codes.quantity)
                .and_then(|e| e.converged.daf);
            for f in &codes.factors {
                rows.push(dict(
                    py,
                    vec![
                        ("station", any(py, codes.station.as_str())?),
                        ("quantity", any(py, codes.quantity.name())?),
                        ("code", any(py, f.code.name())?),
                        ("provision", any(py, f.provision.as_str())?),
                        ("clause", any(py, f.clause.as_str())?),
                        ("basis", any(py, f.basis.as_str())?),
                        ("impact_factor", any(py, f.impact_factor)?),
                        ("code_daf", any(py, f.daf())?),
                        ("computed_daf", any(py, computed)?),
                    ],
                )?);
            }
        }
        Ok(rows)
    }
    /// Time step Δt [s].
    #[getter]
    fn time_step_s(&self) -> f64 {
        self.history.time_step
    }
    /// Modes of the basis.
    #[getter]
    fn mode_count(&self) -> usize {
        self.history.mode_count
    }
    /// Degrees of freedom of the bridge's FE model.
    #[getter]
    fn dof_count(&self) -> usize {
        self.bridge.dof_count
    }
    /// First instant at which every tyre has left the deck.
    #[getter]
    fn exit_step(&self) -> usize {
        self.history.exit_step
    }
    /// Front-axle position x at each instant [m] (no copy).
    #[getter]
    fn front_axle_x_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.arrays.front_axle_position.bind(py).clone()
    }
    /// Modal coordinates q_k(t_i), steps × modes [kg^½·m] (no copy).
    #[getter]
    fn modal_displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.modal_displacement.bind(py).clone()
    }
    /// Modal velocities, steps × modes [kg^½·m/s] (no copy).
    #[getter]
    fn modal_velocity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.modal_velocity.bind(py).clone()
    }
    /// Total tyre contact forces, steps × contacts [N], compressive positive (no copy).
    #[getter]
    fn contact_force_n<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.contact_force.bind(py).clone()
    }
    /// Names of the vehicle DOFs (columns of the vehicle histories).
    #[getter]
    fn vehicle_dof_names(&self) -> Vec<String> {
        self.history.vehicle_dof_names.clone()
    }
    /// Vehicle displacements from static equilibrium, steps × DOFs [m, rad] (no copy).
    #[getter]
    fn vehicle_displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.vehicle_displacement.bind(py).clone()
    }
    /// Vehicle accelerations, steps × DOFs [m/s², rad/s²] (no copy).
    #[getter]
    fn vehicle_acceleration<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.vehicle_acceleration.bind(py).clone()
    }
    /// The station histories as `vbi run --out` writes histories.csv, one 1-D array per
    /// column, the unit in the name: `time_s`, `front_axle_x_m`, then per station
    /// `{station}_deflection_m`, `{station}_static_deflection_m`, `{station}_moment_n_m`,
    /// `{station}_static_moment_n_m`. Computed on first use.
    #[getter]
    fn histories<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let columns = self
            .histories
            .get_or_try_init(py, || self.station_histories(py).map(Bound::unbind))?;
        Ok(columns.bind(py).clone())
    }
    /// The columns of `vbi run`'s vehicles.csv as numpy arrays: `time_s`, every vehicle DOF's
    /// `…_displacement_m` (`_rad`) and `…_acceleration_m_s2` (`_rad_s2`), every contact's
    /// `v<i>_contact<c>_x_m` and `…_force_n`.
    #[getter]
    fn vehicle_histories<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.vehicle_columns(py)
    }
    /// `histories` as a pandas DataFrame (pandas must be installed).
    fn to_dataframe<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py.import("pandas").map_err(|_| {
            pyo3::exceptions::PyImportError::new_err(
                "RunResult.to_dataframe needs pandas: pip install pandas",
            )
        })?;
        pandas.call_method1("DataFrame", (self.histories(py)?,))
    }
    fn __repr__(&self) -> String {
        format!(
            "vbi.RunResult({:?}: {} modes, {} steps of {} s, RDM {} at {})",
            self.scenario_name,
            self.history.mode_count,
            self.history.step_count,
            self.history.time_step,
            optional(self.report.rdm),
            self.report.rdm_station.as_deref().unwrap_or("-")
        )
    }
}

/// One crossing of the scenario and its DAF analysis. `bridge` is the scenario's bridge
/// prepared once (`vbi.prepare(scenario)`), to share among many crossings; without it the
/// bridge is prepared for this run. The GIL is released while Rust runs.
#[pyfunction]
#[pyo3(signature = (scenario, bridge = None))]
pub fn run(
    py: Python<'_>,
    scenario: &Scenario,
    bridge: Option<&PreparedBridge>,
) -> PyResult<RunResult> {
    let prepared = match bridge {
        Some(bridge) => bridge.prepared.clone(),
        None => prepare_spec(py, &scenario.scenario.bridge)?.prepared,
    };
    let scenario = &scenario.scenario;
    let (result, crossing_time_s) = py.detach(|| {
        let started = Instant::now();
        let result = run_crossing(&prepared, scenario);
        (result, started.elapsed().as_secs_f64())
    });
    let result = result.map_err(|e| library_error(&e))?;
    RunResult::new(py, prepared, scenario, result, crossing_time_s)
}
