//! Benchmarks (divan). Run with `cargo bench -p vbi`; CI only compiles and smoke-runs them.

fn main() {
    divan::main();
}
