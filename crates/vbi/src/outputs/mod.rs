//! The one table of output quantities (in the manner of hyperfine's `Metric`): each quantity a
//! row with its name, unit, label, meaning and how it is read from a typed result. Every
//! exporter iterates the table instead of spelling the quantities again: the station entries of
//! `vbi run`'s summary.json ([`StationEntry`] serialises the rows in order), the Python
//! package's `StationDaf` attributes (one lookup of a row by name) and the table of outputs in
//! the documentation. A new output quantity of a station is one row in [`STATION_OUTPUTS`].

mod fatigue;
mod lifetime_fatigue;
mod run_summary;
mod station;

pub use fatigue::{
    fatigue_output, fatigue_outputs_markdown, FatigueEntry, FatigueOutput, FATIGUE_OUTPUTS,
};
pub use lifetime_fatigue::{LifetimeFatigueOutput, LIFETIME_FATIGUE_OUTPUTS};
pub use run_summary::{
    ColumnExtremes, FatigueValues, Provenance, RunSummary, StationAcceleration, StationValues,
    SummaryValue,
};
pub use station::{
    station_output, station_outputs_markdown, study_station_outputs, StationEntry, StationOutput,
    STATION_OUTPUTS,
};

use serde::ser::{Serialize, Serializer};

use crate::modal::Quantity;

/// The unit of an output quantity, as the output states it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// A name or a word: no unit.
    Text,
    /// A ratio [-].
    Dimensionless,
    /// A time [s].
    Second,
    /// The unit of the entry's quantity: m (deflection), N·m (bending moment), N (shear force,
    /// support reaction).
    OfQuantity,
    /// A mode number (1-based) or a count: no unit.
    Count,
    /// A yes or no: no unit.
    Flag,
    /// A stress [Pa].
    Pascal,
}

impl Unit {
    /// The unit's symbol for an entry of `quantity` ("-" for a ratio, "" where there is none).
    pub fn symbol(self, quantity: Quantity) -> &'static str {
        match self {
            Unit::Text | Unit::Count | Unit::Flag => "",
            Unit::Dimensionless => "-",
            Unit::Second => "s",
            Unit::OfQuantity => quantity.unit(),
            Unit::Pascal => "Pa",
        }
    }

    /// The unit in the documentation's tables of outputs.
    pub fn description(self) -> &'static str {
        match self {
            Unit::OfQuantity => "m, N·m or N",
            Unit::Dimensionless => "–",
            Unit::Second => "s",
            Unit::Text => "text",
            Unit::Count => "count",
            Unit::Flag => "yes or no",
            Unit::Pascal => "Pa",
        }
    }
}

/// One output value, borrowed from the result it is read from, in SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OutputValue<'a> {
    /// A name or a word.
    Text(&'a str),
    /// A number that always exists.
    Number(f64),
    /// A number that may be undefined (a DAF over a vanishing static response).
    OptionalNumber(Option<f64>),
    /// A mode number or a count, which may be undefined.
    Count(Option<usize>),
    /// A yes or no that always exists.
    Flag(bool),
    /// A yes or no that may be undefined.
    OptionalFlag(Option<bool>),
    /// A series, one value per mode count K = 1…N or per mode k.
    Series(&'a [f64]),
}

impl OutputValue<'_> {
    /// The value as a CSV cell: a number as Rust writes it (shortest round trip), empty where
    /// undefined, `true`/`false`, a series joined by `;`.
    pub fn cell(&self) -> String {
        let number = |value: f64| format!("{value}");
        match *self {
            OutputValue::Text(text) => text.to_string(),
            OutputValue::Number(value) => number(value),
            OutputValue::OptionalNumber(value) => value.map(number).unwrap_or_default(),
            OutputValue::Count(value) => value.map(|c| c.to_string()).unwrap_or_default(),
            OutputValue::Flag(value) => value.to_string(),
            OutputValue::OptionalFlag(value) => value.map(|f| f.to_string()).unwrap_or_default(),
            OutputValue::Series(values) => values
                .iter()
                .map(|&v| number(v))
                .collect::<Vec<_>>()
                .join(";"),
        }
    }
}

impl Serialize for OutputValue<'_> {
    /// As the field of its type would be: a string, a number, `null` for an undefined value, a
    /// boolean, an array.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match *self {
            OutputValue::Text(text) => text.serialize(serializer),
            OutputValue::Number(value) => value.serialize(serializer),
            OutputValue::OptionalNumber(value) => value.serialize(serializer),
            OutputValue::Count(value) => value.serialize(serializer),
            OutputValue::Flag(value) => value.serialize(serializer),
            OutputValue::OptionalFlag(value) => value.serialize(serializer),
            OutputValue::Series(values) => values.serialize(serializer),
        }
    }
}
