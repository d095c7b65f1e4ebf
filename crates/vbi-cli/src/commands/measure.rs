//! `vbi measure FILE.toml [--out DIR] [--format json|table]`: DAF from measured signals,
//! natural frequencies and damping from acceleration spectra, low-pass filtering at the cut-off
//! mode K1, and model updating (the paper's §6).
//!
//! Writes `DIR/measure.json` and figures (PNG + SVG): `signal_<channel>` (raw, static and
//! K1-filtered signals) and `spectrum_<channel>` (Welch PSD with the picked peaks).
//!
//! With `bridge = "file.toml"` the bridge is discretised and its modes solved: K1 may be given
//! as a mode number (its frequency, from the updated model when updating is asked), and model
//! updating rebuilds and re-solves the model for every trial of the scale factors (E or EI,
//! and the added pavement mass).

use std::path::PathBuf;

use anyhow::{Context, Result};
use serde::Serialize;
use sha2::{Digest, Sha256};
use vbi::signal::{
    automatic_cutoff, cutoff_mode_filtering, measured_daf, pick_peaks, rdm, static_component,
    static_from_influence_line, update_model, welch, CutoffChoice, CutoffRule, IdentifiedFrequency,
    MeasuredQuantity, PeakOptions, SpectralPeak, UpdatedModel, UpdatingOptions, WelchOptions,
};

use vbi::fe::{discretise, MeshOptions};
use vbi::modal::{solve_modes, ModalOptions, ModeKind};
use vbi::model::BridgeModel;

use crate::commands::OutputFormat;
use crate::input::SourceFile;
use crate::inputs::measurement::{self, added_mass, Channel, K1Source, Measurement};
use crate::output;
use crate::plot::{self, Chart, Series, SeriesStyle};

/// Arguments of `vbi measure`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The measurement description (TOML with a [measurement] table).
    pub file: PathBuf,
    /// Output directory for measure.json and the figures.
    #[arg(long, default_value = "measure_out")]
    pub out: PathBuf,
    /// What to print on standard output (json: the same JSON as measure.json).
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

#[derive(Debug, Serialize)]
struct StaticSeparation {
    filter: &'static str,
    filter_order: usize,
    #[serde(flatten)]
    cutoff: CutoffChoice,
    /// The rule in words.
    explanation: String,
}

#[derive(Debug, Serialize)]
struct MomentReport {
    newton_metres_per_strain: f64,
    static_max_n_m: f64,
    dynamic_max_n_m: f64,
}

#[derive(Debug, Serialize)]
struct CutoffModeReport {
    /// Where K1 came from: "given", "model_mode" (the bridge model, updated when updating was
    /// asked) or "run_summary".
    source: &'static str,
    /// K1 (1-based), when known.
    mode: Option<usize>,
    cutoff_hz: f64,
    dynamic_max: f64,
    daf_before: f64,
    daf_after: f64,
    relative_change: f64,
}

#[derive(Debug, Serialize)]
struct ChannelReport {
    name: String,
    /// CSV column.
    column: String,
    kind: MeasuredQuantity,
    unit: String,
    /// "low_pass" or "influence_line".
    static_method: &'static str,
    /// Low-pass cut-off used [Hz] (for "low_pass").
    cutoff_hz: Option<f64>,
    /// Static maximum, in the channel unit (signed, direction of the static response).
    static_max: f64,
    /// Measured maximum in the same direction, in the channel unit.
    dynamic_max: f64,
    daf: f64,
    time_of_static_max_s: f64,
    time_of_dynamic_max_s: f64,
    section: Option<String>,
    moment: Option<MomentReport>,
    cutoff_mode: Option<CutoffModeReport>,
}

#[derive(Debug, Serialize)]
struct RdmReport {
    section: String,
    deflection_channel: String,
    moment_channel: String,
    daf_deflection: f64,
    daf_moment: f64,
    rdm: f64,
}

#[derive(Debug, Serialize)]
struct SpectrumReport {
    channel: String,
    segment_length: usize,
    fft_length: usize,
    segments: usize,
    resolution_hz: f64,
    peaks: Vec<SpectralPeak>,
}

#[derive(Debug, Serialize)]
struct IdentifiedReport {
    frequency_hz: f64,
    damping_ratio: Option<f64>,
    /// The damping is an upper bound (peak narrower than the spectral resolution).
    damping_resolution_limited: bool,
}

#[derive(Debug, Serialize)]
struct Report {
    provenance: Provenance,
    description: Option<String>,
    sampling_rate_hz: f64,
    samples: usize,
    duration_s: f64,
    /// Vehicle speed [m/s], when given.
    speed_m_s: Option<f64>,
    /// Pass frequency v/L or 1/T_pass [Hz], when given.
    pass_frequency_hz: Option<f64>,
    static_separation: Option<StaticSeparation>,
    channels: Vec<ChannelReport>,
    rdm: Vec<RdmReport>,
    spectra: Vec<SpectrumReport>,
    /// Peaks of the spectrum channel (the first acceleration channel unless named).
    frequency_channel: Option<String>,
    identified_frequencies: Vec<IdentifiedReport>,
    updating: Option<UpdatedModel>,
    /// The bridge model, when named.
    bridge: Option<BridgeReport>,
    figures: Vec<String>,
}

/// The bridge model named in the input, before and after updating.
#[derive(Debug, Serialize)]
struct BridgeReport {
    file: String,
    /// Frequencies of the unmodified model [Hz], ascending (as `vbi modes` lists them).
    frequencies_hz: Vec<f64>,
    kinds: Vec<ModeKind>,
    /// The same modes after updating [Hz] (matched to the unmodified ones by kind and order).
    updated_frequencies_hz: Option<Vec<f64>>,
    /// "elastic_modulus_pa" (grillage) or "flexural_rigidity_n_m2" (continuous beam).
    stiffness_parameter: &'static str,
    stiffness_initial: f64,
    stiffness_updated: Option<f64>,
    /// Added (pavement) mass, summed over the girders [kg/m].
    added_mass_initial_kg_per_m: f64,
    added_mass_updated_kg_per_m: Option<f64>,
}

/// The bridge with its stiffness (E of a grillage, EI of a continuous beam) multiplied by
/// `stiffness` and its added (pavement) mass by `mass`. Grillage: E scales G = E/(2(1+ν)) with
/// it, so every member stiffness scales alike; the pavement mass scales through the concrete
/// pavement and asphalt thicknesses (they carry no stiffness). Continuous beam: elastic
/// support springs are not scaled.
fn scaled_bridge(base: &BridgeModel, stiffness: f64, mass: f64) -> BridgeModel {
    let mut model = base.clone();
    match &mut model {
        BridgeModel::ContinuousBeam(b) => {
            b.section.flexural_rigidity *= stiffness;
            b.added_mass_per_length *= mass;
        }
        BridgeModel::Grillage(g) => {
            g.material.elastic_modulus *= stiffness;
            g.deck.pavement_concrete_thickness *= mass;
            g.deck.asphalt_thickness *= mass;
        }
    }
    model
}

fn stiffness_of(model: &BridgeModel) -> (&'static str, f64) {
    match model {
        BridgeModel::ContinuousBeam(b) => ("flexural_rigidity_n_m2", b.section.flexural_rigidity),
        BridgeModel::Grillage(g) => ("elastic_modulus_pa", g.material.elastic_modulus),
    }
}

/// Frequencies [Hz] and kinds of the lowest `mode_count` modes of a bridge model (default
/// mesh, every kind).
fn bridge_modes(model: &BridgeModel, mode_count: usize) -> Result<(Vec<f64>, Vec<ModeKind>)> {
    let fe = discretise(model, &MeshOptions::default()).context("discretising the bridge")?;
    let basis = solve_modes(
        &fe,
        &ModalOptions {
            mode_count,
            ..ModalOptions::default()
        },
    )
    .context("modal analysis of the bridge")?;
    Ok((
        basis.modes.iter().map(|m| m.frequency_hz()).collect(),
        basis.modes.iter().map(|m| m.kind).collect(),
    ))
}

/// Reorders `frequencies` (of modes of `kinds`) so that position j holds the r-th mode of the
/// kind of `reference[j]`, r being its rank within that kind in `reference`: a scaled model
/// whose modes of different kinds swap order is still compared mode by mode. Stops at the
/// first reference mode without a counterpart.
fn align_by_kind(frequencies: &[f64], kinds: &[ModeKind], reference: &[ModeKind]) -> Vec<f64> {
    let mut out = Vec::with_capacity(reference.len());
    for (j, kind) in reference.iter().enumerate() {
        let rank = reference[..j].iter().filter(|k| *k == kind).count();
        match kinds
            .iter()
            .enumerate()
            .filter(|(_, k)| *k == kind)
            .nth(rank)
        {
            Some((i, _)) => out.push(frequencies[i]),
            None => break,
        }
    }
    out
}

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

fn is_daf_channel(c: &Channel) -> bool {
    c.kind != MeasuredQuantity::Acceleration
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    let file = SourceFile::read(&args.file)?;
    crate::inputs::expect_kind(&file, "measurement", "vbi measure")?;
    let m = measurement::load(&file)?;
    let fs = m.sampling_rate_hz;
    let at = |key: &str| format!("measurement.{key}");

    // Spectra of every acceleration channel.
    let mut spectra = Vec::new();
    let mut psds = Vec::new();
    for c in m
        .channels
        .iter()
        .filter(|c| c.kind == MeasuredQuantity::Acceleration)
    {
        let psd = welch(
            &c.samples,
            fs,
            &WelchOptions {
                segment_length: m.spectrum.segment_length,
                fft_length: m.spectrum.fft_length,
            },
        )
        .with_context(|| format!("spectrum of channel `{}`", c.name))?;
        let peaks = pick_peaks(
            &psd,
            &PeakOptions {
                count: m.spectrum.modes,
                min_frequency_hz: m.spectrum.min_frequency_hz,
                max_frequency_hz: m.spectrum.max_frequency_hz,
                min_prominence_db: m.spectrum.min_prominence_db,
            },
        );
        spectra.push(SpectrumReport {
            channel: c.name.clone(),
            segment_length: psd.segment_length,
            fft_length: 2 * (psd.density.len() - 1),
            segments: psd.segments,
            resolution_hz: psd.resolution_hz(),
            peaks,
        });
        psds.push((c, psd));
    }
    let frequency_channel = m
        .spectrum
        .channel
        .clone()
        .or_else(|| spectra.first().map(|s| s.channel.clone()));
    let identified: Vec<IdentifiedReport> = spectra
        .iter()
        .find(|s| Some(&s.channel) == frequency_channel.as_ref())
        .map(|s| {
            s.peaks
                .iter()
                .map(|p| IdentifiedReport {
                    frequency_hz: p.frequency_hz,
                    damping_ratio: p.damping_ratio,
                    damping_resolution_limited: p.resolution_limited,
                })
                .collect()
        })
        .unwrap_or_default();

    // The bridge model and its modes.
    let base_modes = match &m.bridge {
        Some(b) => Some(
            bridge_modes(&b.model, b.mode_count)
                .with_context(|| format!("bridge model {}", b.path.display()))?,
        ),
        None => None,
    };

    // Model updating.
    let updating = match &m.updating {
        None => None,
        Some(u) => {
            if identified.is_empty() {
                return Err(file
                    .error_at(&at("updating"), "no frequency was identified in the acceleration spectrum; lower spectrum.min_prominence_db or check the band")
                    .into());
            }
            if let Some(kinds) = &u.identified_kinds {
                if kinds.len() != identified.len() {
                    return Err(file
                        .error_at(
                            &at("updating.identified_kinds"),
                            format!("{} kinds given but {} frequencies were identified; give one kind per identified frequency", kinds.len(), identified.len()),
                        )
                        .into());
                }
            }
            let options = UpdatingOptions {
                fit_mass: u.fit_mass,
                ..UpdatingOptions::default()
            };
            let result = match (&u.model_frequencies_hz, &m.bridge, &base_modes) {
                (Some(base), _, _) => {
                    let targets: Vec<IdentifiedFrequency> = identified
                        .iter()
                        .enumerate()
                        .map(|(i, p)| IdentifiedFrequency {
                            frequency_hz: p.frequency_hz,
                            kind: u.identified_kinds.as_ref().map(|k| k[i]),
                        })
                        .collect();
                    let base = base.clone();
                    // Frequencies given as numbers scale as √α with a uniform stiffness scale α.
                    let model = move |s: &[f64]| -> Result<Vec<f64>, String> {
                        Ok(base.iter().map(|f| f * s[0].sqrt()).collect())
                    };
                    update_model(model, u.model_kinds.as_deref(), &targets, &options)
                }
                (None, Some(b), Some((_, kinds))) => {
                    // Without identified kinds, every identified mode is taken as vertical
                    // bending (what a vertical accelerometer on the deck sees first).
                    let targets: Vec<IdentifiedFrequency> = identified
                        .iter()
                        .enumerate()
                        .map(|(i, p)| IdentifiedFrequency {
                            frequency_hz: p.frequency_hz,
                            kind: Some(
                                u.identified_kinds
                                    .as_ref()
                                    .map_or(ModeKind::VerticalBending, |k| k[i]),
                            ),
                        })
                        .collect();
                    let model = |s: &[f64]| -> Result<Vec<f64>, String> {
                        let scaled =
                            scaled_bridge(&b.model, s[0], s.get(1).copied().unwrap_or(1.0));
                        let (f, k) =
                            bridge_modes(&scaled, b.mode_count).map_err(|e| format!("{e:#}"))?;
                        Ok(align_by_kind(&f, &k, kinds))
                    };
                    update_model(model, Some(kinds), &targets, &options)
                }
                _ => unreachable!("checked at input: updating has a model"),
            };
            Some(result.map_err(|e| {
                let key = if u.model_frequencies_hz.is_some() {
                    "updating.model_frequencies_hz"
                } else {
                    "bridge"
                };
                let message = match e {
                    vbi::signal::SignalError::NotIdentifiable { cosine } if m.bridge.is_some() => format!(
                        "the stiffness and the added (pavement) mass of this bridge change the paired frequencies alike (sensitivity cosine {cosine}): these modes cannot separate them; set fit_mass = false, or identify modes that feel the pavement differently (give identified_kinds, for example a torsion mode)"
                    ),
                    other => other.to_string(),
                };
                file.error_at(&at(key), message)
            })?)
        }
    };
    // Model frequencies for the cut-off modes: updated when updating was done.
    let model_frequencies: Option<Vec<f64>> = base_modes.as_ref().map(|(f, _)| match &updating {
        Some(u) if u.updated_frequencies_hz.len() == f.len() => u.updated_frequencies_hz.clone(),
        _ => f.clone(),
    });
    let model_first_bending = base_modes.as_ref().and_then(|(_, kinds)| {
        kinds
            .iter()
            .position(|k| *k == ModeKind::VerticalBending)
            .and_then(|i| model_frequencies.as_ref().map(|f| f[i]))
    });
    let bridge_report = match (&m.bridge, &base_modes) {
        (Some(b), Some((f, kinds))) => {
            let (parameter, stiffness) = stiffness_of(&b.model);
            let updated = updating
                .as_ref()
                .map(|u| scaled_bridge(&b.model, u.stiffness_scale, u.mass_scale.unwrap_or(1.0)));
            Some(BridgeReport {
                file: b.path.display().to_string(),
                frequencies_hz: f.clone(),
                kinds: kinds.clone(),
                updated_frequencies_hz: updating
                    .as_ref()
                    .map(|_| model_frequencies.clone().unwrap_or_default()),
                stiffness_parameter: parameter,
                stiffness_initial: stiffness,
                stiffness_updated: updated.as_ref().map(|u| stiffness_of(u).1),
                added_mass_initial_kg_per_m: added_mass(&b.model),
                added_mass_updated_kg_per_m: updated.as_ref().map(added_mass),
            })
        }
        _ => None,
    };

    // Static separation: one low-pass cut-off for all channels that need it.
    let needs_lowpass = m
        .channels
        .iter()
        .any(|c| is_daf_channel(c) && c.static_reference.is_none());
    let static_separation = if needs_lowpass {
        let cutoff = match m.cutoff_hz {
            Some(f) => CutoffChoice {
                cutoff_hz: f,
                pass_frequency_hz: m.pass_frequency_hz,
                quasi_static_limit_hz: None,
                first_frequency_hz: m
                    .first_frequency_hz
                    .or(identified.first().map(|p| p.frequency_hz))
                    .or(model_first_bending),
                rule: CutoffRule::Given,
                separated: true,
            },
            None => {
                let pass = m.pass_frequency_hz.ok_or_else(|| {
                    file.error_at(
                        &at("filter.cutoff_hz"),
                        "the static cut-off cannot be chosen: give filter.cutoff_hz, or the crossing (speed_kmh and bridge_length_m, or pass_duration_s) and the first bridge frequency",
                    )
                })?;
                let first = m.first_frequency_hz.or(identified.first().map(|p| p.frequency_hz)).or(model_first_bending).ok_or_else(|| {
                    file.error_at(
                        &at("first_frequency_hz"),
                        "the static cut-off needs the first bridge frequency: give first_frequency_hz, or an acceleration channel whose spectrum shows a peak, or a bridge model, or filter.cutoff_hz",
                    )
                })?;
                let choice = automatic_cutoff(pass, first)
                    .map_err(|e| file.error_at(&at("first_frequency_hz"), e.to_string()))?;
                if choice.cutoff_hz >= fs / 2.0 {
                    return Err(file
                        .error_at(&at("filter.cutoff_hz"), format!("the automatic cut-off {} Hz is above the Nyquist frequency; give filter.cutoff_hz", choice.cutoff_hz))
                        .into());
                }
                choice
            }
        };
        let explanation = match cutoff.rule {
            CutoffRule::Given => format!("cut-off {} Hz given in the input", cutoff.cutoff_hz),
            CutoffRule::GeometricMean => format!(
                "f_c = sqrt(f_q * f_1) = sqrt({:.4} * {:.4}) = {:.4} Hz, with f_q = {} * v/L the quasi-static limit and f_1 the first bridge frequency",
                cutoff.quasi_static_limit_hz.unwrap_or(f64::NAN),
                cutoff.first_frequency_hz.unwrap_or(f64::NAN),
                cutoff.cutoff_hz,
                vbi::signal::QUASI_STATIC_HARMONICS
            ),
            CutoffRule::HalfFirstFrequency if cutoff.separated => format!(
                "f_c = f_1/2 = {:.4} Hz: the geometric mean sqrt(f_q * f_1) of the quasi-static limit f_q = {:.4} Hz and f_1 lies above f_1/2, and the cap keeps the first mode attenuated (f_q is still below f_1/2)",
                cutoff.cutoff_hz,
                cutoff.quasi_static_limit_hz.unwrap_or(f64::NAN)
            ),
            CutoffRule::HalfFirstFrequency => format!(
                "f_c = f_1/2 = {:.4} Hz because the quasi-static limit f_q = {:.4} Hz reaches f_1/2: quasi-static and dynamic content overlap, the static part is distorted",
                cutoff.cutoff_hz,
                cutoff.quasi_static_limit_hz.unwrap_or(f64::NAN)
            ),
        };
        Some(StaticSeparation {
            filter: "butterworth_zero_phase",
            filter_order: m.filter_order,
            cutoff,
            explanation,
        })
    } else {
        None
    };

    // DAF per channel.
    let mut channels = Vec::new();
    let mut statics: Vec<(usize, Vec<f64>, Option<Vec<f64>>)> = Vec::new();
    for (ci, c) in m
        .channels
        .iter()
        .enumerate()
        .filter(|(_, c)| is_daf_channel(c))
    {
        let context = || format!("channel `{}`", c.name);
        let (static_part, method, cutoff_hz) = match &c.static_reference {
            Some(line) => {
                let loads = m.vehicle.as_ref().expect("checked at input");
                (
                    static_from_influence_line(&m.time, line, loads).with_context(context)?,
                    "influence_line",
                    None,
                )
            }
            None => {
                let s = static_separation
                    .as_ref()
                    .expect("a low-pass is set up when needed");
                (
                    static_component(&c.samples, fs, m.filter_order, s.cutoff.cutoff_hz)
                        .with_context(context)?,
                    "low_pass",
                    Some(s.cutoff.cutoff_hz),
                )
            }
        };
        let d = measured_daf(&c.samples, &static_part).with_context(context)?;
        let moment = match &c.moment {
            Some(conv) => {
                let f = conv.factor().with_context(context)?;
                Some(MomentReport {
                    newton_metres_per_strain: f,
                    static_max_n_m: d.static_max * f,
                    dynamic_max_n_m: d.dynamic_max * f,
                })
            }
            None => None,
        };
        let k1 = match c.k1 {
            None => None,
            Some(K1Source::Given(f)) => Some(("given", None, f)),
            Some(K1Source::RunSummary { mode, frequency_hz }) => {
                Some(("run_summary", Some(mode), frequency_hz))
            }
            Some(K1Source::ModelMode(mode)) => {
                let frequencies = model_frequencies
                    .as_ref()
                    .expect("checked at input: a bridge");
                let f = *frequencies.get(mode - 1).ok_or_else(|| {
                    file.error_at(
                        &at("bridge_modes"),
                        format!("cut-off mode {mode} of channel `{}` is beyond the {} modes computed; raise bridge_modes", c.name, frequencies.len()),
                    )
                })?;
                if f >= 0.999 * fs / 2.0 {
                    return Err(file
                        .error_at(
                            &at("bridge"),
                            format!("cut-off mode {mode} of channel `{}` has frequency {f} Hz, above the Nyquist frequency {} Hz; choose a lower mode or give k1_cutoff_hz", c.name, fs / 2.0),
                        )
                        .into());
                }
                Some(("model_mode", Some(mode), f))
            }
        };
        let (cutoff_mode, filtered) = match k1 {
            Some((source, mode, k1)) => {
                let r = cutoff_mode_filtering(&c.samples, &static_part, fs, m.filter_order, k1)
                    .with_context(context)?;
                (
                    Some(CutoffModeReport {
                        source,
                        mode,
                        cutoff_hz: k1,
                        dynamic_max: r.after.dynamic_max / c.si_per_unit,
                        daf_before: r.before.daf,
                        daf_after: r.after.daf,
                        relative_change: r.relative_change,
                    }),
                    Some(r.filtered),
                )
            }
            None => (None, None),
        };
        channels.push(ChannelReport {
            name: c.name.clone(),
            column: c.column.clone(),
            kind: c.kind,
            unit: c.unit.clone(),
            static_method: method,
            cutoff_hz,
            static_max: d.static_max / c.si_per_unit,
            dynamic_max: d.dynamic_max / c.si_per_unit,
            daf: d.daf,
            time_of_static_max_s: m.time[d.static_max_index],
            time_of_dynamic_max_s: m.time[d.dynamic_max_index],
            section: c.section.clone(),
            moment,
            cutoff_mode,
        });
        statics.push((ci, static_part, filtered));
    }

    // RDM per section: deflection channel against strain or moment channel.
    let mut rdms = Vec::new();
    for d in channels
        .iter()
        .filter(|c| c.kind == MeasuredQuantity::Deflection && c.section.is_some())
    {
        for mo in channels.iter().filter(|c| {
            matches!(
                c.kind,
                MeasuredQuantity::Strain | MeasuredQuantity::BendingMoment
            ) && c.section == d.section
        }) {
            rdms.push(RdmReport {
                section: d.section.clone().unwrap_or_default(),
                deflection_channel: d.name.clone(),
                moment_channel: mo.name.clone(),
                daf_deflection: d.daf,
                daf_moment: mo.daf,
                rdm: rdm(d.daf, mo.daf)?,
            });
        }
    }

    // Figures.
    output::create_output_dir(&args.out)?;
    let mut figures = Vec::new();
    let step = (m.time.len() / 4000).max(1);
    let points = |v: &[f64], scale: f64| -> Vec<(f64, f64)> {
        m.time
            .iter()
            .zip(v)
            .step_by(step)
            .map(|(t, x)| (*t, x / scale))
            .collect()
    };
    for (ci, c) in m.channels.iter().enumerate() {
        let mut series = vec![Series {
            label: "measured".into(),
            points: points(&c.samples, c.si_per_unit),
            style: SeriesStyle::Thin,
        }];
        if let Some((_, s, filtered)) = statics.iter().find(|(i, _, _)| *i == ci) {
            if let Some(f) = filtered {
                series.push(Series::line(
                    format!(
                        "low-pass at K1 ({:.2} Hz)",
                        channels
                            .iter()
                            .find(|r| r.name == c.name)
                            .and_then(|r| r.cutoff_mode.as_ref())
                            .map_or(0.0, |k| k.cutoff_hz)
                    ),
                    points(f, c.si_per_unit),
                ));
            }
            series.push(Series::line("static", points(s, c.si_per_unit)));
        }
        let chart = Chart {
            title: format!("{} ({:?})", c.name, c.kind).to_lowercase(),
            x_label: "time [s]".into(),
            y_label: format!("{} [{}]", c.name, c.unit),
            series,
            ..Chart::default()
        };
        let stem = args.out.join(format!("signal_{}", file_stem(&c.name)));
        plot::write_chart(&chart, &stem)?;
        figures.push(format!("signal_{}", file_stem(&c.name)));
    }
    for ((c, psd), report) in psds.iter().zip(&spectra) {
        // Up to twice the search band (the whole band when unbounded), in dB: the modes stay
        // readable next to the noise floor.
        let f_max = (2.0 * m.spectrum.max_frequency_hz).min(fs / 2.0);
        let db = |p: f64| 10.0 * p.max(1e-300).log10();
        let line: Vec<(f64, f64)> = psd
            .frequency_hz
            .iter()
            .zip(&psd.density)
            .skip(1)
            .filter(|(f, _)| **f <= f_max)
            .map(|(f, p)| (*f, db(*p)))
            .collect();
        let peaks: Vec<(f64, f64)> = report
            .peaks
            .iter()
            .map(|p| (p.frequency_hz, db(p.density)))
            .collect();
        let chart = Chart {
            title: format!("Welch PSD of {} with picked peaks", c.name),
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
        };
        let stem = args.out.join(format!("spectrum_{}", file_stem(&c.name)));
        plot::write_chart(&chart, &stem)?;
        figures.push(format!("spectrum_{}", file_stem(&c.name)));
    }

    let mut hasher = Sha256::new();
    hasher.update(file.text.as_bytes());
    hasher.update(
        std::fs::read(&m.csv_path).with_context(|| format!("reading {}", m.csv_path.display()))?,
    );
    let report = Report {
        provenance: Provenance {
            vbi_version: env!("CARGO_PKG_VERSION"),
            input: file.name(),
            csv: m.csv_path.display().to_string(),
            input_sha256: format!("{:x}", hasher.finalize()),
        },
        description: m.description.clone(),
        sampling_rate_hz: fs,
        samples: m.time.len(),
        duration_s: (m.time.len() - 1) as f64 / fs,
        speed_m_s: m.speed,
        pass_frequency_hz: m.pass_frequency_hz,
        static_separation,
        channels,
        rdm: rdms,
        spectra,
        frequency_channel,
        identified_frequencies: identified,
        updating,
        bridge: bridge_report,
        figures,
    };
    output::write_json(&args.out.join("measure.json"), &report)?;
    match args.format {
        OutputFormat::Json => println!("{}", serde_json::to_string_pretty(&report)?),
        OutputFormat::Table => print_table(&report, &m, &args.out),
    }
    Ok(())
}

fn print_table(r: &Report, m: &Measurement, out: &std::path::Path) {
    println!(
        "{} samples at {} Hz ({:.2} s)",
        r.samples, r.sampling_rate_hz, r.duration_s
    );
    if let Some(s) = &r.static_separation {
        println!(
            "static part: zero-phase Butterworth order {}, {}",
            s.filter_order, s.explanation
        );
    }
    if !r.channels.is_empty() {
        println!(
            "{:<20} {:<15} {:>12} {:>12} {:>8} {:>10} {:>10}",
            "channel", "kind", "static max", "dynamic max", "DAF", "K1 [Hz]", "DAF at K1"
        );
        for c in &r.channels {
            let (k1, after) = c
                .cutoff_mode
                .as_ref()
                .map_or(("-".to_string(), "-".to_string()), |k| {
                    (format!("{:.2}", k.cutoff_hz), format!("{:.4}", k.daf_after))
                });
            println!(
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
        println!(
            "RDM at {}: {:.4} / {:.4} = {:.4}",
            x.section, x.daf_deflection, x.daf_moment, x.rdm
        );
    }
    if let Some(ch) = &r.frequency_channel {
        println!("identified frequencies ({ch}):");
        for (i, p) in r.identified_frequencies.iter().enumerate() {
            let z = p.damping_ratio.map_or("-".to_string(), |z| {
                let bound = if p.damping_resolution_limited {
                    " (upper bound: resolution-limited)"
                } else {
                    ""
                };
                format!("{:.2} %{bound}", 100.0 * z)
            });
            println!("  mode {}: {:.3} Hz, damping {z}", i + 1, p.frequency_hz);
        }
    }
    if let Some(u) = &r.updating {
        let mass = u
            .mass_scale
            .map_or(String::new(), |b| format!(", added-mass scale {b:.4}"));
        println!(
            "model updating: stiffness scale {:.4}{mass}; RMS frequency error {:.4} Hz -> {:.4} Hz",
            u.stiffness_scale, u.initial_rms_error_hz, u.updated_rms_error_hz
        );
        if let Some(b) = &r.bridge {
            if let Some(k) = b.stiffness_updated {
                println!(
                    "  {}: {:.6e} -> {:.6e}",
                    b.stiffness_parameter, b.stiffness_initial, k
                );
            }
        }
        for p in &u.pairs {
            println!(
                "  mode {}: measured {:.3} Hz, model {:.3} -> {:.3} Hz",
                p.model_index + 1,
                p.identified_hz,
                p.initial_hz,
                p.updated_hz
            );
        }
    }
    if let Some(v) = m.speed {
        println!("vehicle speed {:.2} m/s ({:.1} km/h)", v, v * 3.6);
    }
    println!("wrote {}", out.join("measure.json").display());
}
