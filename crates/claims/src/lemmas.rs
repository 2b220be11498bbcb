//! Lemmas 1–3, (11)–(14): the inequalities used in the proofs, checked on adversarial inputs.
//!
//! - Lemma 1 (11), ab ≤ a²/p + p b²: holds as printed but is not sharp; the sharp form is
//!   ab ≤ a²/(2p) + p b²/2 (best constant ½, equality at a = p b). Checked by maximising
//!   ab/(a²/p + p b²) over directions (a, b) and p ∈ [1e-3, 1e3].
//! - Lemma 2 (12), ω(s)² ≤ f ∫_0^f ω² ds for ω(0) = 0: false as printed (no derivative). The
//!   best constant over polynomials of degree ≤ K, ω(f)²/(f∫ω²) = λ_K/f², grows without
//!   bound in K; exact counterexample at the paper's span f = 2: ω = z², ω(2)² = 16 > 64/5.
//!   Corrected: ω(z)² ≤ z ∫_0^z ω'² ≤ f ∫_0^f ω'² (Cauchy–Schwarz), sharp constant 1 (ω = z);
//!   this is the form used in (36).
//! - Lemma 3 (13)–(14): (14) is the exact reaching time of Q̇ = −φ1 Q − φ2 Q^φ3, hence an upper
//!   bound by comparison; checked against an independent adaptive RK4 in time over a grid of
//!   (φ1, φ2, φ3, Q0), and on inequality cases Q̇ = −φ1 Q − φ2 Q^φ3 − ψ(t), ψ ≥ 0.
//!
//! [`compute`] gathers the facts; [`explain`] turns them into [`LemmasEvidence`] and the row.

mod explain;

use crate::numerics::NumericsError;
use wingcheck_model::Config;

use crate::finite_time::reach::{lemma3_time, num_err};
use crate::settings::CheckSettings;
use crate::ClaimsError;

pub use explain::{check, LemmasEvidence};

/// Lemma 1: max over (a, b) ≠ 0 and p ∈ [1e-3, 1e3] (log grid) of ab/(a²/p + p b²); the
/// printed (11) holds iff this is ≤ 1 (the exact value is ½, at a = p b).
pub fn lemma1_max_ratio() -> f64 {
    let mut best: f64 = f64::NEG_INFINITY;
    for i in 0..=60 {
        let p = 10f64.powf(-3.0 + 0.1 * i as f64);
        // Direction (a, b) = (cos t, sin t); refine around the grid maximum by golden section.
        let ratio = |t: f64| {
            let (a, b) = (t.cos(), t.sin());
            a * b / (a * a / p + p * b * b)
        };
        let n = 720;
        let (mut tb, mut rb) = (0.0, f64::NEG_INFINITY);
        for k in 0..n {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            if ratio(t) > rb {
                (tb, rb) = (t, ratio(t));
            }
        }
        let h = std::f64::consts::TAU / n as f64;
        let (mut lo, mut hi) = (tb - h, tb + h);
        for _ in 0..80 {
            let m1 = lo + 0.382 * (hi - lo);
            let m2 = lo + 0.618 * (hi - lo);
            if ratio(m1) < ratio(m2) {
                lo = m1;
            } else {
                hi = m2;
            }
        }
        best = best.max(rb).max(ratio(0.5 * (lo + hi)));
    }
    best
}

/// Solve the symmetric positive definite system G x = v by Cholesky (small dense).
fn spd_solve(g: &[Vec<f64>], v: &[f64]) -> Result<Vec<f64>, ClaimsError> {
    let n = v.len();
    let mut l = vec![vec![0.0; n]; n];
    for i in 0..n {
        for j in 0..=i {
            let s = g[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>();
            if i == j {
                if s <= 0.0 {
                    return Err(num_err("lemma2 Gram matrix", NumericsError::GramPivot(i)));
                }
                l[i][i] = s.sqrt();
            } else {
                l[i][j] = s / l[j][j];
            }
        }
    }
    let mut y = vec![0.0; n];
    for i in 0..n {
        y[i] = (v[i] - (0..i).map(|k| l[i][k] * y[k]).sum::<f64>()) / l[i][i];
    }
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        x[i] = (y[i] - (i + 1..n).map(|k| l[k][i] * x[k]).sum::<f64>()) / l[i][i];
    }
    Ok(x)
}

/// Lemma 2 on [0, f] over ω = Σ_{k=1}^{K} c_k z^k (ω(0) = 0): the maximum of ω(f)²/(f N(ω)),
/// a generalised Rayleigh quotient vᵀG⁻¹v, with N(ω) = ∫_0^f ω² (`derivative = false`, the
/// printed (12)) or N(ω) = ∫_0^f ω'² (`derivative = true`, the corrected form). Dimensionless.
pub fn lemma2_ratio(span: f64, degree: usize, derivative: bool) -> Result<f64, ClaimsError> {
    if !(span > 0.0 && span.is_finite()) || degree == 0 {
        return Err(num_err("lemma2_ratio", NumericsError::Lemma2Inputs { span, degree }));
    }
    // On the unit interval, then scale: ω(f)² / (f ∫ω²) = (unit ratio)/f²; the derivative form is scale-free.
    let g: Vec<Vec<f64>> = (1..=degree)
        .map(|j| {
            (1..=degree)
                .map(|k| if derivative { (j * k) as f64 / (j + k - 1) as f64 } else { 1.0 / (j + k + 1) as f64 })
                .collect()
        })
        .collect();
    let v = vec![1.0; degree];
    let x = spd_solve(&g, &v)?;
    let unit: f64 = x.iter().sum();
    Ok(if derivative { unit } else { unit / (span * span) })
}

/// An exact rational as text: `p` for integers, `p/q` otherwise.
pub(crate) fn exact_text(r: &num_rational::BigRational) -> String {
    if r.is_integer() {
        r.numer().to_string()
    } else {
        wingcheck_cert::exact::to_fraction_string(r)
    }
}

/// Reaching time of Q̇ = −φ1 Q − φ2 Q^φ3 − ψ(t) from Q0 by RK4 in time, independent of (14)
/// (s). Step h = 1% of the local time-to-go estimate Q/(|Q̇|(1 − φ3)) (so Q^{1−φ3}, the natural
/// variable near 0, shrinks geometrically); stops when that estimate is below 1e-13·t and adds it.
pub fn lemma3_numeric(phi1: f64, phi2: f64, phi3: f64, q0: f64, psi: &dyn Fn(f64) -> f64) -> f64 {
    let f = |t: f64, q: f64| -phi1 * q - phi2 * q.max(0.0).powf(phi3) - psi(t);
    let (mut t, mut q) = (0.0, q0);
    for _ in 0..1_000_000 {
        let d = f(t, q);
        let togo = q / (d.abs() * (1.0 - phi3));
        if q <= 0.0 || togo <= 1e-13 * t.max(1e-300) {
            return t + togo.max(0.0);
        }
        let h = 0.01 * togo;
        let next = crate::ode::rk4_step_with(|t, q| Some(f(t, q)), t, q, h, d).unwrap_or(f64::NAN);
        if next <= 0.0 {
            // Crossed within the step: locate linearly.
            return t + h * q / (q - next);
        }
        q = next;
        t += h;
    }
    f64::NAN
}

/// Largest exact ω(f)² = f^{2k} written out digit by digit (bits of its numerator and
/// denominator); beyond it the evidence holds the exact values in closed form (`f^(2k)` …).
/// k ≈ f²/2 grows with the span: at f = 1000, f^{2k} has three million digits, whose decimal
/// text alone took minutes.
pub const EXACT_TEXT_BITS: u64 = 4096;

/// The exact counterexample ω = z^k to the printed Lemma 2 on [0, f] (2k + 1 > f²): ω(f)² =
/// f^{2k} > f∫_0^f z^{2k} dz = f^{2k+2}/(2k+1), while the corrected right-hand side
/// f∫ω'² = k² f^{2k}/(2k−1) ≥ f^{2k} (k² ≥ 2k − 1), all exact (exact rationals as `p` or `p/q`
/// text, or in closed form `f²ᵏ…` (superscript digits) beyond [`EXACT_TEXT_BITS`]).
#[derive(Debug, Clone)]
pub struct Counterexample {
    /// The function, `zᵏ` with the exponent in superscript digits (`z²`).
    pub omega: String,
    /// ω(f)², exact.
    pub lhs: String,
    /// f∫ω², exact (the printed right-hand side).
    pub rhs_printed: String,
    /// f∫ω'², exact (the corrected right-hand side).
    pub rhs_corrected: String,
    /// ω(f)² > f∫ω² (the printed (12) violated), decided exactly.
    pub printed_violated: bool,
    /// ω(f)² ≤ f∫ω'², decided exactly.
    pub corrected_holds: bool,
}

/// The exact counterexample ω = z^k on [0, f], k = ⌊(f² − 1)/2⌋ + 1 ≥ 1 (so ω(0) = 0 and
/// 2k + 1 > f²), in big integers whatever the span: ω(f)² > f∫ω² ⟺ 2k + 1 > f² and
/// ω(f)² ≤ f∫ω'² ⟺ 2k − 1 ≤ k² are decided on those small numbers, f^{2k} itself is formed only
/// when it has at most [`EXACT_TEXT_BITS`] bits.
pub fn counterexample(span: f64) -> Result<Counterexample, ClaimsError> {
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::{Signed, Zero};
    let f = wingcheck_cert::exact::parse_rational(&format!("{span}"))
        .map_err(|cause| num_err("lemma2 span", NumericsError::SpanNotDecimal { span, cause }))?;
    if !f.is_positive() {
        return Err(num_err("lemma2 span", NumericsError::SpanNotPositive(span)));
    }
    let f2 = &f * &f;
    let one = BigRational::from_integer(1.into());
    let two = BigRational::from_integer(2.into());
    let below = ((&f2 - &one) / &two).floor().to_integer();
    let k: BigInt = if below.is_negative() { BigInt::zero() } else { below } + 1;
    let q = |n: &BigInt| BigRational::from_integer(n.clone());
    let (two_k_plus_1, two_k_minus_1) = (BigInt::from(2) * &k + 1, BigInt::from(2) * &k - 1);
    let printed_violated = q(&two_k_plus_1) > f2;
    let corrected_holds = two_k_minus_1 <= &k * &k;
    let two_k: BigInt = BigInt::from(2) * &k;
    let sup = |n: &BigInt| wingcheck_model::format::superscript(n);
    let bits = (f.numer().bits() + f.denom().bits()).saturating_mul(u64::try_from(&two_k).unwrap_or(u64::MAX));
    let (lhs, rhs, rhs_corr) = if bits <= EXACT_TEXT_BITS {
        let f2k = num_traits::Pow::pow(&f, u64::try_from(&two_k).expect("bounded by EXACT_TEXT_BITS"));
        let rhs = &f2k * &f2 / q(&two_k_plus_1);
        let rhs_corr = &f2k * q(&(&k * &k)) / q(&two_k_minus_1);
        (short_exact(&f2k), short_exact(&rhs), short_exact(&rhs_corr))
    } else {
        let ft = if f.is_integer() { exact_text(&f) } else { format!("({})", exact_text(&f)) };
        (
            format!("{ft}{}", sup(&two_k)),
            format!("{ft}{}/{two_k_plus_1}", sup(&(&two_k + 2))),
            format!("{ft}{}·{}/{two_k_minus_1}", sup(&two_k), &k * &k),
        )
    };
    Ok(Counterexample {
        omega: format!("z{}", sup(&k)),
        lhs,
        rhs_printed: rhs,
        rhs_corrected: rhs_corr,
        printed_violated,
        corrected_holds,
    })
}

/// An exact rational's text if short, else its value to 4 significant digits marked `≈` (the
/// sentence that shows it says the value is exact and shown rounded).
fn short_exact(r: &num_rational::BigRational) -> String {
    let text = exact_text(r);
    if text.len() <= 16 {
        text
    } else {
        format!("≈{}", wingcheck_model::quantity::format_value(wingcheck_cert::exact::to_f64(r), None))
    }
}

/// Everything the lemmas row computes, before it is put into words.
#[derive(Debug, Clone)]
pub struct Computed {
    /// max ab/(a²/p + p b²) over the search.
    pub lemma1_max_ratio: f64,
    /// The span f (m).
    pub span: f64,
    /// Best ω(f)²/(f∫ω²) per degree 1…K (printed (12)).
    pub printed: Vec<f64>,
    /// Best ω(f)²/(f∫ω'²) per degree (corrected).
    pub corrected: Vec<f64>,
    /// The exact counterexample.
    pub counterexample: Counterexample,
    /// p = a1/a2 of the configured observer.
    pub p: f64,
    /// σ2(0)²/2 of the configured state.
    pub q0_config: f64,
    /// Equality cases: ((14), RK4) reaching times (s).
    pub lemma3_points: Vec<(f64, f64)>,
    /// max relative difference of RK4 and (14) over the equality cases.
    pub lemma3_max_rel_err: f64,
    /// Inequality cases tried, and how many were slower than (14).
    pub lemma3_inequality: (usize, usize),
}

/// Compute the facts of Lemmas 1–3 for the configuration (span f, p = a1/a2, σ2(0)).
pub fn compute(cfg: &Config, settings: &CheckSettings) -> Result<Computed, ClaimsError> {
    // Lemma 1.
    let l1 = lemma1_max_ratio();
    // Lemma 2, printed and corrected, on the configured span f.
    let span = cfg.wing.span;
    let mut printed = Vec::new();
    let mut corrected = Vec::new();
    for k in 1..=settings.lemma2_max_degree {
        printed.push(lemma2_ratio(span, k, false)?);
        corrected.push(lemma2_ratio(span, k, true)?);
    }
    let counterexample = counterexample(span)?;
    // Lemma 3 on a parameter grid: p = a1/a2 of the configured observer, Q0 including σ2(0)²/2.
    let p = cfg.observer.a1 as f64 / cfg.observer.a2 as f64;
    let q0_config = 0.5 * crate::finite_time::reach::sigma0_other(cfg, 1)?.powi(2);
    let (mut max_err, mut ineq, mut viol) = (0.0_f64, 0, 0);
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    for &phi1 in &[0.1, 1.6, 10.0] {
        for &phi2 in &[0.1, 2f64.powf(p) * 4.0, 50.0] {
            for &phi3 in &[0.1, p, 0.9] {
                for &q0 in &[1e-4, q0_config.max(1e-6), 1.0, 100.0] {
                    let exact = lemma3_time(phi1, phi2, phi3, q0)?;
                    let num = lemma3_numeric(phi1, phi2, phi3, q0, &|_| 0.0);
                    max_err = max_err.max((num - exact).abs() / exact);
                    xs.push(exact);
                    ys.push(num);
                    for c in [0.1, 1.0] {
                        let psi = move |t: f64| c * phi2 * (1.0 + (5.0 * t).sin());
                        let t_in = lemma3_numeric(phi1, phi2, phi3, q0, &psi);
                        ineq += 1;
                        if t_in > exact * (1.0 + 1e-9) {
                            viol += 1;
                        }
                    }
                }
            }
        }
    }
    if !max_err.is_finite() {
        return Err(num_err("lemma3_numeric", NumericsError::ReachingTimeNotConverged));
    }
    Ok(Computed {
        lemma1_max_ratio: l1,
        span,
        printed,
        corrected,
        counterexample,
        p,
        q0_config,
        lemma3_points: xs.into_iter().zip(ys).collect(),
        lemma3_max_rel_err: max_err,
        lemma3_inequality: (ineq, viol),
    })
}
