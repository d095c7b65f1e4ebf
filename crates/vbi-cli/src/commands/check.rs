//! `vbi check FILE`: validate any input file.

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
        println!("{}: ok ({kind})", path.display());
    }
    Ok(())
}
