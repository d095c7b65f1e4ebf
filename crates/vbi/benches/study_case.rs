//! Benchmark of one case of the paper study (issue 6): the largest part of a parametric study's
//! time, through the library pipeline that `vbi study` calls. The bridge half
//! (`crossing::prepare_bridge`: FE model, 50 modes of the kinds a study keeps, influence lines of
//! `paper_bridge(3, 30.0)`) is built once, outside the timing, as `vbi study` shares it among a
//! bridge's cases; each iteration is `crossing::run_crossing`, what `vbi study` does per case:
//! generate the 'medium' road of a seed, assemble the 15-DOF tractor–semitrailer, simulate the
//! coupled crossing at 80 km/h, and analyse it, for the RDM station only (the study's scope) and,
//! for comparison, for every station (`vbi run`'s scope).
//! Run with `cargo bench -p vbi --bench study_case`; figures in docs/performance.md.
//!
//! Under `cargo test --all-targets` divan runs each benchmark once in the dev profile as a smoke
//! test; there the bridge is 2 × 20 m at a 4 m mesh with 10 modes.

use vbi::analysis::StationScope;
use vbi::crossing::{prepare_bridge, run_crossing, BridgeSpec, PreparedBridge, Scenario};
use vbi::model::paper_bridge;
use vbi::road::{RoadSpec, RoughnessClass};

fn main() {
    divan::main();
}

/// True under `cargo bench` (cargo passes `--bench`), false under `cargo test`.
fn benchmarking() -> bool {
    std::env::args().any(|a| a == "--bench")
}

/// The scenario of one case of `examples/studies/paper.toml` at 3 × 30 m, 'medium', 80 km/h: the
/// built-in scenario (paper bridge, five-axle truck, 50 modes of vertical bending and torsion)
/// with the study's road class, seed and analysis scope, exactly as `vbi study` builds it.
fn case_scenario(seed: u64, stations: StationScope) -> Scenario {
    let mut scenario = Scenario {
        road: RoadSpec::of_class(RoughnessClass::Medium),
        ..Scenario::default()
    };
    if !benchmarking() {
        scenario.bridge = BridgeSpec::new(paper_bridge(2, 20.0), 10);
        scenario.bridge.mesh.element_length = 4.0;
    }
    scenario.road.seed = seed;
    scenario.analysis.stations = stations;
    scenario
}

fn bridge() -> PreparedBridge {
    prepare_bridge(&case_scenario(0, StationScope::RdmStation).bridge).expect("paper bridge")
}

fn one_case(bridge: &PreparedBridge, seed: u64, stations: StationScope) -> Option<f64> {
    run_crossing(bridge, &case_scenario(seed, stations))
        .expect("crossing")
        .report
        .rdm
}

#[divan::bench(sample_count = 20)]
fn one_paper_case_rdm_station_analysis(bencher: divan::Bencher) {
    let bridge = bridge();
    let mut seed = 0;
    bencher.bench_local(|| {
        seed += 1;
        one_case(&bridge, seed, StationScope::RdmStation)
    });
}

#[divan::bench(sample_count = 20)]
fn one_paper_case_every_station_analysed(bencher: divan::Bencher) {
    let bridge = bridge();
    let mut seed = 0;
    bencher.bench_local(|| {
        seed += 1;
        one_case(&bridge, seed, StationScope::All)
    });
}
