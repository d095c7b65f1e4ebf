//! The assessment outputs of `vbi study` (issue 14.3), from the finished cases:
//! `convergence.csv` (the Monte Carlo convergence of each group's mean), `daf_vs_static.csv`
//! (DAF against the static response, per bridge), `cases_long.csv` (the metrics of `cases.csv`
//! in long, tidy form) and the figures `histogram_*`, `cdf_*`, `mc_convergence_*` and
//! `daf_vs_static`. The statistics are `vbi::study::assessment`'s; `summary.csv` (written by
//! the study command) carries the per-group assessment columns.

use std::path::Path;

use anyhow::Result;
use vbi::study::assessment::{empirical_cdf, histogram, linear_fit, running_mean};
use vbi::study::record::CASE_METRICS;
use vbi::study::CaseRecord;

use crate::output::{number, write_csv};
use crate::plot::{write_charts, Chart, Series, SeriesStyle};
use crate::study_records::{Manifest, ManifestCase};

/// A finished case: its manifest entry and its record.
pub type FinishedCase<'a> = (&'a ManifestCase, &'a CaseRecord);

/// A metric of a case record.
type Metric = fn(&CaseRecord) -> Option<f64>;

/// The headline metrics whose distributions the assessment shows (name, label, value): the
/// converged DAFs and RDM.
const HEADLINE: [(&str, &str, Metric); 3] = [
    ("daf_u", "converged DAF_u", |r| r.daf_u),
    ("daf_m", "converged DAF_M", |r| r.daf_m),
    ("rdm", "converged RDM", |r| r.rdm),
];

/// At most this many groups get a curve of their own in a figure; beyond, one curve of all cases.
const MAX_CURVES: usize = 8;

/// The groups of cases (the same varied fields but the sample), in case order.
pub fn groups<'a>(cases: &[FinishedCase<'a>]) -> Vec<(Vec<String>, Vec<FinishedCase<'a>>)> {
    let mut groups: Vec<(Vec<String>, Vec<FinishedCase>)> = Vec::new();
    for &(case, record) in cases {
        match groups.iter_mut().find(|(k, _)| *k == case.parameters) {
            Some((_, list)) => list.push((case, record)),
            None => groups.push((case.parameters.clone(), vec![(case, record)])),
        }
    }
    groups
}

/// A group's label for legends: `field=value` pairs, or `all cases`.
fn group_label(manifest: &Manifest, parameters: &[String]) -> String {
    let pairs: Vec<String> = manifest
        .fields
        .iter()
        .zip(parameters)
        .filter(|(_, v)| !v.is_empty())
        .map(|(f, v)| format!("{f}={v}"))
        .collect();
    if pairs.is_empty() {
        "all cases".into()
    } else {
        pairs.join(", ")
    }
}

/// Writes the assessment tables, and the figures when `figures`.
pub fn write(dir: &Path, manifest: &Manifest, cases: &[FinishedCase], figures: bool) -> Result<()> {
    let groups = groups(cases);
    write_convergence(dir, manifest, &groups)?;
    write_daf_vs_static(dir, cases)?;
    write_long(dir, manifest, cases)?;
    if figures {
        draw(dir, manifest, cases, &groups)?;
        draw_design_codes(dir, manifest, cases)?;
    }
    Ok(())
}

/// The figure `design_codes` of the study: the codes' mean 1 + IM over the cases against each
/// bridge's 95th percentile of the converged DAF_u and DAF_M (never one value pooled over
/// bridges, issue 46; the lines say whether their sample count makes it a characteristic value).
fn draw_design_codes(dir: &Path, manifest: &Manifest, cases: &[FinishedCase]) -> Result<()> {
    let records: Vec<&CaseRecord> = cases.iter().map(|(_, r)| *r).collect();
    let summary = crate::design_codes::study_summary(&records);
    let seed = vbi::study::stable_hash(manifest.study_hash.as_bytes());
    let mut bridges: Vec<&str> = Vec::new();
    for (case, _) in cases {
        if !bridges.contains(&case.bridge.as_str()) {
            bridges.push(case.bridge.as_str());
        }
    }
    let mut lines: Vec<(String, f64)> = Vec::new();
    for bridge in &bridges {
        for (name, value) in [
            ("DAF_u", (|r: &CaseRecord| r.daf_u) as Metric),
            ("DAF_M", |r: &CaseRecord| r.daf_m),
        ] {
            let values: Vec<f64> = cases
                .iter()
                .filter(|(case, _)| case.bridge == *bridge)
                .filter_map(|(_, r)| value(r))
                .collect();
            if let Ok(a) = vbi::study::assessment::assess(&values, seed) {
                let kind = if a.supports_characteristic() {
                    "characteristic"
                } else {
                    "95th percentile"
                };
                let of = if bridges.len() == 1 {
                    String::new()
                } else {
                    format!(", {bridge}")
                };
                lines.push((
                    format!("{name}{of} ({kind}, {} samples)", a.count),
                    a.characteristic,
                ));
            }
        }
    }
    let lines: Vec<(&str, f64)> = lines.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    crate::design_codes::write_study_figure(&dir.join("figures"), &summary, &lines)
}

/// `convergence.csv`: per group and headline metric, the mean of the first n samples and its
/// standard error, n = 1…count.
fn write_convergence(
    dir: &Path,
    manifest: &Manifest,
    groups: &[(Vec<String>, Vec<FinishedCase>)],
) -> Result<()> {
    let mut rows = Vec::new();
    for (parameters, list) in groups {
        for (metric, _, value) in HEADLINE {
            let values: Vec<f64> = list.iter().filter_map(|(_, r)| value(r)).collect();
            for point in running_mean(&values) {
                let mut row = parameters.clone();
                row.extend([
                    metric.to_string(),
                    point.samples.to_string(),
                    number(point.mean),
                    number(point.standard_error),
                ]);
                rows.push(row);
            }
        }
    }
    let mut header: Vec<&str> = manifest.fields.iter().map(String::as_str).collect();
    header.extend(["metric", "samples", "mean", "standard_error"]);
    write_csv(&dir.join("convergence.csv"), &header, &rows)
}

/// The (|static extreme|, DAF) points of deflection and moment of the cases of one bridge.
fn static_points(cases: &[FinishedCase], bridge: &str, quantity: usize) -> Vec<(f64, f64)> {
    cases
        .iter()
        .filter(|(c, _)| c.bridge == bridge)
        .filter_map(|(_, r)| match quantity {
            0 => r.static_u_m.zip(r.daf_u),
            _ => r.static_m_nm.zip(r.daf_m),
        })
        .map(|(s, d)| (s.abs(), d))
        .collect()
}

/// The bridges of the cases, in case order, each once.
fn bridges<'a>(cases: &[FinishedCase<'a>]) -> Vec<&'a str> {
    let mut bridges: Vec<&str> = Vec::new();
    for (c, _) in cases {
        if !bridges.contains(&c.bridge.as_str()) {
            bridges.push(&c.bridge);
        }
    }
    bridges
}

/// `daf_vs_static.csv`: per bridge, the least-squares line of the converged DAF against the
/// magnitude of the static extreme (heavier vehicles, lower DAF: a negative slope).
fn write_daf_vs_static(dir: &Path, cases: &[FinishedCase]) -> Result<()> {
    let mut rows = Vec::new();
    for bridge in bridges(cases) {
        for (quantity, metric, unit) in [(0, "daf_u", "m"), (1, "daf_m", "N·m")] {
            let points = static_points(cases, bridge, quantity);
            let fit = linear_fit(&points);
            let cell = |f: fn(&vbi::study::assessment::LinearFit) -> f64| {
                fit.map(|fit| number(f(&fit))).unwrap_or_default()
            };
            rows.push(vec![
                bridge.to_string(),
                metric.to_string(),
                unit.to_string(),
                points.len().to_string(),
                cell(|f| f.slope),
                cell(|f| f.intercept),
                cell(|f| f.correlation),
            ]);
        }
    }
    write_csv(
        &dir.join("daf_vs_static.csv"),
        &[
            "bridge",
            "metric",
            "static_unit",
            "count",
            "slope_per_static_unit",
            "intercept",
            "correlation",
        ],
        &rows,
    )
}

/// `cases_long.csv`: one row per case and numeric metric of `cases.csv`
/// (`case, <fields>, sample, seed, metric, value`); empty values are left out.
fn write_long(dir: &Path, manifest: &Manifest, cases: &[FinishedCase]) -> Result<()> {
    let numeric: Vec<(usize, &str)> = CASE_METRICS
        .iter()
        .enumerate()
        .filter(|(_, m)| !matches!(**m, "rdm_station" | "warnings"))
        .map(|(i, m)| (i, *m))
        .collect();
    let mut rows = Vec::new();
    for (case, record) in cases {
        let cells = record.metric_cells();
        for &(i, metric) in &numeric {
            if cells[i].is_empty() {
                continue;
            }
            let mut row = vec![case.id.clone()];
            row.extend(case.parameters.iter().cloned());
            row.extend([
                case.sample.to_string(),
                case.seed.to_string(),
                metric.to_string(),
                cells[i].clone(),
            ]);
            rows.push(row);
        }
    }
    let mut header = vec!["case"];
    header.extend(manifest.fields.iter().map(String::as_str));
    header.extend(["sample", "seed", "metric", "value"]);
    write_csv(&dir.join("cases_long.csv"), &header, &rows)
}

/// Per headline metric: its values by group (each group its curve), or all cases together when
/// there are more than [`MAX_CURVES`] groups.
fn curves(
    manifest: &Manifest,
    cases: &[FinishedCase],
    groups: &[(Vec<String>, Vec<FinishedCase>)],
    value: Metric,
) -> Vec<(String, Vec<f64>)> {
    let values = |list: &[FinishedCase]| list.iter().filter_map(|(_, r)| value(r)).collect();
    if groups.len() <= MAX_CURVES {
        groups
            .iter()
            .map(|(p, list)| (group_label(manifest, p), values(list)))
            .collect()
    } else {
        vec![(format!("all {} cases", cases.len()), values(cases))]
    }
}

/// The figures: histogram and CDF of each headline metric over all cases, the running mean of
/// each group, and DAF_M against the static moment per bridge.
fn draw(
    dir: &Path,
    manifest: &Manifest,
    cases: &[FinishedCase],
    groups: &[(Vec<String>, Vec<FinishedCase>)],
) -> Result<()> {
    let fig = dir.join("figures");
    for (metric, label, value) in HEADLINE {
        let all: Vec<f64> = cases.iter().filter_map(|(_, r)| value(r)).collect();
        if all.is_empty() {
            continue;
        }
        let h = histogram(&all);
        let bars = h
            .counts
            .iter()
            .enumerate()
            .map(|(i, &c)| (0.5 * (h.edges[i] + h.edges[i + 1]), c as f64))
            .collect();
        let per_group = curves(manifest, cases, groups, value);
        let cdf: Vec<Series> = per_group
            .iter()
            .map(|(name, v)| Series::line(name.clone(), empirical_cdf(v)))
            .collect();
        let running: Vec<Series> = per_group
            .iter()
            .map(|(name, v)| {
                let points = running_mean(v)
                    .iter()
                    .map(|p| (p.samples as f64, p.mean))
                    .collect();
                Series::line(name.clone(), points)
            })
            .collect();
        let charts = [
            Chart {
                title: format!("{label}: histogram of {} cases", all.len()),
                x_label: format!("{label} [-]"),
                y_label: "cases".into(),
                series: vec![Series {
                    label: String::new(),
                    points: bars,
                    style: SeriesStyle::Bars,
                }],
                ..Chart::default()
            },
            Chart {
                title: format!("{label}: empirical distribution"),
                x_label: format!("{label} [-]"),
                y_label: "fraction of cases ≤ x [-]".into(),
                series: cdf,
                ..Chart::default()
            },
            Chart {
                title: format!("{label}: Monte Carlo convergence of the mean"),
                x_label: "number of samples".into(),
                y_label: format!("mean {label} [-]"),
                series: running,
                ..Chart::default()
            },
        ];
        write_charts(&charts, 3, &fig.join(format!("assessment_{metric}")))?;
    }
    let series: Vec<Series> = bridges(cases)
        .iter()
        .map(|bridge| Series {
            label: bridge.to_string(),
            points: static_points(cases, bridge, 1)
                .iter()
                .map(|(s, d)| (s * 1e-3, *d))
                .collect(),
            style: SeriesStyle::Points,
        })
        .collect();
    write_charts(
        &[Chart {
            title: "converged DAF_M against the static moment at the RDM station".into(),
            x_label: "static moment [kN·m]".into(),
            y_label: "converged DAF_M [-]".into(),
            series,
            ..Chart::default()
        }],
        1,
        &fig.join("daf_vs_static"),
    )?;
    Ok(())
}
