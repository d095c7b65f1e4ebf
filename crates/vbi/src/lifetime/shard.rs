//! Shards of a lifetime run, and their merge (`vbi lifetime --shard I/N`, `vbi lifetime merge`,
//! Python's `vbi.lifetime(..., shard=)` and `vbi.merge_lifetime`).
//!
//! A shard hands on a contiguous range of blocks ([`BlockRange`]) and owns the events that
//! start in it (module docs of [`super`]): its static block maxima are the whole run's for its
//! blocks, because every event that reaches them is evaluated; its largest events and counts
//! are those of its own events; its totals are its own events', screened against the final
//! static maxima of every block they reach, as the whole run screens them. So the merge is
//! exact: the block maxima concatenated in block order, the counts summed, the largest events
//! of the union kept, and each block's total the largest of the shards' totals there (an event
//! of one shard may give a total in the next shard's first block). The merged outputs equal the
//! single run's bit for bit (tested).

use serde::{Deserialize, Serialize};

use super::dynamics::EventTotal;
use super::total::close_blocks;
use super::{
    BlockMaximaTally, BlockMaximum, BlockRange, EventPeaks, LifetimeCounts, StaticLifetime,
    TotalBlockMaxima,
};
use crate::codes::CodeImpactFactor;
use crate::study::Shard;

/// What one shard's run gives the merge (`shard.json` of a shard's directory).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LifetimeShard {
    /// The shard, I of N.
    pub shard: Shard,
    /// Its blocks.
    pub blocks: BlockRange,
    /// The counts of its events, and the blocks it handed on.
    pub counts: LifetimeCounts,
    /// Per effect: the static maxima of its blocks, in block order (signed) [N, N·m or m].
    pub static_maxima: Vec<Vec<f64>>,
    /// Per effect: its events' largest extremes, largest first (magnitudes, as
    /// [`EventPeaks::values`] gives them).
    pub peaks: Vec<Vec<f64>>,
    /// With dynamics: the totals of its events.
    pub totals: Option<ShardTotals>,
}

/// The totals of a shard's events ([`LifetimeShard::totals`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShardTotals {
    /// Per effect: each block its events give a total, with the largest of them (signed), in
    /// block order; blocks after the shard's own included.
    pub block_totals: Vec<Vec<(u64, f64)>>,
    /// Events integrated.
    pub integrated: u64,
    /// Events screened in whose crossing was refused.
    pub refused: u64,
    /// The first refusal.
    pub first_refusal: Option<String>,
    /// Per effect: the design codes' factors ([`TotalBlockMaxima::design_codes`]).
    pub design_codes: Vec<Vec<CodeImpactFactor>>,
    /// Per effect: the event with the largest total (its number) and that total.
    pub governing: Vec<Option<(u64, EventTotal)>>,
    /// Per effect: the largest DAF just above the screening threshold
    /// ([`TotalBlockMaxima::edge_daf`]).
    pub edge_daf: Vec<Option<f64>>,
}

impl LifetimeShard {
    /// The shard's part of a finished run of `analysis` (whose [`StaticLifetime::blocks`] are
    /// the shard's): its counts, its static block maxima (`tally`), its largest events and its
    /// totals.
    pub fn new(
        shard: Shard,
        analysis: &StaticLifetime,
        counts: LifetimeCounts,
        (tally, peaks): (&BlockMaximaTally, &EventPeaks),
        totals: Option<&TotalBlockMaxima>,
    ) -> LifetimeShard {
        let effects = analysis.effects.len();
        LifetimeShard {
            shard,
            blocks: analysis.blocks,
            counts,
            static_maxima: tally.values.clone(),
            peaks: (0..effects).map(|e| peaks.values(e)).collect(),
            totals: totals.map(|totals| ShardTotals {
                block_totals: (totals.values.iter())
                    .map(|values| {
                        (values.iter().enumerate())
                            .filter(|(_, &v)| v != 0.0)
                            .map(|(block, &v)| (block as u64, v))
                            .collect()
                    })
                    .collect(),
                integrated: totals.integrated,
                refused: totals.refused,
                first_refusal: totals.first_refusal.clone(),
                design_codes: totals.design_codes.clone(),
                governing: (totals.governing.iter())
                    .map(|g| g.as_ref().map(|g| (g.event, g.total)))
                    .collect(),
                edge_daf: totals.edge_daf.clone(),
            }),
        }
    }
}

/// An effect's governing event in a merge: its shard's position in the merged slice, its
/// number in the record and its total.
pub type GoverningShard = (usize, u64, EventTotal);

/// The whole run, merged from its shards ([`merge_shards`]).
#[derive(Debug, Clone)]
pub struct MergedShards {
    /// The counts.
    pub counts: LifetimeCounts,
    /// The static block maxima, from block 0.
    pub tally: BlockMaximaTally,
    /// The largest events of each effect.
    pub peaks: EventPeaks,
    /// With dynamics: the totals ([`TotalBlockMaxima::governing`] is empty: the governing
    /// events' trucks are in their shards, [`MergedShards::governing`]).
    pub totals: Option<TotalBlockMaxima>,
    /// Per effect: the governing event's shard (its position in the merged slice), number and
    /// total.
    pub governing: Vec<Option<GoverningShard>>,
}

/// Why shards cannot be merged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ShardMergeError {
    /// No shard was given.
    #[error("no shard to merge")]
    Empty,
    /// The shards are not the N shards of one run, each once.
    #[error("the shards are not shards 1 to N of one run, each once: {0}")]
    Incomplete(String),
    /// The shards do not match (their effects, or dynamics in some and not in others).
    #[error("the shards are not of the same run: {0}")]
    Mismatch(String),
}

/// Merges the shards of one run of `analysis` (its [`StaticLifetime::blocks`] all of them),
/// given in any order, keeping `exceedances` + 1 largest events of each effect (module docs).
pub fn merge_shards(
    analysis: &StaticLifetime,
    exceedances: usize,
    shards: &[LifetimeShard],
) -> Result<MergedShards, ShardMergeError> {
    let order = shard_order(analysis, shards)?;
    let effects = analysis.effects.len();
    let mut whole = analysis.clone();
    whole.blocks = BlockRange::ALL;
    let mut counts = LifetimeCounts::default();
    let mut tally = BlockMaximaTally::new(&whole);
    let mut peaks = EventPeaks::new(&whole, exceedances);
    let mut rows: Vec<BlockMaximum> = Vec::with_capacity(effects);
    for &k in &order {
        let shard = &shards[k];
        let part = shard.counts;
        if part.events > 0 {
            if counts.events == 0 {
                counts.first_arrival = part.first_arrival;
            }
            counts.last_departure = part.last_departure;
        }
        counts.trucks += part.trucks;
        counts.events += part.events;
        counts.multiple_presence_events += part.multiple_presence_events;
        for index in 0..part.blocks as usize {
            let block = counts.blocks + index as u64;
            rows.clear();
            rows.extend((0..effects).map(|effect| BlockMaximum {
                block,
                effect,
                value: shard.static_maxima[effect][index],
                time: 0.0,
                trucks: 0,
            }));
            tally.add(&whole, &rows);
        }
        counts.blocks += part.blocks;
        peaks.offer_all(&shard.peaks);
    }
    let dynamics = shards[order[0]].totals.is_some();
    let (totals, governing) = match dynamics {
        false => (None, vec![None; effects]),
        true => {
            let (totals, governing) = merge_totals(&whole, shards, &order, counts)?;
            (Some(totals), governing)
        }
    };
    Ok(MergedShards {
        counts,
        tally,
        peaks,
        totals,
        governing,
    })
}

/// The shards' positions in order 1..N, checked to be one run's partition of its blocks.
fn shard_order(
    analysis: &StaticLifetime,
    shards: &[LifetimeShard],
) -> Result<Vec<usize>, ShardMergeError> {
    let first = shards.first().ok_or(ShardMergeError::Empty)?;
    let count = first.shard.count;
    let mut order: Vec<usize> = (0..shards.len()).collect();
    order.sort_by_key(|&k| shards[k].shard.index);
    let indices: Vec<String> = order.iter().map(|&k| shards[k].shard.to_string()).collect();
    let complete = shards.len() == count
        && (order.iter().enumerate()).all(|(i, &k)| {
            shards[k].shard
                == Shard {
                    index: i + 1,
                    count,
                }
        });
    if !complete {
        return Err(ShardMergeError::Incomplete(format!(
            "given {}",
            indices.join(", ")
        )));
    }
    let mut next = 0;
    for &k in &order {
        let shard = &shards[k];
        let effects = analysis.effects.len();
        if shard.static_maxima.len() != effects || shard.peaks.len() != effects {
            return Err(ShardMergeError::Mismatch(format!(
                "shard {} has {} effects, the analysis {effects}",
                shard.shard,
                shard.static_maxima.len()
            )));
        }
        if shard.totals.is_some() != first.totals.is_some() {
            return Err(ShardMergeError::Mismatch(format!(
                "shard {} is {} dynamics, shard {} {}",
                shard.shard,
                if shard.totals.is_some() {
                    "with"
                } else {
                    "without"
                },
                first.shard,
                if first.totals.is_some() {
                    "with"
                } else {
                    "without"
                },
            )));
        }
        // A shard hands on its range from its first block, or, past the record's end, none.
        let (range, blocks) = (shard.blocks, shard.counts.blocks);
        let last = shard.shard.index == count;
        let contiguous = range.end.is_none() == last
            && range.end.is_none_or(|end| range.first + blocks <= end)
            && (range.first == next || (blocks == 0 && range.first >= next))
            && (shard.static_maxima.iter()).all(|v| v.len() as u64 == blocks);
        if !contiguous {
            return Err(ShardMergeError::Mismatch(format!(
                "shard {}'s blocks do not follow the shard before it (from block {next})",
                shard.shard
            )));
        }
        if blocks > 0 {
            next = range.first + blocks;
        }
    }
    Ok(order)
}

/// The shards' totals merged: each block's largest, the counts summed, the first refusal and
/// design codes of the first shard that has them, and each effect's governing event the
/// largest total's (the earliest on a tie, as the single run keeps it).
fn merge_totals(
    analysis: &StaticLifetime,
    shards: &[LifetimeShard],
    order: &[usize],
    counts: LifetimeCounts,
) -> Result<(TotalBlockMaxima, Vec<Option<GoverningShard>>), ShardMergeError> {
    let effects = analysis.effects.len();
    let mut merged = TotalBlockMaxima::empty(effects);
    let mut governing: Vec<Option<GoverningShard>> = vec![None; effects];
    for &k in order {
        let Some(part) = &shards[k].totals else {
            continue;
        };
        if part.block_totals.len() != effects || part.governing.len() != effects {
            return Err(ShardMergeError::Mismatch(format!(
                "shard {}'s totals have {} effects, the analysis {effects}",
                shards[k].shard,
                part.block_totals.len()
            )));
        }
        for (e, effect) in analysis.effects.iter().enumerate() {
            let sense = effect.sense;
            let values = &mut merged.values[e];
            for &(block, total) in &part.block_totals[e] {
                let block = block as usize;
                if block >= values.len() {
                    values.resize(block + 1, 0.0);
                }
                if sense * total > sense * values[block] {
                    values[block] = total;
                }
            }
            if let Some(daf) = part.edge_daf.get(e).copied().flatten() {
                let edge = &mut merged.edge_daf[e];
                *edge = Some(edge.map_or(daf, |d: f64| d.max(daf)));
            }
            if let Some((event, total)) = part.governing[e] {
                let larger = governing[e]
                    .as_ref()
                    .is_none_or(|(_, _, g)| sense * total.total > sense * g.total);
                if larger {
                    governing[e] = Some((k, event, total));
                }
            }
        }
        merged.integrated += part.integrated;
        merged.refused += part.refused;
        if merged.first_refusal.is_none() {
            merged.first_refusal = part.first_refusal.clone();
        }
        if merged.design_codes.iter().all(Vec::is_empty) && part.integrated > 0 {
            merged.design_codes = part.design_codes.clone();
        }
    }
    merged.events = counts.events as u64;
    close_blocks(analysis, &mut merged, counts.blocks as usize);
    Ok((merged, governing))
}
