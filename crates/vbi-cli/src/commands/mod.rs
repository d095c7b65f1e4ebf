//! One module per subcommand: its arguments and its `run`.

pub mod analytic;
pub mod check;
pub mod lifetime;
pub mod measure;
pub mod modes;
pub mod report;
pub mod road;
pub mod run;
pub mod study;
pub mod vehicle;

/// How a command prints its result on stdout: `--format table|json` of `vbi modes`, `run`,
/// `analytic`, `measure`, `vehicle list` and `vehicle show` (one choice, so one enum).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum OutputFormat {
    /// A human-readable table.
    Table,
    /// JSON for scripts.
    Json,
}
