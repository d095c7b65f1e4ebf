//! VBI-2D's analytical verification cases with the ramp, the vehicle damping and the
//! acceleration on (docs/verification.md §22): `RampOn`, `DampOn` and `AccOn` of
//! `V01_Analytical_Verification_Examples.m` (DanielCanteroNTNU/VBI-2D, commit
//! e10af2e686134bf29d258ce0bb86e9d6c5ceb29f), reproduced in vbi's solver and compared with an
//! independent fixed-step RK4 integration of the same modal equations with the moving contact
//! (`verification_traffic::rk4_reference`).
//!
//! The script's parameters: the simply supported beam L = 25 m, E = 3.5e10 Pa, I = 1.3901 m⁴,
//! m̄ = 18358 kg/m, no beam damping; the sprung mass m_V = 5750 kg on k_V = 1595e3 N/m, entering
//! at x = 0 at v₀ = 25 m/s; g = 9.81 m/s²; a road ramp rising linearly by 0.01 m from L/3 to
//! L/2 and level after (`ramp_on`); c_V = 40e4 N·s/m in parallel with k_V (`damp_on`; else 0);
//! an acceleration of 10 m/s² from x = 0 (`acc_on`; else 0); the record ends when the mass
//! reaches x = L. The cases: RampOn = ramp; DampOn = ramp + damping; AccOn = ramp + damping +
//! acceleration.
//!
//! The script's own results are MATLAB .mat files (`Verification/Verification_Analytical_*.mat`),
//! binary files this project cannot read, so the reference here is the RK4 integration, not
//! VBI-2D's numbers. (The script also differs from the exact equations by design: it takes the
//! coupling matrices at the start of each step and the road's rate as a backward difference.)

use vbi::road::RoadProfile;
use vbi::solver::{simulate, Crossing, SolverOptions, SpeedProfile, VehicleRun};
use vbi::vehicle::ContactKind;

use super::verification_solver::{sprung_mass, Beam};
use super::verification_traffic::{rk4_reference, SprungMassCrossing};

const SPAN: f64 = 25.0;
const RAMP_HEIGHT: f64 = 0.01;
const MASS: f64 = 5750.0;
const STIFFNESS: f64 = 1595e3;
const ENTRY_SPEED: f64 = 25.0;
/// Modes of both integrations (the script takes 100; 10 carry the mid-span deflection to about
/// 1e-4, and both sides use the same ones, so the comparison is exact in them).
const MODES: usize = 10;
/// vbi's time step [s]: Newmark's relative period error (ωΔt)²/12 is 2.2e-8 for mode 1
/// (25.7 rad/s), 1.4e-5 for mode 5 (643 rad/s) and 2.2e-4 for mode 10 (2571 rad/s); over the
/// 1 s record mode 5 drifts by ωT·(ωΔt)²/12 ≈ 9e-3 rad, on a mode that carries about 1/625 of
/// the mid-span deflection (1/k⁴), and the higher odd modes less: a few 1e-6 of the peak, below
/// the tolerances.
const TIME_STEP: f64 = 2e-5;
/// Road samples every 5 mm for vbi. Its road is the C¹ Catmull–Rom interpolant of the samples,
/// which reproduces the ramp exactly except within one spacing of its two kinks, where it rounds
/// them off (by at most 0.074·r′Δx = 9e-7 m).
const ROAD_SPACING: f64 = 0.005;

/// The ramp of `ramp_on`: r = 0 before L/3, 0.01 (x − L/3)/(L/6) up to L/2, 0.01 after; and its
/// slope (exact, with the kinks at L/3 and L/2).
fn ramp(x: f64) -> (f64, f64) {
    let (start, end) = (SPAN / 3.0, SPAN / 2.0);
    let slope = RAMP_HEIGHT / (end - start);
    if x < start {
        (0.0, 0.0)
    } else if x < end {
        (slope * (x - start), slope)
    } else {
        (RAMP_HEIGHT, 0.0)
    }
}

/// The ramp sampled every [`ROAD_SPACING`] from 10 m before the deck to 10 m beyond it.
fn sampled_ramp() -> RoadProfile {
    let (start, count) = (-10.0, ((SPAN + 20.0) / ROAD_SPACING).round() as usize + 1);
    let samples: Vec<f64> = (0..count)
        .map(|i| ramp(start + i as f64 * ROAD_SPACING).0)
        .collect();
    RoadProfile::from_uniform_samples(start, ROAD_SPACING, samples.clone(), samples).unwrap()
}

/// The time at which x(t) = v₀t + ½at² reaches x [s] (cancellation-free root).
fn time_at(x: f64, acceleration: f64) -> f64 {
    2.0 * x / (ENTRY_SPEED + (ENTRY_SPEED * ENTRY_SPEED + 2.0 * acceleration * x).sqrt())
}

/// The largest error of vbi's mid-span deflection and mass displacement against the RK4
/// reference over the script's record (t from 0 to the arrival at x = L), each relative to the
/// reference's peak: (deflection, mass).
fn relative_errors(damping: f64, acceleration: f64) -> (f64, f64) {
    let beam = Beam::vbi2d().with_node_spacing(0.05);
    let mut vehicle = sprung_mass(MASS, STIFFNESS);
    vehicle.damping_matrix[(0, 0)] = damping;
    if let ContactKind::Tyre { damping: c, .. } = &mut vehicle.contacts[0].kind {
        *c = damping;
    }
    let speed = SpeedProfile::constant_acceleration(ENTRY_SPEED, acceleration, 0.0, SPAN).unwrap();
    let crossing = Crossing {
        vehicles: vec![VehicleRun {
            start_position: 0.0,
            speed,
            ..VehicleRun::forward(vehicle, ENTRY_SPEED)
        }],
        road: sampled_ramp(),
        free_vibration_duration: Some(0.01),
    };
    let options = SolverOptions {
        time_step: Some(TIME_STEP),
        ..SolverOptions::default()
    };
    let basis = beam.basis(MODES, 0.0);
    let history = simulate(&basis, &crossing, &options).expect("the crossing runs");
    let arrival = time_at(SPAN, acceleration);
    let count = (arrival / TIME_STEP).floor() as usize + 1;
    let case = SprungMassCrossing {
        beam: &beam,
        modes: MODES,
        damping_ratio: 0.0,
        vehicle: (MASS, STIFFNESS, damping),
        motion: (0.0, ENTRY_SPEED, acceleration),
        road: &ramp,
        breakpoints: [SPAN / 3.0, SPAN / 2.0, SPAN]
            .map(|x| time_at(x, acceleration))
            .to_vec(),
        substeps: 4,
    };
    let reference = rk4_reference(&case, (TIME_STEP, count));
    let mid = &basis.station_deflection[..MODES];
    let largest =
        |values: &mut dyn Iterator<Item = f64>| values.fold(0.0_f64, |m, v| m.max(v.abs()));
    let (mut u_error, mut z_error) = (0.0_f64, 0.0_f64);
    for (i, (u_ref, z_ref)) in reference.iter().enumerate() {
        let q = history.modal_displacements_at(i);
        let u: f64 = mid.iter().zip(q).map(|(p, q)| p * q).sum();
        u_error = u_error.max((u - u_ref).abs());
        z_error = z_error.max((history.vehicle_displacement[i] - z_ref).abs());
    }
    let u_peak = largest(&mut reference.iter().map(|r| r.0));
    let z_peak = largest(&mut reference.iter().map(|r| r.1));
    println!("peaks: mid-span deflection {u_peak:.4e} m, mass {z_peak:.4e} m");
    (u_error / u_peak, z_error / z_peak)
}

/// Runs one case and checks both errors against `tolerance` (relative to the peaks).
fn check_case(name: &str, damping: f64, acceleration: f64, tolerance: f64) {
    let (u, z) = relative_errors(damping, acceleration);
    println!("{name}: deflection {u:.2e}, mass {z:.2e} of the peaks");
    assert!(u <= tolerance, "{name}: deflection {u:e} of its peak");
    assert!(
        z <= tolerance,
        "{name}: mass displacement {z:e} of its peak"
    );
}

/// RampOn: the undamped sprung mass over the ramp at 25 m/s. Tolerance 5e-6 of the peaks:
/// without damping the tyre force only kinks at the ramp's ends (its slope jumps), so what is
/// left is Newmark's period error (a few 1e-6, see [`TIME_STEP`]); measured 1.3e-6 and 1.3e-7.
#[test]
fn vbi2d_ramp_case_matches_an_independent_rk4_integration() {
    check_case("RampOn", 0.0, 0.0, 5e-6);
}

/// DampOn: the ramp with c_V = 40e4 N·s/m. The damper turns the ramp's slope jumps into tyre
/// force jumps of c_V·v·Δr′ = 4e5 × 25 × 0.0024 = 24 kN (0.43 of the weight), which vbi's road
/// spreads over 2Δx/v = 0.4 ms, 20 time steps. Tolerance [`DAMPED_TOLERANCE`].
#[test]
fn vbi2d_damped_ramp_case_matches_an_independent_rk4_integration() {
    check_case("DampOn", 40e4, 0.0, DAMPED_TOLERANCE);
}

/// AccOn: the damped ramp accelerating at 10 m/s² from 25 m/s (33.5 m/s at x = L, reached at
/// t = 0.854 s). Tolerance [`DAMPED_TOLERANCE`].
#[test]
fn vbi2d_accelerating_damped_ramp_case_matches_an_independent_rk4_integration() {
    check_case("AccOn", 40e4, 10.0, DAMPED_TOLERANCE);
}

/// Tolerance of the damped cases, 3e-5 of each peak: vbi's discretisation of the fast force
/// change at the ramp's ends (20 time steps of the rounded kink; an unresolved 24 kN jump would
/// misplace up to J·Δt/2 = 0.24 N·s of impulse, 8e-5 of the 4.6e-4 m peak by the first mode's
/// impulse response φ₁(L/3)φ₁(L/2)/ω₁) plus the period error of [`TIME_STEP`]. Measured at Δt = 20 µs,
/// Δx = 5 mm: 1.7e-5 (DampOn) and 1.4e-5 (AccOn) of the deflection's peak, 2.9e-6 and 1.2e-6 of
/// the mass's; the difference is vbi's discretisation, not a difference of equations: it falls to
/// 5.0e-6 at 10 µs and 2.1e-6 at 5 µs (with 2.5 mm samples).
const DAMPED_TOLERANCE: f64 = 3e-5;

/// Issue 46, item 3: the road under every wheel at every instant. The RampOn crossing on a ramp
/// sampled only up to the deck's end (no exit length, as `exit_length_m = 0` gives) runs on
/// after the mass has left the deck for the free vibration; its wheel then stood past the
/// profile's last sample and read elevation 0, a 10 mm drop that loaded the tyre by k_V · 0.01
/// = 16 kN at the last steps. The road now holds its last value, so the run is the run on the
/// same ramp sampled 10 m further, bit for bit: the mass displacement, the contact force and
/// the bridge's modal displacements at every instant.
#[test]
fn a_wheel_past_the_profiles_end_keeps_its_road_as_on_a_longer_profile() {
    let run = |road: RoadProfile| {
        let beam = Beam::vbi2d().with_node_spacing(0.05);
        let vehicle = sprung_mass(MASS, STIFFNESS);
        let crossing = Crossing {
            vehicles: vec![VehicleRun {
                start_position: 0.0,
                ..VehicleRun::forward(vehicle, ENTRY_SPEED)
            }],
            road,
            free_vibration_duration: Some(0.2),
        };
        let options = SolverOptions {
            time_step: Some(1e-3),
            ..SolverOptions::default()
        };
        simulate(&beam.basis(MODES, 0.0), &crossing, &options).expect("the crossing runs")
    };
    let longer = sampled_ramp();
    let count = ((SPAN + 10.0) / ROAD_SPACING).round() as usize + 1;
    let samples: Vec<f64> = (0..count)
        .map(|i| ramp(-10.0 + i as f64 * ROAD_SPACING).0)
        .collect();
    let ending_at_the_deck =
        RoadProfile::from_uniform_samples(-10.0, ROAD_SPACING, samples.clone(), samples).unwrap();
    let (a, b) = (run(longer), run(ending_at_the_deck));
    // The mass is past the deck's end (x = 25 m) for the last 0.2 s (5 m at 25 m/s).
    let last = a.front_axle_position.last().copied().unwrap_or(0.0);
    assert!(last > SPAN + 4.0, "the mass ends at x = {last} m");
    assert_eq!(a.vehicle_displacement, b.vehicle_displacement);
    assert_eq!(a.contact_force, b.contact_force);
    assert_eq!(a.modal_displacement, b.modal_displacement);
}
