//! Bit-for-bit equality of numbers: what the reuse of a computed result (a shared step
//! geometry, a repeated crossing, a kept set of road phase spreads) is keyed on, so that reuse
//! never changes a bit of an output (−0.0 and 0.0 differ; a NaN equals the same NaN).

/// Whether two slices hold the same numbers bit for bit.
pub(crate) fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}
