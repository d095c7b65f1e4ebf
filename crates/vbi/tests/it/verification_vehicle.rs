//! Verification of the `vehicle` stage: assembly of M, C, K (paper Eq. 19), static wheel loads,
//! natural frequencies and the presets.

use vbi::units::GRAVITY;
use vbi::vehicle::{
    assemble, natural_modes, preset, presets, BodySpec, ContactKind, MotionKind, MultibodySpec,
    VehicleDescription, VehicleError, VehicleModel, VehicleSpec, PRESET_NAMES,
};

fn model(name: &str) -> (VehicleSpec, VehicleModel) {
    let spec = preset(name).unwrap_or_else(|| panic!("preset {name} exists"));
    let model = assemble(&spec).unwrap_or_else(|e| panic!("preset {name} assembles: {e}"));
    (spec, model)
}

fn multibody(spec: &VehicleSpec) -> &MultibodySpec {
    match &spec.description {
        VehicleDescription::Multibody(m) => m,
        VehicleDescription::MovingForces(_) => panic!("{} is not a multibody vehicle", spec.name),
    }
}

/// Largest absolute entry, to scale tolerances.
fn largest(m: &nalgebra::DMatrix<f64>) -> f64 {
    m.iter().fold(0.0_f64, |a, v| a.max(v.abs()))
}

#[test]
fn every_preset_has_symmetric_mass_damping_and_stiffness_and_positive_definite_mass() {
    // Reference: Lagrange's equations give symmetric M, C, K; the kinetic energy is positive,
    // so M is positive definite (paper Eq. 19).
    for spec in presets() {
        let m = assemble(&spec).unwrap();
        let n = m.dof_count();
        for (matrix, what) in [
            (&m.mass_matrix, "M"),
            (&m.damping_matrix, "C"),
            (&m.stiffness_matrix, "K"),
        ] {
            assert_eq!(matrix.shape(), (n, n), "{} {what}", spec.name);
            // Exact: assembly symmetrises; any asymmetry would be a bug, not round-off.
            assert_eq!(
                matrix,
                &matrix.transpose(),
                "{} {what} symmetric",
                spec.name
            );
        }
        if n > 0 {
            assert!(
                m.mass_matrix.clone().cholesky().is_some(),
                "{}: M positive definite",
                spec.name
            );
            assert!(
                m.stiffness_matrix.clone().cholesky().is_some(),
                "{}: K positive definite (statically stable)",
                spec.name
            );
        }
    }
}

#[test]
fn dof_counts_match_the_models_described() {
    // Reference: the paper §4.1 (15 DOF: 3 + 2 + 5 × 2 for the five-axle tractor–semitrailer);
    // Wang & Huang's HS20-44 model type: 3 + 2 + 3 × 2 = 11; VBI-2D: 1 (sprung mass) and
    // 4 (two-axle truck); the quarter car 2.
    for (name, dofs) in [
        ("moving-force", 0),
        ("moving-forces-hs20", 0),
        ("sprung-mass", 1),
        ("quarter-car", 2),
        ("two-axle-truck-vbi2d", 4),
        ("three-axle-truck-36t", 9),
        ("tractor-semitrailer-5axle", 15),
        ("hs20-44", 11),
    ] {
        assert_eq!(model(name).1.dof_count(), dofs, "{name}");
    }
    let (_, m) = model("tractor-semitrailer-5axle");
    assert_eq!(
        &m.dof_names[..5],
        [
            "tractor_bounce",
            "tractor_pitch",
            "tractor_roll",
            "semitrailer_pitch",
            "semitrailer_roll"
        ]
    );
    assert_eq!(m.contacts.len(), 10, "two wheels per axle");
    assert_eq!(PRESET_NAMES.len(), presets().len());
}

#[test]
fn static_wheel_loads_balance_the_weight_and_the_moments() {
    // Reference: statics of the whole vehicle (the hinge force is internal): Σ R = g Σ m,
    // Σ R·x = g Σ m·x about the front axle, Σ R·y = 0 (symmetric vehicles).
    for spec in presets() {
        let m = assemble(&spec).unwrap();
        let weight = spec.total_mass() * GRAVITY;
        // Round-off of a Cholesky solve of at most 15 unknowns: 1e-10 relative is ample.
        assert!(
            (m.total_static_load() - weight).abs() <= 1e-10 * weight,
            "{}: {} N against {} N",
            spec.name,
            m.total_static_load(),
            weight
        );
        let lateral: f64 = m
            .contacts
            .iter()
            .map(|c| c.static_load * c.lateral_offset)
            .sum();
        assert!(
            lateral.abs() <= 1e-10 * weight,
            "{}: Σ R·y = {lateral}",
            spec.name
        );
        let VehicleDescription::Multibody(body) = &spec.description else {
            continue;
        };
        let front = body.axles[0].longitudinal_position;
        let mut gravity_moment: f64 = body
            .bodies
            .iter()
            .map(|b| b.mass * GRAVITY * (b.longitudinal_position - front))
            .sum();
        for axle in &body.axles {
            if let Some(s) = &axle.suspension {
                gravity_moment += s.unsprung_mass * GRAVITY * (axle.longitudinal_position - front);
            }
        }
        let wheel_moment: f64 = m
            .contacts
            .iter()
            .map(|c| c.static_load * c.longitudinal_offset)
            .sum();
        // Moments of about 1e6 N·m; 1e-9 relative covers the round-off of the solve.
        assert!(
            (wheel_moment - gravity_moment).abs() <= 1e-9 * gravity_moment.abs().max(weight),
            "{}: Σ R·x = {wheel_moment}, g Σ m·x = {gravity_moment}",
            spec.name
        );
        assert!(
            m.contacts.iter().all(|c| c.static_load > 0.0),
            "{}",
            spec.name
        );
    }
}

#[test]
fn three_axle_truck_loads_follow_the_statics_of_a_rigid_body_on_three_springs() {
    // Reference: closed-form statics of a rigid body on three springs in series (suspension and
    // tyres, per axle k_i = 2k_s·2k_t / (2k_s + 2k_t)), which is statically indeterminate. The
    // unsprung weight W_u,i settles axle i by e_i = W_u,i / (2k_t) more, so the body force at
    // axle i is F_i = −k_i (z + θ a_i + e_i) with a_i = x_i − x_cg, and
    //   [Σk   Σk·a ] [z]   [−W − Σk·e ]
    //   [Σk·a Σk·a²] [θ] = [   − Σk·a·e],  axle load_i = F_i + W_u,i.
    let (spec, m) = model("three-axle-truck-36t");
    let body = multibody(&spec);
    let truck = &body.bodies[0];
    let weight = truck.mass * GRAVITY;
    let k: Vec<f64> = body
        .axles
        .iter()
        .map(|a| {
            let s = a.suspension.as_ref().unwrap();
            let (ks, kt) = (2.0 * s.stiffness, 2.0 * a.tyre_stiffness);
            ks * kt / (ks + kt)
        })
        .collect();
    let unsprung_weight: Vec<f64> = body
        .axles
        .iter()
        .map(|a| a.suspension.as_ref().unwrap().unsprung_mass * GRAVITY)
        .collect();
    let settlement: Vec<f64> = body
        .axles
        .iter()
        .zip(&unsprung_weight)
        .map(|(a, w)| w / (2.0 * a.tyre_stiffness))
        .collect();
    let arm: Vec<f64> = body
        .axles
        .iter()
        .map(|a| a.longitudinal_position - truck.longitudinal_position)
        .collect();
    let s0: f64 = k.iter().sum();
    let s1: f64 = k.iter().zip(&arm).map(|(k, a)| k * a).sum();
    let s2: f64 = k.iter().zip(&arm).map(|(k, a)| k * a * a).sum();
    let r0 = -weight - (0..3).map(|i| k[i] * settlement[i]).sum::<f64>();
    let r1 = -(0..3).map(|i| k[i] * arm[i] * settlement[i]).sum::<f64>();
    let determinant = s0 * s2 - s1 * s1;
    let z = (r0 * s2 - r1 * s1) / determinant;
    let theta = (s0 * r1 - s1 * r0) / determinant;
    for i in 0..body.axles.len() {
        let expected = -k[i] * (z + theta * arm[i] + settlement[i]) + unsprung_weight[i];
        let computed = m.contacts[2 * i].static_load + m.contacts[2 * i + 1].static_load;
        // Same linear statics by two routes: round-off only.
        assert!(
            (computed - expected).abs() <= 1e-9 * expected,
            "axle {}: {computed} N against {expected} N",
            i + 1
        );
    }
    // Not an equal split: the steer axle carries about 8 t, each rear axle about 14 t.
    let front = m.contacts[0].static_load + m.contacts[1].static_load;
    assert!(
        (front / GRAVITY - 7_964.0).abs() < 5.0,
        "{}",
        front / GRAVITY
    );
}

#[test]
fn hs20_44_static_axle_loads_are_the_aashto_loads() {
    // Reference: AASHTO HS20-44 axle loads 8, 32, 32 kip (1 kip = 4448.2216 N); the
    // tractor–semitrailer is statically determinate, so they hold whatever the springs.
    let (_, m) = model("hs20-44");
    let kip = 4_448.221_615_260_5;
    for (axle, kips) in [8.0, 32.0, 32.0].iter().enumerate() {
        let load = m.contacts[2 * axle].static_load + m.contacts[2 * axle + 1].static_load;
        // Round-off only.
        assert!(
            (load - kips * kip).abs() < 1e-6 * kips * kip,
            "axle {axle}: {load} N"
        );
        // Left and right wheels share the axle load equally (a symmetric vehicle).
        assert!((m.contacts[2 * axle].static_load - load / 2.0).abs() < 1e-6 * load);
    }
    assert!((m.contacts[2].longitudinal_offset + 14.0 * 0.3048).abs() < 1e-12);
    assert!(
        (m.contacts[0].lateral_offset - 3.0 * 0.3048).abs() < 1e-12,
        "6 ft track, left +"
    );
}

#[test]
fn quarter_car_frequencies_match_the_closed_form() {
    // Reference: closed form of the two-mass oscillator,
    //   m_s m_u ω⁴ − (m_s (k_s + k_t) + m_u k_s) ω² + k_s k_t = 0.
    let (spec, m) = model("quarter-car");
    let body = multibody(&spec);
    let ms = body.bodies[0].mass;
    let axle = &body.axles[0];
    let s = axle.suspension.as_ref().unwrap();
    let (mu, ks, kt) = (s.unsprung_mass, s.stiffness, axle.tyre_stiffness);
    let b = ms * (ks + kt) + mu * ks;
    let discriminant = (b * b - 4.0 * ms * mu * ks * kt).sqrt();
    let expected = [
        ((b - discriminant) / (2.0 * ms * mu)).sqrt() / (2.0 * std::f64::consts::PI),
        ((b + discriminant) / (2.0 * ms * mu)).sqrt() / (2.0 * std::f64::consts::PI),
    ];
    let modes = natural_modes(&m).unwrap();
    for (mode, f) in modes.iter().zip(expected) {
        // A dense 2×2 symmetric eigensolve: round-off only.
        assert!(
            (mode.frequency_hz - f).abs() < 1e-10 * f,
            "{} against {f}",
            mode.frequency_hz
        );
    }
    assert_eq!(modes[0].motion, MotionKind::BodyBounce);
    assert_eq!(modes[1].motion, MotionKind::AxleHop);
}

#[test]
fn sprung_mass_frequency_is_the_vbi2d_single_oscillator() {
    // Reference: docs/verification.md §9, m = 5750 kg on k = 1.595e6 N/m:
    // f = √(k/m)/2π = 2.6507 Hz.
    let (_, m) = model("sprung-mass");
    let f = natural_modes(&m).unwrap()[0].frequency_hz;
    let expected = (1.595e6_f64 / 5750.0).sqrt() / (2.0 * std::f64::consts::PI);
    assert!((f - expected).abs() < 1e-12 * expected, "{f}");
    assert_eq!(m.damping_matrix[(0, 0)], 0.0, "c = 0");
    match &m.contacts[0].kind {
        ContactKind::Tyre {
            stiffness,
            coupling,
            ..
        } => {
            assert_eq!(*stiffness, 1.595e6);
            assert_eq!(coupling, &vec![(0, 1.0)]);
        }
        ContactKind::Force => panic!("a sprung mass has a tyre"),
    }
}

#[test]
fn vbi2d_truck_frequencies_split_into_two_quarter_cars() {
    // Reference: closed form. The VBI-2D truck (docs/verification.md §9) is symmetric
    // about its centre of mass, so bounce (in-phase axles) is a quarter car with sprung mass
    // m/2, and pitch (anti-phase axles) a quarter car with sprung mass I/(2a²), a = 2.5 m.
    let (_, m) = model("two-axle-truck-vbi2d");
    let quarter = |ms: f64| -> [f64; 2] {
        let (mu, ks, kt) = (900.0, 6.0e6, 1.75e6);
        let b = ms * (ks + kt) + mu * ks;
        let d = (b * b - 4.0 * ms * mu * ks * kt).sqrt();
        [(b - d) / (2.0 * ms * mu), (b + d) / (2.0 * ms * mu)]
            .map(|w2: f64| w2.sqrt() / (2.0 * std::f64::consts::PI))
    };
    let [bounce, hop_in_phase] = quarter(10_500.0 / 2.0);
    let [pitch, hop_anti_phase] = quarter(5.0e4 / (2.0 * 2.5 * 2.5));
    let mut expected = [bounce, pitch, hop_in_phase, hop_anti_phase];
    expected.sort_by(f64::total_cmp);
    let modes = natural_modes(&m).unwrap();
    for (mode, f) in modes.iter().zip(expected) {
        // 4×4 dense symmetric eigensolve: round-off only.
        assert!(
            (mode.frequency_hz - f).abs() < 1e-9 * f,
            "{} against {f}",
            mode.frequency_hz
        );
    }
    assert_eq!(modes[0].motion, MotionKind::BodyBounce);
    assert_eq!(modes[1].motion, MotionKind::BodyPitch);
    // Static loads: symmetric, (10500/2 + 900) kg per axle.
    for c in &m.contacts {
        assert!((c.static_load - 6150.0 * GRAVITY).abs() < 1e-8 * c.static_load);
    }
}

#[test]
fn every_tyre_displaced_equally_gives_a_pure_bounce() {
    // Reference: rigid-body kinematics. Lifting every tyre base by r lifts the whole vehicle by
    // r without pitch or roll: K q = Σ_wheels k_t r c_w has the solution q = r on every bounce
    // DOF and 0 on every pitch and roll DOF (articulated bodies follow through the hinge).
    let r = 0.01;
    for spec in presets() {
        let m = assemble(&spec).unwrap();
        let n = m.dof_count();
        if n == 0 {
            continue;
        }
        let mut load = nalgebra::DVector::<f64>::zeros(n);
        for c in &m.contacts {
            if let ContactKind::Tyre {
                stiffness,
                coupling,
                ..
            } = &c.kind
            {
                for &(i, coefficient) in coupling {
                    load[i] += stiffness * r * coefficient;
                }
            }
        }
        let q = m.stiffness_matrix.clone().cholesky().unwrap().solve(&load);
        for (name, value) in m.dof_names.iter().zip(q.iter()) {
            let expected = if name.ends_with("_bounce") { r } else { 0.0 };
            // Condition number of K below 1e4 for these vehicles: 1e-9 r is round-off.
            assert!(
                (value - expected).abs() < 1e-9 * r,
                "{}: {name} = {value}, expected {expected}",
                spec.name
            );
        }
        // And every wheel rises by r.
        for c in &m.contacts {
            if let ContactKind::Tyre { coupling, .. } = &c.kind {
                let w: f64 = coupling.iter().map(|&(i, a)| a * q[i]).sum();
                assert!((w - r).abs() < 1e-9 * r, "{}: wheel rises {w}", spec.name);
            }
        }
    }
}

#[test]
fn wheel_couplings_follow_axle_bounce_and_roll_with_left_positive() {
    // Reference: kinematics of a rigid axle, w = z_a ± (track/2) φ_a (left positive).
    let (spec, m) = model("three-axle-truck-36t");
    let track = multibody(&spec).axles[0].track;
    let roll = m.dof_names.iter().position(|n| n == "axle1_roll").unwrap();
    let bounce = m
        .dof_names
        .iter()
        .position(|n| n == "axle1_bounce")
        .unwrap();
    let coupling = |k: usize| match &m.contacts[k].kind {
        ContactKind::Tyre { coupling, .. } => coupling.clone(),
        ContactKind::Force => unreachable!(),
    };
    assert_eq!(coupling(0), vec![(bounce, 1.0), (roll, track / 2.0)]);
    assert_eq!(coupling(1), vec![(bounce, 1.0), (roll, -track / 2.0)]);
    assert!(m.contacts[0].lateral_offset > 0.0 && m.contacts[1].lateral_offset < 0.0);
    // Front to back, offsets relative to the front axle.
    assert_eq!(m.contacts[0].longitudinal_offset, 0.0);
    assert!(m
        .contacts
        .windows(2)
        .all(|w| w[1].longitudinal_offset <= w[0].longitudinal_offset));
}

#[test]
fn truck_presets_bounce_at_1_5_to_3_hz_and_hop_at_8_to_15_hz() {
    // Reference: the usual ranges of heavy vehicles (body bounce 1.5–3 Hz, axle hop 8–15 Hz),
    // the check a user makes before trusting a vehicle (issue 4). The VBI-2D truck is left out
    // of the hop check: its published stiff suspension (6e6 N/m) puts its axle hop at 15.5 to
    // 15.8 Hz.
    for name in [
        "three-axle-truck-36t",
        "tractor-semitrailer-5axle",
        "hs20-44",
        "quarter-car",
        "two-axle-truck-vbi2d",
    ] {
        let (_, m) = model(name);
        let modes = natural_modes(&m).unwrap();
        let bounce: Vec<f64> = modes
            .iter()
            .filter(|m| m.motion == MotionKind::BodyBounce)
            .map(|m| m.frequency_hz)
            .collect();
        assert!(!bounce.is_empty(), "{name} has a bounce mode");
        assert!(
            bounce.iter().all(|f| (1.5..=3.0).contains(f)),
            "{name}: bounce {bounce:?}"
        );
        if name != "two-axle-truck-vbi2d" {
            let hop: Vec<f64> = modes
                .iter()
                .filter(|m| m.motion == MotionKind::AxleHop)
                .map(|m| m.frequency_hz)
                .collect();
            assert!(!hop.is_empty(), "{name} has hop modes");
            assert!(
                hop.iter().all(|f| (8.0..=15.0).contains(f)),
                "{name}: hop {hop:?}"
            );
        }
    }
}

#[test]
fn natural_modes_are_mass_normalised_eigenvectors() {
    // Reference: K φ = ω² M φ with φᵀ M φ = 1 (generalised symmetric eigenproblem).
    let (_, m) = model("tractor-semitrailer-5axle");
    for mode in natural_modes(&m).unwrap() {
        let phi = nalgebra::DVector::from_vec(mode.shape.clone());
        let omega2 = (2.0 * std::f64::consts::PI * mode.frequency_hz).powi(2);
        let residual = &m.stiffness_matrix * &phi - &m.mass_matrix * &phi * omega2;
        let scale = largest(&m.stiffness_matrix) * phi.amax();
        // Round-off of a 15×15 eigensolve scaled by ‖K‖: 1e-10 relative.
        assert!(residual.amax() < 1e-10 * scale, "{}", residual.amax());
        let modal_mass = phi.dot(&(&m.mass_matrix * &phi));
        assert!((modal_mass - 1.0).abs() < 1e-10, "{modal_mass}");
    }
}

#[test]
fn moving_forces_have_no_dofs_and_split_axle_loads_over_the_wheels() {
    // Reference: AASHTO HS20-44 axle loads 8, 32, 32 kip at 14 ft spacing, wheels 6 ft apart.
    let (_, m) = model("moving-forces-hs20");
    assert_eq!(m.dof_count(), 0);
    assert_eq!(m.contacts.len(), 6);
    assert!(m.contacts.iter().all(|c| c.kind == ContactKind::Force));
    let kip = 4_448.221_615_260_5;
    assert!((m.total_static_load() - 72.0 * kip).abs() < 1e-6);
    assert!((m.contacts[0].static_load - 4.0 * kip).abs() < 1e-9);
    assert!(natural_modes(&m).unwrap().is_empty());
}

#[test]
fn invalid_descriptions_are_rejected_with_the_offending_numbers() {
    let mut spec = preset("three-axle-truck-36t").unwrap();
    let VehicleDescription::Multibody(body) = &mut spec.description else {
        unreachable!()
    };
    body.axles[2].suspension.as_mut().unwrap().unsprung_mass = -5.0;
    assert_eq!(
        assemble(&spec).unwrap_err(),
        VehicleError::NotPositive {
            quantity: "axle 3 unsprung mass".into(),
            value: -5.0
        }
    );

    let mut spec = preset("three-axle-truck-36t").unwrap();
    let VehicleDescription::Multibody(body) = &mut spec.description else {
        unreachable!()
    };
    body.axles[1].track = 3.0;
    assert!(matches!(
        assemble(&spec).unwrap_err(),
        VehicleError::WiderThanBody { axle: 2, value, width, .. } if value == 3.0 && width == 2.5
    ));

    // A body with a pitch DOF on a single axle is a mechanism.
    let mut spec = preset("quarter-car").unwrap();
    let VehicleDescription::Multibody(body) = &mut spec.description else {
        unreachable!()
    };
    body.bodies[0].pitch_inertia = Some(1.0e3);
    assert_eq!(assemble(&spec).unwrap_err(), VehicleError::Unstable);

    let mut spec = preset("two-axle-truck-vbi2d").unwrap();
    let VehicleDescription::Multibody(body) = &mut spec.description else {
        unreachable!()
    };
    body.axles.swap(0, 1);
    assert!(matches!(
        assemble(&spec).unwrap_err(),
        VehicleError::AxlesOutOfOrder { axle: 2, .. }
    ));

    let mut spec = preset("hs20-44").unwrap();
    let VehicleDescription::Multibody(body) = &mut spec.description else {
        unreachable!()
    };
    body.bodies.push(BodySpec {
        name: "axle7".into(),
        ..body.bodies[0].clone()
    });
    assert!(matches!(
        assemble(&spec).unwrap_err(),
        VehicleError::BadBodyName { .. }
    ));
}
