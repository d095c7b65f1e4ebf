//! The DAF against the static level (`DIR/daf_against_static.png` and `.svg`, a lifetime with
//! dynamics): per effect, each integrated event's DAF = total / static against its static
//! extreme, each block's DAF = total block maximum / static block maximum against the static
//! block maximum, and the assessment DAF of the first return period at its characteristic
//! static effect: the published trend of Kalin et al. and ARCHES D10 (the DAF decreases as the
//! static effect grows), drawn from vbi's own events. Magnitudes in the effect's governing
//! sense, its SI unit.

use std::path::Path;

use anyhow::Result;

use vbi::lifetime::{EventExtreme, EventTotals, StaticLifetime, TotalBlockMaxima};
use vbi::statistics::extreme_value::ExtremeValueModel;

use crate::inputs::lifetime as lifetime_input;
use crate::plot::{write_charts, Chart, Series, SeriesStyle};

/// The most event points an effect keeps for the figure (16 bytes each).
const MOST_POINTS: usize = 20_000;

/// Each effect's event points (static magnitude, DAF), thinned to at most [`MOST_POINTS`]:
/// when full, every other point is dropped and from then on only every `stride`-th event is
/// taken, the stride doubled. Deterministic, and memory flat in the number of events.
#[derive(Debug, Clone)]
pub struct EventPoints {
    stride: u64,
    points: Vec<Vec<(f64, f64)>>,
}

impl EventPoints {
    /// No points yet, for `effects` effects.
    pub fn new(effects: usize) -> EventPoints {
        EventPoints {
            stride: 1,
            points: vec![Vec::new(); effects],
        }
    }

    /// Takes an integrated event's points (events in order).
    pub fn add(
        &mut self,
        analysis: &StaticLifetime,
        totals: &EventTotals,
        extremes: &[EventExtreme],
    ) {
        let loaded = (totals.totals.iter().enumerate())
            .filter_map(|(e, total)| Some((e, extremes[e].value, total.as_ref()?.total)));
        self.add_event(analysis, totals.event, loaded);
    }

    /// Takes event `number`'s (effect, static extreme, total) of each effect it loads (events
    /// in order): as [`EventPoints::add`], from the rows of events.csv (a merge of shards).
    pub fn add_event(
        &mut self,
        analysis: &StaticLifetime,
        number: u64,
        loaded: impl IntoIterator<Item = (usize, f64, f64)>,
    ) {
        if !number.is_multiple_of(self.stride) {
            return;
        }
        for (e, fixed, total) in loaded {
            if fixed == 0.0 {
                continue;
            }
            let sense = analysis.effects[e].sense;
            self.points[e].push((sense * fixed, total / fixed));
        }
        if self.points.iter().any(|p| p.len() > MOST_POINTS) {
            self.stride *= 2;
            for points in &mut self.points {
                let mut k = 0;
                points.retain(|_| {
                    k += 1;
                    k % 2 == 1
                });
            }
        }
    }
}

/// Points of a chart: (static magnitude, DAF).
type Points = Vec<(f64, f64)>;

/// An effect's chart of its event and block points, or None without points.
fn effect_chart(
    effect: &lifetime_input::EffectSummary,
    events: &[(f64, f64)],
    blocks: Points,
    stride: u64,
) -> Option<Chart> {
    if events.is_empty() && blocks.is_empty() {
        return None;
    }
    let mut series = vec![Series {
        label: match stride {
            1 => format!("{} events integrated", events.len()),
            s => format!("{} events integrated (every {s}th)", events.len()),
        },
        points: events.to_vec(),
        style: SeriesStyle::Points,
    }];
    series.push(Series {
        label: format!("{} block maxima (total / static)", blocks.len()),
        points: blocks,
        style: SeriesStyle::Points,
    });
    if let Some(point) = assessment_point(effect) {
        series.push(Series {
            label: "assessment DAF at the characteristic static effect".into(),
            points: vec![point],
            style: SeriesStyle::Points,
        });
    }
    Some(Chart {
        title: format!("{} {}", effect.station, effect.quantity),
        x_label: format!("static {} [{}]", effect.quantity, effect.unit),
        y_label: "DAF = total / static [-]".into(),
        series,
        ..Chart::default()
    })
}

/// The GEV assessment DAF of the first return period at its characteristic static magnitude.
fn assessment_point(effect: &lifetime_input::EffectSummary) -> Option<(f64, f64)> {
    let total = effect.total.as_ref()?;
    let daf = total.assessment_daf.first()?.gev?;
    let fits = effect.fits.as_ref()?;
    let gev = fits
        .fits
        .iter()
        .find(|f| f.model == ExtremeValueModel::Gev)?;
    Some((gev.return_levels.first()?.value.abs(), daf))
}

/// Writes `stem.png` and `stem.svg`, one chart per effect with points.
pub fn write_daf_plot(
    stem: &Path,
    analysis: &StaticLifetime,
    (tally_values, totals): (&[Vec<f64>], &TotalBlockMaxima),
    events: &EventPoints,
    summary: &lifetime_input::LifetimeSummary,
) -> Result<()> {
    let charts: Vec<Chart> = summary
        .effects
        .iter()
        .enumerate()
        .filter_map(|(e, effect)| {
            let sense = analysis.effects[e].sense;
            let blocks = tally_values[e]
                .iter()
                .zip(&totals.values[e])
                .filter(|(s, _)| **s != 0.0)
                .map(|(s, t)| (sense * s, t / s))
                .collect();
            effect_chart(effect, &events.points[e], blocks, events.stride)
        })
        .collect();
    if charts.is_empty() {
        return Ok(());
    }
    write_charts(&charts, charts.len().min(2), stem)?;
    Ok(())
}
