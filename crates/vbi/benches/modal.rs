//! Modal analysis benchmarks (issue 2): 50 modes by sparse shift-invert Lanczos, single-threaded,
//! of the largest paper bridge (the 4 × 40 m grillage at the default 1 m mesh) and of two
//! ≥ 20,000-DOF models (a plate-like grid, and the same 4 × 40 m grillage at a 0.125 m mesh).
//! Run with `cargo bench --workspace --bench modal`; figures in docs/performance.md.
//!
//! Under `cargo test --all-targets` divan runs each benchmark once in the dev profile as a smoke
//! test; there the models are built at a coarse size (see [`benchmarking`]) so that the smoke
//! run stays cheap. The full sizes run only under `cargo bench`.

#[path = "../tests/it/verification_modal/models.rs"]
mod models;

use vbi::fe::{discretise, FeModel, MeshOptions};
use vbi::modal::{solve_modes, ModalOptions};
use vbi::model::paper_bridge;

fn main() {
    divan::main();
}

/// True under `cargo bench` (cargo passes `--bench` to the benchmark binary), false under
/// `cargo test`, which runs each benchmark once as a smoke test.
fn benchmarking() -> bool {
    std::env::args().any(|a| a == "--bench")
}

fn fifty_modes(bencher: divan::Bencher, model: &FeModel) {
    let options = ModalOptions::default();
    bencher.bench_local(|| {
        let basis = solve_modes(divan::black_box(model), &options).expect("modes of the model");
        assert_eq!(basis.mode_count(), options.mode_count);
        basis
    });
}

/// The 4 × 40 m paper grillage (three box girders, slab strips every 2 m, diaphragms over the
/// supports, 6 DOF per node) meshed with elements of `element_length` [m].
fn paper_4x40(element_length: f64) -> FeModel {
    let mesh = MeshOptions {
        element_length,
        ..MeshOptions::default()
    };
    discretise(&paper_bridge(4, 40.0), &mesh).expect("the paper 4 × 40 m grillage meshes")
}

/// The largest paper bridge at the default mesh (1 m elements): 2,850 free DOFs.
#[divan::bench(sample_count = 10)]
fn fifty_modes_of_the_paper_4x40_grillage(bencher: divan::Bencher) {
    let model = paper_4x40(if benchmarking() { 1.0 } else { 4.0 });
    fifty_modes(bencher, &model);
}

/// The same grillage at 0.125 m elements: 23,010 free DOFs of a real bridge model.
#[divan::bench(sample_count = 5)]
fn fifty_modes_of_the_paper_4x40_grillage_at_20000_dof(bencher: divan::Bencher) {
    let model = paper_4x40(if benchmarking() { 0.125 } else { 4.0 });
    if benchmarking() {
        assert!(model.dof_count() >= 20_000, "{} DOFs", model.dof_count());
    }
    fifty_modes(bencher, &model);
}

/// 82 girder lines × 82 nodes, 3 DOF per node (w, θx, θy), ends simply supported:
/// 20,008 free DOFs.
#[divan::bench(sample_count = 5)]
fn fifty_modes_of_a_20000_dof_grillage(bencher: divan::Bencher) {
    let model = if benchmarking() {
        models::plate_grid(82, 0.5, 40.0, 81)
    } else {
        models::plate_grid(12, 0.5, 40.0, 11)
    };
    if benchmarking() {
        assert!(model.dof_count() >= 20_000, "{} DOFs", model.dof_count());
    }
    fifty_modes(bencher, &model);
}

/// The cost curve in model size: 50 modes of the 4 × 40 m grillage at element lengths of 1, 0.5,
/// 0.25 and 0.125 m (2,850 to 23,010 free DOFs). docs/performance.md gives the fitted exponent
/// of time against DOFs, so that a change that bends the curve is seen.
#[divan::bench(sample_count = 3, args = [1.0, 0.5, 0.25, 0.125])]
fn fifty_modes_by_element_length(bencher: divan::Bencher, element_length: f64) {
    let model = paper_4x40(if benchmarking() { element_length } else { 4.0 });
    fifty_modes(bencher, &model);
}
