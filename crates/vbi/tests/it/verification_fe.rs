//! Verification of the `fe` stage: frequencies and statics of beams against closed forms, and
//! the physical invariants of the grillage (mass, symmetry, equilibrium, reduction to a beam).
//!
//! Solves here are small dense nalgebra solves (test-only); the production sparse eigen solver
//! lives in `linalg`.

use nalgebra::{DMatrix, DVector, SymmetricEigen};
use vbi::fe::{discretise, support_reactions, FeError, FeModel, MeshOptions, SparseRow};
use vbi::fe::{Direction, StationRequest};
use vbi::linalg::SparseMatrix;
use vbi::modal::StationTarget;
use vbi::model::{
    paper_bridge, BeamSection, BearingKind, BridgeModel, ContinuousBeam, Grillage,
    LateralRestraint, SupportKind,
};

// ---------------------------------------------------------------- dense test helpers

fn dense(a: &SparseMatrix) -> DMatrix<f64> {
    let mut d = DMatrix::zeros(a.size, a.size);
    for c in 0..a.size {
        for k in a.column_pointers[c]..a.column_pointers[c + 1] {
            d[(a.row_indices[k], c)] += a.values[k];
        }
    }
    d
}

/// All circular frequencies (ascending) and mass-normalised modes of K φ = ω² M φ, by
/// Cholesky of M (M = L Lᵀ) and the symmetric eigenproblem of L⁻¹ K L⁻ᵀ.
fn dense_modes(fe: &FeModel) -> (Vec<f64>, DMatrix<f64>) {
    let k = dense(&fe.stiffness);
    let m = dense(&fe.mass);
    let l = m.cholesky().expect("M is positive definite").l();
    let y = l.solve_lower_triangular(&k).unwrap();
    let a = l.solve_lower_triangular(&y.transpose()).unwrap();
    let a = (&a + a.transpose()) * 0.5;
    let eigen = SymmetricEigen::new(a);
    let mut order: Vec<usize> = (0..eigen.eigenvalues.len()).collect();
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    let lt = l.transpose();
    let mut phi = DMatrix::zeros(fe.dof_count(), order.len());
    let mut omega = Vec::new();
    for (col, &i) in order.iter().enumerate() {
        omega.push(eigen.eigenvalues[i].max(0.0).sqrt());
        let v = lt
            .solve_upper_triangular(&eigen.eigenvectors.column(i).into_owned())
            .unwrap();
        phi.set_column(col, &v);
    }
    (omega, phi)
}

/// Consistent load vector of downward point loads (x, y, P) [m, m, N] through the deck stencil:
/// f = −P · (N_w · deflection row + N_θ · slope row).
fn load_vector(fe: &FeModel, loads: &[(f64, f64, f64)]) -> DVector<f64> {
    let mut f = DVector::zeros(fe.dof_count());
    for &(x, y, p) in loads {
        for t in fe.deck.stencil(x, y).terms() {
            let dofs = &fe.deck_dofs[t.node];
            for &(d, c) in &dofs.deflection {
                f[d] -= p * t.value_from_deflection * c;
            }
            for &(d, c) in &dofs.slope {
                f[d] -= p * t.value_from_slope * c;
            }
        }
    }
    f
}

pub(crate) fn static_solve(fe: &FeModel, loads: &[(f64, f64, f64)]) -> DVector<f64> {
    let k = dense(&fe.stiffness);
    k.cholesky()
        .expect("K is positive definite")
        .solve(&load_vector(fe, loads))
}

pub(crate) fn read(row: &SparseRow, u: &DVector<f64>) -> f64 {
    row.iter().map(|&(d, c)| c * u[d]).sum()
}

pub(crate) fn station(fe: &FeModel, name: &str) -> usize {
    fe.stations
        .iter()
        .position(|s| s.name == name)
        .unwrap_or_else(|| panic!("no station {name}"))
}

// ---------------------------------------------------------------- beams

/// docs/verification.md §9 (VBI-2D verification beam): L = 25 m, E = 3.5e10 Pa,
/// I = 1.3901 m⁴, m̄ = 18358 kg/m.
fn reference_beam(span_lengths: Vec<f64>) -> ContinuousBeam {
    ContinuousBeam::pinned(
        span_lengths,
        BeamSection {
            flexural_rigidity: 3.5e10 * 1.3901,
            mass_per_length: 18358.0,
        },
    )
}

fn beam_options(elements_per_span: usize) -> MeshOptions {
    MeshOptions {
        elements_per_span: Some(elements_per_span),
        ..MeshOptions::default()
    }
}

fn ss_beam_errors(elements: usize, modes: usize) -> Vec<f64> {
    // Reference: docs/verification.md §1, ω_n = (nπ/L)² √(EI/m̄).
    let beam = reference_beam(vec![25.0]);
    let (ei, m) = (beam.section.flexural_rigidity, beam.section.mass_per_length);
    let fe = discretise(&BridgeModel::ContinuousBeam(beam), &beam_options(elements)).unwrap();
    let (omega, _) = dense_modes(&fe);
    (1..=modes)
        .map(|n| {
            let exact = (n as f64 * std::f64::consts::PI / 25.0).powi(2) * (ei / m).sqrt();
            (omega[n - 1] - exact) / exact
        })
        .collect()
}

#[test]
fn simply_supported_beam_frequencies_of_modes_1_to_10_match_the_closed_form() {
    // Reference: docs/verification.md §1 (closed form).
    let elements = 80;
    let errors = ss_beam_errors(elements, 10);
    for (n, e) in errors.iter().enumerate() {
        // Consistent-mass Hermite elements converge from above with the leading relative error
        // (kh)⁴/1440, k = nπ/L (1.6e-5 for mode 10 at h = L/80). Allow 10 % on that term, plus
        // 1e-8 for the dense solve's round-off, ε·λ_max/λ_min ≈ 1e-16 · 1e8.
        let kh = (n + 1) as f64 * std::f64::consts::PI / elements as f64;
        let bound = 1.1 * kh.powi(4) / 1440.0 + 1e-8;
        assert!(
            *e > -1e-8,
            "mode {}: FE frequency below the exact one: {e}",
            n + 1
        );
        assert!(*e < bound, "mode {}: relative error {e} > {bound}", n + 1);
    }
}

#[test]
fn simply_supported_beam_frequencies_converge_at_the_fourth_order_rate() {
    // Reference: docs/verification.md §1; cubic Hermite elements with consistent mass have
    // eigenvalue error O(h^(2(p+1−m))) = O(h⁴) for p = 3, m = 2 (Strang & Fix §6.3).
    let coarse = ss_beam_errors(8, 3);
    let fine = ss_beam_errors(16, 3);
    for n in 0..3 {
        let rate = (coarse[n] / fine[n]).log2();
        // Asymptotic rate 4; at 8 → 16 elements the pre-asymptotic terms shift it by < 0.3.
        assert!((rate - 4.0).abs() < 0.3, "mode {}: rate {rate}", n + 1);
    }
}

#[test]
fn two_span_beam_frequency_ratios_match_the_closed_form() {
    // Reference: docs/verification.md §3 table (tan a = tanh a for the even modes).
    let beam = reference_beam(vec![20.0, 20.0]);
    let fe = discretise(&BridgeModel::ContinuousBeam(beam), &beam_options(40)).unwrap();
    let (omega, _) = dense_modes(&fe);
    let expected = [1.0, 1.56219, 4.0, 5.0625, 9.0, 10.5625];
    for (n, e) in expected.iter().enumerate() {
        let ratio = omega[n] / omega[0];
        // The table's ratios carry 5–6 significant digits; the FE error at 40 elements per span
        // is below 1e-5 for these modes.
        assert!(
            (ratio - e).abs() / e < 2e-5,
            "mode {}: ratio {ratio}",
            n + 1
        );
    }
}

#[test]
fn two_span_beam_statics_match_the_three_moment_equation() {
    // Reference: docs/verification.md §3: P at l/2 of span 1 gives w = −23Pl³/(1536EI)
    // and M = 13Pl/64 at l/2, and M_B = −3Pl/32 over the middle support.
    let l = 20.0;
    let p = 1.0e5;
    let beam = reference_beam(vec![l, l]);
    let ei = beam.section.flexural_rigidity;
    let fe = discretise(&BridgeModel::ContinuousBeam(beam), &beam_options(10)).unwrap();
    let u = static_solve(&fe, &[(l / 2.0, 0.0, p)]);
    let mid = &fe.station_functionals[station(&fe, "span1_mid_section")];
    let support = &fe.station_functionals[station(&fe, "support2_section")];
    assert!(fe.stations[station(&fe, "support2_section")].over_support);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
    // Hermite elements are nodally exact for point loads: only round-off (1e-9) remains.
    assert!(close(
        read(&mid.deflection, &u),
        -23.0 * p * l.powi(3) / (1536.0 * ei)
    ));
    assert!(close(read(&mid.moment_left, &u), 13.0 * p * l / 64.0));
    assert!(close(read(&mid.moment_right, &u), 13.0 * p * l / 64.0));
    assert!(close(read(&support.moment_left, &u), -3.0 * p * l / 32.0));
    assert!(close(read(&support.moment_right, &u), -3.0 * p * l / 32.0));
    // Reactions: R_A = 13P/32, R_B = 11P/16, R_C = −3P/32 (same three-moment solution).
    let r = support_reactions(
        &BridgeModel::ContinuousBeam(reference_beam(vec![l, l])),
        &beam_options(10),
        u.as_slice(),
    )
    .unwrap();
    for (reaction, expected) in r.iter().zip([13.0 / 32.0, 11.0 / 16.0, -3.0 / 32.0]) {
        assert!(close(reaction.force[2], expected * p), "{reaction:?}");
    }
}

#[test]
fn a_load_inside_an_element_is_read_exactly_from_the_element_on_the_other_side() {
    // Reference: docs/verification.md §1 statics generalised: a SS beam under P at a has
    // M(L/2) = P·a/2 and w(L/2) = −P·a(3L² − 4a²)/(48EI) for a ≤ L/2 (closed form).
    let span = 25.0;
    let beam = reference_beam(vec![span]);
    let ei = beam.section.flexural_rigidity;
    let fe = discretise(&BridgeModel::ContinuousBeam(beam), &beam_options(10)).unwrap();
    // Elements are 2.5 m; the load is inside the element just left of mid-span.
    let a = 11.3;
    let p = 1.0e5;
    let u = static_solve(&fe, &[(a, 0.0, p)]);
    let mid = &fe.station_functionals[station(&fe, "span1_mid_section")];
    let exact_w = -p * a * (3.0 * span * span - 4.0 * a * a) / (48.0 * ei);
    // Nodally exact with the consistent load vector (Hermite shape functions): round-off only.
    assert!((read(&mid.deflection, &u) - exact_w).abs() < 1e-9 * exact_w.abs());
    let m_right = read(&mid.moment_right, &u);
    assert!((m_right - p * a / 2.0).abs() < 1e-9 * p * a);
    // The loaded element's own end force is not exact (it misses the fixed-end moment).
    let m_left = read(&mid.moment_left, &u);
    assert!((m_left - p * a / 2.0).abs() > 1e-3 * p * a);
}

#[test]
fn elastic_supports_add_springs_and_a_stiff_spring_acts_as_a_pin() {
    let mut beam = reference_beam(vec![20.0, 20.0]);
    beam.supports[1] = SupportKind::Elastic {
        vertical_stiffness: 1.0e15,
        rotational_stiffness: 0.0,
    };
    let fe = discretise(&BridgeModel::ContinuousBeam(beam), &beam_options(20)).unwrap();
    let pinned = discretise(
        &BridgeModel::ContinuousBeam(reference_beam(vec![20.0, 20.0])),
        &beam_options(20),
    )
    .unwrap();
    assert_eq!(fe.dof_count(), pinned.dof_count() + 1);
    let (omega, _) = dense_modes(&fe);
    let (omega_pinned, _) = dense_modes(&pinned);
    // A 1e15 N/m spring against a span stiffness ~48EI/l³ ~ 3e8 N/m: relative effect ~1e-7.
    assert!((omega[0] - omega_pinned[0]).abs() < 1e-5 * omega_pinned[0]);
}

#[test]
fn a_beam_on_one_pin_is_reported_as_a_mechanism_naming_the_rotation() {
    let mut beam = reference_beam(vec![20.0]);
    beam.supports[1] = SupportKind::Elastic {
        vertical_stiffness: 0.0,
        rotational_stiffness: 0.0,
    };
    let error = discretise(&BridgeModel::ContinuousBeam(beam), &MeshOptions::default());
    assert!(matches!(
        error,
        Err(FeError::Mechanism {
            direction: Direction::RotationY,
            ..
        })
    ));
}

// ---------------------------------------------------------------- grillage

fn small_grillage() -> Grillage {
    let BridgeModel::Grillage(g) = paper_bridge(2, 20.0) else {
        panic!("the paper bridge is a grillage")
    };
    g
}

fn coarse() -> MeshOptions {
    MeshOptions {
        element_length: 2.0,
        ..MeshOptions::default()
    }
}

#[test]
fn grillage_total_mass_is_the_sum_of_member_and_added_masses() {
    // Reference: bookkeeping. Girders carry ρA + pavement over the whole length; slab strips are
    // massless (their slab is in the girders); diaphragms weigh ρ·b·d over (N − 1)·spacing.
    let g = small_grillage();
    let fe = discretise(&BridgeModel::Grillage(g.clone()), &coarse()).unwrap();
    let length: f64 = g.span_lengths.iter().sum();
    let rho = g.material.density;
    let girders: f64 = (0..g.girder_count)
        .map(|i| (rho * g.girder_section(i).unwrap().area + g.added_mass_per_length(i)) * length)
        .sum();
    let diaphragms = rho
        * g.diaphragm.width
        * g.diaphragm.depth
        * (g.girder_count as f64 - 1.0)
        * g.girder_spacing
        * g.supports.len() as f64;
    let expected = girders + diaphragms;
    // Sums of a few hundred terms: round-off only.
    assert!((fe.total_mass - expected).abs() < 1e-10 * expected);
    // The mass matrix is symmetric (assembled from symmetric element matrices).
    let m = dense(&fe.mass);
    assert!((&m - m.transpose()).abs().max() <= 1e-9 * m.abs().max());
}

#[test]
fn a_centred_load_is_shared_symmetrically_and_the_reactions_balance_it() {
    // Reference: symmetry of the model about y = 0 and static equilibrium (Newton).
    let g = small_grillage();
    let model = BridgeModel::Grillage(g.clone());
    let options = coarse();
    let fe = discretise(&model, &options).unwrap();
    let p = 2.0e5;
    let u = static_solve(&fe, &[(10.0, 0.0, p)]);
    let girder = |i: usize| &fe.station_functionals[station(&fe, &format!("span1_mid_g{i}"))];
    let (w1, w3) = (
        read(&girder(1).deflection, &u),
        read(&girder(3).deflection, &u),
    );
    let (m1, m3) = (
        read(&girder(1).moment_left, &u),
        read(&girder(3).moment_left, &u),
    );
    // Symmetric structure, symmetric load: equal up to round-off of the solve (~1e-12 relative
    // for a condition number ~1e6).
    assert!((w1 - w3).abs() < 1e-8 * w1.abs(), "{w1} {w3}");
    assert!((m1 - m3).abs() < 1e-8 * m1.abs(), "{m1} {m3}");
    // The centre girder, under the load, deflects most.
    let w2 = read(&girder(2).deflection, &u);
    assert!(w2 < w1 && w1 < 0.0);
    // The section reads the mean deflection and the sum of the moments.
    let section = &fe.station_functionals[station(&fe, "span1_mid_section")];
    let m2 = read(&girder(2).moment_left, &u);
    assert!((read(&section.deflection, &u) - (w1 + w2 + w3) / 3.0).abs() < 1e-12 * w2.abs());
    assert!((read(&section.moment_left, &u) - (m1 + m2 + m3)).abs() < 1e-9 * m2.abs());

    // Equilibrium of forces and of moments about the origin, load (0, 0, −P) at (10, 0, 0).
    let reactions = support_reactions(&model, &options, u.as_slice()).unwrap();
    let sum = |f: &dyn Fn(&vbi::fe::SupportReaction) -> f64| reactions.iter().map(f).sum::<f64>();
    // Round-off of a sum of element forces of size ~P: 1e-8 P.
    let tolerance = 1e-8 * p;
    assert!((sum(&|r| r.force[2]) - p).abs() < tolerance);
    assert!(sum(&|r| r.force[0]).abs() < tolerance);
    assert!(sum(&|r| r.force[1]).abs() < tolerance);
    let moment_x = sum(&|r| r.position[1] * r.force[2] + r.moment[0]);
    let moment_y = sum(&|r| -r.position[0] * r.force[2] + r.moment[1]) + 10.0 * p;
    assert!(moment_x.abs() < tolerance * 40.0, "{moment_x}");
    assert!(moment_y.abs() < tolerance * 40.0, "{moment_y}");
}

#[test]
fn an_eccentric_load_is_balanced_by_the_reactions_including_their_torsion() {
    // Reference: static equilibrium; the load sits between girder lines, off the nodes.
    let g = small_grillage();
    let model = BridgeModel::Grillage(g);
    let options = coarse();
    let fe = discretise(&model, &options).unwrap();
    let (x, y, p) = (13.7, 2.1, 1.0e5);
    let u = static_solve(&fe, &[(x, y, p)]);
    let reactions = support_reactions(&model, &options, u.as_slice()).unwrap();
    let sum = |f: &dyn Fn(&vbi::fe::SupportReaction) -> f64| reactions.iter().map(f).sum::<f64>();
    // Round-off of element forces of size ~P times lever arms ≤ 40 m.
    let tolerance = 1e-8 * p * 40.0;
    assert!((sum(&|r| r.force[2]) - p).abs() < tolerance);
    assert!((sum(&|r| r.position[1] * r.force[2] + r.moment[0]) - y * p).abs() < tolerance);
    assert!((sum(&|r| -r.position[0] * r.force[2] + r.moment[1]) + x * p).abs() < tolerance);
}

fn single_girder() -> Grillage {
    let mut g = small_grillage();
    g.girder_count = 1;
    g.deck_width = 2.9;
    g.lateral_restraint = LateralRestraint::AllSupports;
    g
}

fn equivalent_beam(g: &Grillage) -> ContinuousBeam {
    let section = g.girder_section(0).unwrap();
    let mut beam = ContinuousBeam::pinned(
        g.span_lengths.clone(),
        BeamSection {
            flexural_rigidity: g.material.elastic_modulus * section.second_moment_y,
            mass_per_length: g.material.density * section.area,
        },
    );
    beam.added_mass_per_length = g.added_mass_per_length(0);
    beam
}

#[test]
fn a_single_girder_grillage_reproduces_the_beam_frequencies() {
    // Reference: a straight 3D frame element's vertical bending (w, θy) is uncoupled from its
    // other DOFs and uses the same Hermite matrices, so the vertical modes of a one-girder
    // grillage are exactly those of the continuous beam (theory; docs/verification.md §3 for
    // the beam itself).
    let g = single_girder();
    let options = coarse();
    let fe = discretise(&BridgeModel::Grillage(g.clone()), &options).unwrap();
    let beam = discretise(&BridgeModel::ContinuousBeam(equivalent_beam(&g)), &options).unwrap();
    let (omega_beam, _) = dense_modes(&beam);
    let (omega, phi) = dense_modes(&fe);
    let m = dense(&fe.mass);
    let vertical: Vec<f64> = (0..omega.len())
        .filter(|&k| {
            // Share of kinetic energy φᵀMφ in the vertical DOFs.
            let v = phi.column(k);
            let mv = &m * v;
            let total = v.dot(&mv);
            let z: f64 = (0..v.len())
                .filter(|&i| fe.dof_directions[i] == Direction::TranslationZ)
                .map(|i| v[i] * mv[i])
                .sum();
            z > 0.5 * total
        })
        .map(|k| omega[k])
        .collect();
    for n in 0..6 {
        // Identical matrices: only eigen-solver round-off remains (~1e-10 relative).
        assert!(
            (vertical[n] - omega_beam[n]).abs() < 1e-8 * omega_beam[n],
            "mode {}: grillage {} beam {}",
            n + 1,
            vertical[n],
            omega_beam[n]
        );
    }
}

#[test]
fn the_deck_slope_sign_of_the_grillage_matches_the_beam_for_loads_between_nodes() {
    // Reference: dw/dx = −θy with x forward and z up; a load between nodes uses the slope terms
    // of the deck stencil, so a wrong sign would change the one-girder grillage's deflection.
    let g = single_girder();
    let options = coarse();
    let fe = discretise(&BridgeModel::Grillage(g.clone()), &options).unwrap();
    let beam = discretise(&BridgeModel::ContinuousBeam(equivalent_beam(&g)), &options).unwrap();
    let loads = [(7.3, 0.0, 1.0e5), (26.9, 0.0, 5.0e4)];
    let u = static_solve(&fe, &loads);
    let ub = static_solve(&beam, &loads);
    for name in ["span1_mid_section", "span2_mid_section", "support2_section"] {
        let a = &fe.station_functionals[station(&fe, name)];
        let b = &beam.station_functionals[station(&beam, name)];
        let (wa, wb) = (read(&a.deflection, &u), read(&b.deflection, &ub));
        let (ma, mb) = (read(&a.moment_right, &u), read(&b.moment_right, &ub));
        // Same equations in both models: round-off only.
        assert!(
            (wa - wb).abs() <= 1e-9 * wb.abs().max(1e-12),
            "{name}: {wa} {wb}"
        );
        assert!((ma - mb).abs() <= 1e-9 * mb.abs(), "{name}: {ma} {mb}");
    }
}

#[test]
fn a_grillage_without_a_pinned_line_is_reported_naming_the_longitudinal_direction() {
    let mut g = small_grillage();
    g.supports = vec![BearingKind::Roller; g.supports.len()];
    let error = discretise(&BridgeModel::Grillage(g), &coarse()).unwrap_err();
    assert!(matches!(
        error,
        FeError::Mechanism {
            direction: Direction::TranslationX,
            ..
        }
    ));
    assert!(error.to_string().contains("longitudinal"), "{error}");
    let mut g = single_girder();
    g.lateral_restraint = LateralRestraint::PinnedLine;
    assert!(matches!(
        discretise(&BridgeModel::Grillage(g), &coarse()),
        Err(FeError::Mechanism {
            direction: Direction::RotationZ,
            ..
        })
    ));
}

#[test]
fn the_grillage_is_stable_and_its_deck_lines_are_sorted_right_to_left() {
    let fe = discretise(&BridgeModel::Grillage(small_grillage()), &coarse()).unwrap();
    let (omega, _) = dense_modes(&fe);
    // No rigid-body mode: the lowest frequency is a structural one (well above 1 rad/s).
    assert!(omega[0] > 5.0, "{}", omega[0]);
    let y: Vec<f64> = fe.deck.lines.iter().map(|l| l.lateral_position).collect();
    assert!(y.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(fe.deck_dofs.len(), fe.deck.node_count());
    // Default stations: 2 mid-spans + 1 interior support, × (3 girders + section).
    assert_eq!(fe.stations.len(), 12);
    assert_eq!(fe.station_functionals.len(), 12);
    assert_eq!(fe.damping_ratio, 0.05);
}

#[test]
fn user_stations_become_nodes_and_are_named() {
    let options = MeshOptions {
        element_length: 2.0,
        elements_per_span: None,
        default_stations: false,
        stations: vec![
            StationRequest {
                name: Some("quarter".into()),
                position: 5.3,
                target: StationTarget::Girder(1),
            },
            StationRequest {
                name: None,
                position: 20.0,
                target: StationTarget::Section,
            },
        ],
    };
    let fe = discretise(&BridgeModel::Grillage(small_grillage()), &options).unwrap();
    assert_eq!(fe.stations.len(), 2);
    assert_eq!(fe.stations[0].name, "quarter");
    assert!((fe.stations[0].position - 5.3).abs() < 1e-12);
    assert!(fe.deck.lines[1]
        .node_positions
        .contains(&fe.stations[0].position));
    assert_eq!(fe.stations[1].name, "x20_section");
    assert!(fe.stations[1].over_support);
    let mut bad = options.clone();
    bad.stations[0].target = StationTarget::Girder(7);
    assert!(matches!(
        discretise(&BridgeModel::Grillage(small_grillage()), &bad),
        Err(FeError::NoSuchGirder { girder: 7, .. })
    ));
    bad.stations[0].target = StationTarget::Section;
    bad.stations[0].position = 41.0;
    assert!(matches!(
        discretise(&BridgeModel::Grillage(small_grillage()), &bad),
        Err(FeError::StationOffDeck { .. })
    ));
}

#[test]
fn the_largest_paper_bridge_and_a_20000_dof_model_assemble_sparse() {
    // Sizes for the modal benchmarks (issue 2): 4×40 m at the default mesh, and a finer mesh
    // above 20,000 DOF. Assembly is O(elements); stored entries stay a few dozen per row.
    let model = paper_bridge(4, 40.0);
    let fe = discretise(&model, &MeshOptions::default()).unwrap();
    assert!(fe.dof_count() > 2500);
    let fine = MeshOptions {
        element_length: 0.125,
        ..MeshOptions::default()
    };
    let fe = discretise(&model, &fine).unwrap();
    assert!(fe.dof_count() >= 20_000, "{}", fe.dof_count());
    assert!(fe.stiffness.stored_entries() < 40 * fe.dof_count());
    assert!(fe.mass.stored_entries() < 40 * fe.dof_count());
}
