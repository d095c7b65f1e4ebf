//! `vbi measure FILE.toml [FILE2.toml …] [--out DIR] [--format json|table]`: DAF from measured
//! signals, natural frequencies and damping from acceleration spectra, low-pass filtering at the
//! cut-off mode K1, and model updating (the paper's §6).
//!
//! The processing is the library's measurement stage (`vbi::crossing::measure`); this command
//! reads each file through `vbi-input` and writes, for one file, `DIR/measure.json` and figures
//! (PNG + SVG): `signal_<channel>` (raw, static and K1-filtered signals) and
//! `spectrum_<channel>` (Welch PSD with the picked peaks), and `DIR/report.html`
//! ([`crate::measure_report`]). Several files are the runs of one load test
//! ([`crate::measure_batch`]): a folder per run and one table and report over them all.
//!
//! Every file is read and checked before any is processed, and every run is processed before
//! anything is written: a bad file or a failing run writes nothing.

use crate::console::outln;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde::Serialize;
use sha2::{Digest, Sha256};
use vbi::measure::measurement::Measurement;
use vbi::measure::{
    measure, ChannelSpectrum, IdentifiedMode, MeasureError, MeasurementResult, MeasurementSummary,
    SubspaceSummary,
};
use vbi::signal::Psd;

use crate::commands::OutputFormat;
use crate::input::SourceFile;
use crate::inputs::measurement::{self, MeasurementFile};
use crate::measure_batch;
use crate::measure_report::{self, ReportRun};
use crate::output;
use crate::plot::{self, Chart, Series, SeriesStyle};

/// Arguments of `vbi measure`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The measurement descriptions (TOML with a [measurement] table): one run, or several runs
    /// of one load test (passes, speeds, lanes), processed in the order given.
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<PathBuf>,
    /// Output directory: measure.json, the figures and report.html of one run; with several
    /// runs, a folder per run (named by the file's stem) and measurements.csv,
    /// measurements.json and report.html over them all.
    #[arg(long, default_value = "measure_out")]
    pub out: PathBuf,
    /// What to print on standard output (json: the same JSON as measure.json, or as
    /// measurements.json for several runs).
    #[arg(long, value_enum, default_value_t = OutputFormat::Table)]
    pub format: OutputFormat,
}

#[derive(Debug, Serialize)]
struct Provenance {
    vbi_version: &'static str,
    input: String,
    csv: String,
    /// SHA-256 of the TOML text followed by the CSV bytes.
    input_sha256: String,
}

/// `measure.json`: the provenance, the library's summary and the figures written.
#[derive(Debug, Serialize)]
pub(crate) struct Report<'a> {
    provenance: Provenance,
    #[serde(flatten)]
    summary: &'a MeasurementSummary,
    pub(crate) figures: Vec<String>,
}

/// A name made of ASCII letters, digits, `-` and `_` (every other character `_`): a file stem.
fn file_stem(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// `stem`, or `stem_2`, `stem_3`, … when an earlier figure has it: two channel names that map to
/// one file stem (`u 1` and `u/1`) must not overwrite each other's figure.
fn unique_stem(stem: String, taken: &[String]) -> String {
    if !taken.contains(&stem) {
        return stem;
    }
    (2..)
        .map(|k| format!("{stem}_{k}"))
        .find(|s| !taken.contains(s))
        .expect("an unused suffix")
}

/// A measurement file, read and checked as `vbi check` does.
pub(crate) struct LoadedRun {
    /// The TOML file.
    pub(crate) file: SourceFile,
    /// Its measurement and CSV.
    pub(crate) loaded: MeasurementFile,
}

/// Reads and checks one measurement file (the located error of the first problem).
fn load_run(path: &Path) -> Result<LoadedRun> {
    let file = SourceFile::read(path)?;
    crate::inputs::expect_kind(&file, "measurement", "vbi measure")?;
    let loaded = measurement::load(&file)?;
    Ok(LoadedRun { file, loaded })
}

/// Processes one checked run; an error names its file (a value of the file that the processing
/// cannot use points at its key).
fn process(run: &LoadedRun) -> Result<MeasurementResult> {
    let file = &run.file;
    measure(&run.loaded.measurement).map_err(|e| match e {
        MeasureError::Input { field, message } => file
            .error_at(&format!("measurement.{field}"), message)
            .into(),
        other => anyhow::Error::from(other).context(format!("processing {}", file.name())),
    })
}

/// Runs the command: every file read and checked, then every run processed, then the outputs
/// written.
pub fn run(args: &Args) -> Result<()> {
    let runs: Vec<LoadedRun> = args
        .files
        .iter()
        .map(|path| load_run(path))
        .collect::<Result<_>>()?;
    let results: Vec<MeasurementResult> = runs.iter().map(process).collect::<Result<_>>()?;
    match (runs.as_slice(), results.as_slice()) {
        ([run], [result]) => single(args, run, result),
        _ => measure_batch::run(args, &runs, &results),
    }
}

/// One run: `DIR/measure.json`, its figures and `DIR/report.html`.
fn single(args: &Args, run: &LoadedRun, result: &MeasurementResult) -> Result<()> {
    output::create_output_dir(&args.out)?;
    let report = write_run(run, result, &args.out)?;
    let stem = run_stem(&run.file.path);
    let input = run.file.name();
    let rows = measure_batch::rows(&stem, &input, &result.summary);
    let html = args.out.join("report.html");
    measure_report::write(
        &[ReportRun {
            stem: &stem,
            input: &input,
            dir: &args.out,
            directory_label: None,
            figures: &report.figures,
            result,
            rows: &rows,
        }],
        &html,
    )?;
    match args.format {
        OutputFormat::Json => outln!("{}", serde_json::to_string_pretty(&report)?),
        OutputFormat::Table => {
            print_table(&result.summary, &run.loaded.measurement, &args.out);
            outln!("wrote {}", html.display());
        }
    }
    Ok(())
}

/// The name of a run: its file's stem as a file name (see [`file_stem`]), `run` when empty.
pub(crate) fn run_stem(path: &Path) -> String {
    let stem = path
        .file_stem()
        .map(|s| file_stem(&s.to_string_lossy()))
        .unwrap_or_default();
    if stem.is_empty() {
        "run".into()
    } else {
        stem
    }
}

/// Writes a processed run's figures and `measure.json` into `out` (which exists); returns what
/// `measure.json` holds.
pub(crate) fn write_run<'a>(
    run: &LoadedRun,
    result: &'a MeasurementResult,
    out: &Path,
) -> Result<Report<'a>> {
    let figures = draw_figures(&result.record, result, out)?;
    let mut hasher = Sha256::new();
    hasher.update(run.file.text.as_bytes());
    let csv = &run.loaded.csv_path;
    hasher.update(std::fs::read(csv).with_context(|| format!("reading {}", csv.display()))?);
    let report = Report {
        provenance: Provenance {
            vbi_version: env!("CARGO_PKG_VERSION"),
            input: run.file.name(),
            csv: csv.display().to_string(),
            input_sha256: format!("{:x}", hasher.finalize()),
        },
        summary: &result.summary,
        figures,
    };
    output::write_json(&out.join("measure.json"), &report)?;
    Ok(report)
}

/// The figures of every channel (raw, static and K1-filtered signals) and of every spectrum
/// (Welch PSD with the picked peaks); returns their stems.
fn draw_figures(m: &Measurement, result: &MeasurementResult, out: &Path) -> Result<Vec<String>> {
    let mut figures = Vec::new();
    for (index, c) in m.channels.iter().enumerate() {
        let stem = unique_stem(format!("signal_{}", file_stem(&c.name)), &figures);
        plot::write_chart(&signal_chart(m, result, index), &out.join(&stem))?;
        figures.push(stem);
    }
    for (psd, spectrum) in result.densities.iter().zip(&result.summary.spectra) {
        let stem = unique_stem(
            format!("spectrum_{}", file_stem(&spectrum.channel)),
            &figures,
        );
        plot::write_chart(&spectrum_chart(m, psd, spectrum), &out.join(&stem))?;
        figures.push(stem);
    }
    if let Some(subspace) = &result.summary.subspace {
        let stem = "stabilisation_diagram".to_string();
        let chart = stabilisation_chart(subspace, &result.summary.identified_frequencies);
        plot::write_chart(&chart, &out.join(&stem))?;
        figures.push(stem);
    }
    Ok(figures)
}

/// The subspace identification's stabilisation diagram: every pole kept (frequency against
/// model order), the stable ones marked, and the identified modes at the highest order.
fn stabilisation_chart(subspace: &SubspaceSummary, modes: &[IdentifiedMode]) -> Chart {
    let poles = |stable: bool| -> Vec<(f64, f64)> {
        subspace
            .diagram
            .iter()
            .filter(|p| p.stable == stable)
            .map(|p| (p.frequency_hz, p.order as f64))
            .collect()
    };
    let top = subspace.max_order as f64 + 2.0;
    let identified: Vec<(f64, f64)> = modes
        .iter()
        .flat_map(|p| [(p.frequency_hz, 0.0), (p.frequency_hz, top)])
        .collect();
    Chart {
        title: format!(
            "stabilisation diagram ({} acceleration channels)",
            subspace.channels.len()
        ),
        x_label: "frequency [Hz]".into(),
        y_label: "model order [-]".into(),
        series: vec![
            Series {
                label: "poles".into(),
                points: poles(false),
                style: SeriesStyle::Points,
            },
            Series {
                label: "stable poles".into(),
                points: poles(true),
                style: SeriesStyle::Points,
            },
            Series {
                label: "identified modes".into(),
                points: identified,
                style: SeriesStyle::ThinSegments,
            },
        ],
        ..Chart::default()
    }
}

/// A channel's measured signal with its static part and its K1-filtered signal (at most about
/// 4000 points drawn), in the channel's unit.
fn signal_chart(m: &Measurement, result: &MeasurementResult, index: usize) -> Chart {
    let c = &m.channels[index];
    let step = (m.time.len() / 4000).max(1);
    let points = |v: &[f64]| -> Vec<(f64, f64)> {
        m.time
            .iter()
            .zip(v)
            .step_by(step)
            .map(|(t, x)| (*t, x / c.si_per_unit))
            .collect()
    };
    let mut series = vec![Series {
        label: "measured".into(),
        points: points(&c.samples),
        style: SeriesStyle::Thin,
    }];
    if let Some(signals) = result.signals.iter().find(|s| s.channel_index == index) {
        if let Some(filtered) = &signals.filtered_at_cutoff_mode {
            let label = result
                .summary
                .channels
                .iter()
                .find(|r| r.name == c.name)
                .and_then(|r| r.cutoff_mode.as_ref())
                .map_or("low-pass above K1".to_string(), |k| {
                    format!(
                        "low-pass above K1 ({:.2} Hz), f_c = {:.2} Hz",
                        k.mode_frequency_hz, k.cutoff_hz
                    )
                });
            series.push(Series::line(label, points(filtered)));
        }
        series.push(Series::line("static", points(&signals.static_part)));
    }
    Chart {
        title: format!("{} ({:?})", c.name, c.kind).to_lowercase(),
        x_label: "time [s]".into(),
        y_label: format!("{} [{}]", c.name, c.unit),
        series,
        ..Chart::default()
    }
}

/// A Welch PSD in dB with its picked peaks, up to twice the search band (the whole band when
/// unbounded): the modes stay readable next to the noise floor.
fn spectrum_chart(m: &Measurement, psd: &Psd, spectrum: &ChannelSpectrum) -> Chart {
    let f_max = (2.0 * m.spectrum.max_frequency_hz).min(m.sampling_rate_hz / 2.0);
    let db = |p: f64| 10.0 * p.max(1e-300).log10();
    let line: Vec<(f64, f64)> = psd
        .frequency_hz
        .iter()
        .zip(&psd.density)
        .skip(1)
        .filter(|(f, _)| **f <= f_max)
        .map(|(f, p)| (*f, db(*p)))
        .collect();
    let peaks: Vec<(f64, f64)> = spectrum
        .peaks
        .iter()
        .map(|p| (p.frequency_hz, db(p.density)))
        .collect();
    Chart {
        title: format!("Welch PSD of {} with picked peaks", spectrum.channel),
        x_label: "frequency [Hz]".into(),
        y_label: "PSD [dB re 1 (m/s²)²/Hz]".into(),
        series: vec![
            Series::line("PSD", line),
            Series {
                label: "picked peaks".into(),
                points: peaks,
                style: SeriesStyle::Points,
            },
        ],
        ..Chart::default()
    }
}

fn print_table(r: &MeasurementSummary, m: &Measurement, out: &Path) {
    outln!(
        "{} samples at {} Hz ({:.2} s)",
        r.samples,
        r.sampling_rate_hz,
        r.duration_s
    );
    if let Some(s) = &r.static_separation {
        outln!(
            "static part: zero-phase Butterworth order {}, {}",
            s.filter_order,
            s.explanation
        );
    }
    if !r.channels.is_empty() {
        outln!(
            "{:<20} {:<15} {:>12} {:>12} {:>8} {:>10} {:>10}",
            "channel",
            "kind",
            "static max",
            "dynamic max",
            "DAF",
            "K1 [Hz]",
            "DAF at K1"
        );
        for c in &r.channels {
            let (k1, after) =
                c.cutoff_mode
                    .as_ref()
                    .map_or(("-".to_string(), "-".to_string()), |k| {
                        (
                            format!("{:.2}", k.mode_frequency_hz),
                            format!("{:.4}", k.daf_after),
                        )
                    });
            outln!(
                "{:<20} {:<15} {:>12.5} {:>12.5} {:>8.4} {:>10} {:>10}",
                c.name,
                format!("{:?} [{}]", c.kind, c.unit).to_lowercase(),
                c.static_max,
                c.dynamic_max,
                c.daf,
                k1,
                after
            );
        }
    }
    for x in &r.rdm {
        outln!(
            "RDM at {}: {:.4} / {:.4} = {:.4}",
            x.section,
            x.daf_deflection,
            x.daf_moment,
            x.rdm
        );
    }
    if let Some(ch) = &r.frequency_channel {
        match &r.subspace {
            Some(s) => outln!(
                "identified modes ({}, subspace of {}; ± the scatter over model orders):",
                r.identification,
                s.channels.join(", ")
            ),
            None => outln!("identified frequencies ({ch}):"),
        }
        for (i, p) in r.identified_frequencies.iter().enumerate() {
            let z = p.damping_ratio.map_or("-".to_string(), |z| {
                let bound = if p.damping_resolution_limited {
                    " (upper bound: resolution-limited)"
                } else {
                    ""
                };
                let spread = p
                    .damping_std
                    .map_or(String::new(), |s| format!(" ± {:.2}", 100.0 * s));
                format!("{:.2}{spread} %{bound}", 100.0 * z)
            });
            let spread = p
                .frequency_std_hz
                .map_or(String::new(), |s| format!(" ± {s:.3}"));
            outln!(
                "  mode {}: {:.3}{spread} Hz, damping {z}",
                i + 1,
                p.frequency_hz
            );
        }
        let listed = |modes: &[vbi::measure::IdentifiedMode]| {
            let f: Vec<String> = modes
                .iter()
                .map(|p| format!("{:.3}", p.frequency_hz))
                .collect();
            f.join(", ")
        };
        if !r.vehicle_modes.is_empty() {
            outln!(
                "  left out as the vehicle's own modes: {} Hz",
                listed(&r.vehicle_modes)
            );
        }
        if !r.forced_modes.is_empty() {
            outln!(
                "  left out as forced content (gone once the vehicle left): {} Hz",
                listed(&r.forced_modes)
            );
        }
    }
    if let Some(c) = &r.calibration {
        outln!("calibration ({} pairs by {}):", c.modes.len(), c.pairing);
        for p in &c.parameters {
            let u = p
                .standard_uncertainty
                .map_or(String::new(), |u| format!(" ± {u:.4}"));
            outln!("  {}: factor {:.4}{u}", p.name, p.factor);
        }
        outln!(
            "  RMS frequency error {:.3} % -> {:.3} %",
            100.0 * c.initial_rms_frequency_error,
            100.0 * c.updated_rms_frequency_error
        );
    }
    for c in &r.channels {
        if let Some(u) = &c.uncertainty {
            outln!(
                "DAF of {}: {:.4} ± {:.4} (noise {:.4}, static separation {:.4}; 95 %: ± {:.4})",
                c.name,
                c.daf,
                u.combined,
                u.from_noise,
                u.from_static_separation,
                u.expanded_95
            );
        }
    }
    if let Some(u) = &r.updating {
        let mass = u
            .mass_scale
            .map_or(String::new(), |b| format!(", added-mass scale {b:.4}"));
        outln!(
            "model updating: stiffness scale {:.4}{mass}; RMS frequency error {:.4} Hz -> {:.4} Hz",
            u.stiffness_scale,
            u.initial_rms_error_hz,
            u.updated_rms_error_hz
        );
        if let Some(b) = &r.bridge {
            if let Some(k) = b.stiffness_updated {
                outln!(
                    "  {}: {:.6e} -> {:.6e}",
                    b.stiffness_parameter,
                    b.stiffness_initial,
                    k
                );
            }
        }
        for p in &u.pairs {
            outln!(
                "  mode {}: measured {:.3} Hz, model {:.3} -> {:.3} Hz",
                p.model_index + 1,
                p.identified_hz,
                p.initial_hz,
                p.updated_hz
            );
        }
    }
    if let Some(v) = m.speed {
        outln!("vehicle speed {:.2} m/s ({:.1} km/h)", v, v * 3.6);
    }
    outln!("wrote {}", out.join("measure.json").display());
}

#[cfg(test)]
mod tests {
    use super::{file_stem, unique_stem};

    #[test]
    fn channel_names_that_map_to_one_file_stem_get_figures_of_their_own() {
        let mut figures = Vec::new();
        for name in ["u 1", "u/1", "u_1"] {
            let stem = unique_stem(format!("signal_{}", file_stem(name)), &figures);
            figures.push(stem);
        }
        assert_eq!(figures, ["signal_u_1", "signal_u_1_2", "signal_u_1_3"]);
    }
}
