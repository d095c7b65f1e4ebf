//! `vbi study FILE [--out DIR] [--resume] [--shard I/N] [--threads N] [--list] [--no-figures]`
//! and `vbi study merge --out DIR SHARD_DIR...` (docs/study.md).
//!
//! Output directory (its files are typed in [`crate::study_records`]):
//! - `study.json`: the manifest (normalised specification and its hash, the shard, every case
//!   of the study with its parameters and seed, the study file's text);
//! - `journal.jsonl`: one case record per finished case, appended and flushed as soon as the
//!   case ends (every number stored exactly, so the final tables are the same bytes however the
//!   run went);
//! - at the end, sorted by case order: `cases.csv`, `daf_by_modes.csv`, `participation.csv`,
//!   `station_records.csv` (a study with `record`), `summary.csv`, `cutoff_modes.csv`, `figures/*.{png,svg}`, `timing.json`, and for a whole
//!   study with figures its report (`vbi report`).
//!
//! This module calls `commands::report` at the end of a whole study; the report depends only on
//! `study_records`, never on this module, so the dependency runs one way.

use crate::console::outln;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use anyhow::{anyhow, bail, Context, Result};
use rayon::prelude::*;
use serde::Serialize;

use vbi::analysis::cutoff_mode;
use vbi::study::assessment::assess;
use vbi::study::{mean_participation, stable_hash, Shard};

use vbi::crossing::prepare_scenario_bridge;
use vbi::crossing::{integration_batches, Scenario};
use vbi::study::record::{
    case_table_header, case_table_row, per_case_header, station_record_columns, DESIGN_CODE_COLUMNS,
};
use vbi::study::{case_records_with, STUDY_BATCH_SIZE};

use crate::input::{InputError, SourceFile};
use crate::inputs::study::{self as study_input, Study, STRUCTURE_FIELDS};
use crate::output::{create_output_dir, number, write_atomic, write_csv, write_json};
use crate::parquet_table::write_parquet;
use crate::plot::{write_charts, Chart, Series, SeriesStyle};
use crate::progress::Progress;
use crate::study_assessment::{self, FinishedCase};
use crate::study_records::{
    journal_line, read_journal, read_manifest, CaseRecord, Journal, Manifest, ManifestCase,
    ModeRow, SummaryMetric, MODE_COLUMNS, PARTICIPATION_COLUMNS, SUMMARY_METRICS,
};

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
    /// Seconds between progress lines when standard error is not a terminal (a Slurm log, a
    /// pipe); 0 prints a line per case. On a terminal a progress bar is drawn instead.
    #[arg(long, value_name = "SECONDS", default_value_t = crate::progress::DEFAULT_INTERVAL_S)]
    pub progress_interval: f64,
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
    if !(args.progress_interval.is_finite() && args.progress_interval >= 0.0) {
        bail!(
            "--progress-interval {} is not allowed: a number of seconds ≥ 0",
            args.progress_interval
        );
    }
    let (study, shard) = load_study(args)?;
    let manifest = Manifest::of(&study, shard);
    let own = manifest.own_cases()?.to_vec();
    if args.list {
        print_cases(&study, &manifest, &own);
        return Ok(());
    }
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| default_out(args.file.as_deref()));
    let _lock = crate::output::lock_output_dir(&out)?;
    prepare_out(&out, &manifest, args.resume)?;
    let journal_path = out.join("journal.jsonl");
    let mut contents = read_journal(&journal_path)?;
    let remaining = remaining_cases(&study, &own, &contents.records, &journal_path)?;
    let groups = study.bridge_groups(&remaining);
    let journal = Journal::open(&journal_path, &contents)?;
    let mut records = std::mem::take(&mut contents.records);
    // The worker threads run the cases, then the tables' statistics.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .context("starting the worker threads")?;
    let ran = run_cases(&study, &groups, remaining.len(), journal, (args, &pool))?;
    let ran_count = ran.records.len();
    records.extend(ran.records);
    let figures = !args.no_figures && shard.is_none();
    let failures = pool.install(|| finalise(&out, &manifest, &records, figures))?;
    let (threads, wall) = (ran.threads, ran.wall_s);
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
    outln!(
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
    let warned = records.iter().filter(|r| !r.warnings.is_empty()).count();
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

/// The study of the command line (the built-in one without a file) and its shard, checked.
fn load_study(args: &Args) -> Result<(Study, Option<Shard>)> {
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
        None => SourceFile::from_text(PathBuf::from("quick.toml"), BUILT_IN_STUDY.to_string()),
    };
    crate::inputs::expect_kind(&file, "study", "vbi study")?;
    Ok((study_input::load(&file)?, shard))
}

/// `--list`: the cases of the shard.
fn print_cases(study: &Study, manifest: &Manifest, own: &[ManifestCase]) {
    outln!(
        "{}: {} cases ({} in this shard)",
        study.name,
        manifest.cases.len(),
        own.len()
    );
    outln!(
        "base scenario: {}, {}",
        study.base.bridge_label,
        study.base.vehicle.name
    );
    outln!("case\t{}\tsample\tseed", manifest.fields.join("\t"));
    for c in own {
        outln!(
            "{}\t{}\t{}\t{}",
            c.id,
            c.parameters.join("\t"),
            c.sample,
            c.seed
        );
    }
}

/// The default output directory: `<file stem>-results` (`quick-results` for the built-in study).
fn default_out(file: Option<&Path>) -> PathBuf {
    let path = file.unwrap_or(Path::new("quick.toml"));
    PathBuf::from(format!(
        "{}-results",
        path.file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "study".into())
    ))
}

/// Checks that `out` may take this study's results (a new directory, or with `--resume` one of
/// the same study and shard), and writes the manifest of a new one.
fn prepare_out(out: &Path, manifest: &Manifest, resume: bool) -> Result<()> {
    let Some(old) = read_manifest(out)? else {
        if out.join("journal.jsonl").exists() {
            bail!(
                "{} holds a journal but no study.json; refusing to guess what it belongs to",
                out.display()
            );
        }
        create_output_dir(out)?;
        return write_json(&out.join("study.json"), manifest);
    };
    if !resume {
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
    Ok(())
}

/// Indices (into the study's cases) of the shard's cases that the journal does not hold yet.
fn remaining_cases(
    study: &Study,
    own: &[ManifestCase],
    records: &[CaseRecord],
    journal_path: &Path,
) -> Result<Vec<usize>> {
    let own_ids: HashSet<&str> = own.iter().map(|c| c.id.as_str()).collect();
    let done: HashSet<&str> = records.iter().map(|r| r.id.as_str()).collect();
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
    Ok(own
        .iter()
        .filter(|c| !done.contains(c.id.as_str()))
        .map(|c| index_of[c.id.as_str()])
        .collect())
}

/// What [`run_cases`] did.
struct Ran {
    /// The records of the cases run, in the order they finished.
    records: Vec<CaseRecord>,
    /// Worker threads.
    threads: usize,
    /// Wall-clock time [s].
    wall_s: f64,
}

/// Runs the cases of `groups` in parallel (one bridge analysis per group), appending each
/// record to the journal as soon as its case ends.
fn run_cases(
    study: &Study,
    groups: &[(String, Vec<usize>)],
    total: usize,
    journal: Journal,
    (args, pool): (&Args, &rayon::ThreadPool),
) -> Result<Ran> {
    let threads = pool.current_num_threads();
    let bar = Progress::new("cases", total as u64, args.progress_interval);
    let journal = Mutex::new(journal);
    let new_records = Mutex::new(Vec::new());
    let io_error: Mutex<Option<anyhow::Error>> = Mutex::new(None);
    let stop = AtomicBool::new(false);
    let started = Instant::now();
    pool.install(|| {
        groups.par_iter().for_each(|(_, cases)| {
            if stop.load(Ordering::Relaxed) {
                return;
            }
            let bridge = prepare_scenario_bridge(&study.scenarios[cases[0]]);
            let scenarios: Vec<&Scenario> = cases.iter().map(|&i| &study.scenarios[i]).collect();
            let batches = integration_batches(&scenarios, STUDY_BATCH_SIZE);
            batches.par_iter().for_each(|batch| {
                if stop.load(Ordering::Relaxed) {
                    return;
                }
                let batch_cases: Vec<(&str, &Scenario)> = batch
                    .iter()
                    .map(|&b| (study.cases[cases[b]].id.as_str(), scenarios[b]))
                    .collect();
                let records = case_records_with(&batch_cases, &bridge, &study.record);
                for record in records {
                    let written = journal
                        .lock()
                        .map_err(|_| anyhow!("journal lock poisoned"))
                        .and_then(|mut j| j.append(&record));
                    match written {
                        Ok(()) => {
                            new_records.lock().expect("not poisoned").push(record);
                            bar.inc();
                        }
                        Err(e) => {
                            stop.store(true, Ordering::Relaxed);
                            io_error
                                .lock()
                                .expect("not poisoned")
                                .get_or_insert(e.context("appending to the journal"));
                            return;
                        }
                    }
                }
            });
        });
    });
    bar.finish();
    let wall_s = started.elapsed().as_secs_f64();
    if let Some(e) = io_error.into_inner().expect("not poisoned") {
        return Err(e);
    }
    Ok(Ran {
        records: new_records.into_inner().expect("not poisoned"),
        threads,
        wall_s,
    })
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

/// `vbi study merge`.
fn merge(args: &MergeArgs) -> Result<()> {
    let manifests = read_shard_manifests(&args.dirs)?;
    let (records, seen) = read_shard_journals(&args.dirs)?;
    let mut manifest = manifests[0].clone();
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
    let _lock = crate::output::lock_output_dir(&args.out)?;
    write_json(&args.out.join("study.json"), &manifest)?;
    let order: HashMap<&str, usize> = manifest
        .cases
        .iter()
        .map(|c| (c.id.as_str(), c.order))
        .collect();
    let mut sorted: Vec<&CaseRecord> = records.iter().collect();
    sorted.sort_by_key(|r| order.get(r.id.as_str()).copied().unwrap_or(usize::MAX));
    let mut journal = Vec::new();
    for r in &sorted {
        journal.extend(journal_line(r)?);
        journal.push(b'\n');
    }
    write_atomic(&args.out.join("journal.jsonl"), &journal)?;
    let failures = finalise(&args.out, &manifest, &records, !args.no_figures)?;
    outln!(
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

/// The manifests of the shard directories, checked to be of one study.
fn read_shard_manifests(dirs: &[PathBuf]) -> Result<Vec<Manifest>> {
    let mut manifests = Vec::new();
    for dir in dirs {
        let m =
            read_manifest(dir)?.ok_or_else(|| anyhow!("{} holds no study.json", dir.display()))?;
        manifests.push(m);
    }
    let first = &manifests[0];
    for (m, dir) in manifests.iter().zip(dirs).skip(1) {
        if m.study_hash != first.study_hash {
            let changes = spec_changes(&first.spec, &m.spec);
            return Err(InputError::command_line(
                "DIR",
                format!(
                    "{} and {} hold different studies:\n  {}",
                    dirs[0].display(),
                    dir.display(),
                    changes.join("\n  ")
                ),
            )
            .into());
        }
    }
    Ok(manifests)
}

/// The records of the shards' journals, each case once (a case found in two shards must have
/// the same record in both), and the position of each case id among them.
fn read_shard_journals(dirs: &[PathBuf]) -> Result<(Vec<CaseRecord>, HashMap<String, usize>)> {
    let mut records: Vec<CaseRecord> = Vec::new();
    let mut seen: HashMap<String, usize> = HashMap::new();
    for dir in dirs {
        let path = dir.join("journal.jsonl");
        let shard_records = read_journal(&path)?.sound_records(&path)?;
        for r in shard_records {
            match seen.get(&r.id) {
                // Compared as journal lines: exact for every number, NaN included.
                Some(&j) if journal_line(&records[j])? == journal_line(&r)? => {}
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
    Ok((records, seen))
}

/// A finished case of the directory, with its participation unpacked for the statistics and
/// figures.
struct CaseData<'a> {
    case: &'a ManifestCase,
    record: &'a CaseRecord,
    mps_u: Vec<f64>,
    mps_m: Vec<f64>,
    /// Whether each mode is a vertical bending mode.
    bending: Vec<bool>,
}

impl<'a> CaseData<'a> {
    fn new(case: &'a ManifestCase, record: &'a CaseRecord) -> CaseData<'a> {
        CaseData {
            case,
            record,
            mps_u: record.mps_u(),
            mps_m: record.mps_m(),
            bending: record.bending_modes(),
        }
    }
}

/// Writes the tables (and figures) of the directory's cases; returns the number of failed cases.
fn finalise(
    dir: &Path,
    manifest: &Manifest,
    records: &[CaseRecord],
    figures: bool,
) -> Result<usize> {
    let by_id: HashMap<&str, &CaseRecord> = records.iter().map(|r| (r.id.as_str(), r)).collect();
    let cases: Vec<(&ManifestCase, &CaseRecord)> = manifest
        .own_cases()?
        .iter()
        .map(|c| {
            by_id
                .get(c.id.as_str())
                .map(|&r| (c, r))
                .ok_or_else(|| anyhow!("case {} has no result", c.id))
        })
        .collect::<Result<_>>()?;
    // The case tables beside the statistics (both parallel inside).
    let (case_tables, statistics) = rayon::join(
        || write_case_tables(dir, manifest, &cases),
        || write_statistics(dir, manifest, &cases, figures),
    );
    // Both ran to their end: a failure names its file, and says that other tables may be new.
    let beside = "the study's other tables may have been written (each file whole or not at all)";
    match (case_tables, statistics) {
        (Ok(()), Ok(())) => {}
        (Err(e), Ok(())) | (Ok(()), Err(e)) => return Err(e.context(beside)),
        (Err(e), Err(other)) => {
            return Err(e.context(format!("{beside}; also: {other:#}")));
        }
    }
    Ok(cases.iter().filter(|(_, r)| r.error.is_some()).count())
}

/// `summary.csv`, `cutoff_modes.csv`, the assessment tables and (with `figures`) the figures
/// of the finished cases.
fn write_statistics(
    dir: &Path,
    manifest: &Manifest,
    cases: &[(&ManifestCase, &CaseRecord)],
    figures: bool,
) -> Result<()> {
    let data: Vec<CaseData> = cases
        .iter()
        .filter(|(_, r)| r.error.is_none())
        .map(|&(c, r)| CaseData::new(c, r))
        .collect();
    write_summary(dir, manifest, &data)?;
    write_csv(
        &dir.join("cutoff_modes.csv"),
        &CUTOFF_COLUMNS,
        &cutoff_table(manifest, &data),
    )?;
    if figures {
        draw_figures(dir, manifest, &data)?;
    }
    let finished: Vec<FinishedCase> = cases
        .iter()
        .filter(|(_, r)| r.error.is_none())
        .copied()
        .collect();
    study_assessment::write(dir, manifest, &finished, figures)
}

/// `cases.csv`, `daf_by_modes.csv`, `participation.csv`, `design_codes.csv` and (with `record`)
/// `station_records.csv`, in case order. The cases' rows are formatted in parallel, and the
/// files are written in parallel, each whole or not at all (as `write_csv` writes any table).
fn write_case_tables(
    dir: &Path,
    manifest: &Manifest,
    cases: &[(&ManifestCase, &CaseRecord)],
) -> Result<()> {
    type Rows = Vec<Vec<String>>;
    let per_case: Vec<[Rows; 5]> = cases
        .par_iter()
        .map(|&(c, r)| {
            [
                vec![case_table_row(r, &c.parameters, c.sample, c.seed)],
                r.mode_table_rows(),
                r.participation_table_rows(),
                r.design_code_rows(),
                r.station_record_rows(),
            ]
        })
        .collect();
    let mut tables: [Rows; 5] = Default::default();
    for rows in per_case {
        for (table, rows) in tables.iter_mut().zip(rows) {
            table.extend(rows);
        }
    }
    let [case_rows, mode_rows, participation_rows, code_rows, station_rows] = tables;
    let csv = |name: &str, header: Vec<String>, rows: &Rows| {
        let header: Vec<&str> = header.iter().map(String::as_str).collect();
        write_csv(&dir.join(name), &header, rows)
    };
    // The case tables also as Parquet, typed (cases.parquet, daf_by_modes.parquet).
    let parquet = |name: &str, header: Vec<String>, rows: &Rows| {
        let header: Vec<&str> = header.iter().map(String::as_str).collect();
        write_parquet(&dir.join(name), &header, rows)
    };
    let case_header = || case_table_header(&manifest.fields);
    let mut writes: Vec<Box<dyn Fn() -> Result<()> + Sync + '_>> = vec![
        Box::new(|| csv("cases.csv", case_header(), &case_rows)),
        Box::new(|| parquet("cases.parquet", case_header(), &case_rows)),
        Box::new(|| {
            csv(
                "daf_by_modes.csv",
                per_case_header(&MODE_COLUMNS),
                &mode_rows,
            )
        }),
        Box::new(|| {
            parquet(
                "daf_by_modes.parquet",
                per_case_header(&MODE_COLUMNS),
                &mode_rows,
            )
        }),
        Box::new(|| {
            let header = per_case_header(&PARTICIPATION_COLUMNS);
            csv("participation.csv", header, &participation_rows)
        }),
        Box::new(|| {
            csv(
                "design_codes.csv",
                per_case_header(&DESIGN_CODE_COLUMNS),
                &code_rows,
            )
        }),
    ];
    // Only for a study with a `record` (its spec names it), so that the directory of a study
    // without one holds the files it always held.
    if manifest.spec.contains_key("study.record") {
        writes.push(Box::new(|| {
            let header = per_case_header(&station_record_columns());
            csv("station_records.csv", header, &station_rows)
        }));
    }
    // Every file attempted; the first failure in the order above is the one reported, so that
    // the same failure gives the same message whatever the threads.
    let written: Vec<Result<()>> = writes.par_iter().map(|write| write()).collect();
    written.into_iter().collect()
}

/// `summary.csv`: per parameter group, the assessment statistics of [`SUMMARY_METRICS`] over
/// the samples (`vbi::study::assessment::assess`; the bootstrap seeded by the study's hash, the
/// group and the metric, so the table is the same on every run, shard layout and thread count).
fn write_summary(dir: &Path, manifest: &Manifest, data: &[CaseData]) -> Result<()> {
    let mut groups: Vec<(Vec<String>, Vec<&CaseData>)> = Vec::new();
    for d in data {
        match groups.iter_mut().find(|(k, _)| *k == d.case.parameters) {
            Some((_, list)) => list.push(d),
            None => groups.push((d.case.parameters.clone(), vec![d])),
        }
    }
    // Each row's bootstrap has its own seed: the rows are computed in parallel, in order.
    let cells: Vec<(&Vec<String>, &Vec<&CaseData>, &SummaryMetric)> = groups
        .iter()
        .flat_map(|(params, list)| SUMMARY_METRICS.iter().map(move |m| (params, list, m)))
        .collect();
    let rows: Vec<Vec<String>> = cells
        .par_iter()
        .map(|&(params, list, metric)| summary_row(manifest, params, list, metric))
        .collect();
    let mut header: Vec<&str> = manifest.fields.iter().map(String::as_str).collect();
    header.extend(SUMMARY_COLUMNS);
    write_csv(&dir.join("summary.csv"), &header, &rows)
}

/// One row of `summary.csv`: the assessment of `metric` over the cases of one parameter group,
/// its bootstrap seeded by the study, the group and the metric.
fn summary_row(
    manifest: &Manifest,
    params: &[String],
    list: &[&CaseData],
    metric: &SummaryMetric,
) -> Vec<String> {
    let values: Vec<f64> = list
        .iter()
        .filter_map(|d| (metric.value)(d.record))
        .collect();
    let mut row = params.to_vec();
    row.push(metric.name.to_string());
    let key = format!(
        "{}\n{}\n{}",
        manifest.study_hash,
        params.join(","),
        metric.name
    );
    match assess(&values, stable_hash(key.as_bytes())) {
        Ok(a) => row.extend([
            a.count.to_string(),
            number(a.mean),
            number(a.std),
            number(a.min),
            number(a.max),
            number(a.characteristic),
            number(a.standard_error),
            number(a.characteristic_low),
            number(a.characteristic_high),
            number(a.characteristic_normal),
        ]),
        Err(_) => {
            row.push("0".into());
            row.extend(std::iter::repeat_n(
                String::new(),
                SUMMARY_COLUMNS.len() - 2,
            ));
        }
    }
    row
}

/// Columns of `summary.csv` after the group's fields: `p95` is the characteristic value (the
/// 95 % fractile), `p95_low`/`p95_high` its 95 % bootstrap interval, `normal_p95` the
/// normal-theory mean + 1.645 std.
const SUMMARY_COLUMNS: [&str; 11] = [
    "metric",
    "count",
    "mean",
    "std",
    "min",
    "max",
    "p95",
    "standard_error",
    "p95_low",
    "p95_high",
    "normal_p95",
];

/// Columns of `cutoff_modes.csv`.
const CUTOFF_COLUMNS: [&str; 14] = [
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
];

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

fn range_text(values: &[usize]) -> String {
    let (Some(lo), Some(hi)) = (values.iter().min(), values.iter().max()) else {
        return String::new();
    };
    if lo == hi {
        format!("{lo}")
    } else {
        format!("{lo}-{hi}")
    }
}

/// Mean over the cases of their participation restricted to their own vertical bending modes
/// (the k-th bending mode of every bridge aligned); of the moment if `moment`, else of the
/// deflection.
fn bending_mean(list: &[&CaseData], moment: bool) -> Vec<f64> {
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
            // Renormalised over the case's bending modes, so that every case weighs the same
            // in the group's mean.
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
}

/// Rows of `cutoff_modes.csv`: K1, K2 of the mean deck participation (Eq. 30) of every case of
/// a group (the paper averages the cases of each bridge, Fig. 25, then reads Table 2), and
/// the range of the per-case values.
fn cutoff_table(manifest: &Manifest, data: &[CaseData]) -> Vec<Vec<String>> {
    let group_of = |d: &CaseData| -> String {
        match manifest.value_of(d.case, "span_count") {
            Some(n) if !n.is_empty() => format!("{n} spans"),
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
    let cutoff = |share: &[f64], level: f64| -> String {
        cutoff_mode(share, level)
            .map(|k| k.to_string())
            .unwrap_or_default()
    };
    groups
        .iter()
        .map(|(g, list)| {
            let u: Vec<&[f64]> = list.iter().map(|d| d.mps_u.as_slice()).collect();
            let m: Vec<&[f64]> = list.iter().map(|d| d.mps_m.as_slice()).collect();
            let mu = mean_participation(&u);
            let mm = mean_participation(&m);
            let bu = bending_mean(list, false);
            let bm = bending_mean(list, true);
            let range = |k: fn(&CaseRecord) -> Option<usize>| -> String {
                let per_case: Vec<usize> = list.iter().filter_map(|d| k(d.record)).collect();
                range_text(&per_case)
            };
            vec![
                g.clone(),
                list.len().to_string(),
                cutoff(&mu, 0.95),
                cutoff(&mu, 0.99),
                cutoff(&mm, 0.95),
                cutoff(&mm, 0.99),
                range(|r| r.k1_u),
                range(|r| r.k2_u),
                range(|r| r.k1_m),
                range(|r| r.k2_m),
                cutoff(&bu, 0.95),
                cutoff(&bu, 0.99),
                cutoff(&bm, 0.95),
                cutoff(&bm, 0.99),
            ]
        })
        .collect()
}

/// True when every axis outside `free` stands at its reference value.
fn at_reference(manifest: &Manifest, case: &ManifestCase, free: &[&str]) -> bool {
    manifest.axes.iter().all(|(field, _)| {
        free.contains(&field.as_str())
            || manifest.reference.get(field).map(String::as_str) == manifest.value_of(case, field)
    })
}

fn axis_label(field: &str, value: &str) -> String {
    match field {
        "speed_kmh" => format!("{value} km/h"),
        "span_length_m" => format!("{value} m spans"),
        "span_count" => format!("{value} spans"),
        "damping_ratio" => format!("ζ = {value}"),
        "damage_factor" => format!("E × {value}"),
        "lateral_position_m" => format!("y = {value} m"),
        "modes" => format!("{value} modes"),
        _ => value.to_string(),
    }
}

/// A quantity of the figures.
struct FigureQuantity {
    /// File stem (the metric's column name).
    stem: &'static str,
    /// Axis label.
    label: &'static str,
    /// Its value with the first K modes.
    by_modes: fn(&ModeRow) -> Option<f64>,
    /// Its value in a case.
    value: fn(&CaseRecord) -> Option<f64>,
}

/// The figures' quantities: the paper's plain partial sums (its Figs. 11–24), then the
/// converged (static-corrected) DAF_M and RDM. The converged DAF_u is left out: it differs from
/// the paper's by < 1 %.
const QUANTITIES: [FigureQuantity; 5] = [
    FigureQuantity {
        stem: "daf_u_paper",
        label: "the paper's deflection DAF_u",
        by_modes: |m| m.daf_u_paper,
        value: |r| r.daf_u_paper,
    },
    FigureQuantity {
        stem: "daf_m_paper",
        label: "the paper's bending-moment DAF_M",
        by_modes: |m| m.daf_m_paper,
        value: |r| r.daf_m_paper,
    },
    FigureQuantity {
        stem: "rdm_paper",
        label: "the paper's RDM = DAF_u / DAF_M",
        by_modes: |m| m.rdm_paper,
        value: |r| r.rdm_paper,
    },
    FigureQuantity {
        stem: "daf_m",
        label: "converged DAF_M",
        by_modes: |m| m.daf_m,
        value: |r| r.daf_m,
    },
    FigureQuantity {
        stem: "rdm",
        label: "converged RDM",
        by_modes: |m| m.rdm,
        value: |r| r.rdm,
    },
];

/// Element-wise mean over cases of a quantity with the first K modes, K = 1…(the fewest modes
/// of the cases).
fn mean_curve(list: &[&CaseData], by_modes: fn(&ModeRow) -> Option<f64>) -> Vec<(f64, f64)> {
    let n = list
        .iter()
        .map(|d| d.record.daf_by_modes.len())
        .min()
        .unwrap_or(0);
    let mut curve = Vec::new();
    for k in 0..n {
        let values: Vec<f64> = list
            .iter()
            .filter_map(|d| by_modes(&d.record.daf_by_modes[k]))
            .collect();
        if !values.is_empty() {
            curve.push((
                (k + 1) as f64,
                values.iter().sum::<f64>() / values.len() as f64,
            ));
        }
    }
    curve
}

/// The figures of the paper's forms (docs/study.md lists them).
fn draw_figures(dir: &Path, manifest: &Manifest, data: &[CaseData]) -> Result<()> {
    let fig = dir.join("figures");
    create_output_dir(&fig)?;
    // DAF_u, DAF_M, RDM against the number of modes, one curve per value of an axis
    // (Figs. 11–16 per road class and speed, 18–20 per span length, 22–24 per span count).
    for (field, values) in manifest.axes.iter().filter(|(_, v)| v.len() > 1) {
        figures_by_modes(&fig, manifest, data, field, values)?;
    }
    // DAF and RDM against span length and span number (Figs. 17 and 21).
    for (x_field, series_field) in [
        ("span_length_m", "span_count"),
        ("span_count", "span_length_m"),
    ] {
        figures_against_spans(&fig, manifest, data, x_field, series_field)?;
    }
    // Modal participation per bridge type, averaged over its cases (Fig. 25).
    figures_of_participation(&fig, manifest, data)
}

/// The panels of the figures against the number of modes per value of `field`: the fields
/// left free (the others at their reference values), and the cases of each panel by label.
fn by_modes_panels<'a, 'd>(
    manifest: &'a Manifest,
    data: &'d [CaseData<'d>],
    field: &'a str,
) -> (Vec<&'a str>, Vec<(String, Vec<&'d CaseData<'d>>)>) {
    let axis_fields: Vec<&str> = manifest.axes.iter().map(|(f, _)| f.as_str()).collect();
    let structure: Vec<&str> = manifest
        .fields
        .iter()
        .map(String::as_str)
        .filter(|f| STRUCTURE_FIELDS.contains(f))
        .collect();
    let both_spans = axis_fields.contains(&"span_count") && axis_fields.contains(&"span_length_m");
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
    let mut panels: Vec<(String, Vec<&CaseData>)> = Vec::new();
    for d in data
        .iter()
        .filter(|d| at_reference(manifest, d.case, &free))
    {
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
    (free, panels)
}

/// DAF_u, DAF_M, RDM (and the static-corrected ones) against the number of modes, one curve
/// per value of the axis `field`.
fn figures_by_modes(
    fig: &Path,
    manifest: &Manifest,
    data: &[CaseData],
    field: &str,
    values: &[String],
) -> Result<()> {
    let (free, panels) = by_modes_panels(manifest, data, field);
    if panels.is_empty() {
        return Ok(());
    }
    let fixed: Vec<String> = manifest
        .axes
        .iter()
        .filter(|(f, _)| !free.contains(&f.as_str()))
        .map(|(f, _)| axis_label(f, &manifest.reference[f]))
        .collect();
    for quantity in &QUANTITIES {
        let what = quantity.label;
        let charts: Vec<Chart> = panels
            .iter()
            .map(|(label, list)| {
                let series = values
                    .iter()
                    .filter_map(|v| {
                        let of_value: Vec<&CaseData> = list
                            .iter()
                            .copied()
                            .filter(|d| manifest.value_of(d.case, field) == Some(v))
                            .collect();
                        if of_value.is_empty() {
                            return None;
                        }
                        let curve = mean_curve(&of_value, quantity.by_modes);
                        Some(Series::line(axis_label(field, v), curve))
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
            &fig.join(format!("{}_by_modes_per_{field}", quantity.stem)),
        )?;
    }
    Ok(())
}

/// DAF and RDM against `x_field` (span length or span count), one series per value of
/// `series_field`; nothing unless `x_field` is an axis with more than one value.
fn figures_against_spans(
    fig: &Path,
    manifest: &Manifest,
    data: &[CaseData],
    x_field: &str,
    series_field: &str,
) -> Result<()> {
    let axis = |field: &str| manifest.axes.iter().find(|(f, _)| f == field);
    let Some((_, x_values)) = axis(x_field).filter(|(_, v)| v.len() > 1) else {
        return Ok(());
    };
    let series_values: Vec<String> = axis(series_field)
        .map(|(_, v)| v.clone())
        .unwrap_or_else(|| vec![String::new()]);
    let selected: Vec<&CaseData> = data
        .iter()
        .filter(|d| at_reference(manifest, d.case, &[x_field, series_field]))
        .collect();
    let fixed: Vec<String> = manifest
        .axes
        .iter()
        .filter(|(f, _)| f != x_field && f != series_field)
        .map(|(f, _)| axis_label(f, &manifest.reference[f]))
        .collect();
    let mean_at = |quantity: &FigureQuantity, xv: &String, sv: &String| -> Option<(f64, f64)> {
        let values: Vec<f64> = selected
            .iter()
            .filter(|d| {
                manifest.value_of(d.case, x_field) == Some(xv)
                    && (sv.is_empty() || manifest.value_of(d.case, series_field) == Some(sv))
            })
            .filter_map(|d| (quantity.value)(d.record))
            .collect();
        let x: f64 = xv.parse().ok()?;
        (!values.is_empty()).then(|| (x, values.iter().sum::<f64>() / values.len() as f64))
    };
    let charts: Vec<Chart> = QUANTITIES
        .iter()
        .map(|quantity| {
            let what = quantity.label;
            let series = series_values
                .iter()
                .map(|sv| Series {
                    label: if sv.is_empty() {
                        String::new()
                    } else {
                        axis_label(series_field, sv)
                    },
                    points: x_values
                        .iter()
                        .filter_map(|xv| mean_at(quantity, xv, sv))
                        .collect(),
                    style: SeriesStyle::Line,
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
    Ok(())
}

/// The mean deck participation of each bridge type, deflection and moment (Fig. 25).
fn figures_of_participation(fig: &Path, manifest: &Manifest, data: &[CaseData]) -> Result<()> {
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
