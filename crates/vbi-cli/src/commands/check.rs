//! `vbi check FILE`: validate any input file.

use crate::console::outln;
use std::path::PathBuf;

use anyhow::Result;

use crate::input::SourceFile;
use crate::inputs;

/// Arguments of `vbi check`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input files to validate (TOML).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
}

/// Validates each file; the first bad one is an error (exit 2).
pub fn run(args: &Args) -> Result<()> {
    for path in &args.files {
        let file = SourceFile::read(path)?;
        let kind = inputs::validate(&file)?;
        outln!("{}: ok ({kind})", path.display());
        for warning in model_warnings(&file, kind) {
            eprintln!("{}: warning: {warning}", path.display());
        }
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
