//! One module per subcommand: its arguments and its `run`.

pub mod analytic;
pub mod check;
pub mod measure;
pub mod modes;
pub mod road;
pub mod vehicle;
