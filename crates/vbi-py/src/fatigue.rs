//! Fatigue in Python (issue 51): a crossing's details (`RunResult.fatigue`, the rows of the
//! library's table of fatigue outputs) and rainflow counting of any series (`vbi.rainflow`,
//! `vbi.count_cycles`), the library's own counter (ASTM E1049-85 §5.4.4).

use pyo3::prelude::*;
use pyo3::types::PyDict;

use vbi::fatigue::{count_by_range, rainflow as count, DetailFatigue as Entry};
use vbi::outputs::{fatigue_output, FATIGUE_OUTPUTS};

use crate::output_tables::table_attribute;

/// The fatigue of one detail under a crossing: stresses in Pa, damages as Miner's sums.
#[pyclass(module = "vbi", frozen)]
pub struct DetailFatigue {
    pub(crate) entry: Entry,
}

#[pymethods]
impl DetailFatigue {
    /// An output of the detail by its name: a row of the library's table of fatigue outputs
    /// (`vbi.fatigue_outputs()` lists them with their units and meanings). AttributeError for a
    /// name the table does not hold.
    fn __getattr__(&self, py: Python<'_>, name: &str) -> PyResult<Py<PyAny>> {
        let value = fatigue_output(name).map(|row| row.value);
        table_attribute(py, "DetailFatigue", name, value, &self.entry)
    }
    /// The attributes: the names of the table's rows.
    fn __dir__(&self) -> Vec<&'static str> {
        FATIGUE_OUTPUTS.iter().map(|row| row.name).collect()
    }
    fn __repr__(&self) -> String {
        let daf = |v: Option<f64>| v.map_or("None".to_string(), |d| format!("{d:.4}"));
        format!(
            "vbi.DetailFatigue({:?} at {:?}: fatigue DAF {}, no cut-off {})",
            self.entry.detail.name,
            self.entry.detail.station,
            daf(self.entry.amplification.fatigue_daf),
            daf(self.entry.amplification.fatigue_daf_straight_line),
        )
    }
}

/// The table of a fatigue detail's outputs, one dict per row in order: `name` (the attribute
/// of `DetailFatigue`, the key of summary.json's `fatigue` entries and the column of
/// fatigue.csv), `label`, `unit` and `meaning`.
#[pyfunction]
pub fn fatigue_outputs(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    FATIGUE_OUTPUTS
        .iter()
        .map(|row| {
            let dict = PyDict::new(py);
            dict.set_item("name", row.name)?;
            dict.set_item("label", row.label)?;
            dict.set_item("unit", row.unit.symbol(vbi::modal::Quantity::Deflection))?;
            dict.set_item("meaning", row.meaning)?;
            Ok(dict)
        })
        .collect()
}

/// The cycles of a series by rainflow counting (ASTM E1049-85 §5.4.4, the residue as half
/// cycles), in the order counted: (range, mean, count) with count 1.0 or 0.5.
#[pyfunction]
pub fn rainflow(series: Vec<f64>) -> Vec<(f64, f64, f64)> {
    count(&series)
        .into_iter()
        .map(|c| (c.range, c.mean, c.count))
        .collect()
}

/// The counts of a series' cycles by range, summed over equal ranges and sorted by range: what
/// the `rainflow` package's `count_cycles(series)` returns.
#[pyfunction]
pub fn count_cycles(series: Vec<f64>) -> Vec<(f64, f64)> {
    count_by_range(&count(&series))
}
