//! The record of one finished case of a study, typed: [`CaseRecord`] (a line of the `vbi
//! study` journal and a row of its `cases.csv`), its rows of `daf_by_modes.csv` ([`ModeRow`])
//! and `participation.csv` ([`ParticipationRow`]), the table columns, and [`case_record`], the
//! computation of one case from its scenario on a prepared bridge. Pure (no file I/O): the
//! `vbi study` command writes these records to its journal and tables, the Python package
//! returns them as its case table, and both give the same numbers and cells for a case.
//!
//! Numbers are numbers here (`f64`, `usize`), formatted only when a table is written, with
//! [`number`] (shortest round-trip `{}` formatting). serde stores every `f64` as a *string*
//! holding that same text, read back with Rust's correctly rounded `str::parse`: a JSON number
//! parsed by a fast approximate algorithm can land one unit in the last place off, which would
//! make a merged or resumed study's tables differ from an uninterrupted run's. The text form is
//! exact for every `f64`, including `-0`, subnormals, NaN and the infinities (which JSON numbers
//! cannot hold).

use serde::{Deserialize, Serialize};

use crate::analysis::StationDaf;
use crate::codes::{CodeImpactFactor, DesignCode};
use crate::crossing::{
    run_distinct_crossings, PreparedBridge, RunResult, Scenario, ScenarioBridgeError,
};
use crate::modal::{ModeKind, Quantity};
use crate::solver::Recording;

pub use super::cells::number;
use super::cells::{count_cell, exact, float_cell};

pub use crate::crossing::error_chain;

/// The record of one case: its crossing on the bridge prepared for its group (or the failure
/// of that preparation, or of the crossing, as the `error` cell).
pub fn case_record(
    id: &str,
    bridge: &Result<PreparedBridge, ScenarioBridgeError>,
    scenario: &Scenario,
) -> CaseRecord {
    case_record_with(id, bridge, scenario, &[])
}

/// [`case_record`] with the stations and quantities a study records besides its RDM station
/// (its `record`): one [`StationRecord`] per station and quantity, in the order asked. The
/// scenario's analysis must cover those stations
/// ([`StationScope::RdmStationAnd`](crate::analysis::StationScope::RdmStationAnd)).
pub fn case_record_with(
    id: &str,
    bridge: &Result<PreparedBridge, ScenarioBridgeError>,
    scenario: &Scenario,
    record: &[RecordRequest],
) -> CaseRecord {
    case_records_with(&[(id, scenario)], bridge, record)
        .pop()
        .expect("one record per case")
}

/// Crossings of one bridge that a study's worker integrates together
/// ([`integration_batches`](crate::crossing::integration_batches)): those of a batch that differ
/// only in their road share their position-dependent work
/// ([`simulate_batch`](crate::solver::simulate_batch)). They are analysed as they are
/// integrated (no history is held; a panel of instants and the wheel paths of each distinct
/// crossing are); 8 takes 7/8 of the shareable work off each crossing.
pub const STUDY_BATCH_SIZE: usize = 8;

/// [`case_record_with`] of several cases on one bridge, in order, the same records: their
/// crossings run by [`run_distinct_crossings`](crate::crossing::run_distinct_crossings), which integrates those that differ only in their road
/// together (pass a batch of [`integration_batches`](crate::crossing::integration_batches)).
pub fn case_records_with(
    cases: &[(&str, &Scenario)],
    bridge: &Result<PreparedBridge, ScenarioBridgeError>,
    record: &[RecordRequest],
) -> Vec<CaseRecord> {
    let bridge = match bridge {
        Ok(bridge) => bridge,
        Err(e) => {
            let error = format!("bridge analysis: {}", error_chain(e));
            let failed = |(id, _): &(&str, &Scenario)| CaseRecord::failed(id, error.clone());
            return cases.iter().map(failed).collect();
        }
    };
    let scenarios: Vec<&Scenario> = cases.iter().map(|&(_, scenario)| scenario).collect();
    // A repeated run (a smooth road's samples) is held once and read by each of its cases;
    // each crossing is analysed as it is integrated, without its history.
    let runs = run_distinct_crossings(bridge, &scenarios, Recording::OutcomeOnly);
    cases
        .iter()
        .enumerate()
        .map(|(i, &(id, _))| match runs.result(i) {
            Ok(result) => CaseRecord {
                station_records: StationRecord::of_run(record, bridge, result),
                ..CaseRecord::of_run(id, bridge, result)
            },
            Err(e) => CaseRecord::failed(id, error_chain(e)),
        })
        .collect()
}

/// One finished case: a line of `journal.jsonl`, and a row of `cases.csv` after the case id,
/// parameters, sample and seed. The fields are the metric columns ([`CASE_METRICS`]), in
/// order, with the same names; `None` is an empty cell. A failed case has its `error` and
/// nothing else.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseRecord {
    /// Case identifier.
    pub id: String,
    /// Why the case failed, if it did (every other field is then empty).
    pub error: Option<String>,
    /// The station of the RDM (the deflection and moment metrics are taken there).
    pub rdm_station: Option<String>,
    /// The converged (static-corrected) DAF of the deflection at the station [-].
    #[serde(with = "exact::option")]
    pub daf_u: Option<f64>,
    /// The converged DAF of the bending moment at the station [-].
    #[serde(with = "exact::option")]
    pub daf_m: Option<f64>,
    /// The converged RDM = DAF_u / DAF_M [-].
    #[serde(with = "exact::option")]
    pub rdm: Option<f64>,
    /// Convergence indicator of DAF_u ([`crate::analysis::DafConvergence`]: its change over the
    /// last ⌈N/2⌉ modes kept, or twice that over the check modes where larger) [-].
    #[serde(with = "exact::option")]
    pub daf_u_change: Option<f64>,
    /// Convergence indicator of DAF_M [-].
    #[serde(with = "exact::option")]
    pub daf_m_change: Option<f64>,
    /// Convergence indicator of DAF_u in the time step: DAF(Δt) − DAF(2Δt) [-]; None where the
    /// step was not checked (issue 46; a journal written before it reads as None).
    #[serde(with = "exact::option", default)]
    pub daf_u_change_dt: Option<f64>,
    /// The same of DAF_M [-].
    #[serde(with = "exact::option", default)]
    pub daf_m_change_dt: Option<f64>,
    /// Convergence mode of the converged DAF_u.
    pub cm_u: Option<usize>,
    /// Convergence mode of the converged DAF_M.
    pub cm_m: Option<usize>,
    /// Largest static deflection at the station [m].
    #[serde(with = "exact::option")]
    pub static_u_m: Option<f64>,
    /// Largest dynamic deflection at the station, converged series [m].
    #[serde(with = "exact::option")]
    pub dynamic_u_m: Option<f64>,
    /// Largest static moment at the station [N m].
    #[serde(with = "exact::option")]
    pub static_m_nm: Option<f64>,
    /// Largest dynamic moment at the station, converged series [N m].
    #[serde(with = "exact::option")]
    pub dynamic_m_nm: Option<f64>,
    /// The paper's DAF_u: plain modal sum of all N modes [-].
    #[serde(with = "exact::option")]
    pub daf_u_paper: Option<f64>,
    /// The paper's DAF_M [-].
    #[serde(with = "exact::option")]
    pub daf_m_paper: Option<f64>,
    /// The paper's RDM [-].
    #[serde(with = "exact::option")]
    pub rdm_paper: Option<f64>,
    /// Convergence mode of the paper's DAF_u.
    pub cm_u_paper: Option<usize>,
    /// Convergence mode of the paper's DAF_M.
    pub cm_m_paper: Option<usize>,
    /// The paper's largest dynamic deflection (plain modal sum) [m].
    #[serde(with = "exact::option")]
    pub dynamic_u_m_paper: Option<f64>,
    /// The paper's largest dynamic moment (plain modal sum) [N m].
    #[serde(with = "exact::option")]
    pub dynamic_m_nm_paper: Option<f64>,
    /// Deck-wide cut-off mode K1 of the deflection.
    pub k1_u: Option<usize>,
    /// Deck-wide cut-off mode K2 of the deflection.
    pub k2_u: Option<usize>,
    /// Deck-wide cut-off mode K1 of the moment.
    pub k1_m: Option<usize>,
    /// Deck-wide cut-off mode K2 of the moment.
    pub k2_m: Option<usize>,
    /// Cut-off mode K1 of the deflection at the station.
    pub station_k1_u: Option<usize>,
    /// Cut-off mode K2 of the deflection at the station.
    pub station_k2_u: Option<usize>,
    /// Cut-off mode K1 of the moment at the station.
    pub station_k1_m: Option<usize>,
    /// Cut-off mode K2 of the moment at the station.
    pub station_k2_m: Option<usize>,
    /// K1 of the deflection counted among the vertical bending modes only.
    pub k1_u_bending: Option<usize>,
    /// K2 of the deflection among the bending modes.
    pub k2_u_bending: Option<usize>,
    /// K1 of the moment among the bending modes.
    pub k1_m_bending: Option<usize>,
    /// K2 of the moment among the bending modes.
    pub k2_m_bending: Option<usize>,
    /// First natural frequency [Hz].
    #[serde(with = "exact::option")]
    pub f1_hz: Option<f64>,
    /// Number of modes of the basis.
    pub modes: Option<usize>,
    /// Number of contact losses.
    pub contact_losses: Option<usize>,
    /// The solver's warnings (under-resolved modes or road, unsettled tyre contact); one cell,
    /// `"; "`-joined.
    pub warnings: Vec<String>,
    /// The DAFs with the first K modes, K = 1…N: rows of `daf_by_modes.csv`.
    pub daf_by_modes: Vec<ModeRow>,
    /// The deck participation of each mode: rows of `participation.csv`.
    pub participation: Vec<ParticipationRow>,
    /// The stations and quantities of the study's `record`: rows of `station_records.csv`.
    /// Absent from the journal line when empty (a study without `record`), so that such a
    /// study's journal is what it was before.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub station_records: Vec<StationRecord>,
    /// The design codes' factors at the RDM station, its deflection and moment: rows of
    /// `design_codes.csv`. Absent from the journal line when empty (a failed case).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub design_codes: Vec<CodeRecord>,
}

/// One design code's factor for the RDM station's deflection or moment of a case: a row of
/// `design_codes.csv` after the case id ([`DESIGN_CODE_COLUMNS`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CodeRecord {
    /// Deflection or bending moment.
    pub quantity: Quantity,
    /// The code.
    pub code: DesignCode,
    /// The code's case ([`CodeImpactFactor::provision`]).
    pub provision: String,
    /// What the value follows from, with its unit.
    pub basis: String,
    /// The code's IM [-].
    #[serde(with = "exact")]
    pub impact_factor: f64,
    /// The computed (converged) DAF of the quantity [-].
    #[serde(with = "exact::option")]
    pub computed_daf: Option<f64>,
}

/// Columns of `design_codes.csv` after the case id ([`CodeRecord::cells`]).
pub const DESIGN_CODE_COLUMNS: [&str; 8] = [
    "quantity",
    "code",
    "provision",
    "basis",
    "impact_factor",
    "code_daf",
    "computed_daf",
    "computed_over_code",
];

impl CodeRecord {
    /// The records of the RDM station's deflection and moment of a finished crossing.
    pub fn of_run(result: &RunResult) -> Vec<CodeRecord> {
        let report = &result.report;
        let Some(station) = report.rdm_station.as_deref() else {
            return Vec::new();
        };
        report
            .design_codes
            .iter()
            .filter(|c| {
                c.station == station
                    && matches!(c.quantity, Quantity::Deflection | Quantity::BendingMoment)
            })
            .flat_map(|c| {
                let computed = report
                    .entry(c.station_index, c.quantity)
                    .and_then(|e| e.converged.daf);
                c.factors
                    .iter()
                    .map(move |f: &CodeImpactFactor| CodeRecord {
                        quantity: c.quantity,
                        code: f.code,
                        provision: f.provision.clone(),
                        basis: f.basis.clone(),
                        impact_factor: f.impact_factor,
                        computed_daf: computed,
                    })
            })
            .collect()
    }

    /// The code's design DAF, 1 + IM [-].
    pub fn code_daf(&self) -> f64 {
        1.0 + self.impact_factor
    }

    /// The cells of a row of `design_codes.csv` after the case id ([`DESIGN_CODE_COLUMNS`]).
    pub fn cells(&self) -> Vec<String> {
        vec![
            self.quantity.name().to_string(),
            self.code.name().to_string(),
            self.provision.clone(),
            self.basis.clone(),
            number(self.impact_factor),
            number(self.code_daf()),
            float_cell(self.computed_daf),
            float_cell(self.computed_daf.map(|d| d / self.code_daf())),
        ]
    }
}

pub use super::station_record::{station_record_columns, RecordRequest, StationRecord};

/// The DAFs of a case with its first `modes` modes: a row of `daf_by_modes.csv` after the case
/// id ([`MODE_COLUMNS`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModeRow {
    /// Number of modes K.
    pub modes: usize,
    /// The converged (static-corrected) DAF_u(K) [-].
    #[serde(with = "exact::option")]
    pub daf_u: Option<f64>,
    /// The converged DAF_M(K) [-].
    #[serde(with = "exact::option")]
    pub daf_m: Option<f64>,
    /// The converged RDM(K) [-].
    #[serde(with = "exact::option")]
    pub rdm: Option<f64>,
    /// The paper's DAF_u(K): plain partial modal sum [-].
    #[serde(with = "exact::option")]
    pub daf_u_paper: Option<f64>,
    /// The paper's DAF_M(K) [-].
    #[serde(with = "exact::option")]
    pub daf_m_paper: Option<f64>,
    /// The paper's RDM(K) [-].
    #[serde(with = "exact::option")]
    pub rdm_paper: Option<f64>,
    /// The paper's convergence mode of DAF_u had only K modes been kept.
    pub cm_u_paper: Option<usize>,
    /// The paper's convergence mode of DAF_M had only K modes been kept.
    pub cm_m_paper: Option<usize>,
    /// Deck-wide deflection K1 of the first K modes.
    pub k1_u: Option<usize>,
    /// Deck-wide deflection K2 of the first K modes.
    pub k2_u: Option<usize>,
    /// Deck-wide moment K1 of the first K modes.
    pub k1_m: Option<usize>,
    /// Deck-wide moment K2 of the first K modes.
    pub k2_m: Option<usize>,
}

/// The deck participation of one mode: a row of `participation.csv` after the case id
/// ([`PARTICIPATION_COLUMNS`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParticipationRow {
    /// Mode number (1-based).
    pub mode: usize,
    /// Natural frequency [Hz].
    #[serde(with = "exact")]
    pub frequency_hz: f64,
    /// Deflection participation MPS_k (Eq. 30).
    #[serde(with = "exact::option")]
    pub mps_u: Option<f64>,
    /// Moment participation MPS_k.
    #[serde(with = "exact::option")]
    pub mps_m: Option<f64>,
    /// What the mode mostly does.
    pub kind: ModeKind,
}

/// Metric columns of `cases.csv`, after the case id, parameters, sample and seed (and before
/// `error`): the fields of [`CaseRecord`] in order ([`CaseRecord::metric_cells`]).
pub const CASE_METRICS: [&str; 37] = [
    "rdm_station",
    "daf_u",
    "daf_m",
    "rdm",
    "daf_u_change",
    "daf_m_change",
    "daf_u_change_dt",
    "daf_m_change_dt",
    "cm_u",
    "cm_m",
    "static_u_m",
    "dynamic_u_m",
    "static_m_nm",
    "dynamic_m_nm",
    "daf_u_paper",
    "daf_m_paper",
    "rdm_paper",
    "cm_u_paper",
    "cm_m_paper",
    "dynamic_u_m_paper",
    "dynamic_m_nm_paper",
    "k1_u",
    "k2_u",
    "k1_m",
    "k2_m",
    "station_k1_u",
    "station_k2_u",
    "station_k1_m",
    "station_k2_m",
    "k1_u_bending",
    "k2_u_bending",
    "k1_m_bending",
    "k2_m_bending",
    "f1_hz",
    "modes",
    "contact_losses",
    "warnings",
];

/// Columns of `daf_by_modes.csv` after the case id ([`ModeRow::cells`]).
pub const MODE_COLUMNS: [&str; 13] = [
    "modes",
    "daf_u",
    "daf_m",
    "rdm",
    "daf_u_paper",
    "daf_m_paper",
    "rdm_paper",
    "cm_u_paper",
    "cm_m_paper",
    "k1_u",
    "k2_u",
    "k1_m",
    "k2_m",
];

/// Columns of `participation.csv` after the case id ([`ParticipationRow::cells`]).
pub const PARTICIPATION_COLUMNS: [&str; 5] = ["mode", "frequency_hz", "mps_u", "mps_m", "kind"];

/// A metric summarised over the samples in `summary.csv`: its name there, and its value in a
/// record.
#[derive(Debug, Clone, Copy)]
pub struct SummaryMetric {
    /// The `metric` cell of `summary.csv` (the `cases.csv` column it summarises).
    pub name: &'static str,
    /// The metric's value in a record (a mode number as a float).
    pub value: fn(&CaseRecord) -> Option<f64>,
}

fn mode_number(k: Option<usize>) -> Option<f64> {
    k.map(|k| k as f64)
}

/// Metrics summarised over samples in `summary.csv`, in its row order.
pub const SUMMARY_METRICS: [SummaryMetric; 12] = [
    SummaryMetric {
        name: "daf_u",
        value: |r| r.daf_u,
    },
    SummaryMetric {
        name: "daf_m",
        value: |r| r.daf_m,
    },
    SummaryMetric {
        name: "rdm",
        value: |r| r.rdm,
    },
    SummaryMetric {
        name: "daf_u_paper",
        value: |r| r.daf_u_paper,
    },
    SummaryMetric {
        name: "daf_m_paper",
        value: |r| r.daf_m_paper,
    },
    SummaryMetric {
        name: "rdm_paper",
        value: |r| r.rdm_paper,
    },
    SummaryMetric {
        name: "cm_u_paper",
        value: |r| mode_number(r.cm_u_paper),
    },
    SummaryMetric {
        name: "cm_m_paper",
        value: |r| mode_number(r.cm_m_paper),
    },
    SummaryMetric {
        name: "k1_u",
        value: |r| mode_number(r.k1_u),
    },
    SummaryMetric {
        name: "k2_u",
        value: |r| mode_number(r.k2_u),
    },
    SummaryMetric {
        name: "k1_m",
        value: |r| mode_number(r.k1_m),
    },
    SummaryMetric {
        name: "k2_m",
        value: |r| mode_number(r.k2_m),
    },
];

impl CaseRecord {
    /// The record of a finished crossing.
    pub fn of_run(id: &str, bridge: &PreparedBridge, result: &RunResult) -> CaseRecord {
        let report = &result.report;
        let basis = &bridge.basis;
        let station = report
            .rdm_station
            .as_ref()
            .and_then(|name| basis.stations.iter().position(|s| &s.name == name));
        let u = station.and_then(|s| report.entry(s, Quantity::Deflection));
        let m = station.and_then(|s| report.entry(s, Quantity::BendingMoment));
        let deck = &report.deck_participation;
        let bending = &deck.vertical_bending;
        let n = basis.mode_count();
        let at = |e: Option<&StationDaf>, series: fn(&StationDaf) -> &Vec<f64>, k: usize| {
            e.and_then(|e| series(e).get(k).copied())
        };
        let kept = |values: &[Option<usize>], k: usize| values.get(k).copied().flatten();
        let daf_by_modes = (0..n)
            .map(|k| ModeRow {
                modes: k + 1,
                daf_u: at(u, |e| &e.converged.daf_by_modes, k),
                daf_m: at(m, |e| &e.converged.daf_by_modes, k),
                rdm: report.rdm_by_modes.get(k).copied().flatten(),
                daf_u_paper: at(u, |e| &e.paper.daf_by_modes, k),
                daf_m_paper: at(m, |e| &e.paper.daf_by_modes, k),
                rdm_paper: report.rdm_paper_by_modes.get(k).copied().flatten(),
                cm_u_paper: kept(&report.modes_kept.cm_u_paper, k),
                cm_m_paper: kept(&report.modes_kept.cm_m_paper, k),
                k1_u: kept(&report.modes_kept.k1_u, k),
                k2_u: kept(&report.modes_kept.k2_u, k),
                k1_m: kept(&report.modes_kept.k1_m, k),
                k2_m: kept(&report.modes_kept.k2_m, k),
            })
            .collect();
        let participation = (0..n)
            .map(|k| ParticipationRow {
                mode: k + 1,
                frequency_hz: basis.modes[k].frequency_hz(),
                mps_u: deck.deflection.get(k).copied(),
                mps_m: deck.moment.get(k).copied(),
                kind: basis.modes[k].kind,
            })
            .collect();
        let change = |e: Option<&StationDaf>| e.and_then(|e| e.convergence).map(|c| c.change);
        let change_dt =
            |e: Option<&StationDaf>| e.and_then(|e| e.time_step_convergence).map(|c| c.change);
        CaseRecord {
            id: id.to_string(),
            error: None,
            rdm_station: report.rdm_station.clone(),
            daf_u: u.and_then(|e| e.converged.daf),
            daf_m: m.and_then(|e| e.converged.daf),
            rdm: report.rdm,
            daf_u_change: change(u),
            daf_m_change: change(m),
            daf_u_change_dt: change_dt(u),
            daf_m_change_dt: change_dt(m),
            cm_u: u.and_then(|e| e.converged.convergence_mode),
            cm_m: m.and_then(|e| e.converged.convergence_mode),
            static_u_m: u.map(|e| e.static_max),
            dynamic_u_m: u.map(|e| e.converged.dynamic_max),
            static_m_nm: m.map(|e| e.static_max),
            dynamic_m_nm: m.map(|e| e.converged.dynamic_max),
            daf_u_paper: u.and_then(|e| e.paper.daf),
            daf_m_paper: m.and_then(|e| e.paper.daf),
            rdm_paper: report.rdm_paper,
            cm_u_paper: u.and_then(|e| e.paper.convergence_mode),
            cm_m_paper: m.and_then(|e| e.paper.convergence_mode),
            dynamic_u_m_paper: u.map(|e| e.paper.dynamic_max),
            dynamic_m_nm_paper: m.map(|e| e.paper.dynamic_max),
            k1_u: deck.deflection_k1,
            k2_u: deck.deflection_k2,
            k1_m: deck.moment_k1,
            k2_m: deck.moment_k2,
            station_k1_u: u.and_then(|e| e.cutoff_k1),
            station_k2_u: u.and_then(|e| e.cutoff_k2),
            station_k1_m: m.and_then(|e| e.cutoff_k1),
            station_k2_m: m.and_then(|e| e.cutoff_k2),
            k1_u_bending: bending.deflection_k1,
            k2_u_bending: bending.deflection_k2,
            k1_m_bending: bending.moment_k1,
            k2_m_bending: bending.moment_k2,
            f1_hz: basis.modes.first().map(|m| m.frequency_hz()),
            modes: Some(n),
            contact_losses: Some(report.contact_losses.len()),
            warnings: report.warnings.iter().map(|w| w.to_string()).collect(),
            daf_by_modes,
            participation,
            station_records: Vec::new(),
            design_codes: CodeRecord::of_run(result),
        }
    }

    /// The record of a case that failed.
    pub fn failed(id: &str, error: String) -> CaseRecord {
        CaseRecord {
            id: id.to_string(),
            error: Some(error),
            ..CaseRecord::default()
        }
    }

    /// The cells of the metric columns of `cases.csv` ([`CASE_METRICS`], in order).
    pub fn metric_cells(&self) -> Vec<String> {
        vec![
            self.rdm_station.clone().unwrap_or_default(),
            float_cell(self.daf_u),
            float_cell(self.daf_m),
            float_cell(self.rdm),
            float_cell(self.daf_u_change),
            float_cell(self.daf_m_change),
            float_cell(self.daf_u_change_dt),
            float_cell(self.daf_m_change_dt),
            count_cell(self.cm_u),
            count_cell(self.cm_m),
            float_cell(self.static_u_m),
            float_cell(self.dynamic_u_m),
            float_cell(self.static_m_nm),
            float_cell(self.dynamic_m_nm),
            float_cell(self.daf_u_paper),
            float_cell(self.daf_m_paper),
            float_cell(self.rdm_paper),
            count_cell(self.cm_u_paper),
            count_cell(self.cm_m_paper),
            float_cell(self.dynamic_u_m_paper),
            float_cell(self.dynamic_m_nm_paper),
            count_cell(self.k1_u),
            count_cell(self.k2_u),
            count_cell(self.k1_m),
            count_cell(self.k2_m),
            count_cell(self.station_k1_u),
            count_cell(self.station_k2_u),
            count_cell(self.station_k1_m),
            count_cell(self.station_k2_m),
            count_cell(self.k1_u_bending),
            count_cell(self.k2_u_bending),
            count_cell(self.k1_m_bending),
            count_cell(self.k2_m_bending),
            float_cell(self.f1_hz),
            count_cell(self.modes),
            count_cell(self.contact_losses),
            self.warnings.join("; "),
        ]
    }

    /// The deflection participation of each mode, 0 where it is unknown.
    pub fn mps_u(&self) -> Vec<f64> {
        self.participation
            .iter()
            .map(|p| p.mps_u.unwrap_or(0.0))
            .collect()
    }

    /// The moment participation of each mode, 0 where it is unknown.
    pub fn mps_m(&self) -> Vec<f64> {
        self.participation
            .iter()
            .map(|p| p.mps_m.unwrap_or(0.0))
            .collect()
    }

    /// Whether each mode is a vertical bending mode.
    pub fn bending_modes(&self) -> Vec<bool> {
        self.participation
            .iter()
            .map(|p| p.kind == ModeKind::VerticalBending)
            .collect()
    }
}

impl ModeRow {
    /// The cells of a row of `daf_by_modes.csv` after the case id ([`MODE_COLUMNS`]).
    pub fn cells(&self) -> Vec<String> {
        vec![
            self.modes.to_string(),
            float_cell(self.daf_u),
            float_cell(self.daf_m),
            float_cell(self.rdm),
            float_cell(self.daf_u_paper),
            float_cell(self.daf_m_paper),
            float_cell(self.rdm_paper),
            count_cell(self.cm_u_paper),
            count_cell(self.cm_m_paper),
            count_cell(self.k1_u),
            count_cell(self.k2_u),
            count_cell(self.k1_m),
            count_cell(self.k2_m),
        ]
    }
}

impl ParticipationRow {
    /// The cells of a row of `participation.csv` after the case id ([`PARTICIPATION_COLUMNS`]).
    pub fn cells(&self) -> Vec<String> {
        vec![
            self.mode.to_string(),
            number(self.frequency_hz),
            float_cell(self.mps_u),
            float_cell(self.mps_m),
            self.kind.name().to_string(),
        ]
    }
}

/// The header of `cases.csv`: `case`, the study's parameter fields, `sample`, `seed`, the
/// metrics ([`CASE_METRICS`]) and `error`.
pub fn case_table_header(fields: &[String]) -> Vec<String> {
    let mut header = vec!["case".to_string()];
    header.extend(fields.iter().cloned());
    header.extend(["sample".to_string(), "seed".to_string()]);
    header.extend(CASE_METRICS.iter().map(|c| c.to_string()));
    header.push("error".to_string());
    header
}

/// The row of `cases.csv` of a case: its record with the cells of its parameters, sample and
/// seed ([`case_table_header`]).
pub fn case_table_row(
    record: &CaseRecord,
    parameters: &[String],
    sample: usize,
    seed: u64,
) -> Vec<String> {
    let mut row = vec![record.id.clone()];
    row.extend(parameters.iter().cloned());
    row.push(sample.to_string());
    row.push(seed.to_string());
    row.extend(record.metric_cells());
    row.push(record.error.clone().unwrap_or_default());
    row
}

/// The header of a table of rows after the case id: `case` and `columns`.
pub fn per_case_header(columns: &[&str]) -> Vec<String> {
    std::iter::once("case")
        .chain(columns.iter().copied())
        .map(str::to_string)
        .collect()
}

impl CaseRecord {
    /// The rows of `daf_by_modes.csv` of the case ([`MODE_COLUMNS`] after the case id); none
    /// for a failed case.
    pub fn mode_table_rows(&self) -> Vec<Vec<String>> {
        self.daf_by_modes
            .iter()
            .map(|m| std::iter::once(self.id.clone()).chain(m.cells()).collect())
            .collect()
    }

    /// The rows of `station_records.csv` of the case ([`station_record_columns`] after
    /// the case id); none for a failed case.
    pub fn station_record_rows(&self) -> Vec<Vec<String>> {
        self.station_records
            .iter()
            .map(|r| std::iter::once(self.id.clone()).chain(r.cells()).collect())
            .collect()
    }

    /// The rows of `design_codes.csv` of the case ([`DESIGN_CODE_COLUMNS`] after the case id);
    /// none for a failed case.
    pub fn design_code_rows(&self) -> Vec<Vec<String>> {
        self.design_codes
            .iter()
            .map(|r| std::iter::once(self.id.clone()).chain(r.cells()).collect())
            .collect()
    }

    /// The rows of `participation.csv` of the case ([`PARTICIPATION_COLUMNS`] after the case
    /// id); none for a failed case.
    pub fn participation_table_rows(&self) -> Vec<Vec<String>> {
        self.participation
            .iter()
            .map(|p| std::iter::once(self.id.clone()).chain(p.cells()).collect())
            .collect()
    }
}
