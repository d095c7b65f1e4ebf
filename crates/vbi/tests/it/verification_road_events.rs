//! Verification of road events and user profiles: each event's shape against its closed form,
//! exact superposition on the random roughness, linear resampling of a user profile, the
//! refusals, and two end-to-end crossings (a step's contact-force jump against k_t·H, a sine
//! road's excitation frequency against v/λ).
//!
//! Reference: docs/verification.md §8a (closed forms of the event shapes, documented in
//! `vbi::road::EventShape`; the force jump of a tyre spring over a step that rises in a time
//! short against the wheel-hop period).

use std::f64::consts::PI;

use vbi::crossing::{prepare_scenario_bridge, run_crossing, Scenario};
use vbi::road::{
    generate, BumpShape, EventShape, EventTracks, RoadError, RoadEvent, RoadSpec, RoughnessClass,
    Track, TrackCorrelation, UserProfile,
};
use vbi::vehicle::{preset, ContactKind};

fn on_both(shape: EventShape) -> RoadEvent {
    RoadEvent {
        tracks: EventTracks::Both,
        shape,
    }
}

/// A smooth road (zero roughness) over [−10, 40] m carrying the given events.
fn smooth_with(events: Vec<RoadEvent>) -> vbi::road::RoadProfile {
    let spec = RoadSpec {
        events,
        ..RoadSpec::of_class(RoughnessClass::Smooth)
    };
    generate(&spec, -10.0, 40.0, 1).unwrap()
}

/// The closed forms of docs/input-format.md ([road] events), written out here independently
/// of the library's `EventShape::elevation`.
fn closed_form(shape: &EventShape, x: f64) -> f64 {
    match *shape {
        EventShape::Step {
            position,
            height,
            length,
        } => {
            let s = ((x - (position - length / 2.0)) / length).clamp(0.0, 1.0);
            height * (1.0 - (PI * s).cos()) / 2.0
        }
        EventShape::Ramp { start, end, height } => {
            if x <= start {
                0.0
            } else if x >= end {
                height
            } else {
                height * (x - start) / (end - start)
            }
        }
        EventShape::Bump {
            centre,
            length,
            height,
            shape,
        } => {
            if (x - centre).abs() > length / 2.0 {
                return 0.0;
            }
            let s = (x - centre) / length + 0.5;
            match shape {
                BumpShape::Cosine => height * (1.0 - (2.0 * PI * s).cos()) / 2.0,
                BumpShape::HalfSine => height * (PI * s).sin(),
            }
        }
        EventShape::Sine {
            start,
            end,
            wavelength,
            amplitude,
            phase,
        } => {
            if x < start || x > end {
                0.0
            } else {
                amplitude * (2.0 * PI * (x - start) / wavelength + phase).sin()
            }
        }
    }
}

fn shapes() -> Vec<EventShape> {
    vec![
        EventShape::Step {
            position: 0.0,
            height: 0.02,
            length: 0.1,
        },
        EventShape::Ramp {
            start: -8.0,
            end: -0.5,
            height: -0.02,
        },
        EventShape::Bump {
            centre: 12.5,
            length: 0.5,
            height: -0.03,
            shape: BumpShape::Cosine,
        },
        EventShape::Bump {
            centre: 20.0,
            length: 1.0,
            height: 0.01,
            shape: BumpShape::HalfSine,
        },
        EventShape::Sine {
            start: 25.0,
            end: 35.0,
            wavelength: 2.5,
            amplitude: 0.004,
            phase: 0.3,
        },
    ]
}

// Reference: the closed forms above, at every sample; and their landmarks (step and ramp half
// way, bump peak, sine crest) at positions on the 0.05 m grid. Round-off of a few operations
// on numbers of order 1: 1e-15 m on elevations of 0.01 m.
#[test]
fn each_event_shape_matches_its_closed_form_at_every_sample() {
    for shape in shapes() {
        let profile = smooth_with(vec![on_both(shape.clone())]);
        for i in 0..profile.len() {
            let x = profile.position(i);
            let expected = closed_form(&shape, x);
            assert!(
                (profile.left[i] - expected).abs() < 1e-15,
                "{shape:?} at {x}: {} vs {expected}",
                profile.left[i]
            );
            assert_eq!(profile.left[i], profile.right[i]);
        }
    }
    let landmark = |shape: EventShape, x: f64, expected: f64| {
        let value = shape.elevation(x);
        assert!(
            (value - expected).abs() < 1e-15,
            "{shape:?} at {x}: {value}"
        );
    };
    let [step, ramp, cosine, half_sine, sine] = <[EventShape; 5]>::try_from(shapes()).unwrap();
    landmark(step.clone(), 0.0, 0.01);
    landmark(step.clone(), -0.05, 0.0);
    landmark(step, 0.05, 0.02);
    landmark(ramp.clone(), -4.25, -0.01);
    landmark(ramp, 30.0, -0.02); // held after its end
    landmark(cosine.clone(), 12.5, -0.03);
    landmark(cosine, 12.375, -0.015); // s = 1/4: (1 − cos π/2)/2 = 1/2
    landmark(half_sine.clone(), 19.75, 0.01 * (PI / 4.0).sin());
    landmark(half_sine, 20.6, 0.0); // outside
    let crest = 25.0 + 2.5 * (0.25 - 0.3 / (2.0 * PI));
    landmark(sine, crest, 0.004);
}

// Reference: superposition. The events are added to the generated samples, so a road with
// events minus the same road without is their sum at the sample positions; the one addition
// rounds by half an ulp of the sum (|h| < 0.05 m: below 1e-17 m), 1e-16 m allows a few.
#[test]
fn events_superpose_exactly_on_the_random_roughness() {
    let base = RoadSpec {
        track_correlation: TrackCorrelation::Independent,
        ..RoadSpec::of_class(RoughnessClass::Poor)
    };
    let mut events: Vec<RoadEvent> = shapes().into_iter().map(on_both).collect();
    events[2].tracks = EventTracks::Left;
    events[3].tracks = EventTracks::Right;
    let with = RoadSpec {
        events: events.clone(),
        ..base.clone()
    };
    let rough = generate(&base, -10.0, 40.0, 7).unwrap();
    let both = generate(&with, -10.0, 40.0, 7).unwrap();
    assert_eq!((rough.start, rough.spacing), (both.start, both.spacing));
    for track in [Track::Left, Track::Right] {
        for i in 0..rough.len() {
            let x = rough.position(i);
            let sum: f64 = events
                .iter()
                .filter(|e| e.tracks.includes(track))
                .map(|e| closed_form(&e.shape, x))
                .sum();
            let difference = both.samples(track)[i] - rough.samples(track)[i];
            assert!(
                (difference - sum).abs() < 1e-16,
                "{track:?} at {x}: {difference} vs {sum}"
            );
        }
    }
    // The left-only bump is on the left track only.
    let at = ((12.5 - rough.start) / rough.spacing).round() as usize;
    assert!((both.right[at] - rough.right[at]).abs() < 1e-16);
    assert!((both.left[at] - rough.left[at] + 0.03).abs() < 1e-16);
}

// Reference: the tyre-patch moving average is linear, so with smoothing the difference is the
// smoothed events. The averages are differences of prefix sums over 1001 samples, each sum
// below 1 m: accumulated round-off at most 1001 × 2.2e-16 × 1 m ≈ 2.2e-13 m, so 1e-12 m.
#[test]
fn tyre_patch_smoothing_acts_on_the_events_too() {
    let base = RoadSpec {
        tyre_patch_length: 0.25,
        ..RoadSpec::of_class(RoughnessClass::Medium)
    };
    let events: Vec<RoadEvent> = shapes().into_iter().map(on_both).collect();
    let with = RoadSpec {
        events: events.clone(),
        ..base.clone()
    };
    let events_only = RoadSpec {
        events,
        ..RoadSpec {
            roughness: vbi::road::Roughness::Class(RoughnessClass::Smooth),
            ..base.clone()
        }
    };
    let rough = generate(&base, -10.0, 40.0, 3).unwrap();
    let both = generate(&with, -10.0, 40.0, 3).unwrap();
    let smoothed_events = generate(&events_only, -10.0, 40.0, 3).unwrap();
    for i in 0..rough.len() {
        let difference = both.left[i] - rough.left[i];
        assert!((difference - smoothed_events.left[i]).abs() < 1e-12, "{i}");
    }
    // Near the step (x in [−0.45, 0.45] m: no other event varies there) the patch averages
    // 2·round(0.25/0.1) + 1 = 7 samples, so one sample to the next moves by (v[i+4] − v[i−3])/7
    // ≤ H/7 = 2.86 mm, where the unsmoothed step moves by H/2 = 10 mm per sample.
    let near_step: Vec<f64> = (0..smoothed_events.len())
        .filter(|&i| smoothed_events.position(i).abs() <= 0.45)
        .map(|i| smoothed_events.left[i])
        .collect();
    let largest_jump = near_step
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(0.0, f64::max);
    assert!(largest_jump <= 0.02 / 7.0 + 1e-12, "{largest_jump}");
    assert!(largest_jump > 0.02 / 7.0 - 1e-12, "{largest_jump}");
}

/// A user profile: a ramp on the left, a parabola on the right, at irregular positions.
fn user_profile() -> UserProfile {
    let positions: Vec<f64> = (0..=60)
        .map(|i| -15.0 + i as f64 * 1.0 + if i % 3 == 1 { 0.3 } else { 0.0 })
        .collect();
    UserProfile {
        left: positions.iter().map(|x| 0.001 * x).collect(),
        right: positions.iter().map(|x| 1e-4 * x * x).collect(),
        positions,
    }
}

// Reference: linear interpolation reproduces a linear function exactly (round-off 1e-15 m),
// and between the knots of the parabola it lies within the chord error h²/8·|r''| = (1.3 m)²/8 ·
// 2e-4 = 4.3e-5 m of the parabola, at the knots exactly.
#[test]
fn a_user_profile_replaces_the_roughness_and_is_resampled_linearly() {
    let spec = RoadSpec {
        profile: Some(user_profile()),
        events: vec![on_both(shapes()[0].clone())],
        ..RoadSpec::default()
    };
    let profile = generate(&spec, -10.0, 40.0, 1).unwrap();
    for i in 0..profile.len() {
        let x = profile.position(i);
        let step = closed_form(&shapes()[0], x);
        assert!((profile.left[i] - step - 0.001 * x).abs() < 1e-15, "{x}");
        let chord = (profile.right[i] - step - 1e-4 * x * x).abs();
        assert!(chord <= 1.3f64.powi(2) / 8.0 * 2e-4 + 1e-15, "{x}: {chord}");
    }
    // A knot on the grid: x = 0 is knot 15 (not shifted), sample 200.
    assert!((profile.right[200] - closed_form(&shapes()[0], 0.0)).abs() < 1e-15);
}

#[test]
fn a_user_profile_that_does_not_cover_the_extent_is_refused_with_both_extents() {
    let spec = RoadSpec {
        profile: Some(user_profile()),
        ..RoadSpec::default()
    };
    match generate(&spec, -20.0, 40.0, 1) {
        Err(RoadError::ProfileDoesNotCover {
            start,
            end,
            first,
            last,
        }) => {
            assert_eq!((start, end, first, last), (-20.0, 40.0, -15.0, 45.0));
            let message = generate(&spec, -20.0, 40.0, 1).unwrap_err().to_string();
            assert!(message.contains("[-15, 45] m"), "{message}");
            assert!(message.contains("[-20, 40] m"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn unresolved_or_malformed_events_are_refused_by_validate() {
    let refused = |shape: EventShape, quantity: &str| {
        let spec = RoadSpec {
            events: vec![on_both(shapes()[0].clone()), on_both(shape)],
            ..RoadSpec::default()
        };
        match spec.validate() {
            Err(RoadError::InvalidEvent {
                index: 1,
                quantity: q,
                ..
            }) => assert_eq!(q, quantity),
            other => panic!("{quantity}: {other:?}"),
        }
    };
    // Default spacing 0.05 m: a step needs ≥ 0.1 m, a bump and a wavelength ≥ 0.2 m.
    refused(
        EventShape::Step {
            position: 0.0,
            height: 0.02,
            length: 0.09,
        },
        "transition length",
    );
    refused(
        EventShape::Bump {
            centre: 0.0,
            length: -1.0,
            height: 0.02,
            shape: BumpShape::Cosine,
        },
        "length",
    );
    refused(
        EventShape::Ramp {
            start: 0.0,
            end: -1.0,
            height: 0.02,
        },
        "length end - start",
    );
    refused(
        EventShape::Sine {
            start: 0.0,
            end: 10.0,
            wavelength: 0.15,
            amplitude: 0.01,
            phase: 0.0,
        },
        "wavelength",
    );
    refused(
        EventShape::Sine {
            start: 0.0,
            end: 10.0,
            wavelength: 1.0,
            amplitude: f64::INFINITY,
            phase: 0.0,
        },
        "amplitude",
    );
}

/// The default scenario (the paper's 3 × 30 m bridge, 80 km/h) with the quarter-car preset
/// on a smooth road carrying `events`, run.
fn quarter_car_crossing(events: Vec<RoadEvent>) -> vbi::crossing::RunResult {
    let mut scenario = Scenario {
        vehicle: preset("quarter-car").unwrap(),
        ..Scenario::default()
    };
    scenario.road = RoadSpec {
        events,
        ..RoadSpec::of_class(RoughnessClass::Smooth)
    };
    let bridge = prepare_scenario_bridge(&scenario).unwrap();
    run_crossing(&bridge, &scenario).unwrap()
}

// Reference: a tyre spring k_t over a step of height H that rises in L/v = 4.5 ms, short
// against the wheel-hop period (about 80 ms: ω L/v ≈ 0.35 rad): the wheel hardly moves during
// the rise, so the tyre force rises by about k_t H, plus at most c_t · (πH/2L) · v from the tyre
// damper at the steepest slope. Bounds: [0.8 k_t H, k_t H + c_t πHv/(2L) + 0.2 k_t H], the 20 %
// for the wheel's motion during the rise and the bridge's deflection.
#[test]
fn a_step_on_a_smooth_road_gives_a_contact_force_jump_of_about_k_t_h() {
    let (height, length, position) = (0.02, 0.1, 10.0);
    let result = quarter_car_crossing(vec![on_both(EventShape::Step {
        position,
        height,
        length,
    })]);
    let history = &result.history;
    let ContactKind::Tyre {
        stiffness, damping, ..
    } = result.crossing.vehicles[0].vehicle.contacts[0].kind
    else {
        panic!("the quarter-car has a tyre");
    };
    let contacts = history.contacts.len();
    let static_load = history.contacts[0].static_load;
    assert!(history.contact_force.iter().all(|f| f.is_finite()));
    let force_at = |step: usize| history.contact_force[step * contacts];
    let before: Vec<usize> = (0..history.step_count)
        .filter(|&i| history.front_axle_position[i] < position - length)
        .collect();
    let largest_before = before
        .iter()
        .map(|&i| (force_at(i) - static_load).abs())
        .fold(0.0, f64::max);
    let jump = (0..history.step_count)
        .filter(|&i| history.front_axle_position[i] >= position - length)
        .map(|i| force_at(i) - static_load)
        .fold(f64::MIN, f64::max);
    let speed = history.speed;
    let spring = stiffness * height;
    let upper = spring + damping * PI * height * speed / (2.0 * length) + 0.2 * spring;
    assert!(
        jump >= 0.8 * spring && jump <= upper,
        "jump {jump} N, k_t H = {spring} N, upper {upper} N"
    );
    // On the smooth road before the step only the bridge's deflection moves the wheel: far below.
    assert!(largest_before < 0.1 * spring, "{largest_before}");
}

// Reference: a road r(x) = A sin(2πx/λ) crossed at speed v is r(vt): it excites the vehicle at
// f = v/λ. λ = 4 m at 80 km/h: 5.56 Hz, between the quarter-car's body (≈ 1.7 Hz) and wheel-hop
// (≈ 12.5 Hz) frequencies. The contact force's discrete Fourier amplitude over a window of
// whole periods peaks at the bin of v/λ (bins 1/T apart); the test asks for that bin.
#[test]
fn a_sine_road_excites_the_contact_force_at_v_over_lambda() {
    let wavelength = 4.0;
    let result = quarter_car_crossing(vec![on_both(EventShape::Sine {
        start: -80.0,
        end: 112.0,
        wavelength,
        amplitude: 0.003,
        phase: 0.0,
    })]);
    let history = &result.history;
    let speed = history.speed;
    let forced = speed / wavelength;
    // A window from x = −40 m (transients of the start damped) of 24 whole periods.
    let first = history
        .front_axle_position
        .iter()
        .position(|&x| x >= -40.0)
        .unwrap();
    let period_steps = 1.0 / (forced * history.time_step);
    let count = (24.0 * period_steps).round() as usize;
    assert!(first + count < history.step_count);
    let window = &history.contact_force[first..first + count];
    let mean = window.iter().sum::<f64>() / count as f64;
    let duration = count as f64 * history.time_step;
    let amplitude = |f: f64| {
        let (mut re, mut im) = (0.0, 0.0);
        for (i, p) in window.iter().enumerate() {
            let phase = 2.0 * PI * f * i as f64 * history.time_step;
            re += (p - mean) * phase.cos();
            im -= (p - mean) * phase.sin();
        }
        (re * re + im * im).sqrt()
    };
    let bins: Vec<f64> = (1..=(30.0 * duration) as usize)
        .map(|k| k as f64 / duration)
        .collect();
    let peak = bins
        .iter()
        .copied()
        .max_by(|a, b| amplitude(*a).total_cmp(&amplitude(*b)))
        .unwrap();
    assert!(
        (peak - forced).abs() < 0.5 / duration,
        "peak at {peak} Hz, v/λ = {forced} Hz"
    );
}
