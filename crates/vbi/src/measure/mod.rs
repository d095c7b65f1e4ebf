//! The field-measurement stage (the paper's §6): a [`Measurement`] in, a [`MeasurementResult`]
//! out. Spectra of the acceleration channels and the frequencies they identify; the bridge
//! model's modes, updated to the identified frequencies when asked; one static separation
//! (zero-phase low-pass or influence line) per channel; the DAF of every channel (Eq. 1 on
//! measured signals), the effect of low-pass filtering at the cut-off mode K1, and the RDM of
//! each section.
//!
//! ```text
//! Measurement --spectra--> identified frequencies --updating--> model frequencies (K1)
//!             --static separation--> static parts --DAF, K1 filtering--> channels --> RDM
//! ```
//!
//! Nothing here reads or writes a file: `vbi measure` reads the measurement through `vbi-input`
//! and writes this result as `measure.json` and figures; the Python package returns it.

mod calibration;
mod channels;
mod codes;
mod detection;
mod forced_content;
mod influence_lines;
pub mod measurement;
mod preparation;
mod record_weighing;
mod separation;
mod spectra;
mod static_references;
mod uncertainty;
mod updating;
mod warnings;
mod weighing;
mod weighing_accuracy;

use serde::Serialize;

pub(crate) use crate::crossing::error_chain;
use crate::crossing::PipelineError;
use crate::modal::ModeKind;
use crate::signal::{
    CutoffChoice, MeasuredQuantity, Psd, SeparationCheck, SignalError, SpectralPeak, UpdatedModel,
};
use measurement::SpectrumWindow;
pub use measurement::{CalibrationParameter, Measurement, WeighingRequest};

pub use calibration::{
    CalibratedMode, CalibratedParameter, Calibration, MAXIMUM_CONDITION, MINIMUM_PAIRING_MAC,
    SHAPE_WEIGHT,
};
pub use detection::{
    check_speed, detect_entry, DetectedEntry, SpeedCheck, MINIMUM_EXPLAINED_VARIANCE,
    SPEED_TOLERANCE_WITHOUT_AXLES, SPEED_TOLERANCE_WITH_AXLES,
};
pub use forced_content::{
    ForcedContentCheck, FORCED_CONTENT_EXTRA_MODES, FORCED_CONTENT_RATIO, FORCED_CONTENT_WINDOW,
};
pub use influence_lines::{
    crawl_influence_line, model_influence_line, CrawlInfluenceLine, CRAWL_SMOOTHING,
    MAX_CRAWL_NODES, MIN_CRAWL_NODES, MODEL_LINE_SPACING, SAMPLES_PER_NODE,
};
pub use preparation::{
    crossing_window, BaselineCorrection, CrossingWindow, RecordPreparation, ASSUMED_VEHICLE_LENGTH,
    FREE_VIBRATION_MARGIN,
};
pub use spectra::MINIMUM_FREE_VIBRATION;
pub use uncertainty::{
    lowpass_noise_gain, second_difference_noise, DafUncertainty, StaticMethodDaf,
};
pub use updating::{added_mass_per_length, scaled_bridge};
pub use warnings::{
    MeasureWarning, MeasureWarningKind, StaticAlternative, IMPLAUSIBLE_DAMPING_RATIO,
};
pub use weighing::{
    weigh, GivenLoads, VehicleWeighing, WeighingChannel, WeighingSensor, WeighingStart,
    ENTRY_SEARCH, ILL_CONDITIONED, WEIGHING_CUTOFF_FRACTION,
};
pub use weighing_accuracy::{
    axle_groups, class_name, confidence_level, criterion_class, minimum_confidence, system_class,
    tolerance, weighing_accuracy, CriterionClass, Environment, TestConditions, WeighingAccuracy,
    WeighingCriterion, GROUP_SPACING, MINIMUM_RESULTS,
};

/// Errors of the measurement stage.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeasureError {
    /// A value of the measurement that the processing cannot use. `field` is its key under
    /// `measurement.` (for example `filter.cutoff_hz`), so that a reader of the file can point
    /// at it.
    #[error("{message}")]
    Input {
        /// Dotted key under `measurement.`.
        field: String,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// The spectrum of an acceleration channel failed.
    #[error("spectrum of channel `{channel}`")]
    Spectrum {
        /// The channel's name.
        channel: String,
        /// Why.
        #[source]
        source: SignalError,
    },
    /// The static separation, DAF or K1 filtering of a channel failed.
    #[error("channel `{channel}`")]
    Channel {
        /// The channel's name.
        channel: String,
        /// Why.
        #[source]
        source: SignalError,
    },
    /// The bridge model could not be discretised or its modes solved.
    #[error("bridge model {label}")]
    BridgeModel {
        /// The bridge's label.
        label: String,
        /// Why.
        #[source]
        source: PipelineError,
    },
    /// Another signal-processing failure.
    #[error(transparent)]
    Signal(#[from] SignalError),
}

impl MeasureError {
    fn input(field: &str, message: impl Into<String>) -> Self {
        Self::Input {
            field: field.to_string(),
            message: message.into(),
        }
    }
}

/// The static separation used for the channels that need a low-pass.
#[derive(Debug, Clone, Serialize)]
pub struct StaticSeparation {
    /// "butterworth_zero_phase".
    pub filter: &'static str,
    /// Butterworth order.
    pub filter_order: usize,
    /// The cut-off and the rule that chose it.
    #[serde(flatten)]
    pub cutoff: CutoffChoice,
    /// The rule in words.
    pub explanation: String,
    /// Why `separated` is what it is: the rule's verdict and every channel's separation check
    /// (true only when the quasi-static and the dynamic content are apart and the low-pass
    /// keeps the peak of every channel's predicted static response).
    pub reason: String,
}

/// A strain channel's static and dynamic maxima as bending moments.
#[derive(Debug, Clone, Serialize)]
pub struct MeasuredMoment {
    /// Conversion factor [N·m per unit strain].
    pub newton_metres_per_strain: f64,
    /// Static maximum [N·m].
    pub static_max_n_m: f64,
    /// Dynamic maximum [N·m].
    pub dynamic_max_n_m: f64,
}

/// The effect of low-pass filtering a channel at the frequency of its cut-off mode K1.
#[derive(Debug, Clone, Serialize)]
pub struct CutoffModeEffect {
    /// Where K1 came from: "given", "model_mode" (the bridge model, updated when updating was
    /// asked) or "run_summary".
    pub source: &'static str,
    /// K1 (1-based), when known.
    pub mode: Option<usize>,
    /// Frequency of mode K1 [Hz].
    pub mode_frequency_hz: f64,
    /// The filter's cut-off [Hz], above f_K1 so that mode K1 passes with gain `mode_gain`.
    pub cutoff_hz: f64,
    /// Amplitude gain of the zero-phase filter at f_K1 [-] (0.99).
    pub mode_gain: f64,
    /// Dynamic maximum of the filtered signal, in the channel unit.
    pub dynamic_max: f64,
    /// DAF of the unfiltered signal.
    pub daf_before: f64,
    /// DAF of the filtered signal.
    pub daf_after: f64,
    /// (after − before) / before.
    pub relative_change: f64,
}

/// The DAF of one measured channel.
#[derive(Debug, Clone, Serialize)]
pub struct ChannelDaf {
    /// Channel name.
    pub name: String,
    /// CSV column.
    pub column: String,
    /// What it records.
    pub kind: MeasuredQuantity,
    /// Unit of the values below.
    pub unit: String,
    /// "low_pass", "crawl_run", "influence_line" (given), "influence_line_model" (the bridge
    /// model's at the sensor) or "influence_line_crawl" (calibrated from the crawl run).
    pub static_method: &'static str,
    /// Low-pass cut-off used [Hz] (for "low_pass").
    pub cutoff_hz: Option<f64>,
    /// The low-pass checked on the static response the channel's influence-line shape
    /// predicts (for "low_pass", when the span and the speed are known).
    pub separation_check: Option<SeparationCheck>,
    /// Static maximum, in the channel unit (signed, direction of the static response).
    pub static_max: f64,
    /// Measured maximum in the same direction, in the channel unit.
    pub dynamic_max: f64,
    /// dynamic_max / static_max.
    pub daf: f64,
    /// Time of the static maximum [s].
    pub time_of_static_max_s: f64,
    /// Time of the dynamic maximum [s].
    pub time_of_dynamic_max_s: f64,
    /// Section label (for the RDM).
    pub section: Option<String>,
    /// The maxima as bending moments (strain channels with a conversion).
    pub moment: Option<MeasuredMoment>,
    /// Low-pass filtering at K1, when asked.
    pub cutoff_mode: Option<CutoffModeEffect>,
    /// The DAF by every static method the record allows (the one above among them, `chosen`).
    pub static_methods: Vec<StaticMethodDaf>,
    /// The DAF's standard uncertainty from the noise and the static separation.
    pub uncertainty: Option<DafUncertainty>,
    /// The design codes' DAF (1 + IM) at the gauge's section, beside the measured one
    /// (docs/design-codes.md); empty when the loaded span is unknown.
    pub design_codes: Vec<crate::codes::CodeImpactFactor>,
}

/// RDM = DAF_u / DAF_M of one section (the paper's Eq. 31).
#[derive(Debug, Clone, Serialize)]
pub struct MeasuredRdm {
    /// Section label.
    pub section: String,
    /// The deflection channel.
    pub deflection_channel: String,
    /// The strain or moment channel.
    pub moment_channel: String,
    /// DAF of deflection.
    pub daf_deflection: f64,
    /// DAF of moment.
    pub daf_moment: f64,
    /// Their ratio.
    pub rdm: f64,
    /// Its standard uncertainty, RDM·√((u_u/DAF_u)² + (u_M/DAF_M)²) [-], when both DAFs have
    /// one.
    pub uncertainty: Option<f64>,
    /// Whether the side of 1 is measured: |RDM − 1| > 2·uncertainty.
    pub side_of_one_resolved: Option<bool>,
}

/// The Welch spectrum of an acceleration channel and its picked peaks.
#[derive(Debug, Clone, Serialize)]
pub struct ChannelSpectrum {
    /// Channel name.
    pub channel: String,
    /// The part of the record it was taken from.
    pub window: SpectrumWindow,
    /// Time of its first sample [s].
    pub start_time_s: f64,
    /// Welch segment length [samples].
    pub segment_length: usize,
    /// FFT length [samples].
    pub fft_length: usize,
    /// Segments averaged.
    pub segments: usize,
    /// Frequency resolution [Hz].
    pub resolution_hz: f64,
    /// Picked peaks, ascending in frequency.
    pub peaks: Vec<SpectralPeak>,
}

/// A frequency identified from the spectrum.
#[derive(Debug, Clone, Serialize)]
pub struct IdentifiedMode {
    /// Frequency [Hz].
    pub frequency_hz: f64,
    /// Damping ratio [-] by the half-power bandwidth, when measurable.
    pub damping_ratio: Option<f64>,
    /// The damping is an upper bound (peak narrower than the spectral resolution).
    pub damping_resolution_limited: bool,
    /// Standard deviation of the frequency over the subspace model orders [Hz] (subspace
    /// identification only; a lower bound of its statistical uncertainty).
    pub frequency_std_hz: Option<f64>,
    /// Standard deviation of the damping ratio over the model orders [-] (subspace only).
    pub damping_std: Option<f64>,
    /// Mode shape at the acceleration channels ([`SubspaceSummary::channels`]), largest
    /// component +1 (subspace only).
    pub shape: Option<Vec<f64>>,
    /// Modal phase collinearity of the shape [-] (1 for a real mode; subspace only).
    pub modal_phase_collinearity: Option<f64>,
}

/// The subspace identification behind the identified modes.
#[derive(Debug, Clone, Serialize)]
pub struct SubspaceSummary {
    /// The acceleration channels, in the order of the shapes' components.
    pub channels: Vec<String>,
    /// "free_response" (ERA of the free vibration) or "output_only" (SSI-COV of the record).
    pub method: crate::signal::SubspaceMethod,
    /// Time of the first sample used [s].
    pub start_time_s: f64,
    /// Block rows of the Hankel matrix.
    pub block_rows: usize,
    /// Highest model order tried.
    pub max_order: usize,
    /// The stabilisation diagram: every pole kept, by order.
    pub diagram: Vec<crate::signal::StabilisationPole>,
}

/// The bridge model, before and after updating.
#[derive(Debug, Clone, Serialize)]
pub struct BridgeUpdate {
    /// The bridge's label (its file).
    pub file: String,
    /// Frequencies of the unmodified model [Hz], ascending (as `vbi modes` lists them).
    pub frequencies_hz: Vec<f64>,
    /// Their kinds.
    pub kinds: Vec<ModeKind>,
    /// The same modes after updating [Hz] (matched to the unmodified ones by kind and order).
    pub updated_frequencies_hz: Option<Vec<f64>>,
    /// "elastic_modulus_pa" (grillage) or "flexural_rigidity_n_m2" (continuous beam).
    pub stiffness_parameter: &'static str,
    /// The stiffness parameter before updating [Pa or N·m²].
    pub stiffness_initial: f64,
    /// After updating.
    pub stiffness_updated: Option<f64>,
    /// Added (pavement) mass, summed over the girders [kg/m].
    pub added_mass_initial_kg_per_m: f64,
    /// After updating [kg/m].
    pub added_mass_updated_kg_per_m: Option<f64>,
}

/// What the measurement gives, as `measure.json` holds it (without its provenance and figures).
#[derive(Debug, Clone, Serialize)]
pub struct MeasurementSummary {
    /// Free text.
    pub description: Option<String>,
    /// Sampling rate [Hz].
    pub sampling_rate_hz: f64,
    /// Samples per channel.
    pub samples: usize,
    /// (samples − 1) / f_s [s].
    pub duration_s: f64,
    /// Vehicle speed [m/s], when given.
    pub speed_m_s: Option<f64>,
    /// Pass frequency v/L or 1/T_pass [Hz], when given.
    pub pass_frequency_hz: Option<f64>,
    /// The stated speed against the one the record's response shows, when both can be read
    /// ([`check_speed`]).
    pub speed_check: Option<SpeedCheck>,
    /// The crossing window and the baseline correction.
    pub preparation: RecordPreparation,
    /// The low-pass static separation, when a channel needs it.
    pub static_separation: Option<StaticSeparation>,
    /// DAF per channel (every channel but accelerations).
    pub channels: Vec<ChannelDaf>,
    /// RDM per section.
    pub rdm: Vec<MeasuredRdm>,
    /// Spectra of the acceleration channels.
    pub spectra: Vec<ChannelSpectrum>,
    /// Peaks of the spectrum channel (the first acceleration channel unless named).
    pub frequency_channel: Option<String>,
    /// How they were identified: "welch_peaks" (the spectrum's peaks),
    /// "matrix_pencil_free_vibration" (the free decay after the vehicle has left),
    /// "subspace_free_vibration" (ERA of every acceleration channel's free vibration) or
    /// "subspace_whole_record" (SSI-COV of the whole record).
    pub identification: &'static str,
    /// The identified frequencies.
    pub identified_frequencies: Vec<IdentifiedMode>,
    /// Modes identified within 5 % of a frequency of the vehicle
    /// (`[measurement.vehicle] frequencies_hz`) and left out as its forced content.
    pub vehicle_modes: Vec<IdentifiedMode>,
    /// Modes of an identification that read the crossing whose amplitude after the vehicle
    /// has left falls below 10 % of their amplitude while it crossed: the crossing's forced
    /// content (the vehicle's own modes, the quasi-static response's harmonics), left out.
    pub forced_modes: Vec<IdentifiedMode>,
    /// Whether forced content was looked for: "not_needed" (only the free vibration was
    /// read), "checked", or "not_possible" (no exit time or less than 1 s recorded after it).
    pub forced_content_check: ForcedContentCheck,
    /// The subspace identification, when used.
    pub subspace: Option<SubspaceSummary>,
    /// Calibration of the bridge model with several parameters, when asked.
    pub calibration: Option<Calibration>,
    /// Model updating, when asked.
    pub updating: Option<UpdatedModel>,
    /// The bridge model, when named.
    pub bridge: Option<BridgeUpdate>,
    /// The vehicle weighed from the record (bridge weigh-in-motion), when asked.
    pub weighing: Option<VehicleWeighing>,
    /// What the reader must know before using these numbers ([`MeasureWarning`]): a DAF on a
    /// static part whose own check failed, frequencies that may be forced content, implausible
    /// damping.
    pub warnings: Vec<MeasureWarning>,
}

/// The signals behind a channel's DAF, for figures and further processing.
#[derive(Debug, Clone)]
pub struct ChannelSignals {
    /// Index of the channel in [`Measurement::channels`].
    pub channel_index: usize,
    /// The static part [SI].
    pub static_part: Vec<f64>,
    /// The signal low-pass filtered at K1 [SI], when asked.
    pub filtered_at_cutoff_mode: Option<Vec<f64>>,
}

/// The result of the measurement stage.
#[derive(Debug, Clone)]
pub struct MeasurementResult {
    /// The numbers.
    pub summary: MeasurementSummary,
    /// Static parts (and K1-filtered signals) of the DAF channels, in channel order.
    pub signals: Vec<ChannelSignals>,
    /// Welch densities, one per entry of [`MeasurementSummary::spectra`].
    pub densities: Vec<Psd>,
    /// The record as analysed: the measurement with its baseline corrected.
    pub record: Measurement,
}

/// What [`measure`] decides of a measurement before any spectrum: its arrays' shape, the
/// vehicle's entry (searched for when asked), the crossing window and the baseline windows,
/// and the same of its crawl run. Cheap (a copy of the record); `vbi check` runs it so that it
/// refuses what `vbi measure` would refuse there, with the same message (issue 47).
pub fn check_preparation(measurement: &Measurement) -> Result<(), MeasureError> {
    check_shape(measurement)?;
    record_weighing::check_request(measurement)?;
    preparation::prepare(measurement).map(|_| ())
}

/// Processes a measurement: spectra and identified frequencies, the bridge model's modes and
/// their updating, the static separation, the DAF of every channel with its K1 filtering, and
/// the RDM of every section that has a deflection and a strain or moment channel.
pub fn measure(measurement: &Measurement) -> Result<MeasurementResult, MeasureError> {
    check_shape(measurement)?;
    record_weighing::check_request(measurement)?;
    let (mut prepared, preparation) = preparation::prepare(measurement)?;
    let m = &prepared;
    let (spectra, densities) = spectra::spectra(m)?;
    let frequency_channel = m
        .spectrum
        .channel
        .clone()
        .or_else(|| spectra.first().map(|s| s.channel.clone()));
    let spectra::Identified {
        modes: identified,
        method: identification,
        subspace,
        excluded: vehicle_modes,
        forced: forced_modes,
        forced_check: forced_content_check,
    } = spectra::identified(m, &spectra, frequency_channel.as_ref())?;
    let calibration = calibrate_if_asked(m, &identified, subspace.as_ref())?;
    let mut model = updating::model_frequencies(m, &identified, calibration.is_some())?;
    if let Some(c) = &calibration {
        model.calibrated(c);
    }
    let weighing = record_weighing::weigh_record(
        m,
        model.model.as_ref(),
        model.fitted,
        preparation.detected_entry.is_some(),
        record_weighing::weighing_first_frequency(m, &identified, model.first_bending_hz()),
    )?;
    // Without given axle loads, the weighed ones are the vehicle's for every influence-line
    // static part.
    if let (Some(w), Some(vehicle)) = (&weighing, prepared.vehicle.as_mut()) {
        if !prepared
            .weighing
            .as_ref()
            .is_some_and(|r| r.axle_loads_given)
        {
            let unresolved = w.axle_loads_n.iter().any(|&a| a <= 0.0) || !w.well_conditioned;
            if unresolved {
                return Err(MeasureError::input(
                    "vehicle.axle_loads_kn",
                    "the record does not resolve the vehicle's axles (an axle weighs zero or less, or the least squares cannot tell them apart), so the weighed loads cannot stand in for them: give axle_loads_kn",
                ));
            }
            vehicle.axle_loads = w.axle_loads_n.clone();
        }
    }
    let m = &prepared;
    let first = separation::first_frequency(m, &identified, model.first_bending_hz());
    let mut static_separation = separation::static_separation(m, first)?;
    let lines = influence_lines::channel_lines(m, model.model.as_ref(), model.fitted)?;
    let (mut channels, signals) = channels::channel_dafs(
        m,
        static_separation.as_ref(),
        model.frequencies.as_deref(),
        first,
        &lines,
    )?;
    for (daf, channel) in channels
        .iter_mut()
        .zip(m.channels.iter().filter(|c| c.has_daf()))
    {
        daf.design_codes = codes::channel_codes(m, channel, &identified);
    }
    if let Some(s) = static_separation.as_mut() {
        separation::conclude(s, &channels);
    }
    let rdm = channels::section_rdms(&channels)?;
    let summary = MeasurementSummary {
        description: m.description.clone(),
        sampling_rate_hz: m.sampling_rate_hz,
        samples: m.time.len(),
        duration_s: (m.time.len() - 1) as f64 / m.sampling_rate_hz,
        speed_m_s: m.speed,
        pass_frequency_hz: m.pass_frequency_hz,
        speed_check: detection::check_speed(m),
        preparation,
        static_separation,
        channels,
        rdm,
        spectra,
        frequency_channel,
        identification,
        identified_frequencies: identified,
        vehicle_modes,
        forced_modes,
        forced_content_check,
        subspace,
        calibration,
        updating: model.updating,
        bridge: model.bridge,
        weighing,
        warnings: Vec::new(),
    };
    let summary = MeasurementSummary {
        warnings: warnings::warnings_of(&summary),
        ..summary
    };
    Ok(MeasurementResult {
        summary,
        signals,
        densities,
        record: prepared,
    })
}

/// Calibration with the parameters of `updating.parameters`, when given: the sensors are the
/// acceleration channels with a location (their shapes' components from the subspace
/// identification).
fn calibrate_if_asked(
    m: &Measurement,
    identified: &[IdentifiedMode],
    subspace: Option<&SubspaceSummary>,
) -> Result<Option<Calibration>, MeasureError> {
    let Some(spec) = m.updating.as_ref().filter(|u| !u.parameters.is_empty()) else {
        return Ok(None);
    };
    let Some(bridge) = &m.bridge else {
        return Err(MeasureError::input(
            "updating.parameters",
            "calibration re-solves the bridge model: give bridge = \"file.toml\"",
        ));
    };
    // The shapes' components that belong to located sensors, in the subspace's channel order.
    let mut sensors = Vec::new();
    let mut components = Vec::new();
    if let Some(s) = subspace {
        for (k, name) in s.channels.iter().enumerate() {
            let location = m
                .channels
                .iter()
                .find(|c| &c.name == name)
                .and_then(|c| c.location);
            if let Some(location) = location {
                sensors.push(location);
                components.push(k);
            }
        }
    }
    let located: Vec<IdentifiedMode> = identified
        .iter()
        .map(|p| IdentifiedMode {
            shape: p
                .shape
                .as_ref()
                .map(|shape| components.iter().map(|&k| shape[k]).collect()),
            ..p.clone()
        })
        .collect();
    calibration::calibrate(bridge, &spec.parameters, &located, &sensors).map(Some)
}

/// The measurement's arrays fit together: at least two samples at a positive, finite rate, and
/// one sample per time in every channel.
fn check_shape(m: &Measurement) -> Result<(), MeasureError> {
    if !(m.sampling_rate_hz.is_finite() && m.sampling_rate_hz > 0.0) {
        return Err(SignalError::BadSamplingRate {
            sampling_rate_hz: m.sampling_rate_hz,
        }
        .into());
    }
    if m.time.len() < 2 {
        return Err(SignalError::SignalTooShort {
            samples: m.time.len(),
            required: 2,
        }
        .into());
    }
    match m.channels.iter().find(|c| c.samples.len() != m.time.len()) {
        Some(c) => Err(MeasureError::input(
            "channels",
            format!(
                "channel `{}` has {} samples for {} times; expected one sample per time",
                c.name,
                c.samples.len(),
                m.time.len()
            ),
        )),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests;
