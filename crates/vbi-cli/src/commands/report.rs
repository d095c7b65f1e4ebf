//! `vbi report DIR [--out FILE]`: a self-contained HTML report of a study's output directory
//! (inputs, provenance, tables, figures as inline SVG, and the cut-off modes in the form of the
//! paper's Table 2). Default output: `DIR/report.html`.
//!
//! It reads the directory through [`crate::study_records`]: the manifest, and the journal's
//! typed case records for the provenance and the headline figures; the aggregated tables
//! (`summary.csv`, `cutoff_modes.csv`) are shown as `vbi study` wrote them.

use crate::console::outln;
use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context, Result};

use crate::output::write_atomic;
use crate::study_records::{read_journal, read_manifest, CaseRecord, Manifest, SUMMARY_METRICS};

/// Arguments of `vbi report`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// A `vbi study` output directory (or a merged one).
    pub dir: PathBuf,
    /// The HTML file to write (default: DIR/report.html).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// The paper's Table 2 (docs/verification.md §16): K1 and K2 for 2, 3, 4 spans.
/// Rows: K1 deflection, K2 deflection, K1 moment, K2 moment.
const PAPER_TABLE_2: [[usize; 3]; 4] = [[3, 3, 4], [6, 7, 8], [7, 8, 9], [15, 20, 25]];

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

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
        let mut s = String::from("<table><thead><tr>");
        for h in &self.header {
            let _ = write!(s, "<th>{}</th>", escape(h));
        }
        s.push_str("</tr></thead><tbody>");
        for row in &self.rows {
            s.push_str("<tr>");
            for c in row {
                let _ = write!(s, "<td>{}</td>", escape(c));
            }
            s.push_str("</tr>");
        }
        s.push_str("</tbody></table>");
        s
    }
}

fn short(cell: &str) -> String {
    match cell.parse::<f64>() {
        Ok(x) if x.fract() != 0.0 => format!("{x:.4}"),
        _ => cell.to_string(),
    }
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    let dir = &args.dir;
    let manifest = read_manifest(dir)?.ok_or_else(|| {
        anyhow!(
            "{} is not a study output directory (no study.json)",
            dir.display()
        )
    })?;
    let records = finished_records(dir, &manifest)?;
    let not_finished = |e: anyhow::Error| {
        anyhow!("{e:#}; the study has not finished: run `vbi study FILE --resume` first")
    };
    let summary = Table::read(&dir.join("summary.csv")).map_err(not_finished)?;
    let cutoff = Table::read(&dir.join("cutoff_modes.csv")).map_err(not_finished)?;
    let timing = std::fs::read_to_string(dir.join("timing.json")).ok();

    let mut html = String::new();
    let title = format!("vbi study report: {}", manifest.name);
    let _ = write!(
        html,
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title>\
         <style>body{{font-family:sans-serif;max-width:1300px;margin:2em auto;padding:0 1em}}\
         table{{border-collapse:collapse;margin:1em 0;font-size:13px}}\
         td,th{{border:1px solid #ccc;padding:3px 7px;text-align:right}}\
         th{{background:#f0f0f0}} pre{{background:#f7f7f7;padding:1em;overflow:auto}}\
         figure{{margin:1.5em 0}} svg{{max-width:100%;height:auto}}</style></head><body>",
        escape(&title)
    );
    let _ = write!(html, "<h1>{}</h1>", escape(&title));
    provenance(&mut html, &manifest, &records, timing.as_deref());
    stations(&mut html, &records);
    headline(&mut html, &records);
    table_2(&mut html, &cutoff);
    means(&mut html, &summary);
    let _ = write!(
        html,
        "<h2>Cut-off modes per group (cutoff_modes.csv)</h2>{}",
        cutoff.html()
    );
    figures(&mut html, dir)?;
    inputs(&mut html, &manifest);
    html.push_str("</body></html>\n");
    let out = args.out.clone().unwrap_or_else(|| dir.join("report.html"));
    write_atomic(&out, html.as_bytes())?;
    outln!("report written to {}", out.display());
    Ok(())
}

/// The records of the directory's cases (its shard), in case order; an error naming how many
/// are missing when the study has not finished.
fn finished_records(dir: &Path, manifest: &Manifest) -> Result<Vec<CaseRecord>> {
    let (records, _) = read_journal(&dir.join("journal.jsonl"))?;
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
        "<h2>Provenance</h2><table>\
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
        "<h2>Stations</h2><p>DAF_u, DAF_M, RDM, the convergence modes and the figures are \
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
        recorded[i].3.extend(r.daf);
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
        "<h2>Against the paper's statements</h2><table>\
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
        "<h2>Cut-off modes (the paper's Table 2)</h2><p>K1 and K2: the smallest number of modes \
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

/// Means and standard deviations over the samples, per parameter group.
fn means(html: &mut String, summary: &Table) {
    html.push_str("<h2>Means over the roughness samples (summary.csv)</h2>");
    let metric_c = summary.column("metric");
    let mean_c = summary.column("mean");
    let std_c = summary.column("std");
    if let (Some(mc), Some(mean), Some(std)) = (metric_c, mean_c, std_c) {
        let params = &summary.header[..mc];
        let mut groups: BTreeMap<usize, (Vec<String>, BTreeMap<String, String>)> = BTreeMap::new();
        let mut order: Vec<Vec<String>> = Vec::new();
        for row in &summary.rows {
            let key = row[..mc].to_vec();
            let i = match order.iter().position(|k| *k == key) {
                Some(i) => i,
                None => {
                    order.push(key.clone());
                    order.len() - 1
                }
            };
            let entry = groups.entry(i).or_insert_with(|| (key, BTreeMap::new()));
            let text = if row[mean].is_empty() {
                "-".to_string()
            } else {
                format!("{} ± {}", short(&row[mean]), short(&row[std]))
            };
            entry.1.insert(row[mc].clone(), text);
        }
        let metrics = SUMMARY_METRICS.map(|m| m.name);
        html.push_str("<table><tr>");
        for p in params {
            let _ = write!(html, "<th>{}</th>", escape(p));
        }
        for m in metrics {
            let _ = write!(html, "<th>{m} (mean ± std)</th>");
        }
        html.push_str("</tr>");
        for (key, values) in groups.values() {
            html.push_str("<tr>");
            for k in key {
                let _ = write!(html, "<td>{}</td>", escape(k));
            }
            for m in metrics {
                let _ = write!(
                    html,
                    "<td>{}</td>",
                    escape(values.get(m).map(String::as_str).unwrap_or("-"))
                );
            }
            html.push_str("</tr>");
        }
        html.push_str("</table>");
    }
}

/// The figures, inline SVG.
fn figures(html: &mut String, dir: &Path) -> Result<()> {
    html.push_str("<h2>Figures</h2>");
    let mut svgs: Vec<PathBuf> = std::fs::read_dir(dir.join("figures"))
        .map(|d| {
            d.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "svg"))
                .collect()
        })
        .unwrap_or_default();
    svgs.sort();
    if svgs.is_empty() {
        html.push_str("<p>No figures (the study ran with --no-figures, or as a shard).</p>");
    }
    for path in &svgs {
        let svg =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let svg = svg
            .find("<svg")
            .map_or(svg.as_str(), |i| &svg[i..])
            .to_string();
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_default();
        let _ = write!(
            html,
            "<figure>{svg}<figcaption>{}</figcaption></figure>",
            escape(&name)
        );
    }

    Ok(())
}

/// The study file and its normalised specification.
fn inputs(html: &mut String, manifest: &Manifest) {
    let _ = write!(
        html,
        "<h2>Inputs</h2><p>The study file:</p><pre>{}</pre>\
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
