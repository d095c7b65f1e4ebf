//! The lifetime's static fatigue (issue 51): a second pass over the traffic for the
//! `[[fatigue_detail]]`s, fatigue.csv (the rows of the library's table of lifetime fatigue
//! outputs) and fatigue_blocks.csv (each block's Miner's sum per detail).

use std::path::Path;

use anyhow::Result;

use vbi::lifetime::fatigue::{LifetimeDetail, LifetimeFatigue};
use vbi::lifetime::StaticLifetime;
use vbi::outputs::LIFETIME_FATIGUE_OUTPUTS;
use vbi_input::lifetime as lifetime_input;
use vbi_input::SourceFile;

use crate::output::write_csv;

/// Runs the fatigue pass and writes its tables; the printed lines.
pub fn fatigue_pass(
    file: &SourceFile,
    (lifetime, analysis): (&lifetime_input::LifetimeFile, &StaticLifetime),
    details: &[LifetimeDetail],
    out: &Path,
) -> Result<Vec<String>> {
    let reader = lifetime_input::open_traffic(file, lifetime)?;
    let fatigue = lifetime_input::run_fatigue(analysis, details, reader)?;
    write_tables(out, &fatigue)?;
    Ok(lines(&fatigue))
}

fn write_tables(out: &Path, fatigue: &LifetimeFatigue) -> Result<()> {
    let summaries = fatigue.summaries();
    let header: Vec<&str> = LIFETIME_FATIGUE_OUTPUTS.iter().map(|r| r.name).collect();
    let rows: Vec<Vec<String>> = (summaries.iter())
        .map(|s| {
            (LIFETIME_FATIGUE_OUTPUTS.iter())
                .map(|row| (row.value)(s).cell())
                .collect()
        })
        .collect();
    write_csv(&out.join("fatigue.csv"), &header, &rows)?;
    let names: Vec<String> = (fatigue.details.iter())
        .map(|d| format!("{}_static_damage", d.detail.detail.name))
        .collect();
    let header: Vec<&str> = std::iter::once("block")
        .chain(names.iter().map(String::as_str))
        .collect();
    let blocks = (fatigue.details.iter())
        .map(|d| d.block_damage.len())
        .max()
        .unwrap_or(0);
    let rows: Vec<Vec<String>> = (0..blocks)
        .map(|b| {
            std::iter::once(b.to_string())
                .chain(
                    fatigue
                        .details
                        .iter()
                        .map(|d| format!("{}", d.block_damage.get(b).copied().unwrap_or(0.0))),
                )
                .collect()
        })
        .collect();
    write_csv(&out.join("fatigue_blocks.csv"), &header, &rows)
}

/// The printed lines: per detail, its damage per year, fatigue life and Δσ_E,2.
fn lines(fatigue: &LifetimeFatigue) -> Vec<String> {
    let mut lines = vec![format!(
        "fatigue (static, the record as one history; {} events over {:.2} days):",
        fatigue.events,
        fatigue.record_seconds / vbi::lifetime::SECONDS_PER_DAY
    )];
    for s in fatigue.summaries() {
        let life = match s.fatigue_life_years.is_finite() {
            true => format!("{:.4e} years", s.fatigue_life_years),
            false => "no damage".to_string(),
        };
        lines.push(format!(
            "  {} ({}): D = {:.4e} per year, life {life}; Δσ_E,2 (100 years) {:.2} MPa; {} cycles, \
             {} at or above the cut-off; largest range {:.2} MPa",
            s.detail.name,
            s.curve_label,
            s.damage_per_year,
            s.equivalent_range_2e6 / vbi::units::MPA,
            s.sum.cycles,
            s.sum.damaging_cycles,
            s.sum.max_range / vbi::units::MPA,
        ));
    }
    lines
}
