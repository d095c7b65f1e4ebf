//! `vbi analytic`. Placeholder until its issue lands.

use anyhow::{bail, Result};

/// Arguments of `vbi analytic`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<()> {
    bail!("`vbi analytic` is not implemented yet")
}
