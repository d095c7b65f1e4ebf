//! `vbi lifetime FILE --out DIR`: the block maxima of every station's static load effects under a
//! traffic file (docs/lifetime.md). Reads the file and the traffic, line by line, hands them to
//! [`vbi::lifetime::static_block_maxima`], and writes `DIR/block_maxima.csv` (streamed, one row
//! per block, station and quantity) and `DIR/lifetime.json` (what was run, the counts, and per
//! effect the largest and the mean block maximum).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Result;

use vbi::lifetime::{BlockMaximaTally, LifetimeCounts, StaticLifetime};

use crate::commands::OutputFormat;
use crate::input::SourceFile;
use crate::inputs::lifetime as lifetime_input;
use crate::inputs::traffic_file::TrafficFileReader;
use crate::output::{lock_output_dir, write_atomic_with, write_json};

/// Arguments of `vbi lifetime`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Lifetime file (`[lifetime]` TOML).
    pub file: PathBuf,
    /// Directory for block_maxima.csv and lifetime.json.
    #[arg(long, default_value = "lifetime-results")]
    pub out: PathBuf,
    /// Output on stdout.
    #[arg(long, value_enum, default_value_t = OutputFormat::Table)]
    pub format: OutputFormat,
}

pub fn run(args: &Args) -> Result<()> {
    let file = SourceFile::read(&args.file)?;
    crate::inputs::expect_kind(&file, "lifetime", "vbi lifetime")?;
    let lifetime = lifetime_input::load(&file)?;
    let analysis = lifetime_input::prepare(&file, &lifetime)?;
    let reader = lifetime_input::open_traffic(&file, &lifetime)?;
    let _lock = lock_output_dir(&args.out)?;
    let started = Instant::now();
    let (counts, tally) =
        write_block_maxima(&args.out.join("block_maxima.csv"), &analysis, reader)?;
    let summary = lifetime_input::summary(&lifetime, &analysis, counts, &tally);
    write_json(&args.out.join("lifetime.json"), &summary)?;
    match args.format {
        OutputFormat::Json => println!("{}", serde_json::to_string_pretty(&summary)?),
        OutputFormat::Table => print_table(&summary, started.elapsed().as_secs_f64(), args),
    }
    Ok(())
}

/// Streams the traffic through the analysis ([`lifetime_input::run`]) into `path`, row by row;
/// a bad line or a refused truck stops it, and no block_maxima.csv is left.
fn write_block_maxima(
    path: &std::path::Path,
    analysis: &StaticLifetime,
    reader: TrafficFileReader,
) -> Result<(LifetimeCounts, BlockMaximaTally)> {
    let mut ran = None;
    write_atomic_with(path, |out| {
        writeln!(out, "block,station,quantity,static,time_s,trucks")?;
        let mut written: std::io::Result<()> = Ok(());
        ran = Some(lifetime_input::run(analysis, reader, |rows| {
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
        })?);
        Ok(written?)
    })?;
    Ok(ran.expect("written only after the run"))
}

fn print_table(summary: &lifetime_input::LifetimeSummary, seconds: f64, args: &Args) {
    let days = summary.block_seconds / vbi::lifetime::SECONDS_PER_DAY;
    println!(
        "{}: {} trucks in {} events ({} with several trucks on the deck), {} blocks of {} day{}, static, in {:.1} s",
        summary.name,
        summary.trucks,
        summary.events,
        summary.multiple_presence_events,
        summary.blocks,
        vbi::units::shown(days),
        if days == 1.0 { "" } else { "s" },
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
    println!(
        "wrote {}/block_maxima.csv and lifetime.json",
        args.out.display()
    );
}
