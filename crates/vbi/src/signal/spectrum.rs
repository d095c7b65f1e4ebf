//! Welch power spectral density, peak picking of the first modes and half-power damping.
//!
//! The segment spectra of [`welch`] are those of the road profile estimates (`road::welch_psd`;
//! one implementation, in the crate-private `spectral` module); the scaling by the sampling
//! rate, the zero padding and the lines at 0 Hz and Nyquist are the signal's.

use serde::{Deserialize, Serialize};

use super::SignalError;
use crate::spectral::{welch_sums, WelchSums};

/// Options of [`welch`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WelchOptions {
    /// Samples per segment (default 1024). Capped at the signal length. The frequency
    /// resolution is f_s / `fft_length`.
    pub segment_length: usize,
    /// FFT length ≥ `segment_length`: segments are zero-padded to it (default: none, i.e. equal
    /// to the segment length). Padding interpolates the spectrum; it does not sharpen peaks.
    pub fft_length: Option<usize>,
}

impl Default for WelchOptions {
    fn default() -> Self {
        WelchOptions {
            segment_length: 1024,
            fft_length: None,
        }
    }
}

/// A one-sided power spectral density.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Psd {
    /// Frequencies k·f_s/N_fft [Hz], k = 0 … N_fft/2.
    pub frequency_hz: Vec<f64>,
    /// Density [unit²/Hz] of the signal's unit.
    pub density: Vec<f64>,
    /// Segment length actually used [samples].
    pub segment_length: usize,
    /// Number of averaged segments.
    pub segments: usize,
    /// Sampling rate of the signal [Hz].
    pub sampling_rate_hz: f64,
}

impl Psd {
    /// Frequency spacing [Hz].
    pub fn resolution_hz(&self) -> f64 {
        self.frequency_hz.get(1).copied().unwrap_or(0.0)
    }
}

/// Welch's averaged periodogram, as `scipy.signal.welch(x, fs, window='hann', nperseg=L,
/// noverlap=L/2, nfft=N, detrend='constant', scaling='density')`:
///
/// segments of L samples start every L − ⌊L/2⌋ samples (50 % overlap; ⌊(n − ⌊L/2⌋)/step⌋ of
/// them); each has its mean removed, is multiplied by the periodic Hann window
/// w_j = ½ − ½cos(2πj/L) and zero-padded to N; P(f_k) = c_k·|X_k|² / (f_s·Σ w_j²), averaged over
/// segments, with c_k = 2 except at 0 Hz and at the Nyquist frequency (N even), where c_k = 1.
/// With this scaling, Σ_k P(f_k)·Δf equals the mean square of the (demeaned) signal, and white
/// noise of variance σ² has the flat level 2σ²/f_s.
pub fn welch(
    signal: &[f64],
    sampling_rate_hz: f64,
    options: &WelchOptions,
) -> Result<Psd, SignalError> {
    if !(sampling_rate_hz.is_finite() && sampling_rate_hz > 0.0) {
        return Err(SignalError::BadSamplingRate { sampling_rate_hz });
    }
    if let Some(i) = signal.iter().position(|x| !x.is_finite()) {
        return Err(SignalError::NonFiniteSample {
            index: i,
            value: signal[i],
        });
    }
    let segment_length = options.segment_length.min(signal.len());
    if segment_length < 8 {
        return Err(SignalError::SignalTooShort {
            samples: signal.len(),
            required: 8,
        });
    }
    let fft_length = options.fft_length.unwrap_or(segment_length);
    if fft_length < segment_length {
        return Err(SignalError::FftShorterThanSegment {
            fft_length,
            segment_length,
        });
    }
    let overlap = segment_length / 2;
    let step = segment_length - overlap;
    // ⌊(n − ⌊L/2⌋)/step⌋ segments: those starting at 0, step, 2·step, … that fit.
    let WelchSums {
        first: mut density,
        segments,
        window_power,
        ..
    } = welch_sums(signal, None, segment_length, fft_length, step);
    let scale = 1.0 / (sampling_rate_hz * window_power * segments as f64);
    let last = density.len() - 1;
    for (k, d) in density.iter_mut().enumerate() {
        let one_sided = if k == 0 || (k == last && fft_length.is_multiple_of(2)) {
            1.0
        } else {
            2.0
        };
        *d *= scale * one_sided;
    }
    let frequency_hz = (0..density.len())
        .map(|k| k as f64 * sampling_rate_hz / fft_length as f64)
        .collect();
    Ok(Psd {
        frequency_hz,
        density,
        segment_length,
        segments,
        sampling_rate_hz,
    })
}

/// Options of [`pick_peaks`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PeakOptions {
    /// How many peaks (the lowest in frequency) to return (default 3).
    pub count: usize,
    /// Lowest frequency searched [Hz] (default 0.5 Hz: below it lies the quasi-static content
    /// of a crossing, not a bridge mode).
    pub min_frequency_hz: f64,
    /// Highest frequency searched [Hz] (default: +∞, i.e. up to the Nyquist frequency).
    pub max_frequency_hz: f64,
    /// Minimum prominence of a peak [dB] of the density (default 6 dB, a factor 4 in power):
    /// the peak must stand this far above the higher of its two bases, as scipy's
    /// `find_peaks(prominence=…)` measures it on 10·log10(P).
    pub min_prominence_db: f64,
}

impl Default for PeakOptions {
    fn default() -> Self {
        PeakOptions {
            count: 3,
            min_frequency_hz: 0.5,
            max_frequency_hz: f64::INFINITY,
            min_prominence_db: 6.0,
        }
    }
}

/// A picked spectral peak: a natural frequency and its half-power damping.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpectralPeak {
    /// Index of the peak bin in the PSD.
    pub bin: usize,
    /// Peak frequency [Hz], refined by a parabola through the three bins around the maximum
    /// of 10·log10(P): f = f_k + δ·Δf, δ = ½(P₋ − P₊)/(P₋ − 2P₀ + P₊) (dB values).
    pub frequency_hz: f64,
    /// Density at the refined peak [unit²/Hz] (the parabola's vertex).
    pub density: f64,
    /// Prominence [dB].
    pub prominence_db: f64,
    /// Half-power bandwidth f₂ − f₁ [Hz]: where the density falls to half the peak on each
    /// side, by linear interpolation between bins. `None` when a side meets the band edge or
    /// another peak before falling to half power.
    pub half_power_bandwidth_hz: Option<f64>,
    /// Damping ratio ζ = (f₂ − f₁)/(2·f_n) [-] (half-power bandwidth method, exact for an SDOF
    /// to first order in ζ). Biased upwards when the bandwidth spans only a few bins (the Hann
    /// window widens a peak by about 1.5 bins). `None` with the bandwidth.
    pub damping_ratio: Option<f64>,
    /// True when the half-power bandwidth is narrower than two segment bins (2·f_s/L): the
    /// Hann main lobe (−3 dB width 1.44·f_s/L) then dominates the peak's width and the damping
    /// is an upper bound rather than an estimate. Also true when no bandwidth was found.
    pub resolution_limited: bool,
}

/// Picks the first modes of a PSD: local maxima in [min, max] frequency whose prominence in dB
/// reaches `min_prominence_db`, sorted by frequency, the lowest `count` kept; each refined by
/// parabolic interpolation and given its half-power damping.
pub fn pick_peaks(psd: &Psd, options: &PeakOptions) -> Vec<SpectralPeak> {
    let p = &psd.density;
    let f = &psd.frequency_hz;
    let n = p.len();
    if n < 3 {
        return Vec::new();
    }
    let db: Vec<f64> = p.iter().map(|v| 10.0 * v.max(1e-300).log10()).collect();
    let in_band = |k: usize| f[k] >= options.min_frequency_hz && f[k] <= options.max_frequency_hz;
    let Some(first) = (0..n).find(|&k| in_band(k)) else {
        return Vec::new();
    };
    let last = (0..n).rev().find(|&k| in_band(k)).unwrap_or(first);
    let mut peaks = Vec::new();
    for k in (first + 1).max(1)..last.min(n - 2) + 1 {
        if !(db[k] > db[k - 1] && db[k] >= db[k + 1]) {
            continue;
        }
        // Prominence: the lowest point on each side before a higher sample (or the band edge).
        let mut left_min = db[k];
        let mut j = k;
        while j > first {
            j -= 1;
            if db[j] > db[k] {
                break;
            }
            left_min = left_min.min(db[j]);
        }
        let mut right_min = db[k];
        let mut j = k;
        while j < last {
            j += 1;
            if db[j] > db[k] {
                break;
            }
            right_min = right_min.min(db[j]);
        }
        let prominence_db = db[k] - left_min.max(right_min);
        if prominence_db < options.min_prominence_db {
            continue;
        }
        let (a, b, c) = (db[k - 1], db[k], db[k + 1]);
        let curvature = a - 2.0 * b + c;
        let delta = if curvature < 0.0 {
            (0.5 * (a - c) / curvature).clamp(-0.5, 0.5)
        } else {
            0.0
        };
        let df = f[1] - f[0];
        let frequency_hz = f[k] + delta * df;
        let peak_db = b - 0.25 * (a - c) * delta;
        let density = 10f64.powf(peak_db / 10.0);
        let half = density / 2.0;
        let lower = half_power_crossing(p, f, k, half, first, -1);
        let upper = half_power_crossing(p, f, k, half, last, 1);
        let half_power_bandwidth_hz = match (lower, upper) {
            (Some(l), Some(u)) => Some(u - l),
            _ => None,
        };
        let segment_bin_hz = psd.sampling_rate_hz / psd.segment_length as f64;
        peaks.push(SpectralPeak {
            resolution_limited: half_power_bandwidth_hz.is_none_or(|bw| bw < 2.0 * segment_bin_hz),
            bin: k,
            frequency_hz,
            density,
            prominence_db,
            half_power_bandwidth_hz,
            damping_ratio: half_power_bandwidth_hz.map(|bw| bw / (2.0 * frequency_hz)),
        });
    }
    peaks.truncate(options.count);
    peaks
}

/// Walks from the peak bin in `direction` until the density falls below `half`, then
/// interpolates linearly the frequency of the crossing. `None` when the band edge `limit` is
/// reached or the density rises again (another peak) before the crossing.
fn half_power_crossing(
    p: &[f64],
    f: &[f64],
    peak: usize,
    half: f64,
    limit: usize,
    direction: isize,
) -> Option<f64> {
    let mut j = peak;
    loop {
        if j == limit {
            return None;
        }
        let next = (j as isize + direction) as usize;
        if p[next] <= half {
            let t = (p[j] - half) / (p[j] - p[next]);
            return Some(f[j] + t * (f[next] - f[j]));
        }
        if p[next] > p[j] && j != peak {
            return None;
        }
        j = next;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parseval_the_density_integrates_to_the_mean_square() {
        // Reference: Welch scaling with c_k = 2 (one-sided) and 1/(f_s Σw²): Σ P Δf = mean
        // square for a signal that is one whole segment of a pure tone on a bin.
        let fs = 64.0;
        let x: Vec<f64> = (0..256)
            .map(|i| (2.0 * std::f64::consts::PI * 8.0 * i as f64 / fs).sin())
            .collect();
        let psd = welch(
            &x,
            fs,
            &WelchOptions {
                segment_length: 256,
                fft_length: None,
            },
        )
        .unwrap();
        let power: f64 = psd.density.iter().sum::<f64>() * psd.resolution_hz();
        // For a bin-centred tone Σ(x·w)² = ½·Σw² exactly (the cos 2θ·w² term sums to zero),
        // so by Parseval the integral is ½; the tolerance covers round-off only.
        assert!((power - 0.5).abs() < 1e-12, "{power}");
    }
}
