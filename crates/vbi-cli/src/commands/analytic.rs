//! `vbi analytic`: the closed-form moving-force theory of the paper's §2 — DAF_u, DAF_M and RDM
//! of a continuous beam against the number of modes K (Eqs. 15–17).

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};
use vbi::analytical::{
    daf_by_modes, ContinuousBeam, DafOptions, DafTable, MaximumWindow, StaticReference,
};

use crate::commands::OutputFormat;
use crate::input::InputError;
use crate::output;
use crate::plot::{self, Chart, Series};

/// Static reference of the DAF.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Reference {
    /// Largest static response at the section over all load positions.
    Envelope,
    /// Static response with the load at the section (the paper's Eq. 18).
    LoadAtSection,
}

/// Arguments of `vbi analytic`. Defaults: the paper's two-span 20 m beam class (f₁ ≈ 5.0 Hz)
/// at 80 km/h with 5 % damping.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Number of equal spans N (1 = simply supported).
    #[arg(long, default_value_t = 2)]
    pub spans: usize,
    /// Span length l [m].
    #[arg(long, default_value_t = 20.0, allow_negative_numbers = true)]
    pub span_length: f64,
    /// Flexural rigidity EI [N·m²].
    #[arg(long, default_value_t = 3.24e10, allow_negative_numbers = true)]
    pub ei: f64,
    /// Mass per unit length m̄ [kg/m].
    #[arg(long, default_value_t = 2.0e4, allow_negative_numbers = true)]
    pub mass_per_length: f64,
    /// Speed of the force [km/h] (default 80).
    #[arg(long, conflicts_with = "alpha", allow_negative_numbers = true)]
    pub speed_kmh: Option<f64>,
    /// Speed parameter α = v/(2 f₁ l) instead of a speed.
    #[arg(long, allow_negative_numbers = true)]
    pub alpha: Option<f64>,
    /// Modal damping ratio ζ of every mode [-].
    #[arg(long, default_value_t = 0.05, allow_negative_numbers = true)]
    pub damping: f64,
    /// Largest number of modes K; the table covers K = 1 … this.
    #[arg(long, default_value_t = 30)]
    pub modes: usize,
    /// Section as x/l, in span lengths from the first support (0.5 = mid-span of span 1; 1 =
    /// the first interior support, where the hogging moment has a DAF and the deflection none).
    #[arg(long, default_value_t = 0.5, allow_negative_numbers = true)]
    pub section: f64,
    /// Static reference of the DAF.
    #[arg(long, value_enum, default_value_t = Reference::Envelope)]
    pub static_reference: Reference,
    /// Also take the maximum over this many seconds of free vibration after the force leaves
    /// (0: only while the force is on the beam).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub free_vibration: f64,
    /// Number of equally spaced output times of the response histories.
    #[arg(long, default_value_t = 1000)]
    pub output_times: usize,
    /// Output format on standard output.
    #[arg(long, value_enum, default_value_t = OutputFormat::Table)]
    pub format: OutputFormat,
    /// Directory for analytic.csv, analytic.json and the figure analytic_daf.png/.svg.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Largest K accepted on the command line.
const MAX_MODES: usize = 500;

fn positive(option: &str, value: f64, unit: &str) -> Result<f64, InputError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(InputError::command_line(
            option,
            format!("{value} is not allowed; expected a positive number of {unit}"),
        ))
    }
}

/// Checks the options and builds the beam and the options of the library call.
fn prepare(args: &Args) -> Result<(ContinuousBeam, DafOptions), InputError> {
    if args.spans == 0 || args.spans > vbi::analytical::MAX_SPANS {
        return Err(InputError::command_line(
            "--spans",
            format!(
                "{} is not allowed; expected 1 to {}",
                args.spans,
                vbi::analytical::MAX_SPANS
            ),
        ));
    }
    let span_length = positive("--span-length", args.span_length, "m")?;
    let ei = positive("--ei", args.ei, "N·m²")?;
    let mass = positive("--mass-per-length", args.mass_per_length, "kg/m")?;
    let beam = ContinuousBeam::new(args.spans, span_length, ei, mass)
        .map_err(|e| InputError::command_line("--spans", e.to_string()))?;
    let speed = match (args.speed_kmh, args.alpha) {
        (_, Some(alpha)) => beam.speed_from_parameter(positive("--alpha", alpha, "-")?),
        (Some(kmh), None) => {
            vbi::units::kmh_to_metres_per_second(positive("--speed-kmh", kmh, "km/h")?)
        }
        (None, None) => vbi::units::kmh_to_metres_per_second(80.0),
    };
    if !(args.damping.is_finite() && (0.0..1.0).contains(&args.damping)) {
        return Err(InputError::command_line(
            "--damping",
            format!(
                "{} is not allowed; expected a damping ratio 0 ≤ ζ < 1",
                args.damping
            ),
        ));
    }
    if args.modes == 0 || args.modes > MAX_MODES {
        return Err(InputError::command_line(
            "--modes",
            format!("{} is not allowed; expected 1 to {MAX_MODES}", args.modes),
        ));
    }
    let n = args.spans as f64;
    // An interior support (x/l a whole number) is allowed: its hogging moment has a DAF, its
    // deflection none (issue 46). The end supports have neither.
    if !(args.section.is_finite() && args.section > 0.0 && args.section < n) {
        return Err(InputError::command_line(
            "--section",
            format!(
                "{} is not allowed; expected x/l strictly between 0 and {n} (an interior \
                 support gives the hogging moment's DAF; the end supports have none)",
                vbi::units::shown(args.section)
            ),
        ));
    }
    if !(args.free_vibration.is_finite() && args.free_vibration >= 0.0) {
        return Err(InputError::command_line(
            "--free-vibration",
            format!(
                "{} is not allowed; expected a duration ≥ 0 s",
                args.free_vibration
            ),
        ));
    }
    if !(3..=1_000_000).contains(&args.output_times) {
        return Err(InputError::command_line(
            "--output-times",
            format!(
                "{} is not allowed; expected 3 to 1000000",
                args.output_times
            ),
        ));
    }
    let options = DafOptions {
        speed,
        damping_ratio: args.damping,
        modes: args.modes,
        section: Some(args.section * span_length),
        static_reference: match args.static_reference {
            Reference::Envelope => StaticReference::Envelope,
            Reference::LoadAtSection => StaticReference::LoadAtSection,
        },
        window: if args.free_vibration > 0.0 {
            MaximumWindow::WithFreeVibration {
                duration: args.free_vibration,
            }
        } else {
            MaximumWindow::LoadOnBeam
        },
        output_times: args.output_times,
    };
    Ok((beam, options))
}

/// What `--format json` prints and `analytic.json` holds.
#[derive(Debug, serde::Serialize)]
struct Report<'a> {
    beam: &'a ContinuousBeam,
    speed_kmh: f64,
    damping_ratio: f64,
    section_ratio: f64,
    /// Which static reference the DAFs divide by, in words (`static_reference` is the key).
    static_reference_description: &'static str,
    /// Over which window the dynamic maximum is taken, in words (`window` is the key).
    maximum_window: String,
    #[serde(flatten)]
    table: &'a DafTable,
}

fn describe_window(window: MaximumWindow) -> String {
    match window {
        MaximumWindow::LoadOnBeam => "while the force is on the beam".to_string(),
        MaximumWindow::WithFreeVibration { duration } => {
            format!("while the force is on the beam and {duration} s of free vibration after")
        }
    }
}

fn describe_reference(reference: StaticReference) -> &'static str {
    match reference {
        StaticReference::Envelope => "envelope (largest static value over load positions)",
        StaticReference::LoadAtSection => "load at the section (the paper's Eq. 18)",
    }
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    let (beam, options) = prepare(args)?;
    let table = daf_by_modes(&beam, &options).map_err(|e| match e {
        too_long @ vbi::analytical::AnalyticalError::FreeVibrationTooLong { .. } => {
            anyhow::Error::from(InputError::command_line(
                "--free-vibration",
                too_long.to_string(),
            ))
        }
        other => other.into(),
    })?;
    let report = Report {
        beam: &beam,
        speed_kmh: table.speed / vbi::units::KMH,
        damping_ratio: options.damping_ratio,
        section_ratio: args.section,
        static_reference_description: describe_reference(options.static_reference),
        maximum_window: describe_window(options.window),
        table: &table,
    };
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let printed = match args.format {
        OutputFormat::Json => serde_json::to_writer_pretty(&mut out, &report)
            .map_err(std::io::Error::from)
            .and_then(|()| writeln!(out)),
        OutputFormat::Table => write_table(&mut out, &beam, &options, &table),
    };
    match printed {
        // A closed pipe (`vbi analytic | head`) is not an error: the reader has what it wanted.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        other => other.context("writing to standard output")?,
    }
    if let Some(dir) = &args.out {
        write_files(dir, &report, &table)?;
    }
    Ok(())
}

fn write_table(
    out: &mut impl Write,
    beam: &ContinuousBeam,
    options: &DafOptions,
    table: &DafTable,
) -> std::io::Result<()> {
    writeln!(
        out,
        "Moving constant force on {} × {} m continuous beam (EI = {:e} N·m², m̄ = {} kg/m)",
        beam.spans, beam.span_length, beam.flexural_rigidity, beam.mass_per_length
    )?;
    writeln!(
        out,
        "f₁ = {:.4} Hz, v = {:.2} km/h, α = v/(2 f₁ l) = {:.5}, ζ = {}, section x = {} m",
        beam.fundamental_frequency_hz(),
        table.speed / vbi::units::KMH,
        table.alpha,
        options.damping_ratio,
        table.section
    )?;
    writeln!(
        out,
        "static reference: {}: λ₁ = {:.8} (load at {:.4} m), λ₂ = {:.8} (load at {:.4} m)",
        describe_reference(table.static_reference),
        table.lambda_deflection,
        table.static_deflection_load_position,
        table.lambda_moment,
        table.static_moment_load_position
    )?;
    writeln!(out, "maximum taken {}", describe_window(table.window))?;
    if !table.deflection_defined {
        writeln!(
            out,
            "the section is an interior support: the static deflection is zero there, so DAF_u \
             and RDM are undefined (–); DAF_M is the hogging moment's"
        )?;
    }
    writeln!(
        out,
        "plain modal sums (Eqs. 15-17) | static-corrected sums (exact statics + K-mode dynamic part)"
    )?;
    writeln!(
        out,
        "{:>4}  {:>12}  {:>10}  {:>10}  {:>10} | {:>10}  {:>10}  {:>10}",
        "K", "f_K [Hz]", "DAF_u", "DAF_M", "RDM", "DAF_u", "DAF_M", "RDM"
    )?;
    let shown = |values: &[f64], k: usize| -> String {
        values.get(k).map_or("–".to_string(), |v| format!("{v:.6}"))
    };
    for k in 0..table.daf_moment_by_modes.len() {
        writeln!(
            out,
            "{:>4}  {:>12.4}  {:>10}  {:>10}  {:>10} | {:>10}  {:>10}  {:>10}",
            k + 1,
            table.frequencies_hz[k],
            shown(&table.daf_deflection_by_modes, k),
            shown(&table.daf_moment_by_modes, k),
            shown(&table.rdm_by_modes, k),
            shown(&table.daf_deflection_corrected_by_modes, k),
            shown(&table.daf_moment_corrected_by_modes, k),
            shown(&table.rdm_corrected_by_modes, k)
        )?;
    }
    Ok(())
}

fn write_files(dir: &std::path::Path, report: &Report<'_>, table: &DafTable) -> Result<()> {
    output::create_output_dir(dir)?;
    // An undefined value (the deflection's at an interior support) is an empty cell.
    let cell =
        |values: &[f64], k: usize| values.get(k).map_or(String::new(), |v| output::number(*v));
    let rows: Vec<Vec<String>> = (0..table.daf_moment_by_modes.len())
        .map(|k| {
            vec![
                (k + 1).to_string(),
                output::number(table.frequencies_hz[k]),
                cell(&table.daf_deflection_by_modes, k),
                cell(&table.daf_moment_by_modes, k),
                cell(&table.rdm_by_modes, k),
                cell(&table.daf_deflection_corrected_by_modes, k),
                cell(&table.daf_moment_corrected_by_modes, k),
                cell(&table.rdm_corrected_by_modes, k),
            ]
        })
        .collect();
    output::write_csv(
        &dir.join("analytic.csv"),
        &[
            "modes",
            "frequency_hz",
            "daf_deflection",
            "daf_moment",
            "rdm",
            "daf_deflection_static_corrected",
            "daf_moment_static_corrected",
            "rdm_static_corrected",
        ],
        &rows,
    )?;
    output::write_json(&dir.join("analytic.json"), report)?;
    let curve = |values: &[f64]| -> Vec<(f64, f64)> {
        values
            .iter()
            .enumerate()
            .map(|(k, v)| ((k + 1) as f64, *v))
            .collect()
    };
    let chart = Chart {
        title: format!(
            "{} × {} m beam, α = {:.3}: DAF against number of modes",
            report.beam.spans, report.beam.span_length, table.alpha
        ),
        x_label: "number of modes K".into(),
        y_label: "DAF, RDM [-]".into(),
        series: [
            Series::line("DAF deflection", curve(&table.daf_deflection_by_modes)),
            Series::line("DAF moment", curve(&table.daf_moment_by_modes)),
            Series::line("RDM", curve(&table.rdm_by_modes)),
            Series {
                label: "DAF moment, static-corrected".into(),
                points: curve(&table.daf_moment_corrected_by_modes),
                style: plot::SeriesStyle::Thin,
            },
        ]
        .into_iter()
        // The deflection's series are empty at an interior support.
        .filter(|series| !series.points.is_empty())
        .collect(),
        ..Chart::default()
    };
    plot::write_chart(&chart, &dir.join("analytic_daf"))?;
    Ok(())
}
