//! Measured signals (the paper's §6): Butterworth low-pass filters as second-order sections and
//! zero-phase filtering, Welch spectra and peak picking with half-power damping, DAF and RDM from
//! measured deflections and strains, low-pass filtering at the cut-off mode K1, and model
//! updating from identified frequencies.
//!
//! Everything takes plain sample slices in SI units at a uniform sampling rate; reading files,
//! unit conversion and checks of the time axis are the caller's (the `vbi measure` command).

pub mod filter;
pub mod free_decay;
pub mod measured;
pub mod resample;
pub mod separation;
pub mod spectrum;
pub mod subspace;
pub mod updating;

pub use filter::{butterworth_lowpass, Section, SosFilter};
pub use free_decay::{identify_free_decay, DecayMode, DecayOptions};
pub use measured::{
    automatic_cutoff, cutoff_above_mode, cutoff_mode_filtering, measured_daf, rdm,
    static_component, static_from_influence_line, CutoffChoice, CutoffModeFiltering, CutoffRule,
    MeasuredDaf, MeasuredQuantity, MovingLoads, SampledInfluenceLine, StrainToMoment,
    CUTOFF_MODE_GAIN, QUASI_STATIC_HARMONICS,
};
pub use resample::{
    check_time_axis, resample_channels, resample_uniform, Resampled, ResampledChannels, TimeAxis,
    ANTI_ALIAS_FRACTION, GAP_STEP_RATIO, MIN_RESAMPLE_SAMPLES,
};
pub use separation::{
    check_separation, InfluenceShape, SeparationCheck, SEPARATION_PEAK_TOLERANCE,
};
pub use spectrum::{pick_peaks, welch, PeakOptions, Psd, SpectralPeak, WelchOptions};
pub use subspace::{
    identify_free_response, identify_output_only, mac, StabilisationPole, SubspaceIdentification,
    SubspaceMethod, SubspaceMode, SubspaceOptions, HANKEL_ENTRY_LIMIT,
};
pub use updating::{
    pair_modes, stiffness_scale_closed_form, update_model, IdentifiedFrequency, ModePair,
    UpdatedModel, UpdatingMethod, UpdatingOptions,
};

use crate::modal::ModeKind;

/// Errors of the signal stage, with the offending numbers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SignalError {
    /// Sampling rate not positive and finite.
    #[error("sampling rate {sampling_rate_hz} Hz is not allowed; expected a positive number")]
    BadSamplingRate {
        /// The rate [Hz].
        sampling_rate_hz: f64,
    },
    /// Filter order outside 1..=40.
    #[error("filter order {order} is not allowed; expected 1 to 40")]
    BadFilterOrder {
        /// The order.
        order: usize,
    },
    /// Cut-off not strictly between 0 and the Nyquist frequency.
    #[error("cut-off frequency {cutoff_hz} Hz is not allowed; expected between 0 and the Nyquist frequency {nyquist_hz} Hz (exclusive)")]
    BadCutoff {
        /// The cut-off [Hz].
        cutoff_hz: f64,
        /// Half the sampling rate [Hz].
        nyquist_hz: f64,
    },
    /// Too few samples.
    #[error("the signal has {samples} samples; at least {required} are needed")]
    SignalTooShort {
        /// Samples given.
        samples: usize,
        /// Samples needed.
        required: usize,
    },
    /// NaN or infinite sample.
    #[error("sample {index} is {value}; every sample must be a finite number")]
    NonFiniteSample {
        /// Index of the sample.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// FFT shorter than the segment.
    #[error("FFT length {fft_length} is shorter than the segment length {segment_length}")]
    FftShorterThanSegment {
        /// FFT length.
        fft_length: usize,
        /// Segment length.
        segment_length: usize,
    },
    /// Signals of different lengths.
    #[error("the measured signal has {measured} samples but the static reference has {reference}; expected the same non-zero length")]
    LengthMismatch {
        /// Measured samples.
        measured: usize,
        /// Reference samples.
        reference: usize,
    },
    /// The static component is identically zero.
    #[error("the static component is zero everywhere: no DAF can be formed")]
    ZeroStaticResponse,
    /// Bad inputs to the automatic cut-off.
    #[error("pass frequency {pass_frequency_hz} Hz and first bridge frequency {first_frequency_hz} Hz must both be positive")]
    BadCutoffInputs {
        /// v/L [Hz].
        pass_frequency_hz: f64,
        /// f₁ [Hz].
        first_frequency_hz: f64,
    },
    /// DAFs that cannot form an RDM.
    #[error("DAFs {daf_deflection} (deflection) and {daf_moment} (moment) cannot form an RDM; expected finite values and a positive moment DAF")]
    BadDafPair {
        /// Deflection DAF.
        daf_deflection: f64,
        /// Moment DAF.
        daf_moment: f64,
    },
    /// Strain-to-moment factor zero or not finite.
    #[error(
        "strain-to-moment factor {factor} N·m is not allowed; expected a finite non-zero number"
    )]
    BadStrainFactor {
        /// E·I/y or the given factor [N·m].
        factor: f64,
    },
    /// Bad influence-line samples.
    #[error("influence line sample {index}: {reason}")]
    BadInfluenceLine {
        /// Sample index.
        index: usize,
        /// What is wrong.
        reason: String,
    },
    /// Bad moving loads.
    #[error("moving loads: {axles} axle loads, {offsets} axle offsets, speed {speed} m/s; expected as many offsets as loads, at least one, and a positive speed")]
    BadMovingLoads {
        /// Number of loads.
        axles: usize,
        /// Number of offsets.
        offsets: usize,
        /// Speed [m/s].
        speed: f64,
    },
    /// Fewer identified modes than parameters.
    #[error("{identified} identified frequencies cannot determine {parameters} scale factors")]
    TooFewModes {
        /// Identified modes.
        identified: usize,
        /// Parameters.
        parameters: usize,
    },
    /// Some identified modes have a kind and some not.
    #[error("{with_kind} identified modes have a kind and {without_kind} do not; give a kind for all or none")]
    MixedModeKinds {
        /// With a kind.
        with_kind: usize,
        /// Without.
        without_kind: usize,
    },
    /// An identified mode has no model counterpart.
    #[error("identified mode {identified_index} (number {} of kind {kind:?}) has no model mode to pair with", rank + 1)]
    NoModelModeToPair {
        /// Index of the identified mode.
        identified_index: usize,
        /// Its kind.
        kind: Option<ModeKind>,
        /// Its rank within the kind (0-based).
        rank: usize,
    },
    /// Frequencies that cannot be fitted.
    #[error("cannot fit model frequencies {model:?} Hz to identified frequencies {identified:?} Hz; expected positive, finite values in equal numbers")]
    BadFrequencies {
        /// Model frequencies [Hz].
        model: Vec<f64>,
        /// Identified frequencies [Hz].
        identified: Vec<f64>,
    },
    /// Stiffness and mass scales act alike on the frequencies.
    #[error("stiffness and mass scales are not separately identifiable from these frequencies (their sensitivities are parallel, cosine {cosine}); scale only part of the mass (the added mass) or fit the stiffness alone")]
    NotIdentifiable {
        /// Cosine of the angle between the Jacobian columns.
        cosine: f64,
    },
    /// The model closure failed.
    #[error("the bridge model failed at scale factors {scales:?}: {message}")]
    ModelFailed {
        /// Scale factors tried.
        scales: Vec<f64>,
        /// The model's message.
        message: String,
    },
    /// No channel given.
    #[error("no channel given; expected at least one")]
    NoChannels,
    /// A channel's length differs from the first channel's.
    #[error("channel {channel} has {samples} samples but channel 0 has {expected}; expected equal lengths")]
    ChannelLengthMismatch {
        /// Index of the channel.
        channel: usize,
        /// Its samples.
        samples: usize,
        /// Samples of channel 0.
        expected: usize,
    },
    /// NaN or infinite sample of one of several channels.
    #[error(
        "sample {index} of channel {channel} is {value}; every sample must be a finite number"
    )]
    NonFiniteChannelSample {
        /// Index of the channel.
        channel: usize,
        /// Index of the sample.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A time of a record is NaN or infinite.
    #[error("time {index} is {value} s; every time must be a finite number")]
    NonFiniteTime {
        /// Index of the time.
        index: usize,
        /// Its value [s].
        value: f64,
    },
    /// A time not after the one before it.
    #[error("time {index} ({time_s} s) is not after time {} ({previous_s} s); expected strictly increasing times", index - 1)]
    TimeNotIncreasing {
        /// Index of the offending time.
        index: usize,
        /// The time before it [s].
        previous_s: f64,
        /// The offending time [s].
        time_s: f64,
    },
    /// A step of the time axis above GAP_STEP_RATIO × the median step: the logger lost data.
    #[error("the record has a gap from {start_s} s to {end_s} s (between samples {} and {index}): the step of {} s exceeds {} × the median step {median_step_s} s; the logger lost data there; split the record at the gap or fill it explicitly", index - 1, end_s - start_s, resample::GAP_STEP_RATIO)]
    TimeGap {
        /// Index of the first sample after the gap.
        index: usize,
        /// Time before the gap [s].
        start_s: f64,
        /// Time after the gap [s].
        end_s: f64,
        /// Median step of the record [s].
        median_step_s: f64,
    },
    /// A channel's length differs from the time axis's.
    #[error("channel {channel} has {samples} samples but the time axis has {times} times; expected one sample per time")]
    TimeLengthMismatch {
        /// Index of the channel.
        channel: usize,
        /// Its samples.
        samples: usize,
        /// Number of times.
        times: usize,
    },
    /// Frequency band not within (0, Nyquist].
    #[error("frequency band {min_frequency_hz} to {max_frequency_hz} Hz is not allowed; expected 0 < min < max ≤ the Nyquist frequency {nyquist_hz} Hz (max = inf means Nyquist)")]
    BadBand {
        /// Lower end [Hz].
        min_frequency_hz: f64,
        /// Upper end [Hz].
        max_frequency_hz: f64,
        /// Half the sampling rate [Hz].
        nyquist_hz: f64,
    },
    /// An option of the subspace identification out of its range.
    #[error("subspace option {option} = {value} is not allowed; expected {expected}")]
    BadSubspaceOption {
        /// Name of the option.
        option: &'static str,
        /// Its value.
        value: f64,
        /// What is allowed.
        expected: String,
    },
    /// The block Hankel matrix would exceed the memory bound.
    #[error("a block Hankel matrix of {rows} rows and at least {columns} columns exceeds the limit of {limit} entries; use fewer block rows, channels or a lower max_order")]
    HankelTooLarge {
        /// Rows p·l.
        rows: usize,
        /// Columns needed.
        columns: usize,
        /// Largest number of entries.
        limit: usize,
    },
    /// The SVD of the block Hankel matrix did not converge.
    #[error("the SVD of the {rows} × {columns} block Hankel matrix did not converge")]
    SvdNotConverged {
        /// Rows.
        rows: usize,
        /// Columns.
        columns: usize,
    },
    /// Levenberg–Marquardt did not converge.
    #[error(
        "model updating did not converge in {iterations} iterations (RMS error {rms_error_hz} Hz)"
    )]
    NoConvergence {
        /// Iterations done.
        iterations: usize,
        /// RMS frequency error reached [Hz].
        rms_error_hz: f64,
    },
}
