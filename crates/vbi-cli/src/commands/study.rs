//! `vbi study`. Placeholder until its issue lands.

use anyhow::{bail, Result};

/// Arguments of `vbi study`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<()> {
    bail!("`vbi study` is not implemented yet")
}
