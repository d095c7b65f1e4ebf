//! The top-level keys of `[measurement]` that describe the record and the crossing: `version`,
//! the speed (`speed_kmh` or `speed_m_s`), the pass frequency (`span_length_m`,
//! `bridge_length_m` or `pass_duration_s`), `first_frequency_hz`, the crossing window
//! (`entry_time_s`, `detect_entry`) and the baseline keys.

use vbi::measure::measurement::Baseline;
use vbi::signal::MovingLoads;
use vbi::units;

use crate::measurement::raw::RawMeasurement;
use crate::source::{require_in_range, require_positive, InputError, SourceFile};
use crate::values::key_range;

/// `version`: 1 when given.
pub(crate) fn check_version(file: &SourceFile, m: &RawMeasurement) -> Result<(), InputError> {
    let at = |key: &str| format!("measurement.{key}");
    if let Some(v) = m.version {
        if v != 1 {
            return Err(file.error_at(
                &at("version"),
                format!("version {v} is not supported; expected 1"),
            ));
        }
    }
    Ok(())
}

/// The vehicle's speed and what it sets: the pass frequency and the loaded span.
pub(crate) struct Crossing {
    /// Vehicle speed [m/s] (`speed_kmh` converted with [`units::KMH`], or `speed_m_s`).
    pub(crate) speed: Option<f64>,
    /// `span_length_m` [m], 1 to 1000 m.
    pub(crate) span_length: Option<f64>,
    /// v/L of the loaded span or of the bridge, or 1/T_pass [Hz].
    pub(crate) pass_frequency_hz: Option<f64>,
    /// `first_frequency_hz` [Hz].
    pub(crate) first_frequency_hz: Option<f64>,
}

/// The speed, the span length, the pass frequency and the first frequency, checked in that
/// order.
pub(crate) fn crossing(file: &SourceFile, m: &RawMeasurement) -> Result<Crossing, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    let speed = match (m.speed_kmh, m.speed_m_s) {
        (Some(_), Some(_)) => {
            return Err(file.error_at(
                &at("speed_m_s"),
                "give the speed once: speed_kmh or speed_m_s, not both",
            ))
        }
        // The scenario's speed range (the key table's), in the unit the file gives.
        (Some(v), None) => {
            let (low, high) = key_range("speed_kmh");
            Some(require_in_range(file, &at("speed_kmh"), v, low, high, "km/h")? * units::KMH)
        }
        (None, Some(v)) => {
            let (low, high) = key_range("speed_kmh");
            let (low, high) = (low * units::KMH, high * units::KMH);
            Some(require_in_range(
                file,
                &at("speed_m_s"),
                v,
                low,
                high,
                "m/s",
            )?)
        }
        (None, None) => None,
    };
    let span_length = m
        .span_length_m
        .map(|l| require_in_range(file, &at("span_length_m"), l, 1.0, 1000.0, "m"))
        .transpose()?;
    let pass_frequency_hz = match (span_length, m.pass_duration_s) {
        (Some(_), Some(_)) => {
            return Err(file.error_at(
                &at("pass_duration_s"),
                "give span_length_m (with a speed) or pass_duration_s, not both",
            ))
        }
        (Some(l), None) => {
            let v = speed.ok_or_else(|| {
                file.error_at(
                    &at("speed_kmh"),
                    "span_length_m needs the vehicle speed: give speed_kmh or speed_m_s",
                )
            })?;
            Some(v / l)
        }
        (None, _) => pass_frequency(file, m, speed)?,
    };
    let first_frequency_hz = m
        .first_frequency_hz
        .map(|f| require_positive(file, &at("first_frequency_hz"), f, "Hz"))
        .transpose()?;
    Ok(Crossing {
        speed,
        span_length,
        pass_frequency_hz,
        first_frequency_hz,
    })
}

/// The pass frequency without a loaded span: v/L of the whole bridge, or 1/T_pass [Hz].
fn pass_frequency(
    file: &SourceFile,
    m: &RawMeasurement,
    speed: Option<f64>,
) -> Result<Option<f64>, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    Ok(match (m.bridge_length_m, m.pass_duration_s) {
        (Some(_), Some(_)) => {
            return Err(file.error_at(
                &at("pass_duration_s"),
                "give bridge_length_m (with a speed) or pass_duration_s, not both",
            ))
        }
        (Some(l), None) => {
            let l = bridge_length(file, l)?;
            let v = speed.ok_or_else(|| {
                file.error_at(
                    &at("speed_kmh"),
                    "bridge_length_m needs the vehicle speed: give speed_kmh or speed_m_s",
                )
            })?;
            Some(v / l)
        }
        (None, Some(t)) => Some(1.0 / require_positive(file, &at("pass_duration_s"), t, "s")?),
        (None, None) => None,
    })
}

/// The longest bridge a measurement may name [m]: 20 km, longer than any bridge crossed as
/// one record (the span lengths of a model are each at most 1000 m). A length of 1e20 m made
/// the crossing window's samples NaN deep in the processing (issue 47).
const LONGEST_BRIDGE_M: f64 = 20_000.0;

/// `bridge_length_m` [m], from 1 m to [`LONGEST_BRIDGE_M`].
fn bridge_length(file: &SourceFile, length: f64) -> Result<f64, InputError> {
    require_in_range(
        file,
        "measurement.bridge_length_m",
        length,
        1.0,
        LONGEST_BRIDGE_M,
        "m",
    )
}

/// The crossing window and baseline keys, checked.
pub(crate) struct RecordKeys {
    /// `entry_time_s` [s], or the vehicle's; `None` when searched for or without a vehicle.
    pub(crate) entry_time: Option<f64>,
    /// `detect_entry`: asked for, or needed by the vehicle's axles without an entry time.
    pub(crate) detect_entry: bool,
    /// The entry looked for by default: no entry time and no vehicle, `detect_entry` not given.
    pub(crate) detect_entry_by_default: bool,
    /// `bridge_length_m` [m].
    pub(crate) bridge_length: Option<f64>,
    /// `baseline`.
    pub(crate) baseline: Baseline,
    /// `baseline_window_s` [s].
    pub(crate) baseline_window: f64,
}

/// Reads `entry_time_s` (default: the vehicle's), `bridge_length_m`, `baseline` (default
/// `automatic`: a line through the quiet windows before entry and at the end when the record
/// holds both, an offset with the first alone, else none) and `baseline_window_s` (default 1 s).
pub(crate) fn prepare_record(
    file: &SourceFile,
    m: &RawMeasurement,
    vehicle: Option<&MovingLoads>,
) -> Result<RecordKeys, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    // Without an entry time (the record's or the vehicle's) the entry is looked for unless
    // `detect_entry = false`: the vehicle's axles need it (refused when not found), a record
    // without them goes on without it.
    let vehicle_entry = m.vehicle.as_ref().is_some_and(|v| v.entry_time_s.is_some());
    let without_entry = m.entry_time_s.is_none() && !vehicle_entry;
    let by_default = m.detect_entry.is_none() && without_entry;
    let detect_entry = m.detect_entry.unwrap_or(false) || (by_default && vehicle.is_some());
    let detect_entry_by_default = by_default && vehicle.is_none();
    if m.detect_entry == Some(true) && m.entry_time_s.is_some() {
        return Err(file.error_at(
            &at("detect_entry"),
            "entry_time_s is given: the entry is not searched for; remove one of the two",
        ));
    }
    let entry_time = match (m.entry_time_s, vehicle) {
        (None, Some(_)) if detect_entry => None,
        (Some(t), _) if !t.is_finite() => {
            return Err(file.error_at(&at("entry_time_s"), "expected a finite time in s"))
        }
        (Some(t), _) => Some(t),
        (None, Some(v)) => Some(v.entry_time),
        (None, None) => None,
    };
    let bridge_length = m
        .bridge_length_m
        .map(|l| bridge_length(file, l))
        .transpose()?;
    let baseline = m.baseline.unwrap_or(Baseline::Automatic);
    let baseline_window = m
        .baseline_window_s
        .map(|w| require_in_range(file, &at("baseline_window_s"), w, 0.05, 600.0, "s"))
        .transpose()?
        .unwrap_or(1.0);
    Ok(RecordKeys {
        entry_time,
        detect_entry,
        detect_entry_by_default,
        bridge_length,
        baseline,
        baseline_window,
    })
}
