//! Record preparation: the crossing window (when the vehicle enters and leaves the bridge) and
//! the zero-offset (baseline) correction of every channel from the quiet parts of the record.

use crate::units::shown;
use serde::Serialize;

use super::detection::{detect_entry, DetectedEntry};
use super::{error_chain, MeasureError};
use crate::measure::measurement::{Baseline, Measurement};
use crate::signal::MovingLoads;

/// Length assumed for a vehicle whose axle offsets are not given [m]: the longest legal
/// articulated trucks are 16.5–18.75 m (EU Directive 96/53/EC); 20 m keeps the free-vibration
/// window clear of the last axle.
pub const ASSUMED_VEHICLE_LENGTH: f64 = 20.0;

/// Settling time after the last axle leaves before the free vibration is used [s].
pub const FREE_VIBRATION_MARGIN: f64 = 0.5;

/// When the vehicle is on the bridge.
#[derive(Debug, Clone, Serialize)]
pub struct CrossingWindow {
    /// The first axle enters the bridge [s].
    pub entry_time_s: f64,
    /// The last axle leaves the bridge [s], when the bridge length and the speed are known.
    pub exit_time_s: Option<f64>,
    /// How the exit time was found, in words.
    pub exit_rule: String,
}

/// The baseline correction of one channel.
#[derive(Debug, Clone, Serialize)]
pub struct BaselineCorrection {
    /// Channel name.
    pub channel: String,
    /// Offset removed at the entry time, in the channel unit.
    pub offset: f64,
    /// Drift removed, in the channel unit per second (0 for an offset correction).
    pub drift_per_s: f64,
}

/// What was done to the record before the analysis.
#[derive(Debug, Clone, Serialize)]
pub struct RecordPreparation {
    /// The logger's mean sampling rate [Hz] when the record was resampled (`resample_hz`).
    pub resampled_from_hz: Option<f64>,
    /// The crossing window, when the entry time is known (given, or found in the record).
    pub crossing: Option<CrossingWindow>,
    /// The entry time found in the record, when none was given.
    pub detected_entry: Option<DetectedEntry>,
    /// The baseline correction applied (never `automatic`: what it resolved to).
    pub baseline: Baseline,
    /// Length of its quiet windows [s].
    pub baseline_window_s: f64,
    /// Per channel (empty without a correction).
    pub corrections: Vec<BaselineCorrection>,
    /// The crawl run's own preparation, when the record names one.
    pub crawl: Option<Box<RecordPreparation>>,
}

/// The crossing window: the entry time as given, the exit from the bridge length, the speed and
/// the vehicle's length (its last axle offset, or [`ASSUMED_VEHICLE_LENGTH`]).
pub fn crossing_window(m: &Measurement) -> Option<CrossingWindow> {
    let entry = m.entry_time?;
    let (exit, rule) = match (m.bridge_length, m.speed) {
        (Some(length), Some(speed)) => {
            let (vehicle, source) = match &m.vehicle {
                Some(v) => (
                    v.axle_offsets.iter().cloned().fold(0.0, f64::max),
                    "its last axle offset",
                ),
                None => (ASSUMED_VEHICLE_LENGTH, "an assumed vehicle length"),
            };
            let exit = entry + (length + vehicle) / speed;
            let rule = format!(
                "entry + (bridge length {length} m + {vehicle} m, {source}) / speed {speed:.3} m/s"
            );
            (Some(exit), rule)
        }
        _ => (
            None,
            "unknown: give bridge_length_m and the speed".to_string(),
        ),
    };
    Some(CrossingWindow {
        entry_time_s: entry,
        exit_time_s: exit,
        exit_rule: rule,
    })
}

/// The measurement with its baseline corrected, and what was done.
pub(super) fn prepare(m: &Measurement) -> Result<(Measurement, RecordPreparation), MeasureError> {
    let detected_entry = match m.entry_time {
        None if m.detect_entry => Some(detect_entry(m).ok_or_else(|| {
            MeasureError::input(
                "entry_time_s",
                format!(
                    "the vehicle's entry could not be found in the record: it needs the speed, span_length_m (or bridge_length_m) and a deflection, strain or moment channel whose static response explains at least {:.0} % of the record's variance; give entry_time_s instead",
                    100.0 * super::detection::MINIMUM_EXPLAINED_VARIANCE
                ),
            )
        })?),
        None if m.detect_entry_by_default => detect_entry(m),
        _ => None,
    };
    let mut prepared = m.clone();
    prepared.entry_time = m
        .entry_time
        .or(detected_entry.as_ref().map(|d| d.entry_time_s));
    if let (Some(found), Some(vehicle)) = (&detected_entry, prepared.vehicle.as_mut()) {
        vehicle.entry_time = found.entry_time_s;
    }
    let m = &prepared.clone();
    let crossing = crossing_window(m);
    let mut corrections = Vec::new();
    // The automatic correction is an offset when the record holds the window before entry.
    let before = match m.baseline {
        Baseline::None => None,
        Baseline::Automatic => quiet_before_entry(m, crossing.as_ref()).ok(),
        Baseline::Offset | Baseline::Linear => Some(quiet_before_entry(m, crossing.as_ref())?),
    };
    // The automatic correction uses the quiet windows the record holds (issue 52): a line
    // through the windows before entry and at the end when the record goes on past the exit
    // (a logger's drift), an offset with the window before entry alone, else none.
    let end = match (m.baseline, &before) {
        (Baseline::Automatic, Some(_)) => quiet_at_end(m, crossing.as_ref()).ok(),
        (Baseline::Linear, _) => Some(quiet_at_end(m, crossing.as_ref())?),
        _ => None,
    };
    let baseline = match (m.baseline, &before, &end) {
        (Baseline::Automatic, Some(_), Some(_)) => Baseline::Linear,
        (Baseline::Automatic, Some(_), None) => Baseline::Offset,
        (Baseline::Automatic, None, _) => Baseline::None,
        (chosen, _, _) => chosen,
    };
    if let Some(before) = before {
        let after = end;
        let entry = crossing.as_ref().map_or(before.time, |w| w.entry_time_s);
        for c in &mut prepared.channels {
            let (offset, drift) = baseline_of(&c.samples, &before, after.as_ref());
            for (x, t) in c.samples.iter_mut().zip(&m.time) {
                *x -= offset + drift * (t - before.time);
            }
            corrections.push(BaselineCorrection {
                channel: c.name.clone(),
                offset: (offset + drift * (entry - before.time)) / c.si_per_unit,
                drift_per_s: drift / c.si_per_unit,
            });
        }
    }
    let mut crawl_prepared = None;
    if let Some(crawl) = &m.crawl {
        let (crawl, crawl_preparation) = prepare_crawl(m, crawl)?;
        prepared.crawl = Some(Box::new(crawl));
        crawl_prepared = Some(Box::new(crawl_preparation));
    }
    let preparation = RecordPreparation {
        resampled_from_hz: m.resampled_from_hz,
        crossing,
        detected_entry,
        baseline,
        baseline_window_s: m.baseline_window,
        corrections,
        crawl: crawl_prepared,
    };
    Ok((prepared, preparation))
}

/// The crawl run prepared as a record of its own. It is the same vehicle: without axle loads
/// of its own it takes this record's (at its own speed and entry time) for its exit time. Its
/// errors point at this record's `crawl` key.
fn prepare_crawl(
    m: &Measurement,
    crawl: &Measurement,
) -> Result<(Measurement, RecordPreparation), MeasureError> {
    let mut crawl = crawl.clone();
    if crawl.vehicle.is_none() {
        if let (Some(v), Some(speed), Some(entry)) = (&m.vehicle, crawl.speed, crawl.entry_time) {
            crawl.vehicle = Some(MovingLoads {
                speed,
                entry_time: entry,
                ..v.clone()
            });
        }
    }
    prepare(&crawl)
        .map_err(|e| MeasureError::input("crawl", format!("the crawl run: {}", error_chain(&e))))
}

/// A quiet window of the record: its sample range and the time of its middle.
struct QuietWindow {
    range: std::ops::Range<usize>,
    time: f64,
}

impl QuietWindow {
    fn new(time: &[f64], start: f64, end: f64) -> Option<Self> {
        let first = time.partition_point(|&t| t < start);
        let last = time.partition_point(|&t| t < end);
        (last >= first + 10).then(|| QuietWindow {
            range: first..last,
            time: 0.5 * (time[first] + time[last - 1]),
        })
    }
}

/// The window of `baseline_window` seconds that ends when the vehicle enters.
fn quiet_before_entry(
    m: &Measurement,
    crossing: Option<&CrossingWindow>,
) -> Result<QuietWindow, MeasureError> {
    let entry = crossing.map(|w| w.entry_time_s).ok_or_else(|| {
        MeasureError::input(
            "baseline",
            "a baseline correction needs the time the vehicle enters the bridge: give entry_time_s (or [measurement.vehicle] entry_time_s), or baseline = \"none\"",
        )
    })?;
    QuietWindow::new(&m.time, entry - m.baseline_window, entry).ok_or_else(|| {
        MeasureError::input(
            "baseline_window_s",
            format!(
                "the record holds fewer than 10 samples in the {} s before the vehicle enters at {} s; start the record earlier, shorten baseline_window_s, or set baseline = \"none\"",
                shown(m.baseline_window),
                shown(entry)
            ),
        )
    })
}

/// The last `baseline_window` seconds of the record, which must start after the vehicle left.
fn quiet_at_end(
    m: &Measurement,
    crossing: Option<&CrossingWindow>,
) -> Result<QuietWindow, MeasureError> {
    let end = m.time[m.time.len() - 1];
    let start = end - m.baseline_window;
    let exit = crossing.and_then(|w| w.exit_time_s).ok_or_else(|| {
        MeasureError::input(
            "baseline",
            "a linear baseline needs the time the vehicle leaves the bridge: give bridge_length_m and the speed",
        )
    })?;
    if start < exit + FREE_VIBRATION_MARGIN {
        return Err(MeasureError::input(
            "baseline",
            format!("a linear baseline needs {} s of record after the vehicle has left (at {exit:.3} s) and settled; the record ends at {end} s", m.baseline_window),
        ));
    }
    QuietWindow::new(&m.time, start, end + 1.0).ok_or_else(|| {
        MeasureError::input(
            "baseline_window_s",
            "the last window holds fewer than 10 samples",
        )
    })
}

/// Offset (at the middle of the window before entry) and drift per second of one channel: the
/// mean of the window before, and the slope to the mean of the window after when given. The
/// free vibration in the last window averages out over its periods (its mean is below its
/// amplitude over the number of periods).
fn baseline_of(samples: &[f64], before: &QuietWindow, after: Option<&QuietWindow>) -> (f64, f64) {
    let mean =
        |w: &QuietWindow| samples[w.range.clone()].iter().sum::<f64>() / w.range.len() as f64;
    let offset = mean(before);
    let drift = after.map_or(0.0, |a| (mean(a) - offset) / (a.time - before.time));
    (offset, drift)
}
