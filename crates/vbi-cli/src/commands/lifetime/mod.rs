//! `vbi lifetime FILE --out DIR`: the block maxima of every station's static load effects under a
//! traffic file (docs/lifetime.md). Reads the file and the traffic, line by line, hands them to
//! [`vbi::lifetime::static_block_maxima`], and writes `DIR/block_maxima.csv` (streamed, one row
//! per block, station and quantity), `DIR/return_levels.csv` (per effect, law and return period:
//! the level with its bootstrap interval and the law's parameters) and `DIR/lifetime.json` (what
//! was run, the counts, and per effect the block maxima's summary and fits), and the return-level
//! plot `DIR/return_levels.png` and `.svg` ([`figure`]).

mod daf_figure;
mod dynamics;
mod fatigue;
mod figure;
mod merge;

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Result;

use vbi::lifetime::{
    BlockMaximaTally, BlockMaximum, EventPeaks, LifetimeCounts, ReturnLevel, StaticLifetime,
};
use vbi::statistics::extreme_value::ExtremeValueModel;
use vbi::study::Shard;

use crate::commands::OutputFormat;
use crate::input::{InputError, SourceFile};
use crate::inputs::lifetime as lifetime_input;
use crate::inputs::traffic_source::TrafficSource;
use crate::output::{lock_output_dir, write_atomic_with, write_json};
use crate::parquet_table::csv_file_as_parquet;
use crate::progress::Progress;

/// Arguments of `vbi lifetime`.
#[derive(Debug, clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct Args {
    /// `merge`: combine the shards' directories.
    #[command(subcommand)]
    pub command: Option<LifetimeCommand>,
    /// Lifetime file (`[lifetime]` TOML).
    pub file: Option<PathBuf>,
    /// Directory for block_maxima.csv, return_levels.csv (and .png, .svg) and lifetime.json.
    #[arg(long, default_value = "lifetime-results")]
    pub out: PathBuf,
    /// Output on stdout.
    #[arg(long, value_enum, default_value_t = OutputFormat::Table)]
    pub format: OutputFormat,
    /// Run only shard I of N (1 ≤ I ≤ N): the I-th of N contiguous ranges of the record's
    /// blocks, and the events that start in them. --out gets the shard's block_maxima.csv
    /// (static), events.csv and governing/ with dynamics, and shard.json; `vbi lifetime merge`
    /// combines the N shards' directories into the single run's outputs.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// With --shard: do nothing if --out holds this shard of this lifetime file, finished
    /// (its shard.json, written last); run it otherwise.
    #[arg(long, requires = "shard")]
    pub resume: bool,
    /// Seconds between progress lines on standard error when it is not a terminal (a job log,
    /// a pipe); 0 prints a line per block. On a terminal a progress bar is drawn instead. The
    /// progress is the traffic file's kB read (or the hours of traffic generated), with the
    /// rate and the time left.
    #[arg(long, value_name = "SECONDS", default_value_t = crate::progress::DEFAULT_INTERVAL_S)]
    pub progress_interval: f64,
}

/// Subcommands of `vbi lifetime`.
#[derive(Debug, clap::Subcommand)]
pub enum LifetimeCommand {
    /// Combine the directories of the N shards of one lifetime run (`--shard I/N`) into the
    /// outputs of the single run, bit for bit.
    Merge(merge::MergeArgs),
}

pub fn run(args: &Args) -> Result<()> {
    if let Some(LifetimeCommand::Merge(merge_args)) = &args.command {
        return merge::run(merge_args);
    }
    if !(args.progress_interval.is_finite() && args.progress_interval >= 0.0) {
        anyhow::bail!(
            "--progress-interval {} is not allowed: a number of seconds ≥ 0",
            args.progress_interval
        );
    }
    let Some(path) = &args.file else {
        return Err(InputError::command_line(
            "FILE",
            "expected the lifetime file: vbi lifetime FILE.toml [--out DIR]",
        )
        .into());
    };
    let shard = (args.shard.as_deref())
        .map(|s| {
            s.parse::<Shard>()
                .map_err(|e| InputError::command_line("--shard", e.to_string()))
        })
        .transpose()?;
    let file = SourceFile::read(path)?;
    crate::inputs::expect_kind(&file, "lifetime", "vbi lifetime")?;
    let lifetime = lifetime_input::load(&file)?;
    let mut analysis = lifetime_input::prepare(&file, &lifetime)?;
    let details = crate::inputs::fatigue_details::lifetime_details(
        &file,
        &lifetime.fatigue_details,
        &analysis,
    )?;
    if shard.is_some() && !details.is_empty() {
        return Err(file
            .error_at(
                "fatigue_detail",
                "a shard cannot count fatigue: rainflow carries each detail's residue across the \
                 whole record; expected no --shard with [[fatigue_detail]] (run the record whole)",
            )
            .into());
    }
    if let Some(shard) = shard {
        if args.resume && merge::finished_shard(&args.out, &lifetime, shard) {
            println!(
                "shard {shard} of {} is finished in {} (its shard.json): nothing to run",
                lifetime.name,
                args.out.display()
            );
            return Ok(());
        }
        lifetime_input::make_shard(&file, &lifetime, &mut analysis, shard)?;
    }
    let reader = lifetime_input::open_traffic(&file, &lifetime)?;
    let _lock = lock_output_dir(&args.out)?;
    if shard.is_some() {
        merge::start_shard(&args.out)?;
    }
    let started = Instant::now();
    let exceedances = lifetime.return_levels.exceedances;
    let (unit, total) = (reader.progress_unit(), reader.progress().1);
    let unit = match lifetime.dynamics {
        Some(_) => format!("{unit}, with dynamics"),
        None => unit.to_string(),
    };
    let progress = Progress::new(&unit, total, args.progress_interval);
    let block_maxima = args.out.join("block_maxima.csv");
    let ((counts, tally, peaks), totals) = match &lifetime.dynamics {
        None => {
            let ran = write_block_maxima(&block_maxima, &analysis, reader, exceedances, &progress)?;
            progress.finish();
            (ran, None)
        }
        Some(settings) => {
            let (ran, rows, totals, points) = dynamics::dynamic_pass(
                &file,
                &args.out,
                (&analysis, settings),
                (reader, exceedances),
                &progress,
            )?;
            progress.finish();
            match shard {
                // A shard's totals are merged: its table has the static maxima.
                Some(_) => write_static_rows(&block_maxima, &analysis, &rows)?,
                None => dynamics::write_block_maxima(&block_maxima, &analysis, &rows, &totals)?,
            }
            dynamics::write_governing_events(&args.out, &lifetime, (&analysis, settings), &totals)?;
            (ran, Some((totals, points)))
        }
    };
    if let Some(shard) = shard {
        let part = vbi::lifetime::LifetimeShard::new(
            shard,
            &analysis,
            counts,
            (&tally, &peaks),
            totals.as_ref().map(|(totals, _)| totals),
        );
        let seconds = started.elapsed().as_secs_f64();
        return merge::write_shard(&args.out, &lifetime, part, seconds);
    }
    let results = Results {
        counts,
        tally: &tally,
        peaks: &peaks,
        totals: totals.as_ref().map(|(totals, points)| (totals, points)),
    };
    write_results(
        &args.out,
        (&lifetime, &analysis),
        results,
        args.format,
        started,
    )?;
    if !details.is_empty() {
        let lines = fatigue::fatigue_pass(&file, (&lifetime, &analysis), &details, &args.out)?;
        if matches!(args.format, OutputFormat::Table) {
            lines.iter().for_each(|line| println!("{line}"));
        }
    }
    Ok(())
}

/// What the outputs are written from: a run's, or its shards' merged.
pub struct Results<'a> {
    pub counts: LifetimeCounts,
    pub tally: &'a BlockMaximaTally,
    pub peaks: &'a EventPeaks,
    pub totals: Option<(
        &'a vbi::lifetime::TotalBlockMaxima,
        &'a daf_figure::EventPoints,
    )>,
}

/// The outputs after block_maxima.csv (and events.csv and governing/ with dynamics): the
/// summary, the figures, return_levels.csv, lifetime.json, the tables as Parquet, and the
/// table (or the summary as JSON) on standard output.
pub fn write_results(
    out: &Path,
    (lifetime, analysis): (&lifetime_input::LifetimeFile, &StaticLifetime),
    results: Results,
    format: OutputFormat,
    started: Instant,
) -> Result<()> {
    let summary = lifetime_input::summary(
        lifetime,
        analysis,
        results.counts,
        results.tally,
        results.peaks,
        results.totals.map(|(totals, _)| totals),
    );
    if let Some((totals, points)) = results.totals {
        daf_figure::write_daf_plot(
            &out.join("daf_against_static"),
            analysis,
            (&results.tally.values, totals),
            points,
            &summary,
        )?;
    }
    write_return_levels(&out.join("return_levels.csv"), &summary)?;
    figure::write_return_level_plot(
        &out.join("return_levels"),
        analysis,
        results.tally,
        &summary,
    )?;
    write_json(&out.join("lifetime.json"), &summary)?;
    // The tables also as Parquet, typed, for pandas, Polars, DuckDB or Spark.
    let events = lifetime.dynamics.is_some().then_some("events");
    for table in ["block_maxima", "return_levels"].into_iter().chain(events) {
        let csv = out.join(format!("{table}.csv"));
        csv_file_as_parquet(&csv, &out.join(format!("{table}.parquet")))?;
    }
    match format {
        OutputFormat::Json => println!("{}", serde_json::to_string_pretty(&summary)?),
        OutputFormat::Table => print_table(&summary, started.elapsed().as_secs_f64(), out),
    }
    Ok(())
}

/// What the static pass gives: the counts, the block maxima's tally and the largest events.
type StaticPass = (LifetimeCounts, BlockMaximaTally, EventPeaks);

/// Streams the traffic through the analysis ([`lifetime_input::run`]) into `path`, row by row;
/// a bad line or a refused truck stops it, and no block_maxima.csv is left.
fn write_block_maxima(
    path: &std::path::Path,
    analysis: &StaticLifetime,
    reader: TrafficSource,
    exceedances: usize,
    progress: &Progress,
) -> Result<StaticPass> {
    let mut ran = None;
    write_atomic_with(path, |out| {
        writeln!(out, "{STATIC_HEADER}")?;
        let mut written: std::io::Result<()> = Ok(());
        ran = Some(lifetime_input::run(
            analysis,
            reader,
            exceedances,
            |rows| {
                for row in rows {
                    if written.is_err() {
                        break;
                    }
                    written = write_static_row(out, analysis, row);
                }
            },
            // A last line without its newline would count one byte more than the file has.
            |done| progress.set(done),
        )?);
        Ok(written?)
    })?;
    Ok(ran.expect("written only after the run"))
}

/// The header of block_maxima.csv without dynamics.
const STATIC_HEADER: &str = "block,station,quantity,static,time_s,trucks";

/// A row of block_maxima.csv without dynamics.
fn write_static_row(
    out: &mut dyn std::io::Write,
    analysis: &StaticLifetime,
    row: &BlockMaximum,
) -> std::io::Result<()> {
    writeln!(out, "{}", static_cells(analysis, row))
}

/// The static cells of a block_maxima.csv row: `block, station, quantity, static, time_s,
/// trucks` (with dynamics, `total` and `daf` follow).
pub fn static_cells(analysis: &StaticLifetime, row: &BlockMaximum) -> String {
    let effect = &analysis.effects[row.effect];
    format!(
        "{},{},{},{},{},{}",
        row.block,
        effect.station,
        effect.quantity.name(),
        row.value,
        row.time,
        row.trucks
    )
}

/// block_maxima.csv without dynamics, from the rows kept (a shard's with dynamics, whose
/// totals are merged).
fn write_static_rows(path: &Path, analysis: &StaticLifetime, rows: &[BlockMaximum]) -> Result<()> {
    write_atomic_with(path, |out| {
        writeln!(out, "{STATIC_HEADER}")?;
        for row in rows {
            write_static_row(out, analysis, row)?;
        }
        Ok(())
    })
}

/// One row per effect, law and return period: `station, quantity, model` (`gev`, `gumbel` for the
/// block maxima; `gpd` for the peaks over threshold), `period_years, return_level, low, high`
/// (the 95 % profile-likelihood interval; `high` empty where the likelihood sets no upper
/// bound), `bootstrap_low, bootstrap_high` (the 95 % percentile-bootstrap interval; empty
/// without resamples and for `gpd`), `fitted` (the block maxima or exceedances fitted),
/// `location, scale, shape` (the law's parameters, fitted to magnitudes; a `gpd` row's location
/// is its threshold). The levels carry the effect's sign. Fits that could not be made have no
/// rows (lifetime.json says why).
fn write_return_levels(
    path: &std::path::Path,
    summary: &lifetime_input::LifetimeSummary,
) -> Result<()> {
    write_atomic_with(path, |out| {
        writeln!(
            out,
            "station,quantity,model,period_years,return_level,low,high,bootstrap_low,bootstrap_high,fitted,location,scale,shape"
        )?;
        for effect in &summary.effects {
            let mut row = |model: &str, level: &ReturnLevel, fitted: usize, law: [f64; 3]| {
                writeln!(
                    out,
                    "{},{},{model},{},{},{},{},{},{},{fitted},{},{},{}",
                    effect.station,
                    effect.quantity,
                    level.period_years,
                    level.value,
                    level.low,
                    optional(level.high),
                    optional(level.bootstrap_low),
                    optional(level.bootstrap_high),
                    law[0],
                    law[1],
                    law[2]
                )
            };
            if let Some(fits) = &effect.fits {
                for fit in &fits.fits {
                    let law = [fit.law.location, fit.law.scale, fit.law.shape];
                    for level in &fit.return_levels {
                        row(fit.model.name(), level, fits.loaded_blocks, law)?;
                    }
                }
            }
            if let Some(peaks) = &effect.peaks_over_threshold {
                let law = [peaks.law.threshold, peaks.law.scale, peaks.law.shape];
                for level in &peaks.return_levels {
                    row("gpd", level, peaks.exceedances, law)?;
                }
            }
        }
        Ok(())
    })
}

/// An optional number's CSV cell: empty for None.
fn optional(value: Option<f64>) -> String {
    value.map(|v| v.to_string()).unwrap_or_default()
}

fn print_table(summary: &lifetime_input::LifetimeSummary, seconds: f64, out: &Path) {
    let days = summary.block_seconds / vbi::lifetime::SECONDS_PER_DAY;
    let block = if days < 1.0 {
        format!("{} h", vbi::units::shown(summary.block_seconds / 3600.0))
    } else {
        format!(
            "{} day{}",
            vbi::units::shown(days),
            if days == 1.0 { "" } else { "s" }
        )
    };
    println!(
        "{}: {} trucks in {} events ({} with several trucks on the deck), {} blocks of {block}, {}, in {:.1} s",
        summary.name,
        summary.trucks,
        summary.events,
        summary.multiple_presence_events,
        summary.blocks,
        match summary.dynamics {
            true => "static and with dynamics",
            false => "static",
        },
        seconds
    );
    println!("bridge: {}", summary.bridge);
    println!(
        "{:<24} {:<18} {:>16} {:>16}  unit",
        "station", "quantity", "largest block max", "mean block max"
    );
    for effect in &summary.effects {
        println!(
            "{:<24} {:<18} {:>16.6e} {:>16.6e}  {}",
            effect.station,
            effect.quantity,
            effect.largest_block_maximum,
            effect.mean_block_maximum,
            effect.unit
        );
    }
    print_return_levels(summary);
    dynamics::print_totals(summary);
    println!(
        "wrote {}/block_maxima.csv, return_levels.csv (and its plot, .png and .svg, where a fit was made){}, lifetime.json, and each table also as .parquet; `vbi report {}` writes the HTML report",
        out.display(),
        match summary.dynamics {
            true => ", events.csv, daf_against_static.png and .svg, governing/ (each effect's governing event as a vbi run scenario)",
            false => "",
        },
        out.display()
    );
}

/// Each effect's return levels: the GEV's first, with its interval, the Gumbel's beside it.
fn print_return_levels(summary: &lifetime_input::LifetimeSummary) {
    println!(
        "return levels: GEV and Gumbel maximum-likelihood fits of the loaded blocks' maxima, {} days of traffic a year; 95 % profile-likelihood interval (bootstrap intervals, {} resamples, in return_levels.csv)",
        vbi::units::shown(summary.days_per_year),
        summary.bootstrap_resamples
    );
    println!(
        "{:<24} {:<18} {:>6} {:>8} {:>14} {:>14} {:>14} {:>14} {:>14}  unit",
        "station",
        "quantity",
        "blocks",
        "years",
        "GEV level",
        "95 % low*",
        "95 % high*",
        "Gumbel level",
        "POT level"
    );
    println!("  * the GEV level's 95 % profile-likelihood interval; low is the end nearer zero");
    for effect in &summary.effects {
        let Some(fits) = &effect.fits else {
            println!(
                "{:<24} {:<18} no fit: {}",
                effect.station,
                effect.quantity,
                effect.fit_error.as_deref().unwrap_or("")
            );
            continue;
        };
        let law = |model: ExtremeValueModel| fits.fits.iter().find(|f| f.model == model);
        let (gev, gumbel) = (law(ExtremeValueModel::Gev), law(ExtremeValueModel::Gumbel));
        let peaks = effect.peaks_over_threshold.as_ref();
        let number = |v: Option<f64>| v.map_or_else(|| "-".into(), |v| format!("{v:.6e}"));
        for (k, period) in summary.return_periods_years.iter().enumerate() {
            let gev_level = gev.map(|f| &f.return_levels[k]);
            let high = match gev_level {
                Some(level) => level
                    .high
                    .map_or_else(|| "unbounded".into(), |h| format!("{h:.6e}")),
                None => "-".into(),
            };
            println!(
                "{:<24} {:<18} {:>6} {:>8} {:>14} {:>14} {:>14} {:>14} {:>14}  {}",
                effect.station,
                effect.quantity,
                fits.loaded_blocks,
                vbi::units::shown(*period),
                number(gev_level.map(|l| l.value)),
                number(gev_level.map(|l| l.low)),
                high,
                number(gumbel.map(|f| f.return_levels[k].value)),
                number(peaks.map(|p| p.return_levels[k].value)),
                effect.unit
            );
        }
        for error in &fits.errors {
            println!("{:<24} {:<18} {error}", effect.station, effect.quantity);
        }
    }
}
