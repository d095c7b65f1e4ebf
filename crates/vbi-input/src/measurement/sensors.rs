//! Where a channel's sensor is: `position_m`, `lateral_position_m` and `position_in_span` of
//! `[[measurement.channels]]`.

use vbi::measure::measurement::SensorLocation;

use crate::measurement::raw::RawChannel;
use crate::source::{require_in_range, InputError, SourceFile};

/// Largest difference between a given `position_in_span` and the one `position_m` gives [-].
const POSITION_IN_SPAN_TOLERANCE: f64 = 0.02;

/// The gauge's section as a fraction of its span (where the separation check puts the kink of
/// a moment line): `position_in_span` as given, else read from `position_m` in `spans` (the
/// bridge model's, or the loaded span from the first support), else mid-span. Both given must
/// agree within [`POSITION_IN_SPAN_TOLERANCE`]. A gauge over a support reads 0.01 or 0.99.
pub(crate) fn position_in_span(
    file: &SourceFile,
    key: &dyn Fn(&str) -> String,
    raw: &RawChannel,
    spans: &[f64],
) -> Result<f64, InputError> {
    let given = raw
        .position_in_span
        .map(|p| {
            require_in_range(
                file,
                &key("position_in_span"),
                p,
                0.01,
                0.99,
                "(fraction of the span)",
            )
        })
        .transpose()?;
    let derived = raw.position_m.and_then(|x| {
        let mut start = 0.0;
        for (k, &length) in spans.iter().enumerate() {
            if x <= start + length {
                return Some((k, start, length, ((x - start) / length).clamp(0.01, 0.99)));
            }
            start += length;
        }
        None
    });
    match (given, derived) {
        (Some(p), Some((k, start, length, q))) if (p - q).abs() > POSITION_IN_SPAN_TOLERANCE => {
            Err(file.error_at(
                &key("position_in_span"),
                format!(
                    "{p} contradicts position_m = {} m, which is {q:.3} of span {} ({start} to {} m); give one of them, or correct it",
                    raw.position_m.unwrap_or_default(),
                    k + 1,
                    start + length
                ),
            ))
        }
        (Some(p), _) => Ok(p),
        (None, Some((_, _, _, q))) => Ok(q),
        (None, None) => Ok(0.5),
    }
}

/// A channel's place on the deck (`position_m`, with `lateral_position_m`, default 0 on the
/// centreline), checked against the bridge length when given.
pub(crate) fn sensor_location(
    file: &SourceFile,
    key: &dyn Fn(&str) -> String,
    raw: &RawChannel,
    bridge_length: Option<f64>,
) -> Result<Option<SensorLocation>, InputError> {
    let Some(position) = raw.position_m else {
        if raw.lateral_position_m.is_some() {
            return Err(file.error_at(
                &key("lateral_position_m"),
                "lateral_position_m needs position_m, the sensor's distance from the first support",
            ));
        }
        return Ok(None);
    };
    let length = bridge_length.unwrap_or(f64::INFINITY);
    let position = require_in_range(file, &key("position_m"), position, 0.0, length, "m")?;
    let lateral = raw.lateral_position_m.unwrap_or(0.0);
    let lateral = require_in_range(
        file,
        &key("lateral_position_m"),
        lateral,
        -100.0,
        100.0,
        "m",
    )?;
    Ok(Some(SensorLocation {
        position,
        lateral_position: lateral,
    }))
}
