//! The table of `vbi measure`: one [`Row`] per run and DAF channel, the rows of
//! `measurements.csv` (columns [`HEADER`]) and of the measurement report's tables.

use serde::Serialize;
use vbi::measure::MeasurementSummary;

use crate::output;

/// One row of `measurements.csv`: a DAF channel of a run.
#[derive(Debug, Clone, Serialize)]
pub(super) struct Row {
    /// The run's name (its folder under `--out` for several runs).
    pub(super) run: String,
    /// The measurement file as given.
    pub(super) input: String,
    /// The run's description.
    pub(super) description: Option<String>,
    /// Vehicle speed [m/s].
    pub(super) speed_m_s: Option<f64>,
    /// Channel name.
    pub(super) channel: String,
    /// What it records (deflection, strain, bending_moment).
    pub(super) kind: String,
    /// Unit of `static_max` and `dynamic_max`.
    pub(super) unit: String,
    /// How its static part was found: low_pass, influence_line, crawl_run.
    pub(super) static_method: String,
    /// The static low-pass cut-off [Hz] (low_pass).
    pub(super) cutoff_hz: Option<f64>,
    /// The run's static-separation verdict (when a channel uses the low-pass).
    pub(super) separated: Option<bool>,
    /// The channel's own separation check (low-pass, span and speed known).
    pub(super) channel_separated: Option<bool>,
    /// Static maximum, in `unit`.
    pub(super) static_max: f64,
    /// Measured maximum in the same direction, in `unit`.
    pub(super) dynamic_max: f64,
    /// dynamic_max / static_max.
    pub(super) daf: f64,
    /// Frequency of the cut-off mode K1 [Hz].
    pub(super) k1_hz: Option<f64>,
    /// DAF after the low-pass just above K1.
    pub(super) daf_at_k1: Option<f64>,
    /// (daf_at_k1 − daf) / daf.
    pub(super) k1_relative_change: Option<f64>,
    /// Section label.
    pub(super) section: Option<String>,
    /// RDM of the section (DAF of deflection / DAF of moment), when it has both.
    pub(super) rdm: Option<f64>,
    /// The first identified frequency of the run [Hz].
    pub(super) first_frequency_hz: Option<f64>,
}

/// The columns of `measurements.csv`, in the order of [`Row`]'s fields.
pub(super) const HEADER: [&str; 20] = [
    "run",
    "input",
    "description",
    "speed_m_s",
    "channel",
    "kind",
    "unit",
    "static_method",
    "cutoff_hz",
    "separated",
    "channel_separated",
    "static_max",
    "dynamic_max",
    "daf",
    "k1_hz",
    "daf_at_k1",
    "k1_relative_change",
    "section",
    "rdm",
    "first_frequency_hz",
];

/// A channel kind as `measure.json` writes it (`bending_moment`).
fn kind_name<T: Serialize + std::fmt::Debug>(kind: &T) -> String {
    match serde_json::to_value(kind) {
        Ok(serde_json::Value::String(s)) => s,
        _ => format!("{kind:?}").to_lowercase(),
    }
}

/// The rows of one run: one per DAF channel, in channel order.
pub(super) fn rows(run: &str, input: &str, s: &MeasurementSummary) -> Vec<Row> {
    let separated = s.static_separation.as_ref().map(|x| x.cutoff.separated);
    let first_frequency_hz = s.identified_frequencies.first().map(|p| p.frequency_hz);
    s.channels
        .iter()
        .map(|c| {
            let rdm = c
                .section
                .as_ref()
                .and_then(|section| s.rdm.iter().find(|r| &r.section == section))
                .map(|r| r.rdm);
            Row {
                run: run.to_string(),
                input: input.to_string(),
                description: s.description.clone(),
                speed_m_s: s.speed_m_s,
                channel: c.name.clone(),
                kind: kind_name(&c.kind),
                unit: c.unit.clone(),
                static_method: c.static_method.to_string(),
                cutoff_hz: c.cutoff_hz,
                separated,
                channel_separated: c.separation_check.as_ref().map(|x| x.separated),
                static_max: c.static_max,
                dynamic_max: c.dynamic_max,
                daf: c.daf,
                k1_hz: c.cutoff_mode.as_ref().map(|k| k.mode_frequency_hz),
                daf_at_k1: c.cutoff_mode.as_ref().map(|k| k.daf_after),
                k1_relative_change: c.cutoff_mode.as_ref().map(|k| k.relative_change),
                section: c.section.clone(),
                rdm,
                first_frequency_hz,
            }
        })
        .collect()
}

/// A row's CSV cells: numbers in full precision (Rust's shortest round-trip form), an empty
/// cell for a missing value.
pub(super) fn cells(r: &Row) -> Vec<String> {
    let num = |x: Option<f64>| x.map_or(String::new(), output::number);
    let flag = |x: Option<bool>| x.map_or(String::new(), |b| b.to_string());
    let text = |x: &Option<String>| x.clone().unwrap_or_default();
    vec![
        r.run.clone(),
        r.input.clone(),
        text(&r.description),
        num(r.speed_m_s),
        r.channel.clone(),
        r.kind.clone(),
        r.unit.clone(),
        r.static_method.clone(),
        num(r.cutoff_hz),
        flag(r.separated),
        flag(r.channel_separated),
        output::number(r.static_max),
        output::number(r.dynamic_max),
        output::number(r.daf),
        num(r.k1_hz),
        num(r.daf_at_k1),
        num(r.k1_relative_change),
        text(&r.section),
        num(r.rdm),
        num(r.first_frequency_hz),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_has_one_column_per_cell() {
        let row = Row {
            run: "r".into(),
            input: "r.toml".into(),
            description: None,
            speed_m_s: Some(16.666666666666668),
            channel: "u".into(),
            kind: kind_name(&vbi::signal::MeasuredQuantity::BendingMoment),
            unit: "mm".into(),
            static_method: "low_pass".into(),
            cutoff_hz: None,
            separated: Some(false),
            channel_separated: None,
            static_max: -2.5,
            dynamic_max: -2.75,
            daf: 1.1,
            k1_hz: None,
            daf_at_k1: None,
            k1_relative_change: None,
            section: None,
            rdm: None,
            first_frequency_hz: None,
        };
        let c = cells(&row);
        assert_eq!(c.len(), HEADER.len());
        assert_eq!(c[3], "16.666666666666668");
        assert_eq!(c[5], "bending_moment");
        assert_eq!((c[8].as_str(), c[9].as_str()), ("", "false"));
    }
}
