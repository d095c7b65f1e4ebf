//! The design codes' impact factors beside the computed DAFs, as `vbi run` writes them: the
//! table's lines, `design_codes.csv` and the figure `design_codes` (the library computes the
//! factors, `vbi::codes`).

use std::path::Path;

use anyhow::Result;
use vbi::analysis::DafReport;
use vbi::codes::{CodeImpactFactor, DesignCode, StationCodeFactors};
use vbi::modal::Quantity;
use vbi::study::{CaseRecord, CodeRecord};

use crate::output::{number, write_csv};
use crate::plot::{self, Chart, Series, SeriesStyle};

/// Columns of `design_codes.csv`.
pub const COLUMNS: [&str; 10] = [
    "station",
    "quantity",
    "code",
    "provision",
    "clause",
    "basis",
    "impact_factor",
    "code_daf",
    "computed_daf",
    "computed_over_code",
];

/// A short label of a factor for tables and figures: the code, and its case where the code has
/// two (`JTG D60-2015 (code f)`, `AASHTO LRFD (fatigue)`).
pub fn label(factor: &CodeImpactFactor) -> String {
    label_of(factor.code, &factor.provision)
}

/// [`label`] of a code and its case.
pub fn label_of(code: DesignCode, provision: &str) -> String {
    let case = match provision {
        "code_frequency" => " (code's f)",
        "computed_frequency" => " (vbi's f)",
        "strength_service" => " (strength)",
        "fatigue" | "fatigue_roughness" => " (fatigue)",
        "moving_traffic" => " (M1600)",
        "triaxle_group" => " (tri-axle)",
        "single_axle_or_wheel" => " (W80/A160)",
        _ => "",
    };
    format!("{}{case}", code.name())
}

/// The code factors of a station and quantity of the report.
pub fn entry<'a>(
    report: &'a DafReport,
    station: &str,
    quantity: Quantity,
) -> Option<&'a StationCodeFactors> {
    report
        .design_codes
        .iter()
        .find(|c| c.station == station && c.quantity == quantity)
}

/// The factor of `other` (another quantity at the station) of the same code and case as `factor`.
pub fn same_case<'a>(
    other: &'a StationCodeFactors,
    factor: &CodeImpactFactor,
) -> Option<&'a CodeImpactFactor> {
    other
        .factors
        .iter()
        .find(|f| f.code == factor.code && f.provision == factor.provision)
}

/// The rows of `design_codes.csv`: every entry of the report, each code's factor beside its
/// computed DAF (empty where the entry has none, a deflection over a support).
pub fn rows(report: &DafReport) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    for codes in &report.design_codes {
        let computed = report
            .entry(codes.station_index, codes.quantity)
            .and_then(|e| e.converged.daf);
        for f in &codes.factors {
            rows.push(vec![
                codes.station.clone(),
                codes.quantity.name().to_string(),
                f.code.name().to_string(),
                f.provision.clone(),
                f.clause.clone(),
                f.basis.clone(),
                number(f.impact_factor),
                number(f.daf()),
                computed.map(number).unwrap_or_default(),
                computed.map(|d| number(d / f.daf())).unwrap_or_default(),
            ]);
        }
    }
    rows
}

/// Writes `design_codes.csv`.
pub fn write_table(dir: &Path, report: &DafReport) -> Result<()> {
    write_csv(&dir.join("design_codes.csv"), &COLUMNS, &rows(report))
}

/// The console lines of the codes at the RDM station: each code's 1 + IM for the deflection and
/// the moment there, beside the computed (converged) DAFs.
pub fn table_lines(report: &DafReport) -> Vec<String> {
    let Some(station) = report.rdm_station.as_deref() else {
        return Vec::new();
    };
    let (Some(u), Some(m)) = (
        entry(report, station, Quantity::Deflection),
        entry(report, station, Quantity::BendingMoment),
    ) else {
        return Vec::new();
    };
    let computed = |q: Quantity| {
        report
            .entry(u.station_index, q)
            .and_then(|e| e.converged.daf)
            .map_or("-".to_string(), |d| format!("{d:.4}"))
    };
    let mut lines = vec![
        format!(
            "Design codes at {station}: 1 + IM beside the computed DAF (deflection {}, moment {}); \
             docs/design-codes.md",
            computed(Quantity::Deflection),
            computed(Quantity::BendingMoment)
        ),
        format!(
            "  {:<32} {:>10} {:>8}  {}",
            "code (case)", "deflection", "moment", "basis (of the moment's value)"
        ),
    ];
    let row = |mf: &CodeImpactFactor| {
        let uf = same_case(u, mf);
        format!(
            "  {:<32} {:>10} {:>8.4}  {}",
            label(mf),
            uf.map_or("-".to_string(), |f| format!("{:.4}", f.daf())),
            mf.daf(),
            mf.basis
        )
    };
    let (fatigue, peak): (Vec<&CodeImpactFactor>, Vec<&CodeImpactFactor>) =
        m.factors.iter().partition(|f| f.is_fatigue_factor());
    lines.extend(peak.into_iter().map(row));
    if !fatigue.is_empty() {
        lines.push(
            "  fatigue limit state (factors on the fatigue load's stress ranges, calibrated on \
             damage: not comparable with a peak DAF)"
                .to_string(),
        );
        lines.extend(fatigue.into_iter().map(row));
    }
    lines
}

/// The figure `design_codes`: each code's 1 + IM for the moment at the RDM station as a marker,
/// with the computed DAF_u and DAF_M as horizontal lines across. Nothing without an RDM station.
pub fn write_figure(dir: &Path, report: &DafReport) -> Result<()> {
    let Some(station) = report.rdm_station.as_deref() else {
        return Ok(());
    };
    let Some(m) = entry(report, station, Quantity::BendingMoment) else {
        return Ok(());
    };
    let daf = |q: Quantity| {
        report
            .entry(m.station_index, q)
            .and_then(|e| e.converged.daf)
    };
    let computed = [
        (Quantity::Deflection, "DAF_u"),
        (Quantity::BendingMoment, "DAF_M"),
    ]
    .into_iter()
    .filter_map(|(q, name)| daf(q).map(|d| (name, d)));
    // The fatigue factors are no peak DAFs: not drawn against the computed ones (issue 46).
    let points: Vec<(String, f64)> = m
        .factors
        .iter()
        .filter(|f| !f.is_fatigue_factor())
        .map(|f| (short_label(f.code, &f.provision), f.daf()))
        .collect();
    let chart = chart(&format!("at {station}"), &points, computed);
    plot::write_chart(&chart, &dir.join("design_codes"))?;
    Ok(())
}

/// A chart of code DAFs (a marker per factor) and computed DAFs (horizontal lines), the DAF
/// axis zoomed to the values.
pub fn chart<'a>(
    place: &str,
    codes: &[(String, f64)],
    computed: impl Iterator<Item = (&'a str, f64)>,
) -> Chart {
    let n = codes.len() as f64;
    let mut series = vec![Series {
        label: "code: 1 + IM".into(),
        points: codes
            .iter()
            .enumerate()
            .map(|(i, (_, daf))| (i as f64, *daf))
            .collect(),
        style: SeriesStyle::Points,
    }];
    for (name, value) in computed {
        series.push(Series::line(
            format!("computed {name} = {value:.3}"),
            vec![(-0.5, value), (n - 0.5, value)],
        ));
    }
    Chart {
        title: format!("Computed DAF against the design codes {place}"),
        x_label: "design code (case)".into(),
        y_label: "DAF = 1 + IM [-]".into(),
        series,
        x_categories: codes.iter().map(|(label, _)| label.clone()).collect(),
        ..Chart::default()
    }
}

/// A tick label short enough for its place on the axis (about 8 characters).
fn short_label(code: DesignCode, provision: &str) -> String {
    code.short_label(provision).to_string()
}

/// One code case over the cases of a study: its 1 + IM range for the RDM station's moment, and
/// how often the computed DAFs exceeded it.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyCodeSummary {
    /// The code.
    pub code: DesignCode,
    /// The code's case.
    pub provision: String,
    /// Smallest and largest 1 + IM over the cases (moment) [-].
    pub min: f64,
    /// See `min`.
    pub max: f64,
    /// Mean 1 + IM over the cases (moment) [-].
    pub mean: f64,
    /// Cases with a value.
    pub count: usize,
    /// Cases whose computed DAF_u exceeds the code's 1 + IM for the deflection.
    pub exceeded_u: usize,
    /// Cases whose computed DAF_M exceeds the code's 1 + IM for the moment.
    pub exceeded_m: usize,
}

impl StudyCodeSummary {
    /// Whether it is a fatigue factor (`CodeImpactFactor::is_fatigue_factor`): listed, not
    /// compared with the peak DAFs.
    pub fn is_fatigue_factor(&self) -> bool {
        matches!(self.provision.as_str(), "fatigue" | "fatigue_roughness")
    }

    /// The code case's label ([`label_of`]).
    pub fn label(&self) -> String {
        label_of(self.code, &self.provision)
    }

    /// Its 1 + IM over the cases with `decimals` decimals: one value where every case has it,
    /// else the range `min–max`.
    pub fn value_text(&self, decimals: usize) -> String {
        let (low, high) = (
            format!("{:.decimals$}", self.min),
            format!("{:.decimals$}", self.max),
        );
        if low == high {
            low
        } else {
            format!("{low}–{high}")
        }
    }
}

/// The code cases of a study's finished records, in the order of the first record's list.
pub fn study_summary(records: &[&CaseRecord]) -> Vec<StudyCodeSummary> {
    let mut out: Vec<StudyCodeSummary> = Vec::new();
    for record in records {
        for c in &record.design_codes {
            let index = match out
                .iter()
                .position(|s| s.code == c.code && s.provision == c.provision)
            {
                Some(i) => i,
                None => {
                    out.push(StudyCodeSummary {
                        code: c.code,
                        provision: c.provision.clone(),
                        min: f64::INFINITY,
                        max: f64::NEG_INFINITY,
                        mean: 0.0,
                        count: 0,
                        exceeded_u: 0,
                        exceeded_m: 0,
                    });
                    out.len() - 1
                }
            };
            add(&mut out[index], c);
        }
    }
    for s in &mut out {
        s.mean /= s.count.max(1) as f64;
    }
    out
}

fn add(summary: &mut StudyCodeSummary, record: &CodeRecord) {
    let exceeded = record.computed_daf.is_some_and(|d| d > record.code_daf());
    match record.quantity {
        Quantity::Deflection => summary.exceeded_u += usize::from(exceeded),
        _ => {
            summary.exceeded_m += usize::from(exceeded);
            summary.min = summary.min.min(record.code_daf());
            summary.max = summary.max.max(record.code_daf());
            summary.mean += record.code_daf();
            summary.count += 1;
        }
    }
}

/// The study's figure `design_codes`: each code case's mean 1 + IM (moment, RDM station) as a
/// marker, and each bridge's 95th percentile of the computed DAF_u and DAF_M as lines. Nothing
/// without code values.
pub fn write_study_figure(
    dir: &Path,
    summary: &[StudyCodeSummary],
    characteristic: &[(&str, f64)],
) -> Result<()> {
    if summary.is_empty() {
        return Ok(());
    }
    let points: Vec<(String, f64)> = summary
        .iter()
        .filter(|s| !s.is_fatigue_factor())
        .map(|s| (short_label(s.code, &s.provision), s.mean))
        .collect();
    let chart = chart(
        "over the study's cases (the codes' mean; each bridge's 95th percentile of the computed DAF)",
        &points,
        characteristic.iter().copied(),
    );
    plot::write_chart(&chart, &dir.join("design_codes"))?;
    Ok(())
}
