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
//! Evidence keys: `lemma1_max_ratio` (max ab/(a²/p + p b²); ½ means holds, not sharp),
//! `lemma1_holds`, `lemma1_sharp_constant`, `lemma2_printed_ratio_by_degree` (array, on [0, 2]),
//! `lemma2_printed_holds`, `lemma2_counterexample` (object with exact rationals),
//! `lemma2_corrected_ratio_by_degree` (array; 1 means sharp), `lemma2_corrected_max_ratio`,
//! `lemma3_cases`, `lemma3_max_rel_err` (|numeric − (14)|/(14) on the equality ODE),
//! `lemma3_ineq_cases`, `lemma3_violations` (inequality cases slower than (14)); typed as
//! [`LemmasEvidence`] (evidence → [`verdict`] → [`summary`]).

use std::time::Instant;

use serde::{Deserialize, Serialize};
use wingcheck_model::Config;

use crate::finite_time::reach::{lemma3_time, num_err};
use crate::{evidence_map, Basis, ClaimRow, ClaimsError, Line, PlotData, Verdict};

/// Largest degree of the polynomial basis in the Lemma-2 search.
pub const MAX_DEGREE: usize = 8;

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
                    return Err(num_err("lemma2 Gram matrix", format!("not positive definite at {i}")));
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
        return Err(num_err("lemma2_ratio", format!("need f > 0, K ≥ 1; got {span}, {degree}")));
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
fn exact_text(r: &num_rational::BigRational) -> String {
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
        let k1 = d;
        let k2 = f(t + 0.5 * h, q + 0.5 * h * k1);
        let k3 = f(t + 0.5 * h, q + 0.5 * h * k2);
        let k4 = f(t + h, q + h * k3);
        let next = q + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        if next <= 0.0 {
            // Crossed within the step: locate linearly.
            return t + h * q / (q - next);
        }
        q = next;
        t += h;
    }
    f64::NAN
}

/// The exact counterexample to the printed Lemma 2 on [0, f]: ω = z^k with 2k + 1 > f², so
/// ω(f)² = f^{2k} > f∫_0^f z^{2k} dz = f^{2k+2}/(2k+1); the corrected form
/// f∫ω'² = k² f^{2k}/(2k−1) ≥ f^{2k} holds (k² ≥ 2k − 1). Rationals as `p` or `p/q` text.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Lemma2Counterexample {
    /// The span f (m), as configured.
    pub f: f64,
    /// The function, `z^k`.
    pub omega: String,
    /// ω(f)² = f^{2k}, exact.
    pub lhs_omega_f_sq: String,
    /// f∫_0^f ω², exact (the printed right-hand side).
    pub rhs_printed: String,
    /// Whether ω(f)² > f∫ω² (the printed (12) violated), decided exactly.
    pub printed_violated: bool,
    /// f∫_0^f ω'², exact (the corrected right-hand side).
    pub rhs_corrected: String,
    /// Whether ω(f)² ≤ f∫ω'², decided exactly.
    pub corrected_holds: bool,
}

/// Largest exact ω(f)² = f^{2k} written out digit by digit (bits of its numerator and
/// denominator); beyond it the evidence holds the exact values in closed form (`f^(2k)` …).
/// k ≈ f²/2 grows with the span: at f = 1000, f^{2k} has three million digits, whose decimal
/// text alone took minutes.
pub const EXACT_TEXT_BITS: u64 = 4096;

/// The counterexample and its values as f64 (+∞ where they exceed the f64 range).
struct Counterexample {
    evidence: Lemma2Counterexample,
    values: (f64, f64),
}

/// The exact counterexample ω = z^k on [0, f], k = ⌊(f² − 1)/2⌋ + 1 ≥ 1 (so ω(0) = 0 and
/// 2k + 1 > f²), in big integers whatever the span: ω(f)² > f∫ω² ⟺ 2k + 1 > f² and
/// ω(f)² ≤ f∫ω'² ⟺ 2k − 1 ≤ k² are decided on those small numbers, f^{2k} itself is formed only
/// when it has at most [`EXACT_TEXT_BITS`] bits.
fn counterexample(span: f64) -> Result<Counterexample, ClaimsError> {
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::{Signed, Zero};
    let f = wingcheck_cert::exact::parse_rational(&format!("{span}"))
        .map_err(|e| num_err("lemma2 span", format!("span {span} not a decimal: {e}")))?;
    if !f.is_positive() {
        return Err(num_err("lemma2 span", format!("span {span} must be > 0")));
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
    let bits = (f.numer().bits() + f.denom().bits()).saturating_mul(u64::try_from(&two_k).unwrap_or(u64::MAX));
    let (lhs, rhs, rhs_corr, values) = if bits <= EXACT_TEXT_BITS {
        let f2k = num_traits::Pow::pow(&f, u64::try_from(&two_k).expect("bounded by EXACT_TEXT_BITS"));
        let rhs = &f2k * &f2 / q(&two_k_plus_1);
        let rhs_corr = &f2k * q(&(&k * &k)) / q(&two_k_minus_1);
        let show = wingcheck_cert::exact::to_f64;
        let values = (show(&f2k), show(&rhs));
        (exact_text(&f2k), exact_text(&rhs), exact_text(&rhs_corr), values)
    } else {
        let ft = if f.is_integer() { exact_text(&f) } else { format!("({})", exact_text(&f)) };
        (
            format!("{ft}^{two_k}"),
            format!("{ft}^{}/{two_k_plus_1}", &two_k + 2),
            format!("{ft}^{two_k}·{}/{two_k_minus_1}", &k * &k),
            (f64::INFINITY, f64::INFINITY),
        )
    };
    Ok(Counterexample {
        evidence: Lemma2Counterexample {
            f: span,
            omega: format!("z^{k}"),
            lhs_omega_f_sq: lhs,
            rhs_printed: rhs,
            printed_violated,
            rhs_corrected: rhs_corr,
            corrected_holds,
        },
        values,
    })
}

/// The evidence of the `lemmas` row (serialised keys as documented in the module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LemmasEvidence {
    /// max ab/(a²/p + p b²) over directions and p ∈ [1e-3, 1e3] (dimensionless; ½ exactly).
    pub lemma1_max_ratio: f64,
    /// Lemma 1 (11) holds (the maximum is ≤ 1).
    pub lemma1_holds: bool,
    /// The sharp constant of ab ≤ c(a²/p + p b²): ½ (AM–GM, equality at a = p b).
    pub lemma1_sharp_constant: f64,
    /// Best ω(f)²/(f∫ω²) over polynomials of degree ≤ K, K = 1…[`MAX_DEGREE`] (printed (12)).
    pub lemma2_printed_ratio_by_degree: Vec<f64>,
    /// The printed (12) survived the search (every ratio ≤ 1 and no exact counterexample).
    pub lemma2_printed_holds: bool,
    /// Best ω(f)²/(f∫ω'²), K = 1…[`MAX_DEGREE`] (corrected form; 1 means sharp).
    pub lemma2_corrected_ratio_by_degree: Vec<f64>,
    /// Maximum of `lemma2_corrected_ratio_by_degree`.
    pub lemma2_corrected_max_ratio: f64,
    /// The exact counterexample on the configured span.
    pub lemma2_counterexample: Lemma2Counterexample,
    /// Number of (φ1, φ2, φ3, Q0) cases of the equality ODE.
    pub lemma3_cases: usize,
    /// max |numeric − (14)|/(14) over those cases (dimensionless).
    pub lemma3_max_rel_err: f64,
    /// Number of inequality cases Q̇ = −φ1Q − φ2Q^φ3 − ψ(t).
    pub lemma3_ineq_cases: usize,
    /// Inequality cases slower than (14) (violations of Lemma 3).
    pub lemma3_violations: usize,
    /// The span f (m) (context for the texts; not serialised: it is `lemma2_counterexample.f`).
    #[serde(skip)]
    pub span: f64,
    /// p = a1/a2 of the configured observer (context, not serialised).
    #[serde(skip)]
    pub p: f64,
    /// σ2(0)²/2 of the configured state (context, not serialised).
    #[serde(skip)]
    pub q0_config: f64,
    /// ω(f)², f∫ω² of the counterexample as f64 (context, not serialised).
    #[serde(skip)]
    pub counterexample_values: (f64, f64),
    /// (14) and RK4 reaching times per equality case, s (plot data, not serialised).
    #[serde(skip)]
    pub lemma3_points: (Vec<f64>, Vec<f64>),
}

/// Compute the evidence of Lemmas 1–3 for the configuration (span f, p = a1/a2, σ2(0)).
pub fn evidence(cfg: &Config) -> Result<LemmasEvidence, ClaimsError> {
    // Lemma 1.
    let l1 = lemma1_max_ratio();
    // Lemma 2, printed and corrected, on the configured span f.
    let span = cfg.wing.span;
    let mut printed = Vec::new();
    let mut corrected = Vec::new();
    for k in 1..=MAX_DEGREE {
        printed.push(lemma2_ratio(span, k, false)?);
        corrected.push(lemma2_ratio(span, k, true)?);
    }
    let corr_max = corrected.iter().cloned().fold(0.0, f64::max);
    let cx = counterexample(span)?;
    let cex = cx.evidence.printed_violated;
    // Lemma 3 on a parameter grid: p = a1/a2 of the configured observer, Q0 including σ2(0)²/2.
    let p = cfg.observer.a1 as f64 / cfg.observer.a2 as f64;
    let q0_config = 0.5 * crate::finite_time::sigma0_other(cfg, 1)?.powi(2);
    let (mut cases, mut max_err, mut ineq, mut viol) = (0, 0.0_f64, 0, 0);
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    for &phi1 in &[0.1, 1.6, 10.0] {
        for &phi2 in &[0.1, 2f64.powf(p) * 4.0, 50.0] {
            for &phi3 in &[0.1, p, 0.9] {
                for &q0 in &[1e-4, q0_config.max(1e-6), 1.0, 100.0] {
                    let exact = lemma3_time(phi1, phi2, phi3, q0)?;
                    let num = lemma3_numeric(phi1, phi2, phi3, q0, &|_| 0.0);
                    max_err = max_err.max((num - exact).abs() / exact);
                    cases += 1;
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
        return Err(num_err("lemma3_numeric", "the RK4 reaching time did not converge".into()));
    }
    Ok(LemmasEvidence {
        lemma1_max_ratio: l1,
        lemma1_holds: l1 <= 1.0,
        lemma1_sharp_constant: 0.5,
        lemma2_printed_holds: printed.iter().all(|&r| r <= 1.0) && !cex,
        lemma2_printed_ratio_by_degree: printed,
        lemma2_corrected_ratio_by_degree: corrected,
        lemma2_corrected_max_ratio: corr_max,
        counterexample_values: cx.values,
        lemma2_counterexample: cx.evidence,
        lemma3_cases: cases,
        lemma3_max_rel_err: max_err,
        lemma3_ineq_cases: ineq,
        lemma3_violations: viol,
        span,
        p,
        q0_config,
        lemma3_points: (xs, ys),
    })
}

/// Lemma 3 reproduced: the RK4 times agree with (14) to 1e-6 and no inequality case is slower.
fn lemma3_holds(e: &LemmasEvidence) -> bool {
    e.lemma3_max_rel_err < 1e-6 && e.lemma3_violations == 0
}

/// Verdict from the evidence: fails if Lemma 1, Lemma 3 or the corrected Lemma 2 fails; holds
/// after correction if only the printed Lemma 2 fails; else holds. Basis: float computations
/// (the Lemma-2 counterexample itself is exact).
pub fn verdict(e: &LemmasEvidence) -> (Verdict, Basis) {
    let v = if !e.lemma1_holds || !lemma3_holds(e) || e.lemma2_corrected_max_ratio > 1.0 + 1e-9 {
        Verdict::Fails
    } else if !e.lemma2_printed_holds {
        Verdict::HoldsAfterCorrection
    } else {
        Verdict::Holds
    };
    (v, Basis::FloatSolver)
}

/// An exact rational's text if short (or if its value is beyond f64: then the text is the
/// closed form), else its value to 5 digits (marked ≈).
fn short_exact(text: &str, value: f64) -> String {
    if text.len() <= 16 || !value.is_finite() {
        text.to_string()
    } else {
        format!("≈{value:.4e}")
    }
}

/// The summary and the correction, from the evidence.
pub fn summary(e: &LemmasEvidence) -> (String, Option<String>) {
    let printed = &e.lemma2_printed_ratio_by_degree;
    let cex = &e.lemma2_counterexample;
    let span = e.span;
    let lemma1 = if e.lemma1_holds {
        format!(
            "Lemma 1 (11) holds as printed but loosely: max ab/(a²/p + p b²) = {:.6} (the sharp form is \
             ab ≤ a²/(2p) + p b²/2, constant ½; a²/p − ab + p b² = (a/√p − √p b/2)² + ¾ p b² ≥ 0)",
            e.lemma1_max_ratio
        )
    } else {
        format!("Lemma 1 (11) FAILS here: max ab/(a²/p + p b²) = {:.6} > 1", e.lemma1_max_ratio)
    };
    let lemma2 = format!(
        "Lemma 2 (12) is {l2_verdict}: on [0, {span}] the best ratio ω(f)²/(f∫ω²) over polynomials with ω(0) = 0 grows with the degree \
         ({r1:.3} at degree 1, {r8:.3} at degree {MAX_DEGREE}, unbounded as the degree grows); exact counterexample ω = {omega}: \
         ω(f)² = {cl} {cmp} f∫ω² = {cr} (exact rational arithmetic)",
        l2_verdict = if e.lemma2_printed_holds { "not refuted here" } else { "false as printed" },
        r1 = printed.first().copied().unwrap_or(0.0),
        r8 = printed.last().copied().unwrap_or(0.0),
        omega = cex.omega,
        cl = short_exact(&cex.lhs_omega_f_sq, e.counterexample_values.0),
        cr = short_exact(&cex.rhs_printed, e.counterexample_values.1),
        cmp = if cex.printed_violated { ">" } else { "≤" },
    );
    let corrected = if e.lemma2_corrected_max_ratio <= 1.0 + 1e-9 {
        format!(
            "Corrected: ω(z)² ≤ z∫_0^z ω'² ≤ f∫_0^f ω'² (Cauchy–Schwarz), sharp constant 1 (max ratio found {:.12}, \
             attained by ω = z) — the form (36) actually uses",
            e.lemma2_corrected_max_ratio
        )
    } else {
        format!(
            "the corrected form ω(f)² ≤ f∫ω'² FAILS numerically here (max ratio {:.12} > 1)",
            e.lemma2_corrected_max_ratio
        )
    };
    let lemma3 = if lemma3_holds(e) {
        format!(
            "Lemma 3: (14) is the exact reaching time of Q̇ = −φ1Q − φ2Q^φ3 (independent RK4: max relative difference \
             {:.1e} over {} cases, φ3 including p = a1/a2 = {:.6}) and bounds every inequality case tried ({} violations in {}); it is sharp",
            e.lemma3_max_rel_err, e.lemma3_cases, e.p, e.lemma3_violations, e.lemma3_ineq_cases
        )
    } else {
        format!(
            "Lemma 3 is NOT reproduced: independent RK4 differs from (14) by up to {:.1e} relative over {} cases (φ3 including \
             p = a1/a2 = {:.6}), {} of {} inequality cases are slower than (14)",
            e.lemma3_max_rel_err, e.lemma3_cases, e.p, e.lemma3_violations, e.lemma3_ineq_cases
        )
    };
    let correction = (!e.lemma2_printed_holds).then(|| {
        "Lemma 2 (12) must read ω̄(z)² ≤ z∫_0^z ω̄'(s)² ds ≤ f∫_0^f ω̄'(s)² ds (derivative inside the integral); \
         Lemma 1 may be sharpened to ab ≤ a²/(2p) + p b²/2"
            .to_string()
    });
    (format!("{lemma1}. {lemma2}. {corrected}. {lemma3}."), correction)
}

fn plots(e: &LemmasEvidence) -> Vec<PlotData> {
    let degrees: Vec<f64> = (1..=MAX_DEGREE).map(|k| k as f64).collect();
    let line = |label: &str, x: Vec<f64>, y: Vec<f64>, points: bool| Line { label: label.into(), x, y, points };
    let (xs, ys) = &e.lemma3_points;
    let lo = xs.iter().cloned().fold(f64::MAX, f64::min);
    let hi = xs.iter().cloned().fold(0.0, f64::max);
    vec![
        PlotData {
            name: "lemmas-lemma2".into(),
            title: format!(
                "Lemma 2 on [0, {}]: best ratio over polynomials of degree ≤ K; printed (12) reaches {:.1}, corrected form {:.6}",
                e.span,
                e.lemma2_printed_ratio_by_degree.last().copied().unwrap_or(0.0),
                e.lemma2_corrected_max_ratio
            ),
            x_label: "degree K (1)".into(),
            y_label: "max ω(f)² / (f ∫ …) (1)".into(),
            log_x: false,
            log_y: true,
            lines: vec![
                line("printed: f ∫ ω²", degrees.clone(), e.lemma2_printed_ratio_by_degree.clone(), true),
                line("corrected: f ∫ ω'²", degrees.clone(), e.lemma2_corrected_ratio_by_degree.clone(), true),
                line("limit 1", vec![1.0, MAX_DEGREE as f64], vec![1.0, 1.0], false),
            ],
        },
        PlotData {
            name: "lemmas-lemma3".into(),
            title: format!(
                "Lemma 3: numerical reaching time vs (14), {} cases, max relative difference {:.1e}",
                e.lemma3_cases, e.lemma3_max_rel_err
            ),
            x_label: "t_f from (14) (s)".into(),
            y_label: "t_f by RK4 (s)".into(),
            log_x: true,
            log_y: true,
            lines: vec![line("cases", xs.clone(), ys.clone(), true), line("y = x", vec![lo, hi], vec![lo, hi], false)],
        },
    ]
}

/// Check Lemmas 1–3: evidence → verdict → text.
pub fn check(cfg: &Config) -> Result<ClaimRow, ClaimsError> {
    let clock = Instant::now();
    let e = evidence(cfg)?;
    let (verdict, basis) = verdict(&e);
    let (summary, correction) = summary(&e);
    Ok(ClaimRow {
        id: crate::ClaimId::Lemmas,
        equation: "Lemmas 1–3, (11)–(14)".into(),
        claim: "the inequalities used in the proofs".into(),
        verdict,
        basis,
        summary,
        correction,
        evidence: evidence_map(&e),
        highlights: Vec::new(),
        assumptions: vec![
            "Lemma 2 read with ω̄ = ω̄(z) at any z ∈ [0, f]; searched at z = f (the worst point for increasing ω)".into(),
            format!("Lemma 2 search space: polynomials Σ_{{k=1}}^K c_k z^k, K ≤ {MAX_DEGREE}, on the configured span f = {}", e.span),
            format!("Lemma 3 grid: φ1 ∈ {{0.1, 1.6, 10}}, φ2 ∈ {{0.1, 2^p·4, 50}}, φ3 ∈ {{0.1, p, 0.9}} with p = a1/a2 = {:.6}, Q0 ∈ {{1e-4, σ2(0)²/2 = {:.4e}, 1, 100}}; \
             inequality cases ψ = c φ2 (1 + sin 5t), c ∈ {{0.1, 1}}", e.p, e.q0_config),
        ],
        certificates: vec![],
        plots: plots(&e),
        seconds: clock.elapsed().as_secs_f64(),
    })
}
