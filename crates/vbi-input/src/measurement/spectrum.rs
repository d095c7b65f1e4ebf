//! `[measurement.spectrum]`: which channel's spectrum, the Welch segments, how many modes are
//! sought and where.

use vbi::measure::measurement::{Channel, Identification, SpectrumSpec};
use vbi::signal::MeasuredQuantity;

use crate::measurement::raw::RawSpectrum;
use crate::source::{require_in_range, InputError, SourceFile};

/// The spectrum keys, checked against the channels, the record's `row_count` samples and its
/// Nyquist frequency [Hz]: `channel` an acceleration channel, `segment_length` 16 to 2²² samples,
/// `fft_length` at least the segment (or the record) and at most 2²⁴, `modes` 1 to 50, the
/// frequency band within 0 to Nyquist, `min_prominence_db` 0 to 200 dB.
pub(crate) fn spectrum(
    file: &SourceFile,
    s: &RawSpectrum,
    channels: &[Channel],
    row_count: usize,
    nyquist: f64,
) -> Result<SpectrumSpec, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    if let Some(name) = &s.channel {
        match channels.iter().find(|c| &c.name == name) {
            Some(c) if c.kind == MeasuredQuantity::Acceleration => {}
            Some(_) => {
                return Err(file.error_at(
                    &at("spectrum.channel"),
                    format!("channel `{name}` is not an acceleration channel"),
                ))
            }
            None => {
                return Err(file.error_at(
                    &at("spectrum.channel"),
                    format!("no channel is named `{name}`"),
                ))
            }
        }
    }
    let segment_length = s.segment_length.unwrap_or(1024);
    if !(16..=1 << 22).contains(&segment_length) {
        return Err(file.error_at(
            &at("spectrum.segment_length"),
            format!("{segment_length} is not allowed; expected 16 to 4194304 samples"),
        ));
    }
    if let Some(n) = s.fft_length {
        if n < segment_length.min(row_count) || n > 1 << 24 {
            return Err(file.error_at(&at("spectrum.fft_length"), format!("{n} is not allowed; expected at least the segment length ({segment_length}) and at most 16777216")));
        }
    }
    let modes = s.modes.unwrap_or(3);
    if !(1..=50).contains(&modes) {
        return Err(file.error_at(
            &at("spectrum.modes"),
            format!("{modes} is not allowed; expected 1 to 50"),
        ));
    }
    let min_frequency_hz = require_in_range(
        file,
        &at("spectrum.min_frequency_hz"),
        s.min_frequency_hz.unwrap_or(0.5),
        0.0,
        nyquist,
        "Hz",
    )?;
    let max_frequency_hz = require_in_range(
        file,
        &at("spectrum.max_frequency_hz"),
        s.max_frequency_hz.unwrap_or(nyquist),
        min_frequency_hz,
        nyquist,
        "Hz",
    )?;
    let min_prominence_db = require_in_range(
        file,
        &at("spectrum.min_prominence_db"),
        s.min_prominence_db.unwrap_or(6.0),
        0.0,
        200.0,
        "dB",
    )?;

    Ok(SpectrumSpec {
        channel: s.channel.clone(),
        segment_length,
        fft_length: s.fft_length,
        modes,
        min_frequency_hz,
        max_frequency_hz,
        min_prominence_db,
        window: s.window,
        identification: s.identification.unwrap_or(Identification::Automatic),
    })
}
