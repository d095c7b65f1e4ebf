//! A lifetime analysis with dynamics: every event screened against its blocks' static maxima
//! ([`super::dynamics::screened`]), the events that can govern integrated in batches on every
//! core, and each effect's **total** block maxima gathered from their converged dynamic
//! extremes.
//!
//! One pass ([`static_and_total_block_maxima`]): the static pass keeps, as it goes, each event
//! whose static extreme reaches r × its block's *running* maximum for some effect (a block's
//! running maximum never exceeds its final one, so no event that the rule screens in is
//! missed), drops those that later maxima put below r, and decides each kept event once its
//! blocks are handed on. The rule's plain statement, two passes over the traffic
//! ([`total_block_maxima`]), is the reference it is tested against: the same totals bit for bit.
//! Memory: the events kept and one batch, the block maxima, whatever the record's length.

use super::dynamics::{
    event_scenario_at, event_start, event_totals, governing_directions, run_events, screened,
    DynamicSettings, EventTotal, EventTotals, RoadChange,
};
use super::event::{self, event_extreme, EventExtreme, PlacedTruck};
use super::{
    placed_until_failure, watched_static_pass, BlockMaximaTally, BlockMaximum, EventPeaks,
    EventWatch, ExtremeBounds, LifetimeCounts, LifetimeError, OpenBlocks, StaticLifetime,
};
use crate::codes::{CodeImpactFactor, StationCodeFactors};
use crate::crossing::{error_chain, PreparedBridge, RunResult, Scenario};
use crate::traffic::RecordedTruck;
use std::collections::VecDeque;
use std::sync::mpsc::{Receiver, SyncSender};

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
    /// Per effect: the largest DAF (total / static) of the integrated events whose static
    /// extreme lies just above the screening threshold, in [r, r + [`SCREENING_BAND`]) × its
    /// block's static maximum (None without such an event, and with r = 0): what an event
    /// just below the threshold, left out, might have reached ([`screening_risk`]).
    pub edge_daf: Vec<Option<f64>>,
}

/// The width of the band of static levels just above the screening threshold whose events'
/// DAFs stand for those of the events just below it, left out ([`TotalBlockMaxima::edge_daf`]),
/// as a share of the block's static maximum.
pub const SCREENING_BAND: f64 = 0.1;

/// The blocks where the screening may have missed the total maximum: those where an event just
/// below the threshold, at r × the block's static maximum S, with the largest DAF seen just
/// above the threshold (`edge_daf`), would exceed the block's total maximum T: r·|S|·D > |T|.
/// An indicator, not a bound: it assumes the DAFs of the events just below the threshold are
/// like those just above it (the DAF falls as the static level grows, so those below tend to
/// be a little larger). Returns (blocks at risk, blocks with a static maximum), over the
/// blocks from `first` on.
pub fn screening_risk(
    ratio: f64,
    edge_daf: Option<f64>,
    (static_maxima, totals): (&[f64], &[f64]),
    first: usize,
) -> (u64, u64) {
    let mut counted = (0, 0);
    for (s, t) in static_maxima.iter().zip(totals).skip(first) {
        if *s == 0.0 {
            continue;
        }
        counted.1 += 1;
        if let Some(daf) = edge_daf {
            if ratio > 0.0 && ratio * s.abs() * daf > t.abs() {
                counted.0 += 1;
            }
        }
    }
    counted
}

impl TotalBlockMaxima {
    /// No event yet, for `effects` effects.
    pub(crate) fn empty(effects: usize) -> TotalBlockMaxima {
        TotalBlockMaxima {
            values: vec![Vec::new(); effects],
            events: 0,
            integrated: 0,
            refused: 0,
            first_refusal: None,
            design_codes: vec![Vec::new(); effects],
            governing: vec![None; effects],
            edge_daf: vec![None; effects],
        }
    }
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
    let mut outcome = TotalBlockMaxima::empty(effects);
    let mut template = settings.template.clone();
    template.analysis.governing_directions = governing_directions(&analysis.effects);
    let mut failure = None;
    let placed = placed_until_failure(analysis, trucks, &mut failure);
    let mut batch: Vec<Waiting> = Vec::with_capacity(EVENT_BATCH);
    let mut number = 0u64;
    let bounds = ExtremeBounds::new(analysis);
    // How the crossings' totals are read: against the static maxima, at the ratio.
    let read = (analysis, static_maxima, settings.screening_ratio);
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
                let made = (&template, settings.road_changes.as_slice());
                batch.push(waiting(analysis, made, trucks, number, extremes));
                if batch.len() == EVENT_BATCH {
                    integrate(read, bridge, &mut batch, &mut outcome, &mut on_event);
                }
            }
        }
        number += 1;
    })?;
    if let Some(error) = failure {
        return Err(error);
    }
    integrate(read, bridge, &mut batch, &mut outcome, &mut on_event);
    outcome.events = number;
    close_blocks(analysis, &mut outcome, blocks);
    Ok(outcome)
}

/// The totals in the record's `blocks` blocks: a total whose instant lies past the last block
/// (a crossing's free vibration after the record's last event) counts in the last, as a static
/// extreme does; none without blocks.
pub(crate) fn close_blocks(
    analysis: &StaticLifetime,
    outcome: &mut TotalBlockMaxima,
    blocks: usize,
) {
    for (effect, values) in analysis.effects.iter().zip(&mut outcome.values) {
        if blocks == 0 {
            values.clear();
            continue;
        }
        let past = values.split_off(blocks.min(values.len()));
        values.resize(blocks, 0.0);
        for value in past {
            if effect.sense * value > effect.sense * values[blocks - 1] {
                values[blocks - 1] = value;
            }
        }
    }
}

/// What the one pass gives: the static pass's counts, and the totals.
pub type StaticAndTotal = (LifetimeCounts, TotalBlockMaxima);

/// The static block maxima (handed to `on_block` as [`super::static_maxima_and_peaks`] hands
/// them, its events offered to `peaks`) and the total block maxima of the events screened in
/// against them ([`total_block_maxima`]'s rule and outputs, bit for bit), in one pass over the
/// trucks (module docs). `on_event` receives each integrated event's totals with its static
/// extremes, in event order.
pub fn static_and_total_block_maxima(
    analysis: &StaticLifetime,
    (bridge, settings): (&PreparedBridge, &DynamicSettings),
    trucks: impl IntoIterator<Item = RecordedTruck>,
    peaks: &mut EventPeaks,
    (on_block, on_event): (
        impl FnMut(&[BlockMaximum]),
        impl FnMut(&EventTotals, &[EventExtreme]),
    ),
) -> Result<StaticAndTotal, LifetimeError> {
    let mut template = settings.template.clone();
    template.analysis.governing_directions = governing_directions(&analysis.effects);
    let effects = analysis.effects.len();
    // The crossings run on a worker thread (each batch on every core) while the static pass
    // goes on; their results come back in batch order and are folded in event order here, so
    // the outputs do not depend on the timing. One batch waits at most: memory stays flat.
    std::thread::scope(|scope| {
        let (to_worker, batches) = std::sync::mpsc::sync_channel::<Vec<Waiting>>(1);
        let (to_pass, done) = std::sync::mpsc::channel();
        scope.spawn(move || {
            for batch in batches {
                let results = crossings(bridge, &batch);
                if to_pass.send((batch, results)).is_err() {
                    break;
                }
            }
        });
        let mut watch = Screening {
            analysis,
            template,
            road_changes: &settings.road_changes,
            ratio: settings.screening_ratio,
            maxima: BlockMaximaTally::new(analysis),
            kept: VecDeque::new(),
            prune_at: PRUNE_FIRST,
            batch: Vec::with_capacity(EVENT_BATCH),
            worker: Some(to_worker),
            done,
            in_flight: 0,
            outcome: TotalBlockMaxima::empty(effects),
            on_event,
        };
        let counts = watched_static_pass(analysis, trucks, peaks, &mut watch, on_block)?;
        watch.finish();
        let mut outcome = watch.outcome;
        outcome.events = counts.events as u64;
        // A shard before the last keeps the totals its events give the blocks after it, for
        // the merge ([`super::merge_shards`]).
        if analysis.blocks.end.is_none() {
            let blocks = analysis.blocks.first + counts.blocks;
            close_blocks(analysis, &mut outcome, blocks as usize);
        }
        Ok((counts, outcome))
    })
}

/// A batch of events with their crossings ([`crossings`]).
type Crossed = (Vec<Waiting>, Vec<Result<RunResult, String>>);

/// Events kept before the first pruning of those that later maxima put below r.
const PRUNE_FIRST: usize = 16;

/// An event kept by the one pass until its blocks are handed on.
struct Kept {
    number: u64,
    trucks: Vec<PlacedTruck>,
    /// Per effect: its exact static extreme.
    extremes: Vec<EventExtreme>,
    /// The last block an extreme of it falls in.
    last_block: u64,
}

/// The one pass's watch of the static pass (module docs).
struct Screening<'a, F> {
    analysis: &'a StaticLifetime,
    template: Scenario,
    /// The road's changes with the years ([`DynamicSettings::road_changes`]).
    road_changes: &'a [RoadChange],
    ratio: f64,
    /// The static maxima of the blocks handed on.
    maxima: BlockMaximaTally,
    /// The events that may be screened in, in event order.
    kept: VecDeque<Kept>,
    /// The number of events kept at which those below r are dropped next.
    prune_at: usize,
    /// The events screened in, not yet sent to the worker.
    batch: Vec<Waiting>,
    /// The worker's queue of batches (None once the record has ended).
    worker: Option<SyncSender<Vec<Waiting>>>,
    /// The worker's crossings, batch by batch, in order.
    done: Receiver<Crossed>,
    /// Batches sent and not yet folded.
    in_flight: usize,
    outcome: TotalBlockMaxima,
    on_event: F,
}

impl<F: FnMut(&EventTotals, &[EventExtreme])> Screening<'_, F> {
    /// Whether an extreme of effect e reaches r × its block's static maximum so far: the final
    /// one for a block handed on, the running one for an open block (and 0 for a block no
    /// event has loaded yet).
    fn reaches(&self, e: usize, extreme: &EventExtreme, open: Option<&OpenBlocks>) -> bool {
        let sense = self.analysis.effects[e].sense;
        let block = self.analysis.block_of(extreme.time);
        let maximum = match self.maxima.block_value(e, block) {
            Some(value) => value,
            None => open.and_then(|o| o.running(e, block)).unwrap_or(0.0),
        };
        let magnitude = sense * extreme.value;
        magnitude > 0.0 && magnitude >= self.ratio * sense * maximum
    }

    /// Sends the batch to the worker (waiting while it still has one queued).
    fn send(&mut self) {
        let batch = std::mem::replace(&mut self.batch, Vec::with_capacity(EVENT_BATCH));
        if let Some(worker) = &self.worker {
            worker
                .send(batch)
                .expect("the worker lives as long as the pass");
            self.in_flight += 1;
        }
    }

    fn fold(&mut self, batch: Vec<Waiting>, results: Vec<Result<RunResult, String>>) {
        self.in_flight -= 1;
        fold(
            (self.analysis, &self.maxima, self.ratio),
            batch,
            results,
            &mut self.outcome,
            &mut self.on_event,
        );
    }

    /// At the record's end: the last batch sent, the worker's queue closed, every crossing
    /// folded.
    fn finish(&mut self) {
        if !self.batch.is_empty() {
            self.send();
        }
        self.worker = None;
        while self.in_flight > 0 {
            let (batch, results) = self.done.recv().expect("the worker answers every batch");
            self.fold(batch, results);
        }
    }

    /// Drops the kept events that no effect can screen in any more.
    fn prune(&mut self, open: &OpenBlocks) {
        let kept = std::mem::take(&mut self.kept);
        self.kept = kept
            .into_iter()
            .filter(|k| {
                (k.extremes.iter().enumerate()).any(|(e, x)| self.reaches(e, x, Some(open)))
            })
            .collect();
        self.prune_at = (2 * self.kept.len()).max(PRUNE_FIRST);
    }
}

impl<F: FnMut(&EventTotals, &[EventExtreme])> EventWatch for Screening<'_, F> {
    fn ratio(&self) -> f64 {
        self.ratio
    }

    fn event(
        &mut self,
        number: u64,
        trucks: &[PlacedTruck],
        extremes: &[Option<EventExtreme>],
        open: &OpenBlocks,
    ) {
        let candidate = (extremes.iter().enumerate())
            .any(|(e, x)| x.is_some_and(|x| self.reaches(e, &x, Some(open))));
        if !candidate {
            return;
        }
        // Every effect's extreme, for the rule and the events table.
        let extremes: Vec<EventExtreme> = (self.analysis.effects.iter())
            .zip(extremes)
            .map(|(effect, x)| {
                x.unwrap_or_else(|| {
                    event_extreme(
                        trucks,
                        &effect.lines,
                        self.analysis.deck_length,
                        effect.sense,
                    )
                })
            })
            .collect();
        let last_block = (extremes.iter())
            .map(|x| self.analysis.block_of(x.time))
            .max()
            .unwrap_or(0);
        self.kept.push_back(Kept {
            number,
            trucks: trucks.to_vec(),
            extremes,
            last_block,
        });
        if self.kept.len() >= self.prune_at {
            self.prune(open);
        }
    }

    fn block(&mut self, rows: &[BlockMaximum]) {
        self.maxima.add(self.analysis, rows);
    }

    fn settled(&mut self, next_block: u64) {
        // With r = 0 an event's decision needs no block maximum (every event that loads an
        // effect is screened in): none waits for its blocks, and memory stays flat however
        // long the blocks.
        let every = self.ratio == 0.0;
        let decided = |k: &Kept| k.last_block < next_block || every;
        while self.kept.front().is_some_and(decided) {
            let kept = self.kept.pop_front().expect("a front");
            let located: Vec<(f64, u64)> = (kept.extremes.iter())
                .map(|x| (x.value, self.analysis.block_of(x.time)))
                .collect();
            if !screened(self.analysis, &self.maxima, &located, self.ratio) {
                continue;
            }
            let waiting = waiting(
                self.analysis,
                (&self.template, self.road_changes),
                &kept.trucks,
                kept.number,
                kept.extremes,
            );
            self.batch.push(waiting);
            if self.batch.len() == EVENT_BATCH {
                self.send();
            }
        }
        // The crossings done so far, folded in order.
        while let Ok((batch, results)) = self.done.try_recv() {
            self.fold(batch, results);
        }
    }
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
    (template, changes): (&Scenario, &[RoadChange]),
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
        scenario: event_scenario_at(changes, template, &analysis.lanes, &records, number)
            .map_err(|e| error_chain(&e)),
        trucks: records,
        extremes,
    }
}

/// Integrates the batch's events and folds their totals into `outcome`, in event order.
fn integrate(
    (analysis, maxima, ratio): (&StaticLifetime, &BlockMaximaTally, f64),
    bridge: &PreparedBridge,
    batch: &mut Vec<Waiting>,
    outcome: &mut TotalBlockMaxima,
    on_event: &mut impl FnMut(&EventTotals, &[EventExtreme]),
) {
    let results = crossings(bridge, batch);
    fold(
        (analysis, maxima, ratio),
        std::mem::take(batch),
        results,
        outcome,
        on_event,
    );
}

/// The crossing of each event of the batch (in parallel), or why there is none, in order.
fn crossings(bridge: &PreparedBridge, batch: &[Waiting]) -> Vec<Result<RunResult, String>> {
    let scenarios: Vec<Scenario> = batch
        .iter()
        .filter_map(|w| w.scenario.as_ref().ok().cloned())
        .collect();
    let mut results = run_events(bridge, &scenarios).into_iter();
    (batch.iter())
        .map(|waiting| match &waiting.scenario {
            Ok(_) => results
                .next()
                .expect("one result per scenario")
                .map_err(|e| error_chain(&e)),
            Err(reason) => Err(reason.clone()),
        })
        .collect()
}

/// Folds the batch's crossings ([`crossings`]) into `outcome`, in event order, reading each
/// event's static level against its blocks' static maxima (`maxima`) for the screening's
/// edge at `ratio`.
fn fold(
    (analysis, maxima, ratio): (&StaticLifetime, &BlockMaximaTally, f64),
    batch: Vec<Waiting>,
    results: Vec<Result<RunResult, String>>,
    outcome: &mut TotalBlockMaxima,
    on_event: &mut impl FnMut(&EventTotals, &[EventExtreme]),
) {
    for (waiting, result) in batch.into_iter().zip(results) {
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
            // In the block of its instant, as many as there are (the record's blocks are
            // known at its end: `close_blocks`).
            let block = analysis.block_of(total.time) as usize;
            let values = &mut outcome.values[e];
            if block >= values.len() {
                values.resize(block + 1, 0.0);
            }
            if sense * total.total > sense * values[block] {
                values[block] = total.total;
            }
            let fixed = waiting.extremes[e];
            let maximum = maxima.block_value(e, analysis.block_of(fixed.time));
            if let Some(maximum) = maximum.filter(|m| *m != 0.0 && fixed.value != 0.0) {
                let level = fixed.value / maximum;
                if ratio > 0.0 && level >= ratio && level < ratio + SCREENING_BAND {
                    let daf = total.total / fixed.value;
                    let edge = &mut outcome.edge_daf[e];
                    *edge = Some(edge.map_or(daf, |d: f64| d.max(daf)));
                }
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
