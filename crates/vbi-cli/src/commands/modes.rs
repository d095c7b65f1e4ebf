//! `vbi modes`. Placeholder until its issue lands.

use anyhow::{bail, Result};

/// Arguments of `vbi modes`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<()> {
    bail!("`vbi modes` is not implemented yet")
}
