//! The stiffness in factored (strain) form K = Gᵀ D G: G maps the unknowns to as many strain
//! values (curvatures, twist rates) as there are unknowns, D is diagonal and positive
//! (EI or GJ times the quadrature weight). G is triangular in a known order (each strain row
//! has a pivot unknown; its other unknowns are pivots of earlier rows: the clamp fixes node 0,
//! element e's strains determine node e+1 given node e). So K⁻¹ b = G⁻¹ D⁻¹ G⁻ᵀ b is two
//! substitutions — accumulating loads from the tip, integrating strains from the root — whose
//! round-off is relative to the result, not ε·κ(K) as for a Cholesky factor of the assembled K
//! (κ(K) ~ h⁻⁴ for the bending part). This is what keeps the lowest frequencies accurate under
//! refinement.

/// One strain row g·x with its weight: energy contribution ½·weight·(g·x)².
#[derive(Debug, Clone, PartialEq)]
pub struct StrainRow {
    /// The unknown this row determines in forward substitution.
    pub pivot: usize,
    /// Coefficients (unknown, g), the pivot included.
    pub entries: Vec<(usize, f64)>,
    /// Weight (EI or GJ times quadrature weight), > 0.
    pub weight: f64,
}

impl StrainRow {
    fn pivot_coef(&self) -> f64 {
        self.entries.iter().find(|e| e.0 == self.pivot).map(|e| e.1).unwrap_or(0.0)
    }
}

/// K = Gᵀ D G with the rows in substitution order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StrainForm {
    /// Rows in forward-substitution order.
    pub rows: Vec<StrainRow>,
}

impl StrainForm {
    /// The rows with their weights multiplied by `scale` (EI or GJ on unit rows).
    pub fn scaled(rows: Vec<StrainRow>, scale: f64) -> Vec<StrainRow> {
        rows.into_iter().map(|r| StrainRow { weight: r.weight * scale, ..r }).collect()
    }

    /// xᵀ K x = Σ weight·(g·x)² (twice the elastic energy, J).
    pub fn energy_form(&self, x: &[f64]) -> f64 {
        self.rows.iter().map(|r| r.weight * r.entries.iter().map(|&(j, g)| g * x[j]).sum::<f64>().powi(2)).sum()
    }

    /// x = G⁻¹ z: the unknowns whose strains (g·x per row, in row order) are `z`; one
    /// forward substitution, round-off relative to the result.
    pub fn integrate(&self, z: &[f64], x: &mut [f64]) {
        for (r, row) in self.rows.iter().enumerate() {
            let mut acc = z[r];
            for &(j, g) in &row.entries {
                if j != row.pivot {
                    acc -= g * x[j];
                }
            }
            x[row.pivot] = acc / row.pivot_coef();
        }
    }

    /// Overwrite `b` with K⁻¹ b; `work` is resized to the number of rows.
    pub fn solve_in_place(&self, b: &mut [f64], work: &mut Vec<f64>) {
        let nr = self.rows.len();
        work.resize(nr, 0.0);
        // y = G⁻ᵀ b: rows in reverse; b_j for a pivot j has received every later row's share.
        for (r, row) in self.rows.iter().enumerate().rev() {
            let y = b[row.pivot] / row.pivot_coef();
            for &(j, g) in &row.entries {
                if j != row.pivot {
                    b[j] -= g * y;
                }
            }
            work[r] = y / row.weight;
        }
        // x = G⁻¹ z, z = D⁻¹ y.
        self.integrate(work, b);
    }
}
