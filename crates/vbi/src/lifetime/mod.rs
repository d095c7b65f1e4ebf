//! `vbi lifetime`: the load effects of a bridge under a record of real or simulated traffic
//! over its life, block by block (a day, a year), as an assessment needs them (issue 48).
//!
//! This first part is the static analysis, the job PyBTLS does: a time-ordered stream of
//! [`RecordedTruck`]s is grouped into events (the trucks on the deck together, [`event`]); each
//! event's static effect at every station and quantity has its **continuous** extreme taken,
//! exactly for piecewise-linear influence lines ([`EffectLine`], [`event::event_extreme`]); and
//! the largest of each block ([`static_block_maxima`]) is handed on as the block ends, so that
//! memory stays flat in the number of days.
//!
//! Blocks: block i holds the extremes that occur in [i T, (i + 1) T), T the block length [s]
//! (86 400 s for a day), counted from the record's start; a block no truck loads has maximum 0.
//!
//! Shards ([`BlockRange`], [`shard`]): a run may hand on only a contiguous range of blocks, its
//! events being those that start in it; the shards of a partition of the blocks, merged, give
//! the whole run's outputs bit for bit.

mod bound;
pub mod dynamics;
mod effect_line;
pub mod event;
pub mod fatigue;
pub mod from_influence;
mod prepare;
pub mod return_level;
pub mod shard;
pub mod total;

pub use bound::ExtremeBounds;
pub use dynamics::{
    event_road_seed, event_scenario, event_scenario_at, roughness_at, DynamicSettings, EventTotal,
    EventTotals, RoadChange, DEFAULT_SCREENING_RATIO,
};
pub use effect_line::{EffectLine, EffectLineError, SENSE_TIE};
pub use event::{EventExtreme, OutOfOrder, PlacedTruck};
pub use prepare::{prepare_static, DEFAULT_POINTS_PER_ELEMENT};
pub use return_level::{
    empirical_recurrence_intervals, fit_block_maxima, fit_peaks, loaded_probability, loaded_share,
    BlockMaximaFit, EffectFits, PeaksOverThresholdFit, ReturnLevel, ReturnLevelSettings,
    DEFAULT_BOOTSTRAP_RESAMPLES, DEFAULT_DAYS_PER_YEAR, DEFAULT_EXCEEDANCES,
    DEFAULT_RETURN_PERIOD_YEARS,
};
pub use shard::{merge_shards, LifetimeShard, MergedShards, ShardMergeError, ShardTotals};
pub use total::{
    screening_risk, static_and_total_block_maxima, total_block_maxima, GoverningEvent,
    StaticAndTotal, TotalBlockMaxima, SCREENING_BAND,
};

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};

use crate::fe::Quantity;
use crate::traffic::{RecordedTruck, TravelDirection};

/// Seconds in a day: the length of the default block.
pub const SECONDS_PER_DAY: f64 = 86_400.0;

/// A lane of the analysis: the record's direction and lane number, and where its trucks drive.
#[derive(Debug, Clone, PartialEq)]
pub struct LifetimeLane {
    /// The direction of its traffic (forward: direction 1 of a traffic file).
    pub direction: TravelDirection,
    /// The lane number the record gives its trucks, from 1 within the direction.
    pub number: usize,
    /// Lateral position y of the lane's centreline [m], deck coordinates (positive left).
    pub lateral_position: f64,
}

/// One static load effect tracked over the lifetime: a station's quantity, with its influence
/// line along each lane.
#[derive(Debug, Clone, PartialEq)]
pub struct LifetimeEffect {
    /// The station's name.
    pub station: String,
    /// The quantity.
    pub quantity: Quantity,
    /// Its influence line along each lane, in the order of [`StaticLifetime::lanes`] [unit per N].
    pub lines: Vec<EffectLine>,
    /// The sense in which it governs: +1 for the largest value, −1 for the most negative (the
    /// sign of the lines' ordinate of largest magnitude; positive on a tie within
    /// [`effect_line::SENSE_TIE`], as a midspan shear's ±½).
    pub sense: f64,
}

impl LifetimeEffect {
    /// An effect whose sense is that of its lines' largest ordinate.
    pub fn new(station: String, quantity: Quantity, lines: Vec<EffectLine>) -> LifetimeEffect {
        let range = lines
            .iter()
            .map(EffectLine::ordinate_range)
            .fold((0.0, 0.0), |(low, high): (f64, f64), (l, h)| {
                (low.min(l), high.max(h))
            });
        let dominant = effect_line::dominant_of(range);
        LifetimeEffect {
            station,
            quantity,
            lines,
            sense: if dominant < 0.0 { -1.0 } else { 1.0 },
        }
    }
}

/// A static lifetime analysis: the deck, its lanes, the effects and the block length.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticLifetime {
    /// Deck length L between the end supports [m].
    pub deck_length: f64,
    /// The lanes trucks may use.
    pub lanes: Vec<LifetimeLane>,
    /// The effects tracked.
    pub effects: Vec<LifetimeEffect>,
    /// Block length T [s] (a day: [`SECONDS_PER_DAY`]).
    pub block_seconds: f64,
    /// The end of the record [s] when it is known (simulated traffic: its days × 86 400 s):
    /// the blocks are those that start before it, every one handed on, and an extreme at or
    /// after it (the last trucks leaving the deck) counts in the last of them. None (a traffic
    /// file): the blocks run to the last one an event reaches.
    pub record_end: Option<f64>,
    /// The blocks this run hands on ([`BlockRange::ALL`], or one shard's).
    pub blocks: BlockRange,
}

/// The blocks a run hands on, and so its events: those that start in them (a shard of the
/// record, `vbi lifetime --shard I/N`). An event that starts before the range but reaches into
/// it loads the range's blocks; one that starts after it is evaluated only while an event of
/// the range may still be screened against its block's maximum. Its events keep their numbers
/// in the whole record.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct BlockRange {
    /// The first block handed on.
    pub first: u64,
    /// The block after the last one handed on; None: to the record's end.
    pub end: Option<u64>,
}

impl BlockRange {
    /// Every block of the record.
    pub const ALL: BlockRange = BlockRange {
        first: 0,
        end: None,
    };

    /// Shard I of N of a record of `blocks` blocks: blocks `⌊(I−1)·B/N⌋ .. ⌊I·B/N⌋` (sizes
    /// differ by at most one), the last shard's running to the record's end.
    pub fn of_shard(shard: crate::study::Shard, blocks: u64) -> BlockRange {
        let range = shard.range(blocks as usize);
        BlockRange {
            first: range.start as u64,
            end: (shard.index < shard.count).then_some(range.end as u64),
        }
    }

    /// Whether the range holds `block`.
    pub fn holds(&self, block: u64) -> bool {
        block >= self.first && self.end.is_none_or(|end| block < end)
    }

    /// Whether the range ends before `block`.
    fn ends_before(&self, block: u64) -> bool {
        self.end.is_some_and(|end| block >= end)
    }
}

impl StaticLifetime {
    /// The block of an instant [s]: ⌊t / T⌋, within the record's blocks when its end is known.
    pub fn block_of(&self, time: f64) -> u64 {
        let block = (time / self.block_seconds).floor().max(0.0) as u64;
        self.last_block().map_or(block, |last| block.min(last))
    }

    /// The last block, when the record's end is known: the last that starts before it.
    pub fn last_block(&self) -> Option<u64> {
        (self.record_end).map(|end| ((end / self.block_seconds).ceil() as u64).max(1) - 1)
    }
}

/// The extreme of one effect in one block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockMaximum {
    /// Block index from 0.
    pub block: u64,
    /// Index of the effect in [`StaticLifetime::effects`].
    pub effect: usize,
    /// The extreme static value in the effect's sense (signed; its unit: N, N·m or m); 0 when no
    /// truck loads the effect in the block.
    pub value: f64,
    /// When it occurs [s]; the block's start when the value is 0.
    pub time: f64,
    /// Trucks in the event that gives it (0 when none).
    pub trucks: usize,
}

/// Each effect's largest block maximum (in its sense, with its block), the sum of its block
/// maxima and the maxima themselves (for the return levels' fits: 8 bytes per block and effect,
/// 200 kB an effect for 25 000 days), gathered from the rows [`static_block_maxima`] hands on,
/// in order: what `lifetime.json` and Python's summary report.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockMaximaTally {
    /// The block of `values[e][0]`: the first block the run hands on.
    pub first: u64,
    /// Per effect: the largest block maximum in the effect's sense (signed) and its block.
    pub largest: Vec<(f64, u64)>,
    /// Per effect: the sum of its block maxima, added in block order.
    pub sum: Vec<f64>,
    /// Per effect: its block maxima (signed), in block order.
    pub values: Vec<Vec<f64>>,
}

impl BlockMaximaTally {
    /// An empty tally for the effects of `analysis`.
    pub fn new(analysis: &StaticLifetime) -> BlockMaximaTally {
        let n = analysis.effects.len();
        BlockMaximaTally {
            first: analysis.blocks.first,
            largest: vec![(0.0, 0); n],
            sum: vec![0.0; n],
            values: vec![Vec::new(); n],
        }
    }

    /// Adds one block's rows.
    pub fn add(&mut self, analysis: &StaticLifetime, rows: &[BlockMaximum]) {
        for row in rows {
            let sense = analysis.effects[row.effect].sense;
            let (largest, block) = &mut self.largest[row.effect];
            if sense * row.value > sense * *largest {
                (*largest, *block) = (row.value, row.block);
            }
            self.sum[row.effect] += row.value;
            self.values[row.effect].push(row.value);
        }
    }

    /// Effect e's maximum in `block` (signed), once the block has been added.
    pub fn block_value(&self, effect: usize, block: u64) -> Option<f64> {
        let index = block.checked_sub(self.first)?;
        self.values[effect]
            .get(usize::try_from(index).ok()?)
            .copied()
    }

    /// Effect e's mean block maximum over `blocks` blocks (0 without blocks).
    pub fn mean(&self, effect: usize, blocks: u64) -> f64 {
        self.sum[effect] / blocks.max(1) as f64
    }

    /// Effect e's fits and return levels ([`fit_block_maxima`]) for blocks of `block_days`,
    /// from `first_block` on (the blocks before the first truck precede the record: counted as
    /// unloaded blocks, they would lower every level).
    pub fn fit(
        &self,
        analysis: &StaticLifetime,
        effect: usize,
        first_block: u64,
        settings: &ReturnLevelSettings,
    ) -> Result<EffectFits, crate::statistics::extreme_value::ExtremeValueError> {
        let block_days = analysis.block_seconds / SECONDS_PER_DAY;
        let values = &self.values[effect];
        let skipped = first_block.saturating_sub(self.first) as usize;
        fit_block_maxima(
            &values[skipped.min(values.len())..],
            analysis.effects[effect].sense,
            block_days,
            settings,
        )
    }
}

/// The largest event extremes of each effect (in its sense, as magnitudes): the largest
/// `exceedances` and one more, the smallest of which is the peaks-over-threshold fit's
/// threshold. Memory: that many values an effect, whatever the record's length; each event
/// costs one comparison an effect, and a heap operation only when it enters.
#[derive(Debug, Clone)]
pub struct EventPeaks {
    /// Exceedances kept above the threshold (0: none kept).
    pub exceedances: usize,
    /// Per effect: a min-heap of the kept values' bit patterns. Positive finite f64s order as
    /// their bits do (IEEE 754), so the heap holds u64s and needs no float wrapper.
    heaps: Vec<BinaryHeap<Reverse<u64>>>,
}

impl EventPeaks {
    /// An empty tracker of the `exceedances` + 1 largest events of each effect of `analysis`.
    pub fn new(analysis: &StaticLifetime, exceedances: usize) -> EventPeaks {
        EventPeaks {
            exceedances,
            heaps: vec![BinaryHeap::new(); analysis.effects.len()],
        }
    }

    /// Offers effect e's extreme of one event (a magnitude in its sense; 0 or less is no peak).
    pub fn offer(&mut self, effect: usize, magnitude: f64) {
        if self.exceedances == 0 || !(magnitude > 0.0 && magnitude.is_finite()) {
            return;
        }
        let heap = &mut self.heaps[effect];
        let bits = magnitude.to_bits();
        if heap.len() <= self.exceedances {
            heap.push(Reverse(bits));
        } else if heap.peek().is_some_and(|smallest| bits > smallest.0) {
            heap.pop();
            heap.push(Reverse(bits));
        }
    }

    /// The magnitude at or below which an offer to effect e changes nothing: the smallest kept
    /// value once `exceedances` + 1 are kept, 0 before, infinite when none are kept.
    pub fn threshold(&self, effect: usize) -> f64 {
        let heap = &self.heaps[effect];
        match heap.peek() {
            _ if self.exceedances == 0 => f64::INFINITY,
            Some(smallest) if heap.len() > self.exceedances => f64::from_bits(smallest.0),
            _ => 0.0,
        }
    }

    /// A tracker holding `values` (per effect, as [`EventPeaks::values`] gives them): the
    /// peaks of several shards are merged by offering each shard's to one tracker.
    pub fn offer_all(&mut self, values: &[Vec<f64>]) {
        for (effect, values) in values.iter().enumerate() {
            for &value in values {
                self.offer(effect, value);
            }
        }
    }

    /// Effect e's kept values, largest first.
    pub fn values(&self, effect: usize) -> Vec<f64> {
        let mut values: Vec<f64> = self.heaps[effect]
            .iter()
            .map(|bits| f64::from_bits(bits.0))
            .collect();
        values.sort_by(|a, b| b.total_cmp(a));
        values
    }
}

/// Counts of a finished analysis.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct LifetimeCounts {
    /// Trucks read (of a shard: in its events).
    pub trucks: usize,
    /// Events (groups of trucks on the deck together; of a shard: those that start in it).
    pub events: usize,
    /// Events of two trucks or more.
    pub multiple_presence_events: usize,
    /// Blocks handed on.
    pub blocks: u64,
    /// When the first truck reaches the deck [s] (0 without trucks).
    pub first_arrival: f64,
    /// When the last truck leaves it [s] (0 without trucks).
    pub last_departure: f64,
}

impl LifetimeCounts {
    /// The length of the record the trucks cover, from the first arrival to the last
    /// departure [days]: the observation period of the peaks over threshold.
    pub fn record_days(&self) -> f64 {
        (self.last_departure - self.first_arrival).max(0.0) / SECONDS_PER_DAY
    }

    /// The first block a truck reaches (blocks before it precede the record).
    pub fn first_block(&self, block_seconds: f64) -> u64 {
        (self.first_arrival / block_seconds).floor().max(0.0) as u64
    }
}

/// Why a static lifetime analysis stops.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LifetimeError {
    /// A truck is not valid.
    #[error("truck {truck}: {reason}")]
    Truck {
        /// Its number in the stream, from 1.
        truck: usize,
        /// What is wrong.
        reason: String,
    },
    /// A truck drives in a lane the analysis does not have.
    #[error("truck {truck} drives in lane {lane} of direction {direction}, which the analysis does not have (lanes, as direction/lane: {known})")]
    UnknownLane {
        /// Its number in the stream, from 1.
        truck: usize,
        /// Its direction: 1 forward, 2 backward (a traffic file's numbers).
        direction: u8,
        /// Its lane number.
        lane: usize,
        /// The lanes the analysis has, as `direction/lane`.
        known: String,
    },
    /// The stream is not in order of arrival.
    #[error(transparent)]
    OutOfOrder(#[from] OutOfOrder),
}

/// The static block maxima of every effect under a time-ordered stream of trucks: `on_block`
/// receives each block's rows (one per effect, in effect order) as soon as no later event can
/// change them, blocks in order from 0 with none skipped. Memory: one event and the blocks it
/// may still reach.
pub fn static_block_maxima(
    analysis: &StaticLifetime,
    trucks: impl IntoIterator<Item = RecordedTruck>,
    on_block: impl FnMut(&[BlockMaximum]),
) -> Result<LifetimeCounts, LifetimeError> {
    static_maxima_and_peaks(
        analysis,
        trucks,
        &mut EventPeaks::new(analysis, 0),
        on_block,
    )
}

/// [`static_block_maxima`], and every event's extreme offered to `peaks` (the largest events of
/// each effect, for the peaks-over-threshold fit).
pub fn static_maxima_and_peaks(
    analysis: &StaticLifetime,
    trucks: impl IntoIterator<Item = RecordedTruck>,
    peaks: &mut EventPeaks,
    on_block: impl FnMut(&[BlockMaximum]),
) -> Result<LifetimeCounts, LifetimeError> {
    watched_static_pass(analysis, trucks, peaks, &mut NoWatch, on_block)
}

/// What a pass may do beside the static one, event by event: the pass with dynamics keeps the
/// events that may be screened in ([`total::static_and_total_block_maxima`]).
pub(crate) trait EventWatch {
    /// The share r ≤ 1 of the running block maxima from which the watch needs an effect's
    /// exact extreme (1: only where the static pass itself needs it).
    fn ratio(&self) -> f64;
    /// Event `number` (from 0): its trucks and, per effect, its exact extreme where the pass
    /// computed it (None where the bounds show it below both the running block maxima and r ×
    /// them), with the blocks' running maxima after it.
    fn event(
        &mut self,
        number: u64,
        trucks: &[PlacedTruck],
        extremes: &[Option<EventExtreme>],
        open: &OpenBlocks,
    );
    /// A block handed on: no later event changes its rows.
    fn block(&mut self, rows: &[BlockMaximum]);
    /// Every block before `next_block` has been handed on (u64::MAX: the record has ended).
    fn settled(&mut self, next_block: u64);
}

/// The static pass alone.
struct NoWatch;

impl EventWatch for NoWatch {
    fn ratio(&self) -> f64 {
        1.0
    }
    fn event(&mut self, _: u64, _: &[PlacedTruck], _: &[Option<EventExtreme>], _: &OpenBlocks) {}
    fn block(&mut self, _: &[BlockMaximum]) {}
    fn settled(&mut self, _: u64) {}
}

/// The static pass ([`static_maxima_and_peaks`]) with `watch` told of every event, block and
/// settled block. An effect's exact extreme is computed when its bounds may reach the smaller
/// of r × the running maxima of the blocks the event reaches and the peaks' threshold (r the
/// watch's ratio); the static outputs are the same whatever r.
///
/// Of a shard ([`StaticLifetime::blocks`]): the events that end before its first block are
/// only counted (for the numbers of the next); those that start in it are its own (counted,
/// offered to `peaks` and to `watch`); the others load its blocks, and the blocks after it
/// that its own events reach, whose maxima the watch needs; the stream is left once no later
/// event can change a block it needs.
pub(crate) fn watched_static_pass(
    analysis: &StaticLifetime,
    trucks: impl IntoIterator<Item = RecordedTruck>,
    peaks: &mut EventPeaks,
    watch: &mut impl EventWatch,
    mut on_block: impl FnMut(&[BlockMaximum]),
) -> Result<LifetimeCounts, LifetimeError> {
    let range = analysis.blocks;
    let mut counts = LifetimeCounts::default();
    let mut failure = None;
    let finished = std::cell::Cell::new(false);
    let placed = trucks.into_iter().enumerate().map_while(|(index, truck)| {
        if finished.get() {
            return None;
        }
        match place(analysis, &truck, index + 1) {
            Ok(placed) => Some(placed),
            Err(error) => {
                failure = Some(error);
                None
            }
        }
    });
    let mut open = OpenBlocks::new(analysis);
    let bounds = ExtremeBounds::new(analysis);
    let ratio = watch.ratio();
    let mut extremes: Vec<Option<EventExtreme>> = vec![None; analysis.effects.len()];
    let mut events = 0u64;
    // The last block an event of the range reaches: the watch needs its maximum.
    let mut needed: Option<u64> = None;
    let (mut first_arrival, mut last_departure) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut hand_on = |rows: &[BlockMaximum], block: u64, watch: &mut _| {
        if !range.ends_before(block) {
            on_block(rows);
        }
        EventWatch::block(watch, rows);
    };
    event::for_each_event(placed, |trucks| {
        if finished.get() {
            return;
        }
        let number = events;
        events += 1;
        let reach = (
            analysis.block_of(trucks[0].arrival),
            analysis.block_of(event::last_departure(trucks)),
        );
        if reach.1 < range.first {
            return;
        }
        let own = range.holds(reach.0);
        if !own && range.ends_before(reach.0) && needed.is_none_or(|last| reach.0 > last) {
            finished.set(true);
            return;
        }
        if own {
            needed = needed.max(Some(reach.1));
            for truck in trucks {
                first_arrival = first_arrival.min(truck.arrival);
                last_departure = last_departure.max(truck.leaves);
            }
            counts.trucks += trucks.len();
            counts.events += 1;
            counts.multiple_presence_events += usize::from(trucks.len() > 1);
        }
        // An event opens the block it starts in (one from an earlier shard, only the blocks
        // its extremes fall in).
        if !analysis.effects.is_empty() && reach.0 >= range.first {
            open.touch(reach.0);
        }
        for (e, effect) in analysis.effects.iter().enumerate() {
            // Only an event that may beat a running block maximum (or r × it, for the watch)
            // or enter the peaks needs its extreme (bound.rs): the outputs are the same.
            let running = open.smallest_running(e, reach);
            let threshold = (ratio * running).min(peaks.threshold(e));
            extremes[e] = None;
            if !bounds.may_reach(e, trucks, threshold) {
                continue;
            }
            let extreme =
                event::event_extreme(trucks, &effect.lines, analysis.deck_length, effect.sense);
            if own {
                peaks.offer(e, effect.sense * extreme.value);
            }
            open.offer(e, extreme, trucks.len());
            extremes[e] = Some(extreme);
        }
        if own {
            watch.event(number, trucks, &extremes, &open);
        }
        open.hand_on_before(reach.1, &mut |rows, block| hand_on(rows, block, watch));
        watch.settled(open.next_block);
    })?;
    if let Some(error) = failure {
        return Err(error);
    }
    // A shard left before the record's end hands on every block of its range; one the
    // record ends in, only those the record reaches (as the single run).
    let last = match range.end {
        Some(end) if finished.get() => end.checked_sub(1),
        Some(end) => (analysis.last_block()).map(|last| last.min(end.saturating_sub(1))),
        None => analysis.last_block(),
    };
    open.finish(last, &mut |rows, block| hand_on(rows, block, watch));
    watch.settled(u64::MAX);
    let handed_on = match range.end {
        Some(end) => open.next_block.min(end),
        None => open.next_block,
    };
    counts.blocks = handed_on.saturating_sub(range.first);
    if counts.events > 0 {
        (counts.first_arrival, counts.last_departure) = (first_arrival, last_departure);
    }
    Ok(counts)
}

/// The trucks of a stream placed on the analysis's deck, in order, until the first that cannot
/// be: the iterator stops there, and `failure` keeps why.
pub(crate) fn placed_until_failure<'a>(
    analysis: &'a StaticLifetime,
    trucks: impl IntoIterator<Item = RecordedTruck> + 'a,
    failure: &'a mut Option<LifetimeError>,
) -> impl Iterator<Item = PlacedTruck> + 'a {
    trucks
        .into_iter()
        .enumerate()
        .map_while(
            move |(index, truck)| match place(analysis, &truck, index + 1) {
                Ok(placed) => Some(placed),
                Err(error) => {
                    *failure = Some(error);
                    None
                }
            },
        )
}

/// Places a truck, or says why it cannot be.
fn place(
    analysis: &StaticLifetime,
    truck: &RecordedTruck,
    number: usize,
) -> Result<PlacedTruck, LifetimeError> {
    truck.check().map_err(|reason| LifetimeError::Truck {
        truck: number,
        reason,
    })?;
    let lane = lane_index(&analysis.lanes, truck).ok_or_else(|| LifetimeError::UnknownLane {
        truck: number,
        direction: direction_number(truck.direction),
        lane: truck.lane,
        known: lane_list(&analysis.lanes),
    })?;
    Ok(PlacedTruck::new(truck, lane, analysis.deck_length))
}

/// The index in `lanes` of the lane `truck` drives in (its direction and lane number).
pub fn lane_index(lanes: &[LifetimeLane], truck: &RecordedTruck) -> Option<usize> {
    lanes
        .iter()
        .position(|l| l.number == truck.lane && l.direction == truck.direction)
}

/// The lanes as `direction/lane` pairs, for messages: `1/1, 2/1`.
pub fn lane_list(lanes: &[LifetimeLane]) -> String {
    lanes
        .iter()
        .map(|l| format!("{}/{}", direction_number(l.direction), l.number))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A direction's number in traffic files: 1 forward, 2 backward.
pub fn direction_number(direction: TravelDirection) -> u8 {
    match direction {
        TravelDirection::Forward => 1,
        TravelDirection::Backward => 2,
    }
}

/// The blocks that events may still reach, each with its running maxima.
pub(crate) struct OpenBlocks<'a> {
    analysis: &'a StaticLifetime,
    open: BTreeMap<u64, Vec<BlockMaximum>>,
    /// The first block not yet handed on.
    next_block: u64,
}

impl<'a> OpenBlocks<'a> {
    fn new(analysis: &'a StaticLifetime) -> Self {
        OpenBlocks {
            analysis,
            open: BTreeMap::new(),
            next_block: analysis.blocks.first,
        }
    }

    /// The running maximum of effect e in `block` (signed), while the block is open; None
    /// once it has been handed on or before an event reaches it.
    pub(crate) fn running(&self, effect: usize, block: u64) -> Option<f64> {
        self.open.get(&block).map(|rows| rows[effect].value)
    }

    /// The smallest running maximum of effect e (a magnitude in its sense; 0 for a block no
    /// event has reached) over the blocks `first..=last` an event may reach.
    fn smallest_running(&self, effect: usize, (first, last): (u64, u64)) -> f64 {
        let sense = self.analysis.effects[effect].sense;
        (first.max(self.next_block)..=last.max(self.next_block))
            .map(|block| {
                self.open
                    .get(&block)
                    .map_or(0.0, |rows| sense * rows[effect].value)
            })
            .fold(f64::INFINITY, f64::min)
    }

    fn empty_block(&self, block: u64) -> Vec<BlockMaximum> {
        (0..self.analysis.effects.len())
            .map(|effect| BlockMaximum {
                block,
                effect,
                value: 0.0,
                time: block as f64 * self.analysis.block_seconds,
                trucks: 0,
            })
            .collect()
    }

    /// Opens the block (at least the first not handed on) with empty rows, if it is not open:
    /// as an event that does not load any effect there opens it.
    fn touch(&mut self, block: u64) -> &mut Vec<BlockMaximum> {
        let block = block.max(self.next_block);
        if !self.open.contains_key(&block) {
            let empty = self.empty_block(block);
            self.open.insert(block, empty);
        }
        self.open.get_mut(&block).expect("inserted above")
    }

    /// Offers an event's extreme to the block it falls in (none before the run's first block:
    /// an earlier shard's).
    fn offer(&mut self, effect: usize, extreme: EventExtreme, trucks: usize) {
        let block = self.analysis.block_of(extreme.time);
        if block < self.analysis.blocks.first {
            return;
        }
        let sense = self.analysis.effects[effect].sense;
        let row = &mut self.touch(block)[effect];
        if sense * extreme.value > sense * row.value {
            row.value = extreme.value;
            row.time = extreme.time;
            row.trucks = trucks;
        }
    }

    /// Hands on every block before `limit` (and the empty ones between), in order, each with
    /// its number.
    fn hand_on_before(&mut self, limit: u64, on_block: &mut impl FnMut(&[BlockMaximum], u64)) {
        while let Some((&block, _)) = self.open.first_key_value() {
            if block >= limit {
                break;
            }
            let rows = self.open.remove(&block).expect("present");
            while self.next_block < block {
                on_block(&self.empty_block(self.next_block), self.next_block);
                self.next_block += 1;
            }
            on_block(&rows, block);
            self.next_block = block + 1;
        }
    }

    /// Hands on every block left, and the empty ones up to `last` (the record's last block
    /// when its end is known, the last of a shard's range).
    fn finish(&mut self, last: Option<u64>, on_block: &mut impl FnMut(&[BlockMaximum], u64)) {
        self.hand_on_before(u64::MAX, on_block);
        if let Some(last) = last {
            while self.next_block <= last {
                on_block(&self.empty_block(self.next_block), self.next_block);
                self.next_block += 1;
            }
        }
    }
}

#[cfg(test)]
mod tests;
