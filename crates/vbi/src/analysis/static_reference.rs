//! The exact static reference S(t) = Σ_w S_w · IL(x_w(t), y_w): the static wheel loads S_w at the
//! wheels' positions at every instant, through the influence lines of the full stiffness (not
//! truncated modes). It is the denominator of every DAF (Eqs. 15–16).
//!
//! The influence fields are first copied node-major (for each deck node, every station's
//! deflection and left and right moment fields side by side), so that one wheel's reader (the
//! cubics of its element, [`crate::deck::DeckReader`]) reads contiguous rows instead of
//! gathering from 3 × stations fields.

use std::sync::{Arc, Mutex};

use serde::{Deserialize, Serialize};

use super::continuous_extreme::continuous_extreme;
use super::node_major::NodeMajorFields;
use super::single_vehicle::VehiclePaths;
use super::{has_daf, AnalysisError};
use crate::deck::{DeckField, DeckReader};
use crate::influence::InfluenceLines;
use crate::modal::{ModalBasis, Quantity};
use crate::solver::{ContactPath, ResponseHistory, WheelPaths};

/// Response of every station at every instant of a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StaticReference {
    /// Number of stations.
    pub station_count: usize,
    /// Number of instants.
    pub step_count: usize,
    /// Deflection [m], step-major: `deflection[i * station_count + s]`.
    pub deflection: Vec<f64>,
    /// Bending moment [N·m], same layout.
    pub bending_moment: Vec<f64>,
}

impl StaticReference {
    fn zeros(station_count: usize, step_count: usize) -> Self {
        StaticReference {
            station_count,
            step_count,
            deflection: vec![0.0; station_count * step_count],
            bending_moment: vec![0.0; station_count * step_count],
        }
    }

    /// History of one station's deflection or bending moment (empty for the force quantities,
    /// which [`static_force_reference`] gives for the stations that need them).
    pub fn history(&self, station: usize, quantity: Quantity) -> Vec<f64> {
        let table = match quantity {
            Quantity::Deflection => &self.deflection,
            Quantity::BendingMoment => &self.bending_moment,
            Quantity::ShearForce | Quantity::SupportReaction => return Vec::new(),
        };
        (0..self.step_count)
            .map(|i| table[i * self.station_count + station])
            .collect()
    }
}

/// The exact static reference S(t) of every station (see the module documentation).
pub fn static_reference(
    influence: &InfluenceLines,
    history: &ResponseHistory,
) -> Result<StaticReference, AnalysisError> {
    let stations = influence.stations.len();
    let paths = history.wheel_paths();
    // Allocated once the history's sizes are checked.
    let (steps, _) = recorded_contacts(paths)?;
    let mut reference = StaticReference::zeros(stations, steps);
    for_each_static_row(influence, paths, |i, deflection, moment| {
        let row = i * stations..(i + 1) * stations;
        reference.deflection[row.clone()].copy_from_slice(deflection);
        reference.bending_moment[row].copy_from_slice(moment);
    })?;
    Ok(reference)
}

/// Calls `each(i, deflection, moment)` with S(t) of every station at each instant i in turn,
/// the rows of [`static_reference`] (the same sums in the same order), without holding more
/// than one instant.
fn for_each_static_row(
    influence: &InfluenceLines,
    paths: WheelPaths,
    mut each: impl FnMut(usize, &[f64], &[f64]),
) -> Result<(), AnalysisError> {
    let stations = influence.stations.len();
    for (what, len) in [
        ("influence deflection fields", influence.deflection.len()),
        ("influence moment_left fields", influence.moment_left.len()),
        (
            "influence moment_right fields",
            influence.moment_right.len(),
        ),
    ] {
        if len != stations {
            return Err(AnalysisError::Mismatch {
                what,
                expected: stations,
                found: len,
            });
        }
    }
    let table = NodeMajorFields::new(influence);
    let (steps, contacts) = recorded_contacts(paths)?;
    let mut values = vec![0.0; table.count];
    let (mut deflection, mut moment) = (vec![0.0; stations], vec![0.0; stations]);
    let fields = (&table.deflection[..], &table.slope[..]);
    let mut readers: Vec<DeckReader> = (paths.contacts.iter())
        .map(|c| DeckReader::new(&influence.deck, c.lateral_position, table.count))
        .collect();
    for i in 0..steps {
        deflection.fill(0.0);
        moment.fill(0.0);
        let positions = &paths.positions[i * contacts..(i + 1) * contacts];
        for ((contact, &x), reader) in paths.contacts.iter().zip(positions).zip(&mut readers) {
            if !reader.values(fields, x, &mut values) {
                continue;
            }
            let (u, rest) = values.split_at(stations);
            let (left, right) = rest.split_at(stations);
            let load = contact.static_load;
            for (acc, &value) in deflection.iter_mut().zip(u) {
                *acc += load * value;
            }
            // The moment field of the element on the side of the station away from the wheel.
            for (s, acc) in moment.iter_mut().enumerate() {
                let value = if influence.reads_left_element(s, x) {
                    left[s]
                } else {
                    right[s]
                };
                *acc += load * value;
            }
        }
        each(i, &deflection, &moment);
    }
    Ok(())
}

/// The largest sampled local extremes of a static history in each direction, taken instant by
/// instant: the candidates whose extreme between the instants may exceed the sampled extreme's.
/// Two axles of a group crossing a moment station give two peaks within a fraction of a per
/// cent of each other; the larger sampled one need not hold the larger extreme between the
/// instants, so each candidate is refined ([`continuous_extreme`]) and the best taken.
#[derive(Debug, Clone, Default)]
struct SampledPeaks {
    /// The last two instants' (step, value).
    last: [Option<(usize, f64)>; 2],
    /// The largest local maxima (of σ·S for σ = +1, −1), at most [`SampledPeaks::KEPT`] each,
    /// as (step, S).
    kept: [Vec<(usize, f64)>; 2],
}

impl SampledPeaks {
    /// The local extremes kept in each direction: an axle group has at most three axles (a
    /// tridem), and a fourth covers a second vehicle's.
    const KEPT: usize = 4;

    /// Takes the value S at instant i (instants in order).
    fn take(&mut self, i: usize, value: f64) {
        match self.last {
            [Some(before), Some(middle)] => self.consider(middle, (before.1, value)),
            // The first instant is a candidate when the second does not exceed it.
            [None, Some(first)] => self.consider(first, (first.1, value)),
            _ => {}
        }
        self.last = [self.last[1], Some((i, value))];
    }

    /// Keeps `peak` if it is a local extreme between its neighbours' values.
    fn consider(&mut self, peak: (usize, f64), (before, after): (f64, f64)) {
        for (d, sign) in [1.0, -1.0].into_iter().enumerate() {
            let v = sign * peak.1;
            if v >= sign * before && v >= sign * after {
                let kept = &mut self.kept[d];
                kept.push(peak);
                kept.sort_by(|a, b| (sign * b.1).total_cmp(&(sign * a.1)));
                kept.truncate(Self::KEPT);
            }
        }
    }

    /// The candidates in each direction, σ = +1 then σ = −1 (the last instant included).
    fn finish(mut self) -> [Vec<(usize, f64)>; 2] {
        if let [before, Some(last)] = self.last {
            let before = before.map_or(last.1, |b| b.1);
            self.consider(last, (before, last.1));
        }
        self.kept
    }
}

/// The static extreme (step and signed value) of every station's deflection and moment,
/// `[2 s + q]`, the extreme between the instants around it ([`continuous_extreme`]: the value
/// and its fractional instant), and the largest magnitude of each over the stations: all that a
/// DAF analysis reads of the static reference.
#[derive(Debug)]
pub(super) struct StaticExtremes {
    /// The continuous extreme of each, (value, instant).
    continuous: Vec<(f64, f64)>,
    /// The continuous extreme of each in the other direction, (value, instant); (0, 0) where
    /// the run does not load it that way.
    opposite: Vec<(f64, f64)>,
    /// The largest extreme of one vehicle alone, in the direction of each, for a run of two or
    /// more vehicles ([`single_vehicle_extreme`]); empty otherwise.
    single_vehicle: Vec<Option<f64>>,
    largest: [f64; 2],
}

impl StaticExtremes {
    /// The extremes of [`static_reference`] of a run with wheel paths `paths`, taken instant by
    /// instant as its rows are computed (the value of largest magnitude; the first on a tie;
    /// step 0 and 0 for an all-zero history), without holding the reference.
    pub(super) fn of(
        influence: &InfluenceLines,
        paths: WheelPaths,
    ) -> Result<StaticExtremes, AnalysisError> {
        let entries = 2 * influence.stations.len();
        let mut extremes = vec![(0usize, 0.0f64); entries];
        // The sampled extreme in each direction (largest, most negative), 0 where none.
        let mut directed = vec![[(0usize, 0.0f64); 2]; entries];
        let mut peaks = vec![SampledPeaks::default(); entries];
        for_each_static_row(influence, paths, |i, deflection, moment| {
            for (qi, row) in [deflection, moment].into_iter().enumerate() {
                for (s, &v) in row.iter().enumerate() {
                    let best = &mut extremes[2 * s + qi];
                    if v.abs() > best.1.abs() {
                        *best = (i, v);
                    }
                    let [highest, lowest] = &mut directed[2 * s + qi];
                    if v > highest.1 {
                        *highest = (i, v);
                    }
                    if v < lowest.1 {
                        *lowest = (i, v);
                    }
                    peaks[2 * s + qi].take(i, v);
                }
            }
        })?;
        let mut continuous = Vec::with_capacity(entries);
        let mut opposite = Vec::with_capacity(entries);
        for (k, ((&sampled, peaks), directed)) in
            (extremes.iter().zip(peaks).zip(&directed)).enumerate()
        {
            let quantity = [Quantity::Deflection, Quantity::BendingMoment][k % 2];
            let target = (k / 2, quantity);
            let refine = |peak| continuous_extreme(influence, paths, target, peak);
            let best_of = |sign: f64, sampled: (usize, f64), candidates: Vec<(usize, f64)>| {
                candidates
                    .into_iter()
                    .map(refine)
                    .fold(refine(sampled), |best, other| {
                        if sign * other.0 > sign * best.0 {
                            other
                        } else {
                            best
                        }
                    })
            };
            let sign = sampled.1.signum();
            let [positive, negative] = peaks.finish();
            let (main, other, other_sampled) = match sign < 0.0 {
                true => (negative, positive, directed[0]),
                false => (positive, negative, directed[1]),
            };
            continuous.push(best_of(sign, sampled, main));
            // The extreme in the other direction, where the run loads that way at all.
            opposite.push(match other_sampled.1 == 0.0 {
                true => (0.0, 0.0),
                false => best_of(-sign, other_sampled, other),
            });
        }
        let mut largest = [0.0f64; 2];
        for (k, &(value, _)) in continuous.iter().enumerate() {
            largest[k % 2] = largest[k % 2].max(value.abs());
        }
        let single_vehicle = single_vehicle_extremes(influence, paths, &continuous)?;
        Ok(StaticExtremes {
            continuous,
            opposite,
            single_vehicle,
            largest,
        })
    }

    /// Signed value and fractional instant of station `s`'s extreme of quantity `qi` in the
    /// direction opposite to [`StaticExtremes::continuous_at`]'s ((0, 0) where the run does not
    /// load it that way).
    pub(super) fn opposite_at(&self, s: usize, qi: usize) -> (f64, f64) {
        self.opposite[s * 2 + qi]
    }

    /// Whether a static extreme `value` of quantity `qi` has a DAF (see `has_daf`).
    pub(super) fn has_daf_of(&self, value: f64, qi: usize) -> bool {
        has_daf(value, self.largest[qi])
    }

    /// The largest static extreme of one vehicle alone at station `s`, quantity `qi`, in the
    /// direction of the event's (None for a run of one vehicle, or where no vehicle alone loads
    /// the station that way).
    pub(super) fn single_vehicle_at(&self, s: usize, qi: usize) -> Option<f64> {
        self.single_vehicle.get(s * 2 + qi).copied().flatten()
    }

    /// Signed value and fractional instant of station `s`'s extreme of quantity `qi` between
    /// the instants ([`continuous_extreme`]).
    pub(super) fn continuous_at(&self, s: usize, qi: usize) -> (f64, f64) {
        self.continuous[s * 2 + qi]
    }

    /// Whether a station's quantity has a DAF (see `has_daf`).
    pub(super) fn defined(&self, s: usize, qi: usize) -> bool {
        has_daf(self.continuous_at(s, qi).0, self.largest[qi])
    }

    /// The default RDM station: the station not over a support with the largest static
    /// deflection.
    pub(super) fn rdm_station(&self, basis: &ModalBasis) -> Option<usize> {
        (0..basis.stations.len())
            .filter(|&s| !basis.stations[s].over_support && self.defined(s, 0))
            .max_by(|&a, &b| {
                let (ea, eb) = (
                    self.continuous_at(a, 0).0.abs(),
                    self.continuous_at(b, 0).0.abs(),
                );
                ea.total_cmp(&eb).then(b.cmp(&a))
            })
    }
}

/// The largest static extreme of one vehicle alone at every station and quantity `[2 s + q]`,
/// in the direction of the event's (`event`, from [`continuous_extreme`]), taken between the
/// steps ([`crate::analysis`]'s `single_vehicle` module); empty for a run of one vehicle. Each
/// vehicle's S_v(t) comes from [`for_each_static_row`] over its own wheels, every station in
/// one pass, so that all vehicles together cost one pass of the event's wheels.
fn single_vehicle_extremes(
    influence: &InfluenceLines,
    paths: WheelPaths,
    event: &[(f64, f64)],
) -> Result<Vec<Option<f64>>, AnalysisError> {
    let vehicles = VehiclePaths::of_each(paths);
    if vehicles.is_empty() {
        return Ok(Vec::new());
    }
    let mut best: Vec<Option<f64>> = vec![None; event.len()];
    for vehicle in &vehicles {
        // Its sampled extreme in the event's direction (step, value), where it has one.
        let mut sampled: Vec<Option<(usize, f64)>> = vec![None; event.len()];
        for_each_static_row(influence, vehicle.paths(), |i, deflection, moment| {
            for (qi, row) in [deflection, moment].into_iter().enumerate() {
                for (s, &v) in row.iter().enumerate() {
                    let k = 2 * s + qi;
                    let sign = event[k].0.signum();
                    if sign * v > 0.0 && sampled[k].is_none_or(|(_, b)| sign * v > sign * b) {
                        sampled[k] = Some((i, v));
                    }
                }
            }
        })?;
        for (k, found) in sampled.into_iter().enumerate() {
            let Some(found) = found else { continue };
            let quantity = [Quantity::Deflection, Quantity::BendingMoment][k % 2];
            let (value, _) =
                continuous_extreme(influence, vehicle.paths(), (k / 2, quantity), found);
            let sign = event[k].0.signum();
            if best[k].is_none_or(|b| sign * value > sign * b) {
                best[k] = Some(value);
            }
        }
    }
    Ok(best)
}

/// The static references already computed on one bridge, reused by the runs whose wheels take
/// the same paths: their extremes, all that a DAF analysis reads of them.
///
/// S(t) depends only on the influence lines (the bridge's) and on where each wheel is at every
/// instant with which static load: not on the road, nor on the vehicle's response. The road
/// samples of a study's bridge × vehicle × speed all have the same paths, so one computation
/// serves all of them (the paper study: 40 runs each). A run reuses an entry only when its
/// contacts (lateral position and static load) and its recorded positions are equal to the
/// entry's bit for bit, so the reused extremes are those it would compute. Holds at most
/// [`StaticReferenceCache::CAPACITY`] entries, the oldest replaced first; safe to share among
/// threads. A clone starts empty.
///
/// An entry keeps the extremes, not the reference: the reference of every station at every
/// instant takes 16 B per station and instant, megabytes per entry on the paper's bridges (about
/// 21 MB held at once per bridge of the paper study when the entries held it).
#[derive(Debug, Default)]
pub struct StaticReferenceCache {
    entries: Mutex<Vec<CachedExtremes>>,
}

#[derive(Debug)]
struct CachedExtremes {
    /// The contacts of the run it was computed for (lateral positions and static loads).
    contacts: Vec<ContactPath>,
    /// That run's recorded contact positions [m], step-major.
    positions: Vec<f64>,
    extremes: Arc<StaticExtremes>,
}

impl Clone for StaticReferenceCache {
    fn clone(&self) -> Self {
        StaticReferenceCache::default()
    }
}

impl StaticReferenceCache {
    /// Entries kept: a study's bridge meets few distinct wheel paths (vehicles × speeds) at once.
    pub const CAPACITY: usize = 8;

    /// [`StaticExtremes::of`]`(influence, paths)`: stored ones if a run with the same paths
    /// was computed on the same influence lines, else computed and stored. The cache must serve
    /// one set of influence lines only (the [`PreparedBridge`](crate::crossing::PreparedBridge)
    /// that holds it).
    pub(super) fn static_extremes(
        &self,
        influence: &InfluenceLines,
        paths: WheelPaths,
    ) -> Result<Arc<StaticExtremes>, AnalysisError> {
        let same_paths = |entry: &CachedExtremes| paths.same_as(&entry.contacts, &entry.positions);
        if let Some(found) = self.lock().iter().find(|e| same_paths(e)) {
            return Ok(Arc::clone(&found.extremes));
        }
        // Computed outside the lock: two threads may both compute the same extremes once.
        let extremes = Arc::new(StaticExtremes::of(influence, paths)?);
        let mut entries = self.lock();
        if entries.len() >= Self::CAPACITY {
            entries.remove(0);
        }
        entries.push(CachedExtremes {
            contacts: paths.contacts.to_vec(),
            positions: paths.positions.to_vec(),
            extremes: Arc::clone(&extremes),
        });
        Ok(extremes)
    }

    /// Forgets every stored reference.
    pub fn clear(&self) {
        self.lock().clear();
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<CachedExtremes>> {
        // A panic while holding the lock leaves only whole entries behind.
        self.entries.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The exact static history of the force quantity (shear force, or support reaction at a
/// support) of each of `stations`, S(t) = Σ_w S_w · IL(x_w(t), y_w) with the field on the side
/// of the station away from each wheel; an empty history for a station without one. Separate
/// from [`static_reference`], which every run needs for every station, because only the
/// stations analysed in full need it.
pub fn static_force_reference(
    influence: &InfluenceLines,
    history: &ResponseHistory,
    stations: &[usize],
) -> Result<Vec<Vec<f64>>, AnalysisError> {
    static_force_reference_of(influence, history.wheel_paths(), stations)
}

/// [`static_force_reference`] of a run with wheel paths `paths`.
pub(super) fn static_force_reference_of(
    influence: &InfluenceLines,
    paths: WheelPaths,
    stations: &[usize],
) -> Result<Vec<Vec<f64>>, AnalysisError> {
    let (steps, contacts) = recorded_contacts(paths)?;
    let quantities: Vec<Option<Quantity>> = stations
        .iter()
        .map(|&s| {
            let quantity = influence.stations[s].force_quantity();
            influence.has_quantity(s, quantity).then_some(quantity)
        })
        .collect();
    let mut out: Vec<Vec<f64>> = quantities
        .iter()
        .map(|q| match q {
            Some(_) => vec![0.0; steps],
            None => Vec::new(),
        })
        .collect();
    // The stations' left and right lines node-major, read by one reader per contact (each
    // line's values as a `LineReader` of the correction reads it, bit for bit: the cubics are
    // field by field).
    let lined: Vec<usize> = (0..stations.len())
        .filter(|&k| quantities[k].is_some())
        .collect();
    let left = lined.iter().map(|&k| &influence.force_left[stations[k]]);
    let right = lined.iter().map(|&k| &influence.force_right[stations[k]]);
    let fields: Vec<&DeckField> = left.chain(right).collect();
    let table = NodeMajorFields::of(&influence.deck, &fields);
    let mut values = vec![0.0; table.count];
    let mut readers: Vec<DeckReader> = (paths.contacts.iter())
        .map(|c| DeckReader::new(&influence.deck, c.lateral_position, table.count))
        .collect();
    let table_fields = (&table.deflection[..], &table.slope[..]);
    for i in 0..steps {
        let positions = &paths.positions[i * contacts..(i + 1) * contacts];
        for ((contact, &x), reader) in paths.contacts.iter().zip(positions).zip(&mut readers) {
            if !reader.values(table_fields, x, &mut values) {
                continue;
            }
            let (left, right) = values.split_at(lined.len());
            for (j, &k) in lined.iter().enumerate() {
                // The line of the element on the side of the station away from the wheel.
                let value = if influence.reads_left_element(stations[k], x) {
                    left[j]
                } else {
                    right[j]
                };
                out[k][i] += contact.static_load * value;
            }
        }
    }
    Ok(out)
}

/// The run's (steps, contacts), once its recorded contact positions are checked to hold one
/// position per contact and step.
fn recorded_contacts(paths: WheelPaths) -> Result<(usize, usize), AnalysisError> {
    let steps = paths.step_count;
    let contacts = paths.contacts.len();
    // Saturating: a deserialised history may claim any number of instants.
    let recorded = steps.saturating_mul(contacts);
    if paths.positions.len() != recorded {
        return Err(AnalysisError::Mismatch {
            what: "contact positions (steps × contacts)",
            expected: recorded,
            found: paths.positions.len(),
        });
    }
    Ok((steps, contacts))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::{discretise, statics::influence_lines, MeshOptions};
    use crate::model::{BeamSection, BridgeModel, ContinuousBeam};

    /// Two axles 12.01 m apart, the rear one 0.05 % heavier, cross a 20 m simple span at 30 m/s
    /// sampled every 1 ms (3 cm): the mid-span moment has two peaks, one axle over the station
    /// at a time (the other off the span), P₁ l/4 and P₂ l/4, which differ by less than the
    /// sampling's under-read at the influence line's kink (up to P/2 · 1.5 cm), and the 1 cm
    /// beyond a whole number of steps puts them at different phases of the sampling. The static
    /// extreme must be the larger, P₂ l/4, whatever the phase; refined around the larger sampled
    /// peak alone it is the smaller one at some phases.
    #[test]
    fn the_static_extreme_is_the_larger_of_two_nearly_equal_peaks_at_every_sampling_phase() {
        let span = 20.0;
        let section = BeamSection {
            flexural_rigidity: 4.86535e10,
            mass_per_length: 18358.0,
        };
        let beam = BridgeModel::ContinuousBeam(ContinuousBeam::pinned(vec![span], section));
        let fe = discretise(&beam, &MeshOptions::default()).unwrap();
        let influence = influence_lines(&fe).unwrap();
        let station = (influence.stations.iter())
            .position(|s| s.name == "span1_mid_section")
            .unwrap();
        let (front, rear, spacing) = (100e3, 100.05e3, 12.01);
        let contact = |offset: f64, load: f64| ContactPath {
            vehicle: 0,
            longitudinal_offset: offset,
            lateral_position: 0.0,
            static_load: load,
        };
        let contacts = [contact(0.0, front), contact(-spacing, rear)];
        let expected = rear * span / 4.0;
        let (speed, step, steps) = (30.0, 1e-3, 1300);
        let mut single_peak_misses = 0;
        for phase in 0..10 {
            let start = 0.5 + 0.1 * phase as f64 * speed * step;
            let positions: Vec<f64> = (0..steps)
                .flat_map(|i| {
                    let x = start + speed * step * i as f64;
                    [x, x - spacing]
                })
                .collect();
            let paths = WheelPaths {
                contacts: &contacts,
                positions: &positions,
                step_count: steps,
            };
            let extremes = StaticExtremes::of(&influence, paths).unwrap();
            let (value, _) = extremes.continuous_at(station, 1);
            assert!(
                (value / expected - 1.0).abs() < 1e-9,
                "phase {phase}: {value} vs {expected}"
            );
            // The refinement around the larger sampled peak alone (before issue 46's fix).
            let mut sampled = (0, 0.0f64);
            for i in 0..steps {
                let row = [positions[2 * i], positions[2 * i + 1]];
                let moment = |x: f64| {
                    if x < span / 2.0 {
                        x / 2.0
                    } else {
                        (span - x) / 2.0
                    }
                };
                let on = |x: f64| (0.0..=span).contains(&x);
                let m: f64 = (row.iter().zip([front, rear]))
                    .filter(|(x, _)| on(**x))
                    .map(|(x, p)| p * moment(*x))
                    .sum();
                if m > sampled.1 {
                    sampled = (i, m);
                }
            }
            let target = (station, Quantity::BendingMoment);
            let (alone, _) = continuous_extreme(&influence, paths, target, sampled);
            if (alone / expected - 1.0).abs() > 1e-6 {
                single_peak_misses += 1;
            }
        }
        assert!(
            single_peak_misses > 0,
            "the case does not test the two peaks"
        );
    }
}
