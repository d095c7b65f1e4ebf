//! Which of a study's scenarios are integrated together, and which repeat another.
//!
//! Scenarios that differ only in their road share their position-dependent work when they are
//! integrated together ([`simulate_batch`](crate::solver::simulate_batch)): a batch holds such
//! scenarios. A scenario that differs from another only in a seed its road does not read (the
//! roughness samples of the paper's 'smooth' class, a user profile) is the same crossing: it is
//! computed once ([`run_crossings`](super::run_crossings) copies the result), a quarter of the
//! paper study's crossings.

use super::Scenario;
use crate::bits::same_bits;
use crate::road::{RoadProfile, RoadSpec};
use crate::solver::Crossing;

/// The scenarios of one bridge grouped into batches for [`run_crossings`](super::run_crossings),
/// each batch of scenarios that differ only in their road (and their analysis), so that their
/// crossings can be integrated together, with at most `largest` distinct crossings each (its
/// memory); a scenario that repeats another ([`same_run_but_road_seed`]) joins that one's
/// batch, where it is not integrated again. In the order of `scenarios` within each batch, the
/// batches in the order of their first scenario. Indices into `scenarios`. The grouping only
/// makes sharing likely: [`simulate_batch`](crate::solver::simulate_batch) and
/// [`run_crossings`](super::run_crossings) check what they share themselves, so a scenario in
/// the wrong batch costs time, never a number.
pub fn integration_batches(scenarios: &[&Scenario], largest: usize) -> Vec<Vec<usize>> {
    let largest = largest.max(1);
    // Each batch's members and its number of distinct crossings.
    let mut batches: Vec<(Vec<usize>, usize)> = Vec::new();
    for (i, scenario) in scenarios.iter().enumerate() {
        let repeated = |(members, _): &&mut (Vec<usize>, usize)| {
            members
                .iter()
                .any(|&j| same_run_but_road_seed(scenarios[j], scenario))
        };
        if let Some((members, _)) = batches.iter_mut().find(repeated) {
            members.push(i);
            continue;
        }
        let open = batches.iter_mut().find(|(members, distinct)| {
            *distinct < largest && same_crossing_but_road(scenarios[members[0]], scenario)
        });
        match open {
            Some((members, distinct)) => {
                members.push(i);
                *distinct += 1;
            }
            None => batches.push((vec![i], 1)),
        }
    }
    batches.into_iter().map(|(members, _)| members).collect()
}

/// Whether the later of two scenarios and its crossing repeat the earlier's run: the same run
/// but for the road's seed ([`same_run_but_road_seed`]) and the same crossing bit for bit
/// ([`same_crossing_bit_for_bit`]), so that the earlier's result is the later's.
pub fn repeats_run(
    (earlier, earlier_crossing): (&Scenario, &Crossing),
    (later, later_crossing): (&Scenario, &Crossing),
) -> bool {
    same_run_but_road_seed(earlier, later)
        && same_crossing_bit_for_bit(earlier_crossing, later_crossing)
}

/// Whether scenarios `a` and `b` ask for the same crossing apart from its road: the vehicles,
/// their motion and traffic, the free-vibration window and the integration.
fn same_crossing_but_road(a: &Scenario, b: &Scenario) -> bool {
    a.vehicle == b.vehicle
        && a.motion == b.motion
        && a.traffic == b.traffic
        && a.traffic_stream == b.traffic_stream
        && a.platoon_size == b.platoon_size
        && a.platoon_gap.to_bits() == b.platoon_gap.to_bits()
        && a.lane_pattern == b.lane_pattern
        && a.free_vibration_duration == b.free_vibration_duration
        && a.solver == b.solver
}

/// Whether scenarios `a` and `b` ask for the same run (crossing, integration, analysis,
/// design codes) apart from their names and the road's seed, where the road does not read it
/// ([`RoadSpec::reads_seed`]) or both seeds are equal. The crossings' equality bit for bit
/// ([`same_crossing_bit_for_bit`]) is still to be checked: this compares the specifications.
pub fn same_run_but_road_seed(a: &Scenario, b: &Scenario) -> bool {
    // Destructured so that a new field of the scenario must be considered here.
    let Scenario {
        name: _,
        bridge_label: _,
        bridge,
        road,
        analysis,
        rerun_mode_counts,
        fatigue_details,
        // The crossing's own fields, compared by `same_crossing_but_road`.
        vehicle: _,
        motion: _,
        traffic: _,
        traffic_stream: _,
        platoon_size: _,
        platoon_gap: _,
        lane_pattern: _,
        free_vibration_duration: _,
        solver: _,
    } = a;
    same_road_but_seed(road, &b.road)
        && same_crossing_but_road(a, b)
        && *analysis == b.analysis
        && *rerun_mode_counts == b.rerun_mode_counts
        && *fatigue_details == b.fatigue_details
        && *bridge == b.bridge
}

/// Equal road specifications but for a seed that the road does not read.
fn same_road_but_seed(a: &RoadSpec, b: &RoadSpec) -> bool {
    if a.seed != b.seed && (a.reads_seed() || b.reads_seed()) {
        return false;
    }
    // The roughness and profile first: a cheap refusal before the clone of a user profile.
    a.roughness == b.roughness
        && a.profile == b.profile
        && *a
            == RoadSpec {
                seed: a.seed,
                ..b.clone()
            }
}

/// Whether two crossings are the same bit for bit: equal vehicles and motions, and roads and
/// free-vibration windows equal in every bit (so that −0.0 and 0.0 differ).
pub fn same_crossing_bit_for_bit(a: &Crossing, b: &Crossing) -> bool {
    let Crossing {
        vehicles,
        road,
        free_vibration_duration,
    } = a;
    same_profile_bits(road, &b.road)
        && free_vibration_duration.map(f64::to_bits) == b.free_vibration_duration.map(f64::to_bits)
        && *vehicles == b.vehicles
}

/// Road profiles equal in every bit.
fn same_profile_bits(a: &RoadProfile, b: &RoadProfile) -> bool {
    a.start.to_bits() == b.start.to_bits()
        && a.spacing.to_bits() == b.spacing.to_bits()
        && same_bits(&a.left, &b.left)
        && same_bits(&a.right, &b.right)
}
