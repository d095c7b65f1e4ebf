//! `vbi lifetime` with `dynamics = true`: one pass over the traffic, which integrates the
//! events that can govern as their blocks end ([`crate::inputs::lifetime::run_with_dynamics`]),
//! streams them into `DIR/events.csv`, and writes `DIR/block_maxima.csv` with the static and
//! total block maxima side by side.

use std::path::Path;

use anyhow::Result;

use vbi::lifetime::{
    BlockMaximum, DynamicSettings, EventExtreme, EventTotals, StaticLifetime, TotalBlockMaxima,
};

use super::daf_figure::EventPoints;
use crate::input::SourceFile;
use crate::inputs::lifetime as lifetime_input;
use crate::inputs::traffic_source::TrafficSource;
use crate::output::write_atomic_with;
use crate::progress::Progress;

/// The pass with dynamics: the static rows kept (block maxima are written after it, with their
/// totals beside them: 40 bytes per block and effect), every integrated event's totals
/// streamed into `events.csv` (one row per event and effect it loads: `event, trucks, station,
/// quantity, static, crossing_static, total, daf, time_s`), the total block maxima returned.
pub fn dynamic_pass(
    file: &SourceFile,
    out: &Path,
    (analysis, settings): (&StaticLifetime, &DynamicSettings),
    (reader, exceedances): (TrafficSource, usize),
    progress: &Progress,
) -> Result<(
    super::StaticPass,
    Vec<BlockMaximum>,
    TotalBlockMaxima,
    EventPoints,
)> {
    let mut points = EventPoints::new(analysis.effects.len());
    let mut rows = Vec::new();
    let mut ran = None;
    write_atomic_with(&out.join("events.csv"), |csv| {
        writeln!(
            csv,
            "event,trucks,station,quantity,static,crossing_static,total,daf,time_s"
        )?;
        let mut written: std::io::Result<()> = Ok(());
        ran = Some(lifetime_input::run_with_dynamics(
            file,
            (analysis, settings),
            (reader, exceedances),
            (
                |block: &[BlockMaximum]| rows.extend_from_slice(block),
                |totals: &EventTotals, extremes: &[EventExtreme]| {
                    points.add(analysis, totals, extremes);
                    if written.is_ok() {
                        written = write_event_rows(csv, analysis, totals, extremes);
                    }
                },
            ),
            |done| progress.set(done),
        )?);
        Ok(written?)
    })?;
    let (counts, tally, peaks, totals) = ran.expect("written only after the run");
    Ok(((counts, tally, peaks), rows, totals, points))
}

/// An integrated event's rows of `events.csv`: one per effect it loads.
fn write_event_rows(
    csv: &mut dyn std::io::Write,
    analysis: &StaticLifetime,
    totals: &EventTotals,
    extremes: &[EventExtreme],
) -> std::io::Result<()> {
    for (e, total) in totals.totals.iter().enumerate() {
        let Some(total) = total else { continue };
        let effect = &analysis.effects[e];
        let fixed = extremes[e].value;
        let daf = match fixed != 0.0 {
            true => (total.total / fixed).to_string(),
            false => String::new(),
        };
        writeln!(
            csv,
            "{},{},{},{},{fixed},{},{},{daf},{}",
            totals.event,
            totals.trucks,
            effect.station,
            effect.quantity.name(),
            total.static_value,
            total.total,
            total.time
        )?;
    }
    Ok(())
}

/// `block_maxima.csv` with dynamics: one row per block and effect, `block, station, quantity,
/// static, time_s, trucks` as without dynamics, then `total` (the block's largest total
/// extreme, in the effect's sense) and `daf` = total / static (empty where the static maximum
/// is 0).
pub fn write_block_maxima(
    path: &Path,
    analysis: &StaticLifetime,
    rows: &[BlockMaximum],
    totals: &TotalBlockMaxima,
) -> Result<()> {
    write_atomic_with(path, |out| {
        writeln!(out, "block,station,quantity,static,time_s,trucks,total,daf")?;
        for row in rows {
            let total = totals.values[row.effect]
                .get(row.block as usize)
                .copied()
                .unwrap_or(0.0);
            let daf = match row.value != 0.0 {
                true => (total / row.value).to_string(),
                false => String::new(),
            };
            writeln!(out, "{},{total},{daf}", super::static_cells(analysis, row))?;
        }
        Ok(())
    })
}

/// The table of the total effect: per effect and return period, the characteristic static and
/// total effects (GEV levels) and the assessment DAF (GEV, Gumbel), and the events integrated.
pub fn print_totals(summary: &lifetime_input::LifetimeSummary) {
    let Some(events) = &summary.dynamic_events else {
        return;
    };
    println!(
        "dynamics: {} events integrated (screening ratio {}: every event whose static effect reaches that share of its block's maximum), road {}{}",
        events.integrated,
        events.screening_ratio,
        events.road,
        match events.refused {
            0 => String::new(),
            n => format!(
                "; {n} refused, their totals missing (first: {})",
                events.first_refusal.as_deref().unwrap_or("")
            ),
        }
    );
    println!(
        "{:<24} {:<18} {:>8} {:>14} {:>14} {:>10} {:>10} {:>12}  unit",
        "station",
        "quantity",
        "years",
        "static level",
        "total level",
        "DAF (GEV)",
        "DAF (Gum)",
        "largest DAF*"
    );
    println!("  * the largest block's total over its static maximum, for comparison");
    use vbi::statistics::extreme_value::ExtremeValueModel;
    for effect in &summary.effects {
        let Some(total) = &effect.total else { continue };
        let level = |fits: Option<&vbi::lifetime::EffectFits>, k: usize| {
            let fit = fits?
                .fits
                .iter()
                .find(|f| f.model == ExtremeValueModel::Gev)?;
            Some(fit.return_levels.get(k)?.value)
        };
        let number = |v: Option<f64>, digits: usize| {
            v.map_or_else(|| "-".into(), |v| format!("{v:.digits$e}"))
        };
        let ratio = |v: Option<f64>| v.map_or_else(|| "-".into(), |v| format!("{v:.4}"));
        let largest = (effect.largest_block_maximum != 0.0)
            .then(|| total.largest_block_maximum / effect.largest_block_maximum);
        for (k, daf) in total.assessment_daf.iter().enumerate() {
            println!(
                "{:<24} {:<18} {:>8} {:>14} {:>14} {:>10} {:>10} {:>12}  {}",
                effect.station,
                effect.quantity,
                vbi::units::shown(daf.period_years),
                number(level(effect.fits.as_ref(), k), 6),
                number(level(total.fits.as_ref(), k), 6),
                ratio(daf.gev),
                ratio(daf.gumbel),
                ratio(largest),
                effect.unit
            );
        }
        if !total.design_codes.is_empty() {
            let codes: Vec<String> = (total.design_codes.iter())
                .map(|c| format!("{} {:.3} ({})", c.code, c.daf, c.provision))
                .collect();
            println!(
                "{:<24} {:<18} codes' 1 + IM: {}",
                effect.station,
                effect.quantity,
                codes.join(", ")
            );
        }
        if let Some(check) = &total.screening_check {
            println!(
                "{:<24} {:<18} screening: {}",
                effect.station,
                effect.quantity,
                lifetime_input::screening_sentence(check)
            );
        }
        if let Some(error) = &total.fit_error {
            println!(
                "{:<24} {:<18} total: no fit: {error}",
                effect.station, effect.quantity
            );
        }
    }
}

/// Each effect's governing event (the largest total of the record) as a `vbi run` scenario:
/// `DIR/governing/<station>-<quantity>/scenario.toml` and a `[vehicle]` file per truck.
pub fn write_governing_events(
    out: &Path,
    lifetime: &lifetime_input::LifetimeFile,
    (analysis, settings): (&StaticLifetime, &DynamicSettings),
    totals: &TotalBlockMaxima,
) -> Result<()> {
    use crate::inputs::lifetime_replay::{
        governing_directory, governing_files, safe_directory_name,
    };
    for (effect, governing) in analysis.effects.iter().zip(&totals.governing) {
        let Some(governing) = governing else { continue };
        let name = governing_directory(effect);
        if !safe_directory_name(&name) {
            continue;
        }
        let directory = out.join("governing").join(name);
        std::fs::create_dir_all(&directory)?;
        let inputs = (settings, analysis.lanes.as_slice());
        for (file, text) in governing_files(&lifetime.replay, inputs, effect, governing) {
            write_atomic_with(&directory.join(file), |out| {
                Ok(out.write_all(text.as_bytes())?)
            })?;
        }
    }
    Ok(())
}
