//! Verification of crossings with several vehicles, both directions and variable speed
//! (docs/verification.md §15), on the closed-form simply supported beam of
//! `verification_solver` (the VBI-2D beam: L = 25 m, EI = 3.5e10 × 1.3901 N·m², m̄ = 18358 kg/m).
//!
//! References: superposition (the bridge is linear and moving forces carry no DOFs), the mirror
//! symmetry of the sine modes φₖ(L − x) = (−1)^(k+1) φₖ(x), and an independent fixed-step RK4
//! integration, written here, of the same modal equations with the contact moving under uniform
//! deceleration.

use std::f64::consts::PI;

use vbi::crossing::{crossing_of, Entry, Motion, PipelineError, Scenario, TrafficVehicle};
use vbi::solver::{
    simulate, Crossing, ResponseHistory, SolverError, SolverOptions, SpeedProfile, TravelDirection,
    VehicleRun,
};
use vbi::vehicle::{preset, ContactKind, VehicleModel};

use super::verification_solver::{moving_force, smooth, sprung_mass, Beam};

const GRAVITY: f64 = 9.81;

fn run_with_step(crossing: &Crossing, modes: usize, time_step: f64) -> ResponseHistory {
    let basis = Beam::vbi2d().basis(modes, 0.02);
    let options = SolverOptions {
        time_step: Some(time_step),
        ..SolverOptions::default()
    };
    simulate(&basis, crossing, &options).expect("the crossing runs")
}

fn forward(vehicle: VehicleModel, start: f64, speed: f64) -> VehicleRun {
    VehicleRun {
        start_position: start,
        ..VehicleRun::forward(vehicle, speed)
    }
}

fn crossing(vehicles: Vec<VehicleRun>) -> Crossing {
    Crossing {
        vehicles,
        road: smooth(),
        free_vibration_duration: Some(0.5),
    }
}

/// Two moving forces at different speeds: the modal response of both together equals the sum
/// of the responses to each alone, at every instant the three runs share (superposition of a
/// linear system; the Newmark recurrence is linear in the loads, so only round-off separates
/// them: tolerance 1e-12 of the peak).
#[test]
fn two_moving_forces_superpose_to_round_off() {
    let first = forward(moving_force(100e3), -2.0, 20.0);
    let second = forward(moving_force(60e3), -20.0, 25.0);
    let both = run_with_step(&crossing(vec![first.clone(), second.clone()]), 5, 1e-3);
    let alone = [
        run_with_step(&crossing(vec![first]), 5, 1e-3),
        run_with_step(&crossing(vec![second]), 5, 1e-3),
    ];
    let n = both.mode_count;
    let shared = alone.iter().map(|h| h.step_count).min().unwrap() * n;
    let peak = both
        .modal_displacement
        .iter()
        .fold(0.0_f64, |m, q| m.max(q.abs()));
    assert!(peak > 0.0);
    for i in 0..shared {
        let sum = alone[0].modal_displacement[i] + alone[1].modal_displacement[i];
        let error = (both.modal_displacement[i] - sum).abs();
        assert!(
            error <= 1e-12 * peak,
            "entry {i}: {error:e} of peak {peak:e}"
        );
    }
    // The contacts are stacked in the order of the vehicles, with their positions.
    assert_eq!(both.contacts.len(), 2);
    assert_eq!(both.contacts[1].vehicle, 1);
    let last = both.step_count - 1;
    let t = both.time(last);
    assert_eq!(both.contact_position[last * 2 + 1], -20.0 + 25.0 * t);
}

/// A sprung mass driving backward over the symmetric beam gives the mirrored history of the
/// same vehicle driving forward: qₖ^backward(t) = (−1)^(k+1) qₖ^forward(t) and the same vehicle
/// response. The sine modes are sampled at nodes symmetric about mid-span, so only round-off
/// separates the two (tolerance 1e-9 of the peak).
#[test]
fn a_vehicle_in_the_opposite_direction_gives_the_mirrored_history() {
    let vehicle = sprung_mass(5750.0, 1.595e6);
    let ahead = forward(vehicle.clone(), -5.0, 20.0);
    let back = VehicleRun {
        direction: TravelDirection::Backward,
        ..ahead.clone()
    };
    let forward_run = run_with_step(&crossing(vec![ahead]), 5, 5e-4);
    let backward_run = run_with_step(&crossing(vec![back]), 5, 5e-4);
    assert_eq!(forward_run.step_count, backward_run.step_count);
    let n = forward_run.mode_count;
    let peak = forward_run
        .modal_displacement
        .iter()
        .fold(0.0_f64, |m, q| m.max(q.abs()));
    for (i, (f, b)) in forward_run
        .modal_displacement
        .iter()
        .zip(&backward_run.modal_displacement)
        .enumerate()
    {
        let sign = if (i % n).is_multiple_of(2) { 1.0 } else { -1.0 };
        assert!(
            (b - sign * f).abs() <= 1e-9 * peak,
            "step {}, mode {}: {b:e} vs {f:e}",
            i / n,
            i % n + 1
        );
    }
    let z_peak = forward_run
        .vehicle_displacement
        .iter()
        .fold(0.0_f64, |m, z| m.max(z.abs()));
    for (f, b) in forward_run
        .vehicle_displacement
        .iter()
        .zip(&backward_run.vehicle_displacement)
    {
        assert!((f - b).abs() <= 1e-9 * z_peak);
    }
}

/// A sprung mass crossing the closed-form beam, as the RK4 reference below integrates it.
pub(super) struct SprungMassCrossing<'a> {
    /// The beam and how many of its modes, with their damping ratio ζ [-].
    pub(super) beam: &'a Beam,
    pub(super) modes: usize,
    pub(super) damping_ratio: f64,
    /// Mass m [kg], spring k [N/m] and damper c [N·s/m] between the mass and the road.
    pub(super) vehicle: (f64, f64, f64),
    /// Start s₀ [m], speed v₀ at t = 0 [m/s] and constant acceleration a [m/s²]:
    /// x(t) = s₀ + v₀t + ½at².
    pub(super) motion: (f64, f64, f64),
    /// Road elevation and slope (r, r′) at x [m, -].
    pub(super) road: &'a dyn Fn(f64) -> (f64, f64),
    /// Times [s] at which the right-hand side is not smooth (a kink of the road, the contact
    /// leaving the deck): each RK4 step that contains one is split there, so the integration
    /// keeps its fourth order.
    pub(super) breakpoints: Vec<f64>,
    /// RK4 steps per recorded instant.
    pub(super) substeps: usize,
}

/// The modal equations of the beam with one damped sprung mass, integrated by fixed-step RK4
/// with the contact at x(t) = s₀ + v₀t + ½at²: the independent reference of a crossing,
/// q̈ₖ + 2ζωₖq̇ₖ + ωₖ²qₖ = −φₖ(x)P, m z̈ = k(Y + r − z) + c(Ẏ + r′ẋ − ż), P = mg + m z̈,
/// Ẏ = φ·q̇ + ẋφ′·q. Returns the mid-span deflection and the mass's displacement at the
/// instants t_i = i·Δt, i < count.
pub(super) fn rk4_reference(
    case: &SprungMassCrossing,
    (time_step, count): (f64, usize),
) -> Vec<(f64, f64)> {
    let modes = case.modes;
    let (mass, stiffness, damping) = case.vehicle;
    let (start, initial_speed, acceleration) = case.motion;
    let basis = case.beam.basis(modes, case.damping_ratio);
    let omega: Vec<f64> = basis.modes.iter().map(|m| m.circular_frequency).collect();
    let length = basis.deck.length;
    let amplitude = (2.0 / (18358.0 * length)).sqrt();
    let shapes = |x: f64| -> (Vec<f64>, Vec<f64>) {
        if !(0.0..=length).contains(&x) {
            return (vec![0.0; modes], vec![0.0; modes]);
        }
        (1..=modes)
            .map(|k| {
                let a = k as f64 * PI / length;
                (amplitude * (a * x).sin(), amplitude * a * (a * x).cos())
            })
            .unzip()
    };
    // State: q (modes), q̇ (modes), z, ż.
    let derivative = |t: f64, y: &[f64]| -> Vec<f64> {
        let x = start + initial_speed * t + 0.5 * acceleration * t * t;
        let speed = initial_speed + acceleration * t;
        let (phi, slope) = shapes(x);
        let (road, road_slope) = (case.road)(x);
        let (q, qd) = (&y[..modes], &y[modes..2 * modes]);
        let (z, zd) = (y[2 * modes], y[2 * modes + 1]);
        let deck: f64 = phi.iter().zip(q).map(|(p, q)| p * q).sum();
        let deck_rate: f64 = phi.iter().zip(qd).map(|(p, v)| p * v).sum::<f64>()
            + speed * slope.iter().zip(q).map(|(s, q)| s * q).sum::<f64>();
        let spring =
            stiffness * (deck + road - z) + damping * (deck_rate + road_slope * speed - zd);
        let force = mass * GRAVITY + spring;
        let mut out = vec![0.0; 2 * modes + 2];
        for k in 0..modes {
            out[k] = qd[k];
            out[modes + k] = -2.0 * case.damping_ratio * omega[k] * qd[k]
                - omega[k] * omega[k] * q[k]
                - phi[k] * force;
        }
        out[2 * modes] = zd;
        out[2 * modes + 1] = spring / mass;
        out
    };
    let rk4 = |t: f64, h: f64, y: &mut Vec<f64>| {
        let k1 = derivative(t, y);
        let k2 = derivative(t + h / 2.0, &add(y, &k1, h / 2.0));
        let k3 = derivative(t + h / 2.0, &add(y, &k2, h / 2.0));
        let k4 = derivative(t + h, &add(y, &k3, h));
        for (n, value) in y.iter_mut().enumerate() {
            *value += h / 6.0 * (k1[n] + 2.0 * k2[n] + 2.0 * k3[n] + k4[n]);
        }
    };
    let h = time_step / case.substeps as f64;
    let mut y = vec![0.0; 2 * modes + 2];
    let mut out = Vec::with_capacity(count);
    let (mid, _) = shapes(0.5 * length);
    for i in 0..count {
        let deflection: f64 = mid.iter().zip(&y[..modes]).map(|(p, q)| p * q).sum();
        out.push((deflection, y[2 * modes]));
        for j in 0..case.substeps {
            let t = i as f64 * time_step + j as f64 * h;
            match case.breakpoints.iter().find(|&&b| t < b && b < t + h) {
                Some(&b) => {
                    rk4(t, b - t, &mut y);
                    rk4(b, t + h - b, &mut y);
                }
                None => rk4(t, h, &mut y),
            }
        }
    }
    out
}

fn add(y: &[f64], k: &[f64], h: f64) -> Vec<f64> {
    y.iter().zip(k).map(|(a, b)| a + h * b).collect()
}

/// A damped sprung mass braking at 3 m/s² across the beam against the RK4 reference above:
/// mid-span deflection and mass displacement within 2e-4 of their peaks. Newmark's relative
/// period error is (ωΔt)²/12: 5.5e-7 for mode 1 and 3.4e-4 for mode 5 (a few per cent of the
/// deflection), at Δt = 1e-4 s; RK4 at h = 1e-5 s is exact to far below that, except for the
/// O(h) error of the steps where the contact enters and leaves the deck.
#[test]
fn a_braking_sprung_mass_matches_an_independent_rk4_integration() {
    let beam = Beam::vbi2d();
    let (mass, stiffness, damping) = (5750.0, 1.595e6, 2.0e4);
    let mut vehicle = sprung_mass(mass, stiffness);
    vehicle.damping_matrix[(0, 0)] = damping;
    if let ContactKind::Tyre { damping: c, .. } = &mut vehicle.contacts[0].kind {
        *c = damping;
    }
    let (start, entry_speed, acceleration) = (-5.0, 25.0, -3.0);
    let speed =
        SpeedProfile::constant_acceleration(entry_speed, acceleration, start, 25.0).unwrap();
    let run = VehicleRun {
        speed,
        ..forward(vehicle, start, entry_speed)
    };
    let (modes, time_step) = (5, 1e-4);
    let history = run_with_step(&crossing(vec![run]), modes, time_step);
    let initial_speed = (entry_speed * entry_speed - 2.0 * acceleration * 5.0_f64).sqrt();
    assert_eq!(history.speed, initial_speed);
    let flat = |_: f64| (0.0, 0.0);
    let case = SprungMassCrossing {
        beam: &beam,
        modes,
        damping_ratio: 0.02,
        vehicle: (mass, stiffness, damping),
        motion: (start, initial_speed, acceleration),
        road: &flat,
        breakpoints: Vec::new(),
        substeps: 10,
    };
    let reference = rk4_reference(&case, (time_step, history.step_count));
    let basis = beam.basis(modes, 0.02);
    let mid: Vec<f64> = basis.station_deflection[..modes].to_vec();
    let deflection: Vec<f64> = (0..history.step_count)
        .map(|i| {
            let q = history.modal_displacements_at(i);
            mid.iter().zip(q).map(|(p, q)| p * q).sum()
        })
        .collect();
    let peak = |values: &mut dyn Iterator<Item = f64>| values.fold(0.0_f64, |m, v| m.max(v.abs()));
    let u_peak = peak(&mut reference.iter().map(|r| r.0));
    let z_peak = peak(&mut reference.iter().map(|r| r.1));
    let u_error = peak(&mut deflection.iter().zip(&reference).map(|(u, r)| u - r.0));
    let z_error = peak(
        &mut history
            .vehicle_displacement
            .iter()
            .zip(&reference)
            .map(|(z, r)| z - r.1),
    );
    assert!(
        u_error <= 2e-4 * u_peak,
        "deflection: {u_error:e} of {u_peak:e}"
    );
    assert!(z_error <= 2e-4 * z_peak, "mass: {z_error:e} of {z_peak:e}");
}

fn small_scenario() -> Scenario {
    Scenario {
        vehicle: preset("quarter-car").expect("a preset"),
        motion: Motion::constant(20.0, 0.0),
        ..Scenario::default()
    }
}

/// A platoon of three: each copy `platoon_gap` behind the last tyre of the one before; and the
/// road reaches behind the last copy.
#[test]
fn a_platoon_places_each_copy_its_gap_behind_the_one_before() {
    let mut scenario = small_scenario();
    scenario.vehicle = preset("tractor-semitrailer-5axle").expect("a preset");
    scenario.platoon_size = 3;
    scenario.platoon_gap = 12.0;
    let crossing = crossing_of(&scenario).expect("a crossing");
    assert_eq!(crossing.vehicles.len(), 3);
    let trailing = crossing.vehicles[0].vehicle.trailing_length();
    for pair in crossing.vehicles.windows(2) {
        let gap = pair[0].start_position - trailing - pair[1].start_position;
        assert!((gap - 12.0).abs() < 1e-9, "gap {gap}");
    }
    let last = &crossing.vehicles[2];
    assert!(crossing.road.start <= last.start_position - trailing);
}

/// Bad traffic is refused before any modal analysis, naming the vehicle: a braking that stops
/// the vehicle on the deck, a gap with no vehicle ahead in its direction, a wheel outside the
/// deck, and two vehicles on the same spot at t = 0.
#[test]
fn bad_traffic_is_refused_naming_the_vehicle() {
    let mut braking = small_scenario();
    braking.motion.acceleration = -5.0;
    let error = crossing_of(&braking).unwrap_err();
    assert!(
        matches!(error, PipelineError::Traffic { vehicle: 1, .. }),
        "{error}"
    );
    assert!(error.to_string().contains("reaches zero"), "{error}");

    let mut gap = small_scenario();
    gap.traffic.push(TrafficVehicle {
        label: "oncoming".into(),
        vehicle: preset("quarter-car").unwrap(),
        motion: Motion {
            direction: TravelDirection::Backward,
            ..Motion::constant(20.0, 0.0)
        },
        entry: Entry::Gap(5.0),
    });
    let error = crossing_of(&gap).unwrap_err();
    assert!(
        matches!(error, PipelineError::Traffic { vehicle: 2, .. }),
        "{error}"
    );

    let mut outside = Scenario::default();
    outside.motion.lateral_position = 4.0;
    let error = crossing_of(&outside).unwrap_err();
    assert!(error.to_string().contains("outside the deck"), "{error}");

    let mut same_spot = small_scenario();
    let approach = same_spot.road.approach_length;
    same_spot.traffic.push(TrafficVehicle {
        label: "second".into(),
        vehicle: preset("quarter-car").unwrap(),
        motion: Motion::constant(20.0, 0.0),
        entry: Entry::Time(approach / 20.0),
    });
    match crossing_of(&same_spot).unwrap_err() {
        PipelineError::Crossing(SolverError::VehiclesOverlap(overlap)) => {
            assert_eq!((overlap.first, overlap.second), (1, 2))
        }
        other => panic!("{other}"),
    }
}
