//! Verification of the pitching moment of braking and acceleration (docs/verification.md §21):
//! a body with a centre-of-mass height h carries the d'Alembert couple M_θ = m h s̈ (nose-up
//! positive), so a vehicle at constant deceleration on a rigid smooth road transfers load from
//! the rear axles to the front ones.
//!
//! References: the textbook steady load transfer of a two-axle vehicle, ΔP = m a h / l (moment
//! equilibrium about the rear contact), and the equilibrium of any vehicle under a pure couple:
//! the tyre-force changes sum to zero and their moment about the front axle is the couple.
//! The vehicle starts on the approach already braking, in the static equilibrium that includes
//! the moment, so on the rigid road every instant is that equilibrium (to round-off).

use vbi::solver::{
    simulate, Crossing, ResponseHistory, SolverOptions, SolverWarning, SpeedProfile, VehicleRun,
};
use vbi::vehicle::{assemble, preset, VehicleDescription, VehicleModel, VehicleSpec};

use super::verification_solver::{smooth, Beam};

/// Where the vehicles start: 40 m before the deck, the whole approach on the rigid road.
const START: f64 = -40.0;

/// A preset with centre-of-mass heights [m] given body by body (in the preset's order).
fn with_heights(name: &str, heights: &[f64]) -> VehicleSpec {
    let mut spec = preset(name).expect("a preset");
    let VehicleDescription::Multibody(multibody) = &mut spec.description else {
        unreachable!("{name} is a multibody preset")
    };
    for (body, &height) in multibody.bodies.iter_mut().zip(heights) {
        body.centre_of_mass_height = Some(height);
    }
    spec
}

/// The mass m_b and height h_b of every body of a spec [kg, m] (heights 0 when not given).
fn bodies(spec: &VehicleSpec) -> Vec<(f64, f64)> {
    let VehicleDescription::Multibody(multibody) = &spec.description else {
        unreachable!()
    };
    multibody
        .bodies
        .iter()
        .map(|b| (b.mass, b.centre_of_mass_height.unwrap_or(0.0)))
        .collect()
}

/// The vehicle crossing the 25 m VBI-2D beam under a constant acceleration a [m/s²] from the
/// start to beyond the deck, v = 20 m/s at the deck entry; Δt = 1 ms.
fn crossing_under(vehicle: VehicleModel, acceleration: f64) -> ResponseHistory {
    let exit = 25.0 + vehicle.trailing_length();
    let speed =
        SpeedProfile::constant_acceleration(20.0, acceleration, START, exit).expect("no stop");
    let crossing = Crossing {
        vehicles: vec![VehicleRun {
            start_position: START,
            speed,
            ..VehicleRun::forward(vehicle, 20.0)
        }],
        road: smooth(),
        free_vibration_duration: Some(0.1),
    };
    let options = SolverOptions {
        time_step: Some(1e-3),
        ..SolverOptions::default()
    };
    let basis = Beam::vbi2d().basis(5, 0.02);
    simulate(&basis, &crossing, &options).expect("the crossing runs")
}

/// ΔP_w = P_w − S_w of every contact at every instant while the whole vehicle is still on the
/// approach (its front contact before the deck): instants × contacts [N].
fn transfers_on_the_approach(history: &ResponseHistory) -> Vec<Vec<f64>> {
    let count = history.contacts.len();
    (0..history.step_count)
        .take_while(|&i| history.contact_position[i * count] < 0.0)
        .map(|i| {
            let forces = &history.contact_force[i * count..(i + 1) * count];
            forces
                .iter()
                .zip(&history.contacts)
                .map(|(force, path)| force - path.static_load)
                .collect()
        })
        .collect()
}

/// The VBI-2D two-axle truck (body 10 500 kg, axles at ±2.5 m from its centre of mass: l = 5 m;
/// unsprung axles) with h = 1.5 m braking at 3 m/s²: the front axle gains m a h / l =
/// 10 500 × 3 × 1.5 / 5 = 9450 N and the rear loses as much, at every instant on the rigid road.
/// Only the body's mass enters: the unsprung masses have no pitch (the moment of their inertia
/// is not modelled). Tolerance 1e-12 of the transfer (1e-8 N): the transfer is the difference of
/// a recorded force and a static load of 6e4 N, whose unit in the last place is 7e-12 N; a 4 × 4
/// equilibrium solved once and kept by the Newmark recurrence under a constant load leaves a few
/// hundred of those at most (measured: 7e-12 N).
#[test]
fn steady_braking_transfers_m_a_h_over_l_from_the_rear_axle_to_the_front() {
    let (height, deceleration, wheelbase) = (1.5, 3.0, 5.0);
    let spec = with_heights("two-axle-truck-vbi2d", &[height]);
    let body_mass = bodies(&spec)[0].0;
    let history = crossing_under(assemble(&spec).unwrap(), -deceleration);
    let expected = body_mass * deceleration * height / wheelbase;
    assert_eq!(expected, 9450.0);
    let transfers = transfers_on_the_approach(&history);
    assert!(transfers.len() > 1000, "{} instants", transfers.len());
    let error = largest(
        transfers
            .iter()
            .flat_map(|t| [t[0] - expected, t[1] + expected]),
    );
    println!(
        "two-axle transfer: largest error {:.3e} of {expected} N",
        error
    );
    assert!(
        error <= 1e-12 * expected,
        "front and rear transfers differ from ±{expected} N by up to {error} N"
    );
}

/// The largest magnitude of the values.
fn largest(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |m, v| m.max(v.abs()))
}

/// Braking loads the front axle and unloads the rear; accelerating does the opposite (the sign
/// of M_θ = m h s̈, nose-up positive), by m |a| h / l each way.
#[test]
fn braking_loads_the_front_axle_and_accelerating_the_rear() {
    let (height, wheelbase) = (1.2, 5.0);
    let spec = with_heights("two-axle-truck-vbi2d", &[height]);
    let body_mass = bodies(&spec)[0].0;
    for acceleration in [-2.0, 1.5] {
        let history = crossing_under(assemble(&spec).unwrap(), acceleration);
        let first = &transfers_on_the_approach(&history)[0];
        let magnitude = body_mass * acceleration.abs() * height / wheelbase;
        let expected_front = if acceleration < 0.0 {
            magnitude
        } else {
            -magnitude
        };
        assert!(
            (first[0] - expected_front).abs() <= 1e-12 * magnitude,
            "a = {acceleration}: front {} N, expected {expected_front} N",
            first[0]
        );
        assert!(first[0] * first[1] < 0.0, "the rear changes the other way");
    }
}

/// The five-axle tractor–semitrailer (statically determinate through the fifth wheel; ten
/// wheels) with the tractor's centre of mass at 1.1 m and the loaded semitrailer's at 1.9 m,
/// braking at 2.5 m/s²: the wheel-force changes are a pure couple, Σ ΔP_w = 0 and
/// Σ ΔP_w x_w = −s̈ Σ m_b h_b (x_w the wheel's offset from the front axle, positive forwards; a
/// braking moment loads the front), and Σ ΔP_w y_w = 0 (no roll). The split between tractor and
/// trailer is not checked: the fifth-wheel horizontal force is not modelled (docs/theory.md).
/// Tolerance 1e-12 of the couple (1.7e-7 N·m, and N for the sum): wheel loads of 3e4–4e4 N
/// carry units in the last place of 7e-12 N, ten wheels at arms up to 12.35 m a few hundred of
/// them (measured: 4e-11 N and 2e-10 N·m).
#[test]
fn semitrailer_transfers_sum_to_zero_and_make_the_braking_couple() {
    let deceleration = 2.5;
    let spec = with_heights("tractor-semitrailer-5axle", &[1.1, 1.9]);
    // −s̈ Σ m_b h_b with s̈ = −2.5 m/s².
    let couple: f64 = bodies(&spec)
        .iter()
        .map(|(m, h)| m * h * deceleration)
        .sum();
    let history = crossing_under(assemble(&spec).unwrap(), -deceleration);
    let transfers = transfers_on_the_approach(&history);
    assert!(transfers.len() > 1000);
    let lateral: Vec<f64> = history
        .contacts
        .iter()
        .map(|c| c.lateral_position)
        .collect();
    let moment_about = |transfer: &[f64], arms: &mut dyn Iterator<Item = f64>| -> f64 {
        transfer.iter().zip(arms).map(|(dp, arm)| dp * arm).sum()
    };
    let sum = largest(transfers.iter().map(|t| t.iter().sum::<f64>()));
    let moment = largest(transfers.iter().map(|t| {
        moment_about(
            t,
            &mut history.contacts.iter().map(|c| c.longitudinal_offset),
        ) - couple
    }));
    let roll = largest(
        transfers
            .iter()
            .map(|t| moment_about(t, &mut lateral.iter().copied())),
    );
    println!(
        "semitrailer: couple {couple} N·m; largest |Σ ΔP| {sum:.3e} N, moment error \
         {moment:.3e} N·m, |Σ ΔP y| {roll:.3e} N·m"
    );
    assert!(sum <= 1e-12 * couple, "Σ ΔP up to {sum} N");
    assert!(
        moment <= 1e-12 * couple,
        "Σ ΔP x − {couple} up to {moment} N·m"
    );
    assert!(roll <= 1e-12 * couple, "Σ ΔP y up to {roll} N·m");
    assert!(
        transfers.iter().all(|t| t[0] > 0.0),
        "braking loads the steer axle"
    );
}

/// Without heights (every preset) a vehicle has no pitch load, and a height changes nothing at
/// constant speed: the crossing is bit for bit the one without it (the moment's term is skipped
/// when s̈ = 0, and the heights enter nothing else).
#[test]
fn without_heights_or_acceleration_the_crossing_is_bit_for_bit_unchanged() {
    for spec in vbi::vehicle::presets() {
        let model = assemble(&spec).unwrap();
        assert!(
            model.pitch_load_per_acceleration.is_empty(),
            "{}",
            spec.name
        );
    }
    let plain = assemble(&preset("tractor-semitrailer-5axle").unwrap()).unwrap();
    let tall = assemble(&with_heights("tractor-semitrailer-5axle", &[1.1, 1.9])).unwrap();
    assert_eq!(tall.pitch_load_per_acceleration.len(), 2);
    let without = crossing_under(plain, 0.0);
    let with = crossing_under(tall, 0.0);
    assert_eq!(without, with);
}

/// Braking a vehicle without centre-of-mass heights changes only its speed, and says so; with
/// heights, or at constant speed, there is no such warning (issue 46: braking-truck.toml braked
/// in silence).
#[test]
fn braking_without_heights_is_warned_about_and_with_heights_is_not() {
    let warned = |history: &ResponseHistory| {
        history
            .warnings
            .iter()
            .filter(|w| matches!(w, SolverWarning::SpeedChangeWithoutPitch { .. }))
            .count()
    };
    let plain = assemble(&preset("tractor-semitrailer-5axle").unwrap()).unwrap();
    let tall = assemble(&with_heights("tractor-semitrailer-5axle", &[1.1, 1.9])).unwrap();
    let braking = crossing_under(plain.clone(), -2.0);
    assert_eq!(warned(&braking), 1, "{:?}", braking.warnings);
    let text = braking
        .warnings
        .iter()
        .map(ToString::to_string)
        .find(|w| w.contains("no centre-of-mass heights"))
        .expect("the warning's text");
    assert!(
        text.contains("vehicle 1 (tractor-semitrailer-5axle)"),
        "{text}"
    );
    assert_eq!(warned(&crossing_under(tall, -2.0)), 0);
    assert_eq!(warned(&crossing_under(plain, 0.0)), 0);
}
