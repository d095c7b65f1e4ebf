//! Resampling of measured records onto a uniform time grid: a field logger's clock jitters, its
//! rate need not be the one the analysis wants, and every other function of `signal` takes
//! samples at a uniform rate.
//!
//! **Checks of the time axis** ([`check_time_axis`]). The times t_i [s], i = 0 … n−1, must be
//! finite and strictly increasing, n ≥ 4. With the steps h_i = t_{i+1} − t_i and their median
//! h̃, a step h_i > 10·h̃ ([`GAP_STEP_RATIO`]) is a gap: the logger lost data, and interpolating
//! across it would invent a record, so it is refused with the times on either side. The record's
//! mean rate is f_in = (n − 1)/(t_{n−1} − t_0) [Hz] and its jitter max_i |h_i − h̃|/h̃ [-].
//!
//! **Output grid.** t_k = t_0 + k/f_out for k = 0, 1, … while t_k ≤ t_{n−1} (to 10⁻⁹ of the new
//! step, so that a record lasting a whole number of new steps ends on its last sample).
//!
//! **Interpolation: local cubic Hermite with three-point slopes** (Bessel's cubic; Catmull–Rom
//! generalised to non-uniform knots with a second-order slope). On [t_i, t_{i+1}], with
//! s = (t − t_i)/h_i ∈ [0, 1],
//!
//!   p(t) = h₀₀(s)·y_i + h₁₀(s)·h_i·d_i + h₀₁(s)·y_{i+1} + h₁₁(s)·h_i·d_{i+1},
//!
//!   h₀₀ = (1 + 2s)(1 − s)², h₁₀ = s(1 − s)², h₀₁ = s²(3 − 2s), h₁₁ = −s²(1 − s).
//!
//! The slope d_i [unit/s] is that of the parabola through the knot and its two neighbours; with
//! the divided differences δ_i = (y_{i+1} − y_i)/h_i,
//!
//!   d_i = (h_{i−1}·δ_i + h_i·δ_{i−1}) / (h_{i−1} + h_i)   (interior knots),
//!
//!   d_0 = ((2h_0 + h_1)·δ_0 − h_0·δ_1) / (h_0 + h_1),  and its mirror image at t_{n−1}.
//!
//! The interpolant is C¹, reproduces parabolas exactly, and passes through every sample, so a
//! record resampled on its own uniform grid comes back unchanged. Its error for a signal with
//! derivatives bounded by M₃, M₄ is at most
//!
//!   |p − y| ≤ M₄·h⁴/384 + M₃·h³/12,   h = max_i h_i:
//!
//! the first term is the Hermite error with exact slopes, the second the slope error of a
//! three-point parabola, M₃·h_{i−1}·h_i/6 inside and M₃·h_0·(h_0 + h_1)/6 ≤ M₃·h²/3 at the ends,
//! times max_s h·(|h₁₀(s)| + |h₁₁(s)|) = h/4. For a sine of amplitude A and frequency
//! f the second term dominates while 2πf·h is small: (2πf·h)³·A/12, e.g. 5.7·10⁻⁵·A for
//! f = 2 Hz and a largest step h = 7 ms (200 Hz with ±20 % jitter).
//!
//! **Anti-alias rule.** When f_out < f_in (beyond a round-off tolerance of 10⁻⁹), the record is
//! low-passed before it is resampled, by a zero-phase Butterworth filter of order N at
//!
//!   f_c = 0.4·f_out   (80 % of the new Nyquist frequency f_out/2, [`ANTI_ALIAS_FRACTION`]),
//!
//! i.e. `butterworth_lowpass(N, f_c, f_in)?.filtfilt(..)` at the record's mean rate f_in, of
//! magnitude |H(f)|² = 1/(1 + (tan(πf/f_in)/tan(πf_c/f_in))^{2N}) (forwards and backwards). The
//! new Nyquist frequency 1.25·f_c keeps at most about 1/(1 + 1.25^{2N}) of its amplitude (0.14
//! for N = 4), and content above f_out − f_c = 1.5·f_c, the content that would fold back below
//! f_c, at most about 1/(1 + 1.5^{2N}) (0.038 for N = 4; 1.5·10⁻⁴ at 3·f_c).
//!
//! The filter needs a uniform record, and it gets one: the record is first interpolated onto
//! the uniform grid u_j = t_0 + j/f_in, j = 0 … n−1 (the same number of samples, at the mean
//! rate, ending on t_{n−1}), filtered there, and only then interpolated onto t_k. Filtering the
//! raw samples on their index axis instead, as if uniform at f_in, would be valid only for a
//! jitter small against the step: it treats a sample taken δ [s] early as taken on time, an
//! amplitude error of first order in the jitter (up to 2πf·A·δ: 1.4·10⁻² measured for a 2 Hz
//! sine logged at 200 Hz with ±20 % jitter), while regularising first costs one more
//! interpolation, an error of third order in the step (7·10⁻⁶ for the same record). The
//! filter's edges are those of [`SosFilter::filtfilt`](super::SosFilter::filtfilt) (odd
//! reflection): compare resampled records away from their first and last few periods of f_c.
//!
//! Jitter limits how much content far above f_out can be removed: such content is interpolated
//! onto u_j with an error of order one (2πf·h is not small), and that error spreads over all
//! frequencies. A 60 Hz sine logged at 200 Hz and resampled to 50 Hz leaves 10⁻⁵ of its amplitude
//! on a uniform record, 0.5 % with ±1 % jitter and 7 % with ±20 % jitter; a record with strong
//! content near its own Nyquist frequency needs a logger with a steady clock.
//!
//! Hand-written: neither `nalgebra` nor `faer` (the crate's numerical dependencies) interpolates
//! at all, and no well-kept crate offers a local cubic Hermite interpolation on non-uniform
//! knots with these end slopes; the formulas are a dozen lines and are tested here against
//! closed forms.

use serde::{Deserialize, Serialize};

use super::filter::butterworth_lowpass;
use super::SignalError;

/// A step of the time axis larger than this multiple of the median step is a gap in the record
/// (the logger lost data) and is refused [-].
pub const GAP_STEP_RATIO: f64 = 10.0;

/// Anti-alias cut-off as a fraction of the new sampling rate: 0.4·f_out, i.e. 80 % of the new
/// Nyquist frequency [-].
pub const ANTI_ALIAS_FRACTION: f64 = 0.4;

/// Fewest samples of a record that can be resampled (the end slopes need three knots and a
/// cubic four).
pub const MIN_RESAMPLE_SAMPLES: usize = 4;

/// Relative tolerance on the rates below which the new rate counts as equal to the record's
/// mean rate (no anti-alias filter): round-off of (n − 1)/(t_{n−1} − t_0) only [-].
const RATE_TOLERANCE: f64 = 1e-9;

/// How far beyond the record's last time the last grid point may lie, in new steps [-]: keeps
/// the last sample of a record lasting a whole number of new steps against round-off.
const GRID_END_TOLERANCE: f64 = 1e-9;

/// A checked time axis of a record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TimeAxis {
    /// Number of times.
    pub samples: usize,
    /// First time t_0 [s].
    pub start_s: f64,
    /// Last time t_{n−1} [s].
    pub end_s: f64,
    /// Median step h̃ [s].
    pub median_step_s: f64,
    /// Mean sampling rate f_in = (n − 1)/(t_{n−1} − t_0) [Hz].
    pub original_rate_hz: f64,
    /// Largest relative deviation of a step from the median, max_i |h_i − h̃|/h̃ [-].
    pub max_jitter: f64,
}

/// One channel resampled onto a uniform grid ([`resample_uniform`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Resampled {
    /// Grid times t_k = t_0 + k/f_out [s].
    pub time: Vec<f64>,
    /// Samples at the grid times (the record's unit).
    pub samples: Vec<f64>,
    /// The new sampling rate f_out [Hz].
    pub rate_hz: f64,
    /// Mean sampling rate of the record f_in = (n − 1)/(t_{n−1} − t_0) [Hz].
    pub original_rate_hz: f64,
    /// Largest relative deviation of a step of the record from its median step [-].
    pub max_jitter: f64,
    /// Cut-off of the anti-alias low-pass 0.4·f_out [Hz]; `None` when no filter was applied
    /// (f_out ≥ f_in).
    pub anti_alias_cutoff_hz: Option<f64>,
}

/// Several channels of one time axis resampled onto a uniform grid ([`resample_channels`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResampledChannels {
    /// Grid times t_k = t_0 + k/f_out [s].
    pub time: Vec<f64>,
    /// Samples of each channel at the grid times, in the order given (each channel's unit).
    pub channels: Vec<Vec<f64>>,
    /// The new sampling rate f_out [Hz].
    pub rate_hz: f64,
    /// Mean sampling rate of the record f_in = (n − 1)/(t_{n−1} − t_0) [Hz].
    pub original_rate_hz: f64,
    /// Largest relative deviation of a step of the record from its median step [-].
    pub max_jitter: f64,
    /// Cut-off of the anti-alias low-pass 0.4·f_out [Hz]; `None` when no filter was applied
    /// (f_out ≥ f_in).
    pub anti_alias_cutoff_hz: Option<f64>,
}

/// Checks a record's time axis [s] and measures it: at least [`MIN_RESAMPLE_SAMPLES`] times,
/// each finite, strictly increasing, and no step above [`GAP_STEP_RATIO`] × the median step
/// (a gap: the logger lost data). Errors name the offending index and times.
pub fn check_time_axis(times: &[f64]) -> Result<TimeAxis, SignalError> {
    let n = times.len();
    if n < MIN_RESAMPLE_SAMPLES {
        return Err(SignalError::SignalTooShort {
            samples: n,
            required: MIN_RESAMPLE_SAMPLES,
        });
    }
    if let Some(index) = times.iter().position(|t| !t.is_finite()) {
        return Err(SignalError::NonFiniteTime {
            index,
            value: times[index],
        });
    }
    if let Some(i) = times.windows(2).position(|w| w[1] <= w[0]) {
        return Err(SignalError::TimeNotIncreasing {
            index: i + 1,
            previous_s: times[i],
            time_s: times[i + 1],
        });
    }
    let steps: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    let mut sorted = steps.clone();
    sorted.sort_by(f64::total_cmp);
    let m = sorted.len();
    let median_step_s = if m % 2 == 1 {
        sorted[m / 2]
    } else {
        0.5 * (sorted[m / 2 - 1] + sorted[m / 2])
    };
    if let Some(i) = steps
        .iter()
        .position(|&h| h > GAP_STEP_RATIO * median_step_s)
    {
        return Err(SignalError::TimeGap {
            index: i + 1,
            start_s: times[i],
            end_s: times[i + 1],
            median_step_s,
        });
    }
    let max_jitter = steps
        .iter()
        .map(|h| (h - median_step_s).abs() / median_step_s)
        .fold(0.0, f64::max);
    Ok(TimeAxis {
        samples: n,
        start_s: times[0],
        end_s: times[n - 1],
        median_step_s,
        original_rate_hz: (n - 1) as f64 / (times[n - 1] - times[0]),
        max_jitter,
    })
}

/// Resamples one channel of a record with times `times` [s] (strictly increasing, possibly
/// irregular) onto the uniform grid t_k = t_0 + k/`rate_hz` up to the last time: anti-alias
/// zero-phase Butterworth low-pass of `anti_alias_order` (1 to 40, checked even when no filter
/// is needed) at 0.4·`rate_hz` [Hz] when `rate_hz` is below the record's mean rate, then local
/// cubic Hermite interpolation (see the module documentation for the equations and the error
/// bound). One sample per time, all finite; a gap in the time axis is refused
/// ([`check_time_axis`]). A record to be downsampled needs more samples than the filter's edge
/// padding ([`SosFilter::default_pad_length`](super::SosFilter::default_pad_length), 15 for
/// order 4), else [`SignalError::SignalTooShort`].
pub fn resample_uniform(
    times: &[f64],
    samples: &[f64],
    rate_hz: f64,
    anti_alias_order: usize,
) -> Result<Resampled, SignalError> {
    let resampled =
        resample_channels(times, &[samples], rate_hz, anti_alias_order).map_err(|e| match e {
            SignalError::NonFiniteChannelSample { index, value, .. } => {
                SignalError::NonFiniteSample { index, value }
            }
            other => other,
        })?;
    let ResampledChannels {
        time,
        channels,
        rate_hz,
        original_rate_hz,
        max_jitter,
        anti_alias_cutoff_hz,
    } = resampled;
    Ok(Resampled {
        time,
        samples: channels
            .into_iter()
            .next()
            .expect("one channel in, one out"),
        rate_hz,
        original_rate_hz,
        max_jitter,
        anti_alias_cutoff_hz,
    })
}

/// Resamples several channels recorded on one time axis `times` [s] onto the uniform grid
/// t_k = t_0 + k/`rate_hz` [s], as [`resample_uniform`] does one: the time axis is checked once
/// ([`check_time_axis`]), every channel must hold one finite sample per time, and the grid, the
/// interpolation stencils and the anti-alias filter (order `anti_alias_order`, 1 to 40, cut-off
/// 0.4·`rate_hz` [Hz], applied only when `rate_hz` is below the mean rate) are shared.
pub fn resample_channels(
    times: &[f64],
    channels: &[&[f64]],
    rate_hz: f64,
    anti_alias_order: usize,
) -> Result<ResampledChannels, SignalError> {
    if !(rate_hz.is_finite() && rate_hz > 0.0) {
        return Err(SignalError::BadSamplingRate {
            sampling_rate_hz: rate_hz,
        });
    }
    if anti_alias_order == 0 || anti_alias_order > 40 {
        return Err(SignalError::BadFilterOrder {
            order: anti_alias_order,
        });
    }
    if channels.is_empty() {
        return Err(SignalError::NoChannels);
    }
    if let Some(channel) = channels.iter().position(|c| c.len() != times.len()) {
        return Err(SignalError::TimeLengthMismatch {
            channel,
            samples: channels[channel].len(),
            times: times.len(),
        });
    }
    let axis = check_time_axis(times)?;
    for (channel, samples) in channels.iter().enumerate() {
        if let Some(index) = samples.iter().position(|x| !x.is_finite()) {
            return Err(SignalError::NonFiniteChannelSample {
                channel,
                index,
                value: samples[index],
            });
        }
    }

    let n = times.len();
    let (start, end) = (axis.start_s, axis.end_s);
    let last = ((end - start) * rate_hz + GRID_END_TOLERANCE).floor() as usize;
    let time: Vec<f64> = (0..=last).map(|k| start + k as f64 / rate_hz).collect();

    let downsampling = rate_hz < axis.original_rate_hz * (1.0 - RATE_TOLERANCE);
    let (resampled, anti_alias_cutoff_hz) = if downsampling {
        let cutoff_hz = ANTI_ALIAS_FRACTION * rate_hz;
        let filter = butterworth_lowpass(anti_alias_order, cutoff_hz, axis.original_rate_hz)?;
        // The uniform grid at the mean rate, n samples from t_0 to exactly t_{n−1}.
        let regular: Vec<f64> = (0..n)
            .map(|j| {
                if j + 1 == n {
                    end
                } else {
                    start + j as f64 / axis.original_rate_hz
                }
            })
            .collect();
        let onto_regular = Stencil::new(times, &regular);
        let onto_output = Stencil::new(&regular, &time);
        let resampled = channels
            .iter()
            .map(|samples| {
                let uniform = onto_regular.interpolate(times, samples);
                let filtered = filter.filtfilt(&uniform, None)?;
                Ok(onto_output.interpolate(&regular, &filtered))
            })
            .collect::<Result<Vec<_>, SignalError>>()?;
        (resampled, Some(cutoff_hz))
    } else {
        let onto_output = Stencil::new(times, &time);
        let resampled = channels
            .iter()
            .map(|samples| onto_output.interpolate(times, samples))
            .collect();
        (resampled, None)
    };
    Ok(ResampledChannels {
        time,
        channels: resampled,
        rate_hz,
        original_rate_hz: axis.original_rate_hz,
        max_jitter: axis.max_jitter,
        anti_alias_cutoff_hz,
    })
}

/// Slopes d_i [unit/s] of the parabola through each knot and its neighbours (the module
/// documentation's three-point formulas; one-sided at the two ends). At least three knots,
/// strictly increasing.
fn three_point_slopes(knots: &[f64], values: &[f64]) -> Vec<f64> {
    let n = knots.len();
    let h: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
    let d: Vec<f64> = values
        .windows(2)
        .zip(&h)
        .map(|(v, h)| (v[1] - v[0]) / h)
        .collect();
    let mut slopes = Vec::with_capacity(n);
    slopes.push(((2.0 * h[0] + h[1]) * d[0] - h[0] * d[1]) / (h[0] + h[1]));
    for i in 1..n - 1 {
        slopes.push((h[i - 1] * d[i] + h[i] * d[i - 1]) / (h[i - 1] + h[i]));
    }
    let m = n - 2;
    slopes.push(((2.0 * h[m] + h[m - 1]) * d[m] - h[m] * d[m - 1]) / (h[m] + h[m - 1]));
    slopes
}

/// Where each evaluation time falls among the knots: the interval i with t_i ≤ t < t_{i+1}
/// (the first or last interval for a time outside, extrapolating the end cubic) and the
/// fraction s = (t − t_i)/h_i. Shared by every channel of a time axis.
struct Stencil {
    interval: Vec<usize>,
    fraction: Vec<f64>,
}

impl Stencil {
    /// Locates `at` (increasing) among `knots` (strictly increasing, at least two) in one sweep.
    fn new(knots: &[f64], at: &[f64]) -> Stencil {
        let last_interval = knots.len() - 2;
        let mut i = 0;
        let mut interval = Vec::with_capacity(at.len());
        let mut fraction = Vec::with_capacity(at.len());
        for &t in at {
            while i < last_interval && knots[i + 1] <= t {
                i += 1;
            }
            interval.push(i);
            fraction.push((t - knots[i]) / (knots[i + 1] - knots[i]));
        }
        Stencil { interval, fraction }
    }

    /// The local cubic Hermite interpolant of (`knots`, `values`) at the located times.
    fn interpolate(&self, knots: &[f64], values: &[f64]) -> Vec<f64> {
        let slopes = three_point_slopes(knots, values);
        self.interval
            .iter()
            .zip(&self.fraction)
            .map(|(&i, &s)| {
                let h = knots[i + 1] - knots[i];
                let r = 1.0 - s;
                let h00 = (1.0 + 2.0 * s) * r * r;
                let h10 = s * r * r;
                let h01 = s * s * (3.0 - 2.0 * s);
                let h11 = -s * s * r;
                h00 * values[i]
                    + h10 * h * slopes[i]
                    + h01 * values[i + 1]
                    + h11 * h * slopes[i + 1]
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_chacha::ChaCha8Rng;
    use rand_core::{Rng, SeedableRng};
    use std::f64::consts::TAU;

    /// Times k/fs + j_k·jitter/fs, j_k uniform in [−1, 1] (seeded): steps between
    /// (1 − 2·jitter)/fs and (1 + 2·jitter)/fs, strictly increasing for jitter < 0.5.
    fn jittered_times(samples: usize, fs: f64, jitter: f64, seed: u64) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..samples)
            .map(|k| {
                let u = ((rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0;
                (k as f64 + jitter * u) / fs
            })
            .collect()
    }

    /// The module's error bound of the local cubic Hermite interpolation of a sine of amplitude
    /// `amplitude` and frequency `f` [Hz] on knots with largest step `h` [s]:
    /// M₄·h⁴/384 + M₃·h³/12 with M_j = A·(2πf)^j.
    fn hermite_bound(amplitude: f64, f: f64, h: f64) -> f64 {
        let w = TAU * f;
        amplitude * (w.powi(4) * h.powi(4) / 384.0 + w.powi(3) * h.powi(3) / 12.0)
    }

    fn largest_step(times: &[f64]) -> f64 {
        times.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max)
    }

    /// Sum of |g| of the zero-phase filter's impulse response g (an impulse in the middle of a
    /// long zero record): ‖g‖₁ bounds the amplification of any bounded error by the filter.
    fn filtfilt_gain_bound(order: usize, cutoff_hz: f64, fs: f64) -> f64 {
        let mut impulse = vec![0.0; 4001];
        impulse[2000] = 1.0;
        butterworth_lowpass(order, cutoff_hz, fs)
            .unwrap()
            .filtfilt(&impulse, None)
            .unwrap()
            .iter()
            .map(|g| g.abs())
            .sum()
    }

    #[test]
    fn interpolation_reproduces_a_parabola_on_irregular_knots() {
        // Reference: the three-point slopes are exact for a parabola and a cubic Hermite with
        // exact slopes reproduces any cubic, so y = 3 − 2t + 5t² comes back to round-off.
        let knots = [0.0, 0.13, 0.21, 0.5, 0.52, 0.9, 1.4];
        let y = |t: f64| 3.0 - 2.0 * t + 5.0 * t * t;
        let values: Vec<f64> = knots.iter().map(|&t| y(t)).collect();
        let at: Vec<f64> = (0..=140).map(|k| k as f64 * 0.01).collect();
        let got = Stencil::new(&knots, &at).interpolate(&knots, &values);
        for (t, g) in at.iter().zip(got) {
            // Round-off of divided differences over steps down to 0.02.
            assert!((g - y(*t)).abs() < 1e-12, "t = {t}: {g} vs {}", y(*t));
        }
    }

    #[test]
    fn jittered_2_hz_sine_resampled_from_200_to_100_hz_matches_the_sine_within_the_bound() {
        // Reference: sin(2πf·t_k + φ). Downsampling: interpolation onto the uniform mean-rate
        // grid (error ≤ B(h_max), the module's bound on the jittered knots), the anti-alias
        // filter (amplifies that error by at most ‖g‖₁, and changes the 2 Hz sine by
        // 1 − |H(2 Hz)|² ≈ 1e-11), interpolation onto the 100 Hz grid (≤ B(1/f_in)).
        // Away from the filter's edges (0.25 s = 10 periods of the 40 Hz cut-off).
        let (f, fs, phase) = (2.0, 200.0, 0.7);
        let times = jittered_times(2001, fs, 0.2, 7);
        let samples: Vec<f64> = times.iter().map(|&t| (TAU * f * t + phase).sin()).collect();
        let out = resample_uniform(&times, &samples, 100.0, 4).unwrap();
        assert_eq!(out.anti_alias_cutoff_hz, Some(40.0));
        assert!(
            out.max_jitter > 0.3 && out.max_jitter <= 0.4 + 1e-12,
            "{}",
            out.max_jitter
        );
        assert!(
            (out.original_rate_hz - fs).abs() < 0.1,
            "{}",
            out.original_rate_hz
        );
        for (k, t) in out.time.iter().enumerate() {
            assert_eq!(*t, times[0] + k as f64 / 100.0);
        }
        assert!(*out.time.last().unwrap() <= times[2000]);
        assert!(times[2000] - out.time.last().unwrap() < 0.01);

        let filter = butterworth_lowpass(4, 40.0, out.original_rate_hz).unwrap();
        let passband_loss = 1.0
            - filter
                .frequency_response(f, out.original_rate_hz)
                .norm_sqr();
        let tolerance = filtfilt_gain_bound(4, 40.0, out.original_rate_hz)
            * hermite_bound(1.0, f, largest_step(&times))
            + hermite_bound(1.0, f, 1.0 / out.original_rate_hz)
            + passband_loss;
        let mut worst: f64 = 0.0;
        for (t, y) in out.time.iter().zip(&out.samples) {
            if *t > times[0] + 0.25 && *t < times[2000] - 0.25 {
                worst = worst.max((y - (TAU * f * t + phase).sin()).abs());
            }
        }
        eprintln!("2 Hz, 200 → 100 Hz, ±20 % jitter: error {worst:.3e}, bound {tolerance:.3e}");
        assert!(worst <= tolerance, "{worst} > {tolerance}");
    }

    #[test]
    fn sine_of_60_hz_above_the_new_nyquist_is_removed_not_aliased_to_10_hz() {
        // Reference: 60 Hz sampled at 50 Hz aliases to |60 − 50| = 10 Hz at full amplitude
        // (here exactly: every fourth sample of sin(2π·60·j/200) is sin(2π·10·t_k)). The
        // anti-alias filter (order 4 at 20 Hz on 200 Hz, |H(60 Hz)|² ≈ 1e-5) must leave less than
        // 1 % of the amplitude, away from the filter's edges (0.5 s = 10 periods of 20 Hz).
        let fs = 200.0;
        let times: Vec<f64> = (0..2001).map(|j| j as f64 / fs).collect();
        let samples: Vec<f64> = times.iter().map(|&t| (TAU * 60.0 * t).sin()).collect();

        // Without the filter the alias is there: plain interpolation onto the 50 Hz grid.
        let grid: Vec<f64> = (0..=500).map(|k| k as f64 / 50.0).collect();
        let aliased = Stencil::new(&times, &grid).interpolate(&times, &samples);
        for (t, y) in grid.iter().zip(&aliased) {
            assert!((y - (TAU * 10.0 * t).sin()).abs() < 1e-9, "t = {t}: {y}");
        }

        let out = resample_uniform(&times, &samples, 50.0, 4).unwrap();
        assert_eq!(out.anti_alias_cutoff_hz, Some(20.0));
        assert_eq!(out.time.len(), 501);
        let interior: Vec<f64> = out
            .time
            .iter()
            .zip(&out.samples)
            .filter(|(t, _)| **t > 0.5 && **t < 9.5)
            .map(|(_, y)| y.abs())
            .collect();
        let worst = interior.iter().copied().fold(0.0, f64::max);
        eprintln!("60 Hz, 200 → 50 Hz: largest remaining sample {worst:.3e} (1 % allowed)");
        assert!(worst < 0.01, "{worst}");
    }

    #[test]
    fn jittered_1_hz_sine_upsampled_from_50_to_200_hz_matches_the_sine_within_the_bound() {
        // Reference: sin(2πf·t_k + φ); no filter (upsampling), one interpolation over the whole
        // record, ends included: error ≤ M₄h⁴/384 + M₃h³/12 with h the largest jittered step.
        let (f, fs, phase) = (1.0, 50.0, 0.3);
        let times = jittered_times(501, fs, 0.2, 11);
        let samples: Vec<f64> = times.iter().map(|&t| (TAU * f * t + phase).sin()).collect();
        let out = resample_uniform(&times, &samples, 200.0, 4).unwrap();
        assert_eq!(out.anti_alias_cutoff_hz, None);
        assert!(out.time.len() >= 1990, "{}", out.time.len());
        let tolerance = hermite_bound(1.0, f, largest_step(&times));
        let worst = out
            .time
            .iter()
            .zip(&out.samples)
            .map(|(t, y)| (y - (TAU * f * t + phase).sin()).abs())
            .fold(0.0, f64::max);
        eprintln!("1 Hz, 50 → 200 Hz, ±20 % jitter: error {worst:.3e}, bound {tolerance:.3e}");
        assert!(worst <= tolerance, "{worst} > {tolerance}");
    }

    #[test]
    fn uniform_record_resampled_at_its_own_rate_returns_its_samples() {
        // Reference: the interpolant passes through every sample; the grid t_0 + k/f_s lands
        // on the record's times to round-off, so the samples come back to ≤ 1e-12 relative.
        let fs = 128.0;
        let times: Vec<f64> = (0..1000).map(|k| 3.7 + k as f64 / fs).collect();
        let samples: Vec<f64> = times
            .iter()
            .map(|&t| 2.0 + (TAU * 5.0 * t).sin() + 0.3 * (TAU * 31.0 * t).cos())
            .collect();
        let out = resample_uniform(&times, &samples, fs, 4).unwrap();
        assert_eq!(out.anti_alias_cutoff_hz, None);
        assert_eq!(out.time.len(), times.len());
        assert!(out.max_jitter < 1e-9, "{}", out.max_jitter);
        let scale = samples.iter().fold(0.0_f64, |m, y| m.max(y.abs()));
        for (k, (y, x)) in out.samples.iter().zip(&samples).enumerate() {
            assert!((out.time[k] - times[k]).abs() <= 1e-12 * times[k].abs());
            assert!((y - x).abs() <= 1e-12 * scale, "sample {k}: {y} vs {x}");
        }
    }

    #[test]
    fn record_with_a_gap_is_refused_naming_the_times() {
        // Reference: 40 lost samples at 100 Hz make one step of 0.41 s against a median of
        // 0.01 s, more than 10 × the median: refused with the times on either side.
        let times: Vec<f64> = (0..200)
            .filter(|k| !(60..100).contains(k))
            .map(|k| k as f64 / 100.0)
            .collect();
        let samples = vec![1.0; times.len()];
        let error = resample_uniform(&times, &samples, 50.0, 4).unwrap_err();
        let SignalError::TimeGap {
            index,
            start_s,
            end_s,
            median_step_s,
        } = error.clone()
        else {
            panic!("{error:?}");
        };
        assert_eq!((index, start_s, end_s), (60, 0.59, 1.0));
        assert!((median_step_s - 0.01).abs() < 1e-15, "{median_step_s}");
        let message = error.to_string();
        assert!(message.contains("from 0.59 s to 1 s"), "{message}");
        assert!(message.contains("samples 59 and 60"), "{message}");
        // A step of exactly 10 × the median is still accepted.
        let mut times = (0..20).map(|k| k as f64).collect::<Vec<_>>();
        for t in &mut times[10..] {
            *t += 9.0;
        }
        assert!(check_time_axis(&times).is_ok());
    }

    #[test]
    fn times_not_strictly_increasing_are_refused_naming_the_index() {
        // Reference: a repeated time at index 7 and a time going back at index 4.
        let mut times: Vec<f64> = (0..20).map(|k| k as f64 * 0.01).collect();
        times[7] = times[6];
        let samples = vec![0.0; 20];
        let error = resample_uniform(&times, &samples, 50.0, 4).unwrap_err();
        assert_eq!(
            error,
            SignalError::TimeNotIncreasing {
                index: 7,
                previous_s: 0.06,
                time_s: 0.06,
            }
        );
        assert!(error
            .to_string()
            .starts_with("time 7 (0.06 s) is not after time 6"));
        let mut times: Vec<f64> = (0..20).map(|k| k as f64 * 0.01).collect();
        times[4] = 0.025;
        assert!(matches!(
            check_time_axis(&times),
            Err(SignalError::TimeNotIncreasing { index: 4, .. })
        ));
    }

    #[test]
    fn bad_records_and_rates_are_refused() {
        let times: Vec<f64> = (0..50).map(|k| k as f64 * 0.01).collect();
        let samples = vec![0.5; 50];
        let mut bad = times.clone();
        bad[12] = f64::NAN;
        assert!(matches!(
            resample_uniform(&bad, &samples, 50.0, 4),
            Err(SignalError::NonFiniteTime { index: 12, .. })
        ));
        let mut bad = samples.clone();
        bad[3] = f64::INFINITY;
        assert_eq!(
            resample_uniform(&times, &bad, 50.0, 4),
            Err(SignalError::NonFiniteSample {
                index: 3,
                value: f64::INFINITY
            })
        );
        assert_eq!(
            resample_uniform(&times[..3], &samples[..3], 50.0, 4),
            Err(SignalError::SignalTooShort {
                samples: 3,
                required: 4
            })
        );
        assert_eq!(
            resample_uniform(&times, &samples[..49], 50.0, 4),
            Err(SignalError::TimeLengthMismatch {
                channel: 0,
                samples: 49,
                times: 50
            })
        );
        for rate in [0.0, -10.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                resample_uniform(&times, &samples, rate, 4),
                Err(SignalError::BadSamplingRate { .. })
            ));
        }
        assert_eq!(
            resample_uniform(&times, &samples, 200.0, 0),
            Err(SignalError::BadFilterOrder { order: 0 })
        );
        assert_eq!(
            resample_channels(&times, &[], 50.0, 4),
            Err(SignalError::NoChannels)
        );
    }

    #[test]
    fn channels_share_the_axis_and_equal_their_single_channel_resampling() {
        // Reference: resample_uniform channel by channel (the same grid, stencils and filter).
        let times = jittered_times(801, 200.0, 0.1, 3);
        let a: Vec<f64> = times.iter().map(|&t| (TAU * 1.5 * t).sin()).collect();
        let b: Vec<f64> = times
            .iter()
            .map(|&t| 0.01 * (TAU * 4.0 * t).cos() + t)
            .collect();
        for rate in [64.0, 400.0] {
            let both = resample_channels(&times, &[&a, &b], rate, 6).unwrap();
            for (channel, samples) in [&a, &b].into_iter().enumerate() {
                let one = resample_uniform(&times, samples, rate, 6).unwrap();
                assert_eq!(one.time, both.time);
                assert_eq!(one.samples, both.channels[channel]);
                assert_eq!(one.max_jitter, both.max_jitter);
                assert_eq!(one.original_rate_hz, both.original_rate_hz);
                assert_eq!(one.anti_alias_cutoff_hz, both.anti_alias_cutoff_hz);
            }
        }
        let mut bad = b.clone();
        bad[100] = f64::NAN;
        assert!(matches!(
            resample_channels(&times, &[&a, &bad], 64.0, 6),
            Err(SignalError::NonFiniteChannelSample {
                channel: 1,
                index: 100,
                ..
            })
        ));
        assert!(matches!(
            resample_channels(&times, &[&a, &b[..800]], 64.0, 6),
            Err(SignalError::TimeLengthMismatch {
                channel: 1,
                samples: 800,
                times: 801
            })
        ));
    }

    #[test]
    fn time_axis_reports_median_step_mean_rate_and_jitter() {
        // Reference by hand: steps 0.1, 0.1, 0.15, 0.1, 0.08 → median 0.1 s, jitter
        // max(0.5, 0.2) = 0.5, mean rate 5 / 0.53 s.
        let times = [1.0, 1.1, 1.2, 1.35, 1.45, 1.53];
        let axis = check_time_axis(&times).unwrap();
        assert!((axis.median_step_s - 0.1).abs() < 1e-12);
        assert!((axis.max_jitter - 0.5).abs() < 1e-9, "{}", axis.max_jitter);
        assert!((axis.original_rate_hz - 5.0 / 0.53).abs() < 1e-9);
        assert_eq!((axis.samples, axis.start_s, axis.end_s), (6, 1.0, 1.53));
    }

    #[test]
    fn jittered_record_is_filtered_on_a_uniform_grid_not_on_its_index_axis() {
        // Reference: sin(2πf·t_k + φ). Filtering the raw samples as if uniform turns the jitter
        // δ_i into an amplitude error of first order, up to 2πf·A·max|δ| = 4π·0.001 ≈ 1.3e-2
        // for ±20 % of 5 ms, of which the filter's stop band keeps a good part; regularising
        // first keeps the error at third order in the step (the bound of the 2 Hz test).
        let (f, fs, phase) = (2.0, 200.0, 0.7);
        let times = jittered_times(2001, fs, 0.2, 7);
        let samples: Vec<f64> = times.iter().map(|&t| (TAU * f * t + phase).sin()).collect();
        let out = resample_uniform(&times, &samples, 100.0, 4).unwrap();
        let on_index_axis = butterworth_lowpass(4, 40.0, out.original_rate_hz)
            .unwrap()
            .filtfilt(&samples, None)
            .unwrap();
        let naive = Stencil::new(&times, &out.time).interpolate(&times, &on_index_axis);
        let error = |y: &[f64]| {
            out.time
                .iter()
                .zip(y)
                .filter(|(t, _)| **t > times[0] + 0.25 && **t < times[2000] - 0.25)
                .map(|(t, y)| (y - (TAU * f * t + phase).sin()).abs())
                .fold(0.0, f64::max)
        };
        let (naive_error, error) = (error(&naive), error(&out.samples));
        eprintln!("index-axis filtering: error {naive_error:.3e}; regularised: {error:.3e}");
        assert!(naive_error > 1e-3, "{naive_error}");
        assert!(error < 1e-4, "{error}");
    }
}
