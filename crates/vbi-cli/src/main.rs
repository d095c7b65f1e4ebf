//! `vbi`: vehicle–bridge interaction dynamics from the command line.
//!
//! `main` owns the exit codes: 0 success, 2 bad input, usage or I/O error (the message names the
//! file, line, field and what is allowed). A panic is a bug.

mod bridge_summary;
mod commands;
mod console;
mod design_codes;
mod export_matrices;
#[allow(dead_code)]
mod output;
mod parquet_table;
#[allow(dead_code)]
mod plot;
mod progress;
mod study_assessment;
mod study_records;

/// The input files are read by the `vbi-input` crate, which the Python package shares.
use vbi_input as inputs;
use vbi_input::source as input;

use std::process::ExitCode;

/// mimalloc keeps freed memory for reuse: a study allocates and frees megabytes of history per
/// crossing, and glibc's allocator returned it to the system each time (about 10 % of a study's
/// time went to page faults). mimalloc v3 returns freed memory only after a second (its
/// `purge_delay`), longer than a batch of crossings takes. It reads its options when the process
/// loads, so only the environment can change them: `MIMALLOC_PURGE_DELAY=-1` (never return
/// memory) takes the paper study from about 65,000 minor page faults to 600 and its system time
/// from 0.6–1.3 s to 0.4–0.6 s (docs/performance.md). An earlier `set_var` of it from `main`
/// came too late to have any effect, and was removed.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use clap::{Parser, Subcommand};

/// Vehicle–bridge interaction dynamics: bridge modes, moving loads, vehicles on rough roads,
/// dynamic amplification factors (DAF) of deflection and bending moment.
#[derive(Debug, Parser)]
#[command(
    name = "vbi",
    version,
    about,
    max_term_width = 100,
    after_help = AFTER_HELP
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Example lines and where the manual is, after `vbi --help`.
const AFTER_HELP: &str = "\
Examples:
  vbi run                                   the built-in scenario: the paper's 3 x 30 m bridge
  vbi run examples/scenarios/i-girder-two-trucks.toml --out results
  vbi modes examples/bridges/skewed-2x20.toml --out modes   sections, mass, mesh, plan, modes
  vbi check my-bridge.toml                  validate any input file as every command does
  vbi study                                 the quick part of the paper's study, into quick-results/

Manual: docs/ in the repository, a tutorial first (docs/tutorial/index.md; `mdbook build` renders
it all to target/book); input keys: docs/input-format.md; theory: docs/theory.md; verification:
docs/verification.md. Exit codes: 0 success, 2 bad input or usage.";

/// What `vbi run` and `vbi study` report, after their help.
const STATIONS_HELP: &str = "\
Stations: the mid-span of every span and every interior support, on each girder and for the whole
section (each girder only, on a skewed grillage), plus the scenario's [[station]] tables; an
imported modal basis has the stations of its files. Quantities at each: deflection, bending
moment, and the shear force (the support reaction at a support; neither on imported models).
Each gets its static and dynamic extremes, the converged DAF and IM, the paper's DAF by modes,
CM, K1 and K2, and the design codes' impact factors beside it.";

#[derive(Debug, Subcommand)]
enum Command {
    /// Validate an input file (bridge, vehicle, road, scenario, study, measurement).
    Check(commands::check::Args),
    /// Bridge model, FE assembly and modal analysis.
    #[command(
        after_help = "Prints each girder's section (A, I_y, I_z, J, centroid, mass per length), the total mass \
                      and the mesh, then the modes: frequency, period, kind, residual. With --out: \
                      modes.csv, mode_shapes.csv and the mode-shape and plan figures."
    )]
    Modes(commands::modes::Args),
    /// Closed-form moving-force theory of continuous beams (the paper's §2).
    Analytic(commands::analytic::Args),
    /// Vehicle models: list presets, show one.
    #[command(subcommand)]
    Vehicle(commands::vehicle::Command),
    /// One vehicle crossing and its DAF analysis (the built-in scenario without a file).
    #[command(after_help = STATIONS_HELP)]
    Run(commands::run::Args),
    /// Parametric studies: many crossings in parallel, resumable, shardable.
    #[command(after_help = STATIONS_HELP)]
    Study(commands::study::Args),
    /// A self-contained HTML report of a study's results.
    Report(commands::report::Args),
    /// ISO 8608 road roughness profiles.
    Road(commands::road::Args),
    /// Field measurements: DAF from measured signals, frequencies, cut-off filtering, updating.
    Measure(commands::measure::Args),
    /// Lifetime load effects under a traffic file: every station's static block maxima (daily).
    Lifetime(commands::lifetime::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Check(args) => commands::check::run(args),
        Command::Modes(args) => commands::modes::run(args),
        Command::Analytic(args) => commands::analytic::run(args),
        Command::Vehicle(command) => commands::vehicle::run(command),
        Command::Run(args) => commands::run::run(args),
        Command::Study(args) => commands::study::run(args),
        Command::Report(args) => commands::report::run(args),
        Command::Road(args) => commands::road::run(args),
        Command::Measure(args) => commands::measure::run(args),
        Command::Lifetime(args) => commands::lifetime::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            if let Some(input) = error.downcast_ref::<input::InputError>() {
                eprintln!("error: {input}");
            } else {
                let short = |text: String| vbi::units::with_short_numbers(&text).into_owned();
                eprintln!("error: {}", short(error.to_string()));
                for cause in error.chain().skip(1) {
                    eprintln!("  caused by: {}", short(cause.to_string()));
                }
            }
            ExitCode::from(2)
        }
    }
}
