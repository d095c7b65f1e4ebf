//! `vbi vehicle`. Placeholder until its issue lands.

use anyhow::{bail, Result};

/// Subcommands of `vbi vehicle`.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// List the presets.
    List,
}

/// Runs the command.
pub fn run(_command: &Command) -> Result<()> {
    bail!("`vbi vehicle` is not implemented yet")
}
