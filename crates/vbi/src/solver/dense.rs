//! Tiny dense kernels for the per-step systems of the solver (a few tyres, a few vehicle DOFs).
//!
//! Hand-written on purpose: the systems are at most a few tens of unknowns, are solved once per
//! time step, and must not allocate; a general-purpose crate's LU allocates per call.

/// Factorises `a` (`m × m`, row-major) in place by Gaussian elimination with partial pivoting:
/// on return the upper triangle of `a` holds U, `pivots[col]` the row swapped with row `col` at
/// elimination stage `col`, and `multipliers[col * m + row]` the factor by which the pivot row
/// was subtracted from row `row` (> col) at that stage (stored per stage, so that later row
/// swaps do not move them). The strictly lower triangle of `a` is left with the elimination
/// residuals and is not used. Returns false if a pivot is zero or not finite (a singular or
/// non-finite system). Together with [`lu_solve`] this performs, on the right-hand side, exactly
/// the floating-point operations of a fused elimination, in the same order.
pub(crate) fn lu_factor(
    a: &mut [f64],
    pivots: &mut [usize],
    multipliers: &mut [f64],
    m: usize,
) -> bool {
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
        pivots[col] = pivot_row;
        if pivot_row != col {
            for j in 0..m {
                a.swap(col * m + j, pivot_row * m + j);
            }
        }
        let (upper, lower) = a.split_at_mut((col + 1) * m);
        let pivot_row = &upper[col * m + col..col * m + m];
        let pivot = pivot_row[0];
        let stage_multipliers = &mut multipliers[col * m + col + 1..(col + 1) * m];
        for (row, multiplier) in lower.chunks_exact_mut(m).zip(stage_multipliers) {
            let row = &mut row[col..];
            let factor = row[0] / pivot;
            *multiplier = factor;
            if factor == 0.0 {
                continue;
            }
            for (x, p) in row.iter_mut().zip(pivot_row) {
                *x -= factor * p;
            }
        }
    }
    true
}

/// Solves `a x = b` in place with the factors of [`lu_factor`]: the row swaps and eliminations
/// of each stage applied to `b` in stage order, then back substitution with U. `b` (length m)
/// receives x.
pub(crate) fn lu_solve(a: &[f64], pivots: &[usize], multipliers: &[f64], b: &mut [f64], m: usize) {
    for col in 0..m {
        let pivot_row = pivots[col];
        if pivot_row != col {
            b.swap(col, pivot_row);
        }
        let b_col = b[col];
        let stage_multipliers = &multipliers[col * m + col + 1..(col + 1) * m];
        for (x, &factor) in b[col + 1..m].iter_mut().zip(stage_multipliers) {
            if factor == 0.0 {
                continue;
            }
            *x -= factor * b_col;
        }
    }
    for col in (0..m).rev() {
        let mut sum = b[col];
        for j in col + 1..m {
            sum -= a[col * m + j] * b[j];
        }
        b[col] = sum / a[col * m + col];
    }
}

/// Solves `a x = b` in place (`a` destroyed, `b` receives x) by [`lu_factor`] and [`lu_solve`];
/// false for a singular system. Allocates its scratch: for tests.
#[cfg(test)]
pub(crate) fn solve_in_place(a: &mut [f64], b: &mut [f64], m: usize) -> bool {
    let (mut pivots, mut multipliers) = (vec![0; m], vec![0.0; m * m]);
    if !lu_factor(a, &mut pivots, &mut multipliers, m) {
        return false;
    }
    lu_solve(a, &pivots, &multipliers, b, m);
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

/// y = A x for a row-major `rows × cols` matrix: each y_r = [`dot`] of row r with x (the same
/// sums, bit for bit), two rows at a time so that they share the loads of x.
pub(crate) fn mat_vec(a: &[f64], x: &[f64], y: &mut [f64], rows: usize, cols: usize) {
    if cols == 0 {
        // A vehicle without DOFs (moving forces): each row's empty dot.
        y[..rows].fill(0.0);
        return;
    }
    let x = &x[..cols];
    let mut pairs = a[..rows * cols].chunks_exact(2 * cols);
    for (pair, out) in (&mut pairs).zip(y.chunks_exact_mut(2)) {
        let (first, second) = pair.split_at(cols);
        (out[0], out[1]) = dot_two(first, second, x);
    }
    if rows % 2 == 1 {
        y[rows - 1] = dot(pairs.remainder(), x);
    }
}

/// ([`dot`] of a and x, [`dot`] of b and x), each summed exactly as [`dot`] sums it.
#[inline]
fn dot_two(a: &[f64], b: &[f64], x: &[f64]) -> (f64, f64) {
    let n = x.len();
    let (a, b) = (&a[..n], &b[..n]);
    let (mut acc_a, mut acc_b) = ([0.0; 4], [0.0; 4]);
    let chunks = n / 4;
    for c in 0..chunks {
        let i = 4 * c;
        for l in 0..4 {
            acc_a[l] += a[i + l] * x[i + l];
            acc_b[l] += b[i + l] * x[i + l];
        }
    }
    let mut sum_a = (acc_a[0] + acc_a[1]) + (acc_a[2] + acc_a[3]);
    let mut sum_b = (acc_b[0] + acc_b[1]) + (acc_b[2] + acc_b[3]);
    for i in 4 * chunks..n {
        sum_a += a[i] * x[i];
        sum_b += b[i] * x[i];
    }
    (sum_a, sum_b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mat_vec_gives_each_rows_dot_bit_for_bit() {
        // Self-consistency: rows in pairs and an odd last row, lengths with and without a tail,
        // and no rows or no columns (a vehicle without DOFs: moving forces).
        for (rows, cols) in [
            (1, 3),
            (2, 4),
            (5, 7),
            (15, 15),
            (6, 9),
            (0, 4),
            (3, 0),
            (0, 0),
        ] {
            let a: Vec<f64> = (0..rows * cols)
                .map(|i| (0.7 * i as f64).sin() * 1e3)
                .collect();
            let x: Vec<f64> = (0..cols).map(|i| (1.3 * i as f64).cos() * 1e-2).collect();
            let mut y = vec![f64::NAN; rows];
            mat_vec(&a, &x, &mut y, rows, cols);
            for r in 0..rows {
                let expected = dot(&a[r * cols..(r + 1) * cols], &x);
                assert_eq!(
                    y[r].to_bits(),
                    expected.to_bits(),
                    "{rows} x {cols}, row {r}"
                );
            }
        }
    }

    /// The fused elimination the solver used before the factorisation was split into
    /// [`lu_factor`] and [`lu_solve`]: the reference of the bit-for-bit test below.
    fn fused_elimination(a: &mut [f64], b: &mut [f64], m: usize) -> bool {
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

    #[test]
    fn split_factorisation_matches_the_fused_elimination_bit_for_bit() {
        // Pseudo-random 10 × 10 systems with zeros (skipped multipliers) and row swaps.
        let m = 10;
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for trial in 0..50 {
            let mut a: Vec<f64> = (0..m * m).map(|_| next()).collect();
            for i in 0..m {
                if (i + trial) % 3 == 0 {
                    a[i * m + (i + 1) % m] = 0.0;
                }
            }
            let b: Vec<f64> = (0..m).map(|_| next()).collect();
            let (mut a_fused, mut b_fused) = (a.clone(), b.clone());
            assert!(fused_elimination(&mut a_fused, &mut b_fused, m));
            let (mut pivots, mut multipliers, mut x) = (vec![0; m], vec![0.0; m * m], b.clone());
            assert!(lu_factor(&mut a, &mut pivots, &mut multipliers, m));
            lu_solve(&a, &pivots, &multipliers, &mut x, m);
            assert_eq!(
                x.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                b_fused.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
            );
        }
    }

    #[test]
    fn the_split_factorisation_reports_a_singular_system() {
        let mut a = vec![1.0, 2.0, 2.0, 4.0];
        let (mut pivots, mut multipliers) = (vec![0; 2], vec![0.0; 4]);
        assert!(!lu_factor(&mut a, &mut pivots, &mut multipliers, 2));
    }
}
