//! `vbi measure FILE.toml [FILE2.toml …] [--out DIR] [--format json|table]`: DAF from measured
//! signals, natural frequencies and damping from acceleration spectra, low-pass filtering at the
//! cut-off mode K1, and model updating (the paper's §6).
//!
//! The processing is the library's measurement stage (`vbi::crossing::measure`); this command
//! reads each file through `vbi-input` and writes, for one file, `DIR/measure.json` and figures
//! (PNG + SVG): `signal_<channel>` (raw, static and K1-filtered signals) and
//! `spectrum_<channel>` (Welch PSD with the picked peaks), and `DIR/report.html`. Several files
//! are the runs of one load test: a folder per run and one table and report over them all.
//!
//! Every file is read and checked before any is processed, and every run is processed before
//! anything is written: a bad file or a failing run writes nothing.
//!
//! This module holds the arguments and the dispatch; its files depend one way: [`one_run`]
//! (read, check and process a file, write its `measure.json` and [`figures`], and the one-file
//! outputs) and [`batch`] (several files, each run written through [`one_run`]) both write
//! `report.html` with [`report`], and all of them read the table of DAF channels from [`rows`].

use std::path::PathBuf;

use anyhow::Result;
use vbi::measure::MeasurementResult;

use crate::commands::OutputFormat;

mod batch;
mod figures;
mod one_run;

pub(crate) use one_run::located;
mod report;
mod rows;

/// Arguments of `vbi measure`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The measurement descriptions (TOML with a [measurement] table): one run, or several runs
    /// of one load test (passes, speeds, lanes), processed in the order given.
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<PathBuf>,
    /// Output directory: measure.json, the figures and report.html of one run; with several
    /// runs, a folder per run (named by the file's stem) and measurements.csv,
    /// measurements.json and report.html over them all.
    #[arg(long, default_value = "measure_out")]
    pub out: PathBuf,
    /// What to print on standard output (json: the same JSON as measure.json, or as
    /// measurements.json for several runs).
    #[arg(long, value_enum, default_value_t = OutputFormat::Table)]
    pub format: OutputFormat,
}

/// Runs the command: every file read and checked, then every run processed, then the outputs
/// written.
pub fn run(args: &Args) -> Result<()> {
    let runs: Vec<one_run::LoadedRun> = args
        .files
        .iter()
        .map(|path| one_run::load_run(path))
        .collect::<Result<_>>()?;
    let results: Vec<MeasurementResult> =
        runs.iter().map(one_run::process).collect::<Result<_>>()?;
    match (runs.as_slice(), results.as_slice()) {
        ([run], [result]) => one_run::write_outputs(&args.out, args.format, run, result),
        _ => batch::write_outputs(&args.out, args.format, &runs, &results),
    }
}
