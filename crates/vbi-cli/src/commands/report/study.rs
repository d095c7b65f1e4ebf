//! The report of a study's output directory: key results (the converged DAFs and RDM over the
//! cases with their characteristic values and convergence), the stations, the statistics per
//! group, the cut-off modes, the comparison with the paper (only for the paper's study), the
//! figures with captions, the provenance and the inputs.
//!
//! It reads the directory through [`crate::study_records`]: the manifest, and the journal's
//! typed case records for the provenance and the key results; the aggregated tables
//! (`summary.csv`, `cutoff_modes.csv`) as `vbi study` wrote them.

use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use vbi::study::assessment::{assess, MINIMUM_CHARACTERISTIC_SAMPLES};

use super::page::{self, caption, escape, figure, number, svg_figures, Page};
use crate::study_records::{read_journal, CaseRecord, Manifest, SUMMARY_METRICS};

/// The paper's Table 2 (docs/verification.md §16): K1 and K2 for 2, 3, 4 spans.
/// Rows: K1 deflection, K2 deflection, K1 moment, K2 moment.
const PAPER_TABLE_2: [[usize; 3]; 4] = [[3, 3, 4], [6, 7, 8], [7, 8, 9], [15, 20, 25]];

/// A CSV file as header and rows.
struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    fn read(path: &Path) -> Result<Table> {
        let mut reader =
            csv::Reader::from_path(path).with_context(|| format!("reading {}", path.display()))?;
        let header = reader.headers()?.iter().map(str::to_string).collect();
        let rows = reader
            .records()
            .map(|r| r.map(|r| r.iter().map(str::to_string).collect()))
            .collect::<Result<_, _>>()
            .with_context(|| format!("reading {}", path.display()))?;
        Ok(Table { header, rows })
    }

    fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    fn html(&self) -> String {
        let rows: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|r| r.iter().map(|c| page::cell(c)).collect())
            .collect();
        page::table(&self.header, &rows)
    }
}

/// The report of the study in `dir`, as an HTML document.
pub fn report(dir: &Path, manifest: &Manifest) -> Result<String> {
    let records = finished_records(dir, manifest)?;
    let not_finished = |e: anyhow::Error| {
        anyhow!("{e:#}; the study has not finished: run `vbi study FILE --resume` first")
    };
    let summary = Table::read(&dir.join("summary.csv")).map_err(not_finished)?;
    let cutoff = Table::read(&dir.join("cutoff_modes.csv")).map_err(not_finished)?;
    let timing = std::fs::read_to_string(dir.join("timing.json")).ok();

    let mut page = Page::new(&format!("vbi study report: {}", manifest.name));
    let ok: Vec<&CaseRecord> = records.iter().filter(|r| r.error.is_none()).collect();
    let codes = crate::design_codes::study_summary(&ok);
    key_results(&mut page, manifest, &records, &codes);
    let mut body = String::new();
    stations(&mut body, &records);
    page.section("stations", "Stations", body);
    let mut body = String::new();
    means(&mut body, &summary);
    page.section("statistics", "Statistics per group of cases", body);
    let mut body = String::new();
    table_2(&mut body, &cutoff);
    let _ = write!(
        body,
        "<p>Per group (cutoff_modes.csv):</p>{}",
        cutoff.html()
    );
    page.section(
        "cutoff-modes",
        "Cut-off modes K1 and K2 (the paper's Table 2)",
        body,
    );
    if !codes.is_empty() {
        page.section(
            "design-codes",
            "Computed DAF against the design codes",
            design_codes(&codes, ok.len()),
        );
    }
    if is_paper_study(manifest) {
        let mut body = String::new();
        headline(&mut body, &records);
        page.section("paper", "Against the paper's statements", body);
    }
    page.section("figures", "Figures", figures(dir)?);
    let mut body = String::new();
    provenance(&mut body, manifest, &records, timing.as_deref());
    page.section("provenance", "Provenance", body);
    let mut body = String::new();
    inputs(&mut body, manifest);
    page.section("inputs", "Inputs", body);
    Ok(page.html())
}

/// The table of the codes over the cases: each code case's 1 + IM for the moment at the RDM
/// station (range over the cases), and in how many cases the computed DAF_u and DAF_M exceeded
/// the code's value.
fn design_codes(codes: &[crate::design_codes::StudyCodeSummary], cases: usize) -> String {
    let header: Vec<String> = [
        "code (case)",
        "1 + IM, moment [-]",
        "cases with DAF_u above it",
        "cases with DAF_M above it",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<String>> = codes
        .iter()
        .map(|c| {
            // A fatigue factor is no peak DAF: it is listed, not compared (issue 46).
            let (u, m) = if c.is_fatigue_factor() {
                let not = "fatigue factor: not compared".to_string();
                (not.clone(), not)
            } else {
                (
                    format!("{} of {}", c.exceeded_u, cases),
                    format!("{} of {}", c.exceeded_m, cases),
                )
            };
            vec![c.label(), c.value_text(3), u, m]
        })
        .collect();
    format!(
        "<p>Each code's dynamic allowance for the RDM station of the cases, read as \
         docs/design-codes.md states, against the converged DAFs of the {cases} finished \
         cases; design_codes.csv holds every case's values. The fatigue factors (EN 1991-2 \
         Annex B's φ_fat, AASHTO LRFD's 15 %) act on the fatigue load's stress ranges and are \
         calibrated on damage: they are listed, not compared with the peak DAFs.</p>{}",
        page::table(&header, &rows)
    )
}

/// Whether the study is the paper's (its bridges are the paper's presets and its vehicle the
/// paper's truck): only then does the report compare with the paper.
fn is_paper_study(manifest: &Manifest) -> bool {
    let vehicle = manifest
        .spec
        .get("scenario.vehicle.name")
        .map(String::as_str);
    vehicle == Some("\"tractor-semitrailer-5axle\"")
        && manifest
            .cases
            .iter()
            .all(|c| c.bridge.starts_with("paper-"))
}

/// The distinct values of `values`, in order, joined.
fn distinct<'a>(values: impl Iterator<Item = &'a str>) -> String {
    let mut seen: Vec<&str> = Vec::new();
    for v in values {
        if !seen.contains(&v) {
            seen.push(v);
        }
    }
    seen.join(", ")
}

/// The key-results box: what was studied, and the converged DAFs and RDM over each bridge's
/// cases (mean, 95th percentile named for what its sample count supports, with its bootstrap
/// interval, range) with their convergence.
fn key_results(
    page: &mut Page,
    manifest: &Manifest,
    records: &[CaseRecord],
    codes: &[crate::design_codes::StudyCodeSummary],
) {
    let ok: Vec<&CaseRecord> = records.iter().filter(|r| r.error.is_none()).collect();
    page.key_result(
        "bridges",
        distinct(manifest.cases.iter().map(|c| c.bridge.as_str())),
    );
    let vehicle = manifest
        .spec
        .get("scenario.vehicle.name")
        .map(|v| v.trim_matches('"').to_string())
        .unwrap_or_else(|| "–".into());
    page.key_result("vehicle", vehicle);
    page.key_result(
        "cases",
        format!(
            "{} ({} failed), {} roughness sample(s) per combination",
            records.len(),
            records.len() - ok.len(),
            manifest.samples
        ),
    );
    page.key_result(
        "station (RDM station of the cases)",
        distinct(ok.iter().filter_map(|r| r.rdm_station.as_deref())),
    );
    // Each bridge's cases apart: a value pooled over bridges is no bridge's (issue 46, item 9).
    let mut bridges: Vec<&str> = Vec::new();
    for case in &manifest.cases {
        if !bridges.contains(&case.bridge.as_str()) {
            bridges.push(case.bridge.as_str());
        }
    }
    let bridge_of_case: std::collections::HashMap<&str, &str> = manifest
        .cases
        .iter()
        .map(|c| (c.id.as_str(), c.bridge.as_str()))
        .collect();
    let bridge_of = |record: &CaseRecord| bridge_of_case.get(record.id.as_str()).copied();
    let seed = vbi::study::stable_hash(manifest.study_hash.as_bytes());
    for bridge in &bridges {
        let of_bridge: Vec<&CaseRecord> = ok
            .iter()
            .copied()
            .filter(|r| bridge_of(r) == Some(*bridge))
            .collect();
        // The bridge's cases are road samples of one combination, or several combinations
        // (speeds, roads, …) pooled: then the percentile is of the mixture, no fractile of road
        // samples, and each combination's is in the statistics table.
        let mut combinations: Vec<&Vec<String>> = Vec::new();
        for case in manifest.cases.iter().filter(|c| c.bridge == *bridge) {
            if !combinations.contains(&&case.parameters) {
                combinations.push(&case.parameters);
            }
        }
        let pooled = combinations.len() > 1;
        for (label, value) in [
            (
                "converged DAF_u",
                (|r: &CaseRecord| r.daf_u) as fn(&CaseRecord) -> Option<f64>,
            ),
            ("converged DAF_M", |r| r.daf_m),
            ("converged RDM = DAF_u / DAF_M", |r| r.rdm),
        ] {
            let values: Vec<f64> = of_bridge.iter().filter_map(|r| value(r)).collect();
            let text = match assess(&values, seed) {
                Ok(a) => format!(
                    "mean {}, {} {} [95 % interval {} – {}], range {} – {} over {} cases",
                    number(Some(a.mean)),
                    if pooled {
                        format!(
                            "the 95th percentile of its {} combinations' cases together (not a \
                             characteristic value: each combination's is in the statistics table)",
                            combinations.len()
                        )
                    } else {
                        a.fractile_name()
                    },
                    number(Some(a.characteristic)),
                    number(Some(a.characteristic_low)),
                    number(Some(a.characteristic_high)),
                    number(Some(a.min)),
                    number(Some(a.max)),
                    a.count
                ),
                Err(_) => "–".into(),
            };
            if bridges.len() == 1 {
                page.key_result(label, text);
            } else {
                page.key_result(&format!("{label}, {bridge}"), text);
            }
        }
    }
    let changes: Vec<f64> = ok
        .iter()
        .flat_map(|r| [r.daf_u_change, r.daf_m_change])
        .flatten()
        .collect();
    let unsettled = ok
        .iter()
        .filter(|r| r.warnings.iter().any(|w| w.contains("still changes by")))
        .count();
    if !codes.is_empty() {
        let values: Vec<String> = codes
            .iter()
            .map(|c| format!("{} {}", c.label(), c.value_text(2)))
            .collect();
        page.key_result("design codes, 1 + IM of the moment", values.join("; "));
    }
    page.key_result(
        "convergence in the modes",
        format!(
            "largest change of a converged DAF over the last fifth of the modes: {}; {} case(s) \
             beyond the tolerance",
            page::fixed(changes.iter().copied().reduce(f64::max), 4),
            unsettled
        ),
    );
}

/// The records of the directory's cases (its shard), in case order; an error naming how many
/// are missing when the study has not finished.
fn finished_records(dir: &Path, manifest: &Manifest) -> Result<Vec<CaseRecord>> {
    let path = dir.join("journal.jsonl");
    let records = read_journal(&path)?.sound_records(&path)?;
    let mut by_id: HashMap<String, CaseRecord> =
        records.into_iter().map(|r| (r.id.clone(), r)).collect();
    let own = manifest.own_cases()?;
    let finished: Vec<CaseRecord> = own.iter().filter_map(|c| by_id.remove(&c.id)).collect();
    if finished.len() < own.len() {
        bail!(
            "{}: {} of {} cases have no result; the study has not finished: run `vbi study FILE \
             --resume` first",
            dir.display(),
            own.len() - finished.len(),
            own.len()
        );
    }
    Ok(finished)
}

/// Versions, hash, case counts and the last invocation's timing.
fn provenance(
    html: &mut String,
    manifest: &Manifest,
    records: &[CaseRecord],
    timing: Option<&str>,
) {
    let failed = records.iter().filter(|r| r.error.is_some()).count();
    let _ = write!(
        html,
        "<table>\
         <tr><th>vbi version</th><td>{}</td></tr>\
         <tr><th>study file</th><td>{}</td></tr>\
         <tr><th>study hash (SHA-256 of the normalised specification)</th><td>{}</td></tr>\
         <tr><th>cases</th><td>{} ({} failed)</td></tr>\
         <tr><th>roughness samples per combination</th><td>{}</td></tr></table>",
        escape(&manifest.vbi_version),
        escape(&manifest.study_file),
        escape(&manifest.study_hash),
        records.len(),
        failed,
        manifest.samples
    );
    if let Some(t) = timing {
        let _ = write!(
            html,
            "<p>Timing of the last invocation (not part of the results):</p><pre>{}</pre>",
            escape(t)
        );
    }
}

/// The stations the results stand for: the RDM station of the cases (the station of `daf_u`,
/// `daf_m`, `rdm` and the figures), and the stations and quantities of the study's `record`
/// with the range of their DAFs.
fn stations(html: &mut String, records: &[CaseRecord]) {
    let mut rdm: Vec<(&str, usize)> = Vec::new();
    for name in records.iter().filter_map(|r| r.rdm_station.as_deref()) {
        match rdm.iter_mut().find(|(n, _)| *n == name) {
            Some((_, count)) => *count += 1,
            None => rdm.push((name, 1)),
        }
    }
    let list: Vec<String> = rdm
        .iter()
        .map(|(name, count)| format!("<code>{}</code> ({count} cases)", escape(name)))
        .collect();
    let _ = write!(
        html,
        "<p>DAF_u, DAF_M, RDM, the convergence modes and the figures are \
         taken at the RDM station of each case (the station not over a support with the largest \
         static deflection; <code>rdm_station</code> in cases.csv): {}.</p>",
        if list.is_empty() {
            "none (every case failed)".to_string()
        } else {
            list.join(", ")
        }
    );
    let mut recorded: Vec<(&str, &str, &str, Vec<f64>)> = Vec::new();
    for r in records.iter().flat_map(|r| &r.station_records) {
        let (station, quantity) = (r.station.as_str(), r.quantity.name());
        let i = match recorded
            .iter()
            .position(|(s, q, _, _)| *s == station && *q == quantity)
        {
            Some(i) => i,
            None => {
                recorded.push((station, quantity, r.quantity.unit(), Vec::new()));
                recorded.len() - 1
            }
        };
        recorded[i].3.extend(r.number("daf"));
    }
    if recorded.is_empty() {
        return;
    }
    html.push_str(
        "<p>Recorded stations (the study's <code>record</code>; every case in \
         station_records.csv):</p><table><tr><th>station</th><th>quantity</th><th>unit</th>\
         <th>cases with a DAF</th><th>converged DAF min – max</th></tr>",
    );
    for (station, quantity, unit, dafs) in &recorded {
        let range = if dafs.is_empty() {
            "-".to_string()
        } else {
            let lo = dafs.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = dafs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            format!("{lo:.3} – {hi:.3}")
        };
        let _ = write!(
            html,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(station),
            escape(quantity),
            escape(unit),
            dafs.len(),
            range
        );
    }
    html.push_str("</table>");
}

/// The headline figures of every case against the paper's statements.
fn headline(html: &mut String, records: &[CaseRecord]) {
    let values = |value: fn(&CaseRecord) -> Option<f64>| -> Vec<f64> {
        records.iter().filter_map(value).collect()
    };
    let modes = |k: Option<usize>| k.map(|k| k as f64);
    let range = |v: &[f64]| -> String {
        if v.is_empty() {
            return "-".into();
        }
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        format!("{lo:.3} – {hi:.3}")
    };
    let max = |v: &[f64]| v.iter().copied().fold(f64::NAN, f64::max);
    let _ = write!(
        html,
        "<table>\
         <tr><th></th><th>this study (every case)</th><th>paper (§5, §4.2)</th></tr>\
         <tr><th>the paper's RDM = DAF_u / DAF_M (plain modal sums)</th><td>{}</td><td>1.00 – 1.12</td></tr>\
         <tr><th>the paper's DAF_u</th><td>{}</td><td></td></tr>\
         <tr><th>the paper's DAF_M</th><td>{}</td><td></td></tr>\
         <tr><th>largest convergence mode CM of the paper's DAF_u</th><td>{}</td><td>10</td></tr>\
         <tr><th>largest convergence mode CM of the paper's DAF_M</th><td>{}</td><td>40</td></tr>\
         <tr><th>converged RDM (static-corrected series)</th><td>{}</td><td></td></tr>\
         <tr><th>converged DAF_u</th><td>{}</td><td></td></tr>\
         <tr><th>converged DAF_M</th><td>{}</td><td></td></tr></table>\
         <p>The paper's DAFs are plain partial modal sums (DAF(K) over the first K modes). The \
         converged (static-corrected, mode-acceleration) series adds back the truncated modes' \
         quasi-static response exactly, through the influence lines. Both tend to the same \
         response as modes are added; the converged one gets there with far fewer modes, so \
         where they differ it is the bridge's DAF, and the paper's CM and K1/K2 of the moment \
         measure where the list of modes was cut (docs/paper-reproduction.md).</p>",
        range(&values(|r| r.rdm_paper)),
        range(&values(|r| r.daf_u_paper)),
        range(&values(|r| r.daf_m_paper)),
        max(&records.iter().filter_map(|r| modes(r.cm_u_paper)).collect::<Vec<_>>()),
        max(&records.iter().filter_map(|r| modes(r.cm_m_paper)).collect::<Vec<_>>()),
        range(&values(|r| r.rdm)),
        range(&values(|r| r.daf_u)),
        range(&values(|r| r.daf_m)),
    );
}

/// The cut-off modes in the form of the paper's Table 2.
fn table_2(html: &mut String, cutoff: &Table) {
    html.push_str(
        "<p>K1 and K2: the smallest number of modes \
         whose cumulative deck-wide participation (Eq. 30), averaged over the cases of a group, \
         reaches 95 % and 99 %. Ranges: the per-case values. 'Among bending modes': the same \
         counted over the vertical bending modes only (participation restricted to them and \
         renormalised; K is a number of bending modes, as a beam model would count).</p>",
    );
    let groups: Vec<String> = cutoff.rows.iter().map(|r| r[0].clone()).collect();
    let cell = |group: &str, column: &str| -> String {
        cutoff
            .rows
            .iter()
            .find(|r| r[0] == group)
            .and_then(|r| cutoff.column(column).map(|c| r[c].clone()))
            .unwrap_or_default()
    };
    let _ = write!(
        html,
        "<table><tr><th>cut-off mode</th><th colspan=\"{n}\">deflection</th>\
         <th colspan=\"{n}\">bending moment</th></tr><tr><th></th>",
        n = groups.len()
    );
    for _ in 0..2 {
        for g in &groups {
            let _ = write!(html, "<th>{}</th>", escape(g));
        }
    }
    html.push_str("</tr>");
    for (label, u, m) in [("K1", "k1_u", "k1_m"), ("K2", "k2_u", "k2_m")] {
        let _ = write!(html, "<tr><th>{label} (this study)</th>");
        for column in [u, m] {
            for g in &groups {
                let _ = write!(
                    html,
                    "<td>{} <small>({})</small></td>",
                    escape(&cell(g, column)),
                    escape(&cell(g, &format!("{column}_range")))
                );
            }
        }
        html.push_str("</tr>");
    }
    for (label, u, m) in [
        ("K1 among bending modes", "k1_u_bending", "k1_m_bending"),
        ("K2 among bending modes", "k2_u_bending", "k2_m_bending"),
    ] {
        let _ = write!(html, "<tr><th>{label} (this study)</th>");
        for column in [u, m] {
            for g in &groups {
                let _ = write!(html, "<td>{}</td>", escape(&cell(g, column)));
            }
        }
        html.push_str("</tr>");
    }
    // The paper's row, where the groups are span counts.
    let paper_index = |g: &str| -> Option<usize> {
        match g {
            "2 spans" => Some(0),
            "3 spans" => Some(1),
            "4 spans" => Some(2),
            _ => None,
        }
    };
    for (label, k) in [("K1 (paper)", 0), ("K2 (paper)", 1)] {
        let _ = write!(html, "<tr><th>{label}</th>");
        for q in [k, k + 2] {
            for g in &groups {
                let v = paper_index(g)
                    .map(|i| PAPER_TABLE_2[q][i].to_string())
                    .unwrap_or_else(|| "–".into());
                let _ = write!(html, "<td>{v}</td>");
            }
        }
        html.push_str("</tr>");
    }
    html.push_str("</table>");
}

/// Per parameter group: the converged DAFs and RDM as mean ± std and the 95th percentile of the
/// group's road samples (p95) with its bootstrap interval, called characteristic where the
/// sample count supports it ([`MINIMUM_CHARACTERISTIC_SAMPLES`]), then the paper's series and
/// cut-off modes as mean ± std.
fn means(html: &mut String, summary: &Table) {
    let column = |name: &str| summary.column(name);
    let (Some(mc), Some(mean), Some(std)) = (column("metric"), column("mean"), column("std"))
    else {
        return;
    };
    let p95 = (column("p95"), column("p95_low"), column("p95_high"));
    let mut groups: Vec<(Vec<String>, BTreeMap<String, String>)> = Vec::new();
    for row in &summary.rows {
        let key = row[..mc].to_vec();
        let i = match groups.iter().position(|(k, _)| *k == key) {
            Some(i) => i,
            None => {
                groups.push((key, BTreeMap::new()));
                groups.len() - 1
            }
        };
        let mut text = if row[mean].is_empty() {
            "–".to_string()
        } else {
            format!("{} ± {}", page::cell(&row[mean]), page::cell(&row[std]))
        };
        if let ((Some(p), Some(lo), Some(hi)), true) = (p95, HEADLINE.contains(&row[mc].as_str())) {
            if !row[p].is_empty() {
                // Characteristic only where the sample count supports the 95 % fractile.
                let count: usize = column("count")
                    .and_then(|c| row[c].parse().ok())
                    .unwrap_or(0);
                let kind = if count >= MINIMUM_CHARACTERISTIC_SAMPLES {
                    "characteristic"
                } else {
                    "not characteristic"
                };
                let _ = write!(
                    text,
                    "; p95 {} [{} – {}] ({kind}, n = {count})",
                    page::cell(&row[p]),
                    page::cell(&row[lo]),
                    page::cell(&row[hi])
                );
            }
        }
        groups[i].1.insert(row[mc].clone(), text);
    }
    html.push_str(
        "<p>Over the roughness samples of each group: mean ± standard deviation; for the \
         converged DAFs and RDM also the 95th percentile (p95) with its 95 % bootstrap interval \
         (summary.csv), the characteristic value where the group has at least 21 samples (below, \
         the sample's maximum governs it: not characteristic). All DAFs and the RDM are \
         dimensionless; CM, K1, K2 are numbers of modes.</p>",
    );
    let mut header: Vec<String> = summary.header[..mc].to_vec();
    header.extend(SUMMARY_METRICS.iter().map(|m| m.name.to_string()));
    let rows: Vec<Vec<String>> = groups
        .iter()
        .map(|(key, values)| {
            let mut row = key.clone();
            row.extend(
                SUMMARY_METRICS
                    .iter()
                    .map(|m| values.get(m.name).cloned().unwrap_or_else(|| "–".into())),
            );
            row
        })
        .collect();
    html.push_str(&page::table(&header, &rows));
}

/// The converged metrics whose characteristic value the statistics table shows.
const HEADLINE: [&str; 3] = ["daf_u", "daf_m", "rdm"];

/// The figures, inline SVG, each with its caption.
fn figures(dir: &Path) -> Result<String> {
    let figures = svg_figures(&dir.join("figures"))?;
    if figures.is_empty() {
        return Ok(
            "<p>No figures (the study ran with --no-figures, or as a shard).</p>".to_string(),
        );
    }
    Ok(figures
        .iter()
        .map(|(stem, svg)| figure(svg, &caption(stem)))
        .collect())
}

/// The study file and its normalised specification.
fn inputs(html: &mut String, manifest: &Manifest) {
    let _ = write!(
        html,
        "<p>The study file:</p><pre>{}</pre>\
         <p>The normalised specification (what the hash covers):</p><table>",
        escape(&manifest.source)
    );
    for (k, v) in &manifest.spec {
        let _ = write!(
            html,
            "<tr><th>{}</th><td style=\"text-align:left;word-break:break-all\">{}</td></tr>",
            escape(k),
            escape(v)
        );
    }
    html.push_str("</table>");
}
