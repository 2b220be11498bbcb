//! Symmetric sparse matrices (faer CSC, both triangles stored) and a sparse Cholesky solver
//! that is factorised once and then solves in place with a preallocated workspace.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, MatMut, Par, Side};

use crate::SimError;

/// Accumulates entries (i, j, v) of a symmetric matrix; duplicates are summed.
#[derive(Debug, Clone, Default)]
pub struct SymBuilder {
    n: usize,
    entries: std::collections::BTreeMap<(usize, usize), f64>,
}

impl SymBuilder {
    /// An empty n×n symmetric matrix.
    pub fn new(n: usize) -> Self {
        SymBuilder { n, entries: Default::default() }
    }

    /// Add v at (i, j) and, if i ≠ j, at (j, i).
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        *self.entries.entry((i, j)).or_insert(0.0) += v;
        if i != j {
            *self.entries.entry((j, i)).or_insert(0.0) += v;
        }
    }

    /// Add a dense element block `local` (row-major, k×k) at global indices `dofs`
    /// (`None` = constrained degree of freedom, dropped).
    pub fn add_block(&mut self, dofs: &[Option<usize>], local: &[f64]) {
        let k = dofs.len();
        for (a, ia) in dofs.iter().enumerate() {
            for (b, ib) in dofs.iter().enumerate() {
                if let (Some(i), Some(j)) = (ia, ib) {
                    *self.entries.entry((*i, *j)).or_insert(0.0) += local[a * k + b];
                }
            }
        }
    }

    /// Build the CSC matrix.
    pub fn build(&self) -> SymMatrix {
        let triplets: Vec<Triplet<usize, usize, f64>> =
            self.entries.iter().map(|(&(i, j), &v)| Triplet::new(i, j, v)).collect();
        let mat = SparseColMat::try_new_from_triplets(self.n, self.n, &triplets).expect("valid triplets");
        SymMatrix { mat }
    }
}

/// A symmetric sparse matrix with both triangles stored.
#[derive(Debug, Clone)]
pub struct SymMatrix {
    mat: SparseColMat<usize, f64>,
}

impl SymMatrix {
    /// Dimension.
    pub fn dim(&self) -> usize {
        self.mat.nrows()
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.mat.val().len()
    }

    /// y = A x (overwrites y).
    pub fn mul_into(&self, x: &[f64], y: &mut [f64]) {
        let m = self.mat.as_ref();
        let cp = m.symbolic().col_ptr();
        let ri = m.symbolic().row_idx();
        let val = m.val();
        y.iter_mut().for_each(|v| *v = 0.0);
        // A is symmetric: column j of A is row j, so y_j = Σ_i A_ij x_i reads column j contiguously.
        for j in 0..self.dim() {
            let mut acc = 0.0;
            for p in cp[j]..cp[j + 1] {
                acc += val[p] * x[ri[p]];
            }
            y[j] = acc;
        }
    }

    /// xᵀ A y.
    pub fn form(&self, x: &[f64], y: &[f64]) -> f64 {
        let m = self.mat.as_ref();
        let cp = m.symbolic().col_ptr();
        let ri = m.symbolic().row_idx();
        let val = m.val();
        let mut total = 0.0;
        for j in 0..self.dim() {
            let mut acc = 0.0;
            for p in cp[j]..cp[j + 1] {
                acc += val[p] * x[ri[p]];
            }
            total += acc * y[j];
        }
        total
    }

    /// Σ_j |A_ij| of row i.
    pub fn row_abs_sum(&self, i: usize) -> f64 {
        let m = self.mat.as_ref();
        let cp = m.symbolic().col_ptr();
        // symmetric: row i is column i
        m.val()[cp[i]..cp[i + 1]].iter().map(|v| v.abs()).sum()
    }

    /// Entry (i, j) (zero if not stored).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let m = self.mat.as_ref();
        let cp = m.symbolic().col_ptr();
        let ri = m.symbolic().row_idx();
        (cp[j]..cp[j + 1]).find(|&p| ri[p] == i).map(|p| m.val()[p]).unwrap_or(0.0)
    }

    /// Stored entries (i, j, A_ij), both triangles.
    pub fn to_sparse_entries(&self) -> Vec<(usize, usize, f64)> {
        let m = self.mat.as_ref();
        let cp = m.symbolic().col_ptr();
        let ri = m.symbolic().row_idx();
        (0..self.dim()).flat_map(|j| (cp[j]..cp[j + 1]).map(move |p| (ri[p], j, m.val()[p]))).collect()
    }

    /// Dense copy, row-major n×n.
    pub fn to_dense(&self) -> Vec<f64> {
        let n = self.dim();
        let m = self.mat.as_ref();
        let cp = m.symbolic().col_ptr();
        let ri = m.symbolic().row_idx();
        let mut d = vec![0.0; n * n];
        for j in 0..n {
            for p in cp[j]..cp[j + 1] {
                d[ri[p] * n + j] = m.val()[p];
            }
        }
        d
    }

    /// α A + β B + γ C on the union pattern (all three must have the same dimension).
    pub fn combine(terms: &[(f64, &SymMatrix)]) -> SymMatrix {
        let n = terms[0].1.dim();
        let mut b = SymBuilder::new(n);
        for (coef, m) in terms {
            let r = m.mat.as_ref();
            let cp = r.symbolic().col_ptr();
            let ri = r.symbolic().row_idx();
            for j in 0..n {
                for p in cp[j]..cp[j + 1] {
                    *b.entries.entry((ri[p], j)).or_insert(0.0) += coef * r.val()[p];
                }
            }
        }
        b.build()
    }

    pub(crate) fn faer(&self) -> &SparseColMat<usize, f64> {
        &self.mat
    }
}

/// Two symmetric matrices A, B on their union pattern, for the fused product A u − B w
/// (one pass over the pattern instead of two; the right-hand side of every time step).
#[derive(Debug, Clone)]
pub struct SymPair {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    a: Vec<f64>,
    b: Vec<f64>,
}

impl SymPair {
    /// Pair `a` and `b` (same dimension).
    pub fn new(a: &SymMatrix, b: &SymMatrix) -> SymPair {
        let n = a.dim();
        let mut map: std::collections::BTreeMap<(usize, usize), (f64, f64)> = Default::default();
        for (which, m) in [(0, a), (1, b)] {
            let r = m.mat.as_ref();
            let cp = r.symbolic().col_ptr();
            let ri = r.symbolic().row_idx();
            for j in 0..n {
                for p in cp[j]..cp[j + 1] {
                    let e = map.entry((j, ri[p])).or_insert((0.0, 0.0));
                    if which == 0 {
                        e.0 += r.val()[p];
                    } else {
                        e.1 += r.val()[p];
                    }
                }
            }
        }
        let mut col_ptr = vec![0usize; n + 1];
        let mut row_idx = Vec::with_capacity(map.len());
        let (mut av, mut bv) = (Vec::with_capacity(map.len()), Vec::with_capacity(map.len()));
        for (&(j, i), &(x, y)) in &map {
            col_ptr[j + 1] += 1;
            row_idx.push(i);
            av.push(x);
            bv.push(y);
        }
        for j in 0..n {
            col_ptr[j + 1] += col_ptr[j];
        }
        SymPair { col_ptr, row_idx, a: av, b: bv }
    }

    /// out = A u − B w.
    pub fn mul_diff_into(&self, u: &[f64], w: &[f64], out: &mut [f64]) {
        for (j, o) in out.iter_mut().enumerate() {
            let mut acc = 0.0;
            for p in self.col_ptr[j]..self.col_ptr[j + 1] {
                let i = self.row_idx[p];
                acc += self.a[p] * u[i] - self.b[p] * w[i];
            }
            *o = acc;
        }
    }
}

/// Sparse Cholesky A = LLᵀ (AMD ordering, faer), factorised once; [`SpdSolver::solve_in_place`]
/// allocates nothing.
pub struct SpdSolver {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    buffer: MemBuffer,
    n: usize,
}

impl std::fmt::Debug for SpdSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SpdSolver").field("n", &self.n).field("factor_nnz", &self.values.len()).finish()
    }
}

impl SpdSolver {
    /// Factorise a symmetric positive definite matrix.
    pub fn new(a: &SymMatrix) -> Result<SpdSolver, SimError> {
        let m = a.faer().as_ref();
        let symbolic = factorize_symbolic_cholesky(
            m.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        )
        .map_err(|e| SimError::Numerical(format!("symbolic Cholesky failed: {e:?}")))?;
        let mut values = vec![0.0; symbolic.len_val()];
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        let mut buffer = MemBuffer::new(req);
        symbolic
            .factorize_numeric_llt::<f64>(
                &mut values,
                m,
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut buffer),
                Default::default(),
            )
            .map_err(|e| SimError::Numerical(format!("step matrix is not positive definite: {e:?}")))?;
        Ok(SpdSolver { symbolic, values, buffer, n: a.dim() })
    }

    /// Number of stored entries of the factor L.
    pub fn factor_nnz(&self) -> usize {
        self.values.len()
    }

    /// Overwrite `rhs` with A⁻¹ rhs.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        let llt = faer::sparse::linalg::cholesky::LltRef::new(&self.symbolic, &self.values);
        let mat = MatMut::from_column_major_slice_mut(rhs, self.n, 1);
        llt.solve_in_place_with_conj(Conj::No, mat, Par::Seq, MemStack::new(&mut self.buffer));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve_satisfies_the_defining_residual() {
        // A banded SPD matrix (shifted 1-D Laplacian plus a long-range coupling so AMD permutes).
        let n = 40;
        let mut b = SymBuilder::new(n);
        for i in 0..n {
            b.add(i, i, 3.0 + i as f64 * 0.01);
            if i + 1 < n {
                b.add(i, i + 1, -1.0);
            }
        }
        b.add(0, n - 1, 0.3);
        let a = b.build();
        let mut solver = SpdSolver::new(&a).unwrap();
        let rhs: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut x = rhs.clone();
        solver.solve_in_place(&mut x);
        let mut ax = vec![0.0; n];
        a.mul_into(&x, &mut ax);
        // Reference: A x = b by definition.
        for i in 0..n {
            assert!((ax[i] - rhs[i]).abs() < 1e-13);
        }
        // The fused product (2A)x − A x equals A x.
        let pair = SymPair::new(&SymMatrix::combine(&[(2.0, &a)]), &a);
        let mut fused = vec![0.0; n];
        pair.mul_diff_into(&x, &x, &mut fused);
        for i in 0..n {
            assert!((fused[i] - ax[i]).abs() < 1e-13);
        }
    }

    #[test]
    fn indefinite_step_matrix_is_an_error_not_a_panic() {
        let mut b = SymBuilder::new(2);
        b.add(0, 0, 1.0);
        b.add(1, 1, -1.0);
        assert!(matches!(SpdSolver::new(&b.build()), Err(SimError::Numerical(_))));
    }
}
