//! The report of one `vbi run --out` directory, from its `summary.json` and figures: key
//! results (bridge, vehicle, speed, the RDM station's converged DAF_u, DAF_M and RDM with their
//! convergence, the paper's values beside them), every station's DAFs in a table with units,
//! the warnings, the figures with captions, the natural frequencies and the provenance.

use std::path::Path;

use anyhow::{Context, Result};
use serde_json::Value;

use super::page::{self, caption, figure, fixed, number, svg_figures, Page};

/// The report of the run in `dir`, as an HTML document.
pub fn report(dir: &Path) -> Result<String> {
    let path = dir.join("summary.json");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let summary: Value = serde_json::from_str(&text)
        .with_context(|| format!("{} is not a vbi run summary", path.display()))?;
    let provenance = &summary["provenance"];
    let text_of = |v: &Value| match v {
        Value::String(s) => s.clone(),
        Value::Null => "–".into(),
        other => other.to_string(),
    };
    let mut page = Page::new(&format!(
        "vbi run report: {}",
        text_of(&provenance["scenario"])
    ));
    key_results(&mut page, &summary);
    page.section("stations", "DAF at every station", stations(&summary));
    let warnings = summary["warnings"].as_array().cloned().unwrap_or_default();
    if !warnings.is_empty() {
        let items: String = warnings
            .iter()
            .map(|w| format!("<li>{}</li>", page::escape(&text_of(w))))
            .collect();
        page.section("warnings", "Warnings", format!("<ul>{items}</ul>"));
    }
    let figures: String = svg_figures(dir)?
        .iter()
        .map(|(stem, svg)| figure(svg, &caption(stem)))
        .collect();
    page.section(
        "figures",
        "Figures",
        if figures.is_empty() {
            "<p>No figures in the directory.</p>".into()
        } else {
            figures
        },
    );
    page.section("frequencies", "Natural frequencies", frequencies(&summary));
    let rows: Vec<Vec<String>> = provenance
        .as_object()
        .map(|o| {
            o.iter()
                .map(|(k, v)| vec![k.replace('_', " "), text_of(v)])
                .collect()
        })
        .unwrap_or_default();
    page.section(
        "provenance",
        "Provenance",
        page::table(&["item".into(), "value".into()], &rows),
    );
    Ok(page.html())
}

/// The entry of a station and quantity in the summary.
fn entry<'a>(summary: &'a Value, station: &str, quantity: &str) -> Option<&'a Value> {
    summary["stations"]
        .as_array()?
        .iter()
        .find(|e| e["name"] == station && e["quantity"] == quantity)
}

fn key_results(page: &mut Page, summary: &Value) {
    let p = &summary["provenance"];
    let text = |v: &Value| v.as_str().unwrap_or("–").to_string();
    page.key_result("bridge", text(&p["bridge"]));
    page.key_result("vehicle", text(&p["vehicle"]));
    page.key_result("speed", format!("{} km/h", number(p["speed_kmh"].as_f64())));
    let station = summary["rdm_station"].as_str().unwrap_or("–");
    page.key_result("station (RDM station)", station.to_string());
    for (label, quantity) in [("DAF_u", "deflection"), ("DAF_M", "bending_moment")] {
        let value = entry(summary, station, quantity).map_or("–".into(), |e| {
            format!(
                "{} (change over the last modes {}; the paper's plain modal sum {})",
                number(e["daf"].as_f64()),
                fixed(e["daf_change"].as_f64(), 4),
                number(e["daf_paper"].as_f64())
            )
        });
        page.key_result(&format!("converged {label}"), value);
    }
    page.key_result(
        "converged RDM = DAF_u / DAF_M",
        format!(
            "{} (the paper's: {})",
            number(summary["rdm"].as_f64()),
            number(summary["rdm_paper"].as_f64())
        ),
    );
    let entries = summary["stations"].as_array().cloned().unwrap_or_default();
    let unsettled = entries.iter().filter(|e| e["converged"] == false).count();
    page.key_result(
        "convergence in the modes",
        format!(
            "{} modes; {} of {} station quantities change by more than the tolerance over the \
             last modes",
            number(p["modes"].as_f64()),
            unsettled,
            entries.len()
        ),
    );
    page.key_result(
        "warnings",
        summary["warnings"]
            .as_array()
            .map_or(0, Vec::len)
            .to_string(),
    );
}

/// Scale and unit of a quantity in the report's tables.
fn unit_of(quantity: &str) -> (f64, &'static str) {
    match quantity {
        "deflection" => (1e3, "mm"),
        "bending_moment" => (1e-3, "kN·m"),
        _ => (1e-3, "kN"),
    }
}

fn stations(summary: &Value) -> String {
    let header: Vec<String> = [
        "station",
        "quantity",
        "unit",
        "static max",
        "dynamic max",
        "DAF [-]",
        "change over the last modes [-]",
        "paper's DAF [-]",
        "paper's CM",
        "K1",
        "K2",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<String>> = summary["stations"]
        .as_array()
        .map(|entries| {
            entries
                .iter()
                .map(|e| {
                    let quantity = e["quantity"].as_str().unwrap_or("");
                    let (scale, unit) = unit_of(quantity);
                    let scaled = |v: &Value| number(v.as_f64().map(|x| x * scale));
                    vec![
                        e["name"].as_str().unwrap_or("").to_string(),
                        quantity.replace('_', " "),
                        unit.to_string(),
                        scaled(&e["static_max"]),
                        scaled(&e["dynamic_max"]),
                        number(e["daf"].as_f64()),
                        fixed(e["daf_change"].as_f64(), 4),
                        number(e["daf_paper"].as_f64()),
                        number(e["convergence_mode_paper"].as_f64()),
                        number(e["cutoff_k1"].as_f64()),
                        number(e["cutoff_k2"].as_f64()),
                    ]
                })
                .collect()
        })
        .unwrap_or_default();
    format!(
        "<p>DAF: the converged (static-corrected) DAF with all modes; the change is its largest \
         change over the last fifth of the modes kept. The paper's DAF is the plain modal sum, \
         with its convergence mode CM and the cut-off modes K1, K2 (numbers of modes). Extremes \
         are signed: deflection downward negative, sagging moment positive.</p>{}",
        page::table(&header, &rows)
    )
}

fn frequencies(summary: &Value) -> String {
    let rows: Vec<Vec<String>> = summary["frequencies_hz"]
        .as_array()
        .map(|f| {
            f.iter()
                .enumerate()
                .map(|(k, v)| vec![(k + 1).to_string(), number(v.as_f64())])
                .collect()
        })
        .unwrap_or_default();
    page::table(&["mode".into(), "frequency [Hz]".into()], &rows)
}
