//! Shards of `vbi lifetime` (`--shard I/N`): each writes its directory's `shard.json` last, and
//! `vbi lifetime merge FILE --out DIR SHARD_DIR...` combines the N directories into the single
//! run's outputs, bit for bit ([`vbi::lifetime::merge_shards`]): block_maxima.csv from the
//! shards' static rows and the merged totals, events.csv concatenated, each effect's governing
//! event from the shard that holds it, and the summary, fits, figures and tables as the single
//! run writes them.

use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};

use vbi::lifetime::{BlockMaximum, LifetimeShard, StaticLifetime};
use vbi::study::Shard;

use super::daf_figure::EventPoints;
use super::{dynamics, write_results, write_static_rows, Results};
use crate::commands::OutputFormat;
use crate::input::{InputError, SourceFile};
use crate::inputs::lifetime::{self as lifetime_input, LifetimeFile, ShardFile};
use crate::output::{lock_output_dir, write_atomic_with, write_json};

/// Arguments of `vbi lifetime merge`.
#[derive(Debug, clap::Args)]
pub struct MergeArgs {
    /// The lifetime file the shards ran (`[lifetime]` TOML).
    pub file: PathBuf,
    /// The shards' output directories (all N shards of one run, in any order).
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// Merged output directory.
    #[arg(long)]
    pub out: PathBuf,
    /// Output on stdout.
    #[arg(long, value_enum, default_value_t = OutputFormat::Table)]
    pub format: OutputFormat,
}

/// The name of a shard's file.
const SHARD_FILE: &str = "shard.json";

/// Writes a finished shard's `shard.json` (last: its presence says the shard is finished) and
/// says so.
pub fn write_shard(
    out: &Path,
    lifetime: &LifetimeFile,
    part: LifetimeShard,
    seconds: f64,
) -> Result<()> {
    let (shard, counts, blocks) = (part.shard, part.counts, part.blocks);
    let integrated = part.totals.as_ref().map(|t| t.integrated);
    write_json(&out.join(SHARD_FILE), &ShardFile::new(lifetime, part))?;
    let range = match counts.blocks {
        0 if blocks.end == Some(blocks.first) => "no block (more shards than blocks)".to_string(),
        0 => "no block (past the record's end)".to_string(),
        n => format!("blocks {} to {}", blocks.first, blocks.first + n - 1),
    };
    println!(
        "{}: shard {shard}, {range}: {} trucks in {} events{}, in {seconds:.1} s",
        lifetime.name,
        counts.trucks,
        counts.events,
        integrated.map_or_else(String::new, |n| format!(", {n} integrated with dynamics")),
    );
    println!(
        "wrote {}/{SHARD_FILE}, block_maxima.csv{}; combine the {} shards with: vbi lifetime merge FILE --out DIR SHARD_DIR...",
        out.display(),
        match integrated {
            Some(_) => ", events.csv, governing/",
            None => "",
        },
        shard.count
    );
    Ok(())
}

/// Removes a shard's shard.json before it runs: a shard cut short leaves none.
pub fn start_shard(out: &Path) -> Result<()> {
    match std::fs::remove_file(out.join(SHARD_FILE)) {
        Err(error) if error.kind() != std::io::ErrorKind::NotFound => Err(error.into()),
        _ => Ok(()),
    }
}

/// Whether `out` holds shard `shard` of `lifetime`'s run, finished: its shard.json, of this
/// lifetime file (its input hash) and this shard.
pub fn finished_shard(out: &Path, lifetime: &LifetimeFile, shard: Shard) -> bool {
    read_shard(out)
        .is_ok_and(|file| file.input_hash == lifetime.input_hash && file.part.shard == shard)
}

/// A shard directory's shard.json.
fn read_shard(dir: &Path) -> Result<ShardFile> {
    let path = dir.join(SHARD_FILE);
    let text = std::fs::read_to_string(&path).with_context(|| {
        format!(
            "reading {}: the directory holds no finished shard (a shard writes it last)",
            path.display()
        )
    })?;
    serde_json::from_str(&text).with_context(|| format!("reading {}", path.display()))
}

/// `vbi lifetime merge`.
pub fn run(args: &MergeArgs) -> Result<()> {
    let started = Instant::now();
    let file = SourceFile::read(&args.file)?;
    crate::inputs::expect_kind(&file, "lifetime", "vbi lifetime merge")?;
    let lifetime = lifetime_input::load(&file)?;
    let analysis = lifetime_input::prepare(&file, &lifetime)?;
    let mut shards: Vec<(PathBuf, ShardFile)> = Vec::with_capacity(args.dirs.len());
    for dir in &args.dirs {
        shards.push((dir.clone(), read_shard(dir)?));
    }
    shards.sort_by_key(|(_, file)| file.part.shard.index);
    let files: Vec<ShardFile> = shards.iter().map(|(_, file)| file.clone()).collect();
    let merged = lifetime_input::merge_shards(&lifetime, &analysis, &files)
        .map_err(|message| InputError::command_line("SHARD_DIR", message))?;
    let _lock = lock_output_dir(&args.out)?;
    let mut rows = Vec::new();
    for (dir, file) in &shards {
        read_static_rows(
            &dir.join("block_maxima.csv"),
            &analysis,
            &file.part,
            &mut rows,
        )?;
    }
    let block_maxima = args.out.join("block_maxima.csv");
    let points = match (&lifetime.dynamics, &merged.totals) {
        (Some(_), Some(totals)) => {
            dynamics::write_block_maxima(&block_maxima, &analysis, &rows, totals)?;
            let directories: Vec<&Path> = shards.iter().map(|(dir, _)| dir.as_path()).collect();
            let points = concatenate_events(&args.out, &analysis, &directories)?;
            copy_governing_events(&args.out, &analysis, &directories, &merged)?;
            Some(points)
        }
        _ => {
            write_static_rows(&block_maxima, &analysis, &rows)?;
            None
        }
    };
    let results = Results {
        counts: merged.counts,
        tally: &merged.tally,
        peaks: &merged.peaks,
        totals: merged.totals.as_ref().zip(points.as_ref()),
    };
    eprintln!("merged {} shards into {}", shards.len(), args.out.display());
    write_results(
        &args.out,
        (&lifetime, &analysis),
        results,
        args.format,
        started,
    )
}

/// A shard's block_maxima.csv rows (static), checked against its shard.json: one row per
/// block of the shard and effect, in effect order.
fn read_static_rows(
    path: &Path,
    analysis: &StaticLifetime,
    part: &LifetimeShard,
    rows: &mut Vec<BlockMaximum>,
) -> Result<()> {
    let bad = |line: usize, what: &str| {
        anyhow::anyhow!(
            "{}:{line}: {what}: not the block_maxima.csv of the shard's shard.json",
            path.display()
        )
    };
    let reader = std::io::BufReader::new(
        std::fs::File::open(path).with_context(|| format!("reading {}", path.display()))?,
    );
    let effects = analysis.effects.len();
    let expected = part.counts.blocks as usize * effects;
    let mut count = 0;
    for (index, line) in reader.lines().enumerate().skip(1) {
        let line = line?;
        let fields: Vec<&str> = line.split(',').collect();
        let effect = count % effects.max(1);
        let parsed = match fields.as_slice() {
            [block, station, quantity, value, time, trucks]
                if *station == analysis.effects[effect].station
                    && *quantity == analysis.effects[effect].quantity.name() =>
            {
                (|| {
                    Some(BlockMaximum {
                        block: block.parse().ok()?,
                        effect,
                        value: value.parse().ok()?,
                        time: time.parse().ok()?,
                        trucks: trucks.parse().ok()?,
                    })
                })()
            }
            _ => None,
        };
        let row = parsed.ok_or_else(|| bad(index + 1, "an unexpected row"))?;
        let block = (row.block.checked_sub(part.blocks.first)).map(|b| b as usize);
        if block.and_then(|b| part.static_maxima[effect].get(b)) != Some(&row.value) {
            return Err(bad(index + 1, "a block maximum"));
        }
        rows.push(row);
        count += 1;
    }
    if count != expected {
        return Err(bad(count + 1, &format!("{count} rows, not {expected}")));
    }
    Ok(())
}

/// The shards' events.csv concatenated into `out`'s (their rows are the integrated events in
/// the record's order), and the figure's points taken from them as the single run takes them.
fn concatenate_events(
    out: &Path,
    analysis: &StaticLifetime,
    directories: &[&Path],
) -> Result<EventPoints> {
    let mut points = EventPoints::new(analysis.effects.len());
    let mut event: Option<u64> = None;
    let mut loaded: Vec<(usize, f64, f64)> = Vec::new();
    write_atomic_with(&out.join("events.csv"), |csv| {
        let mut header_written = false;
        for dir in directories {
            let path = dir.join("events.csv");
            let reader = std::io::BufReader::new(
                std::fs::File::open(&path)
                    .with_context(|| format!("reading {}", path.display()))?,
            );
            for (index, line) in reader.lines().enumerate() {
                let line = line?;
                if index == 0 {
                    if !header_written {
                        writeln!(csv, "{line}")?;
                        header_written = true;
                    }
                    continue;
                }
                let (number, effect, fixed, total) =
                    event_row(analysis, &line).ok_or_else(|| {
                        anyhow::anyhow!("{}:{}: not a row of events.csv", path.display(), index + 1)
                    })?;
                if event != Some(number) {
                    if let Some(previous) = event {
                        points.add_event(analysis, previous, loaded.drain(..));
                    }
                    event = Some(number);
                }
                loaded.push((effect, fixed, total));
                writeln!(csv, "{line}")?;
            }
        }
        Ok(())
    })?;
    if let Some(previous) = event {
        points.add_event(analysis, previous, loaded.drain(..));
    }
    Ok(points)
}

/// An events.csv row's event number, effect, static extreme and total.
fn event_row(analysis: &StaticLifetime, line: &str) -> Option<(u64, usize, f64, f64)> {
    let fields: Vec<&str> = line.split(',').collect();
    let [event, _, station, quantity, fixed, _, total, _, _] = fields.as_slice() else {
        return None;
    };
    let effect = (analysis.effects.iter())
        .position(|e| e.station == *station && e.quantity.name() == *quantity)?;
    Some((
        event.parse().ok()?,
        effect,
        fixed.parse().ok()?,
        total.parse().ok()?,
    ))
}

/// Each effect's governing event: its directory copied from the shard that holds it.
fn copy_governing_events(
    out: &Path,
    analysis: &StaticLifetime,
    directories: &[&Path],
    merged: &vbi::lifetime::MergedShards,
) -> Result<()> {
    use crate::inputs::lifetime_replay::{governing_directory, safe_directory_name};
    for (effect, governing) in analysis.effects.iter().zip(&merged.governing) {
        let Some((shard, _, _)) = governing else {
            continue;
        };
        let name = governing_directory(effect);
        if !safe_directory_name(&name) {
            continue;
        }
        let from = directories[*shard].join("governing").join(&name);
        let to = out.join("governing").join(&name);
        std::fs::create_dir_all(&to)?;
        let mut entries: Vec<PathBuf> = std::fs::read_dir(&from)
            .with_context(|| format!("reading {}", from.display()))?
            .map(|entry| entry.map(|e| e.path()))
            .collect::<std::io::Result<_>>()?;
        entries.sort();
        for path in entries {
            let text = std::fs::read(&path)?;
            let name = path.file_name().expect("a file in the directory");
            write_atomic_with(&to.join(name), |out| Ok(out.write_all(&text)?))?;
        }
    }
    Ok(())
}
