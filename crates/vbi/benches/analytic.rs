//! Benchmark of the closed-form theory (issue 3): the full DAF-against-K table.
//! Run with `cargo bench -p vbi --bench analytic`. Goal: under 50 ms.

use vbi::analytical::{continuous_beam_modes, daf_by_modes, ContinuousBeam, DafOptions};

fn main() {
    divan::main();
}

fn four_span_beam() -> ContinuousBeam {
    ContinuousBeam::new(4, 20.0, 3.24e10, 2.0e4).expect("valid beam")
}

/// DAF_u(K), DAF_M(K), RDM(K) for K = 1 … 50, 1000 output times, 4 × 20 m beam at 80 km/h,
/// ζ = 0.05, section l/2: modes, statics (envelope), histories and refined maxima.
#[divan::bench]
fn daf_table_4_spans_50_modes_1000_times() -> f64 {
    let beam = four_span_beam();
    let options = DafOptions {
        modes: 50,
        output_times: 1000,
        ..DafOptions::default()
    };
    let table = daf_by_modes(divan::black_box(&beam), divan::black_box(&options)).expect("table");
    table.rdm_by_modes[49]
}

/// The 50 exact modes of the 4-span beam alone.
#[divan::bench]
fn modes_4_spans_50() -> usize {
    continuous_beam_modes(divan::black_box(&four_span_beam()), 50)
        .expect("modes")
        .len()
}
