//! The static fatigue of a lifetime of traffic (issue 51, item 3): every event's exact static
//! stress history at each detail, counted by rainflow as **one history** across the record (the
//! deck is empty and every effect zero between events, and the residue of one event closes with
//! the next), and Miner's sum per block, per year and over the record.
//!
//! The history of an event is read at its breakpoints ([`event::event_history_at_breakpoints`]):
//! E(t) is linear between them, so the counts are those of the continuous history of the
//! tabulated lines, whatever a sampling step would have been.

use super::event::{self, PlacedTruck};
use super::{placed_until_failure, LifetimeError, StaticLifetime};
use crate::fatigue::{DamageSum, DetailFatigueSummary, FatigueDetail, RainflowCounter};
use crate::traffic::RecordedTruck;

/// Seconds in a year of 365.25 days.
pub const SECONDS_PER_YEAR: f64 = 365.25 * 86_400.0;

/// A fatigue detail on one of the lifetime's effects.
#[derive(Debug, Clone, PartialEq)]
pub struct LifetimeDetail {
    /// The detail (its station and quantity name the effect).
    pub detail: FatigueDetail,
    /// The index of its effect in [`StaticLifetime::effects`].
    pub effect: usize,
}

/// One detail's fatigue over the record.
#[derive(Debug, Clone)]
pub struct DetailLifetimeFatigue {
    /// The detail.
    pub detail: LifetimeDetail,
    /// The cycles and Miner's sum over the whole record (the residue's half cycles included).
    pub sum: DamageSum,
    /// Miner's sum of the cycles that closed in each block, from the first block (a cycle
    /// closes with the event whose reversal closes it; the residue's half cycles count in the
    /// last block).
    pub block_damage: Vec<f64>,
}

impl DetailLifetimeFatigue {
    /// The damage of one year of the record's traffic: D × (one year / the record's duration).
    pub fn damage_per_year(&self, record_seconds: f64) -> f64 {
        self.sum.damage * SECONDS_PER_YEAR / record_seconds
    }

    /// The years of such traffic that exhaust the detail, 1/D_year (∞ without damage).
    pub fn fatigue_life_years(&self, record_seconds: f64) -> f64 {
        1.0 / self.damage_per_year(record_seconds)
    }

    /// Δσ_E,2 of a design life of `years` of such traffic: the equivalent constant-amplitude
    /// range at 2 × 10⁶ cycles, Δσ_C (D_year × years)^{1/m} (EN 1993-1-9 §6.2, §8(3)) [Pa].
    pub fn equivalent_range_2e6(&self, record_seconds: f64, years: f64) -> f64 {
        (self.detail.detail.curve)
            .equivalent_range_2e6(self.damage_per_year(record_seconds) * years)
    }
}

/// A 100-year design working life (EN 1990:2002 Table 2.1, category 5: bridges) [years]: the
/// life of the reported Δσ_E,2.
pub const DESIGN_LIFE_YEARS: f64 = 100.0;

impl LifetimeFatigue {
    /// Each detail's summary.
    pub fn summaries(&self) -> Vec<DetailFatigueSummary> {
        let seconds = self.record_seconds;
        self.details
            .iter()
            .map(|d| DetailFatigueSummary {
                detail: d.detail.detail.clone(),
                curve_label: d.detail.detail.curve.label(),
                record_days: seconds / super::SECONDS_PER_DAY,
                sum: d.sum,
                damage_per_year: d.damage_per_year(seconds),
                fatigue_life_years: d.fatigue_life_years(seconds),
                equivalent_range_2e6: d.equivalent_range_2e6(seconds, DESIGN_LIFE_YEARS),
                largest_block_damage: d.block_damage.iter().copied().fold(0.0, f64::max),
            })
            .collect()
    }
}

/// The static fatigue of every detail over a record.
#[derive(Debug, Clone)]
pub struct LifetimeFatigue {
    /// Per detail, in the order given.
    pub details: Vec<DetailLifetimeFatigue>,
    /// The record's duration [s]: its known end (simulated days) or its last departure, less
    /// the start of its first block.
    pub record_seconds: f64,
    /// The events counted.
    pub events: u64,
    /// The trucks counted.
    pub trucks: u64,
}

/// The static fatigue of `details` under a time-ordered stream of trucks: each event's static
/// stress history at each detail, counted as one history across the record. The analysis's
/// whole record (a shard's block range is not read: counting carries across its ends). Memory:
/// one event, each detail's residue and a number per block.
pub fn static_lifetime_fatigue(
    analysis: &StaticLifetime,
    details: &[LifetimeDetail],
    trucks: impl IntoIterator<Item = RecordedTruck>,
) -> Result<LifetimeFatigue, LifetimeError> {
    let mut counters: Vec<RainflowCounter> =
        details.iter().map(|_| RainflowCounter::new()).collect();
    let mut results: Vec<DetailLifetimeFatigue> = details
        .iter()
        .map(|detail| DetailLifetimeFatigue {
            detail: detail.clone(),
            sum: DamageSum::new(detail.detail.curve),
            block_damage: Vec::new(),
        })
        .collect();
    let mut failure = None;
    let placed = placed_until_failure(analysis, trucks, &mut failure);
    let (mut events, mut truck_count, mut last_departure) = (0u64, 0u64, 0.0f64);
    let mut first_block = None;
    event::for_each_event(placed, |trucks: &[PlacedTruck]| {
        events += 1;
        truck_count += trucks.len() as u64;
        last_departure = last_departure.max(event::last_departure(trucks));
        let block = analysis.block_of(trucks[0].arrival);
        let first = *first_block.get_or_insert(block);
        let slot = (block - first) as usize;
        for ((detail, counter), result) in details.iter().zip(&mut counters).zip(&mut results) {
            let lines = &analysis.effects[detail.effect].lines;
            let history = event::event_history_at_breakpoints(trucks, lines, analysis.deck_length);
            if result.block_damage.len() <= slot {
                result.block_damage.resize(slot + 1, 0.0);
            }
            let (sum, block_damage) = (&mut result.sum, &mut result.block_damage[slot]);
            for value in history {
                counter.push(detail.detail.stress(value), |cycle| {
                    let before = sum.damage;
                    sum.add(cycle);
                    *block_damage += sum.damage - before;
                });
            }
        }
    })?;
    if let Some(error) = failure {
        return Err(error);
    }
    for (counter, result) in counters.into_iter().zip(&mut results) {
        let (sum, blocks) = (&mut result.sum, &mut result.block_damage);
        counter.finish(|cycle| {
            let before = sum.damage;
            sum.add(cycle);
            if let Some(last) = blocks.last_mut() {
                *last += sum.damage - before;
            }
        });
    }
    let start = first_block.unwrap_or(0) as f64 * analysis.block_seconds;
    let end = analysis
        .record_end
        .unwrap_or(last_departure)
        .max(last_departure);
    Ok(LifetimeFatigue {
        details: results,
        record_seconds: (end - start).max(0.0),
        events,
        trucks: truck_count,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fatigue::{count_by_range, rainflow, SnCurve};
    use crate::lifetime::tests::{analysis, midspan_moment, quarter_shear, truck, SPAN};
    use crate::model::station::Quantity;
    use crate::traffic::TravelDirection::{Backward, Forward};

    fn detail(quantity: Quantity, curve: SnCurve) -> LifetimeDetail {
        LifetimeDetail {
            detail: FatigueDetail {
                name: "detail".into(),
                station: "mid".into(),
                quantity,
                stress_per_effect: 100.0,
                stress_concentration: 1.0,
                fibre: "section_modulus".into(),
                curve,
            },
            effect: 0,
        }
    }

    /// n single-axle trucks of weight W, each alone on a simple span, raise the midspan moment
    /// from 0 to WL/4 and back: as one history, n cycles of range WL/4 (the residue's two half
    /// cycles included), so that D = n/N_R(σ) exactly; the blocks' damages sum to D.
    #[test]
    fn lone_single_axle_trucks_each_do_one_cycle_of_the_closed_form() {
        let analysis = StaticLifetime {
            block_seconds: 3_600.0,
            ..analysis(vec![midspan_moment()])
        };
        let weight = 40_000.0;
        let n = 30;
        let trucks: Vec<RecordedTruck> = (0..n)
            .map(|i| truck(600.0 * i as f64, 1, Forward, &[], &[weight]))
            .collect();
        let curve = SnCurve::eurocode_direct(71.0e6);
        let fatigue =
            static_lifetime_fatigue(&analysis, &[detail(Quantity::BendingMoment, curve)], trucks)
                .unwrap();
        let result = &fatigue.details[0];
        let stress = 100.0 * weight * 30.0 / 4.0;
        assert_eq!(result.sum.cycles, n as f64);
        assert_eq!(result.sum.max_range, stress);
        let expected = n as f64 / curve.cycles_to_failure(stress);
        assert!((result.sum.damage - expected).abs() <= 1e-12 * expected);
        assert_eq!(result.block_damage.len(), 5);
        let blocks: f64 = result.block_damage.iter().sum();
        assert!((blocks - expected).abs() <= 1e-12 * expected);
        assert_eq!(fatigue.events, n as u64);
    }

    /// The breakpoint history holds every reversal of the continuous history: counting it gives
    /// the counts of the history sampled densely (every millisecond and at every breakpoint,
    /// each 1 ns before and after: the quarter shear's jumps are read on both sides): two
    /// five-axle trucks meeting and a two-axle truck following.
    #[test]
    fn the_breakpoint_history_counts_as_the_densely_sampled_history() {
        let axles: [f64; 4] = [3.6, 6.0, 1.3, 1.3];
        let loads = [60e3, 100e3, 80e3, 80e3, 80e3];
        let trucks = [
            truck(0.0, 1, Forward, &axles, &loads),
            truck(0.4, 1, Backward, &axles, &[50e3, 90e3, 70e3, 70e3, 70e3]),
            truck(1.9, 1, Forward, &[5.0], &[70e3, 110e3]),
        ];
        for (line, quantity) in [
            (midspan_moment(), Quantity::BendingMoment),
            (quarter_shear(), Quantity::ShearForce),
        ] {
            let analysis = analysis(vec![line]);
            let placed: Vec<PlacedTruck> = trucks
                .iter()
                .enumerate()
                .map(|(i, t)| crate::lifetime::place(&analysis, t, i + 1).unwrap())
                .collect();
            let lines = &analysis.effects[0].lines;
            let at_breakpoints = event::event_history_at_breakpoints(&placed, lines, SPAN);
            let end = event::last_departure(&placed);
            // Every breakpoint and a 1 ms grid, each read just before and just after.
            let mut times: Vec<f64> = (0..=(end * 1000.0) as usize)
                .map(|i| i as f64 * 1e-3)
                .collect();
            for truck in &placed {
                for b in 0..truck.loads.len() {
                    for &x in lines[truck.lane].knots() {
                        times.push(
                            truck.arrival
                                + (match truck.forward {
                                    true => x,
                                    false => SPAN - x,
                                } + truck.offsets[b])
                                    / truck.speed,
                        );
                    }
                }
            }
            let mut stamps: Vec<f64> = times.iter().flat_map(|&t| [t - 1e-9, t + 1e-9]).collect();
            stamps.sort_by(f64::total_cmp);
            let sampled: Vec<f64> = (stamps.iter())
                .map(|&t| event::effect_at(&placed, lines, SPAN, t))
                .collect();
            // The dense samples' ±1 ns offsets and round-off make micro-cycles (below 0.02 N·m
            // or N, observed); rainflow extracts them without changing the larger cycles, so
            // the cycles above 1 N·m (10⁻⁶ of the ranges) are compared.
            let counted = |history: &[f64]| {
                let cycles: Vec<_> = rainflow(history)
                    .into_iter()
                    .filter(|c| c.range > 1.0)
                    .collect();
                count_by_range(&cycles)
            };
            let (exact, dense) = (counted(&at_breakpoints), counted(&sampled));
            assert!(exact.len() >= 2, "{quantity:?}: {exact:?}");
            assert_eq!(exact.len(), dense.len(), "{quantity:?}");
            for ((r1, c1), (r2, c2)) in exact.iter().zip(&dense) {
                assert_eq!(c1, c2, "{quantity:?}");
                // ±1 ns of travel at 25 m/s moves a reversal by at most 2.5e-8 m × the largest
                // slope of the lines (1/2) × 500 kN.
                assert!((r1 - r2).abs() <= 1e-2, "{quantity:?}: {r1} {r2}");
            }
        }
    }
}
