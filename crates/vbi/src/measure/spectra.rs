//! Spectra of the acceleration channels and the frequencies they identify.

use super::forced_content::{self, ForcedContentCheck, FORCED_CONTENT_EXTRA_MODES};
use super::preparation::{crossing_window, FREE_VIBRATION_MARGIN};
use super::{ChannelSpectrum, IdentifiedMode, MeasureError, SubspaceSummary};
use crate::measure::measurement::{Identification, Measurement, SpectrumWindow};
use crate::signal::{
    identify_free_decay, identify_free_response, identify_output_only, pick_peaks, welch,
    DecayOptions, MeasuredQuantity, PeakOptions, Psd, SubspaceOptions, WelchOptions,
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
        // The vehicle's own frequencies and the forced content are left out afterwards: pick
        // as many more.
        let peaks = pick_peaks(
            &psd,
            &PeakOptions {
                count: modes_sought(m, window),
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
    spectrum_window_from(m, FREE_VIBRATION_MARGIN)
}

/// [`spectrum_window`] with the free vibration starting `margin` [s] after the exit.
fn spectrum_window_from(
    m: &Measurement,
    margin: f64,
) -> Result<(SpectrumWindow, usize), MeasureError> {
    let exit = crossing_window(m).and_then(|w| w.exit_time_s);
    let free_start = exit.map(|t| m.time.partition_point(|&s| s < t + margin));
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

/// Modes an identification of `window` looks for: `spectrum.modes`, and as many more as the
/// vehicle's frequencies and the forced content may take away.
fn modes_sought(m: &Measurement, window: SpectrumWindow) -> usize {
    let forced = if window == SpectrumWindow::Whole && forced_content::checkable(m) {
        FORCED_CONTENT_EXTRA_MODES
    } else {
        0
    };
    m.spectrum.modes + m.vehicle_frequencies_hz.len() + forced
}

/// The identified modes: the peaks of the frequency channel's spectrum, the matrix pencil of
/// its free vibration, or the subspace identification of every acceleration channel; with the
/// method's name and the subspace's summary. The vehicle's own frequencies and, when the
/// identification read the crossing, its forced content are moved apart; at most
/// `spectrum.modes` are kept.
pub(super) fn identified(
    m: &Measurement,
    spectra: &[ChannelSpectrum],
    frequency_channel: Option<&String>,
) -> Result<Identified, MeasureError> {
    let (modes, method, subspace) = identified_by_method(m, spectra, frequency_channel)?;
    let (modes, excluded) = without_vehicle_frequencies(m, modes);
    let read_crossing = match method {
        "subspace_whole_record" => true,
        "welch_peaks" => {
            let channel =
                frequency_channel.and_then(|name| spectra.iter().find(|s| &s.channel == name));
            channel.is_some_and(|s| s.window == SpectrumWindow::Whole)
        }
        _ => false,
    };
    let (mut modes, forced, forced_check) =
        forced_content::without_forced_content(m, modes, read_crossing);
    modes.truncate(m.spectrum.modes);
    Ok(Identified {
        modes,
        method,
        subspace,
        excluded,
        forced,
        forced_check,
    })
}

/// The identification's outcome.
pub(super) struct Identified {
    /// The bridge's modes.
    pub modes: Vec<IdentifiedMode>,
    /// The method's name in outputs.
    pub method: &'static str,
    /// The subspace identification, when used.
    pub subspace: Option<SubspaceSummary>,
    /// Modes left out as the vehicle's.
    pub excluded: Vec<IdentifiedMode>,
    /// Modes left out as the crossing's forced content.
    pub forced: Vec<IdentifiedMode>,
    /// Whether the forced content was looked for.
    pub forced_check: ForcedContentCheck,
}

/// Relative distance within which an identified mode is taken for the vehicle's own mode [-].
pub const VEHICLE_FREQUENCY_TOLERANCE: f64 = 0.05;

/// The modes apart from those within [`VEHICLE_FREQUENCY_TOLERANCE`] of a frequency of the
/// vehicle (`Measurement::vehicle_frequencies_hz`: its bounce, pitch, axle hop), which a record
/// taken while it crosses holds as forced content, and the excluded ones.
pub(super) fn without_vehicle_frequencies(
    m: &Measurement,
    modes: Vec<IdentifiedMode>,
) -> (Vec<IdentifiedMode>, Vec<IdentifiedMode>) {
    let of_vehicle = |p: &IdentifiedMode| {
        m.vehicle_frequencies_hz
            .iter()
            .any(|f| (p.frequency_hz / f - 1.0).abs() <= VEHICLE_FREQUENCY_TOLERANCE)
    };
    let (excluded, kept): (Vec<_>, Vec<_>) = modes.into_iter().partition(of_vehicle);
    (kept, excluded)
}

/// The modes by the identification asked for (or chosen by `automatic`).
fn identified_by_method(
    m: &Measurement,
    spectra: &[ChannelSpectrum],
    frequency_channel: Option<&String>,
) -> Result<(Vec<IdentifiedMode>, &'static str, Option<SubspaceSummary>), MeasureError> {
    let method = match m.spectrum.identification {
        Identification::Automatic if holds_free_vibration(m) => Identification::Subspace,
        Identification::Automatic => Identification::WelchPeaks,
        chosen => chosen,
    };
    let welch = || {
        (
            spectrum_peaks(spectra, frequency_channel),
            "welch_peaks",
            None,
        )
    };
    match method {
        Identification::WelchPeaks | Identification::Automatic => Ok(welch()),
        Identification::MatrixPencil => {
            let (modes, name) = matrix_pencil(m, spectra, frequency_channel)?;
            Ok((modes, name, None))
        }
        // The automatic choice falls back to the spectrum's peaks when the free vibration
        // proves too short for the subspace method after all.
        Identification::Subspace if m.spectrum.identification == Identification::Automatic => {
            Ok(subspace(m).unwrap_or_else(|_| welch()))
        }
        Identification::Subspace => subspace(m),
    }
}

/// Free vibration that the automatic identification needs before it takes the subspace
/// method [s]: two periods of a 1 Hz mode.
pub const MINIMUM_FREE_VIBRATION: f64 = 2.0;

/// Whether the record has an acceleration channel and holds at least
/// [`MINIMUM_FREE_VIBRATION`] after the vehicle has left.
fn holds_free_vibration(m: &Measurement) -> bool {
    let exit = crossing_window(m).and_then(|w| w.exit_time_s);
    let end = m.time[m.time.len() - 1];
    m.channels
        .iter()
        .any(|c| c.kind == MeasuredQuantity::Acceleration)
        && exit.is_some_and(|t| end - t >= MINIMUM_FREE_VIBRATION)
}

/// Every acceleration channel together: ERA of the free vibration after the vehicle has left
/// when the record holds one (the spectra's window), else SSI-COV of the whole record.
fn subspace(
    m: &Measurement,
) -> Result<(Vec<IdentifiedMode>, &'static str, Option<SubspaceSummary>), MeasureError> {
    let accelerations: Vec<_> = m
        .channels
        .iter()
        .filter(|c| c.kind == MeasuredQuantity::Acceleration)
        .collect();
    if accelerations.is_empty() {
        return Err(MeasureError::input(
            "spectrum.identification",
            "the subspace identification needs at least one acceleration channel",
        ));
    }
    // The response is free from the instant the last axle leaves: ERA needs no settling (a
    // Welch segment does), and the higher modes, damped faster, are strongest right then. The
    // free vibration is used whenever the record holds MINIMUM_FREE_VIBRATION of it (whatever
    // the Welch segment), unless the whole record is asked for.
    let exit = crossing_window(m).and_then(|w| w.exit_time_s);
    let (window, start) = match (m.spectrum.window, exit) {
        (Some(SpectrumWindow::Whole), _) => (SpectrumWindow::Whole, 0),
        (_, Some(t)) if holds_free_vibration(m) => (
            SpectrumWindow::FreeVibration,
            m.time.partition_point(|&s| s < t),
        ),
        (Some(SpectrumWindow::FreeVibration), _) => spectrum_window_from(m, 0.0)?,
        (None, _) => (SpectrumWindow::Whole, 0),
    };
    let options = SubspaceOptions {
        modes: modes_sought(m, window),
        min_frequency_hz: m.spectrum.min_frequency_hz.max(0.1),
        max_frequency_hz: m
            .spectrum
            .max_frequency_hz
            .min(0.999 * m.sampling_rate_hz / 2.0),
        ..SubspaceOptions::default()
    };
    let (series, rate) = band_limited(m, &accelerations, start, options.max_frequency_hz)?;
    let channels: Vec<&[f64]> = series.iter().map(Vec::as_slice).collect();
    let (result, name) = if window == SpectrumWindow::FreeVibration {
        (
            identify_free_response(&channels, rate, &options),
            "subspace_free_vibration",
        )
    } else {
        (
            identify_output_only(&channels, rate, &options),
            "subspace_whole_record",
        )
    };
    let result = result.map_err(|source| MeasureError::Spectrum {
        channel: accelerations[0].name.clone(),
        source,
    })?;
    let modes = result
        .modes
        .iter()
        .map(|p| IdentifiedMode {
            frequency_hz: p.frequency_hz,
            damping_ratio: Some(p.damping_ratio),
            damping_resolution_limited: false,
            frequency_std_hz: Some(p.frequency_std_hz),
            damping_std: Some(p.damping_std),
            shape: Some(p.shape.clone()),
            modal_phase_collinearity: Some(p.modal_phase_collinearity),
        })
        .collect();
    let summary = SubspaceSummary {
        channels: accelerations.iter().map(|c| c.name.clone()).collect(),
        method: result.method,
        start_time_s: m.time[start],
        block_rows: result.block_rows,
        max_order: options.max_order,
        diagram: result.diagram,
    };
    Ok((modes, name, Some(summary)))
}

/// The channels from sample `start` on, low-passed (zero-phase Butterworth of the record's
/// order, over the whole record so that the window starts clear of the filter's edge) at
/// 1.25 × the band's upper end and decimated to at least 4 × that cut-off, with their rate
/// [Hz]. The noise outside the band would otherwise enter the Hankel matrix and bias the weak
/// modes (on the 4 × 30 m record, mode 3 by +0.6 % at 0.0005 m/s² of noise); decimation also
/// lets the block rows span more periods.
fn band_limited(
    m: &Measurement,
    channels: &[&crate::measure::measurement::Channel],
    start: usize,
    max_frequency_hz: f64,
) -> Result<(Vec<Vec<f64>>, f64), MeasureError> {
    let fs = m.sampling_rate_hz;
    let cutoff = 1.25 * max_frequency_hz;
    if cutoff >= 0.8 * fs / 2.0 {
        let series = channels
            .iter()
            .map(|c| c.samples[start..].to_vec())
            .collect();
        return Ok((series, fs));
    }
    let factor = ((fs / (4.0 * cutoff)).floor() as usize).max(1);
    let filter = crate::signal::butterworth_lowpass(m.filter_order, cutoff, fs)?;
    let mut series = Vec::with_capacity(channels.len());
    for c in channels {
        let filtered =
            filter
                .filtfilt(&c.samples, None)
                .map_err(|source| MeasureError::Spectrum {
                    channel: c.name.clone(),
                    source,
                })?;
        series.push(filtered[start..].iter().step_by(factor).copied().collect());
    }
    Ok((series, fs / factor as f64))
}

/// The matrix pencil of the frequency channel's free vibration.
fn matrix_pencil(
    m: &Measurement,
    spectra: &[ChannelSpectrum],
    frequency_channel: Option<&String>,
) -> Result<(Vec<IdentifiedMode>, &'static str), MeasureError> {
    let spectrum = spectra
        .iter()
        .find(|s| Some(&s.channel) == frequency_channel);
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
            frequency_std_hz: None,
            damping_std: None,
            shape: None,
            modal_phase_collinearity: None,
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
                    frequency_std_hz: None,
                    damping_std: None,
                    shape: None,
                    modal_phase_collinearity: None,
                })
                .collect()
        })
        .unwrap_or_default()
}
