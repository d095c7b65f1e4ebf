//! Verification of the `analytical` stage: the closed-form moving-load theory of the paper's §2.
//!
//! ```text
//!   P ↓ → v
//!  ═══════════════╤═══════════════╤═══ …   EI, m̄ uniform, N equal spans l
//!  △              △               △        pinned at every support
//!  0              l              2l
//! ```
//!
//! Reference values: docs/verification.md §1–§4 (closed forms), quoted with their digits.

use std::f64::consts::PI;

use vbi::analytical::fryba::{simply_supported_deflection, sine_mode_response};
use vbi::analytical::{
    continuous_beam_modes, daf_by_modes, frequency_parameters, section_history,
    static_load_factors, static_response, two_span_even_roots, ContinuousBeam, DafOptions,
    MaximumWindow, ModalMovingForce, MovingForce, StaticReference,
};

/// A 20 m two-span beam of the paper's size class: f₁ ≈ 5.0 Hz.
fn paper_beam(spans: usize) -> ContinuousBeam {
    ContinuousBeam::new(spans, 20.0, 3.24e10, 2.0e4).unwrap()
}

/// Deflection (upwards) and sagging moment at `x` and time `t` with the first `k` modes, for a
/// downward force `p` crossing at `speed`.
fn modal_sum(
    beam: &ContinuousBeam,
    k: usize,
    zeta: f64,
    speed: f64,
    p: f64,
    x: f64,
    t: f64,
) -> (f64, f64) {
    let modes = continuous_beam_modes(beam, k).unwrap();
    let mut w = 0.0;
    let mut m = 0.0;
    for mode in &modes {
        let q = p * ModalMovingForce::new(mode, zeta, speed)
            .unwrap()
            .displacement(t);
        w += mode.shape(x) * q;
        m += beam.flexural_rigidity * mode.curvature(x) * q;
    }
    (w, m)
}

// ---------------------------------------------------------------------------------------------
// Modes
// ---------------------------------------------------------------------------------------------

#[test]
fn two_span_even_roots_solve_tan_a_equals_tanh_a() {
    // Reference: docs/verification.md §3, exact roots quoted to 6 decimals.
    let expected = [3.926602, 7.068583, 10.210176, 13.351769, 16.493361];
    let roots = two_span_even_roots(5);
    for (r, e) in roots.iter().zip(expected) {
        // Half a unit of the last quoted digit.
        assert!((r - e).abs() < 5e-7, "{r} vs {e}");
        // And the equation itself to round-off.
        assert!((r.tan() - r.tanh()).abs() < 1e-12 * (1.0 + r.tan().abs()));
    }
    // The general N-span equation gives the same roots for N = 2 (even modes), and kπ for the
    // odd ones (Eq. 6).
    let a = frequency_parameters(2, 10).unwrap();
    for k in 0..5 {
        assert!((a[2 * k] - (k + 1) as f64 * PI).abs() < 1e-13);
        assert!((a[2 * k + 1] - roots[k]).abs() < 1e-12);
    }
}

#[test]
fn two_span_frequency_table_matches_the_reference() {
    // Reference: docs/verification.md §3, table of ω l²/√(EI/m̄) and ω/ω₁.
    let table = [
        (9.86960, 1.00000),
        (15.41821, 1.56219),
        (39.47842, 4.00000),
        (49.96486, 5.06250),
        (88.82644, 9.00000),
        (104.24770, 10.56250),
    ];
    let beam = paper_beam(2);
    let modes = continuous_beam_modes(&beam, 6).unwrap();
    let unit = (beam.flexural_rigidity / beam.mass_per_length).sqrt() / beam.span_length.powi(2);
    for (mode, (omega_bar, ratio)) in modes.iter().zip(table) {
        let w = mode.angular_frequency / unit;
        // Half a unit of the last quoted digit (5 decimals).
        assert!((w - omega_bar).abs() < 5e-6, "{w} vs {omega_bar}");
        let r = mode.angular_frequency / modes[0].angular_frequency;
        assert!((r - ratio).abs() < 5e-6, "{r} vs {ratio}");
    }
    // The paper's approximation 3.927 + (n/2 − 1)π is "within 0.01 %" (docs/verification.md §3):
    // exactly 0.0101 % for the first even mode (3.927 is 3.926602 rounded up), far less afterwards.
    for (k, a) in two_span_even_roots(5).iter().enumerate() {
        let approx = 3.927 + k as f64 * PI;
        assert!(
            (approx - a).abs() / a < 1.02e-4,
            "{k}: {}",
            (approx - a).abs() / a
        );
    }
}

#[test]
fn two_span_mode_shapes_are_eqs_5_and_10_with_unit_modal_mass() {
    // Reference: docs/verification.md §3 (Eqs. 5, 10, 12 of the paper).
    let beam = paper_beam(2);
    let l = beam.span_length;
    let m = beam.mass_per_length;
    let modes = continuous_beam_modes(&beam, 6).unwrap();
    for (n, mode) in modes.iter().enumerate() {
        let a = mode.frequency_parameter;
        let reference = |x: f64| -> f64 {
            if n % 2 == 0 {
                // Odd mode order n+1: sin((n+1+1)πx/(2l)), modal mass m̄ l.
                ((n + 2) as f64 * PI * x / (2.0 * l)).sin()
            } else {
                let xi = if x <= l { x / l } else { (2.0 * l - x) / l };
                (a * xi).sin() - a.sin() / a.sinh() * (a * xi).sinh()
            }
        };
        // Normalise the reference shape by its own modal mass (midpoint rule, 20000 cells:
        // relative error ~1e-9).
        let cells = 20000;
        let h = 2.0 * l / cells as f64;
        let mass: f64 = (0..cells)
            .map(|i| m * reference((i as f64 + 0.5) * h).powi(2) * h)
            .sum();
        let scale = 1.0 / mass.sqrt();
        // Same sign convention: positive slope at x = 0.
        let sign = if reference(1e-3 * l) > 0.0 { 1.0 } else { -1.0 };
        for i in 0..=40 {
            let x = 2.0 * l * i as f64 / 40.0;
            let e = sign * scale * reference(x);
            // 1e-8 of the amplitude: the reference normalisation's quadrature error.
            assert!(
                (mode.shape(x) - e).abs() < 1e-8 * scale,
                "mode {} at x = {x}: {} vs {e}",
                n + 1,
                mode.shape(x)
            );
        }
    }
}

/// Consistent-mass Hermite-cubic FE of N equal pinned spans, assembled here as an independent
/// check; returns the first `count` ω [rad/s] and mode shapes at the nodes.
fn hermite_fe_modes(
    beam: &ContinuousBeam,
    elements_per_span: usize,
    count: usize,
) -> (Vec<f64>, Vec<Vec<f64>>) {
    use nalgebra::{DMatrix, SymmetricEigen};
    let ne = elements_per_span * beam.spans;
    let h = beam.span_length / elements_per_span as f64;
    let ndof = 2 * (ne + 1);
    let (ei, m) = (beam.flexural_rigidity, beam.mass_per_length);
    let ke = [
        [12.0, 6.0 * h, -12.0, 6.0 * h],
        [6.0 * h, 4.0 * h * h, -6.0 * h, 2.0 * h * h],
        [-12.0, -6.0 * h, 12.0, -6.0 * h],
        [6.0 * h, 2.0 * h * h, -6.0 * h, 4.0 * h * h],
    ];
    let me = [
        [156.0, 22.0 * h, 54.0, -13.0 * h],
        [22.0 * h, 4.0 * h * h, 13.0 * h, -3.0 * h * h],
        [54.0, 13.0 * h, 156.0, -22.0 * h],
        [-13.0 * h, -3.0 * h * h, -22.0 * h, 4.0 * h * h],
    ];
    let mut k = DMatrix::<f64>::zeros(ndof, ndof);
    let mut mm = DMatrix::<f64>::zeros(ndof, ndof);
    for e in 0..ne {
        for i in 0..4 {
            for j in 0..4 {
                k[(2 * e + i, 2 * e + j)] += ei / h.powi(3) * ke[i][j];
                mm[(2 * e + i, 2 * e + j)] += m * h / 420.0 * me[i][j];
            }
        }
    }
    // Pinned supports: the deflection DOF of every support node is removed.
    let free: Vec<usize> = (0..ndof)
        .filter(|&d| !(d % 2 == 0 && (d / 2) % elements_per_span == 0))
        .collect();
    let nf = free.len();
    let kf = DMatrix::from_fn(nf, nf, |i, j| k[(free[i], free[j])]);
    let mf = DMatrix::from_fn(nf, nf, |i, j| mm[(free[i], free[j])]);
    // K φ = ω² M φ → L⁻¹ K L⁻ᵀ y = ω² y with M = L Lᵀ.
    let l = mf.cholesky().expect("M is positive definite").l();
    let linv = l.clone().try_inverse().unwrap();
    let a = &linv * kf * linv.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let eig = SymmetricEigen::new(a);
    let mut order: Vec<usize> = (0..nf).collect();
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    let mut omegas = Vec::new();
    let mut shapes = Vec::new();
    for &i in order.iter().take(count) {
        omegas.push(eig.eigenvalues[i].sqrt());
        let y = eig.eigenvectors.column(i).into_owned();
        let phi = linv.transpose() * y;
        let mut full = vec![0.0; ndof];
        for (f, d) in free.iter().enumerate() {
            full[*d] = phi[f];
        }
        // Node deflections only.
        shapes.push((0..=ne).map(|n| full[2 * n]).collect());
    }
    (omegas, shapes)
}

#[test]
fn two_to_six_span_modes_agree_with_an_independent_hermite_fe_model() {
    // Reference: an independent consistent-mass Hermite FE model assembled in this test. Its
    // relative frequency error is (a h/l)⁴/1440 to leading order, so halving the element size
    // must divide the error by ≈ 16, and with 16 elements per span each of the first 3N
    // frequencies must lie within twice that leading term, (a/16)⁴/720, above the exact one.
    // All 3N modes of the first three bands, N = 2 … 6: none is missed or duplicated in the
    // clusters of N close roots per band.
    for spans in [2, 3, 4, 5, 6] {
        let beam = ContinuousBeam::new(spans, 25.0, 5.0e10, 1.5e4).unwrap();
        let count = 3 * spans;
        let exact = continuous_beam_modes(&beam, count).unwrap();
        let (coarse, _) = hermite_fe_modes(&beam, 8, count);
        let (fine, shapes) = hermite_fe_modes(&beam, 16, count);
        for n in 0..count {
            let w = exact[n].angular_frequency;
            let e_coarse = (coarse[n] - w) / w;
            let e_fine = (fine[n] - w) / w;
            assert!(e_fine > 0.0, "a consistent-mass FE bounds ω from above");
            let bound = (exact[n].frequency_parameter / 16.0).powi(4) / 720.0;
            assert!(
                e_fine < bound,
                "{spans} spans, mode {}: {e_fine} > {bound}",
                n + 1
            );
            let rate = e_coarse / e_fine;
            assert!(
                (12.0..20.0).contains(&rate),
                "{spans} spans, mode {}: error ratio {rate} (expected ≈ 16)",
                n + 1
            );
            // Mode shapes at the nodes: MAC ≥ 1 − 1e-8 (shape error is O(h⁴) too).
            let xs: Vec<f64> = (0..shapes[n].len())
                .map(|i| beam.span_length / 16.0 * i as f64)
                .collect();
            let phi: Vec<f64> = xs.iter().map(|&x| exact[n].shape(x)).collect();
            let dot: f64 = phi.iter().zip(&shapes[n]).map(|(a, b)| a * b).sum();
            let na: f64 = phi.iter().map(|a| a * a).sum();
            let nb: f64 = shapes[n].iter().map(|b| b * b).sum();
            let mac = dot * dot / (na * nb);
            assert!(mac > 1.0 - 1e-8, "{spans} spans, mode {}: MAC {mac}", n + 1);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Statics
// ---------------------------------------------------------------------------------------------

#[test]
fn two_span_static_load_factors_are_23_over_1536_and_13_over_64() {
    // Reference: docs/verification.md §3 (three-moment equation, M_B = −3Pl/32).
    let (l1, l2) = static_load_factors(2, 0.5, 0.5).unwrap();
    // Exact rational arithmetic up to a few roundings.
    assert!((l1 - 23.0 / 1536.0).abs() < 1e-16);
    assert!((l2 - 13.0 / 64.0).abs() < 1e-15);
    let (_, m_b) = static_load_factors(2, 1.0, 0.5).unwrap();
    assert!((m_b + 3.0 / 32.0).abs() < 1e-15);
}

#[test]
fn static_deflection_equals_its_modal_series() {
    // Reference: the modal expansion of the flexibility, w(x; x_P) = −P Σ φₙ(x)φₙ(x_P)/ωₙ²,
    // independent of the three-moment solution. With K modes on N spans the series stops near
    // j = K/N half-waves per span; as for Frýba's series the tail is below
    // (96/π⁴) Σ_{j>K/N} j⁻⁴ v₀ < (96/π⁴)(N/K)³/3 v₀, and the tolerance is twice that.
    let k = 300;
    for spans in [1, 3, 4] {
        let beam = ContinuousBeam::new(spans, 20.0, 3.24e10, 2.0e4).unwrap();
        let modes = continuous_beam_modes(&beam, k).unwrap();
        let tail = 2.0 * 96.0 / PI.powi(4) * (spans as f64 / k as f64).powi(3) / 3.0;
        for &(x, xp) in &[(10.0_f64, 10.0_f64), (7.0, 31.0), (33.0, 12.5)] {
            let (x, xp) = (x.min(beam.total_length()), xp.min(beam.total_length()));
            let series: f64 = -modes
                .iter()
                .map(|m| m.shape(x) * m.shape(xp) / m.angular_frequency.powi(2))
                .sum::<f64>();
            let exact = static_response(&beam, x, xp, 1.0).unwrap().deflection;
            let scale = beam.span_length.powi(3) / beam.flexural_rigidity / 48.0;
            assert!(
                (series - exact).abs() < tail * scale,
                "{spans} spans, x = {x}, xp = {xp}: {series} vs {exact}"
            );
        }
    }
}

#[test]
fn two_span_envelope_reference_and_rdm_of_one_mode() {
    // Reference: docs/verification.md §3: envelope 0.01501201 Pl³/EI at 0.4804 l;
    // RDM(1) = 312/(23π²) = 1.374444 (load at the section), 1.37096 (envelope).
    let beam = paper_beam(2);
    let l = beam.span_length;
    let base = DafOptions {
        modes: 1,
        ..DafOptions::default()
    };
    let env = daf_by_modes(&beam, &base).unwrap();
    // Half a unit of the quoted last digit.
    assert!((env.lambda_deflection - 0.01501201).abs() < 5e-9);
    assert!((env.static_deflection_load_position / l - 0.4804).abs() < 5e-5);
    assert!((env.lambda_moment - 13.0 / 64.0).abs() < 1e-12);
    assert!((env.rdm_by_modes[0] - 1.37096).abs() < 5e-6);
    let at = daf_by_modes(
        &beam,
        &DafOptions {
            static_reference: StaticReference::LoadAtSection,
            ..base
        },
    )
    .unwrap();
    let expected = 312.0 / (23.0 * PI * PI);
    assert!((expected - 1.374444).abs() < 5e-7);
    // One mode: the same q₁(t) maximum cancels in the ratio, exact to round-off.
    assert!((at.rdm_by_modes[0] - expected).abs() < 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Moving force
// ---------------------------------------------------------------------------------------------

#[test]
fn resonance_alpha_1_checkpoints_48_over_pi_cubed_and_4_over_pi() {
    // Reference: docs/verification.md §2, α = 1, undamped, t = L/v:
    // w(L/2) = 48/π³ v₀ = 1.5480737 v₀, M(L/2) = 4/π · PL/4 = 1.2732395 PL/4.
    let beam = ContinuousBeam::new(1, 25.0, 4.0e10, 1.8e4).unwrap();
    let l = beam.span_length;
    let p = 1.0e5;
    let v = beam.speed_from_parameter(1.0);
    let v0 = p * l.powi(3) / (48.0 * beam.flexural_rigidity);
    let history = section_history(
        &beam,
        &MovingForce { force: p, speed: v },
        0.0,
        25,
        l / 2.0,
        &[0.5 * l / v, l / v],
    )
    .unwrap();
    let (w, m) = (history.deflection[1], history.bending_moment[1]);
    // The same through the per-mode API.
    let (w2, m2) = modal_sum(&beam, 25, 0.0, v, p, l / 2.0, l / v);
    assert!((w - w2).abs() < 1e-12 * v0 && (m - m2).abs() < 1e-12 * p * l);
    // At t = L/v every mode but the first vanishes exactly: round-off only (1e-9).
    assert!((-w / v0 - 48.0 / PI.powi(3)).abs() < 1e-9, "{}", -w / v0);
    assert!(
        (m / (p * l / 4.0) - 4.0 / PI).abs() < 1e-9,
        "{}",
        m / (p * l / 4.0)
    );
    assert!((48.0 / PI.powi(3) - 1.5480737).abs() < 5e-8);
    assert!((4.0 / PI - 1.2732395).abs() < 5e-8);
    // These are the maxima while the load is on the beam: the deflection DAF is 48/π³.
    let table = daf_by_modes(
        &beam,
        &DafOptions {
            speed: v,
            damping_ratio: 0.0,
            modes: 10,
            ..DafOptions::default()
        },
    )
    .unwrap();
    assert!((table.alpha - 1.0).abs() < 1e-14);
    for k in 1..=10 {
        // Maximum at the end of the window, found to the sampling/refinement accuracy 1e-8.
        assert!(
            (table.daf_deflection_by_modes[k - 1] - 48.0 / PI.powi(3)).abs() < 1e-8,
            "K = {k}: {}",
            table.daf_deflection_by_modes[k - 1]
        );
        assert!((table.time_of_max_deflection[k - 1] - l / v).abs() < 1e-6 * l / v);
    }
}

#[test]
fn frýba_series_equals_the_exact_modal_response() {
    // Reference: docs/verification.md §2, Frýba's undamped series, same number of terms.
    let beam = ContinuousBeam::new(1, 30.0, 6.0e10, 2.2e4).unwrap();
    let l = beam.span_length;
    let v = beam.speed_from_parameter(0.3);
    let v0 = l.powi(3) / (48.0 * beam.flexural_rigidity);
    for &t in &[0.1 * l / v, 0.37 * l / v, 0.8 * l / v, l / v] {
        for &x in &[0.25 * l, 0.5 * l, 0.9 * l] {
            let (w, _) = modal_sum(&beam, 15, 0.0, v, 1.0, x, t);
            let f = simply_supported_deflection(
                l,
                beam.flexural_rigidity,
                beam.mass_per_length,
                1.0,
                v,
                x,
                t,
                15,
            );
            // Two exact evaluations of the same 15-term series: round-off (1e-12 of v₀).
            assert!(
                (-w - f).abs() < 1e-12 * v0,
                "t = {t}, x = {x}: {} vs {f}",
                -w
            );
        }
    }
}

#[test]
fn alpha_one_half_the_whole_beam_passes_through_zero_at_t_equals_l_over_v() {
    // Reference: docs/verification.md §2, α = 0.5.
    let beam = ContinuousBeam::new(1, 20.0, 3.0e10, 2.0e4).unwrap();
    let l = beam.span_length;
    let v = beam.speed_from_parameter(0.5);
    let v0 = l.powi(3) / (48.0 * beam.flexural_rigidity);
    for i in 1..10 {
        let x = l * i as f64 / 10.0;
        let (w, _) = modal_sum(&beam, 20, 0.0, v, 1.0, x, l / v);
        // sin(jπ) = sin(2j²π) = 0 for every mode: round-off only.
        assert!(w.abs() < 1e-10 * v0, "x = {x}: {}", w / v0);
    }
}

#[test]
fn damped_sine_modes_follow_the_corrected_eq_8() {
    // Reference: the paper's Eq. 8 (with the forced −2ζβ cos Ωt term), for the sine modes of a
    // simply supported beam: q = −φ̂ f₀ H(t), φ̂ = √(2/(m̄L)).
    let beam = ContinuousBeam::new(1, 20.0, 3.0e10, 2.0e4).unwrap();
    let l = beam.span_length;
    let v = 30.0;
    let modes = continuous_beam_modes(&beam, 4).unwrap();
    let amp = (2.0 / (beam.mass_per_length * l)).sqrt();
    for (j, mode) in modes.iter().enumerate() {
        let big_omega = (j + 1) as f64 * PI * v / l;
        let r = ModalMovingForce::new(mode, 0.05, v).unwrap();
        for &t in &[0.05, 0.2, 0.45, 0.66] {
            let q = r.displacement(t);
            // Modal force −φ(vt) = −φ̂ sin Ωt.
            let e = -amp * sine_mode_response(mode.angular_frequency, 0.05, big_omega, t);
            // Same closed form, two derivations: round-off relative to the static modal
            // amplitude φ̂/ω².
            let scale = amp / mode.angular_frequency.powi(2);
            assert!((q - e).abs() < 1e-11 * scale, "mode {}, t = {t}", j + 1);
        }
    }
}

#[test]
fn static_limit_daf_tends_to_one() {
    // (The static-corrected series starts from the exact statics, so it tends to 1 for the
    // moment too, whatever K.)
    // Reference: docs/verification.md §2, α → 0: DAF → 1. The deflection series converges
    // fast (tail O(K⁻³)); the K-mode moment tends to the K-mode quasi-static series, which
    // itself converges only as O(1/K), so it is compared with that series.
    let beam = ContinuousBeam::new(2, 20.0, 3.24e10, 2.0e4).unwrap();
    let l = beam.span_length;
    let k = 20;
    let v = beam.speed_from_parameter(1e-3);
    let table = daf_by_modes(
        &beam,
        &DafOptions {
            speed: v,
            damping_ratio: 0.05,
            modes: k,
            output_times: 4001,
            ..DafOptions::default()
        },
    )
    .unwrap();
    // Dynamic part O(α) = 1e-3 plus the deflection truncation (< 1e-4 at K = 20).
    assert!(
        (table.daf_deflection_by_modes[k - 1] - 1.0).abs() < 2e-3,
        "{}",
        table.daf_deflection_by_modes[k - 1]
    );
    // K-mode quasi-static moment at l/2 over load positions.
    let modes = continuous_beam_modes(&beam, k).unwrap();
    let quasi_static = (0..=4000)
        .map(|i| {
            let xp = 2.0 * l * i as f64 / 4000.0;
            modes
                .iter()
                .map(|m| {
                    beam.flexural_rigidity * m.curvature(l / 2.0) * -m.shape(xp)
                        / m.angular_frequency.powi(2)
                })
                .sum::<f64>()
        })
        .fold(f64::NEG_INFINITY, f64::max);
    let expected = quasi_static / table.static_moment;
    assert!(
        (table.daf_moment_by_modes[k - 1] - expected).abs() < 2e-3,
        "{} vs {expected}",
        table.daf_moment_by_modes[k - 1]
    );
    // Static-corrected moment: dynamic part O(α) only.
    for kk in [1, 5, k] {
        let c = table.daf_moment_corrected_by_modes[kk - 1];
        assert!((c - 1.0).abs() < 2e-3, "K = {kk}: {c}");
    }
}

#[test]
fn free_vibration_window_can_only_raise_the_maximum() {
    // The window option: the maximum over a longer window is never smaller.
    let beam = paper_beam(3);
    let base = DafOptions {
        modes: 8,
        ..DafOptions::default()
    };
    let on = daf_by_modes(&beam, &base).unwrap();
    let free = daf_by_modes(
        &beam,
        &DafOptions {
            window: MaximumWindow::WithFreeVibration { duration: 1.0 },
            ..base
        },
    )
    .unwrap();
    // The two runs sample different time grids; each maximum is refined by golden-section
    // search to a value error of ≈ 1e-7 of the variation between samples (≈ 1e-3 here), so
    // 1e-9 bounds the difference in the maxima the two grids find (observed ≤ 5e-12).
    for k in 0..8 {
        assert!(free.daf_deflection_by_modes[k] >= on.daf_deflection_by_modes[k] - 1e-9);
        assert!(free.daf_moment_by_modes[k] >= on.daf_moment_by_modes[k] - 1e-9);
    }
    // Above α ≈ 1 the peak of a simply supported beam comes after the force has left
    // (Frýba), and then the window must find it.
    let beam = ContinuousBeam::new(1, 20.0, 3.24e10, 2.0e4).unwrap();
    let fast = DafOptions {
        speed: beam.speed_from_parameter(1.5),
        damping_ratio: 0.0,
        modes: 3,
        ..DafOptions::default()
    };
    let on = daf_by_modes(&beam, &fast).unwrap();
    let free = daf_by_modes(
        &beam,
        &DafOptions {
            window: MaximumWindow::WithFreeVibration { duration: 1.0 },
            ..fast
        },
    )
    .unwrap();
    // Mode 1 alone, undamped: after the force leaves at T = L/v the free amplitude is
    // 2 f₀ β |cos(ωT/2)| / (ω² |1 − β²|), ωT = π/β (from q = f₀[sin Ωt − β sin ωt]/(ω²(1 − β²))),
    // so DAF_u(1) = (96/π⁴) · 2β |cos(π/(2β))| / |1 − β²| = (96/π⁴) · 1.2 at β = 1.5.
    let expected = 96.0 / PI.powi(4) * 1.2;
    // Refined maximum of a sampled sinusoid (≈ 190 samples per period): 1e-9.
    assert!((free.daf_deflection_by_modes[0] - expected).abs() < 1e-9);
    assert!(free.time_of_max_deflection[0] > free.crossing_time);
    assert!(on.daf_deflection_by_modes[0] < expected - 0.1);
}

#[test]
fn deflection_daf_settles_within_a_few_modes_while_moment_daf_converges_slowly() {
    // Reference: docs/verification.md §2 (deflection converges within 3–5 modes, the moment only
    // as O(1/K)) and §16 (paper: deflection by mode 10, moment up to 40).
    // An N-span beam has N modes per frequency band, so "a few modes" means a few bands: 3N.
    // Paper-like case: 20 m spans, f₁ = 5.0 Hz, 80 km/h (α = 0.111), ζ = 0.05, section l/2.
    for spans in [2, 4] {
        let beam = paper_beam(spans);
        let table = daf_by_modes(
            &beam,
            &DafOptions {
                modes: 50,
                // 500 samples + refinement: the maxima agree with 1000 samples to 1e-5.
                output_times: 500,
                ..DafOptions::default()
            },
        )
        .unwrap();
        let du = &table.daf_deflection_by_modes;
        let dm = &table.daf_moment_by_modes;
        let (last_u, last_m) = (du[49], dm[49]);
        let settled = 3 * spans;
        for k in settled..=50 {
            // Deflection: within 0.5 % of the 50-mode value from K = 3N on (observed 0.07 % for
            // two spans, 0.31 % for four).
            assert!(
                (du[k - 1] / last_u - 1.0).abs() < 5e-3,
                "{spans} spans, K = {k}: {}",
                du[k - 1]
            );
        }
        // Moment: still more than 5 % below the 50-mode value at K = 3N (observed 9 %) …
        assert!(
            dm[settled - 1] / last_m < 0.95,
            "{} vs {last_m}",
            dm[settled - 1]
        );
        // … and still rising at K = 50: the moment series converges as O(1/K) (the static
        // moment has a kink under the load), its change over the last 10 modes exceeds the
        // deflection's by more than 10×.
        let change = |v: &[f64]| (v[49] - v[39]).abs() / v[49];
        assert!(dm[49] > dm[39]);
        assert!(
            change(dm) > 10.0 * change(du),
            "{} vs {}",
            change(dm),
            change(du)
        );
    }
}

/// A long free-vibration window samples the crossing as finely as a short one (issue 17,
/// defect 2: 1000 s left two of the 1000 instants on the crossing and gave DAF_u 0.057): with
/// ζ = 0.05 the response has decayed long before 1000 s, so the DAFs equal the 2 s window's to
/// the golden-section refinement (1e-7); a window beyond MAX_OUTPUT_INSTANTS is refused.
#[test]
fn a_long_free_vibration_window_keeps_the_crossing_sampled() {
    use vbi::analytical::AnalyticalError;
    let beam = paper_beam(2);
    let window = |duration: f64| DafOptions {
        window: MaximumWindow::WithFreeVibration { duration },
        modes: 6,
        ..DafOptions::default()
    };
    let short = daf_by_modes(&beam, &window(2.0)).unwrap();
    let long = daf_by_modes(&beam, &window(1000.0)).unwrap();
    for k in 0..6 {
        let (a, b) = (
            short.daf_deflection_by_modes[k],
            long.daf_deflection_by_modes[k],
        );
        assert!((a - b).abs() < 1e-7, "K = {}: {a} against {b}", k + 1);
        let (a, b) = (short.daf_moment_by_modes[k], long.daf_moment_by_modes[k]);
        assert!((a - b).abs() < 1e-7, "K = {}: {a} against {b}", k + 1);
    }
    assert!(long.daf_deflection_by_modes[5] > 1.0);
    assert!(matches!(
        daf_by_modes(&beam, &window(1e6)),
        Err(AnalyticalError::FreeVibrationTooLong { .. })
    ));
}

/// Issue 46, item 4: the paper's §2 at an interior support. The static deflection is zero there,
/// so the table's deflection DAF is undefined (its series empty) and the hogging moment's DAF is
/// given. References: the three-moment equation of two equal spans (Timoshenko & Young, the
/// source of §3's M_B = −3Pl/32), M_B(a) = −Pa(l² − a²)/(4l²) for the force at a in span 1,
/// whose largest magnitude, at a = l/√3, is Pl/(6√3) = 0.0962250 Pl: the envelope reference
/// λ₂ = |M_s|/l; and the continuity of the moment along the beam: the static-corrected hogging
/// DAF at the support equals the one a micrometre beside it (where the deflection is not yet a
/// zero and the section is an ordinary one) to 1e-6.
#[test]
fn the_hogging_moment_daf_at_an_interior_support_has_the_three_moment_static_reference() {
    let beam = paper_beam(2);
    let l = beam.span_length;
    let options = DafOptions {
        modes: 20,
        section: Some(l),
        ..DafOptions::default()
    };
    let support = daf_by_modes(&beam, &options).expect("an interior support is a section");
    assert!(!support.deflection_defined);
    assert!(support.daf_deflection_by_modes.is_empty());
    assert!(support.rdm_by_modes.is_empty());
    assert!(support.rdm_corrected_by_modes.is_empty());
    assert_eq!(support.daf_moment_by_modes.len(), 20);
    assert_eq!(support.daf_moment_corrected_by_modes.len(), 20);
    let closed_form = 1.0 / (6.0 * 3.0_f64.sqrt());
    assert!((closed_form - 0.0962250).abs() < 5e-8);
    assert!(
        (support.lambda_moment - closed_form).abs() < 1e-9,
        "λ₂ = {}",
        support.lambda_moment
    );
    // At l/√3 in span 1, or at its mirror image in span 2 (the same magnitude).
    let a = support.static_moment_load_position;
    let from_the_end = a.min(2.0 * l - a);
    assert!(
        (from_the_end - l / 3.0_f64.sqrt()).abs() < 1e-4 * l,
        "load at {a} m"
    );
    assert!(support.static_moment < 0.0, "a hogging moment");
    let beside = daf_by_modes(
        &beam,
        &DafOptions {
            section: Some(l * (1.0 - 1e-7)),
            ..options
        },
    )
    .unwrap();
    assert!(beside.deflection_defined);
    let (at, near) = (
        support.daf_moment_corrected_by_modes[19],
        beside.daf_moment_corrected_by_modes[19],
    );
    assert!(at > 1.0 && at < 1.5, "hogging DAF {at}");
    assert!(
        (at - near).abs() < 1e-6,
        "{at} at the support, {near} beside it"
    );
}
