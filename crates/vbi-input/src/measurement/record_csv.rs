//! The record's CSV (`csv`, `csv_format`, read by [`crate::logger_csv`]) and its time axis
//! (`time_column`, `sampling_rate_hz`, `resample_hz`).

use std::path::{Path, PathBuf};

use vbi::measure::measurement::Channel;
use vbi::signal::SignalError;

use crate::logger_csv::{self, CsvFormat, LoggerTable, ReadProblem, TimeFormat};
use crate::measurement::raw::RawMeasurement;
use crate::source::{require_in_range, require_positive, InputError, SourceFile};

/// Relative tolerance on the sampling interval: every Δt must lie within 1 % of the median Δt
/// (a larger step is a gap, a smaller one a duplicated or jittered sample), and a given
/// `sampling_rate_hz` must match 1/median Δt within 0.1 %.
const INTERVAL_TOLERANCE: f64 = 0.01;
const RATE_TOLERANCE: f64 = 0.001;
/// Highest rate a record is resampled to [Hz]: an upper bound on the samples it makes.
const MAX_RESAMPLE_HZ: f64 = 100_000.0;

/// The record's CSV named by `csv` (relative to `folder`), read after checking that channels are
/// listed, with at least 16 data rows; its path and its table.
pub(crate) fn record_table(
    file: &SourceFile,
    m: &RawMeasurement,
    folder: &Path,
) -> Result<(PathBuf, LoggerTable), InputError> {
    let at = |key: &str| format!("measurement.{key}");
    if m.channels.is_empty() {
        return Err(file.error_at(&at("channels"), "at least one channel is required"));
    }
    let csv_path = folder.join(&m.csv);
    let table = read_table(file, m, &csv_path)?;
    let csv_name = table.file.clone();
    if table.row_count() < 16 {
        return Err(file.error_at(
            &at("csv"),
            format!(
                "{csv_name} has {} data rows; at least 16 samples are needed",
                table.row_count()
            ),
        ));
    }
    Ok((csv_path, table))
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
    // Only the columns the measurement reads are kept: its time column and its channels'.
    let columns: Vec<String> = m
        .time_column
        .iter()
        .cloned()
        .chain(
            m.channels
                .iter()
                .map(|c| c.column.clone().unwrap_or_else(|| c.name.clone())),
        )
        .collect();
    logger_csv::read(csv_path, &format, Some(&columns)).map_err(|e| match e {
        ReadProblem::Unreadable(err) => err.at_naming_key(file, "measurement.csv"),
        ReadProblem::Key(k, message) => file.error_at(&format!("{key}.{k}"), message),
        ReadProblem::Csv(err) => err,
    })
}

/// The record's time axis as read: the sampling rate and the times (uniform, or the logger's
/// own when resampling).
type ReadTimes = (f64, Vec<f64>);

/// The time axis: the sampling rate and uniform times t₀ + i/f_s (the time column must be
/// uniform within 1 %), or with `resample_hz` the logger's own times (jitter allowed, gaps
/// and non-increasing times refused) and the record resampled to `resample_hz`.
pub(crate) struct TimeAxisRead {
    /// f_s [Hz], `resample_hz` when resampling.
    pub(crate) sampling_rate_hz: f64,
    /// Uniform times [s] (the logger's own when resampling, replaced after it).
    pub(crate) time: Vec<f64>,
    /// The logger's times [s] when resampling.
    pub(crate) logger_times: Option<Vec<f64>>,
}

/// The time axis of the record `table` (see [`TimeAxisRead`]).
pub(crate) fn time_axis(
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
pub(crate) fn resample_record(
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

/// The sampling rate and the times of `table`: uniform ones from `sampling_rate_hz`, or the
/// time column checked (increasing; uniform within 1 % unless resampling), with a given rate
/// checked against it.
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
            Ok((fs, (0..table.row_count()).map(|i| i as f64 / fs).collect()))
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
