//! Benchmark of one coupled crossing (issue 5): a 3×30 m deck of five girder lines, 50 modes,
//! a synthetic 15-DOF five-axle truck on ten tyres, a rough road, 80 km/h, 1 ms time step,
//! 50 m approach. The modal basis is synthetic (sine shapes with lateral patterns): the cost of a
//! crossing depends on the sizes, not on the shapes. Run with
//! `cargo bench -p vbi --bench crossing`; the counter gives the time per step per mode.

use std::f64::consts::PI;

use divan::counter::ItemsCount;
use divan::Bencher;
use nalgebra::{DMatrix, DVector};
use vbi::deck::{DeckGeometry, DeckLine};
use vbi::modal::{ModalBasis, Mode, ModeKind};
use vbi::road::RoadProfile;
use vbi::solver::{simulate, Crossing, SolverOptions, TravelDirection, VehicleRun};
use vbi::vehicle::{ContactKind, TyreContact, VehicleModel};

fn main() {
    divan::main();
}

const MODES: usize = 50;

/// 3×30 m deck, girder lines at y = −4, −2, 0, 2, 4 m, nodes every 0.5 m (905 nodes).
fn synthetic_basis() -> ModalBasis {
    synthetic_basis_of(MODES)
}

/// [`synthetic_basis`] with `modes` modes.
fn synthetic_basis_of(modes: usize) -> ModalBasis {
    let length = 90.0;
    let xs: Vec<f64> = (0..=180).map(|i| i as f64 * 0.5).collect();
    let lines: Vec<DeckLine> = (0..5)
        .map(|g| DeckLine {
            lateral_position: -4.0 + 2.0 * g as f64,
            node_positions: xs.clone(),
            first_node: g * xs.len(),
        })
        .collect();
    // Mode k: longitudinal half-waves m = k/3 + 1, lateral pattern p = k % 3 (bending, torsion,
    // distortion); f₁ ≈ 3 Hz.
    let shape = |k: usize, x: f64, y: f64| {
        let (m, p) = ((k / 3 + 1) as f64, (k % 3) as i32);
        let lateral = (y / 4.0).powi(p);
        let a = m * PI / 30.0;
        (
            1e-3 * lateral * (a * x).sin(),
            1e-3 * lateral * a * (a * x).cos(),
        )
    };
    let mut deck_deflection = Vec::new();
    let mut deck_slope = Vec::new();
    for line in &lines {
        for &x in &line.node_positions {
            for k in 0..modes {
                let (w, s) = shape(k, x, line.lateral_position);
                deck_deflection.push(w);
                deck_slope.push(s);
            }
        }
    }
    ModalBasis {
        modes: (0..modes)
            .map(|k| Mode {
                circular_frequency: 2.0 * PI * 3.0 * (1.0 + k as f64 * 0.6),
                damping_ratio: 0.02,
                kind: ModeKind::VerticalBending,
                residual: 0.0,
            })
            .collect(),
        deck: DeckGeometry { lines, length },
        deck_deflection,
        deck_slope,
        stations: Vec::new(),
        station_deflection: Vec::new(),
        station_moment: Vec::new(),
        station_force: Vec::new(),
        dof_count: 0,
        check_modes: None,
    }
}

/// Tractor (bounce, pitch, roll), semi-trailer (bounce, pitch) and ten wheel masses (bounce):
/// 15 DOFs, five axles at 0, −3.6, −9.0, −10.3, −11.6 m, track ±0.9 m.
fn synthetic_truck() -> VehicleModel {
    let d = 15;
    let axles = [0.0, -3.6, -9.0, -10.3, -11.6];
    let (tractor_cg, trailer_cg, fifth_wheel) = (-1.8, -8.0, -3.0);
    let mut mass = vec![6000.0, 2.0e4, 5.0e3, 2.0e4, 1.5e5];
    mass.extend([400.0; 10]);
    let mut k = DMatrix::zeros(d, d);
    let mut c = DMatrix::zeros(d, d);
    let mut spring = |b: &[(usize, f64)], stiffness: f64, damping: f64| {
        for &(i, bi) in b {
            for &(j, bj) in b {
                k[(i, j)] += stiffness * bi * bj;
                c[(i, j)] += damping * bi * bj;
            }
        }
    };
    // Fifth wheel: tractor point minus trailer point.
    spring(
        &[
            (0, 1.0),
            (1, -(fifth_wheel - tractor_cg)),
            (3, -1.0),
            (4, fifth_wheel - trailer_cg),
        ],
        5.0e7,
        1.0e4,
    );
    let mut contacts = Vec::new();
    for (a, &x) in axles.iter().enumerate() {
        for (side, y) in [(0, 0.9), (1, -0.9)] {
            let wheel = 5 + 2 * a + side;
            let body: Vec<(usize, f64)> = if a < 2 {
                vec![(0, -1.0), (1, x - tractor_cg), (2, -y)]
            } else {
                vec![(3, -1.0), (4, x - trailer_cg)]
            };
            let mut b = body;
            b.push((wheel, 1.0));
            spring(&b, 1.0e6, 1.5e4);
            spring(&[(wheel, 1.0)], 1.75e6, 1.0e3);
            contacts.push(TyreContact {
                longitudinal_offset: x,
                lateral_offset: y,
                static_load: 36_000.0 * 9.81 / 10.0,
                kind: ContactKind::Tyre {
                    stiffness: 1.75e6,
                    damping: 1.0e3,
                    coupling: vec![(wheel, 1.0)],
                },
            });
        }
    }
    VehicleModel {
        name: "synthetic_15dof".into(),
        dof_names: (0..d).map(|i| format!("dof{i}")).collect(),
        mass_matrix: DMatrix::from_diagonal(&DVector::from_vec(mass)),
        damping_matrix: c,
        stiffness_matrix: k,
        contacts,
        pitch_load_per_acceleration: Vec::new(),
    }
}

/// A 'medium' road (G_d(n₀) = 64e-6 m³) as a deterministic sum of 200 harmonics (Eq. 22), from
/// x = −60 m to 210 m.
fn synthetic_road() -> RoadProfile {
    synthetic_road_from(-60.0)
}

/// The same road from x = `start` [m] to 210 m.
fn synthetic_road_from(start: f64) -> RoadProfile {
    let spacing = 0.05;
    let samples = ((210.0 - start) / spacing).round() as usize;
    let dn = 1.0 / 100.0;
    let harmonics: Vec<(f64, f64, f64)> = (1..=200)
        .map(|i| {
            let n = 0.011 + i as f64 * 0.0145;
            let amplitude = (2.0 * 64e-6 * (n / 0.1f64).powi(-2) * dn).sqrt();
            (n, amplitude, (i as f64 * 2.399_963).rem_euclid(2.0 * PI))
        })
        .collect();
    let track = |shift: f64| -> Vec<f64> {
        (0..samples)
            .map(|s| {
                let x = start + s as f64 * spacing;
                harmonics
                    .iter()
                    .map(|&(n, a, p)| a * (2.0 * PI * n * x + p + shift).cos())
                    .sum()
            })
            .collect()
    };
    RoadProfile {
        highest_spatial_frequency: None,
        start,
        spacing,
        left: track(0.0),
        right: track(1.3),
    }
}

#[divan::bench(sample_count = 20)]
fn crossing_3x30m_50_modes_15_dof_truck(bencher: Bencher) {
    crossing_by_modes(bencher, MODES);
}

/// Runs `crossing` once to count its steps, then benchmarks it, counting time steps.
fn bench_steps(bencher: Bencher, crossing: &Crossing) {
    let basis = synthetic_basis();
    let options = SolverOptions {
        time_step: Some(1.0e-3),
        ..SolverOptions::default()
    };
    bench_steps_with(bencher, &basis, crossing, &options);
}

/// [`bench_steps`] on `basis` with `options`.
fn bench_steps_with(
    bencher: Bencher,
    basis: &ModalBasis,
    crossing: &Crossing,
    options: &SolverOptions,
) {
    let steps = simulate(basis, crossing, options)
        .expect("crossing runs")
        .step_count;
    bencher
        .counter(ItemsCount::new(steps))
        .bench_local(|| simulate(basis, crossing, options).expect("crossing runs"));
}

/// Two trucks meeting: one forward at y = +2 m, one backward at y = −2 m, both starting 50 m
/// before their deck entry at 80 km/h (20 tyres, 30 vehicle DOFs). The counter is time steps.
#[divan::bench(sample_count = 10)]
fn two_trucks_meeting_3x30m_50_modes(bencher: Bencher) {
    let run = |direction, lateral_position| VehicleRun {
        direction,
        lateral_position,
        start_position: -50.0,
        ..VehicleRun::forward(synthetic_truck(), 80.0 / 3.6)
    };
    let crossing = Crossing {
        vehicles: vec![
            run(TravelDirection::Forward, 2.0),
            run(TravelDirection::Backward, -2.0),
        ],
        road: synthetic_road(),
        free_vibration_duration: None,
    };
    bench_steps(bencher, &crossing);
}

/// A stream of ten trucks in one lane, 15 m apart at 80 km/h (100 tyres, 150 vehicle DOFs; up
/// to four trucks on the deck at once). The counter is time steps.
#[divan::bench(sample_count = 10)]
fn ten_truck_stream_3x30m_50_modes(bencher: Bencher) {
    let truck = synthetic_truck();
    let spacing = truck.trailing_length() + 15.0;
    let vehicles: Vec<VehicleRun> = (0..10)
        .map(|i| VehicleRun {
            start_position: -50.0 - i as f64 * spacing,
            ..VehicleRun::forward(truck.clone(), 80.0 / 3.6)
        })
        .collect();
    let start = vehicles[9].start_position - spacing;
    let crossing = Crossing {
        vehicles,
        road: synthetic_road_from(start),
        free_vibration_duration: None,
    };
    bench_steps(bencher, &crossing);
}

/// The crossing of [`crossing_3x30m_50_modes_15_dof_truck`] at 1 ms.
fn one_truck_crossing() -> (Crossing, SolverOptions) {
    let mut crossing = Crossing::new(synthetic_truck(), synthetic_road(), 80.0 / 3.6);
    crossing.vehicles[0].start_position = -50.0;
    let options = SolverOptions {
        time_step: Some(1.0e-3),
        ..SolverOptions::default()
    };
    (crossing, options)
}

/// The cost curve in modes: the one-truck crossing with 10 to 200 modes (the counter is time
/// steps × modes). docs/performance.md gives the fitted line, cost ≈ a + b·N.
#[divan::bench(sample_count = 10, args = [10, 25, 50, 100, 200])]
fn crossing_by_modes(bencher: Bencher, modes: usize) {
    let basis = synthetic_basis_of(modes);
    let (crossing, options) = one_truck_crossing();
    let steps = simulate(&basis, &crossing, &options)
        .expect("crossing runs")
        .step_count;
    bencher
        .counter(ItemsCount::new(steps * modes))
        .bench_local(|| simulate(&basis, &crossing, &options).expect("crossing runs"));
}

/// The cost curve in time steps: the one-truck crossing at Δt = 2, 1 and 0.5 ms (the counter is
/// time steps): the cost per step should not depend on Δt.
#[divan::bench(sample_count = 10, args = [2.0e-3, 1.0e-3, 0.5e-3])]
fn crossing_by_time_step(bencher: Bencher, time_step: f64) {
    let basis = synthetic_basis();
    let (crossing, mut options) = one_truck_crossing();
    options.time_step = Some(time_step);
    bench_steps_with(bencher, &basis, &crossing, &options);
}

/// The cost curve in tyres: a stream of 1, 2, 4 or 8 trucks 3 m apart (10 tyres each, all of
/// them on the 90 m deck together from four trucks on), 50 modes (the counter is time steps).
#[divan::bench(sample_count = 10, args = [1, 2, 4, 8])]
fn crossing_by_trucks_in_a_close_stream(bencher: Bencher, trucks: usize) {
    let truck = synthetic_truck();
    let spacing = truck.trailing_length() + 3.0;
    let vehicles: Vec<VehicleRun> = (0..trucks)
        .map(|i| VehicleRun {
            start_position: -50.0 - i as f64 * spacing,
            ..VehicleRun::forward(truck.clone(), 80.0 / 3.6)
        })
        .collect();
    let start = vehicles[trucks - 1].start_position - spacing;
    let crossing = Crossing {
        vehicles,
        road: synthetic_road_from(start),
        free_vibration_duration: None,
    };
    bench_steps(bencher, &crossing);
}
