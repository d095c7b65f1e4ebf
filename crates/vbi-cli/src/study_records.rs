//! The files of a study's output directory, typed: the manifest `study.json` ([`Manifest`]),
//! the journal `journal.jsonl` (one [`CaseRecord`] per line, [`Journal`], [`read_journal`]) and
//! the cells that the tables `cases.csv`, `daf_by_modes.csv` and `participation.csv` make of a
//! record.
//!
//! Why a module of its own at the crate root, next to `output` and `input`, and not under
//! `commands::study`: these files are a format shared by two commands. `vbi study` writes them
//! (and `vbi study merge` reads and rewrites them); `vbi report` reads them. Under
//! `commands::study` the report would depend on the study command again, which is the module
//! cycle this module removes: now both commands depend on this module, and it depends on no
//! command (only on `inputs::study`, `output` and the library).
//!
//! Numbers are numbers here (`f64`, `usize`), formatted only when a table is written, with
//! [`number`] (shortest round-trip `{}` formatting). In the journal every `f64` is stored as a
//! JSON *string* holding that same text, and read back with Rust's correctly rounded
//! `str::parse`: serde_json, as this workspace builds it (without its `float_roundtrip`
//! feature), parses a JSON number with a fast approximate algorithm that lands one unit in the
//! last place off for about one double in nine, which would make a merged or resumed study's
//! tables differ from an uninterrupted run's. The text form is exact for every `f64`, including
//! `-0`, subnormals, NaN and the infinities (which JSON numbers cannot hold).

use std::collections::BTreeMap;
use std::fs::OpenOptions;
use std::io::Write;
use std::path::Path;

use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};

use vbi::modal::{ModeKind, Quantity};
use vbi::pipeline::{PreparedBridge, RunResult};
use vbi::study::Shard;

use crate::inputs::study::Study;
use crate::output::number;

/// Format of a results directory (`study.json` and the journal's records); results of another
/// format are never mixed. Format 2 added the static-corrected and bending-mode columns; format
/// 3 stores typed records (numbers, not table cells) in the journal.
pub const RESULTS_FORMAT: u32 = 3;

/// One case as recorded in the manifest.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ManifestCase {
    /// Stable identifier.
    pub id: String,
    /// Position in the case order.
    pub order: usize,
    /// Value of each varied field (`fields`), empty when the case does not set it.
    pub parameters: Vec<String>,
    /// Roughness sample index.
    pub sample: usize,
    /// Road seed.
    pub seed: u64,
    /// Bridge label.
    pub bridge: String,
}

/// `study.json`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Manifest {
    /// Results format version ([`RESULTS_FORMAT`]).
    pub format: u32,
    /// vbi version.
    pub vbi_version: String,
    /// Study name.
    pub name: String,
    /// The study file as given.
    pub study_file: String,
    /// SHA-256 of the normalised specification.
    pub study_hash: String,
    /// `I/N`, or None for the whole study.
    pub shard: Option<String>,
    /// Varied fields (parameter columns).
    pub fields: Vec<String>,
    /// Axes: field and values, in order.
    pub axes: Vec<(String, Vec<String>)>,
    /// Values held fixed in figures.
    pub reference: BTreeMap<String, String>,
    /// Samples per combination.
    pub samples: usize,
    /// The normalised specification.
    pub spec: BTreeMap<String, String>,
    /// Text of the study file.
    pub source: String,
    /// Every case of the study (all shards), in order.
    pub cases: Vec<ManifestCase>,
}

impl Manifest {
    /// The manifest of a study (or of one shard of it).
    pub fn of(study: &Study, shard: Option<Shard>) -> Manifest {
        Manifest {
            format: RESULTS_FORMAT,
            vbi_version: env!("CARGO_PKG_VERSION").to_string(),
            name: study.name.clone(),
            study_file: study.path.display().to_string(),
            study_hash: study.hash.clone(),
            shard: shard.map(|s| s.to_string()),
            fields: study.fields.clone(),
            axes: study
                .design
                .axes
                .iter()
                .map(|a| {
                    (
                        a.field.clone(),
                        a.values.iter().map(|v| v.to_string()).collect(),
                    )
                })
                .collect(),
            reference: study.reference.clone(),
            samples: study.design.samples,
            spec: study.spec.clone(),
            source: study.source.clone(),
            cases: study
                .cases
                .iter()
                .zip(&study.scenarios)
                .map(|(c, s)| ManifestCase {
                    id: c.id.clone(),
                    order: c.order,
                    parameters: study
                        .fields
                        .iter()
                        .map(|f| c.value(f).map(|v| v.to_string()).unwrap_or_default())
                        .collect(),
                    sample: c.sample,
                    seed: c.seed,
                    bridge: s.bridge_label.clone(),
                })
                .collect(),
        }
    }

    /// The shard of this directory ([`Shard::WHOLE`] for a whole study).
    pub fn shard(&self) -> Result<Shard> {
        Ok(match &self.shard {
            Some(s) => s.parse()?,
            None => Shard::WHOLE,
        })
    }

    /// The cases of this directory (its shard), in order.
    pub fn own_cases(&self) -> Result<&[ManifestCase]> {
        let range = self.shard()?.range(self.cases.len());
        Ok(&self.cases[range])
    }

    /// Position of a varied field among the parameter columns.
    pub fn field_index(&self, field: &str) -> Option<usize> {
        self.fields.iter().position(|f| f == field)
    }

    /// The value that a case gives a varied field (empty when the case does not set it), or
    /// None when the field is not varied.
    pub fn value_of<'a>(&self, case: &'a ManifestCase, field: &str) -> Option<&'a str> {
        self.field_index(field).map(|i| case.parameters[i].as_str())
    }
}

/// Reads `DIR/study.json`: None when there is none; an error when it is not a manifest or is
/// of another results format.
pub fn read_manifest(dir: &Path) -> Result<Option<Manifest>> {
    let path = dir.join("study.json");
    match std::fs::read_to_string(&path) {
        Ok(text) => {
            let manifest: Manifest = serde_json::from_str(&text)
                .with_context(|| format!("{} is not a vbi study manifest", path.display()))?;
            if manifest.format != RESULTS_FORMAT {
                bail!(
                    "{} holds results of format {} (vbi {}); this vbi writes format {} with other \
                     columns and will not mix them: run the study into a new --out directory",
                    dir.display(),
                    manifest.format,
                    manifest.vbi_version,
                    RESULTS_FORMAT
                );
            }
            Ok(Some(manifest))
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(e).with_context(|| format!("reading {}", path.display())),
    }
}

/// One finished case: a line of `journal.jsonl`, and a row of `cases.csv` after the case id,
/// parameters, sample and seed. The fields are the metric columns ([`CASE_METRICS`]), in
/// order, with the same names; `None` is an empty cell. A failed case has its `error` and
/// nothing else.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseRecord {
    /// Case identifier.
    pub id: String,
    /// Why the case failed, if it did (every other field is then empty).
    pub error: Option<String>,
    /// The station of the RDM (the deflection and moment metrics are taken there).
    pub rdm_station: Option<String>,
    /// DAF of the deflection at the station.
    #[serde(with = "exact::option")]
    pub daf_u: Option<f64>,
    /// DAF of the bending moment at the station.
    #[serde(with = "exact::option")]
    pub daf_m: Option<f64>,
    /// RDM = DAF_u / DAF_M.
    #[serde(with = "exact::option")]
    pub rdm: Option<f64>,
    /// Convergence mode of DAF_u.
    pub cm_u: Option<usize>,
    /// Convergence mode of DAF_M.
    pub cm_m: Option<usize>,
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
    /// Largest static deflection at the station [m].
    #[serde(with = "exact::option")]
    pub static_u_m: Option<f64>,
    /// Largest dynamic deflection at the station [m].
    #[serde(with = "exact::option")]
    pub dynamic_u_m: Option<f64>,
    /// Largest static moment at the station [N m].
    #[serde(with = "exact::option")]
    pub static_m_nm: Option<f64>,
    /// Largest dynamic moment at the station [N m].
    #[serde(with = "exact::option")]
    pub dynamic_m_nm: Option<f64>,
    /// First natural frequency [Hz].
    #[serde(with = "exact::option")]
    pub f1_hz: Option<f64>,
    /// Number of modes of the basis.
    pub modes: Option<usize>,
    /// Number of contact losses.
    pub contact_losses: Option<usize>,
    /// Static-corrected (mode-acceleration) DAF_u at the same station.
    #[serde(with = "exact::option")]
    pub daf_u_corrected: Option<f64>,
    /// Static-corrected DAF_M.
    #[serde(with = "exact::option")]
    pub daf_m_corrected: Option<f64>,
    /// Static-corrected RDM.
    #[serde(with = "exact::option")]
    pub rdm_corrected: Option<f64>,
    /// Convergence mode of the static-corrected DAF_u.
    pub cm_u_corrected: Option<usize>,
    /// Convergence mode of the static-corrected DAF_M.
    pub cm_m_corrected: Option<usize>,
    /// K1 of the deflection counted among the vertical bending modes only.
    pub k1_u_bending: Option<usize>,
    /// K2 of the deflection among the bending modes.
    pub k2_u_bending: Option<usize>,
    /// K1 of the moment among the bending modes.
    pub k1_m_bending: Option<usize>,
    /// K2 of the moment among the bending modes.
    pub k2_m_bending: Option<usize>,
    /// The solver's warnings (under-resolved modes or road, unsettled tyre contact); one cell,
    /// `"; "`-joined.
    pub warnings: Vec<String>,
    /// The DAFs with the first K modes, K = 1…N: rows of `daf_by_modes.csv`.
    pub daf_by_modes: Vec<ModeRow>,
    /// The deck participation of each mode: rows of `participation.csv`.
    pub participation: Vec<ParticipationRow>,
}

/// The DAFs of a case with its first `modes` modes: a row of `daf_by_modes.csv` after the case
/// id ([`MODE_COLUMNS`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModeRow {
    /// Number of modes K.
    pub modes: usize,
    /// DAF_u(K).
    #[serde(with = "exact::option")]
    pub daf_u: Option<f64>,
    /// DAF_M(K).
    #[serde(with = "exact::option")]
    pub daf_m: Option<f64>,
    /// RDM(K).
    #[serde(with = "exact::option")]
    pub rdm: Option<f64>,
    /// Static-corrected DAF_u(K).
    #[serde(with = "exact::option")]
    pub daf_u_corrected: Option<f64>,
    /// Static-corrected DAF_M(K).
    #[serde(with = "exact::option")]
    pub daf_m_corrected: Option<f64>,
    /// Static-corrected RDM(K).
    #[serde(with = "exact::option")]
    pub rdm_corrected: Option<f64>,
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
pub const CASE_METRICS: [&str; 31] = [
    "rdm_station",
    "daf_u",
    "daf_m",
    "rdm",
    "cm_u",
    "cm_m",
    "k1_u",
    "k2_u",
    "k1_m",
    "k2_m",
    "station_k1_u",
    "station_k2_u",
    "station_k1_m",
    "station_k2_m",
    "static_u_m",
    "dynamic_u_m",
    "static_m_nm",
    "dynamic_m_nm",
    "f1_hz",
    "modes",
    "contact_losses",
    // The static-corrected (mode-acceleration) series at the same station.
    "daf_u_corrected",
    "daf_m_corrected",
    "rdm_corrected",
    "cm_u_corrected",
    "cm_m_corrected",
    // Cut-off modes counted among the vertical bending modes only.
    "k1_u_bending",
    "k2_u_bending",
    "k1_m_bending",
    "k2_m_bending",
    // The solver's warnings, "; "-joined.
    "warnings",
];

/// Columns of `daf_by_modes.csv` after the case id ([`ModeRow::cells`]).
pub const MODE_COLUMNS: [&str; 7] = [
    "modes",
    "daf_u",
    "daf_m",
    "rdm",
    "daf_u_corrected",
    "daf_m_corrected",
    "rdm_corrected",
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
        name: "cm_u",
        value: |r| mode_number(r.cm_u),
    },
    SummaryMetric {
        name: "cm_m",
        value: |r| mode_number(r.cm_m),
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
    SummaryMetric {
        name: "daf_u_corrected",
        value: |r| r.daf_u_corrected,
    },
    SummaryMetric {
        name: "daf_m_corrected",
        value: |r| r.daf_m_corrected,
    },
    SummaryMetric {
        name: "rdm_corrected",
        value: |r| r.rdm_corrected,
    },
];

/// A table cell of an optional float: [`number`], or empty.
fn float_cell(value: Option<f64>) -> String {
    value.map(number).unwrap_or_default()
}

/// A table cell of an optional count or mode number, or empty.
fn count_cell(value: Option<usize>) -> String {
    value.map(|v| v.to_string()).unwrap_or_default()
}

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
        let daf_by_modes = (0..n)
            .map(|k| ModeRow {
                modes: k + 1,
                daf_u: u.and_then(|e| e.daf_by_modes.get(k).copied()),
                daf_m: m.and_then(|e| e.daf_by_modes.get(k).copied()),
                rdm: report.rdm_by_modes.get(k).copied().flatten(),
                daf_u_corrected: u.and_then(|e| e.corrected_daf_by_modes.get(k).copied()),
                daf_m_corrected: m.and_then(|e| e.corrected_daf_by_modes.get(k).copied()),
                rdm_corrected: report.corrected_rdm_by_modes.get(k).copied().flatten(),
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
        CaseRecord {
            id: id.to_string(),
            error: None,
            rdm_station: report.rdm_station.clone(),
            daf_u: u.and_then(|e| e.daf),
            daf_m: m.and_then(|e| e.daf),
            rdm: report.rdm,
            cm_u: u.and_then(|e| e.convergence_mode),
            cm_m: m.and_then(|e| e.convergence_mode),
            k1_u: deck.deflection_k1,
            k2_u: deck.deflection_k2,
            k1_m: deck.moment_k1,
            k2_m: deck.moment_k2,
            station_k1_u: u.and_then(|e| e.cutoff_k1),
            station_k2_u: u.and_then(|e| e.cutoff_k2),
            station_k1_m: m.and_then(|e| e.cutoff_k1),
            station_k2_m: m.and_then(|e| e.cutoff_k2),
            static_u_m: u.map(|e| e.static_max),
            dynamic_u_m: u.map(|e| e.dynamic_max),
            static_m_nm: m.map(|e| e.static_max),
            dynamic_m_nm: m.map(|e| e.dynamic_max),
            f1_hz: basis.modes.first().map(|m| m.frequency_hz()),
            modes: Some(n),
            contact_losses: Some(report.contact_losses.len()),
            daf_u_corrected: u.and_then(|e| e.corrected_daf),
            daf_m_corrected: m.and_then(|e| e.corrected_daf),
            rdm_corrected: report.corrected_rdm,
            cm_u_corrected: u.and_then(|e| e.corrected_convergence_mode),
            cm_m_corrected: m.and_then(|e| e.corrected_convergence_mode),
            k1_u_bending: bending.deflection_k1,
            k2_u_bending: bending.deflection_k2,
            k1_m_bending: bending.moment_k1,
            k2_m_bending: bending.moment_k2,
            warnings: report.warnings.iter().map(|w| w.to_string()).collect(),
            daf_by_modes,
            participation,
        }
    }

    /// The record of a case that failed.
    pub fn failed(id: &str, error: String) -> CaseRecord {
        CaseRecord {
            id: id.to_string(),
            error: Some(error),
            rdm_station: None,
            daf_u: None,
            daf_m: None,
            rdm: None,
            cm_u: None,
            cm_m: None,
            k1_u: None,
            k2_u: None,
            k1_m: None,
            k2_m: None,
            station_k1_u: None,
            station_k2_u: None,
            station_k1_m: None,
            station_k2_m: None,
            static_u_m: None,
            dynamic_u_m: None,
            static_m_nm: None,
            dynamic_m_nm: None,
            f1_hz: None,
            modes: None,
            contact_losses: None,
            daf_u_corrected: None,
            daf_m_corrected: None,
            rdm_corrected: None,
            cm_u_corrected: None,
            cm_m_corrected: None,
            k1_u_bending: None,
            k2_u_bending: None,
            k1_m_bending: None,
            k2_m_bending: None,
            warnings: Vec::new(),
            daf_by_modes: Vec::new(),
            participation: Vec::new(),
        }
    }

    /// The cells of the metric columns of `cases.csv` ([`CASE_METRICS`], in order).
    pub fn metric_cells(&self) -> Vec<String> {
        vec![
            self.rdm_station.clone().unwrap_or_default(),
            float_cell(self.daf_u),
            float_cell(self.daf_m),
            float_cell(self.rdm),
            count_cell(self.cm_u),
            count_cell(self.cm_m),
            count_cell(self.k1_u),
            count_cell(self.k2_u),
            count_cell(self.k1_m),
            count_cell(self.k2_m),
            count_cell(self.station_k1_u),
            count_cell(self.station_k2_u),
            count_cell(self.station_k1_m),
            count_cell(self.station_k2_m),
            float_cell(self.static_u_m),
            float_cell(self.dynamic_u_m),
            float_cell(self.static_m_nm),
            float_cell(self.dynamic_m_nm),
            float_cell(self.f1_hz),
            count_cell(self.modes),
            count_cell(self.contact_losses),
            float_cell(self.daf_u_corrected),
            float_cell(self.daf_m_corrected),
            float_cell(self.rdm_corrected),
            count_cell(self.cm_u_corrected),
            count_cell(self.cm_m_corrected),
            count_cell(self.k1_u_bending),
            count_cell(self.k2_u_bending),
            count_cell(self.k1_m_bending),
            count_cell(self.k2_m_bending),
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
            float_cell(self.daf_u_corrected),
            float_cell(self.daf_m_corrected),
            float_cell(self.rdm_corrected),
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

/// A record as one journal line, without its newline.
pub fn journal_line(record: &CaseRecord) -> Result<Vec<u8>> {
    serde_json::to_vec(record).context("formatting a case record")
}

/// Reads a journal: the records of its complete lines, and the length of those lines in
/// bytes (a last line without its newline is a write cut short by a crash: ignored). Read it
/// after [`read_manifest`] has checked the directory's results format.
pub fn read_journal(path: &Path) -> Result<(Vec<CaseRecord>, u64)> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok((Vec::new(), 0)),
        Err(e) => return Err(e).with_context(|| format!("reading {}", path.display())),
    };
    let mut records = Vec::new();
    let mut valid = 0;
    let mut line_number = 0;
    while let Some(end) = bytes[valid..].iter().position(|&b| b == b'\n') {
        line_number += 1;
        let line = &bytes[valid..valid + end];
        let record: CaseRecord = serde_json::from_slice(line).with_context(|| {
            format!(
                "{}: line {line_number} is not a case record of results format \
                 {RESULTS_FORMAT} (the journal is damaged, or comes from another version)",
                path.display()
            )
        })?;
        records.push(record);
        valid += end + 1;
    }
    Ok((records, valid as u64))
}

/// The journal, open for appending.
pub struct Journal {
    file: std::fs::File,
}

impl Journal {
    /// Opens the journal, cutting off an incomplete last line (`valid_length` from
    /// [`read_journal`]).
    pub fn open(path: &Path, valid_length: u64) -> Result<Journal> {
        let file = OpenOptions::new()
            .create(true)
            .truncate(false)
            .read(true)
            .write(true)
            .open(path)
            .with_context(|| format!("opening {}", path.display()))?;
        file.set_len(valid_length)
            .with_context(|| format!("truncating {}", path.display()))?;
        drop(file);
        let file = OpenOptions::new()
            .append(true)
            .open(path)
            .with_context(|| format!("opening {}", path.display()))?;
        Ok(Journal { file })
    }

    /// Appends one record as one line, in one write, and flushes it to the disk.
    pub fn append(&mut self, record: &CaseRecord) -> Result<()> {
        let mut line = journal_line(record)?;
        line.push(b'\n');
        self.file.write_all(&line)?;
        self.file.flush()?;
        self.file.sync_data()?;
        Ok(())
    }
}

/// serde of an `f64` as the JSON string of its shortest round-trip text, read back exactly
/// (the module documentation says why); `exact::option` for an `Option<f64>` (None is `null`).
mod exact {
    use serde::{Deserialize, Deserializer, Serializer};

    use crate::output::number;

    fn parse<E: serde::de::Error>(text: &str) -> Result<f64, E> {
        text.parse()
            .map_err(|_| E::custom(format!("{text:?} is not a number")))
    }

    pub fn serialize<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&number(*value))
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
        parse(&String::deserialize(deserializer)?)
    }

    pub mod option {
        use serde::{Deserialize, Deserializer, Serializer};

        pub fn serialize<S: Serializer>(
            value: &Option<f64>,
            serializer: S,
        ) -> Result<S::Ok, S::Error> {
            match value {
                Some(v) => super::serialize(v, serializer),
                None => serializer.serialize_none(),
            }
        }

        pub fn deserialize<'de, D: Deserializer<'de>>(
            deserializer: D,
        ) -> Result<Option<f64>, D::Error> {
            Option::<String>::deserialize(deserializer)?
                .map(|text| super::parse(&text))
                .transpose()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A record with every kind of value: None, numbers that are not exact in binary, an
    /// underflowing one, negative zero, one that serde_json's default float parser reads one
    /// unit in the last place off, NaN and the infinities.
    fn record() -> CaseRecord {
        CaseRecord {
            error: None,
            rdm_station: Some("span 1 midspan".into()),
            daf_u: Some(0.1 + 0.2),
            daf_m: Some(-0.0),
            rdm: Some(1e-300),
            cm_u: Some(7),
            k1_u: Some(3),
            static_u_m: Some(-0.004_213_987_654_321_9),
            dynamic_u_m: Some(2.597_639_773_290_682_6),
            static_m_nm: Some(5e-324),
            dynamic_m_nm: Some(f64::MAX),
            f1_hz: Some(f64::NAN),
            modes: Some(2),
            contact_losses: Some(0),
            daf_u_corrected: Some(f64::INFINITY),
            daf_m_corrected: Some(f64::NEG_INFINITY),
            warnings: vec!["mode 9 under-resolved".into(), "road \"short\"; 2".into()],
            daf_by_modes: vec![
                ModeRow {
                    modes: 1,
                    daf_u: Some(1.0),
                    daf_m: None,
                    rdm: Some(0.104_940_354_630_094_99),
                    daf_u_corrected: Some(-0.0),
                    daf_m_corrected: None,
                    rdm_corrected: Some(1e300),
                },
                ModeRow {
                    modes: 2,
                    daf_u: None,
                    daf_m: Some(1.004_721_517_217_110_7),
                    rdm: None,
                    daf_u_corrected: None,
                    daf_m_corrected: Some(0.3),
                    rdm_corrected: None,
                },
            ],
            participation: vec![ParticipationRow {
                mode: 1,
                frequency_hz: 4.997_123_456_789_012,
                mps_u: Some(0.987_810_870_231_446_1),
                mps_m: None,
                kind: ModeKind::Torsion,
            }],
            ..CaseRecord::failed("0123456789abcdef", String::new())
        }
    }

    /// Every float of a record, bit for bit.
    fn float_bits(r: &CaseRecord) -> Vec<Option<u64>> {
        let mut floats = vec![
            r.daf_u,
            r.daf_m,
            r.rdm,
            r.static_u_m,
            r.dynamic_u_m,
            r.static_m_nm,
            r.dynamic_m_nm,
            r.f1_hz,
            r.daf_u_corrected,
            r.daf_m_corrected,
            r.rdm_corrected,
        ];
        for m in &r.daf_by_modes {
            floats.extend([
                m.daf_u,
                m.daf_m,
                m.rdm,
                m.daf_u_corrected,
                m.daf_m_corrected,
                m.rdm_corrected,
            ]);
        }
        for p in &r.participation {
            floats.extend([Some(p.frequency_hz), p.mps_u, p.mps_m]);
        }
        floats.iter().map(|f| f.map(f64::to_bits)).collect()
    }

    #[test]
    fn a_case_record_survives_a_journal_round_trip_bit_for_bit() {
        let failed = CaseRecord::failed("fedcba9876543210", "solver: diverged".into());
        for original in [record(), failed] {
            let line = journal_line(&original).unwrap();
            assert!(!line.contains(&b'\n'));
            let back: CaseRecord = serde_json::from_slice(&line).unwrap();
            assert_eq!(float_bits(&back), float_bits(&original));
            // PartialEq (NaN aside: -0 == 0 there, so the bits above are the real check).
            let without_nan = |r: &CaseRecord| CaseRecord {
                f1_hz: r.f1_hz.filter(|f| !f.is_nan()),
                ..r.clone()
            };
            assert_eq!(without_nan(&back), without_nan(&original));
            assert_eq!(journal_line(&back).unwrap(), line);
            assert_eq!(back.metric_cells(), original.metric_cells());
        }
        assert_eq!(
            float_bits(&record())[..2],
            [Some((0.1f64 + 0.2).to_bits()), Some((-0.0f64).to_bits())]
        );
    }

    #[test]
    fn cells_are_written_with_number_and_empty_for_none() {
        let r = record();
        let cells = r.metric_cells();
        assert_eq!(cells.len(), CASE_METRICS.len());
        let cell = |name: &str| &cells[CASE_METRICS.iter().position(|m| *m == name).unwrap()];
        assert_eq!(cell("daf_u"), "0.30000000000000004");
        assert_eq!(cell("daf_m"), "-0");
        assert_eq!(cell("rdm"), &number(1e-300));
        assert_eq!(cell("rdm").parse::<f64>().unwrap(), 1e-300);
        assert_eq!(cell("cm_m"), "");
        assert_eq!(cell("f1_hz"), "NaN");
        assert_eq!(cell("modes"), "2");
        assert_eq!(cell("contact_losses"), "0");
        assert_eq!(cell("daf_u_corrected"), "inf");
        assert_eq!(cell("warnings"), "mode 9 under-resolved; road \"short\"; 2");
        assert_eq!(r.daf_by_modes[0].cells().len(), MODE_COLUMNS.len());
        assert_eq!(
            r.daf_by_modes[0].cells(),
            [
                "1".to_string(),
                "1".into(),
                "".into(),
                "0.10494035463009499".into(),
                "-0".into(),
                "".into(),
                number(1e300),
            ]
        );
        assert_eq!(
            r.participation[0].cells(),
            [
                "1",
                "4.997123456789012",
                "0.9878108702314461",
                "",
                "torsion"
            ]
        );
        assert!(CaseRecord::failed("x", "e".into())
            .metric_cells()
            .iter()
            .all(String::is_empty));
    }

    /// The keys of a one-level JSON object whose values hold no commas, in order.
    fn keys(json: &[u8]) -> Vec<String> {
        String::from_utf8(json.to_vec())
            .unwrap()
            .trim_matches(|c| c == '{' || c == '}')
            .split(',')
            .map(|pair| pair.split('"').nth(1).unwrap().to_string())
            .collect()
    }

    /// The fields of the record and its rows, in declaration order, are the columns of
    /// `cases.csv`, `daf_by_modes.csv` and `participation.csv`.
    #[test]
    fn record_fields_are_the_table_columns_in_order() {
        let line = journal_line(&CaseRecord::failed("x", "e".into())).unwrap();
        let mut expected = vec!["id", "error"];
        expected.extend(CASE_METRICS);
        expected.extend(["daf_by_modes", "participation"]);
        assert_eq!(keys(&line), expected);
        let mut row = record().daf_by_modes[1].clone();
        row.daf_m = None;
        row.daf_m_corrected = None;
        assert_eq!(keys(&serde_json::to_vec(&row).unwrap()), MODE_COLUMNS);
        let row = &record().participation[0];
        assert_eq!(
            keys(&serde_json::to_vec(row).unwrap()),
            PARTICIPATION_COLUMNS
        );
    }

    #[test]
    fn a_line_of_the_old_format_is_refused() {
        let old = r#"{"id":"x","error":null,"metrics":["a"],"daf_by_modes":[],"participation":[]}"#;
        assert!(serde_json::from_str::<CaseRecord>(old).is_err());
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("journal.jsonl");
        std::fs::write(&path, format!("{old}\n")).unwrap();
        let error = format!("{:#}", read_journal(&path).unwrap_err());
        assert!(
            error.contains("line 1 is not a case record of results format 3"),
            "{error}"
        );
    }
}
