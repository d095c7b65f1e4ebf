//! `vbi measure RUN1.toml RUN2.toml … --out DIR`: the runs of one load test (passes, speeds,
//! lanes) in one command, in the order given. Each run's `measure.json` and figures go to
//! `DIR/<stem>/` (the file's stem, made unique: `pass`, `pass_2`, …); over them all,
//! `DIR/measurements.csv` (one row per run and DAF channel, [`HEADER`]),
//! `DIR/measurements.json` (every run's `measure.json` and the same table as records) and
//! `DIR/report.html` ([`crate::measure_report`]).
//!
//! The runs have all been read, checked and processed before this module writes anything
//! ([`crate::commands::measure::run`]).

use std::path::Path;

use anyhow::Result;
use serde::Serialize;
use vbi::measure::{MeasurementResult, MeasurementSummary};

use crate::commands::measure::{run_stem, write_run, Args, LoadedRun, Report};
use crate::commands::OutputFormat;
use crate::console::outln;
use crate::measure_report::{self, ReportRun};
use crate::output;

/// One row of `measurements.csv`: a DAF channel of a run.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Row {
    /// The run's name (its folder under `--out` for several runs).
    pub(crate) run: String,
    /// The measurement file as given.
    pub(crate) input: String,
    /// The run's description.
    pub(crate) description: Option<String>,
    /// Vehicle speed [m/s].
    pub(crate) speed_m_s: Option<f64>,
    /// Channel name.
    pub(crate) channel: String,
    /// What it records (deflection, strain, bending_moment).
    pub(crate) kind: String,
    /// Unit of `static_max` and `dynamic_max`.
    pub(crate) unit: String,
    /// How its static part was found: low_pass, influence_line, crawl_run.
    pub(crate) static_method: String,
    /// The static low-pass cut-off [Hz] (low_pass).
    pub(crate) cutoff_hz: Option<f64>,
    /// The run's static-separation verdict (when a channel uses the low-pass).
    pub(crate) separated: Option<bool>,
    /// The channel's own separation check (low-pass, span and speed known).
    pub(crate) channel_separated: Option<bool>,
    /// Static maximum, in `unit`.
    pub(crate) static_max: f64,
    /// Measured maximum in the same direction, in `unit`.
    pub(crate) dynamic_max: f64,
    /// dynamic_max / static_max.
    pub(crate) daf: f64,
    /// Frequency of the cut-off mode K1 [Hz].
    pub(crate) k1_hz: Option<f64>,
    /// DAF after the low-pass just above K1.
    pub(crate) daf_at_k1: Option<f64>,
    /// (daf_at_k1 − daf) / daf.
    pub(crate) k1_relative_change: Option<f64>,
    /// Section label.
    pub(crate) section: Option<String>,
    /// RDM of the section (DAF of deflection / DAF of moment), when it has both.
    pub(crate) rdm: Option<f64>,
    /// The first identified frequency of the run [Hz].
    pub(crate) first_frequency_hz: Option<f64>,
}

/// The columns of `measurements.csv`, in the order of [`Row`]'s fields.
pub(crate) const HEADER: [&str; 20] = [
    "run",
    "input",
    "description",
    "speed_m_s",
    "channel",
    "kind",
    "unit",
    "static_method",
    "cutoff_hz",
    "separated",
    "channel_separated",
    "static_max",
    "dynamic_max",
    "daf",
    "k1_hz",
    "daf_at_k1",
    "k1_relative_change",
    "section",
    "rdm",
    "first_frequency_hz",
];

/// A channel kind as `measure.json` writes it (`bending_moment`).
fn kind_name<T: Serialize + std::fmt::Debug>(kind: &T) -> String {
    match serde_json::to_value(kind) {
        Ok(serde_json::Value::String(s)) => s,
        _ => format!("{kind:?}").to_lowercase(),
    }
}

/// The rows of one run: one per DAF channel, in channel order.
pub(crate) fn rows(run: &str, input: &str, s: &MeasurementSummary) -> Vec<Row> {
    let separated = s.static_separation.as_ref().map(|x| x.cutoff.separated);
    let first_frequency_hz = s.identified_frequencies.first().map(|p| p.frequency_hz);
    s.channels
        .iter()
        .map(|c| {
            let rdm = c
                .section
                .as_ref()
                .and_then(|section| s.rdm.iter().find(|r| &r.section == section))
                .map(|r| r.rdm);
            Row {
                run: run.to_string(),
                input: input.to_string(),
                description: s.description.clone(),
                speed_m_s: s.speed_m_s,
                channel: c.name.clone(),
                kind: kind_name(&c.kind),
                unit: c.unit.clone(),
                static_method: c.static_method.to_string(),
                cutoff_hz: c.cutoff_hz,
                separated,
                channel_separated: c.separation_check.as_ref().map(|x| x.separated),
                static_max: c.static_max,
                dynamic_max: c.dynamic_max,
                daf: c.daf,
                k1_hz: c.cutoff_mode.as_ref().map(|k| k.mode_frequency_hz),
                daf_at_k1: c.cutoff_mode.as_ref().map(|k| k.daf_after),
                k1_relative_change: c.cutoff_mode.as_ref().map(|k| k.relative_change),
                section: c.section.clone(),
                rdm,
                first_frequency_hz,
            }
        })
        .collect()
}

/// A row's CSV cells: numbers in full precision (Rust's shortest round-trip form), an empty
/// cell for a missing value.
fn cells(r: &Row) -> Vec<String> {
    let num = |x: Option<f64>| x.map_or(String::new(), output::number);
    let flag = |x: Option<bool>| x.map_or(String::new(), |b| b.to_string());
    let text = |x: &Option<String>| x.clone().unwrap_or_default();
    vec![
        r.run.clone(),
        r.input.clone(),
        text(&r.description),
        num(r.speed_m_s),
        r.channel.clone(),
        r.kind.clone(),
        r.unit.clone(),
        r.static_method.clone(),
        num(r.cutoff_hz),
        flag(r.separated),
        flag(r.channel_separated),
        output::number(r.static_max),
        output::number(r.dynamic_max),
        output::number(r.daf),
        num(r.k1_hz),
        num(r.daf_at_k1),
        num(r.k1_relative_change),
        text(&r.section),
        num(r.rdm),
        num(r.first_frequency_hz),
    ]
}

/// The names of the runs: each file's stem; a stem that an earlier run has gets `_2`, `_3`, …,
/// the first of them that no run has (a run keeps its own stem when no other run has it).
pub(crate) fn unique_stems(paths: &[&Path]) -> Vec<String> {
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
}

/// Writes the runs' folders, `measurements.csv`, `measurements.json` and `report.html`, and
/// prints the table (or `measurements.json`).
pub(crate) fn run(args: &Args, runs: &[LoadedRun], results: &[MeasurementResult]) -> Result<()> {
    let out = &args.out;
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
    measure_report::write(&report_runs, &html_path)?;
    match args.format {
        OutputFormat::Json => outln!("{}", serde_json::to_string_pretty(&batch)?),
        OutputFormat::Table => {
            print_table(&table);
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
        let speed = r
            .speed_m_s
            .map_or("-".to_string(), |v| format!("{:.1}", v * 3.6));
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

    #[test]
    fn the_header_has_one_column_per_cell() {
        let row = Row {
            run: "r".into(),
            input: "r.toml".into(),
            description: None,
            speed_m_s: Some(16.666666666666668),
            channel: "u".into(),
            kind: kind_name(&vbi::signal::MeasuredQuantity::BendingMoment),
            unit: "mm".into(),
            static_method: "low_pass".into(),
            cutoff_hz: None,
            separated: Some(false),
            channel_separated: None,
            static_max: -2.5,
            dynamic_max: -2.75,
            daf: 1.1,
            k1_hz: None,
            daf_at_k1: None,
            k1_relative_change: None,
            section: None,
            rdm: None,
            first_frequency_hz: None,
        };
        let c = cells(&row);
        assert_eq!(c.len(), HEADER.len());
        assert_eq!(c[3], "16.666666666666668");
        assert_eq!(c[5], "bending_moment");
        assert_eq!((c[8].as_str(), c[9].as_str()), ("", "false"));
    }
}
