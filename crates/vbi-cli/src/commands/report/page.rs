//! The HTML page of a report: a key-results box first, a table of contents, then numbered
//! sections; tables with units in their headers and numbers as people read them; figures inline
//! (SVG) at a readable width with a sentence caption. Self-contained: no script, no external
//! file.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

/// HTML-escaped text.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A number as a report shows it: a whole number without decimals; otherwise four decimals for
/// magnitudes from 10⁻⁴ to 10⁵, and three significant digits in scientific form beyond; `–` for
/// a missing or non-finite value.
pub fn number(value: Option<f64>) -> String {
    match value {
        Some(x) if x.is_finite() => {
            if x.fract() == 0.0 && x.abs() < 1e15 {
                format!("{x:.0}")
            } else if (1e-4..1e5).contains(&x.abs()) {
                format!("{x:.4}")
            } else {
                format!("{x:.3e}")
            }
        }
        _ => "–".into(),
    }
}

/// A number with a fixed number of decimals (a change of a DAF: `0.0008`); `–` when missing.
pub fn fixed(value: Option<f64>, decimals: usize) -> String {
    match value {
        Some(x) if x.is_finite() => format!("{x:.decimals$}"),
        _ => "–".into(),
    }
}

/// A table cell's text as a report shows it: numbers by [`number`], text as it is.
pub fn cell(text: &str) -> String {
    match text.parse::<f64>() {
        Ok(x) => number(Some(x)),
        Err(_) if text.is_empty() => "–".into(),
        Err(_) => text.to_string(),
    }
}

/// An HTML table from a header (units in brackets) and rows of already formatted cells.
pub fn table(header: &[String], rows: &[Vec<String>]) -> String {
    let mut s = String::from("<table><thead><tr>");
    for h in header {
        let _ = write!(s, "<th>{}</th>", escape(h));
    }
    s.push_str("</tr></thead><tbody>");
    for row in rows {
        s.push_str("<tr>");
        for (i, c) in row.iter().enumerate() {
            let class = if i == 0 { " class=\"name\"" } else { "" };
            let _ = write!(s, "<td{class}>{}</td>", escape(c));
        }
        s.push_str("</tr>");
    }
    s.push_str("</tbody></table>");
    s
}

/// A report page under construction.
pub struct Page {
    title: String,
    key_results: Vec<(String, String)>,
    sections: Vec<(String, String, String)>,
}

impl Page {
    /// An empty page.
    pub fn new(title: &str) -> Page {
        Page {
            title: title.to_string(),
            key_results: Vec::new(),
            sections: Vec::new(),
        }
    }

    /// A line of the key-results box.
    pub fn key_result(&mut self, label: &str, value: String) {
        self.key_results.push((label.to_string(), value));
    }

    /// A section (its anchor `id`, its heading and its HTML body), listed in the contents.
    pub fn section(&mut self, id: &str, heading: &str, body: String) {
        self.sections
            .push((id.to_string(), heading.to_string(), body));
    }

    /// The whole document.
    pub fn html(&self) -> String {
        let mut html = String::new();
        let _ = write!(
            html,
            "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
             <title>{}</title><style>{STYLE}</style></head><body><h1>{}</h1>",
            escape(&self.title),
            escape(&self.title)
        );
        html.push_str("<section id=\"key-results\"><h2>Key results</h2><table class=\"key\">");
        for (label, value) in &self.key_results {
            let _ = write!(
                html,
                "<tr><th>{}</th><td>{}</td></tr>",
                escape(label),
                escape(value)
            );
        }
        html.push_str("</table></section><nav id=\"contents\"><h2>Contents</h2><ol>");
        for (id, heading, _) in &self.sections {
            let _ = write!(html, "<li><a href=\"#{id}\">{}</a></li>", escape(heading));
        }
        html.push_str("</ol></nav>");
        for (i, (id, heading, body)) in self.sections.iter().enumerate() {
            let _ = write!(
                html,
                "<section id=\"{id}\"><h2>{}. {}</h2>{body}</section>",
                i + 1,
                escape(heading)
            );
        }
        html.push_str("</body></html>\n");
        html
    }
}

const STYLE: &str = "body{font-family:sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;\
line-height:1.45;color:#222}h1{font-size:1.7em}h2{font-size:1.3em;margin-top:2em}\
table{border-collapse:collapse;margin:1em 0;font-size:14px}\
td,th{border:1px solid #ccc;padding:4px 8px;text-align:right}td.name{text-align:left}\
th{background:#f0f0f0}table.key{font-size:16px}table.key th,table.key td{text-align:left}\
#key-results{border:2px solid #2a6;padding:0 1em 1em;background:#f4fbf6}\
pre{background:#f7f7f7;padding:1em;overflow:auto}figure{margin:2em 0}\
figure svg{width:100%;height:auto;max-width:1200px}figcaption{font-size:14px;color:#444}";

/// The SVG figures of a directory, sorted by name: (file stem, the `<svg>` element).
pub fn svg_figures(dir: &Path) -> Result<Vec<(String, String)>> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| {
            d.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "svg"))
                // A hidden `.stem.partial.svg` is a figure still being drawn (or abandoned).
                .filter(|p| {
                    !p.file_name()
                        .is_some_and(|n| n.to_string_lossy().starts_with('.'))
                })
                .collect()
        })
        .unwrap_or_default();
    paths.sort();
    paths
        .iter()
        .map(|path| {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("reading {}", path.display()))?;
            let svg = text.find("<svg").map_or(text.as_str(), |i| &text[i..]);
            if !svg.trim_end().ends_with("</svg>") {
                anyhow::bail!(
                    "{} is not a whole SVG figure (torn or foreign); draw the figures again",
                    path.display()
                );
            }
            let stem = path
                .file_stem()
                .map(|s| s.to_string_lossy().to_string())
                .unwrap_or_default();
            Ok((stem, svg.to_string()))
        })
        .collect()
}

/// The figures section's body: every SVG figure of `dir` with its caption, or a sentence
/// saying there is none.
pub fn figures(dir: &Path, caption: impl Fn(&str) -> String) -> Result<String> {
    let figures: String = svg_figures(dir)?
        .iter()
        .map(|(stem, svg)| figure(svg, &caption(stem)))
        .collect();
    Ok(if figures.is_empty() {
        "<p>No figures in the directory.</p>".into()
    } else {
        figures
    })
}

/// A two-column table of a JSON object's fields in their order (`item`, `value`; underscores
/// read as spaces), without the fields named in `skip`.
pub fn fields_table(value: &serde_json::Value, skip: &[&str]) -> String {
    let rows: Vec<Vec<String>> = match value {
        serde_json::Value::Object(fields) => fields
            .iter()
            .filter(|(k, _)| !skip.contains(&k.as_str()))
            .map(|(k, v)| {
                let value = match v {
                    serde_json::Value::String(s) => s.clone(),
                    other => other.to_string(),
                };
                vec![k.replace('_', " "), value]
            })
            .collect(),
        _ => Vec::new(),
    };
    table(&["item".into(), "value".into()], &rows)
}

/// A figure with its caption.
pub fn figure(svg: &str, caption: &str) -> String {
    format!(
        "<figure>{svg}<figcaption>{}</figcaption></figure>",
        escape(caption)
    )
}

/// A sentence that says what a figure of vbi's shows, from its file stem.
pub fn caption(stem: &str) -> String {
    let quantity = |q: &str| match q {
        "daf_u_paper" => "The paper's deflection DAF_u (plain partial modal sums)",
        "daf_m_paper" => "The paper's bending-moment DAF_M (plain partial modal sums)",
        "rdm_paper" => "The paper's RDM = DAF_u / DAF_M",
        "daf_m" => "The converged (static-corrected) bending-moment DAF_M",
        "rdm" => "The converged RDM",
        _ => "The DAF",
    };
    if let Some((q, field)) = stem.split_once("_by_modes_per_") {
        return format!(
            "{} against the number of modes K, one curve per value of {field}, mean over the \
             roughness samples.",
            quantity(q)
        );
    }
    let text = match stem {
        "daf_vs_span_length" => "The final DAFs and RDM against the span length, one curve per number of spans.",
        "daf_vs_span_count" => "The final DAFs and RDM against the number of spans, one curve per span length.",
        "participation_deflection" => "Deck-wide modal participation of the deflection (Eq. 30), mean over the cases of each bridge, first 20 modes.",
        "participation_moment" => "Deck-wide modal participation of the bending moment (Eq. 30), mean over the cases of each bridge, first 20 modes.",
        "assessment_daf_u" => "Converged DAF_u over all cases: histogram, empirical distribution and the Monte Carlo convergence of each group's mean.",
        "assessment_daf_m" => "Converged DAF_M over all cases: histogram, empirical distribution and the Monte Carlo convergence of each group's mean.",
        "assessment_rdm" => "Converged RDM over all cases: histogram, empirical distribution and the Monte Carlo convergence of each group's mean.",
        "daf_vs_static" => "Converged DAF_M against the static moment at the RDM station, one colour per bridge: heavier loading, lower DAF.",
        "history_deflection" => "Deflection at the RDM station against time: the converged dynamic response, the paper's modal sum and the exact static response.",
        "history_moment" => "Bending moment at the RDM station against time: the converged dynamic response, the paper's modal sum and the exact static response.",
        "daf_by_modes" => "DAF and RDM at the RDM station against the number of modes: the converged series and the paper's plain partial sums.",
        "modal_decomposition" => "The deflection at the RDM station decomposed into its first six modal contributions (the paper's Fig. 10).",
        "design_codes" => "The computed converged DAFs against the impact factors of the design codes.",
        "plan" => "Plan of the model: girder lines, slab strips, diaphragms, bearings, the stations and the wheel paths.",
        "mode_shapes" => "The first mode shapes along each deck line.",
        _ => return format!("Figure {stem}."),
    };
    text.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_whole_numbers_decimals_or_scientific() {
        assert_eq!(number(Some(3.0)), "3");
        assert_eq!(number(Some(1.123456)), "1.1235");
        assert_eq!(number(Some(679105.2)), "6.791e5");
        assert_eq!(number(Some(-0.0021)), "-0.0021");
        assert_eq!(number(Some(2.5e-6)), "2.500e-6");
        assert_eq!(number(None), "–");
        assert_eq!(number(Some(f64::NAN)), "–");
        assert_eq!(cell("12"), "12");
        assert_eq!(cell("span1_mid_g2"), "span1_mid_g2");
        assert_eq!(cell(""), "–");
    }

    #[test]
    fn a_page_opens_with_the_key_results_then_the_contents_then_numbered_sections() {
        let mut page = Page::new("t <1>");
        page.key_result("DAF", "1.1".into());
        page.section("a", "First", "<p>x</p>".into());
        page.section("b", "Second", String::new());
        let html = page.html();
        let key = html.find("id=\"key-results\"").unwrap();
        let nav = html.find("id=\"contents\"").unwrap();
        let first = html.find("<section id=\"a\"><h2>1. First</h2>").unwrap();
        assert!(key < nav && nav < first, "{html}");
        assert!(html.contains("<a href=\"#b\">Second</a>"));
        assert!(html.contains("<title>t &lt;1&gt;</title>"));
    }
}
