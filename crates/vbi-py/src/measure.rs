//! `vbi.measure(source)`: a `[measurement]` file (a load-test record and how to process it)
//! read by `vbi-input` as `vbi measure` reads it, and processed by the library's measurement
//! stage (`vbi::crossing::measure`): the numbers of `measure.json` and the signals behind them
//! as numpy arrays.

use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use vbi::measure::{measure as process, MeasureError, MeasurementResult};
use vbi_input::measurement;

use crate::errors::{input_error, library_error};
use crate::source;

/// The parts of the result as a dict: `summary_json` (the JSON of `measure.json` without its
/// provenance and figure list, which the Python side parses), `csv` (the record's path),
/// `time_s`, and per channel name its `record` (baseline-corrected, SI), `static` and
/// `filtered_at_k1` (None when not formed), and per spectrum channel `frequency_hz` and
/// `density`.
#[pyfunction]
#[pyo3(signature = (source))]
pub fn measure_parts<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let file = source::of_kind(source, "measurement", "vbi.measure")?;
    let loaded = measurement::load(&file).map_err(input_error)?;
    let result = py
        .detach(|| process(&loaded.measurement))
        .map_err(|e| match e {
            MeasureError::Input { field, message } => {
                input_error(file.error_at(&format!("measurement.{field}"), message))
            }
            other => library_error(&other),
        })?;
    let summary_json = serde_json::to_string(&result.summary).map_err(|e| library_error(&e))?;
    let parts = PyDict::new(py);
    parts.set_item("summary_json", summary_json)?;
    parts.set_item("csv", loaded.csv_path.display().to_string())?;
    let MeasurementResult {
        record,
        signals,
        densities,
        summary,
    } = result;
    parts.set_item("time_s", record.time.into_pyarray(py))?;
    let channels = PyDict::new(py);
    let mut signals = signals.into_iter().peekable();
    for (index, channel) in record.channels.into_iter().enumerate() {
        let entry = PyDict::new(py);
        entry.set_item("record", channel.samples.into_pyarray(py))?;
        match signals.next_if(|s| s.channel_index == index) {
            Some(s) => {
                entry.set_item("static", s.static_part.into_pyarray(py))?;
                entry.set_item(
                    "filtered_at_k1",
                    s.filtered_at_cutoff_mode.map(|f| f.into_pyarray(py)),
                )?;
            }
            None => {
                entry.set_item("static", py.None())?;
                entry.set_item("filtered_at_k1", py.None())?;
            }
        }
        channels.set_item(channel.name, entry)?;
    }
    parts.set_item("channels", channels)?;
    let spectra = PyDict::new(py);
    for (psd, spectrum) in densities.into_iter().zip(&summary.spectra) {
        let entry = PyDict::new(py);
        entry.set_item("frequency_hz", psd.frequency_hz.into_pyarray(py))?;
        entry.set_item("density", psd.density.into_pyarray(py))?;
        spectra.set_item(&spectrum.channel, entry)?;
    }
    parts.set_item("spectra", spectra)?;
    Ok(parts)
}
