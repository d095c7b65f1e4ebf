//! Road surface roughness: ISO 8608 spectra (paper Eq. 21), seeded generation by random-phase
//! harmonic superposition (Eq. 22) or inverse FFT, left and right wheel tracks with a coherence
//! model, approach lengths, tyre-patch smoothing, measured profiles and spectral estimates;
//! deterministic events (step, ramp, bump, sine) and user profiles ([`events`]).
//!
//! ```
//! use vbi::road::{generate, RoadSpec, Track};
//! let spec = RoadSpec::default(); // the paper's 'medium' road, w = 2
//! let (start, end) = spec.extent_for_bridge(60.0); // [-approach, 60 + exit]
//! let profile = generate(&spec, start, end, spec.seed).unwrap();
//! let (elevation, slope) = profile.elevation_and_slope(Track::Left, 30.0);
//! assert!(elevation.is_finite() && slope.is_finite());
//! ```

pub mod events;
mod generate;
pub(crate) use generate::splitmix64_of;
mod psd;
mod spectrum;

pub use events::{BumpShape, EventShape, EventTracks, RoadEvent, UserProfile};
pub use generate::{
    coherence, generate, generate_sample, uniform_unit, GenerationMethod, HarmonicSet, RoadSpec,
    SampleRng, TrackCorrelation, DEFAULT_COHERENCE_DECAY, MAX_DIRECT_TERMS, MAX_HARMONIC_COUNT,
    MAX_SAMPLE_COUNT, MAX_TYRE_PATCH_LENGTH,
};
pub use psd::{
    DisplacementPsd, PsdReference, Roughness, RoughnessClass, REFERENCE_SPATIAL_FREQUENCY,
};
pub use spectrum::{welch_cross_spectrum, welch_psd, CrossSpectrumPoint, PsdPoint};

use serde::{Deserialize, Serialize};

/// Errors of the road stage; each carries the offending numbers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RoadError {
    /// G_d(n₀) negative or not finite.
    #[error("G_d(n0) = {psd_at_reference} m^3 is not allowed; expected a finite value >= 0")]
    InvalidPsdAtReference {
        /// The value given [m³].
        psd_at_reference: f64,
    },
    /// Waviness not positive or not finite.
    #[error("waviness w = {waviness} is not allowed; expected a finite value > 0")]
    InvalidWaviness {
        /// The value given [-].
        waviness: f64,
    },
    /// A spatial-frequency band that is empty, non-positive or not finite.
    #[error(
        "spatial-frequency band [{lower}, {upper}] cycles/m is not allowed; expected 0 < n1 < n2"
    )]
    InvalidBand {
        /// n₁ [cycles/m].
        lower: f64,
        /// n₂ [cycles/m].
        upper: f64,
    },
    /// The upper band limit reaches the Nyquist frequency of the sampling.
    #[error(
        "upper band limit n2 = {upper} cycles/m is not below the Nyquist frequency {nyquist} cycles/m \
         of the sample spacing {spacing} m; use a finer sample spacing or a lower n2"
    )]
    BandAboveNyquist {
        /// n₂ [cycles/m].
        upper: f64,
        /// 1/(2 Δx) [cycles/m].
        nyquist: f64,
        /// Δx [m].
        spacing: f64,
    },
    /// A length or spacing that must be positive (or non-negative) is not.
    #[error("{quantity} = {value} m is not allowed; expected {allowed}")]
    InvalidLength {
        /// Which quantity.
        quantity: &'static str,
        /// The value given [m].
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
    /// A coherence decay that is negative or not finite.
    #[error("coherence decay rho = {decay} is not allowed; expected a finite value >= 0")]
    InvalidCoherenceDecay {
        /// The value given [-].
        decay: f64,
    },
    /// Zero harmonics requested.
    #[error("number of harmonics {count} is not allowed; expected 1 to {limit}")]
    InvalidHarmonicCount {
        /// The value given.
        count: usize,
        /// The largest allowed.
        limit: usize,
    },
    /// The direct superposition would sum too many terms.
    #[error(
        "the direct superposition of {harmonics} harmonics at {samples} samples sums \
         {harmonics} × {samples} terms per track, over the limit of {limit}; use \
         method = \"inverse_fft\" (the same Eq. 22, in milliseconds) or fewer harmonics"
    )]
    TooManyDirectTerms {
        /// Harmonics asked for.
        harmonics: usize,
        /// Samples of the track.
        samples: usize,
        /// The largest product allowed.
        limit: usize,
    },
    /// The profile range is empty or not finite.
    #[error("profile range [{start}, {end}] m is not allowed; expected finite start < end")]
    InvalidRange {
        /// Start [m].
        start: f64,
        /// End [m].
        end: f64,
    },
    /// Too many samples for the range and spacing.
    #[error("{count} samples ({length} m at {spacing} m) exceed the limit of {limit}")]
    TooManySamples {
        /// Samples needed.
        count: usize,
        /// Profile length [m].
        length: f64,
        /// Spacing [m].
        spacing: f64,
        /// Largest allowed.
        limit: usize,
    },
    /// Measured arrays of different lengths.
    #[error("measured profile arrays differ in length: {positions} positions, {left} left, {right} right samples")]
    LengthMismatch {
        /// Number of positions.
        positions: usize,
        /// Number of left samples.
        left: usize,
        /// Number of right samples.
        right: usize,
    },
    /// Fewer than two samples.
    #[error("a profile needs at least 2 samples, got {count}")]
    TooFewSamples {
        /// Number given.
        count: usize,
    },
    /// Positions not strictly increasing.
    #[error("positions must increase strictly: x[{index}] = {next} m follows {previous} m")]
    NotIncreasing {
        /// Index of the offending sample.
        index: usize,
        /// The preceding position [m].
        previous: f64,
        /// The offending position [m].
        next: f64,
    },
    /// A sample that is NaN or infinite.
    #[error("sample {index} is not finite: {value}")]
    NonFiniteSample {
        /// Index of the sample.
        index: usize,
        /// The value.
        value: f64,
    },
    /// Harmonic frequencies that do not lie on the FFT grid of the requested sampling.
    #[error("harmonic {index} at {frequency} cycles/m is not on the FFT grid of spacing {grid} cycles/m below Nyquist")]
    NotOnFftGrid {
        /// Index of the harmonic.
        index: usize,
        /// Its frequency [cycles/m].
        frequency: f64,
        /// Grid spacing 1/(N Δx) [cycles/m].
        grid: f64,
    },
    /// A road event with a number that is not allowed.
    #[error("road event {index}: {quantity} = {value} is not allowed; expected {allowed}")]
    InvalidEvent {
        /// Index of the event in the list (from 0).
        index: usize,
        /// Which quantity.
        quantity: &'static str,
        /// The value given [m or rad].
        value: f64,
        /// What is allowed.
        allowed: String,
    },
    /// A user profile that does not cover the extent the crossing needs.
    #[error(
        "the road profile covers [{first}, {last}] m but the crossing needs [{start}, {end}] m \
         (approach, bridge and exit, and behind the last tyre); extend the profile or shorten \
         approach_length_m / exit_length_m"
    )]
    ProfileDoesNotCover {
        /// Start of the needed extent [m].
        start: f64,
        /// End of the needed extent [m].
        end: f64,
        /// First position of the profile [m].
        first: f64,
        /// Last position of the profile [m].
        last: f64,
    },
    /// Spectral estimate with a segment too short or longer than the signal.
    #[error("segment length {segment_length} (step {segment_step}) does not fit {count} samples; expected 4 <= segment <= samples and step >= 1")]
    InvalidSegment {
        /// Segment length [samples].
        segment_length: usize,
        /// Step between segments [samples].
        segment_step: usize,
        /// Signal length [samples].
        count: usize,
    },
}

/// A wheel track.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Track {
    /// Left wheel track (y > 0 side of the vehicle).
    Left,
    /// Right wheel track.
    Right,
}

impl Track {
    /// The track of a wheel at a lateral offset from the vehicle centreline [m]; a wheel on the
    /// centreline (2D models) runs on the left track.
    pub fn of_lateral_offset(lateral_offset: f64) -> Track {
        if lateral_offset < 0.0 {
            Track::Right
        } else {
            Track::Left
        }
    }
}

/// Road elevation on two tracks, sampled at a uniform spacing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoadProfile {
    /// Position x of the first sample [m], in bridge coordinates (negative on the approach).
    pub start: f64,
    /// Sample spacing [m].
    pub spacing: f64,
    /// Left track elevation [m], upwards positive.
    pub left: Vec<f64>,
    /// Right track elevation [m], upwards positive.
    pub right: Vec<f64>,
    /// The highest spatial frequency [cycles/m] the profile carries, where it is known: a
    /// generated random road without events is band-limited to its band's n₂
    /// ([`crate::road::RoadSpec::band_upper`]; its cubic interpolation adds images near
    /// multiples of 1/Δx whose amplitude is below (π n₂ Δx)²/… of the band's top, a few per cent
    /// of its smallest harmonic). None: anything up to the samples' Nyquist frequency 1/(2Δx)
    /// (a measured or user profile, events, a smooth road). The default time step reads it
    /// ([`crate::solver::excitation_frequency`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub highest_spatial_frequency: Option<f64>,
}

impl RoadProfile {
    /// A perfectly smooth road over [start, end] [m].
    pub fn smooth(start: f64, end: f64) -> RoadProfile {
        RoadProfile {
            highest_spatial_frequency: None,
            start,
            spacing: (end - start).max(1.0),
            left: vec![0.0; 2],
            right: vec![0.0; 2],
        }
    }

    /// A profile from uniformly spaced samples: first position `start` [m], spacing [m] > 0,
    /// left and right elevations [m] of equal length ≥ 2, all finite.
    pub fn from_uniform_samples(
        start: f64,
        spacing: f64,
        left: Vec<f64>,
        right: Vec<f64>,
    ) -> Result<RoadProfile, RoadError> {
        if !start.is_finite() {
            return Err(RoadError::InvalidRange { start, end: start });
        }
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(RoadError::InvalidLength {
                quantity: "sample spacing",
                value: spacing,
                allowed: "a finite value > 0",
            });
        }
        if left.len() != right.len() {
            return Err(RoadError::LengthMismatch {
                positions: left.len(),
                left: left.len(),
                right: right.len(),
            });
        }
        if left.len() < 2 {
            return Err(RoadError::TooFewSamples { count: left.len() });
        }
        check_finite(&left)?;
        check_finite(&right)?;
        Ok(RoadProfile {
            highest_spatial_frequency: None,
            start,
            spacing,
            left,
            right,
        })
    }

    /// Imports a measured profile: positions x [m] strictly increasing, left and right
    /// elevations [m]. Positions uniform to 10⁻⁶ of the mean spacing are kept as they are;
    /// otherwise both tracks are resampled linearly at the mean spacing
    /// (x_last − x_first)/(count − 1).
    pub fn from_measured(
        positions: &[f64],
        left: &[f64],
        right: &[f64],
    ) -> Result<RoadProfile, RoadError> {
        check_measured(positions, left, right)?;
        let count = positions.len();
        let start = positions[0];
        let spacing = (positions[count - 1] - start) / (count - 1) as f64;
        let uniform = positions
            .iter()
            .enumerate()
            .all(|(i, &x)| (x - (start + i as f64 * spacing)).abs() <= 1e-6 * spacing);
        if uniform {
            return RoadProfile::from_uniform_samples(
                start,
                spacing,
                left.to_vec(),
                right.to_vec(),
            );
        }
        let grid: Vec<f64> = (0..count)
            .map(|i| {
                if i + 1 == count {
                    positions[count - 1]
                } else {
                    start + i as f64 * spacing
                }
            })
            .collect();
        RoadProfile::from_uniform_samples(
            start,
            spacing,
            resample_linear(positions, left, &grid),
            resample_linear(positions, right, &grid),
        )
    }

    /// Number of samples per track.
    pub fn len(&self) -> usize {
        self.left.len()
    }

    /// True when the profile holds no samples.
    pub fn is_empty(&self) -> bool {
        self.left.is_empty()
    }

    /// Position of sample i [m]: start + i·spacing (indexed, never accumulated).
    pub fn position(&self, index: usize) -> f64 {
        self.start + index as f64 * self.spacing
    }

    /// Position of the last sample [m].
    pub fn end(&self) -> f64 {
        self.position(self.len().saturating_sub(1))
    }

    /// The samples of one track [m].
    pub fn samples(&self, track: Track) -> &[f64] {
        match track {
            Track::Left => &self.left,
            Track::Right => &self.right,
        }
    }

    /// Root mean square of one track's samples [m].
    pub fn rms(&self, track: Track) -> f64 {
        let s = self.samples(track);
        if s.is_empty() {
            return 0.0;
        }
        (s.iter().map(|v| v * v).sum::<f64>() / s.len() as f64).sqrt()
    }

    /// Tyre-patch smoothing: a centred moving average over the contact length [m] ≥ 0, of
    /// 2·round(contact_length / (2Δx)) + 1 samples (shrinking at both ends to the samples
    /// available). A contact length below Δx leaves the profile unchanged.
    pub fn smoothed(&self, contact_length: f64) -> Result<RoadProfile, RoadError> {
        if !(contact_length.is_finite() && contact_length >= 0.0) {
            return Err(RoadError::InvalidLength {
                quantity: "tyre-patch length",
                value: contact_length,
                allowed: "a finite value >= 0",
            });
        }
        let half = (contact_length / (2.0 * self.spacing)).round() as usize;
        Ok(RoadProfile {
            // A moving average adds no frequency: the band stays.
            highest_spatial_frequency: self.highest_spatial_frequency,
            start: self.start,
            spacing: self.spacing,
            left: moving_average(&self.left, half),
            right: moving_average(&self.right, half),
        })
    }

    /// Elevation r [m] and slope dr/dx [-] at x [m]: a cubic Hermite (Catmull–Rom) interpolant
    /// through the samples, with central-difference tangents (one-sided at the ends), so the
    /// elevation is C¹ and the slope continuous. Outside the profile the road holds its end
    /// value, level (issue 46: a wheel at or past the last sample read 0, so a 10 mm ramp
    /// with no exit length dropped its wheel 10 mm at the last step).
    pub fn elevation_and_slope(&self, track: Track, x: f64) -> (f64, f64) {
        self.stencil(x).evaluate(self.samples(track))
    }

    /// The part of [`RoadProfile::elevation_and_slope`] at x that depends on x alone (the
    /// sample interval and the Hermite weights), for both tracks (the two wheels of an axle):
    /// [`RoadStencil::evaluate`] on a track's samples gives the same numbers, bit
    /// for bit.
    pub fn stencil(&self, x: f64) -> RoadStencil {
        let s = (x - self.start) / self.spacing;
        if s.is_nan() {
            return RoadStencil::OUTSIDE;
        }
        if s < 0.0 {
            return RoadStencil::BEFORE;
        }
        // s ≥ 0 here, so truncation is the floor (without a libm call on the baseline x86-64
        // target, issue 16); a huge s is cut to 2^52 samples, beyond any profile (which holds
        // at most 2^24), and is read as after its end.
        let interval = s.min(4_503_599_627_370_496.0) as usize;
        let f = s - interval as f64;
        let (f2, f3) = (f * f, f * f * f);
        RoadStencil {
            interval,
            values: [
                2.0 * f3 - 3.0 * f2 + 1.0,
                f3 - 2.0 * f2 + f,
                -2.0 * f3 + 3.0 * f2,
                f3 - f2,
            ],
            slopes: [
                6.0 * f2 - 6.0 * f,
                3.0 * f2 - 4.0 * f + 1.0,
                -6.0 * f2 + 6.0 * f,
                3.0 * f2 - 2.0 * f,
            ],
            spacing: self.spacing,
        }
    }
}

/// The x-dependent part of the road's cubic Hermite interpolant at one point
/// ([`RoadProfile::stencil`]): the sample interval i and, at f = s − i (s = (x − x₀)/Δ), the
/// weights of y_i, m_i, y_i+1, m_i+1 in the elevation (h₀₀ = 2f³ − 3f² + 1, h₁₀ = f³ − 2f² + f,
/// h₀₁ = −2f³ + 3f², h₁₁ = f³ − f²) and their derivatives in the slope (divided by Δ).
#[derive(Clone, Copy, Debug)]
pub struct RoadStencil {
    /// The sample interval i (x between samples i and i + 1); [`RoadStencil::BEFORE_START`]
    /// before the profile, `usize::MAX` at no point (x NaN).
    interval: usize,
    /// h₀₀, h₁₀, h₀₁, h₁₁.
    values: [f64; 4],
    /// dh/df of each.
    slopes: [f64; 4],
    /// The sample spacing Δ [m].
    spacing: f64,
}

impl RoadStencil {
    /// The interval of a point before the profile's start.
    const BEFORE_START: usize = usize::MAX - 1;

    /// No point of any profile (x NaN): zero.
    const OUTSIDE: RoadStencil = RoadStencil {
        interval: usize::MAX,
        values: [0.0; 4],
        slopes: [0.0; 4],
        spacing: 1.0,
    };

    /// A point before the profile's start: its first sample, level.
    const BEFORE: RoadStencil = RoadStencil {
        interval: Self::BEFORE_START,
        values: [0.0; 4],
        slopes: [0.0; 4],
        spacing: 1.0,
    };

    /// Elevation r [m] and slope dr/dx [-] on a track's samples. Before the first sample the
    /// road is level at its first value, at and after the last sample level at its last value.
    pub fn evaluate(&self, samples: &[f64]) -> (f64, f64) {
        let (n, i) = (samples.len(), self.interval);
        // One comparison on the time-step loop's path (x inside the profile); the two markers
        // and every interval at or past the last sample are ≥ n − 1.
        if i >= n.saturating_sub(1) {
            let level = match i {
                usize::MAX => 0.0,
                Self::BEFORE_START => samples.first().copied().unwrap_or(0.0),
                _ => samples.last().copied().unwrap_or(0.0),
            };
            return (level, 0.0);
        }
        let (y0, y1) = (samples[i], samples[i + 1]);
        // Tangents in units of elevation per sample interval.
        let tangent = |k: usize| -> f64 {
            if k == 0 {
                samples[1] - samples[0]
            } else if k + 1 == n {
                samples[n - 1] - samples[n - 2]
            } else {
                0.5 * (samples[k + 1] - samples[k - 1])
            }
        };
        let (m0, m1) = (tangent(i), tangent(i + 1));
        let [h00, h10, h01, h11] = self.values;
        let elevation = h00 * y0 + h10 * m0 + h01 * y1 + h11 * m1;
        let [d00, d10, d01, d11] = self.slopes;
        let slope = (d00 * y0 + d10 * m0 + d01 * y1 + d11 * m1) / self.spacing;
        (elevation, slope)
    }
}

/// Checks measured arrays: equal lengths ≥ 2, finite values, strictly increasing positions.
fn check_measured(positions: &[f64], left: &[f64], right: &[f64]) -> Result<(), RoadError> {
    if positions.len() != left.len() || positions.len() != right.len() {
        return Err(RoadError::LengthMismatch {
            positions: positions.len(),
            left: left.len(),
            right: right.len(),
        });
    }
    let count = positions.len();
    if count < 2 {
        return Err(RoadError::TooFewSamples { count });
    }
    check_finite(positions)?;
    check_finite(left)?;
    check_finite(right)?;
    for i in 1..count {
        if positions[i] <= positions[i - 1] {
            return Err(RoadError::NotIncreasing {
                index: i,
                previous: positions[i - 1],
                next: positions[i],
            });
        }
    }
    Ok(())
}

/// Linear interpolation of `values` at `positions` (strictly increasing, ≥ 2) at each of the
/// increasing `grid` positions: v_j + f (v_{j+1} − v_j), f = (x − x_j)/(x_{j+1} − x_j) clamped
/// to [0, 1] (so a grid position beyond the ends takes the end value).
fn resample_linear(positions: &[f64], values: &[f64], grid: &[f64]) -> Vec<f64> {
    let count = positions.len();
    let mut out = Vec::with_capacity(grid.len());
    let mut j = 0;
    for &x in grid {
        while j + 2 < count && positions[j + 1] < x {
            j += 1;
        }
        let f = ((x - positions[j]) / (positions[j + 1] - positions[j])).clamp(0.0, 1.0);
        out.push(values[j] + f * (values[j + 1] - values[j]));
    }
    out
}

fn check_finite(values: &[f64]) -> Result<(), RoadError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(RoadError::NonFiniteSample {
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

/// Centred moving average of 2·half + 1 samples, shrinking at the ends (prefix sums).
fn moving_average(values: &[f64], half: usize) -> Vec<f64> {
    if half == 0 {
        return values.to_vec();
    }
    let n = values.len();
    let mut prefix = Vec::with_capacity(n + 1);
    prefix.push(0.0);
    for v in values {
        prefix.push(prefix.last().copied().unwrap_or(0.0) + v);
    }
    (0..n)
        .map(|i| {
            let lo = i.saturating_sub(half);
            let hi = (i + half + 1).min(n);
            (prefix[hi] - prefix[lo]) / (hi - lo) as f64
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_road_is_zero_everywhere() {
        let p = RoadProfile::smooth(-10.0, 50.0);
        for x in [-20.0, -10.0, 0.0, 25.0, 49.9, 60.0] {
            assert_eq!(p.elevation_and_slope(Track::Left, x), (0.0, 0.0));
        }
    }

    #[test]
    fn interpolation_is_exact_for_a_cubic_free_parabola_inside() {
        // Catmull–Rom reproduces quadratics exactly away from the ends (central differences
        // are exact for a parabola): round-off only.
        let xs: Vec<f64> = (0..11).map(|i| i as f64 * 0.5).collect();
        let ys: Vec<f64> = xs.iter().map(|x| 0.3 * x * x - x).collect();
        let p = RoadProfile::from_uniform_samples(0.0, 0.5, ys.clone(), ys).unwrap();
        for x in [0.7, 1.3, 2.25, 3.9] {
            let (r, s) = p.elevation_and_slope(Track::Right, x);
            assert!((r - (0.3 * x * x - x)).abs() < 1e-12, "{x}: {r}");
            assert!((s - (0.6 * x - 1.0)).abs() < 1e-12, "{x}: {s}");
        }
        // Outside: level at the end values (issue 46), y(0) = 0 before, y(5) = 2.5 at the last
        // sample and after it.
        assert_eq!(p.elevation_and_slope(Track::Left, -0.1), (0.0, 0.0));
        assert_eq!(p.elevation_and_slope(Track::Left, 5.0), (2.5, 0.0));
        assert_eq!(p.elevation_and_slope(Track::Left, 5.01), (2.5, 0.0));
        assert_eq!(p.elevation_and_slope(Track::Left, 1e300), (2.5, 0.0));
    }

    /// Issue 46, item 3: a wheel at or past a profile's end read elevation 0, so a road that
    /// ends high (a 10 mm ramp with no exit length) dropped the wheel at the last step. The
    /// road is level at its end values outside the profile, at the first sample before it,
    /// and continuous across both ends.
    #[test]
    fn a_profile_holds_its_end_values_outside_it_and_is_continuous_at_both_ends() {
        let ys: Vec<f64> = (0..21).map(|i| 0.010 * (i as f64 / 20.0)).collect();
        let mut first = ys.clone();
        first[0] = -0.002;
        let p = RoadProfile::from_uniform_samples(-1.0, 0.05, first, ys).unwrap();
        let end = -1.0 + 20.0 * 0.05;
        for track in [Track::Left, Track::Right] {
            let inside = p.elevation_and_slope(track, end - 1e-9).0;
            assert!((inside - 0.010).abs() < 1e-9, "{inside}");
            assert_eq!(p.elevation_and_slope(track, end).0, 0.010);
            assert_eq!(p.elevation_and_slope(track, end + 3.0), (0.010, 0.0));
        }
        assert_eq!(p.elevation_and_slope(Track::Left, -1.5), (-0.002, 0.0));
        assert_eq!(p.elevation_and_slope(Track::Right, -1.5), (0.0, 0.0));
        assert_eq!(p.elevation_and_slope(Track::Left, f64::NAN), (0.0, 0.0));
    }

    #[test]
    fn moving_average_over_the_patch_flattens_a_two_sample_wave() {
        let wave: Vec<f64> = (0..20)
            .map(|i| if i % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        let p = RoadProfile::from_uniform_samples(0.0, 0.1, wave.clone(), wave).unwrap();
        let s = p.smoothed(0.2).unwrap(); // 3 samples
        for v in &s.left[1..19] {
            assert!(v.abs() <= 1.0 / 3.0 + 1e-15);
        }
        assert_eq!(p.smoothed(0.0).unwrap(), p);
        assert!(p.smoothed(-1.0).is_err());
    }

    #[test]
    fn measured_profile_non_uniform_positions_are_resampled_linearly() {
        let x = [0.0, 0.4, 1.0, 2.0];
        let y = [0.0, 0.4, 1.0, 2.0]; // a ramp: linear resampling is exact
        let p = RoadProfile::from_measured(&x, &y, &y).unwrap();
        assert_eq!(p.len(), 4);
        assert!((p.spacing - 2.0 / 3.0).abs() < 1e-15);
        for i in 0..4 {
            assert!((p.left[i] - p.position(i)).abs() < 1e-12);
        }
        assert!(matches!(
            RoadProfile::from_measured(&[0.0, 0.0], &[0.0; 2], &[0.0; 2]),
            Err(RoadError::NotIncreasing { index: 1, .. })
        ));
        assert!(matches!(
            RoadProfile::from_measured(&[0.0, 1.0], &[0.0; 2], &[0.0; 3]),
            Err(RoadError::LengthMismatch { .. })
        ));
    }
}
