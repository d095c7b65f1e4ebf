//! The `[measurement]` input file: a CSV of time series with named channels, and how to process
//! them (static separation, spectra, cut-off-mode filtering, model updating). Units are
//! converted to SI here, once; bad data is refused with its file, line and column, nothing is
//! guessed (NaN, empty cells, a time axis that goes back or jumps, a sampling rate that does not
//! match the time column, a channel missing from the CSV).

use std::path::{Path, PathBuf};

use serde::Deserialize;
use vbi::measure::added_mass_per_length;
use vbi::measure::measurement::{
    Baseline, Channel, Identification, K1Source, MeasuredBridge, Measurement, SensorLocation,
    SpectrumSpec, SpectrumWindow, StaticReference, UpdatingSpec, VehicleTrack,
};
use vbi::measure::CalibrationParameter;
use vbi::modal::ModeKind;
use vbi::signal::{
    MeasuredQuantity, MovingLoads, SampledInfluenceLine, SignalError, StrainToMoment,
};
use vbi::units;

use crate::bridge;
use crate::logger_csv::{self, CsvFormat, LoggerTable, RawCsvFormat, ReadProblem, TimeFormat};
use crate::source::{require_in_range, require_positive, InputError, SourceFile};

/// Relative tolerance on the sampling interval: every Δt must lie within 1 % of the median Δt
/// (a larger step is a gap, a smaller one a duplicated or jittered sample), and a given
/// `sampling_rate_hz` must match 1/median Δt within 0.1 %.
const INTERVAL_TOLERANCE: f64 = 0.01;
const RATE_TOLERANCE: f64 = 0.001;
/// Highest rate a record is resampled to [Hz]: an upper bound on the samples it makes.
const MAX_RESAMPLE_HZ: f64 = 100_000.0;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Document {
    measurement: RawMeasurement,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMeasurement {
    version: Option<u32>,
    description: Option<String>,
    csv: String,
    csv_format: Option<RawCsvFormat>,
    time_column: Option<String>,
    sampling_rate_hz: Option<f64>,
    speed_kmh: Option<f64>,
    speed_m_s: Option<f64>,
    bridge_length_m: Option<f64>,
    span_length_m: Option<f64>,
    entry_time_s: Option<f64>,
    detect_entry: Option<bool>,
    baseline: Option<Baseline>,
    baseline_window_s: Option<f64>,
    crawl: Option<String>,
    resample_hz: Option<f64>,
    pass_duration_s: Option<f64>,
    first_frequency_hz: Option<f64>,
    bridge: Option<String>,
    bridge_modes: Option<usize>,
    #[serde(default)]
    filter: RawFilter,
    #[serde(default)]
    spectrum: RawSpectrum,
    vehicle: Option<RawVehicle>,
    updating: Option<RawUpdating>,
    channels: Vec<RawChannel>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFilter {
    order: Option<usize>,
    cutoff_hz: Option<f64>,
    k1_cutoff_hz: Option<f64>,
    k1_mode_deflection: Option<usize>,
    k1_mode_moment: Option<usize>,
    k1_from_run: Option<String>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpectrum {
    channel: Option<String>,
    segment_length: Option<usize>,
    fft_length: Option<usize>,
    modes: Option<usize>,
    min_frequency_hz: Option<f64>,
    max_frequency_hz: Option<f64>,
    min_prominence_db: Option<f64>,
    window: Option<SpectrumWindow>,
    identification: Option<Identification>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawVehicle {
    axle_loads_kn: Vec<f64>,
    axle_offsets_m: Vec<f64>,
    entry_time_s: Option<f64>,
    frequencies_hz: Option<Vec<f64>>,
    lateral_position_m: Option<f64>,
    track_width_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawUpdating {
    model_frequencies_hz: Option<Vec<f64>>,
    model_kinds: Option<Vec<ModeKind>>,
    identified_kinds: Option<Vec<ModeKind>>,
    #[serde(default)]
    fit_mass: bool,
    parameters: Option<Vec<CalibrationParameter>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawChannel {
    name: String,
    column: Option<String>,
    kind: MeasuredQuantity,
    /// Optional with `csv_format.unit_line`: then the CSV's unit line gives it.
    unit: Option<String>,
    section: Option<String>,
    k1_cutoff_hz: Option<f64>,
    k1_mode: Option<usize>,
    moment: Option<RawMoment>,
    /// A table `{ position_m, value_per_kn }`, or "model" or "crawl".
    static_reference: Option<toml::Value>,
    position_in_span: Option<f64>,
    position_m: Option<f64>,
    lateral_position_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMoment {
    modulus_gpa: Option<f64>,
    second_moment_m4: Option<f64>,
    distance_to_neutral_axis_m: Option<f64>,
    knm_per_microstrain: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInfluenceLine {
    position_m: Vec<f64>,
    /// Channel unit per kN.
    value_per_kn: Vec<f64>,
}

/// A measurement file, loaded and checked: the library's [`Measurement`] and the CSV it came
/// from.
#[derive(Debug, Clone)]
pub struct MeasurementFile {
    /// The measurement, in SI.
    pub measurement: Measurement,
    /// The CSV file, resolved against the TOML file's folder.
    pub csv_path: PathBuf,
}

/// Validates a `[measurement]` file (the TOML and its CSV).
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    load(file).map(|_| ())
}

/// SI factor of a unit for a kind of channel, or the list of allowed units.
fn unit_factor(kind: MeasuredQuantity, unit: &str) -> Result<f64, &'static str> {
    let u = unit.trim();
    match kind {
        MeasuredQuantity::Deflection => match u {
            "m" => Ok(1.0),
            "mm" => Ok(units::MM),
            "cm" => Ok(units::CM),
            _ => Err("m, cm, mm"),
        },
        MeasuredQuantity::Strain => match u {
            "strain" | "-" | "m/m" => Ok(1.0),
            "microstrain" | "µε" | "με" | "ue" | "µm/m" | "μm/m" | "um/m" => Ok(1e-6),
            _ => Err("strain (or - , m/m), microstrain (or µε, ue, µm/m)"),
        },
        MeasuredQuantity::BendingMoment => match u {
            "N·m" | "N.m" | "Nm" => Ok(1.0),
            "kN·m" | "kN.m" | "kNm" => Ok(units::KN),
            "MN·m" | "MN.m" | "MNm" => Ok(1e6),
            _ => Err("N·m, kN·m, MN·m (or N.m, kNm …)"),
        },
        MeasuredQuantity::Acceleration => match u {
            "m/s²" | "m/s2" | "m/s^2" => Ok(1.0),
            "g" => Ok(units::GRAVITY),
            "mg" => Ok(units::GRAVITY * 1e-3),
            "cm/s²" | "cm/s2" | "gal" | "Gal" => Ok(0.01),
            _ => Err("m/s² (or m/s2), g, mg, cm/s² (or Gal)"),
        },
    }
}

/// Loads the file and its CSV into SI, checking every value.
pub fn load(file: &SourceFile) -> Result<MeasurementFile, InputError> {
    let doc: Document = file.parse()?;
    let m = doc.measurement;
    let at = |key: &str| format!("measurement.{key}");
    if let Some(v) = m.version {
        if v != 1 {
            return Err(file.error_at(
                &at("version"),
                format!("version {v} is not supported; expected 1"),
            ));
        }
    }
    let folder = file.path.parent().unwrap_or(Path::new(""));
    // The bridge model.
    let bridge = match &m.bridge {
        None => None,
        Some(name) => {
            let path = folder.join(name);
            let source = SourceFile::read(&path).map_err(|e| {
                file.error_at(
                    &at("bridge"),
                    format!(
                        "cannot read the bridge file {}: {}",
                        path.display(),
                        e.message
                    ),
                )
            })?;
            let model = bridge::load(&source)?;
            if let vbi::model::BridgeModel::ImportedModes(_) = model {
                // Model updating scales an FE model's stiffness and mass and solves it again.
                return Err(file.error_at(
                    &at("bridge"),
                    format!(
                        "{} is an imported modal basis, which model updating cannot re-solve; \
                         expected a bridge with an FE model (a continuous beam, a grillage or \
                         imported matrices)",
                        path.display()
                    ),
                ));
            }
            let requested = m.bridge_modes.unwrap_or(DEFAULT_BRIDGE_MODES);
            if !(1..=500).contains(&requested) {
                return Err(file.error_at(
                    &at("bridge_modes"),
                    format!("{requested} is not allowed; expected 1 to 500 modes"),
                ));
            }
            let largest_k1 = m
                .channels
                .iter()
                .filter_map(|c| c.k1_mode)
                .chain(m.filter.k1_mode_deflection)
                .chain(m.filter.k1_mode_moment)
                .max()
                .unwrap_or(0);
            Some(MeasuredBridge {
                label: path.display().to_string(),
                model,
                mode_count: requested.max(largest_k1),
            })
        }
    };
    if m.bridge.is_none() && m.bridge_modes.is_some() {
        return Err(file.error_at(
            &at("bridge_modes"),
            "bridge_modes needs a bridge model: give bridge = \"file.toml\"",
        ));
    }
    // K1 from a `vbi run` summary.
    let run_k1 = match &m.filter.k1_from_run {
        None => None,
        Some(name) => Some(read_run_k1(file, &folder.join(name))?),
    };
    // Speed and pass frequency.
    let speed = match (m.speed_kmh, m.speed_m_s) {
        (Some(_), Some(_)) => {
            return Err(file.error_at(
                &at("speed_m_s"),
                "give the speed once: speed_kmh or speed_m_s, not both",
            ))
        }
        (Some(v), None) => Some(require_positive(file, &at("speed_kmh"), v, "km/h")? * units::KMH),
        (None, Some(v)) => Some(require_positive(file, &at("speed_m_s"), v, "m/s")?),
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
        (None, _) => pass_frequency(file, &m, speed)?,
    };
    let first_frequency_hz = m
        .first_frequency_hz
        .map(|f| require_positive(file, &at("first_frequency_hz"), f, "Hz"))
        .transpose()?;

    // Filter.
    let filter_order = m.filter.order.unwrap_or(4);
    if !(1..=12).contains(&filter_order) {
        return Err(file.error_at(
            &at("filter.order"),
            format!("order {filter_order} is not allowed; expected 1 to 12"),
        ));
    }

    // The CSV.
    if m.channels.is_empty() {
        return Err(file.error_at(&at("channels"), "at least one channel is required"));
    }
    let csv_path = folder.join(&m.csv);
    let table = read_table(file, &m, &csv_path)?;
    let csv_name = table.file.clone();
    let column_of = |name: &str| table.column(name);
    if table.rows.len() < 16 {
        return Err(file.error_at(
            &at("csv"),
            format!(
                "{csv_name} has {} data rows; at least 16 samples are needed",
                table.rows.len()
            ),
        ));
    }

    // Time axis.
    let TimeAxisRead {
        sampling_rate_hz,
        mut time,
        logger_times,
    } = time_axis(file, &m, &table)?;

    // Vehicle for influence-line references.
    let vehicle = match &m.vehicle {
        None => None,
        Some(v) => {
            if v.axle_loads_kn.is_empty() || v.axle_loads_kn.len() != v.axle_offsets_m.len() {
                return Err(file.error_at(
                    &at("vehicle.axle_offsets_m"),
                    format!(
                        "{} axle loads and {} axle offsets; expected one offset per load (the first 0)",
                        v.axle_loads_kn.len(),
                        v.axle_offsets_m.len()
                    ),
                ));
            }
            for (i, p) in v.axle_loads_kn.iter().enumerate() {
                require_positive(file, &at(&format!("vehicle.axle_loads_kn[{i}]")), *p, "kN")?;
            }
            for (i, d) in v.axle_offsets_m.iter().enumerate() {
                require_in_range(
                    file,
                    &at(&format!("vehicle.axle_offsets_m[{i}]")),
                    *d,
                    0.0,
                    f64::INFINITY,
                    "m",
                )?;
            }
            // Without a time of its own the vehicle enters at the record's entry time, given or
            // found in the record (the measurement stage sets it then).
            if v.entry_time_s.is_some() && m.detect_entry == Some(true) {
                return Err(file.error_at(
                    &at("detect_entry"),
                    "[measurement.vehicle] gives entry_time_s: the entry is not searched for; remove one of the two",
                ));
            }
            let entry = match (v.entry_time_s, m.entry_time_s, m.detect_entry) {
                (Some(t), _, _) | (None, Some(t), _) => t,
                (None, None, Some(true)) => 0.0,
                (None, None, _) => {
                    return Err(file.error_at(
                        &at("vehicle.entry_time_s"),
                        "the vehicle needs the time its first axle enters the bridge: give entry_time_s here or in [measurement], or detect_entry = true",
                    ))
                }
            };
            if !entry.is_finite() {
                return Err(
                    file.error_at(&at("vehicle.entry_time_s"), "expected a finite time in s")
                );
            }
            let speed = speed.ok_or_else(|| {
                file.error_at(
                    &at("speed_kmh"),
                    "[measurement.vehicle] needs the vehicle speed: give speed_kmh or speed_m_s",
                )
            })?;
            Some(MovingLoads {
                axle_loads: v.axle_loads_kn.iter().map(|p| p * units::KN).collect(),
                axle_offsets: v.axle_offsets_m.clone(),
                speed,
                entry_time: entry,
            })
        }
    };

    let record = prepare_record(file, &m, vehicle.as_ref())?;
    let crawl = match &m.crawl {
        None => None,
        Some(name) => Some(Box::new(load_crawl(
            file,
            &at("crawl"),
            &folder.join(name),
        )?)),
    };

    let vehicle_track = vehicle_track_of(file, &m)?;
    let context = ReferenceContext {
        has_vehicle: vehicle.is_some(),
        has_bridge: bridge.is_some(),
        has_crawl: crawl.is_some(),
        has_length: m.bridge_length_m.is_some() || bridge.is_some(),
    };

    // The spans the sensors' positions are read in: the bridge model's, else the loaded span
    // from the first support.
    let spans: Vec<f64> = match (&bridge, span_length) {
        (Some(b), _) => b.model.span_lengths().to_vec(),
        (None, Some(l)) => vec![l],
        (None, None) => Vec::new(),
    };

    // Channels.
    let nyquist = sampling_rate_hz / 2.0;
    let mut channels = Vec::with_capacity(m.channels.len());
    for (c, raw) in m.channels.iter().enumerate() {
        let key = |k: &str| format!("measurement.channels[{c}].{k}");
        if channels.iter().any(|o: &Channel| o.name == raw.name) {
            return Err(file.error_at(
                &key("name"),
                format!("channel `{}` is listed twice", raw.name),
            ));
        }
        let column = raw.column.clone().unwrap_or_else(|| raw.name.clone());
        let index = column_of(&column).ok_or_else(|| {
            file.error_at(
                &key(if raw.column.is_some() {
                    "column"
                } else {
                    "name"
                }),
                format!(
                    "channel `{column}` is missing from {csv_name}; {}",
                    table.columns_shown()
                ),
            )
        })?;
        let (unit, factor) = channel_unit(file, &table, c, raw, index)?;
        let samples: Vec<f64> = table
            .numbers(index)?
            .into_iter()
            .map(|v| v * factor)
            .collect();
        let k1_range = |path: String, f: f64| {
            require_in_range(
                file,
                &path,
                f,
                f64::MIN_POSITIVE,
                nyquist * 0.999,
                "Hz (below the Nyquist frequency)",
            )
        };
        let is_moment = matches!(
            raw.kind,
            MeasuredQuantity::Strain | MeasuredQuantity::BendingMoment
        );
        let (filter_mode, filter_mode_key) = if is_moment {
            (m.filter.k1_mode_moment, "filter.k1_mode_moment")
        } else {
            (m.filter.k1_mode_deflection, "filter.k1_mode_deflection")
        };
        if raw.k1_cutoff_hz.is_some() && raw.k1_mode.is_some() {
            return Err(file.error_at(
                &key("k1_mode"),
                "give the cut-off mode once: k1_cutoff_hz or k1_mode, not both",
            ));
        }
        let model_mode = |path: String, mode: usize| -> Result<K1Source, InputError> {
            if mode == 0 {
                return Err(file.error_at(
                    &path,
                    "mode 0 is not allowed; modes are numbered from 1 as `vbi modes` lists them",
                ));
            }
            if bridge.is_none() {
                return Err(file.error_at(
                    &path,
                    "a cut-off mode number needs a bridge model: give bridge = \"file.toml\", or the frequency as k1_cutoff_hz",
                ));
            }
            Ok(K1Source::ModelMode(mode))
        };
        let k1 = if raw.kind == MeasuredQuantity::Acceleration {
            if raw.k1_cutoff_hz.is_some() || raw.k1_mode.is_some() {
                return Err(file.error_at(
                    &key("k1_cutoff_hz"),
                    "an acceleration channel has no DAF and no cut-off mode",
                ));
            }
            None
        } else if let Some(f) = raw.k1_cutoff_hz {
            Some(K1Source::Given(k1_range(key("k1_cutoff_hz"), f)?))
        } else if let Some(mode) = raw.k1_mode {
            Some(model_mode(key("k1_mode"), mode)?)
        } else if let Some(f) = m.filter.k1_cutoff_hz {
            Some(K1Source::Given(k1_range(at("filter.k1_cutoff_hz"), f)?))
        } else if let Some(mode) = filter_mode {
            Some(model_mode(at(filter_mode_key), mode)?)
        } else if let Some(run) = &run_k1 {
            let found = if is_moment {
                run.moment
            } else {
                run.deflection
            };
            match found {
                Some((mode, f)) => {
                    k1_range(at("filter.k1_from_run"), f)?;
                    Some(K1Source::RunSummary {
                        mode,
                        frequency_hz: f,
                    })
                }
                None => None,
            }
        } else {
            None
        };
        let moment = match &raw.moment {
            None => None,
            Some(_) if raw.kind != MeasuredQuantity::Strain => {
                return Err(file.error_at(&key("moment"), "a strain-to-moment conversion applies to strain channels only"))
            }
            Some(mo) => Some(match (mo.knm_per_microstrain, mo.modulus_gpa, mo.second_moment_m4, mo.distance_to_neutral_axis_m) {
                (Some(f), None, None, None) => {
                    if !(f.is_finite() && f != 0.0) {
                        return Err(file.error_at(&key("moment.knm_per_microstrain"), format!("{f} is not allowed; expected a finite non-zero number")));
                    }
                    StrainToMoment::Factor { newton_metres_per_strain: f * units::KN * 1e6 }
                }
                (None, Some(e), Some(i), Some(y)) => {
                    let e = require_positive(file, &key("moment.modulus_gpa"), e, "GPa")?;
                    let i = require_positive(file, &key("moment.second_moment_m4"), i, "m⁴")?;
                    if !(y.is_finite() && y != 0.0) {
                        return Err(file.error_at(&key("moment.distance_to_neutral_axis_m"), format!("{y} is not allowed; expected a finite non-zero distance in m (positive below the neutral axis)")));
                    }
                    StrainToMoment::Section { elastic_modulus: e * units::GPA, second_moment_of_area: i, distance_to_neutral_axis: y }
                }
                _ => {
                    return Err(file.error_at(
                        &key("moment"),
                        "give either knm_per_microstrain, or all of modulus_gpa, second_moment_m4 and distance_to_neutral_axis_m",
                    ))
                }
            }),
        };
        let static_reference = static_reference_of(file, &key, raw, factor, &context)?;
        channels.push(Channel {
            name: raw.name.clone(),
            column,
            kind: raw.kind,
            unit,
            si_per_unit: factor,
            samples,
            section: raw.section.clone(),
            k1,
            moment,
            static_reference,
            position_in_span: position_in_span(file, &key, raw, &spans)?,
            location: sensor_location(file, &key, raw, m.bridge_length_m)?,
        });
    }

    let mut resampled_from_hz = None;
    if let Some(logger_times) = &logger_times {
        time = resample_record(
            file,
            logger_times,
            &mut channels,
            sampling_rate_hz,
            filter_order,
        )?;
        resampled_from_hz = Some(
            (logger_times.len() - 1) as f64
                / (logger_times[logger_times.len() - 1] - logger_times[0]),
        );
    }

    // Spectrum.
    let s = &m.spectrum;
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
        if n < segment_length.min(table.rows.len()) || n > 1 << 24 {
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

    let cutoff_hz = m
        .filter
        .cutoff_hz
        .map(|f| {
            require_in_range(
                file,
                &at("filter.cutoff_hz"),
                f,
                f64::MIN_POSITIVE,
                nyquist * 0.999,
                "Hz (below the Nyquist frequency)",
            )
        })
        .transpose()?;

    // Updating.
    let updating = match m.updating {
        None => None,
        Some(u) => {
            match (&u.model_frequencies_hz, &bridge) {
                (Some(_), Some(_)) => {
                    return Err(file.error_at(
                        &at("updating.model_frequencies_hz"),
                        "the model frequencies come from the bridge model; remove model_frequencies_hz or the bridge",
                    ))
                }
                (None, None) => {
                    return Err(file.error_at(
                        &at("updating"),
                        "model updating needs a model: give bridge = \"file.toml\" or [measurement.updating] model_frequencies_hz",
                    ))
                }
                _ => {}
            }
            if u.fit_mass {
                match &bridge {
                    None => {
                        return Err(file.error_at(
                            &at("updating.fit_mass"),
                            "a mass scale cannot be identified from model frequencies given as numbers: uniform stiffness and mass scales change every frequency alike (ω² ∝ k/m); name the bridge model (bridge = \"file.toml\"), whose added (pavement) mass is then scaled, or fit the stiffness alone (fit_mass = false)",
                        ));
                    }
                    Some(b) if added_mass_per_length(&b.model) <= 0.0 => {
                        return Err(file.error_at(
                            &at("updating.fit_mass"),
                            format!("the bridge {} has no added (pavement) mass to scale; fit the stiffness alone (fit_mass = false)", b.label),
                        ));
                    }
                    Some(_) => {}
                }
            }
            if let Some(freqs) = &u.model_frequencies_hz {
                if freqs.is_empty() {
                    return Err(file.error_at(
                        &at("updating.model_frequencies_hz"),
                        "at least one model frequency is required",
                    ));
                }
                for (i, f) in freqs.iter().enumerate() {
                    require_positive(
                        file,
                        &at(&format!("updating.model_frequencies_hz[{i}]")),
                        *f,
                        "Hz",
                    )?;
                    if i > 0 && *f < freqs[i - 1] {
                        return Err(file.error_at(
                            &at(&format!("updating.model_frequencies_hz[{i}]")),
                            "model frequencies must be in ascending order",
                        ));
                    }
                }
                if let Some(k) = &u.model_kinds {
                    if k.len() != freqs.len() {
                        return Err(file.error_at(
                            &at("updating.model_kinds"),
                            format!(
                                "{} kinds for {} model frequencies; expected one per frequency",
                                k.len(),
                                freqs.len()
                            ),
                        ));
                    }
                }
                if u.identified_kinds.is_some() != u.model_kinds.is_some() {
                    return Err(file.error_at(
                        &at("updating.identified_kinds"),
                        "give both model_kinds and identified_kinds, or neither",
                    ));
                }
            } else if u.model_kinds.is_some() {
                return Err(file.error_at(
                    &at("updating.model_kinds"),
                    "the kinds of the model modes come from the bridge model; remove model_kinds",
                ));
            }
            if !channels
                .iter()
                .any(|c| c.kind == MeasuredQuantity::Acceleration)
            {
                return Err(file.error_at(
                    &at("updating"),
                    "model updating needs identified frequencies: add an acceleration channel",
                ));
            }
            let parameters = u.parameters.unwrap_or_default();
            if !parameters.is_empty() {
                if bridge.is_none() {
                    return Err(file.error_at(
                        &at("updating.parameters"),
                        "calibration re-solves the bridge model: give bridge = \"file.toml\"",
                    ));
                }
                if u.fit_mass {
                    return Err(file.error_at(
                        &at("updating.fit_mass"),
                        "with parameters, the added mass is fitted by \"added_mass\" in the list; remove fit_mass",
                    ));
                }
                if u.identified_kinds.is_some() {
                    return Err(file.error_at(
                        &at("updating.identified_kinds"),
                        "calibration pairs modes by MAC at the sensors (position_m), or by order within the vertical bending modes; remove identified_kinds",
                    ));
                }
            }
            Some(UpdatingSpec {
                model_frequencies_hz: u.model_frequencies_hz,
                fit_mass: u.fit_mass,
                model_kinds: u.model_kinds,
                identified_kinds: u.identified_kinds,
                parameters,
            })
        }
    };

    let measurement = Measurement {
        description: m.description,
        sampling_rate_hz,
        resampled_from_hz,
        time,
        channels,
        speed,
        pass_frequency_hz,
        span_length,
        first_frequency_hz,
        filter_order,
        cutoff_hz,
        spectrum: SpectrumSpec {
            channel: s.channel.clone(),
            segment_length,
            fft_length: s.fft_length,
            modes,
            min_frequency_hz,
            max_frequency_hz,
            min_prominence_db,
            window: s.window,
            identification: s.identification.unwrap_or(Identification::Automatic),
        },
        vehicle,
        vehicle_track,
        updating,
        bridge,
        entry_time: record.entry_time,
        bridge_length: record.bridge_length,
        baseline: record.baseline,
        baseline_window: record.baseline_window,
        detect_entry: record.detect_entry,
        vehicle_frequencies_hz: vehicle_frequencies(file, m.vehicle.as_ref())?,
        crawl,
    };
    Ok(MeasurementFile {
        measurement,
        csv_path,
    })
}

/// `[measurement.vehicle] frequencies_hz`, each positive and finite.
fn vehicle_frequencies(
    file: &SourceFile,
    vehicle: Option<&RawVehicle>,
) -> Result<Vec<f64>, InputError> {
    let given = vehicle
        .and_then(|v| v.frequencies_hz.clone())
        .unwrap_or_default();
    for (i, f) in given.iter().enumerate() {
        require_positive(
            file,
            &format!("measurement.vehicle.frequencies_hz[{i}]"),
            *f,
            "Hz",
        )?;
    }
    Ok(given)
}

/// The record's time axis as read: the sampling rate and the times (uniform, or the logger's
/// own when resampling).
type ReadTimes = (f64, Vec<f64>);

/// The time axis: the sampling rate and uniform times t₀ + i/f_s (the time column must be
/// uniform within 1 %), or with `resample_hz` the logger's own times (jitter allowed, gaps
/// and non-increasing times refused) and the record resampled to `resample_hz`.
struct TimeAxisRead {
    /// f_s [Hz], `resample_hz` when resampling.
    sampling_rate_hz: f64,
    /// Uniform times [s] (the logger's own when resampling, replaced after it).
    time: Vec<f64>,
    /// The logger's times [s] when resampling.
    logger_times: Option<Vec<f64>>,
}

fn time_axis(
    file: &SourceFile,
    m: &RawMeasurement,
    table: &LoggerTable,
) -> Result<TimeAxisRead, InputError> {
    let (rate, times) = read_times(file, m, table)?;
    let Some(target) = m.resample_hz else {
        return Ok(TimeAxisRead {
            sampling_rate_hz: rate,
            time: times,
            logger_times: None,
        });
    };
    let key = "measurement.resample_hz";
    let target = require_in_range(
        file,
        key,
        target,
        rate / 100.0,
        (10.0 * rate).min(MAX_RESAMPLE_HZ),
        "Hz",
    )?;
    Ok(TimeAxisRead {
        sampling_rate_hz: target,
        time: times.clone(),
        logger_times: Some(times),
    })
}

/// Every channel resampled from the logger's times to `rate` [Hz] (an anti-alias low-pass of
/// `order` when the rate falls; [`vbi::signal::resample_channels`]); the new times.
fn resample_record(
    file: &SourceFile,
    logger_times: &[f64],
    channels: &mut [Channel],
    rate: f64,
    order: usize,
) -> Result<Vec<f64>, InputError> {
    let samples: Vec<&[f64]> = channels.iter().map(|c| c.samples.as_slice()).collect();
    let resampled =
        vbi::signal::resample_channels(logger_times, &samples, rate, order).map_err(|e| {
            file.error_at(
                "measurement.resample_hz",
                format!("the record cannot be resampled: {e}"),
            )
        })?;
    for (channel, values) in channels.iter_mut().zip(resampled.channels) {
        channel.samples = values;
    }
    Ok(resampled.time)
}

/// A given `sampling_rate_hz` must match the time column's mean rate within 0.1 %.
fn check_given_rate(
    file: &SourceFile,
    given: Option<f64>,
    measured_rate: f64,
    name: &str,
) -> Result<(), InputError> {
    let Some(fs) = given else { return Ok(()) };
    let key = "measurement.sampling_rate_hz";
    let fs = require_positive(file, key, fs, "Hz")?;
    if (measured_rate / fs - 1.0).abs() > RATE_TOLERANCE {
        return Err(file.error_at(
            key,
            format!(
                "{fs} Hz does not match the time column `{name}`, which is sampled at {measured_rate:.6} Hz; correct one of them"
            ),
        ));
    }
    Ok(())
}

fn read_times(
    file: &SourceFile,
    m: &RawMeasurement,
    table: &LoggerTable,
) -> Result<ReadTimes, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    let csv_name = &table.file;
    let column_of = |name: &str| table.column(name);
    match (&m.time_column, m.sampling_rate_hz) {
        (None, None) => Err(file.error_at(
            &at("sampling_rate_hz"),
            "give sampling_rate_hz or time_column (or both)",
        )),
        (None, Some(fs)) => {
            let fs = require_positive(file, &at("sampling_rate_hz"), fs, "Hz")?;
            Ok((fs, (0..table.rows.len()).map(|i| i as f64 / fs).collect()))
        }
        (Some(name), given) => {
            let index = column_of(name).ok_or_else(|| {
                file.error_at(
                    &at("time_column"),
                    format!(
                        "column `{name}` is not in {csv_name}; {}",
                        table.columns_shown()
                    ),
                )
            })?;
            let t = table.times(index)?;
            let mut steps: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
            for (i, dt) in steps.iter().enumerate() {
                if *dt <= 0.0 {
                    return Err(InputError {
                        file: csv_name.clone(),
                        location: Some((table.lines[i + 1], index + 1)),
                        field: Some(name.clone()),
                        message: format!(
                            "time {} s does not increase from {} s; the time column must increase strictly",
                            t[i + 1], t[i]
                        ),
                    });
                }
            }
            if m.resample_hz.is_some() {
                // Jitter is resampled away; a gap is refused by the check of the axis.
                let axis = vbi::signal::check_time_axis(&t).map_err(|e| {
                    let row = match &e {
                        SignalError::TimeGap { index, .. } => index + 1,
                        SignalError::TimeNotIncreasing { index, .. }
                        | SignalError::NonFiniteTime { index, .. } => *index,
                        _ => 0,
                    };
                    InputError {
                        file: csv_name.clone(),
                        location: Some((table.lines[row.min(t.len() - 1)], index + 1)),
                        field: Some(name.clone()),
                        message: format!("{e}"),
                    }
                })?;
                check_given_rate(file, given, axis.original_rate_hz, name)?;
                return Ok((axis.original_rate_hz, t));
            }
            steps.sort_by(f64::total_cmp);
            let median = steps[steps.len() / 2];
            for i in 0..t.len() - 1 {
                let dt = t[i + 1] - t[i];
                if (dt - median).abs() > INTERVAL_TOLERANCE * median {
                    let what = if dt > median {
                        "a gap"
                    } else {
                        "an irregular step"
                    };
                    return Err(InputError {
                        file: csv_name.clone(),
                        location: Some((table.lines[i + 1], index + 1)),
                        field: Some(name.clone()),
                        message: format!(
                            "{what}: time step {dt} s from {} s to {} s differs from the sampling interval {median} s by more than 1 %; samples must be uniform, or give resample_hz to resample a jittered record",
                            t[i], t[i + 1]
                        ),
                    });
                }
            }
            let measured_rate = (t.len() - 1) as f64 / (t[t.len() - 1] - t[0]);
            check_given_rate(file, given, measured_rate, name)?;
            let t0 = t[0];
            let rate = given.unwrap_or(measured_rate);
            Ok((rate, (0..t.len()).map(|i| t0 + i as f64 / rate).collect()))
        }
    }
}

/// Where the vehicle runs: `[measurement.vehicle]`'s `lateral_position_m` (default 0, the deck
/// centreline) and `track_width_m` (default 0, one wheel line).
fn vehicle_track_of(file: &SourceFile, m: &RawMeasurement) -> Result<VehicleTrack, InputError> {
    let Some(v) = &m.vehicle else {
        return Ok(VehicleTrack::default());
    };
    let at = |k: &str| format!("measurement.vehicle.{k}");
    let lateral_position =
        match v.lateral_position_m {
            Some(y) if !y.is_finite() => return Err(file.error_at(
                &at("lateral_position_m"),
                "expected a finite position in m from the deck centreline (positive to the left)",
            )),
            y => y.unwrap_or(0.0),
        };
    let track_width = v
        .track_width_m
        .map(|w| require_in_range(file, &at("track_width_m"), w, 0.0, 5.0, "m"))
        .transpose()?
        .unwrap_or(0.0);
    Ok(VehicleTrack {
        lateral_position,
        track_width,
    })
}

/// What a channel's static reference needs from the rest of the file.
struct ReferenceContext {
    has_vehicle: bool,
    has_bridge: bool,
    has_crawl: bool,
    has_length: bool,
}

/// A channel's `static_reference`: a table `{ position_m, value_per_kn }` (an influence line in
/// the channel unit per kN), "model" (the bridge model's line at `position_m`) or "crawl" (the
/// line calibrated from the crawl run); each needs `[measurement.vehicle]`.
fn static_reference_of(
    file: &SourceFile,
    key: &dyn Fn(&str) -> String,
    raw: &RawChannel,
    factor: f64,
    context: &ReferenceContext,
) -> Result<Option<StaticReference>, InputError> {
    let Some(value) = &raw.static_reference else {
        return Ok(None);
    };
    let field = key("static_reference");
    let refuse = |message: &str| Err(file.error_at(&field, message));
    if raw.kind == MeasuredQuantity::Acceleration {
        return refuse("an acceleration channel has no static reference");
    }
    if !context.has_vehicle {
        return refuse("a static reference from an influence line needs [measurement.vehicle] (axle loads, offsets, entry time)");
    }
    match value {
        toml::Value::String(name) if name == "model" => {
            if !context.has_bridge {
                return refuse("\"model\" reads the bridge model's influence line: give bridge = \"file.toml\"");
            }
            if raw.position_m.is_none() {
                return refuse("\"model\" reads the bridge model's influence line at the sensor: give position_m (and lateral_position_m on a grillage)");
            }
            if raw.kind == MeasuredQuantity::Strain && raw.moment.is_none() {
                return refuse("\"model\" reads a strain gauge through the model's moment line: give moment = { knm_per_microstrain = ... } or the section");
            }
            Ok(Some(StaticReference::BridgeModel))
        }
        toml::Value::String(name) if name == "crawl" => {
            if !context.has_crawl {
                return refuse("\"crawl\" calibrates the influence line from the crawl run: give crawl = \"file.toml\"");
            }
            if !context.has_length {
                return refuse("\"crawl\" calibrates the influence line over the whole bridge: give bridge_length_m or the bridge model");
            }
            Ok(Some(StaticReference::CrawlRun))
        }
        toml::Value::String(name) => Err(file.error_at(
            &field,
            format!("\"{name}\" is not a static reference; expected \"model\", \"crawl\" or a table {{ position_m = [...], value_per_kn = [...] }}"),
        )),
        table @ toml::Value::Table(_) => {
            let il: RawInfluenceLine = table.clone().try_into().map_err(|e: toml::de::Error| {
                file.error_at(&field, format!("{}; expected {{ position_m = [...], value_per_kn = [...] }}", e.message()))
            })?;
            let values = il
                .value_per_kn
                .iter()
                .map(|v| v * factor / units::KN)
                .collect();
            let line = SampledInfluenceLine::new(il.position_m, values)
                .map_err(|e| file.error_at(&key("static_reference.position_m"), e.to_string()))?;
            Ok(Some(StaticReference::Given(line)))
        }
        other => Err(file.error_at(
            &field,
            format!("a {} is not a static reference; expected \"model\", \"crawl\" or a table {{ position_m = [...], value_per_kn = [...] }}", other.type_str()),
        )),
    }
}

/// Largest difference between a given `position_in_span` and the one `position_m` gives [-].
const POSITION_IN_SPAN_TOLERANCE: f64 = 0.02;

/// The gauge's section as a fraction of its span (where the separation check puts the kink of
/// a moment line): `position_in_span` as given, else read from `position_m` in `spans` (the
/// bridge model's, or the loaded span from the first support), else mid-span. Both given must
/// agree within [`POSITION_IN_SPAN_TOLERANCE`]. A gauge over a support reads 0.01 or 0.99.
fn position_in_span(
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
fn sensor_location(
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

/// The crossing window and baseline keys, checked.
struct RecordKeys {
    entry_time: Option<f64>,
    detect_entry: bool,
    bridge_length: Option<f64>,
    baseline: Baseline,
    baseline_window: f64,
}

/// Reads `entry_time_s` (default: the vehicle's), `bridge_length_m`, `baseline` (default
/// `automatic`: an offset correction when the record holds the quiet window before the entry
/// time, else none) and `baseline_window_s` (default 1 s).
fn prepare_record(
    file: &SourceFile,
    m: &RawMeasurement,
    vehicle: Option<&MovingLoads>,
) -> Result<RecordKeys, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    let detect_entry = m.detect_entry.unwrap_or(false);
    if detect_entry && m.entry_time_s.is_some() {
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
        .map(|l| require_positive(file, &at("bridge_length_m"), l, "m"))
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
        bridge_length,
        baseline,
        baseline_window,
    })
}

/// A crawl run: a measurement file of its own, without a crawl run of its own.
fn load_crawl(file: &SourceFile, key: &str, path: &Path) -> Result<Measurement, InputError> {
    let source = SourceFile::read(path).map_err(|e| {
        file.error_at(
            key,
            format!(
                "cannot read the crawl run {}: {}",
                path.display(),
                e.message
            ),
        )
    })?;
    let crawl = load(&source)?.measurement;
    if crawl.crawl.is_some() {
        return Err(source.error_at(
            "measurement.crawl",
            "a crawl run cannot name a crawl run of its own",
        ));
    }
    Ok(crawl)
}

/// Modes computed for a bridge named in a measurement file when `bridge_modes` is absent.
pub const DEFAULT_BRIDGE_MODES: usize = 20;

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
            let l = require_positive(file, &at("bridge_length_m"), l, "m")?;
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

/// K1 of deflection and of moment, with their frequencies [Hz], from a run summary.
struct RunK1 {
    deflection: Option<(usize, f64)>,
    moment: Option<(usize, f64)>,
}

/// Reads `deck_participation.{deflection,moment}_k1` and `frequencies_hz` of a `vbi run`
/// summary.json.
fn read_run_k1(file: &SourceFile, path: &Path) -> Result<RunK1, InputError> {
    let key = "measurement.filter.k1_from_run";
    let text = crate::source::read_bounded(path, crate::source::MAX_DATA_FILE_BYTES)
        .map_err(|e| e.at_naming_key(file, key))?;
    let json: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| file.error_at(key, format!("{} is not JSON: {e}", path.display())))?;
    let frequencies: Option<Vec<f64>> = json["frequencies_hz"]
        .as_array()
        .map(|a| a.iter().filter_map(|v| v.as_f64()).collect());
    let Some(frequencies) = frequencies else {
        return Err(file.error_at(
            key,
            format!(
                "{} has no `frequencies_hz`; expected the summary.json of `vbi run`",
                path.display()
            ),
        ));
    };
    let k1 = |name: &str| -> Result<Option<(usize, f64)>, InputError> {
        match json["deck_participation"][name].as_u64() {
            None => Ok(None),
            Some(k) => {
                let k = k as usize;
                match k.checked_sub(1).and_then(|i| frequencies.get(i)) {
                    Some(f) => Ok(Some((k, *f))),
                    None => Err(file.error_at(
                        key,
                        format!(
                            "{} gives {name} = {k} but lists {} frequencies",
                            path.display(),
                            frequencies.len()
                        ),
                    )),
                }
            }
        }
    };
    Ok(RunK1 {
        deflection: k1("deflection_k1")?,
        moment: k1("moment_k1")?,
    })
}

/// The record's CSV, read as `csv_format` says (a missing table reads a plain CSV).
fn read_table(
    file: &SourceFile,
    m: &RawMeasurement,
    csv_path: &Path,
) -> Result<LoggerTable, InputError> {
    let key = "measurement.csv_format";
    let format = match &m.csv_format {
        None => CsvFormat::default(),
        Some(raw) => CsvFormat::from_raw(file, key, raw)?,
    };
    if format.time_format == TimeFormat::Timestamp && m.time_column.is_none() {
        return Err(file.error_at(
            &format!("{key}.time_format"),
            "time_format = \"timestamp\" reads the time column: give time_column",
        ));
    }
    logger_csv::read(csv_path, &format).map_err(|e| match e {
        ReadProblem::Unreadable(err) => err.at_naming_key(file, "measurement.csv"),
        ReadProblem::Key(k, message) => file.error_at(&format!("{key}.{k}"), message),
        ReadProblem::Csv(err) => err,
    })
}

/// A channel's unit and its SI factor: its `unit` key, or the CSV's unit line, or both when
/// they agree (the same unit, by its factor).
fn channel_unit(
    file: &SourceFile,
    table: &LoggerTable,
    c: usize,
    raw: &RawChannel,
    index: usize,
) -> Result<(String, f64), InputError> {
    let key = format!("measurement.channels[{c}].unit");
    let factor_at_key = |unit: &str| {
        unit_factor(raw.kind, unit).map_err(|allowed| {
            file.error_at(
                &key,
                format!(
                    "unit `{unit}` is not allowed for a {:?} channel; expected one of {allowed}",
                    raw.kind
                )
                .to_lowercase(),
            )
        })
    };
    match (&raw.unit, table.unit(index)) {
        (Some(unit), None) => Ok((unit.clone(), factor_at_key(unit)?)),
        (None, None) => Err(file.error_at(&key, missing_unit(table, index))),
        (None, Some((line, unit))) => {
            let kind = format!("{:?}", raw.kind).to_lowercase();
            let factor = unit_factor(raw.kind, unit).map_err(|allowed| InputError {
                file: table.file.clone(),
                location: Some((line, index + 1)),
                field: Some(table.header[index].clone()),
                message: format!(
                    "unit `{unit}` (csv_format.unit_line) is not allowed for a {kind} channel; \
                     expected one of {allowed}, or give the channel's unit in \
                     measurement.channels[{c}].unit"
                ),
            })?;
            Ok((unit.to_string(), factor))
        }
        (Some(given), Some((line, unit))) => {
            let factor = factor_at_key(given)?;
            match unit_factor(raw.kind, unit) {
                Ok(f) if f == factor => Ok((given.clone(), factor)),
                _ => Err(file.error_at(
                    &key,
                    format!(
                        "unit `{given}` differs from `{unit}`, the unit of column `{}` in the \
                         unit line of {} (line {line}, csv_format.unit_line); give the same \
                         unit, or remove this unit to take the unit line's",
                        table.header[index], table.file
                    ),
                )),
            }
        }
    }
}

fn missing_unit(table: &LoggerTable, index: usize) -> String {
    match &table.units {
        None => "missing field `unit`; give the channel's unit (or csv_format.unit_line, the \
                 line of the CSV that holds the units)"
            .to_string(),
        Some((line, _)) => format!(
            "the unit line of {} (line {line}) has no unit for column `{}`; give the channel's \
             unit",
            table.file, table.header[index]
        ),
    }
}
