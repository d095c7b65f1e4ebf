//! `vbi study FILE [--out DIR] [--resume] [--shard I/N] [--threads N] [--list] [--no-figures]`
//! and `vbi study merge --out DIR SHARD_DIR...` (docs/study.md).
//!
//! Output directory:
//! - `study.json`: the manifest (normalised specification and its hash, the shard, every case
//!   of the study with its parameters and seed, the study file's text);
//! - `journal.jsonl`: one line per finished case, appended and flushed as soon as the case ends
//!   (numbers already formatted, so the final tables are the same bytes however the run went);
//! - at the end, sorted by case order: `cases.csv`, `daf_by_modes.csv`, `participation.csv`,
//!   `summary.csv`, `cutoff_modes.csv`, `figures/*.{png,svg}`, and `timing.json`.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::fs::OpenOptions;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use anyhow::{anyhow, bail, Context, Result};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use vbi::analysis::cutoff_mode;
use vbi::modal::{ModeKind, Quantity};
use vbi::study::{mean_participation, statistics, Shard};

use vbi::pipeline::{run_crossing, PreparedBridge, RunResult};

use crate::commands::run::prepare_scenario_bridge;
use crate::input::{InputError, SourceFile};
use crate::inputs::study::{self as study_input, Study, STRUCTURE_FIELDS};
use crate::output::{create_output_dir, number, write_atomic, write_csv, write_json};
use crate::plot::{write_charts, Chart, Series, SeriesStyle};

/// Arguments of `vbi study`.
#[derive(Debug, clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct Args {
    /// `merge`: combine shard directories.
    #[command(subcommand)]
    pub command: Option<StudyCommand>,
    /// Study file (`[study]` TOML). Without it: the built-in quick study
    /// (examples/studies/quick.toml: two paper bridges, 'medium' road, 80 km/h, three samples).
    pub file: Option<PathBuf>,
    /// Output directory (default: `<file stem>-results` in the current directory).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Complete an interrupted run in --out: only the missing cases run. Refused if the study
    /// (or the shard) changed.
    #[arg(long)]
    pub resume: bool,
    /// Run only shard I of N (1 ≤ I ≤ N): the I-th of N contiguous blocks of the case order.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Worker threads (default: RAYON_NUM_THREADS or the number of cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Print the cases (and the shard's block) and stop.
    #[arg(long)]
    pub list: bool,
    /// Skip the figures.
    #[arg(long)]
    pub no_figures: bool,
}

/// Subcommands of `vbi study`.
#[derive(Debug, clap::Subcommand)]
pub enum StudyCommand {
    /// Combine the output directories of the shards of one study into one directory, the same
    /// as a single-process run's.
    Merge(MergeArgs),
}

/// Arguments of `vbi study merge`.
#[derive(Debug, clap::Args)]
pub struct MergeArgs {
    /// Shard output directories (all shards of one study).
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// Merged output directory.
    #[arg(long)]
    pub out: PathBuf,
    /// Skip the figures.
    #[arg(long)]
    pub no_figures: bool,
}

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

/// Format of a results directory (`study.json` and the journal's records). Format 2 added the
/// static-corrected and bending-mode columns; results of another format are never mixed.
pub const RESULTS_FORMAT: u32 = 2;

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
    fn of(study: &Study, shard: Option<Shard>) -> Manifest {
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

    fn shard(&self) -> Result<Shard> {
        Ok(match &self.shard {
            Some(s) => s.parse()?,
            None => Shard::WHOLE,
        })
    }

    /// The cases of this directory (its shard), in order.
    fn own_cases(&self) -> Result<&[ManifestCase]> {
        let range = self.shard()?.range(self.cases.len());
        Ok(&self.cases[range])
    }

    fn field_index(&self, field: &str) -> Option<usize> {
        self.fields.iter().position(|f| f == field)
    }
}

/// One finished case: a line of `journal.jsonl`. Numbers are kept as the text written to the
/// CSV files (`{}` formatting: shortest round-trip), so the tables never depend on a re-parse.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Record {
    /// Case identifier.
    pub id: String,
    /// Why the case failed, if it did (the metrics are then empty).
    pub error: Option<String>,
    /// Cells of the metric columns ([`METRICS`]).
    pub metrics: Vec<String>,
    /// Rows `modes, daf_u, daf_m, rdm, daf_u_corrected, daf_m_corrected, rdm_corrected`.
    pub daf_by_modes: Vec<Vec<String>>,
    /// Rows `mode, frequency_hz, mps_u, mps_m, kind`.
    pub participation: Vec<Vec<String>>,
}

/// Metric columns of `cases.csv`, after the case id, parameters, sample and seed.
pub const METRICS: [&str; 31] = [
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
    // The solver's warnings (under-resolved modes or road, unsettled tyre contact), "; "-joined.
    "warnings",
];

/// Metrics summarised over samples in `summary.csv`.
pub const SUMMARY_METRICS: [&str; 12] = [
    "daf_u",
    "daf_m",
    "rdm",
    "cm_u",
    "cm_m",
    "k1_u",
    "k2_u",
    "k1_m",
    "k2_m",
    "daf_u_corrected",
    "daf_m_corrected",
    "rdm_corrected",
];

fn metric(name: &str) -> usize {
    METRICS
        .iter()
        .position(|m| *m == name)
        .expect("a known metric")
}

fn opt(value: Option<f64>) -> String {
    value.map(number).unwrap_or_default()
}

fn opt_index(value: Option<usize>) -> String {
    value.map(|v| v.to_string()).unwrap_or_default()
}

/// The record of a finished crossing.
pub fn record_of(id: &str, bridge: &PreparedBridge, result: &RunResult) -> Record {
    let report = &result.report;
    let basis = &bridge.basis;
    let station = report
        .rdm_station
        .as_ref()
        .and_then(|name| basis.stations.iter().position(|s| &s.name == name));
    let u = station.and_then(|s| report.entry(s, Quantity::Deflection));
    let m = station.and_then(|s| report.entry(s, Quantity::BendingMoment));
    let deck = &report.deck_participation;
    let metrics = vec![
        report.rdm_station.clone().unwrap_or_default(),
        opt(u.and_then(|e| e.daf)),
        opt(m.and_then(|e| e.daf)),
        opt(report.rdm),
        opt_index(u.and_then(|e| e.convergence_mode)),
        opt_index(m.and_then(|e| e.convergence_mode)),
        opt_index(deck.deflection_k1),
        opt_index(deck.deflection_k2),
        opt_index(deck.moment_k1),
        opt_index(deck.moment_k2),
        opt_index(u.and_then(|e| e.cutoff_k1)),
        opt_index(u.and_then(|e| e.cutoff_k2)),
        opt_index(m.and_then(|e| e.cutoff_k1)),
        opt_index(m.and_then(|e| e.cutoff_k2)),
        opt(u.map(|e| e.static_max)),
        opt(u.map(|e| e.dynamic_max)),
        opt(m.map(|e| e.static_max)),
        opt(m.map(|e| e.dynamic_max)),
        opt(basis.modes.first().map(|m| m.frequency_hz())),
        basis.mode_count().to_string(),
        report.contact_losses.len().to_string(),
        opt(u.and_then(|e| e.corrected_daf)),
        opt(m.and_then(|e| e.corrected_daf)),
        opt(report.corrected_rdm),
        opt_index(u.and_then(|e| e.corrected_convergence_mode)),
        opt_index(m.and_then(|e| e.corrected_convergence_mode)),
        opt_index(deck.vertical_bending.deflection_k1),
        opt_index(deck.vertical_bending.deflection_k2),
        opt_index(deck.vertical_bending.moment_k1),
        opt_index(deck.vertical_bending.moment_k2),
        report
            .warnings
            .iter()
            .map(|w| w.to_string())
            .collect::<Vec<_>>()
            .join("; "),
    ];
    let n = basis.mode_count();
    let daf_by_modes = (0..n)
        .map(|k| {
            vec![
                (k + 1).to_string(),
                opt(u.and_then(|e| e.daf_by_modes.get(k).copied())),
                opt(m.and_then(|e| e.daf_by_modes.get(k).copied())),
                opt(report.rdm_by_modes.get(k).copied().flatten()),
                opt(u.and_then(|e| e.corrected_daf_by_modes.get(k).copied())),
                opt(m.and_then(|e| e.corrected_daf_by_modes.get(k).copied())),
                opt(report.corrected_rdm_by_modes.get(k).copied().flatten()),
            ]
        })
        .collect();
    let participation = (0..n)
        .map(|k| {
            vec![
                (k + 1).to_string(),
                number(basis.modes[k].frequency_hz()),
                opt(deck.deflection.get(k).copied()),
                opt(deck.moment.get(k).copied()),
                basis.modes[k].kind.name().to_string(),
            ]
        })
        .collect();
    Record {
        id: id.to_string(),
        error: None,
        metrics,
        daf_by_modes,
        participation,
    }
}

fn failed(id: &str, error: String) -> Record {
    Record {
        id: id.to_string(),
        error: Some(error),
        metrics: vec![String::new(); METRICS.len()],
        daf_by_modes: Vec::new(),
        participation: Vec::new(),
    }
}

/// Reads a journal: the records of its complete lines, and the length of those lines in
/// bytes (a last line without its newline is a write cut short by a crash: ignored).
pub fn read_journal(path: &Path) -> Result<(Vec<Record>, u64)> {
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
        let record: Record = serde_json::from_slice(line).with_context(|| {
            format!(
                "{}: line {line_number} is not a case record (the journal is damaged)",
                path.display()
            )
        })?;
        if record.metrics.len() != METRICS.len() {
            bail!(
                "{}: line {line_number} has {} metric cells where this vbi writes {}: the journal \
                 comes from another version",
                path.display(),
                record.metrics.len(),
                METRICS.len()
            );
        }
        records.push(record);
        valid += end + 1;
    }
    Ok((records, valid as u64))
}

/// The journal, open for appending.
struct Journal {
    file: std::fs::File,
}

impl Journal {
    /// Opens the journal, cutting off an incomplete last line.
    fn open(path: &Path, valid_length: u64) -> Result<Journal> {
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
    fn append(&mut self, record: &Record) -> Result<()> {
        let mut line = serde_json::to_vec(record)?;
        line.push(b'\n');
        self.file.write_all(&line)?;
        self.file.flush()?;
        self.file.sync_data()?;
        Ok(())
    }
}

fn read_manifest(dir: &Path) -> Result<Option<Manifest>> {
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

fn shorten(text: &str) -> String {
    if text.chars().count() > 70 {
        format!("{}…", text.chars().take(70).collect::<String>())
    } else {
        text.to_string()
    }
}

/// What differs between two normalised specifications, one line per key.
pub fn spec_changes(old: &BTreeMap<String, String>, new: &BTreeMap<String, String>) -> Vec<String> {
    let mut changes = Vec::new();
    for (k, v) in old {
        match new.get(k) {
            None => changes.push(format!("{k}: removed (was {})", shorten(v))),
            Some(w) if w != v => changes.push(format!("{k}: {} → {}", shorten(v), shorten(w))),
            _ => {}
        }
    }
    for (k, w) in new {
        if !old.contains_key(k) {
            changes.push(format!("{k}: added ({})", shorten(w)));
        }
    }
    changes
}

/// The study run when no file is given: the repository's quick subset of the paper's study.
const BUILT_IN_STUDY: &str = include_str!("../../../../examples/studies/quick.toml");

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    if let Some(StudyCommand::Merge(merge_args)) = &args.command {
        return merge(merge_args);
    }
    let built_in = PathBuf::from("quick.toml");
    let path = args.file.as_ref().unwrap_or(&built_in);
    let shard = args
        .shard
        .as_deref()
        .map(|s| {
            s.parse::<Shard>()
                .map_err(|e| InputError::command_line("--shard", e.to_string()))
        })
        .transpose()?;
    if args.threads == Some(0) {
        return Err(
            InputError::command_line("--threads", "0 is not allowed; expected at least 1").into(),
        );
    }
    let file = match &args.file {
        Some(path) => SourceFile::read(path)?,
        None => SourceFile::from_text(built_in.clone(), BUILT_IN_STUDY.to_string()),
    };
    let study = study_input::load(&file)?;
    let manifest = Manifest::of(&study, shard);
    let own = manifest.own_cases()?.to_vec();
    if args.list {
        println!(
            "{}: {} cases ({} in this shard)",
            study.name,
            manifest.cases.len(),
            own.len()
        );
        println!(
            "base scenario: {}, {}",
            study.base.bridge_label, study.base.vehicle.name
        );
        println!("case\t{}\tsample\tseed", manifest.fields.join("\t"));
        for c in &own {
            println!(
                "{}\t{}\t{}\t{}",
                c.id,
                c.parameters.join("\t"),
                c.sample,
                c.seed
            );
        }
        return Ok(());
    }
    let out = args.out.clone().unwrap_or_else(|| {
        PathBuf::from(format!(
            "{}-results",
            path.file_stem()
                .map(|s| s.to_string_lossy().to_string())
                .unwrap_or_else(|| "study".into())
        ))
    });
    let journal_path = out.join("journal.jsonl");
    match read_manifest(&out)? {
        Some(old) => {
            if !args.resume {
                return Err(InputError::command_line(
                    "--out",
                    format!(
                        "{} already holds a study's results; pass --resume to complete them, or \
                         choose another --out",
                        out.display()
                    ),
                )
                .into());
            }
            let mut changes = spec_changes(&old.spec, &manifest.spec);
            if old.shard != manifest.shard {
                changes.push(format!(
                    "shard: {} → {}",
                    old.shard.as_deref().unwrap_or("none"),
                    manifest.shard.as_deref().unwrap_or("none")
                ));
            }
            if !changes.is_empty() || old.study_hash != manifest.study_hash {
                return Err(InputError::command_line(
                    "--resume",
                    format!(
                        "the study changed since {} was started; refusing to mix results. \
                         Changes:\n  {}\nRun it into a new --out directory instead.",
                        out.display(),
                        changes.join("\n  ")
                    ),
                )
                .into());
            }
        }
        None => {
            if journal_path.exists() {
                bail!(
                    "{} holds a journal but no study.json; refusing to guess what it belongs to",
                    out.display()
                );
            }
            create_output_dir(&out)?;
            write_json(&out.join("study.json"), &manifest)?;
        }
    }
    let (mut records, valid) = read_journal(&journal_path)?;
    let own_ids: HashSet<&str> = own.iter().map(|c| c.id.as_str()).collect();
    let done: HashSet<String> = records.iter().map(|r| r.id.clone()).collect();
    if let Some(stray) = records.iter().find(|r| !own_ids.contains(r.id.as_str())) {
        bail!(
            "{} holds case {} that is not in this study/shard; the directory was changed by hand",
            journal_path.display(),
            stray.id
        );
    }
    let index_of: HashMap<&str, usize> = study
        .cases
        .iter()
        .enumerate()
        .map(|(i, c)| (c.id.as_str(), i))
        .collect();
    let remaining: Vec<usize> = own
        .iter()
        .filter(|c| !done.contains(&c.id))
        .map(|c| index_of[c.id.as_str()])
        .collect();

    // Group by bridge analysis, in case order.
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    for &i in &remaining {
        let key = &study.bridge_keys[i];
        match groups.iter_mut().find(|(k, _)| k == key) {
            Some((_, list)) => list.push(i),
            None => groups.push((key.clone(), vec![i])),
        }
    }

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .context("starting the worker threads")?;
    let threads = pool.current_num_threads();
    let bar = progress_bar(remaining.len() as u64);
    let journal = Mutex::new(Journal::open(&journal_path, valid)?);
    let new_records = Mutex::new(Vec::new());
    let io_error: Mutex<Option<anyhow::Error>> = Mutex::new(None);
    let stop = AtomicBool::new(false);
    let started = Instant::now();
    pool.install(|| {
        groups.par_iter().for_each(|(_, cases)| {
            if stop.load(Ordering::Relaxed) {
                return;
            }
            let analysis = prepare_scenario_bridge(&study.scenarios[cases[0]]);
            cases.par_iter().for_each(|&i| {
                if stop.load(Ordering::Relaxed) {
                    return;
                }
                let id = &study.cases[i].id;
                let record = match &analysis {
                    Ok(a) => match run_crossing(a, &study.scenarios[i]) {
                        Ok(result) => record_of(id, a, &result),
                        Err(e) => failed(id, format!("{:#}", anyhow::Error::from(e))),
                    },
                    Err(e) => failed(id, format!("bridge analysis: {e:#}")),
                };
                let written = journal
                    .lock()
                    .map_err(|_| anyhow!("journal lock poisoned"))
                    .and_then(|mut j| j.append(&record));
                match written {
                    Ok(()) => {
                        new_records.lock().expect("not poisoned").push(record);
                        bar.inc(1);
                    }
                    Err(e) => {
                        stop.store(true, Ordering::Relaxed);
                        io_error
                            .lock()
                            .expect("not poisoned")
                            .get_or_insert(e.context("appending to the journal"));
                    }
                }
            });
        });
    });
    bar.finish_and_clear();
    let wall = started.elapsed().as_secs_f64();
    if let Some(e) = io_error.into_inner().expect("not poisoned") {
        return Err(e);
    }
    let ran = new_records.into_inner().expect("not poisoned");
    let ran_count = ran.len();
    records.extend(ran);
    let failures = finalise(
        &out,
        &manifest,
        &records,
        !args.no_figures && shard.is_none(),
    )?;
    let timing = Timing {
        cases_run: ran_count,
        cases_already_done: own.len() - remaining.len(),
        bridge_analyses: groups.len(),
        threads,
        wall_s: wall,
        crossings_per_s: ran_count as f64 / wall.max(1e-9),
        crossings_per_s_per_thread: ran_count as f64 / wall.max(1e-9) / threads as f64,
    };
    write_json(&out.join("timing.json"), &timing)?;
    println!(
        "{}: {} cases run, {} already done, {} bridge analyses, {:.1} s on {} threads \
         ({:.2} crossings/s, {:.2} per thread); results in {}",
        study.name,
        timing.cases_run,
        timing.cases_already_done,
        timing.bridge_analyses,
        wall,
        threads,
        timing.crossings_per_s,
        timing.crossings_per_s_per_thread,
        out.display()
    );
    // A whole study (not a shard) ends with its HTML report, so one command gives everything.
    if shard.is_none() && !args.no_figures {
        super::report::run(&super::report::Args {
            dir: out.clone(),
            out: None,
        })?;
    }
    let warned = records
        .iter()
        .filter(|r| {
            r.metrics
                .get(metric("warnings"))
                .is_some_and(|w| !w.is_empty())
        })
        .count();
    if warned > 0 {
        eprintln!(
            "warning: {warned} case(s) have solver warnings; see the `warnings` column of {}",
            out.join("cases.csv").display()
        );
    }
    if failures > 0 {
        bail!(
            "{failures} case(s) failed; their messages are in the `error` column of {}",
            out.join("cases.csv").display()
        );
    }
    Ok(())
}

/// `timing.json`: wall-clock figures of the last invocation (not part of the results).
#[derive(Debug, Serialize)]
struct Timing {
    cases_run: usize,
    cases_already_done: usize,
    bridge_analyses: usize,
    threads: usize,
    wall_s: f64,
    crossings_per_s: f64,
    crossings_per_s_per_thread: f64,
}

fn progress_bar(total: u64) -> indicatif::ProgressBar {
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(total);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{bar:40} {pos}/{len} cases  {per_sec}  elapsed {elapsed}  ETA {eta}",
    ) {
        bar.set_style(style);
    }
    bar
}

/// `vbi study merge`.
fn merge(args: &MergeArgs) -> Result<()> {
    let mut manifests = Vec::new();
    for dir in &args.dirs {
        let m =
            read_manifest(dir)?.ok_or_else(|| anyhow!("{} holds no study.json", dir.display()))?;
        manifests.push(m);
    }
    let first = &manifests[0];
    for (m, dir) in manifests.iter().zip(&args.dirs).skip(1) {
        if m.study_hash != first.study_hash {
            let changes = spec_changes(&first.spec, &m.spec);
            return Err(InputError::command_line(
                "DIR",
                format!(
                    "{} and {} hold different studies:\n  {}",
                    args.dirs[0].display(),
                    dir.display(),
                    changes.join("\n  ")
                ),
            )
            .into());
        }
    }
    let mut records: Vec<Record> = Vec::new();
    let mut seen: HashMap<String, usize> = HashMap::new();
    for dir in &args.dirs {
        let (shard_records, _) = read_journal(&dir.join("journal.jsonl"))?;
        for r in shard_records {
            match seen.get(&r.id) {
                Some(&j) if records[j] == r => {}
                Some(_) => bail!(
                    "case {} appears twice with different results (in {})",
                    r.id,
                    dir.display()
                ),
                None => {
                    seen.insert(r.id.clone(), records.len());
                    records.push(r);
                }
            }
        }
    }
    let mut manifest = first.clone();
    manifest.shard = None;
    let missing = manifest
        .cases
        .iter()
        .filter(|c| !seen.contains_key(&c.id))
        .count();
    if missing > 0 {
        bail!(
            "{missing} of {} cases are missing from the shards given; run or resume the \
             missing shards first",
            manifest.cases.len()
        );
    }
    create_output_dir(&args.out)?;
    write_json(&args.out.join("study.json"), &manifest)?;
    let mut journal = Vec::new();
    let order: HashMap<&str, usize> = manifest
        .cases
        .iter()
        .map(|c| (c.id.as_str(), c.order))
        .collect();
    let mut sorted: Vec<&Record> = records.iter().collect();
    sorted.sort_by_key(|r| order.get(r.id.as_str()).copied().unwrap_or(usize::MAX));
    for r in &sorted {
        journal.extend(serde_json::to_vec(r)?);
        journal.push(b'\n');
    }
    write_atomic(&args.out.join("journal.jsonl"), &journal)?;
    let failures = finalise(&args.out, &manifest, &records, !args.no_figures)?;
    println!(
        "merged {} shard directories: {} cases into {}",
        args.dirs.len(),
        records.len(),
        args.out.display()
    );
    if failures > 0 {
        bail!("{failures} case(s) failed; see the `error` column of cases.csv");
    }
    Ok(())
}

/// Numbers of a finished case, parsed back from its cells for statistics and figures.
struct CaseData<'a> {
    case: &'a ManifestCase,
    record: &'a Record,
    /// DAF_u, DAF_M, RDM, then the static-corrected three, for K = 1…N.
    by_modes: Vec<[Option<f64>; 6]>,
    mps_u: Vec<f64>,
    mps_m: Vec<f64>,
    /// Whether each mode is a vertical bending mode.
    bending: Vec<bool>,
}

fn parse(cell: &str) -> Option<f64> {
    cell.parse().ok()
}

impl CaseData<'_> {
    fn metric(&self, name: &str) -> Option<f64> {
        self.record
            .metrics
            .get(metric(name))
            .and_then(|cell| parse(cell))
    }
}

/// Writes the tables (and figures) of the directory's cases; returns the number of failed cases.
fn finalise(dir: &Path, manifest: &Manifest, records: &[Record], figures: bool) -> Result<usize> {
    let by_id: HashMap<&str, &Record> = records.iter().map(|r| (r.id.as_str(), r)).collect();
    let cases = manifest.own_cases()?;
    let mut case_rows = Vec::new();
    let mut mode_rows = Vec::new();
    let mut participation_rows = Vec::new();
    let mut data = Vec::new();
    let mut failures = 0;
    for c in cases {
        let r = by_id
            .get(c.id.as_str())
            .ok_or_else(|| anyhow!("case {} has no result", c.id))?;
        let mut row = vec![c.id.clone()];
        row.extend(c.parameters.iter().cloned());
        row.push(c.sample.to_string());
        row.push(c.seed.to_string());
        row.extend(r.metrics.iter().cloned());
        row.push(r.error.clone().unwrap_or_default());
        case_rows.push(row);
        if r.error.is_some() {
            failures += 1;
            continue;
        }
        for m in &r.daf_by_modes {
            let mut row = vec![c.id.clone()];
            row.extend(m.iter().cloned());
            mode_rows.push(row);
        }
        for p in &r.participation {
            let mut row = vec![c.id.clone()];
            row.extend(p.iter().cloned());
            participation_rows.push(row);
        }
        data.push(CaseData {
            case: c,
            record: r,
            by_modes: r
                .daf_by_modes
                .iter()
                .map(|m| std::array::from_fn(|q| m.get(q + 1).and_then(|c| parse(c))))
                .collect(),
            mps_u: r
                .participation
                .iter()
                .map(|p| parse(&p[2]).unwrap_or(0.0))
                .collect(),
            mps_m: r
                .participation
                .iter()
                .map(|p| parse(&p[3]).unwrap_or(0.0))
                .collect(),
            bending: r
                .participation
                .iter()
                .map(|p| {
                    p.get(4)
                        .is_some_and(|k| k == ModeKind::VerticalBending.name())
                })
                .collect(),
        });
    }
    let mut header: Vec<&str> = vec!["case"];
    header.extend(manifest.fields.iter().map(String::as_str));
    header.extend(["sample", "seed"]);
    header.extend(METRICS);
    header.push("error");
    write_csv(&dir.join("cases.csv"), &header, &case_rows)?;
    write_csv(
        &dir.join("daf_by_modes.csv"),
        &[
            "case",
            "modes",
            "daf_u",
            "daf_m",
            "rdm",
            "daf_u_corrected",
            "daf_m_corrected",
            "rdm_corrected",
        ],
        &mode_rows,
    )?;
    write_csv(
        &dir.join("participation.csv"),
        &["case", "mode", "frequency_hz", "mps_u", "mps_m", "kind"],
        &participation_rows,
    )?;

    // summary.csv: per parameter group, over the samples.
    let mut groups: Vec<(Vec<String>, Vec<&CaseData>)> = Vec::new();
    for d in &data {
        match groups.iter_mut().find(|(k, _)| *k == d.case.parameters) {
            Some((_, list)) => list.push(d),
            None => groups.push((d.case.parameters.clone(), vec![d])),
        }
    }
    let mut rows = Vec::new();
    for (params, list) in &groups {
        for name in SUMMARY_METRICS {
            let values: Vec<f64> = list.iter().filter_map(|d| d.metric(name)).collect();
            let mut row = params.clone();
            row.push(name.to_string());
            match statistics(&values) {
                Ok(s) => row.extend([
                    s.count.to_string(),
                    number(s.mean),
                    number(s.std),
                    number(s.min),
                    number(s.max),
                    number(s.p95),
                ]),
                Err(_) => {
                    row.push("0".into());
                    row.extend(std::iter::repeat_n(String::new(), 5));
                }
            }
            rows.push(row);
        }
    }
    let mut header: Vec<&str> = manifest.fields.iter().map(String::as_str).collect();
    header.extend(["metric", "count", "mean", "std", "min", "max", "p95"]);
    write_csv(&dir.join("summary.csv"), &header, &rows)?;

    // cutoff_modes.csv: Table 2 of the paper, per span count (or per bridge).
    let rows = cutoff_table(manifest, &data);
    write_csv(
        &dir.join("cutoff_modes.csv"),
        &[
            "group",
            "cases",
            "k1_u",
            "k2_u",
            "k1_m",
            "k2_m",
            "k1_u_range",
            "k2_u_range",
            "k1_m_range",
            "k2_m_range",
            "k1_u_bending",
            "k2_u_bending",
            "k1_m_bending",
            "k2_m_bending",
        ],
        &rows,
    )?;
    if figures {
        draw_figures(dir, manifest, &data)?;
    }
    Ok(failures)
}

/// The bridge-type label of a case: its structure fields (span count × length, or bridge).
fn structure_label(manifest: &Manifest, case: &ManifestCase, skip: &[&str]) -> String {
    let value = |f: &str| {
        manifest
            .field_index(f)
            .map(|i| case.parameters[i].clone())
            .filter(|v| !v.is_empty())
    };
    let n = value("span_count").filter(|_| !skip.contains(&"span_count"));
    let l = value("span_length_m").filter(|_| !skip.contains(&"span_length_m"));
    let b = value("bridge").filter(|_| !skip.contains(&"bridge"));
    let mut parts = Vec::new();
    if let Some(b) = b {
        parts.push(b);
    }
    match (n, l) {
        (Some(n), Some(l)) => parts.push(format!("{n}×{l} m")),
        (Some(n), None) => parts.push(format!("{n} spans")),
        (None, Some(l)) => parts.push(format!("{l} m spans")),
        (None, None) => {}
    }
    if parts.is_empty() {
        "all cases".into()
    } else {
        parts.join(", ")
    }
}

fn range_text(values: &[f64]) -> String {
    if values.is_empty() {
        return String::new();
    }
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if lo == hi {
        format!("{lo}")
    } else {
        format!("{lo}-{hi}")
    }
}

/// Rows of `cutoff_modes.csv`: K1, K2 of the mean deck participation (Eq. 30) of every case of
/// a group (the paper averages the cases of each bridge, Fig. 25, then reads Table 2), and
/// the range of the per-case values.
fn cutoff_table(manifest: &Manifest, data: &[CaseData]) -> Vec<Vec<String>> {
    let group_of = |d: &CaseData| -> String {
        match manifest.field_index("span_count") {
            Some(i) if !d.case.parameters[i].is_empty() => {
                format!("{} spans", d.case.parameters[i])
            }
            _ => structure_label(manifest, d.case, &[]),
        }
    };
    let mut groups: Vec<(String, Vec<&CaseData>)> = Vec::new();
    for d in data {
        let g = group_of(d);
        match groups.iter_mut().find(|(k, _)| *k == g) {
            Some((_, list)) => list.push(d),
            None => groups.push((g, vec![d])),
        }
    }
    groups
        .iter()
        .map(|(g, list)| {
            let u: Vec<&[f64]> = list.iter().map(|d| d.mps_u.as_slice()).collect();
            let m: Vec<&[f64]> = list.iter().map(|d| d.mps_m.as_slice()).collect();
            let mu = mean_participation(&u);
            let mm = mean_participation(&m);
            // Among the bending modes: each case's participation restricted to its own vertical
            // bending modes (the k-th bending mode of every bridge aligned), then averaged.
            let bending_mean = |moment: bool| -> Vec<f64> {
                let restricted: Vec<Vec<f64>> = list
                    .iter()
                    .map(|d| {
                        let share = if moment { &d.mps_m } else { &d.mps_u };
                        let kept: Vec<f64> = share
                            .iter()
                            .zip(&d.bending)
                            .filter(|(_, &b)| b)
                            .map(|(&p, _)| p)
                            .collect();
                        // Renormalised over the case's bending modes, so that every case
                        // weighs the same in the group's mean.
                        let total: f64 = kept.iter().sum();
                        if total > 0.0 {
                            kept.iter().map(|p| p / total).collect()
                        } else {
                            kept
                        }
                    })
                    .collect();
                let refs: Vec<&[f64]> = restricted.iter().map(Vec::as_slice).collect();
                mean_participation(&refs)
            };
            let bu = bending_mean(false);
            let bm = bending_mean(true);
            let per_case =
                |name: &str| -> Vec<f64> { list.iter().filter_map(|d| d.metric(name)).collect() };
            vec![
                g.clone(),
                list.len().to_string(),
                opt_index(cutoff_mode(&mu, 0.95)),
                opt_index(cutoff_mode(&mu, 0.99)),
                opt_index(cutoff_mode(&mm, 0.95)),
                opt_index(cutoff_mode(&mm, 0.99)),
                range_text(&per_case("k1_u")),
                range_text(&per_case("k2_u")),
                range_text(&per_case("k1_m")),
                range_text(&per_case("k2_m")),
                opt_index(cutoff_mode(&bu, 0.95)),
                opt_index(cutoff_mode(&bu, 0.99)),
                opt_index(cutoff_mode(&bm, 0.95)),
                opt_index(cutoff_mode(&bm, 0.99)),
            ]
        })
        .collect()
}

fn value_of<'a>(manifest: &Manifest, case: &'a ManifestCase, field: &str) -> Option<&'a str> {
    manifest
        .field_index(field)
        .map(|i| case.parameters[i].as_str())
}

/// True when every axis outside `free` stands at its reference value.
fn at_reference(manifest: &Manifest, case: &ManifestCase, free: &[&str]) -> bool {
    manifest.axes.iter().all(|(field, _)| {
        free.contains(&field.as_str())
            || manifest.reference.get(field).map(String::as_str) == value_of(manifest, case, field)
    })
}

fn axis_label(field: &str, value: &str) -> String {
    match field {
        "speed_kmh" => format!("{value} km/h"),
        "span_length_m" => format!("{value} m spans"),
        "span_count" => format!("{value} spans"),
        "damping_ratio" => format!("ζ = {value}"),
        "lateral_position_m" => format!("y = {value} m"),
        "modes" => format!("{value} modes"),
        _ => value.to_string(),
    }
}

/// Element-wise mean over cases of DAF_u(K), DAF_M(K), RDM(K) and of the three static-corrected
/// series (the columns of `CaseData::by_modes`).
fn mean_curves(list: &[&CaseData]) -> [Vec<(f64, f64)>; 6] {
    let n = list.iter().map(|d| d.by_modes.len()).min().unwrap_or(0);
    let mut out: [Vec<(f64, f64)>; 6] = Default::default();
    for (q, curve) in out.iter_mut().enumerate() {
        for k in 0..n {
            let values: Vec<f64> = list.iter().filter_map(|d| d.by_modes[k][q]).collect();
            if !values.is_empty() {
                curve.push((
                    (k + 1) as f64,
                    values.iter().sum::<f64>() / values.len() as f64,
                ));
            }
        }
    }
    out
}

/// The figures' quantities: column of `CaseData::by_modes`, metric stem, axis label. The
/// static-corrected DAF_u is left out: it differs from the plain one by < 1 %.
const QUANTITIES: [(usize, &str, &str); 5] = [
    (0, "daf_u", "deflection DAF_u"),
    (1, "daf_m", "bending-moment DAF_M"),
    (2, "rdm", "RDM = DAF_u / DAF_M"),
    (4, "daf_m_corrected", "static-corrected DAF_M"),
    (5, "rdm_corrected", "static-corrected RDM"),
];

/// The figures of the paper's forms (docs/study.md lists them).
fn draw_figures(dir: &Path, manifest: &Manifest, data: &[CaseData]) -> Result<()> {
    let fig = dir.join("figures");
    create_output_dir(&fig)?;
    let axis_fields: Vec<&str> = manifest.axes.iter().map(|(f, _)| f.as_str()).collect();
    let structure: Vec<&str> = manifest
        .fields
        .iter()
        .map(String::as_str)
        .filter(|f| STRUCTURE_FIELDS.contains(f))
        .collect();
    let both_spans = axis_fields.contains(&"span_count") && axis_fields.contains(&"span_length_m");

    // DAF_u, DAF_M, RDM against the number of modes, one curve per value of an axis
    // (Figs. 11–16 per road class and speed, 18–20 per span length, 22–24 per span count).
    for (field, values) in manifest.axes.iter().filter(|(_, v)| v.len() > 1) {
        let field = field.as_str();
        let (panel_fields, free): (Vec<&str>, Vec<&str>) = if STRUCTURE_FIELDS.contains(&field) {
            if both_spans && field != "bridge" {
                let other = if field == "span_count" {
                    "span_length_m"
                } else {
                    "span_count"
                };
                (vec![other], vec![field, other])
            } else {
                (Vec::new(), vec![field])
            }
        } else {
            let mut free = structure.clone();
            free.push(field);
            (structure.clone(), free)
        };
        let selected: Vec<&CaseData> = data
            .iter()
            .filter(|d| at_reference(manifest, d.case, &free))
            .collect();
        let mut panels: Vec<(String, Vec<&CaseData>)> = Vec::new();
        for d in &selected {
            let label = if panel_fields.is_empty() {
                "".to_string()
            } else {
                let skip: Vec<&str> = STRUCTURE_FIELDS
                    .iter()
                    .copied()
                    .filter(|f| !panel_fields.contains(f))
                    .collect();
                structure_label(manifest, d.case, &skip)
            };
            match panels.iter_mut().find(|(k, _)| *k == label) {
                Some((_, list)) => list.push(d),
                None => panels.push((label, vec![d])),
            }
        }
        if panels.is_empty() {
            continue;
        }
        let fixed: Vec<String> = manifest
            .axes
            .iter()
            .filter(|(f, _)| !free.contains(&f.as_str()))
            .map(|(f, _)| axis_label(f, &manifest.reference[f]))
            .collect();
        for &(q, stem, what) in &QUANTITIES {
            let charts: Vec<Chart> = panels
                .iter()
                .map(|(label, list)| {
                    let series = values
                        .iter()
                        .filter_map(|v| {
                            let of_value: Vec<&CaseData> = list
                                .iter()
                                .copied()
                                .filter(|d| value_of(manifest, d.case, field) == Some(v))
                                .collect();
                            if of_value.is_empty() {
                                return None;
                            }
                            let curves = mean_curves(&of_value);
                            Some(Series::line(axis_label(field, v), curves[q].clone()))
                        })
                        .collect();
                    let mut title = label.clone();
                    if !fixed.is_empty() {
                        if !title.is_empty() {
                            title.push_str(", ");
                        }
                        title.push_str(&fixed.join(", "));
                    }
                    Chart {
                        title: if title.is_empty() {
                            format!("{what} against the number of modes")
                        } else {
                            title
                        },
                        x_label: "number of modes K".into(),
                        y_label: format!("{what} (mean over samples)"),
                        series,
                        ..Chart::default()
                    }
                })
                .collect();
            write_charts(
                &charts,
                charts.len().min(3),
                &fig.join(format!("{stem}_by_modes_per_{field}")),
            )?;
        }
    }

    // DAF and RDM against span length and span number (Figs. 17 and 21).
    for (x_field, series_field) in [
        ("span_length_m", "span_count"),
        ("span_count", "span_length_m"),
    ] {
        let Some((_, _)) = manifest
            .axes
            .iter()
            .find(|(f, v)| f == x_field && v.len() > 1)
        else {
            continue;
        };
        let series_values: Vec<String> = manifest
            .axes
            .iter()
            .find(|(f, _)| f == series_field)
            .map(|(_, v)| v.clone())
            .unwrap_or_else(|| vec![String::new()]);
        let selected: Vec<&CaseData> = data
            .iter()
            .filter(|d| at_reference(manifest, d.case, &[x_field, series_field]))
            .collect();
        let x_values: Vec<String> = manifest
            .axes
            .iter()
            .find(|(f, _)| f == x_field)
            .map(|(_, v)| v.clone())
            .unwrap_or_default();
        let fixed: Vec<String> = manifest
            .axes
            .iter()
            .filter(|(f, _)| f != x_field && f != series_field)
            .map(|(f, _)| axis_label(f, &manifest.reference[f]))
            .collect();
        let charts: Vec<Chart> = QUANTITIES
            .iter()
            .map(|&(_, stem, what)| {
                let series = series_values
                    .iter()
                    .map(|sv| {
                        let points = x_values
                            .iter()
                            .filter_map(|xv| {
                                let values: Vec<f64> = selected
                                    .iter()
                                    .filter(|d| {
                                        value_of(manifest, d.case, x_field) == Some(xv)
                                            && (sv.is_empty()
                                                || value_of(manifest, d.case, series_field)
                                                    == Some(sv))
                                    })
                                    .filter_map(|d| d.metric(stem))
                                    .collect();
                                let x: f64 = xv.parse().ok()?;
                                (!values.is_empty())
                                    .then(|| (x, values.iter().sum::<f64>() / values.len() as f64))
                            })
                            .collect();
                        Series {
                            label: if sv.is_empty() {
                                String::new()
                            } else {
                                axis_label(series_field, sv)
                            },
                            points,
                            style: SeriesStyle::Line,
                        }
                    })
                    .collect();
                Chart {
                    title: if fixed.is_empty() {
                        format!("{what}, mean over samples")
                    } else {
                        format!("{what}, {}", fixed.join(", "))
                    },
                    x_label: if x_field == "span_count" {
                        "number of spans".into()
                    } else {
                        "span length [m]".into()
                    },
                    y_label: what.to_string(),
                    series,
                    ..Chart::default()
                }
            })
            .collect();
        let stem = if x_field == "span_count" {
            "daf_vs_span_count"
        } else {
            "daf_vs_span_length"
        };
        write_charts(&charts, 3, &fig.join(stem))?;
    }

    // Modal participation per bridge type, averaged over its cases (Fig. 25).
    let mut panels: Vec<(String, Vec<&CaseData>)> = Vec::new();
    for d in data {
        let label = structure_label(manifest, d.case, &[]);
        match panels.iter_mut().find(|(k, _)| *k == label) {
            Some((_, list)) => list.push(d),
            None => panels.push((label, vec![d])),
        }
    }
    for (stem, what, pick) in [
        (
            "participation_deflection",
            "deflection",
            (|d: &CaseData| d.mps_u.clone()) as fn(&CaseData) -> Vec<f64>,
        ),
        ("participation_moment", "bending moment", |d: &CaseData| {
            d.mps_m.clone()
        }),
    ] {
        let charts: Vec<Chart> = panels
            .iter()
            .map(|(label, list)| {
                let values: Vec<Vec<f64>> = list.iter().map(|d| pick(d)).collect();
                let refs: Vec<&[f64]> = values.iter().map(Vec::as_slice).collect();
                let mean = mean_participation(&refs);
                Chart {
                    title: format!("{label}: participation, {what} (Eq. 30)"),
                    x_label: "mode".into(),
                    y_label: "MPS_k, mean over cases [-]".into(),
                    series: vec![Series {
                        label: String::new(),
                        points: mean
                            .iter()
                            .take(20)
                            .enumerate()
                            .map(|(k, v)| ((k + 1) as f64, *v))
                            .collect(),
                        style: SeriesStyle::Bars,
                    }],
                    ..Chart::default()
                }
            })
            .collect();
        if !charts.is_empty() {
            write_charts(&charts, charts.len().min(3), &fig.join(stem))?;
        }
    }
    Ok(())
}
