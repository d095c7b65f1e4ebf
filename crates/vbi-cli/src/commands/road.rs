//! `vbi road`. Placeholder until its issue lands.

use anyhow::{bail, Result};

/// Arguments of `vbi road`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<()> {
    bail!("`vbi road` is not implemented yet")
}
