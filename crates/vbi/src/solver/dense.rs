//! Tiny dense kernels for the per-step systems of the solver (a few tyres, a few vehicle DOFs).
//!
//! Hand-written on purpose: the systems are at most a few tens of unknowns, are solved once per
//! time step, and must not allocate; a general-purpose crate's LU allocates per call.

/// Solves `a x = b` in place by Gaussian elimination with partial pivoting. `a` is `m × m`
/// row-major and is destroyed; `b` (length m) receives x. Returns false if a pivot is zero or not
/// finite (a singular or non-finite system).
pub(crate) fn solve_in_place(a: &mut [f64], b: &mut [f64], m: usize) -> bool {
    for col in 0..m {
        let mut pivot_row = col;
        let mut pivot_abs = a[col * m + col].abs();
        for row in col + 1..m {
            let v = a[row * m + col].abs();
            if v > pivot_abs {
                pivot_abs = v;
                pivot_row = row;
            }
        }
        if pivot_abs.is_nan() || pivot_abs == 0.0 || pivot_abs.is_infinite() {
            return false;
        }
        if pivot_row != col {
            for j in 0..m {
                a.swap(col * m + j, pivot_row * m + j);
            }
            b.swap(col, pivot_row);
        }
        let (upper, lower) = a.split_at_mut((col + 1) * m);
        let pivot_row = &upper[col * m + col..col * m + m];
        let pivot = pivot_row[0];
        let b_col = b[col];
        for (r, row) in lower.chunks_exact_mut(m).enumerate() {
            let row = &mut row[col..];
            let factor = row[0] / pivot;
            if factor == 0.0 {
                continue;
            }
            for (x, p) in row.iter_mut().zip(pivot_row) {
                *x -= factor * p;
            }
            b[col + 1 + r] -= factor * b_col;
        }
    }
    for col in (0..m).rev() {
        let mut sum = b[col];
        for j in col + 1..m {
            sum -= a[col * m + j] * b[j];
        }
        b[col] = sum / a[col * m + col];
    }
    true
}

/// Dot product of two equal-length slices.
#[inline(always)]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    // Equal lengths made explicit and four independent accumulators: no bounds checks in the
    // loop, and the compiler vectorises and pipelines the sum.
    let n = a.len();
    let b = &b[..n];
    let mut acc = [0.0; 4];
    let chunks = n / 4;
    for c in 0..chunks {
        let i = 4 * c;
        acc[0] += a[i] * b[i];
        acc[1] += a[i + 1] * b[i + 1];
        acc[2] += a[i + 2] * b[i + 2];
        acc[3] += a[i + 3] * b[i + 3];
    }
    let mut sum = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for i in 4 * chunks..n {
        sum += a[i] * b[i];
    }
    sum
}

/// y = A x for a row-major `rows × cols` matrix.
pub(crate) fn mat_vec(a: &[f64], x: &[f64], y: &mut [f64], rows: usize, cols: usize) {
    for r in 0..rows {
        y[r] = dot(&a[r * cols..(r + 1) * cols], x);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaussian_elimination_solves_a_system_that_needs_pivoting() {
        // A zero leading entry forces a row swap.
        let mut a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0];
        let x_true = [1.0, -2.0, 0.5];
        let a0 = a.clone();
        let mut b: Vec<f64> = (0..3)
            .map(|r| (0..3).map(|c| a0[r * 3 + c] * x_true[c]).sum())
            .collect();
        assert!(solve_in_place(&mut a, &mut b, 3));
        for i in 0..3 {
            assert!((b[i] - x_true[i]).abs() < 1e-14);
        }
    }

    #[test]
    fn a_singular_system_is_reported() {
        let mut a = vec![1.0, 2.0, 2.0, 4.0];
        let mut b = vec![1.0, 2.0];
        assert!(!solve_in_place(&mut a, &mut b, 2));
    }
}
