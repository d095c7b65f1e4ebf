//! Spectra of the acceleration channels and the frequencies they identify.

use super::preparation::{crossing_window, FREE_VIBRATION_MARGIN};
use super::{ChannelSpectrum, IdentifiedMode, MeasureError};
use crate::pipeline::measurement::{Identification, Measurement, SpectrumWindow};
use crate::signal::{
    identify_free_decay, pick_peaks, welch, DecayOptions, MeasuredQuantity, PeakOptions, Psd,
    WelchOptions,
};

/// The Welch spectrum of every acceleration channel with its picked peaks, and the densities
/// in the same order.
pub(super) fn spectra(m: &Measurement) -> Result<(Vec<ChannelSpectrum>, Vec<Psd>), MeasureError> {
    let (window, start) = spectrum_window(m)?;
    let mut spectra = Vec::new();
    let mut densities = Vec::new();
    for c in m
        .channels
        .iter()
        .filter(|c| c.kind == MeasuredQuantity::Acceleration)
    {
        let psd = welch(
            &c.samples[start..],
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
            window,
            start_time_s: m.time[start],
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

/// The part of the record the spectra are taken from, and its first sample: the free
/// vibration from [`FREE_VIBRATION_MARGIN`] after the last axle has left, when asked or (by
/// default) when the exit time is known and the free part holds a whole Welch segment.
fn spectrum_window(m: &Measurement) -> Result<(SpectrumWindow, usize), MeasureError> {
    let exit = crossing_window(m).and_then(|w| w.exit_time_s);
    let free_start = exit.map(|t| m.time.partition_point(|&s| s < t + FREE_VIBRATION_MARGIN));
    let long_enough = |start: usize| m.time.len() - start >= m.spectrum.segment_length.max(64);
    match (m.spectrum.window, free_start) {
        (Some(SpectrumWindow::Whole), _) => Ok((SpectrumWindow::Whole, 0)),
        (None, Some(start)) if long_enough(start) => Ok((SpectrumWindow::FreeVibration, start)),
        (None, _) => Ok((SpectrumWindow::Whole, 0)),
        (Some(SpectrumWindow::FreeVibration), Some(start)) if long_enough(start) => {
            Ok((SpectrumWindow::FreeVibration, start))
        }
        (Some(SpectrumWindow::FreeVibration), Some(start)) => Err(MeasureError::input(
            "spectrum.window",
            format!(
                "the free vibration after the vehicle has left holds {} samples, fewer than a Welch segment ({}); record longer, shorten spectrum.segment_length, or use window = \"whole\"",
                m.time.len() - start,
                m.spectrum.segment_length.max(64)
            ),
        )),
        (Some(SpectrumWindow::FreeVibration), None) => Err(MeasureError::input(
            "spectrum.window",
            "the free vibration needs the time the vehicle leaves: give entry_time_s, bridge_length_m and the speed",
        )),
    }
}

/// The identified modes: the peaks of the frequency channel's spectrum, or the matrix pencil
/// of its free vibration when asked; with the method's name.
pub(super) fn identified(
    m: &Measurement,
    spectra: &[ChannelSpectrum],
    frequency_channel: Option<&String>,
) -> Result<(Vec<IdentifiedMode>, &'static str), MeasureError> {
    let spectrum = spectra
        .iter()
        .find(|s| Some(&s.channel) == frequency_channel);
    if m.spectrum.identification == Identification::WelchPeaks {
        return Ok((spectrum_peaks(spectra, frequency_channel), "welch_peaks"));
    }
    let Some(spectrum) = spectrum.filter(|s| s.window == SpectrumWindow::FreeVibration) else {
        return Err(MeasureError::input(
            "spectrum.identification",
            "the matrix pencil identifies a free decay: give entry_time_s, bridge_length_m and the speed, and record the free vibration after the vehicle has left",
        ));
    };
    let channel = m
        .channels
        .iter()
        .find(|c| c.name == spectrum.channel)
        .expect("a spectrum belongs to a channel");
    let start = m.time.partition_point(|&t| t < spectrum.start_time_s);
    let modes = identify_free_decay(
        &channel.samples[start..],
        m.sampling_rate_hz,
        &DecayOptions {
            count: m.spectrum.modes,
            min_frequency_hz: m.spectrum.min_frequency_hz,
            max_frequency_hz: m.spectrum.max_frequency_hz,
        },
    )
    .map_err(|source| MeasureError::Spectrum {
        channel: channel.name.clone(),
        source,
    })?;
    let identified = modes
        .iter()
        .map(|d| IdentifiedMode {
            frequency_hz: d.frequency_hz,
            damping_ratio: Some(d.damping_ratio),
            damping_resolution_limited: false,
        })
        .collect();
    Ok((identified, "matrix_pencil_free_vibration"))
}

/// The peaks of the frequency channel's spectrum, as identified modes.
fn spectrum_peaks(
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
