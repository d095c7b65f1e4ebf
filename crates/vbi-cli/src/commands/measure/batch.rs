//! `vbi measure RUN1.toml RUN2.toml … --out DIR`: the runs of one load test (passes, speeds,
//! lanes) in one command, in the order given. Each run's `measure.json` and figures go to
//! `DIR/<stem>/` (the file's stem, made unique: `pass`, `pass_2`, …); over them all,
//! `DIR/measurements.csv` (one row per run and DAF channel, [`super::rows`]),
//! `DIR/measurements.json` (every run's `measure.json` and the same table as records) and
//! `DIR/report.html` ([`super::report`]).
//!
//! The runs have all been read, checked and processed before this module writes anything
//! ([`super::run`]).

use std::path::Path;
use vbi::units::metres_per_second_to_kmh;

use anyhow::Result;
use serde::Serialize;
use vbi::measure::{
    weighing_accuracy, Environment, MeasurementResult, TestConditions, WeighingAccuracy,
};

use super::one_run::{run_stem, write_run, LoadedRun, Report};
use super::report::{self, ReportRun};
use super::rows::{cells, rows, Row, HEADER};
use crate::commands::OutputFormat;
use crate::console::outln;
use crate::output;

/// The names of the runs: each file's stem; a stem that an earlier run has gets `_2`, `_3`, …,
/// the first of them that no run has (a run keeps its own stem when no other run has it).
pub(super) fn unique_stems(paths: &[&Path]) -> Vec<String> {
    let own: Vec<String> = paths.iter().map(|p| run_stem(p)).collect();
    let mut names: Vec<String> = Vec::with_capacity(own.len());
    for stem in &own {
        let mut name = stem.clone();
        let mut k = 2;
        while names.contains(&name) || (name != *stem && own.contains(&name)) {
            name = format!("{stem}_{k}");
            k += 1;
        }
        names.push(name);
    }
    names
}

/// One run in `measurements.json`.
#[derive(Serialize)]
struct BatchRun<'a> {
    run: &'a str,
    input: String,
    /// Its folder under `--out`.
    directory: &'a str,
    /// Its `measure.json`.
    measure: &'a Report<'a>,
}

/// `measurements.json`.
#[derive(Serialize)]
struct Batch<'a> {
    vbi_version: &'static str,
    runs: Vec<BatchRun<'a>>,
    /// `measurements.csv` as records.
    table: &'a [Row],
    /// The COST 323 classes of the runs weighed against given axle loads (two or more).
    weighing_accuracy: Option<WeighingAccuracy>,
}

/// The test conditions of a load test's runs: one or a few vehicles at several speeds and
/// positions (COST 323's extended repeatability, r2), in an excellent environment (I).
const LOAD_TEST_CONDITIONS: (TestConditions, Environment) = (
    TestConditions::ExtendedRepeatability,
    Environment::Excellent,
);

/// The COST 323 classes of the weighings against given loads, with two or more.
fn accuracy_of(results: &[MeasurementResult]) -> Option<WeighingAccuracy> {
    let weighed: Vec<&vbi::measure::VehicleWeighing> = results
        .iter()
        .filter_map(|r| r.summary.weighing.as_ref())
        .filter(|w| w.against_given.is_some())
        .collect();
    (weighed.len() >= 2).then(|| {
        let (conditions, environment) = LOAD_TEST_CONDITIONS;
        weighing_accuracy(&weighed, conditions, environment)
    })
}

/// The classes, one line per criterion.
fn print_accuracy(a: &WeighingAccuracy) {
    let class = match (&a.class, a.too_few.is_empty()) {
        (Some(class), _) => class.clone(),
        (None, false) => format!(
            "not classed: fewer than {} results of {}",
            vbi::measure::MINIMUM_RESULTS,
            a.too_few
                .iter()
                .map(|c| c.name())
                .collect::<Vec<_>>()
                .join(", ")
        ),
        (None, true) => "no class (a criterion reaches none up to E(100))".to_string(),
    };
    outln!(
        "weighing accuracy (COST 323, {} weighings against the given loads; extended repeatability r2, environment I): {class}",
        a.weighings
    );
    for c in &a.criteria {
        outln!(
            "  {:<16} {:>6}  n {:>3}, mean {:+.2} %, std {:.2} %, pi {:.1} % >= pi0 {:.1} % at ±{:.0} %",
            c.criterion.name(),
            c.class,
            c.count,
            c.mean_percent,
            c.std_percent,
            100.0 * c.confidence,
            100.0 * c.minimum_confidence,
            c.tolerance_percent
        );
    }
}

/// Writes the runs' folders, `measurements.csv`, `measurements.json` and `report.html`, and
/// prints the table (or `measurements.json`).
pub(super) fn write_outputs(
    out: &Path,
    format: OutputFormat,
    runs: &[LoadedRun],
    results: &[MeasurementResult],
) -> Result<()> {
    let _lock = output::lock_output_dir(out)?;
    let paths: Vec<&Path> = runs.iter().map(|r| r.file.path.as_path()).collect();
    let stems = unique_stems(&paths);
    let mut reports = Vec::with_capacity(runs.len());
    let mut table = Vec::new();
    let mut per_run_rows = Vec::with_capacity(runs.len());
    for ((run, result), stem) in runs.iter().zip(results).zip(&stems) {
        let dir = out.join(stem);
        output::create_output_dir(&dir)?;
        reports.push(write_run(run, result, &dir)?);
        let rows = rows(stem, &run.file.name(), &result.summary);
        table.extend(rows.iter().cloned());
        per_run_rows.push(rows);
    }
    let csv_path = out.join("measurements.csv");
    let records: Vec<Vec<String>> = table.iter().map(cells).collect();
    output::write_csv(&csv_path, &HEADER, &records)?;
    let batch = Batch {
        vbi_version: env!("CARGO_PKG_VERSION"),
        runs: runs
            .iter()
            .zip(&stems)
            .zip(&reports)
            .map(|((run, stem), report)| BatchRun {
                run: stem,
                input: run.file.name(),
                directory: stem,
                measure: report,
            })
            .collect(),
        table: &table,
        weighing_accuracy: accuracy_of(results),
    };
    let json_path = out.join("measurements.json");
    output::write_json(&json_path, &batch)?;
    let inputs: Vec<String> = runs.iter().map(|r| r.file.name()).collect();
    let dirs: Vec<std::path::PathBuf> = stems.iter().map(|s| out.join(s)).collect();
    let report_runs: Vec<ReportRun> = (0..runs.len())
        .map(|i| ReportRun {
            stem: &stems[i],
            input: &inputs[i],
            dir: &dirs[i],
            directory_label: Some(&stems[i]),
            figures: &reports[i].figures,
            result: &results[i],
            rows: &per_run_rows[i],
        })
        .collect();
    let html_path = out.join("report.html");
    report::write(&report_runs, &html_path)?;
    match format {
        OutputFormat::Json => outln!("{}", serde_json::to_string_pretty(&batch)?),
        OutputFormat::Table => {
            print_table(&table);
            if let Some(a) = &batch.weighing_accuracy {
                print_accuracy(a);
            }
            for dir in &dirs {
                outln!("wrote {}", dir.join("measure.json").display());
            }
            for path in [&csv_path, &json_path, &html_path] {
                outln!("wrote {}", path.display());
            }
        }
    }
    Ok(())
}

/// One line per run and channel: run, speed, channel, static method, DAF, DAF at K1 and the
/// run's separation verdict.
fn print_table(table: &[Row]) {
    outln!(
        "{:<20} {:>12} {:<20} {:<14} {:>8} {:>10} {:>9}",
        "run",
        "speed [km/h]",
        "channel",
        "static part",
        "DAF",
        "DAF at K1",
        "separated"
    );
    for r in table {
        let speed = r.speed_m_s.map_or("-".to_string(), |v| {
            format!("{:.1}", metres_per_second_to_kmh(v))
        });
        let at_k1 = r.daf_at_k1.map_or("-".to_string(), |d| format!("{d:.4}"));
        let separated = match r.separated {
            Some(true) => "yes",
            Some(false) => "no",
            None => "-",
        };
        outln!(
            "{:<20} {:>12} {:<20} {:<14} {:>8.4} {:>10} {:>9}",
            r.run,
            speed,
            r.channel,
            r.static_method,
            r.daf,
            at_k1,
            separated
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_that_share_a_stem_get_unique_names_in_the_order_given() {
        let paths = [
            Path::new("a/pass.toml"),
            Path::new("b/pass.toml"),
            Path::new("pass_2.toml"),
            Path::new("c/pass.toml"),
            Path::new("x y.toml"),
        ];
        assert_eq!(
            unique_stems(&paths),
            ["pass", "pass_3", "pass_2", "pass_4", "x_y"]
        );
    }
}
