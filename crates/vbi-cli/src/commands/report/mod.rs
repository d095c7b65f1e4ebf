//! `vbi report DIR [--out FILE]`: a self-contained HTML report of a `vbi study` output directory
//! ([`study`]), of a `vbi run --out` directory ([`run`]) or of a `vbi lifetime --out` directory
//! ([`lifetime`]). Default output: `DIR/report.html`.
//! Both open with a key-results box and a table of contents ([`page`]).

use std::path::PathBuf;

use anyhow::{bail, Result};

use crate::console::outln;
use crate::output::write_atomic;
use crate::study_records::read_manifest;

pub mod lifetime;
pub mod page;
pub mod run;
pub mod study;

/// Arguments of `vbi report`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// A `vbi study` output directory (or a merged one), a `vbi run --out` directory, or a
    /// `vbi lifetime --out` directory (or a merge of its shards).
    pub dir: PathBuf,
    /// The HTML file to write (default: DIR/report.html).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    let dir = &args.dir;
    let html = if let Some(manifest) = read_manifest(dir)? {
        study::report(dir, &manifest)?
    } else if dir.join("summary.json").is_file() {
        run::report(dir)?
    } else if dir.join("lifetime.json").is_file() {
        lifetime::report(dir)?
    } else {
        bail!(
            "{} is neither a study output directory (no study.json), a `vbi run --out` \
             directory (no summary.json) nor a `vbi lifetime --out` directory (no lifetime.json)",
            dir.display()
        );
    };
    let out = args.out.clone().unwrap_or_else(|| dir.join("report.html"));
    write_atomic(&out, html.as_bytes())?;
    outln!("report written to {}", out.display());
    Ok(())
}
