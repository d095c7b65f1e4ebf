//! `vbi lifetime FILE --out DIR`: the block maxima of every station's static load effects under a
//! traffic file (docs/lifetime.md). Reads the file and the traffic, line by line, hands them to
//! [`vbi::lifetime::static_block_maxima`], and writes `DIR/block_maxima.csv` (streamed, one row
//! per block, station and quantity), `DIR/return_levels.csv` (per effect, law and return period:
//! the level with its bootstrap interval and the law's parameters) and `DIR/lifetime.json` (what
//! was run, the counts, and per effect the block maxima's summary and fits), and the return-level
//! plot `DIR/return_levels.png` and `.svg` ([`figure`]).

mod daf_figure;
mod dynamics;
mod figure;

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Result;

use vbi::lifetime::{BlockMaximaTally, EventPeaks, LifetimeCounts, ReturnLevel, StaticLifetime};
use vbi::statistics::extreme_value::ExtremeValueModel;

use crate::commands::OutputFormat;
use crate::input::SourceFile;
use crate::inputs::lifetime as lifetime_input;
use crate::inputs::traffic_source::TrafficSource;
use crate::output::{lock_output_dir, write_atomic_with, write_json};
use crate::parquet_table::csv_file_as_parquet;
use crate::progress::Progress;

/// Arguments of `vbi lifetime`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Lifetime file (`[lifetime]` TOML).
    pub file: PathBuf,
    /// Directory for block_maxima.csv, return_levels.csv (and .png, .svg) and lifetime.json.
    #[arg(long, default_value = "lifetime-results")]
    pub out: PathBuf,
    /// Output on stdout.
    #[arg(long, value_enum, default_value_t = OutputFormat::Table)]
    pub format: OutputFormat,
    /// Seconds between progress lines on standard error when it is not a terminal (a job log,
    /// a pipe); 0 prints a line per block. On a terminal a progress bar is drawn instead. The
    /// progress is the traffic file's kB read (or the hours of traffic generated), with the
    /// rate and the time left.
    #[arg(long, value_name = "SECONDS", default_value_t = crate::progress::DEFAULT_INTERVAL_S)]
    pub progress_interval: f64,
}

pub fn run(args: &Args) -> Result<()> {
    if !(args.progress_interval.is_finite() && args.progress_interval >= 0.0) {
        anyhow::bail!(
            "--progress-interval {} is not allowed: a number of seconds ≥ 0",
            args.progress_interval
        );
    }
    let file = SourceFile::read(&args.file)?;
    crate::inputs::expect_kind(&file, "lifetime", "vbi lifetime")?;
    let lifetime = lifetime_input::load(&file)?;
    let analysis = lifetime_input::prepare(&file, &lifetime)?;
    let reader = lifetime_input::open_traffic(&file, &lifetime)?;
    let _lock = lock_output_dir(&args.out)?;
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
            dynamics::write_block_maxima(&block_maxima, &analysis, &rows, &totals)?;
            dynamics::write_governing_events(&args.out, &lifetime, (&analysis, settings), &totals)?;
            (ran, Some((totals, points)))
        }
    };
    let summary = lifetime_input::summary(
        &lifetime,
        &analysis,
        counts,
        &tally,
        &peaks,
        totals.as_ref().map(|(totals, _)| totals),
    );
    if let Some((totals, points)) = &totals {
        daf_figure::write_daf_plot(
            &args.out.join("daf_against_static"),
            &analysis,
            (&tally.values, totals),
            points,
            &summary,
        )?;
    }
    write_return_levels(&args.out.join("return_levels.csv"), &summary)?;
    figure::write_return_level_plot(&args.out.join("return_levels"), &analysis, &tally, &summary)?;
    write_json(&args.out.join("lifetime.json"), &summary)?;
    // The tables also as Parquet, typed, for pandas, Polars, DuckDB or Spark.
    let events = lifetime.dynamics.is_some().then_some("events");
    for table in ["block_maxima", "return_levels"].into_iter().chain(events) {
        let csv = args.out.join(format!("{table}.csv"));
        csv_file_as_parquet(&csv, &args.out.join(format!("{table}.parquet")))?;
    }
    match args.format {
        OutputFormat::Json => println!("{}", serde_json::to_string_pretty(&summary)?),
        OutputFormat::Table => print_table(&summary, started.elapsed().as_secs_f64(), args),
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
        writeln!(out, "block,station,quantity,static,time_s,trucks")?;
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
                    let effect = &analysis.effects[row.effect];
                    written = writeln!(
                        out,
                        "{},{},{},{},{},{}",
                        row.block,
                        effect.station,
                        effect.quantity.name(),
                        row.value,
                        row.time,
                        row.trucks
                    );
                }
            },
            // A last line without its newline would count one byte more than the file has.
            |done| progress.set(done),
        )?);
        Ok(written?)
    })?;
    Ok(ran.expect("written only after the run"))
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

fn print_table(summary: &lifetime_input::LifetimeSummary, seconds: f64, args: &Args) {
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
        "wrote {}/block_maxima.csv, return_levels.csv (and its plot, .png and .svg, where a fit was made){}, lifetime.json, and each table also as .parquet",
        args.out.display(),
        match summary.dynamics {
            true => ", events.csv, daf_against_static.png and .svg, governing/ (each effect's governing event as a vbi run scenario)",
            false => "",
        }
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
