//! Verification of the station forces: shear force and support reaction (issue 12, item 4).
//!
//! - Static: the influence lines of the reactions and of a shear force of a two-span continuous
//!   beam against the closed form of the three-moment equation (docs/verification.md §23.1);
//!   the direct solve K u = f against the influence lines (reciprocity); on the paper's
//!   grillage, the vertical and moment equilibrium of the reactions for loads anywhere on the
//!   deck (§23.2).
//! - Dynamic: the static-corrected reaction and shear histories of a crossing balance the
//!   contact forces and the bridge's inertia and damping forces at every step (§23.3): whole
//!   bridge, Σ R = Σ P + ∫ m̄ (ẅ + damping) dx, and the part left of a shear station,
//!   V = R_A − Σ P_left − ∫₀ˣ m̄ (ẅ + damping) dx, with the integrals of the mode shapes taken
//!   independently of the reaction rows (Hermite integrals of the deck fields).

use vbi::analysis::{analyse, corrected_station_responses, AnalysisOptions};
use vbi::fe::statics::{influence_lines, static_response};
use vbi::fe::{discretise, FeModel, MeshOptions, StationRequest};
use vbi::modal::{solve_modes, ModalBasis, ModalOptions, Quantity, StationTarget};
use vbi::model::{paper_bridge, BeamSection, BridgeModel, ContinuousBeam};
use vbi::road::RoadProfile;
use vbi::solver::{simulate, Crossing, SolverOptions};
use vbi::vehicle::{ContactKind, TyreContact, VehicleModel};

const SPAN: f64 = 20.0;
const EI: f64 = 4.86535e10;
const MASS_PER_LENGTH: f64 = 18358.0;
const SHEAR_STATION: f64 = 7.0;

fn request(name: &str, position: f64) -> StationRequest {
    StationRequest {
        name: Some(name.into()),
        position,
        target: StationTarget::Section,
    }
}

/// Two equal pinned spans of 20 m, 0.5 m elements; stations: the default ones (span
/// mid-points, the middle support `support2_section`) and `A` (x = 0), `V7` (x = 7 m), `C`
/// (x = 40 m).
fn two_span_beam(damping_ratio: f64) -> FeModel {
    let mut beam = ContinuousBeam::pinned(
        vec![SPAN; 2],
        BeamSection {
            flexural_rigidity: EI,
            mass_per_length: MASS_PER_LENGTH,
        },
    );
    beam.damping_ratio = damping_ratio;
    let mesh = MeshOptions {
        element_length: 0.5,
        stations: vec![
            request("A", 0.0),
            request("V7", SHEAR_STATION),
            request("C", 2.0 * SPAN),
        ],
        ..MeshOptions::default()
    };
    discretise(&BridgeModel::ContinuousBeam(beam), &mesh).unwrap()
}

fn station(stations: &[vbi::modal::Station], name: &str) -> usize {
    stations.iter().position(|s| s.name == name).unwrap()
}

/// Reactions (R_A, R_B, R_C) of two equal spans l under a unit downward load at a, upward
/// positive: three-moment equation, M_B = −a′(l² − a′²)/(4l²) with a′ the distance from the
/// nearer end support; the loaded span's end reaction (l − a′ + M_B)/l, the other M_B/l, and
/// R_B = 1 − R_A − R_C.
fn two_span_reactions(l: f64, a: f64) -> [f64; 3] {
    let near = if a <= l { a } else { 2.0 * l - a };
    let hogging = -near * (l * l - near * near) / (4.0 * l * l);
    let loaded = (l - near + hogging) / l;
    let other = hogging / l;
    let (ra, rc) = if a <= l {
        (loaded, other)
    } else {
        (other, loaded)
    };
    [ra, 1.0 - ra - rc, rc]
}

/// Load positions along the beam: on nodes, inside elements (next to the supports too), at
/// and either side of the shear station.
const LOAD_POSITIONS: [f64; 13] = [
    0.0, 0.13, 0.37, 3.3, 6.9, 7.0, 7.1, 19.8, 20.0, 20.3, 28.45, 39.9, 40.0,
];

#[test]
fn two_span_reaction_and_shear_influence_lines_match_the_three_moment_closed_form() {
    let fe = two_span_beam(0.0);
    let lines = influence_lines(&fe).unwrap();
    let [a, b, c, v] = ["A", "support2_section", "C", "V7"].map(|n| station(&fe.stations, n));
    for s in [a, b, c] {
        assert!(
            fe.stations[s].support,
            "{} is a support",
            fe.stations[s].name
        );
        assert_eq!(fe.stations[s].force_quantity(), Quantity::SupportReaction);
    }
    assert_eq!(fe.stations[v].force_quantity(), Quantity::ShearForce);
    let mut worst = 0.0f64;
    for &x in &LOAD_POSITIONS {
        let exact = two_span_reactions(SPAN, x);
        for (s, exact) in [a, b, c].into_iter().zip(exact) {
            let got = lines.unit_load_response(s, Quantity::SupportReaction, x, 0.0);
            worst = worst.max((got - exact).abs());
        }
        // V(7 m) = R_A − (the load if it is left of the section).
        let left = if x < SHEAR_STATION { 1.0 } else { 0.0 };
        let got = lines.unit_load_response(v, Quantity::ShearForce, x, 0.0);
        worst = worst.max((got - (exact[0] - left)).abs());
        // A quantity a station does not have reads zero.
        assert_eq!(
            lines.unit_load_response(v, Quantity::SupportReaction, x, 0.0),
            0.0
        );
    }
    // Hermite elements give exact nodal statics and the influence lines are cubic between
    // nodes: what is left is the round-off of the solve (κ(K) ε ≈ 1e-10 here).
    assert!(worst < 1e-9, "largest error {worst:e} (unit load)");
}

#[test]
fn direct_static_solve_gives_the_forces_of_the_influence_lines() {
    // Two independent routes: K u = f per load with the reaction's direct share, against the
    // reciprocal (Maxwell–Betti) influence fields.
    let fe = two_span_beam(0.0);
    let lines = influence_lines(&fe).unwrap();
    let loads = [
        (3.3, 0.0, 120e3),
        (19.8, 0.0, 80e3),
        (20.0, 0.0, 50e3),
        (33.0, 0.0, 60e3),
    ];
    let response = static_response(&fe, &loads).unwrap();
    for (s, station) in fe.stations.iter().enumerate() {
        let quantity = station.force_quantity();
        let expected: f64 = loads
            .iter()
            .map(|&(x, y, p)| p * lines.unit_load_response(s, quantity, x, y))
            .sum();
        assert!(
            (response.force[s] - expected).abs() <= 1e-9 * 310e3,
            "{}: {} vs {expected}",
            station.name,
            response.force[s]
        );
    }
    // Vertical equilibrium of the direct solve: the three reactions carry the 310 kN.
    let total: f64 = ["A", "support2_section", "C"]
        .map(|n| response.force[station(&fe.stations, n)])
        .iter()
        .sum();
    assert!((total - 310e3).abs() <= 1e-9 * 310e3, "Σ R = {total}");
}

#[test]
fn grillage_reactions_balance_any_load_vertically_and_in_moment() {
    // The paper's 2 × 20 m grillage with section stations at both end supports: for a unit load
    // anywhere on the deck (on a girder or between girders, on nodes or inside elements),
    // Σ R_s = 1 and Σ x_s R_s = x (moments about the first support line).
    let model = paper_bridge(2, 20.0);
    let mesh = MeshOptions {
        stations: vec![request("A", 0.0), request("C", 40.0)],
        ..MeshOptions::default()
    };
    let fe = discretise(&model, &mesh).unwrap();
    let lines = influence_lines(&fe).unwrap();
    let supports: Vec<usize> = ["A", "support2_section", "C"]
        .map(|n| station(&fe.stations, n))
        .to_vec();
    let mut worst = 0.0f64;
    for &x in &[0.0, 0.4, 5.25, 10.0, 19.7, 20.0, 27.3, 39.6, 40.0] {
        for &y in &[-3.1, -1.0, 0.0, 0.7, 2.9] {
            let reactions: Vec<f64> = supports
                .iter()
                .map(|&s| lines.unit_load_response(s, Quantity::SupportReaction, x, y))
                .collect();
            let vertical: f64 = reactions.iter().sum();
            let moment: f64 = supports
                .iter()
                .zip(&reactions)
                .map(|(&s, r)| fe.stations[s].position * r)
                .sum();
            worst = worst
                .max((vertical - 1.0).abs())
                .max((moment - x).abs() / 40.0);
        }
    }
    // Round-off of about 20 000 DOFs' solves: 1e-8 of the unit load.
    assert!(worst < 1e-8, "largest equilibrium error {worst:e}");
}

#[test]
fn the_moment_at_an_end_free_to_rotate_is_zero_for_any_load() {
    // Equilibrium of the end node: with no rotational restraint the girder's end moment
    // balances the members meeting there (none on a beam; on the grillage the end slab strip,
    // whose torsion moments sum to zero over the section). Read from the first element's end
    // force instead, a load inside that element would give a spurious moment (its fixed-end
    // moment).
    let beam = two_span_beam(0.0);
    let beam_lines = influence_lines(&beam).unwrap();
    let grillage = discretise(
        &paper_bridge(2, 20.0),
        &MeshOptions {
            stations: vec![request("A", 0.0), request("C", 40.0)],
            ..MeshOptions::default()
        },
    )
    .unwrap();
    let grillage_lines = influence_lines(&grillage).unwrap();
    let mut worst = 0.0f64;
    for &x in &[0.0, 0.13, 0.5, 0.87, 1.0, 5.0, 20.0, 39.2, 39.9, 40.0] {
        for (lines, stations, y) in [
            (&beam_lines, &beam.stations, 0.0),
            (&grillage_lines, &grillage.stations, 1.3),
        ] {
            for name in ["A", "C"] {
                let s = station(stations, name);
                let m = lines.unit_load_response(s, Quantity::BendingMoment, x, y);
                worst = worst.max(m.abs());
            }
        }
    }
    // Round-off of moments of the order of the span (N·m per N): 1e-9 m.
    assert!(worst < 1e-9, "largest end moment {worst:e} N·m per N");
}

/// ∫ φₖ dx over [0, x_end] of every mode of a one-line deck, exactly for the Hermite cubic
/// between nodes: h/2 (w₀ + w₁) + h²/12 (w₀′ − w₁′) per element.
fn shape_integrals(basis: &ModalBasis, x_end: f64) -> Vec<f64> {
    let n = basis.mode_count();
    let xs = &basis.deck.lines[0].node_positions;
    let mut out = vec![0.0; n];
    for e in 0..xs.len() - 1 {
        if xs[e + 1] > x_end + 1e-12 {
            break;
        }
        let h = xs[e + 1] - xs[e];
        for (k, value) in out.iter_mut().enumerate() {
            let (w0, w1) = (
                basis.deck_deflection[e * n + k],
                basis.deck_deflection[(e + 1) * n + k],
            );
            let (s0, s1) = (
                basis.deck_slope[e * n + k],
                basis.deck_slope[(e + 1) * n + k],
            );
            *value += h / 2.0 * (w0 + w1) + h * h / 12.0 * (s0 - s1);
        }
    }
    out
}

#[test]
fn reaction_and_shear_histories_balance_contact_and_inertia_forces_at_every_step() {
    let damping = 0.02;
    let fe = two_span_beam(damping);
    let lines = influence_lines(&fe).unwrap();
    let basis = solve_modes(
        &fe,
        &ModalOptions {
            mode_count: 10,
            ..ModalOptions::default()
        },
    )
    .unwrap();
    // A two-axle moving load, 100 kN and 60 kN, 4 m apart, at 80 km/h.
    let axle = |offset: f64, load: f64| TyreContact {
        longitudinal_offset: offset,
        lateral_offset: 0.0,
        static_load: load,
        kind: ContactKind::Force,
    };
    let vehicle = VehicleModel {
        name: "two_axle_force".into(),
        dof_names: Vec::new(),
        mass_matrix: nalgebra::DMatrix::zeros(0, 0),
        damping_matrix: nalgebra::DMatrix::zeros(0, 0),
        stiffness_matrix: nalgebra::DMatrix::zeros(0, 0),
        contacts: vec![axle(0.0, 100e3), axle(-4.0, 60e3)],
        pitch_load_per_acceleration: Vec::new(),
    };
    let crossing = Crossing::new(vehicle, RoadProfile::smooth(-10.0, 55.0), 80.0 / 3.6);
    let options = SolverOptions {
        time_step: Some(1e-3),
        ..SolverOptions::default()
    };
    let history = simulate(&basis, &crossing, &options).unwrap();
    let corrected = corrected_station_responses(&basis, &lines, &history)
        .unwrap()
        .expect("a correction exists");
    let series = |name: &str, quantity: Quantity| -> &Vec<f64> {
        let s = station(&basis.stations, name);
        &corrected[s].iter().find(|(q, _)| *q == quantity).unwrap().1
    };
    let reactions = ["A", "support2_section", "C"].map(|n| series(n, Quantity::SupportReaction));
    let shear = series("V7", Quantity::ShearForce);
    let whole = shape_integrals(&basis, 2.0 * SPAN);
    let left = shape_integrals(&basis, SHEAR_STATION);
    let n = basis.mode_count();
    let contacts = history.contacts.len();
    let mut worst = [0.0f64; 2];
    let mut loaded_steps = 0;
    for i in 0..history.step_count {
        // Inertia and damping: ∫ m̄ Σₖ φₖ (q̈ₖ + 2ζₖωₖq̇ₖ) dx over the span of interest.
        let modal = |integrals: &[f64]| -> f64 {
            (0..n)
                .map(|k| {
                    let mode = &basis.modes[k];
                    let a = history.modal_acceleration[i * n + k]
                        + 2.0
                            * mode.damping_ratio
                            * mode.circular_frequency
                            * history.modal_velocity[i * n + k];
                    MASS_PER_LENGTH * integrals[k] * a
                })
                .sum()
        };
        let (mut on_deck, mut left_of_station) = (0.0, 0.0);
        for (w, contact) in history.contacts.iter().enumerate() {
            let x = history.contact_position[i * contacts + w];
            if basis.deck.stencil(x, contact.lateral_position).is_empty() {
                continue;
            }
            let p = history.contact_force[i * contacts + w];
            on_deck += p;
            if x < SHEAR_STATION {
                left_of_station += p;
            }
        }
        if on_deck > 0.0 {
            loaded_steps += 1;
        }
        let total: f64 = reactions.iter().map(|r| r[i]).sum();
        worst[0] = worst[0].max((total - (on_deck + modal(&whole))).abs());
        let expected_shear = reactions[0][i] - left_of_station - modal(&left);
        worst[1] = worst[1].max((shear[i] - expected_shear).abs());
    }
    assert!(
        loaded_steps > 1000,
        "{loaded_steps} steps with a load on the deck"
    );
    // Each side sums ten modal terms of up to the reaction's size and the contact loads:
    // round-off, 1e-9 of the 160 kN carried.
    assert!(
        worst[0] < 1e-9 * 160e3,
        "Σ R equilibrium error {:e} N",
        worst[0]
    );
    assert!(
        worst[1] < 1e-9 * 160e3,
        "shear equilibrium error {:e} N",
        worst[1]
    );

    // The report gives the forces' DAFs beside deflection and moment, and a study's scope
    // (the RDM station only) leaves them out.
    let report = analyse(&basis, &lines, &history, &AnalysisOptions::default()).unwrap();
    let b = station(&basis.stations, "support2_section");
    let reaction = report.entry(b, Quantity::SupportReaction).unwrap();
    assert!(reaction.static_max > 100e3 && reaction.converged.daf.is_some());
    let v = station(&basis.stations, "V7");
    assert!(report
        .entry(v, Quantity::ShearForce)
        .unwrap()
        .converged
        .daf
        .is_some());
    assert!(report.entry(v, Quantity::SupportReaction).is_none());
}
