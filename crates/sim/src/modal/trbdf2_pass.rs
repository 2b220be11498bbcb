//! TR-BDF2 in the modal basis in one pass over the modes per step.
//!
//! The step's two stages each solve with the step matrix S = D + βUTUᵀ (Woodbury, see
//! [`super::woodbury`]); what couples the modes is only the two tip values a solve needs,
//! t = Uᵀy of each stage's D⁻¹r. Both are linear in the step's starting state and in a few
//! scalars, so their state parts are summed in the pass that forms that state (the previous
//! step's) and each step is one pass: with e = f − c and e₂ = f₂ − c₂ (the stages' tip forces
//! less their Woodbury corrections, known before the pass from the carried sums),
//!
//! ```text
//! u   = cz ζ − ce η + φ ld + z·e                     stage 1's solution (D⁻¹ r − D⁻¹U c)
//! ζ₁  = k1 u − k2 ζ − ce η + φ ld + z·e₂             stage 2's solution, k1 = 2A(cz − α ce), k2 = (A + B) cz
//! η₁  = η + 2αA u + α ζ₁
//! t'  = Σ U (cz ζ₁ − ce η₁)                + φ' Uᵀld + Q f'
//! t₂' = Σ U (k1 v' − k2 ζ₁ − ce η₁)        + φ' Σ U (k1 + 1) ld + (Σ U k1 zᵀ) e' + Q f₂'
//! ```
//!
//! (v' = cz ζ₁ − ce η₁; primes: the next step). These are TR-BDF2's stages as
//! [`crate::Stepper`] and the two-pass Woodbury form compute them (η̂ = η + 2αA u,
//! ζ̂ = 2A u − (A + B)ζ, S ζ₁ = ζ̂/α − Ω²η̂ + f̄₂, η₁ = η̂ + αζ₁), the same discrete equations
//! summed in another order, so the states agree to round-off (test below, and
//! `tests/basis.rs` against the nodal stepper). The two-pass form made three passes' worth
//! of loads and stores and waited twice a step for a sum over all modes; this one waits once.
//!
//! Like [`super::woodbury`], every sum over the modes is accumulated in [`WIDTH`] partial sums
//! combined in one fixed order, and the AVX loop does the portable loop's operations in the
//! same order (no fused multiply-add): the same bits on every x86-64 machine.

use super::woodbury::StepSolve;
use crate::trbdf2::{A, B};

/// The TR-BDF2 step of a modal loop: the Woodbury solve of its step matrix (α = γh/2) and
/// the per-mode factors of the one-pass form. Every vector has the padded length.
#[derive(Debug)]
pub(crate) struct Trbdf2Pass {
    /// The step matrix's Woodbury solve (cz, ce, ld, z0, z1, u0, u1, Q, H).
    pub(crate) solve: StepSolve,
    /// k1 = 2A(cz − α ce): the factor of u in ζ₁ (1/s).
    k1: Vec<f64>,
    /// k2 = (A + B) cz: the factor of ζ in ζ₁ (1/s).
    k2: Vec<f64>,
    /// α (s).
    alpha: f64,
    /// 2αA (s): the factor of u in η̂.
    eta_u: f64,
    /// Uᵀ ld per channel: t's part per unit φ.
    lu: [f64; 2],
    /// Σ U (k1 + 1) ld per channel: t₂'s part per unit φ.
    g_ld: [f64; 2],
    /// Σ U_c k1 z_d: t₂'s part per unit of stage 1's e.
    g_z: [[f64; 2]; 2],
}

/// The state parts of the next step's tip sums, carried from the pass that formed the state:
/// Σ U (cz ζ − ce η) and Σ U (k1 v − k2 ζ − ce η) per channel.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct StateSums {
    pub(crate) t: [f64; 2],
    pub(crate) t2: [f64; 2],
}

impl Trbdf2Pass {
    /// The step of TR-BDF2 on the Woodbury solve `solve` of its step matrix, built with
    /// α = γh/2 (s), the same `alpha`.
    pub(crate) fn new(solve: StepSolve, alpha: f64) -> Trbdf2Pass {
        let n = solve.cz.len();
        let k1: Vec<f64> = (0..n).map(|i| 2.0 * A * (solve.cz[i] - alpha * solve.ce[i])).collect();
        let k2: Vec<f64> = (0..n).map(|i| (A + B) * solve.cz[i]).collect();
        let u = [&solve.u0, &solve.u1];
        let z = [&solve.z0, &solve.z1];
        let dot = super::dot;
        let k1_ld: Vec<f64> = (0..n).map(|i| k1[i] * solve.ld[i] + solve.ld[i]).collect();
        let k1_z: [Vec<f64>; 2] = [0, 1].map(|d| (0..n).map(|i| k1[i] * z[d][i]).collect());
        let lu = [0, 1].map(|c| dot(u[c], &solve.ld));
        let g_ld = [0, 1].map(|c| dot(u[c], &k1_ld));
        let g_z = [0, 1].map(|c| [0, 1].map(|d| dot(u[c], &k1_z[d])));
        Trbdf2Pass { solve, k1, k2, alpha, eta_u: 2.0 * alpha * A, lu, g_ld, g_z }
    }

    /// Stage 1's tip sum t = Uᵀ(D⁻¹ r) for the step from a state with sums `sums`, the step
    /// mean φ̄ and the tip forces f.
    #[inline(always)]
    pub(crate) fn stage1_sum(&self, sums: &StateSums, phi: f64, f: [f64; 2]) -> [f64; 2] {
        let q = &self.solve.q;
        // written out per channel: through `[0, 1].map` the closure was not inlined
        let channel = |c: usize| sums.t[c] + phi * self.lu[c] + q[c][0] * f[0] + q[c][1] * f[1];
        [channel(0), channel(1)]
    }

    /// Stage 2's tip sum t₂ = Uᵀ(D⁻¹ r₂) for the same step, with stage 1's e = f − c and
    /// stage 2's tip forces f₂.
    #[inline(always)]
    pub(crate) fn stage2_sum(&self, sums: &StateSums, phi: f64, e: [f64; 2], f2: [f64; 2]) -> [f64; 2] {
        let (q, g) = (&self.solve.q, &self.g_z);
        let channel = |c: usize| {
            sums.t2[c] + phi * self.g_ld[c] + g[c][0] * e[0] + g[c][1] * e[1] + q[c][0] * f2[0] + q[c][1] * f2[1]
        };
        [channel(0), channel(1)]
    }

    /// The sums of a state made otherwise (the initial one): the pass's own expressions
    /// ([`Trbdf2Pass::pass`]'s v' and w').
    pub(crate) fn sums_of(&self, zeta: &[f64], eta: &[f64]) -> StateSums {
        let s = &self.solve;
        let mut acc = [[0.0; WIDTH]; 4];
        for i in (0..s.cz.len()).step_by(WIDTH) {
            for l in 0..WIDTH {
                let j = i + l;
                let ce_eta = s.ce[j] * eta[j];
                let v = s.cz[j] * zeta[j] - ce_eta;
                let w = self.k1[j] * v - (self.k2[j] * zeta[j] + ce_eta);
                accumulate(&mut acc, l, [s.u0[j], s.u1[j]], v, w);
            }
        }
        totals(&acc)
    }

    /// The step's pass: (η, ζ) ← (η₁, ζ₁) from φ̄ and the stages' e = f − c, e₂ = f₂ − c₂;
    /// returns the new state's sums. The expressions are grouped so that each mode's chain of
    /// dependent operations is short (13 deep): the loop is then bound by the number of
    /// operations, not by their latencies.
    pub(crate) fn pass(&self, phi: f64, e: [f64; 2], e2: [f64; 2], zeta: &mut [f64], eta: &mut [f64]) -> StateSums {
        let s = &self.solve;
        let n = s.cz.len();
        assert!(n % WIDTH == 0 && zeta.len() == n && eta.len() == n, "modal state of the wrong length");
        #[cfg(target_arch = "x86_64")]
        if s.avx {
            // SAFETY: the CPU has AVX (`avx`), and both slices have the padded length (checked).
            return unsafe { avx::pass(self, phi, e, e2, zeta, eta) };
        }
        let (eta_u, alpha) = (self.eta_u, self.alpha);
        let mut acc = [[0.0; WIDTH]; 4];
        for i in (0..n).step_by(WIDTH) {
            for l in 0..WIDTH {
                let j = i + l;
                let (et, zt) = (eta[j], zeta[j]);
                let (cz, ce, k1, k2, z0, z1) = (s.cz[j], s.ce[j], self.k1[j], self.k2[j], s.z0[j], s.z1[j]);
                let ce_eta = ce * et;
                let v = cz * zt - ce_eta;
                let phi_ld = phi * s.ld[j];
                let u = v + (phi_ld + (z0 * e[0] + z1 * e[1]));
                let rest = ((phi_ld - ce_eta) - k2 * zt) + (z0 * e2[0] + z1 * e2[1]);
                let zn = k1 * u + rest;
                let en = (et + eta_u * u) + alpha * zn;
                let ce_en = ce * en;
                let vn = cz * zn - ce_en;
                let wn = k1 * vn - (k2 * zn + ce_en);
                accumulate(&mut acc, l, [s.u0[j], s.u1[j]], vn, wn);
                eta[j] = en;
                zeta[j] = zn;
            }
        }
        totals(&acc)
    }
}

/// Width of the partial sums: one AVX register of f64 each.
const WIDTH: usize = 4;

/// Add U·v and U·w to the partial sums of lane l.
#[inline(always)]
fn accumulate(acc: &mut [[f64; WIDTH]; 4], l: usize, u: [f64; 2], v: f64, w: f64) {
    acc[0][l] += u[0] * v;
    acc[1][l] += u[1] * v;
    acc[2][l] += u[0] * w;
    acc[3][l] += u[1] * w;
}

/// The partial sums combined in one fixed order.
#[inline(always)]
fn totals(acc: &[[f64; WIDTH]; 4]) -> StateSums {
    let t = |a: &[f64; WIDTH]| (a[0] + a[1]) + (a[2] + a[3]);
    StateSums { t: [t(&acc[0]), t(&acc[1])], t2: [t(&acc[2]), t(&acc[3])] }
}

/// [`Trbdf2Pass::pass`] with AVX instructions, 4 modes per instruction: the same operations in
/// the same order (lane l of each partial-sum register is the portable loop's partial sum l),
/// no fused multiply-add, so the same bits as the portable loop.
#[cfg(target_arch = "x86_64")]
mod avx {
    use std::arch::x86_64::{__m256d, _mm256_set1_pd, _mm256_setzero_pd, _mm256_storeu_pd};

    use super::super::woodbury::avx::{add, get, mul, put, sub};
    use super::{StateSums, Trbdf2Pass, WIDTH};

    #[target_feature(enable = "avx")]
    pub(super) unsafe fn pass(
        p: &Trbdf2Pass,
        phi: f64,
        e: [f64; 2],
        e2: [f64; 2],
        zeta: &mut [f64],
        eta: &mut [f64],
    ) -> StateSums {
        // SAFETY: the caller upholds this function's contract (the CPU has AVX; every lane read or written lies inside its slice).
        unsafe {
            let s = &p.solve;
            let b = _mm256_set1_pd;
            let (phi, e, e2) = (b(phi), [b(e[0]), b(e[1])], [b(e2[0]), b(e2[1])]);
            let (eta_u, alpha) = (b(p.eta_u), b(p.alpha));
            // channel 0 and 1 of t, then of t₂; lane l of each is the portable loop's partial sum l
            let (mut t0, mut t1, mut t20, mut t21) =
                (_mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd());
            for j in (0..s.cz.len()).step_by(WIDTH) {
                let (et, zt) = (get(eta, j), get(zeta, j));
                let (cz, ce, k1, k2) = (get(&s.cz, j), get(&s.ce, j), get(&p.k1, j), get(&p.k2, j));
                let (z0, z1) = (get(&s.z0, j), get(&s.z1, j));
                let ce_eta = mul(ce, et);
                let v = sub(mul(cz, zt), ce_eta);
                let phi_ld = mul(phi, get(&s.ld, j));
                let u = add(v, add(phi_ld, add(mul(z0, e[0]), mul(z1, e[1]))));
                let rest = add(sub(sub(phi_ld, ce_eta), mul(k2, zt)), add(mul(z0, e2[0]), mul(z1, e2[1])));
                let zn = add(mul(k1, u), rest);
                let en = add(add(et, mul(eta_u, u)), mul(alpha, zn));
                let ce_en = mul(ce, en);
                let vn = sub(mul(cz, zn), ce_en);
                let wn = sub(mul(k1, vn), add(mul(k2, zn), ce_en));
                let (u0, u1) = (get(&s.u0, j), get(&s.u1, j));
                t0 = add(t0, mul(u0, vn));
                t1 = add(t1, mul(u1, vn));
                t20 = add(t20, mul(u0, wn));
                t21 = add(t21, mul(u1, wn));
                put(eta, j, en);
                put(zeta, j, zn);
            }
            let t = |x: __m256d| {
                let mut a = [0.0; WIDTH];
                _mm256_storeu_pd(a.as_mut_ptr(), x);
                (a[0] + a[1]) + (a[2] + a[3])
            };
            StateSums { t: [t(t0), t(t1)], t2: [t(t20), t(t21)] }
        }
    }
}

/// The fixed factors of the TR-BDF2 tip-state update ξ S ẇ = s(τ + g) − S w of one channel
/// (ξ > 0): the stage-1 trapezoid w_γ = (ξSw + α(s(f_n + f_γ) − Sw))/(ξS + αS) and the BDF2
/// stage w₁ = (A w_γ − B w + α s f₁/(ξS))/(1 + α/ξ), with their divisions taken once per run
/// (eight divisions a step were ≈ 18 % of a search point's per-step scalar work, a chain of
/// dependent latencies). The products by reciprocals round differently from the quotients, by
/// ≈ 1 ulp per step.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TipStages {
    /// ξS (N m² s).
    pub(crate) xi_stiff: f64,
    /// 1/(ξS + αS).
    pub(crate) trapezoid_scale: f64,
    /// αs/(ξS).
    pub(crate) bdf2_force: f64,
    /// 1/(1 + α/ξ).
    pub(crate) bdf2_scale: f64,
}

impl TipStages {
    /// The factors for ξ > 0 (all 0 for ξ = 0, where w is algebraic and they are not used).
    pub(crate) fn new(xi: f64, alpha: f64, stiff: f64, sign: f64) -> TipStages {
        if xi.is_nan() || xi <= 0.0 {
            return TipStages { xi_stiff: 0.0, trapezoid_scale: 0.0, bdf2_force: 0.0, bdf2_scale: 0.0 };
        }
        TipStages {
            xi_stiff: xi * stiff,
            trapezoid_scale: 1.0 / (xi * stiff + alpha * stiff),
            bdf2_force: alpha * sign / (xi * stiff),
            bdf2_scale: 1.0 / (1.0 + alpha / xi),
        }
    }
}

#[cfg(test)]
mod tests {
    use wingcheck_model::{apply_overrides, Config};

    use super::super::woodbury::padded_len;
    use super::super::{ModalBasis, ModalLoop, StepInput};
    use super::*;
    use crate::trbdf2::ALPHA;

    /// One TR-BDF2 step in the two-pass Woodbury form this module replaced (stage 1's right-hand
    /// side, the pass between the stages, stage 2's end; the tip values by the same Woodbury
    /// identity), on (η, ζ, x_tip, v_tip): the reference for the one-pass form.
    #[allow(clippy::too_many_arguments)]
    fn two_pass_step(
        sv: &StepSolve,
        alpha: f64,
        ka: [f64; 2],
        input: &StepInput,
        y: &mut [f64],
        zeta: &mut [f64],
        eta: &mut [f64],
        tip: &mut [[f64; 2]; 2],
    ) {
        let [xn, vn] = *tip;
        let forces = |x: [f64; 2]| [0, 1].map(|c| input.tip_input[c] - ka[c] * x[c]);
        let t = sv.rhs(zeta, eta, input.phi, forces(xn), y);
        let (c, u_tip) = sv.correct(t);
        let xg = [0, 1].map(|ch| xn[ch] + 2.0 * alpha * u_tip[ch]);
        let x_hat = [0, 1].map(|ch| A * xg[ch] - B * xn[ch]);
        let t2 = sv.trbdf2_middle(c, [2.0 * alpha * A, 2.0 * A, A + B], input.phi, forces(x_hat), y, zeta, eta);
        let (c2, v1) = sv.correct(t2);
        sv.trbdf2_finish(y, c2, alpha, zeta, eta);
        *tip = [[0, 1].map(|ch| x_hat[ch] + alpha * v1[ch]), v1];
        let _ = vn;
    }

    /// The one-pass form is the two-pass form's TR-BDF2 (the same discrete equations summed in
    /// another order): after 3000 steps with inputs that change every step and a held
    /// estimate that jumps, the states agree to round-off (≤ 1e-11 of each vector's largest
    /// entry; measured 2e-15 to 5e-13) on the paper wing, off-default gains, damping and step, an
    /// SI-scale wing and a wing without Kelvin–Voigt damping. An error in any one factor
    /// (k1, k2, the carried sums, the stage sums' constants) moves them by far more.
    #[test]
    fn one_pass_matches_the_two_pass_woodbury_form() {
        let cases: [&[&str]; 4] = [
            &[],
            &["control.a=3", "control.b=0.2", "wing.xi=0.003", "discretisation.dt=5e-4"],
            &["wing.span=6", "wing.ei=1e7", "wing.gj=1e6", "wing.rho=100", "wing.ip=10", "control.a=2", "control.b=50"],
            &["wing.xi=0", "control.k1=7"],
        ];
        for overrides in cases {
            let mut set: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
            set.push("discretisation.stepper=trbdf2".into());
            let cfg = apply_overrides(&Config::paper(), &set).unwrap();
            let basis = ModalBasis::new(&cfg).unwrap();
            let lp = ModalLoop::new(&cfg, &basis).unwrap();
            let mut a = lp.initial_state(&cfg, &basis);
            // the reference on the same step matrix
            let law = wingcheck_control::BoundaryLaw::of(&cfg);
            let alpha = ALPHA * cfg.discretisation.dt;
            let sv = StepSolve::new(&basis, alpha, cfg.wing.xi, law.b + alpha * law.a, law.gains).unwrap();
            let ka = [law.stiffness(0), law.stiffness(1)];
            let (mut eta, mut zeta, mut y) = (a.eta.clone(), a.zeta.clone(), a.y.clone());
            let mut tip = [a.x_tip, a.v_tip];
            for j in 0..3000 {
                let s = j as f64 * 1e-3;
                let input = StepInput { phi: s.cos(), tip_input: [0.1 * s.sin(), -0.2], g_hat: [0.3, (-1f64).powi(j)] };
                lp.step(&mut a, &input);
                two_pass_step(&sv, alpha, ka, &input, &mut y, &mut zeta, &mut eta, &mut tip);
            }
            let rel = |x: &[f64], y: &[f64]| {
                let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                x.iter().zip(y).fold(0.0f64, |m, (p, q)| m.max((p - q).abs())) / scale
            };
            let (de, dz) = (rel(&a.eta, &eta), rel(&a.zeta, &zeta));
            let dt =
                rel(&[a.x_tip[0], a.x_tip[1], a.v_tip[0], a.v_tip[1]], &[tip[0][0], tip[0][1], tip[1][0], tip[1][1]]);
            println!("{overrides:?}: η {de:.1e}, ζ {dz:.1e}, tips {dt:.1e}");
            assert!(de < 1e-11 && dz < 1e-11 && dt < 1e-11, "{overrides:?}: η {de:e}, ζ {dz:e}, tips {dt:e}");
            assert!(eta.iter().any(|v| *v != 0.0));
        }
    }

    /// The sums a pass carries are those of the state it made: after some steps, the sums of
    /// the state computed afresh ([`Trbdf2Pass::sums_of`]) equal the carried ones to round-off.
    #[test]
    fn carried_sums_are_the_sums_of_the_state() {
        let cfg = apply_overrides(&Config::paper(), &["control.a=0.5".into()]).unwrap();
        let basis = ModalBasis::new(&cfg).unwrap();
        let law = wingcheck_control::BoundaryLaw::of(&cfg);
        let alpha = ALPHA * cfg.discretisation.dt;
        let solve = StepSolve::new(&basis, alpha, cfg.wing.xi, law.b + alpha * law.a, law.gains).unwrap();
        let pass = Trbdf2Pass::new(solve, alpha);
        let n = padded_len(basis.len());
        let (mut eta, mut zeta) = (vec![0.0; n], vec![0.0; n]);
        eta[..basis.len()].copy_from_slice(&basis.eta0);
        let mut sums = pass.sums_of(&zeta, &eta);
        for j in 0..50 {
            let x = j as f64;
            sums = pass.pass(x.sin(), [0.1, -0.3 * x.cos()], [0.2, 0.05], &mut zeta, &mut eta);
        }
        let fresh = pass.sums_of(&zeta, &eta);
        for (c, f) in sums.t.iter().chain(&sums.t2).zip(fresh.t.iter().chain(&fresh.t2)) {
            assert!((c - f).abs() <= 1e-12 * f.abs().max(1e-300), "carried {c:e}, fresh {f:e}");
        }
        assert!(fresh.t.iter().chain(&fresh.t2).all(|v| *v != 0.0));
    }
}
