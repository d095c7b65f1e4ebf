//! The report of one `vbi run --out` directory, from its `summary.json` and figures: key
//! results (bridge, vehicle, speed, the RDM station's converged DAF_u, DAF_M and RDM with their
//! convergence, the paper's values beside them), every station's DAFs in a table with units,
//! the warnings, the figures with captions, the natural frequencies and the provenance.

use std::path::Path;

use anyhow::{Context, Result};
use vbi::codes::StationCodeFactors;
use vbi::modal::Quantity;
use vbi::outputs::{RunSummary, StationValues};

use super::page::{self, caption, fixed, number, Page};

/// The report of the run in `dir`, as an HTML document.
pub fn report(dir: &Path) -> Result<String> {
    let path = dir.join("summary.json");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let summary: Summary = serde_json::from_str(&text)
        .with_context(|| format!("{} is not a vbi run summary", path.display()))?;
    let provenance = &summary.provenance;
    let mut page = Page::new(&format!("vbi run report: {}", provenance.scenario));
    key_results(&mut page, &summary);
    let codes = station_codes(&summary);
    if let Some(values) = code_key_result(&codes) {
        page.key_result("design codes, 1 + IM of the moment there", values);
    }
    page.section("stations", "DAF at every station", stations(&summary));
    if !codes.is_empty() {
        page.section(
            "design-codes",
            "Computed DAF against the design codes",
            codes_table(&summary, &codes),
        );
    }
    if !summary.warnings.is_empty() {
        let items: String = summary
            .warnings
            .iter()
            .map(|w| format!("<li>{}</li>", page::escape(w)))
            .collect();
        page.section("warnings", "Warnings", format!("<ul>{items}</ul>"));
    }
    page.section("figures", "Figures", page::figures(dir, caption)?);
    page.section("frequencies", "Natural frequencies", frequencies(&summary));
    // The provenance's fields in their order, as summary.json writes them.
    page.section(
        "provenance",
        "Provenance",
        page::fields_table(&serde_json::to_value(provenance)?, &[]),
    );
    Ok(page.html())
}

/// summary.json as the report reads it.
type Summary = RunSummary<StationValues>;

/// The entry of a station and quantity in the summary.
fn entry<'a>(summary: &'a Summary, station: &str, quantity: &str) -> Option<&'a StationValues> {
    summary
        .stations
        .iter()
        .find(|e| e.text("name") == station && e.text("quantity") == quantity)
}

fn key_results(page: &mut Page, summary: &Summary) {
    let p = &summary.provenance;
    page.key_result("bridge", p.bridge.clone());
    page.key_result("vehicle", p.vehicle.clone());
    page.key_result("speed", format!("{} km/h", number(Some(p.speed_kmh))));
    let station = summary.rdm_station.as_deref().unwrap_or("–");
    page.key_result("station (RDM station)", station.to_string());
    for (label, quantity) in [("DAF_u", "deflection"), ("DAF_M", "bending_moment")] {
        let value = entry(summary, station, quantity).map_or("–".into(), |e| {
            format!(
                "{} (change over the last modes {}; the paper's plain modal sum {})",
                number(e.number("daf")),
                fixed(e.number("daf_change"), 4),
                number(e.number("daf_paper"))
            )
        });
        page.key_result(&format!("converged {label}"), value);
    }
    page.key_result(
        "converged RDM = DAF_u / DAF_M",
        format!(
            "{} (the paper's: {})",
            number(summary.rdm),
            number(summary.rdm_paper)
        ),
    );
    let entries = &summary.stations;
    let unsettled = entries
        .iter()
        .filter(|e| e.flag("converged") == Some(false))
        .count();
    page.key_result(
        "convergence in the modes",
        format!(
            "{} modes; {} of {} station quantities change by more than the tolerance over the \
             last modes",
            number(Some(p.modes as f64)),
            unsettled,
            entries.len()
        ),
    );
    page.key_result("warnings", summary.warnings.len().to_string());
}

/// The code factors of the RDM station's deflection and moment (empty for a summary without
/// them).
fn station_codes(summary: &Summary) -> Vec<StationCodeFactors> {
    let station = summary.rdm_station.as_deref().unwrap_or("");
    summary
        .design_codes
        .iter()
        .filter(|c| {
            c.station == station
                && matches!(c.quantity, Quantity::Deflection | Quantity::BendingMoment)
        })
        .cloned()
        .collect()
}
/// The key result of the codes: each code's 1 + IM of the moment at the RDM station.
fn code_key_result(codes: &[StationCodeFactors]) -> Option<String> {
    let moment = codes
        .iter()
        .find(|c| c.quantity == Quantity::BendingMoment)?;
    let values: Vec<String> = moment
        .factors
        .iter()
        .map(|f| format!("{} {:.2}", crate::design_codes::label(f), f.daf()))
        .collect();
    Some(values.join("; "))
}

/// The table of the codes at the RDM station: each code's case, clause and basis, its 1 + IM of
/// the deflection and the moment, and the computed DAF over it.
fn codes_table(summary: &Summary, codes: &[StationCodeFactors]) -> String {
    let daf = |quantity: &str| {
        let station = summary.rdm_station.as_deref().unwrap_or("");
        entry(summary, station, quantity).and_then(|e| e.number("daf"))
    };
    let (daf_u, daf_m) = (daf("deflection"), daf("bending_moment"));
    let of = |q: Quantity| codes.iter().find(|c| c.quantity == q);
    let Some(moment) = of(Quantity::BendingMoment) else {
        return String::new();
    };
    let header: Vec<String> = [
        "code (case)",
        "clause",
        "basis",
        "1 + IM, deflection [-]",
        "1 + IM, moment [-]",
        "computed DAF_M / code [-]",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<String>> = moment
        .factors
        .iter()
        .map(|f| {
            let u = of(Quantity::Deflection).and_then(|c| crate::design_codes::same_case(c, f));
            vec![
                crate::design_codes::label(f),
                f.clause.clone(),
                f.basis.clone(),
                fixed(u.map(|g| g.daf()), 3),
                fixed(Some(f.daf()), 3),
                fixed(daf_m.map(|d| d / f.daf()), 3),
            ]
        })
        .collect();
    format!(
        "<p>At {}: the converged DAF_u = {} and DAF_M = {} against the dynamic allowance \
         that each code gives for this station and quantity, read as docs/design-codes.md \
         states (the code's own frequency formula and vbi's computed frequency for JTG D60). \
         design_codes.csv holds every station.</p>{}",
        page::escape(&moment.station),
        fixed(daf_u, 4),
        fixed(daf_m, 4),
        page::table(&header, &rows)
    )
}

/// Scale and unit of a quantity in the report's tables.
fn unit_of(quantity: &str) -> (f64, &'static str) {
    match quantity {
        "deflection" => (1e3, "mm"),
        "bending_moment" => (1e-3, "kN·m"),
        _ => (1e-3, "kN"),
    }
}

fn stations(summary: &Summary) -> String {
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
    let rows: Vec<Vec<String>> = summary
        .stations
        .iter()
        .map(|e| {
            let quantity = e.text("quantity");
            let (scale, unit) = unit_of(quantity);
            let scaled = |name: &str| number(e.number(name).map(|x| x * scale));
            vec![
                e.text("name").to_string(),
                quantity.replace('_', " "),
                unit.to_string(),
                scaled("static_max"),
                scaled("dynamic_max"),
                number(e.number("daf")),
                fixed(e.number("daf_change"), 4),
                number(e.number("daf_paper")),
                number(e.number("convergence_mode_paper")),
                number(e.number("cutoff_k1")),
                number(e.number("cutoff_k2")),
            ]
        })
        .collect();
    format!(
        "<p>DAF: the converged (static-corrected) DAF with all modes; the change is its largest \
         change over the last fifth of the modes kept. The paper's DAF is the plain modal sum, \
         with its convergence mode CM and the cut-off modes K1, K2 (numbers of modes). Extremes \
         are signed: deflection downward negative, sagging moment positive.</p>{}",
        page::table(&header, &rows)
    )
}

fn frequencies(summary: &Summary) -> String {
    let rows: Vec<Vec<String>> = summary
        .frequencies_hz
        .iter()
        .enumerate()
        .map(|(k, v)| vec![(k + 1).to_string(), number(Some(*v))])
        .collect();
    page::table(&["mode".into(), "frequency [Hz]".into()], &rows)
}
