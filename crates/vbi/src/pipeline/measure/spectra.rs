//! Spectra of the acceleration channels and the frequencies they identify.

use super::{ChannelSpectrum, IdentifiedMode, MeasureError};
use crate::pipeline::measurement::Measurement;
use crate::signal::{pick_peaks, welch, MeasuredQuantity, PeakOptions, Psd, WelchOptions};

/// The Welch spectrum of every acceleration channel with its picked peaks, and the densities
/// in the same order.
pub(super) fn spectra(m: &Measurement) -> Result<(Vec<ChannelSpectrum>, Vec<Psd>), MeasureError> {
    let mut spectra = Vec::new();
    let mut densities = Vec::new();
    for c in m
        .channels
        .iter()
        .filter(|c| c.kind == MeasuredQuantity::Acceleration)
    {
        let psd = welch(
            &c.samples,
            m.sampling_rate_hz,
            &WelchOptions {
                segment_length: m.spectrum.segment_length,
                fft_length: m.spectrum.fft_length,
            },
        )
        .map_err(|source| MeasureError::Spectrum {
            channel: c.name.clone(),
            source,
        })?;
        let peaks = pick_peaks(
            &psd,
            &PeakOptions {
                count: m.spectrum.modes,
                min_frequency_hz: m.spectrum.min_frequency_hz,
                max_frequency_hz: m.spectrum.max_frequency_hz,
                min_prominence_db: m.spectrum.min_prominence_db,
            },
        );
        spectra.push(ChannelSpectrum {
            channel: c.name.clone(),
            segment_length: psd.segment_length,
            fft_length: 2 * (psd.density.len() - 1),
            segments: psd.segments,
            resolution_hz: psd.resolution_hz(),
            peaks,
        });
        densities.push(psd);
    }
    Ok((spectra, densities))
}

/// The peaks of the frequency channel, as identified modes.
pub(super) fn identified(
    spectra: &[ChannelSpectrum],
    frequency_channel: Option<&String>,
) -> Vec<IdentifiedMode> {
    spectra
        .iter()
        .find(|s| Some(&s.channel) == frequency_channel)
        .map(|s| {
            s.peaks
                .iter()
                .map(|p| IdentifiedMode {
                    frequency_hz: p.frequency_hz,
                    damping_ratio: p.damping_ratio,
                    damping_resolution_limited: p.resolution_limited,
                })
                .collect()
        })
        .unwrap_or_default()
}
