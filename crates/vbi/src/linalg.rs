//! The only file that imports faer: sparse matrices, sparse Cholesky, shift-invert Lanczos,
//! and the small dense eigen solver used for tests and tiny models.
//!
//! faer breaks its API at each 0.x minor release, so it stays behind this facade.
use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Accum, Conj, Mat, MatMut, MatRef, Par, Side};
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use thiserror::Error;

/// A square sparse matrix in compressed sparse column form, both triangles stored.
/// Built from triplets, duplicates summed.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize, serde::Deserialize)]
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

    /// The 1-norm ‖A‖₁ = max_j Σ_i |a_ij| (the largest absolute column sum).
    pub fn one_norm(&self) -> f64 {
        (0..self.size)
            .map(|c| {
                self.values[self.column_pointers[c]..self.column_pointers[c + 1]]
                    .iter()
                    .map(|v| v.abs())
                    .sum::<f64>()
            })
            .fold(0.0, f64::max)
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

impl SparseMatrix {
    /// The linear combination `alpha · a + beta · b` of two matrices of the same size, on the
    /// union of their patterns. Panics only on a size mismatch (a programming error).
    pub fn linear_combination(alpha: f64, a: &SparseMatrix, beta: f64, b: &SparseMatrix) -> Self {
        assert_eq!(
            a.size, b.size,
            "linear combination of matrices of different sizes"
        );
        let size = a.size;
        let mut column_pointers = Vec::with_capacity(size + 1);
        let mut row_indices = Vec::with_capacity(a.values.len().max(b.values.len()));
        let mut values = Vec::with_capacity(row_indices.capacity());
        column_pointers.push(0);
        for c in 0..size {
            let (mut i, ie) = (a.column_pointers[c], a.column_pointers[c + 1]);
            let (mut j, je) = (b.column_pointers[c], b.column_pointers[c + 1]);
            while i < ie || j < je {
                let ra = if i < ie { a.row_indices[i] } else { usize::MAX };
                let rb = if j < je { b.row_indices[j] } else { usize::MAX };
                if ra == rb {
                    row_indices.push(ra);
                    values.push(alpha * a.values[i] + beta * b.values[j]);
                    i += 1;
                    j += 1;
                } else if ra < rb {
                    row_indices.push(ra);
                    values.push(alpha * a.values[i]);
                    i += 1;
                } else {
                    row_indices.push(rb);
                    values.push(beta * b.values[j]);
                    j += 1;
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

    /// xᵀ A y.
    pub fn bilinear(&self, x: &[f64], y: &[f64]) -> f64 {
        let mut sum = 0.0;
        for c in 0..self.size {
            let mut column = 0.0;
            for k in self.column_pointers[c]..self.column_pointers[c + 1] {
                column += self.values[k] * x[self.row_indices[k]];
            }
            sum += column * y[c];
        }
        sum
    }

    /// The matrix as a dense column-major array (tests and tiny models only).
    pub fn to_dense(&self) -> Vec<f64> {
        let n = self.size;
        let mut dense = vec![0.0; n * n];
        for c in 0..n {
            for k in self.column_pointers[c]..self.column_pointers[c + 1] {
                dense[c * n + self.row_indices[k]] += self.values[k];
            }
        }
        dense
    }

    fn faer_view(&self) -> SparseColMatRef<'_, usize, f64> {
        let symbolic = SymbolicSparseColMatRef::new_checked(
            self.size,
            self.size,
            &self.column_pointers,
            None,
            &self.row_indices,
        );
        SparseColMatRef::new(symbolic, &self.values)
    }
}

/// Errors of the sparse factorisation.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LinalgError {
    /// Cholesky met a zero or negative pivot: the matrix is singular or indefinite.
    #[error(
        "the matrix is not positive definite: the Cholesky factorisation met a non-positive pivot \
         at degree of freedom {dof} (of {size})"
    )]
    NotPositiveDefinite {
        /// The degree of freedom (original numbering) whose pivot failed.
        dof: usize,
        /// Size of the matrix.
        size: usize,
    },
    /// A matrix of another size or pattern than the one analysed.
    #[error("the matrix ({found_size}×{found_size}, {found_entries} entries) does not match the analysed pattern ({expected_size}×{expected_size}, {expected_entries} entries)")]
    PatternMismatch {
        /// Size of the analysed pattern.
        expected_size: usize,
        /// Stored entries of the analysed pattern.
        expected_entries: usize,
        /// Size of the matrix given.
        found_size: usize,
        /// Stored entries of the matrix given.
        found_entries: usize,
    },
    /// A right-hand side of the wrong length.
    #[error("right-hand side of length {found} for a system of size {expected}")]
    RightHandSideLength {
        /// Expected length (size × count).
        expected: usize,
        /// Length given.
        found: usize,
    },
    /// A non-finite entry in the matrix.
    #[error("the matrix has a non-finite entry {value} at row {row}, column {column}")]
    NonFinite {
        /// Row of the entry.
        row: usize,
        /// Column of the entry.
        column: usize,
        /// The value.
        value: f64,
    },
    /// faer could not allocate or analyse.
    #[error("sparse factorisation failed: {message}")]
    Internal {
        /// faer's message.
        message: String,
    },
}

/// The symbolic sparse Cholesky analysis of a pattern (fill-reducing AMD ordering and the
/// elimination tree): computed once, reused by every numeric factorisation of a matrix with the
/// same pattern (K, K − σM on the union pattern, ...).
#[derive(Debug, Clone)]
pub struct CholeskyPattern {
    symbolic: Arc<SymbolicCholesky<usize>>,
    size: usize,
    column_pointers: Vec<usize>,
    row_indices: Vec<usize>,
}

impl CholeskyPattern {
    /// Analyses the pattern of `matrix` (both triangles stored; the upper one is read).
    pub fn analyse(matrix: &SparseMatrix) -> Result<Self, LinalgError> {
        let view = matrix.faer_view();
        let symbolic = factorize_symbolic_cholesky(
            view.symbolic(),
            Side::Upper,
            SymmetricOrdering::Amd,
            Default::default(),
        )
        .map_err(|e| LinalgError::Internal {
            message: format!("{e:?}"),
        })?;
        Ok(Self {
            symbolic: Arc::new(symbolic),
            size: matrix.size,
            column_pointers: matrix.column_pointers.clone(),
            row_indices: matrix.row_indices.clone(),
        })
    }

    /// Number of nonzeros of the factor L.
    pub fn factor_entries(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Bytes that [`CholeskyPattern::factorise`] allocates: the factor's values and the
    /// numeric factorisation's scratch (both known from the symbolic analysis, before any
    /// numeric work).
    pub fn factorisation_bytes(&self) -> u64 {
        let scratch = self
            .symbolic
            .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
            .size_bytes();
        8 * self.symbolic.len_val() as u64 + scratch as u64
    }

    /// The numeric factorisation A = L Lᵀ of a matrix with this pattern.
    pub fn factorise(&self, matrix: &SparseMatrix) -> Result<CholeskyFactor, LinalgError> {
        if matrix.size != self.size
            || matrix.column_pointers != self.column_pointers
            || matrix.row_indices != self.row_indices
        {
            return Err(LinalgError::PatternMismatch {
                expected_size: self.size,
                expected_entries: self.row_indices.len(),
                found_size: matrix.size,
                found_entries: matrix.row_indices.len(),
            });
        }
        for c in 0..matrix.size {
            for k in matrix.column_pointers[c]..matrix.column_pointers[c + 1] {
                if !matrix.values[k].is_finite() {
                    return Err(LinalgError::NonFinite {
                        row: matrix.row_indices[k],
                        column: c,
                        value: matrix.values[k],
                    });
                }
            }
        }
        let par = Par::Seq;
        let mut values = vec![0.0; self.symbolic.len_val()];
        let mut buffer = MemBuffer::try_new(
            self.symbolic
                .factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|e| LinalgError::Internal {
            message: format!("{e:?}"),
        })?;
        let result = self.symbolic.factorize_numeric_llt(
            &mut values,
            matrix.faer_view(),
            Side::Upper,
            LltRegularization::default(),
            par,
            MemStack::new(&mut buffer),
            Default::default(),
        );
        if let Err(error) = result {
            return Err(match error {
                faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                    // faer 0.24 reports a 1-based column from its simplicial factorisation and a
                    // 0-based one from the supernodal (dense-block) one, both in permuted order.
                    let index = match self.symbolic.raw() {
                        faer::sparse::linalg::cholesky::SymbolicCholeskyRaw::Simplicial(_) => {
                            index.saturating_sub(1)
                        }
                        faer::sparse::linalg::cholesky::SymbolicCholeskyRaw::Supernodal(_) => index,
                    };
                    let dof = match self.symbolic.perm() {
                        Some(perm) => perm.arrays().0.get(index).copied().unwrap_or(index),
                        None => index,
                    };
                    LinalgError::NotPositiveDefinite {
                        dof,
                        size: self.size,
                    }
                }
            });
        }
        Ok(CholeskyFactor {
            pattern: self.clone(),
            values,
        })
    }
}

/// A sparse Cholesky factor A = L Lᵀ (faer's supernodal or simplicial LLᵀ, AMD ordering),
/// ready to solve A x = b for one or many right-hand sides.
#[derive(Debug, Clone)]
pub struct CholeskyFactor {
    pattern: CholeskyPattern,
    values: Vec<f64>,
}

impl CholeskyFactor {
    /// Analyses and factorises `matrix` in one call.
    pub fn new(matrix: &SparseMatrix) -> Result<Self, LinalgError> {
        CholeskyPattern::analyse(matrix)?.factorise(matrix)
    }

    /// The symbolic analysis, to factorise another matrix of the same pattern.
    pub fn pattern(&self) -> &CholeskyPattern {
        &self.pattern
    }

    /// Size of the system.
    pub fn size(&self) -> usize {
        self.pattern.size
    }

    /// Solves A x = b in place (`rhs` holds b on entry, x on exit).
    pub fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), LinalgError> {
        self.solve_many_in_place(rhs, 1)
    }

    /// Solves A X = B in place for `count` right-hand sides stored column-major in `rhs`
    /// (`rhs[j * size + i]` is row i of column j).
    pub fn solve_many_in_place(&self, rhs: &mut [f64], count: usize) -> Result<(), LinalgError> {
        let n = self.size();
        if rhs.len() != n * count {
            return Err(LinalgError::RightHandSideLength {
                expected: n * count,
                found: rhs.len(),
            });
        }
        if n == 0 || count == 0 {
            return Ok(());
        }
        let matrix = MatMut::from_column_major_slice_mut(rhs, n, count);
        self.solve_mat(matrix);
        Ok(())
    }

    fn solve_mat(&self, matrix: MatMut<'_, f64>) {
        let par = Par::Seq;
        let count = matrix.ncols();
        let mut buffer = MemBuffer::new(
            self.pattern
                .symbolic
                .solve_in_place_scratch::<f64>(count, par),
        );
        LltRef::new(&self.pattern.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            matrix,
            par,
            MemStack::new(&mut buffer),
        );
    }
}

/// The lowest eigenpairs of K φ = λ M φ.
#[derive(Debug, Clone, PartialEq)]
pub struct Eigenpairs {
    /// Size n of the problem.
    pub size: usize,
    /// Eigenvalues λ = ω² [rad²/s² for K in N/m and M in kg], ascending.
    pub eigenvalues: Vec<f64>,
    /// M-normalised eigenvectors (φᵀ M φ = 1), column-major: vector k is
    /// `vectors[k * size .. (k + 1) * size]`. Sign: the largest-magnitude entry is positive.
    pub vectors: Vec<f64>,
    /// Backward error ‖Kφ − λMφ‖₂ / ((‖K‖₁ + |λ|‖M‖₁)‖φ‖₂) of each pair [-]
    /// ([`backward_error`]).
    pub residuals: Vec<f64>,
}

impl Eigenpairs {
    /// Number of pairs.
    pub fn count(&self) -> usize {
        self.eigenvalues.len()
    }

    /// Eigenvector k.
    pub fn vector(&self, k: usize) -> &[f64] {
        &self.vectors[k * self.size..(k + 1) * self.size]
    }
}

/// Options of the shift-invert Lanczos eigensolver.
#[derive(Debug, Clone, PartialEq)]
pub struct LanczosOptions {
    /// Shift σ [rad²/s²] (default 0). K − σM must be positive definite, so σ must lie below the
    /// lowest eigenvalue; the pairs found are those nearest above σ.
    pub shift: f64,
    /// Convergence tolerance on the Ritz estimate |β_m s_mi| ≤ tolerance · θ_i of the inverted
    /// operator [-] (default 1e-10).
    pub tolerance: f64,
    /// Largest accepted backward error of a returned pair [-] ([`backward_error`], default
    /// 1e-6); a larger one makes the solve fail.
    pub residual_limit: f64,
    /// Dimension of the Krylov space m (default `max(2·count + 10, count + 20)`, at most n;
    /// for 50 modes of a 20,000-DOF grid, m = 110 converges without a restart where m = 100
    /// needs one).
    pub krylov_dimension: Option<usize>,
    /// Maximum number of thick restarts (default 200).
    pub max_restarts: usize,
    /// Seed of the ChaCha starting vector (default 0x5eed).
    pub seed: u64,
}

impl Default for LanczosOptions {
    fn default() -> Self {
        Self {
            shift: 0.0,
            tolerance: 1e-10,
            residual_limit: 1e-6,
            krylov_dimension: None,
            max_restarts: 200,
            seed: 0x5eed,
        }
    }
}

/// Errors of the eigensolvers.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EigenError {
    /// K − σM could not be factorised (singular or indefinite).
    #[error("cannot factorise K − σM with σ = {shift}: {source}")]
    Factorisation {
        /// The shift σ [rad²/s²].
        shift: f64,
        /// The factorisation error.
        source: LinalgError,
    },
    /// K and M differ in size, or the request is empty or larger than the problem.
    #[error("cannot compute {count} eigenpairs of a problem with K {stiffness_size}×{stiffness_size} and M {mass_size}×{mass_size}")]
    InvalidRequest {
        /// Pairs requested.
        count: usize,
        /// Size of K.
        stiffness_size: usize,
        /// Size of M.
        mass_size: usize,
    },
    /// The Lanczos iteration did not converge the wanted pairs.
    #[error("shift-invert Lanczos converged {converged} of {requested} eigenpairs after {restarts} restarts (Krylov dimension {krylov_dimension}, worst Ritz estimate {worst_estimate:e} > tolerance {tolerance:e})")]
    NotConverged {
        /// Pairs requested.
        requested: usize,
        /// Pairs converged.
        converged: usize,
        /// Restarts done.
        restarts: usize,
        /// Krylov dimension m.
        krylov_dimension: usize,
        /// Worst relative Ritz estimate among the wanted pairs.
        worst_estimate: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// A returned pair's true residual is above the limit.
    #[error("eigenpair {index} (λ = {eigenvalue:e}) has backward error ‖Kφ − λMφ‖/((‖K‖ + |λ|‖M‖)‖φ‖) = {residual:e} > limit {limit:e}: it is not an eigenpair of the model")]
    ResidualTooLarge {
        /// 0-based index of the pair.
        index: usize,
        /// Its eigenvalue.
        eigenvalue: f64,
        /// Its backward error ‖Kφ − λMφ‖₂ / ((‖K‖₁ + |λ|‖M‖₁)‖φ‖₂).
        residual: f64,
        /// The limit.
        limit: f64,
    },
    /// The Krylov space closed before reaching the wanted count: M has fewer nonzero
    /// directions than pairs requested.
    #[error("only {available} eigenpairs exist with a nonzero mass (requested {requested})")]
    SubspaceExhausted {
        /// Pairs requested.
        requested: usize,
        /// Dimension of the invariant subspace found.
        available: usize,
    },
    /// M is not positive definite (dense solver).
    #[error("the mass matrix is not positive definite (dense Cholesky failed)")]
    MassNotPositiveDefinite,
    /// The dense solver refuses large problems (O(n³)).
    #[error("the dense eigensolver is limited to {limit} degrees of freedom, got {size}")]
    TooLargeForDense {
        /// Size n.
        size: usize,
        /// The limit.
        limit: usize,
    },
}

/// Largest problem the dense reference solver accepts.
pub const DENSE_EIGEN_LIMIT: usize = 2000;

/// Norms of K and M for [`backward_error`]: the matrix 1-norms ‖A‖₁ = max_j Σ_i |a_ij|
/// (equal to the ∞-norm, A being symmetric).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PencilNorms {
    /// ‖K‖₁ [N/m].
    pub stiffness: f64,
    /// ‖M‖₁ [kg].
    pub mass: f64,
}

impl PencilNorms {
    /// The 1-norms of K and M.
    pub fn of(k: &SparseMatrix, m: &SparseMatrix) -> Self {
        Self {
            stiffness: k.one_norm(),
            mass: m.one_norm(),
        }
    }
}

/// Normwise backward error of an eigenpair (Higham & Higham 1998; Tisseur 2000),
/// η(λ, φ) = ‖Kφ − λMφ‖₂ / ((‖K‖₁ + |λ| ‖M‖₁) ‖φ‖₂) [-]:
/// (λ, φ) is an exact eigenpair of (K + ΔK, M + ΔM) with ‖ΔK‖ ≤ η‖K‖ and ‖ΔM‖ ≤ η‖M‖.
///
/// The matrix 1-norm (the largest absolute column sum) is cheap, and it bounds the spectral
/// norm from above (‖A‖₂ ≤ ‖A‖₁ for a symmetric A, Gershgorin) while exceeding it by at most
/// √(entries per row) (a handful for FE matrices), so η is the spectral-norm backward error to
/// within that factor. Round-off in Kφ is about u‖K‖‖φ‖ (u = 1.1e-16), so a converged pair has
/// η of order 1e-15 for every mode, low or high, whatever the mesh size: unlike ‖r‖/‖Kφ‖, which
/// for mode 1 is η times ‖K‖/(ω₁²‖M‖) ≈ λ_max/λ₁ ∝ (L/h)⁴ and so reaches any fixed limit on a
/// fine enough mesh. η cannot see an error confined to the lowest modes (a mix of modes 1 and 2
/// has η ≈ (λ₂ − λ₁)/λ_max): those are controlled by the Lanczos convergence test on the
/// shift-inverted operator, relative to θ = 1/(λ − σ).
pub fn backward_error(
    k: &SparseMatrix,
    m: &SparseMatrix,
    norms: PencilNorms,
    eigenvalue: f64,
    vector: &[f64],
) -> f64 {
    let n = k.size;
    let mut kx = vec![0.0; n];
    let mut mx = vec![0.0; n];
    k.multiply(vector, &mut kx);
    m.multiply(vector, &mut mx);
    let residual = (0..n)
        .map(|i| (kx[i] - eigenvalue * mx[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    let vector_norm = vector.iter().map(|v| v * v).sum::<f64>().sqrt();
    let scale = (norms.stiffness + eigenvalue.abs() * norms.mass) * vector_norm;
    if scale > 0.0 {
        residual / scale
    } else {
        residual
    }
}

/// The first pair whose backward error is NaN or above `limit`, as the error that refuses it.
/// The one place where eigenpair residuals are judged (the Lanczos and the modal stage).
pub fn check_backward_errors(pairs: &Eigenpairs, limit: f64) -> Result<(), EigenError> {
    let refused = pairs
        .residuals
        .iter()
        .position(|&residual| residual.is_nan() || residual > limit);
    match refused {
        Some(index) => Err(EigenError::ResidualTooLarge {
            index,
            eigenvalue: pairs.eigenvalues[index],
            residual: pairs.residuals[index],
            limit,
        }),
        None => Ok(()),
    }
}

/// M-normalises a vector, makes its largest-magnitude entry positive, and returns its Rayleigh
/// quotient λ = φᵀKφ / φᵀMφ.
fn normalise_pair(k: &SparseMatrix, m: &SparseMatrix, vector: &mut [f64]) -> f64 {
    let mass = m.bilinear(vector, vector);
    let stiffness = k.bilinear(vector, vector);
    let mut largest = 0.0f64;
    for &v in vector.iter() {
        if v.abs() > largest.abs() {
            largest = v;
        }
    }
    let scale = largest.signum() / mass.sqrt();
    for v in vector.iter_mut() {
        *v *= scale;
    }
    stiffness / mass
}

/// The `count` lowest eigenpairs of K φ = λ M φ (K, M symmetric; K − σM positive definite) by
/// shift-invert Lanczos with full M-reorthogonalisation and thick restarts.
///
/// Hand-written: no maintained Rust crate does a sparse generalized shift-invert Lanczos well
/// (faer has no sparse eigensolver; the Lanczos/ARPACK ports handle only standard problems or
/// dense matrices), so it is done here on faer's sparse Cholesky.
///
/// Method (Ericsson & Ruhe 1980; thick restart of Wu & Simon 2000):
/// - operator A = (K − σM)⁻¹ M, self-adjoint in the M-inner product ⟨x, y⟩ = xᵀMy; its
///   eigenvalues θ = 1/(λ − σ) are largest for the λ nearest above σ. One sparse Cholesky
///   factorisation of K − σM serves every application of A (two triangular solves each).
/// - Lanczos: V = [v₁ … v_m] M-orthonormal, H = VᵀMAV (m × m, tridiagonal, arrow-shaped after a
///   restart). Each new vector is M-orthogonalised against all previous ones by classical
///   Gram–Schmidt done twice ("twice is enough", Giraud et al. 2005), with MV stored so that an
///   M-inner product is one dot product.
/// - The small symmetric H is diagonalised by nalgebra's `SymmetricEigen` (not faer's dense
///   self-adjoint solver, which is known to return wrong eigenvectors at n ≳ 1000). A Ritz pair
///   (θ_i, V s_i) has residual norm ‖A x − θ x‖_M = |β_m s_mi|, and converges when that is
///   ≤ tolerance · θ_i.
/// - Thick restart: keep the best k Ritz vectors and the residual vector, and extend again to m.
/// - When M is singular (massless DOFs) the Ritz vectors are purified, x ← A x.
/// - Returned vectors are M-normalised, with λ their Rayleigh quotient φᵀKφ, and the true
///   backward error ([`backward_error`]) checked against `options.residual_limit`.
///
/// Cost per solve: one sparse factorisation, about m + (restarts × (m − k)) pairs of triangular
/// solves and O(n m²) dense work; nothing dense O(n³).
pub fn lowest_eigenpairs(
    k: &SparseMatrix,
    m: &SparseMatrix,
    count: usize,
    options: &LanczosOptions,
) -> Result<Eigenpairs, EigenError> {
    let shifted = SparseMatrix::linear_combination(1.0, k, -options.shift, m);
    let factor = CholeskyFactor::new(&shifted).map_err(|source| EigenError::Factorisation {
        shift: options.shift,
        source,
    })?;
    lowest_eigenpairs_with_factor(k, m, &factor, count, options)
}

/// The Krylov dimension of [`lowest_eigenpairs_with_factor`] for `count` pairs of a problem of
/// size n: the option's, or max(2·count + 10, count + 20), within count..=n.
pub fn krylov_dimension(n: usize, count: usize, options: &LanczosOptions) -> usize {
    let dim = options
        .krylov_dimension
        .unwrap_or((2 * count + 10).max(count + 20))
        .clamp(count.min(n), n);
    dim.max(count)
}

/// Bytes that [`lowest_eigenpairs_with_factor`] allocates for `count` pairs of a problem of
/// size n (the factor aside): the Krylov basis V and MV, n × (dim + 1) each, the projected
/// matrix and its eigenvectors, dim × dim each, and the n × count eigenvectors returned.
pub fn lanczos_bytes(n: usize, count: usize, options: &LanczosOptions) -> u64 {
    let (n, count, dim) = (
        n as u64,
        count as u64,
        krylov_dimension(n, count, options) as u64,
    );
    8 * (2 * n * (dim + 1) + 2 * dim * dim + n * count)
}

/// As [`lowest_eigenpairs`], with the factor of K − σM (σ = `options.shift`) already computed.
pub fn lowest_eigenpairs_with_factor(
    k: &SparseMatrix,
    m: &SparseMatrix,
    factor: &CholeskyFactor,
    count: usize,
    options: &LanczosOptions,
) -> Result<Eigenpairs, EigenError> {
    let n = k.size;
    if count == 0 || count > n || m.size != n || factor.size() != n {
        return Err(EigenError::InvalidRequest {
            count,
            stiffness_size: n,
            mass_size: m.size,
        });
    }
    let mut lanczos = Lanczos::new(m, factor, count, options);
    let dim = lanczos.dim;
    if !lanczos.fresh_vector(0) {
        return Err(EigenError::SubspaceExhausted {
            requested: count,
            available: 0,
        });
    }
    let mut start = 0; // first column to extend from
    let mut restarts = 0;
    loop {
        let (j, beta) = lanczos.extend(start)?;
        let ritz = lanczos.ritz_pairs(j.min(dim), beta);
        let (converged, worst) = ritz.convergence(count, options.tolerance);
        if converged == count {
            let mut phi = lanczos.ritz_vectors(&ritz, count);
            if m.diagonal().iter().any(|&d| d <= 0.0) {
                purify(m, factor, &mut phi, count);
            }
            return normalised_eigenpairs(k, m, &phi, options.residual_limit);
        }
        if restarts >= options.max_restarts || ritz.size < dim {
            return Err(EigenError::NotConverged {
                requested: count,
                converged,
                restarts,
                krylov_dimension: dim,
                worst_estimate: worst,
                tolerance: options.tolerance,
            });
        }
        restarts += 1;
        start = lanczos.thick_restart(&ritz);
    }
}

/// The state of the shift-invert Lanczos of [`lowest_eigenpairs_with_factor`]: the
/// M-orthonormal basis V and Z = MV (n × (dim + 1), one extra column for the residual vector),
/// the projected matrix H = VᵀMAV (dim × dim), the random source of fresh start vectors and
/// the work vectors.
struct Lanczos<'a> {
    m: &'a SparseMatrix,
    factor: &'a CholeskyFactor,
    /// Number of pairs wanted.
    count: usize,
    /// Krylov dimension.
    dim: usize,
    v: Mat<f64>,
    z: Mat<f64>,
    h: nalgebra::DMatrix<f64>,
    rng: ChaCha8Rng,
    work: Vec<f64>,
    mw: Vec<f64>,
    coefficients: Vec<f64>,
    pass_coefficients: Vec<f64>,
}

/// Applies A to `x` into `out`: out = (K − σM)⁻¹ M x (`buffer` holds M x).
fn apply_shift_invert(
    m: &SparseMatrix,
    factor: &CholeskyFactor,
    x: &[f64],
    out: &mut [f64],
    buffer: &mut [f64],
) {
    m.multiply(x, buffer);
    out.copy_from_slice(buffer);
    factor.solve_in_place(out).expect("sizes checked on entry");
}

impl<'a> Lanczos<'a> {
    /// An empty factorisation of the Krylov dimension for `count` pairs, its random source
    /// seeded by `options.seed`.
    fn new(
        m: &'a SparseMatrix,
        factor: &'a CholeskyFactor,
        count: usize,
        options: &LanczosOptions,
    ) -> Self {
        let n = m.size;
        let dim = krylov_dimension(n, count, options);
        Lanczos {
            m,
            factor,
            count,
            dim,
            v: Mat::<f64>::zeros(n, dim + 1),
            z: Mat::<f64>::zeros(n, dim + 1),
            h: nalgebra::DMatrix::<f64>::zeros(dim, dim),
            rng: ChaCha8Rng::seed_from_u64(options.seed),
            work: vec![0.0; n],
            mw: vec![0.0; n],
            coefficients: vec![0.0; dim + 1],
            pass_coefficients: vec![0.0; dim + 1],
        }
    }

    /// Writes a fresh random vector of range(A), M-orthonormal to columns 0..j, into column j
    /// (A applied to a uniform random vector, then Gram–Schmidt twice; up to three attempts).
    /// Returns false when nothing is left (the invariant subspace is exhausted).
    fn fresh_vector(&mut self, j: usize) -> bool {
        let n = self.m.size;
        for _attempt in 0..3 {
            let random: Vec<f64> = (0..n)
                .map(|_| (self.rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64 - 0.5)
                .collect();
            let mut x = vec![0.0; n];
            let mut buffer = vec![0.0; n];
            apply_shift_invert(self.m, self.factor, &random, &mut x, &mut buffer);
            self.m.multiply(&x, &mut buffer);
            let norm0 = dot(&x, &buffer).max(0.0).sqrt();
            if norm0 == 0.0 {
                continue;
            }
            let mut c = vec![0.0; j];
            for _pass in 0..2 {
                orthogonalise(self.v.as_ref(), self.z.as_ref(), j, &mut x, &mut c);
            }
            self.m.multiply(&x, &mut buffer);
            let norm = dot(&x, &buffer).max(0.0).sqrt();
            if norm > 1e-8 * norm0 {
                divide_into(self.v.col_as_slice_mut(j), &x, norm);
                divide_into(self.z.col_as_slice_mut(j), &buffer, norm);
                return true;
            }
        }
        false
    }

    /// Extends the Lanczos factorisation from column `start` to `dim`: v_{j+1} β_j =
    /// A v_j − Σ_{i≤j} v_i H_ij, β_j = ‖·‖_M. On a breakdown (β_j ≤ 1e-12 |H_jj|: the Krylov
    /// space is invariant) β_j = 0 and a fresh direction continues it; when none is left the
    /// factorisation stops if it holds `count` vectors, else fails. Returns the number of
    /// columns reached and the last β.
    fn extend(&mut self, start: usize) -> Result<(usize, f64), EigenError> {
        let dim = self.dim;
        let mut beta = 0.0;
        let mut j = start;
        while j < dim {
            let diagonal = self.orthogonalised_operator_column(j);
            self.m.multiply(&self.work, &mut self.mw);
            beta = dot(&self.work, &self.mw).max(0.0).sqrt();
            // Breakdown: the Krylov space is invariant; continue with a fresh direction.
            let scale = diagonal.abs().max(1e-300);
            if beta <= 1e-12 * scale {
                beta = 0.0;
                if j + 1 < dim + 1 && !self.fresh_vector(j + 1) {
                    if j + 1 >= self.count {
                        // Every wanted pair lies in the invariant subspace found so far.
                        j += 1;
                        break;
                    }
                    return Err(EigenError::SubspaceExhausted {
                        requested: self.count,
                        available: j + 1,
                    });
                }
            } else {
                divide_into(self.v.col_as_slice_mut(j + 1), &self.work, beta);
                divide_into(self.z.col_as_slice_mut(j + 1), &self.mw, beta);
            }
            if j + 1 < dim {
                self.h[(j + 1, j)] = beta;
                self.h[(j, j + 1)] = beta;
            }
            j += 1;
        }
        Ok((j, beta))
    }

    /// w = A v_j into `work`, M-orthogonalised against v_0 … v_j by classical Gram–Schmidt
    /// done twice; the coefficients summed over both passes, H_ij = ⟨v_i, A v_j⟩_M, fill row
    /// and column j of H. Returns H_jj.
    fn orthogonalised_operator_column(&mut self, j: usize) -> f64 {
        apply_shift_invert(
            self.m,
            self.factor,
            self.v.col_as_slice(j),
            &mut self.work,
            &mut self.mw,
        );
        let c = &mut self.coefficients[..j + 1];
        c.fill(0.0);
        let pass = &mut self.pass_coefficients[..j + 1];
        for _pass in 0..2 {
            orthogonalise(
                self.v.as_ref(),
                self.z.as_ref(),
                j + 1,
                &mut self.work,
                pass,
            );
            for (ci, pi) in c.iter_mut().zip(pass.iter()) {
                *ci += pi;
            }
        }
        for i in 0..=j {
            self.h[(i, j)] = c[i];
            self.h[(j, i)] = c[i];
        }
        c[j]
    }

    /// The Ritz pairs of the leading `size` × `size` block of H, ordered by descending θ.
    fn ritz_pairs(&self, size: usize, beta: f64) -> RitzPairs {
        let hs = self.h.view((0, 0), (size, size)).into_owned();
        let eigen = nalgebra::SymmetricEigen::new(hs);
        let mut order: Vec<usize> = (0..size).collect();
        order.sort_by(|&a, &b| eigen.eigenvalues[b].total_cmp(&eigen.eigenvalues[a]));
        RitzPairs {
            eigen,
            order,
            size,
            beta,
        }
    }

    /// The Ritz vectors Φ = V S of the first `take` Ritz pairs (n × take).
    fn ritz_vectors(&self, ritz: &RitzPairs, take: usize) -> Mat<f64> {
        let s = ritz.leading_eigenvectors(take);
        let mut phi = Mat::<f64>::zeros(self.m.size, take);
        faer::linalg::matmul::matmul(
            phi.as_mut(),
            Accum::Replace,
            self.v.as_ref().subcols(0, ritz.size),
            s.as_ref(),
            1.0,
            Par::Seq,
        );
        phi
    }

    /// Thick restart: keeps the best k = count + (dim − count)/2 Ritz vectors V S and Z S in
    /// columns 0..k, H = diag(θ) bordered by β s_mi in row and column k (arrow-shaped), and the
    /// residual vector v_{m+1} moved to column k. Returns k, the column to extend from.
    fn thick_restart(&mut self, ritz: &RitzPairs) -> usize {
        let (count, dim, size) = (self.count, self.dim, ritz.size);
        let j_last = size;
        let keep = (count + (dim - count) / 2).clamp(count.min(dim - 1), dim - 1);
        let s = ritz.leading_eigenvectors(keep);
        let n = self.m.size;
        let mut new_v = Mat::<f64>::zeros(n, keep);
        let mut new_z = Mat::<f64>::zeros(n, keep);
        faer::linalg::matmul::matmul(
            new_v.as_mut(),
            Accum::Replace,
            self.v.as_ref().subcols(0, size),
            s.as_ref(),
            1.0,
            Par::Seq,
        );
        faer::linalg::matmul::matmul(
            new_z.as_mut(),
            Accum::Replace,
            self.z.as_ref().subcols(0, size),
            s.as_ref(),
            1.0,
            Par::Seq,
        );
        self.h.fill(0.0);
        for (col, &i) in ritz.order.iter().take(keep).enumerate() {
            self.h[(col, col)] = ritz.eigen.eigenvalues[i];
            let b = ritz.beta * ritz.eigen.eigenvectors[(size - 1, i)];
            if keep < dim {
                self.h[(col, keep)] = b;
                self.h[(keep, col)] = b;
            }
        }
        // Move the residual vector (column j_last) to column `keep`, then the kept vectors.
        for basis in [&mut self.v, &mut self.z] {
            let residual = basis.col(j_last).to_owned();
            basis.col_mut(keep).copy_from(&residual);
        }
        self.v
            .as_mut()
            .subcols_mut(0, keep)
            .copy_from(new_v.as_ref());
        self.z
            .as_mut()
            .subcols_mut(0, keep)
            .copy_from(new_z.as_ref());
        keep
    }
}

/// The Ritz pairs (θ_i, s_i) of the projected matrix H (size × size), their order by
/// descending θ, and the last β of the factorisation.
struct RitzPairs {
    eigen: nalgebra::SymmetricEigen<f64, nalgebra::Dyn>,
    order: Vec<usize>,
    size: usize,
    beta: f64,
}

impl RitzPairs {
    /// The relative Ritz estimate of pair i, |β s_mi| / |θ_i| (‖A x − θ x‖_M = |β s_mi|).
    fn estimate(&self, i: usize) -> f64 {
        let theta = self.eigen.eigenvalues[i];
        (self.beta * self.eigen.eigenvectors[(self.size - 1, i)]).abs() / theta.abs().max(1e-300)
    }

    /// How many of the `count` largest θ have converged (estimate ≤ `tolerance`), and the
    /// worst estimate among them.
    fn convergence(&self, count: usize, tolerance: f64) -> (usize, f64) {
        let wanted = count.min(self.size);
        let mut worst = 0.0f64;
        let mut converged = 0;
        for &i in self.order.iter().take(wanted) {
            let e = self.estimate(i);
            worst = worst.max(e);
            if e <= tolerance {
                converged += 1;
            }
        }
        (converged, worst)
    }

    /// S: the eigenvectors s_i of the first `take` pairs in order, as columns (size × take).
    fn leading_eigenvectors(&self, take: usize) -> Mat<f64> {
        let mut s = Mat::<f64>::zeros(self.size, take);
        for (col, &i) in self.order.iter().take(take).enumerate() {
            for r in 0..self.size {
                s[(r, col)] = self.eigen.eigenvectors[(r, i)];
            }
        }
        s
    }
}

/// Purification when M is singular: the M-norm does not see the massless DOFs, so their Ritz
/// components are not controlled by the Ritz estimate; one more application of A (x ← A x, up
/// to scale) maps each of the `count` vectors back into range(A), where the massless DOFs are
/// statically condensed (Ericsson & Ruhe 1980, Nour-Omid et al. 1987). One
/// multi-right-hand-side solve.
fn purify(m: &SparseMatrix, factor: &CholeskyFactor, phi: &mut Mat<f64>, count: usize) {
    let n = m.size;
    let mut block = vec![0.0; n * count];
    for col in 0..count {
        let x: Vec<f64> = phi.col(col).iter().copied().collect();
        m.multiply(&x, &mut block[col * n..(col + 1) * n]);
    }
    factor
        .solve_many_in_place(&mut block, count)
        .expect("sizes checked on entry");
    for col in 0..count {
        for i in 0..n {
            phi[(i, col)] = block[col * n + i];
        }
    }
}

/// The eigenpairs from the Ritz vectors Φ: each M-normalised with λ its Rayleigh quotient
/// ([`normalise_pair`]), sorted by ascending λ, with its backward error checked against
/// `residual_limit`.
fn normalised_eigenpairs(
    k: &SparseMatrix,
    m: &SparseMatrix,
    phi: &Mat<f64>,
    residual_limit: f64,
) -> Result<Eigenpairs, EigenError> {
    let (n, count) = (k.size, phi.ncols());
    let mut vectors = Vec::with_capacity(n * count);
    let mut pairs: Vec<(f64, Vec<f64>)> = Vec::with_capacity(count);
    for col in 0..count {
        let mut x: Vec<f64> = phi.col(col).iter().copied().collect();
        let lambda = normalise_pair(k, m, &mut x);
        pairs.push((lambda, x));
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let norms = PencilNorms::of(k, m);
    let mut eigenvalues = Vec::with_capacity(count);
    let mut residuals = Vec::with_capacity(count);
    for (lambda, x) in pairs {
        residuals.push(backward_error(k, m, norms, lambda, &x));
        eigenvalues.push(lambda);
        vectors.extend_from_slice(&x);
    }
    let pairs = Eigenpairs {
        size: n,
        eigenvalues,
        vectors,
        residuals,
    };
    check_backward_errors(&pairs, residual_limit)?;
    Ok(pairs)
}

/// out = x / divisor, element by element (a Lanczos vector normalised into its column).
fn divide_into(out: &mut [f64], x: &[f64], divisor: f64) {
    for (o, xi) in out.iter_mut().zip(x) {
        *o = xi / divisor;
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let chunks = a.len() / 4;
    for c in 0..chunks {
        for l in 0..4 {
            acc[l] += a[4 * c + l] * b[4 * c + l];
        }
    }
    let mut sum = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for i in 4 * chunks..a.len() {
        sum += a[i] * b[i];
    }
    sum
}

/// One classical Gram–Schmidt pass in the M-inner product: c = Zᵀx over the first `count`
/// columns, x ← x − V c.
fn orthogonalise(
    v: MatRef<'_, f64>,
    z: MatRef<'_, f64>,
    count: usize,
    x: &mut [f64],
    c: &mut [f64],
) {
    let n = x.len();
    if count == 0 {
        return;
    }
    let mut cm = Mat::<f64>::zeros(count, 1);
    let xm = MatRef::from_column_major_slice(x, n, 1);
    faer::linalg::matmul::matmul(
        cm.as_mut(),
        Accum::Replace,
        z.subcols(0, count).transpose(),
        xm,
        1.0,
        Par::Seq,
    );
    let xm = MatMut::from_column_major_slice_mut(x, n, 1);
    faer::linalg::matmul::matmul(
        xm,
        Accum::Add,
        v.subcols(0, count),
        cm.as_ref(),
        -1.0,
        Par::Seq,
    );
    for i in 0..count {
        c[i] = cm[(i, 0)];
    }
}

/// Dense reference solver for small problems and tests: M = LLᵀ (nalgebra Cholesky),
/// C = L⁻¹ K L⁻ᵀ, C = Y Λ Yᵀ (nalgebra `SymmetricEigen`), φ = L⁻ᵀ y. Returns the `count`
/// lowest pairs, M-normalised, with their residuals. O(n³): refused above
/// [`DENSE_EIGEN_LIMIT`] degrees of freedom.
pub fn dense_lowest_eigenpairs(
    k: &SparseMatrix,
    m: &SparseMatrix,
    count: usize,
) -> Result<Eigenpairs, EigenError> {
    let n = k.size;
    if count == 0 || count > n || m.size != n {
        return Err(EigenError::InvalidRequest {
            count,
            stiffness_size: n,
            mass_size: m.size,
        });
    }
    if n > DENSE_EIGEN_LIMIT {
        return Err(EigenError::TooLargeForDense {
            size: n,
            limit: DENSE_EIGEN_LIMIT,
        });
    }
    let kd = nalgebra::DMatrix::from_column_slice(n, n, &k.to_dense());
    let md = nalgebra::DMatrix::from_column_slice(n, n, &m.to_dense());
    let chol = nalgebra::Cholesky::new(md).ok_or(EigenError::MassNotPositiveDefinite)?;
    let l = chol.l();
    // C = L⁻¹ K L⁻ᵀ.
    let x = l
        .solve_lower_triangular(&kd)
        .ok_or(EigenError::MassNotPositiveDefinite)?;
    let c = l
        .solve_lower_triangular(&x.transpose())
        .ok_or(EigenError::MassNotPositiveDefinite)?;
    let c = (&c + c.transpose()) * 0.5;
    let eigen = nalgebra::SymmetricEigen::new(c);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
    let lt = l.transpose();
    let mut eigenvalues = Vec::with_capacity(count);
    let mut vectors = Vec::with_capacity(n * count);
    let mut residuals = Vec::with_capacity(count);
    let norms = PencilNorms::of(k, m);
    for &i in order.iter().take(count) {
        let y = eigen.eigenvectors.column(i).into_owned();
        let phi = lt
            .solve_upper_triangular(&y)
            .ok_or(EigenError::MassNotPositiveDefinite)?;
        let mut x: Vec<f64> = phi.iter().copied().collect();
        let lambda = normalise_pair(k, m, &mut x);
        residuals.push(backward_error(k, m, norms, lambda, &x));
        eigenvalues.push(lambda);
        vectors.extend_from_slice(&x);
    }
    Ok(Eigenpairs {
        size: n,
        eigenvalues,
        vectors,
        residuals,
    })
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

    /// A fixed–free chain of n springs and masses with varying values: K tridiagonal, M diagonal
    /// plus a small consistent-like coupling, so that M is not diagonal.
    fn chain(n: usize) -> (SparseMatrix, SparseMatrix) {
        let mut kt = Vec::new();
        let mut mt = Vec::new();
        for i in 0..n {
            let k = 1000.0 * (1.0 + 0.3 * (i as f64 * 0.7).sin());
            let mass = 2.0 + (i as f64 * 1.3).cos();
            kt.push((i, i, k));
            mt.push((i, i, mass));
            if i + 1 < n {
                let k_next = 1000.0 * (1.0 + 0.3 * ((i + 1) as f64 * 0.7).sin());
                kt.push((i, i, k_next));
                kt.push((i, i + 1, -k_next));
                kt.push((i + 1, i, -k_next));
                mt.push((i, i + 1, 0.1));
                mt.push((i + 1, i, 0.1));
            }
        }
        (
            SparseMatrix::from_triplets(n, &kt),
            SparseMatrix::from_triplets(n, &mt),
        )
    }

    #[test]
    fn cholesky_solves_many_right_hand_sides_and_refactorises_on_the_same_pattern() {
        let (k, m) = chain(50);
        let factor = CholeskyFactor::new(&k).unwrap();
        let n = k.size;
        let x_true: Vec<f64> = (0..2 * n).map(|i| (i as f64 * 0.37).sin()).collect();
        let mut rhs = vec![0.0; 2 * n];
        for j in 0..2 {
            k.multiply(&x_true[j * n..(j + 1) * n], &mut rhs[j * n..(j + 1) * n]);
        }
        factor.solve_many_in_place(&mut rhs, 2).unwrap();
        // Tolerance: K has condition number ~1e4 here, so 1e-10 is round-off with margin.
        for i in 0..2 * n {
            assert!((rhs[i] - x_true[i]).abs() < 1e-10, "entry {i}");
        }
        // Same pattern, new values: K + 2M on the union pattern, factorised with K's analysis.
        let union = SparseMatrix::linear_combination(1.0, &k, 0.0, &m);
        let pattern = CholeskyPattern::analyse(&union).unwrap();
        let shifted = SparseMatrix::linear_combination(1.0, &k, 2.0, &m);
        let factor = pattern.factorise(&shifted).unwrap();
        let mut b = vec![0.0; n];
        shifted.multiply(&x_true[..n], &mut b);
        factor.solve_in_place(&mut b).unwrap();
        for i in 0..n {
            assert!((b[i] - x_true[i]).abs() < 1e-10);
        }
        let diagonal =
            SparseMatrix::from_triplets(n, &(0..n).map(|i| (i, i, 1.0)).collect::<Vec<_>>());
        assert!(matches!(
            pattern.factorise(&diagonal),
            Err(LinalgError::PatternMismatch { .. })
        ));
    }

    #[test]
    fn cholesky_of_an_indefinite_matrix_is_a_clear_error() {
        let a = SparseMatrix::from_triplets(3, &[(0, 0, 1.0), (1, 1, -2.0), (2, 2, 1.0)]);
        let error = CholeskyFactor::new(&a).unwrap_err();
        assert_eq!(error, LinalgError::NotPositiveDefinite { dof: 1, size: 3 });
    }

    fn check_against_dense(n: usize, count: usize, options: &LanczosOptions) {
        let (k, m) = chain(n);
        let dense = dense_lowest_eigenpairs(&k, &m, count).unwrap();
        let lanczos = lowest_eigenpairs(&k, &m, count, options).unwrap();
        for i in 0..count {
            // Tolerance: both are converged to ~1e-12 relative; eigenvalues agree to round-off
            // times the condition of the chain (~1e4).
            let rel = (lanczos.eigenvalues[i] - dense.eigenvalues[i]).abs() / dense.eigenvalues[i];
            assert!(rel < 1e-9, "eigenvalue {i}: {rel:e}");
            // Same sign convention, so the vectors themselves agree (eigenvalues are simple).
            let diff: f64 = lanczos
                .vector(i)
                .iter()
                .zip(dense.vector(i))
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            let norm: f64 = dense.vector(i).iter().map(|a| a * a).sum::<f64>().sqrt();
            assert!(diff < 1e-6 * norm, "vector {i}: {:e}", diff / norm);
            assert!(lanczos.residuals[i] < 1e-9, "residual {i}");
        }
    }

    #[test]
    fn lanczos_matches_the_dense_solver_on_a_spring_mass_chain() {
        check_against_dense(120, 12, &LanczosOptions::default());
    }

    #[test]
    fn lanczos_with_thick_restarts_matches_the_dense_solver() {
        // A Krylov space barely larger than the count forces many restarts.
        let options = LanczosOptions {
            krylov_dimension: Some(14),
            ..Default::default()
        };
        check_against_dense(150, 8, &options);
    }

    #[test]
    fn lanczos_on_a_problem_smaller_than_the_krylov_space_returns_every_pair() {
        check_against_dense(9, 9, &LanczosOptions::default());
    }

    #[test]
    fn a_lanczos_run_that_cannot_converge_is_an_error_carrying_the_numbers() {
        let (k, m) = chain(200);
        let options = LanczosOptions {
            krylov_dimension: Some(12),
            max_restarts: 0,
            ..Default::default()
        };
        match lowest_eigenpairs(&k, &m, 10, &options) {
            Err(EigenError::NotConverged {
                requested,
                converged,
                restarts,
                krylov_dimension,
                worst_estimate,
                ..
            }) => {
                assert_eq!((requested, restarts, krylov_dimension), (10, 0, 12));
                assert!(converged < 10 && worst_estimate > 1e-10);
            }
            other => panic!("expected NotConverged, got {other:?}"),
        }
    }
}
