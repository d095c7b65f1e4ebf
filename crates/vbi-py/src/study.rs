//! `vbi.study(...)`: a `[study]` file's cases (or one shard of them) run in parallel, one
//! bridge analysis per bridge group, the cases computed in batches by the library's
//! [`vbi::study::case_records_with`] (as `vbi study` does) and tabled by its row functions: the same records and the same
//! cells as `vbi study` writes to `cases.csv`, `daf_by_modes.csv` and `participation.csv`.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;

use vbi::crossing::{integration_batches, prepare_scenario_bridge, Scenario};
use vbi::study::record::{
    case_table_header, case_table_row, per_case_header, DESIGN_CODE_COLUMNS, MODE_COLUMNS,
    PARTICIPATION_COLUMNS,
};
use vbi::study::{case_records_with, CaseRecord, Shard, STUDY_BATCH_SIZE};
use vbi_input::study::{self as study_input, Study};
use vbi_input::InputError;

use crate::errors::{input_error, library_error};
use crate::source;

/// An error about an argument of `vbi.study`.
fn argument_error(argument: &str, message: String) -> PyErr {
    input_error(InputError {
        file: "<argument>".into(),
        location: None,
        field: Some(argument.into()),
        message,
    })
}

fn load(source: &Bound<'_, PyAny>) -> PyResult<Study> {
    let file = source::of_kind(source, "study", "vbi.study")?;
    study_input::load(&file).map_err(input_error)
}

/// The records of the cases `own` (indices into the study's cases), in case order.
fn run_cases(study: &Study, own: &[usize], threads: Option<usize>) -> PyResult<Vec<CaseRecord>> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| library_error(&e))?;
    let groups = study.bridge_groups(own);
    let mut records: Vec<(usize, CaseRecord)> = pool.install(|| {
        groups
            .par_iter()
            .flat_map(|(_, cases)| {
                let bridge = prepare_scenario_bridge(&study.scenarios[cases[0]]);
                let scenarios: Vec<&Scenario> =
                    cases.iter().map(|&i| &study.scenarios[i]).collect();
                integration_batches(&scenarios, STUDY_BATCH_SIZE)
                    .par_iter()
                    .map(|batch| {
                        let batch_cases: Vec<(&str, &Scenario)> = batch
                            .iter()
                            .map(|&b| (study.cases[cases[b]].id.as_str(), scenarios[b]))
                            .collect();
                        let records = case_records_with(&batch_cases, &bridge, &[]);
                        batch
                            .iter()
                            .map(|&b| cases[b])
                            .zip(records)
                            .collect::<Vec<_>>()
                    })
                    .flatten_iter()
                    .collect::<Vec<_>>()
            })
            .collect()
    });
    records.sort_by_key(|(i, _)| *i);
    Ok(records.into_iter().map(|(_, r)| r).collect())
}

/// A table as `{"columns": [...], "rows": [[cell, ...], ...]}`, cells as the CSV holds them.
fn table<'py>(
    py: Python<'py>,
    columns: Vec<String>,
    rows: Vec<Vec<String>>,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("columns", columns)?;
    dict.set_item("rows", rows)?;
    Ok(dict)
}

/// The tables of a study, or of shard `I/N` of it, as `vbi study` writes them: `cases`,
/// `daf_by_modes`, `participation` and `design_codes`, each `{"columns": [...], "rows": [[str, ...]]}` with the
/// CSV's cells (numbers in their shortest exact text, empty where undefined). `source` is a
/// `[study]` TOML file or a dict of its document; `threads` defaults to one per core. The GIL
/// is released while the cases run.
#[pyfunction]
#[pyo3(signature = (source, *, shard = None, threads = None))]
pub fn study_cells<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    shard: Option<&str>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let study = load(source)?;
    let shard = match shard {
        Some(text) => text
            .parse::<Shard>()
            .map_err(|e| argument_error("shard", e.to_string()))?,
        None => Shard::WHOLE,
    };
    if threads == Some(0) {
        return Err(argument_error(
            "threads",
            "0 is not allowed; expected at least 1".into(),
        ));
    }
    let own: Vec<usize> = shard.range(study.cases.len()).collect();
    let records = py.detach(|| run_cases(&study, &own, threads))?;
    let mut case_rows = Vec::new();
    let (mut mode_rows, mut participation_rows) = (Vec::new(), Vec::new());
    let mut code_rows = Vec::new();
    for (&i, record) in own.iter().zip(&records) {
        let case = &study.cases[i];
        let parameters = study.parameter_cells(i);
        case_rows.push(case_table_row(record, &parameters, case.sample, case.seed));
        mode_rows.extend(record.mode_table_rows());
        participation_rows.extend(record.participation_table_rows());
        code_rows.extend(record.design_code_rows());
    }
    let tables = PyDict::new(py);
    tables.set_item("name", &study.name)?;
    tables.set_item(
        "cases",
        table(py, case_table_header(&study.fields), case_rows)?,
    )?;
    tables.set_item(
        "daf_by_modes",
        table(py, per_case_header(&MODE_COLUMNS), mode_rows)?,
    )?;
    tables.set_item(
        "participation",
        table(
            py,
            per_case_header(&PARTICIPATION_COLUMNS),
            participation_rows,
        )?,
    )?;
    tables.set_item(
        "design_codes",
        table(py, per_case_header(&DESIGN_CODE_COLUMNS), code_rows)?,
    )?;
    Ok(tables)
}

/// The number of cases of a study (to split it into shards).
#[pyfunction]
pub fn study_case_count(source: &Bound<'_, PyAny>) -> PyResult<usize> {
    Ok(load(source)?.cases.len())
}
