//! Symmetric sparse matrices (faer CSC, both triangles stored), assembled by [`SymBuilder`].

use faer::sparse::{SparseColMat, Triplet};

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
}
