//! `vbi report`. Placeholder until its issue lands.

use anyhow::{bail, Result};

/// Arguments of `vbi report`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<()> {
    bail!("`vbi report` is not implemented yet")
}
