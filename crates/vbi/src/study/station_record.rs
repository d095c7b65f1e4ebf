//! One recorded station and quantity of a study's case: a row of `station_records.csv` and a
//! station record of the journal. Its values are the rows of the table of station outputs that
//! a study records ([`study_station_outputs`]: each row's `study_column`), so a new recorded
//! output is one row of that table, not a field spelled here.

use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::ser::{SerializeMap, Serializer};
use serde::{Deserialize, Serialize};

use super::cells::{count_cell, exact, float_cell, number};
use crate::analysis::StationDaf;
use crate::crossing::{PreparedBridge, RunResult};
use crate::modal::Quantity;
use crate::outputs::{study_station_outputs, OutputValue, StationOutput, Unit};

/// A station and the quantities that a study records there (an entry of its `record`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecordRequest {
    /// The station's name, as the bridge names it (`span1_mid_g2`, a `[[station]]` name).
    pub station: String,
    /// The quantities, in the order asked.
    pub quantities: Vec<Quantity>,
}

/// One recorded value: a number (written as its exact text) or a count (a mode number), either
/// undefined where the analysis does not hold the entry or the value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RecordedValue {
    /// A number in the quantity's unit, or a ratio.
    Number(Option<f64>),
    /// A mode number or a count.
    Count(Option<usize>),
}

impl RecordedValue {
    /// The value of `row` in `entry`, or the row's empty value without an entry.
    fn of(row: &StationOutput, entry: Option<&StationDaf>) -> RecordedValue {
        match entry.map(|e| (row.value)(e)) {
            Some(OutputValue::Number(v)) => RecordedValue::Number(Some(v)),
            Some(OutputValue::OptionalNumber(v)) => RecordedValue::Number(v),
            Some(OutputValue::Count(v)) => RecordedValue::Count(v),
            Some(other) => unreachable!("a study records numbers and counts, not {other:?}"),
            None if row.unit == Unit::Count => RecordedValue::Count(None),
            None => RecordedValue::Number(None),
        }
    }

    /// Its table cell: the shortest exact text, or empty.
    fn cell(self) -> String {
        match self {
            RecordedValue::Number(v) => float_cell(v),
            RecordedValue::Count(v) => count_cell(v),
        }
    }
}

/// One recorded station and quantity of a case: a row of `station_records.csv` after the case
/// id ([`station_record_columns`]; the `unit` cell is the quantity's).
#[derive(Debug, Clone, PartialEq)]
pub struct StationRecord {
    /// The station's name.
    pub station: String,
    /// The quantity (its name in the journal and the table).
    pub quantity: Quantity,
    /// The recorded outputs, one per row of [`study_station_outputs`], in order.
    pub values: Vec<RecordedValue>,
}

/// Columns of `station_records.csv` after the case id ([`StationRecord::cells`]): station,
/// quantity, unit, then the recorded outputs' columns.
pub fn station_record_columns() -> Vec<&'static str> {
    ["station", "quantity", "unit"]
        .into_iter()
        .chain(study_station_outputs().filter_map(|row| row.study_column))
        .collect()
}

impl StationRecord {
    /// The records of a finished crossing at the stations and quantities asked, each quantity
    /// that the station has (a station reads the shear force, or at a support the support
    /// reaction: `Station::force_quantity`); the values of a station or quantity that the
    /// analysis does not hold are empty.
    pub fn of_run(
        record: &[RecordRequest],
        bridge: &PreparedBridge,
        result: &RunResult,
    ) -> Vec<StationRecord> {
        let basis = &bridge.basis;
        let stations = &basis.stations;
        record
            .iter()
            .flat_map(|request| {
                let station = stations.iter().position(|s| s.name == request.station);
                let has = move |quantity: Quantity| {
                    station.is_none_or(|s| basis.has_quantity(s, quantity))
                };
                request
                    .quantities
                    .iter()
                    .filter(move |&&q| has(q))
                    .map(move |&quantity| {
                        let entry = station.and_then(|s| result.report.entry(s, quantity));
                        StationRecord {
                            station: request.station.clone(),
                            quantity,
                            values: study_station_outputs()
                                .map(|row| RecordedValue::of(row, entry))
                                .collect(),
                        }
                    })
            })
            .collect()
    }

    /// The recorded number of the column `column` (`daf`, `static_max` …), if it is defined.
    pub fn number(&self, column: &str) -> Option<f64> {
        let at = study_station_outputs().position(|row| row.study_column == Some(column))?;
        match self.values.get(at)? {
            RecordedValue::Number(v) => *v,
            RecordedValue::Count(v) => v.map(|v| v as f64),
        }
    }

    /// The cells of a row of `station_records.csv` after the case id
    /// ([`station_record_columns`]).
    pub fn cells(&self) -> Vec<String> {
        [
            self.station.clone(),
            self.quantity.name().to_string(),
            self.quantity.unit().to_string(),
        ]
        .into_iter()
        .chain(self.values.iter().map(|v| v.cell()))
        .collect()
    }
}

impl Serialize for StationRecord {
    /// The journal's form: `station`, `quantity`, then each recorded output under its column,
    /// a number as the string of its exact text, a count as a number, `null` where undefined.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(2 + self.values.len()))?;
        map.serialize_entry("station", &self.station)?;
        map.serialize_entry("quantity", &self.quantity)?;
        for (row, value) in study_station_outputs().zip(&self.values) {
            let column = row.study_column.expect("a recorded row has its column");
            match *value {
                RecordedValue::Number(v) => map.serialize_entry(column, &v.map(number))?,
                RecordedValue::Count(v) => map.serialize_entry(column, &v)?,
            }
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for StationRecord {
    /// The journal's form back, refusing a key that is not a recorded column and a missing one
    /// (except a column added since journals were first written, [`COLUMNS_ADDED_LATER`], which
    /// an older journal's line lacks: it reads as undefined).
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<StationRecord, D::Error> {
        deserializer.deserialize_map(StationRecordVisitor)
    }
}

/// Recorded columns added after the journal's first form: a line without them reads them as
/// undefined (issue 46: the time-step indicator).
const COLUMNS_ADDED_LATER: &[&str] = &["daf_change_dt"];

struct StationRecordVisitor;

impl<'de> Visitor<'de> for StationRecordVisitor {
    type Value = StationRecord;

    fn expecting(&self, formatter: &mut std::fmt::Formatter) -> std::fmt::Result {
        formatter.write_str("a station record: station, quantity and the recorded outputs")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<StationRecord, A::Error> {
        let rows: Vec<&StationOutput> = study_station_outputs().collect();
        let mut values: Vec<Option<RecordedValue>> = vec![None; rows.len()];
        let (mut station, mut quantity) = (None, None);
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "station" => station = Some(map.next_value::<String>()?),
                "quantity" => quantity = Some(map.next_value::<Quantity>()?),
                column => {
                    let Some(at) = rows.iter().position(|r| r.study_column == Some(column)) else {
                        return Err(de::Error::unknown_field(column, &[]));
                    };
                    values[at] = Some(match rows[at].unit {
                        Unit::Count => RecordedValue::Count(map.next_value()?),
                        _ => RecordedValue::Number(
                            map.next_value::<Option<String>>()?
                                .map(|text| exact::parse(&text))
                                .transpose()?,
                        ),
                    });
                }
            }
        }
        let missing = |name: &'static str| de::Error::missing_field(name);
        let values = values
            .into_iter()
            .zip(&rows)
            .map(|(v, row)| match (v, row.study_column) {
                (Some(v), _) => Ok(v),
                (None, Some(column)) if COLUMNS_ADDED_LATER.contains(&column) => {
                    Ok(RecordedValue::Number(None))
                }
                (None, column) => Err(missing(column.unwrap_or("value"))),
            })
            .collect::<Result<_, _>>()?;
        Ok(StationRecord {
            station: station.ok_or_else(|| missing("station"))?,
            quantity: quantity.ok_or_else(|| missing("quantity"))?,
            values,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record() -> StationRecord {
        StationRecord {
            station: "span1_mid".into(),
            quantity: Quantity::BendingMoment,
            values: vec![
                RecordedValue::Number(Some(1.5e6)),
                RecordedValue::Number(Some(1.6e6)),
                RecordedValue::Number(Some(0.1 + 0.2)),
                RecordedValue::Number(None),
                RecordedValue::Number(Some(2.5e-5)),
                RecordedValue::Count(Some(3)),
                RecordedValue::Number(Some(-0.0)),
                RecordedValue::Number(None),
                RecordedValue::Count(None),
            ],
        }
    }

    /// The journal line of a station record is the one the former derived struct wrote (so a
    /// study's journal reads on), and it reads back exactly.
    #[test]
    fn a_station_record_keeps_the_journal_form_of_the_former_struct_and_reads_back_exactly() {
        let json = serde_json::to_string(&record()).unwrap();
        assert_eq!(
            json,
            r#"{"station":"span1_mid","quantity":"bending_moment","static_max":"1500000","dynamic_max":"1600000","daf":"0.30000000000000004","daf_change":null,"daf_change_dt":"0.000025","cm":3,"dynamic_max_paper":"-0","daf_paper":null,"cm_paper":null}"#
        );
        let back: StationRecord = serde_json::from_str(&json).unwrap();
        assert_eq!(back, record());
        assert_eq!(back.number("daf"), Some(0.1 + 0.2));
        assert_eq!(back.number("cm"), Some(3.0));
        let cells = back.cells();
        assert_eq!(cells.len(), station_record_columns().len());
        assert_eq!(
            cells[..6],
            [
                "span1_mid",
                "bending_moment",
                "N·m",
                "1500000",
                "1600000",
                "0.30000000000000004"
            ]
        );
    }

    #[test]
    fn a_station_record_with_an_unknown_or_a_missing_column_is_refused() {
        let json = serde_json::to_string(&record()).unwrap();
        let unknown = json.replace("\"cm\":3", "\"cm\":3,\"speed\":1");
        assert!(serde_json::from_str::<StationRecord>(&unknown).is_err());
        let missing = json.replace(",\"cm_paper\":null", "");
        assert!(serde_json::from_str::<StationRecord>(&missing).is_err());
    }

    /// A journal written before the time-step indicator was recorded reads on: its lines lack
    /// `daf_change_dt`, which reads as undefined (an empty cell).
    #[test]
    fn a_journal_line_without_the_time_step_indicator_reads_it_as_undefined() {
        let json = serde_json::to_string(&record()).unwrap();
        let former = json.replace(",\"daf_change_dt\":\"0.000025\"", "");
        assert_ne!(former, json);
        let back: StationRecord = serde_json::from_str(&former).unwrap();
        assert_eq!(back.number("daf_change_dt"), None);
        assert_eq!(back.number("daf"), Some(0.1 + 0.2));
    }
}
