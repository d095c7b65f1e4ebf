//! Verification of the grillage's real-deck features (issue 15 item 4): elastic and rotational
//! bearings against the closed forms of a beam on springs, the girder shapes and given
//! properties against each other, the barriers' masses against rigid-body kinetic energy, and
//! the bound that releasing a restraint never raises a frequency (Courant–Fischer minimax).

use vbi::fe::statics::static_response;
use vbi::fe::{discretise, FeError, FeModel, MeshOptions};
use vbi::modal::{solve_modes, ModalOptions, ModeKind};
use vbi::model::{
    paper_bridge, Barriers, BeamSection, Bearing, BridgeModel, ContinuousBeam, Diaphragm,
    GirderShape, GivenSection, Grillage, IntermediateDiaphragms, LateralRestraint, SupportKind,
};

fn grillage(span_count: usize, span_length: f64) -> Grillage {
    let BridgeModel::Grillage(g) = paper_bridge(span_count, span_length) else {
        panic!("the paper bridge is a grillage")
    };
    g
}

/// One girder of the paper's 20 m bridge on one span.
fn single_girder() -> Grillage {
    let mut g = grillage(1, 20.0);
    g.girder_count = 1;
    g.deck_width = 2.9;
    g.lateral_restraint = LateralRestraint::AllSupports;
    g
}

fn fe(g: &Grillage) -> FeModel {
    discretise(&BridgeModel::Grillage(g.clone()), &MeshOptions::default()).unwrap()
}

/// Mid-span deflection [m, up] and sagging moment [N·m] under a load P at mid-span.
fn mid_span_response(model: &FeModel, load: f64) -> (f64, f64) {
    let length = model.deck.length;
    let station = model
        .stations
        .iter()
        .position(|s| s.name == "span1_mid_section")
        .expect("the default mid-span station");
    let response = static_response(model, &[(length / 2.0, 0.0, load)]).unwrap();
    (response.deflection[station], response.moment[station])
}

/// The lowest 8 frequencies of a grillage [Hz].
fn lowest_frequencies(g: &Grillage) -> Vec<f64> {
    solve_modes(
        &fe(g),
        &ModalOptions {
            mode_count: 8,
            ..ModalOptions::default()
        },
    )
    .unwrap()
    .modes
    .iter()
    .map(|m| m.frequency_hz())
    .collect()
}

fn flexural_rigidity(g: &Grillage) -> f64 {
    g.material.elastic_modulus * g.girder_section(0).unwrap().second_moment_y
}

#[test]
fn a_girder_on_elastic_bearings_deflects_by_the_beam_plus_the_springs_closed_form() {
    // Reference: a simply supported beam on two springs k under P at mid-span:
    // δ = PL³/(48EI) + P/(2k) (statics; exact at a node for Hermite elements).
    let mut g = single_girder();
    let k = 2.0e8;
    g.bearings = vec![
        Bearing {
            vertical_stiffness: Some(k),
            ..Bearing::default()
        };
        2
    ];
    let (p, l, ei): (f64, f64, f64) = (1.0e5, 20.0, flexural_rigidity(&g));
    let (deflection, moment) = mid_span_response(&fe(&g), p);
    let expected = p * l.powi(3) / (48.0 * ei) + p / (2.0 * k);
    assert!(
        (-deflection - expected).abs() < 1e-9 * expected,
        "{deflection} vs {expected}"
    );
    assert!((moment - p * l / 4.0).abs() < 1e-9 * p * l);
}

#[test]
fn rotational_bearing_springs_give_the_closed_form_end_moment_and_deflection() {
    // Reference: end springs k_r on a simply supported beam under P at mid-span. The free
    // beam's end rotation θ0 = PL²/(16EI); symmetric end moments M rotate the ends back by
    // ML/(2EI), and M = k_r θ gives M = k_r θ0 / (1 + k_r L/(2EI)). Then
    // δ = PL³/(48EI) − ML²/(8EI) and the mid-span moment PL/4 − M.
    let mut g = single_girder();
    let ei = flexural_rigidity(&g);
    let (p, l): (f64, f64) = (1.0e5, 20.0);
    let k_r = 2.0 * ei / l; // k_r L/(2EI) = 1: half of the fixed-end moment
    g.bearings = vec![
        Bearing {
            rotational_stiffness: k_r,
            ..Bearing::default()
        };
        2
    ];
    let (deflection, moment) = mid_span_response(&fe(&g), p);
    let theta0 = p * l * l / (16.0 * ei);
    let end_moment = k_r * theta0 / (1.0 + k_r * l / (2.0 * ei));
    let expected = p * l.powi(3) / (48.0 * ei) - end_moment * l * l / (8.0 * ei);
    assert!(
        (-deflection - expected).abs() < 1e-9 * expected,
        "{deflection} vs {expected}"
    );
    let expected_moment = p * l / 4.0 - end_moment;
    assert!(
        (moment - expected_moment).abs() < 1e-8 * p * l,
        "{moment} vs {expected_moment}"
    );
}

/// The lowest `count` vertical-bending frequencies [Hz].
fn vertical_frequencies(model: &BridgeModel, count: usize) -> Vec<f64> {
    let fe = discretise(model, &MeshOptions::default()).unwrap();
    let basis = solve_modes(
        &fe,
        &ModalOptions {
            mode_count: 12,
            ..ModalOptions::default()
        },
    )
    .unwrap();
    let found: Vec<f64> = basis
        .modes
        .iter()
        .filter(|m| m.kind == ModeKind::VerticalBending)
        .map(|m| m.frequency_hz())
        .take(count)
        .collect();
    assert_eq!(found.len(), count);
    found
}

#[test]
fn a_girder_on_elastic_bearings_has_the_frequencies_of_the_beam_on_elastic_supports() {
    // Reference: vbi's 2D continuous beam with elastic supports (verified against the beam on
    // springs in docs/verification.md) has the same vertical-plane matrices as a one-girder
    // grillage on bearings with the same vertical and rotational stiffness.
    let mut g = single_girder();
    let (k, k_r) = (3.0e8, 1.0e9);
    g.bearings = vec![
        Bearing {
            vertical_stiffness: Some(k),
            rotational_stiffness: k_r,
            torsion_free: false,
        };
        2
    ];
    let section = g.girder_section(0).unwrap();
    let mut beam = ContinuousBeam::pinned(
        g.span_lengths.clone(),
        BeamSection::from_girder(&section, &g.material),
    );
    beam.added_mass_per_length = g.added_mass_per_length(0);
    beam.supports = vec![
        SupportKind::Elastic {
            vertical_stiffness: k,
            rotational_stiffness: k_r,
        };
        2
    ];
    let grillage = vertical_frequencies(&BridgeModel::Grillage(g), 3);
    let beam = vertical_frequencies(&BridgeModel::ContinuousBeam(beam), 3);
    for (a, b) in grillage.iter().zip(&beam) {
        // Same matrices; Lanczos round-off only.
        assert!((a - b).abs() < 1e-8 * b, "{a} vs {b}");
    }
}

#[test]
fn girder_properties_given_directly_reproduce_the_box_they_were_computed_from() {
    // Reference: the shape only computes the section; the same numbers given directly must
    // give the same model, frequencies and static response to round-off.
    let boxes = grillage(2, 20.0);
    let mut given = boxes.clone();
    let inner = boxes.girder_section(1).unwrap();
    let edge = boxes.girder_section(0).unwrap();
    let as_given = |s: vbi::model::GirderSection| {
        GirderShape::Properties(GivenSection {
            area: s.area,
            second_moment_y: s.second_moment_y,
            second_moment_z: s.second_moment_z,
            torsion_constant: s.torsion_constant,
            centroid_height: s.centroid_height,
            depth: s.depth,
        })
    };
    given.girder = as_given(inner);
    given.edge_girder = Some(as_given(edge));
    let a = fe(&boxes);
    let b = fe(&given);
    assert_eq!(a.stiffness.values, b.stiffness.values);
    assert_eq!(a.mass.values, b.mass.values);
}

#[test]
fn barrier_masses_carry_their_rigid_body_kinetic_energy() {
    // Reference: a rigid vertical translation moves every mass by 1 (energy Σm); a rigid
    // rotation θ about the bridge axis moves a barrier at lateral position y_b by y_b θ, so the
    // added mass must add 2·m_b L in translation and 2·m_b L (W/2 − d)² in rotation.
    let plain = grillage(1, 20.0);
    let mut with = plain.clone();
    let (m_b, d) = (800.0, 0.3);
    with.barriers = Some(Barriers {
        mass_per_length: m_b,
        edge_distance: d,
    });
    let length = 20.0;
    let (a, b) = (fe(&plain), fe(&with));
    let energy = |model: &FeModel, rotation: bool| {
        // The vector of the rigid motion on the free DOFs, from the deck's DOF rows: w = 1 (or
        // y) at every deck node; θx = 0 (or 1) on every node's torsion DOF.
        let mut v = vec![0.0; model.mass.size];
        for (line, deck_line) in model.deck.lines.iter().enumerate() {
            let _ = line;
            for node in 0..deck_line.node_positions.len() {
                let dofs = &model.deck_dofs[deck_line.first_node + node];
                for &(dof, c) in &dofs.deflection {
                    v[dof] = if rotation {
                        deck_line.lateral_position
                    } else {
                        1.0
                    } * c;
                }
            }
        }
        if rotation {
            for (dof, direction) in model.dof_directions.iter().enumerate() {
                if *direction == vbi::fe::Direction::RotationX {
                    v[dof] = 1.0;
                }
            }
        }
        quadratic_form(&model.mass, &v)
    };
    // Supports hold w (and θx) at the support nodes: the barrier there is not moved, so the
    // expected increase counts the interior nodes' tributary lengths only.
    let fe_with = &b;
    let held_length = support_tributary_length(fe_with);
    let moving = length - held_length;
    let translation = energy(&b, false) - energy(&a, false);
    assert!(
        (translation - 2.0 * m_b * moving).abs() < 1e-9 * translation,
        "{translation} vs {}",
        2.0 * m_b * moving
    );
    let arm = with.deck_width / 2.0 - d;
    let rotation = energy(&b, true) - energy(&a, true);
    let expected = 2.0 * m_b * moving * arm * arm;
    assert!(
        (rotation - expected).abs() < 1e-9 * expected,
        "{rotation} vs {expected}"
    );
    assert!((b.total_mass - with.total_mass().unwrap()).abs() < 1e-9 * b.total_mass);
}

/// Tributary length of the end nodes (held vertically at the supports) [m].
fn support_tributary_length(model: &FeModel) -> f64 {
    let xs = &model.deck.lines[0].node_positions;
    (xs[1] - xs[0]) / 2.0 + (xs[xs.len() - 1] - xs[xs.len() - 2]) / 2.0
}

fn quadratic_form(matrix: &vbi::linalg::SparseMatrix, v: &[f64]) -> f64 {
    let mut sum = 0.0;
    for c in 0..matrix.size {
        for k in matrix.column_pointers[c]..matrix.column_pointers[c + 1] {
            sum += v[matrix.row_indices[k]] * matrix.values[k] * v[c];
        }
    }
    sum
}

#[test]
fn releasing_torsion_or_softening_the_bearings_never_raises_a_frequency() {
    // Reference: Courant–Fischer minimax. Removing a restraint or replacing a rigid one by a
    // spring enlarges the admissible space, so the k-th eigenvalue cannot rise; and with the
    // same mass, a stiffer member (diaphragms in the spans) cannot lower one.
    let rigid = grillage(2, 20.0);
    let base = lowest_frequencies(&rigid);
    for bearing in [
        Bearing {
            torsion_free: true,
            ..Bearing::default()
        },
        Bearing {
            vertical_stiffness: Some(5.0e8),
            ..Bearing::default()
        },
    ] {
        let mut g = rigid.clone();
        g.bearings = vec![bearing; g.supports.len()];
        let released = lowest_frequencies(&g);
        for (k, (r, b)) in released.iter().zip(&base).enumerate() {
            assert!(
                *r <= b * (1.0 + 1e-9),
                "mode {}: {r} > {b} ({bearing:?})",
                k + 1
            );
        }
        assert!(released[0] < base[0] * (1.0 - 1e-6) || released[2] < base[2] * (1.0 - 1e-6));
    }
}

#[test]
fn a_single_girder_on_torsionally_free_bearings_is_refused_as_free_in_torsion() {
    let mut g = single_girder();
    g.bearings = vec![
        Bearing {
            torsion_free: true,
            ..Bearing::default()
        };
        2
    ];
    let error = discretise(&BridgeModel::Grillage(g), &MeshOptions::default()).unwrap_err();
    assert!(
        matches!(
            error,
            FeError::Mechanism {
                direction: vbi::fe::Direction::RotationX,
                ..
            }
        ),
        "{error}"
    );
}

#[test]
fn intermediate_diaphragms_add_their_mass_and_stiffen_the_loaded_edge_girder() {
    // References: bookkeeping of the mass (ρ b d over the girder lines' width, per diaphragm);
    // and a stiffer transverse system spreads an edge load: the loaded girder deflects less.
    let plain = grillage(1, 20.0);
    let mut with = plain.clone();
    let section = Diaphragm {
        width: 0.25,
        depth: 1.0,
    };
    with.intermediate_diaphragms = Some(IntermediateDiaphragms {
        per_span: 3,
        section,
    });
    let (a, b) = (fe(&plain), fe(&with));
    let across = 2.0 * with.girder_spacing;
    let added = 3.0 * with.material.density * section.width * section.depth * across;
    assert!((b.total_mass - a.total_mass - added).abs() < 1e-9 * b.total_mass);
    assert!((b.total_mass - with.total_mass().unwrap()).abs() < 1e-9 * b.total_mass);
    let edge_deflection = |model: &FeModel| {
        let station = model
            .stations
            .iter()
            .position(|s| s.name == "span1_mid_g1")
            .unwrap();
        let y = model.deck.lines[0].lateral_position;
        static_response(model, &[(10.0, y, 1.0e5)])
            .unwrap()
            .deflection[station]
    };
    let (da, db) = (edge_deflection(&a), edge_deflection(&b));
    assert!(db.abs() < da.abs() * (1.0 - 1e-3), "{db} vs {da}");
}

// ---------------------------------------------------------------- skew

fn skewed(degrees: f64) -> Grillage {
    let mut g = grillage(2, 20.0);
    g.skew_angle = degrees.to_radians();
    g
}

#[test]
fn a_skew_of_a_thousandth_of_a_degree_has_the_square_decks_frequencies() {
    // Reference: continuity at θ → 0. The skewed bearings' torsional restraint is a stiff
    // spring (1e6 × 4EI/L) about the normal to the support line instead of the square deck's
    // exact restraint of θx: the two must agree to the penalty's 1e-6 and the skew's 1.7e-5 rad.
    let square = lowest_frequencies(&grillage(2, 20.0));
    let nearly = lowest_frequencies(&skewed(1e-3));
    for (k, (a, b)) in nearly.iter().zip(&square).enumerate() {
        assert!((a - b).abs() < 2e-5 * b, "mode {}: {a} vs {b}", k + 1);
    }
}

#[test]
fn the_reactions_of_a_skewed_deck_balance_an_eccentric_load() {
    // Reference: static equilibrium of forces and of moments about x and y, with the bearings
    // at their skewed positions (a wrong node x or a missing coupled spring breaks it).
    use super::verification_fe::static_solve;
    let model = BridgeModel::Grillage(skewed(30.0));
    let options = MeshOptions::default();
    let fe = discretise(&model, &options).unwrap();
    let (x, y, p) = (17.3, 2.1, 1.0e5);
    let u = static_solve(&fe, &[(x, y, p)]);
    let reactions = vbi::fe::support_reactions(&model, &options, u.as_slice()).unwrap();
    let sum = |f: &dyn Fn(&vbi::fe::SupportReaction) -> f64| reactions.iter().map(f).sum::<f64>();
    // Round-off of element forces of size ~P (and the penalty's ~1e6 larger ones) times lever
    // arms ≤ 45 m.
    let tolerance = 1e-6 * p * 45.0;
    assert!((sum(&|r| r.force[2]) - p).abs() < tolerance);
    let moment_x = sum(&|r| r.position[1] * r.force[2] + r.moment[0]) - y * p;
    let moment_y = sum(&|r| -r.position[0] * r.force[2] + r.moment[1]) + x * p;
    assert!(moment_x.abs() < tolerance, "{moment_x}");
    assert!(moment_y.abs() < tolerance, "{moment_y}");
    // The girders' supports are offset by y·tan θ: girder 3 (y = 2.9 m) starts 2·2.9·tan 30°
    // after girder 1.
    let first = |girder: usize| {
        reactions
            .iter()
            .find(|r| r.support == 0 && r.girder == girder)
            .unwrap()
            .position[0]
    };
    assert!((first(2) - first(0) - 5.8 * 30f64.to_radians().tan()).abs() < 1e-12);
}

#[test]
fn a_skewed_deck_is_symmetric_about_its_centre() {
    // Reference: a parallelogram deck on like bearings is symmetric under the half turn about
    // its centre, (x, y) → (X − x, −y) with X the sum of its extremes: the mid-span deflection
    // of girder 1 under a load at P equals that of girder 3 under the load at P's image.
    let model = BridgeModel::Grillage(skewed(25.0));
    let fe = discretise(&model, &MeshOptions::default()).unwrap();
    let line = |g: usize| &fe.deck.lines[g].node_positions;
    let centre_sum = line(0)[0] + line(2)[line(2).len() - 1];
    let (x, y) = (13.4, -1.3);
    let mid = |name: &str| fe.stations.iter().position(|s| s.name == name).unwrap();
    let (g1, g3) = (mid("span1_mid_g1"), mid("span2_mid_g3"));
    assert!((fe.stations[g1].position + fe.stations[g3].position - centre_sum).abs() < 1e-9);
    let here = static_response(&fe, &[(x, y, 1.0e5)]).unwrap();
    let image = static_response(&fe, &[(centre_sum - x, -y, 1.0e5)]).unwrap();
    let (a, b) = (here.deflection[g1], image.deflection[g3]);
    assert!((a - b).abs() < 1e-9 * a.abs(), "{a} vs {b}");
    let (ma, mb) = (here.moment[g1], image.moment[g3]);
    assert!((ma - mb).abs() < 1e-8 * ma.abs(), "{ma} vs {mb}");
}

#[test]
fn a_section_station_on_a_skewed_deck_is_refused_and_defaults_read_each_girder() {
    let g = skewed(20.0);
    let fe = fe(&g);
    assert!(fe.stations.iter().all(|s| s.name.contains("_g")));
    let options = MeshOptions {
        stations: vec![vbi::fe::StationRequest {
            name: None,
            position: 10.0,
            target: vbi::modal::StationTarget::Section,
        }],
        ..MeshOptions::default()
    };
    assert!(matches!(
        discretise(&BridgeModel::Grillage(g), &options),
        Err(FeError::SkewedSection { .. })
    ));
}

#[test]
fn a_skewed_decks_stations_lie_along_their_girders_where_the_codes_look_for_them() {
    // The design codes and the plausibility checks place a station in its span by its distance
    // along the girder: every girder's interior-support station is at 20 m along it, though
    // their deck x differ by the skew's offsets.
    let model = BridgeModel::Grillage(skewed(30.0));
    let fe = discretise(&model, &MeshOptions::default()).unwrap();
    let offsets = model.line_offsets();
    let supports: Vec<&vbi::fe::Station> = fe
        .stations
        .iter()
        .filter(|s| s.name.starts_with("support2_"))
        .collect();
    assert_eq!(supports.len(), 3);
    for station in &supports {
        assert!(
            (station.along_girders(&offsets) - 20.0).abs() < 1e-9,
            "{station:?}"
        );
    }
    assert!(
        (supports[2].position - supports[0].position - 5.8 * 30f64.to_radians().tan()).abs() < 1e-9
    );
    // One girder has nothing to offset: not skewed, and its section stations stay.
    let mut one = skewed(30.0);
    one.girder_count = 1;
    one.deck_width = 2.9;
    assert!(!one.is_skewed());
    assert!(fe_stations_have_section(&one));
}

fn fe_stations_have_section(g: &Grillage) -> bool {
    fe(g).stations.iter().any(|s| s.name.ends_with("_section"))
}

#[test]
fn resizing_a_grillages_spans_keeps_one_bearing_per_support_line() {
    let mut g = grillage(3, 30.0);
    g.bearings = vec![
        Bearing {
            vertical_stiffness: Some(1e9),
            ..Bearing::default()
        };
        4
    ];
    let mut model = BridgeModel::Grillage(g);
    model.resize_spans(2, 25.0);
    let BridgeModel::Grillage(g) = &model else {
        panic!("grillage")
    };
    assert_eq!(g.bearings.len(), 3);
    assert!(model.validate().is_ok());
}
