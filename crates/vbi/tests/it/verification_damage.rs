//! Damping per mode and damage scenarios (docs/verification.md §"Damping laws and damage"):
//! the Rayleigh fit, the ratios a modal basis carries, and the frequencies of damaged beams
//! against invariants and the closed form of a stepped Euler–Bernoulli beam.

use std::f64::consts::PI;

use vbi::fe::{discretise, FeError, MeshOptions, StationRequest};
use vbi::modal::{solve_modes, ModalBasis, ModalOptions, ModeKind, Quantity, StationTarget};
use vbi::model::{
    paper_bridge, BeamSection, BridgeModel, ContinuousBeam, ModeDamping, RayleighDamping,
    StiffnessLoss, SupportChange,
};

/// The 25 m simply supported beam of examples/bridges/ss-beam-25m.toml: EI [N·m²], m̄ [kg/m].
const LENGTH: f64 = 25.0;
const RIGIDITY: f64 = 3.5e10 * 1.3901;
const MASS: f64 = 18358.0;

fn beam(span_lengths: Vec<f64>) -> ContinuousBeam {
    ContinuousBeam::pinned(
        span_lengths,
        BeamSection {
            flexural_rigidity: RIGIDITY,
            mass_per_length: MASS,
        },
    )
}

fn loss(start: f64, end: f64, factor: f64) -> StiffnessLoss {
    StiffnessLoss {
        start,
        end,
        girder: None,
        elastic_modulus_factor: factor,
    }
}

fn modes(model: ContinuousBeam, mesh: &MeshOptions, count: usize) -> ModalBasis {
    let fe = discretise(&BridgeModel::ContinuousBeam(model), mesh).unwrap();
    let options = ModalOptions {
        mode_count: count,
        ..ModalOptions::default()
    };
    solve_modes(&fe, &options).unwrap()
}

/// The fitted ζ(ω) = α/(2ω) + βω/2 returns ζ₁ and ζ₂ at f₁ and f₂ to round-off, and at a third
/// frequency equals the formula with α, β solved independently from the 2 × 2 system
/// [1/(2ω_i), ω_i/2]·[α, β]ᵀ = ζ_i by Cramer's rule.
#[test]
fn a_rayleigh_fit_returns_the_given_ratios_at_its_two_frequencies_and_the_formula_at_a_third() {
    let rayleigh = RayleighDamping {
        first_ratio: 0.02,
        first_frequency: 2.0,
        second_ratio: 0.03,
        second_frequency: 10.0,
    };
    let fit = rayleigh.coefficients().unwrap();
    let (w1, w2) = (2.0 * PI * 2.0, 2.0 * PI * 10.0);
    // Round-off of a few operations on numbers of order 1: 1e-15 relative.
    assert!((fit.damping_ratio(w1) - 0.02).abs() < 1e-15 * 0.02 * 4.0);
    assert!((fit.damping_ratio(w2) - 0.03).abs() < 1e-15 * 0.03 * 4.0);
    let (a, b, c, d) = (1.0 / (2.0 * w1), w1 / 2.0, 1.0 / (2.0 * w2), w2 / 2.0);
    let determinant = a * d - b * c;
    let alpha = (0.02 * d - b * 0.03) / determinant;
    let beta = (a * 0.03 - c * 0.02) / determinant;
    let w3 = 2.0 * PI * 5.0;
    let expected = alpha / (2.0 * w3) + beta * w3 / 2.0;
    assert!((fit.damping_ratio(w3) - expected).abs() < 1e-14 * expected);
    assert!(fit.mass_coefficient > 0.0 && fit.stiffness_coefficient > 0.0);
}

/// A per-mode list reaches the modal basis: the k-th retained mode (ascending frequency) has
/// the k-th ratio, modes beyond the list the last; Rayleigh damping gives each mode
/// α/(2ω) + βω/2 at its own frequency.
#[test]
fn per_mode_and_rayleigh_damping_give_each_retained_mode_its_ratio() {
    let mesh = MeshOptions {
        default_stations: false,
        ..MeshOptions::default()
    };
    let mut model = beam(vec![LENGTH]);
    model.mode_damping = Some(ModeDamping::PerMode {
        ratios: vec![0.01, 0.02, 0.03],
    });
    let basis = modes(model.clone(), &mesh, 5);
    let ratios: Vec<f64> = basis.modes.iter().map(|m| m.damping_ratio).collect();
    assert_eq!(ratios, [0.01, 0.02, 0.03, 0.03, 0.03]);

    let rayleigh = RayleighDamping {
        first_ratio: 0.02,
        first_frequency: 4.0,
        second_ratio: 0.04,
        second_frequency: 40.0,
    };
    model.mode_damping = Some(ModeDamping::Rayleigh(rayleigh));
    let basis = modes(model, &mesh, 5);
    let fit = rayleigh.coefficients().unwrap();
    for mode in &basis.modes {
        assert_eq!(
            mode.damping_ratio,
            fit.damping_ratio(mode.circular_frequency)
        );
    }
}

/// The list numbers the retained modes: on the paper's 2 × 20 m grillage with only vertical
/// bending kept, mode 1 of the list is the first vertical bending mode, whatever other kinds lie
/// below it.
#[test]
fn a_per_mode_list_numbers_the_modes_kept_after_the_kind_filter() {
    let BridgeModel::Grillage(mut grillage) = paper_bridge(2, 20.0) else {
        panic!("the paper bridge is a grillage")
    };
    grillage.mode_damping = Some(ModeDamping::PerMode {
        ratios: vec![0.011, 0.012, 0.013],
    });
    let fe = discretise(&BridgeModel::Grillage(grillage), &MeshOptions::default()).unwrap();
    let options = ModalOptions {
        mode_count: 12,
        keep_kinds: vec![ModeKind::VerticalBending],
        ..ModalOptions::default()
    };
    let basis = solve_modes(&fe, &options).unwrap();
    assert!(basis.mode_count() >= 2);
    assert_eq!(basis.modes[0].damping_ratio, 0.011);
    assert_eq!(basis.modes[1].damping_ratio, 0.012);
    assert!(basis
        .modes
        .iter()
        .all(|m| m.kind == ModeKind::VerticalBending));
}

/// A factor f on E over the whole simply supported beam scales K by f and keeps M, so every
/// eigenvalue scales by f and every frequency by √f exactly (an invariant, no reference); the
/// modal moments EI·φ'' scale by f (the mass-normalised shapes are unchanged), which checks that
/// the stations read the damaged rigidity. Tolerance 1e-9 relative: the Lanczos convergence
/// tolerance 1e-10 on each Ritz value, not the mesh.
#[test]
fn a_uniform_modulus_factor_scales_every_frequency_by_its_square_root_and_moments_by_it() {
    let factor = 0.64;
    let mesh = MeshOptions {
        elements_per_span: Some(50),
        default_stations: false,
        stations: vec![StationRequest {
            name: Some("x8".into()),
            position: 8.0,
            target: StationTarget::Section,
        }],
        ..MeshOptions::default()
    };
    let intact = modes(beam(vec![LENGTH]), &mesh, 6);
    let mut damaged_beam = beam(vec![LENGTH]);
    damaged_beam
        .damage
        .stiffness_losses
        .push(loss(0.0, LENGTH, factor));
    let damaged = modes(damaged_beam, &mesh, 6);
    let intact_moments = intact.station_values(0, Quantity::BendingMoment);
    let damaged_moments = damaged.station_values(0, Quantity::BendingMoment);
    let intact_deflections = intact.station_values(0, Quantity::Deflection);
    let damaged_deflections = damaged.station_values(0, Quantity::Deflection);
    for k in 0..6 {
        let ratio = damaged.modes[k].circular_frequency / intact.modes[k].circular_frequency;
        assert!(
            (ratio - factor.sqrt()).abs() < 1e-9,
            "mode {}: ratio {ratio}",
            k + 1
        );
        // Shapes are defined up to sign: compare with the sign of the deflection.
        let sign = (damaged_deflections[k] / intact_deflections[k]).signum();
        let expected = factor * intact_moments[k] * sign;
        assert!(
            (damaged_moments[k] - expected).abs() < 1e-9 * intact_moments[k].abs(),
            "mode {}: moment {} vs {expected}",
            k + 1,
            damaged_moments[k]
        );
    }
}

/// Krylov functions of the Euler–Bernoulli beam, S, T, U, V at z = λx (S(0) = 1; S' = λV,
/// T' = λS, U' = λT, V' = λU).
fn krylov(z: f64) -> [f64; 4] {
    [
        (z.cosh() + z.cos()) / 2.0,
        (z.sinh() + z.sin()) / 2.0,
        (z.cosh() - z.cos()) / 2.0,
        (z.sinh() - z.sin()) / 2.0,
    ]
}

/// Transfer of the state (w, w', M = EI w'', Q = EI w''') over a segment of length ℓ and
/// rigidity EI in harmonic motion at ω: λ⁴ = m̄ω²/EI.
fn transfer(state: [f64; 4], length: f64, rigidity: f64, omega: f64) -> [f64; 4] {
    let lambda = (MASS * omega * omega / rigidity).powf(0.25);
    let [s, t, u, v] = krylov(lambda * length);
    let [w, slope, moment, shear] = state;
    let (l, ei) = (lambda, rigidity);
    [
        s * w + t * slope / l + u * moment / (ei * l * l) + v * shear / (ei * l * l * l),
        l * v * w + s * slope + t * moment / (ei * l) + u * shear / (ei * l * l),
        ei * l * l * u * w + ei * l * v * slope + s * moment + t * shear / l,
        ei * l * l * l * t * w + ei * l * l * u * slope + l * v * moment + s * shear,
    ]
}

/// Characteristic determinant of the simply supported three-segment beam (EI on [0, a] and
/// [b, L], f·EI on [a, b]): w(0) = M(0) = 0 leave the slope and the shear at x = 0 unknown; the
/// determinant of (w(L), M(L)) for unit slope and unit shear vanishes at a natural frequency.
fn stepped_beam_determinant(omega: f64, a: f64, b: f64, factor: f64) -> f64 {
    let end = |state: [f64; 4]| {
        let state = transfer(state, a, RIGIDITY, omega);
        let state = transfer(state, b - a, factor * RIGIDITY, omega);
        transfer(state, LENGTH - b, RIGIDITY, omega)
    };
    let from_slope = end([0.0, 1.0, 0.0, 0.0]);
    let from_shear = end([0.0, 0.0, 0.0, RIGIDITY]);
    from_slope[0] * from_shear[2] - from_slope[2] * from_shear[0]
}

/// The root of `f` in [low, high] (a sign change) by bisection to round-off.
fn bisect(f: impl Fn(f64) -> f64, mut low: f64, mut high: f64) -> f64 {
    let f_low = f(low);
    assert!(f_low * f(high) < 0.0, "no sign change in [{low}, {high}]");
    for _ in 0..200 {
        let middle = 0.5 * (low + high);
        if f(middle) * f_low > 0.0 {
            low = middle;
        } else {
            high = middle;
        }
        if high - low <= 1e-15 * high {
            break;
        }
    }
    0.5 * (low + high)
}

/// Local stiffness loss: the 25 m simply supported beam with E × 0.5 on [10 m, 14 m] against
/// the exact frequencies of the stepped Euler–Bernoulli beam (transfer matrices, the
/// characteristic determinant solved by bisection), modes 1–3. By min–max the n-th frequency
/// lies between √f·ω_n and ω_n of the intact beam, and for f = 0.5 these brackets do not
/// overlap up to mode 5, so each holds the n-th root. The mesh (0.3 m elements; the region's
/// ends are made nodes) gives the Hermite error (nπh/L)⁴/720 ≤ 2.3e-7 in ω² for n = 3, so the
/// tolerance is 1e-6 on ω (the shifts are 0.6–5 %, matched to better than 1e-4 of themselves).
#[test]
fn a_local_stiffness_loss_shifts_the_frequencies_as_the_stepped_beam_closed_form() {
    let (a, b, factor) = (10.0, 14.0, 0.5);
    let mut damaged_beam = beam(vec![LENGTH]);
    damaged_beam
        .damage
        .stiffness_losses
        .push(loss(a, b, factor));
    let mesh = MeshOptions {
        element_length: 0.3,
        default_stations: false,
        ..MeshOptions::default()
    };
    let damaged = modes(damaged_beam, &mesh, 3);
    for n in 1..=3 {
        let intact = (n as f64 * PI / LENGTH).powi(2) * (RIGIDITY / MASS).sqrt();
        let exact = bisect(
            |omega| stepped_beam_determinant(omega, a, b, factor),
            factor.sqrt() * intact * (1.0 + 1e-9),
            intact * (1.0 - 1e-9),
        );
        let fe = damaged.modes[n - 1].circular_frequency;
        let error = (fe - exact).abs() / exact;
        assert!(
            error < 1e-6,
            "mode {n}: FE {fe} vs exact {exact}: {error:e}"
        );
        let shift = 1.0 - exact / intact;
        assert!(
            shift > 1e-3,
            "mode {n}: the loss shifts the frequency by {shift}"
        );
    }
}

/// A removed middle support of a two-span 2 × 12.5 m beam leaves the 25 m simply supported
/// beam: ω_n = (nπ/L)² √(EI/m̄) (docs/verification.md §1). A 0.25 m mesh: Hermite error
/// (nπh/L)⁴/720 ≤ 1.1e-7 in ω² for n = 3, tolerance 1e-6 on ω. A 1e8 N/m spring in place of the
/// support gives a first frequency between the removed and the rigid support's.
#[test]
fn a_removed_middle_support_leaves_the_simply_supported_beam_of_the_whole_length() {
    let mesh = MeshOptions {
        element_length: 0.25,
        default_stations: false,
        ..MeshOptions::default()
    };
    let intact = modes(beam(vec![12.5, 12.5]), &mesh, 1);
    let mut removed = beam(vec![12.5, 12.5]);
    removed.damage.support_changes.push(SupportChange {
        support: 1,
        vertical_stiffness: 0.0,
    });
    let mut softened = removed.clone();
    softened.damage.support_changes[0].vertical_stiffness = 1e8;
    let removed = modes(removed, &mesh, 3);
    for n in 1..=3 {
        let exact = (n as f64 * PI / LENGTH).powi(2) * (RIGIDITY / MASS).sqrt();
        let fe = removed.modes[n - 1].circular_frequency;
        assert!(
            (fe - exact).abs() < 1e-6 * exact,
            "mode {n}: {fe} vs {exact}"
        );
    }
    let softened = modes(softened, &mesh, 1).modes[0].circular_frequency;
    assert!(softened > removed.modes[0].circular_frequency);
    assert!(softened < intact.modes[0].circular_frequency);
}

/// Bad damage is refused before any analysis: a region off the bridge, a factor of 0, a
/// missing girder; a support change that leaves a mechanism is named as one.
#[test]
fn bad_damage_is_refused_before_the_analysis() {
    let mesh = MeshOptions::default();
    let refused = |beam: ContinuousBeam| discretise(&BridgeModel::ContinuousBeam(beam), &mesh);
    let mut off = beam(vec![LENGTH]);
    off.damage.stiffness_losses.push(loss(20.0, 30.0, 0.5));
    assert!(matches!(refused(off), Err(FeError::Model(_))));
    let mut zero = beam(vec![LENGTH]);
    zero.damage.stiffness_losses.push(loss(5.0, 10.0, 0.0));
    assert!(matches!(refused(zero), Err(FeError::Model(_))));
    let mut girder = beam(vec![LENGTH]);
    girder.damage.stiffness_losses.push(StiffnessLoss {
        girder: Some(1),
        ..loss(5.0, 10.0, 0.5)
    });
    assert!(matches!(refused(girder), Err(FeError::Model(_))));
    let mut mechanism = beam(vec![LENGTH]);
    mechanism.damage.support_changes.push(SupportChange {
        support: 0,
        vertical_stiffness: 0.0,
    });
    assert!(matches!(refused(mechanism), Err(FeError::Mechanism { .. })));
    let BridgeModel::Grillage(mut grillage) = paper_bridge(1, 20.0) else {
        panic!("grillage")
    };
    grillage.damage.support_changes.push(SupportChange {
        support: 1,
        vertical_stiffness: 0.0,
    });
    assert!(matches!(
        discretise(&BridgeModel::Grillage(grillage), &mesh),
        Err(FeError::Mechanism { .. })
    ));
}
