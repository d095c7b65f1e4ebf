//! `vbi check FILE`: validate any input file, and with `--deep` do the command's work without
//! writing anything.
//!
//! `vbi check` decides everything that can be decided without the numbers, with the message
//! and at the key of the command that reads the file; for a measurement that includes the
//! crossing window and the baseline windows of the record (the library's
//! [`check_preparation`](vbi::measure::check_preparation)). `--deep` decides the rest (issue 47),
//! which needs the modes or the record's spectra: a scenario's modal analysis with its re-run
//! mode counts and its crossing, a bridge's modal analysis, a measurement's whole processing.
//! It takes the time of the command, and writes nothing.

use crate::console::outln;
use std::path::PathBuf;

use anyhow::Result;
use vbi::crossing::ScenarioBridgeError;

use crate::input::SourceFile;
use crate::inputs;

/// Arguments of `vbi check`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input files to validate (TOML).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,

    /// Also do the command's work, writing nothing: the modal analysis and crossing of a
    /// scenario, the modal analysis of a bridge, the whole processing of a measurement. What
    /// needs the modes or the spectra (a re-run mode count above the modes kept, a crawl
    /// reference without an identified frequency) is decided only then. A study's, road's or
    /// vehicle's file has nothing more to check.
    #[arg(long)]
    pub deep: bool,
}

/// The modes of a bridge file's deep check: `vbi modes`'s default.
const DEEP_BRIDGE_MODES: usize = 50;

/// Validates each file; the first bad one is an error (exit 2).
pub fn run(args: &Args) -> Result<()> {
    for path in &args.files {
        let file = SourceFile::read(path)?;
        let kind = inputs::kind_of(&file)?;
        if kind == "measurement" {
            check_measurement(&file, args.deep)?;
        } else {
            inputs::validate(&file)?;
            if args.deep {
                deep_check(&file, kind)?;
            }
        }
        let depth = if args.deep { ", deep" } else { "" };
        outln!("{}: ok ({kind}{depth})", path.display());
        for warning in model_warnings(&file, kind) {
            eprintln!("{}: warning: {warning}", path.display());
        }
    }
    Ok(())
}

/// A measurement file read, its record's preparation checked, and with `deep` processed.
fn check_measurement(file: &SourceFile, deep: bool) -> Result<()> {
    let loaded = inputs::measurement::load(file)?;
    let m = &loaded.measurement;
    vbi::measure::check_preparation(m).map_err(|e| crate::commands::measure::located(file, e))?;
    if deep {
        vbi::measure::measure(m).map_err(|e| crate::commands::measure::located(file, e))?;
    }
    Ok(())
}

/// The modal analysis (and crossing) of a scenario or a bridge, located as the command
/// locates it.
fn deep_check(file: &SourceFile, kind: &str) -> Result<()> {
    match kind {
        "scenario" => {
            let loaded = inputs::scenario::load(file)?;
            let scenario = &loaded.scenario;
            let located = |e: &vbi::crossing::PipelineError| {
                inputs::scenario::locate_failure(file, scenario, e)
            };
            let bridge =
                vbi::crossing::prepare_scenario_bridge(scenario).map_err(|e| match &e {
                    ScenarioBridgeError::Prepare { source, .. }
                    | ScenarioBridgeError::RerunModeCounts { source, .. } => located(source),
                })?;
            vbi::crossing::run_crossing(&bridge, scenario).map_err(|e| located(&e))?;
        }
        // `vbi modes` at its default mode count; an imported modal basis has no analysis.
        "bridge" if inputs::bridge::load_imported(file)?.is_none() => {
            let model = inputs::bridge::load(file)?;
            let name = file.name();
            crate::commands::modes::solve(&model, DEEP_BRIDGE_MODES, &name, Some(file))?;
        }
        _ => {}
    }
    Ok(())
}

/// The plausibility warnings that a file's bridge allows before any solve
/// (`vbi::crossing::plausibility::model_warning`): a bridge file or a scenario's bridge.
fn model_warnings(file: &SourceFile, kind: &str) -> Vec<vbi::solver::SolverWarning> {
    let model = match kind {
        "bridge" => inputs::bridge::load(file).ok(),
        "scenario" => inputs::scenario::load(file)
            .ok()
            .map(|loaded| loaded.scenario.bridge.model),
        _ => None,
    };
    model
        .and_then(|model| vbi::crossing::plausibility::model_warning(&model))
        .into_iter()
        .collect()
}
