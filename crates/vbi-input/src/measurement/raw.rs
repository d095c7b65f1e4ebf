//! The `[measurement]` table as written: one struct per sub-table (`[measurement.filter]`,
//! `[measurement.spectrum]`, `[measurement.vehicle]`, `[measurement.updating]`,
//! `[[measurement.channels]]`), in the file's units, before any check.

use serde::Deserialize;
use vbi::measure::measurement::{Baseline, Identification, SpectrumWindow};
use vbi::measure::CalibrationParameter;
use vbi::modal::ModeKind;
use vbi::signal::MeasuredQuantity;

use crate::logger_csv::RawCsvFormat;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Document {
    pub(crate) measurement: RawMeasurement,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMeasurement {
    pub(crate) version: Option<u32>,
    pub(crate) description: Option<String>,
    pub(crate) csv: String,
    pub(crate) csv_format: Option<RawCsvFormat>,
    pub(crate) time_column: Option<String>,
    pub(crate) sampling_rate_hz: Option<f64>,
    pub(crate) speed_kmh: Option<f64>,
    pub(crate) speed_m_s: Option<f64>,
    pub(crate) bridge_length_m: Option<f64>,
    pub(crate) span_length_m: Option<f64>,
    pub(crate) entry_time_s: Option<f64>,
    pub(crate) detect_entry: Option<bool>,
    pub(crate) baseline: Option<Baseline>,
    pub(crate) baseline_window_s: Option<f64>,
    pub(crate) crawl: Option<String>,
    pub(crate) resample_hz: Option<f64>,
    pub(crate) pass_duration_s: Option<f64>,
    pub(crate) first_frequency_hz: Option<f64>,
    pub(crate) bridge: Option<String>,
    pub(crate) bridge_modes: Option<usize>,
    #[serde(default)]
    pub(crate) filter: RawFilter,
    #[serde(default)]
    pub(crate) spectrum: RawSpectrum,
    pub(crate) vehicle: Option<RawVehicle>,
    pub(crate) weighing: Option<RawWeighing>,
    pub(crate) updating: Option<RawUpdating>,
    pub(crate) channels: Vec<RawChannel>,
}

/// `[measurement.weighing]`: bridge weigh-in-motion of the record's vehicle.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawWeighing {
    pub(crate) channels: Option<Vec<String>>,
    pub(crate) fit_entry: Option<bool>,
    pub(crate) split_groups: Option<bool>,
    pub(crate) low_pass: Option<bool>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawFilter {
    pub(crate) order: Option<usize>,
    pub(crate) cutoff_hz: Option<f64>,
    pub(crate) k1_cutoff_hz: Option<f64>,
    pub(crate) k1_mode_deflection: Option<usize>,
    pub(crate) k1_mode_moment: Option<usize>,
    pub(crate) k1_from_run: Option<String>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSpectrum {
    pub(crate) channel: Option<String>,
    pub(crate) segment_length: Option<usize>,
    pub(crate) fft_length: Option<usize>,
    pub(crate) modes: Option<usize>,
    pub(crate) min_frequency_hz: Option<f64>,
    pub(crate) max_frequency_hz: Option<f64>,
    pub(crate) min_prominence_db: Option<f64>,
    pub(crate) window: Option<SpectrumWindow>,
    pub(crate) identification: Option<Identification>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawVehicle {
    #[serde(default)]
    pub(crate) axle_loads_kn: Vec<f64>,
    pub(crate) axle_offsets_m: Vec<f64>,
    pub(crate) entry_time_s: Option<f64>,
    pub(crate) frequencies_hz: Option<Vec<f64>>,
    pub(crate) lateral_position_m: Option<f64>,
    pub(crate) track_width_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawUpdating {
    pub(crate) model_frequencies_hz: Option<Vec<f64>>,
    pub(crate) model_kinds: Option<Vec<ModeKind>>,
    pub(crate) identified_kinds: Option<Vec<ModeKind>>,
    #[serde(default)]
    pub(crate) fit_mass: bool,
    pub(crate) parameters: Option<Vec<CalibrationParameter>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawChannel {
    pub(crate) name: String,
    pub(crate) column: Option<String>,
    pub(crate) kind: MeasuredQuantity,
    /// Optional with `csv_format.unit_line`: then the CSV's unit line gives it.
    pub(crate) unit: Option<String>,
    pub(crate) section: Option<String>,
    pub(crate) k1_cutoff_hz: Option<f64>,
    pub(crate) k1_mode: Option<usize>,
    pub(crate) moment: Option<RawMoment>,
    /// A table `{ position_m, value_per_kn }`, or "model" or "crawl".
    pub(crate) static_reference: Option<toml::Value>,
    pub(crate) position_in_span: Option<f64>,
    pub(crate) position_m: Option<f64>,
    pub(crate) lateral_position_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMoment {
    pub(crate) modulus_gpa: Option<f64>,
    pub(crate) second_moment_m4: Option<f64>,
    pub(crate) distance_to_neutral_axis_m: Option<f64>,
    pub(crate) knm_per_microstrain: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawInfluenceLine {
    pub(crate) position_m: Vec<f64>,
    /// Channel unit per kN.
    pub(crate) value_per_kn: Vec<f64>,
}
