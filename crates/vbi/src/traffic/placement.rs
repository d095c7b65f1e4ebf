//! The vehicles of a scenario's crossing event, placed for t = 0: the scenario's own vehicle (its
//! front axle at the start of the approach), the copies of its platoon, and the further vehicles
//! of `traffic`, each entering at a time or at a gap; and the road extent that every tyre's path
//! needs.
//!
//! Travel coordinates s are distances past the deck entry of a vehicle's direction
//! ([`law`](super::law)). A vehicle given an entry time t_e starts at s₀ with s(t_e) = 0: at
//! constant speed s₀ = −v t_e; under a constant acceleration a with the speed v_e at the entry,
//! s₀ = −v_e t_e + ½ a t_e² (uniform acceleration run backwards from the entry).

use super::{
    check_vehicles_apart, first_catching_up, Entry, Motion, SpeedProfile, TrafficError,
    TrafficSpec, TravelDirection, VehicleRun,
};
use crate::model::BridgeModel;
use crate::vehicle::{assemble, VehicleModel};

/// The vehicles of the scenario's event, in order: its own vehicle, the rest of its platoon,
/// then `traffic`, then the vehicles drawn from `traffic_stream`. Errs (naming the vehicle) on a speed that would reach zero before the
/// vehicle leaves the deck, a gap with no vehicle ahead in the same direction, a tyre outside
/// the deck width, vehicles that overlap at t = 0 ([`check_vehicles_apart`]), or two vehicles
/// in one lane whose gap closes during the event ([`first_catching_up`]: the later of the two
/// in the list is named, the message names both). It needs no modal analysis, so `vbi check`
/// runs it before any work.
pub fn vehicle_runs(scenario: &TrafficSpec) -> Result<Vec<VehicleRun>, TrafficError> {
    let length = scenario.bridge.deck_length();
    let approach_start = scenario.road.extent_for_bridge(length).0;
    let own = assemble(scenario.vehicle).map_err(TrafficError::Vehicle)?;
    let mut runs: Vec<VehicleRun> = Vec::new();
    let mut labels: Vec<String> = Vec::new();
    for copy in 0..scenario.platoon_size.max(1) {
        let start = match runs.last() {
            None => approach_start,
            Some(ahead) => {
                ahead.start_position - ahead.vehicle.trailing_length() - scenario.platoon_gap
            }
        };
        labels.push(match copy {
            0 => scenario.vehicle.name.clone(),
            _ => format!("{} (platoon copy {})", scenario.vehicle.name, copy + 1),
        });
        let run = place(
            own.clone(),
            scenario.motion,
            start,
            length,
            runs.len(),
            &labels,
        )?;
        runs.push(run);
    }
    if let Some(direction) = scenario
        .lane_pattern
        .copy_direction(scenario.motion.direction)
    {
        check_lane_pattern(scenario, &own, &labels)?;
        labels.push(format!("{} (lane 2)", scenario.vehicle.name));
        let motion = Motion {
            direction,
            lateral_position: -scenario.motion.lateral_position,
            ..scenario.motion.clone()
        };
        let run = place(
            own.clone(),
            &motion,
            approach_start,
            length,
            runs.len(),
            &labels,
        )?;
        runs.push(run);
    }
    let drawn = match scenario.traffic_stream {
        Some(stream) => stream
            .draw(scenario.road.seed)
            .map_err(TrafficError::Stream)?,
        None => Vec::new(),
    };
    for further in scenario.traffic.iter().chain(&drawn) {
        labels.push(further.label.clone());
        let vehicle = assemble(&further.vehicle).map_err(TrafficError::Vehicle)?;
        let start = match further.entry {
            Entry::Time(time) => start_for_entry_time(&further.motion, time)
                .map_err(|reason| traffic_error(runs.len(), &labels, reason))?,
            Entry::Gap(gap) => {
                let ahead = runs
                    .iter()
                    .rev()
                    .find(|r| r.direction == further.motion.direction)
                    .ok_or_else(|| {
                        traffic_error(
                            runs.len(),
                            &labels,
                            "an entry by `gap_m` needs a vehicle before it in the list that \
                             travels the same way; give `entry_time_s` instead"
                                .into(),
                        )
                    })?;
                ahead.start_position - ahead.vehicle.trailing_length() - gap
            }
        };
        let run = place(vehicle, &further.motion, start, length, runs.len(), &labels)?;
        runs.push(run);
    }
    check_lanes(scenario.bridge, &runs, &labels)?;
    check_vehicles_apart(&runs, length).map_err(TrafficError::Overlap)?;
    check_no_catching_up(scenario, &runs, &labels)?;
    Ok(runs)
}

/// Refuses a two-lane pattern ([`LanePattern`](super::LanePattern)) that makes no sense: with a
/// platoon or further traffic (the pattern arranges the scenario's one vehicle; give the others
/// as `[[traffic]]` instead), or with lanes that overlap (the vehicle's wheels reach across the
/// deck's centreline, where its mirror image runs).
fn check_lane_pattern(
    scenario: &TrafficSpec,
    own: &VehicleModel,
    labels: &[String],
) -> Result<(), TrafficError> {
    let pattern = scenario.lane_pattern.name();
    let refuse = |reason: String| Err(traffic_error(0, labels, reason));
    if scenario.platoon_size > 1 {
        return refuse(format!(
            "lane_pattern `{pattern}` places one vehicle in each of two lanes; it is not allowed \
             with platoon_size = {}: give platoon_size = 1, or the vehicles as [[traffic]]",
            scenario.platoon_size
        ));
    }
    if !scenario.traffic.is_empty() || scenario.traffic_stream.is_some() {
        return refuse(format!(
            "lane_pattern `{pattern}` places the scenario's vehicle and its copy and is not \
             allowed with [[traffic]] or [traffic_stream]: give lane_pattern = \"single\", or \
             every vehicle as [[traffic]]"
        ));
    }
    let half_width = own
        .contacts
        .iter()
        .map(|c| c.lateral_offset.abs())
        .fold(0.0, f64::max);
    let y = scenario.motion.lateral_position;
    if y.abs() <= half_width {
        return refuse(format!(
            "lane_pattern `{pattern}` puts a copy in the mirrored lane at y = {:.3} m: with \
             lateral_position_m = {y} m the two lanes overlap (the wheels reach {half_width:.3} m \
             either side of the vehicle's centreline); give |lateral_position_m| > \
             {half_width:.3} m, e.g. -1.875 for the right-hand lane of a 7.5 m carriageway",
            0.0 - y
        ));
    }
    Ok(())
}

/// Refuses two vehicles in one lane and direction whose gap closes before the last vehicle has
/// left the deck, naming both (their place in the input), when and where they meet.
fn check_no_catching_up(
    scenario: &TrafficSpec,
    runs: &[VehicleRun],
    labels: &[String],
) -> Result<(), TrafficError> {
    let Some(meeting) = first_catching_up(runs, scenario.bridge.deck_length()) else {
        return Ok(());
    };
    let name = |index: usize| {
        format!(
            "vehicle {} ({}, at `{}`)",
            index + 1,
            labels.get(index).map(String::as_str).unwrap_or_default(),
            input_entry(scenario, index)
        )
    };
    // The error names the later of the two in the list; the message the other one.
    let relation = if meeting.follower > meeting.leader {
        format!("catches up with {} ahead of it", name(meeting.leader))
    } else {
        format!("is caught up by {} behind it", name(meeting.follower))
    };
    let reason = format!(
        "{relation} in the same lane: the gap between the follower's front axle and the \
         leader's last axle closes at t = {:.3} s, {:.2} m past the deck entry (deck x = \
         {:.2} m), before the last vehicle has left the deck; vehicles cannot drive through \
         each other: give the follower a larger gap, a later entry or a lower speed, or the \
         leader less braking",
        meeting.time, meeting.travel, meeting.position
    );
    Err(traffic_error(
        meeting.leader.max(meeting.follower),
        labels,
        reason,
    ))
}

/// The key of the input table that vehicle `index` (0-based) of the event comes from:
/// `scenario` (its own vehicle and the platoon copies), `traffic[k]` (the k-th `[[traffic]]`
/// entry, 0-based) or `traffic_stream`; where a located error points.
pub fn input_entry(scenario: &TrafficSpec, index: usize) -> String {
    let copies = usize::from(!scenario.lane_pattern.is_single());
    let own = scenario.platoon_size.max(1) + copies;
    match index.checked_sub(own) {
        None => "scenario".to_string(),
        Some(k) if k < scenario.traffic.len() => format!("traffic[{k}]"),
        Some(_) => "traffic_stream".to_string(),
    }
}

/// One vehicle placed at travel coordinate `start` with the speed law of `motion` over a deck
/// of length L.
fn place(
    vehicle: VehicleModel,
    motion: &Motion,
    start: f64,
    deck_length: f64,
    index: usize,
    labels: &[String],
) -> Result<VehicleRun, TrafficError> {
    let exit = deck_length + vehicle.trailing_length();
    let speed = if !motion.speed_profile.is_empty() {
        SpeedProfile::Knots(motion.speed_profile.clone())
    } else {
        SpeedProfile::constant_acceleration(motion.speed, motion.acceleration, start, exit)
            .map_err(|stop| {
                traffic_error(
                    index,
                    labels,
                    format!(
                        "at {} m/s² from {} m/s at the deck entry the speed reaches zero at \
                         s = {:.2} m past the entry, before the vehicle has left the deck \
                         (s = {exit:.2} m) or while on the approach from s = {start:.2} m; \
                         give a smaller acceleration or a higher speed",
                        motion.acceleration, motion.speed, stop.travel
                    ),
                )
            })?
    };
    Ok(VehicleRun {
        vehicle,
        direction: motion.direction,
        lateral_position: motion.lateral_position,
        start_position: start,
        speed,
    })
}

/// The start travel coordinate s₀ from which `motion` reaches the deck entry at `time` [s].
/// With a speed profile, s₀ lies before its first knot s₁ (where the speed is the knot's v₁):
/// s₀ = s₁ − v₁ (time − T), T the profile's time from s₁ to the entry (for a first knot at or
/// past the entry, s₀ = −v₁ time).
pub(crate) fn start_for_entry_time(motion: &Motion, time: f64) -> Result<f64, String> {
    if !(time.is_finite() && time >= 0.0) {
        return Err(format!(
            "entry time {time} s is not allowed; expected a finite time >= 0"
        ));
    }
    if let Some(first) = motion.speed_profile.first() {
        if first.travel >= 0.0 {
            return Ok(-first.speed * time);
        }
        let profile = super::SpeedProfile::Knots(motion.speed_profile.clone());
        let to_entry = super::law::TravelLaw::new(first.travel, &profile).time_at_travel(0.0);
        if time < to_entry {
            return Err(format!(
                "entering at {time} s with this `speed_profile` needs at least {to_entry:.3} s \
                 from its first knot at s = {} m; give a later entry or a first knot nearer \
                 the deck",
                first.travel
            ));
        }
        return Ok(first.travel - first.speed * (time - to_entry));
    }
    let (v, a) = (motion.speed, motion.acceleration);
    let speed_at_start = v - a * time;
    if speed_at_start <= 0.0 {
        return Err(format!(
            "entering at {time} s with {v} m/s under {a} m/s² needs a speed of \
             {speed_at_start:.3} m/s at t = 0; give a smaller acceleration or an earlier entry"
        ));
    }
    Ok(-v * time + 0.5 * a * time * time)
}

/// Every tyre of every vehicle inside the deck width (on a grillage; a beam has no width).
fn check_lanes(
    model: &BridgeModel,
    runs: &[VehicleRun],
    labels: &[String],
) -> Result<(), TrafficError> {
    let Some((low, high)) = deck_lateral_extent(model) else {
        return Ok(());
    };
    for (index, run) in runs.iter().enumerate() {
        for contact in &run.vehicle.contacts {
            let y = run.lateral_position + contact.lateral_offset.abs();
            let y_other = run.lateral_position - contact.lateral_offset.abs();
            if y > high || y_other < low {
                return Err(traffic_error(
                    index,
                    labels,
                    format!(
                        "a wheel runs at y = {:.3} m, outside the deck (y from {:.3} to {:.3} m); \
                         move its `lateral_position_m`",
                        if y > high { y } else { y_other },
                        low,
                        high
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The lateral extent (−h, h) [m] that wheels may use, None where any lateral position is the
/// one line's (a beam): a grillage's deck width; for an imported deck of several lines, the
/// outermost lines plus half their mean spacing, the overhang that the lever rule's rigid
/// extrapolation beyond the outer line stands for.
fn deck_lateral_extent(model: &BridgeModel) -> Option<(f64, f64)> {
    let lines: Vec<f64> = match model {
        BridgeModel::Grillage(grillage) => {
            let half = 0.5 * grillage.deck_width;
            return Some((-half, half));
        }
        BridgeModel::ContinuousBeam(_) => return None,
        BridgeModel::ImportedMatrices(m) => {
            m.deck_lines.iter().map(|l| l.lateral_position).collect()
        }
        BridgeModel::ImportedModes(m) => m.data.lines.iter().map(|l| l.lateral_position).collect(),
    };
    if lines.len() < 2 {
        return None;
    }
    let (low, high) = lines
        .iter()
        .fold((f64::MAX, f64::MIN), |(l, h), &y| (l.min(y), h.max(y)));
    let overhang = 0.5 * (high - low) / (lines.len() - 1) as f64;
    let half = low.abs().max(high.abs()) + overhang;
    Some((-half, half))
}

fn traffic_error(index: usize, labels: &[String], reason: String) -> TrafficError {
    TrafficError::Placement {
        vehicle: index + 1,
        label: labels.get(index).cloned().unwrap_or_default(),
        reason,
    }
}

/// The road extent [start, end] in deck x [m] that every tyre's path needs from t = 0 to the
/// exit: the scenario road's [−approach, L + exit], widened (in whole sample spacings, so that
/// samples keep their positions) to reach behind the last tyre of every forward vehicle at t = 0
/// and of every backward one. With the scenario's vehicle alone this is
/// [`RoadSpec::extent_for_crossing`](crate::road::RoadSpec::extent_for_crossing).
pub fn road_extent(scenario: &TrafficSpec, runs: &[VehicleRun]) -> (f64, f64) {
    let length = scenario.bridge.deck_length();
    let spec = &scenario.road;
    if let [single] = runs {
        if single.direction == TravelDirection::Forward {
            return spec.extent_for_crossing(length, single.vehicle.trailing_length());
        }
    }
    let (start, end) = spec.extent_for_bridge(length);
    let (mut behind_start, mut beyond_end) = (0.0_f64, 0.0_f64);
    for run in runs {
        let rear = run.start_position - run.vehicle.trailing_length();
        match run.direction {
            TravelDirection::Forward => behind_start = behind_start.max(start - rear),
            TravelDirection::Backward => beyond_end = beyond_end.max(length - rear - end),
        }
    }
    let whole = |distance: f64| (distance / spec.sample_spacing).ceil() * spec.sample_spacing;
    (start - whole(behind_start), end + whole(beyond_end))
}
