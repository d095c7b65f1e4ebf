//! Unit tests of the solver: the rank-T elimination against a dense assembly of Eq. 29.

use nalgebra::{DMatrix, DVector};

use super::*;
use crate::deck::{DeckGeometry, DeckLine};
use crate::modal::{Mode, ModeKind};
use crate::vehicle::TyreContact;

/// A simply supported beam: one deck line, mass-normalised sine modes with slopes.
fn beam_basis(length: f64, modes: usize, damping_ratio: f64) -> ModalBasis {
    let (ei, mass) = (2.0e9, 5.0e3);
    let nodes: Vec<f64> = (0..=(length / 0.5) as usize)
        .map(|i| i as f64 * 0.5)
        .collect();
    let amp = (2.0 / (mass * length)).sqrt();
    let mut deflection = Vec::new();
    let mut slope = Vec::new();
    for &x in &nodes {
        for k in 1..=modes {
            let a = k as f64 * std::f64::consts::PI / length;
            deflection.push(amp * (a * x).sin());
            slope.push(amp * a * (a * x).cos());
        }
    }
    ModalBasis {
        modes: (1..=modes)
            .map(|k| Mode {
                circular_frequency: (k as f64 * std::f64::consts::PI / length).powi(2)
                    * (ei / mass).sqrt(),
                damping_ratio,
                kind: ModeKind::VerticalBending,
                residual: 0.0,
            })
            .collect(),
        deck: DeckGeometry {
            lines: vec![DeckLine {
                lateral_position: 0.0,
                node_positions: nodes,
                first_node: 0,
            }],
            length,
        },
        deck_deflection: deflection,
        deck_slope: slope,
        stations: Vec::new(),
        station_deflection: Vec::new(),
        station_moment: Vec::new(),
        station_force: Vec::new(),
        dof_count: 0,
        check_modes: None,
    }
}

/// A half car: body bounce and pitch, two axle masses, suspension and tyres with damping.
fn half_car() -> VehicleModel {
    let (mb, ib, ma) = (8000.0, 3.0e4, 500.0);
    let (ks, cs, kt, ct) = (4.0e5, 1.0e4, 1.5e6, 2.0e3);
    let lever = [2.0, -2.0]; // axle positions from the centre of mass
    let mut k = DMatrix::zeros(4, 4);
    let mut c = DMatrix::zeros(4, 4);
    let add = |m: &mut DMatrix<f64>, b: &[f64; 4], value: f64| {
        for i in 0..4 {
            for j in 0..4 {
                m[(i, j)] += value * b[i] * b[j];
            }
        }
    };
    for a in 0..2 {
        // Suspension elongation = axle − (bounce + lever·pitch).
        let mut b = [-1.0, -lever[a], 0.0, 0.0];
        b[2 + a] = 1.0;
        add(&mut k, &b, ks);
        add(&mut c, &b, cs);
        let mut t = [0.0; 4];
        t[2 + a] = 1.0;
        add(&mut k, &t, kt);
        add(&mut c, &t, ct);
    }
    let g = 9.81;
    let total = mb + 2.0 * ma;
    VehicleModel {
        name: "half_car".into(),
        dof_names: vec![
            "bounce".into(),
            "pitch".into(),
            "axle1".into(),
            "axle2".into(),
        ],
        mass_matrix: DMatrix::from_diagonal(&DVector::from_vec(vec![mb, ib, ma, ma])),
        damping_matrix: c,
        stiffness_matrix: k,
        contacts: (0..2)
            .map(|a| TyreContact {
                longitudinal_offset: -4.0 * a as f64,
                lateral_offset: 0.0,
                static_load: total * g / 2.0,
                kind: ContactKind::Tyre {
                    stiffness: kt,
                    damping: ct,
                    coupling: vec![(2 + a, 1.0)],
                },
            })
            .collect(),
        pitch_load_per_acceleration: Vec::new(),
    }
}

fn wavy_road() -> RoadProfile {
    let spacing = 0.05;
    let samples = 1000;
    let h = |x: f64| 0.004 * (0.9 * x).sin() + 0.002 * (3.1 * x + 0.4).sin();
    RoadProfile {
        highest_spatial_frequency: None,
        start: -10.0,
        spacing,
        left: (0..samples)
            .map(|i| h(-10.0 + i as f64 * spacing))
            .collect(),
        right: (0..samples)
            .map(|i| h(-10.0 + i as f64 * spacing))
            .collect(),
    }
}

/// Newmark on the full coupled system of Eq. 29, assembled and factorised densely every step,
/// for vehicles travelling forward on the deck centreline at constant speeds (their DOFs one
/// after the other): the modal coordinates and the vehicle DOFs at every instant, steps × N and
/// steps × d.
fn dense_reference(
    basis: &ModalBasis,
    crossing: &Crossing,
    dt: f64,
    steps: usize,
) -> (Vec<f64>, Vec<f64>) {
    let n = basis.mode_count();
    let firsts: Vec<usize> = crossing
        .vehicles
        .iter()
        .scan(0, |first, run| {
            let this = *first;
            *first += run.vehicle.dof_count();
            Some(this)
        })
        .collect();
    let d: usize = crossing
        .vehicles
        .iter()
        .map(|r| r.vehicle.dof_count())
        .sum();
    let size = n + d;
    let gamma = 0.5;
    // Each DOF's β: the modes' period-matched βₖ (docs/theory.md), the vehicle's ¼.
    let options = SolverOptions::default();
    let beta = DMatrix::from_diagonal(&DVector::from_fn(size, |i, _| {
        if i < n {
            modal_newmark_beta(&options, dt, basis.modes[i].circular_frequency)
        } else {
            0.25
        }
    }));
    let half = DMatrix::<f64>::identity(size, size) * 0.5;
    let speed = |run: &VehicleRun| match run.speed {
        SpeedProfile::Constant(v) => v,
        _ => unreachable!("constant speeds only"),
    };
    let assemble = |t: f64| {
        let mut m = DMatrix::zeros(size, size);
        let mut c = DMatrix::zeros(size, size);
        let mut k = DMatrix::zeros(size, size);
        let mut f = DVector::zeros(size);
        for i in 0..n {
            let mode = &basis.modes[i];
            m[(i, i)] = 1.0;
            c[(i, i)] = 2.0 * mode.damping_ratio * mode.circular_frequency;
            k[(i, i)] = mode.circular_frequency.powi(2);
        }
        for (run, &first) in crossing.vehicles.iter().zip(&firsts) {
            let veh = &run.vehicle;
            let (dv, v) = (veh.dof_count(), speed(run));
            let offset = n + first;
            for i in 0..dv {
                for j in 0..dv {
                    m[(offset + i, offset + j)] = veh.mass_matrix[(i, j)];
                    c[(offset + i, offset + j)] = veh.damping_matrix[(i, j)];
                    k[(offset + i, offset + j)] = veh.stiffness_matrix[(i, j)];
                }
            }
            for contact in &veh.contacts {
                let ContactKind::Tyre {
                    stiffness: kt,
                    damping: ct,
                    coupling,
                } = &contact.kind
                else {
                    unreachable!()
                };
                let x = run.start_position + v * t + contact.longitudinal_offset;
                let (r, rs) = crossing.road.elevation_and_slope(Track::Left, x);
                let mut phi = vec![0.0; n];
                let mut psi = vec![0.0; n];
                let stencil = basis.deck.stencil(x, 0.0);
                if !stencil.is_empty() {
                    stencil.evaluate_many(
                        &basis.deck_deflection,
                        &basis.deck_slope,
                        n,
                        &mut phi,
                        &mut psi,
                    );
                }
                let mut a = vec![0.0; dv];
                for &(dof, coef) in coupling {
                    a[dof] += coef;
                }
                // P = S + k(φq + r − aZ) + c(φq̇ + vψq + v r′ − aŻ); bridge: +φP on the left side.
                for i in 0..n {
                    for j in 0..n {
                        c[(i, j)] += ct * phi[i] * phi[j];
                        k[(i, j)] += kt * phi[i] * phi[j] + ct * v * phi[i] * psi[j];
                    }
                    for j in 0..dv {
                        c[(i, offset + j)] -= ct * phi[i] * a[j];
                        k[(i, offset + j)] -= kt * phi[i] * a[j];
                    }
                    f[i] -= phi[i] * (contact.static_load + kt * r + ct * v * rs);
                }
                // Vehicle: C_v, K_v hold the tyre on a rigid road; the deck motion and road
                // drive it.
                for i in 0..dv {
                    for j in 0..n {
                        c[(offset + i, j)] -= ct * a[i] * phi[j];
                        k[(offset + i, j)] -= kt * a[i] * phi[j] + ct * v * a[i] * psi[j];
                    }
                    f[offset + i] += a[i] * (kt * r + ct * v * rs);
                }
            }
        }
        (m, c, k, f)
    };
    let mut u = DVector::zeros(size);
    let mut ud = DVector::zeros(size);
    let (m0, c0, k0, f0) = assemble(0.0);
    // Static equilibrium of the vehicles on the road: K_v Z₀ = Σ k_t a r (stiffness part only).
    let kv = k0.view((n, n), (d, d)).into_owned();
    let mut fk = DVector::zeros(d);
    for (run, &first) in crossing.vehicles.iter().zip(&firsts) {
        for contact in &run.vehicle.contacts {
            let ContactKind::Tyre {
                stiffness: kt,
                coupling,
                ..
            } = &contact.kind
            else {
                unreachable!()
            };
            let (r, _) = crossing.road.elevation_and_slope(
                Track::Left,
                run.start_position + contact.longitudinal_offset,
            );
            for &(dof, coef) in coupling {
                fk[first + dof] += kt * coef * r;
            }
        }
    }
    let z0 = kv.lu().solve(&fk).unwrap();
    u.rows_mut(n, d).copy_from(&z0);
    let mut ua = m0.clone().lu().solve(&(f0 - &c0 * &ud - &k0 * &u)).unwrap();
    let (mut modal, mut vehicle) = (Vec::new(), Vec::new());
    modal.extend(u.rows(0, n).iter().copied());
    vehicle.extend(u.rows(n, d).iter().copied());
    for i in 1..=steps {
        let (m, c, k, f) = assemble(i as f64 * dt);
        let up = &u + &ud * dt + (&half - &beta) * &ua * (dt * dt);
        let vp = &ud + &ua * (dt * (1.0 - gamma));
        let eff = &m + &c * (gamma * dt) + &k * &beta * (dt * dt);
        let rhs = f - &c * &vp - &k * &up;
        ua = eff.lu().solve(&rhs).unwrap();
        u = up + &beta * &ua * (dt * dt);
        ud = vp + &ua * (gamma * dt);
        modal.extend(u.rows(0, n).iter().copied());
        vehicle.extend(u.rows(n, d).iter().copied());
    }
    (modal, vehicle)
}

/// Asserts |a − b| ≤ tolerance · max |b| entry by entry.
fn assert_close(what: &str, actual: &[f64], expected: &[f64], tolerance: f64) {
    assert_eq!(actual.len(), expected.len(), "{what}: lengths");
    let scale = expected.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(scale > 0.0, "{what}: all zero");
    for (i, (a, b)) in actual.iter().zip(expected).enumerate() {
        assert!(
            (a - b).abs() <= tolerance * scale,
            "{what} value {i}: {a} vs {b}"
        );
    }
}

/// Runs `crossing` at Δt = 2 ms and checks its modal and vehicle displacements against the dense
/// Newmark of Eq. 29 (`dense_reference`) within 1e-9 of the largest value; returns the history.
fn matches_dense_reference(basis: &ModalBasis, crossing: &Crossing) -> ResponseHistory {
    let options = SolverOptions {
        time_step: Some(2.0e-3),
        ..SolverOptions::default()
    };
    let history = simulate(basis, crossing, &options).unwrap();
    let (modal, vehicle) = dense_reference(basis, crossing, 2.0e-3, history.step_count - 1);
    assert_close("q", &history.modal_displacement, &modal, 1e-9);
    assert_close("Z", &history.vehicle_displacement, &vehicle, 1e-9);
    history
}

#[test]
fn rank_t_elimination_matches_a_dense_solve_of_equation_29() {
    // The Schur/Woodbury elimination is algebraically exact, so the two integrations agree to
    // rounding: 1e-9 relative to the largest modal coordinate leaves room for the different
    // operation order over a few hundred steps.
    let basis = beam_basis(10.0, 4, 0.02);
    let mut crossing = Crossing::new(half_car(), wavy_road(), 12.0);
    crossing.vehicles[0].start_position = -3.0;
    crossing.free_vibration_duration = Some(0.1);
    matches_dense_reference(&basis, &crossing);
}

/// A wavy road from x = −40 m to +60 m.
fn long_wavy_road() -> RoadProfile {
    let (start, spacing) = (-40.0, 0.05);
    let h = |x: f64| 0.004 * (0.9 * x).sin() + 0.002 * (3.1 * x + 0.4).sin();
    let left: Vec<f64> = (0..2000).map(|i| h(start + i as f64 * spacing)).collect();
    RoadProfile {
        highest_spatial_frequency: None,
        start,
        spacing,
        right: left.clone(),
        left,
    }
}

#[test]
fn a_stream_entering_and_leaving_the_deck_matches_a_dense_solve_of_equation_29() {
    // Three half cars: the second enters while the first is on the deck, the third waits on
    // the approach road until both have left and crosses alone. The coupled tyre system holds
    // only the vehicles with a tyre on the deck and the others are integrated on their own;
    // the dense Newmark of all modes and all vehicles' DOFs couples everything every step.
    let basis = beam_basis(10.0, 4, 0.02);
    let mut crossing = Crossing::new(half_car(), long_wavy_road(), 12.0);
    for (start, speed) in [(-10.0, 12.0), (-30.0, 15.0)] {
        crossing.vehicles.push(VehicleRun {
            start_position: start,
            ..VehicleRun::forward(half_car(), speed)
        });
    }
    crossing.vehicles[0].start_position = -3.0;
    crossing.free_vibration_duration = Some(0.1);
    let history = matches_dense_reference(&basis, &crossing);
    // The run does hold one, two and no vehicle on the deck at times.
    let on_deck = |step: usize, vehicle: usize| {
        let x = history.contact_position[step * 6 + 2 * vehicle];
        (0.0..=14.0).contains(&x)
    };
    let counts: Vec<usize> = (0..history.step_count)
        .map(|i| (0..3).filter(|&v| on_deck(i, v)).count())
        .collect();
    assert!(counts.contains(&0) && counts.contains(&1) && counts.contains(&2));
}

#[test]
fn a_vehicle_on_the_approach_road_is_unaffected_by_the_bridge() {
    // A half car crosses the deck while a light one, far behind, jumps a 5 cm bump (its tyres
    // leave the road and land: its own system with tyres in flight). The light car never
    // reaches the deck in the steps run: it is integrated with its own constant blocks exactly
    // as when it drives alone, bit for bit.
    let basis = beam_basis(10.0, 4, 0.02);
    let mut light = half_car();
    for c in &mut light.contacts {
        c.static_load *= 0.1;
    }
    let (start, spacing) = (-160.0, 0.05);
    let elevation: Vec<f64> = (0..4000)
        .map(|i| if (600..610).contains(&i) { 0.05 } else { 0.0 })
        .collect();
    let road = RoadProfile {
        highest_spatial_frequency: None,
        start,
        spacing,
        left: elevation.clone(),
        right: elevation,
    };
    let light_run = VehicleRun {
        start_position: -135.0,
        ..VehicleRun::forward(light, 20.0)
    };
    let mut both = Crossing::new(half_car(), road.clone(), 12.0);
    both.vehicles[0].start_position = -3.0;
    both.vehicles.push(light_run.clone());
    let alone = Crossing {
        vehicles: vec![light_run],
        road,
        free_vibration_duration: None,
    };
    let options = SolverOptions {
        time_step: Some(2.0e-3),
        ..SolverOptions::default()
    };
    let mut together = Integrator::new(&basis, &both, &options).unwrap();
    let mut by_itself = Integrator::new(&basis, &alone, &options).unwrap();
    let bits = |values: &[f64]| values.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    let mut in_flight_seen = false;
    for step in 0..750 {
        if step > 0 {
            together.step().unwrap();
            by_itself.step().unwrap();
        }
        assert!(together.contact_positions()[2] < 0.0);
        assert_eq!(
            bits(&together.vehicle_displacements()[4..]),
            bits(by_itself.vehicle_displacements()),
            "step {step}"
        );
        assert_eq!(
            bits(&together.vehicle_accelerations()[4..]),
            bits(by_itself.vehicle_accelerations()),
            "step {step}"
        );
        assert_eq!(
            bits(&together.contact_forces()[2..]),
            bits(by_itself.contact_forces()),
            "step {step}"
        );
        in_flight_seen |= !by_itself.is_in_contact(0) || !by_itself.is_in_contact(1);
    }
    assert!(in_flight_seen, "the light car's tyres never left the road");
    // The first car did cross the deck meanwhile, and it moved the bridge.
    assert!(together.contact_positions()[1] > 10.0);
    assert!(together.modal_displacements()[0] != 0.0);
}

#[test]
fn a_vehicle_on_a_smooth_road_off_the_bridge_stays_at_rest() {
    let basis = beam_basis(10.0, 3, 0.0);
    let mut crossing = Crossing::new(half_car(), RoadProfile::smooth(-50.0, 50.0), 10.0);
    crossing.vehicles[0].start_position = -20.0;
    crossing.free_vibration_duration = Some(0.0);
    let history = simulate(&basis, &crossing, &SolverOptions::default()).unwrap();
    // Until the front axle reaches the deck, nothing moves: exactly zero.
    let before = (1.0 / history.time_step) as usize; // 10 m at 10 m/s: still 1 s off the deck
    assert!(history.modal_displacement[..before * 3]
        .iter()
        .all(|&q| q == 0.0));
    assert!(history.vehicle_displacement[..before * 4]
        .iter()
        .all(|&z| z == 0.0));
}

#[test]
fn invalid_inputs_are_typed_errors() {
    let basis = beam_basis(10.0, 3, 0.0);
    let crossing = Crossing::new(half_car(), RoadProfile::smooth(-50.0, 50.0), -1.0);
    assert!(matches!(
        simulate(&basis, &crossing, &SolverOptions::default()),
        Err(SolverError::InvalidSpeed { .. })
    ));
    let crossing = Crossing::new(half_car(), RoadProfile::smooth(-50.0, 50.0), 10.0);
    let options = SolverOptions {
        newmark_gamma: 0.4,
        ..SolverOptions::default()
    };
    assert!(matches!(
        simulate(&basis, &crossing, &options),
        Err(SolverError::InvalidNewmark { .. })
    ));
    // Central difference-like explicit scheme with a step above its limit 2/ω_max.
    let options = SolverOptions {
        newmark_beta: 0.0,
        time_step: Some(0.5),
        ..SolverOptions::default()
    };
    assert!(matches!(
        simulate(&basis, &crossing, &options),
        Err(SolverError::UnstableTimeStep { .. })
    ));
}

#[test]
fn a_coarse_user_time_step_warns_naming_the_first_under_resolved_mode() {
    let basis = beam_basis(10.0, 3, 0.0);
    let w = basis.modes[1].circular_frequency;
    // Between T₂/20 and T₁/20: mode 2 (and 3) under-resolved, mode 1 fine.
    let dt = 1.5 * 2.0 * std::f64::consts::PI / w / 20.0;
    let mut crossing = Crossing::new(half_car(), RoadProfile::smooth(-50.0, 50.0), 10.0);
    crossing.free_vibration_duration = Some(0.0);
    let options = SolverOptions {
        time_step: Some(dt),
        ..SolverOptions::default()
    };
    let history = simulate(&basis, &crossing, &options).unwrap();
    assert!(matches!(
        history.warnings.as_slice(),
        [SolverWarning::ModeUnderResolved {
            mode: 2,
            further_modes: 1,
            ..
        }]
    ));
    // The default step resolves every mode up to 5 × the excitation frequency (here the half
    // car's highest mode), and names the modes above it, which respond quasi-statically.
    let history = simulate(&basis, &crossing, &SolverOptions::default()).unwrap();
    let resolved = resolved_bridge_frequency(&basis, &crossing);
    let needed: Vec<&Mode> = basis
        .modes
        .iter()
        .filter(|m| m.frequency_hz() <= resolved)
        .collect();
    assert!(!needed.is_empty());
    for mode in needed {
        assert!(
            history.time_step <= 1.0 / (20.0 * mode.frequency_hz()) && history.time_step <= 1e-3
        );
    }
    assert!(history
        .warnings
        .iter()
        .all(|w| matches!(w, SolverWarning::ModesQuasiStatic { .. })));
    assert_eq!(
        history.warnings.is_empty(),
        basis.modes.iter().all(|m| m.frequency_hz() <= resolved)
    );
}

#[test]
fn a_tensile_tyre_force_is_reported_as_loss_of_contact() {
    // A light vehicle on a road with a 5 cm step bump at speed: the tyre unloads completely.
    let basis = beam_basis(10.0, 3, 0.02);
    let mut vehicle = half_car();
    for c in &mut vehicle.contacts {
        c.static_load *= 0.1;
    }
    let road = RoadProfile {
        highest_spatial_frequency: None,
        start: -10.0,
        spacing: 0.05,
        left: (0..600)
            .map(|i| if (200..210).contains(&i) { 0.05 } else { 0.0 })
            .collect(),
        right: vec![0.0; 600],
    };
    let mut crossing = Crossing::new(vehicle, road, 20.0);
    crossing.vehicles[0].start_position = -5.0;
    // Bonded tyres (the linear model): the recorded force is the tensile one, not clipped.
    let bonded = SolverOptions {
        tyre_separation: false,
        ..SolverOptions::default()
    };
    let history = simulate(&basis, &crossing, &bonded).unwrap();
    assert!(!history.contact_losses.is_empty());
    let loss = &history.contact_losses[0];
    assert!(loss.minimum_force < 0.0 && loss.end_time >= loss.start_time);
    let i = (loss.start_time / history.time_step).round() as usize;
    assert!(history.contact_force[i * 2 + loss.contact] < 0.0);
    // With separation (the default) the tyre leaves the road: the same loss is reported, with
    // its would-be tensile force, and no contact force is ever tensile.
    let history = simulate(&basis, &crossing, &SolverOptions::default()).unwrap();
    assert!(!history.contact_losses.is_empty());
    assert!(history.contact_losses[0].minimum_force < 0.0);
    assert!(history.contact_force.iter().all(|&p| p >= 0.0));
}

/// A wheel (one mass on a tyre spring, no suspension) rolling off a 0.2 m step down on the rigid
/// approach road (at t = 0.5 s) leaves the road and falls freely: while in flight its acceleration is −g to
/// round-off and its contact force is zero, and it lands after √(2(h − δ)/g), δ = mg/k_t the
/// static tyre deflection (closed form of free fall). Tolerance 10 ms: the road's cubic
/// interpolation overshoots by up to 2h/27 ≈ 15 mm just before the step and kicks the wheel up
/// at about 0.04 m/s, which lengthens the flight by about 4 ms; the time step adds < 1 ms.
#[test]
fn a_wheel_off_a_step_falls_freely_until_it_lands() {
    let (mass, kt, g, h) = (1000.0, 1.0e6, 9.81, 0.2);
    let vehicle = VehicleModel {
        name: "wheel".into(),
        dof_names: vec!["wheel".into()],
        mass_matrix: DMatrix::from_element(1, 1, mass),
        damping_matrix: DMatrix::zeros(1, 1),
        // The vehicle's own matrices include its tyres on a rigid road.
        stiffness_matrix: DMatrix::from_element(1, 1, kt),
        contacts: vec![TyreContact {
            longitudinal_offset: 0.0,
            lateral_offset: 0.0,
            static_load: mass * g,
            kind: ContactKind::Tyre {
                stiffness: kt,
                damping: 0.0,
                coupling: vec![(0, 1.0)],
            },
        }],
        pitch_load_per_acceleration: Vec::new(),
    };
    // Step at x = −30 m (0.05 m samples), long before the 10 m deck.
    let (road_start, spacing, step_sample) = (-40.0, 0.05, 200);
    let elevation: Vec<f64> = (0..1200)
        .map(|i| if i > step_sample { -h } else { 0.0 })
        .collect();
    let road = RoadProfile {
        highest_spatial_frequency: None,
        start: road_start,
        spacing,
        left: elevation.clone(),
        right: elevation,
    };
    let (speed, start) = (10.0, -35.0);
    let basis = beam_basis(10.0, 3, 0.02);
    let mut crossing = Crossing::new(vehicle, road, speed);
    crossing.vehicles[0].start_position = start;
    let history = simulate(&basis, &crossing, &SolverOptions::default()).unwrap();
    // The undamped tyre is elastic: after landing the wheel bounces off again (several flights).
    // The first flight is the fall, which starts where the road drops.
    let loss = &history.contact_losses[0];
    let step_time = (road_start + step_sample as f64 * spacing - start) / speed;
    assert!((loss.start_time - step_time).abs() <= 0.01, "{loss:?}");
    let dt = history.time_step;
    let (first, last) = (
        (loss.start_time / dt).round() as usize,
        (loss.end_time / dt).round() as usize,
    );
    for i in first + 1..last {
        assert_eq!(history.contact_force[i], 0.0);
        let a = history.vehicle_acceleration[i];
        assert!((a + g).abs() <= 1e-9 * g, "step {i}: acceleration {a}");
    }
    let flight = loss.end_time - loss.start_time;
    let expected = (2.0 * (h - mass * g / kt) / g).sqrt();
    assert!(
        (flight - expected).abs() <= 0.01,
        "flight {flight} s against free fall {expected} s"
    );
}

#[test]
fn a_vehicle_centred_on_a_symmetric_deck_loads_symmetric_girders_equally() {
    // Three girder lines at y = −2, 0, 2 m; modes 1–3 bend the deck uniformly across, modes 4–6
    // twist it (shape ∝ y). A vehicle with wheels at ±0.9 m centred on the deck on a smooth road
    // excites no torsion: the torsional coordinates stay at rounding level and the outer girders
    // deflect equally.
    let length = 10.0;
    let xs: Vec<f64> = (0..=20).map(|i| i as f64 * 0.5).collect();
    let lines: Vec<DeckLine> = (0..3)
        .map(|g| DeckLine {
            lateral_position: -2.0 + 2.0 * g as f64,
            node_positions: xs.clone(),
            first_node: g * xs.len(),
        })
        .collect();
    let n = 6;
    let mut deflection = Vec::new();
    let mut slope = Vec::new();
    for line in &lines {
        for &x in &xs {
            for k in 0..n {
                let a = ((k % 3) + 1) as f64 * std::f64::consts::PI / length;
                let lateral = if k < 3 {
                    1.0
                } else {
                    line.lateral_position / 2.0
                };
                deflection.push(4e-3 * lateral * (a * x).sin());
                slope.push(4e-3 * lateral * a * (a * x).cos());
            }
        }
    }
    let basis = ModalBasis {
        modes: (0..n)
            .map(|k| Mode {
                circular_frequency: 20.0 * (1.0 + k as f64),
                damping_ratio: 0.02,
                kind: if k < 3 {
                    ModeKind::VerticalBending
                } else {
                    ModeKind::Torsion
                },
                residual: 0.0,
            })
            .collect(),
        deck: DeckGeometry { lines, length },
        deck_deflection: deflection,
        deck_slope: slope,
        stations: Vec::new(),
        station_deflection: Vec::new(),
        station_moment: Vec::new(),
        station_force: Vec::new(),
        dof_count: 0,
        check_modes: None,
    };
    // Axle: bounce and roll, tyres at ±0.9 m.
    let (m, inertia, kt, ct) = (4000.0, 1500.0, 1.5e6, 3.0e3);
    let lever = [0.9, -0.9];
    let mut k = DMatrix::zeros(2, 2);
    let mut c = DMatrix::zeros(2, 2);
    for y in lever {
        let b = [1.0, y];
        for i in 0..2 {
            for j in 0..2 {
                k[(i, j)] += kt * b[i] * b[j];
                c[(i, j)] += ct * b[i] * b[j];
            }
        }
    }
    let vehicle = VehicleModel {
        name: "axle".into(),
        dof_names: vec!["bounce".into(), "roll".into()],
        mass_matrix: DMatrix::from_diagonal(&DVector::from_vec(vec![m, inertia])),
        damping_matrix: c,
        stiffness_matrix: k,
        contacts: lever
            .iter()
            .map(|&y| TyreContact {
                longitudinal_offset: 0.0,
                lateral_offset: y,
                static_load: m * 9.81 / 2.0,
                kind: ContactKind::Tyre {
                    stiffness: kt,
                    damping: ct,
                    coupling: vec![(0, 1.0), (1, y)],
                },
            })
            .collect(),
        pitch_load_per_acceleration: Vec::new(),
    };
    let crossing = Crossing::new(vehicle, RoadProfile::smooth(-50.0, 50.0), 15.0);
    let history = simulate(&basis, &crossing, &SolverOptions::default()).unwrap();
    let bending = history
        .modal_displacement
        .iter()
        .fold(0.0f64, |a, q| a.max(q.abs()));
    for i in 0..history.step_count {
        let q = history.modal_displacements_at(i);
        // 1e-12 of the bending response: rounding of the mirrored stencil weights.
        assert!(
            q[3..].iter().all(|t| t.abs() <= 1e-12 * bending),
            "step {i}: {q:?}"
        );
    }
}

/// The per-element cubic (`deck::ElementCubic`) gives the stencil's mode values and slopes to
/// round-off, at every position along a three-line deck, for tyres between lines and on a line,
/// including the element ends and the deck end (hand-written, checked against
/// `DeckGeometry::stencil`).
#[test]
fn element_cubic_matches_the_stencil_to_round_off() {
    let xs: Vec<f64> = vec![0.0, 0.7, 1.5, 2.0, 3.1, 4.0];
    let lines: Vec<DeckLine> = (0..3)
        .map(|g| DeckLine {
            lateral_position: -2.0 + 2.0 * g as f64,
            node_positions: xs.clone(),
            first_node: g * xs.len(),
        })
        .collect();
    let deck = DeckGeometry { lines, length: 4.0 };
    let n = 7;
    let nodes = deck.node_count();
    // Smooth but arbitrary fields.
    let deflection: Vec<f64> = (0..nodes * n)
        .map(|i| (0.37 * i as f64).sin() * 1e-3)
        .collect();
    let slope: Vec<f64> = (0..nodes * n)
        .map(|i| (0.91 * i as f64).cos() * 1e-4)
        .collect();
    let (mut v1, mut s1, mut v2, mut s2) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut v3 = vec![0.0; n];
    for lateral in [-0.9, 0.0, 0.9, 2.0] {
        let weights = deck.lateral_weights(lateral);
        let mut cache = ElementCubic::new(n);
        for step in 0..=400 {
            let x = 4.0 * step as f64 / 400.0;
            let stencil = deck.stencil(x, lateral);
            stencil.evaluate_many(&deflection, &slope, n, &mut v1, &mut s1);
            assert!(cache.reach(&deck, &weights, (&deflection, &slope), x));
            cache.values_and_slopes(x, &mut v2, &mut s2);
            // The values alone (the analysis's route) are the same numbers bit for bit.
            cache.values(x, &mut v3);
            assert!(v2.iter().zip(&v3).all(|(a, b)| a.to_bits() == b.to_bits()));
            for k in 0..n {
                // Round-off of a cubic in ξ ∈ [0, 1] with O(1e-3) coefficients: 1e-15 absolute
                // on values of 1e-3, i.e. ~1e-12 relative; slopes divided by h ≥ 0.5.
                assert!((v1[k] - v2[k]).abs() <= 1e-15, "x {x} y {lateral} mode {k}");
                assert!(
                    (s1[k] - s2[k]).abs() <= 1e-14,
                    "x {x} y {lateral} mode {k} slope"
                );
            }
        }
    }
}

/// A light half car on a road with a 5 cm bump, fast: tyres leave the road and land again
/// (exercises the contact active set), and a plain crossing of the wavy road.
fn stepping_cases() -> Vec<(ModalBasis, Crossing, SolverOptions)> {
    let basis = beam_basis(10.0, 4, 0.02);
    let mut light = half_car();
    for c in &mut light.contacts {
        c.static_load *= 0.1;
    }
    let bump = RoadProfile {
        highest_spatial_frequency: None,
        start: -10.0,
        spacing: 0.05,
        left: (0..600)
            .map(|i| if (200..210).contains(&i) { 0.05 } else { 0.0 })
            .collect(),
        right: vec![0.0; 600],
    };
    let mut separating = Crossing::new(light, bump, 20.0);
    separating.vehicles[0].start_position = -5.0;
    let mut wavy = Crossing::new(half_car(), wavy_road(), 12.0);
    wavy.vehicles[0].start_position = -3.0;
    wavy.free_vibration_duration = Some(0.1);
    vec![
        (basis.clone(), separating, SolverOptions::default()),
        (
            basis,
            wavy,
            SolverOptions {
                time_step: Some(2.0e-3),
                ..SolverOptions::default()
            },
        ),
    ]
}

#[test]
fn the_stepping_api_driven_by_hand_gives_the_history_of_simulate() {
    for (basis, crossing, options) in stepping_cases() {
        let expected = simulate(&basis, &crossing, &options).unwrap();
        let mut integrator = Integrator::new(&basis, &crossing, &options).unwrap();
        let mut steps = 0;
        while !integrator.is_finished() {
            integrator.step().unwrap();
            steps += 1;
        }
        assert_eq!(steps + 1, expected.step_count);
        let history = integrator.finish().unwrap();
        assert!(history == expected, "the hand-driven history differs");
    }
    // The separating case does separate.
    let (basis, crossing, options) = stepping_cases().swap_remove(0);
    let history = simulate(&basis, &crossing, &options).unwrap();
    assert!(!history.contact_losses.is_empty());
}

#[test]
fn the_state_read_between_steps_is_the_recorded_one() {
    for (basis, crossing, options) in stepping_cases() {
        let history = simulate(&basis, &crossing, &options).unwrap();
        let (n, d, c) = (
            history.mode_count,
            history.vehicle_dof_count(),
            history.contacts.len(),
        );
        let dt = history.time_step;
        let mut integrator = Integrator::new(&basis, &crossing, &options).unwrap();
        assert_eq!(integrator.step_count(), history.step_count);
        assert_eq!(integrator.time_step(), dt);
        let mut in_flight_seen = false;
        for i in 0..history.step_count {
            if i > 0 {
                let before = integrator.time();
                integrator.step().unwrap();
                assert!((integrator.time() - before - dt).abs() <= 1e-12 * dt.max(before));
            }
            assert_eq!(integrator.step_index(), i);
            assert_eq!(integrator.time(), history.time(i));
            assert_eq!(integrator.is_finished(), i + 1 == history.step_count);
            assert_eq!(
                integrator.front_axle_position(),
                history.front_axle_position[i]
            );
            assert_eq!(
                integrator.modal_displacements(),
                history.modal_displacements_at(i)
            );
            assert_eq!(
                integrator.modal_velocities(),
                &history.modal_velocity[i * n..(i + 1) * n]
            );
            assert_eq!(
                integrator.contact_forces(),
                &history.contact_force[i * c..(i + 1) * c]
            );
            assert_eq!(
                integrator.vehicle_displacements(),
                &history.vehicle_displacement[i * d..(i + 1) * d]
            );
            assert_eq!(
                integrator.vehicle_accelerations(),
                &history.vehicle_acceleration[i * d..(i + 1) * d]
            );
            assert_eq!(integrator.modal_accelerations().len(), n);
            assert_eq!(integrator.vehicle_velocities().len(), d);
            for contact in 0..c {
                if !integrator.is_in_contact(contact) {
                    // A tyre in flight carries no force, inside a recorded loss interval.
                    in_flight_seen = true;
                    assert_eq!(integrator.contact_forces()[contact], 0.0);
                    let t = integrator.time();
                    assert!(history
                        .contact_losses
                        .iter()
                        .any(|l| l.contact == contact && l.start_time <= t && t <= l.end_time));
                }
            }
        }
        assert!(integrator.is_finished());
        assert_eq!(integrator.warnings(), history.warnings.as_slice());
        // Only the separating case has tyres in flight.
        assert_eq!(
            in_flight_seen,
            options.tyre_separation && !history.contact_losses.is_empty()
        );
    }
}

#[test]
fn a_run_finished_early_is_the_start_of_the_full_history() {
    let (basis, crossing, options) = stepping_cases().swap_remove(1);
    let full = simulate(&basis, &crossing, &options).unwrap();
    let mut integrator = Integrator::new(&basis, &crossing, &options).unwrap();
    for _ in 0..10 {
        integrator.step().unwrap();
    }
    let part = integrator.finish().unwrap();
    assert_eq!(part.step_count, 11);
    assert_eq!(
        part.modal_displacement,
        full.modal_displacement[..11 * part.mode_count]
    );
    assert_eq!(
        part.contact_force,
        full.contact_force[..11 * part.contacts.len()]
    );
    assert_eq!(part.exit_step, 10);
}

#[test]
fn stepping_past_the_end_is_an_error_that_changes_nothing() {
    let (basis, crossing, options) = stepping_cases().swap_remove(1);
    let mut integrator = Integrator::new(&basis, &crossing, &options).unwrap();
    while !integrator.is_finished() {
        integrator.step().unwrap();
    }
    let time = integrator.time();
    assert!(matches!(
        integrator.step(),
        Err(SolverError::AlreadyFinished { .. })
    ));
    assert_eq!(integrator.time(), time);
    assert_eq!(
        integrator.finish().unwrap(),
        simulate(&basis, &crossing, &options).unwrap()
    );
}

/// The quarter-car preset (sprung 3000 kg, unsprung 350 kg, suspension 4e5 N/m) on a tyre of
/// `tyre_stiffness` [N/m].
fn quarter_car_on_tyre(tyre_stiffness: f64) -> VehicleModel {
    let mut spec = crate::vehicle::preset("quarter-car").expect("a preset");
    if let crate::vehicle::VehicleDescription::Multibody(body) = &mut spec.description {
        body.axles[0].tyre_stiffness = tyre_stiffness;
    }
    crate::vehicle::assemble(&spec).expect("a valid quarter car")
}

/// Closed form of a two-DOF quarter car on a rigid road: the frequencies [Hz] of
/// [k_s/m_s, −k_s/m_s; −k_s/m_u, (k_s + k_t)/m_u], ω² = (a + d)/2 ± √(((a − d)/2)² + bc).
fn quarter_car_frequencies(sprung: f64, unsprung: f64, suspension: f64, tyre: f64) -> [f64; 2] {
    let (a, d) = (suspension / sprung, (suspension + tyre) / unsprung);
    let bc = suspension * suspension / (sprung * unsprung);
    let root = ((0.5 * (a - d)).powi(2) + bc).sqrt();
    let hz = |w2: f64| w2.sqrt() / (2.0 * std::f64::consts::PI);
    [hz(0.5 * (a + d) - root), hz(0.5 * (a + d) + root)]
}

/// A quarter car on a 1e10 N/m tyre hops at 851 Hz (closed form, quarter_car_frequencies);
/// the 1 ms default step gave DAF_M 3.94 against 1.12 converged without a word (issue 17,
/// defect 2). The default step now resolves the vehicle's modes (≤ T_hop/20), and a user step
/// of 1 ms is warned about, naming the axle hop.
#[test]
fn the_time_step_resolves_the_vehicles_axle_hop_or_says_that_it_does_not() {
    let vehicle = quarter_car_on_tyre(1e10);
    let [_, hop] = quarter_car_frequencies(3000.0, 350.0, 4.0e5, 1e10);
    let basis = beam_basis(25.0, 4, 0.02);
    let mut crossing = Crossing::new(vehicle, RoadProfile::smooth(-50.0, 50.0), 20.0);
    crossing.free_vibration_duration = Some(0.0);
    // Tolerance: the dense 2 × 2 eigen solve against the closed form, round-off (1e-9).
    assert!((highest_vehicle_frequency(&crossing) - hop).abs() < 1e-9 * hop);
    let options = SolverOptions::default();
    let dt = default_time_step(&basis, &crossing, &options);
    assert!(
        dt <= 1.0 / (20.0 * hop) * (1.0 + 1e-12),
        "default Δt {dt} s"
    );
    let coarse = SolverOptions {
        time_step: Some(1e-3),
        ..SolverOptions::default()
    };
    let history = simulate(&basis, &crossing, &coarse).unwrap();
    assert!(history.warnings.iter().any(|w| matches!(
        w,
        SolverWarning::VehicleModeUnderResolved { mode, .. } if mode == "axle 1 hop"
    )));
}

/// 20 modes of a 25 m beam reach 636 Hz (mode 20 of the closed form (nπ/L)²√(EI/m̄)); the
/// default step followed the highest one (issue 14: 13.8 kHz and 3.6 µs for 50 FE modes). With a
/// quarter car on a smooth road the excitation is the car's axle hop (12.0 Hz, closed form), so
/// modes above 5 × 12.0 Hz respond quasi-statically: the step resolves mode 5 (64 Hz is above,
/// mode 4 at 40.7 Hz below) and the run says which modes it leaves. The mid-span deflection
/// history agrees with a run whose step resolves every mode: max |w| within 0.5 % (the
/// quasi-static modes carry ≈ 1/n⁴ of the static deflection each, < 0.2 % together for
/// n ≥ 5, and their magnification is ≤ 4.2 %).
#[test]
fn the_default_time_step_resolves_the_modes_the_response_needs_and_names_the_others() {
    let basis = beam_basis(25.0, 20, 0.02);
    let mut crossing = Crossing::new(
        quarter_car_on_tyre(1.75e6),
        RoadProfile::smooth(-50.0, 50.0),
        20.0,
    );
    crossing.free_vibration_duration = Some(0.0);
    let [_, hop] = quarter_car_frequencies(3000.0, 350.0, 4.0e5, 1.75e6);
    let resolved = QUASI_STATIC_FREQUENCY_FACTOR * hop;
    assert!((resolved_bridge_frequency(&basis, &crossing) - resolved).abs() < 1e-9 * resolved);
    let default = simulate(&basis, &crossing, &SolverOptions::default()).unwrap();
    let highest_resolved = basis
        .modes
        .iter()
        .map(|m| m.frequency_hz())
        .filter(|&f| f <= resolved)
        .fold(0.0, f64::max);
    assert!((default.time_step - 1.0 / (20.0 * highest_resolved)).abs() < 1e-12);
    let first_quasi_static = basis
        .modes
        .iter()
        .position(|m| m.frequency_hz() > resolved)
        .unwrap();
    assert!(matches!(
        default.warnings.as_slice(),
        [SolverWarning::ModesQuasiStatic { mode, further_modes, .. }]
            if *mode == first_quasi_static + 1 && *further_modes == 19 - first_quasi_static
    ));
    let top = basis.modes[19].frequency_hz();
    let fine = SolverOptions {
        time_step: Some(1.0 / (20.0 * top)),
        ..SolverOptions::default()
    };
    let fine = simulate(&basis, &crossing, &fine).unwrap();
    assert!(fine.warnings.is_empty());
    let mid_node = 25; // x = 12.5 m on the 0.5 m grid of beam_basis
    let largest_mid_span_deflection = |history: &ResponseHistory| {
        let shape = &basis.deck_deflection[mid_node * 20..(mid_node + 1) * 20];
        (0..history.step_count)
            .map(|i| {
                let q = history.modal_displacements_at(i);
                shape.iter().zip(q).map(|(p, q)| p * q).sum::<f64>().abs()
            })
            .fold(0.0, f64::max)
    };
    let (coarse, reference) = (
        largest_mid_span_deflection(&default),
        largest_mid_span_deflection(&fine),
    );
    assert!(
        (coarse - reference).abs() < 5e-3 * reference,
        "{coarse} vs {reference}"
    );
}

#[test]
fn crossings_on_roads_of_other_sample_grids_share_their_geometry_and_keep_their_histories() {
    // Three roads under one shared geometry: the wavy road, the same grid with other heights
    // (the road stencils reused), and a grid shifted and refined (the stencils recomputed).
    let (basis, wavy, options) = stepping_cases().swap_remove(1);
    let mut same_grid = wavy.clone();
    for h in same_grid
        .road
        .left
        .iter_mut()
        .chain(&mut same_grid.road.right)
    {
        *h *= -0.7;
    }
    let mut other_grid = wavy.clone();
    let road = &mut other_grid.road;
    (road.start, road.spacing) = (-10.013, 0.03);
    let count = 1700;
    let h = |x: f64| 0.003 * (1.3 * x).sin();
    road.left = (0..count).map(|i| h(-10.013 + i as f64 * 0.03)).collect();
    road.right = (0..count).map(|i| h(-10.0 + i as f64 * 0.03)).collect();
    let crossings = [wavy, same_grid, other_grid];
    let mut integrators: Vec<Integrator> = crossings
        .iter()
        .map(|c| Integrator::new(&basis, c, &options).unwrap())
        .collect();
    let mut geometry = integrators[0].new_step_geometry(true);
    while !integrators[0].is_finished() {
        for integrator in &mut integrators {
            integrator.step_sharing(&mut geometry).unwrap();
        }
    }
    for (integrator, crossing) in integrators.into_iter().zip(&crossings) {
        let alone = simulate(&basis, crossing, &options).unwrap();
        assert_eq!(
            history_bits(&integrator.finish().unwrap()),
            history_bits(&alone),
            "a shared run differs from its solo run"
        );
    }
}

#[test]
fn crossings_sharing_their_step_geometry_compute_it_once_per_instant_and_keep_their_histories() {
    // The light half-car over a 50 mm bump leaves the road; the same over a 5 mm bump keeps
    // other contact sets: the shared geometry must then serve two contact sets in one instant.
    let (basis, separating, options) = stepping_cases().swap_remove(0);
    let mut gentle = separating.clone();
    for h in &mut gentle.road.left {
        *h *= 0.1;
    }
    let crossings = [separating, gentle];
    let alone: Vec<ResponseHistory> = crossings
        .iter()
        .map(|c| simulate(&basis, c, &options).unwrap())
        .collect();
    assert_ne!(alone[0].contact_losses, alone[1].contact_losses);
    let mut integrators: Vec<Integrator> = crossings
        .iter()
        .map(|c| Integrator::new(&basis, c, &options).unwrap())
        .collect();
    assert!(integrators[0].can_share_geometry_with(&integrators[1]));
    let mut geometry = integrators[0].new_step_geometry(true);
    let mut instants = 0;
    while !integrators[0].is_finished() {
        for integrator in &mut integrators {
            integrator.step_sharing(&mut geometry).unwrap();
        }
        instants += 1;
    }
    assert_eq!(
        geometry.computations(),
        instants,
        "once per instant, not per crossing"
    );
    for (integrator, alone) in integrators.into_iter().zip(&alone) {
        assert!(
            integrator.finish().unwrap() == *alone,
            "a shared run differs from its solo run"
        );
    }
    // Another speed moves the tyres elsewhere: nothing to share.
    let slow = Crossing::new(half_car(), wavy_road(), 12.0);
    let fast = Crossing::new(half_car(), wavy_road(), 15.0);
    let slow = Integrator::new(&basis, &slow, &options).unwrap();
    let fast = Integrator::new(&basis, &fast, &options).unwrap();
    assert!(!slow.can_share_geometry_with(&fast));
}

/// Every recorded number of a history, as bits (so that −0 and +0, or two NaNs, compare as
/// what they are).
fn history_bits(history: &ResponseHistory) -> Vec<u64> {
    let series = [
        &history.front_axle_position,
        &history.contact_position,
        &history.modal_displacement,
        &history.modal_velocity,
        &history.modal_acceleration,
        &history.contact_force,
        &history.vehicle_displacement,
        &history.vehicle_acceleration,
    ];
    series
        .into_iter()
        .flat_map(|values| values.iter().map(|v| v.to_bits()))
        .collect()
}

#[test]
fn a_bridge_left_at_rest_on_the_approach_gives_the_computed_steps_bit_for_bit() {
    // The half car bounces over a 5 cm bump on a 40 m approach while the bridge rests, then
    // crosses; a second one follows. Steps that leave the resting bridge as it is must give
    // exactly the history of steps that compute it.
    let basis = beam_basis(10.0, 4, 0.02);
    let elevation: Vec<f64> = (0..2000)
        .map(|i| if (300..310).contains(&i) { 0.05 } else { 0.0 })
        .collect();
    let road = RoadProfile {
        highest_spatial_frequency: None,
        start: -60.0,
        spacing: 0.05,
        left: elevation.clone(),
        right: elevation,
    };
    let mut crossing = Crossing::new(half_car(), road, 12.0);
    crossing.vehicles[0].start_position = -40.0;
    crossing.vehicles.push(VehicleRun {
        start_position: -52.0,
        ..VehicleRun::forward(half_car(), 12.0)
    });
    crossing.free_vibration_duration = Some(0.2);
    let options = SolverOptions {
        time_step: Some(2.0e-3),
        ..SolverOptions::default()
    };
    let run = |shortcut: bool| {
        let mut integrator = Integrator::new(&basis, &crossing, &options).unwrap();
        if !shortcut {
            integrator = integrator.without_rest_shortcut();
        }
        let mut still_steps = 0;
        while !integrator.is_finished() {
            integrator.step().unwrap();
            still_steps += usize::from(integrator.bridge_left_at_rest());
        }
        (integrator.finish().unwrap(), still_steps)
    };
    let (shortcut, still_steps) = run(true);
    let (computed, _) = run(false);
    // Every step of the approach but the first two (the initial instant, and the computed step
    // that finds the state of rest unchanged), until the first axle reaches the deck.
    let approach_steps = (40.0 / 12.0 / 2.0e-3) as usize;
    assert!(
        (approach_steps - 2..=approach_steps).contains(&still_steps),
        "{still_steps} steps left the bridge at rest, of {approach_steps} on the approach"
    );
    assert!(history_bits(&shortcut) == history_bits(&computed));
    assert!(shortcut.modal_displacement.iter().any(|&q| q != 0.0));
}

/// Reference: the discrete frequency of Newmark's γ = ½ scheme for an undamped mode,
/// cos(Ω̄Δt) = 1 − x²/(2(1 + βx²)), x = ωΔt (Hughes 2000, §9.3; docs/theory.md,
/// "Period-matched modes"). The free vibration of one mode stepped by the solver's own predictor
/// and corrector satisfies u_{n+1} + u_{n−1} = 2 cos(Ω̄Δt) u_n: with the period-matched β the
/// measured Ω̄ is ω (within 1e-9 relative over 1 000 steps: round-off), with β = ¼ it is
/// 2 atan(x/2)/Δt, and above x = π/2 the mode keeps β = ¼.
#[test]
fn a_period_matched_mode_keeps_its_phase_where_average_acceleration_drifts() {
    use super::newmark::{NewmarkConstants, NewmarkState};
    let dt = 1.0e-3;
    for x in [0.005, 0.2, 1.2, 1.5, 2.0] {
        let omega = x / dt;
        for period_matched in [true, false] {
            let options = SolverOptions {
                period_matched_modes: period_matched,
                ..SolverOptions::default()
            };
            let beta = modal_newmark_beta(&options, dt, omega);
            let newmark = NewmarkConstants::new(0.25, 0.5, dt);
            let (beta_dt2, predictor) = ([beta * dt * dt], [dt * dt * (0.5 - beta)]);
            let mut state = NewmarkState::at_rest(vec![1.0]);
            state.acceleration[0] = -omega * omega;
            let mut u = vec![1.0];
            for _ in 0..1000 {
                state.predict_each(&newmark, &predictor, false);
                let (u_pred, _) = state.predicted();
                state.acceleration[0] =
                    -omega * omega * u_pred[0] / (1.0 + beta_dt2[0] * omega * omega);
                state.correct_each(&beta_dt2, newmark.gamma_dt);
                u.push(state.displacement[0]);
            }
            // Ω̄ from the three-term recurrence, at the instants where u is not near zero.
            let measured: Vec<f64> = (1..u.len() - 1)
                .filter(|&n| u[n].abs() > 0.3)
                .map(|n| {
                    ((u[n + 1] + u[n - 1]) / (2.0 * u[n]))
                        .clamp(-1.0, 1.0)
                        .acos()
                        / dt
                })
                .collect();
            let expected = if period_matched && x <= PERIOD_MATCHED_LIMIT {
                omega
            } else {
                2.0 * (x / 2.0).atan() / dt
            };
            for w in measured {
                assert!(
                    (w / expected - 1.0).abs() < 1e-9 * (1.0 + 1.0 / (x * x)),
                    "x = {x}, period matched {period_matched}: Ω̄ = {w} vs {expected}"
                );
            }
        }
    }
}
