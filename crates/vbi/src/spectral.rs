//! Welch's averaged periodogram: the one implementation of the segment spectra behind the road
//! profile estimates (`road::welch_psd`, `road::welch_cross_spectrum`: spatial data, spacing Δx,
//! any segment step, lines 0 < k < M/2) and the measured-signal PSD (`signal::welch`: temporal
//! data, sampling rate f_s, 50 % overlap, zero padding, lines 0 … N/2 with the one-sided factor 1
//! at 0 Hz and at Nyquist).
//!
//! Both estimate the same one-sided density: segments of L samples, each with its mean removed
//! and multiplied by the periodic Hann window w_j = ½ − ½cos(2πj/L), transformed (zero-padded
//! to N ≥ L), |X_k|² summed over the segments. This module returns those sums; each caller
//! checks its own inputs (with its own error type) and applies its own scaling,
//! 2Δx/(Σw²·segments) or c_k/(f_s·Σw²·segments), whose rounding it keeps.

use std::f64::consts::PI;

use realfft::num_complex::Complex;
use realfft::RealFftPlanner;

/// Per-line sums over the segments, lines k = 0 … N/2 of the N-point transform.
pub(crate) struct WelchSums {
    /// Σ |X₁,k|² over the segments of the first signal.
    pub first: Vec<f64>,
    /// Σ |X₂,k|² of the second signal (empty without one).
    pub second: Vec<f64>,
    /// Σ X₁,k X₂,k* (empty without a second signal).
    pub cross: Vec<Complex<f64>>,
    /// Number of segments averaged (≥ 1).
    pub segments: usize,
    /// Σ w_j² of the window [-].
    pub window_power: f64,
}

/// Sums of the Hann-windowed, demeaned segment spectra of one signal, or of two of equal length
/// with their cross spectrum: segments of `segment_length` samples start at 0, `segment_step`,
/// 2·`segment_step`, … while they fit in the signal, and are zero-padded to `fft_length`.
///
/// The caller checks 1 ≤ `segment_length` ≤ `fft_length`, `segment_length` ≤ the signal length,
/// `segment_step` ≥ 1 and equal lengths of the two signals.
pub(crate) fn welch_sums(
    first: &[f64],
    second: Option<&[f64]>,
    segment_length: usize,
    fft_length: usize,
    segment_step: usize,
) -> WelchSums {
    debug_assert!(segment_length >= 1 && segment_length <= fft_length);
    debug_assert!(segment_length <= first.len() && segment_step >= 1);
    debug_assert!(second.is_none_or(|s| s.len() == first.len()));
    let count = first.len();
    let window: Vec<f64> = (0..segment_length)
        .map(|j| 0.5 - 0.5 * (2.0 * PI * j as f64 / segment_length as f64).cos())
        .collect();
    let window_power: f64 = window.iter().map(|w| w * w).sum();
    let fft = RealFftPlanner::<f64>::new().plan_fft_forward(fft_length);
    let lines = fft_length / 2 + 1;
    let cross_lines = if second.is_some() { lines } else { 0 };
    let mut sums = WelchSums {
        first: vec![0.0; lines],
        second: vec![0.0; cross_lines],
        cross: vec![Complex::new(0.0, 0.0); cross_lines],
        segments: 0,
        window_power,
    };
    let mut input = fft.make_input_vec();
    let mut spectrum1 = fft.make_output_vec();
    let mut spectrum2 = fft.make_output_vec();
    // The transform uses its input as scratch space, so the padding is zeroed every time.
    let mut transform = |signal: &[f64], begin: usize, out: &mut Vec<Complex<f64>>| {
        let segment = &signal[begin..begin + segment_length];
        let mean = segment.iter().sum::<f64>() / segment_length as f64;
        input.iter_mut().for_each(|v| *v = 0.0);
        for ((v, s), w) in input.iter_mut().zip(segment).zip(&window) {
            *v = (s - mean) * w;
        }
        fft.process(&mut input, out)
            .expect("buffers come from the same plan");
    };
    let mut begin = 0;
    while begin + segment_length <= count {
        transform(first, begin, &mut spectrum1);
        for (p, x) in sums.first.iter_mut().zip(&spectrum1) {
            *p += x.norm_sqr();
        }
        if let Some(second) = second {
            transform(second, begin, &mut spectrum2);
            for k in 0..lines {
                sums.second[k] += spectrum2[k].norm_sqr();
                sums.cross[k] += spectrum1[k] * spectrum2[k].conj();
            }
        }
        sums.segments += 1;
        begin += segment_step;
    }
    sums
}
