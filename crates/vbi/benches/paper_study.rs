//! Benchmark of a fixed fraction of the paper study (issue 16): the 40 crossings of one of its
//! 27 bridge × speed combinations (`examples/studies/paper.toml`: the 3 × 30 m bridge at 80 km/h,
//! four road classes × ten roughness samples, 50 modes, the 15-DOF five-axle truck), run exactly
//! as `vbi study` runs them: in batches of `STUDY_BATCH_SIZE` crossings integrated together
//! (`study::case_records_with`), each analysed at its RDM station. The bridge half (FE model,
//! 50 modes, influence lines) is built once outside the timing, as the study shares it; the
//! static-reference cache is emptied before each iteration so that every iteration does the
//! study's work for one combination. The whole study is 27 such combinations plus nine bridge
//! analyses (about 1 s in all).
//!
//! Besides divan's timing, it prints the flop count of the crossings' coupled steps
//! (14N + 27·N·m + 2·m²·N per step for N modes and m tyres on the deck: the model of
//! the step) and the floor that count sets at this machine's DGEMM rate (measured here on a
//! 256 × 256 product with nalgebra's matrixmultiply kernels), so that the ratio of the measured
//! time to the floor can be read off: for all 40 crossings, and for the 31 that are integrated
//! (the ten samples of the 'smooth' road are one crossing, computed once), and the CPU time of
//! one run (least of three, every thread of the process) with its ratio to that floor. It also
//! prints the peak resident memory of the process while one combination runs (Linux's VmHWM,
//! reset before it; the prepared bridge included). A second benchmark runs one of its crossings
//! alone (the "single crossing"), with the floor of its own flop count and the ratio of
//! its CPU time to it. Run with
//! `cargo bench -p vbi --bench paper_study`; figures in docs/performance.md.
//!
//! Under `cargo test --all-targets` divan runs it once in the dev profile as a smoke test; there
//! the bridge is 2 × 20 m at a 4 m mesh with 10 modes and the combination has 4 crossings.

use std::time::Instant;

use vbi::analysis::StationScope;
use vbi::crossing::{
    integration_batches, prepare_bridge, repeats_run, BridgeSpec, Motion, PreparedBridge, Scenario,
    ScenarioBridgeError,
};
use vbi::model::paper_bridge;
use vbi::road::{RoadSpec, Roughness, RoughnessClass};
use vbi::solver::Crossing;
use vbi::study::{case_records_with, CaseRecord, STUDY_BATCH_SIZE};

fn main() {
    divan::main();
}

/// Resets the process's peak resident memory (VmHWM) to its current resident memory (Linux:
/// `echo 5 > /proc/self/clear_refs`); false where that is not possible.
fn reset_peak_resident_memory() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// The process's peak resident memory VmHWM [bytes], from `/proc/self/status` (Linux).
fn peak_resident_memory() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kilobytes: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kilobytes * 1024.0)
}

/// True under `cargo bench` (cargo passes `--bench`), false under `cargo test`.
fn benchmarking() -> bool {
    std::env::args().any(|a| a == "--bench")
}

/// The study's seed (`[study] seed = 2023`); the sample seeds here are a fixed function of it.
const SEED: u64 = 2023;

fn bridge_spec() -> BridgeSpec {
    if benchmarking() {
        BridgeSpec::new(paper_bridge(3, 30.0), 50)
    } else {
        let mut spec = BridgeSpec::new(paper_bridge(2, 20.0), 10);
        spec.mesh.element_length = 4.0;
        spec
    }
}

/// The combination's crossings: four road classes × ten samples at 80 km/h (one class × four
/// samples in the smoke test), analysed at the RDM station.
fn scenarios(spec: &BridgeSpec) -> Vec<Scenario> {
    let (classes, samples): (&[RoughnessClass], u64) = if benchmarking() {
        (
            &[
                RoughnessClass::Smooth,
                RoughnessClass::Good,
                RoughnessClass::Medium,
                RoughnessClass::Poor,
            ],
            10,
        )
    } else {
        (&[RoughnessClass::Medium], 4)
    };
    let mut scenarios = Vec::new();
    for &class in classes {
        for sample in 0..samples {
            let mut scenario = Scenario {
                road: RoadSpec::of_class(class),
                ..Scenario::default()
            };
            scenario.bridge = spec.clone();
            scenario.road.seed = SEED.wrapping_mul(1000).wrapping_add(sample);
            scenario.motion = Motion::constant(80.0 / 3.6, 0.0);
            scenario.analysis.stations = StationScope::RdmStation;
            scenarios.push(scenario);
        }
    }
    scenarios
}

/// The combination's prepared bridge and its crossings.
fn combination() -> (Result<PreparedBridge, ScenarioBridgeError>, Vec<Scenario>) {
    let spec = bridge_spec();
    let bridge = prepare_bridge(&spec).map_err(|source| ScenarioBridgeError::Prepare {
        label: "paper".into(),
        source,
    });
    (bridge, scenarios(&spec))
}

/// The combination as `vbi study` runs it: batches of crossings integrated together.
fn run_combination(
    bridge: &Result<PreparedBridge, ScenarioBridgeError>,
    scenarios: &[Scenario],
) -> Vec<CaseRecord> {
    let refs: Vec<&Scenario> = scenarios.iter().collect();
    let mut records = Vec::new();
    for batch in integration_batches(&refs, STUDY_BATCH_SIZE) {
        let cases: Vec<(&str, &Scenario)> = batch.iter().map(|&i| ("case", refs[i])).collect();
        records.extend(case_records_with(&cases, bridge, &[]));
    }
    records
}

/// [`run_combination`] as a fresh study runs it: the bridge's cache of static references
/// emptied first, so that every run computes them again.
fn run_from_scratch(
    bridge: &Result<PreparedBridge, ScenarioBridgeError>,
    scenarios: &[Scenario],
) -> Vec<CaseRecord> {
    if let Ok(prepared) = bridge {
        prepared.static_references.clear();
    }
    run_combination(bridge, scenarios)
}

#[divan::bench(sample_count = 3)]
fn paper_study_one_bridge_and_speed_40_crossings(bencher: divan::Bencher) {
    let (bridge, scenarios) = combination();
    if benchmarking() {
        let floor = print_flop_floor("paper_study", &bridge, &scenarios);
        print_cpu_time_against_floor("paper_study", floor, || {
            run_from_scratch(&bridge, &scenarios);
        });
        if reset_peak_resident_memory() {
            run_combination(&bridge, &scenarios);
            if let Some(peak) = peak_resident_memory() {
                eprintln!(
                    "paper_study: peak resident memory while the combination runs {:.0} MB \
                     (the prepared bridge included; batches of {STUDY_BATCH_SIZE})",
                    peak / 1e6
                );
            }
        }
    }
    bencher.bench_local(|| run_from_scratch(&bridge, &scenarios));
}

/// One crossing of the combination alone (the 'medium' road's first sample), run as `vbi study`
/// runs a case (integrated and analysed at the RDM station): the "single crossing"
/// against the floor of its own flop count.
#[divan::bench(sample_count = 10)]
fn paper_study_one_crossing_alone(bencher: divan::Bencher) {
    let (bridge, scenarios) = combination();
    let medium = scenarios
        .iter()
        .position(|s| s.road.roughness == Roughness::Class(RoughnessClass::Medium))
        .expect("a 'medium' road");
    let alone = &scenarios[medium..=medium];
    if benchmarking() {
        let label = "paper_study_one_crossing_alone";
        let floor = print_flop_floor(label, &bridge, alone);
        print_cpu_time_against_floor(label, floor, || {
            run_from_scratch(&bridge, alone);
        });
    }
    bencher.bench_local(|| run_from_scratch(&bridge, alone));
}

/// The crossings' flop count by the model of a coupled step and its floor at the
/// machine's DGEMM rate, printed once under `label`: the floor of the integrated crossings [s]
/// (None without a bridge).
fn print_flop_floor(
    label: &str,
    bridge: &Result<PreparedBridge, ScenarioBridgeError>,
    scenarios: &[Scenario],
) -> Option<f64> {
    let Ok(bridge) = bridge else {
        return None;
    };
    let n = bridge.basis.mode_count() as f64;
    let (mut flops, mut integrated_flops) = (0.0, 0.0);
    let mut integrated: Vec<(&Scenario, Crossing)> = Vec::new();
    for scenario in scenarios {
        let result = vbi::crossing::run_crossing(bridge, scenario).expect("a crossing");
        let history = &result.history;
        let contacts = history.contacts.len();
        let mut crossing_flops = 0.0;
        for i in 0..history.step_count {
            let positions = &history.contact_position[i * contacts..(i + 1) * contacts];
            let on_deck = positions
                .iter()
                .filter(|&&x| (0.0..=bridge.basis.deck.length).contains(&x))
                .count() as f64;
            crossing_flops += 14.0 * n + 27.0 * n * on_deck + 2.0 * on_deck * on_deck * n;
        }
        flops += crossing_flops;
        let repeat = integrated.iter().any(|(earlier, crossing)| {
            repeats_run((earlier, crossing), (scenario, &result.crossing))
        });
        if !repeat {
            integrated_flops += crossing_flops;
            integrated.push((scenario, result.crossing));
        }
    }
    let rate = dgemm_rate();
    eprintln!(
        "{label}: {} crossings, {:.3} Gflop in their coupled steps; {} integrated (the rest \
         repeat one), {:.3} Gflop; DGEMM rate {:.1} Gflop/s; floor {:.4} s (all) and {:.4} s \
         (integrated)",
        scenarios.len(),
        flops / 1e9,
        integrated.len(),
        integrated_flops / 1e9,
        rate / 1e9,
        flops / rate,
        integrated_flops / rate
    );
    Some(integrated_flops / rate)
}

/// Runs `run` three times and prints, under `label`, its least CPU time (all the process's
/// threads) and wall time, and the ratio of that CPU time to `floor` [s].
fn print_cpu_time_against_floor(label: &str, floor: Option<f64>, mut run: impl FnMut()) {
    let (mut cpu, mut wall) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..3 {
        let (cpu_before, started) = (process_cpu_time(), Instant::now());
        run();
        wall = wall.min(started.elapsed().as_secs_f64());
        if let (Some(before), Some(after)) = (cpu_before, process_cpu_time()) {
            cpu = cpu.min(after - before);
        }
    }
    let ratio = floor.map_or(String::new(), |floor| {
        format!(
            "; {:.1}x the floor of its integrated crossings",
            cpu / floor
        )
    });
    eprintln!("{label}: one run {cpu:.4} s of CPU ({wall:.4} s of wall time), least of 3{ratio}");
}

/// The process's CPU time [s]: the time on the CPU of each of its threads, summed
/// (`/proc/self/task/*/schedstat`, nanoseconds; Linux); None where that is not readable.
fn process_cpu_time() -> Option<f64> {
    let mut nanoseconds = 0u64;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let text = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
        nanoseconds += text.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(nanoseconds as f64 * 1e-9)
}

/// Flop rate [flop/s] of a 256 × 256 × 256 double-precision product, best of five.
fn dgemm_rate() -> f64 {
    let size = 256;
    let a = nalgebra::DMatrix::<f64>::from_fn(size, size, |i, j| ((i * 7 + j * 3) % 11) as f64);
    let b = nalgebra::DMatrix::<f64>::from_fn(size, size, |i, j| ((i * 5 + j) % 13) as f64);
    let mut c = nalgebra::DMatrix::<f64>::zeros(size, size);
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let start = Instant::now();
        c.gemm(1.0, &a, &b, 0.0);
        best = best.min(start.elapsed().as_secs_f64());
    }
    std::hint::black_box(&c);
    2.0 * (size as f64).powi(3) / best
}
