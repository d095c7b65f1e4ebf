//! Verification of the `solver` and `analysis` stages against closed forms and a published case.
//!
//! The bridge in every test is a simply supported Euler–Bernoulli beam built here from its closed
//! form (docs/verification.md §1), so these tests do not depend on the FE stage:
//!
//! ```text
//!        P (or sprung mass) →  v
//!        ↓
//!   ▲━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━▲      one deck line, nodes every 0.5 m (or Δx)
//!   0                L/2            L      φₙ = √(2/(m̄L)) sin(nπx/L), ωₙ = (nπ/L)²√(EI/m̄)
//! ```
//!
//! Stations: mid-span and quarter-span, with modal deflection φₙ(x) and modal moment EI·φₙ″(x);
//! influence lines are the exact static ones of the beam.

use nalgebra::DMatrix;
use std::f64::consts::PI;

use vbi::analysis::{analyse, modal_contributions, station_response, AnalysisOptions, DafReport};
use vbi::deck::{DeckField, DeckGeometry, DeckLine};
use vbi::influence::InfluenceLines;
use vbi::modal::{ModalBasis, Mode, ModeKind, Quantity, Station, StationTarget};
use vbi::road::RoadProfile;
use vbi::solver::{simulate, Crossing, ResponseHistory, SolverOptions};
use vbi::vehicle::{ContactKind, TyreContact, VehicleModel};

/// Beam of the VBI-2D verification case (docs/verification.md §9).
const SPAN: f64 = 25.0;
const YOUNG: f64 = 3.5e10;
const INERTIA: f64 = 1.3901;
const MASS_PER_LENGTH: f64 = 18358.0;
const GRAVITY: f64 = 9.81;

pub(super) struct Beam {
    length: f64,
    flexural_rigidity: f64,
    mass_per_length: f64,
    /// Spacing of the deck nodes [m] (0.5 m unless asked otherwise): between nodes the solver
    /// interpolates each sine mode by a Hermite cubic, whose relative error is about
    /// (kπΔx/L)⁴/384 for mode k.
    node_spacing: f64,
}

impl Beam {
    pub(super) fn vbi2d() -> Beam {
        Beam {
            length: SPAN,
            flexural_rigidity: YOUNG * INERTIA,
            mass_per_length: MASS_PER_LENGTH,
            node_spacing: 0.5,
        }
    }

    /// The same beam with deck nodes every `spacing` metres (a divisor of the span).
    pub(super) fn with_node_spacing(self, spacing: f64) -> Beam {
        Beam {
            node_spacing: spacing,
            ..self
        }
    }

    /// The deck node positions [m], from 0 to L.
    fn nodes(&self) -> Vec<f64> {
        (0..=(self.length / self.node_spacing).round() as usize)
            .map(|i| i as f64 * self.node_spacing)
            .collect()
    }

    fn omega(&self, n: usize) -> f64 {
        (n as f64 * PI / self.length).powi(2)
            * (self.flexural_rigidity / self.mass_per_length).sqrt()
    }

    fn station_positions(&self) -> [(String, f64); 2] {
        [
            ("mid".into(), 0.5 * self.length),
            ("quarter".into(), 0.25 * self.length),
        ]
    }

    /// Mass-normalised sine modes with slopes at the deck nodes and values at the stations.
    pub(super) fn basis(&self, modes: usize, damping_ratio: f64) -> ModalBasis {
        let l = self.length;
        let nodes = self.nodes();
        let amp = (2.0 / (self.mass_per_length * l)).sqrt();
        let a = |k: usize| k as f64 * PI / l;
        let mut deck_deflection = Vec::new();
        let mut deck_slope = Vec::new();
        for &x in &nodes {
            for k in 1..=modes {
                deck_deflection.push(amp * (a(k) * x).sin());
                deck_slope.push(amp * a(k) * (a(k) * x).cos());
            }
        }
        let mut station_deflection = Vec::new();
        let mut station_moment = Vec::new();
        for (_, x) in self.station_positions() {
            for k in 1..=modes {
                station_deflection.push(amp * (a(k) * x).sin());
                // Sagging moment M = EI·w″ for upward-positive w.
                station_moment.push(-self.flexural_rigidity * a(k) * a(k) * amp * (a(k) * x).sin());
            }
        }
        ModalBasis {
            modes: (1..=modes)
                .map(|k| Mode {
                    circular_frequency: self.omega(k),
                    damping_ratio,
                    kind: ModeKind::VerticalBending,
                    residual: 0.0,
                })
                .collect(),
            deck: self.deck(),
            deck_deflection,
            deck_slope,
            stations: self.stations(),
            station_deflection,
            station_moment,
            station_force: Vec::new(),
            dof_count: 0,
            check_modes: None,
        }
    }

    fn deck(&self) -> DeckGeometry {
        DeckGeometry {
            lines: vec![DeckLine {
                lateral_position: 0.0,
                node_positions: self.nodes(),
                first_node: 0,
            }],
            length: self.length,
        }
    }

    fn stations(&self) -> Vec<Station> {
        self.station_positions()
            .into_iter()
            .map(|(name, position)| Station {
                name,
                position,
                target: StationTarget::Girder(0),
                over_support: false,
                support: false,
            })
            .collect()
    }

    /// Exact static influence lines (unit downward load): deflection by Maxwell's reciprocity,
    /// the deflected shape under a unit load at the station; moment from statics.
    pub(super) fn influence(&self) -> InfluenceLines {
        let (l, ei) = (self.length, self.flexural_rigidity);
        let deck = self.deck();
        let xs = deck.lines[0].node_positions.clone();
        let mut deflection = Vec::new();
        let mut moment_left = Vec::new();
        let mut moment_right = Vec::new();
        for (_, s) in self.station_positions() {
            let (a, b) = (s, l - s);
            let (w, dw): (Vec<f64>, Vec<f64>) = xs
                .iter()
                .map(|&x| {
                    if x <= s {
                        (
                            -b * x * (l * l - b * b - x * x) / (6.0 * ei * l),
                            -b * (l * l - b * b - 3.0 * x * x) / (6.0 * ei * l),
                        )
                    } else {
                        let u = l - x;
                        (
                            -a * u * (l * l - a * a - u * u) / (6.0 * ei * l),
                            a * (l * l - a * a - 3.0 * u * u) / (6.0 * ei * l),
                        )
                    }
                })
                .unzip();
            deflection.push(DeckField {
                deflection: w,
                slope: dw,
            });
            // Left element: exact for loads right of the station, M = s(L − x)/L.
            moment_left.push(DeckField {
                deflection: xs.iter().map(|&x| s * (l - x) / l).collect(),
                slope: vec![-s / l; xs.len()],
            });
            // Right element: exact for loads left of the station, M = x(L − s)/L.
            moment_right.push(DeckField {
                deflection: xs.iter().map(|&x| x * (l - s) / l).collect(),
                slope: vec![(l - s) / l; xs.len()],
            });
        }
        InfluenceLines {
            deck,
            stations: self.stations(),
            deflection,
            moment_left,
            moment_right,
            force_left: Vec::new(),
            force_right: Vec::new(),
        }
    }
}

/// A constant moving force P [N] (no DOFs).
pub(super) fn moving_force(load: f64) -> VehicleModel {
    VehicleModel {
        name: "moving_force".into(),
        dof_names: Vec::new(),
        mass_matrix: DMatrix::zeros(0, 0),
        damping_matrix: DMatrix::zeros(0, 0),
        stiffness_matrix: DMatrix::zeros(0, 0),
        contacts: vec![TyreContact {
            longitudinal_offset: 0.0,
            lateral_offset: 0.0,
            static_load: load,
            kind: ContactKind::Force,
        }],
        pitch_load_per_acceleration: Vec::new(),
    }
}

/// One sprung mass m on a spring k (the VBI-2D case: m = 5750 kg, k = 1.595e6 N/m, c = 0).
pub(super) fn sprung_mass(mass: f64, stiffness: f64) -> VehicleModel {
    VehicleModel {
        name: "sprung_mass".into(),
        dof_names: vec!["bounce".into()],
        mass_matrix: DMatrix::from_element(1, 1, mass),
        damping_matrix: DMatrix::zeros(1, 1),
        stiffness_matrix: DMatrix::from_element(1, 1, stiffness),
        contacts: vec![TyreContact {
            longitudinal_offset: 0.0,
            lateral_offset: 0.0,
            static_load: mass * GRAVITY,
            kind: ContactKind::Tyre {
                stiffness,
                damping: 0.0,
                coupling: vec![(0, 1.0)],
            },
        }],
        pitch_load_per_acceleration: Vec::new(),
    }
}

pub(super) fn smooth() -> RoadProfile {
    RoadProfile::smooth(-100.0, 200.0)
}

fn run(basis: &ModalBasis, crossing: &Crossing, time_step: Option<f64>) -> ResponseHistory {
    let options = SolverOptions {
        time_step,
        ..SolverOptions::default()
    };
    simulate(basis, crossing, &options).expect("simulation runs")
}

fn report(beam: &Beam, basis: &ModalBasis, history: &ResponseHistory) -> DafReport {
    analyse(
        basis,
        &beam.influence(),
        history,
        &AnalysisOptions::default(),
    )
    .expect("analysis runs")
}

/// Frýba's moving force on a simply supported beam, mid-span deflection and sagging moment over
/// the whole history (load on the beam, then free vibration), as multiples of v₀ = PL³/48EI and
/// PL/4, from the first `modes` terms (docs/verification.md §2). Mode j's forced part is
/// A_j[sin(jΩt) − (α/j) sin(ω_j t)]; at resonance (j² = α²) its limit; after t = L/v each mode
/// vibrates freely from its state at L/v. Returns the maxima of −w/v₀ and M/(PL/4) on a fine
/// time grid.
fn fryba_maxima(alpha: f64, modes: usize, beam: &Beam) -> (f64, f64) {
    let omega1 = beam.omega(1);
    let big_omega = alpha * omega1;
    let t_exit = PI / big_omega;
    let t_end = t_exit + 2.0 * 2.0 * PI / omega1;
    // Mode j's displacement (per 96/π⁴ v₀) and velocity at time t ≤ L/v.
    let forced = |j: f64, t: f64| -> (f64, f64) {
        let wj = j * j * omega1;
        if (j * j - alpha * alpha).abs() < 1e-9 {
            // Resonant limit of [sin(Ωt) − α sin(Ωt/α)]/(1 − α²) at α = 1 (j = 1):
            // [sin(Ωt) − Ωt cos(Ωt)]/2.
            let p = big_omega * t;
            ((p.sin() - p * p.cos()) / 2.0, big_omega * p * p.sin() / 2.0)
        } else {
            let c = 1.0 / (j * j * (j * j - alpha * alpha));
            (
                c * ((j * big_omega * t).sin() - alpha / j * (wj * t).sin()),
                c * (j * big_omega * (j * big_omega * t).cos() - alpha / j * wj * (wj * t).cos()),
            )
        }
    };
    // 8000 samples over at most 12 T₁: the sampled maximum is within (ω₁δt)²/8 ≈ 1e-5 of the
    // true one.
    let samples = 8_000;
    let (mut max_w, mut max_m) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
    for i in 0..=samples {
        let t = t_end * i as f64 / samples as f64;
        let (mut w, mut m) = (0.0, 0.0);
        // Even modes vanish at mid-span.
        for jn in (1..=modes).step_by(2) {
            let j = jn as f64;
            let shape = (j * PI / 2.0).sin();
            if shape.abs() < 1e-12 {
                continue;
            }
            let y = if t <= t_exit {
                forced(j, t).0
            } else {
                let (y0, v0) = forced(j, t_exit);
                let wj = j * j * omega1;
                let tau = t - t_exit;
                y0 * (wj * tau).cos() + v0 / wj * (wj * tau).sin()
            };
            w += 96.0 / PI.powi(4) * y * shape;
            // Frýba's w is downward positive, so the sagging moment is M = −EI w″
            // = EI v₀ (96/π⁴) Σ y_j (jπ/L)² sin(jπx/L); with v₀ = PL³/48EI,
            // M/(PL/4) = (8/π⁴) Σ (jπ)² y_j sin(jπx/L).
            m += 8.0 / PI.powi(4) * (j * PI).powi(2) * y * shape;
        }
        max_w = max_w.max(w);
        max_m = max_m.max(m);
    }
    (max_w, max_m)
}

#[test]
fn moving_force_deflection_daf_matches_fryba_closed_form_for_speed_parameters_up_to_one() {
    // Reference: docs/verification.md §2, Frýba closed form (all modes kept in both).
    let beam = Beam::vbi2d();
    let modes = 10;
    let basis = beam.basis(modes, 0.0);
    let f1 = beam.omega(1) / (2.0 * PI);
    let load = 1.0e5;
    for alpha in [0.05, 0.1, 0.25, 0.5, 0.75, 1.0] {
        let speed = alpha * 2.0 * f1 * beam.length;
        let mut crossing = Crossing::new(moving_force(load), smooth(), speed);
        crossing.free_vibration_duration = Some(2.0 / f1);
        // The step resolves mode 10 with 20 steps per period (T₁/2000): Newmark's period error
        // (ωΔt)²/12 is 8e-3 on mode 10 and 1e-6 on mode 1. (The default step would leave the
        // modes above 5 × their passage rate quasi-static, with a note; the closed form keeps
        // every mode's dynamics, so the comparison resolves them all.)
        let top = basis.modes[modes - 1].frequency_hz();
        let history = run(&basis, &crossing, Some(1.0 / (20.0 * top)));
        assert!(history.warnings.is_empty());
        let daf = report(&beam, &basis, &history)
            .entry(0, Quantity::Deflection)
            .unwrap()
            .converged
            .daf
            .unwrap();
        // Deflection against the converged series (61 terms: the tail is below 1e-6).
        let (expected, _) = fryba_maxima(alpha, 61, &beam);
        // Moment against the series with the same modes (docs/verification.md §2: a plain modal
        // moment converges slowly, so compare like with like).
        let daf_m = report(&beam, &basis, &history)
            .entry(0, Quantity::BendingMoment)
            .unwrap()
            .paper
            .daf
            .unwrap();
        let (_, expected_m) = fryba_maxima(alpha, modes, &beam);
        // 0.5 % (the issue's tolerance); the expected error is the 10-mode truncation (~1e-4)
        // and the time-grid sampling of the maximum (~1e-5).
        assert!(
            (daf / expected - 1.0).abs() < 0.005,
            "alpha = {alpha}: DAF {daf} vs Frýba {expected}"
        );
        // 0.5 %: the same time-grid and period errors, plus the under-resolved free vibration of
        // the highest modes, whose amplitude is α/j³ of the static moment.
        assert!(
            (daf_m / expected_m - 1.0).abs() < 0.005,
            "alpha = {alpha}: moment DAF {daf_m} vs {modes}-mode series {expected_m}"
        );
        if alpha == 1.0 {
            // The resonant checkpoint 48/π³ is the maximum while the load is on the beam.
            assert!(expected >= 48.0 / PI.powi(3) - 1e-6);
        }
    }
}

#[test]
fn vbi2d_sprung_mass_minimum_mid_span_displacement_matches_the_reference() {
    // Reference: docs/verification.md §11 (VBI-2D, V01_Analytical_Verification_Examples.m):
    // minimum mid-span displacement −4.185451e-4 m at t = 0.436 s; 100 modes, Δt = 1 ms.
    let beam = Beam::vbi2d();
    let basis = beam.basis(100, 0.0);
    let crossing = Crossing::new(sprung_mass(5750.0, 1.595e6), smooth(), 25.0);
    let history = run(&basis, &crossing, Some(1.0e-3));
    let mid = station_response(&basis, &history, 0, Quantity::Deflection).unwrap();
    let (step, min) =
        mid.iter().copied().enumerate().fold(
            (0, f64::INFINITY),
            |b, (i, w)| if w < b.1 { (i, w) } else { b },
        );
    let reference = -4.185451e-4;
    // 0.5 %: the reference evaluates the coupling at the start of each step and symmetrises a
    // damping block, so a correct solver differs from it by about 0.1 % (docs/verification.md §11).
    assert!(
        (min / reference - 1.0).abs() < 0.005,
        "min {min} vs {reference}"
    );
    assert!(
        (history.time(step) - 0.436).abs() < 0.01,
        "at t = {}",
        history.time(step)
    );
    assert!(history.contact_losses.is_empty());
    // 1 ms under-resolves the high modes of a 100-mode basis: the result says so, naming one.
    assert!(!history.warnings.is_empty());
}

#[test]
fn crawling_speed_gives_a_daf_of_one() {
    // Reference: docs/verification.md §2, checkpoint α → 0: DAF → 1. At v = 0.5 m/s
    // (α = 0.0024) on a smooth road the crossing is quasi-static.
    let beam = Beam::vbi2d();
    let modes = 100;
    let basis = beam.basis(modes, 0.0);
    let crossing = Crossing::new(sprung_mass(5750.0, 1.595e6), smooth(), 0.5);
    let history = run(&basis, &crossing, Some(2.0e-3));
    let report = report(&beam, &basis, &history);
    let daf_u = report
        .entry(0, Quantity::Deflection)
        .unwrap()
        .converged
        .daf
        .unwrap();
    // 0.5 %: the dynamic part is of order α ≈ 0.2 %; modal truncation of deflection is 1e-8.
    assert!((daf_u - 1.0).abs() < 0.005, "deflection DAF {daf_u}");
    // The moment of a modal sum converges as 1/j² (docs/verification.md §2): its quasi-static
    // limit is the 100-mode fraction of the exact PL/4, Σ_{odd j<100} 1/j² / (π²/8).
    let fraction: f64 = (1..modes)
        .step_by(2)
        .map(|j| 1.0 / (j * j) as f64)
        .sum::<f64>()
        / (PI * PI / 8.0);
    let moment = report.entry(0, Quantity::BendingMoment).unwrap();
    let daf_m = moment.paper.daf.unwrap();
    assert!(
        (daf_m / fraction - 1.0).abs() < 0.005,
        "the paper's moment DAF {daf_m} vs {fraction}"
    );
    // The converged (static-corrected) moment has the exact static part: DAF → 1 like the
    // deflection, within the same O(α) dynamic part (0.5 %).
    let converged_m = moment.converged.daf.unwrap();
    assert!(
        (converged_m - 1.0).abs() < 0.005,
        "converged moment DAF {converged_m}"
    );
}

/// Moving mass on the beam, integrated independently by RK4 in modal coordinates:
/// (I + m φφᵀ) q̈ = −Λq − m φ (g + 2v φ′·q̇ + v² φ″·q), the mass following the deck exactly.
/// Returns the minimum mid-span deflection over the crossing and `free` seconds after.
fn moving_mass_minimum(beam: &Beam, modes: usize, mass: f64, speed: f64, free: f64) -> f64 {
    let l = beam.length;
    let amp = (2.0 / (beam.mass_per_length * l)).sqrt();
    let a: Vec<f64> = (1..=modes).map(|k| k as f64 * PI / l).collect();
    let w2: Vec<f64> = (1..=modes).map(|k| beam.omega(k).powi(2)).collect();
    let rhs = |t: f64, q: &[f64], qd: &[f64]| -> Vec<f64> {
        let x = speed * t;
        let mut acc: Vec<f64> = (0..modes).map(|k| -w2[k] * q[k]).collect();
        if x <= l {
            let phi: Vec<f64> = a.iter().map(|ak| amp * (ak * x).sin()).collect();
            let dphi: Vec<f64> = a.iter().map(|ak| amp * ak * (ak * x).cos()).collect();
            let ddphi: Vec<f64> = a.iter().map(|ak| -amp * ak * ak * (ak * x).sin()).collect();
            let conv: f64 = (0..modes)
                .map(|k| 2.0 * speed * dphi[k] * qd[k] + speed * speed * ddphi[k] * q[k])
                .sum();
            let b: Vec<f64> = (0..modes)
                .map(|k| acc[k] - mass * phi[k] * (GRAVITY + conv))
                .collect();
            // Sherman–Morrison: (I + m φφᵀ)⁻¹ b = b − m φ (φ·b)/(1 + m φ·φ).
            let pb: f64 = (0..modes).map(|k| phi[k] * b[k]).sum();
            let pp: f64 = phi.iter().map(|p| p * p).sum();
            let f = mass * pb / (1.0 + mass * pp);
            acc = (0..modes).map(|k| b[k] - phi[k] * f).collect();
        }
        acc
    };
    let dt = 1.0e-5;
    let steps = ((l / speed + free) / dt).round() as usize;
    let mut q = vec![0.0; modes];
    let mut qd = vec![0.0; modes];
    let mut min = 0.0f64;
    for i in 0..steps {
        let t = i as f64 * dt;
        let add = |x: &[f64], y: &[f64], h: f64| -> Vec<f64> {
            x.iter().zip(y).map(|(a, b)| a + h * b).collect()
        };
        let k1v = qd.clone();
        let k1a = rhs(t, &q, &qd);
        let k2v = add(&qd, &k1a, dt / 2.0);
        let k2a = rhs(t + dt / 2.0, &add(&q, &k1v, dt / 2.0), &k2v);
        let k3v = add(&qd, &k2a, dt / 2.0);
        let k3a = rhs(t + dt / 2.0, &add(&q, &k2v, dt / 2.0), &k3v);
        let k4v = add(&qd, &k3a, dt);
        let k4a = rhs(t + dt, &add(&q, &k3v, dt), &k4v);
        for k in 0..modes {
            q[k] += dt / 6.0 * (k1v[k] + 2.0 * k2v[k] + 2.0 * k3v[k] + k4v[k]);
            qd[k] += dt / 6.0 * (k1a[k] + 2.0 * k2a[k] + 2.0 * k3a[k] + k4a[k]);
        }
        let mid: f64 = (0..modes)
            .map(|k| amp * (a[k] * l / 2.0).sin() * q[k])
            .sum();
        min = min.min(mid);
    }
    min
}

#[test]
fn a_very_stiff_sprung_mass_tends_to_the_moving_mass() {
    // Limit: a sprung mass whose spring is far stiffer than the beam (ω_v = 100 ω₁) follows the
    // deck, i.e. becomes a moving mass (with its convective acceleration terms). A heavy mass
    // (11 % of the beam) makes the moving-mass effect large enough to be seen.
    let beam = Beam::vbi2d();
    let modes = 6;
    let basis = beam.basis(modes, 0.0);
    let mass = 1.5e5;
    let stiffness = mass * (100.0 * beam.omega(1)).powi(2);
    let speed = 25.0;
    let free = 0.3;
    let mut crossing = Crossing::new(sprung_mass(mass, stiffness), smooth(), speed);
    crossing.free_vibration_duration = Some(free);
    let history = run(&basis, &crossing, Some(5.0e-5));
    let mid = station_response(&basis, &history, 0, Quantity::Deflection).unwrap();
    let sprung = mid.iter().copied().fold(f64::INFINITY, f64::min);
    let moving_mass = moving_mass_minimum(&beam, modes, mass, speed, free);
    let mut force_crossing = Crossing::new(moving_force(mass * GRAVITY), smooth(), speed);
    force_crossing.free_vibration_duration = Some(free);
    let force_history = run(&basis, &force_crossing, Some(5.0e-5));
    let moving_force = station_response(&basis, &force_history, 0, Quantity::Deflection)
        .unwrap()
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    // The moving mass differs visibly from the moving force, and the stiff sprung mass matches
    // the moving mass within 0.5 %: the residual spring flexibility is (ω₁/ω_v)² = 1e-4 and
    // the time steps resolve both (ω_v Δt = 0.13).
    assert!(
        (moving_mass / moving_force - 1.0).abs() > 0.02,
        "mass {moving_mass} force {moving_force}"
    );
    assert!(
        (sprung / moving_mass - 1.0).abs() < 0.005,
        "sprung {sprung} vs moving mass {moving_mass}"
    );
}

#[test]
fn an_undamped_bridge_keeps_its_energy_after_the_vehicle_leaves() {
    // Newmark with γ = ½ conserves Σ ½(q̇² + ω²q² + (βₖ − ¼)Δt² q̈²) exactly for a linear
    // undamped system (Σ ½(q̇² + ω²q²) for average acceleration, βₖ = ¼; each mode's own
    // period-matched βₖ otherwise: docs/theory.md); after the vehicle leaves, the modes are
    // uncoupled and free.
    let beam = Beam::vbi2d();
    let basis = beam.basis(20, 0.0);
    let mut crossing = Crossing::new(sprung_mass(5750.0, 1.595e6), smooth(), 25.0);
    crossing.free_vibration_duration = Some(1.0);
    let dt = 1.0e-3;
    let history = run(&basis, &crossing, Some(dt));
    let n = history.mode_count;
    let options = SolverOptions::default();
    let energy = |i: usize| -> f64 {
        (0..n)
            .map(|k| {
                let w = basis.modes[k].circular_frequency;
                let beta = vbi::solver::modal_newmark_beta(&options, dt, w);
                let q = history.modal_displacement[i * n + k];
                let qd = history.modal_velocity[i * n + k];
                let qdd = history.modal_acceleration[i * n + k];
                0.5 * (qd * qd + w * w * q * q + (beta - 0.25) * dt * dt * qdd * qdd)
            })
            .sum()
    };
    let e0 = energy(history.exit_step);
    assert!(e0 > 0.0);
    for i in history.exit_step..history.step_count {
        // 1e-10: rounding accumulated over ~1000 steps of a conservative map.
        assert!(
            (energy(i) / e0 - 1.0).abs() < 1e-10,
            "step {i}: {} vs {e0}",
            energy(i)
        );
    }
}

#[test]
fn the_modal_contributions_recompose_the_total_and_participation_sums_to_one() {
    let beam = Beam::vbi2d();
    let basis = beam.basis(10, 0.02);
    let crossing = Crossing::new(sprung_mass(5750.0, 1.595e6), smooth(), 25.0);
    let history = run(&basis, &crossing, None);
    let n = basis.mode_count();
    for quantity in [Quantity::Deflection, Quantity::BendingMoment] {
        let total = station_response(&basis, &history, 0, quantity).unwrap();
        let parts = modal_contributions(&basis, &history, 0, quantity).unwrap();
        for (i, t) in total.iter().enumerate() {
            let sum: f64 = parts[i * n..(i + 1) * n].iter().sum();
            assert!((sum - t).abs() <= 1e-12 * t.abs().max(1e-30));
        }
    }
    let report = report(&beam, &basis, &history);
    for e in &report.stations {
        let total: f64 = e.participation.iter().sum();
        assert!((total - 1.0).abs() < 1e-12);
        assert_eq!(e.converged.daf_by_modes.len(), n);
        // DAF(N) of the sampled series; the headline takes the extreme between the instants
        // (analysis::continuous_extreme): at least DAF(N), and within 0.1 % of it at 1 ms.
        let (sampled, daf) = (
            *e.converged.daf_by_modes.last().unwrap(),
            e.converged.daf.unwrap(),
        );
        assert!(
            daf >= sampled && daf - sampled <= 1e-3 * daf,
            "{daf} vs {sampled}"
        );
        assert!(e.cutoff_k1 <= e.cutoff_k2);
    }
    // Sagging at mid-span: the static extreme is a downward deflection and a positive moment.
    let u = report.entry(0, Quantity::Deflection).unwrap();
    let m = report.entry(0, Quantity::BendingMoment).unwrap();
    assert!(u.static_max < 0.0 && m.static_max > 0.0);
    // Mid-span static extremes are exact: P L³/48EI and P L/4 with P = m g (the path passes
    // within v·Δt of mid-span; the extreme is flat there).
    let p = 5750.0 * GRAVITY;
    let exact_u = -p * SPAN.powi(3) / (48.0 * YOUNG * INERTIA);
    assert!((u.static_max / exact_u - 1.0).abs() < 1e-4);
    assert!((m.static_max / (p * SPAN / 4.0) - 1.0).abs() < 1e-3);
    // Deck-wide participation (Eq. 30): every sine mode has nearly the same Σ_j |φ_k(node j)|,
    // so MPS_k follows rms(q_k), about 1/k⁴ quasi-statically: mode 1 carries ~93 % of the
    // deflection, modes 1–2 reach 95 %. The moment needs more modes than the deflection
    // (the paper's Table 2 pattern).
    let deck = &report.deck_participation;
    assert!(deck.deflection[0] > 0.9 && deck.deflection[0] < 0.95);
    assert_eq!(deck.deflection_k1, Some(2));
    assert!(deck.moment_k1 > deck.deflection_k1 && deck.moment_k2 > deck.deflection_k2);
    assert_eq!(report.rdm_station.as_deref(), Some("mid"));
}

#[test]
fn a_crossing_is_deterministic_bit_for_bit() {
    let beam = Beam::vbi2d();
    let basis = beam.basis(30, 0.02);
    let road = RoadProfile {
        highest_spatial_frequency: None,
        start: -20.0,
        spacing: 0.1,
        left: (0..600)
            .map(|i| 0.003 * (0.37 * i as f64).sin() * (0.05 * i as f64).cos())
            .collect(),
        right: vec![0.0; 600],
    };
    let mut crossing = Crossing::new(sprung_mass(5750.0, 1.595e6), road, 22.0);
    crossing.vehicles[0].start_position = -10.0;
    let a = run(&basis, &crossing, None);
    let b = run(&basis, &crossing, None);
    assert_eq!(a, b);
    let ja = serde_json::to_string(&report(&beam, &basis, &a)).unwrap();
    let jb = serde_json::to_string(&report(&beam, &basis, &b)).unwrap();
    assert_eq!(ja, jb);
    // The rough road moves the vehicle from the first step (static equilibrium on the road).
    assert!(a.vehicle_displacement[0] != 0.0);
}

#[test]
fn truncated_reruns_agree_with_partial_modal_sums_where_deflection_has_converged() {
    // The two definitions of DAF(K): partial sums of one N-mode run, and a new run with K modes.
    // With K = N they are the same run (same time step), so bit-identical; for deflection at K = 3
    // both have converged (docs/verification.md §2: deflection converges within 3–5 modes) and
    // agree closely.
    let beam = Beam::vbi2d();
    let basis = beam.basis(10, 0.02);
    let crossing = Crossing::new(sprung_mass(5750.0, 1.595e6), smooth(), 25.0);
    let options = SolverOptions::default();
    let history = simulate(&basis, &crossing, &options).unwrap();
    let full = report(&beam, &basis, &history);
    let runs = vbi::crossing::rerun_truncated(
        &basis,
        &beam.influence(),
        &crossing,
        &options,
        &AnalysisOptions::default(),
        &[3, 10],
    )
    .unwrap();
    let daf_u = |r: &vbi::analysis::TruncatedRun| r.stations[0].daf_paper.unwrap();
    let deflection = full.entry(0, Quantity::Deflection).unwrap();
    assert_eq!(daf_u(&runs[1]), deflection.paper.daf.unwrap());
    assert_eq!(runs[1].stations[0].daf, deflection.converged.daf);
    let partial = deflection.paper.daf_by_modes[2];
    // 0.5 %: modes 4–10 change the mid-span deflection by ~1e-3 (1/k⁴ weights, mode 3 ≈ 1/81),
    // and dropping them hardly changes the coupled motion of a light vehicle.
    assert!(
        (daf_u(&runs[0]) / partial - 1.0).abs() < 0.005,
        "{} vs {partial}",
        daf_u(&runs[0])
    );
    assert!(vbi::crossing::rerun_truncated(
        &basis,
        &beam.influence(),
        &crossing,
        &options,
        &AnalysisOptions::default(),
        &[11],
    )
    .is_err());
}
