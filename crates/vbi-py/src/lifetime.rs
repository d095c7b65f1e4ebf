//! `vbi.lifetime(source)`: a `[lifetime]` file read by `vbi-input` as `vbi lifetime` reads it
//! (`load`, `prepare`, the traffic file streamed by `TrafficFileReader`) and run by the
//! library's [`static_block_maxima`]: the rows of `block_maxima.csv` as numpy columns and the
//! numbers of `lifetime.json`, computed as the command computes them (the same sums in the same
//! order, so the same f64s).

use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use vbi::lifetime::{
    static_block_maxima, BlockMaximaTally, BlockMaximum, LifetimeError, StaticLifetime,
};
use vbi_input::lifetime as lifetime_input;
use vbi_input::traffic_file::TrafficFileReader;
use vbi_input::InputError;

use crate::errors::input_error;
use crate::source;

/// Why a run stopped: a bad line of the traffic file, or a truck the analysis refuses.
enum Failure {
    Line(InputError),
    Truck(LifetimeError),
}

/// The rows and the counts of a run, with the tally `vbi lifetime` keeps for `lifetime.json`.
struct Run {
    rows: Vec<BlockMaximum>,
    counts: vbi::lifetime::LifetimeCounts,
    tally: BlockMaximaTally,
}

/// Streams the traffic through the analysis (no Python object is touched: run without the GIL).
fn run(analysis: &StaticLifetime, reader: TrafficFileReader) -> Result<Run, Failure> {
    let mut bad_line: Option<InputError> = None;
    let trucks = reader.map_while(|truck| match truck {
        Ok(truck) => Some(truck),
        Err(error) => {
            bad_line = Some(error);
            None
        }
    });
    let mut rows = Vec::new();
    let mut tally = BlockMaximaTally::new(analysis);
    let counts = static_block_maxima(analysis, trucks, |block: &[BlockMaximum]| {
        tally.add(analysis, block);
        rows.extend_from_slice(block);
    })
    .map_err(Failure::Truck)?;
    if let Some(error) = bad_line {
        return Err(Failure::Line(error));
    }
    Ok(Run {
        rows,
        counts,
        tally,
    })
}

/// The parts of the result as a dict: `effect` (each row's index into `effects`), `block`,
/// `static`, `time_s` and `trucks` as numpy columns in the order of `block_maxima.csv`;
/// `effects` as `(station, quantity)` pairs; and `summary`, the numbers of `lifetime.json`.
#[pyfunction]
#[pyo3(signature = (source))]
pub fn lifetime_parts<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let file = source::of_kind(source, "lifetime", "vbi.lifetime")?;
    let lifetime = lifetime_input::load(&file).map_err(input_error)?;
    let analysis = lifetime_input::prepare(&file, &lifetime).map_err(input_error)?;
    let reader = TrafficFileReader::open(&lifetime.traffic_file, lifetime.traffic_format)
        .map_err(|e| input_error(e.at_naming_key(&file, "lifetime.traffic_file")))?;
    let traffic_file = lifetime.traffic_file.display().to_string();
    let Run {
        rows,
        counts,
        tally,
    } = py
        .detach(|| run(&analysis, reader))
        .map_err(|failure| match failure {
            Failure::Line(error) => input_error(error),
            // A truck the analysis refuses (a lane it does not have, out of order): the traffic
            // file is at fault, as `vbi lifetime` (exit 2) and `vbi check` say.
            Failure::Truck(error) => input_error(InputError {
                file: traffic_file.clone(),
                location: None,
                field: None,
                message: error.to_string(),
            }),
        })?;

    let parts = PyDict::new(py);
    let column = |f: fn(&BlockMaximum) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
    parts.set_item(
        "effect",
        rows.iter()
            .map(|r| r.effect as u64)
            .collect::<Vec<u64>>()
            .into_pyarray(py),
    )?;
    parts.set_item(
        "block",
        rows.iter()
            .map(|r| r.block)
            .collect::<Vec<u64>>()
            .into_pyarray(py),
    )?;
    parts.set_item("static", column(|r| r.value).into_pyarray(py))?;
    parts.set_item("time_s", column(|r| r.time).into_pyarray(py))?;
    parts.set_item(
        "trucks",
        rows.iter()
            .map(|r| r.trucks as u64)
            .collect::<Vec<u64>>()
            .into_pyarray(py),
    )?;
    let effects = PyList::empty(py);
    for effect in &analysis.effects {
        effects.append((effect.station.as_str(), effect.quantity.name()))?;
    }
    parts.set_item("effects", effects)?;

    // lifetime.json, as `vbi lifetime` writes it (one summary for both).
    let summary = lifetime_input::summary(&lifetime, &analysis, counts, &tally);
    let json = serde_json::to_string(&summary).map_err(|e| crate::errors::library_error(&e))?;
    let summary = py.import("json")?.call_method1("loads", (json,))?;
    parts.set_item("summary", summary)?;
    Ok(parts)
}
