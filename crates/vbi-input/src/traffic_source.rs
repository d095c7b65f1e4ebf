//! Where a lifetime's trucks come from: a traffic file read line by line
//! ([`TrafficFileReader`]), or vbi's own generator in the BTLS way
//! ([`vbi::traffic::generator::TrafficGenerator`], `[lifetime.generator]`), both streamed, with
//! their progress for long runs.

use std::path::PathBuf;

use vbi::traffic::generator::{GraveParameters, HedsTable};
use vbi::traffic::generator::{HeadwayModel, LaneFlow, TrafficGenerator};
use vbi::traffic::RecordedTruck;

use crate::source::InputError;
use crate::traffic_file::{TrafficFileReader, TrafficFormat};

/// The traffic a lifetime file names.
#[derive(Debug, Clone)]
pub enum TrafficInput {
    /// A traffic file in one of the formats of [`TrafficFormat`].
    File {
        /// Its path.
        path: PathBuf,
        /// Its format.
        format: TrafficFormat,
    },
    /// Simulated traffic (`[lifetime.generator]`).
    Generator(Box<GeneratorInput>),
}

/// What `[lifetime.generator]` asks for.
#[derive(Debug, Clone)]
pub struct GeneratorInput {
    /// The Grave parameter folder (PyBTLS's `py/pybtls/data/GraveParameters/<site>`).
    pub parameters_folder: PathBuf,
    /// The lane flow file.
    pub lane_flow_file: PathBuf,
    /// The vehicle model read from the folder.
    pub parameters: GraveParameters,
    /// The folder's HeDS table, if it has one.
    pub heds: Option<HedsTable>,
    /// The lanes' flows read from the lane flow file.
    pub lanes: Vec<LaneFlow>,
    /// The headway model.
    pub headway: HeadwayModel,
    /// Days of traffic.
    pub days: u64,
    /// The seed of the lanes' random streams.
    pub seed: u64,
    /// The no-overlap length of the minimum gap [m] (the bridge's deck length by default).
    pub no_overlap_length: f64,
}

impl TrafficInput {
    /// The traffic file's path, or `generated from <folder>`, for reports.
    pub fn label(&self) -> String {
        match self {
            TrafficInput::File { path, .. } => path.display().to_string(),
            TrafficInput::Generator(generator) => format!(
                "generated: {} days from {} and {}",
                generator.days,
                generator.parameters_folder.display(),
                generator.lane_flow_file.display()
            ),
        }
    }

    /// The format's name, or `generator`.
    pub fn format_name(&self) -> &'static str {
        match self {
            TrafficInput::File { format, .. } => format.name(),
            TrafficInput::Generator(_) => "generator",
        }
    }
}

/// A stream of trucks from a file or the generator.
pub enum TrafficSource {
    /// A traffic file, line by line.
    File(TrafficFileReader),
    /// The generator, with the trucks it has given.
    Generated {
        /// The generator.
        generator: Box<TrafficGenerator>,
        /// Trucks given so far.
        count: usize,
    },
}

impl TrafficSource {
    /// The file's path, or `generator`, for located errors.
    pub fn path(&self) -> String {
        match self {
            TrafficSource::File(reader) => reader.path().to_string(),
            TrafficSource::Generated { .. } => "generator".into(),
        }
    }

    /// The next truck, or the error of a bad line; None at the end.
    pub fn next_truck(&mut self) -> Option<Result<RecordedTruck, InputError>> {
        match self {
            TrafficSource::File(reader) => reader.next(),
            TrafficSource::Generated { generator, count } => {
                let truck = generator.next()?;
                *count += 1;
                Some(Ok(truck))
            }
        }
    }

    /// The line of the truck last read (the file's line, or the generated truck's number).
    pub fn line_number(&self) -> usize {
        match self {
            TrafficSource::File(reader) => reader.line_number(),
            TrafficSource::Generated { count, .. } => *count,
        }
    }

    /// The progress so far and its total, in [`TrafficSource::progress_unit`]s: kB of the file
    /// read, or hours of traffic generated.
    pub fn progress(&self) -> (u64, u64) {
        match self {
            TrafficSource::File(reader) => {
                let size = reader.size();
                (
                    reader.bytes_read().min(size).div_ceil(1000),
                    size.div_ceil(1000),
                )
            }
            TrafficSource::Generated { generator, .. } => {
                let hours = |seconds: f64| (seconds / 3600.0).floor() as u64;
                (hours(generator.last_arrival()), hours(generator.end_time()))
            }
        }
    }

    /// The unit of [`TrafficSource::progress`].
    pub fn progress_unit(&self) -> &'static str {
        match self {
            TrafficSource::File(_) => "kB of traffic",
            TrafficSource::Generated { .. } => "hours of traffic",
        }
    }
}
