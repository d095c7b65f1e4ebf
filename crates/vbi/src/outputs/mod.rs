//! The one table of output quantities (in the manner of hyperfine's `Metric`): each quantity a
//! row with its name, unit, label, meaning and how it is read from a typed result. Every
//! exporter iterates the table instead of spelling the quantities again: the station entries of
//! `vbi run`'s summary.json ([`StationEntry`] serialises the rows in order), the Python
//! package's `StationDaf` attributes (one lookup of a row by name) and the table of outputs in
//! the documentation. A new output quantity of a station is one row in [`STATION_OUTPUTS`].

mod run_summary;
mod station;

pub use run_summary::{
    ColumnExtremes, Provenance, RunSummary, StationAcceleration, StationValues, SummaryValue,
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
}

impl Unit {
    /// The unit's symbol for an entry of `quantity` ("-" for a ratio, "" where there is none).
    pub fn symbol(self, quantity: Quantity) -> &'static str {
        match self {
            Unit::Text | Unit::Count | Unit::Flag => "",
            Unit::Dimensionless => "-",
            Unit::Second => "s",
            Unit::OfQuantity => quantity.unit(),
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
