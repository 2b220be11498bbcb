//! The Woodbury step solve of the implicit schemes in the modal basis (the trapezoidal rule's
//! steps, and the factors of TR-BDF2's one-pass step, `super::trbdf2_pass`), laid out for vector
//! instructions: the coefficients of every mode in one interleaved array of [`Pack`]s of
//! [`LANES`] modes, the state padded with zero modes to a multiple of [`LANES`], and each sum
//! over the modes accumulated in [`LANES`] partial sums combined in one fixed order.
//!
//! Why by hand: a sum written as one running total is a chain of dependent additions (each
//! waits for the previous one, ≈ 4 cycles), which the compiler may not reorder; two of them per
//! stage made the modal TR-BDF2 step latency-bound (0.44 µs for 72 modes). With [`LANES`]
//! independent partial sums the loops vectorise. The operations and their order are fixed by
//! the source, not by the instructions that carry them: SSE2 or AVX ([`ModalLoop`] picks AVX at
//! run time where the CPU has it; no fused multiply-add, which would round differently), so
//! the results are bit-identical on every x86-64 machine (test in `scheme.rs`).
//!
//! [`ModalLoop`]: super::ModalLoop

use super::ModalBasis;
use crate::{NumericalError, SimError};

/// Modes per pack: the width of the partial sums.
pub(crate) const LANES: usize = 8;

/// `n` rounded up to a multiple of [`LANES`]: the length of the state vectors.
pub(crate) fn padded_len(n: usize) -> usize {
    n.div_ceil(LANES) * LANES
}

/// The step matrix S = M/α + C + αK_c of the scheme in the modal basis: D + β U T Uᵀ with
/// D = diag(1/α + (ξ + α)ω_i²) (1/s), β = b + αa, T = diag(k1, k2) and U the tip rows of Φ;
/// solved by the Woodbury identity with a 2×2 capacitance matrix, O(n) per solve. Every
/// vector has the padded length ([`padded_len`]), zero beyond the modes.
#[derive(Debug)]
pub(crate) struct StepSolve {
    /// D⁻¹/α: the factor of ζ in D⁻¹ r.
    pub(crate) cz: Vec<f64>,
    /// D⁻¹Ω²: the factor of η in D⁻¹ r.
    pub(crate) ce: Vec<f64>,
    /// D⁻¹Φᵀf_h: the distributed load's shape.
    pub(crate) ld: Vec<f64>,
    /// D⁻¹U, bending column.
    pub(crate) z0: Vec<f64>,
    /// D⁻¹U, torsion column.
    pub(crate) z1: Vec<f64>,
    /// U (tip rows of Φ), bending.
    pub(crate) u0: Vec<f64>,
    /// U, torsion.
    pub(crate) u1: Vec<f64>,
    /// Q = Uᵀ D⁻¹ U.
    pub(crate) q: [[f64; 2]; 2],
    /// H = (I + βT Q)⁻¹ βT.
    hm: [[f64; 2]; 2],
    /// Run the loops with AVX instructions ([`avx`]; the CPU has them).
    pub(crate) avx: bool,
}

/// Σ of the partial sums, in one fixed order.
#[inline(always)]
pub(crate) fn total(a: &[f64; LANES]) -> f64 {
    ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7]))
}

/// Σ x_i y_i over the common length, in [`LANES`] partial sums combined in one fixed order
/// (independent additions, so the sum vectorises; the same bits on every machine).
pub fn dot(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len().min(y.len());
    let (x, y) = (&x[..n], &y[..n]);
    let mut s = [0.0; LANES];
    for (a, b) in x.chunks_exact(LANES).zip(y.chunks_exact(LANES)) {
        for l in 0..LANES {
            s[l] += a[l] * b[l];
        }
    }
    let tail = n - n % LANES;
    x[tail..].iter().zip(&y[tail..]).fold(total(&s), |acc, (a, b)| acc + a * b)
}

/// (Σ_i a_i y_i, Σ_i b_i y_i) over slices of the padded length, each in [`LANES`] partial sums.
#[inline(always)]
fn dots(a: &[f64], b: &[f64], y: &[f64]) -> [f64; 2] {
    let (mut s0, mut s1) = ([0.0; LANES], [0.0; LANES]);
    for ((a, b), y) in a.chunks_exact(LANES).zip(b.chunks_exact(LANES)).zip(y.chunks_exact(LANES)) {
        for l in 0..LANES {
            s0[l] += a[l] * y[l];
            s1[l] += b[l] * y[l];
        }
    }
    [total(&s0), total(&s1)]
}

impl StepSolve {
    pub(crate) fn new(
        basis: &ModalBasis,
        alpha: f64,
        xi: f64,
        beta: f64,
        gain: [f64; 2],
    ) -> Result<StepSolve, SimError> {
        let (om, u) = (&basis.omega2, &basis.tip);
        let n = om.len();
        let d_inv: Vec<f64> = om.iter().map(|w| 1.0 / (1.0 / alpha + (xi + alpha) * w)).collect();
        let pad = |v: Vec<f64>| {
            let mut v = v;
            v.resize(padded_len(n), 0.0);
            v
        };
        let scaled = |f: &dyn Fn(usize) -> f64| pad((0..n).map(|i| d_inv[i] * f(i)).collect());
        let (cz, ce, ld) = (scaled(&|_| 1.0 / alpha), scaled(&|i| om[i]), scaled(&|i| basis.load[i]));
        let (z0, z1) = (scaled(&|i| u[0][i]), scaled(&|i| u[1][i]));
        let (u0, u1) = (pad(u[0].clone()), pad(u[1].clone()));
        let z: [Vec<f64>; 2] = [0, 1].map(|c| (0..n).map(|i| d_inv[i] * u[c][i]).collect());
        let q = [[dot(&u[0], &z[0]), dot(&u[0], &z[1])], [dot(&u[1], &z[0]), dot(&u[1], &z[1])]];
        let wk = [beta * gain[0], beta * gain[1]];
        let g = [[1.0 + wk[0] * q[0][0], wk[0] * q[0][1]], [wk[1] * q[1][0], 1.0 + wk[1] * q[1][1]]];
        let det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
        if !(det.is_finite() && det > 0.0) {
            return Err(NumericalError::Singular { what: "step matrix capacitance", det }.into());
        }
        let gi = [[g[1][1] / det, -g[0][1] / det], [-g[1][0] / det, g[0][0] / det]];
        let hm = [[gi[0][0] * wk[0], gi[0][1] * wk[1]], [gi[1][0] * wk[0], gi[1][1] * wk[1]]];
        #[cfg(target_arch = "x86_64")]
        let avx = std::arch::is_x86_feature_detected!("avx");
        #[cfg(not(target_arch = "x86_64"))]
        let avx = false;
        Ok(StepSolve { cz, ce, ld, z0, z1, u0, u1, q, hm, avx })
    }

    /// y = D⁻¹ r for r = ζ/α − Ω²η + φ̄ Φᵀf_h + U f (f: tip forces, N and N m); returns Uᵀy.
    pub(crate) fn rhs(&self, zeta: &[f64], eta: &[f64], phi: f64, f: [f64; 2], y: &mut [f64]) -> [f64; 2] {
        self.check(&[zeta, eta, y]);
        #[cfg(target_arch = "x86_64")]
        if self.avx {
            // SAFETY: the CPU has AVX (`avx`), and every slice has the padded length (checked).
            return unsafe { avx::rhs(self, zeta, eta, phi, f, y) };
        }
        for (((y, (zt, et)), (cz, ce)), (ld, (z0, z1))) in y
            .iter_mut()
            .zip(zeta.iter().zip(eta))
            .zip(self.cz.iter().zip(&self.ce))
            .zip(self.ld.iter().zip(self.z0.iter().zip(&self.z1)))
        {
            *y = cz * zt - ce * et + phi * ld + z0 * f[0] + z1 * f[1];
        }
        dots(&self.u0, &self.u1, y)
    }

    /// Panics unless every state vector has the coefficients' (padded) length: the AVX loops
    /// index by it.
    #[inline(always)]
    fn check(&self, v: &[&[f64]]) {
        let n = self.cz.len();
        assert!(n % LANES == 0 && v.iter().all(|x| x.len() == n), "modal state of the wrong length");
    }

    /// The Woodbury correction c = H t of y (the solution is y − D⁻¹U c) and the solution's
    /// tip values Uᵀ(y − D⁻¹U c) = t − Q c, for t = Uᵀy.
    #[inline(always)]
    pub(crate) fn correct(&self, t: [f64; 2]) -> ([f64; 2], [f64; 2]) {
        let (hm, q) = (&self.hm, &self.q);
        let c = [hm[0][0] * t[0] + hm[0][1] * t[1], hm[1][0] * t[0] + hm[1][1] * t[1]];
        (c, [t[0] - q[0][0] * c[0] - q[0][1] * c[1], t[1] - q[1][0] * c[0] - q[1][1] * c[1]])
    }

    /// The trapezoidal step's update from v̄ = y − D⁻¹U c: η += h v̄, ζ = 2v̄ − ζ.
    pub(crate) fn trapezoid_update(&self, y: &[f64], c: [f64; 2], h: f64, zeta: &mut [f64], eta: &mut [f64]) {
        self.check(&[y, zeta, eta]);
        #[cfg(target_arch = "x86_64")]
        if self.avx {
            // SAFETY: as in `rhs`.
            return unsafe { avx::trapezoid_update(self, y, c, h, zeta, eta) };
        }
        for ((y, (zt, et)), (z0, z1)) in
            y.iter().zip(zeta.iter_mut().zip(eta.iter_mut())).zip(self.z0.iter().zip(&self.z1))
        {
            let zbar = y - z0 * c[0] - z1 * c[1];
            *et += h * zbar;
            *zt = 2.0 * zbar - *zt;
        }
    }

    /// TR-BDF2 between its stages: stage 1's solution u = y − D⁻¹U c gives (η, ζ) ←
    /// (η̂, ζ̂) = (η + 2αA u, 2A u − (A + B)ζ), and stage 2's D⁻¹ r into y; returns Uᵀy.
    /// `k` = (2αA, 2A, A + B). The two-pass form of TR-BDF2 (with [`StepSolve::rhs`] and
    /// [`StepSolve::trbdf2_finish`]), kept as the reference the one-pass form
    /// ([`super::trbdf2_pass`]) is tested against.
    #[cfg(test)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn trbdf2_middle(
        &self,
        c: [f64; 2],
        k: [f64; 3],
        phi: f64,
        f2: [f64; 2],
        y: &mut [f64],
        zeta: &mut [f64],
        eta: &mut [f64],
    ) -> [f64; 2] {
        self.check(&[y, zeta, eta]);
        let (eta_u, zeta_u, zeta_z) = (k[0], k[1], k[2]);
        for (((y, (zt, et)), (cz, ce)), (ld, (z0, z1))) in y
            .iter_mut()
            .zip(zeta.iter_mut().zip(eta.iter_mut()))
            .zip(self.cz.iter().zip(&self.ce))
            .zip(self.ld.iter().zip(self.z0.iter().zip(&self.z1)))
        {
            let us = *y - z0 * c[0] - z1 * c[1];
            let (eh, zh) = (*et + eta_u * us, zeta_u * us - zeta_z * *zt);
            *et = eh;
            *zt = zh;
            *y = cz * zh - ce * eh + phi * ld + z0 * f2[0] + z1 * f2[1];
        }
        dots(&self.u0, &self.u1, y)
    }

    /// TR-BDF2's end: ζ₁ = y − D⁻¹U c, η₁ = η̂ + αζ₁ (the two-pass reference, as
    /// [`StepSolve::trbdf2_middle`]).
    #[cfg(test)]
    pub(crate) fn trbdf2_finish(&self, y: &[f64], c: [f64; 2], alpha: f64, zeta: &mut [f64], eta: &mut [f64]) {
        self.check(&[y, zeta, eta]);
        for ((y, (zt, et)), (z0, z1)) in
            y.iter().zip(zeta.iter_mut().zip(eta.iter_mut())).zip(self.z0.iter().zip(&self.z1))
        {
            *zt = y - z0 * c[0] - z1 * c[1];
            *et += alpha * *zt;
        }
    }
}

/// The loops above with AVX instructions, 4 modes per instruction: the same operations in the
/// same order (each lane of a partial sum is one of the [`LANES`] sums), no fused
/// multiply-add, so the same bits as the portable loops. Its element helpers (`get`, `put`,
/// `mul`, `add`, `sub`) serve the one-pass TR-BDF2 loop too.
#[cfg(target_arch = "x86_64")]
pub(super) mod avx {
    use std::arch::x86_64::{
        __m256d, _mm256_add_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_setzero_pd, _mm256_storeu_pd,
        _mm256_sub_pd,
    };

    use super::{total, StepSolve, LANES};

    /// 4 values from index i (i + 4 ≤ len: every caller iterates below the checked length).
    #[inline(always)]
    pub(in crate::modal) unsafe fn get(v: &[f64], i: usize) -> __m256d {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe { _mm256_loadu_pd(v.as_ptr().add(i)) }
    }

    /// Store 4 values at index i (i + 4 ≤ len, as for [`get`]).
    #[inline(always)]
    pub(in crate::modal) unsafe fn put(v: &mut [f64], i: usize, x: __m256d) {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe { _mm256_storeu_pd(v.as_mut_ptr().add(i), x) }
    }

    #[inline(always)]
    pub(in crate::modal) unsafe fn mul(a: __m256d, b: __m256d) -> __m256d {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe { _mm256_mul_pd(a, b) }
    }

    #[inline(always)]
    pub(in crate::modal) unsafe fn add(a: __m256d, b: __m256d) -> __m256d {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe { _mm256_add_pd(a, b) }
    }

    #[inline(always)]
    pub(in crate::modal) unsafe fn sub(a: __m256d, b: __m256d) -> __m256d {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe { _mm256_sub_pd(a, b) }
    }

    /// The two partial-sum vectors of lanes 0–3 and 4–7, in the portable loops' order.
    #[inline(always)]
    unsafe fn sum(lo: __m256d, hi: __m256d) -> f64 {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe {
            let mut a = [0.0; LANES];
            _mm256_storeu_pd(a.as_mut_ptr(), lo);
            _mm256_storeu_pd(a.as_mut_ptr().add(4), hi);
            total(&a)
        }
    }

    /// The [`LANES`] partial sums of (Σ u0 y, Σ u1 y) as four named registers (lanes 0–3 and
    /// 4–7 of each), so that they stay in registers: an array indexed by the pack's half
    /// was kept on the stack, and every addition then waited for the previous one's store.
    struct Dots {
        u0_lo: __m256d,
        u0_hi: __m256d,
        u1_lo: __m256d,
        u1_hi: __m256d,
    }

    impl Dots {
        #[inline(always)]
        unsafe fn new() -> Dots {
            // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
            unsafe {
                let z = _mm256_setzero_pd();
                Dots { u0_lo: z, u0_hi: z, u1_lo: z, u1_hi: z }
            }
        }

        /// Add u·v for the modes i + half .. i + half + 4 of the pack at i (half 0 or 4).
        #[inline(always)]
        unsafe fn accumulate(&mut self, s: &StepSolve, i: usize, half: usize, v: __m256d) {
            // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
            unsafe {
                let j = i + half;
                let (a0, a1) =
                    if half == 0 { (&mut self.u0_lo, &mut self.u1_lo) } else { (&mut self.u0_hi, &mut self.u1_hi) };
                *a0 = add(*a0, mul(get(&s.u0, j), v));
                *a1 = add(*a1, mul(get(&s.u1, j), v));
            }
        }

        #[inline(always)]
        unsafe fn totals(&self) -> [f64; 2] {
            // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
            unsafe { [sum(self.u0_lo, self.u0_hi), sum(self.u1_lo, self.u1_hi)] }
        }
    }

    /// cz ζ − ce η + φ ld + z0 f0 + z1 f1 at i, in the portable loops' order.
    #[inline(always)]
    unsafe fn rhs_at(s: &StepSolve, i: usize, zt: __m256d, et: __m256d, phi: __m256d, f: [__m256d; 2]) -> __m256d {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe {
            let v = sub(mul(get(&s.cz, i), zt), mul(get(&s.ce, i), et));
            add(add(add(v, mul(phi, get(&s.ld, i))), mul(get(&s.z0, i), f[0])), mul(get(&s.z1, i), f[1]))
        }
    }

    /// y − z0 c0 − z1 c1 at i.
    #[inline(always)]
    unsafe fn corrected(s: &StepSolve, i: usize, y: __m256d, c: [__m256d; 2]) -> __m256d {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe { sub(sub(y, mul(get(&s.z0, i), c[0])), mul(get(&s.z1, i), c[1])) }
    }

    #[target_feature(enable = "avx")]
    pub(super) unsafe fn rhs(
        s: &StepSolve,
        zeta: &[f64],
        eta: &[f64],
        phi: f64,
        f: [f64; 2],
        y: &mut [f64],
    ) -> [f64; 2] {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe {
            let (phi, f) = (_mm256_set1_pd(phi), [_mm256_set1_pd(f[0]), _mm256_set1_pd(f[1])]);
            let mut acc = Dots::new();
            // one pack of LANES modes per pass: lanes 0–3 and 4–7 in two registers each
            for i in (0..y.len()).step_by(LANES) {
                for half in [0, 4] {
                    let v = rhs_at(s, i + half, get(zeta, i + half), get(eta, i + half), phi, f);
                    put(y, i + half, v);
                    acc.accumulate(s, i, half, v);
                }
            }
            acc.totals()
        }
    }

    #[target_feature(enable = "avx")]
    pub(super) unsafe fn trapezoid_update(
        s: &StepSolve,
        y: &[f64],
        c: [f64; 2],
        h: f64,
        zeta: &mut [f64],
        eta: &mut [f64],
    ) {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe {
            let (c, h, two) = ([_mm256_set1_pd(c[0]), _mm256_set1_pd(c[1])], _mm256_set1_pd(h), _mm256_set1_pd(2.0));
            for i in (0..y.len()).step_by(4) {
                let zbar = corrected(s, i, get(y, i), c);
                put(eta, i, add(get(eta, i), mul(h, zbar)));
                put(zeta, i, sub(mul(two, zbar), get(zeta, i)));
            }
        }
    }
}
