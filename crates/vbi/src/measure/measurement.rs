//! The typed input of the field-measurement stage ([`super::measure`]): measured channels in SI
//! on one time axis, and how to process them (static separation, spectra, cut-off-mode
//! filtering, model updating), as the paper's §6 does for its load tests.
//!
//! A [`Measurement`] holds values, not files: `vbi-input` reads a `[measurement]` TOML file and
//! its CSV into one, a Python caller may build one from arrays.

use serde::{Deserialize, Serialize};

use crate::modal::ModeKind;
use crate::model::BridgeModel;
use crate::signal::{MeasuredQuantity, MovingLoads, SampledInfluenceLine, StrainToMoment};

/// One measured channel, in SI.
#[derive(Debug, Clone)]
pub struct Channel {
    /// Name (used in outputs).
    pub name: String,
    /// Where it came from (the CSV column).
    pub column: String,
    /// What it records.
    pub kind: MeasuredQuantity,
    /// Unit as given in the file (for reports).
    pub unit: String,
    /// SI value of one unit (1e-3 for mm).
    pub si_per_unit: f64,
    /// Samples in SI: m, strain [-], N·m or m/s².
    pub samples: Vec<f64>,
    /// Section label pairing deflection and strain/moment channels for the RDM.
    pub section: Option<String>,
    /// The cut-off mode K1 for this channel: a frequency, or a mode of the bridge model.
    pub k1: Option<K1Source>,
    /// Strain-to-moment conversion (strain channels).
    pub moment: Option<StrainToMoment>,
    /// The channel's static reference when it is an influence line (else the crawl run when
    /// there is one, else the low-pass).
    pub static_reference: Option<StaticReference>,
    /// Position of the sensor's section in the loaded span, as a fraction of the span (0.5 at
    /// mid-span): where the separation check puts the kink of a moment influence line.
    pub position_in_span: f64,
    /// Where the sensor sits on the deck, when given: the model's mode shapes are read there
    /// for pairing modes by MAC and for calibration.
    pub location: Option<SensorLocation>,
}

/// A channel's influence-line static reference: the static part is the line under the
/// vehicle's static axle loads, R_s(t) = Σ_a P_a·IL(v·(t − t₀) − d_a).
#[derive(Debug, Clone, PartialEq)]
pub enum StaticReference {
    /// An influence line given with the record [SI channel unit per N].
    Given(SampledInfluenceLine),
    /// The bridge model's influence line at the sensor's `location`, of the model updated or
    /// calibrated to the identified modes when the measurement asks for it
    /// ([`super::model_influence_line`]).
    BridgeModel,
    /// The influence line calibrated from the crawl run by least squares under the vehicle's
    /// axle loads ([`super::crawl_influence_line`]).
    CrawlRun,
}

/// Where the vehicle's wheels run across the deck: the line the bridge model's influence
/// lines are read along.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct VehicleTrack {
    /// Lateral position y of the vehicle's centre line [m] from the deck centreline, positive
    /// to the left; 0 by default.
    pub lateral_position: f64,
    /// Distance between the wheels of an axle [m]; 0 (one wheel line) by default.
    pub track_width: f64,
}

impl VehicleTrack {
    /// The wheel lines (lateral position [m], share of the axle load [-]).
    pub fn wheel_lines(&self) -> Vec<(f64, f64)> {
        if self.track_width > 0.0 {
            let half = self.track_width / 2.0;
            vec![
                (self.lateral_position - half, 0.5),
                (self.lateral_position + half, 0.5),
            ]
        } else {
            vec![(self.lateral_position, 1.0)]
        }
    }
}

/// A sensor's place on the deck.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SensorLocation {
    /// Longitudinal position x [m] from the first support, along the girders.
    pub position: f64,
    /// Lateral position y [m] from the deck centreline, positive to the left.
    pub lateral_position: f64,
}

impl Channel {
    /// Whether the channel gets a DAF: every quantity but acceleration (whose spectrum gives
    /// the frequencies instead).
    pub fn has_daf(&self) -> bool {
        self.kind != MeasuredQuantity::Acceleration
    }
}

/// Spectrum options.
#[derive(Debug, Clone)]
pub struct SpectrumSpec {
    /// Channel whose peaks are "the identified frequencies" (an acceleration channel); the
    /// first acceleration channel when `None`.
    pub channel: Option<String>,
    /// Welch segment length [samples].
    pub segment_length: usize,
    /// FFT length [samples].
    pub fft_length: Option<usize>,
    /// Number of modes to pick.
    pub modes: usize,
    /// Band searched, lower end [Hz].
    pub min_frequency_hz: f64,
    /// Band searched, upper end [Hz].
    pub max_frequency_hz: f64,
    /// Minimum peak prominence [dB].
    pub min_prominence_db: f64,
    /// The part of the record the spectrum is taken from; `None`: the free vibration when the
    /// crossing window is known and the free part holds a Welch segment, else the whole record.
    pub window: Option<SpectrumWindow>,
    /// How the frequencies are identified from the frequency channel.
    pub identification: Identification,
}

/// How the bridge's frequencies are identified.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Identification {
    /// The peaks of the Welch spectrum of the spectrum window, with half-power damping.
    WelchPeaks,
    /// The matrix pencil of the free vibration after the vehicle has left (needs the
    /// free-vibration window): finer than the spectrum's bins on clean, long decays.
    MatrixPencil,
    /// `Subspace` when the record holds the free vibration after the vehicle has left (its
    /// exit time known, at least [`crate::measure::MINIMUM_FREE_VIBRATION`] of it),
    /// else `WelchPeaks`: the default.
    Automatic,
    /// Subspace identification of every acceleration channel together: the eigensystem
    /// realisation of the free vibration after the vehicle has left when the record holds it,
    /// else covariance-driven SSI of the whole record; mode shapes at the sensors, damping
    /// with its scatter over model orders.
    Subspace,
}

/// The part of a record a spectrum is taken from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpectrumWindow {
    /// Every sample: the vehicle's forced content (its bounce, the pass harmonics) shows too.
    Whole,
    /// After the last axle has left the bridge: the bridge's own free vibration.
    FreeVibration,
}

/// The zero-offset (baseline) correction of every channel, from quiet parts of the record.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Baseline {
    /// `Linear` when the entry time is known and the record holds the quiet window before it
    /// and, past the exit, the one at its end; `Offset` with the window before entry alone;
    /// else `None`.
    Automatic,
    /// No correction.
    None,
    /// Subtract the mean of the quiet window before the vehicle enters.
    Offset,
    /// Subtract the straight line through the means of the quiet window before entry and of
    /// the last window of the record (a linear drift of the logger).
    Linear,
}

/// Where the frequency of the cut-off mode K1 of a channel comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum K1Source {
    /// Given in the input [Hz].
    Given(f64),
    /// Mode number K1 (1-based, as listed by `vbi modes`) of the bridge model: its frequency,
    /// after updating when the model is updated.
    ModelMode(usize),
    /// K1 and its frequency read from a `vbi run` summary.json (deck participation).
    RunSummary {
        /// K1 (1-based, in the run's modal basis).
        mode: usize,
        /// Its frequency [Hz].
        frequency_hz: f64,
    },
}

/// The bridge model of the measured bridge.
#[derive(Debug, Clone)]
pub struct MeasuredBridge {
    /// Its name in outputs (the file it came from).
    pub label: String,
    /// The model.
    pub model: BridgeModel,
    /// Number of modes to solve (at least the largest K1 mode number asked for).
    pub mode_count: usize,
}

/// Model updating options.
#[derive(Debug, Clone)]
pub struct UpdatingSpec {
    /// Frequencies of the unmodified model [Hz], ascending; `None` when they come from the
    /// bridge model.
    pub model_frequencies_hz: Option<Vec<f64>>,
    /// Also scale the added (pavement) mass of the bridge model.
    pub fit_mass: bool,
    /// Kinds of the model modes.
    pub model_kinds: Option<Vec<ModeKind>>,
    /// Kinds of the identified modes, in order.
    pub identified_kinds: Option<Vec<ModeKind>>,
    /// The parameters of a calibration (the measure stage's `calibrate`); empty: the stiffness
    /// scale (and the mass scale with `fit_mass`) of the classic updating.
    pub parameters: Vec<CalibrationParameter>,
}

/// `[measurement.weighing]`: weigh the vehicle from the record ([`super::weigh`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WeighingRequest {
    /// The channels to weigh with; empty: every deflection, strain or moment channel that has
    /// an influence line (its static reference's, else the crawl run's, else the bridge
    /// model's).
    pub channels: Vec<String>,
    /// Fit the entry time beside the loads; `None`: fitted when it was found in the record,
    /// taken as exact when given (axle detectors).
    pub fit_entry: Option<bool>,
    /// Fit every axle of a group on its own (`split_groups`); by default a group's axles
    /// share its load equally.
    pub split_groups: bool,
    /// Low-pass the records and the influence lines' design alike below the bridge's first
    /// frequency (`low_pass`, default false; [`super::WeighingStart::low_pass_hz`]), where that
    /// frequency is known. Off by default: over the validation battery it did not weigh better
    /// on the whole (docs/verification.md, 29b).
    pub low_pass: bool,
    /// Whether `[measurement.vehicle]` gives the axle loads: when not, the vehicle's loads are
    /// the weighed ones for every influence-line static part (before weighing they are equal
    /// placeholders, only the entry search's template uses them).
    pub axle_loads_given: bool,
}

/// A measurement: channels on one time axis and how to process them.
#[derive(Debug, Clone)]
pub struct Measurement {
    /// Free text.
    pub description: Option<String>,
    /// Sampling rate f_s [Hz].
    pub sampling_rate_hz: f64,
    /// The logger's mean sampling rate [Hz] when the record was resampled to f_s from its own
    /// (jittered or other-rate) times ([`crate::signal::resample_channels`]).
    pub resampled_from_hz: Option<f64>,
    /// Times t_i = t₀ + i/f_s [s].
    pub time: Vec<f64>,
    /// Channels in file order, each with one sample per time.
    pub channels: Vec<Channel>,
    /// Vehicle speed [m/s].
    pub speed: Option<f64>,
    /// Pass frequency v/L or 1/T_pass [Hz], L the loaded span when given (else the bridge).
    pub pass_frequency_hz: Option<f64>,
    /// Length of the loaded span, the span under the sensors [m]: sets the quasi-static
    /// content of their response and the separation check.
    pub span_length: Option<f64>,
    /// First bridge frequency given by the user [Hz].
    pub first_frequency_hz: Option<f64>,
    /// Butterworth order of the static low-pass and of the K1 filter.
    pub filter_order: usize,
    /// Static cut-off [Hz], when given.
    pub cutoff_hz: Option<f64>,
    /// Spectrum options.
    pub spectrum: SpectrumSpec,
    /// Vehicle loads for influence-line static references.
    pub vehicle: Option<MovingLoads>,
    /// Weigh the vehicle from the record (bridge weigh-in-motion), when asked
    /// (`[measurement.weighing]`).
    pub weighing: Option<WeighingRequest>,
    /// Where the vehicle runs across the deck (for the bridge model's influence lines).
    pub vehicle_track: VehicleTrack,
    /// The vehicle's own frequencies [Hz] (body bounce and pitch, axle hop), when known: modes
    /// identified within 5 % of one are the vehicle's forced content, not the bridge's.
    pub vehicle_frequencies_hz: Vec<f64>,
    /// Model updating, when asked.
    pub updating: Option<UpdatingSpec>,
    /// The bridge model, when named.
    pub bridge: Option<MeasuredBridge>,
    /// Time the first axle enters the bridge [s], when known.
    pub entry_time: Option<f64>,
    /// Find the entry time in the record when it is not given
    /// ([`super::detect_entry`]), and refuse the record when it cannot be found.
    pub detect_entry: bool,
    /// Look for the entry time when it is not given and `detect_entry` was not asked for
    /// (issue 52, item 2: the default), and go on without it when it cannot be found.
    pub detect_entry_by_default: bool,
    /// Length of the whole bridge [m], when known: with the entry time and the speed gives the
    /// time the last axle leaves it.
    pub bridge_length: Option<f64>,
    /// The baseline correction.
    pub baseline: Baseline,
    /// Length of the quiet windows of the baseline correction [s].
    pub baseline_window: f64,
    /// A crawl-speed run of the same vehicle over the same bridge, whose channels of the same
    /// names give the static parts (the engineers' static reference): its own speed and entry
    /// time map it onto this record by the vehicle's position.
    pub crawl: Option<Box<Measurement>>,
}

/// What calibration fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CalibrationParameter {
    /// One factor on the girders' stiffness (E of a grillage, EI of a beam).
    Stiffness,
    /// One factor per span on the girders' stiffness.
    SpanStiffness,
    /// One factor on the added (pavement) mass.
    AddedMass,
    /// One factor [-] (unit-free, 1 = the model's value) on the vertical stiffness of every
    /// elastic bearing: a beam's elastic supports, a grillage's bearings with a vertical
    /// stiffness, and the springs of changed supports. Rigid bearings have no stiffness to scale;
    /// a model without an elastic one is refused.
    BearingStiffness,
}

impl CalibrationParameter {
    /// The name in `updating.parameters`.
    pub fn input_name(self) -> &'static str {
        match self {
            Self::Stiffness => "stiffness",
            Self::SpanStiffness => "span_stiffness",
            Self::AddedMass => "added_mass",
            Self::BearingStiffness => "bearing_stiffness",
        }
    }
}
