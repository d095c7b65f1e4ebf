//! One run of `vbi measure`: a measurement file read and checked, processed, and its outputs
//! written: `measure.json` (provenance, the library's summary, the figures written) and the
//! figures ([`super::figures`]) in its folder; for the command given one file, also
//! `report.html` ([`super::report`]) and the table on standard output.

use crate::console::outln;
use std::path::Path;
use vbi::units::metres_per_second_to_kmh;

use anyhow::{Context, Result};
use serde::Serialize;
use sha2::{Digest, Sha256};
use vbi::measure::measurement::Measurement;
use vbi::measure::{measure, MeasureError, MeasurementResult, MeasurementSummary};

use super::figures::{draw_figures, file_stem};
use super::report::ReportRun;
use super::rows::rows;
use crate::commands::OutputFormat;
use crate::input::SourceFile;
use crate::inputs::measurement::{self, MeasurementFile};
use crate::output;

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
pub(super) struct Report<'a> {
    provenance: Provenance,
    #[serde(flatten)]
    summary: &'a MeasurementSummary,
    pub(super) figures: Vec<String>,
}

/// A measurement file, read and checked as `vbi check` does.
pub(super) struct LoadedRun {
    /// The TOML file.
    pub(super) file: SourceFile,
    /// Its measurement and CSV.
    pub(super) loaded: MeasurementFile,
}

/// Reads and checks one measurement file (the located error of the first problem).
pub(super) fn load_run(path: &Path) -> Result<LoadedRun> {
    let file = SourceFile::read(path)?;
    crate::inputs::expect_kind(&file, "measurement", "vbi measure")?;
    let loaded = measurement::load(&file)?;
    Ok(LoadedRun { file, loaded })
}

/// Processes one checked run; an error names its file (a value of the file that the processing
/// cannot use points at its key).
pub(super) fn process(run: &LoadedRun) -> Result<MeasurementResult> {
    measure(&run.loaded.measurement).map_err(|e| located(&run.file, e))
}

/// A processing error of `file`: at its key when it is a value of the file.
pub(crate) fn located(file: &SourceFile, error: MeasureError) -> anyhow::Error {
    match error {
        MeasureError::Input { field, message } => file
            .error_at(&format!("measurement.{field}"), message)
            .into(),
        other => anyhow::Error::from(other).context(format!("processing {}", file.name())),
    }
}

/// The outputs of the command given one file: `DIR/measure.json`, its figures and
/// `DIR/report.html`, and the table (or `measure.json`) on standard output.
pub(super) fn write_outputs(
    out: &Path,
    format: OutputFormat,
    run: &LoadedRun,
    result: &MeasurementResult,
) -> Result<()> {
    output::create_output_dir(out)?;
    let report = write_run(run, result, out)?;
    let stem = run_stem(&run.file.path);
    let input = run.file.name();
    let rows = rows(&stem, &input, &result.summary);
    let html = out.join("report.html");
    super::report::write(
        &[ReportRun {
            stem: &stem,
            input: &input,
            dir: out,
            directory_label: None,
            figures: &report.figures,
            result,
            rows: &rows,
        }],
        &html,
    )?;
    match format {
        OutputFormat::Json => outln!("{}", serde_json::to_string_pretty(&report)?),
        OutputFormat::Table => {
            print_table(&result.summary, &run.loaded.measurement, out);
            outln!("wrote {}", html.display());
        }
    }
    Ok(())
}

/// The name of a run: its file's stem as a file name (see [`file_stem`]), `run` when empty.
pub(super) fn run_stem(path: &Path) -> String {
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
pub(super) fn write_run<'a>(
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

/// A sampling rate as the table shows it: to 1 µHz, without trailing zeros (a rate derived
/// from a time column, 200.00000000000003 Hz, reads 200 Hz; measure.json keeps every digit).
fn sampling_rate(hz: f64) -> String {
    let text = format!("{hz:.6}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn print_table(r: &MeasurementSummary, m: &Measurement, out: &Path) {
    outln!(
        "{} samples at {} Hz ({:.2} s)",
        r.samples,
        sampling_rate(r.sampling_rate_hz),
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
    if let Some(w) = &r.weighing {
        print_weighing(w);
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
    if !r.warnings.is_empty() {
        outln!("warnings ({}):", r.warnings.len());
        for w in &r.warnings {
            outln!("  - {w}");
        }
    }
    if let Some(v) = m.speed {
        outln!(
            "vehicle speed {:.2} m/s ({:.1} km/h)",
            v,
            metres_per_second_to_kmh(v)
        );
    }
    outln!("wrote {}", out.join("measure.json").display());
}

/// The weighed vehicle: gross weight and axle loads [kN] with their standard uncertainties,
/// beside the given ones.
fn print_weighing(w: &vbi::measure::VehicleWeighing) {
    let sensors: Vec<String> = w
        .channels
        .iter()
        .map(|c| format!("{} ({})", c.channel, c.line_source))
        .collect();
    let entry = if w.entry_time_fitted {
        "fitted"
    } else {
        "given"
    };
    let filtered = w.low_pass_hz.map_or(String::new(), |cutoff| {
        format!("; record and lines low-passed at {cutoff:.2} Hz")
    });
    outln!(
        "weighed vehicle (Moses' least squares on {}; entry {:.3} s {entry}{filtered}; ± the fit's own standard deviation, without the vehicle's dynamic axle forces):",
        sensors.join(", "),
        w.entry_time_s
    );
    let kn = vbi::units::KN;
    let against = |weighed: f64, given: Option<f64>| {
        given.map_or(String::new(), |g| {
            format!(
                " (given {:.1}: {:+.2} %)",
                g / kn,
                100.0 * (weighed / g - 1.0)
            )
        })
    };
    let given = w.against_given.as_ref();
    outln!(
        "  gross weight {:.1} ± {:.1} kN{}",
        w.gross_weight_n / kn,
        w.gross_weight_fit_std_n / kn,
        against(w.gross_weight_n, given.map(|g| g.gross_weight_n))
    );
    for (a, (load, std)) in w
        .axle_loads_n
        .iter()
        .zip(&w.axle_load_fit_std_n)
        .enumerate()
    {
        outln!(
            "  axle {} at {:.2} m: {:.1} ± {:.1} kN{}",
            a + 1,
            w.axle_offsets_m[a],
            load / kn,
            std / kn,
            against(*load, given.map(|g| g.axle_loads_n[a]))
        );
    }
}

#[cfg(test)]
mod tests {
    use super::sampling_rate;

    #[test]
    fn a_sampling_rate_from_a_time_column_is_shown_without_its_last_bit() {
        assert_eq!(sampling_rate(200.00000000000003), "200");
        assert_eq!(sampling_rate(500.00000000000006), "500");
        assert_eq!(sampling_rate(199.95), "199.95");
        assert_eq!(sampling_rate(1024.0), "1024");
    }
}
