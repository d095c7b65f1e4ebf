//! The second pass of a lifetime analysis with dynamics: the traffic read again, every event
//! screened against the first pass's static block maxima ([`super::dynamics::screened`]), the
//! events that can govern integrated in batches on every core, and each effect's **total**
//! block maxima gathered from their converged dynamic extremes. Memory: one batch of events
//! and the block maxima, whatever the record's length.

use super::dynamics::{
    event_scenario, event_start, event_totals, governing_directions, run_events, screened,
    DynamicSettings, EventTotal, EventTotals,
};
use super::event::{self, event_extreme, EventExtreme, PlacedTruck};
use super::{place, BlockMaximaTally, ExtremeBounds, LifetimeError, StaticLifetime};
use crate::codes::{CodeImpactFactor, StationCodeFactors};
use crate::crossing::{error_chain, PreparedBridge, Scenario};
use crate::traffic::RecordedTruck;

/// Events integrated together: enough to keep every core busy, few enough to hold.
pub const EVENT_BATCH: usize = 64;

/// What the second pass gives: each effect's total block maxima, and the counts.
#[derive(Debug, Clone, PartialEq)]
pub struct TotalBlockMaxima {
    /// Per effect: the largest converged total extreme of the integrated events in each block
    /// (signed, in the effect's sense; 0 where no integrated event loads it), in block order,
    /// as many blocks as the static pass handed on.
    pub values: Vec<Vec<f64>>,
    /// Events of the record.
    pub events: u64,
    /// Events integrated with dynamics.
    pub integrated: u64,
    /// Events screened in whose crossing was refused (a vehicle that does not assemble, two
    /// trucks of one lane that close up on each other): their totals are missing.
    pub refused: u64,
    /// The first refusal, for the report.
    pub first_refusal: Option<String>,
    /// Per effect: the design codes' impact factors at its station and quantity (those of
    /// the first integrated event's crossing: they depend on the bridge, not on the trucks),
    /// empty until an event is integrated.
    pub design_codes: Vec<Vec<CodeImpactFactor>>,
    /// Per effect: the integrated event with the largest total over the whole record (None
    /// where no event loads it), with its trucks, to be replayed as a `vbi run` scenario.
    pub governing: Vec<Option<GoverningEvent>>,
}

/// The event that gives an effect's largest total over the record.
#[derive(Debug, Clone, PartialEq)]
pub struct GoverningEvent {
    /// The event's number in the record (from 0).
    pub event: u64,
    /// Its trucks, in order of arrival.
    pub trucks: Vec<RecordedTruck>,
    /// The effect's total and static extremes in the event.
    pub total: EventTotal,
}

/// One screened-in event waiting in the batch.
struct Waiting {
    number: u64,
    trucks: Vec<RecordedTruck>,
    start: f64,
    scenario: Result<Scenario, String>,
    extremes: Vec<EventExtreme>,
}

/// The total block maxima of every effect under the same stream of trucks the static pass read
/// (`static_maxima` its block maxima): each event whose static effect reaches the screening
/// ratio of its block's maximum for some effect is integrated ([`DynamicSettings`]);
/// `on_event` receives each integrated event's totals with its static extremes (in event
/// order), for the events table and the progress.
pub fn total_block_maxima(
    analysis: &StaticLifetime,
    static_maxima: &BlockMaximaTally,
    (bridge, settings): (&PreparedBridge, &DynamicSettings),
    trucks: impl IntoIterator<Item = RecordedTruck>,
    mut on_event: impl FnMut(&EventTotals, &[EventExtreme]),
) -> Result<TotalBlockMaxima, LifetimeError> {
    let blocks = static_maxima.values.first().map_or(0, Vec::len);
    let effects = analysis.effects.len();
    let mut outcome = TotalBlockMaxima {
        values: vec![vec![0.0; blocks]; effects],
        events: 0,
        integrated: 0,
        refused: 0,
        first_refusal: None,
        design_codes: vec![Vec::new(); effects],
        governing: vec![None; effects],
    };
    let mut template = settings.template.clone();
    template.analysis.governing_directions = governing_directions(&analysis.effects);
    let mut failure = None;
    let placed = trucks.into_iter().enumerate().map_while(|(index, truck)| {
        match place(analysis, &truck, index + 1) {
            Ok(placed) => Some(placed),
            Err(error) => {
                failure = Some(error);
                None
            }
        }
    });
    let mut batch: Vec<Waiting> = Vec::with_capacity(EVENT_BATCH);
    let mut number = 0u64;
    let bounds = ExtremeBounds::new(analysis);
    event::for_each_event(placed, |trucks| {
        if may_screen(
            analysis,
            static_maxima,
            &bounds,
            trucks,
            settings.screening_ratio,
        ) {
            let extremes: Vec<EventExtreme> = (analysis.effects.iter())
                .map(|e| event_extreme(trucks, &e.lines, analysis.deck_length, e.sense))
                .collect();
            let located: Vec<(f64, u64)> = extremes
                .iter()
                .map(|x| (x.value, block_of(analysis, x.time, blocks)))
                .collect();
            if screened(analysis, static_maxima, &located, settings.screening_ratio) {
                batch.push(waiting(analysis, &template, trucks, number, extremes));
                if batch.len() == EVENT_BATCH {
                    integrate(analysis, bridge, &mut batch, &mut outcome, &mut on_event);
                }
            }
        }
        number += 1;
    })?;
    if let Some(error) = failure {
        return Err(error);
    }
    integrate(analysis, bridge, &mut batch, &mut outcome, &mut on_event);
    outcome.events = number;
    Ok(outcome)
}

/// Whether the event may be screened in: for some effect, its bound ([`ExtremeBounds`]) is
/// positive and reaches the ratio of the smallest static maximum of the blocks its extreme
/// can fall in. When not, no effect's extreme can ([`screened`]), and none is computed.
fn may_screen(
    analysis: &StaticLifetime,
    static_maxima: &BlockMaximaTally,
    bounds: &ExtremeBounds,
    trucks: &[PlacedTruck],
    ratio: f64,
) -> bool {
    let blocks = static_maxima.values.first().map_or(0, Vec::len);
    let first = block_of(analysis, trucks[0].arrival, blocks) as usize;
    let last = block_of(analysis, event::last_departure(trucks), blocks) as usize;
    (analysis.effects.iter()).enumerate().any(|(e, effect)| {
        let smallest = (first..=last)
            .map(|b| {
                static_maxima.values[e]
                    .get(b)
                    .map_or(0.0, |v| effect.sense * v)
            })
            .fold(f64::INFINITY, f64::min);
        bounds.may_reach(e, trucks, ratio * smallest)
    })
}

/// The block of an instant, within the blocks the static pass handed on.
fn block_of(analysis: &StaticLifetime, time: f64, blocks: usize) -> u64 {
    analysis.block_of(time).min(blocks.saturating_sub(1) as u64)
}

/// A screened-in event, its scenario made (or the reason it cannot be).
fn waiting(
    analysis: &StaticLifetime,
    template: &Scenario,
    trucks: &[PlacedTruck],
    number: u64,
    extremes: Vec<EventExtreme>,
) -> Waiting {
    let records: Vec<RecordedTruck> = trucks
        .iter()
        .map(|t| t.record(analysis.lanes[t.lane].number))
        .collect();
    Waiting {
        number,
        start: event_start(template, &records[0]),
        scenario: event_scenario(template, &analysis.lanes, &records, number)
            .map_err(|e| error_chain(&e)),
        trucks: records,
        extremes,
    }
}

/// Integrates the batch's events and folds their totals into `outcome`, in event order.
fn integrate(
    analysis: &StaticLifetime,
    bridge: &PreparedBridge,
    batch: &mut Vec<Waiting>,
    outcome: &mut TotalBlockMaxima,
    on_event: &mut impl FnMut(&EventTotals, &[EventExtreme]),
) {
    let scenarios: Vec<Scenario> = batch
        .iter()
        .filter_map(|w| w.scenario.as_ref().ok().cloned())
        .collect();
    let mut results = run_events(bridge, &scenarios).into_iter();
    let blocks = outcome.values.first().map_or(0, Vec::len);
    for waiting in batch.drain(..) {
        let result = match waiting.scenario {
            Ok(_) => results
                .next()
                .expect("one result per scenario")
                .map_err(|e| error_chain(&e)),
            Err(reason) => Err(reason),
        };
        let result = match result {
            Ok(result) => result,
            Err(reason) => {
                outcome.refused += 1;
                outcome.first_refusal.get_or_insert_with(|| {
                    format!(
                        "event {} ({} trucks): {reason}",
                        waiting.number,
                        waiting.trucks.len()
                    )
                });
                continue;
            }
        };
        outcome.integrated += 1;
        if outcome.integrated == 1 {
            outcome.design_codes = design_codes(analysis, &result.report.design_codes);
        }
        let totals = event_totals(
            analysis,
            &result,
            (waiting.number, waiting.trucks.len(), waiting.start),
        );
        for (e, total) in totals.totals.iter().enumerate() {
            let Some(total) = total else { continue };
            let sense = analysis.effects[e].sense;
            let block = block_of(analysis, total.time, blocks) as usize;
            if block < blocks && sense * total.total > sense * outcome.values[e][block] {
                outcome.values[e][block] = total.total;
            }
            let governing = &mut outcome.governing[e];
            if governing
                .as_ref()
                .is_none_or(|g| sense * total.total > sense * g.total.total)
            {
                *governing = Some(GoverningEvent {
                    event: waiting.number,
                    trucks: waiting.trucks.clone(),
                    total: *total,
                });
            }
        }
        on_event(&totals, &waiting.extremes);
    }
}

/// The codes' factors of each effect, from a crossing's report.
fn design_codes(
    analysis: &StaticLifetime,
    factors: &[StationCodeFactors],
) -> Vec<Vec<CodeImpactFactor>> {
    (analysis.effects.iter())
        .map(|effect| {
            factors
                .iter()
                .find(|f| f.station == effect.station && f.quantity == effect.quantity)
                .map_or_else(Vec::new, |f| f.factors.clone())
        })
        .collect()
}
