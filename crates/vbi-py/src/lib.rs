//! The Python package `vbi` (its native module `vbi._vbi`): the library pipeline of
//! `vbi::crossing` bound with pyo3, inputs read by `vbi-input` exactly as the `vbi` command
//! reads them, arrays as numpy arrays, the GIL released while Rust computes.
//!
//! ```text
//! Bridge / Vehicle / Road (preset, TOML file or dict)   Scenario (file, dict, built-in)
//!        |                                                   |
//!      modes(bridge, n) -> PreparedBridge <- prepare(scenario)
//!                                 |                          |
//!                                 +------- run(scenario, bridge=...) -> RunResult
//! study(file or dict, shard=...) -> the case table of `vbi study`
//! measure(file or dict) -> the numbers of `measure.json` and the signals behind them
//! ```
//!
//! Each function of the package is one `#[pyfunction]` in its own module, registered below.

mod arrays;
mod bridge_modes;
mod errors;
mod extreme_value;
mod fatigue;
mod lifetime;
mod measure;
mod output_tables;
mod parts;
mod run;
mod scenario;
mod source;
mod study;

use pyo3::prelude::*;

/// mimalloc for the extension's own allocations, as for the `vbi` binary: a crossing allocates
/// and frees megabytes of history, which glibc's allocator returns to the system each time
/// (page faults cost about 10 % of a study). Python's objects keep Python's allocator.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The native module; `vbi/__init__.py` re-exports it.
#[pymodule]
fn _vbi(module: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(module)?;
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    module.add_class::<parts::Bridge>()?;
    module.add_class::<parts::Vehicle>()?;
    module.add_class::<parts::Road>()?;
    module.add_class::<scenario::Scenario>()?;
    module.add_class::<bridge_modes::PreparedBridge>()?;
    module.add_class::<run::RunResult>()?;
    module.add_class::<run::StationDaf>()?;
    module.add_class::<fatigue::DetailFatigue>()?;
    module.add_function(wrap_pyfunction!(fatigue::fatigue_outputs, module)?)?;
    module.add_function(wrap_pyfunction!(fatigue::rainflow, module)?)?;
    module.add_function(wrap_pyfunction!(fatigue::count_cycles, module)?)?;
    module.add_function(wrap_pyfunction!(parts::vehicle_presets, module)?)?;
    module.add_function(wrap_pyfunction!(bridge_modes::modes, module)?)?;
    module.add_function(wrap_pyfunction!(bridge_modes::prepare, module)?)?;
    module.add_function(wrap_pyfunction!(run::run, module)?)?;
    module.add_function(wrap_pyfunction!(run::station_outputs, module)?)?;
    module.add_function(wrap_pyfunction!(study::study_cells, module)?)?;
    module.add_function(wrap_pyfunction!(study::study_case_count, module)?)?;
    module.add_function(wrap_pyfunction!(measure::measure_parts, module)?)?;
    module.add_function(wrap_pyfunction!(lifetime::lifetime_parts, module)?)?;
    module.add_function(wrap_pyfunction!(lifetime::lifetime_merge_parts, module)?)?;
    module.add_function(wrap_pyfunction!(lifetime::lifetime_fatigue_parts, module)?)?;
    module.add_function(wrap_pyfunction!(extreme_value::fit_extreme_value, module)?)?;
    module.add_function(wrap_pyfunction!(
        extreme_value::fit_block_maxima_parts,
        module
    )?)?;
    Ok(())
}
