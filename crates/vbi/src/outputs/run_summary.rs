//! `vbi run`'s summary.json, typed: the one struct that the command writes and the run report
//! reads back. Its station entries are the rows of [`STATION_OUTPUTS`](super::STATION_OUTPUTS):
//! written from the analysis as [`StationEntry`](super::StationEntry)s, read back as
//! [`StationValues`], so that the summary is one type, generic in how its entries are held.

use std::collections::BTreeMap;

use serde::{Deserialize, Deserializer, Serialize};

use super::{fatigue_output, station_output};
use crate::analysis::{DeckParticipation, ModesKeptIndicators, TruncatedRun};
use crate::codes::StationCodeFactors;
use crate::solver::ContactLoss;

/// The summary of one crossing. `S` is a station entry: [`super::StationEntry`] when written,
/// [`StationValues`] when read; `F` a fatigue detail's entry: [`super::FatigueEntry`] when
/// written, [`FatigueValues`] when read.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunSummary<S, F = FatigueValues> {
    /// One entry per station and quantity: the rows of the table of station outputs.
    pub stations: Vec<S>,
    /// The station of the RDM.
    pub rdm_station: Option<String>,
    /// RDM = DAF_u / DAF_M of the converged DAFs there [-].
    pub rdm: Option<f64>,
    /// The converged RDM(K), K = 1…N [-].
    pub rdm_by_modes: Vec<Option<f64>>,
    /// The paper's RDM, of the plain modal sums [-].
    pub rdm_paper: Option<f64>,
    /// The paper's RDM(K), K = 1…N [-].
    pub rdm_paper_by_modes: Vec<Option<f64>>,
    /// The natural frequencies of the modes kept [Hz].
    pub frequencies_hz: Vec<f64>,
    /// The modal participation over the whole deck (Eq. 30).
    pub deck_participation: DeckParticipation,
    /// The modes-kept indicators (K1, K2 deck-wide, against the number of modes).
    pub modes_kept: ModesKeptIndicators,
    /// Where tyres left the road.
    pub contact_losses: Vec<ContactLoss>,
    /// The warnings, as printed.
    pub warnings: Vec<String>,
    /// Re-runs with fewer modes (`rerun_modes`).
    pub truncated_runs: Vec<TruncatedRun>,
    /// Each design code's factors beside the computed DAF, per station and quantity.
    pub design_codes: Vec<StationCodeFactors>,
    /// The fatigue of each detail of the scenario (none without details): the rows of the
    /// table of fatigue outputs.
    #[serde(default = "Vec::new")]
    pub fatigue: Vec<F>,
    /// The largest vertical acceleration at each station.
    pub station_accelerations: Vec<StationAcceleration>,
    /// The smallest and largest value of each column of vehicles.csv.
    pub vehicle_extremes: Vec<ColumnExtremes>,
    /// Where the numbers came from.
    pub provenance: Provenance,
}

/// Where the numbers of a run came from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// vbi version.
    pub vbi_version: String,
    /// SHA-256 of the scenario and every file it names.
    pub input_hash: String,
    /// Road seed.
    pub seed: u64,
    /// Time step [s].
    pub time_step_s: f64,
    /// Number of modes in the basis.
    pub modes: usize,
    /// Degrees of freedom of the FE model.
    pub dof_count: usize,
    /// Scenario name.
    pub scenario: String,
    /// Bridge as named in the scenario.
    pub bridge: String,
    /// Vehicle name.
    pub vehicle: String,
    /// Speed of the first vehicle at t = 0 [km/h].
    pub speed_kmh: f64,
}

/// The largest vertical acceleration at a station [m/s²] (absolute value).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StationAcceleration {
    /// The station's name.
    pub station: String,
    /// max |ü| over the run [m/s²].
    #[serde(deserialize_with = "number_or_nan")]
    pub max_abs_m_s2: f64,
}

/// The smallest and largest value of one column of vehicles.csv, in its unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ColumnExtremes {
    /// The column's name.
    pub column: String,
    /// Its smallest value (`null` in JSON, NaN read back, for an empty column).
    #[serde(deserialize_with = "number_or_nan")]
    pub min: f64,
    /// Its largest value.
    #[serde(deserialize_with = "number_or_nan")]
    pub max: f64,
}

/// A number, or NaN for the `null` that JSON writes for a non-finite one.
fn number_or_nan<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(deserializer)?.unwrap_or(f64::NAN))
}

/// One value of a station entry as summary.json holds it.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum SummaryValue {
    /// Undefined (`null`).
    Undefined,
    /// A yes or no.
    Flag(bool),
    /// A number or a count.
    Number(f64),
    /// A name or a word.
    Text(String),
    /// A series (a `null` in it: an undefined value).
    Series(Vec<Option<f64>>),
}

/// A station entry read back from summary.json: each value under the name of its row of the
/// table of station outputs. A name that is no row of the table is refused when read, so the
/// accessors are asked for rows only.
#[derive(Debug, Clone, PartialEq)]
pub struct StationValues(BTreeMap<String, SummaryValue>);

impl StationValues {
    /// The value of the row `name`.
    ///
    /// # Panics
    /// If `name` is not a row of the table of station outputs (a programming error).
    pub fn value(&self, name: &str) -> Option<&SummaryValue> {
        assert!(
            station_output(name).is_some(),
            "`{name}` is no station output"
        );
        self.0.get(name)
    }

    /// The number of the row `name`, if it is one and defined.
    pub fn number(&self, name: &str) -> Option<f64> {
        match self.value(name)? {
            SummaryValue::Number(value) => Some(*value),
            _ => None,
        }
    }

    /// The text of the row `name` ("" where it is none).
    pub fn text(&self, name: &str) -> &str {
        match self.value(name) {
            Some(SummaryValue::Text(text)) => text,
            _ => "",
        }
    }

    /// The yes or no of the row `name`, if it is one.
    pub fn flag(&self, name: &str) -> Option<bool> {
        match self.value(name)? {
            SummaryValue::Flag(flag) => Some(*flag),
            _ => None,
        }
    }
}

impl<'de> Deserialize<'de> for StationValues {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<StationValues, D::Error> {
        let values = BTreeMap::<String, SummaryValue>::deserialize(deserializer)?;
        if let Some(unknown) = values.keys().find(|name| station_output(name).is_none()) {
            return Err(serde::de::Error::custom(format!(
                "`{unknown}` is no output of a station entry"
            )));
        }
        Ok(StationValues(values))
    }
}

/// A detail's entry read back from summary.json, each value under its row's name.
#[derive(Debug, Clone, PartialEq)]
pub struct FatigueValues(pub BTreeMap<String, SummaryValue>);

impl<'de> Deserialize<'de> for FatigueValues {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<FatigueValues, D::Error> {
        let values = BTreeMap::<String, SummaryValue>::deserialize(deserializer)?;
        if let Some(unknown) = values.keys().find(|name| fatigue_output(name).is_none()) {
            return Err(serde::de::Error::custom(format!(
                "`{unknown}` is no output of a fatigue detail"
            )));
        }
        Ok(FatigueValues(values))
    }
}
