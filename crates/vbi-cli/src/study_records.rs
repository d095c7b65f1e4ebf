//! The files of a study's output directory, typed: the manifest `study.json` ([`Manifest`]),
//! the journal `journal.jsonl` (one [`CaseRecord`] per line, [`Journal`], [`read_journal`]).
//!
//! Why a module of its own at the crate root, next to `output` and `input`, and not under
//! `commands::study`: these files are a format shared by two commands. `vbi study` writes them
//! (and `vbi study merge` reads and rewrites them); `vbi report` reads them. Under
//! `commands::study` the report would depend on the study command again, which is the module
//! cycle this module removes: now both commands depend on this module, and it depends on no
//! command (only on `inputs::study`, `output` and the library).
//!
//! The record of a case and its cells ([`CaseRecord`], [`ModeRow`], the column tables) are the
//! library's (`vbi::study::record`), which the Python package shares; its module documentation
//! says why every `f64` of the journal is stored as its exact text.

use std::collections::BTreeMap;
use std::fs::OpenOptions;
use std::io::Write;
use std::path::Path;

use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};

use vbi::study::Shard;

pub use vbi::study::record::{
    CaseRecord, ModeRow, SummaryMetric, MODE_COLUMNS, PARTICIPATION_COLUMNS, SUMMARY_METRICS,
};

use crate::inputs::study::Study;

/// Format of a results directory (`study.json` and the journal's records); results of another
/// format are never mixed. Format 2 added the static-corrected and bending-mode columns; format
/// 3 stores typed records (numbers, not table cells) in the journal; format 4 makes the converged
/// (static-corrected) DAFs the headline columns and names the plain sums `*_paper`; format 5
/// adds the design codes' factors of each case (`design_codes.csv`); format 6 ends each journal
/// line with its checksum (`"sha256"`).
pub const RESULTS_FORMAT: u32 = 6;

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
                .enumerate()
                .map(|(i, (c, s))| ManifestCase {
                    id: c.id.clone(),
                    order: c.order,
                    parameters: study.parameter_cells(i),
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

/// The key that ends every journal line: `,"sha256":"` + 16 hex digits + `"}`.
const CHECKSUM_KEY: &[u8] = b",\"sha256\":\"";
/// Length of the line's tail from [`CHECKSUM_KEY`] on.
const CHECKSUM_TAIL: usize = CHECKSUM_KEY.len() + 16 + 2;

/// The first 8 bytes of the SHA-256 of `record` (a record's JSON), as 16 hex digits.
fn checksum(record: &[u8]) -> String {
    use sha2::{Digest, Sha256};
    Sha256::digest(record)[..8]
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// A record as one journal line, without its newline: the record's JSON object with a last key
/// `sha256`, the checksum of the object without it. A line edited by hand or damaged on the disk
/// fails the checksum ([`parse_journal_line`]).
pub fn journal_line(record: &CaseRecord) -> Result<Vec<u8>> {
    let mut line = serde_json::to_vec(record).context("formatting a case record")?;
    let sum = checksum(&line);
    line.pop(); // the object's closing brace
    line.extend_from_slice(CHECKSUM_KEY);
    line.extend_from_slice(sum.as_bytes());
    line.extend_from_slice(b"\"}");
    Ok(line)
}

/// The record of one journal line, or why the line is refused: no checksum, a checksum that
/// fails (the line was edited or damaged), or not a record of this results format.
fn parse_journal_line(line: &[u8]) -> std::result::Result<CaseRecord, String> {
    let tail_start = line.len().checked_sub(CHECKSUM_TAIL).unwrap_or(usize::MAX);
    let tail = line.get(tail_start..).unwrap_or_default();
    if !(tail.starts_with(CHECKSUM_KEY) && tail.ends_with(b"\"}")) {
        return Err("has no checksum".into());
    }
    let mut record = line[..tail_start].to_vec();
    record.push(b'}');
    let stored = &tail[CHECKSUM_KEY.len()..CHECKSUM_KEY.len() + 16];
    if stored != checksum(&record).as_bytes() {
        return Err("fails its checksum: it was edited or damaged".into());
    }
    serde_json::from_slice(&record)
        .map_err(|_| format!("is not a case record of results format {RESULTS_FORMAT}"))
}

/// What a journal holds: the records of its sound lines, the length in bytes of its complete
/// lines (a last line without its newline is a write cut short by a crash: ignored), and the
/// refused lines, each with its 1-based number and the reason.
#[derive(Debug, Default)]
pub struct JournalContents {
    /// The records of the lines that pass their checksum, in file order.
    pub records: Vec<CaseRecord>,
    /// Bytes of the complete lines.
    pub complete_length: u64,
    /// The refused lines: (line number, reason).
    pub refused: Vec<(usize, String)>,
}

impl JournalContents {
    /// The records, or an error naming the first refused line (for `vbi study merge` and
    /// `vbi report`, which cannot run a case again).
    pub fn sound_records(self, path: &Path) -> Result<Vec<CaseRecord>> {
        match self.refused.first() {
            None => Ok(self.records),
            Some((line, reason)) => bail!(
                "{}:{line}: this journal line {reason}; run `vbi study FILE --out DIR --resume` \
                 on its directory to run the case again",
                path.display()
            ),
        }
    }
}

/// Reads a journal (none: empty). Read it after [`read_manifest`] has checked the directory's
/// results format.
pub fn read_journal(path: &Path) -> Result<JournalContents> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(JournalContents::default()),
        Err(e) => return Err(e).with_context(|| format!("reading {}", path.display())),
    };
    let mut contents = JournalContents::default();
    let mut start = 0;
    while let Some(end) = bytes[start..].iter().position(|&b| b == b'\n') {
        let line_number = contents.records.len() + contents.refused.len() + 1;
        match parse_journal_line(&bytes[start..start + end]) {
            Ok(record) => contents.records.push(record),
            Err(reason) => contents.refused.push((line_number, reason)),
        }
        start += end + 1;
    }
    contents.complete_length = start as u64;
    Ok(contents)
}

/// The journal, open for appending.
pub struct Journal {
    file: std::fs::File,
}

impl Journal {
    /// Opens the journal to resume a study: an incomplete last line is cut off, and refused
    /// lines (see [`JournalContents`]) are dropped with a warning naming each, so that their
    /// cases run again. Dropping rewrites the journal whole from its sound records, whose lines
    /// are byte-identical to the ones read.
    pub fn open(path: &Path, contents: &JournalContents) -> Result<Journal> {
        let mut valid_length = contents.complete_length;
        if !contents.refused.is_empty() {
            for (line, reason) in &contents.refused {
                eprintln!(
                    "warning: {}:{line}: this journal line {reason}; its case runs again",
                    path.display()
                );
            }
            let mut sound = Vec::new();
            for record in &contents.records {
                sound.extend(journal_line(record)?);
                sound.push(b'\n');
            }
            crate::output::write_atomic(path, &sound)?;
            valid_length = sound.len() as u64;
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use vbi::modal::ModeKind;
    use vbi::study::number;
    use vbi::study::record::{ParticipationRow, CASE_METRICS};

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
            daf_u_paper: Some(f64::INFINITY),
            daf_m_paper: Some(f64::NEG_INFINITY),
            warnings: vec!["mode 9 under-resolved".into(), "road \"short\"; 2".into()],
            daf_by_modes: vec![
                ModeRow {
                    modes: 1,
                    daf_u: Some(1.0),
                    daf_m: None,
                    rdm: Some(0.104_940_354_630_094_99),
                    daf_u_paper: Some(-0.0),
                    daf_m_paper: None,
                    rdm_paper: Some(1e300),
                    cm_u_paper: Some(1),
                    cm_m_paper: None,
                    k1_u: Some(1),
                    k2_u: Some(1),
                    k1_m: None,
                    k2_m: Some(1),
                },
                ModeRow {
                    modes: 2,
                    daf_u: None,
                    daf_m: Some(1.004_721_517_217_110_7),
                    rdm: None,
                    daf_u_paper: None,
                    daf_m_paper: Some(0.3),
                    rdm_paper: None,
                    cm_u_paper: Some(2),
                    cm_m_paper: Some(1),
                    k1_u: Some(1),
                    k2_u: Some(2),
                    k1_m: Some(2),
                    k2_m: Some(2),
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
            r.daf_u_paper,
            r.daf_m_paper,
            r.rdm_paper,
        ];
        for m in &r.daf_by_modes {
            floats.extend([
                m.daf_u,
                m.daf_m,
                m.rdm,
                m.daf_u_paper,
                m.daf_m_paper,
                m.rdm_paper,
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
            let back = parse_journal_line(&line).unwrap();
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
        assert_eq!(cell("daf_u_paper"), "inf");
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
                "1".into(),
                "".into(),
                "1".into(),
                "1".into(),
                "".into(),
                "1".into(),
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
        expected.extend(["daf_by_modes", "participation", "sha256"]);
        assert_eq!(keys(&line), expected);
        let mut row = record().daf_by_modes[1].clone();
        row.daf_m = None;
        row.daf_m_paper = None;
        assert_eq!(keys(&serde_json::to_vec(&row).unwrap()), MODE_COLUMNS);
        let row = &record().participation[0];
        assert_eq!(
            keys(&serde_json::to_vec(row).unwrap()),
            PARTICIPATION_COLUMNS
        );
    }

    /// Issue 17, defect 8: a number edited by hand in a journal line flowed into the tables.
    /// Now the line fails its checksum, as do a line of the old format (no checksum) and a
    /// line that is not a record; sound lines around them are kept.
    #[test]
    fn journal_lines_that_fail_their_checksum_are_refused_by_number() {
        let sound = journal_line(&record()).unwrap();
        let edited = String::from_utf8(sound.clone()).unwrap().replacen(
            "\"0.30000000000000004\"",
            "\"0.30000000000000005\"",
            1,
        );
        assert_ne!(edited.as_bytes(), sound.as_slice());
        let old = r#"{"id":"x","error":null,"metrics":["a"],"daf_by_modes":[],"participation":[]}"#;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("journal.jsonl");
        let mut text = Vec::new();
        for line in [
            &sound[..],
            edited.as_bytes(),
            old.as_bytes(),
            b"{}",
            &sound[..],
        ] {
            text.extend_from_slice(line);
            text.push(b'\n');
        }
        text.extend_from_slice(b"{\"id\":"); // a write cut short by a crash
        std::fs::write(&path, &text).unwrap();
        let contents = read_journal(&path).unwrap();
        assert_eq!(contents.records.len(), 2);
        assert_eq!(contents.complete_length, text.len() as u64 - 6);
        let refused: Vec<(usize, &str)> = contents
            .refused
            .iter()
            .map(|(line, reason)| (*line, reason.as_str()))
            .collect();
        assert_eq!(
            refused,
            [
                (2, "fails its checksum: it was edited or damaged"),
                (3, "has no checksum"),
                (4, "has no checksum"),
            ]
        );
        let error = format!("{:#}", contents.sound_records(&path).unwrap_err());
        assert!(error.contains("journal.jsonl:2: this journal line fails its checksum"));
    }
}
