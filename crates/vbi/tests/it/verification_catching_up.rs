//! Verification of the catching-up refusal (docs/verification.md §20): two vehicles in one lane
//! and direction whose gap closes during the event are found, with the time and place of the
//! meeting, from the exact piecewise-quadratic gap g(t) = s_L(t) − ℓ_L − s_F(t).
//!
//! References: hand-solved meetings of uniformly accelerated motions (stated in each test), and
//! cases that cannot meet (a slower follower, other lanes or directions, a braking platoon whose
//! gap shrinks but stays open, a meeting after the event).

use vbi::crossing::{crossing_of, Entry, Motion, PipelineError, Scenario, TrafficVehicle};
use vbi::solver::{first_catching_up, SpeedKnot, SpeedProfile, TravelDirection, VehicleRun};
use vbi::vehicle::{assemble, preset, VehicleModel};

use super::verification_solver::moving_force;

/// The VBI-2D two-axle truck: its last axle 5 m behind its front axle (ℓ = 5 m).
fn truck() -> VehicleModel {
    assemble(&preset("two-axle-truck-vbi2d").unwrap()).unwrap()
}

fn run(vehicle: VehicleModel, start: f64, speed: SpeedProfile) -> VehicleRun {
    VehicleRun {
        start_position: start,
        speed,
        ..VehicleRun::forward(vehicle, 1.0)
    }
}

/// A braking leader: the truck at s = 10 m drives at 20 m/s until s = 20 m (t = 0.5 s), then
/// brakes at 4 m/s² (knots 20 m at 20 m/s, 60 m at √80 m/s: a = (80 − 400)/(2·40) = −4); a
/// moving force follows at 20 m/s from s = 1 m, 4 m behind the truck's last axle. The gap stays
/// 4 m until t = 0.5 s, then g = 4 − ½·4·(t − 0.5)², which closes at t = 0.5 + √2 s, the
/// follower at s = 1 + 20 t = 11 + 20√2 m (the leader still braking: its s = 36 + 20√2 < 60).
/// Tolerance 1e-12 relative: one square root and a few products.
#[test]
fn a_braking_leader_is_caught_up_at_the_hand_solved_time() {
    let knots = vec![
        SpeedKnot {
            travel: 20.0,
            speed: 20.0,
        },
        SpeedKnot {
            travel: 60.0,
            speed: 80.0_f64.sqrt(),
        },
    ];
    let leader = run(truck(), 10.0, SpeedProfile::Knots(knots));
    let follower = run(moving_force(50e3), 1.0, SpeedProfile::Constant(20.0));
    let meeting = first_catching_up(&[leader, follower], 100.0).expect("they meet");
    let (time, travel) = (0.5 + 2.0_f64.sqrt(), 11.0 + 20.0 * 2.0_f64.sqrt());
    println!(
        "braking leader: t = {} s (exact {time}), s = {} m (exact {travel})",
        meeting.time, meeting.travel
    );
    assert_eq!((meeting.leader, meeting.follower), (0, 1));
    assert!((meeting.time - time).abs() <= 1e-12 * time, "{meeting:?}");
    assert!(
        (meeting.travel - travel).abs() <= 1e-12 * travel,
        "{meeting:?}"
    );
    assert_eq!(meeting.position, meeting.travel);
}

/// A faster follower: the truck at 15 m/s from s = 20 m (last axle at 15 m), another at 20 m/s
/// from s = 5 m: the 10 m gap closes at 5 m/s, at t = 2 s, the follower at s = 45 m. The same
/// traffic driving backward on a 60 m deck meets at the same time and travel, at deck
/// x = 60 − 45 = 15 m; the follower listed first is found all the same.
#[test]
fn a_faster_follower_catches_up_when_the_gap_has_closed_at_the_speed_difference() {
    let leader = run(truck(), 20.0, SpeedProfile::Constant(15.0));
    let follower = run(truck(), 5.0, SpeedProfile::Constant(20.0));
    let meeting = first_catching_up(&[follower.clone(), leader.clone()], 60.0).expect("meet");
    assert_eq!((meeting.leader, meeting.follower), (1, 0));
    assert!((meeting.time - 2.0).abs() <= 1e-12, "{meeting:?}");
    assert!((meeting.travel - 45.0).abs() <= 1e-12 * 45.0, "{meeting:?}");
    let backward = |r: VehicleRun| VehicleRun {
        direction: TravelDirection::Backward,
        ..r
    };
    let meeting = first_catching_up(&[backward(leader), backward(follower)], 60.0).unwrap();
    assert!((meeting.time - 2.0).abs() <= 1e-12);
    assert!(
        (meeting.position - 15.0).abs() <= 1e-12 * 15.0,
        "{meeting:?}"
    );
}

/// Traffic that never meets is not refused: a slower follower; a faster one in the other lane
/// (3.5 m to the side) or the other direction; a faster one so far behind that it would meet
/// the leader only after the event (21 against 20 m/s, 195 m of gap: t = 195 s, while the last
/// vehicle leaves the 60 m deck at (60 + 200)/21 ≈ 12.4 s); and a platoon of two five-axle
/// trucks braking from 80 to 40 km/h over 60 m with 20 m between them
/// (`examples/scenarios/braking-truck.toml`): the follower takes each point 1.46 s after the
/// leader, so the front-to-front distance falls from 32.35 m to 16.2 m, above the 12.35 m
/// trailing length.
#[test]
fn traffic_whose_gaps_stay_open_is_not_refused() {
    let leader = run(truck(), 20.0, SpeedProfile::Constant(20.0));
    let slower = run(truck(), 5.0, SpeedProfile::Constant(19.0));
    assert_eq!(first_catching_up(&[leader.clone(), slower], 60.0), None);
    let faster = run(truck(), 5.0, SpeedProfile::Constant(25.0));
    let other_lane = VehicleRun {
        lateral_position: 3.5,
        ..faster.clone()
    };
    assert_eq!(first_catching_up(&[leader.clone(), other_lane], 60.0), None);
    let oncoming = VehicleRun {
        direction: TravelDirection::Backward,
        ..faster
    };
    assert_eq!(first_catching_up(&[leader.clone(), oncoming], 60.0), None);
    let far_behind = run(truck(), -180.0, SpeedProfile::Constant(21.0));
    assert_eq!(first_catching_up(&[leader, far_behind], 60.0), None);

    let mut platoon = Scenario {
        vehicle: preset("tractor-semitrailer-5axle").unwrap(),
        ..Scenario::default()
    };
    platoon.motion.speed_profile = vec![
        SpeedKnot {
            travel: 0.0,
            speed: 80.0 / 3.6,
        },
        SpeedKnot {
            travel: 60.0,
            speed: 40.0 / 3.6,
        },
    ];
    platoon.platoon_size = 2;
    platoon.platoon_gap = 20.0;
    let crossing = crossing_of(&platoon).expect("the braking platoon is placed");
    assert_eq!(crossing.vehicles.len(), 2);
}

/// The pipeline refuses a faster `[[traffic]]` follower before any work, naming both vehicles
/// with their place in the input and the meeting: the scenario's quarter car at 80 km/h from
/// the start of the approach, a second one 10 m behind it at 120 km/h: the gap closes at
/// (100/9) m/s, at t = 0.9 s.
#[test]
fn the_pipeline_refuses_a_catching_up_naming_both_vehicles_and_the_meeting() {
    let mut scenario = Scenario {
        vehicle: preset("quarter-car").unwrap(),
        motion: Motion::constant(80.0 / 3.6, 0.0),
        ..Scenario::default()
    };
    scenario.traffic.push(TrafficVehicle {
        label: "fast car".into(),
        vehicle: preset("quarter-car").unwrap(),
        motion: Motion::constant(120.0 / 3.6, 0.0),
        entry: Entry::Gap(10.0),
    });
    let error = crossing_of(&scenario).unwrap_err();
    assert!(
        matches!(error, PipelineError::Traffic { vehicle: 2, .. }),
        "{error}"
    );
    let message = error.to_string();
    for part in [
        "vehicle 2 (fast car): catches up with vehicle 1 (quarter-car, at `scenario`) ahead",
        "t = 0.900 s",
    ] {
        assert!(message.contains(part), "{part}: {message}");
    }
}
