//! Modal analysis benchmark: 50 modes of a ≥ 20,000-DOF plate-like grillage by sparse
//! shift-invert Lanczos (single-threaded). Run with `cargo bench --workspace --bench modal`.

#[path = "../tests/it/verification_modal/models.rs"]
mod models;

use vbi::modal::{solve_modes, ModalOptions};

fn main() {
    divan::main();
}

/// 82 girder lines × 82 nodes, 3 DOF per node (w, θx, θy), ends simply supported:
/// 20,008 free DOFs.
#[divan::bench(sample_count = 5)]
fn fifty_modes_of_a_20000_dof_grillage(bencher: divan::Bencher) {
    let model = models::plate_grid(82, 0.5, 40.0, 81);
    assert!(model.dof_count() >= 20_000, "{} DOFs", model.dof_count());
    bencher.bench_local(|| {
        let basis = solve_modes(divan::black_box(&model), &ModalOptions::default())
            .expect("modes of the benchmark grid");
        assert_eq!(basis.mode_count(), 50);
        basis
    });
}
