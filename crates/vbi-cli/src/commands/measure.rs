//! `vbi measure`. Placeholder until its issue lands.

use anyhow::{bail, Result};

/// Arguments of `vbi measure`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<()> {
    bail!("`vbi measure` is not implemented yet")
}
