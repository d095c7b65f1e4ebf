//! The `[measurement]` input file: a CSV of time series with named channels, and how to process
//! them (static separation, spectra, cut-off-mode filtering, model updating). Units are
//! converted to SI here, once; bad data is refused with its file, line and column, nothing is
//! guessed (NaN, empty cells, a time axis that goes back or jumps, a sampling rate that does not
//! match the time column, a channel missing from the CSV).

//!
//! One module per part of the file: [`raw`] (the table as written), [`bridge_model`] (`bridge`,
//! `bridge_modes`, `k1_from_run`), [`record`] (the crossing and the record's window),
//! [`record_csv`] (the CSV and its time axis), [`filter`], [`vehicle`], [`channels`] (with
//! [`channel_units`], [`influence`] and [`sensors`]), [`spectrum`] and [`updating`]. [`load`]
//! reads them in that order, so the first refusal of a bad file is always the same.

use std::path::{Path, PathBuf};

use vbi::measure::measurement::Measurement;

use crate::source::{InputError, SourceFile};

mod bridge_model;
mod channel_units;
mod channels;
mod filter;
mod influence;
mod raw;
mod record;
mod record_csv;
mod sensors;
mod spectrum;
mod updating;
mod vehicle;

pub use self::bridge_model::DEFAULT_BRIDGE_MODES;
use self::channels::ChannelSettings;
use self::influence::ReferenceContext;
use self::raw::Document;
use self::record_csv::TimeAxisRead;

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

/// Loads the file and its CSV into SI, checking every value: one step per part of the file,
/// in a fixed order (the first refusal of a bad file is always the same).
pub fn load(file: &SourceFile) -> Result<MeasurementFile, InputError> {
    let doc: Document = file.parse()?;
    let m = doc.measurement;
    record::check_version(file, &m)?;
    let folder = file.path.parent().unwrap_or(Path::new(""));
    let bridge = bridge_model::measured_bridge(file, &m, folder)?;
    let run_k1 = bridge_model::run_k1(file, &m, folder)?;
    let crossing = record::crossing(file, &m)?;
    let filter_order = filter::filter_order(file, &m.filter)?;
    let (csv_path, table) = record_csv::record_table(file, &m, folder)?;
    let TimeAxisRead {
        sampling_rate_hz,
        mut time,
        logger_times,
    } = record_csv::time_axis(file, &m, &table)?;
    let vehicle = vehicle::moving_loads(file, &m, crossing.speed)?;
    let weighing = vehicle::weighing_request(&m);
    let record = record::prepare_record(file, &m, vehicle.as_ref())?;
    refuse_an_entry_after_the_record(file, &m, record.entry_time, &time)?;
    let crawl = match &m.crawl {
        None => None,
        Some(name) => {
            let crawl = load_crawl(file, "measurement.crawl", &folder.join(name))?;
            refuse_a_crawl_not_slower(file, crawl.speed, crossing.speed)?;
            refuse_a_crawl_without_channels(file, &m, &crawl)?;
            Some(Box::new(crawl))
        }
    };
    let vehicle_track = vehicle::vehicle_track_of(file, &m)?;
    let context = ReferenceContext {
        has_vehicle: vehicle.is_some(),
        has_bridge: bridge.is_some(),
        has_crawl: crawl.is_some(),
        has_length: m.bridge_length_m.is_some() || bridge.is_some(),
    };
    // The spans the sensors' positions are read in: the bridge model's, else the loaded span
    // from the first support.
    let spans: Vec<f64> = match (&bridge, crossing.span_length) {
        (Some(b), _) => b.model.span_lengths().to_vec(),
        (None, Some(l)) => vec![l],
        (None, None) => Vec::new(),
    };
    let settings = ChannelSettings {
        table: &table,
        sampling_rate_hz,
        has_bridge: bridge.is_some(),
        run_k1: run_k1.as_ref(),
        context: &context,
        spans: &spans,
    };
    let mut channels = channels::channels(file, &m, &settings)?;
    let mut resampled_from_hz = None;
    if let Some(logger_times) = &logger_times {
        time = record_csv::resample_record(
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
    let nyquist = sampling_rate_hz / 2.0;
    let spectrum = spectrum::spectrum(file, &m.spectrum, &channels, table.row_count(), nyquist)?;
    let cutoff_hz = filter::cutoff_hz(file, &m.filter, nyquist)?;
    let updating = updating::updating(file, m.updating, bridge.as_ref(), &channels)?;
    let vehicle_frequencies_hz = vehicle::vehicle_frequencies(file, m.vehicle.as_ref())?;
    let measurement = Measurement {
        description: m.description,
        sampling_rate_hz,
        resampled_from_hz,
        time,
        channels,
        speed: crossing.speed,
        pass_frequency_hz: crossing.pass_frequency_hz,
        span_length: crossing.span_length,
        first_frequency_hz: crossing.first_frequency_hz,
        filter_order,
        cutoff_hz,
        spectrum,
        vehicle,
        weighing,
        vehicle_track,
        updating,
        bridge,
        entry_time: record.entry_time,
        bridge_length: record.bridge_length,
        baseline: record.baseline,
        baseline_window: record.baseline_window,
        detect_entry: record.detect_entry,
        detect_entry_by_default: record.detect_entry_by_default,
        vehicle_frequencies_hz,
        crawl,
    };
    Ok(MeasurementFile {
        measurement,
        csv_path,
    })
}

/// A crawl run is this record's static reference only if it was driven slower: one at this
/// record's speed or faster (a speed typed in the wrong unit, or the wrong file) is refused at
/// `measurement.crawl`, instead of giving a DAF of the record against a dynamic response.
fn refuse_a_crawl_not_slower(
    file: &SourceFile,
    crawl_speed: Option<f64>,
    speed: Option<f64>,
) -> Result<(), InputError> {
    match (crawl_speed, speed) {
        (Some(crawl), Some(speed)) if crawl >= speed => Err(file.error_at(
            "measurement.crawl",
            format!(
                "the crawl run's speed, {:.1} km/h, is not below this record's {:.1} km/h; a \
                 crawl run is the static reference, driven at crawling speed",
                vbi::units::metres_per_second_to_kmh(crawl),
                vbi::units::metres_per_second_to_kmh(speed)
            ),
        )),
        _ => Ok(()),
    }
}

/// The vehicle enters the bridge before the record ends: an entry time after its last sample
/// (1e308 s, or a time in ms) places the whole crossing outside the record, which was processed
/// without a word (issue 47). Refused at the key that gave it.
fn refuse_an_entry_after_the_record(
    file: &SourceFile,
    m: &raw::RawMeasurement,
    entry_time: Option<f64>,
    time: &[f64],
) -> Result<(), InputError> {
    let (Some(entry), Some(&end)) = (entry_time, time.last()) else {
        return Ok(());
    };
    if entry <= end {
        return Ok(());
    }
    let key = if m.entry_time_s.is_some() {
        "measurement.entry_time_s"
    } else {
        "measurement.vehicle.entry_time_s"
    };
    Err(file.error_at(
        key,
        format!(
            "{} s is after the record ends at {} s; expected the time the vehicle's front axle \
             enters the bridge, within the record",
            vbi::units::shown(entry),
            vbi::units::shown(end)
        ),
    ))
}

/// A crawl run is the static reference of every channel with a DAF (all but accelerations):
/// each needs a channel of the same name in the crawl run. Refused here, as the processing
/// would refuse it, so that `vbi check` decides it (issue 47).
fn refuse_a_crawl_without_channels(
    file: &SourceFile,
    m: &raw::RawMeasurement,
    crawl: &Measurement,
) -> Result<(), InputError> {
    for channel in &m.channels {
        let has_daf = channel.kind != vbi::signal::MeasuredQuantity::Acceleration;
        if has_daf && !crawl.channels.iter().any(|k| k.name == channel.name) {
            return Err(file.error_at(
                "measurement.crawl",
                format!(
                    "a crawl-run static reference needs a channel `{}` in the crawl run",
                    channel.name
                ),
            ));
        }
    }
    Ok(())
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
    // Refused before the crawl run is loaded: a file that names itself as its crawl run, or two
    // that name each other, would otherwise be loaded without end (until the stack overflows).
    let document: Document = source.parse()?;
    if document.measurement.crawl.is_some() {
        return Err(source.error_at(
            "measurement.crawl",
            "a crawl run cannot name a crawl run of its own",
        ));
    }
    Ok(load(&source)?.measurement)
}
