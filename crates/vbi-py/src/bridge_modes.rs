//! `vbi.modes(bridge, n)` and `vbi.prepare(scenario)`: the FE model, modal basis and static
//! influence lines of a bridge (`vbi::crossing::prepare_bridge`), with the modes as numpy arrays.

use std::sync::Arc;

use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;

use vbi::crossing::{prepare_bridge, BridgeSpec};
use vbi::modal::ModalBasis;

use crate::arrays::table;
use crate::errors::library_error;
use crate::parts::Bridge;
use crate::scenario::Scenario;

/// A bridge ready for crossings: its modal basis (modes in ascending frequency) and the exact
/// static influence lines of its stations. Read-only; share one among the crossings of a
/// study, from any thread.
#[pyclass(module = "vbi", frozen)]
pub struct PreparedBridge {
    pub prepared: Arc<vbi::crossing::PreparedBridge>,
}

impl PreparedBridge {
    fn basis(&self) -> &ModalBasis {
        &self.prepared.basis
    }
}

#[pymethods]
impl PreparedBridge {
    /// Number of modes kept in the basis.
    #[getter]
    fn mode_count(&self) -> usize {
        self.basis().mode_count()
    }

    /// Degrees of freedom of the FE model.
    #[getter]
    fn dof_count(&self) -> usize {
        self.prepared.dof_count
    }

    /// Natural frequencies f_k [Hz], ascending.
    #[getter]
    fn frequencies_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        frequencies(py, self.basis())
    }

    /// Modal damping ratios ζ_k [-].
    #[getter]
    fn damping_ratios<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let values: Vec<f64> = self.basis().modes.iter().map(|m| m.damping_ratio).collect();
        values.into_pyarray(py)
    }

    /// What each mode mostly does (`vertical_bending`, `torsion`, ...).
    #[getter]
    fn kinds(&self) -> Vec<&'static str> {
        self.basis().modes.iter().map(|m| m.kind.name()).collect()
    }

    /// Names of the response stations (mid-spans, supports).
    #[getter]
    fn station_names(&self) -> Vec<String> {
        self.basis()
            .stations
            .iter()
            .map(|s| s.name.clone())
            .collect()
    }

    /// Modal deflection at the stations, stations × modes [m per unit modal coordinate q; the
    /// modes are mass-normalised, q in kg^½·m].
    #[getter]
    fn station_deflection<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        table(
            py,
            self.basis().station_deflection.clone(),
            self.mode_count(),
        )
    }

    /// Modal bending moment at the stations, stations × modes [N·m per unit modal coordinate].
    #[getter]
    fn station_moment<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        table(py, self.basis().station_moment.clone(), self.mode_count())
    }

    /// Mode shapes at the deck nodes, nodes × modes [m per unit modal coordinate]; the nodes are
    /// those of `deck_x_m`, `deck_y_m`.
    #[getter]
    fn shapes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        table(py, self.basis().deck_deflection.clone(), self.mode_count())
    }

    /// Longitudinal position x of each deck node [m].
    #[getter]
    fn deck_x_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.deck_nodes(|_, x| x).into_pyarray(py)
    }

    /// Lateral position y of each deck node (its girder line) [m], left positive.
    #[getter]
    fn deck_y_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.deck_nodes(|y, _| y).into_pyarray(py)
    }

    fn __repr__(&self) -> String {
        let first = self.basis().modes.first().map(|m| m.frequency_hz());
        format!(
            "vbi.PreparedBridge({:?}: {} modes, f1 = {:?} Hz, {} DOF)",
            self.prepared.spec.model.span_lengths(),
            self.mode_count(),
            first,
            self.prepared.dof_count
        )
    }
}

impl PreparedBridge {
    fn deck_nodes(&self, value: fn(f64, f64) -> f64) -> Vec<f64> {
        let mut nodes = vec![
            0.0;
            self.basis()
                .deck
                .lines
                .iter()
                .map(|l| l.node_positions.len())
                .sum()
        ];
        for line in &self.basis().deck.lines {
            for (i, &x) in line.node_positions.iter().enumerate() {
                nodes[line.first_node + i] = value(line.lateral_position, x);
            }
        }
        nodes
    }
}

/// The natural frequencies of a basis [Hz].
pub fn frequencies<'py>(py: Python<'py>, basis: &ModalBasis) -> Bound<'py, PyArray1<f64>> {
    let values: Vec<f64> = basis.modes.iter().map(|m| m.frequency_hz()).collect();
    values.into_pyarray(py)
}

/// Prepares a bridge spec with the GIL released.
pub fn prepare_spec(py: Python<'_>, spec: &BridgeSpec) -> PyResult<PreparedBridge> {
    let prepared = py
        .detach(|| prepare_bridge(spec))
        .map_err(|e| library_error(&e))?;
    Ok(PreparedBridge {
        prepared: Arc::new(prepared),
    })
}

/// The first `n` modes of a bridge (meshed with 1 m elements; vertical bending and torsion
/// kept, the modes a truck excites): frequencies [Hz], kinds and shapes as numpy arrays.
#[pyfunction]
#[pyo3(signature = (bridge, n = 50))]
pub fn modes(py: Python<'_>, bridge: &Bridge, n: usize) -> PyResult<PreparedBridge> {
    prepare_spec(py, &BridgeSpec::new(bridge.model.clone(), n))
}

/// The scenario's bridge prepared as its mesh and modal options say, once, to run many
/// crossings on (`vbi.run(scenario, bridge=prepared)`).
#[pyfunction]
pub fn prepare(py: Python<'_>, scenario: &Scenario) -> PyResult<PreparedBridge> {
    prepare_spec(py, &scenario.scenario.bridge)
}
