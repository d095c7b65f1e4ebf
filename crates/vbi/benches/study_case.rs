//! Benchmark of one case of the paper study (issue 6): the largest part of a parametric study's
//! time. The bridge half (FE model, 50 modes, influence lines of `paper_bridge(3, 30.0)`) is built
//! once, outside the timing, as `vbi study` shares it among a bridge's cases; each iteration is
//! what `vbi study` does per case: generate the 'medium' road of a seed, assemble the 15-DOF
//! tractor–semitrailer, simulate the coupled crossing at 80 km/h, and analyse it, for the RDM
//! station only (the study's scope) and, for comparison, for every station (`vbi run`'s scope).
//! Run with `cargo bench -p vbi --bench study_case`; figures in docs/performance.md.
//!
//! Under `cargo test --all-targets` divan runs each benchmark once in the dev profile as a smoke
//! test; there the bridge is 2 × 20 m at a 4 m mesh with 10 modes.

use vbi::analysis::{analyse, AnalysisOptions, StationScope};
use vbi::fe::{discretise, statics::influence_lines, MeshOptions};
use vbi::influence::InfluenceLines;
use vbi::modal::{solve_modes, ModalBasis, ModalOptions};
use vbi::model::paper_bridge;
use vbi::road::{generate, RoadSpec, RoughnessClass};
use vbi::solver::{simulate, Crossing, SolverOptions};
use vbi::vehicle::{assemble, preset};

fn main() {
    divan::main();
}

/// True under `cargo bench` (cargo passes `--bench`), false under `cargo test`.
fn benchmarking() -> bool {
    std::env::args().any(|a| a == "--bench")
}

struct Bridge {
    basis: ModalBasis,
    influence: InfluenceLines,
}

fn bridge() -> Bridge {
    let (model, mesh, modes) = if benchmarking() {
        (paper_bridge(3, 30.0), MeshOptions::default(), 50)
    } else {
        let mesh = MeshOptions {
            element_length: 4.0,
            ..MeshOptions::default()
        };
        (paper_bridge(2, 20.0), mesh, 10)
    };
    let fe = discretise(&model, &mesh).expect("paper bridge");
    let basis = solve_modes(
        &fe,
        &ModalOptions {
            mode_count: modes,
            ..ModalOptions::default()
        },
    )
    .expect("modes");
    let influence = influence_lines(&fe).expect("influence lines");
    Bridge { basis, influence }
}

fn one_case(bridge: &Bridge, seed: u64, stations: StationScope) -> Option<f64> {
    let spec = RoadSpec::of_class(RoughnessClass::Medium);
    let (start, end) = spec.extent_for_bridge(bridge.basis.deck.length);
    let road = generate(&spec, start, end, seed).expect("road");
    let vehicle = assemble(&preset("tractor-semitrailer-5axle").expect("preset")).expect("truck");
    let mut crossing = Crossing::new(vehicle, road, 80.0 / 3.6);
    crossing.start_position = start;
    let history = simulate(&bridge.basis, &crossing, &SolverOptions::default()).expect("crossing");
    let options = AnalysisOptions {
        stations,
        ..AnalysisOptions::default()
    };
    analyse(&bridge.basis, &bridge.influence, &history, &options)
        .expect("analysis")
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
