//! Traffic files: the four fixed-width formats of BTLS and PyBTLS (CASTOR, BeDIT, DITIS, MON;
//! their column tables in docs/lifetime.md, from PyBTLS 1.0.1's `cpp/src/Vehicle.cpp`
//! `createCASTORVehicle` … `createMONVehicle`) and vbi's CSV, read line by line into
//! [`RecordedTruck`]s in SI units, so that a file of any length streams in flat memory.
//!
//! Conventions taken over from BTLS: times count 25-day months and 10-month years,
//! t = 86 400 (250 Y + 25 (M − 1) + D − 1) + 3 600 h + 60 m + s, with MON's year counted from
//! 2010; direction 1 enters at x = 0 and direction 2 at x = L; the lane is numbered from 1
//! within its direction; axle weights of 100 kg are 981 N (g = 9.81 m/s², as PyBTLS's
//! 0.981 kN). The GVW and length fields are not read: the gross weight is the axles' sum, and a
//! truck leaves the deck with its last axle.

use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::Path;

use vbi::lifetime::SECONDS_PER_DAY;
use vbi::traffic::{RecordedTruck, TravelDirection};
use vbi::units::{DM, HUNDRED_KG_WEIGHT, KG_WEIGHT, KMH, KN, MILLISECOND, MM};

use crate::source::InputError;

/// The formats of a traffic file (the `traffic_format` key's words).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TrafficFormat {
    /// BTLS format 1: up to 9 axles, 77 characters.
    Castor,
    /// BTLS format 2: up to 20 axles.
    Bedit,
    /// BTLS format 3: up to 20 axles with track widths.
    Ditis,
    /// BTLS format 4 (Australian WIM): any number of axles, SI-like units.
    Mon,
    /// vbi's CSV (header `time_s,direction,lane,speed_m_per_s,axle_spacings_m,axle_loads_kn`).
    Csv,
}

impl TrafficFormat {
    /// Every format's name, in order.
    pub const NAMES: [&'static str; 5] = ["castor", "bedit", "ditis", "mon", "csv"];

    /// The format's name (one of [`TrafficFormat::NAMES`]).
    pub fn name(self) -> &'static str {
        TrafficFormat::NAMES
            .into_iter()
            .find(|name| TrafficFormat::from_name(name) == Some(self))
            .unwrap_or("castor")
    }

    /// The format of a name.
    pub fn from_name(name: &str) -> Option<TrafficFormat> {
        match name {
            "castor" => Some(TrafficFormat::Castor),
            "bedit" => Some(TrafficFormat::Bedit),
            "ditis" => Some(TrafficFormat::Ditis),
            "mon" => Some(TrafficFormat::Mon),
            "csv" => Some(TrafficFormat::Csv),
            _ => None,
        }
    }
}

/// Days in a month of a traffic file's dates (BTLS's `DAYS_PER_MT`, `ConfigData.h`).
const DAYS_PER_MONTH: u64 = 25;
/// Months in a year of a traffic file's dates (BTLS's `MTS_PER_YR`).
const MONTHS_PER_YEAR: u64 = 10;
/// The year a MON file's year counts from (BTLS's `MON_BASE_YEAR`).
const MON_BASE_YEAR: u64 = 2010;

/// vbi's CSV header.
pub const CSV_HEADER: &str = "time_s,direction,lane,speed_m_per_s,axle_spacings_m,axle_loads_kn";

/// Column layout of a fixed-width format: (start, width) of each field, 0-based.
struct Layout {
    day: (usize, usize),
    month: (usize, usize),
    year: (usize, usize),
    hour: (usize, usize),
    minute: (usize, usize),
    /// Seconds and hundredths (CASTOR, BeDIT, DITIS), or milliseconds in the minute (MON).
    second: (usize, usize),
    hundredths: Option<(usize, usize)>,
    speed: (usize, usize),
    axles: (usize, usize),
    direction: (usize, usize),
    /// Whether the direction field counts from 0 (BeDIT, MON) rather than 1.
    direction_from_zero: bool,
    lane: (usize, usize),
    /// Column of the first axle weight, the stride between axles, the weight's width, and the
    /// spacing's offset from the weight and width.
    first_axle: usize,
    axle_stride: usize,
    weight_width: usize,
    spacing_offset: usize,
    spacing_width: usize,
    /// The most axles the format holds.
    max_axles: usize,
}

impl Layout {
    fn of(format: TrafficFormat) -> Layout {
        let castor = Layout {
            day: (4, 2),
            month: (6, 2),
            year: (8, 2),
            hour: (10, 2),
            minute: (12, 2),
            second: (14, 2),
            hundredths: Some((16, 2)),
            speed: (18, 3),
            axles: (28, 1),
            direction: (29, 1),
            direction_from_zero: false,
            lane: (30, 1),
            first_axle: 34,
            axle_stride: 5,
            weight_width: 3,
            spacing_offset: 3,
            spacing_width: 2,
            max_axles: 9,
        };
        match format {
            TrafficFormat::Castor | TrafficFormat::Csv => castor,
            TrafficFormat::Bedit => Layout {
                axles: (28, 2),
                direction: (30, 1),
                direction_from_zero: true,
                lane: (31, 1),
                first_axle: 35,
                axle_stride: 6,
                spacing_width: 3,
                max_axles: 20,
                ..castor
            },
            TrafficFormat::Ditis => Layout {
                year: (8, 4),
                hour: (12, 2),
                minute: (14, 2),
                second: (16, 2),
                hundredths: Some((18, 2)),
                speed: (20, 3),
                axles: (30, 2),
                direction: (32, 1),
                lane: (33, 1),
                first_axle: 37,
                axle_stride: 9,
                spacing_offset: 6,
                spacing_width: 3,
                max_axles: 20,
                ..castor
            },
            TrafficFormat::Mon => Layout {
                day: (9, 2),
                month: (11, 2),
                year: (13, 4),
                hour: (17, 2),
                minute: (19, 2),
                second: (21, 5),
                hundredths: None,
                speed: (36, 3),
                axles: (26, 2),
                lane: (44, 1),
                direction: (45, 1),
                direction_from_zero: true,
                first_axle: 50,
                axle_stride: 10,
                weight_width: 5,
                spacing_offset: 5,
                spacing_width: 5,
                max_axles: 99,
            },
        }
    }
}

/// Reads a traffic file line by line: an iterator of trucks, each or the error of its line
/// (which names the file, the line, the column and the field). Blank lines are skipped.
pub struct TrafficFileReader {
    path: String,
    format: TrafficFormat,
    lines: std::io::Lines<BufReader<File>>,
    line_number: usize,
    /// The file's size [bytes].
    size: u64,
    /// Bytes of the lines read so far, newlines included.
    bytes_read: u64,
}

impl TrafficFileReader {
    /// Opens `path` to be read as `format`.
    pub fn open(path: &Path, format: TrafficFormat) -> Result<TrafficFileReader, InputError> {
        let name = path.display().to_string();
        let file = File::open(path).map_err(|e| InputError {
            file: name.clone(),
            location: None,
            field: None,
            message: format!("cannot read the traffic file: {e}"),
        })?;
        let size = file.metadata().map(|m| m.len()).unwrap_or(0);
        if !file.metadata().map(|m| m.is_file()).unwrap_or(false) {
            return Err(InputError {
                file: name,
                location: None,
                field: None,
                message: "the traffic file is not a regular file".into(),
            });
        }
        let mut reader = TrafficFileReader {
            path: name,
            format,
            lines: BufReader::new(file).lines(),
            line_number: 0,
            size,
            bytes_read: 0,
        };
        if format == TrafficFormat::Csv {
            reader.read_csv_header()?;
        }
        Ok(reader)
    }

    /// The file's path as given.
    pub fn path(&self) -> &str {
        &self.path
    }

    /// The line last read, from 1.
    pub fn line_number(&self) -> usize {
        self.line_number
    }

    /// The file's size when opened [bytes].
    pub fn size(&self) -> u64 {
        self.size
    }

    /// Bytes of the lines read so far, newlines included [bytes]: with [`Self::size`], how far
    /// a run has got.
    pub fn bytes_read(&self) -> u64 {
        self.bytes_read
    }

    fn error(&self, column: usize, field: &str, message: impl Into<String>) -> InputError {
        InputError {
            file: self.path.clone(),
            location: Some((self.line_number, column + 1)),
            field: Some(field.into()),
            message: message.into(),
        }
    }

    fn read_csv_header(&mut self) -> Result<(), InputError> {
        self.line_number += 1;
        let header = match self.lines.next() {
            Some(Ok(line)) => line,
            _ => String::new(),
        };
        if header.trim().trim_start_matches('\u{feff}') != CSV_HEADER {
            return Err(self.error(0, "header", format!("expected the header `{CSV_HEADER}`")));
        }
        Ok(())
    }

    /// An unsigned integer field at (start, width): blank reads as 0, as BTLS's `atoi` does.
    fn integer(
        &self,
        line: &str,
        (start, width): (usize, usize),
        field: &str,
    ) -> Result<u64, InputError> {
        let Some(text) = line.get(start..start + width) else {
            return Err(self.error(
                start,
                field,
                format!(
                    "the line ends at column {}, inside or before this field (columns {}–{})",
                    line.len(),
                    start + 1,
                    start + width
                ),
            ));
        };
        let text = text.trim();
        if text.is_empty() {
            return Ok(0);
        }
        text.parse::<u64>().map_err(|_| {
            self.error(
                start,
                field,
                format!(
                    "`{text}` is not a whole number (columns {}–{})",
                    start + 1,
                    start + width
                ),
            )
        })
    }

    fn fixed_width(&self, line: &str) -> Result<RecordedTruck, InputError> {
        let layout = Layout::of(self.format);
        let int = |at, field: &str| self.integer(line, at, field);
        let (day, month, year) = (
            int(layout.day, "day")?,
            int(layout.month, "month")?,
            int(layout.year, "year")?,
        );
        if day == 0 || month == 0 {
            return Err(self.error(layout.day.0, "day", "the day and the month count from 1"));
        }
        let year = if self.format == TrafficFormat::Mon {
            year.checked_sub(MON_BASE_YEAR).ok_or_else(|| {
                self.error(
                    layout.year.0,
                    "year",
                    format!("a MON year is from {MON_BASE_YEAR}"),
                )
            })?
        } else {
            year
        };
        let days =
            MONTHS_PER_YEAR * DAYS_PER_MONTH * year + DAYS_PER_MONTH * (month - 1) + (day - 1);
        let seconds = match layout.hundredths {
            Some(hundredths) => {
                int(layout.second, "second")? as f64 + int(hundredths, "hundredths")? as f64 / 100.0
            }
            None => int(layout.second, "millisecond")? as f64 * MILLISECOND,
        };
        let arrival_time = SECONDS_PER_DAY * days as f64
            + 3_600.0 * int(layout.hour, "hour")? as f64
            + 60.0 * int(layout.minute, "minute")? as f64
            + seconds;
        let speed = match self.format {
            TrafficFormat::Mon => int(layout.speed, "speed")? as f64 * KMH,
            _ => int(layout.speed, "speed")? as f64 * DM,
        };
        let direction = match (
            int(layout.direction, "direction")?,
            layout.direction_from_zero,
        ) {
            (0, true) | (1, false) => TravelDirection::Forward,
            (1, true) | (2, false) => TravelDirection::Backward,
            (other, from_zero) => {
                return Err(self.error(
                    layout.direction.0,
                    "direction",
                    format!(
                        "{other} is not a direction; expected {}",
                        if from_zero { "0 or 1" } else { "1 or 2" }
                    ),
                ))
            }
        };
        let axles = int(layout.axles, "axles")? as usize;
        if axles == 0 || axles > layout.max_axles {
            return Err(self.error(
                layout.axles.0,
                "axles",
                format!("{axles} axles; expected 1 to {}", layout.max_axles),
            ));
        }
        let (weight_unit, length_unit) = match self.format {
            TrafficFormat::Mon => (KG_WEIGHT, MM),
            _ => (HUNDRED_KG_WEIGHT, DM),
        };
        let mut axle_loads = Vec::with_capacity(axles);
        let mut axle_spacings = Vec::with_capacity(axles - 1);
        for i in 0..axles {
            let at = layout.first_axle + i * layout.axle_stride;
            let weight_field = format!("axle {} weight", i + 1);
            axle_loads.push(int((at, layout.weight_width), &weight_field)? as f64 * weight_unit);
            if i + 1 < axles {
                let spacing = (at + layout.spacing_offset, layout.spacing_width);
                let spacing_field = format!("axle {} spacing", i + 1);
                let value = int(spacing, &spacing_field)? as f64 * length_unit;
                if value <= 0.0 {
                    return Err(self.error(
                        spacing.0,
                        &format!("axle {} spacing", i + 1),
                        "an axle spacing must be positive",
                    ));
                }
                axle_spacings.push(value);
            }
        }
        let truck = RecordedTruck {
            arrival_time,
            lane: int(layout.lane, "lane")? as usize,
            direction,
            speed,
            axle_spacings,
            axle_loads,
        };
        truck
            .check()
            .map_err(|reason| self.error(0, "truck", reason))?;
        Ok(truck)
    }

    fn csv(&self, line: &str) -> Result<RecordedTruck, InputError> {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != 6 {
            return Err(self.error(
                0,
                "row",
                format!("{} cells; expected 6 ({CSV_HEADER})", cells.len()),
            ));
        }
        let number = |i: usize, name: &str| -> Result<f64, InputError> {
            cells[i]
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| self.error(0, name, format!("`{}` is not a number", cells[i])))
        };
        let list = |i: usize, name: &str| -> Result<Vec<f64>, InputError> {
            if cells[i].is_empty() {
                return Ok(Vec::new());
            }
            cells[i]
                .split(';')
                .map(|v| v.trim().parse::<f64>().ok().filter(|v| v.is_finite()))
                .collect::<Option<Vec<f64>>>()
                .ok_or_else(|| {
                    self.error(
                        0,
                        name,
                        format!("`{}` is not a list of numbers separated by `;`", cells[i]),
                    )
                })
        };
        let direction = match cells[1] {
            "1" => TravelDirection::Forward,
            "2" => TravelDirection::Backward,
            other => {
                return Err(self.error(
                    0,
                    "direction",
                    format!("`{other}` is not a direction; expected 1 or 2"),
                ))
            }
        };
        let lane = cells[2]
            .parse::<usize>()
            .ok()
            .filter(|&l| l >= 1)
            .ok_or_else(|| {
                self.error(
                    0,
                    "lane",
                    format!(
                        "`{}` is not a lane; expected a whole number from 1",
                        cells[2]
                    ),
                )
            })?;
        let truck = RecordedTruck {
            arrival_time: number(0, "time_s")?,
            lane,
            direction,
            speed: number(3, "speed_m_per_s")?,
            axle_spacings: list(4, "axle_spacings_m")?,
            axle_loads: list(5, "axle_loads_kn")?
                .into_iter()
                .map(|w| w * KN)
                .collect(),
        };
        truck
            .check()
            .map_err(|reason| self.error(0, "row", reason))?;
        Ok(truck)
    }
}

impl Iterator for TrafficFileReader {
    type Item = Result<RecordedTruck, InputError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            self.line_number += 1;
            let line = match self.lines.next()? {
                Ok(line) => {
                    self.bytes_read += line.len() as u64 + 1;
                    line
                }
                Err(e) => {
                    return Some(Err(self.error(
                        0,
                        "line",
                        format!("cannot read the line: {e}"),
                    )))
                }
            };
            let line = line.trim_end_matches('\r');
            if line.trim().is_empty() {
                continue;
            }
            return Some(match self.format {
                TrafficFormat::Csv => self.csv(line),
                _ => self.fixed_width(line),
            });
        }
    }
}

#[cfg(test)]
mod tests;
