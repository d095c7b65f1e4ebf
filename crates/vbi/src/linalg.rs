//! The only file that imports faer: sparse matrices, sparse Cholesky, shift-invert Lanczos,
//! and the small dense eigen solver used for tests and tiny models.
//!
//! faer breaks its API at each 0.x minor release, so it stays behind this facade.

/// A square sparse matrix in compressed sparse column form, both triangles stored.
/// Built from triplets, duplicates summed.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SparseMatrix {
    /// Number of rows and columns.
    pub size: usize,
    /// Column pointers, `size + 1` entries.
    pub column_pointers: Vec<usize>,
    /// Row index of each stored entry, ascending within a column.
    pub row_indices: Vec<usize>,
    /// Value of each stored entry.
    pub values: Vec<f64>,
}

impl SparseMatrix {
    /// Builds the matrix from `(row, column, value)` triplets; duplicates are summed, explicit
    /// zeros kept. Panics only on an index ≥ `size` (a programming error, never user input).
    pub fn from_triplets(size: usize, triplets: &[(usize, usize, f64)]) -> Self {
        let mut counts = vec![0usize; size + 1];
        for &(r, c, _) in triplets {
            assert!(
                r < size && c < size,
                "triplet ({r}, {c}) outside a {size}×{size} matrix"
            );
            counts[c + 1] += 1;
        }
        for c in 0..size {
            counts[c + 1] += counts[c];
        }
        let mut next = counts.clone();
        let mut rows = vec![0usize; triplets.len()];
        let mut vals = vec![0.0; triplets.len()];
        for &(r, c, v) in triplets {
            rows[next[c]] = r;
            vals[next[c]] = v;
            next[c] += 1;
        }
        // Sort each column by row and sum duplicates.
        let mut column_pointers = Vec::with_capacity(size + 1);
        let mut row_indices = Vec::with_capacity(triplets.len());
        let mut values = Vec::with_capacity(triplets.len());
        column_pointers.push(0);
        let mut order: Vec<(usize, f64)> = Vec::new();
        for c in 0..size {
            order.clear();
            order.extend((counts[c]..counts[c + 1]).map(|k| (rows[k], vals[k])));
            order.sort_by_key(|&(r, _)| r);
            for &(r, v) in &order {
                if row_indices.len() > *column_pointers.last().unwrap()
                    && *row_indices.last().unwrap() == r
                {
                    *values.last_mut().unwrap() += v;
                } else {
                    row_indices.push(r);
                    values.push(v);
                }
            }
            column_pointers.push(row_indices.len());
        }
        Self {
            size,
            column_pointers,
            row_indices,
            values,
        }
    }

    /// y = A x.
    pub fn multiply(&self, x: &[f64], y: &mut [f64]) {
        y[..self.size].fill(0.0);
        for c in 0..self.size {
            let xc = x[c];
            for k in self.column_pointers[c]..self.column_pointers[c + 1] {
                y[self.row_indices[k]] += self.values[k] * xc;
            }
        }
    }

    /// Number of stored entries.
    pub fn stored_entries(&self) -> usize {
        self.values.len()
    }

    /// The diagonal.
    pub fn diagonal(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.size];
        for c in 0..self.size {
            for k in self.column_pointers[c]..self.column_pointers[c + 1] {
                if self.row_indices[k] == c {
                    d[c] += self.values[k];
                }
            }
        }
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triplets_with_duplicates_are_summed_and_multiply_correctly() {
        let a = SparseMatrix::from_triplets(
            3,
            &[
                (0, 0, 2.0),
                (1, 0, -1.0),
                (0, 1, -1.0),
                (1, 1, 1.0),
                (1, 1, 1.0),
                (2, 2, 3.0),
            ],
        );
        assert_eq!(a.stored_entries(), 5);
        let mut y = [0.0; 3];
        a.multiply(&[1.0, 2.0, 3.0], &mut y);
        assert_eq!(y, [0.0, 3.0, 9.0]);
        assert_eq!(a.diagonal(), vec![2.0, 2.0, 3.0]);
    }
}
