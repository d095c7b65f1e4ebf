//! Spectral estimates of sampled profiles (Welch's method), to compare a profile with its
//! target PSD and two tracks with their coherence. The segment spectra are those of
//! `signal::welch` ([`crate::spectral`]); only the scaling (by the spacing Δx) and the lines
//! reported (0 < k < M/2) are the road's.

use serde::{Deserialize, Serialize};

use super::RoadError;
use crate::spectral::{welch_sums, WelchSums};

/// One line of a one-sided PSD estimate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PsdPoint {
    /// Spatial frequency n [cycles/m].
    pub spatial_frequency: f64,
    /// One-sided PSD G(n) [m³].
    pub psd: f64,
}

/// One line of a one-sided cross-spectral estimate of two tracks.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CrossSpectrumPoint {
    /// Spatial frequency n [cycles/m].
    pub spatial_frequency: f64,
    /// PSD of the first signal [m³].
    pub first_psd: f64,
    /// PSD of the second signal [m³].
    pub second_psd: f64,
    /// Co-spectrum Re G₁₂ [m³].
    pub co_spectrum: f64,
    /// Quadrature spectrum Im G₁₂ [m³].
    pub quad_spectrum: f64,
}

impl CrossSpectrumPoint {
    /// Real coherence Re G₁₂ / √(G₁₁ G₂₂) [-] (the γ of [`super::coherence`]).
    pub fn real_coherence(&self) -> f64 {
        self.co_spectrum / (self.first_psd * self.second_psd).sqrt()
    }
}

/// The segment sums of [`crate::spectral::welch_sums`] (no zero padding), after the checks of
/// the segment length and step.
fn segment_sums(
    first: &[f64],
    second: Option<&[f64]>,
    segment_length: usize,
    segment_step: usize,
) -> Result<WelchSums, RoadError> {
    let count = first.len();
    if segment_length < 4 || segment_length > count || segment_step == 0 {
        return Err(RoadError::InvalidSegment {
            segment_length,
            segment_step,
            count,
        });
    }
    Ok(welch_sums(
        first,
        second,
        segment_length,
        segment_length,
        segment_step,
    ))
}

/// Welch estimate of the one-sided PSD [m³] of uniformly sampled data (spacing Δx [m]):
/// Hann-windowed segments of `segment_length` samples, mean removed, starting every
/// `segment_step` samples (`segment_length / 2` for the usual 50 % overlap, `segment_length`
/// for independent segments), G(n_k) = 2 Δx ⟨|X_k|²⟩ / Σ w², n_k = k/(M Δx), 0 < k < M/2.
pub fn welch_psd(
    samples: &[f64],
    spacing: f64,
    segment_length: usize,
    segment_step: usize,
) -> Result<Vec<PsdPoint>, RoadError> {
    let sums = segment_sums(samples, None, segment_length, segment_step)?;
    let scale = 2.0 * spacing / (sums.window_power * sums.segments as f64);
    let p1 = sums.first;
    Ok((1..segment_length.div_ceil(2))
        .map(|k| PsdPoint {
            spatial_frequency: k as f64 / (segment_length as f64 * spacing),
            psd: p1[k] * scale,
        })
        .collect())
}

/// Welch estimate of the auto- and cross-spectra of two signals of equal length, as
/// [`welch_psd`]; G₁₂ = 2 Δx ⟨X₁ X₂*⟩ / Σ w².
pub fn welch_cross_spectrum(
    first: &[f64],
    second: &[f64],
    spacing: f64,
    segment_length: usize,
    segment_step: usize,
) -> Result<Vec<CrossSpectrumPoint>, RoadError> {
    if first.len() != second.len() {
        return Err(RoadError::LengthMismatch {
            positions: first.len(),
            left: first.len(),
            right: second.len(),
        });
    }
    let sums = segment_sums(first, Some(second), segment_length, segment_step)?;
    let scale = 2.0 * spacing / (sums.window_power * sums.segments as f64);
    let (p1, p2, p12) = (sums.first, sums.second, sums.cross);
    Ok((1..segment_length.div_ceil(2))
        .map(|k| CrossSpectrumPoint {
            spatial_frequency: k as f64 / (segment_length as f64 * spacing),
            first_psd: p1[k] * scale,
            second_psd: p2[k] * scale,
            co_spectrum: p12[k].re * scale,
            quad_spectrum: p12[k].im * scale,
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;

    #[test]
    fn welch_of_a_single_line_integrates_to_its_mean_square() {
        // A cosine of amplitude a on a bin centre: Σ G Δn = a²/2 with the Hann window's
        // energy spread over 3 lines; exact up to round-off.
        let m = 256;
        let dx = 0.1;
        let a = 0.3;
        let x: Vec<f64> = (0..4 * m)
            .map(|j| a * (2.0 * PI * 16.0 * j as f64 / m as f64).cos())
            .collect();
        let psd = welch_psd(&x, dx, m, m).unwrap();
        let dn = 1.0 / (m as f64 * dx);
        let total: f64 = psd.iter().map(|p| p.psd * dn).sum();
        assert!((total - a * a / 2.0).abs() < 1e-12 * a * a, "{total}");
        assert!(welch_psd(&x, dx, 2, 1).is_err());
    }
}
