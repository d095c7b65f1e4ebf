//! The report of one `vbi lifetime --out` directory (or of a merge of its shards), from its
//! `lifetime.json` and figures: key results (the record, and per effect its characteristic
//! static effect, and with dynamics its characteristic total effect and the assessment DAF), the
//! return levels with their intervals, the assessment DAF beside the design codes, the
//! screening, the figures, the governing events as `vbi run` scenarios, the warnings and the
//! provenance.
//!
//! A return level is shown as a characteristic value only when its fit is settled: the
//! upper end of its 95 % profile-likelihood interval is at most twice the lower end (an
//! unbounded or wider interval says the blocks are too few, or not alike, to fix the law's
//! tail; docs/lifetime.md, "Return levels"). Otherwise the key results say so instead.

use std::path::Path;

use anyhow::{Context, Result};
use serde_json::Value;

use super::page::{self, fixed, Page};

/// The widest 95 % interval (upper end over lower end, in magnitude) of a level the key
/// results show as a characteristic value.
const SETTLED_INTERVAL_RATIO: f64 = 2.0;

/// The report of the lifetime run in `dir`, as an HTML document.
pub fn report(dir: &Path) -> Result<String> {
    let path = dir.join("lifetime.json");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let summary: Value = serde_json::from_str(&text)
        .with_context(|| format!("{} is not a vbi lifetime summary", path.display()))?;
    let name = summary["name"].as_str().unwrap_or("lifetime");
    let mut page = Page::new(&format!("vbi lifetime report: {name}"));
    let effects: Vec<&Value> = summary["effects"]
        .as_array()
        .into_iter()
        .flatten()
        .collect();
    let periods: Vec<f64> = (summary["return_periods_years"].as_array().into_iter())
        .flatten()
        .filter_map(Value::as_f64)
        .collect();
    let mut warnings = Vec::new();
    key_results(&mut page, &summary, &effects, &mut warnings);
    page.section(
        "characteristic",
        "Characteristic static effects (return levels)",
        static_levels(&effects, &periods, summary["days_per_year"].as_f64()),
    );
    let dynamics = summary["dynamics"].as_bool() == Some(true);
    if dynamics {
        page.section(
            "assessment-daf",
            "Characteristic total effects and the assessment DAF",
            assessment(&effects, &periods),
        );
        page.section(
            "screening",
            "Dynamics on the events that can govern",
            screening(&summary, &effects),
        );
    }
    page.section("figures", "Figures", page::figures(dir, caption)?);
    if dynamics {
        page.section("governing", "Governing events", governing(dir, &effects));
    }
    for effect in &effects {
        for (what, error) in [
            ("static fit", &effect["fit_error"]),
            ("peaks over threshold", &effect["peaks_error"]),
            ("total fit", &effect["total"]["fit_error"]),
        ] {
            if let Some(error) = error.as_str() {
                warnings.push(format!("{}: {what}: {error}", effect_name(effect)));
            }
        }
    }
    for effect in &effects {
        let check = &effect["total"]["screening_check"];
        if check["blocks_at_risk"].as_u64().is_some_and(|n| n > 0) {
            warnings.push(format!(
                "{}: screening: {} of {} blocks at risk (the largest DAF just above the threshold is {}): a lower screening_ratio integrates more events",
                effect_name(effect),
                check["blocks_at_risk"],
                check["blocks"],
                fixed(check["edge_daf"].as_f64(), 3)
            ));
        }
    }
    if let Some(refusal) = summary["dynamic_events"]["first_refusal"].as_str() {
        let refused = summary["dynamic_events"]["refused"].as_u64().unwrap_or(0);
        warnings.push(format!(
            "{refused} events screened in were refused, their totals missing (first: {refusal})"
        ));
    }
    if !warnings.is_empty() {
        let items: String = (warnings.iter())
            .map(|w| format!("<li>{}</li>", page::escape(w)))
            .collect();
        page.section("warnings", "Warnings", format!("<ul>{items}</ul>"));
    }
    page.section("provenance", "Provenance", provenance(&summary));
    Ok(page.html())
}

/// An effect's name: `station quantity`.
fn effect_name(effect: &Value) -> String {
    let quantity = effect["quantity"].as_str().unwrap_or("").replace('_', " ");
    format!("{} {quantity}", effect["station"].as_str().unwrap_or(""))
}

/// The unit a report shows a quantity in, and its factor from the SI unit of lifetime.json.
fn shown_unit(unit: &str) -> (f64, &'static str) {
    match unit {
        "N·m" => (1e-3, "kN·m"),
        "N" => (1e-3, "kN"),
        "m" => (1e3, "mm"),
        _ => (1.0, ""),
    }
}

/// A value of `effect` in its shown unit, to four significant digits.
fn value_of(effect: &Value, value: Option<f64>) -> String {
    let (factor, _) = shown_unit(effect["unit"].as_str().unwrap_or(""));
    match value {
        Some(v) if v.is_finite() => significant(v * factor),
        _ => "–".into(),
    }
}

/// Four significant digits, without scientific notation for ordinary magnitudes.
fn significant(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let digits = (3 - x.abs().log10().floor() as i32).clamp(0, 8) as usize;
    format!("{x:.digits$}")
}

/// The return level of `model` (`gev`, `gumbel`) for period index k in `fits` (an
/// `EffectFits`), or None.
fn level<'a>(fits: &'a Value, model: &str, k: usize) -> Option<&'a Value> {
    (fits["fits"].as_array()?.iter())
        .find(|f| f["model"] == model)
        .and_then(|f| f["return_levels"].get(k))
}

/// Whether a level's 95 % interval is narrow enough to sign ([`SETTLED_INTERVAL_RATIO`]).
fn settled(level: &Value) -> bool {
    let (low, high) = (level["low"].as_f64(), level["high"].as_f64());
    matches!((low, high), (Some(low), Some(high))
        if low != 0.0 && (high / low).abs() <= SETTLED_INTERVAL_RATIO)
}

/// The key-results box: the record, and per effect the first return period's characteristic
/// static effect (with the total and the assessment DAF with dynamics), or why there is none.
fn key_results(page: &mut Page, summary: &Value, effects: &[&Value], warnings: &mut Vec<String>) {
    let days = summary["block_seconds"].as_f64().unwrap_or(86_400.0) / 86_400.0;
    // Whole hours and days as whole numbers (a block of 1/24 day is 1 h to round-off).
    let whole = |x: f64| match (x - x.round()).abs() < 1e-9 * x.abs().max(1.0) {
        true => format!("{}", x.round()),
        false => significant(x),
    };
    let block = match days {
        d if d < 1.0 => format!("{} h", whole(d * 24.0)),
        1.0 => "1 day".into(),
        d => format!("{} days", whole(d)),
    };
    page.key_result(
        "record",
        format!(
            "{} trucks in {} events ({} with several trucks on the deck) over {} days: {} blocks of {block}",
            summary["trucks"],
            summary["events"],
            summary["multiple_presence_events"],
            summary["record_days"].as_f64().map_or_else(|| "–".into(), |d| whole(d.round())),
            summary["blocks"],
        ),
    );
    page.key_result(
        "traffic and bridge",
        format!(
            "{} ({}); {}",
            summary["traffic_file"].as_str().unwrap_or(""),
            summary["traffic_format"].as_str().unwrap_or(""),
            summary["bridge"].as_str().unwrap_or("")
        ),
    );
    let dynamic = &summary["dynamic_events"];
    if summary["dynamics"].as_bool() == Some(true) {
        page.key_result(
            "dynamics",
            format!(
                "{} events integrated (screening ratio {}, road {}), {} refused",
                dynamic["integrated"],
                dynamic["screening_ratio"],
                dynamic["road"].as_str().unwrap_or(""),
                dynamic["refused"]
            ),
        );
    }
    let period = summary["return_periods_years"][0].as_f64();
    let Some(period) = period else { return };
    for effect in effects {
        let (_, unit) = shown_unit(effect["unit"].as_str().unwrap_or(""));
        let label = format!(
            "{}, {}-year level",
            effect_name(effect),
            vbi::units::shown(period)
        );
        let Some(gev) = level(&effect["fits"], "gev", 0) else {
            let why = effect["fit_error"].as_str().unwrap_or("no fit");
            page.key_result(&label, format!("no characteristic value: {why}"));
            continue;
        };
        let gumbel = level(&effect["fits"], "gumbel", 0);
        let mut text = format!(
            "static {} {unit} (GEV; 95 %: {} to {}; Gumbel {})",
            value_of(effect, gev["value"].as_f64()),
            value_of(effect, gev["low"].as_f64()),
            value_of(effect, gev["high"].as_f64()),
            value_of(effect, gumbel.and_then(|l| l["value"].as_f64())),
        );
        let total = &effect["total"];
        if let Some(total_gev) = level(&total["fits"], "gev", 0) {
            let daf = &total["assessment_daf"][0];
            text.push_str(&format!(
                "; total {} {unit}; assessment DAF {} (GEV), {} (Gumbel)",
                value_of(effect, total_gev["value"].as_f64()),
                fixed(daf["gev"].as_f64(), 3),
                fixed(daf["gumbel"].as_f64(), 3)
            ));
        }
        if !settled(gev) {
            text.push_str(" — the GEV interval is too wide to sign");
            warnings.push(format!(
                "{label}: the GEV level's 95 % interval ({} to {} {unit}) spans more than a factor {SETTLED_INTERVAL_RATIO}: too few or unlike blocks to fix the tail; it is not a characteristic value to sign (docs/lifetime.md, \"Return levels\")",
                value_of(effect, gev["low"].as_f64()),
                value_of(effect, gev["high"].as_f64()),
            ));
        }
        page.key_result(&label, text);
    }
}

/// The static return levels of every effect and period: GEV with its profile and bootstrap
/// intervals, Gumbel, and the peaks over threshold's generalised Pareto.
fn static_levels(effects: &[&Value], periods: &[f64], days_per_year: Option<f64>) -> String {
    let header: Vec<String> = [
        "station",
        "quantity",
        "unit",
        "blocks fitted",
        "period [years]",
        "GEV level",
        "95 % low",
        "95 % high",
        "bootstrap low",
        "bootstrap high",
        "Gumbel level",
        "POT level",
        "settled",
    ]
    .map(String::from)
    .to_vec();
    let mut rows = Vec::new();
    for effect in effects {
        let (_, unit) = shown_unit(effect["unit"].as_str().unwrap_or(""));
        let fits = &effect["fits"];
        for (k, period) in periods.iter().enumerate() {
            let gev = level(fits, "gev", k);
            let field =
                |l: Option<&Value>, name: &str| value_of(effect, l.and_then(|l| l[name].as_f64()));
            let peaks = effect["peaks_over_threshold"]["return_levels"].get(k);
            rows.push(vec![
                effect["station"].as_str().unwrap_or("").to_string(),
                effect["quantity"].as_str().unwrap_or("").replace('_', " "),
                unit.to_string(),
                fits["loaded_blocks"]
                    .as_u64()
                    .map_or("–".into(), |n| n.to_string()),
                vbi::units::shown(*period),
                field(gev, "value"),
                field(gev, "low"),
                field(gev, "high"),
                field(gev, "bootstrap_low"),
                field(gev, "bootstrap_high"),
                field(level(fits, "gumbel", k), "value"),
                field(peaks, "value"),
                match gev {
                    Some(l) if settled(l) => "yes".into(),
                    Some(_) => "no: wide interval".into(),
                    None => "no fit".into(),
                },
            ]);
        }
    }
    format!(
        "<p>Maximum-likelihood fits of the block maxima (GEV and Gumbel) and of the largest \
         events (generalised Pareto), {} days of traffic a year. Levels carry the effect's \
         sign; the 95 % interval is the profile likelihood's, its low end the one nearer zero. \
         A level is settled when the interval's upper end is at most {SETTLED_INTERVAL_RATIO} \
         times its lower end.</p>{}",
        days_per_year.map_or_else(|| "–".into(), vbi::units::shown),
        page::table(&header, &rows)
    )
}

/// Per effect and period: the characteristic static and total effects and their ratio, the
/// assessment DAF, by the GEV and Gumbel levels; the largest block's DAF; the codes' 1 + IM.
fn assessment(effects: &[&Value], periods: &[f64]) -> String {
    let header: Vec<String> = [
        "station",
        "quantity",
        "unit",
        "period [years]",
        "static (GEV)",
        "total (GEV)",
        "assessment DAF (GEV)",
        "static (Gumbel)",
        "total (Gumbel)",
        "assessment DAF (Gumbel)",
        "largest block's DAF",
        "codes' 1 + IM",
    ]
    .map(String::from)
    .to_vec();
    let mut rows = Vec::new();
    for effect in effects {
        let total = &effect["total"];
        if total.is_null() {
            continue;
        }
        let (_, unit) = shown_unit(effect["unit"].as_str().unwrap_or(""));
        let largest = match (
            total["largest_block_maximum"].as_f64(),
            effect["largest_block_maximum"].as_f64(),
        ) {
            (Some(t), Some(s)) if s != 0.0 => Some(t / s),
            _ => None,
        };
        let codes: Vec<f64> = (total["design_codes"].as_array().into_iter())
            .flatten()
            .filter_map(|c| c["daf"].as_f64())
            .collect();
        let codes = match codes
            .iter()
            .copied()
            .reduce(f64::min)
            .zip(codes.iter().copied().reduce(f64::max))
        {
            Some((low, high)) => format!("{} to {}", fixed(Some(low), 3), fixed(Some(high), 3)),
            None => "–".into(),
        };
        for (k, period) in periods.iter().enumerate() {
            let value = |fits: &Value, model: &str| {
                value_of(
                    effect,
                    level(fits, model, k).and_then(|l| l["value"].as_f64()),
                )
            };
            let daf = &total["assessment_daf"][k];
            rows.push(vec![
                effect["station"].as_str().unwrap_or("").to_string(),
                effect["quantity"].as_str().unwrap_or("").replace('_', " "),
                unit.to_string(),
                vbi::units::shown(*period),
                value(&effect["fits"], "gev"),
                value(&total["fits"], "gev"),
                fixed(daf["gev"].as_f64(), 3),
                value(&effect["fits"], "gumbel"),
                value(&total["fits"], "gumbel"),
                fixed(daf["gumbel"].as_f64(), 3),
                fixed(largest, 3),
                codes.clone(),
            ]);
        }
    }
    let codes = code_rows(effects);
    format!(
        "<p>The assessment DAF is the characteristic total (dynamic) effect over the \
         characteristic static effect, each the return level of its own block maxima's law \
         (Caprani, González, Rattigan &amp; OBrien; ARCHES D10; OBrien, Cantero, Enright &amp; \
         González 2010). The heaviest events are the least amplified, so it lies below the DAF \
         of any single heavy event. Beside it: the largest block's total over its static \
         maximum, and the range of the design codes' 1 + IM at the effect (design values for \
         their own load models; EN 1991-2's include the dynamics and have none).</p>{}\
         <h3>The design codes' factors</h3>{}",
        page::table(&header, &rows),
        codes
    )
}

/// Every effect's design-code factors: code, case, clause and 1 + IM.
fn code_rows(effects: &[&Value]) -> String {
    let header: Vec<String> = ["station", "quantity", "code", "case", "clause", "1 + IM"]
        .map(String::from)
        .to_vec();
    let mut rows = Vec::new();
    for effect in effects {
        for code in effect["total"]["design_codes"]
            .as_array()
            .into_iter()
            .flatten()
        {
            rows.push(vec![
                effect["station"].as_str().unwrap_or("").to_string(),
                effect["quantity"].as_str().unwrap_or("").replace('_', " "),
                code["code"].as_str().unwrap_or("").to_string(),
                code["provision"].as_str().unwrap_or("").replace('_', " "),
                code["clause"].as_str().unwrap_or("").to_string(),
                fixed(code["daf"].as_f64(), 3),
            ]);
        }
    }
    page::table(&header, &rows)
}

/// The screening rule, its counts, and each effect's screening check.
fn screening(summary: &Value, effects: &[&Value]) -> String {
    let dynamic = &summary["dynamic_events"];
    let header: Vec<String> = [
        "station",
        "quantity",
        "band of static levels",
        "largest DAF in the band",
        "blocks at risk",
        "blocks checked",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<String>> = (effects.iter())
        .filter_map(|effect| {
            let check = &effect["total"]["screening_check"];
            (!check.is_null()).then(|| {
                vec![
                    effect["station"].as_str().unwrap_or("").to_string(),
                    effect["quantity"].as_str().unwrap_or("").replace('_', " "),
                    format!(
                        "{} to {}",
                        fixed(check["band"][0].as_f64(), 2),
                        fixed(check["band"][1].as_f64(), 2)
                    ),
                    fixed(check["edge_daf"].as_f64(), 3),
                    check["blocks_at_risk"].to_string(),
                    check["blocks"].to_string(),
                ]
            })
        })
        .collect();
    let checks = match rows.is_empty() {
        true => String::new(),
        false => format!(
            "<p>The screening's check: the integrated events whose static extreme lies just \
             above the threshold stand for those just below it, left out. A block is at risk \
             where an event at the threshold with the largest DAF seen in that band would \
             exceed the block's total maximum. It is an indicator, not a bound; where blocks \
             are at risk, a lower ratio (or a stretch at r = 0 beside the run) says whether \
             the totals move.</p>{}",
            page::table(&header, &rows)
        ),
    };
    format!(
        "<p>Each event whose static extreme reaches r = {} of its block's static maximum, for \
         some effect, was integrated as a coupled crossing of multibody trucks built from its \
         axle records, on a {} road sampled per event (OBrien, Cantero, Enright &amp; González \
         2010). An event left out can govern its block's total only if its DAF exceeds the \
         static-maximum event's by the factor 1/r. {} of {} events were integrated; {} were \
         refused. The rule's bias on the characteristic total, measured against VBI on every \
         event, is in docs/lifetime.md (\"The bias on the characteristic value\").</p>{checks}",
        dynamic["screening_ratio"],
        page::escape(dynamic["road"].as_str().unwrap_or("")),
        dynamic["integrated"],
        summary["events"],
        dynamic["refused"]
    )
}

/// The governing events: each effect's directory with the command that replays it.
fn governing(dir: &Path, effects: &[&Value]) -> String {
    let root = dir.join("governing");
    let mut items = String::new();
    for effect in effects {
        let name = crate::inputs::lifetime_replay::governing_directory_of(
            effect["station"].as_str().unwrap_or(""),
            effect["quantity"].as_str().unwrap_or(""),
        );
        let scenario = root.join(&name).join("scenario.toml");
        if scenario.is_file() {
            items.push_str(&format!(
                "<li>{}: <code>vbi run {}</code></li>",
                page::escape(&effect_name(effect)),
                page::escape(&scenario.display().to_string())
            ));
        }
    }
    match items.is_empty() {
        true => "<p>No governing event was written.</p>".into(),
        false => format!(
            "<p>The event with each effect's largest total over the record, as a <code>vbi \
             run</code> scenario that integrates the same crossing, bit for bit.</p><ul>{items}</ul>"
        ),
    }
}

/// What was run: the summary's fields other than the effects, in its order.
fn provenance(summary: &Value) -> String {
    page::fields_table(summary, &["effects", "dynamic_events"])
}

/// A sentence that says what a lifetime figure shows, from its file stem.
fn caption(stem: &str) -> String {
    match stem {
        "return_levels" => "Return levels: each effect's block maxima at their empirical mean recurrence intervals (Gringorten's positions), the GEV, Gumbel and generalised Pareto levels against the mean recurrence interval, and the GEV's 95 % profile-likelihood intervals at the return periods asked.".into(),
        "daf_against_static" => "The DAF against the static level: each integrated event's total over its static extreme, each block's total maximum over its static maximum, and the assessment DAF at the characteristic static effect.".into(),
        _ => page::caption(stem),
    }
}
